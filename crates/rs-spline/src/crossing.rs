//! Certified crossings of two curves, shown by their control polygons alone.

use crate::Point;

/// Where two curves certainly cross, shown by their control points `p` and `q` alone (the
/// curves have positive weights, so each lies in the convex hull of its control points), or
/// `None` when the control points do not show it.
///
/// Each curve lies in the slab of its control points round its chord (the line through its
/// first and last control points, as wide as the farthest control point), grown by `margin`
/// (above any rounding of the control points). If each curve's ends lie outside the other's
/// slab on opposite sides, then within the parallelogram where the slabs overlap one curve
/// joins two opposite sides and the other the two others, so the curves meet, and the second
/// passes from one side of the first to the other. The point returned, where the chords
/// cross, lies in that parallelogram. Curves that share an end are never certified (the end
/// lies in both slabs), nor is a curve whose ends coincide.
///
/// # Examples
///
/// ```
/// use rs_spline::{Point, certain_crossing};
/// let p = |x, y| Point::new(x, y);
/// // The two diagonals of a square cross at its centre.
/// let x = certain_crossing(&[p(0.0, 0.0), p(2.0, 2.0)], &[p(0.0, 2.0), p(2.0, 0.0)], 1e-9);
/// assert_eq!(x, Some(p(1.0, 1.0)));
/// // An end on the other curve is not certified.
/// assert_eq!(certain_crossing(&[p(0.0, 0.0), p(2.0, 0.0)], &[p(1.0, 0.0), p(1.0, 1.0)], 1e-9), None);
/// ```
pub fn certain_crossing(p: &[Point], q: &[Point], margin: f64) -> Option<Point> {
    // The unit normal of a chord, its slab's half-width, and its ends.
    let slab = |pts: &[Point]| {
        let (a, b) = (*pts.first()?, *pts.last()?);
        let len = a.distance(b);
        if len.is_nan() || len <= 0.0 {
            return None;
        }
        let n = (b - a).perp() / len;
        let half = pts.iter().fold(0.0f64, |m, &x| m.max(n.dot(x - a).abs()));
        Some((n, half + margin, a, b))
    };
    let (n1, w1, a, b) = slab(p)?;
    let (n2, w2, c, d) = slab(q)?;
    let across = |n: Point, w: f64, o: Point, x: Point, y: Point| {
        let (sx, sy) = (n.dot(x - o), n.dot(y - o));
        (sx > w && sy < -w) || (sx < -w && sy > w)
    };
    if !(across(n2, w2, c, a, b) && across(n1, w1, a, c, d)) {
        return None;
    }
    // The chords cross (their ends are on opposite sides of each other's line): where.
    let (r, s) = (b - a, d - c);
    let t = (c - a).cross(s) / r.cross(s);
    Some(a + r * t)
}

/// Where two curves that certainly cross ([`certain_crossing`] of their control points, with
/// `margin`) meet, closed in on by halving: each step halves both curves and keeps the first
/// pair of parts, searched down to three more halvings (parts whose control boxes
/// part are skipped), that still certainly crosses; at most `halvings` halvings in all. It stops
/// where no such pair is found (the crossing is then tangent-like at that scale), and the
/// point returned, where the last certain pair's chords cross, lies within that pair's size of
/// the crossing. `None` if the two do not certainly cross.
///
/// # Examples
///
/// ```
/// use rs_spline::{circle, closed_in_crossing, segment, Point, RationalBezier};
/// use rs_spline::prelude::*;
/// // An arc of the unit circle across y = 1/2 meets it at (cos 30°, sin 30°).
/// let arc = circle(Point::new(0.0, 0.0), 1.0).unwrap().subsegment((0.05, 0.11)).unwrap();
/// let line = segment(Point::new(0.0, 0.5), Point::new(2.0, 0.5)).unwrap();
/// let x = closed_in_crossing(arc, line, 1e-9, 40, |c| c.control_points()).unwrap();
/// assert!(x.distance(Point::new(0.75f64.sqrt(), 0.5)) < 1e-12);
/// ```
pub fn closed_in_crossing<C: crate::ParamCurve + Clone>(
    p: C,
    q: C,
    margin: f64,
    halvings: usize,
    control_points: impl Fn(&C) -> &[Point] + Copy,
) -> Option<Point> {
    let mut near = certain_crossing(control_points(&p), control_points(&q), margin)?;
    let (mut p, mut q) = (p, q);
    let mut done = 0;
    while done < halvings {
        let depth = CLOSING_DEPTH.min(halvings - done - 1);
        let Some((a, b, x, levels)) = certain_part(&p, &q, margin, depth, control_points) else {
            break;
        };
        (p, q, near) = (a, b, x);
        done += levels;
    }
    Some(near)
}

/// How many halvings deeper than the next one [`closed_in_crossing`] looks for a certain pair.
const CLOSING_DEPTH: usize = 3;

/// The first pair of parts of `p` and `q` one halving down, or up to `depth` more, that
/// certainly crosses: the parts, the crossing point of their chords and the halvings taken.
fn certain_part<C: crate::ParamCurve + Clone>(
    p: &C,
    q: &C,
    margin: f64,
    depth: usize,
    control_points: impl Fn(&C) -> &[Point] + Copy,
) -> Option<(C, C, Point, usize)> {
    let boxes_meet = |a: &C, b: &C| {
        let bound = |c: &C| crate::BoundingBox::from_points(control_points(c).iter().copied());
        match (bound(a), bound(b)) {
            (Some(x), Some(y)) => x.grown_by(margin).overlaps(&y),
            _ => false,
        }
    };
    let (p0, p1) = p.subdivide();
    let (q0, q1) = q.subdivide();
    for (a, b) in [(&p0, &q0), (&p0, &q1), (&p1, &q0), (&p1, &q1)] {
        if !boxes_meet(a, b) {
            continue;
        }
        if let Some(x) = certain_crossing(control_points(a), control_points(b), margin) {
            return Some((a.clone(), b.clone(), x, 1));
        }
        if depth > 0
            && let Some((c, d, x, levels)) = certain_part(a, b, margin, depth - 1, control_points)
        {
            return Some((c, d, x, levels + 1));
        }
    }
    None
}
