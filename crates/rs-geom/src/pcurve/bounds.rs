//! Bounds on the first and second derivatives of surfaces over parameter boxes and of curves
//! over parameter windows: the constants of a fitted pcurve's deviation bound.
//!
//! # What is rigorous
//!
//! Up to the floating-point rounding of the bounds' own arithmetic (a relative margin of
//! [`MARGIN`] is added), every bound here is proven except an offset surface's:
//!
//! - planes, cylinders, cones, spheres, tori: closed forms from their radii and angles, with
//!   `|cos|` and `|sin|` maximised over the box's `v`;
//! - rational B-spline curves and surfaces, on each knot span the box meets: with `r` the
//!   half diagonal of the box of the span's control points (the curve is in their convex
//!   hull, positive weights), `w_max`, `w_min` their weights, `dw = w_max - w_min`, and
//!   `s1 >= sum |N'_i|`, `s2 >= sum |N''_i|` on the span,
//!   `|C'| <= s1 r (w_max + dw) / w_min` and
//!   `|C''| <= (s2 r (w_max + dw) + 2 s1 dw |C'|) / w_min` (from `w C' = sum N'_i w_i
//!   (P_i - c) - w' (C - c)` for the box's centre `c`, and `w C'' = A'' - w'' C - 2 w' C'`;
//!   `|w'| <= s1 dw` as `sum N'_i = 0`); surfaces alike per parameter, and `|S_uv|` from
//!   `w S_uv = A_uv - w_uv S - w_u S_v - w_v S_u`. The basis sums: `sum |N'_{i,p}| <= 2 p /
//!   delta_p` and `sum |N''_{i,p}| <= 4 p (p - 1) / (delta_p delta_{p-1})`, `delta_q` the least
//!   `t_{i+q} - t_i` over the degree-`(q - 1)` basis functions alive on the span (from the
//!   derivative recurrence and the partition of unity);
//! - lines and conics: closed forms over the window (`|a u + b v| <= sqrt(|u|^2 + |v|^2)` for
//!   `a^2 + b^2 = 1`; `cosh` and `sinh` at the window's farthest end);
//! - surfaces of revolution and extrusion: from their swept curve's bounds (`|S_u|` and
//!   `|S_uu|` of a revolution are the distance from the axis, at most the largest over the
//!   corners of the box that holds the curve; `|S_v|`, `|S_uv|`, `|S_vv|` the curve's `|C'|`,
//!   `|C'|`, `|C''|`);
//! - reparameterised surfaces: the base's bounds by the chain rule.
//!
//! An offset surface's bounds are estimated: the largest derivatives at a grid of
//! [`ESTIMATE_GRID`] x [`ESTIMATE_GRID`] points of the box, times [`ESTIMATE_SAFETY`].
//!
//! A function is *smooth* over the box or window (continuously differentiable, so a
//! second-order bound applies) unless the box crosses a knot of multiplicity at least the
//! degree or the seam of a closed B-spline direction.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use rs_spline::{KnotVector, Point3, RationalBSpline};

use crate::surface::{BSplineSurface, ParamBox, ParamSurface, Surface, copy_from};
use crate::{Conic, ConicKind, Curve};

/// The relative margin added to every bound for the rounding of its own arithmetic.
pub const MARGIN: f64 = 1.0 + 1e-12;

/// Points per side of the grid an offset surface's derivatives are estimated from.
pub const ESTIMATE_GRID: usize = 5;

/// The factor on an offset surface's largest sampled derivatives: its derivatives change
/// little across the box of one fitted span (a fraction of its radii of curvature), so twice
/// the largest sample is a safe estimate, not a proof.
pub const ESTIMATE_SAFETY: f64 = 2.0;

/// Bounds on a surface's derivatives over a box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SurfaceBounds {
    /// `|S_u|`, `|S_v|`.
    pub(crate) d1: [f64; 2],
    /// `|S_uu|`, `|S_uv|`, `|S_vv|`.
    pub(crate) d2: [f64; 3],
    /// Continuously differentiable over the box.
    pub(crate) smooth: bool,
    /// Proven (not estimated).
    pub(crate) rigorous: bool,
}

/// Bounds on a curve over a window.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CurveBounds {
    /// A box holding the curve: its lower corner.
    pub(crate) lo: Point3,
    /// Its upper corner.
    pub(crate) hi: Point3,
    /// `|C'|`.
    pub(crate) d1: f64,
    /// `|C''|`.
    pub(crate) d2: f64,
    /// Continuously differentiable over the window.
    pub(crate) smooth: bool,
}

