//! A positive interior formula of vertical chords (Gauss-Green): the candidates, and the
//! reference rule, of the rules of high degree.
//!
//! The boundary's monotone pieces (those of loops that bound the filled set, vertical ones
//! left out) cut the `x` axis at their end abscissas. Over each interval `(a, b)` between
//! consecutive cuts the same pieces span the whole interval and none ends inside it, so the
//! vertical line at any `x` of it meets them in the same order: sorted by ordinate, they pair
//! up from the bottom into the chords of the filled set (below the lowest the set is empty,
//! and the fill changes at every crossing of a loop that bounds it). Then
//!
//! `integral f dA = sum over intervals of integral_a^b sum over chords integral_y0^y1 f dy dx`,
//!
//! the inner integrals by Gauss-Legendre with `n / 2 + 1` nodes (exact in `y` for degree `n`)
//! and the outer by Gauss-Legendre in `s` of `[0, 1]`. Where a spanning piece stops moving in
//! `x` at an end of the interval (a vertical tangent: `x - a` like `t^2`, the ordinate like
//! `sqrt(x - a)`; or three control points on a vertical line, `t^3`) the map
//! `x = a + (b - a) I_s(p, q)` of [`OuterMap`] makes the chords' ends smooth in `s` again.
//! Each interval's outer order starts at 4 and grows by half until the interval's moments
//! agree with the next order's.
//!
//! Every node lies strictly inside its chord and every weight is positive: a positive interior
//! formula with more nodes than `dim P_n` (about 1.5 to 10 times), whose own moments are
//! consistent with its nodes by construction. Compressing it (`compress` with the formula as
//! the reference rule) takes the moments from the formula itself, `b = Q^T w`, and so needs
//! only a small shift in the orthonormalisation (see `orthogonal`), where Halton points and
//! boundary layers take theirs from Green's theorem through the factor.

use rs_boxes::{MonotoneBox, Monotonicity};
use rs_spline::Point;
use rs_spline::quadrature::gauss_rule;

use crate::basis::{LegendreBasis, graded_products};

/// A positive formula: nodes and their weights.
#[derive(Clone, Debug, Default)]
pub(crate) struct ChordFormula {
    pub(crate) points: Vec<Point>,
    pub(crate) weights: Vec<f64>,
}

/// A control point's offset from its piece's end point is on the vertical line through the end,
/// for the outer map's order ([`end_order`]), when `|dx| <= VERTICAL_SLOPE |d|`.
const VERTICAL_SLOPE: f64 = 1e-3;

/// An interval's outer order is accepted when its moments agree with those of the next order
/// (half as many nodes again) within this times the area (the moments' scale: the area is the
/// first, and `|phi_k| <= n + 1`), or within their own rounding, `eps (n + 1)` times the
/// interval's area: the lower order's error is then about that change.
const OUTER_TOLERANCE: f64 = 1e-15;

/// The first outer order of an interval (a short or straight interval needs no more).
const FIRST_OUTER_ORDER: usize = 4;

/// The highest outer order compared: an interval whose order 32 does not agree with 48 is cut
/// in two halves instead. A chord's end with a singularity near the interval (a circle's
/// arc towards its branch point beyond the interval's end: the lune's arcs needed 72) converges
/// faster on halves, each farther from it relative to its width, than by raising the order.
const MAX_OUTER_ORDER: usize = 48;

/// Most halvings of an interval (a width of `2^-12` of it); the last order is taken there.
const MAX_SPLITS: usize = 12;

