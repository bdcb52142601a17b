//! Building the monotone boxes of a domain (paper steps (i)-(ii) and Remark 2.1).

use rs_roots::{RootsError, clearly_one_signed, real_roots_in};
use rs_spline::{Axis, BoundingBox, Domain, Point};
use std::sync::OnceLock;
use std::sync::atomic::{AtomicUsize, Ordering};

use crate::piece::HalvedPiece;
use crate::{BezierPiece, BoxError, MonotoneBox, Monotonicity, PieceError};
use rs_spline::odds_map;

/// Default most sub-boxes a monotone piece is cut into (Remark 2.1), chosen by
/// measurement (`cargo xtask bench --sweep`, table in the README). Smaller boxes let most points
/// be decided without a root solve: on the paper's three domains with `10^5` Halton points,
/// inRS2 runs 6-14 times faster with 32 sub-boxes than with 1, and 64 or 128 gain at most another
/// 10-20% while doubling or quadrupling the build time, which dominates below `10^4` points. 32
/// keeps build plus classification within about 10% of the best choice from `10^3` to `10^5`
/// points.
pub const DEFAULT_SUBDIVISIONS: usize = 32;

/// Refined boxes per bounding-box diagonal of L1 length along the boundary: a monotone piece
/// whose box has width plus height `l` gets `ceil(BOXES_PER_DIAGONAL * l / diagonal)` boxes
/// (at least 1, at most [`BoxOptions::subdivisions`]), so that boxes are about one size across
/// the domain: the paper's domains, whose pieces span much of the domain, keep 32 on their
/// large pieces, while a glyph-like boundary of hundreds of small pieces gets 1 to 4 each.
/// Chosen by measurement (`cargo xtask bench --only paper --quick`, best of three alternating
/// runs): inRS2 on `10^3` and `10^4` points of the paper's domains within about 5% of 32 boxes
/// on every piece, where 32 per diagonal was up to 15% slower.
pub const BOXES_PER_DIAGONAL: f64 = 64.0;

/// The most sub-boxes per monotone piece a caller may ask for.
pub const MAX_SUBDIVISIONS: usize = 4096;

/// The number of boxes the refinement aims at for a whole domain: a boundary with many monotone
/// pieces gets fewer sub-boxes each (at least one), so that the boxes take at most about
/// `BOX_BUDGET * BYTES_PER_BOX` = 67 MiB (536 bytes a box on 64-bit targets). The paper's domains (10-100 monotone pieces) keep the
/// default 32.
pub const BOX_BUDGET: usize = 1 << 17;

/// The memory of one box (its Bezier piece inline for degree <= 7, bounds, directions,
/// flatness), in bytes.
pub const BYTES_PER_BOX: usize = std::mem::size_of::<MonotoneBox>();

/// Roots of `x'` or `y'` closer than this to a piece's end (in its `[0, 1]` parameter) do not
/// split it; they mark the end point as a tangency instead.
const END_ROOT_MARGIN: f64 = 1e-10;

/// Options for [`MonotoneBoxes::new`]: [`BoxOptions::DEFAULT`] and `with_*` setters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct BoxOptions {
    /// The most sub-boxes per monotone piece (>= 1; 1 means no refinement): a piece gets
    /// fewer when it is short against the domain ([`BOXES_PER_DIAGONAL`]).
    pub subdivisions: usize,
}

impl BoxOptions {
    /// At most [`DEFAULT_SUBDIVISIONS`] sub-boxes per monotone piece.
    pub const DEFAULT: BoxOptions = BoxOptions {
        subdivisions: DEFAULT_SUBDIVISIONS,
    };

    /// With at most `subdivisions` sub-boxes per monotone piece.
    pub const fn with_subdivisions(mut self, subdivisions: usize) -> Self {
        self.subdivisions = subdivisions;
        self
    }
}

