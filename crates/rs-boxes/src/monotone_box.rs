//! Monotone boxes: pieces of the boundary on which both coordinates are monotone.

use rs_spline::Point;

use crate::BezierPiece;

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
    /// The piece of boundary.
    pub piece: BezierPiece,
    /// Index of the domain curve it comes from.
    pub curve: usize,
    /// Index of the boundary loop it belongs to.
    pub boundary_loop: usize,
    /// Its parameter interval in the NURBS parameter of that curve.
    pub param_range: (f64, f64),
    /// `C` at the start of the piece.
    pub start: Point,
    /// `C` at the end of the piece.
    pub end: Point,
    /// `min(start.x, end.x)`.
    pub xmin: f64,
    /// `max(start.x, end.x)`.
    pub xmax: f64,
    /// `min(start.y, end.y)`.
    pub ymin: f64,
    /// `max(start.y, end.y)`.
    pub ymax: f64,
    /// Direction of `x(t)`.
    pub x_dir: Monotonicity,
    /// Direction of `y(t)`.
    pub y_dir: Monotonicity,
}

impl MonotoneBox {
    /// Builds the box of a monotone piece. Directions come from the end points; a piece whose
    /// control points share one x (y) is constant in x (y) exactly.
    pub fn new(
        piece: BezierPiece,
        curve: usize,
        boundary_loop: usize,
        param_range: (f64, f64),
    ) -> Self {
        let (start, end) = (piece.start(), piece.end());
        let x_dir = if piece.is_constant(0) {
            Monotonicity::Constant
        } else {
            Monotonicity::of(start.x, end.x)
        };
        let y_dir = if piece.is_constant(1) {
            Monotonicity::Constant
        } else {
            Monotonicity::of(start.y, end.y)
        };
        Self {
            piece,
            curve,
            boundary_loop,
            param_range,
            start,
            end,
            xmin: start.x.min(end.x),
            xmax: start.x.max(end.x),
            ymin: start.y.min(end.y),
            ymax: start.y.max(end.y),
            x_dir,
            y_dir,
        }
    }

    /// True if `p` lies in the box grown by `tol` on every side.
    pub fn contains_with(&self, p: Point, tol: f64) -> bool {
        p.x >= self.xmin - tol
            && p.x <= self.xmax + tol
            && p.y >= self.ymin - tol
            && p.y <= self.ymax + tol
    }

    /// True if `p` is within `tol` of the piece, measured along a vertical or a horizontal line
    /// (or from an end point). For a monotone piece this catches every point at Euclidean
    /// distance `<= tol / sqrt(2)` and none farther than `tol`.
    pub fn is_near(&self, p: Point, tol: f64) -> bool {
        if !self.contains_with(p, tol) {
            return false;
        }
        if p.distance(self.start) <= tol || p.distance(self.end) <= tol {
            return true;
        }
        // Vertical distance (a vertical piece is covered by the horizontal distance and the
        // end points, and vice versa).
        if self.x_dir != Monotonicity::Constant && p.x >= self.xmin && p.x <= self.xmax {
            if let Some(t) = self.piece.solve_x(p.x) {
                if (self.piece.y_at(t) - p.y).abs() <= tol {
                    return true;
                }
            }
        }
        if self.y_dir != Monotonicity::Constant && p.y >= self.ymin && p.y <= self.ymax {
            if let Some(t) = self.piece.solve_y(p.y) {
                if (self.piece.x_at(t) - p.x).abs() <= tol {
                    return true;
                }
            }
        }
        false
    }
}
