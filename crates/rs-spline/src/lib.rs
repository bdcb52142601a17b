//! B-spline and NURBS algebra for planar boundary curves.
//!
//! A NURBS curve is `C(u) = sum_i N_{i,p}(u) w_i P_i / sum_i N_{i,p}(u) w_i`: B-spline basis
//! functions of degree `p` on a knot vector, control points `P_i` and positive weights `w_i`.
//! Between knots it is a rational Bezier piece, which every algorithm here works on in
//! homogeneous coordinates `(w P, w)`, where the rational curve is polynomial.
//!
//! - [`KnotVector`] and [`NurbsCurve`]: validated NURBS, evaluation with first and second
//!   derivatives (rational quotient rule), knot insertion (Boehm), refinement, splitting,
//!   reversal, clamping, Bezier extraction.
//! - [`RationalBSpline`]: rational B-splines of any dimension ([`Point`], [`Point3`]) on the
//!   same kernels: evaluation through [`rational_sums`] (which [`NurbsCurve`] uses too), knot
//!   insertion, refinement, splitting, subsegments, clamping and reversal (one implementation,
//!   planar results bit for bit [`NurbsCurve`]'s), and the end-span continuation past the
//!   domain (`point_extended`, `extension`).
//! - [`RationalBezier`]: evaluation, derivatives, de Casteljau subdivision in homogeneous
//!   coordinates, control and tight bounding boxes, conversion to `rs-roots` polynomials.
//! - Primitives with exact rational representations: [`segment`], [`polyline`],
//!   [`circular_arc`], [`circle`], [`elliptic_arc`], [`ellipse`].
//! - The curve traits ([`prelude`]): [`ParamCurve`], [`ParamCurveDeriv`], [`ParamCurveArea`]
//!   (Green's theorem), [`ParamCurveArclen`], [`ParamCurveExtrema`], [`Flatten`], implemented by
//!   both curve types; [`Affine`] maps; the uniform [`grid`] index.
//! - [`Domain`]: curves grouped into boundary loops, orientation, signed area, bounding box;
//!   [`NearestBoundary`]: the nearest boundary point of a point, exactly.
//!   (The JSON domain file is read and written by `rs-io`.)
//! - [`quadrature`]: the one cache of Gauss-Legendre rules and the adaptive rule with an error
//!   estimate and bounded work; [`green`]: **the** Green's-theorem integral along a boundary
//!   piece (exact rules on polynomial pieces, the adaptive rule on rational ones).
//!
//! Polynomial coefficients follow `rs-roots`: ascending power basis.
//!
//! # References
//! - A. Sommariva, M. Vianello, *inRS: implementing the indicator function of NURBS-shaped
//!   planar domains*, Applied Mathematics Letters 130 (2022) 108026,
//!   doi:10.1016/j.aml.2022.108026.
//! - J. Spainhour, D. Gunderman, K. Weiss, *Robust containment queries over collections of
//!   rational parametric curves via generalized winding numbers* (2024), arXiv:2403.17371.
//! - L. L. Schumaker, A. Yu, *Approximation by polynomial splines on curved triangulations*
//!   (Vanderbilt University, 2021).
//! - A. I. Ginnis, E. I. Karousos, P. D. Kaklis, *A discrete methodology for controlling the
//!   sign of curvature and torsion for NURBS* (Springer, 2009).
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
mod balance;
mod bezier;
mod bezier_extraction;
mod crossing;
mod curve;
mod domain;
mod error;
pub mod green;
pub mod grid;
mod homogeneous;
mod insertion;
pub mod intersect;
mod kernel;
mod knots;
pub mod limits;
mod line;
mod nearest;
mod nurbs;
mod point;
mod point3;
mod point_source;
mod power_of_two;
pub mod quadrature;
mod rational_bspline;
mod vector;

pub use affine::Affine;
pub use arc::{circle, circular_arc, ellipse, elliptic_arc};
pub use balance::{
    BALANCE_RATIO, Balance, MAX_BALANCE_HALVINGS, Part, balanced_parts, balancing_exponent,
    crowds_ends, odds_map, scale_by_powers_of_two,
};
pub use bezier::RationalBezier;
pub use crossing::{certain_crossing, closed_in_crossing};
pub use curve::{
    ArcLengthTable, Flatten, ParamCurve, ParamCurveArclen, ParamCurveArea, ParamCurveDeriv,
    ParamCurveExtrema, flatten_chain, prelude,
};
pub use domain::{BoundaryLoop, DEFAULT_RELATIVE_CLOSURE_TOLERANCE, Domain, Orientation};
pub use error::{DomainError, SplineError};
pub use homogeneous::{CurveDerivatives, Hpoint};
pub use intersect::{
    CurveHit, CurveOverlap, IntersectError, IntersectOptions, Intersections, intersect,
};
pub use kernel::{rational_quotient, rational_sums, tensor_rational_sums, weights_are_equal};
pub use knots::KnotVector;
pub use line::{polyline, segment};
pub use nearest::{NearestBoundary, NearestPoint};
pub use nurbs::NurbsCurve;
pub use point::{Axis, BoundingBox, Point};
pub use point_source::{PointSource, PointsFn, points_from_fn};
pub use point3::Point3;
pub use power_of_two::times_power_of_two;
pub use rational_bspline::RationalBSpline;
pub use vector::Vector;
