//! Errors of the geometry layer: each names what is wrong in one line.

use thiserror::Error;

/// Why a curve, surface or placement cannot be built or evaluated.
#[derive(Clone, Debug, Error, PartialEq)]
#[non_exhaustive]
pub enum GeomError {
    /// A placement's axes do not span space (a zero axis, or a reference direction along the
    /// axis).
    #[error("degenerate axes: {0}")]
    DegenerateFrame(&'static str),
    /// A number that must be finite is not, or a coordinate is beyond the input limits.
    #[error("{what} is not finite or too large: {value:e}")]
    NotFinite {
        /// What the number is (`radius`, `coordinate`, ...).
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// A length that must be positive is not.
    #[error("{what} must be positive, not {value:e}")]
    NotPositive {
        /// What the number is.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// A curve or surface that the spline layer refused.
    #[error(transparent)]
    Spline(#[from] rs_spline::SplineError),
}
