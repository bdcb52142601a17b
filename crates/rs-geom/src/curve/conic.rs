//! Conics `center + f(t) u + g(t) v` in any dimension: points, derivatives, exact conversion to
//! rational B-splines, closed-form parameters of their points and exact closest points.

use std::f64::consts::{PI, TAU};
use std::ops::Div;

use rs_roots::{Polynomial, real_roots_in};
use rs_spline::{NurbsCurve, Point, RationalBSpline, Vector, circular_arc};

use super::closest::{DISTANCE_ROUNDING, foot_newton};
use super::conic_kind::ConicKind;
use crate::{AffineMap, GeomError};

/// The most rational quadratic pieces of a hyperbola arc: each spans at most one unit of its
/// parameter, where `cosh` stays well conditioned, so an arc converts only up to this many
/// parameter units.
pub const MAX_HYPERBOLA_PIECES: usize = 64;

/// A point within this distance of a conic, relative to the conic's size (`|center| + |u| +
/// |v|`), is on it: its closed-form parameter ([`Conic::parameter_of`]) is its closest one
/// (exact for a point on the conic; for a point this near, off by as little as the point is
/// off the curve), so points read from a file keep the parameters the formulas give.
const ON_CONIC_RELATIVE_DISTANCE: f64 = 1e-12;

/// A conic `center + f(t) u + g(t) v`: `(f, g) = (cos t, sin t)` for an ellipse (`u`, `v` its
/// semi-axes as vectors), `(cosh t, sinh t)` for a hyperbola's branch, `(t^2, 2 t)` for a
/// parabola (`center` its vertex, `u = f x`, `v = f y` with the focal distance `f`).
///
/// # Examples
///
/// ```
/// use rs_geom::{Conic, ConicKind, Point3};
/// let circle = Conic {
///     kind: ConicKind::Ellipse,
///     center: Point3::new(0.0, 0.0, 1.0),
///     u: Point3::new(2.0, 0.0, 0.0),
///     v: Point3::new(0.0, 2.0, 0.0),
/// };
/// let arc = circle.to_bspline(0.0, 1.0).unwrap();
/// let p = arc.point_at(0.3);
/// assert!((p.x.hypot(p.y) - 2.0).abs() < 1e-15 && p.z == 1.0);
/// assert!((circle.closest_parameter(Point3::new(0.0, 5.0, 7.0), None) - 1.5707963267948966).abs() < 1e-15);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Conic<P> {
    /// The kind.
    pub kind: ConicKind,
    /// The centre (the vertex of a parabola).
    pub center: P,
    /// The first axis vector (its length is the first semi-axis, or the focal distance).
    pub u: P,
    /// The second axis vector.
    pub v: P,
}

impl<P: Vector> Conic<P> {
    /// The point at `t`.
    pub fn point(&self, t: f64) -> P {
        self.derivatives(t)[0]
    }

    /// `[C(t), C'(t), C''(t)]`.
    pub fn derivatives(&self, t: f64) -> [P; 3] {
        let (f, g) = self.kind.basis(t);
        [
            self.center + self.u * f[0] + self.v * g[0],
            self.u * f[1] + self.v * g[1],
            self.u * f[2] + self.v * g[2],
        ]
    }

    /// The conic's size, `|center| + |u| + |v|`: the scale of its coordinates' rounding.
    fn size(&self) -> f64 {
        self.center.norm() + self.u.norm() + self.v.norm()
    }

    /// The parameter of a point of the conic, in closed form: with `a = (x - c) . u / |u|^2`
    /// and `b = (x - c) . v / |v|^2` (the point's coordinates along orthogonal axes `u`, `v`),
    /// `atan2(b, a)` in `(-pi, pi]` for an ellipse, `asinh(b)` for a hyperbola, `b / 2` for a
    /// parabola. Exact for points on the conic when `u` and `v` are orthogonal (as every
    /// conic read from STEP or IGES is); for other points the parameter of a nearby point (see
    /// [`Conic::closest_parameter`] for the closest one).
    pub fn parameter_of(&self, x: P) -> f64 {
        let d = x - self.center;
        let a = d.dot(self.u) / self.u.dot(self.u);
        let b = d.dot(self.v) / self.v.dot(self.v);
        match self.kind {
            ConicKind::Ellipse => b.atan2(a),
            ConicKind::Hyperbola => b.asinh(),
            ConicKind::Parabola => 0.5 * b,
        }
    }

