//! The locator's index: the two-level grid of states and mixed-cell records, the parts the
//! boxes are registered as, and the lookup of a point's cell. Plain data, built by `build.rs`
//! and read by the queries of `mod.rs`.

use std::sync::OnceLock;
use std::sync::atomic::{AtomicBool, AtomicU8, AtomicUsize, Ordering};

use rs_spline::Point;
use rs_spline::grid::GridFrame;

/// Side of a block of the coarse level, in cells (a power of two).
pub(super) const BLOCK: usize = 8;
/// `log2(BLOCK)`.
pub(super) const BLOCK_SHIFT: u32 = 3;

/// Width of a strip, the unit the grid is built in, in cells: a few blocks. Narrower strips
/// make a first answer cheaper; wider ones repeat less work between neighbouring strips (a
/// box that spans two is registered from each).
pub(super) const STRIP: usize = 4 * BLOCK;

/// The strip holding column `c` of cells.
#[inline(always)]
pub(super) fn strip_of_column(c: usize) -> usize {
    c / STRIP
}

/// Coarse state: the block holds mixed cells, or cells of both locations; read its cells.
pub(super) const REFINED: u8 = 2;

/// Coarse state: the block's strip is not built yet; build it, then read its cells.
pub(super) const UNBUILT: u8 = 3;

/// A fine entry below this is a uniform state; from it on, `entry - FIRST_RECORD` indexes the
/// mixed-cell records.
pub(super) const FIRST_RECORD: u32 = 2;

/// What the points of one mixed cell need.
#[derive(Clone, Copy, Debug)]
pub(super) struct MixedCell {
    /// Winding number of the nearest uniform cell below in the column (0 below the grid).
    pub(super) winding_below: i32,
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
///
/// The grid is built one *strip* (32 columns of cells, four of blocks) at a time, when a
/// query first needs it: until then its blocks' coarse states read "not built", which sends
/// the query to the strip (built then, once, by the first thread to take it; a thread that
/// finds its strip taken builds untaken ones until it is ready). What a strip holds
/// depends on nothing outside its columns (the states of a column come from a walk up that
/// column), so the strips built on demand are the ones an eager build makes.
#[derive(Debug)]
pub struct LocatorIndex {
    /// Cells per side of the fine grid.
    pub(super) n: usize,
    /// Blocks per side of the coarse grid.
    pub(super) blocks: usize,
    /// Coarse states, a byte per block, block columns first: [`UNBUILT`] until the block's
    /// strip is built, then the strip's own state for it (never changed again).
    pub(super) coarse: Vec<AtomicU8>,
    /// The strips, each built on first use.
    pub(super) strips: Vec<OnceLock<Strip>>,
    /// Whether a thread has taken strip `s` to build (set before it builds, never cleared): a
    /// thread that needs a strip another is building builds strips no thread has taken
    /// meanwhile (`build::LocatorIndex::build_strip`).
    pub(super) taken: Vec<AtomicBool>,
    /// How many strips are built; when all are, `complete` is set.
    pub(super) built: AtomicUsize,
    /// The flat tables, made when the last strip is built: queries then read them as they
    /// would an eagerly built grid's.
    pub(super) complete: OnceLock<Complete>,
    pub(super) lookup: Lookup,
    pub(super) frame: GridFrame,
    /// For each column of cells, the range of critical abscissas that may lie within the
    /// tolerance of one of its points (`build::critical_ranges`).
    pub(super) critical: Vec<(u32, u32)>,
    /// The boxes that may register in strip `s` are `strip_boxes[strip_box_start[s]..
    /// strip_box_start[s + 1]]`, ascending.
    pub(super) strip_box_start: Vec<u32>,
    pub(super) strip_boxes: Vec<u32>,
}

impl Clone for LocatorIndex {
    fn clone(&self) -> Self {
        Self {
            n: self.n,
            blocks: self.blocks,
            coarse: self
                .coarse
                .iter()
                .map(|s| AtomicU8::new(s.load(Ordering::Relaxed)))
                .collect(),
            strips: self.strips.clone(),
            // A strip being built elsewhere is not in the copy: the copy builds its own.
            taken: self
                .strips
                .iter()
                .map(|s| AtomicBool::new(s.get().is_some()))
                .collect(),
            built: AtomicUsize::new(self.built.load(Ordering::Acquire)),
            complete: self.complete.clone(),
            lookup: self.lookup,
            frame: self.frame,
            critical: self.critical.clone(),
            strip_box_start: self.strip_box_start.clone(),
            strip_boxes: self.strip_boxes.clone(),
        }
    }
}

/// The grid over a range of block columns: the coarse states of its blocks, the fine entries
/// of its refined blocks, its mixed-cell records and the parts registered in its cells.
#[derive(Clone, Debug)]
pub(super) struct Strip {
    /// The first block column (global index).
    pub(super) first_block_column: usize,
    /// Blocks per column (the grid's).
    pub(super) blocks: usize,
    /// Coarse states of the strip's blocks, block columns first.
    pub(super) coarse: Vec<u8>,
    /// For each block, the first of its `BLOCK^2` fine entries in `fine` (refined blocks only).
    pub(super) block_start: Vec<u32>,
    /// Fine entries of the refined blocks, column-major within a block.
    pub(super) fine: Vec<u32>,
    pub(super) records: Vec<MixedCell>,
    pub(super) near_items: Vec<u32>,
    pub(super) column_items: Vec<u32>,
    /// Number of mixed cells and of (item, cell) registrations, for reports.
    pub(super) mixed_cells: usize,
    pub(super) incidences: usize,
    pub(super) parts: Parts,
}

impl Strip {
    /// The fine entry of cell `(c, r)` (global column and row, `c` in the strip): a uniform
    /// block's state, else the cell's entry in its block.
    #[inline]
    pub(super) fn entry(&self, c: usize, r: usize) -> u32 {
        let block = self.block(c, r);
        let state = self.coarse[block];
        if state != REFINED {
            return u32::from(state);
        }
        self.fine_entry(block, c, r)
    }

