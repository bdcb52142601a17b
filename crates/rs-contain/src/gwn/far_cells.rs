//! Far cells of a winding field: a grid over the field's box whose cells away from every
//! curve know the crossings a query in them counts, so a batch's query there skips the walk.
//!
//! Why one count serves a whole region: outside the band round the curves the crossings the
//! walk counts (the signed crossings of the cut, the ray from the query towards `-x`, by the
//! chords it settles) are exactly the crossings of the curves themselves (see
//! [`WindingField`](super::WindingField)'s Semantics). They change only where the query
//! crosses a curve, or crosses the height of an open chain's end (where the cut sweeps over
//! the end). A grid cell that lies farther than the band's reach from every curve and holds no
//! chain end's height therefore gives every query in it the same crossings; so does every cell
//! of a connected region of such cells. One walk per region (from a cell's centre) finds them,
//! and the query adds only its chains' ends, as the walk's query does: the same value bit for
//! bit.
//!
//! Once the near cells' queries are many ([`SPLIT_AFTER_WALKS_PER_NEAR_CELL`] per near cell),
//! the near cells that qualify become *split cells* (see `split_cells`): a base count, the
//! few sub-curves through the cell, whose crossings a query decides from their roots, and the
//! steps where the others' ends left of the cell meet them at its heights.

use rs_spline::{Point, RationalBezier};

use std::ops::Deref;
use std::ops::RangeInclusive;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicUsize, Ordering};

use super::curve::{Halve, SmallPolynomial, SubCurve, control_box};
use super::split_cells::{
    MOST_LISTED, QuickTests, RootedSub, SplitCells, Step, steps_at, steps_of,
};

/// Cells per side: `2^8` (256 KiB of counts). On the GWN paper's shapes, random points of the
/// shapes' boxes took 0.87-0.95 of the time at `2^8` they took at `2^7` (where 54-82% of them
/// lie in far cells at `2^6`, 70-90% at `2^7`).
const SIDE_BITS: u32 = 8;

/// Cells per side.
const SIDE: usize = 1 << SIDE_BITS;

/// A cell within reach of a curve, or holding a chain end's height: its queries walk (unless
/// it is made a split cell).
const NEAR: i32 = i32::MIN;

/// A far cell whose region has no count yet (only while building).
const UNSEEN: i32 = i32::MIN + 1;

/// A near cell's entry `SPLIT_FIRST + s` marks split cell `s` (see `split_cells`).
const SPLIT_FIRST: i32 = i32::MIN + 2;

/// The least count a far cell holds (lower counts, of no real domain, leave it near).
const FIRST_COUNT: i32 = SPLIT_FIRST + (SIDE * SIDE) as i32;

// The split cells' marks and the counts must not overlap.
const _: () = assert!(SIDE * SIDE < (i32::MAX / 2) as usize);

/// Most cells one sub-curve's grown box may mark and still be listed by them: a larger box
/// (a piece not halved small enough) leaves its cells to the walk.
const MOST_CELLS_LISTED: usize = 16;

/// Halvings of a piece at most, to cover it by boxes of about two cells (a sub-curve still
/// larger after them marks its whole box, which is only coarser).
const MAX_SPLITS: u32 = 12;

/// Halvings of a piece beyond [`MAX_SPLITS`], at most, for the split cells' sub-curves: a
/// polynomial leaf the roots cannot take is halved while one of its halves can be taken, down
/// to `MAX_SPLITS + EXTRA_SPLITS` halvings of the piece.
const EXTRA_SPLITS: u32 = 4;

/// The widest growth of the curves' boxes, in cells, for which a field has far cells.
const MAX_GROW_CELLS: f64 = 2.0;

/// The margin beyond the band's reach that keeps a far cell's queries far from the curves,
/// relative to the grid's diagonal (the walk's own roundings are below `1e-12` of it).
const RELATIVE_MARGIN: f64 = 1e-9;

/// The far cells of a field (see the module documentation).
#[derive(Clone, Debug)]
pub(super) struct FarCells {
    lo: Point,
    hi: Point,
    /// Cells per unit length in `x` and in `y`.
    per_unit: Point,
    /// Per cell, row by row: the crossings of its queries, or [`NEAR`].
    counts: Vec<i32>,
    /// The band's reach (the split cells' roots decide only beyond twice it).
    reach: f64,
    /// How far the curves' boxes were grown to mark the near cells.
    grow: f64,
    /// The rows holding an open chain's end (all of them for an end not a number).
    chain_rows: Vec<bool>,
    /// The split cells, once made.
    split: LazySplits,
}

/// The split cells, made once the near cells' queries are many: their making costs about
/// half a microsecond a near cell on the shapes of the GWN paper (1.5-6 ms, listing their
/// sub-curves included: more where many small pieces give many sub-curves a cell), and a query
/// they answer saves a few hundredths of one.
#[derive(Debug, Default)]
struct LazySplits {
    /// The counts with the split cells, and the split cells.
    made: OnceLock<Splits>,
    /// Queries that found no count so far (in near cells, or outside the grid).
    walks: AtomicUsize,
    /// The split cells are made once `walks` reaches this.
    after: usize,
    /// The split cells' side tests, made once `split_queries` reaches
    /// [`QUICK_AFTER_QUERIES_PER_ENTRY`] per entry.
    quick: OnceLock<QuickTests>,
    /// Queries the split cells answered so far.
    split_queries: AtomicUsize,
}

