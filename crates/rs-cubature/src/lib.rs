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
//!   by its even-odd boundary sign ([`rs_contain::LoopNesting::boundary_sign`]): holes and
//!   several loops are handled, whatever the loops' orientation. Polynomial pieces of degree
//!   `p`: Gauss-Legendre with `ceil(p (n + 2) / 2)` nodes, exact. Rational pieces: adaptive
//!   Gauss-Legendre with an error estimate and bounded work
//!   ([`rs_spline::quadrature::integrate_adaptive_vector`]); a piece that does not converge is
//!   an error.
//! - **Candidates.** Halton points in the bounding box kept when the grid locator classifies
//!   them [`Location::Inside`](rs_contain::Location::Inside) (farther than the boundary
//!   tolerance, `1e-12` of the box's diagonal, from the boundary):
//!   [`CubatureOptions::candidates_per_polynomial`]` x dim P_n` of them, at most 256 Halton
//!   points tried per candidate wanted.
//! - **Orthonormal basis.** The Vandermonde matrix `V` at the candidates is orthonormalised,
//!   `V = Q R`, by CholeskyQR twice (Householder QR first if `V` is too ill-conditioned), and
//!   the moments carried along: `Q^T w = R^{-T} m` is `V^T w = m`.
//! - **Compression.** Lawson-Hanson non-negative least squares on `min ||Q^T w - R^{-T} m||`,
//!   `w >= 0`, with the passive set's QR factorisation updated column by column; at most
//!   `dim P_n` weights are positive. The nodes are the candidates with positive weights.
//! - **Residual.** Computed afresh from the nodes and weights ([`CubatureRule::residual`]). If
//!   it is above [`CubatureOptions::target_residual`], or the candidates do not resolve the
//!   polynomials, the attempt is repeated with twice the candidates, at most
//!   [`CubatureOptions::max_retries`] times.
//!
//! # Semantics
//! A rule from [`CubatureRule::new`] guarantees: every node classified `Inside` by the
//! domain's [`rs_contain::Classifier`]; every weight `> 0`; at most `dim P_n` nodes; the
//! residual at most the target (default `1e-13`); the weights add up to the even-odd area up
//! to the residual. The domain must be closed (an open boundary is an error). The fill is
//! even-odd. See docs/SEMANTICS.md.
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
//! - T. Fukaya, Y. Nakatsukasa, Y. Yanagisawa, Y. Yamamoto, *CholeskyQR2: a simple and
//!   communication-avoiding algorithm for computing a tall-skinny QR factorization* (2014).

mod basis;
mod candidates;
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
    DEFAULT_MAX_RETRIES, DEFAULT_TARGET_RESIDUAL, MAX_CANDIDATES, MAX_RETRIES,
};

/// The highest degree of exactness a rule or a moment vector may have: 40, `dim P_40 = 861`
/// basis polynomials. The work grows like `n^6` (the orthonormalisation costs
/// `M N^2` with `N = dim P_n` and `M ~ 6 N` candidates) and the memory like `n^4` (the
/// candidates' Vandermonde matrix, 35 MB at degree 40 with the default candidates, up to
/// 138 MB with the default cap); beyond it the scaled Legendre basis at a few thousand
/// Halton points no longer resolves every polynomial reliably in double precision.
pub const MAX_DEGREE: usize = 40;
