//! The two ray-casting baselines of the GWN paper (section 7.2), used inside the same closure
//! framework: the integer winding number of `curve + closure` from signed ray crossings, minus
//! the closure's angle. They need the query off the curve and off the closure segment (the
//! field answers queries within the boundary tolerance of a curve by the average across the
//! jump, and a query on the closure takes the adaptive algorithm) and serve as comparisons;
//! the adaptive algorithm is the reference.

use rs_spline::prelude::*;
use std::f64::consts::TAU;

use rs_spline::{Point, RationalBezier};

use super::QueryStats;
use super::curve::{MAX_DEPTH, control_box, outside};

/// Bezier clipping stops when the root is located to this fraction of the parameter range.
const CLIP_CONVERGED: f64 = 1e-9;

/// Which ray-casting baseline.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RayCaster {
    /// Recursive bisection until a piece is straight to machine precision (Farin 2001).
    BinarySearch,
    /// Bezier clipping against the ray's line (Nishita, Sederberg and Kakimoto 1990).
    BezierClipping,
}

/// A ray from `q` along one of the four axis directions.
#[derive(Clone, Copy)]
struct Ray {
    q: Point,
    d: Point,
}

impl Ray {
    /// Towards the nearest side of the box `[lo, hi]` (the paper's choice).
    fn towards_nearest_side(q: Point, lo: Point, hi: Point) -> Self {
        let options = [
            (hi.x - q.x, Point::new(1.0, 0.0)),
            (q.x - lo.x, Point::new(-1.0, 0.0)),
            (hi.y - q.y, Point::new(0.0, 1.0)),
            (q.y - lo.y, Point::new(0.0, -1.0)),
        ];
        let d = options
            .iter()
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map_or(Point::new(1.0, 0.0), |o| o.1);
        Self { q, d }
    }

    /// Signed distance of `p` to the ray's line (positive on the left).
    fn side(&self, p: Point) -> f64 {
        self.d.cross(p - self.q)
    }

    fn along(&self, p: Point) -> f64 {
        self.d.dot(p - self.q)
    }

    /// Signed crossing of the segment `a -> b` with the ray (half-open in the side coordinate):
    /// +1 when it passes from right to left.
    fn segment_crossing(&self, a: Point, b: Point) -> i32 {
        let (sa, sb) = (self.side(a), self.side(b));
        if (sa > 0.0) == (sb > 0.0) {
            return 0;
        }
        let s = self.along(a) + (self.along(b) - self.along(a)) * (sa / (sa - sb));
        if s <= 0.0 {
            return 0;
        }
        if sb > sa { 1 } else { -1 }
    }

    /// Could the ray meet anything inside the box `[lo, hi]`?
    fn meets_box(&self, lo: Point, hi: Point) -> bool {
        let (q, d) = (self.q, self.d);
        if d.x != 0.0 {
            q.y >= lo.y && q.y <= hi.y && if d.x > 0.0 { hi.x >= q.x } else { lo.x <= q.x }
        } else {
            q.x >= lo.x && q.x <= hi.x && if d.y > 0.0 { hi.y >= q.y } else { lo.y <= q.y }
        }
    }
}

fn closure_angle(q: Point, curve: &RationalBezier) -> f64 {
    let (u, v) = (curve.end_point() - q, curve.start_point() - q);
    u.cross(v).atan2(u.dot(v)) / TAU
}

/// Generalized winding number of `curve` at `q` by ray casting within the closure framework.
pub(crate) fn ray_winding_number(
    curve: &RationalBezier,
    q: Point,
    method: RayCaster,
    stats: &mut QueryStats,
) -> f64 {
    let (u, v) = (curve.end_point() - q, curve.start_point() - q);
    if u.cross(v) == 0.0 && u.dot(v) <= 0.0 {
        // q on the closure: its angle is +-pi, a half turn either way, so the integer count
        // cannot be corrected by it. The adaptive algorithm has no closure.
        return super::curve_winding_number(curve, q, stats);
    }
    stats.curve_evaluations += 1;
    let (lo, hi) = control_box(curve.control_points());
    let w_c = closure_angle(q, curve);
    if outside(lo, hi, q) {
        return -w_c;
    }
    let ray = Ray::towards_nearest_side(q, lo, hi);
    let crossings = match method {
        RayCaster::BinarySearch => Some(binary_search(curve, &ray, stats)),
        RayCaster::BezierClipping => bezier_clipping(curve, &ray, stats),
    };
    let Some(crossings) = crossings else {
        // A crossing too close to q for clipping to tell whether it lies ahead of q.
        return super::curve_winding_number(curve, q, stats);
    };
    let closed = crossings + ray.segment_crossing(curve.end_point(), curve.start_point());
    f64::from(closed) - w_c
}

/// Squared distance of every control point to the chord below `(eps size)^2`.
fn straight_to_machine_precision(p: &[Point]) -> bool {
    let (a, b) = (p[0], p[p.len() - 1]);
    let d = b - a;
    let len2 = d.dot(d);
    let (lo, hi) = control_box(p);
    let size2 = (hi - lo).dot(hi - lo);
    let eps2 = (f64::EPSILON * f64::EPSILON) * size2.max(f64::MIN_POSITIVE);
    p.iter().all(|&x| {
        let c = d.cross(x - a);
        if len2 > 0.0 {
            c * c / len2 <= eps2
        } else {
            (x - a).dot(x - a) <= eps2
        }
    })
}

