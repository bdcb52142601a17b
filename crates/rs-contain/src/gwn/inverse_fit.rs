//! A test of the side of a monotone sub-curve a query lies on, by one polynomial's value
//! instead of a root: the sub-curve as a graph over a direction, with a certified bound.
//!
//! A polynomial sub-curve whose ordinates strictly rise or fall, restricted to a split cell's
//! heights, is the graph `w = G(s)` of a smooth function over any direction `(cs, sn)` along
//! which its control points strictly advance (`s = x cs + y sn` along, `w = y cs - x sn`
//! across): its heights (the direction `(0, +-1)`, where `G` is minus the abscissa as a
//! function of the height), its abscissas (where it is nearly level, and the height is the
//! smooth one), or its chord (where it turns). The polynomial `P` of degree `k` interpolating
//! `G` at the Chebyshev points of the sub-curve's span `[s_0, s_1]` is close to it; how close
//! is *proved*, not estimated: `w(t) - P(u(s(t)))` (with `u` the span's own variable) is a
//! polynomial of degree `n k` in `t` (`n` the sub-curve's degree) whose Bernstein coefficients
//! bound it (a Bernstein polynomial lies within its coefficients' hull).
//!
//! Why that decides the crossing. The sub-curve meets a query's height (one of the cell's and
//! of its own) at one point `P` of the restricted piece, inside the piece's strip `s_0 <= s <=
//! s_1`. A query `q` in the strip lies on one side of the graph, and the horizontal segment
//! from `q` to `P` stays in the strip (it is convex) and meets the curve only at `P` (the curve
//! is monotone in the height): so `q` lies on the side of the graph that `P`'s right (`+x`)
//! side is, which for a curve rising in the height is its right side (`-w`), for a falling
//! one its left (`+w`). A query past the strip's end `s_1` (or before `s_0`), at a height
//! where `P` exists, lies right of `P` along its row if the direction points right (`cs > 0`),
//! left of it if it points left (the row's `s` grows with `x` as `cs`). Each decision is taken
//! only beyond the certified bound plus every rounding plus the distance along the cut within
//! which [`monotone_crossing`](super::monotone::monotone_crossing) would decline (scaled from
//! the cut to `w` by a bound on how fast `w - G(s)` changes along a row): where a test
//! decides, the root would decide the same.

use rs_roots::{bernstein_sign_change_root, de_casteljau_split, de_casteljau_with_derivative};
use rs_spline::Point;

use super::monotone::MonotoneCurve;

/// Highest degree of a fit.
pub(super) const MAX_DEGREE: usize = 8;

/// Control points of a sub-curve a fit takes at most (cubics).
const MAX_POINTS: usize = 4;

/// Coefficients of the bound's polynomial at most (degree `3 MAX_DEGREE`).
const MAX_PRODUCT: usize = 3 * MAX_DEGREE + 1;

/// A fit whose tolerance is at most this multiple of the root's guard (scaled to the frame)
/// is *tight*: no other frame would decide many more queries.
const TIGHT: f64 = 4.0;

/// The direction a fit's sub-curve is a graph over.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Frame {
    /// Along the height, `(0, 1)` for a rising sub-curve, `(0, -1)` for a falling one.
    Heights,
    /// Along the abscissa, the way the sub-curve runs.
    Abscissas,
    /// Along the chord of the sub-curve's piece at the cell's heights.
    Chord,
}

/// A test of the side of a sub-curve a query lies on at its height ([`InverseFit::side`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct InverseFit {
    /// The frame's direction: `s = x cs + y sn`, `w = y cs - x sn`.
    cs: f64,
    sn: f64,
    /// The along-coordinates the polynomial serves (the piece's span, shrunk by its rounding).
    s_lo: f64,
    s_hi: f64,
    /// How far past that span a query is certainly past the piece's end (and beyond the
    /// root's guard along its row).
    beyond: f64,
    /// The polynomial's variable: `u = (s - mid) * inv_half`.
    mid: f64,
    inv_half: f64,
    /// How far across from the polynomial's value a query must lie to be decided.
    tol: f64,
    /// `-1` for a rising sub-curve, `1` for a falling one: the curve passes left of `q` where
    /// `sign (w - P(u)) > tol`.
    sign: f64,
    c: [f64; MAX_DEGREE + 1],
}

