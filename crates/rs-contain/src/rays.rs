//! One monotone box against one ray: a signed crossing, a miss, or the boundary.
//!
//! # Why signed crossings give the winding number
//! Let `C` be closed loops, `p` a point off `C`, and `R` the downward ray from `p`. Moving `R`
//! an infinitesimal distance to the right (the half-open rule below) changes no winding
//! number (`p` is off `C`) and makes `R` miss every end point of every monotone piece. The
//! winding number `w(p)` is the degree of `t -> (C(t) - p) / |C(t) - p|` onto the unit circle,
//! and the number of preimages of the regular value "straight down" counted with their signs
//! is that degree: each piece that is not vertical meets `R` at most once (its `x` is
//! strictly monotone), transversally, and a piece crossing below `p` in the `+x` direction
//! turns counter-clockwise about `p` there (`+1`), one in the `-x` direction clockwise (`-1`).
//! So `w(p)` is the sum of the signed crossings, whatever the loops: nested, overlapping, or
//! crossing themselves. Its parity is the crossing parity, so counting signs changes no
//! even-odd answer; the non-zero rule reads the same sum. The leftward horizontal ray is
//! the same argument turned by a quarter: a piece crossing left of `p` in the `-y` direction
//! counts `+1`.

use rs_boxes::{MonotoneBox, Monotonicity};
use rs_spline::Point;

/// The outcome of testing a ray from a point against one box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Hit {
    /// The point is within the tolerance of the box's piece.
    Boundary,
    /// The ray crosses the piece, adding `+1` or `-1` to the winding number (module docs).
    Cross(i64),
    /// It does not.
    Miss,
}

/// What a crossing of the downward ray adds to the winding number: `+1` where the piece runs
/// in the `+x` direction (module docs; [`rs_boxes::ChordBand::x_sign`]).
#[inline]
pub(crate) fn downward_sign(b: &MonotoneBox) -> i64 {
    b.band.x_sign()
}

/// The downward vertical ray `{x = p.x, y < p.y}` against box `b`: boundary if `p` is near
/// the piece, otherwise [`MonotoneBox::crosses_below`] (half-open rule, see there).
pub(crate) fn vertical(b: &MonotoneBox, p: Point, tol: f64) -> Hit {
    if b.is_near(p, tol) {
        Hit::Boundary
    } else if b.crosses_below(p) {
        Hit::Cross(downward_sign(b))
    } else {
        Hit::Miss
    }
}

/// The leftward horizontal ray `{y = p.y, x < p.x}` against box `b`, with the half-open rule
/// `ymin <= p.y < ymax` (see [`vertical`]); a crossing of a piece running in the `-y`
/// direction adds `+1`.
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
    let cross = Hit::Cross(if b.y_dir == Monotonicity::Decreasing {
        1
    } else {
        -1
    });
    if p.x > b.band.xmax {
        return cross;
    }
    match b.at_y(p.y).map(|(_, x)| x) {
        Some(x) if x < p.x => cross,
        Some(x) if x > p.x => Hit::Miss,
        _ => Hit::Boundary,
    }
}

/// The winding number of the closed boundary made of `boxes` at a point, as the signed
/// crossings of a ray over them, or `None` if the point is on the boundary.
pub(crate) fn winding<'a>(
    boxes: impl IntoIterator<Item = &'a MonotoneBox>,
    hit: impl Fn(&MonotoneBox) -> Hit,
) -> Option<i64> {
    let mut w = 0;
    for b in boxes {
        match hit(b) {
            Hit::Boundary => return None,
            Hit::Cross(s) => w += s,
            Hit::Miss => {}
        }
    }
    Some(w)
}
