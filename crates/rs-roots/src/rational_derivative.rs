//! The sign of a rational Bezier coordinate's derivative, in the Bernstein basis: for deciding
//! without a root solve that a coordinate has no stationary point.

use crate::binomial;

/// The numerator `X' W - X W'` of the derivative of a rational Bezier coordinate
/// `x(t) = X(t) / W(t)` of degree `n` (`X = sum_i w_i c_i B_i^n`, `W = sum_i w_i B_i^n`), in the
/// Bernstein basis of degree `2n - 1` on `[0, 1]` (one more than the polynomial's degree
/// `2n - 2`: a degree-elevated form of it), formed from the control coordinates `coords` and
/// the weights directly, written into `out` (`2n` coefficients; `[0]` for degree 0). Its sign
/// is the sign of `x'(t)` (`W^2 > 0`).
///
/// The coordinate is taken relative to the first control point, which leaves the numerator
/// unchanged (`W' W - W W' = 0`) and makes the first coefficient `n w_0 w_1 (c_1 - c_0)`,
/// exactly zero at a tangency there. With `B_i^{n-1} B_j^n = C(n-1, i) C(n, j) /
/// C(2n-1, i+j) B_{i+j}^{2n-1}` the product is formed without a change of basis.
///
/// # Panics
/// If `weights.len() != coords.len()`, either is empty, or `out.len()` is not
/// `max(2n, 1)` for `n = coords.len() - 1`.
///
/// # Examples
///
/// ```
/// use rs_roots::{clearly_one_signed, rational_derivative_numerator};
/// // x(t) = t^2 on control abscissas 0, 0, 1: x' = 2t, zero only at the start.
/// let mut out = [0.0; 4];
/// rational_derivative_numerator(&[0.0, 0.0, 1.0], &[1.0, 1.0, 1.0], &mut out);
/// assert_eq!(out[0], 0.0);
/// assert!(out.iter().all(|&c| c >= 0.0));
/// assert!(!clearly_one_signed(&out));
/// ```
pub fn rational_derivative_numerator(coords: &[f64], weights: &[f64], out: &mut [f64]) {
    assert_eq!(coords.len(), weights.len(), "one weight per control point");
    assert!(!coords.is_empty(), "a curve has a control point");
    let n = coords.len() - 1;
    assert_eq!(out.len(), (2 * n).max(1), "2n coefficients");
    out.fill(0.0);
    if n == 0 {
        return;
    }
    let (c, w) = (coords, weights);
    let h = |i: usize| w[i] * (c[i] - c[0]);
    let m = 2 * n - 1;
    // The binomials of the three degrees, each computed once (a table for the degrees most
    // curves have; the same values either way).
    const TABLE: usize = 64;
    let table = |d: usize| -> [f64; TABLE] {
        let mut t = [0.0; TABLE];
        for (k, v) in t.iter_mut().enumerate().take((d + 1).min(TABLE)) {
            *v = binomial(d, k);
        }
        t
    };
    let small = m < TABLE;
    let (b_lower, b_n, b_m) = if small {
        (table(n - 1), table(n), table(m))
    } else {
        ([0.0; TABLE], [0.0; TABLE], [0.0; TABLE])
    };
    let choose = |t: &[f64; TABLE], d: usize, k: usize| if small { t[k] } else { binomial(d, k) };
    for i in 0..n {
        let (dh, dw) = (h(i + 1) - h(i), w[i + 1] - w[i]);
        let bi = choose(&b_lower, n - 1, i);
        for j in 0..=n {
            let v = dh * w[j] - h(j) * dw;
            out[i + j] += v * (bi * choose(&b_n, n, j) / choose(&b_m, m, i + j));
        }
    }
    for o in out.iter_mut() {
        *o *= n as f64;
    }
}

/// Whether Bernstein coefficients are all finite, of one sign and at least `1e-6` of the
/// largest in size: the polynomial (a convex combination of them at every `t` in `[0, 1]`) is
/// then at least that far from zero on `[0, 1]`, far beyond the rounding of these coefficients
/// or of a power form's evaluation, so no root solve can report a root there.
pub fn clearly_one_signed(c: &[f64]) -> bool {
    let largest = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let floor = 1e-6 * largest;
    largest.is_finite()
        && largest > 0.0
        && (c.iter().all(|&v| v > floor) || c.iter().all(|&v| v < -floor))
}

