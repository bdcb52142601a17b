//! **The** homogeneous Bezier piece: a rational Bezier piece stored as homogeneous Bernstein
//! coefficients `(w x, w y, w)` beside its Cartesian control points, with the fast evaluations
//! and monotone solves the containment tests need, and the evaluation cell coverage integrates
//! with ([`BezierPiece::relative_to`], [`RelativePiece::point_and_x_derivative`]).

use rs_roots::{
    bernstein_sign_change_root, de_casteljau, de_casteljau_split, de_casteljau_with_derivative,
    rational_derivative_numerator,
};
use smallvec::SmallVec;

use rs_spline::{Axis, Point, RationalBezier, SplineError};

/// A part of a piece ([`BezierPiece::balanced_parts`]); its odds are those of
/// [`crate::MonotoneBox::odds`].
pub type BalancedPart = rs_spline::Part<BezierPiece>;

/// Coefficients kept on the stack (degree <= 7).
const INLINE_COEFFS: usize = 8;

/// Coefficient storage: degree <= 7 stays on the stack.
pub(crate) type Coeffs = SmallVec<[f64; INLINE_COEFFS]>;

/// A rational Bezier piece `C(t) = (X(t), Y(t)) / W(t)` on `[0, 1]`, kept as Cartesian control
/// coordinates `x_i`, `y_i`, weights `w_i > 0` and the homogeneous Bernstein coefficients
/// `w_i x_i`, `w_i y_i`.
///
/// The end points are the stored Cartesian `(x_0, y_0)` and `(x_n, y_n)`, returned exactly by
/// every evaluation at `t = 0` and `t = 1`, and solves use the coefficients `w_i (x_i - v)`, so
/// the sign of a solve's end coefficient always agrees with comparing `v` to the end point.
/// Degree <= 7 stays on the stack.
#[derive(Clone, Debug, PartialEq)]
pub struct BezierPiece {
    x: Coeffs,
    y: Coeffs,
    w: Coeffs,
    hx: Coeffs,
    hy: Coeffs,
}

impl BezierPiece {
    /// The piece of a rational Bezier curve.
    pub fn from_bezier(b: &RationalBezier) -> Self {
        let w: Coeffs = b.weights().iter().copied().collect();
        let x = b.control_points().iter().map(|p| p.x).collect();
        let y = b.control_points().iter().map(|p| p.y).collect();
        Self::from_cartesian(x, y, w)
    }

    fn from_cartesian(x: Coeffs, y: Coeffs, w: Coeffs) -> Self {
        let hx = x.iter().zip(&w).map(|(x, w)| x * w).collect();
        let hy = y.iter().zip(&w).map(|(y, w)| y * w).collect();
        Self { x, y, w, hx, hy }
    }

    fn from_homogeneous(hx: Coeffs, hy: Coeffs, w: Coeffs) -> Self {
        let x = hx.iter().zip(&w).map(|(h, w)| h / w).collect();
        let y = hy.iter().zip(&w).map(|(h, w)| h / w).collect();
        Self { x, y, w, hx, hy }
    }

