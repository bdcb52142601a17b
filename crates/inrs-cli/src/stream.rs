//! Streaming a points file through a batch function.

use std::path::Path;

use inrs::{Point, PointRecord, PointsError};

use crate::cli::error::CliError;
use crate::cli::output::Output;

/// Points per batch when streaming a points file: large enough for the parallel locator,
/// small enough that memory does not depend on the file's length.
const BATCH: usize = 1 << 16;

/// Streams the points file through `values` in batches and writes `x,y,value` rows (the
/// coordinates echoed as written) under `header`.
pub(crate) fn stream_points<T: std::fmt::Display>(
    points: &Path,
    output: Option<&Path>,
    header: &str,
    mut values: impl FnMut(&[Point]) -> Vec<T>,
) -> Result<(), CliError> {
    let in_file = |e: PointsError| match e {
        PointsError::Io { .. } => CliError::Message(e.to_string()),
        other => CliError::Message(format!("{}: {other}", points.display())),
    };
    let mut reader = inrs::open_points(points).map_err(in_file)?;
    let mut out = Output::create(output)?;
    writeln!(out, "{header}")?;
    let mut records: Vec<PointRecord> = Vec::with_capacity(BATCH);
    let mut pts = Vec::with_capacity(BATCH);
    loop {
        records.clear();
        for r in reader.by_ref().take(BATCH) {
            records.push(r.map_err(in_file)?);
        }
        if records.is_empty() {
            break;
        }
        pts.clear();
        pts.extend(records.iter().map(|r| r.point));
        for (r, v) in records.iter().zip(values(&pts)) {
            writeln!(out, "{},{},{}", r.x_text, r.y_text, v)?;
        }
        if records.len() < BATCH {
            break;
        }
    }
    out.finish()
}
