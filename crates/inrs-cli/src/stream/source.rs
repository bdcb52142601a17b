//! The points file a command streams, as a reader of `rs-io` (`inrs::io::points`): its runs
//! read by position by the workers themselves (a regular file), or in order, one at a time
//! (pipes, and CSV files that open with a run's worth of comments).

use std::path::Path;

use inrs::{PointsError, PointsReader, RunSizes, open_points};

use crate::cli::error::CliError;

/// A points file: CSV (any other name) or `.npy` (float64 or float32, shape `(N, 2)`).
pub(crate) struct PointsInput {
    pub(super) reader: Box<dyn PointsReader>,
    pub(super) path: String,
    pub(super) total_bytes: u64,
}

/// The fewest bytes of CSV and points of `.npy` in a run however many columns it is
/// computed for.
const MIN_RUN: RunSizes = RunSizes {
    csv_bytes: 1 << 12,
    npy_points: 1 << 8,
};

impl PointsInput {
    /// Opens `path`, by its extension, in runs for `columns` values a point: with one, runs of
    /// the default sizes (256 KiB of CSV, 16 384 `.npy` points); with more, runs as many times
    /// shorter (down to [`MIN_RUN`]), so that a run's values and rows stay about as large.
    pub(crate) fn open(path: &Path, columns: usize) -> Result<Self, CliError> {
        let columns = columns.max(1);
        let full = RunSizes::default();
        let sizes = RunSizes {
            csv_bytes: (full.csv_bytes / columns).max(MIN_RUN.csv_bytes),
            npy_points: (full.npy_points / columns).max(MIN_RUN.npy_points),
        };
        let reader = open_points(path, sizes).map_err(|e| input_error(path, e))?;
        Ok(Self {
            reader,
            path: path.display().to_string(),
            total_bytes: std::fs::metadata(path).map_or(0, |m| m.len()),
        })
    }

    /// The number of points, exact for `.npy`, estimated from the size for CSV (at least 16
    /// bytes a line).
    pub(crate) fn estimated_points(&self) -> usize {
        self.reader
            .points()
            .unwrap_or((self.total_bytes / 16) as usize)
    }
}

/// The message for a points-file error, naming the file once.
pub(super) fn input_error(path: &Path, e: PointsError) -> CliError {
    match e {
        PointsError::Io { .. } | PointsError::Npy { .. } => CliError::Message(e.to_string()),
        other => CliError::Message(format!("{}: {other}", path.display())),
    }
}
