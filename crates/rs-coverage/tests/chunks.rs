//! A cell's values do not depend on the band of rows it is computed in: every output of every
//! band equals the one-shot grid's bit for bit, for curves through grid vertices.

use rs_coverage::{CellGrid, Coverage, CoverageOptions, GridCoverage};
use rs_spline::{Domain, Point, circle, polyline};

fn everything() -> CoverageOptions {
    CoverageOptions::DEFAULT
        .with_centroids(true)
        .with_apertures(true)
        .with_boundary(true)
        .with_face_centroids(true)
}

/// Bit patterns (NaN equal to NaN).
fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// The arrays of `whole` for rows `j0 .. j1` as a band holds them.
fn assert_band_matches(whole: &Coverage, band: &Coverage, what: &str) {
    let (nx, j0, j1) = (whole.nx, band.rows.start, band.rows.end);
    let cells = |v: &[f64], per: usize| bits(&v[j0 * nx * per..j1 * nx * per]);
    let diff = |name: &str, a: Vec<u64>, b: Vec<u64>| {
        if let Some(k) = a.iter().zip(&b).position(|(a, b)| a != b) {
            panic!(
                "{what}: {name} of rows {j0}..{j1} differ at {k}: {} vs {}",
                f64::from_bits(a[k]),
                f64::from_bits(b[k])
            );
        }
    };
    diff(
        "fractions",
        cells(&whole.fractions, 1),
        bits(&band.fractions),
    );
    let flat = |c: &Option<Vec<[f64; 2]>>| c.as_ref().unwrap().as_flattened().to_vec();
    diff(
        "centroids",
        cells(&flat(&whole.centroids), 2),
        bits(&flat(&band.centroids)),
    );
    diff(
        "boundary lengths",
        cells(whole.boundary_lengths.as_ref().unwrap(), 1),
        bits(band.boundary_lengths.as_ref().unwrap()),
    );
    diff(
        "boundary centroids",
        cells(&flat(&whole.boundary_centroids), 2),
        bits(&flat(&band.boundary_centroids)),
    );
    diff(
        "boundary normals",
        cells(&flat(&whole.boundary_normals), 2),
        bits(&flat(&band.boundary_normals)),
    );
    let x_faces = |v: &Option<Vec<f64>>| v.as_ref().unwrap()[j0 * (nx + 1)..j1 * (nx + 1)].to_vec();
    diff(
        "x apertures",
        bits(&x_faces(&whole.x_apertures)),
        bits(band.x_apertures.as_ref().unwrap()),
    );
    diff(
        "x face centroids",
        bits(&x_faces(&whole.x_face_centroids)),
        bits(band.x_face_centroids.as_ref().unwrap()),
    );
    let y_faces = |v: &Option<Vec<f64>>| v.as_ref().unwrap()[j0 * nx..(j1 + 1) * nx].to_vec();
    diff(
        "y apertures",
        bits(&y_faces(&whole.y_apertures)),
        bits(band.y_apertures.as_ref().unwrap()),
    );
    diff(
        "y face centroids",
        bits(&y_faces(&whole.y_face_centroids)),
        bits(band.y_face_centroids.as_ref().unwrap()),
    );
}

fn check(what: &str, d: &Domain, grid: CellGrid) {
    let cover = GridCoverage::new(d, grid).unwrap();
    let ny = cover.grid().ny();
    let whole = cover.all(everything()).unwrap();
    for chunk in [1, 2, 3, 5, 7, 16] {
        let mut j0 = 0;
        while j0 < ny {
            let j1 = (j0 + chunk).min(ny);
            let band = cover.rows(j0..j1, everything()).unwrap();
            assert_band_matches(&whole, &band, &format!("{what}, chunk {chunk}"));
            j0 = j1;
        }
    }
}

