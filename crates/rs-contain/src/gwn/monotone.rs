//! A sub-curve monotone in `y` crosses the cut (the ray from the query towards `-x`) at most
//! once: where `y(t) = q.y`. Its signed crossing is then decided by the sign of `x(t) - q.x`
//! at that root, with a bound on the root's error, instead of by halving it down to the
//! query's distance (which takes two sub-curves' tests a level, and about `log4(size /
//! distance)` levels).

use rs_spline::Point;

/// Control points of a sub-curve [`monotone_crossing`] takes at most (cubics, as the walks'
/// small polynomial sub-curves).
const MAX_POINTS: usize = 4;

/// The bound on a Bernstein polynomial's rounding (relative coefficients of at most four
/// terms, by de Casteljau on `[0, 1]`), as a multiple of its largest coefficient's size: about
/// `7 eps` at most (the coefficients' subtractions and three levels of blends), doubled.
const ROUNDING: f64 = 16.0 * f64::EPSILON;

/// The signed crossing of the cut at `q` by the polynomial sub-curve with control points `p`
/// (2 to [`MAX_POINTS`] of them): `+1` downwards, `-1` upwards, `0` if it passes right of `q`
/// or not at its height; the sum of the crossings of the chords the adaptive algorithm would
/// replace it by. Decided when the control points' ordinates strictly increase or strictly
/// decrease (then so does `y(t)`, with `|y'| >= n min |dy_i|` and `|x'| <= n max |dx_i|` for
/// degree `n`) and `q` is certainly farther than twice `reach` from the sub-curve; `None`
/// otherwise.
///
/// With `t` an iterate of Newton's method on `y(t) = q.y` and `f`, `g` the computed `y(t) - q.y`
/// and `x(t) - q.x`, each within `e_f`, `e_g` ([`ROUNDING`]) of the exact values at that `t`,
/// the root is within `(|f| + e_f) / min |y'|` of `t`, so the curve meets the query's height
/// within `err = e_g + max |x'| (|f| + e_f) / min |y'|` of `q.x + g`. Every point of the curve
/// is then at least `h / sqrt(1 + L^2)` from `q`, with `h = |g| - err` and
/// `L = max |x'| / min |y'|` (the largest slope of `x` as a function of `y`). The crossing is
/// decided when `|g| > 2 err` and `h > 2 reach (1 + L)`: the chords' signed crossings add up to
/// the curve's whenever `q` is on none of them (the two paths share their ends), with the same
/// rule at an end at the query's height (an end with `y >= q.y` counts as above).
///
/// Why beyond the reach: the sub-curve's control points are the rounded results of halvings,
/// within the field's reach of the true curve (see `WindingField`'s Construction); farther
/// than that, the walk's chords and this root both give the true curve's crossing, while
/// nearer, the walk's answer rests on its own rounding (and may be a coincidence value), so
/// the walk is left to give it, and to tell the sum that `q` may be near.
pub(crate) fn monotone_crossing(p: &[Point], q: Point, reach: f64) -> Option<i64> {
    let n = p.len();
    if !((2..=MAX_POINTS).contains(&n) && q.x.is_finite() && q.y.is_finite()) {
        return None;
    }
    let (a, b) = (p[0], p[n - 1]);
    let rising = b.y > a.y;
    let (mut min_dy, mut max_dx) = (f64::INFINITY, 0.0f64);
    let (mut cy, mut cx) = ([0.0; MAX_POINTS], [0.0; MAX_POINTS]);
    for i in 0..n {
        (cy[i], cx[i]) = (p[i].y - q.y, p[i].x - q.x);
        if i > 0 {
            let dy = if rising {
                p[i].y - p[i - 1].y
            } else {
                p[i - 1].y - p[i].y
            };
            min_dy = min_dy.min(dy);
            max_dx = max_dx.max((p[i].x - p[i - 1].x).abs());
        }
    }
    // Not strictly monotone (or not finite).
    if !(min_dy > 0.0 && max_dx.is_finite()) {
        return None;
    }
    let degree = (n - 1) as f64;
    // Bounds on the exact slopes from the rounded differences.
    let slope_y = degree * min_dy * (1.0 - 2.0 * f64::EPSILON);
    let slope_x = degree * max_dx * (1.0 + 2.0 * f64::EPSILON);
    let (cy, cx) = (&cy[..n], &cx[..n]);
    let (up_a, up_b) = (cy[0] >= 0.0, cy[n - 1] >= 0.0);
    let crossing = i64::from(up_a) - i64::from(up_b);
    let size = |c: &[f64]| c.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let bounds = Bounds {
        e_f: ROUNDING * size(cy),
        e_g: ROUNDING * size(cx),
        ratio: slope_x / slope_y,
        margin: 2.0 * reach * (1.0 + slope_x / slope_y),
    };
    let g = if crossing == 0 {
        // Both ends above the query's height (the lower one perhaps at it) or both below: the
        // curve meets that height at most at its lower end.
        let (low, high) = if rising { (0, n - 1) } else { (n - 1, 0) };
        if up_a && cy[low] == 0.0 {
            Some(cx[low]).filter(|g| bounds.decides(*g, 0.0))
        } else {
            // It keeps a vertical distance of at least |cy| at its end nearest the height.
            let gap = if up_a { cy[low] } else { -cy[high] };
            return (gap > 2.0 * reach).then_some(0);
        }
    } else {
        match n {
            2 => bounds.solve::<2>(cy, cx),
            3 => bounds.solve::<3>(cy, cx),
            _ => bounds.solve::<4>(cy, cx),
        }
    }?;
    Some(if g < 0.0 { crossing } else { 0 })
}

