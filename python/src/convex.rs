//! `convex_domain`: where one control point may move keeping the sign of the curvature (plane)
//! or torsion (space), as `inrs convex-domain` computes it.

use std::path::PathBuf;

use numpy::{IntoPyArray, PyArrayMethods};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use inrs::convex::{
    BoundingBox3, ConvexDomainOptions, FreeCurve, Region, Sign, approximate, parse_curve,
};

use crate::errors::value_error;

/// The sign named by `sign` (`positive`, `negative` or `auto`: the curve's own sign, from
/// [`FreeCurve::own_sign`]).
fn sign_to_keep(
    sign: &str,
    curve: &FreeCurve,
    free: usize,
    h: &inrs::convex::SignNumerator,
) -> PyResult<Sign> {
    match sign {
        "positive" => Ok(Sign::Positive),
        "negative" => Ok(Sign::Negative),
        "auto" => Ok(curve.own_sign(free, h)),
        other => Err(value_error(format!(
            "unknown sign {other:?}: expected \"positive\", \"negative\" or \"auto\""
        ))),
    }
}

/// The curve: from the file at `path` (unreadable: `OSError`) or the JSON `text`, as
/// [`inrs::convex::load_curve`] reads it.
fn curve_from(path: Option<PathBuf>, text: Option<String>, index: usize) -> PyResult<FreeCurve> {
    match (path, text) {
        (Some(path), None) => {
            // `load_curve` is this read followed by `parse_curve`; reading apart tells an
            // unreadable file (OSError) from a malformed one (ValueError).
            let text = inrs::spline::limits::read_text_file(&path)
                .map_err(|e| PyOSError::new_err(format!("{}: {e}", path.display())))?;
            parse_curve(&text, index).map_err(|e| value_error(format!("{}: {e}", path.display())))
        }
        (None, Some(text)) => parse_curve(&text, index).map_err(value_error),
        _ => Err(value_error("give exactly one of path and text")),
    }
}

/// The convex domain of control point `free_index` of a curve within `bbox` (4 or 6 numbers),
/// as `inrs convex-domain` computes it: a dict with `levels` (a list of dicts `level,
/// inequalities, measure, abs_error, rel_error`), `outer_measure`, `outcome`
/// (`"Converged"`, `"Empty"` or `"NotConverged"`), `sign` (`"Positive"` or `"Negative"`),
/// `dimension` and `polygon`, the last inner polygon's vertices `(N, 2)` (`None` in space).
#[pyfunction]
#[pyo3(signature = (path, text, curve_index, free_index, bbox, sign, tol, max_level))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn convex_domain<'py>(
    py: Python<'py>,
    path: Option<PathBuf>,
    text: Option<String>,
    curve_index: usize,
    free_index: usize,
    bbox: Vec<f64>,
    sign: &str,
    tol: f64,
    max_level: u32,
) -> PyResult<Bound<'py, PyDict>> {
    let curve = curve_from(path, text, curve_index)?;
    let bbox = BoundingBox3::from_ranges(&bbox).map_err(value_error)?;
    let h = curve.numerator(free_index).map_err(value_error)?;
    let sign = sign_to_keep(sign, &curve, free_index, &h)?;
    let options = ConvexDomainOptions::DEFAULT
        .with_sign(sign)
        .with_relative_tolerance(tol)
        .with_max_level(max_level);
    let k = py
        .detach(|| approximate(&h, &bbox, &options))
        .map_err(value_error)?;
    let levels = PyList::empty(py);
    for l in &k.levels {
        let d = PyDict::new(py);
        d.set_item("level", l.level)?;
        d.set_item("inequalities", l.inequalities)?;
        d.set_item("measure", l.region.measure())?;
        d.set_item("abs_error", l.abs_error)?;
        d.set_item("rel_error", l.rel_error)?;
        levels.append(d)?;
    }
    let out = PyDict::new(py);
    out.set_item("levels", levels)?;
    out.set_item("outer_measure", k.outer.measure())?;
    out.set_item("outcome", format!("{:?}", k.outcome))?;
    out.set_item("sign", format!("{sign:?}"))?;
    out.set_item("dimension", curve.dimension())?;
    match k.inner() {
        Region::Polygon(p) => {
            let flat: Vec<f64> = p.vertices().iter().flat_map(|v| [v.x, v.y]).collect();
            let n = p.vertices().len();
            out.set_item("polygon", flat.into_pyarray(py).reshape([n, 2])?)?;
        }
        Region::Polytope(_) => out.set_item("polygon", py.None())?,
    }
    Ok(out)
}
