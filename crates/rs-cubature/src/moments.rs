//! Exact moments by Green's theorem: `integral f dA = oint F dy` with `F = integral f dx`,
//! summed over the Bezier pieces of every loop, each loop multiplied by its
//! [`boundary_sign`](rs_contain::LoopNesting::boundary_sign) under the fill rule (which puts
//! the filled set on its left: outer boundaries counter-clockwise, holes clockwise; `0` for a
//! loop that bounds nothing, as the inner of two nested loops of one orientation under the
//! nonzero rule).
//!
//! On a polynomial piece of degree `p` (all weights equal) the integrand `F(C(t)) y'(t)` of a
//! basis of total degree `n` is a polynomial of degree at most `p (n + 1) + p - 1`, integrated
//! exactly by Gauss-Legendre with `ceil(p (n + 2) / 2)` nodes. A rational piece is integrated
//! by the adaptive rule (all components at once, bounded work); a piece that does not converge
//! is an error. Both through `rs_spline::green`, the Green's-theorem kernel cell coverage
//! integrates with too.

use rs_contain::{FillRule, curve_boundary_signs};
use rs_spline::green::{Jacobian, PieceIntegrand, PieceRule, integrate_piece};
use rs_spline::prelude::*;
use rs_spline::quadrature::MAX_GAUSS_NODES;
use rs_spline::{BoundingBox, Domain, Point, RationalBezier};

use crate::basis::{LegendreBasis, dim_polynomials, graded_index};
use crate::{CubatureError, MAX_DEGREE};

/// The absolute tolerance of the adaptive quadrature on a rational piece, relative to the
/// area of the bounding box (the moments' scale: every integrand is normalised so that its
/// moment is at most a small multiple of the area).
const RELATIVE_QUADRATURE_TOLERANCE: f64 = 1e-15;

/// Each curve's boundary sign under `rule` ([`curve_boundary_signs`]): what the moments and
/// the chord formula count every curve with.
///
/// # Errors
/// [`CubatureError::OpenBoundary`] for a loop that does not close, [`CubatureError::Nesting`]
/// for loops whose nesting does not decide the fill.
pub(crate) fn fill_signs(domain: &Domain, rule: FillRule) -> Result<Vec<i64>, CubatureError> {
    domain.require_closed()?;
    curve_boundary_signs(domain, rule).map_err(CubatureError::Nesting)
}

/// `integral F_k(C(t)) y'(t) dt` over the boundary of the filled set, each curve counted
/// with its sign in `curve_sign` ([`fill_signs`]), for the `dim` functions `F_k` that
/// `antiderivatives(p, out)` writes at `p` (returning `max_k |F_k(p)|`), `F_k` of total
/// degree at most `degree + 1`; `abs_tol` for rational pieces. One running sum over all the
/// pieces ([`Jacobian::OnEachWeight`]).
fn green_integrals(
    domain: &Domain,
    curve_sign: &[i64],
    degree: usize,
    dim: usize,
    abs_tol: f64,
    antiderivatives: &mut dyn FnMut(Point, &mut [f64]) -> f64,
) -> Result<Vec<f64>, CubatureError> {
    let mut total = vec![0.0; dim];
    let mut at = vec![0.0; dim];
    for (curve, piece) in domain.bezier_pieces() {
        let sign = curve_sign[curve] as f64;
        if sign == 0.0 {
            continue;
        }
        // A strongly weighted piece as its balanced parts (the same curve, reparametrised and
        // halved: the adaptive rule's nodes would miss the slivers it moves in); an ordinary
        // piece as it is, bit for bit.
        let parts = piece.balanced_parts();
        for part in parts.as_deref().unwrap_or(std::slice::from_ref(&piece)) {
            green_piece(
                part,
                curve,
                sign,
                degree,
                abs_tol,
                &mut *antiderivatives,
                &mut at,
                &mut total,
            )?;
        }
    }
    Ok(total)
}

