//! A grid of cells over a solid's box: cells no patch box reaches are wholly inside or wholly
//! outside (no face passes through them), found once by flood fill and one ray per connected
//! set; a cell the faces pass through keeps the nearest such cell as a reference, so a point
//! there is decided by the crossings of a short segment to the reference's centre.

use std::collections::VecDeque;

use rs_spline::Point3;

/// A cell's state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum CellState {
    /// Wholly outside the solid.
    Outside,
    /// Wholly inside.
    Inside,
    /// A patch box reaches it: its points are decided one by one, from the reference cell
    /// (an index into the grid's cells) when it has one.
    Mixed(Option<u32>),
}

/// Cells of the grid at most (each a byte of state and four of reference).
pub(super) const MAX_CELLS: usize = 1 << 18;

/// The fewest cells along a side of the grid (where the box has that side).
const MIN_SIDE: usize = 16;

/// The most (cell, patch) pairs kept; past it the cells keep no lists of their patches (the
/// hierarchy finds them instead).
const MAX_MEMBERS: usize = 1 << 22;

/// The grid over a box.
#[derive(Clone, Debug)]
pub(super) struct Grid {
    lo: Point3,
    step: Point3,
    n: [usize; 3],
    cells: Vec<CellState>,
    /// For each cell, the patches that may pass within the tolerance of it: `patches[
    /// offsets[c] .. offsets[c + 1]]` (`None` when there were too many pairs to keep).
    members: Option<(Vec<u32>, Vec<u32>)>,
}

/// A cell not yet decided while the grid is built.
const UNSEEN: u8 = 0;
const MIXED: u8 = 1;

