//! The reference inside-counts of the fixtures for 10^3, 10^4 and 10^5 Halton points must match
//! exactly, with every method and several box refinements.

use rs_contain::Locate;
use rs_contain::baselines::halton_points;
use rs_contain::{
    Classifier, ContainOptions, FastWindingField, Location, LocatorOptions, Method, PointLocator,
    WindingField,
};
use rs_spline::Point;
use rs_testkit::FixtureMeta;

/// The paper's fixtures and their rewrites with knots of multiplicity degree + 1 (the inRS
/// Matlab package's form), each with reference counts.
/// The fixtures with reference inside counts, by name.
fn fixtures() -> Vec<(String, FixtureMeta)> {
    let mut v = Vec::new();
    for sub in ["inrs-paper", "breaks"] {
        let dir = format!("{}/../../fixtures/{sub}", env!("CARGO_MANIFEST_DIR"));
        for p in std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()) {
            if p.extension().is_none_or(|e| e != "json") {
                continue;
            }
            let meta = FixtureMeta::load(&p).unwrap();
            if meta.inside_counts.is_empty() {
                continue;
            }
            v.push((
                format!("{sub}/{}", p.file_stem().unwrap().to_string_lossy()),
                meta,
            ));
        }
    }
    v.sort_by(|a, b| a.0.cmp(&b.0));
    assert!(v.len() >= 9, "{}", v.len());
    v
}

#[test]
fn inside_counts_match_the_reference_exactly() {
    let mut checked = 0;
    for (name, meta) in fixtures() {
        let domain = &meta.domain;
        let bbox = meta.reference_box.unwrap();
        for (n, expected) in meta.inside_counts.iter().copied() {
            let pts = halton_points(n, bbox);
            for subdivisions in [1, 8] {
                let c = Classifier::new(
                    domain,
                    ContainOptions::DEFAULT.with_subdivisions(subdivisions),
                )
                .unwrap();
                for method in Method::ALL {
                    if method == Method::InRS1 && n > 10_000 {
                        continue; // O(MN): covered at the smaller sizes
                    }
                    let loc = c.locate_all_with(method, &pts);
                    let inside = loc.iter().filter(|&&l| l == Location::Inside).count();
                    let boundary = loc.iter().filter(|&&l| l == Location::Boundary).count();
                    assert_eq!(
                        (inside, boundary),
                        (expected, 0),
                        "{name}: N = {n}, {method:?}, {subdivisions} sub-boxes"
                    );
                    checked += 1;
                }
                let field = WindingField::new(domain, ContainOptions::default().relative_tolerance)
                    .unwrap();
                let fast = FastWindingField::new(&field);
                let inside = pts
                    .iter()
                    .filter(|&&q| fast.locate(q) == Location::Inside)
                    .count();
                assert_eq!(inside, expected, "{name}: N = {n}, fast winding field");
                let locator = PointLocator::new(&c, LocatorOptions::default());
                let loc = locator.locate_all_parallel(&pts);
                let inside = loc.iter().filter(|&&l| l == Location::Inside).count();
                assert_eq!(
                    inside, expected,
                    "{name}: N = {n}, locator, {subdivisions} sub-boxes"
                );
            }
        }
    }
    assert!(checked >= 30, "{checked}");
}

/// The polygon baseline (flattened within 1e-10, as in the paper's Table 2) reproduces the
/// reference counts too, with about 10^5 sides.
#[test]
fn polygon_baseline_matches_the_reference() {
    for (name, meta) in fixtures() {
        let domain = &meta.domain;
        let poly = rs_contain::baselines::FlattenedPolygon::new(domain, 1e-10);
        let bbox = meta.reference_box.unwrap();
        for (n, expected) in meta.inside_counts.iter().copied() {
            let pts = halton_points(n, bbox);
            let inside = poly.classify(&pts).iter().filter(|&&b| b).count();
            assert_eq!(
                inside,
                expected,
                "{name}: N = {n}, {} sides",
                poly.edge_count()
            );
        }
    }
}

/// A curve whose pieces part at a break is a gap: the crossing methods refuse it, naming the
/// curve and the parameter; the winding numbers accept it and degrade only near the gap.
#[test]
fn a_gap_at_a_break_is_an_error_for_crossings_and_fine_for_winding_numbers() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/breaks/circle_gap.json"
    );
    let d = rs_io::json::domain_from_json_file(path).unwrap();
    let err = Classifier::new(&d, ContainOptions::default()).unwrap_err();
    let msg = err.to_string();
    assert!(
        msg.contains("curve 0") && msg.contains("parameter 0.5"),
        "{msg}"
    );
    let field = WindingField::new(&d, 1e-12).unwrap();
    let w = |x: f64, y: f64| field.winding_number(Point::new(x, y));
    assert!((w(0.0, 0.0) - 1.0).abs() < 1e-3, "{}", w(0.0, 0.0));
    assert!(w(3.0, 0.0).abs() < 1e-3);
    // Far from the gap the field is the circle's.
    assert!((w(0.5, 0.5) - 1.0).abs() < 1e-3);
    let fast = FastWindingField::new(&field);
    assert!((fast.winding_number(Point::new(0.5, 0.5)) - w(0.5, 0.5)).abs() < 1e-12);
}
