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

/// Values a run may hold (points times columns) before its points are cut down, to at most
/// [`MIN_RUN_POINTS`]: with many columns (many domains) a run's rows are that much longer.
const RUN_VALUES: usize = 1 << 21;

/// The fewest points a run is cut down to however many columns: every query then answers
/// thousands of points at a time, while its index is in the cache (runs of a hundred points
/// made 73 faces of a part three times slower than the whole batch per face).
const MIN_RUN_POINTS: usize = 1 << 12;

/// Bytes of CSV a point is taken to take when runs are sized by points: a line of two
/// coordinates in full precision.
const CSV_LINE_BYTES: usize = 40;

impl PointsInput {
    /// Opens `path`, by its extension, in runs for `columns` values a point: for one, runs of
    /// the default sizes (256 KiB of CSV, 16 384 `.npy` points); for more, runs of as many
    /// points (as many lines of [`CSV_LINE_BYTES`]), which every query answers in turn while
    /// its index is cached, fewer beyond [`RUN_VALUES`] values a run (down to
    /// [`MIN_RUN_POINTS`]). (73 faces of a part, 10^6 points: CSV runs of 256 KiB took 1.2
    /// times as long as runs of 16 384 lines, which were as fast as all the points at once.)
    pub(crate) fn open(path: &Path, columns: usize) -> Result<Self, CliError> {
        let full = RunSizes::default();
        let sizes = if columns <= 1 {
            full
        } else {
            let points = (RUN_VALUES / columns).clamp(MIN_RUN_POINTS, full.npy_points);
            RunSizes {
                csv_bytes: points * CSV_LINE_BYTES,
                npy_points: points,
            }
        };
        let reader = open_points(path, sizes).map_err(|e| input_error(path, e))?;
        Ok(Self {
            reader,
            path: path.display().to_string(),
            total_bytes: std::fs::metadata(path).map_or(0, |m| m.len()),
        })
    }

    /// [`PointsInput::open`] for a command that prepares what it computes while the points
    /// are read ([`super::stream_prepared`]): if the file cannot be opened, `named_first`
    /// (reading the domain, say) runs first and its error wins, as it did when the preparation
    /// came before the points.
    pub(crate) fn open_after_errors_of(
        path: &Path,
        columns: usize,
        named_first: impl FnOnce() -> Result<(), CliError>,
    ) -> Result<Self, CliError> {
        Self::open(path, columns).or_else(|e| named_first().and(Err(e)))
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
