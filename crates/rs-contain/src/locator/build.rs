//! Building a [`LocatorIndex`]: the boxes' registrations, the uniform runs of each column
//! (their states found walking up the column),
//! the mixed-cell records and the two levels. The work follows the boundary (its cells, the
//! runs between them, the blocks), not the grid's area: no table of `n x n` cells is built.

use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicU8, Ordering};

use rs_spline::grid::GridFrame;
use rs_spline::{BoundingBox, Point};

use std::sync::OnceLock;

use super::{
    BLOCK, Complete, FIRST_RECORD, INSIDE, LocatorIndex, Lookup, MixedCell, OUTSIDE, Parts,
    REFINED, STRIP, Strip, UNBUILT, VERTICAL_FLAG, strip_of_column,
};
use crate::rays::downward_sign;
use crate::{Classifier, Location};

/// Run state: inRS2 found the run's first cell centre on the boundary, which a cell that
/// meets no box cannot hold (the rounding of the registration against the boundary test): its
/// points are decided by inRS2 itself.
const BY_INRS2: u8 = 2;

impl LocatorIndex {
    /// The index's frame, with every strip still to build: the grid over the classifier's
    /// bounding box, the critical abscissas' column ranges, and the boxes that may register
    /// in each strip (a box's end-point rectangle grown by the tolerance, its band's margin
    /// and a cell each way holds all of its parts' registrations).
    pub(super) fn build(classifier: &Classifier, cells: usize) -> Self {
        let tol = classifier.abs_tol();
        let frame = framed_grid(classifier.outer(), tol, cells);
        let n = frame.n();
        let blocks = n.div_ceil(BLOCK);
        let strips = n.div_ceil(STRIP);
        let (cw, _) = frame.cell_size();
        let all = classifier.boxes().boxes();
        // Each box's range of strips, counted then placed (a counting sort: each strip's
        // boxes ascending).
        let strip_range = |b: &rs_boxes::MonotoneBox| {
            let reach = tol + b.band.margin + cw;
            let first = strip_of_column(frame.col(b.band.xmin - reach));
            let last = strip_of_column(frame.col(b.band.xmax + reach));
            first..=last
        };
        let mut strip_box_start = vec![0u32; strips + 1];
        for b in all {
            for s in strip_range(b) {
                strip_box_start[s + 1] += 1;
            }
        }
        for s in 0..strips {
            strip_box_start[s + 1] += strip_box_start[s];
        }
        let mut next: Vec<u32> = strip_box_start[..strips].to_vec();
        let mut strip_boxes = vec![0u32; strip_box_start[strips] as usize];
        for (bi, b) in all.iter().enumerate() {
            for s in strip_range(b) {
                strip_boxes[next[s] as usize] = bi as u32;
                next[s] += 1;
            }
        }
        Self {
            n,
            blocks,
            coarse: (0..blocks * blocks)
                .map(|_| AtomicU8::new(UNBUILT))
                .collect(),
            strips: (0..strips).map(|_| OnceLock::new()).collect(),
            taken: (0..strips).map(|_| AtomicBool::new(false)).collect(),
            built: std::sync::atomic::AtomicUsize::new(0),
            complete: OnceLock::new(),
            lookup: Lookup::new(&frame, blocks),
            frame,
            critical: critical_ranges(&frame, classifier.boxes().critical_abscissas(), tol),
            strip_box_start,
            strip_boxes,
        }
    }

    /// Strip `s` (the columns `s * STRIP..(s + 1) * STRIP`), built on first use; its coarse states are then
    /// published to the index's table.
    #[inline]
    pub(super) fn strip(&self, classifier: &Classifier, s: usize) -> &Strip {
        match self.strips[s].get() {
            Some(strip) => strip,
            None => self.build_strip(classifier, s),
        }
    }

    /// [`LocatorIndex::strip`]'s first call for strip `s`: builds it, or, when another thread
    /// has taken it, builds the strips no thread has taken (from the next one on, round the
    /// grid) until `s` is ready, then waits for it. Threads whose points come in the same
    /// order (the runs of a stream of Halton or grid points, each starting on the same
    /// columns) otherwise build one strip at a time, each waiting for the other's: two
    /// workers on 10^6 Halton points spent 1.4 ms on their first runs, the 17 strips built
    /// one after the other. A thread that helps so looks for `s` before each strip it builds,
    /// so it builds at most one past the moment `s` is ready; a batch confined to a few strips
    /// may so build strips it does not need (a few each time it finds its strip taken).
    #[cold]
    #[inline(never)]
    fn build_strip(&self, classifier: &Classifier, s: usize) -> &Strip {
        if self.taken[s].swap(true, Ordering::AcqRel) {
            let count = self.strips.len();
            for t in (s + 1..count).chain(0..s) {
                if let Some(strip) = self.strips[s].get() {
                    return strip;
                }
                if !self.taken[t].load(Ordering::Relaxed)
                    && !self.taken[t].swap(true, Ordering::AcqRel)
                {
                    self.build_taken(classifier, t);
                }
            }
        }
        // Taken here, or every other strip is taken: build `s` or wait for the thread that
        // builds it (should that thread have failed, build it here).
        self.build_taken(classifier, s)
    }

    /// Builds strip `s` unless it is built or being built (then waits for it), publishes its
    /// coarse states and, with the last strip, makes the flat tables.
    fn build_taken(&self, classifier: &Classifier, s: usize) -> &Strip {
        let mut built_here = false;
        let strip = self.strips[s].get_or_init(|| {
            built_here = true;
            let columns = s * STRIP..((s + 1) * STRIP).min(self.n);
            let boxes = &self.strip_boxes
                [self.strip_box_start[s] as usize..self.strip_box_start[s + 1] as usize];
            let strip = Strip::build(classifier, &self.frame, &self.critical, columns, boxes);
            // The strip's blocks are a run of the table (block columns first).
            let first = strip.first_block_column * self.blocks;
            for (k, &state) in strip.coarse.iter().enumerate() {
                self.coarse[first + k].store(state, Ordering::Relaxed);
            }
            strip
        });
        // Each strip is counted once, by the call that built it, after it is stored: the
        // count reaching the number of strips means all are, and that call makes the flat
        // tables (only it sets them).
        if built_here && self.built.fetch_add(1, Ordering::AcqRel) + 1 == self.strips.len() {
            let all = self.strips.iter().filter_map(OnceLock::get);
            let _ = self.complete.set(Complete::of(self.blocks, all));
        }
        strip
    }

