//! Bad input: one-line errors, never a wrong rule, never a hang.

use std::time::{Duration, Instant};

use rs_contain::{Classifier, ContainOptions, FillRule, Locate, Location};
use rs_cubature::{
    CubatureError, CubatureOptions, CubatureRule, MAX_DEGREE, dim_polynomials, monomial_moments,
};
use rs_spline::{Domain, Point, circle, polyline};

fn p(x: f64, y: f64) -> Point {
    Point::new(x, y)
}

fn disc() -> Domain {
    Domain::new(vec![circle(p(0.0, 0.0), 1.0).unwrap()]).unwrap()
}

fn one_line(e: &CubatureError) -> String {
    let s = e.to_string();
    assert!(!s.contains('\n'), "{s}");
    s
}

#[test]
fn a_degree_above_the_limit_is_refused() {
    let e = CubatureRule::new(&disc(), MAX_DEGREE + 1).unwrap_err();
    assert!(
        matches!(e, CubatureError::DegreeTooHigh { degree, max } if degree == MAX_DEGREE + 1 && max == MAX_DEGREE)
    );
    assert!(one_line(&e).contains("above the limit"));
    let e = monomial_moments(&disc(), MAX_DEGREE + 1, FillRule::EvenOdd).unwrap_err();
    assert!(matches!(e, CubatureError::DegreeTooHigh { .. }));
}

#[test]
fn an_open_boundary_is_refused() {
    let open = Domain::new(vec![
        polyline(&[p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)]).unwrap(),
    ])
    .unwrap();
    let e = CubatureRule::new(&open, 4).unwrap_err();
    assert!(matches!(e, CubatureError::OpenBoundary(_)), "{e:?}");
    assert!(one_line(&e).starts_with("open boundary"));
    assert!(matches!(
        monomial_moments(&open, 4, FillRule::EvenOdd),
        Err(CubatureError::OpenBoundary(_))
    ));
}

#[test]
fn options_out_of_range_are_refused() {
    let d = disc();
    for o in [
        CubatureOptions::new(4).with_candidates_per_polynomial(0),
        CubatureOptions::new(4).with_max_retries(11),
        CubatureOptions::new(4).with_max_candidates(0),
        CubatureOptions::new(4).with_max_candidates(rs_cubature::MAX_CANDIDATES + 1),
        CubatureOptions::new(4).with_target_residual(0.0),
        CubatureOptions::new(4).with_target_residual(f64::NAN),
    ] {
        let e = CubatureRule::with_options(&d, o).unwrap_err();
        assert!(
            matches!(e, CubatureError::InvalidOption { .. }),
            "{o:?}: {e:?}"
        );
        one_line(&e);
    }
}

/// A thin axis-aligned rectangle fills its bounding box, and the basis is scaled to the box:
/// the outcome must be a correct rule or an error, in bounded time.
#[test]
fn a_thin_rectangle_gives_a_correct_rule_or_an_error() {
    let h = 1e-9;
    let ring = [p(0.0, 0.0), p(1.0, 0.0), p(1.0, h), p(0.0, h), p(0.0, 0.0)];
    let d = Domain::new(vec![polyline(&ring).unwrap()]).unwrap();
    let start = Instant::now();
    match CubatureRule::new(&d, 20) {
        Ok(rule) => {
            assert!(rule.nodes().len() <= dim_polynomials(20));
            assert!(rule.weights().iter().all(|&w| w > 0.0));
            let c = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
            assert!(
                rule.nodes()
                    .iter()
                    .all(|&q| c.locate(q) == Location::Inside)
            );
            eprintln!(
                "thin rectangle: {} nodes, residual {:e}",
                rule.nodes().len(),
                rule.residual()
            );
            let sum: f64 = rule.weights().iter().sum();
            assert!((sum - h).abs() <= 1e-12 * h, "{sum}");
            // x^7 y^3 over [0, 1] x [0, h] = h^4 / 32.
            let got = rule.integrate(|q| q.x.powi(7) * q.y.powi(3)).unwrap();
            assert!((got - h.powi(4) / 32.0).abs() <= 1e-12 * h.powi(4), "{got}");
        }
        Err(e) => {
            eprintln!("thin rectangle: {}", one_line(&e));
        }
    }
    assert!(start.elapsed() < Duration::from_secs(60));
}

