//! Points files: the CSV text and the `NumPy` `.npy` arrays the `inrs` tools read points from,
//! streamed in bounded memory whatever their length.
//!
//! One reader per format, behind one trait ([`PointsReader`]): [`CsvReader`] (the CSV format
//! and its one grammar: one line splitter, one parser of a line and one finder of the first
//! data line, after the byte-order mark, comments and header) and [`NpyReader`] (arrays of
//! shape `(N, 2)`, float64 or float32). Each hands the file out as numbered runs of points
//! ([`PointRun`]: the points, and for CSV the text they were written as) to any number of
//! threads at once: a regular file is read by position (Unix), any other input in order, one
//! run at a time, each run parsed on the thread that took it. [`open_points`] chooses the
//! reader by the file's name.
//!
//! Also: a whole CSV text or file as records ([`parse_points`], [`read_points`]), and the
//! header of the `.npy` arrays results are written as ([`npy_header`]).
//!
//! # Examples
//!
//! ```
//! use rs_io::points::parse_points;
//! let pts = parse_points("x,y\n# a comment\n0.5, 1\n2 3e-1\n").unwrap();
//! assert_eq!(pts.len(), 2);
//! assert_eq!(pts[1].y_text, "3e-1");
//! assert_eq!(
//!     parse_points("1,2\n3;4\n").unwrap_err().to_string(),
//!     "line 2: expected at least two numbers \"x,y\", got \"3;4\""
//! );
//! ```

mod csv;
mod encoded;
mod grammar;
mod npy;
mod run;
mod xyz;

use std::path::Path;

use rs_spline::Point;
use thiserror::Error;

pub use csv::CsvReader;
pub use encoded::{EncodedPoints, NpyType};
pub use npy::{MAX_NPY_POINTS, NPY_HEADER_BYTES, NpyReader, npy_header, read_npy_vector};
pub use run::{CsvPoints, PointRun, PointsReader, ReadProgress, RunPoints, RunSizes};
pub use xyz::{XyzReader, XyzRun};

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

/// Opens the points file `path` in runs of `sizes`: `.npy` ([`NpyReader::open`]) if its name
/// ends so, CSV ([`CsvReader::open`]) otherwise.
///
/// # Errors
/// [`PointsError::Io`] if it cannot be opened; for `.npy`, a bad header; for CSV, a first line
/// too long.
pub fn open_points(
    path: impl AsRef<Path>,
    sizes: RunSizes,
) -> Result<Box<dyn PointsReader>, PointsError> {
    let path = path.as_ref();
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"))
    {
        Ok(Box::new(NpyReader::open(path, sizes)?))
    } else {
        Ok(Box::new(CsvReader::open(path, sizes)?))
    }
}

/// Parses a whole points text (the format of [`CsvReader`]).
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
    records(&CsvReader::new(
        text.as_bytes(),
        "input",
        RunSizes::default(),
    ))
}

/// Reads and parses a whole CSV points file into memory (to stream one, read its runs:
/// [`CsvReader::open`]).
///
/// # Errors
/// [`PointsError::Io`] or as [`parse_points`].
pub fn read_points(path: impl AsRef<Path>) -> Result<Vec<PointRecord>, PointsError> {
    records(&CsvReader::open(path, RunSizes::default())?)
}

/// The first three fields of a CSV points file's header (its first line that is neither blank
/// nor a `#` comment, when that line's first field is not a number; fields as the points'
/// grammar splits them), `None` without one. Reads only as
/// far as that line (at most [`MAX_LINE_BYTES`] a line).
///
/// ```
/// # let dir = std::env::temp_dir().join(format!("rs-io-header-{}", std::process::id()));
/// # std::fs::create_dir_all(&dir).unwrap();
/// let p = dir.join("p.csv");
/// std::fs::write(&p, "# points\nx,y,z\n1,2,3\n").unwrap();
/// assert_eq!(rs_io::points::csv_header(&p).unwrap().unwrap(), ["x", "y", "z"]);
/// std::fs::write(&p, "1,2\n").unwrap();
/// assert!(rs_io::points::csv_header(&p).unwrap().is_none());
/// ```
///
/// # Errors
/// [`PointsError::Io`].
pub fn csv_header(path: impl AsRef<Path>) -> Result<Option<Vec<String>>, PointsError> {
    use std::io::{BufRead, Read};
    let path = path.as_ref();
    let io = |source| PointsError::Io {
        path: path.display().to_string(),
        source,
    };
    let mut lines = std::io::BufReader::new(std::fs::File::open(path).map_err(io)?);
    let mut bytes = Vec::new();
    loop {
        bytes.clear();
        let n = (&mut lines)
            .take(MAX_LINE_BYTES as u64 + 2)
            .read_until(b'\n', &mut bytes)
            .map_err(io)?;
        if n == 0 {
            return Ok(None);
        }
        // A line that is not text is for the points reader to report.
        let Ok(line) = std::str::from_utf8(&bytes) else {
            return Ok(None);
        };
        let Some(text) = grammar::content(line.trim_start_matches('\u{feff}')) else {
            continue;
        };
        let (fields, count) = grammar::first_fields::<3>(text);
        let numeric = count > 0 && grammar::parse_number(fields[0]).is_some();
        return Ok((!numeric).then(|| fields[..count].iter().map(|f| f.to_string()).collect()));
    }
}

/// Every point of a CSV reader's runs, with its text.
fn records(reader: &dyn PointsReader) -> Result<Vec<PointRecord>, PointsError> {
    let (mut run, mut all) = (PointRun::default(), Vec::new());
    while let Some((_, read)) = reader.next_run(&mut run) {
        read?;
        if let RunPoints::Csv(points) = run.points() {
            all.extend((0..points.points.len()).map(|i| points.record(i)));
        }
    }
    Ok(all)
}

/// Opens the points file `path` ([`PointsError::Io`] naming it if it cannot be opened).
fn open_file(path: &Path) -> Result<std::fs::File, PointsError> {
    std::fs::File::open(path).map_err(|source| PointsError::Io {
        path: path.display().to_string(),
        source,
    })
}
