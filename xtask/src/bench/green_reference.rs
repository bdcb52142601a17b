//! Reference integrals of smooth functions over a domain, independent of `inrs::cubature`:
//! Green's theorem `integral f dA = oint F dy` with `F(x, y) = integral_{x0}^{x} f(s, y) ds`,
//! `x0` the bounding box's left side. The inner integral is composite Gauss-Legendre
//! ([`PANELS`] panels over the box's width, [`NODES`] nodes each); the outer one adaptive
//! Gauss-Legendre on every Bezier piece of the boundary (`rs_spline::quadrature`), each loop
//! multiplied by its even-odd boundary sign (filled side on the left).
//!
//! The test functions of the convergence table live here too, in coordinates scaled to the
//! bounding box.

use inrs::contain::{FillRule, curve_boundary_signs};
use inrs::prelude::*;
use inrs::spline::quadrature::{fixed_gauss_rule, integrate_adaptive};
use inrs::{BoundingBox, Domain, Point};

/// Inner panels per bounding-box width: a panel spans at most 1/16 of the width.
const PANELS: f64 = 16.0;
/// Gauss-Legendre nodes per inner panel.
const NODES: usize = 24;
/// The outer quadrature's absolute tolerance relative to `area of the box x max |f|`.
const RELATIVE_TOLERANCE: f64 = 1e-16;

/// A smooth test function on a domain's bounding box.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum TestFunction {
    /// `exp(x + y)` in the domain's own coordinates.
    Exp,
    /// Franke's function of `(u, v)`, the box mapped onto `[0, 1]^2`.
    Franke,
    /// `1 / (1 + 25 r^2)`, `r^2 = u^2 + v^2`, `(u, v)` the box mapped onto `[-1, 1]^2`.
    Runge,
}

impl TestFunction {
    /// All of them, in the table's order.
    pub(super) const ALL: [TestFunction; 3] =
        [TestFunction::Exp, TestFunction::Franke, TestFunction::Runge];

    /// The name in the table.
    pub(super) fn name(self) -> &'static str {
        match self {
            TestFunction::Exp => "exp(x + y)",
            TestFunction::Franke => "Franke",
            TestFunction::Runge => "1 / (1 + 25 r^2)",
        }
    }

    /// The function on the box `b`.
    pub(super) fn on(self, b: BoundingBox) -> impl Fn(Point) -> f64 + Copy {
        let (x0, y0, w, h) = (b.min.x, b.min.y, b.width(), b.height());
        move |p: Point| {
            let (u, v) = ((p.x - x0) / w, (p.y - y0) / h);
            match self {
                TestFunction::Exp => (p.x + p.y).exp(),
                TestFunction::Franke => franke(u, v),
                TestFunction::Runge => {
                    let (u, v) = (2.0 * u - 1.0, 2.0 * v - 1.0);
                    1.0 / (1.0 + 25.0 * (u * u + v * v))
                }
            }
        }
    }
}

/// Franke's test function on `[0, 1]^2` (R. Franke, *Scattered data interpolation: tests of
/// some methods*, Math. Comp. 38 (1982) 181-200).
fn franke(x: f64, y: f64) -> f64 {
    let (a, b) = (9.0 * x, 9.0 * y);
    0.75 * (-((a - 2.0).powi(2) + (b - 2.0).powi(2)) / 4.0).exp()
        + 0.75 * (-(a + 1.0).powi(2) / 49.0 - (b + 1.0) / 10.0).exp()
        + 0.5 * (-((a - 7.0).powi(2) + (b - 3.0).powi(2)) / 4.0).exp()
        - 0.2 * (-(a - 4.0).powi(2) - (b - 7.0).powi(2)).exp()
}

/// `integral f dA` over `d` (even-odd fill) by Green's theorem as the module says, with the
/// largest outer-quadrature error estimate; `Err` if the loops do not nest or an outer
/// quadrature does not converge. `f_max` bounds `|f|` on the box (it sets the tolerance).
pub(super) fn green_integral(
    d: &Domain,
    f: impl Fn(Point) -> f64,
    f_max: f64,
) -> Result<(f64, f64), String> {
    let b = d.bounding_box();
    let sign = curve_boundary_signs(d, FillRule::EvenOdd).map_err(|e| e.to_string())?;
    let (xs, ws) = {
        let rule = fixed_gauss_rule::<NODES>();
        (rule.nodes(), rule.weights())
    };
    let panel = b.width() / PANELS;
    // F(x, y) and the sum of |terms| (its rounding scale).
    let inner = |p: Point| -> (f64, f64) {
        let length = p.x - b.min.x;
        let panels = (length.abs() / panel).ceil().max(1.0);
        let step = length / panels;
        let (mut sum, mut size) = (0.0, 0.0);
        for k in 0..panels as usize {
            let lo = b.min.x + k as f64 * step;
            for (&x, &w) in xs.iter().zip(ws) {
                let v = f(Point::new(lo + 0.5 * (x + 1.0) * step, p.y)) * w * 0.5 * step;
                sum += v;
                size += v.abs();
            }
        }
        (sum, size)
    };
    let tolerance = RELATIVE_TOLERANCE * b.width() * b.height() * f_max;
    let (mut total, mut worst) = (0.0, 0.0f64);
    for (curve, piece) in d.bezier_pieces() {
        if sign[curve] == 0 {
            continue;
        }
        let got = integrate_adaptive(
            |t| {
                let (p, tangent) = piece.point_and_tangent(t);
                let (value, size) = inner(p);
                (value * tangent.y, size * tangent.y.abs())
            },
            0.0,
            1.0,
            tolerance,
        );
        if !got.converged {
            return Err(format!(
                "Green reference: the quadrature on curve {curve} did not converge (error {:.1e})",
                got.error
            ));
        }
        total += sign[curve] as f64 * got.value;
        worst = worst.max(got.error);
    }
    Ok((total, worst))
}

