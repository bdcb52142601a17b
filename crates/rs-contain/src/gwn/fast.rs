//! Accelerated generalized winding numbers: a bounding-volume hierarchy over the pieces that
//! skips every node the query's cut cannot reach, and a subdivision hierarchy per piece built
//! on first use.

use std::sync::OnceLock;

use rs_spline::prelude::*;
use rs_spline::{Point, RationalBezier};

use smallvec::SmallVec;

use super::curve::{SubCurve, SubCurves, is_linear, is_simple_convex, refine_below, settle};
use super::sum::{BATCH, ChordSink, WindingSum};
use super::{QueryStats, WindingField};
use crate::{Locate, Location};

/// Levels of each piece's precomputed subdivision hierarchy (`2^(d+1) - 1` sub-curves).
pub const HIERARCHY_DEPTH: u32 = 6;

/// One sub-curve of a [`CurveHierarchy`], with the tests the adaptive algorithm asks of it.
#[derive(Clone, Debug)]
struct SubNode {
    curve: SubCurve,
    lo: Point,
    hi: Point,
    /// Simple and convex, with the parent's flag inherited as the adaptive algorithm does.
    convex: bool,
    linear: bool,
    children: Option<(u32, u32)>,
}

impl SubNode {
    fn new(curve: SubCurve, parent_convex: bool) -> Self {
        let p = curve.points();
        let (mut lo, mut hi) = (p[0], p[0]);
        for &x in p {
            lo = Point::new(lo.x.min(x.x), lo.y.min(x.y));
            hi = Point::new(hi.x.max(x.x), hi.y.max(x.y));
        }
        Self {
            convex: parent_convex || is_simple_convex(p),
            linear: is_linear(p),
            lo,
            hi,
            curve,
            children: None,
        }
    }
}

/// The subdivision hierarchy of one piece, computed once and shared, immutable, by all queries:
/// the first [`HIERARCHY_DEPTH`] levels of halving, each sub-curve with its control box,
/// convexity and straightness; deeper levels (queries within `2^-6` of the piece's size from
/// it) are computed on the fly.
#[derive(Clone, Debug)]
pub struct CurveHierarchy {
    nodes: Vec<SubNode>,
}

impl CurveHierarchy {
    /// Precomputes the hierarchy of `curve`.
    pub fn new(curve: &RationalBezier) -> Self {
        let mut nodes = Vec::with_capacity((2 << HIERARCHY_DEPTH) - 1);
        nodes.push(SubNode::new(SubCurve::of(curve), false));
        let mut frontier = vec![(0usize, 0u32)];
        while let Some((i, depth)) = frontier.pop() {
            if depth >= HIERARCHY_DEPTH {
                continue;
            }
            let (l, r) = nodes[i].curve.halves();
            let parent_convex = nodes[i].convex;
            let li = nodes.len();
            nodes.push(SubNode::new(l, parent_convex));
            nodes.push(SubNode::new(r, parent_convex));
            nodes[i].children = Some((li as u32, li as u32 + 1));
            frontier.push((li, depth + 1));
            frontier.push((li + 1, depth + 1));
        }
        Self { nodes }
    }
}

/// The cached sub-curves, by index in the hierarchy.
impl SubCurves for CurveHierarchy {
    type Node = u32;
    fn points<'s>(&'s self, i: &'s u32) -> &'s [Point] {
        self.nodes[*i as usize].curve.points()
    }
    fn convex(&self, i: &u32, _parent_convex: bool) -> bool {
        self.nodes[*i as usize].convex
    }
    fn linear(&self, i: &u32) -> bool {
        self.nodes[*i as usize].linear
    }
    fn outside_box(&self, i: &u32, q: Point) -> bool {
        let n = &self.nodes[*i as usize];
        q.x < n.lo.x || q.x > n.hi.x || q.y < n.lo.y || q.y > n.hi.y
    }
}

