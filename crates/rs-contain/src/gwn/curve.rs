//! Generalized winding number of one rational Bezier curve (Spainhour, Gunderman and Weiss
//! 2024, Algorithms 1-5).

use std::f64::consts::{PI, TAU};

use rs_roots::de_casteljau_split;
use rs_spline::{Hpoint, Point, RationalBezier};
use smallvec::SmallVec;

use super::QueryStats;
use super::monotone::{RootCrossing, monotone_crossing};
use super::sum::{AngleSum, ChordSink, cut_crossing};

/// Bisection depth cap: a subcurve on a parameter interval of `2^-64` is below `f64`
/// resolution; a query still inside its control polygon there is coincident with the curve.
pub(crate) const MAX_DEPTH: u32 = 64;

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
    let edges: SmallVec<[Point; 8]> = (0..=n)
        .map(|i| p[(i + 1) % (n + 1)] - p[i])
        .filter(|e| *e != Point::default())
        .collect();
    let m = edges.len();
    if m < 3 {
        return true; // degenerate (collinear or a point): handled as straight by the caller
    }
    // Every turn of one sign, and one revolution in all: the edge directions wind once
    // around the origin, counted by crossings of the cut (no angles needed).
    let (mut pos, mut neg, mut wraps) = (false, false, 0i32);
    for i in 0..m {
        let (e, f) = (edges[i], edges[(i + 1) % m]);
        let c = e.cross(f);
        if c == 0.0 && e.dot(f) < 0.0 {
            return false; // the polygon folds back on itself
        }
        pos |= c > 0.0;
        neg |= c < 0.0;
        wraps += cut_crossing(e, f, c);
    }
    !(pos && neg) && wraps.abs() <= 1
}

/// Algorithm 3 with tolerance 0: every control point lies exactly on the chord's line (the
/// curve is a straight segment, possibly traversed non-uniformly). A curve whose ends meet has
/// no chord line: it is straight only if every control point is that one point.
pub(crate) fn is_linear(p: &[Point]) -> bool {
    let (a, b) = (p[0], p[p.len() - 1]);
    let d = b - a;
    if d == Point::default() {
        return p.iter().all(|&x| x == a);
    }
    p.iter().all(|&x| d.cross(x - a) == 0.0)
}

/// True if `q` may be within `reach` of the straight curve with control points `p` (all on
/// the line through its ends, which differ): inside their box grown by `reach` (the curve may
/// run past its ends and back), and within `reach` of the line.
fn near_line(p: &[Point], q: Point, reach: f64) -> bool {
    let (lo, hi) = control_box(p);
    if outside_by(lo, hi, q, reach) {
        return false;
    }
    let (a, b) = (p[0] - q, p[p.len() - 1] - q);
    let (e, c) = (b - a, a.cross(b));
    c * c <= reach * reach * e.dot(e)
}

/// Where a query lies against a sub-curve's box or convex control polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Outside {
    /// Inside (or on) it.
    No,
    /// Outside it, but perhaps within the reach asked of it.
    Near,
    /// Outside it by more than the reach asked of it.
    Far,
}

/// Twice the signed area of the polygon `p` (closed by `p[n] -> p[0]`), in coordinates
/// relative to `p[0]`: a thin polygon far from the origin would lose its sign to cancellation
/// in absolute ones.
pub(crate) fn polygon_area(p: &[Point]) -> f64 {
    let o = p[0];
    p.windows(2)
        .skip(1)
        .map(|w| (w[0] - o).cross(w[1] - o))
        .sum()
}

/// Where `q` lies against the convex polygon `p` (closed by `p[n] -> p[0]`, simple and convex,
/// twice its signed area `area`, see [`polygon_area`]): outside an edge's line by more than
/// the rounding of the side test, and by more than `reach` (then `q` is farther than `reach`
/// from the polygon).
///
/// A query on an edge's line within that rounding is not outside it: on the closing edge, the
/// chord, the chord's angle at `q` would be `+-pi`, decided by the rounding (a point of the
/// chord of a quarter circle, with the two other edges' sides clear, got half a turn wrong).
///
/// The answer is `Far` if `q` is outside some edge by more than `reach`, else `Near` if it is
/// outside some edge, whatever the order the edges are tested in: every edge is tested, without
/// a branch, on arrays of three and four points (quadratic and cubic sub-curves) unrolled.
#[inline(always)]
fn outside_convex(p: &[Point], area: f64, q: Point, reach: f64) -> Outside {
    if area == 0.0 {
        return Outside::No;
    }
    if let Ok(p) = <&[Point; 4]>::try_from(p) {
        return outside_edges(p, area, q, reach);
    }
    if let Ok(p) = <&[Point; 3]>::try_from(p) {
        return outside_edges(p, area, q, reach);
    }
    outside_edges(p, area, q, reach)
}

