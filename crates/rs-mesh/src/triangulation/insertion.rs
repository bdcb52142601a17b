//! Where an arc that fails the convertibility test gets its new boundary point: at a corner
//! of its curve inside it (a joint of Bezier pieces where the tangent turns) if there is one,
//! else at its parameter midpoint.

use rs_spline::prelude::*;
use rs_spline::{Domain, Point};

use crate::boundary::BoundaryPoint;

/// Two tangent directions whose angle has a sine above this (or that point apart) make a
/// corner: far above the rounding of a joint that is smooth in exact arithmetic, and only
/// ever used to choose where a failing arc is split, so a false corner costs one point.
const CORNER_SINE: f64 = 1e-9;

/// The parameters, ascending, of each curve's corners: the joints of consecutive Bezier
/// pieces where the tangent directions of the two pieces differ (a break point of a polygon
/// written as one curve, a knot of full multiplicity, repeated control points). A corner is
/// scale-invariant: every arc across it, however short, turns by the corner's angle, so
/// splitting such an arc at its parameter midpoint never straightens it; only a vertex at
/// the corner does.
pub(super) fn curve_corners(domain: &Domain) -> Vec<Vec<f64>> {
    domain
        .curves()
        .iter()
        .map(|c| {
            let pieces = c.to_bezier();
            pieces
                .windows(2)
                .filter_map(|w| {
                    let (p, q) = (w[0].control_points(), w[1].control_points());
                    let (last, before) = p.split_last()?;
                    let (first, after) = q.split_first()?;
                    // Both directions pointing along the curve.
                    let d1 = -away(*last, before.iter().rev())?;
                    let d2 = away(*first, after.iter())?;
                    let scale = d1.length() * d2.length();
                    let corner = d1.dot(d2) <= 0.0 || d1.cross(d2).abs() > CORNER_SINE * scale;
                    corner.then_some(w[1].knot_span().0)
                })
                .collect()
        })
        .collect()
}

/// From an end point of a piece towards the first of its other control points (listed from
/// that end) that differs from it: the tangent direction there, up to sign (the lower
/// derivatives vanish where control points repeat; positive weights keep the direction).
fn away<'a>(end: Point, mut others: impl Iterator<Item = &'a Point>) -> Option<Point> {
    others.find(|&&q| q != end).map(|&q| q - end)
}

/// Where to split the failing arc `(u0, u1)` of a curve with `corners` (ascending): at the
/// corner strictly inside it nearest its parameter midpoint, else at that midpoint.
fn split_parameter(corners: &[f64], u0: f64, u1: f64) -> f64 {
    let mid = 0.5 * (u0 + u1);
    let (i, j) = (
        corners.partition_point(|&c| c <= u0),
        corners.partition_point(|&c| c < u1),
    );
    corners
        .get(i..j)
        .unwrap_or_default()
        .iter()
        .copied()
        .min_by(|a, b| (a - mid).abs().total_cmp(&(b - mid).abs()))
        .unwrap_or(mid)
}

/// New boundary points: every failing arc gets one, at a corner of the curve inside it if
/// there is one ([`curve_corners`], [`split_parameter`]), else at its parameter midpoint
/// (away from corners an arc turns less, relative to its chord, the shorter it is). Returns the refined loops and the
/// number of points added (one per distinct failing arc), in one pass over each loop.
pub(super) fn refine_loops(
    domain: &Domain,
    corners: &[Vec<f64>],
    boundary: &[Vec<BoundaryPoint>],
    failing: &[(usize, usize)],
) -> (Vec<Vec<BoundaryPoint>>, usize) {
    let mut split: Vec<Vec<usize>> = vec![Vec::new(); boundary.len()];
    for &(j, k) in failing {
        split[j].push(k);
    }
    let mut added = 0;
    let out = boundary
        .iter()
        .zip(split)
        .enumerate()
        .map(|(j, (l, mut ks))| {
            ks.sort_unstable();
            ks.dedup();
            added += ks.len();
            let mut out = Vec::with_capacity(l.len() + ks.len());
            let mut ks = ks.into_iter().peekable();
            for (k, &pa) in l.iter().enumerate() {
                out.push(pa);
                if ks.next_if_eq(&k).is_none() {
                    continue;
                }
                let pb = l[(k + 1) % l.len()];
                let c = &domain.curves()[pa.curve];
                let u1 = if pb.curve == pa.curve && pb.u > pa.u {
                    pb.u
                } else {
                    c.param_range().1
                };
                let u = split_parameter(&corners[pa.curve], pa.u, u1);
                out.push(BoundaryPoint {
                    loop_index: j,
                    curve: pa.curve,
                    u,
                    point: c.point_at(u),
                });
            }
            out
        })
        .collect();
    (out, added)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::NurbsCurve;

    /// Corners: the joints where a curve turns (a polyline's vertices, a square written as
    /// one quadratic with repeated knots and control points), not the smooth joints of a
    /// rational circle; a failing arc is split at the corner inside it nearest its midpoint,
    /// never at one of its ends, else at its midpoint.
    #[test]
    fn failing_arcs_are_split_at_their_corners() {
        let q = Point::new;
        let square = [
            q(0.0, 0.0),
            q(1.0, 0.0),
            q(1.0, 1.0),
            q(0.0, 1.0),
            q(0.0, 0.0),
        ];
        let polyline = rs_spline::polyline(&square).unwrap();
        // Each side a quadratic with its midpoint as middle control point, corners repeated.
        let mut points = Vec::new();
        for w in square.windows(2) {
            points.extend([w[0], (w[0] + w[1]) * 0.5, w[1]]);
        }
        let mut knots = vec![0.0; 3];
        for k in 1..4 {
            knots.extend([f64::from(k); 3]);
        }
        knots.extend([4.0; 3]);
        let quadratic = NurbsCurve::new(2, knots, points, None).unwrap();
        // A smooth joint between two straight pieces: not a corner.
        let straight = rs_spline::polyline(&[q(0.0, 0.0), q(1.0, 1.0), q(3.0, 3.0)]).unwrap();
        let circle = rs_spline::circle(q(0.0, 0.0), 1.0).unwrap();
        let domain = Domain::new(vec![polyline, quadratic, circle]).unwrap();
        assert_eq!(
            curve_corners(&domain),
            vec![vec![1.0, 2.0, 3.0], vec![1.0, 2.0, 3.0], vec![]]
        );
        let line = Domain::new(vec![
            straight,
            rs_spline::polyline(&[q(3.0, 3.0), q(3.0, 0.0), q(0.0, 0.0)]).unwrap(),
        ]);
        assert_eq!(curve_corners(&line.unwrap())[0], Vec::<f64>::new());
        let corners = [1.0, 2.0, 3.0];
        assert_eq!(split_parameter(&corners, 0.0, 4.0), 2.0);
        assert_eq!(split_parameter(&corners, 0.5, 2.9), 2.0);
        assert_eq!(split_parameter(&corners, 1.0, 2.0), 1.5);
        assert_eq!(split_parameter(&corners, 2.5, 2.75), 2.625);
        assert_eq!(split_parameter(&[], 0.0, 1.0), 0.5);
    }
}
