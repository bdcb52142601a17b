//! `inrs fractions`: the unit disc's cell fractions and face apertures against closed-form
//! circle-segment areas, its centroids against the disc's moments, a grid of many row bands
//! against the library's whole-grid `all()` bit for bit, and one-line errors that leave no
//! file behind.

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
