//! IGES files: the faces of trimmed (144) and bounded (143) surfaces and of B-rep solids
//! (186, 514, 510), with their surfaces, trimming loops in `(u, v)` and 3-D edges, as an
//! `rs_geom` B-rep model.
//!
//! Only the fixed 80-column ASCII form of IGES 5.3 is read (`records` splits it into
//! sections; `globals`, `directory` and `params` read the global section, the directory
//! entries and the free-format parameter data). `faces` finds the faces, shells and solids and
//! reads the loops of 144 and 143 faces, `brep` those of 510 faces, `surfaces` turns surface
//! entities into `rs_geom` surfaces and `curves` curve entities into `rs_geom` curves (every
//! conversion to exact NURBS, every map and every evaluation is `rs_geom`'s):
//!
//! - 144 trimmed surface: the outer boundary (or, with `N1 = 0`, the surface's own parameter
//!   rectangle) then the inner boundaries, each a 142 curve on a parametric surface whose
//!   parameter-space curve is read; if that pointer is 0 and the surface is a plane (108, 190,
//!   or a 128 that is a flat parallelogram), the model-space curve is mapped into `(u, v)`
//!   exactly (the map is affine), on any other surface its pcurve is computed by
//!   `rs_geom::pcurve` (the face's `pcurve_deviation` bounds the 3-D distance). The 142's
//!   model-space curve gives the face's 3-D edges.
//! - 143 bounded surface with 141 boundaries (their parameter-space curves, each model curve's
//!   sense applied).
//! - 510 faces of B-rep solids (186 solids of 514 shells; a 510 no shell lists is a face of
//!   its own), their 508 loops of edges of 504 edge lists (`brep`).
//! - Curves: 100 circular arc, 102 composite curve, 104 conic arc (ellipse, hyperbola,
//!   parabola), 106 copious data (forms 11, 12, 63: polylines), 110 line (form 0), 126
//!   rational B-spline curve (trimmed to `[V0, V1]`), each with its 124 transformation matrices
//!   (chains compose).
//! - Surfaces: 108 plane, 120 surface of revolution, 122 tabulated cylinder, 128 rational
//!   B-spline surface, 140 offset surface, 190 plane, 192 cylinder, 194 cone, 196 sphere, 198
//!   torus, each placed by its 124 chain (`surfaces` gives their parameterisations).
//!
//! Faces come in the order Open CASCADE's `IGESControl_Reader` (`TransferRoots`, `OneShape`)
//! and face explorer give: the root entities (not physically dependent, not in a group; a 510
//! that no shell lists is a root whatever its status, as Open CASCADE reads it) in directory
//! order, 402 groups expanded in their member order, 186 solids and 514 shells in shell order.
//! Checked with Open CASCADE 7.8 (OCP) on the four IGES files of `FreeCAD`'s Idf library, where
//! this is directory order, and with Open CASCADE 8.0 on its own B-rep files. Shells and solids
//! come in the same order: a 186's outer shell, then its voids; shells outside solids after.
//! A face's orientation (`same_sense`) is its 514 flag `OF`, turned for a shell whose 186 flag
//! (`SOF`, `VOF`) is 0 (a void written reversed).
//!
//! Parameter spaces are the file's own (IGES 5.3's): for 128 surfaces they are Open
//! CASCADE's too (checked: same loop vertices and edge mid-points on every 128 face of the
//! Idf files); for a 120 surface of revolution Open CASCADE swaps `u` and `v`, measures the
//! angle from the end angle the other way round and rescales a line generatrix to arc length
//! (an affine change, so classification is unaffected); angles of 192 to 198 are in degrees, as
//! the file's pcurves are (Open CASCADE's in radians); for a 108 plane this reader's axes and
//! Open CASCADE's differ by a rigid motion (they coincide for planes `z = c`).
//!
//! Limits: every pointer is range checked where it is followed; composite curves nest at most
//! [`MAX_DEPTH`] deep, as do 124 chains, offset surfaces and groups, and cycles are reported;
//! the total work of a file (parameter records read, counting repeats) is bounded by a multiple
//! of its size, so shared sub-curves cannot blow up exponentially; counts read from the file
//! are checked against the fields left in their record before anything is allocated.

mod brep;
mod curves;
mod directory;
mod error;
mod faces;
mod globals;
mod params;
mod records;
mod surfaces;

use std::borrow::Cow;
use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::rc::Rc;

use rs_geom::{Affine3, Tolerance};

use super::{CadFormat, CadModel};
use crate::IoError;
use directory::DirEntry;
pub use error::{FieldProblem, IgesError};
use params::Params;
use records::Record;

/// The deepest nesting of composite curves, of 124 transformation chains, of offset surfaces
/// and of groups.
pub const MAX_DEPTH: usize = 32;

