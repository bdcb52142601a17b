//! `NativeDomain`: a domain with its indexes, classification and winding numbers of NumPy
//! points.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use inrs::contain::baselines::WindingAlgorithm;
use inrs::contain::{FastWindingField, FillRule, QueryStats, WindingField, fast_uses_locator};
use inrs::spline::Flatten;
use inrs::{Classifier, ContainOptions, Domain, Method, NurbsCurve, Point};

use crate::errors::{io_error, value_error};
use crate::points::{Points, codes_in_chunks, columns, pairs, with_point_accessor};
use crate::summary::DomainSummary;
use crate::threads::with_threads;

/// One curve of [`NativeDomain::from_curves`]: `(degree, knots, control points (M, 2),
/// weights (M,) or None)`.
type CurveArrays<'py> = (
    usize,
    PyReadonlyArray1<'py, f64>,
    PyReadonlyArray2<'py, f64>,
    Option<PyReadonlyArray1<'py, f64>>,
);

/// A planar domain bounded by NURBS curves (the native object behind `inrs.Domain`).
#[pyclass(module = "inrs._inrs", name = "NativeDomain", frozen)]
pub(crate) struct NativeDomain {
    pub(crate) domain: Domain,
    /// Classifiers by relative tolerance (its bits), built on first use and kept.
    classifiers: Mutex<HashMap<u64, Arc<Classifier>>>,
    /// The winding-number fields by tolerance.
    fields: Mutex<HashMap<u64, Arc<WindingField>>>,
}

impl NativeDomain {
    fn new(domain: Domain) -> Self {
        Self {
            domain,
            classifiers: Mutex::new(HashMap::new()),
            fields: Mutex::new(HashMap::new()),
        }
    }

    fn classifier(&self, tol: f64) -> PyResult<Arc<Classifier>> {
        cached(&self.classifiers, tol, "classifier", || {
            Classifier::new(
                &self.domain,
                ContainOptions::DEFAULT.with_relative_tolerance(tol),
            )
            .map_err(value_error)
        })
    }

    fn field(&self, tol: f64) -> PyResult<Arc<WindingField>> {
        cached(&self.fields, tol, "winding-field", || {
            WindingField::new(&self.domain, tol).map_err(value_error)
        })
    }

    /// Classification codes of `pts` (0 outside, 1 inside, 2 boundary).
    fn classify_points(
        &self,
        py: Python<'_>,
        pts: Points<'_>,
        method: &str,
        tol: f64,
        fill_rule: &str,
        threads: usize,
    ) -> PyResult<Vec<i8>> {
        let method: Method = method.parse().map_err(value_error)?;
        let n = pts.len();
        if method == Method::Gwn {
            let rule: FillRule = fill_rule.parse().map_err(value_error)?;
            let field = (*self.field(tol)?).clone().with_fill_rule(rule);
            return py.detach(|| {
                with_threads(threads, || {
                    let fast = FastWindingField::new(&field);
                    with_point_accessor!(pts, |at| codes_in_chunks(n, |first, out| {
                        fast.locate_indexed_into(|i| at(first + i), out)
                    }))
                })
            });
        }
        let classifier = self.classifier(tol)?;
        py.detach(|| {
            with_threads(threads, || {
                if method == Method::Fast && fast_uses_locator(n) {
                    let locator = classifier.locator();
                    with_point_accessor!(pts, |at| codes_in_chunks(n, |first, out| {
                        locator.locate_indexed_into(|i| at(first + i), out)
                    }))
                } else {
                    let method = if method == Method::Fast {
                        Method::InRS2
                    } else {
                        method
                    };
                    with_point_accessor!(pts, |at| codes_in_chunks(n, |first, out| {
                        let chunk: Vec<Point> = (first..first + out.len()).map(at).collect();
                        out.copy_from_slice(&classifier.classify(&chunk, method));
                    }))
                }
            })
        })
    }

