//! Accelerated generalized winding numbers: a bounding-volume hierarchy over the pieces that
//! skips every node the query's cut cannot reach, and a subdivision hierarchy per piece built
//! on first use.

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use rs_spline::prelude::*;
use rs_spline::{Point, RationalBezier};

use smallvec::SmallVec;

use super::curve::{
    Halve, Outside, Pending, SMALL, SmallPolynomial, SubCurve, SubCurves, control_box, is_linear,
    is_simple_convex, misses_cut, outside_box_reach, polygon_area, refine_below,
    refine_below_small, settle, settle_by_root,
};
use super::far_cells::FarCells;
use super::monotone::{RootCrossing, monotone_crossing};
use super::span_rows::{Leaf, SpanRows};
use super::sum::{BATCH, ChordSink, CrossingSum, WindingSum};
use super::{QueryStats, WindingField};
use crate::locality::locality_order;
use crate::rows::Rows;
use crate::{Location, PointQuery, PointSource};

/// Levels of each piece's precomputed subdivision hierarchy (`2^(d+1) - 1` sub-curves).
pub const HIERARCHY_DEPTH: u32 = 6;

/// What the adaptive algorithm reads of every sub-curve of a [`CurveHierarchy`] it visits:
/// the control box, for the test that settles most of them, and the ends, whose chord is then
/// the sub-curve's contribution. One cache line: a walk reads it for both halves of every
/// sub-curve it opens, and the rest of the sub-curve ([`SubNode`]) only for the one holding
/// the query.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
struct BoxNode {
    lo: Point,
    hi: Point,
    start: Point,
    end: Point,
}

/// One sub-curve of a [`CurveHierarchy`], with the tests the adaptive algorithm asks of it
/// past the box test.
#[derive(Clone, Debug)]
struct SubNode {
    curve: SubCurve,
    /// Simple and convex, with the parent's flag inherited as the adaptive algorithm does.
    convex: bool,
    /// Twice its control polygon's signed area ([`polygon_area`]).
    area: f64,
    linear: bool,
}

impl SubNode {
    fn new(curve: SubCurve, parent_convex: bool) -> Self {
        let p = curve.points();
        Self {
            convex: parent_convex || is_simple_convex(p),
            area: polygon_area(p),
            linear: is_linear(p),
            curve,
        }
    }

    fn box_node(&self) -> BoxNode {
        let p = self.curve.points();
        let (lo, hi) = control_box(p);
        BoxNode {
            lo,
            hi,
            start: p[0],
            end: p[p.len() - 1],
        }
    }
}

/// The tests of one sub-curve of a [`CurveHierarchy`] of a polynomial piece of at most
/// [`SMALL`] control points, past the box test: its control points, convexity, straightness
/// and area, in 80 bytes, read only for the sub-curves holding the query.
#[derive(Clone, Copy, Debug)]
struct SmallTests {
    /// Its control points, the first `len`.
    pts: [Point; SMALL],
    area: f64,
    /// Its control points (2 to [`SMALL`]).
    len: u8,
    convex: bool,
    linear: bool,
}

impl SmallTests {
    /// The box and the tests of sub-curve `c` (at least 2 control points), simple and convex
    /// if its parent is, as [`SubNode::new`] computes them.
    fn of(c: &SmallPolynomial, parent_convex: bool) -> (BoxNode, Self) {
        let p = c.points();
        let n = p.len();
        let (lo, hi) = control_box(p);
        let mut pts = [Point::default(); SMALL];
        pts[..n].copy_from_slice(p);
        let tests = Self {
            pts,
            area: polygon_area(p),
            len: n as u8,
            convex: parent_convex || is_simple_convex(p),
            linear: is_linear(p),
        };
        let ends = BoxNode {
            lo,
            hi,
            start: p[0],
            end: p[n - 1],
        };
        (ends, tests)
    }

    /// Its control points.
    #[inline(always)]
    fn points(&self) -> &[Point] {
        &self.pts[..usize::from(self.len)]
    }
}

/// Sub-curves of a [`CurveHierarchy`] above its last level (the others are its leaves).
const INNER_SUB_CURVES: u32 = (1 << HIERARCHY_DEPTH) - 1;

/// The subdivision hierarchy of one piece, computed once and shared, immutable, by all queries:
/// the first [`HIERARCHY_DEPTH`] levels of halving, each sub-curve with its control box,
/// convexity and straightness; deeper levels (queries within `2^-6` of the piece's size from
/// it) are computed on the fly.
///
/// The sub-curves are stored level by level (heap order: the halves of sub-curve `i` are
/// `2i + 1` and `2i + 2`, side by side), their boxes and ends apart from the rest, in one
/// cache line each; the rest of a polynomial piece's sub-curves (the common case) in 80 bytes
/// each.
#[derive(Clone, Debug)]
pub struct CurveHierarchy {
    boxes: Vec<BoxNode>,
    tests: Tests,
}

/// The tests past the box test of a [`CurveHierarchy`]'s sub-curves.
#[derive(Clone, Debug)]
enum Tests {
    /// A polynomial piece of at most [`SMALL`] control points.
    Small(Vec<SmallTests>),
    /// Any other piece.
    General(Vec<SubNode>),
}

impl CurveHierarchy {
    /// Precomputes the hierarchy of `curve`.
    pub fn new(curve: &RationalBezier) -> Self {
        let root = SubCurve::of(curve);
        match SmallPolynomial::of(&root).filter(|c| c.points().len() >= 2) {
            Some(small) => Self::small(small),
            None => Self::general(root),
        }
    }

    /// The hierarchy of a polynomial piece of 2 to [`SMALL`] control points, halved by value
    /// ([`SmallPolynomial`]'s halves are [`SubCurve::halves`], bit for bit).
    fn small(root: SmallPolynomial) -> Self {
        let total = (2usize << HIERARCHY_DEPTH) - 1;
        let (mut curves, mut boxes, mut tests) = (
            Vec::with_capacity(total),
            Vec::with_capacity(total),
            Vec::with_capacity(total),
        );
        let push = |c: SmallPolynomial,
                    parent_convex: bool,
                    curves: &mut Vec<SmallPolynomial>,
                    boxes: &mut Vec<BoxNode>,
                    tests: &mut Vec<SmallTests>| {
            let (b, t) = SmallTests::of(&c, parent_convex);
            curves.push(c);
            boxes.push(b);
            tests.push(t);
        };
        push(root, false, &mut curves, &mut boxes, &mut tests);
        // Halving the sub-curves in index order appends the halves of `i` at `2i + 1, 2i + 2`.
        for i in 0..INNER_SUB_CURVES as usize {
            let (l, r) = curves[i].halves();
            let parent_convex = tests[i].convex;
            push(l, parent_convex, &mut curves, &mut boxes, &mut tests);
            push(r, parent_convex, &mut curves, &mut boxes, &mut tests);
        }
        Self {
            boxes,
            tests: Tests::Small(tests),
        }
    }

    /// Is it the compact hierarchy of a small polynomial piece? (A probe for the tests.)
    #[cfg(test)]
    pub(super) fn is_compact(&self) -> bool {
        matches!(self.tests, Tests::Small(_))
    }

