//! Offset surfaces: a surface moved along its unit normal by a distance (ISO 10303-42
//! `OFFSET_SURFACE`, IGES 140; `OpenCASCADE`'s `Geom_OffsetSurface` alike).

use rs_spline::Point3;

use super::invert::closest;
use super::{
    Inversion, MAX_NESTING, PARALLEL_SINE, ParamBox, ParamSurface, Pole, Surface,
    SurfaceDerivatives, hostile_point, interior_side, usable_near,
};
use crate::GeomError;
use crate::surface::COINCIDENCE_RELATIVE;

/// The second derivatives are central differences of the analytic first derivatives with steps
/// of this fraction of each parameter's extent: truncation `O(h^2)` and rounding
/// `O(eps / h)` both near `1e-10` of the derivatives.
const DIFFERENCE_STEP: f64 = 1e-5;

/// Samples along a pole line of the base checked to still be one point after the offset.
const POLE_SAMPLES: usize = 8;

/// The most offsets in one chain of surfaces once direct offsets of offsets are merged (an
/// offset of a reparameterised offset): each evaluates its second derivatives from about ten
/// evaluations of the next, so the work grows as `10^k`.
pub const MAX_NESTED_OFFSETS: usize = 3;

/// `S(u, v) = B(u, v) + d N(u, v)`, `N` the base's unit normal `B_u x B_v / |B_u x B_v|` (at
/// a pole of the base, its limit from inside the parameter box). The parameters, box and
/// periods are the base's.
///
/// First derivatives are closed forms (`N_u = (W_u - N (N . W_u)) / |W|`, `W = B_u x B_v`);
/// second derivatives are central differences of them (they need the base's third
/// derivatives), and at a pole of the base the normal's derivatives are one-sided differences
/// of the limit normal.
///
/// An offset of an offset is one offset by the sum of the distances: the same surface where
/// the inner offset keeps the base's orientation (within the base's radii of curvature; past
/// them the inner offset is turned inside out, and files do not nest such surfaces).
#[derive(Clone, Debug, PartialEq)]
pub struct Offset {
    base: Box<Surface>,
    distance: f64,
}

impl Offset {
    /// `base` moved by `distance` along its normal.
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] for a non-finite distance; [`GeomError::NestingTooDeep`] for a
    /// base with [`MAX_NESTING`] offsets and reparameterisations in it, or
    /// [`MAX_NESTED_OFFSETS`] offsets.
    pub fn new(base: Surface, distance: f64) -> Result<Offset, GeomError> {
        let distance = super::finite("offset distance", distance)?;
        if let Surface::Offset(inner) = base {
            return Offset::new(*inner.base, inner.distance + distance);
        }
        if base.depth() >= MAX_NESTING {
            return Err(GeomError::NestingTooDeep { limit: MAX_NESTING });
        }
        if base.offsets() >= MAX_NESTED_OFFSETS {
            return Err(GeomError::NestingTooDeep {
                limit: MAX_NESTED_OFFSETS,
            });
        }
        Ok(Offset {
            base: Box::new(base),
            distance,
        })
    }

    /// The base surface.
    pub fn base(&self) -> &Surface {
        &self.base
    }

    /// The offset distance (along the base's normal).
    pub fn distance(&self) -> f64 {
        self.distance
    }

    /// The base's unit normal at `uv` (its limit at a pole; NaN where it has none).
    fn base_normal(&self, uv: [f64; 2]) -> Point3 {
        self.base
            .limit_normal(uv)
            .unwrap_or(Point3::new(f64::NAN, f64::NAN, f64::NAN))
    }

    /// The difference step of each parameter: [`DIFFERENCE_STEP`] of its finite extent, or of
    /// the parameter change that moves the base by its length scale.
    fn steps(&self, b: &SurfaceDerivatives) -> [f64; 2] {
        let lengths = self.base.param_box().lengths();
        let scale = self.base.length_scale();
        std::array::from_fn(|i| {
            let speed = if i == 0 { b.du.length() } else { b.dv.length() };
            let extent = if lengths[i].is_finite() && lengths[i] > 0.0 {
                lengths[i]
            } else if speed > 0.0 {
                scale / speed
            } else {
                1.0
            };
            DIFFERENCE_STEP * extent
        })
    }

    /// `(S, S_u, S_v, N)`: the point, its analytic first derivatives and the base's normal;
    /// `None` for the last where `uv` is a pole of the base (its normal is then the limit
    /// [`Offset::base_normal`]).
    fn first(&self, uv: [f64; 2]) -> (Point3, Point3, Point3, Option<Point3>) {
        let b = self.base.derivatives(uv);
        let d = self.distance;
        let w = b.du.cross(b.dv);
        let (lu, lv) = (b.du.length(), b.dv.length());
        let regular = lu > super::POLE_DERIVATIVE_RATIO * lv
            && lv > super::POLE_DERIVATIVE_RATIO * lu
            && w.length() > 0.0;
        if regular {
            let wl = w.length();
            let n = w * (1.0 / wl);
            let wu = b.duu.cross(b.dv) + b.du.cross(b.duv);
            let wv = b.duv.cross(b.dv) + b.du.cross(b.dvv);
            let nu = (wu - n * n.dot(wu)) * (1.0 / wl);
            let nv = (wv - n * n.dot(wv)) * (1.0 / wl);
            return (b.point + n * d, b.du + nu * d, b.dv + nv * d, Some(n));
        }
        // A pole of the base: the limit normal, its derivatives one-sided differences into the
        // box.
        let n = self.base_normal(uv);
        let h = self.steps(&b);
        let side = interior_side(&self.base.param_box(), uv);
        let slope = |i: usize| {
            let step = h[i] * side[i];
            let at = |k: f64| {
                let mut q = uv;
                q[i] += k * step;
                self.base_normal(q)
            };
            (at(1.0) * 4.0 - n * 3.0 - at(2.0)) * (0.5 / step)
        };
        (
            b.point + n * d,
            b.du + slope(0) * d,
            b.dv + slope(1) * d,
            None,
        )
    }
}

