//! Property-based fuzzing of the readers: random domain files, SVG path data, SVG documents and
//! points text, built from the formats' own tokens so that most inputs get deep into the
//! parsers. Every input must give `Ok` or an error, never a panic, and what loads must build a
//! classifier (or refuse with an error) and classify a few points. The number of cases is
//! bounded (256 per property; `.ci/run` fixes the seed).

use inrs::contain::WindingField;
use inrs::{Classifier, ContainOptions, Domain, Method, Point, parse_points};
use proptest::prelude::*;

/// Numbers that stress the numerics: zeros, signs, tiny, huge, subnormal, non-finite spellings.
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        (-10.0f64..10.0).prop_map(|v| format!("{v}")),
        Just("0".to_string()),
        Just("-0".to_string()),
        Just("1e308".to_string()),
        Just("-1e308".to_string()),
        Just("1e-300".to_string()),
        Just("5e-324".to_string()),
        Just("1e150".to_string()),
        Just("1e20".to_string()),
        Just("NaN".to_string()),
        Just("\"1\"".to_string()),
        (0u32..40).prop_map(|k| format!("{k}")),
    ]
}

fn numbers(max: usize) -> impl Strategy<Value = String> {
    proptest::collection::vec(number(), 0..max).prop_map(|v| format!("[{}]", v.join(",")))
}

fn points(max: usize) -> impl Strategy<Value = String> {
    proptest::collection::vec((number(), number()), 0..max).prop_map(|v| {
        let p: Vec<String> = v.iter().map(|(x, y)| format!("[{x},{y}]")).collect();
        format!("[{}]", p.join(","))
    })
}

fn curve() -> impl Strategy<Value = String> {
    prop_oneof![
        (0u32..6, points(8), proptest::option::of(numbers(14)), proptest::option::of(numbers(8)))
            .prop_map(|(d, p, k, w)| {
                let mut s = format!("{{\"degree\": {d}, \"control_points\": {p}");
                if let Some(k) = k {
                    s += &format!(", \"knots\": {k}");
                }
                if let Some(w) = w {
                    s += &format!(", \"weights\": {w}");
                }
                s + "}"
            }),
        points(6).prop_map(|p| format!("{{\"polyline\": {p}}}")),
        (number(), number(), number(), number())
            .prop_map(|(a, b, c, d)| format!("{{\"segment\": {{\"from\": [{a},{b}], \"to\": [{c},{d}]}}}}")),
        (number(), number(), number(), number(), number()).prop_map(|(x, y, r, s, w)| format!(
            "{{\"arc\": {{\"center\": [{x},{y}], \"radius\": {r}, \"start_angle\": {s}, \"sweep\": {w}}}}}"
        )),
        (number(), number(), number())
            .prop_map(|(x, y, r)| format!("{{\"circle\": {{\"center\": [{x},{y}], \"radius\": {r}}}}}")),
        Just("{}".to_string()),
        Just("[]".to_string()),
    ]
}

fn domain_text() -> impl Strategy<Value = String> {
    prop_oneof![
        8 => proptest::collection::vec(curve(), 0..5)
            .prop_map(|c| format!("{{\"curves\": [{}]}}", c.join(","))),
        1 => "\\PC{0,40}",
    ]
}

fn path_data() -> impl Strategy<Value = String> {
    let token = prop_oneof![
        Just("M".to_string()),
        Just("m".to_string()),
        Just("L".to_string()),
        Just("H".to_string()),
        Just("v".to_string()),
        Just("C".to_string()),
        Just("s".to_string()),
        Just("Q".to_string()),
        Just("T".to_string()),
        Just("A".to_string()),
        Just("a".to_string()),
        Just("Z".to_string()),
        Just(",".to_string()),
        Just(" ".to_string()),
        Just("0".to_string()),
        Just("1".to_string()),
        Just(".5.5".to_string()),
        Just("-2e3".to_string()),
        number(),
    ];
    proptest::collection::vec(token, 0..40).prop_map(|t| t.join(" "))
}

/// Whatever loaded must build or refuse a classifier and classify points without panicking.
fn exercise(d: &Domain) {
    let pts = [
        Point::new(0.0, 0.0),
        Point::new(0.5, 0.5),
        Point::new(1e6, -1e6),
    ];
    if let Ok(c) = Classifier::new(d, ContainOptions::default()) {
        let a = c.locate_all_with(Method::InRS2, &pts);
        let b = c.locate_all_with(Method::InRS1, &pts);
        assert_eq!(a, b);
    }
    if let Ok(f) = WindingField::new(d, 1e-12) {
        for &p in &pts {
            let _ = f.winding_number(p);
        }
    }
    let _ = inrs::DomainSummary::of(d);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn domain_files_never_panic(text in domain_text()) {
        if let Ok(d) = inrs::io::json::domain_from_json(&text) {
            exercise(&d);
            // What loads round-trips through the writer.
            let again = inrs::io::json::domain_from_json(&inrs::io::json::domain_to_json(&d)).unwrap();
            prop_assert_eq!(again.curves(), d.curves());
        }
    }

    #[test]
    fn svg_path_data_never_panics(d in path_data()) {
        if let Ok(curves) = inrs::io::svg::curves_from_path_data(&d)
            && let Ok(domain) = Domain::new(curves) {
                exercise(&domain);
            }
        let doc = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\"><g transform=\"rotate(30) scale(2)\"><path d=\"{d}\"/></g></svg>"
        );
        if let Ok(domain) = inrs::io::svg::domain_from_svg_str(&doc) {
            exercise(&domain);
        }
    }

    #[test]
    fn points_text_never_panics(lines in proptest::collection::vec(
        prop_oneof![
            (number(), number()).prop_map(|(x, y)| format!("{x},{y}")),
            (number(), number(), "[a-z]{0,6}").prop_map(|(x, y, k)| format!("{x} {y} {k}")),
            Just("x,y".to_string()),
            Just("# comment".to_string()),
            Just(String::new()),
            "\\PC{0,12}",
        ],
        0..12,
    )) {
        let text = lines.join("\n");
        match parse_points(&text) {
            Ok(points) => {
                prop_assert!(points.iter().all(|p| p.point.x.is_finite() && p.point.y.is_finite()));
                prop_assert!(points.len() <= lines.len());
            }
            Err(e) => prop_assert!(e.to_string().starts_with("line ")),
        }
    }
}
