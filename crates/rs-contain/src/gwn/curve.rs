//! Generalized winding number of one rational Bezier curve (Spainhour, Gunderman and Weiss
//! 2024, Algorithms 1-5).

use rs_spline::prelude::*;
use std::f64::consts::TAU;

use rs_spline::{Point, RationalBezier};

use super::QueryStats;

/// Bisection depth cap: a subcurve on a parameter interval of `2^-64` is below `f64`
/// resolution; a query still inside its control polygon there is coincident with the curve.
pub(crate) const MAX_DEPTH: u32 = 64;

/// Signed angle from `a` to `b` in `(-pi, pi]`.
fn signed_angle(a: Point, b: Point) -> f64 {
    a.cross(b).atan2(a.dot(b))
}

/// Angle subtended at `q` by the chord from `a` to `b`, with the coincidence convention: a
/// query on the open chord (angle +-pi, the average of the two sides being 0) contributes 0.
pub(crate) fn chord_angle(q: Point, a: Point, b: Point) -> f64 {
    let (u, v) = (a - q, b - q);
    if u.cross(v) == 0.0 && u.dot(v) <= 0.0 {
        return 0.0;
    }
    signed_angle(u, v)
}

/// Algorithm 4 (after Ma and Hewitt 2003): is the control polygon simple and convex?
///
/// The paper's local test (each `P_i` separated from `P_n`, or `P_0`, by the line
/// `P_{i-1} P_{i+1}`) accepts polygons that turn more than a full revolution; we also require
/// every turn of the closed polygon to have the same sign and the turns to add up to one
/// revolution, so that the polygon really is its own convex hull.
pub(crate) fn is_simple_convex(p: &[Point]) -> bool {
    let n = p.len() - 1;
    let side = |a: Point, b: Point, x: Point| (b - a).cross(x - a);
    for i in 1..n {
        let (a, b) = (p[i - 1], p[i + 1]);
        let other = if 2 * i <= n { p[n] } else { p[0] };
        if side(a, b, p[i]) * side(a, b, other) > 0.0 {
            return false;
        }
    }
    let edges: Vec<Point> = (0..=n)
        .map(|i| p[(i + 1) % (n + 1)] - p[i])
        .filter(|e| *e != Point::default())
        .collect();
    let m = edges.len();
    if m < 3 {
        return true; // degenerate (collinear or a point): handled as straight by the caller
    }
    let (mut pos, mut neg, mut turning) = (false, false, 0.0);
    for i in 0..m {
        let (e, f) = (edges[i], edges[(i + 1) % m]);
        let c = e.cross(f);
        pos |= c > 0.0;
        neg |= c < 0.0;
        turning += c.atan2(e.dot(f));
    }
    !(pos && neg) && turning.abs() < 3.0 * std::f64::consts::PI
}

/// Algorithm 3 with tolerance 0: every control point lies exactly on the chord's line (the
/// curve is a straight segment, possibly traversed non-uniformly).
pub(crate) fn is_linear(p: &[Point]) -> bool {
    let (a, b) = (p[0], p[p.len() - 1]);
    let d = b - a;
    p.iter().all(|&x| d.cross(x - a) == 0.0)
}

/// True if `q` is strictly outside the convex polygon `p` (closed by `p[n] -> p[0]`), which must
/// be simple and convex with non-zero area.
fn outside_convex(p: &[Point], q: Point) -> bool {
    let n = p.len();
    let area: f64 = (0..n).map(|i| p[i].cross(p[(i + 1) % n])).sum();
    if area == 0.0 {
        return false;
    }
    (0..n).any(|i| {
        let (a, b) = (p[i], p[(i + 1) % n]);
        area * (b - a).cross(q - a) < 0.0
    })
}

fn outside_box(p: &[Point], q: Point) -> bool {
    let (mut lo, mut hi) = (p[0], p[0]);
    for &x in p {
        lo = Point::new(lo.x.min(x.x), lo.y.min(x.y));
        hi = Point::new(hi.x.max(x.x), hi.y.max(x.y));
    }
    q.x < lo.x || q.x > hi.x || q.y < lo.y || q.y > hi.y
}

