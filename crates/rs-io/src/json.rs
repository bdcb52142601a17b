//! The JSON domain file (docs/FORMATS.md): read and write.
//!
//! `{"name"?: "...", "curves": [curve, ...]}` where every curve is a NURBS object or one of the
//! primitive forms listed at [`domain_from_json`].

use std::fmt;
use std::path::Path;

use serde_json::{Map, Value, json};

use rs_spline::{
    DEFAULT_RELATIVE_CLOSURE_TOLERANCE, Domain, KnotVector, NurbsCurve, Point, SplineError, circle,
    circular_arc, ellipse, elliptic_arc, limits, polyline, segment,
};

use crate::IoError;

/// Curve forms accepted besides the NURBS form, for error messages.
const FORMS: &str = "a NURBS curve (degree, control_points, knots, weights) or one of \
                     segment, polyline, arc, circle, elliptic_arc, ellipse";

/// Parses a domain file from JSON text (default closure tolerance).
///
/// Every curve is a NURBS object `{"degree", "control_points", "knots"?, "weights"?}`;
/// `knots` may be omitted for a single Bezier piece and `weights` for a B-spline. These
/// primitive forms are accepted too and converted to exact NURBS:
/// `{"segment": {"from": [x, y], "to": [x, y]}}`, `{"polyline": [[x, y], ...]}`,
/// `{"arc": {"center": [x, y], "radius": r, "start_angle": a, "sweep": s}}` (radians),
/// `{"circle": {"center": [x, y], "radius": r}}`,
/// `{"elliptic_arc": {"center", "rx", "ry", "tilt"?, "start_angle", "sweep"}}`,
/// `{"ellipse": {"center", "rx", "ry", "tilt"?}}`. Unknown keys are ignored.
///
/// # Errors
/// [`IoError::Json`] (with line and column), [`IoError::NotADomainFile`],
/// [`IoError::CurveEntry`] and [`IoError::Curve`] (naming the curve index), and
/// [`IoError::Domain`] for curves that do not form a domain.
///
/// # Examples
///
/// ```
/// use rs_io::json::domain_from_json;
/// let d = domain_from_json(r#"{"curves": [{"circle": {"center": [0, 0], "radius": 1}}]}"#).unwrap();
/// assert!(d.is_closed());
/// let err = domain_from_json(r#"{"curves": [{"degree": 1, "control_points": [[0, 0]]}]}"#)
///     .unwrap_err();
/// assert!(err.to_string().starts_with("curve 0:"));
/// ```
pub fn domain_from_json(text: &str) -> Result<Domain, IoError> {
    domain_from_json_with_relative_closure_tolerance(text, DEFAULT_RELATIVE_CLOSURE_TOLERANCE)
}

/// As [`domain_from_json`] with a relative closure tolerance.
///
/// # Errors
/// As [`domain_from_json`]; an invalid tolerance is [`IoError::Domain`].
pub fn domain_from_json_with_relative_closure_tolerance(
    text: &str,
    relative_tolerance: f64,
) -> Result<Domain, IoError> {
    let TopLevel { curves, name } = top_level(text)?;
    let curves = curves.ok_or_else(|| IoError::NotADomainFile("missing \"curves\"".into()))?;
    let curves = curves
        .as_array()
        .ok_or_else(|| IoError::NotADomainFile("\"curves\" must be an array".into()))?;
    let curves = curves
        .iter()
        .enumerate()
        .map(|(i, c)| parse_curve(i, c))
        .collect::<Result<Vec<_>, _>>()?;
    let domain = Domain::with_relative_closure_tolerance(curves, relative_tolerance)?;
    Ok(match name.as_ref().and_then(Value::as_str) {
        Some(name) => domain.with_name(name),
        None => domain,
    })
}

/// The two fields of a domain file the parser reads. Any other field (a fixture's reference
/// numbers, notes) is skipped by the deserializer without being built into a `Value`: on a
/// paper fixture that was a third of the time from text to first answer.
#[derive(serde::Deserialize)]
struct TopLevel {
    curves: Option<Value>,
    name: Option<Value>,
}