impl CurveHierarchy {
    /// The adaptive algorithm on the piece, through the cached sub-curves (handles of four
    /// bytes on the walk's stack) and on the fly past them, in the same order and with the
    /// same tests as `curve::refine` on the piece itself.
    fn refine<K: ChordSink>(&self, q: Point, sink: &mut K, stats: &mut QueryStats) {
        stats.curve_evaluations += 1;
        if self.outside_box(&0, q) {
            let p = self.points(&0);
            sink.chord(p[0], p[p.len() - 1]);
            return;
        }
        // At most one pending right half per cached level.
        let mut stack: SmallVec<[(u32, u32, bool); 16]> = SmallVec::new();
        stack.push((0, 0, false));
        while let Some((i, depth, parent_convex)) = stack.pop() {
            if depth > 0 {
                stats.curve_evaluations += 1;
            }
            let Some(convex) = settle(self, &i, q, depth, parent_convex, sink) else {
                continue;
            };
            let node = &self.nodes[i as usize];
            if let Some((l, r)) = node.children {
                stack.push((r, depth + 1, convex));
                stack.push((l, depth + 1, convex));
            } else {
                let (l, r) = node.curve.halves();
                stats.subdivisions += 1;
                refine_below(l, depth + 1, convex, q, sink, stats);
                refine_below(r, depth + 1, convex, q, sink, stats);
            }
        }
    }
}

/// Depth bound of the walk's stack: the hierarchy is balanced, so its depth is at most
/// `log2(pieces) + 1`.
const STACK: usize = 64;

/// A node of the bounding-volume hierarchy: a contiguous run of pieces in boundary order.
#[derive(Clone, Debug)]
struct BvhNode {
    lo: Point,
    hi: Point,
    /// Start of the first piece and end of the last.
    a: Point,
    b: Point,
    /// Every piece ends exactly where the next starts.
    chain: bool,
    kind: Kind,
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    Leaf(u32),
    Inner(u32, u32),
}

/// Accelerated generalized winding numbers, equal to [`WindingField`]'s up to rounding.
///
/// # Design
/// The winding number is counted as in [`WindingField`]: signed crossings of the horizontal
/// ray from `q` towards `-x` by the chords of the adaptive algorithm, plus the angle between
/// the ends of each open chain. A node whose box lies above, below or right of `q` holds no
/// crossing and is skipped; a node wholly left of `q` whose pieces form one chain from `A` to
/// `B` crosses the ray as its chord `A -> B` does (decided by two comparisons); other nodes
/// are opened, and a leaf whose box holds `q` runs the adaptive algorithm on its piece's
/// subdivision hierarchy ([`CurveHierarchy`], built the first time a query needs it and kept).
/// A query far from the boundary costs a few node tests; one near it visits the nodes along
/// its ray.
///
/// # Examples
///
/// ```
/// use rs_contain::{FastWindingField, WindingField};
/// use rs_spline::{circle, Domain, Point};
/// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let field = WindingField::new(&d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
/// let fast = FastWindingField::new(&field);
/// let q = Point::new(0.3, -0.2);
/// assert!((fast.winding_number(q) - field.winding_number(q)).abs() < 1e-14);
/// ```
#[derive(Clone, Debug)]
pub struct FastWindingField<'a> {
    field: &'a WindingField,
    nodes: Vec<BvhNode>,
    /// The leaves in boundary order when there are at most [`SCAN_PIECES`] of them (then a
    /// query scans them instead of walking the tree); empty otherwise.
    scan: Vec<u32>,
    hierarchies: Vec<OnceLock<CurveHierarchy>>,
}

/// Up to this many pieces a query tests every leaf in turn: the inner nodes of so small a tree
/// hold nearly every query, so the walk only adds their tests and the stack's traffic.
const SCAN_PIECES: usize = 8;

impl<'a> FastWindingField<'a> {
    /// Builds the hierarchy over `field`'s pieces (`O(n log n)` box merges; the pieces'
    /// subdivision hierarchies are built later, as queries reach them).
    pub fn new(field: &'a WindingField) -> Self {
        let pieces = field.pieces();
        let mut nodes = Vec::with_capacity(2 * pieces.len());
        if !pieces.is_empty() {
            build(pieces, 0, pieces.len(), &mut nodes);
        }
        let scan = if pieces.len() <= SCAN_PIECES {
            (0..nodes.len() as u32)
                .filter(|&i| matches!(nodes[i as usize].kind, Kind::Leaf(_)))
                .collect()
        } else {
            Vec::new()
        };
        Self {
            field,
            nodes,
            scan,
            hierarchies: pieces.iter().map(|_| OnceLock::new()).collect(),
        }
    }

