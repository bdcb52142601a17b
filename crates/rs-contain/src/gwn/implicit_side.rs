//! A test of the side of a monotone polynomial sub-curve a query lies on by the sign of the
//! curve's implicit equation: exact but for rounding, where a graph's polynomial fit
//! ([`InverseFit`](super::inverse_fit::InverseFit)) carries an approximation error.
//!
//! A polynomial curve `(x(t), y(t))` of degree `n <= 3` is a piece of the algebraic curve
//! `F(x, y) = 0`, `F` the resultant of `x(t) - x` and `y(t) - y` in `t`: the determinant of
//! their Bezout matrix (Cayley's `(a(t) b(s) - a(s) b(t)) / (t - s)`), whose entries are
//! linear in `(x, y)`, so that `F` has degree `n`. Graph fits converge slowly where the
//! curve's parametrization has critical points near its interval (every frame's graph is
//! singular there); `F` has no such error.
//!
//! Why its sign decides. The region is the piece of the sub-curve at the cell's heights,
//! widened along the rows from its chord by its own offsets and the root's guard: a
//! parallelogram with two sides on rows, sheared onto the square `[-1, 1]^2` (rows stay rows).
//! There the sign of `dF/du` is certified (its tensor Bernstein coefficients share one), so
//! `F` is strictly monotone along every row of the region and changes by at most
//! `max |dF/du|` per unit of `u`. The computed `F` is within a certified `e` of zero on the
//! sub-curve (its composition with the curve is a polynomial of degree `n^2` in `t`, bounded
//! by its Bernstein coefficients). So a query in the region with `F(q) > e + max |dF/du| g`
//! (`F` signed so that `dF/du > 0`, every rounding added) lies right of where the sub-curve
//! meets its height by more than `g`, the root's guard ([`MonotoneCurve::guard`]), and left
//! of it in the mirrored case; a query right of the region lies right of the whole piece by
//! more than the guard, one left of it left. Where the test decides,
//! [`monotone_crossing`](super::monotone::monotone_crossing) decides the same. On a nearly
//! straight piece `F` is nearly the cube of its line, and `dF/du` vanishes a little way off
//! it: the thin region is what lets the sign certify there.

use rs_spline::Point;

use super::inverse_fit::{CellPiece, binomial, elevated, piece_in_cell, product};
use super::monotone::MonotoneCurve;

/// Control points of a sub-curve the test takes at most (cubics).
const MAX_POINTS: usize = 4;

/// Coefficients of a polynomial in `(u, v)` of total degree at most 3: `u^i v^j` at
/// [`slot`]`(i, j)`.
const TERMS: usize = 10;

/// Where `u^i v^j` (`i + j <= 3`) sits in a [`Bivariate`]: by total degree, then by `j`.
const fn slot(i: usize, j: usize) -> usize {
    let d = i + j;
    d * (d + 1) / 2 + j
}

/// A polynomial in `(u, v)` of total degree at most 3.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
struct Bivariate([f64; TERMS]);

impl Bivariate {
    /// The constant `c`.
    fn constant(c: f64) -> Self {
        let mut b = Self::default();
        b.0[0] = c;
        b
    }

    /// `c + cu u + cv v`.
    fn linear(c: f64, cu: f64, cv: f64) -> Self {
        let mut b = Self::constant(c);
        b.0[slot(1, 0)] = cu;
        b.0[slot(0, 1)] = cv;
        b
    }

    /// The exponents of each slot.
    fn exponents() -> impl Iterator<Item = (usize, usize, usize)> {
        (0..=3).flat_map(|d| (0..=d).map(move |j| (d - j, j, slot(d - j, j))))
    }

    fn add(self, o: Self) -> Self {
        let mut r = self;
        for (a, b) in r.0.iter_mut().zip(o.0) {
            *a += b;
        }
        r
    }

    fn sub(self, o: Self) -> Self {
        let mut r = self;
        for (a, b) in r.0.iter_mut().zip(o.0) {
            *a -= b;
        }
        r
    }

    /// The product, whose total degree the callers keep at most 3 (higher terms dropped).
    fn mul(self, o: Self) -> Self {
        let mut r = Self::default();
        for (i, j, a) in Self::exponents() {
            if self.0[a] == 0.0 {
                continue;
            }
            for (k, l, b) in Self::exponents() {
                if i + j + k + l <= 3 {
                    r.0[slot(i + k, j + l)] += self.0[a] * o.0[b];
                }
            }
        }
        r
    }

    /// `sum |c_ij|`.
    fn size(&self) -> f64 {
        self.0.iter().map(|c| c.abs()).sum()
    }