/// The formula of degree `degree` on the domain of the monotone pieces `pieces`
/// ([`MonotoneBoxes::pieces`](rs_boxes::MonotoneBoxes::pieces)), the pieces of curve `c`
/// counted when `signs[c] != 0` (the loops that bound the filled set); `None` when it would
/// have more than `max_points` nodes, or when a vertical line meets the counted pieces an odd
/// number of times (loops touching where the rounding of the crossings decides their order).
pub(crate) fn chord_formula(
    pieces: &[MonotoneBox],
    signs: &[i64],
    basis: &LegendreBasis,
    degree: usize,
    area: f64,
    max_points: usize,
) -> Option<ChordFormula> {
    let kept: Vec<&MonotoneBox> = pieces
        .iter()
        .filter(|b| signs.get(b.curve).is_some_and(|&s| s != 0))
        .filter(|b| b.x_dir != Monotonicity::Constant)
        .collect();
    let mut cuts: Vec<f64> = kept
        .iter()
        .flat_map(|b| [b.band.xmin, b.band.xmax])
        .collect();
    if cuts.iter().any(|x| !x.is_finite()) {
        return None;
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    // Every interval but those between loops (at most one fewer than the loops) holds a chord
    // and so at least 4 nodes: more intervals than that cannot fit the budget.
    let loops = kept.iter().map(|b| b.boundary_loop + 1).max().unwrap_or(0);
    if cuts.len() > max_points.saturating_add(loops + 1) {
        return None;
    }
    let inner = degree / 2 + 1;
    // Each pair of spanning pieces makes at least `4 inner` nodes per interval.
    let per_pair = FIRST_OUTER_ORDER * inner;
    let mut spanning: Vec<Vec<usize>> = vec![Vec::new(); cuts.len().saturating_sub(1)];
    let mut least_nodes = 0usize;
    for (i, b) in kept.iter().enumerate() {
        let first = cuts.partition_point(|&c| c < b.band.xmin);
        let last = cuts.partition_point(|&c| c < b.band.xmax);
        for s in &mut spanning[first..last] {
            s.push(i);
            if s.len() % 2 == 0 {
                least_nodes += per_pair;
            }
        }
        if least_nodes > max_points {
            return None;
        }
    }
    let mut formula = ChordFormula::default();
    let mut scratch = vec![0.0; basis.scratch_len()];
    let fit = Fit {
        basis,
        area,
        max_points,
    };
    for (k, pieces) in spanning.iter().enumerate() {
        if pieces.is_empty() {
            continue;
        }
        if pieces.len() % 2 != 0 {
            return None;
        }
        let pieces: Vec<&MonotoneBox> = pieces.iter().map(|&i| kept[i]).collect();
        let interval = Interval::new(cuts[k], cuts[k + 1], &pieces, inner);
        interval.append_converged(&fit, 0, &mut scratch, &mut formula)?;
    }
    Some(formula)
}

/// What every interval's orders are chosen against: the basis whose moments must agree, the
/// moments' scale (the area), and the most nodes of the whole formula.
struct Fit<'a> {
    basis: &'a LegendreBasis,
    area: f64,
    max_points: usize,
}

/// How an interval's outer variable `s` of `[0, 1]` maps to `x`: `x = a + h I_s(p, q)`, with
/// `h = b - a` and `I_s(p, q) = sum_{j = p}^{p + q - 1} C(p + q - 1, j) s^j (1 - s)^(p + q - 1 - j)`
/// the regularised incomplete beta function of integer orders, `dx / ds = h s^(p - 1)
/// (1 - s)^(q - 1) / B(p, q)`. `x - a` vanishes like `s^p` at `s = 0` and `b - x` like
/// `(1 - s)^q` at `s = 1`: where a piece's `x(t) - a` vanishes like `t^p` at the end (a
/// vertical tangent, `p = 2`; three control points on a vertical line, `p = 3`), `t` is then
/// smooth in `s` and so are the chords' ends. `(1, 1)` is `x = a + h s`, `(2, 1)`
/// `x = a + h s^2`, `(2, 2)` `x = a + h (3 s^2 - 2 s^3)`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct OuterMap {
    p: usize,
    q: usize,
}

impl OuterMap {
    /// `(I_s(p, q), dI/ds)`.
    fn at(self, s: f64) -> (f64, f64) {
        let (p, q) = (self.p, self.q);
        let n = p + q - 1;
        let r = 1.0 - s;
        let mut value = 0.0;
        for j in p..=n {
            value += binomial(n, j) * s.powi(j as i32) * r.powi((n - j) as i32);
        }
        // 1 / B(p, q) = (p + q - 1)! / ((p - 1)! (q - 1)!) = p C(n, p) for n = p + q - 1.
        let derivative = p as f64 * binomial(n, p) * s.powi(p as i32 - 1) * r.powi(q as i32 - 1);
        (value, derivative)
    }
}

