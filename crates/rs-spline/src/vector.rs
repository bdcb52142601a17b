//! The vector spaces curves live in: [`Vector`], implemented by [`Point`] (the plane) and
//! [`Point3`] (space), so one rational B-spline kernel and one conic constructor serve both.

use rs_roots::Blend;

use crate::{Point, Point3};

/// A point or vector of `R^n` with the operations the generic curve kernels need: the linear
/// combinations of [`Blend`] (de Casteljau, de Boor), a dot product (distances, projections)
/// and the coordinates one by one.
pub trait Vector: Blend + PartialEq + std::fmt::Debug + Send + Sync + 'static {
    /// The number of coordinates.
    const DIM: usize;

    /// Dot product.
    fn dot(self, o: Self) -> f64;

    /// Coordinate `i` (`i < DIM`; `NaN` past the last).
    fn coord(self, i: usize) -> f64;

    /// The vector with coordinates `f(0), .., f(DIM - 1)`.
    fn from_fn(f: impl FnMut(usize) -> f64) -> Self;

    /// Euclidean length.
    fn norm(self) -> f64 {
        self.dot(self).sqrt()
    }

    /// Euclidean distance.
    fn distance_to(self, o: Self) -> f64 {
        (self - o).norm()
    }

    /// Every coordinate finite?
    fn all_finite(self) -> bool {
        (0..Self::DIM).all(|i| self.coord(i).is_finite())
    }
}

impl Vector for Point {
    const DIM: usize = 2;

    fn dot(self, o: Self) -> f64 {
        Point::dot(self, o)
    }

    fn coord(self, i: usize) -> f64 {
        match i {
            0 => self.x,
            1 => self.y,
            _ => f64::NAN,
        }
    }

    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        let x = f(0);
        Point::new(x, f(1))
    }
}

impl Vector for Point3 {
    const DIM: usize = 3;

    fn dot(self, o: Self) -> f64 {
        Point3::dot(self, o)
    }

    fn coord(self, i: usize) -> f64 {
        match i {
            0 => self.x,
            1 => self.y,
            2 => self.z,
            _ => f64::NAN,
        }
    }

    fn from_fn(mut f: impl FnMut(usize) -> f64) -> Self {
        let x = f(0);
        let y = f(1);
        Point3::new(x, y, f(2))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_spaces_agree_with_their_types() {
        let p = Point::from_fn(|i| i as f64 + 1.0);
        assert_eq!(p, Point::new(1.0, 2.0));
        assert_eq!(Vector::dot(p, p), 5.0);
        let q = Point3::from_fn(|i| i as f64);
        assert_eq!(q.coord(2), 2.0);
        assert!(q.coord(3).is_nan());
        assert_eq!(q.distance_to(Point3::ORIGIN), 5f64.sqrt());
        assert!(!Point3::new(f64::NAN, 0.0, 0.0).all_finite());
    }
}
