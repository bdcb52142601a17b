//! Generalized winding numbers for collections of rational Bezier and NURBS curves
//! (Spainhour, Gunderman and Weiss 2024).

#[cfg(test)]
mod compact_tests;
mod curve;
mod far_cells;
mod fast;
mod implicit_side;
mod inverse_fit;
#[cfg(test)]
mod lazy_tests;
mod monotone;
mod on_boundary;
mod raycast;
#[cfg(test)]
mod side_cases;
mod span_rows;
mod split_cells;
mod sum;

use rs_boxes::{BoxError, BoxGrid, BoxOptions, MonotoneBoxes};
use smallvec::SmallVec;
use std::sync::{Arc, OnceLock};

use rs_spline::limits::NonNegative;
use rs_spline::prelude::*;
use rs_spline::{Domain, Point, RationalBezier};

use crate::{ContainError, Location, PointQuery, PointSource};
use curve::{SubCurve, control_box, misses_cut, outside, refine};
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

impl std::str::FromStr for WindingAlgorithm {
    type Err = String;

    /// The command line's names: `adaptive`, `binary-search`, `bezier-clipping` (any case).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "adaptive" => Ok(Self::Adaptive),
            "binary-search" => Ok(Self::BinarySearch),
            "bezier-clipping" => Ok(Self::BezierClipping),
            _ => Err(format!(
                "unknown winding algorithm {s:?} (expected adaptive, binary-search or bezier-clipping)"
            )),
        }
    }
}

/// Rule turning the winding-number field into containment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum FillRule {
    /// Inside when the rounded winding number is odd. Agrees with the crossing-number methods
    /// whatever the loops' orientation. The default.
    #[default]
    EvenOdd,
    /// Inside when the rounded winding number is not zero.
    NonZero,
}

impl FillRule {
    /// Whether a point of winding number `w` (off the boundary) is in the filled set: `w` odd
    /// for [`FillRule::EvenOdd`], `w != 0` for [`FillRule::NonZero`]. The one definition
    /// of the rules every method and capability applies.
    ///
    /// ```
    /// use rs_contain::FillRule;
    /// assert!(FillRule::EvenOdd.fills(-1) && !FillRule::EvenOdd.fills(2));
    /// assert!(FillRule::NonZero.fills(2) && !FillRule::NonZero.fills(0));
    /// ```
    #[inline]
    pub const fn fills(self, w: i64) -> bool {
        match self {
            Self::EvenOdd => w.rem_euclid(2) == 1,
            Self::NonZero => w != 0,
        }
    }

    /// The rule's name, as [`FromStr`](std::str::FromStr) reads it: `even-odd` or `nonzero`.
    pub const fn as_str(self) -> &'static str {
        match self {
            Self::EvenOdd => "even-odd",
            Self::NonZero => "nonzero",
        }
    }
}

impl std::fmt::Display for FillRule {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

impl std::str::FromStr for FillRule {
    type Err = String;

