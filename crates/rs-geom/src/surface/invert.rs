//! The closest-point searches shared by the surfaces without a closed form.
//!
//! - [`newton`]: minimises `|S(u, v) - x|^2` by Newton's method on its gradient `(r . S_u, r
//!   . S_v)` (`r = S - x`) with the full Hessian (`S_i . S_j + r . S_ij`, the analytic second
//!   derivatives), damped as Levenberg and Marquardt do where the Hessian is not positive or a
//!   step does not bring the surface nearer; bounded parameters stay in their box (a
//!   parameter at its bound with the gradient pushing outwards is held there), periodic ones
//!   are free. At most [`MAX_NEWTON_STEPS`] steps, each trying at most [`MAX_DAMPINGS`]
//!   dampings.
//! - [`closest`]: [`newton`] from `near`, from given starts and from the best nodes (at most
//!   [`MAX_GRID_STARTS`] local minima) of a sampling grid (at most [`MAX_GRID_SIDE`] values a
//!   side); the nearest result is kept, of results at the same distance the one nearest
//!   `near`. A start at `near` that lands on the surface ends the search.
//! - [`minimize_1d`]: the minimum of a function of one parameter from samples: the best
//!   samples' neighbouring intervals are searched for a zero of the derivative with a
//!   bracketed (safeguarded) Newton iteration of at most [`MAX_1D_STEPS`] steps.

use rs_spline::Point3;

use super::{Inversion, ParamSurface, finish, nearest_copy, usable_near};

/// The most Newton steps of one search from one start (it converges quadratically in a handful
/// from a good start; the bound stops one that does not).
pub(crate) const MAX_NEWTON_STEPS: usize = 64;

/// The most dampings tried for one Newton step (each multiplies the damping by 10, from
/// [`FIRST_DAMPING`]: 10^-6 to 10^10 times the squared derivatives).
pub(crate) const MAX_DAMPINGS: usize = 17;

/// The first damping tried when the undamped step fails, relative to `|S_u|^2` and `|S_v|^2`.
const FIRST_DAMPING: f64 = 1e-6;

/// The most local minima of the sampling grid searched from.
pub(crate) const MAX_GRID_STARTS: usize = 6;

/// The most sample values of one parameter (a grid has at most the square).
pub(crate) const MAX_GRID_SIDE: usize = 64;

/// The most steps of the 1-D search in one interval (it halves the interval at worst: 100
/// halvings exhaust any double interval).
pub(crate) const MAX_1D_STEPS: usize = 100;

/// Results whose distances differ by less than this fraction of the surface's size are at the
/// same distance (the one nearest `near` is kept): a few roundings of a distance.
const TIE_RELATIVE: f64 = 1e-12;

/// A start at `near` whose result is within this fraction of the surface's size of the point
/// has found it: no other result can be nearer by more than rounding.
const ON_SURFACE_RELATIVE: f64 = 1e-14;

/// A Newton step that moves the point by less than this many units in the last place of the
/// coordinates has converged.
const STEP_ULPS: f64 = 4.0;

/// A gradient component `r . S_i` below this many units in the last place of the coordinates
/// times the larger `|S_j|` is rounding: the distance is stationary along that parameter.
const STATIONARY_ULPS: f64 = 16.0;

