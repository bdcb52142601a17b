//! Circular and elliptic arcs as exact rational quadratic NURBS.

use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2};

use crate::limits::MAX_ARC_PIECES;
use crate::{NurbsCurve, Point, SplineError};

/// The elliptic arc `c + R(tilt) (rx cos(theta), ry sin(theta))` for `theta` from
/// `start_angle` to `start_angle + sweep` (radians; negative `sweep` runs clockwise; any span,
/// several turns included), as an exact rational quadratic NURBS on `[0, 1]`.
///
/// The arc is cut into `k = ceil(|sweep| / (pi/2))` equal pieces; each piece of angle `d` has
/// control points `e(theta0)`, `e(theta_mid) / cos(d/2)` (in the unit-circle frame) and
/// `e(theta1)` with weights `1, cos(d/2), 1`, the standard exact conic form; an affine map
/// preserves it, which gives the ellipse from the unit circle. `theta` is the eccentric
/// (parametric) angle, not the polar angle of the point.
///
/// # Errors
/// [`SplineError::InvalidPrimitive`] for non-positive or non-finite radii, a zero or
/// non-finite sweep, or non-finite angles or centre; [`SplineError::LimitExceeded`] for a sweep
/// of more than [`MAX_ARC_PIECES`] quarter turns.
pub fn elliptic_arc(
    center: Point,
    rx: f64,
    ry: f64,
    tilt: f64,
    start_angle: f64,
    sweep: f64,
) -> Result<NurbsCurve, SplineError> {
    check_positive("radius", rx)?;
    check_positive("radius", ry)?;
    check_finite("tilt", tilt)?;
    check_finite("start angle", start_angle)?;
    check_finite("centre x", center.x)?;
    check_finite("centre y", center.y)?;
    if sweep == 0.0 || !sweep.is_finite() {
        return Err(SplineError::InvalidPrimitive {
            what: "sweep",
            value: sweep,
        });
    }
    let pieces = ((sweep.abs() / FRAC_PI_2) - 1e-12).ceil().max(1.0);
    if pieces > MAX_ARC_PIECES as f64 {
        return Err(SplineError::LimitExceeded {
            what: "arc sweep (radians)",
            value: sweep.abs(),
            limit: MAX_ARC_PIECES as f64 * FRAC_PI_2,
        });
    }
    let k = pieces as usize;
    let delta = sweep / k as f64;
    let w_mid = (0.5 * delta).cos();
    let unit = |theta: f64| Point::new(theta.cos(), theta.sin());
    let mut points = vec![unit(start_angle)];
    let mut weights = vec![1.0];
    for j in 0..k {
        let t0 = start_angle + j as f64 * delta;
        points.push(unit(t0 + 0.5 * delta) / w_mid);
        points.push(unit(t0 + delta));
        weights.extend([w_mid, 1.0]);
    }
    let mut knots = vec![0.0; 3];
    for j in 1..k {
        let u = j as f64 / k as f64;
        knots.extend([u, u]);
    }
    knots.extend([1.0; 3]);
    let (s, c) = tilt.sin_cos();
    let map = |p: Point| {
        let (x, y) = (rx * p.x, ry * p.y);
        Point::new(center.x + c * x - s * y, center.y + s * x + c * y)
    };
    NurbsCurve::new(
        2,
        knots,
        points.into_iter().map(map).collect(),
        Some(weights),
    )
}

/// The circular arc of `radius` about `center` from `start_angle` through `sweep` radians
/// (see [`elliptic_arc`]).
///
/// # Errors
/// As [`elliptic_arc`].
///
/// # Examples
///
/// ```
/// use rs_spline::{circular_arc, Point, prelude::*};
/// let a = circular_arc(Point::new(1.0, 1.0), 2.0, 0.0, 3.0).unwrap();
/// for i in 0..=10 {
///     let p = a.point_at(i as f64 / 10.0);
///     assert!((p.distance(Point::new(1.0, 1.0)) - 2.0).abs() < 1e-14);
/// }
/// ```
pub fn circular_arc(
    center: Point,
    radius: f64,
    start_angle: f64,
    sweep: f64,
) -> Result<NurbsCurve, SplineError> {
    elliptic_arc(center, radius, radius, 0.0, start_angle, sweep)
}

/// The full circle of `radius` about `center`, counter-clockwise from `(cx + r, cy)`, as the
/// classic nine-point rational quadratic (corner weights `1/sqrt(2)`); it closes exactly.
///
/// # Errors
/// [`SplineError::InvalidPrimitive`] for a non-positive or non-finite radius or centre.
pub fn circle(center: Point, radius: f64) -> Result<NurbsCurve, SplineError> {
    ellipse(center, radius, radius, 0.0)
}

/// The full ellipse with semi-axes `rx`, `ry` rotated by `tilt`, counter-clockwise, closing
/// exactly (nine-point rational quadratic).
///
/// # Errors
/// As [`circle`], plus a non-finite tilt.
pub fn ellipse(center: Point, rx: f64, ry: f64, tilt: f64) -> Result<NurbsCurve, SplineError> {
    check_positive("radius", rx)?;
    check_positive("radius", ry)?;
    check_finite("tilt", tilt)?;
    check_finite("centre x", center.x)?;
    check_finite("centre y", center.y)?;
    let unit = [
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (-1.0, 1.0),
        (-1.0, 0.0),
        (-1.0, -1.0),
        (0.0, -1.0),
        (1.0, -1.0),
        (1.0, 0.0),
    ];
    let (s, c) = tilt.sin_cos();
    let points = unit
        .iter()
        .map(|&(ux, uy)| {
            let (x, y) = (rx * ux, ry * uy);
            Point::new(center.x + c * x - s * y, center.y + s * x + c * y)
        })
        .collect();
    let w = FRAC_1_SQRT_2;
    NurbsCurve::new(
        2,
        vec![
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
        ],
        points,
        Some(vec![1.0, w, 1.0, w, 1.0, w, 1.0, w, 1.0]),
    )
}

fn check_positive(what: &'static str, value: f64) -> Result<(), SplineError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(SplineError::InvalidPrimitive { what, value })
    }
}

fn check_finite(what: &'static str, value: f64) -> Result<(), SplineError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(SplineError::InvalidPrimitive { what, value })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prelude::*;

    #[test]
    fn arc_end_points_and_piece_count() {
        let a = circular_arc(Point::new(0.0, 0.0), 1.0, 0.25, 2.5).unwrap();
        assert!(
            a.start_point()
                .distance(Point::new(0.25f64.cos(), 0.25f64.sin()))
                < 1e-15
        );
        assert!(
            a.end_point()
                .distance(Point::new(2.75f64.cos(), 2.75f64.sin()))
                < 1e-15
        );
        assert_eq!(a.to_bezier().len(), 2);
        assert_eq!(
            circular_arc(Point::default(), 1.0, 0.0, -7.0)
                .unwrap()
                .to_bezier()
                .len(),
            5
        );
    }

    #[test]
    fn invalid_arcs() {
        assert!(circular_arc(Point::default(), 0.0, 0.0, 1.0).is_err());
        assert!(circular_arc(Point::default(), 1.0, 0.0, 0.0).is_err());
        assert!(circular_arc(Point::default(), 1.0, f64::NAN, 1.0).is_err());
        assert!(circle(Point::default(), -1.0).is_err());
    }

    #[test]
    fn circle_closes_exactly() {
        let c = circle(Point::new(3.0, -1.0), 2.0).unwrap();
        assert_eq!(c.start_point(), c.end_point());
    }
}
