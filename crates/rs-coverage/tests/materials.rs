//! Materials with replacement against independent truths: closed-form areas, per-cell
//! fractions of domains built by hand (lenses from circular arcs, polygons), and a dense
//! polygon clipped cell by cell.

use rs_contain::FillRule;
use rs_coverage::{CellGrid, CoverageOptions, cell_coverage, material_domains};
use rs_spline::{Domain, NurbsCurve, Point, circle, circular_arc, polyline};
use std::f64::consts::PI;

const EO: FillRule = FillRule::EvenOdd;

fn disc(x: f64, y: f64, r: f64) -> Domain {
    Domain::new(vec![circle(Point::new(x, y), r).unwrap()]).unwrap()
}

fn poly(points: &[(f64, f64)]) -> Domain {
    let mut p: Vec<Point> = points.iter().map(|&(x, y)| Point::new(x, y)).collect();
    p.push(p[0]);
    Domain::new(vec![polyline(&p).unwrap()]).unwrap()
}

/// Per-cell fractions of a domain, zeros for an empty region.
fn fractions(d: Option<&Domain>, grid: &CellGrid) -> Vec<f64> {
    match d {
        Some(d) => {
            cell_coverage(d, grid, CoverageOptions::DEFAULT)
                .unwrap()
                .fractions
        }
        None => vec![0.0; grid.nx() * grid.ny()],
    }
}

/// The area covered: fractions times cell areas.
fn area(f: &[f64], grid: &CellGrid) -> f64 {
    let mut total = 0.0;
    for j in 0..grid.ny() {
        for i in 0..grid.nx() {
            total += f[j * grid.nx() + i] * grid.cell_area(i, j);
        }
    }
    total
}

/// Regions of `domains` with replacement (all even-odd).
fn regions(domains: &[&Domain]) -> Vec<Option<Domain>> {
    let input: Vec<(&Domain, FillRule)> = domains.iter().map(|&d| (d, EO)).collect();
    material_domains(&input, true).unwrap()
}

/// Per cell `a == b - c` (fractions) within `tol`.
fn assert_difference(a: &[f64], b: &[f64], c: &[f64], tol: f64) {
    for (i, ((a, b), c)) in a.iter().zip(b).zip(c).enumerate() {
        assert!((a - (b - c)).abs() <= tol, "cell {i}: {a} vs {b} - {c}");
    }
}

/// Per cell `a == b` within `tol`.
fn assert_close(a: &[f64], b: &[f64], tol: f64) {
    assert_difference(a, b, &vec![0.0; a.len()], tol);
}

/// Per cell the materials' fractions add up to at most 1.
fn assert_partition(all: &[Vec<f64>]) {
    for i in 0..all[0].len() {
        let s: f64 = all.iter().map(|f| f[i]).sum();
        assert!((-1e-15..=1.0 + 1e-12).contains(&s), "cell {i}: {s}");
    }
}

/// The lens `D(-c, r) n D(c, r)` built from its two arcs (no intersection routine).
fn lens(c: f64, r: f64) -> Domain {
    let alpha = (c / r).acos();
    Domain::new(vec![
        circular_arc(Point::new(-c, 0.0), r, -alpha, 2.0 * alpha).unwrap(),
        circular_arc(Point::new(c, 0.0), r, PI - alpha, 2.0 * alpha).unwrap(),
    ])
    .unwrap()
}

/// The lens area of two radius-`r` discs whose centres are `d` apart.
fn lens_area(d: f64, r: f64) -> f64 {
    2.0 * r * r * (d / (2.0 * r)).acos() - 0.5 * d * (4.0 * r * r - d * d).sqrt()
}

