//! Bezier extraction of one knot span of a NURBS curve in reused buffers: the arithmetic of
//! [`NurbsCurve::clamped`](crate::NurbsCurve::clamped) on the span's local curve (the same
//! Boehm insertions, projections and re-weightings, in the same order, so the same bits),
//! without its dozen allocations per span.

use crate::homogeneous::Hpoint;
use crate::{Point, RationalBezier};

/// The buffers one curve's spans are extracted in, reused from span to span.
#[derive(Default)]
pub(crate) struct SpanExtraction {
    knots: Vec<f64>,
    hp: Vec<Hpoint>,
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
                .map(|(&q, &w)| Hpoint::weighted(q, w)),
        );
        self.clamp_start(p);
        // `clamped()` builds the start-clamped curve from projected points and re-weights
        // them for the end: the same two roundings here.
        for h in &mut self.hp {
            *h = Hpoint::weighted(h.project(), h.w);
        }
        let j = self.clamp_end(p);
        let pieces = &self.hp[..j];
        RationalBezier::from_valid_parts(
            pieces.iter().map(|h| h.project()).collect(),
            pieces.iter().map(|h| h.w).collect(),
            (knots[k], knots[k + 1]),
        )
    }

    /// `u_0 = ... = u_p = a` (`a = u_p`, the domain's start), dropping what precedes.
    fn clamp_start(&mut self, p: usize) {
        let a = self.knots[p];
        while self.count(a) < p {
            self.insert_once(p, a);
        }
        let j = self.knots.iter().position(|&x| x == a).unwrap_or(0);
        let start = (j + self.count(a)).saturating_sub(p + 1);
        self.knots.drain(..start);
        self.knots[0] = a;
        self.hp.drain(..start);
    }

    /// `u_n = ... = u_{n+p} = b` (the domain's end); returns how many control points (from
    /// the first) the clamped curve keeps.
    fn clamp_end(&mut self, p: usize) -> usize {
        let b = self.knots[self.knots.len() - p - 1];
        while self.count(b) < p {
            self.insert_once(p, b);
        }
        self.knots.iter().position(|&x| x == b).unwrap_or(0)
    }

    fn count(&self, u: f64) -> usize {
        self.knots.iter().filter(|&&x| x == u).count()
    }

    /// Boehm's insertion of `u` once, in place: the new control points are computed from the
    /// top down, so each reads the old points `i - 1` and `i` before they are overwritten.
    fn insert_once(&mut self, p: usize, u: f64) {
        let n = self.hp.len();
        let knots = &self.knots;
        let k = if u >= knots[n] {
            knots.iter().rposition(|&x| x < u)
        } else {
            knots.iter().rposition(|&x| x <= u)
        }
        .unwrap_or(p);
        let last = self.hp[n - 1];
        self.hp.push(last);
        for i in (0..=n).rev() {
            self.hp[i] = if i + p <= k {
                self.hp[i]
            } else if i > k {
                self.hp[i - 1]
            } else {
                let alpha = (u - knots[i]) / (knots[i + p] - knots[i]);
                self.hp[i - 1].lerp(self.hp[i], alpha)
            };
        }
        self.knots.insert(k + 1, u);
    }
}
