//! The reference inside-counts of the fixtures for 10^3, 10^4 and 10^5 Halton points must match
//! exactly, with every method and several box refinements.

use rs_contain::{
    Classifier, ContainOptions, Location, LocatorOptions, Method, PointLocator, halton_points,
};
use rs_spline::{BoundingBox, Domain, Point};
use serde_json::Value;

fn fixtures() -> Vec<(String, Domain, Value)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/inrs-paper");
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (
                p.file_stem().unwrap().to_string_lossy().into_owned(),
                Domain::from_json_str(&text).unwrap(),
                serde_json::from_str(&text).unwrap(),
            )
        })
        .collect();
    v.sort_by(|a, b| a.0.cmp(&b.0));
    v
}

/// (N, expected inside count) pairs recorded in a fixture.
fn references(meta: &Value) -> Vec<(usize, usize)> {
    let refs = &meta["reference_inside_counts_halton"];
    let mut out = Vec::new();
    if let Some(paper) = refs["paper_protocol"].as_object() {
        for (n, r) in paper {
            out.push((
                n.parse().unwrap(),
                r["inRS_nbox200_safe1_in"].as_u64().unwrap() as usize,
            ));
        }
    }
    if let Some(check) = refs.get("N10000_check") {
        out.push((
            check["N"].as_u64().unwrap() as usize,
            check["inRS_nbox100_safe1_in"].as_u64().unwrap() as usize,
        ));
    }
    out.sort();
    out.dedup();
    out
}

fn reference_box(meta: &Value) -> BoundingBox {
    let b: Vec<f64> = meta["bbox_xmin_xmax_ymin_ymax"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    BoundingBox {
        min: Point::new(b[0], b[2]),
        max: Point::new(b[1], b[3]),
    }
}

#[test]
fn inside_counts_match_the_reference_exactly() {
    let mut checked = 0;
    for (name, domain, meta) in fixtures() {
        let bbox = reference_box(&meta);
        for (n, expected) in references(&meta) {
            let pts = halton_points(n, bbox);
            for subdivisions in [1, 8] {
                let c = Classifier::new(
                    &domain,
                    ContainOptions {
                        subdivisions,
                        ..Default::default()
                    },
                )
                .unwrap();
                for method in Method::ALL {
                    if method == Method::InRS1 && n > 10_000 {
                        continue; // O(MN): covered at the smaller sizes
                    }
                    let loc = c.classify(&pts, method);
                    let inside = loc.iter().filter(|&&l| l == Location::Inside).count();
                    let boundary = loc.iter().filter(|&&l| l == Location::Boundary).count();
                    assert_eq!(
                        (inside, boundary),
                        (expected, 0),
                        "{name}: N = {n}, {method:?}, {subdivisions} sub-boxes"
                    );
                    checked += 1;
                }
                let locator = PointLocator::new(&c, LocatorOptions::default());
                let loc = locator.classify_parallel(&pts);
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
    for (name, domain, meta) in fixtures() {
        let poly = rs_contain::FlattenedPolygon::new(&domain, 1e-10);
        let bbox = reference_box(&meta);
        for (n, expected) in references(&meta) {
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
