//! STEP (ISO 10303-21) files: the trimming loops of every `ADVANCED_FACE` and `FACE_SURFACE`
//! in its surface's parameter space.
//!
//! # Parser
//!
//! The Part 21 layer is our own small tokenizer (`tokens`) and instance table
//! (`graph`). The crate `step-io` (0.3, MIT/Apache-2.0, depends on `logos` and `memchr`)
//! was evaluated: its parser does bound nesting (64 levels) and has an untyped `Graph`, but
//! it is marked experimental with breaking changes expected, it brings about 200,000 lines of
//! generated schema code that cannot be left out of the build, and it heals or drops
//! non-standard input with warnings where we want a one-line error naming the instance. The
//! subset we need (strings with `''`, comments, enumerations, typed parameters, `$`, `*`,
//! nested lists, complex instances, references) is a few hundred lines, fully under our
//! hostile-input rules: one pass over the bytes, nesting limited to 32 levels, no count
//! taken from the file before the data it counts has been read.
//!
//! # Face order
//!
//! The faces come in the order `OpenCASCADE`'s `TopExp_Explorer(shape, TopAbs_FACE)` visits
//! them after `STEPControl_Reader::TransferRoots` and `OneShape` (checked with `OpenCASCADE` 7.8
//! on the 28 STEP files of `FreeCAD`'s `Idflibs` and the gmsh demos, assemblies included):
//!
//! 1. roots: the `PRODUCT_DEFINITION`s that are not the component (related product
//!    definition) of any `NEXT_ASSEMBLY_USAGE_OCCURRENCE`, in file order;
//! 2. a product definition: first its own shape (`PRODUCT_DEFINITION_SHAPE` ->
//!    `SHAPE_DEFINITION_REPRESENTATION` -> representation), then its components, one per
//!    `NEXT_ASSEMBLY_USAGE_OCCURRENCE` whose relating product definition it is, in file
//!    order; a component used twice is listed twice (each occurrence is a placed copy);
//! 3. a representation: its items in order, then the representations linked to it by a
//!    `SHAPE_REPRESENTATION_RELATIONSHIP` without a transformation (the
//!    `SHAPE_REPRESENTATION` -> `ADVANCED_BREP_SHAPE_REPRESENTATION` link some systems
//!    write; relationships with a transformation are the assembly placements of step 2);
//! 4. items: `MANIFOLD_SOLID_BREP`/`FACETED_BREP` -> outer shell; `BREP_WITH_VOIDS` -> outer
//!    then void shells; `SHELL_BASED_SURFACE_MODEL` -> its shells; `CLOSED_SHELL`/`OPEN_SHELL`
//!    -> `cfs_faces` in order; `ORIENTED_*_SHELL` -> its shell; `ORIENTED_FACE` -> its face;
//!    `MAPPED_ITEM` -> the mapped representation; other items (placements, styles) are not
//!    shapes.
//!
//! A file with no product structure leading to faces falls back to every shape
//! representation in file order (then every solid or surface model, then every shell). The
//! order of a product's own shape before its components could not be told apart on the real
//! files (their assembly representations hold placements only); it follows `OpenCASCADE`'s
//! `STEPControl_ActorRead`.
//!
//! # Loops
//!
//! The `FACE_OUTER_BOUND` comes first, then the other bounds in the face's order.
//! `OpenCASCADE` keeps the file order of the bounds (its outer wire is found geometrically,
//! by `BRepTools::OuterWire`); the domain built from the loops does not depend on their order.
//! Edges are trimmed between their vertices on the 3-D curve (the parameters of the
//! vertices: exact for lines and conics, a bounded search for B-splines); each pcurve is cut
//! where it passes the vertices' `(u, v)`, since the 3-D curve and the pcurve need not share
//! their parameter (a rational B-spline circle in 3-D, a line in `(u, v)`): on a plane the
//! `(u, v)` is exact, elsewhere the surface is inverted at the vertex starting from the
//! pcurve's point at the 3-D parameter (see `invert`; that point stays where the inversion
//! fails); see `loops` for orientation, seams, periods and poles. A `VERTEX_LOOP` (a cone's apex)
//! bounds nothing in `(u, v)` and is skipped. The face's own `same_sense` is not applied:
//! it flips the surface normal, not the loops in `(u, v)`.
//!
//! Faces on a `PLANE` whose edges have no pcurve are mapped from their 3-D curves into the
//! plane's `(u, v)` (an exact affine map); other faces without pcurves are refused with a
//! message naming the edge and the surface (no projection).
//!
//! # Units
//!
//! Lengths (and so `(u, v)` on planes, the `v` of cylinders, the tolerance) stay in the
//! file's length unit; [`length_unit_mm`] gives millimetres per unit (`OpenCASCADE` converts to
//! millimetres). Angles of circles, ellipses and trims are converted to radians with the
//! context's `PLANE_ANGLE_UNIT`. Pcurves are read as written: a file in degrees would have
//! its angular surface parameters in degrees where `OpenCASCADE` rescales them.
//!
//! # Tolerance
//!
//! The model's [`Tolerance`] states the largest length `UNCERTAINTY_MEASURE_WITH_UNIT` of the
//! representation contexts the faces are read in (in the file's length unit), `None` if none
//! states one. Consecutive curves of a loop must meet within [`gap_tolerance`] of it in
//! `(u, v)`.

