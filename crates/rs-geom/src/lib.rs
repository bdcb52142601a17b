//! 3-D geometry for CAD parts: the surfaces and edges of B-rep faces as objects that can be
//! evaluated, and the B-rep model a STEP or IGES file is read into.
//!
//! - [`Frame`] (a right-handed orthonormal placement, built as ISO 10303-42's `build_axes`)
//!   and [`Affine3`] (placements of assemblies, IGES 124 matrices).
//! - Curves of any dimension ([`Curve`], [`Conic`]): lines, conics and rational B-splines on
//!   `rs-spline`'s one [`KnotVector`](rs_spline::KnotVector) and evaluation kernel; exact
//!   conversion of any of them to a rational B-spline on an interval, closest points, exact
//!   images under affine maps ([`AffineMap`]: [`Affine3`] placements, a plane's
//!   [`PlaneCoordinates`] and [`AffinePlaneCoordinates`]), conic arcs from implicit equations
//!   (IGES 104).
//! - Surfaces: plane, cylinder, cone, sphere, torus, surface of revolution, surface of linear
//!   extrusion, offset surface, rational B-spline surface; each with its point, first and
//!   second derivatives, normal, parameter box, periods, poles and closest-point inversion.
//! - Pcurves ([`pcurve`]): the `(u, v)` curve of a 3-D edge on a face's surface (exact on
//!   planes and iso-lines, fitted with a deviation bound otherwise).
//!
//! Points and vectors are [`Point3`]; parameters are those of the file's standard
//! (ISO 10303-42 for STEP, IGES 5.3 for IGES), documented per surface.

mod affine3;
pub mod brep;
pub mod curve;
mod error;
mod frame;
mod map;
pub mod pcurve;
pub mod properties;
pub mod solid;
pub mod surface;
mod tolerance;

pub use affine3::Affine3;
pub use curve::{Conic, ConicKind, Curve};
pub use error::GeomError;
pub use frame::Frame;
pub use map::{AffineMap, AffinePlaneCoordinates, PlaneCoordinates};
pub use rs_spline::{Point, Point3, Vector};
pub use surface::{ParamSurface, PolynomialDegree, Surface};
pub use tolerance::{CHAIN_FACTOR, DEFAULT_MODEL_TOLERANCE, PRINTED_DIGITS, Tolerance};