#[test]
fn two_overlapping_discs() {
    let (a, b) = (disc(-0.5, 0.0, 1.0), disc(0.5, 0.0, 1.0));
    let r = regions(&[&a, &b]);
    let grid = CellGrid::uniform(-1.7, 1.9, 37, -1.3, 1.4, 29).unwrap();
    let f0 = fractions(r[0].as_ref(), &grid);
    let f1 = fractions(r[1].as_ref(), &grid);
    let lens_a = lens_area(1.0, 1.0);
    assert!((lens_a - (2.0 * PI / 3.0 - 0.75f64.sqrt())).abs() < 1e-15);
    let got = area(&f0, &grid);
    assert!(
        ((got - (PI - lens_a)) / (PI - lens_a)).abs() < 1e-12,
        "{got}"
    );
    // The union: R_0 and D_1 side by side.
    let union = got + area(&f1, &grid);
    assert!(((union - (2.0 * PI - lens_a)) / union).abs() < 1e-12);
    // Per cell: R_0 = D_0 minus the lens, R_1 = D_1.
    let fa = fractions(Some(&a), &grid);
    let fl = fractions(Some(&lens(0.5, 1.0)), &grid);
    assert_difference(&f0, &fa, &fl, 1e-12);
    assert_close(&f1, &fractions(Some(&b), &grid), 1e-13);
    assert_partition(&[f0, f1]);
    // The other order: D_1 minus the lens.
    let r = regions(&[&b, &a]);
    let g0 = fractions(r[0].as_ref(), &grid);
    assert_difference(&g0, &fractions(Some(&b), &grid), &fl, 1e-12);
}

#[test]
fn a_disc_over_an_annulus() {
    let ring = Domain::new(vec![
        circle(Point::new(0.0, 0.0), 2.0).unwrap(),
        circle(Point::new(0.0, 0.0), 1.0).unwrap(),
    ])
    .unwrap();
    let grid = CellGrid::uniform(-2.1, 2.1, 21, -2.1, 2.1, 21).unwrap();
    // Concentric: the ring keeps 1.5 .. 2.
    let d = disc(0.0, 0.0, 1.5);
    let r = regions(&[&ring, &d]);
    let f0 = fractions(r[0].as_ref(), &grid);
    assert!((area(&f0, &grid) / (1.75 * PI) - 1.0).abs() < 1e-12);
    let outer = Domain::new(vec![
        circle(Point::new(0.0, 0.0), 2.0).unwrap(),
        circle(Point::new(0.0, 0.0), 1.5).unwrap(),
    ])
    .unwrap();
    let want = fractions(Some(&outer), &grid);
    assert_difference(&f0, &want, &vec![0.0; want.len()], 1e-12);
    // A disc in the ring touching both of its circles (two internal tangencies).
    let d = disc(1.5, 0.0, 0.5);
    let r = regions(&[&ring, &d]);
    let f0 = fractions(r[0].as_ref(), &grid);
    assert!((area(&f0, &grid) / (2.75 * PI) - 1.0).abs() < 1e-12);
    assert_difference(
        &f0,
        &fractions(Some(&ring), &grid),
        &fractions(Some(&d), &grid),
        1e-12,
    );
    // The ring over the disc: the disc keeps the hole's part, the ring is all there.
    let d = disc(0.0, 0.0, 1.5);
    let r = regions(&[&d, &ring]);
    let f0 = fractions(r[0].as_ref(), &grid);
    assert!((area(&f0, &grid) / PI - 1.0).abs() < 1e-12);
}

#[test]
fn tangent_discs() {
    let grid = CellGrid::uniform(-2.3, 2.3, 23, -2.1, 2.1, 21).unwrap();
    // Touching outside: nothing is taken.
    let (a, b) = (disc(-1.0, 0.0, 1.0), disc(1.0, 0.0, 1.0));
    let r = regions(&[&a, &b]);
    let f0 = fractions(r[0].as_ref(), &grid);
    assert_difference(
        &f0,
        &fractions(Some(&a), &grid),
        &vec![0.0; f0.len()],
        1e-12,
    );
    // Touching inside: the small disc is cut out of the big one, or replaced entirely.
    let (big, small) = (disc(0.0, 0.0, 2.0), disc(1.0, 0.0, 1.0));
    let r = regions(&[&big, &small]);
    let f0 = fractions(r[0].as_ref(), &grid);
    assert!((area(&f0, &grid) / (3.0 * PI) - 1.0).abs() < 1e-12);
    assert_difference(
        &f0,
        &fractions(Some(&big), &grid),
        &fractions(Some(&small), &grid),
        1e-12,
    );
    let r = regions(&[&small, &big]);
    assert!(r[0].is_none());
}