impl Default for BoxOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What makes a boundary point critical for a vertical or horizontal ray (paper, Fig. 1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CriticalKind {
    /// `x'(t) = 0` inside a curve (vertical tangent).
    VerticalTangent,
    /// `y'(t) = 0` inside a curve (horizontal tangent).
    HorizontalTangent,
    /// A vertex where the boundary turns back in x (`x'(t-) x'(t+) < 0`), or meets a vertical
    /// piece.
    XTurningVertex,
    /// A vertex where the boundary turns back in y, or meets a horizontal piece.
    YTurningVertex,
    /// A whole vertical piece (`x` constant).
    VerticalPiece,
    /// A whole horizontal piece (`y` constant).
    HorizontalPiece,
}

impl CriticalKind {
    /// True if the point's abscissa is critical for vertical rays.
    pub fn is_x_critical(self) -> bool {
        matches!(
            self,
            Self::VerticalTangent | Self::XTurningVertex | Self::VerticalPiece
        )
    }
}

/// A critical boundary point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CriticalPoint {
    /// Where it is.
    pub point: Point,
    /// Why it is critical.
    pub kind: CriticalKind,
}

/// The monotone boxes covering a domain's boundary, the global bounding box and the critical
/// abscissas and ordinates.
///
/// # Construction
/// 1. Each loop's rational Bezier pieces are made watertight: the start of every piece is set to
///    the end of the one before (they already agree within the domain's closure tolerance), so
///    consecutive boxes share their end points bit for bit.
/// 2. Each piece is split at the roots in `(0, 1)` of the numerators of `x'(t)` and `y'(t)`
///    (paper eq. (5), roots by `rs-roots`), by successive de Casteljau subdivision so that
///    neighbouring pieces share the split point exactly: the *monotone pieces*
///    ([`MonotoneBoxes::pieces`], one box each).
/// 3. Critical points: vertical/horizontal tangencies, x-/y-turning vertices (where consecutive
///    monotone pieces run in opposite directions, or one is constant), and constant (vertical
///    or horizontal) pieces.
/// 4. Each monotone piece is cut into equal parameter parts, about one per
///    `1 /` [`BOXES_PER_DIAGONAL`] of the bounding box's diagonal along it (its L1 length, the
///    width plus the height of its box), at least 1 and at most
///    [`MonotoneBoxes::subdivisions`]: the refined boxes ([`MonotoneBoxes::boxes`]).
///
/// Steps 1-3 are done by [`MonotoneBoxes::new`]; step 4 is deferred to the first call of
/// [`MonotoneBoxes::boxes`] (thread-safe, done once), so that a caller answering a handful of
/// points never pays for it: [`MonotoneBoxes::for_each_box_of_piece`] gives one piece's refined
/// boxes, bit for bit those of [`MonotoneBoxes::boxes`], computing them on the fly while the
/// whole refinement is not built.
///
/// # Examples
///
/// ```
/// use rs_boxes::{BoxOptions, MonotoneBoxes};
/// use rs_spline::{circle, Domain, Point};
/// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let boxes = MonotoneBoxes::new(&d, BoxOptions::DEFAULT.with_subdivisions(1)).unwrap();
/// assert_eq!(boxes.pieces().len(), 4); // one per quadrant
/// assert!(!boxes.is_refined());
/// assert_eq!(boxes.boxes().len(), 4); // at most one box per piece
/// assert_eq!(boxes.critical_abscissas(), &[-1.0, 1.0]);
/// ```
#[derive(Debug)]
pub struct MonotoneBoxes {
    /// One box per monotone piece, loop by loop in boundary order.
    pieces: Vec<MonotoneBox>,
    /// How each monotone piece is refined (parallel to `pieces`).
    refinement: Vec<Refinement>,
    /// The refined boxes, built on first use.
    boxes: OnceLock<Vec<MonotoneBox>>,
    /// Refined boxes computed on the fly so far by `for_each_box_of_piece` (not kept): once
    /// they reach the number of refined boxes, the refinement is built instead, so that the
    /// work on the fly never exceeds one full build.
    on_the_fly: AtomicUsize,
    /// The number of refined boxes (`boxes().len()`, known before they are built).
    box_count: usize,
    bbox: BoundingBox,
    critical: Vec<CriticalPoint>,
    critical_x: Vec<f64>,
    critical_y: Vec<f64>,
    subdivisions: usize,
}

impl Clone for MonotoneBoxes {
    /// A copy, with the refined boxes if they are built.
    fn clone(&self) -> Self {
        Self {
            pieces: self.pieces.clone(),
            refinement: self.refinement.clone(),
            boxes: self.boxes.clone(),
            on_the_fly: AtomicUsize::new(self.on_the_fly.load(Ordering::Relaxed)),
            box_count: self.box_count,
            bbox: self.bbox,
            critical: self.critical.clone(),
            critical_x: self.critical_x.clone(),
            critical_y: self.critical_y.clone(),
            subdivisions: self.subdivisions,
        }
    }
}

