//! CAD parts: `inrs.cad_model(path)` (faces with their surfaces and 3-D edges, shells, solids)
//! and `inrs.cad_faces(path)` (the faces as `inrs info part.step` lists them), from the
//! library's `CadModel`.

use std::sync::{Arc, OnceLock};

use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

use inrs::geom::ParamSurface;
use inrs::geom::Point3;
use inrs::geom::brep::Edge;
use inrs::geom::properties::{FaceProperties, ModelProperties, SolidProperties};
use inrs::geom::solid::{Location, PointQuery, SolidClassifier};
use inrs::io::cad::{CadFaceSummary, CadModel};

use crate::domain::{NativeDomain, check_closure_tol};
use crate::errors::{io_error, value_error};

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
    /// The gap within which the loops were closed, in `(u, v)`.
    closure_tolerance: f64,
    /// Twice the `(u, v)` area over the loops' length.
    width: f64,
    /// Whether the face is narrower than its closure tolerance.
    narrow: bool,
    /// The bound of fitted pcurves' 3-D deviation from their edges, or `None`.
    pcurve_deviation: Option<f64>,
    /// Whether the loops are the surface's natural parameter box.
    natural_bounds: bool,
    /// Why the face cannot be read, or `None`.
    error: Option<String>,
}

impl From<CadFaceSummary> for CadFace {
    fn from(s: CadFaceSummary) -> Self {
        Self {
            narrow: s.is_narrow(),
            index: s.index,
            entity: s.entity,
            surface: s.surface,
            loops: s.loops,
            curves: s.curves,
            area: s.area,
            bbox: s.bounding_box.map(|b| (b.min.x, b.min.y, b.max.x, b.max.y)),
            closure_tolerance: s.closure_tolerance,
            width: s.width,
            pcurve_deviation: s.pcurve_deviation,
            natural_bounds: s.natural_bounds,
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
    Ok(read(py, path, closure_tol)?.1)
}

/// An edge as Python sees it: `(entity, t0, t1, reversed)`.
type EdgeRow = (String, f64, f64, bool);

/// A file's model and its faces' summaries and domains.
type ReadModel = (CadModel, Vec<(CadFace, Option<NativeDomain>)>);

/// Reads `path` (GIL released).
fn read(py: Python<'_>, path: &str, closure_tol: Option<f64>) -> PyResult<ReadModel> {
    check_closure_tol(closure_tol)?;
    py.detach(|| {
        let m = CadModel::read(path)?;
        let faces = m
            .face_domains(closure_tol)
            .into_iter()
            .enumerate()
            .map(|(k, d)| {
                let summary = CadFaceSummary::of(&m, k, &d, closure_tol);
                (CadFace::from(summary), d.ok().map(NativeDomain::new))
            })
            .collect();
        Ok((m, faces))
    })
    .map_err(io_error)
}

/// A CAD file read once: its faces (summary and domain each), and the model they come from
/// (surfaces, edges, shells, solids).
#[pyclass(module = "inrs._inrs", name = "NativeCadModel", frozen)]
pub(crate) struct NativeCadModel {
    model: Arc<CadModel>,
    faces: Vec<(Py<CadFace>, Option<Py<NativeDomain>>)>,
    /// `Model::properties()`, computed on first use (once, whichever thread asks first).
    properties: OnceLock<ModelProperties>,
    /// Each solid's classifier (or why it cannot be built), built on first use.
    classifiers: Vec<OnceLock<Result<SolidClassifier, String>>>,
}

/// A face's properties as Python sees them: `(area, centroid, second_moments, error,
/// converged)`.
type FaceRow = (f64, [f64; 3], [[f64; 3]; 3], f64, bool);

/// A solid's properties as Python sees them: `(volume, area, centroid, inertia,
/// principal_moments, principal_axes, error, converged, leak_area)`.
type SolidRow = (
    f64,
    f64,
    [f64; 3],
    [[f64; 3]; 3],
    [f64; 3],
    [[f64; 3]; 3],
    f64,
    bool,
    f64,
);

/// One face's or solid's properties: the row, or the library's message.
type Row<T> = (Option<T>, Option<String>);

fn face_row(p: &FaceProperties) -> FaceRow {
    (
        p.area,
        p.centroid.to_array(),
        p.second_moments,
        p.error,
        p.converged,
    )
}

fn solid_row(p: &SolidProperties) -> SolidRow {
    (
        p.volume,
        p.area,
        p.centroid.to_array(),
        p.inertia,
        p.principal_moments,
        p.principal_axes.map(|a| a.to_array()),
        p.error,
        p.converged,
        p.leak_area,
    )
}

fn row<P, T>(r: &Result<P, impl ToString>, f: impl Fn(&P) -> T) -> Row<T> {
    match r {
        Ok(p) => (Some(f(p)), None),
        Err(e) => (None, Some(e.to_string())),
    }
}

impl NativeCadModel {
    fn face(&self, index: usize) -> PyResult<&inrs::geom::brep::Face> {
        self.model.faces.get(index).ok_or_else(|| {
            value_error(format!(
                "face {index} does not exist (the file has {} faces)",
                self.model.faces.len()
            ))
        })
    }

    fn edge(&self, face: usize, loop_index: usize, edge: usize) -> PyResult<&Edge> {
        self.face(face)?
            .edges
            .get(loop_index)
            .and_then(|l| l.get(edge))
            .ok_or_else(|| {
                value_error(format!(
                    "face {face} has no edge {edge} in loop {loop_index}"
                ))
            })
    }
}

/// An `(n, 3)` array of the points `f(i)`, `i < n`.
fn points3<'py>(
    py: Python<'py>,
    n: usize,
    f: impl Fn(usize) -> [f64; 3] + Sync,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = py.detach(|| (0..n).flat_map(&f).collect());
    flat.into_pyarray(py).reshape([n, 3])
}

#[pymethods]
impl NativeCadModel {
    /// Reads `path` with the relative closure tolerance `closure_tol`.
    #[new]
    #[pyo3(signature = (path, closure_tol = None))]
    fn new(py: Python<'_>, path: &str, closure_tol: Option<f64>) -> PyResult<Self> {
        let (model, faces) = read(py, path, closure_tol)?;
        let faces = faces
            .into_iter()
            .map(|(f, d)| Ok((Py::new(py, f)?, d.map(|d| Py::new(py, d)).transpose()?)))
            .collect::<PyResult<_>>()?;
        let classifiers = (0..model.solids.len()).map(|_| OnceLock::new()).collect();
        Ok(Self {
            model: Arc::new(model),
            faces,
            properties: OnceLock::new(),
            classifiers,
        })
    }