    /// The piece in coordinates relative to `origin` (control points `P_i - origin`), as the
    /// homogeneous coefficients an integrand evaluates in a cell's own coordinates.
    #[inline]
    pub fn relative_to(&self, origin: Point) -> RelativePiece<'_> {
        let n = self.w.len();
        if n > INLINE_COEFFS {
            let u: Coeffs = self.x.iter().map(|x| x - origin.x).collect();
            let v: Coeffs = self.y.iter().map(|y| y - origin.y).collect();
            return RelativePiece {
                extent: (largest_magnitude(&u), largest_magnitude(&v)),
                hx: u.iter().zip(&self.w).map(|(u, w)| w * u).collect(),
                hy: v.iter().zip(&self.w).map(|(v, w)| w * v).collect(),
                w: &self.w,
            };
        }
        // Per cell part in coverage: one pass on the stack.
        let (mut hx, mut hy) = ([0.0; INLINE_COEFFS], [0.0; INLINE_COEFFS]);
        let (mut ue, mut ve) = (0.0f64, 0.0f64);
        for i in 0..n {
            let (u, v, w) = (self.x[i] - origin.x, self.y[i] - origin.y, self.w[i]);
            ue = ue.max(u.abs());
            ve = ve.max(v.abs());
            hx[i] = w * u;
            hy[i] = w * v;
        }
        RelativePiece {
            hx: Coeffs::from_buf_and_len(hx, n),
            hy: Coeffs::from_buf_and_len(hy, n),
            w: &self.w,
            extent: (ue, ve),
        }
    }

    /// Degree `n`.
    #[inline]
    pub fn degree(&self) -> usize {
        self.w.len() - 1
    }

    /// Control point `i` in Cartesian coordinates.
    ///
    /// # Panics
    /// If `i > n`.
    #[inline]
    pub fn control_point(&self, i: usize) -> Point {
        Point::new(self.x[i], self.y[i])
    }

    /// The control points' abscissas `x_0 .. x_n`.
    #[inline]
    pub fn xs(&self) -> &[f64] {
        &self.x
    }

    /// The control points' ordinates `y_0 .. y_n`.
    #[inline]
    pub fn ys(&self) -> &[f64] {
        &self.y
    }

    /// The weights `w_i` (all > 0).
    #[inline]
    pub fn weights(&self) -> &[f64] {
        &self.w
    }

    /// All weights equal: `x(t)`, `y(t)` are polynomials of the piece's degree.
    #[inline]
    pub fn is_polynomial(&self) -> bool {
        rs_spline::weights_are_equal(&self.w)
    }

    /// `C(0)`.
    pub fn start(&self) -> Point {
        self.control_point(0)
    }

    /// `C(1)`.
    pub fn end(&self) -> Point {
        self.control_point(self.degree())
    }

    /// The piece as parts whose motion fills their parameter, by `rs_spline::balance`'s rules
    /// (as [`RationalBezier::balanced_parts`] cuts a Bezier piece): its end weights balanced,
    /// and, while a part [`crowds its ends`](rs_spline::crowds_ends), the part halved and each
    /// half balanced again ([`rs_spline::balanced_parts`]). An ordinary piece is one part,
    /// itself, with odds 1. Each part also carries the fractions of this piece's parameter it
    /// spans and its odds.
    pub fn balanced_parts(self) -> Vec<BalancedPart> {
        rs_spline::balanced_parts(self)
    }

    /// Moves the first control point to `p`, keeping its weight (used to make loops
    /// watertight).
    pub(crate) fn set_start(&mut self, p: Point) {
        self.x[0] = p.x;
        self.y[0] = p.y;
        self.hx[0] = p.x * self.w[0];
        self.hy[0] = p.y * self.w[0];
    }

    /// The control points' coordinates along `axis`.
    fn coords(&self, axis: Axis) -> &Coeffs {
        match axis {
            Axis::X => &self.x,
            Axis::Y => &self.y,
        }
    }

    /// Are the control points' coordinates along `axis` all equal?
    pub(crate) fn is_constant(&self, axis: Axis) -> bool {
        let c = self.coords(axis);
        c.iter().all(|&v| v == c[0])
    }

    fn set_constant(&mut self, axis: Axis, v: f64) {
        let (c, h) = match axis {
            Axis::X => (&mut self.x, &mut self.hx),
            Axis::Y => (&mut self.y, &mut self.hy),
        };
        for (i, w) in self.w.iter().enumerate() {
            c[i] = v;
            h[i] = v * w;
        }
    }

    /// `C(t)` by de Casteljau in homogeneous coordinates (the stored end points at `t = 0, 1`).
    pub fn point_at(&self, t: f64) -> Point {
        Point::new(self.x_at(t), self.y_at(t))
    }

    /// `x(t) = X(t) / W(t)`.
    pub fn x_at(&self, t: f64) -> f64 {
        rational_at(&self.x, &self.hx, &self.w, t)
    }

    /// `y(t) = Y(t) / W(t)`.
    pub fn y_at(&self, t: f64) -> f64 {
        rational_at(&self.y, &self.hy, &self.w, t)
    }

    /// The parameter where `x(t) = px`, for a piece whose `x(0) - px` and `x(1) - px` differ in
    /// sign (or vanish): the root of `sum_i w_i (x_i - px) B_i(t)` (the weights
    /// are positive, so no rational root finding is needed). `None` if there is no sign change.
    pub(crate) fn solve_x(&self, px: f64) -> Option<f64> {
        solve_axis(&self.x, &self.w, px)
    }

    /// The parameter where `y(t) = py` (see [`BezierPiece::solve_x`]).
    pub(crate) fn solve_y(&self, py: f64) -> Option<f64> {
        solve_axis(&self.y, &self.w, py)
    }

    /// Splits at `t` into the pieces on `[0, t]` and `[t, 1]`; the shared point is the same
    /// `f64` value in both.
    pub(crate) fn split(&self, t: f64) -> (Self, Self) {
        let (lx, rx) = split_coeffs(&self.hx, t);
        let (ly, ry) = split_coeffs(&self.hy, t);
        let (lw, rw) = split_coeffs(&self.w, t);
        let (mut left, mut right) = (
            Self::from_homogeneous(lx, ly, lw),
            Self::from_homogeneous(rx, ry, rw),
        );
        // A constant coordinate (vertical or horizontal piece) stays exactly constant: rounding
        // in `(1 - t) a + t a` would otherwise tilt it by an ulp.
        for axis in Axis::BOTH {
            if self.is_constant(axis) {
                let v = self.coords(axis)[0];
                left.set_constant(axis, v);
                right.set_constant(axis, v);
            }
        }
        // Both sides must agree on the shared point bit for bit.
        right.x[0] = left.x[left.x.len() - 1];
        right.y[0] = left.y[left.y.len() - 1];
        (left, right)
    }

    /// The numerator of `x'(t)` (for [`Axis::X`]) or `y'(t)`: `X' W - X W'`, in the Bernstein
    /// basis of degree `2n - 1` on `[0, 1]` (`n` the degree; one more than the polynomial's
    /// degree `2n - 2`, a degree-elevated form of it), formed from the control points directly.
    /// Its sign is the sign of the derivative (`W^2 > 0`). The coordinate is taken relative to
    /// the first control point, which leaves the numerator unchanged (`W' W - W W' = 0`) and
    /// makes its first coefficient `n w_0 w_1 (c_1 - c_0)`, exactly zero at a tangency there.
    pub(crate) fn derivative_numerator(&self, axis: Axis) -> SmallVec<[f64; 16]> {
        let n = self.degree();
        let mut out: SmallVec<[f64; 16]> = SmallVec::from_elem(0.0, (2 * n).max(1));
        rational_derivative_numerator(self.coords(axis), &self.w, &mut out);
        out
    }

    /// The piece as a [`RationalBezier`] on `[0, 1]`.
    ///
    /// # Errors
    /// Only if the coefficients were corrupted (subdivision keeps weights positive).
    pub fn to_bezier(&self) -> Result<RationalBezier, SplineError> {
        let pts = (0..self.w.len()).map(|i| self.control_point(i)).collect();
        RationalBezier::new(pts, self.w.to_vec())
    }
}

