//! A curved triangulation from its parts as a mesh or spline file holds them, checked
//! before it is assembled.

use rs_spline::prelude::*;
use rs_spline::{Domain, Point};

use super::curved::{BoundaryArc, CurvedTriangulation, EdgeKind, Parts};
use crate::MeshError;
use crate::boundary::BoundaryPoint;
use crate::limits::MAX_MESH_VERTICES;

impl CurvedTriangulation {
    /// A curved triangulation from its parts, as a mesh or spline file holds them
    /// ([`crate::mesh_from_json`]), checked: vertex indices in range, triangles
    /// counter-clockwise and not flat, every arc on an existing curve and loop with
    /// `u0 < u1` in the curve's parameter range, its end points on its vertices (within
    /// `1e-9` of the domain's size) and joining two consecutive vertices of its triangle.
    ///
    /// # Errors
    /// [`MeshError::Invalid`] naming the first problem.
    pub fn from_parts(
        domain: Domain,
        vertices: Vec<Point>,
        triangles: Vec<[usize; 3]>,
        arcs: Vec<BoundaryArc>,
    ) -> Result<Self, MeshError> {
        let invalid = |m: String| MeshError::Invalid(m);
        if vertices.len() > MAX_MESH_VERTICES {
            return Err(invalid(format!(
                "{} vertices exceed the limit {MAX_MESH_VERTICES}",
                vertices.len()
            )));
        }
        if let Some(i) = vertices.iter().position(|p| !p.is_finite()) {
            return Err(invalid(format!("vertex {i} is not finite")));
        }
        for (t, tri) in triangles.iter().enumerate() {
            if let Some(&v) = tri.iter().find(|&&v| v >= vertices.len()) {
                return Err(invalid(format!(
                    "triangle {t} names vertex {v} of {}",
                    vertices.len()
                )));
            }
            let [a, b, c] = tri.map(|v| vertices[v]);
            if (b - a).cross(c - a) <= 0.0 {
                return Err(invalid(format!(
                    "triangle {t} is not counter-clockwise (or is flat)"
                )));
            }
        }
        let size = domain.bounding_box().diagonal();
        let mut edges = vec![[EdgeKind::Straight; 3]; triangles.len()];
        let mut boundary_vertex = vec![None; vertices.len()];
        let mut loop_lengths = vec![0usize; domain.loops().len()];
        for (i, a) in arcs.iter().enumerate() {
            let bad = |m: &str| invalid(format!("curved edge {i}: {m}"));
            let curve = domain
                .curves()
                .get(a.curve)
                .ok_or_else(|| bad("no such curve"))?;
            if a.loop_index >= domain.loops().len() {
                return Err(bad("no such loop"));
            }
            let (lo, hi) = curve.param_range();
            if !(lo <= a.u0 && a.u0 < a.u1 && a.u1 <= hi) {
                return Err(bad(
                    "parameters outside the curve's range or not increasing",
                ));
            }
            let tri = triangles
                .get(a.triangle)
                .ok_or_else(|| bad("no such triangle"))?;
            let k = (0..3)
                .find(|&k| {
                    let (p, q) = (tri[k], tri[(k + 1) % 3]);
                    (p, q) == (a.from, a.to) || (q, p) == (a.from, a.to)
                })
                .ok_or_else(|| bad("its end vertices are not an edge of its triangle"))?;
            for (u, v) in [(a.u0, a.from), (a.u1, a.to)] {
                if curve.point_at(u).distance(vertices[v]) > 1e-9 * size {
                    return Err(bad("an end of the arc is not at its vertex"));
                }
            }
            if edges[a.triangle][k] != EdgeKind::Straight {
                return Err(bad("a second arc on the same edge"));
            }
            edges[a.triangle][k] = EdgeKind::Curved(i);
            boundary_vertex[a.from] = Some(BoundaryPoint {
                loop_index: a.loop_index,
                curve: a.curve,
                u: a.u0,
                point: vertices[a.from],
            });
            loop_lengths[a.loop_index] += 1;
        }
        Ok(Self::assemble(Parts {
            domain,
            vertices,
            boundary_vertex,
            triangles,
            edges,
            arcs,
            loop_lengths,
        }))
    }
}
