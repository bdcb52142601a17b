//! inrs: exact point containment for planar domains bounded by NURBS and rational Bezier
//! curves.
//!
//! A point `q` is inside a domain bounded by closed curves when a ray from `q` crosses the
//! boundary an odd number of times. inRS counts the crossings exactly: the boundary is cut into
//! pieces monotone in `x` and `y`, so a vertical ray meets each piece's box at most once and one
//! bracketed root of a Bernstein polynomial decides each crossing. For boundaries with gaps the
//! generalized winding number `(1/2 pi) sum of the angles the curves subtend at q` decides
//! instead. See docs/ARCHITECTURE.md for the layers and docs/FORMATS.md for the files.
//!
//! This facade re-exports the layers so that downstream code can depend on one crate:
//! - [`roots`] (`rs-roots`): real polynomial roots.
//! - [`spline`] (`rs-spline`): NURBS algebra, the curve traits, primitives, domains.
//! - [`boxes`] (`rs-boxes`): monotone boxes and critical points.
//! - [`contain`] (`rs-contain`): the inRS classifier (inRS1, inRS2, fallbacks, boundary).
//! - [`coverage`] (`rs-coverage`): exact cell coverage on rectilinear grids (area
//!   fractions, centroids and face apertures), for whole grids or bands of rows.
//! - [`cubature`] (`rs-cubature`): positive interior cubature (Sommariva and Vianello):
//!   rules of degree `n` with at most `(n + 1)(n + 2) / 2` nodes inside the domain and
//!   positive weights, and exact polynomial moments by Green's theorem.
//! - [`mesh`] (`rs-mesh`): well-spaced points, curved triangulations (and their
//!   Clough–Tocher and Powell–Sabin refinements) and point location in them.
//! - [`trispline`] (`rs-trispline`): polynomial splines on curved triangulations:
//!   Bernstein–Bézier polynomials, `S_d^0`, evaluation anywhere in the domain,
//!   quasi-interpolation, the spline file.
//! - [`geom`] (`rs-geom`): 3-D geometry of CAD parts: frames and placements, curves of any
//!   dimension, surfaces with derivatives, normals and inversion, the B-rep model (faces,
//!   shells, solids) and the tolerance policy of CAD files.
//! - [`convex`] (`rs-convex`): convex domains of a free control point keeping the sign of
//!   curvature or torsion.
//! - [`io`] (`rs-io`): domains from JSON domain files, SVG paths and files,
//!   TrueType/OpenType glyphs and (feature `dxf`, on by default) DXF drawings; the points
//!   files (`io::points`: CSV and `.npy`, streamed in runs of points), whose readers are
//!   re-exported here ([`CsvReader`], [`NpyReader`], [`PointsReader`], [`parse_points`], ...).
//!
//! Plus, from `rs-contain`, the domain summary printed by `inrs info` ([`DomainSummary`]).
//! Containment: build a [`Classifier`] and ask it through [`Locate`] (or [`Containment`] for
//! every method and fill rule, as the command line does).
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

// The README's Rust example, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

pub use rs_boxes as boxes;
pub use rs_contain as contain;
pub use rs_convex as convex;
pub use rs_coverage as coverage;
pub use rs_cubature as cubature;
pub use rs_geom as geom;
pub use rs_io as io;
pub use rs_mesh as mesh;
pub use rs_roots as roots;
pub use rs_spline as spline;
pub use rs_trispline as trispline;

pub use rs_contain::{
    Classifier, ContainError, ContainOptions, Containment, Locate, Location, Method, PointQuery,
    engines_many, locate_each, locate_many, prepare_many,
};
pub use rs_spline::{BoundingBox, Domain, DomainError, NurbsCurve, Point, RationalBezier};

// The points files, from `rs-io` (`rs_io::points`, also `inrs::io::points`), at the top level
// where the command line has them.
pub use rs_contain::{DomainSummary, LoopSummary, significant};
pub use rs_io::points::{
    CsvPoints, CsvReader, EncodedPoints, MAX_LINE_BYTES, MAX_NPY_POINTS, NPY_HEADER_BYTES,
    NpyReader, NpyType, PointRecord, PointRun, PointsError, PointsReader, ReadProgress, RunPoints,
    RunSizes, npy_header, open_points, parse_points, read_points,
};

/// The traits most code wants in scope: the curve vocabulary of `rs-spline` and the queries
/// ([`Locate`], [`PointQuery`]).
pub mod prelude {
    pub use rs_contain::{Locate, PointQuery};
    pub use rs_spline::prelude::*;
}
