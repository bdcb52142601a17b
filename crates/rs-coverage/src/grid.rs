//! Rectilinear grids: strictly increasing cell edges along x and y.

use rs_spline::limits::MAX_COORDINATE;
use rs_spline::{BoundingBox, Point};

use crate::CoverageError;

/// Most edges along one axis of a [`CellGrid`] (`2^26`: 512 MiB of edges).
pub const MAX_EDGES: usize = 1 << 26;

/// A rectilinear grid: column `i` is `[x_i, x_{i+1}]`, row `j` is `[y_j, y_{j+1}]`, cell
/// `(i, j)` their product, for strictly increasing finite edges `x_0 < ... < x_nx` and
/// `y_0 < ... < y_ny`. Rows go up: row `j + 1` lies above row `j`.
///
/// # Examples
///
/// ```
/// use rs_coverage::CellGrid;
/// let g = CellGrid::uniform(-1.0, 1.0, 4, 0.0, 1.0, 2).unwrap();
/// assert_eq!(g.x_edges(), &[-1.0, -0.5, 0.0, 0.5, 1.0]);
/// assert_eq!((g.nx(), g.ny()), (4, 2));
/// assert!(CellGrid::new(vec![0.0, 1.0], vec![1.0, 0.0]).is_err()); // reversed
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct CellGrid {
    x: Vec<f64>,
    y: Vec<f64>,
    /// The shortest and the longest side of a cell, over both axes.
    sides: (f64, f64),
}

impl CellGrid {
    /// The grid with these edges.
    ///
    /// # Errors
    /// [`CoverageError::TooFewEdges`] (fewer than 2 along an axis),
    /// [`CoverageError::TooManyEdges`] (more than [`MAX_EDGES`]),
    /// [`CoverageError::EdgeOutOfRange`] (not finite, or larger than `1e150` in size),
    /// [`CoverageError::NotIncreasing`], [`CoverageError::CellsTooSmall`] (the smallest cell's
    /// area underflows).
    pub fn new(x_edges: Vec<f64>, y_edges: Vec<f64>) -> Result<Self, CoverageError> {
        let (width, widest) = check_edges('x', &x_edges)?;
        let (height, highest) = check_edges('y', &y_edges)?;
        if width * height < f64::MIN_POSITIVE {
            return Err(CoverageError::CellsTooSmall { width, height });
        }
        Ok(Self {
            x: x_edges,
            y: y_edges,
            sides: (width.min(height), widest.max(highest)),
        })
    }

    /// The uniform grid of `nx` columns on `[x0, x1]` and `ny` rows on `[y0, y1]`:
    /// `x_i = x0 + i (x1 - x0) / nx` (so `x_0 = x0` and `x_nx = x1` exactly), likewise `y_j`.
    ///
    /// # Errors
    /// As [`CellGrid::new`]; `nx = 0` is [`CoverageError::TooFewEdges`], `x1 <= x0`
    /// [`CoverageError::NotIncreasing`]; the edges are not allocated when a count exceeds
    /// [`MAX_EDGES`].
    pub fn uniform(
        x0: f64,
        x1: f64,
        nx: usize,
        y0: f64,
        y1: f64,
        ny: usize,
    ) -> Result<Self, CoverageError> {
        Self::new(
            uniform_edges('x', x0, x1, nx)?,
            uniform_edges('y', y0, y1, ny)?,
        )
    }

    /// The column edges `x_0 < ... < x_nx`.
    pub fn x_edges(&self) -> &[f64] {
        &self.x
    }

    /// The row edges `y_0 < ... < y_ny`.
    pub fn y_edges(&self) -> &[f64] {
        &self.y
    }

    /// The number of columns.
    pub fn nx(&self) -> usize {
        self.x.len() - 1
    }

    /// The number of rows.
    pub fn ny(&self) -> usize {
        self.y.len() - 1
    }

    /// The area `(x_{i+1} - x_i) (y_{j+1} - y_j)` of cell `(i, j)` (column `i`, row `j`).
    ///
    /// # Panics
    /// If the cell is outside the grid.
    pub fn cell_area(&self, i: usize, j: usize) -> f64 {
        (self.x[i + 1] - self.x[i]) * (self.y[j + 1] - self.y[j])
    }

    /// The shortest and the longest side of a cell, over both axes.
    pub fn cell_sides(&self) -> (f64, f64) {
        self.sides
    }

