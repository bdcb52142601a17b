//! Building a [`LocatorIndex`]: the boxes' registrations, the uniform runs of each column,
//! the mixed-cell records and the two levels. The work follows the boundary (its cells, the
//! runs between them, the blocks), not the grid's area: no table of `n x n` cells is built.

use rs_spline::grid::GridFrame;
use rs_spline::{BoundingBox, Point};

use super::{
    BLOCK, FIRST_RECORD, INSIDE, LocatorIndex, Lookup, MixedCell, OUTSIDE, Parts, REFINED,
    VERTICAL_FLAG,
};
use crate::{Classifier, Location, Method};

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
        let columns = Columns::new(n, pairs, classifier, &frame);
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
            near_items: Vec::new(),
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
        let mut since_uniform: Vec<u32> = Vec::new();
        for c in 0..columns.n {
            let (mut inside_below, mut unknown_below) = (false, false);
            since_uniform.clear();
            for k in columns.start[c]..columns.start[c + 1] {
                let (below, state) = columns.run_below(c, k);
                if !below.is_empty() {
                    inside_below = state == INSIDE;
                    // Above a run of unknown parity, inRS2 decides too.
                    unknown_below = state == BY_INRS2;
                    since_uniform.clear();
                }
                let items = columns.items_of(k);
                since_uniform.extend(items.iter().filter(|&&b| b & VERTICAL_FLAG == 0));
                since_uniform.sort_unstable();
                since_uniform.dedup();
                self.records.push(MixedCell {
                    inside_below,
                    near: push_items(&mut self.near_items, items),
                    column: push_items(&mut self.column_items, &since_uniform),
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
    fn two_levels(&mut self, columns: &Columns, by_inrs2: u32) {
        let (n, blocks) = (self.n, self.blocks);
        for bc in 0..blocks {
            let cols = (bc * BLOCK)..((bc + 1) * BLOCK).min(n);
            for br in 0..blocks {
                let block = bc * blocks + br;
                let rows = (br * BLOCK)..((br + 1) * BLOCK).min(n);
                let mut shared = None;
                let uniform = cols.clone().all(|c| match columns.state_of_rows(c, &rows) {
                    Some(s) if s != BY_INRS2 => *shared.get_or_insert(s) == s,
                    _ => false,
                });
                if uniform {
                    self.coarse[block] = shared.unwrap_or(OUTSIDE);
                    continue;
                }
                self.coarse[block] = REFINED;
                self.block_start[block] = self.fine.len() as u32;
                let start = self.fine.len();
                self.fine.resize(start + BLOCK * BLOCK, u32::from(OUTSIDE));
                for c in cols.clone() {
                    for r in rows.clone() {
                        let entry = match columns.cell(c, r) {
                            Cell::Occupied(k) => FIRST_RECORD + k as u32,
                            Cell::Run(BY_INRS2) => FIRST_RECORD + by_inrs2,
                            Cell::Run(s) => u32::from(s),
                        };
                        self.fine[start + (c - cols.start) * BLOCK + (r - rows.start)] = entry;
                    }
                }
            }
        }
    }
}

/// Registers every box in the cells near its curve: a box that spans a couple of cells as
/// itself, a longer one as its parts (see [`Parts`]). Returns the parts and the sorted,
/// distinct `(cell, item)` pairs, vertical items flagged.
fn register(classifier: &Classifier, frame: &GridFrame) -> (Parts, Vec<(usize, u32)>) {
    let tol = classifier.abs_tol();
    let all = classifier.boxes().boxes();
    let cells = frame.cell_count();
    // Each pair as one integer, `cell << 32 | item`, so that sorting compares one word (a
    // grid has at most 8192^2 < 2^32 cells).
    let mut pairs: Vec<u64> = Vec::new();
    let mut parts = Parts {
        bands: Vec::new(),
        owner: Vec::new(),
    };
    for (bi, b) in all.iter().enumerate() {
        // Vertical boxes are never crossed by the ray (it runs an infinitesimal distance
        // to their right): flag them so the walk down a column skips them.
        let flag = if b.x_dir == rs_boxes::Monotonicity::Constant {
            VERTICAL_FLAG
        } else {
            0
        };
        b.for_grid_parts(frame, |band, _| {
            let id = parts.bands.len() as u32;
            parts.bands.push(band);
            parts.owner.push(bi as u32);
            frame.for_cells_in(band.rectangle_near(tol), |c| {
                pairs.push((c as u64) << 32 | u64::from(id | flag));
            });
        });
    }
    pairs.retain(|&p| ((p >> 32) as usize) < cells);
    pairs.sort_unstable();
    pairs.dedup();
    let pairs = pairs
        .into_iter()
        .map(|p| ((p >> 32) as usize, p as u32))
        .collect();
    (parts, pairs)
}

/// What a cell of the grid is: occupied (the `k`-th occupied cell in column order), or in a
/// run of cells that meet no box, with the run's state.
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
    /// `(cell, item)` pairs; the runs' first cells are classified in one inRS2 batch.
    fn new(n: usize, pairs: Vec<(usize, u32)>, classifier: &Classifier, frame: &GridFrame) -> Self {
        let mut start = vec![0usize; n + 1];
        let mut rows: Vec<u32> = Vec::new();
        let mut item_start: Vec<u32> = Vec::new();
        let mut items: Vec<u32> = Vec::with_capacity(pairs.len());
        let mut last = usize::MAX;
        for (cell, item) in pairs {
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
        columns.classify_runs(classifier, frame);
        columns
    }

    /// Each run's state: its first cell's centre by inRS2 (empty runs are left outside).
    fn classify_runs(&mut self, classifier: &Classifier, frame: &GridFrame) {
        let (cw, ch) = frame.cell_size();
        let origin = frame.bounding_box().min;
        let mut centers = Vec::new();
        let mut slots = Vec::new();
        for c in 0..self.n {
            for j in 0..=(self.start[c + 1] - self.start[c]) {
                let run = self.run(c, j);
                if !run.is_empty() {
                    centers.push(Point::new(
                        origin.x + (c as f64 + 0.5) * cw,
                        origin.y + (run.start as f64 + 0.5) * ch,
                    ));
                    slots.push(self.run_slot(c, j));
                }
            }
        }
        self.runs = vec![OUTSIDE; self.rows.len() + self.n];
        for (slot, l) in slots
            .into_iter()
            .zip(classifier.locate_all_with(Method::InRS2, &centers))
        {
            self.runs[slot] = match l {
                Location::Inside => INSIDE,
                Location::Outside => OUTSIDE,
                Location::Boundary => BY_INRS2,
            };
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
    fn state_of_rows(&self, c: usize, rows: &std::ops::Range<usize>) -> Option<u8> {
        let occupied = self.occupied_rows(c);
        let j = occupied.partition_point(|&x| (x as usize) < rows.start);
        match occupied.get(j) {
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
    use crate::ContainOptions;
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
            let (_, pairs) = register(&c, &frame);
            let occupied: std::collections::BTreeSet<usize> =
                pairs.iter().map(|&(cell, _)| cell).collect();
            let columns = Columns::new(n, pairs.clone(), &c, &frame);
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
                                .filter(|&&(cell, _)| cell == col * n + r)
                                .map(|&(_, i)| i)
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
        let mut columns = Columns::new(n, pairs, &c, &frame);
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
