//! Rational Bezier curves on `[0, 1]`.

use rs_roots::{
    Bernstein, Polynomial, de_casteljau, de_casteljau_split, de_casteljau_with_derivative,
    real_roots_in,
};

use crate::error::check_control_points;
use crate::homogeneous::{Hpoint, rational_derivatives};
use crate::quadrature::{Integral, integrate_adaptive};
use crate::{BoundingBox, CurveDerivatives, Point, SplineError};

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
/// use rs_spline::{Point, RationalBezier};
/// let b = RationalBezier::new(
///     vec![Point::new(0.0, 0.0), Point::new(1.0, 2.0), Point::new(2.0, 0.0)],
///     vec![1.0, 1.0, 1.0],
/// )
/// .unwrap();
/// assert_eq!(b.point_at(0.5), Point::new(1.0, 1.0));
/// let (left, right) = b.subdivide(0.5);
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

    /// The same curve labelled with another parameter range.
    pub fn with_param_range(mut self, u0: f64, u1: f64) -> Self {
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

    /// The original parameter range `[u0, u1]`; local `t` maps to `u0 + t (u1 - u0)`.
    pub fn param_range(&self) -> (f64, f64) {
        self.range
    }

    /// `C(0) = P_0`.
    pub fn start_point(&self) -> Point {
        self.points[0]
    }

    /// `C(1) = P_n`.
    pub fn end_point(&self) -> Point {
        self.points[self.points.len() - 1]
    }

    /// `C(t)` by de Casteljau's algorithm in homogeneous coordinates (stable, any `t`; meant
    /// for `t` in `[0, 1]`).
    pub fn point_at(&self, t: f64) -> Point {
        de_casteljau(&self.homogeneous(), t).project()
    }

    /// `C(t)`, `C'(t)`, `C''(t)` with respect to the local parameter `t` (multiply by
    /// `1 / (u1 - u0)` and its square for derivatives with respect to the original parameter).
    pub fn derivatives(&self, t: f64) -> CurveDerivatives {
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

    /// Splits at local `t` (de Casteljau in homogeneous coordinates) into the pieces on
    /// `[0, t]` and `[t, 1]`, each reparametrised to `[0, 1]`, with parameter ranges split
    /// accordingly.
    pub fn subdivide(&self, t: f64) -> (Self, Self) {
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

    /// The piece on local `[t0, t1]` (`0 <= t0 < t1 <= 1`), reparametrised to `[0, 1]`.
    pub fn sub_curve(&self, t0: f64, t1: f64) -> Self {
        let right = if t0 > 0.0 {
            self.subdivide(t0).1
        } else {
            self.clone()
        };
        if t1 < 1.0 {
            right.subdivide((t1 - t0) / (1.0 - t0)).0
        } else {
            right
        }
    }

    /// The same curve traversed backwards; the parameter range is kept.
    pub fn reversed(&self) -> Self {
        Self {
            points: self.points.iter().rev().copied().collect(),
            weights: self.weights.iter().rev().copied().collect(),
            range: self.range,
        }
    }

    /// Bounding box of the control points (contains the curve because weights are > 0).
    pub fn control_bounding_box(&self) -> BoundingBox {
        BoundingBox::from_points(self.points.iter().copied())
            .unwrap_or(BoundingBox::from_point(self.points[0]))
    }

    /// Tight bounding box: end points and the points where `x'(t) = 0` or `y'(t) = 0` in
    /// `(0, 1)`, found as roots of the derivative numerators (see
    /// [`RationalBezier::derivative_numerators`]). Should the root finder fail, the control
    /// bounding box is returned: larger, but still a box that contains the curve.
    pub fn bounding_box(&self) -> BoundingBox {
        let mut b = BoundingBox::from_point(self.start_point()).including(self.end_point());
        let (dx, dy) = self.derivative_numerators();
        for d in [dx, dy] {
            match real_roots_in(&d, 0.0, 1.0) {
                Ok(roots) => {
                    for t in roots {
                        b = b.including(self.point_at(t));
                    }
                }
                // The zero polynomial (constant coordinate) has no isolated extremes.
                Err(rs_roots::RootsError::ZeroPolynomial) => {}
                // Roots that cannot be computed: the control box still contains the curve.
                Err(_) => return self.control_bounding_box(),
            }
        }
        b
    }

    /// The Green integral `1/2 integral_0^1 (x y' - y x') dt` of the piece: its contribution to
    /// the signed area of a closed loop (adaptive Gauss-Legendre to about `1e-15` of the
    /// squared size of its control polygon, bounded work; see
    /// [`crate::quadrature::integrate_adaptive`]).
    pub fn area_integral(&self) -> Integral {
        self.area_integral_on(0.0, 1.0)
    }

    /// The Green integral over local `[t0, t1]`.
    pub fn area_integral_on(&self, t0: f64, t1: f64) -> Integral {
        let scale = self.control_bounding_box().diagonal().powi(2);
        let f = |t: f64| {
            let d = self.derivatives(t);
            let (a, b) = (d.point.x * d.first.y, d.point.y * d.first.x);
            (0.5 * (a - b), 0.5 * (a.abs() + b.abs()))
        };
        integrate_adaptive(f, t0, t1, 1e-15 * scale.max(f64::MIN_POSITIVE))
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
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let b = quarter_circle().with_param_range(2.0, 4.0);
        let (l, r) = b.subdivide(0.3);
        assert_eq!(l.param_range(), (2.0, 2.6));
        assert_eq!(r.param_range(), (2.6, 4.0));
        for i in 0..=10 {
            let s = i as f64 / 10.0;
            assert!(l.point_at(s).distance(b.point_at(0.3 * s)) < 1e-15);
            assert!(r.point_at(s).distance(b.point_at(0.3 + 0.7 * s)) < 1e-15);
        }
        let mid = b.sub_curve(0.2, 0.7);
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
