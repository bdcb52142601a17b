//! Where a pcurve is cut: at the `(u, v)` of the edge's vertices on the face's surface.
//!
//! A `SURFACE_CURVE`'s 3-D curve and pcurve need not share their parameter (a 3-D rational
//! B-spline circle is not parametrised by angle, its `CIRCLE` pcurve is), so the parameters
//! of the vertices on the 3-D curve only give a nearby start. From there:
//!
//! 1. the vertex's `(u, v)`: closed forms on cylinders, cones, spheres and tori; a bounded,
//!    damped Gauss-Newton iteration (Levenberg-Marquardt, finite-difference derivatives) on
//!    B-spline surfaces and surfaces of revolution or extrusion, started from the pcurve's
//!    point at the start parameter; of the periodic copies, the one nearest that point (so
//!    on a seam the pcurve of the use decides, and at a pole, where `u` is free, the
//!    pcurve's own `u` is kept);
//! 2. the pcurve's parameter of that `(u, v)`: exact on lines and conics (of the periodic
//!    copies of an angle, the one nearest the start), a bounded Gauss-Newton iteration on
//!    B-splines.
//!
//! Each step is accepted only when it lands within the gap tolerance (the point on the
//! surface, then the pcurve through the `(u, v)`); otherwise the start parameter stays (the
//! loop's closure check then decides).

use std::f64::consts::TAU;

use super::curves::{ConicKind, Curve};
use super::geom::{V3, dist, dot, norm, sub};
use super::shape::Shape;
use super::surface::Surface;

/// The most iterations of each search (Gauss-Newton converges in a handful from a start
/// this close; the bound only stops a search that does not).
const MAX_STEPS: usize = 100;

/// How far a B-spline pcurve may be continued past its domain to reach its vertex, relative
/// to the domain's length (the vertex must still be within the gap tolerance of it).
const EXTEND: f64 = 1e-2;

/// The copy of `x` modulo `p` nearest `x0`.
fn near(x: f64, x0: f64, p: f64) -> f64 {
    let d = (x - x0 + 0.5 * p).rem_euclid(p) - 0.5 * p;
    if d.is_finite() { x0 + d } else { x }
}

/// The pieces `[a, b]` of the pcurve `c2` with their outer ends moved to the vertices `lo`
/// (at the first piece's start) and `hi` (at the last piece's end); the pieces unchanged
/// where a vertex's `(u, v)` or its pcurve parameter is not found within `gap`, or where a
/// piece would become empty.
pub(crate) fn cut_at_vertices(
    s: &Surface,
    c2: &Curve,
    pieces: Vec<(f64, f64)>,
    lo: V3,
    hi: V3,
    gap: f64,
) -> Vec<(f64, f64)> {
    let Some(shape) = &s.shape else {
        return clamped(c2, pieces);
    };
    let n = pieces.len();
    if n == 0 {
        return pieces;
    }
    let pieces = clamped(c2, pieces);
    let mut out = pieces.clone();
    if let Some(t) = vertex_param(shape, s, c2, out[0].0, lo, gap) {
        out[0].0 = t;
    }
    if let Some(t) = vertex_param(shape, s, c2, out[n - 1].1, hi, gap) {
        out[n - 1].1 = t;
    }
    if out.iter().all(|(a, b)| a < b) {
        out
    } else {
        pieces
    }
}

/// The pieces within the pcurve's B-spline domain (where the 3-D parameters, unrefined, may
/// overshoot it a little).
pub(crate) fn clamped(c2: &Curve, mut pieces: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    if let Some((a, b)) = c2.spline_domain() {
        for p in &mut pieces {
            *p = (p.0.clamp(a, b), p.1.clamp(a, b));
        }
    }
    pieces
}

/// The parameter near `t0` where the pcurve `c2` passes the `(u, v)` of the point `x`.
fn vertex_param(shape: &Shape, s: &Surface, c2: &Curve, t0: f64, x: V3, gap: f64) -> Option<f64> {
    let start = c2.point(t0);
    // Where the 3-D parameter already gives the vertex (to 1e-9 of the model's size) it
    // stays: the curves meeting there keep the ends they had, bit for bit, rather than ends
    // found by searches from different starts (a sliver face's two sides would then differ
    // by rounding and enclose a spurious area).
    if dist(eval(shape, s, [start[0], start[1]]), x) <= 1e-9 * norm(x).max(1.0) {
        return None;
    }
    let uv = surface_uv(shape, s, x, [start[0], start[1]], gap)?;
    let q = [uv[0], uv[1], 0.0];
    let t = param_near(c2, q, t0, 0)?;
    (t.is_finite() && dist(c2.point_extended(t), q) <= gap).then_some(t)
}

