//! One uniform-grid index for the workspace: a [`GridFrame`] maps points to the cells of a
//! grid over a box (`n x n`, or as many columns and rows as keep the cells near square), and a [`CellIndex`] stores, in compressed sparse rows, the items
//! registered in each cell. The monotone-box grid, the point locator, the mesh's edge index
//! and its point-spacing test are all one of these.

use crate::{BoundingBox, Point};

/// A grid of `columns x rows` equal cells over a box. Cell `(c, r)` (column, row) has index
/// `c * rows + r`. The column of `x` is `floor((x - x0) columns / width)` clamped to
/// `0..columns`: a monotone function of `x`, so every point of a rectangle falls in the cells
/// of [`GridFrame::cell_range`] of that rectangle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridFrame {
    bbox: BoundingBox,
    inv_w: f64,
    inv_h: f64,
    columns: usize,
    rows: usize,
}

impl GridFrame {
    /// The largest resolution accepted (cells per side): 8192^2 cells take 256 MiB of `u32`
    /// offsets.
    pub const MAX_CELLS: usize = 8192;

    /// The most cells of any frame, those of the largest square one: `MAX_CELLS^2`.
    pub const MAX_TOTAL_CELLS: usize = Self::MAX_CELLS * Self::MAX_CELLS;

    /// `n` cells per side (clamped to `1..=MAX_CELLS`) over `bbox`; a side of zero (or
    /// non-finite) width is one column (row) wide.
    pub fn new(bbox: BoundingBox, n: usize) -> Self {
        let n = n.clamp(1, Self::MAX_CELLS);
        Self::with_counts(bbox, n, n)
    }

    /// `columns x rows` cells over `bbox`, at least one each and at most
    /// [`GridFrame::MAX_TOTAL_CELLS`] in all (the longer side gives way); a side of zero (or
    /// non-finite) width is one column (row) wide. A side may have more than `MAX_CELLS`: a
    /// box 10^5 times wider than high wants its cells in few rows of many columns (capped at
    /// `MAX_CELLS` per side, a mesh's spacing grid over a drawing 10^9 long held thousands of
    /// points per cell).
    pub fn with_counts(bbox: BoundingBox, columns: usize, rows: usize) -> Self {
        let most = Self::MAX_TOTAL_CELLS;
        let (mut columns, mut rows) = (columns.clamp(1, most), rows.clamp(1, most));
        if columns.saturating_mul(rows) > most {
            if columns >= rows {
                columns = most / rows;
            } else {
                rows = most / columns;
            }
        }
        let inv = |n: usize, span: f64| {
            if spans_cells(span) {
                n as f64 / span
            } else {
                0.0
            }
        };
        Self {
            bbox,
            inv_w: inv(columns, bbox.width()),
            inv_h: inv(rows, bbox.height()),
            columns,
            rows,
        }
    }

    /// About `cells` cells (at most [`GridFrame::MAX_TOTAL_CELLS`]) over `bbox`, near square:
    /// `sqrt(cells w / h)` columns (at least 1, at most `cells`) and `cells / columns` rows for
    /// a box of width `w` and height `h` (all in one column or row for a side of zero width). An
    /// `n x n` grid over a box 10 000 times wider than high has cells 10 000 times wider than
    /// high, and a shape of the box's height is registered in all `n` rows.
    ///
    /// # Examples
    ///
    /// ```
    /// use rs_spline::grid::GridFrame;
    /// use rs_spline::{BoundingBox, Point};
    /// let thin = BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(400.0, 1.0));
    /// let f = GridFrame::near_square(thin, 1600);
    /// assert_eq!((f.columns(), f.rows()), (800, 2));
    /// assert_eq!(f.cell_size(), (0.5, 0.5));
    /// ```
    pub fn near_square(bbox: BoundingBox, cells: usize) -> Self {
        let (w, h) = (bbox.width(), bbox.height());
        let cells = cells.max(1) as f64;
        let (columns, rows) = match (spans_cells(w), spans_cells(h)) {
            (true, true) => {
                // The columns first, between 1 and all of the cells; the rows share out the
                // rest (each side from its own square root gave a box 10^14 times higher
                // than wide one column and 10^8 rows for 40 cells asked).
                let columns = (cells * (w / h)).sqrt().round().clamp(1.0, cells);
                (columns, (cells / columns).round().max(1.0))
            }
            (true, false) => (cells, 1.0),
            (false, true) => (1.0, cells),
            (false, false) => (1.0, 1.0),
        };
        // `as` saturates: a huge count becomes usize::MAX, then MAX_TOTAL_CELLS.
        Self::with_counts(bbox, columns.round() as usize, rows.round() as usize)
    }

