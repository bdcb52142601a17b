//! Errors.

use rs_boxes::BoxError;
use rs_contain::ContainError;
use rs_spline::{DomainError, SplineError};
use thiserror::Error;

/// Why sampling or meshing failed.
#[derive(Debug, Error)]
pub enum MeshError {
    /// `ny` must be at least 2 and at most [`crate::MAX_LINES`].
    #[error("ny must be at least 2 and at most {max}, got {0}", max = crate::MAX_LINES)]
    TooFewLines(usize),
    /// The requested number of points is zero, above the limit, or unreachable.
    #[error(
        "cannot sample {0} points: the count must be between 1 and {max}, and the domain must fill at least 1/{tries} of its bounding box",
        max = crate::MAX_SAMPLE_POINTS,
        tries = crate::MAX_HALTON_TRIES_PER_POINT
    )]
    InvalidCount(usize),
    /// The sampling would produce more points than [`crate::MAX_SAMPLE_POINTS`].
    #[error("about {estimate:.3e} sample points exceed the limit {limit}: choose a smaller ny")]
    TooManyPoints {
        /// The estimated or reached count.
        estimate: f64,
        /// The limit.
        limit: usize,
    },
    /// The boundary has more Bezier pieces than [`crate::MAX_MESH_PIECES`].
    #[error(
        "the boundary has {pieces} Bezier pieces; meshing and sampling by lines support at most {limit} (docs/SEMANTICS.md, Limits)"
    )]
    TooManyPieces {
        /// The boundary's Bezier pieces.
        pieces: usize,
        /// The limit.
        limit: usize,
    },
    /// The domain has no area.
    #[error("the domain has no area (zero height)")]
    NoArea,
    /// The boundary could not be made convertible by inserting boundary points.
    #[error(
        "the inscribed triangulation is still not convertible after {rounds} rounds of boundary point insertion ({})",
        match near {
            Some(p) => format!(
                "{failing} boundary arcs still cross edges, one near ({}, {}): the boundary probably crosses or overlaps itself there",
                p.x, p.y
            ),
            None => "the last round's interior points fell outside it".to_string(),
        }
    )]
    NotConvertible {
        /// Rounds tried.
        rounds: usize,
        /// Arcs still failing.
        failing: usize,
        /// A point of one of them (none if the last round dropped interior points instead).
        near: Option<rs_spline::Point>,
    },
    /// Boundary point insertion was stopped at its budget with arcs still crossing edges:
    /// the boundary overlaps or crosses itself (or comes closer to itself than the
    /// refinement can separate) near `near`.
    #[error(
        "boundary point insertion stopped at {inserted} points (limit {limit}) with {failing} boundary arcs still crossing edges, one near ({x}, {y}): the boundary probably crosses or overlaps itself there",
        x = near.x,
        y = near.y
    )]
    InsertionLimit {
        /// Boundary points inserted so far.
        inserted: usize,
        /// The budget: see [`crate::CurvedTriangulation::new`].
        limit: usize,
        /// Arcs still failing.
        failing: usize,
        /// A point of one of them.
        near: rs_spline::Point,
    },
    /// Two boundary curves certainly meet at a point other than a shared end (the boundary
    /// crosses itself, or two loops cross): no triangulation has both as edges.
    #[error(
        "the boundary crosses itself near ({x}, {y}): two of its curves meet there, and a curved triangulation needs loops that neither cross nor touch",
        x = near.x,
        y = near.y
    )]
    BoundaryCrosses {
        /// A point within the two curves' crossing region.
        near: rs_spline::Point,
    },
    /// A boundary chord could not be inserted even after refinement (the boundary touches
    /// itself or loops cross).
    #[error("the constrained Delaunay triangulation failed: {0}")]
    Triangulation(String),
    /// The domain is invalid for containment (open loops, ...).
    #[error(transparent)]
    Contain(#[from] ContainError),
    /// Monotone boxes could not be built.
    #[error(transparent)]
    Boxes(#[from] BoxError),
    /// A curve operation failed.
    #[error(transparent)]
    Spline(#[from] SplineError),
    /// The domain is invalid.
    #[error(transparent)]
    Domain(#[from] DomainError),
    /// A triangulation read from a file is not one (an index out of range, an inverted
    /// triangle, an arc off its curve or not on its triangle's edge).
    #[error("invalid triangulation: {0}")]
    Invalid(String),
}
