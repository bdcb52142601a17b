//! The rule: candidates inside the domain, a discrete orthonormal basis at them, and
//! Caratheodory-Tchakaloff compression by non-negative least squares.

use nalgebra::{DMatrix, DVector};
use rs_contain::{Classifier, ContainOptions, FillRule, Locate, Location};
use rs_spline::{Domain, Point, times_power_of_two};

use crate::basis::{LegendreBasis, dim_polynomials};
use crate::candidates::{Candidates, LayerDensity, boundary_layers};
use crate::chords::chord_formula;
use crate::moments::{basis_moments, fill_signs};
use crate::nnls::{NnlsOptions, dot, nnls};
use crate::orthogonal::{HIGH_DEGREE_BASIS, Reference, orthonormalise};
use crate::{CubatureError, MAX_DEGREE};

/// Default of [`CubatureOptions::candidates_per_polynomial`].
pub const DEFAULT_CANDIDATES_PER_POLYNOMIAL: usize = 12;
/// Default of [`CubatureOptions::max_retries`].
pub const DEFAULT_MAX_RETRIES: usize = 4;
/// Default of [`CubatureOptions::max_candidates`]: at degree 40 the candidates' Vandermonde
/// matrix then holds at most `20 000 x 861` values (138 MB).
pub const DEFAULT_MAX_CANDIDATES: usize = 20_000;
/// Default of [`CubatureOptions::target_residual`].
pub const DEFAULT_TARGET_RESIDUAL: f64 = 1e-13;
/// Most candidates any options may ask for.
pub const MAX_CANDIDATES: usize = 200_000;
/// Most retries any options may ask for.
pub const MAX_RETRIES: usize = 10;

/// Options of [`CubatureRule::with_options`]: [`CubatureOptions::DEFAULT`] (degree 10) or
/// [`CubatureOptions::new`], and `with_*` setters.
///
/// ```
/// use rs_cubature::CubatureOptions;
/// let o = CubatureOptions::new(20).with_candidates_per_polynomial(8);
/// assert_eq!((o.degree, o.candidates_per_polynomial), (20, 8));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct CubatureOptions {
    /// The degree of exactness `n`, at most [`MAX_DEGREE`].
    pub degree: usize,
    /// `k` (`1..=1000`): the first attempt wants `k x dim P_n` Halton candidates inside the
    /// domain up to degree 20; each retry doubles it. Above degree 20 the candidates are
    /// `dim P_n` Halton points and boundary layers, after a first attempt on the nodes of the
    /// chord formula (see the crate documentation), and `k` is not used.
    pub candidates_per_polynomial: usize,
    /// Retries after the first attempt of Halton candidates (at most [`MAX_RETRIES`]), each
    /// with twice the candidates, up to `max_candidates` (above degree 20 the chord formula's
    /// attempt comes before them and is not counted).
    pub max_retries: usize,
    /// Most candidates of any attempt (at most [`MAX_CANDIDATES`]).
    pub max_candidates: usize,
    /// The largest residual accepted (see [`CubatureRule::residual`]), in `(0, 1)`.
    pub target_residual: f64,
    /// The set the rule integrates over: what `domain` fills under this rule (the moments
    /// and the candidates' classification both take it). Default [`FillRule::EvenOdd`].
    pub fill_rule: FillRule,
}

impl CubatureOptions {
    /// Degree 10 and the defaults above.
    pub const DEFAULT: CubatureOptions = CubatureOptions {
        degree: 10,
        candidates_per_polynomial: DEFAULT_CANDIDATES_PER_POLYNOMIAL,
        max_retries: DEFAULT_MAX_RETRIES,
        max_candidates: DEFAULT_MAX_CANDIDATES,
        target_residual: DEFAULT_TARGET_RESIDUAL,
        fill_rule: FillRule::EvenOdd,
    };

    /// The defaults with degree `degree`.
    pub const fn new(degree: usize) -> Self {
        Self::DEFAULT.with_degree(degree)
    }

    /// With another degree.
    pub const fn with_degree(mut self, degree: usize) -> Self {
        self.degree = degree;
        self
    }

    /// With another number of candidates per polynomial.
    pub const fn with_candidates_per_polynomial(mut self, k: usize) -> Self {
        self.candidates_per_polynomial = k;
        self
    }

    /// With another number of retries.
    pub const fn with_max_retries(mut self, retries: usize) -> Self {
        self.max_retries = retries;
        self
    }

    /// With another cap on the candidates.
    pub const fn with_max_candidates(mut self, candidates: usize) -> Self {
        self.max_candidates = candidates;
        self
    }

    /// With another target residual.
    pub const fn with_target_residual(mut self, residual: f64) -> Self {
        self.target_residual = residual;
        self
    }

    /// With another fill rule.
    pub const fn with_fill_rule(mut self, rule: FillRule) -> Self {
        self.fill_rule = rule;
        self
    }

    fn check(&self) -> Result<(), CubatureError> {
        let invalid =
            |name, value: String, range| Err(CubatureError::InvalidOption { name, value, range });
        if self.degree > MAX_DEGREE {
            return Err(CubatureError::DegreeTooHigh {
                degree: self.degree,
                max: MAX_DEGREE,
            });
        }
        if !(1..=1000).contains(&self.candidates_per_polynomial) {
            return invalid(
                "candidates_per_polynomial",
                self.candidates_per_polynomial.to_string(),
                "1..=1000",
            );
        }
        if self.max_retries > MAX_RETRIES {
            return invalid("max_retries", self.max_retries.to_string(), "0..=10");
        }
        if !(1..=MAX_CANDIDATES).contains(&self.max_candidates) {
            return invalid(
                "max_candidates",
                self.max_candidates.to_string(),
                "1..=200000",
            );
        }
        if !(self.target_residual > 0.0 && self.target_residual < 1.0) {
            return invalid(
                "target_residual",
                self.target_residual.to_string(),
                "(0, 1)",
            );
        }
        Ok(())
    }
}

