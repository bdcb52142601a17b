//! Streaming points through a computation: CSV or `.npy` in, CSV or `.npy` out, in bounded
//! runs of points that are read, parsed, computed and formatted on all threads and written in
//! input order. Memory depends on the run size, not on the number of points.
//!
//! - [`source`]: the points file, as a reader of `rs-io` (runs read by position or in order);
//! - what a command computes is one or more `inrs::PointQuery` (one value each per point,
//!   read by index from a parsed CSV run or straight from a `.npy` file's bytes);
//! - [`scheduler`]: the workers ([`stream_points`]);
//! - [`in_order`]: the ordered writing, and the bound on the runs in flight;
//! - [`format`]: the output ([`Column`]: CSV rows or `.npy` values);
//! - [`progress`]: the progress bar (also of `inrs fractions`); [`spares`]: the pool of reused
//!   result buffers.

mod format;
mod in_order;
mod progress;
mod scheduler;
mod source;
mod spares;

pub(crate) use format::{Column, write_f64};
pub(crate) use progress::Progress;
pub(crate) use scheduler::{stream_points, stream_prepared};
pub(crate) use source::PointsInput;
