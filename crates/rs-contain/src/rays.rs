//! One monotone box against one ray: crossing, miss, or boundary.

use rs_boxes::{MonotoneBox, Monotonicity};
use rs_spline::Point;

/// The outcome of testing a ray from a point against one box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Hit {
    /// The point is within the tolerance of the box's piece.
    Boundary,
    /// The ray crosses the piece.
    Cross,
    /// It does not.
    Miss,
}

/// The downward vertical ray `{x = p.x, y < p.y}` against box `b`: boundary if `p` is near
/// the piece, otherwise [`MonotoneBox::crosses_below`] (half-open rule, see there).
pub(crate) fn vertical(b: &MonotoneBox, p: Point, tol: f64) -> Hit {
    if b.is_near(p, tol) {
        Hit::Boundary
    } else if b.crosses_below(p) {
        Hit::Cross
    } else {
        Hit::Miss
    }
}

/// The leftward horizontal ray `{y = p.y, x < p.x}` against box `b`, with the half-open rule
/// `ymin <= p.y < ymax` (see [`vertical`]).
pub(crate) fn horizontal(b: &MonotoneBox, p: Point, tol: f64) -> Hit {
    if b.is_near(p, tol) {
        return Hit::Boundary;
    }
    if b.y_dir == Monotonicity::Constant
        || !(b.band.ymin <= p.y && p.y < b.band.ymax)
        || p.x < b.band.xmin
    {
        return Hit::Miss;
    }
    if p.x > b.band.xmax {
        return Hit::Cross;
    }
    match b.at_y(p.y).map(|(_, x)| x) {
        Some(x) if x < p.x => Hit::Cross,
        Some(x) if x > p.x => Hit::Miss,
        _ => Hit::Boundary,
    }
}

/// Crossing parity of a ray over `boxes`, or `None` if the point is on the boundary.
pub(crate) fn parity<'a>(
    boxes: impl IntoIterator<Item = &'a MonotoneBox>,
    hit: impl Fn(&MonotoneBox) -> Hit,
) -> Option<bool> {
    let mut odd = false;
    for b in boxes {
        match hit(b) {
            Hit::Boundary => return None,
            Hit::Cross => odd = !odd,
            Hit::Miss => {}
        }
    }
    Some(odd)
}
