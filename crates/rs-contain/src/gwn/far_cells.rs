//! Far cells of a winding field: a grid over the field's box whose cells away from every
//! curve know the crossings a query in them counts, so a batch's query there skips the walk.
//!
//! Why one count serves a whole region: outside the band round the curves the crossings the
//! walk counts (the signed crossings of the cut, the ray from the query towards `-x`, by the
//! chords it settles) are exactly the crossings of the curves themselves (see
//! [`WindingField`](super::WindingField)'s Semantics). They change only where the query
//! crosses a curve, or crosses the height of an open chain's end (where the cut sweeps over
//! the end). A grid cell that lies farther than the band's reach from every curve and holds no
//! chain end's height therefore gives every query in it the same crossings; so does every cell
//! of a connected region of such cells. One walk per region (from a cell's centre) finds them,
//! and the query adds only its chains' ends, as the walk's query does: the same value bit for
//! bit.

use rs_spline::{Point, RationalBezier};

use std::ops::Deref;

use super::curve::{Halve, SmallPolynomial, SubCurve, control_box};

/// Cells per side: `2^8` (256 KiB of counts). On the GWN paper's shapes, random points of the
/// shapes' boxes took 0.87-0.95 of the time at `2^8` they took at `2^7` (where 54-82% of them
/// lie in far cells at `2^6`, 70-90% at `2^7`).
const SIDE_BITS: u32 = 8;

/// Cells per side.
const SIDE: usize = 1 << SIDE_BITS;

/// A cell within reach of a curve, or holding a chain end's height: its queries walk.
const NEAR: i32 = i32::MIN;

/// A far cell whose region has no count yet (only while building).
const UNSEEN: i32 = i32::MIN + 1;

/// Halvings of a piece at most, to cover it by boxes of about two cells (a sub-curve still
/// larger after them marks its whole box, which is only coarser).
const MAX_SPLITS: u32 = 12;

/// The widest growth of the curves' boxes, in cells, for which a field has far cells.
const MAX_GROW_CELLS: f64 = 2.0;

/// The margin beyond the band's reach that keeps a far cell's queries far from the curves,
/// relative to the grid's diagonal (the walk's own roundings are below `1e-12` of it).
const RELATIVE_MARGIN: f64 = 1e-9;

/// The far cells of a field (see the module documentation).
#[derive(Clone, Debug)]
pub(super) struct FarCells {
    lo: Point,
    hi: Point,
    /// Cells per unit length in `x` and in `y`.
    per_unit: Point,
    /// Per cell, row by row: the crossings of its queries, or [`NEAR`].
    counts: Vec<i32>,
}

impl FarCells {
    /// The far cells of the grid over `[lo, hi]` for `pieces` whose band reaches `reach` from
    /// them, with open chains from `s` to `e` in `chain_ends`; `crossings(q)` is the walk's
    /// count at `q` (`None` if it found `q` on or near a curve). `None` for a box of no width
    /// or height, or not finite.
    pub(super) fn new(
        lo: Point,
        hi: Point,
        reach: f64,
        pieces: &[RationalBezier],
        chain_ends: &[(Point, Point)],
        mut crossings: impl FnMut(Point) -> Option<i64>,
    ) -> Option<Self> {
        let per_unit = |lo: f64, hi: f64| {
            let s = SIDE as f64 / (hi - lo);
            (s.is_finite() && s > 0.0).then_some(s)
        };
        let per_unit = Point::new(per_unit(lo.x, hi.x)?, per_unit(lo.y, hi.y)?);
        let scale = lo.x.abs().max(lo.y.abs()).max(hi.x.abs()).max(hi.y.abs());
        let diagonal = (hi.x - lo.x).hypot(hi.y - lo.y);
        let grow = reach + RELATIVE_MARGIN * diagonal + 64.0 * f64::EPSILON * scale;
        // A band wider than a couple of cells leaves few far cells (and would make each box
        // mark many): no grid then.
        let cell = (1.0 / per_unit.x).min(1.0 / per_unit.y);
        if grow.is_nan() || grow > MAX_GROW_CELLS * cell {
            return None;
        }
        let mut cells = Self {
            lo,
            hi,
            per_unit,
            counts: vec![UNSEEN; SIDE * SIDE],
        };
        cells.mark_curves(pieces, grow);
        let mut marked = [false; SIDE];
        for &(s, e) in chain_ends {
            cells.mark_row_of(s.y, &mut marked);
            cells.mark_row_of(e.y, &mut marked);
        }
        cells.count_regions(&mut crossings);
        Some(cells)
    }

    /// The crossings the walk counts at `q`, if `q` lies in a far cell.
    #[inline(always)]
    pub(super) fn crossings(&self, q: Point) -> Option<i64> {
        let k = self.counts[self.cell(q)?];
        (k != NEAR).then_some(i64::from(k))
    }

