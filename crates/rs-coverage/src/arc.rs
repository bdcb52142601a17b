//! One monotone piece of the boundary, with the integrals over its parts in cells.

use rs_boxes::{MonotoneBox, Monotonicity, RelativePiece};
use rs_spline::green::{Jacobian, PieceIntegrand, PieceRule, integrate_piece};
use std::sync::OnceLock;

use rs_spline::{Axis, Point};

use crate::arc_length::ArcLengthTable;

/// The most nodes of the fixed Gauss-Legendre rule of a polynomial part (degree 16, or 10
/// with moments): higher degrees take the adaptive rule.
const MAX_RULE: usize = 16;

/// Relative tolerance of the adaptive integrals over rational parts, against the cell's
/// area (or its first moments): well below the `1e-12` the fractions promise.
const RELATIVE_TOLERANCE: f64 = 1e-15;

/// The moments of the covered area a cell's integrals give ([`Arc::integrals`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Moments {
    /// The area alone: `b`.
    Area,
    /// With the first moments: `b`, `mx`, `my`.
    First,
    /// With the second moments too: `muu`, `muv`, `mvv`.
    Second,
}

impl Moments {
    /// The integrals computed: 1, 3 or 6.
    fn count(self) -> usize {
        match self {
            Moments::Area => 1,
            Moments::First => 3,
            Moments::Second => 6,
        }
    }
}

/// Integrals over a part of the boundary, in coordinates local to a cell's lower-left corner
/// `(x_c, y_r)`, with `u = x - x_c`, `v = y - y_r`: `[b, mx, my, muu, muv, mvv]` =
/// `int v dx`, `int u v dx`, `int v^2 / 2 dx`, `int u^2 v dx`, `int u v^2 / 2 dx`,
/// `int v^3 / 3 dx` (those beyond the [`Moments`] asked for are 0). With
/// `G_k(v) = int_0^v s^k ds` clamped at the cell's height `h`, Green's theorem on a column's
/// strip gives `int int u^m v^k dA = h-terms of the top line - int u^m G_k(v) dx`.
pub(crate) type PartIntegrals = [f64; 6];

/// Integrals along the arc length of a part, in the cell's local coordinates:
/// `[int ds, int u ds, int v ds]`.
pub(crate) type ArcLengthIntegrals = [f64; 3];

/// A monotone piece of a closed boundary loop (a [`MonotoneBox`] with one box), with its loop's
/// orientation factor.
pub(crate) struct Arc {
    /// The piece: end points, bounds, directions, the crossing solves and its Bezier piece.
    pub(crate) piece: MonotoneBox,
    /// `+1` or `-1`: the factor that puts the filled region on the piece's left (the sign of
    /// its loop under the fill rule, see [`rs_contain::LoopNesting::boundary_sign`]).
    pub(crate) sign: f64,
    /// All weights equal: `x(t)`, `y(t)` are polynomials of the piece's degree.
    polynomial: bool,
    /// Its cumulative arc-length integrals, built the first time a band asks for the
    /// boundary's geometry (the same table from whichever thread builds it); `None` for a
    /// piece whose series would need too many sub-intervals (its parts take the adaptive
    /// rule).
    arc_length: OnceLock<Option<ArcLengthTable>>,
}

impl Arc {
    pub(crate) fn new(piece: MonotoneBox, sign: f64) -> Self {
        let polynomial = piece.piece().is_polynomial();
        Self {
            piece,
            sign,
            polynomial,
            arc_length: OnceLock::new(),
        }
    }

    /// Degree of the piece.
    fn degree(&self) -> usize {
        self.piece.piece().degree()
    }

    /// The piece as a [`RationalBezier`](rs_spline::RationalBezier) (for tests: an evaluation
    /// independent of this one).
    #[cfg(test)]
    pub(crate) fn bezier(&self) -> rs_spline::RationalBezier {
        self.piece
            .piece()
            .to_bezier()
            .expect("a monotone piece is a valid curve")
    }

