//! IGES files: the parameter-space trimming loops of trimmed (144) and bounded (143) surfaces.
//!
//! Only the fixed 80-column ASCII form of IGES 5.3 is read (`records` splits it into
//! sections; `globals`, `directory` and `params` read the global section, the directory
//! entries and the free-format parameter data). `faces` finds the faces and reads their
//! loops, `curves` (with `conics` and `maps`) turns curve entities into exact NURBS:
//!
//! - 144 trimmed surface: the outer boundary (or, with `N1 = 0`, the surface's own parameter
//!   rectangle) then the inner boundaries, each a 142 curve on a parametric surface whose
//!   parameter-space curve is read; if that pointer is 0 and the surface is a plane (108, or a
//!   128 that is a flat parallelogram), the model-space curve is mapped into `(u, v)` exactly
//!   (the map is affine).
//! - 143 bounded surface with 141 boundaries (their parameter-space curves, each model curve's
//!   sense applied).
//! - 510 faces of B-rep solids (186, 514 shells), their 508 loops of edges (`brep`).
//! - Curves: 100 circular arc, 102 composite curve, 104 conic arc (ellipse, hyperbola,
//!   parabola: exact rational quadratics), 106 copious data (forms 11, 12, 63: polylines),
//!   110 line (form 0), 126 rational B-spline curve (trimmed to `[V0, V1]`), each with its 124
//!   transformation matrices (chains compose).
//!
//! Faces come in the order Open CASCADE's `IGESControl_Reader` (`TransferRoots`, `OneShape`)
//! and face explorer give: the root entities (not physically dependent, not in a group) in
//! directory order, 402 groups expanded in their member order, 186 solids and 514 shells
//! in shell order. Checked with Open CASCADE 7.8
//! (OCP) on the four IGES files of `FreeCAD`'s Idf library, where this is directory order.
//!
//! Parameter spaces are the file's own (IGES 5.3's): for 128 surfaces they are Open
//! CASCADE's too (checked: same loop vertices and edge mid-points on every 128 face of the
//! Idf files); for a 120 surface of revolution Open CASCADE swaps `u` and `v`, shifts the
//! angle by the start angle and rescales a line generatrix to arc length (an affine change,
//! so classification is unaffected); for a 108 plane this reader's axes and Open CASCADE's
//! differ by a rigid motion (they coincide for planes `z = c`).
//!
//! Limits: every pointer is range checked where it is followed; composite curves nest at most
//! [`MAX_DEPTH`] deep, as do 124 chains and groups, and cycles are reported; the total work of
//! a file (parameter records read, counting repeats) is bounded by a multiple of its size, so
//! shared sub-curves cannot blow up exponentially; counts read from the file are checked
//! against the fields left in their record before anything is allocated.

mod brep;
mod conics;
mod curves;
mod directory;
mod faces;
mod globals;
mod maps;
mod params;
mod records;

use std::borrow::Cow;
use std::cell::{Cell, RefCell};
use std::collections::HashMap;
use std::rc::Rc;

use super::{CadFormat, CadModel};
use crate::IoError;
use directory::DirEntry;
use params::Params;
use records::Record;

/// The deepest nesting of composite curves, of 124 transformation chains and of groups.
pub const MAX_DEPTH: usize = 32;

/// A file-level error.
fn cad_err(message: String) -> IoError {
    IoError::Cad {
        format: "IGES",
        message,
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

/// A read IGES file: its directory, parameter records and delimiters, and a work budget.
struct Iges<'a> {
    dir: Vec<DirEntry>,
    params: Vec<Record<'a>>,
    globals: globals::Globals,
    /// Parameter records that may still be read (each read costs its record count).
    budget: Cell<usize>,
    /// The model curves of the 504 edge lists read so far, by DE.
    edge_lists: RefCell<HashMap<usize, Rc<Vec<usize>>>>,
}

impl<'a> Iges<'a> {
    /// `DE 57 (126 rational B-spline curve)`.
    fn who(&self, e: &DirEntry) -> String {
        format!("DE {} ({} {})", e.de, e.kind, type_name(e.kind))
    }

    /// The directory entry `de` points to; `from` names the pointer for messages.
    fn entry(&self, de: usize, from: &str) -> Result<&DirEntry, String> {
        if de % 2 == 1 && de / 2 < self.dir.len() {
            Ok(&self.dir[de / 2])
        } else if de == 0 {
            Err(format!("{from}: the pointer is 0 (no entity)"))
        } else {
            Err(format!(
                "{from}: pointer {de} is not a directory entry (odd sequence numbers 1 to {})",
                2 * self.dir.len()
            ))
        }
    }

    /// The parameter record of entry `e`: columns 1-64 of its parameter data lines,
    /// concatenated, after checking that they exist, point back to `e` and start with its
    /// type. The first field (the type) is consumed.
    fn params(&self, e: &DirEntry) -> Result<Params<'a>, String> {
        let who = self.who(e);
        let (start, lines) = (e.param_start, e.param_lines);
        let n = self.params.len();
        let first = usize::try_from(start).ok().filter(|&s| s >= 1 && s <= n);
        let count = usize::try_from(lines).ok().filter(|&c| c >= 1);
        let (Some(first), Some(count)) = (first, count) else {
            return Err(format!(
                "{who}: parameter data at line {start} with {lines} lines is not in the \
                 parameter section (lines 1 to {n})"
            ));
        };
        if count > n - first + 1 {
            return Err(format!(
                "{who}: parameter data at line {start} with {lines} lines runs past the end \
                 of the parameter section ({n} lines)"
            ));
        }
        let left = self.budget.get();
        if count + 1 > left {
            return Err(format!(
                "{who}: the file's entities reference each other too many times (work limit \
                 reached)"
            ));
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
                    return Err(format!(
                        "{who}: parameter line {} (file line {}) belongs to DE {}",
                        first,
                        r.line,
                        String::from_utf8_lossy(back)
                    ));
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
            return Err(format!(
                "{who}: its parameter data is of entity type {kind}"
            ));
        }
        Ok(p)
    }
}

/// Reads the faces of an IGES file's bytes.
///
/// # Errors
/// [`IoError::Cad`] for a file that is not IGES or whose sections are broken (the message
/// names the line). Problems inside a face (a missing curve, a pointer to the wrong entity
/// type, an unsupported entity) are that face's `Err` instead, naming the directory entry.
pub fn read_iges(bytes: &[u8]) -> Result<CadModel, IoError> {
    let sections = records::sections(bytes)?;
    let globals = globals::globals(&sections.global)?;
    let dir = directory::entries(&sections.directory)?;
    let budget = 4 * sections.parameters.len() + 4 * dir.len() + 10_000;
    let iges = Iges {
        dir,
        params: sections.parameters,
        globals,
        budget: Cell::new(budget),
        edge_lists: RefCell::default(),
    };
    let faces = faces::faces(&iges);
    Ok(CadModel {
        format: CadFormat::Iges,
        model: rs_geom::brep::Model {
            faces,
            tolerance: rs_geom::Tolerance::new(globals.resolution)
                .map_err(|e| cad_err(e.to_string()))?,
            ..rs_geom::brep::Model::default()
        },
    })
}
