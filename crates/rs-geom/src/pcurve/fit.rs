//! Fitted pcurves: a cubic B-spline `g(s)` in `(u, v)` whose surface image follows the edge
//! `C(t(s))`, `t(s) = ta + s (tb - ta)` on the stretch, with a computed bound on
//! `D(s) = |S(g(s)) - C(t(s))|` over all of `[0, 1]`.
//!
//! # The fit
//!
//! 1. **Samples.** The edge's points are inverted on the surface in order of `s`, each from the
//!    `(u, v)` of the one before (the first from the previous edge's end or the options'
//!    `near`), periodic copies unwrapped, samples at a pole given the pole's parameter and their
//!    neighbour's free parameter. Between neighbours whose `(u, v)` step is not continuous, a
//!    midpoint is inserted: a step is continuous when it moves a periodic parameter by at most
//!    [`PERIOD_STEP`] of its period and its first-order image `S_u du + S_v dv` is at most
//!    [`JUMP_RATIO`] times the step between the feet (a jump in `(u, v)` whose feet stay
//!    together fails it; any continuous path passes it once its steps are small). A jump that
//!    survives to steps of [`MIN_STEP`] in `s`, or more than [`MAX_SAMPLES`] samples, is
//!    [`GeomError::PcurveWorkLimit`]. Every span of the fit holds at least [`DATA_PER_SPAN`]
//!    samples.
//! 2. **Least squares.** A clamped cubic on `[0, 1]` with a knot at each knot of the edge's
//!    B-spline where the edge is less than twice continuously differentiable (triple where
//!    it is only continuous), at least
//!    [`INITIAL_SPANS`] spans, its end control points the first and last samples' `(u, v)`
//!    exactly, the others minimising the squared `(u, v)` distances to the samples at their
//!    `s` (normal equations, Cholesky). Control points are clamped into the surface's box in
//!    its bounded directions, so `g` stays in it (convex hull).
//! 3. **Bound** (below). Spans whose bound exceeds the target while their fit error (the
//!    largest `D` less the largest distance of their samples from the surface, which no pcurve
//!    can beat) exceeds [`FIT_SHARE`] of the target and of that distance get a knot at their
//!    middle; at most
//!    [`MAX_ROUNDS`] rounds and [`MAX_CONTROL_POINTS`] control points. The round with the
//!    least bound is kept.
//!
//! # The bound
//!
//! On each span `[a, b]` of `g`, with `F(s) = S(g(s)) - C(t(s))`, `D = |F|` is evaluated at
//! `n + 1` equally spaced points `s_i` (step `h`), and for `s` between two of them
//! `|F(s)| <= max(D(s_i), D(s_{i+1})) + min(L1 h / 2, M2 h^2 / 8)` with
//! - `L1 >= |F'|`: `|S_u| |g_u'| + |S_v| |g_v'| + |C_s|`;
//! - `M2 >= |F''|`: `|S_uu| g_u'^2 + 2 |S_uv| |g_u'| |g_v'| + |S_vv| g_v'^2 + |S_u| |g_u''| +
//!   |S_v| |g_v''| + |C_ss|`, used only where `S` and `C` are continuously differentiable over
//!   the span (the error of linear interpolation of a function with a bounded second
//!   derivative);
//!
//! where `|g'|` and `|g''|` (per coordinate) are the largest of the span's derivative control
//! points (a polynomial B-spline's derivative is a B-spline whose control points are the
//! differences; convex hull: rigorous), the surface's derivative bounds are over the box of
//! the span's control points (which holds `g` there) and the edge's over the span's window,
//! both from [`super::bounds`]: rigorous for every surface but offsets, whose bounds are
//! estimated (twice the largest of a grid of samples). `n` is chosen so that the gap term is
//! at most [`GAP_SHARE`] of the target (or of the samples' largest distance from the surface,
//! if larger), within [`MIN_CHECKS`] per span and [`MAX_CHECKS`] per bound (beyond it the gap
//! term is larger, and stated); the kept fit's bound is computed once more with the gap term
//! sized to the largest `D` found instead (see [`TIGHT_FLOOR`]), and the smaller of the two is
//! its deviation. The bound adds [`ROUNDING`]
//! times the edge's size for the rounding of the evaluations. So the stated deviation is
//! proven up to floating-point rounding whenever the surface is not an offset
//! ([`crate::pcurve::Pcurve::rigorous`]).

