//! A small seeded pseudo-random generator for reproducible test inputs.

/// Marsaglia's xorshift64 generator (shifts 13, 7, 17), seeded directly with its state: the
/// same seed gives the same sequence on every run and platform, so a test's random inputs are
/// fixed. Not for statistics beyond test inputs, and not cryptographic.
///
/// # Examples
///
/// ```
/// use rs_testkit::XorShift64;
/// let mut rng = XorShift64::new(0x9E37_79B9_7F4A_7C15);
/// let u = rng.next_f64();
/// assert!((0.0..1.0).contains(&u));
/// let x = rng.uniform(-2.0, 4.0);
/// assert!((-2.0..4.0).contains(&x));
/// assert!(rng.below(10) < 10);
/// ```
#[derive(Clone, Debug)]
pub struct XorShift64 {
    /// Never 0: xorshift maps 0 to 0, and every nonzero state to a nonzero one.
    state: u64,
}

impl XorShift64 {
    /// The generator whose first output is the xorshift step of `seed`.
    ///
    /// # Panics
    /// If `seed` is 0 (the generator would give 0 forever).
    pub fn new(seed: u64) -> Self {
        assert_ne!(seed, 0, "xorshift needs a nonzero seed");
        Self { state: seed }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state ^= self.state << 13;
        self.state ^= self.state >> 7;
        self.state ^= self.state << 17;
        self.state
    }

    /// A float in `[0, 1)`: the top 53 bits of [`XorShift64::next_u64`] over `2^53` (exact, so
    /// every value is a multiple of `2^-53`).
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A float in `[lo, hi)` (up to the rounding of `lo + (hi - lo) u`, which can reach `hi`):
    /// `lo + (hi - lo) * next_f64()`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }

    /// `count` points of the bounding box of `d` grown by `grow` times its width on each side
    /// in `x` (its height in `y`): each [`XorShift64::uniform`] in `x`, then in `y`.
    pub fn points_around(
        &mut self,
        d: &rs_spline::Domain,
        grow: f64,
        count: usize,
    ) -> Vec<rs_spline::Point> {
        let b = d.bounding_box();
        let (gx, gy) = (grow * b.width(), grow * b.height());
        (0..count)
            .map(|_| {
                let x = self.uniform(b.min.x - gx, b.max.x + gx);
                rs_spline::Point::new(x, self.uniform(b.min.y - gy, b.max.y + gy))
            })
            .collect()
    }

    /// An integer in `0..n`: [`XorShift64::next_u64`] modulo `n` (its bias, below `n / 2^64`,
    /// does not matter for test inputs).
    ///
    /// # Panics
    /// If `n` is 0.
    pub fn below(&mut self, n: u64) -> u64 {
        self.next_u64() % n
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sequence of the copies this type replaced: xorshift64 (13, 7, 17) from the seed.
    #[test]
    fn first_outputs_are_the_xorshift_steps_of_the_seed() {
        let mut rng = XorShift64::new(1);
        assert_eq!(rng.next_u64(), 0x4082_2041);
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut rng = XorShift64::new(state);
        for _ in 0..100 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            assert_eq!(rng.next_u64(), state);
        }
    }

    #[test]
    fn floats_stay_in_their_ranges() {
        let mut rng = XorShift64::new(0x9E37_79B9_7F4A_7C15);
        for _ in 0..10_000 {
            let u = rng.next_f64();
            assert!((0.0..1.0).contains(&u));
            assert!((-3.0..5.0).contains(&rng.uniform(-3.0, 5.0)));
            assert!(rng.below(7) < 7);
        }
    }
}
