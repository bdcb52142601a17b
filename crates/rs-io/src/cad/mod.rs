//! CAD files: the trimming loops of the faces of STEP and IGES parts, each face in its own
//! parameter space `(u, v)`.
//!
//! A face of a B-rep is a patch of a surface `S(u, v)`; the part of the patch that belongs to the
//! face is bounded by trimming loops of 2-D curves in `(u, v)` ("pcurves"). This module reads
//! those loops, exactly (NURBS, lines and conics stay what they are), into one [`CadModel`]
//! per file, whose faces come in the order OpenCASCADE's face explorer visits them in the same
//! file; [`CadModel::face_domain`] turns face `K` into a [`Domain`].
//!
//! - [`step`]: STEP AP203/AP214/AP242 (ISO 10303-21 files).
//! - [`iges`]: IGES 5.3 (the fixed-column format): trimmed surfaces (144) and bounded
//!   surfaces (143).

pub mod iges;
pub mod step;

use std::path::Path;

use rs_spline::NurbsCurve;


/// The file formats of [`CadModel`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CadFormat {
    /// ISO 10303-21 (STEP).
    Step,
    /// IGES.
    Iges,
}

impl CadFormat {
    /// The format of a file name (`.step`, `.stp`, `.igs`, `.iges`, any case), if it is one.
    pub fn from_path(path: &Path) -> Option<Self> {
        let ext = path.extension()?.to_string_lossy().to_ascii_lowercase();
        match ext.as_str() {
            "step" | "stp" => Some(Self::Step),
            "igs" | "iges" => Some(Self::Iges),
            _ => None,
        }
    }

    /// `"STEP"` or `"IGES"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Step => "STEP",
            Self::Iges => "IGES",
        }
    }
}

/// One face of a CAD file: where it is in the file, its surface, and its trimming loops in the
/// surface's parameter space (or why they could not be read).
#[derive(Clone, Debug)]
pub struct CadFace {
    /// The face's entity in the file: `#123` (STEP instance) or `DE 57` (IGES directory entry
    /// sequence number).
    pub entity: String,
    /// The surface type as the file names it (`PLANE`, `CYLINDRICAL_SURFACE`,
    /// `B_SPLINE_SURFACE_WITH_KNOTS`, IGES `128 (rational B-spline surface)`, ...).
    pub surface: String,
    /// The loops, the outer one first, each its curves in loop order in `(u, v)`; each curve
    /// ends where the next one starts (within the file's tolerance) and the last returns to
    /// the first. `Err` says why the face could not be read (a one-line message naming the
    /// entity at fault); the other faces of the file are unaffected.
    pub loops: Result<Vec<Vec<NurbsCurve>>, String>,
}

/// The faces of a CAD file.
#[derive(Clone, Debug)]
pub struct CadModel {
    /// The file format.
    pub format: CadFormat,
    /// The file's own tolerance in model units, if it states one: STEP's
    /// `UNCERTAINTY_MEASURE_WITH_UNIT` of length, IGES's minimum resolution (global
    /// parameter 19).
    pub tolerance: Option<f64>,
    /// The faces in OpenCASCADE's face-explorer order of the same file.
    pub faces: Vec<CadFace>,
}
