//! Rational B-spline curves of any dimension (the plane, space), evaluated by the one kernel
//! ([`crate::rational_sums`]) and cut by the one knot-insertion code of `insertion.rs`.

use std::borrow::Cow;

use crate::error::{check_control_points, normalized_weights};
use crate::insertion::{SplineParts, SplineRef, Weighted};
use crate::kernel::{rational_quotient, rational_sums};
use crate::{KnotVector, SplineError, Vector};

/// A rational B-spline curve `C(u) = sum_i N_{i,p}(u) w_i P_i / sum_i N_{i,p}(u) w_i` with
/// control points in any [`Vector`] space (the plane, space), on the domain `[u_p, u_n]` of
/// its [`KnotVector`].
///
/// Preconditions enforced by [`RationalBSpline::new`]: a valid knot vector, finite control
/// points within [`crate::limits::MAX_COORDINATE`], weights finite and `> 0` (rescaled by a
/// power of two as [`crate::NurbsCurve::new`] does). Planar curves with every 2-D algorithm
/// are [`crate::NurbsCurve`]s ([`RationalBSpline::to_planar`]).
///
/// # Examples
///
/// ```
/// use rs_spline::{Point3, RationalBSpline};
/// // A quarter of the unit circle in the plane z = 2, as a rational quadratic.
/// let w = std::f64::consts::FRAC_1_SQRT_2;
/// let c = RationalBSpline::new(
///     2,
///     vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Point3::new(1.0, 0.0, 2.0), Point3::new(1.0, 1.0, 2.0), Point3::new(0.0, 1.0, 2.0)],
///     Some(vec![1.0, w, 1.0]),
/// )
/// .unwrap();
/// let p = c.point_at(0.3);
/// assert!((p.x.hypot(p.y) - 1.0).abs() < 1e-15 && p.z == 2.0);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct RationalBSpline<P> {
    knots: KnotVector,
    points: Vec<P>,
    /// `None`: every weight 1 (a polynomial B-spline).
    weights: Option<Vec<f64>>,
}

impl<P: Vector + std::ops::Div<f64, Output = P>> RationalBSpline<P> {
    /// Validates and builds a curve. `weights: None` means all weights 1.
    ///
    /// # Errors
    /// Every [`SplineError`] about degree, knots, control points and weights.
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<P>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, SplineError> {
        let knots = KnotVector::new(knots, degree, points.len())?;
        Self::from_parts(knots, points, weights)
    }

    /// Builds from an already validated knot vector.
    ///
    /// # Errors
    /// Control point and weight errors, a knot vector for another number of points.
    pub fn from_parts(
        knots: KnotVector,
        points: Vec<P>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, SplineError> {
        if points.len() != knots.n_control() {
            return Err(SplineError::WrongKnotCount {
                expected: points.len() + knots.degree() + 1,
                got: knots.knots().len(),
            });
        }
        let weights = match weights {
            Some(w) => {
                check_control_points(&points, &w)?;
                Some(normalized_weights(w))
            }
            None => {
                check_control_points(&points, &vec![1.0; points.len()])?;
                None
            }
        };
        Ok(Self {
            knots,
            points,
            weights,
        })
    }

    /// The degree `p`.
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }

    /// The knot vector.
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// The control points.
    pub fn control_points(&self) -> &[P] {
        &self.points
    }

    /// The weights, `None` when every weight is 1.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// The knot domain `[u_p, u_n]`.
    pub fn param_range(&self) -> (f64, f64) {
        self.knots.domain()
    }

    /// `C(u)`; `u` is clamped into the domain.
    pub fn point_at(&self, u: f64) -> P {
        let [(a, w), ..] = rational_sums(&self.knots, &self.points, self.weights(), u, 0);
        a / w
    }

    /// `[C(u), C'(u), C''(u)]` by the quotient rule; `u` is clamped into the domain. At a knot
    /// the derivatives are those of the span to its right (of the last span at the domain's
    /// end).
    pub fn derivatives(&self, u: f64) -> [P; 3] {
        rational_quotient(rational_sums(
            &self.knots,
            &self.points,
            self.weights(),
            u,
            2,
        ))
    }

