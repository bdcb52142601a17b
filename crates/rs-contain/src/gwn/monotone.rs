//! A sub-curve monotone in `y` crosses the cut (the ray from the query towards `-x`) at most
//! once: where `y(t) = q.y`. Its signed crossing is then decided by the sign of `x(t) - q.x`
//! at that root, with a bound on the root's error, instead of by halving it down to the
//! query's distance (which takes two sub-curves' tests a level, and about `log4(size /
//! distance)` levels).

use std::cmp::Ordering;

use rs_roots::de_casteljau_with_derivative;
use rs_spline::Point;

use super::sum::chord_crossing;

/// Control points of a sub-curve [`monotone_crossing`] takes at most: cubics, as the walks'
/// small polynomial sub-curves (`curve::SMALL`, which this module does not import: the walks
/// import it).
const MAX_POINTS: usize = 4;

/// The bound on a Bernstein polynomial's rounding (coefficients relative to the query, at most
/// four, by de Casteljau on `[0, 1]`), as a multiple of its largest coefficient's size: about
/// `7 eps` at most (the coefficients' subtractions and three levels of blends), doubled.
const ROUNDING: f64 = 16.0 * f64::EPSILON;

/// The same bound's absolute part, for coefficients near or below the least normal number,
/// where each of the dozen operations may round by half the least subnormal step: `2^-1068`.
const ROUNDING_TINY: f64 = f64::MIN_POSITIVE * (1.0 / (1u64 << 46) as f64);

/// What [`monotone_crossing`] tells the walk about a sub-curve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RootCrossing {
    /// Its signed crossing of the cut: `+1` downwards, `-1` upwards, `0` if it passes right
    /// of the query or not at its height; the sum of the crossings of the chords the adaptive
    /// algorithm would settle it by.
    Decided(i64),
    /// Undecided because the query may be within the margin of where it meets the query's
    /// height (or the root's iterates stalled): its sub-curves meet that height at the same
    /// place, so the walk below it need not ask again.
    TooNear,
    /// Not a sub-curve it takes: not 2 to [`MAX_POINTS`] control points whose ordinates
    /// strictly increase or strictly decrease, or a coordinate not finite; its halves may be.
    NotMonotone,
}

/// The signed crossing of the cut at `q` by the polynomial sub-curve with control points `p`
/// ([`RootCrossing`]). It takes the sub-curve when its control points' ordinates strictly
/// increase or strictly decrease (then so does `y(t)`, with `|y'| >= n min |dy_i|` and
/// `|x'| <= n max |dx_i|` for degree `n`), and decides only where `q` is certainly farther than
/// twice `reach` (scaled by the slope, below) from where the sub-curve meets `q`'s height.
///
/// With `t` an iterate of Newton's method on `y(t) = q.y` and `f`, `g` the computed
/// `y(t) - q.y` and `x(t) - q.x`, each within `e_f`, `e_g` ([`ROUNDING`], [`ROUNDING_TINY`]) of
/// the exact values at that `t`, the root is within `(|f| + e_f) / min |y'|` of `t`, so the
/// curve meets the query's height within `err = e_g + max |x'| (|f| + e_f) / min |y'|` of
/// `q.x + g`. With `h = |g| - err` and `L = max |x'| / min |y'|` (the largest slope of `x` as
/// a function of `y`), every point of the curve is at least `h / sqrt(1 + L^2)` from `q`. The
/// crossing is decided when `|g| > 2 err` and `h > 2 reach (1 + L)`, with the same rule at an
/// end at the query's height as the chords' (an end with `y >= q.y` counts as above).
///
/// Why this is the walk's sum: the sub-curve's control points are the rounded results of
/// halvings, within the field's reach of the true curve (see `WindingField`'s
/// Construction). The walk settles every sub-curve of it it reaches with `q` outside its box
/// or its control polygon; beyond the reach from the curve, those chords, joined end to end,
/// can be deformed into the true curve without passing `q`, and so can this sub-curve's
/// control polygon's curve, so both cross the cut as the true curve does. Nearer, the walk's
/// answer rests on its own rounding (and may be a coincidence value), so it is left to the
/// walk, which also tells the sum that `q` may be near.
///
/// (The walks call it only with `q` inside the sub-curve's control box and at least three
/// control points, two-point sub-curves being straight and settled first; the branches for a
/// `q` above or below the sub-curve serve other callers and the tests.)
pub(crate) fn monotone_crossing(p: &[Point], q: Point, reach: f64) -> RootCrossing {
    // (On the walk's path: the points read in place, no copy, and the chord's root as the
    // first iterate.)
    slopes(p).map_or(RootCrossing::NotMonotone, |(rising, slope_ratio)| {
        crossing_from(p, rising, slope_ratio, |s| s, q, reach)
    })
}

