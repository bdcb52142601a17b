//! Inscribed triangulations (constrained Delaunay, by `spade`), the convertibility check of
//! Definition 4.2 with automatic boundary point insertion, and the curved triangulation of
//! Algorithm 4.1.

use rs_spline::prelude::*;
use std::collections::{HashMap, HashSet, VecDeque};

use rs_roots::{Bernstein, bernstein_roots};
use rs_spline::grid::{CellIndex, GridFrame};
use rs_spline::{BoundingBox, Domain, NurbsCurve, Point, RationalBezier, SplineError};
use spade::handles::FixedVertexHandle;
use spade::{
    ConstrainedDelaunayTriangulation, Intersection, LineIntersectionIterator, Point2,
    Triangulation as _,
};

use crate::MeshError;
use crate::boundary::BoundaryPoint;
use crate::sample::WellSpacedPoints;

mod refine;

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

/// A boundary chord (arc): its loop and the index of its first point in the loop.
type Chord = (usize, usize);

enum Attempt {
    Done(Box<CurvedTriangulation>),
    /// Interior points (indices) lying outside every kept triangle.
    DropInterior(Vec<usize>),
    /// Arcs (loop, index of the arc's first point in the loop) to split.
    Refine(Vec<(usize, usize)>),
    /// Two boundary arcs certainly cross near this point.
    Crosses(Point),
}

fn p2(p: Point) -> Point2<f64> {
    Point2::new(p.x, p.y)
}

/// The constrained Delaunay triangulation of the inscribed polygon.
type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// The vertices inserted so far: coordinates, boundary data, and spade's handle of each.
#[derive(Default)]
struct Vertices {
    points: Vec<Point>,
    boundary: Vec<Option<BoundaryPoint>>,
    index: HashMap<FixedVertexHandle, usize>,
}

impl Vertices {
    /// The triangulation of the boundary points (`boundary`'s loops in order) and the
    /// vertex index of each point by loop, numbered in loop order as [`Vertices::register`]
    /// numbers them. The points go in in a shuffled order (a fixed seed: the same mesh every
    /// run), each located from its nearest loop neighbour inserted before it: randomised
    /// insertion changes the triangulation by `O(n)` edges in all, whatever the shape, where
    /// loop order cost a flip of every edge back to the loop's start per point on a long, thin
    /// domain (quadratic: 3.4 s for the 30 000 points of a 3000 x 1 rectangle at ny 5, minutes
    /// for 77 000). The nearest inserted neighbour is a walk of expected `n / k` indices for
    /// the `k`-th point: `O(n log n)` in all, and so is the location from it.
    fn load_boundary(
        boundary: &[Vec<BoundaryPoint>],
    ) -> Result<(Cdt, Self, Vec<Vec<usize>>), MeshError> {
        let points: Vec<Point> = boundary.iter().flatten().map(|bp| bp.point).collect();
        let mut cdt = Cdt::default();
        let mut handles: Vec<Option<FixedVertexHandle>> = vec![None; points.len()];
        for i in shuffled(points.len()) {
            let hint = handles[..i]
                .iter()
                .rev()
                .chain(handles[i..].iter())
                .find_map(|h| *h);
            let p = p2(points[i]);
            let h = match hint {
                Some(hint) => cdt.insert_with_hint(p, hint),
                None => cdt.insert(p),
            }
            .map_err(insertion_error)?;
            handles[i] = Some(h);
        }
        let mut v = Self::default();
        let mut handles = handles.into_iter().flatten();
        let loops = boundary
            .iter()
            .map(|l| {
                l.iter()
                    .zip(&mut handles)
                    .map(|(bp, h)| v.register(h, bp.point, Some(*bp)))
                    .collect()
            })
            .collect();
        Ok((cdt, v, loops))
    }

    /// Inserts `p` (a repeated position keeps its first index); returns its index.
    fn insert(
        &mut self,
        cdt: &mut Cdt,
        p: Point,
        boundary: Option<BoundaryPoint>,
    ) -> Result<usize, MeshError> {
        let h = cdt.insert(p2(p)).map_err(insertion_error)?;
        Ok(self.register(h, p, boundary))
    }

