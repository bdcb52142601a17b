//! A surface in other parameters: swapped, scaled and shifted. IGES 120 (surface of
//! revolution: `(curve parameter, angle)`, ISO's swapped), IGES 122 (tabulated cylinder: the
//! directrix's parameter normalised), pcurves of STEP files in degrees (the angles scaled by
//! `pi / 180`), and the images of elementary surfaces under scalings and reflections.

use rs_spline::Point3;

use super::{
    Inversion, MAX_NESTING, ParamBox, ParamSurface, Pole, Surface, SurfaceDerivatives,
    hostile_point, usable_near,
};
use crate::GeomError;

/// `S(u, v) = B(a p + b, c q + d)` with `(p, q) = (u, v)`, or `(v, u)` when swapped: `scale =
/// [a, c]` and `offset = [b, d]` act on the base's parameters, after the swap. Derivatives by
/// the chain rule; the normal is the base's, turned where the map reverses orientation (`a c
/// < 0` without swap, `a c > 0` with); periods, poles and box are the base's mapped back.
#[derive(Clone, Debug, PartialEq)]
pub struct Reparam {
    base: Box<Surface>,
    swap: bool,
    scale: [f64; 2],
    offset: [f64; 2],
}

impl Reparam {
    /// `base` in the parameters `(u, v) -> (scale[0] p + offset[0], scale[1] q + offset[1])`
    /// with `(p, q) = (u, v)`, or `(v, u)` when `swap`. A base that is itself a [`Reparam`]
    /// is composed with this one into one map.
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] for a non-finite scale or offset; [`GeomError::Zero`] for a
    /// zero scale; [`GeomError::NestingTooDeep`] for a base with [`MAX_NESTING`] offsets and
    /// reparameterisations in it.
    pub fn new(
        base: Surface,
        swap: bool,
        scale: [f64; 2],
        offset: [f64; 2],
    ) -> Result<Reparam, GeomError> {
        for s in scale {
            super::finite("parameter scale", s)?;
            if s == 0.0 {
                return Err(GeomError::Zero {
                    what: "parameter scale",
                });
            }
        }
        for o in offset {
            super::finite("parameter offset", o)?;
        }
        if let Surface::Reparam(inner) = base {
            // base(A_i(s_i(A_o(s_o(p))))) = base(A(s_i s_o (p))) with the outer map's
            // coefficients permuted by the inner swap.
            let perm = |a: [f64; 2]| if inner.swap { [a[1], a[0]] } else { a };
            let (sc, of) = (perm(scale), perm(offset));
            return Reparam::new(
                *inner.base,
                inner.swap ^ swap,
                [inner.scale[0] * sc[0], inner.scale[1] * sc[1]],
                [
                    inner.scale[0] * of[0] + inner.offset[0],
                    inner.scale[1] * of[1] + inner.offset[1],
                ],
            );
        }
        if base.depth() >= MAX_NESTING {
            return Err(GeomError::NestingTooDeep { limit: MAX_NESTING });
        }
        Ok(Reparam {
            base: Box::new(base),
            swap,
            scale,
            offset,
        })
    }

    /// The base surface.
    pub fn base(&self) -> &Surface {
        &self.base
    }

    /// Whether `u` and `v` are swapped before scaling.
    pub fn swap(&self) -> bool {
        self.swap
    }

    /// The scales of the base's two parameters.
    pub fn scale(&self) -> [f64; 2] {
        self.scale
    }

    /// The offsets of the base's two parameters.
    pub fn offset(&self) -> [f64; 2] {
        self.offset
    }

    /// Which of our parameters the base's parameter `k` comes from.
    fn ours(&self, k: usize) -> usize {
        if self.swap { 1 - k } else { k }
    }

    /// The base's parameters of our `uv`.
    pub fn to_base(&self, uv: [f64; 2]) -> [f64; 2] {
        std::array::from_fn(|k| self.scale[k] * uv[self.ours(k)] + self.offset[k])
    }

    /// Our parameters of the base's `st`.
    pub fn from_base(&self, st: [f64; 2]) -> [f64; 2] {
        let mut uv = [0.0; 2];
        for (k, &t) in st.iter().enumerate() {
            uv[self.ours(k)] = (t - self.offset[k]) / self.scale[k];
        }
        uv
    }

    /// The base's sampling grid in our parameters.
    pub(crate) fn sample_grid(&self) -> Option<[Vec<f64>; 2]> {
        let grid = self.base.sample_grid()?;
        let mut out: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
        for (k, values) in grid.into_iter().enumerate() {
            let mut mapped: Vec<f64> = values
                .into_iter()
                .map(|t| (t - self.offset[k]) / self.scale[k])
                .collect();
            mapped.sort_by(f64::total_cmp);
            out[self.ours(k)] = mapped;
        }
        Some(out)
    }
}

