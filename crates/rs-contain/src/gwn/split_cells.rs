//! Split cells: near cells of the far-cell grid ([`FarCells`](super::far_cells::FarCells))
//! whose queries count the crossings from a base and the roots of the few sub-curves that
//! pass through them, instead of walking.
//!
//! Why a base serves a whole cell: cover the curves by the far cells' sub-curves (each piece
//! halved until its sub-curves' boxes span about two cells). A cell's *listed* sub-curves are
//! those whose boxes, grown by the far cells' growth, meet it; every other one stays farther
//! than the band's reach from every point of the cell, wholly left of it, right of it, above
//! it or below it. Beyond the reach, the crossings the walk counts are those of the curves
//! themselves (see `WindingField`'s Semantics): the sum over the listed sub-curves plus the
//! sum over the others. Of the others, one right of the cell, above it or below it crosses
//! no query's cut there; one left of it crosses as its chord does, `side(start) - side(end)`
//! with `side(e) = [e.y >= q.y]`. Summed over the others left of the cell, the sides of the
//! ends they share with one another cancel, and so do those of ends outside the cell's
//! heights (constant there); what varies with the query is the sides of the ends they share
//! with the listed sub-curves (and the open chains' ends, whose rows the far cells mark and
//! split cells avoid). At a point `p` of the cell's heights, as many sub-curves start as end
//! (the curves are closed chains there), so the others there add up to minus the listed
//! ones' count `l_p`; if `p` lies left of the cell, those others are left of it too (they
//! hold `p`), and they add the *step* `-l_p [p.y >= q.y]`; right of it they add nothing;
//! within the cell's columns there are none (their boxes would meet it), and a cell whose
//! listed ends do not balance there stays near. (A chain's end, where the count does not
//! balance, may lie at the grown box's heights only in a neighbouring row: its step is then
//! the same for every query of the cell and every point its base is taken at, and the base
//! absorbs it.) So a query's count is the listed sub-curves'
//! crossings, the steps, and a constant, the cell's base: every query of a split cell, and
//! every point of a side its base is taken at (in its row or its neighbour's, neither a chain
//! end's row), lies strictly above or below every chain end's height, as rows are monotone
//! in the height. The base comes from a neighbouring cell whose count at a point of their
//! common side is known: that count less the listed sub-curves' crossings and the steps
//! there. A query then adds its listed sub-curves' crossings, each decided by its root
//! ([`MonotoneCurve::crossing`], the walk's
//! [`monotone_crossing`](super::monotone::monotone_crossing) made once per sub-curve, with a
//! nearer first iterate) or by its box (from beyond twice the reach), its steps, and the
//! open chains' ends, as a far cell's query does: the walk's value bit for bit. A query the
//! roots cannot decide (too near a sub-curve) walks.
//!
//! Once the split cells have answered many queries, each entry also gets a side test, and a
//! query reads its cell's tests first, without branches; only an entry whose test cannot
//! decide (the query within the test's margin of the curve) is read again by its box and root.
//! A cell's tests are its sub-curves' implicit equations ([`ImplicitSide`]: exact but for
//! rounding, deciding down to about the root's own margin) where each certifies over its
//! piece's region, else certified polynomial fits ([`InverseFit`]). Where a test decides, the
//! root decides the same, so the values stay the walk's bit for bit.

use rs_spline::Point;

use super::curve::{SmallPolynomial, control_box, outside_by};
use super::implicit_side::ImplicitSide;
use super::inverse_fit::{Frame, InverseFit};
use super::monotone::{MonotoneCurve, RootCrossing};
use super::sum::chord_crossing;

/// Most sub-curves listed in a split cell: more, and the walk is left to it. (On the large GWN
/// shapes, 24-35 of 4,792-7,460 near cells meet more, where many short pieces meet, holding
/// 1.2-1.5% of the points near the curves; allowing 96 split most of them, but their queries
/// then cost about what their walks do.)
pub(super) const MOST_LISTED: usize = 24;

/// A sub-curve a split cell lists: its control points (a polynomial of degree at most 3), its
/// control box, and, if [`monotone_crossing`](super::monotone::monotone_crossing) takes it (its
/// control ordinates strictly increase or strictly decrease), that function's form made once
/// (given the start its many queries are worth, [`MonotoneCurve::with_inverse_start`], once
/// the split cells are made: [`SplitCells::drop_unread`]); one it does not take decides only
/// queries outside its box.
#[derive(Clone, Copy, Debug)]
pub(super) struct RootedSub {
    curve: SmallPolynomial,
    lo: Point,
    hi: Point,
    root: Option<MonotoneCurve>,
}

