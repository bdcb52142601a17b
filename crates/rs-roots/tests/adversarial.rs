//! Root finders against polynomials built from known roots: adversarial cases and property tests.

use proptest::prelude::*;
use rs_roots::{Polynomial, RootsError, bernstein_roots_in, real_roots_in};

type Finder = fn(&Polynomial, f64, f64) -> Result<Vec<f64>, RootsError>;
const FINDERS: [(&str, Finder); 2] = [
    ("companion", real_roots_in),
    ("bernstein", bernstein_roots_in),
];

/// Asserts that `found` matches the distinct `expected` roots lying in `[a, b]` one to one,
/// each within `tol`.
fn assert_roots(name: &str, found: &[f64], expected: &[f64], a: f64, b: f64, tol: f64) {
    let mut exp: Vec<f64> = expected
        .iter()
        .copied()
        .filter(|r| (a..=b).contains(r))
        .collect();
    exp.sort_by(f64::total_cmp);
    exp.dedup();
    assert_eq!(
        found.len(),
        exp.len(),
        "{name}: found {found:?}, expected {exp:?} on [{a}, {b}]"
    );
    for (f, e) in found.iter().zip(&exp) {
        assert!(
            (f - e).abs() <= tol,
            "{name}: root {f} vs expected {e} (tol {tol})"
        );
    }
    assert!(
        found.windows(2).all(|w| w[0] < w[1]),
        "{name}: not ascending {found:?}"
    );
}

fn check_all(expected: &[f64], a: f64, b: f64, tol: f64) {
    let p = Polynomial::from_roots(expected);
    for (name, finder) in FINDERS {
        let found = finder(&p, a, b).unwrap();
        assert_roots(name, &found, expected, a, b, tol);
    }
}

fn check_none(p: &Polynomial, a: f64, b: f64) {
    for (name, finder) in FINDERS {
        let found = finder(p, a, b).unwrap();
        assert!(found.is_empty(), "{name}: spurious roots {found:?}");
    }
}

#[test]
fn t_cubed_is_one_root() {
    // Known hazard: the unbounded Schur iteration hangs on the companion matrix of t^3.
    let p = Polynomial::new(vec![0.0, 0.0, 0.0, 1.0]);
    for (name, finder) in FINDERS {
        let r = finder(&p, -1.0, 1.0).unwrap();
        assert_eq!(r.len(), 1, "{name}: {r:?}");
        assert!(r[0].abs() < 1e-5, "{name}: {r:?}");
    }
}

#[test]
fn t4_plus_one_has_no_real_roots() {
    check_none(&Polynomial::new(vec![1.0, 0.0, 0.0, 0.0, 1.0]), -10.0, 10.0);
}

#[test]
fn shifted_quartic_plus_one_has_no_real_roots() {
    // (t - 0.5)^4 + 1
    let p = &Polynomial::from_roots(&[0.5; 4]) + &Polynomial::constant(1.0);
    check_none(&p, -10.0, 10.0);
}

#[test]
fn t10_minus_c() {
    for &c in &[1.0, 0.5, 1e-3, 2.0] {
        let mut coeffs = vec![0.0; 11];
        coeffs[0] = -c;
        coeffs[10] = 1.0;
        let p = Polynomial::new(coeffs);
        let r0: f64 = f64::powf(c, 0.1);
        for (name, finder) in FINDERS {
            let r = finder(&p, -2.0, 2.0).unwrap();
            assert_eq!(r.len(), 2, "{name}, c = {c}: {r:?}");
            assert!(
                (r[0] + r0).abs() < 1e-12 && (r[1] - r0).abs() < 1e-12,
                "{name}: {r:?}"
            );
        }
    }
}