impl Default for CubatureOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A positive interior cubature rule of degree `n` on a domain: at most `dim P_n =
/// (n + 1)(n + 2) / 2` nodes, each strictly inside the domain (classified
/// [`Location::Inside`](rs_contain::Location::Inside), farther than the boundary tolerance
/// from the boundary), each weight `> 0`, integrating every polynomial of total degree `<= n`
/// exactly up to [`CubatureRule::residual`] (Sommariva and Vianello's Caratheodory-Tchakaloff
/// compression; see the crate documentation for the method).
///
/// # Examples
///
/// ```
/// use rs_cubature::{dim_polynomials, CubatureRule};
/// use rs_spline::{circle, Domain, Point};
/// let disc = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let rule = CubatureRule::new(&disc, 8).unwrap();
/// assert!(rule.nodes().len() <= dim_polynomials(8));
/// assert!(rule.weights().iter().all(|&w| w > 0.0));
/// // The integral of x^2 y^4 over the unit disc is pi / 64.
/// let got = rule.integrate(|p| p.x.powi(2) * p.y.powi(4)).unwrap();
/// assert!((got - std::f64::consts::PI / 64.0).abs() < 1e-13);
/// ```
#[derive(Clone, Debug)]
pub struct CubatureRule {
    degree: usize,
    nodes: Vec<Point>,
    weights: Vec<f64>,
    residual: f64,
    candidates: usize,
}

/// A rule made from one set of candidates, and its residual.
struct Attempt {
    nodes: Vec<Point>,
    weights: Vec<f64>,
    residual: f64,
}

impl CubatureRule {
    /// The rule of degree `degree` with the default options.
    ///
    /// # Errors
    /// As [`CubatureRule::with_options`].
    pub fn new(domain: &Domain, degree: usize) -> Result<Self, CubatureError> {
        Self::with_options(domain, CubatureOptions::new(degree))
    }

    /// The rule of degree `options.degree`.
    ///
    /// Exact moments of the scaled Legendre basis (Green's theorem); then, attempt by attempt
    /// (above degree 20, first the nodes of a positive formula of vertical chords when it has at
    /// most `10 dim P_n` of them, see the crate documentation; then
    /// the first with `candidates_per_polynomial x dim P_n` Halton candidates up to degree
    /// 20, `dim P_n` and boundary layers above, each retry with twice as many, up to
    /// `max_candidates`): candidates strictly inside, a discrete
    /// orthonormal basis at them, Lawson-Hanson NNLS for non-negative weights matching the
    /// moments, and the residual computed afresh from the nodes and weights; the first rule
    /// whose residual is at most `target_residual` is returned.
    ///
    /// # Errors
    /// [`CubatureError::DegreeTooHigh`], [`CubatureError::InvalidOption`];
    /// [`CubatureError::OpenBoundary`]; [`CubatureError::Nesting`];
    /// [`CubatureError::MomentsNotConverged`]; [`CubatureError::NoArea`];
    /// [`CubatureError::AreaTooSmall`] below [`SMALLEST_AREA`];
    /// [`CubatureError::TooFewCandidates`] when the last attempt had fewer than `dim P_n`
    /// candidates inside or they did not resolve the polynomials (a domain too thin or too
    /// small against its bounding box); [`CubatureError::ResidualNotReached`].
    pub fn with_options(domain: &Domain, options: CubatureOptions) -> Result<Self, CubatureError> {
        options.check()?;
        // Checks the loops close, as everything after needs.
        let signs = fill_signs(domain, options.fill_rule)?;
        let degree = options.degree;
        let basis = LegendreBasis::new(degree, domain.bounding_box());
        let moments = basis_moments(domain, &signs, &basis, degree)?;
        let area = moments[0];
        if !(area > 0.0 && area.is_finite()) {
            return Err(CubatureError::NoArea { area });
        }
        if area < SMALLEST_AREA {
            return Err(CubatureError::AreaTooSmall {
                area,
                smallest: SMALLEST_AREA,
            });
        }
        let unit = UnitMoments::of(&moments);
        let classifier = Classifier::new(
            domain,
            ContainOptions::DEFAULT.with_fill_rule(options.fill_rule),
        )?;
        let mut candidates = Candidates::new(&classifier);
        let dim = basis.len();
        let mut error = None;
        let mut best_residual = f64::INFINITY;
        let layered = degree > CANDIDATES_GROWTH_DEGREE;
        let mut with_layers = Vec::new();
        if let Some(rule) = chord_rule(&classifier, &signs, &basis, area, &unit, &options) {
            return Ok(rule);
        }
        for attempt in 0..=options.max_retries {
            let (wanted, points, uniform) = if layered {
                let uniform = layered_candidates(
                    LayeredAttempt {
                        domain,
                        classifier: &classifier,
                        degree,
                        area,
                        attempt,
                        max_candidates: options.max_candidates,
                    },
                    &mut candidates,
                    &mut with_layers,
                );
                (with_layers.len(), with_layers.as_slice(), uniform)
            } else {
                let wanted = options
                    .candidates_per_polynomial
                    .saturating_mul(dim)
                    .saturating_mul(1 << attempt)
                    .min(options.max_candidates);
                candidates.grow_to(wanted);
                (wanted, candidates.points(), usize::MAX)
            };
            let too_few = |reason| CubatureError::TooFewCandidates {
                found: points.len(),
                generated: candidates.generated(),
                needed: wanted.max(dim),
                reason,
            };
            if points.len() < dim {
                error = Some(too_few("fewer than dim P_n"));
            } else {
                match compress(
                    &basis,
                    points,
                    Reference::Uniform(uniform),
                    &unit.moments,
                    options.target_residual,
                ) {
                    None => {
                        error = Some(too_few("they do not resolve the polynomials of the degree"))
                    }
                    Some(a) if a.residual <= options.target_residual => {
                        return Ok(Self {
                            degree,
                            nodes: a.nodes,
                            weights: unit.weights(a.weights),
                            residual: a.residual,
                            candidates: points.len(),
                        });
                    }
                    Some(a) => {
                        best_residual = best_residual.min(a.residual);
                        error = Some(CubatureError::ResidualNotReached {
                            residual: best_residual,
                            target: options.target_residual,
                            candidates: points.len(),
                        });
                    }
                }
            }
            if wanted >= options.max_candidates {
                break;
            }
        }
        let tried = if layered {
            with_layers.len()
        } else {
            candidates.points().len()
        };
        Err(error.unwrap_or(CubatureError::ResidualNotReached {
            residual: best_residual,
            target: options.target_residual,
            candidates: tried,
        }))
    }

    /// The degree of exactness.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The nodes, all strictly inside the domain, at most `dim P_n` of them.
    pub fn nodes(&self) -> &[Point] {
        &self.nodes
    }

    /// The weights, all `> 0`, one per node; they add up to the area (within the residual).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// `max_k |sum_i w_i phi_k(x_i) - m_k| / max_k |m_k|` over the scaled Legendre basis
    /// `phi_k` (see the crate documentation) with its exact moments `m_k`, computed afresh from
    /// the nodes and weights. The moment of `phi_0 = 1` is the area and `|phi_k| <= n + 1` on
    /// the bounding box, so a polynomial `p = sum_k c_k phi_k` is integrated within
    /// `residual x max|m| x sum_k |c_k|`.
    pub fn residual(&self) -> f64 {
        self.residual
    }

    /// The candidates of the attempt that made the rule.
    pub fn candidates(&self) -> usize {
        self.candidates
    }

    /// `sum_i w_i f(x_i)`.
    ///
    /// # Errors
    /// [`CubatureError::NonFiniteValue`] naming the first node where `f` is not finite.
    pub fn integrate(&self, mut f: impl FnMut(Point) -> f64) -> Result<f64, CubatureError> {
        let mut sum = 0.0;
        for (index, (&point, &w)) in self.nodes.iter().zip(&self.weights).enumerate() {
            let value = f(point);
            if !value.is_finite() {
                return Err(CubatureError::NonFiniteValue {
                    index,
                    point,
                    value,
                });
            }
            sum += w * value;
        }
        Ok(sum)
    }

    /// `sum_i w_i values[i]` with the values already computed at [`CubatureRule::nodes`].
    ///
    /// # Errors
    /// [`CubatureError::ValuesLength`] unless there is one value per node;
    /// [`CubatureError::NonFiniteValue`] naming the first non-finite value.
    pub fn integrate_values(&self, values: &[f64]) -> Result<f64, CubatureError> {
        if values.len() != self.nodes.len() {
            return Err(CubatureError::ValuesLength {
                expected: self.nodes.len(),
                got: values.len(),
            });
        }
        let mut at = values.iter();
        self.integrate(|_| at.next().copied().unwrap_or(f64::NAN))
    }
}

/// The most nodes of the chord formula per polynomial of the basis: beyond, it is left for
/// the layered candidates (a domain with many loops over one abscissa).
const CHORD_NODES_PER_POLYNOMIAL: usize = 10;

/// The rule compressed from the vertical-chord formula (see `chords`), when its degree is
/// above [`CANDIDATES_GROWTH_DEGREE`] (where the layered candidates would be tried), the
/// formula exists within its budget, and the rule is within the target; else `None` (the
/// layered attempts follow). `signs` are the curves' boundary signs the moments took, `area`
/// the domain's area in its own units (the formula's weights are).
fn chord_rule(
    classifier: &Classifier,
    signs: &[i64],
    basis: &LegendreBasis,
    area: f64,
    unit: &UnitMoments,
    options: &CubatureOptions,
) -> Option<CubatureRule> {
    let degree = options.degree;
    if degree <= CANDIDATES_GROWTH_DEGREE {
        return None;
    }
    let budget = (CHORD_NODES_PER_POLYNOMIAL * basis.len()).min(options.max_candidates);
    // The classifier's monotone pieces are the domain's (its refinement does not change them).
    let pieces = classifier.boxes().pieces();
    let formula = chord_formula(pieces, signs, basis, degree, area, budget)?;
    // The nodes the grid locator says are inside (a Gauss node within the boundary
    // tolerance of a loop, on a short chord, is left out with its weight), with the weights
    // of the unit moments (the same power of two).
    let locations = classifier.locator().locate_all(&formula.points);
    let (points, weights): (Vec<Point>, Vec<f64>) = formula
        .points
        .iter()
        .zip(&formula.weights)
        .zip(&locations)
        .filter(|(_, l)| **l == Location::Inside)
        .map(|((&p, &w), _)| (p, times_power_of_two(w, -unit.exponent)))
        .unzip();
    if points.len() < basis.len() {
        return None;
    }
    let a = compress(
        basis,
        &points,
        Reference::Rule(&weights),
        &unit.moments,
        options.target_residual,
    )?;
    (a.residual <= options.target_residual).then(|| CubatureRule {
        degree,
        nodes: a.nodes,
        weights: unit.weights(a.weights),
        residual: a.residual,
        candidates: points.len(),
    })
}

/// The least area a rule is made for, `2^-970` (about `1e-292`): the moments of a smaller
/// domain come out of sums whose terms are subnormal, each rounded to `2^-1074`, more than
/// `eps^2` of the area.
pub const SMALLEST_AREA: f64 = f64::MIN_POSITIVE / f64::EPSILON;

/// The moments divided by the power of two `2^e` nearest below the area, and `e`: the rule is
/// made for them, and its weights multiplied back by `2^e` ([`UnitMoments::weights`]). The
/// compression squares the moments' size (the NNLS's norms of residuals and gradients), which
/// overflowed for a domain larger than about `1e77` across and underflowed for one smaller than
/// `1e-77`; scaled so that the area is in `[1, 2)` it squares numbers near 1. A power of two
/// scales every value, every rounding and every comparison of the rule's making exactly: a
/// rule is the one the moments themselves gave, bit for bit, wherever they gave one, and a
/// domain of any size gets the rule of its unit-sized copy, scaled (test `scale.rs`).
struct UnitMoments {
    moments: Vec<f64>,
    exponent: i32,
}

impl UnitMoments {
    /// For `moments` whose first, the area, is at least [`SMALLEST_AREA`] and finite.
    fn of(moments: &[f64]) -> Self {
        let exponent = moments.first().map_or(0, |a| a.log2().floor() as i32);
        Self {
            moments: moments
                .iter()
                .map(|&m| times_power_of_two(m, -exponent))
                .collect(),
            exponent,
        }
    }

    /// The weights of the domain's rule from those of the rule made for [`UnitMoments::moments`].
    fn weights(&self, weights: Vec<f64>) -> Vec<f64> {
        weights
            .into_iter()
            .map(|w| times_power_of_two(w, self.exponent))
            .collect()
    }
}

/// Above this degree the candidates are `dim P_n` Halton points and boundary layers
/// ([`boundary_layers`]) instead of `k x dim P_n` Halton points. Halton points alone needed
/// more per polynomial as the degree grew (degree 20 succeeded with `12 N`, degree 30 needed
/// `16-18 N` and degree 40 about `22 N`): a positive rule of high degree has nodes near the
/// boundary that uniform points reach only in large numbers. Above it too, the chord
/// formula's nodes are the first attempt ([`chord_rule`]).
const CANDIDATES_GROWTH_DEGREE: usize = 20;

/// What [`layered_candidates`] needs of a rule's attempt above degree 20.
struct LayeredAttempt<'a> {
    domain: &'a Domain,
    classifier: &'a Classifier,
    degree: usize,
    /// The domain's area (the first moment).
    area: f64,
    attempt: usize,
    max_candidates: usize,
}

