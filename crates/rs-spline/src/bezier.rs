//! Rational Bezier curves on `[0, 1]`.

use rs_roots::{
    Bernstein, Polynomial, RootsError, bernstein_roots, de_casteljau, de_casteljau_split,
    de_casteljau_with_derivative, no_interior_root, rational_derivative_numerator, real_roots_in,
};

use crate::curve::prelude::*;
use crate::curve::{basis_derivative_size, derivative_rounding_size, one_norm};
use crate::error::check_control_points;
use crate::homogeneous::{Hpoint, rational_derivatives, rational_point_and_tangent};
use crate::quadrature::{Integral, integrate_adaptive};
use crate::{Axis, BoundingBox, CurveDerivatives, Point, SplineError};

/// A rational Bezier curve `C(t) = sum_i B_{i,n}(t) w_i P_i / sum_i B_{i,n}(t) w_i`, `t` in
/// `[0, 1]`, with the parameter range `[u0, u1]` it came from (the knot span of a NURBS, or
/// `[0, 1]`).
///
/// Precondition (enforced by [`RationalBezier::new`]): at least two finite control points and
/// finite weights > 0, so the denominator is positive on `[0, 1]`.
///
/// # Examples
///
/// ```
/// use rs_spline::{Point, RationalBezier, prelude::*};
/// let b = RationalBezier::new(
///     vec![Point::new(0.0, 0.0), Point::new(1.0, 2.0), Point::new(2.0, 0.0)],
///     vec![1.0, 1.0, 1.0],
/// )
/// .unwrap();
/// assert_eq!(b.point_at(0.5), Point::new(1.0, 1.0));
/// let (left, right) = b.subdivide();
/// assert_eq!(left.end_point(), right.start_point());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct RationalBezier {
    points: Vec<Point>,
    weights: Vec<f64>,
    range: (f64, f64),
}

impl RationalBezier {
    /// Validates and builds a rational Bezier curve on `[0, 1]` with parameter range `[0, 1]`.
    ///
    /// # Errors
    /// [`SplineError::TooFewControlPoints`], [`SplineError::NonFiniteControlPoint`],
    /// [`SplineError::WeightCountMismatch`], [`SplineError::NonPositiveWeight`].
    pub fn new(points: Vec<Point>, weights: Vec<f64>) -> Result<Self, SplineError> {
        if points.len() < 2 {
            return Err(SplineError::TooFewControlPoints {
                degree: points.len().saturating_sub(1).max(1),
                needed: 2,
                got: points.len(),
            });
        }
        check_control_points(&points, &weights)?;
        Ok(Self {
            points,
            weights,
            range: (0.0, 1.0),
        })
    }

    /// The same curve labelled with the knot span `[u0, u1]` of the NURBS it belongs to.
    pub fn with_knot_span(mut self, u0: f64, u1: f64) -> Self {
        self.range = (u0, u1);
        self
    }

    pub(crate) fn from_valid_parts(
        points: Vec<Point>,
        weights: Vec<f64>,
        range: (f64, f64),
    ) -> Self {
        Self {
            points,
            weights,
            range,
        }
    }

    /// Replaces the first control point and its weight (the shared end of the piece before,
    /// in [`NurbsCurve::to_bezier`](crate::NurbsCurve::to_bezier)).
    pub(crate) fn set_start(&mut self, point: Point, weight: f64) {
        self.points[0] = point;
        self.weights[0] = weight;
    }

    fn from_homogeneous(hp: &[Hpoint], range: (f64, f64)) -> Self {
        Self {
            points: Hpoint::project_all(hp),
            weights: hp.iter().map(|h| h.w).collect(),
            range,
        }
    }

    fn homogeneous(&self) -> Vec<Hpoint> {
        Hpoint::weighted_all(&self.points, &self.weights)
    }

    /// Degree `n` (number of control points minus one).
    pub fn degree(&self) -> usize {
        self.points.len() - 1
    }

    /// Control points `P_0 .. P_n`.
    pub fn control_points(&self) -> &[Point] {
        &self.points
    }

