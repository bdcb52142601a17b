//! `monomial_moments` on the inRS paper's domains and on a domain with two holes, against an
//! independent computation: the boundary flattened within `1e-13` of the bounding box's
//! diagonal (`Domain::flatten_loop`) and the polygon's exact moments, summed over a fan of
//! triangles from the box's centre with the closed form of Dirichlet's integral on a triangle
//! (no Green's theorem, no quadrature):
//!
//! `integral over the triangle (0, p, q) of x^a y^b = det(p, q) a! b! / (a + b + 2)! G(a, b)`,
//! `G(a, b) = sum_{i <= a, k <= b} C(i + k, i) C(a - i + b - k, a - i) p_x^i p_y^k q_x^(a-i)
//! q_y^(b-k)`, computed by the recurrences of its generating function
//! `1 / ((1 - p_x X - p_y Y)(1 - q_x X - q_y Y))`.
//!
//! Tolerance: the polygon and the domain differ by a region of area at most `delta x
//! perimeter` (`delta` the flattening accuracy), on which `|x^a y^b| <= max over the box`;
//! relative to the scale `area x max over the box of |x^a y^b|` the error is at most
//! `delta perimeter / area`, allowed twice, plus `1e-13` for rounding.
//!
//! Cost: about 10^7 vertices per domain, flattened once; the per-edge recurrences run degree
//! by degree on slices and the edges are shared among threads.

use rs_cubature::monomial_moments;
mod common;

use common::{binomial, factorial};
use rs_spline::prelude::*;
use rs_spline::{Domain, Point, circle, polyline};

const DEGREE: usize = 20;
const RELATIVE_FLATTENING: f64 = 1e-13;

fn index(a: usize, b: usize) -> usize {
    let k = a + b;
    k * (k + 1) / 2 + b
}

/// Moments about `c` (of `(x - cx)^a (y - cy)^b`) of the polygon `ring` (closed or not),
/// positive for a counter-clockwise ring; with the ring's shoelace area. The edges are
/// shared among threads (each sums its own range; the sums are then added).
fn ring_moments(ring: &[Point], c: Point, degree: usize) -> (Vec<f64>, f64) {
    let n = ring.len();
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get().min(8));
    let chunk = n.div_ceil(threads);
    let parts: Vec<(Vec<f64>, f64)> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..n)
            .step_by(chunk.max(1))
            .map(|start| s.spawn(move || edge_sums(ring, start..(start + chunk).min(n), c, degree)))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let dim = (degree + 1) * (degree + 2) / 2;
    let mut total = vec![0.0; dim];
    let mut area = 0.0;
    for (sums, a) in parts {
        area += a;
        for (t, v) in total.iter_mut().zip(sums) {
            *t += v;
        }
    }
    for k in 0..=degree {
        for b in 0..=k {
            let a = k - b;
            total[index(a, b)] *= factorial(a) * factorial(b) / factorial(a + b + 2);
        }
    }
    (total, area)
}

/// `sum_e det(p_e, q_e) G(a, b)` over the edges `edges` of the ring (edge `e` from vertex `e`
/// to vertex `e + 1`, cyclically; vertices about `c`), and their shoelace area.
fn edge_sums(
    ring: &[Point],
    edges: std::ops::Range<usize>,
    c: Point,
    degree: usize,
) -> (Vec<f64>, f64) {
    let dim = (degree + 1) * (degree + 2) / 2;
    let mut total = vec![0.0; dim];
    let mut block = vec![0.0; dim];
    let (mut f0, mut g) = (vec![0.0; dim], vec![0.0; dim]);
    let mut area = 0.0;
    let n = ring.len();
    let last = edges.end;
    for e in edges {
        let (p, q) = (ring[e] - c, ring[(e + 1) % n] - c);
        let det = p.x * q.y - q.x * p.y;
        area += 0.5 * det;
        // Degree by degree (entries `b = 0..=k` of degree `k` start at `index(k, 0)`):
        // f0(a, b) = p_x f0(a - 1, b) + p_y f0(a, b - 1), g(a, b) = f0(a, b) + q_x g(a - 1, b)
        // + q_y g(a, b - 1), with f0 = g = 1 at degree 0 and missing terms zero.
        f0[0] = 1.0;
        g[0] = 1.0;
        block[0] += det;
        for k in 1..=degree {
            let (before, from) = (index(k - 1, 0), index(k, 0));
            let (f_prev, f_cur) = f0[before..from + k + 1].split_at_mut(k);
            let (g_prev, g_cur) = g[before..from + k + 1].split_at_mut(k);
            let out = &mut block[from..from + k + 1];
            // b = 0 and b = k have one predecessor; 0 < b < k two: (a - 1, b) is entry b of
            // degree k - 1 and (a, b - 1) entry b - 1.
            f_cur[0] = p.x * f_prev[0];
            g_cur[0] = f_cur[0] + q.x * g_prev[0];
            for (((f, g), fp), gp) in f_cur[1..k]
                .iter_mut()
                .zip(g_cur[1..k].iter_mut())
                .zip(f_prev.windows(2))
                .zip(g_prev.windows(2))
            {
                *f = p.x * fp[1] + p.y * fp[0];
                *g = *f + q.x * gp[1] + q.y * gp[0];
            }
            f_cur[k] = p.y * f_prev[k - 1];
            g_cur[k] = f_cur[k] + q.y * g_prev[k - 1];
            for (o, g) in out.iter_mut().zip(g_cur.iter()) {
                *o += det * g;
            }
        }
        // Sums in blocks of 4096 edges: the rounding of ten million small terms stays small.
        if e % 4096 == 4095 || e + 1 == last {
            for (t, b) in total.iter_mut().zip(block.iter_mut()) {
                *t += *b;
                *b = 0.0;
            }
        }
    }
    (total, area)
}

