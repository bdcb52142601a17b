//! Errors of the box construction.

use thiserror::Error;

/// Invalid box options, or a piece whose monotone splits cannot be computed.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum BoxError {
    /// Each monotone piece needs at least one box.
    #[error("subdivisions must be at least 1")]
    ZeroSubdivisions,
    /// More sub-boxes per monotone piece than [`crate::MAX_SUBDIVISIONS`].
    #[error("subdivisions {requested} exceeds the limit {limit}")]
    TooManySubdivisions {
        /// The number asked for.
        requested: usize,
        /// The limit.
        limit: usize,
    },
    /// A piece could not be cut into monotone parts (its tangency roots could not be
    /// computed): containment would not be exact, so nothing is built.
    #[error("curve {curve}, piece starting at parameter {parameter:?}: {source}")]
    Piece {
        /// Index of the curve.
        curve: usize,
        /// Start of the piece's parameter range.
        parameter: f64,
        /// What failed.
        source: PieceError,
    },
}

/// Why a piece could not be cut into monotone parts.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum PieceError {
    /// The root finder failed on a derivative numerator (for example, coefficients overflow).
    #[error("tangency roots: {0}")]
    Roots(#[from] rs_roots::RootsError),
    /// The piece is not a valid rational Bezier curve.
    #[error("invalid piece: {0}")]
    Spline(#[from] rs_spline::SplineError),
}
