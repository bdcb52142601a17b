//! Conic arcs `A x^2 + B x y + C y^2 + D x + E y + F = 0` from a start to an end point
//! (entity 104), as exact rational quadratics.
//!
//! - Ellipse: centre, semi-axes and tilt from the coefficients, then [`elliptic_arc`]
//!   counter-clockwise from the start to the end (a full ellipse when they are equal).
//! - Hyperbola, parabola: one rational quadratic Bezier. Its end points are the arc's, its
//!   middle point `P1` is where the tangents at the ends meet, and its middle weight follows
//!   from the conic: with `q` the conic's symmetric bilinear form on homogeneous points,
//!   the Bezier's point at `t = 1/2` is `P0 + 2 w P1 + P2` (homogeneous); `q(P0, P1) =
//!   q(P2, P1) = 0` (`P1` lies on both tangents) and `q(P0, P0) = q(P2, P2) = 0`, so it is on
//!   the conic iff `2 q(P0, P2) + 4 w^2 q(P1, P1) = 0`, i.e. `w^2 = -q(P0, P2) / (2 q(P1,
//!   P1))`. A parabola has `w = 1`. A positive `w^2` means both ends are on one branch, whose
//!   arc between them turns by less than a half turn and is that single piece.

use std::f64::consts::TAU;

use rs_spline::{NurbsCurve, Point, elliptic_arc};

/// The conic's kind, as the 104 form number says (1 ellipse, 2 hyperbola, 3 parabola).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ConicKind {
    /// Form 1.
    Ellipse,
    /// Form 2.
    Hyperbola,
    /// Form 3.
    Parabola,
}

/// The coefficients `A..F` of a conic.
#[derive(Clone, Copy, Debug)]
pub(super) struct Conic {
    pub(super) c: [f64; 6],
}

impl Conic {
    /// `q(p, r)` for the homogeneous points `(p, 1)`, `(r, 1)`.
    fn form(&self, p: Point, r: Point) -> f64 {
        let [a, b, c, d, e, f] = self.c;
        a * p.x * r.x
            + 0.5 * b * (p.x * r.y + p.y * r.x)
            + c * p.y * r.y
            + 0.5 * d * (p.x + r.x)
            + 0.5 * e * (p.y + r.y)
            + f
    }

    /// The conic's value at `p`.
    pub(super) fn value(&self, p: Point) -> f64 {
        self.form(p, p)
    }

    /// The gradient at `p` (a normal of the tangent there).
    fn gradient(&self, p: Point) -> Point {
        let [a, b, c, d, e, _] = self.c;
        Point::new(2.0 * a * p.x + b * p.y + d, b * p.x + 2.0 * c * p.y + e)
    }

    /// The kind the coefficients give (by the discriminant `B^2 - 4 A C`).
    pub(super) fn kind(&self) -> ConicKind {
        let [a, b, c, ..] = self.c;
        let disc = b * b - 4.0 * a * c;
        let size = (b * b).max((4.0 * a * c).abs());
        if disc.abs() <= 1e-12 * size {
            ConicKind::Parabola
        } else if disc < 0.0 {
            ConicKind::Ellipse
        } else {
            ConicKind::Hyperbola
        }
    }
}

/// The arc of `conic` (of `kind`) from `start` to `end`.
pub(super) fn conic_arc(
    conic: &Conic,
    kind: ConicKind,
    start: Point,
    end: Point,
) -> Result<NurbsCurve, String> {
    if conic.c.iter().any(|x| !x.is_finite()) {
        return Err("a coefficient is not finite".into());
    }
    let found = conic.kind();
    if found != kind {
        return Err(format!(
            "the coefficients describe a {found:?}, the form number a {kind:?}"
        ));
    }
    match kind {
        ConicKind::Ellipse => ellipse_arc(conic, start, end),
        ConicKind::Hyperbola | ConicKind::Parabola => bezier_arc(conic, kind, start, end),
    }
}

