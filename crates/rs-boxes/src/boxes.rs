//! Building the monotone boxes of a domain (paper steps (i)-(ii) and Remark 2.1).

use rs_roots::{RootsError, real_roots_in};
use rs_spline::{Axis, BoundingBox, Domain, Point};

use crate::{BezierPiece, BoxError, MonotoneBox, Monotonicity, PieceError};

/// Default number of sub-boxes each monotone piece is cut into (Remark 2.1), chosen by
/// measurement (`cargo xtask bench --sweep`, table in the README). Smaller boxes let most points
/// be decided without a root solve: on the paper's three domains with `10^5` Halton points,
/// inRS2 runs 6-14 times faster with 32 sub-boxes than with 1, and 64 or 128 gain at most another
/// 10-20% while doubling or quadrupling the build time, which dominates below `10^4` points. 32
/// keeps build plus classification within about 10% of the best choice from `10^3` to `10^5`
/// points.
pub const DEFAULT_SUBDIVISIONS: usize = 32;

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
    /// Sub-boxes per monotone piece (>= 1; 1 means no refinement).
    pub subdivisions: usize,
}

impl BoxOptions {
    /// [`DEFAULT_SUBDIVISIONS`] sub-boxes per monotone piece.
    pub const DEFAULT: BoxOptions = BoxOptions {
        subdivisions: DEFAULT_SUBDIVISIONS,
    };