    /// The resolution for registering shapes grown by `abs_tol` over `bbox`: at most `cells` per
    /// side, and cells no narrower than `abs_tol` (at least 1 per side). Each shape registers the
    /// cells of its rectangle grown by `abs_tol`, so cells much narrower than that multiply the
    /// registrations, and the memory, without sharpening anything.
    pub fn cells_for_tolerance(bbox: BoundingBox, abs_tol: f64, cells: usize) -> usize {
        let span = bbox.width().max(bbox.height());
        if abs_tol > 0.0 && span.is_finite() {
            cells.min(((span / abs_tol) as usize).max(1))
        } else {
            cells
        }
    }

    /// Cells per side of a square grid ([`GridFrame::new`]); the columns of another.
    #[inline]
    pub fn n(&self) -> usize {
        debug_assert_eq!(self.columns, self.rows, "n() of a grid that is not square");
        self.columns
    }

    /// Columns of cells (along x).
    #[inline]
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// Rows of cells (along y).
    #[inline]
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of cells, `columns x rows`.
    pub fn cell_count(&self) -> usize {
        self.columns * self.rows
    }

    /// The box covered.
    pub fn bounding_box(&self) -> BoundingBox {
        self.bbox
    }

    /// Cells per unit length along x and y (`columns / width`, `rows / height`; 0 for a side
    /// of zero width): the factors [`GridFrame::col`] and [`GridFrame::row`] multiply by.
    pub fn scales(&self) -> (f64, f64) {
        (self.inv_w, self.inv_h)
    }

    /// The box the cells cover.
    pub fn bbox(&self) -> BoundingBox {
        self.bbox
    }

    /// The width and height of a cell.
    #[inline]
    pub fn cell_size(&self) -> (f64, f64) {
        (
            self.bbox.width() / self.columns as f64,
            self.bbox.height() / self.rows as f64,
        )
    }

    /// The column of abscissa `x` (clamped into the grid).
    #[inline]
    pub fn col(&self, x: f64) -> usize {
        (((x - self.bbox.min.x) * self.inv_w).max(0.0) as usize).min(self.columns - 1)
    }

    /// The row of ordinate `y` (clamped into the grid).
    #[inline]
    pub fn row(&self, y: f64) -> usize {
        (((y - self.bbox.min.y) * self.inv_h).max(0.0) as usize).min(self.rows - 1)
    }

    /// The index of the cell holding `p`, or `None` outside the box.
    #[inline]
    pub fn cell_of(&self, p: Point) -> Option<usize> {
        self.bbox
            .contains(p)
            .then(|| self.col(p.x) * self.rows + self.row(p.y))
    }

    /// Columns `c0..=c1` and rows `r0..=r1` of the cells meeting the rectangle `r` (clamped).
    #[inline]
    pub fn cell_range(&self, r: BoundingBox) -> (usize, usize, usize, usize) {
        (
            self.col(r.min.x),
            self.col(r.max.x),
            self.row(r.min.y),
            self.row(r.max.y),
        )
    }

    /// Calls `f` with the index of every cell meeting the rectangle `r`.
    pub fn for_cells_in(&self, r: BoundingBox, mut f: impl FnMut(usize)) {
        let (c0, c1, r0, r1) = self.cell_range(r);
        for c in c0..=c1 {
            for row in r0..=r1 {
                f(c * self.rows + row);
            }
        }
    }
}

/// Can a side of this length be cut into cells? (Zero or non-finite sides are one cell.)
fn spans_cells(side: f64) -> bool {
    side > 0.0 && side.is_finite()
}

