//! Rational pieces whose weights crowd their motion into slivers at their parameter ends, and
//! the reparametrisation that spreads it out again: **the** decision, shared by the Bezier
//! pieces here ([`RationalBezier::balanced_parts`](crate::RationalBezier::balanced_parts)) and
//! the monotone boxes of `rs-boxes`.
//!
//! A rational piece of weights `w_i` is the same curve with weights `w_i c^i` for any `c > 0`
//! (a Mobius reparametrisation: the new piece at `s` is the old one at
//! `t = c s / ((1 - s) + c s)`); with `c` a power of two every weight is scaled exactly. A
//! piece whose end weights differ greatly moves within a sliver at one parameter end, and one
//! whose inner weights dwarf both ends (a quadratic of weights `1, w, 1` stays near its middle
//! control point for parameters between about `1 / w` and `1 - 1 / w`) at both: there an
//! adaptive rule started from Gauss nodes does not look, and near `t = 1` the parameter's own
//! resolution is too coarse. Balanced end weights and halving fix both.

/// End-weight ratio above which a piece is reparametrised to equal end weights, and the ratio
/// of its largest weight to its end weights above which it is halved: `2^10`, far above the
/// ratios of conics and ordinary NURBS (whose pieces so keep their parametrisation), far below
/// the `1e7` from which a piece's integrals lose digits.
pub const BALANCE_RATIO: f64 = 1024.0;

/// The most halvings of a piece: each takes about the square root of the weights' spread, so
/// six bring the format's largest ratio, `1e12`, far below [`BALANCE_RATIO`] (at most 64
/// parts).
pub const MAX_BALANCE_HALVINGS: u32 = 6;

/// The exponent `k` that balances `weights` (of a piece of degree `n = len - 1 >= 1`): with
/// `c = 2^k` the power of two nearest `(w_0 / w_n)^(1/n)`, the weights `w_i c^i` have end
/// weights within `2^(n/2)` of each other. 0 when the end weights are within
/// [`BALANCE_RATIO`] of each other (the piece is left as it is).
pub fn balancing_exponent(weights: &[f64]) -> i32 {
    let n = weights.len().saturating_sub(1);
    if n == 0 {
        return 0;
    }
    // The ratio's logarithm as a difference (the ratio itself of weights `1e-300` and `1e300`
    // would underflow): within 2^11 for positive weights, so `|k i| <= |log2 ratio| + n / 2`
    // stays inside `powi`'s range whatever the degree.
    let log_ratio = weights[0].log2() - weights[n].log2();
    if !log_ratio.is_finite() || log_ratio.abs() <= BALANCE_RATIO.log2() {
        return 0;
    }
    (log_ratio / n as f64).round() as i32
}

/// Whether the largest of `weights` exceeds the smaller end weight by more than
/// [`BALANCE_RATIO`]: a piece (with balanced ends) that moves within slivers at both ends,
/// to be halved.
pub fn crowds_ends(weights: &[f64]) -> bool {
    let ends = weights[0].min(weights[weights.len() - 1]);
    let largest = weights.iter().copied().fold(0.0f64, f64::max);
    largest > BALANCE_RATIO * ends
}

/// The fraction `tau` of `[0, 1]` whose odds `tau / (1 - tau)` are `odds` times those of `s`:
/// `odds s / ((1 - s) + odds s)`, `s` itself when `odds` is 1 (the Mobius maps of `[0, 1]`
/// onto itself that fix both ends; they compose by multiplying their factors).
pub fn odds_map(odds: f64, s: f64) -> f64 {
    if odds == 1.0 {
        s
    } else {
        odds * s / ((1.0 - s) + odds * s)
    }
}

/// A rational piece that [`balanced_parts`] cuts: its weights, its reweighting by a power of
/// two, and its halves. (The Bezier pieces here and the monotone boxes' pieces of `rs-boxes`,
/// which keep homogeneous coefficients beside their points.)
pub trait Balance: Sized {
    /// Its weights `w_0 .. w_n` (all positive).
    fn balance_weights(&self) -> &[f64];

    /// The same curve with weights `w_i 2^(k i)` and the factor `c = 2^k` of the
    /// reparametrisation (the new piece at `s` is the old one at `t = odds_map(c, s)`);
    /// itself and 1 when a scaled value would leave the normal range.
    fn reweighted(self, k: i32) -> (Self, f64);

    /// Its halves, on `[0, 1/2]` and `[1/2, 1]`, each reparametrised to `[0, 1]`.
    fn halves(&self) -> (Self, Self);

    /// The same curve with its end weights balanced ([`balancing_exponent`]), and the factor
    /// of the reparametrisation (1 for a piece left as it is).
    fn balanced(self) -> (Self, f64) {
        match balancing_exponent(self.balance_weights()) {
            0 => (self, 1.0),
            k => self.reweighted(k),
        }
    }
}

/// Scales entry `i` of every one of `columns` (a piece's weights, and any coefficients that
/// carry them) by `2^(k i)`, exactly, and returns the factor `2^k`; leaves them all as they
/// are and returns `None` when a nonzero entry would leave the normal range.
pub fn scale_by_powers_of_two(k: i32, columns: &mut [&mut [f64]]) -> Option<f64> {
    let scale = |i: usize| 2f64.powi(k * i as i32);
    let normal = columns.iter().all(|c| {
        c.iter()
            .enumerate()
            .all(|(i, &v)| v == 0.0 || (v * scale(i)).is_normal())
    });
    if !normal {
        return None;
    }
    for c in columns.iter_mut() {
        for (i, v) in c.iter_mut().enumerate() {
            *v *= scale(i);
        }
    }
    Some(2f64.powi(k))
}

