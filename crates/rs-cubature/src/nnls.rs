//! Non-negative least squares, `min ||A x - b||` over `x >= 0`, by the active-set method of
//! Lawson and Hanson (*Solving Least Squares Problems*, 1974, ch. 23), with the least-squares
//! problem of the passive set kept as a QR factorisation updated column by column.
//!
//! `A` has `n` rows and `m >= n` columns (here: the discrete orthonormal basis at the
//! candidate points, one column per candidate). The passive set never holds more than `n`
//! columns, so a solution has at most `n` positive entries: the Caratheodory bound.

/// One dot product, in eight independent sums (vectorised).
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for k in 0..8 {
            acc[k] += x[k] * y[k];
        }
    }
    let mut tail = 0.0;
    for (x, y) in ra.iter().zip(rb) {
        tail += x * y;
    }
    acc.iter().sum::<f64>() + tail
}

/// `y += alpha x`.
fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += alpha * xi;
    }
}

/// The QR factorisation `A_P = Q R` of the passive columns, with `Q` (`n x n`, orthogonal) and
/// `Q^T b` kept up to date as columns come and go.
///
/// Invariants: `q` is orthogonal (column-major, `n x n`); the first `cols.len()` columns of
/// `r` (column-major, `n x n`) are upper triangular and `A[:, cols[i]] = Q r[:, i]`;
/// `qtb = Q^T b`.
struct PassiveQr {
    n: usize,
    q: Vec<f64>,
    r: Vec<f64>,
    qtb: Vec<f64>,
    cols: Vec<usize>,
    scratch: Vec<f64>,
}

impl PassiveQr {
    fn new(n: usize, b: &[f64]) -> Self {
        let mut q = vec![0.0; n * n];
        for i in 0..n {
            q[i * n + i] = 1.0;
        }
        Self {
            n,
            q,
            r: vec![0.0; n * n],
            qtb: b.to_vec(),
            cols: Vec::with_capacity(n),
            scratch: vec![0.0; n],
        }
    }

    fn len(&self) -> usize {
        self.cols.len()
    }

    /// Appends column `a` (candidate `j`) unless it is numerically in the span of the passive
    /// columns (`false` then: `|R_kk| <= 1e-12 |a|`) or the set is full.
    fn insert(&mut self, a: &[f64], j: usize) -> bool {
        let (n, k) = (self.n, self.cols.len());
        if k == n {
            return false;
        }
        // c = Q^T a.
        let mut c = vec![0.0; n];
        for (i, ci) in c.iter_mut().enumerate() {
            *ci = dot(&self.q[i * n..(i + 1) * n], a);
        }
        let tail = c[k..].iter().map(|x| x * x).sum::<f64>().sqrt();
        let size = dot(a, a).sqrt();
        if !(tail > 1e-12 * size) {
            return false;
        }
        // A Householder reflection H = I - 2 v v^T / (v^T v) on rows k.. maps c[k..] to
        // (alpha, 0, ...); Q <- Q H keeps A_P = Q R for the old columns (H fixes rows < k of
        // their R, which are zero below).
        let alpha = if c[k] > 0.0 { -tail } else { tail };
        let mut v = c[k..].to_vec();
        v[0] -= alpha;
        let vv = dot(&v, &v);
        if vv > 0.0 {
            // s = Q[:, k..] v; Q[:, k + l] -= (2 v_l / vv) s.
            let s = &mut self.scratch;
            s.fill(0.0);
            for (l, &vl) in v.iter().enumerate() {
                let col = (k + l) * n;
                axpy(vl, &self.q[col..col + n], s);
            }
            for (l, &vl) in v.iter().enumerate() {
                let col = (k + l) * n;
                axpy(-2.0 * vl / vv, s, &mut self.q[col..col + n]);
            }
            let t = dot(&v, &self.qtb[k..]);
            axpy(-2.0 * t / vv, &v, &mut self.qtb[k..]);
        }
        let col = &mut self.r[k * n..(k + 1) * n];
        col[..k].copy_from_slice(&c[..k]);
        col[k] = alpha;
        col[k + 1..].fill(0.0);
        self.cols.push(j);
        true
    }

