//! `inrs fractions`: the unit disc's cell fractions and face apertures against closed-form
//! circle-segment areas, its centroids against the disc's moments, a grid of many row bands
//! against the library's whole-grid `all()` bit for bit, a torus' volume from a revolved disc,
//! a square's boundary cell by cell, rectilinear edges files against `--grid`, and one-line
//! errors that leave no file behind.

#[allow(dead_code)]
mod common;
use common::{fixture, inrs, read_npy, temp_file};

use std::path::{Path, PathBuf};

use inrs::coverage::{CellGrid, CoverageOptions, GridCoverage};

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    common::scratch("fractions", name)
}

/// `int sqrt(1 - t^2) dt` from `u` to `v` (`-1 <= u <= v <= 1`) in closed form through
/// `t = sin(theta)`: `(D + cos(S) sin(D)) / 2` with `D`, `S` the difference and sum of the
/// angles. (The textbook `(t sqrt(1 - t^2) + asin(t)) / 2` at both ends loses 1e-12 of a
/// 64 x 64 cell near `t = -1` to cancellation; in this form the angles' rounding is damped by
/// `cos^2` at the ends: 5e-14 at worst on this grid against 40-digit mpmath.)
fn half_chord_integral(u: f64, v: f64) -> f64 {
    let (tu, tv) = (u.asin(), v.asin());
    let d = tv - tu;
    0.5 * (d + (tu + tv).cos() * d.sin())
}

/// The area of the unit disc in the rectangle `[a, b] x [c, d]`, in closed form: the
/// integral over `x` of the length of `[c, d]` within `[-s(x), s(x)]`, `s = sqrt(1 - x^2)`,
/// split where a rectangle side meets the circle so that each piece's bounds are a side or
/// the circle throughout.
fn disc_area_in(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let mut cuts = vec![a, b];
    for y in [c, d] {
        if y.abs() < 1.0 {
            let x = (1.0 - y * y).sqrt();
            cuts.extend([-x, x]);
        }
    }
    cuts.extend([-1.0, 1.0]);
    cuts.retain(|&x| (a..=b).contains(&x));
    cuts.sort_by(f64::total_cmp);
    let mut area = 0.0;
    for w in cuts.windows(2) {
        let (u, v) = (w[0], w[1]);
        let m = 0.5 * (u + v);
        if v <= u || m.abs() >= 1.0 {
            continue;
        }
        let s = (1.0 - m * m).sqrt();
        if s <= c || -s >= d {
            continue;
        }
        let arc = half_chord_integral(u, v);
        // Top: the circle where it is below d, else d; bottom: the circle where it is above c.
        let top = if s < d { arc } else { d * (v - u) };
        let bottom = if -s > c { -arc } else { c * (v - u) };
        area += top - bottom;
    }
    area
}

/// The covered length fraction of the segment `[lo, hi]` of the line at `t` (a vertical face
/// `x = t` or a horizontal one `y = t`) in the unit disc.
fn disc_chord_fraction(t: f64, lo: f64, hi: f64) -> f64 {
    if t.abs() >= 1.0 {
        return 0.0;
    }
    let s = (1.0 - t * t).sqrt();
    (hi.min(s) - lo.max(-s)).max(0.0) / (hi - lo)
}

/// The uniform edges `x0 + i (x1 - x0) / n` as the grid's help states them.
fn edges(x0: f64, x1: f64, n: usize) -> Vec<f64> {
    (0..=n)
        .map(|i| {
            if i == n {
                x1
            } else {
                x0 + (x1 - x0) * i as f64 / n as f64
            }
        })
        .collect()
}

