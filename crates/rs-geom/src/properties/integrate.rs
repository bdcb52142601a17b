//! Integrals over a trimmed face: `int int_D g(u, v) du dv` over the face's `(u, v)` domain
//! `D`, by Green's theorem on its loops.
//!
//! Along `u`: with `G(u, v) = int_a^u g(s, v) ds` (`a` the domain's least `u`), `dG/du = g`, so
//! `int int_D g du dv = oint_{dD} G dv` along the loops (outer ones counter-clockwise, holes
//! clockwise: the orientation `Model::face_domain` gives them). Along `v` likewise, with
//! `H(u, v) = int_b^v g(u, s) ds` and `int int_D g = -oint_{dD} H du`. The inner integral runs
//! along a parameter in which the integrand is a polynomial where there is one (the straight
//! lines of a plane, cylinder, cone or extrusion), else along the one with fewer knot lines
//! inside the domain; it is split at each knot line. The outer integral runs along each
//! Bezier piece of the loops, split where the piece crosses a knot line.
//!
//! Both are Green's-theorem piece integrals ([`integrate_piece`]): a polynomial integrand of
//! known degree (the caller's `degrees`) is integrated exactly, up to rounding, by the Gauss
//! rule with the fewest nodes exact for it (inner: the integrand's degree in its parameter;
//! outer: a polynomial piece on a surface polynomial in both parameters, a plane). Where no
//! degree is known each loop piece's share is integrated twice with fixed Gauss-Legendre
//! rules of 8 and 12 nodes on every part (inner and outer): where the two agree within the
//! tolerance (or the rounding of the sums) the second is taken, as an adaptive rule accepts
//! an interval whose halves agree with it, at a fraction of the cost, with the difference as
//! the error estimate; else adaptive Gauss-Legendre decides for that piece,
//! stopping when halving an interval changes no component by more than its tolerance or the
//! rounding noise of the integrand's magnitude, or at the depth and interval limits (bounded
//! work), with an error estimate.

use rs_roots::{Bernstein, bernstein_roots};
use rs_spline::green::{Jacobian, PieceIntegrand, PieceRule, integrate_piece};
use rs_spline::prelude::*;
use rs_spline::quadrature::{GaussRule, MAX_GAUSS_NODES, fixed_gauss_rule};
use rs_spline::{BoundingBox, Domain, Point, RationalBezier};

/// An integral of a vector-valued integrand over a face's domain, with how far it can be
/// trusted.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct DomainIntegral {
    /// The integral of each component.
    pub(crate) values: Vec<f64>,
    /// An estimate of the absolute error of the worst component: the outer rule's estimate
    /// plus the inner rules' largest estimate times the loops' total variation across (0 where
    /// both rules are exact).
    pub(crate) error: f64,
    /// Whether every adaptive rule met its tolerance within its bounded work.
    pub(crate) converged: bool,
}

/// The relative tolerance of the integrals, against the integrand's size times the box.
const TOLERANCE: f64 = 16.0 * f64::EPSILON;

/// The most evaluations of the integrand for one face: the adaptive rules nest (an inner
/// integral at every node of the outer one), so their own interval limits alone would allow
/// hours on a singular integrand. Past it the integrand reads as zero and the integral is
/// reported as not converged. Real faces take a few hundred thousand.
pub(crate) const MAX_EVALUATIONS: usize = 20_000_000;