impl SurfaceBounds {
    fn exact(d1: [f64; 2], d2: [f64; 3]) -> SurfaceBounds {
        SurfaceBounds {
            d1,
            d2,
            smooth: true,
            rigorous: true,
        }
    }

    fn with_margin(mut self) -> SurfaceBounds {
        for x in self.d1.iter_mut().chain(self.d2.iter_mut()) {
            *x *= MARGIN;
        }
        self
    }
}

/// Bounds on the derivatives of `s` over the box `bx` (finite).
pub(crate) fn surface_bounds(s: &Surface, bx: &ParamBox) -> SurfaceBounds {
    let b = match s {
        Surface::Plane(_) => SurfaceBounds::exact([1.0, 1.0], [0.0; 3]),
        Surface::Cylinder(c) => {
            let r = c.radius();
            SurfaceBounds::exact([r, 1.0], [r, 0.0, 0.0])
        }
        Surface::Cone(c) => {
            let t = c.semi_angle().tan();
            let rho = (c.radius() + bx.v.0 * t)
                .abs()
                .max((c.radius() + bx.v.1 * t).abs());
            SurfaceBounds::exact([rho, t.hypot(1.0)], [rho, t, 0.0])
        }
        Surface::Sphere(sp) => {
            let r = sp.radius();
            let (c, s) = (max_abs_cos(bx.v), max_abs_sin(bx.v));
            SurfaceBounds::exact([r * c, r], [r * c, r * s, r])
        }
        Surface::Torus(t) => {
            let (big, r) = (t.major_radius(), t.minor_radius());
            let (lo, hi) = cos_range(bx.v);
            let rho = (big + r * lo).abs().max((big + r * hi).abs());
            let s = max_abs_sin(bx.v);
            SurfaceBounds::exact([rho, r], [rho, r * s, r])
        }
        Surface::Revolution(rev) => {
            let cb = curve_bounds(rev.curve(), bx.v, rev.periods()[1]);
            let (o, d) = (rev.axis_point(), rev.axis());
            let rho = corners(cb.lo, cb.hi)
                .map(|p| {
                    let q = p - o;
                    (q - d * q.dot(d)).length()
                })
                .fold(0.0, f64::max);
            SurfaceBounds {
                d1: [rho, cb.d1],
                d2: [rho, cb.d1, cb.d2],
                smooth: cb.smooth,
                rigorous: true,
            }
        }
        Surface::Extrusion(e) => {
            let cb = curve_bounds(e.curve(), bx.u, e.periods()[0]);
            SurfaceBounds {
                d1: [cb.d1, e.vector().length()],
                d2: [cb.d2, 0.0, 0.0],
                smooth: cb.smooth,
                rigorous: true,
            }
        }
        Surface::BSpline(b) => bspline_surface_bounds(b, bx),
        Surface::Reparam(r) => {
            let (scale, offset) = (r.scale(), r.offset());
            // Our parameter of the base's parameter k.
            let ours = |k: usize| if r.swap() { 1 - k } else { k };
            let range = |k: usize| {
                let (a, b) = bx.range(ours(k));
                let (a, b) = (scale[k] * a + offset[k], scale[k] * b + offset[k]);
                (a.min(b), a.max(b))
            };
            let base = surface_bounds(
                r.base(),
                &ParamBox {
                    u: range(0),
                    v: range(1),
                },
            );
            let mut d1 = [0.0; 2];
            let mut d2 = [0.0; 3];
            for k in 0..2 {
                d1[ours(k)] = scale[k].abs() * base.d1[k];
                // The base's second derivative in k twice: index 0 (uu) or 2 (vv).
                d2[2 * ours(k)] = scale[k] * scale[k] * base.d2[2 * k];
            }
            d2[1] = (scale[0] * scale[1]).abs() * base.d2[1];
            SurfaceBounds { d1, d2, ..base }
        }
        Surface::Offset(_) => estimated(s, bx),
    };
    b.with_margin()
}

