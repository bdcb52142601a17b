//! SVG documents: every rendered `path`, `rect`, `circle`, `ellipse`, `polygon` and `polyline`,
//! with the transforms of the element and its ancestors applied.

use rs_spline::prelude::*;
use rs_spline::{Point, SplineError};

use super::path_data::read_path_data;
use super::transform::parse_transform;
use crate::IoError;
use crate::builder::LoopBuilder;
use rs_spline::Affine;

/// Containers whose children are not drawn where they stand (definitions, clip paths, masks,
/// patterns, markers) or are not geometry.
const SKIPPED: &[&str] = &[
    "defs",
    "clipPath",
    "mask",
    "symbol",
    "pattern",
    "marker",
    "metadata",
    "title",
    "desc",
    "style",
    "script",
    "linearGradient",
    "radialGradient",
    "filter",
    "text",
    "foreignObject",
];

/// The deepest nesting of `svg`, `g`, `a` and `switch` elements read (drawing programs nest a
/// few levels; the reader recurses, so the depth is bounded).
pub const MAX_SVG_DEPTH: usize = 256;

/// The most XML nodes a document may have (elements, attributes' text, text nodes).
pub const MAX_SVG_NODES: u32 = 10_000_000;

const SVG_NS: &str = "http://www.w3.org/2000/svg";

/// Reads the shapes of an SVG document into `builder`; a path drawn up to an error in its
/// data adds that error to `warnings`.
pub(crate) fn read_document(
    text: &str,
    builder: &mut LoopBuilder,
    warnings: &mut Vec<IoError>,
) -> Result<(), IoError> {
    // DTDs are accepted (matplotlib, Illustrator and Inkscape write the SVG 1.1 one); roxmltree
    // expands internal entities with a depth and reference-count limit (entity-expansion
    // bombs fail fast) and never fetches external ones.
    let options = roxmltree::ParsingOptions {
        allow_dtd: true,
        nodes_limit: MAX_SVG_NODES,
        entity_resolver: None,
    };
    let doc = roxmltree::Document::parse_with_options(text, options)
        .map_err(|e| IoError::Xml(e.to_string()))?;
    let root = doc.root_element();
    if root.tag_name().name() != "svg" {
        return Err(IoError::Xml(format!(
            "the root element is <{}>, not <svg>",
            root.tag_name().name()
        )));
    }
    let mut reader = Reader {
        doc: &doc,
        warnings,
    };
    reader.visit(root, Affine::IDENTITY, builder, 0)
}

/// The document being read and the errors recovered from so far.
struct Reader<'d, 'w> {
    doc: &'d roxmltree::Document<'d>,
    warnings: &'w mut Vec<IoError>,
}

impl Reader<'_, '_> {
    fn visit(
        &mut self,
        node: roxmltree::Node<'_, '_>,
        parent: Affine,
        builder: &mut LoopBuilder,
        depth: usize,
    ) -> Result<(), IoError> {
        let doc = self.doc;
        let ns = node.tag_name().namespace();
        if ns.is_some_and(|n| n != SVG_NS) {
            return Ok(());
        }
        let name = node.tag_name().name();
        if SKIPPED.contains(&name) || is_hidden(node) {
            return Ok(());
        }
        let fail = |message: String| {
            let element = match node.attribute("id") {
                Some(id) => format!("{name} id={id:?}"),
                None => name.to_string(),
            };
            IoError::SvgElement {
                element,
                line: doc.text_pos_at(node.range().start).row,
                message,
            }
        };
        let own = match node.attribute("transform") {
            Some(t) => parse_transform(t).map_err(|m| fail(format!("transform: {m}")))?,
            None => Affine::IDENTITY,
        };
        let ctm = parent.then_apply_to(own);
        builder.set_transform(ctm);
        if matches!(name, "svg" | "g" | "a" | "switch") {
            if depth >= MAX_SVG_DEPTH {
                return Err(fail(format!(
                    "groups nested more than {MAX_SVG_DEPTH} deep (the limit)"
                )));
            }
            for child in node.children().filter(roxmltree::Node::is_element) {
                self.visit(child, ctm, builder, depth + 1)?;
            }
        } else if let Some(recovered) = shape(node, name, builder).map_err(fail)? {
            self.warnings.push(fail(format!(
                "{recovered}; drawn up to its last complete segment, as renderers draw it"
            )));
        }
        // The element's last subpath is finished under its own transform, and nothing of its
        // pen state reaches the next element.
        builder.end_path();
        if let Some(e) = builder.take_error() {
            return Err(fail(e.to_string()));
        }
        builder.set_transform(parent);
        Ok(())
    }
}

