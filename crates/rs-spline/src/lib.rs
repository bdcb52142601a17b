//! B-spline and NURBS algebra for planar boundary curves.
//!
//! - [`KnotVector`] and [`NurbsCurve`]: validated NURBS, evaluation with first and second
//!   derivatives (rational quotient rule), knot insertion (Boehm), refinement, splitting,
//!   reversal, clamping, Bezier extraction.
//! - [`RationalBezier`]: evaluation, derivatives, de Casteljau subdivision in homogeneous
//!   coordinates, control and tight bounding boxes, conversion to `rs-roots` polynomials.
//! - Primitives with exact rational representations: [`segment`], [`polyline`],
//!   [`circular_arc`], [`circle`], [`elliptic_arc`], [`ellipse`].
//! - [`Domain`]: curves grouped into boundary loops, orientation, signed area, bounding box,
//!   and the JSON domain file of `shared/design/CONTRACTS.md`.
//!
//! Polynomial coefficients follow `rs-roots`: ascending power basis.
//!
//! # Examples
//!
//! ```
//! use rs_spline::{circle, Point, prelude::*};
//! let c = circle(Point::new(0.0, 0.0), 1.0).unwrap();
//! // Knot insertion and Bezier extraction leave the curve unchanged.
//! let refined = c.insert_knot(0.1, 2).unwrap();
//! assert!(refined.point_at(0.3).distance(c.point_at(0.3)) < 1e-15);
//! assert_eq!(c.to_bezier().len(), 4);
//! ```

mod affine;
mod arc;
mod bezier;
mod curve;
mod domain;
mod error;
pub mod grid;
mod homogeneous;
mod knots;
pub mod limits;
mod line;
mod nurbs;
mod point;
pub mod quadrature;

pub use affine::Affine;
pub use arc::{circle, circular_arc, ellipse, elliptic_arc};
pub use bezier::RationalBezier;
pub use curve::{
    ArcLengthTable, Flatten, ParamCurve, ParamCurveArclen, ParamCurveArea, ParamCurveDeriv,
    ParamCurveExtrema, prelude,
};
pub use domain::{BoundaryLoop, DEFAULT_CLOSURE_TOLERANCE, Domain, Orientation};
pub use error::{DomainError, SplineError};
pub use homogeneous::CurveDerivatives;
pub use knots::KnotVector;
pub use line::{polyline, segment};
pub use nurbs::NurbsCurve;
pub use point::{Axis, BoundingBox, Point};
