//! The torus `o + (R + r cos v)(cos u x + sin u y) + r sin v z` (ISO 10303-42
//! `TOROIDAL_SURFACE` and `DEGENERATE_TOROIDAL_SURFACE`, IGES 198; `OpenCASCADE`'s
//! `Geom_ToroidalSurface` alike).

use std::f64::consts::{PI, TAU};

use rs_spline::Point3;

use super::{
    ANGLE, Inversion, ON_AXIS_RELATIVE, ParamBox, ParamSurface, Pole, SurfaceDerivatives,
    cylindrical, finish, hostile_point, positive, radial, usable_near,
};
use crate::{Frame, GeomError};

/// A torus about a frame's `z` axis: `S(u, v) = o + (R + r cos v) rho(u) + r sin v z` with
/// `rho(u) = cos u x + sin u y`, major radius `R > 0`, minor radius `r > 0`; both parameters
/// angles of period `2 pi`. A minor radius `r >= R` (a horn or spindle torus, ISO's
/// `DEGENERATE_TOROIDAL_SURFACE`, whole) has poles where `R + r cos v = 0`. The normal
/// `S_u x S_v` points away from the tube's centre circle where `R + r cos v > 0`.
#[derive(Clone, Debug, PartialEq)]
pub struct Torus {
    frame: Frame,
    major: f64,
    minor: f64,
}

impl Torus {
    /// The torus about `frame`'s `z` axis with radii `major` (of the tube's centre circle) and
    /// `minor` (of the tube).
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] or [`GeomError::NotPositive`] for a radius that is not a
    /// positive number.
    pub fn new(frame: Frame, major: f64, minor: f64) -> Result<Torus, GeomError> {
        Ok(Torus {
            frame,
            major: positive("torus major radius", major)?,
            minor: positive("torus minor radius", minor)?,
        })
    }

    /// Its frame.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// Its major radius `R`.
    pub fn major_radius(&self) -> f64 {
        self.major
    }

    /// Its minor radius `r`.
    pub fn minor_radius(&self) -> f64 {
        self.minor
    }
}

impl ParamSurface for Torus {
    fn point(&self, uv: [f64; 2]) -> Point3 {
        let (rho, _) = radial(&self.frame, uv[0]);
        let (s, c) = uv[1].sin_cos();
        self.frame.origin + rho * (self.major + self.minor * c) + self.frame.z * (self.minor * s)
    }

    fn derivatives(&self, uv: [f64; 2]) -> SurfaceDerivatives {
        let (rho, tangent) = radial(&self.frame, uv[0]);
        let (s, c) = uv[1].sin_cos();
        let (big, r, z) = (self.major + self.minor * c, self.minor, self.frame.z);
        SurfaceDerivatives {
            point: self.frame.origin + rho * big + z * (r * s),
            du: tangent * big,
            dv: (z * c - rho * s) * r,
            duu: rho * -big,
            duv: tangent * (-r * s),
            dvv: (rho * c + z * s) * -r,
        }
    }

    /// `sign(R + r cos v) (cos v rho(u) + sin v z)`; `None` at the poles of a horn or spindle
    /// torus.
    fn normal(&self, uv: [f64; 2]) -> Option<Point3> {
        let (s, c) = uv[1].sin_cos();
        let big = self.major + self.minor * c;
        if big.abs() <= ON_AXIS_RELATIVE * (self.major + self.minor) {
            return None;
        }
        let (rho, _) = radial(&self.frame, uv[0]);
        Some((rho * c + self.frame.z * s) * big.signum())
    }

    fn param_box(&self) -> ParamBox {
        ParamBox { u: ANGLE, v: ANGLE }
    }

    fn periods(&self) -> [Option<f64>; 2] {
        [Some(TAU), Some(TAU)]
    }

    /// None for a ring torus (`r < R`); `v = pi` for a horn torus (`r = R`); `v = +-acos(-R /
    /// r)` (in `[0, 2 pi)`) for a spindle torus.
    fn poles(&self) -> Vec<Pole> {
        if self.minor < self.major {
            return Vec::new();
        }
        let v = (-self.major / self.minor).acos();
        if v == PI {
            return vec![Pole { param: 1, value: v }];
        }
        vec![
            Pole { param: 1, value: v },
            Pole {
                param: 1,
                value: TAU - v,
            },
        ]
    }

