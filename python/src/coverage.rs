//! Exact cell coverage of a domain on a rectilinear grid ([`inrs::coverage`]) as NumPy arrays:
//! area (or revolved volume) fractions, centroids of the covered parts, face apertures, the
//! boundary's length, centroid and normal in each cell and face centroids, for the whole grid or
//! for one band of rows (the blocks of `inrs.dask.cell_fractions`, whose height is the
//! library's [`coverage_band_rows`]); several materials on one grid through the library's one
//! entry point [`MaterialCoverage`]: [`material_coverage`] (the whole grid, a leading material
//! axis) and [`NativeMaterials`] (prepared once, then bands of rows of one material: the blocks
//! of `inrs.dask.cell_fractions` for several domains).

use numpy::{
    IntoPyArray, PyArray2, PyArrayDyn, PyArrayMethods, PyReadonlyArray1, PyReadwriteArrayDyn,
};
use pyo3::prelude::*;

use inrs::Domain;
use inrs::contain::FillRule;
use inrs::coverage::{
    CellGrid, Coverage, CoverageArray, CoverageOptions, CoverageSlices, GridCoverage,
    MaterialCoverage, band_rows,
};
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

/// The grid of the edges `x_edges`, `y_edges`, as the library checks them (`ValueError` with
/// its message).
fn grid_of(
    x_edges: &PyReadonlyArray1<'_, f64>,
    y_edges: &PyReadonlyArray1<'_, f64>,
) -> PyResult<CellGrid> {
    CellGrid::new(x_edges.as_array().to_vec(), y_edges.as_array().to_vec()).map_err(value_error)
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

/// An array of any shape, or `None`.
type Stacked<'py> = Option<Bound<'py, PyArrayDyn<f64>>>;

/// The arrays of a coverage in the library's order ([`CoverageArray::ALL`]): the fractions,
/// then, when asked for, the others (`None` for those not asked for), each of the shape
/// [`CoverageArray::shape`] gives, under a leading axis of materials for several.
type CoverageArrays<'py> = (
    Bound<'py, PyArrayDyn<f64>>,
    Stacked<'py>,
    Stacked<'py>,
    Stacked<'py>,
    Stacked<'py>,
    Stacked<'py>,
    Stacked<'py>,
    Stacked<'py>,
    Stacked<'py>,
);

/// The arrays `values(a)` gives for each of [`CoverageArray::ALL`], shaped by `shape(a)`, as
/// [`CoverageArrays`].
fn coverage_arrays<'py>(
    py: Python<'py>,
    mut values: impl FnMut(CoverageArray) -> Option<Vec<f64>>,
    shape: impl Fn(CoverageArray) -> Vec<usize>,
) -> PyResult<CoverageArrays<'py>> {
    let [f, c, xa, ya, bl, bc, bn, xf, yf] = CoverageArray::ALL.map(|a| {
        values(a)
            .map(|v| v.into_pyarray(py).reshape(shape(a)))
            .transpose()
    });
    let fractions = f?.ok_or_else(|| value_error("internal error: no fractions"))?;
    Ok((fractions, c?, xa?, ya?, bl?, bc?, bn?, xf?, yf?))
}

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
    let grid = grid_of(&x_edges, &y_edges)?;
    let (nx, ny) = (grid.nx(), grid.ny());
    let d = &domain.domain;
    let cover = py
        .detach(|| GridCoverage::with_fill_rule(d, grid, fill_rule))
        .map_err(value_error)?;
    let Some((j0, j1)) = rows else {
        // The whole grid into NumPy's own arrays (zeroed by `calloc`, on huge pages where the
        // system has them): the values are written once, where they stay.
        cover.check_all(options).map_err(value_error)?;
        let arrays = CoverageArray::ALL.map(|a| {
            a.computed(options)
                .then(|| PyArrayDyn::<f64>::zeros(py, a.shape(nx, ny), false))
        });
        {
            let mut views: Vec<(CoverageArray, PyReadwriteArrayDyn<'_, f64>)> = CoverageArray::ALL
                .into_iter()
                .zip(&arrays)
                .filter_map(|(a, v)| Some((a, v.as_ref()?.readwrite())))
                .collect();
            let mut slices = CoverageSlices::fractions(&mut []);
            for (a, v) in &mut views {
                let values = v
                    .as_slice_mut()
                    .map_err(|_| value_error("internal error: a new array is not contiguous"))?;
                slices = slices.with(*a, values);
            }
            py.detach(|| with_threads(threads, || cover.all_into(options, slices)))?
                .map_err(value_error)?;
        }
        let [f, c, xa, ya, bl, bc, bn, xf, yf] = arrays;
        let fractions = f.ok_or_else(|| value_error("internal error: no fractions"))?;
        return Ok((fractions, c, xa, ya, bl, bc, bn, xf, yf));
    };
    let mut coverage = py
        .detach(|| with_threads(threads, || cover.rows(j0..j1, options)))?
        .map_err(value_error)?;
    let n = coverage.ny();
    coverage_arrays(py, |a| coverage.take_values(a), |a| a.shape(nx, n))
}

/// The values of `array` moved out of each coverage, one after the other (each coverage's part is
/// freed once copied); `None` when the coverages do not hold them.
fn stack(covers: &mut [Coverage], array: CoverageArray) -> Option<Vec<f64>> {
    let k = covers.len();
    let mut out: Option<Vec<f64>> = None;
    for c in covers.iter_mut() {
        let v = c.take_values(array)?;
        match &mut out {
            None => {
                let mut first = v;
                first.reserve_exact(first.len().saturating_mul(k.saturating_sub(1)));
                out = Some(first);
            }
            Some(o) => o.extend_from_slice(&v),
        }
    }
    out
}

