//! Conic arcs given implicitly, `A x^2 + B x y + C y^2 + D x + E y + F = 0`, from a start to an
//! end point (IGES 104): the conic in its parameterisation and the arc's parameter interval, so
//! the arc converts by [`Conic::to_bspline`] as every other conic does.

use std::f64::consts::TAU;

use rs_spline::Point;

use super::{Conic, ConicKind};
use crate::GeomError;

/// A discriminant `B^2 - 4 A C` within this fraction of `max(B^2, |4 A C|)` is zero: the
/// coefficients of a parabola written with a dozen significant digits.
const PARABOLA_RELATIVE_DISCRIMINANT: f64 = 1e-12;

/// The symmetric bilinear form of the conic, `q(p, r)` for the homogeneous points `(p, 1)`,
/// `(r, 1)`: `q(p, p)` is the conic's value at `p`.
fn form(c: &[f64; 6], p: Point, r: Point) -> f64 {
    let [a, b, cc, d, e, f] = *c;
    a * p.x * r.x
        + 0.5 * b * (p.x * r.y + p.y * r.x)
        + cc * p.y * r.y
        + 0.5 * d * (p.x + r.x)
        + 0.5 * e * (p.y + r.y)
        + f
}

/// The kind the coefficients give, by the sign of the discriminant `B^2 - 4 A C` (zero within
/// [`PARABOLA_RELATIVE_DISCRIMINANT`]: a parabola).
pub(crate) fn implicit_kind(c: &[f64; 6]) -> ConicKind {
    let [a, b, cc, ..] = *c;
    let disc = b * b - 4.0 * a * cc;
    let size = (b * b).max((4.0 * a * cc).abs());
    if disc.abs() <= PARABOLA_RELATIVE_DISCRIMINANT * size {
        ConicKind::Parabola
    } else if disc < 0.0 {
        ConicKind::Ellipse
    } else {
        ConicKind::Hyperbola
    }
}

impl Conic<Point> {
    /// The conic with the implicit equation `A x^2 + B x y + C y^2 + D x + E y + F = 0`
    /// (`coefficients = [A, B, C, D, E, F]`) and the parameter interval `[t0, t1]` (`t0 < t1`)
    /// of its arc from `start` to `end`, as IGES 104 defines conic arcs:
    ///
    /// - ellipse: centre where the gradient vanishes, axes from the rotation by
    ///   `theta = atan2(B, A - C) / 2` that removes the `x y` term (`u` along the first
    ///   rotated axis, `v` at a quarter turn counter-clockwise from it); the arc runs
    ///   counter-clockwise from `start` to `end`, the whole ellipse when they are equal;
    /// - hyperbola: the same centre and rotation; `u` along the transverse axis towards the
    ///   branch holding both ends, `v` along the conjugate axis oriented so that the parameter
    ///   grows from `start` to `end`;
    /// - parabola: `center` the vertex, `u = f a` along the axis towards the opening, `v = f n`
    ///   across it (oriented so the parameter grows from `start` to `end`), `f` the focal
    ///   distance.
    ///
    /// The ends' parameters are their closed-form ones ([`Conic::parameter_of`]): an end a
    /// little off the conic is taken where its coordinates along the axes say.
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] for non-finite coefficients or points;
    /// [`GeomError::ConicKindMismatch`] when the discriminant says another kind than `kind`;
    /// [`GeomError::NoRealConic`] for coefficients with no real curve of the kind (an
    /// imaginary ellipse, a point, lines); [`GeomError::ClosedOpenConicArc`] for a hyperbola or
    /// parabola arc from a point to itself; [`GeomError::EndsOnDifferentBranches`].
    ///
    /// # Examples
    ///
    /// ```
    /// use rs_geom::{Conic, ConicKind, Point};
    /// // x^2 / 4 + y^2 = 1 from (2, 0) to (0, 1): a quarter, counter-clockwise.
    /// let (e, (t0, t1)) = Conic::from_implicit(
    ///     [0.25, 0.0, 1.0, 0.0, 0.0, -1.0],
    ///     ConicKind::Ellipse,
    ///     Point::new(2.0, 0.0),
    ///     Point::new(0.0, 1.0),
    /// )
    /// .unwrap();
    /// assert!((t1 - t0 - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    /// assert!(e.point(t1).distance(Point::new(0.0, 1.0)) < 1e-15);
    /// ```
    pub fn from_implicit(
        coefficients: [f64; 6],
        kind: ConicKind,
        start: Point,
        end: Point,
    ) -> Result<(Conic<Point>, (f64, f64)), GeomError> {
        if let Some(&value) = coefficients.iter().find(|x| !x.is_finite()) {
            return Err(GeomError::NotFinite {
                what: "conic coefficient",
                value,
            });
        }
        for p in [start, end] {
            if !p.is_finite() {
                return Err(GeomError::NotFinite {
                    what: "conic arc end",
                    value: if p.x.is_finite() { p.y } else { p.x },
                });
            }
        }
        let found = implicit_kind(&coefficients);
        if found != kind {
            return Err(GeomError::ConicKindMismatch {
                found,
                expected: kind,
            });
        }
        if kind != ConicKind::Ellipse && start == end {
            return Err(GeomError::ClosedOpenConicArc(kind));
        }
        match kind {
            ConicKind::Ellipse => ellipse(&central(&coefficients), start, end),
            ConicKind::Hyperbola => hyperbola(&central(&coefficients), start, end),
            ConicKind::Parabola => parabola(&coefficients, start, end),
        }
    }
}