/// A [`BezierPiece`] in coordinates relative to an origin `o` ([`BezierPiece::relative_to`]):
/// its homogeneous coefficients `w_i (x_i - o_x)`, `w_i (y_i - o_y)` (each one rounded
/// subtraction and one product) and its weights, so that values are computed in the origin's
/// coordinates (a cell's, for coverage) without the rounding of the absolute ones.
#[derive(Clone, Debug, PartialEq)]
pub struct RelativePiece<'a> {
    hx: Coeffs,
    hy: Coeffs,
    w: &'a [f64],
    extent: (f64, f64),
}

impl RelativePiece<'_> {
    /// `(max_i |x_i - o_x|, max_i |y_i - o_y|)`: the size of the terms the relative coordinates
    /// are sums of (their rounding scale).
    #[inline]
    pub fn extent(&self) -> (f64, f64) {
        self.extent
    }

    /// `(x(t) - o_x, y(t) - o_y, x'(t))`, what a Green's-theorem integral `integral P dx`
    /// evaluates: one de Casteljau pass for each of `X`, `Y`, `W` (with the derivatives of `X`
    /// and `W`), one division `r = 1 / W`, then `x = X r`, `y = Y r` and the quotient rule
    /// `x' = (X' W - X W') r^2`. The end points are computed too, not the stored ones.
    #[inline]
    pub fn point_and_x_derivative(&self, t: f64) -> (f64, f64, f64) {
        let (x, dx) = de_casteljau_with_derivative(&self.hx, t);
        let (w, dw) = de_casteljau_with_derivative(self.w, t);
        let y = de_casteljau(&self.hy, t);
        let inv = 1.0 / w;
        (x * inv, y * inv, (dx * w - x * dw) * inv * inv)
    }

    /// `(x(t) - o_x, y(t) - o_y, x'(t), y'(t))`: [`RelativePiece::point_and_x_derivative`]
    /// with `y' = (Y' W - Y W') r^2` too, what an integral along the arc length
    /// (`ds = |(x', y')| dt`) evaluates.
    #[inline]
    pub fn point_and_derivatives(&self, t: f64) -> (f64, f64, f64, f64) {
        let (x, dx) = de_casteljau_with_derivative(&self.hx, t);
        let (y, dy) = de_casteljau_with_derivative(&self.hy, t);
        let (w, dw) = de_casteljau_with_derivative(self.w, t);
        let inv = 1.0 / w;
        let inv2 = inv * inv;
        (
            x * inv,
            y * inv,
            (dx * w - x * dw) * inv2,
            (dy * w - y * dw) * inv2,
        )
    }
}