/// The rounding and slope bounds of one sub-curve in [`monotone_crossing`].
struct Bounds {
    /// Bound on the rounding of `y(t) - q.y`.
    e_f: f64,
    /// Bound on the rounding of `x(t) - q.x`.
    e_g: f64,
    /// `L`: a bound on `|x'| / |y'|`.
    ratio: f64,
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

    /// `g` at the first iterate of Newton's method on `y(t) = q.y` (safeguarded by bisection,
    /// from the chord's root) that decides the side ([`Bounds::decides`], with
    /// `err = e_g + L (|f| + e_f)`); `None` once the root is resolved to rounding (`|f| <= e_f`)
    /// or the iterates stop moving without deciding (the query too near the curve).
    ///
    /// `cy`, `cx`: the `N` Bernstein coefficients of `y - q.y` and `x - q.x`, `cy`'s ends of
    /// opposite signs (or one zero). Each iteration shrinks the bracket or takes a Newton step
    /// inside it; at most [`MAX_NEWTON`] of them.
    #[inline(always)]
    fn solve<const N: usize>(&self, cy: &[f64], cx: &[f64]) -> Option<f64> {
        let (cy, cx): (&[f64; N], &[f64; N]) = (cy.try_into().ok()?, cx.try_into().ok()?);
        let (first, last) = (cy[0], cy[N - 1]);
        let (mut lo, mut hi) = (0.0f64, 1.0f64);
        let mut t = if first == 0.0 {
            0.0
        } else if last == 0.0 {
            1.0
        } else {
            first / (first - last)
        };
        for _ in 0..MAX_NEWTON {
            let (f, df, g) = blend_with_derivative(cy, cx, t);
            if self.decides(g, self.e_g + self.ratio * (f.abs() + self.e_f)) {
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
            let newton = t - f / df;
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

/// Most Newton iterations of [`Bounds::solve`]: bisection alone halves the bracket to one ulp
/// of `[0, 1]` in about 60.
const MAX_NEWTON: usize = 64;

/// `y(t)`, `y'(t)` and `x(t)` of the Bernstein coefficients `cy`, `cx` by de Casteljau.
#[inline(always)]
fn blend_with_derivative<const N: usize>(cy: &[f64; N], cx: &[f64; N], t: f64) -> (f64, f64, f64) {
    let (mut y, mut x) = (*cy, *cx);
    let s = 1.0 - t;
    for level in 1..N - 1 {
        for i in 0..N - level {
            y[i] = s * y[i] + t * y[i + 1];
            x[i] = s * x[i] + t * x[i + 1];
        }
    }
    let df = (y[1] - y[0]) * (N - 1) as f64;
    (s * y[0] + t * y[1], df, s * x[0] + t * x[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gwn::QueryStats;
    use crate::gwn::curve::{SubCurve, refine_below};
    use crate::gwn::sum::WindingSum;
    use rs_spline::RationalBezier;
    use rs_spline::prelude::*;
    use rs_testkit::XorShift64;

    /// A polynomial curve of `n` control points whose ordinates strictly rise (or fall) by
    /// random steps, abscissas anywhere in `[-1, 1]`.
    fn monotone_curve(rng: &mut XorShift64, n: usize) -> Vec<Point> {
        let sign = if rng.next_f64() < 0.5 { 1.0 } else { -1.0 };
        let mut y = rng.next_f64() - 0.5;
        (0..n)
            .map(|_| {
                y += 0.01 + rng.next_f64();
                Point::new(2.0 * rng.next_f64() - 1.0, sign * y)
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
    /// monotone in `y`, queries at `1e-1` to `1e-15` from the curve along the cut (either
    /// side) and anywhere in its box, with no reach and with `1e-12`; and it decides nearly
    /// all of those farther than `1e-9`.
    #[test]
    fn crossings_from_the_root_are_the_walks() {
        let mut rng = XorShift64::new(3);
        let (mut far, mut far_decided, mut decided) = (0, 0, 0);
        for case in 0..3000 {
            let p = monotone_curve(&mut rng, 2 + case % 3);
            let curve = RationalBezier::new(p.clone(), vec![1.0; p.len()]).unwrap();
            for k in 1..=15 {
                let on = curve.point_at(rng.next_f64());
                let d = 10f64.powi(-k) * if rng.next_f64() < 0.5 { 1.0 } else { -1.0 };
                let (lo, hi) = super::super::curve::control_box(&p);
                let anywhere = Point::new(
                    lo.x + rng.next_f64() * (hi.x - lo.x),
                    lo.y + rng.next_f64() * (hi.y - lo.y),
                );
                for q in [Point::new(on.x + d, on.y), anywhere] {
                    for reach in [0.0, 1e-12] {
                        let ours = monotone_crossing(&p, q, reach);
                        if let Some(c) = ours {
                            decided += 1;
                            assert_eq!(walks_crossing(&p, q, reach), Some(c), "{p:?} at {q:?}");
                        }
                        if k <= 9 && q.y == on.y {
                            far += 1;
                            far_decided += usize::from(ours.is_some());
                        }
                    }
                }
            }
        }
        assert!(far_decided * 100 >= far * 99, "{far_decided} of {far}");
        assert!(decided > 100_000, "{decided}");
    }

    /// It declines at the curve's ends and points, within twice the reach along the cut, and
    /// on curves not strictly monotone in `y` (a flat step, a turn, a horizontal line).
    #[test]
    fn declines_on_near_and_non_monotone_curves() {
        let p = [
            Point::new(0.0, 0.0),
            Point::new(0.3, 1.0),
            Point::new(0.7, 2.0),
            Point::new(1.0, 3.0),
        ];
        assert_eq!(monotone_crossing(&p, p[0], 0.0), None);
        assert_eq!(monotone_crossing(&p, p[3], 0.0), None);
        // x(1/2) = 0.5 at y(1/2) = 1.5.
        let mid = Point::new(0.5, 1.5);
        assert_eq!(monotone_crossing(&p, mid, 0.0), None);
        assert_eq!(
            monotone_crossing(&p, Point::new(0.5 + 1e-3, 1.5), 0.0),
            Some(-1)
        );
        assert_eq!(
            monotone_crossing(&p, Point::new(0.5 - 1e-3, 1.5), 0.0),
            Some(0)
        );
        // |x'| / |y'| is at most 0.4 / 1: within 2 reach (1 + 0.4) of the curve it declines.
        assert_eq!(
            monotone_crossing(&p, Point::new(0.5 + 1e-3, 1.5), 4e-4),
            None
        );
        assert_eq!(
            monotone_crossing(&p, Point::new(0.5 + 1e-3, 1.5), 3e-5),
            Some(-1)
        );
        // Below the curve's lower end: no crossing, unless within twice the reach of it.
        assert_eq!(monotone_crossing(&p, Point::new(2.0, -1.0), 0.0), Some(0));
        assert_eq!(monotone_crossing(&p, Point::new(2.0, -1e-6), 1e-6), None);
        // At the lower end's height, left and right of it: the end counts as above the cut.
        assert_eq!(monotone_crossing(&p, Point::new(1.0, 0.0), 0.0), Some(0));
        assert_eq!(monotone_crossing(&p, Point::new(-1.0, 0.0), 0.0), Some(0));
        // At the upper end's height, right of it: the curve crosses upwards.
        assert_eq!(monotone_crossing(&p, Point::new(2.0, 3.0), 0.0), Some(-1));
        for bad in [
            [p[0], p[1], p[1], p[3]],
            [p[0], p[2], p[1], p[3]],
            [
                p[0],
                Point::new(1.0, 0.0),
                Point::new(2.0, 0.0),
                Point::new(3.0, 0.0),
            ],
        ] {
            assert_eq!(monotone_crossing(&bad, Point::new(2.0, 1.5), 0.0), None);
        }
        assert_eq!(monotone_crossing(&p, Point::new(f64::NAN, 1.0), 0.0), None);
    }
}