#[test]
fn circles_through_grid_vertices_give_the_same_bits_in_every_band() {
    // The unit circle on dyadic grids passes through (+-1, 0), (0, +-1) and, at 0.6/0.8,
    // through the vertices (0.6, 0.8) etc. of a grid of step 0.2.
    let c = |x: f64, y: f64, r: f64| circle(Point::new(x, y), r).unwrap();
    check(
        "unit circle, step 1/8",
        &Domain::new(vec![c(0.0, 0.0, 1.0)]).unwrap(),
        CellGrid::uniform(-1.5, 1.5, 24, -1.5, 1.5, 24).unwrap(),
    );
    let edges: Vec<f64> = (0..=15).map(|k| -1.4 + 0.2 * k as f64).collect();
    check(
        "unit circle, step 0.2",
        &Domain::new(vec![c(0.0, 0.0, 1.0)]).unwrap(),
        CellGrid::new(edges.clone(), edges).unwrap(),
    );
    check(
        "ring",
        &Domain::new(vec![c(0.25, -0.25, 1.0), c(0.25, -0.25, 0.5)]).unwrap(),
        CellGrid::uniform(-1.0, 1.5, 40, -1.5, 1.0, 37).unwrap(),
    );
}

#[test]
fn circles_through_integer_vertices_give_the_same_bits_in_every_band() {
    // x^2 + y^2 = 25 passes through (3, 4), (4, 3), (5, 0), ... exactly; also scaled by 1/8.
    for scale in [1.0, 0.125] {
        let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 5.0 * scale).unwrap()]).unwrap();
        check(
            &format!("radius {}", 5.0 * scale),
            &d,
            CellGrid::uniform(-6.0 * scale, 6.0 * scale, 12, -6.0 * scale, 6.0 * scale, 12)
                .unwrap(),
        );
        check(
            &format!("radius {}, fine", 5.0 * scale),
            &d,
            CellGrid::uniform(-6.0 * scale, 6.0 * scale, 48, -6.0 * scale, 6.0 * scale, 48)
                .unwrap(),
        );
    }
}

#[test]
fn circles_through_many_vertices_give_the_same_bits_in_every_band() {
    // Radius 25 passes through 12 integer points besides the axes' 4 ((7, 24), (15, 20),
    // ...), radius 65 through 32; centres on vertices and off them.
    for (r, (cx, cy)) in [(25.0, (0.0, 0.0)), (65.0, (3.0, -2.0)), (25.0, (0.5, 0.25))] {
        let d = Domain::new(vec![circle(Point::new(cx, cy), r).unwrap()]).unwrap();
        let n = (2.0 * r + 4.0) as usize;
        let grid = CellGrid::uniform(cx - r - 2.0, cx + r + 2.0, n, cy - r - 2.0, cy + r + 2.0, n);
        check(&format!("radius {r} about ({cx}, {cy})"), &d, grid.unwrap());
    }
}

/// A reproducible stream of numbers in `[0, 1)`.
fn lcg(seed: &mut u64) -> f64 {
    *seed = seed
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    (*seed >> 11) as f64 / (1u64 << 53) as f64
}

#[test]
fn rectilinear_grids_through_points_of_the_curve_give_the_same_bits_in_every_band() {
    // Edges at the coordinates of points of the circle (within rounding of it), plus a few
    // others: vertices the curve passes through, within a few units in the last place.
    let mut seed = 7;
    for trial in 0..12 {
        let (cx, cy, r) = (
            lcg(&mut seed) - 0.5,
            lcg(&mut seed) - 0.5,
            0.5 + lcg(&mut seed),
        );
        let d = Domain::new(vec![circle(Point::new(cx, cy), r).unwrap()]).unwrap();
        let mut xs = vec![cx - 2.0, cx + 2.0];
        let mut ys = vec![cy - 2.0, cy + 2.0];
        for _ in 0..14 {
            let a = std::f64::consts::TAU * lcg(&mut seed);
            xs.push(cx + r * a.cos());
            ys.push(cy + r * a.sin());
            xs.push(cx + 4.0 * lcg(&mut seed) - 2.0);
            ys.push(cy + 4.0 * lcg(&mut seed) - 2.0);
        }
        for e in [&mut xs, &mut ys] {
            e.sort_by(f64::total_cmp);
            e.dedup();
        }
        check(
            &format!("trial {trial}"),
            &d,
            CellGrid::new(xs, ys).unwrap(),
        );
    }
}

