//! Sub-linear point location: a uniform grid of cells with precomputed locations over the
//! monotone boxes, answering almost every point in constant time with the same result as inRS2.

use std::borrow::Cow;

use rs_spline::Point;
use rs_spline::grid::{CellIndex, GridFrame};

use smallvec::SmallVec;

use crate::{Classifier, Locate, Location, Method};

/// Cell state: every point of the cell is outside.
const OUTSIDE: u8 = 0;
/// Cell state: every point of the cell is inside.
const INSIDE: u8 = 1;
/// Cell state: the cell meets a box (grown by the tolerance); decide point by point.
const MIXED: u8 = 2;

/// Locations of the uniform states, indexed by state.
const UNIFORM: [Location; 2] = [Location::Outside, Location::Inside];

/// Default grid resolution: cells per side of the bounding box. Chosen by measurement
/// (`cargo xtask bench`, README): on the paper's domains, 1024 x 1024 cells leave well under 1% of
/// uniformly spread points in boundary cells, and finer grids only add build time and memory.
pub const DEFAULT_GRID_CELLS: usize = 1024;

/// Options of a [`PointLocator`]: [`LocatorOptions::DEFAULT`] and `with_*` setters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct LocatorOptions {
    /// Cells per side of the grid (clamped to `1..=8192`, and coarser when the boundary
    /// tolerance is wider than a cell).
    pub cells: usize,
}

impl LocatorOptions {
    /// [`DEFAULT_GRID_CELLS`] cells per side.
    pub const DEFAULT: LocatorOptions = LocatorOptions {
        cells: DEFAULT_GRID_CELLS,
    };

    /// With `cells` cells per side.
    pub const fn with_cells(mut self, cells: usize) -> Self {
        self.cells = cells;
        self
    }
}

impl Default for LocatorOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A point-location index over a [`Classifier`]'s monotone boxes.
///
/// # Design
/// A uniform `n x n` grid covers the bounding box grown by the tolerance. Each monotone box,
/// grown by the boundary tolerance, is registered in every cell it meets (compressed sparse
/// rows). A cell that meets no box contains no boundary point, so all of its points share one
/// location: for each column, the first cell of every run of such cells is classified exactly by
/// inRS2 (one batch for the whole grid) and the run inherits it. A query then costs:
/// - outside the grown bounding box, or in a uniform cell: one cell lookup, `O(1)`;
/// - in a *mixed* cell: the boundary test against the boxes of its cell, then the crossing
///   parity from the nearest uniform cell below in the same column (its known location) plus
///   the crossings of the vertical ray with the distinct boxes registered between the two, one
///   bracketed solve at most per box, `O(k)` for `k` boxes in that stretch of the column. Points
///   on a critical abscissa take inRS2's fallback (horizontal ray, winding number).
///
/// Results are identical to [`Method::InRS2`]: uniform cells are classified by inRS2 itself and
/// no box below the reference cell can reach it, so the crossings counted above it are exactly
/// those inRS2 counts there, with the same per-box test.
///
/// # Cost
/// Build: `O(n^2 + (cells met by boxes))` memory and time plus one inRS2 batch over the run
/// starts; memory is 5.25 bytes per cell (a byte and two bits of state, a 4-byte offset) plus
/// 4 bytes per (box, cell) incidence: about 5.5 MiB for the default 1024 x 1024 grid,
/// independent of the number of points. Queries read only the 2-bit states (256 KiB at 1024).
/// Each box is registered only in the cells near its curve (its piece is halved until each part
/// spans a couple of cells), so incidences grow with the boundary's length in cells, not with the
/// boxes' areas (timings: `cargo xtask bench`, reported in the README). Worst case per query: a
/// mixed cell in a column that is mixed all the way down, `O(N)` for `N` boxes in that column;
/// fine grids and refined boxes keep `k` small.
///
/// # Examples
///
/// ```
/// use rs_contain::{Classifier, ContainOptions, Location, Locate, LocatorOptions, Method, PointLocator};
/// use rs_spline::{circle, Domain, Point};
/// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let c = Classifier::new(&d, ContainOptions::default()).unwrap();
/// let loc = PointLocator::new(&c, LocatorOptions::DEFAULT.with_cells(64));
/// let pts = [Point::new(0.0, 0.0), Point::new(0.9, 0.0), Point::new(1.0, 0.0)];
/// assert_eq!(loc.locate_all(&pts), c.classify(&pts, Method::InRS2));
/// assert_eq!(loc.locate(Point::new(3.0, 0.0)), Location::Outside);
/// ```
#[derive(Clone, Debug)]
pub struct PointLocator<'a> {
    classifier: &'a Classifier,
    ix: Cow<'a, LocatorIndex>,
}

