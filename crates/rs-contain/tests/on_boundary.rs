//! Winding numbers in the boundary band: a point within the boundary tolerance of a curve gets
//! the average across the jump from every algorithm, exactly as a point on the curve does, and
//! the value stays exact outside the band (docs/SEMANTICS.md).
//!
//! The query points are curves evaluated in `f64` at parameters that are not dyadic (so they
//! lie on the curve only up to rounding), on straight pieces, conics, cubics, at knots, at
//! corners and at the ends of open chains; the expected values are independent: analytic
//! (`0`, `1/2`, interior angles from the edges' directions) or, for open curves, the principal
//! value summed over a dense polyline of the curve seen from the point.

use std::f64::consts::TAU;

use rs_contain::baselines::WindingAlgorithm;
use rs_contain::{
    Classifier, ContainOptions, DEFAULT_RELATIVE_TOLERANCE, FastWindingField, FillRule, Locate,
    Location, Method, QueryStats, WindingField,
};
use rs_spline::prelude::*;
use rs_spline::{Domain, NurbsCurve, Point, circle, segment};

/// Every algorithm's winding number at `q`: adaptive, binary search, Bezier clipping, the fast
/// field one at a time and in a batch.
fn all_algorithms(field: &WindingField, q: Point) -> [(&'static str, f64); 5] {
    let fast = FastWindingField::new(field);
    let mut stats = QueryStats::default();
    [
        ("adaptive", field.winding_number(q)),
        (
            "binary-search",
            field.winding_number_with(q, WindingAlgorithm::BinarySearch, &mut stats),
        ),
        (
            "bezier-clipping",
            field.winding_number_with(q, WindingAlgorithm::BezierClipping, &mut stats),
        ),
        ("fast", fast.winding_number(q)),
        ("fast-batch", fast.winding_numbers(&[q, q, q])[1]),
    ]
}

/// Asserts that every algorithm gives `want` (within `eps`) at `q`.
fn assert_all(field: &WindingField, q: Point, want: f64, eps: f64, what: &str) {
    for (name, got) in all_algorithms(field, q) {
        assert!(
            (got - want).abs() <= eps,
            "{what}: {name} at {q:?}: {got}, want {want}"
        );
    }
}

/// The unit normal of `c` at `u`.
fn normal(c: &NurbsCurve, u: f64) -> Point {
    let t = c.derivatives(u).first;
    t.perp() / t.length()
}

/// Parameters in `(a, b)` that are not dyadic.
fn parameters(c: &NurbsCurve, n: usize) -> Vec<f64> {
    let (a, b) = c.param_range();
    (1..=n)
        .map(|k| a + (b - a) * (k as f64 * 0.1 + 0.0123456789).fract())
        .collect()
}

/// Checks the band on domain `d` at curve `ci`'s parameter `u`: every algorithm gives `want` at
/// the curve's point, at points within the band across it (vertical and horizontal distance at
/// most the tolerance), and `want -+ 1/2` (the two sides' exact values) a few tolerances away
/// when `sides` is given (`+1` if the left of the curve is the inside).
fn check_point(d: &Domain, ci: usize, u: f64, want: f64, sides: Option<f64>, what: &str) {
    let field = WindingField::new(d, DEFAULT_RELATIVE_TOLERANCE).unwrap();
    let c = &d.curves()[ci];
    let p = c.point_at(u);
    let n = normal(c, u);
    let tol =
        DEFAULT_RELATIVE_TOLERANCE * field.monotone_boxes().unwrap().bounding_box().diagonal();
    // Within the band: |n.x|, |n.y| <= 1, so a step of 0.6 tol along the normal is within 0.6
    // tol vertically and horizontally of p (and p within rounding of the curve).
    for s in [0.0, 0.6, -0.6, 0.3, -0.3] {
        let q = p + n * (s * tol);
        assert!(field.is_on_boundary(q), "{what}: {q:?} not in the band");
        assert_all(&field, q, want, 1e-9, &format!("{what}, {s} tol across"));
    }
    if let Some(side) = sides {
        for (s, w) in [(20.0, want + 0.5 * side), (-20.0, want - 0.5 * side)] {
            let q = p + n * (s * tol);
            assert!(!field.is_on_boundary(q), "{what}: {q:?} in the band");
            assert_all(&field, q, w, 1e-9, &format!("{what}, {s} tol across"));
        }
    }
}

/// Closed curves through their points at non-dyadic parameters: 1/2 inside the band (the
/// curves are counter-clockwise), 1 and 0 on the two sides just outside it.
#[test]
fn smooth_closed_curves_give_one_half() {
    // A circle (rational quadratic NURBS, knots at the quarter turns), an ellipse, and a
    // closed cubic B-spline with interior knots.
    let ellipse = {
        let c = circle(Point::new(0.3, -0.2), 1.7).unwrap();
        let pts = c
            .control_points()
            .iter()
            .map(|p| Point::new(p.x * 2.3, p.y * 0.7))
            .collect();
        NurbsCurve::new(
            2,
            c.knots().knots().to_vec(),
            pts,
            Some(c.weights().to_vec()),
        )
        .unwrap()
    };
    let spline = {
        // Control points on a flower r = 1 + 0.3 sin 3t, closed by repeating the first.
        let mut pts: Vec<Point> = (0..11)
            .map(|k| {
                let t = k as f64 / 11.0 * TAU;
                let r = 1.0 + 0.3 * (3.0 * t).sin();
                Point::new(r * t.cos(), r * t.sin())
            })
            .collect();
        pts.push(pts[0]);
        let n = pts.len();
        let mut knots = vec![0.0; 4];
        knots.extend((1..n - 3).map(|k| k as f64 / (n - 3) as f64));
        knots.extend([1.0; 4]);
        NurbsCurve::new(3, knots, pts, None).unwrap()
    };
    for (name, c) in [
        ("circle", circle(Point::new(-0.4, 0.9), 2.5).unwrap()),
        ("ellipse", ellipse),
        ("cubic spline", spline),
    ] {
        let knots = c.knots().interior_breaks();
        let d = Domain::new(vec![c.clone()]).unwrap();
        for u in parameters(&c, 7).into_iter().chain(knots) {
            check_point(&d, 0, u, 0.5, Some(1.0), &format!("{name} at {u}"));
        }
    }
}

/// A triangle with non-axis edges: 1/2 on the edges, the interior angle over 2 pi at the
/// corners (also a little off them, within the band of both edges), 0 on an open segment.
#[test]
fn straight_pieces_and_corners() {
    let v = [
        Point::new(-1.3, -0.7),
        Point::new(2.1, 0.1),
        Point::new(0.2, 1.9),
    ];
    let d = Domain::new(
        (0..3)
            .map(|i| segment(v[i], v[(i + 1) % 3]).unwrap())
            .collect(),
    )
    .unwrap();
    for ci in 0..3 {
        for u in parameters(&d.curves()[ci], 5) {
            check_point(&d, ci, u, 0.5, Some(1.0), &format!("edge {ci} at {u}"));
        }
    }
    let field = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).unwrap();
    let tol =
        DEFAULT_RELATIVE_TOLERANCE * field.monotone_boxes().unwrap().bounding_box().diagonal();
    for i in 0..3 {
        let (prev, next) = (v[(i + 2) % 3] - v[i], v[(i + 1) % 3] - v[i]);
        let interior = next.cross(prev).atan2(next.dot(prev)) / TAU;
        // At the corner, and within the band of both edges near it (the bisector's direction
        // inwards and outwards, 0.4 tol away).
        let bisector = (prev / prev.length() + next / next.length()) * 0.5;
        let bisector = bisector / bisector.length();
        for q in [
            v[i],
            v[i] + bisector * (0.4 * tol),
            v[i] - bisector * (0.4 * tol),
        ] {
            assert!(field.is_on_boundary(q));
            assert_all(&field, q, interior, 1e-9, &format!("corner {i}"));
        }
    }
    // One open segment on its own: 0 at its points, the limit 0 at its ends too.
    let s = segment(Point::new(0.1, 0.35), Point::new(0.75, -0.4)).unwrap();
    let d = Domain::new(vec![s.clone()]).unwrap();
    for u in parameters(&s, 5).into_iter().chain([0.0, 1.0]) {
        check_point(&d, 0, u, 0.0, None, &format!("open segment at {u}"));
    }
}

