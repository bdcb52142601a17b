//! CAD files: the trimming loops of the faces of STEP and IGES parts, each face in its own
//! parameter space `(u, v)`.
//!
//! A face of a B-rep is a patch of a surface `S(u, v)`; the part of the patch that belongs to the
//! face is bounded by trimming loops of 2-D curves in `(u, v)` ("pcurves"). This module reads
//! those loops, exactly (NURBS, lines and conics stay what they are), into one [`CadModel`]
//! per file, whose faces come in the order `OpenCASCADE`'s face explorer visits them in the same
//! file; [`CadModel::face_domain`] turns face `K` into a [`Domain`]. The
//! model itself (faces, shells, solids) is `rs-geom`'s [`Model`].
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
//! - [`iges`]: IGES 5.3 (the fixed-column format): trimmed surfaces (144), bounded surfaces
//!   (143) and B-rep solids (186, 514, 510), with their surfaces and 3-D edges.

pub mod iges;
mod spec;
pub mod step;
mod summary;

use std::ops::{Deref, DerefMut};
use std::path::Path;

use rs_geom::brep::{Model, ModelError};
use rs_spline::Domain;

use crate::IoError;
pub use spec::{CadSelection, split_cad_spec};
pub use summary::{CadFaceSummary, CadShellSummary, CadSolidSummary};

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

/// A CAD file read into a boundary representation: its faces, shells and solids in
/// `OpenCASCADE`'s explorer order ([`Model`], which this dereferences to), and its format.
#[derive(Clone, Debug)]
pub struct CadModel {
    /// The file format.
    pub format: CadFormat,
    /// The faces, shells and solids.
    pub model: Model,
}

impl Deref for CadModel {
    type Target = Model;
    fn deref(&self) -> &Model {
        &self.model
    }
}

impl DerefMut for CadModel {
    fn deref_mut(&mut self) -> &mut Model {
        &mut self.model
    }
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

    /// Face `index` (`#face:K`) as a domain in its surface's `(u, v)`
    /// ([`Model::face_domain`]: loops closed within the file's tolerance or
    /// `relative_closure_tolerance` of the face's `(u, v)` diagonal, watertight, oriented by
    /// nesting).
    ///
    /// # Errors
    /// [`IoError::Cad`] for an index past the last face; [`IoError::CadFace`] for a face that
    /// could not be read (the reader's reason) or whose loop has a gap beyond the tolerance
    /// (naming the loop, the two curves and the gap); [`IoError::Domain`] for an invalid
    /// tolerance.
    pub fn face_domain(
        &self,
        index: usize,
        relative_closure_tolerance: Option<f64>,
    ) -> Result<Domain, IoError> {
        self.model
            .face_domain(index, relative_closure_tolerance)
            .map_err(|e| self.io_error(e))
    }

    /// Every face as a domain ([`CadModel::face_domain`]), in file order, each `Err` for a
    /// face that cannot be read: one pass over a file for callers that want all its faces.
    pub fn face_domains(
        &self,
        relative_closure_tolerance: Option<f64>,
    ) -> Vec<Result<Domain, IoError>> {
        self.model
            .face_domains(relative_closure_tolerance)
            .into_iter()
            .map(|r| r.map_err(|e| self.io_error(e)))
            .collect()
    }

    /// The [`IoError`] of a model error, naming the format.
    pub fn io_error(&self, e: ModelError) -> IoError {
        let format = self.format.name();
        match e {
            ModelError::Face {
                index,
                entity,
                error,
            } => IoError::CadFace {
                format,
                index,
                entity,
                message: error.to_string(),
            },
            ModelError::Domain(e) => IoError::Domain(e),
            other => IoError::Cad {
                format,
                message: other.to_string(),
            },
        }
    }
}
