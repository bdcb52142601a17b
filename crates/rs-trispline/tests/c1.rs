//! `C^1` splines for scattered data (Schumaker and Yu 2021, Sections 9-10) against
//! independent truth: the Hermite elements reproduce the polynomials of their degree from
//! exact derivatives, each two-stage method reproduces the polynomials of its fit's degree,
//! every spline interpolates its data, joins with `C^1` across every interior edge (and `C^2`
//! at the vertices for `S_5^{1,2}`), minimal energy reproduces linear functions and has less
//! energy than the two-stage Powell–Sabin spline, and bad data are clear errors.

mod common;
use common::test_points;

use std::collections::HashMap;

use rs_contain::{Classifier, ContainOptions, Locate, Location};
use rs_mesh::{CurvedTriangulation, EdgeKind, well_spaced_points};
use rs_spline::{Domain, Point};
use rs_trispline::bb::{Jet, Order};
use rs_trispline::{
    C1Space, ExactJets, ScatteredFit, Spline, TriSplineError, energy, hermite_interpolate,
    interpolate_on, interpolate_scattered, spline_from_json, spline_to_json,
};

const SPACES: [C1Space; 4] = [
    C1Space::SuperSpline,
    C1Space::CloughTocher,
    C1Space::PowellSabin,
    C1Space::MinimalEnergy,
];

fn domains() -> Vec<(String, Domain)> {
    let mut v: Vec<(String, Domain)> = ["s4_disk_ellipse_segment", "s3_m_shape"]
        .iter()
        .map(|n| (n.to_string(), rs_testkit::inrs_fixture(n).domain))
        .collect();
    let annulus = rs_testkit::annulus();
    v.push((annulus.name, annulus.domain));
    v
}

fn mesh(d: &Domain, ny: usize, space: C1Space) -> CurvedTriangulation {
    let pts = well_spaced_points(d, ny).unwrap();
    match space.refinement() {
        None => CurvedTriangulation::new(d, &pts).unwrap(),
        Some(how) => CurvedTriangulation::new_refined(d, &pts, how).unwrap(),
    }
}

/// A polynomial of total degree `deg` with coefficients that do not cancel, with its
/// derivatives.
fn polynomial(deg: usize) -> impl Fn(Point) -> Jet + Sync {
    move |p: Point| {
        let mut j = Jet::default();
        let pw = |x: f64, n: i32| if n < 0 { 0.0 } else { x.powi(n) };
        for a in 0..=deg as i32 {
            for b in 0..=deg as i32 - a {
                let c = ((a * 7 + b * 3) % 5) as f64 - 1.7;
                let (fa, fb) = (f64::from(a), f64::from(b));
                j.value += c * pw(p.x, a) * pw(p.y, b);
                j.gradient[0] += c * fa * pw(p.x, a - 1) * pw(p.y, b);
                j.gradient[1] += c * fb * pw(p.x, a) * pw(p.y, b - 1);
                j.hessian[0] += c * fa * (fa - 1.0) * pw(p.x, a - 2) * pw(p.y, b);
                j.hessian[1] += c * fa * fb * pw(p.x, a - 1) * pw(p.y, b - 1);
                j.hessian[2] += c * fb * (fb - 1.0) * pw(p.x, a) * pw(p.y, b - 2);
            }
        }
        j
    }
}

fn max_error(s: &Spline, f: &dyn Fn(Point) -> f64) -> f64 {
    let eval = s.evaluator().unwrap();
    // Points of the closed domain (a sliver point of a hole's arc lies in the hole).
    let inside = Classifier::new(s.mesh().domain(), ContainOptions::DEFAULT).unwrap();
    let pts: Vec<Point> = test_points(s.mesh())
        .into_iter()
        .filter(|&p| inside.locate(p) != Location::Outside)
        .collect();
    let mut worst = 0.0f64;
    for (p, v) in pts.iter().zip(eval.evaluate_all(&pts)) {
        let v = v.unwrap_or_else(|| panic!("{p:?} is in no triangle"));
        worst = worst.max((v.value - f(*p)).abs());
    }
    worst
}

