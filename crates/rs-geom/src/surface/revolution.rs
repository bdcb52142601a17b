//! Surfaces of revolution: a curve turned about an axis (ISO 10303-42
//! `SURFACE_OF_REVOLUTION`: `u` the angle, `v` the curve's parameter; `OpenCASCADE`'s
//! `Geom_SurfaceOfRevolution` alike. IGES 120 orders them `(curve parameter, angle)` and
//! measures the angle from a start angle: a [`super::Reparam`] of this with the parameters
//! swapped; `OpenCASCADE` reads IGES 120 swapped back, and reparameterises a line generatrix
//! by length).

use std::f64::consts::TAU;

use rs_spline::Point3;

use super::invert::minimize_1d;
use super::swept::Swept;
use super::{
    ANGLE, COINCIDENCE_RELATIVE, Inversion, ON_AXIS_RELATIVE, ParamBox, ParamSurface, Pole,
    SurfaceDerivatives, finish, hostile_point, interior_side, normal_from_derivatives, usable_near,
};
use crate::{Curve, GeomError};

/// Results of the 1-D search whose distances differ by less than this fraction of the
/// surface's size are at the same distance (the one nearest `near` is kept).
const TIE_RELATIVE: f64 = 1e-12;

/// The surface swept by a curve `C` turned about an axis through `o` along the unit `d`:
/// `S(u, v) = o + R_d(u) (C(v) - o)`, `R_d(u)` the rotation by `u` about `d` (right-handed).
/// `u` is an angle (period `2 pi`); `v` the curve's parameter, on its range (periodic where
/// the curve is closed). Where the curve ends on the axis the line `v = end` is a pole.
#[derive(Clone, Debug, PartialEq)]
pub struct Revolution {
    swept: Swept,
    axis_point: Point3,
    axis: Point3,
    poles: Vec<Pole>,
    size: f64,
}

impl Revolution {
    /// The surface swept by `curve` turned about the axis through `axis_point` along
    /// `axis_direction` (any length).
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] for a non-finite axis point or a curve whose start is not
    /// finite; [`GeomError::DegenerateFrame`] for a zero or non-finite axis direction.
    pub fn new(
        curve: Curve<Point3>,
        axis_point: Point3,
        axis_direction: Point3,
    ) -> Result<Revolution, GeomError> {
        if !axis_point.is_finite() {
            return Err(GeomError::NotFinite {
                what: "axis point",
                value: axis_point.max_abs(),
            });
        }
        let axis = axis_direction
            .normalized()
            .ok_or(GeomError::DegenerateFrame("the axis of revolution is zero"))?;
        let swept = Swept::new(curve)?;
        let size = swept.extent(axis_point);
        let mut s = Revolution {
            swept,
            axis_point,
            axis,
            poles: Vec::new(),
            size,
        };
        if s.swept.is_bounded() {
            let (a, b) = s.swept.range;
            for t in [a, b] {
                if s.distance_from_axis(s.swept.point(t)) <= COINCIDENCE_RELATIVE * size {
                    s.poles.push(Pole { param: 1, value: t });
                }
            }
        }
        Ok(s)
    }

    /// The swept curve.
    pub fn curve(&self) -> &Curve<Point3> {
        &self.swept.curve
    }

    /// The point on the axis.
    pub fn axis_point(&self) -> Point3 {
        self.axis_point
    }

    /// The unit axis direction.
    pub fn axis(&self) -> Point3 {
        self.axis
    }

    /// The largest distance of the swept curve's samples from the axis point.
    pub(crate) fn size(&self) -> f64 {
        self.size
    }

    fn distance_from_axis(&self, p: Point3) -> f64 {
        let c = p - self.axis_point;
        (c - self.axis * c.dot(self.axis)).length()
    }

    /// The vector `p` turned by the angle with cosine `c` and sine `s` about the axis.
    fn rotate(&self, p: Point3, c: f64, s: f64) -> Point3 {
        let d = self.axis;
        let along = d * d.dot(p);
        along + (p - along) * c + d.cross(p) * s
    }

    /// The grid for offsets of this surface: angles and the curve's samples.
    pub(crate) fn sample_grid(&self) -> Option<[Vec<f64>; 2]> {
        self.swept.is_bounded().then(|| {
            [
                super::invert::sample_params(ANGLE, &[], 16, 16),
                self.swept.samples(self.swept.range),
            ]
        })
    }
}

