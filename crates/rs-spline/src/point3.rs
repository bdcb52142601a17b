//! Points (and vectors) of `R^3`: control points of space curves and surfaces, polytope
//! corners.

use std::ops::{Add, Div, Index, Mul, Neg, Sub};

/// A point or a vector of `R^3` (one type for both, as [`crate::Point`] in the plane).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Point3 {
    /// First coordinate.
    pub x: f64,
    /// Second coordinate.
    pub y: f64,
    /// Third coordinate.
    pub z: f64,
}

impl Point3 {
    /// The origin `(0, 0, 0)`.
    pub const ORIGIN: Point3 = Point3::new(0.0, 0.0, 0.0);
    /// The unit vector along `x`.
    pub const X: Point3 = Point3::new(1.0, 0.0, 0.0);
    /// The unit vector along `y`.
    pub const Y: Point3 = Point3::new(0.0, 1.0, 0.0);
    /// The unit vector along `z`.
    pub const Z: Point3 = Point3::new(0.0, 0.0, 1.0);

    /// The point `(x, y, z)`.
    pub const fn new(x: f64, y: f64, z: f64) -> Self {
        Self { x, y, z }
    }

    /// Dot product.
    pub fn dot(self, o: Point3) -> f64 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Cross product `self x o`.
    pub fn cross(self, o: Point3) -> Point3 {
        Point3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }

    /// Euclidean length.
    pub fn length(self) -> f64 {
        self.dot(self).sqrt()
    }

    /// Euclidean distance to `o`.
    pub fn distance(self, o: Point3) -> f64 {
        (self - o).length()
    }

    /// The unit vector along `self`, `None` for a zero or non-finite vector.
    pub fn normalized(self) -> Option<Point3> {
        let l = self.length();
        (l > 0.0 && l.is_finite()).then(|| self * (1.0 / l))
    }

    /// Linear interpolation `(1 - t) self + t o`.
    pub fn lerp(self, o: Point3, t: f64) -> Point3 {
        self + (o - self) * t
    }

    /// The corners `(min, max)` of the axis-aligned box of `points`, coordinate by
    /// coordinate; `None` for no points.
    pub fn bounds(points: impl IntoIterator<Item = Point3>) -> Option<(Point3, Point3)> {
        points.into_iter().fold(None, |b, p| {
            Some(match b {
                None => (p, p),
                Some((lo, hi)) => (
                    Point3::new(lo.x.min(p.x), lo.y.min(p.y), lo.z.min(p.z)),
                    Point3::new(hi.x.max(p.x), hi.y.max(p.y), hi.z.max(p.z)),
                ),
            })
        })
    }

    /// The largest absolute coordinate.
    pub fn max_abs(self) -> f64 {
        self.x.abs().max(self.y.abs()).max(self.z.abs())
    }

    /// All three coordinates finite?
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }

    /// The coordinates as an array.
    pub fn to_array(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }
}

impl From<[f64; 3]> for Point3 {
    fn from([x, y, z]: [f64; 3]) -> Self {
        Self { x, y, z }
    }
}

impl From<Point3> for [f64; 3] {
    fn from(p: Point3) -> Self {
        p.to_array()
    }
}

impl Index<usize> for Point3 {
    type Output = f64;
    /// Coordinate `i` (0, 1, 2).
    ///
    /// # Panics
    /// For `i > 2` (a programming error).
    fn index(&self, i: usize) -> &f64 {
        match i {
            0 => &self.x,
            1 => &self.y,
            2 => &self.z,
            _ => panic!("Point3 has three coordinates, not {}", i + 1),
        }
    }
}

impl Add for Point3 {
    type Output = Point3;
    fn add(self, o: Point3) -> Point3 {
        Point3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl Sub for Point3 {
    type Output = Point3;
    fn sub(self, o: Point3) -> Point3 {
        Point3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Mul<f64> for Point3 {
    type Output = Point3;
    fn mul(self, s: f64) -> Point3 {
        Point3::new(self.x * s, self.y * s, self.z * s)
    }
}

impl Div<f64> for Point3 {
    type Output = Point3;
    fn div(self, s: f64) -> Point3 {
        Point3::new(self.x / s, self.y / s, self.z / s)
    }
}

impl Neg for Point3 {
    type Output = Point3;
    fn neg(self) -> Point3 {
        Point3::new(-self.x, -self.y, -self.z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn products_and_lengths() {
        let (a, b) = (Point3::new(1.0, 2.0, 2.0), Point3::new(0.0, 0.0, 1.0));
        assert_eq!(a.length(), 3.0);
        assert_eq!(a.cross(b), Point3::new(2.0, -1.0, 0.0));
        assert_eq!(Point3::X.cross(Point3::Y), Point3::Z);
        assert_eq!(a.distance(a + b), 1.0);
        assert_eq!(Point3::ORIGIN.normalized(), None);
        assert_eq!((b * 2.0).normalized(), Some(b));
        assert_eq!(a[2], 2.0);
        assert_eq!(a.max_abs(), 2.0);
    }
}
