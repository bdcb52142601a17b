//! The accelerated winding-number field equals the reference everywhere: far, near, on the
//! curves, for closed shapes, open chains and gaps; far queries cost O(log N).

use rs_contain::Locate;
use rs_contain::baselines::halton_points;
use rs_contain::{FastWindingField, QueryStats, WindingField};
use rs_spline::prelude::*;
use rs_spline::{Domain, Point, circular_arc, segment};
use rs_testkit::all_cases;

fn flower() -> Domain {
    rs_io::json::domain_from_json_file(format!(
        "{}/../../fixtures/synthetic/flower500.json",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
}

fn check_equal(name: &str, d: &Domain) {
    let field = WindingField::new(d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
    let fast = FastWindingField::new(&field);
    let s = d.bounding_box().diagonal();
    let mut bb = d.bounding_box();
    bb.min = bb.min - Point::new(0.1 * s, 0.1 * s);
    bb.max = bb.max + Point::new(0.1 * s, 0.1 * s);
    let mut pts = halton_points(2000, bb);
    for b in field.pieces().iter().step_by(7) {
        pts.push(b.start_point());
        pts.push(b.point_at(0.5));
        let d1 = b.derivatives(0.3);
        let n = d1.first.perp() / d1.first.length();
        pts.push(d1.point + n * 1e-9);
        pts.push(d1.point - n * 1e-7);
    }
    for b in field.pieces() {
        // On (or within rounding of) the segment between a piece's ends: for a one-piece
        // chain, the segment its ends' angle is measured across.
        pts.push((b.start_point() + b.end_point()) * 0.5);
    }
    // Out of reach of the chain ends' scaled products, and not a number.
    pts.extend([
        Point::new(1e130, 0.5),
        Point::new(-3e125, 1e140),
        Point::new(f64::NAN, 0.0),
    ]);
    for &q in &pts {
        let (w, f) = (field.winding_number(q), fast.winding_number(q));
        if q.x.is_nan() {
            // Not a point: whatever the two give (0 or NaN), they give the same.
            assert!(
                w == f || (w.is_nan() && f.is_nan()),
                "{name} at {q:?}: {w} vs {f}"
            );
            continue;
        }
        assert!((w - f).abs() < 1e-12, "{name} at {q:?}: {w} vs {f}");
        assert_eq!(field.locate(q), fast.locate(q), "{name} at {q:?}");
    }
    assert_batches_match(name, &fast, &pts);
}

/// The batch queries give each point exactly (bit for bit) what a query of its own gives.
fn assert_batches_match(name: &str, fast: &FastWindingField, pts: &[Point]) {
    let single: Vec<f64> = pts.iter().map(|&q| fast.winding_number(q)).collect();
    for (label, batch) in [
        ("winding_numbers", fast.winding_numbers(pts)),
        (
            "winding_numbers_parallel",
            fast.winding_numbers_parallel(pts),
        ),
    ] {
        assert_eq!(batch.len(), pts.len());
        for ((q, a), b) in pts.iter().zip(&single).zip(&batch) {
            let same = a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan());
            assert!(same, "{name}, {label} at {q:?}: {a} vs {b}");
        }
    }
    let located: Vec<_> = pts.iter().map(|&q| fast.locate(q)).collect();
    assert_eq!(fast.locate_all(pts), located, "{name}: locate_all");
    assert_eq!(fast.locate_all_parallel(pts), located, "{name}: parallel");
}

#[test]
fn fast_field_equals_the_reference() {
    for case in all_cases() {
        check_equal(&case.name, &case.domain);
    }
    check_equal("flower500", &flower());
    // An open chain with a gap and an overlap.
    let open = Domain::new(vec![
        circular_arc(Point::new(0.0, 0.0), 1.0, 0.0, 4.0).unwrap(),
        segment(Point::new(-0.7, -0.7), Point::new(0.9, -0.2)).unwrap(),
        circular_arc(Point::new(0.2, 0.1), 0.5, 1.0, 7.0).unwrap(),
    ])
    .unwrap();
    check_equal("open chain", &open);
}

#[test]
fn far_queries_take_one_angle_per_chain() {
    let d = flower();
    let field = WindingField::new(&d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
    let fast = FastWindingField::new(&field);
    // The whole loop is one exact chain: a query outside its box costs one angle.
    let mut stats = QueryStats::default();
    let w = fast.winding_number_counted(Point::new(3.0, 0.5), &mut stats);
    assert!(w.abs() < 1e-15);
    assert_eq!(stats.curve_evaluations, 1);
    // A query inside visits O(log N) nodes, not the 500 curves.
    let mut stats = QueryStats::default();
    let w = fast.winding_number_counted(Point::new(0.1, 0.2), &mut stats);
    assert!((w - 1.0).abs() < 1e-12);
    assert!(stats.curve_evaluations < 60, "{stats:?}");
    // The reference visits every curve.
    let mut reference = QueryStats::default();
    field.winding_number_with(
        Point::new(0.1, 0.2),
        rs_contain::baselines::WindingAlgorithm::Adaptive,
        &mut reference,
    );
    assert!(reference.curve_evaluations >= 500);
    // Near the boundary the precomputed hierarchy answers without new subdivisions (built by
    // the second query that refines the piece; the first walks it on the fly).
    let q = field.pieces()[10].point_at(0.37) * (1.0 - 1e-3);
    let mut first = QueryStats::default();
    let w = fast.winding_number_counted(q, &mut first);
    assert!(first.subdivisions > 0, "{first:?}");
    fast.winding_number_counted(q, &mut QueryStats::default());
    let mut near = QueryStats::default();
    assert_eq!(
        fast.winding_number_counted(q, &mut near).to_bits(),
        w.to_bits()
    );
    assert_eq!(near.subdivisions, 0, "{near:?}");
    assert_eq!(near.curve_evaluations, first.curve_evaluations);
}

/// The GWN paper's five shapes (three closed, two open curve collections): the fast field
/// equals the per-curve field to 1e-12, and both equal a dense polyline's angle sum (one
/// `atan2` per edge, an independent reference) away from the curves.
#[test]
fn axom_shapes_match_dense_angle_sums() {
    use rs_testkit::{DensePolygon, NearBoundary};
    for name in rs_testkit::GWN_SHAPES {
        let d = rs_testkit::gwn_shape(name);
        let field = WindingField::new(&d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
        let fast = FastWindingField::new(&field);
        let size = d.bounding_box().diagonal();
        let dense = DensePolygon::open_curves(&d, 1e-7 * size);
        let near = NearBoundary::new(&dense, 1e-4 * size);
        let mut pts = halton_points(400, d.bounding_box().grown_by(0.05 * size));
        // Points just off the curves, on both sides, and on them.
        for b in field.pieces().iter().step_by(5) {
            let d1 = b.derivatives(0.41);
            let n = d1.first.perp() / d1.first.length();
            pts.extend([
                d1.point + n * 1e-7 * size,
                d1.point - n * 1e-7 * size,
                d1.point,
            ]);
            pts.push(b.start_point());
        }
        let (mut compared, mut max_ref_diff) = (0, 0.0f64);
        for &q in &pts {
            let (w, f) = (field.winding_number(q), fast.winding_number(q));
            assert!((w - f).abs() < 1e-12, "{name} at {q:?}: {w} vs {f}");
            if !near.is_near(q) {
                let r = dense.winding_number(q);
                max_ref_diff = max_ref_diff.max((w - r).abs());
                compared += 1;
            }
        }
        assert!(compared > 300, "{name}: {compared}");
        assert!(max_ref_diff < 1e-9, "{name}: {max_ref_diff}");
        assert_batches_match(name, &fast, &pts);
    }
}

/// Points at `1e-{first}` to `1e-{last}` of the diagonal from every piece of `d` (either side,
/// along the normal and along the cut), and each piece's start.
fn near_points(d: &Domain, per_piece: usize, (first, last): (f64, f64)) -> Vec<Point> {
    let diagonal = d.bounding_box().diagonal();
    let mut rng = rs_testkit::XorShift64::new(17);
    let mut pts = Vec::new();
    for (_, b) in d.bezier_pieces() {
        pts.push(b.start_point());
        for _ in 0..per_piece {
            let d1 = b.derivatives(rng.next_f64());
            let length = d1.first.length();
            if length.is_nan() || length <= 0.0 {
                continue;
            }
            let s = diagonal * 10f64.powf(-first - (last - first) * rng.next_f64());
            let s = if rng.next_f64() < 0.5 { s } else { -s };
            pts.push(d1.point + d1.first.perp() * (s / length));
            pts.push(d1.point + Point::new(s, 0.0));
        }
    }
    pts
}

/// Near the curves, where the fast field settles sub-curves monotone in `y` from the root of
/// `y(t) = q.y` instead of halving them, its values are the reference walk's bit for bit (the
/// reference keeps the paper's walk): the GWN paper's five shapes and the test cases, with
/// the default boundary tolerance, none, and `1e-5`; and on points at `1e-2` to `1e-10` of the
/// butterfly's diagonal from its curves, the warm field halves a sub-curve for fewer than one
/// point in ten (the walk down to `1e-9` and below halves several times a point).
#[test]
fn near_the_curves_the_roots_give_the_reference_walks_bits() {
    let mut domains: Vec<(String, Domain)> = ["butterfly", "rose", "fish", "bubble", "twirl"]
        .iter()
        .map(|s| (s.to_string(), rs_testkit::gwn_shape(s)))
        .collect();
    domains.extend(all_cases().into_iter().map(|c| (c.name, c.domain)));
    for (name, d) in &domains {
        let pts = near_points(d, 40, (1.0, 15.0));
        for tol in [rs_contain::DEFAULT_RELATIVE_TOLERANCE, 0.0, 1e-5] {
            let field = WindingField::new(d, tol).unwrap();
            let fast = FastWindingField::new(&field);
            let batch = fast.winding_numbers(&pts);
            for (q, b) in pts.iter().zip(&batch) {
                let w = field.winding_number(*q);
                assert_eq!(w.to_bits(), b.to_bits(), "{name}, tol {tol}, at {q:?}");
                let single = fast.winding_number(*q);
                assert_eq!(w.to_bits(), single.to_bits(), "{name}, tol {tol}, at {q:?}");
            }
        }
    }
    let d = rs_testkit::gwn_shape("butterfly");
    let field = WindingField::new(&d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
    let fast = FastWindingField::new(&field);
    let near = near_points(&d, 8, (2.0, 10.0));
    fast.winding_numbers(&near);
    fast.winding_numbers(&near);
    let mut stats = QueryStats::default();
    for &q in &near {
        fast.winding_number_counted(q, &mut stats);
    }
    assert!(
        stats.subdivisions * 10 < near.len(),
        "{stats:?} for {} points",
        near.len()
    );
}