/// `int int_D g(u, v) du dv` of the `dim` components `g` writes into its output (returning
/// their magnitude, the size of the terms they are sums of, for the rounding test) over the
/// domain `domain`, split at the surface's knot lines (`[u values, v values]`). `degrees[k]`
/// is the integrand's degree in parameter `k` where it is a polynomial in it (between knot
/// lines), `None` where it is not. Where a rule is adaptive, each component to about `16 eps`
/// of the integrand's size over the domain's box, or to `abs_floor` where that is larger.
/// `None` where an integrand value is not finite.
pub(crate) fn integrate_over_domain(
    domain: &Domain,
    lines: [&[f64]; 2],
    degrees: [Option<usize>; 2],
    abs_floor: f64,
    dim: usize,
    g: &dyn Fn([f64; 2], &mut [f64]) -> f64,
) -> Option<DomainIntegral> {
    let evaluations = std::cell::Cell::new(0usize);
    let budgeted = |uv: [f64; 2], out: &mut [f64]| -> f64 {
        let n = evaluations.get();
        if n >= MAX_EVALUATIONS {
            out.fill(0.0);
            return 0.0;
        }
        evaluations.set(n + 1);
        g(uv, out)
    };
    let g: &dyn Fn([f64; 2], &mut [f64]) -> f64 = &budgeted;
    let b = domain.bounding_box();
    let (lo, hi) = ([b.min.x, b.min.y], [b.max.x, b.max.y]);
    let inside = |k: usize| lines[k].iter().filter(|&&l| lo[k] < l && l < hi[k]).count();
    // The inner integral runs at every node of the outer one: along a parameter where it is
    // exact, else along the one with fewer knot lines.
    let inner = match degrees {
        [Some(_), None] => 0,
        [None, Some(_)] => 1,
        _ => usize::from(inside(1) < inside(0)),
    };
    let outer_axis = 1 - inner;
    // Absolute tolerances from the integrand's size over the domain's box, so that a stretch
    // where the integrand is tiny (a piece grazing a knot line) is not refined to its own
    // rounding noise: the outer integral's over the box's area, and never below the caller's
    // floor (a sliver's integrals cancel far below what the whole model can resolve); the
    // inner one's over the box's width along it, in the same proportion.
    let span = [hi[0] - lo[0], hi[1] - lo[1]];
    let size = integrand_size(&b, dim, g);
    let outer_tol = (TOLERANCE * size * span[0] * span[1]).max(abs_floor);
    let inner_tol = if span[outer_axis] > 0.0 {
        outer_tol / span[outer_axis]
    } else {
        outer_tol
    };
    // `G` has degree `degrees[inner] + 1` in the inner parameter, so at most the sum plus one
    // in both; along a polynomial piece of degree `p`, `G(C(t)) C'(t)` has degree
    // `p (sum + 1) + p - 1`.
    let joint = match degrees {
        [Some(a), Some(b)] => Some(a + b + 1),
        _ => None,
    };
    let pieces: Vec<LoopPiece> = domain
        .bezier_pieces()
        .into_iter()
        .map(|(_, piece)| {
            let p = piece.degree();
            // Split where the piece crosses a knot line: the inner integral is only
            // piecewise smooth across it.
            let mut cuts = crossings(&piece, 0, lines[0]);
            cuts.extend(crossings(&piece, 1, lines[1]));
            cuts.sort_by(f64::total_cmp);
            cuts.dedup();
            LoopPiece {
                exact_degree: joint
                    .filter(|_| piece.is_polynomial())
                    .map(|k| p * k + p.saturating_sub(1)),
                variation: control_variation(&piece, outer_axis),
                piece,
                cuts,
            }
        })
        .collect();
    let green = Green {
        lines,
        start: lo[inner],
        inner,
        inner_degree: degrees[inner],
        dim,
        tolerances: [inner_tol, outer_tol],
    };
    let mut sum = DomainIntegral {
        values: vec![0.0; dim],
        error: 0.0,
        converged: true,
    };
    for lp in &pieces {
        let piece = green.piece(lp, g)?;
        for (s, v) in sum.values.iter_mut().zip(&piece.values) {
            *s += v;
        }
        // The inner rules' worst error, integrated along the piece: at most times its
        // variation across.
        sum.error += piece.outer.error + piece.inner.error * lp.variation;
        sum.converged &= piece.outer.converged && piece.inner.converged;
    }
    // Past the budget the integrand reads as zero: not converged, whatever the rules say.
    sum.converged &= evaluations.get() < MAX_EVALUATIONS;
    Some(sum)
}

/// The rounding noise of a sum relative to its scale (the adaptive rule's).
const NOISE: f64 = 256.0 * f64::EPSILON;

