//! Clough–Tocher and Powell–Sabin refinements of a curved triangulation (Schumaker and Yu
//! 2021, Section 8 and Fig. 7): every triangle split into 3 or 6, each boundary arc kept on
//! the sub-triangle that has (part of) its chord.

use std::collections::HashMap;

use rs_spline::Point;
use rs_spline::prelude::*;

use super::convertible::{EdgeGrid, arc_is_clear};
use super::curved::{BoundaryArc, CurvedTriangulation, EdgeKind, Parts, Refinement};
use crate::boundary::BoundaryPoint;

/// The refinement of `t` (an unrefined triangulation), or the places `(loop, k)` of the arcs
/// of `t` whose refined arcs meet another edge or whose sub-triangles come out inverted.
pub(super) fn refine(
    t: &CurvedTriangulation,
    how: Refinement,
) -> Result<CurvedTriangulation, Vec<(usize, usize)>> {
    let mut r = Refined::start(t, how);
    for tri in 0..t.triangles().len() {
        match how {
            Refinement::CloughTocher => r.clough_tocher(t, tri),
            Refinement::PowellSabin => r.powell_sabin(t, tri),
        }
    }
    let failing = r.check(t);
    if !failing.is_empty() {
        return Err(failing);
    }
    Ok(CurvedTriangulation::assemble(Parts {
        domain: t.domain().clone(),
        vertices: r.vertices,
        boundary_vertex: r.boundary_vertex,
        triangles: r.triangles,
        edges: r.edges,
        arcs: r.arcs,
        loop_lengths: t.loop_lengths().to_vec(),
    })
    .into_refinement(how, r.parent)
    .with_counts(t.inserted_boundary_points(), t.dropped_interior_points()))
}

/// The refinement under construction.
struct Refined {
    vertices: Vec<Point>,
    boundary_vertex: Vec<Option<BoundaryPoint>>,
    triangles: Vec<[usize; 3]>,
    edges: Vec<[EdgeKind; 3]>,
    arcs: Vec<BoundaryArc>,
    parent: Vec<usize>,
    /// Which unrefined arc each refined arc comes from.
    arc_parent: Vec<usize>,
    /// Powell–Sabin: the split point of each edge (unordered vertex pair).
    edge_point: HashMap<(usize, usize), usize>,
    /// Powell–Sabin: the incentre of each unrefined triangle.
    incentre: Vec<Point>,
    /// Powell–Sabin: the triangles of each edge (unordered vertex pair).
    edge_triangles: HashMap<(usize, usize), Vec<usize>>,
}

impl Refined {
    fn start(t: &CurvedTriangulation, how: Refinement) -> Self {
        let n = t.triangles().len() * how.factor();
        let (incentre, edge_triangles) = match how {
            Refinement::PowellSabin => {
                let mut edges: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
                for (s, v) in t.triangles().iter().enumerate() {
                    for k in 0..3 {
                        let (a, b) = (v[k], v[(k + 1) % 3]);
                        edges.entry((a.min(b), a.max(b))).or_default().push(s);
                    }
                }
                let centres = t
                    .triangles()
                    .iter()
                    .map(|tri| incentre(tri.map(|v| t.vertices()[v])))
                    .collect();
                (centres, edges)
            }
            Refinement::CloughTocher => (Vec::new(), HashMap::new()),
        };
        Self {
            vertices: t.vertices().to_vec(),
            boundary_vertex: t.boundary_vertices().to_vec(),
            triangles: Vec::with_capacity(n),
            edges: Vec::with_capacity(n),
            arcs: Vec::with_capacity(2 * t.arcs().len()),
            parent: Vec::with_capacity(n),
            arc_parent: Vec::new(),
            edge_point: HashMap::new(),
            incentre,
            edge_triangles,
        }
    }

    fn vertex(&mut self, p: Point, boundary: Option<BoundaryPoint>) -> usize {
        self.vertices.push(p);
        self.boundary_vertex.push(boundary);
        self.vertices.len() - 1
    }

    /// Adds sub-triangle `tri` of unrefined triangle `parent`, its edge 0 an arc (`Some`:
    /// the arc, and the unrefined arc it comes from) or straight.
    fn triangle(&mut self, tri: [usize; 3], parent: usize, arc: Option<(BoundaryArc, usize)>) {
        let index = self.triangles.len();
        let mut kinds = [EdgeKind::Straight; 3];
        if let Some((mut a, from)) = arc {
            a.triangle = index;
            kinds[0] = EdgeKind::Curved(self.arcs.len());
            self.arcs.push(a);
            self.arc_parent.push(from);
        }
        self.triangles.push(tri);
        self.edges.push(kinds);
        self.parent.push(parent);
    }

    fn clough_tocher(&mut self, t: &CurvedTriangulation, tri: usize) {
        let v = t.triangles()[tri];
        let p = v.map(|i| t.vertices()[i]);
        let c = self.vertex((p[0] + p[1] + p[2]) * (1.0 / 3.0), None);
        for k in 0..3 {
            let arc = match t.edge_kinds(tri)[k] {
                EdgeKind::Curved(i) => Some((t.arcs()[i].clone(), i)),
                EdgeKind::Straight => None,
            };
            self.triangle([v[k], v[(k + 1) % 3], c], tri, arc);
        }
    }

