//! SVG elliptical arcs (endpoint form) as exact rational quadratic NURBS.

use std::f64::consts::{PI, TAU};

use rs_spline::limits::MAX_COORDINATE;
use rs_spline::{NurbsCurve, Point, SplineError, elliptic_arc};

use crate::builder::with_end_points;

/// A chord shorter than this fraction of the smaller radius has no computable sagitta.
const DEGENERATE_CHORD: f64 = 1e-15;
/// A sweep this close to a full turn is a half-turn measured across the branch cut.
const HALF_TURN_ROUNDING: f64 = 1e-12;

/// What an SVG arc command draws.
#[derive(Debug)]
pub(crate) enum ArcSegment {
    /// The end point equals the start: the command draws nothing.
    Nothing,
    /// A zero radius: the command is a straight line to the end point.
    Line,
    /// An elliptical arc, exact, from the start point to the end point (bit-exact ends).
    Curve(NurbsCurve),
}

/// Converts the SVG arc from `p0` to `p1` with radii `rx`, `ry`, x-axis rotation `phi_deg`
/// (degrees) and the two flags to centre form, following the SVG implementation notes
/// (F.6.5 conversion, F.6.6 out-of-range radii: radii too small to reach `p1` are scaled up
/// uniformly), then to [`elliptic_arc`], whose conic form is exact. The curve's ends are set
/// to `p0` and `p1` exactly so the path stays watertight.
///
/// With `u = R(-phi) (p0 - p1) / 2`, the centre in the rotated frame is
/// `c' = +-sqrt((rx^2 ry^2 - rx^2 u_y^2 - ry^2 u_x^2) / (rx^2 u_y^2 + ry^2 u_x^2)) (rx u_y / ry, -ry u_x / rx)`,
/// the sign `+` when `large_arc != sweep`.
pub(crate) fn endpoint_arc(
    p0: Point,
    rx: f64,
    ry: f64,
    phi_deg: f64,
    large_arc: bool,
    sweep: bool,
    p1: Point,
) -> Result<ArcSegment, SplineError> {
    if p0 == p1 {
        return Ok(ArcSegment::Nothing);
    }
    let (mut rx, mut ry) = (rx.abs(), ry.abs());
    if rx == 0.0 || ry == 0.0 {
        return Ok(ArcSegment::Line);
    }
    if rx.max(ry) > MAX_COORDINATE || rx.is_nan() || ry.is_nan() {
        return Err(SplineError::LimitExceeded {
            what: "arc radius",
            value: rx.max(ry),
            limit: MAX_COORDINATE,
        });
    }
    if !phi_deg.is_finite() {
        return Err(SplineError::InvalidPrimitive {
            what: "x-axis rotation",
            value: phi_deg,
        });
    }
    let phi = (phi_deg % 360.0).to_radians();
    let (s, c) = phi.sin_cos();
    // The centre conversion multiplies four lengths: work in units of the larger radius so
    // that nothing overflows or underflows, and scale the centre back at the end.
    let unit = rx.max(ry);
    rx /= unit;
    ry /= unit;
    let (hx, hy) = (0.5 * (p0.x - p1.x) / unit, 0.5 * (p0.y - p1.y) / unit);
    let ux = c * hx + s * hy;
    let uy = -s * hx + c * hy;
    // A chord below 1e-15 of the radii: the small arc is the chord in double precision (its
    // sagitta is below rounding), and the large one a full ellipse whose start and end angles
    // cannot be told apart.
    let chord_ratio = ux.hypot(uy) / rx.min(ry);
    if chord_ratio < DEGENERATE_CHORD {
        if large_arc {
            return Err(SplineError::LimitExceeded {
                what: "large arc's radius / chord",
                value: 1.0 / chord_ratio,
                limit: 1e15,
            });
        }
        return Ok(ArcSegment::Line);
    }
    let lambda = (ux / rx).powi(2) + (uy / ry).powi(2);
    if lambda > 1.0 {
        let k = lambda.sqrt();
        rx *= k;
        ry *= k;
    }
    let (rx2, ry2) = (rx * rx, ry * ry);
    let den = rx2 * uy * uy + ry2 * ux * ux;
    let num = (rx2 * ry2 - den).max(0.0);
    let mut coef = (num / den).sqrt();
    if large_arc == sweep {
        coef = -coef;
    }
    let cxp = coef * rx * uy / ry;
    let cyp = -coef * ry * ux / rx;
    let center = Point::new(
        unit * (c * cxp - s * cyp) + 0.5 * (p0.x + p1.x),
        unit * (s * cxp + c * cyp) + 0.5 * (p0.y + p1.y),
    );
    let theta1 = ((uy - cyp) / ry).atan2((ux - cxp) / rx);
    let theta2 = ((-uy - cyp) / ry).atan2((-ux - cxp) / rx);
    let mut dtheta = (theta2 - theta1) % TAU;
    if sweep && dtheta <= 0.0 {
        dtheta += TAU;
    } else if !sweep && dtheta >= 0.0 {
        dtheta -= TAU;
    }
    // A half-turn found as a full turn (rounding at theta2 = theta1 + pi) is pulled back.
    if dtheta.abs() > TAU - HALF_TURN_ROUNDING {
        dtheta = dtheta.signum() * PI;
    }
    let curve = elliptic_arc(center, rx * unit, ry * unit, phi, theta1, dtheta)?;
    Ok(ArcSegment::Curve(with_end_points(&curve, p0, p1)?))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::prelude::*;

    fn arc(p0: Point, rx: f64, ry: f64, phi: f64, la: bool, sw: bool, p1: Point) -> NurbsCurve {
        match endpoint_arc(p0, rx, ry, phi, la, sw, p1).unwrap() {
            ArcSegment::Curve(c) => c,
            other => panic!("expected a curve, got {other:?}"),
        }
    }

    #[test]
    fn huge_radii_are_scaled_or_refused_never_nan() {
        // A radius of 1e6 on a unit chord: a nearly straight arc with the right sagitta.
        let (p0, p1) = (Point::new(0.0, 0.0), Point::new(1.0, 0.0));
        match endpoint_arc(p0, 1e6, 1e6, 0.0, false, true, p1) {
            Ok(ArcSegment::Curve(c)) => {
                assert_eq!(c.end_point(), p1);
                let sagitta = 1e6 - (1e12f64 - 0.25).sqrt();
                // The centre lies 1e6 away: its rounding (1e-10) bounds the accuracy.
                assert!(
                    (c.point_at(0.5).y.abs() - sagitta).abs() < 1e-9,
                    "{:?}",
                    c.point_at(0.5)
                );
            }
            other => panic!("{other:?}"),
        }
        // A radius of 1e100: the chord itself in double precision; the large arc is refused.
        assert!(matches!(
            endpoint_arc(p0, 1e100, 1e100, 0.0, false, true, p1),
            Ok(ArcSegment::Line)
        ));
        let e = endpoint_arc(p0, 1e100, 1e100, 0.0, true, true, p1).unwrap_err();
        assert!(e.to_string().contains("radius / chord"), "{e}");
        let e = endpoint_arc(p0, 1e308, 1e308, 0.0, false, true, p1).unwrap_err();
        assert!(e.to_string().contains("arc radius"), "{e}");
        // Large arcs scale with the chord: radii 1e-200 on a chord of 2e-200.
        let (q0, q1) = (Point::new(-1e-200, 0.0), Point::new(1e-200, 0.0));
        assert!(matches!(
            endpoint_arc(q0, 1e-200, 1e-200, 0.0, false, true, q1),
            Ok(ArcSegment::Curve(_))
        ));
    }

    #[test]
    fn quarter_circle_flags_pick_the_four_arcs() {
        let (p0, p1) = (Point::new(1.0, 0.0), Point::new(0.0, 1.0));
        // Small arc, positive sweep: centre (0, 0), a quarter turn.
        let a = arc(p0, 1.0, 1.0, 0.0, false, true, p1);
        let b = arc(p0, 1.0, 1.0, 0.0, true, true, p1);
        let c = arc(p0, 1.0, 1.0, 0.0, false, false, p1);
        for (curve, centre) in [
            (&a, Point::new(0.0, 0.0)),
            (&b, Point::new(1.0, 1.0)),
            (&c, Point::new(1.0, 1.0)),
        ] {
            assert_eq!(curve.start_point(), p0);
            assert_eq!(curve.end_point(), p1);
            for i in 0..=16 {
                let q = curve.point_at(i as f64 / 16.0);
                assert!((q.distance(centre) - 1.0).abs() < 1e-14);
            }
        }
        // The large arc goes the long way round its centre (1, 1), the small one the short way.
        let mid = b.point_at(0.5);
        assert!(mid.x > 1.0 && mid.y > 1.0, "{mid:?}");
        let mid = c.point_at(0.5);
        assert!(mid.x < 1.0 && mid.y < 1.0, "{mid:?}");
    }

    #[test]
    fn rotated_ellipse_points_satisfy_the_ellipse_equation() {
        let (p0, p1) = (Point::new(-2.0, 0.5), Point::new(3.0, 1.0));
        let (rx, ry, phi) = (4.0, 1.5, 30.0f64);
        let (s, c) = phi.to_radians().sin_cos();
        // Implicit equation of the rotated ellipse about `ctr`.
        let f = |q: Point, ctr: Point| {
            let d = q - ctr;
            let (x, y) = (c * d.x + s * d.y, -s * d.x + c * d.y);
            (x / rx).powi(2) + (y / ry).powi(2) - 1.0
        };
        for (la, sw) in [(false, false), (false, true), (true, false), (true, true)] {
            let a = arc(p0, rx, ry, phi, la, sw, p1);
            let pts: Vec<Point> = (0..=40).map(|i| a.point_at(i as f64 / 40.0)).collect();
            // One of the two ellipses through p0 and p1 (computed independently in the
            // unit-circle frame) holds every point.
            let fits = centres(p0, p1, rx, ry, phi)
                .into_iter()
                .filter(|&ctr| pts.iter().all(|&q| f(q, ctr).abs() < 1e-12))
                .count();
            assert_eq!(fits, 1, "flags {la} {sw}");
            // The sweep flag is the direction: positive angle direction means the cross
            // product of successive chords (from the centre) is positive.
            let turn: f64 = pts
                .windows(3)
                .map(|w| (w[1] - w[0]).cross(w[2] - w[1]))
                .sum();
            assert_eq!(turn > 0.0, sw, "flags {la} {sw}");
        }
    }

    /// Both centres of the ellipses with radii rx, ry (rotated by phi degrees) through p0
    /// and p1, by mapping to the unit-circle frame.
    fn centres(p0: Point, p1: Point, rx: f64, ry: f64, phi: f64) -> Vec<Point> {
        let (s, c) = phi.to_radians().sin_cos();
        let to = |q: Point| Point::new((c * q.x + s * q.y) / rx, (-s * q.x + c * q.y) / ry);
        let from = |q: Point| {
            let (x, y) = (q.x * rx, q.y * ry);
            Point::new(c * x - s * y, s * x + c * y)
        };
        let (a, b) = (to(p0), to(p1));
        let m = (a + b) * 0.5;
        let h = (b - a).length() * 0.5;
        let n = (b - a).perp() / (2.0 * h);
        let t = (1.0 - h * h).max(0.0).sqrt();
        vec![from(m + n * t), from(m - n * t)]
    }

    #[test]
    fn radii_too_small_are_scaled_to_a_half_ellipse() {
        let (p0, p1) = (Point::new(0.0, 0.0), Point::new(4.0, 0.0));
        let a = arc(p0, 1.0, 1.0, 0.0, false, true, p1);
        for i in 0..=16 {
            let q = a.point_at(i as f64 / 16.0);
            assert!((q.distance(Point::new(2.0, 0.0)) - 2.0).abs() < 1e-14);
        }
        // Positive sweep from (0,0) to (4,0) about (2,0) passes below (angle increases from pi).
        assert!(a.point_at(0.5).y < -1.9);
    }

    #[test]
    fn degenerate_arcs() {
        let p = Point::new(1.0, 2.0);
        assert!(matches!(
            endpoint_arc(p, 1.0, 1.0, 0.0, false, false, p).unwrap(),
            ArcSegment::Nothing
        ));
        assert!(matches!(
            endpoint_arc(p, 0.0, 1.0, 0.0, false, false, Point::new(3.0, 3.0)).unwrap(),
            ArcSegment::Line
        ));
    }
}