#[test]
fn t11_minus_at() {
    // Known hazard: t^11 - a t was one of the hanging cases. Roots: 0 and +-a^(1/10).
    let a = 0.3;
    let mut coeffs = vec![0.0; 12];
    coeffs[1] = -a;
    coeffs[11] = 1.0;
    let p = Polynomial::new(coeffs);
    let r0: f64 = f64::powf(a, 0.1);
    for (name, finder) in FINDERS {
        let r = finder(&p, -2.0, 2.0).unwrap();
        assert_eq!(r.len(), 3, "{name}: {r:?}");
        assert!(
            (r[0] + r0).abs() < 1e-12 && r[1].abs() < 1e-12 && (r[2] - r0).abs() < 1e-12,
            "{name}: {r:?}"
        );
    }
}

#[test]
fn double_roots_reported_once() {
    check_all(&[0.3, 0.3, 0.8], 0.0, 1.0, 1e-7);
    check_all(&[0.1, 0.1, 0.7, 0.7], 0.0, 1.0, 1e-7);
    check_all(&[-0.2, 0.45, 0.45, 1.7], 0.0, 1.0, 1e-7);
}

#[test]
fn triple_roots_reported_once() {
    check_all(&[0.6, 0.6, 0.6], 0.0, 1.0, 1e-4);
    check_all(&[0.25, 0.6, 0.6, 0.6, 0.9], 0.0, 1.0, 1e-4);
}

#[test]
fn clustered_roots_one_millionth_apart() {
    check_all(&[0.5, 0.500001, 0.9], 0.0, 1.0, 1e-9);
    check_all(&[0.1, 0.100001, 0.6, 0.600001], 0.0, 1.0, 1e-9);
    // Three roots 1e-4 apart are still resolvable in f64 (p between them ~ 4e-13).
    check_all(&[0.2, 0.2001, 0.2002], 0.0, 1.0, 1e-8);
}

#[test]
fn roots_exactly_at_the_interval_ends() {
    check_all(&[0.0, 0.5, 1.0], 0.0, 1.0, 1e-13);
    check_all(&[0.25, 0.75, 0.9, 3.0], 0.25, 0.75, 1e-13);
}

#[test]
fn degree_twenty() {
    // Roots spread over [-2, 2] plus complex pairs: still one to one.
    let roots: Vec<f64> = (0..20).map(|i| -1.9 + 0.2 * i as f64).collect();
    check_all(&roots, -0.55, 1.45, 1e-6);
    // Few real roots, many complex: (t^2 + 1)^8 (t - 0.3)(t - 0.7)(t + 0.5)(t - 1.2)
    let mut p = Polynomial::from_roots(&[0.3, 0.7, -0.5, 1.2]);
    for _ in 0..8 {
        p = &p * &Polynomial::new(vec![1.0, 0.0, 1.0]);
    }
    assert_eq!(p.degree(), Some(20));
    for (name, finder) in FINDERS {
        let r = finder(&p, 0.0, 1.0).unwrap();
        assert_roots(name, &r, &[0.3, 0.7], 0.0, 1.0, 1e-10);
    }
}

#[test]
fn degenerate_inputs() {
    for (name, finder) in FINDERS {
        assert_eq!(
            finder(&Polynomial::zero(), 0.0, 1.0),
            Err(RootsError::ZeroPolynomial),
            "{name}"
        );
        assert!(matches!(
            finder(&Polynomial::new(vec![f64::NAN, 1.0]), 0.0, 1.0),
            Err(RootsError::NonFiniteCoefficient { index: 0, .. })
        ));
        assert!(matches!(
            finder(&Polynomial::new(vec![1.0, 1.0]), 1.0, 0.0),
            Err(RootsError::InvalidInterval { .. })
        ));
        assert!(
            finder(&Polynomial::constant(2.0), 0.0, 1.0)
                .unwrap()
                .is_empty()
        );
        assert_eq!(
            finder(&Polynomial::new(vec![-0.5, 1.0]), 0.0, 1.0).unwrap(),
            vec![0.5]
        );
    }
}

#[test]
fn negligible_leading_coefficient() {
    // A cubic whose leading coefficient is conversion noise behaves as the quadratic.
    let p = Polynomial::new(vec![0.06, -0.5, 1.0, 1e-19]); // roots 0.2, 0.3
    for (name, finder) in FINDERS {
        let r = finder(&p, 0.0, 1.0).unwrap();
        assert_roots(name, &r, &[0.2, 0.3], 0.0, 1.0, 1e-12);
    }
}

