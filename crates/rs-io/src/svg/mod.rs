//! SVG input: path data strings and SVG files.
//!
//! Coordinates are SVG user units as written (y pointing down, `viewBox` not applied): the
//! domain is the shape, not its rendering. Every subpath is closed as a renderer fills it;
//! containment is even-odd by default, so overlapping shapes cancel where they overlap.
//!
//! A `path` element whose data has an error (`d="M 13,9 3,19 h 11 v -3 l"`: a command
//! without its arguments, as real icon themes have) is drawn up to its last complete
//! segment, as the SVG specification says and renderers do; [`load_svg_file`] and
//! [`load_svg_str`] report each such error beside the domain ([`crate::Loaded`]). Path data
//! given on its own ([`curves_from_path_data`]) is read strictly: an error is an error.

mod arc;
mod document;
mod number;
mod path_data;
mod transform;

pub use document::{MAX_SVG_DEPTH, MAX_SVG_NODES};

use std::path::Path;

use rs_spline::{Domain, NurbsCurve};

use crate::IoError;
use crate::builder::LoopBuilder;
pub use crate::builder::OpenSubpaths;

/// The boundary curves of SVG path data, one closed loop per subpath (open subpaths closed
/// by a straight segment, as for filling). Elliptical arcs become exact rational quadratics;
/// lines and Bezier commands keep their degree.
///
/// # Errors
/// [`IoError::PathData`] with the byte position of the first malformed token.
///
/// # Examples
///
/// ```
/// let curves = rs_io::svg::curves_from_path_data("M0 0 H2 V1 A1 1 0 0 1 0 1 z").unwrap();
/// assert_eq!(curves.len(), 4);
/// assert_eq!(curves[3].degree(), 1); // the closing segment
/// ```
pub fn curves_from_path_data(d: &str) -> Result<Vec<NurbsCurve>, IoError> {
    let mut b = LoopBuilder::new(OpenSubpaths::Close);
    if let Some(grammar) = path_data::read_path_data(d, &mut b)? {
        return Err(grammar);
    }
    b.into_curves().map_err(|e| IoError::PathData {
        position: d.len(),
        message: e.to_string(),
    })
}

/// The domain bounded by SVG path data (see [`curves_from_path_data`]).
///
/// # Errors
/// As [`curves_from_path_data`]; [`IoError::Empty`] if no subpath encloses area.
///
/// # Examples
///
/// ```
/// // A ring: two circles drawn with arcs.
/// let d = rs_io::svg::domain_from_path_data(
///     "M 3 0 A 3 3 0 1 1 -3 0 A 3 3 0 1 1 3 0 Z M 1 0 A 1 1 0 1 0 -1 0 A 1 1 0 1 0 1 0 Z",
/// )
/// .unwrap();
/// assert_eq!(d.loops().len(), 2);
/// assert!((d.signed_area() - 8.0 * std::f64::consts::PI).abs() < 1e-12);
/// ```
pub fn domain_from_path_data(d: &str) -> Result<Domain, IoError> {
    domain(curves_from_path_data(d)?, "SVG path data")
}

/// The domain bounded by every drawn shape of an SVG document (`path`, `rect`, `circle`,
/// `ellipse`, `polygon`, `polyline`), transforms applied; shapes inside `defs`, `clipPath`,
/// `mask`, `symbol`, `pattern` and `marker`, hidden ones (`display: none`), text, images and
/// `use` references are not read.
///
/// # Errors
/// [`IoError::Xml`] for malformed XML, [`IoError::SvgElement`] naming the element (and its
/// line) with a bad attribute, [`IoError::Empty`] if nothing encloses area. (Path data with
/// an error is drawn up to it: [`load_svg_str`] reports it.)
pub fn domain_from_svg_str(text: &str) -> Result<Domain, IoError> {
    domain_from_svg_str_with(text, OpenSubpaths::Close)
}

