//! Affine maps between the spaces curves live in: placements of space ([`Affine3`]), maps of the
//! plane ([`rs_spline::Affine`]) and the coordinates of a plane ([`PlaneCoordinates`]: space to
//! a plane's `(u, v)`). They carry curves exactly (see [`crate::Curve::map_affine`]): points
//! map as points, vectors (directions, conic axes) by the linear part only.

use rs_spline::{Affine, Point, Point3};

use crate::{Affine3, Frame};

/// An affine map from the space of `P` to the space of `Q`: `point(p) = L p + t`,
/// `vector(v) = L v`.
///
/// Curves map through it exactly: a line's origin as a point and its direction as a vector, a
/// conic's centre as a point and its axes as vectors, a B-spline's control points as points
/// (weights and knots kept).
pub trait AffineMap<P, Q> {
    /// The image of the point `p`.
    fn point(&self, p: P) -> Q;

    /// The image of the vector `v` (the linear part only).
    fn vector(&self, v: P) -> Q;
}

impl AffineMap<Point3, Point3> for Affine3 {
    fn point(&self, p: Point3) -> Point3 {
        self.apply(p)
    }

    fn vector(&self, v: Point3) -> Point3 {
        self.apply_vector(v)
    }
}

impl AffineMap<Point, Point> for Affine {
    fn point(&self, p: Point) -> Point {
        self.apply(p)
    }

    fn vector(&self, v: Point) -> Point {
        let [a, b, c, d, ..] = self.m;
        Point::new(a * v.x + c * v.y, b * v.x + d * v.y)
    }
}

/// The coordinates of space points in a plane: `p -> ((p - o) . x, (p - o) . y)` for the plane
/// through `o` with orthonormal axes `x`, `y` (a plane's `(u, v)` in ISO 10303-42, where
/// `S(u, v) = o + u x + v y`); a point off the plane maps to its orthogonal projection's
/// coordinates.
///
/// # Examples
///
/// ```
/// use rs_geom::{AffineMap, Frame, PlaneCoordinates, Point, Point3};
/// let f = Frame::new(Point3::new(0.0, 0.0, 2.0), None, None).unwrap();
/// let uv = PlaneCoordinates::new(&f);
/// assert_eq!(uv.point(Point3::new(1.0, -3.0, 2.0)), Point::new(1.0, -3.0));
/// assert_eq!(uv.vector(Point3::new(0.5, 0.0, 9.0)), Point::new(0.5, 0.0));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneCoordinates {
    /// The plane's origin, `(u, v) = (0, 0)`.
    pub origin: Point3,
    /// The unit direction of `u`.
    pub x: Point3,
    /// The unit direction of `v`, orthogonal to `x`.
    pub y: Point3,
}

impl PlaneCoordinates {
    /// The plane `z = 0` with `(u, v) = (x, y)`.
    pub const XY: PlaneCoordinates = PlaneCoordinates {
        origin: Point3::ORIGIN,
        x: Point3::X,
        y: Point3::Y,
    };

    /// The coordinates in the plane through `frame`'s origin spanned by its `x` and `y` axes.
    pub fn new(frame: &Frame) -> Self {
        Self {
            origin: frame.origin,
            x: frame.x,
            y: frame.y,
        }
    }
}

impl AffineMap<Point3, Point> for PlaneCoordinates {
    fn point(&self, p: Point3) -> Point {
        let d = p - self.origin;
        Point::new(d.dot(self.x), d.dot(self.y))
    }

    fn vector(&self, v: Point3) -> Point {
        Point::new(v.dot(self.x), v.dot(self.y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn maps_split_points_and_vectors() {
        let m = Affine3 {
            m: [
                [0.0, -1.0, 0.0, 1.0],
                [1.0, 0.0, 0.0, 2.0],
                [0.0, 0.0, 2.0, 3.0],
            ],
        };
        let p = Point3::new(1.0, 2.0, 3.0);
        assert_eq!(m.point(p), Point3::new(-1.0, 3.0, 9.0));
        assert_eq!(m.vector(p), Point3::new(-2.0, 1.0, 6.0));
        let a = Affine {
            m: [2.0, 0.5, -1.0, 3.0, 10.0, 20.0],
        };
        let q = Point::new(1.0, -1.0);
        assert_eq!(a.point(q), a.apply(q));
        assert_eq!(a.vector(q), a.apply(q) - a.apply(Point::new(0.0, 0.0)));
        let f = Frame::new(
            Point3::new(1.0, 1.0, 1.0),
            Some(Point3::new(1.0, 1.0, 1.0)),
            Some(Point3::X),
        )
        .unwrap();
        let uv = PlaneCoordinates::new(&f);
        let w = f.to_world(0.25, -1.5, 0.0);
        assert!(uv.point(w).distance(Point::new(0.25, -1.5)) < 1e-15);
        // Off the plane: the projection's coordinates.
        assert!(uv.point(w + f.z * 3.0).distance(Point::new(0.25, -1.5)) < 1e-15);
        assert_eq!(PlaneCoordinates::XY.point(p), Point::new(1.0, 2.0));
    }
}
