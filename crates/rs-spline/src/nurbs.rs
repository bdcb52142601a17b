//! Planar NURBS curves.

use rs_roots::RootsError;

use crate::bezier_extraction::SpanExtraction;
use crate::curve::prelude::*;
use crate::error::{check_control_points, normalized_weights};
use crate::homogeneous::{Hpoint, rational_derivatives, rational_point_and_tangent};
use crate::quadrature::Integral;
use crate::{BoundingBox, CurveDerivatives, KnotVector, Point, RationalBezier, SplineError};

/// A planar NURBS curve `C(u) = sum_i N_{i,p}(u) w_i P_i / sum_i N_{i,p}(u) w_i` on the domain
/// `[u_p, u_n]` of its knot vector.
///
/// Preconditions enforced by [`NurbsCurve::new`]: degree >= 1, at least `degree + 1` finite
/// control points, a valid [`KnotVector`], weights finite and > 0. All weights positive means
/// the curve lies in the convex hull of its control points and every Bezier piece has a
/// positive denominator.
///
/// # Examples
///
/// ```
/// use rs_spline::{NurbsCurve, Point, prelude::*};
/// // A quarter of the unit circle as a rational quadratic.
/// let w = std::f64::consts::FRAC_1_SQRT_2;
/// let c = NurbsCurve::new(
///     2,
///     vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
///     vec![Point::new(1.0, 0.0), Point::new(1.0, 1.0), Point::new(0.0, 1.0)],
///     Some(vec![1.0, w, 1.0]),
/// )
/// .unwrap();
/// let p = c.point_at(0.3);
/// assert!((p.length() - 1.0).abs() < 1e-15);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsCurve {
    knots: KnotVector,
    points: Vec<Point>,
    weights: Vec<f64>,
}

impl NurbsCurve {
    /// Validates and builds a curve. `weights: None` means all weights 1 (a B-spline).
    ///
    /// Weights whose largest value is beyond `2^32` or below `2^-32` are rescaled exactly by a
    /// power of two (the curve is unchanged); the limits of [`crate::limits`] apply.
    ///
    /// # Errors
    /// Every [`SplineError`] about degree, knots, control points and weights.
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<Point>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, SplineError> {
        let knots = KnotVector::new(knots, degree, points.len())?;
        Self::from_parts(knots, points, weights)
    }

    /// A single Bezier piece of degree `points.len() - 1` on `[0, 1]`.
    ///
    /// # Errors
    /// As [`NurbsCurve::new`].
    pub fn bezier(points: Vec<Point>, weights: Option<Vec<f64>>) -> Result<Self, SplineError> {
        if points.len() < 2 {
            return Err(SplineError::TooFewControlPoints {
                degree: 1,
                needed: 2,
                got: points.len(),
            });
        }
        Self::from_parts(KnotVector::bezier(points.len() - 1), points, weights)
    }

    /// Builds from an already validated knot vector.
    ///
    /// # Errors
    /// Control point and weight errors.
    pub fn from_parts(
        knots: KnotVector,
        points: Vec<Point>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, SplineError> {
        if points.len() != knots.n_control() {
            return Err(SplineError::WrongKnotCount {
                expected: points.len() + knots.degree() + 1,
                got: knots.knots().len(),
            });
        }
        let weights = weights.unwrap_or_else(|| vec![1.0; points.len()]);
        check_control_points(&points, &weights)?;
        let weights = normalized_weights(weights);
        Ok(Self {
            knots,
            points,
            weights,
        })
    }

    fn from_homogeneous(knots: Vec<f64>, degree: usize, hp: &[Hpoint]) -> Self {
        Self {
            knots: KnotVector::from_raw(knots, degree),
            points: Hpoint::project_all(hp),
            weights: hp.iter().map(|h| h.w).collect(),
        }
    }

    fn homogeneous(&self) -> Vec<Hpoint> {
        Hpoint::weighted_all(&self.points, &self.weights)
    }

    /// The same curve with control point `i` moved to `p` (weights and knots kept).
    ///
    /// # Errors
    /// [`SplineError::ControlPointIndex`], [`SplineError::NonFiniteControlPoint`].
    pub fn with_control_point(&self, i: usize, p: Point) -> Result<Self, SplineError> {
        if i >= self.points.len() {
            return Err(SplineError::ControlPointIndex {
                index: i,
                count: self.points.len(),
            });
        }
        let mut points = self.points.clone();
        points[i] = p;
        check_control_points(&points, &self.weights)?;
        Ok(Self {
            knots: self.knots.clone(),
            points,
            weights: self.weights.clone(),
        })
    }

    /// Degree `p`.
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }

