//! Affine maps of the plane; they map rational curves exactly (control points move, weights
//! stay).

use crate::{NurbsCurve, Point, SplineError};

/// The affine map `(x, y) -> (a x + c y + e, b x + d y + f)`, the SVG `matrix(a b c d e f)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine {
    /// The six coefficients `[a, b, c, d, e, f]`.
    pub m: [f64; 6],
}

impl Affine {
    /// The identity.
    pub const IDENTITY: Affine = Affine {
        m: [1.0, 0.0, 0.0, 1.0, 0.0, 0.0],
    };

    /// A translation by `(tx, ty)`.
    pub fn translate(tx: f64, ty: f64) -> Self {
        Affine {
            m: [1.0, 0.0, 0.0, 1.0, tx, ty],
        }
    }

    /// A scaling by `sx`, `sy` about the origin.
    pub fn scale(sx: f64, sy: f64) -> Self {
        Affine {
            m: [sx, 0.0, 0.0, sy, 0.0, 0.0],
        }
    }

    /// A rotation by `angle` radians about the origin (counter-clockwise in a y-up frame).
    pub fn rotate(angle: f64) -> Self {
        let (s, c) = angle.sin_cos();
        Affine {
            m: [c, s, -s, c, 0.0, 0.0],
        }
    }

    /// `self * other`: apply `other` first, then `self`.
    pub fn then_apply_to(self, other: Affine) -> Affine {
        let [a1, b1, c1, d1, e1, f1] = self.m;
        let [a2, b2, c2, d2, e2, f2] = other.m;
        Affine {
            m: [
                a1 * a2 + c1 * b2,
                b1 * a2 + d1 * b2,
                a1 * c2 + c1 * d2,
                b1 * c2 + d1 * d2,
                a1 * e2 + c1 * f2 + e1,
                b1 * e2 + d1 * f2 + f1,
            ],
        }
    }

    /// The image of `p`.
    pub fn apply(&self, p: Point) -> Point {
        let [a, b, c, d, e, f] = self.m;
        Point::new(a * p.x + c * p.y + e, b * p.x + d * p.y + f)
    }

    /// The determinant `a d - b c` (zero for a singular map).
    pub fn determinant(&self) -> f64 {
        self.m[0] * self.m[3] - self.m[1] * self.m[2]
    }

    /// True for the identity map.
    pub fn is_identity(&self) -> bool {
        *self == Self::IDENTITY
    }

    /// The image of a rational curve: same degree, knots and weights, mapped control points
    /// (exact, since affine maps commute with the rational combination).
    ///
    /// # Errors
    /// [`SplineError`] if a coefficient is not finite.
    pub fn apply_to_curve(&self, c: &NurbsCurve) -> Result<NurbsCurve, SplineError> {
        if self.is_identity() {
            return Ok(c.clone());
        }
        NurbsCurve::new(
            c.degree(),
            c.knots().knots().to_vec(),
            c.control_points().iter().map(|&p| self.apply(p)).collect(),
            Some(c.weights().to_vec()),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prelude::*;

    #[test]
    fn composition_applies_the_right_map_first() {
        let t = Affine::translate(1.0, 2.0);
        let s = Affine::scale(3.0, -1.0);
        let ts = t.then_apply_to(s); // scale, then translate
        let p = Point::new(2.0, 5.0);
        assert_eq!(ts.apply(p), t.apply(s.apply(p)));
        assert_eq!(ts.apply(p), Point::new(7.0, -3.0));
        assert_eq!(ts.determinant(), -3.0);
    }

    #[test]
    fn mapped_circle_is_the_mapped_point_set() {
        let c = crate::circle(Point::new(1.0, 0.0), 2.0).unwrap();
        let m = Affine {
            m: [2.0, 0.5, -0.3, 1.5, 4.0, -1.0],
        };
        let mc = m.apply_to_curve(&c).unwrap();
        for i in 0..=20 {
            let u = i as f64 / 20.0;
            assert!(mc.point_at(u).distance(m.apply(c.point_at(u))) < 1e-13);
        }
    }
}