fn binary_search(curve: &RationalBezier, ray: &Ray, stats: &mut QueryStats) -> i32 {
    let mut crossings = 0;
    let mut stack = vec![(curve.clone(), 0u32)];
    while let Some((c, depth)) = stack.pop() {
        stats.curve_evaluations += 1;
        let p = c.control_points();
        let (lo, hi) = control_box(p);
        if !ray.meets_box(lo, hi) {
            continue;
        }
        if depth >= MAX_DEPTH || straight_to_machine_precision(p) {
            crossings += ray.segment_crossing(p[0], p[p.len() - 1]);
            continue;
        }
        stats.subdivisions += 1;
        let (l, r) = c.subdivide();
        stack.push((r, depth + 1));
        stack.push((l, depth + 1));
    }
    crossings
}

/// The parameter interval where the convex hull of `(i / n, f_i)` meets the axis, or `None`.
fn hull_axis_interval(f: &[f64]) -> Option<(f64, f64)> {
    let n = (f.len() - 1) as f64;
    let (mut tmin, mut tmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..f.len() {
        if f[i] == 0.0 {
            tmin = tmin.min(i as f64 / n);
            tmax = tmax.max(i as f64 / n);
        }
        for j in i + 1..f.len() {
            if (f[i] > 0.0 && f[j] < 0.0) || (f[i] < 0.0 && f[j] > 0.0) {
                let (ti, tj) = (i as f64 / n, j as f64 / n);
                let t = ti + (tj - ti) * f[i] / (f[i] - f[j]);
                tmin = tmin.min(t);
                tmax = tmax.max(t);
            }
        }
    }
    (tmin <= tmax).then_some((tmin.max(0.0), tmax.min(1.0)))
}

/// The signed crossings of the ray by `curve`, or `None` when a crossing converged on (to
/// [`CLIP_CONVERGED`]) may lie on either side of the query along the ray.
fn bezier_clipping(curve: &RationalBezier, ray: &Ray, stats: &mut QueryStats) -> Option<i32> {
    let mut crossings = 0;
    let mut stack = vec![(curve.clone(), 0u32)];
    while let Some((c, depth)) = stack.pop() {
        stats.curve_evaluations += 1;
        let p = c.control_points();
        if p.iter().all(|&x| ray.along(x) < 0.0) {
            continue; // entirely behind the query
        }
        // Bernstein coefficients of the numerator of the signed distance to the ray's line.
        let f: Vec<f64> = p
            .iter()
            .zip(c.weights())
            .map(|(&x, w)| w * ray.side(x))
            .collect();
        // Rounding level of those coefficients: a piece whose coefficients are all within it
        // lies on the ray's line to machine precision, so it is the crossing itself.
        let noise: f64 = 64.0
            * f64::EPSILON
            * p.iter()
                .zip(c.weights())
                .map(|(&x, w)| w * ((x - ray.q).length() + ray.q.length()))
                .sum::<f64>();
        let on_line = f.iter().all(|v| v.abs() <= noise);
        let interval = hull_axis_interval(&f);
        if interval.is_none() && !on_line {
            continue;
        }
        let (t0, t1) = interval.unwrap_or((0.0, 1.0));
        let (a, b) = c.knot_span();
        let (ua, ub) = curve.knot_span();
        // Converged: the root is located to 1e-9 of the curve's parameter range. Going further
        // lets rounding flip the sign of a coefficient next to the root and lose it.
        let converged = (t1 - t0) * (b - a) <= CLIP_CONVERGED * (ub - ua);
        if on_line || converged || depth >= MAX_DEPTH {
            // The converged piece must lie wholly ahead of the query or wholly behind it.
            let sliver = c.subsegment((t0, t1)).unwrap_or_else(|_| c.clone());
            let along = sliver.control_points().iter().map(|&x| ray.along(x));
            let (lo, hi) = along.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                (l.min(v), h.max(v))
            });
            if lo <= 0.0 && hi >= 0.0 {
                return None;
            }
            // Evaluate on the original curve: a converged sliver may have collapsed to a point.
            let u = a + 0.5 * (t0 + t1) * (b - a);
            let d = curve.derivatives(((u - ua) / (ub - ua)).clamp(0.0, 1.0));
            if ray.along(d.point) > 0.0 {
                let s = ray.d.cross(d.first);
                crossings += if s > 0.0 {
                    1
                } else if s < 0.0 {
                    -1
                } else {
                    0
                };
            }
            continue;
        }
        stats.subdivisions += 1;
        // Clip to the hull's interval when it shrinks the piece enough (it is never empty
        // here: an empty one has converged above), else halve.
        match c.subsegment((t0, t1)) {
            Ok(clipped) if t1 - t0 <= 0.8 => stack.push((clipped, depth + 1)),
            _ => {
                let (l, r) = c.subdivide();
                stack.push((r, depth + 1));
                stack.push((l, depth + 1));
            }
        }
    }
    Some(crossings)
}
