//! A uniform grid over monotone boxes: which boxes can be near a point.

use rs_spline::Point;

use crate::MonotoneBox;

/// Largest grid resolution (cells per side).
const MAX_CELLS: usize = 1024;

/// The boxes registered in the cells their rectangles (grown by a tolerance) meet, so that the
/// boxes a point can be within the tolerance of are found in its cell.
///
/// The cell index is a monotone function of the coordinate, so every point of a grown box falls
/// in one of its registered cells; a point outside the grid is near no box. The resolution is
/// about `2 sqrt(N)` cells per side for `N` boxes (at most 1024).
///
/// # Examples
///
/// ```
/// use rs_boxes::{BoxGrid, BoxOptions, MonotoneBoxes};
/// use rs_spline::{circle, Domain, Point};
/// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let boxes = MonotoneBoxes::new(&d, BoxOptions::default()).unwrap();
/// let grid = BoxGrid::new(boxes.boxes(), 1e-9);
/// assert!(grid.candidates(Point::new(0.0, 0.0)).is_empty()); // the centre meets no box
/// assert!(!grid.candidates(Point::new(1.0, 0.0)).is_empty());
/// ```
#[derive(Clone, Debug)]
pub struct BoxGrid {
    x0: f64,
    y0: f64,
    x1: f64,
    y1: f64,
    inv_w: f64,
    inv_h: f64,
    n: usize,
    offsets: Vec<u32>,
    ids: Vec<u32>,
}

impl BoxGrid {
    /// Registers `boxes`, each grown by `tol`.
    pub fn new(boxes: &[MonotoneBox], tol: f64) -> Self {
        let (mut x0, mut y0, mut x1, mut y1) = (
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        );
        for b in boxes {
            x0 = x0.min(b.xmin - tol);
            y0 = y0.min(b.ymin - tol);
            x1 = x1.max(b.xmax + tol);
            y1 = y1.max(b.ymax + tol);
        }
        let n = ((2.0 * (boxes.len() as f64).sqrt()).ceil() as usize).clamp(1, MAX_CELLS);
        let inv = |span: f64| if span > 0.0 { n as f64 / span } else { 0.0 };
        let mut grid = Self {
            x0,
            y0,
            x1,
            y1,
            inv_w: inv(x1 - x0),
            inv_h: inv(y1 - y0),
            n,
            offsets: vec![0; n * n + 1],
            ids: Vec::new(),
        };
        if boxes.is_empty() {
            return grid;
        }
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for (i, b) in boxes.iter().enumerate() {
            let (c0, c1) = (grid.col(b.xmin - tol), grid.col(b.xmax + tol));
            let (r0, r1) = (grid.row(b.ymin - tol), grid.row(b.ymax + tol));
            for c in c0..=c1 {
                for r in r0..=r1 {
                    pairs.push(((c * n + r) as u32, i as u32));
                }
            }
        }
        pairs.sort_unstable();
        let mut k = 0;
        for cell in 0..n * n {
            grid.offsets[cell] = k as u32;
            while k < pairs.len() && pairs[k].0 as usize == cell {
                k += 1;
            }
        }
        grid.offsets[n * n] = pairs.len() as u32;
        grid.ids = pairs.into_iter().map(|(_, i)| i).collect();
        grid
    }

    fn col(&self, x: f64) -> usize {
        (((x - self.x0) * self.inv_w).max(0.0) as usize).min(self.n - 1)
    }

    fn row(&self, y: f64) -> usize {
        (((y - self.y0) * self.inv_h).max(0.0) as usize).min(self.n - 1)
    }

    /// Indices of the boxes registered in `p`'s cell (empty outside the grid).
    pub fn candidates(&self, p: Point) -> &[u32] {
        if !(p.x >= self.x0 && p.x <= self.x1 && p.y >= self.y0 && p.y <= self.y1) {
            return &[];
        }
        let cell = self.col(p.x) * self.n + self.row(p.y);
        &self.ids[self.offsets[cell] as usize..self.offsets[cell + 1] as usize]
    }
}