impl RootedSub {
    /// `c` if it has 2 to 4 control points, all finite.
    pub(super) fn of(c: SmallPolynomial) -> Option<Self> {
        let p = c.points();
        let finite = p.iter().all(|v| v.x.is_finite() && v.y.is_finite());
        if !(finite && p.len() >= 2) {
            return None;
        }
        let (lo, hi) = control_box(p);
        Some(Self {
            curve: c,
            lo,
            hi,
            root: MonotoneCurve::new(p),
        })
    }

    /// Whether the sub-curve with control points `p` would be listed with a root (what
    /// `RootedSub::of(p)` would tell), without making it.
    pub(super) fn would_have_root(p: &[Point]) -> bool {
        p.iter().all(|v| v.x.is_finite() && v.y.is_finite()) && MonotoneCurve::new(p).is_some()
    }

    /// Its first control point.
    pub(super) fn start(&self) -> Point {
        self.curve.points()[0]
    }

    /// Its last control point.
    pub(super) fn end(&self) -> Point {
        let p = self.curve.points();
        p[p.len() - 1]
    }

    /// Its signed crossing of the cut at `q`, as the walk counts it, or `None` if `q` may be
    /// within twice `reach` of it (then the walk must decide): from its chord when `q` lies
    /// outside its box grown by twice the reach (its curve, within the reach of its control
    /// polygon, then lies wholly left of `q`, right of it, above or below it), else from its
    /// root ([`MonotoneCurve::crossing`]).
    #[inline(always)]
    pub(super) fn crossing(&self, q: Point, reach: f64) -> Option<i64> {
        match outside_box_crossing((self.lo, self.hi), (self.start().y, self.end().y), q, reach) {
            Some(k) => Some(k),
            None => self.root_crossing(q, reach),
        }
    }

    /// Its crossing from its root ([`MonotoneCurve::crossing`]) for a `q` in or near its box,
    /// `None` if the root declines or it is not monotone.
    #[inline(always)]
    fn root_crossing(&self, q: Point, reach: f64) -> Option<i64> {
        match self.root.as_ref()?.crossing(q, reach) {
            RootCrossing::Decided(k) => Some(k),
            RootCrossing::TooNear | RootCrossing::NotMonotone => None,
        }
    }
}

/// The crossing at `q` of a sub-curve with control box `(lo, hi)` and ends at heights
/// `ends`, if `q` lies outside the box grown by twice `reach` (its curve, within the reach of
/// its control polygon, then lies wholly left of `q`, right of it, above or below it): left of
/// the query its chord's crossing (0 above or below it), right of it none. `None` otherwise.
#[inline(always)]
fn outside_box_crossing(
    (lo, hi): (Point, Point),
    (start_y, end_y): (f64, f64),
    q: Point,
    reach: f64,
) -> Option<i64> {
    outside_by(lo, hi, q, 2.0 * reach).then(|| {
        if q.x > hi.x {
            chord_crossing(start_y, end_y, q.y)
        } else {
            0
        }
    })
}

/// A split cell: its base (the crossings of the sub-curves it does not list, and of those it
/// lists that give every query in it the same) and its entries, `entries[first..end]`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Split {
    base: i64,
    first: u32,
    end: u32,
    /// The cell's box (which holds every query it serves).
    cell: (Point, Point),
}

/// An entry as a split cell's queries read it first, branch-free: its sub-curve's ends'
/// heights and the test of its side ([`ImplicitSide`] or [`InverseFit`]; always left for a
/// chord).
#[derive(Clone, Copy, Debug)]
struct Quick<T> {
    start_y: f64,
    end_y: f64,
    side: T,
}

impl<T> Quick<T> {
    /// Entry `e`'s heights with the test `side`.
    fn of(e: &Entry, side: T) -> Self {
        Self {
            start_y: e.start_y,
            end_y: e.end_y,
            side,
        }
    }
}

/// A test of the side of an entry's sub-curve a query lies on, as a cell's first pass reads
/// it: `(left, decided)` at `q`, a query in the cell at a height of the sub-curve (elsewhere
/// the answer does not count), whether the curve passes left of `q` at `q`'s height, and
/// whether that, or its passing right of it, is certain. Branch-free.
trait SideTest {
    fn side(&self, q: Point) -> (bool, bool);
}

impl SideTest for InverseFit {
    #[inline(always)]
    fn side(&self, q: Point) -> (bool, bool) {
        InverseFit::side(self, q)
    }
}

impl SideTest for ImplicitSide {
    #[inline(always)]
    fn side(&self, q: Point) -> (bool, bool) {
        ImplicitSide::side(self, q)
    }
}

