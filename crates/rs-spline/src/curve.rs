//! The curve vocabulary: small traits that [`NurbsCurve`](crate::NurbsCurve) and
//! [`RationalBezier`](crate::RationalBezier) implement, so every layer above asks a curve for
//! what it needs (a point, a sub-curve, its area contribution, its length, its extrema, a
//! polyline) instead of computing it again.
//!
//! The parameter of every method is the curve's own: `u` in [`ParamCurve::param_range`], the
//! knot domain of a NURBS and `[0, 1]` for a rational Bezier piece. Import them all with
//! `use rs_spline::prelude::*`.

use rs_roots::{RootsError, newton_bracketed};

use crate::quadrature::{Integral, integrate_adaptive};
use crate::{BoundingBox, CurveDerivatives, Point, SplineError};

/// A parametric planar curve `C(u)`, `u` in `[a, b] = param_range()`.
pub trait ParamCurve: Sized {
    /// The parameter range `[a, b]`, `a < b`.
    fn param_range(&self) -> (f64, f64);

    /// `C(u)`; a parameter outside the range is clamped into it by NURBS and extrapolates a
    /// Bezier piece (meant for `u` in the range).
    fn point_at(&self, u: f64) -> Point;

    /// `C(a)`.
    fn start_point(&self) -> Point {
        self.point_at(self.param_range().0)
    }

    /// `C(b)`.
    fn end_point(&self) -> Point {
        self.point_at(self.param_range().1)
    }

    /// The part of the curve on `[u0, u1]`, `a <= u0 < u1 <= b`: for a NURBS with the
    /// parameters kept, for a Bezier piece reparametrised to `[0, 1]`.
    ///
    /// # Errors
    /// [`SplineError::ParameterOutOfDomain`] for a range that is not increasing and inside
    /// `[a, b]`.
    fn subsegment(&self, range: (f64, f64)) -> Result<Self, SplineError>;

    /// Splits at `u` strictly inside the range into the curves on `[a, u]` and `[u, b]` (for a
    /// Bezier piece each reparametrised to `[0, 1]`); the shared end point is the same value
    /// in both.
    ///
    /// # Errors
    /// [`SplineError::ParameterOutOfDomain`] unless `a < u < b`.
    fn split_at(&self, u: f64) -> Result<(Self, Self), SplineError>;

    /// Splits at the middle of the parameter range (never fails).
    fn subdivide(&self) -> (Self, Self);

    /// The same point set traversed backwards on the same parameter range.
    fn reversed(&self) -> Self;
}

/// First and second derivatives with respect to the curve's own parameter.
pub trait ParamCurveDeriv: ParamCurve {
    /// `C(u)`, `C'(u)`, `C''(u)`.
    fn derivatives(&self, u: f64) -> CurveDerivatives;

    /// `C(u)` and `C'(u)`, the same values as [`ParamCurveDeriv::derivatives`] gives, without
    /// the second derivative (what arc lengths and areas integrate).
    fn point_and_tangent(&self, u: f64) -> (Point, Point) {
        let d = self.derivatives(u);
        (d.point, d.first)
    }
}

/// The signed area contribution of a curve (Green's theorem).
pub trait ParamCurveArea: ParamCurve {
    /// `1/2 integral_{u0}^{u1} (x y' - y x') du` over `[u0, u1]` within the range, with its
    /// error estimate; summed over a closed loop it is the loop's signed area
    /// (counter-clockwise positive). Adaptive Gauss-Legendre to about `1e-15` of the squared
    /// size of the control polygon, with bounded work.
    fn area_integral_on(&self, u0: f64, u1: f64) -> Integral;

    /// The Green integral over the whole range.
    fn area_integral(&self) -> Integral {
        let (a, b) = self.param_range();
        self.area_integral_on(a, b)
    }
}

/// How large the basis derivatives of a degree-`degree` span `[a, b]` add up to at most,
/// `2 degree / (b - a)`: a computed `C'(u)` combines coordinates with weights of that size.
pub(crate) fn basis_derivative_size(degree: usize, a: f64, b: f64) -> f64 {
    2.0 * degree as f64 / (b - a)
}

