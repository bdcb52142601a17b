//! Non-negative least squares, `min ||A x - b||` over `x >= 0`, by the active-set method of
//! Lawson and Hanson (*Solving Least Squares Problems*, 1974, ch. 23), with the least-squares
//! problem of the passive set kept as a QR factorisation updated column by column.
//!
//! `A` has `n` rows and `m >= n` columns (here: the discrete orthonormal basis at the
//! candidate points, one column per candidate). The passive set never holds more than `n`
//! columns, so a solution has at most `n` positive entries: the Caratheodory bound.

use nalgebra::{DMatrix, DMatrixViewMut};

/// One dot product, in eight independent sums (vectorised): [`dots`] of one vector.
#[inline(always)]
pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    dots([a], b)[0]
}

/// Vectors [`dots_into`] multiplies side by side.
const DOT_LANES: usize = 8;

/// `out(t, x(t) . v)` for `t` in `0..count`, in order, each bit for bit [`dot`]'s: eight of
/// the vectors side by side ([`dots`]), then four, then one at a time. One dot product alone
/// is a single chain of additions (its eight sums fill one vector register), so it waits on
/// each addition; several side by side keep the adder busy.
#[inline(always)]
fn dots_into<'x>(
    count: usize,
    x: impl Fn(usize) -> &'x [f64],
    v: &[f64],
    mut out: impl FnMut(usize, f64),
) {
    let t = dots_by::<DOT_LANES, _, _>(0, count, &x, v, &mut out);
    let t = dots_by::<4, _, _>(t, count, &x, v, &mut out);
    dots_by::<1, _, _>(t, count, &x, v, &mut out);
}

/// [`dots_into`] from `t` on, `L` vectors side by side while `L` are left; returns where it
/// stopped.
#[inline(always)]
fn dots_by<'x, const L: usize, X: Fn(usize) -> &'x [f64], O: FnMut(usize, f64)>(
    mut t: usize,
    count: usize,
    x: &X,
    v: &[f64],
    out: &mut O,
) -> usize {
    while t + L <= count {
        let group: [&[f64]; L] = std::array::from_fn(|l| x(t + l));
        for (l, d) in dots(group, v).into_iter().enumerate() {
            out(t + l, d);
        }
        t += L;
    }
    t
}

/// `products[e][i] = q_i . columns[e]` for the first `k0` columns `q_i` of `q` (`n` rows,
/// column-major), each bit for bit [`dot`]'s (the same [`dots`], products commute): one pass
/// over `q`, each of its columns multiplied by all of `columns` ([`dots_into`], several side
/// by side) while it is in the cache, with the best instruction set at hand (chosen at run
/// time).
fn head_products(q: &[f64], n: usize, k0: usize, columns: &[&[f64]], products: &mut [Vec<f64>]) {
    pulp::Arch::new().dispatch(HeadProducts {
        q: &q[..k0 * n],
        n,
        columns,
        products,
    });
}

/// [`head_products`] as an operation `pulp` compiles for each instruction set.
struct HeadProducts<'a> {
    q: &'a [f64],
    n: usize,
    columns: &'a [&'a [f64]],
    products: &'a mut [Vec<f64>],
}

impl pulp::WithSimd for HeadProducts<'_> {
    type Output = ();
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Self {
            q,
            n,
            columns,
            products,
        } = self;
        for (i, qi) in q.chunks_exact(n.max(1)).enumerate() {
            dots_into(columns.len(), |e| columns[e], qi, |e, d| products[e][i] = d);
        }
    }
}

/// The dot products of `L` vectors `x` (each as long as `v`) with `v`, side by side, each in
/// eight independent sums over the whole eights of entries, then the rest in order: the one
/// definition of the products' rounding (several vectors side by side keep the adder busy).
#[inline(always)]
fn dots<const L: usize>(x: [&[f64]; L], v: &[f64]) -> [f64; L] {
    debug_assert!(x.iter().all(|x| x.len() == v.len()));
    let whole = v.len() / 8 * 8;
    let heads = x.map(|x| &x[..whole]);
    let mut acc = [[0.0f64; 8]; L];
    for (s, y) in v[..whole].chunks_exact(8).enumerate() {
        for (acc, x) in acc.iter_mut().zip(&heads) {
            let x = &x[8 * s..8 * s + 8];
            for k in 0..8 {
                acc[k] += x[k] * y[k];
            }
        }
    }
    let mut out = [0.0; L];
    for ((o, acc), x) in out.iter_mut().zip(&acc).zip(&x) {
        let mut tail = 0.0;
        for (a, b) in x[whole..].iter().zip(&v[whole..]) {
            tail += a * b;
        }
        *o = acc.iter().sum::<f64>() + tail;
    }
    out
}

/// `y += alpha x`.
#[inline(always)]
fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    for (yi, xi) in y.iter_mut().zip(x) {
        *yi += alpha * xi;
    }
}