/// The candidates of attempt `a` above degree 20 into `out`: `dim P_n` Halton points inside
/// (doubled per retry, at most half of `max_candidates`, grown in `candidates`), then the
/// boundary layers ([`boundary_layers`], at [`layer_density`]) up to `max_candidates` in
/// all. Returns how many of them are Halton points (they come first).
fn layered_candidates(
    a: LayeredAttempt<'_>,
    candidates: &mut Candidates<'_>,
    out: &mut Vec<Point>,
) -> usize {
    let dim = dim_polynomials(a.degree);
    let halton = (dim << a.attempt).min(a.max_candidates / 2).max(1);
    candidates.grow_to(halton);
    out.clear();
    out.extend_from_slice(candidates.points());
    let room = a.max_candidates - out.len();
    let density = layer_density(a.attempt);
    let mut layers = boundary_layers(a.domain, a.classifier, a.degree, a.area, density, room);
    layers.truncate(room);
    out.extend(layers);
    candidates.points().len()
}

/// The density of the boundary layers of attempt `attempt` above degree 20 (see
/// [`boundary_layers`]): `1.5` times the Gauss points' density across the domain, `2.5 (n + 1)`
/// points per diagonal along the boundary, both times `sqrt 2` per retry (twice the points).
/// Measured at degree 30 on the paper's domains (with `dim P_n` Halton points besides): normal
/// density 1 and along 2 fail on `s4_disk_ellipse_segment` and `s5_lune` (about `2.6 N`
/// candidates), 0.5 and 3 on all three; 1.5 and 2.5 succeed on them, the disc, the L shape, the
/// cubic leaf and the nested fill-rule fixtures with `5-8 N`, the disc fails with 1 and 2 and
/// `3 N` Halton points.
fn layer_density(attempt: usize) -> LayerDensity {
    let growth = std::f64::consts::SQRT_2.powi(attempt.min(MAX_RETRIES) as i32);
    LayerDensity {
        normal: 1.5 * growth,
        along: 2.5 * growth,
    }
}

