//! Curved domains meshed (Schumaker and Yu 2021, sections 2-5 and 11): well-spaced points,
//! inscribed constrained Delaunay triangulations, their conversion to curved triangulations,
//! and point location in them.
//!
//! - [`well_spaced_points`]: Algorithm 11.1 (horizontal lines cut exactly with the boundary
//!   through the monotone boxes, interior points at spacing `~h`, boundary points nearly
//!   equally spaced by arc length on every loop); [`halton_points_in`]: quasi-Monte Carlo.
//! - [`CurvedTriangulation`]: inscribed triangulation (spade's constrained Delaunay, holes
//!   excluded by crossing parity), the convertibility check of Definition 4.2 with automatic
//!   insertion of boundary points, and Algorithm 4.1 (boundary edges become boundary arcs);
//!   exact curved-triangle areas by Green's theorem.
//! - [`Refinement`]: Clough–Tocher and Powell–Sabin refinements of a curved triangulation
//!   (Section 8), built with [`CurvedTriangulation::new_refined`], convertibility re-checked.
//! - [`CurvedLocator`]: which curved triangle holds a point, exact between an arc and its
//!   chord, `None` outside the domain.
//! - [`ExtendedRing`]: the ring of straight triangles of Algorithm 5.1 round the companion
//!   triangles ([`CurvedTriangulation::extended_ring`]), for drawing.
//! - [`mesh_svg`]: a figure of a curved triangulation.
//!
//! # Examples
//!
//! ```
//! use rs_mesh::{CurvedLocator, CurvedTriangulation, well_spaced_points};
//! use rs_spline::{circle, Domain, Point};
//! let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
//! let pts = well_spaced_points(&d, 8).unwrap();
//! let mesh = CurvedTriangulation::new(&d, &pts).unwrap();
//! let area: f64 = (0..mesh.triangles().len()).map(|t| mesh.triangle_area(t)).sum();
//! assert!((area - std::f64::consts::PI).abs() < 1e-10); // exactly the disc
//! let locator = CurvedLocator::new(&mesh).unwrap();
//! assert!(locator.triangle_at(Point::new(0.999, 0.0)).is_some()); // between an arc and its chord
//! assert!(locator.triangle_at(Point::new(1.001, 0.0)).is_none());
//! ```

mod boundary;
mod error;
mod extended;
mod json;
mod limits;
mod locate;
mod sample;
mod svg;
mod triangulation;

pub use boundary::{BoundaryPoint, check_boundary_pieces};
pub use error::MeshError;
pub use extended::ExtendedRing;
pub use json::{mesh_from_json, mesh_json, mesh_value};
pub use limits::{
    MAX_HALTON_TRIES_PER_POINT, MAX_LINES, MAX_MESH_PIECES, MAX_MESH_VERTICES, MAX_SAMPLE_POINTS,
};
pub use locate::CurvedLocator;
pub use sample::{WellSpacedPoints, halton_points_in, well_spaced_points};
pub use svg::mesh_svg;
pub use triangulation::{
    BoundaryArc, CurvedTriangulation, EdgeKind, MAX_INSERTED_EXTRA, MAX_INSERTED_PER_POINT,
    Refinement,
};
