//! Polygons against exact polygon clipping: squares, diamonds and concave shapes aligned with
//! the grid lines and across them, edges on grid lines, vertices on grid vertices, holes in
//! either orientation. The references (Sutherland-Hodgman clipping to each cell, the exact
//! crossings of each face line) are written here, independent of the library.

use rs_coverage::{CellGrid, CoverageOptions, cell_coverage};
use rs_spline::{Domain, NurbsCurve, Point, polyline};

/// A polygon loop and its even-odd depth (0 outer, 1 hole).
type Loop = (Vec<[f64; 2]>, usize);

/// Clips the closed polygon `poly` (no repeated last vertex) to the half-plane
/// `coord(axis) * side >= bound * side`.
fn clip(poly: &[[f64; 2]], axis: usize, bound: f64, side: f64) -> Vec<[f64; 2]> {
    let inside = |p: &[f64; 2]| (p[axis] - bound) * side >= 0.0;
    let mut out = Vec::new();
    for k in 0..poly.len() {
        let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
        let (pin, qin) = (inside(&p), inside(&q));
        if pin {
            out.push(p);
        }
        if pin != qin {
            let t = (bound - p[axis]) / (q[axis] - p[axis]);
            let mut r = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
            r[axis] = bound;
            out.push(r);
        }
    }
    out
}

/// `(area, first moment x, first moment y)` of `poly` clipped to the cell, signed by the
/// polygon's orientation, with the moments about the cell's corner `(a, c)`.
fn clipped_moments(poly: &[[f64; 2]], [a, b, c, d]: [f64; 4]) -> (f64, f64, f64) {
    let mut p = clip(poly, 0, a, 1.0);
    p = clip(&p, 0, b, -1.0);
    p = clip(&p, 1, c, 1.0);
    p = clip(&p, 1, d, -1.0);
    let local: Vec<[f64; 2]> = p.iter().map(|v| [v[0] - a, v[1] - c]).collect();
    let (mut area, mut mx, mut my) = (0.0, 0.0, 0.0);
    for k in 0..local.len() {
        let (p, q) = (local[k], local[(k + 1) % local.len()]);
        let cross = p[0] * q[1] - q[0] * p[1];
        area += 0.5 * cross;
        mx += (p[0] + q[0]) * cross / 6.0;
        my += (p[1] + q[1]) * cross / 6.0;
    }
    (area, mx, my)
}

fn signed_area(poly: &[[f64; 2]]) -> f64 {
    (0..poly.len())
        .map(|k| {
            let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
            0.5 * (p[0] * q[1] - q[0] * p[1])
        })
        .sum()
}

/// The covered area and moments (about the corner) of the cell: each loop's clipped part
/// with the sign `(-1)^depth`, whatever the loop's orientation.
fn cell_truth(loops: &[Loop], cell: [f64; 4]) -> (f64, f64, f64) {
    let mut total = (0.0, 0.0, 0.0);
    for (poly, depth) in loops {
        let s = signed_area(poly).signum() * if depth % 2 == 0 { 1.0 } else { -1.0 };
        let (a, mx, my) = clipped_moments(poly, cell);
        total = (total.0 + s * a, total.1 + s * mx, total.2 + s * my);
    }
    total
}

/// The covered length of `[lo, hi]` on the line `coord(axis) = v` (generic: no vertex on
/// it), by even-odd parity of its crossings with every loop's edges.
fn covered_on_line(loops: &[Loop], axis: usize, v: f64, lo: f64, hi: f64) -> f64 {
    let other = 1 - axis;
    let mut ts = Vec::new();
    for (poly, _) in loops {
        for k in 0..poly.len() {
            let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
            if (p[axis] <= v) != (q[axis] <= v) {
                let t = (v - p[axis]) / (q[axis] - p[axis]);
                ts.push(p[other] + t * (q[other] - p[other]));
            }
        }
    }
    ts.sort_by(f64::total_cmp);
    ts.chunks(2)
        .map(|c| (c[1].min(hi) - c[0].max(lo)).max(0.0))
        .sum()
}

