//! The coverage of a domain on a grid: preparation, row bands and whole grids.

use std::ops::Range;
use std::sync::Mutex;

use rs_boxes::{BoxOptions, MonotoneBoxes};
use rs_contain::{FillRule, fill_nesting};
use rs_spline::{BoundingBox, Domain};

use crate::arc::Arc;
use crate::band::{Band, BandOut, BoundaryOut};
use crate::in_order::{InOrder, in_order};
use crate::{CellGrid, CoverageArray, CoverageError, CoverageOptions, CoverageSlices};

/// Most cells one call computes ([`GridCoverage::all`], [`GridCoverage::rows`],
/// [`cell_coverage`]): `2^28`, 2 GiB of fractions. Larger grids are computed in row bands
/// ([`GridCoverage::bands`]).
pub const MAX_CELLS: usize = 1 << 28;

/// The coverage of a band of rows `rows` of a grid with `nx` columns (all rows for a whole
/// grid). Arrays are row-major, the band's first row first: entry `(r, i)` is column `i` of
/// row `rows.start + r`, the cell `[x_i, x_{i+1}] x [y_j, y_{j+1}]` with `j = rows.start + r`.
///
/// Revolved ([`CoverageOptions::axisymmetric`], radius `r = |x|` about the y axis, `|y|`
/// about the x axis), a cell stands for the ring it sweeps: its fraction is the covered
/// volume of the ring over the ring's volume, `int int r dA / int int_cell r dA`; its
/// centroid the covered part's centroid weighted by `r` (`int int x r dA / int int r dA`,
/// likewise `y`: the meridian-plane centroid of the revolved part); a face parallel to the
/// axis sweeps a cylinder (its aperture is the covered fraction of its length, as planar),
/// a face across the axis an annulus (the covered fraction of its area, weighted by `r`).
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Coverage {
    /// The grid's rows this coverage holds.
    pub rows: Range<usize>,
    /// The grid's columns.
    pub nx: usize,
    /// `(rows, nx)`: the covered fraction of each cell's area, in `[0, 1]`.
    pub fractions: Vec<f64>,
    /// `(rows, nx)`: the centroid `[x, y]` of each cell's covered part (inside the cell),
    /// `[NaN, NaN]` where the fraction is 0; with [`CoverageOptions::centroids`].
    pub centroids: Option<Vec<[f64; 2]>>,
    /// `(rows, nx + 1)`: the covered fraction of each vertical face `x = x_i`,
    /// `y in [y_j, y_{j+1}]`; with [`CoverageOptions::apertures`].
    pub x_apertures: Option<Vec<f64>>,
    /// `(rows + 1, nx)`: the covered fraction of each horizontal face `y = y_j`,
    /// `x in [x_i, x_{i+1}]`, for the lines `rows.start ..= rows.end` (a band shares its
    /// first and last line with the bands below and above); with
    /// [`CoverageOptions::apertures`].
    pub y_apertures: Option<Vec<f64>>,
    /// `(rows, nx)`: the length of the boundary inside each cell, 0 where there is none;
    /// with [`CoverageOptions::boundary`]. A boundary running on a cell face belongs to
    /// the cell left of it (vertical faces) or below it (horizontal faces), as a face takes
    /// the value just to its right or above it.
    pub boundary_lengths: Option<Vec<f64>>,
    /// `(rows, nx)`: the centroid `[x, y]` of the boundary inside each cell (its arc
    /// length's), `[NaN, NaN]` where there is none; with [`CoverageOptions::boundary`].
    pub boundary_centroids: Option<Vec<[f64; 2]>>,
    /// `(rows, nx)`: the unit vector along the integral of the outward normal over the
    /// boundary inside each cell (`integral of n ds = (dy, -dx)` summed over its parts),
    /// pointing out of the covered part (into the body, as `AMReX`'s `bnorm`), `[NaN, NaN]`
    /// where there is none or the integral is 0; with [`CoverageOptions::boundary`].
    pub boundary_normals: Option<Vec<[f64; 2]>>,
    /// `(rows, nx + 1)`: the centroid `y` of each vertical face's covered part, `NaN` where
    /// it is empty; with [`CoverageOptions::face_centroids`].
    pub x_face_centroids: Option<Vec<f64>>,
    /// `(rows + 1, nx)`: the centroid `x` of each horizontal face's covered part, `NaN`
    /// where it is empty (lines as [`Coverage::y_apertures`]); with
    /// [`CoverageOptions::face_centroids`].
    pub y_face_centroids: Option<Vec<f64>>,
}

impl Coverage {
    /// The number of rows held.
    pub fn ny(&self) -> usize {
        self.rows.len()
    }

    /// The fraction of cell `(i, j)` (column `i`, grid row `j`); `None` outside the rows
    /// held.
    pub fn fraction(&self, i: usize, j: usize) -> Option<f64> {
        if i >= self.nx || !self.rows.contains(&j) {
            return None;
        }
        self.fractions
            .get((j - self.rows.start) * self.nx + i)
            .copied()
    }