    /// `even-odd` (or `evenodd`) and `nonzero` (or `non-zero`), in any case.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "even-odd" | "evenodd" => Ok(Self::EvenOdd),
            "nonzero" | "non-zero" => Ok(Self::NonZero),
            _ => Err(format!(
                "unknown fill rule {s:?} (expected even-odd or nonzero)"
            )),
        }
    }
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
/// - At points on a curve, and at every point within the boundary tolerance of one (the band
///   [`WindingField::is_on_boundary`] tests, relative `1e-12` of the bounding-box diagonal by
///   default), the average across the jump (the paper's section 6): `0` inside a straight
///   piece, `1/2` on a smooth closed curve, the interior angle over `2 pi` at a corner, the
///   angle from the tangent to the far end at an end of an open chain; every algorithm gives
///   it. Outside the band the value is exact.
/// - Containment: points within the boundary tolerance (the same band as the crossing-number
///   methods, relative `1e-12` of the bounding-box diagonal by default) are
///   [`Location::Boundary`]; otherwise the winding number is rounded to the nearest integer and
///   the [`FillRule`] decides.
///
/// # Construction: what is built when
/// - The constructors build what every query reads: the rational Bezier pieces, per piece its
///   far-field frame (its control box grown by the reach of the band, see below) and its
///   first sub-curve, and the ends of the open chains. That is linear in the pieces, with no
///   root finding and a few allocations per field (besides the pieces' own control points).
/// - The *boundary index* (the monotone boxes, which piece each box lies on, the grid of the
///   boxes, and the exact tolerance, which is relative to the boxes' bounding box) is built on
///   the first query that may be in the band: a query the adaptive walk finds within the
///   band's reach of a piece ([`WindingField::is_on_boundary`], the average across the jump,
///   [`WindingField::monotone_boxes`]). It is built once, by whichever thread needs it first
///   (`OnceLock`), and shared. A query farther than the reach from every piece never builds
///   it. The reach is twice the tolerance, plus the widest gap between consecutive pieces, plus
///   a bound on the rounding of the pieces' splits, which grows with their degree, their
///   weight ratio and the boxes per monotone piece: about `4e-12` of the largest coordinate for
///   cubic polynomial pieces.
/// - A field made by a [`crate::Classifier`] ([`crate::Classifier::winding_field`]) shares the
///   classifier's monotone boxes instead of building its own; only their grid is built on
///   first need.
/// - If the monotone boxes cannot be built (a piece whose tangency roots cannot be computed,
///   which the input limits of `rs_spline::limits` leave no known way to reach), no point is
///   in the band: every answer is the exact winding number, [`WindingField::monotone_boxes`]
///   reports the error.
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
    /// Per piece: the box where a query may be near it, and its chord, for the far-field test.
    frames: Vec<PieceFrame>,
    /// The union of the frames' boxes: a query outside it is in no piece's band.
    near_lo: Point,
    /// See `near_lo`.
    near_hi: Point,
    /// Per piece: the index of its curve in the domain (which monotone boxes lie on it).
    piece_curves: Vec<u32>,
    /// The widest gap between consecutive pieces of a loop: the monotone boxes close every
    /// joint, so they lie this far from the pieces at most.
    joint_gap: f64,
    /// How far a query may be from the pieces and still be in the band: at least twice the
    /// tolerance, the rounding margin and the joint gap (see [`BandReach`]).
    reach: f64,
    /// Per piece: its whole curve as the adaptive algorithm's first sub-curve.
    roots: Vec<SubCurve>,
    /// Start and end of every open chain of pieces (see [`chains`]).
    open_chains: ChainEnds,
    /// Where the monotone boxes come from (given, or built from the domain).
    source: BoxSource,
    /// The boundary index, built on first need (see the type's Construction).
    index: OnceLock<Result<BoundaryIndex, BoxError>>,
    relative_tolerance: f64,
    rule: FillRule,
}

/// Where a field's monotone boxes come from.
#[derive(Clone, Debug)]
enum BoxSource {
    /// Built before (by a classifier of the same domain) and shared.
    Given(Arc<MonotoneBoxes>),
    /// Built from this domain, with the default options, on first need.
    Domain(Arc<Domain>),
}

/// What the band tests read: the monotone boxes, the piece of each, their grid and the exact
/// tolerance and rounding margin (both relative to the boxes' bounding box).
#[derive(Clone, Debug)]
struct BoundaryIndex {
    boxes: Arc<MonotoneBoxes>,
    /// Per monotone box: the piece it lies on.
    box_pieces: Vec<u32>,
    grid: BoxGrid,
    /// The boundary tolerance: the relative tolerance times the boxes' bounding-box diagonal.
    tol: f64,
    /// A bound on the rounding of coordinates near the boundary (a few ulps of the largest).
    rounding: f64,
}

/// The band's own rounding margin, in units of `f64::EPSILON` times the boxes' coordinate
/// scale (see [`BoundaryIndex::rounding`]).
const BAND_ROUNDING_ULPS: f64 = 256.0;

/// Roundings [`relative_band_margin`] counts as one split more each: the products `x w` that
/// make a piece's homogeneous coordinates, the band's root solve (a root to within about half
/// a unit in the last place of its parameter, which moves the point by `|x'|` times that, and
/// `|x'| <= d rho` times the scale on `[0, 1]`) and the evaluation at the root.
const SPLIT_LIKE: usize = 3;

/// The factor by which [`relative_band_margin`] exceeds the error bound it covers: for the
/// rounding of the few operations that compute the bound and the reach, and for the
/// second-order terms the bound leaves out.
const MARGIN_SAFETY: f64 = 8.0;

