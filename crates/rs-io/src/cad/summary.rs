//! One line per face of a CAD file, as `inrs info part.step` prints it.

use std::fmt;

use rs_spline::{BoundingBox, Domain};

use super::CadModel;
use crate::IoError;

/// Facts about one face of a CAD file: its place, its surface, and either its loops, curves,
/// `(u, v)` area and box, or why it cannot be read.
#[derive(Clone, Debug, PartialEq)]
pub struct CadFaceSummary {
    /// The face's index (`#face:K`).
    pub index: usize,
    /// Its entity in the file (`#123`, `DE 57`).
    pub entity: String,
    /// The surface type as the file names it.
    pub surface: String,
    /// Number of trimming loops (0 when refused).
    pub loops: usize,
    /// Number of trimming curves (0 when refused).
    pub curves: usize,
    /// The area of the face's parameter domain (0 when refused).
    pub area: f64,
    /// Its `(u, v)` bounding box (`None` when refused).
    pub bounding_box: Option<BoundingBox>,
    /// Why the face cannot be read as a domain, if it cannot.
    pub error: Option<String>,
}

impl CadModel {
    /// One summary per face, in file order, with the closure tolerance of
    /// [`CadModel::face_domain`].
    pub fn face_summaries(&self, relative_closure_tolerance: Option<f64>) -> Vec<CadFaceSummary> {
        self.face_domains(relative_closure_tolerance)
            .iter()
            .enumerate()
            .map(|(index, d)| CadFaceSummary::of(self, index, d))
            .collect()
    }

    /// Every face as a domain ([`CadModel::face_domain`]), in file order, each `Err` for a
    /// face that cannot be read: one pass over a file for callers that want all its faces.
    pub fn face_domains(
        &self,
        relative_closure_tolerance: Option<f64>,
    ) -> Vec<Result<Domain, IoError>> {
        (0..self.faces.len())
            .map(|index| self.face_domain(index, relative_closure_tolerance))
            .collect()
    }
}

impl CadFaceSummary {
    /// The summary of face `index` of `model` from its domain (or the reason it has none), as
    /// [`CadModel::face_domains`] gives it.
    ///
    /// # Panics
    /// If `index` is not a face of `model`.
    pub fn of(model: &CadModel, index: usize, domain: &Result<Domain, IoError>) -> Self {
        let face = &model.faces[index];
        let mut s = CadFaceSummary {
            index,
            entity: face.entity.clone(),
            surface: face.surface.clone(),
            loops: 0,
            curves: 0,
            area: 0.0,
            bounding_box: None,
            error: None,
        };
        match domain {
            Ok(d) => {
                s.loops = d.loops().len();
                s.curves = d.curves().len();
                s.area = d.signed_area();
                s.bounding_box = Some(d.bounding_box());
            }
            Err(IoError::CadFace { message, .. }) => s.error = Some(message.clone()),
            Err(other) => s.error = Some(other.to_string()),
        }
        s
    }
}

impl fmt::Display for CadFaceSummary {
    /// `face 3  #245  PLANE  loops 2  curves 9  area 1.25  u [0, 2]  v [-1, 0.5]`, or the
    /// reason the face is refused.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "face {:<4} {:<9} {:<28}",
            self.index, self.entity, self.surface
        )?;
        match (&self.error, self.bounding_box) {
            (Some(e), _) => write!(f, " refused: {e}"),
            (None, Some(b)) => write!(
                f,
                " loops {}  curves {}  area {:.6e}  u [{:.6e}, {:.6e}]  v [{:.6e}, {:.6e}]",
                self.loops, self.curves, self.area, b.min.x, b.max.x, b.min.y, b.max.y
            ),
            (None, None) => Ok(()),
        }
    }
}