    /// Every strip, built now (for reports over the whole grid, and for an eager build).
    pub(super) fn built_strips<'s>(
        &'s self,
        classifier: &Classifier,
    ) -> impl Iterator<Item = &'s Strip> {
        (0..self.strips.len()).map(move |s| self.strip(classifier, s))
    }
}

impl Strip {
    /// The strip of the grid `frame` over its columns `columns` (global cell columns, starting
    /// on a block's first), from the boxes `boxes` (global indices, ascending; every box that
    /// registers in these columns must be among them) and the critical abscissas' ranges of
    /// every column of the grid.
    pub(super) fn build(
        classifier: &Classifier,
        frame: &GridFrame,
        critical: &[(u32, u32)],
        columns: Range<usize>,
        boxes: &[u32],
    ) -> Self {
        let (parts, owner_local, pairs) = register(classifier, frame, &columns, boxes);
        let incidences = pairs.len();
        let first_block_column = columns.start / BLOCK;
        let cols = Columns::new(
            frame.n(),
            columns,
            &pairs,
            classifier,
            frame,
            (&owner_local, boxes),
            critical,
        );
        Self::from_columns(frame, parts, &cols, incidences, first_block_column)
    }

    /// The strip from its columns.
    fn from_columns(
        frame: &GridFrame,
        parts: Parts,
        columns: &Columns,
        incidences: usize,
        first_block_column: usize,
    ) -> Self {
        let blocks = frame.n().div_ceil(BLOCK);
        let block_columns = columns.ncols.div_ceil(BLOCK);
        let mut strip = Self {
            first_block_column,
            blocks,
            coarse: vec![OUTSIDE; block_columns * blocks],
            block_start: vec![0; block_columns * blocks],
            fine: Vec::new(),
            records: Vec::new(),
            // The `k`-th occupied cell's items are its record's near items: one copy of all.
            near_items: columns.items.clone(),
            column_items: Vec::new(),
            mixed_cells: columns.rows.len(),
            incidences,
            parts,
        };
        let by_inrs2 = strip.mixed_records(columns);
        strip.two_levels(columns, by_inrs2);
        strip
    }

    /// One record per occupied cell, in the columns' order (the `k`-th occupied cell's record
    /// is record `k`), walking each column upwards; then one record for the cells of
    /// [`BY_INRS2`] runs, whose index is returned.
    fn mixed_records(&mut self, columns: &Columns) -> u32 {
        self.records.reserve(columns.rows.len() + 1);
        // `since_uniform` stays sorted and distinct: each cell's items (sorted and distinct,
        // from the sorted pairs) are merged in through `merged`, in time linear in the two
        // lists (no sort per cell). A record whose list is its predecessor's (in the same column, no run between, no
        // new item) shares its range in `column_items`.
        let mut since_uniform: Vec<u32> = Vec::new();
        let mut merged: Vec<u32> = Vec::new();
        for c in 0..columns.ncols {
            let (mut winding_below, mut unknown_below) = (0, false);
            since_uniform.clear();
            let mut shared = None;
            for k in columns.start[c]..columns.start[c + 1] {
                let (below, state, winding) = columns.run_below(c, k);
                if !below.is_empty() {
                    winding_below = winding;
                    // Above a run of unknown parity, inRS2 decides too.
                    unknown_below = state == BY_INRS2;
                    since_uniform.clear();
                    shared = None;
                }
                merge_sorted(
                    &since_uniform,
                    columns
                        .items_of(k)
                        .iter()
                        .copied()
                        .filter(|&b| b & VERTICAL_FLAG == 0),
                    &mut merged,
                );
                if merged.len() != since_uniform.len() {
                    // A union that grew: a new list (a union of the same length is the list).
                    shared = None;
                }
                std::mem::swap(&mut since_uniform, &mut merged);
                let column = *shared
                    .get_or_insert_with(|| push_items(&mut self.column_items, &since_uniform));
                self.records.push(MixedCell {
                    winding_below,
                    near: (columns.item_start[k], columns.item_start[k + 1]),
                    column,
                    by_inrs2: unknown_below,
                    critical: columns.critical[c],
                });
            }
        }
        self.records.push(MixedCell {
            winding_below: 0,
            near: (0, 0),
            column: (0, 0),
            by_inrs2: true,
            critical: (0, 0),
        });
        (self.records.len() - 1) as u32
    }

    /// The coarse states, and the fine entries of the refined blocks: a block is uniform if
    /// it holds no occupied cell and its columns' runs there share one location.
    ///
    /// The blocks are visited in the order of the table (block columns, then blocks upwards),
    /// and each column of a block column is walked upwards once: `next[i]` is the first of
    /// column `cols.start + i`'s occupied cells at or above the current block's first row (the
    /// index a binary search would give, found by moving forward). A uniform block and the
    /// blocks above it that lie wholly below the next occupied cell of its columns are filled
    /// at once (they share its runs, so its state).
    fn two_levels(&mut self, columns: &Columns, by_inrs2: u32) {
        let (n, blocks) = (columns.n, self.blocks);
        for bc in 0..columns.ncols.div_ceil(BLOCK) {
            let cols = (bc * BLOCK)..((bc + 1) * BLOCK).min(columns.ncols);
            let mut next = [0usize; BLOCK];
            let mut br = 0;
            while br < blocks {
                let block = bc * blocks + br;
                let rows = (br * BLOCK)..((br + 1) * BLOCK).min(n);
                for (i, c) in cols.clone().enumerate() {
                    let occupied = columns.occupied_rows(c);
                    // Bounded by the column's occupied cells.
                    while occupied
                        .get(next[i])
                        .is_some_and(|&x| (x as usize) < rows.start)
                    {
                        next[i] += 1;
                    }
                }
                let mut shared = None;
                let uniform = cols.clone().enumerate().all(|(i, c)| {
                    match columns.state_at(c, next[i], &rows) {
                        Some(s) if s != BY_INRS2 => *shared.get_or_insert(s) == s,
                        _ => false,
                    }
                });
                if uniform {
                    // The blocks above, up to the first occupied cell of these columns, hold
                    // none either and lie in the same runs: the same state, and `next` is
                    // already right for the first block after them.
                    let free_until = cols
                        .clone()
                        .enumerate()
                        .map(|(i, c)| {
                            columns
                                .occupied_rows(c)
                                .get(next[i])
                                .map_or(n, |&x| x as usize)
                        })
                        .min()
                        .unwrap_or(n);
                    // A uniform block holds no occupied cell: the next one is at or above
                    // its end, so at least this block is filled (and, below the grid's
                    // last row, the block holding that cell is not).
                    debug_assert!(free_until >= rows.end);
                    let end = if free_until >= n {
                        blocks
                    } else {
                        free_until / BLOCK
                    };
                    self.coarse[block..bc * blocks + end].fill(shared.unwrap_or(OUTSIDE));
                    br = end;
                    continue;
                }
                self.coarse[block] = REFINED;
                self.block_start[block] = self.fine.len() as u32;
                let start = self.fine.len();
                self.fine.resize(start + BLOCK * BLOCK, u32::from(OUTSIDE));
                for (i, c) in cols.clone().enumerate() {
                    let occupied = columns.occupied_rows(c);
                    let mut j = next[i];
                    let entries = &mut self.fine[start + i * BLOCK..][..rows.len()];
                    for (r, entry) in rows.clone().zip(entries) {
                        // `j` counts the occupied cells below row `r`, as `Columns::cell`'s
                        // search would.
                        *entry = if occupied.get(j).is_some_and(|&x| x as usize == r) {
                            j += 1;
                            FIRST_RECORD + (columns.start[c] + j - 1) as u32
                        } else {
                            match columns.runs[columns.run_slot(c, j)] {
                                BY_INRS2 => FIRST_RECORD + by_inrs2,
                                s => u32::from(s),
                            }
                        };
                    }
                }
                br += 1;
            }
        }
    }
}

