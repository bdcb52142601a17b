//! Splines on curved triangulations: quasi-interpolation of a function ([`FitPlan`]),
//! scattered-data interpolation ([`interpolate`]), and evaluation ([`NativeSpline`]).

use numpy::{IntoPyArray, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

use inrs::PointQuery;
use inrs::trispline::bb::Order;
use inrs::trispline::{C1Space, QuasiInterpolation, Spline, TriSplineError};

use crate::domain::NativeDomain;
use crate::errors::value_error;
use crate::mesh::triangulation;
use crate::points::{PointArrays, pairs, with_point_source};
use crate::threads::with_threads;

/// A quasi-interpolation waiting for the function's values (`inrs.fit` fills them in, calling
/// the function once on all points).
#[pyclass(module = "inrs._inrs", name = "FitPlan")]
pub(crate) struct FitPlan {
    plan: Option<QuasiInterpolation>,
}

#[pymethods]
impl FitPlan {
    /// The plan on the curved triangulation of `inrs.mesh(domain, ny, refine)`.
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

/// `(spline, vertices added, indices of the data points not interpolated)`.
type Interpolated = (NativeSpline, usize, Vec<usize>);

/// The `C^1` spline of `space` (`s512`, `ct`, `ps`, `min-energy`) through the data `z[i]` at
/// `xy[i]` (an `(N, 2)` array, any layout): the curved triangulation whose vertices are the
/// data points, as `inrs fit --data --space` builds it
/// ([`inrs::trispline::interpolate_scattered`]). Returns the spline, the number of vertices
/// that are not data points, and the indices of the data points that are not vertices (between
/// a boundary arc and its chord: not interpolated).
#[pyfunction]
pub(crate) fn interpolate(
    py: Python<'_>,
    domain: &NativeDomain,
    xy: PyReadonlyArray2<'_, f64>,
    z: PyReadonlyArray1<'_, f64>,
    space: &str,
) -> PyResult<Interpolated> {
    let space: C1Space = space.parse().map_err(value_error)?;
    let points = pairs(&xy)?.to_vec();
    let values = z.as_array().to_vec();
    let fit = py
        .detach(|| inrs::trispline::interpolate_scattered(&domain.domain, &points, &values, space))
        .map_err(|e| match e {
            // The point by its row, as the command line names it by its line.
            TriSplineError::DataPoint {
                index,
                x,
                y,
                reason,
            } => value_error(format!("the point xy[{index}] = ({x}, {y}) {reason}")),
            other => value_error(other),
        })?;
    Ok((
        NativeSpline { spline: fit.spline },
        fit.added_vertices,
        fit.unused_points,
    ))
}

/// A spline on a curved triangulation (the native object behind `inrs.Spline`).
#[pyclass(module = "inrs._inrs", name = "NativeSpline", frozen)]
pub(crate) struct NativeSpline {
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

    /// The space's name in the spline file: `s0` (continuous, from `inrs.fit`), `s512`, `ct`,
    /// `ps` or `min-energy`.
    #[getter]
    fn space(&self) -> &'static str {
        self.spline.kind().name()
    }

    /// Values (and gradients if `derivatives`) at the points; NaN outside the domain. Returns
    /// an `(N, 3)` array `value, dx, dy` with `derivatives`, else an `(N,)` one.
    fn evaluate<'py>(
        &self,
        points: PointArrays<'py>,
        derivatives: bool,
        threads: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = points.py();
        let pts = points.points()?;
        let order = if derivatives {
            Order::Gradient
        } else {
            Order::Value
        };
        // The library's evaluator is the query, reading the arrays in place as classify does.
        let jets = py.detach(|| {
            with_threads(threads, || {
                let eval = self
                    .spline
                    .evaluator()
                    .map_err(value_error)?
                    .with_order(order);
                let mut jets = vec![None; pts.len()];
                with_point_source!(pts, |points| eval.par_values_into(&points, &mut jets));
                Ok::<_, PyErr>(jets)
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
