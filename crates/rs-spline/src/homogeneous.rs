//! Homogeneous (weighted) points `(w x, w y, w)` used by rational algorithms, and the quotient
//! rule that turns homogeneous derivatives into Cartesian ones.

use std::ops::{Add, Mul, Sub};

use crate::Point;

/// A point in homogeneous coordinates `(w x, w y, w)`: where a rational curve is polynomial, so
/// de Casteljau's algorithm ([`rs_roots::de_casteljau_split`]) subdivides it exactly as it does
/// a polynomial one.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Hpoint {
    /// `w x`.
    pub x: f64,
    /// `w y`.
    pub y: f64,
    /// The weight `w`.
    pub w: f64,
}

impl Hpoint {
    /// `(w p.x, w p.y, w)`.
    pub fn weighted(p: Point, w: f64) -> Self {
        Self {
            x: w * p.x,
            y: w * p.y,
            w,
        }
    }

    /// The homogeneous points of control points and their weights.
    pub(crate) fn weighted_all(points: &[Point], weights: &[f64]) -> Vec<Hpoint> {
        points
            .iter()
            .zip(weights)
            .map(|(&p, &w)| Hpoint::weighted(p, w))
            .collect()
    }

    /// The Cartesian points of homogeneous points.
    pub(crate) fn project_all(hp: &[Hpoint]) -> Vec<Point> {
        hp.iter().map(|h| h.project()).collect()
    }

    /// The Cartesian point `(x / w, y / w)`.
    pub fn project(self) -> Point {
        Point::new(self.x / self.w, self.y / self.w)
    }
}

impl Add for Hpoint {
    type Output = Hpoint;
    fn add(self, o: Hpoint) -> Hpoint {
        Hpoint {
            x: self.x + o.x,
            y: self.y + o.y,
            w: self.w + o.w,
        }
    }
}

impl Sub for Hpoint {
    type Output = Hpoint;
    fn sub(self, o: Hpoint) -> Hpoint {
        Hpoint {
            x: self.x - o.x,
            y: self.y - o.y,
            w: self.w - o.w,
        }
    }
}

impl Mul<f64> for Hpoint {
    type Output = Hpoint;
    fn mul(self, s: f64) -> Hpoint {
        Hpoint {
            x: self.x * s,
            y: self.y * s,
            w: self.w * s,
        }
    }
}

/// A curve point with its first and second parametric derivatives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveDerivatives {
    /// `C(u)`.
    pub point: Point,
    /// `C'(u)`.
    pub first: Point,
    /// `C''(u)`.
    pub second: Point,
}

/// Quotient rule for `C = A / w` from homogeneous derivatives `h = [A, A', A'']` (with the
/// weight in `.w`): `C' = (A' - w' C) / w`, `C'' = (A'' - 2 w' C' - w'' C) / w`.
pub(crate) fn rational_derivatives(h: [Hpoint; 3]) -> CurveDerivatives {
    let (point, first) = rational_point_and_tangent([h[0], h[1]]);
    let w = h[0].w;
    let second = (Point::new(h[2].x, h[2].y) - first * (2.0 * h[1].w) - point * h[2].w) / w;
    CurveDerivatives {
        point,
        first,
        second,
    }
}

/// The quotient rule's first two: `C = A / w` and `C' = (A' - w' C) / w` from `h = [A, A']`.
pub(crate) fn rational_point_and_tangent(h: [Hpoint; 2]) -> (Point, Point) {
    let w = h[0].w;
    let point = Point::new(h[0].x, h[0].y) / w;
    let first = (Point::new(h[1].x, h[1].y) - point * h[1].w) / w;
    (point, first)
}