/// Nodes of the two fixed Gauss-Legendre rules tried first where the integrand's degree is
/// not known.
const FIXED_LOW: usize = 8;
/// See [`FIXED_LOW`].
const FIXED_HIGH: usize = 12;

/// One Bezier piece of a face's loops, split where it crosses knot lines.
struct LoopPiece {
    piece: RationalBezier,
    /// Its parameters in `(0, 1)` where it crosses a knot line, ascending.
    cuts: Vec<f64>,
    /// The degree in its parameter of the outer integrand where that is a polynomial.
    exact_degree: Option<usize>,
    /// The total variation of its outer coordinate (a bound from the control polygon).
    variation: f64,
}

/// The rules of a piece where the integrand's degree is not known.
#[derive(Clone, Copy)]
enum Rules {
    /// Adaptive Gauss-Legendre to the tolerances.
    Adaptive,
    /// One fixed Gauss-Legendre rule on every part.
    Fixed(&'static GaussRule),
}

/// Green's theorem over a face's loops: `oint G d(outer)` with `G` the integral along
/// `inner` from `start`.
struct Green<'a> {
    lines: [&'a [f64]; 2],
    start: f64,
    inner: usize,
    /// The integrand's degree along `inner` where it is a polynomial in it.
    inner_degree: Option<usize>,
    dim: usize,
    /// The adaptive rules' absolute tolerances: `[inner, outer]`.
    tolerances: [f64; 2],
}

/// One piece's share of the outer integral: its values, the outer rule's accuracy and the
/// worst of the inner rules' (its error the largest estimate, to be scaled by the piece's
/// variation).
struct PieceSum {
    values: Vec<f64>,
    outer: Accuracy,
    inner: Accuracy,
}

impl Green<'_> {
    /// A piece's share of `oint G d(outer)`: exact where the degrees are known; elsewhere
    /// two fixed rules of different orders, taken where they agree within the tolerance or
    /// the rounding of their sums (as the adaptive rule accepts an interval whose halves agree
    /// with it), else the adaptive rule. `None` where an integrand value is not finite.
    fn piece(&self, lp: &LoopPiece, g: &dyn Fn([f64; 2], &mut [f64]) -> f64) -> Option<PieceSum> {
        if lp.exact_degree.is_some() && self.inner_degree.is_some() {
            return self.piece_with(lp, Rules::Adaptive, g);
        }
        let low = self.piece_with(lp, Rules::Fixed(fixed_gauss_rule::<FIXED_LOW>()), g);
        let high = self.piece_with(lp, Rules::Fixed(fixed_gauss_rule::<FIXED_HIGH>()), g);
        if let (Some(low), Some(mut high)) = (low, high) {
            let diff = low
                .values
                .iter()
                .zip(&high.values)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            // A weaker test than the adaptive rule's (16 nodes against two halves of 16): the
            // two rules share no nodes, so their agreement within the tolerance means both
            // resolve the piece (a kink or an unresolved peak leaves them apart); the noise
            // allowance is each part's length times its integrand's peak magnitude, an upper
            // bound of the terms' size, as the adaptive rule's.
            let noise = NOISE * low.outer.scale.max(high.outer.scale);
            if diff <= self.tolerances[1].max(noise) {
                high.outer.error = diff;
                return Some(high);
            }
        }
        self.piece_with(lp, Rules::Adaptive, g)
    }