/// A file-level error.
fn cad_err(e: &IgesError) -> IoError {
    IoError::Cad {
        format: "IGES",
        message: e.to_string(),
    }
}

/// The name of an entity type, for messages and a face's surface name.
fn type_name(kind: i64) -> &'static str {
    match kind {
        100 => "circular arc",
        102 => "composite curve",
        104 => "conic arc",
        106 => "copious data",
        108 => "plane",
        110 => "line",
        112 => "parametric spline curve",
        114 => "parametric spline surface",
        118 => "ruled surface",
        120 => "surface of revolution",
        122 => "tabulated cylinder",
        124 => "transformation matrix",
        126 => "rational B-spline curve",
        128 => "rational B-spline surface",
        130 => "offset curve",
        140 => "offset surface",
        141 => "boundary",
        142 => "curve on a parametric surface",
        143 => "bounded surface",
        144 => "trimmed surface",
        186 => "manifold solid B-rep object",
        190 => "plane surface",
        192 => "right circular cylindrical surface",
        194 => "right circular conical surface",
        196 => "spherical surface",
        198 => "toroidal surface",
        402 => "associativity instance",
        502 => "vertex list",
        504 => "edge list",
        508 => "loop",
        510 => "face",
        514 => "shell",
        _ => "entity",
    }
}

/// A read IGES file: its directory, parameter records and delimiters, its tolerance, a work
/// budget, and the lists and surfaces read so far.
struct Iges<'a> {
    dir: Vec<DirEntry>,
    params: Vec<Record<'a>>,
    globals: globals::Globals,
    /// The file's tolerance policy.
    tolerance: Tolerance,
    /// Parameter records that may still be read (each read costs its record count).
    budget: Cell<usize>,
    /// The 504 edge lists read so far, by DE.
    edge_lists: RefCell<HashMap<usize, Rc<Vec<brep::EdgeEntry>>>>,
    /// The surfaces read so far, by DE.
    surfaces: RefCell<HashMap<usize, Rc<surfaces::SurfaceInfo>>>,
}

impl<'a> Iges<'a> {
    /// `DE 57 (126 rational B-spline curve)`.
    fn who(&self, e: &DirEntry) -> String {
        format!("DE {} ({} {})", e.de, e.kind, type_name(e.kind))
    }

    /// The directory entry `de` points to; `from` names the pointer for messages.
    fn entry(&self, de: usize, from: &str) -> Result<&DirEntry, IgesError> {
        if de % 2 == 1 && de / 2 < self.dir.len() {
            Ok(&self.dir[de / 2])
        } else if de == 0 {
            Err(IgesError::NullPointer {
                from: from.to_string(),
            })
        } else {
            Err(IgesError::BadPointer {
                from: from.to_string(),
                pointer: de,
                entries: self.dir.len(),
            })
        }
    }

    /// The directory entry `de` points to, which must be of type `kind` (`expected` says so
    /// in words for the message).
    fn entry_of(
        &self,
        de: usize,
        from: &str,
        kind: i64,
        expected: &'static str,
    ) -> Result<&DirEntry, IgesError> {
        let e = self.entry(de, from)?;
        if e.kind == kind {
            Ok(e)
        } else {
            Err(IgesError::WrongType {
                from: from.to_string(),
                de: e.de,
                kind: e.kind,
                expected,
            })
        }
    }

