//! The sphere `o + r cos v (cos u x + sin u y) + r sin v z` (ISO 10303-42
//! `SPHERICAL_SURFACE`, IGES 196; `OpenCASCADE`'s `Geom_SphericalSurface` alike).

use std::f64::consts::{FRAC_PI_2, TAU};

use rs_spline::Point3;

use super::{
    ANGLE, Inversion, ParamBox, ParamSurface, Pole, SurfaceDerivatives, finish, hostile_point,
    positive, radial, usable_near,
};
use crate::{Frame, GeomError};

/// A sphere of radius `r` about a frame's origin: `S(u, v) = o + r cos v rho(u) + r sin v z`
/// with `rho(u) = cos u x + sin u y`; `u` the longitude (period `2 pi`), `v` the latitude in
/// `[-pi / 2, pi / 2]`, whose ends are poles. The normal `S_u x S_v` points outwards.
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    frame: Frame,
    radius: f64,
}

impl Sphere {
    /// The sphere of radius `radius` about `frame`'s origin.
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] or [`GeomError::NotPositive`] for a radius that is not a
    /// positive number.
    pub fn new(frame: Frame, radius: f64) -> Result<Sphere, GeomError> {
        Ok(Sphere {
            frame,
            radius: positive("sphere radius", radius)?,
        })
    }

    /// Its frame.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// Its radius.
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The outward unit vector at `uv`.
    fn outward(&self, uv: [f64; 2]) -> Point3 {
        let (rho, _) = radial(&self.frame, uv[0]);
        let (s, c) = uv[1].sin_cos();
        rho * c + self.frame.z * s
    }
}

impl ParamSurface for Sphere {
    fn point(&self, uv: [f64; 2]) -> Point3 {
        self.frame.origin + self.outward(uv) * self.radius
    }

    fn derivatives(&self, uv: [f64; 2]) -> SurfaceDerivatives {
        let (rho, tangent) = radial(&self.frame, uv[0]);
        let (s, c) = uv[1].sin_cos();
        let r = self.radius;
        let z = self.frame.z;
        SurfaceDerivatives {
            point: self.frame.origin + (rho * c + z * s) * r,
            du: tangent * (r * c),
            dv: (z * c - rho * s) * r,
            duu: rho * (-r * c),
            duv: tangent * (-r * s),
            dvv: (rho * c + z * s) * -r,
        }
    }

    /// The outward `cos v rho(u) + sin v z`, at the poles too (`S_u` vanishes there); turned
    /// inwards where `cos v < 0`, outside the parameter box, as `S_u x S_v` is.
    fn normal(&self, uv: [f64; 2]) -> Option<Point3> {
        let n = self.outward(uv);
        Some(if uv[1].cos() < 0.0 { -n } else { n })
    }

    fn param_box(&self) -> ParamBox {
        ParamBox {
            u: ANGLE,
            v: (-FRAC_PI_2, FRAC_PI_2),
        }
    }

    fn periods(&self) -> [Option<f64>; 2] {
        [Some(TAU), None]
    }

    fn poles(&self) -> Vec<Pole> {
        vec![
            Pole {
                param: 1,
                value: -FRAC_PI_2,
            },
            Pole {
                param: 1,
                value: FRAC_PI_2,
            },
        ]
    }

    /// Closed form: the point's longitude and latitude about the centre (`near`'s longitude
    /// on the axis, `near`'s parameters at the centre).
    fn invert(&self, x: Point3, near: Option<[f64; 2]>) -> Inversion {
        if let Some(bad) = hostile_point(x, near, [0.0, 0.0]) {
            return bad;
        }
        let near = usable_near(near);
        let (u, rho, h) = super::cylindrical(&self.frame, x, near.map(|n| n[0]));
        let v = if rho == 0.0 && h == 0.0 {
            near.map_or(0.0, |n| n[1].clamp(-FRAC_PI_2, FRAC_PI_2))
        } else {
            h.atan2(rho)
        };
        finish(self, x, [u, v], near)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::testing::{Rng, check_derivatives, check_normal, check_round_trip};

    #[test]
    fn points_derivatives_normals_and_inversion() {
        let mut rng = Rng::new(4);
        for _ in 0..40 {
            let frame = rng.frame(10.0);
            let r = rng.range(0.1, 5.0);
            let s = Sphere::new(frame, r).unwrap();
            let uv = [rng.range(-7.0, 7.0), rng.range(-1.5, 1.5)];
            check_derivatives(&s, uv, 1.0);
            check_normal(&s, uv);
            let p = s.point(uv);
            assert!((p.distance(frame.origin) - r).abs() < 1e-13 * (r + 20.0));
            // The normal is the closed form (p - c) / r.
            assert!(
                s.normal(uv)
                    .unwrap()
                    .distance((p - frame.origin) * (1.0 / r))
                    < 1e-12
            );
            let size = r + 20.0;
            check_round_trip(&s, uv, None, 1e-12, size);
            check_round_trip(&s, uv, Some([uv[0] + 3.0, 0.0]), 1e-12, size);
            let x = rng.point(12.0);
            let inv = s.invert(x, None);
            let expected = (x.distance(frame.origin) - r).abs();
            assert!((inv.distance - expected).abs() < 1e-12 * size);
        }
    }

    #[test]
    fn poles_keep_their_normal_and_the_angle_of_near() {
        let frame = Frame::new(
            Point3::new(1.0, 2.0, 3.0),
            Some(Point3::new(1.0, 1.0, 0.0)),
            None,
        )
        .unwrap();
        let s = Sphere::new(frame, 2.0).unwrap();
        for v in [-FRAC_PI_2, FRAC_PI_2] {
            let n = s.normal([0.4, v]).unwrap();
            assert!(n.distance(frame.z * v.signum()) < 1e-15);
            // The line v = +-pi/2 is one point.
            assert!(s.point([0.4, v]).distance(s.point([5.0, v])) < 1e-15 * 10.0);
            let top = frame.origin + frame.z * (2.0 * v.signum());
            let inv = s.invert(top + frame.z * v.signum(), Some([0.4, 0.0]));
            assert!((inv.uv[0] - 0.4).abs() < 1e-12 && (inv.uv[1] - v).abs() < 1e-15);
            assert!((inv.distance - 1.0).abs() < 1e-14);
        }
        assert_eq!(s.poles().len(), 2);
        // The centre is at distance r from every point: near's parameters are kept.
        let inv = s.invert(frame.origin, Some([1.0, 0.5]));
        assert_eq!(inv.uv, [1.0, 0.5]);
        assert!((inv.distance - 2.0).abs() < 1e-15);
    }
}
