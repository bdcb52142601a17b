//! Well-spaced points and curved triangulations, as arrays.

use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use inrs::Domain;
use inrs::mesh::{CurvedTriangulation, EdgeKind, Refinement, halton_points_in, well_spaced_points};

use crate::domain::NativeDomain;
use crate::errors::value_error;

/// Points `(N, 2)` and a boundary mask `(N,)`.
type Sampled<'py> = (Bound<'py, PyArray2<f64>>, Bound<'py, PyArray1<bool>>);

/// Well-spaced points of Algorithm 11.1: `(points (N, 2), boundary mask (N,))`.
#[pyfunction]
pub(crate) fn sample<'py>(
    py: Python<'py>,
    domain: &NativeDomain,
    ny: usize,
) -> PyResult<Sampled<'py>> {
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

/// The first `count` Halton points inside the domain (`inrs sample --method halton --count`),
/// `(count, 2)`.
#[pyfunction]
pub(crate) fn sample_halton<'py>(
    py: Python<'py>,
    domain: &NativeDomain,
    count: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let pts = py
        .detach(|| halton_points_in(&domain.domain, count))
        .map_err(value_error)?;
    let flat: Vec<f64> = pts.iter().flat_map(|p| [p.x, p.y]).collect();
    flat.into_pyarray(py).reshape([pts.len(), 2])
}

/// The curved triangulation of the well-spaced points with `ny` bands, refined as `refine`
/// (`none`, `ct` or `ps`) names.
pub(crate) fn triangulation(
    domain: &Domain,
    ny: usize,
    refine: &str,
) -> PyResult<CurvedTriangulation> {
    let refinement = Refinement::parse_optional(refine).map_err(value_error)?;
    let pts = well_spaced_points(domain, ny).map_err(value_error)?;
    match refinement {
        None => CurvedTriangulation::new(domain, &pts),
        Some(how) => CurvedTriangulation::new_refined(domain, &pts, how),
    }
    .map_err(value_error)
}

/// The curved triangulation as arrays: a dict with `vertices` (N, 2), `triangles` (T, 3)
/// counter-clockwise, and `curved_edges`, a dict of equal-length arrays `triangle`, `edge`,
/// `curve`, `loop`, `u0`, `u1`, `start`, `end` (edge `k` of a triangle runs from its vertex `k`
/// to `k + 1` and follows domain curve `curve` from `u0`, at vertex `start`, to `u1`).
#[pyfunction]
#[pyo3(signature = (domain, ny, refine = "none"))]
pub(crate) fn mesh<'py>(
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