/// Adds to `total` the integrals of `sign F_k(C(t)) y'(t)` along `piece` of curve `curve`
/// ([`green_integrals`]), `at` the antiderivatives' scratch.
///
/// # Errors
/// [`CubatureError::MomentsNotConverged`] if the piece's integrals, or for a rational piece
/// its own area integral, do not converge.
#[allow(clippy::too_many_arguments)]
fn green_piece(
    piece: &RationalBezier,
    curve: usize,
    sign: f64,
    degree: usize,
    abs_tol: f64,
    antiderivatives: &mut dyn FnMut(Point, &mut [f64]) -> f64,
    at: &mut [f64],
    total: &mut [f64],
) -> Result<(), CubatureError> {
    let p = piece.degree();
    let polynomial = piece.is_polynomial();
    // F_k(C(t)) y'(t): degree p (degree + 1) + p - 1.
    let quadrature =
        PieceRule::for_piece(polynomial, p * (degree + 2) - 1, MAX_GAUSS_NODES, abs_tol);
    let mut integrand = MomentIntegrand {
        piece,
        sign,
        per_parameter: 2.0 * p as f64,
        antiderivatives,
        at,
    };
    let got = integrate_piece(
        &mut integrand,
        (0.0, 1.0),
        quadrature,
        Jacobian::OnEachWeight,
        total,
    );
    if !got.converged {
        return Err(CubatureError::MomentsNotConverged {
            curve,
            error: got.error,
        });
    }
    // A rational piece whose weights are spread so far that it moves within a sliver of its
    // parameter ends can have its moments' quadrature accept a wrong integral as converged
    // (its nodes miss the motion: at degree 0 a one-node rule of weight `9e-16` for an area
    // of `0.5`, before such pieces were balanced); its own area integral does not converge
    // there, and refuses it too.
    if !polynomial {
        let area = piece.area_integral();
        if !area.converged {
            return Err(CubatureError::MomentsNotConverged {
                curve,
                error: area.error,
            });
        }
    }
    Ok(())
}

/// `sign F_k(C(t)) y'(t)` along one Bezier piece of a loop whose boundary sign is `sign`.
struct MomentIntegrand<'a> {
    piece: &'a RationalBezier,
    sign: f64,
    /// `2 p` for a piece of degree `p`: the rounding of `y'` is about `eps 2 p |y|`
    /// (differences of coordinates).
    per_parameter: f64,
    antiderivatives: &'a mut dyn FnMut(Point, &mut [f64]) -> f64,
    /// Scratch for the `F_k` at a node.
    at: &'a mut [f64],
}

impl PieceIntegrand for MomentIntegrand<'_> {
    fn add_node(&mut self, t: f64, weight: f64, sum: &mut [f64]) {
        let (pt, tangent) = self.piece.point_and_tangent(t);
        (self.antiderivatives)(pt, self.at);
        let factor = self.sign * weight * tangent.y;
        for (s, a) in sum.iter_mut().zip(self.at.iter()) {
            *s += factor * a;
        }
    }

    fn values(&mut self, t: f64, out: &mut [f64]) -> f64 {
        let (pt, tangent) = self.piece.point_and_tangent(t);
        let largest = (self.antiderivatives)(pt, out);
        // The sign is exact: the adaptive rule's values are the unsigned ones negated.
        let dy = self.sign * tangent.y;
        for o in out.iter_mut() {
            *o *= dy;
        }
        largest * (tangent.y.abs() + self.per_parameter * pt.y.abs())
    }
}

/// The area of `bbox` (at least the smallest positive number).
fn box_area(bbox: BoundingBox) -> f64 {
    (bbox.width() * bbox.height()).max(f64::MIN_POSITIVE)
}

/// The exact integrals of the scaled Legendre basis over the set `domain` fills, its curves
/// counted with their signs `curve_sign` ([`fill_signs`]).
pub(crate) fn basis_moments(
    domain: &Domain,
    curve_sign: &[i64],
    basis: &LegendreBasis,
    degree: usize,
) -> Result<Vec<f64>, CubatureError> {
    let dim = basis.len();
    let mut scratch = vec![0.0; basis.scratch_len()];
    let abs_tol = RELATIVE_QUADRATURE_TOLERANCE * box_area(domain.bounding_box());
    green_integrals(domain, curve_sign, degree, dim, abs_tol, &mut |p, out| {
        basis.x_antiderivatives_into(p, &mut scratch, out)
    })
}

