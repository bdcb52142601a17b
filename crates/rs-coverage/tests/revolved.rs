//! Revolved cells (`CoverageOptions::axisymmetric`) against independent truth: per-cell
//! volumes of a torus by a quadrature that never sees the boundary's Green integrals (the
//! disc's chords integrated in the angle `x = R + sin(theta)`, piecewise smooth between the
//! cells' edges), spheres from half discs on the axis, Pappus' volume of NURBS profiles.

mod common;

use std::f64::consts::PI;

use rs_contain::FillRule;
use rs_coverage::{CellGrid, CoverageError, CoverageOptions, GridCoverage};
use rs_spline::prelude::*;
use rs_spline::{Affine, Axis, Domain, Point, circle, circular_arc, segment};

/// Gauss-Legendre nodes and weights on `[-1, 1]` (Golub-Welsch free: Newton on `P_n`).
fn gauss(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
            let mut dp = 0.0;
            for _ in 0..100 {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                    (p0, p1) = (p1, p2);
                }
                dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let dx = p1 / dp;
                x -= dx;
                if dx.abs() < 1e-16 {
                    break;
                }
            }
            (x, 2.0 / ((1.0 - x * x) * dp * dp))
        })
        .collect()
}

/// `[int int x dA, int int x^2 dA, int int x y dA]` over the cell `[x0, x1] x [y0, y1]`
/// within the disc of radius 1 about `(cx, 0)`: in `x = cx + sin(theta)` the chord is
/// `|y| <= cos(theta)`, the integrand smooth between the angles where a chord end or the
/// cell's sides change.
fn disc_cell_moments(cx: f64, (x0, x1): (f64, f64), (y0, y1): (f64, f64)) -> [f64; 3] {
    let rule = gauss(24);
    let clamp = |v: f64| v.clamp(-1.0, 1.0);
    let (a, b) = (clamp(x0 - cx).asin(), clamp(x1 - cx).asin());
    if b <= a {
        return [0.0; 3];
    }
    let mut cuts = vec![a, b];
    for y in [y0, y1] {
        if y.abs() < 1.0 {
            let t = y.abs().acos();
            cuts.extend([t, -t].into_iter().filter(|&t| a < t && t < b));
        }
    }
    cuts.sort_by(f64::total_cmp);
    let mut sum = [0.0; 3];
    for w in cuts.windows(2) {
        let (h, m) = (0.5 * (w[1] - w[0]), 0.5 * (w[1] + w[0]));
        for &(s, wt) in &rule {
            let t = m + h * s;
            let (x, c) = (cx + t.sin(), t.cos());
            let (lo, hi) = (y0.max(-c), y1.min(c));
            if hi <= lo {
                continue;
            }
            let dx = c; // dx / dtheta
            let f = wt * h * dx;
            sum[0] += f * x * (hi - lo);
            sum[1] += f * x * x * (hi - lo);
            sum[2] += f * x * 0.5 * (hi * hi - lo * lo);
        }
    }
    sum
}

fn revolved(axis: Axis) -> CoverageOptions {
    CoverageOptions::DEFAULT.with_axisymmetric(Some(axis))
}

/// The ring a cell sweeps about the y axis, over `2 pi`: `h (x1^2 - x0^2) / 2`.
fn ring(g: &CellGrid, i: usize, j: usize) -> f64 {
    let (x, y) = (g.x_edges(), g.y_edges());
    0.5 * (y[j + 1] - y[j]) * (x[i + 1] * x[i + 1] - x[i] * x[i])
}

