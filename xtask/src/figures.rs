//! SVG figures for `cargo xtask demo`: monotone boxes (inRS paper Fig. 2), refined boxes
//! (Fig. 3), classified points (Fig. 4) and a winding-number field of a non-watertight shape.

use std::path::{Path, PathBuf};

use inrs::boxes::{BoxOptions, MonotoneBoxes};
use inrs::contain::{FastWindingField, WindingField};
use inrs::{BoundingBox, Domain, Location, Point};
use rs_figure::{ChartAxis, FieldImage, Figure, Marker, Style};

/// Writes `fig` as the SVG file `svg` and, where `rsvg-convert` is installed, a PNG beside it:
/// the files written.
pub(crate) fn write_figure(svg: &Path, fig: &Figure) -> Result<Vec<PathBuf>, String> {
    std::fs::write(svg, fig.to_svg()).map_err(|e| format!("{}: {e}", svg.display()))?;
    let mut written = vec![svg.to_path_buf()];
    written.extend(png_beside(svg));
    Ok(written)
}

/// Renders `svg` to a PNG beside it (`rsvg-convert`, white background) and returns its path;
/// `None` (and a note on standard output) where the tool is missing or fails. The PNG is a
/// convenience for viewers without SVG support; its absence is not an error.
pub(crate) fn png_beside(svg: &Path) -> Option<PathBuf> {
    let png = svg.with_extension("png");
    let converted = std::process::Command::new("rsvg-convert")
        .args(["--background-color", "white", "--output"])
        .arg(&png)
        .arg(svg)
        .status();
    match converted {
        Ok(s) if s.success() => Some(png),
        _ => {
            let _ = std::fs::remove_file(&png);
            println!(
                "(rsvg-convert not available: {} written as SVG only)",
                svg.display()
            );
            None
        }
    }
}

/// Pixel width of a figure's plot area.
pub(crate) const SIZE: f64 = 560.0;

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
        let r = BoundingBox::from_point(Point::new(b.band.xmin, b.band.ymin))
            .including(Point::new(b.band.xmax, b.band.ymax));
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

/// Each point as a dot coloured by its location (inside green, outside red, boundary black).
pub(crate) fn mark_locations(fig: &mut Figure, pts: &[Point], loc: &[Location]) {
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
}

fn points_figure(d: &Domain, pts: &[Point], loc: &[Location], caption: &str) -> Figure {
    let mut fig = Figure::new(d.bounding_box(), SIZE);
    mark_locations(&mut fig, pts, loc);
    draw_boundary(&mut fig, d);
    fig.caption(caption);
    fig
}

/// The generalized winding number as a colour map (an embedded PNG `width` pixels wide, one
/// sample per pixel, viridis from 0 to 1 with a colour bar), the curves on top.
fn winding_figure(d: &Domain, width: usize, caption: &str) -> Result<Figure, String> {
    let field = WindingField::new(d, inrs::contain::DEFAULT_RELATIVE_TOLERANCE)
        .map_err(|e| e.to_string())?;
    let fast = FastWindingField::new(&field);
    let mut bb = d.bounding_box();
    let pad = 0.1 * bb.diagonal();
    bb.min = bb.min - Point::new(pad, pad);
    bb.max = bb.max + Point::new(pad, pad);
    let mut fig = Figure::new(bb, SIZE);
    let image = FieldImage::sample(&fig, width, |q| Some(fast.winding_number(q)));
    let hi = image.range().map_or(1.0, |(_, hi)| hi.max(1.0));
    fig.field(&image, 0.0, hi, "generalized winding number");
    draw_boundary(&mut fig, d);
    fig.caption(caption);
    Ok(fig)
}

/// A CAD face in its `(u, v)`: each trimming loop in its own colour (the outer one first) over
/// the classified points, on a chart with `u` and `v` at their own scales (a face's parameter
/// box is often far from square).
pub(crate) fn cad_face_figure(
    d: &Domain,
    pts: &[Point],
    loc: &[Location],
    caption: &str,
) -> Figure {
    let mut bb = d.bounding_box();
    for p in pts {
        bb = bb.including(*p);
    }
    // Equal scales on both axes unless that would make the plot too flat or too tall.
    let aspect = (bb.height() / bb.width()).clamp(0.4, 1.2);
    let aspect = if aspect.is_finite() { aspect } else { 0.75 };
    let mut fig = Figure::chart(
        bb,
        SIZE,
        aspect * SIZE,
        ChartAxis::linear("u"),
        ChartAxis::linear("v"),
    );
    mark_locations(&mut fig, pts, loc);
    let outer = Style::stroke("#000000", 1.8).labelled("outer trimming loop");
    let inner = Style::stroke("#1f3fbf", 1.8).labelled("inner trimming loop (hole)");
    for (i, l) in d.loops().iter().enumerate() {
        let style = if i == 0 { &outer } else { &inner };
        for c in &d.curves()[l.curves()] {
            fig.curve(c, style);
        }
    }
    fig.caption(caption);
    fig
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
        280,
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

    #[test]
    fn every_demo_figure_explains_itself() {
        let d = rs_testkit::inrs_fixture("s4_disk_ellipse_segment").domain;
        let dir = std::env::temp_dir().join(format!("xtask-figures-{}", std::process::id()));
        let pts = inrs::contain::baselines::halton_points(200, d.bounding_box());
        let loc = vec![Location::Inside; pts.len()];
        let mut written = domain_figures(&dir, "s4", &d, &pts, &loc).unwrap();
        written.push(gap_figure(&dir, &d, 1, Point::new(0.2, -0.15)).unwrap());
        let captions = [
            "monotone boxes and critical points",
            "boxes refined 4 times",
            "200 Halton points",
            "Generalized winding number of a boundary with a gap",
        ];
        for (path, caption) in written.iter().zip(captions) {
            let svg = std::fs::read_to_string(path).unwrap();
            rs_testkit::assert_figure(&svg, caption, &path.display().to_string());
        }
        // The winding field is one embedded image of a few hundred kB at most, with a bar.
        let field = std::fs::read_to_string(&written[3]).unwrap();
        assert_eq!(field.matches("<image").count(), 1);
        assert!(field.len() < 400_000, "{} bytes", field.len());
        assert!(field.contains("generalized winding number"));
        std::fs::remove_dir_all(&dir).ok();
    }
}