impl ParamSurface for Reparam {
    fn point(&self, uv: [f64; 2]) -> Point3 {
        self.base.point(self.to_base(uv))
    }

    /// The chain rule: `S_u = a B_s`, `S_uv = a c B_st`, ... (with the swap, `S_u = c B_t`,
    /// `S_uu = c^2 B_tt`, `S_vv = a^2 B_ss`).
    fn derivatives(&self, uv: [f64; 2]) -> SurfaceDerivatives {
        let b = self.base.derivatives(self.to_base(uv));
        let [a, c] = self.scale;
        let (bs, bt, bss, btt) = (b.du * a, b.dv * c, b.duu * (a * a), b.dvv * (c * c));
        let mixed = b.duv * (a * c);
        if self.swap {
            SurfaceDerivatives {
                point: b.point,
                du: bt,
                dv: bs,
                duu: btt,
                duv: mixed,
                dvv: bss,
            }
        } else {
            SurfaceDerivatives {
                point: b.point,
                du: bs,
                dv: bt,
                duu: bss,
                duv: mixed,
                dvv: btt,
            }
        }
    }

    fn normal(&self, uv: [f64; 2]) -> Option<Point3> {
        let n = self.base.normal(self.to_base(uv))?;
        let positive = (self.scale[0] * self.scale[1] > 0.0) != self.swap;
        Some(if positive { n } else { -n })
    }

    fn param_box(&self) -> ParamBox {
        let bx = self.base.param_box();
        let mut ranges = [(0.0, 0.0); 2];
        for k in 0..2 {
            let (lo, hi) = bx.range(k);
            let (a, b) = (
                (lo - self.offset[k]) / self.scale[k],
                (hi - self.offset[k]) / self.scale[k],
            );
            ranges[self.ours(k)] = (a.min(b), a.max(b));
        }
        ParamBox {
            u: ranges[0],
            v: ranges[1],
        }
    }

    fn periods(&self) -> [Option<f64>; 2] {
        let base = self.base.periods();
        let mut out = [None; 2];
        for k in 0..2 {
            out[self.ours(k)] = base[k].map(|p| p / self.scale[k].abs());
        }
        out
    }

    fn poles(&self) -> Vec<Pole> {
        self.base
            .poles()
            .into_iter()
            .map(|p| Pole {
                param: self.ours(p.param),
                value: (p.value - self.offset[p.param]) / self.scale[p.param],
            })
            .collect()
    }

