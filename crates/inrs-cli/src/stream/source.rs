//! The points file a command streams, as a chunk source of `rs-io` (`inrs::io::points`): cut
//! by position and read by the workers themselves (a regular file), or read in order by a
//! reading thread (pipes, and CSV files that open with a block of comments).

use std::path::Path;

use inrs::PointsError;
use inrs::io::points::{ChunkSizes, ChunkSource, open_chunks};

use crate::cli::error::CliError;

/// A points file: CSV (any other name) or `.npy` (float64 or float32, shape `(N, 2)`).
pub(crate) struct PointsInput {
    pub(super) source: Box<dyn ChunkSource>,
    pub(super) path: String,
    pub(super) total_bytes: u64,
}

impl PointsInput {
    /// Opens `path`, by its extension, in chunks of the default sizes (CSV: 256 KiB; `.npy`:
    /// 65 536 points, read 4 096 at a time).
    pub(crate) fn open(path: &Path) -> Result<Self, CliError> {
        let source = open_chunks(path, ChunkSizes::default()).map_err(|e| input_error(path, e))?;
        Ok(Self {
            source,
            path: path.display().to_string(),
            total_bytes: std::fs::metadata(path).map_or(0, |m| m.len()),
        })
    }

    /// The number of points, exact for `.npy`, estimated from the size for CSV (at least 16
    /// bytes a line).
    pub(crate) fn estimated_points(&self) -> usize {
        self.source
            .points()
            .unwrap_or((self.total_bytes / 16) as usize)
    }
}

/// The message for a points-file error, naming the file once.
pub(crate) fn input_error(path: &Path, e: PointsError) -> CliError {
    match e {
        PointsError::Io { .. } | PointsError::Npy { .. } => CliError::Message(e.to_string()),
        other => CliError::Message(format!("{}: {other}", path.display())),
    }
}
