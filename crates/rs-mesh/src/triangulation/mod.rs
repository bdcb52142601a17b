//! Inscribed triangulations (constrained Delaunay, by `spade`), the convertibility check of
//! Definition 4.2 with automatic boundary point insertion, and the curved triangulation of
//! Algorithm 4.1.

use rs_spline::prelude::*;
use std::collections::HashSet;

use rs_spline::{Domain, NurbsCurve, Point};
use spade::Triangulation as _;

use crate::MeshError;
use crate::boundary::BoundaryPoint;
use crate::sample::WellSpacedPoints;

mod arcs;
mod cdt;
mod convertible;
mod crossing;
mod insertion;
mod refine;

use arcs::{attach_arcs, chord_arc};
use cdt::{Vertices, constrain_chords, faces_inside, stray_interior};
use crossing::where_arcs_meet;
use insertion::{curve_corners, refine_loops};
use refine::refine;

/// Rounds of boundary point insertion tried before giving up.
const MAX_ROUNDS: usize = 16;
/// Boundary points that insertion may add per initial boundary point (see
/// [`CurvedTriangulation::new`]); the domains of the tests need at most 4.
pub const MAX_INSERTED_PER_POINT: usize = 16;
/// Boundary points that insertion may add beyond [`MAX_INSERTED_PER_POINT`] per initial one.
pub const MAX_INSERTED_EXTRA: usize = 4096;

/// Which kind of edge a triangle edge is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeKind {
    /// A straight (interior) edge.
    Straight,
    /// A boundary arc: index into [`CurvedTriangulation::arcs`].
    Curved(usize),
}

/// A piece of a boundary curve between two consecutive boundary vertices.
#[derive(Clone, Debug, PartialEq)]
pub struct BoundaryArc {
    /// Loop of the domain.
    pub loop_index: usize,
    /// Curve of the domain the arc lies on.
    pub curve: usize,
    /// Parameter range on that curve, from `u0` (at vertex `from`) to `u1` (at vertex `to`).
    pub u0: f64,
    /// End parameter.
    pub u1: f64,
    /// Vertex at `u0`.
    pub from: usize,
    /// Vertex at `u1`.
    pub to: usize,
    /// The curved triangle it bounds.
    pub triangle: usize,
}

/// How a refinement splits each triangle `v0 v1 v2` (counter-clockwise).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Refinement {
    /// At the barycentre `c`: sub-triangles `v_k v_(k+1) c` for `k = 0, 1, 2` (numbered
    /// `3 t + k`); edge `k` of the triangle is edge 0 of sub-triangle `k`.
    CloughTocher,
    /// At the incentre `c` and one point `m_k` per edge: sub-triangles `v_k m_k c` and
    /// `m_k v_(k+1) c` (numbered `6 t + 2 k` and `6 t + 2 k + 1`). On an interior edge `m_k` is
    /// where the segment joining the incentres of the two triangles sharing it crosses it (the
    /// Powell–Sabin choice); on a boundary edge it is the point of the boundary arc at the
    /// arc's parameter midpoint, a new boundary vertex, and the arc is split there.
    PowellSabin,
}

impl Refinement {
    /// Sub-triangles per triangle.
    pub fn factor(self) -> usize {
        match self {
            Refinement::CloughTocher => 3,
            Refinement::PowellSabin => 6,
        }
    }
}

/// A curved triangulation of a domain (Definition 3.2) with straight interior edges: an
/// inscribed constrained Delaunay triangulation whose boundary edges are replaced by the
/// boundary arcs they cut off (Algorithm 4.1), or a Clough–Tocher or Powell–Sabin refinement
/// of one ([`CurvedTriangulation::new_refined`]).
#[derive(Clone, Debug)]
pub struct CurvedTriangulation {
    domain: Domain,
    vertices: Vec<Point>,
    boundary_vertex: Vec<Option<BoundaryPoint>>,
    triangles: Vec<[usize; 3]>,
    edges: Vec<[EdgeKind; 3]>,
    arcs: Vec<BoundaryArc>,
    /// Number of boundary vertices of each loop (arc `i` joins the `k`-th and `(k+1)`-th
    /// vertices of its loop, arcs listed loop by loop in that order).
    loop_lengths: Vec<usize>,
    /// For a refinement: how, and the triangle of the unrefined triangulation each triangle
    /// lies in.
    refinement: Option<(Refinement, Vec<usize>)>,
    inserted_boundary_points: usize,
    dropped_interior_points: usize,
}

