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
//!    `MAPPED_ITEM` -> the mapped representation (its placement is not applied: the files seen
//!    map presentation only); other items (placements, styles) are not shapes.
//!
//! A file with no product structure leading to faces falls back to every shape
//! representation in file order (then every solid or surface model, then every shell). The
//! order of a product's own shape before its components could not be told apart on the real
//! files (their assembly representations hold placements only); it follows `OpenCASCADE`'s
//! `STEPControl_ActorRead`.
//!
//! # Shells, solids, placements
//!
//! The model's shells and solids come in the same walk, so the faces of the solids' shells,
//! then of the free shells, then the free faces are the face order (as `OpenCASCADE`'s
//! explorers give them). A `MANIFOLD_SOLID_BREP` is a solid of its outer `CLOSED_SHELL`, a
//! `BREP_WITH_VOIDS` of its outer shell and its voids; a solid whose outer shell is not
//! closed (an `OPEN_SHELL`, or a `CLOSED_SHELL` some `EDGE_CURVE` of which only one of its
//! faces uses) is no solid for `OpenCASCADE`, and its shells stay free shells. A face's
//! `same_sense` (its outward normal along `S_u x S_v`) composes the face's own flag with an
//! `ORIENTED_FACE` and an `ORIENTED_CLOSED_SHELL` (a void) of orientation `.F.`.
//!
//! A component placed by an assembly occurrence (`NEXT_ASSEMBLY_USAGE_OCCURRENCE` ->
//! `PRODUCT_DEFINITION_SHAPE` -> `CONTEXT_DEPENDENT_SHAPE_REPRESENTATION` ->
//! `REPRESENTATION_RELATIONSHIP_WITH_TRANSFORMATION` -> `ITEM_DEFINED_TRANSFORMATION`) is
//! moved by `T = A(item_2) A(item_1)^-1` (`A(p)` the map of placement `p`'s frame), the
//! occurrences' maps composed from the top (`T_1 T_2 ... T_n`), as `OpenCASCADE` locates them.
//! A face's surface and 3-D edges are placed; its `(u, v)` loops are not changed by a
//! placement. A face used by several occurrences is read once and placed per occurrence.
//!
//! # Loops
//!
//! The `FACE_OUTER_BOUND` comes first, then the other bounds in the face's order.
//! `OpenCASCADE` keeps the file order of the bounds (its outer wire is found geometrically,
//! by `BRepTools::OuterWire`); the domain built from the loops does not depend on their order.
//! See `loops` for the cutting of pcurves at the vertices, orientation, seams, periods and
//! poles. A `VERTEX_LOOP` (a cone's apex) bounds nothing in `(u, v)` and is skipped; a face
//! bounded by nothing else (a whole sphere) is its surface's natural parameter box, with the
//! seams and poles as `OpenCASCADE`'s wire runs them, where that box is finite (an unbounded
//! surface is an error). The face's own `same_sense` is not applied to the loops: it flips the
//! surface normal, not the loops in `(u, v)`.
//!
//! Edges without a pcurve on the face's surface: on a `PLANE` their 3-D curves are mapped
//! into the plane's `(u, v)` (an exact affine map); on other surfaces their pcurves are
//! computed by `rs_geom::pcurve` (exact iso-lines of the surface where the edge is one, as on
//! patch boundaries; otherwise a fit with a bound on its 3-D deviation, the largest of a face's
//! in [`Face::pcurve_deviation`]); an edge whose pcurve's bound exceeds the file's tolerance
//! refuses its face, naming the edge, the bound and the tolerance.
//!
//! # Units
//!
//! Lengths (and so `(u, v)` on planes, the `v` of cylinders, the tolerance) stay in the
//! file's length unit; the model's `length_unit` names it, with millimetres per unit
//! (`OpenCASCADE` converts to millimetres). A component whose representation context has another length
//! unit than its assembly's is scaled into the assembly's by its occurrence's placement
//! (`A(item_2) k A(item_1)^-1`, `k` the ratio of the units), and a second root part in another
//! unit than the first into the first's: the model is in the unit of the first face's placed
//! coordinates; `(u, v)` stay the file's. Angles of circles,
//! ellipses and trims are converted to radians with the context's `PLANE_ANGLE_UNIT`.
//! Pcurves are read as written: in a file in degrees the angular parameters of surfaces stay
//! in degrees (the surfaces are read in those parameters) where `OpenCASCADE` rescales them.
//!
//! # Tolerance
//!
//! The model's [`Tolerance`] states the largest length `UNCERTAINTY_MEASURE_WITH_UNIT` of the
//! representation contexts the faces are read in (in the file's length unit), `None` if none
//! states one. Consecutive curves of a loop must meet within its
//! [`Tolerance::chain_gap`] in `(u, v)`.
//!
//! # Errors
//!
//! [`StepError`]: one line, naming the instance at fault. A broken file (syntax, its shape
//! structure) is an [`IoError::Cad`]; a broken face is listed with its error (a
//! `FaceError::Read` holding the [`StepError`]) while the other faces read.

