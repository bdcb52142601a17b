//! The convertibility test of Definition 4.2: a boundary arc meets no edge of the
//! triangulation other than its own chord, except at that edge's end points. Candidate edges
//! come from a grid of their bounding boxes; each is tested against the arc's Bezier pieces
//! by the roots of the pieces' signed distances to the edge's line.

use rs_roots::{Bernstein, bernstein_roots};
use rs_spline::grid::{CellIndex, GridFrame};
use rs_spline::prelude::*;
use rs_spline::{BoundingBox, NurbsCurve, Point, RationalBezier};

/// An arc whose control points lie within this (relative to its chord length and the domain
/// size) of its chord is straight: it cannot leave its chord's triangle.
const STRAIGHT_ARC: f64 = 1e-13;
/// A crossing within this fraction of the domain size of a segment's end vertex is the vertex.
const AT_VERTEX: f64 = 1e-11;
/// A crossing at segment parameter `s` is on the segment for `s` in `[-ON_SEGMENT, 1 + ON_SEGMENT]`.
const ON_SEGMENT: f64 = 1e-12;
/// A piece whose signed distances to a segment's line are all below this (relative to the
/// segment's length and the domain size) lies on that line.
const ON_LINE: f64 = 1e-14;

/// True if the arc meets no edge of the triangulation other than its own chord `(a, b)`,
/// except at that edge's end points.
pub(super) fn arc_is_clear(
    arc: &NurbsCurve,
    chord: (usize, usize),
    vertices: &[Point],
    grid: &EdgeGrid,
    size: f64,
) -> bool {
    let pieces = arc.to_bezier();
    let straight = pieces.iter().all(|b| {
        let p = b.control_points();
        let (s, e) = (p[0], p[p.len() - 1]);
        let len = e.distance(s);
        p.iter()
            .all(|q| (*q - s).cross(e - s).abs() <= STRAIGHT_ARC * len * len.max(size))
    });
    if straight && pieces.len() == 1 {
        return true;
    }
    let bbox = arc.control_bounding_box();
    let boxes: Vec<BoundingBox> = pieces.iter().map(|b| b.control_bounding_box()).collect();
    for (a, b) in grid.candidates(bbox) {
        if (a, b) == chord || (b, a) == chord {
            continue;
        }
        let (p, q) = (vertices[a], vertices[b]);
        // Where a piece can meet the segment: within its control box (the piece lies in its
        // control polygon's hull) and within the segment's box grown by what `within` accepts
        // beyond its ends (`ON_SEGMENT`) and by the rounding of the points tested (far below
        // `AT_VERTEX` of the domain). Disjoint boxes skip the root search.
        let reach = ON_SEGMENT * p.distance(q) + AT_VERTEX * size;
        let segment = BoundingBox::from_point(p).including(q).grown_by(reach);
        for (piece, piece_box) in pieces.iter().zip(&boxes) {
            if piece_box.overlaps(&segment) && crosses_inside_segment(piece, p, q, size) {
                return false;
            }
        }
    }
    true
}

/// True if the piece meets the segment `p q` at a point that is not one of `p`, `q`.
fn crosses_inside_segment(piece: &RationalBezier, p: Point, q: Point, size: f64) -> bool {
    let d = q - p;
    let len2 = d.dot(d);
    let n = d.perp();
    let coeffs: Vec<f64> = piece
        .control_points()
        .iter()
        .zip(piece.weights())
        .map(|(c, w)| w * n.dot(*c - p))
        .collect();
    let eps = AT_VERTEX * size;
    let at_end = |x: Point| x.distance(p) <= eps || x.distance(q) <= eps;
    let within = |x: Point| {
        let s = (x - p).dot(d) / len2;
        (-ON_SEGMENT..=1.0 + ON_SEGMENT).contains(&s) && !at_end(x)
    };
    let scale = coeffs.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    if scale <= ON_LINE * len2.sqrt() * size {
        // The piece lies on the segment's line: test its sampled points against the segment.
        return (1..16).any(|i| within(piece.point_at(i as f64 / 16.0)));
    }
    match bernstein_roots(&Bernstein::new(coeffs)) {
        Ok(roots) => roots.into_iter().any(|t| within(piece.point_at(t))),
        // Crossings that cannot be computed cannot be ruled out: report one, so that the
        // caller inserts boundary points (or fails with NotConvertible) instead of keeping an
        // arc that might cross an edge.
        Err(_) => true,
    }
}

/// Edges registered in the cells their bounding boxes meet.
pub(super) struct EdgeGrid {
    index: CellIndex<(usize, usize)>,
}

impl EdgeGrid {
    /// About one edge per cell, at most 65 536 cells, the cells near square (a grid of as
    /// many rows as columns over a long, thin domain would register every edge across it in
    /// every row: memory growing with the square of the edges).
    pub(super) fn new(vertices: &[Point], edges: &[(usize, usize)]) -> Self {
        let bb = BoundingBox::from_points(vertices.iter().copied())
            .unwrap_or(BoundingBox::from_point(Point::new(0.0, 0.0)));
        let frame = GridFrame::near_square(bb, edges.len().clamp(1, 1 << 16));
        let mut pairs = Vec::new();
        for &(a, b) in edges {
            let eb = BoundingBox::from_point(vertices[a]).including(vertices[b]);
            frame.for_cells_in(eb, |c| pairs.push((c, (a, b))));
        }
        Self {
            index: CellIndex::new(frame, pairs),
        }
    }

    /// The distinct edges registered in the cells meeting `b`.
    fn candidates(&self, b: BoundingBox) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        self.index
            .frame()
            .for_cells_in(b, |c| out.extend_from_slice(self.index.cell(c)));
        out.sort_unstable();
        out.dedup();
        out
    }
}