/// The relative margin (times the pieces' coordinate scale) that covers every rounding between
/// the exact pieces and the curves the band and the walk test: the monotone boxes' curves (the
/// band) and the adaptive walk's sub-curves (the near mark), plus the band's own rounding
/// margin ([`BAND_ROUNDING_ULPS`]). Computed per field from the pieces' largest degree `d`,
/// their largest weight ratio `rho = max w / min w` (1 for polynomial pieces) and the most
/// refined boxes per monotone piece, `subdivisions`.
///
/// Why it covers them: a box's curve comes from its watertight piece (the joint gap, counted
/// apart) by at most `S = (4d - 4) + (subdivisions - 1)` de Casteljau splits in homogeneous
/// coordinates, each applied to the part the previous one left: the roots of the numerators of
/// `x'` and `y'` (degree `2d - 2` each), then the sub-boxes cut off one by one. A walk's
/// sub-curve comes from its piece by at most `MAX_DEPTH` halvings. One split at `s` of `d + 1`
/// coefficients rounds each level's blend `a (1 - s) + b s` by at most `3 u max(|a|, |b|)`
/// (`u = eps / 2`: `1 - s`, two products and a sum), and the blends of the later levels, convex
/// combinations, do not grow the earlier levels' errors; so a split moves each coefficient by
/// at most `3 d u M`, `M` the largest magnitude of the coefficients split, which no split grows
/// (its coefficients are convex combinations). The exact split being a convex combination too,
/// the errors of consecutive splits add: after `S` of them the homogeneous coefficients are
/// within `3 d S u M` of the exact sub-curve's, `M <= w_max scale` for the coordinates and
/// `w_max` for the weights. A point `H(t) / W(t)` then moves by at most
/// `(dH + |x| dW) / W(t) <= 6 d S u rho scale` (`W(t) >= w_min`), and the projection of the
/// control points rounds by `u scale` more. With [`SPLIT_LIKE`] roundings counted as splits,
/// and the walk's halvings on top (the band's point and the walk's sub-curve both within their
/// bound of the exact piece), the margin covers
/// `6 d (S + SPLIT_LIKE + MAX_DEPTH) rho + 1 + BAND_ROUNDING_ULPS` units of `eps scale` (each
/// `u` counted as a whole `eps`), times [`MARGIN_SAFETY`]. The tolerance may be 0, so the
/// margin alone must cover them.
///
/// On cubic polynomial pieces with the default 32 boxes per monotone piece that is about
/// `3.8e-12` of the scale. (One fixed margin of `2^-30` of the scale for every field sent each
/// query between this and `1e-9` of the scale through the band's root solves: a quarter of the
/// work on points near the curves.)
fn relative_band_margin(pieces: &[RationalBezier], subdivisions: usize) -> f64 {
    let degree = pieces.iter().map(|b| b.degree()).max().unwrap_or(0);
    let weight_ratio = pieces
        .iter()
        .map(|b| {
            let (lo, hi) = b
                .weights()
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(lo, hi), &w| {
                    (lo.min(w), hi.max(w))
                });
            hi / lo
        })
        .fold(1.0f64, f64::max);
    let splits = (4 * degree).saturating_sub(4) + subdivisions.saturating_sub(1) + SPLIT_LIKE;
    let splits_and_halvings = splits + curve::MAX_DEPTH as usize;
    let ulps =
        6.0 * degree as f64 * splits_and_halvings as f64 * weight_ratio + 1.0 + BAND_ROUNDING_ULPS;
    MARGIN_SAFETY * ulps * f64::EPSILON
}

/// The far-field bounds of the band, computed from the pieces alone (the boxes and their exact
/// tolerance come later).
#[derive(Clone, Copy, Debug)]
struct BandReach {
    /// How far from a piece's control box a query may be and still be in the band of one of
    /// its boxes: `2 tol' + margin + joint_gap`, where `tol' >= tol` is the relative tolerance
    /// times the diagonal of the pieces' control box grown by the joint gap and the margin,
    /// and `margin` is [`relative_band_margin`] times the scale.
    reach: f64,
}