    /// The arrays for `rows` of `nx` columns as a band expects them: zeros, the centroids
    /// `NaN` (see `BandOut`).
    pub(crate) fn zeroed(
        rows: Range<usize>,
        nx: usize,
        options: CoverageOptions,
    ) -> Result<Self, CoverageError> {
        let n = rows.len();
        let cells = n * nx;
        let nan_pairs = |on: bool| on.then(|| filled(cells, [f64::NAN; 2])).transpose();
        let faces = options.face_centroids;
        Ok(Self {
            fractions: zeros(cells)?,
            centroids: nan_pairs(options.centroids)?,
            x_apertures: options.apertures.then(|| zeros(n * (nx + 1))).transpose()?,
            y_apertures: options.apertures.then(|| zeros((n + 1) * nx)).transpose()?,
            boundary_lengths: options.boundary.then(|| zeros(cells)).transpose()?,
            boundary_centroids: nan_pairs(options.boundary)?,
            boundary_normals: nan_pairs(options.boundary)?,
            x_face_centroids: faces.then(|| filled(n * (nx + 1), f64::NAN)).transpose()?,
            y_face_centroids: faces.then(|| filled((n + 1) * nx, f64::NAN)).transpose()?,
            rows,
            nx,
        })
    }

    /// This coverage's arrays made those of `rows` of `nx` columns with `options` (their
    /// values left as they are: a band sets them, see `BandOut`): the allocations of a band
    /// already written reused for the next one.
    fn reshaped(
        mut self,
        rows: Range<usize>,
        nx: usize,
        options: CoverageOptions,
    ) -> Result<Self, CoverageError> {
        fn fit<T: Clone>(
            v: Option<Vec<T>>,
            on: bool,
            len: usize,
            value: T,
        ) -> Result<Option<Vec<T>>, CoverageError> {
            if !on {
                return Ok(None);
            }
            let mut v = v.unwrap_or_default();
            v.try_reserve_exact(len.saturating_sub(v.len()))
                .map_err(|_| out_of_memory::<T>(len))?;
            v.resize(len, value);
            Ok(Some(v))
        }
        let n = rows.len();
        let (cells, x_faces, y_faces) = (n * nx, n * (nx + 1), (n + 1) * nx);
        let nan = [f64::NAN; 2];
        let fractions = std::mem::take(&mut self.fractions);
        Ok(Self {
            fractions: fit(Some(fractions), true, cells, 0.0)?.unwrap_or_default(),
            centroids: fit(self.centroids, options.centroids, cells, nan)?,
            x_apertures: fit(self.x_apertures, options.apertures, x_faces, 0.0)?,
            y_apertures: fit(self.y_apertures, options.apertures, y_faces, 0.0)?,
            boundary_lengths: fit(self.boundary_lengths, options.boundary, cells, 0.0)?,
            boundary_centroids: fit(self.boundary_centroids, options.boundary, cells, nan)?,
            boundary_normals: fit(self.boundary_normals, options.boundary, cells, nan)?,
            x_face_centroids: fit(
                self.x_face_centroids,
                options.face_centroids,
                x_faces,
                f64::NAN,
            )?,
            y_face_centroids: fit(
                self.y_face_centroids,
                options.face_centroids,
                y_faces,
                f64::NAN,
            )?,
            rows,
            nx,
        })
    }

    /// The arrays, borrowed as [`CoverageSlices`] (pairs flattened).
    fn slices(&mut self) -> CoverageSlices<'_> {
        fn pairs(v: &mut Option<Vec<[f64; 2]>>) -> Option<&mut [f64]> {
            v.as_deref_mut().map(|p| p.as_flattened_mut())
        }
        CoverageSlices {
            fractions: &mut self.fractions,
            centroids: pairs(&mut self.centroids),
            x_apertures: self.x_apertures.as_deref_mut(),
            y_apertures: self.y_apertures.as_deref_mut(),
            boundary_lengths: self.boundary_lengths.as_deref_mut(),
            boundary_centroids: pairs(&mut self.boundary_centroids),
            boundary_normals: pairs(&mut self.boundary_normals),
            x_face_centroids: self.x_face_centroids.as_deref_mut(),
            y_face_centroids: self.y_face_centroids.as_deref_mut(),
        }
    }
}

impl Coverage {
    /// The values of `array` in row-major order (pairs flattened), `None` where this
    /// coverage does not hold it.
    pub fn values(&self, array: CoverageArray) -> Option<&[f64]> {
        match array {
            CoverageArray::Fractions => Some(&self.fractions),
            CoverageArray::Centroids => self.centroids.as_deref().map(<[_]>::as_flattened),
            CoverageArray::XApertures => self.x_apertures.as_deref(),
            CoverageArray::YApertures => self.y_apertures.as_deref(),
            CoverageArray::BoundaryLengths => self.boundary_lengths.as_deref(),
            CoverageArray::BoundaryCentroids => {
                self.boundary_centroids.as_deref().map(<[_]>::as_flattened)
            }
            CoverageArray::BoundaryNormals => {
                self.boundary_normals.as_deref().map(<[_]>::as_flattened)
            }
            CoverageArray::XFaceCentroids => self.x_face_centroids.as_deref(),
            CoverageArray::YFaceCentroids => self.y_face_centroids.as_deref(),
        }
    }

    /// The values of `array` moved out of this coverage (pairs flattened; the fractions
    /// leave an empty vector), `None` where it does not hold them.
    pub fn take_values(&mut self, array: CoverageArray) -> Option<Vec<f64>> {
        let pairs = |v: Option<Vec<[f64; 2]>>| v.map(Vec::into_flattened);
        match array {
            CoverageArray::Fractions => Some(std::mem::take(&mut self.fractions)),
            CoverageArray::Centroids => pairs(self.centroids.take()),
            CoverageArray::XApertures => self.x_apertures.take(),
            CoverageArray::YApertures => self.y_apertures.take(),
            CoverageArray::BoundaryLengths => self.boundary_lengths.take(),
            CoverageArray::BoundaryCentroids => pairs(self.boundary_centroids.take()),
            CoverageArray::BoundaryNormals => pairs(self.boundary_normals.take()),
            CoverageArray::XFaceCentroids => self.x_face_centroids.take(),
            CoverageArray::YFaceCentroids => self.y_face_centroids.take(),
        }
    }
}