use nalgebra::DMatrix;
use rs_spline::{KnotVector, NurbsCurve, ParamCurve, Point, Point3, RationalBSpline};

use super::bounds::{curve_bounds, surface_bounds};
use super::{Arc, ArcPcurve, Context, Sample, Start};
use crate::surface::{ParamBox, ParamSurface};
use crate::{Curve, GeomError};

/// The degree of fitted pcurves.
pub const DEGREE: usize = 3;

/// The most rounds of fitting and refinement.
pub const MAX_ROUNDS: usize = 16;

/// The most control points of a fitted pcurve.
pub const MAX_CONTROL_POINTS: usize = 512;

/// The most samples of the edge inverted for one stretch.
pub const MAX_SAMPLES: usize = 4096;

/// The least number of spans of a fit.
pub const INITIAL_SPANS: usize = 4;

/// The least number of samples in each span of a fit (its ends included): enough for the four
/// cubic basis functions alive there to be determined.
pub const DATA_PER_SPAN: usize = 6;

/// A step between samples is a jump when its first-order image is more than this many times
/// the step between their feet (a continuous path's ratio tends to 1 as steps shrink; a
/// quarter turn on a circle gives 1.11, a turn of pi about a pole 1.57).
pub const JUMP_RATIO: f64 = 2.0;

/// A step between samples moving a periodic parameter by more than this fraction of its period
/// is a jump (it may have taken the wrong periodic copy).
pub const PERIOD_STEP: f64 = 0.25;

/// Steps between samples no shorter than this in `s` are bisected to resolve a jump; a jump
/// still there is a discontinuity of the edge's closest points.
pub const MIN_STEP: f64 = 1e-12;

/// The share of the target deviation left to the gap term of the bound.
pub const GAP_SHARE: f64 = 0.25;

/// A span is refined while its fit error exceeds this share of the target.
pub const FIT_SHARE: f64 = 0.25;

/// The least number of check intervals per span.
pub const MIN_CHECKS: usize = 8;

/// The most evaluations of `D` for one bound.
pub const MAX_CHECKS: usize = 1 << 18;

/// The least gap goal of the final bound, as a fraction of the target: once a fit is kept,
/// its bound is computed again with the gap term sized to the largest `D` found (not less than
/// this share of the target), which costs at most `1 / sqrt` of it in more evaluations.
pub const TIGHT_FLOOR: f64 = 1e-3;

/// The rounding of an evaluated `D`, relative to the edge's size.
pub const ROUNDING: f64 = 64.0 * f64::EPSILON;