/// Whether the ordinates of the control points `p` (2 to [`MAX_POINTS`]) rise, and `L`, a
/// bound on `|x'| / |y'|` from their differences; `None` unless they strictly increase or
/// strictly decrease (finite, with a slope bound above zero).
#[inline(always)]
fn slopes(p: &[Point]) -> Option<(bool, f64)> {
    let n = p.len();
    if !(2..=MAX_POINTS).contains(&n) {
        return None;
    }
    let rising = p[n - 1].y > p[0].y;
    let (mut min_dy, mut max_dx) = (f64::INFINITY, 0.0f64);
    for w in p.windows(2) {
        let (dy, dx) = (w[1].y - w[0].y, (w[1].x - w[0].x).abs());
        let dy = if rising { dy } else { -dy };
        // Written to fail on NaN, which `min` and `max` would skip.
        if !(dy > 0.0 && dx <= f64::MAX) {
            return None;
        }
        (min_dy, max_dx) = (min_dy.min(dy), max_dx.max(dx));
    }
    let degree = (n - 1) as f64;
    // Bounds on the exact slopes from the rounded differences (and their products' rounding
    // near the least normal number).
    let slope_y = degree * min_dy * (1.0 - 2.0 * f64::EPSILON) - ROUNDING_TINY;
    let slope_x = degree * max_dx * (1.0 + 2.0 * f64::EPSILON) + ROUNDING_TINY;
    if slope_y.partial_cmp(&0.0) != Some(Ordering::Greater) {
        return None;
    }
    Some((rising, slope_x / slope_y))
}

/// A polynomial sub-curve [`monotone_crossing`] takes (2 to [`MAX_POINTS`] finite control
/// points whose ordinates strictly increase or strictly decrease), with what it derives from
/// the control points alone: a sub-curve asked about many queries (a split cell's) is made
/// once.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MonotoneCurve {
    p: [Point; MAX_POINTS],
    n: usize,
    rising: bool,
    /// `L`: a bound on `|x'| / |y'|`.
    slope_ratio: f64,
    /// `(m0 - 1, m1 - 1)` for the first iterate ([`MonotoneCurve::first_iterate`]): the
    /// slopes at the ends of `t` as a function of the height's fraction `s` of the way from the
    /// first end's to the last's; `None` for the chord's root (the walk's start: no operation
    /// added to its path).
    bend: Option<(f64, f64)>,
}

impl MonotoneCurve {
    /// The sub-curve with control points `p`, `None` if [`monotone_crossing`] does not take
    /// it. Its first iterate is the chord's root.
    #[inline(always)]
    pub(crate) fn new(p: &[Point]) -> Option<Self> {
        let (rising, slope_ratio) = slopes(p)?;
        let mut points = [Point::default(); MAX_POINTS];
        points[..p.len()].copy_from_slice(p);
        Some(Self {
            p: points,
            n: p.len(),
            rising,
            slope_ratio,
            bend: None,
        })
    }