    /// The index of the vertex of handle `h` at `p`: the next index the first time, the first
    /// one's after (the triangulation gives a repeated position the handle it gave it first).
    fn register(
        &mut self,
        h: FixedVertexHandle,
        p: Point,
        boundary: Option<BoundaryPoint>,
    ) -> usize {
        *self.index.entry(h).or_insert_with(|| {
            self.points.push(p);
            self.boundary.push(boundary);
            self.points.len() - 1
        })
    }
}

/// `0..n` in a shuffled order, the same for every call (Fisher–Yates with a fixed xorshift
/// seed).
fn shuffled(n: usize) -> Vec<usize> {
    let mut order: Vec<usize> = (0..n).collect();
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    for i in (1..n).rev() {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        order.swap(i, (state % (i as u64 + 1)) as usize);
    }
    order
}

/// spade's insertion errors in words.
fn insertion_error(e: spade::InsertionError) -> MeshError {
    MeshError::Triangulation(
        match e {
            spade::InsertionError::TooLarge => {
                "a vertex coordinate is beyond the triangulator's range (|x| <= 3.2e60): meshing needs smaller coordinates"
            }
            spade::InsertionError::TooSmall => {
                "a nonzero vertex coordinate is below the triangulator's range (|x| >= 1.8e-43): meshing needs larger coordinates"
            }
            spade::InsertionError::NAN => "a vertex coordinate is NaN",
        }
        .to_string(),
    )
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

/// Adds every boundary chord as a constraint; returns the chords (loop, index in the loop)
/// that cannot be added, those already added that they cross, and chords that share an edge
/// (each once): all of them must be split; and the pairs of chords found crossing. The
/// crossed chords are found from the constraint edges the triangulation reports between the
/// chord's ends (a walk along the chord), each edge mapped to the chord it belongs to, so the
/// work follows the chords' lengths, not their number.
fn constrain_chords(
    cdt: &mut Cdt,
    v: &Vertices,
    loops: &[Vec<usize>],
) -> (Vec<Chord>, Vec<(Chord, Chord)>) {
    let handle: HashMap<usize, FixedVertexHandle> = v.index.iter().map(|(h, i)| (*i, *h)).collect();
    // The chord each constraint edge belongs to (by its end vertices): the whole chord, or a
    // piece of it when the triangulation split it at a vertex lying on it.
    let mut owner: HashMap<(FixedVertexHandle, FixedVertexHandle), (usize, usize)> = HashMap::new();
    let key = |a: FixedVertexHandle, b: FixedVertexHandle| (a.min(b), a.max(b));
    let mut failing = Vec::new();
    let mut crossing = Vec::new();
    let mut seen = HashSet::new();
    let mut fail = |chord: (usize, usize), failing: &mut Vec<(usize, usize)>| {
        if seen.insert(chord) {
            failing.push(chord);
        }
    };
    for (j, ids) in loops.iter().enumerate() {
        for k in 0..ids.len() {
            let (a, b) = (ids[k], ids[(k + 1) % ids.len()]);
            let (ha, hb) = (handle[&a], handle[&b]);
            if a == b {
                fail((j, k), &mut failing);
                continue;
            }
            let crossed: Vec<_> = cdt
                .get_conflicting_edges_between_vertices(ha, hb)
                .map(|e| {
                    let [p, q] = e.vertices();
                    key(p.fix(), q.fix())
                })
                .collect();
            if !crossed.is_empty() {
                fail((j, k), &mut failing);
                for e in crossed {
                    if let Some(&chord) = owner.get(&e) {
                        fail(chord, &mut failing);
                        crossing.push(((j, k), chord));
                    }
                }
                continue;
            }
            let before = cdt.num_constraints();
            cdt.add_constraint(ha, hb);
            if cdt.num_constraints() == before + 1 && cdt.exists_constraint(ha, hb) {
                owner.insert(key(ha, hb), (j, k));
                continue;
            }
            // Split at vertices lying on the chord, or along an edge constrained already: its
            // pieces are the constraint edges along it. A piece that another chord holds too
            // (the two arcs of a loop of two points share their chord; loops that overlap)
            // would count twice in the faces' crossing parity: both chords are split.
            for piece in LineIntersectionIterator::new_from_handles(cdt, ha, hb) {
                if let Intersection::EdgeOverlap(e) = piece {
                    let [p, q] = e.vertices();
                    let held = *owner.entry(key(p.fix(), q.fix())).or_insert((j, k));
                    if held != (j, k) {
                        fail(held, &mut failing);
                        fail((j, k), &mut failing);
                    }
                }
            }
        }
    }
    (failing, crossing)
}

/// Crossing parity of the constraint loops for every inner face, by flood fill from the
/// convex hull: `true` inside the domain.
fn faces_inside(cdt: &Cdt) -> HashMap<usize, bool> {
    let mut inside: HashMap<usize, bool> = HashMap::new();
    let mut queue = VecDeque::new();
    for e in cdt.convex_hull() {
        if let Some(f) = e.rev().face().as_inner() {
            let parity = cdt.is_constraint_edge(e.as_undirected().fix());
            if inside.insert(f.fix().index(), parity).is_none() {
                queue.push_back(f);
            }
        }
    }
    while let Some(f) = queue.pop_front() {
        let parity = inside[&f.fix().index()];
        for e in f.adjacent_edges() {
            if let Some(g) = e.rev().face().as_inner()
                && let std::collections::hash_map::Entry::Vacant(slot) =
                    inside.entry(g.fix().index())
            {
                slot.insert(parity ^ cdt.is_constraint_edge(e.as_undirected().fix()));
                queue.push_back(g);
            }
        }
    }
    inside
}

/// Interior points (indices into `interior_vertex`) in no kept triangle: they lie between an
/// arc and its chord.
fn stray_interior(triangles: &[[usize; 3]], interior_vertex: &[usize], n: usize) -> Vec<usize> {
    let mut used = vec![false; n];
    for t in triangles {
        for &v in t {
            used[v] = true;
        }
    }
    interior_vertex
        .iter()
        .enumerate()
        .filter(|(_, v)| !used[**v])
        .map(|(i, _)| i)
        .collect()
}

/// Arcs, edge kinds per triangle, and the chords whose arcs cannot replace them (an arc
/// meeting another edge, a chord owned by no kept triangle).
type Attached = (Vec<BoundaryArc>, Vec<[EdgeKind; 3]>, Vec<(usize, usize)>);

/// Replaces every boundary chord by its arc where the arc meets no other edge (paper
/// Definition 4.2, convertibility).
fn attach_arcs(
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
fn chord_arc(
    domain: &Domain,
    pa: &BoundaryPoint,
    pb: &BoundaryPoint,
) -> Result<NurbsCurve, SplineError> {
    domain.curves()[pa.curve].subsegment((pa.u, arc_end(domain, pa, pb)))
}

/// A point where two curves certainly meet, if their control polygons show it: each curve
/// lies in the slab of its control points round its chord (the convex hull property), each
/// one's ends lie outside the other's slab on opposite sides (by `1e-9 size`, above any
/// rounding here), so within the parallelogram where the slabs overlap one curve joins two
/// opposite sides and the other the two others, and two such paths meet. The point
/// returned, where the chords cross, lies in that parallelogram. Curves that share an end
/// are never certified (the end lies in both slabs).
fn arcs_certainly_meet(p: &NurbsCurve, q: &NurbsCurve, size: f64) -> Option<Point> {
    let margin = 1e-9 * size;
    // The unit normal of a chord, its slab's half-width, and its ends.
    let slab = |c: &NurbsCurve| {
        let pts = c.control_points();
        let (a, b) = (pts[0], pts[pts.len() - 1]);
        let len = a.distance(b);
        if len.is_nan() || len <= 0.0 {
            return None;
        }
        let n = (b - a).perp() / len;
        let half = pts.iter().fold(0.0f64, |m, &x| m.max(n.dot(x - a).abs()));
        Some((n, half + margin, a, b))
    };
    let (n1, w1, a, b) = slab(p)?;
    let (n2, w2, c, d) = slab(q)?;
    let across = |n: Point, w: f64, o: Point, x: Point, y: Point| {
        let (sx, sy) = (n.dot(x - o), n.dot(y - o));
        (sx > w && sy < -w) || (sx < -w && sy > w)
    };
    if !(across(n2, w2, c, a, b) && across(n1, w1, a, c, d)) {
        return None;
    }
    // The chords cross (their ends are on opposite sides of each other's line): where.
    let (r, s) = (b - a, d - c);
    let t = (c - a).cross(s) / r.cross(s);
    Some(a + r * t)
}

/// Halvings of two certainly meeting arcs ([`where_arcs_meet`]) to close in on where.
const MEETING_HALVINGS: usize = 40;

/// A point where two arcs certainly meet ([`arcs_certainly_meet`]), closed in on by halving
/// both and keeping a pair of halves that still certainly meets, up to
/// [`MEETING_HALVINGS`] times (until no pair is certain: the meeting point is then near a
/// half's end).
fn where_arcs_meet(p: NurbsCurve, q: NurbsCurve, size: f64) -> Option<Point> {
    let mut near = arcs_certainly_meet(&p, &q, size)?;
    let (mut p, mut q) = (p, q);
    for _ in 0..MEETING_HALVINGS {
        let (ps, qs) = (p.subdivide(), q.subdivide());
        let (ps, qs) = ([ps.0, ps.1], [qs.0, qs.1]);
        let Some((x, i, j)) = (0..4).find_map(|k| {
            let (i, j) = (k / 2, k % 2);
            arcs_certainly_meet(&ps[i], &qs[j], size).map(|x| (x, i, j))
        }) else {
            break;
        };
        near = x;
        let [p0, p1] = ps;
        let [q0, q1] = qs;
        p = if i == 0 { p0 } else { p1 };
        q = if j == 0 { q0 } else { q1 };
    }
    Some(near)
}

/// Two tangent directions whose angle has a sine above this (or that point apart) make a
/// corner: far above the rounding of a joint that is smooth in exact arithmetic, and only
/// ever used to choose where a failing arc is split, so a false corner costs one point.
const CORNER_SINE: f64 = 1e-9;

/// The parameters, ascending, of each curve's corners: the joints of consecutive Bezier
/// pieces where the tangent directions of the two pieces differ (a break point of a polygon
/// written as one curve, a knot of full multiplicity, repeated control points). A corner is
/// scale-invariant: every arc across it, however short, turns by the corner's angle, so
/// splitting such an arc at its parameter midpoint never straightens it; only a vertex at
/// the corner does.
fn curve_corners(domain: &Domain) -> Vec<Vec<f64>> {
    domain
        .curves()
        .iter()
        .map(|c| {
            let pieces = c.to_bezier();
            pieces
                .windows(2)
                .filter_map(|w| {
                    let (p, q) = (w[0].control_points(), w[1].control_points());
                    let (last, before) = p.split_last()?;
                    let (first, after) = q.split_first()?;
                    // Both directions pointing along the curve.
                    let d1 = -away(*last, before.iter().rev())?;
                    let d2 = away(*first, after.iter())?;
                    let scale = d1.length() * d2.length();
                    let corner = d1.dot(d2) <= 0.0 || d1.cross(d2).abs() > CORNER_SINE * scale;
                    corner.then_some(w[1].knot_span().0)
                })
                .collect()
        })
        .collect()
}

/// From an end point of a piece towards the first of its other control points (listed from
/// that end) that differs from it: the tangent direction there, up to sign (the lower
/// derivatives vanish where control points repeat; positive weights keep the direction).
fn away<'a>(end: Point, mut others: impl Iterator<Item = &'a Point>) -> Option<Point> {
    others.find(|&&q| q != end).map(|&q| q - end)
}

/// Where to split the failing arc `(u0, u1)` of a curve with `corners` (ascending): at the
/// corner strictly inside it nearest its parameter midpoint, else at that midpoint.
fn split_parameter(corners: &[f64], u0: f64, u1: f64) -> f64 {
    let mid = 0.5 * (u0 + u1);
    let (i, j) = (
        corners.partition_point(|&c| c <= u0),
        corners.partition_point(|&c| c < u1),
    );
    corners
        .get(i..j)
        .unwrap_or_default()
        .iter()
        .copied()
        .min_by(|a, b| (a - mid).abs().total_cmp(&(b - mid).abs()))
        .unwrap_or(mid)
}

/// New boundary points: every failing arc gets one, at a corner of the curve inside it if
/// there is one ([`curve_corners`], [`split_parameter`]), else at its parameter midpoint
/// (away from corners an arc turns less, relative to its chord, the shorter it is). Returns the refined loops and the
/// number of points added (one per distinct failing arc), in one pass over each loop.
fn refine_loops(
    domain: &Domain,
    corners: &[Vec<f64>],
    boundary: &[Vec<BoundaryPoint>],
    failing: &[(usize, usize)],
) -> (Vec<Vec<BoundaryPoint>>, usize) {
    let mut split: Vec<Vec<usize>> = vec![Vec::new(); boundary.len()];
    for &(j, k) in failing {
        split[j].push(k);
    }
    let mut added = 0;
    let out = boundary
        .iter()
        .zip(split)
        .enumerate()
        .map(|(j, (l, mut ks))| {
            ks.sort_unstable();
            ks.dedup();
            added += ks.len();
            let mut out = Vec::with_capacity(l.len() + ks.len());
            let mut ks = ks.into_iter().peekable();
            for (k, &pa) in l.iter().enumerate() {
                out.push(pa);
                if ks.next_if_eq(&k).is_none() {
                    continue;
                }
                let pb = l[(k + 1) % l.len()];
                let c = &domain.curves()[pa.curve];
                let u1 = if pb.curve == pa.curve && pb.u > pa.u {
                    pb.u
                } else {
                    c.param_range().1
                };
                let u = split_parameter(&corners[pa.curve], pa.u, u1);
                out.push(BoundaryPoint {
                    loop_index: j,
                    curve: pa.curve,
                    u,
                    point: c.point_at(u),
                });
            }
            out
        })
        .collect();
    (out, added)
}

/// An arc whose control points lie within this (relative to its chord length and the domain
/// size) of its chord is straight: it cannot leave its chord's triangle.
const STRAIGHT_ARC: f64 = 1e-13;
/// A crossing within this fraction of the domain size of a segment's end vertex is the vertex.
const AT_VERTEX: f64 = 1e-11;
/// A crossing at segment parameter `s` is on the segment for `s` in `[-ON_SEGMENT, 1 + ON_SEGMENT]`.
const ON_SEGMENT: f64 = 1e-12;
/// A piece whose signed distances to a segment's line are all below this (relative to the
/// segment's length and the domain size) lies on that line.
const ON_LINE: f64 = 1e-14;

/// True if the arc meets no edge of the triangulation other than its own chord `(a, b)`,
/// except at that edge's end points.
pub(crate) fn arc_is_clear(
    arc: &NurbsCurve,
    chord: (usize, usize),
    vertices: &[Point],
    grid: &EdgeGrid,
    size: f64,
) -> bool {
    let pieces = arc.to_bezier();
    let straight = pieces.iter().all(|b| {
        let p = b.control_points();
        let (s, e) = (p[0], p[p.len() - 1]);
        let len = e.distance(s);
        p.iter()
            .all(|q| (*q - s).cross(e - s).abs() <= STRAIGHT_ARC * len * len.max(size))
    });
    if straight && pieces.len() == 1 {
        return true;
    }
    let bbox = arc.control_bounding_box();
    let boxes: Vec<BoundingBox> = pieces.iter().map(|b| b.control_bounding_box()).collect();
    for (a, b) in grid.candidates(bbox) {
        if (a, b) == chord || (b, a) == chord {
            continue;
        }
        let (p, q) = (vertices[a], vertices[b]);
        // Where a piece can meet the segment: within its control box (the piece lies in its
        // control polygon's hull) and within the segment's box grown by what `within` accepts
        // beyond its ends (`ON_SEGMENT`) and by the rounding of the points tested (far below
        // `AT_VERTEX` of the domain). Disjoint boxes skip the root search.
        let reach = ON_SEGMENT * p.distance(q) + AT_VERTEX * size;
        let segment = BoundingBox::from_point(p).including(q).grown_by(reach);
        for (piece, piece_box) in pieces.iter().zip(&boxes) {
            if piece_box.overlaps(&segment) && crosses_inside_segment(piece, p, q, size) {
                return false;
            }
        }
    }
    true
}

/// True if the piece meets the segment `p q` at a point that is not one of `p`, `q`.
fn crosses_inside_segment(piece: &RationalBezier, p: Point, q: Point, size: f64) -> bool {
    let d = q - p;
    let len2 = d.dot(d);
    let n = d.perp();
    let coeffs: Vec<f64> = piece
        .control_points()
        .iter()
        .zip(piece.weights())
        .map(|(c, w)| w * n.dot(*c - p))
        .collect();
    let eps = AT_VERTEX * size;
    let at_end = |x: Point| x.distance(p) <= eps || x.distance(q) <= eps;
    let within = |x: Point| {
        let s = (x - p).dot(d) / len2;
        (-ON_SEGMENT..=1.0 + ON_SEGMENT).contains(&s) && !at_end(x)
    };
    let scale = coeffs.iter().fold(0.0f64, |m, c| m.max(c.abs()));
    if scale <= ON_LINE * len2.sqrt() * size {
        // The piece lies on the segment's line: test its sampled points against the segment.
        return (1..16).any(|i| within(piece.point_at(i as f64 / 16.0)));
    }
    match bernstein_roots(&Bernstein::new(coeffs)) {
        Ok(roots) => roots.into_iter().any(|t| within(piece.point_at(t))),
        // Crossings that cannot be computed cannot be ruled out: report one, so that the
        // caller inserts boundary points (or fails with NotConvertible) instead of keeping an
        // arc that might cross an edge.
        Err(_) => true,
    }
}

/// Edges registered in the cells their bounding boxes meet.
pub(crate) struct EdgeGrid {
    index: CellIndex<(usize, usize)>,
}

impl EdgeGrid {
    /// About one edge per cell, at most 65 536 cells, the cells near square (a grid of as
    /// many rows as columns over a long, thin domain registered every edge across it in every
    /// row: 867 MB for the 800 000 edges of a 10 000 x 1 rectangle).
    pub(crate) fn new(vertices: &[Point], edges: &[(usize, usize)]) -> Self {
        let bb = BoundingBox::from_points(vertices.iter().copied())
            .unwrap_or(BoundingBox::from_point(Point::new(0.0, 0.0)));
        let frame = GridFrame::near_square(bb, edges.len().clamp(1, 1 << 16));
        let mut pairs = Vec::new();
        for &(a, b) in edges {
            let eb = BoundingBox::from_point(vertices[a]).including(vertices[b]);
            frame.for_cells_in(eb, |c| pairs.push((c, (a, b))));
        }
        Self {
            index: CellIndex::new(frame, pairs),
        }
    }

    /// The distinct edges registered in the cells meeting `b`.
    fn candidates(&self, b: BoundingBox) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        self.index
            .frame()
            .for_cells_in(b, |c| out.extend_from_slice(self.index.cell(c)));
        out.sort_unstable();
        out.dedup();
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Segments and arcs that cross are certified, with the crossing found by halving;
    /// ends touching the other curve, shared ends, parallel and missing pairs are not.
    #[test]
    fn arcs_certainly_meet_only_when_their_polygons_show_it() {
        let seg = |a: (f64, f64), b: (f64, f64)| {
            rs_spline::segment(Point::new(a.0, a.1), Point::new(b.0, b.1)).unwrap()
        };
        let x = arcs_certainly_meet(
            &seg((0.0, 0.0), (2.0, 2.0)),
            &seg((0.0, 2.0), (2.0, 0.0)),
            2.0,
        );
        assert_eq!(x, Some(Point::new(1.0, 1.0)));
        // An arc of the unit circle across y = 1/2: they meet at (cos 30°, sin 30°).
        let arc = rs_spline::circle(Point::new(0.0, 0.0), 1.0)
            .unwrap()
            .subsegment((0.05, 0.11))
            .unwrap();
        assert!(arc.start_point().y < 0.5 && arc.end_point().y > 0.5);
        let line = seg((0.0, 0.5), (2.0, 0.5));
        let coarse = arcs_certainly_meet(&arc, &line, 2.0);
        let fine = where_arcs_meet(arc.clone(), line.clone(), 2.0).unwrap();
        let exact = Point::new(0.75f64.sqrt(), 0.5);
        assert!(
            coarse.is_some() && fine.distance(exact) < 1e-12,
            "{coarse:?} {fine:?}"
        );
        for (p, q) in [
            (seg((0.0, 0.0), (2.0, 2.0)), seg((2.0, 2.0), (4.0, 0.0))), // a shared end
            (seg((0.0, 0.0), (2.0, 0.0)), seg((1.0, 0.0), (1.0, 1.0))), // an end on the other
            (seg((0.0, 0.0), (2.0, 0.0)), seg((0.0, 1.0), (2.0, 1.0))), // parallel
            (seg((0.0, 0.0), (1.0, 1.0)), seg((2.0, 0.0), (3.0, -1.0))), // apart
        ] {
            assert_eq!(arcs_certainly_meet(&p, &q, 4.0), None);
            assert_eq!(where_arcs_meet(p, q, 4.0), None);
        }
        // An arc whose bulge reaches past the other's end: not certain, though it may meet.
        let bulge = rs_spline::circle(Point::new(0.0, 0.0), 1.0)
            .unwrap()
            .subsegment((0.0, 0.5))
            .unwrap();
        assert_eq!(
            arcs_certainly_meet(&bulge, &seg((0.0, 0.5), (0.0, 2.0)), 2.0),
            None
        );
    }

    /// Corners: the joints where a curve turns (a polyline's vertices, a square written as
    /// one quadratic with repeated knots and control points), not the smooth joints of a
    /// rational circle; a failing arc is split at the corner inside it nearest its midpoint,
    /// never at one of its ends, else at its midpoint.
    #[test]
    fn failing_arcs_are_split_at_their_corners() {
        let q = Point::new;
        let square = [
            q(0.0, 0.0),
            q(1.0, 0.0),
            q(1.0, 1.0),
            q(0.0, 1.0),
            q(0.0, 0.0),
        ];
        let polyline = rs_spline::polyline(&square).unwrap();
        // Each side a quadratic with its midpoint as middle control point, corners repeated.
        let mut points = Vec::new();
        for w in square.windows(2) {
            points.extend([w[0], (w[0] + w[1]) * 0.5, w[1]]);
        }
        let mut knots = vec![0.0; 3];
        for k in 1..4 {
            knots.extend([f64::from(k); 3]);
        }
        knots.extend([4.0; 3]);
        let quadratic = NurbsCurve::new(2, knots, points, None).unwrap();
        // A smooth joint between two straight pieces: not a corner.
        let straight = rs_spline::polyline(&[q(0.0, 0.0), q(1.0, 1.0), q(3.0, 3.0)]).unwrap();
        let circle = rs_spline::circle(q(0.0, 0.0), 1.0).unwrap();
        let domain = Domain::new(vec![polyline, quadratic, circle]).unwrap();
        assert_eq!(
            curve_corners(&domain),
            vec![vec![1.0, 2.0, 3.0], vec![1.0, 2.0, 3.0], vec![]]
        );
        let line = Domain::new(vec![
            straight,
            rs_spline::polyline(&[q(3.0, 3.0), q(3.0, 0.0), q(0.0, 0.0)]).unwrap(),
        ]);
        assert_eq!(curve_corners(&line.unwrap())[0], Vec::<f64>::new());
        let corners = [1.0, 2.0, 3.0];
        assert_eq!(split_parameter(&corners, 0.0, 4.0), 2.0);
        assert_eq!(split_parameter(&corners, 0.5, 2.9), 2.0);
        assert_eq!(split_parameter(&corners, 1.0, 2.0), 1.5);
        assert_eq!(split_parameter(&corners, 2.5, 2.75), 2.625);
        assert_eq!(split_parameter(&[], 0.0, 1.0), 0.5);
    }

    #[test]
    fn shuffled_is_a_fixed_permutation() {
        for n in [0, 1, 2, 7, 1000] {
            let order = shuffled(n);
            let mut sorted = order.clone();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..n).collect::<Vec<_>>());
            assert_eq!(order, shuffled(n));
        }
        // Not the identity (or any near it): 1000 points moved on average by about n / 3.
        let moved: usize = shuffled(1000)
            .iter()
            .enumerate()
            .map(|(i, &j)| i.abs_diff(j))
            .sum();
        assert!(moved > 250_000, "{moved}");
    }
}
