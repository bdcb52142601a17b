//! The construction of a curved triangulation from sampled points (Algorithm 4.1 with the
//! convertibility check of Definition 4.2): rounds of one attempt each (constrained Delaunay
//! triangulation of the chords, interior points added, arcs attached), boundary points
//! inserted where arcs fail, until the triangulation is convertible; refined when asked. This
//! module drives the others and calls the refinement; nothing it uses calls back into it.

use rs_spline::prelude::*;
use std::collections::HashSet;

use rs_spline::{Domain, Point};
use spade::Triangulation as _;

use super::arcs::{attach_arcs, chord_arc};
use super::cdt::{Vertices, constrain_chords, faces_inside, stray_interior};
use super::crossing::{check_no_crossing, where_arcs_meet};
use super::curved::{CurvedTriangulation, Parts, Refinement};
use super::insertion::{curve_corners, refine_loops};
use super::refine::refine;
use crate::MeshError;
use crate::boundary::{BoundaryPoint, check_boundary_pieces};
use crate::limits::MAX_MESH_VERTICES;
use crate::sample::WellSpacedPoints;

/// Rounds of boundary point insertion tried before giving up.
const MAX_ROUNDS: usize = 16;
/// Boundary points that insertion may add per initial boundary point (see
/// [`CurvedTriangulation::new`]); the domains of the tests need at most 4.
pub const MAX_INSERTED_PER_POINT: usize = 16;
/// Boundary points that insertion may add beyond [`MAX_INSERTED_PER_POINT`] per initial one.
pub const MAX_INSERTED_EXTRA: usize = 4096;

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
    /// [`MeshError::TooManyPieces`] for a boundary of more than [`crate::MAX_MESH_PIECES`]
    /// Bezier pieces, [`MeshError::NotConvertible`] if 16 rounds of insertion do not suffice,
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
        check_no_crossing(domain)?;
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

/// The outcome of one attempt ([`build`]).
enum Attempt {
    /// A convertible triangulation.
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
        Parts {
            domain: domain.clone(),
            vertices: v.points,
            boundary_vertex: v.boundary,
            triangles,
            edges,
            arcs,
            loop_lengths: loop_vertices.iter().map(Vec::len).collect(),
        },
    ))))
}
