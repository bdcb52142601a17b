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
//! and Yanagisawa, 2020). The shift regularises: `Q` is then left short of orthonormal, and
//! the NNLS on it takes several times the iterations; one more, unshifted, pass
//! ([`normalising_pass`]) makes it orthonormal when that is safe. The weights' accuracy does
//! not rest on this factorisation: the rule refines them against the residual in the basis
//! itself, through [`Orthonormal::map`].

use nalgebra::{DMatrix, DMatrixView, DVector};

/// Above this ratio of the largest to the least diagonal entry of a pass's factor (about
/// `cond` of what it factored), another pass is made: one pass leaves `Q^T Q - I` of about
/// `eps cond^2`, which then exceeds `1e-6`.
const NEXT_PASS_RATIO: f64 = 1e5;

/// Most Cholesky passes (shifted where the Gram matrix is numerically singular), before
/// [`normalising_pass`].
const MAX_PASSES: usize = 3;

/// `Q^T` and `b = R^{-T} m`, with `R^T` itself (for refinement).
pub(crate) struct Orthonormal {
    /// `Q^T`, `N x M`, one column per candidate.
    pub(crate) qt: DMatrix<f64>,
    /// `R^{-T} m`.
    pub(crate) b: DVector<f64>,
    /// `R^T`, `N x N`, lower triangular.
    rt: DMatrix<f64>,
    /// Whether [`normalising_pass`] made `Q` orthonormal after shifted passes had left it
    /// regularised.
    pub(crate) normalised: bool,
}

impl Orthonormal {
    /// `max_k |(R^T r)_k|`: for `r = b - Q^T w`, the largest error of the moments,
    /// `max_k |m_k - sum_i w_i phi_k(x_i)|` (as `R^T (b - Q^T w) = m - V^T w`). Compiled for
    /// each instruction set `pulp` knows, the best one at hand chosen at run time (the same
    /// operations in the same order whichever: the same bits).
    pub(crate) fn moment_error(&self, r: &[f64]) -> f64 {
        pulp::Arch::new().dispatch(MomentError {
            rt: self.rt.as_slice(),
            n: self.rt.nrows(),
            r,
        })
    }

    /// `R^{-T} v`: a vector of moments (or of residuals of moments) in the orthonormal basis.
    pub(crate) fn map(&self, v: &[f64]) -> DVector<f64> {
        let v = DVector::from_column_slice(v);
        self.rt
            .solve_lower_triangular(&v)
            .unwrap_or_else(|| DVector::zeros(v.len()))
    }
}

/// [`Orthonormal::moment_error`] as an operation `pulp` compiles for each instruction set:
/// `R^T` (`n x n`, column-major, lower triangular) times `r`, its largest entry in size.
struct MomentError<'a> {
    rt: &'a [f64],
    n: usize,
    r: &'a [f64],
}

impl pulp::WithSimd for MomentError<'_> {
    type Output = f64;
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> f64 {
        let Self { rt, n, r } = self;
        // R^T is lower triangular: column k has entries in rows k.. only. Column slices of the
        // column-major storage (a strided iterator was 10% of the whole rule at degree 30).
        let mut sums = vec![0.0; n];
        for (k, &rk) in r.iter().enumerate() {
            let column = &rt[k * n + k..(k + 1) * n];
            for (s, &l) in sums[k..].iter_mut().zip(column) {
                *s += l * rk;
            }
        }
        sums.iter().fold(0.0f64, |a, s| a.max(s.abs()))
    }
}

/// The rule the moments are checked against, and taken from, in the orthonormal basis.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Reference<'a> {
    /// Equal weights on the first `U` candidates, quasi-uniform (Halton points): a
    /// quasi-Monte Carlo rule, only a check of the moments' consistency ([`normalising_pass`]);
    /// the moments in the orthonormal basis are `b = R^{-T} m`.
    Uniform(usize),
    /// A positive rule on all the candidates whose moments are those wanted (the chord
    /// formula, see `chords`): `b = Q^T w`, consistent with the candidates by construction, so
    /// the shifted passes need only a [`RULE_SHIFT_SCALE`] of the usual shift.
    Rule(&'a [f64]),
}

impl Reference<'_> {
    /// The factor of the shift of [`shifted_cholesky`].
    fn shift_scale(self) -> f64 {
        match self {
            Reference::Uniform(_) => 1.0,
            Reference::Rule(_) => RULE_SHIFT_SCALE,
        }
    }
}

/// The shift of [`shifted_cholesky`] for a [`Reference::Rule`], times the usual one. The
/// usual shift keeps the moments, mapped through an ill-conditioned factor, consistent with
/// the candidates (a smaller one left the L shape and `s4_disk_ellipse_segment` without rules
/// at degrees 32 to 40); with `b = Q^T w` there is nothing to keep consistent, and the smaller
/// shift leaves `Q` nearer orthonormal: fewer passes, fewer NNLS iterations.
const RULE_SHIFT_SCALE: f64 = 1e-7;