impl Clone for LazySplits {
    fn clone(&self) -> Self {
        Self {
            made: self.made.clone(),
            walks: AtomicUsize::new(self.walks.load(Ordering::Relaxed)),
            after: self.after,
            quick: self.quick.clone(),
            split_queries: AtomicUsize::new(self.split_queries.load(Ordering::Relaxed)),
        }
    }
}

/// Queries answered by the split cells, per entry of theirs, after which their side tests
/// are made: a test costs about two microseconds to make (butterfly: 14,412 entries, about 25
/// ms), and saves a query in its cell about two hundredths of one, so by then the queries
/// answered would about have paid for the tests had they had them.
const QUICK_AFTER_QUERIES_PER_ENTRY: usize = 64;

/// The counts with the split cells marked in them (`SPLIT_FIRST + s` for split cell `s`), and
/// the split cells.
#[derive(Clone, Debug)]
struct Splits {
    counts: Vec<i32>,
    cells: SplitCells,
}

/// Most sub-curves listed for the split cells (about 100 bytes each while they are made):
/// a field of more, many small pieces, gets none.
const MOST_SUB_CURVES: usize = 1 << 18;

/// Near-cell queries per near cell after which the split cells are made: about as many as the
/// queries whose savings pay for them (a split cell costs about half a microsecond to make,
/// and saves 0.03-0.08 us a query), so that a run of few queries near the curves does not pay
/// for them (a fresh field's first batch of random points on the GWN paper's shapes makes
/// them not at all, one of 10^5 points near the curves of the large shapes after about
/// 60,000 of them).
const SPLIT_AFTER_WALKS_PER_NEAR_CELL: usize = 8;

/// What the marking of the curves records for the split cells: the sub-curves, the cells
/// each one's grown box marks, and the cells no split can serve.
#[derive(Debug, Default)]
struct Listing {
    subs: Vec<RootedSub>,
    /// `(cell, sub-curve)`.
    pairs: Vec<(u32, u32)>,
    /// Cells marked by a sub-curve no split cell may list (rational, of a box marking more
    /// than [`MOST_CELLS_LISTED`] cells, or outside the grid).
    unlisted: Vec<bool>,
    /// The sub-curves covering the curves, listed or not.
    covering: usize,
    /// More sub-curves than [`MOST_SUB_CURVES`]: no split cells.
    too_many: bool,
}

impl FarCells {
    /// The far cells of the grid over `[lo, hi]` for `pieces` whose band reaches `reach` from
    /// them, with open chains from `s` to `e` in `chain_ends`; `crossings(q)` is the walk's
    /// count at `q` (`None` if it found `q` on or near a curve). `None` for a box of no width
    /// or height, or not finite.
    pub(super) fn new(
        lo: Point,
        hi: Point,
        reach: f64,
        pieces: &[RationalBezier],
        chain_ends: &[(Point, Point)],
        mut crossings: impl FnMut(Point) -> Option<i64>,
    ) -> Option<Self> {
        let per_unit = |lo: f64, hi: f64| {
            let s = SIDE as f64 / (hi - lo);
            (s.is_finite() && s > 0.0).then_some(s)
        };
        let per_unit = Point::new(per_unit(lo.x, hi.x)?, per_unit(lo.y, hi.y)?);
        let scale = lo.x.abs().max(lo.y.abs()).max(hi.x.abs()).max(hi.y.abs());
        let diagonal = (hi.x - lo.x).hypot(hi.y - lo.y);
        let grow = reach + RELATIVE_MARGIN * diagonal + 64.0 * f64::EPSILON * scale;
        // A band wider than a couple of cells leaves few far cells (and would make each box
        // mark many): no grid then.
        let cell = (1.0 / per_unit.x).min(1.0 / per_unit.y);
        if grow.is_nan() || grow > MAX_GROW_CELLS * cell {
            return None;
        }
        let mut cells = Self {
            lo,
            hi,
            per_unit,
            counts: vec![UNSEEN; SIDE * SIDE],
            reach,
            grow,
            chain_rows: Vec::new(),
            split: LazySplits::default(),
        };
        cells.mark_curves(pieces);
        let mut marked = [false; SIDE];
        for &(s, e) in chain_ends {
            cells.mark_row_of(s.y, &mut marked);
            cells.mark_row_of(e.y, &mut marked);
        }
        cells.count_regions(&mut crossings);
        cells.chain_rows = marked.to_vec();
        let near = cells.counts.iter().filter(|&&k| k == NEAR).count();
        cells.split = LazySplits {
            after: SPLIT_AFTER_WALKS_PER_NEAR_CELL * near,
            ..LazySplits::default()
        };
        Some(cells)
    }

    /// The crossings the walk counts at `q`, if `q` lies in a far cell, or in a split cell whose
    /// sub-curves' roots (or side tests) decide them; a query in a split cell adds one to
    /// `split_queries`.
    #[inline(always)]
    pub(super) fn crossings(&self, q: Point, split_queries: &mut usize) -> Option<i64> {
        let i = self.cell(q)?;
        match self.split.made.get() {
            None => Some(self.counts[i]).filter(|&k| k != NEAR).map(i64::from),
            Some(s) => s.crossings(i, q, self.reach, self.split.quick.get(), split_queries),
        }
    }

