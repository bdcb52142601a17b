//! Adaptive Gauss-Legendre quadrature with an error estimate and bounded work.

use smallvec::SmallVec;

use super::gauss::{GaussRule, fixed_gauss_rule};

/// Per-component scratch of the adaptive rule.
type Scratch = SmallVec<[f64; 4]>;

/// Number of nodes of the rule used by [`integrate_adaptive`]: exact for polynomials of degree
/// up to 31.
const ORDER: usize = 16;
/// Recursion depth limit of [`integrate_adaptive`] (intervals of `2^-40` of the start).
const MAX_DEPTH: u32 = 40;

/// Most intervals [`integrate_adaptive`] examines for one integral (each costs two 16-point
/// rules); past it the remaining intervals are accepted as they are and the result says so.
pub const MAX_INTERVALS: usize = 1 << 14;

/// The result of an adaptive integration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Integral {
    /// The estimate of the integral.
    pub value: f64,
    /// An estimate of its absolute error: the sum over the accepted intervals of the difference
    /// between the rule on the interval and on its two halves.
    pub error: f64,
    /// False if the interval budget ([`MAX_INTERVALS`]) or the depth limit ended the
    /// refinement before every interval met the tolerance.
    pub converged: bool,
}

impl Integral {
    /// The integral of nothing: 0, exactly, converged.
    pub const ZERO: Integral = Integral {
        value: 0.0,
        error: 0.0,
        converged: true,
    };
}

/// The integral over a union of intervals: values and error estimates add, and it converged
/// if every part did.
impl std::ops::Add for Integral {
    type Output = Integral;
    fn add(self, o: Integral) -> Integral {
        Integral {
            value: self.value + o.value,
            error: self.error + o.error,
            converged: self.converged && o.converged,
        }
    }
}

impl std::iter::Sum for Integral {
    fn sum<I: Iterator<Item = Integral>>(iter: I) -> Integral {
        iter.fold(Integral::ZERO, |a, b| a + b)
    }
}

/// The integral of a vector-valued integrand by adaptive Gauss-Legendre:
/// [`integrate_adaptive_vector`]'s answer.
#[derive(Clone, Debug, PartialEq)]
pub struct VectorIntegral {
    /// The estimate of the integral of each component.
    pub values: Vec<f64>,
    /// An estimate of the absolute error of the worst component: the sum over the accepted
    /// intervals of the largest difference between the rule on the interval and on its halves.
    pub error: f64,
    /// False if the interval budget ([`MAX_INTERVALS`]) or the depth limit ended the
    /// refinement before every interval met the tolerance.
    pub converged: bool,
}

/// The 16-point `rule` on `[a, b]` for the `out.len()` components of `f`, written to `out`;
/// returns the integral of the rounding magnitude `f` returns.
fn fixed_into(
    rule: &GaussRule,
    f: &mut impl FnMut(f64, &mut [f64]) -> f64,
    a: f64,
    b: f64,
    at: &mut [f64],
    out: &mut [f64],
) -> f64 {
    let (h, nodes) = rule.on(a, b);
    let mut abs = 0.0;
    if let ([one], [_]) = (&mut *out, &*at) {
        // One component (scalar integrals, coverage's moments): the same sums without the
        // loops over components.
        let mut sum = 0.0;
        for (t, wi) in nodes {
            let scale = f(t, at);
            sum += wi * at[0];
            abs += wi * scale;
        }
        *one = sum * h;
        return h.abs() * abs;
    }
    out.fill(0.0);
    for (t, wi) in nodes {
        let scale = f(t, at);
        for (o, &v) in out.iter_mut().zip(at.iter()) {
            *o += wi * v;
        }
        abs += wi * scale;
    }
    for o in out.iter_mut() {
        *o *= h;
    }
    h.abs() * abs
}

