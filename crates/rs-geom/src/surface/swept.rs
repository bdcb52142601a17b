//! The swept curve of a surface of revolution or of extrusion: its parameter range, period,
//! evaluation (a closed curve's parameter taken modulo its period) and sampling for the 1-D
//! closest-point searches.

use rs_spline::Point3;

use super::invert::sample_params;
use crate::{Curve, GeomError};

/// Samples per knot span (or per window of a curve without knots) of a swept curve in the 1-D
/// searches.
const SAMPLES_PER_SPAN: usize = 16;

/// The most samples of a swept curve in one 1-D search.
const MAX_SAMPLES: usize = 128;

/// The most doublings of the search window on an unbounded curve (lines, parabolas,
/// hyperbola branches): from a unit window, `2^60` times wider than any part of a model.
const MAX_WINDOW_DOUBLINGS: usize = 60;

/// Trimmed curves nested deeper than this are not searched for knots (files nest one).
const MAX_TRIM_DEPTH: usize = 8;

/// A curve swept into a surface.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Swept {
    pub(crate) curve: Curve<Point3>,
    /// The period where the curve is closed (an ellipse, a closed B-spline, a trimmed window
    /// of a whole period).
    pub(crate) period: Option<f64>,
    /// The parameter range: the curve's, `[0, 2 pi]` for a whole ellipse, infinite for lines,
    /// parabolas and hyperbolas.
    pub(crate) range: (f64, f64),
}

impl Swept {
    /// The curve with its range and period; an error when the curve's point at its start (at
    /// 0 when unbounded) is not finite.
    pub(crate) fn new(curve: Curve<Point3>) -> Result<Swept, GeomError> {
        let period = curve.period().filter(|&p| {
            curve
                .range()
                .is_none_or(|(a, b)| b - a >= p * (1.0 - 1e-12))
        });
        let range = match (curve.range(), period) {
            (Some(r), _) => r,
            (None, Some(p)) => (0.0, p),
            (None, None) => (f64::NEG_INFINITY, f64::INFINITY),
        };
        let start = if range.0.is_finite() { range.0 } else { 0.0 };
        let p = curve.point(start);
        if !p.is_finite() {
            return Err(GeomError::NotFinite {
                what: "swept curve point",
                value: p.max_abs(),
            });
        }
        Ok(Swept {
            curve,
            period,
            range,
        })
    }

    /// Is the range finite?
    pub(crate) fn is_bounded(&self) -> bool {
        self.range.0.is_finite() && self.range.1.is_finite()
    }

    /// `t` moved by whole periods into a closed curve's range.
    fn param(&self, t: f64) -> f64 {
        match self.period {
            Some(p) if self.is_bounded() => super::copy_from(t, self.range.0, p),
            _ => t,
        }
    }

    /// The point at `t`.
    pub(crate) fn point(&self, t: f64) -> Point3 {
        self.curve.point(self.param(t))
    }

    /// `[C, C', C'']` at `t`.
    pub(crate) fn derivatives(&self, t: f64) -> [Point3; 3] {
        self.curve.derivatives(self.param(t))
    }

    /// Sample parameters on `window` (finite): the knots of a B-spline inside it, and
    /// [`SAMPLES_PER_SPAN`] per interval between them, at most about [`MAX_SAMPLES`].
    pub(crate) fn samples(&self, window: (f64, f64)) -> Vec<f64> {
        let mut breaks = Vec::new();
        knots(&self.curve, &mut breaks, 0);
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        sample_params(window, &breaks, SAMPLES_PER_SPAN, MAX_SAMPLES)
    }

    /// The range if finite; otherwise a window `[t0 - T, t0 + T]` doubled from `T = 1` until
    /// `outside` holds at both ends (at most [`MAX_WINDOW_DOUBLINGS`] times): where a caller's
    /// lower bound of the distance exceeds a distance already reached.
    pub(crate) fn window(&self, t0: f64, outside: impl Fn(f64) -> bool) -> (f64, f64) {
        if self.is_bounded() {
            return self.range;
        }
        let mut half = 1.0f64.max(t0.abs());
        for _ in 0..MAX_WINDOW_DOUBLINGS {
            if outside(t0 - half) && outside(t0 + half) {
                break;
            }
            half *= 2.0;
        }
        (t0 - half, t0 + half)
    }

    /// The largest distance from `origin` of the curve's samples on its range (on `[-1, 1]`
    /// when unbounded), at least the smallest positive number.
    pub(crate) fn extent(&self, origin: Point3) -> f64 {
        let window = if self.is_bounded() {
            self.range
        } else {
            (-1.0, 1.0)
        };
        self.samples(window)
            .iter()
            .map(|&t| self.point(t).distance(origin))
            .filter(|d| d.is_finite())
            .fold(f64::MIN_POSITIVE, f64::max)
    }
}

/// Appends the knots of a B-spline curve (through trimmed windows) to `out`.
fn knots(curve: &Curve<Point3>, out: &mut Vec<f64>, depth: usize) {
    match curve {
        Curve::BSpline(b) => out.extend(b.knots().interior_breaks()),
        Curve::Trimmed { basis, .. } if depth < MAX_TRIM_DEPTH => knots(basis, out, depth + 1),
        _ => {}
    }
}