/// The size of the terms a computed `C'(u)` (`tangent`, at `point`) is a sum of:
/// `|C'(u)| + per_parameter |C(u)|` (in the 1-norm: a size, not a length), with
/// `per_parameter` from [`basis_derivative_size`]. A quadrature of an integrand built from
/// `C'` takes it as the rounding floor: a short curve far from the origin has a derivative
/// whose rounding (coordinates of `|C(u)|`'s size, differenced) is far above `eps |C'(u)|`.
pub(crate) fn derivative_rounding_size(point: Point, tangent: Point, per_parameter: f64) -> f64 {
    one_norm(tangent) + per_parameter * one_norm(point)
}

/// `|x| + |y|`: at least the length and at most 1.42 times it, without a square root.
pub(crate) fn one_norm(p: Point) -> f64 {
    p.x.abs() + p.y.abs()
}

/// Arc length `s(u) = integral_a^u |C'(v)| dv` and its inverse.
pub trait ParamCurveArclen: ParamCurveDeriv {
    /// The parameter ranges on which the curve is smooth (its Bezier spans), in order.
    fn smooth_spans(&self) -> Vec<(f64, f64)>;

    /// Length of the part on `[u0, u1]`, within `accuracy` (absolute) where the adaptive
    /// quadrature converges (its work is bounded; see
    /// [`integrate_adaptive`](crate::quadrature::integrate_adaptive)).
    fn arclen_on(&self, u0: f64, u1: f64, accuracy: f64) -> Integral {
        let spans = self.smooth_spans();
        let share = accuracy / spans.len().max(1) as f64;
        spans
            .into_iter()
            .filter_map(|(a, b)| {
                let (lo, hi) = (u0.max(a), u1.min(b));
                (lo < hi).then(|| {
                    // With `|v|` alone as the speed's rounding magnitude, a short curve far
                    // from the origin (control points at 1e8, length 40) could never meet the
                    // tolerance: every panel took the whole interval budget, 7 s per curve.
                    let per_parameter = basis_derivative_size(crate::limits::MAX_DEGREE, a, b);
                    let speed = |u: f64| {
                        let (point, tangent) = self.point_and_tangent(u);
                        let size = derivative_rounding_size(point, tangent, per_parameter);
                        (tangent.length(), size)
                    };
                    integrate_adaptive(speed, lo, hi, share.max(f64::MIN_POSITIVE))
                })
            })
            .sum()
    }

    /// Length of the whole curve.
    fn arclen(&self, accuracy: f64) -> f64 {
        let (a, b) = self.param_range();
        self.arclen_on(a, b, accuracy).value
    }

    /// The parameter `u` with `s(u) = s` (clamped to `[0, length]`), by Newton's method on
    /// `s(u) - s` safeguarded by bisection, each step one arc-length integral.
    ///
    /// # Errors
    /// [`RootsError`] only if the speed is not finite.
    fn inv_arclen(&self, s: f64, accuracy: f64) -> Result<f64, RootsError> {
        let (a, b) = self.param_range();
        let total = self.arclen(accuracy);
        if s.is_nan() || s <= 0.0 {
            return Ok(a);
        }
        if s >= total {
            return Ok(b);
        }
        let xtol = f64::EPSILON * (b - a).abs().max(a.abs().max(b.abs()));
        newton_bracketed(
            |u| {
                let speed = self.point_and_tangent(u).1.length();
                (self.arclen_on(a, u, accuracy).value - s, speed)
            },
            a,
            b,
            xtol,
        )
    }
}

/// Cumulative arc length of a curve tabulated at a fixed number of panels per smooth span and
/// interpolated linearly in between: `s(u)` and its inverse at the cost of a binary search,
/// for code that needs many of them (placing points equally spaced along a boundary). Exact
/// at the table's nodes to the quadrature accuracy; in between, the linear interpolation
/// errs by `O(h^2 |C''| )` for panel width `h`.
#[derive(Clone, Debug)]
pub struct ArcLengthTable {
    u: Vec<f64>,
    s: Vec<f64>,
}

