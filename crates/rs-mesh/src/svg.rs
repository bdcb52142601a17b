//! An SVG figure of a curved triangulation: each curved triangle filled up to its arc, straight
//! edges thin, boundary arcs thick, the chords of the companion triangles dashed.

use rs_figure::{Figure, Marker, Style};
use rs_spline::{Point, prelude::*};

use crate::{CurvedTriangulation, EdgeKind};

/// The figure as SVG text, the plot area `width` pixels wide, with axes, a legend and a
/// caption.
pub fn mesh_svg(mesh: &CurvedTriangulation, width: f64) -> String {
    let mut fig = Figure::new(mesh.domain().bounding_box(), width);
    let cell = Style::stroke("#5070a0", 0.6)
        .with_fill("#dde8f6", 1.0)
        .labelled("curved triangle");
    let arc_style = Style::stroke("#000000", 1.6).labelled("boundary arc");
    let chord = Style::stroke("#c04040", 0.6)
        .dashed("2 2")
        .labelled("chord of the companion triangle");
    let v = mesh.vertices();
    let tolerance = 0.25 / fig.scale();
    let mut arcs: Vec<Vec<Point>> = Vec::new();
    let mut chords: Vec<[Point; 2]> = Vec::new();
    for (t, tri) in mesh.triangles().iter().enumerate() {
        // The outline: straight edges as they are, curved ones along the arc, each traversed
        // from corner k to corner k + 1.
        let mut outline = Vec::new();
        for (k, kind) in mesh.edge_kinds(t).iter().enumerate() {
            let (a, b) = (v[tri[k]], v[tri[(k + 1) % 3]]);
            // Each edge contributes its points from corner k up to, not including, corner k + 1.
            let mut edge = vec![a];
            if let EdgeKind::Curved(i) = kind
                && let Ok(curve) = mesh.arc_curve(&mesh.arcs()[*i])
            {
                let mut pts = Vec::new();
                curve.flatten(tolerance, &mut |p| pts.push(p));
                let d = |p: Option<&Point>| p.map_or(0.0, |p| p.distance(a));
                if d(pts.first()) > d(pts.last()) {
                    pts.reverse();
                }
                arcs.push(pts.clone());
                chords.push([a, b]);
                pts.pop();
                edge = pts;
            }
            outline.extend(edge);
        }
        fig.polygon(&outline, &cell);
    }
    if let Ok(ring) = mesh.extended_ring() {
        let ring_style = Style::stroke("#7a9a50", 0.5)
            .dashed("1 2")
            .labelled("extended ring (Algorithm 5.1)");
        for t in &ring.triangles {
            fig.polygon(t, &ring_style);
        }
    }
    for c in &chords {
        fig.polyline(c, &chord);
    }
    for a in &arcs {
        fig.polyline(a, &arc_style);
    }
    let boundary = Style::fill("#c04040")
        .with_marker(Marker::Dot(1.8))
        .labelled("boundary vertex");
    let interior = Style::fill("#203060")
        .with_marker(Marker::Dot(1.8))
        .labelled("interior vertex");
    for (i, &p) in v.iter().enumerate() {
        let s = if mesh.boundary_vertex(i).is_some() {
            &boundary
        } else {
            &interior
        };
        fig.mark(p, s);
    }
    fig.caption(&format!(
        "Curved triangulation: {} vertices, {} triangles, {} of them with a boundary arc as one side.",
        v.len(),
        mesh.triangles().len(),
        mesh.arcs().len()
    ));
    fig.to_svg()
}
