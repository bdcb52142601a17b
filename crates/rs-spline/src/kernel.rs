//! The one evaluation kernel every B-spline of this workspace goes through: homogeneous sums of
//! basis functions times weighted control points ([`rational_sums`]) and the quotient rule that
//! turns them into points and derivatives ([`rational_quotient`]).

use rs_roots::Blend;

use crate::KnotVector;

/// Whether the weights `w_0 .. w_n` are all equal (true for none), so that they cancel in
/// `sum w_j B_j P_j / sum w_j B_j` and the rational curve is the polynomial one with the same
/// control points. Exact comparison: a weight off by one ulp makes the curve rational.
pub fn weights_are_equal(weights: &[f64]) -> bool {
    weights.iter().all(|&w| w == weights[0])
}

/// Homogeneous sums at `u` (clamped into the domain) on the knot span holding it: for each
/// derivative order `d <= nd` (at most 2), `(sum_j w_j N_j^(d)(u) P_j, sum_j w_j N_j^(d)(u))`
/// over the `p + 1` basis functions non-zero there; entries past `nd` are zero. Without
/// `weights` every weight is 1.
///
/// This is the one B-spline evaluation kernel (de Boor's basis functions, The NURBS Book
/// A2.3, in [`KnotVector`]): planar [`crate::NurbsCurve`]s, curves of any dimension and
/// tensor-product surfaces are all evaluated through it. Each term is `(w P) N` and `w N`,
/// summed in the order of the basis functions.
pub fn rational_sums<P: Blend>(
    knots: &KnotVector,
    points: &[P],
    weights: Option<&[f64]>,
    u: f64,
    nd: usize,
) -> [(P, f64); 3] {
    let (a, b) = knots.domain();
    let u = u.clamp(a, b);
    let p = knots.degree();
    let k = knots.span(u);
    let nd = nd.min(2);
    knots.with_basis_derivatives(k, u, nd, |basis| span_sums(basis, p, k, points, weights))
}

/// The sums of [`rational_sums`] from the basis table `basis` (row `d` the `p + 1` basis
/// functions' `d`-th derivatives on span `k`): `(sum w N^(d) P, sum w N^(d))` for each row,
/// each term `(w P) N` and `w N` in the order of the basis functions.
fn span_sums<P: Blend>(
    basis: &[f64],
    p: usize,
    k: usize,
    points: &[P],
    weights: Option<&[f64]>,
) -> [(P, f64); 3] {
    let mut out = [(P::default(), 0.0); 3];
    for (slot, row) in out.iter_mut().zip(basis.chunks_exact(p + 1)) {
        for (j, &n) in row.iter().enumerate() {
            let i = k - p + j;
            let w = weights.map_or(1.0, |w| w[i]);
            slot.0 = slot.0 + points[i] * w * n;
            slot.1 += w * n;
        }
    }
    out
}

/// The homogeneous sums of a tensor-product surface at `(u, v)` (each clamped into its
/// knot domain): `out[du][dv]` is `(sum w N_i^(du)(u) M_j^(dv)(v) P_ij, sum w N^(du) M^(dv))`
/// for `du + dv <= nd` (at most 2; the rest zero), over the `(p + 1)(q + 1)` control points
/// `points[i * nv + j]` (row `i` along `u`, `nv` points a row) non-zero there.
///
/// Each row's sums along `v` are [`rational_sums`]' terms in its order, combined along `u` in
/// the order of the basis functions; each direction's basis functions are worked out once
/// (on the stack), not once per row.
///
/// # Panics
/// If `points` (or `weights`) holds fewer than `n_u * n_v` entries, the knot vectors' numbers
/// of control points (a surface checks this when it is built).
pub fn tensor_rational_sums<P: Blend>(
    knots: [&KnotVector; 2],
    points: &[P],
    weights: Option<&[f64]>,
    uv: [f64; 2],
    nd: usize,
) -> [[(P, f64); 3]; 3] {
    let [ku, kv] = knots;
    let nd = nd.min(2);
    let (a, b) = ku.domain();
    let u = uv[0].clamp(a, b);
    let (c, d) = kv.domain();
    let v = uv[1].clamp(c, d);
    let (p, q) = (ku.degree(), kv.degree());
    let (k, l) = (ku.span(u), kv.span(v));
    let nv = kv.n_control();
    ku.with_basis_derivatives(k, u, nd, |bu| {
        kv.with_basis_derivatives(l, v, nd, |bv| {
            let mut h = [[(P::default(), 0.0); 3]; 3];
            for r in 0..=p {
                let i = k - p + r;
                let row = &points[i * nv..(i + 1) * nv];
                let row_weights = weights.map(|w| &w[i * nv..(i + 1) * nv]);
                // The row's sums along v, as `rational_sums` forms them.
                let along = span_sums(bv, q, l, row, row_weights);
                for (du, basis) in bu.chunks_exact(p + 1).enumerate() {
                    let n = basis[r];
                    for dv in 0..=nd - du {
                        let (ref mut pt, ref mut w) = h[du][dv];
                        *pt = *pt + along[dv].0 * n;
                        *w += along[dv].1 * n;
                    }
                }
            }
            h
        })
    })
}

/// The quotient rule for `C = A / w` from homogeneous sums `[A, A', A'']` with their weights:
/// `C = A / w`, `C' = (A' - w' C) / w`, `C'' = (A'' - 2 w' C' - w'' C) / w`.
pub fn rational_quotient<P: Blend + std::ops::Div<f64, Output = P>>(h: [(P, f64); 3]) -> [P; 3] {
    let w = h[0].1;
    let point = h[0].0 / w;
    let first = (h[1].0 - point * h[1].1) / w;
    let second = (h[2].0 - first * (2.0 * h[1].1) - point * h[2].1) / w;
    [point, first, second]
}
