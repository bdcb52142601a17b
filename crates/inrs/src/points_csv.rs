//! The points file: `x,y` per line, read as a stream.

use std::io::BufRead;
use std::path::Path;

use rs_spline::Point;
use thiserror::Error;

/// The longest line a points file may have, in bytes (a file without line breaks is an error,
/// not an unbounded allocation).
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
    /// A line is not a point.
    #[error("line {line}: {message}")]
    Line {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
}

/// A streaming reader of a points file: one point per line, `x,y` separated by a comma or white
/// space; further columns are allowed and ignored (so the `x,y,kind` files of `inrs sample` and
/// the `x,y,location` files of `inrs classify` read back); an optional header line whose first
/// two fields are `x` and `y`; blank lines and `#` comment lines ignored; a UTF-8 byte-order
/// mark at the start (Excel's "CSV UTF-8") skipped; Windows line ends accepted. Numbers are
/// parsed exactly as written (shortest round-trip `f64`); NaN and infinities are rejected.
///
/// Memory is one line at a time (at most [`MAX_LINE_BYTES`]), whatever the file's size.
///
/// # Examples
///
/// ```
/// let text = "\u{feff}x,y,kind\n# a comment\n0.5, 1, boundary\n2 3e-1\n";
/// let pts: Vec<_> = inrs::PointReader::new(text.as_bytes()).collect::<Result<_, _>>().unwrap();
/// assert_eq!(pts.len(), 2);
/// assert_eq!(pts[1].point, inrs::Point::new(2.0, 0.3));
/// assert_eq!(pts[1].y_text, "3e-1");
/// ```
#[derive(Debug)]
pub struct PointReader<R> {
    input: R,
    line: usize,
    seen_data: bool,
    buf: Vec<u8>,
    failed: bool,
    path: String,
}

impl<R: BufRead> PointReader<R> {
    /// Reads points from `input`.
    pub fn new(input: R) -> Self {
        Self::named(input, "input")
    }

    /// Reads points from `input`, naming it `path` in I/O errors.
    pub fn named(input: R, path: impl Into<String>) -> Self {
        Self {
            input,
            line: 0,
            seen_data: false,
            buf: Vec::new(),
            failed: false,
            path: path.into(),
        }
    }

    /// Reads the next line into `buf` (without its end), at most [`MAX_LINE_BYTES`] bytes.
    /// `Ok(false)` at the end of the input.
    fn next_line(&mut self) -> Result<bool, PointsError> {
        self.buf.clear();
        let limit = (MAX_LINE_BYTES + 2) as u64;
        let input: &mut R = &mut self.input;
        let read = std::io::Read::take(input, limit).read_until(b'\n', &mut self.buf);
        let n = read.map_err(|source| PointsError::Io {
            path: self.path.clone(),
            source,
        })?;
        if n == 0 {
            return Ok(false);
        }
        self.line += 1;
        if self.buf.last() == Some(&b'\n') {
            self.buf.pop();
        } else if n as u64 == limit {
            return Err(PointsError::Line {
                line: self.line,
                message: format!("line longer than {MAX_LINE_BYTES} bytes"),
            });
        }
        if self.buf.last() == Some(&b'\r') {
            self.buf.pop();
        }
        Ok(true)
    }

    fn parse_line(&mut self) -> Result<Option<PointRecord>, PointsError> {
        let line_no = self.line;
        let err = |message: String| PointsError::Line {
            line: line_no,
            message,
        };
        let mut text = std::str::from_utf8(&self.buf)
            .map_err(|e| err(format!("not UTF-8 text (byte {})", e.valid_up_to() + 1)))?;
        if line_no == 1 {
            text = text.strip_prefix('\u{feff}').unwrap_or(text);
        }
        let line = text.trim();
        if line.is_empty() || line.starts_with('#') {
            return Ok(None);
        }
        let (fields, count) = first_two_fields(line);
        if !self.seen_data
            && count >= 2
            && fields[0].eq_ignore_ascii_case("x")
            && fields[1].eq_ignore_ascii_case("y")
        {
            self.seen_data = true;
            return Ok(None);
        }
        self.seen_data = true;
        if count < 2 {
            return Err(err(format!(
                "expected at least two numbers \"x,y\", got {:?}",
                shorten(line)
            )));
        }
        let num = |s: &str| -> Result<f64, PointsError> {
            match s.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                Ok(_) => Err(err(format!("{:?} is not a finite number", shorten(s)))),
                Err(_) => Err(err(format!("{:?} is not a number", shorten(s)))),
            }
        };
        let (x, y) = (num(fields[0])?, num(fields[1])?);
        Ok(Some(PointRecord {
            point: Point::new(x, y),
            x_text: fields[0].to_string(),
            y_text: fields[1].to_string(),
        }))
    }
}