    /// The general hierarchy of any piece, small polynomial or not. (For the tests.)
    #[cfg(test)]
    pub(super) fn general_of(curve: &RationalBezier) -> Self {
        Self::general(SubCurve::of(curve))
    }

    /// The hierarchy of any other piece.
    fn general(root: SubCurve) -> Self {
        let total = (2usize << HIERARCHY_DEPTH) - 1;
        let mut nodes = Vec::with_capacity(total);
        nodes.push(SubNode::new(root, false));
        // Halving the sub-curves in index order appends the halves of `i` at `2i + 1, 2i + 2`.
        for i in 0..INNER_SUB_CURVES as usize {
            let (l, r) = nodes[i].curve.halves();
            let parent_convex = nodes[i].convex;
            nodes.push(SubNode::new(l, parent_convex));
            nodes.push(SubNode::new(r, parent_convex));
        }
        Self {
            boxes: nodes.iter().map(SubNode::box_node).collect(),
            tests: Tests::General(nodes),
        }
    }

    /// The adaptive algorithm on the piece, through the cached sub-curves (handles of four
    /// bytes on the walk's stack) and on the fly past them, with the same tests as
    /// `curve::refine` on the piece itself. Its caller has found `q` in the piece's box (the
    /// leaf's), so there is no far-field shortcut to take first; the whole piece's tests
    /// ([`settle`]) give its chord for a `q` outside it anyway.
    pub(super) fn refine<K: ChordSink>(&self, q: Point, sink: &mut K, stats: &mut QueryStats) {
        match &self.tests {
            Tests::Small(tests) => walk_hierarchy(
                &SmallView {
                    boxes: &self.boxes,
                    tests,
                },
                q,
                sink,
                stats,
            ),
            Tests::General(nodes) => walk_hierarchy(
                &GeneralView {
                    boxes: &self.boxes,
                    nodes,
                },
                q,
                sink,
                stats,
            ),
        }
    }
}

/// A [`CurveHierarchy`]'s sub-curves, by index, and the walk on the fly below its leaves.
trait Hierarchy: SubCurves<Node = u32> {
    /// The adaptive algorithm below leaf `i`, with `state` its depth, whether it is simple and
    /// convex, and whether its halves may be settled by their roots ([`settle_by_root`]): its
    /// halves, each walked on the fly.
    fn below<K: ChordSink>(
        &self,
        i: u32,
        state: (u32, bool, bool),
        q: Point,
        sink: &mut K,
        stats: &mut QueryStats,
    );
}

/// The walk of [`CurveHierarchy::refine`]: depth-first, the left half next and the right one
/// pending until all of the left's sub-curves are done (the order [`refine_below`] takes).
///
/// A cached sub-curve above the leaves leaves at most one pending right half per level below
/// the root, so a fixed stack of [`HIERARCHY_DEPTH`] entries holds them (the walk below the
/// leaves keeps its own).
#[inline(always)]
fn walk_hierarchy<H: Hierarchy, K: ChordSink>(
    h: &H,
    q: Point,
    sink: &mut K,
    stats: &mut QueryStats,
) {
    let mut pending: [Pending<u32>; HIERARCHY_DEPTH as usize] =
        [(0, 0, false, false); HIERARCHY_DEPTH as usize];
    let mut len = 0;
    let mut next: Option<Pending<u32>> = Some((0, 0, false, true));
    loop {
        let (i, depth, parent_convex, roots) = match next.take() {
            Some(n) => n,
            None if len > 0 => {
                len -= 1;
                pending[len]
            }
            None => break,
        };
        stats.curve_evaluations += 1;
        let Some(convex) = settle(h, &i, q, depth, parent_convex, sink) else {
            continue;
        };
        let Some(roots) = settle_by_root(h, &i, q, roots, sink) else {
            continue;
        };
        if i < INNER_SUB_CURVES {
            pending[len] = (2 * i + 2, depth + 1, convex, roots);
            len += 1;
            next = Some((2 * i + 1, depth + 1, convex, roots));
        } else {
            h.below(i, (depth, convex, roots), q, sink, stats);
        }
    }
}

/// A polynomial piece's hierarchy.
struct SmallView<'h> {
    boxes: &'h [BoxNode],
    tests: &'h [SmallTests],
}

impl SubCurves for SmallView<'_> {
    type Node = u32;
    type Points<'s>
        = &'s [Point]
    where
        Self: 's;
    #[inline(always)]
    fn points<'s>(&'s self, i: &'s u32) -> &'s [Point] {
        self.tests[*i as usize].points()
    }
    #[inline(always)]
    fn ends(&self, i: &u32) -> (Point, Point) {
        let b = &self.boxes[*i as usize];
        (b.start, b.end)
    }
    #[inline(always)]
    fn convex(&self, i: &u32, _parent_convex: bool) -> bool {
        self.tests[*i as usize].convex
    }
    #[inline(always)]
    fn linear(&self, i: &u32) -> bool {
        self.tests[*i as usize].linear
    }
    #[inline(always)]
    fn area(&self, i: &u32) -> f64 {
        self.tests[*i as usize].area
    }
    #[inline(always)]
    fn outside_box(&self, i: &u32, q: Point, reach: f64) -> Outside {
        let b = &self.boxes[*i as usize];
        outside_box_reach(b.lo, b.hi, q, reach)
    }
    #[inline(always)]
    fn monotone_crossing(&self, i: &u32, q: Point, reach: f64) -> RootCrossing {
        monotone_crossing(self.tests[*i as usize].points(), q, reach)
    }
}

impl Hierarchy for SmallView<'_> {
    /// The same halves as [`SubCurve::halves`] of the leaf (the same de Casteljau split of the
    /// same points), walked as [`refine_below`] walks them.
    fn below<K: ChordSink>(
        &self,
        i: u32,
        (depth, convex, roots): (u32, bool, bool),
        q: Point,
        sink: &mut K,
        stats: &mut QueryStats,
    ) {
        let t = &self.tests[i as usize];
        let (l, r) = SmallPolynomial::from_array(t.pts, usize::from(t.len)).halves();
        stats.subdivisions += 1;
        refine_below_small(l, (depth + 1, convex, roots), q, sink, stats);
        refine_below_small(r, (depth + 1, convex, roots), q, sink, stats);
    }
}

/// Any other piece's hierarchy.
struct GeneralView<'h> {
    boxes: &'h [BoxNode],
    nodes: &'h [SubNode],
}

impl SubCurves for GeneralView<'_> {
    type Node = u32;
    type Points<'s>
        = &'s [Point]
    where
        Self: 's;
    fn points<'s>(&'s self, i: &'s u32) -> &'s [Point] {
        self.nodes[*i as usize].curve.points()
    }
    fn ends(&self, i: &u32) -> (Point, Point) {
        let b = &self.boxes[*i as usize];
        (b.start, b.end)
    }
    fn convex(&self, i: &u32, _parent_convex: bool) -> bool {
        self.nodes[*i as usize].convex
    }
    fn linear(&self, i: &u32) -> bool {
        self.nodes[*i as usize].linear
    }
    fn area(&self, i: &u32) -> f64 {
        self.nodes[*i as usize].area
    }
    fn outside_box(&self, i: &u32, q: Point, reach: f64) -> Outside {
        let b = &self.boxes[*i as usize];
        outside_box_reach(b.lo, b.hi, q, reach)
    }
}

