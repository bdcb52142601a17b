//! Points files as sources of chunks: read in order by a reading thread, or cut by position
//! and read by the workers themselves.

use std::path::Path;

use inrs::{CsvBlocks, Point, PointsError};

use super::spares::Spares;
use crate::cli::error::CliError;

/// Bytes per CSV block (one parallel task).
const CSV_BLOCK_BYTES: usize = 1 << 18;
/// Points per parallel task for `.npy` input.
const NPY_TASK_POINTS: usize = 1 << 16;

/// A points file: CSV (any other name) or `.npy` (float64 or float32, shape `(N, 2)`).
pub(crate) struct PointsInput {
    pub(super) source: Source,
    pub(super) path: String,
    pub(super) total_bytes: u64,
}

pub(super) enum Source {
    /// Read in order by a reading thread.
    InOrder(Sequential),
    /// Cut by position, each chunk read by the worker that takes it.
    #[cfg(unix)]
    ByPosition(Positional),
}

/// A file read in order: a pipe, a CSV file that opens with a block of comments, or any
/// file where reading by position is not available.
pub(super) enum Sequential {
    Csv(CsvBlocks<std::fs::File>),
    Npy(inrs::NpyPoints<std::io::BufReader<std::fs::File>>),
}

/// A regular file read by position (see [`inrs::CsvPointsFile`], [`inrs::NpyPointsFile`]).
#[cfg(unix)]
pub(super) enum Positional {
    Csv(inrs::CsvPointsFile),
    Npy(inrs::NpyPointsFile),
}

/// One unit of parallel work read in order: a block of CSV lines, or points from `.npy`.
pub(super) enum Chunk {
    Csv(inrs::CsvBlock),
    Points(Vec<Point>),
}

impl PointsInput {
    /// Opens `path`, by its extension.
    pub(crate) fn open(path: &Path) -> Result<Self, CliError> {
        let source = if has_extension(path, "npy") {
            open_npy(path)?
        } else {
            open_csv(path)?
        };
        Ok(Self {
            source,
            path: path.display().to_string(),
            total_bytes: std::fs::metadata(path).map_or(0, |m| m.len()),
        })
    }

    /// The number of points, exact for `.npy`, estimated from the size for CSV (at least 16
    /// bytes a line).
    pub(crate) fn estimated_points(&self) -> usize {
        match &self.source {
            Source::InOrder(Sequential::Npy(r)) => r.len(),
            #[cfg(unix)]
            Source::ByPosition(Positional::Npy(f)) => f.len(),
            _ => (self.total_bytes / 16) as usize,
        }
    }
}

impl Sequential {
    /// The next chunk (`None` at the end); CSV is read into a buffer from `spares`.
    pub(super) fn next_chunk(&mut self, spares: &Spares) -> Result<Option<Chunk>, PointsError> {
        match self {
            Self::Csv(blocks) => {
                blocks.recycle(spares.take());
                blocks.next_block().map(|b| b.map(Chunk::Csv))
            }
            Self::Npy(reader) => {
                let mut pts = Vec::new();
                reader
                    .read_block(NPY_TASK_POINTS, &mut pts)
                    .map(|n| (n > 0).then_some(Chunk::Points(pts)))
            }
        }
    }

    /// Bytes read so far.
    pub(super) fn bytes_read(&self) -> u64 {
        match self {
            Self::Csv(r) => r.bytes_read(),
            Self::Npy(r) => r.bytes_read(),
        }
    }
}

#[cfg(unix)]
impl Positional {
    /// The number of chunks.
    pub(super) fn chunks(&self) -> usize {
        match self {
            Self::Csv(f) => f.blocks(),
            Self::Npy(f) => f.len().div_ceil(NPY_TASK_POINTS),
        }
    }

    /// Where chunk `k` starts in the file (for progress).
    pub(super) fn offset_of(&self, k: usize) -> u64 {
        match self {
            Self::Csv(f) => f.offset_of_block(k),
            Self::Npy(f) => f.offset_of(k.saturating_mul(NPY_TASK_POINTS).min(f.len())),
        }
    }
}

/// Chunk `k` of a `.npy` file read by position: its first point and how many.
#[cfg(unix)]
pub(super) fn npy_chunk(file: &inrs::NpyPointsFile, k: usize) -> (usize, usize) {
    let first = k * NPY_TASK_POINTS;
    (first, NPY_TASK_POINTS.min(file.len().saturating_sub(first)))
}

/// A CSV points file: read by position if it is a regular file with data in its first block
/// (Unix), else in order.
fn open_csv(path: &Path) -> Result<Source, CliError> {
    #[cfg(unix)]
    if let Some(file) =
        inrs::CsvPointsFile::open(path, CSV_BLOCK_BYTES).map_err(|e| input_error(path, e))?
    {
        return Ok(Source::ByPosition(Positional::Csv(file)));
    }
    Ok(Source::InOrder(Sequential::Csv(
        inrs::open_points_blocks(path, CSV_BLOCK_BYTES).map_err(|e| input_error(path, e))?,
    )))
}

/// A `.npy` points file: read by position if it is a regular file (Unix), else in order (a
/// named pipe cannot be read by position).
fn open_npy(path: &Path) -> Result<Source, CliError> {
    #[cfg(unix)]
    if std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
        let file = inrs::NpyPointsFile::open(path).map_err(|e| input_error(path, e))?;
        return Ok(Source::ByPosition(Positional::Npy(file)));
    }
    Ok(Source::InOrder(Sequential::Npy(
        inrs::open_npy_points(path).map_err(|e| input_error(path, e))?,
    )))
}

pub(super) fn has_extension(path: &Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// The message for a points-file error, naming the file once.
pub(super) fn input_error(path: &Path, e: PointsError) -> CliError {
    match e {
        PointsError::Io { .. } | PointsError::Npy { .. } => CliError::Message(e.to_string()),
        other => CliError::Message(format!("{}: {other}", path.display())),
    }
}
