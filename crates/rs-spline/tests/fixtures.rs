//! Every fixture loads, closes, and matches its recorded area, orientation and bounding box.

use rs_spline::prelude::*;
use rs_spline::{Domain, Orientation};
use rs_testkit::FixtureMeta;

fn fixture_files() -> Vec<std::path::PathBuf> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/inrs-paper");
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .collect();
    v.sort();
    v
}

#[test]
fn fixtures_load_close_and_match_metadata() {
    let files = fixture_files();
    assert_eq!(files.len(), 6, "{files:?}");
    for path in files {
        let name = path.display().to_string();
        let meta = FixtureMeta::load(&path).unwrap();
        let d = &meta.domain;
        assert!(d.is_closed(), "{name}: {:?}", d.loops());
        d.require_closed().unwrap();
        assert_eq!(d.loops().len(), 1, "{name}");

        let area = meta.signed_area.unwrap();
        assert!(
            (d.signed_area() - area).abs() <= 1e-12 * area.abs(),
            "{name}: area {} vs {area}",
            d.signed_area()
        );
        let expected = match meta.orientation.as_deref().unwrap() {
            "ccw" => Orientation::CounterClockwise,
            _ => Orientation::Clockwise,
        };
        assert_eq!(d.loop_orientation(0), expected, "{name}");

        let bb = meta.reference_box.unwrap();
        let got = d.bounding_box();
        assert!(
            got.min.distance(bb.min) < 1e-12 && got.max.distance(bb.max) < 1e-12,
            "{name}: bbox {got:?} vs {bb:?}"
        );
        let text = std::fs::read_to_string(&path).unwrap();
        let named: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(d.name(), named["name"].as_str());
    }
}

#[test]
fn reversed_fixtures_flip_orientation() {
    for path in fixture_files() {
        let d = rs_io::json::domain_from_json_file(&path).unwrap();
        let rev: Vec<_> = d.curves().iter().rev().map(|c| c.reversed()).collect();
        let r = Domain::new(rev).unwrap();
        assert!(r.is_closed());
        assert!((r.signed_area() + d.signed_area()).abs() < 1e-12 * d.signed_area().abs());
    }
}
