//! The boundary index of a [`WindingField`] is built lazily: a query away from the curves
//! leaves it unbuilt, every point of the band is one the walk finds near (so gating the
//! boundary test on the walk changes no answer), and a classifier's field shares its boxes.

use rs_spline::prelude::*;
use rs_spline::{Domain, Point};
use rs_testkit::XorShift64;

use super::curve::outside;
use super::sum::WindingSum;
use super::{FastWindingField, QueryStats, WindingAlgorithm, WindingField};
use crate::{Classifier, ContainOptions, DEFAULT_RELATIVE_TOLERANCE, Location, PointQuery};

/// The five GWN shapes, the paper's three domains and the 500-petal flower.
fn fixtures() -> Vec<(String, Domain)> {
    let mut out = Vec::new();
    for name in rs_testkit::GWN_SHAPES {
        out.push((name.to_string(), rs_testkit::gwn_shape(name)));
    }
    for name in [
        "inrs-paper/s3_m_shape.json",
        "inrs-paper/s4_disk_ellipse_segment.json",
        "inrs-paper/s5_lune.json",
        "synthetic/flower500.json",
    ] {
        let path = rs_testkit::fixture_path(name);
        let d = rs_io::load_domain(path.to_str().expect("UTF-8 path")).expect("fixture");
        out.push((name.to_string(), d));
    }
    out
}

/// Random points over the bounding box grown by 5%, and points on every piece (ends and
/// inside) and moved off it along the normal by a few tolerances and by `1e-13`, `1e-12` and
/// `1e-11` of the diagonal, either way.
fn queries(d: &Domain, random: usize, seed: u64) -> Vec<Point> {
    let b = d.bounding_box();
    let diag = b.diagonal();
    let g = b.grown_by(0.05 * diag);
    let mut rng = XorShift64::new(seed);
    let mut pts: Vec<Point> = (0..random)
        .map(|_| Point::new(rng.uniform(g.min.x, g.max.x), rng.uniform(g.min.y, g.max.y)))
        .collect();
    let tol = DEFAULT_RELATIVE_TOLERANCE * diag;
    for (_, p) in d.bezier_pieces() {
        for t in [0.0, 0.123456789, 0.5, 0.8, 1.0] {
            let dv = p.derivatives(t);
            let len = dv.first.length();
            pts.push(dv.point);
            if len > 0.0 {
                let n = dv.first.perp() / len;
                for s in [
                    0.4 * tol,
                    0.9 * tol,
                    1.1 * tol,
                    3.0 * tol,
                    1e-13 * diag,
                    1e-11 * diag,
                ] {
                    pts.push(dv.point + n * s);
                    pts.push(dv.point - n * s);
                }
            }
        }
    }
    pts
}

/// Asserts that the band point `q` is one both walks (the per-curve field's and the fast
/// field's) find near, and that it lies in some piece's frame.
fn assert_near_by_both_walks(name: &str, field: &WindingField, fast: &FastWindingField, q: Point) {
    let mut sum = WindingSum::tracking(q, field.near_reach());
    field.add_pieces(q, &[], &mut sum, &mut QueryStats::default());
    assert!(
        sum.near(),
        "{name}: {q:?} in the band, not near by the walk"
    );
    let (mut stack, mut stats) = ([0; super::fast::STACK], QueryStats::default());
    let fast_sum = fast.crossing_sum(q, &[], &mut stack, &mut stats);
    assert!(fast_sum.near(), "{name}: {q:?} not near by the fast walk");
    assert!(
        field.frames.iter().any(|f| !outside(f.lo, f.hi, q)),
        "{name}: {q:?} outside every frame"
    );
}

/// `q` in the band without the frames' gate: some box is near it.
fn in_band(field: &WindingField, q: Point) -> bool {
    let index = field.boundary_index().expect("boxes");
    index.boxes.boxes().iter().any(|b| b.is_near(q, index.tol))
}