/// The grid of a [`PointLocator`], without the classifier it indexes (so that a
/// [`Classifier`] can build it once and lend it; see [`Classifier::locator`]).
#[derive(Clone, Debug)]
pub struct LocatorIndex {
    /// The boxes registered in the cells near their curves (vertical ones flagged).
    cells: CellIndex<u32>,
    n: usize,
    state: Vec<u8>,
    /// `state` packed two bits per cell (32 cells per word) for cache-friendly queries.
    packed: Vec<u64>,
}

impl LocatorIndex {
    /// Registers every box in the cells near its curve, then classifies the box-free cells.
    fn build(classifier: &Classifier, cells: usize) -> Self {
        let tol = classifier.abs_tol();
        let frame = GridFrame::new(
            classifier.outer(),
            GridFrame::cells_for_tolerance(classifier.outer(), tol, cells),
        );
        let n = frame.n();
        let all = classifier.boxes().boxes();
        let mut pairs: Vec<(usize, u32)> = Vec::new();
        for (bi, b) in all.iter().enumerate() {
            // Vertical boxes are never crossed by the ray (it runs an infinitesimal distance
            // to their right): flag them so the walk down a column skips them.
            let id = if b.x_dir == rs_boxes::Monotonicity::Constant {
                bi as u32 | VERTICAL_FLAG
            } else {
                bi as u32
            };
            b.for_cells_near(&frame, tol, |c| pairs.push((c, id)));
        }
        let mut ix = Self {
            cells: CellIndex::new(frame, pairs),
            n,
            state: vec![OUTSIDE; n * n],
            packed: Vec::new(),
        };
        ix.classify_uniform_cells(classifier);
        ix.packed = vec![0u64; (n * n).div_ceil(32)];
        for (i, &st) in ix.state.iter().enumerate() {
            ix.packed[i >> 5] |= u64::from(st) << ((i & 31) * 2);
        }
        ix
    }

    /// Marks the cells that meet a box mixed, and classifies each run of box-free cells in a
    /// column by its first cell (one inRS2 batch for the whole grid).
    fn classify_uniform_cells(&mut self, classifier: &Classifier) {
        let n = self.n;
        let frame = *self.cells.frame();
        let (cw, ch) = frame.cell_size();
        let origin = frame.bounding_box().min;
        let mut starts: Vec<usize> = Vec::new();
        for c in 0..n {
            let mut prev_mixed = true;
            for r in 0..n {
                let cell = c * n + r;
                let mixed = self.cells.is_occupied(cell);
                if mixed {
                    self.state[cell] = MIXED;
                } else if prev_mixed {
                    starts.push(cell);
                }
                prev_mixed = mixed;
            }
        }
        let centers: Vec<Point> = starts
            .iter()
            .map(|&cell| {
                let (c, r) = (cell / n, cell % n);
                Point::new(
                    origin.x + (c as f64 + 0.5) * cw,
                    origin.y + (r as f64 + 0.5) * ch,
                )
            })
            .collect();
        let located = classifier.classify(&centers, Method::InRS2);
        for (&cell, &l) in starts.iter().zip(&located) {
            let s = match l {
                Location::Inside => INSIDE,
                Location::Outside => OUTSIDE,
                // Cannot happen for a box-free cell; deciding point by point is always right.
                Location::Boundary => MIXED,
            };
            let (c, r0) = (cell / n, cell % n);
            for r in r0..n {
                let i = c * n + r;
                if self.cells.is_occupied(i) {
                    break;
                }
                self.state[i] = s;
            }
        }
    }
}