    /// A piece's share with `rules` where no exact rule applies; `None` where an integrand
    /// value is not finite.
    fn piece_with(
        &self,
        lp: &LoopPiece,
        rules: Rules,
        g: &dyn Fn([f64; 2], &mut [f64]) -> f64,
    ) -> Option<PieceSum> {
        let (inner, outer_axis) = (self.inner, 1 - self.inner);
        let [inner_tol, outer_tol] = self.tolerances;
        let inner_rule = match (self.inner_degree, rules) {
            (Some(d), _) => PieceRule::for_piece(true, d, MAX_GAUSS_NODES, inner_tol),
            (None, Rules::Adaptive) => PieceRule::Adaptive { abs_tol: inner_tol },
            (None, Rules::Fixed(rule)) => PieceRule::Exact(rule),
        };
        // Green's theorem: `+oint G dv` along u, `-oint H du` along v.
        let sign = if inner == 0 { 1.0 } else { -1.0 };
        let mut values = vec![0.0; self.dim];
        let mut inner_accuracy = Accuracy {
            error: 0.0,
            converged: true,
            scale: 0.0,
        };
        let mut finite = true;
        let mut outer = |t: f64, out: &mut [f64]| -> f64 {
            let (p, d) = lp.piece.point_and_tangent(t);
            let (p, d) = ([p.x, p.y], [d.x, d.y]);
            let along = inner_integral(
                self.start,
                p,
                inner,
                self.lines[inner],
                inner_rule,
                self.dim,
                g,
            );
            inner_accuracy.error = inner_accuracy.error.max(along.accuracy.error);
            inner_accuracy.converged &= along.accuracy.converged;
            let factor = sign * d[outer_axis];
            let mut magnitude = factor.abs() * along.accuracy.scale;
            for (o, &gi) in out.iter_mut().zip(&along.values) {
                *o = gi * factor;
                finite &= o.is_finite();
                magnitude = magnitude.max(o.abs());
            }
            if !finite {
                out.fill(0.0);
            }
            magnitude
        };
        let cuts = lp.cuts.iter().copied();
        let outer_accuracy =
            add_between(
                &mut values,
                &mut outer,
                (0.0, 1.0),
                cuts,
                |from, to| match (lp.exact_degree, rules) {
                    // Adaptive to the outer tolerance only if the exact rule had too many nodes.
                    (Some(d), _) => {
                        PieceRule::for_piece(true, d, MAX_GAUSS_NODES, outer_tol * (to - from))
                    }
                    (None, Rules::Adaptive) => PieceRule::Adaptive {
                        abs_tol: outer_tol * (to - from),
                    },
                    (None, Rules::Fixed(rule)) => PieceRule::Exact(rule),
                },
            );
        finite.then_some(PieceSum {
            values,
            outer: outer_accuracy,
            inner: inner_accuracy,
        })
    }
}

/// An integral along one parameter and how far it can be trusted.
struct LineIntegral {
    values: Vec<f64>,
    accuracy: Accuracy,
}

/// The integral of `g` along parameter `axis` from `start` to `p`'s coordinate, the other
/// parameter at `p`'s, split at the knot lines `breaks` (ascending) between them, each part
/// by `rule`.
fn inner_integral(
    start: f64,
    p: [f64; 2],
    axis: usize,
    breaks: &[f64],
    rule: PieceRule,
    dim: usize,
    g: &dyn Fn([f64; 2], &mut [f64]) -> f64,
) -> LineIntegral {
    let end = p[axis];
    let inside = breaks.iter().copied().filter(|&b| start < b && b < end);
    let at = |s: f64| {
        let mut q = p;
        q[axis] = s;
        q
    };
    let mut values = vec![0.0; dim];
    let accuracy = add_between(
        &mut values,
        |s, out| g(at(s), out),
        (start, end),
        inside,
        |_, _| rule,
    );
    LineIntegral { values, accuracy }
}

/// How far a sum of piece integrals can be trusted: the summed error estimates, whether every
/// part converged, and the rounding scale (each part's length times the largest magnitude
/// its integrand returned).
struct Accuracy {
    error: f64,
    converged: bool,
    scale: f64,
}

/// Adds to `sum` the integral of `f` over `range` split at `cuts` (ascending, inside it),
/// each part `[from, to]` by [`integrate_piece`] with the rule `rule(from, to)`.
fn add_between(
    sum: &mut [f64],
    f: impl FnMut(f64, &mut [f64]) -> f64,
    (start, end): (f64, f64),
    cuts: impl IntoIterator<Item = f64>,
    rule: impl Fn(f64, f64) -> PieceRule,
) -> Accuracy {
    let mut integrand = Along {
        f,
        scratch: vec![0.0; sum.len()],
        peak: 0.0,
    };
    let mut accuracy = Accuracy {
        error: 0.0,
        converged: true,
        scale: 0.0,
    };
    let mut from = start;
    for to in cuts.into_iter().chain(std::iter::once(end)) {
        let part = integrate_piece(
            &mut integrand,
            (from, to),
            rule(from, to),
            Jacobian::OnTheSum,
            sum,
        );
        accuracy.error += part.error;
        accuracy.converged &= part.converged;
        accuracy.scale += (to - from).abs() * integrand.peak;
        integrand.peak = 0.0;
        from = to;
    }
    accuracy
}