/// Outer NNLS iterations from one full pass over the candidates' gradients to the next; in
/// between only the `N` columns with the largest gradients at the last full pass are scored.
/// The full passes (`M N` per iteration, `M` from `12 N` to `23 N`, memory-bound) were most of
/// the NNLS's work. Measured (CPU time, one rule, medians; working set `N` or `2 N`, a full
/// pass every 4 or 8 iterations, against every iteration): degree 30 on the paper's three
/// domains 281, 890, 1114 ms -> 273, 721, 845 ms with `N` and 4 (`2 N` and 4: 258, 733, 900;
/// `2 N` and 8: 254, 688, 894); degree 40 2097, 5820, 6122 ms -> 2141, 4295, 4785 ms (`2 N`
/// and 4: 2156, 5152, 4938). The iterations grow (405 -> 510 at degree 40 on `s5_lune`: a
/// stale working set picks less well) but each costs less.
const FULL_GRADIENT_PASS_EVERY: usize = 4;

/// Most steps of iterative refinement of the weights (each solves on the passive set's
/// factorisation, `O(N^2)`); one or two bring the residual to rounding on the paper's domains.
const MAX_REFINEMENTS: usize = 3;

/// The rule from the candidates `points` (at least `dim P_n` of them) with their `reference`
/// rule (see [`Reference`]), or `None` if they do not resolve the basis. A rule made on a basis
/// the normalising pass orthonormalised (see `orthogonal`) that misses `target_residual` is
/// made again on the regularised one, and the one with the smaller residual is kept: the pass
/// never costs a rule the candidates allow without it (in the survey that set its limit, no
/// rule needed this).
fn compress(
    basis: &LegendreBasis,
    points: &[Point],
    reference: Reference<'_>,
    moments: &[f64],
    target_residual: f64,
) -> Option<Attempt> {
    better_of_passes(target_residual, |normalise| {
        compress_with(
            basis,
            points,
            reference,
            moments,
            target_residual,
            normalise,
        )
    })
}