    /// The entry of cell `(c, r)` of block `block` (the strip's index of a refined block).
    #[inline(always)]
    pub(super) fn fine_entry(&self, block: usize, c: usize, r: usize) -> u32 {
        let within = (c & (BLOCK - 1)) * BLOCK + (r & (BLOCK - 1));
        self.fine[self.block_start[block] as usize + within]
    }

    /// The strip's index of the block of cell `(c, r)`.
    #[inline(always)]
    pub(super) fn block(&self, c: usize, r: usize) -> usize {
        ((c >> BLOCK_SHIFT) - self.first_block_column) * self.blocks + (r >> BLOCK_SHIFT)
    }
}

/// The parts the boxes are registered as, each with its chord band
/// ([`rs_boxes::MonotoneBox::for_grid_parts`]): a box that spans more than a couple of cells is
/// halved until each part fits (a box's band is wide when its piece is curved across many
/// cells, a part's is narrow, so a part decides by its band most of the points its box would
/// decide by a solve); a smaller box is one part, with its own band.
///
/// The cells register parts by index. The bands are copied here, also a whole box's, so that
/// queries read them from one compact array and not from the boxes (544 bytes apart: on
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

/// The grid once every strip is built, in the two flat tables an eager build would make: the
/// coarse states as plain bytes (which the compiler can gather side by side) and the refined
/// blocks' fine entries (copied from the strips; a mixed cell's entry still names a record of
/// its strip).
#[derive(Clone, Debug)]
pub(super) struct Complete {
    /// Blocks per column.
    pub(super) blocks: usize,
    pub(super) coarse: Box<[u8]>,
    /// For each block, the first of its `BLOCK^2` entries in `fine` (refined blocks only).
    pub(super) block_start: Box<[u32]>,
    pub(super) fine: Box<[u32]>,
}

impl Complete {
    /// The flat tables of the built `strips` (in order) over `blocks x blocks` blocks.
    pub(super) fn of<'s>(blocks: usize, strips: impl Iterator<Item = &'s Strip> + Clone) -> Self {
        // Each table made at its final size: grown by doubling, every regrowth copied it into
        // fresh pages (9 of the 153 page faults of a cold build on `s5_lune`).
        let (blocks_in, fine_in) = strips
            .clone()
            .fold((0, 0), |(b, f), s| (b + s.coarse.len(), f + s.fine.len()));
        let mut coarse = Vec::with_capacity(blocks_in);
        let mut block_start = Vec::with_capacity(blocks_in);
        let mut fine = Vec::with_capacity(fine_in);
        for strip in strips {
            coarse.extend_from_slice(&strip.coarse);
            let base = fine.len() as u32;
            block_start.extend(strip.block_start.iter().map(|&b| b + base));
            fine.extend_from_slice(&strip.fine);
        }
        debug_assert_eq!(coarse.len(), blocks * blocks);
        Self {
            blocks,
            coarse: coarse.into(),
            block_start: block_start.into(),
            fine: fine.into(),
        }
    }

