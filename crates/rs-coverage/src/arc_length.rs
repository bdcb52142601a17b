//! Cumulative arc-length integrals of one monotone piece as piecewise Chebyshev series, so that
//! the boundary's length and first moments in each cell are differences of two evaluations
//! instead of an adaptive quadrature per cell part.
//!
//! On `[0, 1]` the piece `c(t)` has the speed `s(t) = |c'(t)|`, smooth (a monotone piece has no
//! cusp: `x'` and `y'` keep their signs). With a reference point `r` (the piece's first control
//! point), `S(t) = int_0^t [1, x - r_x, y - r_y] s dt`. Each component is interpolated at the
//! 33 Chebyshev points of a sub-interval, the interval halved while the last three
//! coefficients exceed the values' rounding (`4 eps` of the largest coefficient, times the
//! piece's weight ratio: a rational piece's speed carries the rounding of its quotient rule,
//! which grows with it), and the series integrated exactly
//! (`int T_k = (T_{k+1} / (k + 1) - T_{k-1} / (k - 1)) / 2`). Strong weights concentrate the
//! speed near the ends (a middle weight of `1e8` puts most of the length in `1e-8` of the
//! parameters): the halving follows it there, where one adaptive quadrature over a part can
//! miss it. A piece that needs more than [`MAX_SPANS`] sub-intervals has no table
//! ([`ArcLengthTable::new`] is `None`): its parts take the bounded adaptive rule instead
//! (`Arc::arc_length_integrals`). A part's
//! length is then `S_0(t1) - S_0(t0)`, its moment about a cell corner `c`
//! `S_1(t1) - S_1(t0) + (r_x - c_x) length`: rounding of about `eps` times the piece's own
//! length and size (times the weight ratio for a rational piece: the rounding of its speed),
//! far below the `1e-12` of a cell the outputs promise on grids up to `10^5` cells a side for
//! polynomial pieces and circles.

use std::sync::OnceLock;

use rs_boxes::BezierPiece;
use rs_spline::Point;

/// Chebyshev points per sub-interval minus one.
const N: usize = 32;

/// Most sub-intervals of one piece's table (about 210 KB): beyond it the piece's parts take
/// the adaptive rule.
pub(crate) const MAX_SPANS: usize = 256;

/// The factors by which [`ArcLengthTable::new`] takes the speed's rounding larger, in turn,
/// until its series converge within [`MAX_SPANS`] sub-intervals.
const NOISE_RETRIES: [f64; 3] = [1.0, 8.0, 64.0];

/// `cos(pi m / N)` for `m` in `0 .. 2N`.
fn cosines() -> &'static [f64; 2 * N] {
    static TABLE: OnceLock<[f64; 2 * N]> = OnceLock::new();
    TABLE
        .get_or_init(|| std::array::from_fn(|m| (std::f64::consts::PI * m as f64 / N as f64).cos()))
}

/// One sub-interval: its ends and the antiderivatives' Chebyshev coefficients (in the
/// sub-interval's own variable on `[-1, 1]`, scaled by its half width), plus `S` at its start.
struct Span {
    a: f64,
    b: f64,
    start: [f64; 3],
    coeffs: [[f64; N + 2]; 3],
}

/// The cumulative arc-length integrals of a piece ([module docs](self)).
pub(crate) struct ArcLengthTable {
    reference: Point,
    spans: Vec<Span>,
}