    /// Weights `w_0 .. w_n` (all > 0).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Whether the piece is a polynomial curve: all its weights are equal (so they cancel).
    pub fn is_polynomial(&self) -> bool {
        crate::weights_are_equal(&self.weights)
    }

    /// The knot span `[u0, u1]` of the NURBS this piece was extracted from (`[0, 1]` for a
    /// piece built directly); local `t` corresponds to `u0 + t (u1 - u0)`.
    pub fn knot_span(&self) -> (f64, f64) {
        self.range
    }

    /// The piece as parts whose motion fills their parameter (the rules of `balance.rs`,
    /// [`crate::BALANCE_RATIO`]): its end weights balanced
    /// ([`balancing_exponent`](crate::balancing_exponent)) and, while a part
    /// [`crowds_ends`](crate::crowds_ends), the part halved and each half balanced again,
    /// at most [`MAX_BALANCE_HALVINGS`](crate::MAX_BALANCE_HALVINGS) times: the same curve, in
    /// order. `None` for a piece that is its own one part (every ordinary piece).
    pub fn balanced_parts(&self) -> Option<Vec<Self>> {
        if self.is_polynomial()
            || (crate::balancing_exponent(&self.weights) == 0 && !crate::crowds_ends(&self.weights))
        {
            return None;
        }
        let parts = crate::balanced_parts(self.clone());
        Some(parts.into_iter().map(|part| part.piece).collect())
    }

    /// Splits at local `t` in `[0, 1]` (one de Casteljau pass in homogeneous coordinates) into
    /// the pieces on `[0, t]` and `[t, 1]`, each reparametrised to `[0, 1]`, with the knot span
    /// split accordingly. Total on `[0, 1]`; [`ParamCurve::split_at`] is the checked form.
    fn split_unchecked(&self, t: f64) -> (Self, Self) {
        let h = self.homogeneous();
        let (mut left, mut right) = (h.clone(), h.clone());
        de_casteljau_split(&h, t, &mut left, &mut right);
        let (u0, u1) = self.range;
        let um = u0 + t * (u1 - u0);
        (
            Self::from_homogeneous(&left, (u0, um)),
            Self::from_homogeneous(&right, (um, u1)),
        )
    }

    /// The numerators `X(t) = sum w_i x_i B_i`, `Y(t) = sum w_i y_i B_i` and the denominator
    /// `W(t) = sum w_i B_i` as power-basis polynomials in `t`, so `C(t) = (X/W, Y/W)`.
    pub fn numerators(&self) -> (Polynomial, Polynomial, Polynomial) {
        let xs: Vec<f64> = self
            .points
            .iter()
            .zip(&self.weights)
            .map(|(p, w)| w * p.x)
            .collect();
        let ys: Vec<f64> = self
            .points
            .iter()
            .zip(&self.weights)
            .map(|(p, w)| w * p.y)
            .collect();
        (
            Bernstein::new(xs).to_power(),
            Bernstein::new(ys).to_power(),
            Bernstein::new(self.weights.clone()).to_power(),
        )
    }

    /// Numerators of the derivative, `x'(t) = (X' W - X W') / W^2` and likewise for `y`:
    /// returns `(X' W - X W', Y' W - Y W')`, polynomials of degree at most `2n - 2` whose signs
    /// are the signs of `x'(t)` and `y'(t)`.
    pub fn derivative_numerators(&self) -> (Polynomial, Polynomial) {
        let (x, y, w) = self.numerators();
        let dw = w.derivative();
        let dx = &(&x.derivative() * &w) - &(&x * &dw);
        let dy = &(&y.derivative() * &w) - &(&y * &dw);
        (dx, dy)
    }

