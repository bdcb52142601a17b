//! Positive interior cubature on NURBS-shaped domains: for a degree `n`, a rule with at most
//! `dim P_n = (n + 1)(n + 2) / 2` nodes, all strictly inside the domain, all weights positive,
//! exact (up to a reported residual) for every polynomial of total degree `<= n`. The method
//! of Sommariva and Vianello: exact moments by Green's theorem on the boundary's Bezier
//! pieces, then Caratheodory-Tchakaloff compression of a discrete measure on candidate points
//! by non-negative least squares.
//!
//! # Method
//! - **Basis.** Products of normalised Legendre polynomials of the coordinates scaled to the
//!   bounding box, `phi_ij = sqrt((2i + 1)(2j + 1)) P_i(u) P_j(v)`, `u = (x - cx) / hx`,
//!   `v = (y - cy) / hy`, `i + j <= n`, in graded order. Orthogonal on the box, so their
//!   Vandermonde matrix at points spread over the domain is far better conditioned than
//!   that of raw monomials.
//! - **Moments.** `integral phi dA = oint F dy`, `F = integral phi dx` (the antiderivative of
//!   `P_i` is `(P_{i+1} - P_{i-1}) / (2i + 1)`), on every Bezier piece, each loop multiplied
//!   by its boundary sign under the fill rule ([`CubatureOptions::fill_rule`],
//!   [`rs_contain::LoopNesting::boundary_sign`]): holes and several loops are handled,
//!   whatever the loops' orientation; loops that cross are refused. Polynomial pieces of degree
//!   `p`: Gauss-Legendre with `ceil(p (n + 2) / 2)` nodes, exact. Rational pieces: adaptive
//!   Gauss-Legendre with an error estimate and bounded work; a piece that does not converge is
//!   an error. Both by [`rs_spline::green`], the Green's-theorem kernel cell coverage uses too.
//! - **Candidates.** Points kept when the grid locator classifies them
//!   [`Location::Inside`](rs_contain::Location::Inside) (farther than the boundary
//!   tolerance, `1e-12` of the box's diagonal, from the boundary). Up to degree 20: Halton
//!   points in the bounding box, `k x dim P_n` of them in the first attempt, `k` the
//!   [`CubatureOptions::candidates_per_polynomial`], at most 256 Halton points tried per
//!   candidate wanted. Above degree 20 (where `k` is not used): `dim P_n` Halton points and
//!   **boundary layers**, because positive rules of high degree cluster their nodes towards
//!   the boundary (Gauss-like, about `1 / n^2` of the width from it) and uniform points
//!   under-sample it (they needed `18 dim P_n` at degree 30 and `24 dim P_n` at 40). Every
//!   Bezier piece is sampled by arc length (about `2.5 (n + 1)` points per bounding-box
//!   diagonal, clustered like Chebyshev points towards the piece's ends that are corners) and
//!   each sample offset along both normals by `K = ceil(1.5 (n + 2) / 4)` distances
//!   `w (1 - cos theta_k)`, `theta_k = (k - 1/2) pi / (2 K)`, `w = 2 area / boundary length`
//!   (spaced as Gauss points are across the width, one and a half times as dense). That is
//!   `4.9-8.3 dim P_n` candidates in all on the paper's domains at degrees 30 and 40. Each
//!   retry doubles the Halton points and the layers' points (`sqrt 2` more along the boundary
//!   and across).
//! - **Chord formula** (above degree 20). Before those attempts, the candidates are the nodes
//!   of a positive interior formula of the filled set itself: the `x` axis is cut at the end
//!   abscissas of the boundary's monotone pieces, so that over each interval the same pieces
//!   span it and pair up, sorted by ordinate, into vertical chords of the set; each chord gets
//!   `n / 2 + 1` Gauss-Legendre nodes (exact in `y`), each interval Gauss-Legendre nodes in a
//!   variable `s` with `x = a + (b - a) I_s(p, q)` (an incomplete beta function that undoes
//!   vertical tangents at the interval's ends), their number raised by half from 4 until the
//!   interval's moments agree with the next order's (an interval that needs more than 32 is
//!   halved instead). Every weight is positive and every node strictly inside its chord (kept
//!   when the grid locator says `Inside`). The compression then takes the moments from the
//!   formula, `b = Q^T w`, consistent with the candidates by construction, so the Cholesky QR
//!   needs a shift `1e-7` times the usual one: two or three passes, `Q` near orthonormal and
//!   an NNLS of a few dozen iterations, whose entering columns' Householder reflections are
//!   applied to its `Q` together, by two matrix products (compact WY), not one pass over `Q`
//!   each. The weights are refined against Green's theorem's
//!   moments (as below, then by conjugate gradients on the nodes' Vandermonde matrix, stopped
//!   early, from the moments' errors in compensated sums: the rounding of plain sums was as
//!   large as the errors) and the rule accepted on its residual, as any other. The formula is
//!   skipped when it would have more than `10 dim P_n` nodes (many loops stacked over the same
//!   abscissas), and an attempt on it that misses the target falls back to the Halton points
//!   and layers.
//! - **Orthonormal basis.** The Vandermonde matrix `V` at the candidates is orthonormalised,
//!   `V = Q R`, by Cholesky QR (a second pass when the first factor is ill-conditioned, a
//!   shifted pass when the Gram matrix is numerically singular; each pass applies its factor
//!   by a blocked triangular solve, backward stable where multiplying by the factor's inverse
//!   is not: matrix products at `gemm` speed), and the moments carried along:
//!   `Q^T w = R^{-T} m` is `V^T w = m`. After three shifted passes one more, unshifted, pass
//!   makes `Q` orthonormal when that keeps the moments consistent with the candidates (the
//!   shift leaves `Q` regularised, and the NNLS on it takes several times the iterations); a
//!   rule made on the normalised basis that misses its target is made again without it, the
//!   one with the smaller residual kept.
//! - **Compression.** Non-negative least squares on `min ||Q^T w - R^{-T} m||`, `w >= 0`:
//!   Lawson-Hanson's active-set method with the deviation-maximisation choice of entering
//!   columns (LHDM, Dessole, Marcuzzi and Vianello: several nearly orthogonal columns with
//!   large gradients enter at once) and the passive set's QR factorisation updated column by
//!   column; above degree 20, between full passes over all the candidates' gradients (every
//!   fourth iteration) only the `dim P_n` with the largest are scored (up to degree 20 every
//!   pass is full: those rules are unchanged bit for bit); at most `dim P_n` weights are
//!   positive. An attempt whose moments are out of reach
//!   fails fast: the NNLS stops when the largest error of the moments of its iterate has not
//!   halved over the last `max(dim P_n / 4, 50)` iterations while above the target (a stall:
//!   the residual then converges to the distance from the moments to the cone of the
//!   candidates, far above the target). The nodes are the candidates with
//!   positive weights. The weights are then refined (at most three steps, kept while they stay
//!   positive and the residual falls): the residual of the moments is computed in the basis
//!   itself, mapped by `R^{-T}` and solved for on the passive set, so the final accuracy does
//!   not depend on how orthonormal `Q` is.
//! - **Residual.** Computed afresh from the nodes and weights ([`CubatureRule::residual`]). If
//!   it is above [`CubatureOptions::target_residual`], or the candidates do not resolve the
//!   polynomials, the attempt is repeated with twice the candidates, at most
//!   [`CubatureOptions::max_retries`] times.
//!
//! # Semantics
//! A rule from [`CubatureRule::new`] guarantees: every node classified `Inside` by the
//! domain's [`rs_contain::Classifier`]; every weight `> 0`; at most `dim P_n` nodes; the
//! residual at most the target (default `1e-13`); the weights add up to the filled area up
//! to the residual. The domain must be closed (an open boundary is an error). The fill is
//! even-odd unless [`CubatureOptions::with_fill_rule`] says otherwise; loops that cross each
//! other or themselves are refused ([`rs_contain::fill_nesting`]). See docs/SEMANTICS.md.
//!
//! # Examples
//!
//! ```
//! use rs_cubature::CubatureRule;
//! use rs_spline::{circle, Domain, Point};
//! // An annulus: 1 <= r <= 2. The integral of x^2 over it is (2^4 - 1) pi / 4.
//! let d = Domain::new(vec![
//!     circle(Point::new(0.0, 0.0), 2.0).unwrap(),
//!     circle(Point::new(0.0, 0.0), 1.0).unwrap(),
//! ])
//! .unwrap();
//! let rule = CubatureRule::new(&d, 6).unwrap();
//! let got = rule.integrate(|p| p.x * p.x).unwrap();
//! assert!((got - 15.0 * std::f64::consts::PI / 4.0).abs() < 1e-12);
//! ```
//!
//! # References
//! - A. Sommariva, M. Vianello, *Compression of multivariate discrete measures and
//!   applications*, Numer. Funct. Anal. Optim. 36 (2015) 1198-1223.
//! - A. Sommariva, M. Vianello, *Low cardinality positive interior cubature on NURBS-shaped
//!   domains*, BIT Numer. Math. 63 (2023).
//! - C. L. Lawson, R. J. Hanson, *Solving Least Squares Problems* (Prentice-Hall, 1974),
//!   chapter 23.
//! - M. Dessole, F. Marcuzzi, M. Vianello, *Accelerating the Lawson-Hanson NNLS solver: a new
//!   strategy based on Deviation Maximization*, Adv. Comput. Math. (2020).
//! - T. Fukaya, Y. Nakatsukasa, Y. Yanagisawa, Y. Yamamoto, *`CholeskyQR2`: a simple and
//!   communication-avoiding algorithm for computing a tall-skinny QR factorization* (2014);
//!   T. Fukaya, R. Kannan, Y. Nakatsukasa, Y. Yamamoto, Y. Yanagisawa, *Shifted Cholesky QR
//!   for computing the QR factorization of ill-conditioned matrices*, SIAM J. Sci. Comput.
//!   42 (2020).

