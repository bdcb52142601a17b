//! First and second derivatives against central finite differences, and tight boxes against
//! dense sampling.

use rs_spline::prelude::*;
use rs_spline::{Domain, NurbsCurve, Point, RationalBezier, circle, elliptic_arc};

/// Checks `C'` and `C''` at points well inside knot spans, where the curve is smooth.
fn check_nurbs(c: &NurbsCurve, what: &str) {
    let (a, b) = c.param_range();
    let mut ends = vec![a];
    ends.extend(c.knots().interior_breaks());
    ends.push(b);
    let scale = c.control_bounding_box().diagonal().max(1.0);
    for span in ends.windows(2) {
        let (s0, s1) = (span[0], span[1]);
        let h = 1e-4 * (s1 - s0);
        for frac in [0.2, 0.5, 0.8] {
            let u = s0 + frac * (s1 - s0);
            let d = c.derivatives(u);
            let (pm, pp) = (c.point_at(u - h), c.point_at(u + h));
            let fd1 = (pp - pm) / (2.0 * h);
            let fd2 = (pp - d.point * 2.0 + pm) / (h * h);
            let d1_scale = d.first.length().max(scale / (s1 - s0));
            let d2_scale = d.second.length().max(scale / (s1 - s0).powi(2));
            assert!(
                (d.first - fd1).length() <= 1e-6 * d1_scale,
                "{what}: C'({u}) = {:?}, finite difference {fd1:?}",
                d.first
            );
            assert!(
                (d.second - fd2).length() <= 1e-4 * d2_scale,
                "{what}: C''({u}) = {:?}, finite difference {fd2:?}",
                d.second
            );
            assert_eq!(d.point, c.point_at(u));
        }
    }
}

fn check_bezier(b: &RationalBezier, what: &str) {
    let h = 1e-5;
    let scale = b.control_bounding_box().diagonal().max(1.0);
    for t in [0.1, 0.33, 0.5, 0.77, 0.9] {
        let d = b.derivatives(t);
        let fd1 = (b.point_at(t + h) - b.point_at(t - h)) / (2.0 * h);
        let fd2 = (b.point_at(t + h) - d.point * 2.0 + b.point_at(t - h)) / (h * h);
        assert!(
            (d.first - fd1).length() <= 1e-6 * d.first.length().max(scale),
            "{what}"
        );
        assert!(
            (d.second - fd2).length() <= 1e-3 * d.second.length().max(scale),
            "{what}"
        );
    }
}

fn fixtures() -> Vec<(String, Domain)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/inrs-paper");
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let path = e.unwrap().path();
            (
                path.display().to_string(),
                rs_io::json::domain_from_json_file(&path).unwrap(),
            )
        })
        .collect()
}

#[test]
fn nurbs_derivatives_match_finite_differences() {
    for (name, d) in fixtures() {
        for c in d.curves() {
            check_nurbs(c, &name);
            for b in c.to_bezier() {
                check_bezier(&b, &name);
            }
        }
    }
    let cubic = NurbsCurve::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.4, 0.7, 1.0, 1.0, 1.0, 1.0],
        vec![
            Point::new(0.0, 0.0),
            Point::new(1.0, 2.0),
            Point::new(2.0, -1.0),
            Point::new(3.0, 3.0),
            Point::new(4.0, 0.0),
            Point::new(5.0, 1.0),
        ],
        Some(vec![1.0, 3.0, 0.2, 1.0, 5.0, 1.0]),
    )
    .unwrap();
    check_nurbs(&cubic, "cubic");
    check_nurbs(
        &elliptic_arc(Point::new(1.0, 2.0), 3.0, 0.5, 0.4, 0.3, 4.0).unwrap(),
        "ellipse",
    );
}

#[test]
fn circle_derivatives_are_analytic_in_direction() {
    // On a circle, C' is tangent (C' . (C - c) = 0) and C'' has a component towards the centre.
    let c = circle(Point::new(2.0, -1.0), 3.0).unwrap();
    for i in 0..40 {
        let u = (i as f64 + 0.5) / 40.0;
        let d = c.derivatives(u);
        let r = d.point - Point::new(2.0, -1.0);
        assert!(d.first.dot(r).abs() < 1e-12 * d.first.length() * 3.0);
        // Curvature = |C' x C''| / |C'|^3 = 1 / radius.
        let k = d.first.cross(d.second) / d.first.length().powi(3);
        assert!((k - 1.0 / 3.0).abs() < 1e-12, "curvature {k}");
    }
}

#[test]
fn tight_bounding_box_matches_dense_sampling() {
    for (name, d) in fixtures() {
        for c in d.curves() {
            let bb = c.bounding_box();
            let (a, b) = c.param_range();
            let tol = 1e-12 * bb.diagonal();
            let mut seen = rs_spline::BoundingBox::from_point(c.start_point());
            for i in 0..=20000 {
                let p = c.point_at(a + (b - a) * i as f64 / 20000.0);
                assert!(
                    p.x >= bb.min.x - tol
                        && p.x <= bb.max.x + tol
                        && p.y >= bb.min.y - tol
                        && p.y <= bb.max.y + tol,
                    "{name}: {p:?} outside {bb:?}"
                );
                seen = seen.including(p);
            }
            // Dense sampling gets within sampling resolution of every side.
            let res = 1e-6 * bb.diagonal().max(1.0);
            assert!(
                (seen.min.x - bb.min.x).abs() < res && (seen.max.x - bb.max.x).abs() < res,
                "{name}"
            );
            assert!(
                (seen.min.y - bb.min.y).abs() < res && (seen.max.y - bb.max.y).abs() < res,
                "{name}"
            );
        }
    }
}
