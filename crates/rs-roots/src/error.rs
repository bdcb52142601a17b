//! Error type of the root finders.

use thiserror::Error;

/// What can go wrong when asking for roots.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RootsError {
    /// A coefficient is NaN or infinite.
    #[error("coefficient {index} is not finite ({value:?})")]
    NonFiniteCoefficient {
        /// Index of the offending coefficient (ascending order).
        index: usize,
        /// Its value.
        value: f64,
    },
    /// The polynomial is identically zero, so every point is a root.
    #[error("the zero polynomial has infinitely many roots")]
    ZeroPolynomial,
    /// The search interval is empty, reversed or not finite.
    #[error("invalid interval [{a:?}, {b:?}]")]
    InvalidInterval {
        /// Lower end.
        a: f64,
        /// Upper end.
        b: f64,
    },
    /// A bracketed solver was given an interval without a sign change.
    #[error("no sign change on the bracket: f(a) = {fa:?}, f(b) = {fb:?}")]
    NoSignChange {
        /// Function value at the lower end.
        fa: f64,
        /// Function value at the upper end.
        fb: f64,
    },
    /// The function returned NaN or an infinity during a bracketed solve.
    #[error("function value is not finite at t = {t:?}")]
    NonFiniteValue {
        /// Where it happened.
        t: f64,
    },
}

/// Checks that all coefficients are finite.
pub(crate) fn check_finite(coeffs: &[f64]) -> Result<(), RootsError> {
    match coeffs.iter().position(|c| !c.is_finite()) {
        Some(index) => Err(RootsError::NonFiniteCoefficient {
            index,
            value: coeffs[index],
        }),
        None => Ok(()),
    }
}

/// Checks that `[a, b]` is a finite, non-reversed interval.
pub(crate) fn check_interval(a: f64, b: f64) -> Result<(), RootsError> {
    if a.is_finite() && b.is_finite() && a <= b {
        Ok(())
    } else {
        Err(RootsError::InvalidInterval { a, b })
    }
}
