//! Arcs lie on their circle or ellipse; segments and polylines are straight; areas are exact.

use rs_spline::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

use rs_spline::{
    Domain, NurbsCurve, Point, circle, circular_arc, ellipse, elliptic_arc, polyline, segment,
};

/// Implicit ellipse residual `(x'/rx)^2 + (y'/ry)^2 - 1` in the ellipse's own frame.
fn ellipse_residual(p: Point, c: Point, rx: f64, ry: f64, tilt: f64) -> f64 {
    let (s, co) = tilt.sin_cos();
    let d = p - c;
    let (x, y) = (co * d.x + s * d.y, -s * d.x + co * d.y);
    (x / rx).powi(2) + (y / ry).powi(2) - 1.0
}

fn dense(c: &NurbsCurve, n: usize) -> Vec<Point> {
    let (a, b) = c.param_range();
    (0..=n)
        .map(|i| c.point_at(a + (b - a) * i as f64 / n as f64))
        .collect()
}

#[test]
fn circular_arcs_lie_on_their_circle() {
    let center = Point::new(-1.5, 2.25);
    for &(start, sweep) in &[
        (0.0, 0.3),
        (0.3, FRAC_PI_2),
        (1.0, PI),
        (-2.0, 4.5),
        (0.7, TAU),
        (0.2, -5.0),
        (3.0, 3.0 * TAU + 0.1),
    ] {
        let a = circular_arc(center, 0.75, start, sweep).unwrap();
        for p in dense(&a, 500) {
            assert!(
                (p.distance(center) - 0.75).abs() < 1e-14,
                "start {start}, sweep {sweep}"
            );
        }
        let end = center + Point::new((start + sweep).cos(), (start + sweep).sin()) * 0.75;
        assert!(a.end_point().distance(end) < 1e-14);
        // Every piece spans at most a quarter turn.
        let pieces = a.to_bezier().len() as f64;
        assert!(
            pieces >= (sweep.abs() / FRAC_PI_2).ceil() && pieces * FRAC_PI_2 >= sweep.abs() - 1e-12
        );
    }
}

#[test]
fn arc_sweeps_the_right_angle() {
    // The winding angle of the arc about its centre equals the sweep.
    let center = Point::new(0.0, 0.0);
    for &sweep in &[0.5, 2.0, -3.0, 7.0] {
        let a = circular_arc(center, 1.0, 0.4, sweep).unwrap();
        let pts = dense(&a, 4000);
        let angle: f64 = pts
            .windows(2)
            .map(|w| w[0].cross(w[1]).atan2(w[0].dot(w[1])))
            .sum();
        assert!((angle - sweep).abs() < 1e-9, "sweep {sweep}: {angle}");
    }
}

#[test]
fn elliptic_arcs_lie_on_their_ellipse() {
    let c = Point::new(0.5, -0.25);
    for &(rx, ry, tilt, start, sweep) in &[
        (2.0, 0.5, 0.0, 0.0, TAU),
        (2.0, 0.5, 0.7, 0.3, 2.0),
        (0.1, 3.0, -1.2, -1.0, -4.0),
    ] {
        let e = elliptic_arc(c, rx, ry, tilt, start, sweep).unwrap();
        for p in dense(&e, 500) {
            assert!(ellipse_residual(p, c, rx, ry, tilt).abs() < 1e-13);
        }
        let full = ellipse(c, rx, ry, tilt).unwrap();
        for p in dense(&full, 500) {
            assert!(ellipse_residual(p, c, rx, ry, tilt).abs() < 1e-13);
        }
    }
}

#[test]
fn full_shapes_have_exact_areas() {
    let c = circle(Point::new(3.0, 4.0), 2.0).unwrap();
    let d = Domain::new(vec![c]).unwrap();
    assert!((d.signed_area() - 4.0 * PI).abs() < 1e-13 * 4.0 * PI);
    let e = Domain::new(vec![ellipse(Point::new(0.0, 0.0), 3.0, 0.5, 0.3).unwrap()]).unwrap();
    assert!((e.signed_area() - 1.5 * PI).abs() < 1e-13 * 1.5 * PI);
    let arc = Domain::new(vec![
        circular_arc(Point::new(0.0, 0.0), 1.0, 0.0, -TAU).unwrap(),
    ])
    .unwrap();
    assert!((arc.signed_area() + PI).abs() < 1e-13);
    // Half disc: arc plus closing segment.
    let half = Domain::new(vec![
        circular_arc(Point::new(0.0, 0.0), 1.0, 0.0, PI).unwrap(),
        segment(Point::new(-1.0, 0.0), Point::new(1.0, 0.0)).unwrap(),
    ])
    .unwrap();
    assert!(half.is_closed());
    assert!((half.signed_area() - FRAC_PI_2).abs() < 1e-13);
}

#[test]
fn polygons_have_shoelace_areas() {
    let pts = [
        Point::new(0.0, 0.0),
        Point::new(4.0, 0.0),
        Point::new(4.0, 3.0),
        Point::new(2.0, 1.0),
        Point::new(0.0, 3.0),
        Point::new(0.0, 0.0),
    ];
    let shoelace: f64 = 0.5 * pts.windows(2).map(|w| w[0].cross(w[1])).sum::<f64>();
    let d = Domain::new(vec![polyline(&pts).unwrap()]).unwrap();
    assert!((d.signed_area() - shoelace).abs() < 1e-14);
    let s = segment(Point::new(1.0, 1.0), Point::new(3.0, 2.0)).unwrap();
    for p in dense(&s, 10) {
        assert!((p - Point::new(1.0, 1.0)).cross(Point::new(2.0, 1.0)).abs() < 1e-15);
    }
}