/// The first pass over a cell's side tests at `q`, without branches: the crossings of the
/// chords of the entries whose tests put the curve left of `q`, and the bit masks of the
/// entries left undecided (at most 64) and of those put left. An entry whose sub-curve's ends'
/// heights hold `q.y` must be decided by its test; outside those heights by more than
/// `two_reach` (where its control box, whose heights are its ends', leaves `q` above or below
/// it) it adds its chord's crossing, 0, as the box does; nearer, it is undecided.
#[inline(always)]
fn first_pass<T: SideTest>(quick: &[Quick<T>], q: Point, two_reach: f64) -> (i64, u64, u64) {
    let mut total = 0;
    let (mut undecided, mut lefts) = (0u64, 0u64);
    for (i, e) in quick.iter().enumerate() {
        let (left, decided) = e.side.side(q);
        let (low, high) = (e.start_y.min(e.end_y), e.start_y.max(e.end_y));
        let within = q.y >= low && q.y <= high;
        let near = q.y >= low - two_reach && q.y <= high + two_reach;
        let bit = 1u64 << i;
        undecided |= bit & (u64::from(near & !(within & decided))).wrapping_neg();
        lefts |= bit & u64::from(left).wrapping_neg();
        total += i64::from(left) * chord_crossing(e.start_y, e.end_y, q.y);
    }
    (total, undecided, lefts)
}

/// Where a split cell's side tests are ([`QuickTests`]): its first in one of the lists.
#[derive(Clone, Copy, Debug)]
enum CellTests {
    /// None: a sub-curve it reads by its root is not monotone (read by its box and the walk),
    /// or it has more than 64 entries.
    Roots,
    /// In [`QuickTests::implicit`] from this index.
    Implicit(u32),
    /// In [`QuickTests::fits`] from this index.
    Fits(u32),
}

/// The split cells' entries' side tests ([`Quick`], one for each entry of a cell that has
/// them), made once the split cells' queries are many ([`SplitCells::quick_tests`]): a test
/// costs about two microseconds to make, and saves a query that reads it a few hundredths of
/// one.
#[derive(Clone, Debug, Default)]
pub(super) struct QuickTests {
    /// The cells whose every entry's implicit test certifies, their tests in order.
    implicit: Vec<Quick<ImplicitSide>>,
    /// The other cells' fits, in order.
    fits: Vec<Quick<InverseFit>>,
    /// Per split cell, where its tests are.
    cells: Vec<CellTests>,
}

/// A listed sub-curve as a split cell's queries read it: its control box, its ends' heights,
/// and its index in [`SplitCells::subs`] ([`CHORD_ONLY`] for one wholly left of the cell, whose
/// chord decides every query there).
#[derive(Clone, Copy, Debug)]
struct Entry {
    lo: Point,
    hi: Point,
    start_y: f64,
    end_y: f64,
    sub: u32,
}

/// [`Entry::sub`] of a sub-curve wholly left of its cell.
const CHORD_ONLY: u32 = u32::MAX;

/// The split cells of a grid: their bases and listed sub-curves.
#[derive(Clone, Debug, Default)]
pub(super) struct SplitCells {
    splits: Vec<Split>,
    entries: Vec<Entry>,
    /// The sub-curves the entries read.
    pub(super) subs: Vec<RootedSub>,
}

impl SplitCells {
    /// No split cells yet, over the sub-curves `subs`.
    pub(super) fn over(subs: Vec<RootedSub>) -> Self {
        Self {
            subs,
            ..Self::default()
        }
    }

    /// The split cells made so far.
    pub(super) fn len(&self) -> usize {
        self.splits.len()
    }

    /// The crossings at `q` in split cell `s`, `None` if a listed sub-curve cannot decide.
    ///
    /// First, once they are made (`tests`), from the entries' side tests, branch-free (in a
    /// cell of at most 64 entries, all of whose rooted sub-curves are monotone): an entry whose
    /// sub-curve's ends' heights hold `q.y` adds its chord's crossing if its test puts the
    /// curve left of `q`, and must be decided by it; outside those heights by more than twice
    /// `reach` (where its control box, whose heights are its ends', leaves `q` above or below
    /// it) it adds its chord's crossing, 0, as the box does. An entry nearer those heights, or
    /// whose test does not decide, is read again by its box and root
    /// ([`SplitCells::entry_crossing`]), which give the same crossing wherever a test decides.
    #[inline(always)]
    pub(super) fn crossings(
        &self,
        s: usize,
        q: Point,
        reach: f64,
        tests: Option<&QuickTests>,
    ) -> Option<i64> {
        let split = self.splits[s];
        let (first, end) = (split.first as usize, split.end as usize);
        let len = end - first;
        let pass = tests.and_then(|t| match t.cells[s] {
            CellTests::Roots => None,
            CellTests::Implicit(k) => {
                let k = k as usize;
                Some(first_pass(&t.implicit[k..k + len], q, 2.0 * reach))
            }
            CellTests::Fits(k) => {
                let k = k as usize;
                Some(first_pass(&t.fits[k..k + len], q, 2.0 * reach))
            }
        });
        if let Some((left_chords, mut undecided, lefts)) = pass {
            let mut total = split.base + left_chords;
            // Only the undecided entries again, by box and root.
            let entries = &self.entries[first..end];
            while undecided != 0 {
                let i = undecided.trailing_zeros() as usize;
                undecided &= undecided - 1;
                let e = &entries[i];
                let quick_crossing = if lefts >> i & 1 == 1 {
                    chord_crossing(e.start_y, e.end_y, q.y)
                } else {
                    0
                };
                total += self.entry_crossing(e, q, reach)? - quick_crossing;
            }
            return Some(total);
        }
        self.exact_crossings(split, q, reach)
    }