    fn winding_points(
        &self,
        py: Python<'_>,
        pts: Points<'_>,
        tol: f64,
        threads: usize,
    ) -> PyResult<Vec<f64>> {
        let field = self.field(tol)?;
        py.detach(|| {
            with_threads(threads, || {
                let fast = FastWindingField::new(&field);
                let mut out = vec![0.0; pts.len()];
                with_point_accessor!(pts, |at| fast
                    .winding_numbers_indexed_parallel_into(at, &mut out));
                out
            })
        })
    }

    /// Winding numbers of `pts` by one of the ray-casting baselines (as `inrs winding
    /// --algorithm` computes them: [`WindingField::winding_number_with`] point by point), in
    /// parallel.
    fn winding_points_with(
        &self,
        py: Python<'_>,
        pts: Points<'_>,
        tol: f64,
        algorithm: WindingAlgorithm,
        threads: usize,
    ) -> PyResult<Vec<f64>> {
        use rayon::prelude::*;
        const TASK: usize = 1 << 12;
        let field = self.field(tol)?;
        py.detach(|| {
            with_threads(threads, || {
                let mut out = vec![0.0; pts.len()];
                with_point_accessor!(pts, |at| out.par_chunks_mut(TASK).enumerate().for_each(
                    |(c, out)| {
                        let mut stats = QueryStats::default();
                        for (i, w) in out.iter_mut().enumerate() {
                            *w = field.winding_number_with(at(c * TASK + i), algorithm, &mut stats);
                        }
                    }
                ));
                out
            })
        })
    }
}

/// The value cached in `cache` for tolerance `tol` (checked first), built by `build` and kept
/// on first use.
fn cached<T>(
    cache: &Mutex<HashMap<u64, Arc<T>>>,
    tol: f64,
    what: &str,
    build: impl FnOnce() -> PyResult<T>,
) -> PyResult<Arc<T>> {
    check_tolerance(tol)?;
    let mut cache = cache
        .lock()
        .map_err(|_| value_error(format!("{what} cache poisoned")))?;
    if let Some(v) = cache.get(&tol.to_bits()) {
        return Ok(Arc::clone(v));
    }
    let v = Arc::new(build()?);
    cache.insert(tol.to_bits(), Arc::clone(&v));
    Ok(v)
}

fn check_tolerance(tol: f64) -> PyResult<()> {
    if tol.is_finite() && tol >= 0.0 {
        Ok(())
    } else {
        Err(value_error(format!(
            "tolerance {tol} must be finite and >= 0"
        )))
    }
}

#[pymethods]
impl NativeDomain {
    /// Reads a domain file: JSON, SVG, DXF, or a font glyph `font.ttf#B`.
    #[staticmethod]
    fn load(path: &str) -> PyResult<Self> {
        Ok(Self::new(inrs::io::load_domain(path).map_err(io_error)?))
    }