impl CurvedTriangulation {
    /// Builds the curved triangulation of `domain` from sampled points (boundary points per
    /// loop in loop order, interior points): a constrained Delaunay triangulation with every
    /// boundary chord as a constraint, triangles kept by crossing parity of the constraint
    /// loops (holes excluded), then checked for convertibility (Definition 4.2: no boundary arc
    /// meets an edge of the triangulation except at that edge's end points, every chord an
    /// edge). Arcs that fail get a new boundary point, at a corner of the curve inside the
    /// arc if there is one (a joint of Bezier pieces where the tangent turns: no split
    /// elsewhere straightens an arc across a corner), else at the arc's parameter midpoint,
    /// and the triangulation is rebuilt, until it is convertible. Interior points that end up
    /// between a boundary arc and its chord are dropped.
    ///
    /// Insertion is bounded: at most [`MAX_INSERTED_PER_POINT`] times the initial boundary
    /// points plus [`MAX_INSERTED_EXTRA`], and at most [`MAX_MESH_VERTICES`] vertices in all.
    /// A boundary that overlaps or crosses itself never becomes convertible (the arcs along
    /// the overlap keep failing, and their number doubles with every round), so it ends in
    /// [`MeshError::InsertionLimit`], naming a point near the trouble.
    ///
    /// # Errors
    /// [`MeshError::TooManyPieces`] for a boundary of more than [`MAX_MESH_PIECES`] Bezier
    /// pieces, [`MeshError::NotConvertible`] if 16 rounds of insertion do not suffice,
    /// [`MeshError::InsertionLimit`] if the insertion budget does not,
    /// [`MeshError::Triangulation`] if spade rejects a point.
    pub fn new(domain: &Domain, points: &WellSpacedPoints) -> Result<Self, MeshError> {
        Self::build_until(domain, points, Ok)
    }

    /// The Clough–Tocher or Powell–Sabin refinement of the curved triangulation of `domain`
    /// from `points` (paper Section 8, Fig. 7; see [`Refinement`]): built as
    /// [`CurvedTriangulation::new`] builds the unrefined one, then split; if a boundary arc of
    /// the refinement meets one of its new edges (Definition 4.2 again) or a sub-triangle comes
    /// out inverted, the unrefined arc gets a boundary point (at a corner inside it, else at
    /// its parameter midpoint, as in [`CurvedTriangulation::new`]) and both are rebuilt.
    ///
    /// # Errors
    /// As [`CurvedTriangulation::new`].
    pub fn new_refined(
        domain: &Domain,
        points: &WellSpacedPoints,
        how: Refinement,
    ) -> Result<Self, MeshError> {
        Self::build_until(domain, points, |t| refine(&t, how))
    }

