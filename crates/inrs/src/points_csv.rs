//! The points file (`shared/design/CONTRACTS.md`, section 2): `x,y` per line.

use std::path::Path;

use rs_spline::Point;
use thiserror::Error;

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

/// Parses points: one per line, `x,y` separated by a comma or white space, an optional header
/// line `x,y`, blank lines and `#` comment lines ignored. Numbers are parsed exactly as written
/// (shortest round-trip `f64`); NaN and infinities are rejected.
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
    let mut out = Vec::new();
    let mut seen_data = false;
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = if line.contains(',') {
            line.split(',').map(str::trim).collect()
        } else {
            line.split_whitespace().collect()
        };
        if !seen_data
            && fields.len() == 2
            && fields[0].eq_ignore_ascii_case("x")
            && fields[1].eq_ignore_ascii_case("y")
        {
            seen_data = true;
            continue;
        }
        seen_data = true;
        let err = |message: String| PointsError::Line {
            line: i + 1,
            message,
        };
        if fields.len() != 2 {
            return Err(err(format!("expected two numbers \"x,y\", got {line:?}")));
        }
        let num = |s: &str| -> Result<f64, PointsError> {
            match s.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                Ok(_) => Err(err(format!("{s:?} is not a finite number"))),
                Err(_) => Err(err(format!("{s:?} is not a number"))),
            }
        };
        let (x, y) = (num(fields[0])?, num(fields[1])?);
        out.push(PointRecord {
            point: Point::new(x, y),
            x_text: fields[0].to_string(),
            y_text: fields[1].to_string(),
        });
    }
    Ok(out)
}

/// Reads and parses a points file.
///
/// # Errors
/// [`PointsError::Io`] or as [`parse_points`].
pub fn read_points(path: impl AsRef<Path>) -> Result<Vec<PointRecord>, PointsError> {
    let path = path.as_ref();
    let text = std::fs::read_to_string(path).map_err(|source| PointsError::Io {
        path: path.display().to_string(),
        source,
    })?;
    parse_points(&text)
}
