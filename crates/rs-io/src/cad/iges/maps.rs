//! Affine maps: 124 transformation matrices (3-D, or their 2-D part in parameter space) and
//! the map from a plane's model space into its surface parameters `(u, v)`.
//!
//! Affine maps take rational curves to rational curves exactly (control points move, weights
//! and knots stay), which is why every map here is affine and no curve is ever resampled.

/// Dot product of 3-vectors.
pub(super) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Cross product of 3-vectors.
pub(super) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a - b`.
pub(super) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// The 3-D affine map `x' = M x + t`, rows `[M_i1, M_i2, M_i3, t_i]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Map3 {
    pub(super) m: [[f64; 4]; 3],
}

impl Map3 {
    /// The identity.
    pub(super) const IDENTITY: Map3 = Map3 {
        m: [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
        ],
    };

    /// A 124's twelve numbers `R11 R12 R13 T1 R21 R22 R23 T2 R31 R32 R33 T3` as a 3-D map.
    pub(super) fn from_124(v: [f64; 12]) -> Self {
        Map3 {
            m: [
                [v[0], v[1], v[2], v[3]],
                [v[4], v[5], v[6], v[7]],
                [v[8], v[9], v[10], v[11]],
            ],
        }
    }

    /// The 2-D part of a 124 for parameter-space curves: `x' = R11 x + R12 y + T1`,
    /// `y' = R21 x + R22 y + T2` (z is not a parameter and passes through).
    pub(super) fn from_124_2d(v: [f64; 12]) -> Self {
        Map3 {
            m: [
                [v[0], v[1], 0.0, v[3]],
                [v[4], v[5], 0.0, v[7]],
                [0.0, 0.0, 1.0, 0.0],
            ],
        }
    }

    /// The image of `p`.
    pub(super) fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let r = |i: usize| {
            let m = self.m[i];
            m[0] * p[0] + m[1] * p[1] + m[2] * p[2] + m[3]
        };
        [r(0), r(1), r(2)]
    }

    /// The image of the vector `v` (the linear part only).
    pub(super) fn apply_vector(&self, v: [f64; 3]) -> [f64; 3] {
        let r = |i: usize| {
            let m = self.m[i];
            m[0] * v[0] + m[1] * v[1] + m[2] * v[2]
        };
        [r(0), r(1), r(2)]
    }

    /// `outer` after `self`: `x -> outer(self(x))`.
    pub(super) fn then(self, outer: Map3) -> Map3 {
        let mut m = [[0.0; 4]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, cell) in row.iter_mut().enumerate() {
                let mut s = if j == 3 { outer.m[i][3] } else { 0.0 };
                for k in 0..3 {
                    s += outer.m[i][k] * self.m[k][j];
                }
                *cell = s;
            }
        }
        Map3 { m }
    }
}

/// The affine map from a plane in model space to its surface's parameters:
/// `p = origin + a e1 + b e2` has `(u, v) = (u0 + a, v0 + b)` after `e1`, `e2` are scaled to
/// one unit of parameter. Model points are checked to lie on the plane within `tol`.
#[derive(Clone, Debug)]
pub(super) struct PlaneMap {
    /// Rows of the affine map `p -> (u, v)`: `u = r0 . (p, 1)`, `v = r1 . (p, 1)`.
    rows: [[f64; 4]; 2],
    /// Unit normal of the plane.
    normal: [f64; 3],
    /// `normal . origin`.
    offset: f64,
    /// Largest distance off the plane accepted for a model-space point.
    pub(super) tol: f64,
}

impl PlaneMap {
    /// The map for the plane through `origin` spanned by `e1` (one unit of `u`) and `e2`
    /// (one unit of `v`), with `(u, v) = (u0, v0)` at `origin`. `None` if `e1`, `e2` are
    /// (nearly) parallel or not finite.
    pub(super) fn new(
        origin: [f64; 3],
        e1: [f64; 3],
        e2: [f64; 3],
        (u0, v0): (f64, f64),
        tol: f64,
    ) -> Option<Self> {
        let n = cross(e1, e2);
        let n_len = dot(n, n).sqrt();
        let scale = dot(e1, e1).sqrt() * dot(e2, e2).sqrt();
        if !(n_len.is_finite() && n_len > 1e-12 * scale) {
            return None;
        }
        // Solve the Gram system [e1.e1 e1.e2; e1.e2 e2.e2] (a, b) = (r.e1, r.e2) for
        // r = p - origin: (a, b) = G^-1 (r.e1, r.e2), linear in p.
        let (g11, g12, g22) = (dot(e1, e1), dot(e1, e2), dot(e2, e2));
        let det = g11 * g22 - g12 * g12;
        if !(det.is_finite() && det > 0.0) {
            return None;
        }
        let row = |c1: f64, c2: f64, p0: f64| -> [f64; 4] {
            // a = (c1 e1 + c2 e2) . (p - origin) + p0
            let w = [
                c1 * e1[0] + c2 * e2[0],
                c1 * e1[1] + c2 * e2[1],
                c1 * e1[2] + c2 * e2[2],
            ];
            [w[0], w[1], w[2], p0 - dot(w, origin)]
        };
        let rows = [
            row(g22 / det, -g12 / det, u0),
            row(-g12 / det, g11 / det, v0),
        ];
        let normal = [n[0] / n_len, n[1] / n_len, n[2] / n_len];
        let ok = rows.iter().flatten().all(|x| x.is_finite());
        ok.then_some(PlaneMap {
            rows,
            normal,
            offset: dot(normal, origin),
            tol,
        })
    }

    /// The signed distance of `p` from the plane.
    pub(super) fn distance(&self, p: [f64; 3]) -> f64 {
        dot(self.normal, p) - self.offset
    }

    /// The parameters `(u, v)` of `p` (its projection if it is off the plane).
    pub(super) fn uv(&self, p: [f64; 3]) -> (f64, f64) {
        let r = |row: [f64; 4]| row[0] * p[0] + row[1] * p[1] + row[2] * p[2] + row[3];
        (r(self.rows[0]), r(self.rows[1]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compose_and_plane_inverse() {
        let rot = Map3::from_124([0.0, -1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 2.0, 0.0, 0.0, 1.0, 3.0]);
        let shift = Map3::from_124([1.0, 0.0, 0.0, 5.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
        // rot first, then shift.
        let both = rot.then(shift);
        assert_eq!(both.apply([1.0, 0.0, 0.0]), [6.0, 3.0, 3.0]);
        assert_eq!(
            shift.apply(rot.apply([0.5, -2.0, 1.0])),
            both.apply([0.5, -2.0, 1.0])
        );
        let pm = PlaneMap::new(
            [1.0, 1.0, 1.0],
            [2.0, 0.0, 0.0],
            [1.0, 0.0, 3.0],
            (10.0, 20.0),
            1e-9,
        )
        .unwrap();
        let p = [1.0 + 2.0 * 0.25 + 1.0 * 0.5, 1.0, 1.0 + 3.0 * 0.5];
        let (u, v) = pm.uv(p);
        assert!((u - 10.25).abs() < 1e-14 && (v - 20.5).abs() < 1e-14);
        assert!(pm.distance(p).abs() < 1e-14);
        assert!((pm.distance([0.0, 3.0, 0.0]) + 2.0).abs() < 1e-14);
        assert!(
            PlaneMap::new([0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], (0.0, 0.0), 0.0).is_none()
        );
    }
}