impl<'a> CoverageSlices<'a> {
    /// The arrays cut into the outputs of bands of `band_rows` rows (at least one) of a grid
    /// of `ny` rows and `nx` columns, the last band lower and writing the top line's faces:
    /// those of [`band_range`]`(k, band_rows, ny)`. `fresh`: the arrays hold the bands'
    /// entry values (see [`BandOut`]).
    fn band_outs(
        self,
        (nx, ny): (usize, usize),
        band_rows: usize,
        fresh: bool,
    ) -> Vec<BandOut<'a>> {
        let band_rows = band_rows.clamp(1, ny.max(1));
        let cells = band_rows * nx;
        let faces = band_rows * (nx + 1);
        let pairs =
            |p: Option<&'a mut [f64]>| p.map(|p| p.as_chunks_mut::<2>().0.chunks_mut(cells));
        let mut fractions = self.fractions.chunks_mut(cells);
        let mut centroids = pairs(self.centroids);
        let mut x_apertures = self.x_apertures.map(|x| x.chunks_mut(faces));
        // Horizontal faces: the lines of each band's rows, and the grid's top line.
        let y_faces = |y: Option<&'a mut [f64]>| match y {
            Some(y) => {
                let (lines, top) = y.split_at_mut((ny * nx).min(y.len()));
                (Some(lines.chunks_mut(cells)), Some(top))
            }
            None => (None, None),
        };
        let (mut y_lines, mut y_top) = y_faces(self.y_apertures);
        let (mut yc_lines, mut yc_top) = y_faces(self.y_face_centroids);
        let mut x_centroids = self.x_face_centroids.map(|x| x.chunks_mut(faces));
        let mut boundary = match (
            self.boundary_lengths,
            pairs(self.boundary_centroids),
            pairs(self.boundary_normals),
        ) {
            (Some(l), Some(c), Some(n)) => Some((l.chunks_mut(cells), c, n)),
            _ => None,
        };
        let bands = ny.div_ceil(band_rows);
        let mut outs = Vec::with_capacity(bands);
        for k in 0..bands {
            let (Some(f), c, x, y) = (
                fractions.next(),
                centroids.as_mut().and_then(Iterator::next),
                x_apertures.as_mut().and_then(Iterator::next),
                y_lines.as_mut().and_then(Iterator::next),
            ) else {
                break;
            };
            let last = k + 1 == bands;
            outs.push(BandOut {
                fractions: f,
                centroids: c,
                x_apertures: x,
                y_apertures: y,
                y_top: if last { y_top.take() } else { None },
                boundary: boundary.as_mut().and_then(|(l, c, n)| {
                    Some(BoundaryOut {
                        lengths: l.next()?,
                        centroids: c.next()?,
                        normals: n.next()?,
                    })
                }),
                x_face_centroids: x_centroids.as_mut().and_then(Iterator::next),
                y_face_centroids: yc_lines.as_mut().and_then(Iterator::next),
                y_top_centroids: if last { yc_top.take() } else { None },
                fresh,
            });
        }
        outs
    }
}

/// The error for an array of `len` values that cannot be had.
fn out_of_memory<T>(len: usize) -> CoverageError {
    CoverageError::OutOfMemory {
        bytes: len.saturating_mul(std::mem::size_of::<T>()),
    }
}

/// `len` zeros, or [`CoverageError::OutOfMemory`]. The size is reserved fallibly first; the
/// vector itself is `vec![0.0; len]`, which the system hands out zeroed (`calloc`): its pages
/// are touched only where a band writes, so cells the covered set never reaches cost nothing.
fn zeros(len: usize) -> Result<Vec<f64>, CoverageError> {
    let mut probe: Vec<f64> = Vec::new();
    probe
        .try_reserve_exact(len)
        .map_err(|_| out_of_memory::<f64>(len))?;
    drop(probe);
    Ok(vec![0.0; len])
}

/// A vector of `len` copies of `value`, or [`CoverageError::OutOfMemory`]. With the
/// `parallel` feature the (first-touch) writes are spread over rayon's threads.
fn filled<T: Clone + Send + Sync>(len: usize, value: T) -> Result<Vec<T>, CoverageError> {
    let mut v = Vec::new();
    v.try_reserve_exact(len)
        .map_err(|_| out_of_memory::<T>(len))?;
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        v.par_extend(rayon::iter::repeat_n(value, len));
    }
    #[cfg(not(feature = "parallel"))]
    v.resize(len, value);
    Ok(v)
}

/// A domain prepared for coverage on a grid: its boundary cut into monotone pieces, each with
/// the orientation of its loop that puts the filled set (even-odd or nonzero) on its left. Build once, then ask for the whole grid
/// ([`GridCoverage::all`]), for a band of rows ([`GridCoverage::rows`]) from any thread, or
/// for every band in order ([`GridCoverage::bands`]).
///
/// # Examples
///
/// ```
/// use rs_coverage::{CellGrid, CoverageOptions, GridCoverage};
/// use rs_spline::{circle, Domain, Point};
/// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let grid = CellGrid::uniform(-1.0, 1.0, 64, -1.0, 1.0, 64).unwrap();
/// let cover = GridCoverage::new(&d, grid).unwrap();
/// // Streaming: two bands of rows give the whole grid's values.
/// let whole = cover.all(CoverageOptions::DEFAULT).unwrap();
/// let low = cover.rows(0..20, CoverageOptions::DEFAULT).unwrap();
/// let high = cover.rows(20..64, CoverageOptions::DEFAULT).unwrap();
/// assert_eq!([low.fractions, high.fractions].concat(), whole.fractions);
/// ```
pub struct GridCoverage {
    grid: CellGrid,
    arcs: Vec<Arc>,
    /// The boundary's tight box (`None` without pieces kept): which side of an axis of
    /// revolution the domain lies on.
    extent: Option<BoundingBox>,
}