mod basis;
mod candidates;
mod chords;
mod error;
mod moments;
mod nnls;
mod orthogonal;
mod rule;

pub use basis::dim_polynomials;
pub use error::CubatureError;
pub use moments::monomial_moments;
/// The point type of the nodes (from `rs-spline`).
pub use rs_spline::Point;
pub use rule::{
    CubatureOptions, CubatureRule, DEFAULT_CANDIDATES_PER_POLYNOMIAL, DEFAULT_MAX_CANDIDATES,
    DEFAULT_MAX_RETRIES, DEFAULT_TARGET_RESIDUAL, MAX_CANDIDATES, MAX_RETRIES, SMALLEST_AREA,
};

/// The highest degree of exactness a rule or a moment vector may have: 40, `dim P_40 = 861`
/// basis polynomials. The work of a rule grows like `n^6` (the orthonormalisation costs
/// `M N^2` with `N = dim P_n` and `M` candidates, `12 N` up to degree 20 and about `2-10 N`
/// beyond, the chord formula's nodes or the boundary layers) and its memory like `n^4` (the
/// candidates' Vandermonde matrix, `4 900 x 861` values, 34 MB, at degree 40 on the paper's
/// lune; at most `20 000 x 861`, 138 MB, with the default cap). Measured on one core on the
/// inRS paper's three domains with the default options: degree 20 in about 30-55 ms, degree
/// 30 in 0.10-0.18 s, degree 40 in 0.55-0.95 s (the box-scaled Legendre basis is so
/// ill-conditioned on these domains that the orthonormalisation takes two or three Cholesky
/// passes, the first shifted). A domain
/// on which positive weights need more candidates than the cap gets an error
/// (`ResidualNotReached`), not a wrong rule. Moments alone ([`monomial_moments`]) are cheap at
/// any degree up to it.
pub const MAX_DEGREE: usize = 40;