/// Registers the boxes `boxes` (global indices) in the cells of the columns `columns` near
/// their curves: a box that spans a couple of cells as itself, a longer one as its parts (see
/// [`Parts`]; a part that meets none of these columns is left out). Returns the parts, each
/// part's box as an index into `boxes`, and the sorted, distinct `(cell, item)` pairs, vertical
/// items flagged, each as one integer `cell << 32 | item` (see [`pair_cell`] and [`pair_item`]),
/// the cell numbered within the columns (`(c - columns.start) * n + r`).
fn register(
    classifier: &Classifier,
    frame: &GridFrame,
    columns: &Range<usize>,
    boxes: &[u32],
) -> (Parts, Vec<u32>, Vec<u64>) {
    let tol = classifier.abs_tol();
    let all = classifier.boxes().boxes();
    let rows = frame.rows();
    // Sized once: a box has about as many parts in these columns as the share of its end
    // points' rectangle in them spans cells along its longer side (each part spans at most
    // two; the rows taken in proportion to the columns, so that a long box does not reserve
    // its whole length in every strip it reaches, which the strip would keep), and a part
    // meets a few cells (growing the vectors instead took a tenth of a strip's build).
    let expected_parts: usize = boxes
        .iter()
        .map(|&bi| {
            let band = &all[bi as usize].band;
            let (c0, c1, r0, r1) = frame.cell_range(BoundingBox {
                min: Point::new(band.xmin, band.ymin),
                max: Point::new(band.xmax, band.ymax),
            });
            let across = c1
                .min(columns.end - 1)
                .saturating_sub(c0.max(columns.start))
                + 1;
            let up = (r1 - r0 + 1) * across / (c1 - c0 + 1);
            across.max(up)
        })
        .sum();
    // Each pair as one integer, `cell << 32 | item`, so that sorting compares one word (a
    // grid has at most 8192^2 < 2^32 cells).
    let mut pairs: Vec<u64> = Vec::with_capacity(4 * expected_parts);
    let mut parts = Parts {
        bands: Vec::with_capacity(expected_parts),
        owner: Vec::with_capacity(expected_parts),
    };
    let mut owner_local: Vec<u32> = Vec::with_capacity(expected_parts);
    // Halves farther than this from the columns are not halved further (a cell covers the
    // halving's rounding; `add` drops the parts that meet none of the columns).
    let reach = tol + frame.cell_size().0;
    let mut add = |band: rs_boxes::ChordBand, local: usize, flag: u32| {
        let (c0, c1, r0, r1) = frame.cell_range(band.rectangle_near(tol));
        let (c0, c1) = (c0.max(columns.start), c1.min(columns.end - 1));
        if c0 > c1 {
            return;
        }
        let id = parts.bands.len() as u32;
        parts.bands.push(band);
        parts.owner.push(boxes[local]);
        owner_local.push(local as u32);
        for c in c0..=c1 {
            for r in r0..=r1 {
                let cell = (c - columns.start) * rows + r;
                pairs.push((cell as u64) << 32 | u64::from(id | flag));
            }
        }
    };
    for (local, &bi) in boxes.iter().enumerate() {
        let b = &all[bi as usize];
        // Vertical boxes are never crossed by the ray (it runs an infinitesimal distance
        // to their right): flag them so the walk down a column skips them.
        let flag = if b.x_dir == rs_boxes::Monotonicity::Constant {
            VERTICAL_FLAG
        } else {
            0
        };
        // `for_grid_parts`'s first test, made without copying the piece: a box whose end
        // points' rectangle (its band's, bit for bit) spans at most two cells each way is
        // its only part, with its own band. Most boxes of a long boundary are that small.
        let ends = BoundingBox {
            min: Point::new(b.band.xmin, b.band.ymin),
            max: Point::new(b.band.xmax, b.band.ymax),
        };
        let (c0, c1, r0, r1) = frame.cell_range(ends);
        if c1 - c0 <= 1 && r1 - r0 <= 1 {
            add(b.band, local, flag);
        } else {
            b.for_grid_parts_near(frame, columns.clone(), reach, |band, _| {
                add(band, local, flag)
            });
        }
    }
    pairs.sort_unstable();
    pairs.dedup();
    (parts, owner_local, pairs)
}

/// The cell of a registration `cell << 32 | item`.
fn pair_cell(pair: u64) -> usize {
    (pair >> 32) as usize
}

/// The item (vertical ones flagged) of a registration `cell << 32 | item`.
fn pair_item(pair: u64) -> u32 {
    pair as u32
}

/// `out` becomes the sorted, distinct union of `sorted` (sorted and distinct) and `more`
/// (ascending and distinct).
fn merge_sorted(sorted: &[u32], more: impl Iterator<Item = u32>, out: &mut Vec<u32>) {
    out.clear();
    let mut i = 0;
    for m in more {
        while i < sorted.len() && sorted[i] < m {
            out.push(sorted[i]);
            i += 1;
        }
        if sorted.get(i) == Some(&m) {
            i += 1;
        }
        out.push(m);
    }
    out.extend_from_slice(&sorted[i..]);
}

/// What a cell of the grid is: occupied (the `k`-th occupied cell in column order), or in a
/// run of cells that meet no box, with the run's state (the tests' view of one cell).
#[cfg(test)]
enum Cell {
    Occupied(usize),
    Run(u8),
}

