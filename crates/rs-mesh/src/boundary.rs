//! Boundary points placed by arc length on every loop.

use rs_spline::prelude::*;
use rs_spline::quadrature::gauss_legendre;
use rs_spline::{Domain, NurbsCurve, Point};

/// A point on the boundary: which loop and curve, and the curve's NURBS parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundaryPoint {
    /// Index of the loop in the domain.
    pub loop_index: usize,
    /// Index of the curve in the domain.
    pub curve: usize,
    /// The parameter on that curve.
    pub u: f64,
    /// `C(u)`.
    pub point: Point,
}

/// Panels per Bezier span of the arc-length table.
const PANELS: usize = 32;

/// Cumulative arc length of a curve, tabulated at `PANELS` points per knot span (4-point
/// Gauss-Legendre per panel) and interpolated linearly in between.
#[derive(Clone, Debug)]
pub(crate) struct ArcLength {
    u: Vec<f64>,
    s: Vec<f64>,
}

impl ArcLength {
    pub(crate) fn new(c: &NurbsCurve) -> Self {
        let (nodes, weights) = gauss_legendre(4);
        let speed = |u: f64| c.derivatives(u).first.length();
        let mut breaks = vec![c.param_range().0];
        breaks.extend(c.knots().interior_breaks());
        breaks.push(c.param_range().1);
        let (mut us, mut ss) = (vec![breaks[0]], vec![0.0]);
        for w in breaks.windows(2) {
            for k in 0..PANELS {
                let a = w[0] + (w[1] - w[0]) * k as f64 / PANELS as f64;
                let b = w[0] + (w[1] - w[0]) * (k + 1) as f64 / PANELS as f64;
                let (m, r) = (0.5 * (a + b), 0.5 * (b - a));
                let len: f64 = nodes
                    .iter()
                    .zip(&weights)
                    .map(|(x, wt)| wt * r * speed(m + r * x))
                    .sum();
                us.push(b);
                ss.push(ss[ss.len() - 1] + len);
            }
        }
        Self { u: us, s: ss }
    }

    /// Total length.
    pub(crate) fn length(&self) -> f64 {
        self.s[self.s.len() - 1]
    }

    /// Arc length from the start to parameter `u`.
    pub(crate) fn s_at(&self, u: f64) -> f64 {
        interpolate(&self.u, &self.s, u)
    }

    /// The parameter at arc length `s`.
    pub(crate) fn u_at(&self, s: f64) -> f64 {
        interpolate(&self.s, &self.u, s)
    }
}

fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let i = xs.partition_point(|&v| v < x).clamp(1, xs.len() - 1);
    let (x0, x1) = (xs[i - 1], xs[i]);
    if x1 <= x0 {
        return ys[i];
    }
    let t = ((x - x0) / (x1 - x0)).clamp(0.0, 1.0);
    ys[i - 1] + t * (ys[i] - ys[i - 1])
}

/// Places nearly equally spaced points (spacing about `h` by arc length) on every loop.
///
/// Every curve's start point is kept (corners and curve junctions stay vertices, so each
/// boundary arc lies on one curve). `extra` points (curve, parameter) are kept where they are at
/// least `h / 3` (by arc length) from the points kept before them and from the curve's end;
/// the gaps in between are filled with equally spaced points. Returns the points of each loop
/// in loop order.
pub(crate) fn place_boundary_points(
    domain: &Domain,
    h: f64,
    extra: &[(usize, f64)],
) -> Vec<Vec<BoundaryPoint>> {
    let mut out = Vec::new();
    for (j, l) in domain.loops().iter().enumerate() {
        let mut pts = Vec::new();
        for ci in l.curves() {
            let c = &domain.curves()[ci];
            let table = ArcLength::new(c);
            let len = table.length();
            let (u_start, u_end) = c.param_range();
            let mut wanted: Vec<f64> = extra
                .iter()
                .filter(|(k, u)| *k == ci && *u > u_start && *u < u_end)
                .map(|&(_, u)| table.s_at(u))
                .collect();
            wanted.sort_by(f64::total_cmp);
            let mut kept = vec![0.0];
            for s in wanted {
                if s - kept[kept.len() - 1] >= h / 3.0 && len - s >= h / 3.0 {
                    kept.push(s);
                }
            }
            kept.push(len);
            let mut all = Vec::new();
            for w in kept.windows(2) {
                let n = ((w[1] - w[0]) / h).round().max(1.0) as usize;
                for k in 0..n {
                    all.push(w[0] + (w[1] - w[0]) * k as f64 / n as f64);
                }
            }
            for (k, s) in all.into_iter().enumerate() {
                let (u, point) = if k == 0 {
                    (u_start, c.start_point())
                } else {
                    let u = table.u_at(s);
                    (u, c.point_at(u))
                };
                pts.push(BoundaryPoint {
                    loop_index: j,
                    curve: ci,
                    u,
                    point,
                });
            }
        }
        out.push(pts);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_arc_length_is_two_pi_r() {
        let c = rs_spline::circle(Point::new(1.0, 2.0), 3.0).unwrap();
        let t = ArcLength::new(&c);
        assert!((t.length() - 6.0 * std::f64::consts::PI).abs() < 1e-10);
        for s in [0.5, 3.0, 10.0] {
            assert!((t.s_at(t.u_at(s)) - s).abs() < 1e-12);
        }
    }
}