    /// The knot vector.
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// Control points `P_i`.
    pub fn control_points(&self) -> &[Point] {
        &self.points
    }

    /// Weights `w_i` (all > 0).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// True if every weight equals the first (the curve is then polynomial).
    pub fn is_polynomial(&self) -> bool {
        self.weights.iter().all(|&w| w == self.weights[0])
    }

    /// Homogeneous derivatives `[A, A', A'']` at `u` (clamped to the domain).
    fn homogeneous_derivatives(&self, u: f64, nd: usize) -> [Hpoint; 3] {
        let (a, b) = self.param_range();
        let u = u.clamp(a, b);
        let p = self.degree();
        let k = self.knots.span(u);
        self.knots.with_basis_derivatives(k, u, nd, |basis| {
            let mut out = [Hpoint::default(); 3];
            for (slot, row) in out.iter_mut().zip(basis.chunks_exact(p + 1)) {
                for (j, &n) in row.iter().enumerate() {
                    let i = k - p + j;
                    *slot = *slot + Hpoint::weighted(self.points[i], self.weights[i]) * n;
                }
            }
            out
        })
    }

    fn check_in_domain(&self, u: f64) -> Result<(), SplineError> {
        let (start, end) = self.param_range();
        if u.is_finite() && u >= start && u <= end {
            Ok(())
        } else {
            Err(SplineError::ParameterOutOfDomain { u, start, end })
        }
    }

    /// Inserts `u` once (Boehm) in span `k`: `u_k <= u < u_{k+1}`, or `u_k < u = u_{k+1}` at
    /// the domain end `u = u_n` (the half-open span there would need a control point `P_n`).
    fn insert_once(knots: &mut Vec<f64>, hp: &mut Vec<Hpoint>, p: usize, u: f64) {
        let n = hp.len();
        let k = if u >= knots[n] {
            knots.iter().rposition(|&x| x < u)
        } else {
            knots.iter().rposition(|&x| x <= u)
        }
        .unwrap_or(p);
        let mut q = Vec::with_capacity(hp.len() + 1);
        for i in 0..=hp.len() {
            if i + p <= k {
                q.push(hp[i]);
            } else if i > k {
                q.push(hp[i - 1]);
            } else {
                let alpha = (u - knots[i]) / (knots[i + p] - knots[i]);
                q.push(hp[i - 1].lerp(hp[i], alpha));
            }
        }
        knots.insert(k + 1, u);
        *hp = q;
    }

    /// Inserts the knot `u` `times` times (Boehm's algorithm, in homogeneous coordinates). The
    /// curve is unchanged as a point set and as a function of `u`.
    ///
    /// # Errors
    /// [`SplineError::ParameterOutOfDomain`] if `u` is outside `[u_p, u_n]`;
    /// [`SplineError::MultiplicityExceeded`] if the multiplicity would exceed `p`.
    pub fn insert_knot(&self, u: f64, times: usize) -> Result<Self, SplineError> {
        self.check_in_domain(u)?;
        let p = self.degree();
        let current = self.knots.multiplicity(u);
        if current + times > p {
            return Err(SplineError::MultiplicityExceeded {
                value: u,
                times,
                current,
                max: p,
            });
        }
        let mut knots = self.knots.knots().to_vec();
        let mut hp = self.homogeneous();
        for _ in 0..times {
            Self::insert_once(&mut knots, &mut hp, p, u);
        }
        Ok(Self::from_homogeneous(knots, p, &hp))
    }

