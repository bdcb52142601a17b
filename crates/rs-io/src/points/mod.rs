//! Points files: the CSV text and the `NumPy` `.npy` arrays the `inrs` tools read points from,
//! streamed in bounded memory whatever their length.
//!
//! - The CSV format ([`PointReader`] describes it): read record by record ([`PointReader`],
//!   [`parse_points`], [`read_points`]), or in blocks of whole lines parsed on any thread
//!   ([`CsvBlocks`], read in order; [`CsvPointsFile`], read by position). One grammar serves
//!   them all: one line splitter, one parser of a line and one finder of the first data line
//!   (after the byte-order mark, comments and header).
//! - `.npy` arrays of shape `(N, 2)`, float64 or float32: read in order ([`NpyPoints`]) or by
//!   position ([`NpyPointsFile`]), the points handed over as stored ([`EncodedPoints`]); and the
//!   header of the arrays results are written as ([`npy_header`]).
//! - Either format as numbered chunks for parallel work ([`ChunkSource`]): read in order by one
//!   thread at a time ([`Sequential`]) or by position by any number at once ([`Positional`],
//!   Unix); [`open_chunks`] chooses.
//!
//! # Examples
//!
//! ```
//! use rs_io::points::{PointReader, parse_points};
//! let pts = parse_points("x,y\n# a comment\n0.5, 1\n2 3e-1\n").unwrap();
//! assert_eq!(pts.len(), 2);
//! assert_eq!(pts[1].y_text, "3e-1");
//! let mut r = PointReader::new("1,2\n3;4\n".as_bytes());
//! assert!(r.next().unwrap().is_ok());
//! assert_eq!(
//!     r.next().unwrap().unwrap_err().to_string(),
//!     "line 2: expected at least two numbers \"x,y\", got \"3;4\""
//! );
//! ```

mod csv;
mod grammar;
mod npy;
mod source;

use std::path::Path;

use rs_spline::Point;
use thiserror::Error;

#[cfg(unix)]
pub use csv::CsvPointsFile;
pub use csv::{CsvBlock, CsvBlocks, ParsedBlock, PointReader};
#[cfg(unix)]
pub use npy::NpyPointsFile;
pub use npy::{EncodedPoints, MAX_NPY_POINTS, NPY_HEADER_BYTES, NpyPoints, NpyType, npy_header};
#[cfg(unix)]
pub use source::Positional;
pub use source::{
    Chunk, ChunkPoints, ChunkScratch, ChunkSizes, ChunkSource, Sequential, open_chunks,
};

/// The longest line a points file may have, in bytes, without its end (`\n` or `\r\n`): a
/// file without line breaks is an error, not an unbounded allocation.
pub const MAX_LINE_BYTES: usize = 64 * 1024;

/// A parsed point with the text it was written as (echoed unchanged in outputs).
#[derive(Clone, Debug, PartialEq)]
pub struct PointRecord {
    /// The point.
    pub point: Point,
    /// The abscissa as written.
    pub x_text: String,
    /// The ordinate as written.
    pub y_text: String,
}

/// A bad points file.
#[derive(Debug, Error)]
pub enum PointsError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The underlying error.
        source: std::io::Error,
    },
    /// A `.npy` points file is not an array of shape `(N, 2)` of floats, or is cut short.
    #[error("{path}: {message}")]
    Npy {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// A line is not a point.
    #[error("line {line}: {message}")]
    Line {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
}

/// Parses a whole points text (see [`PointReader`] for the format).
///
/// # Errors
/// [`PointsError::Line`] with the line number of the first bad line.
///
/// # Examples
///
/// ```
/// let pts = rs_io::points::parse_points("x,y\n# a comment\n0.5, 1\n2 3e-1\n").unwrap();
/// assert_eq!(pts.len(), 2);
/// assert_eq!(pts[1].point, rs_spline::Point::new(2.0, 0.3));
/// assert_eq!(pts[1].y_text, "3e-1");
/// let e = rs_io::points::parse_points("1,2\n3;4\n").unwrap_err();
/// assert!(e.to_string().starts_with("line 2:"));
/// ```
pub fn parse_points(text: &str) -> Result<Vec<PointRecord>, PointsError> {
    PointReader::new(text.as_bytes()).collect()
}

/// Opens a points file for streaming, record by record.
///
/// # Errors
/// [`PointsError::Io`] if it cannot be opened.
pub fn open_points(path: impl AsRef<Path>) -> Result<PointReader<std::fs::File>, PointsError> {
    let path = path.as_ref();
    Ok(PointReader::named(
        open_file(path)?,
        path.display().to_string(),
    ))
}

/// Reads and parses a whole points file into memory (use [`open_points`] to stream).
///
/// # Errors
/// [`PointsError::Io`] or as [`parse_points`].
pub fn read_points(path: impl AsRef<Path>) -> Result<Vec<PointRecord>, PointsError> {
    open_points(path)?.collect()
}

/// Opens a points file for block-wise parsing (see [`CsvBlocks`]).
///
/// # Errors
/// [`PointsError::Io`] if it cannot be opened.
pub fn open_points_blocks(
    path: impl AsRef<Path>,
    block_bytes: usize,
) -> Result<CsvBlocks<std::fs::File>, PointsError> {
    let path = path.as_ref();
    Ok(CsvBlocks::new(
        open_file(path)?,
        path.display().to_string(),
        block_bytes,
    ))
}

/// Opens a `.npy` points file to read in order (see [`NpyPoints`]).
///
/// # Errors
/// As [`NpyPoints::new`], and [`PointsError::Io`] if it cannot be opened.
pub fn open_npy_points(
    path: impl AsRef<Path>,
) -> Result<NpyPoints<std::io::BufReader<std::fs::File>>, PointsError> {
    let path = path.as_ref();
    NpyPoints::new(
        std::io::BufReader::with_capacity(1 << 20, open_file(path)?),
        path.display().to_string(),
    )
}

/// Opens the points file `path` ([`PointsError::Io`] naming it if it cannot be opened).
fn open_file(path: &Path) -> Result<std::fs::File, PointsError> {
    std::fs::File::open(path).map_err(|source| PointsError::Io {
        path: path.display().to_string(),
        source,
    })
}