/// The orthonormalisation of `vt = V^T` (`N x M`, one column per candidate), or `None` if the
/// candidates do not resolve the basis (a factor not invertible). `reference` is the rule
/// the [`normalising_pass`]'s consistency test takes (equal weights on the first `U`
/// candidates, the Halton points, all of them up to degree 20; or a positive rule on all the
/// candidates), and decides `b` and the shift (see [`Reference`]). With `normalise` false, no normalising pass is tried (`Q` stays regularised where the
/// shifted passes left it so).
pub(crate) fn orthonormalise(
    vt: DMatrix<f64>,
    m: &[f64],
    reference: Reference<'_>,
    normalise: bool,
) -> Option<Orthonormal> {
    let n = vt.nrows();
    let mut qt = vt;
    let mut rt = DMatrix::<f64>::identity(n, n);
    let mut regularised = false;
    for pass in 0..MAX_PASSES {
        let gram = gram_lower(&qt, qt.ncols());
        let (l, shifted) = match cholesky_lower(gram.clone()) {
            Some(l) => (l, false),
            None => (
                shifted_cholesky(gram, qt.ncols(), reference.shift_scale())?,
                true,
            ),
        };
        if !solve_lower_blocked(&l, &mut qt) {
            return None;
        }
        // The first pass's factor is `R^T` itself (`I L` is `L` bit for bit: a product
        // with ones and exact zeros; the N^3 product was 2% of a degree-40 rule).
        let d = l.diagonal();
        rt = if pass == 0 { l } else { &rt * &l };
        regularised = shifted;
        if !shifted && d.max() <= NEXT_PASS_RATIO * d.min() {
            break;
        }
    }
    let normalised = regularised && normalise && normalising_pass(&mut qt, &mut rt, m, reference)?;
    // A factor with a zero or non-finite diagonal entry: the candidates do not resolve the
    // basis (a shifted factor is always invertible, so this is rank deficiency or overflow).
    let d = rt.diagonal();
    if !d.iter().all(|v| v.is_finite() && *v > 0.0) {
        return None;
    }
    let b = match reference {
        Reference::Uniform(_) => rt.solve_lower_triangular(&DVector::from_column_slice(m))?,
        Reference::Rule(w) => &qt * DVector::from_column_slice(w),
    };
    Some(Orthonormal {
        qt,
        b,
        rt,
        normalised,
    })
}

/// After [`MAX_PASSES`] passes of which the last was shifted: one more, unshifted, pass when it
/// is safe, i.e. when
/// 1. the Gram matrix of all the candidates has a Cholesky factor (not the shifted one);
/// 2. the moments stay consistent with the candidates: with the pass's factor `L`,
///    `rho = ||L^{-1} (b - Q^T w)|| / ||L^{-1} Q^T w||` for the reference rule `w`: the equal
///    weights `w = area / U` on the first `U` candidates, the Halton points (all `M` of them
///    up to degree 20; above, the boundary layers that follow them are not uniform and get no
///    weight) (a quasi-Monte Carlo rule: `rho` is its error in the new orthonormal basis), or
///    a [`Reference::Rule`] (then `b = Q^T w` and `rho` is rounding), is at most
///    [`MAX_MOMENT_INCONSISTENCY`]. Normalising directions the shift had damped also scales
///    up the moments' rounding errors in them; `rho` then grows far beyond the rule's error.
///
/// The pass orthonormalises `Q`, and the NNLS on it then takes a fraction of the iterations:
/// at degree 30 on `s5_lune` 88-132 instead of 359-371 (`rho` 0.19), the rule's residual
/// `1e-14` -> `8e-16`; at degree 40 on the unit disc and `s5_lune` (`rho` 0.66 and 0.59) the
/// whole rule 2.38 -> 1.22 s and 2.10 -> 1.52 s, the residual `2.2e-15` -> `2.8e-16` and
/// `2.8e-15` -> `1.0e-15`. Without the tests, an unshifted pass after shifted ones gave
/// `rho` 0.8 at degree 35 and 2.4 at degree 40 on `s4_disk_ellipse_segment`, and at 40 a
/// failed rule (residual 0.16); there, at degrees 31 to 40, `rho` is 0.8 to 3 or the Gram
/// matrix has no factor, and the pass is refused. (A rule made after the pass that misses
/// its target is made again without it, the one with the smaller residual kept: see
/// `compress`.)
///
/// `Some(true)` if the pass was made, `Some(false)` if refused; `None` if it made a non-finite
/// or zero factor (then the candidates do not resolve the basis).
fn normalising_pass(
    qt: &mut DMatrix<f64>,
    rt: &mut DMatrix<f64>,
    m: &[f64],
    reference: Reference<'_>,
) -> Option<bool> {
    let cols = qt.ncols();
    let Some(l) = cholesky_lower(gram_lower(qt, cols)) else {
        return Some(false);
    };
    let qw = match reference {
        Reference::Uniform(uniform) => {
            let area = m.first().copied().unwrap_or(0.0);
            let uniform = uniform.clamp(1, cols);
            qt.columns(0, uniform).column_sum() * (area / uniform as f64)
        }
        Reference::Rule(w) => &*qt * DVector::from_column_slice(w),
    };
    let consistent = rt
        .solve_lower_triangular(&DVector::from_column_slice(m))
        .and_then(|b| {
            Some((
                l.solve_lower_triangular(&b)?,
                l.solve_lower_triangular(&qw)?,
            ))
        })
        .map(|(b, qw)| (&b - &qw).norm() / qw.norm())
        .is_some_and(|rho| rho <= MAX_MOMENT_INCONSISTENCY);
    if !consistent {
        return Some(false);
    }
    if !solve_lower_blocked(&l, qt) {
        return None;
    }
    *rt = &*rt * &l;
    Some(true)
}

