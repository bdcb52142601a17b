//! Monotone boxes: pieces of the boundary on which both coordinates are monotone.

use std::ops::Range;

use rs_spline::grid::GridFrame;
use rs_spline::{Axis, BoundingBox, Point};
use smallvec::SmallVec;

use crate::BezierPiece;
use crate::chord_band::{ChordBand, halving_margin};
use crate::piece::HalvedPiece;
use rs_spline::odds_map;

/// How a coordinate varies along a piece, from its start to its end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Monotonicity {
    /// Strictly increasing.
    Increasing,
    /// Strictly decreasing.
    Decreasing,
    /// Constant (a vertical piece for x, a horizontal one for y): a degenerate box.
    Constant,
}

impl Monotonicity {
    fn of(a: f64, b: f64) -> Self {
        if a < b {
            Self::Increasing
        } else if a > b {
            Self::Decreasing
        } else {
            Self::Constant
        }
    }

    /// True if the two directions are opposite or either is constant: the boundary turns back
    /// (or runs along the ray) at a point joining such pieces.
    pub fn turns_against(self, other: Self) -> bool {
        self != other || self == Self::Constant
    }
}

/// A monotone box `[xmin, xmax] x [ymin, ymax]` (paper eq. (6)): a piece of the boundary on
/// which `x(t)` and `y(t)` are both monotone, so the box is spanned by the piece's end points
/// and a vertical (horizontal) line meets the piece at most once.
#[derive(Clone, Debug, PartialEq)]
pub struct MonotoneBox {
    /// The piece of boundary (read it through [`MonotoneBox::piece`]: private so that it stays
    /// the one the band was made from).
    piece: BezierPiece,
    /// Index of the domain curve it comes from.
    pub curve: usize,
    /// Index of the boundary loop it belongs to.
    pub boundary_loop: usize,
    /// Its parameter interval in the NURBS parameter of that curve.
    pub param_range: (f64, f64),
    /// How the piece's parameter `s` maps onto `param_range` ([`MonotoneBox::nurbs_parameter`]):
    /// the odds `tau / (1 - tau)` of the fraction `tau` of the range are `odds` times
    /// `s / (1 - s)`. 1 (the map is linear) unless the piece was reparametrised to balance
    /// its end weights ([`rs_spline::BALANCE_RATIO`]).
    pub odds: f64,
    /// The piece's end points `C(u0)`, `C(u1)`, their rectangle `[xmin, xmax] x [ymin, ymax]`
    /// (the box), and the band round its chord that decides most containment queries without a
    /// solve ([`MonotoneBox::is_near`], [`MonotoneBox::crosses_below`]).
    pub band: ChordBand,
    /// Direction of `x(t)`.
    pub x_dir: Monotonicity,
    /// Direction of `y(t)`.
    pub y_dir: Monotonicity,
}

/// Halving depth cap of [`MonotoneBox::for_cells_near`].
const MAX_REGISTER_DEPTH: u32 = 24;

/// What [`MonotoneBox::for_grid_parts`] halves a piece of degree <= 7 against.
struct HalvedParts<'a> {
    frame: &'a GridFrame,
    /// The parts wanted meet these columns of the frame; a half whose end points' rectangle,
    /// grown by `reach`, meets none of them is not visited.
    columns: Range<usize>,
    reach: f64,
    /// The box's own band (its only part when it spans at most two cells each way).
    band: ChordBand,
    vertical: bool,
    margin: f64,
}

impl HalvedParts<'_> {
    /// Calls `f` with the parts of `piece` (at halving depth `depth`) in order, depth first,
    /// the left half before the right: the parts and order of the `BezierPiece::split` stack.
    /// The recursion is at most `MAX_REGISTER_DEPTH` deep. `piece` is halved in place (it is
    /// left as the last left half).
    fn visit<F: FnMut(ChordBand, bool)>(&self, piece: &mut HalvedPiece, depth: u32, f: &mut F) {
        let part = BoundingBox::from_point(piece.start()).including(piece.end());
        let (g0, g1) = (
            self.frame.col(part.min.x - self.reach),
            self.frame.col(part.max.x + self.reach),
        );
        if g1 < self.columns.start || g0 >= self.columns.end {
            return;
        }
        // The stopping test is on the part itself, not grown by a tolerance: a tolerance
        // wider than a cell must not make the halving run to its cap.
        let (c0, c1, r0, r1) = self.frame.cell_range(part);
        let small = c1 - c0 <= 1 && r1 - r0 <= 1;
        if depth == 0 && small {
            f(self.band, true);
        } else if small || depth >= MAX_REGISTER_DEPTH {
            let (xs, ys) = (piece.xs(), piece.ys());
            let control = |i: usize| Point::new(xs[i], ys[i]);
            f(
                ChordBand::of_controls(xs.len(), control, self.vertical, self.margin),
                false,
            );
        } else {
            let mut right = piece.halve();
            self.visit(piece, depth + 1, f);
            self.visit(&mut right, depth + 1, f);
        }
    }
}

