//! Accelerated generalized winding numbers: a bounding-volume hierarchy over the pieces with
//! exact chain shortcuts, and a precomputed subdivision hierarchy per piece.

use rs_spline::prelude::*;
use std::f64::consts::TAU;

use rs_spline::{Point, RationalBezier};

use super::curve::{SubCurves, adaptive_winding, chord_angle, is_simple_convex};
use super::{QueryStats, WindingField};
use crate::{Locate, Location};

/// Levels of each piece's precomputed subdivision hierarchy (`2^(d+1) - 1` sub-curves).
pub const HIERARCHY_DEPTH: u32 = 6;

/// One sub-curve of a [`CurveHierarchy`].
#[derive(Clone, Debug)]
struct SubNode {
    curve: RationalBezier,
    /// Simple and convex, with the parent's flag inherited as the adaptive algorithm does.
    convex: bool,
    children: Option<(usize, usize)>,
}

/// The subdivision hierarchy of one piece, computed once and shared, immutable, by all queries:
/// the first [`HIERARCHY_DEPTH`] levels of halving; deeper levels (queries within `2^-6` of the
/// piece's size from it) are computed on the fly.
#[derive(Clone, Debug)]
pub struct CurveHierarchy {
    nodes: Vec<SubNode>,
}

impl CurveHierarchy {
    /// Precomputes the hierarchy of `curve`.
    pub fn new(curve: &RationalBezier) -> Self {
        let mut nodes = vec![SubNode {
            convex: is_simple_convex(curve.control_points()),
            curve: curve.clone(),
            children: None,
        }];
        let mut frontier = vec![(0usize, 0u32)];
        while let Some((i, depth)) = frontier.pop() {
            if depth >= HIERARCHY_DEPTH {
                continue;
            }
            let (l, r) = nodes[i].curve.subdivide();
            let parent_convex = nodes[i].convex;
            let li = nodes.len();
            for half in [l, r] {
                nodes.push(SubNode {
                    convex: parent_convex || is_simple_convex(half.control_points()),
                    curve: half,
                    children: None,
                });
            }
            nodes[i].children = Some((li, li + 1));
            frontier.push((li, depth + 1));
            frontier.push((li + 1, depth + 1));
        }
        Self { nodes }
    }
}

/// A node of the adaptive algorithm: a cached sub-curve, or one computed past the cache.
pub(crate) enum Node {
    Cached(usize),
    Owned(RationalBezier),
}

impl SubCurves for CurveHierarchy {
    type Node = Node;
    fn points<'s>(&'s self, node: &'s Node) -> &'s [Point] {
        match node {
            Node::Cached(i) => self.nodes[*i].curve.control_points(),
            Node::Owned(c) => c.control_points(),
        }
    }
    fn convex(&self, node: &Node, parent_convex: bool) -> bool {
        match node {
            Node::Cached(i) => self.nodes[*i].convex,
            Node::Owned(c) => parent_convex || is_simple_convex(c.control_points()),
        }
    }
    fn halves(&self, node: &Node) -> (Node, Node, bool) {
        match node {
            Node::Cached(i) => match self.nodes[*i].children {
                Some((l, r)) => (Node::Cached(l), Node::Cached(r), false),
                None => {
                    let (l, r) = self.nodes[*i].curve.subdivide();
                    (Node::Owned(l), Node::Owned(r), true)
                }
            },
            Node::Owned(c) => {
                let (l, r) = c.subdivide();
                (Node::Owned(l), Node::Owned(r), true)
            }
        }
    }
}

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

#[derive(Clone, Debug)]
enum Kind {
    Leaf(usize),
    Inner(usize, usize),
}

/// Accelerated generalized winding numbers, equal to [`WindingField`]'s up to rounding.
///
/// # Design
/// - A bounding-volume hierarchy over the pieces in boundary order: each node covers a
///   contiguous run of pieces with the bounding box of their control points. A query outside a
///   node's box whose pieces form one chain from `A` to `B` (each piece ends exactly where the
///   next begins) takes the single angle of the chord `A -> B`: the chain closed by `B -> A`
///   lies in the box, so the query is outside it and has winding number 0 about it, which makes
///   the chain's winding number exactly minus that of the closing chord (the paper's far-field
///   argument applied to a whole subtree). Other nodes are opened; a leaf runs the adaptive
///   algorithm. A query far from a closed boundary therefore costs `O(log N)` angles.
/// - Each piece's first [`HIERARCHY_DEPTH`] levels of bisection are precomputed once
///   ([`CurveHierarchy`]), so queries near the boundary reuse them instead of subdividing.
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
    hierarchies: Vec<CurveHierarchy>,
}