/// The closest point found by [`newton`] from `near` (if any), from `starts`, and from the
/// best nodes of the grid `grid` (values of `u` by values of `v`); of results at the same
/// distance, the one nearest `near`; periodic parameters placed by [`finish`]. `size` is the
/// surface's length scale (for the tolerances). `x` must be finite.
pub(crate) fn closest<S: ParamSurface + ?Sized>(
    s: &S,
    x: Point3,
    near: Option<[f64; 2]>,
    starts: &[[f64; 2]],
    grid: Option<&[Vec<f64>; 2]>,
    size: f64,
) -> Inversion {
    let near = usable_near(near);
    let size = size.max(f64::MIN_POSITIVE);
    let mut found: Vec<([f64; 2], f64)> = Vec::new();
    let run = |start: [f64; 2], found: &mut Vec<([f64; 2], f64)>| {
        let uv = newton(s, x, start);
        let d = s.point(uv).distance(x);
        found.push((uv, if d.is_nan() { f64::INFINITY } else { d }));
        d
    };
    if let Some(n) = near
        && run(n, &mut found) <= ON_SURFACE_RELATIVE * size
    {
        return finish(s, x, found[0].0, near);
    }
    for &start in starts {
        if start.iter().all(|t| t.is_finite()) {
            run(start, &mut found);
        }
    }
    if let Some(grid) = grid {
        for start in grid_starts(s, x, grid) {
            run(start, &mut found);
        }
    }
    let Some(best) = found.iter().map(|f| f.1).min_by(f64::total_cmp) else {
        let uv = near.unwrap_or_else(|| s.param_box().clamp([0.0, 0.0]));
        return finish(s, x, uv, near);
    };
    let tie = best + TIE_RELATIVE * size;
    let periods = s.periods();
    let lengths = s.param_box().lengths();
    let gap = |uv: [f64; 2]| -> f64 {
        let Some(n) = near else { return 0.0 };
        (0..2)
            .map(|i| {
                let t = periods[i].map_or(uv[i], |p| nearest_copy(uv[i], n[i], p));
                let l = if lengths[i].is_finite() && lengths[i] > 0.0 {
                    lengths[i]
                } else {
                    1.0
                };
                ((t - n[i]) / l).abs()
            })
            .sum()
    };
    let uv = found
        .iter()
        .filter(|f| f.1 <= tie)
        .min_by(|a, b| gap(a.0).total_cmp(&gap(b.0)))
        .map_or(found[0].0, |f| f.0);
    finish(s, x, uv, near)
}

/// The grid nodes (at most [`MAX_GRID_STARTS`]) that are local minima of the distance to
/// `x`, nearest first.
fn grid_starts<S: ParamSurface + ?Sized>(s: &S, x: Point3, grid: &[Vec<f64>; 2]) -> Vec<[f64; 2]> {
    let (us, vs) = (&grid[0], &grid[1]);
    let (m, n) = (us.len(), vs.len());
    if m == 0 || n == 0 {
        return Vec::new();
    }
    let dist: Vec<f64> = us
        .iter()
        .flat_map(|&u| vs.iter().map(move |&v| [u, v]))
        .map(|uv| {
            let d = s.point(uv).distance(x);
            if d.is_nan() { f64::INFINITY } else { d }
        })
        .collect();
    let at = |i: usize, j: usize| dist[i * n + j];
    let mut minima: Vec<(f64, usize, usize)> = Vec::new();
    for i in 0..m {
        for j in 0..n {
            let d = at(i, j);
            let lowest = (i.saturating_sub(1)..(i + 2).min(m))
                .all(|a| (j.saturating_sub(1)..(j + 2).min(n)).all(|b| at(a, b) >= d));
            if lowest {
                minima.push((d, i, j));
            }
        }
    }
    minima.sort_by(|a, b| a.0.total_cmp(&b.0));
    minima
        .into_iter()
        .take(MAX_GRID_STARTS)
        .map(|(_, i, j)| [us[i], vs[j]])
        .collect()
}

