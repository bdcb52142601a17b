//! Several materials on one grid: each material's coverage, later domains replacing earlier
//! ones ([`material_domains`]): the one entry point of the front ends for several domains.

use std::ops::Range;

use rs_contain::FillRule;
use rs_spline::Domain;

use crate::coverage::{
    Bands, Coverage, GridCoverage, band_range, band_rows, check_cells, check_options,
    stream_band_rows, threads,
};
use crate::{CellGrid, CoverageError, CoverageOptions, material_domains};

/// The coverage of a grid by several materials, in the order given: with replacement,
/// material `k` holds `D_k \ (D_{k+1} u ... u D_{n-1})` (a later domain replaces the earlier
/// ones in its cells, Axom's shaping rule), so that the fractions of a cell sum to at most 1
/// up to rounding; without it, each domain's own coverage (plain overlaps). The last material
/// (and every material without replacement) is its domain as given, under its fill rule: its
/// values are [`GridCoverage`]'s for that domain bit for bit.
///
/// # Examples
///
/// ```
/// use rs_contain::FillRule;
/// use rs_coverage::{CellGrid, CoverageOptions, MaterialCoverage};
/// use rs_spline::{circle, Domain, Point};
/// let disc = |x: f64| Domain::new(vec![circle(Point::new(x, 0.0), 1.0).unwrap()]).unwrap();
/// let (a, b) = (disc(-0.5), disc(0.5));
/// let grid = CellGrid::uniform(-2.0, 2.0, 8, -2.0, 2.0, 8).unwrap();
/// let domains = [(&a, FillRule::EvenOdd), (&b, FillRule::EvenOdd)];
/// let m = MaterialCoverage::new(&domains, grid, true).unwrap();
/// let c = m.all(CoverageOptions::DEFAULT).unwrap();
/// // The cell [0, 0.5] x [0, 0.5] lies in both discs: the second replaces the first.
/// let cell = 4 * 8 + 4;
/// assert!(c[0].fractions[cell] < 1e-15 && c[1].fractions[cell] == 1.0);
/// ```
pub struct MaterialCoverage {
    grid: CellGrid,
    /// Per material: its coverage, `None` where its region is empty.
    materials: Vec<Option<GridCoverage>>,
}

impl MaterialCoverage {
    /// Prepares the materials `domains` (each with its fill rule) on `grid`, replacing or not.
    ///
    /// # Errors
    /// A domain's own refusal (open or crossing loops: as [`GridCoverage::with_fill_rule`])
    /// as [`CoverageError::Material`] naming it; as [`material_domains`] with `replace` for
    /// the boundaries together (too many pairs of pieces, an intersection not found, a
    /// region that does not chain: [`CoverageError::Unchained`], as the material's).
    pub fn new(
        domains: &[(&Domain, FillRule)],
        grid: CellGrid,
        replace: bool,
    ) -> Result<Self, CoverageError> {
        let as_given = |k: usize, (d, rule): &(&Domain, FillRule)| {
            GridCoverage::with_fill_rule(d, grid.clone(), *rule)
                .map(Some)
                .map_err(|e| CoverageError::in_material(k, e))
        };
        let materials = match domains.split_last() {
            Some((last, earlier)) if replace && !earlier.is_empty() => {
                let regions = material_domains(domains, true)?;
                let mut m = regions
                    .iter()
                    .take(earlier.len())
                    .enumerate()
                    .map(|(k, r)| {
                        r.as_ref()
                            .map(|d| GridCoverage::new(d, grid.clone()))
                            .transpose()
                            .map_err(|e| CoverageError::in_material(k, e))
                    })
                    .collect::<Result<Vec<_>, _>>()?;
                m.push(as_given(earlier.len(), last)?);
                m
            }
            _ => domains
                .iter()
                .enumerate()
                .map(|(k, d)| as_given(k, d))
                .collect::<Result<_, _>>()?,
        };
        Ok(Self { grid, materials })
    }

    /// The number of materials.
    pub fn len(&self) -> usize {
        self.materials.len()
    }

    /// True without materials.
    pub fn is_empty(&self) -> bool {
        self.materials.is_empty()
    }

    /// The grid.
    pub fn grid(&self) -> &CellGrid {
        &self.grid
    }

    /// Material `k`'s coverage, `None` if its region is empty (or `k` is out of range).
    pub fn material(&self, k: usize) -> Option<&GridCoverage> {
        self.materials.get(k).and_then(Option::as_ref)
    }

    /// Checks `options` for every material ([`GridCoverage::check_options`]).
    ///
    /// # Errors
    /// As [`GridCoverage::check_options`]; a domain across the axis of revolution as
    /// [`CoverageError::Material`] naming it.
    pub fn check_options(&self, options: CoverageOptions) -> Result<(), CoverageError> {
        self.materials
            .iter()
            .enumerate()
            .filter_map(|(k, m)| Some((k, m.as_ref()?)))
            .try_for_each(|(k, m)| {
                m.check_options(options).map_err(|e| match e {
                    CoverageError::AcrossAxis { what: "domain", .. } => {
                        CoverageError::in_material(k, e)
                    }
                    e => e,
                })
            })
    }