/// How one monotone piece is cut into refined boxes.
#[derive(Clone, Copy, Debug)]
struct Refinement {
    /// The monotone piece's local parameters `[t0, t1]` in its Bezier piece.
    t: (f64, f64),
    /// The Bezier piece's knot span (curve parameter `u0 + t (u1 - u0)`).
    span: (f64, f64),
    /// Refined boxes of this piece (>= 1).
    count: usize,
    /// Index of its first refined box in [`MonotoneBoxes::boxes`].
    first: usize,
}

/// Tangency flags at a piece's ends: (vertical, horizontal).
type EndFlags = (bool, bool);

impl MonotoneBoxes {
    /// Builds the monotone pieces of every loop of `domain` (closed or not), their critical
    /// points and bounding box; the refined boxes are built on the first call of
    /// [`MonotoneBoxes::boxes`].
    ///
    /// The refinement is fitted to each piece's size against the domain (see the type's
    /// Construction), and to the boundary's size: with `m` monotone pieces, no piece gets more
    /// than `min(subdivisions, max(1, BOX_BUDGET / m))` boxes, so memory stays linear in the
    /// boundary (about [`BYTES_PER_BOX`] bytes a box) whatever the requested refinement.
    ///
    /// # Errors
    /// [`BoxError::ZeroSubdivisions`], [`BoxError::TooManySubdivisions`] (more than
    /// [`MAX_SUBDIVISIONS`]), [`BoxError::Piece`] if the tangency roots of a piece cannot be
    /// computed (its pieces would not be monotone).
    pub fn new(domain: &Domain, options: BoxOptions) -> Result<Self, BoxError> {
        if options.subdivisions == 0 {
            return Err(BoxError::ZeroSubdivisions);
        }
        if options.subdivisions > MAX_SUBDIVISIONS {
            return Err(BoxError::TooManySubdivisions {
                requested: options.subdivisions,
                limit: MAX_SUBDIVISIONS,
            });
        }
        let (pieces, mut refinement, critical) = monotone_pieces(domain)?;
        let subdivisions = options
            .subdivisions
            .min((BOX_BUDGET / pieces.len().max(1)).max(1));
        let bbox = pieces
            .iter()
            .map(|b| BoundingBox {
                min: Point::new(b.band.xmin, b.band.ymin),
                max: Point::new(b.band.xmax, b.band.ymax),
            })
            .reduce(BoundingBox::union)
            .unwrap_or_else(|| domain.bounding_box());
        let diagonal = bbox.diagonal();
        let mut box_count = 0;
        for (b, r) in pieces.iter().zip(&mut refinement) {
            let l1 = (b.band.xmax - b.band.xmin) + (b.band.ymax - b.band.ymin);
            r.count = boxes_for(l1, diagonal, subdivisions);
            r.first = box_count;
            box_count += r.count;
        }
        let mut critical_x: Vec<f64> = critical
            .iter()
            .filter(|c| c.kind.is_x_critical())
            .map(|c| c.point.x)
            .collect();
        let mut critical_y: Vec<f64> = critical
            .iter()
            .filter(|c| !c.kind.is_x_critical())
            .map(|c| c.point.y)
            .collect();
        for v in [&mut critical_x, &mut critical_y] {
            v.sort_by(f64::total_cmp);
            v.dedup();
        }
        Ok(Self {
            pieces,
            refinement,
            boxes: OnceLock::new(),
            on_the_fly: AtomicUsize::new(0),
            box_count,
            bbox,
            critical,
            critical_x,
            critical_y,
            subdivisions,
        })
    }

    /// The most refined boxes a monotone piece gets: the requested
    /// [`BoxOptions::subdivisions`], reduced if needed so that the domain has at most about
    /// [`BOX_BUDGET`] boxes (never below 1). Pieces short against the domain's diagonal get
    /// fewer (see the type's Construction).
    pub fn subdivisions(&self) -> usize {
        self.subdivisions
    }

    /// The monotone pieces, one box each, loop by loop in boundary order (built by
    /// [`MonotoneBoxes::new`]); a strongly weighted one as its balanced parts
    /// ([`BezierPiece::balanced_parts`]).
    pub fn pieces(&self) -> &[MonotoneBox] {
        &self.pieces
    }

