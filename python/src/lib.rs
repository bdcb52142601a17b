//! The native part of the `inrs` Python package: domains, classification and winding numbers on
//! NumPy arrays (the GIL released while Rust works, all cores by default), sampling, meshing and
//! splines. The Python layer (`inrs/__init__.py`) turns any array-like into the float64 arrays
//! these functions take (a copy only when the input is not float64); any memory layout is read
//! in place.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Instant;

use numpy::ndarray::{ArrayView1, ArrayView2};
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use inrs::contain::{
    DEFAULT_RELATIVE_TOLERANCE, FAST_METHOD_MIN_POINTS, FastWindingField, FillRule, Locate,
    WindingField, fast_uses_locator,
};
use inrs::mesh::{CurvedTriangulation, EdgeKind, Refinement, well_spaced_points};
use inrs::spline::Flatten;
use inrs::trispline::bb::Order;
use inrs::trispline::{QuasiInterpolation, Spline};
use inrs::{Classifier, ContainOptions, Domain, DomainSummary, Location, Method, Point};

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// A reader's error: unreadable files are `OSError`, everything else `ValueError`.
fn io_error(e: inrs::io::IoError) -> PyErr {
    match e {
        inrs::io::IoError::Read { .. } => PyOSError::new_err(e.to_string()),
        other => value_error(other),
    }
}

/// Thread pools by size (0: rayon's global pool, all cores).
fn with_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> PyResult<T> {
    static POOLS: OnceLock<Mutex<HashMap<usize, Arc<rayon::ThreadPool>>>> = OnceLock::new();
    if threads == 0 {
        return Ok(f());
    }
    let pool = {
        let mut pools = POOLS
            .get_or_init(|| Mutex::new(HashMap::new()))
            .lock()
            .map_err(|_| value_error("thread pool cache poisoned"))?;
        match pools.get(&threads) {
            Some(p) => Arc::clone(p),
            None => {
                let p = Arc::new(
                    rayon::ThreadPoolBuilder::new()
                        .num_threads(threads)
                        .build()
                        .map_err(value_error)?,
                );
                pools.insert(threads, Arc::clone(&p));
                p
            }
        }
    };
    Ok(pool.install(f))
}

/// The points of an `(N, 2)` float64 array, or of two 1-D ones, in any memory layout (read in
/// place, never copied).
#[derive(Clone, Copy)]
enum Points<'a> {
    Pairs(ArrayView2<'a, f64>),
    Columns(ArrayView1<'a, f64>, ArrayView1<'a, f64>),
}

impl Points<'_> {
    fn len(&self) -> usize {
        match self {
            Points::Pairs(v) => v.nrows(),
            Points::Columns(x, _) => x.len(),
        }
    }
}

/// Runs `$body` with `$at: Fn(usize) -> Point` reading the points' memory directly: one
/// specialised accessor per layout (contiguous slices or strided views), so the hot loops in
/// `$body` are compiled for each and never branch on the layout per point.
macro_rules! with_point_accessor {
    ($pts:expr, |$at:ident| $body:expr) => {
        match $pts {
            Points::Pairs(v) => match v.as_slice() {
                Some(s) => {
                    let $at = |i: usize| Point::new(s[2 * i], s[2 * i + 1]);
                    $body
                }
                None => {
                    let $at = |i: usize| Point::new(v[[i, 0]], v[[i, 1]]);
                    $body
                }
            },
            Points::Columns(x, y) => match (x.as_slice(), y.as_slice()) {
                (Some(x), Some(y)) => {
                    let $at = |i: usize| Point::new(x[i], y[i]);
                    $body
                }
                _ => {
                    let $at = |i: usize| Point::new(x[i], y[i]);
                    $body
                }
            },
        }
    };
}

impl Points<'_> {
    /// A copy as points, for the kernels that take a slice.
    fn to_vec(self) -> Vec<Point> {
        with_point_accessor!(self, |at| (0..self.len()).map(at).collect())
    }
}

fn pairs<'a>(xy: &'a PyReadonlyArray2<'_, f64>) -> PyResult<Points<'a>> {
    if xy.shape()[1] != 2 {
        return Err(value_error(format!(
            "points must have shape (N, 2), got {:?}",
            xy.shape()
        )));
    }
    Ok(Points::Pairs(xy.as_array()))
}

fn columns<'a>(
    x: &'a PyReadonlyArray1<'_, f64>,
    y: &'a PyReadonlyArray1<'_, f64>,
) -> PyResult<Points<'a>> {
    if x.len() != y.len() {
        return Err(value_error(format!(
            "x and y differ in length: {} and {}",
            x.len(),
            y.len()
        )));
    }
    Ok(Points::Columns(x.as_array(), y.as_array()))
}