impl MonotoneBox {
    /// Calls `f` with every cell of `frame` that holds a point within `abs_tol` of the box's curve
    /// (some cells twice): those of each of [`MonotoneBox::for_grid_parts`]'s parts'
    /// [`ChordBand::rectangle_near`]. The cells follow the curve, not the box: their number
    /// grows with the curve's length in cells, not with the box's area.
    pub fn for_cells_near(&self, frame: &GridFrame, abs_tol: f64, mut f: impl FnMut(usize)) {
        self.for_grid_parts(frame, |part, _| {
            frame.for_cells_in(part.rectangle_near(abs_tol), &mut f)
        });
    }

    /// Calls `f` with the chord band of each part of the piece, in order from its start, halved
    /// until each part's end-point rectangle spans at most two cells of `frame` each way (or 24
    /// halvings), and whether that part is the whole piece. A monotone part lies in the
    /// rectangle of its end points, and the parts share out the box's abscissas `[xmin, xmax)`
    /// exactly (consecutive parts share their end point bit for bit). A part's band carries a
    /// margin covering the halving's rounding, so what it decides holds for this box's curve.
    pub fn for_grid_parts(&self, frame: &GridFrame, f: impl FnMut(ChordBand, bool)) {
        self.for_grid_parts_near(frame, 0..frame.columns(), 0.0, f);
    }

    /// [`MonotoneBox::for_grid_parts`]'s parts that may lie within `reach` of the columns
    /// `columns` of `frame`, the same parts in the same order, with at least every part whose
    /// end points' rectangle grown by `reach` meets those columns (more may come): a half
    /// lying farther from them is not halved further. `reach` must cover the halving's
    /// rounding (a part lies in its half's end-point rectangle up to it): a cell width is
    /// plenty.
    pub fn for_grid_parts_near(
        &self,
        frame: &GridFrame,
        columns: Range<usize>,
        reach: f64,
        mut f: impl FnMut(ChordBand, bool),
    ) {
        let vertical = self.x_dir == Monotonicity::Constant;
        let margin = halving_margin(&self.piece);
        // Degree <= 7 (every piece in practice): halve fixed-size copies, which give the very
        // control points of `BezierPiece::split(0.5)` (so the very parts and bands) without
        // its SmallVec copies and moves.
        if let Some(mut whole) = HalvedPiece::of(&self.piece) {
            let parts = HalvedParts {
                frame,
                columns,
                reach,
                band: self.band,
                vertical,
                margin,
            };
            parts.visit(&mut whole, 0, &mut f);
            return;
        }
        let mut stack: SmallVec<[(BezierPiece, u32); 16]> = SmallVec::new();
        stack.push((self.piece.clone(), 0));
        while let Some((piece, depth)) = stack.pop() {
            let part = BoundingBox::from_point(piece.start()).including(piece.end());
            // The stopping test is on the part itself, not grown by a tolerance: a tolerance
            // wider than a cell must not make the halving run to its cap.
            let (c0, c1, r0, r1) = frame.cell_range(part);
            if depth == 0 && c1 - c0 <= 1 && r1 - r0 <= 1 {
                f(self.band, true);
            } else if (c1 - c0 <= 1 && r1 - r0 <= 1) || depth >= MAX_REGISTER_DEPTH {
                f(ChordBand::of_piece(&piece, vertical, margin), false);
            } else {
                let (left, right) = piece.split(0.5);
                stack.push((right, depth + 1));
                stack.push((left, depth + 1));
            }
        }
    }

    /// Builds the box of a monotone piece. Directions come from the end points; a piece whose
    /// control points share one x (y) is constant in x (y) exactly.
    pub(crate) fn new(
        piece: BezierPiece,
        curve: usize,
        boundary_loop: usize,
        param_range: (f64, f64),
        odds: f64,
    ) -> Self {
        let (start, end) = (piece.start(), piece.end());
        let x_dir = if piece.is_constant(Axis::X) {
            Monotonicity::Constant
        } else {
            Monotonicity::of(start.x, end.x)
        };
        let y_dir = if piece.is_constant(Axis::Y) {
            Monotonicity::Constant
        } else {
            Monotonicity::of(start.y, end.y)
        };
        let band = ChordBand::of_piece(&piece, x_dir == Monotonicity::Constant, 0.0);
        Self {
            piece,
            curve,
            boundary_loop,
            param_range,
            odds,
            band,
            x_dir,
            y_dir,
        }
    }

    /// The NURBS parameter of the curve [`MonotoneBox::curve`] at the piece's parameter `s`
    /// (`0 <= s <= 1`): `u0 + tau (u1 - u0)` over [`MonotoneBox::param_range`], with `tau = s`
    /// unless the piece was reparametrised ([`MonotoneBox::odds`]); exactly `u0` and `u1` at
    /// the ends.
    pub fn nurbs_parameter(&self, s: f64) -> f64 {
        let (u0, u1) = self.param_range;
        if s == 0.0 {
            u0
        } else if s == 1.0 {
            u1
        } else {
            u0 + odds_map(self.odds, s) * (u1 - u0)
        }
    }