    /// The value at `(u, v)`, by Horner's scheme in `u` within each power of `v`, then in `v`.
    #[inline(always)]
    fn at(&self, u: f64, v: f64) -> f64 {
        let c = &self.0;
        let v3 = c[slot(0, 3)];
        let v2 = c[slot(0, 2)] + u * c[slot(1, 2)];
        let v1 = c[slot(0, 1)] + u * (c[slot(1, 1)] + u * c[slot(2, 1)]);
        let v0 = c[0] + u * (c[slot(1, 0)] + u * (c[slot(2, 0)] + u * c[slot(3, 0)]));
        v0 + v * (v1 + v * (v2 + v * v3))
    }

    /// Bounds `(min, max)` of the polynomial of total degree at most 2 with these coefficients
    /// over `[-1, 1]^2`, from its tensor Bernstein coefficients of degree `(2, 2)`, widened by
    /// their rounding.
    fn range_on_square(&self) -> (f64, f64) {
        // The Bernstein coefficients of `1`, `u`, `u^2` on `[-1, 1]` at degree 2.
        const B: [[f64; 3]; 3] = [[1.0, 1.0, 1.0], [-1.0, 0.0, 1.0], [1.0, -1.0, 1.0]];
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        // Coefficient `(k, l)`: `sum c_ij B[i][k] B[j][l]`.
        for (k, l) in (0..3).flat_map(|k| (0..3).map(move |l| (k, l))) {
            let mut b = 0.0;
            for (i, j, s) in Self::exponents() {
                if i + j <= 2 {
                    b += self.0[s] * B[i][k] * B[j][l];
                }
            }
            (lo, hi) = (lo.min(b), hi.max(b));
        }
        let rounding = 16.0 * f64::EPSILON * self.size();
        (lo - rounding, hi + rounding)
    }

    /// `dF/du` (a polynomial of total degree at most 2).
    fn d_du(&self) -> Self {
        let mut r = Self::default();
        for (i, j, s) in Self::exponents() {
            if i >= 1 {
                r.0[slot(i - 1, j)] = i as f64 * self.0[s];
            }
        }
        r
    }

    /// `dF/dv`.
    fn d_dv(&self) -> Self {
        let mut r = Self::default();
        for (i, j, s) in Self::exponents() {
            if j >= 1 {
                r.0[slot(i, j - 1)] = j as f64 * self.0[s];
            }
        }
        r
    }
}

/// The implicit equation `F(u, v)` (up to a constant factor) of the polynomial curve with
/// Bernstein control points `(us[i], vs[i])` (2 to 4): the determinant of the Bezout matrix of
/// `u(t) - u` and `v(t) - v` in the power basis, with `m_kl = a_k b_l - a_l b_k` for their
/// power coefficients `a`, `b` (only `a_0` and `b_0` hold `u` and `v`).
fn implicit(us: &[f64], vs: &[f64]) -> Bivariate {
    let power = |c: &[f64]| -> [f64; MAX_POINTS] {
        match *c {
            [p0, p1] => [p0, p1 - p0, 0.0, 0.0],
            [p0, p1, p2] => [p0, 2.0 * (p1 - p0), p2 - 2.0 * p1 + p0, 0.0],
            [p0, p1, p2, p3] => [
                p0,
                3.0 * (p1 - p0),
                3.0 * (p2 - 2.0 * p1 + p0),
                p3 - 3.0 * (p2 - p1) - p0,
            ],
            _ => [0.0; MAX_POINTS],
        }
    };
    let (a, b) = (power(us), power(vs));
    let n = us.len() - 1;
    // `m_0l = (a_0 - u) b_l - a_l (b_0 - v)`, linear; `m_kl` (k, l >= 1) constants.
    let m0 = |l: usize| Bivariate::linear(a[0] * b[l] - a[l] * b[0], -b[l], a[l]);
    let m = |k: usize, l: usize| Bivariate::constant(a[k] * b[l] - a[l] * b[k]);
    match n {
        1 => m0(1),
        2 => m0(1).mul(m(1, 2)).sub(m0(2).mul(m0(2))),
        _ => {
            // [[m01, m02, m03], [m02, m03 + m12, m13], [m03, m13, m23]].
            let (m01, m02, m03) = (m0(1), m0(2), m0(3));
            let (m12, m13, m23) = (m(1, 2), m(1, 3), m(2, 3));
            let m11 = m03.add(m12);
            let first = m01.mul(m11.mul(m23).sub(m13.mul(m13)));
            let second = m02.mul(m02.mul(m23).sub(m13.mul(m03)));
            let third = m03.mul(m02.mul(m13).sub(m11.mul(m03)));
            first.sub(second).add(third)
        }
    }
}

