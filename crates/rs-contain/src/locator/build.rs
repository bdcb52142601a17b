//! Building a [`LocatorIndex`]: the boxes' registrations, the uniform runs of each column
//! (their states found walking up the column),
//! the mixed-cell records and the two levels. The work follows the boundary (its cells, the
//! runs between them, the blocks), not the grid's area: no table of `n x n` cells is built.

use rs_spline::grid::GridFrame;
use rs_spline::{BoundingBox, Point};

use super::{
    BLOCK, FIRST_RECORD, INSIDE, LocatorIndex, Lookup, MixedCell, OUTSIDE, Parts, REFINED,
    VERTICAL_FLAG,
};
use crate::{Classifier, Location};

/// Run state: inRS2 found the run's first cell centre on the boundary, which a cell that
/// meets no box cannot hold (the rounding of the registration against the boundary test): its
/// points are decided by inRS2 itself.
const BY_INRS2: u8 = 2;

impl LocatorIndex {
    /// Registers every box (or its parts) in the cells near its curve, classifies the uniform
    /// runs between them, and stores the two levels and the mixed-cell records.
    pub(super) fn build(classifier: &Classifier, cells: usize) -> Self {
        let tol = classifier.abs_tol();
        let frame = framed_grid(classifier.outer(), tol, cells);
        let n = frame.n();
        let (parts, pairs) = register(classifier, &frame);
        let incidences = pairs.len();
        let columns = Columns::new(n, &pairs, classifier, &frame, &parts);
        Self::from_columns(&frame, parts, &columns, incidences)
    }