    fn powell_sabin(&mut self, t: &CurvedTriangulation, tri: usize) {
        let v = t.triangles()[tri];
        let c = self.vertex(self.incentre[tri], None);
        for k in 0..3 {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            match t.edge_kinds(tri)[k] {
                EdgeKind::Curved(i) => {
                    let arc = &t.arcs()[i];
                    let curve = &t.domain().curves()[arc.curve];
                    let um = 0.5 * (arc.u0 + arc.u1);
                    let m = self.vertex(
                        curve.point_at(um),
                        Some(BoundaryPoint {
                            loop_index: arc.loop_index,
                            curve: arc.curve,
                            u: um,
                            point: curve.point_at(um),
                        }),
                    );
                    let first = BoundaryArc {
                        u1: um,
                        to: m,
                        ..arc.clone()
                    };
                    let second = BoundaryArc {
                        u0: um,
                        from: m,
                        ..arc.clone()
                    };
                    // The half starting at the arc's `from` lies on the sub-triangle with that
                    // vertex.
                    let (at_a, at_b) = if arc.from == a {
                        (first, second)
                    } else {
                        (second, first)
                    };
                    self.triangle([a, m, c], tri, Some((at_a, i)));
                    self.triangle([m, b, c], tri, Some((at_b, i)));
                }
                EdgeKind::Straight => {
                    let m = self.interior_edge_point(t, tri, a, b);
                    self.triangle([a, m, c], tri, None);
                    self.triangle([m, b, c], tri, None);
                }
            }
        }
    }

    /// The split point of interior edge `a b` of `tri`, shared with the other triangle.
    fn interior_edge_point(
        &mut self,
        t: &CurvedTriangulation,
        tri: usize,
        a: usize,
        b: usize,
    ) -> usize {
        let key = (a.min(b), a.max(b));
        if let Some(&m) = self.edge_point.get(&key) {
            return m;
        }
        let (pa, pb) = (t.vertices()[a], t.vertices()[b]);
        let other = self
            .edge_triangles
            .get(&key)
            .and_then(|ts| ts.iter().copied().find(|&s| s != tri));
        let point = other
            .and_then(|s| line_crossing(self.incentre[tri], self.incentre[s], pa, pb))
            .unwrap_or((pa + pb) * 0.5);
        let m = self.vertex(point, None);
        self.edge_point.insert(key, m);
        m
    }

    /// The unrefined arcs (by place in their loop) whose refined arcs meet another edge, or
    /// whose sub-triangles are inverted or flat.
    fn check(&self, t: &CurvedTriangulation) -> Vec<(usize, usize)> {
        let size = t.domain().bounding_box().diagonal();
        let mut bad: Vec<usize> = Vec::new();
        for (s, tri) in self.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|v| self.vertices[v]);
            if (b - a).cross(c - a) <= 0.0 {
                // Only a sub-triangle on a boundary arc can turn over (its split point is
                // on the curve); blame the arc of its parent.
                let parent = self.parent[s];
                bad.extend(t.edge_kinds(parent).iter().filter_map(|e| match e {
                    EdgeKind::Curved(i) => Some(*i),
                    EdgeKind::Straight => None,
                }));
            }
        }
        let mut all_edges: Vec<(usize, usize)> = self
            .triangles
            .iter()
            .flat_map(|v| (0..3).map(move |k| (v[k].min(v[(k + 1) % 3]), v[k].max(v[(k + 1) % 3]))))
            .collect();
        all_edges.sort_unstable();
        all_edges.dedup();
        let grid = EdgeGrid::new(&self.vertices, &all_edges);
        for (i, arc) in self.arcs.iter().enumerate() {
            let curve = &t.domain().curves()[arc.curve];
            let clear = curve
                .subsegment((arc.u0, arc.u1))
                .is_ok_and(|c| arc_is_clear(&c, (arc.from, arc.to), &self.vertices, &grid, size));
            if !clear {
                bad.push(self.arc_parent[i]);
            }
        }
        bad.sort_unstable();
        bad.dedup();
        bad.into_iter().map(|i| t.arc_position(i)).collect()
    }
}

/// The incentre: the vertices weighted by the lengths of the opposite sides.
fn incentre(p: [Point; 3]) -> Point {
    let w = [
        p[1].distance(p[2]),
        p[2].distance(p[0]),
        p[0].distance(p[1]),
    ];
    let sum = w[0] + w[1] + w[2];
    (p[0] * w[0] + p[1] * w[1] + p[2] * w[2]) * (1.0 / sum)
}

/// Where the segment `p q` crosses the segment `a b`, strictly inside `a b`.
fn line_crossing(p: Point, q: Point, a: Point, b: Point) -> Option<Point> {
    let (d, e) = (q - p, b - a);
    let denom = d.cross(e);
    if denom == 0.0 {
        return None;
    }
    let s = (a - p).cross(d) / denom;
    (s > 0.0 && s < 1.0).then(|| a + e * s)
}

#[cfg(test)]
mod tests {
    use super::Refinement;

    #[test]
    fn refinements_parse_from_their_names() {
        for (name, how) in [
            ("ct", Refinement::CloughTocher),
            ("CT", Refinement::CloughTocher),
            ("clough-tocher", Refinement::CloughTocher),
            ("ps", Refinement::PowellSabin),
            ("powell-sabin", Refinement::PowellSabin),
        ] {
            assert_eq!(name.parse::<Refinement>(), Ok(how), "{name}");
            assert_eq!(Refinement::parse_optional(name), Ok(Some(how)), "{name}");
        }
        assert_eq!(
            "none".parse::<Refinement>().unwrap_err(),
            "unknown refinement \"none\" (expected ct or ps)"
        );
        assert_eq!(Refinement::parse_optional("none"), Ok(None));
        assert_eq!(Refinement::parse_optional("None"), Ok(None));
        assert_eq!(
            Refinement::parse_optional("cubic").unwrap_err(),
            "unknown refinement \"cubic\" (expected none, ct or ps)"
        );
    }
}
