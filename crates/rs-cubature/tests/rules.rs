//! Rules of degree 5, 10 and 20 on the inRS paper's domains, a disc and an annulus, and of
//! degree 30 on the paper's M-shaped domain: every
//! monomial `x^a y^b`, `a + b <= n`, integrated by the rule within `1e-12` of its exact moment
//! (`monomial_moments`, itself checked against closed forms and fine polygons in the other
//! tests) relative to `area x max over the bounding box of |x^a y^b|`; every node classified
//! `Inside` by inRS2 (a method other than the grid locator that chose the candidates); every
//! weight `> 0`; at most `dim P_n` nodes; the weights adding up to the even-odd area within
//! `1e-12` relative.

use rs_contain::{Classifier, ContainOptions, FillRule, Location, Method, filled_area};
use rs_cubature::{CubatureRule, dim_polynomials, monomial_moments};
use rs_spline::{Domain, Point, circle};

fn check_rule(name: &str, domain: &Domain, degree: usize) {
    let rule = CubatureRule::new(domain, degree).unwrap_or_else(|e| panic!("{name} {degree}: {e}"));
    assert_eq!(rule.degree(), degree);
    let (nodes, weights) = (rule.nodes(), rule.weights());
    assert_eq!(nodes.len(), weights.len());
    assert!(!nodes.is_empty());
    assert!(
        nodes.len() <= dim_polynomials(degree),
        "{name} {degree}: {} nodes",
        nodes.len()
    );
    assert!(
        weights.iter().all(|&w| w > 0.0),
        "{name} {degree}: a weight <= 0"
    );
    assert!(rule.residual() <= rs_cubature::DEFAULT_TARGET_RESIDUAL);
    assert!(rule.candidates() >= nodes.len());

    let classifier = Classifier::new(domain, ContainOptions::DEFAULT).unwrap();
    let locations = classifier.locate_all_with(Method::InRS2, nodes);
    for (p, l) in nodes.iter().zip(&locations) {
        assert_eq!(*l, Location::Inside, "{name} {degree}: node {p:?}");
    }

    let area = filled_area(domain, FillRule::EvenOdd).unwrap();
    let sum: f64 = weights.iter().sum();
    assert!(
        (sum - area).abs() <= 1e-12 * area,
        "{name} {degree}: {sum} vs area {area}"
    );

    let exact = monomial_moments(domain, degree, FillRule::EvenOdd).unwrap();
    let bbox = domain.bounding_box();
    let rx = bbox.min.x.abs().max(bbox.max.x.abs());
    let ry = bbox.min.y.abs().max(bbox.max.y.abs());
    let mut k = 0;
    let mut worst = 0.0f64;
    for total in 0..=degree {
        for b in 0..=total {
            let a = total - b;
            let got = rule
                .integrate(|p: Point| p.x.powi(a as i32) * p.y.powi(b as i32))
                .unwrap();
            let scale = area * rx.powi(a as i32) * ry.powi(b as i32);
            let err = (got - exact[k]).abs() / scale;
            worst = worst.max(err);
            assert!(
                err <= 1e-12,
                "{name} {degree}: x^{a} y^{b}: {got} vs {} (relative {err:e})",
                exact[k]
            );
            k += 1;
        }
    }
    eprintln!(
        "{name} {degree}: {} nodes of {} candidates, residual {:e}, worst monomial {worst:e}",
        nodes.len(),
        rule.candidates(),
        rule.residual()
    );
}

const DEGREES: [usize; 3] = [5, 10, 20];

#[test]
fn rules_on_the_paper_domains() {
    for name in rs_testkit::PAPER_DOMAINS {
        let path = rs_testkit::fixture_path(&format!("inrs-paper/{name}.json"));
        let d = rs_io::json::domain_from_json_file(&path).unwrap();
        for degree in DEGREES {
            check_rule(name, &d, degree);
        }
    }
}

/// Degree 30 (496 polynomials) on S(3), from the chord formula's nodes; about 0.2 s in a
/// release build.
#[test]
fn a_rule_of_degree_30_on_the_m_shaped_domain() {
    let path = rs_testkit::fixture_path("inrs-paper/s3_m_shape.json");
    let d = rs_io::json::domain_from_json_file(&path).unwrap();
    check_rule("s3_m_shape", &d, 30);
}

#[test]
fn rules_on_a_disc_and_an_annulus() {
    let disc = Domain::new(vec![circle(Point::new(0.5, -1.0), 1.5).unwrap()]).unwrap();
    let c = Point::new(0.0, 0.0);
    let annulus = Domain::new(vec![circle(c, 1.0).unwrap(), circle(c, 0.5).unwrap()]).unwrap();
    for degree in DEGREES {
        check_rule("disc", &disc, degree);
        check_rule("annulus", &annulus, degree);
    }
}

#[test]
fn integrate_and_integrate_values_agree() {
    let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
    let rule = CubatureRule::new(&d, 6).unwrap();
    let f = |p: Point| (p.x * 3.0).cos() + p.y * p.y;
    let values: Vec<f64> = rule.nodes().iter().map(|&p| f(p)).collect();
    assert_eq!(
        rule.integrate(f).unwrap(),
        rule.integrate_values(&values).unwrap()
    );
}