    /// Whether `x'(t)` (for [`Axis::X`]) or `y'(t)` has no isolated root in `(0, 1)` to look
    /// for (the extrema are interior): the coordinate is constant, or its derivative keeps one
    /// sign on the open interval clear of rounding, zero at most at an end (see
    /// [`no_interior_root`]: its numerator's Bernstein coefficients,
    /// [`rational_derivative_numerator`]). False for degrees beyond 16, which are not checked.
    fn derivative_has_no_isolated_root(&self, axis: Axis) -> bool {
        const MOST: usize = 17;
        let n = self.points.len();
        if n > MOST {
            return false;
        }
        // A constant coordinate has no isolated extremum (its power-form numerator cancels to
        // zero, up to rounding): nothing to solve for.
        let first = self.points[0].coord(axis);
        if self.points.iter().all(|p| p.coord(axis) == first) {
            return true;
        }
        let mut coords = [0.0; MOST];
        for (c, p) in coords.iter_mut().zip(&self.points) {
            *c = p.coord(axis);
        }
        let mut numerator = [0.0; 2 * MOST];
        let len = (2 * (n - 1)).max(1);
        rational_derivative_numerator(&coords[..n], &self.weights, &mut numerator[..len]);
        no_interior_root(&numerator[..len])
    }

    /// The local parameter `t` in `[0, 1]` of a point of the piece nearest to `p`, and its
    /// distance from `p`: the best of the two end points and every stationary point of the
    /// squared distance, the roots in `[0, 1]` of
    /// `(X - p_x W)(X' W - X W') + (Y - p_y W)(Y' W - Y W')` (`|C - p|^2`'s derivative times
    /// `W^3 / 2`, degree `3n - 1`), found by the certified Bernstein isolation
    /// [`bernstein_roots`]. The whole piece is searched, so the answer is the global minimum
    /// whatever the parametrisation's speed (up to the root finder's full precision); ties
    /// keep the smaller `t`. Coordinates are taken relative to `p` and scaled by the largest
    /// offset of a control point, and weights by the largest weight, so the product cannot
    /// overflow. A piece whose points are all equally far from `p` (an arc about `p`) answers
    /// `t = 0`.
    pub fn nearest_to(&self, p: Point) -> (f64, f64) {
        let at = |t: f64| (t, self.point_at(t).distance(p));
        let offset = self
            .points
            .iter()
            .map(|q| (q.x - p.x).abs().max((q.y - p.y).abs()))
            .fold(0.0, f64::max);
        let heaviest = self.weights.iter().copied().fold(0.0, f64::max);
        let (mut best, end) = (at(0.0), at(1.0));
        if end.1 < best.1 {
            best = end;
        }
        if !(offset > 0.0 && offset.is_finite() && heaviest > 0.0 && heaviest.is_finite()) {
            // Every control point is p: the piece is the point p.
            return best;
        }
        let w: Vec<f64> = self.weights.iter().map(|w| w / heaviest).collect();
        let wb = Bernstein::new(w.clone());
        let dw = wb.derivative();
        let term = |coord: fn(Point) -> f64| {
            let a = Bernstein::new(
                self.points
                    .iter()
                    .zip(&w)
                    .map(|(&q, &wi)| wi * (coord(q) - coord(p)) / offset)
                    .collect::<Vec<_>>(),
            );
            let tangent = a.derivative().mul(&wb).add(&a.mul(&dw).scale(-1.0));
            a.mul(&tangent)
        };
        let slope = term(|q| q.x).add(&term(|q| q.y));
        // `ZeroPolynomial`: the distance is constant, so an end point is a nearest point;
        // the coefficients are finite by the scaling, so no other error arises.
        for t in bernstein_roots(&slope).unwrap_or_default() {
            let c = at(t.clamp(0.0, 1.0));
            if c.1 < best.1 {
                best = c;
            }
        }
        best
    }
}

impl ParamCurve for RationalBezier {
    /// Always `[0, 1]` (the knot span it came from is [`RationalBezier::knot_span`]).
    fn param_range(&self) -> (f64, f64) {
        (0.0, 1.0)
    }

    /// `C(t)` by de Casteljau's algorithm in homogeneous coordinates (stable, any `t`).
    fn point_at(&self, t: f64) -> Point {
        de_casteljau(&self.homogeneous(), t).project()
    }