    /// The piece (its control points `P_0` and `P_n` are the band's `start` and `end` bit for
    /// bit): the rational Bezier curve that [`MonotoneBox::point_at`], [`MonotoneBox::at_x`]
    /// and [`MonotoneBox::at_y`] evaluate, for callers that integrate along it.
    pub fn piece(&self) -> &BezierPiece {
        &self.piece
    }

    /// The piece's point at local parameter `t` in `[0, 1]` (exactly the band's `start` and
    /// `end` at `t = 0` and `t = 1`). The curve parameter is
    /// `u0 + t (u1 - u0)` with `(u0, u1) = param_range`.
    pub fn point_at(&self, t: f64) -> Point {
        self.piece.point_at(t)
    }

    /// Where the piece meets the vertical line at abscissa `x`: its local parameter `t` and
    /// ordinate `y(t)`, by one bracketed solve of `x(t) = x` (at most one root, the piece being
    /// monotone). `None` if `x` is outside `[xmin, xmax]`.
    pub fn at_x(&self, x: f64) -> Option<(f64, f64)> {
        self.piece.solve_x(x).map(|t| (t, self.piece.y_at(t)))
    }

    /// Where the piece meets the horizontal line at ordinate `y`: its local parameter `t` and
    /// abscissa `x(t)` (see [`MonotoneBox::at_x`]).
    pub fn at_y(&self, y: f64) -> Option<(f64, f64)> {
        self.piece.solve_y(y).map(|t| (t, self.piece.x_at(t)))
    }

    /// True if the downward vertical ray from `p` crosses the piece, for a `p` that is not near
    /// it (see [`MonotoneBox::is_near`]). Half-open in x (`xmin <= p.x < xmax`): the ray runs an
    /// infinitesimal distance to the right of `p.x`, so a ray through a shared end point counts
    /// once where the boundary passes and zero or two times where it turns back, and vertical
    /// pieces are never crossed. Decided without a solve when `p` is above or below the piece by
    /// more than its vertical slack; otherwise by one bracketed solve of `x(t) = p.x`.
    pub fn crosses_below(&self, p: Point) -> bool {
        self.band
            .crossing_below(p)
            .unwrap_or_else(|| self.at_x(p.x).is_some_and(|(_, y)| y < p.y))
    }

    /// True if `p` lies in the box grown by `abs_tol` on every side.
    pub fn contains_with(&self, p: Point, abs_tol: f64) -> bool {
        p.x >= self.band.xmin - abs_tol
            && p.x <= self.band.xmax + abs_tol
            && p.y >= self.band.ymin - abs_tol
            && p.y <= self.band.ymax + abs_tol
    }

    /// True if `p` is within `abs_tol` of the piece, measured along a vertical or a horizontal line
    /// (or from an end point). For a monotone piece this catches every point at Euclidean
    /// distance `<= abs_tol / sqrt(2)` and none farther than `abs_tol`.
    #[inline]
    pub fn is_near(&self, p: Point, abs_tol: f64) -> bool {
        self.near_parameter(p, abs_tol).is_some()
    }

    /// Where the piece comes within `abs_tol` of `p` in the sense of [`MonotoneBox::is_near`]:
    /// the local parameter (see [`MonotoneBox::point_at`]) of the nearer end point if one is
    /// within `abs_tol`, else of the point straight below or above `p`, else of the point
    /// straight left or right of it; `None` if `p` is not near. A monotone piece passes near
    /// `p` at most once (its points between two near ones lie in their rectangle), so the
    /// parameter names that one passage.
    pub fn near_parameter(&self, p: Point, abs_tol: f64) -> Option<f64> {
        // Outside the box grown by `abs_tol`, or farther than `flatness + abs_tol` from the
        // chord segment, p is not near (decides most points without a solve).
        if !self.band.may_be_near(p, abs_tol) {
            return None;
        }
        let tol2 = abs_tol * abs_tol;
        let (ds, de) = (p - self.band.start, p - self.band.end);
        let (ds, de) = (ds.dot(ds), de.dot(de));
        if ds <= tol2 || de <= tol2 {
            return Some(if ds <= de { 0.0 } else { 1.0 });
        }
        // Vertical distance (a vertical piece is covered by the horizontal distance and the
        // end points, and vice versa).
        if self.x_dir != Monotonicity::Constant
            && p.x >= self.band.xmin
            && p.x <= self.band.xmax
            && let Some((t, y)) = self.at_x(p.x)
            && (y - p.y).abs() <= abs_tol
        {
            return Some(t);
        }
        if self.y_dir != Monotonicity::Constant
            && p.y >= self.band.ymin
            && p.y <= self.band.ymax
            && let Some((t, x)) = self.at_y(p.y)
            && (x - p.x).abs() <= abs_tol
        {
            return Some(t);
        }
        None
    }
}