impl GridCoverage {
    /// Prepares `domain` for coverage on `grid` under the even-odd rule:
    /// [`GridCoverage::with_fill_rule`] with [`FillRule::EvenOdd`].
    ///
    /// # Errors
    /// As [`GridCoverage::with_fill_rule`].
    pub fn new(domain: &Domain, grid: CellGrid) -> Result<Self, CoverageError> {
        Self::with_fill_rule(domain, grid, FillRule::EvenOdd)
    }

    /// Prepares `domain` for coverage on `grid` under `rule`. Each loop's pieces are
    /// multiplied by its [`rs_contain::LoopNesting::boundary_sign`], which puts the filled set
    /// on their left; a loop that does not bound the filled set (sign 0: the inner of two
    /// nested loops of one orientation under [`FillRule::NonZero`]) is left out, so that the
    /// crossing parity of the loops kept (the apertures and the covered lengths) is the
    /// filled set's indicator. Exact for loops that do not cross each other; loops that do are
    /// refused.
    ///
    /// # Errors
    /// [`CoverageError::Domain`] for an open boundary (a loop that does not close, or a curve
    /// that falls apart at a break); [`CoverageError::Nesting`] when the loops' nesting does
    /// not decide the fill (loops that cross, a loop on another, or more than
    /// [`rs_contain::MAX_NESTED_LOOPS`] loops: [`rs_contain::fill_nesting`]);
    /// [`CoverageError::Boxes`] when a piece cannot be cut into monotone pieces.
    ///
    /// # Examples
    ///
    /// ```
    /// use rs_contain::FillRule;
    /// use rs_coverage::{CellGrid, CoverageOptions, GridCoverage};
    /// use rs_spline::{circle, Domain, Point};
    /// // Two counter-clockwise circles: nonzero fills the big disc, even-odd the ring.
    /// let c = |r: f64| circle(Point::new(0.0, 0.0), r).unwrap();
    /// let d = Domain::new(vec![c(2.0), c(1.0)]).unwrap();
    /// let grid = CellGrid::uniform(-0.5, 0.5, 1, -0.5, 0.5, 1).unwrap();
    /// let centre = |rule| {
    ///     let cover = GridCoverage::with_fill_rule(&d, grid.clone(), rule).unwrap();
    ///     cover.all(CoverageOptions::DEFAULT).unwrap().fractions[0]
    /// };
    /// assert_eq!(centre(FillRule::NonZero), 1.0);
    /// assert_eq!(centre(FillRule::EvenOdd), 0.0);
    /// ```
    pub fn with_fill_rule(
        domain: &Domain,
        grid: CellGrid,
        rule: FillRule,
    ) -> Result<Self, CoverageError> {
        domain.require_closed()?;
        let nesting = fill_nesting(domain).map_err(CoverageError::Nesting)?;
        // Outer boundaries counter-clockwise, holes clockwise: the filled set on the left.
        let signs: Vec<i64> = nesting.iter().map(|n| n.boundary_sign(rule)).collect();
        let boxes = MonotoneBoxes::new(domain, BoxOptions::DEFAULT.with_subdivisions(1))?;
        let arcs: Vec<Arc> = boxes
            .pieces()
            .iter()
            .filter(|p| signs[p.boundary_loop] != 0)
            .map(|p| Arc::new(p.clone(), signs[p.boundary_loop] as f64))
            .collect();
        // The pieces' tight box; a loop left out (sign 0) lies inside the filled set, within
        // the box of the loops kept.
        let extent = (!arcs.is_empty()).then(|| boxes.bounding_box());
        Ok(Self { grid, arcs, extent })
    }

    /// Checks that `options` can be computed: revolved, the domain and the grid each on one
    /// side of the axis, and neither boundary geometry nor face centroids (planar only); the
    /// cells neither so large nor so small that the moments of the outputs asked overflow or
    /// lose their precision.
    ///
    /// # Errors
    /// [`CoverageError::AcrossAxis`], [`CoverageError::PlanarOnly`],
    /// [`CoverageError::CellsOutOfRange`].
    pub fn check_options(&self, options: CoverageOptions) -> Result<(), CoverageError> {
        check_options(&self.grid, self.extent.as_ref(), options)
    }

    /// The grid.
    pub fn grid(&self) -> &CellGrid {
        &self.grid
    }

    /// The coverage of the grid's rows `rows` (`j0 .. j1`), with the horizontal faces of the
    /// lines `j0 ..= j1`. The work is `O(pieces + crossings of the boundary with the band's
    /// lines + cells of the band)`; the memory beyond the output is that of the band's
    /// crossings and one row. The values of a cell do not depend on the band it is computed
    /// in, bit for bit, also where the boundary passes through a grid vertex: a crossing with
    /// a vertical line is held between the piece's crossings with the horizontal lines on
    /// either side of it (its own when it passes through the vertex), which are the same
    /// solves in every band, and the walk takes the crossings in that order.
    ///
    /// # Errors
    /// [`CoverageError::BadRows`] for an empty range or one beyond the grid;
    /// [`CoverageError::TooManyCells`] beyond [`MAX_CELLS`];
    /// [`CoverageError::AcrossAxis`], [`CoverageError::PlanarOnly`],
    /// [`CoverageError::CellsOutOfRange`] ([`GridCoverage::check_options`]);
    /// [`CoverageError::OutOfMemory`].
    pub fn rows(
        &self,
        rows: Range<usize>,
        options: CoverageOptions,
    ) -> Result<Coverage, CoverageError> {
        self.rows_reusing(rows, options, None)
    }