    /// The same sub-curve, its first iterate from the cubic that interpolates `t` as a
    /// function of the height at its ends with the slopes there (`dt/dy = 1 / y'`): on a small
    /// sub-curve, nearer the root than the chord's by about the square of the chord's error
    /// relative to the sub-curve, so that most queries are decided by the first or second
    /// iterate. Worth its two divisions for a sub-curve many queries ask about.
    pub(crate) fn with_inverse_start(self) -> Self {
        let n = self.n;
        let p = &self.p[..n];
        let degree = (n - 1) as f64;
        let rise = p[n - 1].y - p[0].y;
        // `dt/ds` at the ends, `s` the height's fraction: `rise / y'`, `y'(0) = n (y1 - y0)`.
        let m0 = rise / (degree * (p[1].y - p[0].y));
        let m1 = rise / (degree * (p[n - 1].y - p[n - 2].y));
        let bend = (m0 - 1.0, m1 - 1.0);
        let finite = bend.0.is_finite() && bend.1.is_finite();
        Self {
            bend: finite.then_some(bend),
            ..self
        }
    }

    /// Its control points.
    pub(crate) fn points(&self) -> &[Point] {
        &self.p[..self.n]
    }

    /// How far from it along the cut a query in its box grown by twice `reach` must lie for
    /// [`MonotoneCurve::crossing`] to decide: the margin `2 reach (1 + L)` plus eight times the
    /// error bound its converged root carries (`e_g + 2 L e_f`, [`ROUNDING`] times
    /// coefficients as large as the grown box's sides; `f64::MIN_POSITIVE` bounds
    /// [`ROUNDING_TINY`]).
    pub(crate) fn guard(&self, reach: f64) -> f64 {
        let p = self.points();
        let o = p[0];
        let (size_x, size_y) = p.iter().fold((0.0f64, 0.0f64), |(sx, sy), v| {
            (sx.max((v.x - o.x).abs()), sy.max((v.y - o.y).abs()))
        });
        let e_g = ROUNDING * 2.0 * (size_x + reach) + f64::MIN_POSITIVE;
        let e_f = ROUNDING * 2.0 * (size_y + reach) + f64::MIN_POSITIVE;
        let l = self.slope_ratio;
        8.0 * (e_g + 2.0 * l * e_f) + 2.0 * reach * (1.0 + l)
    }

    /// The first iterate for the root of `y(t) = q.y` at the height's fraction `s` of the way
    /// from the first end's to the last's (the chord's root): `t(s) = s + s (1 - s) ((1 - s)
    /// a - s b)` with `(a, b)` [`MonotoneCurve::bend`], the cubic through `(0, 0)` and
    /// `(1, 1)` with slopes `a + 1` and `b + 1` there, kept within `[0, 1]`; `s` itself
    /// without a bend.
    #[inline(always)]
    fn first_iterate(&self, s: f64) -> f64 {
        let Some((a, b)) = self.bend else {
            return s;
        };
        let r = 1.0 - s;
        let t = s + s * r * (r * a - s * b);
        t.clamp(0.0, 1.0)
    }

    /// Its signed crossing of the cut at `q` ([`monotone_crossing`], from its first
    /// iterate).
    #[inline(always)]
    pub(crate) fn crossing(&self, q: Point, reach: f64) -> RootCrossing {
        let start = |s| self.first_iterate(s);
        crossing_from(
            &self.p[..self.n],
            self.rising,
            self.slope_ratio,
            start,
            q,
            reach,
        )
    }
}

