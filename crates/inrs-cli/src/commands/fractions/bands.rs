//! The coverage of a grid written band by band, in order, into `.npy` files whose headers
//! carry the whole grid's shape: memory holds a few bands, whatever the grid. Several
//! materials are written one after the other (material 0's whole grid, then material 1's,
//! ...), each band by band, under a leading axis: the files' C order.

use std::path::{Path, PathBuf};

use inrs::NpyType;
use inrs::coverage::{Coverage, CoverageArray, CoverageError, CoverageOptions, MaterialCoverage};

use crate::cli::error::CliError;
use crate::cli::output::Output;
use crate::stream::Progress;

/// The values of `array` in `band` (of a grid of `ny` rows) to append to its file, `None`
/// when the band does not hold it: a band holds the horizontal faces of its bottom and top
/// lines; the top line is the next band's bottom one, so it is written by the last band only.
fn band_values(array: CoverageArray, band: &Coverage, ny: usize) -> Option<&[f64]> {
    let values = band.values(array)?;
    if !array.on_horizontal_faces() {
        return Some(values);
    }
    let lines = band.ny() + usize::from(band.rows.end == ny);
    values.get(..lines * band.nx)
}

/// The files of a run: each array written and its file, the fractions first.
pub(super) struct OutputPaths(pub(super) Vec<(CoverageArray, PathBuf)>);

/// The open outputs, each under a temporary name until [`Outputs::finish`]; dropped (on any
/// error) they leave nothing behind.
struct Outputs {
    files: Vec<(CoverageArray, Output)>,
    /// Reused for the bytes of each array of a band (big-endian machines only).
    bytes: Vec<u8>,
}

/// Opens `path` and writes a float64 `.npy` header for `shape`.
fn npy_file(path: &Path, shape: &[usize]) -> Result<Output, CliError> {
    let mut out = Output::create(Some(path))?;
    out.write_bytes(&inrs::npy_header(NpyType::F64, shape))?;
    Ok(out)
}

impl Outputs {
    /// Every file with its header for a grid of `nx` columns and `ny` rows
    /// ([`CoverageArray::shape`]), under a leading axis of `leading` materials if given.
    fn create(
        paths: &OutputPaths,
        leading: Option<usize>,
        nx: usize,
        ny: usize,
    ) -> Result<Self, CliError> {
        let files = paths
            .0
            .iter()
            .map(|(array, path)| {
                let shape: Vec<usize> = leading.into_iter().chain(array.shape(nx, ny)).collect();
                Ok((*array, npy_file(path, &shape)?))
            })
            .collect::<Result<_, CliError>>()?;
        Ok(Self {
            files,
            bytes: Vec::new(),
        })
    }

    /// Appends a band of a grid of `ny` rows to every file.
    fn write(&mut self, band: &Coverage, ny: usize) -> Result<(), CliError> {
        for (array, out) in &mut self.files {
            let values = band_values(*array, band, ny).ok_or_else(|| {
                CliError::Message(format!(
                    "internal error: the library's band of rows {:?} has no {}",
                    band.rows,
                    array.name()
                ))
            })?;
            out.write_f64s(values, &mut self.bytes)?;
        }
        Ok(())
    }

    /// Moves every file into place.
    fn finish(self) -> Result<(), CliError> {
        for (_, out) in self.files {
            out.finish()?;
        }
        Ok(())
    }
}

/// Computes the coverage of `cover`'s grid by each of its materials with `options` and
/// writes it to `paths`, under a leading axis of `leading` materials if given (`None`: one
/// material, the grid's own shapes): material 0's whole grid, then material 1's, ..., each in
/// the library's bands ([`MaterialCoverage::bands`], of [`MaterialCoverage::stream_band_rows`]
/// rows, each handed back once written),
/// computed on all cores a few ahead of the one written, so memory holds a few bands whatever
/// the grid. A failure (the library's, named by `material_error` with its material, or a
/// write's) stops the run and removes every file.
pub(super) fn write_materials(
    cover: &MaterialCoverage,
    options: CoverageOptions,
    paths: &OutputPaths,
    leading: Option<usize>,
    material_error: impl Fn(usize, CoverageError) -> CliError,
) -> Result<(), CliError> {
    let (nx, ny) = (cover.grid().nx(), cover.grid().ny());
    let mut outputs = Outputs::create(paths, leading, nx, ny)?;
    let cells = nx as u64 * ny as u64;
    let mut progress = Progress::cells(cells.saturating_mul(cover.len() as u64));
    let band_rows = cover.stream_band_rows(options);
    for k in 0..cover.len() {
        let done = cells.saturating_mul(k as u64);
        cover.bands(k, band_rows, options, |mut bands| {
            while let Some((rows, band)) = bands.next() {
                let band = band.map_err(|e| material_error(k, e))?;
                outputs.write(&band, ny)?;
                // Its memory holds a band still to come.
                bands.recycle(band);
                progress.update(done + rows.end as u64 * nx as u64);
            }
            Ok::<(), CliError>(())
        })?;
    }
    progress.finish();
    outputs.finish()
}