/// Counter-clockwise elliptic arc from `start` to `end`.
fn ellipse_arc(conic: &Conic, start: Point, end: Point) -> Result<NurbsCurve, String> {
    let [a, b, c, d, e, _] = conic.c;
    let det = 4.0 * a * c - b * b;
    let centre = Point::new((b * e - 2.0 * c * d) / det, (b * d - 2.0 * a * e) / det);
    let f0 = conic.value(centre);
    // Principal axes: rotating by theta removes the xy term.
    let theta = 0.5 * b.atan2(a - c);
    let (s, co) = theta.sin_cos();
    let a1 = a * co * co + b * co * s + c * s * s;
    let c1 = a * s * s - b * co * s + c * co * co;
    let (rx2, ry2) = (-f0 / a1, -f0 / c1);
    if !(rx2 > 0.0 && ry2 > 0.0 && rx2.is_finite() && ry2.is_finite()) {
        return Err("the coefficients describe no real ellipse".into());
    }
    let (rx, ry) = (rx2.sqrt(), ry2.sqrt());
    // Eccentric angle of a point in the ellipse's own frame.
    let angle = |p: Point| {
        let (dx, dy) = (p.x - centre.x, p.y - centre.y);
        let (lx, ly) = (co * dx + s * dy, -s * dx + co * dy);
        (ly / ry).atan2(lx / rx)
    };
    let (t0, t1) = (angle(start), angle(end));
    let mut sweep = if start == end {
        TAU
    } else {
        (t1 - t0).rem_euclid(TAU)
    };
    if sweep <= 0.0 {
        sweep = TAU;
    }
    elliptic_arc(centre, rx, ry, theta, t0, sweep).map_err(|e| e.to_string())
}