/// The first two fields of a line (comma-separated if it has a comma, else white-space
/// separated) and how many fields it has (counting stops at 2).
fn first_two_fields(line: &str) -> ([&str; 2], usize) {
    fn two<'a>(mut it: impl Iterator<Item = &'a str>) -> ([&'a str; 2], usize) {
        match (it.next(), it.next()) {
            (Some(a), Some(b)) => ([a, b], 2),
            (Some(a), None) => ([a, ""], 1),
            _ => (["", ""], 0),
        }
    }
    if line.contains(',') {
        two(line.split(',').map(str::trim))
    } else {
        two(line.split_whitespace())
    }
}

/// At most 60 characters of `s`, for error messages.
fn shorten(s: &str) -> String {
    if s.chars().count() <= 60 {
        s.to_string()
    } else {
        s.chars().take(57).collect::<String>() + "..."
    }
}

impl<R: BufRead> Iterator for PointReader<R> {
    type Item = Result<PointRecord, PointsError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        loop {
            let step = self.next_line().and_then(|more| {
                if more {
                    self.parse_line().map(Some)
                } else {
                    Ok(None)
                }
            });
            match step {
                Ok(Some(Some(record))) => return Some(Ok(record)),
                Ok(Some(None)) => continue,
                Ok(None) => return None,
                Err(e) => {
                    self.failed = true;
                    return Some(Err(e));
                }
            }
        }
    }
}

/// Parses a whole points text (see [`PointReader`] for the format).
///
/// # Errors
/// [`PointsError::Line`] with the line number of the first bad line.
///
/// # Examples
///
/// ```
/// let pts = inrs::parse_points("x,y\n# a comment\n0.5, 1\n2 3e-1\n").unwrap();
/// assert_eq!(pts.len(), 2);
/// assert_eq!(pts[1].point, inrs::Point::new(2.0, 0.3));
/// assert_eq!(pts[1].y_text, "3e-1");
/// assert!(inrs::parse_points("1,2\n3;4\n").unwrap_err().to_string().starts_with("line 2:"));
/// ```
pub fn parse_points(text: &str) -> Result<Vec<PointRecord>, PointsError> {
    PointReader::new(text.as_bytes()).collect()
}

/// Opens a points file for streaming.
///
/// # Errors
/// [`PointsError::Io`] if it cannot be opened.
pub fn open_points(
    path: impl AsRef<Path>,
) -> Result<PointReader<std::io::BufReader<std::fs::File>>, PointsError> {
    let path = path.as_ref();
    let file = std::fs::File::open(path).map_err(|source| PointsError::Io {
        path: path.display().to_string(),
        source,
    })?;
    Ok(PointReader::named(
        std::io::BufReader::with_capacity(1 << 16, file),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_the_tool_writes_read_back() {
        let sample = "x,y,kind\n0.5,0.25,boundary\n1,2,interior\n";
        let pts = parse_points(sample).unwrap();
        assert_eq!(pts.len(), 2);
        let classified = "x,y,location\r\n0.5,0.25,inside\r\n";
        assert_eq!(parse_points(classified).unwrap()[0].x_text, "0.5");
    }

    #[test]
    fn a_byte_order_mark_is_skipped_only_at_the_start() {
        assert_eq!(parse_points("\u{feff}1,2\n").unwrap().len(), 1);
        assert_eq!(parse_points("\u{feff}x,y\n1,2\n").unwrap().len(), 1);
        assert!(parse_points("1,2\n\u{feff}3,4\n").is_err());
    }

    #[test]
    fn bad_lines_are_errors_with_their_number() {
        for (text, line) in [
            ("1,2\n3\n", 2),
            ("1,nan\n", 1),
            ("1,2\n\n# c\n1e999,0\n", 4),
            ("\u{0}\u{ff}", 1),
        ] {
            let e = parse_points(text).unwrap_err().to_string();
            assert!(e.starts_with(&format!("line {line}:")), "{text:?}: {e}");
        }
        let invalid_utf8: &[u8] = b"1,2\n\xff\xfe,3\n";
        let e = PointReader::new(invalid_utf8)
            .collect::<Result<Vec<_>, _>>()
            .unwrap_err();
        assert!(e.to_string().contains("line 2: not UTF-8"), "{e}");
    }

    #[test]
    fn a_file_without_line_breaks_is_bounded() {
        let long = "1".repeat(MAX_LINE_BYTES * 3);
        let e = parse_points(&long).unwrap_err().to_string();
        assert!(e.contains("longer than"), "{e}");
    }

    #[test]
    fn reading_stops_after_the_first_error() {
        let mut r = PointReader::new("1,2\nbad\n3,4\n".as_bytes());
        assert!(r.next().unwrap().is_ok());
        assert!(r.next().unwrap().is_err());
        assert!(r.next().is_none());
    }
}