/// Adds the outline of one shape element `name` to `builder`. Lines enclose nothing; images,
/// `use` references and unknown elements are not read. A path drawn up to an error in its data
/// gives that error (`Ok(Some(message))`).
fn shape(
    node: roxmltree::Node<'_, '_>,
    name: &str,
    builder: &mut LoopBuilder,
) -> Result<Option<String>, String> {
    let curve_err = |e: SplineError| e.to_string();
    match name {
        "path" => {
            if let Some(d) = node.attribute("d") {
                let recovered = read_path_data(d, builder).map_err(|e| e.to_string())?;
                return Ok(recovered.map(|e| e.to_string()));
            }
        }
        "rect" => {
            let x = length(node, "x", 0.0)?;
            let y = length(node, "y", 0.0)?;
            let w = length(node, "width", 0.0)?;
            let h = length(node, "height", 0.0)?;
            if w < 0.0 || h < 0.0 {
                return Err(format!("negative size {w} x {h}"));
            }
            let rx = optional_length(node, "rx")?;
            let ry = optional_length(node, "ry")?;
            if w > 0.0 && h > 0.0 {
                rect(builder, x, y, w, h, rx, ry).map_err(curve_err)?;
            }
        }
        "circle" | "ellipse" => {
            let center = Point::new(length(node, "cx", 0.0)?, length(node, "cy", 0.0)?);
            let (rx, ry) = if name == "circle" {
                let r = length(node, "r", 0.0)?;
                (r, r)
            } else {
                (length(node, "rx", 0.0)?, length(node, "ry", 0.0)?)
            };
            if rx < 0.0 || ry < 0.0 {
                return Err(format!("negative radius {rx}, {ry}"));
            }
            if rx > 0.0 && ry > 0.0 {
                let e = rs_spline::ellipse(center, rx, ry, 0.0).map_err(curve_err)?;
                builder.move_to(e.start_point());
                builder.curve(e);
                builder.close();
            }
        }
        "polygon" | "polyline" => {
            if let Some(points) = node.attribute("points") {
                let values = numbers(points)?;
                let mut it = values.chunks_exact(2).map(|c| Point::new(c[0], c[1]));
                if let Some(first) = it.next() {
                    builder.move_to(first);
                    for p in it {
                        builder.line_to(p).map_err(curve_err)?;
                    }
                    if name == "polygon" {
                        builder.close();
                    }
                }
            }
        }
        _ => {}
    }
    Ok(None)
}

fn is_hidden(node: roxmltree::Node<'_, '_>) -> bool {
    node.attribute("display") == Some("none")
        || node.attribute("style").is_some_and(|s| {
            s.split(';').any(|decl| {
                let mut kv = decl.splitn(2, ':');
                let (k, v) = (
                    kv.next().unwrap_or("").trim(),
                    kv.next().unwrap_or("").trim(),
                );
                k == "display" && v == "none"
            })
        })
}

/// A rectangle, with elliptical corners when `rx`/`ry` are given (SVG 2 rules: one radius
/// stands for both, each is clamped to half the side).
fn rect(
    b: &mut LoopBuilder,
    x: f64,
    y: f64,
    w: f64,
    h: f64,
    rx: Option<f64>,
    ry: Option<f64>,
) -> Result<(), SplineError> {
    let (rx, ry) = match (rx, ry) {
        (None, None) => (0.0, 0.0),
        (Some(r), None) | (None, Some(r)) => (r, r),
        (Some(a), Some(b)) => (a, b),
    };
    let (rx, ry) = (rx.clamp(0.0, w / 2.0), ry.clamp(0.0, h / 2.0));
    let p = Point::new;
    if rx == 0.0 || ry == 0.0 {
        b.move_to(p(x, y));
        for q in [p(x + w, y), p(x + w, y + h), p(x, y + h)] {
            b.line_to(q)?;
        }
        b.close();
        return Ok(());
    }
    use std::f64::consts::{FRAC_PI_2, PI};
    // Each corner: a straight side to the arc's exact start, then the quarter ellipse
    // (centre, start angle) with its ends set to the exact tangent points.
    let corner = |b: &mut LoopBuilder,
                  from: Point,
                  to: Point,
                  centre: Point,
                  start: f64|
     -> Result<(), SplineError> {
        b.line_to(from)?;
        let arc = rs_spline::elliptic_arc(centre, rx, ry, 0.0, start, FRAC_PI_2)?;
        b.curve(crate::builder::with_end_points(&arc, from, to)?);
        Ok(())
    };
    let (x1, y1) = (x + w, y + h);
    b.move_to(p(x + rx, y));
    corner(
        b,
        p(x1 - rx, y),
        p(x1, y + ry),
        p(x1 - rx, y + ry),
        -FRAC_PI_2,
    )?;
    corner(b, p(x1, y1 - ry), p(x1 - rx, y1), p(x1 - rx, y1 - ry), 0.0)?;
    corner(
        b,
        p(x + rx, y1),
        p(x, y1 - ry),
        p(x + rx, y1 - ry),
        FRAC_PI_2,
    )?;
    corner(b, p(x, y + ry), p(x + rx, y), p(x + rx, y + ry), PI)?;
    b.close();
    Ok(())
}

fn length(node: roxmltree::Node<'_, '_>, attr: &str, default: f64) -> Result<f64, String> {
    Ok(optional_length(node, attr)?.unwrap_or(default))
}

/// A length attribute in user units (a number, optionally with `px`).
fn optional_length(node: roxmltree::Node<'_, '_>, attr: &str) -> Result<Option<f64>, String> {
    let Some(text) = node.attribute(attr) else {
        return Ok(None);
    };
    match super::number::user_length(text) {
        Some(v) => Ok(Some(v)),
        None => Err(format!(
            "attribute {attr}={text:?} is not a length in user units"
        )),
    }
}

fn numbers(text: &str) -> Result<Vec<f64>, String> {
    let values = super::number::number_list(text, "points")?;
    if values.len() % 2 == 1 {
        return Err(format!(
            "points: odd number of coordinates ({})",
            values.len()
        ));
    }
    Ok(values)
}