#[test]
fn a_torus_is_right_cell_by_cell_with_its_weighted_centroids() {
    let (big_r, cells) = (2.0, 40);
    let d = Domain::new(vec![circle(Point::new(big_r, 0.0), 1.0).unwrap()]).unwrap();
    let grid = CellGrid::uniform(0.7, 3.3, cells, -1.2, 1.2, cells - 3).unwrap();
    let cover = GridCoverage::new(&d, grid.clone()).unwrap();
    let c = cover.all(revolved(Axis::Y).with_centroids(true)).unwrap();
    let centroids = c.centroids.as_ref().unwrap();
    let (x, y) = (grid.x_edges(), grid.y_edges());
    let mut total = 0.0;
    for j in 0..grid.ny() {
        for i in 0..grid.nx() {
            let k = j * grid.nx() + i;
            let [m, mxx, mxy] = disc_cell_moments(big_r, (x[i], x[i + 1]), (y[j], y[j + 1]));
            let want = m / ring(&grid, i, j);
            assert!(
                (c.fractions[k] - want).abs() < 1e-12,
                "cell ({i}, {j}): {} vs {want}",
                c.fractions[k]
            );
            total += c.fractions[k] * ring(&grid, i, j);
            if want > 0.0 {
                // A centroid carries about eps / fraction of the cell's size (the module's
                // accuracy note): a small covered part's moments are differences.
                let [cx, cy] = centroids[k];
                let size = (x[i + 1] - x[i]) * (1e-11 + 32.0 * f64::EPSILON / want);
                assert!((cx - mxx / m).abs() < size, "cell ({i}, {j}) x");
                assert!(
                    (cy - mxy / m).abs() < size,
                    "cell ({i}, {j}) y: {cy} vs {} (x {cx} vs {}), fraction {}",
                    mxy / m,
                    mxx / m,
                    c.fractions[k]
                );
            } else if c.fractions[k] == 0.0 {
                assert!(centroids[k][0].is_nan());
            }
        }
    }
    // Pappus: 2 pi (pi r^2) R over 2 pi.
    assert!((total - PI * big_r).abs() < 1e-12 * PI * big_r, "{total}");
}

#[test]
fn a_disc_about_the_x_axis_is_the_same_torus_turned() {
    // The disc about (0, 2) revolved about the x axis is the torus above, x and y exchanged.
    let d = Domain::new(vec![circle(Point::new(0.0, 2.0), 1.0).unwrap()]).unwrap();
    let t = Domain::new(vec![circle(Point::new(2.0, 0.0), 1.0).unwrap()]).unwrap();
    let g = CellGrid::uniform(-1.2, 1.2, 17, 0.7, 3.3, 23).unwrap();
    let gt = CellGrid::new(g.y_edges().to_vec(), g.x_edges().to_vec()).unwrap();
    let options = |axis| revolved(axis).with_centroids(true).with_apertures(true);
    let a = GridCoverage::new(&d, g.clone())
        .unwrap()
        .all(options(Axis::X))
        .unwrap();
    let b = GridCoverage::new(&t, gt)
        .unwrap()
        .all(options(Axis::Y))
        .unwrap();
    for j in 0..g.ny() {
        for i in 0..g.nx() {
            // Cell (i, j) of `g` is cell (j, i) of the turned grid.
            let (p, q) = (j * g.nx() + i, i * g.ny() + j);
            assert!(
                (a.fractions[p] - b.fractions[q]).abs() < 1e-13,
                "({i}, {j})"
            );
            let (ca, cb) = (
                a.centroids.as_ref().unwrap()[p],
                b.centroids.as_ref().unwrap()[q],
            );
            if a.fractions[p] > 0.0 {
                let tol = 1e-12 + 32.0 * f64::EPSILON / a.fractions[p];
                assert!(
                    (ca[0] - cb[1]).abs() < tol && (ca[1] - cb[0]).abs() < tol,
                    "({i}, {j}): {ca:?} vs {cb:?}, fraction {}",
                    a.fractions[p]
                );
            }
        }
    }
    // Faces across the axis are annuli on both: vertical faces of `g`, horizontal of `gt`.
    let (xa, yb) = (a.x_apertures.unwrap(), b.y_apertures.unwrap());
    for j in 0..g.ny() {
        for i in 0..=g.nx() {
            let (p, q) = (j * (g.nx() + 1) + i, i * g.ny() + j);
            assert!((xa[p] - yb[q]).abs() < 1e-13, "face ({i}, {j})");
        }
    }
}

/// The half disc of radius `r` about `centre` from `start` through half a turn, closed by
/// the diameter (the arc's own end points, so the loop closes exactly).
fn half_disc(centre: Point, r: f64, start: f64) -> Domain {
    let arc = circular_arc(centre, r, start, PI).unwrap();
    let (t0, t1) = arc.knots().domain();
    let (end, start) = (arc.point_at(t1), arc.point_at(t0));
    Domain::new(vec![arc, segment(end, start).unwrap()]).unwrap()
}