impl BandReach {
    /// The reach for pieces whose control boxes' union is `[lo, hi]`, `joint_gap` apart at most.
    ///
    /// Why it holds: the monotone boxes' pieces are the domain's pieces made watertight (the
    /// first control point of each moved onto the end of the one before, at most `joint_gap`
    /// away), split. Moving one control point by `d` moves every point of a rational Bezier
    /// curve with positive weights by at most `d` (the rational basis functions are `>= 0` and
    /// add up to 1), and every point of a piece lies in its control box, so every point of a
    /// box's curve lies within `joint_gap` of its piece's control box, plus the splits'
    /// rounding (below `relative_margin * scale`, see [`relative_band_margin`]). The boxes'
    /// bounding box therefore lies in `[lo, hi]` grown by `joint_gap + margin`, so its
    /// diagonal, and with it the exact tolerance `tol`, is at most the bound's (`hypot` and
    /// the products are monotone, and the margin dwarfs their rounding). A point in the band
    /// of a box is within `tol` of the box's curve, measured vertically, horizontally or from
    /// an end, up to the solve's rounding; so it lies within `tol + joint_gap + margin <=
    /// reach` of its piece's control box. `reach` is also at least the band's own reach,
    /// `2 tol + rounding + joint_gap` (the margin holds the rounding margin,
    /// [`BAND_ROUNDING_ULPS`], at a scale below the bound's). The walk's sub-curves lie within
    /// the margin of the exact piece too, so a query in the band comes within the reach of a
    /// sub-curve the walk settles.
    fn of(
        lo: Point,
        hi: Point,
        joint_gap: f64,
        relative_tolerance: f64,
        relative_margin: f64,
    ) -> Self {
        let scale = coordinate_scale(rs_spline::BoundingBox { min: lo, max: hi });
        let margin = relative_margin * scale;
        let grow = joint_gap + margin;
        let diagonal = rs_spline::BoundingBox { min: lo, max: hi }
            .grown_by(grow)
            .diagonal();
        let tol = relative_tolerance * diagonal;
        // The margin is taken at the grown scale, which may exceed `scale` by `grow`.
        let margin = relative_margin * (scale + 4.0 * grow);
        Self {
            reach: 2.0 * tol + margin + joint_gap,
        }
    }
}

impl WindingField {
    /// The field of every curve of `domain`, with boundary tolerance `relative_tolerance`
    /// times the bounding-box diagonal, and the even-odd fill rule. Builds the pieces and
    /// their frames; the monotone boxes and their grid wait for the first query that may be
    /// in the band (see the type's Construction).
    ///
    /// # Errors
    /// [`ContainError::InvalidTolerance`]. (The monotone boxes are built later; if they cannot
    /// be, see the type's Construction.)
    pub fn new(domain: &Domain, relative_tolerance: f64) -> Result<Self, ContainError> {
        NonNegative::new(relative_tolerance).map_err(|e| ContainError::InvalidTolerance(e.0))?;
        Ok(Self::build(
            domain,
            BoxSource::Domain(Arc::new(domain.clone())),
            relative_tolerance,
        ))
    }

    /// The field over boxes built before from the same domain (shared, not built again);
    /// `relative_tolerance` already checked. Only their grid is built, on first need.
    pub(crate) fn from_shared_boxes(
        domain: &Domain,
        boxes: Arc<MonotoneBoxes>,
        relative_tolerance: f64,
    ) -> Self {
        Self::build(domain, BoxSource::Given(boxes), relative_tolerance)
    }

    /// The pieces, their frames and roots, and the open chains; the boundary index left for
    /// later.
    fn build(domain: &Domain, source: BoxSource, relative_tolerance: f64) -> Self {
        let numbered = domain.bezier_pieces();
        let joint_gap = widest_joint(domain, &numbered);
        let mut piece_curves = Vec::with_capacity(numbered.len());
        let mut pieces = Vec::with_capacity(numbered.len());
        for (c, b) in numbered {
            piece_curves.push(c as u32);
            pieces.push(b);
        }
        let mut frames: Vec<PieceFrame> = pieces.iter().map(PieceFrame::of).collect();
        let rs_spline::BoundingBox { min: lo, max: hi } = frames
            .iter()
            .map(|f| rs_spline::BoundingBox {
                min: f.lo,
                max: f.hi,
            })
            .reduce(rs_spline::BoundingBox::union)
            .unwrap_or(rs_spline::BoundingBox::from_point(Point::default()));
        let subdivisions = match &source {
            BoxSource::Given(boxes) => boxes.subdivisions(),
            BoxSource::Domain(_) => BoxOptions::default().subdivisions,
        };
        let relative_margin = relative_band_margin(&pieces, subdivisions);
        let reach = BandReach::of(lo, hi, joint_gap, relative_tolerance, relative_margin).reach;
        for f in &mut frames {
            f.grow(reach);
        }
        Self {
            frames,
            near_lo: Point::new(lo.x - reach, lo.y - reach),
            near_hi: Point::new(hi.x + reach, hi.y + reach),
            piece_curves,
            joint_gap,
            reach,
            roots: pieces.iter().map(SubCurve::of).collect(),
            open_chains: ChainEnds::new(
                chains(&pieces)
                    .into_iter()
                    .map(|r| (pieces[r.start].start_point(), pieces[r.end - 1].end_point()))
                    .filter(|(s, e)| s != e)
                    .collect(),
            ),
            pieces,
            source,
            index: OnceLock::new(),
            relative_tolerance,
            rule: FillRule::EvenOdd,
        }
    }

