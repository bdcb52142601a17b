//! The circular cylinder `o + r (cos u x + sin u y) + v z` (ISO 10303-42
//! `CYLINDRICAL_SURFACE`, IGES 192; `OpenCASCADE`'s `Geom_CylindricalSurface` alike).

use rs_spline::Point3;

use super::{
    ANGLE, Inversion, ParamBox, ParamSurface, Pole, SurfaceDerivatives, cylindrical, finish,
    hostile_point, positive, radial, usable_near,
};
use crate::{Frame, GeomError};

/// A circular cylinder about a frame's `z` axis: `S(u, v) = o + r rho(u) + v z` with
/// `rho(u) = cos u x + sin u y`; `u` an angle (period `2 pi`), `v` the height along `z`
/// (unbounded). The normal `S_u x S_v` points away from the axis.
#[derive(Clone, Debug, PartialEq)]
pub struct Cylinder {
    frame: Frame,
    radius: f64,
}

impl Cylinder {
    /// The cylinder of radius `radius` about `frame`'s `z` axis.
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] or [`GeomError::NotPositive`] for a radius that is not a
    /// positive number.
    pub fn new(frame: Frame, radius: f64) -> Result<Cylinder, GeomError> {
        Ok(Cylinder {
            frame,
            radius: positive("cylinder radius", radius)?,
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
}

impl ParamSurface for Cylinder {
    fn point(&self, uv: [f64; 2]) -> Point3 {
        let (rho, _) = radial(&self.frame, uv[0]);
        self.frame.origin + rho * self.radius + self.frame.z * uv[1]
    }

    fn derivatives(&self, uv: [f64; 2]) -> SurfaceDerivatives {
        let (rho, tangent) = radial(&self.frame, uv[0]);
        let r = self.radius;
        SurfaceDerivatives {
            point: self.frame.origin + rho * r + self.frame.z * uv[1],
            du: tangent * r,
            dv: self.frame.z,
            duu: rho * -r,
            ..SurfaceDerivatives::default()
        }
    }

    /// `cos u x + sin u y`.
    fn normal(&self, uv: [f64; 2]) -> Option<Point3> {
        Some(radial(&self.frame, uv[0]).0)
    }

    fn param_box(&self) -> ParamBox {
        ParamBox {
            u: ANGLE,
            v: (f64::NEG_INFINITY, f64::INFINITY),
        }
    }

    fn periods(&self) -> [Option<f64>; 2] {
        [Some(std::f64::consts::TAU), None]
    }

    fn poles(&self) -> Vec<Pole> {
        Vec::new()
    }

    /// Closed form: `u` the point's angle about the axis (`near`'s on the axis), `v` its
    /// height.
    fn invert(&self, x: Point3, near: Option<[f64; 2]>) -> Inversion {
        if let Some(bad) = hostile_point(x, near, [0.0, 0.0]) {
            return bad;
        }
        let near = usable_near(near);
        let (u, _, h) = cylindrical(&self.frame, x, near.map(|n| n[0]));
        finish(self, x, [u, h], near)
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::TAU;

    use super::*;
    use crate::surface::testing::{Rng, check_derivatives, check_normal, check_round_trip};

    #[test]
    fn points_derivatives_normals_and_inversion() {
        let mut rng = Rng::new(2);
        for _ in 0..30 {
            let frame = rng.frame(10.0);
            let r = rng.range(0.1, 5.0);
            let s = Cylinder::new(frame, r).unwrap();
            let uv = [rng.range(-7.0, 7.0), rng.range(-5.0, 5.0)];
            check_derivatives(&s, uv, 1.0);
            check_normal(&s, uv);
            // On its implicit equation: distance r from the axis.
            let l = frame.to_local(s.point(uv));
            assert!((l.x.hypot(l.y) - r).abs() < 1e-13 * (r + 10.0));
            let size = r + 20.0;
            check_round_trip(&s, uv, None, 1e-12, size);
            check_round_trip(&s, uv, Some([uv[0] + 0.3, 0.0]), 1e-12, size);
            // A point off the surface along the normal, inside or outside: the distance is
            // |rho - r| and the foot's parameters those of the point.
            let h = rng.range(-0.9 * r, 3.0);
            let x = s.point(uv) + s.normal(uv).unwrap() * h;
            let inv = s.invert(x, Some(uv));
            assert!((inv.distance - h.abs()).abs() < 1e-12 * size);
            assert!(
                (inv.uv[0] - uv[0]).abs() < 1e-12 * size
                    && (inv.uv[1] - uv[1]).abs() < 1e-12 * size
            );
        }
    }

    #[test]
    fn on_the_axis_the_angle_of_near_is_kept() {
        let s = Cylinder::new(Frame::WORLD, 2.0).unwrap();
        let inv = s.invert(Point3::new(0.0, 0.0, 3.0), Some([1.25, 0.0]));
        assert_eq!(inv.uv, [1.25, 3.0]);
        assert_eq!(inv.distance, 2.0);
        // Without near, the copy in [0, 2 pi).
        let inv = s.invert(Point3::new(0.0, -1.0, 0.0), None);
        assert!((inv.uv[0] - 1.5 * std::f64::consts::PI).abs() < 1e-15);
        let inv = s.invert(Point3::new(0.0, -1.0, 0.0), Some([0.1, 0.0]));
        assert!((inv.uv[0] + 0.5 * std::f64::consts::PI).abs() < 1e-15);
        assert_eq!(s.periods(), [Some(TAU), None]);
        assert!(matches!(
            Cylinder::new(Frame::WORLD, -1.0),
            Err(GeomError::NotPositive { .. })
        ));
        assert!(matches!(
            Cylinder::new(Frame::WORLD, f64::NAN),
            Err(GeomError::NotFinite { .. })
        ));
    }
}
