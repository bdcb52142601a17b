//! The plane `o + u x + v y` (ISO 10303-42 `PLANE`, IGES 190; `OpenCASCADE`'s `Geom_Plane`
//! alike).

use rs_spline::Point3;

use super::{Inversion, ParamBox, ParamSurface, Pole, SurfaceDerivatives, hostile_point};
use crate::Frame;

/// The plane through a frame's origin spanned by its `x` and `y` axes: `S(u, v) = o + u x +
/// v y`, normal `z`. Both parameters are lengths, unbounded.
#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    frame: Frame,
}

impl Plane {
    /// The plane of `frame`.
    pub fn new(frame: Frame) -> Plane {
        Plane { frame }
    }

    /// Its frame.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }
}

impl ParamSurface for Plane {
    fn point(&self, uv: [f64; 2]) -> Point3 {
        self.frame.to_world(uv[0], uv[1], 0.0)
    }

    fn derivatives(&self, uv: [f64; 2]) -> SurfaceDerivatives {
        SurfaceDerivatives {
            point: self.point(uv),
            du: self.frame.x,
            dv: self.frame.y,
            ..SurfaceDerivatives::default()
        }
    }

    fn normal(&self, _uv: [f64; 2]) -> Option<Point3> {
        Some(self.frame.z)
    }

    fn param_box(&self) -> ParamBox {
        ParamBox::UNBOUNDED
    }

    fn periods(&self) -> [Option<f64>; 2] {
        [None, None]
    }

    fn poles(&self) -> Vec<Pole> {
        Vec::new()
    }

    /// The orthogonal projection: `(u, v)` are the point's local `x` and `y` coordinates.
    fn invert(&self, x: Point3, near: Option<[f64; 2]>) -> Inversion {
        if let Some(bad) = hostile_point(x, near, [0.0, 0.0]) {
            return bad;
        }
        let l = self.frame.to_local(x);
        let uv = [l.x, l.y];
        Inversion {
            uv,
            distance: self.point(uv).distance(x),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::testing::{Rng, check_derivatives, check_normal};

    #[test]
    fn derivatives_normals_and_projection() {
        let mut rng = Rng::new(1);
        for _ in 0..20 {
            let frame = rng.frame(10.0);
            let s = Plane::new(frame);
            let uv = [rng.range(-5.0, 5.0), rng.range(-5.0, 5.0)];
            check_derivatives(&s, uv, 1.0);
            check_normal(&s, uv);
            // A point off the plane by h along z comes back to uv at distance |h|.
            let h = rng.range(-3.0, 3.0);
            let x = s.point(uv) + frame.z * h;
            let inv = s.invert(x, None);
            assert!((inv.uv[0] - uv[0]).abs() < 1e-12 * 20.0);
            assert!((inv.uv[1] - uv[1]).abs() < 1e-12 * 20.0);
            assert!((inv.distance - h.abs()).abs() < 1e-12 * 20.0);
        }
        let s = Plane::new(Frame::WORLD);
        assert!(s.periods() == [None, None] && s.poles().is_empty());
        assert_eq!(s.param_box(), ParamBox::UNBOUNDED);
    }
}
