//! Root isolation for Bernstein polynomials by sign-variation subdivision.

use crate::bracket::itp;
use crate::error::{RootsError, check_finite, check_interval};
use crate::{Bernstein, Polynomial};

/// Subdivision depth after which an interval that still shows two or more sign changes is
/// reported as one (multiple or clustered) root: `2^-48 ~ 3.6e-15` of the start interval.
const MAX_DEPTH: u32 = 48;
/// Roots closer than this (in the `[0, 1]` parameter) are one root: a few leaf widths.
const DEDUP_WIDTH: f64 = 6e-14;

/// All roots of a Bernstein polynomial in `[0, 1]`, ascending, each reported once.
///
/// The algorithm is certified by the variation-diminishing property: an interval whose
/// coefficients show no sign change holds no root; one showing exactly one sign change with
/// opposite signs at its ends holds exactly one, which [`itp`] finds to full precision. Other
/// intervals, and one-signed intervals whose smallest coefficient is within rounding of zero
/// (where a double root may have been perturbed into a near-miss), are halved by de Casteljau
/// down to 48 levels, where a remaining cluster whose value is within rounding of zero is
/// reported as one root at its midpoint (a root of multiplicity >= 2, or roots closer than
/// `6e-14` apart, which are reported once). End points whose coefficient is within rounding of
/// zero are roots.
///
/// # Errors
/// [`RootsError::NonFiniteCoefficient`] for NaN/inf coefficients and
/// [`RootsError::ZeroPolynomial`] if every coefficient is zero.
///
/// # Examples
///
/// ```
/// use rs_roots::{bernstein_roots, Bernstein, Polynomial};
/// let p = Polynomial::from_roots(&[0.25, 0.5, 0.5, 3.0]);
/// let r = bernstein_roots(&Bernstein::from_power(&p, 4)).unwrap();
/// assert_eq!(r.len(), 2);
/// assert!((r[0] - 0.25).abs() < 1e-14 && (r[1] - 0.5).abs() < 1e-7);
/// ```
pub fn bernstein_roots(b: &Bernstein) -> Result<Vec<f64>, RootsError> {
    check_finite(b.coeffs())?;
    if b.coeffs().iter().all(|&c| c == 0.0) {
        return Err(RootsError::ZeroPolynomial);
    }
    let n = b.degree();
    let noise = 4.0 * (n as f64 + 1.0) * f64::EPSILON * b.magnitude();
    let c = b.coeffs();
    if let Some(ends) = only_end_roots(c, noise) {
        return Ok(ends);
    }
    let mut roots = Vec::new();
    if c[0].abs() <= noise {
        roots.push(0.0);
    }
    if c[n].abs() <= noise {
        roots.push(1.0);
    }
    let mut stack = vec![(0.0f64, 1.0f64, 0u32, b.clone())];
    while let Some((lo, hi, depth, piece)) = stack.pop() {
        let v = piece.sign_variations();
        let pc = piece.coeffs();
        // With one sign, |b| >= min_k |b_k| on the piece: certified root-free unless that bound
        // is within rounding (a double root perturbed into a near-miss).
        if v == 0 && pc.iter().all(|c| c.abs() > noise) {
            continue;
        }
        let (first, last) = (pc[0], pc[pc.len() - 1]);
        if v == 1 && first != 0.0 && last != 0.0 && (first > 0.0) != (last > 0.0) {
            let s = itp(|s| piece.eval(s), 0.0, 1.0, 0.0)?;
            roots.push(lo + s * (hi - lo));
            continue;
        }
        if pc.iter().all(|c| c.abs() <= noise) {
            // The whole piece is zero to rounding: one numerical root (cluster) here.
            roots.push(0.5 * (lo + hi));
            continue;
        }
        if depth >= MAX_DEPTH {
            if piece.eval(0.5).abs() <= noise {
                roots.push(0.5 * (lo + hi));
            }
            continue;
        }
        let mid = 0.5 * (lo + hi);
        let (left, right) = piece.split(0.5);
        if left.coeffs()[n] == 0.0 {
            roots.push(mid);
        }
        stack.push((mid, hi, depth + 1, right));
        stack.push((lo, mid, depth + 1, left));
    }
    roots.sort_by(f64::total_cmp);
    Ok(merge_clusters(roots, |s| b.eval(s), 4.0 * noise))
}

