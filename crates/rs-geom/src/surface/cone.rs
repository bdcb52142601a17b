//! The circular cone `o + (r + v tan a)(cos u x + sin u y) + v z` (ISO 10303-42
//! `CONICAL_SURFACE`: `v` is the height along the axis; `OpenCASCADE`'s `Geom_ConicalSurface`
//! measures `v` along the slant, `v_occ = v / cos a`; IGES 194 as ISO).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use rs_spline::Point3;

use super::{
    ANGLE, Inversion, ON_AXIS_RELATIVE, ParamBox, ParamSurface, Pole, SurfaceDerivatives,
    cylindrical, finish, hostile_point, radial, usable_near,
};
use crate::{Frame, GeomError};

/// A circular cone about a frame's `z` axis: `S(u, v) = o + (r + v tan a) rho(u) + v z` with
/// `rho(u) = cos u x + sin u y`, radius `r >= 0` at `v = 0` and semi-angle `0 < a < pi / 2`;
/// `u` an angle (period `2 pi`), `v` the height along `z` (unbounded: both nappes). The apex,
/// at `v = -r / tan a`, is a pole. The normal `S_u x S_v` points away from the axis where
/// `r + v tan a > 0`.
#[derive(Clone, Debug, PartialEq)]
pub struct Cone {
    frame: Frame,
    radius: f64,
    semi_angle: f64,
    /// `(tan a, cos a, sin a)`.
    trig: (f64, f64, f64),
}

impl Cone {
    /// The cone about `frame`'s `z` axis with radius `radius` at the origin's height and
    /// semi-angle `semi_angle` (radians).
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] or [`GeomError::NotPositive`] for a radius that is not finite
    /// and `>= 0`; [`GeomError::OutOfRange`] for a semi-angle not strictly between `0` and
    /// `pi / 2`.
    pub fn new(frame: Frame, radius: f64, semi_angle: f64) -> Result<Cone, GeomError> {
        if !radius.is_finite() {
            return Err(GeomError::NotFinite {
                what: "cone radius",
                value: radius,
            });
        }
        if radius < 0.0 {
            return Err(GeomError::NotPositive {
                what: "cone radius",
                value: radius,
            });
        }
        if !(semi_angle > 0.0 && semi_angle < FRAC_PI_2) {
            return Err(GeomError::OutOfRange {
                what: "cone semi-angle",
                value: semi_angle,
                min: 0.0,
                max: FRAC_PI_2,
            });
        }
        let (s, c) = semi_angle.sin_cos();
        Ok(Cone {
            frame,
            radius,
            semi_angle,
            trig: (semi_angle.tan(), c, s),
        })
    }

    /// Its frame.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// Its radius at `v = 0`.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// Its semi-angle (radians).
    pub fn semi_angle(&self) -> f64 {
        self.semi_angle
    }

    /// The `v` of its apex, `-r / tan a`.
    pub fn apex_v(&self) -> f64 {
        -self.radius / self.trig.0
    }

    /// The signed distance from the axis at height `v`, `r + v tan a`.
    fn rho(&self, v: f64) -> f64 {
        self.radius + v * self.trig.0
    }
}

impl ParamSurface for Cone {
    fn point(&self, uv: [f64; 2]) -> Point3 {
        let (rho, _) = radial(&self.frame, uv[0]);
        self.frame.origin + rho * self.rho(uv[1]) + self.frame.z * uv[1]
    }

    fn derivatives(&self, uv: [f64; 2]) -> SurfaceDerivatives {
        let (rho, tangent) = radial(&self.frame, uv[0]);
        let (r, t) = (self.rho(uv[1]), self.trig.0);
        SurfaceDerivatives {
            point: self.frame.origin + rho * r + self.frame.z * uv[1],
            du: tangent * r,
            dv: rho * t + self.frame.z,
            duu: rho * -r,
            duv: tangent * t,
            dvv: Point3::ORIGIN,
        }
    }

    /// `sign(r + v tan a) (cos a rho(u) - sin a z)`; `None` at the apex.
    fn normal(&self, uv: [f64; 2]) -> Option<Point3> {
        let r = self.rho(uv[1]);
        if r.abs() <= ON_AXIS_RELATIVE * (self.radius + (uv[1] * self.trig.0).abs()) {
            return None;
        }
        let (rho, _) = radial(&self.frame, uv[0]);
        let (_, c, s) = self.trig;
        Some((rho * c - self.frame.z * s) * r.signum())
    }

    fn param_box(&self) -> ParamBox {
        ParamBox {
            u: ANGLE,
            v: (f64::NEG_INFINITY, f64::INFINITY),
        }
    }

    fn periods(&self) -> [Option<f64>; 2] {
        [Some(TAU), None]
    }

