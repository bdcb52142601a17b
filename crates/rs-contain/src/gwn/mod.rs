//! Generalized winding numbers for collections of rational Bezier and NURBS curves
//! (Spainhour, Gunderman and Weiss 2024).

mod curve;
mod fast;
mod raycast;
mod sum;

use rs_boxes::{BoxGrid, BoxOptions, MonotoneBoxes};
use std::sync::Arc;

use rs_spline::prelude::*;
use rs_spline::{Domain, Point, RationalBezier};

use crate::{ContainError, Locate, Location};
use curve::{SubCurve, control_box, misses_cut, refine};
use sum::{ChainEnds, WindingSum};

pub use curve::curve_winding_number;
pub use fast::{CurveHierarchy, FastWindingField, HIERARCHY_DEPTH};

/// Work counters of one or more queries, for the paper's comparison (its Fig. 15 and 16).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct QueryStats {
    /// Curves and sub-curves examined (a bounding-box or hull test, or a clipping step).
    pub curve_evaluations: usize,
    /// Bisections or clippings performed.
    pub subdivisions: usize,
}

/// How the per-curve winding number is computed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum WindingAlgorithm {
    /// The paper's adaptive algorithm (Algorithms 1-5): exact, robust at coincident points.
    #[default]
    Adaptive,
    /// Ray casting by geometric binary search, inside the closure framework (baseline).
    BinarySearch,
    /// Ray casting by Bezier clipping, inside the closure framework (baseline).
    BezierClipping,
}

/// Rule turning the winding-number field into containment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum FillRule {
    /// Inside when the rounded winding number is odd. Agrees with the crossing-number methods
    /// whatever the loops' orientation. The default.
    #[default]
    EvenOdd,
    /// Inside when the rounded winding number is not zero.
    NonZero,
}

/// The generalized winding-number field of a collection of curves.
///
/// # Semantics
/// - Any collection: closed or open loops, gaps, overlaps, reversed curves. NURBS curves are
///   split into rational Bezier pieces by knot insertion. The value at `q` is the sum over the
///   pieces of the angle each subtends at `q`, over `2 pi`: an integer for closed loops (1
///   inside a counter-clockwise loop, 2 inside a doubly wound one), a real number near a gap.
/// - Exact up to floating point at any distance (see [`curve_winding_number`]); no tolerance
///   ever treats a curved piece as straight.
/// - Evaluation: each piece is replaced by the chords of the adaptive algorithm (its own chord
///   when `q` is outside its control box, which takes two comparisons when the box does not
///   reach the horizontal ray from `q` towards `-x`). The angles are not added one `atan2` at
///   a time: the chords' signed crossings of that ray are counted (exact integers), and each
///   open chain of pieces adds the angle between its two ends, once; a closed chain adds
///   nothing. So a query costs no `atan2` at all on a closed boundary.
/// - At points on a curve, the average across the jump (the paper's section 6).
/// - Containment: points within the boundary tolerance (the same band as the crossing-number
///   methods, relative `1e-12` of the bounding-box diagonal by default) are
///   [`Location::Boundary`]; otherwise the winding number is rounded to the nearest integer and
///   the [`FillRule`] decides.
///
/// # Examples
///
/// ```
/// use rs_contain::{FillRule, Locate, Location, WindingField};
/// use rs_spline::{circle, Domain, Point};
/// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let f = WindingField::new(&d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
/// assert!((f.winding_number(Point::new(0.3, 0.2)) - 1.0).abs() < 1e-14);
/// assert!((f.winding_number(Point::new(1.0, 0.0)) - 0.5).abs() < 1e-14); // on the curve
/// let nonzero = f.with_fill_rule(FillRule::NonZero);
/// assert_eq!(nonzero.locate(Point::new(2.0, 0.0)), Location::Outside);
/// ```
#[derive(Clone, Debug)]
pub struct WindingField {
    pieces: Vec<RationalBezier>,
    /// Per piece: its control box and chord, for the far-field test.
    frames: Vec<PieceFrame>,
    /// Per piece: its whole curve as the adaptive algorithm's first sub-curve.
    roots: Vec<SubCurve>,
    /// Start and end of every open chain of pieces (see [`chains`]).
    open_chains: ChainEnds,
    boxes: Arc<MonotoneBoxes>,
    grid: BoxGrid,
    tol: f64,
    rule: FillRule,
}

impl WindingField {
    /// The field of every curve of `domain`, with boundary tolerance `relative_tolerance`
    /// times the bounding-box diagonal, and the even-odd fill rule.
    ///
    /// # Errors
    /// [`ContainError::InvalidTolerance`], [`ContainError::Boxes`].
    pub fn new(domain: &Domain, relative_tolerance: f64) -> Result<Self, ContainError> {
        if !(relative_tolerance.is_finite() && relative_tolerance >= 0.0) {
            return Err(ContainError::InvalidTolerance(relative_tolerance));
        }
        let boxes = MonotoneBoxes::new(domain, BoxOptions::default())?;
        Ok(Self::from_shared_boxes(
            domain,
            Arc::new(boxes),
            relative_tolerance,
        ))
    }