/// Every point of the band (some monotone box near it, every box tried) lies in its piece's
/// frame and is one the adaptive walk finds near, in the per-curve field and in the fast one;
/// so the locations gated on the walk equal the old ones (the boundary test for every point,
/// then the rounded winding number), one by one and in batches, and the field, a lazily built
/// copy and the classifier's field (sharing the classifier's boxes) agree bit for bit.
#[test]
fn the_band_is_near_and_gating_changes_no_answer() {
    for (name, d) in fixtures() {
        let eager = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).expect("field");
        assert!(eager.monotone_boxes().is_ok());
        let lazy = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).expect("field");
        // The GWN shapes are open: no classifier, the standalone field stands in.
        let classifier = Classifier::new(&d, ContainOptions::DEFAULT).ok();
        let shared = classifier.as_ref().map_or(&lazy, |c| c.winding_field());
        let (fast_eager, fast_lazy, fast_shared) = (
            FastWindingField::new(&eager),
            FastWindingField::new(&lazy),
            FastWindingField::new(shared),
        );
        let pts = queries(&d, 400, 0x5eed);
        let mut band = 0;
        for &q in &pts {
            let on = in_band(&eager, q);
            let has_passages = !eager.passages(q).is_empty();
            if on || has_passages {
                band += 1;
                assert_near_by_both_walks(&name, &eager, &fast_eager, q);
            }
            let want = if on {
                Location::Boundary
            } else {
                eager.location_from_winding(eager.winding_number(q), eager.fill_rule())
            };
            for (what, got) in [
                ("field", PointQuery::<Location>::value(&eager, q)),
                ("lazy field", PointQuery::<Location>::value(&lazy, q)),
                ("shared field", PointQuery::<Location>::value(shared, q)),
                ("fast", PointQuery::<Location>::value(&fast_eager, q)),
                ("lazy fast", PointQuery::<Location>::value(&fast_lazy, q)),
                (
                    "shared fast",
                    PointQuery::<Location>::value(&fast_shared, q),
                ),
            ] {
                assert_eq!(got, want, "{name} {what}: {q:?}");
            }
            let w = eager.winding_number(q).to_bits();
            assert_eq!(lazy.winding_number(q).to_bits(), w, "{name}: {q:?}");
            assert_eq!(shared.winding_number(q).to_bits(), w, "{name}: {q:?}");
            let fw = fast_eager.winding_number(q).to_bits();
            assert_eq!(fast_lazy.winding_number(q).to_bits(), fw, "{name}: {q:?}");
            assert_eq!(fast_shared.winding_number(q).to_bits(), fw, "{name}: {q:?}");
        }
        assert!(
            band > 10 * d.bezier_pieces().len(),
            "{name}: {band} band points"
        );
        // Batches (eight winding numbers side by side) give the same as one by one.
        let fresh = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).expect("field");
        let fast_fresh = FastWindingField::new(&fresh);
        let mut locations = vec![Location::Outside; pts.len()];
        fast_fresh.values_into(&pts[..], &mut locations);
        let mut winding = vec![0.0f64; pts.len()];
        fast_fresh.values_into(&pts[..], &mut winding);
        for (i, &q) in pts.iter().enumerate() {
            assert_eq!(
                locations[i],
                PointQuery::<Location>::value(&fast_eager, q),
                "{name}: {q:?}"
            );
            assert_eq!(
                winding[i].to_bits(),
                fast_eager.winding_number(q).to_bits(),
                "{name}: {q:?}"
            );
        }
    }
}

/// Queries far from every curve (outside every piece's control box grown by `1e-3` of the
/// diagonal: in the shapes' holes, inside them and round them), one by one and in batches,
/// by the per-curve field, the fast field and the ray-casting baselines, leave the boundary
/// index unbuilt; one query on a curve builds it.
#[test]
fn queries_away_from_the_curves_leave_the_boxes_unbuilt() {
    let mut inside = 0;
    for (name, d) in fixtures() {
        let field = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).expect("field");
        let fast = FastWindingField::new(&field);
        let b = d.bounding_box();
        let margin = 1e-3 * b.diagonal();
        let boxes: Vec<_> = d
            .bezier_pieces()
            .iter()
            .map(|(_, p)| {
                let (lo, hi) = super::curve::control_box(p.control_points());
                (
                    Point::new(lo.x - margin, lo.y - margin),
                    Point::new(hi.x + margin, hi.y + margin),
                )
            })
            .collect();
        let pts: Vec<Point> = queries(&d, 4000, 7)
            .into_iter()
            .filter(|&q| boxes.iter().all(|&(lo, hi)| outside(lo, hi, q)))
            .collect();
        assert!(pts.len() > 50, "{name}: {} far points", pts.len());
        // Points inside the shapes too (a winding number away from 0), not only round them.
        inside += pts
            .iter()
            .filter(|&&q| fast.winding_number(q).abs() > 0.5)
            .count();
        let mut locations = vec![Location::Outside; pts.len()];
        fast.values_into(&pts[..], &mut locations);
        let mut winding = vec![0.0f64; pts.len()];
        fast.values_into(&pts[..], &mut winding);
        for &q in &pts {
            let _ = PointQuery::<Location>::value(&field, q);
            let _ = PointQuery::<Location>::value(&fast, q);
            let _ = field.winding_number(q);
        }
        for &q in pts.iter().take(5) {
            for a in [
                WindingAlgorithm::BinarySearch,
                WindingAlgorithm::BezierClipping,
            ] {
                let _ = field.winding_number_with(q, a, &mut QueryStats::default());
            }
        }
        assert!(
            !field.boundary_index_built(),
            "{name}: built by far queries"
        );
        let on = d.bezier_pieces()[0].1.point_at(0.5);
        assert_eq!(PointQuery::<Location>::value(&fast, on), Location::Boundary);
        assert!(
            field.boundary_index_built(),
            "{name}: not built by a boundary query"
        );
    }
    assert!(inside > 1000, "{inside} far points inside");
}

