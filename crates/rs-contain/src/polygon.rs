//! The polygon baseline of the papers: the boundary flattened to polylines within a tolerance,
//! classified by a sorted-points crossing algorithm in the manner of INPOLY2.

use rs_spline::prelude::*;
use rs_spline::{Domain, Point};

/// The boundary of a domain flattened to closed polylines, for comparisons.
///
/// Each rational Bezier piece is halved until the control points of every part are within
/// `tolerance` of its chord, so the polyline is within `tolerance` of the curve (convex-hull
/// property). Classification (even-odd rule) sorts the points by ordinate and, for each edge,
/// finds the points in its ordinate span `[y0, y1)` by binary search and toggles those whose
/// rightward horizontal ray crosses it: `O(E log M + M k)` for `E` edges, `M` points and `k`
/// edges met per horizontal line, the strategy of INPOLY2 (Engwirda) that the inRS paper
/// compares against. Points exactly on an edge are not singled out (there is no boundary
/// class): this is a baseline, not a replacement.
#[derive(Clone, Debug)]
pub struct FlattenedPolygon {
    edges: Vec<(Point, Point)>,
}

impl FlattenedPolygon {
    /// Flattens every loop of `domain` to within `accuracy` (an absolute distance, see
    /// [`Flatten::flatten`](rs_spline::Flatten::flatten)) with
    /// [`Domain::flatten_loop`]; each loop is closed by an edge back to its start.
    pub fn new(domain: &Domain, accuracy: f64) -> Self {
        Self::from_loops(domain, |i, pts| {
            domain.flatten_loop(i, accuracy, &mut |p| pts.push(p));
        })
    }

    /// A fixed linearisation: every piece replaced by `segments` chords of equal parameter
    /// length, whatever its shape (the approximation the GWN paper's Fig. 14 warns about).
    pub fn uniform(domain: &Domain, segments: usize) -> Self {
        let k = segments.max(1);
        Self::from_loops(domain, |i, pts| {
            for ci in domain.loops()[i].curves() {
                for b in domain.curves()[ci].to_bezier() {
                    // Each piece starts where the previous one ends: its start only once.
                    if pts.is_empty() {
                        pts.push(b.start_point());
                    }
                    pts.extend((1..=k).map(|j| b.point_at(j as f64 / k as f64)));
                }
            }
        })
    }

    /// Closed polylines, one per loop: `polyline(i, pts)` appends loop `i`'s open polyline to
    /// the empty `pts`, and an edge back to its first point closes it unless it ends there.
    fn from_loops(domain: &Domain, mut polyline: impl FnMut(usize, &mut Vec<Point>)) -> Self {
        let mut edges = Vec::new();
        let mut pts: Vec<Point> = Vec::new();
        for i in 0..domain.loops().len() {
            pts.clear();
            polyline(i, &mut pts);
            if let (Some(&first), Some(&last)) = (pts.first(), pts.last())
                && first != last
            {
                pts.push(first);
            }
            edges.extend(pts.windows(2).map(|w| (w[0], w[1])));
        }
        Self { edges }
    }

    /// Number of edges (sides).
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// Inside (`true`) or not for every point, in input order (even-odd rule).
    pub fn classify(&self, points: &[Point]) -> Vec<bool> {
        let mut order: Vec<usize> = (0..points.len()).collect();
        order.sort_by(|&a, &b| points[a].y.total_cmp(&points[b].y));
        let ys: Vec<f64> = order.iter().map(|&i| points[i].y).collect();
        let mut odd = vec![false; points.len()];
        for &(a, b) in &self.edges {
            let (lo, hi) = if a.y <= b.y { (a, b) } else { (b, a) };
            if lo.y == hi.y {
                continue; // horizontal edges never cross a horizontal ray (half-open spans)
            }
            let start = ys.partition_point(|&y| y < lo.y);
            let end = ys.partition_point(|&y| y < hi.y);
            let slope = (hi.x - lo.x) / (hi.y - lo.y);
            for &i in &order[start..end] {
                let p = points[i];
                if p.x < lo.x + (p.y - lo.y) * slope {
                    odd[i] = !odd[i];
                }
            }
        }
        odd
    }
}