    /// The boundary index, built on the first call (see the type's Construction); the error if
    /// the monotone boxes cannot be built.
    fn boundary_index(&self) -> Result<&BoundaryIndex, &BoxError> {
        self.index
            .get_or_init(|| {
                let boxes = match &self.source {
                    BoxSource::Given(b) => Arc::clone(b),
                    BoxSource::Domain(d) => Arc::new(MonotoneBoxes::new(d, BoxOptions::default())?),
                };
                let bbox = boxes.bounding_box();
                let tol = self.relative_tolerance * bbox.diagonal();
                let rounding = BAND_ROUNDING_ULPS * f64::EPSILON * coordinate_scale(bbox);
                Ok(BoundaryIndex {
                    box_pieces: pieces_of_boxes(&self.piece_curves, &self.pieces, &boxes),
                    grid: BoxGrid::new(boxes.boxes(), tol),
                    boxes,
                    tol,
                    rounding,
                })
            })
            .as_ref()
    }

    /// The boundary index if `q` may be in the band (inside the union of the pieces' frames)
    /// and the index can be built; `None` otherwise (then `q` is in no band).
    fn index_near(&self, q: Point) -> Option<&BoundaryIndex> {
        if outside(self.near_lo, self.near_hi, q) {
            return None;
        }
        self.boundary_index().ok()
    }

    /// Has the boundary index been built (or its build been tried)? A probe for the tests of
    /// laziness.
    #[cfg(test)]
    pub(crate) fn boundary_index_built(&self) -> bool {
        self.index.get().is_some()
    }

    /// The same field answering [`Locate`](crate::Locate) with fill rule `rule`.
    pub fn with_fill_rule(mut self, rule: FillRule) -> Self {
        self.rule = rule;
        self
    }

    /// The fill rule of [`Locate`](crate::Locate).
    pub fn fill_rule(&self) -> FillRule {
        self.rule
    }

    /// The monotone boxes of the collection's curves, with their grid: built on the first call
    /// unless a query in the band built them before (see the type's Construction).
    ///
    /// # Errors
    /// [`ContainError::Boxes`] if they cannot be built.
    pub fn monotone_boxes(&self) -> Result<&MonotoneBoxes, ContainError> {
        match self.boundary_index() {
            Ok(index) => Ok(&index.boxes),
            Err(e) => Err(ContainError::Boxes(e.clone())),
        }
    }

    /// Per piece, the corners of the box outside which no query is near it (the far-field
    /// test's box).
    pub(crate) fn near_box(&self, piece: usize) -> (Point, Point) {
        let f = &self.frames[piece];
        (f.lo, f.hi)
    }

    /// The rational Bezier pieces of the collection.
    pub fn pieces(&self) -> &[RationalBezier] {
        &self.pieces
    }

    /// Piece `p`'s whole curve as the adaptive algorithm's first sub-curve.
    pub(crate) fn root(&self, p: usize) -> &SubCurve {
        &self.roots[p]
    }

    /// The generalized winding number at `q` (adaptive algorithm).
    pub fn winding_number(&self, q: Point) -> f64 {
        self.adaptive_winding_number(q, &mut QueryStats::default())
    }

    /// Every piece by the adaptive algorithm, the far ones by their box alone, added as
    /// crossings and chain ends (see the type's Semantics); a query in the band takes
    /// [`WindingField::band_winding_number`]. No allocation for pieces of degree <= 3.
    fn adaptive_winding_number(&self, q: Point, stats: &mut QueryStats) -> f64 {
        let mut sum = WindingSum::tracking(q, self.reach);
        self.add_pieces(q, &[], &mut sum, stats);
        if sum.near()
            && let Some(w) = self.band_winding_number(q, stats)
        {
            return w;
        }
        self.add_open_chain_ends(std::slice::from_mut(&mut sum));
        sum.value()
    }

    /// How far from the pieces a query may be in the band (see [`WindingSum::tracking`]).
    pub(crate) fn near_reach(&self) -> f64 {
        self.reach
    }

    /// Adds every piece but those in `skip` (sorted) to `sum` by the adaptive algorithm. A
    /// piece whose near box holds `q` is refined, which tells `sum` whether `q` may be near it.
    fn add_pieces(&self, q: Point, skip: &[u32], sum: &mut WindingSum, stats: &mut QueryStats) {
        for (i, (f, root)) in self.frames.iter().zip(&self.roots).enumerate() {
            if misses_cut(f.lo, f.hi, q) {
                // No crossing, and q is not on the chord.
                stats.curve_evaluations += 1;
            } else if q.x > f.hi.x {
                stats.curve_evaluations += 1;
                sum.left_crossing(f.start, f.end);
            } else if skip.binary_search(&(i as u32)).is_err() {
                refine(root.clone(), q, sum, stats);
            }
        }
    }