impl Hierarchy for GeneralView<'_> {
    fn below<K: ChordSink>(
        &self,
        i: u32,
        (depth, convex, _roots): (u32, bool, bool),
        q: Point,
        sink: &mut K,
        stats: &mut QueryStats,
    ) {
        let (l, r) = self.nodes[i as usize].curve.halves();
        stats.subdivisions += 1;
        refine_below(l, depth + 1, convex, q, sink, stats);
        refine_below(r, depth + 1, convex, q, sink, stats);
    }
}

/// Depth bound of the walk's stack: the hierarchy is balanced, so its depth is at most
/// `log2(pieces) + 1`.
pub(super) const STACK: usize = 64;

/// A node of the bounding-volume hierarchy: a contiguous run of pieces in boundary order.
#[derive(Clone, Debug)]
struct BvhNode {
    lo: Point,
    hi: Point,
    /// The chords of the maximal chains its pieces form (runs of pieces each ending exactly
    /// where the next starts), `first..last` in [`FastWindingField::chords`]; an empty range
    /// if there are more than [`LEFT_CHAINS`].
    chords: (u32, u32),
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
/// `B` crosses the ray as its chord `A -> B` does (decided by two comparisons), and one whose
/// pieces form several chains as their chords do, without opening the node; other nodes
/// are opened, and a leaf whose box holds `q` runs the adaptive algorithm on its piece's
/// subdivision hierarchy ([`CurveHierarchy`], built the second time a query needs it and kept;
/// the first query walks the piece's sub-curves on the fly, with the same result). Where
/// the walk would halve a polynomial sub-curve of degree 3 or less whose control points'
/// ordinates strictly rise or fall (so that it is monotone in `y`), the
/// sub-curve's crossing is decided instead from the root of `y(t) = q.y` by Newton's method,
/// with a bound on the root's error, when `q` is certainly farther than twice the band's reach
/// from it (`monotone`): the chords' crossings would add up to the same whole number, so the
/// values are the reference walk's bit for bit, and a query near a curve takes a few Newton
/// steps instead of halving down to its distance (two sub-curves' tests a level).
/// A query far from the boundary costs a few node tests; one near it visits the nodes along
/// its ray. Fields of 33 to 16,384 pieces mostly answer without the walk: the leaves are kept
/// by rows of their height, and in its row a query adds the crossings of the leaves spanning
/// the row wholly left of it by one binary search (their chords' crossings summed beforehand,
/// sorted by their right sides), and visits the few others one by one (half the walk's time
/// on the GWN paper's large shapes, the same values bit for bit); a row with more than 64
/// others is left to the walk. Once its batches have brought `2^14` points, the field builds
/// its far cells (a grid whose cells away from the curves know their queries' crossings, see
/// `far_cells`), where a batch's query skips the walk.
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
    /// The nodes' chain chords (see [`BvhNode::chords`]).
    chords: Vec<(Point, Point)>,
    /// With at most [`ROW_PIECES`] pieces, the leaves by rows of the pieces' height
    /// ([`leaf_rows`]; then a query visits its row's leaves instead of walking the tree).
    rows: Option<Rows>,
    /// With more than [`ROW_PIECES`] and at most [`SPAN_ROW_PIECES`] pieces, the leaves by
    /// rows, each row's spanning leaves with their chords' crossings summed ([`SpanRows`];
    /// then a query reads its row instead of walking the tree).
    span_rows: Option<Box<SpanRows>>,
    hierarchies: Vec<HierarchySlot>,
    /// The grid whose far cells answer a batch's queries without the walk.
    far_cells: FarCellsSlot,
}

/// A field's [`FarCells`], built once its batches have brought [`FAR_CELLS_MIN_POINTS`]
/// points (`None` inside if the field's box has no area).
#[derive(Debug, Default)]
struct FarCellsSlot {
    cells: OnceLock<Option<Box<FarCells>>>,
    /// Points of the batches answered so far.
    answered: AtomicUsize,
}

impl Clone for FarCellsSlot {
    fn clone(&self) -> Self {
        Self {
            cells: self.cells.clone(),
            answered: AtomicUsize::new(self.answered.load(Ordering::Relaxed)),
        }
    }
}

/// A piece's subdivision hierarchy, built on the second query that refines the piece (the
/// first walks the same sub-curves on the fly: a piece refined once, as by a single query on a
/// freshly built field, never pays for the 127 sub-curves).
#[derive(Debug, Default)]
struct HierarchySlot {
    hierarchy: OnceLock<CurveHierarchy>,
    /// Some query has refined the piece (on the fly, or through the hierarchy).
    refined: AtomicBool,
}

impl Clone for HierarchySlot {
    fn clone(&self) -> Self {
        Self {
            hierarchy: self.hierarchy.clone(),
            refined: AtomicBool::new(self.refined.load(Ordering::Relaxed)),
        }
    }
}

/// A node wholly left of the query made of at most this many chains adds their chords'
/// crossings without being opened (more are opened: their children's boxes may lie above or
/// below the query); this also bounds the chords stored to this many per node.
const LEFT_CHAINS: usize = 8;

/// Up to this many pieces a query visits the leaves of its row ([`leaf_rows`]) instead of
/// walking the tree: the inner nodes of so small a tree hold nearly every query, so the walk
/// mostly adds their tests and the stack's traffic.
const ROW_PIECES: usize = 32;

/// Up to this many pieces (and above [`ROW_PIECES`]) a query reads its row of the leaves'
/// [`SpanRows`] instead of walking the tree: one binary search adds the crossings of the
/// leaves spanning the row wholly left of it. (Beyond, the rows' registrations, 16 per leaf
/// on average plus the rows, would coarsen them.)
const SPAN_ROW_PIECES: usize = 1 << 14;

/// Points the batch queries put in their locality order at a time: the order takes 6 bytes a
/// point of a block. (Measured on the GWN paper's shapes with 10^5 points: blocks of `2^15`
/// gained as much as `2^16` and more than `2^14`.)
const LOCALITY_BLOCK: usize = 1 << 15;

/// Once a field's batches have brought this many points, it builds its [`FarCells`] and its
/// batches read them. (Their build, a box per two cells of curve and a walk per region of far
/// cells, took 0.01-0.3 ms on the GWN paper's shapes; a random point in a far cell saves
/// 0.02-0.04 us.)
pub(super) const FAR_CELLS_MIN_POINTS: usize = 1 << 14;

/// Rows per piece of a small field's [`Rows`].
const ROWS_PER_PIECE: usize = 4;

/// Up to this many pieces a small field's [`Rows`] is one row: finding a query's row costs more
/// than the few leaves it would skip.
const ONE_ROW_PIECES: usize = 8;