impl ParamSurface for Revolution {
    fn point(&self, uv: [f64; 2]) -> Point3 {
        let (s, c) = uv[0].sin_cos();
        self.axis_point + self.rotate(self.swept.point(uv[1]) - self.axis_point, c, s)
    }

    /// `S_u = d x R (C - o)`, `S_v = R C'`, `S_uu = d x S_u`, `S_uv = d x R C'`, `S_vv = R C''`.
    fn derivatives(&self, uv: [f64; 2]) -> SurfaceDerivatives {
        let (s, c) = uv[0].sin_cos();
        let [p, d1, d2] = self.swept.derivatives(uv[1]);
        let d = self.axis;
        let rp = self.rotate(p - self.axis_point, c, s);
        let r1 = self.rotate(d1, c, s);
        let du = d.cross(rp);
        SurfaceDerivatives {
            point: self.axis_point + rp,
            du,
            dv: r1,
            duu: d.cross(du),
            duv: d.cross(r1),
            dvv: self.rotate(d2, c, s),
        }
    }

    /// The unit `S_u x S_v`; at a pole (the curve's end on the axis) its limit from the
    /// curve's side, `(d x R C') x R C'` oriented as the surface beside it.
    fn normal(&self, uv: [f64; 2]) -> Option<Point3> {
        normal_from_derivatives(&self.derivatives(uv), interior_side(&self.param_box(), uv))
    }

    fn param_box(&self) -> ParamBox {
        ParamBox {
            u: ANGLE,
            v: self.swept.range,
        }
    }

    fn periods(&self) -> [Option<f64>; 2] {
        [Some(TAU), self.swept.period]
    }

    fn poles(&self) -> Vec<Pole> {
        self.poles.clone()
    }

    /// The angle is a closed form: turning the curve's point to the point's half-plane
    /// through the axis brings it nearest. What remains is the nearest point of the curve's
    /// meridian image `(distance from the axis, height)` to the point's, a 1-D search on the
    /// curve (samples per knot span, then a bracketed Newton iteration; see
    /// [`crate::surface`]).
    fn invert(&self, x: Point3, near: Option<[f64; 2]>) -> Inversion {
        if let Some(bad) = hostile_point(x, near, [0.0, self.swept.range.0.max(0.0)]) {
            return bad;
        }
        let near = usable_near(near);
        let d = self.axis;
        let xo = x - self.axis_point;
        let hx = d.dot(xo);
        let xp = xo - d * hx;
        let rx = xp.length();
        // The squared meridian distance as a function of v, with two derivatives.
        let mid = if self.swept.is_bounded() {
            0.5 * (self.swept.range.0 + self.swept.range.1)
        } else {
            f64::INFINITY
        };
        let meridian = |t: f64| -> [f64; 3] {
            let [p, p1, p2] = self.swept.derivatives(t);
            let c = p - self.axis_point;
            let (h, h1, h2) = (d.dot(c), d.dot(p1), d.dot(p2));
            let (cp, c1, c2) = (c - d * h, p1 - d * h1, p2 - d * h2);
            let rc = cp.length();
            let (r1, r2) = if rc > 0.0 {
                let r1 = cp.dot(c1) / rc;
                (r1, (c1.dot(c1) + cp.dot(c2) - r1 * r1) / rc)
            } else {
                // On the axis: the distance from it grows as |C'| away from the point, seen
                // from inside the range (from below at its upper end).
                (c1.length() * if t > mid { -1.0 } else { 1.0 }, 0.0)
            };
            let (er, eh) = (rc - rx, h - hx);
            [
                er * er + eh * eh,
                2.0 * (er * r1 + eh * h1),
                2.0 * (r1 * r1 + er * r2 + h1 * h1 + eh * h2),
            ]
        };
        let near_v = near.map(|n| match self.swept.period {
            Some(p) if self.swept.is_bounded() => super::copy_from(n[1], self.swept.range.0, p),
            _ => n[1],
        });
        let t0 = near_v.unwrap_or(0.0);
        let reach = xo.length() + meridian(t0)[0].sqrt();
        let window = self.swept.window(t0, |t| {
            (self.swept.point(t) - self.axis_point).length() > reach
        });
        let samples = self.swept.samples(window);
        let tie = TIE_RELATIVE * (self.size + xo.length());
        let prefer = if self.swept.is_bounded() {
            near_v
        } else {
            Some(t0)
        };
        let v = minimize_1d(meridian, &samples, prefer, tie);
        let cp = {
            let c = self.swept.point(v) - self.axis_point;
            c - d * d.dot(c)
        };
        let near_u = near.map_or(0.0, |n| n[0]);
        let u = if rx <= ON_AXIS_RELATIVE * xo.length()
            || cp.length() <= ON_AXIS_RELATIVE * self.size
        {
            near_u
        } else {
            d.dot(cp.cross(xp)).atan2(cp.dot(xp))
        };
        finish(self, x, [u, v], near)
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI};

