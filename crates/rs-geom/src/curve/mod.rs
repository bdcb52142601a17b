//! Curves of any dimension in their native parameterisations: lines, conics, rational
//! B-splines and trimmed windows of them. A STEP pcurve is a `Curve<Point>`, an edge a
//! `Curve<Point3>`; both are evaluated, inverted and converted exactly by the same code.
//!
//! Parameterisations (ISO 10303-42; IGES 5.3 curves are converted to these when read):
//! - [`Curve::Line`]: `origin + t direction` (`direction` with its length: a STEP `VECTOR`'s
//!   orientation times its magnitude);
//! - [`Curve::Conic`]: `center + f(t) u + g(t) v`, `(f, g) = (cos t, sin t)` for ellipses and
//!   circles (`u`, `v` the semi-axes as vectors), `(cosh t, sinh t)` for hyperbolas, `(t^2, 2
//!   t)` for parabolas (`u = f x`, `v = f y` with the focal distance `f`);
//! - [`Curve::BSpline`]: its knots;
//! - [`Curve::Trimmed`]: its basis curve's parameter, restricted to `[t0, t1]`.

mod closest;
mod conic;
mod conic_kind;
mod implicit;

use std::ops::Div;

use rs_spline::{NurbsCurve, Point, RationalBSpline, Vector};

pub use conic::{Conic, MAX_HYPERBOLA_PIECES};
pub use conic_kind::ConicKind;

use crate::{AffineMap, GeomError};
use conic::check_interval;

/// A curve in its native parameterisation (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub enum Curve<P> {
    /// `origin + t direction`, unbounded.
    Line {
        /// The point at `t = 0`.
        origin: P,
        /// The derivative (with its length).
        direction: P,
    },
    /// A conic, unbounded (periodic for ellipses).
    Conic(Conic<P>),
    /// A rational B-spline on its knot domain.
    BSpline(RationalBSpline<P>),
    /// The window `[t0, t1]` of a basis curve, in the basis curve's parameter.
    Trimmed {
        /// The basis curve.
        basis: Box<Curve<P>>,
        /// The window, `t0 < t1`.
        range: (f64, f64),
    },
}

/// Parameters within this fraction of a period of a periodic curve's range are in it
/// ([`Curve::pieces_in_range`]).
const PERIODIC_RANGE_SLACK: f64 = 1e-9;

/// The most whole periods [`Curve::pieces_in_range`] translates an interval by.
const MAX_PERIODS_SHIFTED: f64 = 1e6;

impl<P: Vector + std::ops::Div<f64, Output = P>> Curve<P> {
    /// The point at `t` (a B-spline's parameter clamped to its domain).
    pub fn point(&self, t: f64) -> P {
        match self {
            Curve::Line { origin, direction } => *origin + *direction * t,
            Curve::Conic(c) => c.point(t),
            Curve::BSpline(b) => b.point_at(t),
            Curve::Trimmed { basis, .. } => basis.point(t),
        }
    }

    /// `[C(t), C'(t), C''(t)]`.
    pub fn derivatives(&self, t: f64) -> [P; 3] {
        match self {
            Curve::Line { origin, direction } => {
                [*origin + *direction * t, *direction, P::default()]
            }
            Curve::Conic(c) => c.derivatives(t),
            Curve::BSpline(b) => b.derivatives(t),
            Curve::Trimmed { basis, .. } => basis.derivatives(t),
        }
    }

    /// The parameter interval of a bounded curve (a B-spline's knot domain, a trimmed curve's
    /// window); `None` for lines and conics, whose parameter is unbounded.
    pub fn range(&self) -> Option<(f64, f64)> {
        match self {
            Curve::BSpline(b) => Some(b.param_range()),
            Curve::Trimmed { range, .. } => Some(*range),
            Curve::Line { .. } | Curve::Conic(_) => None,
        }
    }

    /// The parameters strictly inside the curve's range where it is only piecewise smooth (a
    /// B-spline's distinct interior knots), ascending; none for lines and conics.
    pub fn breaks(&self) -> Vec<f64> {
        match self {
            Curve::BSpline(b) => b.knots().interior_breaks(),
            Curve::Trimmed { basis, range } => basis
                .breaks()
                .into_iter()
                .filter(|&t| range.0 < t && t < range.1)
                .collect(),
            Curve::Line { .. } | Curve::Conic(_) => Vec::new(),
        }
    }

    /// The period in which an edge's or trim's parameter window wraps: a whole ellipse's
    /// `2 pi`, a closed B-spline's domain ([`Curve::period`]); a trimmed curve is its window and
    /// does not wrap.
    pub fn window_period(&self) -> Option<f64> {
        match self {
            Curve::Trimmed { .. } => None,
            _ => self.period(),
        }
    }