/// Algorithm 5: the winding-number contribution of a curve with a simple convex control
/// polygon when `q` is one of its end points: the angle from the tangent at the coincident end
/// to the other end (or from the other end to the reversed tangent), over `2 pi`.
pub(crate) fn convex_endpoint_winding(p: &[Point], q: Point) -> f64 {
    let n = p.len() - 1;
    if q == p[0] {
        // Tangent direction at the start: the first control point different from P0.
        let t = p
            .iter()
            .find(|&&x| x != q)
            .map_or(Point::default(), |&x| x - q);
        signed_angle(t, p[n] - q) / TAU
    } else {
        let t = p
            .iter()
            .rev()
            .find(|&&x| x != q)
            .map_or(Point::default(), |&x| q - x);
        signed_angle(p[0] - q, -t) / TAU
    }
}

/// Where the adaptive algorithm gets its sub-curves: computed on the fly, or from a
/// precomputed hierarchy (see [`super::fast::CurveHierarchy`]).
pub(crate) trait SubCurves {
    /// A handle to one sub-curve.
    type Node;
    /// Its control points.
    fn points<'s>(&'s self, node: &'s Self::Node) -> &'s [Point];
    /// Its simple-convex flag, given whether its parent was simple and convex.
    fn convex(&self, node: &Self::Node, parent_convex: bool) -> bool;
    /// Its two halves (de Casteljau at 1/2); `true` if they had to be computed.
    fn halves(&self, node: &Self::Node) -> (Self::Node, Self::Node, bool);
}

/// Sub-curves computed on demand.
pub(crate) struct OnTheFly;

impl SubCurves for OnTheFly {
    type Node = RationalBezier;
    fn points<'s>(&'s self, node: &'s RationalBezier) -> &'s [Point] {
        node.control_points()
    }
    fn convex(&self, node: &RationalBezier, parent_convex: bool) -> bool {
        parent_convex || is_simple_convex(node.control_points())
    }
    fn halves(&self, node: &RationalBezier) -> (RationalBezier, RationalBezier, bool) {
        let (l, r) = node.subdivide();
        (l, r, true)
    }
}

/// Algorithms 1 and 2: the generalized winding number of `curve` at `q`, exact up to rounding.
///
/// Far field: if `q` is outside the curve's control bounding box, the curve is replaced by its
/// chord (the reversed linear closure) and contributes one angle. Near field: the curve is
/// bisected until, for every piece, `q` is outside its box or its simple convex control polygon
/// (then the piece and its chord have the same winding number at `q`), the piece is exactly
/// straight, or `q` is one of its end points (Algorithm 5). The result equals the paper's
/// `PolygonWindingNumber(polyline + closure) - w_closure`, evaluated as the sum of the pieces'
/// chord angles, which has no singular case for a `q` lying on the closure line.
///
/// Coincident points follow the paper's convention (the average across the jump): 0 on a
/// straight piece, the tangent formula at end points, and 0 for a piece still holding `q` at
/// the depth cap (a point within rounding of the curve's interior).
pub fn curve_winding_number(curve: &RationalBezier, q: Point, stats: &mut QueryStats) -> f64 {
    adaptive_winding(&OnTheFly, curve.clone(), q, stats)
}

/// The adaptive algorithm over any source of sub-curves.
pub(crate) fn adaptive_winding<S: SubCurves>(
    source: &S,
    root: S::Node,
    q: Point,
    stats: &mut QueryStats,
) -> f64 {
    stats.curve_evaluations += 1;
    {
        let pts = source.points(&root);
        if outside_box(pts, q) {
            return chord_angle(q, pts[0], pts[pts.len() - 1]) / TAU;
        }
    }
    let mut total = 0.0;
    let mut stack: Vec<(S::Node, u32, bool)> = vec![(root, 0, false)];
    while let Some((c, depth, parent_convex)) = stack.pop() {
        if depth > 0 {
            stats.curve_evaluations += 1;
        }
        let convex = source.convex(&c, parent_convex);
        let p = source.points(&c);
        let (a, b) = (p[0], p[p.len() - 1]);
        if is_linear(p) {
            total += chord_angle(q, a, b) / TAU;
            continue;
        }
        if convex && (q == a || q == b) {
            total += convex_endpoint_winding(p, q);
            continue;
        }
        if outside_box(p, q) || (convex && outside_convex(p, q)) {
            total += chord_angle(q, a, b) / TAU;
            continue;
        }
        if depth >= MAX_DEPTH {
            // q is within rounding of this tiny piece: coincident, average 0 over the piece.
            continue;
        }
        let (l, r, computed) = source.halves(&c);
        if computed {
            stats.subdivisions += 1;
        }
        // Sub-curves of a simple convex curve are simple and convex (paper, section 5).
        stack.push((r, depth + 1, convex));
        stack.push((l, depth + 1, convex));
    }
    total
}