/// Most coefficients of a [`HalvedPiece`]: degree <= 7 (larger degrees halve through
/// [`BezierPiece::split`]).
pub(crate) const HALVED_COEFFS: usize = 8;

/// A piece of degree at most 7 in fixed-size arrays, for the repeated halvings of
/// [`MonotoneBox::for_grid_parts`](crate::MonotoneBox::for_grid_parts) and the cuts of the
/// refined boxes: [`HalvedPiece::split_at`] (and [`HalvedPiece::halve`], at `t = 0.5`) gives,
/// bit for bit, the control points and weights of [`BezierPiece::split`] at the same `t`
/// (the same de Casteljau blends `a * (1 - s) + b * s` in the same order, the same divisions,
/// the same fix-ups of constant coordinates and of the shared point), without the `SmallVec`
/// copies and moves.
#[derive(Clone, Copy, Debug)]
pub(crate) struct HalvedPiece {
    /// Number of coefficients, `degree + 1`, in `1..=HALVED_COEFFS`.
    len: usize,
    x: [f64; HALVED_COEFFS],
    y: [f64; HALVED_COEFFS],
    w: [f64; HALVED_COEFFS],
    hx: [f64; HALVED_COEFFS],
    hy: [f64; HALVED_COEFFS],
}

impl HalvedPiece {
    /// The piece in fixed-size arrays, `None` above degree 7 (or for an empty piece).
    pub(crate) fn of(piece: &BezierPiece) -> Option<Self> {
        let len = piece.w.len();
        if len == 0 || len > HALVED_COEFFS {
            return None;
        }
        let mut out = Self {
            len,
            x: [0.0; HALVED_COEFFS],
            y: [0.0; HALVED_COEFFS],
            w: [0.0; HALVED_COEFFS],
            hx: [0.0; HALVED_COEFFS],
            hy: [0.0; HALVED_COEFFS],
        };
        out.x[..len].copy_from_slice(&piece.x);
        out.y[..len].copy_from_slice(&piece.y);
        out.w[..len].copy_from_slice(&piece.w);
        out.hx[..len].copy_from_slice(&piece.hx);
        out.hy[..len].copy_from_slice(&piece.hy);
        Some(out)
    }

    /// The piece as a [`BezierPiece`] (the same coefficients).
    pub(crate) fn to_piece(self) -> BezierPiece {
        let n = self.len;
        BezierPiece {
            x: Coeffs::from_slice(&self.x[..n]),
            y: Coeffs::from_slice(&self.y[..n]),
            w: Coeffs::from_slice(&self.w[..n]),
            hx: Coeffs::from_slice(&self.hx[..n]),
            hy: Coeffs::from_slice(&self.hy[..n]),
        }
    }

    /// The control points' abscissas.
    pub(crate) fn xs(&self) -> &[f64] {
        &self.x[..self.len]
    }