/// Exact integrals over the set `domain` fills under `rule` of the monomials `x^a y^b`,
/// `a + b <= degree`, in graded order (degree 0; then `x`, `y`; then `x^2`, `x y`, `y^2`;
/// ...). Under [`FillRule::EvenOdd`] holes are holes however the loops run; under
/// [`FillRule::NonZero`] a loop inside another of the same orientation adds nothing.
///
/// Computed by Green's theorem on the raw monomials, `integral x^a y^b dA = oint x^(a+1) y^b /
/// (a + 1) dy`, each component scaled by `max |x|^a max |y|^b` over the bounding box while it
/// is integrated. The absolute error of a moment is then a few units of rounding times
/// `perimeter x max |x|^(a+1) max |y|^b`: relative to `area x max over the box |x^a y^b|`, it
/// grows with the ratio of the perimeter times the box's reach from the origin to the area.
/// Raw monomials suit tests and moderate degrees; the rules work in the scaled Legendre
/// basis instead (see the crate documentation).
///
/// # Errors
/// [`CubatureError::DegreeTooHigh`] above [`MAX_DEGREE`]; [`CubatureError::OpenBoundary`];
/// [`CubatureError::Nesting`] (coincident or crossing loops, whose nesting does not decide
/// the fill); [`CubatureError::MomentsNotConverged`] if a rational piece's quadrature hits
/// its work bound.
///
/// # Examples
///
/// ```
/// use rs_contain::FillRule;
/// use rs_cubature::monomial_moments;
/// use rs_spline::{circle, polyline, Domain, Point};
/// let p = |x: f64, y: f64| Point::new(x, y);
/// let square = polyline(&[p(0.0, 0.0), p(2.0, 0.0), p(2.0, 1.0), p(0.0, 1.0), p(0.0, 0.0)]).unwrap();
/// let m = monomial_moments(&Domain::new(vec![square]).unwrap(), 2, FillRule::EvenOdd).unwrap();
/// // 1, x, y, x^2, x y, y^2 over [0, 2] x [0, 1].
/// let exact = [2.0, 2.0, 1.0, 8.0 / 3.0, 1.0, 2.0 / 3.0];
/// assert!(m.iter().zip(exact).all(|(a, b)| (a - b).abs() < 1e-14));
/// // Two counter-clockwise circles: a ring under even-odd, the big disc under nonzero.
/// let c = |r: f64| circle(p(0.0, 0.0), r).unwrap();
/// let d = Domain::new(vec![c(2.0), c(1.0)]).unwrap();
/// let area = |rule| monomial_moments(&d, 0, rule).unwrap()[0];
/// let pi = std::f64::consts::PI;
/// assert!((area(FillRule::EvenOdd) - 3.0 * pi).abs() < 1e-12);
/// assert!((area(FillRule::NonZero) - 4.0 * pi).abs() < 1e-12);
/// ```
pub fn monomial_moments(
    domain: &Domain,
    degree: usize,
    rule: FillRule,
) -> Result<Vec<f64>, CubatureError> {
    if degree > MAX_DEGREE {
        return Err(CubatureError::DegreeTooHigh {
            degree,
            max: MAX_DEGREE,
        });
    }
    let bbox = domain.bounding_box();
    let reach = |lo: f64, hi: f64| {
        let r = lo.abs().max(hi.abs());
        if r > 0.0 { r } else { 1.0 }
    };
    let (rx, ry) = (reach(bbox.min.x, bbox.max.x), reach(bbox.min.y, bbox.max.y));
    let dim = dim_polynomials(degree);
    let mut scales = vec![0.0; dim];
    for a in 0..=degree {
        for b in 0..=degree - a {
            scales[graded_index(a, b)] = rx.powi(a as i32) * ry.powi(b as i32);
        }
    }
    let (mut xs, mut ys) = (vec![0.0; degree + 2], vec![0.0; degree + 1]);
    let abs_tol = RELATIVE_QUADRATURE_TOLERANCE * box_area(bbox);
    let curve_sign = fill_signs(domain, rule)?;
    let scaled = green_integrals(domain, &curve_sign, degree, dim, abs_tol, &mut |p, out| {
        // Powers of x / rx and y / ry: every component at most |x| / (a + 1) <= rx.
        let (u, v) = (p.x / rx, p.y / ry);
        xs[0] = 1.0;
        ys[0] = 1.0;
        for k in 1..xs.len() {
            xs[k] = xs[k - 1] * u;
        }
        for k in 1..ys.len() {
            ys[k] = ys[k - 1] * v;
        }
        let mut largest = 0.0f64;
        for a in 0..=degree {
            for b in 0..=degree - a {
                let f = rx * xs[a + 1] * ys[b] / (a + 1) as f64;
                largest = largest.max(f.abs());
                out[graded_index(a, b)] = f;
            }
        }
        largest
    })?;
    Ok(scaled.iter().zip(&scales).map(|(m, s)| m * s).collect())
}
