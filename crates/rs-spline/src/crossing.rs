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