/// The rule `make(true)` makes with the normalising pass allowed (with whether the pass was
/// made), unless the pass was made and the rule misses `target`: then `make(false)`'s, the
/// rule without the pass, if its residual is no larger.
fn better_of_passes(
    target: f64,
    mut make: impl FnMut(bool) -> Option<(Attempt, bool)>,
) -> Option<Attempt> {
    let (attempt, normalised) = make(true)?;
    if normalised
        && attempt.residual > target
        && let Some((again, _)) = make(false)
        && again.residual <= attempt.residual
    {
        return Some(again);
    }
    Some(attempt)
}

/// [`compress`] on the basis orthonormalised with the normalising pass allowed
/// (`normalise`) or not; with the rule, whether the pass was made.
fn compress_with(
    basis: &LegendreBasis,
    points: &[Point],
    reference: Reference<'_>,
    moments: &[f64],
    target_residual: f64,
    normalise: bool,
) -> Option<(Attempt, bool)> {
    let n = basis.len();
    let mut scratch = vec![0.0; basis.scratch_len()];
    let mut vt = DMatrix::zeros(n, points.len());
    for (p, column) in points.iter().zip(vt.as_mut_slice().chunks_exact_mut(n)) {
        basis.values_into(*p, &mut scratch, column);
    }
    let orthonormal = orthonormalise(vt, moments, reference, normalise)?;
    let b = orthonormal.b.as_slice();
    // LHDM: up to N / 20 columns enter at once, those within half the best gradient whose
    // mutual cosines are at most 0.2. Measured at degree 20 on the paper's domains: about 30
    // iterations instead of 240 for Lawson-Hanson, the NNLS 8 times faster. Between full
    // passes over the gradients only the N columns with the largest ones are scored (see
    // `nnls`'s working set).
    let options = NnlsOptions {
        residual_tolerance: 1e-15 * dot(b, b).sqrt(),
        max_entering: n.div_ceil(20),
        gradient_fraction: 0.5,
        max_cosine: 0.2,
        // Above degree 20 only (see `HIGH_DEGREE_BASIS`).
        working_set: if n > HIGH_DEGREE_BASIS { n } else { 0 },
        full_pass_every: FULL_GRADIENT_PASS_EVERY,
        // The chord formula's rules are new: they take the faster, differently rounded,
        // inserts (the layered candidates' rules keep their bits).
        blocked_inserts: matches!(reference, Reference::Rule(_)),
    };
    let scale = moments.iter().fold(0.0f64, |a, m| a.max(m.abs()));
    let mut stall = StallTest::new(n, target_residual);
    let solution = nnls(orthonormal.qt.as_slice(), n, b, options, |r| {
        stall.stalled(orthonormal.moment_error(r) / scale)
    });
    let nodes: Vec<Point> = solution.columns().iter().map(|&j| points[j]).collect();
    let mut weights = solution.values().to_vec();
    // Iterative refinement on the passive set, in the basis itself: the residual there is
    // computed accurately, mapped as the moments were and solved for a correction.
    let mut values = DMatrix::zeros(n, nodes.len());
    for (p, column) in nodes.iter().zip(values.as_mut_slice().chunks_exact_mut(n)) {
        basis.values_into(*p, &mut scratch, column);
    }
    let mut res = residual_of(&values, &weights, moments);
    // A stalled attempt is far from the target: refinement cannot bring it there.
    let refinements = if solution.stalled() {
        0
    } else {
        MAX_REFINEMENTS
    };
    for _ in 0..refinements {
        let rho = DVector::from_iterator(
            n,
            moments
                .iter()
                .zip(values_times(&values, &weights))
                .map(|(m, s)| m - s),
        );
        let correction = solution.solve_passive(orthonormal.map(rho.as_slice()).as_slice());
        let tried: Vec<f64> = weights
            .iter()
            .zip(&correction)
            .map(|(w, c)| w + c)
            .collect();
        if tried.iter().any(|&w| w.is_nan() || w <= 0.0) {
            break;
        }
        let r = residual_of(&values, &tried, moments);
        if r < res {
            weights = tried;
            res = r;
        } else {
            break;
        }
    }
    if let Reference::Rule(_) = reference
        && let Some(better) = refine_by_conjugate_gradients(&values, &weights, moments)
    {
        weights = better;
    }
    // Nodes and weights by candidate index; zero weights (an inner loop cut short) dropped.
    let mut chosen: Vec<(usize, Point, f64)> = solution
        .columns()
        .iter()
        .zip(nodes)
        .zip(weights)
        .filter(|(_, w)| *w > 0.0)
        .map(|((&j, p), w)| (j, p, w))
        .collect();
    chosen.sort_by_key(|c| c.0);
    let nodes: Vec<Point> = chosen.iter().map(|c| c.1).collect();
    let weights: Vec<f64> = chosen.iter().map(|c| c.2).collect();
    let residual = residual(basis, &nodes, &weights, moments);
    Some((
        Attempt {
            nodes,
            weights,
            residual,
        },
        orthonormal.normalised,
    ))
}

