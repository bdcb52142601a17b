//! Curves of any dimension in their native parameterisations: lines, conics, rational
//! B-splines and trimmed windows of them. A STEP pcurve is a `Curve<Point>`, an edge a
//! `Curve<Point3>`; both are evaluated, inverted and converted exactly by the same code.
//!
//! Parameterisations (ISO 10303-42; IGES 5.3 curves are converted to these when read):
//! - [`Curve::Line`]: `origin + t direction` (`direction` with its length: a STEP `VECTOR`'s
//!   orientation times its magnitude);
//! - [`Curve::Conic`]: `center + f(t) u + g(t) v`, `(f, g) = (cos t, sin t)` for ellipses and
//!   circles (`u`, `v` the semi-axes as vectors), `(cosh t, sinh t)` for hyperbolas, `(t^2, 2
//!   t)` for parabolas (`u = f x`, `v = f y` with the focal distance `f`);
//! - [`Curve::BSpline`]: its knots;
//! - [`Curve::Trimmed`]: its basis curve's parameter, restricted to `[t0, t1]`.

use rs_spline::{RationalBSpline, Vector};

/// The kind of a [`Conic`], which fixes its parameterisation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConicKind {
    /// `(cos t, sin t)`: ellipses and circles, period `2 pi`.
    Ellipse,
    /// `(cosh t, sinh t)`: one branch of a hyperbola.
    Hyperbola,
    /// `(t^2, 2 t)`: a parabola.
    Parabola,
}

/// A conic `center + f(t) u + g(t) v` (see the module documentation for `f`, `g`).
#[derive(Clone, Debug, PartialEq)]
pub struct Conic<P> {
    /// The kind.
    pub kind: ConicKind,
    /// The centre (the vertex of a parabola).
    pub center: P,
    /// The first axis vector (its length is the first semi-axis, or the focal distance).
    pub u: P,
    /// The second axis vector.
    pub v: P,
}

impl ConicKind {
    /// `(f, f', f'')` and `(g, g', g'')` at `t`.
    fn basis(self, t: f64) -> ([f64; 3], [f64; 3]) {
        match self {
            ConicKind::Ellipse => {
                let (s, c) = t.sin_cos();
                ([c, -s, -c], [s, c, -s])
            }
            ConicKind::Hyperbola => {
                let (s, c) = (t.sinh(), t.cosh());
                ([c, s, c], [s, c, s])
            }
            ConicKind::Parabola => ([t * t, 2.0 * t, 2.0], [2.0 * t, 2.0, 0.0]),
        }
    }
}

impl<P: Vector> Conic<P> {
    /// The point at `t`.
    pub fn point(&self, t: f64) -> P {
        self.derivatives(t)[0]
    }

    /// `[C(t), C'(t), C''(t)]`.
    pub fn derivatives(&self, t: f64) -> [P; 3] {
        let (f, g) = self.kind.basis(t);
        [
            self.center + self.u * f[0] + self.v * g[0],
            self.u * f[1] + self.v * g[1],
            self.u * f[2] + self.v * g[2],
        ]
    }
}

/// A curve in its native parameterisation (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub enum Curve<P> {
    /// `origin + t direction`, unbounded.
    Line {
        /// The point at `t = 0`.
        origin: P,
        /// The derivative (with its length).
        direction: P,
    },
    /// A conic, unbounded (periodic for ellipses).
    Conic(Conic<P>),
    /// A rational B-spline on its knot domain.
    BSpline(RationalBSpline<P>),
    /// The window `[t0, t1]` of a basis curve, in the basis curve's parameter.
    Trimmed {
        /// The basis curve.
        basis: Box<Curve<P>>,
        /// The window, `t0 < t1`.
        range: (f64, f64),
    },
}

impl<P: Vector + std::ops::Div<f64, Output = P>> Curve<P> {
    /// The point at `t` (a B-spline's parameter clamped to its domain).
    pub fn point(&self, t: f64) -> P {
        match self {
            Curve::Line { origin, direction } => *origin + *direction * t,
            Curve::Conic(c) => c.point(t),
            Curve::BSpline(b) => b.point_at(t),
            Curve::Trimmed { basis, .. } => basis.point(t),
        }
    }