/// `y += alpha_t x(t)` for `t` in `0..count`, in order, bit for bit [`axpy`] after [`axpy`]:
/// each entry of `y` takes the same additions in the same order, four vectors at a time in
/// one pass over `y` (a quarter of its loads and stores).
#[inline(always)]
fn axpys<'x>(
    count: usize,
    alpha: impl Fn(usize) -> f64,
    x: impl Fn(usize) -> &'x [f64],
    y: &mut [f64],
) {
    let len = y.len();
    let mut t = 0;
    while t + 4 <= count {
        let (a0, a1, a2, a3) = (alpha(t), alpha(t + 1), alpha(t + 2), alpha(t + 3));
        let (x0, x1, x2, x3) = (
            &x(t)[..len],
            &x(t + 1)[..len],
            &x(t + 2)[..len],
            &x(t + 3)[..len],
        );
        for i in 0..len {
            let mut v = y[i];
            v += a0 * x0[i];
            v += a1 * x1[i];
            v += a2 * x2[i];
            v += a3 * x3[i];
            y[i] = v;
        }
        t += 4;
    }
    while t < count {
        axpy(alpha(t), x(t), y);
        t += 1;
    }
}

/// A Householder reflection of [`PassiveQr::reflection`]: the new diagonal entry of `R`,
/// `v` on rows `k..` and `v^T v`.
struct Reflection {
    alpha: f64,
    v: Vec<f64>,
    vv: f64,
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

    /// Appends the columns `a_j` (column `j` of `a`, `n` rows, column-major) of `entering` in
    /// order, each as [`PassiveQr::insert_with`] appends it; `added(j, inserted)` reports each.
    ///
    /// Each `Q^T a_j` is the one inserting the columns one by one computes, bit for bit, with
    /// less memory traffic: an insert changes only the columns of `Q` from its position on, so
    /// the entries of every entering column against the columns before the first insert's
    /// position `k0` are taken in one pass over them ([`head_products`]), and only the rest
    /// after each insert. At degree 40 `Q` holds `861^2` values (6 MB, past the caches): one
    /// pass over them instead of one per entering column.
    #[inline(always)]
    fn insert_all(&mut self, a: &[f64], entering: &[usize], mut added: impl FnMut(usize, bool)) {
        let (n, k0) = (self.n, self.cols.len());
        let column = |j: usize| &a[j * n..(j + 1) * n];
        let columns: Vec<&[f64]> = entering.iter().map(|&j| column(j)).collect();
        let mut products = vec![vec![0.0; n]; entering.len()];
        head_products(&self.q, n, k0, &columns, &mut products);
        for ((&j, &a_j), c) in entering.iter().zip(&columns).zip(products) {
            let inserted = self.insert_with(a_j, j, k0, c);
            added(j, inserted);
        }
    }

    /// [`PassiveQr::insert_all`] with the reflections gathered and applied to `Q` together:
    /// every entering column's `Q^T a_j` is taken against the `Q` before the call in one pass
    /// ([`head_products`] over all of `Q`), each column then reflected by the reflections of
    /// the columns inserted before it (short vectors), and `Q` updated once at the end by the
    /// compact WY form of their product, `H_1 .. H_b = I - V T V^T` (Schreiber and Van Loan):
    /// two matrix products at `gemm`'s speed instead of two passes over `Q` per column (at
    /// degree 40, `Q` is 6 MB: the inserts were 330-340 ms of a 450 ms NNLS). The same
    /// factorisation in exact arithmetic; rounded differently, so only the chord formula's
    /// compression, whose rules are new, takes it.
    #[inline(always)]
    fn insert_all_blocked(
        &mut self,
        a: &[f64],
        entering: &[usize],
        mut added: impl FnMut(usize, bool),
    ) {
        let (n, k0) = (self.n, self.cols.len());
        let column = |j: usize| &a[j * n..(j + 1) * n];
        let columns: Vec<&[f64]> = entering.iter().map(|&j| column(j)).collect();
        let mut products = vec![vec![0.0; n]; entering.len()];
        head_products(&self.q, n, n, &columns, &mut products);
        // The reflections made here: (first row k, v on rows k.., tau = 2 / v^T v).
        let mut reflections: Vec<(usize, Vec<f64>, f64)> = Vec::new();
        for ((&j, &a_j), mut c) in entering.iter().zip(&columns).zip(products) {
            for (k, v, tau) in &reflections {
                let t = tau * dot(v, &c[*k..]);
                axpy(-t, v, &mut c[*k..]);
            }
            let k = self.cols.len();
            let Some(h) = self.reflection(a_j, &c) else {
                added(j, false);
                continue;
            };
            self.append(j, &c, &h);
            if h.vv > 0.0 {
                reflections.push((k, h.v, 2.0 / h.vv));
            }
            added(j, true);
        }
        self.reflect_q(k0, &reflections);
    }

    /// `Q <- Q H_1 .. H_b` for the reflections `(k_i, v_i, tau_i)`, `H_i = I - tau_i v_i
    /// v_i^T` on rows `k_i..` (all at or after `k0`), by the compact WY form `I - V T V^T`:
    /// `V` holds the `v_i` (zero above row `k_i`), `T` is upper triangular with `T_ii =
    /// tau_i` and `T[..i, i] = -tau_i T[..i, ..i] V[:, ..i]^T v_i`.
    fn reflect_q(&mut self, k0: usize, reflections: &[(usize, Vec<f64>, f64)]) {
        let (n, b) = (self.n, reflections.len());
        if b == 0 || k0 >= n {
            return;
        }
        let rows = n - k0;
        let mut v = DMatrix::<f64>::zeros(rows, b);
        for (i, (k, vi, _)) in reflections.iter().enumerate() {
            v.view_mut((k - k0, i), (vi.len(), 1)).copy_from_slice(vi);
        }
        let mut t = DMatrix::<f64>::zeros(b, b);
        for (i, (_, _, tau)) in reflections.iter().enumerate() {
            t[(i, i)] = *tau;
            if i > 0 {
                let vtv = v.columns(0, i).tr_mul(&v.column(i));
                let z = t.view((0, 0), (i, i)) * vtv * (-tau);
                t.view_mut((0, i), (i, 1)).copy_from(&z);
            }
        }
        let mut q = DMatrixViewMut::from_slice(&mut self.q, n, n);
        let mut tail = q.columns_range_mut(k0..);
        let w = &tail * &v * &t;
        tail.gemm(-1.0, &w, &v.transpose(), 1.0);
    }