    /// [`GridCoverage::rows`] in the arrays of `spare` (a band already consumed) when given.
    fn rows_reusing(
        &self,
        rows: Range<usize>,
        options: CoverageOptions,
        spare: Option<Coverage>,
    ) -> Result<Coverage, CoverageError> {
        let ny = self.grid.ny();
        if rows.start >= rows.end || rows.end > ny {
            return Err(CoverageError::BadRows {
                start: rows.start,
                end: rows.end,
                rows: ny,
            });
        }
        self.check_cells(rows.len())?;
        self.check_options(options)?;
        let nx = self.grid.nx();
        let fresh = spare.is_none();
        let mut out = match spare {
            Some(spare) => spare.reshaped(rows.clone(), nx, options)?,
            None => Coverage::zeroed(rows.clone(), nx, options)?,
        };
        // One band: the whole arrays.
        let shape = (nx, rows.len());
        if let Some(whole) = out.slices().band_outs(shape, rows.len(), fresh).pop() {
            self.cover(rows, options, whole);
        }
        Ok(out)
    }

    /// The rows of a band of [`GridCoverage::bands`] and [`GridCoverage::all`] with
    /// `options`: [`band_rows`] for this grid and rayon's threads (one thread without the
    /// `parallel` feature).
    pub fn band_rows(&self, options: CoverageOptions) -> usize {
        band_rows(self.grid.nx(), self.grid.ny(), options, threads())
    }

    /// The rows of a band streamed to a file with `options` ([`stream_band_rows`] for this
    /// grid and rayon's threads).
    pub fn stream_band_rows(&self, options: CoverageOptions) -> usize {
        stream_band_rows(self.grid.nx(), self.grid.ny(), options, threads())
    }