/// Merges sorted neighbours that cannot be told apart: closer than [`DEDUP_WIDTH`], or with a
/// midpoint where `|f|` is still within `noise` (callers pass a few times the rounding level,
/// because leaves at the edge of a double root's noise band sit right at that level). Keeps the member with the smallest `|f|`.
fn merge_clusters(sorted: Vec<f64>, f: impl Fn(f64) -> f64, noise: f64) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(sorted.len());
    for x in sorted {
        if let Some(last) = out.last_mut() {
            let mid = 0.5 * (*last + x);
            if x - *last <= DEDUP_WIDTH || f(mid).abs() <= noise {
                if f(x).abs() < f(*last).abs() {
                    *last = x;
                }
                continue;
            }
        }
        out.push(x);
    }
    out
}

/// The roots when the coefficients tell them without a search: every coefficient of one sign
/// and above `noise`, except exact zeros at the ends. A positive combination of the Bernstein
/// basis vanishes nowhere in `(0, 1)`, so the zero ends (`t = 0` for `c_0 = 0`, `t = 1` for
/// `c_n = 0`) are the only roots. The common case of a curve tested against a segment through
/// its own end point, and of no root at all, without the subdivision's allocations.
fn only_end_roots(c: &[f64], noise: f64) -> Option<Vec<f64>> {
    let n = c.len() - 1;
    let (start, end) = (c[0] == 0.0, c[n] == 0.0);
    let inner = &c[usize::from(start)..c.len() - usize::from(end)];
    let positive = inner.first().is_some_and(|&x| x > 0.0);
    let one_sign = !inner.is_empty()
        && inner
            .iter()
            .all(|&x| x.abs() > noise && (x > 0.0) == positive);
    one_sign.then(|| {
        let mut ends = Vec::new();
        if start {
            ends.push(0.0);
        }
        if end {
            ends.push(1.0);
        }
        ends
    })
}

/// All real roots of `p` in `[a, b]` by Bernstein isolation of `p(a + (b - a) s)`.
///
/// This is the certified fallback of [`crate::real_roots_in`], usable on its own. Like it, it
/// reports a root where `p` has a local extremum within Horner's rounding bound of zero (a
/// double root blurred by rounding in the coefficients).
///
/// # Errors
/// As [`bernstein_roots`], plus [`RootsError::InvalidInterval`].
pub fn bernstein_roots_in(p: &Polynomial, a: f64, b: f64) -> Result<Vec<f64>, RootsError> {
    check_finite(p.coeffs())?;
    check_interval(a, b)?;
    if p.is_zero() {
        return Err(RootsError::ZeroPolynomial);
    }
    if a == b {
        return Ok(if p.eval(a).abs() <= p.eval_error_bound(a) {
            vec![a]
        } else {
            Vec::new()
        });
    }
    let q = p.compose_affine(a, b - a);
    if q.is_zero() {
        // p vanishes to rounding on [a, b]: the interval is too small to tell.
        return Ok(vec![0.5 * (a + b)]);
    }
    let n = q.degree().unwrap_or(0);
    let mut roots: Vec<f64> = bernstein_roots(&Bernstein::from_power(&q, n))?
        .into_iter()
        .map(|s| polish_in_t(p, (a + s * (b - a)).clamp(a, b), a, b))
        .collect();
    // A double root of the intended polynomial may be, for the coefficients as stored, a
    // near-miss whose minimum is within Horner's rounding bound: it is a root of p' at which p
    // vanishes to rounding (the criterion of `real_roots_in`).
    let dp = p.derivative();
    if !dp.is_zero() && dp.degree().unwrap_or(0) >= 1 {
        for x in bernstein_roots_in(&dp, a, b)? {
            if p.eval(x).abs() <= p.eval_error_bound(x) {
                roots.push(x);
            }
        }
    }
    roots.sort_by(f64::total_cmp);
    Ok(merge_numerical_roots(p, roots))
}

/// Merges sorted neighbours whose midpoint is still a numerical root of `p` (one multiple root
/// or an unresolvable cluster), keeping the member with the smaller residual.
fn merge_numerical_roots(p: &Polynomial, sorted: Vec<f64>) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(sorted.len());
    for x in sorted {
        if let Some(last) = out.last_mut() {
            let mid = 0.5 * (*last + x);
            if x - *last <= DEDUP_WIDTH * (1.0 + x.abs())
                || p.eval(mid).abs() <= p.eval_error_bound(mid)
            {
                if p.eval(x).abs() < p.eval(*last).abs() {
                    *last = x;
                }
                continue;
            }
        }
        out.push(x);
    }
    out
}

