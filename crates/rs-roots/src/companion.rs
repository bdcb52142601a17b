//! Real roots in an interval from the eigenvalues of the companion matrix, hardened.

use nalgebra::DMatrix;
use nalgebra::linalg::Schur;

use crate::closed_form::quadratic_roots;
use crate::error::{RootsError, check_finite, check_interval};
use crate::isolate::bernstein_roots_in;
use crate::{Polynomial, bracket::itp};

/// Iterations of the Schur (QR) algorithm per matrix dimension before giving up.
const SCHUR_ITERATIONS_PER_DIM: usize = 40;
/// Taylor shifts tried when the Schur iteration fails to converge.
const RETRY_SHIFTS: [f64; 2] = [0.5, -0.3719];
/// Eigenvalues whose imaginary part exceeds this fraction of `1 + |z|` are not real candidates.
/// Generous because a root of multiplicity m is perturbed by about `eps^(1/m)`.
const IMAGINARY_CUTOFF: f64 = 1e-2;
/// Newton polishing iterations per candidate (linear convergence on multiple roots needs many).
const POLISH_ITERATIONS: usize = 100;

/// All real roots of `p` in the closed interval `[a, b]`, ascending, a multiple root once.
///
/// Method:
/// 1. Leading coefficients that are rounding noise on `[a, b]` are dropped
///    ([`Polynomial::trim_negligible`]); exact zero roots are deflated; degree <= 2 uses
///    [`quadratic_roots`].
/// 2. Otherwise the eigenvalues of the balanced companion matrix come from nalgebra's
///    `Schur::try_new` with a finite iteration limit. If it does not converge, the polynomial is
///    Taylor-shifted (`t = s + h`, `h = 0.5`, then `h = -0.3719`) and tried again; if that also
///    fails, [`bernstein_roots_in`] answers.
/// 3. Eigenvalues with a small imaginary part (double roots come back as complex pairs
///    `r +- 1e-8 i`) are polished by Newton's method and accepted only if the residual is
///    within Horner's rounding bound ([`Polynomial::eval_error_bound`]); a candidate just
///    outside `[a, b]` is clamped if the end point is itself a numerical root.
/// 4. Candidates whose midpoint is still a numerical root are one (multiple) root.
/// 5. A sign change of `p` between `a` (or `b`) and the nearest root found means a root was
///    missed; then [`bernstein_roots_in`] answers instead.
///
/// Terminates on every finite input.
///
/// # Errors
/// [`RootsError::NonFiniteCoefficient`], [`RootsError::InvalidInterval`] and
/// [`RootsError::ZeroPolynomial`].
///
/// # Examples
///
/// ```
/// use rs_roots::{real_roots_in, Polynomial};
/// let p = Polynomial::from_roots(&[-1.0, 0.25, 0.25, 0.75]);
/// let r = real_roots_in(&p, 0.0, 1.0).unwrap();
/// assert_eq!(r.len(), 2);
/// assert!((r[0] - 0.25).abs() < 1e-7 && (r[1] - 0.75).abs() < 1e-14);
/// ```
pub fn real_roots_in(p: &Polynomial, a: f64, b: f64) -> Result<Vec<f64>, RootsError> {
    roots_with_schur_limit(p, a, b, SCHUR_ITERATIONS_PER_DIM)
}

/// [`real_roots_in`] with the Schur iteration budget per matrix dimension as a parameter, so
/// tests can force the shifted retries and the fallback.
fn roots_with_schur_limit(
    p: &Polynomial,
    a: f64,
    b: f64,
    iterations_per_dim: usize,
) -> Result<Vec<f64>, RootsError> {
    check_finite(p.coeffs())?;
    check_interval(a, b)?;
    if p.is_zero() {
        return Err(RootsError::ZeroPolynomial);
    }
    let radius = a.abs().max(b.abs());
    let q = p.trim_negligible(radius);
    let c = q.coeffs();
    let zeros = c.iter().take_while(|&&x| x == 0.0).count();
    let reduced = Polynomial::new(c[zeros..].to_vec());
    let mut candidates: Vec<f64> = Vec::new();
    if zeros > 0 {
        candidates.push(0.0);
    }
    match reduced.degree() {
        None | Some(0) => {}
        Some(1) | Some(2) => {
            let rc = reduced.coeffs();
            candidates.extend(quadratic_roots(
                rc[0],
                rc[1],
                rc.get(2).copied().unwrap_or(0.0),
            ));
        }
        Some(_) => match eigen_candidates(&reduced, iterations_per_dim) {
            Some(z) => candidates.extend(z),
            None => return bernstein_roots_in(p, a, b),
        },
    }
    let mut accepted: Vec<f64> = candidates
        .into_iter()
        .filter_map(|x0| polish(p, x0))
        .filter_map(|x| into_interval(p, x, a, b))
        .collect();
    accepted.sort_by(f64::total_cmp);
    let roots = merge_clusters(p, accepted);
    if misses_end_root(p, &roots, a, b) {
        return bernstein_roots_in(p, a, b);
    }
    Ok(roots)
}

