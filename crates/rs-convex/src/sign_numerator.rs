//! The numerator of the signed curvature (plane) or torsion (space) of a NURBS as an exact
//! piecewise Bernstein polynomial whose coefficients are affine in one free control point.
//!
//! For a curve `F(d; t) = d N(t) + s(t)` with free control point `d` (Ginnis, Karousos and
//! Kaklis 2009, formulas (1)-(7)), the sign of the curvature is the sign of
//! `h_t(x, y) = F1' F2'' - F1'' F2' = a1(t) x + a2(t) y + b(t)` and the sign of the torsion
//! that of `H_t(x, y, z) = [F', F'', F'''] = a1 x + a2 y + a3 z + b`.
//!
//! For a rational curve we use the homogeneous form, which is polynomial on every Bezier
//! piece and has the same sign: with `P = (w x, w y, w)` (columns `X, Y, W`),
//! `det[P; P'; P''] = W^3 (C' x C'')`, and in space `-det[P; P'; P''; P'''] = W^4 [C', C'', C''']`
//! (`P = (w x, w y, w z, w)`). Both are multilinear in the rows, and two rows proportional to the
//! free point's homogeneous vector cancel, so they are affine in `d`: the coefficients follow
//! exactly from the numerator at `d = 0` and at the unit vectors. For polynomial curves (all
//! weights equal) the Cartesian forms above are used directly (degree `2p - 3` in the plane and
//! `3p - 6` in space, as in the paper's tables).
//!
//! Each Bezier piece is in its own local parameter `s` in `[0, 1]`; this multiplies the
//! numerator by a positive constant per piece, which changes no sign.

use rs_roots::Bernstein;

use rs_spline::{NurbsCurve, Point, RationalBezier, SplineError};

use crate::{Point3, SpaceCurve};

/// One coefficient of the numerator: the affine function `a . d + b` of the free control point
/// (`a.z = 0` in the plane).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AffineForm {
    /// The linear part `(a1, a2, a3)`.
    pub a: Point3,
    /// The constant part.
    pub b: f64,
}

impl AffineForm {
    /// `a . d + b`.
    pub fn eval(&self, d: Point3) -> f64 {
        self.a.dot(d) + self.b
    }

    /// `-(a . d + b)`.
    pub fn negated(&self) -> Self {
        Self {
            a: self.a * -1.0,
            b: -self.b,
        }
    }
}

/// The curvature or torsion numerator of a curve with one free control point, piece by piece
/// in the Bernstein basis, each coefficient affine in the free point.
#[derive(Clone, Debug, PartialEq)]
pub struct SignNumerator {
    dimension: usize,
    /// Per piece: the Bernstein polynomials `a1, a2, a3, b` (all of one degree).
    pieces: Vec<[Bernstein; 4]>,
}

impl SignNumerator {
    /// The curvature numerator `h_t(x, y)` of a planar NURBS whose control point `free` moves.
    ///
    /// # Errors
    /// [`SplineError::ControlPointIndex`] if `free` is out of range.
    ///
    /// # Examples
    ///
    /// ```
    /// use rs_convex::SignNumerator;
    /// use rs_spline::{NurbsCurve, Point};
    /// // Quadratic Bezier (0,0), d, (2,0): h = 4 (d - P0) x (P2 - d) = -8 y, for every t.
    /// let c = NurbsCurve::bezier(vec![Point::new(0.0, 0.0), Point::new(1.0, 1.0), Point::new(2.0, 0.0)], None).unwrap();
    /// let h = SignNumerator::curvature(&c, 1).unwrap();
    /// for f in h.inequalities() {
    ///     assert!((f.a[0]).abs() < 1e-12 && (f.a[1] + 8.0).abs() < 1e-12 && f.b.abs() < 1e-12);
    /// }
    /// ```
    pub fn curvature(curve: &NurbsCurve, free: usize) -> Result<Self, SplineError> {
        let polynomial = all_equal(curve.weights());
        let at = |d: Point| -> Result<Vec<Bernstein>, SplineError> {
            let moved = curve.with_control_point(free, d)?;
            Ok(moved
                .to_bezier()
                .iter()
                .map(|b| planar_numerator(b, polynomial))
                .collect())
        };
        let h0 = at(Point::new(0.0, 0.0))?;
        let hx = at(Point::new(1.0, 0.0))?;
        let hy = at(Point::new(0.0, 1.0))?;
        let pieces = h0
            .into_iter()
            .zip(hx)
            .zip(hy)
            .map(|((b, x), y)| {
                let zero = b.scale(0.0);
                [x.add(&b.scale(-1.0)), y.add(&b.scale(-1.0)), zero, b]
            })
            .collect();
        Ok(Self {
            dimension: 2,
            pieces,
        })
    }

