//! Bracketed solvers with guaranteed convergence for a sign change on `[a, b]`.

use crate::de_casteljau_with_derivative;
use crate::error::{RootsError, check_interval};

/// Hard cap on iterations of every bracketed solver (far above what bisection needs to shrink any
/// finite `f64` interval to one ulp).
const MAX_ITER: usize = 2200;

/// Finds a root of `f` on `[a, b]` with the ITP method (Oliveira and Takahashi, 2020).
///
/// Preconditions: `f(a)` and `f(b)` have opposite signs or one of them is zero. Returns `t` with
/// `f(t) == 0` or a bracket of width at most `2 * xtol` (or one ulp) around a sign change,
/// in at most `ceil(log2((b - a) / (2 xtol))) + 1` evaluations beyond the two endpoints: never
/// slower than bisection, superlinear on smooth functions.
///
/// # Examples
///
/// ```
/// use rs_roots::itp;
/// let r = itp(|t| t * t * t - 2.0, 0.0, 2.0, 1e-15).unwrap();
/// assert!((r - 2f64.cbrt()).abs() < 1e-14);
/// ```
pub fn itp<F: FnMut(f64) -> f64>(mut f: F, a: f64, b: f64, xtol: f64) -> Result<f64, RootsError> {
    check_interval(a, b)?;
    let (mut a, mut b) = (a, b);
    let mut ya = finite(f(a), a)?;
    let mut yb = finite(f(b), b)?;
    if ya == 0.0 {
        return Ok(a);
    }
    if yb == 0.0 {
        return Ok(b);
    }
    if (ya > 0.0) == (yb > 0.0) {
        return Err(RootsError::NoSignChange { fa: ya, fb: yb });
    }
    let sign = if ya < 0.0 { 1.0 } else { -1.0 };
    ya *= sign;
    yb *= sign;
    let xtol = xtol.max(0.0);
    let width0 = b - a;
    let k1 = 0.2 / width0;
    let n_half = if xtol > 0.0 {
        ((width0 / (2.0 * xtol)).log2().ceil()).max(0.0) as i32
    } else {
        1100
    };
    let n_max = n_half + 1;
    for j in 0..MAX_ITER {
        if b - a <= 2.0 * xtol {
            break;
        }
        let half = 0.5 * (a + b);
        let width = b - a;
        let r = (xtol * 2f64.powi(n_max - j as i32) - 0.5 * width).max(0.0);
        let delta = k1 * width * width;
        let xf = (yb * a - ya * b) / (yb - ya);
        let sigma = (half - xf).signum();
        let xt = if delta <= (half - xf).abs() {
            xf + sigma * delta
        } else {
            half
        };
        let mut x = if (xt - half).abs() <= r {
            xt
        } else {
            half - sigma * r
        };
        if !(x > a && x < b) {
            x = half;
            if !(x > a && x < b) {
                break; // a and b are adjacent floats
            }
        }
        let y = sign * finite(f(x), x)?;
        if y > 0.0 {
            b = x;
            yb = y;
        } else if y < 0.0 {
            a = x;
            ya = y;
        } else {
            return Ok(x);
        }
    }
    Ok(0.5 * (a + b))
}

/// Finds a root on `[a, b]` by Newton's method safeguarded with bisection: a Newton step is
/// taken when it stays strictly inside the current bracket, otherwise the bracket is bisected.
///
/// `f_df(t)` returns `(f(t), f'(t))`. Preconditions as for [`itp`]. Starts from the secant
/// through the end values and stops when a step is at most `xtol`, the bracket is one ulp wide,
/// or `f` vanishes; the result always lies in `[a, b]`.
///
/// # Examples
///
/// ```
/// use rs_roots::newton_bracketed;
/// let r = newton_bracketed(|t| (t.cos() - t, -t.sin() - 1.0), 0.0, 1.0, 1e-15).unwrap();
/// assert!((r.cos() - r).abs() < 1e-15);
/// ```
pub fn newton_bracketed<F: FnMut(f64) -> (f64, f64)>(
    mut f_df: F,
    a: f64,
    b: f64,
    xtol: f64,
) -> Result<f64, RootsError> {
    check_interval(a, b)?;
    let fa = finite(f_df(a).0, a)?;
    let fb = finite(f_df(b).0, b)?;
    safeguarded_newton(f_df, (a, fa), (b, fb), xtol)
}