    /// `C(0) = P_0`, exactly.
    fn start_point(&self) -> Point {
        self.points[0]
    }

    /// `C(1) = P_n`, exactly.
    fn end_point(&self) -> Point {
        self.points[self.points.len() - 1]
    }

    fn subsegment(&self, (t0, t1): (f64, f64)) -> Result<Self, SplineError> {
        if !(0.0 <= t0 && t0 < t1 && t1 <= 1.0) {
            return Err(SplineError::ParameterOutOfDomain {
                u: if (0.0..=1.0).contains(&t0) { t1 } else { t0 },
                start: 0.0,
                end: 1.0,
            });
        }
        let right = if t0 > 0.0 {
            self.split_unchecked(t0).1
        } else {
            self.clone()
        };
        Ok(if t1 < 1.0 {
            right.split_unchecked((t1 - t0) / (1.0 - t0)).0
        } else {
            right
        })
    }

    fn split_at(&self, t: f64) -> Result<(Self, Self), SplineError> {
        if t > 0.0 && t < 1.0 {
            Ok(self.split_unchecked(t))
        } else {
            Err(SplineError::ParameterOutOfDomain {
                u: t,
                start: 0.0,
                end: 1.0,
            })
        }
    }

    fn subdivide(&self) -> (Self, Self) {
        self.split_unchecked(0.5)
    }

    /// Control points and weights in reverse order; the knot span is kept.
    fn reversed(&self) -> Self {
        Self {
            points: self.points.iter().rev().copied().collect(),
            weights: self.weights.iter().rev().copied().collect(),
            range: self.range,
        }
    }
}

impl ParamCurveDeriv for RationalBezier {
    /// Derivatives with respect to the local `t` (multiply by `1 / (u1 - u0)` and its square
    /// for derivatives with respect to the knot-span parameter).
    fn derivatives(&self, t: f64) -> CurveDerivatives {
        let h = self.homogeneous();
        let n = h.len() - 1;
        let (value, first) = de_casteljau_with_derivative(&h, t);
        // Second differences of the control polygon, scaled: the Bernstein form of C''.
        let d1: Vec<Hpoint> = h.windows(2).map(|w| (w[1] - w[0]) * n as f64).collect();
        let d2: Vec<Hpoint> = d1
            .windows(2)
            .map(|w| (w[1] - w[0]) * (n as f64 - 1.0))
            .collect();
        rational_derivatives([value, first, de_casteljau(&d2, t)])
    }

    fn point_and_tangent(&self, t: f64) -> (Point, Point) {
        let (value, first) = de_casteljau_with_derivative(&self.homogeneous(), t);
        rational_point_and_tangent([value, first])
    }
}

impl ParamCurveArea for RationalBezier {
    /// Over a strongly weighted piece, the sum over its balanced parts
    /// ([`RationalBezier::balanced_parts`]), whose motion the adaptive rule follows.
    fn area_integral(&self) -> Integral {
        match self.balanced_parts() {
            None => self.area_integral_on(0.0, 1.0),
            Some(parts) => parts.iter().map(|p| p.area_integral_on(0.0, 1.0)).sum(),
        }
    }

    fn area_integral_on(&self, t0: f64, t1: f64) -> Integral {
        let scale = self.control_bounding_box().diagonal().powi(2);
        // The rounding magnitude of `x y' - y x'`: `|C|` times that of `C'` (a small piece far
        // from the origin has a derivative rounded far above `eps |C'|`, so a floor of
        // `eps (|x y'| + |y x'|)` alone lies below the integrand's own rounding and no panel
        // could meet it).
        let per_parameter = basis_derivative_size(self.degree(), 0.0, 1.0);
        let f = |t: f64| {
            let (p, v) = self.point_and_tangent(t);
            let (a, b) = (p.x * v.y, p.y * v.x);
            let terms = one_norm(p) * derivative_rounding_size(p, v, per_parameter);
            (0.5 * (a - b), 0.5 * terms)
        };
        integrate_adaptive(f, t0, t1, 1e-15 * scale.max(f64::MIN_POSITIVE))
    }
}

