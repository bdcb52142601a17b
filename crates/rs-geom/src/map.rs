//! Affine maps between the spaces curves live in: placements of space ([`Affine3`]), maps of the
//! plane ([`rs_spline::Affine`]) and the coordinates of a plane ([`PlaneCoordinates`]: space to
//! a plane's `(u, v)` for orthonormal axes, [`AffinePlaneCoordinates`] for any two axes). They carry curves exactly (see [`crate::Curve::map_affine`]): points
//! map as points, vectors (directions, conic axes) by the linear part only.

use rs_spline::{Affine, Point, Point3};

use crate::{Affine3, Frame, GeomError};

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

/// Below this sine of the angle between the two axes of an [`AffinePlaneCoordinates`] they do
/// not span a plane (rounding of vectors written with ten or more digits is far below it).
const MIN_AXES_SINE: f64 = 1e-12;

/// The parameters of the affine plane `S(u, v) = o + (u - u0) e1 + (v - v0) e2` spanned by two
/// independent vectors `e1`, `e2` of any lengths and angle (a degree 1 x 1 B-spline patch that
/// is a parallelogram, a plane placed by a scaling or shear): `p -> (u, v)` with `(u - u0, v -
/// v0) = G^-1 (r . e1, r . e2)`, `r = p - o` and `G` the Gram matrix of `e1`, `e2`. It is the
/// exact inverse of `S` on the plane; a point off the plane maps to its orthogonal
/// projection's parameters, and [`AffinePlaneCoordinates::distance`] says how far off it is.
///
/// The map is stored as two rows `u = a . p + b`, so every point costs three products and
/// three sums per parameter, whatever the axes.
///
/// # Examples
///
/// ```
/// use rs_geom::{AffineMap, AffinePlaneCoordinates, Point, Point3};
/// // S(u, v) = (2u + v, v, v) on the plane y = z.
/// let s = AffinePlaneCoordinates::new(
///     Point3::ORIGIN,
///     Point3::new(2.0, 0.0, 0.0),
///     Point3::new(1.0, 1.0, 1.0),
///     Point::new(0.0, 0.0),
/// )
/// .unwrap();
/// assert_eq!(s.point(Point3::new(1.0, 1.0, 1.0)), Point::new(0.0, 1.0));
/// assert_eq!(s.distance(Point3::new(0.0, 1.0, 1.0)), 0.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AffinePlaneCoordinates {
    /// `u = rows[0] . (p, 1)`, `v = rows[1] . (p, 1)`.
    rows: [[f64; 4]; 2],
    /// The unit normal `e1 x e2 / |e1 x e2|`.
    normal: Point3,
    /// `normal . o`.
    offset: f64,
}

impl AffinePlaneCoordinates {
    /// The parameters of `S(u, v) = origin + (u - uv0.x) e1 + (v - uv0.y) e2`.
    ///
    /// # Errors
    /// [`GeomError::DegenerateFrame`] when `e1` and `e2` are (nearly) parallel, zero or not
    /// finite, or the map is not finite.
    pub fn new(
        origin: Point3,
        e1: Point3,
        e2: Point3,
        uv0: Point,
    ) -> Result<AffinePlaneCoordinates, GeomError> {
        let degenerate = GeomError::DegenerateFrame("the plane's two axes are parallel or zero");
        let n = e1.cross(e2);
        let n_len = n.dot(n).sqrt();
        let scale = e1.dot(e1).sqrt() * e2.dot(e2).sqrt();
        if !(n_len.is_finite() && n_len > MIN_AXES_SINE * scale) {
            return Err(degenerate);
        }
        let (g11, g12, g22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
        let det = g11 * g22 - g12 * g12;
        if !(det.is_finite() && det > 0.0) {
            return Err(degenerate);
        }
        // Row of `c1 (r . e1) + c2 (r . e2) + p0`, linear in p.
        let row = |c1: f64, c2: f64, p0: f64| -> [f64; 4] {
            let w = e1 * c1 + e2 * c2;
            [w.x, w.y, w.z, p0 - w.dot(origin)]
        };
        let rows = [
            row(g22 / det, -g12 / det, uv0.x),
            row(-g12 / det, g11 / det, uv0.y),
        ];
        if !rows.iter().flatten().all(|x| x.is_finite()) || !origin.is_finite() {
            return Err(degenerate);
        }
        let normal = n / n_len;
        Ok(AffinePlaneCoordinates {
            rows,
            normal,
            offset: normal.dot(origin),
        })
    }

    /// The signed distance of `p` from the plane, positive on the side of `e1 x e2`.
    pub fn distance(&self, p: Point3) -> f64 {
        self.normal.dot(p) - self.offset
    }

    /// The unit normal `e1 x e2 / |e1 x e2|`.
    pub fn normal(&self) -> Point3 {
        self.normal
    }
}

impl AffineMap<Point3, Point> for AffinePlaneCoordinates {
    fn point(&self, p: Point3) -> Point {
        let r = |row: [f64; 4]| row[0] * p.x + row[1] * p.y + row[2] * p.z + row[3];
        Point::new(r(self.rows[0]), r(self.rows[1]))
    }