    /// The torsion numerator `H_t(x, y, z)` of a space NURBS whose control point `free` moves.
    ///
    /// # Errors
    /// [`SplineError::ControlPointIndex`] if `free` is out of range.
    pub fn torsion(curve: &SpaceCurve, free: usize) -> Result<Self, SplineError> {
        let polynomial = all_equal(curve.weights());
        let at = |d: Point3| -> Result<Vec<Bernstein>, SplineError> {
            let moved = curve.with_control_point(free, d)?;
            let xy = moved.xy().to_bezier();
            let z = moved.z().to_bezier();
            Ok(xy
                .iter()
                .zip(&z)
                .map(|(a, b)| spatial_numerator(a, b, polynomial))
                .collect())
        };
        let h0 = at(Point3::default())?;
        let hx = at(Point3::new(1.0, 0.0, 0.0))?;
        let hy = at(Point3::new(0.0, 1.0, 0.0))?;
        let hz = at(Point3::new(0.0, 0.0, 1.0))?;
        let pieces = h0
            .into_iter()
            .zip(hx)
            .zip(hy)
            .zip(hz)
            .map(|(((b, x), y), z)| {
                let minus = b.scale(-1.0);
                [x.add(&minus), y.add(&minus), z.add(&minus), b]
            })
            .collect();
        Ok(Self {
            dimension: 3,
            pieces,
        })
    }

    /// 2 for curvature, 3 for torsion.
    pub fn dimension(&self) -> usize {
        self.dimension
    }

    /// Number of Bernstein pieces.
    pub fn piece_count(&self) -> usize {
        self.pieces.len()
    }

    /// Degree of the numerator on each piece.
    pub fn degree(&self) -> usize {
        self.pieces.first().map_or(0, |p| p[3].degree())
    }

    /// The numerator after `level` rounds of simultaneous midpoint knot insertion: every piece
    /// split at its midpoint `level` times (de Casteljau subdivision, exact), giving
    /// `2^level` times as many pieces and coefficients.
    pub fn refined(&self, level: u32) -> Self {
        let mut pieces = self.pieces.clone();
        for _ in 0..level {
            pieces = pieces
                .iter()
                .flat_map(|p| {
                    let halves = p.clone().map(|b| b.split(0.5));
                    let left = halves.clone().map(|h| h.0);
                    let right = halves.map(|h| h.1);
                    [left, right]
                })
                .collect();
        }
        Self {
            dimension: self.dimension,
            pieces,
        }
    }

    /// Every Bernstein coefficient as an affine form of the free point: the discrete
    /// inequalities (14)/(16) of the paper are `form > 0` for every returned form.
    pub fn inequalities(&self) -> Vec<AffineForm> {
        let mut out = Vec::new();
        for [a1, a2, a3, b] in &self.pieces {
            for k in 0..b.coeffs().len() {
                out.push(AffineForm {
                    a: Point3::new(a1.coeffs()[k], a2.coeffs()[k], a3.coeffs()[k]),
                    b: b.coeffs()[k],
                });
            }
        }
        out
    }

    /// The numerator at local parameter `s` of `piece` as an affine form of the free point:
    /// `h_t` of formula (4) or `H_t` of (7), up to a positive factor.
    pub fn at(&self, piece: usize, s: f64) -> AffineForm {
        let [a1, a2, a3, b] = &self.pieces[piece];
        AffineForm {
            a: Point3::new(a1.eval(s), a2.eval(s), a3.eval(s)),
            b: b.eval(s),
        }
    }
}

fn all_equal(w: &[f64]) -> bool {
    w.iter().all(|&x| x == w[0])
}

/// Bernstein coefficients of the homogeneous (or Cartesian) coordinates of a piece.
fn coordinates(b: &RationalBezier, homogeneous: bool) -> [Bernstein; 3] {
    let pts = b.control_points();
    let w = b.weights();
    let hw = |k: usize| if homogeneous { w[k] } else { 1.0 };
    [
        Bernstein::new((0..pts.len()).map(|k| hw(k) * pts[k].x).collect::<Vec<_>>()),
        Bernstein::new((0..pts.len()).map(|k| hw(k) * pts[k].y).collect::<Vec<_>>()),
        Bernstein::new(w.to_vec()),
    ]
}