impl ArcLengthTable {
    /// The table of `piece` on `[0, 1]`, or `None` if it needs more than [`MAX_SPANS`]
    /// sub-intervals even with the speed's rounding taken [`NOISE_RETRIES`] times larger.
    pub(crate) fn new(piece: &BezierPiece) -> Option<Self> {
        // The rounding the speed's values carry, relative to their size: about the weights'
        // ratio in units of rounding; where the series' tails do not fall below that (the
        // speed cancels more: a part halved from a strongly weighted piece, nearly straight
        // and turning within a sliver), eight and 64 times it.
        let weights = piece.weights();
        let (wmin, wmax) = weights
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), &w| {
                (lo.min(w), hi.max(w))
            });
        let noise = 4.0 * f64::EPSILON * (wmax / wmin).max(1.0);
        NOISE_RETRIES
            .iter()
            .find_map(|&k| Self::with_noise(piece, k * noise))
    }

    /// [`ArcLengthTable::new`] with the speed's rounding taken as `noise` (relative).
    fn with_noise(piece: &BezierPiece, noise: f64) -> Option<Self> {
        let reference = piece.control_point(0);
        let relative = piece.relative_to(reference);
        let f = |t: f64| {
            let (u, v, dx, dy) = relative.point_and_derivatives(t);
            let ds = (dx * dx + dy * dy).sqrt();
            [ds, u * ds, v * ds]
        };
        let mut spans = Vec::new();
        let mut stack = vec![(0.0, 1.0)];
        let mut start = [0.0; 3];
        // Left to right: the stack holds the right halves still to do; every halving adds
        // one sub-interval, so the work is bounded by `MAX_SPANS`.
        while let Some((a, b)) = stack.pop() {
            let (coeffs, converged) = interpolate(&f, a, b, noise);
            if !converged {
                if spans.len() + stack.len() + 2 > MAX_SPANS {
                    return None;
                }
                let m = 0.5 * (a + b);
                stack.push((m, b));
                stack.push((a, m));
                continue;
            }
            let half = 0.5 * (b - a);
            let integrals = coeffs.map(|c| antiderivative(&c, half));
            let span = Span {
                a,
                b,
                start,
                coeffs: integrals,
            };
            // The antiderivative vanishes at the start: its value at the end is the span's.
            for (s, c) in start.iter_mut().zip(&span.coeffs) {
                *s += c.iter().sum::<f64>();
            }
            spans.push(span);
        }
        Some(Self { reference, spans })
    }

    /// `S(t)` ([module docs](self)), `t` clamped into `[0, 1]`.
    fn at(&self, t: f64) -> [f64; 3] {
        let t = t.clamp(0.0, 1.0);
        let k = self
            .spans
            .partition_point(|s| s.b < t)
            .min(self.spans.len() - 1);
        let s = &self.spans[k];
        let x = ((2.0 * t - s.a - s.b) / (s.b - s.a)).clamp(-1.0, 1.0);
        std::array::from_fn(|c| s.start[c] + clenshaw(&s.coeffs[c], x))
    }

    /// `[int ds, int (x - c_x) ds, int (y - c_y) ds]` over `[t0, t1]`, about `corner`.
    pub(crate) fn integrals(&self, (t0, t1): (f64, f64), corner: Point) -> [f64; 3] {
        let (s0, s1) = (self.at(t0), self.at(t1));
        let len = s1[0] - s0[0];
        [
            len,
            (s1[1] - s0[1]) + (self.reference.x - corner.x) * len,
            (s1[2] - s0[2]) + (self.reference.y - corner.y) * len,
        ]
    }
}

/// The Chebyshev coefficients (first kind, `a_0` whole) of the three components of `f` on
/// `[a, b]` from its values at the `N + 1` Chebyshev points, and whether every component's
/// last three coefficients are below `noise` times its largest.
fn interpolate(
    f: &impl Fn(f64) -> [f64; 3],
    a: f64,
    b: f64,
    noise: f64,
) -> ([[f64; N + 1]; 3], bool) {
    let cos = cosines();
    let values: Vec<[f64; 3]> = (0..=N)
        .map(|j| f(0.5 * (a + b) + 0.5 * (b - a) * cos[j]))
        .collect();
    let mut coeffs = [[0.0; N + 1]; 3];
    for k in 0..=N {
        for (j, v) in values.iter().enumerate() {
            let w = if j == 0 || j == N { 0.5 } else { 1.0 };
            let c = w * cos[(k * j) % (2 * N)];
            for (out, v) in coeffs.iter_mut().zip(v) {
                out[k] += c * v;
            }
        }
    }
    let mut converged = true;
    for c in &mut coeffs {
        for (k, ck) in c.iter_mut().enumerate() {
            *ck *= if k == 0 || k == N { 1.0 } else { 2.0 } / N as f64;
        }
        let largest = c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let tail = c[N - 2..].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        converged &= tail <= noise * largest;
    }
    (coeffs, converged)
}