    /// The refined boxes, loop by loop in boundary order: each monotone piece's boxes in order
    /// from its start, consecutive boxes sharing their end points bit for bit. Built on the
    /// first call (once, whichever thread asks) and kept.
    pub fn boxes(&self) -> &[MonotoneBox] {
        self.boxes.get_or_init(|| {
            let mut all = Vec::with_capacity(self.box_count);
            for (b, r) in self.pieces.iter().zip(&self.refinement) {
                refine(b, r, |sub| all.push(sub));
            }
            all
        })
    }

    /// Whether the refined boxes ([`MonotoneBoxes::boxes`]) have been built.
    pub fn is_refined(&self) -> bool {
        self.boxes.get().is_some()
    }

    /// The number of refined boxes, without building them.
    pub fn box_count(&self) -> usize {
        self.box_count
    }

    /// The number of refined boxes of monotone piece `piece` (an index of
    /// [`MonotoneBoxes::pieces`]).
    ///
    /// # Panics
    /// If `piece` is out of range.
    pub fn boxes_of_piece(&self, piece: usize) -> std::ops::Range<usize> {
        let r = &self.refinement[piece];
        r.first..r.first + r.count
    }

    /// Calls `f` with the refined boxes of monotone piece `piece` in order, bit for bit
    /// `boxes()[boxes_of_piece(piece)]`: from [`MonotoneBoxes::boxes`] once built, else
    /// computed on the fly and dropped (a piece left whole is its own box). Once the boxes
    /// computed on the fly reach [`MonotoneBoxes::box_count`], the refinement is built and
    /// kept, so that many calls never cost more than twice a full build.
    ///
    /// # Panics
    /// If `piece` is out of range.
    pub fn for_each_box_of_piece(&self, piece: usize, mut f: impl FnMut(&MonotoneBox)) {
        let r = &self.refinement[piece];
        if r.count == 1 {
            f(&self.pieces[piece]);
            return;
        }
        let built = match self.boxes.get() {
            Some(all) => Some(all.as_slice()),
            None if self.on_the_fly.fetch_add(r.count, Ordering::Relaxed) + r.count
                > self.box_count =>
            {
                Some(self.boxes())
            }
            None => None,
        };
        match built {
            Some(all) => all[r.first..r.first + r.count].iter().for_each(f),
            None => refine(&self.pieces[piece], r, |sub| f(&sub)),
        }
    }

    /// The global bounding box (union of the boxes: the tight box of the boundary).
    pub fn bounding_box(&self) -> BoundingBox {
        self.bbox
    }

    /// Every critical point with its kind.
    pub fn critical_points(&self) -> &[CriticalPoint] {
        &self.critical
    }

    /// Sorted distinct abscissas of the points critical for vertical rays.
    pub fn critical_abscissas(&self) -> &[f64] {
        &self.critical_x
    }

    /// Sorted distinct ordinates of the points critical for horizontal rays.
    pub fn critical_ordinates(&self) -> &[f64] {
        &self.critical_y
    }

    /// True if `x` is within `abs_tol` of a critical abscissa (binary search).
    pub fn is_critical_x(&self, x: f64, abs_tol: f64) -> bool {
        near_sorted(&self.critical_x, x, abs_tol)
    }

    /// [`MonotoneBoxes::is_critical_x`] among the critical abscissas `among` (a range of
    /// [`MonotoneBoxes::critical_abscissas`]' indices): the same answer whenever the range
    /// holds every critical abscissa within `abs_tol` of `x`.
    pub fn is_critical_x_among(&self, x: f64, abs_tol: f64, among: std::ops::Range<usize>) -> bool {
        near_sorted(&self.critical_x[among], x, abs_tol)
    }

    /// True if `y` is within `abs_tol` of a critical ordinate (binary search).
    pub fn is_critical_y(&self, y: f64, abs_tol: f64) -> bool {
        near_sorted(&self.critical_y, y, abs_tol)
    }
}

