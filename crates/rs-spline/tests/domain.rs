//! Domains: loops close within the closure tolerance only; holes and components.

use rs_spline::prelude::*;
use rs_spline::{Domain, DomainError, NurbsCurve, Point, circle, segment};

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
    let looser = Domain::with_relative_closure_tolerance(vec![a, b, c], 1e-5).unwrap();
    assert!(looser.is_closed());
    assert!(
        Domain::with_relative_closure_tolerance(vec![circle(Point::default(), 1.0).unwrap()], -1.0)
            .is_err()
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

/// A loop is flattened as one open polyline: from its first curve's start to its last curve's
/// end (the gap left open), every joint once; each loop on its own.
#[test]
fn flatten_loop_chains_the_loop_curves_and_leaves_the_gap() {
    let (a, b, c) = (
        Point::new(0.0, 0.0),
        Point::new(1.0, 0.0),
        Point::new(0.0, 1.0),
    );
    let gap_end = Point::new(1e-12, 0.0);
    let curves = vec![
        segment(a, b).unwrap(),
        segment(b, c).unwrap(),
        segment(c, gap_end).unwrap(),
        circle(Point::new(5.0, 5.0), 1.0).unwrap(),
    ];
    let d = Domain::new(curves).unwrap();
    assert_eq!(d.loops().len(), 2);
    let mut pts = Vec::new();
    d.flatten_loop(0, 1e-3, &mut |p| pts.push(p));
    assert_eq!(pts, [a, b, c, gap_end]);
    let (mut ring, mut alone) = (Vec::new(), Vec::new());
    d.flatten_loop(1, 1e-3, &mut |p| ring.push(p));
    d.curves()[3].flatten(1e-3, &mut |p| alone.push(p));
    assert_eq!(ring, alone);
}

/// A thin loop whose second curve starts a hair away from the first's end: the error names the
/// two curves that miss and their gap, not the (large) gap of the one-curve loop the grouping
/// cut off; a looser closure tolerance given afterwards joins them.
#[test]
fn the_open_loop_error_names_the_two_curves_that_miss() {
    let a = segment(Point::new(0.0, 0.0), Point::new(1.0, 0.0)).unwrap();
    let b = segment(Point::new(1.0, 2e-8), Point::new(0.5, 0.1)).unwrap();
    let c = segment(Point::new(0.5, 0.1), Point::new(0.0, 0.0)).unwrap();
    let d = Domain::new(vec![a, b, c]).unwrap();
    assert_eq!(d.loops().len(), 2);
    assert_eq!(d.loops()[0].gap_to_next(), Some(2e-8));
    match d.require_closed() {
        Err(DomainError::CurvesMiss {
            curve: 0,
            next: 1,
            gap,
            ..
        }) => assert_eq!(gap, 2e-8),
        other => panic!("expected CurvesMiss, got {other:?}"),
    }
    let msg = d.require_closed().unwrap_err().to_string();
    assert!(
        msg.starts_with("open boundary: curve 0 ends 2e-8 away from the start of curve 1"),
        "{msg}"
    );
    let joined = d.with_closure_tolerance(1e-7).unwrap();
    assert_eq!(joined.loops().len(), 1);
    assert!(joined.is_closed());
    assert_eq!(joined.loops()[0].gap_to_next(), None);
}

/// A quadratic of weights `1, w, 1` closed by its chord moves within `1 / w` of both parameter
/// ends: its area once came out `3.6e-4` for `0.5` at `w = 1e11`, flagged as an estimate. Its
/// balanced parts (the same curve, reparametrised and halved) give the 20-digit areas
/// (mpmath) within `2e-13` (`9e-14` at `w = 1e12`, the others within `4e-15`), converged; the cubic `(0,0), (0.3,1), (0.8,1.2), (1,0)` of weights
/// `1, w, 1, 1` too. An ordinary piece (a circle's quarter, weights `1, 1/sqrt 2, 1`) is its
/// own one part.
#[test]
fn strongly_weighted_pieces_have_their_areas() {
    let p = Point::new;
    let quadratic = rs_testkit::weighted_arc;
    let cubic = |w: f64| {
        rs_testkit::closed_by_chord(
            &[(0.0, 0.0), (0.3, 1.0), (0.8, 1.2), (1.0, 0.0)],
            &[1.0, w, 1.0, 1.0],
        )
    };
    for (d, area) in [
        (quadratic(1e3), 0.499_996_699_543_694_5),
        (quadratic(1e8), 0.499_999_999_999_999_1),
        (quadratic(1e11), 0.5),
        (quadratic(1e12), 0.5),
        (cubic(1e8), 0.500_043_526_385_004_2),
        (cubic(1e11), 0.500_001_376_572_130_3),
    ] {
        let integral = d.loop_area_integral(0);
        assert!(integral.converged, "{area}");
        assert!(
            (integral.value + area).abs() < 2e-13,
            "{} vs -{area}",
            integral.value
        );
    }
    let quarter = NurbsCurve::bezier(
        vec![p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
        Some(vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0]),
    )
    .unwrap();
    assert!(quarter.to_bezier()[0].balanced_parts().is_none());
    let heavy = quadratic(1e11).curves()[0].to_bezier().remove(0);
    let parts = heavy.balanced_parts().unwrap();
    assert!(parts.len() >= 2 && parts.len() <= 64, "{}", parts.len());
    assert_eq!(parts[0].start_point(), heavy.start_point());
    assert_eq!(parts[parts.len() - 1].end_point(), heavy.end_point());
}