    /// Inserts every value of `new_knots` once (knot refinement). Values may repeat.
    ///
    /// # Errors
    /// As [`NurbsCurve::insert_knot`] for each value.
    pub fn refine(&self, new_knots: &[f64]) -> Result<Self, SplineError> {
        let mut c = self.clone();
        for &u in new_knots {
            c = c.insert_knot(u, 1)?;
        }
        Ok(c)
    }

    /// Clamps the start: afterwards `u_0 = ... = u_p` and `C(u_p) = P_0`.
    fn clamp_start(&self) -> Self {
        let p = self.degree();
        let a = self.param_range().0;
        let mut knots = self.knots.knots().to_vec();
        let mut hp = self.homogeneous();
        while knots.iter().filter(|&&k| k == a).count() < p {
            Self::insert_once(&mut knots, &mut hp, p, a);
        }
        let j = knots.iter().position(|&k| k == a).unwrap_or(0);
        let mult = knots.iter().filter(|&&k| k == a).count();
        // Keep exactly p + 1 copies of a in front; drop what precedes them.
        let start = (j + mult).saturating_sub(p + 1);
        let mut new_knots = knots[start..].to_vec();
        new_knots[0] = a;
        Self::from_homogeneous(new_knots, p, &hp[start..])
    }

    /// Clamps the end: afterwards `u_n = ... = u_{n+p}` and `C(u_n) = P_{n-1}`.
    fn clamp_end(&self) -> Self {
        let p = self.degree();
        let b = self.param_range().1;
        let mut knots = self.knots.knots().to_vec();
        let mut hp = self.homogeneous();
        while knots.iter().filter(|&&k| k == b).count() < p {
            Self::insert_once(&mut knots, &mut hp, p, b);
        }
        let j = knots.iter().position(|&k| k == b).unwrap_or(0);
        // Keep exactly p + 1 copies of b at the end; drop what follows them.
        let mut new_knots = knots[..j + p + 1].to_vec();
        new_knots[j + p] = b;
        Self::from_homogeneous(new_knots, p, &hp[..j])
    }

    /// The same curve with clamped end knots (multiplicity `p + 1`), so that `P_0` and
    /// `P_{n-1}` are the end points. Unclamped curves are converted by knot insertion; knot
    /// values are kept exactly.
    pub fn clamped(&self) -> Self {
        self.clamp_start().clamp_end()
    }

    /// Bezier extraction: the rational Bezier pieces of the curve, one per non-empty knot span,
    /// in order, each on `[0, 1]` and carrying its original parameter range.
    ///
    /// Each span is extracted on its own: its `p + 1` control points and `2p` neighbouring
    /// knots form a one-span curve that is clamped at both ends by Boehm insertion, so the work
    /// is `O(p^2)` per span and linear in the number of spans (in buffers reused from span to
    /// span).
    pub fn to_bezier(&self) -> Vec<RationalBezier> {
        let p = self.degree();
        let knots = self.knots.knots();
        let n = self.points.len();
        let mut pieces: Vec<RationalBezier> = Vec::with_capacity(n - p);
        let mut extraction = SpanExtraction::default();
        for k in (p..n).filter(|&k| knots[k] < knots[k + 1]) {
            let mut piece = extraction.piece(p, k, knots, &self.points, &self.weights);
            // Where the curve is continuous (multiplicity <= p) both pieces have C(u_k) as an
            // end; share it bit for bit instead of two roundings of the same point.
            if let Some(prev) = pieces.last()
                && knots[k - p..=k].iter().filter(|&&x| x == knots[k]).count() <= p
            {
                piece.set_start(prev.end_point(), prev.weights()[p]);
            }
            pieces.push(piece);
        }
        pieces
    }

