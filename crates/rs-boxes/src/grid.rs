//! A uniform grid over monotone boxes: which boxes can be near a point.

use rs_spline::grid::{CellIndex, GridFrame};
use rs_spline::{BoundingBox, Point};

use crate::MonotoneBox;

/// Largest grid resolution (cells per side).
const MAX_CELLS: usize = 1024;

/// The boxes registered in the cells near their curves, so that the boxes a point can be
/// within the tolerance of are found in its cell: a [`CellIndex`] of box indices.
///
/// Every point within the tolerance of a box's curve falls in one of its registered cells; a
/// point outside the grid is near no box. The resolution is about `2 sqrt(N)` cells per side
/// for `N` boxes (at most 1024).
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
    index: CellIndex<u32>,
}

impl BoxGrid {
    /// Registers `boxes`, each in the cells within `abs_tol` of its curve
    /// ([`MonotoneBox::for_cells_near`]).
    pub fn new(boxes: &[MonotoneBox], abs_tol: f64) -> Self {
        let bbox = boxes
            .iter()
            .map(|b| BoundingBox::from_point(b.band.start).including(b.band.end))
            .reduce(BoundingBox::union)
            .unwrap_or(BoundingBox::from_point(Point::new(0.0, 0.0)))
            .grown_by(abs_tol);
        // About 2 sqrt(N) cells per side, and cells no narrower than the tolerance.
        let n = ((2.0 * (boxes.len() as f64).sqrt()).ceil() as usize).clamp(1, MAX_CELLS);
        let frame = GridFrame::new(bbox, GridFrame::cells_for_tolerance(bbox, abs_tol, n));
        let mut pairs = Vec::new();
        for (i, b) in boxes.iter().enumerate() {
            b.for_cells_near(&frame, abs_tol, |c| pairs.push((c, i as u32)));
        }
        Self {
            index: CellIndex::new(frame, pairs),
        }
    }

    /// Indices of the boxes registered in `p`'s cell (empty outside the grid).
    pub fn candidates(&self, p: Point) -> &[u32] {
        self.index.at(p)
    }
}