impl ParamCurveArclen for RationalBezier {
    fn smooth_spans(&self) -> Vec<(f64, f64)> {
        vec![(0.0, 1.0)]
    }
}

impl ParamCurveExtrema for RationalBezier {
    /// Roots in `(0, 1)` of the derivative numerators (see
    /// [`RationalBezier::derivative_numerators`]); a constant coordinate has none.
    fn extrema(&self) -> Result<Vec<f64>, RootsError> {
        // Most pieces are monotone in one coordinate or both: a derivative numerator whose
        // Bernstein coefficients are clearly one-signed has no root in [0, 1], so the solve
        // below would find none either, and is skipped (all of it when both are).
        let solve = [Axis::X, Axis::Y].map(|axis| !self.derivative_has_no_isolated_root(axis));
        let mut out = Vec::new();
        if solve == [false, false] {
            return Ok(out);
        }
        let (dx, dy) = self.derivative_numerators();
        for (d, _) in [dx, dy].into_iter().zip(solve).filter(|(_, s)| *s) {
            match real_roots_in(&d, 0.0, 1.0) {
                Ok(roots) => out.extend(roots.into_iter().filter(|&t| t > 0.0 && t < 1.0)),
                // The zero polynomial (constant coordinate) has no isolated extremes.
                Err(RootsError::ZeroPolynomial) => {}
                Err(e) => return Err(e),
            }
        }
        out.sort_by(f64::total_cmp);
        out.dedup();
        Ok(out)
    }

    fn control_bounding_box(&self) -> BoundingBox {
        BoundingBox::from_points(self.points.iter().copied())
            .unwrap_or(BoundingBox::from_point(self.points[0]))
    }
}

impl Flatten for RationalBezier {
    fn flatten(&self, accuracy: f64, emit: &mut dyn FnMut(Point)) {
        emit(self.start_point());
        let floor = FLATTEN_RELATIVE_FLOOR * self.control_bounding_box().diagonal();
        let tol = if accuracy > floor { accuracy } else { floor };
        flatten_into(self, tol, 0, emit);
    }
}

/// The smallest flattening tolerance, relative to a piece's control-box diagonal.
const FLATTEN_RELATIVE_FLOOR: f64 = 1e-13;

/// Halving depth cap of [`Flatten::flatten`] (2^-40 of a piece's parameter range).
const MAX_FLATTEN_DEPTH: u32 = 40;

/// Emits the end points of the parts of `b` whose control points lie within `tol` of their
/// chords, left to right.
fn flatten_into(b: &RationalBezier, tol: f64, depth: u32, emit: &mut dyn FnMut(Point)) {
    let p = b.control_points();
    let (a, e) = (p[0], p[p.len() - 1]);
    let chord = e - a;
    let len = chord.length();
    let flat = p.iter().all(|&q| {
        let d = if len > 0.0 {
            chord.cross(q - a).abs() / len
        } else {
            q.distance(a)
        };
        d <= tol
    });
    if flat || depth >= MAX_FLATTEN_DEPTH {
        emit(e);
    } else {
        let (l, r) = b.subdivide();
        flatten_into(&l, tol, depth + 1, emit);
        flatten_into(&r, tol, depth + 1, emit);
    }
}

impl crate::Balance for RationalBezier {
    fn balance_weights(&self) -> &[f64] {
        &self.weights
    }

    /// Weights `w_i 2^(k i)`, the control points unchanged (itself when a scaled weight would
    /// leave the normal range).
    fn reweighted(mut self, k: i32) -> (Self, f64) {
        let c = crate::scale_by_powers_of_two(k, &mut [&mut self.weights]);
        (self, c.unwrap_or(1.0))
    }