    /// [`PassiveQr::insert_with`] with no entry of `Q^T a` known.
    #[cfg(test)]
    fn insert(&mut self, a: &[f64], j: usize) -> bool {
        self.insert_with(a, j, 0, vec![0.0; self.n])
    }

    /// Appends column `a` (candidate `j`) unless it is numerically in the span of the passive
    /// columns (`false` then: `|R_kk| <= 1e-12 |a|`) or the set is full; `c` (`n` entries)
    /// holds `(Q^T a)[..known]` already.
    #[inline(always)]
    fn insert_with(&mut self, a: &[f64], j: usize, known: usize, mut c: Vec<f64>) -> bool {
        let (n, k) = (self.n, self.cols.len());
        if k == n {
            return false;
        }
        // c = Q^T a (its first `known` entries given).
        let q = &self.q;
        dots_into(
            n - known.min(n),
            |t| &q[(known + t) * n..(known + t + 1) * n],
            a,
            |t, d| c[known + t] = d,
        );
        let Some(h) = self.reflection(a, &c) else {
            return false;
        };
        let (v, vv) = (&h.v, h.vv);
        if vv > 0.0 {
            // s = Q[:, k..] v; Q[:, k + l] -= (2 v_l / vv) s.
            let s = &mut self.scratch;
            s.fill(0.0);
            let q = &self.q;
            axpys(v.len(), |l| v[l], |l| &q[(k + l) * n..(k + l + 1) * n], s);
            for (l, &vl) in v.iter().enumerate() {
                let col = (k + l) * n;
                axpy(-2.0 * vl / vv, s, &mut self.q[col..col + n]);
            }
        }
        self.append(j, &c, &h);
        true
    }

    /// The Householder reflection `H = I - 2 v v^T / (v^T v)` on rows `k..` (`k` the passive
    /// columns) that maps `c[k..]` to `(alpha, 0, ..)`, for `c = Q^T a`; `Q <- Q H` keeps
    /// `A_P = Q R` for the passive columns (`H` fixes rows `< k` of their `R`, which are zero
    /// below). `None` when the set is full or `a` is numerically in the span of the passive
    /// columns (`|alpha| <= 1e-12 |a|`).
    #[inline(always)]
    fn reflection(&self, a: &[f64], c: &[f64]) -> Option<Reflection> {
        let k = self.cols.len();
        if k >= self.n {
            return None;
        }
        let tail = c[k..].iter().map(|x| x * x).sum::<f64>().sqrt();
        let size = dot(a, a).sqrt();
        if tail.is_nan() || tail <= 1e-12 * size {
            return None;
        }
        let alpha = if c[k] > 0.0 { -tail } else { tail };
        let mut v = c[k..].to_vec();
        v[0] -= alpha;
        let vv = dot(&v, &v);
        Some(Reflection { alpha, v, vv })
    }

    /// Appends candidate `j` with `c = Q^T a` under the reflection `h` (made for it by
    /// [`PassiveQr::reflection`]): `Q^T b` reflected, `R`'s new column `(c[..k], alpha, 0..)`.
    /// `Q` itself is the caller's to reflect (at once, or with others).
    #[inline(always)]
    fn append(&mut self, j: usize, c: &[f64], h: &Reflection) {
        let (n, k) = (self.n, self.cols.len());
        if h.vv > 0.0 {
            let t = dot(&h.v, &self.qtb[k..]);
            axpy(-2.0 * t / h.vv, &h.v, &mut self.qtb[k..]);
        }
        let col = &mut self.r[k * n..(k + 1) * n];
        col[..k].copy_from_slice(&c[..k]);
        col[k] = h.alpha;
        col[k + 1..].fill(0.0);
        self.cols.push(j);
    }

    /// Removes the passive column at position `pos`, restoring the triangle by Givens
    /// rotations of rows `pos..` (applied to `R`, `Q^T b` and `Q`).
    #[inline(always)]
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
    #[inline(always)]
    fn solve(&self, z: &mut Vec<f64>) {
        self.back_substitute(&self.qtb, z);
    }

    /// `z = R^{-1} c[..k]` for the passive triangle `R`.
    #[inline(always)]
    fn back_substitute(&self, c: &[f64], z: &mut Vec<f64>) {
        let (n, k) = (self.n, self.cols.len());
        z.clear();
        z.extend_from_slice(&c[..k]);
        let r = &self.r;
        // Columns i = k - 1 down to 0: z_i = z_i / r_ii, then z_l -= r_li z_i for l < i. By
        // blocks of four columns: their triangle first, then each entry above it takes the
        // four columns' updates in the same order, in one pass (the same bits, a quarter of
        // the passes over z).
        let mut end = k;
        while end >= 4 {
            let top = end - 4;
            for i in (top..end).rev() {
                let zi = z[i] / r[i * n + i];
                z[i] = zi;
                for l in top..i {
                    z[l] -= r[i * n + l] * zi;
                }
            }
            let (c0, c1, c2, c3) = (
                &r[(end - 1) * n..(end - 1) * n + top],
                &r[(end - 2) * n..(end - 2) * n + top],
                &r[(end - 3) * n..(end - 3) * n + top],
                &r[top * n..top * n + top],
            );
            let (z0, z1, z2, z3) = (z[end - 1], z[end - 2], z[end - 3], z[top]);
            for (l, zl) in z[..top].iter_mut().enumerate() {
                let mut v = *zl;
                v -= c0[l] * z0;
                v -= c1[l] * z1;
                v -= c2[l] * z2;
                v -= c3[l] * z3;
                *zl = v;
            }
            end = top;
        }
        for i in (0..end).rev() {
            let zi = z[i] / r[i * n + i];
            z[i] = zi;
            for (l, zl) in z[..i].iter_mut().enumerate() {
                *zl -= r[i * n + l] * zi;
            }
        }
    }
}