    /// Where the piece meets the horizontal line at ordinate `y` (between its end ordinates):
    /// its parameter and abscissa, the stored end point exactly when `y` is an end's ordinate,
    /// and the piece's own abscissa when it is vertical.
    pub(crate) fn at_y(&self, y: f64) -> (f64, f64) {
        let b = &self.piece.band;
        if y == b.start.y {
            return (0.0, b.start.x);
        }
        if y == b.end.y {
            return (1.0, b.end.x);
        }
        self.on_line(Axis::Y, y, self.piece.at_y(y))
    }

    /// Where the piece meets the vertical line at abscissa `x` (strictly between its end
    /// abscissas): its parameter and ordinate (see [`Arc::at_y`]).
    pub(crate) fn at_x(&self, x: f64) -> (f64, f64) {
        self.on_line(Axis::X, x, self.piece.at_x(x))
    }

    /// The parameter and other coordinate where the piece meets the line on which the `axis`
    /// coordinate is `c`, from the solve's answer `solved`. A monotone piece whose ends
    /// bracket `c` has one root; without a sign change (impossible between the ends) the
    /// nearer end stands in. A piece constant in the other coordinate gives its own.
    fn on_line(&self, axis: Axis, c: f64, solved: Option<(f64, f64)>) -> (f64, f64) {
        let b = &self.piece.band;
        let other = |p: Point| p.coord(axis.other());
        let (t, v) = solved.unwrap_or_else(|| {
            if (c - b.start.coord(axis)).abs() <= (c - b.end.coord(axis)).abs() {
                (0.0, other(b.start))
            } else {
                (1.0, other(b.end))
            }
        });
        let other_dir = match axis {
            Axis::X => self.piece.y_dir,
            Axis::Y => self.piece.x_dir,
        };
        if other_dir == Monotonicity::Constant {
            (t, other(b.start))
        } else {
            // Within the piece's own range: a solve a rounding beyond the piece's end (a
            // tangent to the line at the end) must not place the crossing outside it.
            let (lo, hi) = match axis {
                Axis::X => (b.ymin, b.ymax),
                Axis::Y => (b.xmin, b.xmax),
            };
            (t, v.clamp(lo, hi))
        }
    }

    /// The integrals of [`PartIntegrals`] over the parameters `[t0, t1]`, relative to the cell
    /// corner `corner` of a cell `width` by `height`, by `rs_spline::green`'s kernel.
    ///
    /// Polynomial pieces use the Gauss-Legendre rule that is exact for the integrands
    /// (`v x'` has degree `2n - 1`, `u v x'` and `v^2 x'` degree `3n - 1`) up to
    /// [`MAX_RULE`] nodes, all the integrals in one pass; rational ones (and higher degrees) the
    /// bounded adaptive rule, each integral on its own with a tolerance of `1e-15` of the
    /// cell's area (or moments). The control points are shifted to the corner before
    /// evaluation, so the values are computed in the cell's coordinates.
    pub(crate) fn integrals(
        &self,
        range: (f64, f64),
        corner: Point,
        (width, height): (f64, f64),
        moments: Moments,
    ) -> PartIntegrals {
        let local = Local::new(self, corner);
        let n = self.degree();
        let degree = match moments {
            Moments::Area => 2 * n,
            Moments::First => 3 * n,
            Moments::Second => 4 * n,
        }
        .saturating_sub(1);
        let area = width * height;
        let count = moments.count();
        // The kernel adds to `sum`: from +0.0 that is its result bit for bit (never -0.0, as
        // t1 > t0 and its own sums start at +0.0).
        let mut sum = [0.0; 6];
        match PieceRule::for_piece(self.polynomial, degree, MAX_RULE, RELATIVE_TOLERANCE * area) {
            exact @ PieceRule::Exact(_) => {
                let mut all = CellMoments {
                    local: &local,
                    moments,
                };
                integrate_piece(
                    &mut all,
                    range,
                    exact,
                    Jacobian::OnTheSum,
                    &mut sum[..count],
                );
            }
            PieceRule::Adaptive { abs_tol } => {
                CellMoment::<B>::integrate(&local, range, abs_tol, &mut sum[B]);
                if moments >= Moments::First {
                    CellMoment::<MX>::integrate(&local, range, abs_tol * width, &mut sum[MX]);
                    CellMoment::<MY>::integrate(&local, range, abs_tol * height, &mut sum[MY]);
                }
                if moments == Moments::Second {
                    let (w2, wh, h2) = (width * width, width * height, height * height);
                    CellMoment::<MUU>::integrate(&local, range, abs_tol * w2, &mut sum[MUU]);
                    CellMoment::<MUV>::integrate(&local, range, abs_tol * wh, &mut sum[MUV]);
                    CellMoment::<MVV>::integrate(&local, range, abs_tol * h2, &mut sum[MVV]);
                }
            }
        }
        sum
    }