/// The derivative at `t` of `f` by differences with step `h`: central where `[t - h, t + h]`
/// is in `[lo, hi]`, otherwise the one-sided second-order formula into the range.
fn difference(f: impl Fn(f64) -> Point3, t: f64, h: f64, lo: f64, hi: f64) -> Point3 {
    if t - h >= lo && t + h <= hi {
        (f(t + h) - f(t - h)) * (0.5 / h)
    } else if t + 2.0 * h <= hi {
        (f(t + h) * 4.0 - f(t) * 3.0 - f(t + 2.0 * h)) * (0.5 / h)
    } else {
        (f(t) * 3.0 - f(t - h) * 4.0 + f(t - 2.0 * h)) * (0.5 / h)
    }
}

impl ParamSurface for Offset {
    fn point(&self, uv: [f64; 2]) -> Point3 {
        self.base.point(uv) + self.base_normal(uv) * self.distance
    }

    fn derivatives(&self, uv: [f64; 2]) -> SurfaceDerivatives {
        let (point, du, dv, _) = self.first(uv);
        let b = self.base.derivatives(uv);
        let h = self.steps(&b);
        let bx = self.base.param_box();
        let periods = self.base.periods();
        let range = |i: usize| {
            if periods[i].is_some() {
                (f64::NEG_INFINITY, f64::INFINITY)
            } else {
                bx.range(i)
            }
        };
        let (ur, vr) = (range(0), range(1));
        let along_u = |i: usize| {
            difference(
                |t| {
                    let (_, a, b, _) = self.first([t, uv[1]]);
                    if i == 0 { a } else { b }
                },
                uv[0],
                h[0],
                ur.0,
                ur.1,
            )
        };
        let along_v = |i: usize| {
            difference(
                |t| {
                    let (_, a, b, _) = self.first([uv[0], t]);
                    if i == 0 { a } else { b }
                },
                uv[1],
                h[1],
                vr.0,
                vr.1,
            )
        };
        SurfaceDerivatives {
            point,
            du,
            dv,
            duu: along_u(0),
            duv: (along_v(0) + along_u(1)) * 0.5,
            dvv: along_v(1),
        }
    }