    /// The rounds of [`CurvedTriangulation::new`]: build, then `finish` the triangulation (or
    /// name the arcs, by their place in their loop, to split before the next round).
    fn build_until(
        domain: &Domain,
        points: &WellSpacedPoints,
        finish: impl Fn(Self) -> Result<Self, Vec<(usize, usize)>>,
    ) -> Result<Self, MeshError> {
        check_boundary_pieces(domain)?;
        let vertices = points.interior.len() + points.boundary.iter().map(Vec::len).sum::<usize>();
        if vertices > MAX_MESH_VERTICES {
            return Err(MeshError::TooManyPoints {
                estimate: vertices as f64,
                limit: MAX_MESH_VERTICES,
            });
        }
        let mut boundary = normalized_loops(domain, &points.boundary);
        let initial: usize = boundary.iter().map(Vec::len).sum();
        let budget = (MAX_INSERTED_PER_POINT * initial + MAX_INSERTED_EXTRA)
            .min(MAX_MESH_VERTICES.saturating_sub(points.interior.len() + initial));
        let mut interior = points.interior.clone();
        let mut inserted = 0;
        let mut dropped = 0;
        let size = domain.bounding_box().diagonal();
        let corners = curve_corners(domain);
        for round in 0..MAX_ROUNDS {
            let attempt = build(domain, &boundary, &interior, size)?;
            let attempt = match attempt {
                Attempt::Done(t) => match finish(*t) {
                    Ok(t) => Attempt::Done(Box::new(t)),
                    Err(failing) => Attempt::Refine(failing),
                },
                other => other,
            };
            match attempt {
                Attempt::Done(t) => return Ok(t.with_counts(inserted, dropped)),
                Attempt::DropInterior(stray) => {
                    dropped += stray.len();
                    let stray: HashSet<usize> = stray.into_iter().collect();
                    interior = interior
                        .into_iter()
                        .enumerate()
                        .filter(|(i, _)| !stray.contains(i))
                        .map(|(_, p)| p)
                        .collect();
                }
                Attempt::Crosses(near) => return Err(MeshError::BoundaryCrosses { near }),
                Attempt::Refine(failing) => {
                    let near = failing.first().map(|&(j, k)| boundary[j][k].point);
                    if round + 1 == MAX_ROUNDS {
                        return Err(MeshError::NotConvertible {
                            rounds: MAX_ROUNDS,
                            failing: failing.len(),
                            near,
                        });
                    }
                    let (refined, added) = refine_loops(domain, &corners, &boundary, &failing);
                    if inserted + added > budget {
                        return Err(MeshError::InsertionLimit {
                            inserted,
                            limit: budget,
                            failing: added,
                            near: near.unwrap_or_default(),
                        });
                    }
                    inserted += added;
                    boundary = refined;
                }
            }
        }
        Err(MeshError::NotConvertible {
            rounds: MAX_ROUNDS,
            failing: 0,
            near: None,
        })
    }

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
        Ok(Self::assemble(
            domain,
            vertices,
            boundary_vertex,
            triangles,
            edges,
            arcs,
            loop_lengths,
        ))
    }

    /// A curved triangulation from parts that fit together, unchecked: every constructor of
    /// the crate ends here (the checked one for parts read from a file is
    /// [`CurvedTriangulation::from_parts`]). The callers keep its invariants: triangles
    /// counter-clockwise with vertex indices in range, `boundary_vertex` one entry per vertex,
    /// `edges` one entry per triangle, edge `k` of triangle `t` is `Curved(i)` exactly when arc
    /// `i` joins that edge's vertices and names `t`, and `loop_lengths` counts the arcs of each
    /// loop, listed loop by loop in loop order. Not a refinement, no boundary point inserted,
    /// no interior point dropped (see [`CurvedTriangulation::into_refinement`] and
    /// [`CurvedTriangulation::with_counts`]).
    pub(crate) fn assemble(
        domain: Domain,
        vertices: Vec<Point>,
        boundary_vertex: Vec<Option<BoundaryPoint>>,
        triangles: Vec<[usize; 3]>,
        edges: Vec<[EdgeKind; 3]>,
        arcs: Vec<BoundaryArc>,
        loop_lengths: Vec<usize>,
    ) -> Self {
        Self {
            domain,
            vertices,
            boundary_vertex,
            triangles,
            edges,
            arcs,
            loop_lengths,
            refinement: None,
            inserted_boundary_points: 0,
            dropped_interior_points: 0,
        }
    }

    /// This triangulation marked as the refinement `how` of another, `parent[t]` the triangle
    /// of the unrefined triangulation that triangle `t` lies in.
    pub(crate) fn into_refinement(mut self, how: Refinement, parent: Vec<usize>) -> Self {
        self.refinement = Some((how, parent));
        self
    }

    /// This triangulation with the counts of boundary points inserted and interior points
    /// dropped while building it.
    pub(crate) fn with_counts(mut self, inserted: usize, dropped: usize) -> Self {
        self.inserted_boundary_points = inserted;
        self.dropped_interior_points = dropped;
        self
    }

    /// The domain.
    pub fn domain(&self) -> &Domain {
        &self.domain
    }

    /// Vertex coordinates.
    pub fn vertices(&self) -> &[Point] {
        &self.vertices
    }

    /// For each vertex: where it lies on the boundary, or `None` for an interior vertex.
    pub fn boundary_vertex(&self, v: usize) -> Option<&BoundaryPoint> {
        self.boundary_vertex[v].as_ref()
    }

    /// Triangles as counter-clockwise vertex triples (the companion triangles).
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.triangles
    }

    /// Kinds of the three edges of triangle `t`; edge `k` joins vertex `k` to vertex `k + 1`.
    pub fn edge_kinds(&self, t: usize) -> [EdgeKind; 3] {
        self.edges[t]
    }

    /// The boundary arcs (one per boundary edge of the inscribed triangulation).
    pub fn arcs(&self) -> &[BoundaryArc] {
        &self.arcs
    }

    /// For each vertex: where it lies on the boundary, or `None` for an interior vertex.
    pub(crate) fn boundary_vertices(&self) -> &[Option<BoundaryPoint>] {
        &self.boundary_vertex
    }

    /// Number of boundary vertices of each loop, in loop order (see
    /// [`CurvedTriangulation::arc_position`]).
    pub(crate) fn loop_lengths(&self) -> &[usize] {
        &self.loop_lengths
    }

    /// For a refinement: how it was refined.
    pub fn refinement(&self) -> Option<Refinement> {
        self.refinement.as_ref().map(|r| r.0)
    }

    /// For a refinement: the triangle of the unrefined triangulation that triangle `t` lies in
    /// (the sub-triangles of one are consecutive: 3 for Clough–Tocher, 6 for Powell–Sabin).
    pub fn parent_triangle(&self, t: usize) -> Option<usize> {
        self.refinement.as_ref().map(|r| r.1[t])
    }

    /// The place `(loop, k)` of arc `i` in its loop: it joins the `k`-th and `(k+1)`-th
    /// boundary vertices of that loop.
    pub(crate) fn arc_position(&self, i: usize) -> (usize, usize) {
        let mut k = i;
        for (j, &n) in self.loop_lengths.iter().enumerate() {
            if k < n {
                return (j, k);
            }
            k -= n;
        }
        (self.loop_lengths.len().saturating_sub(1), k)
    }

    /// Boundary points inserted to make the triangulation convertible.
    pub fn inserted_boundary_points(&self) -> usize {
        self.inserted_boundary_points
    }

    /// Interior points dropped because they lay between a boundary arc and its chord.
    pub fn dropped_interior_points(&self) -> usize {
        self.dropped_interior_points
    }

    /// The curve piece of an arc as its own NURBS, oriented from `from` to `to`.
    ///
    /// # Errors
    /// [`MeshError::Spline`] if the parameters fall outside the curve (never for arcs built
    /// here).
    pub fn arc_curve(&self, arc: &BoundaryArc) -> Result<NurbsCurve, MeshError> {
        Ok(self.domain.curves()[arc.curve].subsegment((arc.u0, arc.u1))?)
    }

    /// Signed area of curved triangle `t` by Green's theorem, `1/2 closed-integral(x dy - y dx)`:
    /// the shoelace terms for straight edges, adaptive Gauss-Legendre on each knot span of a
    /// curved edge (orientation taken from the triangle).
    pub fn triangle_area(&self, t: usize) -> f64 {
        let tri = self.triangles[t];
        let mut area = 0.0;
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            match self.edges[t][k] {
                EdgeKind::Straight => {
                    area += 0.5 * self.vertices[a].cross(self.vertices[b]);
                }
                EdgeKind::Curved(i) => {
                    let arc = &self.arcs[i];
                    let c = &self.domain.curves()[arc.curve];
                    let sign = if arc.from == a { 1.0 } else { -1.0 };
                    area += sign * c.area_integral_on(arc.u0, arc.u1).value;
                }
            }
        }
        area
    }
}

