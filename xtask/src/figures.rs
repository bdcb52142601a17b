//! SVG figures for `cargo xtask demo`: monotone boxes (inRS paper Fig. 2), refined boxes
//! (Fig. 3), classified points (Fig. 4) and a winding-number field of a non-watertight shape.

use inrs::prelude::*;
use std::path::{Path, PathBuf};

use inrs::boxes::{BoxOptions, MonotoneBoxes};
use inrs::contain::WindingField;
use inrs::{BoundingBox, Domain, Location, Point};
use svg::Document;
use svg::node::element::path::Data;
use svg::node::element::{Circle, Path as SvgPath, Rectangle, Text};

/// Pixel size of the longer side of a figure.
const SIZE: f64 = 560.0;
const MARGIN: f64 = 20.0;

/// Maps domain coordinates to SVG pixels (y up in the domain, down in SVG).
struct Frame {
    bbox: BoundingBox,
    scale: f64,
}

impl Frame {
    fn new(bbox: BoundingBox) -> Self {
        let span = bbox.width().max(bbox.height()).max(f64::MIN_POSITIVE);
        Self {
            bbox,
            scale: SIZE / span,
        }
    }

    fn x(&self, x: f64) -> f64 {
        MARGIN + (x - self.bbox.min.x) * self.scale
    }

    fn y(&self, y: f64) -> f64 {
        MARGIN + (self.bbox.max.y - y) * self.scale
    }

    fn document(&self, title: &str) -> Document {
        let w = 2.0 * MARGIN + self.bbox.width() * self.scale;
        let h = 2.0 * MARGIN + self.bbox.height() * self.scale + 16.0;
        Document::new()
            .set("viewBox", (0.0, 0.0, w, h))
            .set("width", w)
            .set("height", h)
            .add(
                Rectangle::new()
                    .set("width", w)
                    .set("height", h)
                    .set("fill", "white"),
            )
            .add(
                Text::new(title)
                    .set("x", MARGIN)
                    .set("y", h - 4.0)
                    .set("font-family", "sans-serif")
                    .set("font-size", 12),
            )
    }
}

/// The boundary curves as one SVG path (each Bezier piece sampled at 64 points).
fn boundary_path(d: &Domain, f: &Frame, color: &str) -> SvgPath {
    let mut data = Data::new();
    for (_, b) in d.bezier_pieces() {
        let p0 = b.start_point();
        data = data.move_to((f.x(p0.x), f.y(p0.y)));
        for i in 1..=64 {
            let p = b.point_at(i as f64 / 64.0);
            data = data.line_to((f.x(p.x), f.y(p.y)));
        }
    }
    SvgPath::new()
        .set("d", data)
        .set("fill", "none")
        .set("stroke", color)
        .set("stroke-width", 1.5)
}

fn boxes_figure(d: &Domain, subdivisions: usize, title: &str) -> Result<Document, String> {
    let boxes = MonotoneBoxes::new(d, BoxOptions { subdivisions }).map_err(|e| e.to_string())?;
    let f = Frame::new(d.bounding_box());
    let mut doc = f.document(title);
    for b in boxes.boxes() {
        doc = doc.add(
            Rectangle::new()
                .set("x", f.x(b.xmin))
                .set("y", f.y(b.ymax))
                .set("width", ((b.xmax - b.xmin) * f.scale).max(0.8))
                .set("height", ((b.ymax - b.ymin) * f.scale).max(0.8))
                .set("fill", "#dbe8ff")
                .set("fill-opacity", 0.5)
                .set("stroke", "#3466c2")
                .set("stroke-width", 0.7),
        );
    }
    doc = doc.add(boundary_path(d, &f, "black"));
    for c in boxes.critical_points() {
        doc = doc.add(
            Circle::new()
                .set("cx", f.x(c.point.x))
                .set("cy", f.y(c.point.y))
                .set("r", 2.5)
                .set("fill", "#d62728"),
        );
    }
    Ok(doc)
}

fn points_figure(d: &Domain, pts: &[Point], loc: &[Location], title: &str) -> Document {
    let f = Frame::new(d.bounding_box());
    let mut doc = f.document(title);
    for (p, l) in pts.iter().zip(loc) {
        let color = match l {
            Location::Inside => "#2ca02c",
            Location::Outside => "#d62728",
            Location::Boundary => "black",
        };
        doc = doc.add(
            Circle::new()
                .set("cx", f.x(p.x))
                .set("cy", f.y(p.y))
                .set("r", 1.6)
                .set("fill", color),
        );
    }
    doc.add(boundary_path(d, &f, "black"))
}

