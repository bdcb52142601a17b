//! Closed-form roots for degree one and two.

/// The real root of `c0 + c1 t`, if `c1 != 0`.
pub fn linear_root(c0: f64, c1: f64) -> Option<f64> {
    if c1 == 0.0 { None } else { Some(-c0 / c1) }
}

/// Real roots of `c0 + c1 t + c2 t^2`, ascending, a double root reported once.
///
/// Uses the cancellation-free form `q = -(c1 + sign(c1) sqrt(D)) / 2`, `t1 = q / c2`,
/// `t2 = c0 / q` with `D = c1^2 - 4 c2 c0`. A discriminant within rounding of zero
/// (`|D| <= 8 eps (c1^2 + 4 |c2 c0|)`) is treated as a double root, so `(t - 0.1)^2` is not
/// lost to rounding. Falls back to [`linear_root`] when `c2 == 0`. The all-zero polynomial
/// returns no roots (callers that care check for it first).
///
/// # Examples
///
/// ```
/// use rs_roots::quadratic_roots;
/// assert_eq!(quadratic_roots(2.0, -3.0, 1.0), vec![1.0, 2.0]);
/// assert_eq!(quadratic_roots(0.25, -1.0, 1.0), vec![0.5]);
/// assert!(quadratic_roots(1.0, 0.0, 1.0).is_empty());
/// ```
pub fn quadratic_roots(c0: f64, c1: f64, c2: f64) -> Vec<f64> {
    if c2 == 0.0 {
        return linear_root(c0, c1).into_iter().collect();
    }
    let disc = c1 * c1 - 4.0 * c2 * c0;
    let noise = 8.0 * f64::EPSILON * (c1 * c1 + 4.0 * (c2 * c0).abs());
    if disc.abs() <= noise {
        return vec![-c1 / (2.0 * c2)];
    }
    if disc < 0.0 {
        return Vec::new();
    }
    let q = -0.5 * (c1 + c1.signum() * disc.sqrt());
    let (mut r1, mut r2) = (q / c2, c0 / q);
    if c1 == 0.0 {
        // q = -sqrt(D)/2: the roots are +-sqrt(-c0/c2); both formulas above are still fine,
        // but make sure they are symmetric.
        r1 = -(-c0 / c2).sqrt();
        r2 = -r1;
    }
    if r1 > r2 {
        std::mem::swap(&mut r1, &mut r2);
    }
    vec![r1, r2]
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn linear() {
        assert_eq!(linear_root(2.0, -4.0), Some(0.5));
        assert_eq!(linear_root(2.0, 0.0), None);
    }

    #[test]
    fn quadratic_avoids_cancellation() {
        // Roots 1e-9 and 1e9: the textbook formula loses the small one completely.
        let r = quadratic_roots(1.0, -(1e9 + 1e-9), 1.0);
        assert_eq!(r.len(), 2);
        assert_relative_eq!(r[0], 1e-9, max_relative = 1e-14);
        assert_relative_eq!(r[1], 1e9, max_relative = 1e-14);
    }

    #[test]
    fn quadratic_double_root_survives_rounding() {
        for &r in &[0.1, 1.0 / 3.0, 0.7, -2.9] {
            let roots = quadratic_roots(r * r, -2.0 * r, 1.0);
            assert_eq!(roots.len(), 1, "double root {r} -> {roots:?}");
            assert_relative_eq!(roots[0], r, max_relative = 1e-12);
        }
    }

    #[test]
    fn quadratic_symmetric_and_degenerate() {
        assert_eq!(quadratic_roots(-4.0, 0.0, 1.0), vec![-2.0, 2.0]);
        assert_eq!(quadratic_roots(3.0, 0.0, 0.0), Vec::<f64>::new());
        assert_eq!(quadratic_roots(0.0, 2.0, 1.0), vec![-2.0, 0.0]);
    }
}