    /// The generalized winding number at `q`.
    pub fn winding_number(&self, q: Point) -> f64 {
        self.winding_number_counted(q, &mut QueryStats::default())
    }

    /// The generalized winding number at `q`, adding the work done to `stats` (a node decided
    /// by its chord counts as one curve evaluation).
    pub fn winding_number_counted(&self, q: Point, stats: &mut QueryStats) -> f64 {
        let mut sum = self.crossing_sum(q, &mut [0; STACK], stats);
        self.field
            .add_open_chain_ends(std::slice::from_mut(&mut sum));
        sum.value()
    }

    /// The crossings and coincident pieces at `q`, without the open chains' ends; `stack` is
    /// scratch for the walk (a caller answering many points passes the same one: zeroing it
    /// per point was 3% of a query on small shapes).
    fn crossing_sum(
        &self,
        q: Point,
        stack: &mut [u32; STACK],
        stats: &mut QueryStats,
    ) -> WindingSum {
        let mut sum = WindingSum::new(q);
        for &i in &self.scan {
            self.visit(i, q, &mut sum, stats);
        }
        // Depth-first, left child first: at most one pending right child per level, and the
        // tree is balanced (depth at most log2(pieces) + 1 < STACK).
        let mut len = 0;
        if self.scan.is_empty() && !self.nodes.is_empty() {
            stack[0] = self.nodes.len() as u32 - 1;
            len = 1;
        }
        while len > 0 {
            len -= 1;
            if let Some((l, r)) = self.visit(stack[len], q, &mut sum, stats) {
                stack[len] = r;
                stack[len + 1] = l;
                len += 2;
            }
        }
        sum
    }

    /// Adds to `sum` what node `i` holds for `q` when that takes no look inside it (nothing if
    /// its box lies above, below or right of `q`; its chord's crossing if it is one chain left
    /// of `q`), or runs the adaptive algorithm on a leaf; returns an inner node's children
    /// otherwise.
    #[inline(always)]
    fn visit(
        &self,
        i: u32,
        q: Point,
        sum: &mut WindingSum,
        stats: &mut QueryStats,
    ) -> Option<(u32, u32)> {
        let n = &self.nodes[i as usize];
        if q.y < n.lo.y || q.y > n.hi.y || q.x < n.lo.x {
            return None;
        }
        if q.x > n.hi.x && n.chain {
            stats.curve_evaluations += 1;
            sum.left_crossing(n.a, n.b);
            return None;
        }
        match n.kind {
            Kind::Leaf(p) => {
                let h = self.hierarchy(p as usize);
                h.refine(q, sum, stats);
                None
            }
            Kind::Inner(l, r) => Some((l, r)),
        }
    }

    /// The subdivision hierarchy of piece `p`, built on first use.
    fn hierarchy(&self, p: usize) -> &CurveHierarchy {
        self.hierarchies[p].get_or_init(|| CurveHierarchy::new(&self.field.pieces()[p]))
    }

    /// Winding numbers of many points, in input order, on the current thread: each equal to
    /// [`FastWindingField::winding_number`]'s (see
    /// [`FastWindingField::winding_numbers_indexed_into`]).
    pub fn winding_numbers(&self, points: &[Point]) -> Vec<f64> {
        let mut out = vec![0.0; points.len()];
        self.winding_numbers_indexed_into(|i| points[i], &mut out);
        out
    }

    /// The winding numbers of the points `point(0), point(1), ...` written to `out`, for points
    /// held in any layout, without copying them: each equal to
    /// [`FastWindingField::winding_number`]'s. The open chains' ends are added for
    /// eight points at a time (one pass over the chains, each step done for the eight at
    /// once), which on shapes of many open curves takes about half the time of one point at a
    /// time.
    pub fn winding_numbers_indexed_into(&self, point: impl Fn(usize) -> Point, out: &mut [f64]) {
        let mut stats = QueryStats::default();
        let mut sums = [WindingSum::new(Point::default()); BATCH];
        let mut stack = [0; STACK];
        for (g, group) in out.chunks_mut(BATCH).enumerate() {
            let sums = &mut sums[..group.len()];
            for (k, sum) in sums.iter_mut().enumerate() {
                *sum = self.crossing_sum(point(g * BATCH + k), &mut stack, &mut stats);
            }
            self.field.add_open_chain_ends(sums);
            for (o, sum) in group.iter_mut().zip(sums.iter()) {
                *o = sum.value();
            }
        }
    }