/// The principal value at `p` on open curve `c` at parameter `u0` (`p = c(u0)` up to
/// rounding): the angles the polyline of `c` subtends at `p` on `[a, u0)` and `(u0, b]`, each
/// ending (starting) at the tangent, summed over 200 000 chords.
fn principal_value(c: &NurbsCurve, u0: f64) -> f64 {
    let (a, b) = c.param_range();
    let p = c.point_at(u0);
    let t = c.derivatives(u0).first;
    let angle = |x: Point, y: Point| x.cross(y).atan2(x.dot(y));
    let mut sum = 0.0;
    let n = 200_000;
    if u0 > a {
        let mut prev = c.point_at(a) - p;
        for k in 1..n {
            let cur = c.point_at(a + (u0 - a) * k as f64 / n as f64) - p;
            sum += angle(prev, cur);
            prev = cur;
        }
        sum += angle(prev, -t);
    }
    if u0 < b {
        let mut prev = t;
        for k in 1..=n {
            let cur = c.point_at(u0 + (b - u0) * k as f64 / n as f64) - p;
            if k > 1 || cur != Point::default() {
                sum += angle(prev, cur);
                prev = cur;
            }
        }
    }
    sum / TAU
}

/// The cubic and a rational cubic B-spline with an interior knot, open: the principal
/// value at points along them, at the knot and at both ends of the open chain.
#[test]
fn open_curves_give_the_principal_value() {
    let cubic = NurbsCurve::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        vec![
            Point::new(0.0, 0.0),
            Point::new(0.0, 1.0),
            Point::new(-1.0, 1.0),
            Point::new(-1.0, 0.0),
        ],
        None,
    )
    .unwrap();
    let rational = NurbsCurve::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.37, 1.0, 1.0, 1.0, 1.0],
        vec![
            Point::new(-1.0, -0.5),
            Point::new(-0.3, 1.2),
            Point::new(0.8, 1.1),
            Point::new(1.5, -0.2),
            Point::new(0.4, -1.3),
        ],
        Some(vec![1.0, 2.5, 0.6, 1.8, 1.0]),
    )
    .unwrap();
    for (name, c) in [("cubic", cubic), ("rational spline", rational)] {
        let d = Domain::new(vec![c.clone()]).unwrap();
        let (a, b) = c.param_range();
        let mut us = vec![a, b];
        us.extend(parameters(&c, 5));
        if name == "rational spline" {
            us.push(0.37);
        }
        for u in us {
            let want = principal_value(&c, u);
            // Off the curve the field's value jumps by 1 across it: no side values to check at
            // the ends; inside, the two sides are want -+ 1/2 (the curve turns left).
            let sides = (u > a && u < b).then_some(1.0);
            check_point(&d, 0, u, want, sides, &format!("{name} at {u}"));
        }
    }
}