/// The largest `rho` of [`normalising_pass`]. Surveyed at degrees 21 to 40 on the paper's six
/// domains and the three nested fill-rule fixtures (180 rules): the passes with `rho` up to 0.67
/// (`s5_lune` at degrees 31 to 40, the disc at 38 and 40, the nested discs at 37 to 40, the
/// L shape at 22) made rules at residuals of `2.8e-16` to `2.6e-15`, those refused had `rho`
/// 0.8 to 4.4 (`s4_disk_ellipse_segment`, the L shape); earlier, a pass at 0.8 made a failed
/// rule. (A limit of 0.4, with a cheaper test on a prefix of the candidates before it,
/// refused every pass above degree 30.)
const MAX_MOMENT_INCONSISTENCY: f64 = 0.7;

/// Rows of the diagonal blocks of [`solve_lower_blocked`]: the work off the diagonal, all but
/// `1 / (number of blocks)` of it, runs as matrix products.
const SOLVE_BLOCK: usize = 64;
/// Rows of the blocks each diagonal block of [`SOLVE_BLOCK`] rows is solved by, the same way:
/// the forward substitution left (one column at a time, short vectors) is a quarter of what
/// it was with the diagonal blocks solved whole. Measured at degree 30 on
/// `s4_disk_ellipse_segment`: the substitution was 21% of the rule's time.
const INNER_SOLVE_BLOCK: usize = 16;

/// Bases up to this size (`dim P_20`) keep the rules they had before the high-degree paths
/// (the inner blocks of [`solve_lower_blocked`] and the NNLS's working set): those paths regroup
/// the arithmetic and so move nodes and weights by rounding, and at these degrees a rule takes
/// tens of milliseconds anyway; a user's rule of degree 20 or less is the same bit for bit.
pub(crate) const HIGH_DEGREE_BASIS: usize = 231;

/// Rows per block of [`gram_lower`]'s product: `N / 128` products of a block of rows with
/// all the rows above it (4 to 7 at degrees 30 to 40), each large enough for `gemm`'s speed.
const GRAM_BLOCK: usize = 128;

/// A matrix whose lower triangle is the Gram matrix `A A^T` of the first `cols` columns `A` of
/// `a` (`N x M`): what a Cholesky factorisation reads. Above [`HIGH_DEGREE_BASIS`] rows only
/// the lower triangle is multiplied out, a block of rows `I` at a time (`A_I A_J^T` for every
/// row `J` up to the end of `I`; the upper triangle is left zero outside the diagonal blocks):
/// half the work of the full product (the Gram products were about a quarter of a degree-30
/// rule's time). `A^T` is read in place, through a view with swapped strides: `gemm` packs its
/// operands into the same panels whatever their strides, so the product is the one of a
/// transposed copy bit for bit, without the copy (`M N` entries, 49 MB at degree 40, written
/// across the cache lines: 60 ms a pass on `s3_m_shape`). The full product stays below
/// [`HIGH_DEGREE_BASIS`], where it moves no rule (a regrouped sum may differ by rounding).
fn gram_lower(a: &DMatrix<f64>, cols: usize) -> DMatrix<f64> {
    let n = a.nrows();
    let cols = cols.min(a.ncols());
    // The first `cols` columns: the first `n cols` entries of the column-major storage.
    let data = &a.as_slice()[..n * cols];
    let a = DMatrixView::from_slice(data, n, cols);
    if n <= HIGH_DEGREE_BASIS {
        return a * a.transpose();
    }
    // Entry (j, i) of `A^T` is entry (i, j) of `A`, at `i + j n`: row stride `n`, column 1.
    let at = DMatrixView::from_slice_with_strides(data, cols, n, n, 1);
    let mut g = DMatrix::zeros(n, n);
    let mut start = 0;
    while start < n {
        let end = (start + GRAM_BLOCK).min(n);
        let rows = a.rows_range(start..end);
        g.view_mut((start, 0), (end - start, end))
            .gemm(1.0, &rows, &at.columns_range(..end), 0.0);
        start = end;
    }
    g
}

