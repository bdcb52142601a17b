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

    #[test]
    fn degenerate_axes_are_errors() {
        let o = Point3::ORIGIN;
        assert!(Frame::new(o, Some(Point3::ORIGIN), None).is_err());
        assert!(Frame::new(o, None, Some(Point3::new(0.0, 0.0, 3.0))).is_err());
        assert!(Frame::new(o, Some(Point3::new(f64::NAN, 0.0, 1.0)), None).is_err());
        assert!(Frame::new(Point3::new(f64::INFINITY, 0.0, 0.0), None, None).is_err());
    }
}
