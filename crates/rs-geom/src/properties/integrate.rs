//! Integrals over a trimmed face: `int int_D g(u, v) du dv` over the face's `(u, v)` domain
//! `D`, by Green's theorem on its loops.
//!
//! With `G(u, v) = int_a^u g(s, v) ds` (`a` the domain's least `u`), `dG/du = g`, so
//! `int int_D g du dv = oint_{dD} G dv` along the loops (outer ones counter-clockwise, holes
//! clockwise: the orientation `Model::face_domain` gives them). Both integrals are adaptive
//! Gauss-Legendre ([`integrate_adaptive_vector`]): the outer one along each Bezier piece of the
//! loops, the inner one along `u` at each of its nodes. Each stops when halving an interval
//! changes no component by more than the rounding noise of the integrand's magnitude, or at
//! the depth and interval limits (bounded work); polynomial integrands of degree up to 31 in
//! the parameter are exact at the first level (a plane's, and a polynomial B-spline surface's
//! within a knot span).

use rs_spline::prelude::*;
use rs_spline::quadrature::integrate_adaptive_vector;
use rs_spline::{Domain, Point};

/// An integral of a vector-valued integrand over a face's domain, with how far it can be
/// trusted.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct DomainIntegral {
    /// The integral of each component.
    pub(crate) values: Vec<f64>,
    /// An estimate of the absolute error of the worst component: the outer rule's estimate
    /// plus the inner rules' largest estimate times the loops' total variation in `v`.
    pub(crate) error: f64,
    /// Whether every adaptive rule met its tolerance within its bounded work.
    pub(crate) converged: bool,
}

/// `int int_D g(u, v) du dv` of the `dim` components `g` writes into its output (returning
/// their magnitude, the size of the terms they are sums of, for the rounding test) over the
/// domain `domain`. `None` where an integrand value is not finite.
pub(crate) fn integrate_over_domain(
    domain: &Domain,
    dim: usize,
    g: &dyn Fn([f64; 2], &mut [f64]) -> f64,
) -> Option<DomainIntegral> {
    let b = domain.bounding_box();
    let a = b.min.x;
    let mut values = vec![0.0; dim];
    let (mut outer_error, mut inner_error, mut converged) = (0.0f64, 0.0f64, true);
    let mut v_variation = 0.0;
    let mut finite = true;
    for (_, piece) in domain.bezier_pieces() {
        let mut outer = |t: f64, out: &mut [f64]| -> f64 {
            let (p, d) = piece.point_and_tangent(t);
            let inner = inner_integral(a, p, dim, g);
            inner_error = inner_error.max(inner.error);
            converged &= inner.converged;
            let mut magnitude = 0.0f64;
            for (o, &gi) in out.iter_mut().zip(&inner.values) {
                *o = gi * d.y;
                finite &= o.is_finite();
                magnitude = magnitude.max(o.abs());
            }
            if !finite {
                out.fill(0.0);
            }
            magnitude
        };
        let along = integrate_adaptive_vector(&mut outer, dim, 0.0, 1.0, 0.0);
        for (v, s) in values.iter_mut().zip(&along.values) {
            *v += s;
        }
        outer_error += along.error;
        converged &= along.converged;
        v_variation += piece_v_variation(&piece);
    }
    finite.then_some(DomainIntegral {
        values,
        error: outer_error + inner_error * v_variation,
        converged,
    })
}

/// `G(u, v) = int_a^u g(s, v) ds` at `p = (u, v)`.
fn inner_integral(
    a: f64,
    p: Point,
    dim: usize,
    g: &dyn Fn([f64; 2], &mut [f64]) -> f64,
) -> rs_spline::quadrature::VectorIntegral {
    integrate_adaptive_vector(|s, out| g([s, p.y], out), dim, a, p.x, 0.0)
}

/// The total variation of `v` along a piece, from its control polygon (an upper bound).
fn piece_v_variation(piece: &rs_spline::RationalBezier) -> f64 {
    piece
        .control_points()
        .windows(2)
        .map(|w| (w[1].y - w[0].y).abs())
        .sum()
}
