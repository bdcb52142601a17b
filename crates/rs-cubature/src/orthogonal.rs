//! A discrete orthonormal basis at the candidates: from the Vandermonde matrix `V` (`M x N`,
//! the scaled Legendre basis at `M` candidates), `Q = V R^{-1}` with (nearly) orthonormal
//! columns and the moments carried along, `b = R^{-T} m`, so that `V^T w = m` when
//! `Q^T w = b`.
//!
//! `R` comes from Cholesky factorisations of Gram matrices (Cholesky QR): the matrix products
//! run at the speed of a blocked `gemm`, several times faster than Householder QR on one
//! core. A second pass restores the orthogonality the first loses when `cond(V)` is large;
//! when a Gram matrix is numerically singular (`cond(V)` beyond about `1e8`) that pass
//! is shifted (`V^T V + s I`: the shifted Cholesky QR of Fukaya, Kannan, Nakatsukasa, Yamamoto
//! and Yanagisawa, 2020). The weights' accuracy does not rest on this factorisation: the
//! rule refines them against the residual in the basis itself, through [`Orthonormal::map`].

use nalgebra::{Cholesky, DMatrix, DVector};

/// Above this ratio of the largest to the least diagonal entry of a pass's factor (about
/// `cond` of what it factored), another pass is made: one pass leaves `Q^T Q - I` of about
/// `eps cond^2`, which then exceeds `1e-6`.
const NEXT_PASS_RATIO: f64 = 1e5;

/// Most Cholesky passes (shifted where the Gram matrix is numerically singular).
const MAX_PASSES: usize = 3;

/// `Q^T` and `b = R^{-T} m`, with `R^T` itself (for refinement).
pub(crate) struct Orthonormal {
    /// `Q^T`, `N x M`, one column per candidate.
    pub(crate) qt: DMatrix<f64>,
    /// `R^{-T} m`.
    pub(crate) b: DVector<f64>,
    /// `R^T`, `N x N`, lower triangular.
    rt: DMatrix<f64>,
}

impl Orthonormal {
    /// `R^{-T} v`: a vector of moments (or of residuals of moments) in the orthonormal basis.
    pub(crate) fn map(&self, v: &[f64]) -> DVector<f64> {
        let v = DVector::from_column_slice(v);
        self.rt
            .solve_lower_triangular(&v)
            .unwrap_or_else(|| DVector::zeros(v.len()))
    }
}

/// The orthonormalisation of `vt = V^T` (`N x M`, one column per candidate), or `None` if the
/// candidates do not resolve the basis (a factor not invertible).
pub(crate) fn orthonormalise(vt: DMatrix<f64>, m: &[f64]) -> Option<Orthonormal> {
    let n = vt.nrows();
    let mut qt = vt;
    let mut rt = DMatrix::<f64>::identity(n, n);
    for _ in 0..MAX_PASSES {
        let gram = &qt * qt.transpose();
        let (l, shifted) = match Cholesky::new(gram.clone()) {
            Some(c) => (c.unpack(), false),
            None => (shifted_cholesky(gram, qt.ncols())?, true),
        };
        let l_inv = l.solve_lower_triangular(&DMatrix::identity(n, n))?;
        qt = &l_inv * qt;
        rt = &rt * &l;
        let d = l.diagonal();
        if !shifted && d.max() <= NEXT_PASS_RATIO * d.min() {
            break;
        }
    }
    // A factor with a zero or non-finite diagonal entry: the candidates do not resolve the
    // basis (a shifted factor is always invertible, so this is rank deficiency or overflow).
    let d = rt.diagonal();
    if !d.iter().all(|v| v.is_finite() && *v > 0.0) {
        return None;
    }
    let b = rt.solve_lower_triangular(&DVector::from_column_slice(m))?;
    Some(Orthonormal { qt, b, rt })
}

/// The Cholesky factor of `gram + s I` with the shift of shifted Cholesky QR,
/// `s = 11 (M N + N (N + 1)) eps ||V||^2` (`||V||^2` bounded by the trace of the Gram matrix).
fn shifted_cholesky(mut gram: DMatrix<f64>, m: usize) -> Option<DMatrix<f64>> {
    let n = gram.nrows();
    let shift = 11.0 * ((m * n + n * (n + 1)) as f64) * f64::EPSILON * gram.trace();
    for i in 0..n {
        gram[(i, i)] += shift;
    }
    Cholesky::new(gram).map(Cholesky::unpack)
}