/// The covered length of `[lo, hi]` on the line `coord(axis) = v + 0` (just past `v`): the
/// length is linear in the line's position between the breakpoints (vertices, and edges
/// crossing `lo` or `hi`), so two generic lines just past `v` extrapolate to the limit.
fn covered_just_past(loops: &[Loop], axis: usize, v: f64, lo: f64, hi: f64, step: f64) -> f64 {
    let other = 1 - axis;
    let mut next = v + step;
    for (poly, _) in loops {
        for k in 0..poly.len() {
            let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
            for b in [lo, hi] {
                if (p[other] <= b) != (q[other] <= b) {
                    let t = (b - p[other]) / (q[other] - p[other]);
                    let at = p[axis] + t * (q[axis] - p[axis]);
                    if at > v {
                        next = next.min(at);
                    }
                }
            }
            if p[axis] > v {
                next = next.min(p[axis]);
            }
        }
    }
    let delta = (next - v) / 4.0;
    let l1 = covered_on_line(loops, axis, v + delta, lo, hi);
    let l2 = covered_on_line(loops, axis, v + 2.0 * delta, lo, hi);
    2.0 * l1 - l2
}

fn domain(loops: &[Loop]) -> Domain {
    let curves: Vec<NurbsCurve> = loops
        .iter()
        .map(|(poly, _)| {
            let mut pts: Vec<Point> = poly.iter().map(|p| Point::new(p[0], p[1])).collect();
            pts.push(pts[0]);
            polyline(&pts).unwrap()
        })
        .collect();
    Domain::new(curves).unwrap()
}

/// Every cell's fraction and centroid, and every face's aperture, against the references.
fn check(name: &str, loops: &[Loop], grid: &CellGrid) {
    let d = domain(loops);
    let options = CoverageOptions::DEFAULT
        .with_centroids(true)
        .with_apertures(true);
    let c = cell_coverage(&d, grid, options).unwrap();
    let (xs, ys) = (grid.x_edges(), grid.y_edges());
    let (nx, ny) = (grid.nx(), grid.ny());
    let cent = c.centroids.as_ref().unwrap();
    for j in 0..ny {
        for i in 0..nx {
            let cell = [xs[i], xs[i + 1], ys[j], ys[j + 1]];
            let (w, h) = (xs[i + 1] - xs[i], ys[j + 1] - ys[j]);
            let (area, mx, my) = cell_truth(loops, cell);
            let k = j * nx + i;
            let f = c.fractions[k];
            assert!(
                (f - area / (w * h)).abs() <= 1e-13,
                "{name}: cell ({i}, {j}): {f} vs {}",
                area / (w * h)
            );
            if area > 1e-9 * w * h {
                let [x, y] = cent[k];
                let (ex, ey) = (xs[i] + mx / area, ys[j] + my / area);
                assert!(
                    (x - ex).abs() <= 1e-12 * w && (y - ey).abs() <= 1e-12 * h,
                    "{name}: centroid of ({i}, {j}): ({x}, {y}) vs ({ex}, {ey})"
                );
            }
        }
    }
    let xa = c.x_apertures.as_ref().unwrap();
    let ya = c.y_apertures.as_ref().unwrap();
    for j in 0..ny {
        let h = ys[j + 1] - ys[j];
        for (i, &x) in xs.iter().enumerate() {
            let expected = covered_just_past(loops, 0, x, ys[j], ys[j + 1], h) / h;
            let got = xa[j * (nx + 1) + i];
            assert!(
                (got - expected).abs() <= 1e-13,
                "{name}: face x = {x}, row {j}: {got} vs {expected}"
            );
        }
    }
    for (j, &y) in ys.iter().enumerate() {
        for i in 0..nx {
            let w = xs[i + 1] - xs[i];
            let expected = covered_just_past(loops, 1, y, xs[i], xs[i + 1], w) / w;
            let got = ya[j * nx + i];
            assert!(
                (got - expected).abs() <= 1e-13,
                "{name}: face y = {y}, column {i}: {got} vs {expected}"
            );
        }
    }
    // The total is the polygon's area.
    let total: f64 = (0..ny)
        .flat_map(|j| (0..nx).map(move |i| (i, j)))
        .map(|(i, j)| c.fractions[j * nx + i] * grid.cell_area(i, j))
        .sum();
    let expected: f64 = loops
        .iter()
        .map(|(p, depth)| signed_area(p).abs() * if depth % 2 == 0 { 1.0 } else { -1.0 })
        .sum();
    let covered_box = grid.bounding_box();
    let inside_grid = loops.iter().all(|(p, _)| {
        p.iter().all(|v| {
            v[0] >= covered_box.min.x
                && v[0] <= covered_box.max.x
                && v[1] >= covered_box.min.y
                && v[1] <= covered_box.max.y
        })
    });
    if inside_grid {
        assert!(
            (total - expected).abs() <= 1e-13 * expected,
            "{name}: {total} vs {expected}"
        );
    }
}