    /// The pieces of the curve's parameter range that `[lo, hi]` (increasing) covers when its
    /// parameter repeats with `period`: an unbounded curve (line, conic) or one without a
    /// period takes `[lo, hi]` as it is; a bounded one takes it translated by whole periods
    /// into its range, and where the range spans a whole period an interval across its end
    /// wraps around: two pieces, `[lo, b]` then `[a, hi - period]`. Parameters within `1e-9`
    /// of a period of the range are in it (vertices printed to ten digits land a little
    /// outside); an interval more than `1e6` periods away is taken as it is.
    pub fn pieces_in_range(&self, lo: f64, hi: f64, period: Option<f64>) -> Vec<(f64, f64)> {
        let (Some((a, b)), Some(p)) = (self.range(), period) else {
            return vec![(lo, hi)];
        };
        let eps = PERIODIC_RANGE_SLACK * p;
        if lo >= a - eps && hi <= b + eps {
            return vec![(lo, hi)];
        }
        let full = (b - a - p).abs() <= eps;
        let k = ((lo - a) / p).floor();
        if !k.is_finite() || k.abs() > MAX_PERIODS_SHIFTED {
            return vec![(lo, hi)];
        }
        let (l2, h2) = (lo - k * p, hi - k * p);
        if h2 <= b + eps {
            return vec![(l2, h2)];
        }
        if full {
            let mut out = Vec::new();
            if b - l2 > eps {
                out.push((l2, b));
            }
            if h2 - p - a > eps {
                out.push((a, h2 - p));
            }
            if !out.is_empty() {
                return out;
            }
        }
        // A partial curve: the translation that overlaps its range most.
        let k2 = ((a - lo) / p).round();
        vec![(lo + k2 * p, hi + k2 * p)]
    }

    /// The period of a closed curve: `2 pi` for ellipses (and trimmed windows of them), the
    /// domain's length for a B-spline whose ends meet (within `1e-12` of its size).
    pub fn period(&self) -> Option<f64> {
        match self {
            Curve::Conic(Conic {
                kind: ConicKind::Ellipse,
                ..
            }) => Some(std::f64::consts::TAU),
            Curve::BSpline(b) => {
                let (a, e) = b.param_range();
                let size = b
                    .control_points()
                    .iter()
                    .map(|p| p.norm())
                    .fold(0.0, f64::max);
                (e > a && b.point_at(a).distance_to(b.point_at(e)) <= 1e-12 * size.max(1e-300))
                    .then_some(e - a)
            }
            Curve::Trimmed { basis, .. } => basis.period(),
            Curve::Line { .. } | Curve::Conic(_) => None,
        }
    }

    /// The exact rational B-spline of the curve on `[t0, t1]` (`t0 < t1`):
    /// - a line: the degree-1 segment between its points at `t0` and `t1`, on `[0, 1]`;
    /// - a conic: [`Conic::to_bspline`] (rational quadratic pieces, their own parameter);
    /// - a B-spline: its subsegment on `[t0, t1]` clipped to its domain (the curve itself when
    ///   the interval covers the domain), in its own parameter (see
    ///   [`Curve::to_bspline_extended`] to continue it past its domain);
    /// - a trimmed curve: its basis curve's on `[t0, t1]` (the trim is not applied).
    ///
    /// # Errors
    /// [`GeomError::EmptyInterval`] unless `t0 < t1` (finite); a B-spline's interval that
    /// misses its domain ([`GeomError::Spline`]); the errors of [`Conic::to_bspline`].
    pub fn to_bspline(&self, t0: f64, t1: f64) -> Result<RationalBSpline<P>, GeomError> {
        check_interval(t0, t1)?;
        match self {
            Curve::Line { .. } => Ok(RationalBSpline::new(
                1,
                vec![0.0, 0.0, 1.0, 1.0],
                vec![self.point(t0), self.point(t1)],
                None,
            )?),
            Curve::Conic(c) => c.to_bspline(t0, t1),
            Curve::BSpline(b) => {
                let (a, e) = b.param_range();
                if t0 <= a && t1 >= e {
                    return Ok(b.clone());
                }
                Ok(b.subsegment((t0.max(a), t1.min(e)))?)
            }
            Curve::Trimmed { basis, .. } => basis.to_bspline(t0, t1),
        }
    }

    /// [`Curve::to_bspline`] of the curve's image under `map`, with the map applied to each
    /// curve's data where it is exact and cheapest: a line's end points (after evaluating them
    /// here), a conic's centre and axes (before converting), a B-spline's control points
    /// (before the subsegment). This is the arithmetic of the CAD readers' conversions of
    /// edges into a plane's `(u, v)`.
    ///
    /// # Errors
    /// As [`Curve::to_bspline`]; [`GeomError::NotFinite`] or [`GeomError::Spline`] for
    /// images beyond the coordinate limits.
    pub fn to_bspline_mapped<Q, M>(
        &self,
        map: &M,
        t0: f64,
        t1: f64,
    ) -> Result<RationalBSpline<Q>, GeomError>
    where
        Q: Vector + Div<f64, Output = Q>,
        M: AffineMap<P, Q> + ?Sized,
    {
        check_interval(t0, t1)?;
        match self {
            Curve::Line { .. } => Ok(self.to_bspline(t0, t1)?.map_points(|p| map.point(p))?),
            Curve::Trimmed { basis, .. } => basis.to_bspline_mapped(map, t0, t1),
            Curve::Conic(_) | Curve::BSpline(_) => self.map_affine(map)?.to_bspline(t0, t1),
        }
    }