impl Grid {
    /// The grid over `[lo, hi]` with about [`MAX_CELLS`] cells, cubes as near as the box
    /// allows; `mark(grid, visit)` calls `visit(cell, patch)` for every cell a patch may pass
    /// within the tolerance of; `decide(p)` says whether a point far from every face is inside
    /// (`None` where it cannot tell: that connected set of cells stays mixed).
    pub(super) fn new(
        lo: Point3,
        hi: Point3,
        mark: impl FnOnce(&Grid, &mut dyn FnMut(usize, u32)),
        mut decide: impl FnMut(Point3) -> Option<bool>,
    ) -> Grid {
        let extent = hi - lo;
        let volume = extent.x.max(0.0) * extent.y.max(0.0) * extent.z.max(0.0);
        let mut h = if volume > 0.0 {
            (volume / MAX_CELLS as f64).cbrt()
        } else {
            extent.max_abs().max(f64::MIN_POSITIVE)
        };
        // At least MIN_SIDE cells a side where the box has any thickness: a thin plate's cells
        // are flat, so that its middle lies in cells no face reaches.
        let cells = |h: f64| {
            [extent.x, extent.y, extent.z].map(|e| {
                let n = (e / h).floor() as usize;
                if e > 0.0 { n.max(MIN_SIDE) } else { 1 }
            })
        };
        // A flat box (a thin plate) has sides of one cell: widen the cells until the grid has
        // at most `MAX_CELLS` (each step 1.25 times; a few dozen steps from any finite box).
        let mut n = cells(h);
        let count = |n: [usize; 3]| n.iter().fold(1usize, |a, &b| a.saturating_mul(b));
        while count(n) > MAX_CELLS && h.is_finite() {
            h *= 1.25;
            n = cells(h);
        }
        let step = Point3::new(
            extent.x / n[0] as f64,
            extent.y / n[1] as f64,
            extent.z / n[2] as f64,
        );
        let mut grid = Grid {
            lo,
            step,
            n,
            cells: Vec::new(),
            members: None,
        };
        let total = n[0] * n[1] * n[2];
        let mut mixed = vec![false; total];
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        let mut kept = true;
        mark(&grid, &mut |cell, patch| {
            mixed[cell] = true;
            if kept {
                if pairs.len() < MAX_MEMBERS {
                    pairs.push((cell as u32, patch));
                } else {
                    kept = false;
                    pairs = Vec::new();
                }
            }
        });
        if kept {
            pairs.sort_unstable();
            pairs.dedup();
            let mut offsets = vec![0u32; total + 1];
            for &(c, _) in &pairs {
                offsets[c as usize + 1] += 1;
            }
            for c in 0..total {
                offsets[c + 1] += offsets[c];
            }
            grid.members = Some((offsets, pairs.into_iter().map(|(_, p)| p).collect()));
        }
        let mut seen: Vec<u8> = mixed
            .iter()
            .map(|&m| if m { MIXED } else { UNSEEN })
            .collect();
        let mut cells = vec![CellState::Mixed(None); total];
        // Connected sets of unmarked cells: no face passes between two of them.
        let mut queue = VecDeque::new();
        let mut members = Vec::new();
        for start in 0..total {
            if seen[start] != UNSEEN {
                continue;
            }
            members.clear();
            seen[start] = 2;
            queue.push_back(start);
            while let Some(c) = queue.pop_front() {
                members.push(c);
                grid.for_neighbours(c, |m| {
                    if seen[m] == UNSEEN {
                        seen[m] = 2;
                        queue.push_back(m);
                    }
                });
            }
            // The first member whose centre the rays decide decides the set, checked by the
            // last one (breadth first, the farthest): where they disagree, a face passes between
            // them unmarked (a box that missed its surface) and the set stays mixed, its points
            // decided one by one.
            let first = members.iter().take(8).find_map(|&c| decide(grid.centre(c)));
            let last = members
                .iter()
                .rev()
                .take(8)
                .find_map(|&c| decide(grid.centre(c)));
            let state = match (first, last) {
                (Some(a), Some(b)) if a == b => Some(if a {
                    CellState::Inside
                } else {
                    CellState::Outside
                }),
                _ => None,
            };
            if let Some(state) = state {
                for &c in &members {
                    cells[c] = state;
                }
            }
        }
        // Each mixed cell's nearest decided cell (breadth first from all decided cells).
        let mut reference: Vec<Option<u32>> = vec![None; total];
        for (c, s) in cells.iter().enumerate() {
            if !matches!(s, CellState::Mixed(_)) {
                reference[c] = Some(c as u32);
                queue.push_back(c);
            }
        }
        while let Some(c) = queue.pop_front() {
            let r = reference[c];
            grid.for_neighbours(c, |m| {
                if reference[m].is_none() {
                    reference[m] = r;
                    queue.push_back(m);
                }
            });
        }
        for (c, s) in cells.iter_mut().enumerate() {
            if let CellState::Mixed(r) = s {
                *r = reference[c];
            }
        }
        grid.cells = cells;
        grid
    }

    /// One mixed cell over `[lo, hi]` (every point decided on its own).
    pub(super) fn single(lo: Point3, hi: Point3) -> Grid {
        Grid {
            lo,
            step: hi - lo,
            n: [1, 1, 1],
            cells: vec![CellState::Mixed(None)],
            members: None,
        }
    }

    /// The patches that may pass within the tolerance of cell `c`, if kept.
    pub(super) fn members(&self, c: usize) -> Option<&[u32]> {
        let (offsets, patches) = self.members.as_ref()?;
        Some(&patches[offsets[c] as usize..offsets[c + 1] as usize])
    }

    /// The state of the cell holding `p` (a point in the box).
    pub(super) fn state(&self, p: Point3) -> CellState {
        self.cells[self.index(p)]
    }

    /// The state of cell `c`.
    pub(super) fn state_of(&self, c: u32) -> CellState {
        self.cells[c as usize]
    }

    /// The cell holding `p` (clamped into the grid).
    pub(super) fn index(&self, p: Point3) -> usize {
        let [i, j, k] = self.coordinates(p);
        (i * self.n[1] + j) * self.n[2] + k
    }

