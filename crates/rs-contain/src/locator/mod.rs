//! Sub-linear point location: a uniform grid of cells with precomputed locations over the
//! monotone boxes, answering almost every point in constant time with the same result as inRS2.

use std::borrow::Cow;

use rs_spline::Point;

use crate::{Classifier, Location, PointQuery, PointSource};

mod index;
pub use index::LocatorIndex;
use index::*;

mod build;

/// Coarse state and fine entry: every point of the block or cell is outside.
const OUTSIDE: u8 = 0;
/// Coarse state and fine entry: every point of the block or cell is inside.
const INSIDE: u8 = 1;

/// The location a coarse state or a uniform fine entry stands for: [`Location::Boundary`]
/// marks a refined block, whose points are decided one by one (a real boundary point only ever
/// comes from that decision).
const STATE_LOCATION: [Location; 4] = [
    Location::Outside,
    Location::Inside,
    Location::Boundary,
    Location::Boundary,
];

/// Default grid resolution: cells per side of the bounding box. Chosen by measurement
/// (`cargo xtask bench --sweep`, docs/BENCHMARKS.md): on the paper's domains 512 x 512 cells
/// leave about 1% of uniformly spread points in boundary cells and locate 10^6 points as fast
/// as 1024 x 1024 (the two-level tables stay in cache), with a build four times cheaper.
pub const DEFAULT_GRID_CELLS: usize = 512;

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
/// A uniform `n x n` grid covers the bounding box grown by the tolerance. Each monotone box
/// is registered in every cell near its curve (within the boundary tolerance): a box that
/// spans a couple of cells as itself, a longer one as the parts it is halved into until each
/// spans a couple of cells, each with its own chord band ([`rs_boxes::ChordBand`]), narrow
/// where the box's is wide. A cell that
/// meets no box contains no boundary point, so all of its points share one location: for each
/// column, the first cell of every run of such cells gets inRS2's location of its centre and
/// the run inherits it. That location is found walking the column upwards: inRS2's parity at
/// the run below, changed by the boxes registered in the occupied cells between whose
/// crossing test (inRS2's own) differs at the two centres. The others are *mixed*.
///
/// Since a column's states come from its own walk, the grid is built in *strips* of 32
/// columns, each from the boxes that reach it (a box's parts far from the strip are not
/// halved further), each when a query first falls in it: [`Classifier::locator`]'s first
/// answer costs about one strip, not the grid. Until a strip is built its blocks read "not
/// built", which sends a query to the strip (built then, once, whichever thread asks first).
/// When the last strip is built, its call copies the strips' tables into the flat two-level
/// tables below, which queries read from then on. [`PointLocator::new`] builds every strip.
///
/// The grid is stored in two levels, so that the table a query reads first stays in the
/// processor's first-level cache: a coarse grid of `8 x 8` blocks of cells, a byte per block
/// (all outside, all inside, or refined: about 4 KiB for the default 512 x 512 cells, plus a
/// ring of outside cells round the grid), and, for the refined blocks only, one entry per cell (outside, inside, or the index of a mixed-cell
/// record). A mixed-cell record holds what its points need, precomputed: the parity of the
/// nearest uniform cell below in the same column, the boxes and parts registered in the cell,
/// the distinct non-vertical boxes and parts registered between that uniform cell and this
/// one, and the critical abscissas within the tolerance of the cell's column (a point's own
/// abscissa is searched for among these only).
///
/// A query then costs:
/// - outside the grown bounding box, or in a uniform block: one lookup, without a branch;
/// - in a refined block: a second lookup;
/// - in a mixed cell: the boundary test against the cell's boxes and parts, then the parity
///   below plus the crossings of the vertical ray with the record's column items. A part's
///   band decides almost every point without a solve; the few within a band are decided by
///   the box's own test (one bracketed solve at most). Points on a critical abscissa take
///   inRS2's fallback (horizontal ray, winding number).
///
/// Results are identical to [`Method::InRS2`](crate::Method::InRS2): uniform cells are classified by inRS2 itself and
/// no box below the reference cell can reach it, so the crossings counted above it are exactly
/// those inRS2 counts there. A box near a point has a part registered in the point's cell whose
/// band may be near it, and then the box's own test decides; of a box's parts exactly one spans
/// the point's abscissa (they share out the box's half-open range), and its band answers only
/// where it is beyond the rounding of the halving from the point, else the box's own test does.
///
/// # Cost
/// Build: the boxes' registrations (each box only in the cells near its curve: its piece is
/// halved until each part spans a couple of cells; a box that reaches two strips is halved
/// from each), a walk up each column (the runs' states from the boxes of the occupied cells
/// between them), and a walk over the `(n / 8)^2` blocks; no table of all
/// `n^2` cells is made, so the work grows with the boundary's length in cells and the number
/// of blocks. Memory: a byte per block of the coarse table, 256 bytes per refined block, the
/// mixed-cell records with their item lists, and the parts' chord bands (96 bytes each, at
/// least one part per box), which grow with the number of boxes and the boundary's length in
/// cells; the registrations themselves are dropped after the build
/// (timings: `cargo xtask bench`, reported in the README). Worst case per query: a mixed cell
/// in a column that is mixed all the way down, `O(N)` for `N` items in that column; fine grids
/// and refined boxes keep it small.
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
/// assert_eq!(loc.locate_all(&pts), c.locate_all_with(Method::InRS2, &pts));
/// assert_eq!(loc.locate_all(&pts), vec![Location::Inside, Location::Inside, Location::Boundary]);
/// ```
#[derive(Clone, Debug)]
pub struct PointLocator<'a> {
    classifier: &'a Classifier,
    ix: Cow<'a, LocatorIndex>,
}

