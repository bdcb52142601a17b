//! Surfaces of linear extrusion: a curve swept along a vector (ISO 10303-42
//! `SURFACE_OF_LINEAR_EXTRUSION`: `u` the curve's parameter, `v` the multiple of the extrusion
//! vector with its magnitude; `OpenCASCADE`'s `Geom_SurfaceOfLinearExtrusion` measures `v` along
//! the unit direction, `v_occ = v |D|`; IGES 122 (tabulated cylinder) normalises the
//! directrix's parameter to `[0, 1]` and runs `v` from the directrix to the generatrix's end:
//! a [`super::Reparam`] of this).

use rs_spline::Point3;

use super::invert::minimize_1d;
use super::swept::Swept;
use super::{
    Inversion, ParamBox, ParamSurface, Pole, SurfaceDerivatives, finish, hostile_point,
    interior_side, normal_from_derivatives, usable_near,
};
use crate::{Curve, GeomError};

/// Results of the 1-D search whose distances differ by less than this fraction of the
/// surface's size are at the same distance (the one nearest `near` is kept).
const TIE_RELATIVE: f64 = 1e-12;

/// The surface swept by a curve `C` moved along a vector `D`: `S(u, v) = C(u) + v D`. `u` is
/// the curve's parameter, on its range (periodic where the curve is closed); `v` is
/// unbounded.
#[derive(Clone, Debug, PartialEq)]
pub struct Extrusion {
    swept: Swept,
    vector: Point3,
    size: f64,
}

impl Extrusion {
    /// The surface swept by `curve` along `vector` (with its length).
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] for a non-finite vector or a curve whose start is not finite;
    /// [`GeomError::Zero`] for a zero vector.
    pub fn new(curve: Curve<Point3>, vector: Point3) -> Result<Extrusion, GeomError> {
        if !vector.is_finite() {
            return Err(GeomError::NotFinite {
                what: "extrusion vector",
                value: vector.max_abs(),
            });
        }
        if vector.length() == 0.0 {
            return Err(GeomError::Zero {
                what: "extrusion vector",
            });
        }
        let swept = Swept::new(curve)?;
        let start = swept.point(if swept.range.0.is_finite() {
            swept.range.0
        } else {
            0.0
        });
        let size = swept.extent(start) + vector.length();
        Ok(Extrusion {
            swept,
            vector,
            size,
        })
    }

    /// The swept curve.
    pub fn curve(&self) -> &Curve<Point3> {
        &self.swept.curve
    }

    /// The extrusion vector.
    pub fn vector(&self) -> Point3 {
        self.vector
    }

    /// The curve's extent plus the vector's length.
    pub(crate) fn size(&self) -> f64 {
        self.size
    }
}

impl ParamSurface for Extrusion {
    fn point(&self, uv: [f64; 2]) -> Point3 {
        self.swept.point(uv[0]) + self.vector * uv[1]
    }

    fn derivatives(&self, uv: [f64; 2]) -> SurfaceDerivatives {
        let [p, d1, d2] = self.swept.derivatives(uv[0]);
        SurfaceDerivatives {
            point: p + self.vector * uv[1],
            du: d1,
            dv: self.vector,
            duu: d2,
            ..SurfaceDerivatives::default()
        }
    }

    /// The unit `C' x D`; `None` where the curve runs along the vector or stops (`C' = 0`).
    fn normal(&self, uv: [f64; 2]) -> Option<Point3> {
        normal_from_derivatives(&self.derivatives(uv), interior_side(&self.param_box(), uv))
    }

    fn param_box(&self) -> ParamBox {
        ParamBox {
            u: self.swept.range,
            v: (f64::NEG_INFINITY, f64::INFINITY),
        }
    }

    fn periods(&self) -> [Option<f64>; 2] {
        [self.swept.period, None]
    }

    /// None: every line `u = const` is a line.
    fn poles(&self) -> Vec<Pole> {
        Vec::new()
    }

