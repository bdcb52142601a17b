//! Rational B-spline curves of any dimension (the plane, space), and the one evaluation
//! kernel every B-spline of this workspace goes through.

use rs_roots::Blend;

use crate::error::{check_control_points, normalized_weights};
use crate::{KnotVector, SplineError, Vector};

/// Homogeneous sums at `u` (clamped into the domain) on the knot span holding it: for each
/// derivative order `d <= nd` (at most 2), `(sum_j w_j N_j^(d)(u) P_j, sum_j w_j N_j^(d)(u))`
/// over the `p + 1` basis functions non-zero there; entries past `nd` are zero. Without
/// `weights` every weight is 1.
///
/// This is the one B-spline evaluation kernel (de Boor's basis functions, The NURBS Book
/// A2.3, in [`KnotVector`]): planar [`crate::NurbsCurve`]s, curves of any dimension and
/// tensor-product surfaces are all evaluated through it. Each term is `(w P) N` and `w N`,
/// summed in the order of the basis functions.
pub fn rational_sums<P: Blend>(
    knots: &KnotVector,
    points: &[P],
    weights: Option<&[f64]>,
    u: f64,
    nd: usize,
) -> [(P, f64); 3] {
    let (a, b) = knots.domain();
    let u = u.clamp(a, b);
    let p = knots.degree();
    let k = knots.span(u);
    let nd = nd.min(2);
    knots.with_basis_derivatives(k, u, nd, |basis| {
        let mut out = [(P::default(), 0.0); 3];
        for (slot, row) in out.iter_mut().zip(basis.chunks_exact(p + 1)) {
            for (j, &n) in row.iter().enumerate() {
                let i = k - p + j;
                let w = weights.map_or(1.0, |w| w[i]);
                slot.0 = slot.0 + points[i] * w * n;
                slot.1 += w * n;
            }
        }
        out
    })
}

/// The quotient rule for `C = A / w` from homogeneous sums `[A, A', A'']` with their weights:
/// `C = A / w`, `C' = (A' - w' C) / w`, `C'' = (A'' - 2 w' C' - w'' C) / w`.
pub fn rational_quotient<P: Blend + std::ops::Div<f64, Output = P>>(h: [(P, f64); 3]) -> [P; 3] {
    let w = h[0].1;
    let point = h[0].0 / w;
    let first = (h[1].0 - point * h[1].1) / w;
    let second = (h[2].0 - first * (2.0 * h[1].1) - point * h[2].1) / w;
    [point, first, second]
}

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
}