    /// A domain from the text of a JSON domain file.
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        Ok(Self::new(
            inrs::io::json::domain_from_json(text).map_err(io_error)?,
        ))
    }

    /// A domain from NURBS curves given as arrays, `(degree, knots, control points (M, 2),
    /// weights (M,) or None)` each, checked as the JSON reader checks a curve of the NURBS
    /// form ([`NurbsCurve::new`], then [`Domain::new`]); errors name the curve by its index.
    #[staticmethod]
    #[pyo3(signature = (curves, name = None))]
    fn from_curves(curves: Vec<CurveArrays<'_>>, name: Option<&str>) -> PyResult<Self> {
        let mut built = Vec::with_capacity(curves.len());
        for (i, (degree, knots, points, weights)) in curves.iter().enumerate() {
            let points = pairs(points)
                .map_err(|_| {
                    value_error(format!(
                        "curve {i}: control points must have shape (M, 2), got {:?}",
                        points.shape()
                    ))
                })?
                .to_vec();
            let weights = weights.as_ref().map(|w| w.as_array().to_vec());
            let curve = NurbsCurve::new(*degree, knots.as_array().to_vec(), points, weights)
                .map_err(|source| {
                    io_error(inrs::io::IoError::Curve {
                        origin: format!("curve {i}"),
                        source,
                    })
                })?;
            built.push(curve);
        }
        let domain = Domain::new(built).map_err(|e| io_error(e.into()))?;
        Ok(Self::new(match name {
            Some(name) => domain.with_name(name),
            None => domain,
        }))
    }

    /// The JSON domain file (round-trips exactly).
    fn to_json(&self) -> String {
        inrs::io::json::domain_to_json(&self.domain)
    }

    /// The name, if any.
    #[getter]
    fn name(&self) -> Option<String> {
        self.domain.name().map(str::to_string)
    }

    /// Curves, loops, areas and bounds (see [`DomainSummary`]).
    fn summary(&self) -> DomainSummary {
        DomainSummary::of(&self.domain)
    }

    /// Codes for an `(N, 2)` float64 array (any layout).
    fn classify_pairs<'py>(
        &self,
        py: Python<'py>,
        xy: PyReadonlyArray2<'py, f64>,
        method: &str,
        tol: f64,
        fill_rule: &str,
        threads: usize,
    ) -> PyResult<Bound<'py, PyArray1<i8>>> {
        let pts = pairs(&xy)?;
        Ok(self
            .classify_points(py, pts, method, tol, fill_rule, threads)?
            .into_pyarray(py))
    }

    /// Codes for two 1-D float64 arrays (any layout).
    #[allow(clippy::too_many_arguments)]
    fn classify_columns<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        y: PyReadonlyArray1<'py, f64>,
        method: &str,
        tol: f64,
        fill_rule: &str,
        threads: usize,
    ) -> PyResult<Bound<'py, PyArray1<i8>>> {
        let pts = columns(&x, &y)?;
        Ok(self
            .classify_points(py, pts, method, tol, fill_rule, threads)?
            .into_pyarray(py))
    }

    /// Generalized winding numbers for two 1-D float64 arrays (any layout); points within
    /// `tol` (relative) of a curve get the average across the jump. `algorithm` is a name of
    /// `inrs winding --algorithm`: `adaptive` (the accelerated field), `binary-search` or
    /// `bezier-clipping` (the GWN paper's ray-casting baselines).
    #[pyo3(signature = (x, y, tol, threads, algorithm = "adaptive"))]
    fn winding_columns<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        y: PyReadonlyArray1<'py, f64>,
        tol: f64,
        threads: usize,
        algorithm: &str,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let algorithm: WindingAlgorithm = algorithm.parse().map_err(value_error)?;
        let pts = columns(&x, &y)?;
        let w = if algorithm == WindingAlgorithm::Adaptive {
            self.winding_points(py, pts, tol, threads)?
        } else {
            self.winding_points_with(py, pts, tol, algorithm, threads)?
        };
        Ok(w.into_pyarray(py))
    }

    /// The boundary flattened: per loop, an `(M, 2)` array of a closed polyline within
    /// `accuracy` of the curves.
    fn flatten<'py>(
        &self,
        py: Python<'py>,
        accuracy: f64,
    ) -> PyResult<Vec<Bound<'py, PyArray2<f64>>>> {
        if !(accuracy.is_finite() && accuracy > 0.0) {
            return Err(value_error("accuracy must be finite and > 0"));
        }
        let mut rings = Vec::new();
        for l in self.domain.loops() {
            let mut pts: Vec<f64> = Vec::new();
            for (k, ci) in l.curves().enumerate() {
                let c = &self.domain.curves()[ci];
                let mut emit = |p: Point| {
                    pts.push(p.x);
                    pts.push(p.y);
                };
                if k == 0 {
                    c.flatten(accuracy, &mut emit);
                } else {
                    c.flatten_after_start(accuracy, &mut emit);
                }
            }
            let n = pts.len() / 2;
            rings.push(pts.into_pyarray(py).reshape([n, 2])?);
        }
        Ok(rings)
    }
}
