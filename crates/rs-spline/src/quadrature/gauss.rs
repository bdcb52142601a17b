//! Gauss-Legendre rules: computed once per number of nodes, kept for the life of the process.
//!
//! This is the one cache of rules of the workspace: the adaptive rule, the exact rules of
//! Green's-theorem integrals along polynomial pieces, spline energies and the benchmarks'
//! references all take their nodes and weights from [`gauss_rule`].

use std::sync::OnceLock;

/// The most nodes of a rule [`gauss_rule`] gives (and so the most rules it keeps): enough for
/// the exact integrals of the cubature moments (at most `ceil(32 (40 + 2) / 2) = 672` nodes for
/// curves of degree 32 and moments of degree 40). Keeping every rule up to this size would
/// take about 8 MiB; only the rules asked for are computed.
pub const MAX_GAUSS_NODES: usize = 1024;

/// The rules by number of nodes less one, each computed by its first user.
static RULES: [OnceLock<GaussRule>; MAX_GAUSS_NODES] = [const { OnceLock::new() }; MAX_GAUSS_NODES];

/// The `n`-node Gauss-Legendre rule on `[-1, 1]`: nodes ascending, weights positive, exact for
/// polynomials of degree `2 n - 1`.
#[derive(Debug, PartialEq)]
pub struct GaussRule {
    nodes: Vec<f64>,
    weights: Vec<f64>,
}

impl GaussRule {
    /// The nodes `x_1 < ... < x_n` in `(-1, 1)`.
    #[inline]
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// The weights `w_i > 0` (summing to 2).
    #[inline]
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// The rule on `[a, b]`: the half-length `h = (b - a) / 2` and the pairs `(t_i, w_i)`
    /// with `t_i = (a + b) / 2 + h x_i`, so that `integral_a^b f ~ h sum_i w_i f(t_i)`.
    /// Every user maps the nodes through this one formula (so a rule on `[0, 1]` puts its
    /// nodes at the same `f64` values for all of them).
    #[inline]
    pub fn on(&self, a: f64, b: f64) -> (f64, impl Iterator<Item = (f64, f64)> + '_) {
        let (half, mid) = (0.5 * (b - a), 0.5 * (a + b));
        let pairs = self
            .nodes
            .iter()
            .zip(&self.weights)
            .map(move |(&x, &w)| (mid + half * x, w));
        (half, pairs)
    }
}

/// The `n`-node Gauss-Legendre rule, computed on first use and kept (thread-safe: each rule is
/// computed once, by the first caller; later calls read it without locking). `None` for
/// `n = 0` or `n >` [`MAX_GAUSS_NODES`].
///
/// # Examples
///
/// ```
/// use rs_spline::quadrature::gauss_rule;
/// let rule = gauss_rule(3).unwrap();
/// // Exact for degree 5: the integral of x^4 over [-1, 1] is 2 / 5.
/// let i: f64 = rule.nodes().iter().zip(rule.weights()).map(|(x, w)| w * x.powi(4)).sum();
/// assert!((i - 0.4).abs() < 1e-15);
/// assert!(std::ptr::eq(rule, gauss_rule(3).unwrap()));
/// assert!(gauss_rule(0).is_none());
/// ```
#[inline]
pub fn gauss_rule(n: usize) -> Option<&'static GaussRule> {
    let cell = RULES.get(n.checked_sub(1)?)?;
    Some(cell.get_or_init(|| gauss_legendre(n)))
}

/// [`gauss_rule`] for a number of nodes fixed at compile time, checked there to be in
/// `1 ..= MAX_GAUSS_NODES` (so there is no `None` to handle).
#[inline]
pub fn fixed_gauss_rule<const N: usize>() -> &'static GaussRule {
    const { assert!(N >= 1 && N <= MAX_GAUSS_NODES) };
    RULES[N - 1].get_or_init(|| gauss_legendre(N))
}

/// The rule with the fewest nodes that is exact for polynomials of degree `degree`:
/// `ceil((degree + 1) / 2)` nodes (at least one), `None` beyond [`MAX_GAUSS_NODES`].
#[inline]
pub fn gauss_rule_exact_for(degree: usize) -> Option<&'static GaussRule> {
    gauss_rule((degree + 1).div_ceil(2).max(1))
}

/// Nodes and weights of the `n`-point rule, computed by Newton's method on the Legendre
/// polynomial `P_n` (at most 100 steps per node).
fn gauss_legendre(n: usize) -> GaussRule {
    let mut nodes = vec![0.0; n];
    let mut weights = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        // Chebyshev-like initial guess for the i-th largest root.
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (p, d) = legendre(n, x);
            dp = d;
            let dx = p / d;
            x -= dx;
            if dx.abs() <= 1e-16 {
                break;
            }
        }
        let (_, d) = legendre(n, x);
        if d.is_finite() {
            dp = d;
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        nodes[i] = -x;
        nodes[n - 1 - i] = x;
        weights[i] = w;
        weights[n - 1 - i] = w;
    }
    GaussRule { nodes, weights }
}

/// `(P_n(x), P_n'(x))` by the three-term recurrence.
fn legendre(n: usize, x: f64) -> (f64, f64) {
    let (mut p0, mut p1) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=n {
        let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
        p0 = p1;
        p1 = p2;
    }
    let d = n as f64 * (x * p1 - p0) / (x * x - 1.0);
    (p1, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_are_exact_for_their_degree() {
        for n in [1, 2, 5, 16, 24, 97, 672] {
            let rule = gauss_rule(n).unwrap();
            assert_eq!(rule.nodes().len(), n);
            assert!((rule.weights().iter().sum::<f64>() - 2.0).abs() < 1e-13);
            assert!(rule.nodes().windows(2).all(|p| p[0] < p[1]));
            let top = 2 * n - 2;
            let integral: f64 = rule
                .nodes()
                .iter()
                .zip(rule.weights())
                .map(|(x, w)| w * x.powi(top as i32))
                .sum();
            assert!((integral - 2.0 / (top + 1) as f64).abs() < 1e-13, "{n}");
        }
    }

    #[test]
    fn the_cache_is_bounded_and_shared() {
        assert!(gauss_rule(0).is_none());
        assert!(gauss_rule(MAX_GAUSS_NODES + 1).is_none());
        assert!(gauss_rule(MAX_GAUSS_NODES).is_some());
        assert!(std::ptr::eq(
            fixed_gauss_rule::<7>(),
            gauss_rule(7).unwrap()
        ));
        let threads: Vec<_> = (0..4)
            .map(|_| std::thread::spawn(|| gauss_rule(40).unwrap() as *const GaussRule as usize))
            .collect();
        let first = gauss_rule(40).unwrap() as *const GaussRule as usize;
        for t in threads {
            assert_eq!(t.join().unwrap(), first);
        }
        assert_eq!(gauss_rule_exact_for(0).unwrap().nodes().len(), 1);
        assert_eq!(gauss_rule_exact_for(5).unwrap().nodes().len(), 3);
        assert_eq!(gauss_rule_exact_for(6).unwrap().nodes().len(), 4);
    }

    #[test]
    fn mapped_nodes_on_the_unit_interval() {
        let rule = gauss_rule(4).unwrap();
        let (half, pairs) = rule.on(0.0, 1.0);
        assert_eq!(half, 0.5);
        for ((t, w), (&x, &wx)) in pairs.zip(rule.nodes().iter().zip(rule.weights())) {
            // Bit for bit the usual `(x + 1) / 2`.
            assert_eq!(t, 0.5 * (x + 1.0));
            assert_eq!(w, wx);
        }
    }
}
