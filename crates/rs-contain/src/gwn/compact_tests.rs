//! The compact walks (a polynomial piece's hierarchy in cache lines, sub-curves of at most four
//! control points moved by value) against the walks they replace: the same chords and special
//! values in the same order, so the same sums bit for bit, and the same near marks.

use rs_spline::prelude::*;
use rs_spline::{Point, RationalBezier};

use super::QueryStats;
use super::curve::{OnTheFly, SubCurve, refine_below, walk};
use super::fast::CurveHierarchy;
use super::sum::WindingSum;

/// Polynomial pieces of 2 to 4 control points: straight, bent, an S, a loop, a cusp, one with
/// repeated control points, and one far from the origin.
fn pieces() -> Vec<RationalBezier> {
    let p = |x: f64, y: f64| Point::new(x, y);
    let poly = |pts: Vec<Point>| {
        let n = pts.len();
        RationalBezier::new(pts, vec![1.0; n]).expect("valid piece")
    };
    vec![
        poly(vec![p(0.0, 0.0), p(1.0, 0.5)]),
        poly(vec![p(0.0, 0.0), p(0.5, 1.0), p(1.0, 0.0)]),
        poly(vec![p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0), p(1.0, 0.0)]),
        poly(vec![p(0.0, 0.0), p(2.0, 1.0), p(-1.0, 1.0), p(1.0, 0.0)]),
        poly(vec![p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0), p(1.0, 0.0)]),
        poly(vec![p(0.0, 0.0), p(0.0, 0.0), p(1.0, 1.0), p(1.0, 1.0)]),
        poly(vec![
            p(1e6, 1e6),
            p(1e6 + 3.0, 1e6 + 1.0),
            p(1e6 + 1.0, 1e6 + 2.0),
            p(1e6 + 2.0, 1e6 - 1.0),
        ]),
    ]
}

/// Queries about `b`: a grid over its box grown by a quarter, its control points, points of
/// the curve, and points at `1e-12..1e-2` of its size off the curve on both sides.
fn queries(b: &RationalBezier) -> Vec<Point> {
    let pts = b.control_points();
    let (mut lo, mut hi) = (pts[0], pts[0]);
    for q in pts {
        lo = Point::new(lo.x.min(q.x), lo.y.min(q.y));
        hi = Point::new(hi.x.max(q.x), hi.y.max(q.y));
    }
    let size = (hi.x - lo.x).max(hi.y - lo.y).max(1e-300);
    let mut out: Vec<Point> = pts.to_vec();
    for i in 0..=24 {
        for j in 0..=24 {
            let (u, v) = (i as f64 / 24.0 * 1.5 - 0.25, j as f64 / 24.0 * 1.5 - 0.25);
            out.push(Point::new(lo.x + u * size, lo.y + v * size));
        }
    }
    let (t0, t1) = b.param_range();
    for k in 0..=256 {
        let t = t0 + (t1 - t0) * k as f64 / 256.0;
        let (q, d) = b.point_and_tangent(t);
        out.push(q);
        let len = d.x.hypot(d.y);
        if len > 0.0 {
            for e in [1e-12, 1e-9, 1e-6, 1e-4, 1e-2] {
                let s = e * size / len;
                out.push(Point::new(q.x - s * d.y, q.y + s * d.x));
                out.push(Point::new(q.x + s * d.y, q.y - s * d.x));
            }
        }
    }
    out
}

/// The sum's bits and its near mark.
fn outcome(sum: &WindingSum) -> (u64, bool) {
    (sum.value().to_bits(), sum.near())
}

/// The walk on the fly from a piece's root by value ([`refine_below`], which takes a small
/// polynomial piece by value) and by [`SubCurve`] (the walk it replaces).
#[test]
fn small_walk_on_the_fly_matches_the_sub_curve_walk() {
    for b in pieces() {
        let reach = 1e-9;
        for q in queries(&b) {
            let (mut small, mut general) = (
                WindingSum::tracking(q, reach),
                WindingSum::tracking(q, reach),
            );
            let (mut s1, mut s2) = (QueryStats::default(), QueryStats::default());
            refine_below(SubCurve::of(&b), 0, false, q, &mut small, &mut s1);
            walk(
                &OnTheFly,
                SubCurve::of(&b),
                (0, false, true),
                q,
                &mut general,
                &mut s2,
            );
            assert_eq!(outcome(&small), outcome(&general), "{b:?} at {q:?}");
            assert_eq!(s1, s2, "{b:?} at {q:?}");
        }
    }
}

/// A polynomial piece's compact hierarchy and the general one (every sub-curve a
/// [`SubCurve`]) of the same piece, and the walk on the fly from its root: the same sums bit
/// for bit and the same near marks.
#[test]
fn compact_hierarchy_matches_the_general_one_and_the_walk_on_the_fly() {
    for b in pieces() {
        let compact = CurveHierarchy::new(&b);
        assert!(compact.is_compact(), "{b:?}");
        let general = CurveHierarchy::general_of(&b);
        assert!(!general.is_compact());
        for reach in [0.0, 1e-9, 1e-3] {
            for q in queries(&b) {
                let mut sums = [WindingSum::tracking(q, reach); 3];
                let mut stats = [QueryStats::default(); 3];
                compact.refine(q, &mut sums[0], &mut stats[0]);
                general.refine(q, &mut sums[1], &mut stats[1]);
                stats[2].curve_evaluations += 1;
                walk(
                    &OnTheFly,
                    SubCurve::of(&b),
                    (0, false, true),
                    q,
                    &mut sums[2],
                    &mut stats[2],
                );
                assert_eq!(outcome(&sums[0]), outcome(&sums[1]), "{b:?} at {q:?}");
                assert_eq!(outcome(&sums[0]), outcome(&sums[2]), "{b:?} at {q:?}");
                assert_eq!(stats[0], stats[1], "{b:?} at {q:?}");
            }
        }
    }
}