    /// The parameter of the point of the conic nearest `x`, within `window` (`None`: the whole
    /// conic; an ellipse's parameter then in `(-pi, pi]`, else in the window, whichever copy
    /// of the period lies in it).
    ///
    /// A point on the conic (within `1e-12` of its size, `|center| + |u| + |v|`) gets its
    /// closed-form parameter ([`Conic::parameter_of`]). Otherwise the candidates are the roots
    /// of the foot condition `(C(t) - x) . C'(t) = 0`, exactly: a quartic in `tan(t / 2)` for
    /// an ellipse (on each half of the period), a quartic in `e^t` for a hyperbola (on each
    /// side of `t = 0`), a cubic in `t` for a parabola; each polished by Newton's method in
    /// `t`, with the window's ends; the nearest wins, the closed form when none is nearer by
    /// more than rounding (on a circle, where it is every point's foot, the closed form). `x`
    /// off the conic's plane is measured in space (its foot is its projection's).
    pub fn closest_parameter(&self, x: P, window: Option<(f64, f64)>) -> f64 {
        let distance = |t: f64| self.point(t).distance_to(x);
        let closed = self.in_window(self.parameter_of(x), window);
        if let Some(t) = closed
            && distance(t) <= ON_CONIC_RELATIVE_DISTANCE * self.size()
        {
            return t;
        }
        let mut best: Option<(f64, f64)> = None;
        let mut consider = |t: f64| {
            let d = distance(t);
            if t.is_finite() && best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, t));
            }
        };
        let bounds = window.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
        for t in self.foot_candidates(x, window) {
            consider(foot_newton(|t| self.derivatives(t), x, t, bounds));
        }
        if let Some((lo, hi)) = window {
            consider(lo);
            consider(hi);
        }
        // The closed form stays unless a candidate is nearer by more than rounding (on a
        // circle it is the foot of every point).
        match (closed, best) {
            (Some(t), Some((bd, _)))
                if distance(t) <= bd + DISTANCE_ROUNDING * (bd + self.point(t).norm()) =>
            {
                t
            }
            (Some(t), None) => t,
            (_, Some((_, t))) => t,
            (None, None) => window.map_or(0.0, |w| w.0),
        }
    }

    /// `t` (an ellipse's moved by whole periods) within `window`, or `None`.
    fn in_window(&self, t: f64, window: Option<(f64, f64)>) -> Option<f64> {
        let Some((lo, hi)) = window else {
            return Some(t);
        };
        let t = if self.kind == ConicKind::Ellipse && t < lo {
            t + TAU * ((lo - t) / TAU).ceil()
        } else if self.kind == ConicKind::Ellipse && t > hi {
            t - TAU * ((t - hi) / TAU).ceil()
        } else {
            t
        };
        (lo <= t && t <= hi).then_some(t)
    }

    /// The roots of the foot condition (see [`Conic::closest_parameter`]) within `window`.
    fn foot_candidates(&self, x: P, window: Option<(f64, f64)>) -> Vec<f64> {
        let d = x - self.center;
        let (a, b, m) = (self.u.dot(self.u), self.v.dot(self.v), self.u.dot(self.v));
        let (p, q) = (d.dot(self.u), d.dot(self.v));
        let roots = |c: Vec<f64>, lo: f64, hi: f64| -> Vec<f64> {
            if lo < hi {
                real_roots_in(&Polynomial::new(c), lo, hi).unwrap_or_default()
            } else {
                Vec::new()
            }
        };
        let mut out = Vec::new();
        match self.kind {
            ConicKind::Ellipse => {
                // (b - a) sin cos + m (cos^2 - sin^2) + p sin - q cos, times (1 + s^2)^2 with
                // s = tan(t / 2), on t in [-pi/2, pi/2]; the other half t = pi + t' is the same
                // with (u, v) -> (-u, -v).
                for (sign, shift) in [(1.0, 0.0), (-1.0, PI)] {
                    let (p, q) = (sign * p, sign * q);
                    let c = vec![
                        m - q,
                        2.0 * (b - a) + 2.0 * p,
                        -6.0 * m,
                        -2.0 * (b - a) + 2.0 * p,
                        m + q,
                    ];
                    for s in roots(c, -1.0, 1.0) {
                        let t = shift + 2.0 * s.atan();
                        let t = if t > PI { t - TAU } else { t };
                        out.extend(self.in_window(t, window));
                    }
                }
            }
            ConicKind::Hyperbola => {
                // (a + b) sinh cosh + m (cosh^2 + sinh^2) - p sinh - q cosh, times 4 z^2 with
                // z = e^t, on t <= 0; t >= 0 is t = -t' with v -> -v.
                let (lo, hi) = window.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
                for sign in [1.0, -1.0] {
                    let (m, q) = (sign * m, sign * q);
                    let c = vec![
                        -(a + b) + 2.0 * m,
                        2.0 * p - 2.0 * q,
                        0.0,
                        -2.0 * p - 2.0 * q,
                        (a + b) + 2.0 * m,
                    ];
                    // This side's t' = sign t runs over [t0, t1] within t' <= 0.
                    let (t0, t1) = if sign > 0.0 { (lo, hi) } else { (-hi, -lo) };
                    let (z0, z1) = (t0.exp(), t1.min(0.0).exp());
                    for z in roots(c, z0, z1) {
                        if z > 0.0 {
                            out.push(sign * z.ln());
                        }
                    }
                }
                out.retain(|&t| lo <= t && t <= hi);
            }
            ConicKind::Parabola => {
                // a t^3 + 3 m t^2 + (2 b - p) t - q, its roots within Cauchy's bound.
                let c = vec![-q, 2.0 * b - p, 3.0 * m, a];
                let r = 1.0 + (q.abs().max((2.0 * b - p).abs()).max((3.0 * m).abs())) / a;
                let (lo, hi) = window.unwrap_or((-r, r));
                out = roots(c, lo.max(-r), hi.min(r));
            }
        }
        out
    }

    /// The image under an affine map: the centre as a point, the axes as vectors (exact).
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] for a non-finite image.
    pub fn map_affine<Q: Vector, M: AffineMap<P, Q> + ?Sized>(
        &self,
        map: &M,
    ) -> Result<Conic<Q>, GeomError> {
        let c = Conic {
            kind: self.kind,
            center: map.point(self.center),
            u: map.vector(self.u),
            v: map.vector(self.v),
        };
        for (what, p) in [
            ("conic centre", c.center),
            ("conic axis", c.u),
            ("conic axis", c.v),
        ] {
            if !p.all_finite() {
                return Err(GeomError::NotFinite {
                    what,
                    value: p.norm(),
                });
            }
        }
        Ok(c)
    }
}