/// [`monotone_crossing`] of the sub-curve with control points `p` (taken by it: [`slopes`]
/// gave `rising` and `slope_ratio`), Newton's iterates starting at `start` of the chord's
/// root.
#[inline(always)]
fn crossing_from(
    p: &[Point],
    rising: bool,
    slope_ratio: f64,
    start: impl Fn(f64) -> f64,
    q: Point,
    reach: f64,
) -> RootCrossing {
    if !(q.x.is_finite() && q.y.is_finite()) {
        return RootCrossing::NotMonotone;
    }
    let n = p.len();
    let mut c = [Point::default(); MAX_POINTS];
    for (c, &p) in c.iter_mut().zip(p) {
        *c = p - q;
    }
    let c = &c[..n];
    let up_a = c[0].y >= 0.0;
    let crossing = chord_crossing(c[0].y, c[n - 1].y, 0.0);
    let (mut size_y, mut size_x) = (0.0f64, 0.0f64);
    for v in c {
        (size_y, size_x) = (size_y.max(v.y.abs()), size_x.max(v.x.abs()));
    }
    let bounds = Bounds {
        e_f: ROUNDING * size_y + ROUNDING_TINY,
        e_g: ROUNDING * size_x + ROUNDING_TINY,
        slope_ratio,
        margin: 2.0 * reach * (1.0 + slope_ratio),
    };
    // The curve meets the query's height within its control box, at most `size_x` from
    // `q` along the cut: no closer to deciding than that.
    if size_x.partial_cmp(&bounds.margin) != Some(Ordering::Greater) {
        return RootCrossing::TooNear;
    }
    let g = if crossing == 0 {
        // Both ends above the query's height (the lower one perhaps at it) or both below:
        // the curve meets that height at most at its lower end.
        let (low, high) = if rising { (0, n - 1) } else { (n - 1, 0) };
        if up_a && c[low].y == 0.0 {
            Some(c[low].x).filter(|&g| bounds.decides(g, 0.0))
        } else {
            // It keeps a vertical distance of at least |y - q.y| at its end nearest the
            // height.
            let gap = if up_a { c[low].y } else { -c[high].y };
            return if gap > 2.0 * reach {
                RootCrossing::Decided(0)
            } else {
                RootCrossing::TooNear
            };
        }
    } else {
        bounds.decisive_abscissa(c, start)
    };
    match g {
        Some(g) => RootCrossing::Decided(if g < 0.0 { crossing } else { 0 }),
        None => RootCrossing::TooNear,
    }
}

/// The rounding and slope bounds of one sub-curve in [`monotone_crossing`].
struct Bounds {
    /// Bound on the rounding of `y(t) - q.y`.
    e_f: f64,
    /// Bound on the rounding of `x(t) - q.x`.
    e_g: f64,
    /// `L`: a bound on `|x'| / |y'|`.
    slope_ratio: f64,
    /// `2 reach (1 + L)`: how far along the cut the curve must pass from `q`.
    margin: f64,
}

impl Bounds {
    /// Does `g`, within `err` of where the curve meets the query's height (relative to `q`),
    /// decide the side: `|g| > 2 err` and `|g| - err > margin`?
    #[inline(always)]
    fn decides(&self, g: f64, err: f64) -> bool {
        g.abs() > 2.0 * err && g.abs() - err > self.margin
    }

    /// `x(t) - q.x` at the first iterate `t` of Newton's method on `y(t) = q.y` (safeguarded
    /// by bisection, from `start` of the chord's root, a point of `[0, 1]`) that decides the
    /// side ([`Bounds::decides`], with
    /// `err = e_g + L (|f| + e_f)`); `None` once the root is resolved to rounding
    /// (`|f| <= e_f`) or the iterates stop moving without deciding (the query too near).
    ///
    /// `c`: the Bernstein coefficients of the curve less `q`, whose ordinates at the ends have
    /// opposite signs (or one is zero). Each iteration shrinks the bracket or takes a Newton
    /// step inside it; at most [`MAX_NEWTON`] of them.
    #[inline(always)]
    fn decisive_abscissa(&self, c: &[Point], start: impl Fn(f64) -> f64) -> Option<f64> {
        let (first, last) = (c[0].y, c[c.len() - 1].y);
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        let mut t = if first == 0.0 {
            0.0
        } else if last == 0.0 {
            1.0
        } else {
            start(first / (first - last))
        };
        for _ in 0..MAX_NEWTON {
            let (at, tangent) = de_casteljau_with_derivative(c, t);
            let (f, g) = (at.y, at.x);
            if self.decides(g, self.e_g + self.slope_ratio * (f.abs() + self.e_f)) {
                return Some(g);
            }
            if f.abs() <= self.e_f {
                return None;
            }
            if (f > 0.0) == (first > 0.0) {
                lo = t;
            } else {
                hi = t;
            }
            let newton = t - f / tangent.y;
            let next = if newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if next == t {
                break;
            }
            t = next;
        }
        None
    }
}