    /// The base's normal, turned where the offset reverses the surface (past a centre of
    /// curvature: `S_u x S_v` against it); `None` where the offset surface folds
    /// (`S_u x S_v = 0`) or the base has no normal. At a pole of the base, its limit normal,
    /// turned as the offset is beside the pole.
    fn normal(&self, uv: [f64; 2]) -> Option<Point3> {
        let (_, du, dv, n) = self.first(uv);
        let Some(n) = n else {
            let n = self.base.limit_normal(uv)?;
            let b = self.base.derivatives(uv);
            let h = self.steps(&b);
            let side = interior_side(&self.param_box(), uv);
            let beside = [uv[0] + 1e2 * h[0] * side[0], uv[1] + 1e2 * h[1] * side[1]];
            let (_, du, dv, _) = self.first(beside);
            let s = du.cross(dv).dot(n);
            return if s < 0.0 { Some(-n) } else { Some(n) };
        };
        let w = du.cross(dv);
        let s = w.dot(n);
        if w.length() <= PARALLEL_SINE * du.length() * dv.length() || s == 0.0 {
            return None;
        }
        Some(n * s.signum())
    }

    fn param_box(&self) -> ParamBox {
        self.base.param_box()
    }

    fn periods(&self) -> [Option<f64>; 2] {
        self.base.periods()
    }

    /// The base's poles whose line stays one point (a sphere's: its normal is the same along
    /// it); the apices of a cone offset towards its axis (`d < 0`: each nappe's offset is a
    /// cone, with apex at `v = -(r +- d cos a) / tan a`; offset away from the axis the nappes
    /// never reach it); the poles of a ring torus offset to a tube of radius `r + d` that
    /// reaches the axis (`R + (r + d) cos v = 0`).
    fn poles(&self) -> Vec<Pole> {
        let scale = self.base.length_scale() + self.distance.abs();
        let mut out: Vec<Pole> = self
            .base
            .poles()
            .into_iter()
            .filter(|p| {
                let line = |k: usize| {
                    let t = std::f64::consts::TAU * k as f64 / POLE_SAMPLES as f64;
                    let mut uv = [t, t];
                    uv[p.param] = p.value;
                    let other = 1 - p.param;
                    let (a, b) = self.param_box().range(other);
                    if a.is_finite() && b.is_finite() {
                        uv[other] = a + (b - a) * k as f64 / POLE_SAMPLES as f64;
                    }
                    self.point(uv)
                };
                let first = line(0);
                (1..=POLE_SAMPLES).all(|k| line(k).distance(first) <= COINCIDENCE_RELATIVE * scale)
            })
            .collect();
        match &*self.base {
            Surface::Cone(c) if self.distance < 0.0 => {
                let (s, co) = c.semi_angle().sin_cos();
                let shift = self.distance * co;
                for r in [c.radius() + shift, c.radius() - shift] {
                    out.push(Pole {
                        param: 1,
                        value: -r / (s / co),
                    });
                }
            }
            Surface::Torus(t) if t.minor_radius() < t.major_radius() => {
                let tube = t.minor_radius() + self.distance;
                let c = -t.major_radius() / tube;
                if (-1.0..=1.0).contains(&c) {
                    let v = c.acos();
                    out.push(Pole { param: 1, value: v });
                    if v != std::f64::consts::PI && v != 0.0 {
                        out.push(Pole {
                            param: 1,
                            value: std::f64::consts::TAU - v,
                        });
                    }
                }
            }
            _ => {}
        }
        out
    }