    /// Tells the grid that `n` queries found no count ([`FarCells::crossings`] gave `None`):
    /// once they reach [`SPLIT_AFTER_WALKS_PER_NEAR_CELL`] per near cell, the split cells are
    /// made (by the call that reaches that count) for the field's `pieces` (those the grid was
    /// made for).
    ///
    /// Once the split cells are made, `split_queries` (the queries they answered) count
    /// towards their side tests ([`QUICK_AFTER_QUERIES_PER_ENTRY`]).
    pub(super) fn note_walks(&self, n: usize, split_queries: usize, pieces: &[RationalBezier]) {
        let split = &self.split;
        if let Some(made) = split.made.get() {
            if split_queries == 0 || split.quick.get().is_some() {
                return;
            }
            let after = QUICK_AFTER_QUERIES_PER_ENTRY.saturating_mul(made.cells.entry_count());
            let before = split
                .split_queries
                .fetch_add(split_queries, Ordering::Relaxed);
            if before < after && before.saturating_add(split_queries) >= after {
                split
                    .quick
                    .get_or_init(|| made.cells.quick_tests(self.reach));
            }
            return;
        }
        if n == 0 {
            return;
        }
        // Only the call that brings the count to the threshold makes them; others, meanwhile,
        // walk on.
        let before = split.walks.fetch_add(n, Ordering::Relaxed);
        if before < split.after && before.saturating_add(n) >= split.after {
            split
                .made
                .get_or_init(|| self.splits(self.list_curves(pieces)));
        }
    }

    /// The point at grid coordinates `(c, r)` (for whole ones, cell `(c, r)`'s lower left
    /// corner).
    fn at(&self, c: f64, r: f64) -> Point {
        Point::new(
            self.lo.x + c / self.per_unit.x,
            self.lo.y + r / self.per_unit.y,
        )
    }

    /// The cell holding `q`; `None` outside the grid (or not a number).
    #[inline(always)]
    fn cell(&self, q: Point) -> Option<usize> {
        let inside = q.x >= self.lo.x && q.x <= self.hi.x && q.y >= self.lo.y && q.y <= self.hi.y;
        inside.then(|| self.column(q.x) + SIDE * self.row(q.y))
    }

    /// The column of abscissa `x` in `[lo.x, hi.x]`: non-decreasing in `x` (each operation
    /// rounds monotonically), so a cell whose column lies outside a box's columns holds no
    /// point of the box.
    #[inline(always)]
    fn column(&self, x: f64) -> usize {
        (((x - self.lo.x) * self.per_unit.x) as usize).min(SIDE - 1)
    }

    /// The row of ordinate `y` in `[lo.y, hi.y]` (as [`FarCells::column`]).
    #[inline(always)]
    fn row(&self, y: f64) -> usize {
        (((y - self.lo.y) * self.per_unit.y) as usize).min(SIDE - 1)
    }

    /// Marks every cell holding a point within the growth of a curve: each covering
    /// sub-curve's control box ([`FarCells::cover`]) grown by the growth.
    fn mark_curves(&mut self, pieces: &[RationalBezier]) {
        let mut counts = std::mem::take(&mut self.counts);
        self.cover(pieces, false, &mut |_, _, (blo, bhi)| {
            if let Some((columns, rows)) = self.box_cells(blo, bhi, self.grow) {
                for r in rows {
                    counts[r * SIDE + columns.start()..=r * SIDE + columns.end()].fill(NEAR);
                }
            }
        });
        self.counts = counts;
    }

    /// Gives `leaf(points, polynomial, (lo, hi))` each sub-curve covering `pieces`: its control
    /// points (a rational one's are not its curve's Bezier points), whether its piece is
    /// polynomial, and its control box (which holds it). Each piece is halved until its
    /// sub-curves' boxes span about two cells, at most [`MAX_SPLITS`] times; with `extra`, a
    /// polynomial one the split cells' roots cannot take (a horizontal tangent in it or at an
    /// end) is halved further while one of its halves can be taken (see [`EXTRA_SPLITS`]).
    fn cover(
        &self,
        pieces: &[RationalBezier],
        extra: bool,
        leaf: &mut impl FnMut(&[Point], bool, (Point, Point)),
    ) {
        for piece in pieces {
            let c = SubCurve::of(piece);
            match SmallPolynomial::of(&c) {
                Some(small) => self.cover_piece(small, true, extra, leaf),
                None => self.cover_piece(c, false, extra, leaf),
            }
        }
    }

    /// [`FarCells::cover`] for one piece, `c`.
    fn cover_piece<C: Halve + Deref<Target = [Point]>>(
        &self,
        c: C,
        polynomial: bool,
        extra: bool,
        leaf: &mut impl FnMut(&[Point], bool, (Point, Point)),
    ) {
        let (cell_x, cell_y) = (1.0 / self.per_unit.x, 1.0 / self.per_unit.y);
        let monotone = |c: &C| polynomial && RootedSub::would_have_root(c);
        let mut stack = vec![(c, 0)];
        while let Some((c, splits)) = stack.pop() {
            let (blo, bhi) = control_box(&c);
            let small = bhi.x - blo.x <= 2.0 * cell_x && bhi.y - blo.y <= 2.0 * cell_y;
            let halves = if !(small || splits >= MAX_SPLITS) {
                Some(c.halves())
            } else if extra && !monotone(&c) && splits < MAX_SPLITS + EXTRA_SPLITS {
                // Only where it helps: a half without the tangent (a leaf that stays not
                // monotone in both halves, such as one with coincident control points at
                // both ends, is kept whole).
                Some(c.halves()).filter(|(l, r)| monotone(l) || monotone(r))
            } else {
                None
            };
            match halves {
                Some((l, r)) => {
                    stack.push((r, splits + 1));
                    stack.push((l, splits + 1));
                }
                None => leaf(&c, polynomial, (blo, bhi)),
            }
        }
    }