/// The largest `|f|` at a 101 x 101 grid over `b` (the test functions peak inside the box,
/// so this is within a few percent of the maximum; only the tolerance uses it).
pub(super) fn grid_max(b: BoundingBox, f: impl Fn(Point) -> f64) -> f64 {
    let mut m = 0.0f64;
    for j in 0..=100 {
        for i in 0..=100 {
            let p = Point::new(
                b.min.x + b.width() * i as f64 / 100.0,
                b.min.y + b.height() * j as f64 / 100.0,
            );
            m = m.max(f(p).abs());
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use inrs::cubature::monomial_moments;

    /// `I_1(z)` by its power series `sum_k (z / 2)^(2k + 1) / (k! (k + 1)!)`.
    fn bessel_i1(z: f64) -> f64 {
        let mut term = z / 2.0;
        let mut sum = term;
        for k in 1..40 {
            term *= (z / 2.0) * (z / 2.0) / (k as f64 * (k + 1) as f64);
            sum += term;
        }
        sum
    }

    #[test]
    fn exp_over_a_disc_with_a_hole_matches_its_closed_form() {
        // integral over the unit disc of exp(x + y) = 2 pi I_1(sqrt 2) / sqrt 2 (polar
        // coordinates: the angular integral is 2 pi I_0(sqrt 2 r)); the same over the disc of
        // radius 1/2 at the origin is subtracted for the hole, whichever way it runs.
        let disc = |r: f64| {
            let s = 2f64.sqrt() * r;
            2.0 * std::f64::consts::PI * r * bessel_i1(s) / 2f64.sqrt()
        };
        let c = |r: f64| inrs::spline::circle(Point::new(0.0, 0.0), r).unwrap();
        for hole in [c(0.5), c(0.5).reversed()] {
            let d = Domain::new(vec![c(1.0), hole]).unwrap();
            let f = |p: Point| (p.x + p.y).exp();
            let (got, _) = green_integral(&d, f, grid_max(d.bounding_box(), f)).unwrap();
            let want = disc(1.0) - disc(0.5);
            assert!((got - want).abs() < 2e-15 * want, "{got} vs {want}");
        }
    }

    #[test]
    fn polynomials_on_the_paper_domains_match_the_exact_moments() {
        // monomial_moments integrates x^a y^b exactly by another route (x^(a+1) / (a+1) in
        // closed form, Gauss-Legendre on polynomial pieces).
        for name in rs_testkit::PAPER_DOMAINS {
            let d = rs_testkit::inrs_fixture(name).domain;
            let m = monomial_moments(&d, 7, FillRule::EvenOdd).unwrap();
            // (a, b) = (3, 4): graded index 7 * 8 / 2 + 4.
            let f = |p: Point| p.x.powi(3) * p.y.powi(4);
            let (got, _) = green_integral(&d, f, grid_max(d.bounding_box(), f)).unwrap();
            let want = m[7 * 8 / 2 + 4];
            let scale = grid_max(d.bounding_box(), f) * m[0];
            assert!(
                (got - want).abs() < 1e-14 * scale,
                "{name}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn the_test_functions_are_what_they_say() {
        let b = BoundingBox::from_point(Point::new(-1.0, 2.0)).including(Point::new(3.0, 4.0));
        // Franke at (0, 0) of [0, 1]^2, the box's lower left corner.
        let f0 = 0.75 * (-2f64).exp()
            + 0.75 * (-1.0 / 49.0 - 0.1f64).exp()
            + 0.5 * (-58.0 / 4.0f64).exp()
            - 0.2 * (-65f64).exp();
        assert!((TestFunction::Franke.on(b)(Point::new(-1.0, 2.0)) - f0).abs() < 1e-15);
        // 1 / (1 + 25 r^2) is 1 at the box's centre and 1/51 at its corners.
        assert_eq!(TestFunction::Runge.on(b)(Point::new(1.0, 3.0)), 1.0);
        assert!((TestFunction::Runge.on(b)(Point::new(3.0, 4.0)) - 1.0 / 51.0).abs() < 1e-16);
        assert_eq!(TestFunction::Exp.on(b)(Point::new(1.0, -1.0)), 1.0);
    }
}