/// The compression's stall test: is the NNLS making so little progress that the rule's
/// residual will not reach the target in this attempt?
///
/// Lawson-Hanson terminates, in exact arithmetic, at the point of the cone of the candidates'
/// columns nearest the moments; when the moments lie outside that cone (no positive weights
/// on these candidates match them: too few candidates at a high degree) the residual
/// converges to that distance, slowly, and the iteration runs to its cap. The test follows the
/// residual in the rule's own measure, `e = max_k |m_k - sum_i w_i phi_k(x_i)| / max_k |m_k|`
/// of the current iterate, and reports a stall when its best value fell by less than
/// [`STALL_FACTOR`] over the last `window` outer iterations while still above the target.
/// Measured at degree 30 on the paper's domains with `12 x dim P_n` candidates (without the
/// test): `e` at `2e-3` to `4e-3` after 50 iterations and still above `2e-3` after 1588 (the
/// cap), about 3 s of NNLS per attempt; with the test they stop after about 150 iterations.
/// The attempts that succeed end within about 550 iterations with `e` falling by orders of
/// magnitude per window; the stalls seen at degrees 30 and 40 had `e` of `4e-4` to `7e-3`
/// (once `2e-6`, after 939 iterations). A false stall costs only a retry with twice the
/// candidates; a rule is accepted on its final residual alone.
struct StallTest {
    /// `max(N / 4, STALL_MIN_WINDOW)` iterations for `N` basis polynomials.
    window: usize,
    target_residual: f64,
    /// The best `e` up to each iteration so far (at most the NNLS's `3 N + 100`).
    best: Vec<f64>,
}

/// The least progress over a window that is not a stall: the best residual halves.
const STALL_FACTOR: f64 = 2.0;
/// The shortest window of [`StallTest`], in outer iterations.
const STALL_MIN_WINDOW: usize = 50;

impl StallTest {
    fn new(n: usize, target_residual: f64) -> Self {
        Self {
            window: (n / 4).max(STALL_MIN_WINDOW),
            target_residual,
            best: Vec::new(),
        }
    }

    /// Records `e` of the current iterate; `true` on a stall.
    fn stalled(&mut self, e: f64) -> bool {
        let best = self.best.last().map_or(e, |&b| b.min(e));
        self.best.push(best);
        let now = self.best.len() - 1;
        now >= self.window
            && best > self.target_residual
            && self.best[now - self.window] < STALL_FACTOR * best
    }
}

/// `sum_i w_i phi(x_i)` from the basis values at the nodes (one column per node).
fn values_times(values: &DMatrix<f64>, weights: &[f64]) -> Vec<f64> {
    (values * DVector::from_column_slice(weights))
        .as_slice()
        .to_vec()
}

/// Most conjugate-gradient steps of [`refine_by_conjugate_gradients`].
const MAX_CG_STEPS: usize = 40;

/// Refinement of the weights in the directions the nodes resolve well: conjugate gradients on
/// the normal equations (CGLS) of `V_P^T c = rho`, `rho = m - V_P^T w` compensated
/// ([`moment_errors`]), stopped early. The residual of a rule
/// compressed from the chord formula lies mostly along the large singular values of its
/// nodes' Vandermonde matrix (measured on `s3_m_shape` at degree 40: `1.8e-14` of its
/// `1.8e-14` in directions of singular value `>= 1`, where a correction of norm `7e-16`
/// removes it), while the full solve of the refinement above also inverts directions of
/// singular value `1e-8` and below, where the rounding of `rho` in plain sums (about
/// `eps x sum |w phi|`, as large as `rho` itself) becomes corrections far larger than the
/// weights. CGLS reaches the large singular values first. The weights `w + c` of the step
/// with the smallest residual (by the recurrence's) whose weights are all positive are
/// returned when their compensated residual is below `w`'s; else `None`. Measured at degree
/// 40 against moments to 34 digits (mpmath), true residuals without / with it: `s3_m_shape`
/// `2.1e-15` / `7.3e-16`, `s4_disk_ellipse_segment` `2.2e-15` / `5.9e-16`, `s5_lune`
/// `3.6e-15` / `6.6e-16`.
fn refine_by_conjugate_gradients(
    values: &DMatrix<f64>,
    weights: &[f64],
    moments: &[f64],
) -> Option<Vec<f64>> {
    let worst = |r: &[f64]| r.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let rho = moment_errors(values, weights, moments);
    let start = worst(&rho);
    let mut best: Option<(f64, Vec<f64>)> = None;
    // CGLS for min ||A c - rho||, A = V_P^T (`values`, one column per node).
    let mut c = DVector::zeros(weights.len());
    let mut r = DVector::from_column_slice(&rho);
    let mut g = values.tr_mul(&r);
    let mut p = g.clone();
    let mut gamma = g.norm_squared();
    for _ in 0..MAX_CG_STEPS {
        if gamma.is_nan() || gamma <= 0.0 {
            break;
        }
        let q = values * &p;
        let qq = q.norm_squared();
        if qq.is_nan() || qq <= 0.0 {
            break;
        }
        let alpha = gamma / qq;
        c.axpy(alpha, &p, 1.0);
        r.axpy(-alpha, &q, 1.0);
        // The recurrence's residual `r` stands for `rho - A c` (its rounding is relative to
        // its own size, not the moments'); the step kept is checked, compensated, at the end.
        let e = worst(r.as_slice());
        if e < best.as_ref().map_or(start, |b| b.0) {
            let tried: Vec<f64> = weights.iter().zip(c.iter()).map(|(w, d)| w + d).collect();
            if tried.iter().all(|&w| w > 0.0) {
                best = Some((e, tried));
            }
        }
        g = values.tr_mul(&r);
        let next = g.norm_squared();
        p = &g + &p * (next / gamma);
        gamma = next;
    }
    let (_, tried) = best?;
    (worst(&moment_errors(values, &tried, moments)) < start).then_some(tried)
}

