//! Convex polytopes in 3-D clipped by half-spaces (face lists).

use crate::Point3;
use crate::clip::{Cut, clip_cycle};

/// The corner type of [`ConvexPolytope`] (kept as an alias of [`Point3`]).
pub type P3 = Point3;

/// Vertices closer than this fraction of the polytope's size are one vertex.
const SAME_VERTEX: f64 = 1e-12;

/// A convex polytope as a list of planar faces (each a cyclically ordered vertex list).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ConvexPolytope {
    faces: Vec<Vec<P3>>,
}

impl ConvexPolytope {
    /// The box `[min, max]`.
    pub fn cuboid(min: P3, max: P3) -> Self {
        let v = |i: usize| {
            Point3::new(
                if i & 1 == 0 { min.x } else { max.x },
                if i & 2 == 0 { min.y } else { max.y },
                if i & 4 == 0 { min.z } else { max.z },
            )
        };
        let faces = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ]
        .iter()
        .map(|f| f.iter().map(|&i| v(i)).collect())
        .collect();
        Self { faces }
    }

    /// The faces.
    pub fn faces(&self) -> &[Vec<P3>] {
        &self.faces
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }

    /// The distinct vertices (merged within `1e-12` of the polytope's size).
    pub fn vertices(&self) -> Vec<P3> {
        let all: Vec<P3> = self.faces.iter().flatten().copied().collect();
        let size = bounding_size(&all);
        let mut out: Vec<P3> = Vec::new();
        for p in all {
            if !out.iter().any(|q| (p - *q).length() <= SAME_VERTEX * size) {
                out.push(p);
            }
        }
        out
    }

    /// True if nothing with volume is left.
    pub fn is_empty(&self) -> bool {
        self.faces.len() < 4 || self.volume() <= 0.0
    }

    /// Volume: tetrahedra from the vertex centroid over a fan of every face.
    pub fn volume(&self) -> f64 {
        let Some(c) = self.vertex_centroid() else {
            return 0.0;
        };
        let mut v = 0.0;
        for f in &self.faces {
            for i in 1..f.len().saturating_sub(1) {
                let d = (f[0] - c).dot((f[i] - c).cross(f[i + 1] - c));
                v += d.abs() / 6.0;
            }
        }
        v
    }

    /// The mean of the distinct vertices (inside a non-empty polytope).
    pub fn vertex_centroid(&self) -> Option<P3> {
        let v = self.vertices();
        (!v.is_empty())
            .then(|| v.iter().fold(Point3::default(), |a, &p| a + p) * (1.0 / v.len() as f64))
    }

    /// The part where `a . x + b >= 0`; `size` is a length typical of the polytope (for the
    /// rounding threshold). `a = 0` keeps everything if `b > 0`, nothing otherwise.
    pub fn clip(&self, a: P3, b: f64, size: f64) -> Self {
        let eps = match Cut::new(a.length(), b, size) {
            Cut::All(true) => return self.clone(),
            Cut::All(false) => return Self::default(),
            Cut::By { eps } => eps,
        };
        let na = a.length();
        let f = |p: P3| a.dot(p) + b;
        let mut faces = Vec::new();
        let mut cap: Vec<P3> = Vec::new();
        // A face lying in the cutting plane is already the cap (a plane through a face, a
        // duplicate plane): adding the section again would count that face twice.
        let mut face_in_plane = false;
        for face in &self.faces {
            if face.iter().all(|&p| f(p).abs() <= eps) {
                face_in_plane = true;
                faces.push(face.clone());
                continue;
            }
            let out = clip_cycle(face, f, eps, size, |p| cap.push(p));
            if out.len() >= 3 {
                faces.push(out);
            }
        }
        // The cap: the section of the polytope by the plane, ordered by angle about its centre.
        let mut pts: Vec<P3> = Vec::new();
        for p in cap {
            if !pts.iter().any(|q| (p - *q).length() <= SAME_VERTEX * size) {
                pts.push(p);
            }
        }
        if pts.len() >= 3 && faces.len() >= 3 && !face_in_plane {
            let c = pts.iter().fold(Point3::default(), |s, &p| s + p) * (1.0 / pts.len() as f64);
            let nrm = a * (1.0 / na);
            let helper = if nrm.x.abs() < 0.9 {
                Point3::new(1.0, 0.0, 0.0)
            } else {
                Point3::new(0.0, 1.0, 0.0)
            };
            let u = nrm.cross(helper);
            let u = u * (1.0 / u.length());
            let v = nrm.cross(u);
            pts.sort_by(|p, q| {
                let ap = (*p - c).dot(v).atan2((*p - c).dot(u));
                let aq = (*q - c).dot(v).atan2((*q - c).dot(u));
                ap.total_cmp(&aq)
            });
            faces.push(pts);
        }
        if faces.len() < 4 {
            faces.clear();
        }
        Self { faces }
    }
}

