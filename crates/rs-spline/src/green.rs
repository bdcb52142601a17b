//! Green's-theorem integrals along the Bezier pieces of a boundary: the one kernel that cell
//! coverage (`rs-coverage`) and cubature moments (`rs-cubature`) integrate with.
//!
//! Green's theorem turns an integral over a region into one over its boundary, and that into
//! a sum over the boundary's pieces `C(t) = (x(t), y(t))`, `t` in `[t0, t1]`:
//! `oint P dx + Q dy = sum_pieces integral_{t0}^{t1} (P(C(t)) x'(t) + Q(C(t)) y'(t)) dt`.
//! On a polynomial piece (all weights equal) with polynomial `P` and `Q` the integrand is a
//! polynomial in `t` of a degree the caller knows, integrated exactly (up to rounding) by the
//! Gauss-Legendre rule with the fewest nodes exact for it ([`gauss_rule_exact_for`]); on a
//! rational piece it is a rational function, integrated by the adaptive rule
//! ([`integrate_adaptive_vector`]) to an absolute tolerance, with bounded work and an error
//! estimate. [`PieceRule::for_piece`] makes that choice, [`integrate_piece`] carries it out.
//!
//! The integrand ([`PieceIntegrand`]) evaluates the piece itself: the kernel only picks the
//! parameters and weights and sums. An exact rule's sum is rounded in the order the caller
//! asks for ([`Jacobian`]), so each caller keeps the bits its results have always had.
//!
//! [`integrate_adaptive_vector`]: crate::quadrature::integrate_adaptive_vector

use crate::quadrature::{GaussRule, gauss_rule_exact_for, integrate_adaptive_into};

/// The quadrature of one piece's integral: [`PieceRule::for_piece`]'s choice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PieceRule {
    /// A fixed Gauss-Legendre rule exact for the integrand (a polynomial piece).
    Exact(&'static GaussRule),
    /// The adaptive rule, to the absolute tolerance `abs_tol` over the whole piece (a rational
    /// piece, or a polynomial integrand whose exact rule has too many nodes).
    Adaptive {
        /// The absolute tolerance of the adaptive rule.
        abs_tol: f64,
    },
}

impl PieceRule {
    /// The rule for an integrand of degree `integrand_degree` in `t` along a piece: the exact
    /// rule when the piece is `polynomial` (all its weights equal) and that rule has at most
    /// `max_nodes` nodes (and at most [`MAX_GAUSS_NODES`](crate::quadrature::MAX_GAUSS_NODES)),
    /// else the adaptive rule to `abs_tol`.
    ///
    /// For `P x' + Q y'` on a piece of degree `p`, with `P`, `Q` of degree `k`, the degree is
    /// `p k + p - 1` (`x'` has degree `p - 1`).
    #[inline]
    pub fn for_piece(
        polynomial: bool,
        integrand_degree: usize,
        max_nodes: usize,
        abs_tol: f64,
    ) -> Self {
        match gauss_rule_exact_for(integrand_degree) {
            Some(rule) if polynomial && rule.nodes().len() <= max_nodes => Self::Exact(rule),
            _ => Self::Adaptive { abs_tol },
        }
    }
}

/// The integrand of a Green's-theorem integral along one piece, `g(t) = P(C(t)) x'(t) +
/// Q(C(t)) y'(t)`, with as many components as the `sum` [`integrate_piece`] adds to.
///
/// Both methods integrate the same function; they differ only in where the rounding falls,
/// which each caller fixes to keep its results bit for bit.
pub trait PieceIntegrand {
    /// One node of an exact rule: adds `weight` times `g(t)` to `sum`, component by
    /// component, in the integrand's own order of operations.
    fn add_node(&mut self, t: f64, weight: f64, sum: &mut [f64]);

    /// The adaptive rule's view: writes `g(t)` into `out` and returns the rounding magnitude
    /// of the values (at least the size of the terms each is a sum of; see
    /// [`integrate_adaptive_vector`]).
    ///
    /// [`integrate_adaptive_vector`]: crate::quadrature::integrate_adaptive_vector
    fn values(&mut self, t: f64, out: &mut [f64]) -> f64;
}