    fn vector(&self, v: Point3) -> Point {
        let r = |row: [f64; 4]| row[0] * v.x + row[1] * v.y + row[2] * v.z;
        Point::new(r(self.rows[0]), r(self.rows[1]))
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

    /// The coordinates of a skew plane invert its affine parameterisation, project points off
    /// it and agree with [`PlaneCoordinates`] on orthonormal axes.
    #[test]
    fn affine_plane_coordinates_invert_any_two_axes() {
        let o = Point3::new(1.0, -2.0, 0.5);
        let (e1, e2) = (Point3::new(2.0, 0.5, -1.0), Point3::new(-0.25, 3.0, 1.5));
        let uv0 = Point::new(10.0, -20.0);
        let m = AffinePlaneCoordinates::new(o, e1, e2, uv0).unwrap();
        let s = |u: f64, v: f64| o + e1 * (u - uv0.x) + e2 * (v - uv0.y);
        let normal = e1.cross(e2).normalized().unwrap();
        for (u, v) in [(10.0, -20.0), (10.5, -19.0), (7.0, -25.5), (1e3, 1e3)] {
            let q = m.point(s(u, v));
            assert!(
                q.distance(Point::new(u, v)) < 1e-12 * (1.0 + u.abs() + v.abs()),
                "{q:?}"
            );
            assert!(m.distance(s(u, v)).abs() < 1e-12 * (1.0 + u.abs() + v.abs()));
            // A point off the plane: the parameters of its foot, its signed distance.
            let off = s(u, v) + normal * 0.75;
            assert!(m.point(off).distance(Point::new(u, v)) < 1e-12 * (1.0 + u.abs() + v.abs()));
            assert!((m.distance(off) - 0.75).abs() < 1e-12 * (1.0 + u.abs() + v.abs()));
        }
        // Vectors map by the linear part: the axes are the unit steps.
        assert!(m.vector(e1).distance(Point::new(1.0, 0.0)) < 1e-15);
        assert!(m.vector(e2).distance(Point::new(0.0, 1.0)) < 1e-15);
        // Orthonormal axes: the plane coordinates of the frame.
        let f = Frame::new(o, Some(Point3::new(1.0, 2.0, 2.0)), Some(Point3::X)).unwrap();
        let a = AffinePlaneCoordinates::new(f.origin, f.x, f.y, Point::new(0.0, 0.0)).unwrap();
        let p = Point3::new(3.0, -1.0, 7.0);
        assert!(a.point(p).distance(PlaneCoordinates::new(&f).point(p)) < 1e-14);
        for (a, b) in [
            (e1, e1 * -3.0),
            (e1, Point3::ORIGIN),
            (Point3::new(f64::NAN, 0.0, 0.0), e2),
        ] {
            assert!(matches!(
                AffinePlaneCoordinates::new(o, a, b, uv0),
                Err(GeomError::DegenerateFrame(_))
            ));
        }
    }
}
