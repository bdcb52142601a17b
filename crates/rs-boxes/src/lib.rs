//! Monotone boxes of NURBS boundaries (Sommariva and Vianello, inRS, section 2).
//!
//! The boundary is cut where `x'(t) = 0` or `y'(t) = 0` into pieces on which both coordinates
//! are monotone; each piece's bounding box is spanned by its end points (a *monotone box*), and
//! a vertical or horizontal line meets the piece at most once, at a parameter found by a
//! bracketed solve. Boxes may be refined (Remark 2.1); the critical points where a ray can touch
//! the boundary without crossing it are collected for the containment layer.
//!
//! - [`MonotoneBoxes`]: construction, global bounding box, critical abscissas/ordinates.
//! - [`MonotoneBox`]: one box, with its piece, directions, ray crossings and a
//!   boundary-distance test.
//! - [`BezierPiece`]: **the** homogeneous Bezier piece, a rational Bezier piece stored as
//!   homogeneous Bernstein coefficients beside its Cartesian control points (exact end points,
//!   monotone solves, splits) and, relative to an origin, the evaluation cell coverage
//!   integrates with ([`RelativePiece`]).
//! - [`ChordBand`]: the band round a piece's chord (or a part of it) that decides most
//!   containment queries without a solve.
//! - [`BoxGrid`]: a uniform grid finding the boxes that can be near a point.

mod boxes;
mod chord_band;
mod error;
mod grid;
mod monotone_box;
mod piece;

pub use boxes::{
    BOX_BUDGET, BOXES_PER_DIAGONAL, BYTES_PER_BOX, BoxOptions, CriticalKind, CriticalPoint,
    DEFAULT_SUBDIVISIONS, MAX_SUBDIVISIONS, MonotoneBoxes,
};
pub use chord_band::ChordBand;
pub use error::{BoxError, PieceError};
pub use grid::BoxGrid;
pub use monotone_box::{MonotoneBox, Monotonicity};
pub use piece::{BalancedPart, BezierPiece, RelativePiece};