/// `C(n, k)` for the small `n` of [`OuterMap`].
fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64)
}

/// The highest order of [`OuterMap`] at an end (a piece of degree `d` vanishes to order at
/// most `d`; the pieces here have degree at most 32, and orders above 4 were not seen).
const MAX_END_ORDER: usize = 6;

/// One interval between consecutive cuts and the pieces spanning it.
struct Interval<'a> {
    a: f64,
    b: f64,
    pieces: &'a [&'a MonotoneBox],
    map: OuterMap,
    inner: usize,
}

impl<'a> Interval<'a> {
    fn new(a: f64, b: f64, pieces: &'a [&'a MonotoneBox], inner: usize) -> Self {
        // The order at abscissa `x`: the largest of the pieces that end there.
        let order_at = |x: f64| {
            pieces
                .iter()
                .flat_map(|p| {
                    let (start, end) = match p.x_dir {
                        Monotonicity::Increasing => (p.band.xmin, p.band.xmax),
                        _ => (p.band.xmax, p.band.xmin),
                    };
                    [
                        (start == x).then(|| end_order(p, true)),
                        (end == x).then(|| end_order(p, false)),
                    ]
                })
                .flatten()
                .fold(1, usize::max)
        };
        Self {
            a,
            b,
            pieces,
            map: OuterMap {
                p: order_at(a),
                q: order_at(b),
            },
            inner,
        }
    }

    /// `(x, dx/ds)` at `s`.
    fn x_at(&self, s: f64) -> (f64, f64) {
        let h = self.b - self.a;
        let (value, derivative) = self.map.at(s);
        (self.a + h * value, h * derivative)
    }

    /// The interval's nodes with `outer` nodes in `s` into `out`; `None` if a vertical line
    /// meets the pieces an odd number of times or misses one.
    fn nodes(&self, outer: usize, out: &mut ChordFormula) -> Option<()> {
        let outer_rule = gauss_rule(outer)?;
        let inner_rule = gauss_rule(self.inner)?;
        let (half, pairs) = outer_rule.on(0.0, 1.0);
        let mut ys = Vec::with_capacity(self.pieces.len());
        for (s, ws) in pairs {
            let (x, dx) = self.x_at(s);
            let weight = half * ws * dx;
            if weight.is_nan() || weight <= 0.0 {
                continue;
            }
            ys.clear();
            for p in self.pieces {
                ys.push(p.at_x(x)?.1);
            }
            if ys.len() % 2 != 0 || ys.iter().any(|y| !y.is_finite()) {
                return None;
            }
            ys.sort_by(f64::total_cmp);
            for chord in ys.chunks_exact(2) {
                let (h, pairs) = inner_rule.on(chord[0], chord[1]);
                for (y, wy) in pairs {
                    let w = weight * h * wy;
                    if w > 0.0 {
                        out.points.push(Point::new(x, y));
                        out.weights.push(w);
                    }
                }
            }
        }
        Some(())
    }

    /// Appends the interval's nodes at the first outer order whose moments agree with the
    /// next one's (see [`OUTER_TOLERANCE`]); when none up to [`MAX_OUTER_ORDER`] does, the
    /// two halves' nodes instead (at most [`MAX_SPLITS`] deep, where the last order is taken).
    fn append_converged(
        &self,
        fit: &Fit<'_>,
        depth: usize,
        scratch: &mut [f64],
        out: &mut ChordFormula,
    ) -> Option<()> {
        let (basis, area) = (fit.basis, fit.area);
        let mut order = FIRST_OUTER_ORDER;
        let mut current = ChordFormula::default();
        self.nodes(order, &mut current)?;
        let mut moments = formula_moments(basis, &current, scratch);
        loop {
            let next_order = order + order.div_ceil(2);
            if next_order > MAX_OUTER_ORDER {
                if depth < MAX_SPLITS {
                    let middle = 0.5 * (self.a + self.b);
                    let (left, right) = self.halves(middle);
                    left.append_converged(fit, depth + 1, scratch, out)?;
                    return right.append_converged(fit, depth + 1, scratch, out);
                }
                break;
            }
            let mut next = ChordFormula::default();
            self.nodes(next_order, &mut next)?;
            let next_moments = formula_moments(basis, &next, scratch);
            // A moment that is not a number never agrees.
            let change = moments
                .iter()
                .zip(&next_moments)
                .map(|(m, n)| (m - n).abs())
                .fold(
                    0.0f64,
                    |c, d| if d.is_nan() { f64::INFINITY } else { c.max(d) },
                );
            let rounding =
                f64::EPSILON * (basis.degree() + 1) as f64 * current.weights.iter().sum::<f64>();
            if change <= (OUTER_TOLERANCE * area).max(rounding) {
                break;
            }
            (current, moments, order) = (next, next_moments, next_order);
        }
        // The budget bounds the work too: halvings could otherwise make `2^MAX_SPLITS`
        // intervals of an interval whose moments never agree.
        if out.points.len() + current.points.len() > fit.max_points {
            return None;
        }
        out.points.extend_from_slice(&current.points);
        out.weights.extend_from_slice(&current.weights);
        Some(())
    }

    /// The interval cut at `middle`: the same pieces, each half keeping the map's order at
    /// its outer end.
    fn halves(&self, middle: f64) -> (Self, Self) {
        let half = |a, b, p, q| Interval {
            a,
            b,
            pieces: self.pieces,
            map: OuterMap { p, q },
            inner: self.inner,
        };
        (
            half(self.a, middle, self.map.p, 1),
            half(middle, self.b, 1, self.map.q),
        )
    }
}