/// The domains of a Python list of `NativeDomain`s, each with `fill_rule` (as
/// `Domain.classify` parses it); `ValueError` for an empty list or an unknown rule.
fn with_rule<'a>(
    domains: &'a [Bound<'_, NativeDomain>],
    fill_rule: &str,
) -> PyResult<Vec<(&'a Domain, FillRule)>> {
    if domains.is_empty() {
        return Err(value_error("domains is empty: give at least one domain"));
    }
    let fill_rule: FillRule = fill_rule.parse().map_err(value_error)?;
    Ok(domains
        .iter()
        .map(|d| (&d.get().domain, fill_rule))
        .collect())
}

/// The coverage of the grid with edges `x_edges`, `y_edges` by the materials `domains` (in
/// the order given, each under `fill_rule`), later domains replacing earlier ones with
/// `replace` (else plain overlaps): [`MaterialCoverage::new`], then
/// [`MaterialCoverage::all`] on `threads` threads (0 for all), the GIL released. Each array
/// has a leading axis of `len(domains)`, material `k` first at index `k`. The library's
/// errors (bad edges, an open boundary, crossing loops, boundaries whose intersections are
/// not found, too many cells, an axis a domain or the grid crosses, planar-only outputs
/// revolved) are `ValueError`s with its one-line message.
#[pyfunction]
#[pyo3(signature = (
    domains, x_edges, y_edges, replace, centroids, apertures, fill_rule, threads,
    boundary=false, face_centroids=false, axisymmetric=None
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn material_coverage<'py>(
    py: Python<'py>,
    domains: Vec<Bound<'py, NativeDomain>>,
    x_edges: PyReadonlyArray1<'py, f64>,
    y_edges: PyReadonlyArray1<'py, f64>,
    replace: bool,
    centroids: bool,
    apertures: bool,
    fill_rule: &str,
    threads: usize,
    boundary: bool,
    face_centroids: bool,
    axisymmetric: Option<&str>,
) -> PyResult<CoverageArrays<'py>> {
    let materials = with_rule(&domains, fill_rule)?;
    let options = coverage_options(centroids, apertures, boundary, face_centroids, axisymmetric)?;
    let grid = grid_of(&x_edges, &y_edges)?;
    let (nx, ny) = (grid.nx(), grid.ny());
    let mut covers = py
        .detach(|| {
            with_threads(threads, || {
                MaterialCoverage::new(&materials, grid, replace)?.all(options)
            })
        })?
        .map_err(value_error)?;
    let k = covers.len();
    coverage_arrays(
        py,
        |a| stack(&mut covers, a),
        |a| [k].into_iter().chain(a.shape(nx, ny)).collect(),
    )
}

/// Several materials prepared on one grid ([`MaterialCoverage::new`]: the regions with
/// replacement and each one's index, built once), whose bands of rows are then computed one
/// material at a time: the per-process object behind the blocks of
/// `inrs.dask.cell_fractions` for several domains.
#[pyclass(module = "inrs._inrs", name = "NativeMaterials", frozen)]
pub(crate) struct NativeMaterials {
    cover: MaterialCoverage,
}

#[pymethods]
impl NativeMaterials {
    /// Prepares the materials `domains` (each under `fill_rule`) on the grid of `x_edges`,
    /// `y_edges`, later ones replacing earlier ones with `replace`; the GIL released.
    /// `ValueError` with the library's message.
    #[new]
    #[pyo3(signature = (domains, x_edges, y_edges, fill_rule, replace))]
    fn new<'py>(
        py: Python<'py>,
        domains: Vec<Bound<'py, NativeDomain>>,
        x_edges: PyReadonlyArray1<'py, f64>,
        y_edges: PyReadonlyArray1<'py, f64>,
        fill_rule: &str,
        replace: bool,
    ) -> PyResult<Self> {
        let materials = with_rule(&domains, fill_rule)?;
        let grid = grid_of(&x_edges, &y_edges)?;
        let cover = py
            .detach(|| MaterialCoverage::new(&materials, grid, replace))
            .map_err(value_error)?;
        Ok(Self { cover })
    }

    /// The number of materials.
    fn __len__(&self) -> usize {
        self.cover.len()
    }

    /// Material `k`'s fractions of the rows `j0 .. j1`, shape `(j1 - j0, nx)`, revolved about
    /// `axisymmetric` (`None`, `"x"` or `"y"`): [`MaterialCoverage::rows`] on the calling
    /// thread, the GIL released (one band as the library's band iterator computes it).
    #[pyo3(signature = (k, j0, j1, axisymmetric=None))]
    fn rows<'py>(
        &self,
        py: Python<'py>,
        k: usize,
        j0: usize,
        j1: usize,
        axisymmetric: Option<&str>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let options = coverage_options(false, false, false, false, axisymmetric)?;
        let cover = &self.cover;
        let band = py
            .detach(|| {
                cover.check_options(options)?;
                cover.rows(k, j0..j1, options)
            })
            .map_err(value_error)?;
        let (n, nx) = (band.ny(), cover.grid().nx());
        band.fractions.into_pyarray(py).reshape([n, nx])
    }
}