    /// The cell coordinates of `p`, clamped into the grid.
    fn coordinates(&self, p: Point3) -> [usize; 3] {
        // `as usize` truncates towards zero and sends NaN and negatives to 0: the floor of
        // the non-negative values, clamped below for free.
        let at = |x: f64, lo: f64, step: f64, n: usize| (((x - lo) / step) as usize).min(n - 1);
        [
            at(p.x, self.lo.x, self.step.x, self.n[0]),
            at(p.y, self.lo.y, self.step.y, self.n[1]),
            at(p.z, self.lo.z, self.step.z, self.n[2]),
        ]
    }

    /// The ranges of cell coordinates the box `[lo, hi]` reaches, per axis.
    pub(super) fn ranges(&self, lo: Point3, hi: Point3) -> [(usize, usize); 3] {
        let a = self.coordinates(lo);
        let b = self.coordinates(hi);
        std::array::from_fn(|k| (a[k], b[k]))
    }

    /// The linear index of cell `[i, j, k]`.
    pub(super) fn linear(&self, [i, j, k]: [usize; 3]) -> usize {
        (i * self.n[1] + j) * self.n[2] + k
    }

    /// The centre of cell `c`.
    pub(super) fn centre(&self, c: usize) -> Point3 {
        let k = c % self.n[2];
        let j = (c / self.n[2]) % self.n[1];
        let i = c / (self.n[1] * self.n[2]);
        Point3::new(
            self.lo.x + (i as f64 + 0.5) * self.step.x,
            self.lo.y + (j as f64 + 0.5) * self.step.y,
            self.lo.z + (k as f64 + 0.5) * self.step.z,
        )
    }

    fn for_neighbours(&self, c: usize, mut f: impl FnMut(usize)) {
        let [n0, n1, n2] = self.n;
        let k = c % n2;
        let j = (c / n2) % n1;
        let i = c / (n1 * n2);
        if i > 0 {
            f(c - n1 * n2);
        }
        if i + 1 < n0 {
            f(c + n1 * n2);
        }
        if j > 0 {
            f(c - n2);
        }
        if j + 1 < n1 {
            f(c + n2);
        }
        if k > 0 {
            f(c - 1);
        }
        if k + 1 < n2 {
            f(c + 1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A connected set of unmarked cells whose far ends the rays decide differently (a face
    /// passing between them unmarked) is not decided: its points are left to the rays.
    #[test]
    fn a_set_whose_ends_disagree_stays_mixed() {
        let one = Point3::new(1.0, 1.0, 1.0);
        let origin = Point3::new(0.0, 0.0, 0.0);
        let g = Grid::new(origin, one, |_, _| {}, |p| Some(p.x < 0.5));
        assert_eq!(g.state(one * 0.25), CellState::Mixed(None));
        let g = Grid::new(origin, one, |_, _| {}, |_| Some(true));
        assert_eq!(g.state(one * 0.25), CellState::Inside);
    }

    /// Boxes of any shape get at most `MAX_CELLS` cells: a cube, a thin plate, a needle, a box
    /// flat in one direction.
    #[test]
    fn grids_stay_within_their_cell_budget() {
        for extent in [
            Point3::new(1.0, 1.0, 1.0),
            Point3::new(1.0, 1.0, 1e-9),
            Point3::new(1e-9, 1e-9, 1.0),
            Point3::new(1.0, 1.0, 0.0),
            Point3::new(1e300, 1.0, 1e-300),
        ] {
            let mut cells = 0;
            let g = Grid::new(
                Point3::new(0.0, 0.0, 0.0),
                extent,
                |g, _| cells = g.n.iter().product(),
                |_| Some(false),
            );
            assert!(cells <= MAX_CELLS, "{extent:?}: {cells}");
            assert_eq!(g.state(extent * 0.5), CellState::Outside);
        }
    }
}