impl ArcLengthTable {
    /// Tabulates `curve` at `panels` (at least 1) equal parameter steps per smooth span, each
    /// panel's length by [`ParamCurveArclen::arclen_on`] to `1e-14` of the control box.
    pub fn new<C: ParamCurveArclen + ParamCurveExtrema>(curve: &C, panels: usize) -> Self {
        let panels = panels.max(1);
        let accuracy = 1e-14 * curve.control_bounding_box().diagonal();
        let (a, _) = curve.param_range();
        let (mut us, mut ss) = (vec![a], vec![0.0]);
        for (lo, hi) in curve.smooth_spans() {
            for k in 0..panels {
                let p0 = lo + (hi - lo) * k as f64 / panels as f64;
                let p1 = lo + (hi - lo) * (k + 1) as f64 / panels as f64;
                let len = curve.arclen_on(p0, p1, accuracy).value;
                us.push(p1);
                ss.push(ss[ss.len() - 1] + len);
            }
        }
        Self { u: us, s: ss }
    }

    /// Total length.
    pub fn length(&self) -> f64 {
        self.s[self.s.len() - 1]
    }

    /// Arc length from the start to parameter `u` (clamped to the range).
    pub fn s_at(&self, u: f64) -> f64 {
        interpolate(&self.u, &self.s, u)
    }

    /// The parameter at arc length `s` (clamped to `[0, length]`).
    pub fn u_at(&self, s: f64) -> f64 {
        interpolate(&self.s, &self.u, s)
    }
}

/// Piecewise-linear interpolation of the table `(xs, ys)` (ascending `xs`) at `x`, clamped.
fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    if xs.len() < 2 {
        return ys.first().copied().unwrap_or(0.0);
    }
    let i = xs.partition_point(|&v| v < x).clamp(1, xs.len() - 1);
    let (x0, x1) = (xs[i - 1], xs[i]);
    if x1 <= x0 {
        return ys[i];
    }
    let t = ((x - x0) / (x1 - x0)).clamp(0.0, 1.0);
    ys[i - 1] + t * (ys[i] - ys[i - 1])
}

/// Where a curve turns in x or y, and boxes that contain it.
pub trait ParamCurveExtrema: ParamCurve {
    /// The parameters strictly inside the range where `x'(u) = 0` or `y'(u) = 0`, ascending.
    ///
    /// # Errors
    /// [`RootsError`] if the derivative numerators' roots cannot be computed.
    fn extrema(&self) -> Result<Vec<f64>, RootsError>;

    /// The bounding box of the control points; it contains the curve (weights are > 0).
    fn control_bounding_box(&self) -> BoundingBox;

    /// The tight bounding box: end points and the points at [`ParamCurveExtrema::extrema`];
    /// should the root finder fail, the control box (larger, but it contains the curve).
    fn bounding_box(&self) -> BoundingBox {
        let ends = BoundingBox::from_point(self.start_point()).including(self.end_point());
        match self.extrema() {
            Ok(us) => us
                .into_iter()
                .fold(ends, |b, u| b.including(self.point_at(u))),
            Err(_) => self.control_bounding_box(),
        }
    }
}

/// A polyline within a distance of the curve.
pub trait Flatten {
    /// Calls `emit` with the start point and then every vertex of a polyline whose distance
    /// from the curve is at most `accuracy` (an absolute distance): each Bezier piece is halved
    /// until the control points of every part are within `accuracy` of its chord (convex-hull
    /// property). The tolerance is raised to `1e-13` of a piece's control-box diagonal at the
    /// least, and halving stops at depth 40, so the work is bounded for every input.
    fn flatten(&self, accuracy: f64, emit: &mut dyn FnMut(Point));

    /// The points of [`Flatten::flatten`] after the start point: for chaining curves that
    /// meet end to start, so each shared point is emitted once.
    fn flatten_after_start(&self, accuracy: f64, emit: &mut dyn FnMut(Point)) {
        let mut started = false;
        self.flatten(accuracy, &mut |p| {
            if started {
                emit(p);
            }
            started = true;
        });
    }
}