    /// The cell holding `q`; `None` outside the grid (or not a number).
    #[inline(always)]
    fn cell(&self, q: Point) -> Option<usize> {
        let inside = q.x >= self.lo.x && q.x <= self.hi.x && q.y >= self.lo.y && q.y <= self.hi.y;
        inside.then(|| self.column(q.x) + SIDE * self.row(q.y))
    }

    /// The column of abscissa `x` in `[lo.x, hi.x]`: non-decreasing in `x` (each operation
    /// rounds monotonically), so a cell whose column lies outside a box's columns holds no
    /// point of the box.
    #[inline(always)]
    fn column(&self, x: f64) -> usize {
        (((x - self.lo.x) * self.per_unit.x) as usize).min(SIDE - 1)
    }

    /// The row of ordinate `y` in `[lo.y, hi.y]` (as [`FarCells::column`]).
    #[inline(always)]
    fn row(&self, y: f64) -> usize {
        (((y - self.lo.y) * self.per_unit.y) as usize).min(SIDE - 1)
    }

    /// Marks every cell holding a point within `grow` of a curve: each piece halved until its
    /// sub-curves' control boxes (which hold them) span about two cells, each box grown by
    /// `grow`.
    fn mark_curves(&mut self, pieces: &[RationalBezier], grow: f64) {
        for piece in pieces {
            let c = SubCurve::of(piece);
            match SmallPolynomial::of(&c) {
                Some(small) => self.mark_curve(small, grow),
                None => self.mark_curve(c, grow),
            }
        }
    }

    /// [`FarCells::mark_curves`] for one piece, `c`.
    fn mark_curve<C: Halve + Deref<Target = [Point]>>(&mut self, c: C, grow: f64) {
        let (cell_x, cell_y) = (1.0 / self.per_unit.x, 1.0 / self.per_unit.y);
        let mut stack = vec![(c, 0)];
        while let Some((c, splits)) = stack.pop() {
            let (blo, bhi) = control_box(&c);
            let small = bhi.x - blo.x <= 2.0 * cell_x && bhi.y - blo.y <= 2.0 * cell_y;
            if small || splits >= MAX_SPLITS {
                self.mark_box(blo, bhi, grow);
            } else {
                let (l, r) = c.halves();
                stack.push((r, splits + 1));
                stack.push((l, splits + 1));
            }
        }
    }

    /// Marks every cell holding a point of the box `[blo, bhi]` grown by `grow`.
    fn mark_box(&mut self, blo: Point, bhi: Point, grow: f64) {
        let (x0, x1) = (blo.x - grow, bhi.x + grow);
        let (y0, y1) = (blo.y - grow, bhi.y + grow);
        // A box with a NaN corner marks everything (every comparison below fails).
        let misses = x1 < self.lo.x || x0 > self.hi.x || y1 < self.lo.y || y0 > self.hi.y;
        if misses {
            return;
        }
        let columns = self.column(x0.max(self.lo.x))..=self.column(x1.min(self.hi.x));
        for r in self.row(y0.max(self.lo.y))..=self.row(y1.min(self.hi.y)) {
            self.counts[r * SIDE + columns.start()..=r * SIDE + columns.end()].fill(NEAR);
        }
    }

    /// Marks the row holding ordinate `y` (if the grid reaches it) unless `marked` says it is
    /// already: queries above and below that height count a chain's end differently.
    fn mark_row_of(&mut self, y: f64, marked: &mut [bool; SIDE]) {
        if y >= self.lo.y && y <= self.hi.y {
            let r = self.row(y);
            if !std::mem::replace(&mut marked[r], true) {
                self.counts[r * SIDE..(r + 1) * SIDE].fill(NEAR);
            }
        } else if y.is_nan() {
            self.counts.fill(NEAR);
        }
    }

