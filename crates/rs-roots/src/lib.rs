//! Real roots of real polynomials, for the inRS containment layers.
//!
//! The real roots of `p(t) = sum_i c_i t^i` in `[a, b]` are the real eigenvalues of its
//! companion matrix, polished by Newton's method and accepted only within Horner's rounding
//! bound; on `[0, 1]` the Bernstein form `sum_k b_k C(n,k) t^k (1-t)^(n-k)` is evaluated and
//! split by de Casteljau's algorithm (the workspace's one kernel), and its coefficient sign
//! changes bound the roots.
//!
//! # Conventions
//! Every power-basis coefficient slice in this crate (and in the crates above it) is in
//! **ascending** order: `c[i]` multiplies `t^i`. Bernstein coefficients `b_0 .. b_n` are on
//! `[0, 1]`.
//!
//! # What is here
//! - [`Polynomial`]: power basis; Horner evaluation with a rounding bound, derivative,
//!   arithmetic, Taylor shift.
//! - [`Bernstein`]: Bernstein basis on `[0, 1]`; conversions, de Casteljau evaluation and split.
//! - [`real_roots_in`]: all real roots in `[a, b]` from the companion matrix, hardened to
//!   terminate on every input (see its docs), with [`bernstein_roots_in`] as fallback.
//! - [`linear_root`], [`quadratic_roots`]: closed forms, cancellation-free.
//! - [`itp`] and [`newton_bracketed`]: guaranteed-convergence solvers for one sign change.
//! - [`bernstein_roots`]: certified sign-variation root isolation.
//!
//! # Examples
//!
//! ```
//! use rs_roots::{real_roots_in, Polynomial};
//! // t^3 - t = t (t - 1)(t + 1)
//! let p = Polynomial::new(vec![0.0, -1.0, 0.0, 1.0]);
//! assert_eq!(real_roots_in(&p, -2.0, 2.0).unwrap(), vec![-1.0, 0.0, 1.0]);
//! ```

mod bernstein;
mod bracket;
mod closed_form;
mod companion;
mod error;
mod isolate;
mod polynomial;
mod rational_derivative;

pub use bernstein::{
    Bernstein, Blend, binomial, de_casteljau, de_casteljau_split, de_casteljau_with_derivative,
};
pub use bracket::{bernstein_sign_change_root, itp, newton_bracketed};
pub use closed_form::{linear_root, quadratic_roots};
pub use companion::real_roots_in;
pub use error::RootsError;
pub use isolate::{bernstein_roots, bernstein_roots_in};
pub use polynomial::Polynomial;
pub use rational_derivative::{
    clearly_one_signed, no_interior_root, rational_derivative_numerator,
};