/// Items registered per cell of a [`GridFrame`], in compressed sparse rows: `offsets[cell]` to
/// `offsets[cell + 1]` index `items`. Built once from `(cell, item)` pairs; each cell's items
/// are sorted and distinct.
///
/// # Examples
///
/// ```
/// use rs_spline::grid::{CellIndex, GridFrame};
/// use rs_spline::{BoundingBox, Point};
/// let frame = GridFrame::new(
///     BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(1.0, 1.0)),
///     4,
/// );
/// let mut pairs = Vec::new();
/// // Item 7 covers the lower-left quarter, item 3 one cell at the top right.
/// frame.for_cells_in(
///     BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(0.4, 0.4)),
///     |c| pairs.push((c, 7u32)),
/// );
/// pairs.push((frame.cell_of(Point::new(0.9, 0.9)).unwrap(), 3));
/// let index = CellIndex::new(frame, pairs);
/// assert_eq!(index.at(Point::new(0.1, 0.1)), &[7]);
/// assert_eq!(index.at(Point::new(0.95, 0.99)), &[3]);
/// assert!(index.at(Point::new(0.6, 0.1)).is_empty());
/// assert!(index.at(Point::new(2.0, 0.0)).is_empty()); // outside the frame
/// ```
#[derive(Clone, Debug)]
pub struct CellIndex<T> {
    frame: GridFrame,
    offsets: Vec<u32>,
    items: Vec<T>,
}

impl<T: Copy + Ord> CellIndex<T> {
    /// The index of `pairs` (cell, item); pairs naming a cell outside the frame are dropped.
    /// At most `u32::MAX` pairs are kept.
    pub fn new(frame: GridFrame, mut pairs: Vec<(usize, T)>) -> Self {
        let cells = frame.cell_count();
        pairs.retain(|&(c, _)| c < cells);
        pairs.truncate(u32::MAX as usize);
        pairs.sort_unstable();
        pairs.dedup();
        let mut offsets = vec![0u32; cells + 1];
        for &(c, _) in &pairs {
            offsets[c + 1] += 1;
        }
        for c in 0..cells {
            offsets[c + 1] += offsets[c];
        }
        Self {
            frame,
            offsets,
            items: pairs.into_iter().map(|(_, t)| t).collect(),
        }
    }
}

impl CellIndex<u32> {
    /// The index of `points` by position: each point's index (as `u32`; at most `u32::MAX`
    /// points) in the cell holding it; points outside the frame are left out.
    ///
    /// # Examples
    ///
    /// ```
    /// use rs_spline::grid::{CellIndex, GridFrame};
    /// use rs_spline::{BoundingBox, Point};
    /// let frame = GridFrame::new(BoundingBox::from_point(Point::new(0.0, 0.0)).grown_by(1.0), 4);
    /// let pts = [Point::new(0.9, 0.9), Point::new(-0.9, -0.9), Point::new(5.0, 0.0)];
    /// let index = CellIndex::of_points(frame, &pts);
    /// assert_eq!(index.at(Point::new(0.95, 0.8)), &[0]);
    /// assert_eq!(index.at(Point::new(-0.8, -0.95)), &[1]);
    /// ```
    pub fn of_points(frame: GridFrame, points: &[Point]) -> Self {
        let pairs = points
            .iter()
            .enumerate()
            .filter_map(|(i, &p)| frame.cell_of(p).map(|c| (c, i as u32)))
            .collect();
        Self::new(frame, pairs)
    }
}

impl<T> CellIndex<T> {
    /// The frame.
    pub fn frame(&self) -> &GridFrame {
        &self.frame
    }

    /// The items of cell `cell` (empty past the last cell).
    pub fn cell(&self, cell: usize) -> &[T] {
        match (self.offsets.get(cell), self.offsets.get(cell + 1)) {
            (Some(&a), Some(&b)) => &self.items[a as usize..b as usize],
            _ => &[],
        }
    }

    /// The items of the cell holding `p` (empty outside the frame).
    pub fn at(&self, p: Point) -> &[T] {
        self.frame.cell_of(p).map_or(&[], |c| self.cell(c))
    }

    /// Does cell `cell` hold any item?
    pub fn is_occupied(&self, cell: usize) -> bool {
        !self.cell(cell).is_empty()
    }

