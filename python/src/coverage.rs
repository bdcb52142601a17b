//! Exact cell coverage of a domain on a rectilinear grid ([`inrs::coverage`]) as NumPy arrays:
//! area fractions, centroids of the covered parts and face apertures, for the whole grid or
//! for one band of rows (the blocks of `inrs.dask.cell_fractions`, whose height is the
//! library's [`coverage_band_rows`]).

use numpy::{IntoPyArray, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

use inrs::contain::FillRule;
use inrs::coverage::{CellGrid, CoverageOptions, GridCoverage, band_rows};

use crate::domain::NativeDomain;
use crate::errors::value_error;
use crate::threads::with_threads;

/// The options of `centroids` and `apertures`.
fn coverage_options(centroids: bool, apertures: bool) -> CoverageOptions {
    CoverageOptions::DEFAULT
        .with_centroids(centroids)
        .with_apertures(apertures)
}

/// The rows of each band the library cuts a grid of `nx` columns and `ny` rows into for these
/// outputs on rayon's threads ([`band_rows`], the rule of `GridCoverage::all` and `bands`):
/// the default height of the blocks of `inrs.dask.cell_fractions`.
#[pyfunction]
pub(crate) fn coverage_band_rows(nx: usize, ny: usize, centroids: bool, apertures: bool) -> usize {
    band_rows(
        nx,
        ny,
        coverage_options(centroids, apertures),
        rayon::current_num_threads(),
    )
}

/// The arrays of one coverage of `rows` rows and `nx` columns: fractions `(rows, nx)`, then,
/// when asked for, centroids `(rows, nx, 2)`, vertical-face apertures `(rows, nx + 1)` and
/// horizontal-face apertures `(rows + 1, nx)`.
type CoverageArrays<'py> = (
    Bound<'py, PyArray2<f64>>,
    Option<Bound<'py, PyArray3<f64>>>,
    Option<Bound<'py, PyArray2<f64>>>,
    Option<Bound<'py, PyArray2<f64>>>,
);

/// The coverage of the grid with edges `x_edges`, `y_edges` by `domain` under `fill_rule`
/// (`even-odd` or `nonzero`, as `Domain.classify` parses it): [`GridCoverage::with_fill_rule`],
/// then [`GridCoverage::all`] (`rows` is `None`, on `threads` threads, 0
/// for all) or [`GridCoverage::rows`] for the rows `j0 .. j1` (`rows = (j0, j1)`, one band as
/// `GridCoverage::bands` computes it, on the calling thread: the other rows are never built). The GIL is released while
/// the library works; its errors (bad edges, open boundary, too many cells) are `ValueError`s
/// with its one-line message.
#[pyfunction]
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
) -> PyResult<CoverageArrays<'py>> {
    let fill_rule: FillRule = fill_rule.parse().map_err(value_error)?;
    let grid = CellGrid::new(x_edges.as_array().to_vec(), y_edges.as_array().to_vec())
        .map_err(value_error)?;
    let nx = grid.nx();
    let options = coverage_options(centroids, apertures);
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
    Ok((
        coverage.fractions.into_pyarray(py).reshape([n, nx])?,
        coverage
            .centroids
            .map(|c| c.into_flattened().into_pyarray(py).reshape([n, nx, 2]))
            .transpose()?,
        coverage
            .x_apertures
            .map(|a| a.into_pyarray(py).reshape([n, nx + 1]))
            .transpose()?,
        coverage
            .y_apertures
            .map(|a| a.into_pyarray(py).reshape([n + 1, nx]))
            .transpose()?,
    ))
}