    /// `v` is a closed form (the projection onto the vector's line through the curve's point);
    /// what remains is the nearest point of the curve projected along the vector, a 1-D search
    /// on the curve (samples per knot span, then a bracketed Newton iteration; see
    /// [`crate::surface`]).
    fn invert(&self, x: Point3, near: Option<[f64; 2]>) -> Inversion {
        if let Some(bad) = hostile_point(x, near, [self.swept.range.0.max(0.0), 0.0]) {
            return bad;
        }
        let near = usable_near(near);
        let dir = self.vector * (1.0 / self.vector.length());
        let across = |p: Point3| p - dir * dir.dot(p);
        let f = |t: f64| -> [f64; 3] {
            let [p, p1, p2] = self.swept.derivatives(t);
            let (q, q1, q2) = (across(x - p), across(p1), across(p2));
            [q.dot(q), -2.0 * q.dot(q1), 2.0 * (q1.dot(q1) - q.dot(q2))]
        };
        let near_u = near.map(|n| match self.swept.period {
            Some(p) if self.swept.is_bounded() => super::copy_from(n[0], self.swept.range.0, p),
            _ => n[0],
        });
        let t0 = near_u.unwrap_or(0.0);
        let reach = f(t0)[0].sqrt();
        let window = self
            .swept
            .window(t0, |t| across(x - self.swept.point(t)).length() > reach);
        let samples = self.swept.samples(window);
        let tie = TIE_RELATIVE * (self.size + (x - self.swept.point(t0)).length());
        let prefer = if self.swept.is_bounded() {
            near_u
        } else {
            Some(t0)
        };
        let u = minimize_1d(f, &samples, prefer, tie);
        let v = (x - self.swept.point(u)).dot(self.vector) / self.vector.dot(self.vector);
        finish(self, x, [u, v], near)
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::TAU;

    use rs_spline::RationalBSpline;

    use super::*;
    use crate::surface::Cylinder;
    use crate::surface::testing::{Rng, check_derivatives, check_normal, check_round_trip};
    use crate::{Conic, ConicKind, Frame};

    #[test]
    fn an_extruded_circle_is_a_cylinder() {
        let mut rng = Rng::new(21);
        for _ in 0..10 {
            let f = rng.frame(5.0);
            let r = rng.range(0.5, 3.0);
            let h = rng.range(0.5, 3.0);
            let circle = Curve::Conic(Conic {
                kind: ConicKind::Ellipse,
                center: f.origin,
                u: f.x * r,
                v: f.y * r,
            });
            let s = Extrusion::new(circle, f.z * h).unwrap();
            let cyl = Cylinder::new(f, r).unwrap();
            assert_eq!(s.periods(), [Some(TAU), None]);
            for _ in 0..10 {
                let uv = [rng.range(-7.0, 7.0), rng.range(-3.0, 3.0)];
                let p = s.point(uv);
                assert!(p.distance(cyl.point([uv[0], uv[1] * h])) < 1e-13 * 10.0);
                check_derivatives(&s, uv, 1.0);
                check_normal(&s, uv);
                check_round_trip(&s, uv, None, 1e-12, 10.0);
                check_round_trip(&s, uv, Some([uv[0] - 3.0, 0.0]), 1e-12, 10.0);
                let x = f.origin + rng.point(5.0);
                let (i, j) = (s.invert(x, None), cyl.invert(x, None));
                assert!(
                    (i.distance - j.distance).abs() < 1e-12 * 10.0,
                    "{i:?} vs {j:?}"
                );
            }
        }
    }

    #[test]
    fn an_extruded_bspline_inverts_by_its_spans() {
        // A wavy cubic in the x-y plane, extruded along a tilted vector.
        let curve = RationalBSpline::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0],
            vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 2.0, 0.0),
                Point3::new(2.0, -2.0, 0.0),
                Point3::new(3.0, 2.0, 0.0),
                Point3::new(4.0, -1.0, 0.0),
                Point3::new(5.0, 1.0, 0.0),
                Point3::new(6.0, 0.0, 0.0),
            ],
            Some(vec![1.0, 0.8, 1.3, 1.0, 0.7, 1.1, 1.0]),
        )
        .unwrap();
        let s = Extrusion::new(Curve::BSpline(curve), Point3::new(0.3, 0.2, 2.0)).unwrap();
        assert_eq!(s.periods(), [None, None]);
        assert_eq!(s.param_box().u, (0.0, 1.0));
        let mut rng = Rng::new(22);
        for k in 0..40 {
            // Points inside knot spans, away from the knots by more than the differences' steps.
            let u = 0.25 * f64::from(k % 4) + rng.range(0.03, 0.22);
            let uv = [u, rng.range(-2.0, 2.0)];
            check_derivatives(&s, uv, 0.1);
            check_normal(&s, uv);
            check_round_trip(&s, uv, None, 1e-10, 10.0);
            // Off the surface along its normal (within the curvature radius): back to uv.
            let x = s.point(uv) + s.normal(uv).unwrap() * rng.range(-0.05, 0.05);
            let inv = s.invert(x, None);
            assert!(inv.distance <= x.distance(s.point(uv)) + 1e-12);
        }
        // The foot is global: no node of a dense grid over u (each with its nearest v, a
        // projection) is nearer.
        let dense: Vec<Point3> = (0..=4000)
            .map(|i| s.curve().point(f64::from(i) / 4000.0))
            .collect();
        let d = s.vector();
        for _ in 0..40 {
            let x = Point3::new(
                rng.range(-1.0, 7.0),
                rng.range(-3.0, 3.0),
                rng.range(-3.0, 3.0),
            );
            let inv = s.invert(x, None);
            let best = dense
                .iter()
                .map(|&c| {
                    let r = x - c;
                    (r - d * (r.dot(d) / d.dot(d))).length()
                })
                .fold(f64::INFINITY, f64::min);
            assert!(inv.distance <= best + 1e-12, "{inv:?} vs {best}");
        }
        // A point beyond the curve's end: the foot is on the end line u = 1.
        let x = s.point([1.0, 0.5]) + Point3::new(2.0, 0.0, 0.0);
        let inv = s.invert(x, None);
        assert_eq!(inv.uv[0], 1.0);
    }

    #[test]
    fn an_extruded_line_is_a_plane_and_a_parallel_one_is_degenerate() {
        let line = Curve::Line {
            origin: Point3::new(1.0, 0.0, 0.0),
            direction: Point3::new(0.0, 2.0, 0.0),
        };
        let s = Extrusion::new(line.clone(), Point3::new(0.0, 0.0, 3.0)).unwrap();
        let inv = s.invert(Point3::new(5.0, 4.0, 6.0), None);
        assert!((inv.uv[0] - 2.0).abs() < 1e-14 && (inv.uv[1] - 2.0).abs() < 1e-14);
        assert!((inv.distance - 4.0).abs() < 1e-14);
        assert!(s.normal([0.0, 0.0]).unwrap().distance(Point3::X) < 1e-15);
        // Extruded along itself: no normal; inversion still bounded, near's u kept.
        let flat = Extrusion::new(line, Point3::new(0.0, 1.0, 0.0)).unwrap();
        assert!(flat.normal([0.0, 0.0]).is_none());
        let inv = flat.invert(Point3::new(1.0, 5.0, 1.0), Some([0.5, 0.0]));
        assert!((inv.distance - 1.0).abs() < 1e-14 && (inv.uv[0] - 0.5).abs() < 1e-14);
        assert!(matches!(
            Extrusion::new(
                Curve::Line {
                    origin: Point3::ORIGIN,
                    direction: Point3::X
                },
                Point3::ORIGIN
            ),
            Err(GeomError::Zero { .. })
        ));
        let _ = Frame::WORLD;
    }
}
