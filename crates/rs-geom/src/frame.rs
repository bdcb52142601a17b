//! Right-handed orthonormal frames: the placement of every elementary surface and conic.

use rs_spline::Point3;

use crate::GeomError;

/// A right-handed orthonormal frame: an origin and unit axes `x`, `y = z x x`, `z`.
///
/// Built as ISO 10303-42's `build_axes` builds an `AXIS2_PLACEMENT_3D`: `z` is the axis, `x`
/// the reference direction made orthogonal to it, `y` completes the frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// The origin.
    pub origin: Point3,
    /// The first axis (the reference direction).
    pub x: Point3,
    /// The second axis, `z x x`.
    pub y: Point3,
    /// The third axis (the placement's axis, a surface's axis of symmetry).
    pub z: Point3,
}

/// Below this sine of the angle between the axis and the reference direction, the reference
/// direction does not fix `x` (ISO 10303-42 requires them not parallel).
const MIN_SINE: f64 = 1e-12;

impl Frame {
    /// The world frame.
    pub const WORLD: Frame = Frame {
        origin: Point3::ORIGIN,
        x: Point3::X,
        y: Point3::Y,
        z: Point3::Z,
    };

    /// The frame at `origin` with axis `axis` (default `z`) and reference direction `reference`
    /// (default `x`), neither needing unit length: `x` is `reference` minus its component along
    /// the axis, normalised.
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] for a non-finite origin; [`GeomError::DegenerateFrame`] for a
    /// zero or non-finite axis or reference direction, or a reference direction along the axis.
    pub fn new(
        origin: Point3,
        axis: Option<Point3>,
        reference: Option<Point3>,
    ) -> Result<Frame, GeomError> {
        if !origin.is_finite() {
            return Err(GeomError::NotFinite {
                what: "origin",
                value: origin.max_abs(),
            });
        }
        let z = axis
            .unwrap_or(Point3::Z)
            .normalized()
            .ok_or(GeomError::DegenerateFrame("the axis is zero"))?;
        let reference = match reference {
            Some(r) => r.normalized().ok_or(GeomError::DegenerateFrame(
                "the reference direction is zero",
            ))?,
            None if z.x.abs() < 1.0 - MIN_SINE => Point3::X,
            // An axis along the world x axis leaves the default reference direction undefined
            // (ISO 10303-42); the world z is perpendicular to it.
            None => Point3::Z,
        };
        if reference.cross(z).length() <= MIN_SINE {
            return Err(GeomError::DegenerateFrame(
                "the reference direction is along the axis",
            ));
        }
        let x =
            (reference - z * reference.dot(z))
                .normalized()
                .ok_or(GeomError::DegenerateFrame(
                    "the reference direction is along the axis",
                ))?;
        Ok(Frame {
            origin,
            x,
            y: z.cross(x),
            z,
        })
    }

    /// The frame at `origin` with axis `axis` (any length) and the reference direction
    /// `OpenCASCADE`'s `gp_Ax2(origin, axis)` chooses when none is given (IGES form 0 surfaces
    /// 190 to 198, which `OpenCASCADE` reads this way): with `(a, b, c)` the absolute
    /// components of the unit axis `A`, the reference direction is
    ///
    /// - `(-A_z, 0, A_x)` if `a > c`, else `(A_z, 0, -A_x)`, when `b` is the smallest;
    /// - `(0, -A_z, A_y)` if `b > c`, else `(0, A_z, -A_y)`, when `a` is (and `b` is not);
    /// - `(-A_y, A_x, 0)` if `a > b`, else `(A_y, -A_x, 0)`, when `c` is.
    ///
    /// # Errors
    /// As [`Frame::new`]: a non-finite origin, a zero or non-finite axis.
    ///
    /// # Examples
    ///
    /// ```
    /// use rs_geom::{Frame, Point3};
    /// let f = Frame::with_default_reference(Point3::ORIGIN, Point3::new(0.0, 0.0, -1.0)).unwrap();
    /// assert_eq!(f.x, Point3::new(-1.0, 0.0, 0.0));
    /// ```
    pub fn with_default_reference(origin: Point3, axis: Point3) -> Result<Frame, GeomError> {
        let z = axis
            .normalized()
            .ok_or(GeomError::DegenerateFrame("the axis is zero"))?;
        let (a, b, c) = (z.x.abs(), z.y.abs(), z.z.abs());
        let reference = if b <= a && b <= c {
            if a > c {
                Point3::new(-z.z, 0.0, z.x)
            } else {
                Point3::new(z.z, 0.0, -z.x)
            }
        } else if a <= b && a <= c {
            if b > c {
                Point3::new(0.0, -z.z, z.y)
            } else {
                Point3::new(0.0, z.z, -z.y)
            }
        } else if a > b {
            Point3::new(-z.y, z.x, 0.0)
        } else {
            Point3::new(z.y, -z.x, 0.0)
        };
        Frame::new(origin, Some(z), Some(reference))
    }

    /// The world point with local coordinates `(a, b, c)`: `origin + a x + b y + c z`.
    pub fn to_world(&self, a: f64, b: f64, c: f64) -> Point3 {
        self.origin + self.x * a + self.y * b + self.z * c
    }

    /// The world vector with local components `(a, b, c)`.
    pub fn vector_to_world(&self, a: f64, b: f64, c: f64) -> Point3 {
        self.x * a + self.y * b + self.z * c
    }

    /// The local coordinates of the world point `p`.
    pub fn to_local(&self, p: Point3) -> Point3 {
        let d = p - self.origin;
        Point3::new(d.dot(self.x), d.dot(self.y), d.dot(self.z))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_frame_is_right_handed_and_orthonormal() {
        let f = Frame::new(
            Point3::new(1.0, 2.0, 3.0),
            Some(Point3::new(0.0, 0.0, 2.0)),
            Some(Point3::new(1.0, 1.0, 5.0)),
        )
        .unwrap();
        assert!((f.x.length() - 1.0).abs() < 1e-15 && f.x.dot(f.z).abs() < 1e-15);
        assert!(f.x.cross(f.y).distance(f.z) < 1e-15);
        let p = f.to_world(0.5, -2.0, 1.5);
        assert!(f.to_local(p).distance(Point3::new(0.5, -2.0, 1.5)) < 1e-14);
        let tilted = Frame::new(Point3::ORIGIN, Some(Point3::new(1.0, 0.0, 0.0)), None).unwrap();
        assert!(tilted.x.dot(tilted.z).abs() < 1e-15);
    }

    /// `OpenCASCADE`'s own `gp_Ax2(P, A).XDirection()` (OCP 8.0), printed for these axes.
    #[test]
    fn default_reference_directions_are_opencascades() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let cases = [
            ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0]),
            ([0.0, 0.0, -1.0], [-1.0, 0.0, 0.0]),
            ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0]),
            ([1.0, 1.0, 1.0], [h, 0.0, -h]),
            (
                [-1.0, 2.0, 0.5],
                [0.894427190999916, 0.447213595499958, 0.0],
            ),
            (
                [0.3, -0.2, -5.0],
                [-0.9982048454657787, 0.0, -0.05989229072794672],
            ),
            (
                [2.0, -3.0, 1.0],
                [-0.8320502943378437, -0.5547001962252293, 0.0],
            ),
            ([-1.0, -1.0, 0.0], [-h, h, 0.0]),
            ([0.0, -1.0, -1.0], [0.0, -h, h]),
        ];
        for (axis, x) in cases {
            let axis = Point3::new(axis[0], axis[1], axis[2]);
            let f = Frame::with_default_reference(Point3::new(1.0, 2.0, 3.0), axis).unwrap();
            assert!(
                f.x.distance(Point3::new(x[0], x[1], x[2])) < 1e-15,
                "{axis:?}: {f:?}"
            );
            assert!(f.z.distance(axis.normalized().unwrap()) < 1e-15);
            assert!(f.x.cross(f.y).distance(f.z) < 1e-15);
        }
        assert!(Frame::with_default_reference(Point3::ORIGIN, Point3::ORIGIN).is_err());
    }

    #[test]
    fn degenerate_axes_are_errors() {
        let o = Point3::ORIGIN;
        assert!(Frame::new(o, Some(Point3::ORIGIN), None).is_err());
        assert!(Frame::new(o, None, Some(Point3::new(0.0, 0.0, 3.0))).is_err());
        assert!(Frame::new(o, Some(Point3::new(f64::NAN, 0.0, 1.0)), None).is_err());
        assert!(Frame::new(Point3::new(f64::INFINITY, 0.0, 0.0), None, None).is_err());
    }
}