    /// Removes the passive column at position `pos`, restoring the triangle by Givens
    /// rotations of rows `pos..` (applied to `R`, `Q^T b` and `Q`).
    fn remove(&mut self, pos: usize) {
        let n = self.n;
        let k = self.cols.len();
        self.cols.remove(pos);
        self.r.copy_within((pos + 1) * n..k * n, pos * n);
        for i in pos..k - 1 {
            // Column i now has a subdiagonal entry at row i + 1.
            let (a, b) = (self.r[i * n + i], self.r[i * n + i + 1]);
            let h = a.hypot(b);
            if h == 0.0 {
                continue;
            }
            let (c, s) = (a / h, b / h);
            for col in i..k - 1 {
                let (x, y) = (self.r[col * n + i], self.r[col * n + i + 1]);
                self.r[col * n + i] = c * x + s * y;
                self.r[col * n + i + 1] = -s * x + c * y;
            }
            self.r[i * n + i + 1] = 0.0;
            let (x, y) = (self.qtb[i], self.qtb[i + 1]);
            self.qtb[i] = c * x + s * y;
            self.qtb[i + 1] = -s * x + c * y;
            let (left, right) = self.q.split_at_mut((i + 1) * n);
            let (qi, qj) = (&mut left[i * n..], &mut right[..n]);
            for (x, y) in qi.iter_mut().zip(qj.iter_mut()) {
                let (a, b) = (*x, *y);
                *x = c * a + s * b;
                *y = -s * a + c * b;
            }
        }
    }

    /// The least-squares solution on the passive columns: `R z = (Q^T b)[..k]`.
    fn solve(&self, z: &mut Vec<f64>) {
        let (n, k) = (self.n, self.cols.len());
        z.clear();
        z.extend_from_slice(&self.qtb[..k]);
        for i in (0..k).rev() {
            let zi = z[i] / self.r[i * n + i];
            z[i] = zi;
            for (l, zl) in z[..i].iter_mut().enumerate() {
                *zl -= self.r[i * n + l] * zi;
            }
        }
    }
}

/// The passive columns and their positive values, and why the iteration stopped.
#[derive(Clone, Debug)]
pub(crate) struct NnlsSolution {
    /// Candidate (column) indices.
    pub(crate) columns: Vec<usize>,
    /// Their values, all `> 0`.
    pub(crate) values: Vec<f64>,
}