/// [`domain_from_svg_str`], with subpaths that no close command ends read as `open` says:
/// [`OpenSubpaths::Keep`] gives the curves as drawn (`polyline`s and unclosed paths stay open),
/// a curve collection for generalized winding numbers.
///
/// # Errors
/// As [`domain_from_svg_str`].
///
/// # Examples
///
/// ```
/// use rs_io::svg::{OpenSubpaths, domain_from_svg_str_with};
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M0 0 C1 1 2 1 3 0"/></svg>"#;
/// let open = domain_from_svg_str_with(svg, OpenSubpaths::Keep).unwrap();
/// assert_eq!(open.curves().len(), 1);
/// assert!(open.require_closed().is_err());
/// let filled = domain_from_svg_str_with(svg, OpenSubpaths::Close).unwrap();
/// assert_eq!(filled.curves().len(), 2); // with its closing segment
/// ```
pub fn domain_from_svg_str_with(text: &str, open: OpenSubpaths) -> Result<Domain, IoError> {
    load_svg_str(text, open).map(|l| l.domain)
}

/// [`domain_from_svg_str_with`], with the errors it recovered from: each `path` whose data
/// has an error, drawn up to its last complete segment, as an [`IoError::SvgElement`] naming
/// the element, its line, the byte and what was expected there.
///
/// # Errors
/// As [`domain_from_svg_str`].
///
/// # Examples
///
/// ```
/// use rs_io::svg::{OpenSubpaths, load_svg_str};
/// let svg = r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="M 13,9 3,19 h 11 v -3 l"/></svg>"#;
/// let read = load_svg_str(svg, OpenSubpaths::Close).unwrap();
/// assert_eq!(read.domain.curves().len(), 4); // three segments and the closing one
/// assert_eq!(read.warnings.len(), 1);
/// assert!(read.warnings[0].to_string().contains("drawn up to its last complete segment"));
/// ```
pub fn load_svg_str(text: &str, open: OpenSubpaths) -> Result<crate::Loaded, IoError> {
    read_svg(text, open, "SVG document")
}

/// [`domain_from_svg_str`] on a file (named in the domain).
///
/// # Errors
/// [`IoError::Read`], then as [`domain_from_svg_str`].
pub fn domain_from_svg_file(path: impl AsRef<Path>) -> Result<Domain, IoError> {
    domain_from_svg_file_with(path, OpenSubpaths::Close)
}

/// [`domain_from_svg_str_with`] on a file (named in the domain).
///
/// # Errors
/// [`IoError::Read`], then as [`domain_from_svg_str`].
pub fn domain_from_svg_file_with(
    path: impl AsRef<Path>,
    open: OpenSubpaths,
) -> Result<Domain, IoError> {
    load_svg_file(path, open).map(|l| l.domain)
}

/// [`domain_from_svg_file_with`], with the errors it recovered from (see [`load_svg_str`]).
///
/// # Errors
/// As [`domain_from_svg_file`].
pub fn load_svg_file(path: impl AsRef<Path>, open: OpenSubpaths) -> Result<crate::Loaded, IoError> {
    let path = path.as_ref();
    let text = rs_spline::limits::read_text_file(path).map_err(|source| IoError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let name = path.display().to_string();
    let read = read_svg(&text, open, "SVG file")?;
    Ok(crate::Loaded {
        domain: read.domain.with_name(name),
        warnings: read.warnings,
    })
}

/// The domain of an SVG document and the errors it recovered from; `what` names the input in
/// errors.
fn read_svg(text: &str, open: OpenSubpaths, what: &str) -> Result<crate::Loaded, IoError> {
    let mut b = LoopBuilder::new(open);
    let mut warnings: Vec<IoError> = Vec::new();
    document::read_document(text, &mut b, &mut warnings)?;
    let curves = b.into_curves().map_err(curve_error)?;
    if curves.is_empty()
        && let Some(first) = warnings.first()
    {
        // Nothing drawn: the path data errors say why.
        return Err(IoError::Empty(format!("{what} ({first})")));
    }
    Ok(crate::Loaded {
        domain: domain(curves, what)?,
        warnings,
    })
}

/// A curve of the document its transform could not map (the reader reports these per
/// element; this covers the end of the document).
fn curve_error(source: rs_spline::SplineError) -> IoError {
    IoError::Curve {
        origin: "SVG document".to_string(),
        source,
    }
}

fn domain(curves: Vec<NurbsCurve>, what: &str) -> Result<Domain, IoError> {
    if curves.is_empty() {
        return Err(IoError::Empty(what.to_string()));
    }
    Ok(Domain::new(curves)?)
}