    /// The crossings at `q` in split cell `split` from its entries' boxes and roots, `None` if
    /// a listed sub-curve cannot decide.
    #[inline(never)]
    fn exact_crossings(&self, split: Split, q: Point, reach: f64) -> Option<i64> {
        let mut total = split.base;
        for e in &self.entries[split.first as usize..split.end as usize] {
            total += self.entry_crossing(e, q, reach)?;
        }
        Some(total)
    }

    /// Entry `e`'s crossing at `q` from its chord, box or root, `None` if its root cannot
    /// decide.
    #[inline(always)]
    fn entry_crossing(&self, e: &Entry, q: Point, reach: f64) -> Option<i64> {
        if e.sub == CHORD_ONLY {
            return Some(chord_crossing(e.start_y, e.end_y, q.y));
        }
        // As `RootedSub::crossing`, from the entry's copy of the box and ends.
        match outside_box_crossing((e.lo, e.hi), (e.start_y, e.end_y), q, reach) {
            Some(k) => Some(k),
            None => self.subs[e.sub as usize].root_crossing(q, reach),
        }
    }

    /// The sum of the crossings at `q` of the sub-curves `listed` (indices into
    /// [`SplitCells::subs`]), `None` if one cannot decide.
    pub(super) fn listed_crossings(&self, listed: &[u32], q: Point, reach: f64) -> Option<i64> {
        let mut total = 0;
        for &i in listed {
            total += self.subs[i as usize].crossing(q, reach)?;
        }
        Some(total)
    }

    /// Makes split cell number [`SplitCells::len`]: base `base` for the sub-curves `listed`
    /// and the steps `steps` (each read as chords from its height to `-inf` or back: the same
    /// sides), of a cell that holds every query it serves within `(lo, hi)`. The entries keep only the
    /// sub-curves whose crossing varies over that box: one whose box grown by twice `reach`
    /// lies right of it, above it or below it crosses no query's cut there, and one wholly
    /// left of it is decided by its chord, a constant if both its ends lie above or below the
    /// box (added to the base).
    pub(super) fn push(
        &mut self,
        base: i64,
        listed: &[u32],
        steps: &[Step],
        (lo, hi): (Point, Point),
        reach: f64,
    ) {
        let r = 2.0 * reach;
        let first = self.entries.len() as u32;
        let mut base = base;
        // A step of `k` reads as `|k|` chords from its height to below every query (or back).
        for &(h, k) in steps {
            let (start_y, end_y) = if k > 0 {
                (h, f64::NEG_INFINITY)
            } else {
                (f64::NEG_INFINITY, h)
            };
            let entry = Entry {
                lo,
                hi,
                start_y,
                end_y,
                sub: CHORD_ONLY,
            };
            self.entries
                .extend(std::iter::repeat_n(entry, k.unsigned_abs() as usize));
        }
        for &i in listed {
            let sub = &self.subs[i as usize];
            let (slo, shi) = (sub.lo, sub.hi);
            let (start_y, end_y) = (sub.start().y, sub.end().y);
            if slo.x - r > hi.x || slo.y - r > hi.y || shi.y + r < lo.y {
                continue;
            }
            let left = shi.x + r < lo.x;
            let side = |y: f64| {
                if y > hi.y {
                    Some(1)
                } else if y < lo.y {
                    Some(0)
                } else {
                    None
                }
            };
            if left && let (Some(a), Some(b)) = (side(start_y), side(end_y)) {
                base += a - b;
                continue;
            }
            self.entries.push(Entry {
                lo: slo,
                hi: shi,
                start_y,
                end_y,
                sub: if left { CHORD_ONLY } else { i },
            });
        }
        let end = self.entries.len() as u32;
        self.splits.push(Split {
            base,
            first,
            end,
            cell: (lo, hi),
        });
    }

    /// The heights of the steps' entries (for the tests).
    #[cfg(test)]
    pub(super) fn step_heights(&self) -> Vec<f64> {
        self.entries
            .iter()
            .filter(|e| e.sub == CHORD_ONLY)
            .filter_map(|e| {
                if e.start_y == f64::NEG_INFINITY {
                    Some(e.end_y)
                } else if e.end_y == f64::NEG_INFINITY {
                    Some(e.start_y)
                } else {
                    None
                }
            })
            .collect()
    }