impl<P: Vector + Div<f64, Output = P>> Conic<P> {
    /// The arc on `[t0, t1]` as an exact rational quadratic B-spline (its own parameter, not
    /// `t`): the unit conic's arc mapped by `p -> u p.x + v p.y + center` (coordinate `i`:
    /// `(u_i x + v_i y) + c_i`; in the plane, the arithmetic of [`rs_spline::Affine::apply`]).
    /// The unit arcs:
    /// - ellipse: [`rs_spline::circular_arc`] of radius 1 from `t0` through `t1 - t0` (on
    ///   `[0, 1]`, a piece per quarter turn);
    /// - hyperbola: pieces of at most one parameter unit (at most [`MAX_HYPERBOLA_PIECES`]),
    ///   each the rational quadratic with ends on `(cosh, sinh)`, middle point `(cosh m, sinh
    ///   m) / cosh h` (the tangents' intersection, `m` the middle parameter, `h` the half
    ///   width) and middle weight `cosh h`; knots `0, 1, ..., k`;
    /// - parabola: the one polynomial Bezier `(t0^2, 2 t0)`, `(t0 t1, t0 + t1)`,
    ///   `(t1^2, 2 t1)` on `[0, 1]` (the tangents at the ends meet at the middle point).
    ///
    /// # Errors
    /// [`GeomError::EmptyInterval`] unless `t0 < t1` (both finite);
    /// [`GeomError::HyperbolaTooLong`]; [`GeomError::NotFinite`] where `cosh` overflows;
    /// [`GeomError::Spline`] for arcs of too many turns or coordinates beyond the limits.
    pub fn to_bspline(&self, t0: f64, t1: f64) -> Result<RationalBSpline<P>, GeomError> {
        check_interval(t0, t1)?;
        let unit = match self.kind {
            ConicKind::Ellipse => circular_arc(Point::new(0.0, 0.0), 1.0, t0, t1 - t0)?,
            ConicKind::Hyperbola => unit_hyperbola(t0, t1)?,
            ConicKind::Parabola => NurbsCurve::bezier(
                vec![
                    Point::new(t0 * t0, 2.0 * t0),
                    Point::new(t0 * t1, t0 + t1),
                    Point::new(t1 * t1, 2.0 * t1),
                ],
                None,
            )?,
        };
        self.place(&unit)
    }