/// Most Newton iterations of [`Bounds::decisive_abscissa`]: bisection alone halves the bracket
/// to one ulp of `[0, 1]` in about 60.
const MAX_NEWTON: usize = 64;

#[cfg(test)]
mod tests {
    use super::RootCrossing::{Decided, NotMonotone, TooNear};
    use super::*;
    use crate::gwn::QueryStats;
    use crate::gwn::curve::{SubCurve, refine_below};
    use crate::gwn::sum::WindingSum;
    use rs_spline::RationalBezier;
    use rs_spline::prelude::*;
    use rs_testkit::XorShift64;

    /// A polynomial curve of `n` control points whose ordinates strictly rise (or fall) by
    /// random steps, abscissas anywhere in `[-1, 1]`, all moved by `offset`.
    fn monotone_curve(rng: &mut XorShift64, n: usize, offset: Point) -> Vec<Point> {
        let sign = if rng.next_f64() < 0.5 { 1.0 } else { -1.0 };
        let mut y = rng.next_f64() - 0.5;
        (0..n)
            .map(|_| {
                y += 0.01 + rng.next_f64();
                offset + Point::new(2.0 * rng.next_f64() - 1.0, sign * y)
            })
            .collect()
    }

    /// The crossing the paper's walk gives: its chords' crossings, `None` where it added a
    /// coincidence value (the query within rounding of the curve).
    fn walks_crossing(p: &[Point], q: Point, reach: f64) -> Option<i64> {
        let curve = RationalBezier::new(p.to_vec(), vec![1.0; p.len()]).unwrap();
        let mut sum = WindingSum::tracking(q, reach);
        refine_below(
            SubCurve::of(&curve),
            0,
            false,
            q,
            &mut sum,
            &mut QueryStats::default(),
        );
        sum.crossings_alone()
    }

    /// Wherever it decides, the root's crossing is the walk's: lines, quadratics and cubics
    /// monotone in `y`, at the origin and moved by `1e3` and `1e6`, queries at `1e-1` to
    /// `1e-15` from the curve along the cut (either side) and anywhere in its box, with a
    /// reach like a field's (`4e-12` of the largest coordinate: the walk's own rounding stays
    /// within it); and it decides nearly all of those farther than a thousand reaches.
    #[test]
    fn crossings_from_the_root_are_the_walks() {
        let mut rng = XorShift64::new(3);
        let (mut far, mut far_decided, mut decided) = (0, 0, 0);
        for case in 0..3000 {
            let offset = [0.0, 1e3, 1e6][case % 3];
            let p = monotone_curve(&mut rng, 2 + case % 3, Point::new(offset, -offset));
            let reach = 4e-12 * (offset + 3.0);
            let curve = RationalBezier::new(p.clone(), vec![1.0; p.len()]).unwrap();
            for k in 1..=15 {
                let on = curve.point_at(rng.next_f64());
                let d = 10f64.powi(-k) * if rng.next_f64() < 0.5 { 1.0 } else { -1.0 };
                let (lo, hi) = crate::gwn::curve::control_box(&p);
                let anywhere = Point::new(
                    lo.x + rng.next_f64() * (hi.x - lo.x),
                    lo.y + rng.next_f64() * (hi.y - lo.y),
                );
                for q in [Point::new(on.x + d, on.y), anywhere] {
                    let ours = monotone_crossing(&p, q, reach);
                    if let Decided(c) = ours {
                        decided += 1;
                        assert_eq!(walks_crossing(&p, q, reach), Some(c), "{p:?} at {q:?}");
                    }
                    // From the other first iterate, the same answer where both decide.
                    let inverse = MonotoneCurve::new(&p).unwrap().with_inverse_start();
                    if let Decided(c) = inverse.crossing(q, reach) {
                        assert_eq!(walks_crossing(&p, q, reach), Some(c), "{p:?} at {q:?}");
                    }
                    if d.abs() > 1e3 * reach && q.y == on.y {
                        far += 1;
                        far_decided += usize::from(matches!(ours, Decided(_)));
                    }
                }
            }
        }
        assert!(far_decided * 100 >= far * 99, "{far_decided} of {far}");
        assert!(decided > 40_000, "{decided}");
    }