/// `sum_i w_i phi_k(x_i)` for every basis polynomial. The nodes of one outer node's chords
/// share its abscissa and come one after another (`Interval::nodes`), and `phi_ij` is the
/// product of a factor in `x` and one in `y`: over each run of nodes with the same `x`, the
/// sums `S_j = sum w P_j(y)` (`n + 1` values a node) and then `P_i(x) S_j` (`dim P_n` a run),
/// instead of `dim P_n` products a node (the formula took a tenth of a degree-40 rule).
fn formula_moments(basis: &LegendreBasis, f: &ChordFormula, scratch: &mut [f64]) -> Vec<f64> {
    let n = basis.degree();
    let mut moments = vec![0.0; basis.len()];
    let (px, rest) = scratch.split_at_mut(n + 1);
    let py = &mut rest[..=n];
    let mut sums = vec![0.0; n + 1];
    let mut at = 0;
    while at < f.points.len() {
        let x = f.points[at].x;
        // At least the node itself (a NaN abscissa equals nothing, its own too).
        let run = 1 + f.points[at + 1..].iter().take_while(|p| p.x == x).count();
        sums.fill(0.0);
        for (p, w) in f.points[at..at + run].iter().zip(&f.weights[at..at + run]) {
            basis.y_factors_into(p.y, py);
            for (s, v) in sums.iter_mut().zip(py.iter()) {
                *s += w * v;
            }
        }
        basis.x_factors_into(x, px);
        graded_products(n, px, &sums, |k, value| moments[k] += value);
        at += run;
    }
    moments
}