/// Options of [`nnls`]: when to stop, and how many columns may enter at once.
#[derive(Clone, Copy, Debug)]
pub(crate) struct NnlsOptions {
    /// Stop when `||A x - b|| <= residual_tolerance`.
    pub(crate) residual_tolerance: f64,
    /// Most columns entering the passive set per iteration (1: Lawson-Hanson; more: the
    /// deviation-maximisation choice of Dessole, Marcuzzi and Vianello, LHDM).
    pub(crate) max_entering: usize,
    /// LHDM: a column may enter with the best one if its gradient is at least this fraction
    /// of the largest ...
    pub(crate) gradient_fraction: f64,
    /// ... and the cosine of its angle with each column entering with it is at most this.
    pub(crate) max_cosine: f64,
    /// Columns scored between full passes (`0`: every column, every iteration): see
    /// [`nnls`]'s working set.
    pub(crate) working_set: usize,
    /// Outer iterations from one full pass over the gradients to the next (at least 1).
    pub(crate) full_pass_every: usize,
    /// Entering columns inserted with their reflections applied to `Q` together
    /// ([`PassiveQr::insert_all_blocked`]) rather than one by one.
    pub(crate) blocked_inserts: bool,
}

/// The solution of [`nnls`]: the passive columns with their values, and the factorisation of
/// the passive columns, for refinement.
pub(crate) struct NnlsSolution {
    qr: PassiveQr,
    /// The values of the passive columns `qr.cols`, in order.
    x: Vec<f64>,
    /// Whether the caller's stall test ended the iteration.
    stalled: bool,
}

impl NnlsSolution {
    /// The passive columns (candidate indices).
    pub(crate) fn columns(&self) -> &[usize] {
        &self.qr.cols
    }

    /// Whether the caller's stall test ended the iteration (the residual is then not
    /// expected to reach what the caller needs).
    pub(crate) fn stalled(&self) -> bool {
        self.stalled
    }

    /// Their values (all `> 0` unless the iteration cap ended an inner loop).
    pub(crate) fn values(&self) -> &[f64] {
        &self.x
    }

    /// The least-squares solution `z` of `A_P z = rhs` on the passive columns (for iterative
    /// refinement: `rhs` a residual mapped as `b` was).
    pub(crate) fn solve_passive(&self, rhs: &[f64]) -> Vec<f64> {
        let n = self.qr.n;
        let mut qtr = vec![0.0; n];
        for (i, v) in qtr.iter_mut().enumerate() {
            *v = dot(&self.qr.q[i * n..(i + 1) * n], rhs);
        }
        let mut z = Vec::new();
        self.qr.back_substitute(&qtr, &mut z);
        z
    }
}

/// Lawson-Hanson NNLS (with LHDM's several entering columns if
/// `options.max_entering > 1`) for `A` (`n x m`, column-major in `a`) and `b`, stopped when
/// `||A x - b|| <= residual_tolerance`, at optimality (no gradient above rounding), when
/// `stalled(r)` (called with the residual `r = b - A x` before each outer iteration) says
/// so, or after `3 n + 100` outer iterations (each with at most `2 n` inner steps): the work
/// is bounded.
///
/// **Working set.** The gradients `A^T r` of all `m` columns cost `m n` per iteration, most
/// of the iteration's work when `m` is many times `n`. A full pass every
/// `options.full_pass_every` iterations scores every column and keeps the
/// `options.working_set` with the largest gradients; the iterations in between score only
/// those. Any column with a positive gradient may enter (Lawson and Hanson's convergence
/// needs no more), so this changes which columns enter, not what the method converges to.
/// Optimality (no gradient above rounding) is only ever declared after a full pass: when the
/// working set offers no column, a full pass is made at once.
///
/// The whole iteration is compiled for each instruction set `pulp` knows and the best one at
/// hand is chosen at run time (the same arithmetic in the same order: Rust never fuses a
/// product and a sum, so the bits do not depend on the choice; wider vectors only do more of
/// the independent operations at once).
pub(crate) fn nnls(
    a: &[f64],
    n: usize,
    b: &[f64],
    options: NnlsOptions,
    stalled: impl FnMut(&[f64]) -> bool,
) -> NnlsSolution {
    pulp::Arch::new().dispatch(Nnls {
        a,
        n,
        b,
        options,
        stalled,
    })
}

/// [`nnls`] as an operation `pulp` compiles for each instruction set.
struct Nnls<'a, F> {
    a: &'a [f64],
    n: usize,
    b: &'a [f64],
    options: NnlsOptions,
    stalled: F,
}