/// The leaves of the tree, in boundary order, with their chords.
fn leaves(nodes: &[BvhNode], chords: &[(Point, Point)]) -> Vec<Leaf> {
    let mut out: Vec<Leaf> = nodes
        .iter()
        .filter_map(|n| match n.kind {
            Kind::Leaf(p) => Some(Leaf {
                lo: n.lo,
                hi: n.hi,
                piece: p,
                // A leaf keeps its piece's chord (see `build`).
                chord: chords[n.chords.0 as usize],
            }),
            Kind::Inner(..) => None,
        })
        .collect();
    out.sort_by_key(|l| l.piece);
    out
}

/// The leaves of a small tree by rows of the pieces' height, in boundary order: a leaf off a
/// query's row lies above or below the query, where the tree walk would skip it too.
fn leaf_rows(nodes: &[BvhNode]) -> Rows {
    let leaves: Vec<(u32, f64, f64)> = (0..nodes.len() as u32)
        .filter(|&i| matches!(nodes[i as usize].kind, Kind::Leaf(_)))
        .map(|i| (i, nodes[i as usize].lo.y, nodes[i as usize].hi.y))
        .collect();
    let rows = if leaves.len() <= ONE_ROW_PIECES {
        1
    } else {
        ROWS_PER_PIECE * leaves.len()
    };
    Rows::new(&leaves, rows, usize::MAX)
}

impl<'a> FastWindingField<'a> {
    /// Builds the hierarchy over `field`'s pieces: `2n - 1` nodes by `n - 1` box merges, with
    /// their chain chords, in three allocations (the nodes, the chords, the per-piece slots);
    /// plus, for at most 32 pieces, the leaves' rows, and for 33 to 16,384 their span rows
    /// (about half a microsecond a piece on the GWN paper's shapes). The pieces' subdivision
    /// hierarchies are built later, as queries reach them; so are the field's monotone boxes
    /// (see [`WindingField`]'s Construction).
    pub fn new(field: &'a WindingField) -> Self {
        let pieces = field.pieces();
        let mut nodes = Vec::with_capacity((2 * pieces.len()).saturating_sub(1));
        // Each node keeps at most LEFT_CHAINS chords, most a handful: about two per piece is
        // enough for closed loops, and the vector grows if not.
        let mut chords = Vec::with_capacity(2 * pieces.len());
        if !pieces.is_empty() {
            build(field, 0, pieces.len(), &mut nodes, &mut chords);
        }
        let rows = (!pieces.is_empty() && pieces.len() <= ROW_PIECES).then(|| leaf_rows(&nodes));
        let span_rows = (pieces.len() > ROW_PIECES && pieces.len() <= SPAN_ROW_PIECES)
            .then(|| Box::new(SpanRows::new(leaves(&nodes, &chords))));
        Self {
            field,
            nodes,
            chords,
            rows,
            span_rows,
            hierarchies: pieces.iter().map(|_| HierarchySlot::default()).collect(),
            far_cells: FarCellsSlot::default(),
        }
    }

    /// The field's [`FarCells`] over the tree's box, for a batch of `n` points: built once the
    /// batches have brought [`FAR_CELLS_MIN_POINTS`] points, `None` before.
    fn far_cells(&self, n: usize) -> Option<&FarCells> {
        let slot = &self.far_cells;
        if let Some(cells) = slot.cells.get() {
            return cells.as_deref();
        }
        let before = slot.answered.fetch_add(n, Ordering::Relaxed);
        if before.saturating_add(n) < FAR_CELLS_MIN_POINTS {
            return None;
        }
        slot.cells
            .get_or_init(|| {
                let root = self.nodes.last()?;
                let (mut stack, mut stats) = ([0; STACK], QueryStats::default());
                FarCells::new(
                    root.lo,
                    root.hi,
                    self.field.near_reach(),
                    self.field.pieces(),
                    self.field.open_chain_ends(),
                    |q| {
                        self.crossing_sum(q, &[], &mut stack, &mut stats)
                            .crossings_alone()
                    },
                )
                .map(Box::new)
            })
            .as_deref()
    }

    /// The generalized winding number at `q`.
    pub fn winding_number(&self, q: Point) -> f64 {
        self.winding_number_counted(q, &mut QueryStats::default())
    }

    /// The generalized winding number at `q`, adding the work done to `stats` (a node decided
    /// by its chord counts as one curve evaluation; the leaves a span row adds by its binary
    /// search count nothing, so counts from fields read by rows and by the walk differ).
    pub fn winding_number_counted(&self, q: Point, stats: &mut QueryStats) -> f64 {
        let mut stack = [0; STACK];
        let mut sum = self.crossing_sum(q, &[], &mut stack, stats);
        if sum.near()
            && let Some(w) = self.band_winding_number(q, &mut stack, stats)
        {
            return w;
        }
        self.field
            .add_open_chain_ends(std::slice::from_mut(&mut sum));
        sum.value()
    }

    /// The winding number at a `q` in the band (see [`WindingField`]'s Semantics), `None` if
    /// `q` is not in the band: the walk without the pieces `q` passes near, and those pieces
    /// cut at the passages.
    fn band_winding_number(
        &self,
        q: Point,
        stack: &mut [u32; STACK],
        stats: &mut QueryStats,
    ) -> Option<f64> {
        let passages = self.field.passages(q);
        if passages.is_empty() {
            return None;
        }
        let skip = super::passage_pieces(&passages);
        let mut sum = self.crossing_sum(q, &skip, stack, stats);
        self.field.add_passages(q, &passages, &mut sum, stats);
        self.field
            .add_open_chain_ends(std::slice::from_mut(&mut sum));
        Some(sum.value())
    }

    /// The crossings and coincident pieces at `q` of every piece but those in `skip` (sorted),
    /// without the open chains' ends; the sum records whether `q` may be near a piece
    /// ([`WindingSum::near`]: only then may it be in the band, as a leaf's box holds every point
    /// near its piece and its refinement tells whether `q` comes within the field's reach of a
    /// settled sub-curve); `stack` is scratch for the walk
    /// (a caller answering many points passes the same one, so it is not zeroed per point).
    ///
    /// A leaf whose box holds `q` is always visited: the boxes of its ancestors hold `q` too,
    /// so none is skipped, nor decided by its chords (which needs `q` right of its box). So
    /// leaving out the pieces of `skip` there leaves them out of the sum.
    ///
    /// The three ways (span rows, rows, the walk) give the same sum bit for bit: the same
    /// leaves are refined, in boundary order, and the others add the same whole number of
    /// crossings (a node's chain chord crosses the ray as its pieces' chords do together,
    /// their joints being shared exactly, and a leaf above or below `q` adds none).
    pub(super) fn crossing_sum(
        &self,
        q: Point,
        skip: &[u32],
        stack: &mut [u32; STACK],
        stats: &mut QueryStats,
    ) -> WindingSum {
        let mut sum = WindingSum::tracking(q, self.field.near_reach());
        if let Some(rows) = self
            .span_rows
            .as_ref()
            .filter(|_| !q.x.is_nan() && !q.y.is_nan())
        {
            // The pieces whose leaf holds q, refined in boundary order as the walk refines
            // them (their coincidence terms add in the same order).
            let mut hits: SmallVec<[u32; 8]> = SmallVec::new();
            if let Some(decided) = rows.add(q, &mut sum, &mut hits) {
                stats.curve_evaluations += decided;
                hits.sort_unstable();
                for p in hits {
                    if skip.binary_search(&p).is_err() {
                        self.refine_piece(p as usize, q, &mut sum, stats);
                    }
                }
                return sum;
            }
        }
        // A NaN ordinate takes the walk (no row is its).
        if let Some(rows) = self.rows.as_ref().filter(|_| !q.y.is_nan()) {
            if rows.spans(q.y) {
                for &i in rows.near(q.y) {
                    self.visit(i, q, skip, &mut sum, stats);
                }
            }
            return sum;
        }
        self.walk_tree(q, skip, stack, &mut sum, stats);
        sum
    }