/// The columns of a strip, column by column: their occupied cells (those where an item is
/// registered), their items, and the state of each run of unoccupied cells between them.
/// Columns are numbered within the strip (`c` is the grid's column `offset + c`).
struct Columns {
    /// Cells per column (the grid's rows).
    n: usize,
    /// Number of columns.
    ncols: usize,
    /// The grid's column of the first.
    offset: usize,
    /// Column `c`'s occupied cells are `start[c]..start[c + 1]`.
    start: Vec<usize>,
    /// The row of each occupied cell (ascending within a column).
    rows: Vec<u32>,
    /// The items of occupied cell `k` are `items[item_start[k]..item_start[k + 1]]`.
    item_start: Vec<u32>,
    items: Vec<u32>,
    /// Column `c` has `start[c + 1] - start[c] + 1` runs (some empty): the one below each
    /// occupied cell and the one at the top; run `j` of column `c` is `runs[start[c] + c + j]`,
    /// the location of its first cell's centre by inRS2 ([`OUTSIDE`], [`INSIDE`] or
    /// [`BY_INRS2`]).
    runs: Vec<u8>,
    /// The winding number of each run's first cell's centre, beside `runs` (0 for a
    /// [`BY_INRS2`] run, whose records above are decided by inRS2).
    run_windings: Vec<i32>,
    /// For column `c`, the range of critical abscissas (indices into
    /// `MonotoneBoxes::critical_abscissas`) that may lie within the tolerance of one of its
    /// points (see [`critical_ranges`]).
    critical: Vec<(u32, u32)>,
}

impl Columns {
    /// The columns `columns` of the grid `frame` (`n` cells per side) from the sorted,
    /// distinct `(cell, item)` pairs of the `parts` ([`register`]'s, with each part's box as an
    /// index into the strip's `boxes`), with the runs' states (see
    /// [`Columns::classify_runs`]); `critical` holds the ranges of every column of the grid.
    #[allow(clippy::too_many_arguments)]
    fn new(
        n: usize,
        columns: Range<usize>,
        pairs: &[u64],
        classifier: &Classifier,
        frame: &GridFrame,
        (owner_local, boxes): (&[u32], &[u32]),
        critical: &[(u32, u32)],
    ) -> Self {
        let ncols = columns.len();
        let mut start = vec![0usize; ncols + 1];
        // Sized once: the number of occupied cells, the distinct cells of the sorted pairs.
        let occupied = pairs.len().min(1)
            + pairs
                .windows(2)
                .filter(|w| pair_cell(w[0]) != pair_cell(w[1]))
                .count();
        let mut rows: Vec<u32> = Vec::with_capacity(occupied);
        let mut item_start: Vec<u32> = Vec::with_capacity(occupied + 1);
        let mut items: Vec<u32> = Vec::with_capacity(pairs.len());
        let mut last = usize::MAX;
        for &pair in pairs {
            let (cell, item) = (pair_cell(pair), pair_item(pair));
            if cell != last {
                let (c, r) = (cell / n, cell % n);
                start[c + 1] += 1;
                rows.push(r as u32);
                item_start.push(items.len() as u32);
                last = cell;
            }
            items.push(item);
        }
        item_start.push(items.len() as u32);
        for c in 0..ncols {
            start[c + 1] += start[c];
        }
        let mut strip = Self {
            n,
            ncols,
            offset: columns.start,
            start,
            rows,
            item_start,
            items,
            runs: Vec::new(),
            run_windings: Vec::new(),
            critical: critical[columns].to_vec(),
        };
        strip.classify_runs(classifier, frame, owner_local, boxes);
        strip
    }

    /// Each run's state and winding number: the location inRS2 gives its first cell's centre
    /// (empty runs are left outside), found walking each column upwards instead of by an inRS2
    /// batch.
    ///
    /// inRS2 at a point `p` off the boundary is the sum of the signs of the boxes whose
    /// [`MonotoneBox::crosses_below`](rs_boxes::MonotoneBox::crosses_below) holds at `p` (the
    /// winding number, read by the fill rule). From one run's first centre `q` to the next
    /// run's `p` (same abscissa, higher), that test changes only for boxes whose curve meets
    /// the column between them, in the occupied cells between the two runs (a run's cells meet
    /// no box): so the winding number at `p` is the one at `q` plus the signs of those cells'
    /// boxes (non-vertical, each once) crossed below `p` and not `q`, minus those crossed below
    /// `q` and not `p`, the very test inRS2 makes. Below the first run no box is crossed.
    /// inRS2's other answers are kept: outside the grown bounding box a point is outside; a
    /// column on a critical abscissa takes inRS2's fallback at each centre; a centre near one
    /// of the boxes registered just below it (which the registration's reach rules out but
    /// for rounding) is on the boundary, a [`BY_INRS2`] run.
    fn classify_runs(
        &mut self,
        classifier: &Classifier,
        frame: &GridFrame,
        owner_local: &[u32],
        boxes: &[u32],
    ) {
        let (cw, ch) = frame.cell_size();
        let origin = frame.bounding_box().min;
        let (tol, outer) = (classifier.abs_tol(), classifier.outer());
        let all = classifier.boxes().boxes();
        let mono = classifier.boxes();
        self.runs = vec![OUTSIDE; self.rows.len() + self.ncols];
        self.run_windings = vec![0; self.rows.len() + self.ncols];
        // The strip's boxes are numbered by their place in `boxes` here (`b`), so that these
        // tables grow with the strip, not with the domain.
        // The boxes of the occupied cells since the last run, each once: `seen[b] == epoch`
        // once box `b` is among `candidates` (a new epoch for every new list; fewer than
        // `2^32` lists, one per run).
        let mut seen = vec![0u32; boxes.len()];
        let mut epoch = 0u32;
        let mut candidates: Vec<u32> = Vec::new();
        // `MonotoneBox::crosses_below` (the band's answer, else the solve's) at a point of
        // column `c`, its solve made once per box and column: where the curve meets the
        // column is `solved[b]` while `solved_in[b]` is `c + 1`.
        let mut solved: Vec<Option<(f64, f64)>> = vec![None; boxes.len()];
        let mut solved_in = vec![0usize; boxes.len()];
        let mut crosses_below = |b: usize, p: Point, c: usize| {
            let bx = &all[boxes[b] as usize];
            bx.band.crossing_below(p).unwrap_or_else(|| {
                if solved_in[b] != c + 1 {
                    solved_in[b] = c + 1;
                    solved[b] = bx.at_x(p.x);
                }
                solved[b].is_some_and(|(_, y)| y < p.y)
            })
        };
        for c in 0..self.ncols {
            let x = origin.x + ((self.offset + c) as f64 + 0.5) * cw;
            let (first, end) = self.critical[c];
            let critical =
                first < end && mono.is_critical_x_among(x, tol, first as usize..end as usize);
            let occupied = self.start[c + 1] - self.start[c];
            let (mut winding, mut below) = (0_i64, None::<Point>);
            candidates.clear();
            epoch += 1;
            for j in 0..=occupied {
                let run = self.run(c, j);
                if !run.is_empty() {
                    let p = Point::new(x, origin.y + (run.start as f64 + 0.5) * ch);
                    let w = if critical {
                        classifier.winding_with_decision(p).0
                    } else {
                        let mut near = false;
                        for &b in &candidates {
                            let b = b as usize;
                            let bx = &all[boxes[b] as usize];
                            near |= bx.is_near(p, tol);
                            let crossed_below_q = below.is_some_and(|q| crosses_below(b, q, c));
                            let crossed_below_p = crosses_below(b, p, c);
                            if crossed_below_p != crossed_below_q {
                                let sign = downward_sign(bx);
                                winding += if crossed_below_p { sign } else { -sign };
                            }
                        }
                        if !outer.contains(p) {
                            Some(0)
                        } else if near {
                            None
                        } else {
                            Some(winding)
                        }
                    };
                    let slot = self.run_slot(c, j);
                    self.runs[slot] = match classifier.location(w) {
                        Location::Inside => INSIDE,
                        Location::Outside => OUTSIDE,
                        Location::Boundary => BY_INRS2,
                    };
                    // A column's winding number is bounded by its boxes (fewer than 2^31).
                    self.run_windings[slot] = w.unwrap_or(0) as i32;
                    below = Some(p);
                    candidates.clear();
                    epoch += 1;
                }
                if j < occupied {
                    for &item in self.items_of(self.start[c] + j) {
                        if item & VERTICAL_FLAG == 0 {
                            let b = owner_local[item as usize];
                            if seen[b as usize] != epoch {
                                seen[b as usize] = epoch;
                                candidates.push(b);
                            }
                        }
                    }
                }
            }
        }
    }