    /// The columns and rows of the cells holding a point of the box `[blo, bhi]` grown by
    /// `grow`; a box with a NaN corner holds them all, one wholly outside the grid none.
    fn box_cells(
        &self,
        blo: Point,
        bhi: Point,
        grow: f64,
    ) -> Option<(RangeInclusive<usize>, RangeInclusive<usize>)> {
        let (x0, x1) = (blo.x - grow, bhi.x + grow);
        let (y0, y1) = (blo.y - grow, bhi.y + grow);
        // (Every comparison with a NaN fails: its box is not missed, and `max` and `min`
        // below take the grid's side.)
        let misses = x1 < self.lo.x || x0 > self.hi.x || y1 < self.lo.y || y0 > self.hi.y;
        if misses {
            return None;
        }
        let columns = self.column(x0.max(self.lo.x))..=self.column(x1.min(self.hi.x));
        let rows = self.row(y0.max(self.lo.y))..=self.row(y1.min(self.hi.y));
        Some((columns, rows))
    }

    /// The sub-curves that cover the curves for the split cells ([`FarCells::cover`], halving
    /// further where that helps the roots; none past [`MOST_SUB_CURVES`]), each with the cells
    /// its box grown by the growth holds (all near).
    fn list_curves(&self, pieces: &[RationalBezier]) -> Listing {
        let mut listing = Listing {
            unlisted: vec![false; SIDE * SIDE],
            ..Listing::default()
        };
        self.cover(pieces, true, &mut |p, polynomial, (blo, bhi)| {
            if listing.too_many {
                return;
            }
            let cells = self.box_cells(blo, bhi, self.grow);
            let marks = cells
                .as_ref()
                .map_or(0, |(c, r)| c.clone().count() * r.clone().count());
            let sub = rooted(p, polynomial)
                .filter(|_| (1..=MOST_CELLS_LISTED).contains(&marks))
                .map(|r| {
                    listing.subs.push(r);
                    (listing.subs.len() - 1) as u32
                });
            listing.covering += 1;
            listing.too_many = listing.covering > MOST_SUB_CURVES;
            if let Some((columns, rows)) = cells {
                for r in rows {
                    let row = r * SIDE + columns.start()..=r * SIDE + columns.end();
                    match sub {
                        Some(s) => listing.pairs.extend(row.map(|i| (i as u32, s))),
                        None => listing.unlisted[row].fill(true),
                    }
                }
            }
        });
        listing
    }

    /// Marks the row holding ordinate `y` (if the grid reaches it) unless `marked` says it is
    /// already: queries above and below that height count a chain's end differently.
    fn mark_row_of(&mut self, y: f64, marked: &mut [bool; SIDE]) {
        if y >= self.lo.y && y <= self.hi.y {
            let r = self.row(y);
            if !std::mem::replace(&mut marked[r], true) {
                self.counts[r * SIDE..(r + 1) * SIDE].fill(NEAR);
            }
        } else if y.is_nan() {
            // Every row may hold it: every cell is near, and no row may be split.
            self.counts.fill(NEAR);
            marked.fill(true);
        }
    }

    /// Gives every connected region of far cells (through their sides) the count of a walk
    /// from the centre of one of its cells; a region whose walk finds no count (or whose
    /// centre rounds into another cell) is marked near. The regions are found by their rows'
    /// runs of far cells, a run joined to every run of the row below that shares a column
    /// (union-find): a pass over the cells and one over the runs.
    fn count_regions(&mut self, crossings: &mut impl FnMut(Point) -> Option<i64>) {
        // Runs as (row, first column, end column), row by row; `rows[r]..rows[r + 1]` are
        // row r's.
        let mut runs: Vec<(usize, usize, usize)> = Vec::new();
        let mut rows = Vec::with_capacity(SIDE + 1);
        for r in 0..SIDE {
            rows.push(runs.len());
            let row = &self.counts[r * SIDE..(r + 1) * SIDE];
            let mut c = 0;
            while c < SIDE {
                if row[c] == UNSEEN {
                    let start = c;
                    while c < SIDE && row[c] == UNSEEN {
                        c += 1;
                    }
                    runs.push((r, start, c));
                } else {
                    c += 1;
                }
            }
        }
        rows.push(runs.len());
        let mut parent: Vec<usize> = (0..runs.len()).collect();
        for r in 1..SIDE {
            let (below, this) = (rows[r - 1]..rows[r], rows[r]..rows[r + 1]);
            let (mut i, mut j) = (below.start, this.start);
            while i < below.end && j < this.end {
                let ((_, a0, a1), (_, b0, b1)) = (runs[i], runs[j]);
                if a0 < b1 && b0 < a1 {
                    let (ra, rb) = (root(&mut parent, i), root(&mut parent, j));
                    parent[ra.max(rb)] = ra.min(rb);
                }
                // The run ending first meets no later run of the other row.
                if a1 <= b1 {
                    i += 1;
                } else {
                    j += 1;
                }
            }
        }
        // A set's root is its first run (the lesser root becomes the parent), so it gets its
        // count before the set's other runs read it.
        let mut count = vec![NEAR; runs.len()];
        for (k, &(r, start, end)) in runs.iter().enumerate() {
            let first = root(&mut parent, k);
            count[k] = if first == k {
                self.region_count(r * SIDE + start, crossings)
            } else {
                count[first]
            };
            self.counts[r * SIDE + start..r * SIDE + end].fill(count[k]);
        }
    }