    /// On small sub-curves (a cubic halved eight times), the inverse start lies nearer the
    /// root than the chord's: by at least a hundredfold on nine in ten of them, and never
    /// farther.
    #[test]
    fn the_inverse_start_is_nearer_the_root() {
        let mut rng = XorShift64::new(11);
        let (mut cases, mut much_nearer) = (0, 0);
        while cases < 2000 {
            let p = monotone_curve(&mut rng, 4, Point::new(0.0, 0.0));
            let curve = RationalBezier::new(p.clone(), vec![1.0; 4]).unwrap();
            let a = rng.next_f64() * (1.0 - 1.0 / 256.0);
            let part = curve.subsegment((a, a + 1.0 / 256.0)).unwrap();
            let small = part.control_points().to_vec();
            let Some(m) = MonotoneCurve::new(&small) else {
                continue;
            };
            cases += 1;
            let m = m.with_inverse_start();
            let t = rng.next_f64();
            let y = de_casteljau_with_derivative(&small, t).0.y;
            let s = (small[0].y - y) / (small[0].y - small[3].y);
            let (chord, inverse) = ((s - t).abs(), (m.first_iterate(s) - t).abs());
            assert!(
                inverse <= chord + 1e-12,
                "{small:?} at {t}: {inverse} > {chord}"
            );
            much_nearer += usize::from(inverse * 100.0 <= chord);
        }
        assert!(much_nearer * 10 >= cases * 9, "{much_nearer} of {cases}");
    }