    /// The rectangle `[x_0, x_nx] x [y_0, y_ny]`.
    pub fn bounding_box(&self) -> BoundingBox {
        BoundingBox {
            min: Point::new(self.x[0], self.y[0]),
            max: Point::new(self.x[self.nx()], self.y[self.ny()]),
        }
    }
}

/// Checks one axis' edges; returns the smallest and the largest gap between consecutive
/// edges.
fn check_edges(axis: char, edges: &[f64]) -> Result<(f64, f64), CoverageError> {
    if edges.len() < 2 {
        return Err(CoverageError::TooFewEdges {
            axis,
            got: edges.len(),
        });
    }
    if edges.len() > MAX_EDGES {
        return Err(CoverageError::TooManyEdges {
            axis,
            got: edges.len(),
            limit: MAX_EDGES,
        });
    }
    if let Some(index) = edges
        .iter()
        .position(|v| !v.is_finite() || v.abs() > MAX_COORDINATE)
    {
        return Err(CoverageError::EdgeOutOfRange {
            axis,
            index,
            value: edges[index],
            limit: MAX_COORDINATE,
        });
    }
    let (mut smallest, mut largest) = (f64::INFINITY, 0.0f64);
    for (index, pair) in edges.windows(2).enumerate() {
        if pair[1] <= pair[0] {
            return Err(CoverageError::NotIncreasing {
                axis,
                index: index + 1,
                previous: pair[0],
                value: pair[1],
            });
        }
        smallest = smallest.min(pair[1] - pair[0]);
        largest = largest.max(pair[1] - pair[0]);
    }
    Ok((smallest, largest))
}

/// `n + 1` uniform edges on `[a, b]`, the last exactly `b`.
fn uniform_edges(axis: char, a: f64, b: f64, n: usize) -> Result<Vec<f64>, CoverageError> {
    if n == 0 {
        return Err(CoverageError::TooFewEdges { axis, got: 1 });
    }
    if n >= MAX_EDGES {
        return Err(CoverageError::TooManyEdges {
            axis,
            got: n.saturating_add(1),
            limit: MAX_EDGES,
        });
    }
    let span = b - a;
    Ok((0..=n)
        .map(|i| {
            if i == n {
                b
            } else {
                a + span * i as f64 / n as f64
            }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_edges_are_exact_at_the_ends_and_on_dyadic_steps() {
        let g = CellGrid::uniform(-1.0, 1.0, 2048, -3.0, 0.1, 7).unwrap();
        assert_eq!(g.x_edges()[0], -1.0);
        assert_eq!(g.x_edges()[1024], 0.0);
        assert_eq!(g.x_edges()[2048], 1.0);
        assert_eq!(g.y_edges()[7], 0.1);
        assert!((g.cell_area(3, 2) - (2.0 / 2048.0) * (3.1 / 7.0)).abs() < 1e-16);
    }

    #[test]
    fn bad_edges_are_named() {
        let e = |x: Vec<f64>| CellGrid::new(x, vec![0.0, 1.0]).unwrap_err();
        assert!(matches!(
            e(vec![0.0]),
            CoverageError::TooFewEdges { axis: 'x', got: 1 }
        ));
        assert!(matches!(
            e(vec![0.0, f64::NAN]),
            CoverageError::EdgeOutOfRange { index: 1, .. }
        ));
        assert!(matches!(
            e(vec![0.0, 2.0, 1.0]),
            CoverageError::NotIncreasing { index: 2, .. }
        ));
        let msg = e(vec![0.0, 1.0, 1.0]).to_string();
        assert_eq!(
            msg,
            "x edges must increase strictly: edge 2 (1.0) is not above edge 1 (1.0)"
        );
        assert!(matches!(
            CellGrid::new(vec![0.0, 1e-200], vec![0.0, 1e-200]),
            Err(CoverageError::CellsTooSmall { .. })
        ));
        assert!(matches!(
            CellGrid::uniform(0.0, 1.0, 0, 0.0, 1.0, 1),
            Err(CoverageError::TooFewEdges { axis: 'x', got: 1 })
        ));
        assert!(matches!(
            CellGrid::uniform(0.0, 1.0, 1, 1.0, 0.0, 1),
            Err(CoverageError::NotIncreasing { axis: 'y', .. })
        ));
        assert!(matches!(
            CellGrid::uniform(0.0, 1.0, usize::MAX, 0.0, 1.0, 1),
            Err(CoverageError::TooManyEdges { axis: 'x', .. })
        ));
    }
}