    fn poles(&self) -> Vec<Pole> {
        vec![Pole {
            param: 1,
            value: self.apex_v(),
        }]
    }

    /// Closed form. In the plane through the axis and the point, the cone is two lines through
    /// the apex (the generatrix at the point's angle `u` and the one at `u + pi`); the foot
    /// is the nearer of the two orthogonal projections.
    fn invert(&self, x: Point3, near: Option<[f64; 2]>) -> Inversion {
        if let Some(bad) = hostile_point(x, near, [0.0, 0.0]) {
            return bad;
        }
        let near = usable_near(near);
        let (u, rho, h) = cylindrical(&self.frame, x, near.map(|n| n[0]));
        let (_, c, s) = self.trig;
        let r = self.radius;
        // Signed distances to the lines rho = r + v tan a and rho = -(r + v tan a).
        let d1 = ((rho - r) * c - h * s).abs();
        let d2 = ((rho + r) * c + h * s).abs();
        let uv = if d2 < d1 {
            [u + PI, (h * c - (r + rho) * s) * c]
        } else {
            [u, ((rho - r) * s + h * c) * c]
        };
        finish(self, x, uv, near)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::testing::{Rng, check_derivatives, check_normal, check_round_trip};

    #[test]
    fn points_derivatives_normals_and_inversion() {
        let mut rng = Rng::new(3);
        for _ in 0..40 {
            let frame = rng.frame(10.0);
            let (r, a) = (rng.range(0.0, 3.0), rng.range(0.05, 1.5));
            let s = Cone::new(frame, r, a).unwrap();
            let mut uv = [rng.range(-7.0, 7.0), rng.range(-4.0, 4.0)];
            if (uv[1] - s.apex_v()).abs() < 0.05 {
                uv[1] += 0.2;
            }
            check_derivatives(&s, uv, 1.0);
            check_normal(&s, uv);
            // On its implicit equation: distance |r + v tan a| from the axis at height v.
            let l = frame.to_local(s.point(uv));
            assert!((l.x.hypot(l.y) - (r + l.z * a.tan()).abs()).abs() < 1e-12 * 40.0);
            let size = 40.0 + r;
            check_round_trip(&s, uv, None, 1e-12, size);
            check_round_trip(&s, uv, Some([uv[0] - 2.0, uv[1]]), 1e-12, size);
            // Points anywhere: the foot's distance is the analytic one (the nearer of the two
            // generatrices in the point's meridian plane).
            let x = frame.to_world(
                rng.range(-5.0, 5.0),
                rng.range(-5.0, 5.0),
                rng.range(-5.0, 5.0),
            );
            let l = frame.to_local(x);
            let (rho, h) = (l.x.hypot(l.y), l.z);
            let (sa, ca) = a.sin_cos();
            let expected = ((rho - r) * ca - h * sa)
                .abs()
                .min(((rho + r) * ca + h * sa).abs());
            let inv = s.invert(x, None);
            assert!(
                (inv.distance - expected).abs() < 1e-12 * size,
                "{inv:?} vs {expected}"
            );
            // The foot is where the point's offset is along the normal.
            if let Some(n) = s.normal(inv.uv) {
                let off = x - s.point(inv.uv);
                assert!(off.cross(n).length() < 1e-11 * size);
            }
        }
    }

    #[test]
    fn apex_is_a_pole_without_normal() {
        let s = Cone::new(Frame::WORLD, 1.0, std::f64::consts::FRAC_PI_4).unwrap();
        let apex = s.apex_v();
        assert!((apex + 1.0).abs() < 1e-15);
        assert_eq!(
            s.poles(),
            vec![Pole {
                param: 1,
                value: apex
            }]
        );
        assert!(s.normal([0.3, apex]).is_none());
        assert!(s.point([0.3, apex]).distance(s.point([2.0, apex])) < 1e-15);
        // The apex inverts to itself with near's angle.
        let inv = s.invert(Point3::new(0.0, 0.0, -1.0), Some([0.7, 0.0]));
        assert!(inv.distance < 1e-15 && (inv.uv[0] - 0.7).abs() < 1e-15);
        // Below the apex, inside the lower nappe: the foot is on the lower nappe.
        let inv = s.invert(Point3::new(0.0, 0.0, -3.0), None);
        assert!((inv.distance - 2.0 * std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-15);
        assert!(inv.uv[1] < apex);
        assert!(Cone::new(Frame::WORLD, 1.0, 0.0).is_err());
        assert!(Cone::new(Frame::WORLD, 1.0, FRAC_PI_2).is_err());
        assert!(Cone::new(Frame::WORLD, -1.0, 0.5).is_err());
        assert!(Cone::new(Frame::WORLD, 0.0, 0.5).is_ok());
    }
}
