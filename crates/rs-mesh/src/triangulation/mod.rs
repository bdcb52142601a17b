//! Curved triangulations (Schumaker and Yu 2021, Sections 3, 4 and 8): the type, its
//! construction from sampled points, and its refinements.
//!
//! The modules depend one way. `curved` holds the type, with private fields and one crate
//! constructor; every other module builds or reads it through those. `build` drives the
//! construction and calls the others, the refinement included; none of them calls back.
//!
//! - `curved`: [`CurvedTriangulation`], its edge kinds and boundary arcs, the
//!   [`Refinement`] kinds, accessors, exact areas.
//! - `parts`: [`CurvedTriangulation::from_parts`], parts read from a file, checked.
//! - `build`: [`CurvedTriangulation::new`] and [`CurvedTriangulation::new_refined`]: rounds
//!   of attempts, boundary points inserted until the triangulation is convertible.
//! - `cdt`: the constrained Delaunay triangulation of the chords, faces inside kept.
//! - `arcs`: chords replaced by their arcs (Algorithm 4.1).
//! - `convertible`: the test of Definition 4.2, that an arc meets no other edge.
//! - `crossing`: certified crossings of two boundary arcs (a boundary crossing itself).
//! - `insertion`: where an arc that fails the test gets its new boundary point.
//! - `refine`: Clough–Tocher and Powell–Sabin refinements (Section 8).

mod arcs;
mod build;
mod cdt;
mod convertible;
mod crossing;
mod curved;
mod insertion;
mod parts;
mod refine;

pub use build::{MAX_INSERTED_EXTRA, MAX_INSERTED_PER_POINT};
pub use curved::{BoundaryArc, CurvedTriangulation, EdgeKind, Refinement};
