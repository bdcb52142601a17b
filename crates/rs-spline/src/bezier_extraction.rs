//! Bezier extraction of one knot span of a NURBS curve in reused buffers: the arithmetic of
//! [`NurbsCurve::clamped`](crate::NurbsCurve::clamped) on the span's local curve (the same
//! Boehm insertions of [`crate::insertion`], projections and re-weightings, in the same order,
//! so the same bits), without its dozen allocations per span.

use crate::insertion::{Weighted, clamp_end, clamp_start};
use crate::{Point, RationalBezier};

/// The buffers one curve's spans are extracted in, reused from span to span.
#[derive(Default)]
pub(crate) struct SpanExtraction {
    knots: Vec<f64>,
    hp: Vec<Weighted<Point>>,
}

impl SpanExtraction {
    /// The Bezier piece of span `k` (`knots[k] < knots[k + 1]`, `p <= k < points.len()`) of
    /// the degree-`p` curve with `knots`, `points` and `weights`: its local curve (the `p + 1`
    /// control points `k - p ..= k` and the knots `k - p ..= k + p + 1`) clamped at the start,
    /// projected, re-weighted and clamped at the end, as `clamped()` does.
    pub(crate) fn piece(
        &mut self,
        p: usize,
        k: usize,
        knots: &[f64],
        points: &[Point],
        weights: &[f64],
    ) -> RationalBezier {
        self.knots.clear();
        self.knots.extend_from_slice(&knots[k - p..=k + p + 1]);
        self.hp.clear();
        self.hp.extend(
            points[k - p..=k]
                .iter()
                .zip(&weights[k - p..=k])
                .map(|(&q, &w)| Weighted::new(q, w)),
        );
        clamp_start(&mut self.knots, &mut self.hp, p);
        // `clamped()` builds the start-clamped curve from projected points and re-weights
        // them for the end: the same two roundings here.
        for h in &mut self.hp {
            *h = Weighted::new(h.project(), h.w);
        }
        clamp_end(&mut self.knots, &mut self.hp, p);
        RationalBezier::from_valid_parts(
            self.hp.iter().map(|h| h.project()).collect(),
            self.hp.iter().map(|h| h.w).collect(),
            (knots[k], knots[k + 1]),
        )
    }
}