/// A local minimum of `|S(u, v) - x|^2` from `start` (see the module documentation): bounded
/// parameters clamped to the parameter box, periodic ones free.
pub(crate) fn newton<S: ParamSurface + ?Sized>(s: &S, x: Point3, start: [f64; 2]) -> [f64; 2] {
    let bx = s.param_box();
    let periods = s.periods();
    let bounds: [(f64, f64); 2] = std::array::from_fn(|i| {
        if periods[i].is_some() {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            bx.range(i)
        }
    });
    let clamp = |uv: [f64; 2]| -> [f64; 2] {
        std::array::from_fn(|i| uv[i].clamp(bounds[i].0, bounds[i].1))
    };
    let mut uv = clamp(start);
    let mut d = s.derivatives(uv);
    let mut r = d.point - x;
    let mut f = r.dot(r);
    if !f.is_finite() {
        return uv;
    }
    // The size of the point's coordinates: steps below their rounding have converged.
    let coords = x.max_abs().max(d.point.max_abs());
    let mut damping = 0.0f64;
    for _ in 0..MAX_NEWTON_STEPS {
        let g = [r.dot(d.du), r.dot(d.dv)];
        let norms = [d.du.dot(d.du), d.dv.dot(d.dv)];
        let h = [
            [norms[0] + r.dot(d.duu), d.du.dot(d.dv) + r.dot(d.duv)],
            [d.du.dot(d.dv) + r.dot(d.duv), norms[1] + r.dot(d.dvv)],
        ];
        // Held: a parameter at its bound with the descent direction leaving the box, one
        // whose derivative vanishes against the other's (a pole line, where it moves nothing),
        // or one along which the distance is stationary to rounding (its gradient below the
        // rounding of r . S_i, whose S_i is computed to the rounding of the larger derivative;
        // where both are, the search has converged).
        let big = norms[0].max(norms[1]);
        let free: [bool; 2] = std::array::from_fn(|i| {
            let (a, b) = bounds[i];
            !((uv[i] <= a && g[i] > 0.0) || (uv[i] >= b && g[i] < 0.0))
                && norms[i] > super::POLE_DERIVATIVE_RATIO * super::POLE_DERIVATIVE_RATIO * big
                && g[i].abs() > STATIONARY_ULPS * f64::EPSILON * coords * big.sqrt()
        });
        if !free[0] && !free[1] {
            break;
        }
        let measure = |g: [f64; 2], norms: [f64; 2]| -> f64 {
            (0..2)
                .filter(|&i| free[i] && norms[i] > 0.0)
                .map(|i| g[i] * g[i] / norms[i])
                .sum()
        };
        let here = measure(g, norms);
        let mut moved = None;
        for _ in 0..MAX_DAMPINGS {
            if let Some(step) = solve(h, g, norms, damping, free) {
                let cand = clamp([uv[0] + step[0], uv[1] + step[1]]);
                let shift = (d.du * (cand[0] - uv[0]) + d.dv * (cand[1] - uv[1])).length();
                if cand == uv || shift <= STEP_ULPS * f64::EPSILON * coords {
                    moved = Some(false);
                    break;
                }
                let dc = s.derivatives(cand);
                let rc = dc.point - x;
                let fc = rc.dot(rc);
                // Better: nearer, or (within the rounding of the squared distance, where the
                // distance is flat) closer to stationary.
                let better = fc < f
                    || (fc <= f * (1.0 + 16.0 * f64::EPSILON)
                        && measure(
                            [rc.dot(dc.du), rc.dot(dc.dv)],
                            [dc.du.dot(dc.du), dc.dv.dot(dc.dv)],
                        ) < here);
                if better {
                    (uv, d, r, f) = (cand, dc, rc, fc);
                    damping = if damping <= FIRST_DAMPING {
                        0.0
                    } else {
                        damping * 0.1
                    };
                    moved = Some(true);
                    break;
                }
            }
            damping = if damping == 0.0 {
                FIRST_DAMPING
            } else {
                damping * 10.0
            };
        }
        if moved != Some(true) {
            break;
        }
    }
    uv
}

/// The damped Newton step `-(H + damping diag(norms))^-1 g` in the free parameters (zero in
/// the others); `None` where the damped Hessian is not positive definite.
fn solve(
    h: [[f64; 2]; 2],
    g: [f64; 2],
    norms: [f64; 2],
    damping: f64,
    free: [bool; 2],
) -> Option<[f64; 2]> {
    let floor = 1e-30 * (norms[0] + norms[1]);
    let a = h[0][0] + damping * norms[0].max(floor);
    let c = h[1][1] + damping * norms[1].max(floor);
    let step = match free {
        [true, true] => {
            let b = h[0][1];
            let det = a * c - b * b;
            if !(a > 0.0 && det > 0.0 && det.is_finite()) {
                return None;
            }
            [(b * g[1] - c * g[0]) / det, (b * g[0] - a * g[1]) / det]
        }
        [true, false] => {
            if a.is_nan() || a <= 0.0 {
                return None;
            }
            [-g[0] / a, 0.0]
        }
        [false, true] => {
            if c.is_nan() || c <= 0.0 {
                return None;
            }
            [0.0, -g[1] / c]
        }
        [false, false] => return None,
    };
    step.iter().all(|t| t.is_finite()).then_some(step)
}

