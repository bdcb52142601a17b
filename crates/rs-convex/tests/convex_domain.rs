//! Convex domains against independent truth: the curvature of the moved curve by the rational
//! quotient rule (rs-spline's evaluator, not the Bernstein numerator), the torsion of a
//! polynomial space curve from its hodographs, and an analytic half-plane.

use rs_convex::{
    BoundingBox3, ConvexDomain, ConvexDomainOptions, ConvexPolygon, Outcome, Point3, Region, Sign,
    SignNumerator, SpaceCurve, approximate,
};
use rs_spline::prelude::*;
use rs_spline::{NurbsCurve, Point};

/// Minimum of `C' x C''` (divided by `|C'|^3`, the curvature) over a dense parameter grid.
fn min_curvature(c: &NurbsCurve) -> f64 {
    let (a, b) = c.param_range();
    (0..=4000)
        .map(|i| {
            let d = c.derivatives(a + (b - a) * i as f64 / 4000.0);
            d.first.cross(d.second) / d.first.length().powi(3).max(1e-300)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Minimum of `C' x C''` over a dense grid, relative to the largest `|C'| |C''|` (for points
/// on the domain's boundary, where the curve may lose regularity, e.g. `d` on a neighbour).
fn min_numerator(c: &NurbsCurve) -> f64 {
    let (a, b) = c.param_range();
    let (mut lo, mut scale) = (f64::INFINITY, 0.0f64);
    for i in 0..=4000 {
        let d = c.derivatives(a + (b - a) * i as f64 / 4000.0);
        lo = lo.min(d.first.cross(d.second));
        scale = scale.max(d.first.length() * d.second.length());
    }
    lo / scale
}

fn polygon(r: &Region) -> &ConvexPolygon {
    match r {
        Region::Polygon(p) => p,
        Region::Polytope(_) => panic!("expected a polygon"),
    }
}

fn cubic() -> NurbsCurve {
    // A convex-ish cubic with the free point d = P2 at the origin (as in the paper's Fig. 1,
    // with a 20-unit box centred at d).
    NurbsCurve::bezier(
        vec![
            Point::new(-6.0, 4.0),
            Point::new(-5.0, -3.0),
            Point::new(0.0, 0.0),
            Point::new(6.0, 3.0),
        ],
        None,
    )
    .unwrap()
}

fn run(c: &NurbsCurve, free: usize, r: &[f64], sign: Sign) -> ConvexDomain {
    let h = SignNumerator::curvature(c, free).unwrap();
    let options = ConvexDomainOptions::DEFAULT
        .with_sign(sign)
        .with_relative_tolerance(1e-4)
        .with_max_level(9);
    approximate(&h, &BoundingBox3::from_ranges(r).unwrap(), &options).unwrap()
}

#[test]
fn inner_polygons_are_nested_growing_and_inside_the_outer_bound() {
    let k = run(&cubic(), 2, &[-10.0, 10.0, -10.0, 10.0], Sign::Positive);
    assert_eq!(k.outcome, Outcome::Converged);
    let last = k.levels.last().unwrap();
    assert!(last.rel_error.unwrap() <= 1e-4);
    let outer = polygon(&k.outer);
    for w in k.levels.windows(2) {
        let (a, b) = (polygon(&w[0].region), polygon(&w[1].region));
        assert_eq!(w[1].inequalities, 2 * w[0].inequalities);
        assert!(b.area() >= a.area() - 1e-12, "level {} shrank", w[1].level);
        for v in a.vertices() {
            assert!(
                b.contains(*v, 1e-9),
                "level {} is not inside level {}",
                w[0].level,
                w[1].level
            );
        }
    }
    assert_eq!(k.levels[0].inequalities, 4); // degree 2p - 3 = 3: four coefficients
    for l in &k.levels {
        for v in polygon(&l.region).vertices() {
            assert!(
                outer.contains(*v, 1e-9),
                "inner vertex {v:?} outside the outer bound"
            );
        }
    }
    // Theorem 1 / Remark 1: the gap to the outer bound closes.
    let inner = polygon(k.inner());
    assert!(
        outer.area() - inner.area() < 2e-3 * outer.area(),
        "{} vs {}",
        inner.area(),
        outer.area()
    );
}

#[test]
fn every_vertex_keeps_the_sign_and_points_beyond_the_outer_bound_break_it() {
    let c = cubic();
    let k = run(&c, 2, &[-10.0, 10.0, -10.0, 10.0], Sign::Positive);
    for l in &k.levels {
        let p = polygon(&l.region);
        let centre = p.vertex_centroid().unwrap();
        for &v in p.vertices() {
            let on = c.with_control_point(2, v).unwrap();
            assert!(
                min_numerator(&on) >= -1e-9,
                "vertex {v:?} of level {}",
                l.level
            );
            // Slightly inside: strictly the right sign everywhere.
            let inside = c.with_control_point(2, v + (centre - v) * 1e-3).unwrap();
            assert!(min_curvature(&inside) > 0.0, "near {v:?}");
        }
    }
    // Beyond an edge of the outer bound that is not a side of the box: a sign change.
    let outer = polygon(&k.outer);
    let vs = outer.vertices();
    let on_box = |p: Point| p.x.abs() >= 10.0 - 1e-9 || p.y.abs() >= 10.0 - 1e-9;
    let mut tested = 0;
    for i in 0..vs.len() {
        let (a, b) = (vs[i], vs[(i + 1) % vs.len()]);
        if on_box(a) && on_box(b) {
            continue;
        }
        let m = (a + b) * 0.5;
        let outward = -(b - a).perp() / (b - a).length(); // counter-clockwise polygon
        let beyond = c.with_control_point(2, m + outward * 0.05).unwrap();
        assert!(min_curvature(&beyond) < 0.0, "beyond {m:?}");
        tested += 1;
    }
    assert!(tested >= 2);
}

#[test]
fn quadratic_bezier_domain_is_an_exact_half_plane() {
    // h = 4 (d - P0) x (P2 - d): positive curvature iff d is to the right of P0 -> P2... for
    // P0 = (0, 0), P2 = (4, 2): (d - P0) x (P2 - P0) > 0, i.e. 2 x - 4 y > 0, y < x / 2.
    for weights in [None, Some(vec![1.0, 3.0, 0.5])] {
        let c = NurbsCurve::bezier(
            vec![
                Point::new(0.0, 0.0),
                Point::new(3.0, -1.0),
                Point::new(4.0, 2.0),
            ],
            weights,
        )
        .unwrap();
        let k = run(&c, 1, &[-2.0, 6.0, -3.0, 5.0], Sign::Positive);
        // The box [-2, 6] x [-3, 5] below y = x / 2.
        let exact = ConvexPolygon::rectangle(-2.0, 6.0, -3.0, 5.0).clip(0.5, -1.0, 0.0, 10.0);
        assert!((polygon(&k.levels[0].region).area() - exact.area()).abs() < 1e-9);
        assert!((polygon(&k.outer).area() - exact.area()).abs() < 1e-9);
        assert_eq!(k.outcome, Outcome::Converged);
        assert_eq!(k.levels.len(), 2); // nothing to gain at level 1
    }
}

#[test]
fn rational_curves_bracket_the_domain_too() {
    let c = NurbsCurve::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0],
        vec![
            Point::new(0.0, 0.0),
            Point::new(2.0, -1.5),
            Point::new(4.0, -1.0),
            Point::new(5.5, 1.0),
            Point::new(6.0, 3.0),
        ],
        Some(vec![1.0, 2.0, 0.7, 1.5, 1.0]),
    )
    .unwrap();
    let k = run(&c, 2, &[0.0, 8.0, -5.0, 3.0], Sign::Positive);
    assert!(!k.inner().is_empty());
    let outer = polygon(&k.outer);
    for l in &k.levels {
        for &v in polygon(&l.region).vertices() {
            assert!(outer.contains(v, 1e-9));
            assert!(
                min_numerator(&c.with_control_point(2, v).unwrap()) >= -1e-9,
                "{v:?}"
            );
        }
    }
    assert!(outer.area() - polygon(k.inner()).area() < 1e-2 * outer.area());
}

#[test]
fn empty_domains_are_reported() {
    // A line: zero curvature whatever the point.
    let line = NurbsCurve::bezier(vec![Point::new(0.0, 0.0), Point::new(1.0, 1.0)], None).unwrap();
    let k = run(&line, 1, &[-1.0, 1.0, -1.0, 1.0], Sign::Positive);
    assert_eq!(k.outcome, Outcome::Empty);
    assert!(k.outer.is_empty() && k.inner().is_empty());
    // An S-shaped cubic B-spline whose inflection is in a piece the free (first) point does
    // not touch: no position keeps the sign.
    let s = NurbsCurve::new(
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0],
        vec![
            Point::new(0.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(2.0, 1.0),
            Point::new(3.0, 0.0),
            Point::new(4.0, -3.0),
            Point::new(5.0, 4.0),
        ],
        None,
    )
    .unwrap();
    assert!(min_curvature(&s) < 0.0 && min_curvature(&s.reversed()) < 0.0);
    let k = run(&s, 0, &[-5.0, 5.0, -5.0, 5.0], Sign::Positive);
    assert_eq!(k.outcome, Outcome::Empty);
}

/// Torsion numerator `[C', C'', C''']` of a polynomial Bezier space curve from its hodographs.
fn torsion_numerator(p: &[[f64; 3]], t: f64) -> f64 {
    fn hodograph(p: &[[f64; 3]]) -> Vec<[f64; 3]> {
        let n = (p.len() - 1) as f64;
        p.windows(2)
            .map(|w| {
                [
                    n * (w[1][0] - w[0][0]),
                    n * (w[1][1] - w[0][1]),
                    n * (w[1][2] - w[0][2]),
                ]
            })
            .collect()
    }
    fn eval(p: &[[f64; 3]], t: f64) -> [f64; 3] {
        let mut q = p.to_vec();
        while q.len() > 1 {
            q = q
                .windows(2)
                .map(|w| std::array::from_fn(|k| (1.0 - t) * w[0][k] + t * w[1][k]))
                .collect();
        }
        q[0]
    }
    let d1 = hodograph(p);
    let d2 = hodograph(&d1);
    let d3 = hodograph(&d2);
    let (a, b, c) = (eval(&d1, t), eval(&d2, t), eval(&d3, t));
    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

/// The torsion numerator of a space Bezier curve with control point 2 free, and the sign the
/// given curve has at the middle (the sign to keep).
fn torsion_with_free_point_2(pts: &[[f64; 3]; 6]) -> (SignNumerator, Sign) {
    let c = SpaceCurve::bezier(&pts.map(Point3::from), None).unwrap();
    let h = SignNumerator::torsion(&c, 2).unwrap();
    let sign = if torsion_numerator(pts, 0.5) > 0.0 {
        Sign::Positive
    } else {
        Sign::Negative
    };
    (h, sign)
}

/// `v` with the sign to keep made positive.
fn signed(sign: Sign, v: f64) -> f64 {
    if sign == Sign::Positive { v } else { -v }
}

#[test]
fn torsion_polytopes_keep_the_sign_and_grow() {
    // A quintic helix-like space curve, free point 2 at the origin, a 200-unit box (as in the
    // paper's Fig. 5 setting).
    let pts = [
        [-40.0, -10.0, -30.0],
        [-30.0, 30.0, -20.0],
        [0.0, 0.0, 0.0],
        [30.0, -30.0, 10.0],
        [40.0, 10.0, 30.0],
        [20.0, 40.0, 50.0],
    ];
    let (h, sign) = torsion_with_free_point_2(&pts);
    assert_eq!(h.degree(), 9); // 3p - 6: ten coefficients, as in the paper's Table 3
    let options = ConvexDomainOptions::DEFAULT
        .with_sign(sign)
        .with_relative_tolerance(1e-3)
        .with_max_level(5)
        .with_outer_samples(128);
    let bbox = BoundingBox3::from_ranges(&[-100.0, 100.0, -100.0, 100.0, -100.0, 100.0]).unwrap();
    let k = approximate(&h, &bbox, &options).unwrap();
    assert!(!k.inner().is_empty(), "{:?}", k.outcome);
    // Minimum of the signed torsion numerator over a dense grid, relative to its largest
    // magnitude.
    let want = |d: [f64; 3]| {
        let mut q = pts;
        q[2] = d;
        let values: Vec<f64> = (0..=2000)
            .map(|i| torsion_numerator(&q, i as f64 / 2000.0))
            .map(|v| signed(sign, v))
            .collect();
        let scale = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        values.iter().fold(f64::INFINITY, |m, &v| m.min(v)) / scale
    };
    let mut last = 0.0;
    for l in &k.levels {
        let v = l.region.measure();
        assert!(
            v >= last - 1e-6 * v.abs().max(1.0),
            "volume shrank at level {}",
            l.level
        );
        last = v;
        for d in l.region.vertices3() {
            let d = d.to_array();
            assert!(want(d) >= -1e-9, "vertex {d:?} of level {}", l.level);
        }
    }
    assert!(k.outer.measure() >= k.inner().measure());
    // Just beyond a vertex of the outer polytope that is not on the box, some sampled
    // half-space is violated: the torsion changes sign (checked at the sampled parameters).
    let Region::Polytope(outer) = &k.outer else {
        panic!()
    };
    let c_out = outer.vertex_centroid().unwrap().to_array();
    let on_box = |v: [f64; 3]| v.iter().any(|x| x.abs() >= 100.0 - 1e-9);
    let signed_min_at_samples = |d: [f64; 3]| {
        let mut q = pts;
        q[2] = d;
        (0..options.outer_samples)
            .map(|i| torsion_numerator(&q, i as f64 / (options.outer_samples - 1) as f64))
            .map(|v| signed(sign, v))
            .fold(f64::INFINITY, f64::min)
    };
    let mut beyond = 0;
    for v in outer
        .vertices()
        .into_iter()
        .map(|v| v.to_array())
        .filter(|v| !on_box(*v))
    {
        let d: [f64; 3] = std::array::from_fn(|i| v[i] + 1e-3 * (v[i] - c_out[i]));
        assert!(signed_min_at_samples(d) < 0.0, "beyond {v:?}");
        beyond += 1;
    }
    assert!(beyond >= 3, "{beyond}");
    // A point well inside the last polytope keeps the sign strictly.
    let Region::Polytope(p) = k.inner() else {
        panic!()
    };
    let centre = p.vertex_centroid().unwrap().to_array();
    assert!(want(centre) > 0.0);
}

#[test]
fn bad_input_is_an_error_not_a_panic() {
    let h = SignNumerator::curvature(&cubic(), 2).unwrap();
    let b3 = BoundingBox3::from_ranges(&[0.0, 1.0, 0.0, 1.0, 0.0, 1.0]).unwrap();
    assert!(approximate(&h, &b3, &ConvexDomainOptions::default()).is_err());
    assert!(BoundingBox3::from_ranges(&[0.0, 1.0, 1.0]).is_err());
    assert!(BoundingBox3::from_ranges(&[1.0, 0.0, 0.0, 1.0]).is_err());
    assert!(BoundingBox3::from_ranges(&[0.0, f64::NAN, 0.0, 1.0]).is_err());
    let b2 = BoundingBox3::from_ranges(&[0.0, 1.0, 0.0, 1.0]).unwrap();
    let bad = ConvexDomainOptions::DEFAULT.with_relative_tolerance(-1.0);
    assert!(approximate(&h, &b2, &bad).is_err());
    let too_deep = ConvexDomainOptions::DEFAULT.with_max_level(40);
    let e = approximate(&h, &b2, &too_deep).unwrap_err().to_string();
    assert!(e.contains("max level 40"), "{e}");
}

/// The inner polytopes lie inside the true domain and the outer bound contains it, checked
/// against a Monte Carlo estimate of the true volume, in the case that used to double-count a
/// face: the t = 0 constraint plane (through P0, P1, P3, all at z = 0) is the box floor.
#[test]
fn torsion_volumes_bracket_a_monte_carlo_estimate_when_a_constraint_is_a_box_face() {
    let pts = [
        [-40.0, -10.0, 0.0],
        [-30.0, 30.0, 0.0],
        [0.0, 0.0, 20.0],
        [30.0, -30.0, 0.0],
        [40.0, 10.0, 30.0],
        [20.0, 40.0, 50.0],
    ];
    let (h, sign) = torsion_with_free_point_2(&pts);
    let options = ConvexDomainOptions::DEFAULT
        .with_sign(sign)
        .with_relative_tolerance(1e-4)
        .with_max_level(4)
        .with_outer_samples(128);
    let r = [-100.0, 100.0, -100.0, 100.0, 0.0, 100.0];
    let bbox = BoundingBox3::from_ranges(&r).unwrap();
    let k = approximate(&h, &bbox, &options).unwrap();
    // Monte Carlo: the fraction of the box where the sign holds at 129 parameters (a fixed
    // xorshift sequence, so the test is deterministic; 3 sigma is about 4% of the volume).
    let n = 100_000;
    let mut hits = 0usize;
    let mut rng = rs_testkit::XorShift64::new(0x9e37_79b9_7f4a_7c15);
    for _ in 0..n {
        let d = [
            rng.uniform(r[0], r[1]),
            rng.uniform(r[2], r[3]),
            rng.uniform(r[4], r[5]),
        ];
        let mut q = pts;
        q[2] = d;
        let keeps = (0..=128).all(|i| signed(sign, torsion_numerator(&q, i as f64 / 128.0)) >= 0.0);
        hits += usize::from(keeps);
    }
    let volume = 200.0 * 200.0 * 100.0;
    let p = hits as f64 / n as f64;
    let truth = p * volume;
    let sigma = (p * (1.0 - p) / n as f64).sqrt() * volume;
    assert!(p > 0.01, "the test needs a non-trivial domain: {p}");
    for l in &k.levels {
        let v = l.region.measure();
        assert!(
            v <= truth + 3.0 * sigma,
            "level {}: {v} > {truth} +- {sigma}",
            l.level
        );
    }
    assert!(
        k.outer.measure() >= truth - 3.0 * sigma,
        "outer {} < {truth}",
        k.outer.measure()
    );
    assert!(k.outer.measure() >= k.inner().measure());
}