mod error;
mod faces;
mod geometry;
mod graph;
mod loops;
mod surface;
mod tokens;
mod units;

use std::collections::HashMap;
use std::collections::hash_map::Entry;

use rs_geom::brep::{Edge, Face, FaceError, LengthUnit, Model, ReadError};
use rs_geom::{Affine3, Surface, Tolerance};

use super::{CadFormat, CadModel};
use crate::IoError;
pub use error::StepError;
use faces::{FaceUse, ShellUse, SolidUse};
use graph::Graph;
use loops::{FaceContext, FaceLoops};
use surface::FaceSurface;
use units::Units;

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

fn cad(e: StepError) -> IoError {
    IoError::Cad {
        format: "STEP",
        message: e.to_string(),
    }
}

/// The most control points of all listed faces together (assemblies list shared faces once
/// per use; this bounds the memory of the model).
const MAX_TOTAL_POINTS: usize = 1 << 26;

/// Reads the faces, shells and solids of a STEP file's text.
///
/// # Errors
/// [`IoError::Cad`] for a file that is not ISO 10303-21 or whose entity graph is broken
/// (missing or cyclic references in the shape structure, nesting beyond the limits). A face
/// whose loops cannot be read is listed with an `Err` in [`Face::loops`] (a
/// [`FaceError::Read`] of a [`StepError`]); one whose surface cannot be read has it in
/// [`Face::surface_error`].
pub fn read_step(text: &[u8]) -> Result<CadModel, IoError> {
    let g = Graph::parse(text).map_err(cad)?;
    let structure = faces::structure(&g).map_err(cad)?;
    let mut contexts: HashMap<Option<u64>, Units> = HashMap::new();
    for u in &structure.faces {
        for c in [u.context, u.unit_context] {
            if let Entry::Vacant(e) = contexts.entry(c) {
                let units = match c {
                    Some(c) => units::context_units(&g, c).map_err(cad)?,
                    None => Units::default(),
                };
                e.insert(units);
            }
        }
    }
    let stated = structure
        .faces
        .iter()
        .filter_map(|u| contexts.get(&u.context).and_then(|c| c.uncertainty))
        .reduce(f64::max);
    let tolerance = Tolerance::new(stated)
        .map_err(|e| cad(StepError::geometry("the file's uncertainty", e)))?;
    // The model's length unit: the first face's (placed) coordinates'.
    let model_units = structure
        .faces
        .first()
        .and_then(|u| u.unit_context)
        .and_then(|c| contexts.get(&Some(c)));
    let unit = model_units.map(|u| u.mm_per_length);
    let length_unit = model_units.and_then(|u| {
        u.length_name.clone().map(|name| LengthUnit {
            name,
            millimetres: u.mm_per_length,
        })
    });
    // A face used many times (assemblies) is read once.
    let mut read: HashMap<(u64, Option<u64>), ReadFace> = HashMap::new();
    let mut faces = Vec::with_capacity(structure.faces.len().min(1 << 16));
    let mut points = 0usize;
    for u in &structure.faces {
        let key = (u.face, u.context);
        let units = contexts.get(&u.context).cloned().unwrap_or_default();
        if let Entry::Vacant(e) = read.entry(key) {
            e.insert(read_face(&g, u.face, &units, tolerance).map_err(cad)?);
        }
        let r = &read[&key];
        if let Ok(l) = &r.loops {
            points += l
                .loops
                .iter()
                .flatten()
                .map(|c| c.control_points().len())
                .sum::<usize>();
            if points > MAX_TOTAL_POINTS {
                return Err(cad(StepError::TooMany {
                    what: "control points of the faces in all".into(),
                    limit: MAX_TOTAL_POINTS,
                }));
            }
        }
        // Coordinates in another length unit than the model's (a second root part) are scaled
        // into it; `(u, v)` stay the file's.
        let placed_mm = contexts
            .get(&u.unit_context)
            .map_or(1.0, |c| c.mm_per_length);
        let scale = unit
            .filter(|&mm| mm != placed_mm && mm > 0.0)
            .map(|mm| faces::uniform_scale(placed_mm / mm));
        let placement = match (u.placement, scale) {
            (p, None) => p,
            (None, Some(s)) => Some(s),
            (Some(p), Some(s)) => Some(s.after(p)),
        };
        faces.push(r.placed(u, placement));
    }
    let shells = structure.shells.iter().map(ShellUse::to_shell).collect();
    let solids = structure.solids.iter().map(SolidUse::to_solid).collect();
    Ok(CadModel {
        format: CadFormat::Step,
        model: Model {
            faces,
            shells,
            solids,
            tolerance,
            length_unit,
        },
    })
}