    /// The unit curve mapped by `p -> u p.x + v p.y + center` (kept as it is when that is the
    /// identity of the plane, as [`rs_spline::Affine::apply_to_curve`] keeps it).
    fn place(&self, unit: &NurbsCurve) -> Result<RationalBSpline<P>, GeomError> {
        let axis = |k: usize| P::from_fn(|i| if i == k { 1.0 } else { 0.0 });
        let identity =
            P::DIM == 2 && self.u == axis(0) && self.v == axis(1) && self.center == P::default();
        let points = unit
            .control_points()
            .iter()
            .map(|&p| {
                if identity {
                    P::from_fn(|i| if i == 0 { p.x } else { p.y })
                } else {
                    self.u * p.x + self.v * p.y + self.center
                }
            })
            .collect();
        let weights = (self.kind != ConicKind::Parabola).then(|| unit.weights().to_vec());
        Ok(RationalBSpline::from_parts(
            unit.knots().clone(),
            points,
            weights,
        )?)
    }
}

/// `Err` unless `t0 < t1`, both finite.
pub(crate) fn check_interval(t0: f64, t1: f64) -> Result<(), GeomError> {
    if t0.is_finite() && t1.is_finite() && t0 < t1 {
        Ok(())
    } else {
        Err(GeomError::EmptyInterval { t0, t1 })
    }
}

