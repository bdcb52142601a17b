//! Helpers of the curve tests: a seeded generator and random placements.

use rs_spline::{Point, Point3};

/// xorshift64: a fixed stream of test inputs from a seed.
pub(crate) struct Rng(u64);

impl Rng {
    pub(crate) fn new(seed: u64) -> Self {
        Self(seed | 1)
    }

    /// Uniform in `[0, 1)`.
    pub(crate) fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in `[lo, hi)`.
    pub(crate) fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }

    pub(crate) fn point(&mut self, r: f64) -> Point {
        Point::new(self.uniform(-r, r), self.uniform(-r, r))
    }

    pub(crate) fn point3(&mut self, r: f64) -> Point3 {
        Point3::new(
            self.uniform(-r, r),
            self.uniform(-r, r),
            self.uniform(-r, r),
        )
    }

    /// A random orthonormal pair `(x, y)` of space.
    pub(crate) fn axes(&mut self) -> (Point3, Point3) {
        loop {
            let a = self.point3(1.0);
            let b = self.point3(1.0);
            if let Some(x) = a.normalized()
                && let Some(y) = (b - x * b.dot(x)).normalized()
                && a.length() > 0.2
                && (b - x * b.dot(x)).length() > 0.2
            {
                return (x, y);
            }
        }
    }
}
