//! The curved triangulation: its edges, its boundary arcs, how it was refined, and what can
//! be read from it. Its fields are private to this module: every constructor goes through
//! [`CurvedTriangulation::assemble`] (from its [`Parts`]) and every reader through the accessors, so the modules
//! that build or refine a triangulation depend on this one and never the reverse.

use rs_spline::prelude::*;
use rs_spline::{Domain, NurbsCurve, Point};

use crate::MeshError;
use crate::boundary::BoundaryPoint;

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

    /// The refinement named `name`, or `None` for `none` (the triangulation itself): the
    /// choices of `inrs mesh --refine` and of the Python package's `refine`.
    ///
    /// # Errors
    /// A one-line message naming the choices (`none`, `ct` or `ps`).
    pub fn parse_optional(name: &str) -> Result<Option<Self>, String> {
        if name.eq_ignore_ascii_case("none") {
            return Ok(None);
        }
        name.parse()
            .map(Some)
            .map_err(|_| format!("unknown refinement {name:?} (expected none, ct or ps)"))
    }
}

impl std::str::FromStr for Refinement {
    type Err = String;

    /// `ct` (or `clough-tocher`) and `ps` (or `powell-sabin`), in any case; see
    /// [`Refinement::parse_optional`] for `none`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "ct" | "clough-tocher" => Ok(Self::CloughTocher),
            "ps" | "powell-sabin" => Ok(Self::PowellSabin),
            _ => Err(format!("unknown refinement {s:?} (expected ct or ps)")),
        }
    }
}

/// A curved triangulation of a domain (Definition 3.2) with straight interior edges: an
/// inscribed constrained Delaunay triangulation whose boundary edges are replaced by the
/// boundary arcs they cut off (Algorithm 4.1), or a Clough–Tocher or Powell–Sabin refinement
/// of one ([`CurvedTriangulation::new_refined`]).
#[derive(Clone, Debug)]
pub struct CurvedTriangulation {
    parts: Parts,
    /// For a refinement: how, and the triangle of the unrefined triangulation each triangle
    /// lies in.
    refinement: Option<(Refinement, Vec<usize>)>,
    inserted_boundary_points: usize,
    dropped_interior_points: usize,
}

/// What a curved triangulation is made of, as its builders hand it to
/// [`CurvedTriangulation::assemble`]. The builders keep its invariants: triangles
/// counter-clockwise with vertex indices in range, `boundary_vertex` one entry per vertex,
/// `edges` one entry per triangle, edge `k` of triangle `t` `Curved(i)` exactly when arc `i`
/// joins that edge's vertices and names `t`, and `loop_lengths` the number of boundary
/// vertices of each loop, which places arcs listed loop by loop
/// ([`CurvedTriangulation::arc_position`]; a refinement keeps the unrefined one's).
#[derive(Clone, Debug)]
pub(crate) struct Parts {
    pub(crate) domain: Domain,
    pub(crate) vertices: Vec<Point>,
    pub(crate) boundary_vertex: Vec<Option<BoundaryPoint>>,
    pub(crate) triangles: Vec<[usize; 3]>,
    pub(crate) edges: Vec<[EdgeKind; 3]>,
    pub(crate) arcs: Vec<BoundaryArc>,
    /// Number of boundary vertices of each loop (arc `i` joins the `k`-th and `(k+1)`-th
    /// vertices of its loop, arcs listed loop by loop in that order).
    pub(crate) loop_lengths: Vec<usize>,
}

impl CurvedTriangulation {
    /// A curved triangulation from parts that fit together (the [`Parts`] invariants),
    /// unchecked: every constructor of the crate ends here (the checked one for parts read
    /// from a file is [`CurvedTriangulation::from_parts`]). Not a refinement, no boundary
    /// point inserted, no interior point dropped (see
    /// [`CurvedTriangulation::into_refinement`] and [`CurvedTriangulation::with_counts`]).
    pub(crate) fn assemble(parts: Parts) -> Self {
        Self {
            parts,
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
        &self.parts.domain
    }

    /// Vertex coordinates.
    pub fn vertices(&self) -> &[Point] {
        &self.parts.vertices
    }

    /// For each vertex: where it lies on the boundary, or `None` for an interior vertex.
    pub fn boundary_vertex(&self, v: usize) -> Option<&BoundaryPoint> {
        self.parts.boundary_vertex[v].as_ref()
    }

    /// Triangles as counter-clockwise vertex triples (the companion triangles).
    pub fn triangles(&self) -> &[[usize; 3]] {
        &self.parts.triangles
    }

    /// Kinds of the three edges of triangle `t`; edge `k` joins vertex `k` to vertex `k + 1`.
    pub fn edge_kinds(&self, t: usize) -> [EdgeKind; 3] {
        self.parts.edges[t]
    }

    /// The boundary arcs (one per boundary edge of the inscribed triangulation).
    pub fn arcs(&self) -> &[BoundaryArc] {
        &self.parts.arcs
    }

    /// For each vertex: where it lies on the boundary, or `None` for an interior vertex.
    pub(crate) fn boundary_vertices(&self) -> &[Option<BoundaryPoint>] {
        &self.parts.boundary_vertex
    }

    /// Number of boundary vertices of each loop, in loop order (see
    /// [`CurvedTriangulation::arc_position`]).
    pub(crate) fn loop_lengths(&self) -> &[usize] {
        &self.parts.loop_lengths
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
        for (j, &n) in self.parts.loop_lengths.iter().enumerate() {
            if k < n {
                return (j, k);
            }
            k -= n;
        }
        (self.parts.loop_lengths.len().saturating_sub(1), k)
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
        Ok(self.parts.domain.curves()[arc.curve].subsegment((arc.u0, arc.u1))?)
    }

    /// Signed area of curved triangle `t` by Green's theorem, `1/2 closed-integral(x dy - y dx)`:
    /// the shoelace terms for straight edges, adaptive Gauss-Legendre on each knot span of a
    /// curved edge (orientation taken from the triangle).
    pub fn triangle_area(&self, t: usize) -> f64 {
        let tri = self.parts.triangles[t];
        let mut area = 0.0;
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            match self.parts.edges[t][k] {
                EdgeKind::Straight => {
                    area += 0.5 * self.parts.vertices[a].cross(self.parts.vertices[b]);
                }
                EdgeKind::Curved(i) => {
                    let arc = &self.parts.arcs[i];
                    let c = &self.parts.domain.curves()[arc.curve];
                    let sign = if arc.from == a { 1.0 } else { -1.0 };
                    area += sign * c.area_integral_on(arc.u0, arc.u1).value;
                }
            }
        }
        area
    }
}
