//! Splines on curved triangulations against independent truth: the dimension formula (5.2),
//! exact reproduction of polynomials of the spline's degree (d = 1..8) on domains with holes
//! and corners, refined or not, continuity across every interior edge, evaluation in the
//! slivers, Clough–Tocher and Powell–Sabin refinements that tile the domain, and the spline
//! file's round trip.

mod common;
use common::test_points;

use std::collections::{HashMap, HashSet};

use rs_mesh::{CurvedTriangulation, EdgeKind, Refinement, well_spaced_points};
use rs_spline::prelude::*;
use rs_spline::{Domain, Point};
use rs_trispline::bb::{Order, coefficient_count};
use rs_trispline::{SplineSpace, quasi_interpolate, spline_from_json, spline_to_json};

fn domains() -> Vec<(String, Domain)> {
    let mut v: Vec<(String, Domain)> = ["s4_disk_ellipse_segment", "l_shape", "s3_m_shape"]
        .iter()
        .map(|n| (n.to_string(), rs_testkit::inrs_fixture(n).domain))
        .collect();
    let annulus = rs_testkit::annulus();
    v.push((annulus.name, annulus.domain));
    v
}

fn mesh(d: &Domain, ny: usize) -> CurvedTriangulation {
    CurvedTriangulation::new(d, &well_spaced_points(d, ny).unwrap()).unwrap()
}

/// A polynomial of total degree `deg` with coefficients that do not cancel.
fn polynomial(deg: usize) -> impl Fn(Point) -> f64 + Sync {
    move |p: Point| {
        let mut v = 0.0;
        for a in 0..=deg {
            for b in 0..=deg - a {
                let c = ((a * 7 + b * 3) % 5) as f64 - 1.7;
                v += c * p.x.powi(a as i32) * p.y.powi(b as i32);
            }
        }
        v
    }
}

#[test]
fn dimension_is_formula_5_2() {
    for (name, d) in domains() {
        let m = mesh(&d, 7);
        let nv = m.vertices().len();
        let mut edges = HashSet::new();
        for t in m.triangles() {
            for k in 0..3 {
                edges.insert((t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3])));
            }
        }
        let (ne, nt) = (edges.len(), m.triangles().len());
        for deg in 1..=6 {
            let space = SplineSpace::new(&m, deg);
            let distinct: HashSet<u32> = (0..nt)
                .flat_map(|t| space.triangle_indices(t).to_vec())
                .collect();
            let inner = if deg >= 3 {
                (deg - 1) * (deg - 2) / 2
            } else {
                0
            };
            let formula = nv + (deg - 1) * ne + inner * nt;
            assert_eq!(space.dimension(), formula, "{name} d={deg}");
            assert_eq!(distinct.len(), formula, "{name} d={deg}");
            assert_eq!(*distinct.iter().max().unwrap() as usize, formula - 1);
        }
    }
}

#[test]
fn quasi_interpolation_reproduces_polynomials_of_its_degree() {
    for (name, d) in domains() {
        let m = mesh(&d, 6);
        let pts = test_points(&m);
        for deg in 1..=8 {
            let f = polynomial(deg);
            let s = quasi_interpolate(m.clone(), deg, &f).unwrap();
            let eval = s.evaluator().unwrap();
            let scale = pts.iter().map(|&p| f(p).abs()).fold(1.0, f64::max);
            let mut evaluated = 0;
            for &p in &pts {
                if let Some(j) = eval.evaluate(p, Order::Value) {
                    evaluated += 1;
                    let err = (j.value - f(p)).abs();
                    assert!(err < 1e-9 * scale, "{name} d={deg} at {p:?}: error {err:e}");
                }
            }
            assert!(
                evaluated > pts.len() * 9 / 10,
                "{name}: {evaluated} of {}",
                pts.len()
            );
        }
    }
}

