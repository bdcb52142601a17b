//! Errors.

use crate::limits::MAX_LEVEL;
use rs_spline::SplineError;
use thiserror::Error;

/// Why a convex domain could not be computed.
#[derive(Debug, Error)]
pub enum ConvexError {
    /// The bounding box is malformed.
    #[error("invalid box: {0}")]
    InvalidBox(String),
    /// The tolerance is negative or not finite.
    #[error("invalid tolerance {0}: must be finite and non-negative")]
    InvalidTolerance(f64),
    /// The refinement level is too deep.
    #[error("max level {0} is above {max} (each level doubles the inequalities)", max = MAX_LEVEL)]
    InvalidLevel(u32),
    /// A planar curve with a 3-D box or the reverse.
    #[error("the curve is {curve}-D but the box is {bbox}-D")]
    DimensionMismatch {
        /// Dimension of the curve.
        curve: usize,
        /// Dimension of the box.
        bbox: usize,
    },
    /// The curve file is malformed.
    #[error("curve file: {0}")]
    CurveFile(String),
    /// The curve is invalid.
    #[error(transparent)]
    Spline(#[from] SplineError),
    /// A planar curve entry of the file is invalid.
    #[error(transparent)]
    Curve(#[from] rs_io::IoError),
}