/// `fixtures/fill-rule`: a rule for each fill rule on nested loops (weights adding up to the
/// rule's filled area, every node inside by that rule, `x^2` integrated as the moments say);
/// loops that cross are refused, naming the crossing.
#[test]
fn fill_rule_fixtures_get_their_rules_rule_or_are_refused() {
    use rs_cubature::{CubatureError, CubatureOptions};
    for (case, crossing) in rs_testkit::fill_rule_fixtures() {
        let d = &case.domain;
        for rule in [FillRule::EvenOdd, FillRule::NonZero] {
            let got = CubatureRule::with_options(d, CubatureOptions::new(6).with_fill_rule(rule));
            if crossing {
                let e = got.unwrap_err();
                assert!(matches!(e, CubatureError::Nesting(_)), "{}: {e}", case.name);
                assert!(e.to_string().contains("loops cross"), "{e}");
                continue;
            }
            let r = got.unwrap();
            let area = filled_area(d, rule).unwrap();
            let sum: f64 = r.weights().iter().sum();
            assert!(
                (sum - area).abs() < 1e-12 * area,
                "{} ({rule}): {sum} vs {area}",
                case.name
            );
            let c = Classifier::new(d, ContainOptions::DEFAULT.with_fill_rule(rule)).unwrap();
            let nodes = c.locate_all_with(Method::InRS2, r.nodes());
            assert!(
                nodes.iter().all(|l| *l == Location::Inside),
                "{} ({rule})",
                case.name
            );
            let m = monomial_moments(d, 2, rule).unwrap();
            let x2 = r.integrate(|p| p.x * p.x).unwrap();
            assert!(
                (x2 - m[3]).abs() < 1e-12 * m[3].abs().max(1.0),
                "{}: {x2} vs {}",
                case.name,
                m[3]
            );
        }
    }
}

/// `(a - 1)!!`-style closed form: the integral of `x^a y^b` over the disc of radius `r` centred
/// at the origin, `r^(a+b+2) / (a+b+2) * 2 pi (a-1)!! (b-1)!! / (a+b)!!` for even `a`, `b`, else 0.
fn disc_monomial(r: f64, a: usize, b: usize) -> f64 {
    if a % 2 == 1 || b % 2 == 1 {
        return 0.0;
    }
    let double_factorial = |k: usize| (1..=k).rev().step_by(2).map(|i| i as f64).product::<f64>();
    let angular = 2.0
        * std::f64::consts::PI
        * double_factorial(a.saturating_sub(1))
        * double_factorial(b.saturating_sub(1))
        / double_factorial(a + b);
    r.powi((a + b + 2) as i32) / (a + b + 2) as f64 * angular
}

/// Degree 30 on a disc (from the chord formula's nodes): every monomial `x^a y^b`, `a + b <= 30`,
/// integrated within `1e-12` of its closed form relative to `area r^(a+b)`, and the rule's
/// properties (every node `Inside` by inRS2, weights `> 0`, at most `dim P_30` nodes).
#[test]
fn a_rule_of_degree_30_on_a_disc_integrates_monomials_exactly() {
    let r = 1.25;
    let disc = Domain::new(vec![circle(Point::new(0.0, 0.0), r).unwrap()]).unwrap();
    check_rule("disc", &disc, 30);
    let rule = CubatureRule::new(&disc, 30).unwrap();
    let area = std::f64::consts::PI * r * r;
    for total in 0..=30 {
        for b in 0..=total {
            let a = total - b;
            let got = rule
                .integrate(|p: Point| p.x.powi(a as i32) * p.y.powi(b as i32))
                .unwrap();
            let exact = disc_monomial(r, a, b);
            let err = (got - exact).abs() / (area * r.powi(total as i32));
            assert!(err <= 1e-12, "x^{a} y^{b}: {got} vs {exact} ({err:e})");
        }
    }
}

/// Degree 40 (861 polynomials) on the cubic leaf (a cusp-like tip): the rule's properties
/// and every monomial against the exact moments (see `check_rule`).
#[test]
fn a_rule_of_degree_40_on_the_cubic_leaf() {
    let path = rs_testkit::fixture_path("inrs-paper/leaf_cubic.json");
    let d = rs_io::json::domain_from_json_file(&path).unwrap();
    check_rule("leaf_cubic", &d, 40);
}

/// Degree 36 (703 polynomials), where the first attempt compresses the vertical-chord formula:
/// a disc with an off-centre hole (vertical tangents on both loops) and the lune (rational
/// pieces, corners) get rules with every property of `check_rule` (every monomial within
/// `1e-12` of Green's theorem's moment, every node `Inside` by inRS2, weights `> 0`).
#[test]
fn rules_of_degree_36_from_the_chord_formula() {
    let holed = Domain::new(vec![
        circle(Point::new(0.0, 0.0), 1.25).unwrap(),
        circle(Point::new(0.3, -0.2), 0.5).unwrap(),
    ])
    .unwrap();
    check_rule("holed disc", &holed, 36);
    let lune = rs_testkit::inrs_fixture("s5_lune").domain;
    check_rule("s5_lune", &lune, 36);
}