/// A bound on `|F(u(t), v(t))|` over `t` in `[0, 1]` for the curve with Bernstein control
/// points `(us, vs)` (at most [`MAX_POINTS`]): the largest plain Bernstein coefficient of the
/// composition (degree `3 n`), plus a bound on its computation's rounding.
fn on_curve_bound(f: &Bivariate, us: &[f64], vs: &[f64]) -> f64 {
    const LEN: usize = 3 * (MAX_POINTS - 1) + 1;
    let n = us.len() - 1;
    let total = 3 * n;
    // Scaled Bernstein forms of u^i and v^j, i, j <= 3.
    let mut upow = [[0.0; LEN]; 4];
    let mut vpow = [[0.0; LEN]; 4];
    upow[0][0] = 1.0;
    vpow[0][0] = 1.0;
    let mut u1 = [0.0; MAX_POINTS];
    let mut v1 = [0.0; MAX_POINTS];
    for i in 0..=n {
        u1[i] = binomial(n, i) * us[i];
        v1[i] = binomial(n, i) * vs[i];
    }
    for p in 1..4 {
        let (head, tail) = upow.split_at_mut(p);
        product(&head[p - 1][..=n * (p - 1)], &u1[..=n], &mut tail[0]);
        let (head, tail) = vpow.split_at_mut(p);
        product(&head[p - 1][..=n * (p - 1)], &v1[..=n], &mut tail[0]);
    }
    let mut sum = [0.0; LEN];
    let mut term = [0.0; LEN];
    let mut raised = [0.0; LEN];
    for (i, j, s) in Bivariate::exponents() {
        let c = f.0[s];
        if c == 0.0 {
            continue;
        }
        let d = n * (i + j);
        product(&upow[i][..=n * i], &vpow[j][..=n * j], &mut term);
        elevated(&term[..=d], total, &mut raised);
        for (acc, r) in sum.iter_mut().zip(&raised).take(total + 1) {
            *acc += c * r;
        }
    }
    let mut bound = 0.0f64;
    for (k, s) in sum.iter().enumerate().take(total + 1) {
        bound = bound.max((s / binomial(total, k)).abs());
    }
    // Each plain coefficient is a convex combination of products of the factors' plain
    // coefficients, so its terms are at most `sum |c_ij| max|u|^i max|v|^j`, each after some
    // thirty roundings.
    let (su, sv) = (
        us.iter().fold(0.0f64, |m, u| m.max(u.abs())),
        vs.iter().fold(0.0f64, |m, v| m.max(v.abs())),
    );
    let terms: f64 = Bivariate::exponents()
        .map(|(i, j, s)| f.0[s].abs() * su.powi(i as i32) * sv.powi(j as i32))
        .sum();
    bound + 64.0 * f64::EPSILON * terms
}

/// A test of the side of a sub-curve a query lies on at its height, by its implicit
/// equation's sign ([`ImplicitSide::side`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct ImplicitSide {
    /// The region's map onto `[-1, 1]^2`: `u = ((x - cx) - m (y - cy)) kx`, `v = (y - cy) ky`.
    cx: f64,
    cy: f64,
    m: f64,
    kx: f64,
    ky: f64,
    /// How far from zero `F` must be to decide.
    tol: f64,
    /// The implicit equation in `(u, v)`, signed so that `dF/du > 0` over the square.
    f: Bivariate,
}

impl ImplicitSide {
    /// The test of the polynomial sub-curve `root` (2 to 4 control points, ordinates strictly
    /// rising or falling) at its heights within those of `cell` (a split cell's box, holding
    /// every query it serves), deciding only beyond its root's guard
    /// ([`MonotoneCurve::guard`]) for the field's `reach`. `None` if the cell's heights hold
    /// none of the sub-curve's, `dF/dx` may vanish over the region, or a step fails (then the
    /// cell's fits decide).
    pub(super) fn new(root: &MonotoneCurve, cell: (Point, Point), reach: f64) -> Option<Self> {
        Self::with_width(root, cell, reach).map(|(test, _)| test)
    }

