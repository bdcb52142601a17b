//! The extended triangulation of Algorithm 5.1 (Schumaker and Yu 2021, Section 5.2, Fig. 4):
//! the companion triangles plus a ring of `2 n_b` straight triangles outside the boundary
//! chords, reaching far enough out to cover every sliver between a boundary arc and its chord.
//! Used for drawing; the exact point location is [`crate::CurvedLocator`]'s.

use rs_spline::prelude::*;
use rs_spline::{Affine, Point};

use crate::{CurvedTriangulation, MeshError};

/// The ring of an extended triangulation: for each boundary arc (chord `a b`), the triangles
/// `a b b'` and `a b' a'`, where `a'`, `b'` are the boundary vertices moved by `offset` along
/// their outward normals (the mean of the outward normals of their two chords).
#[derive(Clone, Debug)]
pub struct ExtendedRing {
    /// The offset used.
    pub offset: f64,
    /// The ring's triangles, counter-clockwise.
    pub triangles: Vec<[Point; 3]>,
    /// For each ring triangle, the curved triangle whose polynomial applies there (the one
    /// with the arc).
    pub neighbour: Vec<usize>,
}

impl CurvedTriangulation {
    /// The ring of Algorithm 5.1 with the offset `1.5` times the largest distance a boundary
    /// arc bulges out of its chord (plus a little), so that the ring covers every outer sliver.
    ///
    /// # Errors
    /// [`MeshError::Spline`] if an arc cannot be cut from its curve.
    pub fn extended_ring(&self) -> Result<ExtendedRing, MeshError> {
        let v = self.vertices();
        // Outward unit normal of each arc's chord: away from its triangle's third vertex.
        let mut chord_normal = Vec::with_capacity(self.arcs().len());
        let mut bulge = 0.0f64;
        for arc in self.arcs() {
            let (a, b) = (v[arc.from], v[arc.to]);
            let tri = self.triangles()[arc.triangle];
            let third = tri
                .iter()
                .copied()
                .find(|&i| i != arc.from && i != arc.to)
                .map_or(a, |i| v[i]);
            let d = b - a;
            let mut n = Point::new(d.y, -d.x) * (1.0 / d.length());
            if n.dot(third - a) > 0.0 {
                n = n * -1.0;
            }
            // How far the arc goes out: the largest outward offset of the arc from the chord.
            let map = Affine {
                m: [n.x, 0.0, n.y, 0.0, 0.0, 0.0],
            }
            .then_apply_to(Affine::translate(-a.x, -a.y));
            let out = map.apply_to_curve(&self.arc_curve(arc)?)?;
            bulge = bulge.max(out.bounding_box().max.x);
            chord_normal.push(n);
        }
        let size = self.domain().bounding_box().diagonal();
        let offset = 1.5 * bulge + 1e-3 * size;
        // Vertex normals: the mean of the normals of the (one or two) chords at the vertex.
        let mut vertex_normal = vec![Point::new(0.0, 0.0); v.len()];
        for (arc, n) in self.arcs().iter().zip(&chord_normal) {
            vertex_normal[arc.from] = vertex_normal[arc.from] + *n;
            vertex_normal[arc.to] = vertex_normal[arc.to] + *n;
        }
        let moved = |i: usize| {
            let n = vertex_normal[i];
            let len = n.length();
            if len > 0.0 {
                v[i] + n * (offset / len)
            } else {
                v[i]
            }
        };
        let mut triangles = Vec::with_capacity(2 * self.arcs().len());
        let mut neighbour = Vec::with_capacity(2 * self.arcs().len());
        for arc in self.arcs() {
            let (a, b) = (v[arc.from], v[arc.to]);
            let (a2, b2) = (moved(arc.from), moved(arc.to));
            for tri in [[a, b, b2], [a, b2, a2]] {
                let area = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
                triangles.push(if area < 0.0 {
                    [tri[0], tri[2], tri[1]]
                } else {
                    tri
                });
                neighbour.push(arc.triangle);
            }
        }
        Ok(ExtendedRing {
            offset,
            triangles,
            neighbour,
        })
    }
}