    fn halves(&self) -> (Self, Self) {
        self.split_unchecked(0.5)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A butterfly's 5-unit cubic at (13 246, 7 462): its derivative is rounded at about 1e-12,
    /// which `x y'` carries to 1e-8, far above `eps (|x y'| + |y x'|)`; with that as the
    /// rounding floor no panel would converge. The integral converges to the same curve's at
    /// the origin moved back by Green's theorem:
    /// `A = A_0 + (x_0 (y(t_1) - y(t_0)) - y_0 (x(t_1) - x(t_0))) / 2`.
    #[test]
    fn a_small_piece_far_from_the_origin_converges_to_the_moved_area() {
        let offset = Point::new(13245.794, 7462.1385);
        let local = [(0.0, 0.0), (2.0, 0.0), (3.0, 3.0), (3.0, 6.0)].map(|(x, y)| Point::new(x, y));
        let far: Vec<Point> = local.iter().map(|&p| p + offset).collect();
        let (near, far) = (
            RationalBezier::new(local.to_vec(), vec![1.0; 4]).unwrap(),
            RationalBezier::new(far, vec![1.0; 4]).unwrap(),
        );
        for (t0, t1) in [(0.0, 1.0), (0.75, 1.0), (0.1, 0.35)] {
            let got = far.area_integral_on(t0, t1);
            assert!(got.converged, "{got:?}");
            let at_origin = near.area_integral_on(t0, t1);
            assert!(at_origin.converged);
            let d = near.point_at(t1) - near.point_at(t0);
            let moved = at_origin.value + 0.5 * (offset.x * d.y - offset.y * d.x);
            // The control points at 1.3e4 are themselves rounded to 2e-12.
            assert!((got.value - moved).abs() < 1e-7, "{} vs {moved}", got.value);
        }
    }

    fn quarter_circle() -> RationalBezier {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        RationalBezier::new(
            vec![
                Point::new(1.0, 0.0),
                Point::new(1.0, 1.0),
                Point::new(0.0, 1.0),
            ],
            vec![1.0, w, 1.0],
        )
        .unwrap()
    }

    #[test]
    fn evaluation_matches_numerators() {
        let b = quarter_circle();
        let (x, y, w) = b.numerators();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let p = b.point_at(t);
            assert!((p.x - x.eval(t) / w.eval(t)).abs() < 1e-15);
            assert!((p.y - y.eval(t) / w.eval(t)).abs() < 1e-15);
            assert!((p.length() - 1.0).abs() < 1e-15);
        }
    }

    #[test]
    fn subdivision_preserves_the_curve() {
        let b = quarter_circle().with_knot_span(2.0, 4.0);
        let (l, r) = b.split_at(0.3).unwrap();
        assert_eq!(l.knot_span(), (2.0, 2.6));
        assert_eq!(r.knot_span(), (2.6, 4.0));
        for i in 0..=10 {
            let s = i as f64 / 10.0;
            assert!(l.point_at(s).distance(b.point_at(0.3 * s)) < 1e-15);
            assert!(r.point_at(s).distance(b.point_at(0.3 + 0.7 * s)) < 1e-15);
        }
        let mid = b.subsegment((0.2, 0.7)).unwrap();
        assert!(mid.start_point().distance(b.point_at(0.2)) < 1e-15);
        assert!(mid.end_point().distance(b.point_at(0.7)) < 1e-15);
    }

    #[test]
    fn tight_box_is_inside_control_box() {
        let b = RationalBezier::new(
            vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 2.0),
                Point::new(2.0, 0.0),
            ],
            vec![1.0, 1.0, 1.0],
        )
        .unwrap();
        let tight = b.bounding_box();
        assert!((tight.max.y - 1.0).abs() < 1e-15);
        assert_eq!(b.control_bounding_box().max.y, 2.0);
    }

    #[test]
    fn validation() {
        assert!(RationalBezier::new(vec![Point::new(0.0, 0.0)], vec![1.0]).is_err());
        assert!(
            RationalBezier::new(
                vec![Point::new(0.0, 0.0), Point::new(1.0, 0.0)],
                vec![1.0, -1.0]
            )
            .is_err()
        );
    }
}
