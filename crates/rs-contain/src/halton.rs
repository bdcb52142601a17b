//! Halton points, the test and benchmark clouds of the paper.

use rs_spline::{BoundingBox, Point};

/// The radical inverse of `i` in `base`: the digits of `i` mirrored about the radix point.
pub fn radical_inverse(mut i: u64, base: u64) -> f64 {
    let inv = 1.0 / base as f64;
    let mut factor = inv;
    let mut value = 0.0;
    while i > 0 {
        value += (i % base) as f64 * factor;
        i /= base;
        factor *= inv;
    }
    value
}

/// The first `n` Halton points in bases 2 and 3, starting with `(0, 0)` (no skip), mapped to
/// the box: `(xmin + h2(i) (xmax - xmin), ymin + h3(i) (ymax - ymin))`. This is the protocol of
/// the inRS paper and of the reference counts stored in the fixtures.
///
/// # Examples
///
/// ```
/// use rs_contain::baselines::halton_points;
/// use rs_spline::{BoundingBox, Point};
/// let b = BoundingBox { min: Point::new(0.0, 0.0), max: Point::new(1.0, 1.0) };
/// let p = halton_points(3, b);
/// assert_eq!(p, vec![Point::new(0.0, 0.0), Point::new(0.5, 1.0 / 3.0), Point::new(0.25, 2.0 / 3.0)]);
/// ```
pub fn halton_points(n: usize, bbox: BoundingBox) -> Vec<Point> {
    halton_points_from(0, n, bbox)
}

/// Points `start .. start + n` of the sequence of [`halton_points`] (so that blocks of one
/// long sequence can be made apart, on separate workers); indices past `u64::MAX` are not
/// made (the result is then shorter).
///
/// # Examples
///
/// ```
/// use rs_contain::baselines::{halton_points, halton_points_from};
/// use rs_spline::{BoundingBox, Point};
/// let b = BoundingBox { min: Point::new(-1.0, 0.0), max: Point::new(1.0, 2.0) };
/// assert_eq!(halton_points_from(5, 4, b), halton_points(9, b)[5..]);
/// ```
pub fn halton_points_from(start: u64, n: usize, bbox: BoundingBox) -> Vec<Point> {
    let (w, h) = (bbox.width(), bbox.height());
    let end = start.saturating_add(n as u64);
    (start..end)
        .map(|i| {
            Point::new(
                bbox.min.x + radical_inverse(i, 2) * w,
                bbox.min.y + radical_inverse(i, 3) * h,
            )
        })
        .collect()
}
