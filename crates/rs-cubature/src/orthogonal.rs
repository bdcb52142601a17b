//! A discrete orthonormal basis at the candidates: from the Vandermonde matrix `V` (`M x N`,
//! the scaled Legendre basis at `M` candidates), `Q = V R^{-1}` with orthonormal columns and
//! the moments carried along, `b = R^{-T} m`, so that `V^T w = m` exactly when `Q^T w = b`.
//!
//! `R` comes from Cholesky factorisations of Gram matrices, twice (CholeskyQR2: the second
//! pass restores the orthogonality the first loses, to rounding, when `cond(V) < 1e7`):
//! matrix products run at the speed of a blocked `gemm`, several times faster than
//! Householder QR on one core. A Vandermonde matrix too ill-conditioned for that goes
//! through Householder QR first (nalgebra's), then one Cholesky pass.

use nalgebra::{Cholesky, DMatrix, DVector};

/// The smallest ratio of the least to the largest diagonal entry of the first Cholesky
/// factor (about `1 / cond(V)`) for which CholeskyQR2 alone is used.
const CHOLESKY_MIN_RATIO: f64 = 1e-7;

/// The smallest ratio of the least to the largest `|R_ii|` of the Householder factor for which
/// the candidates are taken to resolve the polynomials (`cond(V)` up to about `1e12`).
const RESOLVED_MIN_RATIO: f64 = 1e-12;

/// `(Q^T, R^{-T} m)` from `vt = V^T` (`N x M`, one column per candidate), or `None` if the
/// candidates do not resolve the basis (`V` numerically rank deficient).
pub(crate) fn orthonormalise(vt: DMatrix<f64>, m: &[f64]) -> Option<(DMatrix<f64>, DVector<f64>)> {
    let b = DVector::from_column_slice(m);
    match cholesky_pass(&vt, &b, CHOLESKY_MIN_RATIO) {
        Some((q1, b1)) => cholesky_pass(&q1, &b1, 0.5),
        None => {
            let (q1, b1) = householder_pass(vt, b)?;
            cholesky_pass(&q1, &b1, 0.5)
        }
    }
}

/// One CholeskyQR step on the rows of `at` (`A^T`): `G = A^T A = L L^T`, returns
/// `(L^{-1} A^T, L^{-1} b)`, or `None` if `G` is not numerically positive definite or
/// `min L_ii / max L_ii < min_ratio`.
fn cholesky_pass(
    at: &DMatrix<f64>,
    b: &DVector<f64>,
    min_ratio: f64,
) -> Option<(DMatrix<f64>, DVector<f64>)> {
    let n = at.nrows();
    let gram = at * at.transpose();
    let l = Cholesky::new(gram)?.unpack();
    let diag = l.diagonal();
    let (lo, hi) = (diag.min(), diag.max());
    if !(lo > min_ratio * hi) {
        return None;
    }
    let l_inv = l.solve_lower_triangular(&DMatrix::identity(n, n))?;
    Some((&l_inv * at, &l_inv * b))
}

/// Householder QR of `V = vt^T`: returns `(R^{-T} V^T, R^{-T} b)`, or `None` if
/// `min |R_ii| / max |R_ii| < RESOLVED_MIN_RATIO`.
fn householder_pass(vt: DMatrix<f64>, b: DVector<f64>) -> Option<(DMatrix<f64>, DVector<f64>)> {
    let r = vt.transpose().qr().r();
    let diag = r.diagonal().abs();
    let (lo, hi) = (diag.min(), diag.max());
    if !(lo > RESOLVED_MIN_RATIO * hi) {
        return None;
    }
    let rt = r.transpose();
    let q1 = rt.solve_lower_triangular(&vt)?;
    let b1 = rt.solve_lower_triangular(&b)?;
    Some((q1, b1))
}
