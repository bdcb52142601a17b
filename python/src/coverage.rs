//! Exact cell coverage of a domain on a rectilinear grid ([`inrs::coverage`]) as NumPy arrays:
//! area (or revolved volume) fractions, centroids of the covered parts, face apertures, the
//! boundary's length, centroid and normal in each cell and face centroids, for the whole grid or
//! for one band of rows (the blocks of `inrs.dask.cell_fractions`, whose height is the
//! library's [`coverage_band_rows`]).

use numpy::{IntoPyArray, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

use inrs::contain::FillRule;
use inrs::coverage::{CellGrid, CoverageOptions, GridCoverage, band_rows};
use inrs::spline::Axis;

use crate::domain::NativeDomain;
use crate::errors::value_error;
use crate::threads::with_threads;

/// The axis of `axisymmetric`: `None`, `"x"` or `"y"` (any case).
fn axis(axisymmetric: Option<&str>) -> PyResult<Option<Axis>> {
    match axisymmetric.map(str::to_ascii_lowercase).as_deref() {
        None => Ok(None),
        Some("x") => Ok(Some(Axis::X)),
        Some("y") => Ok(Some(Axis::Y)),
        Some(_) => Err(value_error(format!(
            "axisymmetric must be None, 'x' or 'y', got {:?}",
            axisymmetric.unwrap_or_default()
        ))),
    }
}

/// The library's options for the outputs asked for.
fn coverage_options(
    centroids: bool,
    apertures: bool,
    boundary: bool,
    face_centroids: bool,
    axisymmetric: Option<&str>,
) -> PyResult<CoverageOptions> {
    Ok(CoverageOptions::DEFAULT
        .with_centroids(centroids)
        .with_apertures(apertures)
        .with_boundary(boundary)
        .with_face_centroids(face_centroids)
        .with_axisymmetric(axis(axisymmetric)?))
}

/// The rows of each band the library cuts a grid of `nx` columns and `ny` rows into for these
/// outputs on rayon's threads ([`band_rows`], the rule of `GridCoverage::all` and `bands`):
/// the default height of the blocks of `inrs.dask.cell_fractions`.
#[pyfunction]
#[pyo3(signature = (nx, ny, centroids, apertures, boundary=false, face_centroids=false))]
pub(crate) fn coverage_band_rows(
    nx: usize,
    ny: usize,
    centroids: bool,
    apertures: bool,
    boundary: bool,
    face_centroids: bool,
) -> PyResult<usize> {
    Ok(band_rows(
        nx,
        ny,
        coverage_options(centroids, apertures, boundary, face_centroids, None)?,
        rayon::current_num_threads(),
    ))
}

/// An array of `rows` x `columns` values, or `None`.
type Grid2<'py> = Option<Bound<'py, PyArray2<f64>>>;
/// An array of `rows` x `columns` pairs, or `None`.
type Grid3<'py> = Option<Bound<'py, PyArray3<f64>>>;

/// The arrays of one coverage of `rows` rows and `nx` columns: fractions `(rows, nx)`, then,
/// when asked for, centroids `(rows, nx, 2)`, vertical-face apertures `(rows, nx + 1)`,
/// horizontal-face apertures `(rows + 1, nx)`, boundary lengths `(rows, nx)`, boundary
/// centroids and normals `(rows, nx, 2)`, vertical-face centroids `(rows, nx + 1)` and
/// horizontal-face centroids `(rows + 1, nx)`.
type CoverageArrays<'py> = (
    Bound<'py, PyArray2<f64>>,
    Grid3<'py>,
    Grid2<'py>,
    Grid2<'py>,
    Grid2<'py>,
    Grid3<'py>,
    Grid3<'py>,
    Grid2<'py>,
    Grid2<'py>,
);

/// The coverage of the grid with edges `x_edges`, `y_edges` by `domain` under `fill_rule`
/// (`even-odd` or `nonzero`, as `Domain.classify` parses it), revolved about `axisymmetric`
/// (`None`, `"x"` or `"y"`): [`GridCoverage::with_fill_rule`], then [`GridCoverage::all`]
/// (`rows` is `None`, on `threads` threads, 0 for all) or [`GridCoverage::rows`] for the rows
/// `j0 .. j1` (`rows = (j0, j1)`, one band as `GridCoverage::bands` computes it, on the
/// calling thread: the other rows are never built). The GIL is released while the library
/// works; its errors (bad edges, open boundary, too many cells, an axis the domain or the
/// grid crosses, planar-only outputs revolved) are `ValueError`s with its one-line message.
#[pyfunction]
#[pyo3(signature = (
    domain, x_edges, y_edges, rows, centroids, apertures, fill_rule, threads,
    boundary=false, face_centroids=false, axisymmetric=None
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn cell_coverage<'py>(
    py: Python<'py>,
    domain: &NativeDomain,
    x_edges: PyReadonlyArray1<'py, f64>,
    y_edges: PyReadonlyArray1<'py, f64>,
    rows: Option<(usize, usize)>,
    centroids: bool,
    apertures: bool,
    fill_rule: &str,
    threads: usize,
    boundary: bool,
    face_centroids: bool,
    axisymmetric: Option<&str>,
) -> PyResult<CoverageArrays<'py>> {
    let fill_rule: FillRule = fill_rule.parse().map_err(value_error)?;
    let options = coverage_options(centroids, apertures, boundary, face_centroids, axisymmetric)?;
    let grid = CellGrid::new(x_edges.as_array().to_vec(), y_edges.as_array().to_vec())
        .map_err(value_error)?;
    let nx = grid.nx();
    let d = &domain.domain;
    let coverage = py
        .detach(|| {
            with_threads(threads, || {
                let cover = GridCoverage::with_fill_rule(d, grid, fill_rule)?;
                match rows {
                    Some((j0, j1)) => cover.rows(j0..j1, options),
                    None => cover.all(options),
                }
            })
        })?
        .map_err(value_error)?;
    let n = coverage.ny();
    let cells = |v: Option<Vec<f64>>, columns: usize, lines: usize| {
        v.map(|a| a.into_pyarray(py).reshape([lines, columns]))
            .transpose()
    };
    let pairs = |v: Option<Vec<[f64; 2]>>| {
        v.map(|c| c.into_flattened().into_pyarray(py).reshape([n, nx, 2]))
            .transpose()
    };
    Ok((
        coverage.fractions.into_pyarray(py).reshape([n, nx])?,
        pairs(coverage.centroids)?,
        cells(coverage.x_apertures, nx + 1, n)?,
        cells(coverage.y_apertures, nx, n + 1)?,
        cells(coverage.boundary_lengths, nx, n)?,
        pairs(coverage.boundary_centroids)?,
        pairs(coverage.boundary_normals)?,
        cells(coverage.x_face_centroids, nx + 1, n)?,
        cells(coverage.y_face_centroids, nx, n + 1)?,
    ))
}