/// [`outside_convex`]'s tests of every edge of `p` (a slice, or an array whose length the
/// compiler then knows), with `area` not 0.
#[inline(always)]
fn outside_edges<P: AsRef<[Point]> + ?Sized>(p: &P, area: f64, q: Point, reach: f64) -> Outside {
    let p = p.as_ref();
    let n = p.len();
    // `c` below is rounded by a few units in the last place of `|e| |d|`.
    let rounding = 4.0 * f64::EPSILON;
    let (mut out, mut far) = (false, false);
    for i in 0..n {
        let (a, b) = (p[i], p[if i + 1 == n { 0 } else { i + 1 }]);
        let (e, d) = (b - a, q - a);
        let c = e.cross(d);
        let ee = e.dot(e);
        let outside = (area * c < 0.0) & (c * c > rounding * rounding * ee * d.dot(d));
        out |= outside;
        far |= outside & (c * c > reach * reach * ee);
    }
    if far {
        Outside::Far
    } else if out {
        Outside::Near
    } else {
        Outside::No
    }
}

/// Where `q` lies against the box with corners `lo` and `hi` (see [`Outside`]).
#[inline(always)]
pub(crate) fn outside_box_reach(lo: Point, hi: Point, q: Point, reach: f64) -> Outside {
    if !outside(lo, hi, q) {
        Outside::No
    } else if outside_by(lo, hi, q, reach) {
        Outside::Far
    } else {
        Outside::Near
    }
}

/// The lower and upper corners of the bounding box of control points `p` (at least one).
/// (A plain loop: folding `BoundingBox::including` compiled to 1.4% more instructions over a
/// pass of butterfly's grid, in building the sub-curve hierarchies.)
pub(crate) fn control_box(p: &[Point]) -> (Point, Point) {
    let (mut lo, mut hi) = (p[0], p[0]);
    for &x in p {
        lo = Point::new(lo.x.min(x.x), lo.y.min(x.y));
        hi = Point::new(hi.x.max(x.x), hi.y.max(x.y));
    }
    (lo, hi)
}

/// Does the box with corners `lo` and `hi` lie above, below or right of `q`? Then nothing in
/// it crosses the cut (the horizontal ray from `q` towards `-x`) and `q` is not in it.
#[inline(always)]
pub(crate) fn misses_cut(lo: Point, hi: Point, q: Point) -> bool {
    q.y < lo.y || q.y > hi.y || q.x < lo.x
}

/// Is `q` outside the box with corners `lo` and `hi`?
#[inline(always)]
pub(crate) fn outside(lo: Point, hi: Point, q: Point) -> bool {
    q.x < lo.x || q.x > hi.x || q.y < lo.y || q.y > hi.y
}

/// Is `q` outside the box with corners `lo` and `hi` grown by `reach`?
#[inline(always)]
pub(crate) fn outside_by(lo: Point, hi: Point, q: Point, reach: f64) -> bool {
    q.x < lo.x - reach || q.x > hi.x + reach || q.y < lo.y - reach || q.y > hi.y + reach
}