/// A part of a piece ([`balanced_parts`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Part<P> {
    /// The part, on `[0, 1]`.
    pub piece: P,
    /// The fractions of the piece's parameter it spans.
    pub fractions: (f64, f64),
    /// The odds factor mapping its own parameter onto that span: its `s` lies
    /// [`odds_map`]`(odds, s)` of the way along it.
    pub odds: f64,
}

/// The piece as parts whose motion fills their parameter, in order: its end weights balanced
/// ([`balancing_exponent`]), and, while a part [`crowds_ends`], the part halved and each half
/// balanced again, at most [`MAX_BALANCE_HALVINGS`] times (at most 64 parts). Each part's odds
/// compose its own balancing with the restriction of its parent's Mobius map to the half
/// (whose factor is the map's slope at the half's start over the half's share of its image:
/// `(1 + a) / 2` for the first half of a map of factor `a`, `2 a / (1 + a)` for the second).
/// An ordinary piece is one part, itself, with odds 1.
pub fn balanced_parts<P: Balance>(piece: P) -> Vec<Part<P>> {
    fn walk<P: Balance>(
        piece: P,
        fractions: (f64, f64),
        odds: f64,
        depth: u32,
        out: &mut Vec<Part<P>>,
    ) {
        let (piece, c) = piece.balanced();
        let odds = odds * c;
        if depth >= MAX_BALANCE_HALVINGS || !crowds_ends(piece.balance_weights()) {
            out.push(Part {
                piece,
                fractions,
                odds,
            });
            return;
        }
        let (f0, f1) = fractions;
        let mid = f0 + (f1 - f0) * odds_map(odds, 0.5);
        let (left, right) = piece.halves();
        walk(left, (f0, mid), (1.0 + odds) / 2.0, depth + 1, out);
        walk(right, (mid, f1), 2.0 * odds / (1.0 + odds), depth + 1, out);
    }
    let mut out = Vec::with_capacity(1);
    walk(piece, (0.0, 1.0), 1.0, 0, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ends within the ratio stay; beyond it the exponent balances them within `2^(n/2)`,
    /// however far apart the weights (no overflow of the ratio or of `k i`); a middle weight
    /// that dwarfs both ends crowds them.
    #[test]
    fn exponents_balance_any_positive_weights() {
        assert_eq!(balancing_exponent(&[1.0, 0.7, 1.0]), 0);
        assert_eq!(balancing_exponent(&[1.0, 5.0, 1000.0]), 0);
        assert_eq!(balancing_exponent(&[1.0]), 0);
        for w in [
            vec![1.0, 1.0, 4096.0],
            vec![1e-300, 1.0, 1e300],
            vec![1e300, 1.0, 1e-300],
            vec![f64::MIN_POSITIVE / 1e10, 2.0, 3.0, f64::MAX],
        ] {
            let n = w.len() - 1;
            let k = balancing_exponent(&w);
            // The new end weights are `w_0` and `w_n 2^(k n)`.
            let log_ratio = w[0].log2() - w[n].log2() - f64::from(k) * n as f64;
            assert!(log_ratio.abs() <= n as f64 / 2.0, "{w:?}: k {k}");
        }
        assert!(crowds_ends(&[1.0, 1e4, 1.0]));
        assert!(!crowds_ends(&[1.0, 1000.0, 2.0]));
        // Weights as far apart as a curve may have them (`limits::MAX_WEIGHT_RATIO`): the parts
        // are bounded (at most 64) and the area converges.
        use crate::ParamCurveArea;
        for w in [
            vec![1.0, 1e12, 1.0],
            vec![1e-6, 1.0, 1e6],
            vec![1e6, 1e-6, 1.0],
        ] {
            let p = crate::Point::new;
            let piece =
                crate::RationalBezier::new(vec![p(0.0, 0.0), p(0.5, 1.0), p(1.0, 0.0)], w.clone())
                    .unwrap();
            let parts = piece.balanced_parts().unwrap();
            assert!(!parts.is_empty() && parts.len() <= 64, "{w:?}");
            let area = piece.area_integral();
            assert!(area.converged && area.value.is_finite(), "{w:?}: {area:?}");
        }
        assert_eq!(odds_map(1.0, 0.3), 0.3);
        // Scaling by powers of two: exact, zeros kept, nothing touched when a value would leave
        // the normal range.
        let (mut w, mut h) = ([1.0, 3.0, 0.1], [0.0, -1.5, 7.0]);
        assert_eq!(scale_by_powers_of_two(2, &mut [&mut w, &mut h]), Some(4.0));
        assert_eq!((w, h), ([1.0, 12.0, 1.6], [0.0, -6.0, 112.0]));
        let mut tiny = [1.0, 1e-300];
        assert_eq!(scale_by_powers_of_two(-100, &mut [&mut tiny]), None);
        assert_eq!(tiny, [1.0, 1e-300]);
        assert!((odds_map(4.0, 0.5) - 0.8).abs() < 1e-16);
    }
}