    /// The parameter record of entry `e`: columns 1-64 of its parameter data lines,
    /// concatenated, after checking that they exist, point back to `e` and start with its
    /// type. The first field (the type) is consumed.
    fn params(&self, e: &DirEntry) -> Result<Params<'a>, IgesError> {
        let who = self.who(e);
        let (start, lines) = (e.param_start, e.param_lines);
        let n = self.params.len();
        let first = usize::try_from(start).ok().filter(|&s| s >= 1 && s <= n);
        let count = usize::try_from(lines).ok().filter(|&c| c >= 1);
        let (Some(first), Some(count)) = (first, count) else {
            return Err(IgesError::ParameterLines {
                who,
                start,
                lines,
                available: n,
                past_end: false,
            });
        };
        if count > n - first + 1 {
            return Err(IgesError::ParameterLines {
                who,
                start,
                lines,
                available: n,
                past_end: true,
            });
        }
        let left = self.budget.get();
        if count + 1 > left {
            return Err(IgesError::WorkLimit { who });
        }
        self.budget.set(left - count - 1);
        let mut text = Vec::with_capacity(count * 64);
        for r in &self.params[first - 1..first - 1 + count] {
            let back = records::trim(r.columns(66, 72));
            if !back.is_empty() && back.iter().all(u8::is_ascii_digit) {
                let back_de = std::str::from_utf8(back)
                    .ok()
                    .and_then(|s| s.parse::<usize>().ok());
                if back_de != Some(e.de) {
                    return Err(IgesError::ParameterOwner {
                        who,
                        line: first,
                        file_line: r.line,
                        owner: String::from_utf8_lossy(back).into_owned(),
                    });
                }
            }
            text.extend_from_slice(r.columns(1, 64));
            // Short lines are blank-padded, so fields cannot run together across lines.
            text.resize(text.len() + 64 - r.columns(1, 64).len(), b' ');
        }
        let mut p = Params::new(
            Cow::Owned(text),
            self.globals.delim,
            self.globals.end,
            who.clone(),
        );
        let kind = p.int("entity type")?;
        if kind != e.kind {
            return Err(IgesError::ParameterType { who, kind });
        }
        Ok(p)
    }

    /// The maps of `e`'s 124 chain (its matrix, then that matrix's own, ...): in 3-D for model
    /// space, and their 2-D parts for parameter space (`x' = R11 x + R12 y + T1`, `y' = R21 x +
    /// R22 y + T2`, `z' = z`).
    fn transforms(&self, e: &DirEntry) -> Result<[Affine3; 2], IgesError> {
        let mut acc = [Affine3::IDENTITY, Affine3::IDENTITY];
        let mut ptr = e.transform;
        let mut seen: Vec<usize> = Vec::new();
        while ptr != 0 {
            let who = self.who(e);
            let Ok(de) = usize::try_from(ptr) else {
                return Err(IgesError::NegativeTransform { who, pointer: ptr });
            };
            if seen.contains(&de) {
                return Err(IgesError::TransformCycle { who, de });
            }
            if seen.len() >= MAX_DEPTH {
                return Err(IgesError::TransformChain { who });
            }
            seen.push(de);
            let t = self.entry_of(
                de,
                &format!("{who}: transformation matrix"),
                124,
                "a 124 transformation matrix",
            )?;
            let mut p = self.params(t)?;
            let mut v = [0.0; 12];
            for (i, x) in v.iter_mut().enumerate() {
                *x = p.real(
                    [
                        "R11", "R12", "R13", "T1", "R21", "R22", "R23", "T2", "R31", "R32", "R33",
                        "T3",
                    ][i],
                )?;
            }
            let model = Affine3 {
                m: [
                    [v[0], v[1], v[2], v[3]],
                    [v[4], v[5], v[6], v[7]],
                    [v[8], v[9], v[10], v[11]],
                ],
            };
            let param = Affine3 {
                m: [
                    [v[0], v[1], 0.0, v[3]],
                    [v[4], v[5], 0.0, v[7]],
                    [0.0, 0.0, 1.0, 0.0],
                ],
            };
            acc = [model.after(acc[0]), param.after(acc[1])];
            ptr = t.transform;
        }
        Ok(acc)
    }
}

/// Reads the faces, shells and solids of an IGES file's bytes.
///
/// # Errors
/// [`IoError::Cad`] for a file that is not IGES or whose sections are broken (the message
/// names the line: an [`IgesError`] of the file's structure). Problems inside a face (a
/// missing curve, a pointer to the wrong entity type, an unsupported entity) are that face's
/// `Err` instead, an [`IgesError`] naming the directory entry.
pub fn read_iges(bytes: &[u8]) -> Result<CadModel, IoError> {
    let sections = records::sections(bytes).map_err(|e| cad_err(&e))?;
    let globals = globals::globals(&sections.global).map_err(|e| cad_err(&e))?;
    let dir = directory::entries(&sections.directory).map_err(|e| cad_err(&e))?;
    let budget = 4 * sections.parameters.len() + 4 * dir.len() + 10_000;
    let tolerance = Tolerance::new(globals.resolution).map_err(|e| IoError::Cad {
        format: "IGES",
        message: format!("global section: parameter 19 (minimum resolution): {e}"),
    })?;
    let length_unit = globals.length_unit.clone();
    let iges = Iges {
        dir,
        params: sections.parameters,
        globals,
        tolerance,
        budget: Cell::new(budget),
        edge_lists: RefCell::default(),
        surfaces: RefCell::default(),
    };
    let (faces, shells, solids) = faces::model(&iges);
    let mut model = rs_geom::brep::Model {
        faces,
        shells,
        solids,
        tolerance,
        length_unit,
    };
    // A 514 of form 1 says it is closed (OpenCASCADE writes form 1 for open shells too): an
    // edge only one of its faces uses makes it open, as a STEP CLOSED_SHELL's does.
    for k in 0..model.shells.len() {
        if model.shells[k].closed && !model.free_edges(&model.shells[k].faces).is_empty() {
            model.shells[k].closed = false;
        }
    }
    Ok(CadModel {
        format: CadFormat::Iges,
        model,
    })
}
