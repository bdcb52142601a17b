//! Point containment for planar domains bounded by NURBS curves: the crossing-number algorithm
//! inRS of Sommariva and Vianello (2022), with inRS1 and inRS2 point loops, horizontal-ray and
//! winding-number fallbacks, and boundary detection; and generalized winding numbers for any
//! collection of rational Bezier / NURBS curves (Spainhour, Gunderman and Weiss 2024,
//! [`WindingField`]), with the paper's two ray-casting baselines.
//!
//! # Semantics
//! - **Domain**: the boundary loops of an [`rs_spline::Domain`], every loop closed (within the
//!   domain's closure tolerance; junction gaps are closed by moving the next piece's start onto
//!   the previous piece's end). A point is inside when a ray from it crosses the boundary an odd
//!   number of times: the even-odd rule, which for properly nested loops is the usual region
//!   with holes. Orientation is irrelevant: reversing any loop changes nothing.
//! - **Boundary**: with `tol = relative_tolerance x diagonal of the bounding box` (default
//!   [`DEFAULT_RELATIVE_TOLERANCE`] `= 1e-12`), a point is [`Location::Boundary`] when its
//!   vertical or horizontal distance to a monotone piece of the boundary, or its distance to a
//!   piece's end point, is at most `tol`. Every point within Euclidean distance `tol / sqrt(2)` of the
//!   boundary is `Boundary`; no point farther than `tol` is. All other points are `Inside` or
//!   `Outside`, exactly up to floating-point rounding in the crossing solves, which is far below
//!   `tol` (points `1e-8 x size` from the boundary are classified correctly).
//! - **Algorithm** (paper section 2): points outside the bounding box grown by `tol` are
//!   outside. Otherwise the downward vertical ray counts crossings with the monotone boxes it
//!   meets: above a box it crosses without any solve; inside a box one bracketed solve of
//!   `sum_i w_i (x_i - px) B_i(t) = 0` decides. If the point's abscissa is within `tol` of a
//!   critical abscissa (vertical tangency, x-turning vertex, vertical piece), the leftward
//!   horizontal ray is used; if its ordinate is also critical, the winding number (computed
//!   exactly by [`WindingField`]) decides, by parity.
//!   Crossings use half-open intervals (the ray is moved an infinitesimal distance off the
//!   vertices), so counts are exact at shared end points.
//! - **Invalid input**: an open boundary is an error when building the [`Classifier`];
//!   non-finite query coordinates are `Outside`.
//!
//! # Examples
//!
//! ```
//! use rs_contain::{Classifier, ContainOptions, Locate, Location, Method};
//! use rs_spline::{circle, Domain, Point};
//! // An annulus: outer circle and a hole (orientation does not matter).
//! let d = Domain::new(vec![
//!     circle(Point::new(0.0, 0.0), 2.0).unwrap(),
//!     circle(Point::new(0.0, 0.0), 1.0).unwrap(),
//! ])
//! .unwrap();
//! let c = Classifier::new(&d, ContainOptions::default()).unwrap();
//! assert_eq!(c.locate(Point::new(1.5, 0.0)), Location::Inside);
//! assert_eq!(c.locate(Point::new(0.5, 0.0)), Location::Outside);
//! assert_eq!(c.locate(Point::new(0.0, -1.0)), Location::Boundary);
//! ```

mod classifier;
mod crossings;
mod engine;
mod error;
mod filled_area;
mod gwn;
mod halton;
mod locality;
mod location;
mod locator;
mod many;
mod polygon;
mod query;
mod rays;
mod rows;
mod summary;

pub use classifier::{Classifier, ContainOptions, DEFAULT_RELATIVE_TOLERANCE};
pub use crossings::{BoundaryCrossing, boundary_crossing};
pub use engine::{Containment, Engine, FAST_ONE_BY_ONE_MAX_POINTS};
pub use error::ContainError;
pub use filled_area::{
    LoopNesting, MAX_NESTED_LOOPS, NestingError, curve_boundary_signs, even_odd_area, fill_nesting,
    filled_area, loop_depths, loop_nesting,
};
pub use gwn::{
    CurveHierarchy, FastWindingField, FillRule, HIERARCHY_DEPTH, QueryStats, WindingField,
    WindingNumbers, curve_winding_number,
};
pub use location::{Decision, FAST_METHOD_MIN_POINTS, Location, Method, fast_uses_locator};
pub use locator::{DEFAULT_GRID_CELLS, LocatorIndex, LocatorOptions, PointLocator};
pub use many::{DomainLocations, engines_many, locate_each, locate_many, prepare_many};
pub use query::{Locate, PointQuery};
/// Points read by index (from `rs-spline`, re-exported beside the queries that read them).
pub use rs_spline::{PointSource, PointsFn, points_from_fn};
pub use summary::{DomainSummary, LoopSummary, significant};

/// What the papers compare against, and the points they compare on: kept out of the core API
/// because no one should classify with them, but needed to reproduce the papers' tables.
///
/// - [`FlattenedPolygon`](baselines::FlattenedPolygon): the boundary flattened to a polygon
///   and an INPOLY2-style crossing test (the inRS paper's baseline).
/// - [`WindingAlgorithm`](baselines::WindingAlgorithm): the GWN paper's two ray-casting
///   variants besides the adaptive algorithm, for
///   [`WindingField::winding_number_with`].
/// - [`halton_points`](baselines::halton_points), [`halton_points_from`](baselines::halton_points_from)
///   and [`radical_inverse`](baselines::radical_inverse): the quasi-random test points of the
///   papers' experiments.
pub mod baselines {
    pub use crate::gwn::WindingAlgorithm;
    pub use crate::halton::{halton_points, halton_points_from, radical_inverse};
    pub use crate::polygon::FlattenedPolygon;
}