    /// The field over boxes built before from the same domain; `relative_tolerance` already
    /// checked.
    pub(crate) fn from_shared_boxes(
        domain: &Domain,
        boxes: Arc<MonotoneBoxes>,
        relative_tolerance: f64,
    ) -> Self {
        let tol = relative_tolerance * boxes.bounding_box().diagonal();
        let pieces: Vec<RationalBezier> =
            domain.bezier_pieces().into_iter().map(|(_, b)| b).collect();
        let grid = BoxGrid::new(boxes.boxes(), tol);
        Self {
            frames: pieces.iter().map(PieceFrame::of).collect(),
            roots: pieces.iter().map(SubCurve::of).collect(),
            open_chains: ChainEnds::new(
                chains(&pieces)
                    .into_iter()
                    .map(|r| (pieces[r.start].start_point(), pieces[r.end - 1].end_point()))
                    .filter(|(s, e)| s != e)
                    .collect(),
            ),
            pieces,
            boxes,
            grid,
            tol,
            rule: FillRule::EvenOdd,
        }
    }

    /// The same field answering [`Locate`] with fill rule `rule`.
    pub fn with_fill_rule(mut self, rule: FillRule) -> Self {
        self.rule = rule;
        self
    }

    /// The fill rule of [`Locate`].
    pub fn fill_rule(&self) -> FillRule {
        self.rule
    }

    /// The monotone boxes of the collection's curves.
    pub fn monotone_boxes(&self) -> &MonotoneBoxes {
        &self.boxes
    }

    /// The rational Bezier pieces of the collection.
    pub fn pieces(&self) -> &[RationalBezier] {
        &self.pieces
    }

    /// The generalized winding number at `q` (adaptive algorithm).
    pub fn winding_number(&self, q: Point) -> f64 {
        self.adaptive_winding_number(q, &mut QueryStats::default())
    }

    /// Every piece by the adaptive algorithm, the far ones by their box alone, added as
    /// crossings and chain ends (see the type's Semantics). No allocation for pieces of
    /// degree <= 3.
    fn adaptive_winding_number(&self, q: Point, stats: &mut QueryStats) -> f64 {
        let mut sum = WindingSum::new(q);
        for (f, root) in self.frames.iter().zip(&self.roots) {
            if misses_cut(f.lo, f.hi, q) {
                // No crossing, and q is not on the chord.
                stats.curve_evaluations += 1;
            } else if q.x > f.hi.x {
                stats.curve_evaluations += 1;
                sum.left_crossing(f.start, f.end);
            } else {
                refine(root.clone(), q, &mut sum, stats);
            }
        }
        self.add_open_chain_ends(std::slice::from_mut(&mut sum));
        sum.value()
    }

    /// The turns between the ends of every open chain, added to each of `sums`.
    pub(crate) fn add_open_chain_ends(&self, sums: &mut [WindingSum]) {
        if !self.open_chains.is_empty() {
            self.open_chains.add_to(sums);
        }
    }

    /// The generalized winding number at `q` with a chosen algorithm, adding its work to
    /// `stats`.
    pub fn winding_number_with(
        &self,
        q: Point,
        algorithm: WindingAlgorithm,
        stats: &mut QueryStats,
    ) -> f64 {
        if algorithm == WindingAlgorithm::Adaptive {
            return self.adaptive_winding_number(q, stats);
        }
        self.pieces
            .iter()
            .map(|c| match algorithm {
                WindingAlgorithm::Adaptive => curve_winding_number(c, q, stats),
                WindingAlgorithm::BinarySearch => {
                    raycast::ray_winding_number(c, q, raycast::RayCaster::BinarySearch, stats)
                }
                WindingAlgorithm::BezierClipping => {
                    raycast::ray_winding_number(c, q, raycast::RayCaster::BezierClipping, stats)
                }
            })
            .sum()
    }

    /// True if `q` is within the boundary tolerance of a curve.
    pub fn is_on_boundary(&self, q: Point) -> bool {
        let boxes = self.boxes.boxes();
        self.grid
            .candidates(q)
            .iter()
            .any(|&i| boxes[i as usize].is_near(q, self.tol))
    }

    /// Inside or outside from a winding number off the boundary: rounded, then the fill rule.
    pub(crate) fn location_from_winding(&self, w: f64, rule: FillRule) -> Location {
        let w = w.round() as i64;
        let inside = match rule {
            FillRule::EvenOdd => w.rem_euclid(2) == 1,
            FillRule::NonZero => w != 0,
        };
        if inside {
            Location::Inside
        } else {
            Location::Outside
        }
    }
}

impl Locate for WindingField {
    /// Boundary within the tolerance, otherwise the rounded winding number and the fill rule.
    fn locate(&self, q: Point) -> Location {
        if self.is_on_boundary(q) {
            return Location::Boundary;
        }
        self.location_from_winding(self.winding_number(q), self.rule)
    }
}

/// What the far-field test needs of a piece: its control box and its chord.
#[derive(Clone, Copy, Debug)]
struct PieceFrame {
    lo: Point,
    hi: Point,
    start: Point,
    end: Point,
}

impl PieceFrame {
    fn of(b: &RationalBezier) -> Self {
        let p = b.control_points();
        let (lo, hi) = control_box(p);
        Self {
            lo,
            hi,
            start: p[0],
            end: p[p.len() - 1],
        }
    }
}

/// The maximal runs of pieces in which each piece starts exactly (bit for bit) where the
/// previous one ends, as index ranges.
pub(crate) fn chains(pieces: &[RationalBezier]) -> Vec<std::ops::Range<usize>> {
    let mut out: Vec<std::ops::Range<usize>> = Vec::new();
    for (i, b) in pieces.iter().enumerate() {
        match out.last_mut() {
            Some(r) if pieces[r.end - 1].end_point() == b.start_point() => r.end = i + 1,
            _ => out.push(i..i + 1),
        }
    }
    out
}
