//! The space `S_d^0` of continuous splines of degree `d` on a curved triangulation
//! (Schumaker and Yu 2021, Section 5): one Bernstein–Bézier coefficient per domain point of
//! the companion triangulation, shared by the triangles that share the point, so continuity
//! is built in.

use std::collections::HashMap;

use rs_mesh::CurvedTriangulation;

use crate::bb::{coefficient_count, multi_indices};

/// The global numbering of the domain points of degree `d`: vertices first, then the `d - 1`
/// points inside each edge (from its lower-numbered vertex), then the `C(d - 1, 2)` points
/// inside each triangle.
#[derive(Clone, Debug)]
pub struct SplineSpace {
    degree: usize,
    vertices: usize,
    edges: usize,
    triangles: usize,
    /// For each triangle, the global index of each of its domain points, in coefficient
    /// order.
    global: Vec<u32>,
}

impl SplineSpace {
    /// The space of degree `d` on `mesh` (the degree is not checked here).
    pub fn new(mesh: &CurvedTriangulation, d: usize) -> Self {
        let nv = mesh.vertices().len();
        let mut edge_ids: HashMap<(usize, usize), usize> = HashMap::new();
        for tri in mesh.triangles() {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                let next = edge_ids.len();
                edge_ids.entry((a.min(b), a.max(b))).or_insert(next);
            }
        }
        let ne = edge_ids.len();
        let inner = if d >= 3 { (d - 1) * (d - 2) / 2 } else { 0 };
        let n = coefficient_count(d);
        let mut global = Vec::with_capacity(mesh.triangles().len() * n);
        for (t, tri) in mesh.triangles().iter().enumerate() {
            let mut next_inner = 0;
            for (i, j, k) in multi_indices(d) {
                let id = match (i == 0, j == 0, k == 0) {
                    (false, true, true) => tri[0],
                    (true, false, true) => tri[1],
                    (true, true, false) => tri[2],
                    (_, _, true) => edge_point(&edge_ids, nv, d, (tri[0], tri[1]), j),
                    (true, _, _) => edge_point(&edge_ids, nv, d, (tri[1], tri[2]), k),
                    (_, true, _) => edge_point(&edge_ids, nv, d, (tri[2], tri[0]), i),
                    _ => {
                        next_inner += 1;
                        nv + ne * (d - 1) + t * inner + next_inner - 1
                    }
                };
                global.push(id as u32);
            }
        }
        Self {
            degree: d,
            vertices: nv,
            edges: ne,
            triangles: mesh.triangles().len(),
            global,
        }
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The dimension: `n_v + (d - 1) n_e + C(d - 1, 2) n_t` (the paper's formula (5.2)).
    pub fn dimension(&self) -> usize {
        let d = self.degree;
        let inner = if d >= 3 { (d - 1) * (d - 2) / 2 } else { 0 };
        self.vertices + (d - 1) * self.edges + inner * self.triangles
    }

    /// Numbers of vertices, edges and triangles.
    pub fn counts(&self) -> (usize, usize, usize) {
        (self.vertices, self.edges, self.triangles)
    }

    /// The global indices of the domain points of triangle `t`, in coefficient order.
    pub fn triangle_indices(&self, t: usize) -> &[u32] {
        let n = coefficient_count(self.degree);
        &self.global[t * n..(t + 1) * n]
    }
}

/// The global index of the point `steps / d` of the way along edge `(from, to)` (`0 < steps <
/// d`), numbered from the edge's lower vertex.
fn edge_point(
    ids: &HashMap<(usize, usize), usize>,
    nv: usize,
    d: usize,
    (from, to): (usize, usize),
    steps: usize,
) -> usize {
    let e = ids[&(from.min(to), from.max(to))];
    let from_low = if from < to { steps } else { d - steps };
    nv + e * (d - 1) + from_low - 1
}