/// The order to which the piece's `x(t)` stops moving at its start (`at_start`) or end: the
/// first control point from that end whose offset `d` from the end point has `|d.x| >
/// VERTICAL_SLOPE |d|` (for a Bezier piece, `x - x_0` vanishes like `t^j` when the control
/// points `1 .. j - 1` lie on the vertical line through the end), at most [`MAX_END_ORDER`].
fn end_order(b: &MonotoneBox, at_start: bool) -> usize {
    let p = b.piece();
    let n = p.degree();
    let index = |j: usize| if at_start { j } else { n - j };
    let from = p.control_point(index(0));
    (1..=n)
        .find(|&j| {
            let d = p.control_point(index(j)) - from;
            d.x.abs() > VERTICAL_SLOPE * d.length()
        })
        .unwrap_or(n)
        .min(MAX_END_ORDER)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::moments::{basis_moments, fill_signs};
    use rs_boxes::{BoxOptions, MonotoneBoxes};
    use rs_contain::{Classifier, ContainOptions, FillRule, Location, Method};
    use rs_spline::prelude::*;
    use rs_spline::{Domain, circle};

    /// The domain's monotone pieces and its curves' even-odd signs.
    fn pieces_and_signs(d: &Domain) -> (MonotoneBoxes, Vec<i64>) {
        let boxes = MonotoneBoxes::new(d, BoxOptions::DEFAULT).unwrap();
        (boxes, fill_signs(d, FillRule::EvenOdd).unwrap())
    }

    /// The formula of `domain` at `degree` with no budget, and the domain's exact moments.
    fn formula_and_moments(domain: &Domain, degree: usize) -> (ChordFormula, Vec<f64>, f64) {
        let basis = LegendreBasis::new(degree, domain.bounding_box());
        let (boxes, signs) = pieces_and_signs(domain);
        let exact = basis_moments(domain, &signs, &basis, degree).unwrap();
        let f = chord_formula(boxes.pieces(), &signs, &basis, degree, exact[0], usize::MAX);
        let f = f.unwrap();
        let mut scratch = vec![0.0; basis.scratch_len()];
        let got = formula_moments(&basis, &f, &mut scratch);
        let worst = got
            .iter()
            .zip(&exact)
            .fold(0.0f64, |w, (g, e)| w.max((g - e).abs()))
            / exact[0];
        (f, exact, worst)
    }

    /// A disc with an off-centre hole (vertical tangents at four abscissas, rational pieces):
    /// the formula's moments of degree 36 are the exact ones (Green's theorem) within
    /// `1e-14` of the area, every weight is positive and every node strictly inside by inRS2
    /// (not the locator the rule filters with).
    #[test]
    fn a_holed_disc_is_integrated_to_rounding_by_positive_interior_nodes() {
        let d = Domain::new(vec![
            circle(Point::new(0.0, 0.0), 1.25).unwrap(),
            circle(Point::new(0.3, -0.2), 0.5).unwrap().reversed(),
        ])
        .unwrap();
        let (f, _, worst) = formula_and_moments(&d, 36);
        assert!(worst <= 1e-14, "{worst:e}");
        assert!(f.weights.iter().all(|&w| w > 0.0));
        let classifier = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
        let locations = classifier.locate_all_with(Method::InRS2, &f.points);
        assert!(locations.iter().all(|l| *l == Location::Inside));
        // Fewer nodes than the 8 dim P_n the rule allows it.
        assert!(f.points.len() < 8 * 703, "{} nodes", f.points.len());
    }

    /// On the paper's domains (polygons, cubic and rational pieces, a cusp-like tip) at
    /// degree 40 the formula's moments agree with Green's theorem's within `1e-14` of the area.
    #[test]
    fn the_paper_domains_are_integrated_to_rounding() {
        for name in rs_testkit::PAPER_DOMAINS {
            let d = rs_testkit::inrs_fixture(name).domain;
            let (f, _, worst) = formula_and_moments(&d, 40);
            assert!(
                worst <= 1e-14,
                "{name}: {worst:e} ({} nodes)",
                f.points.len()
            );
        }
    }

    /// A formula over its budget is not made: eight holes stacked over the same abscissas make
    /// nine chords on every vertical line through them (at degree 20, at least `9 x 11 x 4`
    /// nodes per interval, and far more at the orders their arcs need); with room, it is.
    #[test]
    fn a_formula_over_its_budget_is_not_made() {
        let mut loops = vec![circle(Point::new(0.0, 0.0), 30.0).unwrap()];
        for i in 0..8 {
            let y = -14.0 + 4.0 * i as f64;
            loops.push(circle(Point::new(0.0, y), 0.5).unwrap().reversed());
        }
        let d = Domain::new(loops).unwrap();
        let degree = 20;
        let basis = LegendreBasis::new(degree, d.bounding_box());
        let (boxes, signs) = pieces_and_signs(&d);
        let pieces = boxes.pieces();
        let budget = 10 * basis.len();
        assert!(chord_formula(pieces, &signs, &basis, degree, 1.0, budget).is_none());
        let f = chord_formula(pieces, &signs, &basis, degree, 1.0, usize::MAX).unwrap();
        assert!(f.points.len() > budget, "{}", f.points.len());
    }
}
