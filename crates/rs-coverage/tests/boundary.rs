//! The embedded boundary of each cell (`CoverageOptions::boundary`) and the faces' centroids
//! against closed forms: a circle's arcs per cell from the angles where it crosses the grid
//! lines, a square on grid lines, and the divergence theorem per cell (the integral of the
//! outward normal over the boundary in a cell balances the covered faces).

use std::f64::consts::TAU;

use rs_coverage::{CellGrid, Coverage, CoverageOptions, GridCoverage};
use rs_spline::prelude::*;
use rs_spline::{Domain, NurbsCurve, Point, circle, polyline};

fn eb() -> CoverageOptions {
    CoverageOptions::DEFAULT
        .with_apertures(true)
        .with_boundary(true)
        .with_face_centroids(true)
}

/// Per cell `[length, int x ds, int y ds, int n_x ds, int n_y ds]` of the circle of radius
/// `r` about `(cx, cy)` (counter-clockwise, the disc on its left): the arcs between the
/// angles where it meets the grid lines, each in the cell of its midpoint.
fn circle_by_cells(grid: &CellGrid, (cx, cy, r): (f64, f64, f64)) -> Vec<[f64; 5]> {
    let (xs, ys) = (grid.x_edges(), grid.y_edges());
    let mut angles = vec![0.0, TAU];
    let norm = |a: f64| a.rem_euclid(TAU);
    for &x in xs {
        let c = (x - cx) / r;
        if c.abs() < 1.0 {
            angles.extend([norm(c.acos()), norm(-c.acos())]);
        }
    }
    for &y in ys {
        let s = (y - cy) / r;
        if s.abs() < 1.0 {
            angles.extend([norm(s.asin()), norm(std::f64::consts::PI - s.asin())]);
        }
    }
    angles.sort_by(f64::total_cmp);
    let mut out = vec![[0.0; 5]; grid.nx() * grid.ny()];
    for w in angles.windows(2) {
        let (a, b) = (w[0], w[1]);
        if b <= a {
            continue;
        }
        let m = 0.5 * (a + b);
        let (px, py) = (cx + r * m.cos(), cy + r * m.sin());
        let i = xs.partition_point(|&e| e < px);
        let j = ys.partition_point(|&e| e < py);
        if i == 0 || j == 0 || i > grid.nx() || j > grid.ny() {
            continue;
        }
        let o = &mut out[(j - 1) * grid.nx() + i - 1];
        o[0] += r * (b - a);
        o[1] += r * (cx * (b - a) + r * (b.sin() - a.sin()));
        o[2] += r * (cy * (b - a) - r * (b.cos() - a.cos()));
        o[3] += r * (b.sin() - a.sin());
        o[4] += r * (a.cos() - b.cos());
    }
    out
}

/// The divergence theorem per cell: the integral of the outward normal over the boundary in
/// the cell is minus the covered faces' outward lengths; the unit normal must point along it,
/// and where the faces balance the boundary has no normal.
fn assert_divergence(grid: &CellGrid, c: &Coverage) {
    assert_divergence_within(grid, c, 1e-12);
}

/// [`assert_divergence`] with the length at least `|int n ds|` to `tol` relative (the
/// rounding of a strongly weighted curve's speed is about its weight ratio times `eps`).
fn assert_divergence_within(grid: &CellGrid, c: &Coverage, tol: f64) {
    let (xs, ys, nx) = (grid.x_edges(), grid.y_edges(), grid.nx());
    let (ax, ay) = (
        c.x_apertures.as_ref().unwrap(),
        c.y_apertures.as_ref().unwrap(),
    );
    let (lengths, normals) = (
        c.boundary_lengths.as_ref().unwrap(),
        c.boundary_normals.as_ref().unwrap(),
    );
    for j in 0..grid.ny() {
        for i in 0..nx {
            let (w, h) = (xs[i + 1] - xs[i], ys[j + 1] - ys[j]);
            let flux = [
                (ax[j * (nx + 1) + i + 1] - ax[j * (nx + 1) + i]) * h,
                (ay[(j + 1) * nx + i] - ay[j * nx + i]) * w,
            ];
            let size = flux[0].hypot(flux[1]);
            let k = j * nx + i;
            let n = normals[k];
            if size > 1e-9 * (w + h) {
                assert!(
                    lengths[k] >= size * (1.0 - tol),
                    "cell ({i}, {j}): |int n ds| {size} > length {}",
                    lengths[k]
                );
                assert!(
                    (n[0] + flux[0] / size).abs() < 1e-12 && (n[1] + flux[1] / size).abs() < 1e-12,
                    "cell ({i}, {j}): normal {n:?} vs faces' flux {flux:?}"
                );
            } else if lengths[k] == 0.0 {
                assert!(
                    size == 0.0,
                    "cell ({i}, {j}): faces unbalanced, no boundary"
                );
                assert!(n[0].is_nan() && n[1].is_nan());
            }
        }
    }
}