/// `x <- L^{-1} x` for a lower triangular `L` (`N x N`) and `x` (`N x M`), by blocks of rows:
/// each diagonal block solved (itself by blocks of [`INNER_SOLVE_BLOCK`] rows, then by forward
/// substitution), the rows below it updated by one matrix product. Backward stable like
/// forward substitution (each row is a triangular solve with the same operations regrouped),
/// unlike multiplying by a computed inverse, whose error grows with `cond(L)`. `false` if a
/// diagonal entry is zero (`x` then partly solved).
///
/// The candidates (columns of `x`, independent of each other) are solved [`SOLVE_CHUNK`] at a
/// time, each chunk copied out, solved and copied back: every entry takes the same operations
/// in the same order as when all the columns are solved at once (`gemm` sums each entry over
/// the same inner dimension whatever the number of columns), so the same bits, but each
/// block's product reads and writes a chunk in the core's cache instead of all of `x` (49 MB
/// at degree 40 on `s3_m_shape`, read and written once per block of rows: 14 times a pass).
/// Measured there: 160-172 ms a pass -> 140-143 ms.
fn solve_lower_blocked(l: &DMatrix<f64>, x: &mut DMatrix<f64>) -> bool {
    let (n, m) = x.shape();
    let width = SOLVE_CHUNK;
    if m <= width || n == 0 {
        return solve_lower_by_blocks(l.as_view(), x, 0, SOLVE_BLOCK);
    }
    // Whole chunks, the last one with the rest besides (fewer than `2 width` columns): a
    // chunk of at most five columns would be multiplied by `nalgebra`'s own loops, not
    // `gemm`, and so rounded differently.
    let chunks = m / width;
    let mut chunk = DMatrix::zeros(n, width);
    let data = x.as_mut_slice();
    for c in 0..chunks {
        let end = if c + 1 == chunks { m } else { (c + 1) * width };
        let columns = &mut data[c * width * n..end * n];
        if columns.len() != chunk.len() {
            chunk = DMatrix::zeros(n, columns.len() / n);
        }
        chunk.as_mut_slice().copy_from_slice(columns);
        if !solve_lower_by_blocks(l.as_view(), &mut chunk, 0, SOLVE_BLOCK) {
            return false;
        }
        columns.copy_from_slice(chunk.as_slice());
    }
    true
}

/// Candidates per chunk of [`solve_lower_blocked`]: `128 N` values, 0.9 MB at degree 40,
/// within the core's second-level cache (1 MB here). 64 and 256 measured the same.
const SOLVE_CHUNK: usize = 128;

/// [`solve_lower_blocked`] for the rows `first..first + L.nrows()` of `x`, with diagonal blocks
/// of `block` rows (solved by blocks of [`INNER_SOLVE_BLOCK`] rows when larger, for `L` of more
/// than [`HIGH_DEGREE_BASIS`] rows).
fn solve_lower_by_blocks(
    l: DMatrixView<'_, f64>,
    x: &mut DMatrix<f64>,
    first: usize,
    block: usize,
) -> bool {
    let n = l.nrows();
    let mut start = 0;
    while start < n {
        let size = block.min(n - start);
        let end = start + size;
        let diagonal = l.view((start, start), (size, size));
        let solved = if size > INNER_SOLVE_BLOCK && n > HIGH_DEGREE_BASIS {
            solve_lower_by_blocks(diagonal, x, first + start, INNER_SOLVE_BLOCK)
        } else {
            forward_substitute(diagonal, x, first + start)
        };
        if !solved {
            return false;
        }
        if end < n {
            let (top, mut below) =
                x.rows_range_pair_mut(first + start..first + end, first + end..first + n);
            below.gemm(-1.0, &l.view((end, start), (n - end, size)), &top, 1.0);
        }
        start = end;
    }
    true
}

/// Columns of [`cholesky_lower`] updated together by each finished column before them.
const CHOLESKY_COLUMNS: usize = 8;

/// The lower Cholesky factor `L` of `g` (`g = L L^T`; only its lower triangle is read), with
/// zeros above the diagonal; `None` if a pivot is zero, negative or not a number. The same
/// factor as `nalgebra`'s `Cholesky::new(g).map(Cholesky::unpack)`, bit for bit: column `j` is
/// `g`'s minus `L_jk` times column `k` for `k = 0, 1, .., j - 1` in that order (each entry
/// `y <- (-L_jk) x + y`), then its pivot's square root, the entries below divided by it. Here
/// each finished column is read once for [`CHOLESKY_COLUMNS`] columns after it (each entry
/// still takes its updates in the same order): column by column, every column read all those
/// before it again, the whole factor (6 MB at degree 40) from beyond the core's cache, which
/// made the factorisation about 5% of a degree-40 rule (an 861 x 861 factor: 27 -> 18 ms).
fn cholesky_lower(mut g: DMatrix<f64>) -> Option<DMatrix<f64>> {
    let n = g.nrows();
    let a = g.as_mut_slice();
    let mut j0 = 0;
    while j0 < n {
        let j1 = (j0 + CHOLESKY_COLUMNS).min(n);
        let (done, rest) = a.split_at_mut(j0 * n);
        let block = &mut rest[..(j1 - j0) * n];
        // The columns finished before the block, each read once for all of the block;
        // compiled for each instruction set `pulp` knows (the same operations in the same
        // order whichever).
        pulp::Arch::new().dispatch(UpdateBlock { done, block, n, j0 });
        // The block's own columns, one after the other.
        for t in 0..j1 - j0 {
            let j = j0 + t;
            let (before, from_j) = block.split_at_mut(t * n);
            let col_j = &mut from_j[..n];
            for col_k in before.chunks_exact(n) {
                axpy_below(j, col_j, col_k);
            }
            let pivot = col_j[j];
            // `nalgebra`'s test: a zero pivot, or one whose square root is not taken
            // (negative or not a number).
            if pivot == 0.0 || pivot.partial_cmp(&0.0).is_none_or(|o| o.is_lt()) {
                return None;
            }
            let root = pivot.sqrt();
            col_j[j] = root;
            for y in &mut col_j[j + 1..] {
                *y /= root;
            }
        }
        j0 = j1;
    }
    g.fill_upper_triangle(0.0, 1);
    Some(g)
}