    /// The breaks of the curve: every interior knot of multiplicity `p + 1`, with the distance
    /// between the end of the Bezier piece before it and the start of the piece after it (zero
    /// where the pieces meet; a gap otherwise). Ascending in the parameter.
    pub fn breaks(&self) -> Vec<(f64, f64)> {
        let p = self.degree();
        // An interior knot has index >= p + 1, so `i - 1` is a control point index.
        self.knots
            .interior_runs()
            .filter(|&(_, _, mult)| mult > p)
            .map(|(i, u, _)| (u, self.points[i - 1].distance(self.points[i])))
            .collect()
    }
}

impl ParamCurve for NurbsCurve {
    /// The knot domain `[u_p, u_n]`.
    fn param_range(&self) -> (f64, f64) {
        self.knots.domain()
    }

    /// `C(u)`; `u` is clamped into the domain.
    fn point_at(&self, u: f64) -> Point {
        self.homogeneous_derivatives(u, 0)[0].project()
    }

    fn subsegment(&self, (u0, u1): (f64, f64)) -> Result<Self, SplineError> {
        let (a, b) = self.param_range();
        if !(a <= u0 && u0 < u1 && u1 <= b) {
            return Err(SplineError::ParameterOutOfDomain {
                u: if (a..=b).contains(&u0) { u1 } else { u0 },
                start: a,
                end: b,
            });
        }
        let right = if u0 > a {
            self.split_at(u0)?.1
        } else {
            self.clone()
        };
        if u1 < b {
            Ok(right.split_at(u1)?.0)
        } else {
            Ok(right)
        }
    }

    /// Splits at `u` strictly inside the domain into the curves on `[a, u]` and `[u, b]`.
    ///
    /// # Errors
    /// [`SplineError::ParameterOutOfDomain`] unless `a < u < b`.
    fn split_at(&self, u: f64) -> Result<(Self, Self), SplineError> {
        let (a, b) = self.param_range();
        if !(u > a && u < b) {
            return Err(SplineError::ParameterOutOfDomain {
                u,
                start: a,
                end: b,
            });
        }
        let p = self.degree();
        let have = self.knots.multiplicity(u);
        if have > p {
            // A break: the pieces on either side already have their own control points.
            let knots = self.knots.knots();
            let hp = self.homogeneous();
            let j = knots.iter().position(|&k| k == u).unwrap_or(0);
            return Ok((
                Self::from_homogeneous(knots[..j + p + 1].to_vec(), p, &hp[..j]),
                Self::from_homogeneous(knots[j..].to_vec(), p, &hp[j..]),
            ));
        }
        let c = self.insert_knot(u, p - have)?;
        let knots = c.knots.knots();
        let hp = c.homogeneous();
        let j = knots.iter().position(|&k| k == u).unwrap_or(0);
        let mut left_knots = knots[..j + p].to_vec();
        left_knots.push(u);
        let mut right_knots = vec![u];
        right_knots.extend_from_slice(&knots[j..]);
        Ok((
            Self::from_homogeneous(left_knots, p, &hp[..j]),
            Self::from_homogeneous(right_knots, p, &hp[j - 1..]),
        ))
    }

    fn subdivide(&self) -> (Self, Self) {
        let (a, b) = self.param_range();
        // The midpoint of a non-empty domain is strictly inside it.
        self.split_at(0.5 * (a + b))
            .unwrap_or_else(|_| (self.clone(), self.clone()))
    }

    /// The same curve traversed backwards on the same domain: `C_rev(u) = C(a + b - u)` for the
    /// domain `[a, b]`.
    fn reversed(&self) -> Self {
        let (a, b) = self.param_range();
        let knots: Vec<f64> = self
            .knots
            .knots()
            .iter()
            .rev()
            .map(|&k| a + b - k)
            .collect();
        Self {
            knots: KnotVector::from_raw(knots, self.degree()),
            points: self.points.iter().rev().copied().collect(),
            weights: self.weights.iter().rev().copied().collect(),
        }
    }
}

