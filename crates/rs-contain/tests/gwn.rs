//! Generalized winding numbers: integers on closed shapes, agreement with an independent angle
//! sum, graceful behaviour at defects, the three algorithms agree, the coincident-point
//! convention, work counters.

use rs_contain::Locate;
use rs_spline::prelude::*;
use std::f64::consts::{PI, TAU};

use rs_contain::baselines::{WindingAlgorithm, halton_points};
use rs_contain::{
    Classifier, ContainOptions, FillRule, Location, Method, QueryStats, WindingField,
    curve_winding_number,
};
use rs_spline::{
    BoundingBox, Domain, NurbsCurve, Point, RationalBezier, circle, circular_arc, segment,
};
use rs_testkit::DensePolygon;

fn field(curves: Vec<NurbsCurve>) -> WindingField {
    WindingField::new(
        &Domain::new(curves).unwrap(),
        rs_contain::DEFAULT_RELATIVE_TOLERANCE,
    )
    .unwrap()
}

fn fixture(name: &str) -> Domain {
    rs_testkit::inrs_fixture(name).domain
}

/// Angle subtended at `q` by a dense polyline of the curve, over 2 pi: independent of the
/// adaptive algorithm, accurate when `q` is far compared with the polyline's deviation.
fn dense_angle(b: &RationalBezier, q: Point, n: usize) -> f64 {
    let pts: Vec<Point> = (0..=n).map(|i| b.point_at(i as f64 / n as f64)).collect();
    pts.windows(2)
        .map(|w| {
            let (u, v) = (w[0] - q, w[1] - q);
            u.cross(v).atan2(u.dot(v))
        })
        .sum::<f64>()
        / TAU
}

#[test]
fn closed_shapes_give_integers() {
    let once = field(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]);
    let twice = field(vec![
        circular_arc(Point::new(0.0, 0.0), 1.0, 0.3, 2.0 * TAU).unwrap(),
    ]);
    let cw = field(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap().reversed()]);
    for q in halton_points(
        2000,
        BoundingBox {
            min: Point::new(-2.0, -2.0),
            max: Point::new(2.0, 2.0),
        },
    ) {
        let r = q.length();
        if (r - 1.0).abs() < 1e-9 {
            continue;
        }
        let inside = if r < 1.0 { 1.0 } else { 0.0 };
        assert!((once.winding_number(q) - inside).abs() < 1e-12, "{q:?}");
        assert!(
            (twice.winding_number(q) - 2.0 * inside).abs() < 1e-12,
            "{q:?}"
        );
        assert!((cw.winding_number(q) + inside).abs() < 1e-12, "{q:?}");
    }
    // Every fixture: 1 inside, 0 outside (all counter-clockwise), at points 1e-9 from the curve.
    for name in [
        "s3_m_shape",
        "s4_disk_ellipse_segment",
        "s5_lune",
        "l_shape",
        "leaf_cubic",
    ] {
        let d = fixture(name);
        let f = WindingField::new(&d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
        for c in d.curves() {
            let (a, b) = c.param_range();
            for i in 1..20 {
                let u = a + (b - a) * (i as f64 + 0.5) / 20.0;
                let dv = c.derivatives(u);
                let n = dv.first.perp() / dv.first.length();
                let w_in = f.winding_number(dv.point + n * 1e-9);
                let w_out = f.winding_number(dv.point - n * 1e-9);
                assert!(
                    (w_in - 1.0).abs() < 1e-9 && w_out.abs() < 1e-9,
                    "{name}: {w_in} {w_out}"
                );
            }
        }
    }
}

