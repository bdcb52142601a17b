//! Newton's method on one patch: where a ray crosses it, and the foot of a point on it.

use rs_spline::Point3;

use super::patches::Cell;
use crate::surface::{ParamSurface, Surface};

/// Newton steps at most.
const MAX_STEPS: usize = 32;

/// How far (a fraction of the cell's sides) an iterate may leave the cell: a crossing outside
/// it belongs to a neighbouring patch.
const ROOM: f64 = 0.5;

/// A crossing in a cell is kept when it lies in the cell grown by this fraction of its sides
/// (the same crossing found from two neighbouring cells is counted once by the caller).
const EDGE_SLACK: f64 = 1e-7;

/// What Newton's method found on a cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Crossing {
    /// No crossing in the cell.
    None,
    /// The ray `p + t d` meets the surface at `uv`, at `t`.
    At { uv: [f64; 2], t: f64 },
    /// The iteration did not settle: the ray is too near the patch for its crossing to be
    /// told (the caller shoots another ray).
    Unsettled,
}

/// The crossing of the ray `p + t d` with `surface` over `cell`: Newton's method on
/// `S(u, v) - p - t d = 0` from the cell's centre, the parameters held within the cell grown
/// by [`ROOM`] and within `domain` (the surface's parameter box, infinite where periodic). `scale` is the size of the part (convergence is to rounding of it).
pub(super) fn ray_crossing(
    surface: &Surface,
    cell: Cell,
    domain: Cell,
    p: Point3,
    d: Point3,
    scale: f64,
) -> Crossing {
    // Held in the surface's own parameter range too: past it a bounded surface is evaluated
    // at its end (clamped), where Newton's step would stall.
    let room = cell.grown(ROOM).intersection(&domain);
    let mut uv = cell.centre();
    let mut t = (surface.point(uv) - p).dot(d);
    let small = 64.0 * f64::EPSILON * scale;
    let mut held = 0;
    for _ in 0..MAX_STEPS {
        let [s, su, sv] = surface.first_derivatives(uv);
        let f = s - p - d * t;
        // Solve [S_u S_v -d] x = -f by Cramer's rule.
        let nd = -d;
        let det = su.dot(sv.cross(nd));
        if det == 0.0 || !det.is_finite() {
            return Crossing::Unsettled;
        }
        let g = -f;
        let du = g.dot(sv.cross(nd)) / det;
        let dv = su.dot(g.cross(nd)) / det;
        let dt = su.dot(sv.cross(g)) / det;
        let next = [uv[0] + du, uv[1] + dv];
        let clamped = room.clamp(next);
        if clamped != next {
            held += 1;
            if held >= 3 {
                return Crossing::None;
            }
        } else {
            held = 0;
        }
        uv = clamped;
        t += dt;
        let [a, b] = cell.sides();
        let tiny_step =
            du.abs() <= 1e-14 * a.max(uv[0].abs()) && dv.abs() <= 1e-14 * b.max(uv[1].abs());
        if f.length() <= small || tiny_step {
            let residual = (surface.point(uv) - p - d * t).length();
            if residual > 1e-9 * scale {
                return if cell.contains(uv) {
                    Crossing::Unsettled
                } else {
                    Crossing::None
                };
            }
            return if cell.grown(EDGE_SLACK).contains(uv) {
                Crossing::At { uv, t }
            } else {
                Crossing::None
            };
        }
    }
    if cell.contains(uv) {
        Crossing::Unsettled
    } else {
        Crossing::None
    }
}

/// The point of `surface` over `cell` nearest `p` (Gauss and Newton's method on the squared
/// distance from the cell's centre, held in the cell): its parameters and distance.
pub(super) fn foot(surface: &Surface, cell: Cell, p: Point3) -> ([f64; 2], f64) {
    let mut uv = cell.centre();
    for _ in 0..MAX_STEPS {
        let [s, su, sv] = surface.first_derivatives(uv);
        let r = s - p;
        // (J^T J) x = -J^T r.
        let (a, b, c) = (su.dot(su), su.dot(sv), sv.dot(sv));
        let (g0, g1) = (-su.dot(r), -sv.dot(r));
        let det = a * c - b * b;
        if det <= 0.0 || !det.is_finite() {
            break;
        }
        let du = (g0 * c - g1 * b) / det;
        let dv = (a * g1 - b * g0) / det;
        let next = cell.clamp([uv[0] + du, uv[1] + dv]);
        let moved = next != uv;
        let [sa, sb] = cell.sides();
        let done = (next[0] - uv[0]).abs() <= 1e-15 * sa.max(uv[0].abs())
            && (next[1] - uv[1]).abs() <= 1e-15 * sb.max(uv[1].abs());
        uv = next;
        if !moved || done {
            break;
        }
    }
    (uv, surface.point(uv).distance(p))
}