/// Algorithm 5: the winding-number contribution of a curve with a simple convex control
/// polygon when `q` is one of its end points: the angle from the tangent at the coincident end
/// to the other end (or from the other end to the reversed tangent), over `2 pi`. The curve
/// turns the way its polygon does, so when the two directions are opposite the angle is `+pi`
/// for a counter-clockwise polygon and `-pi` for a clockwise one.
///
/// A closed piece with both ends at `q` subtends the angle from its start tangent to its
/// reversed end tangent, turning the way the polygon turns (`1/2` at a smooth point, the
/// interior angle over `2 pi` at a corner).
pub(crate) fn convex_endpoint_winding(p: &[Point], q: Point) -> f64 {
    let n = p.len() - 1;
    let area = polygon_area(p);
    // Directions from q: to the first control point past q (the start tangent), to the last
    // one before q (the reversed end tangent).
    let first = p.iter().find(|&&x| x != q).map(|&x| x - q);
    let last = p.iter().rev().find(|&&x| x != q).map(|&x| x - q);
    let (Some(first), Some(last)) = (first, last) else {
        return 0.0; // every control point at q: a point, no angle
    };
    let (from, to) = if q == p[0] && q == p[n] {
        (first, last)
    } else if q == p[0] {
        (first, p[n] - q)
    } else {
        (p[0] - q, last)
    };
    let (c, d) = (from.cross(to), from.dot(to));
    let angle = if c == 0.0 && d < 0.0 {
        // Opposite directions: half a turn, the polygon's way.
        if area > 0.0 {
            PI
        } else if area < 0.0 {
            -PI
        } else {
            0.0
        }
    } else {
        c.atan2(d)
    };
    let closed = q == p[0] && q == p[n];
    let angle = if closed && area > 0.0 && angle <= 0.0 {
        angle + TAU
    } else if closed && area < 0.0 && angle >= 0.0 {
        angle - TAU
    } else {
        angle
    };
    angle / TAU
}

/// A sub-curve of the adaptive algorithm, on the stack for degree <= 3: its control points
/// and, for a rational piece, its homogeneous control points (subdivided exactly there).
#[derive(Clone, Debug, Default)]
pub(crate) struct SubCurve {
    pts: SmallVec<[Point; 4]>,
    /// Homogeneous control points; empty when all weights are equal (a polynomial piece).
    h: SmallVec<[Hpoint; 4]>,
}

impl SubCurve {
    /// The sub-curve holding all of `b`.
    pub(crate) fn of(b: &RationalBezier) -> Self {
        let (pts, w) = (b.control_points(), b.weights());
        let h = if w.iter().all(|&x| x == w[0]) {
            SmallVec::new()
        } else {
            pts.iter()
                .zip(w)
                .map(|(&p, &w)| Hpoint::weighted(p, w))
                .collect()
        };
        Self {
            pts: pts.iter().copied().collect(),
            h,
        }
    }

    /// Its control points.
    pub(crate) fn points(&self) -> &[Point] {
        &self.pts
    }

    /// The same sub-curve with its first (last) control point moved to `start` (`end`) where
    /// given, weights kept.
    pub(crate) fn with_ends(mut self, start: Option<Point>, end: Option<Point>) -> Self {
        let n = self.pts.len() - 1;
        for (i, p) in [(0, start), (n, end)] {
            if let Some(p) = p {
                self.pts[i] = p;
                if let Some(h) = self.h.get_mut(i) {
                    *h = Hpoint::weighted(p, h.w);
                }
            }
        }
        self
    }

    /// Its halves by de Casteljau at `1/2` (see [`SubCurve::split`]).
    pub(crate) fn halves(&self) -> (Self, Self) {
        self.split(0.5)
    }

    /// Its parts on `[0, t]` and `[t, 1]` by de Casteljau (in homogeneous coordinates for a
    /// rational piece), for `t` in `(0, 1)`. The parts keep the curve's end points bit for bit
    /// (projecting `w p` back can move them by a rounding) and share their middle one, so a
    /// query at an end stays at an end of the part holding it.
    #[inline(always)]
    pub(crate) fn split(&self, t: f64) -> (Self, Self) {
        let n = self.pts.len();
        if self.h.is_empty() {
            let (mut l, mut r) = (
                SmallVec::from_elem(Point::default(), n),
                SmallVec::from_elem(Point::default(), n),
            );
            de_casteljau_split(&self.pts, t, &mut l, &mut r);
            (
                Self {
                    pts: l,
                    h: SmallVec::new(),
                },
                Self {
                    pts: r,
                    h: SmallVec::new(),
                },
            )
        } else {
            let (mut l, mut r) = (
                SmallVec::from_elem(Hpoint::default(), n),
                SmallVec::from_elem(Hpoint::default(), n),
            );
            de_casteljau_split(&self.h, t, &mut l, &mut r);
            let project = |h: SmallVec<[Hpoint; 4]>| Self {
                pts: h.iter().map(|h| h.project()).collect(),
                h,
            };
            let (mut left, mut right) = (project(l), project(r));
            left.pts[0] = self.pts[0];
            right.pts[n - 1] = self.pts[n - 1];
            right.pts[0] = left.pts[n - 1];
            (left, right)
        }
    }