    /// Material `k`'s coverage of the rows `rows` ([`GridCoverage::rows`]; zeros and `NaN`s
    /// for an empty region).
    ///
    /// # Errors
    /// As [`GridCoverage::rows`] (an empty region refuses the options a grid refuses);
    /// [`CoverageError::BadRows`] also for `k` out of range.
    pub fn rows(
        &self,
        k: usize,
        rows: Range<usize>,
        options: CoverageOptions,
    ) -> Result<Coverage, CoverageError> {
        let ny = self.grid.ny();
        match self.materials.get(k) {
            Some(Some(m)) => m.rows(rows, options),
            Some(None) if rows.start < rows.end && rows.end <= ny => {
                check_options(&self.grid, None, options)?;
                Coverage::zeroed(rows, self.grid.nx(), options)
            }
            _ => Err(CoverageError::BadRows {
                start: rows.start,
                end: rows.end,
                rows: ny,
            }),
        }
    }

    /// Every material's coverage of the whole grid ([`GridCoverage::all`]).
    ///
    /// # Errors
    /// As [`GridCoverage::all`] and [`MaterialCoverage::check_options`].
    pub fn all(&self, options: CoverageOptions) -> Result<Vec<Coverage>, CoverageError> {
        self.check_options(options)?;
        self.materials
            .iter()
            .map(|m| match m {
                Some(m) => m.all(options),
                None => {
                    check_cells(&self.grid, self.grid.ny())?;
                    Coverage::zeroed(0..self.grid.ny(), self.grid.nx(), options)
                }
            })
            .collect()
    }

    /// The rows of a band for these outputs ([`GridCoverage::band_rows`]).
    pub fn band_rows(&self, options: CoverageOptions) -> usize {
        band_rows(self.grid.nx(), self.grid.ny(), options, threads())
    }

    /// The rows of a band streamed to a file ([`GridCoverage::stream_band_rows`]).
    pub fn stream_band_rows(&self, options: CoverageOptions) -> usize {
        stream_band_rows(self.grid.nx(), self.grid.ny(), options, threads())
    }

    /// Runs `consume` with material `k`'s bands of `band_rows` rows in row order
    /// ([`GridCoverage::bands`]); an empty region's bands are zeros made as they are taken
    /// (each band carries a refusal of the options on the grid, as a region's do).
    pub fn bands<T>(
        &self,
        k: usize,
        band_rows: usize,
        options: CoverageOptions,
        consume: impl FnOnce(MaterialBands<'_>) -> T,
    ) -> T {
        match self.materials.get(k) {
            Some(Some(m)) => m.bands(band_rows, options, |b| {
                consume(MaterialBands {
                    inner: Inner::Bands(b),
                })
            }),
            _ => {
                let (nx, ny) = (self.grid.nx(), self.grid.ny());
                consume(MaterialBands {
                    inner: Inner::Empty {
                        materials: self,
                        next: 0,
                        band_rows: band_rows.clamp(1, ny),
                        nx,
                        ny,
                        options,
                    },
                })
            }
        }
    }
}

/// The bands of one material in row order, `(rows, coverage)` ([`MaterialCoverage::bands`]).
pub struct MaterialBands<'a> {
    inner: Inner<'a>,
}

enum Inner<'a> {
    /// A region's bands, computed on all cores.
    Bands(Bands<'a>),
    /// An empty region's: zeros (or the options' refusal, as every material's bands carry
    /// it), band `next` the next one.
    Empty {
        materials: &'a MaterialCoverage,
        next: usize,
        band_rows: usize,
        nx: usize,
        ny: usize,
        options: CoverageOptions,
    },
}

impl MaterialBands<'_> {
    /// Hands a band back once consumed ([`Bands::recycle`]); nothing for an empty region.
    pub fn recycle(&self, band: Coverage) {
        if let Inner::Bands(b) = &self.inner {
            b.recycle(band);
        }
    }
}

impl Iterator for MaterialBands<'_> {
    type Item = (Range<usize>, Result<Coverage, CoverageError>);

    fn next(&mut self) -> Option<Self::Item> {
        match &mut self.inner {
            Inner::Bands(b) => b.next(),
            Inner::Empty {
                materials,
                next,
                band_rows,
                nx,
                ny,
                options,
            } => {
                let rows = band_range(*next, *band_rows, *ny);
                if rows.is_empty() {
                    return None;
                }
                *next += 1;
                let band = check_options(&materials.grid, None, *options)
                    .and_then(|()| Coverage::zeroed(rows.clone(), *nx, *options));
                Some((rows, band))
            }
        }
    }
}
