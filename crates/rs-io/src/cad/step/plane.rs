//! Faces on a `PLANE` without pcurves: their 3-D edge curves mapped into the plane's
//! `(u, v) = ((X - P) . x, (X - P) . y)` (`y = axis x x_dir`), an affine map of the control
//! points, so lines, conics and B-splines stay exact. A curve that leaves the plane is an
//! error, never projected.

use super::curves::Curve;
use super::geom::{Frame, dot, sub};

/// Samples on a curve checked against the plane (conics are planar, so a few points that are
/// in the plane put the whole conic there; B-spline control points are checked all).
const SAMPLES: usize = 16;

/// Checks that the curve on `[lo, hi]` lies in the plane within `tol`.
pub(crate) fn check_in_plane(
    c: &Curve,
    lo: f64,
    hi: f64,
    f: &Frame,
    tol: f64,
) -> Result<(), String> {
    let off = |p: [f64; 3]| dot(sub(p, f.origin), f.z).abs();
    let worst = match c {
        Curve::Spline(s) => s.points.iter().map(|&p| off(p)).fold(0.0, f64::max),
        _ => (0..=SAMPLES)
            .map(|i| off(c.point(lo + (hi - lo) * i as f64 / SAMPLES as f64)))
            .fold(0.0, f64::max),
    };
    if worst > tol {
        return Err(format!(
            "its 3-D curve leaves the face's plane by {worst:.3e} (more than the tolerance {tol:.3e})"
        ));
    }
    Ok(())
}