fn sub(a: &Bernstein, b: &Bernstein) -> Bernstein {
    a.add(&b.scale(-1.0))
}

/// `det [r1; r2; r3]` of 3 x 3 matrices of Bernstein polynomials.
fn det3(r1: [&Bernstein; 3], r2: [&Bernstein; 3], r3: [&Bernstein; 3]) -> Bernstein {
    let m0 = sub(&r2[1].mul(r3[2]), &r2[2].mul(r3[1]));
    let m1 = sub(&r2[0].mul(r3[2]), &r2[2].mul(r3[0]));
    let m2 = sub(&r2[0].mul(r3[1]), &r2[1].mul(r3[0]));
    r1[0]
        .mul(&m0)
        .add(&r1[1].mul(&m1).scale(-1.0))
        .add(&r1[2].mul(&m2))
}

fn planar_numerator(b: &RationalBezier, polynomial: bool) -> Bernstein {
    let [x, y, w] = coordinates(b, !polynomial);
    let (x1, y1) = (x.derivative(), y.derivative());
    let (x2, y2) = (x1.derivative(), y1.derivative());
    if polynomial {
        sub(&x1.mul(&y2), &x2.mul(&y1))
    } else {
        let w1 = w.derivative();
        let w2 = w1.derivative();
        det3([&x, &y, &w], [&x1, &y1, &w1], [&x2, &y2, &w2])
    }
}