#[test]
fn refinements_tile_the_domain_and_reproduce_polynomials() {
    for (name, d) in domains() {
        let pts = well_spaced_points(&d, 6).unwrap();
        let area = d.signed_area().abs();
        for how in [Refinement::CloughTocher, Refinement::PowellSabin] {
            let r = CurvedTriangulation::new_refined(&d, &pts, how).unwrap();
            assert_eq!(r.refinement(), Some(how));
            // Each unrefined triangle split into exactly `factor` sub-triangles.
            let mut children: HashMap<usize, usize> = HashMap::new();
            for t in 0..r.triangles().len() {
                *children.entry(r.parent_triangle(t).unwrap()).or_default() += 1;
            }
            assert!(
                children.values().all(|&c| c == how.factor()),
                "{name} {how:?}"
            );
            assert_eq!(r.triangles().len(), how.factor() * children.len());
            // Valid sub-triangles whose curved areas add up to the domain's.
            let mut total = 0.0;
            for t in 0..r.triangles().len() {
                let [a, b, c] = r.triangles()[t].map(|v| r.vertices()[v]);
                assert!((b - a).cross(c - a) > 0.0, "{name} {how:?}: triangle {t}");
                let at = r.triangle_area(t);
                assert!(at > 0.0, "{name} {how:?}: curved triangle {t} area {at}");
                total += at;
            }
            assert!(
                (total - area).abs() < 1e-12 * area,
                "{name} {how:?}: {total} vs {area}"
            );
            // S_d^0 on the refinement reproduces polynomials of degree d.
            let f = polynomial(3);
            let s = quasi_interpolate(r, 3, &f).unwrap();
            let eval = s.evaluator().unwrap();
            for p in test_points(s.mesh()) {
                if let Some(j) = eval.evaluate(p, Order::Value) {
                    assert!(
                        (j.value - f(p)).abs() < 1e-9 * (1.0 + f(p).abs()),
                        "{name} {p:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn splines_are_continuous_across_every_interior_edge() {
    let f = |p: Point| (10.0 * p.x).sin() + (10.0 * p.y).sin();
    for (name, d) in domains() {
        for deg in [2, 5] {
            let m = mesh(&d, 8);
            let s = quasi_interpolate(m, deg, &f).unwrap();
            let m = s.mesh();
            let mut owner: HashMap<(usize, usize), usize> = HashMap::new();
            let mut checked = 0;
            for (t, tri) in m.triangles().iter().enumerate() {
                for k in 0..3 {
                    if m.edge_kinds(t)[k] != EdgeKind::Straight {
                        continue;
                    }
                    let (a, b) = (tri[k], tri[(k + 1) % 3]);
                    let key = (a.min(b), a.max(b));
                    let Some(&other) = owner.get(&key) else {
                        owner.insert(key, t);
                        continue;
                    };
                    for i in 0..=10 {
                        let p = m.vertices()[a]
                            + (m.vertices()[b] - m.vertices()[a]) * (i as f64 / 10.0);
                        let (u, v) = (
                            s.evaluate_on(t, p, Order::Value).value,
                            s.evaluate_on(other, p, Order::Value).value,
                        );
                        assert!(
                            (u - v).abs() <= 1e-12 * (1.0 + u.abs()),
                            "{name} d={deg}: {u} vs {v}"
                        );
                    }
                    checked += 1;
                }
            }
            assert!(checked > 20, "{name}: {checked}");
        }
    }
}

#[test]
fn slivers_evaluate_their_triangles_polynomial() {
    let f = |p: Point| (3.0 * p.x).exp() * p.y;
    for (name, d) in domains() {
        let s = quasi_interpolate(mesh(&d, 6), 4, &f).unwrap();
        let eval = s.evaluator().unwrap();
        let m = s.mesh();
        let mut slivers = 0;
        for a in m.arcs() {
            let c = m.arc_curve(a).unwrap();
            let (u0, u1) = c.param_range();
            for t in [0.25, 0.5, 0.75] {
                let on = c.point_at(u0 + t * (u1 - u0));
                let chord = m.vertices()[a.from] * (1.0 - t) + m.vertices()[a.to] * t;
                // Just inside the curve, between it and the chord (where the arc bulges out).
                let p = on * 0.999 + chord * 0.001;
                let [va, vb, vc] = m.triangles()[a.triangle].map(|v| m.vertices()[v]);
                let tri = rs_trispline::bb::Triangle::new(va, vb, vc);
                if tri.barycentric(p).iter().any(|&b| b < -1e-9) && on.distance(chord) > 1e-6 {
                    let got = eval.evaluate(p, Order::Gradient).unwrap();
                    let want = s.evaluate_on(a.triangle, p, Order::Gradient);
                    assert_eq!(got, want, "{name} at {p:?}");
                    slivers += 1;
                }
            }
        }
        assert!(slivers > 0, "{name}: no sliver point tested");
    }
}

#[test]
fn the_spline_file_round_trips() {
    let d = rs_testkit::inrs_fixture("s4_disk_ellipse_segment").domain;
    let f = |p: Point| (2.0 * p.x).sin() * p.y;
    let s = quasi_interpolate(mesh(&d, 5), 3, &f).unwrap();
    let text = spline_to_json(&s);
    let back = spline_from_json(&text).unwrap();
    assert_eq!(back.degree(), 3);
    assert_eq!(back.coefficients(), s.coefficients());
    assert_eq!(back.mesh().triangles(), s.mesh().triangles());
    let (e1, e2) = (s.evaluator().unwrap(), back.evaluator().unwrap());
    for p in test_points(s.mesh()) {
        assert_eq!(
            e1.evaluate(p, Order::Hessian),
            e2.evaluate(p, Order::Hessian)
        );
    }
    // The coefficients are stored per triangle in the documented order: c_300 is the value
    // at the first vertex.
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let t0 = v["triangles"][0].as_array().unwrap()[0].as_u64().unwrap() as usize;
    let c300 = v["coefficients"][0][0].as_f64().unwrap();
    let at = s.mesh().vertices()[t0];
    assert!((c300 - s.evaluate_on(0, at, Order::Value).value).abs() < 1e-14);
    assert_eq!(
        v["coefficients"][0].as_array().unwrap().len(),
        coefficient_count(3)
    );
    // Broken files are errors, never panics.
    for broken in [
        text.replace("\"degree\":3", "\"degree\":30"),
        text.replace("\"space\":\"s0\"", "\"space\":\"s9\""),
        text.replacen("[[", "[[9999,", 1),
        "{}".to_string(),
        text[..text.len() / 2].to_string(),
    ] {
        assert!(spline_from_json(&broken).is_err());
    }
}

/// The ordinary triangle quasi-interpolation samples on lies in the curved triangle: every
/// domain point of it is in the domain (inside or on the boundary) and in the companion
/// triangle; it is the companion exactly where no arc bulges into it, and smaller (but not
/// tiny) where the boundary is concave, as round the annulus's hole.
#[test]
fn inner_triangles_lie_in_their_curved_triangles() {
    use rs_contain::{Classifier, ContainOptions, Locate, Location};
    use rs_trispline::bb::Triangle;
    for (name, d) in domains() {
        let m = mesh(&d, 7);
        let c = Classifier::new(&d, ContainOptions::default()).unwrap();
        let mut shrunk = 0;
        for t in 0..m.triangles().len() {
            let [a, b, v] = m.triangles()[t].map(|i| m.vertices()[i]);
            let companion = Triangle::new(a, b, v);
            let inner = rs_trispline::inner_triangle(&m, t).unwrap();
            if inner != companion {
                shrunk += 1;
                let ratio = inner.double_area() / companion.double_area();
                assert!(
                    ratio > 0.05 && ratio < 1.0,
                    "{name} triangle {t}: ratio {ratio}"
                );
            }
            for p in inner.domain_points(5) {
                assert_ne!(
                    c.locate(p),
                    Location::Outside,
                    "{name} triangle {t} at {p:?}"
                );
                assert!(companion.barycentric(p).iter().all(|&x| x >= -1e-12));
            }
        }
        if name.contains("annulus") {
            assert!(shrunk > 0, "{name}: no triangle at the hole was shrunk");
        }
    }
}