/// Parameter values on `range` (finite): its ends, the `breaks` inside it (knots, ascending)
/// and `per_span` values per interval between them, at most about `max` in all (every `k`-th
/// break kept when there are more).
pub(crate) fn sample_params(
    range: (f64, f64),
    breaks: &[f64],
    per_span: usize,
    max: usize,
) -> Vec<f64> {
    let (a, b) = range;
    if !(a.is_finite() && b.is_finite()) || b <= a {
        return if a.is_finite() { vec![a] } else { Vec::new() };
    }
    let mut knots = vec![a];
    let inside: Vec<f64> = breaks.iter().copied().filter(|&t| t > a && t < b).collect();
    let max = max.max(2);
    let stride = inside.len().div_ceil(max).max(1);
    knots.extend(inside.iter().step_by(stride));
    knots.push(b);
    let spans = knots.len() - 1;
    let per = (max / spans).clamp(1, per_span.max(1));
    let mut out = Vec::with_capacity(spans * per + 1);
    for w in knots.windows(2) {
        for k in 0..per {
            out.push(w[0] + (w[1] - w[0]) * k as f64 / per as f64);
        }
    }
    out.push(b);
    out
}

/// The `t` minimising a squared distance given with its first two derivatives by `f(t) ->
/// [f, f', f'']` over `[samples[0], samples[last]]` (sorted, finite): the best samples (at
/// most [`MAX_GRID_STARTS`] local minima), each refined in the intervals beside it where `f'`
/// goes from negative to positive, and `near`'s interval; of values at the same distance
/// `sqrt(f)` (within `tie`), the one nearest `near`.
pub(crate) fn minimize_1d(
    f: impl Fn(f64) -> [f64; 3],
    samples: &[f64],
    near: Option<f64>,
    tie: f64,
) -> f64 {
    let Some((&first, &last)) = samples.first().zip(samples.last()) else {
        return near.unwrap_or(0.0);
    };
    let value = |t: f64| {
        let v = f(t)[0];
        if v.is_nan() { f64::INFINITY } else { v }
    };
    let vals: Vec<f64> = samples.iter().map(|&t| value(t)).collect();
    let n = samples.len();
    let mut minima: Vec<usize> = (0..n)
        .filter(|&i| (i == 0 || vals[i - 1] >= vals[i]) && (i + 1 == n || vals[i + 1] >= vals[i]))
        .collect();
    minima.sort_by(|&a, &b| vals[a].total_cmp(&vals[b]));
    minima.truncate(MAX_GRID_STARTS);
    let mut candidates: Vec<f64> = Vec::new();
    let mut intervals: Vec<(f64, f64)> = Vec::new();
    for &i in &minima {
        candidates.push(samples[i]);
        if i > 0 {
            intervals.push((samples[i - 1], samples[i]));
        }
        if i + 1 < n {
            intervals.push((samples[i], samples[i + 1]));
        }
    }
    if let Some(t) = near.filter(|t| t.is_finite()) {
        let t = t.clamp(first, last);
        candidates.push(t);
        let k = samples.partition_point(|&s| s <= t);
        if k > 0 && k < n {
            intervals.push((samples[k - 1], samples[k]));
        }
    }
    for (a, b) in intervals {
        if let Some(t) = derivative_zero(&f, a, b) {
            candidates.push(t);
        }
    }
    let scored: Vec<(f64, f64)> = candidates.iter().map(|&t| (t, value(t))).collect();
    let best = scored.iter().map(|c| c.1).fold(f64::INFINITY, f64::min);
    let limit = best.sqrt() + tie;
    let gap = |t: f64| near.map_or(0.0, |n| (t - n).abs());
    scored
        .iter()
        .filter(|c| c.1.sqrt() <= limit)
        .min_by(|a, b| gap(a.0).total_cmp(&gap(b.0)))
        .map_or(first, |c| c.0)
}