    /// Runs `consume` with the grid's bands of `band_rows` rows (the last one lower; 0 is
    /// taken as 1), in row order: `(rows, coverage)` with `coverage` as
    /// [`GridCoverage::rows`]`(rows, options)` gives it. Returns what `consume` returns.
    ///
    /// The bands are computed on the calling thread and rayon's pool while `consume` takes
    /// them, at most `2 x threads` of them ahead of the one it takes next (fewer for bands of
    /// more than [`BAND_BYTES`], so that those ahead hold at most `2 x threads x BAND_BYTES`;
    /// at least one), so memory holds a few bands whatever the grid's size: stream a grid larger than [`MAX_CELLS`] (or than
    /// memory) to a file band by band. The bands' values are those of one band, or of
    /// [`GridCoverage::all`], bit for bit, whatever the bands' height. When `consume` returns
    /// early (dropping the
    /// iterator), the bands being computed are finished and no more are started. The
    /// iterator lives in `consume` because the bands are computed by rayon jobs that borrow
    /// the coverage (as `std::thread::scope` lends its scope).
    ///
    /// A band's error ([`CoverageError::TooManyCells`] for bands of more than [`MAX_CELLS`]
    /// cells, [`CoverageError::OutOfMemory`]) comes in its place; the bands after it are still
    /// computed if `consume` asks for them.
    ///
    /// # Examples
    ///
    /// ```
    /// use rs_coverage::{CellGrid, CoverageOptions, GridCoverage};
    /// use rs_spline::{circle, Domain, Point};
    /// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
    /// let grid = CellGrid::uniform(-1.0, 1.0, 64, -1.0, 1.0, 50).unwrap();
    /// let cover = GridCoverage::new(&d, grid).unwrap();
    /// let options = CoverageOptions::DEFAULT;
    /// let mut fractions = Vec::new();
    /// let rows = cover.bands(16, options, |bands| {
    ///     let mut rows = Vec::new();
    ///     for (range, band) in bands {
    ///         fractions.extend(band.unwrap().fractions); // or write it to a file
    ///         rows.push(range);
    ///     }
    ///     rows
    /// });
    /// assert_eq!(rows, [0..16, 16..32, 32..48, 48..50]);
    /// assert_eq!(fractions, cover.all(options).unwrap().fractions);
    /// ```
    pub fn bands<T>(
        &self,
        band_rows: usize,
        options: CoverageOptions,
        consume: impl FnOnce(Bands<'_>) -> T,
    ) -> T {
        let (nx, ny) = (self.grid.nx(), self.grid.ny());
        let band_rows = band_rows.clamp(1, ny);
        // Bands handed back by the consumer ([`Bands::recycle`]): their arrays hold the next
        // bands, so that a grid streamed to a file reuses a few bands' memory instead of
        // taking (and faulting in) new pages for every band.
        let spares: Mutex<Vec<Coverage>> = Mutex::new(Vec::new());
        let compute = |k: usize| {
            let rows = band_range(k, band_rows, ny);
            let spare = spares.lock().ok().and_then(|mut s| s.pop());
            (rows.clone(), self.rows_reusing(rows, options, spare))
        };
        // Two bands a thread ahead, and no more than that many bands of `BAND_BYTES` hold
        // (rows longer than a band's bytes: fewer bands ahead).
        let ahead = 2 * threads();
        let band_bytes = band_rows
            .saturating_mul(nx)
            .saturating_mul(bytes_per_cell(options));
        let window = ahead.min(ahead.saturating_mul(BAND_BYTES) / band_bytes.max(1));
        in_order(ny.div_ceil(band_rows), window, &compute, |items| {
            consume(Bands {
                items,
                spares: &spares,
                limit: window + 1,
            })
        })
    }

    /// The coverage of the whole grid: its bands of [`GridCoverage::band_rows`] rows, each
    /// computed as [`GridCoverage::rows`] computes it, in place, on rayon's pool: the values
    /// of [`GridCoverage::bands`] with [`GridCoverage::band_rows`] rows, bit for bit. In place
    /// the bands need no order, so the pool's work stealing balances them (bands differ in
    /// cost: [`GridCoverage::bands`]' in-order claiming left up to one band's time idle).
    ///
    /// # Errors
    /// [`CoverageError::TooManyCells`] beyond [`MAX_CELLS`] (use [`GridCoverage::bands`]);
    /// [`CoverageError::AcrossAxis`], [`CoverageError::PlanarOnly`],
    /// [`CoverageError::CellsOutOfRange`] ([`GridCoverage::check_options`]);
    /// [`CoverageError::OutOfMemory`].
    pub fn all(&self, options: CoverageOptions) -> Result<Coverage, CoverageError> {
        let ny = self.grid.ny();
        self.check_all(options)?;
        let mut out = Coverage::zeroed(0..ny, self.grid.nx(), options)?;
        self.cover_grid(options, out.slices(), true);
        Ok(out)
    }

    /// [`GridCoverage::all`] into the caller's arrays: the same values, bit for bit, written
    /// where they stay (a `NumPy` array, a reused buffer), each row's values set while the
    /// row is in cache instead of the whole array zeroed first. What the arrays hold on entry
    /// does not matter.
    ///
    /// # Errors
    /// [`CoverageError::Output`] unless `out` holds exactly the arrays `options` asks for,
    /// each of the length of its shape ([`CoverageArray::shape`] for the grid's `ny` rows);
    /// otherwise as [`GridCoverage::all`].
    ///
    /// # Examples
    ///
    /// ```
    /// use rs_coverage::{CellGrid, CoverageOptions, CoverageSlices, GridCoverage};
    /// use rs_spline::{circle, Domain, Point};
    /// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
    /// let grid = CellGrid::uniform(-1.0, 1.0, 64, -1.0, 1.0, 50).unwrap();
    /// let cover = GridCoverage::new(&d, grid).unwrap();
    /// let mut fractions = vec![f64::NAN; 64 * 50];
    /// let options = CoverageOptions::DEFAULT;
    /// cover.all_into(options, CoverageSlices::fractions(&mut fractions)).unwrap();
    /// assert_eq!(fractions, cover.all(options).unwrap().fractions);
    /// ```
    pub fn all_into(
        &self,
        options: CoverageOptions,
        mut out: CoverageSlices<'_>,
    ) -> Result<(), CoverageError> {
        let (nx, ny) = (self.grid.nx(), self.grid.ny());
        self.check_all(options)?;
        out.check(nx, ny, options)?;
        self.cover_grid(options, out, false);
        Ok(())
    }

    /// The whole grid's bands into `out` (checked), on rayon's pool; `fresh`: the arrays hold
    /// the bands' entry values (see [`BandOut`]).
    fn cover_grid(&self, options: CoverageOptions, out: CoverageSlices<'_>, fresh: bool) {
        let (nx, ny) = (self.grid.nx(), self.grid.ny());
        let band_rows = self.band_rows(options);
        let bands = out
            .band_outs((nx, ny), band_rows, fresh)
            .into_iter()
            .enumerate();
        let compute = |(k, o): (usize, BandOut<'_>)| {
            self.cover(band_range(k, band_rows, ny), options, o);
        };
        #[cfg(feature = "parallel")]
        {
            use rayon::prelude::*;
            // One band per task: a band's cost dwarfs a task's.
            bands
                .collect::<Vec<_>>()
                .into_par_iter()
                .with_max_len(1)
                .for_each(compute);
        }
        #[cfg(not(feature = "parallel"))]
        bands.for_each(compute);
    }

    /// Whether the whole grid can be computed with `options` ([`GridCoverage::all`]'s
    /// checks, before any array is made): a front end allocating the arrays itself asks first.
    ///
    /// # Errors
    /// [`CoverageError::TooManyCells`] beyond [`MAX_CELLS`]; [`CoverageError::AcrossAxis`],
    /// [`CoverageError::PlanarOnly`] ([`GridCoverage::check_options`]).
    pub fn check_all(&self, options: CoverageOptions) -> Result<(), CoverageError> {
        self.check_cells(self.grid.ny())?;
        self.check_options(options)
    }

    fn check_cells(&self, rows: usize) -> Result<(), CoverageError> {
        check_cells(&self.grid, rows)
    }

    /// The one computation of a band: the rows `rows` with `options` into `out` (see
    /// [`BandOut`] for its values on entry).
    fn cover(&self, rows: Range<usize>, options: CoverageOptions, out: BandOut<'_>) {
        Band {
            xs: self.grid.x_edges(),
            ys: self.grid.y_edges(),
            rows,
            moments: options.moments(),
            vertical_faces: options.apertures || options.face_centroids,
            boundary: options.boundary,
            axis: options.axisymmetric,
        }
        .cover(&self.arcs, out);
    }
}

/// The bands of a grid in row order, from [`GridCoverage::bands`]: `(rows, coverage)`.
pub struct Bands<'a> {
    items: InOrder<'a, (Range<usize>, Result<Coverage, CoverageError>)>,
    spares: &'a Mutex<Vec<Coverage>>,
    /// Most spares kept (the bands that can be in flight).
    limit: usize,
}