impl ParamCurveDeriv for NurbsCurve {
    /// `C(u)`, `C'(u)` and `C''(u)` by the rational quotient rule; `u` is clamped into the
    /// domain. At a knot the derivatives are those of the span to its right (of the last span
    /// at the domain end).
    fn derivatives(&self, u: f64) -> CurveDerivatives {
        rational_derivatives(self.homogeneous_derivatives(u, 2))
    }

    fn point_and_tangent(&self, u: f64) -> (Point, Point) {
        let [value, first, _] = self.homogeneous_derivatives(u, 1);
        rational_point_and_tangent([value, first])
    }
}

impl ParamCurveArea for NurbsCurve {
    /// Piece by piece over the Bezier spans (see [`RationalBezier`]'s implementation).
    fn area_integral_on(&self, u0: f64, u1: f64) -> Integral {
        self.to_bezier()
            .iter()
            .filter_map(|b| {
                let (a, c) = b.knot_span();
                let (lo, hi) = (u0.max(a), u1.min(c));
                (lo < hi).then(|| b.area_integral_on((lo - a) / (c - a), (hi - a) / (c - a)))
            })
            .sum()
    }
}

impl ParamCurveArclen for NurbsCurve {
    /// The non-empty knot spans.
    fn smooth_spans(&self) -> Vec<(f64, f64)> {
        let (a, b) = self.param_range();
        let mut cuts = vec![a];
        cuts.extend(self.knots.interior_breaks());
        cuts.push(b);
        cuts.windows(2).map(|w| (w[0], w[1])).collect()
    }
}

impl ParamCurveExtrema for NurbsCurve {
    /// The extrema of every Bezier piece, mapped to `u`. A knot where a coordinate's
    /// derivative jumps across zero is not listed (it is a piece end point, which the tight
    /// box includes anyway).
    fn extrema(&self) -> Result<Vec<f64>, RootsError> {
        let mut out = Vec::new();
        for b in self.to_bezier() {
            let (a, c) = b.knot_span();
            out.extend(b.extrema()?.into_iter().map(|t| a + t * (c - a)));
        }
        Ok(out)
    }

    /// Bounding box of the control polygon (it contains the curve, since weights are > 0).
    fn control_bounding_box(&self) -> BoundingBox {
        BoundingBox::from_points(self.points.iter().copied())
            .unwrap_or(BoundingBox::from_point(Point::default()))
    }

    /// The union of the tight boxes of the Bezier pieces (each falls back to its control box
    /// on its own).
    fn bounding_box(&self) -> BoundingBox {
        self.to_bezier()
            .iter()
            .map(RationalBezier::bounding_box)
            .reduce(BoundingBox::union)
            .unwrap_or_else(|| self.control_bounding_box())
    }
}