/// `m - V^T w` from the basis values `values` (one column per node), compensated: each
/// product's and each sum's rounding error kept exactly (`fma`, Knuth's two-sum) and added
/// up beside the sums (Ogita, Rump and Oishi's `Dot2`: as accurate as plain sums in twice the
/// working precision), so that `rho` is known to far below its own size.
fn moment_errors(values: &DMatrix<f64>, weights: &[f64], moments: &[f64]) -> Vec<f64> {
    let n = values.nrows();
    let mut high = moments.to_vec();
    let mut low = vec![0.0; n];
    for (column, &w) in values.as_slice().chunks_exact(n).zip(weights) {
        for ((h, l), &v) in high.iter_mut().zip(&mut low).zip(column) {
            let product = -w * v;
            let product_error = (-w).mul_add(v, -product);
            let sum = *h + product;
            let back = sum - *h;
            let sum_error = (*h - (sum - back)) + (product - back);
            *h = sum;
            *l += sum_error + product_error;
        }
    }
    high.iter().zip(&low).map(|(h, l)| h + l).collect()
}

/// [`residual`] from the basis values at the nodes.
fn residual_of(values: &DMatrix<f64>, weights: &[f64], moments: &[f64]) -> f64 {
    relative_moment_error(&values_times(values, weights), moments)
}

/// `max_k |sums_k - m_k| / max_k |m_k|`: the residual's measure.
fn relative_moment_error(sums: &[f64], moments: &[f64]) -> f64 {
    let scale = moments.iter().fold(0.0f64, |a, m| a.max(m.abs()));
    let worst = sums
        .iter()
        .zip(moments)
        .fold(0.0f64, |a, (s, m)| a.max((s - m).abs()));
    worst / scale
}

