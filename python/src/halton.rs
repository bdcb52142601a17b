//! The papers' quasi-random test clouds.

use numpy::{IntoPyArray, PyArray2, PyArrayMethods};
use pyo3::prelude::*;

use inrs::Point;

use crate::errors::value_error;

/// The most points [`halton_points`] makes at once (16 GiB of coordinates): larger clouds are
/// made in blocks with `start`.
const MAX_HALTON_POINTS: usize = 1 << 30;

/// Halton points `start .. start + n` (bases 2 and 3, the papers' test clouds) of the box
/// `(xmin, ymin, xmax, ymax)`, as an `(n, 2)` array.
#[pyfunction]
pub(crate) fn halton_points<'py>(
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
