//! Errors of the box construction.

use thiserror::Error;

/// Invalid box options.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum BoxError {
    /// Each monotone piece needs at least one box.
    #[error("subdivisions must be at least 1")]
    ZeroSubdivisions,
}