/// `max_k |sum_i w_i phi_k(x_i) - m_k| / max_k |m_k|`, from the nodes and weights.
fn residual(basis: &LegendreBasis, nodes: &[Point], weights: &[f64], moments: &[f64]) -> f64 {
    let n = basis.len();
    let mut scratch = vec![0.0; basis.scratch_len()];
    let mut values = vec![0.0; n];
    let mut sums = vec![0.0; n];
    for (&p, &w) in nodes.iter().zip(weights) {
        basis.values_into(p, &mut scratch, &mut values);
        for (s, v) in sums.iter_mut().zip(&values) {
            *s += w * v;
        }
    }
    relative_moment_error(&sums, moments)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rule made after the normalising pass that misses its target is made again without
    /// the pass, and the one with the smaller residual is kept; a rule within its target, or
    /// made without the pass, is kept as it is.
    #[test]
    fn a_normalised_rule_that_misses_its_target_is_made_again_without_the_pass() {
        let rule = |residual: f64| Attempt {
            nodes: vec![Point::new(residual, 0.0)],
            weights: vec![1.0],
            residual,
        };
        let target = 1e-13;
        // (first rule's residual, pass made, second rule's residual or none): the residual of
        // the rule kept, and whether the second was made.
        let cases = [
            (1e-12, true, Some(1e-14), 1e-14, true),
            (1e-12, true, Some(1e-11), 1e-12, true),
            (1e-12, true, None, 1e-12, true),
            (1e-12, false, Some(1e-14), 1e-12, false),
            (1e-14, true, Some(1e-15), 1e-14, false),
        ];
        for (first, made, second, kept, again) in cases {
            let mut asked = Vec::new();
            let got = better_of_passes(target, |normalise| {
                asked.push(normalise);
                if normalise {
                    Some((rule(first), made))
                } else {
                    second.map(|r| (rule(r), false))
                }
            })
            .unwrap();
            assert_eq!(got.residual, kept, "{first} {made} {second:?}");
            assert_eq!(asked, if again { vec![true, false] } else { vec![true] });
        }
    }

    /// On the L shape at degree 22 (the layered candidates' first attempt) the normalising pass is
    /// made, and `compress` keeps that rule: within the target, and also with a target no
    /// rule reaches (the rule without the pass has the larger residual there).
    #[test]
    fn the_l_shape_at_degree_22_takes_the_normalising_pass() {
        let domain = rs_testkit::inrs_fixture("l_shape").domain;
        let degree = 22;
        let basis = LegendreBasis::new(degree, domain.bounding_box());
        let moments = basis_moments(
            &domain,
            &fill_signs(&domain, FillRule::EvenOdd).unwrap(),
            &basis,
            degree,
        )
        .unwrap();
        let classifier = Classifier::new(&domain, ContainOptions::DEFAULT).unwrap();
        let mut candidates = Candidates::new(&classifier);
        let mut points = Vec::new();
        let uniform = layered_candidates(
            LayeredAttempt {
                domain: &domain,
                classifier: &classifier,
                degree,
                area: moments[0],
                attempt: 0,
                max_candidates: DEFAULT_MAX_CANDIDATES,
            },
            &mut candidates,
            &mut points,
        );
        let bits = |a: &Attempt| -> Vec<u64> {
            a.nodes
                .iter()
                .flat_map(|p| [p.x, p.y])
                .chain(a.weights.iter().copied())
                .map(f64::to_bits)
                .collect()
        };
        for target in [DEFAULT_TARGET_RESIDUAL, 1e-30] {
            let run = |normalise| {
                compress_with(
                    &basis,
                    &points,
                    Reference::Uniform(uniform),
                    &moments,
                    target,
                    normalise,
                )
                .unwrap()
            };
            let (normalised, made) = run(true);
            assert!(made, "the pass is made here");
            let (regularised, made) = run(false);
            assert!(!made);
            assert!(normalised.residual < regularised.residual);
            let got = compress(
                &basis,
                &points,
                Reference::Uniform(uniform),
                &moments,
                target,
            )
            .unwrap();
            assert_eq!(bits(&got), bits(&normalised));
        }
    }

    /// [`chord_rule`] of `domain` at `degree` with the default options (even-odd), and the
    /// basis and moments it was made against.
    fn chord_rule_of(
        domain: &Domain,
        degree: usize,
    ) -> (Option<CubatureRule>, LegendreBasis, Vec<f64>) {
        let classifier = Classifier::new(domain, ContainOptions::DEFAULT).unwrap();
        let signs = fill_signs(domain, FillRule::EvenOdd).unwrap();
        let basis = LegendreBasis::new(degree, domain.bounding_box());
        let moments = basis_moments(domain, &signs, &basis, degree).unwrap();
        let unit = UnitMoments::of(&moments);
        let options = CubatureOptions::new(degree);
        let rule = chord_rule(&classifier, &signs, &basis, moments[0], &unit, &options);
        (rule, basis, moments)
    }

    /// Above degree 20 the first attempt compresses the chord formula: on the disc with an
    /// ellipse segment (vertical tangents, a corner) at degrees 21, 30 and 36 it makes a rule
    /// within the target from the formula's nodes (fewer than the layered attempt's, about
    /// `2 dim P_n` against `5 dim P_n`); at degree 20 it is not tried.
    #[test]
    fn the_chord_formula_makes_the_first_rule_above_degree_20() {
        let domain = rs_testkit::inrs_fixture("s4_disk_ellipse_segment").domain;
        for (degree, made) in [(20, false), (21, true), (30, true), (36, true)] {
            let (rule, basis, _) = chord_rule_of(&domain, degree);
            assert_eq!(rule.is_some(), made, "degree {degree}");
            if let Some(rule) = rule {
                assert!(rule.residual() <= DEFAULT_TARGET_RESIDUAL);
                assert!(rule.weights().iter().all(|&w| w > 0.0));
                assert!(rule.nodes().len() <= basis.len());
                // The formula's nodes, fewer than the layered attempt's (about 5 dim P_n).
                assert!(rule.candidates() < 4 * basis.len(), "{}", rule.candidates());
            }
        }
    }

    /// Where the chord formula is over its budget (three nested discs at degree 21: their
    /// stacked chords need more than `10 dim P_n` nodes) the rule comes from the Halton points
    /// and boundary layers after it, within the target: the layered attempts above degree 20,
    /// end to end.
    #[test]
    fn a_formula_over_its_budget_falls_back_to_the_layered_candidates() {
        let path = rs_testkit::fixture_path("fill-rule/three_nested.json");
        let domain = rs_io::json::domain_from_json_file(&path).unwrap();
        let degree = 21;
        let (chord, basis, moments) = chord_rule_of(&domain, degree);
        assert!(chord.is_none());
        let rule = CubatureRule::new(&domain, degree).unwrap();
        assert!(
            rule.residual() <= DEFAULT_TARGET_RESIDUAL,
            "{}",
            rule.residual()
        );
        assert!(rule.weights().iter().all(|&w| w > 0.0));
        assert!(rule.nodes().len() <= basis.len());
        let sum: f64 = rule.weights().iter().sum();
        assert!(
            (sum - moments[0]).abs() <= 1e-13 * moments[0],
            "{sum} vs {}",
            moments[0]
        );
    }

    /// The moments' errors are compensated: `0 - (1 + 1e16 - 1e16)` is `-1`, where plain sums
    /// lose the `1` (`1 + 1e16` rounds to `1e16`); and a product's rounding is kept too.
    #[test]
    fn moment_errors_keep_what_plain_sums_lose() {
        let values = DMatrix::from_column_slice(1, 3, &[1.0, 1e16, -1e16]);
        assert_eq!(values_times(&values, &[1.0; 3]), vec![0.0]);
        assert_eq!(moment_errors(&values, &[1.0; 3], &[0.0]), vec![-1.0]);
        // (1 + 2^-30)^2 = 1 + 2^-29 + 2^-60: the product rounds the last term away.
        let x = 1.0 + 2f64.powi(-30);
        let values = DMatrix::from_column_slice(1, 1, &[x]);
        let got = moment_errors(&values, &[x], &[1.0 + 2f64.powi(-29)]);
        assert_eq!(got, vec![-(2f64.powi(-60))]);
    }

    #[test]
    fn a_residual_halving_every_window_never_stalls() {
        // N = 400: a window of 100 iterations; e halves every 100 iterations.
        let mut t = StallTest::new(400, 1e-13);
        for i in 0..1300 {
            let e = 0.5f64.powf(i as f64 / 99.0);
            assert!(!t.stalled(e), "iteration {i}");
        }
    }

    #[test]
    fn a_flat_residual_stalls_after_one_window_but_not_below_the_target() {
        let mut t = StallTest::new(400, 1e-13);
        let first = (0..1000).position(|_| t.stalled(3e-3));
        assert_eq!(first, Some(100));
        let mut t = StallTest::new(400, 1e-13);
        assert!((0..1000).all(|_| !t.stalled(5e-14)));
        // The short window of small bases.
        let mut t = StallTest::new(21, 1e-13);
        assert_eq!(
            (0..1000).position(|_| t.stalled(1.0)),
            Some(STALL_MIN_WINDOW)
        );
    }
}