impl Flatten for NurbsCurve {
    /// The Bezier pieces flattened in order; each piece's start (the previous piece's end)
    /// is emitted once.
    fn flatten(&self, accuracy: f64, emit: &mut dyn FnMut(Point)) {
        let pieces = self.to_bezier();
        crate::flatten_chain(pieces.iter().map(|b| b as &dyn Flatten), accuracy, emit);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_curve() -> NurbsCurve {
        NurbsCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0],
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

    /// `to_bezier` (in reused buffers) gives the pieces of the construction it replaced, bit
    /// for bit: each span's local curve through `clamped()`, the shared start copied from the
    /// piece before. Random degrees 1 to 6, weights, clamped and unclamped knot vectors with
    /// repeated interior knots.
    #[test]
    fn extraction_equals_clamping_each_span_bit_for_bit() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut checked, mut unclamped) = (0, 0);
        for case in 0..400 {
            let p = 1 + case % 6;
            let n = p + 1 + (case / 6) % 9;
            let clamped_ends = case % 3 != 0;
            let mut knots: Vec<f64> = Vec::new();
            let mut u = 0.0;
            for i in 0..n + p + 1 {
                let repeat = i > 0 && next() < 0.25;
                let at_end = clamped_ends && (i <= p || i >= n);
                if !(repeat || (at_end && i <= p && i > 0) || (at_end && i > n)) {
                    u += 0.1 + next();
                }
                knots.push(u);
            }
            let points: Vec<Point> = (0..n)
                .map(|_| Point::new(next() * 10.0 - 5.0, next() * 3.0))
                .collect();
            let weights: Vec<f64> = (0..n).map(|_| 0.2 + next() * 3.0).collect();
            let Ok(c) = NurbsCurve::new(p, knots.clone(), points.clone(), Some(weights.clone()))
            else {
                continue;
            };
            let mut want: Vec<RationalBezier> = Vec::new();
            for k in (p..n).filter(|&k| knots[k] < knots[k + 1]) {
                let mut local = NurbsCurve {
                    knots: KnotVector::from_raw(knots[k - p..=k + p + 1].to_vec(), p),
                    points: points[k - p..=k].to_vec(),
                    weights: weights[k - p..=k].to_vec(),
                }
                .clamped();
                if let Some(prev) = want.last()
                    && knots[k - p..=k].iter().filter(|&&x| x == knots[k]).count() <= p
                {
                    local.points[0] = prev.end_point();
                    local.weights[0] = prev.weights()[p];
                }
                want.push(RationalBezier::from_valid_parts(
                    local.points,
                    local.weights,
                    (knots[k], knots[k + 1]),
                ));
            }
            let got = c.to_bezier();
            assert_eq!(got.len(), want.len(), "case {case}");
            checked += 1;
            unclamped += usize::from(!clamped_ends);
            for (g, w) in got.iter().zip(&want) {
                let bits = |b: &RationalBezier| {
                    b.control_points()
                        .iter()
                        .flat_map(|q| [q.x.to_bits(), q.y.to_bits()])
                        .chain(b.weights().iter().map(|w| w.to_bits()))
                        .collect::<Vec<_>>()
                };
                assert_eq!(bits(g), bits(w), "case {case}");
                assert_eq!(g.knot_span(), w.knot_span(), "case {case}");
            }
        }
        assert!(checked >= 300 && unclamped >= 100, "{checked} {unclamped}");
    }

    #[test]
    fn clamped_curve_interpolates_end_points() {
        let c = sample_curve();
        assert!(c.start_point().distance(Point::new(0.0, 0.0)) < 1e-15);
        assert!(c.end_point().distance(Point::new(6.0, 1.0)) < 1e-15);
    }

    #[test]
    fn rejects_bad_weights_and_points() {
        let pts = vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0)];
        assert!(matches!(
            NurbsCurve::bezier(pts.clone(), Some(vec![1.0, 0.0])),
            Err(SplineError::NonPositiveWeight { index: 1, .. })
        ));
        assert!(matches!(
            NurbsCurve::bezier(pts.clone(), Some(vec![1.0])),
            Err(SplineError::WeightCountMismatch { .. })
        ));
        assert!(matches!(
            NurbsCurve::bezier(vec![Point::new(f64::NAN, 0.0), Point::new(1.0, 0.0)], None),
            Err(SplineError::NonFiniteControlPoint { index: 0, .. })
        ));
    }

    #[test]
    fn insertion_limits() {
        let c = sample_curve();
        assert!(matches!(
            c.insert_knot(0.5, 2),
            Err(SplineError::MultiplicityExceeded { current: 2, .. })
        ));
        assert!(matches!(
            c.insert_knot(1.5, 1),
            Err(SplineError::ParameterOutOfDomain { .. })
        ));
        assert!(c.split_at(0.0).is_err());
    }

    #[test]
    fn breaks_split_into_independent_pieces() {
        // A degree-2 polygon with multiplicity-3 breaks, the way the inRS Matlab package
        // writes polygons.
        let pts = [
            (0.0, 0.0),
            (1.0, 0.0),
            (2.0, 0.0),
            (2.0, 0.0),
            (2.0, 1.0),
            (2.0, 2.0),
        ];
        let c = NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0],
            pts.iter().map(|&(x, y)| Point::new(x, y)).collect(),
            None,
        )
        .unwrap();
        let pieces = c.to_bezier();
        assert_eq!(pieces.len(), 2);
        assert_eq!(pieces[0].end_point(), Point::new(2.0, 0.0));
        assert_eq!(pieces[1].start_point(), Point::new(2.0, 0.0));
        assert_eq!(c.breaks(), vec![(0.5, 0.0)]);
        assert_eq!(c.point_at(0.75), Point::new(2.0, 1.0));
        let (l, r) = c.split_at(0.5).unwrap();
        assert_eq!(l.end_point(), Point::new(2.0, 0.0));
        assert_eq!(r.start_point(), Point::new(2.0, 0.0));
        assert_eq!(r.point_at(0.75), Point::new(2.0, 1.0));
        // A gap: the second piece starts elsewhere.
        let mut moved = pts.to_vec();
        moved[3] = (2.0, 0.5);
        let g = NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0],
            moved.iter().map(|&(x, y)| Point::new(x, y)).collect(),
            None,
        )
        .unwrap();
        assert_eq!(g.breaks(), vec![(0.5, 0.5)]);
    }

    #[test]
    fn extraction_is_linear_in_the_spans() {
        // 10^5 control points: the old global insertion was quadratic (minutes); this must
        // take well under a second even unoptimised.
        let n = 100_000;
        let pts: Vec<Point> = (0..n)
            .map(|i| Point::new(i as f64, ((i * 7919) % 13) as f64))
            .collect();
        let c = NurbsCurve::new(
            3,
            KnotVector::uniform_clamped(3, n).unwrap().knots().to_vec(),
            pts,
            None,
        )
        .unwrap();
        let pieces = c.to_bezier();
        assert_eq!(pieces.len(), n - 3);
        for (i, b) in pieces.iter().enumerate().step_by(997) {
            let (u0, u1) = b.knot_span();
            let u = 0.5 * (u0 + u1);
            assert!(b.point_at(0.5).distance(c.point_at(u)) < 1e-9, "span {i}");
        }
    }

    #[test]
    fn huge_and_tiny_weights_are_rescaled_exactly() {
        let pts = vec![
            Point::new(0.0, 0.0),
            Point::new(0.5, -1.0),
            Point::new(1.0, 0.0),
        ];
        let plain = NurbsCurve::bezier(pts.clone(), Some(vec![1.0, 2.0, 1.0])).unwrap();
        for s in [1e50, 1e-300, 1e300] {
            let c = NurbsCurve::bezier(pts.clone(), Some(vec![s, 2.0 * s, s])).unwrap();
            let w = c.weights();
            assert!(
                w.iter()
                    .all(|&x| (2f64.powi(-33)..=2f64.powi(32)).contains(&x))
            );
            assert_eq!(w[1] / w[0], 2.0);
            for i in 0..=8 {
                let t = i as f64 / 8.0;
                assert!(c.point_at(t).distance(plain.point_at(t)) < 1e-15);
            }
        }
        assert!(matches!(
            NurbsCurve::bezier(pts, Some(vec![1e20, 1e35, 1e50])),
            Err(SplineError::LimitExceeded { .. })
        ));
    }

    #[test]
    fn bezier_pieces_follow_the_spans() {
        let pieces = sample_curve().to_bezier();
        let ranges: Vec<(f64, f64)> = pieces.iter().map(|b| b.knot_span()).collect();
        assert_eq!(ranges, vec![(0.0, 0.3), (0.3, 0.5), (0.5, 1.0)]);
        assert!(pieces.iter().all(|b| b.degree() == 3));
    }
}