/// The zero of `f'` in `[a, b]` when `f'(a) < 0 < f'(b)` (a minimum of `f` inside), by Newton
/// steps on `f'` kept inside the shrinking bracket (bisection where a step would leave it).
fn derivative_zero(f: &impl Fn(f64) -> [f64; 3], a: f64, b: f64) -> Option<f64> {
    let (fa, fb) = (f(a)[1], f(b)[1]);
    if !(fa < 0.0 && fb > 0.0) {
        return None;
    }
    let (mut lo, mut hi) = (a, b);
    let mut t = 0.5 * (a + b);
    for _ in 0..MAX_1D_STEPS {
        let [_, g, h] = f(t);
        if g == 0.0 || g.is_nan() {
            break;
        }
        if g < 0.0 {
            lo = t;
        } else {
            hi = t;
        }
        let step = t - g / h;
        let next = if h > 0.0 && step > lo && step < hi {
            step
        } else {
            0.5 * (lo + hi)
        };
        if next == t {
            break;
        }
        let converged = (next - t).abs() <= 2.0 * f64::EPSILON * t.abs().max(next.abs());
        t = next;
        if converged || hi - lo <= 2.0 * f64::EPSILON * lo.abs().max(hi.abs()) {
            break;
        }
    }
    Some(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn samples_cover_the_range_with_its_breaks() {
        let s = sample_params((0.0, 1.0), &[0.25, 0.5], 2, 100);
        assert_eq!(s, vec![0.0, 0.125, 0.25, 0.375, 0.5, 0.75, 1.0]);
        let many: Vec<f64> = (1..1000).map(|i| f64::from(i) / 1000.0).collect();
        let s = sample_params((0.0, 1.0), &many, 4, 64);
        assert!(s.len() <= 66 && s[0] == 0.0 && *s.last().unwrap() == 1.0);
        assert!(s.windows(2).all(|w| w[0] < w[1]));
        assert!(sample_params((0.0, f64::INFINITY), &[], 4, 64).len() <= 1);
    }

    #[test]
    fn one_dimensional_minima_are_found_to_rounding() {
        // f = (t - 0.3)^2 (t + 1)^2 + 0.1 has minima at 0.3 and -1 (equal): near picks.
        let f = |t: f64| {
            let (a, b) = (t - 0.3, t + 1.0);
            [
                a * a * b * b + 0.1,
                2.0 * a * b * (a + b),
                2.0 * (a * a + b * b + 4.0 * a * b),
            ]
        };
        let samples: Vec<f64> = (0..=20).map(|i| -2.0 + 0.2 * f64::from(i)).collect();
        let t = minimize_1d(f, &samples, Some(0.0), 1e-12);
        assert!((t - 0.3).abs() < 1e-15, "{t}");
        let t = minimize_1d(f, &samples, Some(-0.8), 1e-12);
        assert!((t + 1.0).abs() < 1e-15, "{t}");
        // A minimum at the range's end.
        let g = |t: f64| [t, 1.0, 0.0];
        assert_eq!(minimize_1d(g, &[1.0, 2.0, 3.0], None, 0.0), 1.0);
        // NaN values are never chosen; no samples give near.
        let h = |t: f64| {
            if t < 0.5 {
                [f64::NAN; 3]
            } else {
                [t, 1.0, 0.0]
            }
        };
        assert_eq!(minimize_1d(h, &[0.0, 0.25, 0.5, 1.0], None, 0.0), 0.5);
        assert_eq!(minimize_1d(h, &[], Some(7.0), 0.0), 7.0);
    }
}