    /// The split cells (see `split_cells`) of the near cells that qualify, from `listing`:
    /// outside the rows of the open chains' ends (`chain_rows`), marked only by polynomial
    /// sub-curves of small boxes, at most [`MOST_LISTED`], whose ends at the cell's heights
    /// (grown by the growth) balance within its columns (their steps, [`steps_of`], taken
    /// where they do not, left of it). Each takes its base from a neighbour whose count is
    /// known at a point of their common side, breadth first from the far cells; one no
    /// neighbour can give its base (every point tried too near a sub-curve) stays near.
    fn splits(&self, listing: Listing) -> Splits {
        let Listing {
            subs,
            mut pairs,
            unlisted,
            too_many,
            ..
        } = listing;
        if too_many {
            pairs.clear();
        }
        pairs.sort_unstable();
        pairs.dedup();
        let mut made = Splits {
            counts: self.counts.clone(),
            cells: SplitCells::over(subs),
        };
        // Per candidate cell, its listed sub-curves' range in `lists` and its steps' in
        // `steps`.
        let mut lists: Vec<u32> = Vec::new();
        let mut steps: Vec<Step> = Vec::new();
        let mut candidate: Vec<[u32; 4]> = Vec::new();
        let mut candidate_of = vec![u32::MAX; SIDE * SIDE];
        for run in pairs.chunk_by(|a, b| a.0 == b.0) {
            let i = run[0].0 as usize;
            let r = i / SIDE;
            if unlisted[i]
                || self.chain_rows[r]
                || run.len() > MOST_LISTED
                || self.counts[i] != NEAR
            {
                continue;
            }
            let first = lists.len() as u32;
            lists.extend(run.iter().map(|&(_, s)| s));
            let first_step = steps.len();
            let listed = &lists[first as usize..];
            if !steps_of(&made.cells.subs, listed, self.cell_box(i), &mut steps) {
                lists.truncate(first as usize);
                steps.truncate(first_step);
                continue;
            }
            candidate_of[i] = candidate.len() as u32;
            candidate.push([
                first,
                lists.len() as u32,
                first_step as u32,
                steps.len() as u32,
            ]);
        }
        let neighbours = |i: usize| {
            let (c, r) = (i % SIDE, i / SIDE);
            [
                (c > 0).then(|| i - 1),
                (c + 1 < SIDE).then(|| i + 1),
                (r > 0).then(|| i - SIDE),
                (r + 1 < SIDE).then(|| i + SIDE),
            ]
            .into_iter()
            .flatten()
        };
        let mut queue: std::collections::VecDeque<usize> = (0..SIDE * SIDE)
            .filter(|&i| {
                self.counts[i] >= FIRST_COUNT && neighbours(i).any(|j| candidate_of[j] != u32::MAX)
            })
            .collect();
        while let Some(a) = queue.pop_front() {
            for b in neighbours(a) {
                let k = candidate_of[b];
                if k == u32::MAX || made.counts[b] != NEAR {
                    continue;
                }
                let [first, end, first_step, end_step] = candidate[k as usize];
                let listed = &lists[first as usize..end as usize];
                let steps = &steps[first_step as usize..end_step as usize];
                if let Some(base) = self.base_across(&made, a, b, listed, steps) {
                    made.counts[b] = SPLIT_FIRST + made.cells.len() as i32;
                    made.cells
                        .push(base, listed, steps, self.cell_box(b), self.reach);
                    queue.push_back(b);
                }
            }
        }
        made.cells.drop_unread();
        made
    }

    /// Cell `i`'s box grown by the curves' growth (which holds every query the grid puts in
    /// it).
    fn cell_box(&self, i: usize) -> (Point, Point) {
        let (c, r) = ((i % SIDE) as f64, (i / SIDE) as f64);
        let g = Point::new(self.grow, self.grow);
        (self.at(c, r) - g, self.at(c + 1.0, r + 1.0) + g)
    }

    /// The base of candidate cell `b` (listing the sub-curves `listed`) from its neighbour
    /// `a`'s count at points of their common side (the middle, then the quarters): the first
    /// point that decides gives it, and the next that decides, if any, must agree (which the
    /// argument ensures: a second opinion where one is at hand), else `None`.
    fn base_across(
        &self,
        made: &Splits,
        a: usize,
        b: usize,
        listed: &[u32],
        steps: &[Step],
    ) -> Option<i64> {
        let (ca, ra) = (a % SIDE, a / SIDE);
        let (cb, rb) = (b % SIDE, b / SIDE);
        let side = |f: f64| {
            if ra == rb {
                self.at(ca.max(cb) as f64, ra as f64 + f)
            } else {
                self.at(ca as f64 + f, ra.max(rb) as f64)
            }
        };
        let mut base = None;
        for f in [0.5, 0.25, 0.75] {
            let e = side(f);
            let at_a = made.crossings(a, e, self.reach, None, &mut 0);
            let listed = made.cells.listed_crossings(listed, e, self.reach);
            if let (Some(at_a), Some(listed)) = (at_a, listed) {
                let here = at_a - listed - steps_at(steps, e.y);
                match base {
                    None => base = Some(here),
                    Some(b) => return (b == here).then_some(b),
                }
            }
        }
        base
    }