#[test]
fn a_circles_arcs_per_cell_are_its_closed_forms() {
    for (grid, disc) in [
        (
            CellGrid::uniform(-1.3, 1.7, 19, -1.4, 1.6, 23).unwrap(),
            (0.2, 0.1, 1.1),
        ),
        (
            CellGrid::uniform(-1.0, 1.0, 8, -1.0, 1.0, 8).unwrap(),
            (0.0, 0.0, 1.0),
        ),
        (
            CellGrid::uniform(-3.0, 3.0, 61, -3.0, 3.0, 47).unwrap(),
            (0.3, -0.2, 2.5),
        ),
    ] {
        let d = Domain::new(vec![circle(Point::new(disc.0, disc.1), disc.2).unwrap()]).unwrap();
        let c = GridCoverage::new(&d, grid.clone())
            .unwrap()
            .all(eb())
            .unwrap();
        let want = circle_by_cells(&grid, disc);
        let (lengths, centroids, normals) = (
            c.boundary_lengths.as_ref().unwrap(),
            c.boundary_centroids.as_ref().unwrap(),
            c.boundary_normals.as_ref().unwrap(),
        );
        let scale = disc.2;
        for (k, w) in want.iter().enumerate() {
            let (i, j) = (k % grid.nx(), k / grid.nx());
            if w[0] < 1e-9 * scale {
                // A vertex grazed within rounding: nothing or next to nothing.
                assert!(lengths[k] < 1e-9 * scale, "cell ({i}, {j})");
                continue;
            }
            assert!(
                (lengths[k] - w[0]).abs() < 1e-13 * scale,
                "cell ({i}, {j}) length"
            );
            let [x, y] = centroids[k];
            assert!(
                (x - w[1] / w[0]).abs() < 1e-12 * scale,
                "cell ({i}, {j}) centroid x"
            );
            assert!(
                (y - w[2] / w[0]).abs() < 1e-12 * scale,
                "cell ({i}, {j}) centroid y"
            );
            let n = w[3].hypot(w[4]);
            let [nx, ny] = normals[k];
            assert!((nx - w[3] / n).abs() < 1e-11, "cell ({i}, {j}) normal x");
            assert!((ny - w[4] / n).abs() < 1e-11, "cell ({i}, {j}) normal y");
        }
        assert_divergence(&grid, &c);
    }
}

