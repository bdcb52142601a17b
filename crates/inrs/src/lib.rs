//! inrs: exact point containment for planar domains bounded by NURBS and rational Bezier
//! curves.
//!
//! This facade re-exports the layers so that downstream code can depend on one crate:
//! - [`roots`] (`rs-roots`): real polynomial roots.
//! - [`spline`] (`rs-spline`): NURBS algebra, primitives, domains and domain files.
//!
//! The containment algorithms (crossing-number inRS and generalized winding numbers) are added
//! as their own layers and re-exported here as they land.
//!
//! # Examples
//!
//! ```
//! use inrs::spline::{circle, Domain, Point};
//! let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
//! let s = inrs::DomainSummary::of(&d);
//! assert_eq!(s.bezier_pieces, 4);
//! assert!((s.signed_area - std::f64::consts::PI).abs() < 1e-13);
//! ```

pub use rs_roots as roots;
pub use rs_spline as spline;

pub use rs_spline::{BoundingBox, Domain, DomainError, NurbsCurve, Point, RationalBezier};

mod summary;

pub use summary::{DomainSummary, LoopSummary};
