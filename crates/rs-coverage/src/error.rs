//! Errors of the coverage kernel: bad grids, domains it cannot cover, outputs too large.

use rs_boxes::BoxError;
use rs_spline::DomainError;
use thiserror::Error;

/// Why a grid or a coverage could not be built.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum CoverageError {
    /// Fewer than two edges along an axis: no cell.
    #[error("a grid needs at least 2 {axis} edges (one cell), got {got}")]
    TooFewEdges {
        /// `'x'` or `'y'`.
        axis: char,
        /// The number of edges given.
        got: usize,
    },
    /// More edges along an axis than [`crate::MAX_EDGES`].
    #[error("{got} {axis} edges exceed the limit of {limit}")]
    TooManyEdges {
        /// `'x'` or `'y'`.
        axis: char,
        /// The number of edges asked for.
        got: usize,
        /// The limit.
        limit: usize,
    },
    /// An edge that is not finite or is larger than [`rs_spline::limits::MAX_COORDINATE`].
    #[error("{axis} edge {index} is {value:?}: edges must be finite and at most {limit:e} in size")]
    EdgeOutOfRange {
        /// `'x'` or `'y'`.
        axis: char,
        /// Index of the edge.
        index: usize,
        /// Its value.
        value: f64,
        /// The largest magnitude allowed.
        limit: f64,
    },
    /// Edges that do not increase strictly (reversed, repeated or unsorted).
    #[error(
        "{axis} edges must increase strictly: edge {index} ({value:?}) is not above edge {} ({previous:?})",
        index - 1
    )]
    NotIncreasing {
        /// `'x'` or `'y'`.
        axis: char,
        /// Index of the edge that is not above the one before it (>= 1).
        index: usize,
        /// The edge before it.
        previous: f64,
        /// Its value.
        value: f64,
    },
    /// The narrowest column times the lowest row is below the smallest normal `f64`: cell
    /// areas and fractions would lose their precision.
    #[error(
        "cells too small: the narrowest width {width:e} times the lowest height {height:e} underflows"
    )]
    CellsTooSmall {
        /// The narrowest column width.
        width: f64,
        /// The lowest row height.
        height: f64,
    },
    /// The cells are too large or too small for an output whose moments grow like a power of
    /// their size (centroids, revolved volumes): the moments would overflow or lose their
    /// precision among the subnormal numbers.
    #[error(
        "cells from {smallest:e} to {largest:e} across are out of range for {what}: their moments would {} (scale the coordinates{})",
        if *overflow { "overflow" } else { "lose their precision" },
        if *radius > 0.0 { format!("; radius up to {radius:e}") } else { String::new() }
    )]
    CellsOutOfRange {
        /// `"centroids"`, `"revolved fractions"` or `"revolved centroids"`.
        what: &'static str,
        /// The shortest side of a cell.
        smallest: f64,
        /// The longest side of a cell.
        largest: f64,
        /// Revolved: the grid's largest distance from the axis (0 for planar cells).
        radius: f64,
        /// Whether the moments would overflow (else underflow).
        overflow: bool,
    },
    /// More cells in one call than [`crate::MAX_CELLS`].
    #[error(
        "{rows} rows of {columns} cells exceed the limit of {limit} cells for one call: compute the grid in row bands"
    )]
    TooManyCells {
        /// Rows asked for.
        rows: usize,
        /// Columns of the grid.
        columns: usize,
        /// The limit on `rows * columns`.
        limit: usize,
    },
    /// Output arrays that do not match the options and the grid
    /// ([`crate::GridCoverage::all_into`]).
    #[error("output {array}: {}", match (expected, got) {
        (Some(e), Some(g)) => format!("{g} values given, the grid needs {e}"),
        (Some(e), None) => format!("not given, the options ask for it ({e} values)"),
        (None, _) => "given, but the options do not ask for it".to_string(),
    })]
    Output {
        /// The array's name ([`crate::CoverageArray::name`]).
        array: &'static str,
        /// The values it needs, `None` when the options do not ask for it.
        expected: Option<usize>,
        /// The values given, `None` when it was not given.
        got: Option<usize>,
    },
    /// A row range that is empty or outside the grid.
    #[error("rows {start}..{end} are not a non-empty range of the grid's {rows} rows")]
    BadRows {
        /// First row asked for.
        start: usize,
        /// One past the last row asked for.
        end: usize,
        /// Rows of the grid.
        rows: usize,
    },
    /// The boundary is open (or falls apart at a curve's break): coverage needs closed loops.
    #[error("open boundary: {0}")]
    Domain(#[from] DomainError),
    /// The loops' nesting does not decide the fill (coincident or crossing loops, or too
    /// many loops: [`rs_contain::fill_nesting`]).
    #[error("{0}")]
    Nesting(rs_contain::NestingError),
    /// The boundary could not be cut into monotone pieces.
    #[error("monotone pieces: {0}")]
    Boxes(#[from] BoxError),
    /// Revolved about an axis, the domain or the grid lies on both sides of it: a revolved
    /// cell or region would overlap its mirror image.
    #[error(
        "the {what} crosses the axis of revolution ({axis:?} axis): its {} runs from {low:e} to {high:e}; it must lie on one side (touching is fine)",
        match axis { rs_spline::Axis::X => "y", rs_spline::Axis::Y => "x" }
    )]
    AcrossAxis {
        /// `"domain"` or `"grid"`.
        what: &'static str,
        /// The axis of revolution.
        axis: rs_spline::Axis,
        /// The smallest radius coordinate.
        low: f64,
        /// The largest.
        high: f64,
    },
    /// An output defined for planar cells only was asked for revolved ones.
    #[error("{what} are computed for planar cells only, not with an axis of revolution")]
    PlanarOnly {
        /// The output.
        what: &'static str,
    },
    /// More pairs of boundary pieces of different materials meet than
    /// [`crate::MAX_PIECE_PAIRS`].
    #[error(
        "{pairs} pairs of boundary pieces of different materials meet, more than the limit of {limit}"
    )]
    TooManyPiecePairs {
        /// The pairs whose control boxes meet (counted up to one past the limit).
        pairs: usize,
        /// The limit.
        limit: usize,
    },
    /// Two materials' boundary pieces whose intersections were not found within the budget.
    #[error("material boundaries: {0}")]
    Intersection(#[from] rs_spline::IntersectError),
    /// A split boundary piece could not be built (non-finite points).
    #[error("material boundaries: {0}")]
    Curve(#[from] rs_spline::SplineError),
    /// A material's domain could not be classified against.
    #[error("material boundaries: {0}")]
    Contain(#[from] rs_contain::ContainError),
    /// The kept boundary pieces of a material's region do not close into loops (it comes
    /// as [`CoverageError::Material`] naming the material).
    #[error("its region's boundary does not close into loops (an intersection was missed)")]
    Unchained,
    /// One material's domain could not be prepared: the domain's own error.
    #[error("material {material}: {source}")]
    Material {
        /// The material (index of its domain).
        material: usize,
        /// Why.
        source: Box<CoverageError>,
    },
    /// The output could not be allocated.
    #[error("cannot allocate {bytes} bytes for the output: compute the grid in smaller row bands")]
    OutOfMemory {
        /// The bytes asked for.
        bytes: usize,
    },
}

impl CoverageError {
    /// `e` as material `k`'s error ([`CoverageError::Material`]).
    pub(crate) fn in_material(material: usize, e: CoverageError) -> Self {
        CoverageError::Material {
            material,
            source: Box::new(e),
        }
    }
}