#[test]
fn single_curve_equals_the_subtended_angle() {
    // Rational cubic and quartic pieces; queries far, near and inside the hull.
    let curves = [
        RationalBezier::new(
            vec![
                Point::new(0.0, 0.0),
                Point::new(1.0, 2.0),
                Point::new(2.0, -1.0),
                Point::new(3.0, 1.0),
            ],
            vec![1.0, 3.0, 0.5, 1.0],
        )
        .unwrap(),
        RationalBezier::new(
            vec![
                Point::new(0.0, 0.0),
                Point::new(2.0, 3.0),
                Point::new(-1.0, 3.0),
                Point::new(1.0, -1.0),
                Point::new(2.0, 0.5),
            ],
            vec![1.0, 0.4, 2.0, 1.0, 0.7],
        )
        .unwrap(),
    ];
    for b in &curves {
        let poly: Vec<Point> = (0..=20000)
            .map(|i| b.point_at(i as f64 / 20000.0))
            .collect();
        for q in halton_points(
            150,
            BoundingBox {
                min: Point::new(-2.0, -2.0),
                max: Point::new(4.0, 4.0),
            },
        ) {
            let dist = poly
                .iter()
                .map(|p| p.distance(q))
                .fold(f64::INFINITY, f64::min);
            if dist < 1e-2 {
                continue;
            }
            let w = curve_winding_number(b, q, &mut QueryStats::default());
            let reference = dense_angle(b, q, 60_000);
            assert!((w - reference).abs() < 1e-8, "{q:?}: {w} vs {reference}");
        }
    }
}