/// One rational quadratic Bezier for a hyperbola or parabola arc.
fn bezier_arc(
    conic: &Conic,
    kind: ConicKind,
    start: Point,
    end: Point,
) -> Result<NurbsCurve, String> {
    if start == end {
        return Err("the start and end points are equal (an open conic has no closed arc)".into());
    }
    let (g0, g2) = (conic.gradient(start), conic.gradient(end));
    let det = g0.cross(g2);
    if det.abs() <= 1e-14 * g0.length() * g2.length() || !det.is_finite() {
        return Err("the tangents at the start and end are parallel".into());
    }
    // Solve g0 . X = g0 . start, g2 . X = g2 . end.
    let (r0, r2) = (g0.dot(start), g2.dot(end));
    let p1 = Point::new((r0 * g2.y - r2 * g0.y) / det, (g0.x * r2 - g2.x * r0) / det);
    let w = match kind {
        ConicKind::Parabola => 1.0,
        _ => {
            let w2 = -conic.form(start, end) / (2.0 * conic.value(p1));
            if !(w2 > 0.0 && w2.is_finite()) {
                return Err(
                    "the start and end points are not on one branch of the hyperbola".into(),
                );
            }
            w2.sqrt()
        }
    };
    NurbsCurve::bezier(vec![start, p1, end], Some(vec![1.0, w, 1.0])).map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::prelude::*;

    fn on_conic(conic: &Conic, curve: &NurbsCurve, scale: f64) {
        let (a, b) = curve.param_range();
        for i in 0..=64 {
            let p = curve.point_at(a + (b - a) * i as f64 / 64.0);
            let g = conic.gradient(p).length();
            assert!(
                conic.value(p).abs() / g < 1e-12 * scale,
                "{p:?} off the conic"
            );
        }
    }

    #[test]
    fn rotated_ellipse_arc() {
        // (x', y') = R(-0.3) (p - (1, 2)), x'^2/9 + y'^2/4 = 1: expand into A..F.
        let (s, c) = 0.3f64.sin_cos();
        let (ia, ib) = (1.0 / 9.0, 1.0 / 4.0);
        let a = ia * c * c + ib * s * s;
        let b = 2.0 * (ia - ib) * c * s;
        let cc = ia * s * s + ib * c * c;
        let (x0, y0) = (1.0, 2.0);
        let d = -2.0 * a * x0 - b * y0;
        let e = -b * x0 - 2.0 * cc * y0;
        let f = a * x0 * x0 + b * x0 * y0 + cc * y0 * y0 - 1.0;
        let conic = Conic {
            c: [a, b, cc, d, e, f],
        };
        let point = |t: f64| {
            let (lx, ly) = (3.0 * t.cos(), 2.0 * t.sin());
            Point::new(x0 + c * lx - s * ly, y0 + s * lx + c * ly)
        };
        let arc = conic_arc(&conic, ConicKind::Ellipse, point(0.5), point(2.0)).unwrap();
        on_conic(&conic, &arc, 3.0);
        assert!(arc.start_point().distance(point(0.5)) < 1e-12);
        assert!(arc.end_point().distance(point(2.0)) < 1e-12);
        // Counter-clockwise: the middle of the arc is the point at t = 1.25.
        let (u0, u1) = arc.param_range();
        let mid = arc.point_at(0.5 * (u0 + u1));
        assert!(mid.distance(point(1.25)) < 1e-12);
        // From 2.0 back to 0.5 counter-clockwise is the long way round.
        let long = conic_arc(&conic, ConicKind::Ellipse, point(2.0), point(0.5)).unwrap();
        let (u0, u1) = long.param_range();
        assert!(long.point_at(0.5 * (u0 + u1)).distance(point(1.25 + PI)) < 1e-12);
        // Equal ends: the whole ellipse.
        let full = conic_arc(&conic, ConicKind::Ellipse, point(1.0), point(1.0)).unwrap();
        assert_eq!(full.to_bezier().len(), 4);
        on_conic(&conic, &full, 3.0);
    }

    use std::f64::consts::PI;

    #[test]
    fn hyperbola_and_parabola_arcs() {
        // x^2/4 - y^2 = 1, right branch (2 cosh t, sinh t).
        let h = Conic {
            c: [0.25, 0.0, -1.0, 0.0, 0.0, -1.0],
        };
        let pt = |t: f64| Point::new(2.0 * t.cosh(), t.sinh());
        let arc = conic_arc(&h, ConicKind::Hyperbola, pt(-1.0), pt(1.5)).unwrap();
        on_conic(&h, &arc, 4.0);
        assert_eq!(arc.start_point(), pt(-1.0));
        assert_eq!(arc.end_point(), pt(1.5));
        assert!(arc.weights()[1] > 1.0);
        // Every point of the arc is on the right branch between the ends.
        let (u0, u1) = arc.param_range();
        for i in 0..=16 {
            let p = arc.point_at(u0 + (u1 - u0) * i as f64 / 16.0);
            assert!(p.x > 0.0 && p.y >= pt(-1.0).y - 1e-12 && p.y <= pt(1.5).y + 1e-12);
        }
        // Ends on the two branches: refused.
        let other = Point::new(-2.0, 0.0);
        assert!(conic_arc(&h, ConicKind::Hyperbola, pt(0.5), other).is_err());
        // y = x^2 - 1: -x^2 + y + 1 = 0 ... as A = 1, E = -1, F = -1: x^2 - y - 1 = 0.
        let p = Conic {
            c: [1.0, 0.0, 0.0, 0.0, -1.0, -1.0],
        };
        let arc = conic_arc(
            &p,
            ConicKind::Parabola,
            Point::new(-1.0, 0.0),
            Point::new(2.0, 3.0),
        )
        .unwrap();
        on_conic(&p, &arc, 3.0);
        assert!(arc.is_polynomial());
        // Wrong form number for the coefficients.
        assert!(
            conic_arc(
                &p,
                ConicKind::Ellipse,
                Point::new(-1.0, 0.0),
                Point::new(2.0, 3.0)
            )
            .is_err()
        );
    }
}