/// Codes (0 outside, 1 inside, 2 boundary) of `n` points, in parallel chunks: `fill(first,
/// locations)` locates the points `first..first + locations.len()`, and each chunk's codes go
/// straight into the result (no array of locations the size of the input).
fn codes_in_chunks(n: usize, fill: impl Fn(usize, &mut [Location]) + Sync) -> Vec<i8> {
    use rayon::prelude::*;
    const TASK: usize = 1 << 16;
    let mut codes = vec![0i8; n];
    codes
        .par_chunks_mut(TASK)
        .enumerate()
        .for_each(|(c, codes)| {
            let mut buffer = [Location::Outside; TASK];
            let locations = &mut buffer[..codes.len()];
            fill(c * TASK, locations);
            for (code, location) in codes.iter_mut().zip(locations.iter()) {
                *code = location.code();
            }
        });
    codes
}

/// `(curves, loops, filled area, signed area, bounds, loops' (first, last, closed, area))`.
type Summary = (
    usize,
    usize,
    Option<f64>,
    f64,
    (f64, f64, f64, f64),
    Vec<(usize, usize, bool, f64)>,
);

/// Points `(N, 2)` and a boundary mask `(N,)`.
type Sampled<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<bool>>);

/// A planar domain bounded by NURBS curves (the native object behind `inrs.Domain`).
#[pyclass(module = "inrs._inrs", name = "NativeDomain", frozen)]
struct NativeDomain {
    domain: Domain,
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
            let rule = match fill_rule {
                "even-odd" | "evenodd" => FillRule::EvenOdd,
                "nonzero" | "non-zero" => FillRule::NonZero,
                other => {
                    return Err(value_error(format!(
                        "unknown fill rule {other:?} (even-odd or nonzero)"
                    )));
                }
            };
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

    /// The JSON domain file (round-trips exactly).
    fn to_json(&self) -> String {
        inrs::io::json::domain_to_json(&self.domain)
    }

    /// The name, if any.
    #[getter]
    fn name(&self) -> Option<String> {
        self.domain.name().map(str::to_string)
    }

    /// A summary: `(curves, loops, filled area (even-odd) or None, signed area, (xmin, ymin,
    /// xmax, ymax), [(first curve, last curve, closed, signed area) per loop])`.
    fn summary(&self) -> Summary {
        let s = DomainSummary::of(&self.domain);
        let b = s.bounding_box;
        let loops = s
            .loops
            .iter()
            .map(|l| (l.curves.0, l.curves.1, l.closed, l.signed_area))
            .collect();
        (
            s.curves,
            s.loops.len(),
            s.filled_area,
            s.signed_area,
            (b.min.x, b.min.y, b.max.x, b.max.y),
            loops,
        )
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
    /// `tol` (relative) of a curve get the average across the jump.
    fn winding_columns<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        y: PyReadonlyArray1<'py, f64>,
        tol: f64,
        threads: usize,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let pts = columns(&x, &y)?;
        Ok(self.winding_points(py, pts, tol, threads)?.into_pyarray(py))
    }

    /// Seconds the Rust kernel of the default method takes on these points, copied first (for
    /// measuring the Python call's overhead).
    fn kernel_seconds(
        &self,
        py: Python<'_>,
        xy: PyReadonlyArray2<'_, f64>,
        threads: usize,
    ) -> PyResult<f64> {
        let pts: Vec<Point> = pairs(&xy)?.to_vec();
        let classifier = self.classifier(DEFAULT_RELATIVE_TOLERANCE)?;
        py.detach(|| {
            with_threads(threads, || {
                let locator = classifier.locator();
                let start = Instant::now();
                let out = locator.locate_all_parallel(&pts);
                let t = start.elapsed().as_secs_f64();
                std::hint::black_box(out);
                t
            })
        })
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

/// The most points [`halton_points`] makes at once (16 GiB of coordinates): larger clouds are
/// made in blocks with `start`.
const MAX_HALTON_POINTS: usize = 1 << 30;

/// Halton points `start .. start + n` (bases 2 and 3, the papers' test clouds) of the box
/// `(xmin, ymin, xmax, ymax)`, as an `(n, 2)` array.
#[pyfunction]
fn halton_points<'py>(
    py: Python<'py>,
    n: usize,
    bounds: (f64, f64, f64, f64),
    start: u64,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    if n > MAX_HALTON_POINTS {
        return Err(value_error(format!(
            "n = {n} is more than {MAX_HALTON_POINTS} points; make them in blocks with start"
        )));
    }
    if start.checked_add(n as u64).is_none() {
        return Err(value_error(format!(
            "start = {start} plus n = {n} overflows"
        )));
    }
    let (xmin, ymin, xmax, ymax) = bounds;
    if ![xmin, ymin, xmax, ymax].iter().all(|v| v.is_finite()) || xmin > xmax || ymin > ymax {
        return Err(value_error(format!(
            "bounds must be finite (xmin, ymin, xmax, ymax) with xmin <= xmax, ymin <= ymax, got {bounds:?}"
        )));
    }
    let b = inrs::BoundingBox {
        min: Point::new(xmin, ymin),
        max: Point::new(xmax, ymax),
    };
    let flat: Vec<f64> = py.detach(|| {
        inrs::contain::baselines::halton_points_from(start, n, b)
            .iter()
            .flat_map(|p| [p.x, p.y])
            .collect()
    });
    flat.into_pyarray(py).reshape([n, 2])
}

/// Well-spaced points of Algorithm 11.1: `(points (N, 2), boundary mask (N,))`.
#[pyfunction]
fn sample<'py>(py: Python<'py>, domain: &NativeDomain, ny: usize) -> PyResult<Sampled<'py>> {
    let pts = py
        .detach(|| well_spaced_points(&domain.domain, ny))
        .map_err(value_error)?;
    let nb: usize = pts.boundary.iter().map(Vec::len).sum();
    let all = pts.all_points();
    let mask: Vec<bool> = (0..all.len()).map(|i| i < nb).collect();
    let flat: Vec<f64> = all.iter().flat_map(|p| [p.x, p.y]).collect();
    Ok((
        flat.into_pyarray(py).reshape([all.len(), 2])?,
        mask.into_pyarray(py),
    ))
}