/// Where an exact rule on `[t0, t1]` applies the Jacobian `h = (t1 - t0) / 2` of its map from
/// `[-1, 1]`: the two orders of rounding the callers' results were computed in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Jacobian {
    /// Once, to the rule's sum: `sum += h * sum_i w_i g(t_i)` (cell coverage: a part's
    /// integral on its own).
    OnTheSum,
    /// To each weight: every node adds `(h w_i) g(t_i)` straight to `sum` (moments: one
    /// running sum over all the pieces of a boundary).
    OnEachWeight,
}

/// How far an integral along a piece can be trusted.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PieceAccuracy {
    /// The adaptive rule's estimate of the absolute error of the worst component (0 for an
    /// exact rule, whose error is rounding).
    pub error: f64,
    /// False if the adaptive rule hit its work bound before meeting the tolerance.
    pub converged: bool,
}

/// Most components whose rule sums [`integrate_piece`] keeps on the stack (more allocate).
const STACK_COMPONENTS: usize = 6;

/// `integral_{t0}^{t1} g(t) dt` along one piece, added to `sum` (one entry per component of
/// `integrand`), by `rule`: the exact rule's nodes mapped onto `[t0, t1]` (rounded as
/// `jacobian` says), or the adaptive rule (each component's integral added to `sum`).
///
/// # Examples
///
/// ```
/// use rs_spline::green::{Jacobian, PieceIntegrand, PieceRule, integrate_piece};
/// // The segment from (0, 0) to (2, 1), C(t) = (2t, t): `integral y dx` along it is 1.
/// struct YDx;
/// impl PieceIntegrand for YDx {
///     fn add_node(&mut self, t: f64, weight: f64, sum: &mut [f64]) {
///         sum[0] += weight * t * 2.0;
///     }
///     fn values(&mut self, t: f64, out: &mut [f64]) -> f64 {
///         out[0] = t * 2.0;
///         out[0].abs()
///     }
/// }
/// let mut sum = [0.0];
/// // y x' = 2t has degree 1: one node.
/// let rule = PieceRule::for_piece(true, 1, 16, 1e-15);
/// let accuracy = integrate_piece(&mut YDx, (0.0, 1.0), rule, Jacobian::OnTheSum, &mut sum);
/// assert!(accuracy.converged);
/// assert_eq!(sum[0], 1.0);
/// ```
pub fn integrate_piece(
    integrand: &mut impl PieceIntegrand,
    (t0, t1): (f64, f64),
    rule: PieceRule,
    jacobian: Jacobian,
    sum: &mut [f64],
) -> PieceAccuracy {
    // The rule's own sum where it needs one: on the stack for a few components.
    let (mut stack, mut heap) = ([0.0; STACK_COMPONENTS], Vec::new());
    let dim = sum.len();
    match rule {
        PieceRule::Exact(gauss) => {
            let (half, nodes) = gauss.on(t0, t1);
            match jacobian {
                Jacobian::OnTheSum => {
                    let rule_sum = zeroed(&mut stack, &mut heap, dim);
                    for (t, w) in nodes {
                        integrand.add_node(t, w, rule_sum);
                    }
                    for (s, r) in sum.iter_mut().zip(rule_sum.iter()) {
                        *s += half * r;
                    }
                }
                Jacobian::OnEachWeight => {
                    for (t, w) in nodes {
                        integrand.add_node(t, half * w, sum);
                    }
                }
            }
            PieceAccuracy {
                error: 0.0,
                converged: true,
            }
        }
        PieceRule::Adaptive { abs_tol } => {
            let values = zeroed(&mut stack, &mut heap, dim);
            let (error, converged) =
                integrate_adaptive_into(|t, out| integrand.values(t, out), t0, t1, abs_tol, values);
            for (s, v) in sum.iter_mut().zip(values.iter()) {
                *s += v;
            }
            PieceAccuracy { error, converged }
        }
    }
}

