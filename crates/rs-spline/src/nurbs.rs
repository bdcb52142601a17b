//! Planar NURBS curves.

use rs_roots::RootsError;

use crate::bezier_extraction::SpanExtraction;
use crate::curve::prelude::*;
use crate::error::{check_control_points, normalized_weights};
use crate::insertion::{SplineParts, SplineRef};
use crate::kernel::{rational_quotient, rational_sums};
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

    /// The curve's data for the knot algorithms of [`crate::insertion`], which planar and
    /// space curves share.
    fn parts(&self) -> SplineRef<'_, Point> {
        SplineRef {
            knots: &self.knots,
            points: &self.points,
            weights: &self.weights,
        }
    }

    /// The curve of data the knot algorithms made from a valid curve (knots, points and weights
    /// valid by construction).
    fn from_spline_parts(c: SplineParts<Point>) -> Self {
        Self {
            knots: c.knots,
            points: c.points,
            weights: c.weights,
        }
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
        crate::weights_are_equal(&self.weights)
    }

    /// Inserts the knot `u` `times` times (Boehm's algorithm, in homogeneous coordinates). The
    /// curve is unchanged as a point set and as a function of `u`.
    ///
    /// # Errors
    /// [`SplineError::ParameterOutOfDomain`] if `u` is outside `[u_p, u_n]`;
    /// [`SplineError::MultiplicityExceeded`] if the multiplicity would exceed `p`.
    pub fn insert_knot(&self, u: f64, times: usize) -> Result<Self, SplineError> {
        self.parts()
            .insert_knot(u, times)
            .map(Self::from_spline_parts)
    }

    /// Inserts every value of `new_knots` once (knot refinement). Values may repeat.
    ///
    /// # Errors
    /// As [`NurbsCurve::insert_knot`] for each value.
    pub fn refine(&self, new_knots: &[f64]) -> Result<Self, SplineError> {
        self.parts().refine(new_knots).map(Self::from_spline_parts)
    }

    /// The same curve with clamped end knots (multiplicity `p + 1`), so that `P_0` and
    /// `P_{n-1}` are the end points. Unclamped curves are converted by knot insertion; knot
    /// values are kept exactly.
    pub fn clamped(&self) -> Self {
        Self::from_spline_parts(self.parts().clamped())
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
        let [(a, w), ..] = rational_sums(&self.knots, &self.points, Some(&self.weights), u, 0);
        a / w
    }

    fn subsegment(&self, range: (f64, f64)) -> Result<Self, SplineError> {
        self.parts().subsegment(range).map(Self::from_spline_parts)
    }

    /// Splits at `u` strictly inside the domain into the curves on `[a, u]` and `[u, b]`.
    ///
    /// # Errors
    /// [`SplineError::ParameterOutOfDomain`] unless `a < u < b`.
    fn split_at(&self, u: f64) -> Result<(Self, Self), SplineError> {
        let (left, right) = self.parts().split_at(u)?;
        Ok((
            Self::from_spline_parts(left),
            Self::from_spline_parts(right),
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
        Self::from_spline_parts(self.parts().reversed())
    }
}

impl ParamCurveDeriv for NurbsCurve {
    /// `C(u)`, `C'(u)` and `C''(u)` by the rational quotient rule; `u` is clamped into the
    /// domain. At a knot the derivatives are those of the span to its right (of the last span
    /// at the domain end).
    fn derivatives(&self, u: f64) -> CurveDerivatives {
        let [point, first, second] = rational_quotient(rational_sums(
            &self.knots,
            &self.points,
            Some(&self.weights),
            u,
            2,
        ));
        CurveDerivatives {
            point,
            first,
            second,
        }
    }

    /// The quotient rule's first two terms from the kernel's sums of order `<= 1`.
    fn point_and_tangent(&self, u: f64) -> (Point, Point) {
        let [(a, w), (a1, w1), _] =
            rational_sums(&self.knots, &self.points, Some(&self.weights), u, 1);
        let point = a / w;
        (point, (a1 - point * w1) / w)
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

    /// Random curves of degrees 1 to 6 (clamped and unclamped knots, repeated interior knots,
    /// breaks), from a fixed seed.
    fn random_curves(cases: usize) -> Vec<NurbsCurve> {
        let mut rng = rs_testkit::XorShift64::new(0x5eed_cafe);
        let mut out = Vec::new();
        for case in 0..cases {
            let p = 1 + case % 6;
            let n = p + 1 + (case / 6) % 9;
            let clamped_ends = case % 3 != 0;
            let mut knots: Vec<f64> = Vec::new();
            let mut u = rng.uniform(-2.0, 1.0);
            for i in 0..n + p + 1 {
                let repeat = i > 0 && rng.next_f64() < 0.25;
                let at_end = clamped_ends && (i <= p || i >= n);
                if !(repeat || (at_end && i <= p && i > 0) || (at_end && i > n)) {
                    u += 0.1 + rng.next_f64();
                }
                knots.push(u);
            }
            let points: Vec<Point> = (0..n)
                .map(|_| Point::new(rng.uniform(-5.0, 5.0), rng.uniform(0.0, 3.0)))
                .collect();
            let weights: Vec<f64> = (0..n).map(|_| rng.uniform(0.2, 3.2)).collect();
            if let Ok(c) = NurbsCurve::new(p, knots, points, Some(weights)) {
                out.push(c);
            }
        }
        out
    }

    /// Parameters to test a curve at: every knot in the domain, the spans' midpoints and a few
    /// uneven points.
    fn test_parameters(c: &NurbsCurve) -> Vec<f64> {
        let (a, b) = c.param_range();
        let mut us: Vec<f64> = c
            .knots()
            .knots()
            .iter()
            .copied()
            .filter(|u| (a..=b).contains(u))
            .collect();
        us.extend((1..8).map(|i| a + (b - a) * (f64::from(i) / 8.0).powf(1.3)));
        us
    }

    /// The evaluation through the kernel `rational_sums` is the NURBS Book's formula, written
    /// out here on its own, bit for bit: `A^(d) = sum_j N_j^(d) (w_j P_j)`, `w^(d) = sum_j
    /// N_j^(d) w_j` summed in the order of the basis functions (algorithm A4.2), then the
    /// quotient rule `C = A / w`, `C' = (A' - w' C) / w`, `C'' = (A'' - 2 w' C' - w'' C) / w`.
    #[test]
    fn evaluation_is_the_nurbs_book_formula_bit_for_bit() {
        let curves = random_curves(300);
        assert!(curves.len() > 250);
        let mut checked = 0;
        for c in &curves {
            let p = c.degree();
            for u in test_parameters(c) {
                let k = c.knots().span(u);
                let n = c.knots().basis_derivatives(k, u, 2);
                let (mut ax, mut ay, mut w) = ([0.0; 3], [0.0; 3], [0.0; 3]);
                for d in 0..3 {
                    for (j, &nj) in n[d].iter().enumerate() {
                        let i = k - p + j;
                        let (q, wi) = (c.control_points()[i], c.weights()[i]);
                        ax[d] += (wi * q.x) * nj;
                        ay[d] += (wi * q.y) * nj;
                        w[d] += wi * nj;
                    }
                }
                let point = Point::new(ax[0] / w[0], ay[0] / w[0]);
                let first = Point::new(
                    (ax[1] - point.x * w[1]) / w[0],
                    (ay[1] - point.y * w[1]) / w[0],
                );
                let second = Point::new(
                    (ax[2] - first.x * (2.0 * w[1]) - point.x * w[2]) / w[0],
                    (ay[2] - first.y * (2.0 * w[1]) - point.y * w[2]) / w[0],
                );
                let bits = |q: Point| (q.x.to_bits(), q.y.to_bits());
                let d = c.derivatives(u);
                assert_eq!(bits(d.point), bits(point), "{u}");
                assert_eq!(bits(d.first), bits(first), "{u}");
                assert_eq!(bits(d.second), bits(second), "{u}");
                assert_eq!(bits(c.point_at(u)), bits(point));
                let (q, t) = c.point_and_tangent(u);
                assert_eq!((bits(q), bits(t)), (bits(point), bits(first)));
                checked += 1;
            }
        }
        assert!(checked > 3000, "{checked}");
    }

    /// Homogeneous control points `[w x, w y, w]`, as the reference algorithms below use them.
    type H = [f64; 3];

    fn reference_homogeneous(c: &NurbsCurve) -> Vec<H> {
        c.control_points()
            .iter()
            .zip(c.weights())
            .map(|(q, &w)| [w * q.x, w * q.y, w])
            .collect()
    }

    fn reference_curve(knots: Vec<f64>, p: usize, hp: &[H]) -> NurbsCurve {
        NurbsCurve {
            knots: KnotVector::from_raw(knots, p),
            points: hp
                .iter()
                .map(|h| Point::new(h[0] / h[2], h[1] / h[2]))
                .collect(),
            weights: hp.iter().map(|h| h[2]).collect(),
        }
    }

    /// Boehm's insertion written out (The NURBS Book, A5.1 with r = 1) into a new vector of
    /// points: `Q_i = (1 - a_i) P_{i-1} + a_i P_i` for `k - p < i <= k`.
    fn reference_insert(knots: &mut Vec<f64>, hp: &mut Vec<H>, p: usize, u: f64) {
        let n = hp.len();
        let k = if u >= knots[n] {
            knots.iter().rposition(|&x| x < u)
        } else {
            knots.iter().rposition(|&x| x <= u)
        }
        .unwrap();
        let mut q = Vec::with_capacity(n + 1);
        for i in 0..=n {
            q.push(if i + p <= k {
                hp[i]
            } else if i > k {
                hp[i - 1]
            } else {
                let a = (u - knots[i]) / (knots[i + p] - knots[i]);
                let (l, r) = (hp[i - 1], hp[i]);
                [
                    l[0] * (1.0 - a) + r[0] * a,
                    l[1] * (1.0 - a) + r[1] * a,
                    l[2] * (1.0 - a) + r[2] * a,
                ]
            });
        }
        knots.insert(k + 1, u);
        *hp = q;
    }

    fn reference_insert_knot(c: &NurbsCurve, u: f64, times: usize) -> NurbsCurve {
        let mut knots = c.knots().knots().to_vec();
        let mut hp = reference_homogeneous(c);
        for _ in 0..times {
            reference_insert(&mut knots, &mut hp, c.degree(), u);
        }
        reference_curve(knots, c.degree(), &hp)
    }

    /// Splitting written out: insert `u` up to multiplicity `p` (from the projected curve), cut
    /// the knots at its first copy, the left curve ending and the right one starting with the
    /// point there.
    fn reference_split(c: &NurbsCurve, u: f64) -> (NurbsCurve, NurbsCurve) {
        let p = c.degree();
        let have = c.knots().multiplicity(u);
        let c = if have > p {
            c.clone()
        } else {
            reference_insert_knot(c, u, p - have)
        };
        let knots = c.knots().knots();
        let hp = reference_homogeneous(&c);
        let j = knots.iter().position(|&k| k == u).unwrap();
        if have > p {
            return (
                reference_curve(knots[..j + p + 1].to_vec(), p, &hp[..j]),
                reference_curve(knots[j..].to_vec(), p, &hp[j..]),
            );
        }
        let mut left = knots[..j + p].to_vec();
        left.push(u);
        let mut right = vec![u];
        right.extend_from_slice(&knots[j..]);
        (
            reference_curve(left, p, &hp[..j]),
            reference_curve(right, p, &hp[j - 1..]),
        )
    }

    /// Clamping written out: insert the domain's start `a` up to multiplicity `p` and drop the
    /// knots and points before its first `p + 1` copies; project; then the same at the end.
    fn reference_clamped(c: &NurbsCurve) -> NurbsCurve {
        let p = c.degree();
        let count = |k: &[f64], u: f64| k.iter().filter(|&&x| x == u).count();
        let a = c.param_range().0;
        let mut knots = c.knots().knots().to_vec();
        let mut hp = reference_homogeneous(c);
        while count(&knots, a) < p {
            reference_insert(&mut knots, &mut hp, p, a);
        }
        let j = knots.iter().position(|&k| k == a).unwrap();
        let start = (j + count(&knots, a)).saturating_sub(p + 1);
        let mut front = knots[start..].to_vec();
        front[0] = a;
        let c = reference_curve(front, p, &hp[start..]);
        let b = c.param_range().1;
        let mut knots = c.knots().knots().to_vec();
        let mut hp = reference_homogeneous(&c);
        while count(&knots, b) < p {
            reference_insert(&mut knots, &mut hp, p, b);
        }
        let j = knots.iter().position(|&k| k == b).unwrap();
        let mut back = knots[..j + p + 1].to_vec();
        back[j + p] = b;
        reference_curve(back, p, &hp[..j])
    }

    fn curve_bits(c: &NurbsCurve) -> Vec<u64> {
        c.knots()
            .knots()
            .iter()
            .map(|k| k.to_bits())
            .chain(
                c.control_points()
                    .iter()
                    .flat_map(|q| [q.x.to_bits(), q.y.to_bits()]),
            )
            .chain(c.weights().iter().map(|w| w.to_bits()))
            .collect()
    }

    /// Knot insertion, splitting and subsegments (through the code `RationalBSpline` shares)
    /// are the algorithms written out above, bit for bit, on random curves at knots (existing,
    /// repeated, breaks) and between them.
    #[test]
    fn knot_algorithms_are_boehm_written_out_bit_for_bit() {
        let curves = random_curves(300);
        let (mut inserted, mut split) = (0, 0);
        for c in &curves {
            let p = c.degree();
            let (a, b) = c.param_range();
            for u in test_parameters(c) {
                let have = c.knots().multiplicity(u);
                for times in 1..=p.saturating_sub(have) {
                    let got = c.insert_knot(u, times).unwrap();
                    assert_eq!(
                        curve_bits(&got),
                        curve_bits(&reference_insert_knot(c, u, times))
                    );
                    inserted += 1;
                }
                if u > a && u < b {
                    let (l, r) = c.split_at(u).unwrap();
                    let (rl, rr) = reference_split(c, u);
                    assert_eq!(curve_bits(&l), curve_bits(&rl), "{u}");
                    assert_eq!(curve_bits(&r), curve_bits(&rr), "{u}");
                    split += 1;
                    // A window: split at its start, then the right part at its end.
                    let u1 = u + 0.5 * (b - u);
                    if u1 < b {
                        let want = reference_split(&reference_split(c, u).1, u1).0;
                        assert_eq!(
                            curve_bits(&c.subsegment((u, u1)).unwrap()),
                            curve_bits(&want)
                        );
                    }
                }
            }
            assert_eq!(curve_bits(&c.clamped()), curve_bits(&reference_clamped(c)));
            // Refinement: each value inserted once, one after the other.
            let mut want = c.clone();
            let mut us = Vec::new();
            for u in test_parameters(c).into_iter().step_by(2) {
                if want.knots().multiplicity(u) < p {
                    want = reference_insert_knot(&want, u, 1);
                    us.push(u);
                }
            }
            assert_eq!(curve_bits(&c.refine(&us).unwrap()), curve_bits(&want));
        }
        assert!(inserted > 2000 && split > 1500, "{inserted} {split}");
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