/// The least and largest `cos v` over `[a, b]`: the ends' values, and `+-1` where a multiple
/// of `pi` lies inside.
fn cos_range((a, b): (f64, f64)) -> (f64, f64) {
    if b - a >= TAU || (b - a).is_nan() {
        return (-1.0, 1.0);
    }
    let (ca, cb) = (a.cos(), b.cos());
    let (mut lo, mut hi) = (ca.min(cb), ca.max(cb));
    let mut k = (a / PI).ceil();
    while k * PI <= b {
        // An even multiple of pi is a maximum of the cosine, an odd one a minimum.
        if k.rem_euclid(2.0) == 0.0 {
            hi = 1.0;
        } else {
            lo = -1.0;
        }
        k += 1.0;
    }
    (lo, hi)
}

/// The largest `|cos v|` over `[a, b]`.
fn max_abs_cos(v: (f64, f64)) -> f64 {
    let (lo, hi) = cos_range(v);
    lo.abs().max(hi.abs())
}

/// The largest `|sin v|` over `[a, b]`.
fn max_abs_sin((a, b): (f64, f64)) -> f64 {
    max_abs_cos((a - FRAC_PI_2, b - FRAC_PI_2))
}

/// The eight corners of the box `[lo, hi]`.
fn corners(lo: Point3, hi: Point3) -> impl Iterator<Item = Point3> {
    (0..8).map(move |i| {
        Point3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    })
}

/// Estimated bounds (see the module documentation).
fn estimated(s: &Surface, bx: &ParamBox) -> SurfaceBounds {
    let within = s.param_box();
    let mut d1 = [0.0f64; 2];
    let mut d2 = [0.0f64; 3];
    let n = ESTIMATE_GRID - 1;
    for i in 0..=n {
        for j in 0..=n {
            let f = |(a, b): (f64, f64), k: usize| a + (b - a) * k as f64 / n as f64;
            let uv = within.clamp([f(bx.u, i), f(bx.v, j)]);
            let d = s.derivatives(uv);
            d1[0] = d1[0].max(d.du.length());
            d1[1] = d1[1].max(d.dv.length());
            d2[0] = d2[0].max(d.duu.length());
            d2[1] = d2[1].max(d.duv.length());
            d2[2] = d2[2].max(d.dvv.length());
        }
    }
    SurfaceBounds {
        d1: d1.map(|x| x * ESTIMATE_SAFETY),
        d2: d2.map(|x| x * ESTIMATE_SAFETY),
        smooth: true,
        rigorous: false,
    }
}

/// Bounds on `sum |N'_{i,p}|` and `sum |N''_{i,p}|` on the (non-empty) knot span `k`.
fn basis_sums(kv: &KnotVector, k: usize) -> (f64, f64) {
    let t = kv.knots();
    let p = kv.degree();
    // The least t_{i+q} - t_i over the degree q - 1 basis functions alive on span k.
    let delta = |q: usize| {
        (k + 1 - q..=k)
            .map(|i| t[i + q] - t[i])
            .fold(f64::INFINITY, f64::min)
    };
    let pf = p as f64;
    let dp = delta(p);
    let s1 = 2.0 * pf / dp;
    let s2 = if p >= 2 {
        4.0 * pf * (pf - 1.0) / (dp * delta(p - 1))
    } else {
        0.0
    };
    (s1, s2)
}

/// The non-empty knot spans of `kv` meeting the window `w` (brought into the domain by whole
/// periods where `period` is given; split at the seam, or the whole domain, where it wraps),
/// and whether the function is continuously differentiable across the window.
fn spans(kv: &KnotVector, period: Option<f64>, (w0, w1): (f64, f64)) -> (Vec<usize>, bool) {
    let (a, b) = kv.domain();
    let mut windows = Vec::with_capacity(2);
    let mut smooth = true;
    match period {
        Some(p) if w1 - w0 >= p || (w1 - w0).is_nan() => {
            windows.push((a, b));
            smooth = false;
        }
        Some(p) => {
            let s0 = copy_from(w0, a, p);
            let s1 = s0 + (w1 - w0);
            if s1 <= b {
                windows.push((s0, s1));
            } else {
                windows.push((s0, b));
                windows.push((a, (s1 - p).min(b)));
                smooth = false;
            }
        }
        None => windows.push((w0.clamp(a, b), w1.clamp(a, b))),
    }
    let t = kv.knots();
    let p = kv.degree();
    let mut out = Vec::new();
    for (lo, hi) in windows {
        for k in kv.span(lo)..=kv.span(hi) {
            if t[k] < t[k + 1] && !out.contains(&k) {
                out.push(k);
            }
        }
        for &x in t {
            if x > lo && x < hi && kv.multiplicity(x) >= p {
                smooth = false;
            }
        }
    }
    (out, smooth)
}

