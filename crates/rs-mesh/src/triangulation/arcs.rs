//! Algorithm 4.1: every boundary chord of the inscribed triangulation replaced by the
//! boundary arc it cuts off, where that arc meets no other edge (Definition 4.2).

use std::collections::HashMap;

use rs_spline::prelude::*;
use rs_spline::{Domain, NurbsCurve, SplineError};

use super::cdt::Vertices;
use super::convertible::{EdgeGrid, arc_is_clear};
use super::curved::{BoundaryArc, EdgeKind};
use crate::MeshError;
use crate::boundary::BoundaryPoint;

/// Arcs, edge kinds per triangle, and the chords whose arcs cannot replace them (an arc
/// meeting another edge, a chord owned by no kept triangle).
type Attached = (Vec<BoundaryArc>, Vec<[EdgeKind; 3]>, Vec<(usize, usize)>);

/// Replaces every boundary chord by its arc where the arc meets no other edge (paper
/// Definition 4.2, convertibility).
pub(super) fn attach_arcs(
    domain: &Domain,
    v: &Vertices,
    loops: &[Vec<usize>],
    triangles: &[[usize; 3]],
    size: f64,
) -> Result<Attached, MeshError> {
    let mut edge_of: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            edge_of.insert((tri[k], tri[(k + 1) % 3]), (t, k));
        }
    }
    let all_edges: Vec<(usize, usize)> = edge_of
        .keys()
        .filter(|(a, b)| a < b || !edge_of.contains_key(&(*b, *a)))
        .copied()
        .collect();
    let grid = EdgeGrid::new(&v.points, &all_edges);
    let mut arcs = Vec::new();
    let mut edges = vec![[EdgeKind::Straight; 3]; triangles.len()];
    let mut failing = Vec::new();
    for (j, ids) in loops.iter().enumerate() {
        for k in 0..ids.len() {
            let (a, b) = (ids[k], ids[(k + 1) % ids.len()]);
            let (Some(pa), Some(pb)) = (v.boundary[a], v.boundary[b]) else {
                failing.push((j, k));
                continue;
            };
            let owner = edge_of.get(&(a, b)).or_else(|| edge_of.get(&(b, a)));
            let Some(&(t, e)) = owner else {
                failing.push((j, k));
                continue;
            };
            let u1 = arc_end(domain, &pa, &pb);
            let arc_curve = chord_arc(domain, &pa, &pb)?;
            if !arc_is_clear(&arc_curve, (a, b), &v.points, &grid, size) {
                failing.push((j, k));
                continue;
            }
            edges[t][e] = EdgeKind::Curved(arcs.len());
            arcs.push(BoundaryArc {
                loop_index: j,
                curve: pa.curve,
                u0: pa.u,
                u1,
                from: a,
                to: b,
                triangle: t,
            });
        }
    }
    Ok((arcs, edges, failing))
}

/// Where the boundary arc from `pa` to the next boundary point `pb` ends on `pa`'s curve: at
/// `pb` on the same curve, else at the curve's end.
fn arc_end(domain: &Domain, pa: &BoundaryPoint, pb: &BoundaryPoint) -> f64 {
    if pb.curve == pa.curve && pb.u > pa.u {
        pb.u
    } else {
        domain.curves()[pa.curve].param_range().1
    }
}

/// The boundary arc from `pa` to the next boundary point `pb` (see [`arc_end`]).
pub(super) fn chord_arc(
    domain: &Domain,
    pa: &BoundaryPoint,
    pb: &BoundaryPoint,
) -> Result<NurbsCurve, SplineError> {
    domain.curves()[pa.curve].subsegment((pa.u, arc_end(domain, pa, pb)))
}