    /// The integral a revolved cell's volume takes from a part, over the parameters
    /// `[t0, t1]` in the cell's coordinates: about the y axis `int x v dx` (`x = x_c + u`),
    /// about the x axis `int (y_r + v / 2) v dx`, the combinations `x_c b + mx` and
    /// `y_r b + my` of [`PartIntegrals`] as one integrand (one evaluation of the piece per
    /// node, one adaptive run on a rational piece). Rules as [`Arc::integrals`], the
    /// tolerance scaled by the distance to the axis.
    pub(crate) fn volume_integral(
        &self,
        range: (f64, f64),
        corner: Point,
        (width, height): (f64, f64),
        axis: Axis,
    ) -> f64 {
        let local = Local::new(self, corner);
        let degree = (3 * self.degree()).saturating_sub(1);
        let radius = match axis {
            Axis::Y => corner.x.abs() + width,
            Axis::X => corner.y.abs() + height,
        };
        let tol = RELATIVE_TOLERANCE * width * height * radius;
        let mut integrand = Volume {
            local: &local,
            axis,
            origin: match axis {
                Axis::Y => corner.x,
                Axis::X => corner.y,
            },
        };
        let mut sum = [0.0];
        let rule = PieceRule::for_piece(self.polynomial, degree, MAX_RULE, tol);
        integrate_piece(&mut integrand, range, rule, Jacobian::OnTheSum, &mut sum);
        sum[0]
    }

    /// The integrals of [`ArcLengthIntegrals`] over the parameters `[t0, t1]`, relative to
    /// the cell corner `corner` of a cell `width` by `height`: differences of the piece's
    /// cumulative arc-length integrals ([`ArcLengthTable`]), or, for a piece without a table
    /// (strong weights whose rounding the series cannot resolve within its bound), the
    /// bounded adaptive rule on `ds`, `(u / width) ds`, `(v / height) ds` to `1e-15` of the
    /// cell's half perimeter.
    pub(crate) fn arc_length_integrals(
        &self,
        range: (f64, f64),
        corner: Point,
        (width, height): (f64, f64),
    ) -> ArcLengthIntegrals {
        let table = self
            .arc_length
            .get_or_init(|| ArcLengthTable::new(self.piece.piece()));
        if let Some(table) = table {
            return table.integrals(range, corner);
        }
        let piece = self.piece.piece().relative_to(corner);
        let mut speed = ArcLength {
            piece: &piece,
            scale: (1.0 / width, 1.0 / height),
        };
        let mut sum = [0.0; 3];
        integrate_piece(
            &mut speed,
            range,
            PieceRule::Adaptive {
                abs_tol: RELATIVE_TOLERANCE * (width + height),
            },
            Jacobian::OnTheSum,
            &mut sum,
        );
        [sum[0], sum[1] * width, sum[2] * height]
    }
}

/// The integrand of [`Arc::volume_integral`]: `g v x'` with `g = x_c + u` about the y axis,
/// `y_r + v / 2` about the x axis (`origin`: `x_c` or `y_r`).
struct Volume<'a> {
    local: &'a Local<'a>,
    axis: Axis,
    origin: f64,
}

impl Volume<'_> {
    /// The value at `t` and its rounding magnitude.
    #[inline]
    fn at(&self, t: f64) -> (f64, f64) {
        let (u, v, dx) = self.local.eval(t);
        let (um, vm) = self.local.sizes();
        let (g, gm) = match self.axis {
            Axis::Y => (self.origin + u, self.origin.abs() + um),
            Axis::X => (self.origin + 0.5 * v, self.origin.abs() + 0.5 * vm),
        };
        let value = g * v * dx;
        (value, (gm * vm * dx).abs().max(value.abs()))
    }
}