    /// Keeps only the sub-curves some entry reads (the others, most of a field's, were listed
    /// by cells that did not become split cells, or are decided by their chords alone), their
    /// roots starting from [`MonotoneCurve::with_inverse_start`] from now on (worth its two
    /// divisions only for a sub-curve the queries read; while the cells were being made, the
    /// chord's root served, deciding the same crossings).
    pub(super) fn drop_unread(&mut self) {
        let mut new_index = vec![u32::MAX; self.subs.len()];
        let mut kept = Vec::new();
        for e in self.entries.iter_mut().filter(|e| e.sub != CHORD_ONLY) {
            let i = e.sub as usize;
            if new_index[i] == u32::MAX {
                new_index[i] = kept.len() as u32;
                let mut sub = self.subs[i];
                sub.root = sub.root.map(MonotoneCurve::with_inverse_start);
                kept.push(sub);
            }
            e.sub = new_index[i];
        }
        self.subs = kept;
    }
}

/// The side test of the monotone sub-curve `sub` (its root's form `root`) in a cell of box
/// `cell`: of the tests its box and a fit over each [`Frame`] give, the one that
/// leaves the narrowest band about the curve undecided ([`InverseFit::width_across`] its
/// chord).
fn side_test(
    sub: &RootedSub,
    root: &MonotoneCurve,
    cell: (Point, Point),
    reach: f64,
) -> InverseFit {
    let chord = sub.end() - sub.start();
    let chord = chord * (1.0 / chord.x.hypot(chord.y));
    let mut best = InverseFit::of_box(sub.lo.x, sub.hi.x, reach);
    let mut width = best.width_across(chord);
    // The chord's frame first: on most pieces its fit is tight, and the others are not made.
    for frame in [Frame::Chord, Frame::Heights, Frame::Abscissas] {
        if let Some((f, tight)) = InverseFit::new(root, cell, frame, reach) {
            let w = f.width_across(chord);
            if w < width {
                (best, width) = (f, w);
            }
            if tight {
                break;
            }
        }
    }
    best
}

impl SplitCells {
    /// The side tests of every split cell's entries, for the field's `reach`: a chord's
    /// always left; a monotone sub-curve's [`ImplicitSide`] over its piece at the cell's
    /// heights if every entry's certifies, else each one's [`side_test`]; a cell reading a
    /// sub-curve that is not monotone, or of more than 64 entries, is left to its boxes and
    /// roots.
    pub(super) fn quick_tests(&self, reach: f64) -> QuickTests {
        let mut tests = QuickTests {
            cells: Vec::with_capacity(self.splits.len()),
            implicit: Vec::with_capacity(self.entries.len()),
            fits: Vec::new(),
        };
        for split in &self.splits {
            let entries = &self.entries[split.first as usize..split.end as usize];
            let roots = entries
                .iter()
                .map(|e| match e.sub {
                    CHORD_ONLY => Some(None),
                    k => self.subs[k as usize].root.as_ref().map(Some),
                })
                .collect::<Option<Vec<_>>>();
            let (Some(roots), true) = (roots, entries.len() <= 64) else {
                tests.cells.push(CellTests::Roots);
                continue;
            };
            let from = tests.implicit.len();
            let all = entries.iter().zip(&roots).all(|(e, root)| {
                // An entry whose heights miss the cell's decides none of its queries (they
                // are not within them): any test serves.
                let apart = e.start_y.max(e.end_y) < split.cell.0.y
                    || e.start_y.min(e.end_y) > split.cell.1.y;
                let side = match root {
                    Some(root) if !apart => ImplicitSide::new(root, split.cell, reach),
                    _ => Some(ImplicitSide::always_left()),
                };
                side.map(|side| tests.implicit.push(Quick::of(e, side)))
                    .is_some()
            });
            let index = |v: usize| u32::try_from(v).ok();
            match (all, index(from), index(tests.fits.len())) {
                (true, Some(k), _) => tests.cells.push(CellTests::Implicit(k)),
                (false, _, Some(k)) => {
                    tests.implicit.truncate(from);
                    for (e, root) in entries.iter().zip(&roots) {
                        let side = match root {
                            None => InverseFit::always_left(),
                            Some(root) => {
                                side_test(&self.subs[e.sub as usize], root, split.cell, reach)
                            }
                        };
                        tests.fits.push(Quick::of(e, side));
                    }
                    tests.cells.push(CellTests::Fits(k));
                }
                _ => {
                    tests.implicit.truncate(from);
                    tests.cells.push(CellTests::Roots);
                }
            }
        }
        tests
    }

    /// The entries the split cells read (the making of their side tests costs about this
    /// many times two microseconds).
    pub(super) fn entry_count(&self) -> usize {
        self.entries.len()
    }
}