    /// Every face's and every solid's properties (`Model::properties()`, computed once with
    /// the GIL released and kept): `(faces, solids)`, each a list of `(row, message)` with
    /// one of the two `None`.
    fn properties(&self, py: Python<'_>) -> (Vec<Row<FaceRow>>, Vec<Row<SolidRow>>) {
        let p = self.computed(py);
        (
            p.faces.iter().map(|r| row(r, face_row)).collect(),
            p.solids.iter().map(|r| row(r, solid_row)).collect(),
        )
    }

    /// `"STEP"` or `"IGES"`.
    fn format(&self) -> &'static str {
        self.model.format.name()
    }

    /// The file's stated tolerance (model units), or `None`.
    fn tolerance(&self) -> Option<f64> {
        self.model.tolerance.stated()
    }

    /// The file's length unit: `(name, millimetres per unit)`, or `None` when it states none.
    fn length_unit(&self) -> Option<(String, f64)> {
        self.model
            .length_unit
            .as_ref()
            .map(|u| (u.name.clone(), u.millimetres))
    }

    /// The faces with their domains.
    fn faces(&self, py: Python<'_>) -> Vec<(Py<CadFace>, Option<Py<NativeDomain>>)> {
        self.faces
            .iter()
            .map(|(f, d)| (f.clone_ref(py), d.as_ref().map(|d| d.clone_ref(py))))
            .collect()
    }

    /// The shells: `(entity, closed, face indices)` each.
    fn shells(&self) -> Vec<(String, bool, Vec<usize>)> {
        self.model
            .shells
            .iter()
            .map(|s| (s.entity.clone(), s.closed, s.faces.clone()))
            .collect()
    }

    /// The solids: `(entity, shell indices)` each, the outer shell first.
    fn solids(&self) -> Vec<(String, Vec<usize>)> {
        self.model
            .solids
            .iter()
            .map(|s| (s.entity.clone(), s.shells.clone()))
            .collect()
    }

    /// Face `face`'s surface kind (`"plane"`, `"cylinder"`, ...), its orientation and whether
    /// its surface was read (with the reason when not).
    fn surface_of(&self, face: usize) -> PyResult<(Option<&'static str>, bool, Option<String>)> {
        let f = self.face(face)?;
        Ok((
            f.surface.as_ref().map(|s| s.kind_name()),
            f.same_sense,
            f.surface_error.as_ref().map(ToString::to_string),
        ))
    }