impl PieceIntegrand for Volume<'_> {
    fn add_node(&mut self, t: f64, weight: f64, sum: &mut [f64]) {
        sum[0] += weight * self.at(t).0;
    }

    fn values(&mut self, t: f64, out: &mut [f64]) -> f64 {
        let (value, magnitude) = self.at(t);
        out[0] = value;
        magnitude
    }
}

/// The integrands of [`ArcLengthIntegrals`] for the adaptive rule, the local coordinates
/// scaled by `scale` (`1 / width`, `1 / height`) so that the three have the size of the
/// length.
struct ArcLength<'a> {
    piece: &'a RelativePiece<'a>,
    scale: (f64, f64),
}

impl PieceIntegrand for ArcLength<'_> {
    fn add_node(&mut self, t: f64, weight: f64, sum: &mut [f64]) {
        let mut v = [0.0; 3];
        self.values(t, &mut v);
        for (s, v) in sum.iter_mut().zip(v) {
            *s += weight * v;
        }
    }

    fn values(&mut self, t: f64, out: &mut [f64]) -> f64 {
        let (u, v, dx, dy) = self.piece.point_and_derivatives(t);
        // No overflow: derivatives of coordinates within `MAX_COORDINATE`.
        let ds = (dx * dx + dy * dy).sqrt();
        out[0] = ds;
        out[1] = u * self.scale.0 * ds;
        out[2] = v * self.scale.1 * ds;
        ds
    }
}

/// Index of `b = int v dx` in the sums (and the `M` of its [`CellMoment`]).
const B: usize = 0;
/// Index of `mx = int u v dx`.
const MX: usize = 1;
/// Index of `my = int v^2 / 2 dx`.
const MY: usize = 2;
/// Index of `muu = int u^2 v dx`.
const MUU: usize = 3;
/// Index of `muv = int u v^2 / 2 dx`.
const MUV: usize = 4;
/// Index of `mvv = int v^3 / 3 dx`.
const MVV: usize = 5;

/// Integrand `M` of [`PartIntegrals`] ([`B`], [`MX`] or [`MY`]) at `(u, v)` with `x' = dx`,
/// and its rounding magnitude: the integrand with `u`, `v` replaced by the sizes `um`, `vm` of
/// the coordinates they are computed from, or the value if larger (`integrate_adaptive`'s
/// magnitude of a scalar integrand).
#[inline]
fn integrand<const M: usize>((u, v, dx): (f64, f64, f64), (um, vm): (f64, f64)) -> (f64, f64) {
    let (value, scale) = match M {
        B => (v * dx, vm * dx),
        MX => (u * v * dx, um * vm * dx),
        MY => (0.5 * v * v * dx, 0.5 * vm * vm * dx),
        MUU => (u * u * v * dx, um * um * vm * dx),
        MUV => (0.5 * u * v * v * dx, 0.5 * um * vm * vm * dx),
        _ => (v * v * v * dx / 3.0, vm * vm * vm * dx / 3.0),
    };
    (value, scale.abs().max(value.abs()))
}

/// The integrands of [`PartIntegrals`] all at once (those of `moments`): what the exact rule
/// sums, one evaluation of the piece per node.
struct CellMoments<'a> {
    local: &'a Local<'a>,
    moments: Moments,
}

impl PieceIntegrand for CellMoments<'_> {
    /// `f = weight x' v`, then `f`, `f u`, `f v / 2`: the moments share the weighted `b` term.
    fn add_node(&mut self, t: f64, weight: f64, sum: &mut [f64]) {
        let (u, v, dx) = self.local.eval(t);
        let f = weight * dx * v;
        sum[B] += f;
        if self.moments >= Moments::First {
            sum[MX] += f * u;
            sum[MY] += 0.5 * f * v;
        }
        if self.moments == Moments::Second {
            sum[MUU] += f * u * u;
            sum[MUV] += 0.5 * f * u * v;
            sum[MVV] += f * v * v / 3.0;
        }
    }

    fn values(&mut self, t: f64, out: &mut [f64]) -> f64 {
        let (at, sizes) = (self.local.eval(t), self.local.sizes());
        let (b, mut magnitude) = integrand::<B>(at, sizes);
        out[B] = b;
        if self.moments >= Moments::First {
            let (mx, mx_magnitude) = integrand::<MX>(at, sizes);
            let (my, my_magnitude) = integrand::<MY>(at, sizes);
            (out[MX], out[MY]) = (mx, my);
            magnitude = magnitude.max(mx_magnitude).max(my_magnitude);
        }
        if self.moments == Moments::Second {
            for (k, m) in [
                (MUU, integrand::<MUU>(at, sizes)),
                (MUV, integrand::<MUV>(at, sizes)),
                (MVV, integrand::<MVV>(at, sizes)),
            ] {
                out[k] = m.0;
                magnitude = magnitude.max(m.1);
            }
        }
        magnitude
    }
}