/// The coefficients of `half * int_{-1}^x f`, `f = sum a_k T_k` (degree `N + 1`).
fn antiderivative(a: &[f64; N + 1], half: f64) -> [f64; N + 2] {
    let at = |k: usize| a.get(k).copied().unwrap_or(0.0);
    let mut c = [0.0; N + 2];
    c[1] = at(0) - 0.5 * at(2);
    for (k, ck) in c.iter_mut().enumerate().skip(2) {
        *ck = (at(k - 1) - at(k + 1)) / (2 * k) as f64;
    }
    // The constant making the value at -1 zero: T_k(-1) = (-1)^k.
    c[0] = -c
        .iter()
        .enumerate()
        .skip(1)
        .map(|(k, v)| if k % 2 == 0 { *v } else { -v })
        .sum::<f64>();
    c.map(|v| v * half)
}

/// `sum c_k T_k(x)` by Clenshaw's recurrence.
fn clenshaw(c: &[f64], x: f64) -> f64 {
    let (mut b1, mut b2) = (0.0, 0.0);
    for &ck in c.iter().skip(1).rev() {
        (b1, b2) = (2.0 * x * b1 - b2 + ck, b1);
    }
    c[0] + x * b1 - b2
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_boxes::{BoxOptions, MonotoneBoxes};
    use rs_spline::{Domain, NurbsCurve, polyline};

    /// The tables of the monotone pieces of the quadratic `(0,0), (1,0), (1,1)` with middle
    /// weight `w`, closed by its chord: their sub-interval counts.
    fn spans(w: f64) -> Vec<Option<usize>> {
        let pts = vec![
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
        ];
        let q = NurbsCurve::bezier(pts, Some(vec![1.0, w, 1.0])).unwrap();
        let chord = polyline(&[Point::new(1.0, 1.0), Point::new(0.0, 0.0)]).unwrap();
        let d = Domain::new(vec![q, chord]).unwrap();
        let boxes = MonotoneBoxes::new(&d, BoxOptions::DEFAULT.with_subdivisions(1)).unwrap();
        boxes
            .pieces()
            .iter()
            .map(|p| ArcLengthTable::new(p.piece()).map(|t| t.spans.len()))
            .collect()
    }

    #[test]
    fn strong_weights_are_followed_to_the_ends_within_the_bound() {
        for w in [1.0, 1e4, 1e8, 1e12] {
            for n in spans(w) {
                let n = n.unwrap_or_else(|| panic!("weight {w}: no table"));
                assert!(n <= 128, "weight {w}: {n} sub-intervals");
            }
        }
    }

    #[test]
    fn chebyshev_antiderivatives_are_exact_on_polynomials() {
        // f = 1 + 2 x + 3 x^2 on [-1, 1]: a = [2.5, 2, 1.5] (x^2 = (T0 + T2) / 2).
        let mut a = [0.0; N + 1];
        a[0] = 2.5;
        a[1] = 2.0;
        a[2] = 1.5;
        let c = antiderivative(&a, 1.0);
        for x in [-1.0, -0.3, 0.0, 0.5, 1.0] {
            let want = (x + x * x + x * x * x) - (-1.0 + 1.0 - 1.0);
            assert!((clenshaw(&c, x) - want).abs() < 1e-14, "{x}");
        }
    }
}
