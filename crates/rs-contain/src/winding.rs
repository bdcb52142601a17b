//! The winding-number fallback, exact up to rounding.

use std::f64::consts::TAU;

use rs_boxes::{BezierPiece, MonotoneBox};
use rs_spline::Point;

/// Subdivision depth cap; a piece `2^-60` of a box is far below any tolerance.
const MAX_DEPTH: u32 = 60;

/// The winding number of the boundary about `p` (a point not on the boundary), as a real
/// number that is an integer up to rounding.
///
/// The paper integrates `d(angle)` by Gaussian quadrature, which is hard near the boundary. We
/// use instead that a monotone piece lies in the rectangle spanned by its end points: if `p` is
/// outside that rectangle, the piece and its chord are homotopic in the plane minus `p`, so the
/// piece subtends exactly the chord's angle `atan2(a x b, a . b)` with `a = start - p`,
/// `b = end - p`. Pieces whose rectangle holds `p` are halved (they stay monotone) until it no
/// longer does, which happens after about `log2(size / distance)` levels.
pub(crate) fn winding_number<'a>(
    boxes: impl IntoIterator<Item = &'a MonotoneBox>,
    p: Point,
) -> f64 {
    let total: f64 = boxes
        .into_iter()
        .map(|b| piece_angle(&b.piece, b.start, b.end, p, 0))
        .sum();
    total / TAU
}

fn piece_angle(piece: &BezierPiece, start: Point, end: Point, p: Point, depth: u32) -> f64 {
    let inside_rect = p.x >= start.x.min(end.x)
        && p.x <= start.x.max(end.x)
        && p.y >= start.y.min(end.y)
        && p.y <= start.y.max(end.y);
    if !inside_rect || depth >= MAX_DEPTH {
        let (a, b) = (start - p, end - p);
        return a.cross(b).atan2(a.dot(b));
    }
    let (l, r) = piece.split(0.5);
    let mid = l.end();
    piece_angle(&l, start, mid, p, depth + 1) + piece_angle(&r, mid, end, p, depth + 1)
}