impl Classifier {
    /// The grid locator with the default options, its index made on the first call and kept:
    /// each strip of its grid (a column of blocks) is built when a query first needs it, so a
    /// few queries pay for the strips they fall in, not for the whole grid.
    pub fn locator(&self) -> PointLocator<'_> {
        let index = self
            .grid
            .get_or_init(|| LocatorIndex::build(self, LocatorOptions::default().cells));
        PointLocator::with_index(self, index)
    }
}

impl<'a> PointLocator<'a> {
    /// Builds the index, all of it (the locator of [`Classifier::locator`] builds each strip
    /// of the grid when a query first needs it).
    pub fn new(classifier: &'a Classifier, options: LocatorOptions) -> Self {
        let ix = LocatorIndex::build(classifier, options.cells);
        ix.built_strips(classifier).for_each(drop);
        Self {
            classifier,
            ix: Cow::Owned(ix),
        }
    }

    /// A locator over `classifier` with an index built before for it.
    pub(crate) fn with_index(classifier: &'a Classifier, index: &'a LocatorIndex) -> Self {
        Self {
            classifier,
            ix: Cow::Borrowed(index),
        }
    }

    /// The grid resolution (cells per side).
    pub fn cells(&self) -> usize {
        self.ix.n
    }

    /// The grid's strips, each built now if it was not yet.
    fn strips(&self) -> impl Iterator<Item = &Strip> {
        self.ix.built_strips(self.classifier)
    }

    /// Fraction of cells that are mixed (meet a box). Builds the whole grid.
    pub fn mixed_fraction(&self) -> f64 {
        let mixed: usize = self.strips().map(|s| s.mixed_cells).sum();
        mixed as f64 / (self.ix.n * self.ix.n) as f64
    }

    /// Number of (item, cell) incidences registered while building (an item is a box or a
    /// part of one; a part that spans two strips counts in each). Builds the whole grid.
    pub fn incidences(&self) -> usize {
        self.strips().map(|s| s.incidences).sum()
    }

