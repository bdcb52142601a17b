//! Streaming points through a computation: CSV or `.npy` in, CSV or `.npy` out, in bounded
//! batches that are parsed, computed and formatted on all threads and written in input order.
//! Memory depends on the batch size, not on the number of points.
//!
//! - [`source`]: the points file, as a chunk source of `rs-io` (read by position or in order);
//! - [`kernel`]: what a command computes ([`kernel::PointsKernel`], [`IndexedQuery`],
//!   [`ByIndex`]);
//! - [`scheduler`]: the workers ([`stream_points`]);
//! - [`in_order`]: the ordered writing, and the bound on the chunks in flight;
//! - [`format`]: the output ([`Column`]: CSV rows or `.npy` values);
//! - [`progress`]: the progress bar; [`spares`]: the pools of reused buffers.

mod format;
mod in_order;
mod kernel;
mod progress;
mod scheduler;
mod source;
mod spares;

pub(crate) use format::{Column, write_f64};
pub(crate) use kernel::{ByIndex, IndexedQuery};
pub(crate) use scheduler::stream_points;
pub(crate) use source::PointsInput;
