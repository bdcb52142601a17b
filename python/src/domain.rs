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
use inrs::contain::{FillRule, WindingField};
use inrs::spline::limits::NonNegative;
use inrs::{ContainOptions, Containment, Domain, Location, Method, NurbsCurve, Point, PointQuery};

use crate::errors::{io_error, value_error};
use crate::points::{PointArrays, pairs, with_point_source};
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
    /// What classifies, by its options (the library's value, validated: the key is the
    /// options themselves), built on first use and kept.
    containments: Mutex<HashMap<ContainOptions, Arc<Containment>>>,
    /// The winding-number fields by tolerance.
    fields: Mutex<HashMap<u64, Arc<WindingField>>>,
}

impl NativeDomain {
    pub(crate) fn new(domain: Domain) -> Self {
        Self {
            domain,
            containments: Mutex::new(HashMap::new()),
            fields: Mutex::new(HashMap::new()),
        }
    }

    fn containment(&self, options: ContainOptions) -> PyResult<Arc<Containment>> {
        cached(&self.containments, options, "classifier", || {
            Containment::new(&self.domain, options).map_err(value_error)
        })
    }

    fn field(&self, tol: f64) -> PyResult<Arc<WindingField>> {
        check_tolerance(tol)?;
        cached(&self.fields, tol.to_bits(), "winding-field", || {
            WindingField::new(&self.domain, tol).map_err(value_error)
        })
    }
}

/// The options of a classification, from the words Python passes (`method` and `fill_rule`
/// as their `FromStr` reads them), validated once ([`ContainOptions::validated`]): what
/// every classification of the package and its cache key are.
pub(crate) fn contain_options(tol: f64, method: &str, fill_rule: &str) -> PyResult<ContainOptions> {
    let method: Method = method.parse().map_err(value_error)?;
    let fill_rule: FillRule = fill_rule.parse().map_err(value_error)?;
    ContainOptions::DEFAULT
        .with_relative_tolerance(tol)
        .with_method(method)
        .with_fill_rule(fill_rule)
        .validated()
        .map_err(value_error)
}

/// The value cached in `cache` under `key`, built by `build` and kept on first use.
fn cached<K: std::hash::Hash + Eq, T>(
    cache: &Mutex<HashMap<K, Arc<T>>>,
    key: K,
    what: &str,
    build: impl FnOnce() -> PyResult<T>,
) -> PyResult<Arc<T>> {
    let mut cache = cache
        .lock()
        .map_err(|_| value_error(format!("{what} cache poisoned")))?;
    if let Some(v) = cache.get(&key) {
        return Ok(Arc::clone(v));
    }
    let v = Arc::new(build()?);
    cache.insert(key, Arc::clone(&v));
    Ok(v)
}

/// The boundary tolerance: finite and non-negative.
pub(crate) fn check_tolerance(tol: f64) -> PyResult<()> {
    NonNegative::new(tol)
        .map(|_| ())
        .map_err(|e| value_error(format!("tolerance {e}")))
}

/// `closure_tol=`: `None`, or finite and non-negative.
pub(crate) fn check_closure_tol(closure_tol: Option<f64>) -> PyResult<()> {
    match closure_tol.map(NonNegative::new) {
        Some(Err(e)) => Err(value_error(format!("closure_tol {e}"))),
        _ => Ok(()),
    }
}