    /// [`ImplicitSide::new`], with the width along a row about the sub-curve within which it
    /// may leave a query undecided (at most).
    fn with_width(root: &MonotoneCurve, cell: (Point, Point), reach: f64) -> Option<(Self, f64)> {
        let eps = f64::EPSILON;
        let CellPiece {
            origin: o,
            points: r,
            n,
            heights: (a, b),
            ..
        } = piece_in_cell(root, cell)?;
        let r = &r[..=n];
        let guard = root.guard(reach);
        // The region: the piece's heights, and along each row the piece's offsets from its
        // chord `x = x_0 + m (y - y_0)` grown by the guard; sheared onto the square by
        // `u = ((x - cx) - m (y - cy)) kx`, `v = (y - cy) ky`, which keeps rows rows.
        let m = (r[n].x - r[0].x) / (r[n].y - r[0].y);
        if !m.is_finite() {
            return None;
        }
        let (mut e0, mut e1) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in r {
            let e = (v.x - r[0].x) - m * (v.y - r[0].y);
            (e0, e1) = (e0.min(e), e1.max(e));
            (y0, y1) = (y0.min(v.y), y1.max(v.y));
        }
        let (y0, y1) = (y0.min(a), y1.max(b));
        let (hx, hy) = (0.5 * (e1 - e0), 0.5 * (y1 - y0));
        let grow = |h: f64| h * (1.0 + 1.0 / (1u64 << 20) as f64) + guard + 4.0 * reach;
        let (hx, hy) = (grow(hx), grow(hy));
        let (kx, ky) = (1.0 / hx, 1.0 / hy);
        if !(kx.is_finite() && ky.is_finite() && hx.is_finite() && hy.is_finite()) {
            return None;
        }
        let lcy = 0.5 * (y0 + y1);
        let lcx = r[0].x + m * (lcy - r[0].y) + 0.5 * (e0 + e1);
        let (cx, cy) = (o.x + lcx, o.y + lcy);
        let mut us = [0.0; MAX_POINTS];
        let mut vs = [0.0; MAX_POINTS];
        for (i, v) in r.iter().enumerate() {
            us[i] = ((v.x - lcx) - m * (v.y - lcy)) * kx;
            vs[i] = (v.y - lcy) * ky;
        }
        let (us, vs) = (&us[..=n], &vs[..=n]);
        let f = implicit(us, vs);
        let (lo, hi) = f.d_du().range_on_square();
        let sign = if lo > 0.0 {
            1.0
        } else if hi < 0.0 {
            -1.0
        } else {
            return None;
        };
        // Negation is exact, in the coefficients and in the values.
        let mut f = f;
        for c in &mut f.0 {
            *c *= sign;
        }
        let big_u = lo.abs().max(hi.abs());
        let (vlo, vhi) = f.d_dv().range_on_square();
        let big_v = vlo.abs().max(vhi.abs());
        // Every point's map onto the square, the queries' and the control points', rounds by
        // at most `4 eps` of the coordinates' sizes (relative to the box); the restriction's
        // de Casteljau steps move the control points by `8 (n + 1) eps` of the piece's size.
        let size_x = r.iter().fold(0.0f64, |s, v| s.max(v.x.abs()));
        let size_y = r.iter().fold(0.0f64, |s, v| s.max(v.y.abs()));
        let scale_x = (cell.0.x.abs().max(cell.1.x.abs()) + o.x.abs() + cx.abs() + hx + size_x)
            + m.abs() * (cell.0.y.abs().max(cell.1.y.abs()) + o.y.abs() + cy.abs() + hy + size_y);
        let scale_y = cell.0.y.abs().max(cell.1.y.abs()) + o.y.abs() + cy.abs() + hy + size_y;
        let (du, dv) = (4.0 * eps * scale_x * kx, 4.0 * eps * scale_y * ky);
        // (A move of `(dx, dy)` moves `u` by at most `(|dx| + |m| |dy|) kx`.)
        let restriction =
            8.0 * (n + 1) as f64 * eps * (size_x + size_y) * ((1.0 + m.abs()) * kx + ky);
        let moved = big_u * du + big_v * dv;
        let on_curve = on_curve_bound(&f, us, vs) + moved + big_u.max(big_v) * restriction;
        let evaluation = 24.0 * eps * f.size();
        let tol = 2.0 * (on_curve + evaluation + moved) + big_u * guard * kx * (1.0 + 16.0 * eps);
        let m_u = lo.abs().min(hi.abs());
        let undecided = tol / m_u * hx;
        (tol.is_finite() && undecided.is_finite()).then_some((
            Self {
                cx,
                cy,
                m,
                kx,
                ky,
                tol,
                f,
            },
            undecided,
        ))
    }