    /// The curve's image under an affine map, exactly: a line's origin as a point and its
    /// direction as a vector, a conic's centre as a point and its axes as vectors, a
    /// B-spline's control points as points (knots and weights kept), a trimmed curve's basis
    /// (its range kept). With [`crate::PlaneCoordinates`], a space curve in a plane becomes the
    /// plane curve of its `(u, v)`; with an [`crate::Affine3`], the placed curve.
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] for a non-finite image; [`GeomError::Spline`] for control
    /// points beyond the coordinate limits.
    pub fn map_affine<Q, M>(&self, map: &M) -> Result<Curve<Q>, GeomError>
    where
        Q: Vector + Div<f64, Output = Q>,
        M: AffineMap<P, Q> + ?Sized,
    {
        Ok(match self {
            Curve::Line { origin, direction } => {
                let (origin, direction) = (map.point(*origin), map.vector(*direction));
                for p in [origin, direction] {
                    if !p.all_finite() {
                        return Err(GeomError::NotFinite {
                            what: "line",
                            value: p.norm(),
                        });
                    }
                }
                Curve::Line { origin, direction }
            }
            Curve::Conic(c) => Curve::Conic(c.map_affine(map)?),
            Curve::BSpline(b) => Curve::BSpline(b.map_points(|p| map.point(p))?),
            Curve::Trimmed { basis, range } => Curve::Trimmed {
                basis: Box::new(basis.map_affine(map)?),
                range: *range,
            },
        })
    }

    /// The parameter of the point of the curve nearest `x`, searched within `window`
    /// (intersected with a B-spline's domain and a trimmed curve's range; `None`: the whole
    /// curve):
    /// - a line: the orthogonal projection `(x - o) . d / |d|^2`, clamped into the window;
    /// - a conic: exact ([`Conic::closest_parameter`]: the closed form for points on it, the
    ///   roots of the foot condition otherwise);
    /// - a B-spline: a bounded search: 16 samples per knot span in the window (4096 in all at
    ///   most, fewer per span on curves of more than 256 spans, at least the knots),
    ///   golden-section search around the (at most four) nearest sampled local minima, then
    ///   Newton's method on the foot condition; an end of the window is kept, exactly, unless
    ///   the refined point is nearer by more than rounding (vertices at ends are the common
    ///   case);
    /// - a trimmed curve: its basis curve's within its range.
    ///
    /// A window with `lo > hi` (or not a number) gives `lo`; a B-spline window that misses the
    /// domain gives the domain's nearer end; a line of zero direction gives `0` (or the
    /// window's start).
    pub fn closest_parameter(&self, x: P, window: Option<(f64, f64)>) -> f64 {
        if let Some((lo, hi)) = window
            && (lo > hi || lo.is_nan() || hi.is_nan())
        {
            return lo;
        }
        match self {
            Curve::Line { origin, direction } => {
                let dd = direction.dot(*direction);
                if dd == 0.0 {
                    return window.map_or(0.0, |w| w.0);
                }
                let t = (x - *origin).dot(*direction) / dd;
                match window {
                    Some((lo, hi)) => t.min(hi).max(lo),
                    None => t,
                }
            }
            Curve::Conic(c) => c.closest_parameter(x, window),
            Curve::BSpline(b) => {
                let (a, e) = b.param_range();
                let (lo, hi) = window.unwrap_or((a, e));
                let (lo, hi) = (lo.clamp(a, e), hi.clamp(a, e));
                if lo < hi {
                    closest::bspline_closest_parameter(b, x, (lo, hi))
                } else {
                    lo
                }
            }
            Curve::Trimmed { basis, range } => {
                let (lo, hi) = window.unwrap_or(*range);
                basis.closest_parameter(x, Some((lo.max(range.0), hi.min(range.1))))
            }
        }
    }

    /// The domain of the B-spline under the curve (through trims), `None` for lines and
    /// conics.
    pub fn spline_domain(&self) -> Option<(f64, f64)> {
        match self {
            Curve::BSpline(b) => Some(b.param_range()),
            Curve::Trimmed { basis, .. } => basis.spline_domain(),
            Curve::Line { .. } | Curve::Conic(_) => None,
        }
    }

    /// The point at `t`, a B-spline continued past its domain by its end spans' polynomials
    /// ([`RationalBSpline::point_extended`]): how a pcurve that stops a little short of its
    /// vertex reaches it. Other curves: [`Curve::point`].
    pub fn point_extended(&self, t: f64) -> P {
        match self {
            Curve::BSpline(b) => b.point_extended(t),
            Curve::Trimmed { basis, .. } => basis.point_extended(t),
            Curve::Line { .. } | Curve::Conic(_) => self.point(t),
        }
    }

    /// [`Curve::to_bspline`] on `[t0, t1]`, where a B-spline's interval may reach past its
    /// domain `[a, b]`: the part inside, with the end spans' continuations on `[t0, a]` and
    /// `[b, t1]` ([`RationalBSpline::extension`], Bezier curves on `[0, 1]`) before and after
    /// it. Other curves: one piece.
    ///
    /// # Errors
    /// As [`Curve::to_bspline`] and [`RationalBSpline::extension`].
    pub fn to_bspline_extended(
        &self,
        t0: f64,
        t1: f64,
    ) -> Result<Vec<RationalBSpline<P>>, GeomError> {
        check_interval(t0, t1)?;
        let b = match self {
            Curve::BSpline(b) => b,
            Curve::Trimmed { basis, .. } => return basis.to_bspline_extended(t0, t1),
            Curve::Line { .. } | Curve::Conic(_) => return Ok(vec![self.to_bspline(t0, t1)?]),
        };
        let (a, e) = b.param_range();
        let mut out = Vec::new();
        if t0 < a {
            out.push(b.extension(t0, a.min(t1))?);
        }
        if t0.max(a) < t1.min(e) {
            out.push(self.to_bspline(t0.max(a), t1.min(e))?);
        }
        if t1 > e {
            out.push(b.extension(t0.max(e), t1)?);
        }
        Ok(out)
    }
}