#[pymethods]
impl NativeDomain {
    /// Reads a domain file: JSON, SVG, DXF, a font glyph `font.ttf#B`, or a face of a STEP or
    /// IGES part `part.step#face:3`; `closure_tol` (relative) overrides the closure tolerance.
    /// Returns the domain and the messages of what the reader recovered from (an SVG path
    /// drawn up to an error in its data), which the Python layer turns into warnings.
    #[staticmethod]
    #[pyo3(signature = (path, closure_tol = None))]
    fn load(path: &str, closure_tol: Option<f64>) -> PyResult<(Self, Vec<String>)> {
        check_closure_tol(closure_tol)?;
        let options = inrs::io::LoadOptions {
            closure_tolerance: closure_tol,
        };
        let loaded = inrs::io::load_domain_with_warnings(path, &options).map_err(io_error)?;
        let warnings = loaded
            .warnings
            .iter()
            .map(|w| format!("{path}: {w}"))
            .collect();
        Ok((Self::new(loaded.domain), warnings))
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
    #[pyo3(signature = (curves, name = None, closure_tol = None))]
    fn from_curves(
        curves: Vec<CurveArrays<'_>>,
        name: Option<&str>,
        closure_tol: Option<f64>,
    ) -> PyResult<Self> {
        check_closure_tol(closure_tol)?;
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
        let tol = closure_tol.unwrap_or(inrs::spline::DEFAULT_RELATIVE_CLOSURE_TOLERANCE);
        let domain =
            Domain::with_relative_closure_tolerance(built, tol).map_err(|e| io_error(e.into()))?;
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

    /// Curves, loops, areas and bounds (see [`DomainSummary`]), the area filled under
    /// `fill_rule`.
    #[pyo3(signature = (fill_rule = "even-odd"))]
    fn summary(&self, fill_rule: &str) -> PyResult<DomainSummary> {
        let rule: FillRule = fill_rule.parse().map_err(value_error)?;
        Ok(DomainSummary::of(&self.domain, rule))
    }

    /// The area the domain fills under `fill_rule`: a `ValueError` naming why where its loops'
    /// nesting does not decide it (open, coincident or crossing loops).
    #[pyo3(signature = (fill_rule = "even-odd"))]
    fn filled_area(&self, fill_rule: &str) -> PyResult<f64> {
        let rule: FillRule = fill_rule.parse().map_err(value_error)?;
        inrs::contain::filled_area(&self.domain, rule).map_err(value_error)
    }

    /// Codes for the points (an `(N, 2)` array or a tuple `(x, y)` of 1-D ones, float64 in any
    /// layout).
    fn classify<'py>(
        &self,
        py: Python<'py>,
        points: PointArrays<'py>,
        method: &str,
        tol: f64,
        fill_rule: &str,
        threads: usize,
    ) -> PyResult<Bound<'py, PyArray1<i8>>> {
        // The library's `Containment` for the options picks the algorithm for the batch.
        let containment = self.containment(contain_options(tol, method, fill_rule)?)?;
        let pts = points.points()?;
        let codes: Vec<i8> = py.detach(|| {
            with_threads(threads, || {
                let engine = containment.engine(pts.len());
                let mut locations = vec![Location::Outside; pts.len()];
                with_point_source!(pts, |points| engine
                    .par_values_into(&points, &mut locations));
                locations.iter().map(|l| l.code()).collect()
            })
        })?;
        Ok(codes.into_pyarray(py))
    }

    /// Generalized winding numbers at the points (as [`NativeDomain::classify`] takes them);
    /// points within `tol` (relative) of a curve get the average across the jump. `algorithm`
    /// is a name of `inrs winding --algorithm`: `adaptive` (the accelerated field),
    /// `binary-search` or `bezier-clipping` (the GWN paper's ray-casting baselines).
    #[pyo3(signature = (points, tol, threads, algorithm = "adaptive"))]
    fn winding<'py>(
        &self,
        points: PointArrays<'py>,
        tol: f64,
        threads: usize,
        algorithm: &str,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let py = points.py();
        let algorithm: WindingAlgorithm = algorithm.parse().map_err(value_error)?;
        // As `inrs winding --algorithm` computes them (`WindingField::winding_numbers_by`).
        let field = self.field(tol)?;
        let pts = points.points()?;
        let out = py.detach(|| {
            with_threads(threads, || {
                let numbers = field.winding_numbers_by(algorithm);
                let mut out = vec![0.0; pts.len()];
                with_point_source!(pts, |points| numbers.par_values_into(&points, &mut out));
                out
            })
        })?;
        Ok(out.into_pyarray(py))
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
        for i in 0..self.domain.loops().len() {
            let mut pts: Vec<f64> = Vec::new();
            self.domain.flatten_loop(i, accuracy, &mut |p: Point| {
                pts.push(p.x);
                pts.push(p.y);
            });
            let n = pts.len() / 2;
            rings.push(pts.into_pyarray(py).reshape([n, 2])?);
        }
        Ok(rings)
    }
}