    /// The control points' ordinates.
    pub(crate) fn ys(&self) -> &[f64] {
        &self.y[..self.len]
    }

    /// `C(0)`.
    pub(crate) fn start(&self) -> Point {
        Point::new(self.x[0], self.y[0])
    }

    /// `C(1)`.
    pub(crate) fn end(&self) -> Point {
        Point::new(self.x[self.len - 1], self.y[self.len - 1])
    }

    /// Halves the piece in place: it becomes the half on `[0, 0.5]` and the half on `[0.5, 1]`
    /// is returned, both equal bit for bit to [`BezierPiece::split`]`(0.5)`'s (one copy of the
    /// arrays per halving).
    pub(crate) fn halve(&mut self) -> Self {
        self.split_at(0.5)
    }

    /// Splits the piece in place at `s`: it becomes the part on `[0, s]` and the part on
    /// `[s, 1]` is returned, both equal bit for bit to [`BezierPiece::split`]`(s)`'s (the
    /// refinement of [`MonotoneBoxes`](crate::MonotoneBoxes) cuts its boxes off with it).
    pub(crate) fn split_at(&mut self, s: f64) -> Self {
        let n = self.len;
        // Constancy of the piece being split, as `split` tests it.
        let (x0, y0) = (self.x[0], self.y[0]);
        let x_constant = self.xs().iter().all(|&v| v == x0);
        let y_constant = self.ys().iter().all(|&v| v == y0);
        let mut right = *self;
        let left = self;
        // The one de Casteljau kernel, as `split` calls it, on the arrays in place.
        let (hx, hy, w) = (left.hx, left.hy, left.w);
        de_casteljau_split(&hx[..n], s, &mut left.hx[..n], &mut right.hx[..n]);
        de_casteljau_split(&hy[..n], s, &mut left.hy[..n], &mut right.hy[..n]);
        de_casteljau_split(&w[..n], s, &mut left.w[..n], &mut right.w[..n]);
        // from_homogeneous.
        for half in [&mut *left, &mut right] {
            for i in 0..n {
                half.x[i] = half.hx[i] / half.w[i];
                half.y[i] = half.hy[i] / half.w[i];
            }
        }
        // Constant coordinates stay exactly constant (as in `split`).
        if x_constant {
            for half in [&mut *left, &mut right] {
                for i in 0..n {
                    half.x[i] = x0;
                    half.hx[i] = x0 * half.w[i];
                }
            }
        }
        if y_constant {
            for half in [&mut *left, &mut right] {
                for i in 0..n {
                    half.y[i] = y0;
                    half.hy[i] = y0 * half.w[i];
                }
            }
        }
        // Both sides agree on the shared point bit for bit.
        right.x[0] = left.x[n - 1];
        right.y[0] = left.y[n - 1];
        right
    }
}

