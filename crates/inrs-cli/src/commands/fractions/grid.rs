//! `--grid x0,x1,nx,y0,y1,ny`: a uniform grid, checked before anything is read; the cell
//! limit of every grid.

use inrs::coverage::{CellGrid, CoverageError, MAX_EDGES};

/// The most cells of one `inrs fractions` run, `nx x ny` (2^32: 32 GiB of fractions, written
/// band by band, so memory does not grow with it).
pub(crate) const MAX_GRID_CELLS: u64 = 1 << 32;

/// The most columns (rows) of a grid: one fewer than the library's edges per axis.
pub(crate) const MAX_CELLS_PER_AXIS: usize = MAX_EDGES - 1;

/// A uniform grid as given on the command line: `nx` columns on `[x0, x1]`, `ny` rows on
/// `[y0, y1]`; `x0 < x1`, `y0 < y1` finite, `1 <= nx, ny <= MAX_CELLS_PER_AXIS`,
/// `nx ny <= MAX_GRID_CELLS` (checked by [`parse_grid`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct GridSpec {
    pub(crate) x0: f64,
    pub(crate) x1: f64,
    pub(crate) nx: usize,
    pub(crate) y0: f64,
    pub(crate) y1: f64,
    pub(crate) ny: usize,
}

impl GridSpec {
    /// The library's grid: `x_i = x0 + i (x1 - x0) / nx`, `x_nx = x1` exactly (likewise `y`).
    ///
    /// # Errors
    /// What [`CellGrid::uniform`] refuses beyond [`parse_grid`]'s checks: bounds beyond
    /// `1e150`, cells whose area underflows.
    pub(crate) fn cell_grid(&self) -> Result<CellGrid, CoverageError> {
        CellGrid::uniform(self.x0, self.x1, self.nx, self.y0, self.y1, self.ny)
    }
}

/// Parses `x0,x1,nx,y0,y1,ny`, with a one-line message naming the value at fault.
pub(crate) fn parse_grid(s: &str) -> Result<GridSpec, String> {
    let fields: Vec<&str> = s.split(',').map(str::trim).collect();
    let [x0, x1, nx, y0, y1, ny] = fields[..] else {
        return Err(format!(
            "expected x0,x1,nx,y0,y1,ny (6 values), got {} value{}",
            fields.len(),
            if fields.len() == 1 { "" } else { "s" }
        ));
    };
    let g = GridSpec {
        x0: bound("x0", x0)?,
        x1: bound("x1", x1)?,
        nx: count("nx", nx)?,
        y0: bound("y0", y0)?,
        y1: bound("y1", y1)?,
        ny: count("ny", ny)?,
    };
    if g.x0 >= g.x1 {
        return Err(format!("x0 = {:?} must be below x1 = {:?}", g.x0, g.x1));
    }
    if g.y0 >= g.y1 {
        return Err(format!("y0 = {:?} must be below y1 = {:?}", g.y0, g.y1));
    }
    check_cells(g.nx, g.ny)?;
    Ok(g)
}

/// `nx x ny` at most [`MAX_GRID_CELLS`].
pub(crate) fn check_cells(nx: usize, ny: usize) -> Result<(), String> {
    let cells = nx as u64 * ny as u64;
    if cells > MAX_GRID_CELLS {
        return Err(format!(
            "{nx} x {ny} = {cells} cells exceed the limit of 2^32 ({MAX_GRID_CELLS}) cells"
        ));
    }
    Ok(())
}

/// A finite bound.
fn bound(name: &str, s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(v) => Err(format!("{name} = {v} must be finite")),
        Err(_) => Err(format!("{name} = {s:?} is not a number")),
    }
}

/// A cell count from 1 to [`MAX_CELLS_PER_AXIS`].
fn count(name: &str, s: &str) -> Result<usize, String> {
    match s.parse::<u64>() {
        Ok(n) if (1..=MAX_CELLS_PER_AXIS as u64).contains(&n) => Ok(n as usize),
        _ => Err(format!(
            "{name} = {s:?}: expected a whole number from 1 to {MAX_CELLS_PER_AXIS}"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_is_read_in_order_with_its_edges_exact_at_the_ends() {
        let g = parse_grid("-1.5, 2,3,0,1e-3,7").unwrap();
        assert_eq!(
            g,
            GridSpec {
                x0: -1.5,
                x1: 2.0,
                nx: 3,
                y0: 0.0,
                y1: 1e-3,
                ny: 7
            }
        );
        let cells = g.cell_grid().unwrap();
        assert_eq!((cells.nx(), cells.ny()), (3, 7));
        assert_eq!(cells.x_edges()[3], 2.0);
        assert_eq!(cells.y_edges()[7], 1e-3);
    }

    #[test]
    fn bad_grids_get_a_message_naming_the_value() {
        let e = |s: &str| parse_grid(s).unwrap_err();
        assert_eq!(
            e("0,1,4"),
            "expected x0,x1,nx,y0,y1,ny (6 values), got 3 values"
        );
        assert_eq!(
            e("0,1,4,0,1,4,5"),
            "expected x0,x1,nx,y0,y1,ny (6 values), got 7 values"
        );
        assert_eq!(e("0,x,4,0,1,4"), "x1 = \"x\" is not a number");
        assert_eq!(e("0,inf,4,0,1,4"), "x1 = inf must be finite");
        assert_eq!(e("nan,1,4,0,1,4"), "x0 = NaN must be finite");
        assert!(e("0,1,0,0,1,4").starts_with("nx = \"0\": expected a whole number from 1 to"));
        assert!(e("0,1,4,0,1,-4").starts_with("ny = \"-4\""));
        assert!(e("0,1,2.5,0,1,4").starts_with("nx = \"2.5\""));
        assert_eq!(e("1,0,4,0,1,4"), "x0 = 1.0 must be below x1 = 0.0");
        assert_eq!(e("0,1,4,2,2,4"), "y0 = 2.0 must be below y1 = 2.0");
        assert_eq!(
            e("0,1,65536,0,1,65537"),
            "65536 x 65537 = 4295032832 cells exceed the limit of 2^32 (4294967296) cells"
        );
        assert!(parse_grid("0,1,65536,0,1,65536").is_ok());
        assert!(e("0,1,67108864,0,1,1").contains("from 1 to 67108863"));
    }
}