fn data(m: &CurvedTriangulation, f: &dyn Fn(Point) -> f64) -> (Vec<Point>, Vec<f64>) {
    let sites = well_spaced_points(m.domain(), 7).unwrap().all_points();
    let values = sites.iter().map(|&p| f(p)).collect();
    (sites, values)
}

#[test]
fn hermite_elements_reproduce_polynomials_of_their_degree() {
    for (name, d) in domains() {
        for space in &SPACES[..3] {
            let deg = space.degree();
            let m = mesh(&d, 7, *space);
            let f = polynomial(deg);
            let s =
                hermite_interpolate(m, *space, &ExactJets::new(&mesh(&d, 7, *space), &f)).unwrap();
            let e = max_error(&s, &|p| f(p).value);
            assert!(e < 1e-9, "{name} {space:?}: error {e:e}");
            // One degree more is not reproduced (the test can fail).
            let g = polynomial(deg + 1);
            let m = mesh(&d, 7, *space);
            let s =
                hermite_interpolate(m, *space, &ExactJets::new(&mesh(&d, 7, *space), &g)).unwrap();
            assert!(max_error(&s, &|p| g(p).value) > 1e-6, "{name} {space:?}");
        }
    }
}

#[test]
fn two_stage_methods_reproduce_polynomials_of_their_fit_degree() {
    for (name, d) in domains() {
        for space in SPACES {
            // Minimal energy reproduces linear functions only (tested below).
            let deg = if space == C1Space::MinimalEnergy {
                1
            } else {
                space.fit_degree()
            };
            let m = mesh(&d, 7, space);
            let f = polynomial(deg);
            let f = |p: Point| f(p).value;
            let (sites, values) = data(&m, &f);
            let fit = interpolate_on(m, space, &sites, &values).unwrap();
            let e = max_error(&fit.spline, &f);
            assert!(e < 1e-8, "{name} {space:?}: error {e:e}");
        }
    }
}

fn wave(p: Point) -> f64 {
    (20.0 * p.x).sin() + (20.0 * p.y).sin()
}

/// Every interior edge of the spline's mesh (shared by two triangles): points along it and
/// the two triangles.
fn interior_edges(m: &CurvedTriangulation) -> Vec<(Point, Point, usize, usize)> {
    let mut by_edge: HashMap<(usize, usize), Vec<usize>> = HashMap::new();
    for (t, tri) in m.triangles().iter().enumerate() {
        for k in 0..3 {
            if m.edge_kinds(t)[k] == EdgeKind::Straight {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                by_edge.entry((a.min(b), a.max(b))).or_default().push(t);
            }
        }
    }
    by_edge
        .into_iter()
        .filter(|(_, ts)| ts.len() == 2)
        .map(|((a, b), ts)| (m.vertices()[a], m.vertices()[b], ts[0], ts[1]))
        .collect()
}

fn fitted(d: &Domain, space: C1Space, ny: usize) -> (ScatteredFit, Vec<Point>, Vec<f64>) {
    let m = mesh(d, ny, space);
    let sites = well_spaced_points(d, ny).unwrap().all_points();
    let values: Vec<f64> = sites.iter().map(|&p| wave(p)).collect();
    (
        interpolate_on(m, space, &sites, &values).unwrap(),
        sites,
        values,
    )
}