fn bounding_size(points: &[P3]) -> f64 {
    Point3::bounds(points.iter().copied()).map_or(0.0, |(lo, hi)| (hi - lo).length())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cube_cut_by_planes() {
        let c = ConvexPolytope::cuboid(Point3::default(), Point3::new(1.0, 2.0, 3.0));
        assert!((c.volume() - 6.0).abs() < 1e-14);
        assert_eq!(c.vertices().len(), 8);
        // Cut off the corner x + y + z <= 1 from the unit cube: volume 1 - 1/6 remains.
        let u = ConvexPolytope::cuboid(Point3::default(), Point3::new(1.0, 1.0, 1.0));
        let cut = u.clip(Point3::new(1.0, 1.0, 1.0), -1.0, 1.0);
        assert!(
            (cut.volume() - (1.0 - 1.0 / 6.0)).abs() < 1e-14,
            "{}",
            cut.volume()
        );
        assert_eq!(cut.face_count(), 7);
        assert_eq!(cut.vertices().len(), 7); // the plane passes through three vertices
        // Keep only the corner: a tetrahedron.
        let tet = u.clip(Point3::new(-1.0, -1.0, -1.0), 1.0, 1.0);
        assert!((tet.volume() - 1.0 / 6.0).abs() < 1e-15);
        assert_eq!(tet.face_count(), 4);
        assert!(u.clip(Point3::new(1.0, 0.0, 0.0), -2.0, 1.0).is_empty());
        // Clipping by the plane of a face, from either side, or twice by one plane.
        for (a, b) in [
            (Point3::new(0.0, 0.0, 1.0), 0.0),
            (Point3::new(0.0, 0.0, -1.0), 1.0),
            (Point3::new(1.0, 0.0, 0.0), 0.0),
        ] {
            let same = u.clip(a, b, 1.0);
            assert_eq!(same.face_count(), 6, "{a:?} {b}");
            assert!((same.volume() - 1.0).abs() < 1e-15, "{}", same.volume());
        }
        assert!(u.clip(Point3::new(0.0, 0.0, -1.0), 0.0, 1.0).is_empty());
        let twice = cut.clip(Point3::new(1.0, 1.0, 1.0), -1.0, 1.0);
        assert_eq!(twice.face_count(), 7);
        assert!((twice.volume() - cut.volume()).abs() < 1e-15);
        // A parallel plane inside: half the cube, still six faces.
        let upper = u.clip(Point3::new(0.0, 0.0, 1.0), -0.5, 1.0).clip(
            Point3::new(0.0, 0.0, 2.0),
            -1.0,
            1.0,
        );
        assert_eq!(upper.face_count(), 6);
        assert!((upper.volume() - 0.5).abs() < 1e-15);
        // Halving along the plane through four vertices.
        let half = u.clip(Point3::new(1.0, -1.0, 0.0), 0.0, 1.0);
        assert!((half.volume() - 0.5).abs() < 1e-15);
        assert_eq!(half.face_count(), 5);
    }
}