    /// Number of (cell, item) registrations.
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// No registrations at all?
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> BoundingBox {
        BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(1.0, 2.0))
    }

    #[test]
    fn cells_are_monotone_and_cover_rectangles() {
        let f = GridFrame::new(unit(), 10);
        assert_eq!(f.col(-5.0), 0);
        assert_eq!(f.col(0.99999), 9);
        assert_eq!(f.col(7.0), 9);
        assert_eq!(f.row(1.0), 5);
        assert_eq!(f.cell_of(Point::new(1.5, 0.0)), None);
        let r = BoundingBox::from_point(Point::new(0.05, 0.05)).including(Point::new(0.25, 0.3));
        let mut cells = Vec::new();
        f.for_cells_in(r, |c| cells.push(c));
        // Columns 0..=2, rows 0..=1.
        assert_eq!(cells, vec![0, 1, 10, 11, 20, 21]);
        for i in 0..=20 {
            for j in 0..=20 {
                let p = Point::new(
                    r.min.x + r.width() * i as f64 / 20.0,
                    r.min.y + r.height() * j as f64 / 20.0,
                );
                assert!(cells.contains(&f.cell_of(p).unwrap()));
            }
        }
    }

    #[test]
    fn rectangular_frames_index_column_by_column() {
        let f = GridFrame::with_counts(unit(), 3, 5);
        assert_eq!(f.cell_count(), 15);
        assert_eq!(f.cell_size(), (1.0 / 3.0, 0.4));
        assert_eq!(f.cell_of(Point::new(0.5, 1.9)), Some(5 + 4));
        let mut cells = Vec::new();
        f.for_cells_in(unit(), |c| cells.push(c));
        assert_eq!(cells, (0..15).collect::<Vec<_>>());
        // Near square: 10^4 x 1 at 10^4 cells is 10^4 columns of one row, beyond `MAX_CELLS`
        // per side; 10^9 x 10^4 at 2^20 cells, 3 rows of 323 817 columns.
        let thin = BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(1e4, 1.0));
        let f = GridFrame::near_square(thin, 10_000);
        assert_eq!((f.columns(), f.rows()), (10_000, 1));
        let long = BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(1e9, 1e4));
        let f = GridFrame::near_square(long, 1 << 20);
        assert_eq!((f.columns(), f.rows()), (323_817, 3));
        // About the cells asked for, however thin the box (one column of 40 rows, not 10^8).
        let tall = BoundingBox::from_point(Point::new(-1.0, 0.0)).including(Point::new(1.0, 5e14));
        let f = GridFrame::near_square(tall, 40);
        assert_eq!((f.columns(), f.rows()), (1, 40));
        for aspect in [1e-300, 1e-20, 1e-3, 0.37, 1.0, 8.0, 1e9, 1e300] {
            let b =
                BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(aspect, 1.0));
            for cells in [1, 2, 7, 1000, 1 << 20] {
                let n = GridFrame::near_square(b, cells).cell_count();
                assert!(n >= cells / 2 && n <= 2 * cells, "{aspect} {cells}: {n}");
            }
        }
        // At most MAX_TOTAL_CELLS in all, the longer side giving way, whatever is asked.
        let f = GridFrame::with_counts(unit(), usize::MAX, 2);
        assert_eq!((f.columns(), f.rows()), (GridFrame::MAX_TOTAL_CELLS / 2, 2));
        let f = GridFrame::with_counts(unit(), 3, usize::MAX);
        assert_eq!((f.columns(), f.rows()), (3, GridFrame::MAX_TOTAL_CELLS / 3));
        assert_eq!(
            GridFrame::new(unit(), usize::MAX).columns(),
            GridFrame::MAX_CELLS
        );
        let flat = BoundingBox::from_point(Point::new(0.0, 3.0)).including(Point::new(2.0, 3.0));
        assert_eq!(GridFrame::near_square(flat, 50).columns(), 50);
        let f = GridFrame::near_square(unit(), 200); // 1 x 2: 10 x 20 cells of 0.1
        assert_eq!((f.columns(), f.rows()), (10, 20));
    }

    #[test]
    fn degenerate_frames_have_one_column() {
        let f = GridFrame::new(BoundingBox::from_point(Point::new(1.0, 1.0)), 16);
        assert_eq!(f.cell_of(Point::new(1.0, 1.0)), Some(0));
        let idx = CellIndex::new(f, vec![(0, 5u32), (0, 5), (0, 2), (99_999, 1)]);
        assert_eq!(idx.cell(0), &[2, 5]);
        assert_eq!(idx.len(), 2);
        assert!(idx.cell(300).is_empty());
    }
}