    /// The base's inversion, in the base's parameters (`near` mapped there and the answer
    /// mapped back).
    fn invert(&self, x: Point3, near: Option<[f64; 2]>) -> Inversion {
        let near = usable_near(near);
        if let Some(bad) = hostile_point(x, near, [0.0, 0.0]) {
            return bad;
        }
        let inv = self.base.invert(x, near.map(|n| self.to_base(n)));
        let uv = self.from_base(inv.uv);
        let uv = match near {
            Some(_) => uv,
            None => super::place_periodic(uv, None, self.periods(), &self.param_box()),
        };
        Inversion {
            uv,
            distance: inv.distance,
        }
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{PI, TAU};

    use super::*;
    use crate::surface::testing::{Rng, check_derivatives, check_normal, check_round_trip};
    use crate::surface::{Cone, Revolution, Torus};
    use crate::{Curve, Frame};

    #[test]
    fn chain_rule_periods_poles_and_inversion() {
        let mut rng = Rng::new(51);
        let f = rng.frame(3.0);
        let cone = Surface::Cone(Cone::new(f, 1.0, 0.5).unwrap());
        let torus = Surface::Torus(Torus::new(f, 3.0, 1.0).unwrap());
        for base in [cone, torus] {
            for swap in [false, true] {
                // Degrees in the angle, a reversed and shifted second parameter.
                let scale = [PI / 180.0, -2.0];
                let s = Reparam::new(base.clone(), swap, scale, [0.3, 1.0]).unwrap();
                for _ in 0..10 {
                    let (p, q) = (rng.range(-200.0, 200.0), rng.range(-0.5, 0.5));
                    let uv = if swap { [q, p] } else { [p, q] };
                    let st = s.to_base(uv);
                    assert!(s.point(uv).distance(base.point(st)) < 1e-15 * 10.0);
                    assert_eq!(
                        s.from_base(st).map(|t| (t * 1e9).round()),
                        uv.map(|t| (t * 1e9).round())
                    );
                    // Steps of 1e-2 in both: a hundredth of a degree, a hundredth of v.
                    check_derivatives(&s, uv, 1.0);
                    check_normal(&s, uv);
                    check_round_trip(&s, uv, Some(uv), 1e-12, 1e3);
                }
                let periods = s.periods();
                let angle = if swap { 1 } else { 0 };
                assert!((periods[angle].unwrap() - 360.0).abs() < 1e-12);
                for p in s.poles() {
                    let mut a = [10.0, 10.0];
                    a[p.param] = p.value;
                    let mut b = a;
                    b[1 - p.param] = 100.0;
                    assert!(s.point(a).distance(s.point(b)) < 1e-12);
                }
                let bx = s.param_box();
                assert!((bx.range(angle).1 - bx.range(angle).0 - 360.0).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn iges_120_is_a_swapped_revolution_and_nesting_composes() {
        // IGES 120: (t along the generatrix, angle); ISO's revolution is (angle, t).
        let line = Curve::Line {
            origin: Point3::new(1.0, 0.0, 0.0),
            direction: Point3::new(0.5, 0.0, 1.0),
        };
        let rev = Surface::Revolution(Revolution::new(line, Point3::ORIGIN, Point3::Z).unwrap());
        let iges = Reparam::new(rev.clone(), true, [1.0, 1.0], [0.0, 0.0]).unwrap();
        assert_eq!(iges.point([0.5, 1.0]), rev.point([1.0, 0.5]));
        assert_eq!(iges.periods(), [None, Some(TAU)]);
        let inv = iges.invert(rev.point([2.0, 0.7]), None);
        assert!((inv.uv[0] - 0.7).abs() < 1e-12 && (inv.uv[1] - 2.0).abs() < 1e-12);
        // A reparameterisation of a reparameterisation is one map.
        let twice = Reparam::new(
            Surface::Reparam(iges.clone()),
            true,
            [2.0, 3.0],
            [1.0, -1.0],
        )
        .unwrap();
        assert!(!twice.swap() && !matches!(twice.base(), Surface::Reparam(_)));
        for uv in [[0.1, 0.2], [-1.0, 2.0]] {
            let direct = iges.point([2.0 * uv[1] + 1.0, 3.0 * uv[0] - 1.0]);
            assert!(twice.point(uv).distance(direct) < 1e-14);
        }
        assert!(matches!(
            Reparam::new(rev.clone(), false, [0.0, 1.0], [0.0, 0.0]),
            Err(GeomError::Zero { .. })
        ));
        assert!(Reparam::new(rev, false, [1.0, 1.0], [f64::NAN, 0.0]).is_err());
        let _ = Frame::WORLD;
    }
}