/// A thin sliver along the diagonal of its bounding box fills `1e-9` of it: no candidates can
/// be found within the bounded search, and the answer is an error naming the cause.
#[test]
fn a_diagonal_sliver_is_too_thin_for_the_candidates() {
    let w = 1e-9;
    let ring = [
        p(0.0, 0.0),
        p(1.0, 1.0 - w),
        p(1.0, 1.0),
        p(0.0, w),
        p(0.0, 0.0),
    ];
    let d = Domain::new(vec![polyline(&ring).unwrap()]).unwrap();
    let start = Instant::now();
    let e = CubatureRule::new(&d, 10).unwrap_err();
    assert!(
        matches!(e, CubatureError::TooFewCandidates { found, .. } if found < dim_polynomials(10)),
        "{e:?}"
    );
    assert!(one_line(&e).contains("too thin or too small"));
    eprintln!("sliver: {e}");
    assert!(start.elapsed() < Duration::from_secs(60));
}

#[test]
fn a_non_finite_integrand_value_names_the_node() {
    let rule = CubatureRule::new(&disc(), 4).unwrap();
    let target = rule.nodes()[3];
    let e = rule
        .integrate(|q| if q == target { f64::INFINITY } else { 1.0 })
        .unwrap_err();
    match &e {
        CubatureError::NonFiniteValue {
            index,
            point,
            value,
        } => {
            assert_eq!((*index, *point), (3, target));
            assert!(value.is_infinite());
        }
        other => panic!("{other:?}"),
    }
    assert!(one_line(&e).contains("node 3"));
    let mut values = vec![1.0; rule.nodes().len()];
    values[5] = f64::NAN;
    assert!(matches!(
        rule.integrate_values(&values),
        Err(CubatureError::NonFiniteValue { index: 5, .. })
    ));
}

#[test]
fn a_wrong_number_of_values_is_refused() {
    let rule = CubatureRule::new(&disc(), 4).unwrap();
    let n = rule.nodes().len();
    let e = rule.integrate_values(&vec![1.0; n + 1]).unwrap_err();
    assert!(
        matches!(e, CubatureError::ValuesLength { expected, got } if expected == n && got == n + 1)
    );
    one_line(&e);
}

/// Weights spread so far (a middle weight of `1e8` and more) that the piece moves within
/// `1 / w` of its parameter ends: its moments' quadrature once accepted a wrong area there (a
/// degree-0 rule of weight `9e-16` for an area of `0.5`), then such pieces were refused; now
/// they are integrated as their balanced parts. Every rule's weights are positive and add up
/// to the area (by a 40-digit integral, mpmath: `0.4999999999999990943` at `1e8`, within
/// `1e-17` of `1/2` from `1e9` on; `0.49999669954369455` at `1e3`), and by the symmetry about
/// `x = 1/2` its first moment in `x` is half the area.
#[test]
fn strongly_weighted_pieces_are_integrated_as_balanced_parts() {
    for (w, area) in [
        (1e3, 0.499_996_699_543_694_5),
        (1e8, 0.499_999_999_999_999_1),
        (1e10, 0.5),
        (1e12, 0.5),
    ] {
        for degree in [0, 1, 4, 10] {
            let rule = CubatureRule::new(&rs_testkit::weighted_arc(w), degree)
                .unwrap_or_else(|e| panic!("w {w:e}, degree {degree}: {e}"));
            assert!(rule.weights().iter().all(|&x| x > 0.0));
            let sum: f64 = rule.weights().iter().sum();
            assert!(
                (sum - area).abs() < 1e-14,
                "w {w:e}, degree {degree}: {sum}"
            );
            if degree >= 1 {
                let mx: f64 = rule
                    .nodes()
                    .iter()
                    .zip(rule.weights())
                    .map(|(p, w)| p.x * w)
                    .sum();
                assert!(
                    (mx - 0.5 * area).abs() < 1e-14,
                    "w {w:e}, degree {degree}: {mx}"
                );
            }
        }
    }
}
