//! The JSON domain file: round trips, primitives, loops and every kind of bad input.

use rs_io::IoError;
use rs_io::json::{domain_from_json, domain_from_json_file, save_domain_json};
use rs_spline::{DomainError, SplineError};

fn bad(name: &str) -> IoError {
    let path = format!("{}/../../fixtures/bad/{name}", env!("CARGO_MANIFEST_DIR"));
    let d = domain_from_json_file(&path);
    match d {
        Err(e) => e,
        Ok(d) => match d.require_closed() {
            Err(e) => IoError::Domain(e),
            Ok(()) => panic!("{name} loaded and closed"),
        },
    }
}

#[test]
fn bad_files_give_the_right_errors() {
    assert!(matches!(
        bad("wrong_knot_count.json"),
        IoError::Curve { origin, source: SplineError::WrongKnotCount {
                expected: 6,
                got: 5
            } } if origin == "curve 0"
    ));
    assert!(matches!(
        bad("decreasing_knots.json"),
        IoError::Curve { origin, source: SplineError::DecreasingKnots { index: 3, .. } } if origin == "curve 1"
    ));
    assert!(matches!(
        bad("negative_weight.json"),
        IoError::Curve { origin, source: SplineError::NonPositiveWeight { index: 1, .. } } if origin == "curve 0"
    ));
    assert!(matches!(
        bad("weight_count.json"),
        IoError::Curve { origin, source: SplineError::WeightCountMismatch {
                weights: 2,
                points: 3
            } } if origin == "curve 0"
    ));
    assert!(matches!(bad("nan.json"), IoError::Json { line: 1, .. }));
    assert!(matches!(
        bad("malformed.json"),
        IoError::Json { line: 3, .. }
    ));
    assert!(matches!(
        bad("open_loop.json"),
        IoError::Domain(DomainError::OpenLoop {
            first_curve: 0,
            last_curve: 2,
            ..
        })
    ));
    assert!(matches!(
        bad("no_curves.json"),
        IoError::Domain(DomainError::NoCurves)
    ));
    assert!(matches!(
        bad("no_curves_key.json"),
        IoError::NotADomainFile(_)
    ));
    assert!(matches!(
        bad("missing_knots.json"),
        IoError::Curve { origin, source: SplineError::MissingKnots { needed: 4, got: 5 } } if origin == "curve 0"
    ));
    assert!(matches!(
        bad("short_point.json"),
        IoError::CurveEntry { curve: 0, .. }
    ));
    assert!(matches!(
        bad("unknown_form.json"),
        IoError::CurveEntry { curve: 0, .. }
    ));
    assert!(matches!(
        bad("zero_radius.json"),
        IoError::Curve { origin, source: SplineError::InvalidPrimitive { .. } } if origin == "curve 0"
    ));
    assert!(matches!(
        bad("degree_zero.json"),
        IoError::Curve { origin, source: SplineError::ZeroDegree } if origin == "curve 0"
    ));
    assert!(matches!(bad("does_not_exist.json"), IoError::Read { .. }));
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
        let d = domain_from_json_file(&path).unwrap();
        let out = tmp.join(path.file_name().unwrap());
        save_domain_json(&d, &out).unwrap();
        let back = domain_from_json_file(&out).unwrap();
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
    let d = domain_from_json(text).unwrap();
    assert_eq!(d.name(), Some("mixed"));
    assert_eq!(d.curves().len(), 8);
    let loops: Vec<_> = d.loops().iter().map(|l| l.curves()).collect();
    assert_eq!(loops, vec![0..=2, 3..=3, 4..=4, 5..=5, 6..=7]);
    assert!(d.is_closed());
}