impl Bands<'_> {
    /// Hands a band back once consumed (written out): its arrays hold a band still to be
    /// computed, whose values are those of a new band bit for bit. Optional; a band not
    /// handed back is freed as usual.
    pub fn recycle(&self, band: Coverage) {
        if let Ok(mut spares) = self.spares.lock()
            && spares.len() < self.limit
        {
            spares.push(band);
        }
    }
}

impl Iterator for Bands<'_> {
    type Item = (Range<usize>, Result<Coverage, CoverageError>);

    fn next(&mut self) -> Option<Self::Item> {
        self.items.next()
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        self.items.size_hint()
    }
}

impl ExactSizeIterator for Bands<'_> {}

/// [`GridCoverage::check_options`] for a domain whose pieces span `extent` (`None`: no
/// piece, an empty region) on `grid`.
pub(crate) fn check_options(
    grid: &CellGrid,
    extent: Option<&BoundingBox>,
    options: CoverageOptions,
) -> Result<(), CoverageError> {
    check_moment_range(grid, options)?;
    let Some(axis) = options.axisymmetric else {
        return Ok(());
    };
    if options.boundary || options.face_centroids {
        return Err(CoverageError::PlanarOnly {
            what: if options.boundary {
                "the boundary's lengths, centroids and normals"
            } else {
                "face centroids"
            },
        });
    }
    // The coordinate that is the radius.
    let radius = axis.other();
    let span = |b: &BoundingBox| (b.min.coord(radius), b.max.coord(radius));
    let (g0, g1) = span(&grid.bounding_box());
    if g0 < 0.0 && g1 > 0.0 {
        return Err(CoverageError::AcrossAxis {
            what: "grid",
            axis,
            low: g0,
            high: g1,
        });
    }
    if let Some((d0, d1)) = extent.map(span)
        && d0 < 0.0
        && d1 > 0.0
    {
        return Err(CoverageError::AcrossAxis {
            what: "domain",
            axis,
            low: d0,
            high: d1,
        });
    }
    Ok(())
}

/// The largest power of two the moments behind a cell's outputs may reach: headroom of
/// `2^23` below `f64::MAX` for the sums of a cell's parts.
const MOMENT_MAX_EXPONENT: f64 = 1000.0;
/// The least: below `2^-970 = f64::MIN_POSITIVE / eps` subnormal rounding (`2^-1074`) is more
/// than `eps^2` of the value.
const MOMENT_MIN_EXPONENT: f64 = -970.0;

/// [`CoverageError::CellsOutOfRange`] where `options` ask for outputs whose moments, for the
/// sizes of `grid`'s cells, would overflow or fall among the subnormal numbers (a silent
/// `NaN` or a wrong value, not an error, before this check). With `s` a cell's side and `r`
/// the grid's largest radius, the moments grow like `s^3` for planar centroids (the first
/// moments of a covered part), `r s^2` for revolved fractions (the revolved volume) and
/// `r s^3` and `s^4` for revolved centroids; the fractions, apertures, boundary and face
/// outputs of planar cells like `s^2` at most, within range for every grid
/// ([`CellGrid::new`] refuses cells whose area underflows; edges are at most `1e150`). So
/// planar centroids need cells from about `1e-97` to `1e100` across; revolved volumes and
/// centroids tighter bounds, by the radius.
fn check_moment_range(grid: &CellGrid, options: CoverageOptions) -> Result<(), CoverageError> {
    let (smallest, largest) = grid.cell_sides();
    let (lo, hi) = (smallest.log2(), largest.log2());
    let radius = options.axisymmetric.map(|axis| {
        let b = grid.bounding_box();
        let r = axis.other();
        b.min.coord(r).abs().max(b.max.coord(r).abs()).max(largest)
    });
    let log_r = radius.map_or(0.0, f64::log2);
    // (what, the largest moment's log2, the smallest one's)
    let needs = match (options.axisymmetric.is_some(), options.centroids) {
        (false, false) => return Ok(()),
        (false, true) => ("centroids", 3.0 * hi, 3.0 * lo),
        (true, false) => ("revolved fractions", log_r + 2.0 * hi, 3.0 * lo),
        (true, true) => (
            "revolved centroids",
            (log_r + 2.0 * hi).max(log_r + 3.0 * hi).max(4.0 * hi),
            (3.0 * lo).min(4.0 * lo),
        ),
    };
    let (what, top, bottom) = needs;
    if top > MOMENT_MAX_EXPONENT || bottom < MOMENT_MIN_EXPONENT {
        return Err(CoverageError::CellsOutOfRange {
            what,
            smallest,
            largest,
            radius: radius.unwrap_or(0.0),
            overflow: top > MOMENT_MAX_EXPONENT,
        });
    }
    Ok(())
}

/// [`CoverageError::TooManyCells`] for `rows` rows of `grid` beyond [`MAX_CELLS`].
pub(crate) fn check_cells(grid: &CellGrid, rows: usize) -> Result<(), CoverageError> {
    let columns = grid.nx();
    if rows.checked_mul(columns).is_none_or(|c| c > MAX_CELLS) {
        return Err(CoverageError::TooManyCells {
            rows,
            columns,
            limit: MAX_CELLS,
        });
    }
    Ok(())
}

/// Output bytes a band holds ([`band_rows`]): 8 MiB, `2^20` cells of fractions alone.
pub const BAND_BYTES: usize = 8 << 20;