    /// Adds to `sum` every piece but those in `skip` by the walk down the tree: depth-first,
    /// left child first (so the leaves holding `q` are refined in boundary order).
    fn walk_tree(
        &self,
        q: Point,
        skip: &[u32],
        stack: &mut [u32; STACK],
        sum: &mut WindingSum,
        stats: &mut QueryStats,
    ) {
        // At most one pending right child per level, and the tree is balanced (depth at most
        // log2(pieces) + 1 < STACK).
        let mut len = 0;
        if !self.nodes.is_empty() {
            stack[0] = self.nodes.len() as u32 - 1;
            len = 1;
        }
        while len > 0 {
            len -= 1;
            if let Some((l, r)) = self.visit(stack[len], q, skip, sum, stats) {
                stack[len] = r;
                stack[len + 1] = l;
                len += 2;
            }
        }
    }

    /// Adds to `sum` what node `i` holds for `q` when that takes no look inside it (nothing if
    /// its box lies above, below or right of `q`; its chains' chord crossings if it lies wholly
    /// left of `q` and keeps them), or runs the adaptive algorithm on a leaf (unless its piece
    /// is in `skip`); returns an inner node's children otherwise.
    #[inline(always)]
    fn visit(
        &self,
        i: u32,
        q: Point,
        skip: &[u32],
        sum: &mut WindingSum,
        stats: &mut QueryStats,
    ) -> Option<(u32, u32)> {
        let n = &self.nodes[i as usize];
        if misses_cut(n.lo, n.hi, q) {
            return None;
        }
        if q.x > n.hi.x && n.chords.0 < n.chords.1 {
            // Wholly left of q: each chain crosses the ray as its chord does (one above or
            // below q adds 0), without opening the node.
            stats.curve_evaluations += 1;
            for &(a, b) in &self.chords[n.chords.0 as usize..n.chords.1 as usize] {
                sum.left_crossing(a, b);
            }
            return None;
        }
        match n.kind {
            Kind::Leaf(p) => {
                if skip.binary_search(&p).is_err() {
                    self.refine_piece(p as usize, q, sum, stats);
                }
                None
            }
            Kind::Inner(l, r) => Some((l, r)),
        }
    }

    /// The adaptive algorithm on piece `p`: through its subdivision hierarchy, built by the
    /// second query that needs it; the first walks the piece on the fly.
    ///
    /// Both walks send `sum` the same chords and coincident pieces in the same order (bit for
    /// bit the same sum): each starts with [`settle`] on the whole piece (no far-field shortcut
    /// first, see [`CurveHierarchy::refine`]), halves a sub-curve by the same
    /// [`SubCurve::halves`], computes the same tests of it (convexity inherited from the parent
    /// or [`is_simple_convex`], [`is_linear`], the control box and polygon area), and pushes the
    /// right half before the left.
    #[inline(always)]
    fn refine_piece(&self, p: usize, q: Point, sum: &mut WindingSum, stats: &mut QueryStats) {
        let slot = &self.hierarchies[p];
        let sum = &mut CrossingSum(sum);
        if let Some(h) = slot.hierarchy.get() {
            h.refine(q, sum, stats);
        } else if slot.refined.swap(true, Ordering::Relaxed) {
            slot.hierarchy
                .get_or_init(|| CurveHierarchy::new(&self.field.pieces()[p]))
                .refine(q, sum, stats);
        } else {
            stats.curve_evaluations += 1;
            refine_below(self.field.root(p).clone(), 0, false, q, sum, stats);
        }
    }

    /// The far cells, if a batch has built them. (A probe for the tests.)
    #[cfg(test)]
    pub(super) fn built_far_cells(&self) -> Option<&FarCells> {
        self.far_cells.cells.get().and_then(Option::as_deref)
    }

    /// Has a query built piece `p`'s subdivision hierarchy? (A probe for the tests.)
    #[cfg(test)]
    pub(super) fn hierarchy_built(&self, p: usize) -> bool {
        self.hierarchies[p].hierarchy.get().is_some()
    }

    /// Winding numbers of many points, in input order, on the current thread: each equal to
    /// [`FastWindingField::winding_number`]'s (the batch of [`PointQuery`]`<f64>`).
    pub fn winding_numbers(&self, points: &[Point]) -> Vec<f64> {
        let mut out = vec![0.0; points.len()];
        self.values_into(points, &mut out);
        out
    }

    /// Winding numbers of many points on the calling thread and rayon's pool (with the
    /// `parallel` feature, on by default; otherwise on the current thread).
    pub fn winding_numbers_parallel(&self, points: &[Point]) -> Vec<f64> {
        let mut out = vec![0.0; points.len()];
        self.par_values_into(points, &mut out);
        out
    }

