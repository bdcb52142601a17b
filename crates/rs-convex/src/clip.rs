//! The one half-space clip of the crate: a Sutherland-Hodgman pass over a cyclic vertex list,
//! for the polygons of the plane and the faces of polytopes in space.

use std::ops::{Add, Mul, Sub};

use rs_spline::Point;

use crate::Point3;

/// A vertex is on the cutting line (plane) when `|a . x + b|` is at most this times
/// `|a| size + |b|`.
pub(crate) const ON_PLANE: f64 = 1e-13;
/// A normal shorter than this fraction of `|b| / size` cuts nothing: the half-space is all or
/// nothing, by the sign of `b`.
pub(crate) const NEGLIGIBLE_NORMAL: f64 = 1e-14;
/// Normals shorter than this are zero.
const ZERO_NORMAL: f64 = 1e-300;
/// Consecutive vertices closer than this times `size` are merged.
pub(crate) const MERGE: f64 = 1e-14;

/// A vertex type of a clipped polygon: a point of the plane or of space.
pub(crate) trait Vertex:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self>
{
    /// Euclidean length (of a difference of vertices).
    fn norm(self) -> f64;
}

impl Vertex for Point {
    fn norm(self) -> f64 {
        self.length()
    }
}

impl Vertex for Point3 {
    fn norm(self) -> f64 {
        self.length()
    }
}

/// What a half-space `a . x + b >= 0` does to a region of typical size `size`.
pub(crate) enum Cut {
    /// The normal is negligible: everything is kept (`b > 0`) or nothing.
    All(bool),
    /// A real cut; vertices with `|a . x + b| <= eps` are on the boundary.
    By { eps: f64 },
}

impl Cut {
    /// Classifies the half-space with normal length `norm` and offset `b`.
    pub(crate) fn new(norm: f64, b: f64, size: f64) -> Self {
        if norm <= ZERO_NORMAL || norm * size <= NEGLIGIBLE_NORMAL * b.abs() {
            Cut::All(b > 0.0)
        } else {
            Cut::By {
                eps: ON_PLANE * (norm * size + b.abs()),
            }
        }
    }
}

/// The part of the cyclic polygon `cycle` where `f >= -eps` (`f` affine), its consecutive
/// duplicates merged; `on_boundary` receives every kept vertex on the boundary and every new
/// crossing vertex (the section of a polytope is assembled from them).
pub(crate) fn clip_cycle<V: Vertex>(
    cycle: &[V],
    f: impl Fn(V) -> f64,
    eps: f64,
    size: f64,
    mut on_boundary: impl FnMut(V),
) -> Vec<V> {
    let n = cycle.len();
    let mut out = Vec::with_capacity(n + 1);
    for i in 0..n {
        let (p, q) = (cycle[i], cycle[(i + 1) % n]);
        let (fp, fq) = (f(p), f(q));
        if fp >= -eps {
            out.push(p);
            if fp.abs() <= eps {
                on_boundary(p);
            }
        }
        if (fp > eps && fq < -eps) || (fp < -eps && fq > eps) {
            let x = p + (q - p) * (fp / (fp - fq));
            out.push(x);
            on_boundary(x);
        }
    }
    out.dedup_by(|x, y| (*x - *y).norm() <= MERGE * size);
    if out.len() > 1 && (out[0] - out[out.len() - 1]).norm() <= MERGE * size {
        out.pop();
    }
    out
}