/// The fitted pcurve of the stretch `arc` with its bound (see the module documentation).
///
/// # Errors
/// [`GeomError::EdgeOffSurface`] for a sample too far from the surface;
/// [`GeomError::PcurveWorkLimit`] for a jump of the closest points; the spline layer's
/// errors.
pub(crate) fn fit(ctx: &Context<'_>, arc: &Arc, start: &Start) -> Result<ArcPcurve, GeomError> {
    let near = start.near.or(start.uv);
    let mut knots = initial_knots(&edge_breaks(ctx.edge, arc));
    let mut samples = vec![ctx.first_sample(arc, start)?];
    let mut values = knots.clone();
    values.dedup();
    values.push(1.0);
    for s in values {
        let previous = samples[samples.len() - 1].uv;
        samples.push(ctx.sample(arc, s, Some(previous))?);
    }
    ctx.settle(&mut samples, near);
    let bx = ctx.surface.param_box();
    let periods = ctx.surface.periods();
    let mut best: Option<(NurbsCurve, Check)> = None;
    for _ in 0..MAX_ROUNDS {
        fill(ctx, arc, &mut samples, &knots, near)?;
        let kv = clamped(&knots)?;
        let data: Vec<(f64, [f64; 2])> = samples.iter().map(|p| (p.s, p.uv)).collect();
        let Some(mut points) = least_squares(&kv, &data) else {
            return Err(GeomError::PcurveWorkLimit {
                surface: ctx.surface.kind_name(),
                parameter: arc.t(0.5),
                samples: samples.len(),
            });
        };
        for p in &mut points {
            for i in 0..2 {
                if periods[i].is_none() {
                    let (a, b) = bx.range(i);
                    p[i] = p[i].clamp(a, b);
                }
            }
        }
        let curve = NurbsCurve::new(
            DEGREE,
            kv.knots().to_vec(),
            points.iter().map(|p| Point::new(p[0], p[1])).collect(),
            None,
        )?;
        // No pcurve comes nearer than the samples' distances: a gap term far below them
        // would cost evaluations for nothing.
        let floor = samples.iter().map(Sample::distance).fold(0.0, f64::max);
        let check = check(
            ctx,
            arc,
            &curve,
            &samples,
            GAP_SHARE * ctx.fit_target.max(floor),
        );
        let done = check.bound <= ctx.fit_target;
        let refine: Vec<f64> = check
            .spans
            .iter()
            .filter(|sp| {
                sp.bound > ctx.fit_target && sp.excess > FIT_SHARE * ctx.fit_target.max(sp.floor)
            })
            .map(|sp| 0.5 * (sp.a + sp.b))
            .collect();
        if best
            .as_ref()
            .is_none_or(|(_, b)| check.bound < b.bound || b.bound.is_nan())
        {
            best = Some((curve, check));
        }
        if done || refine.is_empty() || kv.n_control() + refine.len() > MAX_CONTROL_POINTS {
            break;
        }
        knots.extend(refine);
        knots.sort_by(f64::total_cmp);
    }
    let (curve, mut check) = best.expect("at least one round");
    // The gap term was sized to the target; sized to the deviation found it is tighter, for
    // a few more evaluations (both bounds hold).
    let tight = GAP_SHARE * check.largest.max(TIGHT_FLOOR * ctx.fit_target);
    if tight < GAP_SHARE * ctx.fit_target {
        let again = self::check(ctx, arc, &curve, &samples, tight);
        if again.bound < check.bound {
            check = again;
        }
    }
    // The ends of the kept round's fit (a sample at a pole may have taken another free
    // parameter from a neighbour added since): its end control points, exactly.
    let cps = curve.control_points();
    let (first, last) = (cps[0], cps[cps.len() - 1]);
    Ok(ArcPcurve {
        start: [first.x, first.y],
        end: [last.x, last.y],
        curve,
        deviation: check.bound,
        rigorous: check.rigorous,
        fitted: true,
        iso: None,
    })
}

/// The B-spline under a curve (through trims).
fn spline_of(c: &Curve<Point3>) -> Option<&RationalBSpline<Point3>> {
    match c {
        Curve::BSpline(b) => Some(b),
        Curve::Trimmed { basis, .. } => spline_of(basis),
        Curve::Line { .. } | Curve::Conic(_) => None,
    }
}