/// A central conic (ellipse or hyperbola) in its own axes: `x'^2 / rx2 + y'^2 / ry2 = 1` in
/// the coordinates `x' = (p - centre) . e1`, `y' = (p - centre) . e2`.
#[derive(Clone, Copy)]
struct Central {
    /// Where the gradient vanishes.
    centre: Point,
    /// The unit axes `(cos, sin)`, `(-sin, cos)` of `theta = atan2(B, A - C) / 2`.
    e1: Point,
    e2: Point,
    /// The squared semi-axes `-f0 / a1`, `-f0 / c1`, from the conic's value `f0` at the centre
    /// and the quadratic form's values `a1`, `c1` along the axes (negative along a
    /// hyperbola's conjugate axis).
    rx2: f64,
    ry2: f64,
}

/// The conic `c` about its centre and axes.
fn central(c: &[f64; 6]) -> Central {
    let [a, b, cc, d, e, _] = *c;
    let det = 4.0 * a * cc - b * b;
    let centre = Point::new((b * e - 2.0 * cc * d) / det, (b * d - 2.0 * a * e) / det);
    let f0 = form(c, centre, centre);
    let theta = 0.5 * b.atan2(a - cc);
    let (s, co) = theta.sin_cos();
    let a1 = a * co * co + b * co * s + cc * s * s;
    let c1 = a * s * s - b * co * s + cc * co * co;
    Central {
        centre,
        e1: Point::new(co, s),
        e2: Point::new(-s, co),
        rx2: -f0 / a1,
        ry2: -f0 / c1,
    }
}

fn ellipse(k: &Central, start: Point, end: Point) -> Result<(Conic<Point>, (f64, f64)), GeomError> {
    let (centre, e1, e2) = (k.centre, k.e1, k.e2);
    let (rx2, ry2) = (k.rx2, k.ry2);
    if !(rx2 > 0.0 && ry2 > 0.0 && rx2.is_finite() && ry2.is_finite()) {
        return Err(GeomError::NoRealConic(ConicKind::Ellipse));
    }
    let (rx, ry) = (rx2.sqrt(), ry2.sqrt());
    let conic = Conic {
        kind: ConicKind::Ellipse,
        center: centre,
        u: e1 * rx,
        v: e2 * ry,
    };
    let t0 = conic.parameter_of(start);
    let sweep = if start == end {
        TAU
    } else {
        (conic.parameter_of(end) - t0).rem_euclid(TAU)
    };
    let sweep = if sweep > 0.0 { sweep } else { TAU };
    Ok((conic, (t0, t0 + sweep)))
}

