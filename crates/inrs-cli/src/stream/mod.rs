//! Streaming points through a computation: CSV or `.npy` in, CSV or `.npy` out, in bounded
//! batches that are parsed, computed and formatted on all threads and written in input order.
//! Memory depends on the batch size, not on the number of points.
//!
//! - [`source`]: the points file, as a chunk source of `rs-io` (read by position or in order);
//! - what a command computes is any `inrs::PointQuery` (one value per point, read by index
//!   from a parsed CSV block or straight from a `.npy` file's bytes);
//! - [`scheduler`]: the workers ([`stream_points`]);
//! - [`in_order`]: the ordered writing, and the bound on the chunks in flight;
//! - [`format`]: the output ([`Column`]: CSV rows or `.npy` values);
//! - [`progress`]: the progress bar (also of `inrs fractions`); [`spares`]: the pools of reused buffers.

mod format;
mod in_order;
mod progress;
mod scheduler;
mod source;
mod spares;

pub(crate) use format::{Column, write_f64};
pub(crate) use progress::Progress;
pub(crate) use scheduler::stream_points;
pub(crate) use source::{PointsInput, input_error};