#[test]
fn a_square_on_grid_lines_gives_its_sides_to_the_cells_left_and_below() {
    // [0.25, 1] x [0.5, 1.5] on the grid of step 0.25 over [0, 2]^2.
    let pts = [
        (0.25, 0.5),
        (1.0, 0.5),
        (1.0, 1.5),
        (0.25, 1.5),
        (0.25, 0.5),
    ];
    let pts: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
    let d = Domain::new(vec![polyline(&pts).unwrap()]).unwrap();
    let grid = CellGrid::uniform(0.0, 2.0, 8, 0.0, 2.0, 8).unwrap();
    let c = GridCoverage::new(&d, grid.clone())
        .unwrap()
        .all(eb())
        .unwrap();
    let (lengths, centroids, normals) = (
        c.boundary_lengths.as_ref().unwrap(),
        c.boundary_centroids.as_ref().unwrap(),
        c.boundary_normals.as_ref().unwrap(),
    );
    let at = |i: usize, j: usize| j * 8 + i;
    let mut with_boundary = 0;
    for j in 0..8 {
        for i in 0..8 {
            let k = at(i, j);
            let (x0, y0) = (0.25 * i as f64, 0.25 * j as f64);
            // Left side x = 0.25: column 0, rows 2..6, normal (-1, 0); right side x = 1:
            // column 3 (left of the line), normal (1, 0); bottom y = 0.5: row 1, normal
            // (0, -1); top y = 1.5: row 5, normal (0, 1).
            let mut want: Vec<([f64; 2], [f64; 2])> = Vec::new();
            if i == 0 && (2..6).contains(&j) {
                want.push(([0.25, y0 + 0.125], [-1.0, 0.0]));
            }
            if i == 3 && (2..6).contains(&j) {
                want.push(([1.0, y0 + 0.125], [1.0, 0.0]));
            }
            if j == 1 && (1..4).contains(&i) {
                want.push(([x0 + 0.125, 0.5], [0.0, -1.0]));
            }
            if j == 5 && (1..4).contains(&i) {
                want.push(([x0 + 0.125, 1.5], [0.0, 1.0]));
            }
            match want.as_slice() {
                [] => {
                    assert_eq!(lengths[k], 0.0, "({i}, {j})");
                    assert!(centroids[k][0].is_nan() && normals[k][0].is_nan());
                }
                [(centroid, normal)] => {
                    with_boundary += 1;
                    assert_eq!(lengths[k], 0.25, "({i}, {j})");
                    assert_eq!(centroids[k], *centroid, "({i}, {j})");
                    assert_eq!(normals[k], *normal, "({i}, {j})");
                }
                [(c0, n0), (c1, n1)] => {
                    // The corner cells (3, 5)... hold two sides.
                    with_boundary += 1;
                    assert_eq!(lengths[k], 0.5, "({i}, {j})");
                    let mid = [0.5 * (c0[0] + c1[0]), 0.5 * (c0[1] + c1[1])];
                    assert!((centroids[k][0] - mid[0]).abs() < 1e-15);
                    assert!((centroids[k][1] - mid[1]).abs() < 1e-15);
                    let n = [n0[0] + n1[0], n0[1] + n1[1]];
                    let s = n[0].hypot(n[1]);
                    assert!((normals[k][0] - n[0] / s).abs() < 1e-15);
                    assert!((normals[k][1] - n[1] / s).abs() < 1e-15);
                }
                _ => unreachable!(),
            }
        }
    }
    assert_eq!(with_boundary, 4 + 4 + 3 + 3 - 1);
    assert_divergence(&grid, &c);
}

#[test]
fn face_centroids_are_the_covered_chords_midpoints() {
    let (cx, cy, r) = (0.1, -0.05, 0.9);
    let d = Domain::new(vec![circle(Point::new(cx, cy), r).unwrap()]).unwrap();
    let grid = CellGrid::uniform(-1.0, 1.0, 13, -1.0, 1.0, 11).unwrap();
    let c = GridCoverage::new(&d, grid.clone())
        .unwrap()
        .all(eb())
        .unwrap();
    let (xs, ys, nx) = (grid.x_edges(), grid.y_edges(), grid.nx());
    let (fx, fy) = (c.x_face_centroids.unwrap(), c.y_face_centroids.unwrap());
    // The chord of the line x = a is |y - cy| <= s; a face's covered part is its clip.
    let clip = |(lo, hi): (f64, f64), (a, b): (f64, f64)| (lo.max(a), hi.min(b));
    for j in 0..grid.ny() {
        for (i, &x) in xs.iter().enumerate() {
            let s2 = r * r - (x - cx) * (x - cx);
            let got = fx[j * (nx + 1) + i];
            let (lo, hi) = if s2 > 0.0 {
                clip((cy - s2.sqrt(), cy + s2.sqrt()), (ys[j], ys[j + 1]))
            } else {
                (0.0, 0.0)
            };
            if hi - lo > 1e-12 {
                assert!((got - 0.5 * (lo + hi)).abs() < 1e-13, "x face ({i}, {j})");
            } else if hi <= lo {
                assert!(got.is_nan(), "x face ({i}, {j}): {got}");
            }
        }
    }
    for (j, &y) in ys.iter().enumerate() {
        for i in 0..nx {
            let s2 = r * r - (y - cy) * (y - cy);
            let got = fy[j * nx + i];
            let (lo, hi) = if s2 > 0.0 {
                clip((cx - s2.sqrt(), cx + s2.sqrt()), (xs[i], xs[i + 1]))
            } else {
                (0.0, 0.0)
            };
            if hi - lo > 1e-12 {
                assert!((got - 0.5 * (lo + hi)).abs() < 1e-13, "y face ({i}, {j})");
            } else if hi <= lo {
                assert!(got.is_nan(), "y face ({i}, {j}): {got}");
            }
        }
    }
}