    /// Its part on `[s0, s1]` (`0 <= s0 < s1 <= 1`), keeping the end points it shares with
    /// the curve bit for bit; `None` when the parameters are too close for the part to be cut
    /// off (the inner parameter rounds to 1).
    pub(crate) fn part(&self, s0: f64, s1: f64) -> Option<Self> {
        let right = if s0 > 0.0 {
            self.split(s0).1
        } else {
            self.clone()
        };
        if s1 >= 1.0 {
            return Some(right);
        }
        let t = (s1 - s0) / (1.0 - s0);
        (t > 0.0 && t < 1.0).then(|| right.split(t).0)
    }
}

/// Where the adaptive algorithm gets its sub-curves' tests: computed on the fly, or from a
/// precomputed hierarchy (see [`super::fast::CurveHierarchy`]).
pub(crate) trait SubCurves {
    /// A handle to one sub-curve.
    type Node;
    /// Its control points, borrowed or (from a compact store) copied out.
    type Points<'s>: std::ops::Deref<Target = [Point]>
    where
        Self: 's;
    /// Its control points.
    fn points<'s>(&'s self, node: &'s Self::Node) -> Self::Points<'s>;
    /// Its first and last control points (its ends).
    fn ends(&self, node: &Self::Node) -> (Point, Point) {
        let p = self.points(node);
        (p[0], p[p.len() - 1])
    }
    /// Its simple-convex flag, given whether its parent was simple and convex.
    fn convex(&self, node: &Self::Node, parent_convex: bool) -> bool;
    /// Is it exactly straight ([`is_linear`])?
    fn linear(&self, node: &Self::Node) -> bool {
        is_linear(&self.points(node))
    }
    /// Twice the signed area of its control polygon ([`polygon_area`]).
    fn area(&self, node: &Self::Node) -> f64 {
        polygon_area(&self.points(node))
    }
    /// Where `q` lies against its control bounding box, with `reach` (see [`Outside`]).
    fn outside_box(&self, node: &Self::Node, q: Point, reach: f64) -> Outside {
        let (lo, hi) = control_box(&self.points(node));
        outside_box_reach(lo, hi, q, reach)
    }
    /// Its signed crossing of the cut from the root of `y(t) = q.y`, for a small polynomial
    /// sub-curve ([`monotone_crossing`]); [`RootCrossing::NotMonotone`] for the others (the
    /// default: rational and higher-degree sub-curves).
    fn monotone_crossing(&self, _node: &Self::Node, _q: Point, _reach: f64) -> RootCrossing {
        RootCrossing::NotMonotone
    }
}

/// Sub-curves computed on demand, halves included.
pub(crate) struct OnTheFly;