fn hyperbola(
    k: &Central,
    start: Point,
    end: Point,
) -> Result<(Conic<Point>, (f64, f64)), GeomError> {
    let (centre, e1, e2) = (k.centre, k.e1, k.e2);
    let (rx2, ry2) = (k.rx2, k.ry2);
    // x'^2 / rx2 + y'^2 / ry2 = 1 with one of rx2, ry2 negative; the positive one is the
    // transverse axis.
    let (transverse, conjugate, ra2, rb2) = if rx2 > 0.0 {
        (e1, e2, rx2, -ry2)
    } else {
        (e2, e1, ry2, -rx2)
    };
    if !(ra2 > 0.0 && rb2 > 0.0 && ra2.is_finite() && rb2.is_finite()) {
        return Err(GeomError::NoRealConic(ConicKind::Hyperbola));
    }
    let (ra, rb) = (ra2.sqrt(), rb2.sqrt());
    let side = |p: Point| (p - centre).dot(transverse);
    let (s0, s1) = (side(start), side(end));
    if (s0 * s1).is_nan() || s0 * s1 <= 0.0 {
        return Err(GeomError::EndsOnDifferentBranches);
    }
    let branch = if s0 > 0.0 { 1.0 } else { -1.0 };
    let conic = Conic {
        kind: ConicKind::Hyperbola,
        center: centre,
        u: transverse * (branch * ra),
        v: conjugate * rb,
    };
    oriented(conic, start, end)
}

fn parabola(
    c: &[f64; 6],
    start: Point,
    end: Point,
) -> Result<(Conic<Point>, (f64, f64)), GeomError> {
    let [a, b, cc, d, e, f] = *c;
    let theta = 0.5 * b.atan2(a - cc);
    let (s, co) = theta.sin_cos();
    let a1 = a * co * co + b * co * s + cc * s * s;
    let c1 = a * s * s - b * co * s + cc * co * co;
    // The axis is the eigenvector of the quadratic part with the (nearly) zero eigenvalue;
    // across it the form is lambda r^2 with lambda = A + C, its trace.
    let (axis, across) = if a1.abs() < c1.abs() {
        (Point::new(co, s), Point::new(-s, co))
    } else {
        (Point::new(-s, co), Point::new(co, s))
    };
    let lambda = a + cc;
    // With p = s axis + r across: lambda r^2 + ea s + en r + F = 0, so
    // s - s0 = -(lambda / ea) (r - r0)^2 about the vertex (s0, r0).
    let (ea, en) = (d * axis.x + e * axis.y, d * across.x + e * across.y);
    let r0 = -en / (2.0 * lambda);
    let s0 = -(lambda * r0 * r0 + en * r0 + f) / ea;
    let kappa = -lambda / ea;
    // y^2 = 4 f x with x = |s - s0|, y = r - r0: f = 1 / (4 |kappa|).
    let focal = 0.25 / kappa.abs();
    let vertex = axis * s0 + across * r0;
    if !(focal > 0.0 && focal.is_finite() && vertex.is_finite()) {
        return Err(GeomError::NoRealConic(ConicKind::Parabola));
    }
    let opening = if kappa > 0.0 { axis } else { axis * -1.0 };
    let conic = Conic {
        kind: ConicKind::Parabola,
        center: vertex,
        u: opening * focal,
        v: across * focal,
    };
    oriented(conic, start, end)
}

