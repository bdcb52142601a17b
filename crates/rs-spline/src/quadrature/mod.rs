//! Gauss-Legendre quadrature: the one cache of fixed rules ([`gauss_rule`]) and the adaptive
//! rule with an error estimate and bounded work ([`integrate_adaptive_vector`],
//! [`integrate_adaptive`]). Green's-theorem integrals along boundary pieces, which choose
//! between the two, are [`crate::green`]'s.

mod adaptive;
mod gauss;

pub(crate) use adaptive::integrate_adaptive_into;
pub use adaptive::{
    Integral, MAX_INTERVALS, VectorIntegral, integrate_adaptive, integrate_adaptive_vector,
};
pub use gauss::{GaussRule, MAX_GAUSS_NODES, fixed_gauss_rule, gauss_rule, gauss_rule_exact_for};