impl<'a> PointLocator<'a> {
    /// Builds the index.
    pub fn new(classifier: &'a Classifier, options: LocatorOptions) -> Self {
        Self {
            classifier,
            ix: Cow::Owned(LocatorIndex::build(classifier, options.cells)),
        }
    }

    /// A locator over `classifier` with an index built before for it.
    pub(crate) fn with_index(classifier: &'a Classifier, index: &'a LocatorIndex) -> Self {
        Self {
            classifier,
            ix: Cow::Borrowed(index),
        }
    }

    /// The index, to keep (see [`PointLocator::with_index`]).
    pub(crate) fn into_index(self) -> LocatorIndex {
        self.ix.into_owned()
    }

    /// The grid resolution (cells per side).
    pub fn cells(&self) -> usize {
        self.ix.n
    }

    /// Fraction of cells that are mixed (meet a box).
    pub fn mixed_fraction(&self) -> f64 {
        self.ix.state.iter().filter(|&&s| s == MIXED).count() as f64 / self.ix.state.len() as f64
    }

    /// Number of (box, cell) incidences stored.
    pub fn incidences(&self) -> usize {
        self.ix.cells.len()
    }

    /// The location of one point (same as [`Method::InRS2`]).
    fn locate_point(&self, p: Point) -> Location {
        if !self.classifier.outer().contains(p) {
            return Location::Outside;
        }
        let frame = self.ix.cells.frame();
        let (c, r) = (frame.col(p.x), frame.row(p.y));
        let cell = c * self.ix.n + r;
        let state = ((self.ix.packed[cell >> 5] >> ((cell & 31) * 2)) & 3) as usize;
        // Inside and outside cells come in no predictable order: look the answer up instead of
        // branching on it; only mixed cells (rare) branch.
        if state == MIXED as usize {
            self.locate_mixed(p, c, r)
        } else {
            UNIFORM[state]
        }
    }

    fn cell_boxes(&self, cell: usize) -> &[u32] {
        self.ix.cells.cell(cell)
    }

    fn locate_mixed(&self, p: Point, c: usize, r: usize) -> Location {
        let cls = self.classifier;
        let tol = cls.abs_tol();
        let all = cls.boxes().boxes();
        if cls.boxes().is_critical_x(p.x, tol) {
            return cls.fallback(p).0;
        }
        let n = self.ix.n;
        if self
            .cell_boxes(c * n + r)
            .iter()
            .any(|&b| all[(b & !VERTICAL_FLAG) as usize].is_near(p, tol))
        {
            return Location::Boundary;
        }
        // Nearest uniform cell below in this column; below the grid everything is outside.
        let mut odd = false;
        let mut first = 0;
        for k in (0..r).rev() {
            let s = self.ix.state[c * n + k];
            if s != MIXED {
                odd = s == INSIDE;
                first = k + 1;
                break;
            }
        }
        let mut seen: SmallVec<[u32; 32]> = (first..=r)
            .flat_map(|row| self.cell_boxes(c * n + row).iter().copied())
            .filter(|&b| b & VERTICAL_FLAG == 0)
            .collect();
        seen.sort_unstable();
        seen.dedup();
        // No box is near p (checked above), so inRS2's per-box test reduces to the crossing.
        let crossings = seen
            .iter()
            .filter(|&&b| all[b as usize].crosses_below(p))
            .count();
        if odd ^ (crossings % 2 == 1) {
            Location::Inside
        } else {
            Location::Outside
        }
    }

    /// Locations of a stream of points, lazily: nothing is held but the index.
    pub fn locate_iter<I>(&'a self, points: I) -> impl Iterator<Item = Location> + 'a
    where
        I: IntoIterator<Item = Point>,
        I::IntoIter: 'a,
    {
        points.into_iter().map(move |p| self.locate_point(p))
    }
}

impl Locate for PointLocator<'_> {
    /// The location of one point (same as [`Method::InRS2`]).
    fn locate(&self, p: Point) -> Location {
        self.locate_point(p)
    }
}

/// High bit of a registered box index: the box is vertical (constant x).
const VERTICAL_FLAG: u32 = 1 << 31;