/// The refined boxes of a monotone piece of L1 length `l1` (width plus height of its box) in a
/// domain of diagonal `diagonal`: `ceil(BOXES_PER_DIAGONAL * l1 / diagonal)`, clamped to
/// `1..=most` (1 for a degenerate domain).
fn boxes_for(l1: f64, diagonal: f64, most: usize) -> usize {
    let want = (BOXES_PER_DIAGONAL * l1 / diagonal).ceil();
    if want >= most as f64 {
        most
    } else if want >= 1.0 {
        want as usize
    } else {
        // Also NaN (a domain of one point).
        1
    }
}

/// Pushes the `r.count` refined boxes of the monotone piece `b` (equal parameter parts, split
/// off one by one from its start so that consecutive boxes share their end points exactly).
fn refine(b: &MonotoneBox, r: &Refinement, mut push: impl FnMut(MonotoneBox)) {
    let k = r.count;
    if k == 1 {
        push(b.clone());
        return;
    }
    let ((t_prev, t), (u0, u1)) = (r.t, r.span);
    let param = |t: f64| u0 + t * (u1 - u0);
    // The parts are equal in the piece's parameter `s`; the `j`-th starts at the fraction
    // `odds_map(odds, j / k)` of the box's span of the Bezier piece (`j / k` unless the piece
    // was reparametrised), and its own parameter maps onto its span by the odds factor of
    // that Mobius map's restriction to its part: its slope at the part's start over the
    // part's share of the span.
    let odds = b.odds;
    let fraction = |j: usize| odds_map(odds, j as f64 / k as f64);
    // (`(t - t_prev) * j / k` as before for a piece not reparametrised: the same bits.)
    let at = |j: usize| {
        if odds == 1.0 {
            t_prev + (t - t_prev) * j as f64 / k as f64
        } else {
            t_prev + (t - t_prev) * fraction(j)
        }
    };
    let range = |j: usize| (param(at(j)), param(at(j + 1)));
    let part_odds = |j: usize| {
        if odds == 1.0 {
            return 1.0;
        }
        let s = j as f64 / k as f64;
        let slope = odds / ((1.0 - s) + odds * s).powi(2);
        slope / k as f64 / (fraction(j + 1) - fraction(j))
    };
    // Degree <= 7 (every piece in practice): the cuts on fixed-size arrays, bit for bit
    // `BezierPiece::split`'s, without its SmallVec copies and moves.
    if let Some(mut part) = HalvedPiece::of(b.piece()) {
        for j in 0..k {
            let sub = if j + 1 < k {
                let right = part.split_at(1.0 / (k - j) as f64);
                std::mem::replace(&mut part, right)
            } else {
                part
            };
            push(MonotoneBox::new(
                sub.to_piece(),
                b.curve,
                b.boundary_loop,
                range(j),
                part_odds(j),
            ));
        }
        return;
    }
    let mut part = b.piece().clone();
    for j in 0..k {
        let sub = if j + 1 < k {
            let (left, right) = part.split(1.0 / (k - j) as f64);
            part = right;
            left
        } else {
            part.clone()
        };
        push(MonotoneBox::new(
            sub,
            b.curve,
            b.boundary_loop,
            range(j),
            part_odds(j),
        ));
    }
}

fn near_sorted(v: &[f64], x: f64, tol: f64) -> bool {
    let i = v.partition_point(|&c| c < x - tol);
    i < v.len() && v[i] <= x + tol
}