impl<F: FnMut(&[f64]) -> bool> pulp::WithSimd for Nnls<'_, F> {
    type Output = NnlsSolution;
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> NnlsSolution {
        nnls_iteration(self.a, self.n, self.b, self.options, self.stalled)
    }
}

/// The body of [`nnls`], inlined into each of its instruction sets' copies (as is every
/// function it calls that does arithmetic on vectors).
#[inline(always)]
fn nnls_iteration(
    a: &[f64],
    n: usize,
    b: &[f64],
    options: NnlsOptions,
    mut stalled: impl FnMut(&[f64]) -> bool,
) -> NnlsSolution {
    let m = a.len() / n;
    let column = |j: usize| &a[j * n..(j + 1) * n];
    let norms: Vec<f64> = (0..m).map(|j| dot(column(j), column(j)).sqrt()).collect();
    let col_norm_max = norms.iter().fold(0.0f64, |a, &b| a.max(b));
    let b_norm = dot(b, b).sqrt();
    // Gradients below this are rounding: the components of A^T r carry errors of about
    // eps |a_j| |r| per term.
    let gradient_floor = 16.0 * f64::EPSILON * col_norm_max * b_norm.max(f64::MIN_POSITIVE);
    let mut qr = PassiveQr::new(n, b);
    let mut passive = vec![false; m];
    // Columns that failed to enter since the passive set last changed.
    let mut blocked = vec![false; m];
    let mut x: Vec<f64> = Vec::with_capacity(n);
    let mut z = Vec::with_capacity(n);
    let mut r = b.to_vec();
    let mut g = vec![0.0; m];
    let mut order: Vec<usize> = Vec::new();
    let mut entering: Vec<usize> = Vec::new();
    // The columns scored this iteration: all of them after a full pass, else the working set.
    let mut scored: Vec<usize> = Vec::with_capacity(m);
    let mut live: Vec<usize> = Vec::with_capacity(m);
    let mut working: Vec<usize> = Vec::new();
    let all_columns = options.working_set == 0 || options.working_set >= m;
    let mut since_full = usize::MAX;
    let cap = 3 * n + 100;
    let mut iterations = 0;
    while iterations < cap {
        iterations += 1;
        if dot(&r, &r).sqrt() <= options.residual_tolerance {
            break;
        }
        if stalled(&r) {
            return NnlsSolution {
                qr,
                x,
                stalled: true,
            };
        }
        let mut full = all_columns || since_full >= options.full_pass_every.max(1);
        // At most two rounds: the working set's, then (if it offers nothing) a full pass.
        let (best, g_best) = loop {
            scored.clear();
            if full {
                scored.extend(0..m);
                since_full = 0;
            } else {
                scored.extend_from_slice(&working);
            }
            // The gradients of the columns free to enter, several side by side; then the
            // best in the order scored.
            live.clear();
            for &j in &scored {
                if passive[j] || blocked[j] {
                    g[j] = f64::NEG_INFINITY;
                } else {
                    live.push(j);
                }
            }
            dots_into(live.len(), |t| column(live[t]), &r, |t, d| g[live[t]] = d);
            let mut best = (usize::MAX, f64::NEG_INFINITY);
            for &j in &scored {
                // The last of equal maxima, as `Iterator::max_by` picks.
                if g[j].total_cmp(&best.1).is_ge() {
                    best = (j, g[j]);
                }
            }
            if full && !all_columns {
                keep_largest(&mut working, &g, options.working_set, gradient_floor);
            }
            if full || (best.1 > gradient_floor && !best.1.is_nan()) {
                break best;
            }
            full = true;
        };
        since_full = since_full.saturating_add(1);
        if best == usize::MAX || g_best.is_nan() || g_best <= gradient_floor {
            break;
        }
        // The entering columns: the best, then (LHDM) others with a large gradient nearly
        // orthogonal to those chosen, scanned by decreasing gradient.
        entering.clear();
        entering.push(best);
        let room = options.max_entering.min(n - qr.len());
        if room > 1 {
            let threshold = options.gradient_fraction * g_best;
            order.clear();
            order.extend(
                scored
                    .iter()
                    .copied()
                    .filter(|&j| j != best && g[j] >= threshold && g[j] > gradient_floor),
            );
            order.sort_unstable_by(|&p, &q| g[q].total_cmp(&g[p]));
            for &j in order.iter() {
                if entering.len() >= room {
                    break;
                }
                let apart = entering.iter().all(|&l| {
                    dot(column(j), column(l)).abs() <= options.max_cosine * norms[j] * norms[l]
                });
                if apart {
                    entering.push(j);
                }
            }
        }
        let mut added = 0;
        let mut on_insert = |j: usize, inserted: bool| {
            if inserted {
                passive[j] = true;
                x.push(0.0);
                added += 1;
            } else {
                blocked[j] = true;
            }
        };
        if options.blocked_inserts {
            qr.insert_all_blocked(a, &entering, &mut on_insert);
        } else {
            qr.insert_all(a, &entering, &mut on_insert);
        }
        if added == 0 {
            continue;
        }
        let mut changed = false;
        // Inner loop: move towards the unconstrained solution on the passive set until it is
        // positive, dropping the columns that reach zero.
        for _ in 0..2 * n {
            qr.solve(&mut z);
            // An entering column (value still 0) whose solution is not positive would stop the
            // step at once: it leaves again, and is not tried until the set changes.
            let mut dropped = false;
            for pos in (0..x.len()).rev() {
                if x[pos] == 0.0 && z[pos] <= 0.0 {
                    let j = qr.cols[pos];
                    passive[j] = false;
                    blocked[j] = true;
                    qr.remove(pos);
                    x.remove(pos);
                    dropped = true;
                }
            }
            if dropped {
                if x.is_empty() {
                    break;
                }
                continue;
            }
            if z.iter().all(|&v| v > 0.0) {
                x.copy_from_slice(&z);
                changed = true;
                break;
            }
            // Step to the first value that reaches zero; it (and any other at zero) leaves.
            let (mut alpha, mut first) = (1.0f64, 0);
            for (pos, (&xi, &zi)) in x.iter().zip(&z).enumerate() {
                if zi <= 0.0 {
                    let t = xi / (xi - zi);
                    if t < alpha {
                        alpha = t;
                        first = pos;
                    }
                }
            }
            for (xi, &zi) in x.iter_mut().zip(&z) {
                *xi += alpha * (zi - *xi);
            }
            x[first] = 0.0;
            for pos in (0..x.len()).rev() {
                if x[pos] <= 0.0 {
                    passive[qr.cols[pos]] = false;
                    qr.remove(pos);
                    x.remove(pos);
                }
            }
            changed = true;
            if x.is_empty() {
                break;
            }
        }
        if changed {
            blocked.iter_mut().for_each(|b| *b = false);
        }
        r.copy_from_slice(b);
        axpys(x.len(), |p| -x[p], |p| column(qr.cols[p]), &mut r);
    }
    NnlsSolution {
        qr,
        x,
        stalled: false,
    }
}