/// Calls `emit` with the points of one polyline through `curves` taken in order, each curve
/// starting where the previous one ends: all of the first curve's [`Flatten::flatten`], then
/// each later curve's [`Flatten::flatten_after_start`], so every shared end point is emitted
/// once (the later curve's start is dropped, not the earlier curve's end). Nothing is added to
/// close the chain: for a loop, the last point is the last curve's end, which may differ from
/// the first point by the loop's gap. No points for no curves.
///
/// # Examples
///
/// ```
/// use rs_spline::{Flatten, Point, flatten_chain, segment};
/// let (a, b, c) = (Point::new(0.0, 0.0), Point::new(1.0, 0.0), Point::new(1.0, 1.0));
/// let (ab, bc) = (segment(a, b).unwrap(), segment(b, c).unwrap());
/// let mut pts = Vec::new();
/// flatten_chain([&ab as &dyn Flatten, &bc], 1e-3, &mut |p| pts.push(p));
/// assert_eq!(pts, [a, b, c]);
/// ```
pub fn flatten_chain<'a>(
    curves: impl IntoIterator<Item = &'a dyn Flatten>,
    accuracy: f64,
    emit: &mut dyn FnMut(Point),
) {
    for (i, c) in curves.into_iter().enumerate() {
        if i == 0 {
            c.flatten(accuracy, emit);
        } else {
            c.flatten_after_start(accuracy, emit);
        }
    }
}

/// The traits, for `use rs_spline::prelude::*`.
pub mod prelude {
    pub use super::{
        Flatten, ParamCurve, ParamCurveArclen, ParamCurveArea, ParamCurveDeriv, ParamCurveExtrema,
    };
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{NurbsCurve, circle, segment};
    use std::f64::consts::PI;

    /// A short cubic far from the origin (a mutated drawing's: control points at -1.4e8,
    /// length 44): the speed's rounding there is about 1e-8 of it, far above 256 eps of the
    /// speed, so with that as the noise floor no panel met the tolerance and each used the
    /// whole interval budget (7.5 s per curve for the table). Now the integrals converge, to
    /// the length of the same cubic at the origin within the rounding of its coordinates.
    #[test]
    fn a_short_curve_far_from_the_origin_converges() {
        let at = |dy: f64| {
            let pts = [
                (954.2, -80.5),
                (934.1, -85.1),
                (930.9, -86.0),
                (912.5, -93.1),
            ];
            let pts = pts.map(|(x, y)| Point::new(x, y + dy)).to_vec();
            NurbsCurve::bezier(pts, None).unwrap()
        };
        let (near, far) = (at(0.0), at(-138_699_700.0));
        let exact = near.arclen_on(0.0, 1.0, 1e-13);
        assert!(exact.converged);
        let got = far.arclen_on(0.0, 1.0, 1e-14 * 43.0);
        assert!(got.converged, "{got:?}");
        // Coordinates near 1.4e8 are rounded to 3e-8: the curve itself moved by that much.
        assert!((got.value - exact.value).abs() < 1e-6, "{got:?} {exact:?}");
        let table = ArcLengthTable::new(&far, 32);
        assert!((table.length() - exact.value).abs() < 1e-6);
    }

    /// The point and tangent are `derivatives`' first two, bit for bit, on a rational NURBS of
    /// several spans and on its rational Bezier pieces.
    #[test]
    fn point_and_tangent_are_the_first_two_derivatives() {
        let c = circle(Point::new(1.0, 2.0), 3.0).unwrap();
        let (a, b) = c.param_range();
        for i in 0..=40 {
            let u = a + (b - a) * i as f64 / 40.0;
            let d = c.derivatives(u);
            assert_eq!(c.point_and_tangent(u), (d.point, d.first), "u = {u}");
        }
        for piece in c.to_bezier() {
            for i in 0..=10 {
                let t = i as f64 / 10.0;
                let d = piece.derivatives(t);
                assert_eq!(piece.point_and_tangent(t), (d.point, d.first), "t = {t}");
            }
        }
    }

    #[test]
    fn circle_length_and_its_inverse() {
        let c = circle(Point::new(1.0, 2.0), 3.0).unwrap();
        assert!((c.arclen(1e-13) - 6.0 * PI).abs() < 1e-12);
        // A quarter of the length is reached at a quarter of the turn: the point there is
        // 90 degrees round from the start.
        let u = c.inv_arclen(1.5 * PI, 1e-13).unwrap();
        let q = c.point_at(u) - Point::new(1.0, 2.0);
        let start = c.start_point() - Point::new(1.0, 2.0);
        assert!(q.dot(start).abs() < 1e-9, "{q:?} {start:?}");
        let t = ArcLengthTable::new(&c, 32);
        assert!((t.length() - 6.0 * PI).abs() < 1e-10);
        for s in [0.5, 3.0, 10.0] {
            assert!((t.s_at(t.u_at(s)) - s).abs() < 1e-12);
        }
    }