#[test]
fn half_discs_on_the_axis_make_spheres() {
    let r = 1.25;
    // About the y axis: the half disc x >= 0; about the x axis: y >= 0.
    for (axis, d, grid) in [
        (
            Axis::Y,
            half_disc(Point::new(0.0, 0.5), r, -0.5 * PI),
            CellGrid::uniform(0.0, 1.5, 30, -1.0, 2.0, 37).unwrap(),
        ),
        (
            Axis::X,
            half_disc(Point::new(0.25, 0.0), r, 0.0),
            CellGrid::uniform(-1.5, 2.0, 41, 0.0, 1.5, 27).unwrap(),
        ),
    ] {
        let c = GridCoverage::new(&d, grid.clone())
            .unwrap()
            .all(revolved(axis))
            .unwrap();
        let (x, y) = (grid.x_edges(), grid.y_edges());
        let mut total = 0.0;
        for j in 0..grid.ny() {
            for i in 0..grid.nx() {
                let (w, h) = (x[i + 1] - x[i], y[j + 1] - y[j]);
                let swept = match axis {
                    Axis::Y => 0.5 * h * (x[i + 1] * x[i + 1] - x[i] * x[i]),
                    Axis::X => 0.5 * w * (y[j + 1] * y[j + 1] - y[j] * y[j]),
                };
                total += c.fractions[j * grid.nx() + i] * swept;
            }
        }
        // 4/3 pi r^3 over 2 pi.
        let want = 2.0 / 3.0 * r * r * r;
        assert!(
            (total - want).abs() < 1e-12 * want,
            "{axis:?}: {total} vs {want}"
        );
    }
}

#[test]
fn pappus_gives_the_volume_of_nurbs_profiles() {
    // The paper's fixtures moved right of the y axis: the revolved volume over 2 pi is the
    // first moment int int x dA = oint x^2 / 2 dy, integrated on the whole loops
    // (`common::domain_moments`).
    let mut checked = 0;
    for name in rs_testkit::INRS_FIXTURES {
        let path = rs_testkit::fixture_path(&format!("inrs-paper/{name}.json"));
        let d = rs_io::load_domain(path.to_str().unwrap()).unwrap();
        let b = d.bounding_box();
        let shift = Affine::translate(0.5 * b.diagonal() - b.min.x, 0.0);
        let curves: Vec<_> = d
            .curves()
            .iter()
            .map(|c| shift.apply_to_curve(c).unwrap())
            .collect();
        let d = Domain::new(curves).unwrap();
        let b = d.bounding_box();
        let grid =
            CellGrid::uniform(0.0, b.max.x * 1.01, 53, b.min.y - 0.1, b.max.y + 0.1, 47).unwrap();
        let Ok(cover) = GridCoverage::new(&d, grid.clone()) else {
            continue;
        };
        let c = cover.all(revolved(Axis::Y)).unwrap();
        let mut total = 0.0;
        for j in 0..grid.ny() {
            for i in 0..grid.nx() {
                total += c.fractions[j * grid.nx() + i] * ring(&grid, i, j);
            }
        }
        let (_, want, _) = common::domain_moments(&d, FillRule::EvenOdd);
        assert!(
            (total - want).abs() < 1e-12 * want.abs(),
            "{name}: {total} vs {want}"
        );
        checked += 1;
    }
    assert!(checked >= 4, "only {checked} closed fixtures");
}

#[test]
fn domains_and_grids_across_the_axis_are_refused() {
    let d = Domain::new(vec![circle(Point::new(0.5, 0.0), 1.0).unwrap()]).unwrap();
    let grid = CellGrid::uniform(0.0, 2.0, 4, -1.0, 1.0, 4).unwrap();
    let e = GridCoverage::new(&d, grid)
        .unwrap()
        .all(revolved(Axis::Y))
        .unwrap_err();
    assert!(
        matches!(e, CoverageError::AcrossAxis { what: "domain", .. }),
        "{e}"
    );
    assert_eq!(
        e.to_string(),
        "the domain crosses the axis of revolution (Y axis): its x runs from -5e-1 to 1.5e0; it must lie on one side (touching is fine)"
    );
    let d = Domain::new(vec![circle(Point::new(2.0, 0.0), 1.0).unwrap()]).unwrap();
    let grid = CellGrid::uniform(-1.0, 3.0, 4, -1.0, 1.0, 4).unwrap();
    let cover = GridCoverage::new(&d, grid).unwrap();
    let e = cover.rows(0..2, revolved(Axis::Y)).unwrap_err();
    assert!(
        matches!(e, CoverageError::AcrossAxis { what: "grid", .. }),
        "{e}"
    );
    let e = cover.all(revolved(Axis::X)).unwrap_err();
    assert!(
        matches!(e, CoverageError::AcrossAxis { what: "grid", .. }),
        "{e}"
    );
    let e = cover
        .all(revolved(Axis::Y).with_boundary(true))
        .unwrap_err();
    assert!(matches!(e, CoverageError::PlanarOnly { .. }), "{e}");
}