impl<'a> FastWindingField<'a> {
    /// Builds the hierarchy over `field`'s pieces.
    pub fn new(field: &'a WindingField) -> Self {
        let pieces = field.pieces();
        let hierarchies = pieces.iter().map(CurveHierarchy::new).collect();
        let mut nodes = Vec::with_capacity(2 * pieces.len());
        if !pieces.is_empty() {
            build(pieces, 0, pieces.len(), &mut nodes);
        }
        Self {
            field,
            nodes,
            hierarchies,
        }
    }

    /// The generalized winding number at `q`.
    pub fn winding_number(&self, q: Point) -> f64 {
        self.winding_number_counted(q, &mut QueryStats::default())
    }

    /// The generalized winding number at `q`, adding the work done to `stats` (a shortcut
    /// angle counts as one curve evaluation).
    pub fn winding_number_counted(&self, q: Point, stats: &mut QueryStats) -> f64 {
        if self.nodes.is_empty() {
            return 0.0;
        }
        let mut total = 0.0;
        let mut stack: Vec<usize> = Vec::with_capacity(64);
        stack.push(self.nodes.len() - 1);
        while let Some(i) = stack.pop() {
            let n = &self.nodes[i];
            let outside = q.x < n.lo.x || q.x > n.hi.x || q.y < n.lo.y || q.y > n.hi.y;
            if outside && n.chain {
                stats.curve_evaluations += 1;
                total += chord_angle(q, n.a, n.b) / TAU;
                continue;
            }
            match n.kind {
                Kind::Leaf(p) => {
                    let h = &self.hierarchies[p];
                    total += adaptive_winding(h, Node::Cached(0), q, stats);
                }
                Kind::Inner(l, r) => {
                    stack.push(r);
                    stack.push(l);
                }
            }
        }
        total
    }

    /// Winding numbers of many points, in input order, on the current thread.
    pub fn winding_numbers(&self, points: &[Point]) -> Vec<f64> {
        points.iter().map(|&q| self.winding_number(q)).collect()
    }

    /// Winding numbers of many points, split over rayon's thread pool (with the `parallel`
    /// feature, on by default; otherwise on the current thread).
    pub fn winding_numbers_parallel(&self, points: &[Point]) -> Vec<f64> {
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            points
                .par_iter()
                .with_min_len(1024)
                .map(|&q| self.winding_number(q))
                .collect()
        }
        #[cfg(not(feature = "parallel"))]
        {
            self.winding_numbers(points)
        }
    }
}

impl Locate for FastWindingField<'_> {
    /// As the [`WindingField`]'s [`Locate`], with its fill rule, from the fast winding number.
    fn locate(&self, q: Point) -> Location {
        if self.field.is_on_boundary(q) {
            return Location::Boundary;
        }
        self.field
            .location_from_winding(self.winding_number(q), self.field.fill_rule())
    }
}

/// Builds the subtree over pieces `[i, j)`; returns its index (children before parents).
fn build(pieces: &[RationalBezier], i: usize, j: usize, nodes: &mut Vec<BvhNode>) -> usize {
    let (a, b) = (pieces[i].start_point(), pieces[j - 1].end_point());
    let chain = (i + 1..j).all(|k| pieces[k - 1].end_point() == pieces[k].start_point());
    let kind = if j - i == 1 {
        Kind::Leaf(i)
    } else {
        let m = (i + j) / 2;
        Kind::Inner(build(pieces, i, m, nodes), build(pieces, m, j, nodes))
    };
    let (mut lo, mut hi) = (a, a);
    for p in pieces[i..j].iter().flat_map(|c| c.control_points()) {
        lo = Point::new(lo.x.min(p.x), lo.y.min(p.y));
        hi = Point::new(hi.x.max(p.x), hi.y.max(p.y));
    }
    nodes.push(BvhNode {
        lo,
        hi,
        a,
        b,
        chain,
        kind,
    });
    nodes.len() - 1
}