#[test]
fn strongly_weighted_pieces_get_their_lengths_in_bounded_work() {
    // Weights up to 1e8 (the speed's rounding grows with the weight ratio) and a degree-15
    // piece with weights 1e3 and 1e-3: every cell's length adds up to the curves' length.
    let quadratic = |w: f64| {
        let pts = vec![
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
        ];
        NurbsCurve::bezier(pts, Some(vec![1.0, w, 1.0])).unwrap()
    };
    let wavy = {
        let pts: Vec<Point> = (0..=15)
            .map(|k| Point::new(k as f64 / 15.0, if k % 2 == 0 { 0.0 } else { 0.3 }))
            .collect();
        let w: Vec<f64> = (0..=15)
            .map(|k| if k % 3 == 0 { 1e3 } else { 1e-3 })
            .collect();
        NurbsCurve::bezier(pts, Some(w)).unwrap()
    };
    // The loops' lengths (the curve closed by a segment) by 40-digit quadrature (mpmath,
    // the speed by central differences of step 1e-25, the parameters split down to 1e-14 at
    // both ends where strong weights put the length).
    for (name, curve, ratio, want) in [
        ("weight 1e4", quadratic(1e4), 1e4, 3.414_128_851_063_517),
        ("weight 1e8", quadratic(1e8), 1e8, 3.414_213_553_900_964),
        (
            "degree 15",
            wavy,
            1e6,
            1.310_449_648_953_833 + 0.8 + 1.0 + 0.5,
        ),
    ] {
        let (t0, t1) = curve.knots().domain();
        let (a, b) = (curve.point_at(t1), curve.point_at(t0));
        // The quadratics close by their chord; the wavy curve from below (its chord crosses it).
        let closing = if a.y > 0.5 {
            vec![a, b]
        } else {
            vec![a, Point::new(1.0, -0.5), Point::new(0.0, -0.5), b]
        };
        let d = Domain::new(vec![curve, polyline(&closing).unwrap()]).unwrap();
        let bb = d.bounding_box();
        let grid = CellGrid::uniform(
            bb.min.x - 0.05,
            bb.max.x + 0.05,
            13,
            bb.min.y - 0.05,
            bb.max.y + 0.05,
            11,
        )
        .unwrap();
        let c = GridCoverage::new(&d, grid.clone())
            .unwrap()
            .all(eb())
            .unwrap();
        let total: f64 = c.boundary_lengths.as_ref().unwrap().iter().sum();
        let tol = 16.0 * f64::EPSILON * ratio;
        assert!(
            (total - want).abs() < tol * want,
            "{name}: {total} vs {want}"
        );
        assert_divergence_within(&grid, &c, tol);
    }
}

#[test]
fn the_fixtures_balance_their_faces_in_every_cell() {
    let mut checked = 0;
    for name in rs_testkit::INRS_FIXTURES {
        let path = rs_testkit::fixture_path(&format!("inrs-paper/{name}.json"));
        let d = rs_io::load_domain(path.to_str().unwrap()).unwrap();
        let b = d.bounding_box();
        let grid = CellGrid::uniform(
            b.min.x - 0.1,
            b.max.x + 0.1,
            37,
            b.min.y - 0.1,
            b.max.y + 0.1,
            41,
        )
        .unwrap();
        let Ok(cover) = GridCoverage::new(&d, grid.clone()) else {
            continue;
        };
        assert_divergence(&grid, &cover.all(eb()).unwrap());
        checked += 1;
    }
    assert!(checked >= 4, "only {checked} closed fixtures");
}