    /// Bytes held by the index (tables, records, item lists and the parts' chord bands).
    /// Builds the whole grid.
    pub fn memory_bytes(&self) -> usize {
        let strips: usize = self
            .strips()
            .map(|s| {
                s.coarse.len()
                    + 4 * (s.block_start.len() + s.fine.len())
                    + std::mem::size_of::<MixedCell>() * s.records.len()
                    + 4 * (s.near_items.len() + s.column_items.len())
                    + (std::mem::size_of::<rs_boxes::ChordBand>() + 4) * s.parts.bands.len()
            })
            .sum();
        let ix = &self.ix;
        strips
            + ix.coarse.len()
            + 4 * (ix.critical.len() * 2 + ix.strip_box_start.len() + ix.strip_boxes.len())
            + std::mem::size_of::<std::sync::OnceLock<Strip>>() * ix.strips.len()
            + ix.complete.get().map_or(0, Complete::memory_bytes)
    }

    /// Strip `s` of the grid, built now if it was not yet.
    #[inline]
    fn strip(&self, s: usize) -> &Strip {
        self.ix.strip(self.classifier, s)
    }

    /// The location of one point (same as [`Method::InRS2`](crate::Method::InRS2)).
    fn locate_point(&self, p: Point) -> Location {
        let state = match self.ix.complete() {
            Some(tables) => tables.coarse_state(p),
            None => self.ix.filling().coarse_state(p),
        };
        match STATE_LOCATION[state] {
            Location::Boundary => self.locate_refined(p),
            uniform => uniform,
        }
    }

    /// A point of a refined (or not yet built) block: its cell's entry in its strip, then the
    /// mixed-cell record if any.
    fn locate_refined(&self, p: Point) -> Location {
        let (c, r) = self.ix.lookup.cell(p);
        let strip = self.strip(strip_of_column(c));
        let entry = strip.entry(c, r);
        if entry < FIRST_RECORD {
            return STATE_LOCATION[entry as usize];
        }
        self.locate_mixed(p, strip, entry)
    }

