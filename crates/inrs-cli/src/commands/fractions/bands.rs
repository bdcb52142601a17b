//! The coverage of a grid written band by band, in order, into `.npy` files whose headers
//! carry the whole grid's shape: memory holds a few bands, whatever the grid.

use std::path::{Path, PathBuf};

use inrs::NpyType;
use inrs::coverage::{Coverage, CoverageError, CoverageOptions, GridCoverage};

use crate::cli::error::CliError;
use crate::cli::output::Output;
use crate::stream::Progress;

/// The files of a run: the fractions, and the optional centroids and apertures.
pub(super) struct OutputPaths {
    pub(super) fractions: PathBuf,
    pub(super) centroids: Option<PathBuf>,
    pub(super) x_apertures: Option<PathBuf>,
    pub(super) y_apertures: Option<PathBuf>,
}

/// The open outputs, each under a temporary name until [`Outputs::finish`]; dropped (on any
/// error) they leave nothing behind.
struct Outputs {
    fractions: Output,
    centroids: Option<Output>,
    x_apertures: Option<Output>,
    y_apertures: Option<Output>,
    /// Reused for the bytes of each array of a band.
    bytes: Vec<u8>,
}

/// Opens `path` and writes a float64 `.npy` header for `shape`.
fn npy_file(path: &Path, shape: &[usize]) -> Result<Output, CliError> {
    let mut out = Output::create(Some(path))?;
    out.write_bytes(&inrs::npy_header(NpyType::F64, shape))?;
    Ok(out)
}

impl Outputs {
    /// Every file with its header: fractions `(ny, nx)`, centroids `(ny, nx, 2)`, vertical
    /// faces `(ny, nx + 1)`, horizontal faces `(ny + 1, nx)`.
    fn create(paths: &OutputPaths, nx: usize, ny: usize) -> Result<Self, CliError> {
        let open = |p: &Option<PathBuf>, shape: &[usize]| {
            p.as_deref().map(|p| npy_file(p, shape)).transpose()
        };
        Ok(Self {
            fractions: npy_file(&paths.fractions, &[ny, nx])?,
            centroids: open(&paths.centroids, &[ny, nx, 2])?,
            x_apertures: open(&paths.x_apertures, &[ny, nx + 1])?,
            y_apertures: open(&paths.y_apertures, &[ny + 1, nx])?,
            bytes: Vec::new(),
        })
    }

    /// Appends a band of a grid of `ny` rows. A band holds the horizontal faces of its bottom
    /// and top lines; the top line is the next band's bottom one, so it is written by the
    /// last band only.
    fn write(&mut self, band: &Coverage, ny: usize) -> Result<(), CliError> {
        let bytes = &mut self.bytes;
        put(&mut self.fractions, bytes, &band.fractions)?;
        if let (Some(out), Some(c)) = (&mut self.centroids, &band.centroids) {
            put(out, bytes, c.as_flattened())?;
        }
        if let (Some(out), Some(x)) = (&mut self.x_apertures, &band.x_apertures) {
            put(out, bytes, x)?;
        }
        if let (Some(out), Some(y)) = (&mut self.y_apertures, &band.y_apertures) {
            let lines = if band.rows.end == ny {
                band.ny() + 1
            } else {
                band.ny()
            };
            put(out, bytes, &y[..lines * band.nx])?;
        }
        Ok(())
    }

    /// Moves every file into place.
    fn finish(self) -> Result<(), CliError> {
        self.fractions.finish()?;
        for out in [self.centroids, self.x_apertures, self.y_apertures]
            .into_iter()
            .flatten()
        {
            out.finish()?;
        }
        Ok(())
    }
}

/// Writes `values` as little-endian float64 through the buffer `bytes`.
fn put(out: &mut Output, bytes: &mut Vec<u8>, values: &[f64]) -> Result<(), CliError> {
    bytes.clear();
    bytes.extend(values.iter().flat_map(|v| v.to_le_bytes()));
    out.write_bytes(bytes)
}

/// Computes the coverage of `cover`'s grid with `options` and writes it to `paths`: the
/// library's bands ([`GridCoverage::bands`], of [`GridCoverage::band_rows`] rows), computed on
/// all cores a few ahead of the one written, so memory holds a few bands whatever the grid. A
/// failure (the library's, or a write's) stops the run and removes every file.
pub(super) fn write_coverage(
    cover: &GridCoverage,
    options: CoverageOptions,
    paths: &OutputPaths,
    domain_error: impl Fn(CoverageError) -> CliError,
) -> Result<(), CliError> {
    let (nx, ny) = (cover.grid().nx(), cover.grid().ny());
    let mut outputs = Outputs::create(paths, nx, ny)?;
    let mut progress = Progress::cells(nx as u64 * ny as u64);
    cover.bands(cover.band_rows(options), options, |bands| {
        for (rows, band) in bands {
            outputs.write(&band.map_err(&domain_error)?, ny)?;
            progress.update(rows.end as u64 * nx as u64);
        }
        Ok::<(), CliError>(())
    })?;
    progress.finish();
    outputs.finish()
}
