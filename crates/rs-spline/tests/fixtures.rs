//! Every fixture loads, closes, and matches its recorded area, orientation and bounding box.

use rs_spline::prelude::*;
use rs_spline::{Domain, Orientation};
use serde_json::Value;

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
        let text = std::fs::read_to_string(&path).unwrap();
        let meta: Value = serde_json::from_str(&text).unwrap();
        let d = rs_io::json::domain_from_json_file(&path).unwrap();
        assert!(d.is_closed(), "{name}: {:?}", d.loops());
        d.require_closed().unwrap();
        assert_eq!(d.loops().len(), 1, "{name}");

        let area = meta["signed_area"].as_f64().unwrap();
        assert!(
            (d.signed_area() - area).abs() <= 1e-12 * area.abs(),
            "{name}: area {} vs {area}",
            d.signed_area()
        );
        let expected = match meta["orientation"].as_str().unwrap() {
            "ccw" => Orientation::CounterClockwise,
            _ => Orientation::Clockwise,
        };
        assert_eq!(d.loop_orientation(0), expected, "{name}");

        let bb: Vec<f64> = meta["bbox_xmin_xmax_ymin_ymax"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let got = d.bounding_box();
        for (g, e) in [got.min.x, got.max.x, got.min.y, got.max.y].iter().zip(&bb) {
            assert!((g - e).abs() < 1e-12, "{name}: bbox {got:?} vs {bb:?}");
        }
        assert_eq!(d.name(), meta["name"].as_str());
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