    /// With `subdivisions` sub-boxes per monotone piece.
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
///    neighbouring pieces share the split point exactly.
/// 3. Each monotone piece is cut into [`BoxOptions::subdivisions`] equal parameter parts.
/// 4. Critical points: vertical/horizontal tangencies, x-/y-turning vertices (where consecutive
///    boxes run in opposite directions, or one is constant), and constant (vertical or
///    horizontal) pieces.
///
/// # Examples
///
/// ```
/// use rs_boxes::{BoxOptions, MonotoneBoxes};
/// use rs_spline::{circle, Domain, Point};
/// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let boxes = MonotoneBoxes::new(&d, BoxOptions::DEFAULT.with_subdivisions(1)).unwrap();
/// assert_eq!(boxes.boxes().len(), 4); // one per quadrant
/// assert_eq!(boxes.critical_abscissas(), &[-1.0, 1.0]);
/// ```
#[derive(Clone, Debug)]
pub struct MonotoneBoxes {
    boxes: Vec<MonotoneBox>,
    bbox: BoundingBox,
    critical: Vec<CriticalPoint>,
    critical_x: Vec<f64>,
    critical_y: Vec<f64>,
    subdivisions: usize,
}

/// Tangency flags at a piece's ends: (vertical, horizontal).
type EndFlags = (bool, bool);

impl MonotoneBoxes {
    /// Builds the boxes of every loop of `domain` (closed or not).
    ///
    /// The refinement is fitted to the boundary's size: with `m` monotone pieces each is cut
    /// into `min(subdivisions, max(1, BOX_BUDGET / m))` boxes, so memory stays linear in the
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
        let (loops, monotone_pieces) = split_loops(domain)?;
        let subdivisions = options
            .subdivisions
            .min((BOX_BUDGET / monotone_pieces.max(1)).max(1));
        let (boxes, critical) = build_boxes(domain, loops, monotone_pieces, subdivisions);
        let bbox = boxes
            .iter()
            .map(|b| BoundingBox {
                min: Point::new(b.band.xmin, b.band.ymin),
                max: Point::new(b.band.xmax, b.band.ymax),
            })
            .reduce(BoundingBox::union)
            .unwrap_or_else(|| domain.bounding_box());
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
            boxes,
            bbox,
            critical,
            critical_x,
            critical_y,
            subdivisions,
        })
    }

    /// The sub-boxes per monotone piece actually used: the requested
    /// [`BoxOptions::subdivisions`], reduced if needed so that the domain has at most about
    /// [`BOX_BUDGET`] boxes (never below 1).
    pub fn subdivisions(&self) -> usize {
        self.subdivisions
    }

    /// The boxes, loop by loop in boundary order.
    pub fn boxes(&self) -> &[MonotoneBox] {
        &self.boxes
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

fn near_sorted(v: &[f64], x: f64, tol: f64) -> bool {
    let i = v.partition_point(|&c| c < x - tol);
    i < v.len() && v[i] <= x + tol
}

/// One loop's pieces: (curve, knot span, watertight piece, its monotone splits).
type SplitLoop = Vec<(usize, (f64, f64), BezierPiece, Splits)>;

/// First pass: the watertight pieces of every loop (each piece starts exactly where the
/// previous one ends) and their monotone splits, with the number of monotone pieces, so that
/// the refinement can be fitted to the box budget.
fn split_loops(domain: &Domain) -> Result<(Vec<SplitLoop>, usize), BoxError> {
    let mut loops = Vec::with_capacity(domain.loops().len());
    let mut monotone_pieces = 0usize;
    for l in domain.loops() {
        let mut pieces: Vec<(usize, (f64, f64), BezierPiece)> = l
            .curves()
            .flat_map(|ci| {
                domain.curves()[ci]
                    .to_bezier()
                    .into_iter()
                    .map(move |b| (ci, b.knot_span(), BezierPiece::from_bezier(&b)))
            })
            .collect();
        for i in 1..pieces.len() {
            let end = pieces[i - 1].2.end();
            pieces[i].2.set_start(end);
        }
        if l.is_closed() {
            let end = pieces[pieces.len() - 1].2.end();
            pieces[0].2.set_start(end);
        }
        let mut split = Vec::with_capacity(pieces.len());
        for (ci, range, piece) in pieces {
            let s = monotone_splits(&piece).map_err(|source| BoxError::Piece {
                curve: ci,
                parameter: range.0,
                source,
            })?;
            monotone_pieces += s.0.len() + 1;
            split.push((ci, range, piece, s));
        }
        loops.push(split);
    }
    Ok((loops, monotone_pieces))
}

/// Second pass: the boxes of every loop (each monotone piece cut into `subdivisions`), with
/// the tangency flags carried across piece joins, and the loop's critical points.
fn build_boxes(
    domain: &Domain,
    loops: Vec<SplitLoop>,
    monotone_pieces: usize,
    subdivisions: usize,
) -> (Vec<MonotoneBox>, Vec<CriticalPoint>) {
    let mut boxes = Vec::with_capacity(monotone_pieces * subdivisions);
    let mut critical = Vec::new();
    for (li, (l, split)) in domain.loops().iter().zip(loops).enumerate() {
        let first = boxes.len();
        // Tangency flags at the start of each box of this loop.
        let mut start_flags: Vec<EndFlags> = Vec::new();
        let mut pending_end: EndFlags = (false, false);
        for (ci, range, piece, (splits, at_start, at_end)) in split {
            let before = boxes.len();
            split_piece(
                &piece,
                ci,
                li,
                range,
                &splits,
                subdivisions,
                &mut boxes,
                &mut start_flags,
            );
            let idx = before - first;
            start_flags[idx].0 |= at_start.0 || pending_end.0;
            start_flags[idx].1 |= at_start.1 || pending_end.1;
            pending_end = at_end;
        }
        let last = boxes.len();
        if l.is_closed() {
            start_flags[0].0 |= pending_end.0;
            start_flags[0].1 |= pending_end.1;
        }
        collect_critical(
            &boxes[first..last],
            &start_flags,
            l.is_closed(),
            &mut critical,
        );
    }
    (boxes, critical)
}

/// Split parameters of a piece at the roots of `x'` and `y'` in `(0, 1)`, each with its
/// (vertical, horizontal) tangency flags, plus the flags of roots at the ends.
fn monotone_splits(piece: &BezierPiece) -> Result<Splits, PieceError> {
    let mut splits: Vec<(f64, EndFlags)> = Vec::new();
    let (mut at_start, mut at_end) = ((false, false), (false, false));
    let bez = piece.to_bezier()?;
    let (dx, dy) = bez.derivative_numerators();
    for (axis, d) in [(Axis::X, dx), (Axis::Y, dy)] {
        if piece.is_constant(axis) {
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

/// Cuts `piece` at `splits` and each part into `k` equal parameter parts, pushing the boxes and
/// the tangency flags at their starts.
#[allow(clippy::too_many_arguments)]
fn split_piece(
    piece: &BezierPiece,
    curve: usize,
    loop_index: usize,
    (u0, u1): (f64, f64),
    splits: &[(f64, EndFlags)],
    k: usize,
    boxes: &mut Vec<MonotoneBox>,
    start_flags: &mut Vec<EndFlags>,
) {
    let param = |t: f64| u0 + t * (u1 - u0);
    let mut rest = piece.clone();
    let mut t_prev = 0.0;
    let mut flags_prev: EndFlags = (false, false);
    let ends = splits
        .iter()
        .copied()
        .chain(std::iter::once((1.0, (false, false))));
    for (t, flags) in ends {
        let monotone = if t < 1.0 {
            let (left, right) = rest.split((t - t_prev) / (1.0 - t_prev));
            rest = right;
            left
        } else {
            rest.clone()
        };
        // Refine into k equal parts of [t_prev, t].
        let mut part = monotone;
        for j in 0..k {
            let a = t_prev + (t - t_prev) * j as f64 / k as f64;
            let b = t_prev + (t - t_prev) * (j + 1) as f64 / k as f64;
            let sub = if j + 1 < k {
                let (left, right) = part.split(1.0 / (k - j) as f64);
                part = right;
                left
            } else {
                part.clone()
            };
            boxes.push(MonotoneBox::new(
                sub,
                curve,
                loop_index,
                (param(a), param(b)),
            ));
            start_flags.push(if j == 0 { flags_prev } else { (false, false) });
        }
        t_prev = t;
        flags_prev = flags;
    }
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
        if vt || x_turn {
            out.push(CriticalPoint {
                point: b.band.start,
                kind: if vt {
                    CriticalKind::VerticalTangent
                } else {
                    CriticalKind::XTurningVertex
                },
            });
        }
        if ht || y_turn {
            out.push(CriticalPoint {
                point: b.band.start,
                kind: if ht {
                    CriticalKind::HorizontalTangent
                } else {
                    CriticalKind::YTurningVertex
                },
            });
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