fn triangulation(domain: &Domain, ny: usize, refine: &str) -> PyResult<CurvedTriangulation> {
    let pts = well_spaced_points(domain, ny).map_err(value_error)?;
    match refine {
        "none" => CurvedTriangulation::new(domain, &pts),
        "ct" => CurvedTriangulation::new_refined(domain, &pts, Refinement::CloughTocher),
        "ps" => CurvedTriangulation::new_refined(domain, &pts, Refinement::PowellSabin),
        other => {
            return Err(value_error(format!(
                "unknown refinement {other:?} (none, ct or ps)"
            )));
        }
    }
    .map_err(value_error)
}

/// The curved triangulation as arrays: a dict with `vertices` (N, 2), `triangles` (T, 3)
/// counter-clockwise, and `curved_edges`, a dict of equal-length arrays `triangle`, `edge`,
/// `curve`, `loop`, `u0`, `u1`, `start`, `end` (edge `k` of a triangle runs from its vertex `k`
/// to `k + 1` and follows domain curve `curve` from `u0`, at vertex `start`, to `u1`).
#[pyfunction]
#[pyo3(signature = (domain, ny, refine = "none"))]
fn mesh<'py>(
    py: Python<'py>,
    domain: &NativeDomain,
    ny: usize,
    refine: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let m = py.detach(|| triangulation(&domain.domain, ny, refine))?;
    let out = PyDict::new(py);
    let v: Vec<f64> = m.vertices().iter().flat_map(|p| [p.x, p.y]).collect();
    out.set_item(
        "vertices",
        v.into_pyarray(py).reshape([m.vertices().len(), 2])?,
    )?;
    let t: Vec<i64> = m.triangles().iter().flatten().map(|&i| i as i64).collect();
    out.set_item(
        "triangles",
        t.into_pyarray(py).reshape([m.triangles().len(), 3])?,
    )?;
    let edges = PyDict::new(py);
    let (mut tri, mut edge, mut curve, mut lp, mut u0, mut u1, mut from, mut to) = (
        vec![],
        vec![],
        vec![],
        vec![],
        vec![],
        vec![],
        vec![],
        vec![],
    );
    for t in 0..m.triangles().len() {
        for (k, kind) in m.edge_kinds(t).iter().enumerate() {
            if let EdgeKind::Curved(i) = kind {
                let a = &m.arcs()[*i];
                tri.push(t as i64);
                edge.push(k as i64);
                curve.push(a.curve as i64);
                lp.push(a.loop_index as i64);
                u0.push(a.u0);
                u1.push(a.u1);
                from.push(a.from as i64);
                to.push(a.to as i64);
            }
        }
    }
    edges.set_item("triangle", tri.into_pyarray(py))?;
    edges.set_item("edge", edge.into_pyarray(py))?;
    edges.set_item("curve", curve.into_pyarray(py))?;
    edges.set_item("loop", lp.into_pyarray(py))?;
    edges.set_item("u0", u0.into_pyarray(py))?;
    edges.set_item("u1", u1.into_pyarray(py))?;
    edges.set_item("start", from.into_pyarray(py))?;
    edges.set_item("end", to.into_pyarray(py))?;
    out.set_item("curved_edges", edges)?;
    Ok(out)
}

