//! The JSON domain file: round trips, primitives, loops and every kind of bad input.

use rs_spline::prelude::*;
use rs_spline::{Domain, DomainError, Point, SplineError, circle, segment};

fn bad(name: &str) -> DomainError {
    let path = format!("{}/../../fixtures/bad/{name}", env!("CARGO_MANIFEST_DIR"));
    let d = Domain::from_json_file(&path);
    match d {
        Err(e) => e,
        Ok(d) => match d.require_closed() {
            Err(e) => e,
            Ok(()) => panic!("{name} loaded and closed"),
        },
    }
}

#[test]
fn bad_files_give_the_right_errors() {
    assert!(matches!(
        bad("wrong_knot_count.json"),
        DomainError::Curve {
            curve: 0,
            source: SplineError::WrongKnotCount {
                expected: 6,
                got: 5
            }
        }
    ));
    assert!(matches!(
        bad("decreasing_knots.json"),
        DomainError::Curve {
            curve: 1,
            source: SplineError::DecreasingKnots { index: 3, .. }
        }
    ));
    assert!(matches!(
        bad("negative_weight.json"),
        DomainError::Curve {
            curve: 0,
            source: SplineError::NonPositiveWeight { index: 1, .. }
        }
    ));
    assert!(matches!(
        bad("weight_count.json"),
        DomainError::Curve {
            curve: 0,
            source: SplineError::WeightCountMismatch {
                weights: 2,
                points: 3
            }
        }
    ));
    assert!(matches!(bad("nan.json"), DomainError::Json { line: 1, .. }));
    assert!(matches!(
        bad("malformed.json"),
        DomainError::Json { line: 3, .. }
    ));
    assert!(matches!(
        bad("open_loop.json"),
        DomainError::OpenLoop {
            first_curve: 0,
            last_curve: 2,
            ..
        }
    ));
    assert!(matches!(bad("no_curves.json"), DomainError::NoCurves));
    assert!(matches!(bad("no_curves_key.json"), DomainError::Format(_)));
    assert!(matches!(
        bad("missing_knots.json"),
        DomainError::Curve {
            curve: 0,
            source: SplineError::MissingKnots { needed: 4, got: 5 }
        }
    ));
    assert!(matches!(
        bad("short_point.json"),
        DomainError::CurveFormat { curve: 0, .. }
    ));
    assert!(matches!(
        bad("unknown_form.json"),
        DomainError::CurveFormat { curve: 0, .. }
    ));
    assert!(matches!(
        bad("zero_radius.json"),
        DomainError::Curve {
            curve: 0,
            source: SplineError::InvalidPrimitive { .. }
        }
    ));
    assert!(matches!(
        bad("degree_zero.json"),
        DomainError::Curve {
            curve: 0,
            source: SplineError::ZeroDegree
        }
    ));
    assert!(matches!(bad("does_not_exist.json"), DomainError::Io { .. }));
}

#[test]
fn error_messages_name_the_curve_and_the_problem() {
    let msg = bad("decreasing_knots.json").to_string();
    assert_eq!(msg, "curve 1: knots decrease at index 3: 0.7 > 0.5");
    let msg = bad("open_loop.json").to_string();
    assert!(
        msg.starts_with("open boundary: the loop of curves 0..=2"),
        "{msg}"
    );
    let msg = bad("malformed.json").to_string();
    assert!(msg.starts_with("invalid JSON at line 3, column"), "{msg}");
}

#[test]
fn save_and_load_round_trip_exactly() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/inrs-paper");
    let tmp = std::env::temp_dir().join(format!("rs-spline-roundtrip-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    for e in std::fs::read_dir(dir).unwrap() {
        let path = e.unwrap().path();
        let d = Domain::from_json_file(&path).unwrap();
        let out = tmp.join(path.file_name().unwrap());
        d.save_json(&out).unwrap();
        let back = Domain::from_json_file(&out).unwrap();
        assert_eq!(back.curves(), d.curves());
        assert_eq!(back.name(), d.name());
    }
    std::fs::remove_dir_all(&tmp).unwrap();
}

#[test]
fn primitive_forms_and_optional_fields() {
    let text = r#"{
        "name": "mixed",
        "source": "ignored metadata",
        "curves": [
            {"segment": {"from": [0, 0], "to": [2, 0]}},
            {"arc": {"center": [2, 1], "radius": 1, "start_angle": -1.5707963267948966, "sweep": 3.141592653589793}},
            {"polyline": [[2, 2], [0, 2], [0, 0]]},
            {"circle": {"center": [1, 1], "radius": 0.25}},
            {"ellipse": {"center": [0.5, 0.5], "rx": 0.2, "ry": 0.1, "tilt": 0.3}},
            {"elliptic_arc": {"center": [1.5, 1.5], "rx": 0.2, "ry": 0.1, "start_angle": 0, "sweep": 6.283185307179586}},
            {"degree": 2, "control_points": [[3, 3], [4, 4], [5, 3]]},
            {"degree": 1, "control_points": [[5, 3], [3, 3]], "weights": null, "color": "red"}
        ]
    }"#;
    let d = Domain::from_json_str(text).unwrap();
    assert_eq!(d.name(), Some("mixed"));
    assert_eq!(d.curves().len(), 8);
    let loops: Vec<_> = d.loops().iter().map(|l| l.curves()).collect();
    assert_eq!(loops, vec![0..=2, 3..=3, 4..=4, 5..=5, 6..=7]);
    assert!(d.is_closed());
}

#[test]
fn loops_close_within_tolerance_only() {
    let a = segment(Point::new(0.0, 0.0), Point::new(1.0, 0.0)).unwrap();
    let b = segment(Point::new(1.0, 0.0), Point::new(0.0, 1.0)).unwrap();
    // Gap of 1e-12 * size closes; 1e-6 does not (default relative tolerance 1e-9).
    let c = segment(Point::new(0.0, 1.0), Point::new(1e-12, 0.0)).unwrap();
    let d = Domain::new(vec![a.clone(), b.clone(), c]).unwrap();
    assert!(d.is_closed());
    let c = segment(Point::new(0.0, 1.0), Point::new(1e-6, 0.0)).unwrap();
    let d = Domain::new(vec![a.clone(), b.clone(), c.clone()]).unwrap();
    assert!(!d.is_closed());
    assert!((d.loops()[0].gap() - 1e-6).abs() < 1e-18);
    let looser = Domain::with_closure_tolerance(vec![a, b, c], 1e-5).unwrap();
    assert!(looser.is_closed());
    assert!(
        Domain::with_closure_tolerance(vec![circle(Point::default(), 1.0).unwrap()], -1.0).is_err()
    );
    assert!(matches!(Domain::new(vec![]), Err(DomainError::NoCurves)));
}

#[test]
fn holes_and_components() {
    let outer = circle(Point::new(0.0, 0.0), 3.0).unwrap();
    let hole = circle(Point::new(1.0, 0.0), 1.0).unwrap().reversed();
    let island = circle(Point::new(10.0, 0.0), 0.5).unwrap();
    let d = Domain::new(vec![outer, hole, island]).unwrap();
    assert_eq!(d.loops().len(), 3);
    let expected = std::f64::consts::PI * (9.0 - 1.0 + 0.25);
    assert!((d.signed_area() - expected).abs() < 1e-12 * expected);
    assert_eq!(d.bezier_pieces().len(), 12);
    assert!((d.bounding_box().max.x - 10.5).abs() < 1e-12);
}