    /// For each group of [`BATCH`] points: their crossing sums (from the far cells or the split
    /// cells where they are made and hold the point, telling the far cells how many walked),
    /// the open chains' ends added to all at once, then
    /// `finish(q, sum, stack, stats)` per point writes its output.
    ///
    /// The points are taken block by block ([`LOCALITY_BLOCK`]), each in its locality order
    /// ([`locality_order`] over the field's box): a query then mostly reads the hierarchies
    /// and rows its predecessor read, and takes its branches. Each value is the one its point
    /// gets alone, written to its place: 10^5 points near the curves of the GWN paper's shapes
    /// took 0.72-0.92 of the time they took in their given (random) order, random points in
    /// their boxes 0.80-0.89.
    #[inline(always)]
    fn sums_into<T>(
        &self,
        point: impl Fn(usize) -> Point,
        out: &mut [T],
        finish: impl Fn(Point, &WindingSum, &mut [u32; STACK], &mut QueryStats) -> T,
    ) {
        let mut stats = QueryStats::default();
        let mut sums = [WindingSum::new(Point::default()); BATCH];
        let mut stack = [0; STACK];
        let (lo, hi) = self
            .nodes
            .last()
            .map_or_else(Default::default, |n| (n.lo, n.hi));
        let far = self.far_cells(out.len());
        let reach = self.field.near_reach();
        let mut order = Vec::new();
        let mut sorted = Vec::new();
        for (b, block) in out.chunks_mut(LOCALITY_BLOCK).enumerate() {
            let first = b * LOCALITY_BLOCK;
            locality_order(block.len(), |i| point(first + i), lo, hi, &mut order);
            // The block's points in that order, gathered in one pass whose loads do not wait on
            // each other. Read by each query from anywhere in the block (512 KB of points),
            // its point's load missed the core's cache after the previous query's work, and
            // the query waited on it: perf put 16% of a near query's time on butterfly there.
            sorted.clear();
            sorted.extend(order.iter().map(|&i| point(first + i as usize)));
            let (mut walks, mut split_queries) = (0, 0);
            for (group, points) in order.chunks(BATCH).zip(sorted.chunks(BATCH)) {
                let sums = &mut sums[..group.len()];
                for (sum, &q) in sums.iter_mut().zip(points) {
                    *sum = match far.and_then(|f| f.crossings(q, &mut split_queries)) {
                        Some(k) => WindingSum::with_crossings(q, reach, k),
                        None => {
                            walks += 1;
                            self.crossing_sum(q, &[], &mut stack, &mut stats)
                        }
                    };
                }
                self.field.add_open_chain_ends(sums);
                for (&i, sum) in group.iter().zip(sums.iter()) {
                    block[i as usize] = finish(sum.q(), sum, &mut stack, &mut stats);
                }
            }
            if let Some(f) = far {
                f.note_walks(walks, split_queries, self.field.pieces());
            }
        }
    }
}

impl PointQuery<f64> for FastWindingField<'_> {
    /// [`FastWindingField::winding_number`].
    fn value(&self, q: Point) -> f64 {
        self.winding_number(q)
    }

    /// The open chains' ends are added for eight points at a time (one pass over the chains,
    /// each step done for the eight at once), which on shapes of many open curves takes about
    /// half the time of one point at a time.
    fn values_into<P: PointSource + ?Sized>(&self, points: &P, out: &mut [f64]) {
        assert_eq!(points.len(), out.len(), "one value per point");
        self.sums_into(
            |i| points.point(i),
            out,
            |q, sum, stack, stats| {
                if sum.near()
                    && let Some(w) = self.band_winding_number(q, stack, stats)
                {
                    return w;
                }
                sum.value()
            },
        );
    }
}

impl PointQuery<Location> for FastWindingField<'_> {
    /// As the [`WindingField`]'s [`Locate`](crate::Locate), with its fill rule, from the fast
    /// winding number. The boundary test runs only for a query the walk found within reach of
    /// a piece (every point of the band is: see [`WindingField`]'s Construction), so a query
    /// away from the curves leaves the field's boundary index unbuilt.
    fn value(&self, q: Point) -> Location {
        let (mut stack, mut stats) = ([0; STACK], QueryStats::default());
        let mut sum = self.crossing_sum(q, &[], &mut stack, &mut stats);
        let rule = self.field.fill_rule();
        if sum.near() {
            if self.field.is_on_boundary(q) {
                return Location::Boundary;
            }
            if let Some(w) = self.band_winding_number(q, &mut stack, &mut stats) {
                return self.field.location_from_winding(w, rule);
            }
        }
        self.field
            .add_open_chain_ends(std::slice::from_mut(&mut sum));
        self.field.location_from_winding(sum.value(), rule)
    }

    /// The winding numbers computed together, as for [`PointQuery`]`<f64>`.
    fn values_into<P: PointSource + ?Sized>(&self, points: &P, out: &mut [Location]) {
        assert_eq!(points.len(), out.len(), "one value per point");
        let rule = self.field.fill_rule();
        self.sums_into(
            |i| points.point(i),
            out,
            |q, sum, _, _| {
                // Only a query the walk brought within reach of a piece may be in the band.
                if sum.near() && self.field.is_on_boundary(q) {
                    return Location::Boundary;
                }
                self.field.location_from_winding(sum.value(), rule)
            },
        );
    }
}