/// Whether Bernstein coefficients rule out a root strictly inside `(0, 1)`: as
/// [`clearly_one_signed`], except that the first and the last coefficient may also be exactly
/// zero (a root at an end, such as a tangency at a curve's end point; every other coefficient
/// then keeps the polynomial away from zero on the open interval, since each basis polynomial
/// is positive there).
pub fn no_interior_root(c: &[f64]) -> bool {
    let largest = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let floor = 1e-6 * largest;
    let last = c.len().saturating_sub(1);
    // The coefficients that must clear the floor: all but exact zeros at the two ends.
    let counted = |k: usize, v: f64| (k != 0 && k != last) || v != 0.0;
    let signed = |keep: fn(f64, f64) -> bool| {
        c.iter()
            .enumerate()
            .all(|(k, &v)| !counted(k, v) || keep(v, floor))
    };
    c.len() > 2
        && largest.is_finite()
        && largest > 0.0
        && (signed(|v, f| v > f) || signed(|v, f| v < -f))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::de_casteljau;

    /// Against the quotient rule evaluated directly: `X' W - X W'` from the Bernstein sums of
    /// `X`, `W` and their derivatives, at eleven parameters, degrees 1 to 6.
    #[test]
    fn equals_the_quotient_rule_numerator() {
        for n in 1..=6usize {
            let c: Vec<f64> = (0..=n)
                .map(|i| (i as f64 * 1.3).sin() * 2.0 + 0.5)
                .collect();
            let w: Vec<f64> = (0..=n)
                .map(|i| 1.0 + 0.5 * (i as f64 * 0.7).cos())
                .collect();
            let mut out = vec![0.0; 2 * n];
            rational_derivative_numerator(&c, &w, &mut out);
            let wc: Vec<f64> = c.iter().zip(&w).map(|(c, w)| c * w).collect();
            let deriv = |b: &[f64]| -> Vec<f64> {
                b.windows(2).map(|p| n as f64 * (p[1] - p[0])).collect()
            };
            let scale: f64 = out.iter().map(|v| v.abs()).sum::<f64>().max(1.0);
            for k in 0..=10 {
                let t = k as f64 / 10.0;
                let (x, dx) = (de_casteljau(&wc, t), de_casteljau(&deriv(&wc), t));
                let (ww, dw) = (de_casteljau(&w, t), de_casteljau(&deriv(&w), t));
                let want = dx * ww - x * dw;
                let got = de_casteljau(&out, t);
                assert!(
                    (got - want).abs() <= 1e-12 * scale,
                    "n {n} t {t}: {got} {want}"
                );
            }
        }
    }

    #[test]
    fn one_signed_needs_a_margin_and_finite_coefficients() {
        assert!(clearly_one_signed(&[1.0, 2.0, 0.5]));
        assert!(clearly_one_signed(&[-1.0, -2.0]));
        assert!(!clearly_one_signed(&[1.0, 0.0, 2.0]));
        assert!(!clearly_one_signed(&[1.0, 1e-9, 2.0]));
        assert!(!clearly_one_signed(&[0.0, 0.0]));
        assert!(!clearly_one_signed(&[1.0, f64::NAN]));
        assert!(!clearly_one_signed(&[1.0, f64::INFINITY]));
        assert!(!clearly_one_signed(&[1.0, -1.0]));
    }

    #[test]
    fn end_zeros_leave_the_open_interval_root_free() {
        assert!(no_interior_root(&[0.0, 1.0, 2.0, 0.0]));
        assert!(no_interior_root(&[0.0, -1.0, -2.0]));
        assert!(no_interior_root(&[1.0, 2.0, 0.5]));
        assert!(!no_interior_root(&[0.0, 0.0, 1.0]));
        assert!(!no_interior_root(&[0.0, 1.0, -1.0, 0.0]));
        assert!(!no_interior_root(&[0.0, 0.0, 0.0]));
        assert!(!no_interior_root(&[1.0, 1e-9, 2.0]));
        // Two coefficients: both are ends, and zeros there leave nothing to decide by.
        assert!(!no_interior_root(&[0.0, 1.0]));
        assert!(!no_interior_root(&[0.0, f64::NAN, 1.0]));
    }
}