impl Curve<Point> {
    /// The planar NURBS of a plane curve on `[t0, t1]` ([`Curve::to_bspline`]), with every 2-D
    /// algorithm.
    ///
    /// # Errors
    /// As [`Curve::to_bspline`].
    pub fn to_planar_nurbs(&self, t0: f64, t1: f64) -> Result<NurbsCurve, GeomError> {
        Ok(self.to_bspline(t0, t1)?.to_planar()?)
    }
}

#[cfg(test)]
mod testing;

#[cfg(test)]
mod tests {
    use rs_spline::{Point, Point3};

    use super::*;

    #[test]
    fn conics_and_lines_evaluate_with_their_derivatives() {
        let e = Conic {
            kind: ConicKind::Ellipse,
            center: Point3::new(1.0, 0.0, 0.0),
            u: Point3::new(2.0, 0.0, 0.0),
            v: Point3::new(0.0, 1.0, 0.0),
        };
        let [p, d1, d2] = e.derivatives(0.5);
        let (s, c) = 0.5f64.sin_cos();
        assert!(p.distance(Point3::new(1.0 + 2.0 * c, s, 0.0)) < 1e-15);
        assert!(d1.distance(Point3::new(-2.0 * s, c, 0.0)) < 1e-15);
        assert!(d2.distance(Point3::new(-2.0 * c, -s, 0.0)) < 1e-15);
        let curve = Curve::Conic(e);
        assert_eq!(curve.period(), Some(std::f64::consts::TAU));
        assert_eq!(curve.range(), None);
        let line = Curve::Line {
            origin: Point::new(1.0, 2.0),
            direction: Point::new(0.0, 3.0),
        };
        assert_eq!(line.point(2.0), Point::new(1.0, 8.0));
        let trimmed = Curve::Trimmed {
            basis: Box::new(line),
            range: (0.0, 1.0),
        };
        assert_eq!(trimmed.range(), Some((0.0, 1.0)));
        assert_eq!(trimmed.derivatives(0.5)[1], Point::new(0.0, 3.0));
        let h = Conic {
            kind: ConicKind::Hyperbola,
            center: Point::new(0.0, 0.0),
            u: Point::new(1.0, 0.0),
            v: Point::new(0.0, 1.0),
        };
        let q = h.point(0.7);
        assert!((q.x * q.x - q.y * q.y - 1.0).abs() < 1e-14);
        let par = Conic {
            kind: ConicKind::Parabola,
            center: Point::new(0.0, 0.0),
            u: Point::new(0.5, 0.0),
            v: Point::new(0.0, 0.5),
        };
        let q = par.point(-1.5);
        // y^2 = 4 f x with f = 1/2.
        assert!((q.y * q.y - 2.0 * q.x).abs() < 1e-14);
    }

    use std::f64::consts::{PI, TAU};

    use rs_spline::{Affine, circular_arc, segment};

    use crate::curve::testing::Rng;
    use crate::{Affine3, Frame, PlaneCoordinates};

