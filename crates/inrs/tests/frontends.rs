//! The library cells of docs/FRONTENDS.md not exercised elsewhere, through the facade `inrs`:
//! classification by every method and fill rule through [`inrs::Containment`], winding numbers
//! by every algorithm through `WindingField::winding_numbers_by`, the domain summary and the
//! JSON writer, and a cubature rule with its integrals, each against analytic values.

use inrs::contain::baselines::WindingAlgorithm;
use inrs::contain::{FillRule, WindingField};
use inrs::io::json::{domain_from_json, domain_to_json};
use inrs::{ContainOptions, Containment, Domain, Location, Method, Point, PointQuery};

/// Two counter-clockwise circles about the origin, radii 2 and 1: winding number 2 inside the
/// small one, 1 in the ring, 0 outside.
const NESTED: &str = r#"{"curves": [{"circle": {"center": [0, 0], "radius": 2}},
                                    {"circle": {"center": [0, 0], "radius": 1}}]}"#;

fn nested() -> Domain {
    domain_from_json(NESTED).unwrap()
}

/// The centre, a point of the ring, a point outside, a point on the inner circle.
fn probes() -> Vec<Point> {
    vec![
        Point::new(0.0, 0.0),
        Point::new(1.5, 0.0),
        Point::new(3.0, 0.0),
        Point::new(0.0, 1.0),
    ]
}

fn classify(d: &Domain, method: Method, rule: FillRule, points: &[Point]) -> Vec<Location> {
    let options = ContainOptions::DEFAULT
        .with_method(method)
        .with_fill_rule(rule);
    let containment = Containment::new(d, options).unwrap();
    let engine = containment.engine(points.len());
    let mut out = vec![Location::Outside; points.len()];
    engine.values_into(points, &mut out);
    out
}

#[test]
fn containment_classifies_by_every_method_and_fill_rule() {
    use Location::{Boundary, Inside, Outside};
    let d = nested();
    let even_odd = [Outside, Inside, Outside, Boundary];
    for method in [Method::Fast, Method::InRS1, Method::InRS2, Method::Gwn] {
        assert_eq!(
            classify(&d, method, FillRule::EvenOdd, &probes()),
            even_odd,
            "{method:?}"
        );
    }
    // Non-zero fills the inner disk (winding number 2), whatever the method.
    for method in [Method::Fast, Method::InRS1, Method::InRS2, Method::Gwn] {
        assert_eq!(
            classify(&d, method, FillRule::NonZero, &probes()),
            [Inside, Inside, Outside, Boundary],
            "{method:?}"
        );
    }
    // Enough points for the fast method's grid locator: the same answers as inRS2.
    let many: Vec<Point> = (0..3 * inrs::contain::FAST_METHOD_MIN_POINTS)
        .map(|i| {
            let t = i as f64 * 0.618_033_988_749_895;
            Point::new(
                3.0 * (t.fract() - 0.5) * 2.0,
                3.0 * ((t * 0.7).fract() - 0.5) * 2.0,
            )
        })
        .collect();
    for rule in [FillRule::EvenOdd, FillRule::NonZero] {
        assert_eq!(
            classify(&d, Method::Fast, rule, &many),
            classify(&d, Method::InRS2, rule, &many),
            "{rule:?}"
        );
    }
}

#[test]
fn winding_numbers_by_every_algorithm() {
    let field = WindingField::new(&nested(), inrs::contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
    // A quarter of the unit circle, open: it subtends a quarter turn at the centre.
    let quarter = domain_from_json(
        r#"{"curves": [{"degree": 2, "control_points": [[1, 0], [1, 1], [0, 1]],
                        "weights": [1, 0.7071067811865476, 1]}]}"#,
    )
    .unwrap();
    let arc = WindingField::new(&quarter, inrs::contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
    for algorithm in [
        WindingAlgorithm::Adaptive,
        WindingAlgorithm::BinarySearch,
        WindingAlgorithm::BezierClipping,
    ] {
        let numbers = field.winding_numbers_by(algorithm);
        let got: Vec<f64> = probes()[..3].iter().map(|&p| numbers.value(p)).collect();
        for (g, want) in got.iter().zip([2.0, 1.0, 0.0]) {
            assert!((g - want).abs() < 1e-12, "{algorithm:?}: {got:?}");
        }
        let w = arc
            .winding_numbers_by(algorithm)
            .value(Point::new(0.0, 0.0));
        assert!((w - 0.25).abs() < 1e-12, "{algorithm:?}: {w}");
    }
}

#[test]
fn domain_summary_of_nested_circles() {
    let s = inrs::DomainSummary::of(&nested());
    let pi = std::f64::consts::PI;
    assert_eq!((s.curves, s.loops.len(), s.max_degree), (2, 2, 2));
    assert!(s.rational && s.areas_converged);
    assert!(
        (s.signed_area - 5.0 * pi).abs() < 1e-12,
        "{}",
        s.signed_area
    );
    // Even-odd: the ring only.
    assert!((s.filled_area.unwrap() - 3.0 * pi).abs() < 1e-12);
    assert!((s.bounding_box.max.x - 2.0).abs() < 1e-12);
}