mod curves;
mod faces;
mod geom;
mod graph;
mod invert;
mod loops;
mod plane;
mod shape;
mod surface;
mod tokens;
mod units;

use std::collections::HashMap;

use rs_spline::NurbsCurve;

use rs_geom::Tolerance;
use rs_geom::brep::{Face, Model};

use super::{CadFormat, CadModel, legacy_face};
use crate::IoError;
use graph::Graph;
use units::Units;

/// The gap accepted between consecutive curves of a loop in `(u, v)`, from the file's
/// uncertainty `tol` (`1e-6` when it states none): `10 tol`, at least `1e-6`. Pcurves are
/// approximations written to the file's tolerance in 3-D; the factor 10 leaves room for
/// the parameter scale of the surface without accepting a wrong trim (whose gap is of the
/// size of a curve).
pub fn gap_tolerance(tol: Option<f64>) -> f64 {
    (10.0 * tol.unwrap_or(1e-6)).max(1e-6)
}

/// Millimetres per length unit of the STEP file `text` (its first representation context
/// with a length unit), 1 when it states none.
///
/// # Errors
/// [`IoError::Cad`] for a file that does not parse.
pub fn length_unit_mm(text: &[u8]) -> Result<f64, IoError> {
    let g = Graph::parse(text).map_err(cad)?;
    for i in g.instances() {
        if i.is("GLOBAL_UNIT_ASSIGNED_CONTEXT")
            && let Ok(u) = units::context_units(&g, i.label)
        {
            return Ok(u.mm_per_length);
        }
    }
    Ok(1.0)
}

fn cad(message: String) -> IoError {
    IoError::Cad {
        format: "STEP",
        message,
    }
}

/// Reads the faces of a STEP file's text.
///
/// # Errors
/// [`IoError::Cad`] for a file that is not ISO 10303-21 or whose entity graph is broken
/// (missing or cyclic references in the shape structure, nesting beyond the limits). A face
/// whose loops cannot be read is listed with an `Err` in [`Face::loops`].
pub fn read_step(text: &[u8]) -> Result<CadModel, IoError> {
    let g = Graph::parse(text).map_err(cad)?;
    let uses = faces::face_order(&g).map_err(cad)?;
    let mut contexts: HashMap<Option<u64>, Units> = HashMap::new();
    for u in &uses {
        if let std::collections::hash_map::Entry::Vacant(e) = contexts.entry(u.context) {
            let units = match u.context {
                Some(c) => units::context_units(&g, c).map_err(cad)?,
                None => Units::default(),
            };
            e.insert(units);
        }
    }
    let tolerance = contexts
        .values()
        .filter_map(|u| u.uncertainty)
        .reduce(f64::max);
    let gap = gap_tolerance(tolerance);
    // A face used many times (assemblies) is read once.
    let mut read: HashMap<(u64, Option<u64>), Face> = HashMap::new();
    let mut faces = Vec::with_capacity(uses.len().min(1 << 16));
    let mut points = 0usize;
    for u in uses {
        let face = match read.get(&(u.face, u.context)) {
            Some(f) => f.clone(),
            None => {
                let units = contexts.get(&u.context).copied().unwrap_or_default();
                let f = read_face(&g, u.face, &units, gap)?;
                read.insert((u.face, u.context), f.clone());
                f
            }
        };
        if let Ok(loops) = &face.loops {
            points += loops
                .iter()
                .flatten()
                .map(|c| c.control_points().len())
                .sum::<usize>();
            if points > MAX_TOTAL_POINTS {
                return Err(cad(format!(
                    "the faces hold more than {MAX_TOTAL_POINTS} control points in all"
                )));
            }
        }
        faces.push(face);
    }
    Ok(CadModel {
        format: CadFormat::Step,
        model: Model {
            faces,
            tolerance: Tolerance::new(tolerance).map_err(|e| cad(e.to_string()))?,
            ..Model::default()
        },
    })
}

/// The most control points of all listed faces together (assemblies list shared faces once
/// per use; this bounds the memory of the model).
const MAX_TOTAL_POINTS: usize = 1 << 26;

fn read_face(g: &Graph, label: u64, units: &Units, gap: f64) -> Result<Face, IoError> {
    let inst = g.get(label, "a shell").map_err(cad)?;
    let entity = format!("#{label}");
    let geometry = inst
        .simple()
        .and_then(|a| a.reference(2, "face_geometry"))
        .and_then(|s| surface::Surface::read(g, s, &inst.what(), units.radians_per_angle));
    let (surface, loops): (String, Result<Vec<Vec<NurbsCurve>>, String>) = match geometry {
        Ok(s) => {
            let cx = loops::FaceContext {
                g,
                surface: &s,
                radians: units.radians_per_angle,
                gap,
            };
            let loops = loops::face_loops(&cx, inst);
            (s.name.clone(), loops)
        }
        Err(m) => (String::from("?"), Err(m)),
    };
    Ok(legacy_face(entity, surface, loops))
}
