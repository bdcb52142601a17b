//! The locator's index: the two-level grid of states and mixed-cell records, the parts the
//! boxes are registered as, and the lookup of a point's cell. Plain data, built by `build.rs`
//! and read by the queries of `mod.rs`.

use rs_spline::Point;
use rs_spline::grid::GridFrame;

/// Side of a block of the coarse level, in cells (a power of two).
pub(super) const BLOCK: usize = 8;
/// `log2(BLOCK)`.
pub(super) const BLOCK_SHIFT: u32 = 3;

/// Coarse state: the block holds mixed cells, or cells of both locations; read its cells.
pub(super) const REFINED: u8 = 2;

/// A fine entry below this is a uniform state; from it on, `entry - FIRST_RECORD` indexes the
/// mixed-cell records.
pub(super) const FIRST_RECORD: u32 = 2;

/// What the points of one mixed cell need.
#[derive(Clone, Copy, Debug)]
pub(super) struct MixedCell {
    /// Parity of the nearest uniform cell below in the column (false below the grid).
    pub(super) inside_below: bool,
    /// The parts (see [`Parts`]) registered in the cell
    /// (`near_items[near.0..near.1]`, vertical ones flagged).
    pub(super) near: (u32, u32),
    /// The distinct non-vertical parts registered from that uniform cell up to this one
    /// (`column_items[column.0..column.1]`).
    pub(super) column: (u32, u32),
    /// The cell's points are decided by inRS2 itself: the parity below is unknown (a cell
    /// that meets no box was found on the boundary: rounding of the registration against
    /// the boundary test).
    pub(super) by_inrs2: bool,
    /// The critical abscissas that may lie within the tolerance of a point of the cell (a
    /// range of `MonotoneBoxes::critical_abscissas`, usually empty): a point's abscissa is
    /// searched for among these only.
    pub(super) critical: (u32, u32),
}

/// The grid of a [`PointLocator`](crate::PointLocator), without the classifier it indexes (so that a
/// [`Classifier`](crate::Classifier) can build it once and lend it; see [`Classifier::locator`](crate::Classifier::locator)).
#[derive(Clone, Debug)]
pub struct LocatorIndex {
    /// Cells per side of the fine grid.
    pub(super) n: usize,
    /// Blocks per side of the coarse grid.
    pub(super) blocks: usize,
    /// Coarse states, a byte per block.
    pub(super) coarse: Vec<u8>,
    /// For each block, the first of its `BLOCK^2` fine entries in `fine` (refined blocks only).
    pub(super) block_start: Vec<u32>,
    /// Fine entries of the refined blocks, column-major within a block.
    pub(super) fine: Vec<u32>,
    pub(super) records: Vec<MixedCell>,
    pub(super) near_items: Vec<u32>,
    pub(super) column_items: Vec<u32>,
    /// Number of mixed cells and of (box, cell) registrations, for reports.
    pub(super) mixed_cells: usize,
    pub(super) incidences: usize,
    pub(super) lookup: Lookup,
    pub(super) parts: Parts,
}

/// The parts the boxes are registered as, each with its chord band
/// ([`rs_boxes::MonotoneBox::for_grid_parts`]): a box that spans more than a couple of cells is
/// halved until each part fits (a box's band is wide when its piece is curved across many
/// cells, a part's is narrow, so a part decides by its band most of the points its box would
/// decide by a solve); a smaller box is one part, with its own band.
///
/// The cells register parts by index. The bands are copied here, also a whole box's, so that
/// queries read them from one compact array and not from the boxes (536 bytes apart: on
/// 46 000 boxes nearly every read missed the caches).
#[derive(Clone, Debug)]
pub(super) struct Parts {
    pub(super) bands: Vec<rs_boxes::ChordBand>,
    /// The box each part was cut from.
    pub(super) owner: Vec<u32>,
}

impl Parts {
    /// The chord band of part `item`.
    #[inline]
    pub(super) fn band(&self, item: u32) -> &rs_boxes::ChordBand {
        &self.bands[item as usize]
    }

    /// The box part `item` was cut from (read only when its band cannot decide).
    #[inline]
    pub(super) fn owner<'b>(
        &self,
        boxes: &'b [rs_boxes::MonotoneBox],
        item: u32,
    ) -> &'b rs_boxes::MonotoneBox {
        &boxes[self.owner[item as usize] as usize]
    }
}

/// What a query needs to find its cell: the grid's box and the cells per unit length.
#[derive(Clone, Copy, Debug)]
pub(super) struct Lookup {
    pub(super) min: Point,
    pub(super) inv_w: f64,
    pub(super) inv_h: f64,
    /// `n - 1`, the last column and row.
    pub(super) last: f64,
    pub(super) blocks: usize,
}

