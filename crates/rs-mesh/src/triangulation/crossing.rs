//! Certified crossings of two boundary arcs: a point where they certainly meet, shown by
//! their control polygons and closed in on by halving. A boundary that crosses itself is
//! reported there instead of being split without end.

use rs_spline::prelude::*;
use rs_spline::{NurbsCurve, Point};

/// A point where two curves certainly meet, if their control polygons show it
/// ([`rs_spline::certain_crossing`] with a margin of `1e-9 size`, above any rounding here).
/// Curves that share an end are never certified.
fn arcs_certainly_meet(p: &NurbsCurve, q: &NurbsCurve, size: f64) -> Option<Point> {
    rs_spline::certain_crossing(p.control_points(), q.control_points(), 1e-9 * size)
}

/// Halvings of two certainly meeting arcs ([`where_arcs_meet`]) to close in on where.
const MEETING_HALVINGS: usize = 40;

/// A point where two arcs certainly meet ([`arcs_certainly_meet`]), closed in on by halving
/// both and keeping a pair of halves that still certainly meets, up to
/// [`MEETING_HALVINGS`] times (until no pair is certain: the meeting point is then near a
/// half's end).
pub(super) fn where_arcs_meet(p: NurbsCurve, q: NurbsCurve, size: f64) -> Option<Point> {
    let mut near = arcs_certainly_meet(&p, &q, size)?;
    let (mut p, mut q) = (p, q);
    for _ in 0..MEETING_HALVINGS {
        let (ps, qs) = (p.subdivide(), q.subdivide());
        let (ps, qs) = ([ps.0, ps.1], [qs.0, qs.1]);
        let Some((x, i, j)) = (0..4).find_map(|k| {
            let (i, j) = (k / 2, k % 2);
            arcs_certainly_meet(&ps[i], &qs[j], size).map(|x| (x, i, j))
        }) else {
            break;
        };
        near = x;
        let [p0, p1] = ps;
        let [q0, q1] = qs;
        p = if i == 0 { p0 } else { p1 };
        q = if j == 0 { q0 } else { q1 };
    }
    Some(near)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Segments and arcs that cross are certified, with the crossing found by halving;
    /// ends touching the other curve, shared ends, parallel and missing pairs are not.
    #[test]
    fn arcs_certainly_meet_only_when_their_polygons_show_it() {
        let seg = |a: (f64, f64), b: (f64, f64)| {
            rs_spline::segment(Point::new(a.0, a.1), Point::new(b.0, b.1)).unwrap()
        };
        let x = arcs_certainly_meet(
            &seg((0.0, 0.0), (2.0, 2.0)),
            &seg((0.0, 2.0), (2.0, 0.0)),
            2.0,
        );
        assert_eq!(x, Some(Point::new(1.0, 1.0)));
        // An arc of the unit circle across y = 1/2: they meet at (cos 30°, sin 30°).
        let arc = rs_spline::circle(Point::new(0.0, 0.0), 1.0)
            .unwrap()
            .subsegment((0.05, 0.11))
            .unwrap();
        assert!(arc.start_point().y < 0.5 && arc.end_point().y > 0.5);
        let line = seg((0.0, 0.5), (2.0, 0.5));
        let coarse = arcs_certainly_meet(&arc, &line, 2.0);
        let fine = where_arcs_meet(arc.clone(), line.clone(), 2.0).unwrap();
        let exact = Point::new(0.75f64.sqrt(), 0.5);
        assert!(
            coarse.is_some() && fine.distance(exact) < 1e-12,
            "{coarse:?} {fine:?}"
        );
        for (p, q) in [
            (seg((0.0, 0.0), (2.0, 2.0)), seg((2.0, 2.0), (4.0, 0.0))), // a shared end
            (seg((0.0, 0.0), (2.0, 0.0)), seg((1.0, 0.0), (1.0, 1.0))), // an end on the other
            (seg((0.0, 0.0), (2.0, 0.0)), seg((0.0, 1.0), (2.0, 1.0))), // parallel
            (seg((0.0, 0.0), (1.0, 1.0)), seg((2.0, 0.0), (3.0, -1.0))), // apart
        ] {
            assert_eq!(arcs_certainly_meet(&p, &q, 4.0), None);
            assert_eq!(where_arcs_meet(p, q, 4.0), None);
        }
        // An arc whose bulge reaches past the other's end: not certain, though it may meet.
        let bulge = rs_spline::circle(Point::new(0.0, 0.0), 1.0)
            .unwrap()
            .subsegment((0.0, 0.5))
            .unwrap();
        assert_eq!(
            arcs_certainly_meet(&bulge, &seg((0.0, 0.5), (0.0, 2.0)), 2.0),
            None
        );
    }
}