    /// The rows of column `c`'s occupied cells.
    fn occupied_rows(&self, c: usize) -> &[u32] {
        &self.rows[self.start[c]..self.start[c + 1]]
    }

    /// Where run `j` of column `c` keeps its state in `runs`.
    fn run_slot(&self, c: usize, j: usize) -> usize {
        self.start[c] + c + j
    }

    /// The rows of run `j` of column `c` (below its `j`-th occupied cell, or at the top).
    fn run(&self, c: usize, j: usize) -> std::ops::Range<usize> {
        let occupied = self.occupied_rows(c);
        let first = if j == 0 {
            0
        } else {
            occupied[j - 1] as usize + 1
        };
        let end = occupied.get(j).map_or(self.n, |&r| r as usize);
        first..end.max(first)
    }

    /// The run just below occupied cell `k` of column `c`, its state and winding number.
    fn run_below(&self, c: usize, k: usize) -> (std::ops::Range<usize>, u8, i32) {
        let j = k - self.start[c];
        let slot = self.run_slot(c, j);
        (self.run(c, j), self.runs[slot], self.run_windings[slot])
    }

    /// The items registered in occupied cell `k`.
    fn items_of(&self, k: usize) -> &[u32] {
        &self.items[self.item_start[k] as usize..self.item_start[k + 1] as usize]
    }

    /// The cell at column `c`, row `r`.
    #[cfg(test)]
    fn cell(&self, c: usize, r: usize) -> Cell {
        let occupied = self.occupied_rows(c);
        let j = occupied.partition_point(|&x| (x as usize) < r);
        if occupied.get(j).is_some_and(|&x| x as usize == r) {
            Cell::Occupied(self.start[c] + j)
        } else {
            Cell::Run(self.runs[self.run_slot(c, j)])
        }
    }

    /// The state shared by the cells `rows` of column `c`, if none is occupied (they then lie
    /// in one run).
    #[cfg(test)]
    fn state_of_rows(&self, c: usize, rows: &std::ops::Range<usize>) -> Option<u8> {
        let j = self
            .occupied_rows(c)
            .partition_point(|&x| (x as usize) < rows.start);
        self.state_at(c, j, rows)
    }

    /// [`Columns::state_of_rows`] given `j`, the number of column `c`'s occupied cells below
    /// `rows`.
    fn state_at(&self, c: usize, j: usize, rows: &std::ops::Range<usize>) -> Option<u8> {
        match self.occupied_rows(c).get(j) {
            Some(&x) if (x as usize) < rows.end => None,
            _ => Some(self.runs[self.run_slot(c, j)]),
        }
    }
}

/// The grid over `outer` with about `cells` cells per side (fewer when the tolerance is wider
/// than a cell), plus one cell on every side: that ring lies outside `outer`, so no box is
/// registered there and every point off the grid can be clamped into it.
fn framed_grid(outer: BoundingBox, abs_tol: f64, cells: usize) -> GridFrame {
    let n =
        GridFrame::cells_for_tolerance(outer, abs_tol, cells).clamp(1, GridFrame::MAX_CELLS - 2);
    let (cw, ch) = (outer.width() / n as f64, outer.height() / n as f64);
    let ring = BoundingBox {
        min: Point::new(outer.min.x - cw, outer.min.y - ch),
        max: Point::new(outer.max.x + cw, outer.max.y + ch),
    };
    GridFrame::new(ring, n + 2)
}

/// For each column of `frame`, the range of the sorted critical `abscissas` that may lie
/// within `abs_tol` of a point in it ([`rs_boxes::MonotoneBoxes::is_critical_x`]): abscissa
/// `xc` is in the range of the columns of `xc - abs_tol` to `xc + abs_tol`, grown by a few
/// units in the last place (the test rounds `x - abs_tol` and `x + abs_tol`) and by a column
/// on each side. A column is a function of `x` that never decreases, so an abscissa that near
/// a point lies in the range of the point's column; and since the columns of successive
/// abscissas never move left, each column's abscissas are consecutive.
fn critical_ranges(frame: &GridFrame, abscissas: &[f64], abs_tol: f64) -> Vec<(u32, u32)> {
    let n = frame.n();
    let mut ranges = vec![(0u32, 0u32); n];
    for (i, &xc) in abscissas.iter().enumerate() {
        let reach = abs_tol + 4.0 * f64::EPSILON * (xc.abs() + abs_tol);
        let first = frame.col(xc - reach).saturating_sub(1);
        let last = (frame.col(xc + reach) + 1).min(n - 1);
        for r in &mut ranges[first..=last] {
            if r.0 == r.1 {
                r.0 = i as u32;
            }
            r.1 = i as u32 + 1;
        }
    }
    ranges
}

