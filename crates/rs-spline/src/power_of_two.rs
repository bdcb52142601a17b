//! Exact scaling by a power of two over the whole exponent range.

/// `x 2^e` for `|e| <= 1100`, exactly where the result and `x 2^(e / 2)` are normal: two
/// factors, each a normal power of two (`2^e` alone is not one for `e < -1022` or `e > 1023`).
pub fn times_power_of_two(x: f64, e: i32) -> f64 {
    let half = e / 2;
    x * 2f64.powi(half) * 2f64.powi(e - half)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Exact across the range, where one factor `2^e` would overflow or underflow.
    #[test]
    fn scales_exactly_across_the_range() {
        assert_eq!(times_power_of_two(3.0, 4), 48.0);
        assert_eq!(
            times_power_of_two(f64::MAX, -1024),
            f64::MAX / 2f64.powi(1023) / 2.0
        );
        assert_eq!(times_power_of_two(f64::MIN_POSITIVE, 1060), 2f64.powi(38));
        assert_eq!(times_power_of_two(1.5, -1060), 1.5 * 2f64.powi(-1060));
        for e in -1100..=1100 {
            let x = times_power_of_two(1.25, e);
            if x.is_normal() {
                assert_eq!(times_power_of_two(x, -e), 1.25, "{e}");
            }
        }
    }
}