    #[test]
    fn segment_length_is_the_distance() {
        let c = segment(Point::new(0.0, 0.0), Point::new(3.0, 4.0)).unwrap();
        assert!((c.arclen(1e-14) - 5.0).abs() < 1e-14);
        let u = c.inv_arclen(2.5, 1e-14).unwrap();
        assert!(c.point_at(u).distance(Point::new(1.5, 2.0)) < 1e-13);
        assert_eq!(c.inv_arclen(-1.0, 1e-14).unwrap(), c.param_range().0);
        assert_eq!(c.inv_arclen(9.0, 1e-14).unwrap(), c.param_range().1);
    }

    #[test]
    fn flatten_stays_within_tolerance() {
        let c = circle(Point::new(0.0, 0.0), 2.0).unwrap();
        for tol in [1e-2, 1e-4, 1e-7] {
            let mut pts = Vec::new();
            c.flatten(tol, &mut |p| pts.push(p));
            assert_eq!(pts.first(), Some(&c.start_point()));
            assert!(pts.last().unwrap().distance(c.end_point()) < 1e-15);
            // The chord midpoints are within tol of the circle, and the vertices on it.
            for w in pts.windows(2) {
                let m = (w[0] + w[1]) * 0.5;
                assert!(
                    2.0 - m.length() <= tol * (1.0 + 1e-9),
                    "{tol}: {}",
                    2.0 - m.length()
                );
                assert!((w[1].length() - 2.0).abs() < 1e-14);
            }
            // No more than about twice the optimal count: angle step 2 acos(1 - tol / r).
            let optimal = 2.0 * PI / (2.0 * (1.0 - tol / 2.0).acos());
            assert!(
                (pts.len() as f64) < 4.0 * optimal + 8.0,
                "{tol}: {}",
                pts.len()
            );
        }
        // A zero tolerance still terminates (raised to the floor, 1e-13 of the piece's size).
        let short = c.to_bezier()[0].subsegment((0.0, 0.01)).unwrap();
        let mut n = 0usize;
        short.flatten(0.0, &mut |_| n += 1);
        assert!(n > 1000 && n <= (1 << 20) + 1, "{n}");
    }

    #[test]
    fn flatten_after_start_drops_only_the_start_point() {
        let c = circle(Point::new(1.0, 0.5), 2.0).unwrap();
        for piece in [&c as &dyn Flatten, &c.to_bezier()[1]] {
            let (mut all, mut rest) = (Vec::new(), Vec::new());
            piece.flatten(1e-3, &mut |p| all.push(p));
            piece.flatten_after_start(1e-3, &mut |p| rest.push(p));
            assert!(all.len() > 4);
            assert_eq!(all[1..], rest[..]);
        }
        // A NURBS emits each break point between its pieces once.
        let mut pts = Vec::new();
        c.flatten(1e-3, &mut |p| pts.push(p));
        assert!(pts.windows(2).all(|w| w[0] != w[1]));
    }

    #[test]
    fn extrema_and_tight_box() {
        let c = NurbsCurve::bezier(
            vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 2.0),
                Point::new(2.0, 0.0),
            ],
            None,
        )
        .unwrap();
        assert_eq!(c.extrema().unwrap(), vec![0.5]);
        let b = c.bounding_box();
        assert!((b.max.y - 1.0).abs() < 1e-15);
        assert_eq!(c.control_bounding_box().max.y, 2.0);
        let (l, r) = c.subdivide();
        assert_eq!(l.end_point(), r.start_point());
        let mid = c.subsegment((0.25, 0.75)).unwrap();
        assert!(mid.start_point().distance(c.point_at(0.25)) < 1e-15);
        assert!(c.subsegment((0.5, 0.5)).is_err());
        assert!(c.subsegment((-0.1, 0.5)).is_err());
        assert!(c.split_at(1.0).is_err());
        // Green: the parabola closed by its chord (on y = 0, which adds nothing) bounds 4/3,
        // traversed clockwise.
        assert!((c.area_integral().value + 4.0 / 3.0).abs() < 1e-15);
        let half = c.area_integral_on(0.0, 0.5).value + c.area_integral_on(0.5, 1.0).value;
        assert!((half + 4.0 / 3.0).abs() < 1e-15);
    }
}