    /// Gives every connected region of far cells (through their sides) the count of a walk
    /// from the centre of one of its cells; a region whose walk finds no count (or whose
    /// centre rounds into another cell) is marked near. The regions are found by their rows'
    /// runs of far cells, a run joined to every run of the row below that shares a column
    /// (union-find): a pass over the cells and one over the runs.
    fn count_regions(&mut self, crossings: &mut impl FnMut(Point) -> Option<i64>) {
        // Runs as (row, first column, end column), row by row; `rows[r]..rows[r + 1]` are
        // row r's.
        let mut runs: Vec<(usize, usize, usize)> = Vec::new();
        let mut rows = Vec::with_capacity(SIDE + 1);
        for r in 0..SIDE {
            rows.push(runs.len());
            let row = &self.counts[r * SIDE..(r + 1) * SIDE];
            let mut c = 0;
            while c < SIDE {
                if row[c] == UNSEEN {
                    let start = c;
                    while c < SIDE && row[c] == UNSEEN {
                        c += 1;
                    }
                    runs.push((r, start, c));
                } else {
                    c += 1;
                }
            }
        }
        rows.push(runs.len());
        let mut parent: Vec<usize> = (0..runs.len()).collect();
        for r in 1..SIDE {
            let (below, this) = (rows[r - 1]..rows[r], rows[r]..rows[r + 1]);
            let (mut i, mut j) = (below.start, this.start);
            while i < below.end && j < this.end {
                let ((_, a0, a1), (_, b0, b1)) = (runs[i], runs[j]);
                if a0 < b1 && b0 < a1 {
                    let (ra, rb) = (root(&mut parent, i), root(&mut parent, j));
                    parent[ra.max(rb)] = ra.min(rb);
                }
                // The run ending first meets no later run of the other row.
                if a1 <= b1 {
                    i += 1;
                } else {
                    j += 1;
                }
            }
        }
        // A set's root is its first run (the lesser root becomes the parent), so it gets its
        // count before the set's other runs read it.
        let mut count = vec![NEAR; runs.len()];
        for (k, &(r, start, end)) in runs.iter().enumerate() {
            let first = root(&mut parent, k);
            count[k] = if first == k {
                self.region_count(r * SIDE + start, crossings)
            } else {
                count[first]
            };
            self.counts[r * SIDE + start..r * SIDE + end].fill(count[k]);
        }
    }

    /// The walk's count at the centre of cell `i`, [`NEAR`] if it has none.
    fn region_count(&self, i: usize, crossings: &mut impl FnMut(Point) -> Option<i64>) -> i32 {
        let (c, r) = (i % SIDE, i / SIDE);
        let centre = Point::new(
            self.lo.x + (c as f64 + 0.5) / self.per_unit.x,
            self.lo.y + (r as f64 + 0.5) / self.per_unit.y,
        );
        (self.cell(centre) == Some(i))
            .then(|| crossings(centre))
            .flatten()
            .and_then(|k| i32::try_from(k).ok())
            .filter(|&k| k > UNSEEN)
            .unwrap_or(NEAR)
    }

    /// The share of cells that are far (for the tests).
    #[cfg(test)]
    pub(super) fn far_share(&self) -> f64 {
        self.counts.iter().filter(|&&k| k != NEAR).count() as f64 / self.counts.len() as f64
    }
}