/// `C(n, i)` for `n` up to `3 MAX_DEGREE` (exact in `f64`), from a table made at compile time.
pub(super) fn binomial(n: usize, i: usize) -> f64 {
    BINOMIALS[n][i] as f64
}

/// Pascal's triangle to row `3 MAX_DEGREE`.
const BINOMIALS: [[u64; MAX_PRODUCT]; MAX_PRODUCT] = {
    let mut t = [[0u64; MAX_PRODUCT]; MAX_PRODUCT];
    let mut n = 0;
    while n < MAX_PRODUCT {
        t[n][0] = 1;
        let mut i = 1;
        while i <= n {
            t[n][i] = t[n - 1][i - 1] + t[n - 1][i];
            i += 1;
        }
        n += 1;
    }
    t
};

/// The product of two polynomials in scaled Bernstein form (`sum a_i s^i (1 - s)^(m - i)`),
/// a convolution.
pub(super) fn product(a: &[f64], b: &[f64], out: &mut [f64]) -> usize {
    let len = a.len() + b.len() - 1;
    out[..len].fill(0.0);
    for (i, &x) in a.iter().enumerate() {
        for (j, &y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    len
}

/// The scaled Bernstein form `a` (degree `a.len() - 1`) raised to degree `to` (at most
/// `3 MAX_DEGREE`), into `out`: times `(s + (1 - s))^(to - deg)`, a convolution with that
/// power's binomials.
pub(super) fn elevated(a: &[f64], to: usize, out: &mut [f64]) {
    let by = to + 1 - a.len();
    let mut ones = [0.0; MAX_PRODUCT];
    for (i, o) in ones.iter_mut().enumerate().take(by + 1) {
        *o = binomial(by, i);
    }
    product(a, &ones[..=by], out);
}

impl InverseFit {
    /// The test of degree [`MAX_DEGREE`] in `frame` of the polynomial sub-curve `root` (2 to
    /// 4 finite control points, ordinates strictly rising or falling) at its heights within
    /// those of `cell` (a split cell's box, which holds every query it serves), deciding only
    /// beyond its root's guard ([`MonotoneCurve::guard`]) for the field's `reach`; with whether
    /// it is tight ([`TIGHT`]). `None` if the cell's heights hold none of its own, its piece
    /// there does not advance along the frame, or a step fails (then the root decides, as
    /// before).
    pub(super) fn new(
        root: &MonotoneCurve,
        cell: (Point, Point),
        frame: Frame,
        reach: f64,
    ) -> Option<(Self, bool)> {
        let eps = f64::EPSILON;
        let CellPiece {
            origin: o,
            points: r,
            n,
            rising,
            ..
        } = piece_in_cell(root, cell)?;
        let r = &r[..=n];
        let (cs, sn) = match frame {
            Frame::Heights => (0.0, if rising { 1.0 } else { -1.0 }),
            Frame::Abscissas if r[n].x > r[0].x => (1.0, 0.0),
            Frame::Abscissas if r[n].x < r[0].x => (-1.0, 0.0),
            Frame::Abscissas => return None,
            Frame::Chord => {
                let d = r[n] - r[0];
                let length = d.x.hypot(d.y);
                if !(length > 0.0 && length.is_finite()) {
                    return None;
                }
                (d.x / length, d.y / length)
            }
        };
        let (size_x, size_y) = r.iter().fold((0.0f64, 0.0f64), |(sx, sy), v| {
            (sx.max(v.x.abs()), sy.max(v.y.abs()))
        });
        // The piece in the frame (`x` across, `y` along), each coordinate within
        // `turn_rounding` of the exact rotation (none for the axes' frames).
        let mut framed = [Point::default(); MAX_POINTS];
        for (f, v) in framed.iter_mut().zip(r) {
            *f = Point::new(v.y * cs - v.x * sn, v.x * cs + v.y * sn);
        }
        let framed = &framed[..=n];
        let turn_rounding = 4.0 * eps * (size_x + size_y);
        // Strictly advancing along the frame, and `|dw/ds|` at most `slope`.
        let (mut min_ds, mut max_dw) = (f64::INFINITY, 0.0f64);
        for w in framed.windows(2) {
            let (ds, dw) = (w[1].y - w[0].y, (w[1].x - w[0].x).abs());
            // Written to fail on NaN.
            if !(ds > 2.0 * turn_rounding && dw <= f64::MAX) {
                return None;
            }
            (min_ds, max_dw) = (min_ds.min(ds), max_dw.max(dw));
        }
        let slope = (max_dw + 2.0 * turn_rounding) * (1.0 + 4.0 * eps)
            / ((min_ds - 2.0 * turn_rounding) * (1.0 - 4.0 * eps));
        if !slope.is_finite() {
            return None;
        }
        let guard_along_cut = root.guard(reach);
        // Along a row, `w - G(s)` changes by at most `|sn| + slope |cs|` per unit of `x`.
        let guard = (sn.abs() + slope * cs.abs()) * guard_along_cut * (1.0 + 4.0 * eps);
        // The size of the queries' coordinates (in the cell) and of the sub-curve's, for the
        // rounding of their `s` and `w` and of the origin's.
        let scale = cell.0.x.abs().max(cell.1.x.abs())
            + cell.0.y.abs().max(cell.1.y.abs())
            + o.x.abs()
            + o.y.abs()
            + 2.0 * (size_x + size_y)
            + 4.0 * reach;
        let mut fit = Self::fit(framed, guard, turn_rounding, scale)?;
        // From the sub-curve's first point to the plane's origin.
        let (s_origin, w_origin) = (o.x * cs + o.y * sn, o.y * cs - o.x * sn);
        fit.mid += s_origin;
        fit.c[0] += w_origin;
        let strip_rounding = 8.0 * eps * scale + 2.0 * turn_rounding;
        fit.s_lo = framed[0].y + s_origin + strip_rounding;
        fit.s_hi = framed[n].y + s_origin - strip_rounding;
        fit.beyond = cs.abs() * guard_along_cut * (1.0 + 4.0 * eps) + 2.0 * strip_rounding;
        (fit.cs, fit.sn) = (cs, sn);
        fit.sign = if rising { -1.0 } else { 1.0 };
        let tight = fit.tol <= TIGHT * guard;
        (fit.s_lo <= fit.s_hi && fit.beyond.is_finite()).then_some((fit, tight))
    }

    /// The polynomial of degree [`MAX_DEGREE`] through the graph `x = X(y)` of the curve with
    /// control points `p` (`y` strictly rising: the frame's across and along) at the
    /// Chebyshev points of its span, its tolerance twice the sum of its certified bound and
    /// every rounding (`point_rounding`: of the control points; `scale`: the size of the
    /// queries' coordinates, whose `s` and `w` round with it), plus `guard`.
    fn fit(p: &[Point], guard: f64, point_rounding: f64, scale: f64) -> Option<Self> {
        let eps = f64::EPSILON;
        let n = p.len() - 1;
        let (a, b) = (p[0].y, p[n].y);
        let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
        let inv_half = 1.0 / half;
        if !(inv_half.is_finite() && half > 0.0) {
            return None;
        }
        let k = MAX_DEGREE;
        let nodes = k + 1;
        let mut values = [0.0; MAX_DEGREE + 1];
        let mut us = [0.0; MAX_DEGREE + 1];
        for (j, (value, u)) in values.iter_mut().zip(&mut us).enumerate().take(nodes) {
            *u = chebyshev_angle(j, nodes).cos();
            let t = parameter_at(p, mid + half * *u)?;
            *value = de_casteljau_with_derivative(p, t).0.x;
        }
        let c = chebyshev_to_monomial(&values[..nodes], &us[..nodes]);
        let (bound, magnitude) = certify(p, -mid, inv_half, &c[..nodes]);
        if !(bound.is_finite() && magnitude.is_finite()) {
            return None;
        }
        let (size_x, size_y) = p.iter().fold((0.0f64, 0.0f64), |(sx, sy), v| {
            (sx.max(v.x.abs()), sy.max(v.y.abs()))
        });
        let sum_c: f64 = c.iter().map(|c| c.abs()).sum();
        let lipschitz: f64 = 2.0
            * c.iter()
                .enumerate()
                .map(|(j, c)| j as f64 * c.abs())
                .sum::<f64>();
        // A change of `ds` in `s` moves `P(u)` by at most `lipschitz inv_half ds`.
        let carry = 1.0 + lipschitz * inv_half;
        let rounding_fit = (4 * n * k + 16) as f64 * eps * magnitude;
        let restriction = 8.0 * (n + 1) as f64 * eps * (size_x + size_y) * carry;
        let evaluation = (4 * k + 8) as f64 * eps * sum_c + 3.0 * eps * lipschitz;
        let query = 8.0 * eps * scale * carry;
        // The bound and the roundings doubled (a margin for the bounds' own rounding), the
        // guard taken as it is (already an upper bound).
        let tol = 2.0
            * (bound + rounding_fit + restriction + point_rounding * carry + evaluation + query)
            + guard * (1.0 + 16.0 * eps);
        tol.is_finite().then_some(Self {
            cs: 0.0,
            sn: 1.0,
            s_lo: f64::NEG_INFINITY,
            s_hi: f64::INFINITY,
            beyond: 0.0,
            mid,
            inv_half,
            tol,
            sign: 1.0,
            c,
        })
    }

    /// The test of a sub-curve with abscissas in `[lo, hi]` from its control box alone: a
    /// query farther than half the box's width, twice `reach` and their rounding from its
    /// middle lies outside the box grown by twice the reach, left or right of the curve.
    pub(super) fn of_box(lo: f64, hi: f64, reach: f64) -> Self {
        let eps = f64::EPSILON;
        let mut c = [0.0; MAX_DEGREE + 1];
        // Across the heights' frame `(0, 1)`, `w = -x`: minus the middle.
        c[0] = -(0.5 * lo + 0.5 * hi);
        let tol = 0.5 * (hi - lo) + 2.0 * reach + 8.0 * eps * (lo.abs() + hi.abs() + 2.0 * reach);
        Self {
            cs: 0.0,
            sn: 1.0,
            s_lo: f64::NEG_INFINITY,
            s_hi: f64::INFINITY,
            beyond: 0.0,
            mid: 0.0,
            inv_half: 0.0,
            tol,
            sign: -1.0,
            c,
        }
    }

    /// The test that puts every query right of the curve (a sub-curve wholly left of every
    /// query that reads it: a chord).
    pub(super) fn always_left() -> Self {
        Self {
            tol: 0.0,
            c: {
                let mut c = [0.0; MAX_DEGREE + 1];
                c[0] = f64::INFINITY;
                c
            },
            ..Self::of_box(0.0, 0.0, 0.0)
        }
    }

    /// The width of the band about the sub-curve this test leaves undecided, along the
    /// normal of a sub-curve of unit direction `chord`: the tolerance times the cosine of the
    /// angle between the frame's direction and the chord.
    pub(super) fn width_across(&self, chord: Point) -> f64 {
        self.tol * (self.cs * chord.x + self.sn * chord.y).abs()
    }

    /// `(left, decided)` at `q`, a query in the cell at a height of the sub-curve (elsewhere
    /// the answer does not count): whether the curve passes left of `q` at `q`'s height, and
    /// whether that, or its passing right of it, is certain. Branch-free.
    #[inline(always)]
    pub(super) fn side(&self, q: Point) -> (bool, bool) {
        let s = q.x * self.cs + q.y * self.sn;
        let w = q.y * self.cs - q.x * self.sn;
        let g = estrin(&self.c, (s - self.mid) * self.inv_half);
        let d = self.sign * (w - g);
        let inside = s >= self.s_lo && s <= self.s_hi;
        let past_end = s > self.s_hi + self.beyond;
        let before_start = s < self.s_lo - self.beyond;
        let left = (inside & (d > self.tol))
            | (past_end & (self.cs > 0.0))
            | (before_start & (self.cs < 0.0));
        let decided = (inside & (d.abs() > self.tol)) | past_end | before_start;
        (left, decided)
    }
}

/// A monotone sub-curve's piece at a cell's heights ([`piece_in_cell`]).
pub(super) struct CellPiece {
    /// The sub-curve's first control point, which the piece's are relative to.
    pub(super) origin: Point,
    /// The piece's control points, relative to `origin` (`n + 1` of them).
    pub(super) points: [Point; MAX_POINTS],
    /// Its degree.
    pub(super) n: usize,
    /// Whether its heights rise.
    pub(super) rising: bool,
    /// The heights it covers, the cell's and the sub-curve's in common, relative to `origin`.
    pub(super) heights: (f64, f64),
}

/// The piece of the polynomial sub-curve `root` (2 to [`MAX_POINTS`] control points, heights
/// strictly rising or falling) at its heights within those of `cell`, relative to its first
/// point ([`restricted_to_heights`]); `None` if they hold none of its own or a height is not
/// found.
pub(super) fn piece_in_cell(root: &MonotoneCurve, cell: (Point, Point)) -> Option<CellPiece> {
    let p = root.points();
    let n = p.len().checked_sub(1)?;
    if !(1..MAX_POINTS).contains(&n) {
        return None;
    }
    let rising = p[n].y > p[0].y;
    let (y_min, y_max) = if rising {
        (p[0].y, p[n].y)
    } else {
        (p[n].y, p[0].y)
    };
    let (a, b) = (cell.0.y.max(y_min), cell.1.y.min(y_max));
    if a.partial_cmp(&b) != Some(std::cmp::Ordering::Less) {
        return None;
    }
    let o = p[0];
    let mut local = [Point::default(); MAX_POINTS];
    for (l, &v) in local.iter_mut().zip(p) {
        *l = v - o;
    }
    let whole = a <= y_min && b >= y_max;
    let heights = (a - o.y, b - o.y);
    let points = restricted_to_heights(&local[..=n], heights, rising, whole)?;
    Some(CellPiece {
        origin: o,
        points,
        n,
        rising,
        heights,
    })
}

/// The sub-curve with control points `c` (relative to its first point; heights strictly
/// rising if `rising`, else falling) restricted to parameters covering its heights in
/// `(a, b)` (widened, its ends' heights clearing the band by their rounding), or all of it if
/// `whole` or the restriction cannot show that; `None` if a height is not found.
fn restricted_to_heights(
    c: &[Point],
    (a, b): (f64, f64),
    rising: bool,
    whole: bool,
) -> Option<[Point; MAX_POINTS]> {
    let n = c.len() - 1;
    let mut r = [Point::default(); MAX_POINTS];
    r[..=n].copy_from_slice(c);
    if whole {
        return Some(r);
    }
    let size_y = c.iter().fold(0.0f64, |s, v| s.max(v.y.abs()));
    let clear = 8.0 * (n + 1) as f64 * f64::EPSILON * size_y + f64::EPSILON * a.abs().max(b.abs());
    // On a falling sub-curve the lower height comes later.
    let flip = |y: f64| if rising { y } else { -y };
    let mut oriented = [Point::default(); MAX_POINTS];
    for (o, v) in oriented.iter_mut().zip(c) {
        *o = Point::new(v.x, flip(v.y));
    }
    let (ya, yb) = if rising { (a, b) } else { (-b, -a) };
    let t0 = parameter_at(&oriented[..=n], ya)?;
    let t1 = parameter_at(&oriented[..=n], yb)?;
    let widen = 1.0 / (1u64 << 30) as f64;
    let (t0, t1) = ((t0 - widen).max(0.0), (t1 + widen).min(1.0));
    let mut left = [Point::default(); MAX_POINTS];
    let mut right = [Point::default(); MAX_POINTS];
    let mut restricted = [Point::default(); MAX_POINTS];
    de_casteljau_split(c, t1, &mut left[..=n], &mut right[..=n]);
    if t0 > 0.0 {
        de_casteljau_split(
            &left[..=n],
            t0 / t1,
            &mut right[..=n],
            &mut restricted[..=n],
        );
    } else {
        restricted = left;
    }
    let (first, last) = (flip(restricted[0].y), flip(restricted[n].y));
    if first <= ya - clear && last >= yb + clear {
        r = restricted;
    }
    Some(r)
}

/// The angle of the `j`-th of `nodes` Chebyshev points of the first kind.
fn chebyshev_angle(j: usize, nodes: usize) -> f64 {
    std::f64::consts::PI * (2 * j + 1) as f64 / (2 * nodes) as f64
}

/// `sum c_j u^j` by Estrin's scheme: the pairs `c_2i + c_2i+1 u`, by Horner's scheme in `u^2`
/// (five dependent steps at degree 8 instead of Horner's eight).
#[inline(always)]
fn estrin(c: &[f64; MAX_DEGREE + 1], u: f64) -> f64 {
    let u2 = u * u;
    let mut p = 0.0;
    for pair in c.chunks(2).rev() {
        let b = pair.get(1).copied().unwrap_or(0.0);
        p = p * u2 + (pair[0] + b * u);
    }
    p
}

/// The parameter where the polynomial curve `c` (at most [`MAX_POINTS`] control points) meets
/// height `y` (to one ulp, by the workspace's bracketed Newton iteration); `None` if its end
/// heights do not bracket `y`.
fn parameter_at(c: &[Point], y: f64) -> Option<f64> {
    let mut f = [0.0; MAX_POINTS];
    for (f, v) in f.iter_mut().zip(c) {
        *f = v.y - y;
    }
    bernstein_sign_change_root(&f[..c.len()])
}

/// The monomial coefficients (in `u`) of the polynomial of degree `values.len() - 1` through
/// `(us[j], values[j])`, the Chebyshev points of the first kind: its Chebyshev coefficients
/// (`T_m(u_j)` by the recurrence), then the Chebyshev polynomials' monomial forms.
fn chebyshev_to_monomial(values: &[f64], us: &[f64]) -> [f64; MAX_DEGREE + 1] {
    let nodes = values.len();
    let mut out = [0.0; MAX_DEGREE + 1];
    // T_{m-1} and T_m in monomial form, and at the nodes.
    let mut prev = [0.0; MAX_DEGREE + 1];
    let mut cur = [0.0; MAX_DEGREE + 1];
    prev[0] = 1.0;
    cur[1] = 1.0;
    let mut at_prev = [1.0; MAX_DEGREE + 1];
    let mut at_cur = [0.0; MAX_DEGREE + 1];
    at_cur[..nodes].copy_from_slice(us);
    for m in 0..nodes {
        let at = if m == 0 { &at_prev } else { &at_cur };
        let mut a: f64 = values.iter().zip(at).map(|(v, t)| v * t).sum();
        a *= 2.0 / nodes as f64;
        if m == 0 {
            a *= 0.5;
        }
        let t_m = if m == 0 { prev } else { cur };
        for (o, t) in out.iter_mut().zip(t_m) {
            *o += a * t;
        }
        if m >= 1 {
            // T_{m+1} = 2 u T_m - T_{m-1}.
            let mut next = [0.0; MAX_DEGREE + 1];
            for i in 0..MAX_DEGREE {
                next[i + 1] = 2.0 * cur[i];
            }
            for (x, p) in next.iter_mut().zip(prev) {
                *x -= p;
            }
            prev = cur;
            cur = next;
            let mut at_next = [0.0; MAX_DEGREE + 1];
            for j in 0..nodes {
                at_next[j] = 2.0 * us[j] * at_cur[j] - at_prev[j];
            }
            at_prev = at_cur;
            at_cur = at_next;
        }
    }
    out
}

/// A bound on `|x(s) - P(u(s))|` over `s` in `[0, 1]` for the curve with control points `r`,
/// `u = (y + shift) * inv_half`, and `P` of coefficients `c`: the largest Bernstein
/// coefficient of the difference, a polynomial of degree `n k`; and a bound on the size of
/// the terms those coefficients sum (the scale of their rounding).
fn certify(r: &[Point], shift: f64, inv_half: f64, c: &[f64]) -> (f64, f64) {
    let n = r.len() - 1;
    let k = c.len() - 1;
    // Scaled Bernstein coefficients of u(s), and the largest of its plain ones.
    let mut u = [0.0; MAX_POINTS];
    let mut u_size = 0.0f64;
    for i in 0..=n {
        let plain = (r[i].y + shift) * inv_half;
        u[i] = binomial(n, i) * plain;
        u_size = u_size.max(plain.abs());
    }
    let u = &u[..=n];
    // Horner's scheme on P(u(s)): P <- P u + c_j, in scaled form.
    let mut p = [0.0; MAX_PRODUCT];
    let mut scratch = [0.0; MAX_PRODUCT];
    p[0] = c[k];
    let mut len = 1;
    for j in (0..k).rev() {
        let l = product(&p[..len], u, &mut scratch);
        p[..l].copy_from_slice(&scratch[..l]);
        len = l;
        let d = len - 1;
        for (i, p) in p.iter_mut().enumerate().take(len) {
            *p += c[j] * binomial(d, i);
        }
    }
    // x(s), elevated to the same degree: times (s + (1 - s))^(d - n).
    let d = len - 1;
    let mut x = [0.0; MAX_POINTS];
    let mut x_size = 0.0f64;
    for i in 0..=n {
        x[i] = binomial(n, i) * r[i].x;
        x_size = x_size.max(r[i].x.abs());
    }
    let mut xe = [0.0; MAX_PRODUCT];
    elevated(&x[..=n], d, &mut xe);
    let mut bound = 0.0f64;
    for i in 0..=d {
        bound = bound.max(((xe[i] - p[i]) / binomial(d, i)).abs());
    }
    // The terms' scale: a product's plain Bernstein coefficients are convex combinations of
    // its factors' products, so `|P(u(s))|`'s terms are at most `sum |c_j| max|u_i|^j`.
    let mut terms = 0.0f64;
    for &c in c.iter().rev() {
        terms = terms * u_size + c.abs();
    }
    (bound, x_size + terms)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gwn::side_cases::SideCase;
    use rs_testkit::XorShift64;

    /// Wherever a side test decides, the root decides the same crossing: small cubics (at the
    /// origin and moved by `1e3`), bands over part or all of their heights, every frame,
    /// queries displaced along the cut from the curve by `1e-1` to `1e-13` of its size (either
    /// side), anywhere in and around its box, and past its ends ([`SideCase`]); and the tests
    /// decide nearly all queries farther than a thousand times their tolerance.
    #[test]
    fn side_tests_decide_as_the_root_does() {
        let mut rng = XorShift64::new(7);
        let (mut cases, mut tight, mut decided, mut far, mut far_decided) = (0, 0, 0, 0, 0);
        while cases < 1500 {
            let Some(case) = SideCase::draw(&mut rng, cases) else {
                continue;
            };
            let frame = [Frame::Heights, Frame::Abscissas, Frame::Chord][cases % 3];
            let Some((fit, is_tight)) = InverseFit::new(&case.root, case.cell, frame, case.reach)
            else {
                continue;
            };
            cases += 1;
            tight += usize::from(is_tight);
            for (q, displaced) in case.queries(&mut rng) {
                let (left, sure) = fit.side(q);
                if sure {
                    decided += 1;
                    case.assert_root_agrees(q, left, &format!("{frame:?}"));
                }
                if let Some(d) = displaced
                    && d > 1e3 * fit.tol
                    && case.root_decides_without_margin(q)
                {
                    far += 1;
                    far_decided += usize::from(sure);
                }
            }
        }
        assert!(decided > 20_000, "{decided}");
        assert!(far_decided * 100 >= far * 99, "{far_decided} of {far}");
        assert!(tight * 2 >= cases, "{tight} of {cases} tight");
    }

    /// The box's test decides exactly the queries beyond the box grown by twice the reach
    /// (less its rounding), the chord's every query, left.
    #[test]
    fn box_and_chord_tests() {
        let reach = 1e-3;
        let t = InverseFit::of_box(1.0, 3.0, reach);
        assert_eq!(t.side(Point::new(3.01, 5.0)), (true, true));
        assert_eq!(t.side(Point::new(0.99, -5.0)), (false, true));
        for x in [1.0, 2.0, 3.0, 3.0015, 0.9985] {
            assert!(!t.side(Point::new(x, 0.0)).1, "{x}");
        }
        let chord = InverseFit::always_left();
        for q in [
            Point::new(-1e300, 0.0),
            Point::new(0.0, 1e300),
            Point::new(5.0, -2.0),
        ] {
            assert_eq!(chord.side(q), (true, true));
        }
    }
}