/// The `(u, v)` of `x` on the surface nearest `start` among the periodic copies; `None`
/// unless the surface passes within `tol` of `x` there.
pub(crate) fn surface_uv(
    shape: &Shape,
    s: &Surface,
    x: V3,
    start: [f64; 2],
    tol: f64,
) -> Option<[f64; 2]> {
    let mut uv = closed_form(shape, x, start).unwrap_or_else(|| newton(shape, s, x, start));
    for (d, p) in s.period.iter().enumerate() {
        if let Some(p) = p {
            uv[d] = near(uv[d], start[d], *p);
        }
    }
    let off = dist(eval(shape, s, uv), x);
    (uv.iter().all(|t| t.is_finite()) && off <= tol).then_some(uv)
}

/// The exact `(u, v)` of the point of an elementary surface nearest `x` (in the half-plane
/// through the axis that holds `x`); `u` of `start` where `x` is on the axis.
fn closed_form(shape: &Shape, x: V3, start: [f64; 2]) -> Option<[f64; 2]> {
    let f = match shape {
        Shape::Cylinder { f, .. }
        | Shape::Cone { f, .. }
        | Shape::Sphere { f, .. }
        | Shape::Torus { f, .. } => f,
        _ => return None,
    };
    let d = sub(x, f.origin);
    let (a, b, h) = (dot(d, f.x), dot(d, f.y), dot(d, f.z));
    let rho = a.hypot(b);
    let size = norm(d).max(f64::MIN_POSITIVE);
    let u = if rho <= 1e-14 * size {
        start[0]
    } else {
        b.atan2(a)
    };
    let v = match shape {
        Shape::Cylinder { .. } => h,
        // The nearest point of the line (r + v tan, v) to (rho, h).
        Shape::Cone { r, tan, .. } => ((rho - r) * tan + h) / (1.0 + tan * tan),
        Shape::Sphere { .. } => h.atan2(rho),
        Shape::Torus { major, .. } => h.atan2(rho - major),
        _ => return None,
    };
    Some([u, v])
}

/// The surface at `uv`, a closed B-spline direction taken modulo its period.
fn eval(shape: &Shape, s: &Surface, uv: [f64; 2]) -> V3 {
    let mut w = uv;
    for (d, x) in w.iter_mut().enumerate() {
        if let (Some(p), Some((a, _))) = (s.period[d], shape.domain(d))
            && p > 0.0
        {
            *x = a + (*x - a).rem_euclid(p);
        }
    }
    shape.point(w[0], w[1])
}