#[test]
fn a_thin_curved_sliver_is_resolved() {
    // A crescent 1e-7 thick: two circular arcs with nearly the same shape. No tolerance may
    // straighten them; points inside the sliver wind once.
    let outer = circular_arc(Point::new(0.0, 0.0), 1.0, 0.0, PI).unwrap();
    let inner = circular_arc(Point::new(0.0, 1e-7), 1.0, PI, -PI).unwrap();
    let close_right = segment(outer.start_point(), inner.end_point()).unwrap();
    let close_left = segment(outer.end_point(), inner.start_point()).unwrap();
    let d = Domain::new(vec![outer, close_left, inner, close_right.reversed()]).unwrap();
    let f = WindingField::new(&d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
    for k in 1..50 {
        let th = PI * k as f64 / 50.0;
        let on_outer = Point::new(th.cos(), th.sin());
        // Midway between the arcs (vertical gap ~1e-7 near the top).
        let q = on_outer - Point::new(0.0, 0.5e-7 * th.sin().max(0.2));
        let w = f.winding_number(q);
        let expected = if (q - Point::new(0.0, 1e-7)).length() > 1.0 {
            1.0
        } else {
            0.0
        };
        assert!((w - expected).abs() < 1e-6, "theta {th}: {w}");
    }
}

#[test]
fn defects_change_containment_only_nearby() {
    let d = fixture("s4_disk_ellipse_segment");
    let full = WindingField::new(&d, rs_contain::DEFAULT_RELATIVE_TOLERANCE)
        .unwrap()
        .with_fill_rule(FillRule::NonZero);
    let pts = halton_points(20_000, d.bounding_box());
    // Removing a straight segment cannot change rounded containment (it subtends less than pi
    // everywhere). Removing the quarter circle (curve 0) changes it exactly where the arc
    // subtends more than pi: between the arc and its chord x + y = 1.
    let removed = WindingField::new(
        &Domain::new(d.curves()[1..].to_vec()).unwrap(),
        rs_contain::DEFAULT_RELATIVE_TOLERANCE,
    )
    .unwrap()
    .with_fill_rule(FillRule::NonZero);
    let mut changed = 0;
    for &q in &pts {
        let before = full.locate(q);
        let after = removed.locate(q);
        if before != after && before != Location::Boundary && after != Location::Boundary {
            changed += 1;
            assert!(
                q.length() <= 1.0 && q.x + q.y >= 1.0,
                "{q:?} changed outside the arc's segment"
            );
        }
    }
    assert!(changed > 500, "{changed}");
    let without_segment = WindingField::new(
        &Domain::new(d.curves()[..2].to_vec()).unwrap(),
        rs_contain::DEFAULT_RELATIVE_TOLERANCE,
    )
    .unwrap()
    .with_fill_rule(FillRule::NonZero);
    for &q in &pts {
        let (a, b) = (full.locate(q), without_segment.locate(q));
        assert!(
            a == b || a == Location::Boundary || b == Location::Boundary,
            "{q:?}"
        );
    }
    // Move the start of curve 1 by 1e-6: a gap. Changes stay within 1e-5 of it.
    let mut curves = d.curves().to_vec();
    let c1 = &curves[1];
    let mut pts1 = c1.control_points().to_vec();
    pts1[0] = pts1[0] + Point::new(1e-6, 0.0);
    curves[1] = NurbsCurve::new(
        c1.degree(),
        c1.knots().knots().to_vec(),
        pts1,
        Some(c1.weights().to_vec()),
    )
    .unwrap();
    let gap_at = d.curves()[1].start_point();
    let moved = WindingField::new(
        &Domain::new(curves).unwrap(),
        rs_contain::DEFAULT_RELATIVE_TOLERANCE,
    )
    .unwrap()
    .with_fill_rule(FillRule::NonZero);
    let mut near: Vec<Point> = pts.clone();
    for i in -20..=20 {
        for j in -20..=20 {
            near.push(gap_at + Point::new(i as f64 * 3e-7, j as f64 * 3e-7));
        }
    }
    for &q in &near {
        let before = full.locate(q);
        let after = moved.locate(q);
        if before != after && before != Location::Boundary && after != Location::Boundary {
            assert!(q.distance(gap_at) < 1e-5, "{q:?} changed far from the gap");
        }
    }
}

#[test]
fn the_three_algorithms_agree() {
    let mut cases: Vec<Domain> = [
        "s3_m_shape",
        "s4_disk_ellipse_segment",
        "s5_lune",
        "leaf_cubic",
    ]
    .iter()
    .map(|n| fixture(n))
    .collect();
    // An open chain with a gap, too.
    cases.push(
        Domain::new(vec![
            circular_arc(Point::new(0.0, 0.0), 1.0, 0.0, 4.0).unwrap(),
            segment(Point::new(-0.7, -0.7), Point::new(0.9, -0.2)).unwrap(),
        ])
        .unwrap(),
    );
    let mut totals = [QueryStats::default(); 3];
    for d in &cases {
        let f = WindingField::new(d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
        let poly = DensePolygon::new(d, 1e-8);
        let mut bb = d.bounding_box();
        bb.min = bb.min - Point::new(0.2, 0.2);
        bb.max = bb.max + Point::new(0.2, 0.2);
        for q in halton_points(1500, bb) {
            if poly.distance(q) < 1e-6 {
                continue;
            }
            let w: Vec<f64> = [
                WindingAlgorithm::Adaptive,
                WindingAlgorithm::BinarySearch,
                WindingAlgorithm::BezierClipping,
            ]
            .iter()
            .enumerate()
            .map(|(k, &alg)| f.winding_number_with(q, alg, &mut totals[k]))
            .collect();
            assert!(
                (w[0] - w[1]).abs() < 1e-9 && (w[0] - w[2]).abs() < 1e-9,
                "{q:?}: {w:?}"
            );
        }
    }
    for t in totals {
        assert!(t.curve_evaluations > 0 && t.subdivisions > 0, "{totals:?}");
    }
}

#[test]
fn coincident_points_follow_the_convention() {
    // On a straight segment: 0 (interior and end points).
    let s = field(vec![
        segment(Point::new(0.0, 0.0), Point::new(2.0, 1.0)).unwrap(),
    ]);
    for t in [0.0, 0.3, 0.5, 1.0] {
        assert_eq!(s.winding_number(Point::new(2.0 * t, t)), 0.0);
    }
    // At the start of a quarter circle: the angle from the tangent (0, 1) to the chord
    // direction (-1, 1) is pi/4, so 1/8; at its end, from (1, -1) to the reversed tangent
    // (1, 0): also pi/4.
    let quarter = field(vec![
        circular_arc(Point::new(0.0, 0.0), 1.0, 0.0, PI / 2.0).unwrap(),
    ]);
    assert!((quarter.winding_number(Point::new(1.0, 0.0)) - 0.125).abs() < 1e-15);
    assert!((quarter.winding_number(Point::new(0.0, 1.0)) - 0.125).abs() < 1e-15);
    // On a closed smooth curve: 1/2, at knots (end points of pieces) and in the interior.
    let c = field(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]);
    assert!((c.winding_number(Point::new(1.0, 0.0)) - 0.5).abs() < 1e-15);
    assert!((c.winding_number(Point::new(0.0, -1.0)) - 0.5).abs() < 1e-15);
    // Interior points of the pieces that bisection reproduces exactly (parameter 1/2).
    for piece in c.pieces() {
        assert!((c.winding_number(piece.point_at(0.5)) - 0.5).abs() < 1e-12);
    }
    // At a convex corner of a square: the interior angle over 2 pi = 1/4.
    let p = Point::new;
    let sq = field(vec![
        rs_spline::polyline(&[
            p(0.0, 0.0),
            p(1.0, 0.0),
            p(1.0, 1.0),
            p(0.0, 1.0),
            p(0.0, 0.0),
        ])
        .unwrap(),
    ]);
    assert!((sq.winding_number(p(1.0, 1.0)) - 0.25).abs() < 1e-15);
    assert!((sq.winding_number(p(0.5, 0.0)) - 0.5).abs() < 1e-15);
}

#[test]
fn far_queries_cost_one_evaluation_per_curve() {
    let d = fixture("s5_lune");
    let f = WindingField::new(&d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
    let mut stats = QueryStats::default();
    f.winding_number_with(
        Point::new(10.0, 10.0),
        WindingAlgorithm::Adaptive,
        &mut stats,
    );
    assert_eq!(
        stats,
        QueryStats {
            curve_evaluations: f.pieces().len(),
            subdivisions: 0
        }
    );
    let mut near = QueryStats::default();
    f.winding_number_with(Point::new(0.5, 0.2), WindingAlgorithm::Adaptive, &mut near);
    assert!(near.curve_evaluations >= f.pieces().len());
}

#[test]
fn gwn_containment_agrees_with_inrs_on_watertight_fixtures() {
    for name in rs_testkit::INRS_FIXTURES {
        let d = fixture(name);
        let c = Classifier::new(&d, ContainOptions::default()).unwrap();
        let pts = halton_points(10_000, d.bounding_box());
        let gwn = c.locate_all_with(Method::Gwn, &pts);
        assert_eq!(gwn, c.locate_all_with(Method::InRS2, &pts), "{name}");
        // Non-zero and even-odd agree on these simple closed shapes.
        let f = c.winding_field().clone().with_fill_rule(FillRule::NonZero);
        assert_eq!(f.locate_all(&pts), gwn, "{name}");
    }
}

/// A point on the chord of a piece, with the two other sides of its control polygon clear,
/// is inside the polygon: the chord's angle there is `+-pi`, which rounding used to decide
/// (the clockwise circle of radius 2 gave `-1/2` at `(-1, -1)`, on the chord of its third
/// quarter, and inRS1's winding-number fallback there called the point inside).
#[test]
fn a_point_on_a_chord_is_not_outside_the_control_polygon() {
    let clockwise = circular_arc(Point::new(0.0, 0.0), 2.0, 0.0, -TAU).unwrap();
    let d = Domain::new(vec![clockwise]).unwrap();
    let f = WindingField::new(&d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
    for q in [
        Point::new(-1.0, -1.0),
        Point::new(1.0, 1.0),
        Point::new(-1.5, -0.5),
    ] {
        assert!(
            (f.winding_number(q) + 1.0).abs() < 1e-12,
            "{q:?}: {}",
            f.winding_number(q)
        );
    }
    let mut stats = QueryStats::default();
    let total: f64 = d
        .bezier_pieces()
        .iter()
        .map(|(_, b)| curve_winding_number(b, Point::new(-1.0, -1.0), &mut stats))
        .sum();
    assert!((total + 1.0).abs() < 1e-12, "{total}");
}