    /// The index of the grid `frame` from its columns.
    fn from_columns(frame: &GridFrame, parts: Parts, columns: &Columns, incidences: usize) -> Self {
        let n = frame.n();
        let blocks = n.div_ceil(BLOCK);
        let mut ix = Self {
            n,
            blocks,
            coarse: vec![OUTSIDE; blocks * blocks],
            block_start: vec![0; blocks * blocks],
            fine: Vec::new(),
            records: Vec::new(),
            // The `k`-th occupied cell's items are its record's near items: one copy of all.
            near_items: columns.items.clone(),
            column_items: Vec::new(),
            mixed_cells: columns.rows.len(),
            incidences,
            lookup: Lookup::new(frame, blocks),
            parts,
        };
        let by_inrs2 = ix.mixed_records(columns);
        ix.two_levels(columns, by_inrs2);
        ix
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
        for c in 0..columns.n {
            let (mut inside_below, mut unknown_below) = (false, false);
            since_uniform.clear();
            let mut shared = None;
            for k in columns.start[c]..columns.start[c + 1] {
                let (below, state) = columns.run_below(c, k);
                if !below.is_empty() {
                    inside_below = state == INSIDE;
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
                    inside_below,
                    near: (columns.item_start[k], columns.item_start[k + 1]),
                    column,
                    by_inrs2: unknown_below,
                    critical: columns.critical[c],
                });
            }
        }
        self.records.push(MixedCell {
            inside_below: false,
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
    /// index a binary search would give, found by moving forward).
    fn two_levels(&mut self, columns: &Columns, by_inrs2: u32) {
        let (n, blocks) = (self.n, self.blocks);
        for bc in 0..blocks {
            let cols = (bc * BLOCK)..((bc + 1) * BLOCK).min(n);
            let mut next = [0usize; BLOCK];
            for br in 0..blocks {
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
                    self.coarse[block] = shared.unwrap_or(OUTSIDE);
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
            }
        }
    }
}

/// Registers every box in the cells near its curve: a box that spans a couple of cells as
/// itself, a longer one as its parts (see [`Parts`]). Returns the parts and the sorted,
/// distinct `(cell, item)` pairs, vertical items flagged, each as one integer
/// `cell << 32 | item` (see [`pair_cell`] and [`pair_item`]).
fn register(classifier: &Classifier, frame: &GridFrame) -> (Parts, Vec<u64>) {
    let tol = classifier.abs_tol();
    let all = classifier.boxes().boxes();
    let cells = frame.cell_count();
    // Each pair as one integer, `cell << 32 | item`, so that sorting compares one word (a
    // grid has at most 8192^2 < 2^32 cells). A part meets a few cells.
    let mut pairs: Vec<u64> = Vec::with_capacity(4 * all.len());
    let mut parts = Parts {
        bands: Vec::with_capacity(all.len()),
        owner: Vec::with_capacity(all.len()),
    };
    let mut add = |band: rs_boxes::ChordBand, bi: usize, flag: u32| {
        let id = parts.bands.len() as u32;
        parts.bands.push(band);
        parts.owner.push(bi as u32);
        frame.for_cells_in(band.rectangle_near(tol), |c| {
            pairs.push((c as u64) << 32 | u64::from(id | flag));
        });
    };
    for (bi, b) in all.iter().enumerate() {
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
            add(b.band, bi, flag);
        } else {
            b.for_grid_parts(frame, |band, _| add(band, bi, flag));
        }
    }
    pairs.retain(|&p| pair_cell(p) < cells);
    pairs.sort_unstable();
    pairs.dedup();
    (parts, pairs)
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

/// The grid column by column: its occupied cells (those where an item is registered), their
/// items, and the state of each run of unoccupied cells between them.
struct Columns {
    n: usize,
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
    /// For column `c`, the range of critical abscissas (indices into
    /// `MonotoneBoxes::critical_abscissas`) that may lie within the tolerance of one of its
    /// points (see [`critical_ranges`]).
    critical: Vec<(u32, u32)>,
}

impl Columns {
    /// The columns of the grid `frame` (`n` cells per side) from the sorted, distinct
    /// `(cell, item)` pairs of the `parts` ([`register`]'s), with the runs' states (see
    /// [`Columns::classify_runs`]).
    fn new(
        n: usize,
        pairs: &[u64],
        classifier: &Classifier,
        frame: &GridFrame,
        parts: &Parts,
    ) -> Self {
        let mut start = vec![0usize; n + 1];
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
        for c in 0..n {
            start[c + 1] += start[c];
        }
        let mut columns = Self {
            n,
            start,
            rows,
            item_start,
            items,
            runs: Vec::new(),
            critical: critical_ranges(
                frame,
                classifier.boxes().critical_abscissas(),
                classifier.abs_tol(),
            ),
        };
        columns.classify_runs(classifier, frame, parts);
        columns
    }

    /// Each run's state: the location inRS2 gives its first cell's centre (empty runs are left
    /// outside), found walking each column upwards instead of by an inRS2 batch.
    ///
    /// inRS2 at a point `p` off the boundary is the parity of the boxes whose
    /// [`MonotoneBox::crosses_below`](rs_boxes::MonotoneBox::crosses_below) holds at `p`. From
    /// one run's first centre `q` to the next run's `p` (same abscissa, higher), that test
    /// changes only for boxes whose curve meets the column between them, in the occupied cells
    /// between the two runs (a run's cells meet no box): so the parity at `p` is the parity at
    /// `q` plus the number of those cells' boxes (non-vertical, each once) whose test differs
    /// at `p` and at `q`, the very test inRS2 makes. Below the first run no box is crossed.
    /// inRS2's other answers are kept: outside the grown bounding box a point is outside; a
    /// column on a critical abscissa takes inRS2's fallback at each centre; a centre near one
    /// of the boxes registered just below it (which the registration's reach rules out but
    /// for rounding) is on the boundary, a [`BY_INRS2`] run.
    fn classify_runs(&mut self, classifier: &Classifier, frame: &GridFrame, parts: &Parts) {
        let (cw, ch) = frame.cell_size();
        let origin = frame.bounding_box().min;
        let (tol, outer) = (classifier.abs_tol(), classifier.outer());
        let boxes = classifier.boxes();
        let all = boxes.boxes();
        self.runs = vec![OUTSIDE; self.rows.len() + self.n];
        // The boxes of the occupied cells since the last run, each once: `seen[b] == epoch`
        // once box `b` is among `candidates` (a new epoch for every new list; fewer than
        // `2^32` lists, one per run).
        let mut seen = vec![0u32; all.len()];
        let mut epoch = 0u32;
        let mut candidates: Vec<u32> = Vec::new();
        // `MonotoneBox::crosses_below` (the band's answer, else the solve's) at a point of
        // column `c`, its solve made once per box and column: where the curve meets the
        // column is `solved[b]` while `solved_in[b]` is `c + 1`.
        let mut solved: Vec<Option<(f64, f64)>> = vec![None; all.len()];
        let mut solved_in = vec![0usize; all.len()];
        let mut crosses_below = |b: usize, p: Point, c: usize| {
            all[b].band.crossing_below(p).unwrap_or_else(|| {
                if solved_in[b] != c + 1 {
                    solved_in[b] = c + 1;
                    solved[b] = all[b].at_x(p.x);
                }
                solved[b].is_some_and(|(_, y)| y < p.y)
            })
        };
        for c in 0..self.n {
            let x = origin.x + (c as f64 + 0.5) * cw;
            let (first, end) = self.critical[c];
            let critical =
                first < end && boxes.is_critical_x_among(x, tol, first as usize..end as usize);
            let occupied = self.start[c + 1] - self.start[c];
            let (mut odd, mut below) = (false, None::<Point>);
            candidates.clear();
            epoch += 1;
            for j in 0..=occupied {
                let run = self.run(c, j);
                if !run.is_empty() {
                    let p = Point::new(x, origin.y + (run.start as f64 + 0.5) * ch);
                    let location = if critical {
                        classifier.classify_point_with_decision(p).0
                    } else {
                        let mut near = false;
                        for &b in &candidates {
                            let b = b as usize;
                            near |= all[b].is_near(p, tol);
                            let crossed_below_q = below.is_some_and(|q| crosses_below(b, q, c));
                            odd ^= crosses_below(b, p, c) != crossed_below_q;
                        }
                        if !outer.contains(p) {
                            Location::Outside
                        } else if near {
                            Location::Boundary
                        } else if odd {
                            Location::Inside
                        } else {
                            Location::Outside
                        }
                    };
                    let slot = self.run_slot(c, j);
                    self.runs[slot] = match location {
                        Location::Inside => INSIDE,
                        Location::Outside => OUTSIDE,
                        Location::Boundary => BY_INRS2,
                    };
                    below = Some(p);
                    candidates.clear();
                    epoch += 1;
                }
                if j < occupied {
                    for &item in self.items_of(self.start[c] + j) {
                        if item & VERTICAL_FLAG == 0 {
                            let b = parts.owner[item as usize];
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

    /// The run just below occupied cell `k` of column `c`, and its state.
    fn run_below(&self, c: usize, k: usize) -> (std::ops::Range<usize>, u8) {
        let j = k - self.start[c];
        (self.run(c, j), self.runs[self.run_slot(c, j)])
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
            let (parts, pairs) = register(&c, &frame);
            let occupied: std::collections::BTreeSet<usize> =
                pairs.iter().map(|&p| pair_cell(p)).collect();
            let columns = Columns::new(n, &pairs, &c, &frame, &parts);
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
        let (parts, _) = register(c, frame);
        let ix = LocatorIndex::from_columns(frame, parts, columns, pairs.len());
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
                let (parts, _) = register(&c, &frame);
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
                    let (parts, pairs) = register(&c, &frame);
                    let columns = Columns::new(n, &pairs, &c, &frame, &parts);
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
        let frame = framed_grid(c.outer(), c.abs_tol(), 16);
        let n = frame.n();
        let (parts, pairs) = register(&c, &frame);
        let incidences = pairs.len();
        let mut columns = Columns::new(n, &pairs, &c, &frame, &parts);
        // The middle column's run inside the circle (between its two boundary crossings),
        // marked of unknown parity; its state was inside.
        let col = n / 2;
        let j = (1..=columns.start[col + 1] - columns.start[col])
            .find(|&j| {
                !columns.run(col, j).is_empty() && columns.runs[columns.run_slot(col, j)] == INSIDE
            })
            .unwrap();
        let slot = columns.run_slot(col, j);
        columns.runs[slot] = BY_INRS2;
        let run = columns.run(col, j);
        let ix = LocatorIndex::from_columns(&frame, parts, &columns, incidences);
        // The occupied cells right above the run take inRS2 too.
        let above = columns.start[col] + j;
        assert!(ix.records[above].by_inrs2);
        assert!(
            !ix.records[columns.start[col]].by_inrs2,
            "below the run: parity known"
        );
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
        let by_inrs2 = FIRST_RECORD + (ix.records.len() - 1) as u32;
        assert!(ix.records[(by_inrs2 - FIRST_RECORD) as usize].by_inrs2);
        for p in &pts[..5 * run.len()] {
            assert_eq!(
                ix.tables().fine_entry(*p),
                by_inrs2,
                "a cell of the run at {p:?}"
            );
        }
        let expected = c.locate_all_with(Method::InRS2, &pts);
        assert!(expected.contains(&Location::Inside));
        assert_eq!(crate::Locate::locate_all(&loc, &pts), expected);
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