    /// The curve with every control point mapped by `f`, knots and weights kept: the exact
    /// image of the curve under `f` when `f` is affine (a placement, a projection into a
    /// plane's coordinates).
    ///
    /// # Errors
    /// Control point errors of the images (non-finite, beyond the coordinate limit).
    pub fn map_points<Q: Vector + std::ops::Div<f64, Output = Q>>(
        &self,
        f: impl FnMut(P) -> Q,
    ) -> Result<RationalBSpline<Q>, SplineError> {
        RationalBSpline::from_parts(
            self.knots.clone(),
            self.points.iter().copied().map(f).collect(),
            self.weights.clone(),
        )
    }

    /// True when every weight is 1 (`weights()` is `None`).
    pub fn is_polynomial(&self) -> bool {
        self.weights.is_none()
    }

    /// The weights as a slice, ones for a polynomial curve.
    fn weight_slice(&self) -> Cow<'_, [f64]> {
        match &self.weights {
            Some(w) => Cow::Borrowed(w),
            None => Cow::Owned(vec![1.0; self.points.len()]),
        }
    }

    /// Runs one of the knot algorithms of [`crate::insertion`] (shared with
    /// [`crate::NurbsCurve`]) on the curve's data.
    fn with_parts<R>(&self, f: impl FnOnce(SplineRef<'_, P>) -> R) -> R {
        let weights = self.weight_slice();
        f(SplineRef {
            knots: &self.knots,
            points: &self.points,
            weights: &weights,
        })
    }

    /// The curve of data a knot algorithm made from this curve. Its weights are convex
    /// combinations of this curve's, so a polynomial curve's stay exactly 1 (`fl(fl(1 - a) + a)
    /// = 1` for `a` in `[0, 1]`) and are dropped again.
    fn with_spline_parts(&self, c: SplineParts<P>) -> Self {
        let weights = self.weights.as_ref().map(|_| c.weights);
        Self {
            knots: c.knots,
            points: c.points,
            weights,
        }
    }

    /// Inserts the knot `u` `times` times (Boehm's algorithm in homogeneous coordinates, the
    /// code [`crate::NurbsCurve::insert_knot`] runs). The curve is unchanged as a point set and
    /// as a function of `u`.
    ///
    /// # Errors
    /// [`SplineError::ParameterOutOfDomain`] if `u` is outside the domain;
    /// [`SplineError::MultiplicityExceeded`] if the multiplicity would exceed the degree.
    pub fn insert_knot(&self, u: f64, times: usize) -> Result<Self, SplineError> {
        let c = self.with_parts(|r| r.insert_knot(u, times))?;
        Ok(self.with_spline_parts(c))
    }

    /// Inserts every value of `new_knots` once, in order (knot refinement). Values may repeat.
    ///
    /// # Errors
    /// As [`RationalBSpline::insert_knot`] for each value.
    pub fn refine(&self, new_knots: &[f64]) -> Result<Self, SplineError> {
        let c = self.with_parts(|r| r.refine(new_knots))?;
        Ok(self.with_spline_parts(c))
    }

    /// Splits at `u` strictly inside the domain `[a, b]` into the curves on `[a, u]` and
    /// `[u, b]` (each keeps its part of the parameter).
    ///
    /// # Errors
    /// [`SplineError::ParameterOutOfDomain`] unless `a < u < b`.
    pub fn split_at(&self, u: f64) -> Result<(Self, Self), SplineError> {
        let (l, r) = self.with_parts(|r| r.split_at(u))?;
        Ok((self.with_spline_parts(l), self.with_spline_parts(r)))
    }

    /// The curve on the window `[u0, u1]` of the domain (`a <= u0 < u1 <= b`), in the same
    /// parameter; the same curve for the whole domain.
    ///
    /// # Errors
    /// [`SplineError::ParameterOutOfDomain`] for an empty window or one not inside the domain.
    pub fn subsegment(&self, range: (f64, f64)) -> Result<Self, SplineError> {
        let c = self.with_parts(|r| r.subsegment(range))?;
        Ok(self.with_spline_parts(c))
    }

    /// The same curve with clamped end knots (multiplicity `p + 1`): its first and last control
    /// points are its end points. Knot values are kept exactly.
    pub fn clamped(&self) -> Self {
        let c = self.with_parts(|r| r.clamped());
        self.with_spline_parts(c)
    }

    /// The same curve traversed backwards on the same domain `[a, b]`:
    /// `C_rev(u) = C(a + b - u)`.
    pub fn reversed(&self) -> Self {
        let c = self.with_parts(|r| r.reversed());
        self.with_spline_parts(c)
    }

    /// The first (`start`) or last non-empty knot span `k` (`u_k < u_{k+1}`); one exists, the
    /// domain being non-empty.
    fn end_span(&self, start: bool) -> usize {
        let p = self.degree();
        let n = self.points.len();
        let knots = self.knots.knots();
        let non_empty = |&k: &usize| knots[k] < knots[k + 1];
        if start {
            (p..n).find(non_empty).unwrap_or(p)
        } else {
            (p..n).rev().find(non_empty).unwrap_or(n - 1)
        }
    }

    /// The polar form (blossom) of the polynomial of knot span `k` at the `p` arguments `us`,
    /// in homogeneous coordinates `(w P, w)`: de Boor's algorithm with the argument `us[r - 1]`
    /// at level `r` (The NURBS Book, section 5.2; with every argument `u` it is `C(u)`'s
    /// homogeneous point). The arguments may lie outside the span: the span's polynomial is
    /// continued.
    fn blossom(&self, k: usize, us: &[f64]) -> Weighted<P> {
        let p = self.degree();
        let knots = self.knots.knots();
        let w = |i: usize| self.weights.as_ref().map_or(1.0, |w| w[i]);
        let mut d: Vec<Weighted<P>> = (0..=p)
            .map(|j| Weighted::new(self.points[k - p + j], w(k - p + j)))
            .collect();
        for r in 1..=p {
            let t = us.get(r - 1).copied().unwrap_or(f64::NAN);
            for j in (r..=p).rev() {
                let i = k - p + j;
                let den = knots[i + p + 1 - r] - knots[i];
                let alpha = if den > 0.0 { (t - knots[i]) / den } else { 0.0 };
                d[j] = d[j - 1] * (1.0 - alpha) + d[j] * alpha;
            }
        }
        d[p]
    }

    /// The point at `t`, continued past the domain `[a, b]` by the polynomial (in homogeneous
    /// coordinates) of the first span before `a` and of the last span after `b`: how a curve
    /// that stops a little short of where it should end is extended to it. Inside the domain,
    /// [`RationalBSpline::point_at`]. A rational curve continued far may reach a zero weight
    /// (a non-finite point).
    pub fn point_extended(&self, t: f64) -> P {
        let (a, b) = self.param_range();
        if t < a || t > b {
            let k = self.end_span(t < a);
            self.blossom(k, &vec![t; self.degree()]).project()
        } else {
            self.point_at(t)
        }
    }

    /// The continuation of the curve over `[t0, t1]` before its domain (`t1 <= a`: the first
    /// span's polynomial) or after it (`t0 >= b`: the last span's), as one Bezier curve on
    /// `[0, 1]` (its parameter `s` is `t0 + s (t1 - t0)`), exact: control point `i` is the
    /// span's polar form at `t0` (`p - i` times) and `t1` (`i` times), in homogeneous
    /// coordinates (The NURBS Book, section 5.2). A polynomial curve's extension is
    /// polynomial.
    ///
    /// # Errors
    /// [`SplineError::ExtensionInterval`] for an empty interval or one reaching into the
    /// domain; [`SplineError::NonPositiveWeight`] where a rational curve's continuation reaches
    /// a zero weight; the control point errors of [`RationalBSpline::new`].
    pub fn extension(&self, t0: f64, t1: f64) -> Result<Self, SplineError> {
        let (a, b) = self.param_range();
        let before = t1 <= a;
        // NaN fails both comparisons below.
        if !(t0 < t1 && (before || t0 >= b)) {
            return Err(SplineError::ExtensionInterval {
                t0,
                t1,
                start: a,
                end: b,
            });
        }
        let k = self.end_span(before);
        let p = self.degree();
        let mut points = Vec::with_capacity(p + 1);
        let mut weights = Vec::with_capacity(p + 1);
        for i in 0..=p {
            let mut us = vec![t0; p - i];
            us.extend(std::iter::repeat_n(t1, i));
            let h = self.blossom(k, &us);
            if !(h.w > 0.0 && h.w.is_finite()) {
                return Err(SplineError::NonPositiveWeight {
                    index: i,
                    value: h.w,
                });
            }
            points.push(h.project());
            weights.push(h.w);
        }
        let weights = self.weights.as_ref().map(|_| weights);
        Self::from_parts(KnotVector::bezier(p), points, weights)
    }
}