/// A classifier's field shares the classifier's monotone boxes (no second build), and a
/// field's boxes are the ones `MonotoneBoxes::new` builds with the default options.
#[test]
fn the_classifier_field_shares_its_boxes() {
    for (name, d) in fixtures().into_iter().skip(5) {
        let c = Classifier::new(&d, ContainOptions::DEFAULT).expect("classifier");
        let field = c.winding_field();
        assert!(!field.boundary_index_built());
        let boxes = field.monotone_boxes().expect("boxes");
        assert!(std::ptr::eq(boxes, c.boxes()), "{name}: boxes built again");
        let own = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).expect("field");
        let built = rs_boxes::MonotoneBoxes::new(&d, rs_boxes::BoxOptions::default()).unwrap();
        assert_eq!(own.monotone_boxes().expect("boxes").boxes(), built.boxes());
    }
}

/// A piece's subdivision hierarchy is built by the second walk that refines it, not the first,
/// and the on-the-fly walk of the first gives the same winding number bit for bit (on and near
/// every piece of the fixtures, where the walks go deepest).
#[test]
fn hierarchies_wait_for_a_second_query() {
    for (name, d) in fixtures().into_iter().skip(3) {
        let field = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).expect("field");
        let pts = queries(&d, 0, 3);
        let warm = FastWindingField::new(&field);
        for &q in &pts {
            let _ = warm.winding_number(q);
            let _ = warm.winding_number(q);
        }
        for &q in &pts {
            // A fresh field per query: its first walk of every piece is on the fly.
            let cold = FastWindingField::new(&field);
            let w = cold.winding_number(q);
            assert_eq!(
                w.to_bits(),
                warm.winding_number(q).to_bits(),
                "{name}: {q:?}"
            );
            // (A query in the band walks again without the pieces it passes: that second walk
            // builds the hierarchies of the others it refines.)
            assert!(
                !field.passages(q).is_empty()
                    || (0..field.pieces().len()).all(|p| !cold.hierarchy_built(p)),
                "{name}: {q:?} built a hierarchy"
            );
            assert_eq!(
                cold.winding_number(q).to_bits(),
                w.to_bits(),
                "{name}: {q:?}"
            );
        }
        let q = pts[1];
        let fresh = FastWindingField::new(&field);
        let _ = fresh.winding_number(q);
        let _ = fresh.winding_number(q);
        assert!(
            (0..field.pieces().len()).any(|p| fresh.hierarchy_built(p)),
            "{name}"
        );
    }
}

/// With no tolerance at all (the band only the rounding margins), and on rational pieces of
/// weight ratios up to the limit, every point of the band is still one the walks find near and
/// lies in its piece's frame: the per-field margin, not twice the tolerance, covers the
/// rounding there.
#[test]
fn the_band_is_near_without_tolerance_and_with_heavy_weights() {
    let mut domains = fixtures();
    for w in [10.0, 1e3, 1e6] {
        domains.push((format!("weights {w}"), super::tests::heavy_weights(w)));
    }
    let mut band = 0;
    for (name, d) in domains {
        for tolerance in [0.0, 1e-15, DEFAULT_RELATIVE_TOLERANCE] {
            let field = WindingField::new(&d, tolerance).expect("field");
            let fast = FastWindingField::new(&field);
            for q in queries(&d, 100, 0x0ba5e) {
                if !in_band(&field, q) && field.passages(q).is_empty() {
                    continue;
                }
                band += 1;
                assert_near_by_both_walks(&format!("{name} ({tolerance})"), &field, &fast, q);
            }
        }
    }
    assert!(band > 1000, "{band} band points");
}