/// Boundary points grouped by their loop, every curve's start added if missing, sorted along
/// the loop (so each arc between consecutive points lies on one curve).
fn normalized_loops(domain: &Domain, given: &[Vec<BoundaryPoint>]) -> Vec<Vec<BoundaryPoint>> {
    let mut loops: Vec<Vec<BoundaryPoint>> = vec![Vec::new(); domain.loops().len()];
    for bp in given.iter().flatten() {
        if let Some(l) = loops.get_mut(bp.loop_index) {
            l.push(*bp);
        }
    }
    for (j, l) in domain.loops().iter().enumerate() {
        for ci in l.curves() {
            let c = &domain.curves()[ci];
            let u = c.param_range().0;
            if !loops[j].iter().any(|b| b.curve == ci && b.u == u) {
                loops[j].push(BoundaryPoint {
                    loop_index: j,
                    curve: ci,
                    u,
                    point: c.start_point(),
                });
            }
        }
        loops[j].sort_by(|a, b| a.curve.cmp(&b.curve).then(a.u.total_cmp(&b.u)));
        loops[j].dedup_by(|a, b| a.curve == b.curve && a.u == b.u);
    }
    loops
}

/// The most vertices a curved triangulation is built with (about 1 GB of triangulation data).
pub const MAX_MESH_VERTICES: usize = 2_000_000;

