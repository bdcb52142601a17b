//! Small exact counting functions shared by the closed-form and polygon-oracle tests.

/// `n choose k` as a float (exact for the sizes the tests use).
pub(crate) fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
}

/// `n!` as a float.
pub(crate) fn factorial(n: usize) -> f64 {
    (1..=n).fold(1.0, |f, i| f * i as f64)
}
