//! The constrained Delaunay triangulation (by `spade`) of the inscribed polygon: boundary
//! points and interior points numbered as inserted, every boundary chord a constraint (the
//! chords that cannot be one named for splitting), and the faces inside the chord loops
//! found by crossing parity.

use std::collections::{HashMap, HashSet, VecDeque};

use rs_spline::Point;
use spade::handles::FixedVertexHandle;
use spade::{
    ConstrainedDelaunayTriangulation, Intersection, LineIntersectionIterator, Point2,
    Triangulation as _,
};

use crate::MeshError;
use crate::boundary::BoundaryPoint;

/// A boundary chord (arc): its loop and the index of its first point in the loop.
pub(super) type Chord = (usize, usize);

fn p2(p: Point) -> Point2<f64> {
    Point2::new(p.x, p.y)
}

/// The constrained Delaunay triangulation of the inscribed polygon.
pub(super) type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// The vertices inserted so far: coordinates, boundary data, and spade's handle of each.
#[derive(Default)]
pub(super) struct Vertices {
    pub(super) points: Vec<Point>,
    pub(super) boundary: Vec<Option<BoundaryPoint>>,
    pub(super) index: HashMap<FixedVertexHandle, usize>,
}

impl Vertices {
    /// The triangulation of the boundary points (`boundary`'s loops in order) and the
    /// vertex index of each point by loop, numbered in loop order as [`Vertices::register`]
    /// numbers them. The points go in in a shuffled order (a fixed seed: the same mesh every
    /// run), each located from its nearest loop neighbour inserted before it: randomised
    /// insertion changes the triangulation by `O(n)` edges in all, whatever the shape, where
    /// loop order would flip every edge back to the loop's start for each point on a long,
    /// thin domain (quadratic in the points). The nearest inserted neighbour is a walk of
    /// expected `n / k` indices for the `k`-th point: `O(n log n)` in all, and so is the
    /// location from it.
    pub(super) fn load_boundary(
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
    pub(super) fn insert(
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

/// Adds every boundary chord as a constraint; returns the chords (loop, index in the loop)
/// that cannot be added, those already added that they cross, and chords that share an edge
/// (each once): all of them must be split; and the pairs of chords found crossing. The
/// crossed chords are found from the constraint edges the triangulation reports between the
/// chord's ends (a walk along the chord), each edge mapped to the chord it belongs to, so the
/// work follows the chords' lengths, not their number.
pub(super) fn constrain_chords(
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
pub(super) fn faces_inside(cdt: &Cdt) -> HashMap<usize, bool> {
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
pub(super) fn stray_interior(
    triangles: &[[usize; 3]],
    interior_vertex: &[usize],
    n: usize,
) -> Vec<usize> {
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

#[cfg(test)]
mod tests {
    use super::*;

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