    /// The winding number at a `q` in the band, the average across the jump (see
    /// `on_boundary`); `None` if `q` is not in the band.
    fn band_winding_number(&self, q: Point, stats: &mut QueryStats) -> Option<f64> {
        let passages = self.passages(q);
        if passages.is_empty() {
            return None;
        }
        let skip = passage_pieces(&passages);
        let mut sum = WindingSum::new(q);
        self.add_pieces(q, &skip, &mut sum, stats);
        self.add_passages(q, &passages, &mut sum, stats);
        self.add_open_chain_ends(std::slice::from_mut(&mut sum));
        Some(sum.value())
    }

    /// Each open chain's start and end.
    pub(crate) fn open_chain_ends(&self) -> &[(Point, Point)] {
        self.open_chains.ends()
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
        // The ray-casting baselines need the query off the curves: in the band, the average
        // across the jump as above. Only a query in some piece's frame may be in the band (a
        // scan as long as the baselines' own, which keeps the boxes unbuilt for the others).
        if self.frames.iter().any(|f| !outside(f.lo, f.hi, q))
            && let Some(w) = self.band_winding_number(q, stats)
        {
            return w;
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

    /// True if `q` is within the boundary tolerance of a curve. Builds the boundary index
    /// unless `q` lies outside every piece's frame (see the type's Construction).
    pub fn is_on_boundary(&self, q: Point) -> bool {
        let Some(index) = self.index_near(q) else {
            return false;
        };
        let boxes = index.boxes.boxes();
        index
            .grid
            .candidates(q)
            .iter()
            .any(|&i| boxes[i as usize].is_near(q, index.tol))
    }

    /// Inside or outside from a winding number off the boundary: rounded, then the fill rule.
    pub(crate) fn location_from_winding(&self, w: f64, rule: FillRule) -> Location {
        if rule.fills(w.round() as i64) {
            Location::Inside
        } else {
            Location::Outside
        }
    }
}

impl PointQuery<Location> for WindingField {
    /// Boundary within the tolerance, otherwise the rounded winding number and the fill rule.
    ///
    /// The boundary test runs only for a query the adaptive walk found within reach of a piece
    /// (the walk's near flag): every point of the band is (see the Construction), so the answer is
    /// the one testing every query gives, and a query away from the curves leaves the boundary
    /// index unbuilt.
    fn value(&self, q: Point) -> Location {
        let mut stats = QueryStats::default();
        let mut sum = WindingSum::tracking(q, self.reach);
        self.add_pieces(q, &[], &mut sum, &mut stats);
        if sum.near() {
            if self.is_on_boundary(q) {
                return Location::Boundary;
            }
            if let Some(w) = self.band_winding_number(q, &mut stats) {
                return self.location_from_winding(w, self.rule);
            }
        }
        self.add_open_chain_ends(std::slice::from_mut(&mut sum));
        self.location_from_winding(sum.value(), self.rule)
    }
}

impl WindingField {
    /// What answers winding-number queries with `algorithm`: the accelerated field
    /// ([`FastWindingField`]) for [`WindingAlgorithm::Adaptive`], the field itself for the
    /// ray-casting baselines.
    pub fn winding_numbers_by(&self, algorithm: WindingAlgorithm) -> WindingNumbers<'_> {
        match algorithm {
            WindingAlgorithm::Adaptive => WindingNumbers::Fast(FastWindingField::new(self)),
            other => WindingNumbers::Baseline(self, other),
        }
    }
}

/// Winding numbers with a chosen algorithm, as a [`PointQuery`]`<f64>`: see
/// [`WindingField::winding_numbers_by`].
pub enum WindingNumbers<'a> {
    /// The accelerated adaptive algorithm.
    Fast(FastWindingField<'a>),
    /// A ray-casting baseline of the field.
    Baseline(&'a WindingField, WindingAlgorithm),
}

impl PointQuery<f64> for WindingNumbers<'_> {
    fn value(&self, q: Point) -> f64 {
        match self {
            WindingNumbers::Fast(f) => f.winding_number(q),
            WindingNumbers::Baseline(field, a) => {
                field.winding_number_with(q, *a, &mut QueryStats::default())
            }
        }
    }

    fn values_into<P: PointSource + ?Sized>(&self, points: &P, out: &mut [f64]) {
        match self {
            WindingNumbers::Fast(f) => f.values_into(points, out),
            WindingNumbers::Baseline(field, a) => {
                assert_eq!(points.len(), out.len(), "one value per point");
                let mut stats = QueryStats::default();
                for (i, o) in out.iter_mut().enumerate() {
                    *o = field.winding_number_with(points.point(i), *a, &mut stats);
                }
            }
        }
    }
}

/// The scale of coordinates in box `b`: the larger of its diagonal and its largest absolute
/// coordinate (what a rounding margin is relative to).
fn coordinate_scale(b: rs_spline::BoundingBox) -> f64 {
    [b.min.x, b.min.y, b.max.x, b.max.y]
        .iter()
        .fold(b.diagonal(), |m, v| m.max(v.abs()))
}

/// The widest gap between consecutive pieces of one loop of `domain` (`pieces` as
/// [`Domain::bezier_pieces`] lists them), closing joints included: how far the monotone boxes,
/// which close every joint, may lie from the pieces.
fn widest_joint(domain: &Domain, pieces: &[(usize, RationalBezier)]) -> f64 {
    let mut widest = 0.0f64;
    for l in domain.loops() {
        let curves = l.curves();
        let first = pieces.partition_point(|(c, _)| c < curves.start());
        let end = pieces.partition_point(|(c, _)| c <= curves.end());
        let of_loop = &pieces[first..end];
        for w in of_loop.windows(2) {
            widest = widest.max(w[0].1.end_point().distance(w[1].1.start_point()));
        }
        if l.is_closed()
            && let (Some((_, first)), Some((_, last))) = (of_loop.first(), of_loop.last())
        {
            widest = widest.max(last.end_point().distance(first.start_point()));
        }
    }
    widest
}

/// The pieces of `passages`, once each.
pub(crate) fn passage_pieces(passages: &on_boundary::Passages) -> SmallVec<[u32; 4]> {
    let mut pieces: SmallVec<[u32; 4]> = passages.iter().map(|p| p.0).collect();
    pieces.dedup();
    pieces
}

/// What the far-field test needs of a piece: the box where a query may be near it (its
/// control box grown by the band's reach, [`BandReach`]: it holds every point of the band of
/// the piece's monotone boxes, and every point the adaptive walk may find within the reach of
/// the piece), and its chord.
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