/// `max_i |c_i|`.
fn largest_magnitude(c: &[f64]) -> f64 {
    c.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

/// `X(t) / W(t)`, exact at the ends.
fn rational_at(c: &[f64], h: &[f64], w: &[f64], t: f64) -> f64 {
    if t == 0.0 {
        c[0]
    } else if t == 1.0 {
        c[c.len() - 1]
    } else {
        de_casteljau(h, t) / de_casteljau(w, t)
    }
}

/// Root of `sum_i w_i (c_i - v) B_i(t)`: the end coefficients vanish exactly when `v` equals
/// an end point's coordinate.
fn solve_axis(c: &[f64], w: &[f64], v: f64) -> Option<f64> {
    let f: Coeffs = c.iter().zip(w).map(|(c, w)| w * (c - v)).collect();
    bernstein_sign_change_root(&f)
}

/// Splits Bernstein coefficients at `t` into stack-allocated halves.
fn split_coeffs(c: &[f64], t: f64) -> (Coeffs, Coeffs) {
    let n = c.len();
    let (mut left, mut right): (Coeffs, Coeffs) =
        (SmallVec::from_elem(0.0, n), SmallVec::from_elem(0.0, n));
    de_casteljau_split(c, t, &mut left, &mut right);
    (left, right)
}

/// The balancing rules' view of a piece ([`rs_spline::balanced_parts`]).
impl rs_spline::Balance for BezierPiece {
    fn balance_weights(&self) -> &[f64] {
        self.weights()
    }

    /// Weights and homogeneous coefficients `w_i 2^(k i)` times theirs (scaled exactly, the
    /// control points unchanged); itself when a scaled value would leave the normal range.
    fn reweighted(mut self, k: i32) -> (Self, f64) {
        let columns: &mut [&mut [f64]] = &mut [&mut self.w, &mut self.hx, &mut self.hy];
        let c = rs_spline::scale_by_powers_of_two(k, columns);
        (self, c.unwrap_or(1.0))
    }

    fn halves(&self) -> (Self, Self) {
        self.split(0.5)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn arc() -> BezierPiece {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        BezierPiece::from_bezier(
            &RationalBezier::new(
                vec![
                    Point::new(1.0, 0.0),
                    Point::new(1.0, 1.0),
                    Point::new(0.0, 1.0),
                ],
                vec![1.0, w, 1.0],
            )
            .unwrap(),
        )
    }

    /// A piece whose end weights differ by more than the ratio is the same curve after
    /// balancing: its point at `s` is the old one at `t = c s / ((1 - s) + c s)`, its ends and
    /// control points are the same bits, its end weights within a factor `2^(n/2)` of each
    /// other; ordinary pieces (a quarter circle, ratio 1; a ratio of 1000) are left alone.
    #[test]
    fn balancing_end_weights_keeps_the_curve() {
        use rs_spline::Balance;
        assert_eq!(arc().balanced(), (arc(), 1.0));
        let piece = |w: Vec<f64>| {
            let n = w.len();
            let pts = (0..n)
                .map(|i| Point::new(i as f64 / (n - 1) as f64, (i % 2) as f64))
                .collect();
            BezierPiece::from_bezier(&RationalBezier::new(pts, w).unwrap())
        };
        let mild = piece(vec![1.0, 3.0, 1000.0]);
        assert_eq!(mild.clone().balanced(), (mild, 1.0));
        for w in [
            vec![1.0, 5e9, 5e9],
            vec![5e9, 5e9, 1.0],
            vec![3e-7, 1.0, 2.0, 0.5],
            vec![1e11, 1.0, 1e3, 7.0, 1e-1],
        ] {
            let old = piece(w.clone());
            let (new, c) = old.clone().balanced();
            let n = old.degree();
            assert!(c != 1.0 && c.log2().fract() == 0.0, "{w:?}: {c}");
            let ratio = new.weights()[0] / new.weights()[n];
            assert!(ratio.log2().abs() <= n as f64 / 2.0, "{w:?}: {ratio}");
            assert_eq!((new.xs(), new.ys()), (old.xs(), old.ys()), "{w:?}");
            for i in 0..=32 {
                let s = f64::from(i) / 32.0;
                let t = c * s / ((1.0 - s) + c * s);
                let (p, q) = (new.point_at(s), old.point_at(t));
                assert!(p.distance(q) < 1e-12, "{w:?} at {s}: {p:?} {q:?}");
            }
        }
    }

    #[test]
    fn solves_on_a_quarter_circle() {
        let a = arc();
        for &px in &[0.0, 0.1, 0.5, 0.999, 1.0] {
            let t = a.solve_x(px).unwrap();
            let p = a.point_at(t);
            assert!((p.x - px).abs() < 1e-15, "{px}: {p:?}");
            assert!((p.y - (1.0 - px * px).sqrt()).abs() < 1e-7);
        }
        assert!(a.solve_x(1.5).is_none());
        let t = a.solve_y(0.6).unwrap();
        assert!((a.y_at(t) - 0.6).abs() < 1e-15);
    }

    /// The Bernstein derivative numerators equal the power-form ones of `rs-spline` (up to
    /// rounding) on rational pieces of degrees 1 to 5, and vanish exactly at an end tangency.
    #[test]
    fn derivative_numerators_match_the_power_form() {
        for n in 1..=5usize {
            let pts: Vec<Point> = (0..=n)
                .map(|i| {
                    Point::new(
                        (i as f64 * 1.7).sin() * 3.0 + 1.0,
                        (i * i) as f64 * 0.3 - 2.0,
                    )
                })
                .collect();
            let w: Vec<f64> = (0..=n)
                .map(|i| 1.0 + 0.4 * (i as f64 * 0.9).cos())
                .collect();
            let b = RationalBezier::new(pts, w).unwrap();
            let piece = BezierPiece::from_bezier(&b);
            let (dx, dy) = b.derivative_numerators();
            for (axis, d) in [(Axis::X, dx), (Axis::Y, dy)] {
                let c = piece.derivative_numerator(axis);
                assert_eq!(c.len(), 2 * n);
                let scale: f64 = c.iter().map(|v| v.abs()).sum();
                for k in 0..=10 {
                    let t = k as f64 / 10.0;
                    let got = de_casteljau(&c, t);
                    assert!((got - d.eval(t)).abs() <= 1e-12 * scale, "{n} {axis:?} {t}");
                }
            }
        }
        let a = arc();
        assert_eq!(a.derivative_numerator(Axis::X)[0], 0.0);
        assert_eq!(*a.derivative_numerator(Axis::Y).last().unwrap(), 0.0);
    }

    /// Repeated halvings of the fixed-size piece equal `split(0.5)`'s bit for bit, on
    /// rational pieces of degrees 1 to 7 and on pieces with a constant coordinate.
    #[test]
    fn halving_equals_split_bit_for_bit() {
        let mut pieces = vec![arc()];
        for n in 1..=7usize {
            let pts: Vec<Point> = (0..=n)
                .map(|i| Point::new((i as f64 * 1.3).cos() * 7.1 + 0.3, (i as f64).sqrt() * 2.9))
                .collect();
            let w: Vec<f64> = (0..=n)
                .map(|i| 0.7 + 0.5 * (i as f64 * 2.1).sin().abs())
                .collect();
            pieces.push(BezierPiece::from_bezier(
                &RationalBezier::new(pts.clone(), w.clone()).unwrap(),
            ));
            let vert: Vec<Point> = pts.iter().map(|p| Point::new(0.1, p.y)).collect();
            pieces.push(BezierPiece::from_bezier(
                &RationalBezier::new(vert, w.clone()).unwrap(),
            ));
            let horiz: Vec<Point> = pts.iter().map(|p| Point::new(p.x, -3.3)).collect();
            pieces.push(BezierPiece::from_bezier(
                &RationalBezier::new(horiz, w).unwrap(),
            ));
        }
        let mut compared = 0;
        for p in pieces {
            let h = HalvedPiece::of(&p).unwrap();
            let mut stack = vec![(p, h, 0)];
            while let Some((p, h, depth)) = stack.pop() {
                assert_eq!(h.xs(), &p.x[..]);
                assert_eq!(h.ys(), &p.y[..]);
                assert_eq!(&h.w[..h.len], &p.w[..]);
                assert_eq!(&h.hx[..h.len], &p.hx[..]);
                assert_eq!(&h.hy[..h.len], &p.hy[..]);
                assert_eq!((h.start(), h.end()), (p.start(), p.end()));
                compared += 1;
                assert_eq!(h.to_piece(), p);
                if depth < 4 {
                    let (l, r) = p.split(0.5);
                    let mut hl = h;
                    let hr = hl.halve();
                    stack.push((l, hl, depth + 1));
                    stack.push((r, hr, depth + 1));
                }
                // The refinement's cuts: at 1 / k for k parts still to cut.
                for k in [2.0, 3.0, 7.0, 32.0] {
                    let (l, r) = p.split(1.0 / k);
                    let mut hl = h;
                    let hr = hl.split_at(1.0 / k);
                    assert_eq!((hl.to_piece(), hr.to_piece()), (l, r), "1/{k}");
                }
            }
        }
        assert_eq!(compared, 22 * 31);
        let big = vec![Point::new(0.0, 0.0); 9];
        let big = BezierPiece::from_bezier(&RationalBezier::new(big, vec![1.0; 9]).unwrap());
        assert!(HalvedPiece::of(&big).is_none());
    }

    #[test]
    fn split_shares_the_point_exactly() {
        let (l, r) = arc().split(0.37);
        assert_eq!(l.end(), r.start());
        assert!((l.point_at(0.5).length() - 1.0).abs() < 1e-15);
    }
}