/// Integrand `M` of [`PartIntegrals`] alone: what the adaptive rule integrates, each integral
/// on its own (to its own tolerance).
struct CellMoment<'a, const M: usize> {
    local: &'a Local<'a>,
}

impl<const M: usize> CellMoment<'_, M> {
    /// Adds its integral over `range` to `sum` by the adaptive rule to `abs_tol`.
    fn integrate(local: &Local<'_>, range: (f64, f64), abs_tol: f64, sum: &mut f64) {
        let rule = PieceRule::Adaptive { abs_tol };
        let mut one = [*sum];
        integrate_piece(
            &mut CellMoment::<M> { local },
            range,
            rule,
            Jacobian::OnTheSum,
            &mut one,
        );
        *sum = one[0];
    }
}

impl<const M: usize> PieceIntegrand for CellMoment<'_, M> {
    fn add_node(&mut self, t: f64, weight: f64, sum: &mut [f64]) {
        let (value, _) = integrand::<M>(self.local.eval(t), self.local.sizes());
        sum[0] += weight * value;
    }

    fn values(&mut self, t: f64, out: &mut [f64]) -> f64 {
        let (value, magnitude) = integrand::<M>(self.local.eval(t), self.local.sizes());
        out[0] = value;
        magnitude
    }
}

/// A piece in a cell's local coordinates, `u = x - x_c`, `v = y - y_r`
/// ([`rs_boxes::BezierPiece::relative_to`] the cell's corner), so that the integrands are
/// computed in the cell's coordinates.
struct Local<'a> {
    piece: RelativePiece<'a>,
    /// The largest `|x_i - x_c|` and `|y_i - y_r|`: the size of the terms `u` and `v` are
    /// sums of (their rounding scale for the adaptive rule).
    sizes: (f64, f64),
}

impl<'a> Local<'a> {
    fn new(arc: &'a Arc, corner: Point) -> Self {
        let piece = arc.piece.piece().relative_to(corner);
        Self {
            sizes: piece.extent(),
            piece,
        }
    }

    /// `(u(t), v(t), x'(t))`: the local coordinates and the derivative of `x`
    /// ([`RelativePiece::point_and_x_derivative`]).
    #[inline]
    fn eval(&self, t: f64) -> (f64, f64, f64) {
        self.piece.point_and_x_derivative(t)
    }