#[test]
fn tangents_at_grid_vertices_give_the_same_bits_in_every_band() {
    // The unit circle about (0, 0.6) on 48 cells over [-1.6, 1.6]: its leftmost point
    // (-1, 0.6) is the vertex (x_9, y_33) within rounding (y_33 = 0.6000000000000001), a
    // vertical tangent whose crossing with y_33 is solved a rounding left of x = -1.
    let d = Domain::new(vec![circle(Point::new(0.0, 0.6), 1.0).unwrap()]).unwrap();
    check(
        "vertical tangent at a vertex",
        &d,
        CellGrid::uniform(-1.6, 1.6, 48, -1.6, 1.6, 48).unwrap(),
    );
    // Circles whose extreme points (left, right, top, bottom) sit on grid vertices of
    // uniform grids, within the rounding of the grid's edges.
    let mut seed = 11;
    for trial in 0..24 {
        let n = 8 + (lcg(&mut seed) * 40.0) as usize;
        let (x0, step) = (-2.0 + lcg(&mut seed), 4.0 / n as f64);
        let grid = CellGrid::uniform(x0, x0 + 4.0, n, x0, x0 + 4.0, n).unwrap();
        let (i, j) = (
            1 + (lcg(&mut seed) * (n as f64 / 2.0)) as usize,
            1 + (lcg(&mut seed) * (n as f64 - 2.0)) as usize,
        );
        let r = step * (1 + (lcg(&mut seed) * 4.0) as usize) as f64 * 0.999_999_999;
        let (vx, vy) = (grid.x_edges()[i], grid.y_edges()[j]);
        let centre = match trial % 4 {
            0 => Point::new(vx + r, vy),
            1 => Point::new(vx - r, vy),
            2 => Point::new(vx, vy - r),
            _ => Point::new(vx, vy + r),
        };
        let d = Domain::new(vec![circle(centre, r).unwrap()]).unwrap();
        check(&format!("tangent trial {trial}"), &d, grid);
    }
}

#[test]
fn axom_contours_give_the_same_bits_in_every_band() {
    for name in ["butterfly", "rose", "fish"] {
        let path = rs_testkit::fixture_path(&format!("axom-contours/{name}.svg"));
        let d = rs_io::load_domain(path.to_str().unwrap()).unwrap();
        let b = d.bounding_box();
        let grid = CellGrid::uniform(b.min.x, b.max.x, 41, b.min.y, b.max.y, 43).unwrap();
        check(name, &d, grid);
    }
}

#[test]
fn fixtures_give_the_same_bits_in_every_band() {
    for name in rs_testkit::INRS_FIXTURES {
        let path = rs_testkit::fixture_path(&format!("inrs-paper/{name}.json"));
        let d = rs_io::load_domain(path.to_str().unwrap()).unwrap();
        if GridCoverage::new(&d, CellGrid::uniform(0.0, 1.0, 1, 0.0, 1.0, 1).unwrap()).is_err() {
            continue;
        }
        let b = d.bounding_box();
        let grid = CellGrid::uniform(b.min.x, b.max.x, 29, b.min.y, b.max.y, 31).unwrap();
        check(name, &d, grid);
    }
}

#[test]
fn polygons_on_grid_lines_give_the_same_bits_in_every_band() {
    // Edges on grid lines and diagonals through vertices.
    let pts = [
        (0.0, 0.0),
        (2.0, 0.0),
        (2.0, 1.0),
        (1.0, 2.0),
        (0.0, 1.0),
        (0.0, 0.0),
    ];
    let pts: Vec<Point> = pts.iter().map(|&(x, y)| Point::new(x, y)).collect();
    check(
        "house",
        &Domain::new(vec![polyline(&pts).unwrap()]).unwrap(),
        CellGrid::uniform(-0.5, 2.5, 12, -0.5, 2.5, 12).unwrap(),
    );
}
