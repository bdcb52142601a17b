//! `inrs.cad_faces(path)`: the faces of a STEP or IGES file, as `inrs info part.step` lists
//! them (the library's `CadModel::face_summaries`).

use pyo3::prelude::*;

use inrs::io::cad::{CadFaceSummary, CadModel};

use crate::domain::{NativeDomain, check_closure_tol};
use crate::errors::io_error;

/// One face of a CAD file: its index (`#face:K`), entity, surface, and its loops, curves,
/// `(u, v)` area and box, or why it is refused.
#[pyclass(module = "inrs._inrs", name = "CadFace", frozen, get_all)]
pub(crate) struct CadFace {
    /// The face's index: `Domain.load(f"{path}#face:{index}")` reads it.
    index: usize,
    /// Its entity in the file (`#123` for STEP, `DE 57` for IGES).
    entity: String,
    /// The surface type as the file names it.
    surface: String,
    /// Number of trimming loops (0 when refused).
    loops: usize,
    /// Number of trimming curves (0 when refused).
    curves: usize,
    /// Area of the face's parameter domain (0 when refused).
    area: f64,
    /// `(umin, vmin, umax, vmax)`, or `None` when refused.
    bbox: Option<(f64, f64, f64, f64)>,
    /// Why the face cannot be read, or `None`.
    error: Option<String>,
}

impl From<CadFaceSummary> for CadFace {
    fn from(s: CadFaceSummary) -> Self {
        Self {
            index: s.index,
            entity: s.entity,
            surface: s.surface,
            loops: s.loops,
            curves: s.curves,
            area: s.area,
            bbox: s.bounding_box.map(|b| (b.min.x, b.min.y, b.max.x, b.max.y)),
            error: s.error,
        }
    }
}

#[pymethods]
impl CadFace {
    fn __repr__(&self) -> String {
        match &self.error {
            Some(e) => format!(
                "CadFace(index={}, entity={:?}, surface={:?}, error={e:?})",
                self.index, self.entity, self.surface
            ),
            None => format!(
                "CadFace(index={}, entity={:?}, surface={:?}, loops={}, curves={}, area={})",
                self.index, self.entity, self.surface, self.loops, self.curves, self.area
            ),
        }
    }
}

/// The faces of a STEP (`.step`, `.stp`) or IGES (`.igs`, `.iges`) file in file order, each
/// with its domain (`None` when refused), from one read of the file.
#[pyfunction]
#[pyo3(signature = (path, closure_tol = None))]
pub(crate) fn cad_faces(
    py: Python<'_>,
    path: &str,
    closure_tol: Option<f64>,
) -> PyResult<Vec<(CadFace, Option<NativeDomain>)>> {
    check_closure_tol(closure_tol)?;
    let faces = py.detach(|| {
        CadModel::read(path).map(|m| {
            m.face_domains(closure_tol)
                .into_iter()
                .enumerate()
                .map(|(k, d)| {
                    let summary = CadFaceSummary::of(&m, k, &d, closure_tol);
                    (CadFace::from(summary), d.ok().map(NativeDomain::new))
                })
                .collect::<Vec<_>>()
        })
    });
    faces.map_err(io_error)
}