    /// `(u_size, v_size)`.
    #[inline]
    fn sizes(&self) -> (f64, f64) {
        self.sizes
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_boxes::{BoxOptions, MonotoneBoxes};
    use rs_spline::prelude::*;
    use rs_spline::{Domain, circle, polyline};

    fn arcs(d: &Domain) -> Vec<Arc> {
        let boxes = MonotoneBoxes::new(d, BoxOptions::DEFAULT.with_subdivisions(1)).unwrap();
        boxes
            .pieces()
            .iter()
            .map(|p| Arc::new(p.clone(), 1.0))
            .collect()
    }

    /// Over a whole closed loop, `-sum b` relative to the origin is Green's area, and the
    /// moments are the loop's first moments (closed forms for a circle of radius 2 about
    /// (1, -0.5): area 4 pi, moments 4 pi * centre).
    #[test]
    fn whole_loop_integrals_are_the_area_and_moments() {
        let (cx, cy, r) = (1.0, -0.5, 2.0);
        let d = Domain::new(vec![circle(Point::new(cx, cy), r).unwrap()]).unwrap();
        let mut total = [0.0; 6];
        let mut arc_length = [0.0; 3];
        for a in arcs(&d) {
            let p = a.integrals(
                (0.0, 1.0),
                Point::new(0.0, 0.0),
                (1.0, 1.0),
                Moments::Second,
            );
            for (t, p) in total.iter_mut().zip(p) {
                *t += p;
            }
            let l = a.arc_length_integrals((0.0, 1.0), Point::new(0.0, 0.0), (1.0, 2.0));
            for (t, l) in arc_length.iter_mut().zip(l) {
                *t += l;
            }
        }
        let area = std::f64::consts::PI * r * r;
        let close = |got: f64, want: f64| (got - want).abs() < 1e-14 * area * (1.0 + want.abs());
        assert!(close(-total[B], area), "{total:?}");
        assert!(close(-total[MX], area * cx), "{total:?}");
        assert!(close(-total[MY], area * cy), "{total:?}");
        // int int x^2 dA = pi r^4 / 4 + A cx^2, int int x y dA = A cx cy, likewise y^2.
        let quarter = std::f64::consts::PI * r.powi(4) / 4.0;
        assert!(close(-total[MUU], quarter + area * cx * cx), "{total:?}");
        assert!(close(-total[MUV], area * cx * cy), "{total:?}");
        assert!(close(-total[MVV], quarter + area * cy * cy), "{total:?}");
        // The length 2 pi r, its first moments 2 pi r times the centre (the loop's sign is
        // not applied: the length is unsigned).
        let length = 2.0 * std::f64::consts::PI * r;
        let near = |got: f64, want: f64| (got - want).abs() < 1e-14 * length * 4.0;
        assert!(near(arc_length[0], length), "{arc_length:?}");
        assert!(near(arc_length[1], length * cx), "{arc_length:?}");
        assert!(near(arc_length[2], length * cy), "{arc_length:?}");
    }

    /// The Gauss-Legendre path is exact on polynomial pieces: a triangle's area and moments.
    #[test]
    fn polynomial_pieces_are_integrated_exactly() {
        let pts = [(0.0, 0.0), (3.0, 0.0), (0.0, 2.0), (0.0, 0.0)];
        let pts: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
        let d = Domain::new(vec![polyline(&pts).unwrap()]).unwrap();
        let corner = Point::new(0.5, 0.25);
        let mut total = [0.0; 6];
        for a in arcs(&d) {
            assert!(a.polynomial);
            let p = a.integrals((0.0, 1.0), corner, (1.0, 1.0), Moments::Second);
            for (t, p) in total.iter_mut().zip(p) {
                *t += p;
            }
        }
        // Area 3, centroid (1, 2/3); about the corner (0.5, 0.25) the second moments of the
        // triangle (0,0), (3,0), (0,2): int x^2 = 4.5, int x y = 1.5, int y^2 = 2.
        let (cx, cy) = (0.5, 0.25);
        assert!((-total[B] - 3.0).abs() < 1e-15);
        assert!((-total[MX] - 3.0 * (1.0 - cx)).abs() < 1e-15);
        assert!((-total[MY] - 3.0 * (2.0 / 3.0 - cy)).abs() < 1e-15);
        let uu = 4.5 - 2.0 * cx * 3.0 + cx * cx * 3.0;
        let uv = 1.5 - cx * 2.0 - cy * 3.0 + cx * cy * 3.0;
        let vv = 2.0 - 2.0 * cy * 2.0 + cy * cy * 3.0;
        assert!((-total[MUU] - uu).abs() < 1e-14, "{total:?}");
        assert!((-total[MUV] - uv).abs() < 1e-14, "{total:?}");
        assert!((-total[MVV] - vv).abs() < 1e-14, "{total:?}");
    }

    #[test]
    fn crossings_are_on_the_curve() {
        let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
        for a in arcs(&d) {
            let b = a.bezier();
            let band = a.piece.band;
            let y = 0.5 * (band.ymin + band.ymax);
            let (t, x) = a.at_y(y);
            assert!(b.point_at(t).distance(Point::new(x, y)) < 1e-15);
            let (t, _) = a.at_y(band.start.y);
            assert_eq!(t, 0.0);
            let x = 0.3 * band.xmin + 0.7 * band.xmax;
            let (t, y) = a.at_x(x);
            assert!(b.point_at(t).distance(Point::new(x, y)) < 1e-15);
        }
    }
}