    /// The walk's count at the centre of cell `i`, [`NEAR`] if it has none.
    fn region_count(&self, i: usize, crossings: &mut impl FnMut(Point) -> Option<i64>) -> i32 {
        let (c, r) = (i % SIDE, i / SIDE);
        let centre = self.at(c as f64 + 0.5, r as f64 + 0.5);
        (self.cell(centre) == Some(i))
            .then(|| crossings(centre))
            .flatten()
            .and_then(|k| i32::try_from(k).ok())
            .filter(|&k| k >= FIRST_COUNT)
            .unwrap_or(NEAR)
    }

    /// The share of cells that are far (for the tests).
    #[cfg(test)]
    pub(super) fn far_share(&self) -> f64 {
        self.counts.iter().filter(|&&k| k >= FIRST_COUNT).count() as f64 / self.counts.len() as f64
    }

    /// The share of cells that are split (for the tests); `None` before they are made.
    #[cfg(test)]
    pub(super) fn split_share(&self) -> Option<f64> {
        let made = self.split.made.get()?;
        Some(made.cells.len() as f64 / self.counts.len() as f64)
    }
}

impl Splits {
    /// The crossings of a query `q` in cell `i` ([`FarCells::crossings`]), with the split
    /// cells' side tests `tests` once made; a query in a split cell adds one to
    /// `split_queries`.
    #[inline(always)]
    fn crossings(
        &self,
        i: usize,
        q: Point,
        reach: f64,
        tests: Option<&QuickTests>,
        split_queries: &mut usize,
    ) -> Option<i64> {
        let k = self.counts[i];
        if k >= FIRST_COUNT {
            Some(i64::from(k))
        } else if k == NEAR {
            None
        } else {
            *split_queries += 1;
            self.cells
                .crossings((k - SPLIT_FIRST) as usize, q, reach, tests)
        }
    }
}

/// The sub-curve with control points `p` as the split cells list it, if its piece is
/// `polynomial` (a rational sub-curve's points are not its curve's Bezier points).
fn rooted(p: &[Point], polynomial: bool) -> Option<RootedSub> {
    polynomial
        .then(|| SmallPolynomial::from_points(p))
        .flatten()
        .and_then(RootedSub::of)
}