/// Builds the subtree over `field`'s pieces `[i, j)`; returns its index (children before
/// parents). Its chain chords go to the end of `chords`.
fn build(
    field: &WindingField,
    i: usize,
    j: usize,
    nodes: &mut Vec<BvhNode>,
    chords: &mut Vec<(Point, Point)>,
) -> u32 {
    let (kind, lo, hi, own) = if j - i == 1 {
        let (lo, hi) = field.near_box(i);
        let p = &field.pieces()[i];
        let one: SmallVec<[(Point, Point); LEFT_CHAINS]> =
            SmallVec::from_elem((p.start_point(), p.end_point()), 1);
        (Kind::Leaf(i as u32), lo, hi, Some(one))
    } else {
        let m = (i + j) / 2;
        let (l, r) = (
            build(field, i, m, nodes, chords),
            build(field, m, j, nodes, chords),
        );
        let (ln, rn) = (&nodes[l as usize], &nodes[r as usize]);
        let lo = Point::new(ln.lo.x.min(rn.lo.x), ln.lo.y.min(rn.lo.y));
        let hi = Point::new(ln.hi.x.max(rn.hi.x), ln.hi.y.max(rn.hi.y));
        // The children's chains, the left's last joined to the right's first if it ends
        // exactly where that starts; none if either child has none, or if they come to more
        // than LEFT_CHAINS (counted first, so the list never outgrows its inline storage).
        let (lc, rc) = (ln.chords, rn.chords);
        let (left, right) = (
            &chords[lc.0 as usize..lc.1 as usize],
            &chords[rc.0 as usize..rc.1 as usize],
        );
        let joined = matches!((left.last(), right.first()), (Some(l), Some(r)) if l.1 == r.0);
        let own = (!left.is_empty()
            && !right.is_empty()
            && left.len() + right.len() - usize::from(joined) <= LEFT_CHAINS)
            .then(|| {
                let mut own: SmallVec<[(Point, Point); LEFT_CHAINS]> = SmallVec::from_slice(left);
                let mut right = right;
                if joined && let (Some(last), Some(&(_, b))) = (own.last_mut(), right.first()) {
                    last.1 = b;
                    right = &right[1..];
                }
                own.extend_from_slice(right);
                own
            });
        (Kind::Inner(l, r), lo, hi, own)
    };
    let start = chords.len() as u32;
    if let Some(own) = own {
        chords.extend_from_slice(&own);
    }
    nodes.push(BvhNode {
        lo,
        hi,
        chords: (start, chords.len() as u32),
        kind,
    });
    nodes.len() as u32 - 1
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::{Domain, circular_arc, segment};

    /// The maximal chains of `pieces`, each as its first start and last end.
    fn chains_of(pieces: &[RationalBezier]) -> Vec<(Point, Point)> {
        let mut out: Vec<(Point, Point)> = Vec::new();
        for (k, p) in pieces.iter().enumerate() {
            match out.last_mut() {
                Some(last) if k > 0 && pieces[k - 1].end_point() == p.start_point() => {
                    last.1 = p.end_point();
                }
                _ => out.push((p.start_point(), p.end_point())),
            }
        }
        out
    }

    /// A small field's rows list every leaf whose box spans a query's ordinate, in boundary
    /// order, and the fast field's values equal the per-curve field's on a grid through the
    /// pieces' corners, above and below them.
    #[test]
    fn rows_hold_every_leaf_a_query_cannot_skip() {
        let mut curves = vec![circular_arc(Point::new(0.0, 0.0), 1.0, 0.3, 5.0).unwrap()];
        for k in 0..9 {
            let x = k as f64 * 0.37 - 1.5;
            curves.push(
                segment(
                    Point::new(x, -2.0 + 0.1 * k as f64),
                    Point::new(x + 0.2, 1.7),
                )
                .unwrap(),
            );
        }
        let d = Domain::new(curves).unwrap();
        let field = WindingField::new(&d, crate::DEFAULT_RELATIVE_TOLERANCE).unwrap();
        let fast = FastWindingField::new(&field);
        let rows = fast.rows.as_ref().expect("a small field has rows");
        assert!(rows.len() > 1);
        let leaves: Vec<u32> = (0..fast.nodes.len() as u32)
            .filter(|&i| matches!(fast.nodes[i as usize].kind, Kind::Leaf(_)))
            .collect();
        let mut ys: Vec<f64> = leaves
            .iter()
            .flat_map(|&i| [fast.nodes[i as usize].lo.y, fast.nodes[i as usize].hi.y])
            .collect();
        ys.extend((0..400).map(|k| -2.5 + k as f64 * 0.0113));
        for &y in &ys {
            let near = rows.near(y);
            let want: Vec<u32> = leaves
                .iter()
                .copied()
                .filter(|&i| !(y < fast.nodes[i as usize].lo.y || y > fast.nodes[i as usize].hi.y))
                .collect();
            assert!(want.is_empty() || rows.spans(y), "y {y} off the span");
            assert!(
                want.iter().all(|i| near.contains(i)),
                "y {y}: {near:?} lacks some of {want:?}"
            );
            assert!(near.windows(2).all(|w| w[0] < w[1]), "boundary order");
            for x in [-3.0, -0.9, 0.05, 0.6, 3.0] {
                let q = Point::new(x, y);
                assert!(
                    (fast.winding_number(q) - field.winding_number(q)).abs() < 1e-12,
                    "{q:?}"
                );
            }
        }
        assert!(!rows.spans(f64::NAN));
        assert!(!rows.spans(99.0));
    }

    /// Walks the tree with each node's piece range (the build halves `[i, j)` at its middle).
    fn check(fast: &FastWindingField, node: u32, i: usize, j: usize, seen: &mut usize) {
        let n = &fast.nodes[node as usize];
        let want = chains_of(&fast.field.pieces()[i..j]);
        let got = &fast.chords[n.chords.0 as usize..n.chords.1 as usize];
        if want.len() <= LEFT_CHAINS {
            assert_eq!(got, &want[..], "pieces {i}..{j}");
        } else {
            assert!(
                got.is_empty(),
                "pieces {i}..{j}: {} chains kept",
                want.len()
            );
        }
        *seen += 1;
        if let Kind::Inner(l, r) = n.kind {
            let m = (i + j) / 2;
            check(fast, l, i, m, seen);
            check(fast, r, m, j, seen);
        }
    }

    /// Every node keeps the chords of the maximal chains its pieces form (pieces joined end to
    /// start exactly), or none when they are more than `LEFT_CHAINS`: on open arcs with gaps,
    /// closed loops and a long run of separate segments.
    #[test]
    fn nodes_keep_their_chains_chords() {
        let mut curves = vec![
            circular_arc(Point::new(0.0, 0.0), 1.0, 0.0, 4.0).unwrap(),
            segment(Point::new(-0.7, -0.7), Point::new(0.9, -0.2)).unwrap(),
            circular_arc(Point::new(0.2, 0.1), 0.5, 1.0, 7.0).unwrap(),
        ];
        curves.push(rs_spline::circle(Point::new(3.0, 0.0), 0.5).unwrap());
        for k in 0..20 {
            let x = k as f64 * 0.1;
            curves.push(segment(Point::new(x, 2.0), Point::new(x + 0.05, 2.1)).unwrap());
        }
        let d = Domain::new(curves).unwrap();
        let field = WindingField::new(&d, crate::DEFAULT_RELATIVE_TOLERANCE).unwrap();
        let fast = FastWindingField::new(&field);
        let pieces = field.pieces().len();
        assert!(chains_of(field.pieces()).len() > 2 * LEFT_CHAINS);
        let mut seen = 0;
        check(&fast, fast.nodes.len() as u32 - 1, 0, pieces, &mut seen);
        assert_eq!(seen, fast.nodes.len());
    }

    /// A field of many pieces sharing heights exactly: a zigzag of segments whose ends repeat
    /// three heights, horizontal and vertical steps, open arcs and circles (220 pieces).
    fn shared_heights() -> Domain {
        let zigzag: Vec<Point> = (0..120)
            .map(|k| Point::new(k as f64 * 0.1, (k % 3) as f64 * 0.5))
            .collect();
        let mut curves = vec![rs_spline::polyline(&zigzag).unwrap()];
        let steps: Vec<Point> = (0..60)
            .map(|k| Point::new((k / 2) as f64 * 0.2, ((k + 1) / 2) as f64 * 0.25))
            .collect();
        curves.push(rs_spline::polyline(&steps).unwrap());
        // A star: segments through one point, at their middles, the later ones reaching less
        // far right (so a query there refines them out of boundary order unless sorted).
        for (m, n) in [(5.0, 1.0), (4.0, 3.0), (3.0, -2.0), (2.0, 5.0), (1.0, -4.0)] {
            let c = Point::new(20.0, 10.0);
            curves.push(segment(c - Point::new(m, n), c + Point::new(m, n)).unwrap());
        }
        for k in 0..12 {
            let c = Point::new(k as f64, 3.0 + (k % 2) as f64);
            curves.push(circular_arc(c, 0.75, 0.0, 4.0).unwrap());
            curves.push(rs_spline::circle(c, 0.25).unwrap());
        }
        Domain::new(curves).unwrap()
    }

    /// A comb of 600 teeth as tall as the comb, one polyline: its rows coarsen, and the rows
    /// holding the teeth's ends are left to the walk.
    fn comb() -> Domain {
        let teeth: Vec<Point> = (0..1200)
            .map(|k| Point::new((k / 2) as f64, if (k + 1) % 4 < 2 { 0.0 } else { 100.0 }))
            .collect();
        Domain::new(vec![rs_spline::polyline(&teeth).unwrap()]).unwrap()
    }

    /// Reading a large field's span rows gives the walk's sums bit for bit, and the same
    /// near marks: on the GWN paper's three large shapes, a field of shared heights and a comb
    /// (some of whose rows are left to the walk), at
    /// every leaf's box sides, its chord's ends and the floats beside them, on the pieces'
    /// ends (where coincidence terms add) with and without the piece skipped, and at random
    /// points.
    #[test]
    fn span_rows_give_the_walks_sums_bit_for_bit() {
        let mut domains = vec![("shared heights".to_string(), shared_heights())];
        for name in ["butterfly", "rose", "fish"] {
            domains.push((name.to_string(), rs_testkit::gwn_shape(name)));
        }
        domains.push(("comb".to_string(), comb()));
        for (name, d) in domains {
            let field = WindingField::new(&d, crate::DEFAULT_RELATIVE_TOLERANCE).unwrap();
            let fast = FastWindingField::new(&field);
            let rows = fast.span_rows.as_ref();
            assert!(rows.is_some(), "{name}: {} pieces", field.pieces().len());
            // The comb leaves rows to the walk; on the GWN shapes every query takes the span
            // rows (the field of shared heights has some of each).
            let walked = rows.map_or(0, |r| r.rows_left_to_walk());
            assert!(rows.is_some_and(|r| r.spans_in_order()), "{name}");
            match name.as_str() {
                "comb" => assert!(walked > 0, "{name}"),
                "shared heights" => {}
                _ => assert_eq!(walked, 0, "{name}: {walked} rows left to the walk"),
            }
            let mut queries: Vec<(Point, Vec<u32>)> = Vec::new();
            let around = |v: f64| [v.next_down(), v, v.next_up()];
            for l in leaves(&fast.nodes, &fast.chords) {
                let (a, b) = l.chord;
                let ys = [l.lo.y, l.hi.y, a.y, b.y, 0.5 * (l.lo.y + l.hi.y)];
                let xs = [l.lo.x, l.hi.x, a.x, b.x, 0.5 * (l.lo.x + l.hi.x)];
                for y in ys.into_iter().flat_map(around) {
                    for x in xs.into_iter().flat_map(around) {
                        queries.push((Point::new(x, y), Vec::new()));
                    }
                }
                let middle = Point::new(0.5 * (a.x + b.x), 0.5 * (a.y + b.y));
                for e in [a, b, middle] {
                    queries.push((e, Vec::new()));
                    queries.push((e, vec![l.piece]));
                }
            }
            let bb = d.bounding_box();
            let mut seed = 52u64;
            for _ in 0..20_000 {
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let u = (seed >> 11) as f64 / (1u64 << 53) as f64;
                seed = seed
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let v = (seed >> 11) as f64 / (1u64 << 53) as f64;
                let q = Point::new(
                    bb.min.x - 0.1 * bb.width() + 1.2 * u * bb.width(),
                    bb.min.y - 0.1 * bb.height() + 1.2 * v * bb.height(),
                );
                queries.push((q, Vec::new()));
            }
            let (inf, mid) = (f64::INFINITY, bb.min + (bb.max - bb.min) * 0.5);
            for q in [
                Point::new(inf, mid.y),
                Point::new(-inf, mid.y),
                Point::new(mid.x, inf),
                Point::new(inf, inf),
            ] {
                queries.push((q, Vec::new()));
            }
            let (mut stack, mut stats) = ([0; STACK], QueryStats::default());
            let mut near = 0;
            for (q, skip) in &queries {
                let rows = fast.crossing_sum(*q, skip, &mut stack, &mut stats);
                let mut walk = WindingSum::tracking(*q, field.near_reach());
                fast.walk_tree(*q, skip, &mut stack, &mut walk, &mut stats);
                assert_eq!(
                    rows.value().to_bits(),
                    walk.value().to_bits(),
                    "{name} at {q:?} skipping {skip:?}: {} vs {}",
                    rows.value(),
                    walk.value()
                );
                assert_eq!(rows.near(), walk.near(), "{name} at {q:?}");
                near += usize::from(rows.near());
            }
            assert!(
                near > 1000,
                "{name}: {near} of {} queries near",
                queries.len()
            );
        }
    }

    /// Batches answered in their locality order give each point its own value, bit for bit,
    /// in its place: random points over a shape's box, points near its curves, a grid row by
    /// row (taken as it comes), points far outside, on the curves' ends and not numbers; in
    /// batches of fewer points than the order takes, of one block and of several blocks, for
    /// the winding numbers and the locations, on one thread and in parallel tasks.
    #[test]
    fn batches_in_locality_order_give_each_point_its_own_value() {
        for name in ["twirl", "fish"] {
            let d = rs_testkit::gwn_shape(name);
            let field = WindingField::new(&d, crate::DEFAULT_RELATIVE_TOLERANCE).unwrap();
            let (lo, hi) = {
                let b = d.bounding_box();
                (b.min, b.max)
            };
            let (w, h) = (hi.x - lo.x, hi.y - lo.y);
            let mut rng = rs_testkit::XorShift64::new(7);
            let mut random = |count: usize| rng.points_around(&d, 0.1, count);
            let mut near = Vec::new();
            for (k, (_, b)) in d.bezier_pieces().into_iter().enumerate() {
                for j in 0..=64 {
                    let t = j as f64 / 64.0;
                    let (p, tangent) = b.point_and_tangent(t);
                    let s = 10f64.powi(-(((j + k) % 12) as i32)) / tangent.length().max(1e-300);
                    near.push(Point::new(p.x - s * tangent.y, p.y + s * tangent.x));
                    near.push(p);
                }
            }
            let grid: Vec<Point> = (0..200 * 200)
                .map(|k| {
                    Point::new(
                        lo.x + w * (k % 200) as f64 / 199.0,
                        lo.y + h * (k / 200) as f64 / 199.0,
                    )
                })
                .collect();
            let odd = [
                Point::new(f64::NAN, lo.y),
                Point::new(lo.x, f64::NAN),
                Point::new(f64::INFINITY, 0.0),
                Point::new(1e300, -1e300),
            ];
            let mut mixed = random(3 * LOCALITY_BLOCK / 2);
            mixed.extend_from_slice(&near);
            mixed.extend_from_slice(&odd);
            let mut shuffled = near.clone();
            shuffled.extend(random(5000));
            let mut swaps = rs_testkit::XorShift64::new(11);
            for i in (1..shuffled.len()).rev() {
                shuffled.swap(i, (swaps.next_u64() % (i as u64 + 1)) as usize);
            }
            let batches: Vec<(&str, Vec<Point>)> = vec![
                ("few", random(crate::locality::MIN_ORDERED - 1)),
                ("shuffled", shuffled),
                ("grid", grid),
                ("blocks", mixed),
            ];
            let fast = FastWindingField::new(&field);
            for (what, points) in batches {
                let values = fast.winding_numbers(&points);
                let parallel = fast.winding_numbers_parallel(&points);
                let mut locations = vec![Location::Outside; points.len()];
                fast.values_into(&points[..], &mut locations);
                for (i, &q) in points.iter().enumerate() {
                    let want = fast.winding_number(q).to_bits();
                    assert_eq!(values[i].to_bits(), want, "{name} {what} {i}: {q:?}");
                    assert_eq!(parallel[i].to_bits(), want, "{name} {what} {i}: {q:?}");
                    let location = PointQuery::<Location>::value(&fast, q);
                    assert_eq!(locations[i], location, "{name} {what} {i}: {q:?}");
                }
            }
        }
    }
}