impl SubCurves for OnTheFly {
    type Node = SubCurve;
    type Points<'s> = &'s [Point];
    fn points<'s>(&'s self, node: &'s SubCurve) -> &'s [Point] {
        node.points()
    }
    fn convex(&self, node: &SubCurve, parent_convex: bool) -> bool {
        parent_convex || is_simple_convex(node.points())
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
/// the depth cap. There is no tolerance: a point within rounding of the curve's interior but
/// not on it bit for bit may get either side's value. [`super::WindingField`] gives every
/// point within its boundary tolerance the average across the jump.
pub fn curve_winding_number(curve: &RationalBezier, q: Point, stats: &mut QueryStats) -> f64 {
    let mut sum = AngleSum::new(q);
    refine(SubCurve::of(curve), q, &mut sum, stats);
    sum.turns
}

/// The adaptive algorithm on `root` computed on the fly: sends `sink` the chords (and the
/// coincident pieces) whose angles at `q` add up to the curve's winding number.
pub(crate) fn refine<K: ChordSink>(root: SubCurve, q: Point, sink: &mut K, stats: &mut QueryStats) {
    stats.curve_evaluations += 1;
    let pts = root.points();
    let (lo, hi) = control_box(pts);
    let outside = outside_box_reach(lo, hi, q, sink.reach());
    if outside != Outside::No {
        if K::TRACKS_NEAR && outside == Outside::Near {
            sink.mark_near();
        }
        sink.chord(pts[0], pts[pts.len() - 1]);
        return;
    }
    refine_below(root, 0, false, q, sink, stats);
}

/// The adaptive algorithm from sub-curve `c` (at `depth`, its parent simple and convex or
/// not) down, its halves computed as needed.
pub(crate) fn refine_below<K: ChordSink>(
    c: SubCurve,
    depth: u32,
    parent_convex: bool,
    q: Point,
    sink: &mut K,
    stats: &mut QueryStats,
) {
    let state = (depth, parent_convex, true);
    match SmallPolynomial::of(&c) {
        Some(small) => walk(&OnTheFlySmall, small, state, q, sink, stats),
        None => walk(&OnTheFly, c, state, q, sink, stats),
    }
}

/// A polynomial sub-curve of at most [`SMALL`] control points, held by value: the walk on the
/// fly moves these instead of [`SubCurve`]s (whose two small vectors, the homogeneous one
/// unused, make every push and pop of the walk's stack a call to copy about 180 bytes).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SmallPolynomial {
    pts: [Point; SMALL],
    len: usize,
}

/// Control points of a [`SmallPolynomial`] at most (cubics).
pub(crate) const SMALL: usize = 4;

impl SmallPolynomial {
    /// `c` by value, if it is polynomial (no homogeneous points) and of degree below [`SMALL`].
    pub(crate) fn of(c: &SubCurve) -> Option<Self> {
        if !c.h.is_empty() {
            return None;
        }
        Self::from_points(c.points())
    }

    /// The polynomial sub-curve with control points `p`, if they are at most [`SMALL`] (and
    /// at least one).
    pub(crate) fn from_points(p: &[Point]) -> Option<Self> {
        if p.is_empty() || p.len() > SMALL {
            return None;
        }
        let mut pts = [Point::default(); SMALL];
        pts[..p.len()].copy_from_slice(p);
        Some(Self { pts, len: p.len() })
    }

    /// The sub-curve with the first `len` of `pts` as control points (`len` from 1 to
    /// [`SMALL`]).
    #[inline(always)]
    pub(crate) fn from_array(pts: [Point; SMALL], len: usize) -> Self {
        Self { pts, len }
    }