#[test]
fn every_spline_interpolates_its_data_and_is_c1_across_every_interior_edge() {
    for (name, d) in domains() {
        for space in SPACES {
            let (fit, sites, values) = fitted(&d, space, 9);
            let s = &fit.spline;
            // Interpolation at every data point that is a vertex (all but dropped ones).
            let eval = s.evaluator().unwrap();
            let mut checked = 0;
            for (i, (&p, &z)) in sites.iter().zip(&values).enumerate() {
                if fit.unused_points.contains(&i) {
                    continue;
                }
                let v = eval.evaluate(p, Order::Value).unwrap().value;
                assert!(
                    (v - z).abs() <= 1e-10 * z.abs().max(1.0),
                    "{name} {space:?}: {v} at {p:?}, data {z}"
                );
                checked += 1;
            }
            assert!(checked + fit.unused_points.len() == sites.len() && checked > 20);
            // C1 across every interior edge, macro-element inner edges included.
            let edges = interior_edges(s.mesh());
            assert!(edges.len() > 50, "{name}");
            let mut worst = 0.0f64;
            for (a, b, t0, t1) in edges {
                for t in [0.1, 0.37, 0.5, 0.81] {
                    let p = a.lerp(b, t);
                    let (j0, j1) = (
                        s.evaluate_on(t0, p, Order::Hessian),
                        s.evaluate_on(t1, p, Order::Hessian),
                    );
                    let scale = 20.0f64.max(j0.gradient[0].abs()).max(j0.gradient[1].abs());
                    assert!((j0.value - j1.value).abs() <= 1e-10 * scale);
                    for k in 0..2 {
                        let gap = (j0.gradient[k] - j1.gradient[k]).abs() / scale;
                        worst = worst.max(gap);
                    }
                }
            }
            assert!(worst <= 1e-9, "{name} {space:?}: gradient gap {worst:e}");
        }
    }
}

#[test]
fn the_quintic_super_spline_is_c2_at_every_vertex() {
    let (name, d) = &domains()[0];
    let (fit, _, _) = fitted(d, C1Space::SuperSpline, 9);
    let s = &fit.spline;
    let mut around: HashMap<usize, Vec<usize>> = HashMap::new();
    for (t, tri) in s.mesh().triangles().iter().enumerate() {
        for &v in tri {
            around.entry(v).or_default().push(t);
        }
    }
    for (v, ts) in around {
        let p = s.mesh().vertices()[v];
        let h0 = s.evaluate_on(ts[0], p, Order::Hessian).hessian;
        for &t in &ts[1..] {
            let h = s.evaluate_on(t, p, Order::Hessian).hessian;
            for k in 0..3 {
                assert!(
                    (h[k] - h0[k]).abs() <= 1e-9 * 400.0,
                    "{name} vertex {v}: {h:?} {h0:?}"
                );
            }
        }
    }
    // The cubic C1 spaces are not C2 there: the test sees a difference.
    let (fit, _, _) = fitted(d, C1Space::CloughTocher, 9);
    let s = &fit.spline;
    let v = s.mesh().triangles()[0][0];
    let p = s.mesh().vertices()[v];
    let hs: Vec<[f64; 3]> = (0..s.mesh().triangles().len())
        .filter(|&t| s.mesh().triangles()[t].contains(&v))
        .map(|t| s.evaluate_on(t, p, Order::Hessian).hessian)
        .collect();
    assert!(hs.iter().any(|h| (h[0] - hs[0][0]).abs() > 1e-6));
}

#[test]
fn minimal_energy_reproduces_linear_functions_and_beats_the_two_stage_energy() {
    for (name, d) in domains() {
        let f = |p: Point| 2.0 - 3.0 * p.x + 0.5 * p.y;
        let m = mesh(&d, 9, C1Space::MinimalEnergy);
        let (sites, values) = data(&m, &f);
        let fit = interpolate_on(m, C1Space::MinimalEnergy, &sites, &values).unwrap();
        assert!(max_error(&fit.spline, &f) < 1e-9, "{name}");
        assert!(energy(&fit.spline) < 1e-12, "{name}");

        let (ps, _, _) = fitted(&d, C1Space::PowellSabin, 9);
        let (me, _, _) = fitted(&d, C1Space::MinimalEnergy, 9);
        let (e_ps, e_me) = (energy(&ps.spline), energy(&me.spline));
        assert!(e_me < e_ps, "{name}: minimal {e_me} two-stage {e_ps}");
        assert!(e_me > 0.0);
    }
}