/// The root of run `k`'s set, halving the path to it on the way.
fn root(parent: &mut [usize], mut k: usize) -> usize {
    while parent[k] != k {
        parent[k] = parent[parent[k]];
        k = parent[k];
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gwn::fast::FAR_CELLS_MIN_POINTS;
    use crate::gwn::{FastWindingField, WindingField};
    use crate::{DEFAULT_RELATIVE_TOLERANCE, Location, PointQuery};
    use rs_spline::{Domain, ParamCurve, circle, circular_arc, segment};

    /// Curves of every kind a far cell meets: two loops round one region (winding 2 there),
    /// a reversed loop, an open arc, a polyline with gaps between its segments (a wide band
    /// reach), a horizontal segment (both its ends at one height), rational pieces.
    fn mixed() -> Domain {
        let o = Point::new(0.0, 0.0);
        let mut curves = vec![
            circle(o, 3.0).unwrap(),
            circle(Point::new(0.5, 0.2), 1.0).unwrap(),
            circle(Point::new(-1.5, -1.0), 0.7).unwrap().reversed(),
            circular_arc(Point::new(1.0, -1.5), 0.8, 0.4, 4.0).unwrap(),
            segment(Point::new(-2.0, 1.5), Point::new(2.5, 1.5)).unwrap(),
        ];
        for k in 0..6 {
            let x = -2.5 + 0.8 * k as f64;
            curves.push(segment(Point::new(x, 2.2), Point::new(x + 0.75, 2.6)).unwrap());
        }
        Domain::new(curves).unwrap()
    }

    /// Batches reading the far cells give every point the value the walk gives it alone, bit
    /// for bit (the winding number and the location): random points over the shapes' boxes,
    /// points at every open chain's end heights and one ulp above and below them (where the
    /// count changes), points on the cells' edges, a grid; most of the cells are far.
    #[test]
    fn far_cells_give_each_point_the_walks_value() {
        let shapes = [
            ("twirl", rs_testkit::gwn_shape("twirl")),
            ("bubble", rs_testkit::gwn_shape("bubble")),
            ("fish", rs_testkit::gwn_shape("fish")),
            ("mixed", mixed()),
        ];
        for (name, d) in shapes {
            let field = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).unwrap();
            let fast = FastWindingField::new(&field);
            let b = d.bounding_box();
            let (lo, w, h) = (b.min, b.width(), b.height());
            let mut rng = rs_testkit::XorShift64::new(5);
            let mut random = |count: usize| rng.points_around(&d, 0.1, count);
            assert!(fast.built_far_cells().is_none(), "{name}: no batch yet");
            fast.winding_numbers(&random(FAR_CELLS_MIN_POINTS - 1));
            assert!(
                fast.built_far_cells().is_none(),
                "{name}: too few points yet"
            );
            fast.winding_numbers(&random(1));
            let cells = fast
                .built_far_cells()
                .expect("built once enough points came");
            assert!(cells.far_share() > 0.5, "{name}: {}", cells.far_share());

            let mut points = random(30_000);
            let across = |y: f64, points: &mut Vec<Point>| {
                for k in 0..400 {
                    points.push(Point::new(lo.x - 0.05 * w + 1.1 * w * k as f64 / 399.0, y));
                }
            };
            for &(s, e) in field.open_chain_ends() {
                for y in [s.y, e.y] {
                    for y in [y.next_down(), y, y.next_up()] {
                        across(y, &mut points);
                    }
                }
            }
            for k in 0..=SIDE {
                let x = cells.lo.x + k as f64 / cells.per_unit.x;
                let y = cells.lo.y + k as f64 / cells.per_unit.y;
                for t in 0..40 {
                    let f = (t as f64 + 0.37) / 40.0;
                    points.push(Point::new(x, cells.lo.y + f * (cells.hi.y - cells.lo.y)));
                    points.push(Point::new(cells.lo.x + f * (cells.hi.x - cells.lo.x), y));
                }
            }
            for k in 0..150 * 150 {
                let (i, j) = ((k % 150) as f64 / 149.0, (k / 150) as f64 / 149.0);
                points.push(Point::new(lo.x + i * w, lo.y + j * h));
            }
            let far = points
                .iter()
                .filter(|&&q| cells.crossings(q).is_some())
                .count();
            assert!(far > points.len() / 3, "{name}: {far} of {}", points.len());

            let values = fast.winding_numbers(&points);
            let mut locations = vec![Location::Outside; points.len()];
            fast.values_into(&points[..], &mut locations);
            for (i, &q) in points.iter().enumerate() {
                let want = fast.winding_number(q);
                assert_eq!(values[i].to_bits(), want.to_bits(), "{name} {i}: {q:?}");
                let location = PointQuery::<Location>::value(&fast, q);
                assert_eq!(locations[i], location, "{name} {i}: {q:?}");
            }
        }
    }

    /// A point within the band's reach of a curve is in no far cell, even across a cell's
    /// edge from the curve's box: pieces ending a fraction of the reach short of a column's
    /// and a row's edge, queries a fraction of the reach past it (and the chain ends' rows
    /// are near).
    #[test]
    fn points_within_reach_of_a_curve_are_in_no_far_cell() {
        let reach = 1e-9;
        // Cell edges of the unit box at 2^-8 steps are exact.
        let edge = 0.5;
        let pieces: Vec<RationalBezier> = [
            segment(Point::new(0.25, 0.3), Point::new(edge - 0.3 * reach, 0.4)),
            segment(Point::new(0.7, 0.2), Point::new(0.8, edge - 0.3 * reach)),
            circular_arc(Point::new(0.3, 0.7), 0.1, 0.0, 1.0),
        ]
        .into_iter()
        .flat_map(|c| c.unwrap().to_bezier())
        .collect();
        let ends: Vec<(Point, Point)> = pieces
            .iter()
            .map(|b| (b.start_point(), b.end_point()))
            .collect();
        let cells = FarCells::new(
            Point::new(0.0, 0.0),
            Point::new(1.0, 1.0),
            reach,
            &pieces,
            &ends,
            |_| Some(0),
        )
        .unwrap();
        assert!(cells.far_share() > 0.9);
        let near = [
            Point::new(edge + 0.5 * reach, 0.4),
            Point::new(0.8, edge + 0.5 * reach),
        ];
        for q in near {
            assert!(cells.crossings(q).is_none(), "{q:?}");
        }
        for b in &pieces {
            for k in 0..=100 {
                let p = b.point_at(
                    b.param_range().0 + (b.param_range().1 - b.param_range().0) * k as f64 / 100.0,
                );
                for a in 0..8 {
                    let angle = a as f64 * std::f64::consts::FRAC_PI_4;
                    let q = Point::new(
                        p.x + 0.9 * reach * angle.cos(),
                        p.y + 0.9 * reach * angle.sin(),
                    );
                    assert!(cells.crossings(q).is_none(), "{q:?}");
                }
            }
        }
        // Far from every curve and every end's height, the cells are far.
        assert_eq!(cells.crossings(Point::new(0.9, 0.9)), Some(0));
    }
}