    /// A point of a mixed cell, whose fine entry is `entry`: the boundary test against the
    /// cell's items, then the winding number below plus the signed crossings of the record's
    /// column items.
    fn locate_mixed(&self, p: Point, strip: &Strip, entry: u32) -> Location {
        let rec = &strip.records[(entry - FIRST_RECORD) as usize];
        let cls = self.classifier;
        if rec.by_inrs2 {
            return cls.classify_point_with_decision(p).0;
        }
        let tol = cls.abs_tol();
        let all = cls.boxes().boxes();
        let critical = rec.critical.0 as usize..rec.critical.1 as usize;
        if !critical.is_empty() && cls.boxes().is_critical_x_among(p.x, tol, critical) {
            return cls.location(cls.fallback(p).0);
        }
        let parts = &strip.parts;
        // A box near p has a part (or is an item itself) whose band may be near p, registered
        // in p's cell: the bands screen, the box's own test decides.
        let near = &strip.near_items[rec.near.0 as usize..rec.near.1 as usize];
        if near.iter().any(|&item| {
            let item = item & !VERTICAL_FLAG;
            parts.band(item).may_be_near(p, tol) && parts.owner(all, item).is_near(p, tol)
        }) {
            return Location::Boundary;
        }
        // No box is near p (checked above), so inRS2's per-box test reduces to the crossing,
        // which the one part of the box over p.x decides (the parts share out its abscissas),
        // by its band or else by the box's own test; its sign is its box's direction, which
        // the part's band keeps.
        let column = &strip.column_items[rec.column.0 as usize..rec.column.1 as usize];
        let crossings: i64 = column
            .iter()
            .map(|&item| {
                let band = parts.band(item);
                let crossed = band
                    .crossing_below(p)
                    .unwrap_or_else(|| parts.owner(all, item).crosses_below(p));
                if crossed { band.x_sign() } else { 0 }
            })
            .sum();
        cls.location(Some(i64::from(rec.winding_below) + crossings))
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

impl PointQuery<Location> for PointLocator<'_> {
    /// The location of one point (same as [`Method::InRS2`](crate::Method::InRS2)).
    fn value(&self, p: Point) -> Location {
        self.locate_point(p)
    }

    /// In chunks, while the chunk is in cache: the blocks of 256 points side by side (in
    /// floating point, which the compiler turns into vector instructions: copies for AVX-512
    /// and AVX2 beside the baseline one, picked at run time), then every point's block state
    /// by a branch-free lookup in the coarse table (the positions of points in refined blocks
    /// noted without a branch too), then those points' cell entries the same way (noting the
    /// points in mixed cells), then the points in mixed cells one by one.
    fn values_into<P: PointSource + ?Sized>(&self, points: &P, out: &mut [Location]) {
        assert_eq!(points.len(), out.len(), "one location per point");
        // The final table once the grid is built; the one being filled in before.
        match self.ix.complete() {
            Some(tables) => pulp::Arch::new().dispatch(LocateChunks {
                locator: self,
                tables,
                points,
                out,
            }),
            None => pulp::Arch::new().dispatch(LocateChunks {
                locator: self,
                tables: self.ix.filling(),
                points,
                out,
            }),
        }
    }

    /// Large tasks: the grid answers a point in a few nanoseconds.
    fn parallel_chunk(&self) -> usize {
        PARALLEL_TASK
    }
}

impl PointLocator<'_> {
    /// [`PointQuery::values_into`], inlined into each instruction set's copy.
    #[inline(always)]
    fn locate_chunks<G: GridView, P: PointSource + ?Sized>(
        &self,
        tables: Tables<G>,
        points: &P,
        out: &mut [Location],
    ) {
        let point = |i| points.point(i);
        const CHUNK: usize = 2048;
        let mut refined = [0u16; CHUNK];
        let mut entries = [0u32; CHUNK];
        // The column of each refined point's cell, for its strip if it is mixed.
        let mut columns = [0u16; CHUNK];
        let mut mixed = [0u16; CHUNK];
        // A slice is read in place; other sources decode each block of points into `decoded`.
        let slice = points.as_slice();
        let mut decoded = [Point::default(); LANES];
        for (c, out) in out.chunks_mut(CHUNK).enumerate() {
            let first = c * CHUNK;
            let mut k = 0;
            let (mut xs, mut ys, mut blocks) = ([0.0; LANES], [0.0; LANES], [0u64; LANES]);
            for (g, group) in out.chunks_mut(LANES).enumerate() {
                let base = g * LANES;
                let n = group.len();
                let group_points = match slice {
                    Some(all) => &all[first + base..first + base + n],
                    None => {
                        points.points_into(first + base, &mut decoded[..n]);
                        &decoded[..n]
                    }
                };
                for ((x, y), p) in xs.iter_mut().zip(&mut ys).zip(group_points) {
                    (*x, *y) = (p.x, p.y);
                }
                tables.lookup.blocks(&xs, &ys, &mut blocks);
                for (l, o) in group.iter_mut().enumerate() {
                    // `& 3` and `& (CHUNK - 1)` change nothing (a state is below 4, `k <= i`);
                    // they spare the bounds checks the compiler cannot drop. (Lanes past the
                    // group's end hold the blocks of stale coordinates and are not read.)
                    let state = tables.grid.state(blocks[l] as usize);
                    *o = STATE_LOCATION[state];
                    refined[k & (CHUNK - 1)] = (base + l) as u16;
                    // A refined block, or one whose strip is not built yet.
                    k += usize::from(state >= REFINED as usize);
                }
            }
            // The refined blocks' points: their fine entries without a branch, noting those
            // in mixed cells, then those one by one.
            let mut m = 0;
            for j in 0..k {
                let i = usize::from(refined[j]);
                let (c, r) = tables.lookup.cell(point(first + i));
                let entry = tables.grid.entry(c, r, |s| self.strip(s));
                entries[j] = entry;
                // A column is below 8192 (`GridFrame::MAX_CELLS`).
                columns[j] = c as u16;
                out[i] = STATE_LOCATION[entry.min(FIRST_RECORD) as usize];
                mixed[m & (CHUNK - 1)] = j as u16;
                m += usize::from(entry >= FIRST_RECORD);
            }
            for &j in &mixed[..m] {
                let i = usize::from(refined[usize::from(j)]);
                let strip = self.strip(strip_of_column(usize::from(columns[usize::from(j)])));
                out[i] = self.locate_mixed(point(first + i), strip, entries[usize::from(j)]);
            }
        }
    }
}