/// Real parts of the nearly-real eigenvalues of the companion matrix of `p` (degree >= 3,
/// `p(0) != 0`), with shifted retries; `None` if the Schur iteration never converged.
fn eigen_candidates(p: &Polynomial, iterations_per_dim: usize) -> Option<Vec<f64>> {
    if let Some(z) = companion_eigenvalues(p, iterations_per_dim) {
        return Some(z);
    }
    RETRY_SHIFTS.iter().find_map(|&h| {
        companion_eigenvalues(&p.taylor_shift(h), iterations_per_dim)
            .map(|z| z.into_iter().map(|x| x + h).collect())
    })
}

/// Eigenvalues `z` of the (balanced) companion matrix with `|Im z| <= cutoff (1 + |z|)`,
/// as their real parts.
fn companion_eigenvalues(p: &Polynomial, iterations_per_dim: usize) -> Option<Vec<f64>> {
    let c = p.coeffs();
    let n = c.len() - 1;
    let lead = c[n];
    let mut m = DMatrix::<f64>::zeros(n, n);
    for i in 1..n {
        m[(i, i - 1)] = 1.0;
    }
    for i in 0..n {
        m[(i, n - 1)] = -c[i] / lead;
    }
    if m.iter().any(|v| !v.is_finite()) {
        return None;
    }
    balance(&mut m);
    // nalgebra treats a limit of 0 as "no limit": never pass 0.
    let limit = (iterations_per_dim * n.max(4)).max(1);
    let schur = Schur::try_new(m, f64::EPSILON, limit)?;
    let (_, t) = schur.unpack();
    Some(
        quasi_triangular_eigenvalues(&t)
            .into_iter()
            .filter(|&(re, im)| {
                re.is_finite() && im.abs() <= IMAGINARY_CUTOFF * (1.0 + re.hypot(im))
            })
            .map(|(re, _)| re)
            .collect(),
    )
}

/// Eigenvalues `(re, im)` of a real quasi-upper-triangular matrix (1x1 and 2x2 diagonal
/// blocks). Computed here because nalgebra 0.35's `complex_eigenvalues` returns a NaN imaginary
/// part for a 2x2 block whose eigenvalues are real (seen on a double root).
fn quasi_triangular_eigenvalues(t: &DMatrix<f64>) -> Vec<(f64, f64)> {
    let n = t.nrows();
    let mut out = Vec::with_capacity(n);
    let mut i = 0;
    while i < n {
        if i + 1 < n && t[(i + 1, i)] != 0.0 {
            let (a, b, c, d) = (t[(i, i)], t[(i, i + 1)], t[(i + 1, i)], t[(i + 1, i + 1)]);
            let half_tr = 0.5 * (a + d);
            let disc = 0.25 * (a - d) * (a - d) + b * c;
            if disc >= 0.0 {
                let r = disc.sqrt();
                out.push((half_tr - r, 0.0));
                out.push((half_tr + r, 0.0));
            } else {
                let im = (-disc).sqrt();
                out.push((half_tr, im));
                out.push((half_tr, -im));
            }
            i += 2;
        } else {
            out.push((t[(i, i)], 0.0));
            i += 1;
        }
    }
    out
}

/// Diagonal similarity scaling by powers of two (Parlett-Reinsch, as in LAPACK's gebal) so
/// that rows and columns have comparable norms; bounded sweeps, never loops on overflow.
fn balance(m: &mut DMatrix<f64>) {
    let n = m.nrows();
    for _sweep in 0..64 {
        let mut converged = true;
        for i in 0..n {
            let mut col = 0.0;
            let mut row = 0.0;
            for j in 0..n {
                if j != i {
                    col += m[(j, i)].abs();
                    row += m[(i, j)].abs();
                }
            }
            if col == 0.0 || row == 0.0 || !col.is_finite() || !row.is_finite() {
                continue;
            }
            let s = col + row;
            let mut f = 1.0;
            let mut steps = 0;
            while col < row / 2.0 && steps < 1000 {
                col *= 2.0;
                row /= 2.0;
                f *= 2.0;
                steps += 1;
            }
            while col >= row * 2.0 && steps < 2000 {
                col /= 2.0;
                row *= 2.0;
                f /= 2.0;
                steps += 1;
            }
            if col + row < 0.95 * s {
                converged = false;
                for j in 0..n {
                    m[(j, i)] *= f;
                    m[(i, j)] /= f;
                }
            }
        }
        if converged {
            break;
        }
    }
}

/// Newton's method from `x0` until the residual is within rounding; `None` if it never gets
/// there (the candidate was the real part of a genuinely complex root).
fn polish(p: &Polynomial, x0: f64) -> Option<f64> {
    let mut x = x0;
    for _ in 0..POLISH_ITERATIONS {
        let (v, d) = p.eval_with_derivative(x);
        if v.abs() <= p.eval_error_bound(x) {
            return Some(x);
        }
        if d == 0.0 || !d.is_finite() {
            return None;
        }
        let next = x - v / d;
        if !next.is_finite() || next == x {
            break;
        }
        x = next;
    }
    (p.eval(x).abs() <= p.eval_error_bound(x)).then_some(x)
}