#[test]
fn the_energy_of_a_quadratic_is_its_hessian_norm_times_the_area() {
    // s = x^2 + 3 x y - y^2: s_xx^2 + 2 s_xy^2 + s_yy^2 = 4 + 18 + 4 = 26 everywhere.
    let (_, d) = &domains()[0];
    let f = |p: Point| Jet {
        value: p.x * p.x + 3.0 * p.x * p.y - p.y * p.y,
        gradient: [2.0 * p.x + 3.0 * p.y, 3.0 * p.x - 2.0 * p.y],
        hessian: [2.0, 3.0, -2.0],
    };
    for space in &SPACES[..3] {
        let m = mesh(d, 7, *space);
        let area: f64 = (0..m.triangles().len())
            .map(|t| {
                let [a, b, c] = m.triangles()[t].map(|v| m.vertices()[v]);
                0.5 * (b - a).cross(c - a)
            })
            .sum();
        let s = hermite_interpolate(m, *space, &ExactJets::new(&mesh(d, 7, *space), &f)).unwrap();
        let e = energy(&s);
        assert!(
            (e - 26.0 * area).abs() < 1e-8 * e,
            "{space:?}: {e} {}",
            26.0 * area
        );
    }
}

#[test]
fn scattered_points_in_any_order_are_interpolated_and_bad_points_are_named() {
    let (_, d) = &domains()[0];
    // Boundary points slightly off the curve (within the tolerance) and interior points, in
    // a shuffled order.
    let pts = well_spaced_points(d, 9).unwrap();
    let mut points: Vec<Point> = pts.all_points();
    points.reverse();
    let values: Vec<f64> = points.iter().map(|&p| wave(p)).collect();
    for space in SPACES {
        let fit = interpolate_scattered(d, &points, &values, space).unwrap();
        let eval = fit.spline.evaluator().unwrap();
        for (i, (&p, &z)) in points.iter().zip(&values).enumerate() {
            if !fit.unused_points.contains(&i) {
                let v = eval.evaluate(p, Order::Value).unwrap().value;
                assert!((v - z).abs() < 1e-9, "{space:?} {p:?}: {v} {z}");
            }
        }
        // The file keeps the space and the spline.
        let back = spline_from_json(&spline_to_json(&fit.spline)).unwrap();
        assert_eq!(back.kind(), space.kind());
        assert_eq!(back.coefficients(), fit.spline.coefficients());
    }
    // A point outside, a repeated point, a value that is not finite: errors naming the point.
    let mut bad = points.clone();
    bad[4] = Point::new(100.0, 100.0);
    let e = interpolate_scattered(d, &bad, &values, C1Space::PowellSabin).unwrap_err();
    assert!(
        matches!(e, TriSplineError::DataPoint { index: 4, .. }),
        "{e}"
    );
    assert!(e.to_string().contains("data point 5") && e.to_string().contains("outside"));
    let mut bad = points.clone();
    bad[7] = bad[2];
    let e = interpolate_scattered(d, &bad, &values, C1Space::PowellSabin).unwrap_err();
    assert!(
        e.to_string().contains("data point 8") && e.to_string().contains("repeats"),
        "{e}"
    );
    let mut bad_values = values.clone();
    bad_values[3] = f64::NAN;
    let e = interpolate_scattered(d, &points, &bad_values, C1Space::CloughTocher).unwrap_err();
    assert!(
        matches!(e, TriSplineError::DataPoint { index: 3, .. }),
        "{e}"
    );
    // A mesh that is not the space's refinement.
    let m = mesh(d, 7, C1Space::SuperSpline);
    let (sites, vals) = data(&m, &wave);
    assert!(matches!(
        interpolate_on(m, C1Space::PowellSabin, &sites, &vals),
        Err(TriSplineError::WrongTriangulation { .. })
    ));
}