/// Points per parallel task.
const PARALLEL_TASK: usize = 1 << 16;

/// [`PointQuery::values_into`] as an operation `pulp` runs with the best instruction
/// set at hand.
struct LocateChunks<'l, 'a, G, P: ?Sized> {
    locator: &'l PointLocator<'a>,
    tables: Tables<G>,
    points: &'l P,
    out: &'l mut [Location],
}

impl<G: GridView, P: PointSource + ?Sized> pulp::WithSimd for LocateChunks<'_, '_, G, P> {
    type Output = ();
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        self.locator
            .locate_chunks(self.tables, self.points, self.out);
    }
}

/// High bit of a registered box index: the box is vertical (constant x).
const VERTICAL_FLAG: u32 = 1 << 31;

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::grid::GridFrame;
    use std::sync::atomic::Ordering;

    /// What `each(t)` returns on each of `threads` threads run at once, in thread order.
    fn on_threads<T: Send>(threads: usize, each: impl Fn(usize) -> T + Sync) -> Vec<T> {
        std::thread::scope(|scope| {
            let each = &each;
            let handles: Vec<_> = (0..threads).map(|t| scope.spawn(move || each(t))).collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        })
    }

    /// A locator whose strips are built by the queries that first need them, from several
    /// threads at once (the same strip asked for by many), answers as inRS2 does, point by
    /// point and in batches; once every strip is built its flat tables are made and give the
    /// same answers again; a fresh locator asked one point builds only that point's strip.
    #[test]
    fn strips_built_on_demand_by_concurrent_queries_answer_as_inrs2() {
        use crate::{ContainOptions, Locate, Method};
        for case in rs_testkit::fixtures() {
            let c = Classifier::new(&case.domain, ContainOptions::default()).unwrap();
            let b = c.outer();
            let pts = crate::baselines::halton_points(40_000, b.grown_by(0.05 * b.diagonal()));
            let expected = c.locate_all_with(Method::InRS2, &pts);
            let one = Classifier::new(&case.domain, ContainOptions::default()).unwrap();
            let _ = one.locator().locate(pts[7]);
            let ix = one.grid.get().unwrap();
            let built = ix.strips.iter().filter(|s| s.get().is_some()).count();
            assert_eq!(built, 1, "{}", case.name);
            assert!(ix.complete.get().is_none());
            let loc = c.locator();
            let got = on_threads(4, |t| {
                if t % 2 == 0 {
                    loc.locate_all(&pts)
                } else {
                    pts.iter().map(|&p| loc.locate(p)).collect()
                }
            });
            for g in &got {
                assert_eq!(g, &expected, "{}", case.name);
            }
            let ix = c.grid.get().unwrap();
            assert!(ix.strips.iter().all(|s| s.get().is_some()));
            assert!(ix.complete.get().is_some(), "{}", case.name);
            // Each strip built once, however many threads asked for it or helped.
            assert_eq!(ix.built.load(Ordering::Acquire), ix.strips.len());
            assert_eq!(loc.locate_all(&pts), expected, "{}", case.name);
        }
    }

    /// Threads whose points come in the same order (each asks for the strips in the same
    /// order, so each finds the others building the strip it needs and builds untaken ones
    /// meanwhile): every answer is inRS2's, each strip is built once, and the flat tables are
    /// made; a copy of a locator some of whose strips are built builds the rest itself.
    #[test]
    fn threads_asking_for_strips_in_the_same_order_build_each_once() {
        use crate::{ContainOptions, Locate, Method};
        for case in rs_testkit::fixtures() {
            let c = Classifier::new(&case.domain, ContainOptions::default()).unwrap();
            let b = c.outer();
            // Halton points: the same columns at the start of every thread's share.
            let pts = crate::baselines::halton_points(4_096, b.grown_by(0.05 * b.diagonal()));
            let expected = c.locate_all_with(Method::InRS2, &pts);
            for threads in [2, 3, 8] {
                let fresh = Classifier::new(&case.domain, ContainOptions::default()).unwrap();
                let loc = fresh.locator();
                let got = on_threads(threads, |_| loc.locate_all(&pts));
                assert!(
                    got.iter().all(|g| g == &expected),
                    "{} x{threads}",
                    case.name
                );
                let ix = fresh.grid.get().unwrap();
                assert_eq!(ix.built.load(Ordering::Acquire), ix.strips.len());
                assert!(ix.taken.iter().all(|t| t.load(Ordering::Acquire)));
                assert!(ix.complete.get().is_some(), "{}", case.name);
            }
            // A copy taken with one strip built: its other strips are not taken in it.
            let one = Classifier::new(&case.domain, ContainOptions::default()).unwrap();
            let _ = one.locator().locate(pts[0]);
            let copy = one.grid.get().unwrap().clone();
            let taken = copy
                .taken
                .iter()
                .filter(|t| t.load(Ordering::Acquire))
                .count();
            assert_eq!(taken, 1, "{}", case.name);
            let loc = PointLocator::with_index(&one, &copy);
            assert_eq!(loc.locate_all(&pts), expected, "{}", case.name);
        }
    }

    /// `Lookup::blocks` gives the block `Lookup::cell` and `Lookup::block` give, for points
    /// on cell edges, inside cells, off the grid, and not finite.
    #[test]
    fn blocks_side_by_side_equal_one_by_one() {
        let frame = GridFrame::new(
            rs_spline::BoundingBox {
                min: Point::new(-1.3, 0.2),
                max: Point::new(2.9, 5.0),
            },
            520,
        );
        let lookup = Lookup::new(&frame, 520usize.div_ceil(BLOCK));
        let (lo, hi) = (frame.bounding_box().min, frame.bounding_box().max);
        let mut points = Vec::new();
        for i in 0..=523 {
            for j in [0usize, 1, 7, 8, 9, 63, 64, 250, 511, 517, 519, 520, 521] {
                let t = |k: usize, a: f64, b: f64| a + (b - a) * k as f64 / 520.0;
                points.push(Point::new(t(i, lo.x, hi.x), t(j, lo.y, hi.y)));
                points.push(Point::new(t(j, lo.x, hi.x), t(i, lo.y, hi.y)));
                let nudge = |v: f64| f64::from_bits(v.to_bits() + 1);
                points.push(Point::new(nudge(t(i, lo.x, hi.x)), t(j, lo.y, hi.y)));
            }
        }
        for v in [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -1e300,
            1e300,
            0.0,
            -0.0,
        ] {
            points.push(Point::new(v, 1.0));
            points.push(Point::new(0.5, v));
        }
        let mut rng = rs_testkit::XorShift64::new(0x2545_f491_4f6c_dd1d);
        for _ in 0..20_000 {
            points.push(Point::new(rng.uniform(-2.0, 4.0), rng.uniform(-0.5, 5.5)));
        }
        for group in points.chunks(LANES) {
            let (mut xs, mut ys, mut got) = ([0.0; LANES], [0.0; LANES], [0u64; LANES]);
            for (l, p) in group.iter().enumerate() {
                (xs[l], ys[l]) = (p.x, p.y);
            }
            lookup.blocks(&xs, &ys, &mut got);
            for (l, &p) in group.iter().enumerate() {
                let (c, r) = lookup.cell(p);
                assert_eq!(got[l] as usize, lookup.block(c, r), "{p:?}");
            }
        }
    }
}