    /// A clamped rational (or polynomial) B-spline in space with `spans` random knot spans.
    fn random_bspline(
        rng: &mut Rng,
        p: usize,
        spans: usize,
        rational: bool,
    ) -> RationalBSpline<Point3> {
        let n = p + spans;
        let mut knots = vec![0.0; p + 1];
        let mut u = 0.0;
        for _ in 0..spans - 1 {
            u += rng.uniform(0.2, 1.0);
            knots.push(u);
        }
        u += rng.uniform(0.2, 1.0);
        knots.extend(std::iter::repeat_n(u, p + 1));
        // A wandering polygon (no self-approach): steps mostly along x.
        let mut q = rng.point3(5.0);
        let points = (0..n)
            .map(|_| {
                q = q + Point3::new(
                    rng.uniform(0.5, 1.5),
                    rng.uniform(-1.0, 1.0),
                    rng.uniform(-1.0, 1.0),
                );
                q
            })
            .collect();
        let weights = rational.then(|| (0..n).map(|_| rng.uniform(0.5, 2.0)).collect());
        RationalBSpline::new(p, knots, points, weights).unwrap()
    }

    /// A closed uniform cubic B-spline (unclamped knots, the first three control points
    /// repeated at the end): periodic, its domain [3, n].
    fn periodic_bspline(n: usize) -> RationalBSpline<Point> {
        let mut points: Vec<Point> = (0..n)
            .map(|i| {
                let a = TAU * i as f64 / n as f64;
                Point::new(2.0 * a.cos() + 0.3 * (3.0 * a).cos(), a.sin())
            })
            .collect();
        points.extend_from_within(..3);
        let knots = (0..points.len() + 4).map(|i| i as f64).collect();
        RationalBSpline::new(3, knots, points, None).unwrap()
    }

    fn conic3(rng: &mut Rng, kind: ConicKind) -> Conic<Point3> {
        let (x, y) = rng.axes();
        Conic {
            kind,
            center: rng.point3(5.0),
            u: x * rng.uniform(0.5, 3.0),
            v: y * rng.uniform(0.5, 3.0),
        }
    }

    /// One curve of each kind in space, with a parameter interval inside it.
    fn curves(rng: &mut Rng) -> Vec<(Curve<Point3>, (f64, f64))> {
        let b = random_bspline(rng, 3, 12, true);
        let (a, e) = b.param_range();
        let trimmed = Curve::Trimmed {
            basis: Box::new(Curve::Conic(conic3(rng, ConicKind::Ellipse))),
            range: (2.0, 5.0),
        };
        vec![
            (
                Curve::Line {
                    origin: rng.point3(5.0),
                    direction: rng.point3(2.0),
                },
                (-1.5, 2.0),
            ),
            (Curve::Conic(conic3(rng, ConicKind::Ellipse)), (-2.0, 2.5)),
            (Curve::Conic(conic3(rng, ConicKind::Hyperbola)), (-1.5, 2.0)),
            (Curve::Conic(conic3(rng, ConicKind::Parabola)), (-1.5, 2.0)),
            (Curve::BSpline(b), (a + 0.1 * (e - a), a + 0.8 * (e - a))),
            (trimmed, (2.5, 4.5)),
        ]
    }

    fn size(c: &Curve<Point3>, (t0, t1): (f64, f64)) -> f64 {
        (0..=8)
            .map(|i| c.point(t0 + (t1 - t0) * f64::from(i) / 8.0).length())
            .fold(1.0, f64::max)
    }

    #[test]
    fn derivatives_match_central_differences() {
        let mut rng = Rng::new(1);
        let h = 1e-5;
        for _ in 0..10 {
            for (c, (t0, t1)) in curves(&mut rng) {
                for i in 1..8 {
                    let t = t0 + (t1 - t0) * f64::from(i) / 8.0 + 0.01;
                    let [p, d1, d2] = c.derivatives(t);
                    assert_eq!(p, c.point(t));
                    let fd1 = (c.point(t + h) - c.point(t - h)) / (2.0 * h);
                    let fd2 = (c.point(t + h) - p * 2.0 + c.point(t - h)) / (h * h);
                    let s = size(&c, (t0, t1)) * (1.0 + d1.length() + d2.length());
                    assert!(d1.distance(fd1) < 1e-8 * s, "{c:?} {t}");
                    assert!(d2.distance(fd2) < 1e-4 * s, "{c:?} {t}");
                }
            }
        }
    }

    /// Points of every kind of curve give back their parameters; a B-spline of many spans and
    /// a periodic one included.
    #[test]
    fn closest_parameter_recovers_t_on_every_curve_kind() {
        let mut rng = Rng::new(2);
        for _ in 0..10 {
            for (c, (t0, t1)) in curves(&mut rng) {
                for i in 0..=20 {
                    let t = t0 + (t1 - t0) * f64::from(i) / 20.0;
                    let x = c.point(t);
                    let window = c.range();
                    let got = c.closest_parameter(x, window);
                    assert!((got - t).abs() < 1e-9 * (1.0 + t.abs()), "{c:?} {t} {got}");
                    assert!(c.point(got).distance(x) < 1e-12 * size(&c, (t0, t1)));
                }
            }
        }
        // Many spans.
        let b = random_bspline(&mut rng, 3, 300, true);
        let (a, e) = b.param_range();
        let c = Curve::BSpline(b);
        for i in 0..=500 {
            let t = a + (e - a) * f64::from(i) / 500.0;
            let got = c.closest_parameter(c.point(t), None);
            assert!((got - t).abs() < 1e-10 * (e - a), "{t} {got}");
        }
        // The ends exactly.
        assert_eq!(c.closest_parameter(c.point(a), None), a);
        assert_eq!(c.closest_parameter(c.point(e), None), e);
        // Periodic: every point, the seam at the domain's start.
        let p = Curve::BSpline(periodic_bspline(11));
        let (a, e) = p.range().unwrap();
        assert_eq!(p.period(), Some(e - a));
        assert_eq!(p.closest_parameter(p.point(e), None), a);
        for i in 1..200 {
            let t = a + (e - a) * f64::from(i) / 200.0;
            let got = p.closest_parameter(p.point(t), None);
            assert!((got - t).abs() < 1e-10 * (e - a), "{t} {got}");
        }
    }