fn unit_grid(n: usize) -> CellGrid {
    CellGrid::uniform(0.0, 1.0, n, 0.0, 1.0, n).unwrap()
}

#[test]
fn squares_aligned_with_the_grid_and_across_it() {
    let square = |x0: f64, y0: f64, x1: f64, y1: f64| vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
    // Edges on grid lines, corners on grid vertices.
    check(
        "aligned",
        &[(square(0.25, 0.25, 0.75, 0.75), 0)],
        &unit_grid(4),
    );
    // The same square clockwise.
    let mut cw = square(0.25, 0.25, 0.75, 0.75);
    cw.reverse();
    check("aligned cw", &[(cw, 0)], &unit_grid(8));
    // Across the lines, and on the grid's outer lines.
    check(
        "across",
        &[(square(0.1, 0.3, 0.83, 0.61), 0)],
        &unit_grid(7),
    );
    check(
        "grid box",
        &[(square(0.0, 0.0, 1.0, 1.0), 0)],
        &unit_grid(5),
    );
    // Larger than the grid: every cell full, the faces on the grid's border covered.
    check(
        "beyond",
        &[(square(-1.0, -1.0, 2.0, 2.0), 0)],
        &unit_grid(3),
    );
    // Non-uniform edges.
    let grid = CellGrid::new(
        vec![0.0, 0.1, 0.25, 0.3, 0.7, 1.0],
        vec![0.0, 0.25, 0.5, 0.9, 1.0],
    )
    .unwrap();
    check("non-uniform", &[(square(0.1, 0.25, 0.7, 0.9), 0)], &grid);
    check(
        "non-uniform across",
        &[(square(0.05, 0.2, 0.65, 0.95), 0)],
        &grid,
    );
}

#[test]
fn diamonds_through_grid_vertices() {
    let diamond = vec![[0.5, 0.0], [1.0, 0.5], [0.5, 1.0], [0.0, 0.5]];
    check("diamond", &[(diamond.clone(), 0)], &unit_grid(4));
    check("diamond 6", &[(diamond, 0)], &unit_grid(6));
    // A triangle with its hypotenuse through many grid vertices.
    let tri = vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    check("triangle", &[(tri, 0)], &unit_grid(8));
}