#[cfg(test)]
impl QuickTests {
    /// Whether split cell `s`'s side tests are implicit equations.
    fn implicit_in(&self, s: usize) -> bool {
        matches!(self.cells[s], CellTests::Implicit(_))
    }

    /// Whether the side tests of split cell `s` (of `len` entries) decide every entry at
    /// whose heights `q` lies; `None` if the cell has none.
    fn decide_all(&self, s: usize, q: Point, len: usize) -> Option<bool> {
        fn all<T: SideTest>(quick: &[Quick<T>], q: Point) -> bool {
            quick.iter().all(|t| {
                let (low, high) = (t.start_y.min(t.end_y), t.start_y.max(t.end_y));
                !(q.y >= low && q.y <= high) || t.side.side(q).1
            })
        }
        match self.cells[s] {
            CellTests::Roots => None,
            CellTests::Implicit(k) => Some(all(&self.implicit[k as usize..k as usize + len], q)),
            CellTests::Fits(k) => Some(all(&self.fits[k as usize..k as usize + len], q)),
        }
    }
}

/// A step of a split cell: `k [h >= q.y]` at height `h`, the sides of the ends at `h` of the
/// sub-curves it does not list, left of it, that end where listed ones start or start where
/// they end.
pub(super) type Step = (f64, i64);

/// The steps (see the module's documentation) of a cell of box `(lo, hi)` (its queries'
/// box) listing the sub-curves `listed` (indices into `subs`), pushed to `steps`: at every
/// point of the box's heights where as many of the listed sub-curves do not end as start
/// (compared exactly), lying left of the box, the step of the others there. `false` (the cell
/// must stay near) if such a point lies within the box's columns.
pub(super) fn steps_of(
    subs: &[RootedSub],
    listed: &[u32],
    (lo, hi): (Point, Point),
    steps: &mut Vec<Step>,
) -> bool {
    // The point's bits, the point, and +1 for a start, -1 for an end.
    type EndAt = ((u64, u64), Point, i64);
    let mut ends: smallvec::SmallVec<[EndAt; 64]> = smallvec::SmallVec::new();
    for &i in listed {
        let s = &subs[i as usize];
        for (p, sign) in [(s.start(), 1), (s.end(), -1)] {
            // (Listed sub-curves have finite control points.)
            if p.y >= lo.y && p.y <= hi.y {
                ends.push(((p.x.to_bits(), p.y.to_bits()), p, sign));
            }
        }
    }
    ends.sort_unstable_by_key(|e| e.0);
    for run in ends.chunk_by(|a, b| a.0 == b.0) {
        let listed_count: i64 = run.iter().map(|e| e.2).sum();
        let p = run[0].1;
        if listed_count == 0 || p.x > hi.x {
            continue;
        }
        if p.x >= lo.x {
            return false;
        }
        steps.push((p.y, -listed_count));
    }
    true
}