/// `len` zeros: in `stack` when they fit, else in `heap`.
fn zeroed<'a>(
    stack: &'a mut [f64; STACK_COMPONENTS],
    heap: &'a mut Vec<f64>,
    len: usize,
) -> &'a mut [f64] {
    if len <= STACK_COMPONENTS {
        &mut stack[..len]
    } else {
        heap.resize(len, 0.0);
        heap
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prelude::*;
    use crate::{Point, RationalBezier};

    /// `integral x dy` along a rational Bezier piece (its point and tangent from the curve).
    struct XDy<'a>(&'a RationalBezier);

    impl PieceIntegrand for XDy<'_> {
        fn add_node(&mut self, t: f64, weight: f64, sum: &mut [f64]) {
            let (p, d) = self.0.point_and_tangent(t);
            sum[0] += weight * p.x * d.y;
        }
        fn values(&mut self, t: f64, out: &mut [f64]) -> f64 {
            let (p, d) = self.0.point_and_tangent(t);
            out[0] = p.x * d.y;
            out[0].abs()
        }
    }

    fn quarter(weights: Vec<f64>) -> RationalBezier {
        let pts = vec![
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.0, 1.0),
        ];
        RationalBezier::new(pts, weights).unwrap()
    }

    /// The exact rule (both roundings) and the adaptive rule agree on a polynomial piece, and
    /// the adaptive rule gives the quarter disc's `integral x dy = pi / 4` on the circular arc.
    #[test]
    fn exact_and_adaptive_rules_agree() {
        let parabola = quarter(vec![1.0; 3]);
        // x has degree 2, y' degree 1: the integrand has degree 3.
        let exact = PieceRule::for_piece(true, 3, 16, 1e-15);
        assert!(matches!(exact, PieceRule::Exact(r) if r.nodes().len() == 2));
        let mut sums = [[0.0], [0.0], [0.0]];
        for (s, (rule, jacobian)) in sums.iter_mut().zip([
            (exact, Jacobian::OnTheSum),
            (exact, Jacobian::OnEachWeight),
            (PieceRule::Adaptive { abs_tol: 1e-15 }, Jacobian::OnTheSum),
        ]) {
            let got = integrate_piece(&mut XDy(&parabola), (0.0, 1.0), rule, jacobian, s);
            assert!(got.converged);
        }
        // x = 1 - t^2, y = 2t - t^2: integral (1 - t^2)(2 - 2t) dt over [0, 1] = 5 / 6.
        for s in sums {
            assert!((s[0] - 5.0 / 6.0).abs() < 1e-15, "{s:?}");
        }
        let arc = quarter(vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0]);
        let rule = PieceRule::for_piece(false, 3, 16, 1e-15);
        assert_eq!(rule, PieceRule::Adaptive { abs_tol: 1e-15 });
        let mut s = [0.0];
        let got = integrate_piece(&mut XDy(&arc), (0.0, 1.0), rule, Jacobian::OnTheSum, &mut s);
        assert!(got.converged && got.error < 1e-14);
        assert!((s[0] - std::f64::consts::FRAC_PI_4).abs() < 1e-15);
    }

    /// Too many nodes for the caller's bound: the adaptive rule.
    #[test]
    fn high_degrees_go_adaptive() {
        let rule = PieceRule::for_piece(true, 40, 16, 1e-12);
        assert_eq!(rule, PieceRule::Adaptive { abs_tol: 1e-12 });
        let rule = PieceRule::for_piece(true, 40, 1024, 1e-12);
        assert!(matches!(rule, PieceRule::Exact(r) if r.nodes().len() == 21));
    }

    /// The rule's sum is added to what `sum` holds; parts of a piece add up to the whole.
    #[test]
    fn parts_add_up() {
        let parabola = quarter(vec![1.0; 3]);
        let rule = PieceRule::for_piece(true, 3, 16, 1e-15);
        let mut s = [0.0];
        for part in [(0.0, 0.3), (0.3, 0.8), (0.8, 1.0)] {
            integrate_piece(&mut XDy(&parabola), part, rule, Jacobian::OnTheSum, &mut s);
        }
        assert!((s[0] - 5.0 / 6.0).abs() < 1e-15);
    }
}