impl RationalBSpline<crate::Point> {
    /// The planar curve with every 2-D algorithm (subsegments, Bezier extraction, areas, ...).
    ///
    /// # Errors
    /// None in practice (the data was validated); kept for the constructor's contract.
    pub fn to_planar(&self) -> Result<crate::NurbsCurve, SplineError> {
        crate::NurbsCurve::from_parts(
            self.knots.clone(),
            self.points.clone(),
            self.weights.clone(),
        )
    }
}

impl From<&crate::NurbsCurve> for RationalBSpline<crate::Point> {
    /// The planar curve as a curve of any dimension (its weights kept, all 1 included).
    fn from(c: &crate::NurbsCurve) -> Self {
        Self {
            knots: c.knots().clone(),
            points: c.control_points().to_vec(),
            weights: Some(c.weights().to_vec()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prelude::*;
    use crate::{NurbsCurve, Point, Point3, circle};
    use proptest::prelude::*;

    /// The kernel gives a planar NURBS's points and derivatives bit for bit, in 2-D and lifted
    /// to 3-D.
    #[test]
    fn planar_and_space_curves_agree_with_nurbs_curve() {
        let c = circle(Point::new(1.0, -2.0), 3.0).unwrap();
        let r = RationalBSpline::from(&c);
        let lifted = r.map_points(|p| Point3::new(p.x, p.y, 7.0)).unwrap();
        let (a, b) = c.param_range();
        for i in 0..=40 {
            let u = a + (b - a) * f64::from(i) / 40.0;
            let d = c.derivatives(u);
            let [p, d1, d2] = r.derivatives(u);
            assert_eq!((p, d1, d2), (d.point, d.first, d.second));
            assert_eq!(r.point_at(u), c.point_at(u));
            let [q, q1, _] = lifted.derivatives(u);
            assert_eq!((q.x, q.y, q1.x, q1.y), (p.x, p.y, d1.x, d1.y));
            // A constant coordinate: 7 exactly, its derivative zero up to the quotient's rounding.
            assert!((q.z - 7.0).abs() < 1e-14 && q1.z.abs() < 1e-13);
        }
        assert_eq!(r.to_planar().unwrap(), c);
    }

    #[test]
    fn polynomial_curves_and_errors() {
        let c = RationalBSpline::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![Point3::ORIGIN, Point3::new(2.0, 4.0, 6.0)],
            None,
        )
        .unwrap();
        assert_eq!(c.point_at(0.5), Point3::new(1.0, 2.0, 3.0));
        assert_eq!(c.derivatives(0.25)[1], Point3::new(2.0, 4.0, 6.0));
        assert!(c.weights().is_none());
        let bad = RationalBSpline::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![Point3::ORIGIN, Point3::new(f64::NAN, 0.0, 0.0)],
            None,
        );
        assert!(matches!(
            bad,
            Err(SplineError::NonFiniteControlPoint { index: 1, .. })
        ));
        let zero_weight = RationalBSpline::new(
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![Point3::ORIGIN, Point3::X],
            Some(vec![1.0, 0.0]),
        );
        assert!(matches!(
            zero_weight,
            Err(SplineError::NonPositiveWeight { index: 1, .. })
        ));
        let _ = NurbsCurve::bezier(vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0)], None);
    }

    fn bits2(c: &RationalBSpline<Point>) -> Vec<u64> {
        let w = c.weights().map(<[f64]>::to_vec).unwrap_or_default();
        c.knots()
            .knots()
            .iter()
            .chain(c.control_points().iter().flat_map(|q| [&q.x, &q.y]))
            .chain(&w)
            .map(|x| x.to_bits())
            .collect()
    }

    fn nurbs_bits(c: &NurbsCurve) -> Vec<u64> {
        bits2(&RationalBSpline::from(c))
    }

    fn sample_curve() -> NurbsCurve {
        NurbsCurve::new(
            3,
            vec![-1.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.5, 1.0, 1.0, 1.5, 2.0],
            vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 2.0),
                Point::new(2.0, -1.0),
                Point::new(3.0, 0.5),
                Point::new(4.0, 2.0),
                Point::new(5.0, 0.0),
                Point::new(6.0, 1.0),
            ],
            Some(vec![1.0, 0.5, 2.0, 1.0, 3.0, 0.7, 1.0]),
        )
        .unwrap()
    }

    /// The knot algorithms of a planar `RationalBSpline` are `NurbsCurve`'s, bit for bit; lifted
    /// to space, the x and y of every result are the planar ones and z stays what it was.
    #[test]
    fn knot_algorithms_are_shared_with_nurbs_curve() {
        let c = sample_curve();
        let r = RationalBSpline::from(&c);
        let lifted = r.map_points(|p| Point3::new(p.x, p.y, -3.0)).unwrap();
        let flat = |s: &RationalBSpline<Point3>| {
            // z is a projected combination of -3's: -3 up to rounding.
            assert!(s.control_points().iter().all(|q| (q.z + 3.0).abs() < 1e-14));
            s.map_points(|q| Point::new(q.x, q.y)).unwrap()
        };
        for u in [0.0, 0.1, 0.3, 0.5, 0.77, 1.0] {
            let times = 3 - c.knots().multiplicity(u);
            let want = nurbs_bits(&c.insert_knot(u, times).unwrap());
            assert_eq!(bits2(&r.insert_knot(u, times).unwrap()), want);
            assert_eq!(bits2(&flat(&lifted.insert_knot(u, times).unwrap())), want);
            if u > 0.0 && u < 1.0 {
                let (l, rr) = c.split_at(u).unwrap();
                let (gl, gr) = r.split_at(u).unwrap();
                assert_eq!((bits2(&gl), bits2(&gr)), (nurbs_bits(&l), nurbs_bits(&rr)));
                let (sl, sr) = lifted.split_at(u).unwrap();
                assert_eq!(
                    (bits2(&flat(&sl)), bits2(&flat(&sr))),
                    (nurbs_bits(&l), nurbs_bits(&rr))
                );
                let w = (u, 0.5 * (u + 1.0));
                assert_eq!(
                    bits2(&r.subsegment(w).unwrap()),
                    nurbs_bits(&c.subsegment(w).unwrap())
                );
            }
        }
        assert_eq!(bits2(&r.clamped()), nurbs_bits(&c.clamped()));
        assert_eq!(bits2(&r.reversed()), nurbs_bits(&c.reversed()));
        assert_eq!(
            bits2(&r.refine(&[0.1, 0.1, 0.9]).unwrap()),
            nurbs_bits(&c.refine(&[0.1, 0.1, 0.9]).unwrap())
        );
        assert!(matches!(
            r.insert_knot(0.5, 2),
            Err(SplineError::MultiplicityExceeded { current: 2, .. })
        ));
        assert!(r.split_at(0.0).is_err() && r.subsegment((0.5, 0.5)).is_err());
        assert!(r.subsegment((0.5, 1.5)).is_err());
    }

    /// A polynomial curve stays polynomial through every knot algorithm (weights `None`), with
    /// the points its lerps give.
    #[test]
    fn polynomial_curves_stay_polynomial() {
        let c = RationalBSpline::new(
            2,
            vec![0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0],
            vec![
                Point3::ORIGIN,
                Point3::X,
                Point3::new(1.0, 1.0, 1.0),
                Point3::Z,
            ],
            None,
        )
        .unwrap();
        let s = c.subsegment((0.1, 0.7)).unwrap();
        assert!(s.is_polynomial() && s.param_range() == (0.1, 0.7));
        let weighted = RationalBSpline::new(
            2,
            c.knots().knots().to_vec(),
            c.control_points().to_vec(),
            Some(vec![1.0; 4]),
        )
        .unwrap()
        .subsegment((0.1, 0.7))
        .unwrap();
        assert!(weighted.weights().unwrap().iter().all(|&w| w == 1.0));
        assert_eq!(weighted.control_points(), s.control_points());
        assert!(c.reversed().is_polynomial() && c.clamped().is_polynomial());
    }

    /// The end-span continuation is the span's polynomial: on a single polynomial Bezier span
    /// on `[0, 1]` it is the Bernstein polynomial evaluated outside `[0, 1]`.
    #[test]
    fn extension_continues_the_end_span_polynomial() {
        let pts = [
            Point3::new(0.0, 0.0, 1.0),
            Point3::new(1.0, 2.0, 0.0),
            Point3::new(3.0, -1.0, 2.0),
            Point3::new(4.0, 1.0, 1.0),
        ];
        let c = RationalBSpline::new(
            3,
            vec![0.0; 4].into_iter().chain([1.0; 4]).collect(),
            pts.to_vec(),
            None,
        )
        .unwrap();
        let bernstein = |t: f64| {
            let s = 1.0 - t;
            pts[0] * (s * s * s)
                + pts[1] * (3.0 * s * s * t)
                + pts[2] * (3.0 * s * t * t)
                + pts[3] * (t * t * t)
        };
        for t in [-0.7, -0.1, 1.05, 2.0] {
            assert!(c.point_extended(t).distance(bernstein(t)) < 1e-13, "{t}");
        }
        let before = c.extension(-0.7, 0.0).unwrap();
        assert!(before.is_polynomial() && before.param_range() == (0.0, 1.0));
        for i in 0..=10 {
            let s = f64::from(i) / 10.0;
            let t = -0.7 + 0.7 * s;
            assert!(before.point_at(s).distance(bernstein(t)) < 1e-13);
        }
        assert!(before.point_at(1.0).distance(c.point_at(0.0)) < 1e-15);
        let after = c.extension(1.0, 2.0).unwrap();
        assert!(after.point_at(0.0).distance(c.point_at(1.0)) < 1e-14);
        assert!(after.point_at(1.0).distance(bernstein(2.0)) < 1e-12);
        for bad in [(-1.0, 0.5), (0.5, 2.0), (0.0, -1.0), (f64::NAN, 0.0)] {
            assert!(matches!(
                c.extension(bad.0, bad.1),
                Err(SplineError::ExtensionInterval { .. })
            ));
        }
    }

    /// A rational curve with several spans: the extension follows the first and last spans
    /// (checked against the points past the domain), its weights stay rational, and a
    /// continuation to a zero weight is refused.
    #[test]
    fn rational_extension_uses_the_end_spans() {
        let c = RationalBSpline::from(&sample_curve());
        let (a, b) = c.param_range();
        assert_eq!((a, b), (0.0, 1.0));
        let e = c.extension(-0.2, 0.0).unwrap();
        assert!(e.weights().is_some());
        for i in 0..=8 {
            let s = f64::from(i) / 8.0;
            let q = c.point_extended(-0.2 + 0.2 * s);
            assert!(e.point_at(s).distance(q) < 1e-13, "{s}");
        }
        // Inside the domain point_extended is point_at; just past it, close to the end point.
        assert_eq!(c.point_extended(0.4), c.point_at(0.4));
        assert!(c.point_extended(1.0 + 1e-9).distance(c.point_at(1.0)) < 1e-7);
        // Middle weight 3: the weight polynomial -4 t^2 + 4 t + 1 is zero at t = -0.207.
        let arc = RationalBSpline::new(
            2,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![
                Point::new(1.0, 0.0),
                Point::new(1.0, 1.0),
                Point::new(0.0, 1.0),
            ],
            Some(vec![1.0, 3.0, 1.0]),
        )
        .unwrap();
        assert!(arc.extension(-0.2, 0.0).is_ok());
        assert!(matches!(
            arc.extension(-1.0, 0.0),
            Err(SplineError::NonPositiveWeight { .. })
        ));
    }

    fn arb_curve3() -> impl Strategy<Value = RationalBSpline<Point3>> {
        (1usize..=4, 0usize..6, any::<u64>()).prop_map(|(p, extra, seed)| {
            let mut rng = rs_testkit::XorShift64::new(seed | 1);
            let n = p + 1 + extra;
            let mut knots = vec![0.0; p + 1];
            let (mut u, mut run) = (0.0, p + 1);
            for _ in 0..n - p - 1 {
                // Repeated interior knots, up to multiplicity p.
                if run >= p || rng.next_f64() > 0.2 {
                    u += rng.uniform(0.05, 1.0);
                    run = 0;
                }
                run += 1;
                knots.push(u);
            }
            let end = u + rng.uniform(0.05, 1.0);
            knots.extend(std::iter::repeat_n(end, p + 1));
            let points = (0..n)
                .map(|_| {
                    Point3::new(
                        rng.uniform(-4.0, 4.0),
                        rng.uniform(-4.0, 4.0),
                        rng.uniform(-4.0, 4.0),
                    )
                })
                .collect();
            let weights =
                (rng.next_f64() < 0.7).then(|| (0..n).map(|_| rng.uniform(0.3, 3.0)).collect());
            RationalBSpline::new(p, knots, points, weights).unwrap()
        })
    }

    fn size(c: &RationalBSpline<Point3>) -> f64 {
        c.control_points()
            .iter()
            .map(|q| q.length())
            .fold(1.0, f64::max)
    }

    proptest! {
        /// Knot insertion leaves the curve unchanged as a function of its parameter (to 1e-14
        /// of its size).
        #[test]
        fn insertion_keeps_the_curve(c in arb_curve3(), s in 0.0f64..=1.0, times in 1usize..4) {
            let (a, b) = c.param_range();
            let u = a + s * (b - a);
            let have = c.knots().multiplicity(u);
            prop_assume!(have + times <= c.degree());
            let r = c.insert_knot(u, times).unwrap();
            prop_assert_eq!(r.control_points().len(), c.control_points().len() + times);
            for i in 0..=32 {
                let t = a + (b - a) * f64::from(i) / 32.0;
                prop_assert!(r.point_at(t).distance(c.point_at(t)) <= 1e-14 * size(&c), "{}", t);
            }
        }

        /// A subsegment is the curve on its window, in the same parameter, and its ends are the
        /// curve's points there.
        #[test]
        fn subsegment_keeps_the_curve(c in arb_curve3(), s0 in 0.0f64..1.0, s1 in 0.0f64..1.0) {
            let (a, b) = c.param_range();
            let (lo, hi) = (s0.min(s1), s0.max(s1));
            prop_assume!(hi - lo > 1e-3);
            let (u0, u1) = (a + lo * (b - a), a + hi * (b - a));
            let sub = c.subsegment((u0, u1)).unwrap();
            prop_assert_eq!(sub.param_range(), (u0, u1));
            for i in 0..=16 {
                let t = u0 + (u1 - u0) * f64::from(i) / 16.0;
                prop_assert!(sub.point_at(t).distance(c.point_at(t)) <= 1e-14 * size(&c), "{}", t);
            }
            let first = *sub.clamped().control_points().first().unwrap();
            prop_assert!(first.distance(c.point_at(u0)) <= 1e-14 * size(&c));
            let rev = c.reversed();
            prop_assert!(rev.point_at(a + b - u0).distance(c.point_at(u0)) <= 1e-14 * size(&c));
        }
    }
}