/// The updates of [`cholesky_lower`]'s block of columns `j0..` (`block`, at most
/// [`CHOLESKY_COLUMNS`] columns of `n` entries) by every finished column before it (`done`),
/// in order: each finished column read once for all of the block's columns.
struct UpdateBlock<'a> {
    done: &'a [f64],
    block: &'a mut [f64],
    n: usize,
    j0: usize,
}

impl pulp::WithSimd for UpdateBlock<'_> {
    type Output = ();
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Self { done, block, n, j0 } = self;
        for col_k in done.chunks_exact(n) {
            for (t, col_j) in block.chunks_exact_mut(n).enumerate() {
                axpy_below(j0 + t, col_j, col_k);
            }
        }
    }
}

/// `y <- (-L_jk) x + y` on rows `j..` of column `j` (`col_j`) by finished column `k` (`col_k`,
/// whose row `j` is `L_jk`): one step of [`cholesky_lower`].
#[inline(always)]
fn axpy_below(j: usize, col_j: &mut [f64], col_k: &[f64]) {
    let f = -col_k[j];
    for (y, &x) in col_j[j..].iter_mut().zip(&col_k[j..]) {
        *y += f * x;
    }
}

/// Entries of the buffer [`forward_substitute`] solves a chunk of columns in (16 KB: the
/// chunk stays in the core's first-level cache).
const SUBSTITUTION_CHUNK: usize = 2048;

/// Entries [`forward_substitute`] leaves between the end of a row of its buffer and the next
/// row: rows a power of two apart (2 KB) fell into the same few sets of the first-level cache,
/// and stores to them waited on each other.
const SUBSTITUTION_PAD: usize = 8;

/// `x <- L^{-1} x` for a small lower triangular `L` (`s x s`, a diagonal block of
/// [`solve_lower_by_blocks`]) and the rows `first..first + s` of `x` (`s x M` of them), by
/// forward substitution: `false` if a diagonal entry is zero. The same operations as
/// `nalgebra`'s `solve_lower_triangular_mut`, bit for bit: in each column, for
/// `i = 0, 1, ..`, `x_i <- x_i / L_ii`, then `x_r <- x_r - x_i L_ri` for every `r > i`. Here the columns are taken a chunk at a time, copied into rows (a
/// column's `s` entries are contiguous, a row's are `N` apart), and each step runs along the
/// rows, across the chunk's columns: column by column, a step was a loop of fewer than `s`
/// entries and the whole substitution a chain of dependent steps per column, 13% of a
/// degree-40 rule.
fn forward_substitute(l: DMatrixView<'_, f64>, x: &mut DMatrix<f64>, first: usize) -> bool {
    if (0..l.nrows()).any(|i| l[(i, i)] == 0.0) {
        return false;
    }
    let rows = x.nrows();
    // Compiled for each instruction set `pulp` knows, the best at hand chosen at run time:
    // the same operations in the same order whichever, so the same bits.
    pulp::Arch::new().dispatch(ForwardSubstitute {
        l,
        x: x.as_mut_slice(),
        rows,
        first,
    });
    true
}

/// [`forward_substitute`] as an operation `pulp` compiles for each instruction set: `x` the
/// column-major storage of a matrix of `rows` rows.
struct ForwardSubstitute<'a, 'b> {
    l: DMatrixView<'a, f64>,
    x: &'b mut [f64],
    rows: usize,
    first: usize,
}

impl pulp::WithSimd for ForwardSubstitute<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let Self { l, x, rows, first } = self;
        let s = l.nrows();
        if s == 0 || rows == 0 {
            return;
        }
        let m = x.len() / rows;
        let chunk = (SUBSTITUTION_CHUNK / s).max(1);
        // Row i of a chunk at `buffer[i stride..i stride + width]`.
        let stride = chunk + SUBSTITUTION_PAD;
        let mut buffer = vec![0.0; s * stride];
        let mut start = 0;
        while start < m {
            let width = chunk.min(m - start);
            let columns = x.chunks_exact(rows).skip(start).take(width);
            for (c, column) in columns.enumerate() {
                for (i, &v) in column[first..first + s].iter().enumerate() {
                    buffer[i * stride + c] = v;
                }
            }
            for i in 0..s {
                let (head, tail) = buffer.split_at_mut((i + 1) * stride);
                let row_i = &mut head[i * stride..i * stride + width];
                let d = l[(i, i)];
                for v in row_i.iter_mut() {
                    *v /= d;
                }
                for (r, row_r) in tail.chunks_mut(stride).enumerate() {
                    let f = l[(i + 1 + r, i)];
                    for (y, &v) in row_r[..width].iter_mut().zip(row_i.iter()) {
                        *y -= v * f;
                    }
                }
            }
            let columns = x.chunks_exact_mut(rows).skip(start).take(width);
            for (c, column) in columns.enumerate() {
                for (i, v) in column[first..first + s].iter_mut().enumerate() {
                    *v = buffer[i * stride + c];
                }
            }
            start += width;
        }
    }
}