    /// The walk's sub-curves start from the chord's root itself: without a bend the first
    /// iterate is `s` bit for bit (at 0, 1, subnormal and random `s`), so the walk's
    /// decisions are those of the chord-started search.
    #[test]
    fn no_bend_starts_at_the_chords_root() {
        let p = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.5, 3.0),
        ];
        let m = MonotoneCurve::new(&p).unwrap();
        let mut rng = XorShift64::new(17);
        let fixed = [0.0, 1.0, f64::MIN_POSITIVE, 5e-324, 1.0f64.next_down(), 0.5];
        for s in fixed
            .into_iter()
            .chain((0..100_000).map(|_| rng.next_f64()))
        {
            assert_eq!(m.first_iterate(s).to_bits(), s.to_bits(), "{s:e}");
        }
        // With a bend, the start stays within [0, 1] even for extreme slopes at the ends.
        let steep = [
            Point::new(0.0, 0.0),
            Point::new(0.0, 1e-300),
            Point::new(0.0, 1.0),
        ];
        let m = MonotoneCurve::new(&steep).unwrap().with_inverse_start();
        for s in fixed
            .into_iter()
            .chain((0..100_000).map(|_| rng.next_f64()))
        {
            let t = m.first_iterate(s);
            assert!((0.0..=1.0).contains(&t), "{s:e}: {t:e}");
        }
    }

    /// It declines at the curve's ends and points, within its rounding of the curve (one ulp
    /// from a point of it), within twice the reach along the cut, and on curves not strictly
    /// monotone in `y` (a flat step, a turn, a horizontal line) or not finite; and with
    /// coordinates near the least subnormal number its bound on the rounding still holds.
    #[test]
    fn declines_on_near_and_non_monotone_curves() {
        let p = [
            Point::new(0.0, 0.0),
            Point::new(0.3, 1.0),
            Point::new(0.7, 2.0),
            Point::new(1.0, 3.0),
        ];
        assert_eq!(monotone_crossing(&p, p[0], 0.0), TooNear);
        assert_eq!(monotone_crossing(&p, p[3], 0.0), TooNear);
        // y(1/2) = 1.5 and x(1/2) = 0.5 exactly.
        let mid = Point::new(0.5, 1.5);
        assert_eq!(monotone_crossing(&p, mid, 0.0), TooNear);
        let ulp = 0.5 * f64::EPSILON;
        for side in [1.0, -1.0] {
            let q = Point::new(0.5 + side * ulp, 1.5);
            assert_eq!(monotone_crossing(&p, q, 0.0), TooNear, "{q:?}");
        }
        assert_eq!(
            monotone_crossing(&p, Point::new(0.5 + 1e-3, 1.5), 0.0),
            Decided(-1)
        );
        assert_eq!(
            monotone_crossing(&p, Point::new(0.5 - 1e-3, 1.5), 0.0),
            Decided(0)
        );
        // |x'| / |y'| is at most 0.4 / 1: within 2 reach (1 + 0.4) of the curve it declines.
        let q = Point::new(0.5 + 1e-3, 1.5);
        assert_eq!(monotone_crossing(&p, q, 4e-4), TooNear);
        assert_eq!(monotone_crossing(&p, q, 3e-5), Decided(-1));
        // Below the curve's lower end: no crossing, unless within twice the reach of it.
        assert_eq!(
            monotone_crossing(&p, Point::new(2.0, -1.0), 0.0),
            Decided(0)
        );
        assert_eq!(monotone_crossing(&p, Point::new(2.0, -1e-6), 1e-6), TooNear);
        // At the lower end's height, left and right of it: the end counts as above the cut.
        assert_eq!(monotone_crossing(&p, Point::new(1.0, 0.0), 0.0), Decided(0));
        assert_eq!(
            monotone_crossing(&p, Point::new(-1.0, 0.0), 0.0),
            Decided(0)
        );
        // At the upper end's height, right of it: the curve crosses upwards.
        assert_eq!(
            monotone_crossing(&p, Point::new(2.0, 3.0), 0.0),
            Decided(-1)
        );
        let nan = Point::new(f64::NAN, 1.0);
        for bad in [
            [p[0], p[1], p[1], p[3]],
            [p[0], p[2], p[1], p[3]],
            [
                p[0],
                Point::new(1.0, 0.0),
                Point::new(2.0, 0.0),
                Point::new(3.0, 0.0),
            ],
            [p[0], nan, p[2], p[3]],
        ] {
            assert_eq!(
                monotone_crossing(&bad, Point::new(2.0, 1.5), 0.0),
                NotMonotone
            );
        }
        assert_eq!(monotone_crossing(&p, nan, 0.0), NotMonotone);
        // A cubic a few hundred subnormal steps across, whose crossing is right of the query
        // (exactly: 0), where a bound relative to the coefficients alone decided -1.
        let tiny = f64::from_bits(1);
        let small = [(7.0, 4.0), (0.0, 8.0), (-5.0, 10.0), (-5.0, 13.0)]
            .map(|(x, y)| Point::new(x * tiny, y * tiny));
        let q = Point::new(5.0 * tiny, 5.0 * tiny);
        assert_ne!(monotone_crossing(&small, q, 0.0), Decided(-1));
    }
}