/// The top level of `text`. When the direct read fails (not JSON, not an object, or a shape
/// it refuses such as a repeated key), the text is read again as a `Value`, which gives the
/// established errors and, for a repeated key, the last value as before.
fn top_level(text: &str) -> Result<TopLevel, IoError> {
    if let Ok(top) = serde_json::from_str::<TopLevel>(text) {
        return Ok(top);
    }
    let value: Value = serde_json::from_str(text).map_err(|e| json_error(&e))?;
    let Value::Object(mut top) = value else {
        return Err(IoError::NotADomainFile(
            "the top level must be a JSON object".into(),
        ));
    };
    Ok(TopLevel {
        curves: top.remove("curves"),
        name: top.remove("name"),
    })
}

/// Reads a domain file (at most [`limits::MAX_FILE_BYTES`]).
///
/// # Errors
/// [`IoError::Read`] if it cannot be read, otherwise as [`domain_from_json`].
pub fn domain_from_json_file(path: impl AsRef<Path>) -> Result<Domain, IoError> {
    let path = path.as_ref();
    let text = limits::read_text_file(path).map_err(|source| IoError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    domain_from_json(&text)
}

/// The domain as JSON text in the NURBS form (primitives are written as their NURBS), one
/// curve per line. Numbers are written in shortest round-trip form, so reading the text back
/// gives the same curves bit for bit.
pub fn domain_to_json(domain: &Domain) -> String {
    let mut out = String::from("{");
    if let Some(name) = domain.name() {
        out.push_str("\"name\": ");
        out.push_str(&Value::String(name.into()).to_string());
        out.push_str(",\n ");
    }
    out.push_str("\"curves\": [");
    for (i, c) in domain.curves().iter().enumerate() {
        let curve = json!({
            "degree": c.degree(),
            "knots": c.knots().knots(),
            "control_points": c.control_points().iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
            "weights": c.weights(),
        });
        out.push_str(if i == 0 { "\n  " } else { ",\n  " });
        out.push_str(&curve.to_string());
    }
    out.push_str("\n]}");
    out
}

/// Writes [`domain_to_json`] to `path`.
///
/// # Errors
/// [`IoError::Write`].
pub fn save_domain_json(domain: &Domain, path: impl AsRef<Path>) -> Result<(), IoError> {
    let path = path.as_ref();
    std::fs::write(path, domain_to_json(domain) + "\n").map_err(|source| IoError::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// A `serde_json` error as [`IoError::Json`], without serde's " at line L column C" suffix.
fn json_error(e: &serde_json::Error) -> IoError {
    let full = e.to_string();
    let message = match full.rfind(" at line ") {
        Some(i) => full[..i].to_string(),
        None => full,
    };
    IoError::Json {
        line: e.line(),
        column: e.column(),
        message,
    }
}

fn format_err(curve: usize, message: impl Into<String>) -> IoError {
    IoError::CurveEntry {
        curve,
        message: message.into(),
    }
}

fn spline_err(curve: usize) -> impl Fn(SplineError) -> IoError {
    move |source| IoError::Curve {
        origin: format!("curve {curve}"),
        source,
    }
}

/// `v` as a number; `what` names it in the error (a lazy `format_args!` label: it is
/// formatted only when the value is wrong, so a valid file formats nothing).
fn number(curve: usize, v: &Value, what: impl fmt::Display) -> Result<f64, IoError> {
    v.as_f64()
        .ok_or_else(|| format_err(curve, format!("{what} must be a number, got {v}")))
}

fn field<'a>(
    curve: usize,
    obj: &'a Map<String, Value>,
    key: &str,
    form: &str,
) -> Result<&'a Value, IoError> {
    obj.get(key)
        .ok_or_else(|| format_err(curve, format!("{form} needs \"{key}\"")))
}

fn point(curve: usize, v: &Value, what: impl fmt::Display + Copy) -> Result<Point, IoError> {
    match v.as_array().map(Vec::as_slice) {
        Some([x, y]) => Ok(Point::new(number(curve, x, what)?, number(curve, y, what)?)),
        _ => Err(format_err(curve, format!("{what} must be [x, y], got {v}"))),
    }
}

fn points(curve: usize, v: &Value, what: &str) -> Result<Vec<Point>, IoError> {
    v.as_array()
        .ok_or_else(|| format_err(curve, format!("{what} must be an array of [x, y]")))?
        .iter()
        .enumerate()
        .map(|(i, p)| point(curve, p, format_args!("{what}[{i}]")))
        .collect()
}

fn numbers(curve: usize, v: &Value, what: &str) -> Result<Vec<f64>, IoError> {
    v.as_array()
        .ok_or_else(|| format_err(curve, format!("{what} must be an array of numbers")))?
        .iter()
        .enumerate()
        .map(|(i, x)| number(curve, x, format_args!("{what}[{i}]")))
        .collect()
}

fn object<'a>(curve: usize, v: &'a Value, form: &str) -> Result<&'a Map<String, Value>, IoError> {
    v.as_object()
        .ok_or_else(|| format_err(curve, format!("\"{form}\" must be an object")))
}