/// A function of one parameter as a piece integrand: `f(t, out)` writes its components and
/// returns their rounding magnitude.
struct Along<F> {
    f: F,
    scratch: Vec<f64>,
    /// The largest magnitude returned since it was last reset.
    peak: f64,
}

impl<F: FnMut(f64, &mut [f64]) -> f64> PieceIntegrand for Along<F> {
    fn add_node(&mut self, t: f64, weight: f64, sum: &mut [f64]) {
        let magnitude = (self.f)(t, &mut self.scratch);
        self.peak = self.peak.max(magnitude);
        for (s, v) in sum.iter_mut().zip(&self.scratch) {
            *s += weight * v;
        }
    }

    fn values(&mut self, t: f64, out: &mut [f64]) -> f64 {
        let magnitude = (self.f)(t, out);
        self.peak = self.peak.max(magnitude);
        magnitude
    }
}

/// Points per side of the [`grid`] on which an integrand's size is sampled.
const SIZE_GRID: usize = 9;

/// The largest magnitude `g` returns on the [`grid`] over the box `b` (at least the smallest
/// positive normal number, so that tolerances are never zero).
fn integrand_size(b: &BoundingBox, dim: usize, g: &dyn Fn([f64; 2], &mut [f64]) -> f64) -> f64 {
    let mut out = vec![0.0; dim];
    grid(b, SIZE_GRID)
        .map(|uv| g(uv, &mut out))
        .filter(|m| m.is_finite())
        .fold(f64::MIN_POSITIVE, f64::max)
}

/// The `n x n` grid of parameters over the box `b` (`n >= 2`), corners included, `u` fastest:
/// where a face's surface is sampled for its size (the model's frame, the integrand's
/// magnitude).
pub(crate) fn grid(b: &BoundingBox, n: usize) -> impl Iterator<Item = [f64; 2]> + '_ {
    let n = n.max(2);
    let at = move |i: usize, lo: f64, hi: f64| lo + (hi - lo) * i as f64 / (n - 1) as f64;
    (0..n * n).map(move |k| [at(k % n, b.min.x, b.max.x), at(k / n, b.min.y, b.max.y)])
}

/// Coordinate `axis` (0: `u`, 1: `v`) of the piece's control points.
fn control_coordinates(piece: &RationalBezier, axis: usize) -> Vec<f64> {
    let coordinate = |p: &Point| if axis == 0 { p.x } else { p.y };
    piece.control_points().iter().map(coordinate).collect()
}

/// The total variation of coordinate `axis` along a piece, from its control polygon (an
/// upper bound).
fn control_variation(piece: &RationalBezier, axis: usize) -> f64 {
    let c = control_coordinates(piece, axis);
    c.windows(2).map(|w| (w[1] - w[0]).abs()).sum()
}

/// The parameters in `(0, 1)` where coordinate `axis` of the piece equals one of `lines`:
/// the roots of `sum w_i (c_i - line) B_i(t)`.
fn crossings(piece: &RationalBezier, axis: usize, lines: &[f64]) -> Vec<f64> {
    let coords = control_coordinates(piece, axis);
    let (lo, hi) = coords
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &c| {
            (a.min(c), b.max(c))
        });
    let mut out = Vec::new();
    for &line in lines.iter().filter(|&&l| lo < l && l < hi) {
        let c: Vec<f64> = coords
            .iter()
            .zip(piece.weights())
            .map(|(&x, &w)| w * (x - line))
            .collect();
        if let Ok(roots) = bernstein_roots(&Bernstein::new(c)) {
            out.extend(roots.into_iter().filter(|&t| 0.0 < t && t < 1.0));
        }
    }
    out
}