/// Lawson-Hanson NNLS for `A` (`n x m`, column-major in `a`) and `b`, stopped when
/// `||A x - b|| <= residual_tolerance`, at optimality, or after `3 n + 100` column
/// additions (each followed by at most `n` removal steps): the work is bounded.
pub(crate) fn nnls(a: &[f64], n: usize, b: &[f64], residual_tolerance: f64) -> NnlsSolution {
    let m = a.len() / n;
    let column = |j: usize| &a[j * n..(j + 1) * n];
    let col_norm_max = (0..m)
        .map(|j| dot(column(j), column(j)))
        .fold(0.0f64, f64::max)
        .sqrt();
    let b_norm = dot(b, b).sqrt();
    // Gradients below this are rounding: the components of A^T r carry errors of about
    // eps |a_j| |r| per term.
    let gradient_floor = 16.0 * f64::EPSILON * col_norm_max * b_norm.max(f64::MIN_POSITIVE);
    let mut qr = PassiveQr::new(n, b);
    let mut passive = vec![false; m];
    let mut blocked = vec![false; m];
    let mut x: Vec<f64> = Vec::with_capacity(n); // values of the passive columns, in order
    let mut z = Vec::with_capacity(n);
    let mut r = b.to_vec();
    let mut g = vec![0.0; m];
    let cap = 3 * n + 100;
    for _ in 0..cap {
        if dot(&r, &r).sqrt() <= residual_tolerance {
            break;
        }
        for (j, gj) in g.iter_mut().enumerate() {
            *gj = if passive[j] || blocked[j] {
                f64::NEG_INFINITY
            } else {
                dot(column(j), &r)
            };
        }
        let Some((j, &gj)) = g.iter().enumerate().max_by(|p, q| p.1.total_cmp(q.1)) else {
            break;
        };
        if !(gj > gradient_floor) {
            break;
        }
        if !qr.insert(column(j), j) {
            blocked[j] = true;
            continue;
        }
        passive[j] = true;
        x.push(0.0);
        // Inner loop: move towards the unconstrained solution on the passive set until it is
        // positive, dropping the columns that reach zero.
        let mut entering = true;
        for _ in 0..=n {
            qr.solve(&mut z);
            if z.iter().all(|&v| v > 0.0) {
                x.copy_from_slice(&z);
                break;
            }
            if entering && z[z.len() - 1] <= 0.0 {
                // Rounding made the entering column useless: take it out again.
                let last = qr.len() - 1;
                passive[qr.cols[last]] = false;
                blocked[qr.cols[last]] = true;
                qr.remove(last);
                x.pop();
                break;
            }
            entering = false;
            let mut alpha = 1.0f64;
            for (&xi, &zi) in x.iter().zip(&z) {
                if zi <= 0.0 {
                    alpha = alpha.min(xi / (xi - zi));
                }
            }
            for (xi, &zi) in x.iter_mut().zip(&z) {
                *xi += alpha * (zi - *xi);
            }
            for pos in (0..x.len()).rev() {
                if x[pos] <= 0.0 || (z[pos] <= 0.0 && x[pos] <= f64::EPSILON * x[pos].abs()) {
                    passive[qr.cols[pos]] = false;
                    qr.remove(pos);
                    x.remove(pos);
                }
            }
            if x.is_empty() {
                break;
            }
        }
        // A removed or rejected column may be worth trying again once the set has changed.
        if qr.len() > 0 {
            blocked.iter_mut().for_each(|b| *b = false);
        }
        r.copy_from_slice(b);
        for (&j, &xj) in qr.cols.iter().zip(&x) {
            axpy(-xj, column(j), &mut r);
        }
    }
    let (columns, values) = qr
        .cols
        .iter()
        .zip(&x)
        .filter(|&(_, &v)| v > 0.0)
        .map(|(&j, &v)| (j, v))
        .unzip();
    NnlsSolution { columns, values }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A right-hand side made from known non-negative weights is reached exactly.
    #[test]
    fn matches_a_consistent_problem_with_a_positive_solution() {
        // A 3 x 6, b = A x* with x* >= 0 having three positive entries.
        let a = [
            1.0, 0.2, 0.1, //
            0.3, 1.0, 0.0, //
            0.5, 0.5, 0.5, //
            0.0, 0.1, 1.0, //
            0.9, 0.1, 0.3, //
            0.2, 0.8, 0.7,
        ];
        let xs = [0.0, 0.7, 0.0, 1.3, 0.0, 0.4];
        let mut b = [0.0; 3];
        for (j, &xj) in xs.iter().enumerate() {
            axpy(xj, &a[3 * j..3 * j + 3], &mut b);
        }
        let s = nnls(&a, 3, &b, 1e-14);
        assert!(s.columns.len() <= 3);
        assert!(s.values.iter().all(|&v| v > 0.0));
        let mut got = [0.0; 3];
        for (&j, &v) in s.columns.iter().zip(&s.values) {
            axpy(v, &a[3 * j..3 * j + 3], &mut got);
        }
        for k in 0..3 {
            assert!((got[k] - b[k]).abs() < 1e-13, "{got:?} vs {b:?}");
        }
    }

    #[test]
    fn an_unreachable_right_hand_side_gets_the_nearest_point_of_the_cone() {
        // Columns e1 and e2 in R^2, b = (1, -1): the best x >= 0 is (1, 0).
        let a = [1.0, 0.0, 0.0, 1.0];
        let s = nnls(&a, 2, &[1.0, -1.0], 1e-14);
        assert_eq!(s.columns, vec![0]);
        assert!((s.values[0] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn removals_keep_the_factorisation() {
        let n = 4;
        let a: Vec<f64> = (0..n * 7)
            .map(|i| ((i * 37 % 11) as f64 - 5.0) / 3.0)
            .collect();
        let mut qr = PassiveQr::new(n, &[1.0, 2.0, 3.0, 4.0]);
        for j in [0, 3, 5, 6] {
            assert!(qr.insert(&a[j * n..(j + 1) * n], j));
        }
        qr.remove(1);
        qr.remove(0);
        // Q R reproduces the remaining columns.
        for (pos, &j) in qr.cols.iter().enumerate() {
            for i in 0..n {
                let v: f64 = (0..n).map(|l| qr.q[l * n + i] * qr.r[pos * n + l]).sum();
                assert!((v - a[j * n + i]).abs() < 1e-13);
            }
        }
    }
}