/// Tolerance for a simple root `r` of `p`: the coefficients determine it only to about
/// `rounding bound / |p'(r)|` (its condition), so no fixed tolerance is right for random roots.
fn conditioned_tol(p: &Polynomial, r: f64, floor: f64) -> f64 {
    let (_, d) = p.eval_with_derivative(r);
    floor.max(10.0 * p.eval_error_bound(r) / d.abs())
}

/// As `assert_roots`, with the tolerance of every simple root set by its condition.
fn assert_conditioned(name: &str, p: &Polynomial, found: &[f64], expected: &[f64]) {
    let mut exp: Vec<f64> = expected
        .iter()
        .copied()
        .filter(|r| (0.0..=1.0).contains(r))
        .collect();
    exp.sort_by(f64::total_cmp);
    exp.dedup();
    assert_eq!(
        found.len(),
        exp.len(),
        "{name}: found {found:?}, expected {exp:?}"
    );
    for (f, e) in found.iter().zip(&exp) {
        let tol = conditioned_tol(p, *e, 1e-10);
        assert!(
            (f - e).abs() <= tol,
            "{name}: root {f} vs expected {e} (tol {tol})"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Random well-separated roots, some inside and some outside [0, 1], plus a complex pair.
    #[test]
    fn random_separated_roots(
        raw in proptest::collection::vec(-1.0f64..2.0, 1..9),
        re in -1.0f64..2.0,
        im in 0.05f64..1.0,
    ) {
        let mut roots = raw.clone();
        roots.sort_by(f64::total_cmp);
        roots.dedup_by(|x, y| (*x - *y).abs() < 0.02);
        // Keep roots away from the ends so "in or out" is well defined.
        roots.retain(|r| (r.abs() > 1e-3) && ((r - 1.0).abs() > 1e-3));
        let quad = Polynomial::new(vec![re * re + im * im, -2.0 * re, 1.0]);
        let p = &Polynomial::from_roots(&roots) * &quad;
        for (name, finder) in FINDERS {
            let found = finder(&p, 0.0, 1.0).unwrap();
            assert_conditioned(name, &p, &found, &roots);
        }
    }

    /// Random roots with a double root among them.
    #[test]
    fn random_with_double_root(
        raw in proptest::collection::vec(0.0f64..1.0, 1..5),
        double in 0.05f64..0.95,
    ) {
        let mut roots = raw.clone();
        roots.retain(|r| (r - double).abs() > 0.05 && *r > 1e-3 && *r < 1.0 - 1e-3);
        roots.sort_by(f64::total_cmp);
        roots.dedup_by(|x, y| (*x - *y).abs() < 0.05);
        let mut all = roots.clone();
        all.push(double);
        all.push(double);
        let p = Polynomial::from_roots(&all);
        let mut expected = roots.clone();
        expected.push(double);
        for (name, finder) in FINDERS {
            let found = finder(&p, 0.0, 1.0).unwrap();
            // A double root is only determined to ~sqrt(eps / |p''/2|) by f64 coefficients.
            assert_roots(name, &found, &expected, 0.0, 1.0, 1e-5);
        }
    }

    /// Every reported root is a numerical root, whatever the polynomial.
    #[test]
    fn reported_roots_have_small_residual(coeffs in proptest::collection::vec(-10.0f64..10.0, 2..12)) {
        let p = Polynomial::new(coeffs);
        prop_assume!(!p.is_zero());
        for (_, finder) in FINDERS {
            for r in finder(&p, -2.0, 2.0).unwrap() {
                prop_assert!((-2.0..=2.0).contains(&r));
                let (v, d) = p.eval_with_derivative(r);
                // Residual within rounding, up to the error of the root times the slope.
                prop_assert!(v.abs() <= 1e3 * p.eval_error_bound(r) + 1e-9 * d.abs(), "p({r}) = {v}");
            }
        }
    }
}