    use rs_spline::RationalBSpline;

    use super::*;
    use crate::surface::testing::{Rng, check_derivatives, check_normal, check_round_trip};
    use crate::surface::{Cone, Sphere, Torus};
    use crate::{Conic, ConicKind, Frame};

    /// A circle of radius `r` about `c` in the plane spanned by `a` and `b` (unit, orthogonal).
    fn circle(c: Point3, a: Point3, b: Point3, r: f64) -> Curve<Point3> {
        Curve::Conic(Conic {
            kind: ConicKind::Ellipse,
            center: c,
            u: a * r,
            v: b * r,
        })
    }

    #[test]
    fn a_revolved_circle_is_a_torus() {
        let mut rng = Rng::new(11);
        for _ in 0..10 {
            let f = rng.frame(5.0);
            let (big, r) = (rng.range(1.0, 3.0), rng.range(0.1, 0.9));
            // The torus's meridian circle in the plane of x and z, at distance R along x:
            // ISO's torus point at (u, v) is the circle's point at v turned by u.
            let c = circle(f.origin + f.x * big, f.x, f.z, r);
            let s = Revolution::new(c, f.origin, f.z).unwrap();
            let t = Torus::new(f, big, r).unwrap();
            assert_eq!(s.periods(), [Some(TAU), Some(TAU)]);
            assert!(s.poles().is_empty());
            for _ in 0..10 {
                let uv = [rng.range(-7.0, 7.0), rng.range(-7.0, 7.0)];
                let (a, b) = (s.derivatives(uv), t.derivatives(uv));
                for (p, q) in [
                    (a.point, b.point),
                    (a.du, b.du),
                    (a.dv, b.dv),
                    (a.duu, b.duu),
                    (a.duv, b.duv),
                    (a.dvv, b.dvv),
                ] {
                    assert!(p.distance(q) < 1e-13 * 10.0, "{p:?} vs {q:?}");
                }
                check_derivatives(&s, uv, 1.0);
                check_normal(&s, uv);
                check_round_trip(&s, uv, None, 1e-12, 10.0);
                check_round_trip(&s, uv, Some([uv[0] + 2.0, uv[1] - 2.0]), 1e-12, 10.0);
                let x = f.origin + rng.point(5.0);
                let (i, j) = (s.invert(x, None), t.invert(x, None));
                assert!(
                    (i.distance - j.distance).abs() < 1e-12 * 10.0,
                    "{i:?} vs {j:?}"
                );
            }
        }
    }