/// `x` if it lies in `[a, b]`; the nearer end if `x` is outside but that end is itself a
/// numerical root; otherwise `None`.
fn into_interval(p: &Polynomial, x: f64, a: f64, b: f64) -> Option<f64> {
    if (a..=b).contains(&x) {
        return Some(x);
    }
    let end = x.clamp(a, b);
    (p.eval(end).abs() <= p.eval_error_bound(end)).then_some(end)
}

/// Merges neighbours that cannot be told apart: their midpoint is still a numerical root.
fn merge_clusters(p: &Polynomial, sorted: Vec<f64>) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(sorted.len());
    for x in sorted {
        if let Some(&last) = out.last() {
            let mid = 0.5 * (last + x);
            if x == last || p.eval(mid).abs() <= p.eval_error_bound(mid) {
                // Keep the representative with the smaller residual.
                if p.eval(x).abs() < p.eval(last).abs() {
                    let idx = out.len() - 1;
                    out[idx] = x;
                }
                continue;
            }
        }
        out.push(x);
    }
    out
}

/// True if `p` changes sign between `a` and the first found root (or `b` and the last one,
/// or `a` and `b` when nothing was found): a root was missed.
fn misses_end_root(p: &Polynomial, roots: &[f64], a: f64, b: f64) -> bool {
    let definite = |t: f64| {
        let v = p.eval(t);
        if v.abs() > p.eval_error_bound(t) {
            v.signum()
        } else {
            0.0
        }
    };
    let changes = |s: f64, t: f64| {
        let (u, v) = (definite(s), definite(t));
        u * v < 0.0
            && itp(|x| p.eval(x), s.min(t), s.max(t), 0.0)
                .map(|r| p.eval(r).abs() <= 1e6 * p.eval_error_bound(r))
                .unwrap_or(false)
    };
    match (roots.first(), roots.last()) {
        (Some(&first), Some(&last)) => {
            changes(a, 0.5 * (a + first)) || changes(0.5 * (last + b), b)
        }
        _ => changes(a, b),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn balance_keeps_eigenvalues() {
        let p = Polynomial::from_roots(&[1e-3, 1.0, 1e3]);
        let r = real_roots_in(&p, -1e4, 1e4).unwrap();
        assert_eq!(r.len(), 3);
        for (x, e) in r.iter().zip([1e-3, 1.0, 1e3]) {
            assert!((x - e).abs() <= 1e-12 * e, "{x} vs {e}");
        }
    }

    #[test]
    fn double_root_in_a_two_by_two_block() {
        // Regression: nalgebra's complex_eigenvalues gave NaN for this block and lost the root.
        let p =
            Polynomial::from_roots(&[0.9901700020117117, 0.16458150284226603, 0.16458150284226603]);
        let r = real_roots_in(&p, 0.0, 1.0).unwrap();
        assert_eq!(r.len(), 2, "{r:?}");
        assert!((r[0] - 0.16458150284226603).abs() < 1e-7);
    }

    #[test]
    fn schur_failure_falls_back_to_isolation() {
        // One Schur iteration cannot converge on a degree-6 companion matrix: the shifted
        // retries fail too and the Bernstein isolator must answer, with the same roots.
        let p = Polynomial::from_roots(&[-0.5, 0.1, 0.35, 0.6, 0.6, 2.0]);
        assert!(eigen_candidates(&p, 1).is_none());
        let r = roots_with_schur_limit(&p, 0.0, 1.0, 1).unwrap();
        assert_eq!(r.len(), 3, "{r:?}");
        assert!((r[0] - 0.1).abs() < 1e-14 && (r[1] - 0.35).abs() < 1e-14);
        assert!((r[2] - 0.6).abs() < 1e-7);
        assert_eq!(real_roots_in(&p, 0.0, 1.0).unwrap().len(), 3);
    }

    #[test]
    fn shifted_retry_recovers_roots() {
        // The retry path on its own: eigenvalues of the shifted polynomial, shifted back.
        let p = Polynomial::from_roots(&[0.2, 0.45, 0.9]);
        let h = RETRY_SHIFTS[0];
        let mut z = companion_eigenvalues(&p.taylor_shift(h), SCHUR_ITERATIONS_PER_DIM).unwrap();
        z.iter_mut().for_each(|x| *x += h);
        z.sort_by(f64::total_cmp);
        for (x, e) in z.iter().zip([0.2, 0.45, 0.9]) {
            assert!((x - e).abs() < 1e-13);
        }
    }

    #[test]
    fn deflates_zero_roots() {
        let p = Polynomial::new(vec![0.0, 0.0, 0.0, -1.0, 1.0]); // t^3 (t - 1)
        assert_eq!(real_roots_in(&p, -1.0, 2.0).unwrap(), vec![0.0, 1.0]);
    }
}