/// `working <-` the (at most) `size` indices `j` with the largest `g[j] > floor`, in no
/// particular order.
#[inline(always)]
fn keep_largest(working: &mut Vec<usize>, g: &[f64], size: usize, floor: f64) {
    working.clear();
    working.extend((0..g.len()).filter(|&j| g[j] > floor));
    if working.len() > size {
        working.select_nth_unstable_by(size - 1, |&p, &q| g[q].total_cmp(&g[p]));
        working.truncate(size);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pulp::WithSimd;

    const LH: NnlsOptions = NnlsOptions {
        residual_tolerance: 1e-14,
        max_entering: 1,
        gradient_fraction: 1.0,
        max_cosine: 0.0,
        working_set: 0,
        full_pass_every: 1,
        blocked_inserts: false,
    };
    const LHDM: NnlsOptions = NnlsOptions {
        residual_tolerance: 1e-14,
        max_entering: 3,
        gradient_fraction: 0.1,
        max_cosine: 0.9,
        working_set: 0,
        full_pass_every: 1,
        blocked_inserts: false,
    };
    /// LHDM scoring a working set of one column between full passes every third iteration.
    const WORKING: NnlsOptions = NnlsOptions {
        working_set: 1,
        full_pass_every: 3,
        ..LHDM
    };

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
        for options in [LH, LHDM, WORKING] {
            let s = nnls(&a, 3, &b, options, |_| false);
            assert!(s.columns().len() <= 3);
            assert!(s.values().iter().all(|&v| v > 0.0));
            let mut got = [0.0; 3];
            for (&j, &v) in s.columns().iter().zip(s.values()) {
                axpy(v, &a[3 * j..3 * j + 3], &mut got);
            }
            for k in 0..3 {
                assert!((got[k] - b[k]).abs() < 1e-13, "{got:?} vs {b:?}");
            }
        }
    }

    #[test]
    fn an_unreachable_right_hand_side_gets_the_nearest_point_of_the_cone() {
        // Columns e1 and e2 in R^2, b = (1, -1): the best x >= 0 is (1, 0).
        let a = [1.0, 0.0, 0.0, 1.0];
        for options in [LH, LHDM, WORKING] {
            let s = nnls(&a, 2, &[1.0, -1.0], options, |_| false);
            assert_eq!(s.columns(), [0]);
            assert!((s.values()[0] - 1.0).abs() < 1e-15);
        }
    }

    /// With a working set smaller than the columns the solution needs, the full passes still
    /// bring them in: a consistent problem with five positive weights among forty columns is
    /// matched, and optimality is declared only after a full pass.
    #[test]
    fn a_small_working_set_still_reaches_the_solution() {
        let (n, m) = (6, 40);
        let a: Vec<f64> = (0..n * m)
            .map(|i| {
                (((i * 53 + 7) % 29) as f64 - 14.0) / 14.0 + if i % n == 0 { 2.0 } else { 0.0 }
            })
            .collect();
        let mut b = vec![0.0; n];
        for (j, xj) in [(3, 0.5), (11, 1.25), (19, 0.75), (27, 2.0), (38, 0.3)] {
            axpy(xj, &a[j * n..(j + 1) * n], &mut b);
        }
        for options in [
            LHDM,
            WORKING,
            NnlsOptions {
                working_set: 2,
                full_pass_every: 100,
                ..LH
            },
        ] {
            let s = nnls(&a, n, &b, options, |_| false);
            assert!(s.values().iter().all(|&v| v > 0.0));
            let mut got = vec![0.0; n];
            for (&j, &v) in s.columns().iter().zip(s.values()) {
                axpy(v, &a[j * n..(j + 1) * n], &mut got);
            }
            let err = got
                .iter()
                .zip(&b)
                .map(|(g, b)| (g - b).abs())
                .fold(0.0, f64::max);
            assert!(err < 1e-12, "{options:?}: {got:?} vs {b:?}");
        }
    }

    #[test]
    fn a_stall_ends_the_iteration_at_once() {
        let a = [1.0, 0.0, 0.0, 1.0];
        let mut calls = 0;
        let s = nnls(&a, 2, &[1.0, 2.0], LH, |r| {
            calls += 1;
            assert_eq!(r, [1.0, 2.0]);
            true
        });
        assert!(s.stalled());
        assert_eq!(calls, 1);
        assert!(s.columns().is_empty());
        let s = nnls(&a, 2, &[1.0, 2.0], LH, |_| false);
        assert!(!s.stalled());
        assert_eq!(s.columns().len(), 2);
    }

    /// Values of many sizes and signs, from a fixed sequence.
    fn values(count: usize, seed: u64) -> Vec<f64> {
        let mut rng = rs_testkit::XorShift64::new(seed);
        (0..count)
            .map(|_| {
                let unit = rng.next_f64() - 0.5;
                unit * 10f64.powi((rng.next_u64() % 7) as i32 - 3)
            })
            .collect()
    }

    /// The products side by side are [`dot`]'s bit for bit: lengths with and without a tail
    /// past the eight sums, groups of eight columns and the rest.
    #[test]
    fn head_products_are_dot_bit_for_bit() {
        for n in [1, 7, 8, 9, 23, 64, 231] {
            let q = values(5 * n, n as u64);
            for count in [1, 3, 7, 8, 9, 17] {
                let all = values(count * n, 1000 + count as u64);
                let columns: Vec<&[f64]> = all.chunks_exact(n).collect();
                let mut products = vec![vec![f64::NAN; 5]; count];
                head_products(&q, n, 5, &columns, &mut products);
                for (e, column) in columns.iter().enumerate() {
                    for (i, qi) in q.chunks_exact(n).enumerate() {
                        let want = dot(qi, column);
                        assert_eq!(
                            products[e][i].to_bits(),
                            want.to_bits(),
                            "n {n} e {e} i {i}"
                        );
                    }
                }
            }
        }
    }

    /// The iteration compiled for the best instruction set at hand (`nnls`) gives the bits of
    /// its baseline copy: the same passive columns, values and factorisation, for
    /// Lawson-Hanson, LHDM and a working set, on a problem of several dozen iterations with
    /// removals.
    #[test]
    fn the_dispatched_iteration_is_the_baseline_bit_for_bit() {
        let (n, m) = (45, 400);
        let a = values(n * m, 21);
        // Moments of positive weights on a few columns, and of a mix that needs more.
        let mut b = vec![0.0; n];
        for (k, j) in (0..m).step_by(13).enumerate() {
            axpy(0.5 + (k % 7) as f64, &a[j * n..(j + 1) * n], &mut b);
        }
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let wide = NnlsOptions {
            max_entering: 5,
            gradient_fraction: 0.5,
            max_cosine: 0.2,
            ..LH
        };
        for options in [
            LH,
            wide,
            NnlsOptions {
                working_set: 60,
                full_pass_every: 4,
                ..wide
            },
        ] {
            let fast = nnls(&a, n, &b, options, |_| false);
            let base = Nnls {
                a: &a,
                n,
                b: &b,
                options,
                stalled: |_: &[f64]| false,
            }
            .with_simd(pulp::Scalar);
            assert!(fast.columns().len() > 10, "{options:?}");
            assert_eq!(fast.columns(), base.columns(), "{options:?}");
            assert_eq!(bits(fast.values()), bits(base.values()), "{options:?}");
            assert_eq!(bits(&fast.qr.q), bits(&base.qr.q), "{options:?}");
            assert_eq!(bits(&fast.qr.r), bits(&base.qr.r), "{options:?}");
        }
    }

    /// `dots_into` gives `dot`'s bits for every count (groups of eight, of four and single
    /// vectors), in order.
    #[test]
    fn dots_into_is_dot_bit_for_bit() {
        for n in [1, 8, 13, 231] {
            let v = values(n, 5 + n as u64);
            let all = values(21 * n, 77);
            let x: Vec<&[f64]> = all.chunks_exact(n).collect();
            for count in 0..=21 {
                let mut got = Vec::new();
                dots_into(count, |t| x[t], &v, |t, d| got.push((t, d.to_bits())));
                let want: Vec<(usize, u64)> =
                    (0..count).map(|t| (t, dot(x[t], &v).to_bits())).collect();
                assert_eq!(got, want, "n {n} count {count}");
            }
        }
    }

    /// `axpys` is `axpy` after `axpy`, bit for bit, for every count.
    #[test]
    fn axpys_is_axpy_in_order_bit_for_bit() {
        for n in [1, 7, 64] {
            let all = values(11 * n, 9);
            let x: Vec<&[f64]> = all.chunks_exact(n).collect();
            let alpha = values(11, 4);
            for count in 0..=11 {
                let mut got = values(n, 3);
                let mut want = got.clone();
                axpys(count, |t| alpha[t], |t| x[t], &mut got);
                for t in 0..count {
                    axpy(alpha[t], x[t], &mut want);
                }
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&got), bits(&want), "n {n} count {count}");
            }
        }
    }

    /// The back substitution by blocks of four columns gives column-by-column substitution's
    /// bits, for every size of the triangle (whole blocks and a remainder).
    #[test]
    fn blocked_back_substitution_is_column_by_column_bit_for_bit() {
        let n = 19;
        let mut qr = PassiveQr::new(n, &values(n, 1));
        let entries = values(n * n, 2);
        for i in 0..n {
            for l in 0..=i {
                qr.r[i * n + l] = if l == i {
                    2.0 + entries[i * n + l].abs()
                } else {
                    entries[i * n + l]
                };
            }
        }
        let c = values(n, 8);
        for k in 0..=n {
            qr.cols = (0..k).collect();
            let mut got = Vec::new();
            qr.back_substitute(&c, &mut got);
            let mut want = c[..k].to_vec();
            for i in (0..k).rev() {
                let zi = want[i] / qr.r[i * n + i];
                want[i] = zi;
                for (l, w) in want[..i].iter_mut().enumerate() {
                    *w -= qr.r[i * n + l] * zi;
                }
            }
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&got), bits(&want), "k {k}");
        }
    }

    /// Thirteen rows, twenty columns (column 5 is column 1 + column 2: in their span once both
    /// are in) and a right-hand side, with four batches of entering columns (the last past a
    /// full set): what the insert tests feed both ways of inserting.
    fn insert_problem() -> (usize, Vec<f64>, Vec<f64>, [&'static [usize]; 4]) {
        let n = 13;
        let mut a = values(n * 20, 7);
        for i in 0..n {
            a[5 * n + i] = a[n + i] + a[2 * n + i];
        }
        let b = values(n, 3);
        let batches: [&[usize]; 4] = [
            &[0, 3],
            &[1, 2, 5, 4, 6],
            &[7, 8, 9, 10, 11, 12, 13],
            &[14, 15, 16, 17, 18, 19],
        ];
        (n, a, b, batches)
    }

    /// The blocked inserts (reflections applied to `Q` together, compact WY) make the
    /// factorisation the one-by-one inserts make, to rounding: the same columns accepted and
    /// refused (one in the span, the last past a full set), `Q`, `R` and `Q^T b` within
    /// `1e-14` of their largest entries, and the invariants `Q^T Q = I`, `A_P = Q R` and
    /// `Q^T b` kept, through removals between the batches.
    #[test]
    fn blocked_inserts_are_one_by_one_inserts_to_rounding() {
        let (n, a, b, batches) = insert_problem();
        let mut one = PassiveQr::new(n, &b);
        let mut blocked = PassiveQr::new(n, &b);
        for batch in batches {
            let mut got = Vec::new();
            blocked.insert_all_blocked(&a, batch, |j, inserted| got.push((j, inserted)));
            let want: Vec<(usize, bool)> = batch
                .iter()
                .map(|&j| (j, one.insert(&a[j * n..(j + 1) * n], j)))
                .collect();
            assert_eq!(got, want);
            // Within `1e-14` of the larger entry in size (`R` and `Q^T b` scale with `A`, `b`).
            let close = |x: &[f64], y: &[f64]| {
                let size = x.iter().chain(y).fold(0.0f64, |m, v| m.max(v.abs()));
                x.iter().zip(y).all(|(p, q)| (p - q).abs() <= 1e-14 * size)
            };
            assert!(close(&blocked.q, &one.q));
            assert!(close(&blocked.r, &one.r));
            assert!(close(&blocked.qtb, &one.qtb));
            // Q orthogonal, A_P = Q R, Q^T b.
            let q = DMatrix::from_column_slice(n, n, &blocked.q);
            assert!((q.tr_mul(&q) - DMatrix::<f64>::identity(n, n)).amax() <= 1e-13);
            for (i, &j) in blocked.cols.iter().enumerate() {
                let r = DMatrix::from_column_slice(n, 1, &blocked.r[i * n..(i + 1) * n]);
                let a_j = DMatrix::from_column_slice(n, 1, &a[j * n..(j + 1) * n]);
                assert!((&q * r - &a_j).amax() <= 1e-14 * a_j.amax().max(1.0) * n as f64);
            }
            let qtb = q.tr_mul(&DMatrix::from_column_slice(n, 1, &b));
            let kept = DMatrix::from_column_slice(n, 1, &blocked.qtb);
            assert!((qtb - &kept).amax() <= 1e-14 * kept.amax() * n as f64);
            one.remove(0);
            blocked.remove(0);
        }
        assert_eq!(blocked.cols, one.cols);
    }

    /// Entering columns inserted together leave the factorisation one-by-one inserts leave,
    /// bit for bit, including a column in the span of the others (refused) and a full set.
    #[test]
    fn inserting_together_is_inserting_one_by_one() {
        let (n, a, b, batches) = insert_problem();
        let mut one = PassiveQr::new(n, &b);
        let mut together = PassiveQr::new(n, &b);
        let mut refused = Vec::new();
        for batch in batches {
            let mut got = Vec::new();
            together.insert_all(&a, batch, |j, inserted| got.push((j, inserted)));
            let want: Vec<(usize, bool)> = batch
                .iter()
                .map(|&j| (j, one.insert(&a[j * n..(j + 1) * n], j)))
                .collect();
            assert_eq!(got, want);
            refused.extend(got.iter().filter(|g| !g.1).map(|g| g.0));
            // A removal between batches, as the inner loop makes.
            one.remove(0);
            together.remove(0);
        }
        // Column 5 in the span, and the last ones past a full set.
        assert!(refused.contains(&5) && refused.contains(&19), "{refused:?}");
        assert_eq!(together.cols, one.cols);
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&together.q), bits(&one.q));
        assert_eq!(bits(&together.r), bits(&one.r));
        assert_eq!(bits(&together.qtb), bits(&one.qtb));
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
