//! Certified crossings of two boundary arcs: a point where they certainly meet, shown by
//! their control polygons and closed in on by halving. A boundary that crosses itself is
//! reported there instead of being split without end.

use rs_spline::{Domain, NurbsCurve, Point};

use crate::MeshError;

/// The margin of the certificates on arcs: `1e-9` of the domain's size, above any rounding.
const RELATIVE_MARGIN: f64 = 1e-9;

/// Halvings of two certainly meeting arcs ([`where_arcs_meet`]) to close in on where.
const MEETING_HALVINGS: usize = 40;

/// A point where two arcs certainly meet (their control polygons show it:
/// [`rs_spline::certain_crossing`]; arcs that share an end are never certified), closed in on
/// by halving both ([`rs_spline::closed_in_crossing`], at most [`MEETING_HALVINGS`] times).
pub(super) fn where_arcs_meet(p: NurbsCurve, q: NurbsCurve, size: f64) -> Option<Point> {
    rs_spline::closed_in_crossing(p, q, RELATIVE_MARGIN * size, MEETING_HALVINGS, |c| {
        c.control_points()
    })
}

/// Refuses a boundary whose loops cross each other or themselves (a figure eight) before any
/// triangle is built: no curved triangulation has both crossing arcs as edges, and building
/// one anyway gives arcs that miss their vertices. Touching loops are left to the
/// triangulation, which names them.
///
/// # Errors
/// [`MeshError::BoundaryCrosses`] where the loops cross ([`rs_contain::boundary_crossing`]);
/// [`MeshError::Boxes`] if the boundary cannot be cut into monotone pieces.
pub(crate) fn check_no_crossing(domain: &Domain) -> Result<(), MeshError> {
    match rs_contain::boundary_crossing(domain)? {
        Some(crossing) => Err(MeshError::BoundaryCrosses {
            near: crossing.near,
        }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::prelude::*;

    /// Whether two arcs certainly meet, without closing in.
    fn arcs_certainly_meet(p: &NurbsCurve, q: &NurbsCurve, size: f64) -> Option<Point> {
        rs_spline::certain_crossing(
            p.control_points(),
            q.control_points(),
            RELATIVE_MARGIN * size,
        )
    }

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
