//! SVG figures for `cargo xtask demo`: monotone boxes (inRS paper Fig. 2), refined boxes
//! (Fig. 3), classified points (Fig. 4) and a winding-number field of a non-watertight shape.

use std::path::{Path, PathBuf};

use inrs::boxes::{BoxOptions, MonotoneBoxes};
use inrs::contain::WindingField;
use inrs::{BoundingBox, Domain, Location, Point};
use rs_figure::{Figure, Marker, Style};

/// Pixel width of a figure's plot area.
const SIZE: f64 = 560.0;

/// The boundary curves drawn on top of a figure.
fn draw_boundary(fig: &mut Figure, d: &Domain) {
    let style = Style::stroke("#000000", 1.5).labelled("boundary curves");
    for c in d.curves() {
        fig.curve(c, &style);
    }
}

fn boxes_figure(d: &Domain, subdivisions: usize, caption: &str) -> Result<Figure, String> {
    let boxes = MonotoneBoxes::new(d, BoxOptions::DEFAULT.with_subdivisions(subdivisions))
        .map_err(|e| e.to_string())?;
    let mut fig = Figure::new(d.bounding_box(), SIZE);
    let style = Style::stroke("#3466c2", 0.7)
        .with_fill("#dbe8ff", 0.5)
        .labelled("monotone box");
    for b in boxes.boxes() {
        let r = BoundingBox::from_point(Point::new(b.xmin, b.ymin))
            .including(Point::new(b.xmax, b.ymax));
        fig.rect(r, &style);
    }
    draw_boundary(&mut fig, d);
    let critical = Style::fill("#d62728")
        .with_marker(Marker::Dot(2.5))
        .labelled("critical point (x' = 0 or y' = 0)");
    for c in boxes.critical_points() {
        fig.mark(c.point, &critical);
    }
    fig.caption(caption);
    Ok(fig)
}

fn points_figure(d: &Domain, pts: &[Point], loc: &[Location], caption: &str) -> Figure {
    let mut fig = Figure::new(d.bounding_box(), SIZE);
    let dot = |color: &str, label: &str| {
        Style::fill(color)
            .with_marker(Marker::Dot(1.6))
            .labelled(label)
    };
    let (inside, outside, boundary) = (
        dot("#2ca02c", "inside"),
        dot("#d62728", "outside"),
        dot("#000000", "on the boundary"),
    );
    for (p, l) in pts.iter().zip(loc) {
        let style = match l {
            Location::Inside => &inside,
            Location::Outside => &outside,
            Location::Boundary => &boundary,
        };
        fig.mark(*p, style);
    }
    draw_boundary(&mut fig, d);
    fig.caption(caption);
    fig
}

/// The colour of winding number `w`: white (0) to blue (1), then towards orange (2).
fn winding_color(w: f64) -> String {
    if w <= 1.0 {
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
    }
}

/// The generalized winding number on a raster of `n x n` cells, with the curves on top.
fn winding_figure(d: &Domain, n: usize, caption: &str) -> Result<Figure, String> {
    let field = WindingField::new(d, inrs::contain::DEFAULT_RELATIVE_TOLERANCE)
        .map_err(|e| e.to_string())?;
    let mut bb = d.bounding_box();
    let pad = 0.1 * bb.diagonal();
    bb.min = bb.min - Point::new(pad, pad);
    bb.max = bb.max + Point::new(pad, pad);
    let mut fig = Figure::new(bb, SIZE);
    let (cw, ch) = (bb.width() / n as f64, bb.height() / n as f64);
    for i in 0..n {
        for j in 0..n {
            let lo = Point::new(bb.min.x + i as f64 * cw, bb.min.y + j as f64 * ch);
            let q = lo + Point::new(0.5 * cw, 0.5 * ch);
            let color = winding_color(field.winding_number(q));
            // Cells overlap by 0.6 pixel so that no seams show.
            let grow = 0.6 / fig.scale();
            let cell = BoundingBox::from_point(lo).including(lo + Point::new(cw + grow, ch + grow));
            fig.rect(cell, &Style::fill(&color));
        }
    }
    for (w, label) in [
        (0.0, "winding number 0"),
        (0.5, "winding number 0.5"),
        (1.0, "winding number 1"),
        (2.0, "winding number 2"),
    ] {
        fig.legend_entry(
            &Style::stroke("#888888", 0.5)
                .with_fill(&winding_color(w), 1.0)
                .labelled(label),
        );
    }
    draw_boundary(&mut fig, d);
    fig.caption(caption);
    Ok(fig)
}

fn save(path: &Path, fig: &Figure) -> Result<(), String> {
    std::fs::write(path, fig.to_svg()).map_err(|e| format!("{}: {e}", path.display()))
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
    for (name, fig) in figures {
        let path = dir.join(name);
        save(&path, &fig)?;
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
    let fig = winding_figure(
        &open,
        120,
        "Generalized winding number of a boundary with a gap: 1 deep inside, 0 far outside, \
         varying smoothly across the gap, so a rounded value still classifies the points.",
    )?;
    let path = dir.join("winding_field_with_gap.svg");
    save(&path, &fig)?;
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
        let svg = boxes_figure(&d, 3, "boxes caption").unwrap().to_svg();
        // 4 quadrants x 3 sub-boxes, and the legend's swatch.
        assert_eq!(svg.matches(r##"fill="#dbe8ff""##).count(), 12 + 1);
        // The four tangency points, and the legend's swatch.
        assert_eq!(svg.matches(r##"fill="#d62728""##).count(), 4 + 1);
        assert!(svg.contains("boxes caption") && svg.contains("monotone box"));
        assert!(svg.contains(r#"class="axes""#));
        let pts = [Point::new(0.0, 0.0), Point::new(2.0, 0.0)];
        let svg = points_figure(&d, &pts, &[Location::Inside, Location::Outside], "t").to_svg();
        assert_eq!(svg.matches(r##"fill="#2ca02c""##).count(), 1 + 1);
        assert_eq!(svg.matches(r##"fill="#d62728""##).count(), 1 + 1);
        assert!(svg.contains(">inside<") && svg.contains(">outside<"));
    }
}