    /// The nearest point by brute force on `[lo, hi]`.
    fn brute_force(c: &Curve<Point3>, x: Point3, lo: f64, hi: f64) -> f64 {
        let (mut a, mut b) = (lo, hi);
        let mut best = f64::INFINITY;
        let mut at = lo;
        for _ in 0..3 {
            let n = 5000;
            for i in 0..=n {
                let t = a + (b - a) * f64::from(i) / f64::from(n);
                let d = c.point(t).distance(x);
                if d < best {
                    (best, at) = (d, t);
                }
            }
            let h = (b - a) / f64::from(n);
            (a, b) = ((at - h).max(lo), (at + h).min(hi));
        }
        best
    }

    #[test]
    fn closest_parameter_off_the_curve_is_the_nearest_point() {
        let mut rng = Rng::new(3);
        for _ in 0..6 {
            for (c, w) in curves(&mut rng) {
                for _ in 0..10 {
                    let x = c.point(rng.uniform(w.0, w.1)) + rng.point3(2.0);
                    let t = c.closest_parameter(x, Some(w));
                    assert!(w.0 <= t && t <= w.1);
                    let d = c.point(t).distance(x);
                    let brute = brute_force(&c, x, w.0, w.1);
                    assert!(d <= brute + 1e-12 * size(&c, w), "{c:?} {d} {brute}");
                    // Inside the window the foot condition holds to rounding (the Newton
                    // steps; golden-section search alone leaves about 1e-8 here).
                    if w.0 < t && t < w.1 {
                        let [p, d1, _] = c.derivatives(t);
                        let g = (p - x).dot(d1);
                        assert!(g.abs() < 1e-12 * d1.length() * size(&c, w), "{c:?} {g:e}");
                    }
                }
            }
        }
    }

    #[test]
    fn line_and_window_conventions() {
        let line = Curve::Line {
            origin: Point::new(1.0, 1.0),
            direction: Point::new(2.0, 0.0),
        };
        assert_eq!(line.closest_parameter(Point::new(4.0, 7.0), None), 1.5);
        assert_eq!(
            line.closest_parameter(Point::new(4.0, 7.0), Some((0.0, 1.0))),
            1.0
        );
        assert_eq!(
            line.closest_parameter(Point::new(4.0, 7.0), Some((3.0, 1.0))),
            3.0
        );
        let point = Curve::Line {
            origin: Point::new(1.0, 1.0),
            direction: Point::new(0.0, 0.0),
        };
        assert_eq!(point.closest_parameter(Point::new(4.0, 7.0), None), 0.0);
        let circle = Curve::Conic(Conic {
            kind: ConicKind::Ellipse,
            center: Point::new(0.0, 0.0),
            u: Point::new(1.0, 0.0),
            v: Point::new(0.0, 1.0),
        });
        // (-1, 0): pi, also in a window a whole turn later.
        assert_eq!(circle.closest_parameter(Point::new(-1.0, 0.0), None), PI);
        let t = circle.closest_parameter(Point::new(-1.0, 0.0), Some((4.0, 10.0)));
        assert!((t - 3.0 * PI).abs() < 1e-15);
        let trimmed = Curve::Trimmed {
            basis: Box::new(circle.clone()),
            range: (0.0, 1.0),
        };
        assert_eq!(trimmed.closest_parameter(Point::new(0.5, -1.0), None), 0.0);
        assert_eq!(trimmed.closest_parameter(Point::new(-1.0, -0.1), None), 1.0);
        let b = Curve::BSpline(periodic_bspline(8));
        assert_eq!(b.range(), Some((3.0, 11.0)));
        assert_eq!(
            b.closest_parameter(Point::new(9.0, 0.0), Some((20.0, 30.0))),
            11.0
        );
    }