    /// The test that puts every query right of the curve (a sub-curve wholly left of every
    /// query that reads it: a chord).
    pub(super) fn always_left() -> Self {
        Self {
            cx: 0.0,
            cy: 0.0,
            m: 0.0,
            kx: 0.0,
            ky: 0.0,
            tol: 0.0,
            f: Bivariate::constant(1.0),
        }
    }

    /// `(left, decided)` at `q`, a query in the cell at a height of the sub-curve (elsewhere
    /// the answer does not count): whether the curve passes left of `q` at `q`'s height, and
    /// whether that, or its passing right of it, is certain. Right of the region (`u > 1`) the
    /// curve passes left of `q`, left of it right; inside, by the sign of `F`. Branch-free.
    #[inline(always)]
    pub(super) fn side(&self, q: Point) -> (bool, bool) {
        let dy = q.y - self.cy;
        let u = ((q.x - self.cx) - self.m * dy) * self.kx;
        let v = dy * self.ky;
        let d = self.f.at(u, v);
        // Within the square by more than the map's rounding, or outside it.
        let edge = 1.0 - 1.0 / (1u64 << 30) as f64;
        let inside = u.abs() <= edge;
        let (right_of, left_of) = (u > edge, u < -edge);
        let left = (inside & (d > self.tol)) | right_of;
        let decided = (inside & (d.abs() > self.tol)) | right_of | left_of;
        (left, decided)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gwn::side_cases::SideCase;
    use rs_spline::RationalBezier;
    use rs_spline::prelude::*;
    use rs_testkit::XorShift64;

    /// The implicit equation vanishes on its curve and not off it (cubics, quadratics, lines).
    #[test]
    fn implicit_equation_vanishes_on_the_curve() {
        let mut rng = XorShift64::new(3);
        for n in 1..=3 {
            for _ in 0..50 {
                let us: Vec<f64> = (0..=n).map(|_| 2.0 * rng.next_f64() - 1.0).collect();
                let vs: Vec<f64> = (0..=n).map(|_| 2.0 * rng.next_f64() - 1.0).collect();
                let f = implicit(&us, &vs);
                let pts: Vec<Point> = us
                    .iter()
                    .zip(&vs)
                    .map(|(&u, &v)| Point::new(u, v))
                    .collect();
                let curve = RationalBezier::new(pts, vec![1.0; n + 1]).unwrap();
                for k in 0..=10 {
                    let p = curve.point_at(k as f64 / 10.0);
                    assert!(f.at(p.x, p.y).abs() < 1e-12 * f.size(), "{n} {:?}", f);
                }
                let bound = on_curve_bound(&f, &us, &vs);
                assert!(bound < 1e-12 * f.size(), "{bound}");
                // Off the curve (a point far from the control points' hull) it does not.
                assert!(f.at(5.0, 5.0).abs() > 1e-9 * f.size());
            }
        }
    }

    /// Wherever the implicit test decides, the root decides the same crossing: small cubics
    /// (at the origin and moved by `1e3`), bands over part or all of their heights, queries
    /// displaced along the cut from the curve by `1e-1` to `1e-13` of its size (either side)
    /// and anywhere in and around its box ([`SideCase`]); nearly all certify, and they decide
    /// every query farther than a thousand times their undecided width, and nearly every
    /// query farther than eight times the root's guard.
    #[test]
    fn implicit_tests_decide_as_the_root_does() {
        let mut rng = XorShift64::new(11);
        let (mut cases, mut made, mut decided, mut far, mut far_decided) = (0, 0, 0, 0, 0);
        let (mut beyond, mut beyond_decided) = (0, 0);
        while cases < 1500 {
            let Some(case) = SideCase::draw(&mut rng, cases) else {
                continue;
            };
            cases += 1;
            let Some((test, width)) = ImplicitSide::with_width(&case.root, case.cell, case.reach)
            else {
                continue;
            };
            made += 1;
            let guard = case.root.guard(case.reach);
            for (q, displaced) in case.queries(&mut rng) {
                let (left, sure) = test.side(q);
                if sure {
                    decided += 1;
                    case.assert_root_agrees(q, left, "implicit");
                }
                if let Some(d) = displaced {
                    if d > 1e3 * width {
                        far += 1;
                        far_decided += usize::from(sure);
                    }
                    if d > 8.0 * guard {
                        beyond += 1;
                        beyond_decided += usize::from(sure);
                    }
                }
            }
        }
        assert!(made * 100 >= cases * 98, "{made} of {cases} certified");
        assert!(decided > 20_000, "{decided}");
        assert_eq!(far_decided, far);
        assert!(
            beyond_decided * 100 >= beyond * 99,
            "{beyond_decided} of {beyond}"
        );
    }
}