#[test]
fn domain_to_json_round_trips_and_classifies_the_same() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/inrs-paper/leaf_cubic.json"
    );
    let d = inrs::io::load_domain(path).unwrap();
    let text = domain_to_json(&d);
    let back = domain_from_json(&text).unwrap();
    assert_eq!(domain_to_json(&back), text);
    let bbox = inrs::BoundingBox {
        min: Point::new(-1.1, -1.1),
        max: Point::new(1.1, 1.1),
    };
    let points = inrs::contain::baselines::halton_points(2000, bbox);
    assert_eq!(
        classify(&back, Method::InRS2, FillRule::EvenOdd, &points),
        classify(&d, Method::InRS2, FillRule::EvenOdd, &points)
    );
    let (a, b) = (inrs::DomainSummary::of(&d), inrs::DomainSummary::of(&back));
    assert_eq!(a.signed_area, b.signed_area);
}

/// fixtures/cad/plate.step: a 10 x 10 plate with a hole of radius 2 about (5, 5), on a tilted
/// plane, with pcurves (written by the STEP reader's tests).
fn plate_step() -> String {
    format!(
        "{}/../../fixtures/cad/plate.step",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn a_cad_face_is_a_domain_in_its_parameters() {
    use inrs::io::cad::CadModel;
    let model = CadModel::read(plate_step()).unwrap();
    let faces = model.face_summaries(None);
    assert_eq!(faces.len(), 1);
    assert_eq!((faces[0].loops, faces[0].curves), (2, 5));
    assert_eq!(faces[0].surface, "PLANE");
    let area = 100.0 - 4.0 * std::f64::consts::PI;
    assert!((faces[0].area - area).abs() < 1e-12, "{}", faces[0].area);
    let d = model.face_domain(0, None).unwrap();
    let same = inrs::io::load_domain(&format!("{}#face:0", plate_step())).unwrap();
    assert_eq!(domain_to_json(&d), domain_to_json(&same));
    let points = [
        Point::new(1.0, 1.0),
        Point::new(5.0, 5.0),
        Point::new(11.0, 5.0),
    ];
    let expected = [Location::Inside, Location::Outside, Location::Outside];
    for method in Method::ALL {
        assert_eq!(classify(&d, method, FillRule::EvenOdd, &points), expected);
    }
}

#[test]
fn a_closure_tolerance_joins_curves_for_any_source() {
    use inrs::io::{LoadOptions, load_domain, load_domain_with};
    let thin = format!(
        "{}/../../fixtures/bad/thin_gap.json",
        env!("CARGO_MANIFEST_DIR")
    );
    assert!(load_domain(&thin).unwrap().require_closed().is_err());
    let options = LoadOptions {
        closure_tolerance: Some(1e-8),
    };
    let d = load_domain_with(&thin, &options).unwrap();
    assert!(d.require_closed().is_ok());
    let points = [Point::new(0.05, 0.001), Point::new(0.05, -0.001)];
    assert_eq!(
        classify(&d, Method::InRS2, FillRule::EvenOdd, &points),
        [Location::Inside, Location::Outside]
    );
}

#[test]
fn cubature_rule_and_integrals_on_a_ring() {
    use inrs::cubature::{CubatureError, CubatureRule, MAX_DEGREE, dim_polynomials};
    // Even-odd, the nested circles fill the ring 1 <= r <= 2: area 3 pi, integral of x^2
    // (2^4 - 1) pi / 4, of x^2 y^2 (2^6 - 1) pi / 24.
    let d = nested();
    let pi = std::f64::consts::PI;
    let rule = CubatureRule::new(&d, 8).unwrap();
    assert_eq!(rule.degree(), 8);
    assert!(!rule.nodes().is_empty() && rule.nodes().len() <= dim_polynomials(8));
    assert_eq!(rule.weights().len(), rule.nodes().len());
    assert!(rule.weights().iter().all(|&w| w > 0.0));
    assert!(rule.residual() <= 1e-13);
    let containment = Containment::new(&d, ContainOptions::DEFAULT).unwrap();
    let engine = containment.engine(rule.nodes().len());
    let mut at = vec![Location::Outside; rule.nodes().len()];
    engine.values_into(rule.nodes(), &mut at);
    assert!(at.iter().all(|&l| l == Location::Inside));
    let area: f64 = rule.weights().iter().sum();
    assert!((area - 3.0 * pi).abs() < 1e-12, "{area}");
    let x2 = rule.integrate(|p| p.x * p.x).unwrap();
    assert!((x2 - 15.0 * pi / 4.0).abs() < 1e-12, "{x2}");
    let values: Vec<f64> = rule.nodes().iter().map(|p| p.x * p.x * p.y * p.y).collect();
    let x2y2 = rule.integrate_values(&values).unwrap();
    assert!((x2y2 - 63.0 * pi / 24.0).abs() < 1e-12, "{x2y2}");
    assert_eq!(
        x2y2,
        rule.integrate(|p| p.x * p.x * p.y * p.y).unwrap(),
        "the same sum in the same order"
    );
    // Errors: a value per node, finite values (the node named), the degree limit.
    assert!(matches!(
        rule.integrate_values(&values[1..]),
        Err(CubatureError::ValuesLength { expected, got }) if expected == values.len() && got == expected - 1
    ));
    let mut bad = values.clone();
    bad[3] = f64::NAN;
    match rule.integrate_values(&bad) {
        Err(
            e @ CubatureError::NonFiniteValue {
                index: 3, point, ..
            },
        ) => {
            assert_eq!(point, rule.nodes()[3]);
            assert!(e.to_string().contains("at node 3 ("), "{e}");
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        CubatureRule::new(&d, MAX_DEGREE + 1),
        Err(CubatureError::DegreeTooHigh { .. })
    ));
}