    /// A random affine map of space, neither rigid nor orthogonal.
    fn random_affine(rng: &mut Rng) -> Affine3 {
        let mut m = [[0.0; 4]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                *x = rng.uniform(-1.0, 1.0) + if i == j { 2.0 } else { 0.0 };
            }
        }
        Affine3 { m }
    }

    /// Mapping a curve and evaluating it is evaluating and mapping the point (and the
    /// derivatives as vectors), for placements of space and for a plane's coordinates.
    #[test]
    fn mapping_commutes_with_evaluation() {
        let mut rng = Rng::new(4);
        for _ in 0..10 {
            let m = random_affine(&mut rng);
            let (x, y) = rng.axes();
            let plane = PlaneCoordinates {
                origin: rng.point3(3.0),
                x,
                y,
            };
            for (c, (t0, t1)) in curves(&mut rng) {
                let mapped = c.map_affine(&m).unwrap();
                let flat = c.map_affine(&plane).unwrap();
                assert_eq!(mapped.range(), c.range());
                let s = size(&c, (t0, t1));
                for i in 0..=10 {
                    let t = t0 + (t1 - t0) * f64::from(i) / 10.0;
                    let [p, d1, d2] = c.derivatives(t);
                    let [q, q1, q2] = mapped.derivatives(t);
                    assert!(q.distance(m.point(p)) < 1e-13 * 4.0 * s, "{c:?}");
                    assert!(q1.distance(m.vector(d1)) < 1e-13 * 4.0 * s * (1.0 + d1.length()));
                    assert!(q2.distance(m.vector(d2)) < 1e-12 * 4.0 * s * (1.0 + d2.length()));
                    let [f, f1, _] = flat.derivatives(t);
                    assert!(f.distance(plane.point(p)) < 1e-13 * s);
                    assert!(f1.distance(plane.vector(d1)) < 1e-13 * s * (1.0 + d1.length()));
                }
            }
        }
        // The plane's own map of rs-spline.
        let a = Affine {
            m: [1.5, 0.5, -0.25, 2.0, 3.0, -1.0],
        };
        let c = Curve::Conic(Conic {
            kind: ConicKind::Hyperbola,
            center: Point::new(1.0, 2.0),
            u: Point::new(1.0, 0.5),
            v: Point::new(-0.5, 1.0),
        });
        let mc = c.map_affine(&a).unwrap();
        for t in [-1.0, 0.0, 0.7] {
            assert!(mc.point(t).distance(a.apply(c.point(t))) < 1e-14);
        }
    }

    /// Each conversion is the curve on its interval: its ends are the curve's points there and
    /// every point of it is on the curve, within the interval.
    #[test]
    fn conversions_are_the_curve_on_the_interval() {
        let mut rng = Rng::new(5);
        for _ in 0..10 {
            for (c, (t0, t1)) in curves(&mut rng) {
                let b = c.to_bspline(t0, t1).unwrap();
                let s = size(&c, (t0, t1));
                let (a, e) = b.param_range();
                assert!(b.point_at(a).distance(c.point(t0)) < 1e-14 * s);
                assert!(b.point_at(e).distance(c.point(t1)) < 1e-14 * s);
                for i in 0..=40 {
                    let p = b.point_at(a + (e - a) * f64::from(i) / 40.0);
                    let t = c.closest_parameter(p, Some((t0, t1)));
                    assert!(c.point(t).distance(p) < 1e-13 * s, "{c:?}");
                }
            }
        }
    }

    fn bits(c: &RationalBSpline<Point>) -> Vec<u64> {
        let n = c.to_planar().unwrap();
        n.knots()
            .knots()
            .iter()
            .chain(n.control_points().iter().flat_map(|p| [&p.x, &p.y]))
            .chain(n.weights())
            .map(|x| x.to_bits())
            .collect()
    }

    /// The STEP reader's conversions of 3-D edges into a plane's (u, v), written out with its
    /// arithmetic (`Point::new(dot(p - o, ex), dot(p - o, ey))`, the unit arc under an
    /// `Affine`, the segment between mapped end points, mapped control points then the
    /// subsegment), are `to_bspline_mapped` bit for bit.
    #[test]
    fn mapped_conversions_keep_the_readers_arithmetic() {
        let mut rng = Rng::new(6);
        let frame = Frame::new(
            Point3::new(1.0, -2.0, 0.5),
            Some(Point3::new(0.3, -0.4, 1.0)),
            Some(Point3::new(1.0, 0.2, 0.0)),
        )
        .unwrap();
        let plane = PlaneCoordinates::new(&frame);
        let dot = |a: Point3, b: Point3| a.x * b.x + a.y * b.y + a.z * b.z;
        let point = |p: Point3| {
            let d = Point3::new(
                p.x - frame.origin.x,
                p.y - frame.origin.y,
                p.z - frame.origin.z,
            );
            Point::new(dot(d, frame.x), dot(d, frame.y))
        };
        let vector = |v: Point3| Point::new(dot(v, frame.x), dot(v, frame.y));
        for _ in 0..20 {
            // A circle of the plane.
            let r = rng.uniform(0.5, 3.0);
            let c = Conic {
                kind: ConicKind::Ellipse,
                center: frame.to_world(rng.uniform(-2.0, 2.0), rng.uniform(-2.0, 2.0), 0.0),
                u: frame.x * r,
                v: frame.y * r,
            };
            let (t0, t1) = (rng.uniform(-PI, PI), rng.uniform(3.5, 7.0));
            let (mu, mv, mc) = (vector(c.u), vector(c.v), point(c.center));
            let want = Affine {
                m: [mu.x, mu.y, mv.x, mv.y, mc.x, mc.y],
            }
            .apply_to_curve(&circular_arc(Point::new(0.0, 0.0), 1.0, t0, t1 - t0).unwrap())
            .unwrap();
            let got = Curve::Conic(c).to_bspline_mapped(&plane, t0, t1).unwrap();
            assert_eq!(bits(&got), bits(&(&want).into()));
            // A line.
            let (o, d) = (
                frame.to_world(rng.uniform(-2.0, 2.0), 1.0, 0.0),
                frame.x * 1.5,
            );
            let line = Curve::Line {
                origin: o,
                direction: d,
            };
            let want = segment(point(o + d * t0), point(o + d * t1)).unwrap();
            let got = line.to_bspline_mapped(&plane, t0, t1).unwrap();
            assert_eq!(bits(&got), bits(&(&want).into()));
            // A B-spline of the plane.
            let b = random_bspline(&mut rng, 3, 6, true)
                .map_points(|p| frame.to_world(p.x, p.y, 0.0))
                .unwrap();
            let (a, e) = b.param_range();
            let w = (a + 0.2 * (e - a), a + 0.7 * (e - a));
            let want = rs_spline::NurbsCurve::new(
                3,
                b.knots().knots().to_vec(),
                b.control_points().iter().map(|&p| point(p)).collect(),
                b.weights().map(<[f64]>::to_vec),
            )
            .unwrap();
            let want = rs_spline::ParamCurve::subsegment(&want, w).unwrap();
            let got = Curve::BSpline(b)
                .to_bspline_mapped(&plane, w.0, w.1)
                .unwrap();
            assert_eq!(bits(&got), bits(&(&want).into()));
        }
    }

    #[test]
    fn extended_conversions_continue_the_end_spans() {
        let mut rng = Rng::new(7);
        // A rational curve's continuation may reach a zero weight soon; a polynomial one's is
        // defined everywhere.
        let rational = Curve::BSpline(random_bspline(&mut rng, 3, 5, true));
        let (a, e) = rational.range().unwrap();
        let pieces = rational.to_bspline_extended(a - 1e-3, e).unwrap();
        assert!(pieces[0].weights().is_some() && pieces.len() == 2);
        let b = random_bspline(&mut rng, 3, 5, false);
        let (a, e) = b.param_range();
        let c = Curve::Trimmed {
            basis: Box::new(Curve::BSpline(b)),
            range: (a, e),
        };
        assert_eq!(c.spline_domain(), Some((a, e)));
        let pieces = c.to_bspline_extended(a - 0.1, e + 0.2).unwrap();
        assert_eq!(pieces.len(), 3);
        let ends = |p: &RationalBSpline<Point3>| {
            let (s, t) = p.param_range();
            (p.point_at(s), p.point_at(t))
        };
        assert!(ends(&pieces[0]).0.distance(c.point_extended(a - 0.1)) < 1e-13);
        assert!(ends(&pieces[0]).1.distance(ends(&pieces[1]).0) < 1e-13);
        assert!(ends(&pieces[1]).1.distance(ends(&pieces[2]).0) < 1e-13);
        assert!(ends(&pieces[2]).1.distance(c.point_extended(e + 0.2)) < 1e-12);
        assert_eq!(c.to_bspline_extended(a, e).unwrap().len(), 1);
        assert_eq!(c.point_extended(0.5 * (a + e)), c.point(0.5 * (a + e)));
    }

    #[test]
    fn conversion_errors() {
        let line = Curve::Line {
            origin: Point::new(0.0, 0.0),
            direction: Point::new(1.0, 0.0),
        };
        assert!(matches!(
            line.to_bspline(1.0, 0.0),
            Err(GeomError::EmptyInterval { .. })
        ));
        assert!(matches!(
            line.to_bspline(0.0, f64::INFINITY),
            Err(GeomError::EmptyInterval { .. })
        ));
        let n = line.to_planar_nurbs(0.0, 2.0).unwrap();
        assert_eq!(rs_spline::ParamCurve::end_point(&n), Point::new(2.0, 0.0));
        let b = Curve::BSpline(periodic_bspline(6));
        assert!(matches!(
            b.to_bspline(20.0, 30.0),
            Err(GeomError::Spline(_))
        ));
        let huge = Affine3 {
            m: [
                [f64::INFINITY, 0.0, 0.0, 0.0],
                [0.0, 1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0, 0.0],
            ],
        };
        let l3 = Curve::Line {
            origin: Point3::X,
            direction: Point3::Y,
        };
        assert!(matches!(
            l3.map_affine(&huge),
            Err(GeomError::NotFinite { .. })
        ));
    }
}