/// `integral_a^b f` for an integrand with `dim` components, by adaptive 16-point
/// Gauss-Legendre: **the** adaptive kernel ([`integrate_adaptive`] is its one-component case).
///
/// `f(t, values)` writes the `dim` components at `t` into `values` and returns their rounding
/// magnitude: at least the size of the terms whose sum each component is, so that a value
/// computed with cancellation is not refined below the noise of its own evaluation. An
/// interval is accepted when its estimate and the sum over its halves agree, in every
/// component, within `abs_tol` (scaled by the interval's share of `[a, b]`) or within the
/// rounding noise (`256 eps integral magnitude`), or at depth 40. At most [`MAX_INTERVALS`]
/// intervals are examined, so the work is bounded for every integrand;
/// [`VectorIntegral::converged`] says whether every interval met the tolerance. Exact to
/// rounding for polynomials of degree <= 31.
///
/// # Examples
///
/// ```
/// use rs_spline::quadrature::integrate_adaptive_vector;
/// // (integral of 1 / (1 + t^2), integral of t^3) on [0, 1] = (pi / 4, 1 / 4).
/// let got = integrate_adaptive_vector(
///     |t, v| {
///         v[0] = 1.0 / (1.0 + t * t);
///         v[1] = t * t * t;
///         1.0
///     },
///     2,
///     0.0,
///     1.0,
///     1e-15,
/// );
/// assert!(got.converged);
/// assert!((got.values[0] - std::f64::consts::FRAC_PI_4).abs() < 1e-15);
/// assert!((got.values[1] - 0.25).abs() < 1e-15);
/// ```
pub fn integrate_adaptive_vector(
    f: impl FnMut(f64, &mut [f64]) -> f64,
    dim: usize,
    a: f64,
    b: f64,
    abs_tol: f64,
) -> VectorIntegral {
    let mut values = vec![0.0; dim];
    let (error, converged) = integrate_adaptive_into(f, a, b, abs_tol, &mut values);
    VectorIntegral {
        values,
        error,
        converged,
    }
}

/// [`integrate_adaptive_vector`] with the values written into `values` (overwritten; its
/// length is the number of components), for callers that keep them on the stack: the error
/// estimate and whether it converged.
pub(crate) fn integrate_adaptive_into(
    mut f: impl FnMut(f64, &mut [f64]) -> f64,
    a: f64,
    b: f64,
    abs_tol: f64,
    values: &mut [f64],
) -> (f64, bool) {
    let dim = values.len();
    let total = b - a;
    values.fill(0.0);
    let (mut error, mut converged) = (0.0, true);
    // Scratch on the stack for a few components (the scalar rule and small moment vectors
    // allocate nothing).
    let zeros = || Scratch::from_elem(0.0, dim);
    let (mut at, mut left, mut right) = (zeros(), zeros(), zeros());
    // The intervals still to examine, a stack; `wholes` holds their rule estimates, `dim`
    // values per interval, in the same order.
    let mut stack: SmallVec<[(f64, f64, u32); 16]> = SmallVec::new();
    stack.push((a, b, 0u32));
    let mut wholes: SmallVec<[f64; 32]> = SmallVec::from_elem(0.0, dim);
    let rule = fixed_gauss_rule::<ORDER>();
    fixed_into(rule, &mut f, a, b, &mut at, &mut wholes);
    let mut examined = 0usize;
    while let Some((lo, hi, depth)) = stack.pop() {
        examined += 1;
        let whole_at = wholes.len() - dim;
        let mid = 0.5 * (lo + hi);
        let left_abs = fixed_into(rule, &mut f, lo, mid, &mut at, &mut left);
        let right_abs = fixed_into(rule, &mut f, mid, hi, &mut at, &mut right);
        let share = if total != 0.0 { (hi - lo) / total } else { 1.0 };
        let noise = 256.0 * f64::EPSILON * (left_abs + right_abs);
        // The largest difference over the components; a NaN stays (it never meets the test).
        let mut diff = 0.0f64;
        for ((w, l), r) in wholes[whole_at..].iter().zip(&left).zip(&right) {
            let d = (w - (l + r)).abs();
            if d > diff || d.is_nan() {
                diff = d;
            }
        }
        let met = diff <= (abs_tol * share).max(noise);
        if met || depth >= MAX_DEPTH || examined + stack.len() >= MAX_INTERVALS || !diff.is_finite()
        {
            wholes.truncate(whole_at);
            for ((o, l), r) in values.iter_mut().zip(&left).zip(&right) {
                *o += l + r;
            }
            error += diff;
            converged &= met;
        } else {
            wholes.truncate(whole_at);
            stack.push((mid, hi, depth + 1));
            wholes.extend_from_slice(&right);
            stack.push((lo, mid, depth + 1));
            wholes.extend_from_slice(&left);
        }
    }
    (error, converged)
}