    /// Grows the near box by `reach` on every side.
    fn grow(&mut self, reach: f64) {
        self.lo = Point::new(self.lo.x - reach, self.lo.y - reach);
        self.hi = Point::new(self.hi.x + reach, self.hi.y + reach);
    }
}

/// The index in `pieces` (in curve order, as [`Domain::bezier_pieces`] lists them, the curve
/// of each in `curves`) of the piece each monotone box lies on: the piece of the box's curve
/// whose knot span holds the middle of the box's parameter range.
fn pieces_of_boxes(curves: &[u32], pieces: &[RationalBezier], boxes: &MonotoneBoxes) -> Vec<u32> {
    boxes
        .boxes()
        .iter()
        .map(|b| {
            let first = curves.partition_point(|&c| (c as usize) < b.curve);
            let count = curves[first..].partition_point(|&c| c as usize == b.curve);
            let mid = 0.5 * (b.param_range.0 + b.param_range.1);
            let within = pieces[first..first + count].partition_point(|p| p.knot_span().1 <= mid);
            (first + within.min(count.saturating_sub(1))) as u32
        })
        .collect()
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

#[cfg(test)]
mod tests {
    use super::{
        BoxSource, FillRule, MARGIN_SAFETY, WindingAlgorithm, WindingField, coordinate_scale,
        relative_band_margin,
    };
    use rs_boxes::{BoxOptions, MonotoneBoxes};
    use rs_spline::{Domain, NurbsCurve, Point};
    use std::sync::Arc;

    /// A closed loop of a rational quadratic (weights `1, w, 1`: ratio `w`) and a rational
    /// cubic (weights `1, 1/w, w, 1`: ratio `w^2`): weight ratios the paper's domains do not
    /// have.
    pub(super) fn heavy_weights(w: f64) -> Domain {
        let upper = NurbsCurve::bezier(
            vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 3.0),
                Point::new(2.0, 0.0),
            ],
            Some(vec![1.0, w, 1.0]),
        )
        .unwrap();
        let lower = NurbsCurve::bezier(
            vec![
                Point::new(2.0, 0.0),
                Point::new(1.5, -1.0),
                Point::new(0.5, -2.0),
                Point::new(0.0, 0.0),
            ],
            Some(vec![1.0, 1.0 / w, w, 1.0]),
        )
        .unwrap();
        Domain::new(vec![upper, lower]).unwrap()
    }

    /// The premise of the band's reach, measured: every monotone box's control points (whose
    /// hull holds the box's curve) lie within the joint gap plus the rounding bound of
    /// [`relative_band_margin`] *before* its safety factor (the split part of it alone would
    /// do) of its piece's control box; on the paper's domains, the GWN shapes, rational pieces
    /// of weight ratio up to 1e12 (the limit), and boxes refined up to 4096 times, shared as a
    /// classifier shares them.
    #[test]
    fn band_margin_covers_the_boxes_rounding() {
        let mut domains: Vec<(String, Domain)> = rs_testkit::all_cases()
            .into_iter()
            .map(|c| (c.name, c.domain))
            .collect();
        for name in rs_testkit::GWN_SHAPES {
            domains.push((name.to_string(), rs_testkit::gwn_shape(name)));
        }
        for w in [10.0, 1e3, 1e6] {
            domains.push((format!("weights {w}"), heavy_weights(w)));
        }
        let mut checked = 0;
        for (name, d) in &domains {
            for subdivisions in [BoxOptions::default().subdivisions, 4096] {
                let boxes = Arc::new(
                    MonotoneBoxes::new(d, BoxOptions::default().with_subdivisions(subdivisions))
                        .unwrap(),
                );
                let field = WindingField::build(d, BoxSource::Given(Arc::clone(&boxes)), 1e-12);
                let index = field.boundary_index().unwrap();
                let scale = coordinate_scale(boxes.bounding_box());
                let bound = relative_band_margin(field.pieces(), boxes.subdivisions())
                    / MARGIN_SAFETY
                    * scale
                    + field.joint_gap;
                for (b, &p) in boxes.boxes().iter().zip(&index.box_pieces) {
                    let (lo, hi) = super::control_box(field.pieces()[p as usize].control_points());
                    for i in 0..=b.piece().degree() {
                        let c = b.piece().control_point(i);
                        let out = (lo.x - c.x).max(c.x - hi.x).max(lo.y - c.y).max(c.y - hi.y);
                        assert!(
                            out <= bound,
                            "{name} ({subdivisions}): {c:?} {out} > {bound}"
                        );
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 10_000, "{checked} control points checked");
    }

    /// The margin is per field: a few `1e-12` of the scale for cubic polynomial pieces (not the
    /// worst case of every input the limits allow), larger for larger weight ratios.
    #[test]
    fn band_margin_grows_with_degree_weights_and_boxes() {
        let cubic = heavy_weights(1.0);
        let m = relative_band_margin(
            &cubic
                .bezier_pieces()
                .into_iter()
                .map(|(_, b)| b)
                .collect::<Vec<_>>(),
            32,
        );
        assert!(m > 1e-12 && m < 5e-12, "{m}");
        let heavy = heavy_weights(1e3);
        let pieces: Vec<_> = heavy.bezier_pieces().into_iter().map(|(_, b)| b).collect();
        let w = relative_band_margin(&pieces, 32);
        assert!(w > 900.0 * m, "{w} vs {m}");
        assert!(relative_band_margin(&pieces, 4096) > 10.0 * w);
    }

    #[test]
    fn fill_rules_parse_from_their_names() {
        for (name, rule) in [
            ("even-odd", FillRule::EvenOdd),
            ("evenodd", FillRule::EvenOdd),
            ("EvenOdd", FillRule::EvenOdd),
            ("nonzero", FillRule::NonZero),
            ("non-zero", FillRule::NonZero),
            ("NonZero", FillRule::NonZero),
        ] {
            assert_eq!(name.parse::<FillRule>(), Ok(rule), "{name}");
        }
        let e = "winding".parse::<FillRule>().unwrap_err();
        assert_eq!(
            e,
            "unknown fill rule \"winding\" (expected even-odd or nonzero)"
        );
        assert!("".parse::<FillRule>().is_err());
    }

    #[test]
    fn winding_algorithms_parse_from_the_command_line_names() {
        for (name, algorithm) in [
            ("adaptive", WindingAlgorithm::Adaptive),
            ("binary-search", WindingAlgorithm::BinarySearch),
            ("bezier-clipping", WindingAlgorithm::BezierClipping),
            ("Bezier-Clipping", WindingAlgorithm::BezierClipping),
        ] {
            assert_eq!(name.parse::<WindingAlgorithm>(), Ok(algorithm), "{name}");
        }
        let e = "binary_search".parse::<WindingAlgorithm>().unwrap_err();
        assert!(!e.contains('\n'));
        assert!(
            e.contains("\"binary_search\"")
                && e.contains("adaptive, binary-search or bezier-clipping"),
            "{e}"
        );
    }
}