    /// `[C(t), C'(t), C''(t)]`.
    pub fn derivatives(&self, t: f64) -> [P; 3] {
        match self {
            Curve::Line { origin, direction } => {
                [*origin + *direction * t, *direction, P::default()]
            }
            Curve::Conic(c) => c.derivatives(t),
            Curve::BSpline(b) => b.derivatives(t),
            Curve::Trimmed { basis, .. } => basis.derivatives(t),
        }
    }

    /// The parameter interval of a bounded curve (a B-spline's knot domain, a trimmed curve's
    /// window); `None` for lines and conics, whose parameter is unbounded.
    pub fn range(&self) -> Option<(f64, f64)> {
        match self {
            Curve::BSpline(b) => Some(b.param_range()),
            Curve::Trimmed { range, .. } => Some(*range),
            Curve::Line { .. } | Curve::Conic(_) => None,
        }
    }

    /// The period of a closed curve: `2 pi` for ellipses (and trimmed windows of them), the
    /// domain's length for a B-spline whose ends meet (within `1e-12` of its size).
    pub fn period(&self) -> Option<f64> {
        match self {
            Curve::Conic(Conic {
                kind: ConicKind::Ellipse,
                ..
            }) => Some(std::f64::consts::TAU),
            Curve::BSpline(b) => {
                let (a, e) = b.param_range();
                let size = b
                    .control_points()
                    .iter()
                    .map(|p| p.norm())
                    .fold(0.0, f64::max);
                (e > a && b.point_at(a).distance_to(b.point_at(e)) <= 1e-12 * size.max(1e-300))
                    .then_some(e - a)
            }
            Curve::Trimmed { basis, .. } => basis.period(),
            Curve::Line { .. } | Curve::Conic(_) => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use rs_spline::{Point, Point3};

    use super::*;

    #[test]
    fn conics_and_lines_evaluate_with_their_derivatives() {
        let e = Conic {
            kind: ConicKind::Ellipse,
            center: Point3::new(1.0, 0.0, 0.0),
            u: Point3::new(2.0, 0.0, 0.0),
            v: Point3::new(0.0, 1.0, 0.0),
        };
        let [p, d1, d2] = e.derivatives(0.5);
        let (s, c) = 0.5f64.sin_cos();
        assert!(p.distance(Point3::new(1.0 + 2.0 * c, s, 0.0)) < 1e-15);
        assert!(d1.distance(Point3::new(-2.0 * s, c, 0.0)) < 1e-15);
        assert!(d2.distance(Point3::new(-2.0 * c, -s, 0.0)) < 1e-15);
        let curve = Curve::Conic(e);
        assert_eq!(curve.period(), Some(std::f64::consts::TAU));
        assert_eq!(curve.range(), None);
        let line = Curve::Line {
            origin: Point::new(1.0, 2.0),
            direction: Point::new(0.0, 3.0),
        };
        assert_eq!(line.point(2.0), Point::new(1.0, 8.0));
        let trimmed = Curve::Trimmed {
            basis: Box::new(line),
            range: (0.0, 1.0),
        };
        assert_eq!(trimmed.range(), Some((0.0, 1.0)));
        assert_eq!(trimmed.derivatives(0.5)[1], Point::new(0.0, 3.0));
        let h = Conic {
            kind: ConicKind::Hyperbola,
            center: Point::new(0.0, 0.0),
            u: Point::new(1.0, 0.0),
            v: Point::new(0.0, 1.0),
        };
        let q = h.point(0.7);
        assert!((q.x * q.x - q.y * q.y - 1.0).abs() < 1e-14);
        let par = Conic {
            kind: ConicKind::Parabola,
            center: Point::new(0.0, 0.0),
            u: Point::new(0.5, 0.0),
            v: Point::new(0.0, 0.5),
        };
        let q = par.point(-1.5);
        // y^2 = 4 f x with f = 1/2.
        assert!((q.y * q.y - 2.0 * q.x).abs() < 1e-14);
    }
}