/// The box of `points`, its half diagonal and the weights' extremes.
fn hull(points: impl Iterator<Item = (Point3, f64)>) -> (Point3, Point3, f64, f64, f64) {
    let inf = f64::INFINITY;
    let (mut lo, mut hi) = (Point3::new(inf, inf, inf), Point3::new(-inf, -inf, -inf));
    let (mut wmax, mut wmin) = (0.0f64, inf);
    for (p, w) in points {
        lo = Point3::new(lo.x.min(p.x), lo.y.min(p.y), lo.z.min(p.z));
        hi = Point3::new(hi.x.max(p.x), hi.y.max(p.y), hi.z.max(p.z));
        wmax = wmax.max(w);
        wmin = wmin.min(w);
    }
    (lo, hi, 0.5 * lo.distance(hi), wmax, wmin)
}

/// Bounds on a rational B-spline surface over a box (see the module documentation).
fn bspline_surface_bounds(s: &BSplineSurface, bx: &ParamBox) -> SurfaceBounds {
    let [ku, kv] = s.knots();
    let periods = s.periods();
    let (su, smooth_u) = spans(ku, periods[0], bx.u);
    let (sv, smooth_v) = spans(kv, periods[1], bx.v);
    let (p, q) = (ku.degree(), kv.degree());
    let nv = kv.n_control();
    let points = s.control_points();
    let weights = s.weights();
    let mut out = SurfaceBounds {
        d1: [0.0; 2],
        d2: [0.0; 3],
        smooth: smooth_u && smooth_v,
        rigorous: true,
    };
    for &i in &su {
        let (s1u, s2u) = basis_sums(ku, i);
        for &j in &sv {
            let (s1v, s2v) = basis_sums(kv, j);
            let net = (i - p..=i).flat_map(|a| {
                (j - q..=j).map(move |b| {
                    let at = a * nv + b;
                    (points[at], weights.map_or(1.0, |w| w[at]))
                })
            });
            let (_, _, r, wmax, wmin) = hull(net);
            let dw = wmax - wmin;
            let lead = r * (wmax + dw);
            let du = s1u * lead / wmin;
            let dv = s1v * lead / wmin;
            let duu = (s2u * lead + 2.0 * s1u * dw * du) / wmin;
            let dvv = (s2v * lead + 2.0 * s1v * dw * dv) / wmin;
            let duv = (s1u * s1v * lead + s1u * dw * dv + s1v * dw * du) / wmin;
            out.d1 = [out.d1[0].max(du), out.d1[1].max(dv)];
            out.d2 = [out.d2[0].max(duu), out.d2[1].max(duv), out.d2[2].max(dvv)];
        }
    }
    out
}

/// Bounds on `c` over the window `w` (finite; `period` the period of the parameter where the
/// curve is closed).
pub(crate) fn curve_bounds(c: &Curve<Point3>, w: (f64, f64), period: Option<f64>) -> CurveBounds {
    let b = match c {
        Curve::Line { origin, direction } => {
            let (a, e) = (*origin + *direction * w.0, *origin + *direction * w.1);
            CurveBounds {
                lo: Point3::new(a.x.min(e.x), a.y.min(e.y), a.z.min(e.z)),
                hi: Point3::new(a.x.max(e.x), a.y.max(e.y), a.z.max(e.z)),
                d1: direction.length(),
                d2: 0.0,
                smooth: true,
            }
        }
        Curve::Conic(conic) => conic_bounds(conic, w),
        Curve::BSpline(b) => bspline_curve_bounds(b, w, period),
        Curve::Trimmed { basis, .. } => return curve_bounds(basis, w, period),
    };
    // The box grown by the rounding of the points it holds.
    let grow = (b.hi - b.lo).max_abs() * (MARGIN - 1.0)
        + b.lo.max_abs().max(b.hi.max_abs()) * BOX_ROUNDING;
    let grow = Point3::new(grow, grow, grow);
    CurveBounds {
        lo: b.lo - grow,
        hi: b.hi + grow,
        d1: b.d1 * MARGIN,
        d2: b.d2 * MARGIN,
        smooth: b.smooth,
    }
}