/// A few Newton steps on `p` itself: the change of variable to `[0, 1]` costs accuracy on wide
/// intervals. A step is kept only while it reduces `|p|` and stays in `[a, b]`.
fn polish_in_t(p: &Polynomial, mut x: f64, a: f64, b: f64) -> f64 {
    let mut best = p.eval(x).abs();
    for _ in 0..8 {
        let (v, d) = p.eval_with_derivative(x);
        if d == 0.0 || v == 0.0 {
            break;
        }
        let next = x - v / d;
        if !(a..=b).contains(&next) {
            break;
        }
        let value = p.eval(next).abs();
        if value >= best {
            break;
        }
        best = value;
        x = next;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Coefficients of one sign but for exact zeros at the ends: the ends are the only roots
    /// (the polynomial keeps one sign inside); anything else goes to the subdivision.
    #[test]
    fn zero_ends_with_one_sign_inside_are_the_only_roots() {
        let cases: [(&[f64], &[f64]); 5] = [
            (&[0.0, 1.0, 2.0, 0.5], &[0.0]),
            (&[-3.0, -1.0, -2.0, 0.0], &[1.0]),
            (&[0.0, 4.0, 1e-3, 0.0], &[0.0, 1.0]),
            (&[2.0, 1.0, 3.0], &[]),
            (&[0.0, -1.0], &[0.0]),
        ];
        for (c, want) in cases {
            let got = bernstein_roots(&Bernstein::new(c.to_vec())).unwrap();
            assert_eq!(got, want, "{c:?}");
            // Independently: no sign change at 999 points inside.
            let b = Bernstein::new(c.to_vec());
            let signs: Vec<bool> = (1..1000).map(|i| b.eval(i as f64 / 1000.0) > 0.0).collect();
            assert!(signs.iter().all(|&s| s == signs[0]), "{c:?}");
        }
        // A coefficient within rounding of zero, or a sign change, is left to the subdivision.
        assert!(only_end_roots(&[0.0, 1e-300, 1.0], 1e-20).is_none());
        assert!(only_end_roots(&[0.0, 1.0, -1.0, 2.0], 1e-20).is_none());
        assert!(only_end_roots(&[0.0, 0.0], 1e-20).is_none());
        let p = Polynomial::from_roots(&[0.0, 0.4, 3.0]);
        let c = Bernstein::from_power(&p, 3);
        assert!(only_end_roots(c.coeffs(), 1e-20).is_none());
        let got = bernstein_roots(&c).unwrap();
        assert_eq!(got.len(), 2);
        assert!(got[0] == 0.0 && (got[1] - 0.4).abs() < 1e-14, "{got:?}");
    }

    #[test]
    fn finds_simple_and_end_roots() {
        let p = Polynomial::from_roots(&[0.0, 0.3, 1.0, 2.0]);
        let r = bernstein_roots_in(&p, 0.0, 1.0).unwrap();
        assert_eq!(r.len(), 3, "{r:?}");
        assert!(r[0].abs() < 1e-15 && (r[1] - 0.3).abs() < 1e-14 && (r[2] - 1.0).abs() < 1e-14);
    }

    #[test]
    fn reports_double_root_once() {
        let p = Polynomial::from_roots(&[0.4, 0.4, 0.9]);
        let r = bernstein_roots_in(&p, 0.0, 1.0).unwrap();
        assert_eq!(r.len(), 2, "{r:?}");
        assert!((r[0] - 0.4).abs() < 1e-7 && (r[1] - 0.9).abs() < 1e-14);
    }

    #[test]
    fn double_root_blurred_into_a_near_miss() {
        // Regression (found by proptest): the stored coefficients turn the double root at
        // 0.92 into a minimum ~1e-14 above zero, within Horner's bound but above the Bernstein
        // form's own rounding level.
        let p = Polynomial::from_roots(&[
            0.016886577981135513,
            0.342783837638317,
            0.5046241779113043,
            0.7912837046169144,
            0.9217156081048709,
            0.9217156081048709,
        ]);
        let r = bernstein_roots_in(&p, 0.0, 1.0).unwrap();
        assert_eq!(r.len(), 5, "{r:?}");
        assert!((r[4] - 0.9217156081048709).abs() < 1e-6);
    }

    #[test]
    fn no_roots_when_positive() {
        let p = Polynomial::new(vec![1.0, 0.0, 0.0, 0.0, 1.0]);
        assert!(bernstein_roots_in(&p, -3.0, 3.0).unwrap().is_empty());
    }

    #[test]
    fn zero_polynomial_is_an_error() {
        assert_eq!(
            bernstein_roots(&Bernstein::new(vec![0.0, 0.0])),
            Err(RootsError::ZeroPolynomial)
        );
    }
}