/// Appends `items` to `all` and returns their range.
fn push_items(all: &mut Vec<u32>, items: &[u32]) -> (u32, u32) {
    let start = all.len() as u32;
    all.extend_from_slice(items);
    (start, all.len() as u32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{ContainOptions, Method};
    use rs_spline::{Domain, circle};

    /// Every box, as the strip over the whole grid takes them.
    fn all_boxes(c: &Classifier) -> Vec<u32> {
        (0..c.boxes().boxes().len() as u32).collect()
    }

    /// The registration and the columns of the strip over the whole grid `frame`.
    fn whole_grid(c: &Classifier, frame: &GridFrame) -> (Parts, Vec<u64>, Columns) {
        let n = frame.n();
        let boxes = all_boxes(c);
        let (parts, owner_local, pairs) = register(c, frame, &(0..n), &boxes);
        let critical = critical_ranges(frame, c.boxes().critical_abscissas(), c.abs_tol());
        let columns = Columns::new(n, 0..n, &pairs, c, frame, (&owner_local, &boxes), &critical);
        (parts, pairs, columns)
    }

    /// The sparse columns against the dense grid they stand for: every cell is occupied
    /// exactly where an item is registered, every other cell carries the inRS2 location of
    /// its run's first cell, which is its own centre's location too, and a block's rows share
    /// a state exactly when none of them is occupied.
    #[test]
    fn columns_match_the_dense_grid() {
        let d = Domain::new(vec![
            circle(Point::new(0.0, 0.0), 1.0).unwrap(),
            circle(Point::new(0.2, 0.1), 0.4).unwrap(),
        ])
        .unwrap();
        let c = Classifier::new(&d, ContainOptions::default()).unwrap();
        for cells in [5, 40] {
            let frame = framed_grid(c.outer(), c.abs_tol(), cells);
            let n = frame.n();
            let (_, pairs, columns) = whole_grid(&c, &frame);
            let occupied: std::collections::BTreeSet<usize> =
                pairs.iter().map(|&p| pair_cell(p)).collect();
            let (cw, ch) = frame.cell_size();
            let origin = frame.bounding_box().min;
            let mut k_expected = 0;
            for col in 0..n {
                for r in 0..n {
                    match columns.cell(col, r) {
                        Cell::Occupied(k) => {
                            assert!(occupied.contains(&(col * n + r)));
                            assert_eq!(k, k_expected, "occupied cells in column order");
                            k_expected += 1;
                            let items: Vec<u32> = pairs
                                .iter()
                                .filter(|&&p| pair_cell(p) == col * n + r)
                                .map(|&p| pair_item(p))
                                .collect();
                            assert_eq!(columns.items_of(k), &items[..]);
                        }
                        Cell::Run(s) => {
                            assert!(!occupied.contains(&(col * n + r)));
                            let centre = Point::new(
                                origin.x + (col as f64 + 0.5) * cw,
                                origin.y + (r as f64 + 0.5) * ch,
                            );
                            let expected = match c.locate_all_with(Method::InRS2, &[centre])[0] {
                                Location::Inside => INSIDE,
                                _ => OUTSIDE,
                            };
                            assert_eq!(s, expected, "cells {cells}: cell ({col}, {r})");
                        }
                    }
                }
                for r0 in (0..n).step_by(3) {
                    let rows = r0..(r0 + 3).min(n);
                    let any = rows.clone().any(|r| occupied.contains(&(col * n + r)));
                    match columns.state_of_rows(col, &rows) {
                        None => assert!(any),
                        Some(s) => {
                            assert!(!any);
                            assert!(
                                rows.clone().all(
                                    |r| matches!(columns.cell(col, r), Cell::Run(t) if t == s)
                                )
                            );
                        }
                    }
                }
            }
            assert_eq!(k_expected, columns.rows.len());
            assert!(k_expected > 0 && k_expected < n * n);
            two_levels_match_the_cells(&c, &frame, &columns, &pairs);
        }
    }

    /// The two levels built from `columns` against each cell: a block is uniform exactly
    /// when its cells are all in runs of one state (not [`BY_INRS2`]), which is the block's
    /// state; a refined block's entry of a cell is its record (an occupied cell), its run's
    /// state, or the inRS2 record.
    fn two_levels_match_the_cells(
        c: &Classifier,
        frame: &GridFrame,
        columns: &Columns,
        pairs: &[u64],
    ) {
        let n = frame.n();
        let (parts, _, _) = whole_grid(c, frame);
        let ix = Strip::from_columns(frame, parts, columns, pairs.len(), 0);
        let by_inrs2 = FIRST_RECORD + (ix.records.len() - 1) as u32;
        let (mut uniform, mut refined) = (0, 0);
        for bc in 0..ix.blocks {
            for br in 0..ix.blocks {
                let block = bc * ix.blocks + br;
                let cells: Vec<(usize, usize)> = (bc * BLOCK..((bc + 1) * BLOCK).min(n))
                    .flat_map(|col| (br * BLOCK..((br + 1) * BLOCK).min(n)).map(move |r| (col, r)))
                    .collect();
                let states: std::collections::BTreeSet<Option<u8>> = cells
                    .iter()
                    .map(|&(col, r)| match columns.cell(col, r) {
                        Cell::Run(s) if s != BY_INRS2 => Some(s),
                        _ => None,
                    })
                    .collect();
                let expect_uniform = states.len() == 1 && !states.contains(&None);
                if ix.coarse[block] == REFINED {
                    refined += 1;
                    assert!(!expect_uniform, "block ({bc}, {br})");
                    for &(col, r) in &cells {
                        let within = (col - bc * BLOCK) * BLOCK + (r - br * BLOCK);
                        let entry = ix.fine[ix.block_start[block] as usize + within];
                        let expected = match columns.cell(col, r) {
                            Cell::Occupied(k) => FIRST_RECORD + k as u32,
                            Cell::Run(BY_INRS2) => by_inrs2,
                            Cell::Run(s) => u32::from(s),
                        };
                        assert_eq!(entry, expected, "cell ({col}, {r})");
                    }
                } else {
                    uniform += 1;
                    assert!(expect_uniform, "block ({bc}, {br})");
                    assert_eq!(states.first(), Some(&Some(ix.coarse[block])));
                }
            }
        }
        assert!(refined > 0);
        assert!(uniform > 0 || ix.blocks < 3);
    }

    /// The registration's parts are `for_grid_parts`'s, box by box and in order (also for the
    /// boxes that are their own part, which the registration cuts short), at grids where
    /// most boxes are one part and where most are halved.
    #[test]
    fn registered_parts_are_the_grid_parts() {
        let d = Domain::new(vec![
            circle(Point::new(0.0, 0.0), 1.0).unwrap(),
            circle(Point::new(0.2, 0.1), 0.4).unwrap(),
        ])
        .unwrap();
        // Parts that are whole boxes, and parts cut from boxes, over all the grids.
        let (mut whole, mut cut) = (0, 0);
        for subdivisions in [1, 8] {
            let c = Classifier::new(
                &d,
                ContainOptions::default().with_subdivisions(subdivisions),
            )
            .unwrap();
            for cells in [4, 40, 512] {
                let frame = framed_grid(c.outer(), c.abs_tol(), cells);
                let (parts, _, _) = whole_grid(&c, &frame);
                let (mut bands, mut owner) = (Vec::new(), Vec::new());
                for (bi, b) in c.boxes().boxes().iter().enumerate() {
                    b.for_grid_parts(&frame, |band, is_whole| {
                        bands.push(band);
                        owner.push(bi as u32);
                        whole += usize::from(is_whole);
                        cut += usize::from(!is_whole);
                    });
                }
                assert_eq!(parts.bands, bands, "cells {cells}");
                assert_eq!(parts.owner, owner, "cells {cells}");
            }
        }
        assert!(whole > 0 && cut > 0, "{whole} whole, {cut} cut");
    }

    /// Every run's state is inRS2's location of its first cell's centre, on the paper's
    /// fixtures, an annulus and a staircase (vertical and horizontal edges, critical
    /// abscissas on grid columns), at a coarse and at the default grid, and with the boxes
    /// halved into sub-boxes or not.
    #[test]
    fn run_states_are_inrs2_at_the_first_centres() {
        let mut cases = rs_testkit::fixtures();
        cases.push(rs_testkit::annulus());
        cases.push(rs_testkit::staircase());
        for case in &cases {
            for subdivisions in [1, 4] {
                let options = ContainOptions::default().with_subdivisions(subdivisions);
                let c = Classifier::new(&case.domain, options).unwrap();
                for cells in [64, 512] {
                    let frame = framed_grid(c.outer(), c.abs_tol(), cells);
                    let n = frame.n();
                    let (_, _, columns) = whole_grid(&c, &frame);
                    let (cw, ch) = frame.cell_size();
                    let origin = frame.bounding_box().min;
                    let (mut centres, mut states) = (Vec::new(), Vec::new());
                    for col in 0..n {
                        for j in 0..=columns.occupied_rows(col).len() {
                            let run = columns.run(col, j);
                            if !run.is_empty() {
                                centres.push(Point::new(
                                    origin.x + (col as f64 + 0.5) * cw,
                                    origin.y + (run.start as f64 + 0.5) * ch,
                                ));
                                states.push(columns.runs[columns.run_slot(col, j)]);
                            }
                        }
                    }
                    let expected: Vec<u8> = c
                        .locate_all_with(Method::InRS2, &centres)
                        .into_iter()
                        .map(|l| match l {
                            Location::Inside => INSIDE,
                            Location::Outside => OUTSIDE,
                            Location::Boundary => BY_INRS2,
                        })
                        .collect();
                    assert!(expected.contains(&INSIDE) && expected.contains(&OUTSIDE));
                    for (k, (&got, &want)) in states.iter().zip(&expected).enumerate() {
                        assert_eq!(got, want, "{} cells {cells}: {:?}", case.name, centres[k]);
                    }
                }
            }
        }
    }

    /// `merge_sorted` gives the sorted, distinct union, as sorting and deduplicating would.
    #[test]
    fn merge_sorted_is_the_sorted_union() {
        let mut rng = rs_testkit::XorShift64::new(0x9e37_79b9_7f4a_7c15);
        let mut out = Vec::new();
        for _ in 0..2000 {
            let pick = |rng: &mut rs_testkit::XorShift64| {
                let len = rng.below(20);
                let mut v: Vec<u32> = (0..len).map(|_| rng.below(40) as u32).collect();
                v.sort_unstable();
                v.dedup();
                v
            };
            let (a, b) = (pick(&mut rng), pick(&mut rng));
            merge_sorted(&a, b.iter().copied(), &mut out);
            let mut expected: Vec<u32> = a.iter().chain(&b).copied().collect();
            expected.sort_unstable();
            expected.dedup();
            assert_eq!(out, expected, "{a:?} and {b:?}");
        }
    }

    /// A run whose first cell's centre inRS2 puts on the boundary (which a cell meeting no box
    /// cannot hold; forced here) is decided by inRS2 itself, and so are the occupied cells
    /// above it up to the next run: the parity below them is unknown.
    #[test]
    fn runs_of_unknown_parity_are_decided_by_inrs2() {
        use crate::locator::PointLocator;
        let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
        let c = Classifier::new(&d, ContainOptions::default()).unwrap();
        let ix = LocatorIndex::build(&c, 16);
        let frame = ix.frame;
        let n = frame.n();
        // The strip of the middle column, built by hand.
        let col = n / 2;
        let s = strip_of_column(col);
        let cols = s * STRIP..((s + 1) * STRIP).min(n);
        let boxes =
            &ix.strip_boxes[ix.strip_box_start[s] as usize..ix.strip_box_start[s + 1] as usize];
        let (parts, owner_local, pairs) = register(&c, &frame, &cols, boxes);
        let incidences = pairs.len();
        let mut columns = Columns::new(
            n,
            cols.clone(),
            &pairs,
            &c,
            &frame,
            (&owner_local, boxes),
            &ix.critical,
        );
        // The middle column's run inside the circle (between its two boundary crossings),
        // marked of unknown parity; its state was inside.
        let lc = col - cols.start;
        let j = (1..=columns.start[lc + 1] - columns.start[lc])
            .find(|&j| {
                !columns.run(lc, j).is_empty() && columns.runs[columns.run_slot(lc, j)] == INSIDE
            })
            .unwrap();
        let slot = columns.run_slot(lc, j);
        columns.runs[slot] = BY_INRS2;
        let run = columns.run(lc, j);
        let strip = Strip::from_columns(&frame, parts, &columns, incidences, s);
        // The occupied cells right above the run take inRS2 too.
        let above = columns.start[lc] + j;
        assert!(strip.records[above].by_inrs2);
        assert!(
            !strip.records[columns.start[lc]].by_inrs2,
            "below the run: parity known"
        );
        let by_inrs2 = FIRST_RECORD + (strip.records.len() - 1) as u32;
        assert!(strip.records[(by_inrs2 - FIRST_RECORD) as usize].by_inrs2);
        // Installed in the index as its strip `s` (the others are built on demand).
        for (k, &state) in strip.coarse.iter().enumerate() {
            ix.coarse[strip.first_block_column * ix.blocks + k].store(state, Ordering::Relaxed);
        }
        assert!(ix.strips[s].set(strip).is_ok());
        // Points across the run's cells and the cell above it: inRS2's answers.
        let loc = PointLocator::with_index(&c, &ix);
        let (cw, ch) = frame.cell_size();
        let origin = frame.bounding_box().min;
        let pts: Vec<Point> = (run.start..=run.end)
            .flat_map(|r| {
                (0..5).map(move |k| {
                    Point::new(
                        origin.x + (col as f64 + 0.1 + 0.2 * k as f64) * cw,
                        origin.y + (r as f64 + 0.3) * ch,
                    )
                })
            })
            .collect();
        let strip = ix.strip(&c, s);
        for p in &pts[..5 * run.len()] {
            let (pc, pr) = ix.lookup.cell(*p);
            assert_eq!(strip.entry(pc, pr), by_inrs2, "a cell of the run at {p:?}");
        }
        let expected = c.locate_all_with(Method::InRS2, &pts);
        assert!(expected.contains(&Location::Inside));
        assert_eq!(crate::Locate::locate_all(&loc, &pts), expected);
    }

    /// The strips built one by one (each from its own boxes) hold what the strip over the
    /// whole grid holds: every cell's uniform state, and for a mixed cell a record with the
    /// same parity below, the same inRS2 flag and critical range, and the same parts (box and
    /// band) near it and below it. On the paper's fixtures and an annulus, at a coarse grid,
    /// the default one and one whose last strip is narrower than a block.
    #[test]
    fn strips_one_by_one_equal_the_whole_grid() {
        let mut cases = rs_testkit::fixtures();
        cases.push(rs_testkit::annulus());
        for case in &cases {
            let c = Classifier::new(&case.domain, ContainOptions::default()).unwrap();
            for cells in [30, 61, 512] {
                let ix = LocatorIndex::build(&c, cells);
                let frame = ix.frame;
                let n = frame.n();
                let (parts, pairs, columns) = whole_grid(&c, &frame);
                let whole = Strip::from_columns(&frame, parts, &columns, pairs.len(), 0);
                let key = |st: &Strip, item: u32| {
                    let item = item & !VERTICAL_FLAG;
                    let b = st.parts.band(item);
                    (
                        st.parts.owner[item as usize],
                        [b.xmin, b.xmax, b.ymin, b.ymax, b.margin].map(f64::to_bits),
                    )
                };
                let set = |st: &Strip, items: &[u32]| {
                    items
                        .iter()
                        .map(|&i| key(st, i))
                        .collect::<std::collections::BTreeSet<_>>()
                };
                let (mut mixed, mut uniform) = (0, 0);
                for col in 0..n {
                    let strip = ix.strip(&c, strip_of_column(col));
                    for r in 0..n {
                        let (a, b) = (whole.entry(col, r), strip.entry(col, r));
                        if a < FIRST_RECORD || b < FIRST_RECORD {
                            assert_eq!(a, b, "{} cells {cells}: ({col}, {r})", case.name);
                            uniform += 1;
                            continue;
                        }
                        mixed += 1;
                        let (ra, rb) = (
                            &whole.records[(a - FIRST_RECORD) as usize],
                            &strip.records[(b - FIRST_RECORD) as usize],
                        );
                        assert_eq!(ra.winding_below, rb.winding_below);
                        assert_eq!(ra.by_inrs2, rb.by_inrs2);
                        assert_eq!(ra.critical, rb.critical);
                        let items = |st: &Strip, range: (u32, u32), column: bool| {
                            let list = if column {
                                &st.column_items
                            } else {
                                &st.near_items
                            };
                            set(st, &list[range.0 as usize..range.1 as usize])
                        };
                        assert_eq!(items(&whole, ra.near, false), items(strip, rb.near, false));
                        assert_eq!(
                            items(&whole, ra.column, true),
                            items(strip, rb.column, true)
                        );
                    }
                }
                assert!(mixed > 0 && uniform > 0, "{} cells {cells}", case.name);
                // The coarse table, published as the strips were built, is theirs.
                for (k, state) in ix.coarse.iter().enumerate() {
                    assert_eq!(state.load(Ordering::Relaxed), whole.coarse[k]);
                }
            }
        }
    }

    /// The critical-abscissa test among a column's range agrees with the test among all of
    /// them round every critical abscissa, also far from the origin (where a cell is a few
    /// thousand units in the last place wide) and with a tolerance wider than a cell; and
    /// most columns have an empty range.
    #[test]
    fn critical_ranges_hold_every_flagged_abscissa() {
        for (centre, radius, cells) in [(0.0, 1.0, 512), (1.0e6, 1.0e-3, 512), (3.0, 2.0, 8)] {
            let d =
                Domain::new(vec![circle(Point::new(centre, -centre), radius).unwrap()]).unwrap();
            let c = Classifier::new(&d, ContainOptions::default()).unwrap();
            let tol = c.abs_tol();
            let frame = framed_grid(c.outer(), tol, cells);
            let critical = c.boxes().critical_abscissas();
            assert!(!critical.is_empty());
            let ranges = critical_ranges(&frame, critical, tol);
            let mut flagged_points = 0;
            for &xc in critical {
                for k in -40..=40 {
                    let x = xc + tol * f64::from(k) / 32.0;
                    for x in [x.next_down(), x, x.next_up()] {
                        let (first, end) = ranges[frame.col(x)];
                        let among = first as usize..end as usize;
                        let flagged = c.boxes().is_critical_x(x, tol);
                        flagged_points += usize::from(flagged);
                        assert_eq!(
                            c.boxes().is_critical_x_among(x, tol, among),
                            flagged,
                            "x = {x:e} near {xc:e}"
                        );
                    }
                }
            }
            assert!(flagged_points > 0);
            if cells > 8 {
                let flagged_columns = ranges.iter().filter(|r| r.0 < r.1).count();
                assert!(flagged_columns < frame.n() / 8, "{flagged_columns} columns");
            }
        }
    }
}