/// The rounding of an evaluated point relative to its coordinates, by which a box holding a
/// curve is grown.
const BOX_ROUNDING: f64 = 16.0 * f64::EPSILON;

/// Closed-form bounds of a conic over a window.
fn conic_bounds(c: &Conic<Point3>, (a, b): (f64, f64)) -> CurveBounds {
    let (u, v) = (c.u, c.v);
    let far = a.abs().max(b.abs());
    // Per coordinate, |f u_i + g v_i| <= reach_i; the derivatives' lengths.
    let (reach, d1, d2) = match c.kind {
        ConicKind::Ellipse => {
            let both = u.length().hypot(v.length());
            (
                Point3::new(u.x.hypot(v.x), u.y.hypot(v.y), u.z.hypot(v.z)),
                both,
                both,
            )
        }
        ConicKind::Hyperbola => {
            let (ch, sh) = (far.cosh(), far.sinh());
            let r = |x: f64, y: f64| ch * x.abs() + sh * y.abs();
            (
                Point3::new(r(u.x, v.x), r(u.y, v.y), r(u.z, v.z)),
                sh * u.length() + ch * v.length(),
                ch * u.length() + sh * v.length(),
            )
        }
        ConicKind::Parabola => {
            let r = |x: f64, y: f64| far * far * x.abs() + 2.0 * far * y.abs();
            (
                Point3::new(r(u.x, v.x), r(u.y, v.y), r(u.z, v.z)),
                2.0 * far * u.length() + 2.0 * v.length(),
                2.0 * u.length(),
            )
        }
    };
    CurveBounds {
        lo: c.center - reach,
        hi: c.center + reach,
        d1,
        d2,
        smooth: true,
    }
}

