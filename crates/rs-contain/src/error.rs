//! Errors of the containment layer.

use rs_boxes::BoxError;
use rs_spline::DomainError;
use thiserror::Error;

/// Why a classifier could not be built.
#[derive(Debug, Error)]
pub enum ContainError {
    /// The domain is not usable (for crossing numbers: a loop does not close).
    #[error(transparent)]
    Domain(#[from] DomainError),
    /// Invalid box options.
    #[error(transparent)]
    Boxes(#[from] BoxError),
    /// The boundary tolerance must be finite and >= 0.
    #[error("invalid boundary tolerance {0:?} (must be finite and >= 0)")]
    InvalidTolerance(f64),
}