/// The generalized winding number on a raster of `n x n` cells, white (0) to blue (1), then
/// towards orange (2), with the curves on top.
fn winding_figure(d: &Domain, n: usize, title: &str) -> Result<Document, String> {
    let field =
        WindingField::new(d, inrs::contain::DEFAULT_TOLERANCE).map_err(|e| e.to_string())?;
    let mut bb = d.bounding_box();
    let pad = 0.1 * bb.diagonal();
    bb.min = bb.min - Point::new(pad, pad);
    bb.max = bb.max + Point::new(pad, pad);
    let f = Frame::new(bb);
    let mut doc = f.document(title);
    let (cw, ch) = (bb.width() / n as f64, bb.height() / n as f64);
    for i in 0..n {
        for j in 0..n {
            let q = Point::new(
                bb.min.x + (i as f64 + 0.5) * cw,
                bb.min.y + (j as f64 + 0.5) * ch,
            );
            let w = field.winding_number(q);
            let color = if w <= 1.0 {
                let t = w.max(0.0);
                format!(
                    "rgb({},{},255)",
                    (255.0 - 215.0 * t) as u8,
                    (255.0 - 160.0 * t) as u8
                )
            } else {
                let u = (w - 1.0).min(1.0);
                format!(
                    "rgb({},{},{})",
                    (40.0 + 215.0 * u) as u8,
                    (95.0 + 55.0 * u) as u8,
                    (255.0 - 215.0 * u) as u8
                )
            };
            doc = doc.add(
                Rectangle::new()
                    .set("x", f.x(bb.min.x + i as f64 * cw))
                    .set("y", f.y(bb.min.y + (j + 1) as f64 * ch))
                    .set("width", cw * f.scale + 0.3)
                    .set("height", ch * f.scale + 0.3)
                    .set("fill", color),
            );
        }
    }
    Ok(doc.add(boundary_path(d, &f, "black")))
}

/// Writes the figures of one domain; returns the files written.
pub(crate) fn domain_figures(
    dir: &Path,
    stem: &str,
    d: &Domain,
    pts: &[Point],
    loc: &[Location],
) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let figures = [
        (
            format!("{stem}_boxes.svg"),
            boxes_figure(
                d,
                1,
                &format!("{stem}: monotone boxes and critical points (inRS Fig. 2)"),
            )?,
        ),
        (
            format!("{stem}_refined_boxes.svg"),
            boxes_figure(
                d,
                4,
                &format!("{stem}: boxes refined 4 times (inRS Fig. 3)"),
            )?,
        ),
        (
            format!("{stem}_points.svg"),
            points_figure(
                d,
                pts,
                loc,
                &format!(
                    "{stem}: {} Halton points, inside green, outside red (inRS Fig. 4)",
                    pts.len()
                ),
            ),
        ),
    ];
    let mut written = Vec::new();
    for (name, doc) in figures {
        let path = dir.join(name);
        svg::save(&path, &doc).map_err(|e| format!("{}: {e}", path.display()))?;
        written.push(path);
    }
    Ok(written)
}

/// Writes the winding-number field of a non-watertight version of `d` (the start of curve
/// `curve` moved by `offset`, opening a gap).
pub(crate) fn gap_figure(
    dir: &Path,
    d: &Domain,
    curve: usize,
    offset: Point,
) -> Result<PathBuf, String> {
    let mut curves = d.curves().to_vec();
    let c = &curves[curve];
    let mut pts = c.control_points().to_vec();
    pts[0] = pts[0] + offset;
    curves[curve] = inrs::NurbsCurve::new(
        c.degree(),
        c.knots().knots().to_vec(),
        pts,
        Some(c.weights().to_vec()),
    )
    .map_err(|e| e.to_string())?;
    let open = Domain::new(curves).map_err(|e| e.to_string())?;
    let doc = winding_figure(
        &open,
        120,
        "generalized winding number of a boundary with a gap (white 0, blue 1)",
    )?;
    let path = dir.join("winding_field_with_gap.svg");
    svg::save(&path, &doc).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figures_hold_one_rectangle_per_box_and_one_dot_per_point() {
        let d = Domain::new(vec![
            inrs::spline::circle(Point::new(0.0, 0.0), 1.0).unwrap(),
        ])
        .unwrap();
        let doc = boxes_figure(&d, 3, "t").unwrap().to_string();
        // Background plus 4 quadrants x 3 sub-boxes.
        assert_eq!(doc.matches("<rect").count(), 1 + 12);
        assert_eq!(doc.matches("<circle").count(), 4); // the four tangency points
        let pts = [Point::new(0.0, 0.0), Point::new(2.0, 0.0)];
        let doc = points_figure(&d, &pts, &[Location::Inside, Location::Outside], "t").to_string();
        assert_eq!(doc.matches("<circle").count(), 2);
        assert!(doc.contains("#2ca02c") && doc.contains("#d62728"));
    }
}