    #[test]
    fn a_revolved_quarter_circle_is_a_hemisphere_with_a_pole() {
        // The rational quadratic quarter circle from (2, 0, 0) to (0, 0, 2) (x-z plane),
        // turned about z: a hemisphere of radius 2 whose v = 1 end is the north pole.
        let w = FRAC_1_SQRT_2;
        let arc = RationalBSpline::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![
                Point3::new(2.0, 0.0, 0.0),
                Point3::new(2.0, 0.0, 2.0),
                Point3::new(0.0, 0.0, 2.0),
            ],
            Some(vec![1.0, w, 1.0]),
        )
        .unwrap();
        let s = Revolution::new(
            Curve::BSpline(arc),
            Point3::ORIGIN,
            Point3::new(0.0, 0.0, 3.0),
        )
        .unwrap();
        let sphere = Sphere::new(Frame::WORLD, 2.0).unwrap();
        assert_eq!(
            s.poles(),
            vec![Pole {
                param: 1,
                value: 1.0
            }]
        );
        assert_eq!(s.periods(), [Some(TAU), None]);
        assert_eq!(s.param_box().v, (0.0, 1.0));
        let mut rng = Rng::new(12);
        for _ in 0..30 {
            let uv = [rng.range(-4.0, 10.0), rng.range(0.02, 0.98)];
            let p = s.point(uv);
            assert!((p.length() - 2.0).abs() < 1e-14 * 4.0);
            check_derivatives(&s, uv, 1.0);
            check_normal(&s, uv);
            // Outward normal, as the sphere's.
            assert!(s.normal(uv).unwrap().distance(p * 0.5) < 1e-12);
            check_round_trip(&s, uv, None, 1e-12, 4.0);
            // Points off the surface: the foot is the sphere's (in the upper half space).
            let x = Point3::new(
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
                rng.range(0.1, 3.0),
            );
            let (i, j) = (s.invert(x, None), sphere.invert(x, None));
            assert!(
                (i.distance - j.distance).abs() < 1e-12 * 4.0,
                "{i:?} vs {j:?}"
            );
            assert!(s.point(i.uv).distance(sphere.point(j.uv)) < 1e-10);
        }
        // The pole: one point, normal +z (the limit from the curve's side), near's angle kept.
        assert!(s.point([0.3, 1.0]).distance(s.point([2.0, 1.0])) < 1e-15);
        assert!(s.normal([0.3, 1.0]).unwrap().distance(Point3::Z) < 1e-14);
        let inv = s.invert(Point3::new(0.0, 0.0, 2.5), Some([1.1, 0.9]));
        assert!((inv.distance - 0.5).abs() < 1e-14 && (inv.uv[1] - 1.0).abs() < 1e-12);
        assert!((inv.uv[0] - 1.1).abs() < 1e-15);
        // Below the equator (outside the hemisphere) the foot is on its rim.
        let inv = s.invert(Point3::new(0.0, 3.0, -1.0), None);
        assert!((inv.uv[1] - 0.0).abs() < 1e-15 && (inv.uv[0] - FRAC_PI_2).abs() < 1e-14);
        assert!((inv.distance - 2f64.sqrt()).abs() < 1e-14);
    }

    #[test]
    fn closed_swept_curves_make_a_periodic_v_and_trimmed_arcs_do_not() {
        // The rational quadratic full circle of radius 0.5 about (2, 0, 0) in the x-z plane
        // (nine points, knots in quarters): a closed B-spline, so v has period 1.
        let w = FRAC_1_SQRT_2;
        let c = |x: f64, z: f64| Point3::new(2.0 + 0.5 * x, 0.0, 0.5 * z);
        let circle = RationalBSpline::new(
            2,
            vec![
                0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
            ],
            vec![
                c(1.0, 0.0),
                c(1.0, 1.0),
                c(0.0, 1.0),
                c(-1.0, 1.0),
                c(-1.0, 0.0),
                c(-1.0, -1.0),
                c(0.0, -1.0),
                c(1.0, -1.0),
                c(1.0, 0.0),
            ],
            Some(vec![1.0, w, 1.0, w, 1.0, w, 1.0, w, 1.0]),
        )
        .unwrap();
        let s = Revolution::new(Curve::BSpline(circle), Point3::ORIGIN, Point3::Z).unwrap();
        let torus = Torus::new(Frame::WORLD, 2.0, 0.5).unwrap();
        assert_eq!(s.periods(), [Some(TAU), Some(1.0)]);
        assert_eq!(s.param_box().v, (0.0, 1.0));
        let mut rng = Rng::new(15);
        for _ in 0..20 {
            let uv = [rng.range(-4.0, 10.0), rng.range(0.02, 0.98)];
            assert!(s.point([uv[0], uv[1] + 3.0]).distance(s.point(uv)) < 1e-14 * 4.0);
            check_round_trip(&s, uv, Some([uv[0], uv[1] - 2.0]), 1e-12, 4.0);
            let x = rng.point(4.0);
            let (i, j) = (s.invert(x, None), torus.invert(x, None));
            assert!(
                (i.distance - j.distance).abs() < 1e-12 * 4.0,
                "{i:?} vs {j:?}"
            );
        }
        // Beside the seam v = 0 = 1: the copy nearest near, on either side.
        let x = s.point([0.5, 0.999]);
        let inv = s.invert(x, Some([0.5, 0.01]));
        assert!((inv.uv[1] + 0.001).abs() < 1e-12, "{inv:?}");
        // A trimmed half of an ellipse: the period of its basis is no period of the surface.
        let half = Curve::Trimmed {
            basis: Box::new(circle_curve()),
            range: (0.0, PI),
        };
        let s = Revolution::new(half, Point3::ORIGIN, Point3::Z).unwrap();
        assert_eq!(s.periods(), [Some(TAU), None]);
        assert_eq!(s.param_box().v, (0.0, PI));
    }

    fn circle_curve() -> Curve<Point3> {
        circle(Point3::new(2.0, 0.0, 0.0), Point3::X, Point3::Z, 0.5)
    }

    #[test]
    fn a_revolved_line_is_a_cone_and_unbounded() {
        let mut rng = Rng::new(13);
        for _ in 0..10 {
            let f = rng.frame(5.0);
            let (r, a) = (rng.range(0.2, 2.0), rng.range(0.2, 1.3));
            // The cone's generatrix at u = 0: (r + v tan a) x + v z.
            let line = Curve::Line {
                origin: f.origin + f.x * r,
                direction: f.x * a.tan() + f.z,
            };
            let s = Revolution::new(line, f.origin, f.z).unwrap();
            let cone = Cone::new(f, r, a).unwrap();
            assert_eq!(s.periods(), [Some(TAU), None]);
            assert_eq!(s.param_box().v, (f64::NEG_INFINITY, f64::INFINITY));
            for _ in 0..10 {
                let uv = [rng.range(-7.0, 7.0), rng.range(-3.0, 3.0)];
                assert!(s.point(uv).distance(cone.point(uv)) < 1e-13 * 10.0);
                check_derivatives(&s, uv, 1.0);
                check_round_trip(&s, uv, Some(uv), 1e-12, 10.0);
                let x = f.to_world(
                    rng.range(-4.0, 4.0),
                    rng.range(-4.0, 4.0),
                    rng.range(-4.0, 4.0),
                );
                let (i, j) = (s.invert(x, None), cone.invert(x, None));
                assert!(
                    (i.distance - j.distance).abs() < 1e-12 * 10.0,
                    "{i:?} vs {j:?}"
                );
            }
        }
    }

    #[test]
    fn a_skew_line_sweeps_a_hyperboloid() {
        // The line (1, t, t) turned about z: x^2 + y^2 - z^2 = 1.
        let line = Curve::Line {
            origin: Point3::new(1.0, 0.0, 0.0),
            direction: Point3::new(0.0, 1.0, 1.0),
        };
        let s = Revolution::new(line, Point3::ORIGIN, Point3::Z).unwrap();
        let mut rng = Rng::new(14);
        for _ in 0..20 {
            let uv = [rng.range(-4.0, 4.0), rng.range(-3.0, 3.0)];
            let p = s.point(uv);
            assert!((p.x * p.x + p.y * p.y - p.z * p.z - 1.0).abs() < 1e-13 * 10.0);
            check_derivatives(&s, uv, 1.0);
            check_normal(&s, uv);
            check_round_trip(&s, uv, None, 1e-12, 10.0);
            // Off the surface: the foot's offset is along the normal.
            let x = p + s.normal(uv).unwrap() * rng.range(-0.3, 0.3);
            let inv = s.invert(x, Some(uv));
            let n = s.normal(inv.uv).unwrap();
            assert!((x - s.point(inv.uv)).cross(n).length() < 1e-12 * 10.0);
            assert!(inv.distance <= x.distance(p) + 1e-14);
        }
        assert!(
            Revolution::new(
                Curve::Line {
                    origin: Point3::ORIGIN,
                    direction: Point3::X
                },
                Point3::ORIGIN,
                Point3::ORIGIN
            )
            .is_err()
        );
        let _ = PI;
    }
}
