//! The one evaluation kernel every B-spline of this workspace goes through: homogeneous sums of
//! basis functions times weighted control points ([`rational_sums`]) and the quotient rule that
//! turns them into points and derivatives ([`rational_quotient`]).

use rs_roots::Blend;

use crate::KnotVector;

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
    knots.with_basis_derivatives(k, u, nd, |basis| {
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
