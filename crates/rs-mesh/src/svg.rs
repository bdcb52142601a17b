//! An SVG figure of a curved triangulation: straight edges thin, boundary arcs thick.

use rs_spline::prelude::*;
use std::fmt::Write;

use rs_spline::Point;

use crate::{CurvedTriangulation, EdgeKind};

/// The figure as SVG text (`width` pixels wide, y up), with the companion triangles' chords
/// dashed under the arcs so the conversion is visible, and vertices as dots.
pub fn mesh_svg(mesh: &CurvedTriangulation, width: f64) -> String {
    let bb = mesh.domain().bounding_box();
    let margin = 10.0;
    let s = (width - 2.0 * margin) / bb.width().max(bb.height()).max(f64::MIN_POSITIVE);
    let height = bb.height() * s + 2.0 * margin;
    let map = |p: Point| {
        (
            margin + (p.x - bb.min.x) * s,
            height - margin - (p.y - bb.min.y) * s,
        )
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}">"#
    );
    let _ = writeln!(
        out,
        r##"<rect width="100%" height="100%" fill="#ffffff"/>"##
    );
    let v = mesh.vertices();
    for (t, tri) in mesh.triangles().iter().enumerate() {
        let pts: Vec<String> = tri
            .iter()
            .map(|&i| {
                let (x, y) = map(v[i]);
                format!("{x:.2},{y:.2}")
            })
            .collect();
        let _ = writeln!(
            out,
            r##"<polygon points="{}" fill="#dde8f6" stroke="#5070a0" stroke-width="0.6"/>"##,
            pts.join(" ")
        );
        for (k, kind) in mesh.edge_kinds(t).iter().enumerate() {
            if let EdgeKind::Curved(i) = kind {
                let arc = &mesh.arcs()[*i];
                let c = &mesh.domain().curves()[arc.curve];
                let samples: Vec<String> = (0..=24)
                    .map(|j| {
                        let u = arc.u0 + (arc.u1 - arc.u0) * j as f64 / 24.0;
                        let (x, y) = map(c.point_at(u));
                        format!("{x:.2},{y:.2}")
                    })
                    .collect();
                let (a, b) = (map(v[tri[k]]), map(v[tri[(k + 1) % 3]]));
                let _ = writeln!(
                    out,
                    r##"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="#c04040" stroke-width="0.5" stroke-dasharray="2 2"/>"##,
                    a.0, a.1, b.0, b.1
                );
                let _ = writeln!(
                    out,
                    r##"<polyline points="{}" fill="none" stroke="#000000" stroke-width="1.6"/>"##,
                    samples.join(" ")
                );
            }
        }
    }
    for (i, p) in v.iter().enumerate() {
        let (x, y) = map(*p);
        let fill = if mesh.boundary_vertex(i).is_some() {
            "#c04040"
        } else {
            "#203060"
        };
        let _ = writeln!(
            out,
            r#"<circle cx="{x:.2}" cy="{y:.2}" r="1.6" fill="{fill}"/>"#
        );
    }
    out.push_str("</svg>\n");
    out
}