/// The unit hyperbola `(cosh t, sinh t)` on `[t0, t1]` (see [`Conic::to_bspline`]).
fn unit_hyperbola(t0: f64, t1: f64) -> Result<NurbsCurve, GeomError> {
    let k = (t1 - t0).ceil().max(1.0);
    if k > MAX_HYPERBOLA_PIECES as f64 {
        return Err(GeomError::HyperbolaTooLong {
            t0,
            t1,
            max: MAX_HYPERBOLA_PIECES,
        });
    }
    let k = k as usize;
    let h = (t1 - t0) / k as f64;
    let d = 0.5 * h;
    let w = d.cosh();
    let at = |t: f64| Point::new(t.cosh(), t.sinh());
    let mut points = vec![at(t0)];
    let mut weights = vec![1.0];
    let mut knots = vec![0.0; 3];
    for j in 0..k {
        let a = t0 + j as f64 * h;
        points.push(at(a + d) / w);
        points.push(at(a + h));
        weights.extend([w, 1.0]);
        if j + 1 < k {
            let u = (j + 1) as f64;
            knots.extend([u, u]);
        }
    }
    knots.extend([k as f64; 3]);
    if let Some(p) = points.iter().find(|p| !p.is_finite()) {
        return Err(GeomError::NotFinite {
            what: "hyperbola arc point",
            value: p.x,
        });
    }
    Ok(NurbsCurve::new(2, knots, points, Some(weights))?)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;
    use rs_spline::{Affine, Point3};

    use super::*;
    use crate::curve::testing::Rng;

    const KINDS: [ConicKind; 3] = [
        ConicKind::Ellipse,
        ConicKind::Hyperbola,
        ConicKind::Parabola,
    ];

    /// A conic in space with random centre, orthogonal axes and sizes.
    fn random_conic(rng: &mut Rng, kind: ConicKind) -> Conic<Point3> {
        let (x, y) = rng.axes();
        let (a, b) = match kind {
            ConicKind::Parabola => {
                let f = rng.uniform(0.3, 3.0);
                (f, f)
            }
            _ => (rng.uniform(0.5, 4.0), rng.uniform(0.5, 4.0)),
        };
        Conic {
            kind,
            center: rng.point3(10.0),
            u: x * a,
            v: y * b,
        }
    }

    /// The parameter range a test draws from.
    fn range(kind: ConicKind) -> (f64, f64) {
        match kind {
            ConicKind::Ellipse => (-PI, PI),
            _ => (-3.0, 3.0),
        }
    }

    /// The coordinates `(a, b)` of `p` along the conic's (orthogonal) axes, in units of their
    /// lengths, and the distance of `p` from the conic's plane.
    fn local(c: &Conic<Point3>, p: Point3) -> (f64, f64, f64) {
        let d = p - c.center;
        let (a, b) = (d.dot(c.u) / c.u.dot(c.u), d.dot(c.v) / c.v.dot(c.v));
        let off = (d - c.u * a - c.v * b).length();
        (a, b, off)
    }

    /// The relative residual of the conic's implicit equation in its own frame:
    /// `a^2 + b^2 = 1`, `a^2 - b^2 = 1` (`a > 0`), `b^2 = 4 a` (`a = t^2`, `b = 2 t`).
    fn residual(kind: ConicKind, a: f64, b: f64) -> f64 {
        match kind {
            ConicKind::Ellipse => (a * a + b * b - 1.0).abs(),
            ConicKind::Hyperbola => {
                assert!(a > 0.0);
                (a * a - b * b - 1.0).abs() / (a * a + b * b)
            }
            ConicKind::Parabola => (b * b - 4.0 * a).abs() / (1.0 + b * b + 4.0 * a.abs()),
        }
    }

    #[test]
    fn arcs_in_space_lie_on_their_conics_between_their_ends() {
        let mut rng = Rng::new(17);
        for case in 0..300 {
            let kind = KINDS[case % 3];
            let c = random_conic(&mut rng, kind);
            let (lo, hi) = range(kind);
            let t0 = rng.uniform(lo, hi);
            let t1 = match kind {
                ConicKind::Ellipse => t0 + rng.uniform(0.01, 2.5 * TAU),
                _ => rng.uniform(t0 + 0.01, hi + 1.0),
            };
            let arc = c.to_bspline(t0, t1).unwrap();
            let size = c.size();
            let (a, b) = arc.param_range();
            assert!(arc.point_at(a).distance(c.point(t0)) < 1e-14 * size);
            assert!(arc.point_at(b).distance(c.point(t1)) < 1e-14 * size);
            let mut previous = t0;
            for i in 0..=200 {
                let p = arc.point_at(a + (b - a) * f64::from(i) / 200.0);
                let (x, y, off) = local(&c, p);
                assert!(off < 1e-13 * size, "{kind} {off:e}");
                assert!(residual(kind, x, y) < 1e-12, "{kind} {case}");
                // The arc runs from t0 to t1: its points' parameters grow, within [t0, t1].
                let mut t = c.parameter_of(p);
                if kind == ConicKind::Ellipse {
                    t += TAU * ((previous - t) / TAU).round();
                }
                assert!(
                    t >= previous - 1e-9 && t <= t1 + 1e-9,
                    "{kind} {t} {previous}"
                );
                previous = t;
            }
            assert!((previous - t1).abs() < 1e-9);
        }
    }

    /// In the plane, a conic's arc is the unit arc under the reader's `Affine` map
    /// `(u.x, u.y, v.x, v.y, c.x, c.y)`, bit for bit.
    #[test]
    fn planar_arcs_are_the_affine_image_of_the_unit_arc_bit_for_bit() {
        let mut rng = Rng::new(5);
        let bits = |c: &NurbsCurve| -> Vec<u64> {
            c.knots()
                .knots()
                .iter()
                .chain(c.control_points().iter().flat_map(|p| [&p.x, &p.y]))
                .chain(c.weights())
                .map(|x| x.to_bits())
                .collect()
        };
        for case in 0..90 {
            let kind = KINDS[case % 3];
            let (u, v, center) = (rng.point(3.0), rng.point(3.0), rng.point(10.0));
            let (lo, hi) = range(kind);
            let t0 = rng.uniform(lo, hi);
            let t1 = t0 + rng.uniform(0.1, 4.0);
            let unit = match kind {
                ConicKind::Ellipse => circular_arc(Point::new(0.0, 0.0), 1.0, t0, t1 - t0).unwrap(),
                ConicKind::Hyperbola => unit_hyperbola(t0, t1).unwrap(),
                ConicKind::Parabola => NurbsCurve::bezier(
                    vec![
                        Point::new(t0 * t0, 2.0 * t0),
                        Point::new(t0 * t1, t0 + t1),
                        Point::new(t1 * t1, 2.0 * t1),
                    ],
                    None,
                )
                .unwrap(),
            };
            let want = Affine {
                m: [u.x, u.y, v.x, v.y, center.x, center.y],
            }
            .apply_to_curve(&unit)
            .unwrap();
            let c = Conic { kind, center, u, v };
            let got = c.to_bspline(t0, t1).unwrap().to_planar().unwrap();
            assert_eq!(bits(&got), bits(&want), "{kind}");
            // The unit conic itself: the unit arc unchanged.
            let unit_conic = Conic {
                kind,
                center: Point::new(0.0, 0.0),
                u: Point::new(1.0, 0.0),
                v: Point::new(0.0, 1.0),
            };
            let got = unit_conic.to_bspline(t0, t1).unwrap().to_planar().unwrap();
            assert_eq!(bits(&got), bits(&unit), "{kind}");
        }
    }

    #[test]
    fn derivatives_match_central_differences() {
        let mut rng = Rng::new(3);
        let h = 1e-5;
        for case in 0..60 {
            let kind = KINDS[case % 3];
            let c = random_conic(&mut rng, kind);
            let (lo, hi) = range(kind);
            let t = rng.uniform(lo, hi);
            let [p, d1, d2] = c.derivatives(t);
            let fd1 = (c.point(t + h) - c.point(t - h)) / (2.0 * h);
            let fd2 = (c.point(t + h) - p * 2.0 + c.point(t - h)) / (h * h);
            let scale = c.u.length() + c.v.length();
            assert!(d1.distance(fd1) < 1e-8 * scale * t.cosh(), "{kind}");
            assert!(d2.distance(fd2) < 1e-4 * scale * t.cosh(), "{kind}");
        }
    }

    #[test]
    fn closest_parameter_recovers_points_on_conics() {
        let mut rng = Rng::new(11);
        for case in 0..300 {
            let kind = KINDS[case % 3];
            let c = random_conic(&mut rng, kind);
            let (lo, hi) = range(kind);
            let t = rng.uniform(lo, hi);
            let x = c.point(t);
            let got = c.closest_parameter(x, None);
            assert!(
                (got - t).abs() < 1e-12 * (1.0 + t.abs()),
                "{kind} {t} {got}"
            );
            assert_eq!(got, c.parameter_of(x));
            // In a window: the window's copy of the period, or the window's nearer end.
            let k = f64::from(i32::try_from(case % 5).unwrap()) - 2.0;
            let shift = if kind == ConicKind::Ellipse {
                k * TAU
            } else {
                0.0
            };
            let w = (t + shift - 0.25, t + shift + 0.5);
            assert!((c.closest_parameter(x, Some(w)) - (t + shift)).abs() < 1e-11);
            let beyond = (t + shift + 0.5, t + shift + 1.0);
            assert_eq!(c.closest_parameter(x, Some(beyond)), beyond.0, "{kind}");
        }
    }

    /// On a circle the closed form is every point's foot: it is what comes back, bit for bit,
    /// for points off the circle and off its plane.
    #[test]
    fn circles_keep_the_closed_form_everywhere() {
        let mut rng = Rng::new(12);
        for _ in 0..200 {
            let (x, y) = rng.axes();
            let r = rng.uniform(0.1, 5.0);
            let c = Conic {
                kind: ConicKind::Ellipse,
                center: rng.point3(10.0),
                u: x * r,
                v: y * r,
            };
            let p = c.center + rng.point3(3.0 * r);
            assert_eq!(c.closest_parameter(p, None), c.parameter_of(p));
        }
    }

    /// The nearest point by brute force: dense samples on `[lo, hi]`, then the best sample's
    /// neighbourhood sampled again, twice.
    fn brute_force(c: &Conic<Point3>, x: Point3, lo: f64, hi: f64) -> f64 {
        let (mut a, mut b) = (lo, hi);
        let mut best = (f64::INFINITY, lo);
        for _ in 0..3 {
            let n = 4000;
            for i in 0..=n {
                let t = a + (b - a) * f64::from(i) / f64::from(n);
                let d = c.point(t).distance(x);
                if d < best.0 {
                    best = (d, t);
                }
            }
            let h = (b - a) / f64::from(n);
            (a, b) = ((best.1 - h).max(lo), (best.1 + h).min(hi));
        }
        best.0
    }

    fn arb_case() -> impl Strategy<Value = (Conic<Point3>, Point3, Option<(f64, f64)>)> {
        (0usize..3, any::<u64>(), any::<bool>()).prop_map(|(k, seed, windowed)| {
            let mut rng = Rng::new(seed);
            let kind = KINDS[k];
            let mut c = random_conic(&mut rng, kind);
            if seed % 4 == 0 {
                // A planar conic (the plane z = 0) with points in its plane.
                c.center.z = 0.0;
                c.u.z = 0.0;
                c.v.z = 0.0;
                c.u = c.u.normalized().unwrap() * c.u.length().max(0.5);
                c.v = Point3::Z.cross(c.u).normalized().unwrap() * c.v.length().max(0.5);
            }
            let mut x = c.center + rng.point3(6.0);
            if seed % 4 == 0 {
                x.z = 0.0;
            }
            let window = windowed.then(|| {
                let (lo, hi) = range(kind);
                let a = rng.uniform(lo, hi);
                (a, a + rng.uniform(0.1, 3.0))
            });
            (c, x, window)
        })
    }

    proptest! {
        /// Off the conic, the parameter found is the nearest point's: no sample of the conic
        /// (in the window) is nearer, and the foot condition holds.
        #[test]
        fn closest_parameter_is_the_nearest_point((c, x, window) in arb_case()) {
            let t = c.closest_parameter(x, window);
            let d = c.point(t).distance(x);
            let (lo, hi) = window.unwrap_or(match c.kind {
                ConicKind::Ellipse => (-PI, PI),
                _ => (-9.0, 9.0),
            });
            if let Some((a, b)) = window {
                prop_assert!(a <= t && t <= b);
            }
            let brute = brute_force(&c, x, lo, hi);
            prop_assert!(d <= brute + 1e-12 * c.size(), "{} {} {}", c.kind, d, brute);
            if t > lo && t < hi {
                let [p, d1, _] = c.derivatives(t);
                let g = (p - x).dot(d1);
                prop_assert!(g.abs() <= 1e-9 * d1.length() * (1.0 + d), "{}", g);
            }
        }
    }

    #[test]
    fn conversion_errors() {
        let c = Conic {
            kind: ConicKind::Hyperbola,
            center: Point::new(0.0, 0.0),
            u: Point::new(1.0, 0.0),
            v: Point::new(0.0, 1.0),
        };
        assert!(matches!(
            c.to_bspline(1.0, 1.0),
            Err(GeomError::EmptyInterval { .. })
        ));
        assert!(matches!(
            c.to_bspline(f64::NAN, 1.0),
            Err(GeomError::EmptyInterval { .. })
        ));
        assert!(matches!(
            c.to_bspline(0.0, 64.0),
            Ok(b) if b.control_points().len() == 129
        ));
        assert!(matches!(
            c.to_bspline(0.0, 64.5),
            Err(GeomError::HyperbolaTooLong { max: 64, .. })
        ));
        assert!(matches!(
            c.to_bspline(700.0, 720.0),
            Err(GeomError::NotFinite { .. })
        ));
        let e = Conic {
            kind: ConicKind::Ellipse,
            ..c
        };
        // Past rs-spline's limit on quarter turns.
        assert!(matches!(e.to_bspline(0.0, 1e9), Err(GeomError::Spline(_))));
        assert_eq!(ConicKind::Parabola.to_string(), "parabola");
    }
}