/// The one bracketed Newton iteration of the workspace, given the end values `fa = f(a)`,
/// `fb = f(b)` (`a < b`) already computed: exact zeros at the ends are returned as they are,
/// equal signs are [`RootsError::NoSignChange`], and otherwise `f` is oriented so that it is
/// negative at the left end of the bracket before iterating.
pub(crate) fn safeguarded_newton<F: FnMut(f64) -> (f64, f64)>(
    mut f_df: F,
    (a, fa): (f64, f64),
    (b, fb): (f64, f64),
    xtol: f64,
) -> Result<f64, RootsError> {
    if fa == 0.0 {
        return Ok(a);
    }
    if fb == 0.0 {
        return Ok(b);
    }
    if (fa > 0.0) == (fb > 0.0) || fa.is_nan() || fb.is_nan() {
        return Err(RootsError::NoSignChange { fa, fb });
    }
    // Negation is exact, so the oriented values are the true ones up to sign.
    let sign = if fa > 0.0 { -1.0 } else { 1.0 };
    let (mut lo, mut hi) = (a, b);
    let (ga, gb) = (sign * fa, sign * fb);
    let mut t = a + (b - a) * (ga / (ga - gb));
    if !(t >= a && t <= b) {
        t = 0.5 * (a + b);
    }
    for _ in 0..MAX_ITER {
        let (f, df) = f_df(t);
        let (f, df) = (sign * finite(f, t)?, sign * df);
        if f == 0.0 {
            return Ok(t);
        }
        if f < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return Ok(t);
        }
        let newton = t - f / df;
        let next = if df > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            mid
        };
        if (next - t).abs() <= xtol {
            return Ok(next);
        }
        t = next;
    }
    Ok(t)
}

/// The root in `[0, 1]` of the Bernstein polynomial with coefficients `c` whose end
/// coefficients differ in sign (or one vanishes), by [`newton_bracketed`]'s iteration to one
/// ulp; `None` without a sign change. On a monotone piece this is the unique root, and the end
/// coefficients decide exactly whether the root is an end point.
///
/// # Examples
///
/// ```
/// use rs_roots::bernstein_sign_change_root;
/// // b(s) = -1 (1-s)^2 + 2 * 0 s (1-s) + 1 s^2 = 2s - 1
/// assert_eq!(bernstein_sign_change_root(&[-1.0, 0.0, 1.0]), Some(0.5));
/// assert_eq!(bernstein_sign_change_root(&[1.0, 2.0, 1.0]), None);
/// ```
pub fn bernstein_sign_change_root(c: &[f64]) -> Option<f64> {
    let (&first, &last) = (c.first()?, c.last()?);
    safeguarded_newton(
        |t| de_casteljau_with_derivative(c, t),
        (0.0, first),
        (1.0, last),
        0.5 * f64::EPSILON,
    )
    .ok()
}

fn finite(v: f64, t: f64) -> Result<f64, RootsError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(RootsError::NonFiniteValue { t })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn itp_converges_on_hard_functions() {
        // Flat near the root, steep elsewhere.
        let r = itp(|t: f64| (t - 0.3).powi(9), 0.0, 1.0, 1e-14).unwrap();
        assert!((r - 0.3).abs() < 2e-2); // flat: any point where the sign flips is right
        let r = itp(|t: f64| (t - 1.0 / 3.0).signum(), 0.0, 1.0, 1e-15).unwrap();
        assert!((r - 1.0 / 3.0).abs() < 4e-15);
        let r = itp(|t: f64| t.exp() - 2.0, -10.0, 10.0, 1e-15).unwrap();
        assert!((r - 2f64.ln()).abs() < 1e-14);
    }

    #[test]
    fn itp_rejects_bad_brackets() {
        assert!(matches!(
            itp(|t| t * t + 1.0, -1.0, 1.0, 1e-12),
            Err(RootsError::NoSignChange { .. })
        ));
        assert!(itp(|t| t, 1.0, -1.0, 1e-12).is_err());
        assert!(itp(|_| f64::NAN, -1.0, 1.0, 1e-12).is_err());
        assert_eq!(itp(|t| t, 0.0, 1.0, 1e-12), Ok(0.0));
    }

    #[test]
    fn itp_terminates_with_zero_tolerance() {
        let r = itp(|t| t - 0.1, 0.0, 1.0, 0.0).unwrap();
        assert!((r - 0.1).abs() <= 2.0 * f64::EPSILON);
    }

    #[test]
    fn newton_bracketed_handles_flat_and_steep() {
        let r = newton_bracketed(|t| (t * t * t - 0.001, 3.0 * t * t), -1.0, 1.0, 1e-15).unwrap();
        assert!((r - 0.1).abs() < 1e-14);
        // Newton from the midpoint would jump out: tanh is almost flat far from 0.
        let r = newton_bracketed(
            |t: f64| (t.tanh() - 0.5, 1.0 - t.tanh().powi(2)),
            -20.0,
            30.0,
            1e-15,
        )
        .unwrap();
        assert!((r - 0.5f64.atanh()).abs() < 1e-13);
    }

    #[test]
    fn newton_bracketed_rejects_bad_brackets() {
        assert!(newton_bracketed(|t| (t * t + 1.0, 2.0 * t), -1.0, 1.0, 1e-12).is_err());
    }
}