    /// At the rows of `uv` (`(n, 2)`), as an `(n, 3)` array: the points `S(u, v)` of face
    /// `face`'s surface, or with `normals` the face's outward unit normals (the surface's
    /// `S_u x S_v` normalised, reversed where the face's sense is; NaN where the normal is
    /// undefined).
    fn surface_at<'py>(
        &self,
        py: Python<'py>,
        face: usize,
        uv: PyReadonlyArray2<'py, f64>,
        normals: bool,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let s = self.surface(face)?;
        let uv = pairs_of(&uv)?;
        if !normals {
            return points3(py, uv.len(), |i| s.point(uv[i]).to_array());
        }
        let sign = if self.face(face)?.same_sense {
            1.0
        } else {
            -1.0
        };
        points3(py, uv.len(), |i| {
            s.normal(uv[i])
                .map_or([f64::NAN; 3], |n| (n * sign).to_array())
        })
    }

    /// Where the rows of `xyz` (`(n, 3)`) lie against solid `solid`: an int8 array (0
    /// outside, 1 inside, 2 boundary). The solid's classifier is built on first use (with the
    /// GIL released) and kept; the points are classified on all cores.
    fn classify_solid<'py>(
        &self,
        py: Python<'py>,
        solid: usize,
        xyz: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<i8>>> {
        let a = xyz.as_array();
        if a.ncols() != 3 {
            return Err(value_error(format!(
                "points for a solid must have shape (n, 3) (x, y, z), got {:?}",
                a.shape()
            )));
        }
        let points: Vec<Point3> = a
            .rows()
            .into_iter()
            .map(|r| Point3::new(r[0], r[1], r[2]))
            .collect();
        let cell = self.classifiers.get(solid).ok_or_else(|| {
            value_error(format!(
                "solid {solid} does not exist (the file has {} solids)",
                self.classifiers.len()
            ))
        })?;
        let codes = py.detach(|| {
            let c = cell
                .get_or_init(|| SolidClassifier::new(&self.model, solid).map_err(|e| e.to_string()))
                .as_ref()
                .map_err(Clone::clone)?;
            let mut out = vec![Location::Outside; points.len()];
            c.par_values_into(&points[..], &mut out);
            Ok::<_, String>(out.into_iter().map(Location::code).collect::<Vec<i8>>())
        });
        Ok(codes.map_err(value_error)?.into_pyarray(py))
    }

    /// The 3-D edges of face `face`, loop by loop: `(entity, t0, t1, reversed)` each.
    fn edges(&self, face: usize) -> PyResult<Vec<Vec<EdgeRow>>> {
        Ok(self
            .face(face)?
            .edges
            .iter()
            .map(|l| {
                l.iter()
                    .map(|e| (e.entity.clone(), e.range.0, e.range.1, e.reversed))
                    .collect()
            })
            .collect())
    }

    /// The points of edge `edge` of loop `loop_index` of face `face` at its curve's
    /// parameters `t`, as an `(n, 3)` array.
    fn edge_points<'py>(
        &self,
        py: Python<'py>,
        face: usize,
        loop_index: usize,
        edge: usize,
        t: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let e = self.edge(face, loop_index, edge)?;
        let t = t.as_array().to_vec();
        points3(py, t.len(), |i| e.curve.point(t[i]).to_array())
    }

    /// `n` points along edge `edge` of loop `loop_index` of face `face`, in loop order.
    fn edge_sample<'py>(
        &self,
        py: Python<'py>,
        face: usize,
        loop_index: usize,
        edge: usize,
        n: usize,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let e = self.edge(face, loop_index, edge)?;
        if !(2..=1 << 24).contains(&n) {
            return Err(value_error(format!("n must be 2 to 2**24, not {n}")));
        }
        let p = py.detach(|| e.sample(n));
        points3(py, p.len(), |i| p[i].to_array())
    }
}

impl NativeCadModel {
    /// The model's properties, computed on first use with the GIL released (a second thread
    /// asking meanwhile waits for the first's, also without the GIL).
    fn computed(&self, py: Python<'_>) -> &ModelProperties {
        if let Some(p) = self.properties.get() {
            return p;
        }
        py.detach(|| self.properties.get_or_init(|| self.model.properties()))
    }

    fn surface(&self, face: usize) -> PyResult<&inrs::geom::Surface> {
        let f = self.face(face)?;
        f.surface.as_ref().ok_or_else(|| {
            value_error(match &f.surface_error {
                Some(e) => format!("face {face} ({}): its surface was not read: {e}", f.entity),
                None => format!(
                    "face {face} ({}): its surface ({}) was not read",
                    f.entity, f.surface_name
                ),
            })
        })
    }
}

/// The rows of an `(n, 2)` array as `[u, v]` pairs.
fn pairs_of(uv: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<[f64; 2]>> {
    let a = uv.as_array();
    if a.ncols() != 2 {
        return Err(value_error(format!(
            "uv must have shape (n, 2), got {:?}",
            a.shape()
        )));
    }
    Ok(a.rows().into_iter().map(|r| [r[0], r[1]]).collect())
}