    /// Bytes held.
    pub(super) fn memory_bytes(&self) -> usize {
        self.coarse.len() + 4 * (self.block_start.len() + self.fine.len())
    }
}

/// The grid as a query reads it: [`Complete`] once every strip is built, else the coarse table
/// being filled in and the strips.
pub(super) trait GridView: Copy {
    /// The state of block `block`: `OUTSIDE`, `INSIDE`, `REFINED` or `UNBUILT`.
    fn state(self, block: usize) -> usize;

    /// The entry of cell `(c, r)`, in a block whose state read `REFINED` or `UNBUILT`;
    /// `strip` gives the strip of a column (built now if it was not yet).
    fn entry<'s>(self, c: usize, r: usize, strip: impl FnOnce(usize) -> &'s Strip) -> u32;
}

/// [`Complete`]'s tables as slices held in locals (so that the loops over many points keep
/// them in registers, not reloading them through the index on every point).
#[derive(Clone, Copy)]
pub(super) struct CompleteView<'a> {
    blocks: usize,
    coarse: &'a [u8],
    block_start: &'a [u32],
    fine: &'a [u32],
}

impl GridView for CompleteView<'_> {
    #[inline(always)]
    fn state(self, block: usize) -> usize {
        usize::from(self.coarse[block]) & 3
    }

    /// The block is refined (this table has no [`UNBUILT`] state).
    #[inline(always)]
    fn entry<'s>(self, c: usize, r: usize, _: impl FnOnce(usize) -> &'s Strip) -> u32 {
        let block = (c >> BLOCK_SHIFT) * self.blocks + (r >> BLOCK_SHIFT);
        let within = (c & (BLOCK - 1)) * BLOCK + (r & (BLOCK - 1));
        self.fine[self.block_start[block] as usize + within]
    }
}

impl GridView for &[AtomicU8] {
    /// A relaxed load: a state other than [`UNBUILT`] is final, and [`UNBUILT`] sends the
    /// query to the strip, which waits for its build.
    #[inline(always)]
    fn state(self, block: usize) -> usize {
        usize::from(self[block].load(Ordering::Relaxed)) & 3
    }

    #[inline(always)]
    fn entry<'s>(self, c: usize, r: usize, strip: impl FnOnce(usize) -> &'s Strip) -> u32 {
        strip(strip_of_column(c)).entry(c, r)
    }
}

/// The table a query reads first and what it needs to find its cell in it, copied out of
/// the index into locals: the loops over many points then keep them in registers instead of
/// reloading each through the index on every point.
#[derive(Clone, Copy)]
pub(super) struct Tables<G> {
    pub(super) lookup: Lookup,
    pub(super) grid: G,
}

impl<G: GridView> Tables<G> {
    /// The coarse state of `p`'s block, without a branch.
    #[inline]
    pub(super) fn coarse_state(&self, p: Point) -> usize {
        let (c, r) = self.lookup.cell(p);
        self.grid.state(self.lookup.block(c, r))
    }
}

impl LocatorIndex {
    /// The flat tables, once every strip is built.
    pub(super) fn complete(&self) -> Option<Tables<CompleteView<'_>>> {
        self.complete.get().map(|c| Tables {
            lookup: self.lookup,
            grid: CompleteView {
                blocks: c.blocks,
                coarse: &c.coarse,
                block_start: &c.block_start,
                fine: &c.fine,
            },
        })
    }

    /// The coarse table being filled in, strip by strip.
    pub(super) fn filling(&self) -> Tables<&[AtomicU8]> {
        Tables {
            lookup: self.lookup,
            grid: &self.coarse,
        }
    }
}

/// Points whose blocks are found side by side ([`Lookup::blocks`]): their coordinates and
/// indices take 6 KiB of the first-level cache.
pub(super) const LANES: usize = 256;