    /// Its control points.
    pub(crate) fn points(&self) -> &[Point] {
        &self.pts[..self.len]
    }
}

impl std::ops::Deref for SubCurve {
    type Target = [Point];
    fn deref(&self) -> &[Point] {
        self.points()
    }
}

impl std::ops::Deref for SmallPolynomial {
    type Target = [Point];
    fn deref(&self) -> &[Point] {
        self.points()
    }
}

/// The adaptive algorithm from the small polynomial sub-curve `c` down, with `state` as
/// [`walk`] takes it (its depth, whether its parent is simple and convex, whether it may be
/// settled by its root): [`refine_below`] on the same sub-curve.
pub(crate) fn refine_below_small<K: ChordSink>(
    c: SmallPolynomial,
    state: (u32, bool, bool),
    q: Point,
    sink: &mut K,
    stats: &mut QueryStats,
) {
    walk(&OnTheFlySmall, c, state, q, sink, stats);
}

/// A sub-curve the walk on the fly can halve.
pub(crate) trait Halve: Sized {
    /// Its halves by de Casteljau at `1/2`.
    fn halves(&self) -> (Self, Self);
}

impl Halve for SubCurve {
    fn halves(&self) -> (Self, Self) {
        SubCurve::halves(self)
    }
}

impl Halve for SmallPolynomial {
    /// The same split as [`SubCurve::split`] of a polynomial sub-curve at `1/2` (the same
    /// [`de_casteljau_split`] on the same points: the same halves, bit for bit).
    #[inline(always)]
    fn halves(&self) -> (Self, Self) {
        let n = self.len;
        let (mut l, mut r) = ([Point::default(); SMALL], [Point::default(); SMALL]);
        de_casteljau_split(&self.pts[..n], 0.5, &mut l[..n], &mut r[..n]);
        (Self { pts: l, len: n }, Self { pts: r, len: n })
    }
}

/// [`OnTheFly`] on [`SmallPolynomial`]s.
pub(crate) struct OnTheFlySmall;

impl SubCurves for OnTheFlySmall {
    type Node = SmallPolynomial;
    type Points<'s> = &'s [Point];
    fn points<'s>(&'s self, node: &'s SmallPolynomial) -> &'s [Point] {
        node.points()
    }
    fn convex(&self, node: &SmallPolynomial, parent_convex: bool) -> bool {
        parent_convex || is_simple_convex(node.points())
    }
    #[inline(always)]
    fn monotone_crossing(&self, node: &SmallPolynomial, q: Point, reach: f64) -> RootCrossing {
        monotone_crossing(node.points(), q, reach)
    }
}

/// The adaptive algorithm from `c` down on the fly: depth-first, the left half first, at most
/// one pending right half per level (on the stack for any query not within `2^-32` of the
/// piece's size from it).
///
/// `(depth, parent_convex, roots)`: `c`'s depth, whether its parent is simple and convex, and
/// whether it may be settled by its root ([`settle_by_root`]).
#[inline(always)]
pub(crate) fn walk<S: SubCurves, K: ChordSink>(
    source: &S,
    c: S::Node,
    (depth, parent_convex, roots): (u32, bool, bool),
    q: Point,
    sink: &mut K,
    stats: &mut QueryStats,
) where
    S::Node: Halve,
{
    let mut stack: SmallVec<[Pending<S::Node>; 32]> = SmallVec::new();
    let mut next = Some((c, depth, parent_convex, roots));
    while let Some((c, depth, parent_convex, roots)) = next.take().or_else(|| stack.pop()) {
        if depth > 0 {
            stats.curve_evaluations += 1;
        }
        if let Some(convex) = settle(source, &c, q, depth, parent_convex, sink) {
            let Some(roots) = settle_by_root(source, &c, q, roots, sink) else {
                continue;
            };
            let (l, r) = c.halves();
            stats.subdivisions += 1;
            // Sub-curves of a simple convex curve are simple and convex (paper, section 5).
            // The left half next, the right one after all of the left's sub-curves.
            stack.push((r, depth + 1, convex, roots));
            next = Some((l, depth + 1, convex, roots));
        }
    }
}

/// A sub-curve a walk has still to visit ([`walk`], and the fast field's walk down a cached
/// hierarchy, by index): it, its depth, whether its parent is simple and convex, and whether
/// it may be settled by its root.
pub(crate) type Pending<N> = (N, u32, bool, bool);

/// After [`settle`] opened sub-curve `c`, for a sink that takes crossings whole
/// ([`ChordSink::COUNTS_CROSSINGS`]) and with `roots` true: its crossing from its root
/// ([`monotone_crossing`]), sent to `sink` (`None`: settled). Otherwise `Some` of whether its
/// halves may ask in turn: not once the query was found too near where it meets the query's
/// height, as theirs is the same place.
#[inline(always)]
pub(crate) fn settle_by_root<S: SubCurves, K: ChordSink>(
    source: &S,
    c: &S::Node,
    q: Point,
    roots: bool,
    sink: &mut K,
) -> Option<bool> {
    if !(K::COUNTS_CROSSINGS && roots) {
        return Some(roots);
    }
    match source.monotone_crossing(c, q, sink.reach()) {
        RootCrossing::Decided(k) => {
            sink.crossings(k);
            None
        }
        RootCrossing::TooNear => Some(false),
        RootCrossing::NotMonotone => Some(true),
    }
}

/// One step of the adaptive algorithm on sub-curve `c` of `source` at `depth`: sends `sink`
/// its contribution and returns `None` when it is settled (straight; `q` at an end of a
/// simple convex piece; `q` outside its box or its simple convex control polygon; the depth
/// cap), or returns whether it is simple and convex when it must be halved.
#[inline(always)]
pub(crate) fn settle<S: SubCurves, K: ChordSink>(
    source: &S,
    c: &S::Node,
    q: Point,
    depth: u32,
    parent_convex: bool,
    sink: &mut K,
) -> Option<bool> {
    // Every exit but the last tells `sink` whether `q` may be near the sub-curve: only then
    // may `q` be in a boundary band round the curve.
    //
    // The tests in the paper's order are: straight (the chord; near if `near_line`), `q` at an
    // end of a simple convex sub-curve, outside the box (the chord; near if within the
    // reach). A `q` outside the box is at neither end (both lie in it), and `near_line` is
    // false for a `q` outside the box grown by the reach; so for such a `q` every order sends
    // the same chord and the same mark, and the box, the cheapest test, goes first: the
    // sub-curves it settles (most of a walk's) skip the straightness and convexity tests, and
    // need only their ends besides the box.
    let outside = source.outside_box(c, q, sink.reach());
    if outside != Outside::No {
        if K::TRACKS_NEAR
            && outside == Outside::Near
            && (!source.linear(c) || near_line(&source.points(c), q, sink.reach()))
        {
            sink.mark_near();
        }
        let (a, b) = source.ends(c);
        sink.chord(a, b);
        return None;
    }
    let p = source.points(c);
    let p: &[Point] = &p;
    let (a, b) = (p[0], p[p.len() - 1]);
    if source.linear(c) {
        if K::TRACKS_NEAR && near_line(p, q, sink.reach()) {
            sink.mark_near();
        }
        sink.chord(a, b);
        return None;
    }
    let convex = source.convex(c, parent_convex);
    if convex && (q == a || q == b) {
        sink.mark_near();
        sink.special(convex_endpoint_winding(p, q), a, b);
        return None;
    }
    if convex {
        let hull = outside_convex(p, source.area(c), q, sink.reach());
        if hull != Outside::No {
            if K::TRACKS_NEAR && hull == Outside::Near {
                sink.mark_near();
            }
            sink.chord(a, b);
            return None;
        }
    }
    if depth >= MAX_DEPTH {
        // q is within rounding of this tiny piece: coincident, average 0 over the piece.
        sink.mark_near();
        sink.special(0.0, a, b);
        return None;
    }
    Some(convex)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The edge tests with the first edge found outside by more than `reach` returned at once
    /// (the loop `outside_convex` had before it tested every edge).
    fn first_far(p: &[Point], area: f64, q: Point, reach: f64) -> Outside {
        let n = p.len();
        let mut seen = Outside::No;
        for i in 0..n {
            let (a, b) = (p[i], p[if i + 1 == n { 0 } else { i + 1 }]);
            let (e, d) = (b - a, q - a);
            let c = e.cross(d);
            let rounding = 4.0 * f64::EPSILON;
            if area * c < 0.0 && c * c > rounding * rounding * e.dot(e) * d.dot(d) {
                if c * c > reach * reach * e.dot(e) {
                    return Outside::Far;
                }
                seen = Outside::Near;
            }
        }
        seen
    }

    /// Testing every edge gives the answer of stopping at the first far one, on convex
    /// polygons of 3, 4 and 6 points (the arrays and the general loop) at queries inside, on
    /// the edges' lines, just outside, within and beyond the reach.
    #[test]
    fn every_edge_tested_gives_the_first_far_edges_answer() {
        let mut seed = 5u64;
        let mut unit = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut seen = [0usize; 3];
        for n in [3usize, 4, 6] {
            for _ in 0..2000 {
                // A convex polygon: points on an ellipse at increasing angles.
                let (rx, ry, turn) = (0.5 + unit(), 0.5 + unit(), unit());
                let p: Vec<Point> = (0..n)
                    .map(|k| {
                        let t = std::f64::consts::TAU * (k as f64 + turn * 0.9) / n as f64;
                        Point::new(rx * t.cos(), ry * t.sin())
                    })
                    .collect();
                let area = polygon_area(&p);
                for _ in 0..20 {
                    let k = (unit() * n as f64) as usize % n;
                    let (a, b) = (p[k], p[(k + 1) % n]);
                    let along = a + (b - a) * unit();
                    let step = [0.0, 1e-17, 1e-9, 1e-3, 0.3][(unit() * 5.0) as usize % 5];
                    let normal = Point::new(b.y - a.y, a.x - b.x) * (step * area.signum());
                    for q in [
                        along + normal,
                        along - normal,
                        Point::new(unit() - 0.5, unit() - 0.5),
                    ] {
                        for reach in [0.0, 1e-6, 0.1] {
                            let want = first_far(&p, area, q, reach);
                            assert_eq!(outside_convex(&p, area, q, reach), want, "{p:?} {q:?}");
                            seen[want as usize] += 1;
                        }
                    }
                }
            }
        }
        assert!(seen.iter().all(|&k| k > 1000), "{seen:?}");
    }
}