/// The Cholesky factor of `gram + s I` with the shift of shifted Cholesky QR,
/// `s = 11 (M N + N (N + 1)) eps ||V||^2` (`||V||^2` bounded by the trace of the Gram matrix).
fn shifted_cholesky(mut gram: DMatrix<f64>, m: usize, scale: f64) -> Option<DMatrix<f64>> {
    let n = gram.nrows();
    let shift = scale * 11.0 * ((m * n + n * (n + 1)) as f64) * f64::EPSILON * gram.trace();
    for i in 0..n {
        gram[(i, i)] += shift;
    }
    cholesky_lower(gram)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Cholesky;
    use pulp::WithSimd;

    /// A symmetric positive definite matrix of size `n` from `B B^T + I` (`B` of pseudo-random
    /// entries), with a spread of scales like a Gram matrix's.
    fn spd(n: usize, seed: u64) -> DMatrix<f64> {
        let mut rng = rs_testkit::XorShift64::new(seed);
        let b = DMatrix::from_fn(n, n + 3, |i, _| rng.uniform(-0.5, 0.5) * (1.0 + i as f64));
        &b * b.transpose() + DMatrix::identity(n, n)
    }

    /// The blocked factorisation is `nalgebra`'s bit for bit, for sizes around the block's and
    /// a degree-30-like one, with the upper triangle zero and garbage there ignored; and it
    /// fails where `nalgebra`'s does (a zero, a negative and a not-a-number pivot, in the
    /// first block and past it).
    #[test]
    fn blocked_cholesky_is_nalgebras_bit_for_bit() {
        for (n, seed) in [
            (1, 1),
            (7, 2),
            (8, 3),
            (9, 4),
            (17, 5),
            (64, 6),
            (100, 7),
            (497, 8),
        ] {
            let mut g = spd(n, seed);
            // Only the lower triangle is read.
            for j in 1..n {
                g[(0, j)] = f64::NAN;
            }
            let want = Cholesky::new(g.clone())
                .map(Cholesky::unpack)
                .expect("factor");
            let got = cholesky_lower(g).expect("factor");
            assert!(
                got.iter()
                    .zip(want.iter())
                    .all(|(a, b)| a.to_bits() == b.to_bits()),
                "n {n}"
            );
        }
        for bad in [0.0, -1.0, f64::NAN] {
            for (n, at) in [(12, 3), (30, 21)] {
                let mut g = spd(n, 9);
                // Make the pivot at `at` exactly `bad` after its updates: take the factor of
                // the leading part and set the diagonal entry to its squared row plus `bad`.
                let l = Cholesky::new(g.clone())
                    .map(Cholesky::unpack)
                    .expect("factor");
                let row_sq: f64 = (0..at).map(|k| l[(at, k)] * l[(at, k)]).sum();
                g[(at, at)] = row_sq + bad;
                let want = Cholesky::new(g.clone()).map(Cholesky::unpack);
                let got = cholesky_lower(g);
                assert_eq!(got.is_some(), want.is_some(), "n {n} at {at} pivot {bad}");
                if bad.is_nan() || bad < 0.0 {
                    assert!(got.is_none(), "n {n} at {at} pivot {bad}");
                }
            }
        }
    }

    /// The Gram product through the strided view of `A^T` is the product with a transposed
    /// copy bit for bit (above `HIGH_DEGREE_BASIS`, blocks of `GRAM_BLOCK` rows), for all the
    /// columns and for a prefix of them.
    #[test]
    fn gram_through_the_strided_view_equals_the_copy_bit_for_bit() {
        let n = 2 * GRAM_BLOCK + 45;
        let a = DMatrix::from_fn(n, 3 * n / 2, |i, j| {
            (((i * 37 + j * 11) % 23) as f64 - 11.0) / 7.0 + 1e-3 * (i as f64).sqrt()
        });
        for cols in [a.ncols(), 4 * n / 3] {
            let view = a.columns(0, cols);
            let at = view.transpose();
            let mut want = DMatrix::zeros(n, n);
            let mut start = 0;
            while start < n {
                let end = (start + GRAM_BLOCK).min(n);
                want.view_mut((start, 0), (end - start, end)).gemm(
                    1.0,
                    &view.rows_range(start..end),
                    &at.columns_range(..end),
                    0.0,
                );
                start = end;
            }
            let got = gram_lower(&a, cols);
            assert!(
                got.iter()
                    .zip(want.iter())
                    .all(|(x, y)| x.to_bits() == y.to_bits()),
                "cols {cols}"
            );
        }
    }

    /// Above `HIGH_DEGREE_BASIS` rows (with a last block shorter than the others) the lower
    /// triangle equals the full product's up to rounding, and so does the Cholesky factor;
    /// below, it is the full product bit for bit.
    #[test]
    fn gram_lower_triangle_equals_the_full_product() {
        for n in [
            HIGH_DEGREE_BASIS,
            HIGH_DEGREE_BASIS + 1,
            2 * GRAM_BLOCK + 45,
        ] {
            let a = DMatrix::from_fn(n, 3 * n / 2, |i, j| {
                (((i * 37 + j * 11) % 23) as f64 - 11.0) / 7.0
            });
            let full = &a * a.transpose();
            let g = gram_lower(&a, a.ncols());
            if n <= HIGH_DEGREE_BASIS {
                assert_eq!(g, full);
            } else {
                let lower = (&g - &full).lower_triangle();
                assert!(lower.amax() <= 1e-12 * full.amax(), "n {n}");
                let shift = DMatrix::<f64>::identity(n, n) * (n as f64 * full.amax());
                let (l, want) = (
                    Cholesky::new(g + &shift).map(Cholesky::unpack),
                    Cholesky::new(&full + &shift).map(Cholesky::unpack),
                );
                let (l, want) = (l.expect("factor"), want.expect("factor"));
                assert!((&l - &want).amax() <= 1e-12 * want.amax(), "n {n}");
            }
        }
    }

    /// The forward substitution by chunks of columns is `nalgebra`'s bit for bit, for block
    /// sizes 1 to 64 and column counts around a chunk's, and reports a zero diagonal entry.
    #[test]
    fn chunked_forward_substitution_is_nalgebras_bit_for_bit() {
        for s in [1, 2, 5, 16, 17, 64] {
            let l = DMatrix::from_fn(s, s, |i, j| {
                if i == j {
                    0.5 + ((i * 7) % 5) as f64 / 3.0
                } else if i > j {
                    (((i * 31 + j * 17) % 13) as f64 - 6.0) / 11.0
                } else {
                    f64::NAN // never read
                }
            });
            let chunk = SUBSTITUTION_CHUNK / s;
            for m in [1, chunk - 1, chunk, 2 * chunk + 3] {
                let x = DMatrix::from_fn(s, m, |i, j| {
                    (((i * 13 + j * 7) % 19) as f64 - 9.0) / 7.0 + 1e-3 * j as f64
                });
                let mut want = x.clone();
                assert!(l.solve_lower_triangular_mut(&mut want));
                // Inside a taller matrix, as the blocked solve calls it.
                let mut tall = DMatrix::from_element(s + 5, m, 7.0);
                tall.rows_mut(3, s).copy_from(&x);
                assert!(forward_substitute(l.as_view(), &mut tall, 3));
                let got = tall.rows(3, s).into_owned();
                assert!(
                    tall.rows(0, 3)
                        .iter()
                        .chain(tall.rows(s + 3, 2).iter())
                        .all(|&v| v == 7.0)
                );
                assert!(
                    got.iter()
                        .zip(want.iter())
                        .all(|(a, b)| a.to_bits() == b.to_bits()),
                    "s {s} m {m}"
                );
            }
            let mut singular = l.clone();
            singular[(s - 1, s - 1)] = 0.0;
            let mut x = DMatrix::from_element(s, 3, 1.0);
            assert!(!forward_substitute(singular.as_view(), &mut x, 0));
        }
    }

    /// The blocked solve (three blocks and a remainder) matches forward substitution.
    #[test]
    fn blocked_solve_matches_forward_substitution() {
        let n = 2 * SOLVE_BLOCK + 7;
        let l = DMatrix::from_fn(n, n, |i, j| {
            if i == j {
                2.0 + (i % 5) as f64
            } else if i > j {
                (((i * 31 + j * 17) % 13) as f64 - 6.0) / 13.0
            } else {
                0.0
            }
        });
        let x = DMatrix::from_fn(n, 9, |i, j| ((i * 7 + j * 3) % 11) as f64 - 5.0);
        let want = l.solve_lower_triangular(&x).unwrap();
        let mut got = x.clone();
        assert!(solve_lower_blocked(&l, &mut got));
        assert!((&got - &want).amax() <= 1e-12 * want.amax());
        // A zero on the diagonal is reported.
        let mut singular = l.clone();
        singular[(SOLVE_BLOCK + 3, SOLVE_BLOCK + 3)] = 0.0;
        assert!(!solve_lower_blocked(&singular, &mut x.clone()));
    }

    /// Solving the candidates a chunk at a time gives the bits of solving them all at once,
    /// above and below [`HIGH_DEGREE_BASIS`] rows (whole chunks and a part chunk at the end,
    /// and fewer columns than a chunk); a zero on the diagonal is reported from a chunk.
    #[test]
    fn chunked_solve_is_the_whole_solve_bit_for_bit() {
        for (n, m, seed) in [
            (50, 3 * SOLVE_CHUNK + 17, 21),
            (300, 2 * SOLVE_CHUNK + 5, 22),
            (300, 40, 23),
        ] {
            let l = cholesky_lower(spd(n, seed)).expect("factor");
            let mut rng = rs_testkit::XorShift64::new(seed);
            let x = DMatrix::from_fn(n, m, |_, _| rng.uniform(-1.0, 1.0));
            let mut whole = x.clone();
            assert!(solve_lower_by_blocks(
                l.as_view(),
                &mut whole,
                0,
                SOLVE_BLOCK
            ));
            let mut chunked = x.clone();
            assert!(solve_lower_blocked(&l, &mut chunked));
            assert_eq!(
                chunked
                    .as_slice()
                    .iter()
                    .map(|v| v.to_bits())
                    .collect::<Vec<_>>(),
                whole
                    .as_slice()
                    .iter()
                    .map(|v| v.to_bits())
                    .collect::<Vec<_>>(),
                "n = {n}, m = {m}"
            );
            let mut singular = l.clone();
            singular[(n - 1, n - 1)] = 0.0;
            assert!(!solve_lower_blocked(&singular, &mut x.clone()));
        }
    }

    /// The normalising pass makes well-conditioned rows orthonormal, keeping `R^T Q^T = V^T`,
    /// when the moments are those of a positive measure on the candidates; moments far from
    /// any such measure (a rounding error blown up, as it would be) stop it.
    #[test]
    fn the_normalising_pass_orthonormalises_only_with_consistent_moments() {
        let (n, m) = (5, 40);
        // Row 0 constant: its moment is the area, as phi_0's.
        let v = DMatrix::from_fn(n, m, |i, j| {
            if i == 0 {
                1.0
            } else {
                (((i * 17 + j * 29 + i * j * 3) % 23) as f64 - 11.0) * (i as f64) / 11.0
            }
        });
        let area = 2.5;
        let moments = &v * DVector::from_element(m, area / m as f64);
        let (mut qt, mut rt) = (v.clone(), DMatrix::identity(n, n));
        assert_eq!(
            normalising_pass(
                &mut qt,
                &mut rt,
                moments.as_slice(),
                Reference::Uniform(usize::MAX)
            ),
            Some(true)
        );
        assert!((&qt * qt.transpose() - DMatrix::<f64>::identity(n, n)).amax() < 1e-12);
        assert!((&rt * &qt - &v).amax() < 1e-12 * v.amax());
        let mut far = moments.clone();
        far[n - 1] += 100.0 * moments.amax();
        let (mut qt, mut rt) = (v.clone(), DMatrix::identity(n, n));
        assert_eq!(
            normalising_pass(
                &mut qt,
                &mut rt,
                far.as_slice(),
                Reference::Uniform(usize::MAX)
            ),
            Some(false)
        );
        assert_eq!(qt, v);
        assert_eq!(rt, DMatrix::identity(n, n));
    }

    /// `moment_error` is `max |R^T r|`.
    #[test]
    fn moment_error_is_the_largest_entry_of_r_transpose_times_r() {
        let rt = DMatrix::from_fn(
            4,
            4,
            |i, j| if i >= j { (i + 2 * j + 1) as f64 } else { 0.0 },
        );
        let o = Orthonormal {
            qt: DMatrix::zeros(4, 4),
            b: DVector::zeros(4),
            rt: rt.clone(),
            normalised: false,
        };
        let r = [0.5, -1.0, 2.0, 0.25];
        let want = (&rt * DVector::from_column_slice(&r)).amax();
        assert!((o.moment_error(&r) - want).abs() <= 1e-14 * want);
        // Compiled for the best instruction set at hand, the baseline's bits (a size with a
        // tail past the vectors' width).
        let n = 203;
        let rt = DMatrix::from_fn(n, n, |i, j| {
            if i >= j {
                ((i * 31 + j * 17) % 29) as f64 / 7.0 - 2.0
            } else {
                0.0
            }
        });
        let o = Orthonormal {
            qt: DMatrix::zeros(n, 1),
            b: DVector::zeros(n),
            rt,
            normalised: false,
        };
        // Several residuals, each with its largest entry in another row; and a short one.
        for seed in 1..=6u64 {
            let mut rng = rs_testkit::XorShift64::new(seed);
            let len = if seed == 6 { n - 2 } else { n };
            let r: Vec<f64> = (0..len).map(|_| rng.next_f64() * 4.0 - 2.0).collect();
            let base = MomentError {
                rt: o.rt.as_slice(),
                n,
                r: &r,
            }
            .with_simd(pulp::Scalar);
            assert_eq!(o.moment_error(&r).to_bits(), base.to_bits());
            // Both give the plain column-by-column sums' bits.
            let mut sums = vec![0.0; n];
            for (k, &rk) in r.iter().enumerate() {
                for (l, s) in sums.iter_mut().enumerate().skip(k) {
                    *s += o.rt[(l, k)] * rk;
                }
            }
            let want = sums.iter().fold(0.0f64, |a, s| a.max(s.abs()));
            assert_eq!(base.to_bits(), want.to_bits(), "seed {seed}");
        }
    }
}