/// A face as read once, before its uses are placed.
struct ReadFace {
    entity: String,
    surface_name: String,
    surface: Result<Surface, StepError>,
    same_sense: bool,
    loops: Result<FaceLoops, StepError>,
}

impl ReadFace {
    /// The model face of one use: reversed by its shell or `ORIENTED_FACE`, its surface and
    /// edges moved by `placement`.
    fn placed(&self, u: &FaceUse, placement: Option<Affine3>) -> Face {
        let fail = |e: StepError| FaceError::Read(ReadError::new(e));
        let mut surface = self.surface.clone();
        let mut edges = self
            .loops
            .as_ref()
            .map(|l| l.edges.clone())
            .unwrap_or_default();
        if let Some(m) = placement {
            surface = surface.and_then(|s| {
                s.transformed(&m)
                    .map_err(|e| StepError::geometry(format!("{} placed", self.entity), e))
            });
            for e in edges.iter_mut().flatten() {
                place_edge(e, &m);
            }
        }
        let (surface, surface_error) = match surface {
            Ok(s) => (Some(s), None),
            Err(e) => (None, Some(fail(e))),
        };
        Face {
            entity: self.entity.clone(),
            surface_name: self.surface_name.clone(),
            surface,
            surface_error,
            same_sense: self.same_sense ^ u.reversed,
            loops: self
                .loops
                .as_ref()
                .map(|l| l.loops.clone())
                .map_err(|e| fail(e.clone())),
            edges,
            pcurve_deviation: self.loops.as_ref().ok().and_then(|l| l.pcurve_deviation),
            natural_bounds: self.loops.as_ref().is_ok_and(|l| l.natural),
        }
    }
}

/// The edge moved by `m` (its curve mapped exactly; a curve the map cannot carry keeps its
/// place, which only a non-finite map can cause).
fn place_edge(e: &mut Edge, m: &Affine3) {
    if let Ok(c) = e.curve.map_affine(m) {
        e.curve = c;
    }
}

fn read_face(
    g: &Graph,
    label: u64,
    units: &Units,
    tolerance: Tolerance,
) -> Result<ReadFace, StepError> {
    let inst = g.get(label, "a shell")?;
    let entity = format!("#{label}");
    let what = inst.what();
    let attrs = inst.simple();
    let same_sense = attrs
        .as_ref()
        .ok()
        .and_then(|a| a.boolean(3, "same_sense").ok())
        .unwrap_or(true);
    let surface_label = attrs.and_then(|a| a.reference(2, "face_geometry"));
    let found = surface_label.and_then(|s| g.get(s, &what).map(|i| (s, i)));
    let (s_label, s_inst) = match found {
        Ok(x) => x,
        Err(e) => {
            return Ok(ReadFace {
                entity,
                surface_name: String::from("?"),
                surface: Err(e.clone()),
                same_sense,
                loops: Err(e),
            });
        }
    };
    let name = s_inst.type_name();
    let surface = geometry::surface(g, s_label, &what, units.radians_per_angle);
    let fs = FaceSurface::new(s_label, name.clone(), surface.as_ref().ok().cloned());
    let cx = FaceContext {
        g,
        surface: &fs,
        radians: units.radians_per_angle,
        tolerance,
    };
    // A surface of a type the reader does not know leaves the loops readable (their pcurves
    // are read without periods or poles); a broken one refuses the face.
    let loops = match &surface {
        Err(e) if !matches!(e, StepError::Unsupported { .. }) => Err(e.clone()),
        _ => loops::face_loops(&cx, inst),
    };
    Ok(ReadFace {
        entity,
        surface_name: name,
        surface,
        same_sense,
        loops,
    })
}
