//! The closest point of a B-spline curve to a point: a bounded search (samples per knot span,
//! golden-section search around the best local minima, Newton's method on the foot condition),
//! keeping an exact end of the window when it is as near (to rounding).

use rs_spline::{RationalBSpline, Vector};

/// Samples per non-empty knot span in the window (fewer when the window holds many spans).
const SAMPLES_PER_SPAN: usize = 16;

/// The most samples of one search; past `MAX_SAMPLES / SAMPLES_PER_SPAN` spans each span gets
/// fewer (at least its ends, which are knots).
const MAX_SAMPLES: usize = 4096;

/// Local minima of the sampled distance refined (the nearest samples first): a point almost
/// equally near two parts of the curve is decided by the refined distances, not the samples.
const REFINED_MINIMA: usize = 4;

/// Golden-section steps on a bracket of two sample intervals: `0.618^60 ~ 3e-13` of it.
const GOLDEN_STEPS: usize = 60;

/// Newton steps on the foot condition after the golden-section search (which resolves a
/// flat minimum, a point off the curve, only to about the square root of the rounding), and
/// after the polynomial roots of a conic's foot condition.
const NEWTON_STEPS: usize = 8;

/// The rounding of a computed distance, relative to the distance plus the size of the
/// coordinates it comes from (a rational point evaluated through de Boor's basis and a quotient
/// is good to some dozens of units in the last place). A Newton step may come this much farther
/// (a flat minimum's computed distance moves by its rounding while the parameter converges);
/// an exact end of the window, or a conic's closed form, this much farther than the refined
/// point is as near.
pub(crate) const DISTANCE_ROUNDING: f64 = 64.0 * f64::EPSILON;

/// The parameter in `[lo, hi]` (within the domain) of the point of `c` nearest `x`.
pub(crate) fn bspline_closest_parameter<P>(
    c: &RationalBSpline<P>,
    x: P,
    (lo, hi): (f64, f64),
) -> f64
where
    P: Vector + std::ops::Div<f64, Output = P>,
{
    let distance = |t: f64| c.point_at(t).distance_to(x);
    let ts = samples(c, lo, hi);
    let ds: Vec<f64> = ts.iter().map(|&t| distance(t)).collect();
    // Sample local minima, nearest first.
    let mut minima: Vec<usize> = (0..ts.len())
        .filter(|&i| (i == 0 || ds[i] <= ds[i - 1]) && (i + 1 == ts.len() || ds[i] <= ds[i + 1]))
        .collect();
    minima.sort_by(|&i, &j| ds[i].total_cmp(&ds[j]));
    minima.truncate(REFINED_MINIMA);
    let mut best = (f64::INFINITY, lo);
    for i in minima {
        let (a, b) = (ts[i.saturating_sub(1)], ts[(i + 1).min(ts.len() - 1)]);
        let t = foot_newton(|t| c.derivatives(t), x, golden(&distance, a, b), (a, b));
        let d = distance(t);
        if d < best.0 {
            best = (d, t);
        }
    }
    // An exact end of the window wins unless the refined point is nearer by more than
    // rounding (a vertex at the end of an edge is the common case; the curve may pass the same
    // point again inside, as on a seam).
    let slack = best.0 + DISTANCE_ROUNDING * (best.0 + c.point_at(best.1).norm());
    let (d_lo, d_hi) = (distance(lo), distance(hi));
    if d_lo <= slack && d_lo <= d_hi {
        lo
    } else if d_hi <= slack {
        hi
    } else {
        best.1
    }
}

/// The sample parameters in `[lo, hi]`: its ends, the knots inside it, and evenly spaced points
/// within each span, ascending.
fn samples<P: Vector + std::ops::Div<f64, Output = P>>(
    c: &RationalBSpline<P>,
    lo: f64,
    hi: f64,
) -> Vec<f64> {
    let mut cuts = vec![lo];
    for &k in c.knots().knots() {
        if k > lo && k < hi && cuts.last() != Some(&k) {
            cuts.push(k);
        }
    }
    cuts.push(hi);
    let spans = cuts.len() - 1;
    let per_span = (MAX_SAMPLES / spans).clamp(1, SAMPLES_PER_SPAN);
    let mut ts = Vec::with_capacity(spans * per_span + 1);
    for w in cuts.windows(2) {
        let h = (w[1] - w[0]) / per_span as f64;
        ts.extend((0..per_span).map(|i| w[0] + h * i as f64));
    }
    ts.push(hi);
    ts
}

/// Golden-section search for the minimum of `f` on `[a, b]`.
fn golden(f: &impl Fn(f64) -> f64, a: f64, b: f64) -> f64 {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (a, b);
    for _ in 0..GOLDEN_STEPS {
        let m1 = hi - g * (hi - lo);
        let m2 = lo + g * (hi - lo);
        if f(m1) < f(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    0.5 * (lo + hi)
}

/// Newton's method on the foot condition `g(t) = (C(t) - x) . C'(t) = 0` from `t` within
/// `[a, b]` (`g' = |C'|^2 + (C - x) . C''`, `derivatives(t) = [C, C', C'']`): each step is kept
/// only if it lowers `|g|` and comes no farther from `x` than rounding allows (at a minimum the
/// distance is flat: its computed value moves by rounding, its parameter does not).
pub(crate) fn foot_newton<P: Vector>(
    derivatives: impl Fn(f64) -> [P; 3],
    x: P,
    t: f64,
    (a, b): (f64, f64),
) -> f64 {
    let foot = |t: f64| {
        let [p, d1, d2] = derivatives(t);
        let r = p - x;
        (r.dot(d1), d1.dot(d1) + r.dot(d2), r.norm(), p.norm())
    };
    let mut t = t;
    let (mut g, mut dg, mut d, mut size) = foot(t);
    for _ in 0..NEWTON_STEPS {
        if dg.is_nan() || dg <= 0.0 {
            break;
        }
        let next = (t - g / dg).clamp(a, b);
        if next == t {
            break;
        }
        let (gn, dgn, dn, sn) = foot(next);
        if !(gn.abs() < g.abs() && dn <= d + DISTANCE_ROUNDING * (d + size.max(sn))) {
            break;
        }
        (t, g, dg, d, size) = (next, gn, dgn, dn, sn);
    }
    t
}