/// `integral_a^b f` by adaptive 16-point Gauss-Legendre ([`integrate_adaptive_vector`] with
/// one component).
///
/// `f(t)` returns the integrand and its rounding magnitude: the size of the terms whose sum the
/// integrand is (for `x y' - y x'`, `|x y'| + |y x'|`), so that a value computed with
/// cancellation is not refined below the noise of its own evaluation. An interval is accepted
/// when its estimate and the sum over its halves agree within `abs_tol` (scaled by the
/// interval's share of `[a, b]`) or within the rounding noise (`256 eps integral |terms|`), or
/// at depth 40. At most [`MAX_INTERVALS`] intervals are examined, so the work is bounded for
/// every integrand; [`Integral::converged`] says whether every interval met the tolerance.
/// Exact to rounding for polynomials of degree <= 31.
pub fn integrate_adaptive(f: impl Fn(f64) -> (f64, f64), a: f64, b: f64, abs_tol: f64) -> Integral {
    let one = |t: f64, out: &mut [f64]| {
        let (v, scale) = f(t);
        out[0] = v;
        scale.abs().max(v.abs())
    };
    let got = integrate_adaptive_vector(one, 1, a, b, abs_tol);
    Integral {
        value: got.values[0],
        error: got.error,
        converged: got.converged,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn adaptive_handles_peaks() {
        // integral of 1 / (1e-4 + x^2) on [-1, 1] = 2 atan(100) / 1e-2
        let exact = 2.0 * 100f64.atan() / 1e-2;
        let got = integrate_adaptive(|x| (1.0 / (1e-4 + x * x), 0.0), -1.0, 1.0, 1e-12);
        assert!(got.converged);
        assert!((got.value - exact).abs() < 1e-10 * exact);
    }

    #[test]
    fn unattainable_tolerances_stop_at_the_rounding_noise() {
        // A large, nearly cancelling integrand: 1e6 + 1e-3 sin(x) over [0, 3], tolerance 0.
        let got = integrate_adaptive(|x| (1e6 + 1e-3 * (7.0 * x).sin(), 0.0), 0.0, 3.0, 0.0);
        let exact = 3e6 + 1e-3 * (1.0 - 21f64.cos()) / 7.0;
        assert!((got.value - exact).abs() < 1e-8, "{got:?} vs {exact}");
    }

    #[test]
    fn cancelling_integrands_stop_at_their_own_noise() {
        // The value is a difference of two terms of size 1e8 that cancel to 1: refining below
        // 1e-8 relative is chasing the evaluation's rounding.
        let f = |x: f64| {
            let (a, b) = (1e8 * (1.0 + x), 1e8 * x + 1e8 - 1.0 - x.sin());
            (a - b, a.abs() + b.abs())
        };
        let got = integrate_adaptive(f, 0.0, 1.0, 1e-15);
        let exact = 1.0 + (1.0 - 1f64.cos());
        assert!((got.value - exact).abs() < 1e-6, "{got:?}");
    }

    #[test]
    fn the_work_is_bounded_for_any_integrand() {
        // Not integrable at 0: the refinement never meets the tolerance there.
        let calls = std::cell::Cell::new(0usize);
        let got = integrate_adaptive(
            |x: f64| {
                calls.set(calls.get() + 1);
                (1.0 / x, 0.0)
            },
            0.0,
            1.0,
            1e-15,
        );
        assert!(!got.converged);
        assert!(calls.get() <= 33 * 2 * MAX_INTERVALS, "{}", calls.get());
    }
}