#[test]
fn nearly_tangent_discs() {
    let grid = CellGrid::uniform(-2.2, 2.2, 22, -1.1, 1.1, 11).unwrap();
    for depth in [1e-6, 1e-9] {
        let c = 1.0 - 0.5 * depth;
        let (a, b) = (disc(-c, 0.0, 1.0), disc(c, 0.0, 1.0));
        let r = regions(&[&a, &b]);
        let f0 = fractions(r[0].as_ref(), &grid);
        let want = PI - lens_area(2.0 * c, 1.0);
        assert!((area(&f0, &grid) / want - 1.0).abs() < 1e-12, "{depth}");
        assert_difference(
            &f0,
            &fractions(Some(&a), &grid),
            &fractions(Some(&lens(c, 1.0)), &grid),
            1e-12,
        );
        assert_partition(&[f0, fractions(r[1].as_ref(), &grid)]);
    }
}

#[test]
fn squares_sharing_an_edge_and_overlapping() {
    let grid = CellGrid::uniform(-0.25, 2.25, 10, -0.25, 1.75, 8).unwrap();
    let a = poly(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]);
    let b = poly(&[(1.0, 0.0), (2.0, 0.0), (2.0, 1.0), (1.0, 1.0)]);
    let r = regions(&[&a, &b]);
    assert_difference(
        &fractions(r[0].as_ref(), &grid),
        &fractions(Some(&a), &grid),
        &vec![0.0; 80],
        1e-13,
    );
    // A square sharing half an edge's length, reversed.
    let c = poly(&[(1.0, 0.5), (1.0, 1.5), (2.0, 1.5), (2.0, 0.5)]);
    let r = regions(&[&a, &c]);
    assert_difference(
        &fractions(r[0].as_ref(), &grid),
        &fractions(Some(&a), &grid),
        &vec![0.0; 80],
        1e-13,
    );
    // Overlapping: an L shape is left.
    let d = poly(&[(0.5, 0.5), (1.5, 0.5), (1.5, 1.5), (0.5, 1.5)]);
    let r = regions(&[&a, &d]);
    let l = poly(&[
        (0.0, 0.0),
        (1.0, 0.0),
        (1.0, 0.5),
        (0.5, 0.5),
        (0.5, 1.0),
        (0.0, 1.0),
    ]);
    assert_difference(
        &fractions(r[0].as_ref(), &grid),
        &fractions(Some(&l), &grid),
        &vec![0.0; 80],
        1e-13,
    );
}

#[test]
fn an_identical_copy_replaces_the_earlier() {
    let grid = CellGrid::uniform(-1.2, 1.2, 12, -1.2, 1.2, 12).unwrap();
    let a = disc(0.0, 0.0, 1.0);
    let r = regions(&[&a, &a.clone()]);
    let f0 = fractions(r[0].as_ref(), &grid);
    assert!(area(&f0, &grid).abs() < 1e-14);
    assert_close(
        &fractions(r[1].as_ref(), &grid),
        &fractions(Some(&a), &grid),
        1e-13,
    );
    // The copy of a square beside another square.
    let s = poly(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]);
    let t = poly(&[(1.0, 0.0), (1.5, 0.0), (1.5, 1.0), (1.0, 1.0)]);
    let r = regions(&[&s, &t, &s.clone()]);
    assert!(r[0].is_none());
    assert!(r[1].is_some() && r[2].is_some());
}

#[test]
fn without_replacement_every_domain_is_itself() {
    let (a, b) = (disc(-0.5, 0.0, 1.0), disc(0.5, 0.0, 1.0));
    let r = material_domains(&[(&a, EO), (&b, EO)], false).unwrap();
    assert_eq!(r[0].as_ref().unwrap().curves(), a.curves());
    assert_eq!(r[1].as_ref().unwrap().curves(), b.curves());
}

#[test]
fn three_materials_partition_the_cells() {
    let grid = CellGrid::uniform(-1.6, 1.6, 16, -1.6, 1.6, 16).unwrap();
    let (a, b, c) = (
        disc(-0.4, -0.2, 1.0),
        disc(0.4, -0.2, 1.0),
        disc(0.0, 0.5, 0.8),
    );
    let r = regions(&[&a, &b, &c]);
    let f: Vec<Vec<f64>> = r.iter().map(|d| fractions(d.as_ref(), &grid)).collect();
    assert_partition(&f);
    assert_close(&f[2], &fractions(Some(&c), &grid), 1e-13);
    // The last two are the union of b and c, whatever a does.
    let r12 = regions(&[&b, &c]);
    let f1 = fractions(r12[0].as_ref(), &grid);
    for i in 0..f1.len() {
        assert!((f[1][i] - f1[i]).abs() < 1e-12);
    }
}

