//! Convex domains of a free NURBS control point (Ginnis, Karousos and Kaklis 2009): where can
//! one control point move so that the curvature (planar curve) or torsion (space curve) keeps
//! its sign along the whole curve?
//!
//! The sign numerator `h_t(d) = a(t) . d + b(t)` is affine in the free point `d`
//! ([`SignNumerator`]: the curvature or torsion numerator, exact as piecewise Bernstein
//! polynomials with coefficients affine in the free point), so the exact domain `K = {d : h_t(d) > 0 for all t}` is
//! convex. [`approximate`] brackets `K` within a user box:
//! - inner polygons/polytopes from the Bernstein coefficients (`h` is a non-negative
//!   combination of them), refined by midpoint knot insertion; nested and converging;
//! - an outer polygon/polytope from the half-planes at sampled parameters (each necessary).
//!
//! [`ConvexPolygon`] and [`ConvexPolytope`] clip by half-planes / half-spaces.
//!
//! # Examples
//!
//! ```
//! use rs_convex::{approximate, BoundingBox3, ConvexDomainOptions, Sign, SignNumerator};
//! use rs_spline::{NurbsCurve, Point};
//! // Quadratic Bezier (0,0), d, (2,0): positive curvature exactly when d is below the chord.
//! let c = NurbsCurve::bezier(vec![Point::new(0.0, 0.0), Point::new(1.0, -1.0), Point::new(2.0, 0.0)], None).unwrap();
//! let h = SignNumerator::curvature(&c, 1).unwrap();
//! let bbox = BoundingBox3::from_ranges(&[-1.0, 3.0, -2.0, 2.0]).unwrap();
//! let k = approximate(&h, &bbox, &ConvexDomainOptions::default()).unwrap();
//! assert!((k.inner().measure() - 8.0).abs() < 1e-12); // the lower half of the box
//! assert!((k.outer.measure() - 8.0).abs() < 1e-12);
//! ```

mod approximation;
mod clip;
mod curve_file;
mod error;
mod limits;
mod polygon;
mod polytope;
mod sign_numerator;
mod space_curve;
mod svg;

pub use approximation::{
    BoundingBox3, ConvexDomain, ConvexDomainOptions, Level, MAX_BOX_COORDINATE, Outcome, Region,
    Sign, approximate,
};
pub use curve_file::{FreeCurve, load_curve, parse_curve};
pub use error::ConvexError;
pub use limits::MAX_LEVEL;
pub use polygon::ConvexPolygon;
pub use polytope::{ConvexPolytope, P3};
pub use rs_spline::Point3;
pub use sign_numerator::{AffineForm, SignNumerator};
pub use space_curve::SpaceCurve;
pub use svg::to_svg;
