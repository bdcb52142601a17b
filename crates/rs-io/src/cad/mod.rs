//! CAD files: the trimming loops of the faces of STEP and IGES parts, each face in its own
//! parameter space `(u, v)`.
//!
//! A face of a B-rep is a patch of a surface `S(u, v)`; the part of the patch that belongs to the
//! face is bounded by trimming loops of 2-D curves in `(u, v)` ("pcurves"). This module reads
//! those loops, exactly (NURBS, lines and conics stay what they are), into one [`CadModel`]
//! per file, whose faces come in the order `OpenCASCADE`'s face explorer visits them in the same
//! file; [`CadModel::face_domain`] turns face `K` into a [`Domain`](rs_spline::Domain).
//!
//! # Tolerance
//! Consecutive trimming curves of real files meet only within the model's tolerance (often
//! `1e-7`), above the default closure tolerance of a domain (`1e-9` of its diagonal). A face's
//! loops close within the larger of the two, the file's tolerance taken as a distance in
//! `(u, v)`, unless the caller gives a relative closure tolerance; end points that meet within
//! it are made bit-identical (the end of each curve is moved onto the start of the next), so
//! the loops are watertight as every reader's are. A larger gap is an error naming the loop,
//! the two curves and the gap.
//!
//! # Examples
//!
//! ```no_run
//! use rs_io::cad::CadModel;
//! let model = CadModel::read("part.step")?;
//! for face in model.face_summaries(None) {
//!     println!("{face}");
//! }
//! let domain = model.face_domain(3, None)?;
//! # Ok::<(), rs_io::IoError>(())
//! ```
//!
//! - [`step`]: STEP AP203/AP214/AP242 (ISO 10303-21 files).
//! - [`iges`]: IGES 5.3 (the fixed-column format): trimmed surfaces (144) and bounded
//!   surfaces (143).

mod face;
pub mod iges;
mod spec;
pub mod step;
mod summary;

use std::path::Path;

use rs_spline::NurbsCurve;

use crate::IoError;
pub use spec::{FaceSelection, split_face_spec};
pub use summary::CadFaceSummary;

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
    /// The faces in `OpenCASCADE`'s face-explorer order of the same file.
    pub faces: Vec<CadFace>,
}

impl CadModel {
    /// Reads a STEP (`.step`, `.stp`) or IGES (`.igs`, `.iges`) file (at most
    /// [`rs_spline::limits::MAX_FILE_BYTES`]).
    ///
    /// # Errors
    /// [`IoError::Read`], [`IoError::UnknownFormat`] for another extension, the reader's
    /// [`IoError::Cad`].
    pub fn read(path: impl AsRef<Path>) -> Result<Self, IoError> {
        let path = path.as_ref();
        let format = CadFormat::from_path(path).ok_or_else(|| IoError::UnknownFormat {
            path: path.to_path_buf(),
        })?;
        let bytes = rs_spline::limits::read_file(path).map_err(|source| IoError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        Self::from_bytes(format, &bytes)
    }

    /// Reads the faces of a file's contents in `format`.
    ///
    /// # Errors
    /// The reader's [`IoError::Cad`].
    pub fn from_bytes(format: CadFormat, bytes: &[u8]) -> Result<Self, IoError> {
        match format {
            CadFormat::Step => step::read_step(bytes),
            CadFormat::Iges => iges::read_iges(bytes),
        }
    }
}