/// A closed cubic B-spline (a blob, not a conic).
fn blob() -> Domain {
    let p = Point::new;
    let pts = vec![
        p(1.0, 0.0),
        p(1.2, 0.8),
        p(0.2, 1.1),
        p(-0.9, 0.9),
        p(-1.1, -0.2),
        p(-0.6, -1.0),
        p(0.5, -0.9),
        p(1.0, 0.0),
    ];
    let n = pts.len();
    let mut knots = vec![0.0; 4];
    knots.extend((1..n - 3).map(|i| i as f64 / (n - 3) as f64));
    knots.extend([1.0; 4]);
    Domain::new(vec![NurbsCurve::new(3, knots, pts, None).unwrap()]).unwrap()
}

/// Area of `subject` (a closed ring) clipped by the convex counter-clockwise polygon `clip`
/// (Sutherland-Hodgman; exact in area for any simple subject).
fn clipped_area(subject: &[Point], clip: &[Point]) -> f64 {
    if clip.len() < 3 {
        return 0.0;
    }
    let mut ring = subject.to_vec();
    for k in 0..clip.len() {
        let (a, b) = (clip[k], clip[(k + 1) % clip.len()]);
        let side = |p: Point| (b - a).cross(p - a);
        let mut out = Vec::with_capacity(ring.len());
        for i in 0..ring.len() {
            let (p, q) = (ring[i], ring[(i + 1) % ring.len()]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                out.push(p + (q - p) * (sp / (sp - sq)));
            }
        }
        ring = out;
        if ring.is_empty() {
            return 0.0;
        }
    }
    let n = ring.len();
    (0..n)
        .map(|i| ring[i].cross(ring[(i + 1) % n]))
        .sum::<f64>()
        / 2.0
}

/// `R = a n b` of two convex counter-clockwise polygons (Sutherland-Hodgman).
fn convex_and(a: &[Point], b: &[Point]) -> Vec<Point> {
    let mut ring = a.to_vec();
    for k in 0..b.len() {
        let (p0, p1) = (b[k], b[(k + 1) % b.len()]);
        let side = |p: Point| (p1 - p0).cross(p - p0);
        let mut out = Vec::new();
        for i in 0..ring.len() {
            let (p, q) = (ring[i], ring[(i + 1) % ring.len()]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                out.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                out.push(p + (q - p) * (sp / (sp - sq)));
            }
        }
        ring = out;
    }
    ring
}

#[test]
fn a_triangle_over_a_spline_blob_against_a_dense_polygon() {
    let shape = blob();
    let tri = [(-0.3, -1.5), (1.6, 0.3), (-0.2, 0.6)];
    let t = poly(&tri);
    let r = regions(&[&shape, &t]);
    let grid = CellGrid::uniform(-1.3, 1.5, 7, -1.2, 1.3, 5).unwrap();
    let f0 = fractions(r[0].as_ref(), &grid);
    assert_close(
        &fractions(r[1].as_ref(), &grid),
        &fractions(Some(&t), &grid),
        1e-13,
    );
    // The blob flattened to 1e-11 (counter-clockwise), clipped cell by cell.
    let mut ring = Vec::new();
    shape.flatten_loop(0, 1e-11, &mut |p| ring.push(p));
    ring.pop();
    let tri: Vec<Point> = tri.iter().map(|&(x, y)| Point::new(x, y)).collect();
    let (xe, ye) = (grid.x_edges(), grid.y_edges());
    for j in 0..grid.ny() {
        for i in 0..grid.nx() {
            let cell = [
                Point::new(xe[i], ye[j]),
                Point::new(xe[i + 1], ye[j]),
                Point::new(xe[i + 1], ye[j + 1]),
                Point::new(xe[i], ye[j + 1]),
            ];
            let whole = clipped_area(&ring, &cell);
            let under = clipped_area(&ring, &convex_and(&cell, &tri));
            let want = (whole - under) / grid.cell_area(i, j);
            let got = f0[j * grid.nx() + i];
            assert!(
                (got - want).abs() < 1e-9,
                "cell ({i}, {j}): {got} vs {want}"
            );
        }
    }
}