/// The rows of each band of a grid of `nx` columns and `ny` rows computed with `options` on
/// `threads` threads: the one rule by which [`GridCoverage::all`], [`GridCoverage::bands`]
/// and the front ends (`inrs fractions`, the blocks of `inrs.dask.cell_fractions`) cut a grid.
///
/// Rows of about [`BAND_BYTES`] of output (8 bytes a cell for the fraction, 16 more for the
/// centroid, about 16 more for the faces), at least one, and no more than
/// `ceil(ny / (4 threads))`, so that every thread has about four bands to take when the grid
/// has the rows (each band walks every piece of the boundary, so more bands cost more).
///
/// # Examples
///
/// ```
/// use rs_coverage::{CoverageOptions, band_rows};
/// let fractions = CoverageOptions::DEFAULT;
/// assert_eq!(band_rows(4096, 4096, fractions, 2), 256); // 2^20 cells
/// assert_eq!(band_rows(1024, 1024, fractions, 4), 64); // four bands a thread
/// ```
pub fn band_rows(nx: usize, ny: usize, options: CoverageOptions, threads: usize) -> usize {
    let by_size = BAND_BYTES / bytes_per_cell(options) / nx.max(1);
    let by_threads = ny.div_ceil(threads.max(1).saturating_mul(4));
    by_size.min(by_threads).max(1)
}

/// Output bytes a band streamed to a file holds ([`stream_band_rows`]): 512 KiB, `2^16`
/// cells of fractions alone.
pub const STREAM_BAND_BYTES: usize = 1 << 19;

/// Rows of about [`STREAM_BAND_BYTES`] of output (at least one, at most [`band_rows`]): the
/// band height for [`GridCoverage::bands`] writing a grid out. The few bands computed ahead
/// of the one written then stay small, and bands handed back ([`Bands::recycle`]) hold the
/// later ones in memory already paged in: at 2048^2 the fractions of the unit disc streamed
/// to a file took 1,000 page faults instead of 6,900 and 21 instead of 36 ms of CPU (bands of
/// 32 rows against 256, recycled). The values do not depend on the bands' height.
///
/// # Examples
///
/// ```
/// use rs_coverage::{CoverageOptions, stream_band_rows};
/// let fractions = CoverageOptions::DEFAULT;
/// assert_eq!(stream_band_rows(2048, 2048, fractions, 2), 32); // 2^16 cells
/// assert_eq!(stream_band_rows(1 << 20, 8, fractions, 2), 1);
/// ```
pub fn stream_band_rows(nx: usize, ny: usize, options: CoverageOptions, threads: usize) -> usize {
    let by_size = STREAM_BAND_BYTES / bytes_per_cell(options) / nx.max(1);
    by_size.clamp(1, band_rows(nx, ny, options, threads))
}

/// Output bytes per cell: 8 for the fraction, 16 for the centroid, about 16 for the faces'
/// apertures and 16 for their centroids, 40 for the boundary.
fn bytes_per_cell(options: CoverageOptions) -> usize {
    let on = |b: bool, bytes: usize| if b { bytes } else { 0 };
    8 + on(options.centroids, 16)
        + on(options.apertures, 16)
        + on(options.face_centroids, 16)
        + on(options.boundary, 40)
}

/// Band `k` of the bands of `band_rows` rows (at least one) of a grid of `ny` rows: the one
/// way the grid is cut.
pub(crate) fn band_range(k: usize, band_rows: usize, ny: usize) -> Range<usize> {
    let j0 = k.saturating_mul(band_rows).min(ny);
    j0..j0.saturating_add(band_rows).min(ny)
}

/// The threads bands are computed on: rayon's, or one without the `parallel` feature.
pub(crate) fn threads() -> usize {
    #[cfg(feature = "parallel")]
    return rayon::current_num_threads();
    #[cfg(not(feature = "parallel"))]
    1
}

/// The coverage of the whole `grid` by `domain` (even-odd fill): [`GridCoverage::new`] then
/// [`GridCoverage::all`]. For the nonzero rule, [`GridCoverage::with_fill_rule`].
///
/// # Errors
/// As [`GridCoverage::new`] and [`GridCoverage::all`].
///
/// # Examples
///
/// ```
/// use rs_coverage::{cell_coverage, CellGrid, CoverageOptions};
/// use rs_spline::{polyline, Domain, Point};
/// // The square [0.5, 1.5]^2 on the unit grid [0, 2]^2: a quarter of each cell.
/// let pts = [(0.5, 0.5), (1.5, 0.5), (1.5, 1.5), (0.5, 1.5), (0.5, 0.5)]
///     .map(|(x, y)| Point::new(x, y));
/// let d = Domain::new(vec![polyline(&pts).unwrap()]).unwrap();
/// let grid = CellGrid::uniform(0.0, 2.0, 2, 0.0, 2.0, 2).unwrap();
/// let c = cell_coverage(&d, &grid, CoverageOptions::DEFAULT.with_centroids(true)).unwrap();
/// assert!(c.fractions.iter().all(|f| (f - 0.25).abs() < 1e-15));
/// let [x, y] = c.centroids.unwrap()[0]; // cell (0, 0): the part [0.5, 1]^2
/// assert!((x - 0.75).abs() < 1e-15 && (y - 0.75).abs() < 1e-15);
/// ```
pub fn cell_coverage(
    domain: &Domain,
    grid: &CellGrid,
    options: CoverageOptions,
) -> Result<Coverage, CoverageError> {
    GridCoverage::new(domain, grid.clone())?.all(options)
}