/// The conic with `v` turned so that its parameter grows from `start` to `end`, and that
/// interval.
fn oriented(
    mut conic: Conic<Point>,
    start: Point,
    end: Point,
) -> Result<(Conic<Point>, (f64, f64)), GeomError> {
    let (t0, t1) = (conic.parameter_of(start), conic.parameter_of(end));
    if t0 > t1 {
        conic.v = conic.v * -1.0;
        return Ok((
            conic.clone(),
            (conic.parameter_of(start), conic.parameter_of(end)),
        ));
    }
    if t0 < t1 {
        Ok((conic, (t0, t1)))
    } else {
        Err(GeomError::ClosedOpenConicArc(conic.kind))
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;
    use crate::curve::testing::Rng;

    /// A conic given by a frame (centre, unit axis `a`, `n` a quarter turn from it), sizes and
    /// the kind: its implicit coefficients (times `scale`), its points by the construction's
    /// parameter `s`, and the relative residual of a point in the frame's equation.
    struct Truth {
        kind: ConicKind,
        centre: Point,
        a: Point,
        n: Point,
        r1: f64,
        r2: f64,
        /// The branch of a hyperbola (+1, -1).
        branch: f64,
    }

    impl Truth {
        fn random(rng: &mut Rng, kind: ConicKind) -> Self {
            let tilt = rng.uniform(-PI, PI);
            let (s, c) = tilt.sin_cos();
            Truth {
                kind,
                centre: rng.point(10.0),
                a: Point::new(c, s),
                n: Point::new(-s, c),
                r1: rng.uniform(0.3, 4.0),
                r2: rng.uniform(0.3, 4.0),
                branch: if rng.next_f64() < 0.5 { 1.0 } else { -1.0 },
            }
        }

        fn local(&self, p: Point) -> (f64, f64) {
            let d = p - self.centre;
            (d.dot(self.a), d.dot(self.n))
        }

        /// `x^2 / r1^2 + y^2 / r2^2 = 1`, `x^2 / r1^2 - y^2 / r2^2 = 1`, `y^2 = 4 r1 x`, as
        /// `[A, B, C, D, E, F]` times `scale`.
        fn coefficients(&self, scale: f64) -> [f64; 6] {
            let (a, n, c) = (self.a, self.n, self.centre);
            // q(x, y) = alpha x'^2 + beta y'^2 + gamma x' + delta with x' = a . (p - c),
            // y' = n . (p - c).
            let (alpha, beta, gamma, delta) = match self.kind {
                ConicKind::Ellipse => (
                    1.0 / (self.r1 * self.r1),
                    1.0 / (self.r2 * self.r2),
                    0.0,
                    -1.0,
                ),
                ConicKind::Hyperbola => (
                    1.0 / (self.r1 * self.r1),
                    -1.0 / (self.r2 * self.r2),
                    0.0,
                    -1.0,
                ),
                ConicKind::Parabola => (0.0, 1.0, -4.0 * self.r1, 0.0),
            };
            let (ac, nc) = (a.dot(c), n.dot(c));
            let q = [
                alpha * a.x * a.x + beta * n.x * n.x,
                2.0 * (alpha * a.x * a.y + beta * n.x * n.y),
                alpha * a.y * a.y + beta * n.y * n.y,
                -2.0 * alpha * ac * a.x - 2.0 * beta * nc * n.x + gamma * a.x,
                -2.0 * alpha * ac * a.y - 2.0 * beta * nc * n.y + gamma * a.y,
                alpha * ac * ac + beta * nc * nc - gamma * ac + delta,
            ];
            q.map(|x| x * scale)
        }

        fn point(&self, s: f64) -> Point {
            let (x, y) = match self.kind {
                ConicKind::Ellipse => (self.r1 * s.cos(), self.r2 * s.sin()),
                ConicKind::Hyperbola => (self.branch * self.r1 * s.cosh(), self.r2 * s.sinh()),
                ConicKind::Parabola => (self.r1 * s * s, 2.0 * self.r1 * s),
            };
            self.centre + self.a * x + self.n * y
        }

        fn residual(&self, p: Point) -> f64 {
            let (x, y) = self.local(p);
            let (x, y) = (x / self.r1, y / self.r2);
            match self.kind {
                ConicKind::Ellipse => (x * x + y * y - 1.0).abs(),
                ConicKind::Hyperbola => (x * x - y * y - 1.0).abs() / (x * x + y * y),
                ConicKind::Parabola => {
                    let (x, y) = self.local(p);
                    (y * y - 4.0 * self.r1 * x).abs()
                        / (self.r1 * self.r1 + y * y + (4.0 * self.r1 * x).abs())
                }
            }
        }
    }

    const KINDS: [ConicKind; 3] = [
        ConicKind::Ellipse,
        ConicKind::Hyperbola,
        ConicKind::Parabola,
    ];

    /// Random conics in any position, their coefficients scaled by a random factor of either
    /// sign, random arcs: every point of the converted arc satisfies the conic's equation, the
    /// arc starts and ends at the given points and runs the right way (counter-clockwise on
    /// ellipses, along the branch between the ends otherwise).
    #[test]
    fn arcs_from_coefficients_lie_on_the_conic_between_their_ends() {
        let mut rng = Rng::new(2024);
        for case in 0..600 {
            let kind = KINDS[case % 3];
            let truth = Truth::random(&mut rng, kind);
            let scale = rng.uniform(0.1, 10.0) * if case % 2 == 0 { 1.0 } else { -1.0 };
            let coefficients = truth.coefficients(scale);
            let (s0, s1) = match kind {
                ConicKind::Ellipse => (rng.uniform(-PI, PI), rng.uniform(-PI, PI)),
                _ => (rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5)),
            };
            let (start, end) = (truth.point(s0), truth.point(s1));
            let (conic, (t0, t1)) = Conic::from_implicit(coefficients, kind, start, end).unwrap();
            assert!(t0 < t1);
            let size = 1.0 + truth.centre.length() + truth.r1 + truth.r2;
            assert!(
                conic.point(t0).distance(start) < 1e-12 * size,
                "{kind} {case}"
            );
            assert!(
                conic.point(t1).distance(end) < 1e-12 * size,
                "{kind} {case}"
            );
            let want_length = match kind {
                ConicKind::Ellipse => (s1 - s0).rem_euclid(TAU),
                _ => (s1 - s0).abs(),
            };
            assert!((t1 - t0 - want_length).abs() < 1e-9, "{kind} {case}");
            // The middle of the arc is the construction's point half way.
            let mid = match kind {
                ConicKind::Ellipse => s0 + 0.5 * want_length,
                _ => 0.5 * (s0 + s1),
            };
            assert!(conic.point(0.5 * (t0 + t1)).distance(truth.point(mid)) < 1e-9 * size);
            let arc = conic.to_bspline(t0, t1).unwrap();
            let (a, b) = arc.param_range();
            for i in 0..=100 {
                let p = arc.point_at(a + (b - a) * f64::from(i) / 100.0);
                assert!(
                    truth.residual(p) < 1e-11,
                    "{kind} {case} {}",
                    truth.residual(p)
                );
                let f = form(&coefficients, p, p);
                let [ca, cb, cc, cd, ce, _] = coefficients;
                let grad = Point::new(
                    2.0 * ca * p.x + cb * p.y + cd,
                    cb * p.x + 2.0 * cc * p.y + ce,
                );
                assert!(f.abs() / grad.length() < 1e-11 * size, "{kind} {case}");
                if kind == ConicKind::Hyperbola {
                    assert!(truth.local(p).0 * truth.branch > 0.0);
                }
            }
            assert!(arc.point_at(a).distance(start) < 1e-12 * size);
            assert!(arc.point_at(b).distance(end) < 1e-12 * size);
        }
    }

    /// The cases of the IGES reader's tests: a rotated ellipse both ways round and whole, a
    /// hyperbola with ends on one branch and on two, a parabola, a wrong form.
    #[test]
    fn reader_cases_and_errors() {
        let truth = Truth {
            kind: ConicKind::Ellipse,
            centre: Point::new(1.0, 2.0),
            a: Point::new(0.3f64.cos(), 0.3f64.sin()),
            n: Point::new(-(0.3f64.sin()), 0.3f64.cos()),
            r1: 3.0,
            r2: 2.0,
            branch: 1.0,
        };
        let q = truth.coefficients(1.0);
        let (e, (t0, t1)) =
            Conic::from_implicit(q, ConicKind::Ellipse, truth.point(0.5), truth.point(2.0))
                .unwrap();
        assert!((t1 - t0 - 1.5).abs() < 1e-12);
        assert!(e.point(0.5 * (t0 + t1)).distance(truth.point(1.25)) < 1e-12);
        let (e, (t0, t1)) =
            Conic::from_implicit(q, ConicKind::Ellipse, truth.point(2.0), truth.point(0.5))
                .unwrap();
        assert!((t1 - t0 - (TAU - 1.5)).abs() < 1e-12);
        assert!(e.point(0.5 * (t0 + t1)).distance(truth.point(1.25 + PI)) < 1e-12);
        let (e, (t0, t1)) =
            Conic::from_implicit(q, ConicKind::Ellipse, truth.point(1.0), truth.point(1.0))
                .unwrap();
        assert_eq!(t1 - t0, TAU);
        assert_eq!(e.to_bspline(t0, t1).unwrap().control_points().len(), 9);

        // x^2/4 - y^2 = 1, right branch (2 cosh t, sinh t).
        let h = [0.25, 0.0, -1.0, 0.0, 0.0, -1.0];
        let pt = |t: f64| Point::new(2.0 * t.cosh(), t.sinh());
        let (c, (t0, t1)) =
            Conic::from_implicit(h, ConicKind::Hyperbola, pt(1.5), pt(-1.0)).unwrap();
        assert!(c.point(t0).distance(pt(1.5)) < 1e-14 && (t1 - t0 - 2.5).abs() < 1e-14);
        assert!(matches!(
            Conic::from_implicit(h, ConicKind::Hyperbola, pt(0.5), Point::new(-2.0, 0.0)),
            Err(GeomError::EndsOnDifferentBranches)
        ));
        assert!(matches!(
            Conic::from_implicit(h, ConicKind::Hyperbola, pt(0.5), pt(0.5)),
            Err(GeomError::ClosedOpenConicArc(ConicKind::Hyperbola))
        ));
        // x^2 - y - 1 = 0 from (-1, 0) to (2, 3).
        let p = [1.0, 0.0, 0.0, 0.0, -1.0, -1.0];
        let (c, (t0, t1)) = Conic::from_implicit(
            p,
            ConicKind::Parabola,
            Point::new(-1.0, 0.0),
            Point::new(2.0, 3.0),
        )
        .unwrap();
        assert!(c.point(t0).distance(Point::new(-1.0, 0.0)) < 1e-14);
        assert!(c.point(t1).distance(Point::new(2.0, 3.0)) < 1e-14);
        assert!(
            c.center.distance(Point::new(0.0, -1.0)) < 1e-15 && (c.u.length() - 0.25).abs() < 1e-15
        );
        assert!(matches!(
            Conic::from_implicit(
                p,
                ConicKind::Ellipse,
                Point::new(-1.0, 0.0),
                Point::new(2.0, 3.0)
            ),
            Err(GeomError::ConicKindMismatch {
                found: ConicKind::Parabola,
                expected: ConicKind::Ellipse
            })
        ));
        // No real curve: x^2 + y^2 + 1 = 0; x^2 - y^2 = 0 (two lines); x^2 - 1 = 0 (two lines).
        let o = Point::new(1.0, 0.0);
        let cases = [
            ([1.0, 0.0, 1.0, 0.0, 0.0, 1.0], ConicKind::Ellipse),
            ([1.0, 0.0, -1.0, 0.0, 0.0, 0.0], ConicKind::Hyperbola),
            ([1.0, 0.0, 0.0, 0.0, 0.0, -1.0], ConicKind::Parabola),
        ];
        for (q, kind) in cases {
            assert!(matches!(
                Conic::from_implicit(q, kind, o, Point::new(1.0, 1.0)),
                Err(GeomError::NoRealConic(k)) if k == kind
            ));
        }
        assert!(matches!(
            Conic::from_implicit(
                [f64::NAN, 0.0, 1.0, 0.0, 0.0, -1.0],
                ConicKind::Ellipse,
                o,
                o
            ),
            Err(GeomError::NotFinite { .. })
        ));
        assert!(matches!(
            Conic::from_implicit(q, ConicKind::Ellipse, Point::new(f64::INFINITY, 0.0), o),
            Err(GeomError::NotFinite { .. })
        ));
    }
}