/// The steps' sum at height `y`.
pub(super) fn steps_at(steps: &[Step], y: f64) -> i64 {
    steps.iter().map(|&(h, k)| k * i64::from(h >= y)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_testkit::XorShift64;

    fn sub(p: &[Point]) -> RootedSub {
        RootedSub::of(SmallPolynomial::from_points(p).unwrap()).unwrap()
    }

    /// The signed crossing of the ray from `q` towards `-x` by a dense polyline on the cubic
    /// `p` (+1 downwards), counted as the chords count it (an end with `y >= q.y` above).
    fn polyline_crossing(p: &[Point], q: Point) -> i64 {
        let at = |t: f64| {
            let s = 1.0 - t;
            let b = [s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t];
            p.iter()
                .zip(b)
                .fold(Point::new(0.0, 0.0), |a, (&v, w)| a + v * w)
        };
        let n = 20_000;
        let mut total = 0;
        for k in 0..n {
            let (a, b) = (at(k as f64 / n as f64), at((k + 1) as f64 / n as f64));
            let (up_a, up_b) = (a.y >= q.y, b.y >= q.y);
            if up_a != up_b {
                let x = a.x + (b.x - a.x) * (q.y - a.y) / (b.y - a.y);
                if x < q.x {
                    total += i64::from(up_a) - i64::from(up_b);
                }
            }
        }
        total
    }

    /// A listed sub-curve's crossing, where it decides, is the curve's: random cubics whose
    /// ordinates rise or fall, queries in and around their boxes farther than `1e-5` of the box
    /// from them (where a dense polyline crosses as the curve does); one not monotone decides
    /// only outside its box grown by twice the reach, and declines inside it.
    #[test]
    fn a_listed_sub_curves_crossing_is_the_curves() {
        let mut rng = XorShift64::new(17);
        let reach = 1e-12;
        let (mut decided, mut tried) = (0, 0);
        for _ in 0..300 {
            let sign = if rng.next_f64() < 0.5 { 1.0 } else { -1.0 };
            let mut y = 0.0;
            let p: Vec<Point> = (0..4)
                .map(|_| {
                    y += 0.05 + rng.next_f64();
                    Point::new(2.0 * rng.next_f64() - 1.0, sign * y)
                })
                .collect();
            let s = sub(&p);
            assert!(s.root.is_some());
            for _ in 0..100 {
                let q = Point::new(
                    s.lo.x - 0.5 + (s.hi.x - s.lo.x + 1.0) * rng.next_f64(),
                    s.lo.y - 0.5 + (s.hi.y - s.lo.y + 1.0) * rng.next_f64(),
                );
                // Keep away from the curve and from its ends' heights.
                let near = (0..=2000).any(|k| {
                    let t = k as f64 / 2000.0;
                    let u = 1.0 - t;
                    let b = [u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t];
                    let c = p
                        .iter()
                        .zip(b)
                        .fold(Point::new(0.0, 0.0), |a, (&v, w)| a + v * w);
                    (c - q).length() < 1e-3
                }) || (q.y - p[0].y).abs() < 1e-3
                    || (q.y - p[3].y).abs() < 1e-3;
                if near {
                    continue;
                }
                tried += 1;
                if let Some(k) = s.crossing(q, reach) {
                    decided += 1;
                    assert_eq!(k, polyline_crossing(&p, q), "{p:?} {q:?}");
                }
            }
        }
        assert!(decided == tried && tried > 10_000, "{decided} of {tried}");
        // A cubic with a horizontal tangent inside: decided outside its grown box only.
        let bump = sub(&[
            Point::new(0.0, 0.0),
            Point::new(1.0, 2.0),
            Point::new(2.0, 2.0),
            Point::new(3.0, 0.0),
        ]);
        assert!(bump.root.is_none());
        assert_eq!(bump.crossing(Point::new(5.0, 1.0), reach), Some(0));
        assert_eq!(bump.crossing(Point::new(5.0, -1.0), reach), Some(0));
        assert_eq!(bump.crossing(Point::new(-1.0, 1.0), reach), Some(0));
        assert_eq!(bump.crossing(Point::new(1.5, 1.0), reach), None);
        assert_eq!(
            bump.crossing(Point::new(3.0 + 1.5 * reach, 1.0), reach),
            None
        );
    }

    /// A split cell's entries give every query in its box the sum of its listed sub-curves'
    /// crossings, or decline where one of them does: the sub-curves right of the box, above
    /// it or below it dropped, those left of it read by their chords (their constant part
    /// folded into the base), the others by box and root; and its steps' sum. Random cubics
    /// (rising, falling, bumps) around a box, queries in it and on its sides.
    #[test]
    fn a_split_cells_entries_sum_as_its_listed_sub_curves() {
        let mut rng = XorShift64::new(29);
        let reach = 1e-12;
        let (lo, hi) = (Point::new(0.0, 0.0), Point::new(1.0, 1.0));
        let (mut decided, mut dropped, mut chords) = (0, 0, 0);
        // Queries in cells whose side tests serve, and those every test decides; cells whose
        // tests are implicit equations.
        let (mut usable, mut by_tests, mut implicit) = (0, 0, 0);
        for round in 0..300 {
            let mut subs: Vec<RootedSub> = (0..8)
                .map(|_| {
                    let o = Point::new(4.0 * rng.next_f64() - 1.5, 4.0 * rng.next_f64() - 1.5);
                    let tall = 1.0 + 3.0 * rng.next_f64();
                    let p: Vec<Point> = (0..4)
                        .map(|_| {
                            o + Point::new(rng.next_f64() - 0.5, tall * (rng.next_f64() - 0.5))
                        })
                        .collect();
                    sub(&p)
                })
                .collect();
            // One grazing the box from above, below or the right, half the reach away.
            let (g, h) = (0.5 * reach, rng.next_f64());
            subs.push(sub(&match round % 3 {
                0 => [Point::new(h, 1.0 + g), Point::new(h + 0.1, 1.5)],
                1 => [Point::new(h, -0.5), Point::new(h + 0.1, -g)],
                _ => [Point::new(1.0 + g, h), Point::new(1.5, h + 0.1)],
            }));
            let listed: Vec<u32> = (0..subs.len() as u32).collect();
            let base = round as i64 - 150;
            // Steps at random heights of the box (and at its ends and at a query's height).
            let steps: Vec<Step> = (0..round % 4)
                .map(|j| {
                    let y = [rng.next_f64(), 0.0, 1.0, h][j];
                    (y, [1, -1, 2, -2][(round / 4) % 4])
                })
                .collect();
            let mut cells = SplitCells::over(subs.clone());
            cells.push(base, &listed, &steps, (lo, hi), reach);
            cells.drop_unread();
            let tests = cells.quick_tests(reach);
            implicit += usize::from(tests.implicit_in(0));
            let entries = &cells.entries;
            let step_entries: usize = steps.iter().map(|s| s.1.unsigned_abs() as usize).sum();
            dropped += listed.len() + step_entries - entries.len();
            chords += entries.iter().filter(|e| e.sub == CHORD_ONLY).count() - step_entries;
            for k in 0..200 {
                let t = if k % 10 < 5 { rng.next_f64() } else { h };
                let q = match k % 5 {
                    0 => Point::new(t, 0.0),
                    1 => Point::new(t, 1.0),
                    2 => Point::new(0.0, t),
                    3 => Point::new(1.0, t),
                    _ => Point::new(t, rng.next_f64()),
                };
                let want: Option<i64> = subs.iter().map(|s| s.crossing(q, reach)).sum();
                let got = cells.crossings(0, q, reach, None);
                let want = want.map(|w| base + w + steps_at(&steps, q.y));
                assert_eq!(got, want, "round {round} q {q:?}");
                // The side tests give the same, or walk where the roots walk.
                let quick = cells.crossings(0, q, reach, Some(&tests));
                assert_eq!(quick, want, "round {round} q {q:?}: side tests");
                if let Some(all) = tests.decide_all(0, q, cells.entries.len()) {
                    usable += 1;
                    by_tests += usize::from(all);
                }
                decided += usize::from(got.is_some());
            }
        }
        assert!(
            decided > 30_000 && dropped > 300 && chords > 100,
            "{decided} {dropped} {chords}"
        );
        assert!(
            usable > 5_000 && by_tests * 10 >= usable * 9,
            "{by_tests} of {usable} decided by the side tests"
        );
        // Both kinds of tests served (33 cells' implicit equations certify at this seed).
        assert!(
            (15..=285).contains(&implicit),
            "{implicit} of 300 cells implicit"
        );
    }

    /// A cell's steps: at each point of its heights where the listed sub-curves do not
    /// balance (as many starting as ending, exactly), left of the cell, minus their count;
    /// none right of it or outside its heights; a point within its columns refuses the cell.
    #[test]
    fn steps_where_the_listed_ends_do_not_balance() {
        let p = Point::new;
        // The cell: [0, 1] x [0, 1]. A chain through it from the left, at height 0.5, to the
        // right, and one from (-1, 0.25) up out of it.
        let subs = vec![
            sub(&[p(-2.0, 0.5), p(-0.5, 0.5)]),
            sub(&[p(-0.5, 0.5), p(1.5, 0.6)]),
            sub(&[p(1.5, 0.6), p(3.0, 0.6)]),
            sub(&[p(-1.0, 0.25), p(0.5, 2.0)]),
        ];
        let cell = (p(0.0, 0.0), p(1.0, 1.0));
        let steps = |listed: &[u32]| {
            let mut out = Vec::new();
            steps_of(&subs, listed, cell, &mut out).then_some(out)
        };
        // Listing the middle one: it starts at (-0.5, 0.5), left: the unlisted one ending
        // there adds -(+1) [0.5 >= y]; its end, right of the cell, adds nothing.
        assert_eq!(steps(&[1]), Some(vec![(0.5, -1)]));
        // Listing the first two too: their shared end balances; (-2, 0.5) starts the first.
        assert_eq!(steps(&[0, 1]), Some(vec![(0.5, -1)]));
        // The fourth's start, left of the cell at 0.25; its end above the cell's heights.
        assert_eq!(steps(&[3]), Some(vec![(0.25, -1)]));
        let mut both = steps(&[1, 3]).unwrap();
        both.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert_eq!(both, vec![(0.25, -1), (0.5, -1)]);
        // An end within the cell's columns that does not balance refuses it.
        let inside = vec![sub(&[p(-1.0, 0.5), p(0.5, 0.5)])];
        assert!(
            !steps_of(&inside, &[0], cell, &mut Vec::new()),
            "an unbalanced end inside the cell"
        );
        // One ulp off does not balance.
        let off = vec![
            sub(&[p(-2.0, 0.5), p(-0.5, 0.5)]),
            sub(&[p(-0.5, 0.5f64.next_up()), p(1.5, 0.6)]),
        ];
        let mut out = Vec::new();
        assert!(steps_of(&off, &[0, 1], cell, &mut out));
        out.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        assert_eq!(out, vec![(0.5, -1), (0.5, 1), (0.5f64.next_up(), -1)]);
        // The steps' sum at a height.
        assert_eq!(steps_at(&[(0.25, -1), (0.5, 2)], 0.3), 2);
        assert_eq!(steps_at(&[(0.25, -1), (0.5, 2)], 0.25), 1);
    }
}
