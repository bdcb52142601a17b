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
                    let speed = |u: f64| {
                        let v = self.derivatives(u).first.length();
                        (v, v)
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
                let d = self.derivatives(u).first.length();
                (self.arclen_on(a, u, accuracy).value - s, d)
            },
            a,
            b,
            xtol,
        )
    }
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
    /// from the curve is at most `tolerance` (absolute): each Bezier piece is halved until the
    /// control points of every part are within `tolerance` of its chord (convex-hull
    /// property). The tolerance is raised to `1e-13` of a piece's control-box diagonal at the
    /// least, and halving stops at depth 40, so the work is bounded for every input.
    fn flatten(&self, tolerance: f64, emit: &mut dyn FnMut(Point));
}

/// The traits, for `use rs_spline::prelude::*`.
pub mod prelude {
    pub use super::{
        Flatten, ParamCurve, ParamCurveArclen, ParamCurveArea, ParamCurveDeriv, ParamCurveExtrema,
    };
}