fn spatial_numerator(xy: &RationalBezier, z: &RationalBezier, polynomial: bool) -> Bernstein {
    let [x, y, w] = coordinates(xy, !polynomial);
    let [zc, _, _] = coordinates(z, !polynomial);
    let d = |b: &Bernstein| b.derivative();
    let (x1, y1, z1) = (d(&x), d(&y), d(&zc));
    let (x2, y2, z2) = (d(&x1), d(&y1), d(&z1));
    let (x3, y3, z3) = (d(&x2), d(&y2), d(&z2));
    if polynomial {
        return det3([&x1, &y1, &z1], [&x2, &y2, &z2], [&x3, &y3, &z3]);
    }
    let (w1, w2, w3) = (d(&w), d(&d(&w)), d(&d(&d(&w))));
    // Laplace expansion of det[P; P'; P''; P'''] along the first row (X, Y, Z, W), negated.
    let rows = [
        [&x1, &y1, &z1, &w1],
        [&x2, &y2, &z2, &w2],
        [&x3, &y3, &z3, &w3],
    ];
    let minor = |skip: usize| {
        let cols: Vec<usize> = (0..4).filter(|&j| j != skip).collect();
        let (a, b, c) = (cols[0], cols[1], cols[2]);
        det3(
            [rows[0][a], rows[0][b], rows[0][c]],
            [rows[1][a], rows[1][b], rows[1][c]],
            [rows[2][a], rows[2][b], rows[2][c]],
        )
    };
    let top = [&x, &y, &zc, &w];
    let mut det = top[0].mul(&minor(0));
    for (j, t) in top.iter().enumerate().skip(1) {
        let term = t.mul(&minor(j));
        det = if j % 2 == 1 {
            sub(&det, &term)
        } else {
            det.add(&term)
        };
    }
    det.scale(-1.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::prelude::*;

    /// Signed curvature numerator `C' x C''` by the rational quotient rule.
    fn curvature_sign(c: &NurbsCurve, u: f64) -> f64 {
        let d = c.derivatives(u);
        d.first.cross(d.second)
    }

    #[test]
    fn affine_forms_reproduce_the_numerator_of_moved_curves() {
        let pts = vec![
            Point::new(0.0, 0.0),
            Point::new(1.0, 2.0),
            Point::new(3.0, 2.5),
            Point::new(4.0, -1.0),
            Point::new(6.0, 0.5),
        ];
        for weights in [None, Some(vec![1.0, 0.6, 1.7, 0.9, 1.2])] {
            let c = NurbsCurve::new(
                3,
                vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0],
                pts.clone(),
                weights,
            )
            .unwrap();
            let h = SignNumerator::curvature(&c, 2).unwrap();
            assert_eq!(h.piece_count(), 2);
            for d in [
                Point::new(0.5, -3.0),
                Point::new(2.0, 7.0),
                Point::new(-4.0, 1.0),
            ] {
                let moved = c.with_control_point(2, d).unwrap();
                for (k, (u0, u1)) in [(0.0, 0.4), (0.4, 1.0)].into_iter().enumerate() {
                    for i in 0..=10 {
                        let s = i as f64 / 10.0;
                        let u = u0 + s * (u1 - u0);
                        let exact = curvature_sign(&moved, u);
                        let ours = h.at(k, s).eval(Point3::new(d.x, d.y, 0.0));
                        // Same sign (up to rounding near zeros).
                        assert!(
                            exact * ours > 0.0 || exact.abs() < 1e-9 || ours.abs() < 1e-9,
                            "{exact} vs {ours}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn refinement_keeps_the_function_and_doubles_the_pieces() {
        let c = NurbsCurve::bezier(
            vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 3.0),
                Point::new(2.0, -1.0),
                Point::new(3.0, 1.0),
            ],
            None,
        )
        .unwrap();
        let h = SignNumerator::curvature(&c, 1).unwrap();
        assert_eq!(h.degree(), 3);
        assert_eq!(h.inequalities().len(), 4);
        let r = h.refined(3);
        assert_eq!(r.piece_count(), 8);
        assert_eq!(r.inequalities().len(), 32);
        let d = Point3::new(0.3, -0.7, 0.0);
        for k in 0..8 {
            for i in 0..=4 {
                let s = i as f64 / 4.0;
                let t = (k as f64 + s) / 8.0;
                // Subdivision re-expresses the same polynomial on each half: same values.
                let want = h.at(0, t).eval(d);
                assert!((r.at(k, s).eval(d) - want).abs() < 1e-12);
            }
        }
    }

    /// The torsion numerator `[C', C'', C''']` of a space curve: first and second derivatives
    /// by the rational quotient rule, the third by central differences of the second.
    fn torsion_sign(c: &SpaceCurve, u: f64) -> f64 {
        let d = |u: f64| {
            let (a, b) = (c.xy().derivatives(u), c.z().derivatives(u));
            (
                [a.first.x, a.first.y, b.first.x],
                [a.second.x, a.second.y, b.second.x],
            )
        };
        let (d1, d2) = d(u);
        let h = 1e-5;
        let (p, m) = (d(u + h).1, d(u - h).1);
        let d3: [f64; 3] = std::array::from_fn(|k| (p[k] - m[k]) / (2.0 * h));
        d1[0] * (d2[1] * d3[2] - d2[2] * d3[1]) - d1[1] * (d2[0] * d3[2] - d2[2] * d3[0])
            + d1[2] * (d2[0] * d3[1] - d2[1] * d3[0])
    }

    #[test]
    fn rational_torsion_numerator_has_the_sign_of_the_torsion() {
        let pts = [
            [0.0, 0.0, 0.0],
            [1.0, 2.0, 0.5],
            [3.0, 1.0, -1.0],
            [4.0, -1.0, 2.0],
            [5.0, 1.0, 1.0],
        ]
        .map(Point3::from);
        let c = SpaceCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
            &pts,
            Some(vec![1.0, 2.5, 0.6, 1.4, 1.0]),
        )
        .unwrap();
        let h = SignNumerator::torsion(&c, 2).unwrap();
        assert_eq!(h.dimension(), 3);
        let mut compared = 0;
        for d in [[3.0, 1.0, -1.0], [0.5, -2.0, 4.0], [-1.0, 3.0, 2.0]].map(Point3::from) {
            let moved = c.with_control_point(2, d).unwrap();
            for (k, (u0, u1)) in [(0.0, 0.5), (0.5, 1.0)].into_iter().enumerate() {
                for i in 1..10 {
                    let s = i as f64 / 10.0;
                    let exact = torsion_sign(&moved, u0 + s * (u1 - u0));
                    let ours = h.at(k, s).eval(d);
                    // Skip near-zeros, where the finite difference cannot tell the sign.
                    if exact.abs() > 1e-6 {
                        assert!(exact * ours > 0.0, "{exact} vs {ours} at piece {k}, s {s}");
                        compared += 1;
                    }
                }
            }
        }
        assert!(compared > 40, "{compared}");
    }

    #[test]
    fn out_of_range_free_index_is_an_error() {
        let c = NurbsCurve::bezier(vec![Point::new(0.0, 0.0), Point::new(1.0, 1.0)], None).unwrap();
        assert!(matches!(
            SignNumerator::curvature(&c, 2),
            Err(SplineError::ControlPointIndex { index: 2, count: 2 })
        ));
    }
}