    /// Newton's method on the offset surface (see [`crate::surface`]) from `near`, from the
    /// base's closest point (where the offset's normal is the base's, the same parameters),
    /// and from the best nodes of the base's sampling grid where its box is bounded.
    fn invert(&self, x: Point3, near: Option<[f64; 2]>) -> Inversion {
        let fallback = self.param_box().clamp([0.0, 0.0]);
        if let Some(bad) = hostile_point(x, near, fallback) {
            return bad;
        }
        let near = usable_near(near);
        let start = self.base.invert(x, near).uv;
        let grid = self.base.sample_grid();
        let size = self.base.length_scale() + self.distance.abs();
        closest(self, x, near, &[start], grid.as_ref(), size)
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::FRAC_PI_2;

    use super::*;
    use crate::Frame;
    use crate::surface::testing::{
        Rng, check_derivatives, check_normal, check_round_trip, sphere_octant,
    };
    use crate::surface::{Cone, Cylinder, Plane, Sphere, Torus};

    #[test]
    fn offset_of_a_plane_is_the_shifted_plane() {
        let mut rng = Rng::new(31);
        for _ in 0..10 {
            let f = rng.frame(5.0);
            let d = rng.range(-3.0, 3.0);
            let s = Offset::new(Surface::Plane(Plane::new(f)), d).unwrap();
            let shifted = Plane::new(Frame {
                origin: f.origin + f.z * d,
                ..f
            });
            for _ in 0..5 {
                let uv = [rng.range(-4.0, 4.0), rng.range(-4.0, 4.0)];
                let (a, b) = (s.derivatives(uv), shifted.derivatives(uv));
                assert!(a.point.distance(b.point) < 1e-14 * 10.0);
                assert!(a.du.distance(b.du) < 1e-14 && a.dv.distance(b.dv) < 1e-14);
                for v in [a.duu, a.duv, a.dvv] {
                    assert!(v.length() < 1e-9);
                }
                check_normal(&s, uv);
                check_round_trip(&s, uv, None, 1e-10, 10.0);
                let x = rng.point(6.0);
                let inv = s.invert(x, None);
                assert!((inv.distance - shifted.invert(x, None).distance).abs() < 1e-12 * 10.0);
            }
        }
    }

    #[test]
    fn offset_of_a_sphere_is_the_concentric_sphere() {
        let mut rng = Rng::new(32);
        for _ in 0..10 {
            let f = rng.frame(5.0);
            let r = rng.range(1.0, 3.0);
            let d = rng.range(-0.9 * r, 2.0);
            let s = Offset::new(Surface::Sphere(Sphere::new(f, r).unwrap()), d).unwrap();
            let big = Sphere::new(f, r + d).unwrap();
            assert_eq!(s.poles().len(), 2);
            for _ in 0..5 {
                let uv = [rng.range(-4.0, 4.0), rng.range(-1.4, 1.4)];
                let (a, b) = (s.derivatives(uv), big.derivatives(uv));
                assert!(a.point.distance(b.point) < 1e-13 * 10.0);
                assert!(a.du.distance(b.du) < 1e-13 * 10.0 && a.dv.distance(b.dv) < 1e-13 * 10.0);
                for (p, q) in [(a.duu, b.duu), (a.duv, b.duv), (a.dvv, b.dvv)] {
                    assert!(p.distance(q) < 1e-8 * 10.0, "{p:?} vs {q:?}");
                }
                check_derivatives(&s, uv, 1.0);
                check_normal(&s, uv);
                check_round_trip(&s, uv, None, 1e-10, 10.0);
                let x = f.origin + rng.point(6.0);
                let inv = s.invert(x, None);
                let expected = (x.distance(f.origin) - (r + d)).abs();
                assert!(
                    (inv.distance - expected).abs() < 1e-12 * 10.0,
                    "{inv:?} vs {expected}"
                );
            }
            // At the poles: the concentric sphere's pole, the normal the base's.
            for v in [-FRAC_PI_2, FRAC_PI_2] {
                assert!(s.point([0.7, v]).distance(big.point([0.7, v])) < 1e-13 * 10.0);
                assert!(s.normal([0.7, v]).unwrap().distance(f.z * v.signum()) < 1e-12);
                let sd = s.derivatives([0.7, v]);
                assert!(sd.dv.distance(big.derivatives([0.7, v]).dv) < 1e-6 * 10.0);
            }
        }
    }

    #[test]
    fn offsets_of_cylinders_cones_and_tori() {
        let mut rng = Rng::new(33);
        let f = rng.frame(3.0);
        let cyl = Offset::new(Surface::Cylinder(Cylinder::new(f, 2.0).unwrap()), 0.5).unwrap();
        let wide = Cylinder::new(f, 2.5).unwrap();
        let cone = Offset::new(Surface::Cone(Cone::new(f, 1.0, 0.6).unwrap()), -0.4).unwrap();
        let outer = Offset::new(Surface::Cone(Cone::new(f, 1.0, 0.6).unwrap()), 0.4).unwrap();
        let torus = Offset::new(Surface::Torus(Torus::new(f, 3.0, 1.0).unwrap()), -0.3).unwrap();
        let thin = Torus::new(f, 3.0, 0.7).unwrap();
        for _ in 0..10 {
            // Above the offset cone's apices (v = -0.98 and -1.94) and the base's (-1.46).
            let uv = [rng.range(-4.0, 4.0), rng.range(-0.5, 1.5)];
            assert!(cyl.point(uv).distance(wide.point(uv)) < 1e-13 * 10.0);
            assert!(torus.point(uv).distance(thin.point(uv)) < 1e-13 * 10.0);
            for s in [&cyl, &cone, &outer, &torus] {
                check_derivatives(s, uv, 1.0);
                check_normal(s, uv);
                check_round_trip(s, uv, Some(uv), 1e-10, 10.0);
            }
            // The offset cone is a cone of the same angle: the distance to the base is |d|.
            let p = cone.point(uv);
            let base = cone.base().invert(p, Some(uv));
            assert!((base.distance - 0.4).abs() < 1e-12);
        }
        // The inner offset's nappes reach the axis at v = -(r +- d cos a) / tan a: poles; the
        // base's apex is no pole of either offset (its line is a circle).
        let poles = cone.poles();
        assert_eq!(poles.len(), 2);
        for apex in poles {
            assert!(
                cone.point([0.1, apex.value])
                    .distance(cone.point([2.0, apex.value]))
                    < 1e-12
            );
        }
        assert!(outer.poles().is_empty());
        let fat = Offset::new(Surface::Torus(Torus::new(f, 1.0, 0.5).unwrap()), 0.7).unwrap();
        for p in fat.poles() {
            assert!(
                fat.point([0.1, p.value])
                    .distance(fat.point([2.0, p.value]))
                    < 1e-12
            );
        }
        assert_eq!(fat.poles().len(), 2);
    }

    #[test]
    fn offset_of_a_rational_octant_is_the_concentric_octant() {
        let s = Offset::new(Surface::BSpline(sphere_octant(2.0)), 0.5).unwrap();
        let sphere = Sphere::new(Frame::WORLD, 2.5).unwrap();
        // The pole column stays a pole: the normal is +z all along it.
        assert_eq!(
            s.poles(),
            vec![Pole {
                param: 1,
                value: 1.0
            }]
        );
        assert!(s.point([0.3, 1.0]).distance(Point3::new(0.0, 0.0, 2.5)) < 1e-12);
        let mut rng = Rng::new(34);
        for _ in 0..20 {
            let uv = [rng.range(0.03, 0.97), rng.range(0.03, 0.97)];
            assert!((s.point(uv).length() - 2.5).abs() < 1e-13 * 4.0);
            check_derivatives(&s, uv, 0.1);
            check_normal(&s, uv);
            check_round_trip(&s, uv, None, 1e-10, 4.0);
            let dir = Point3::new(
                rng.range(0.05, 1.0),
                rng.range(0.05, 1.0),
                rng.range(0.05, 1.0),
            );
            let x = dir * (rng.range(0.2, 5.0) / dir.length());
            let (i, j) = (s.invert(x, Some(uv)), sphere.invert(x, None));
            assert!(
                (i.distance - j.distance).abs() < 1e-12 * 4.0,
                "{i:?} vs {j:?}"
            );
            assert!(s.point(i.uv).distance(sphere.point(j.uv)) < 1e-10 * 4.0);
        }
    }

    #[test]
    fn offsets_of_offsets_merge_and_nesting_is_bounded() {
        let mut s = Surface::Plane(Plane::new(Frame::WORLD));
        for _ in 0..40 {
            s = Surface::Offset(Offset::new(s, 0.1).unwrap());
        }
        let Surface::Offset(o) = &s else {
            unreachable!()
        };
        assert!(matches!(o.base(), Surface::Plane(_)) && (o.distance() - 4.0).abs() < 1e-12);
        assert!((s.point([1.0, 2.0]).z - 4.0).abs() < 1e-12);
        // Offsets of reparameterised offsets: at most MAX_NESTED_OFFSETS in a chain.
        let sphere = Surface::Sphere(Sphere::new(Frame::WORLD, 1.0).unwrap());
        let mut s = sphere;
        for k in 0..MAX_NESTED_OFFSETS {
            s = Surface::Offset(Offset::new(s, 0.1).unwrap());
            s = Surface::Reparam(
                crate::surface::Reparam::new(s, k % 2 == 0, [1.0, 1.0], [0.0, 0.0]).unwrap(),
            );
        }
        assert!(matches!(
            Offset::new(s.clone(), 0.1),
            Err(GeomError::NestingTooDeep { .. })
        ));
        // The swapped reparameterisation turns the normal inwards: 1 + 0.1 - 0.1 - 0.1.
        let uv = [0.4, 0.3];
        assert!((s.point(uv).length() - 0.9).abs() < 1e-12);
        check_derivatives(&s, uv, 1.0);
        assert!(Offset::new(s, f64::NAN).is_err());
    }
}