/// The monotone pieces of every loop (one box each, their refinement still to be counted),
/// and the critical points.
///
/// Each loop's Bezier pieces are made watertight (each starts exactly where the previous one
/// ends), split at their tangency roots, and the tangency flags are carried across piece joins.
#[allow(clippy::type_complexity)]
fn monotone_pieces(
    domain: &Domain,
) -> Result<(Vec<MonotoneBox>, Vec<Refinement>, Vec<CriticalPoint>), BoxError> {
    let mut boxes = Vec::new();
    let mut refinement = Vec::new();
    let mut critical = Vec::new();
    // Tangency flags at the start of each monotone piece of the current loop.
    let mut start_flags: Vec<EndFlags> = Vec::new();
    let mut pieces: Vec<(usize, (f64, f64), BezierPiece)> = Vec::new();
    for (li, l) in domain.loops().iter().enumerate() {
        pieces.clear();
        pieces.extend(l.curves().flat_map(|ci| {
            domain.curves()[ci]
                .to_bezier()
                .into_iter()
                .map(move |b| (ci, b.knot_span(), BezierPiece::from_bezier(&b)))
        }));
        for i in 1..pieces.len() {
            let end = pieces[i - 1].2.end();
            pieces[i].2.set_start(end);
        }
        if l.is_closed()
            && let Some(end) = pieces.last().map(|p| p.2.end())
        {
            pieces[0].2.set_start(end);
        }
        let first = boxes.len();
        // At least one monotone piece per Bezier piece: grown once, not box by box.
        boxes.reserve(pieces.len());
        refinement.reserve(pieces.len());
        start_flags.clear();
        let mut pending_end: EndFlags = (false, false);
        for (ci, span, piece) in pieces.drain(..) {
            let (splits, at_start, at_end) =
                monotone_splits(&piece).map_err(|source| BoxError::Piece {
                    curve: ci,
                    parameter: span.0,
                    source,
                })?;
            let idx = boxes.len() - first;
            split_piece(
                piece,
                ci,
                li,
                span,
                &splits,
                &mut boxes,
                &mut refinement,
                &mut start_flags,
            );
            start_flags[idx].0 |= at_start.0 || pending_end.0;
            start_flags[idx].1 |= at_start.1 || pending_end.1;
            pending_end = at_end;
        }
        if l.is_closed()
            && let Some(f) = start_flags.first_mut()
        {
            f.0 |= pending_end.0;
            f.1 |= pending_end.1;
        }
        collect_critical(&boxes[first..], &start_flags, l.is_closed(), &mut critical);
    }
    Ok((boxes, refinement, critical))
}

/// Split parameters of a piece at the roots of `x'` and `y'` in `(0, 1)`, each with its
/// (vertical, horizontal) tangency flags, plus the flags of roots at the ends.
fn monotone_splits(piece: &BezierPiece) -> Result<Splits, PieceError> {
    let mut splits: Vec<(f64, EndFlags)> = Vec::new();
    let (mut at_start, mut at_end) = ((false, false), (false, false));
    // Most pieces have no tangency in one or both coordinates: a derivative numerator whose
    // Bernstein coefficients all have one sign, clear of rounding, has no root in [0, 1]
    // (it is a convex combination of them), so the solve below would find none either.
    let solve = Axis::BOTH.map(|axis| {
        !piece.is_constant(axis) && !clearly_one_signed(&piece.derivative_numerator(axis))
    });
    if solve == [false, false] {
        return Ok((Vec::new(), at_start, at_end));
    }
    let bez = piece.to_bezier()?;
    let (dx, dy) = bez.derivative_numerators();
    for ((axis, d), solve) in [(Axis::X, dx), (Axis::Y, dy)].into_iter().zip(solve) {
        if !solve {
            continue;
        }
        let roots = match real_roots_in(&d, 0.0, 1.0) {
            Ok(r) => r,
            // The numerator cancels to zero: the coordinate is constant up to rounding, so the
            // piece is monotone in it either way.
            Err(RootsError::ZeroPolynomial) => Vec::new(),
            Err(e) => return Err(e.into()),
        };
        for t in roots {
            let flags = match axis {
                Axis::X => (true, false),
                Axis::Y => (false, true),
            };
            if t <= END_ROOT_MARGIN {
                at_start = or(at_start, flags);
            } else if t >= 1.0 - END_ROOT_MARGIN {
                at_end = or(at_end, flags);
            } else {
                splits.push((t, flags));
            }
        }
    }
    splits.sort_by(|a, b| a.0.total_cmp(&b.0));
    // A root of both x' and y' (a cusp) splits once.
    let mut merged: Vec<(f64, EndFlags)> = Vec::with_capacity(splits.len());
    for (t, f) in splits {
        match merged.last_mut() {
            Some((lt, lf)) if t - *lt <= END_ROOT_MARGIN => *lf = or(*lf, f),
            _ => merged.push((t, f)),
        }
    }
    Ok((merged, at_start, at_end))
}

/// Split parameters with their tangency flags, and the flags at the piece's two ends.
type Splits = (Vec<(f64, EndFlags)>, EndFlags, EndFlags);

fn or(a: EndFlags, b: EndFlags) -> EndFlags {
    (a.0 || b.0, a.1 || b.1)
}