/// The most Bezier pieces a boundary to be meshed or sampled by lines may have: every piece
/// gets an arc-length table (about 0.25 ms each) and its start is a vertex, so 10^4 pieces
/// take a few seconds and a 10^6-command SVG path would take minutes.
pub const MAX_MESH_PIECES: usize = 10_000;

/// Refuses, before any work, a boundary of more than [`MAX_MESH_PIECES`] Bezier pieces.
///
/// # Errors
/// [`MeshError::TooManyPieces`].
pub fn check_boundary_pieces(domain: &Domain) -> Result<(), MeshError> {
    let pieces: usize = domain
        .curves()
        .iter()
        .map(|c| c.knots().interior_breaks().len() + 1)
        .sum();
    if pieces > MAX_MESH_PIECES {
        return Err(MeshError::TooManyPieces {
            pieces,
            limit: MAX_MESH_PIECES,
        });
    }
    Ok(())
}

enum Attempt {
    Done(Box<CurvedTriangulation>),
    /// Interior points (indices) lying outside every kept triangle.
    DropInterior(Vec<usize>),
    /// Arcs (loop, index of the arc's first point in the loop) to split.
    Refine(Vec<(usize, usize)>),
    /// Two boundary arcs certainly cross near this point.
    Crosses(Point),
}

/// One attempt at the curved triangulation (paper Algorithm 4.1): constrained Delaunay
/// triangulation of the boundary chords, interior points added, the faces inside the chord
/// loops kept, and every chord replaced by its arc if the arc meets no other edge. Says which
/// chords to split or which interior points to drop when that fails.
fn build(
    domain: &Domain,
    boundary: &[Vec<BoundaryPoint>],
    interior: &[Point],
    size: f64,
) -> Result<Attempt, MeshError> {
    let (mut cdt, mut v, loop_vertices) = Vertices::load_boundary(boundary)?;
    let (failing, crossing) = constrain_chords(&mut cdt, &v, &loop_vertices);
    if !failing.is_empty() {
        for (c, d) in crossing {
            let arc = |(j, k): (usize, usize)| {
                let l = &boundary[j];
                chord_arc(domain, &l[k], &l[(k + 1) % l.len()])
            };
            if let Some(x) = where_arcs_meet(arc(c)?, arc(d)?, size) {
                return Ok(Attempt::Crosses(x));
            }
        }
        return Ok(Attempt::Refine(failing));
    }
    let interior_vertex = interior
        .iter()
        .map(|&p| v.insert(&mut cdt, p, None))
        .collect::<Result<Vec<_>, _>>()?;
    let inside = faces_inside(&cdt);
    let mut triangles = Vec::new();
    for f in cdt.inner_faces() {
        if inside.get(&f.fix().index()).copied().unwrap_or(false) {
            triangles.push(f.vertices().map(|h| v.index[&h.fix()]));
        }
    }
    let stray = stray_interior(&triangles, &interior_vertex, v.points.len());
    if !stray.is_empty() {
        return Ok(Attempt::DropInterior(stray));
    }
    let (arcs, edges, failing) = attach_arcs(domain, &v, &loop_vertices, &triangles, size)?;
    if !failing.is_empty() {
        return Ok(Attempt::Refine(failing));
    }
    Ok(Attempt::Done(Box::new(CurvedTriangulation::assemble(
        domain.clone(),
        v.points,
        v.boundary,
        triangles,
        edges,
        arcs,
        loop_vertices.iter().map(Vec::len).collect(),
    ))))
}