/// The closed domain (the cubic closed by a segment): every algorithm gives 1/2 at the
/// cubic's points, `classify` and `classify --method gwn` call them boundary with both fill
/// rules, and the two agree on which points of a grid across the boundary are boundary.
#[test]
fn classify_and_gwn_agree_on_the_band() {
    let pts = [
        Point::new(0.0, 0.0),
        Point::new(0.0, 1.0),
        Point::new(-1.0, 1.0),
        Point::new(-1.0, 0.0),
    ];
    let cubic = NurbsCurve::bezier(pts.to_vec(), None).unwrap();
    let d = Domain::new(vec![
        cubic.clone(),
        segment(Point::new(-1.0, 0.0), Point::new(0.0, 0.0)).unwrap(),
    ])
    .unwrap();
    let field = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).unwrap();
    let classifier = Classifier::new(&d, ContainOptions::DEFAULT).unwrap();
    let tol =
        DEFAULT_RELATIVE_TOLERANCE * field.monotone_boxes().unwrap().bounding_box().diagonal();
    let mut queries = Vec::new();
    for u in [0.1, 0.4, 0.7] {
        let p = cubic.point_at(u);
        assert_all(&field, p, 0.5, 1e-12, &format!("cubic at {u}"));
        let n = normal(&cubic, u);
        queries
            .extend([-3.0, -1.0, -0.7, -0.3, 0.0, 0.3, 0.7, 1.0, 3.0].map(|s| p + n * (s * tol)));
    }
    // Along the closing segment (y = 0, horizontal) and across it.
    for x in [-0.9, -0.123456789, -0.5] {
        for dy in [-2.0, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0] {
            queries.push(Point::new(x, dy * tol));
        }
        assert_all(&field, Point::new(x, 0.0), 0.5, 1e-12, "closing segment");
    }
    for rule in [FillRule::EvenOdd, FillRule::NonZero] {
        let gwn = field.clone().with_fill_rule(rule);
        let fast_field = FastWindingField::new(&gwn);
        let fast = fast_field.locate_all(&queries);
        for method in Method::ALL {
            let by_method = classifier.locate_all_with(method, &queries);
            for ((q, a), b) in queries.iter().zip(&by_method).zip(&fast) {
                let on = field.is_on_boundary(*q);
                assert_eq!(*a == Location::Boundary, on, "{method:?} at {q:?}");
                assert_eq!(*b == Location::Boundary, on, "gwn {rule:?} at {q:?}");
                assert_eq!(gwn.locate(*q) == Location::Boundary, on, "{q:?}");
                if !on {
                    assert_eq!(a, b, "{method:?} and gwn {rule:?} at {q:?}");
                }
            }
        }
    }
}