/// Bounds of a rational B-spline curve over a window (see the module documentation).
fn bspline_curve_bounds(
    c: &RationalBSpline<Point3>,
    w: (f64, f64),
    period: Option<f64>,
) -> CurveBounds {
    let kv = c.knots();
    let (ks, smooth) = spans(kv, period, w);
    let p = kv.degree();
    let points = c.control_points();
    let weights = c.weights();
    let inf = f64::INFINITY;
    let mut out = CurveBounds {
        lo: Point3::new(inf, inf, inf),
        hi: Point3::new(-inf, -inf, -inf),
        d1: 0.0,
        d2: 0.0,
        smooth,
    };
    for k in ks {
        let (s1, s2) = basis_sums(kv, k);
        let (lo, hi, r, wmax, wmin) =
            hull((k - p..=k).map(|i| (points[i], weights.map_or(1.0, |w| w[i]))));
        let dw = wmax - wmin;
        let lead = r * (wmax + dw);
        let d1 = s1 * lead / wmin;
        let d2 = (s2 * lead + 2.0 * s1 * dw * d1) / wmin;
        out.lo = Point3::new(out.lo.x.min(lo.x), out.lo.y.min(lo.y), out.lo.z.min(lo.z));
        out.hi = Point3::new(out.hi.x.max(hi.x), out.hi.y.max(hi.y), out.hi.z.max(hi.z));
        out.d1 = out.d1.max(d1);
        out.d2 = out.d2.max(d2);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::testing::{Rng, one_of_each, sphere_octant};

    /// The largest derivatives of `s` at a dense grid of `bx`.
    fn sampled(s: &Surface, bx: &ParamBox, n: usize) -> ([f64; 2], [f64; 3]) {
        let mut d1 = [0.0f64; 2];
        let mut d2 = [0.0f64; 3];
        for i in 0..=n {
            for j in 0..=n {
                let f = |(a, b): (f64, f64), k: usize| a + (b - a) * k as f64 / n as f64;
                let d = s.derivatives([f(bx.u, i), f(bx.v, j)]);
                d1 = [d1[0].max(d.du.length()), d1[1].max(d.dv.length())];
                d2 = [
                    d2[0].max(d.duu.length()),
                    d2[1].max(d.duv.length()),
                    d2[2].max(d.dvv.length()),
                ];
            }
        }
        (d1, d2)
    }

    /// Every surface's bounds hold at a dense grid of random boxes inside its parameter box
    /// (the offset's estimate included), and the closed forms are attained on elementary
    /// surfaces (within the grid's resolution).
    #[test]
    fn surface_bounds_hold_on_dense_grids() {
        let mut rng = Rng::new(11);
        let mut all = one_of_each(&mut rng);
        all.push(Surface::BSpline(sphere_octant(2.0)));
        for s in &all {
            let within = s.param_box();
            for _ in 0..10 {
                let pick = |rng: &mut Rng, (a, b): (f64, f64)| {
                    let (a, b) = (a.max(-3.0), b.min(3.0));
                    let x = rng.range(a, b);
                    let y = rng.range(a, b);
                    (x.min(y), x.max(y))
                };
                let bx = ParamBox {
                    u: pick(&mut rng, within.u),
                    v: pick(&mut rng, within.v),
                };
                let b = surface_bounds(s, &bx);
                let (d1, d2) = sampled(s, &bx, 24);
                for (got, bound) in d1.iter().chain(&d2).zip(b.d1.iter().chain(&b.d2)) {
                    assert!(got <= bound, "{}: {got} > {bound} on {bx:?}", s.kind_name());
                }
                assert_eq!(b.rigorous, !matches!(s, Surface::Offset(_)));
                if matches!(
                    s,
                    Surface::Cylinder(_) | Surface::Sphere(_) | Surface::Torus(_)
                ) {
                    for (got, bound) in d1.iter().zip(&b.d1) {
                        assert!(*got >= 0.9 * bound, "{}: {got} << {bound}", s.kind_name());
                    }
                }
            }
        }
    }

    /// Curve bounds hold at dense samples of random windows, on every kind of curve.
    #[test]
    fn curve_bounds_hold_on_dense_samples() {
        let mut rng = Rng::new(12);
        let bs = RationalBSpline::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.3, 0.3, 0.7, 1.0, 1.0, 1.0, 1.0],
            (0..8).map(|_| rng.point(3.0)).collect(),
            Some((0..8).map(|_| rng.range(0.3, 3.0)).collect()),
        )
        .unwrap();
        let conic = |kind| {
            Curve::Conic(Conic {
                kind,
                center: Point3::new(1.0, 2.0, 3.0),
                u: Point3::new(2.0, 0.5, 0.0),
                v: Point3::new(-0.5, 1.0, 1.5),
            })
        };
        let curves = [
            Curve::Line {
                origin: Point3::new(1.0, 0.0, 0.0),
                direction: Point3::new(0.5, -2.0, 1.0),
            },
            conic(ConicKind::Ellipse),
            conic(ConicKind::Hyperbola),
            conic(ConicKind::Parabola),
            Curve::BSpline(bs),
        ];
        for c in &curves {
            for _ in 0..20 {
                let (x, y) = (rng.range(0.0, 1.0), rng.range(0.0, 1.0));
                let w = (x.min(y), x.max(y));
                let b = curve_bounds(c, w, None);
                for i in 0..=400 {
                    let t = w.0 + (w.1 - w.0) * f64::from(i) / 400.0;
                    let [p, d1, d2] = c.derivatives(t);
                    assert!(d1.length() <= b.d1 && d2.length() <= b.d2, "{c:?} at {t}");
                    for (lo, x, hi) in [(b.lo.x, p.x, b.hi.x), (b.lo.y, p.y, b.hi.y)] {
                        assert!(lo <= x && x <= hi, "{c:?} at {t}");
                    }
                }
                let crosses = w.0 < 0.3 && w.1 > 0.3;
                if matches!(c, Curve::BSpline(_)) {
                    assert_eq!(b.smooth, !crosses);
                }
            }
        }
    }

    #[test]
    fn trigonometric_extremes() {
        assert_eq!(max_abs_cos((-0.1, 0.2)), 1.0);
        assert!((max_abs_cos((0.5, 1.0)) - 0.5f64.cos()).abs() < 1e-15);
        assert_eq!(max_abs_sin((1.0, 2.0)), 1.0);
        assert!((max_abs_sin((-0.2, 0.1)) - 0.2f64.sin()).abs() < 1e-15);
        assert_eq!(max_abs_cos((0.0, 7.0)), 1.0);
        assert_eq!(
            cos_range((2.0, 4.0)),
            (-1.0, 2.0f64.cos().max(4.0f64.cos()))
        );
        assert_eq!(cos_range((-1.0, 0.5)), ((-1.0f64).cos(), 1.0));
        assert_eq!(cos_range((3.0, 7.0)), (-1.0, 1.0));
    }
}