    /// Closed form. In the plane through the axis and the point the torus is two circles of
    /// radius `r` about `(+-R, 0)`; the foot is the radial projection onto the nearer (`near`'s
    /// parameters where the point is on the axis or a circle's centre).
    fn invert(&self, x: Point3, near: Option<[f64; 2]>) -> Inversion {
        if let Some(bad) = hostile_point(x, near, [0.0, 0.0]) {
            return bad;
        }
        let near = usable_near(near);
        let (u, rho, h) = cylindrical(&self.frame, x, near.map(|n| n[0]));
        let (big, r) = (self.major, self.minor);
        let (da, db) = ((rho - big).hypot(h), (rho + big).hypot(h));
        let uv = if (db - r).abs() < (da - r).abs() {
            [u + PI, h.atan2(-rho - big)]
        } else if da == 0.0 {
            [u, near.map_or(0.0, |n| n[1])]
        } else {
            [u, h.atan2(rho - big)]
        };
        finish(self, x, uv, near)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::testing::{Rng, check_derivatives, check_normal, check_round_trip};

    /// The distance from `x` to the torus: to the nearer of the two circles of its meridian
    /// plane.
    fn distance(t: &Torus, x: Point3) -> f64 {
        let l = t.frame.to_local(x);
        let rho = l.x.hypot(l.y);
        let d = |c: f64| ((rho - c).hypot(l.z) - t.minor).abs();
        d(t.major).min(d(-t.major))
    }

    #[test]
    fn points_derivatives_normals_and_inversion() {
        let mut rng = Rng::new(5);
        for i in 0..60 {
            let frame = rng.frame(10.0);
            let big = rng.range(0.5, 5.0);
            // Ring tori, and every fourth a spindle torus.
            let r = if i % 4 == 3 {
                big * rng.range(1.1, 2.0)
            } else {
                big * rng.range(0.05, 0.95)
            };
            let s = Torus::new(frame, big, r).unwrap();
            let uv = [rng.range(-7.0, 7.0), rng.range(-7.0, 7.0)];
            check_derivatives(&s, uv, 1.0);
            let (_, c) = uv[1].sin_cos();
            if (big + r * c).abs() > 1e-3 {
                check_normal(&s, uv);
            }
            // On its implicit equation (sqrt(x^2 + y^2) - R)^2 + z^2 = r^2 (with the signed
            // distance from the axis).
            let l = frame.to_local(s.point(uv));
            let signed = (l.x.hypot(l.y)) * (big + r * c).signum();
            assert!(((signed - big).hypot(l.z) - r).abs() < 1e-12 * 20.0);
            let size = big + r + 20.0;
            if r < big {
                check_round_trip(&s, uv, None, 1e-12, size);
                check_round_trip(&s, uv, Some([uv[0] + 2.5, uv[1] - 2.5]), 1e-12, size);
            } else {
                // A spindle's inner sheets overlap: the point comes back, maybe with other
                // parameters.
                let inv = s.invert(s.point(uv), None);
                assert!(inv.distance < 1e-12 * size);
            }
            let x = frame.origin + rng.point(8.0);
            let inv = s.invert(x, None);
            assert!((inv.distance - distance(&s, x)).abs() < 1e-12 * size);
        }
    }

    #[test]
    fn spindle_poles() {
        let s = Torus::new(Frame::WORLD, 1.0, 2.0).unwrap();
        let poles = s.poles();
        assert_eq!(poles.len(), 2);
        for p in &poles {
            assert!(s.point([0.3, p.value]).distance(s.point([2.0, p.value])) < 1e-14);
            assert!(s.normal([0.3, p.value]).is_none());
        }
        let horn = Torus::new(Frame::WORLD, 1.0, 1.0).unwrap();
        assert_eq!(
            horn.poles(),
            vec![Pole {
                param: 1,
                value: PI
            }]
        );
        assert!(Torus::new(Frame::WORLD, 1.0, 1.0).unwrap().poles().len() == 1);
        assert!(
            Torus::new(Frame::WORLD, 2.0, 1.0)
                .unwrap()
                .poles()
                .is_empty()
        );
        // The tube's centre circle: every point of the tube's circle is at distance r.
        let ring = Torus::new(Frame::WORLD, 2.0, 0.5).unwrap();
        let inv = ring.invert(Point3::new(0.0, 2.0, 0.0), Some([1.0, 1.25]));
        assert!((inv.uv[1] - 1.25).abs() < 1e-15 && (inv.distance - 0.5).abs() < 1e-15);
        assert!(Torus::new(Frame::WORLD, 0.0, 1.0).is_err());
    }
}
