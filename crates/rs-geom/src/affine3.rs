//! Affine maps of space: the placements of assembly components (STEP), transformation matrices
//! (IGES 124).

use std::ops::Mul;

use rs_spline::Point3;

use crate::Frame;

/// The affine map `p -> M p + t` of space, rows `[M_i1, M_i2, M_i3, t_i]`.
///
/// Affine maps take rational curves and surfaces to rational curves and surfaces exactly
/// (the control points move, weights and knots stay).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine3 {
    /// The rows `[M_i1, M_i2, M_i3, t_i]`.
    pub m: [[f64; 4]; 3],
}

impl Affine3 {
    /// The identity.
    pub const IDENTITY: Affine3 = Affine3 {
        m: [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
        ],
    };

    /// The map from `frame`'s local coordinates to the world:
    /// `(a, b, c) -> origin + a x + b y + c z`.
    pub fn from_frame(frame: &Frame) -> Affine3 {
        let (x, y, z, o) = (frame.x, frame.y, frame.z, frame.origin);
        Affine3 {
            m: [
                [x.x, y.x, z.x, o.x],
                [x.y, y.y, z.y, o.y],
                [x.z, y.z, z.z, o.z],
            ],
        }
    }

    /// The rigid motion that carries frame `from` onto frame `to` (a point with local
    /// coordinates `c` in `from` goes to the point with the same local coordinates in `to`):
    /// STEP's `ITEM_DEFINED_TRANSFORMATION` and `MAPPED_ITEM` placements.
    pub fn between(from: &Frame, to: &Frame) -> Affine3 {
        Affine3::from_frame(to).after(Affine3::from_frame(from).rigid_inverse())
    }

    /// The image of the point `p`.
    pub fn apply(&self, p: Point3) -> Point3 {
        let r = |i: usize| {
            let m = self.m[i];
            m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3]
        };
        Point3::new(r(0), r(1), r(2))
    }

    /// The image of the vector `v` (the linear part only).
    pub fn apply_vector(&self, v: Point3) -> Point3 {
        let r = |i: usize| {
            let m = self.m[i];
            m[0] * v.x + m[1] * v.y + m[2] * v.z
        };
        Point3::new(r(0), r(1), r(2))
    }

    /// `self` after `inner`: `p -> self(inner(p))`.
    pub fn after(self, inner: Affine3) -> Affine3 {
        let mut m = [[0.0; 4]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, cell) in row.iter_mut().enumerate() {
                let mut s = if j == 3 { self.m[i][3] } else { 0.0 };
                for k in 0..3 {
                    s += self.m[i][k] * inner.m[k][j];
                }
                *cell = s;
            }
        }
        Affine3 { m }
    }

    /// The inverse of a rigid motion (orthonormal linear part): the transpose, and the
    /// translation turned back. Not the inverse of other maps.
    pub fn rigid_inverse(&self) -> Affine3 {
        let mut m = [[0.0; 4]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, cell) in row.iter_mut().take(3).enumerate() {
                *cell = self.m[j][i];
            }
            row[3] = -(0..3).map(|k| self.m[k][i] * self.m[k][3]).sum::<f64>();
        }
        Affine3 { m }
    }

    /// The determinant of the linear part.
    pub fn determinant(&self) -> f64 {
        let a = &self.m;
        a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0])
    }

    /// The largest deviation of the linear part's columns from an orthonormal basis (`0` for a
    /// rotation or reflection; a similarity's columns deviate by its scale).
    pub fn orthonormality_error(&self) -> f64 {
        let col = |j: usize| Point3::new(self.m[0][j], self.m[1][j], self.m[2][j]);
        let mut worst = 0.0f64;
        for i in 0..3 {
            for j in i..3 {
                let target = if i == j { 1.0 } else { 0.0 };
                worst = worst.max((col(i).dot(col(j)) - target).abs());
            }
        }
        worst
    }

    /// Is this the identity?
    pub fn is_identity(&self) -> bool {
        *self == Affine3::IDENTITY
    }

    /// Every entry finite?
    pub fn is_finite(&self) -> bool {
        self.m.iter().flatten().all(|x| x.is_finite())
    }
}

impl Mul<Point3> for Affine3 {
    type Output = Point3;
    /// The image of the point `p`.
    fn mul(self, p: Point3) -> Point3 {
        self.apply(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn composition_and_frames() {
        let rot = Affine3 {
            m: [
                [0.0, -1.0, 0.0, 1.0],
                [1.0, 0.0, 0.0, 2.0],
                [0.0, 0.0, 1.0, 3.0],
            ],
        };
        let shift = Affine3 {
            m: [
                [1.0, 0.0, 0.0, 5.0],
                [0.0, 1.0, 0.0, 0.0],
                [0.0, 0.0, 1.0, 0.0],
            ],
        };
        let both = shift.after(rot);
        let p = Point3::new(0.5, -2.0, 1.0);
        assert_eq!(both.apply(p), shift.apply(rot.apply(p)));
        assert_eq!(both * Point3::X, Point3::new(6.0, 3.0, 3.0));
        assert!(rot.orthonormality_error() < 1e-15 && (rot.determinant() - 1.0).abs() < 1e-15);
        let back = rot.rigid_inverse().after(rot);
        assert!(back.apply(p).distance(p) < 1e-15);

        let a = Frame::new(Point3::new(1.0, 0.0, 0.0), None, None).unwrap();
        let b = Frame::new(Point3::new(0.0, 5.0, 0.0), Some(Point3::X), Some(Point3::Y)).unwrap();
        let m = Affine3::between(&a, &b);
        // a's origin goes to b's origin, a's axes to b's.
        assert!(m.apply(a.origin).distance(b.origin) < 1e-15);
        assert!(m.apply_vector(a.z).distance(b.z) < 1e-15);
        assert!(m.apply_vector(a.x).distance(b.x) < 1e-15);
        assert!(Affine3::IDENTITY.is_identity() && m.is_finite());
    }
}