/// The root of run `k`'s set, halving the path to it on the way.
fn root(parent: &mut [usize], mut k: usize) -> usize {
    while parent[k] != k {
        parent[k] = parent[parent[k]];
        k = parent[k];
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gwn::fast::FAR_CELLS_MIN_POINTS;
    use crate::gwn::{FastWindingField, WindingField};
    use crate::{DEFAULT_RELATIVE_TOLERANCE, Location, PointQuery};
    use rs_spline::{Domain, ParamCurve, ParamCurveDeriv, circle, circular_arc, segment};

    /// Curves of every kind a far cell meets: two loops round one region (winding 2 there),
    /// a reversed loop, an open arc, a polyline with gaps between its segments (a wide band
    /// reach), a horizontal segment (both its ends at one height), rational pieces.
    fn mixed() -> Domain {
        let o = Point::new(0.0, 0.0);
        let mut curves = vec![
            circle(o, 3.0).unwrap(),
            circle(Point::new(0.5, 0.2), 1.0).unwrap(),
            circle(Point::new(-1.5, -1.0), 0.7).unwrap().reversed(),
            circular_arc(Point::new(1.0, -1.5), 0.8, 0.4, 4.0).unwrap(),
            segment(Point::new(-2.0, 1.5), Point::new(2.5, 1.5)).unwrap(),
        ];
        for k in 0..6 {
            let x = -2.5 + 0.8 * k as f64;
            curves.push(segment(Point::new(x, 2.2), Point::new(x + 0.75, 2.6)).unwrap());
        }
        Domain::new(curves).unwrap()
    }

    /// A loop of a rational arc (a circle's left part) joined, exactly at its ends, to nearly
    /// level segments running right and a vertical one: the split cells along the segments
    /// right of the joins take steps there, where their unlisted partners are the arc's
    /// rational sub-curves.
    fn joined() -> Domain {
        let arc = circular_arc(Point::new(0.0, 0.0), 1.0, 1.9, 4.4).unwrap();
        let pieces = arc.to_bezier();
        let top = pieces[0].start_point();
        let bottom = pieces[pieces.len() - 1].end_point();
        let (c, d) = (
            Point::new(2.0, bottom.y - 0.01),
            Point::new(2.0, top.y + 0.02),
        );
        let curves = vec![
            arc,
            segment(bottom, c).unwrap(),
            segment(c, d).unwrap(),
            segment(d, top).unwrap(),
        ];
        Domain::new(curves).unwrap()
    }

    /// A batch gives every point of `points` the winding number and the location a single
    /// query gives it (the walk), bit for bit.
    fn batches_match_single_queries(name: &str, fast: &FastWindingField, points: &[Point]) {
        let values = fast.winding_numbers(points);
        let mut locations = vec![Location::Outside; points.len()];
        fast.values_into(points, &mut locations);
        for (i, &q) in points.iter().enumerate() {
            let want = fast.winding_number(q);
            assert_eq!(values[i].to_bits(), want.to_bits(), "{name} {i}: {q:?}");
            let location = PointQuery::<Location>::value(fast, q);
            assert_eq!(locations[i], location, "{name} {i}: {q:?}");
        }
    }

    /// Batches reading the far cells give every point the value the walk gives it alone, bit
    /// for bit (the winding number and the location): random points over the shapes' boxes,
    /// points at every open chain's end heights and one ulp above and below them (where the
    /// count changes), points on the cells' edges, a grid; most of the cells are far.
    #[test]
    fn far_cells_give_each_point_the_walks_value() {
        let shapes = [
            ("twirl", rs_testkit::gwn_shape("twirl")),
            ("bubble", rs_testkit::gwn_shape("bubble")),
            ("fish", rs_testkit::gwn_shape("fish")),
            ("mixed", mixed()),
        ];
        for (name, d) in shapes {
            let field = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).unwrap();
            let fast = FastWindingField::new(&field);
            let b = d.bounding_box();
            let (lo, w, h) = (b.min, b.width(), b.height());
            let mut rng = rs_testkit::XorShift64::new(5);
            let mut random = |count: usize| rng.points_around(&d, 0.1, count);
            assert!(fast.built_far_cells().is_none(), "{name}: no batch yet");
            fast.winding_numbers(&random(FAR_CELLS_MIN_POINTS - 1));
            assert!(
                fast.built_far_cells().is_none(),
                "{name}: too few points yet"
            );
            fast.winding_numbers(&random(1));
            let cells = fast
                .built_far_cells()
                .expect("built once enough points came");
            assert!(cells.far_share() > 0.5, "{name}: {}", cells.far_share());

            let mut points = random(30_000);
            let across = |y: f64, points: &mut Vec<Point>| {
                for k in 0..400 {
                    points.push(Point::new(lo.x - 0.05 * w + 1.1 * w * k as f64 / 399.0, y));
                }
            };
            for &(s, e) in field.open_chain_ends() {
                for y in [s.y, e.y] {
                    for y in [y.next_down(), y, y.next_up()] {
                        across(y, &mut points);
                    }
                }
            }
            for k in 0..=SIDE {
                let x = cells.lo.x + k as f64 / cells.per_unit.x;
                let y = cells.lo.y + k as f64 / cells.per_unit.y;
                for t in 0..40 {
                    let f = (t as f64 + 0.37) / 40.0;
                    points.push(Point::new(x, cells.lo.y + f * (cells.hi.y - cells.lo.y)));
                    points.push(Point::new(cells.lo.x + f * (cells.hi.x - cells.lo.x), y));
                }
            }
            for k in 0..150 * 150 {
                let (i, j) = ((k % 150) as f64 / 149.0, (k / 150) as f64 / 149.0);
                points.push(Point::new(lo.x + i * w, lo.y + j * h));
            }
            let far = points
                .iter()
                .filter(|&&q| cells.crossings(q, &mut 0).is_some())
                .count();
            assert!(far > points.len() / 3, "{name}: {far} of {}", points.len());

            batches_match_single_queries(name, &fast, &points);
        }
    }

    /// A point within the band's reach of a curve is in no far cell, even across a cell's
    /// edge from the curve's box: pieces ending a fraction of the reach short of a column's
    /// and a row's edge, queries a fraction of the reach past it (and the chain ends' rows
    /// are near).
    #[test]
    fn points_within_reach_of_a_curve_are_in_no_far_cell() {
        let reach = 1e-9;
        // Cell edges of the unit box at 2^-8 steps are exact.
        let edge = 0.5;
        let pieces: Vec<RationalBezier> = [
            segment(Point::new(0.25, 0.3), Point::new(edge - 0.3 * reach, 0.4)),
            segment(Point::new(0.7, 0.2), Point::new(0.8, edge - 0.3 * reach)),
            circular_arc(Point::new(0.3, 0.7), 0.1, 0.0, 1.0),
        ]
        .into_iter()
        .flat_map(|c| c.unwrap().to_bezier())
        .collect();
        let ends: Vec<(Point, Point)> = pieces
            .iter()
            .map(|b| (b.start_point(), b.end_point()))
            .collect();
        let cells = FarCells::new(
            Point::new(0.0, 0.0),
            Point::new(1.0, 1.0),
            reach,
            &pieces,
            &ends,
            |_| Some(0),
        )
        .unwrap();
        assert!(cells.far_share() > 0.9);
        let near = [
            Point::new(edge + 0.5 * reach, 0.4),
            Point::new(0.8, edge + 0.5 * reach),
        ];
        for q in near {
            assert!(cells.crossings(q, &mut 0).is_none(), "{q:?}");
        }
        for b in &pieces {
            for k in 0..=100 {
                let p = b.point_at(
                    b.param_range().0 + (b.param_range().1 - b.param_range().0) * k as f64 / 100.0,
                );
                for a in 0..8 {
                    let angle = a as f64 * std::f64::consts::FRAC_PI_4;
                    let q = Point::new(
                        p.x + 0.9 * reach * angle.cos(),
                        p.y + 0.9 * reach * angle.sin(),
                    );
                    assert!(cells.crossings(q, &mut 0).is_none(), "{q:?}");
                }
            }
        }
        // Far from every curve and every end's height, the cells are far.
        assert_eq!(cells.crossings(Point::new(0.9, 0.9), &mut 0), Some(0));
    }

    /// Points near the curves of `d`: on its pieces at random parameters, moved along the
    /// normal by `1e-1` to `1e-14` of the diagonal (log-uniform, either side), and along the
    /// cut by as much.
    fn near_points(d: &Domain, count: usize, seed: u64) -> Vec<Point> {
        let pieces: Vec<_> = d.bezier_pieces().into_iter().map(|(_, b)| b).collect();
        let diagonal = d.bounding_box().diagonal();
        let mut rng = rs_testkit::XorShift64::new(seed);
        let mut out = Vec::with_capacity(count);
        while out.len() < count {
            let piece = &pieces[(rng.next_u64() % pieces.len() as u64) as usize];
            let (t0, t1) = piece.param_range();
            let (p, tangent) = piece.point_and_tangent(t0 + rng.next_f64() * (t1 - t0));
            let length = tangent.x.hypot(tangent.y);
            if !(length > 0.0 && length.is_finite()) {
                continue;
            }
            let distance = diagonal * 10f64.powf(-1.0 - 13.0 * rng.next_f64());
            let s = if rng.next_u64() & 1 == 0 { 1.0 } else { -1.0 } * distance;
            out.push(Point::new(
                p.x - s * tangent.y / length,
                p.y + s * tangent.x / length,
            ));
            out.push(Point::new(p.x + s, p.y));
        }
        out
    }

    /// Batches reading the split cells give every point the value the walk gives it alone, bit
    /// for bit (the winding number and the location): points near the curves (most of them
    /// in split cells), on the cells' edges and at every open chain's end height and one ulp
    /// either side; the split cells are made once the near cells' queries are many, and not
    /// before.
    #[test]
    fn split_cells_give_each_point_the_walks_value() {
        // With the least share of the points answered by split cells (the mixed and joined
        // shapes' circles are rational: their cells walk).
        let shapes = [
            ("twirl", rs_testkit::gwn_shape("twirl"), 4),
            ("bubble", rs_testkit::gwn_shape("bubble"), 4),
            ("fish", rs_testkit::gwn_shape("fish"), 4),
            ("mixed", mixed(), 20),
            ("joined", joined(), 20),
        ];
        for (name, d, least) in shapes {
            let field = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).unwrap();
            let fast = FastWindingField::new(&field);
            let mut points = near_points(&d, 20_000, 11);
            fast.winding_numbers(&points[..FAR_CELLS_MIN_POINTS]);
            let cells = fast.built_far_cells().expect("far cells built");
            // (The joined loop has so few near cells that the first batch makes them.)
            assert!(
                cells.split_share().is_none() || name == "joined",
                "{name}: split cells too soon"
            );
            // Enough queries in near cells make them.
            for _ in 0..100 {
                if cells.split_share().is_some() {
                    break;
                }
                fast.winding_numbers(&points);
            }
            let share = cells.split_share().expect("split cells made");
            assert!(share > 0.004, "{name}: {share}");
            if name == "joined" {
                // Steps where the segments meet the arc (rational, never listed).
                let pieces = d.bezier_pieces();
                let (top, bottom) = (
                    pieces[0].1.start_point(),
                    pieces[pieces.len() - 4].1.end_point(),
                );
                let heights = cells.split.made.get().expect("made").cells.step_heights();
                assert!(
                    heights.contains(&top.y) && heights.contains(&bottom.y),
                    "{heights:?}"
                );
            }
            // Every listed sub-curve's ends' heights, and one ulp either side, across the
            // columns about its box (where the chords' rule at an end and the balance of the
            // listings matter).
            let made = cells.split.made.get().expect("made");
            let cell_x = 1.0 / cells.per_unit.x;
            for sub in made.cells.subs.iter().step_by(3) {
                for y in [sub.start().y, sub.end().y] {
                    for y in [y.next_down(), y, y.next_up()] {
                        for k in 0..24 {
                            let left = sub.start().x.min(sub.end().x);
                            let x = left - 4.0 * cell_x + k as f64 * 0.37 * cell_x;
                            points.push(Point::new(x, y));
                        }
                    }
                }
            }

            let (lo, hi) = (cells.lo, cells.hi);
            for &(s, e) in field.open_chain_ends() {
                for y in [s.y, e.y] {
                    for y in [y.next_down(), y, y.next_up()] {
                        for k in 0..200 {
                            let x = lo.x + (hi.x - lo.x) * (k as f64 + 0.5) / 200.0;
                            points.push(Point::new(x, y));
                        }
                    }
                }
            }
            let near = points.clone();
            for q in near.iter().take(4_000) {
                // The edges of the cell holding a near point.
                let c = ((q.x - lo.x) * cells.per_unit.x).floor();
                let r = ((q.y - lo.y) * cells.per_unit.y).floor();
                let x = lo.x + c / cells.per_unit.x;
                let y = lo.y + r / cells.per_unit.y;
                points.push(Point::new(x, q.y));
                points.push(Point::new(q.x, y));
            }
            let split = points
                .iter()
                .filter(|&&q| {
                    let base = cells.cell(q).map(|i| cells.counts[i]);
                    base == Some(NEAR) && cells.crossings(q, &mut 0).is_some()
                })
                .count();
            assert!(
                split > points.len() / least,
                "{name}: {split} of {}",
                points.len()
            );

            batches_match_single_queries(name, &fast, &points);
            // And with the split cells' side tests made (the queries that make them are many).
            assert!(
                cells.split.quick.get().is_none(),
                "{name}: side tests too soon"
            );
            let made = cells.split.made.get().expect("made");
            cells
                .split
                .quick
                .get_or_init(|| made.cells.quick_tests(cells.reach));
            batches_match_single_queries(name, &fast, &points);
        }
    }
}