impl Lookup {
    pub(super) fn new(frame: &GridFrame, blocks: usize) -> Self {
        let b = frame.bounding_box();
        // The frame's own scales: a point's cell here is the one `GridFrame::col` and `row`
        // give, the cell its boxes were registered by.
        let (inv_w, inv_h) = frame.scales();
        Self {
            min: b.min,
            inv_w,
            inv_h,
            last: (frame.n() - 1) as f64,
            blocks,
        }
    }

    /// The column and row of `p`'s cell, clamped into the grid: a point off the grid's box
    /// (or NaN) falls in the ring of cells along its border, which lie outside the domain's
    /// box and are all outside.
    #[inline]
    pub(super) fn cell(&self, p: Point) -> (usize, usize) {
        let c = self.index((p.x - self.min.x) * self.inv_w);
        let r = self.index((p.y - self.min.y) * self.inv_h);
        (c, r)
    }

    /// The coarse-table indices of the blocks of the points `(x[l], y[l])`, the same as
    /// [`Lookup::cell`] then [`Lookup::block`] give, in floating point (vectorised over the
    /// points): `floor(floor(f) / 8) = floor(f / 8)` for `f >= 0` (dividing by 8 is exact), and
    /// the index, an integer below `2^32`, is read from the low bits of its sum with `2^52`.
    #[inline(always)]
    pub(super) fn blocks(&self, x: &[f64; LANES], y: &[f64; LANES], out: &mut [u64; LANES]) {
        const TWO_52: f64 = 4_503_599_627_370_496.0;
        let floor8 = |f: f64| {
            let f = if f > 0.0 { f } else { 0.0 };
            let f = (if f < self.last { f } else { self.last }) * 0.125;
            let rounded = (f + TWO_52) - TWO_52;
            rounded - if rounded > f { 1.0 } else { 0.0 }
        };
        let blocks = self.blocks as f64;
        for ((o, &x), &y) in out.iter_mut().zip(x).zip(y) {
            let c = floor8((x - self.min.x) * self.inv_w);
            let r = floor8((y - self.min.y) * self.inv_h);
            *o = (c * blocks + r + TWO_52).to_bits() & 0xffff_ffff;
        }
    }

    /// The index in the coarse table of the block holding cell `(c, r)`.
    #[inline(always)]
    pub(super) fn block(&self, c: usize, r: usize) -> usize {
        (c >> BLOCK_SHIFT) * self.blocks + (r >> BLOCK_SHIFT)
    }

    /// `floor(f)` clamped to `0..=last` (0 for NaN), as `GridFrame::col` computes it, in a
    /// few branch-free instructions: each `if` is one `max`/`min` instruction, and adding
    /// `2^52` rounds to an integer held in the low bits (no saturating conversion).
    #[inline]
    pub(super) fn index(&self, f: f64) -> usize {
        const TWO_52: f64 = 4_503_599_627_370_496.0;
        let f = if f > 0.0 { f } else { 0.0 };
        let f = if f < self.last { f } else { self.last };
        let t = f + TWO_52;
        let rounded = t - TWO_52;
        (t.to_bits() as u32 as usize) - usize::from(rounded > f)
    }
}

/// The two tables a query reads and what it needs to find its cell in them, copied out of the
/// index into locals: the loops over many points then keep them in registers instead of
/// reloading each through the index on every point.
#[derive(Clone, Copy)]
pub(super) struct Tables<'a> {
    pub(super) lookup: Lookup,
    pub(super) coarse: &'a [u8],
    pub(super) block_start: &'a [u32],
    pub(super) fine: &'a [u32],
}

impl Tables<'_> {
    /// The coarse state of `p`'s block (`OUTSIDE`, `INSIDE` or `REFINED`), without a branch.
    #[inline]
    pub(super) fn coarse_state(&self, p: Point) -> usize {
        let (c, r) = self.lookup.cell(p);
        usize::from(self.coarse[self.lookup.block(c, r)])
    }

    /// The fine entry of `p`'s cell, in a refined block.
    #[inline]
    pub(super) fn fine_entry(&self, p: Point) -> u32 {
        let (c, r) = self.lookup.cell(p);
        let block = self.lookup.block(c, r);
        let within = (c & (BLOCK - 1)) * BLOCK + (r & (BLOCK - 1));
        self.fine[self.block_start[block] as usize + within]
    }
}

impl LocatorIndex {
    /// The tables queries read.
    pub(super) fn tables(&self) -> Tables<'_> {
        Tables {
            lookup: self.lookup,
            coarse: &self.coarse,
            block_start: &self.block_start,
            fine: &self.fine,
        }
    }
}

/// Points whose blocks are found side by side ([`Lookup::blocks`]): their coordinates and
/// indices take 6 KiB of the first-level cache.
pub(super) const LANES: usize = 256;