/// The knots strictly inside the stretch where the edge's B-spline is less smooth than a
/// cubic at a simple knot (twice continuously differentiable), as `s` (ascending), each with
/// whether the edge is only continuous there (multiplicity at least its degree): there the
/// fit needs a knot of its own.
fn edge_breaks(edge: &Curve<Point3>, arc: &Arc) -> Vec<(f64, bool)> {
    let Some(b) = spline_of(edge) else {
        return Vec::new();
    };
    let kv = b.knots();
    let (lo, hi) = arc.window();
    let p = kv.degree();
    let mut out: Vec<(f64, bool)> = kv
        .interior_breaks()
        .into_iter()
        .filter(|&k| k > lo && k < hi && kv.multiplicity(k) + 2 > p)
        .map(|k| (arc.s(k), kv.multiplicity(k) >= p))
        .filter(|&(s, _)| s > 0.0 && s < 1.0)
        .collect();
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

/// The interior knots of the first fit: the edge's breaks (triple where it is only
/// continuous), then the longest spans halved until there are [`INITIAL_SPANS`].
fn initial_knots(breaks: &[(f64, bool)]) -> Vec<f64> {
    let mut cuts: Vec<f64> = breaks.iter().map(|b| b.0).collect();
    while cuts.len() + 1 < INITIAL_SPANS {
        let mut ends = vec![0.0];
        ends.extend(&cuts);
        ends.push(1.0);
        let (i, _) = ends
            .windows(2)
            .enumerate()
            .max_by(|a, b| (a.1[1] - a.1[0]).total_cmp(&(b.1[1] - b.1[0])))
            .expect("two ends");
        cuts.insert(i, 0.5 * (ends[i] + ends[i + 1]));
    }
    let mut knots = Vec::new();
    for s in cuts {
        let triple = breaks.iter().any(|b| b.0 == s && b.1);
        knots.extend(std::iter::repeat_n(s, if triple { DEGREE } else { 1 }));
    }
    knots
}

/// The clamped cubic knot vector on `[0, 1]` with the interior knots `interior`.
fn clamped(interior: &[f64]) -> Result<KnotVector, GeomError> {
    let mut knots = vec![0.0; DEGREE + 1];
    knots.extend(interior);
    knots.extend([1.0; DEGREE + 1]);
    let n = knots.len() - DEGREE - 1;
    Ok(KnotVector::new(knots, DEGREE, n)?)
}

/// Adds samples until every span between `knots` holds [`DATA_PER_SPAN`] of them and every
/// step between neighbours is continuous (see the module documentation).
fn fill(
    ctx: &Context<'_>,
    arc: &Arc,
    samples: &mut Vec<Sample>,
    knots: &[f64],
    near: Option<[f64; 2]>,
) -> Result<(), GeomError> {
    let mut cuts = vec![0.0];
    cuts.extend(knots);
    cuts.push(1.0);
    cuts.dedup();
    loop {
        let mut wanted: Vec<f64> = Vec::new();
        for w in cuts.windows(2) {
            let (a, b) = (w[0], w[1]);
            let (i0, i1) = (
                samples.partition_point(|p| p.s < a),
                samples.partition_point(|p| p.s <= b),
            );
            // The span's samples and ends; the middle of the widest gap until there are
            // enough.
            let mut have: Vec<f64> = samples[i0..i1].iter().map(|p| p.s).collect();
            let missing = DATA_PER_SPAN.saturating_sub(have.len());
            have.push(a);
            have.push(b);
            for _ in 0..missing {
                have.sort_by(f64::total_cmp);
                have.dedup();
                let (i, _) = have
                    .windows(2)
                    .enumerate()
                    .max_by(|x, y| (x.1[1] - x.1[0]).total_cmp(&(y.1[1] - y.1[0])))
                    .expect("the span's ends");
                let mid = 0.5 * (have[i] + have[i + 1]);
                wanted.push(mid);
                have.push(mid);
            }
        }
        for pair in samples.windows(2) {
            let (a, b) = (&pair[0], &pair[1]);
            if !continuous(ctx, a, b) {
                if b.s - a.s <= MIN_STEP {
                    return Err(jump(ctx, arc, a.s, samples.len()));
                }
                wanted.push(0.5 * (a.s + b.s));
            }
        }
        if wanted.is_empty() {
            return Ok(());
        }

        if samples.len() + wanted.len() > MAX_SAMPLES {
            return Err(jump(ctx, arc, wanted[0], samples.len()));
        }
        wanted.sort_by(f64::total_cmp);
        wanted.dedup();
        let before = samples.len();
        for s in wanted {
            let at = samples.partition_point(|p| p.s < s);
            if at == 0 || at == samples.len() || samples[at].s == s {
                continue;
            }
            let previous = samples[at - 1].uv;
            let sample = ctx.sample(arc, s, Some(previous))?;
            samples.insert(at, sample);
        }
        if samples.len() == before {
            // No new sample fits between the old ones: the steps are at rounding.
            return Err(jump(ctx, arc, samples[0].s, before));
        }
        ctx.settle(samples, near);
    }
}

/// The work-limit error for a jump near `s`.
fn jump(ctx: &Context<'_>, arc: &Arc, s: f64, samples: usize) -> GeomError {
    GeomError::PcurveWorkLimit {
        surface: ctx.surface.kind_name(),
        parameter: arc.t(s),
        samples,
    }
}

/// Whether the step from sample `a` to sample `b` is continuous (see the module
/// documentation).
fn continuous(ctx: &Context<'_>, a: &Sample, b: &Sample) -> bool {
    let periods = ctx.surface.periods();
    let step = [b.uv[0] - a.uv[0], b.uv[1] - a.uv[1]];
    for i in 0..2 {
        if let Some(p) = periods[i]
            && (step[i].abs() > PERIOD_STEP * p || step[i].is_nan())
        {
            return false;
        }
    }
    let d = ctx.surface.derivatives(a.uv);
    let predicted = d.du * step[0] + d.dv * step[1];
    predicted.length() <= JUMP_RATIO * b.foot.distance(a.foot) + ctx.iso_tol
}

/// The control points (`D` coordinates) of the B-spline on `kv` whose first and last are the
/// first and last data exactly and whose others minimise the sum of squared distances to the
/// data `(s, x)` (normal equations by Cholesky, with a ridge of `1e-12` of the largest
/// diagonal if they are singular); `None` if they still are.
pub(crate) fn least_squares<const D: usize>(
    kv: &KnotVector,
    data: &[(f64, [f64; D])],
) -> Option<Vec<[f64; D]>> {
    let n = kv.n_control();
    let p = kv.degree();
    let (first, last) = (data.first()?.1, data.last()?.1);
    let m = n - 2;
    let mut a = DMatrix::<f64>::zeros(m, m);
    let mut rhs = DMatrix::<f64>::zeros(m, D);
    for &(s, x) in data {
        let k = kv.span(s);
        let basis = &kv.basis_derivatives(k, s, 0)[0];
        let mut r = x;
        for (c, &nb) in basis.iter().enumerate() {
            let fixed = match k - p + c {
                0 => first,
                i if i == n - 1 => last,
                _ => continue,
            };
            for (ri, fi) in r.iter_mut().zip(fixed) {
                *ri -= nb * fi;
            }
        }
        for (c, &nb) in basis.iter().enumerate() {
            let i = k - p + c;
            if i == 0 || i == n - 1 {
                continue;
            }
            for (e, &ne) in basis.iter().enumerate() {
                let j = k - p + e;
                if j != 0 && j != n - 1 {
                    a[(i - 1, j - 1)] += nb * ne;
                }
            }
            for (dim, ri) in r.iter().enumerate() {
                rhs[(i - 1, dim)] += nb * ri;
            }
        }
    }
    let chol = a.clone().cholesky().or_else(|| {
        let ridge = 1e-12 * a.diagonal().max();
        let mut b = a;
        for i in 0..m {
            b[(i, i)] += ridge;
        }
        b.cholesky()
    })?;
    let x = chol.solve(&rhs);
    let mut out = Vec::with_capacity(n);
    out.push(first);
    for i in 0..m {
        out.push(std::array::from_fn(|dim| x[(i, dim)]));
    }
    out.push(last);
    out.iter()
        .all(|p| p.iter().all(|c| c.is_finite()))
        .then_some(out)
}

/// The bound of one span of a fit.
#[derive(Clone, Copy, Debug, PartialEq)]
struct SpanCheck {
    /// The span's start.
    a: f64,
    /// Its end.
    b: f64,
    /// Its bound on `D`.
    bound: f64,
    /// Its samples' largest distance from the surface.
    floor: f64,
    /// Its largest `D` less `floor`.
    excess: f64,
}

/// The bound of a fit.
#[derive(Clone, Debug, PartialEq)]
struct Check {
    /// The bound on `D` over `[0, 1]`.
    bound: f64,
    /// Proven (no estimated surface bound used).
    rigorous: bool,
    /// The largest `D` evaluated.
    largest: f64,
    /// Per span.
    spans: Vec<SpanCheck>,
}

/// The bound of a span's gap term: its constants and check count.
struct Plan {
    a: f64,
    b: f64,
    l1: f64,
    m2: f64,
    smooth: bool,
    n: usize,
}

/// The bound on `D` of the fit `curve` of the stretch (see the module documentation).
fn check(ctx: &Context<'_>, arc: &Arc, curve: &NurbsCurve, samples: &[Sample], goal: f64) -> Check {
    let kv = curve.knots();
    let t = kv.knots();
    let cps = curve.control_points();
    let speed = arc.speed().abs();
    let mut rigorous = true;
    let mut plans = Vec::new();
    for k in DEGREE..kv.n_control() {
        if t[k] >= t[k + 1] {
            continue;
        }
        let local = &cps[k - DEGREE..=k];
        let range = |f: fn(&Point) -> f64| {
            local
                .iter()
                .map(f)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                    (lo.min(x), hi.max(x))
                })
        };
        let bx = ParamBox {
            u: range(|p| p.x),
            v: range(|p| p.y),
        };
        let sb = surface_bounds(ctx.surface, &bx);
        rigorous &= sb.rigorous;
        // The derivative's and second derivative's control points alive on the span.
        let q: Vec<Point> = (k - DEGREE..k)
            .map(|i| (cps[i + 1] - cps[i]) * (DEGREE as f64 / (t[i + DEGREE + 1] - t[i + 1])))
            .collect();
        let r: Vec<Point> = (0..DEGREE - 1)
            .map(|j| {
                let i = k - DEGREE + j;
                (q[j + 1] - q[j]) * ((DEGREE - 1) as f64 / (t[i + DEGREE + 1] - t[i + 2]))
            })
            .collect();
        let largest =
            |ps: &[Point], f: fn(&Point) -> f64| ps.iter().map(|p| f(p).abs()).fold(0.0, f64::max);
        let (gu1, gv1) = (largest(&q, |p| p.x), largest(&q, |p| p.y));
        let (gu2, gv2) = (largest(&r, |p| p.x), largest(&r, |p| p.y));
        let (ta, tb) = (arc.t(t[k]), arc.t(t[k + 1]));
        let cb = curve_bounds(ctx.edge, (ta.min(tb), ta.max(tb)), None);
        let l1 = sb.d1[0] * gu1 + sb.d1[1] * gv1 + cb.d1 * speed;
        let m2 = sb.d2[0] * gu1 * gu1
            + 2.0 * sb.d2[1] * gu1 * gv1
            + sb.d2[2] * gv1 * gv1
            + sb.d1[0] * gu2
            + sb.d1[1] * gv2
            + cb.d2 * speed * speed;
        let smooth = sb.smooth && cb.smooth;
        let len = t[k + 1] - t[k];
        let h = (2.0 * goal / l1).max(if smooth {
            (8.0 * goal / m2).sqrt()
        } else {
            0.0
        });
        let n = (len / h).ceil();
        let n = if n.is_finite() {
            (n as usize).clamp(MIN_CHECKS, MAX_CHECKS)
        } else {
            MAX_CHECKS
        };
        plans.push(Plan {
            a: t[k],
            b: t[k + 1],
            l1,
            m2,
            smooth,
            n,
        });
    }
    let total: usize = plans.iter().map(|p| p.n).sum();
    if total > MAX_CHECKS {
        for p in &mut plans {
            p.n = (p.n * MAX_CHECKS / total).max(MIN_CHECKS);
        }
    }
    let mut spans = Vec::with_capacity(plans.len());
    let mut bound = 0.0f64;
    let mut overall = 0.0f64;
    for plan in plans {
        let len = plan.b - plan.a;
        let mut largest = 0.0f64;
        for i in 0..=plan.n {
            let s = if i == plan.n {
                plan.b
            } else {
                plan.a + len * i as f64 / plan.n as f64
            };
            let g = curve.point_at(s);
            let d = ctx
                .surface
                .point([g.x, g.y])
                .distance(ctx.edge.point(arc.t(s)));
            largest = largest.max(if d.is_nan() { f64::INFINITY } else { d });
        }
        let h = len / plan.n as f64;
        let second = if plan.smooth {
            plan.m2 * h * h / 8.0
        } else {
            f64::INFINITY
        };
        let gap = (plan.l1 * h / 2.0).min(second);
        let span_bound = largest + if gap.is_nan() { f64::INFINITY } else { gap };
        let floor = samples
            .iter()
            .filter(|p| p.s >= plan.a && p.s <= plan.b)
            .map(Sample::distance)
            .fold(0.0, f64::max);
        bound = bound.max(span_bound);
        overall = overall.max(largest);
        spans.push(SpanCheck {
            a: plan.a,
            b: plan.b,
            bound: span_bound,
            floor,
            excess: largest - floor,
        });
    }
    Check {
        bound: bound + ROUNDING * ctx.size,
        rigorous,
        largest: overall,
        spans,
    }
}