/// Runs `inrs fractions` and asserts it succeeded.
fn fractions_ok(args: &[&str]) {
    let out = inrs(&[&["fractions"], args].concat());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The unit disc on a 64 x 64 grid (offset, so that the circle crosses cells in every way):
/// every fraction and every face aperture within 1e-12 of the closed form, the fractions'
/// total the disc's area, cells clear of the circle exactly 0 or 1, centroids inside their
/// cells (NaN where empty, the centre where full) and adding up to the disc's zero first
/// moments.
#[test]
fn unit_disc_fractions_are_circle_segment_areas() {
    let dir = scratch("disc");
    let out = dir.join("disc.npy");
    let (x0, x1, y0, y1, n) = (-1.1, 1.05, -1.05, 1.1, 64);
    fractions_ok(&[
        "--domain",
        &fixture("inrs-paper/circle.json"),
        "--grid=-1.1,1.05,64,-1.05,1.1,64",
        "--centroids",
        "--apertures",
        "--output",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        common::entries(&dir),
        [
            "disc.centroids.npy",
            "disc.npy",
            "disc.x_apertures.npy",
            "disc.y_apertures.npy"
        ]
    );
    let (xs, ys) = (edges(x0, x1, n), edges(y0, y1, n));
    let (shape, f) = read_npy(&out);
    assert_eq!(shape, [n, n]);
    let (shape, centroids) = read_npy(&dir.join("disc.centroids.npy"));
    assert_eq!(shape, [n, n, 2]);
    let (shape, xa) = read_npy(&dir.join("disc.x_apertures.npy"));
    assert_eq!(shape, [n, n + 1]);
    let (shape, ya) = read_npy(&dir.join("disc.y_apertures.npy"));
    assert_eq!(shape, [n + 1, n]);

    let cell_area = (xs[1] - xs[0]) * (ys[1] - ys[0]);
    let (mut total, mut mx, mut my) = (0.0, 0.0, 0.0);
    let (mut full, mut empty) = (0, 0);
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (xs[i], xs[i + 1], ys[j], ys[j + 1]);
            let area = (b - a) * (d - c);
            let want = disc_area_in(a, b, c, d) / area;
            let got = f[j * n + i];
            assert!(
                (got - want).abs() < 1e-12,
                "cell ({i}, {j}): {got} against {want}"
            );
            let [cx, cy] = [centroids[2 * (j * n + i)], centroids[2 * (j * n + i) + 1]];
            // The corners farthest from and nearest to the centre.
            let far = a.abs().max(b.abs()).hypot(c.abs().max(d.abs()));
            let near_x = if a > 0.0 { a } else { (-b).max(0.0) };
            let near_y = if c > 0.0 { c } else { (-d).max(0.0) };
            if far < 1.0 {
                assert_eq!(got, 1.0, "cell ({i}, {j}) is inside");
                assert!((cx - 0.5 * (a + b)).abs() < 1e-12 && (cy - 0.5 * (c + d)).abs() < 1e-12);
                full += 1;
            } else if near_x.hypot(near_y) > 1.0 {
                assert_eq!(got, 0.0, "cell ({i}, {j}) is outside");
                assert!(
                    cx.is_nan() && cy.is_nan(),
                    "cell ({i}, {j}): an empty centroid"
                );
                empty += 1;
            } else {
                assert!((a..=b).contains(&cx) && (c..=d).contains(&cy), "({i}, {j})");
            }
            total += got * area;
            if got > 0.0 {
                mx += got * area * cx;
                my += got * area * cy;
            }
        }
    }
    assert!(
        full > 2000 && empty > 300,
        "{full} full, {empty} empty cells"
    );
    assert!((total - std::f64::consts::PI).abs() < 1e-12, "area {total}");
    assert!((total - f.iter().sum::<f64>() * cell_area).abs() < 1e-12);
    assert!(mx.abs() < 1e-12 && my.abs() < 1e-12, "moments {mx}, {my}");

    for j in 0..n {
        for i in 0..=n {
            let want = disc_chord_fraction(xs[i], ys[j], ys[j + 1]);
            let got = xa[j * (n + 1) + i];
            assert!(
                (got - want).abs() < 1e-12,
                "x face ({i}, {j}): {got}, {want}"
            );
        }
    }
    for j in 0..=n {
        for i in 0..n {
            let want = disc_chord_fraction(ys[j], xs[i], xs[i + 1]);
            let got = ya[j * n + i];
            assert!(
                (got - want).abs() < 1e-12,
                "y face ({i}, {j}): {got}, {want}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `--fill-rule`: two counter-clockwise circles (radii 1 and 0.5, written as a JSON domain
/// here) fill the unit disc under nonzero, every cell within 1e-12 of the closed form and the
/// total `pi`; under even-odd (the default, and asked for by name) they fill the annulus,
/// `3 pi / 4`.
#[test]
fn fill_rule_nonzero_fills_nested_circles_of_one_orientation() {
    use inrs::spline::{Domain, Point, circle};
    let dir = scratch("nonzero");
    let domain = dir.join("two_circles.json");
    let c = |r: f64| circle(Point::new(0.0, 0.0), r).unwrap();
    let d = Domain::new(vec![c(1.0), c(0.5)]).unwrap();
    std::fs::write(&domain, inrs::io::json::domain_to_json(&d)).unwrap();
    let (x0, x1, y0, y1, n) = (-1.1, 1.05, -1.05, 1.1, 32);
    let (xs, ys) = (edges(x0, x1, n), edges(y0, y1, n));
    let cell_area = (xs[1] - xs[0]) * (ys[1] - ys[0]);
    let run = |rule: Option<&str>, name: &str| {
        let out = dir.join(name);
        let mut args = vec![
            "--domain",
            domain.to_str().unwrap(),
            "--grid=-1.1,1.05,32,-1.05,1.1,32",
            "--output",
            out.to_str().unwrap(),
        ];
        if let Some(rule) = rule {
            args.extend(["--fill-rule", rule]);
        }
        fractions_ok(&args);
        let (shape, f) = read_npy(&out);
        assert_eq!(shape, [n, n]);
        f
    };
    let pi = std::f64::consts::PI;
    let nonzero = run(Some("nonzero"), "nonzero.npy");
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (xs[i], xs[i + 1], ys[j], ys[j + 1]);
            let want = disc_area_in(a, b, c, d) / ((b - a) * (d - c));
            let got = nonzero[j * n + i];
            assert!((got - want).abs() < 1e-12, "cell ({i}, {j}): {got}, {want}");
        }
    }
    let total = nonzero.iter().sum::<f64>() * cell_area;
    assert!((total - pi).abs() < 1e-12, "nonzero area {total}");
    for (rule, name) in [(None, "default.npy"), (Some("even-odd"), "even_odd.npy")] {
        let total = run(rule, name).iter().sum::<f64>() * cell_area;
        assert!((total - 0.75 * pi).abs() < 1e-12, "{rule:?}: area {total}");
    }
    let o = inrs(&[
        "fractions",
        "--domain",
        domain.to_str().unwrap(),
        "--grid=0,1,2,0,1,2",
        "--fill-rule",
        "winding",
        "--output",
        dir.join("bad.npy").to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    assert!(!dir.join("bad.npy").exists());
    std::fs::remove_dir_all(&dir).ok();
}

/// A grid of many row bands (1500 x 1500 on the gear, which has a hole with an island in
/// it): every array equals the library's whole-grid `all()` bit for bit, the faces shared by
/// two bands written once.
#[test]
fn a_grid_of_many_bands_equals_the_whole_grid_bit_for_bit() {
    let dir = scratch("bands");
    let gear = fixture("io/gear.svg");
    let (x0, x1, y0, y1, n) = (7.3, 113.1, 8.2, 71.9, 1500);
    let grid = format!("{x0},{x1},{n},{y0},{y1},{n}");
    let out = dir.join("gear.npy");
    fractions_ok(&[
        "--domain",
        &gear,
        "--grid",
        &grid,
        "--centroids",
        "--apertures",
        "--output",
        out.to_str().unwrap(),
    ]);
    let d = inrs::io::load_domain(&gear).unwrap();
    let cells = CellGrid::uniform(x0, x1, n, y0, y1, n).unwrap();
    let options = CoverageOptions::DEFAULT
        .with_centroids(true)
        .with_apertures(true);
    let whole = GridCoverage::new(&d, cells).unwrap().all(options).unwrap();
    let same = |file: &str, shape: &[usize], want: &[f64]| {
        let (got_shape, got) = read_npy(&dir.join(file));
        assert_eq!(got_shape, shape, "{file}");
        assert_eq!(got.len(), want.len(), "{file}");
        let differ = got
            .iter()
            .zip(want)
            .filter(|(g, w)| g.to_bits() != w.to_bits() && !(g.is_nan() && w.is_nan()))
            .count();
        assert_eq!(differ, 0, "{file}: {differ} values differ from all()");
    };
    same("gear.npy", &[n, n], &whole.fractions);
    same(
        "gear.centroids.npy",
        &[n, n, 2],
        whole.centroids.as_ref().unwrap().as_flattened(),
    );
    same(
        "gear.x_apertures.npy",
        &[n, n + 1],
        whole.x_apertures.as_ref().unwrap(),
    );
    same(
        "gear.y_apertures.npy",
        &[n + 1, n],
        whole.y_apertures.as_ref().unwrap(),
    );
    // The gear's area (even-odd, as `inrs info` prints it) from the fractions alone.
    let area: f64 =
        whole.fractions.iter().sum::<f64>() * (x1 - x0) / n as f64 * (y1 - y0) / n as f64;
    assert!((area - 5279.98158716).abs() < 1e-6, "{area}");
    // Fractions alone: fewer, larger bands; the values of `all()` without the moments (which
    // may differ from those with them in the last bit).
    let fractions_only = GridCoverage::new(&d, CellGrid::uniform(x0, x1, n, y0, y1, n).unwrap())
        .unwrap()
        .all(CoverageOptions::DEFAULT)
        .unwrap();
    let alone = dir.join("alone.npy");
    fractions_ok(&[
        "--domain",
        &gear,
        "--grid",
        &grid,
        "--output",
        alone.to_str().unwrap(),
    ]);
    same("alone.npy", &[n, n], &fractions_only.fractions);
    assert_eq!(
        common::entries(&dir),
        [
            "alone.npy",
            "gear.centroids.npy",
            "gear.npy",
            "gear.x_apertures.npy",
            "gear.y_apertures.npy"
        ]
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Bad grids, a bad output name, an unreadable domain and an open boundary: one line on
/// standard error each, the usual exit status (2 for the command line, 1 for the input), no
/// file written, and an existing output left as it was.
#[test]
fn bad_input_gets_one_line_and_leaves_no_file() {
    let dir = scratch("errors");
    let out = dir.join("f.npy");
    std::fs::write(&out, "old").unwrap();
    let circle = fixture("inrs-paper/circle.json");
    let open = temp_file(
        "open_chain.json",
        r#"{"curves": [{"degree": 1, "control_points": [[0, 0], [1, 0]]},
                       {"degree": 1, "control_points": [[1, 0], [1, 1]]}]}"#,
    );
    let run = |domain: &str, grid: &str, output: &Path, extra: &[&str]| {
        let grid = format!("--grid={grid}");
        let args = [
            &["fractions", "--domain", domain, &grid, "--output"][..],
            &[output.to_str().unwrap()],
            extra,
        ]
        .concat();
        let o = inrs(&args);
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("inrs: "), "{err}");
        (o.status.code(), err)
    };
    let cases: [(&str, &str, &str, Option<i32>); 9] = [
        (&circle, "0,1,4,0,1", "(6 values), got 5 values", Some(2)),
        (
            &circle,
            "0,one,4,0,1,4",
            "x1 = \"one\" is not a number",
            Some(2),
        ),
        (
            &circle,
            "0,1,0,0,1,4",
            "nx = \"0\": expected a whole number",
            Some(2),
        ),
        (&circle, "0,1,4,0,1,-3", "ny = \"-3\"", Some(2)),
        (
            &circle,
            "1,-1,4,0,1,4",
            "x0 = 1.0 must be below x1 = -1.0",
            Some(2),
        ),
        (&circle, "0,1,4,0,inf,4", "y1 = inf must be finite", Some(2)),
        (
            &circle,
            "0,1,100000,0,1,100000",
            "exceed the limit of 2^32",
            Some(2),
        ),
        (&circle, "0,1e200,4,0,1,4", "--grid: x edge", Some(1)),
        (&open, "-1,2,8,-1,2,8", "open boundary", Some(1)),
    ];
    for (domain, grid, message, code) in cases {
        let (status, err) = run(domain, grid, &out, &["--centroids", "--apertures"]);
        assert!(err.contains(message), "{grid}: {err}");
        assert_eq!(status, code, "{grid}: {err}");
        assert_eq!(common::entries(&dir), ["f.npy"], "{grid}");
        assert_eq!(std::fs::read(&out).unwrap(), b"old");
    }
    let (status, err) = run(&circle, "0,1,4,0,1,4", &dir.join("f.csv"), &[]);
    assert!(err.contains("must be a file name ending in .npy"), "{err}");
    assert_eq!(status, Some(2));
    let missing = dir.join("missing.json");
    let (status, err) = run(missing.to_str().unwrap(), "0,1,4,0,1,4", &out, &[]);
    assert!(err.contains("missing.json"), "{err}");
    assert_eq!(status, Some(1));
    // An output in a directory that does not exist: nothing is created.
    let (status, err) = run(&circle, "0,1,4,0,1,4", &dir.join("no/f.npy"), &[]);
    assert!(err.contains("f.npy"), "{err}");
    assert_eq!(status, Some(1));
    assert_eq!(common::entries(&dir), ["f.npy"]);
    assert_eq!(std::fs::read(&out).unwrap(), b"old");
    std::fs::remove_dir_all(&dir).ok();
}

/// Writes `values` as a 1-D float64 `.npy` file (as `numpy.save` does).
fn write_edges(path: &Path, values: &[f64]) {
    let mut bytes = inrs::npy_header(inrs::NpyType::F64, &[values.len()]);
    bytes.extend(values.iter().flat_map(|v| v.to_le_bytes()));
    std::fs::write(path, bytes).unwrap();
}

/// Every new output of a run with all of them, with its shape; the NaN conventions (a cell
/// without boundary: length 0, centroid and normal NaN; an uncovered face: centroid NaN).
#[test]
fn boundary_and_face_centroids_have_their_files_and_shapes() {
    let dir = scratch("eb_files");
    let out = dir.join("d.npy");
    let (nx, ny) = (12, 10);
    fractions_ok(&[
        "--domain",
        &fixture("inrs-paper/circle.json"),
        "--grid=-1.2,1.1,12,-1.05,1.3,10",
        "--centroids",
        "--apertures",
        "--boundary",
        "--face-centroids",
        "--output",
        out.to_str().unwrap(),
    ]);
    assert_eq!(
        common::entries(&dir),
        [
            "d.boundary_centroids.npy",
            "d.boundary_lengths.npy",
            "d.boundary_normals.npy",
            "d.centroids.npy",
            "d.npy",
            "d.x_apertures.npy",
            "d.x_face_centroids.npy",
            "d.y_apertures.npy",
            "d.y_face_centroids.npy"
        ]
    );
    let read = |name: &str, shape: &[usize]| {
        let (got, values) = read_npy(&dir.join(format!("d.{name}.npy")));
        assert_eq!(got, shape, "{name}");
        values
    };
    let lengths = read("boundary_lengths", &[ny, nx]);
    let centroids = read("boundary_centroids", &[ny, nx, 2]);
    let normals = read("boundary_normals", &[ny, nx, 2]);
    for (k, &l) in lengths.iter().enumerate() {
        let (c, n) = (&centroids[2 * k..2 * k + 2], &normals[2 * k..2 * k + 2]);
        if l == 0.0 {
            assert!(c.iter().chain(n).all(|v| v.is_nan()), "cell {k}");
        } else {
            assert!(c.iter().chain(n).all(|v| v.is_finite()), "cell {k}");
            assert!((n[0].hypot(n[1]) - 1.0).abs() < 1e-15, "cell {k}: {n:?}");
        }
    }
    // The unit circle's length, cell by cell.
    let total: f64 = lengths.iter().sum();
    assert!(
        (total - 2.0 * std::f64::consts::PI).abs() < 1e-12,
        "{total}"
    );
    for (name, shape, apertures) in [
        ("x_face_centroids", [ny, nx + 1], "x_apertures"),
        ("y_face_centroids", [ny + 1, nx], "y_apertures"),
    ] {
        let faces = read(name, &shape);
        let open = read(apertures, &shape);
        for (c, a) in faces.iter().zip(&open) {
            assert_eq!(c.is_nan(), *a == 0.0, "{name}: {c} with aperture {a}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The ring swept by cell `[x0, x1] x [y0, y1]` about the y axis: `pi (y1 - y0) (x1^2 - x0^2)`.
fn ring_volume(x0: f64, x1: f64, y0: f64, y1: f64) -> f64 {
    std::f64::consts::PI * (y1 - y0) * (x1 * x1 - x0 * x0)
}

/// A disc of radius `r` whose centre is `R` from the axis, revolved about the y axis (and,
/// mirrored, about the x axis): the fractions times the rings' volumes add up to the torus'
/// volume `2 pi^2 r^2 R` within 1e-12 relative; the revolved centroids and apertures are
/// written too.
#[test]
fn a_disc_revolved_is_a_torus() {
    let dir = scratch("torus");
    let (r, big_r, yc) = (0.5, 2.0, 0.3);
    let torus = 2.0 * std::f64::consts::PI.powi(2) * r * r * big_r;
    let about_y = temp_file(
        "torus_about_y.json",
        &format!(r#"{{"curves": [{{"circle": {{"center": [{big_r}, {yc}], "radius": {r}}}}}]}}"#),
    );
    let about_x = temp_file(
        "torus_about_x.json",
        &format!(r#"{{"curves": [{{"circle": {{"center": [{yc}, {big_r}], "radius": {r}}}}}]}}"#),
    );
    // Radius 0 .. 3 in 75 columns, the axis' direction -0.5 .. 1.1 in 40 rows.
    let (r0, r1, nr, a0, a1, na) = (0.0, 3.0, 75, -0.5, 1.1, 40);
    let rs = edges(r0, r1, nr);
    let zs = edges(a0, a1, na);
    let volume = |fractions: &[f64], transposed: bool| {
        let mut v = 0.0;
        for (k, f) in fractions.iter().enumerate() {
            let (i, j) = if transposed {
                (k / na, k % na)
            } else {
                (k % nr, k / nr)
            };
            v += f * ring_volume(rs[i], rs[i + 1], zs[j], zs[j + 1]);
        }
        v
    };
    let y = dir.join("y.npy");
    fractions_ok(&[
        "--domain",
        &about_y,
        &format!("--grid={r0},{r1},{nr},{a0},{a1},{na}"),
        "--axisymmetric",
        "y",
        "--centroids",
        "--apertures",
        "--output",
        y.to_str().unwrap(),
    ]);
    let (shape, fy) = read_npy(&y);
    assert_eq!(shape, [na, nr]);
    let vy = volume(&fy, false);
    assert!((vy - torus).abs() <= 1e-12 * torus, "{vy} vs {torus}");
    let (shape, _) = read_npy(&dir.join("y.centroids.npy"));
    assert_eq!(shape, [na, nr, 2]);
    // About the x axis: the same torus, the grid transposed (rows are the radius).
    let x = dir.join("x.npy");
    fractions_ok(&[
        "--domain",
        &about_x,
        &format!("--grid={a0},{a1},{na},{r0},{r1},{nr}"),
        "--axisymmetric",
        "x",
        "--output",
        x.to_str().unwrap(),
    ]);
    let (shape, fx) = read_npy(&x);
    assert_eq!(shape, [nr, na]);
    let vx = volume(&fx, true);
    assert!((vx - torus).abs() <= 1e-12 * torus, "{vx} vs {torus}");
    std::fs::remove_dir_all(&dir).ok();
}

/// The square `[0.25, 1.75]^2` on the grid `[0, 2]^2` of 4 x 4 cells (its sides inside the
/// cells): lengths, centroids and normals of its sides cell by cell, exact.
#[test]
fn a_squares_boundary_is_its_sides_cell_by_cell() {
    let dir = scratch("square");
    let square = temp_file(
        "eb_square.json",
        r#"{"curves": [{"polyline":
            [[0.25, 0.25], [1.75, 0.25], [1.75, 1.75], [0.25, 1.75], [0.25, 0.25]]}]}"#,
    );
    let out = dir.join("s.npy");
    fractions_ok(&[
        "--domain",
        &square,
        "--grid=0,2,4,0,2,4",
        "--boundary",
        "--face-centroids",
        "--output",
        out.to_str().unwrap(),
    ]);
    let (_, lengths) = read_npy(&dir.join("s.boundary_lengths.npy"));
    let (_, centroids) = read_npy(&dir.join("s.boundary_centroids.npy"));
    let (_, normals) = read_npy(&dir.join("s.boundary_normals.npy"));
    let s = std::f64::consts::FRAC_1_SQRT_2;
    for j in 0..4 {
        for i in 0..4 {
            let k = 4 * j + i;
            let (low_x, high_x, low_y, high_y) = (i == 0, i == 3, j == 0, j == 3);
            let (c, n) = (&centroids[2 * k..2 * k + 2], &normals[2 * k..2 * k + 2]);
            let (x0, y0) = (0.5 * i as f64, 0.5 * j as f64);
            // Which sides cross the cell: a corner cell holds two quarter-length pieces.
            match (low_x || high_x, low_y || high_y) {
                (false, false) => {
                    assert_eq!(lengths[k], 0.0, "cell ({i}, {j})");
                    assert!(c[0].is_nan() && c[1].is_nan() && n[0].is_nan() && n[1].is_nan());
                }
                (true, true) => {
                    assert_eq!(lengths[k], 0.5, "cell ({i}, {j})");
                    let (sx, sy) = (
                        if low_x { -1.0 } else { 1.0 },
                        if low_y { -1.0 } else { 1.0 },
                    );
                    assert!(
                        (n[0] - sx * s).abs() < 1e-15 && (n[1] - sy * s).abs() < 1e-15,
                        "{n:?}"
                    );
                    // The two pieces' midpoints, averaged.
                    let side_x = if low_x { 0.25 } else { 1.75 };
                    let side_y = if low_y { 0.25 } else { 1.75 };
                    let mid_x = if low_x { 0.375 } else { 1.625 };
                    let mid_y = if low_y { 0.375 } else { 1.625 };
                    assert_eq!(
                        c,
                        [0.5 * (side_x + mid_x), 0.5 * (side_y + mid_y)],
                        "cell ({i}, {j})"
                    );
                }
                (true, false) => {
                    assert_eq!(lengths[k], 0.5, "cell ({i}, {j})");
                    let side = if low_x { 0.25 } else { 1.75 };
                    assert_eq!(n, [if low_x { -1.0 } else { 1.0 }, 0.0], "cell ({i}, {j})");
                    assert_eq!(c, [side, y0 + 0.25], "cell ({i}, {j})");
                }
                (false, true) => {
                    assert_eq!(lengths[k], 0.5, "cell ({i}, {j})");
                    let side = if low_y { 0.25 } else { 1.75 };
                    assert_eq!(n, [0.0, if low_y { -1.0 } else { 1.0 }], "cell ({i}, {j})");
                    assert_eq!(c, [x0 + 0.25, side], "cell ({i}, {j})");
                }
            }
        }
    }
    // Face centroids: the vertical face x = 0.5 of row 0 is covered on [0.25, 0.5].
    let (_, xc) = read_npy(&dir.join("s.x_face_centroids.npy"));
    assert_eq!(xc[1], 0.375);
    assert!(xc[0].is_nan(), "x = 0 is outside the square");
    assert_eq!(xc[5 + 2], 0.75, "row 1, x = 1: covered on [0.5, 1]");
    let (_, yc) = read_npy(&dir.join("s.y_face_centroids.npy"));
    assert_eq!(
        yc[4 + 3],
        1.625,
        "line y = 0.5, column 3: covered on [1.5, 1.75]"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// `--x-edges` / `--y-edges` holding the uniform grid's own edges give the files of `--grid`
/// byte for byte, every output on.
#[test]
fn rectilinear_edges_files_equal_the_uniform_grid_bit_for_bit() {
    let dir = scratch("edges");
    let gear = fixture("io/gear.svg");
    let (x0, x1, nx, y0, y1, ny) = (7.3, 113.1, 301, 8.2, 71.9, 203);
    let cells = CellGrid::uniform(x0, x1, nx, y0, y1, ny).unwrap();
    let (xe, ye) = (dir.join("xe.npy"), dir.join("ye.npy"));
    write_edges(&xe, cells.x_edges());
    write_edges(&ye, cells.y_edges());
    let all = [
        "--centroids",
        "--apertures",
        "--boundary",
        "--face-centroids",
    ];
    let uniform = dir.join("u.npy");
    let grid = format!("--grid={x0},{x1},{nx},{y0},{y1},{ny}");
    fractions_ok(
        &[
            &[
                "--domain",
                &gear,
                &grid,
                "--output",
                uniform.to_str().unwrap(),
            ],
            &all[..],
        ]
        .concat(),
    );
    let rect = dir.join("r.npy");
    fractions_ok(
        &[
            &[
                "--domain",
                &gear,
                "--x-edges",
                xe.to_str().unwrap(),
                "--y-edges",
                ye.to_str().unwrap(),
                "--output",
                rect.to_str().unwrap(),
            ],
            &all[..],
        ]
        .concat(),
    );
    for name in [
        "",
        ".centroids",
        ".x_apertures",
        ".y_apertures",
        ".boundary_lengths",
        ".boundary_centroids",
        ".boundary_normals",
        ".x_face_centroids",
        ".y_face_centroids",
    ] {
        let u = std::fs::read(dir.join(format!("u{name}.npy"))).unwrap();
        let r = std::fs::read(dir.join(format!("r{name}.npy"))).unwrap();
        assert!(u == r, "u{name}.npy and r{name}.npy differ");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// An axis the grid or the domain crosses, planar-only outputs revolved, and bad edges files
/// (another type, another shape, missing, too few, not increasing, both grid forms): one line
/// each, and no file created (an existing output stays as it was).
#[test]
fn eb_and_edges_errors_get_one_line_and_leave_no_file() {
    let dir = scratch("eb_errors");
    let out = dir.join("f.npy");
    std::fs::write(&out, "old").unwrap();
    let circle = fixture("inrs-paper/circle.json");
    let put = |name: &str, bytes: Vec<u8>| {
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        p.to_str().unwrap().to_string()
    };
    let good = put("good.npy", {
        let mut b = inrs::npy_header(inrs::NpyType::F64, &[3]);
        b.extend([0.0f64, 0.5, 1.0].iter().flat_map(|v| v.to_le_bytes()));
        b
    });
    let int8 = put("int8.npy", {
        let mut b = inrs::npy_header(inrs::NpyType::I8, &[3]);
        b.extend([0u8, 1, 2]);
        b
    });
    let matrix = put("matrix.npy", {
        let mut b = inrs::npy_header(inrs::NpyType::F64, &[2, 2]);
        b.extend([0.0f64; 4].iter().flat_map(|v| v.to_le_bytes()));
        b
    });
    let one = put("one.npy", {
        let mut b = inrs::npy_header(inrs::NpyType::F64, &[1]);
        b.extend(0.0f64.to_le_bytes());
        b
    });
    let down = put("down.npy", {
        let mut b = inrs::npy_header(inrs::NpyType::F64, &[3]);
        b.extend([0.0f64, 1.0, 0.5].iter().flat_map(|v| v.to_le_bytes()));
        b
    });
    let missing = dir.join("missing.npy").to_str().unwrap().to_string();
    let half_disc = temp_file(
        "eb_right_disc.json",
        r#"{"curves": [{"circle": {"center": [0.5, 0], "radius": 1}}]}"#,
    );
    let o = out.to_str().unwrap();
    let cases: Vec<(Vec<&str>, &str, i32)> = vec![
        (
            vec![
                "--domain",
                &circle,
                "--grid=-1,1,4,-1,1,4",
                "--axisymmetric",
                "y",
            ],
            "--axisymmetric y: the grid crosses the axis of revolution",
            1,
        ),
        (
            vec![
                "--domain",
                &half_disc,
                "--grid=0,2,4,-1,1,4",
                "--axisymmetric",
                "y",
            ],
            "--axisymmetric y: the domain crosses the axis of revolution",
            1,
        ),
        (
            vec![
                "--domain",
                &circle,
                "--grid=-1,1,4,0,1,4",
                "--axisymmetric",
                "x",
                "--boundary",
            ],
            "computed for planar cells only",
            1,
        ),
        (
            vec![
                "--domain",
                &circle,
                "--grid=-1,1,4,0,1,4",
                "--axisymmetric",
                "x",
                "--face-centroids",
            ],
            "face centroids are computed for planar cells only",
            1,
        ),
        (
            vec!["--domain", &circle, "--x-edges", &int8, "--y-edges", &good],
            "--x-edges: ",
            1,
        ),
        (
            vec![
                "--domain",
                &circle,
                "--x-edges",
                &good,
                "--y-edges",
                &matrix,
            ],
            "shape (2, 2): expected a 1-D array",
            1,
        ),
        (
            vec![
                "--domain",
                &circle,
                "--x-edges",
                &missing,
                "--y-edges",
                &good,
            ],
            "missing.npy",
            1,
        ),
        (
            vec!["--domain", &circle, "--x-edges", &one, "--y-edges", &good],
            "at least 2 x edges",
            1,
        ),
        (
            vec!["--domain", &circle, "--x-edges", &good, "--y-edges", &down],
            "y edges must increase strictly",
            1,
        ),
        (
            vec![
                "--domain",
                &circle,
                "--x-edges",
                &good,
                "--y-edges",
                &good,
                "--grid=0,1,2,0,1,2",
            ],
            "cannot be used with",
            2,
        ),
        (
            vec!["--domain", &circle, "--x-edges", &good],
            "--y-edges",
            2,
        ),
        (vec!["--domain", &circle], "required arguments", 2),
    ];
    for (args, message, code) in cases {
        let all = [
            &["fractions"][..],
            &args,
            &["--centroids", "--apertures", "--output", o],
        ]
        .concat();
        let run = inrs(&all);
        let err = String::from_utf8_lossy(&run.stderr).into_owned();
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(
            err.starts_with("inrs: ") && err.contains(message),
            "{args:?}: {err}"
        );
        assert_eq!(run.status.code(), Some(code), "{args:?}: {err}");
        assert_eq!(std::fs::read(&out).unwrap(), b"old", "{args:?}");
        let mut left = common::entries(&dir);
        left.retain(|e| e.starts_with("f."));
        assert_eq!(left, ["f.npy"], "{args:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