/// Cuts `piece` at `splits` into monotone pieces, pushing one box for each (for each of its
/// balanced parts, [`BezierPiece::balanced_parts`], where strong weights crowd its ends), its
/// refinement record (count still to be set) and the tangency flags at its start.
#[allow(clippy::too_many_arguments)]
fn split_piece(
    piece: BezierPiece,
    curve: usize,
    loop_index: usize,
    (u0, u1): (f64, f64),
    splits: &[(f64, EndFlags)],
    boxes: &mut Vec<MonotoneBox>,
    refinement: &mut Vec<Refinement>,
    start_flags: &mut Vec<EndFlags>,
) {
    let param = |t: f64| u0 + t * (u1 - u0);
    let mut push = |monotone: BezierPiece, (t_prev, t): (f64, f64), flags_prev: EndFlags| {
        // The parameter range a refinement into one box gives (`refine`'s formula with
        // k = 1), so that a piece left whole is bit for bit its own refined box.
        // At the piece's ends: `t_prev` and `t` themselves in the record, `refine`'s formula in
        // the range.
        let record = |f: f64| match f {
            0.0 => t_prev,
            1.0 => t,
            _ => t_prev + (t - t_prev) * f,
        };
        let range = |f: f64| match f {
            0.0 | 1.0 => param(t_prev + (t - t_prev) * f / 1.0),
            _ => param(t_prev + (t - t_prev) * f),
        };
        let mut flags = flags_prev;
        for part in monotone.balanced_parts() {
            let (fa, fb) = part.fractions;
            boxes.push(MonotoneBox::new(
                part.piece,
                curve,
                loop_index,
                (range(fa), range(fb)),
                part.odds,
            ));
            refinement.push(Refinement {
                t: (record(fa), record(fb)),
                span: (u0, u1),
                count: 1,
                first: 0,
            });
            start_flags.push(flags);
            // A cut inside a monotone piece is no tangency.
            flags = (false, false);
        }
    };
    // Every split lies in (0, 1) (roots at the ends mark tangencies instead); the piece is
    // moved, not copied, into its last part (the whole piece when it has no split).
    let mut rest = piece;
    let mut t_prev = 0.0;
    let mut flags_prev: EndFlags = (false, false);
    for &(t, flags) in splits {
        let (left, right) = rest.split((t - t_prev) / (1.0 - t_prev));
        rest = right;
        push(left, (t_prev, t), flags_prev);
        t_prev = t;
        flags_prev = flags;
    }
    push(rest, (t_prev, 1.0), flags_prev);
}

/// Critical points of one loop's boxes.
fn collect_critical(
    boxes: &[MonotoneBox],
    start_flags: &[EndFlags],
    closed: bool,
    out: &mut Vec<CriticalPoint>,
) {
    let n = boxes.len();
    for (i, b) in boxes.iter().enumerate() {
        if b.x_dir == Monotonicity::Constant {
            out.push(CriticalPoint {
                point: b.band.start,
                kind: CriticalKind::VerticalPiece,
            });
        }
        if b.y_dir == Monotonicity::Constant {
            out.push(CriticalPoint {
                point: b.band.start,
                kind: CriticalKind::HorizontalPiece,
            });
        }
        let prev = if i > 0 {
            Some(&boxes[i - 1])
        } else if closed {
            boxes.last()
        } else {
            None
        };
        let (vt, ht) = start_flags[i];
        let (x_turn, y_turn) = match prev {
            Some(p) => (
                p.x_dir.turns_against(b.x_dir),
                p.y_dir.turns_against(b.y_dir),
            ),
            // The free end of an open chain is critical both ways.
            None => (true, true),
        };
        // A tangent names the point where there is one, else the turn does; x before y.
        for (tangent, turn, kinds) in [
            (
                vt,
                x_turn,
                (CriticalKind::VerticalTangent, CriticalKind::XTurningVertex),
            ),
            (
                ht,
                y_turn,
                (
                    CriticalKind::HorizontalTangent,
                    CriticalKind::YTurningVertex,
                ),
            ),
        ] {
            if tangent || turn {
                out.push(CriticalPoint {
                    point: b.band.start,
                    kind: if tangent { kinds.0 } else { kinds.1 },
                });
            }
        }
        if !closed && i + 1 == n {
            for kind in [CriticalKind::XTurningVertex, CriticalKind::YTurningVertex] {
                out.push(CriticalPoint {
                    point: b.band.end,
                    kind,
                });
            }
        }
    }
}
