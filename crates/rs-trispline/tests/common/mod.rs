//! Helpers shared by the spline integration tests.

use rs_mesh::{CurvedTriangulation, well_spaced_points};
use rs_spline::Point;
use rs_spline::prelude::*;

/// Points of the domain: well-spaced ones (interior and boundary) and points between every
/// curved boundary arc and its chord (for an arc of a hole, that point lies in the hole).
pub(crate) fn test_points(m: &CurvedTriangulation) -> Vec<Point> {
    let mut pts = well_spaced_points(m.domain(), 23).unwrap().all_points();
    for a in m.arcs() {
        let c = m.arc_curve(a).unwrap();
        let (u0, u1) = c.param_range();
        let on = c.point_at(0.5 * (u0 + u1));
        let chord_mid = (m.vertices()[a.from] + m.vertices()[a.to]) * 0.5;
        pts.push(on * 0.9 + chord_mid * 0.1);
    }
    pts
}