    /// Winding numbers of many points, split over rayon's thread pool (with the `parallel`
    /// feature, on by default; otherwise on the current thread).
    pub fn winding_numbers_parallel(&self, points: &[Point]) -> Vec<f64> {
        let mut out = vec![0.0; points.len()];
        self.winding_numbers_indexed_parallel_into(|i| points[i], &mut out);
        out
    }

    /// [`FastWindingField::winding_numbers_indexed_into`] on chunks of 4096 points spread over
    /// rayon's pool (with the `parallel` feature; otherwise on the current thread).
    pub fn winding_numbers_indexed_parallel_into(
        &self,
        point: impl Fn(usize) -> Point + Sync,
        out: &mut [f64],
    ) {
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            const TASK: usize = 4096;
            out.par_chunks_mut(TASK)
                .enumerate()
                .for_each(|(c, o)| self.winding_numbers_indexed_into(|i| point(c * TASK + i), o));
        }
        #[cfg(not(feature = "parallel"))]
        self.winding_numbers_indexed_into(point, out);
    }
}

impl Locate for FastWindingField<'_> {
    /// As the [`WindingField`]'s [`Locate`], with its fill rule, from the fast winding number.
    fn locate(&self, q: Point) -> Location {
        self.location(q, || self.winding_number(q))
    }

    /// See [`FastWindingField::locate_indexed_into`].
    fn locate_all(&self, points: &[Point]) -> Vec<Location> {
        let mut out = vec![Location::Outside; points.len()];
        self.locate_indexed_into(|i| points[i], &mut out);
        out
    }
}

impl FastWindingField<'_> {
    /// The locations of the points `point(0), point(1), ...` written to `out`, each as
    /// [`Locate::locate`] gives it, the winding numbers computed together
    /// ([`FastWindingField::winding_numbers_indexed_into`]).
    pub fn locate_indexed_into(&self, point: impl Fn(usize) -> Point, out: &mut [Location]) {
        const CHUNK: usize = 256;
        let mut w = [0.0; CHUNK];
        for (c, out) in out.chunks_mut(CHUNK).enumerate() {
            let w = &mut w[..out.len()];
            self.winding_numbers_indexed_into(|i| point(c * CHUNK + i), w);
            for (i, (o, &w)) in out.iter_mut().zip(w.iter()).enumerate() {
                *o = self.location(point(c * CHUNK + i), || w);
            }
        }
    }

    /// The location of `q`, from its winding number `w()` unless `q` is on the boundary.
    fn location(&self, q: Point, w: impl FnOnce() -> f64) -> Location {
        if self.field.is_on_boundary(q) {
            return Location::Boundary;
        }
        self.field
            .location_from_winding(w(), self.field.fill_rule())
    }
}

/// Builds the subtree over pieces `[i, j)`; returns its index (children before parents).
fn build(pieces: &[RationalBezier], i: usize, j: usize, nodes: &mut Vec<BvhNode>) -> u32 {
    let (a, b) = (pieces[i].start_point(), pieces[j - 1].end_point());
    let (kind, lo, hi, chain) = if j - i == 1 {
        let p = pieces[i].control_points();
        let (mut lo, mut hi) = (p[0], p[0]);
        for &x in p {
            lo = Point::new(lo.x.min(x.x), lo.y.min(x.y));
            hi = Point::new(hi.x.max(x.x), hi.y.max(x.y));
        }
        (Kind::Leaf(i as u32), lo, hi, true)
    } else {
        let m = (i + j) / 2;
        let (l, r) = (build(pieces, i, m, nodes), build(pieces, m, j, nodes));
        let (ln, rn) = (&nodes[l as usize], &nodes[r as usize]);
        let chain = ln.chain && rn.chain && ln.b == rn.a;
        let lo = Point::new(ln.lo.x.min(rn.lo.x), ln.lo.y.min(rn.lo.y));
        let hi = Point::new(ln.hi.x.max(rn.hi.x), ln.hi.y.max(rn.hi.y));
        (Kind::Inner(l, r), lo, hi, chain)
    };
    nodes.push(BvhNode {
        lo,
        hi,
        a,
        b,
        chain,
        kind,
    });
    nodes.len() as u32 - 1
}