/// Minimises `|S(u, v) - x|` from `start`: Levenberg-Marquardt steps (each accepted only if
/// it brings the surface nearer `x`), bounded directions clamped to their domain.
fn newton(shape: &Shape, s: &Surface, x: V3, start: [f64; 2]) -> [f64; 2] {
    let dom = [shape.domain(0), shape.domain(1)];
    let fix = |mut uv: [f64; 2]| {
        for d in 0..2 {
            if let (None, Some((a, b))) = (s.period[d], dom[d]) {
                uv[d] = uv[d].clamp(a, b);
            }
        }
        uv
    };
    // The parameters' scales (a domain's length, 1 for angles); finite-difference steps are
    // a 1e-7 of them.
    let pscale: [f64; 2] = std::array::from_fn(|d| {
        dom[d]
            .map(|(a, b)| b - a)
            .filter(|l| *l > 0.0 && l.is_finite())
            .unwrap_or(1.0)
    });
    let h = pscale.map(|p| 1e-7 * p);
    let f = |uv: [f64; 2]| eval(shape, s, uv);
    let scale = norm(x).max(1.0);
    let mut uv = fix(start);
    let mut r = sub(f(uv), x);
    let mut e = norm(r);
    let mut lambda = 0.0f64;
    for _ in 0..MAX_STEPS {
        if e.is_nan() || e <= 1e-15 * scale {
            break;
        }
        let partial = |d: usize| {
            let (mut a, mut b) = (uv, uv);
            a[d] -= h[d];
            b[d] += h[d];
            let (a, b) = (fix(a), fix(b));
            let den = b[d] - a[d];
            let (pa, pb) = (f(a), f(b));
            [
                (pb[0] - pa[0]) / den,
                (pb[1] - pa[1]) / den,
                (pb[2] - pa[2]) / den,
            ]
        };
        let (su, sv) = (partial(0), partial(1));
        let (a, b, c) = (dot(su, su), dot(su, sv), dot(sv, sv));
        let (gu, gv) = (-dot(su, r), -dot(sv, r));
        let mu = lambda * (a + c);
        let det = (a + mu) * (c + mu) - b * b;
        let step = if det > 0.0 && det.is_finite() {
            [
                (gu * (c + mu) - b * gv) / det,
                ((a + mu) * gv - b * gu) / det,
            ]
        } else {
            [f64::NAN; 2]
        };
        let next = fix([uv[0] + step[0], uv[1] + step[1]]);
        let rn = sub(f(next), x);
        let en = norm(rn);
        if en < e {
            let moved = (next[0] - uv[0]).abs() > 1e-15 * pscale[0]
                || (next[1] - uv[1]).abs() > 1e-15 * pscale[1];
            (uv, r, e) = (next, rn, en);
            lambda = if lambda < 1e-12 { 0.0 } else { lambda * 0.1 };
            if !moved {
                break;
            }
        } else {
            lambda = if lambda == 0.0 { 1e-6 } else { lambda * 10.0 };
            if lambda > 1e8 {
                break;
            }
        }
    }
    uv
}

/// The parameter of the point `q` (`z = 0`) on the 2-D curve `c`, near `t0`: exact on lines
/// and conics, a bounded Gauss-Newton iteration on B-splines (`None` if it does not find
/// `q`'s foot). `depth` counts the trimmed curves passed (their chains are bounded when read).
fn param_near(c: &Curve, q: V3, t0: f64, depth: usize) -> Option<f64> {
    match c {
        Curve::Line { .. } => c.invert(q).ok(),
        Curve::Conic {
            kind: ConicKind::Ellipse,
            ..
        } => Some(near(c.invert(q).ok()?, t0, TAU)),
        Curve::Conic { .. } => c.invert(q).ok(),
        Curve::Trimmed { basis, .. } if depth < 8 => param_near(basis, q, t0, depth + 1),
        Curve::Trimmed { .. } => None,
        Curve::Spline(_) => {
            // The pcurve may stop a little short of its vertex (a file's pcurve whose knots
            // end before the vertex's parameter): it is then continued by its end span, by at
            // most `EXTEND` of its domain.
            let (a, b) = c.range()?;
            let (lo, hi) = (a - EXTEND * (b - a), b + EXTEND * (b - a));
            let h = 1e-7 * (b - a);
            let f = |t: f64| c.point_extended(t);
            let mut t = t0.clamp(lo, hi);
            let mut e = dist(f(t), q);
            for _ in 0..MAX_STEPS {
                let (ta, tb) = ((t - h).max(lo), (t + h).min(hi));
                let (pa, pb) = (f(ta), f(tb));
                let d = [
                    (pb[0] - pa[0]) / (tb - ta),
                    (pb[1] - pa[1]) / (tb - ta),
                    0.0,
                ];
                let dd = dot(d, d);
                if dd.is_nan() || dd <= 0.0 {
                    break;
                }
                let next = (t + dot(sub(q, f(t)), d) / dd).clamp(lo, hi);
                let en = dist(f(next), q);
                if en.is_nan() || en >= e {
                    break;
                }
                let done = (next - t).abs() <= 1e-15 * (b - a);
                (t, e) = (next, en);
                if done {
                    break;
                }
            }
            // An end within rounding of the domain's is the domain's (no sliver of extension).
            for end in [a, b] {
                if (t - end).abs() <= 1e-9 * (b - a) {
                    t = end;
                }
            }
            Some(t)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_picks_the_closest_copy() {
        assert!((near(0.1, TAU - 0.05, TAU) - (TAU + 0.1)).abs() < 1e-12);
        assert!((near(TAU - 0.1, 0.05, TAU) + 0.1).abs() < 1e-12);
        assert_eq!(near(1.0, 1.0, TAU), 1.0);
    }
}