#[test]
fn concave_polygons_with_holes() {
    // A comb: vertical and horizontal edges on grid lines, teeth across them.
    let comb = vec![
        [0.0, 0.0],
        [1.0, 0.0],
        [1.0, 0.9],
        [0.8, 0.9],
        [0.8, 0.3],
        [0.6, 0.3],
        [0.6, 0.75],
        [0.375, 0.75],
        [0.375, 0.25],
        [0.125, 0.5],
        [0.0, 0.5],
    ];
    check("comb", &[(comb.clone(), 0)], &unit_grid(8));
    check("comb 5", &[(comb, 0)], &unit_grid(5));
    // A square with a square hole, the hole in either orientation (even-odd fill).
    let outer = vec![[0.1, 0.1], [0.9, 0.1], [0.9, 0.9], [0.1, 0.9]];
    let hole = vec![[0.25, 0.25], [0.25, 0.625], [0.625, 0.625], [0.625, 0.25]];
    let mut hole_ccw = hole.clone();
    hole_ccw.reverse();
    check("hole cw", &[(outer.clone(), 0), (hole, 1)], &unit_grid(8));
    check(
        "hole ccw",
        &[(outer.clone(), 0), (hole_ccw, 1)],
        &unit_grid(8),
    );
    // A star across lines, with an island in a hole.
    let star: Vec<[f64; 2]> = (0..10)
        .map(|k| {
            let r = if k % 2 == 0 { 0.45 } else { 0.2 };
            let a = std::f64::consts::PI * k as f64 / 5.0 + 0.1;
            [0.5 + r * a.cos(), 0.5 + r * a.sin()]
        })
        .collect();
    let hole = vec![[0.43, 0.43], [0.43, 0.57], [0.57, 0.57], [0.57, 0.43]];
    let island = vec![[0.47, 0.47], [0.53, 0.47], [0.53, 0.53], [0.47, 0.53]];
    let loops = [(star, 0), (hole, 1), (island, 2)];
    check("star", &loops, &unit_grid(9));
    check(
        "star 32",
        &loops,
        &CellGrid::uniform(0.02, 0.97, 32, 0.05, 0.99, 29).unwrap(),
    );
}

#[test]
fn squares_touching_at_a_grid_vertex() {
    let a = vec![[0.25, 0.25], [0.5, 0.25], [0.5, 0.5], [0.25, 0.5]];
    let b = vec![[0.5, 0.5], [0.75, 0.5], [0.75, 0.75], [0.5, 0.75]];
    check("touching", &[(a, 0), (b, 0)], &unit_grid(4));
}

/// Random star-shaped polygons with vertices on the lattice of sixteenths, on grids of
/// eighths and of other steps: edges along grid lines, vertices on grid vertices and on
/// lines, collinear edges, everywhere.
#[test]
fn random_lattice_stars() {
    let mut rng = rs_testkit::XorShift64::new(0x5eed_c0fe);
    let grids = [
        unit_grid(8),
        unit_grid(4),
        CellGrid::uniform(0.0, 1.0, 5, 0.0, 1.0, 7).unwrap(),
        CellGrid::uniform(-0.25, 1.25, 12, 0.0, 1.0, 16).unwrap(),
    ];
    let mut checked = 0;
    for case in 0..160 {
        let n = 3 + rng.below(9) as usize;
        let mut pts: Vec<([f64; 2], f64)> = (0..n)
            .map(|_| {
                let a = rng.uniform(0.0, std::f64::consts::TAU);
                let r = rng.uniform(0.05, 0.5);
                let snap = |v: f64| (v * 16.0).round() / 16.0;
                let p = [snap(0.5 + r * a.cos()), snap(0.5 + r * a.sin())];
                (p, (p[1] - 0.5).atan2(p[0] - 0.5))
            })
            .filter(|(p, _)| *p != [0.5, 0.5])
            .collect();
        // Sorted by angle about the centre, one vertex per angle: a simple polygon when the
        // centre is inside it (every gap between angles below pi).
        pts.sort_by(|a, b| a.1.total_cmp(&b.1));
        pts.dedup_by(|a, b| a.1 == b.1);
        if pts.len() < 3 {
            continue;
        }
        let gaps = pts
            .windows(2)
            .map(|w| w[1].1 - w[0].1)
            .chain(std::iter::once(
                pts[0].1 + std::f64::consts::TAU - pts[pts.len() - 1].1,
            ));
        if gaps.into_iter().any(|g| g >= std::f64::consts::PI - 1e-9) {
            continue;
        }
        let poly: Vec<[f64; 2]> = pts.iter().map(|p| p.0).collect();
        let grid = &grids[case % grids.len()];
        check(&format!("star {case} {poly:?}"), &[(poly, 0)], grid);
        checked += 1;
    }
    assert!(checked >= 100, "only {checked} stars");
}
