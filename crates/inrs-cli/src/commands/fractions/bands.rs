//! The coverage of a grid computed band by band on all cores and written in order into
//! `.npy` files whose headers carry the whole grid's shape: memory holds a few bands, whatever
//! the grid.

use std::ops::Range;
use std::path::{Path, PathBuf};

use inrs::NpyType;
use inrs::coverage::{Coverage, CoverageError, CoverageOptions, GridCoverage};
use rayon::prelude::*;

use crate::cli::error::CliError;
use crate::cli::output::Output;
use crate::stream::Progress;

/// Output bytes per band (2^20 cells of fractions alone): a band is the unit of work and of
/// writing; with centroids and apertures the bands have fewer cells.
const BAND_BYTES: usize = 8 << 20;

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

/// Output bytes per cell: 8 for the fraction, 16 for the centroid, about 16 for the faces.
fn bytes_per_cell(options: CoverageOptions) -> usize {
    8 + if options.centroids { 16 } else { 0 } + if options.apertures { 16 } else { 0 }
}

/// The rows of each band: about `band_cells` cells (at least one row), and at least two
/// bands per thread when the grid has the rows for it, so that small grids use every core.
fn band_rows(band_cells: usize, nx: usize, ny: usize, threads: usize) -> usize {
    let by_size = (band_cells / nx.max(1)).max(1);
    let by_threads = ny.div_ceil(2 * threads.max(1)).max(1);
    by_size.min(by_threads)
}

/// Computes the coverage of `cover`'s grid with `options` and writes it to `paths`.
///
/// The bands go in groups of two per thread: while one group is written in order (by one
/// thread), the next is computed on the others (`rayon::join`), so that at most two groups
/// are held: `4 x threads x 8 MiB` of output in memory. A failure (the library's, or a write's) stops the run and removes every file.
pub(super) fn write_coverage(
    cover: &GridCoverage,
    options: CoverageOptions,
    paths: &OutputPaths,
    domain_error: impl Fn(CoverageError) -> CliError + Sync,
) -> Result<(), CliError> {
    let (nx, ny) = (cover.grid().nx(), cover.grid().ny());
    let threads = rayon::current_num_threads();
    let rows = band_rows(BAND_BYTES / bytes_per_cell(options), nx, ny, threads);
    let bands: Vec<Range<usize>> = (0..ny)
        .step_by(rows)
        .map(|j| j..(j + rows).min(ny))
        .collect();
    let group = 2 * threads.max(1);
    let compute = |g: usize| -> Vec<Result<Coverage, CoverageError>> {
        let start = (g * group).min(bands.len());
        let end = (start + group).min(bands.len());
        bands[start..end]
            .par_iter()
            .map(|r| cover.rows(r.clone(), options))
            .collect()
    };
    let mut outputs = Outputs::create(paths, nx, ny)?;
    let mut progress = Progress::cells(nx as u64 * ny as u64);
    let mut done = 0u64;
    let mut write_group = |computed: Vec<Result<Coverage, CoverageError>>| {
        for band in computed {
            let band = band.map_err(&domain_error)?;
            outputs.write(&band, ny)?;
            done += (band.ny() * band.nx) as u64;
            progress.update(done);
        }
        Ok::<(), CliError>(())
    };
    let mut computed = compute(0);
    for g in 1..=bands.len().div_ceil(group) {
        let (written, next) = rayon::join(|| write_group(computed), || compute(g));
        written?;
        computed = next;
    }
    progress.finish();
    outputs.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_hold_about_a_million_cells_and_feed_every_thread() {
        let fractions = BAND_BYTES / bytes_per_cell(CoverageOptions::DEFAULT);
        assert_eq!(fractions, 1 << 20);
        let all = CoverageOptions::DEFAULT
            .with_centroids(true)
            .with_apertures(true);
        assert_eq!(BAND_BYTES / bytes_per_cell(all), (1 << 20) / 5);
        // Large grids: 2^20 cells a band.
        assert_eq!(band_rows(fractions, 4096, 4096, 2), 256);
        assert_eq!(band_rows(fractions, 1000, 100_000, 8), 1048);
        // Rows longer than a band: one row at a time.
        assert_eq!(band_rows(fractions, 1 << 22, 100, 2), 1);
        // Small grids: two bands per thread.
        assert_eq!(band_rows(fractions, 64, 64, 2), 16);
        assert_eq!(band_rows(fractions, 1024, 1024, 4), 128);
        assert_eq!(band_rows(fractions, 10, 3, 8), 1);
    }
}