/// The oracle: the flattened loops, each counted with `+1` (outer) or `-1` (hole) times the
/// sign of its own area; moments about the box centre turned into raw moments by the binomial
/// expansion. Returns the moments, the area and the perimeter.
fn polygon_moments(domain: &Domain, roles: &[f64], degree: usize) -> (Vec<f64>, f64, f64) {
    let bbox = domain.bounding_box();
    let c = Point::new(
        0.5 * (bbox.min.x + bbox.max.x),
        0.5 * (bbox.min.y + bbox.max.y),
    );
    let accuracy = RELATIVE_FLATTENING * bbox.diagonal();
    let dim = (degree + 1) * (degree + 2) / 2;
    let mut central = vec![0.0; dim];
    let (mut area, mut perimeter) = (0.0, 0.0);
    for (i, role) in roles.iter().enumerate() {
        let mut ring = Vec::new();
        domain.flatten_loop(i, accuracy, &mut |p| ring.push(p));
        assert!(ring.len() >= 3, "loop {i}: {} vertices", ring.len());
        perimeter += ring.windows(2).map(|w| (w[1] - w[0]).length()).sum::<f64>();
        let (m, a) = ring_moments(&ring, c, degree);
        let sign = role * a.signum();
        area += sign * a;
        for (t, v) in central.iter_mut().zip(m) {
            *t += sign * v;
        }
    }
    let mut raw = vec![0.0; dim];
    for a in 0..=degree {
        for b in 0..=degree - a {
            let mut s = 0.0;
            for p in 0..=a {
                for q in 0..=b {
                    s += binomial(a, p)
                        * binomial(b, q)
                        * c.x.powi((a - p) as i32)
                        * c.y.powi((b - q) as i32)
                        * central[index(p, q)];
                }
            }
            raw[index(a, b)] = s;
        }
    }
    (raw, area, perimeter)
}

fn check(name: &str, domain: &Domain, roles: &[f64]) {
    let got = monomial_moments(domain, DEGREE, rs_contain::FillRule::EvenOdd).unwrap();
    let (want, area, perimeter) = polygon_moments(domain, roles, DEGREE);
    let bbox = domain.bounding_box();
    let rx = bbox.min.x.abs().max(bbox.max.x.abs());
    let ry = bbox.min.y.abs().max(bbox.max.y.abs());
    let tolerance = 2.0 * RELATIVE_FLATTENING * bbox.diagonal() * perimeter / area + 1e-13;
    let mut worst = 0.0f64;
    for a in 0..=DEGREE {
        for b in 0..=DEGREE - a {
            let k = index(a, b);
            let scale = area * rx.powi(a as i32) * ry.powi(b as i32);
            let err = (got[k] - want[k]).abs() / scale;
            worst = worst.max(err);
            assert!(
                err <= tolerance,
                "{name}: x^{a} y^{b}: {} vs polygon {} (relative {err:e} > {tolerance:e})",
                got[k],
                want[k]
            );
        }
    }
    eprintln!("{name}: worst relative difference {worst:e} (tolerance {tolerance:e})");
}

#[test]
fn paper_domains_match_their_fine_polygons() {
    for name in rs_testkit::PAPER_DOMAINS {
        let path = rs_testkit::fixture_path(&format!("inrs-paper/{name}.json"));
        let d = rs_io::json::domain_from_json_file(&path).unwrap();
        assert_eq!(d.loops().len(), 1, "{name}");
        check(name, &d, &[1.0]);
    }
}

#[test]
fn a_rational_spline_with_two_holes_matches_its_fine_polygon() {
    let outer = rs_testkit::periodic_spline(3, 12).domain.curves()[0].clone();
    let p = |x: f64, y: f64| Point::new(x, y);
    let triangle = polyline(&[p(0.25, -0.1), p(0.45, -0.1), p(0.3, 0.15), p(0.25, -0.1)]).unwrap();
    let d = Domain::new(vec![
        outer,
        circle(p(0.0, 0.0), 0.2).unwrap().reversed(),
        triangle,
    ])
    .unwrap();
    assert_eq!(d.loops().len(), 3);
    check("spline with two holes", &d, &[1.0, -1.0, -1.0]);
}
