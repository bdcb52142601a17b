//! An SVG figure of a planar convex domain: the box, the nested inner polygons, the outer
//! bound, and the curve with its control polygon and free point.

use rs_spline::prelude::*;
use std::fmt::Write;

use rs_spline::{NurbsCurve, Point};

use crate::{ConvexDomain, Region};

/// The figure as SVG text (600 px wide, y up), or `None` for a space curve's polytopes.
pub fn to_svg(domain: &ConvexDomain, curve: Option<&NurbsCurve>, free: usize) -> Option<String> {
    let Region::Polygon(outer) = &domain.outer else {
        return None;
    };
    let mut pts: Vec<Point> = outer.vertices().to_vec();
    for l in &domain.levels {
        if let Region::Polygon(p) = &l.region {
            pts.extend_from_slice(p.vertices());
        }
    }
    if let Some(c) = curve {
        pts.extend_from_slice(c.control_points());
    }
    let (mut lo, mut hi) = (
        Point::new(f64::INFINITY, f64::INFINITY),
        Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for p in &pts {
        lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    if !lo.x.is_finite() {
        lo = Point::new(0.0, 0.0);
        hi = Point::new(1.0, 1.0);
    }
    let span = (hi.x - lo.x).max(hi.y - lo.y).max(1e-300);
    let (w, margin) = (600.0, 20.0);
    let s = (w - 2.0 * margin) / span;
    let h = (hi.y - lo.y) * s + 2.0 * margin;
    let map = |p: Point| (margin + (p.x - lo.x) * s, h - margin - (p.y - lo.y) * s);
    let poly = |vs: &[Point]| {
        vs.iter()
            .map(|&p| {
                let (x, y) = map(p);
                format!("{x:.2},{y:.2}")
            })
            .collect::<Vec<_>>()
            .join(" ")
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h:.0}" viewBox="0 0 {w} {h:.0}">"#
    );
    let _ = writeln!(
        out,
        r##"<rect width="100%" height="100%" fill="#ffffff"/>"##
    );
    let _ = writeln!(
        out,
        r##"<polygon points="{}" fill="#f3d6d6" stroke="#b03030" stroke-dasharray="6 3" stroke-width="1.2"><title>outer bound</title></polygon>"##,
        poly(outer.vertices())
    );
    // Inner levels as outlines from light to dark blue, the last one filled.
    let n = domain.levels.len().max(1);
    for (i, l) in domain.levels.iter().enumerate() {
        if let Region::Polygon(p) = &l.region {
            if p.is_empty() {
                continue;
            }
            let last = i + 1 == domain.levels.len();
            let shade = 200 - (170 * (i + 1) / n) as i32;
            let fill = if last { "#7f96d9" } else { "none" };
            let _ = writeln!(
                out,
                r##"<polygon points="{}" fill="{fill}" fill-opacity="0.5" stroke="rgb({shade},{shade},230)" stroke-width="1.2"><title>level {}: {} inequalities</title></polygon>"##,
                poly(p.vertices()),
                l.level,
                l.inequalities
            );
        }
    }
    if let Some(c) = curve {
        let samples: Vec<Point> = (0..=400)
            .map(|i| {
                let (a, b) = c.param_range();
                c.point_at(a + (b - a) * i as f64 / 400.0)
            })
            .collect();
        let _ = writeln!(
            out,
            r##"<polyline points="{}" fill="none" stroke="#000000" stroke-width="2"/>"##,
            poly(&samples)
        );
        let _ = writeln!(
            out,
            r##"<polyline points="{}" fill="none" stroke="#808080" stroke-width="1"/>"##,
            poly(c.control_points())
        );
        for (i, &p) in c.control_points().iter().enumerate() {
            let (x, y) = map(p);
            let (r, fill) = if i == free {
                (6.0, "#e08000")
            } else {
                (3.0, "#404040")
            };
            let _ = writeln!(
                out,
                r#"<circle cx="{x:.2}" cy="{y:.2}" r="{r}" fill="{fill}"/>"#
            );
        }
    }
    out.push_str("</svg>\n");
    Some(out)
}