/// Parses one curve entry of a domain file (any form accepted by [`domain_from_json`]);
/// `i` is its index, for error messages.
///
/// # Errors
/// [`IoError::CurveEntry`] or [`IoError::Curve`], naming curve `i`.
pub fn curve_from_json(i: usize, v: &Value) -> Result<NurbsCurve, IoError> {
    parse_curve(i, v)
}

/// Parses curve `i` of the file.
fn parse_curve(i: usize, v: &Value) -> Result<NurbsCurve, IoError> {
    let obj = v
        .as_object()
        .ok_or_else(|| format_err(i, format!("expected {FORMS}")))?;
    if obj.contains_key("degree") || obj.contains_key("control_points") {
        return parse_nurbs(i, obj);
    }
    let se = spline_err(i);
    if let Some(s) = obj.get("segment") {
        let s = object(i, s, "segment")?;
        let a = point(i, field(i, s, "from", "segment")?, "segment.from")?;
        let b = point(i, field(i, s, "to", "segment")?, "segment.to")?;
        return segment(a, b).map_err(se);
    }
    if let Some(p) = obj.get("polyline") {
        return polyline(&points(i, p, "polyline")?).map_err(se);
    }
    if let Some(a) = obj.get("arc") {
        let a = object(i, a, "arc")?;
        let num = |k: &str| number(i, field(i, a, k, "arc")?, format_args!("arc.{k}"));
        let c = point(i, field(i, a, "center", "arc")?, "arc.center")?;
        return circular_arc(c, num("radius")?, num("start_angle")?, num("sweep")?).map_err(se);
    }
    if let Some(a) = obj.get("circle") {
        let a = object(i, a, "circle")?;
        let c = point(i, field(i, a, "center", "circle")?, "circle.center")?;
        let r = number(i, field(i, a, "radius", "circle")?, "circle.radius")?;
        return circle(c, r).map_err(se);
    }
    for form in ["elliptic_arc", "ellipse"] {
        if let Some(a) = obj.get(form) {
            let a = object(i, a, form)?;
            let num = |k: &str| number(i, field(i, a, k, form)?, format_args!("{form}.{k}"));
            let c = point(
                i,
                field(i, a, "center", form)?,
                format_args!("{form}.center"),
            )?;
            let tilt = match a.get("tilt") {
                Some(t) => number(i, t, format_args!("{form}.tilt"))?,
                None => 0.0,
            };
            let (rx, ry) = (num("rx")?, num("ry")?);
            return if form == "ellipse" {
                ellipse(c, rx, ry, tilt)
            } else {
                elliptic_arc(c, rx, ry, tilt, num("start_angle")?, num("sweep")?)
            }
            .map_err(se);
        }
    }
    Err(format_err(i, format!("expected {FORMS}")))
}

fn parse_nurbs(i: usize, obj: &Map<String, Value>) -> Result<NurbsCurve, IoError> {
    let dv = field(i, obj, "degree", "a NURBS curve")?;
    let degree = match dv.as_u64() {
        Some(d) if d <= limits::MAX_DEGREE as u64 => d as usize,
        _ => {
            return Err(format_err(
                i,
                format!(
                    "degree must be an integer between 1 and {}, got {dv}",
                    limits::MAX_DEGREE
                ),
            ));
        }
    };
    let pts = points(
        i,
        field(i, obj, "control_points", "a NURBS curve")?,
        "control_points",
    )?;
    let weights = match obj.get("weights") {
        Some(Value::Null) | None => None,
        Some(w) => Some(numbers(i, w, "weights")?),
    };
    let se = spline_err(i);
    match obj.get("knots") {
        Some(Value::Null) | None => {
            if degree == 0 {
                return Err(se(SplineError::ZeroDegree));
            }
            if pts.len() != degree + 1 {
                return Err(se(SplineError::MissingKnots {
                    needed: degree + 1,
                    got: pts.len(),
                }));
            }
            NurbsCurve::from_parts(KnotVector::bezier(degree), pts, weights).map_err(se)
        }
        Some(k) => NurbsCurve::new(degree, numbers(i, k, "knots")?, pts, weights).map_err(se),
    }
}