/// A quasi-interpolation waiting for the function's values (`inrs.fit` fills them in, calling
/// the function once on all points).
#[pyclass(module = "inrs._inrs", name = "FitPlan")]
struct FitPlan {
    plan: Option<QuasiInterpolation>,
}

#[pymethods]
impl FitPlan {
    #[new]
    #[pyo3(signature = (domain, ny, degree, refine = "none"))]
    fn new(
        py: Python<'_>,
        domain: &NativeDomain,
        ny: usize,
        degree: usize,
        refine: &str,
    ) -> PyResult<Self> {
        let plan = py.detach(|| {
            let m = triangulation(&domain.domain, ny, refine)?;
            QuasiInterpolation::new(m, degree).map_err(value_error)
        })?;
        Ok(Self { plan: Some(plan) })
    }

    /// Where the function is needed: an `(N, 2)` array.
    fn points<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let plan = self
            .plan
            .as_ref()
            .ok_or_else(|| value_error("plan already used"))?;
        let v: Vec<f64> = plan.points().iter().flat_map(|p| [p.x, p.y]).collect();
        v.into_pyarray(py).reshape([plan.points().len(), 2])
    }

    /// The spline from the values at [`FitPlan::points`].
    fn finish(
        &mut self,
        py: Python<'_>,
        values: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<NativeSpline> {
        let plan = self
            .plan
            .take()
            .ok_or_else(|| value_error("plan already used"))?;
        let values = values.as_slice().map_err(value_error)?.to_vec();
        let spline = py.detach(|| plan.finish(&values)).map_err(value_error)?;
        Ok(NativeSpline { spline })
    }
}

/// A spline on a curved triangulation (the native object behind `inrs.Spline`).
#[pyclass(module = "inrs._inrs", name = "NativeSpline", frozen)]
struct NativeSpline {
    spline: Spline,
}

#[pymethods]
impl NativeSpline {
    /// A spline from the text of a spline file.
    #[staticmethod]
    fn from_json(text: &str) -> PyResult<Self> {
        Ok(Self {
            spline: inrs::trispline::spline_from_json(text).map_err(value_error)?,
        })
    }

    /// The spline file's text.
    fn to_json(&self) -> String {
        inrs::trispline::spline_to_json(&self.spline)
    }

    /// `(degree, triangles, coefficients of the space)`.
    fn summary(&self) -> (usize, usize, usize) {
        (
            self.spline.degree(),
            self.spline.mesh().triangles().len(),
            self.spline.dimension(),
        )
    }

    /// Values (and gradients if `derivatives`) at the points; NaN outside the domain. Returns
    /// an `(N, 3)` array `value, dx, dy` with `derivatives`, else an `(N,)` one.
    fn evaluate_columns<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        y: PyReadonlyArray1<'py, f64>,
        derivatives: bool,
        threads: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let pts = columns(&x, &y)?;
        let order = if derivatives {
            Order::Gradient
        } else {
            Order::Value
        };
        let jets = py.detach(|| {
            with_threads(threads, || {
                let eval = self.spline.evaluator().map_err(value_error)?;
                let pts: Vec<Point> = pts.to_vec();
                Ok::<_, PyErr>(eval.evaluate_all(&pts, order))
            })
        })??;
        if derivatives {
            let v: Vec<f64> = jets
                .iter()
                .flat_map(|j| match j {
                    Some(j) => [j.value, j.gradient[0], j.gradient[1]],
                    None => [f64::NAN; 3],
                })
                .collect();
            Ok(v.into_pyarray(py).reshape([jets.len(), 3])?.into_any())
        } else {
            let v: Vec<f64> = jets
                .iter()
                .map(|j| j.map_or(f64::NAN, |j| j.value))
                .collect();
            Ok(v.into_pyarray(py).into_any())
        }
    }
}

/// The native module `inrs._inrs`.
#[pymodule]
fn _inrs(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<NativeDomain>()?;
    m.add_class::<NativeSpline>()?;
    m.add_class::<FitPlan>()?;
    m.add_function(wrap_pyfunction!(sample, m)?)?;
    m.add_function(wrap_pyfunction!(mesh, m)?)?;
    m.add_function(wrap_pyfunction!(halton_points, m)?)?;
    m.add("OUTSIDE", Location::Outside.code())?;
    m.add("INSIDE", Location::Inside.code())?;
    m.add("BOUNDARY", Location::Boundary.code())?;
    m.add("DEFAULT_TOLERANCE", DEFAULT_RELATIVE_TOLERANCE)?;
    m.add("FAST_METHOD_MIN_POINTS", FAST_METHOD_MIN_POINTS)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