/// Outside the band every algorithm gives the same value (a circle crossed by an open
/// segment, 400 points scattered over both, those in the band left out).
#[test]
fn off_the_band_values_are_unchanged_across_algorithms() {
    let d = Domain::new(vec![
        circle(Point::new(0.0, 0.0), 1.0).unwrap(),
        segment(Point::new(-2.0, 0.3), Point::new(1.7, 0.31)).unwrap(),
    ])
    .unwrap();
    let field = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).unwrap();
    for k in 0..400 {
        let q = Point::new(
            -2.2 + 4.4 * ((k as f64) * 0.618_033_988_7).fract(),
            -1.3 + 2.6 * ((k as f64) * 0.414_213_562_3).fract(),
        );
        if field.is_on_boundary(q) {
            continue;
        }
        let values = all_algorithms(&field, q);
        for (name, w) in values {
            assert!(
                (w - values[0].1).abs() < 1e-9,
                "{name} at {q:?}: {w} vs {}",
                values[0].1
            );
        }
    }
}

/// The fast field decides which queries may be in the band from its walk alone (a query no
/// settled sub-curve comes within reach of skips the band test): on the paper's domains and
/// the GWN shapes, at points on the pieces and across them at fractions and multiples of the
/// tolerance, its batch locations call exactly the band's points boundary, and its winding
/// numbers there are the per-curve field's.
#[test]
fn the_walk_never_misses_the_band() {
    let mut domains: Vec<(String, Domain)> = rs_testkit::all_cases()
        .into_iter()
        .map(|c| (c.name, c.domain))
        .collect();
    for name in rs_testkit::GWN_SHAPES {
        domains.push((name.to_string(), rs_testkit::gwn_shape(name)));
    }
    for (name, d) in domains {
        let field = WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).unwrap();
        let fast = FastWindingField::new(&field);
        let tol =
            DEFAULT_RELATIVE_TOLERANCE * field.monotone_boxes().unwrap().bounding_box().diagonal();
        let mut queries = Vec::new();
        for b in field.pieces() {
            for t in [0.0, 0.123456789, 0.3, 0.5, 0.777] {
                let d1 = b.derivatives(t);
                let len = d1.first.length();
                let n = if len > 0.0 {
                    d1.first.perp() / len
                } else {
                    Point::new(0.0, 1.0)
                };
                for s in [0.0, 0.5, -0.5, 0.9, -0.9, 1.2, -1.2, 3.0, -3.0] {
                    queries.push(d1.point + n * (s * tol));
                }
            }
        }
        let located = fast.locate_all(&queries);
        let batch = fast.winding_numbers(&queries);
        for ((q, l), w) in queries.iter().zip(&located).zip(&batch) {
            let on = field.is_on_boundary(*q);
            assert_eq!(*l == Location::Boundary, on, "{name} at {q:?}");
            let plain = field.winding_number(*q);
            assert!((w - plain).abs() < 1e-9, "{name} at {q:?}: {w} vs {plain}");
        }
    }
}
