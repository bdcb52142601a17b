//! inrs's fast winding field against LLNL Axom's 2-D generalized winding numbers on the GWN
//! paper's five shapes (issue 52's rows): Axom's fast approximation of PR #1838
//! (`quest::fast_approximate_winding_number`, Taylor order 2, memoized curve subdivisions) and
//! its exact method (`primal::winding_number` summed over the curves, memoized), both on one
//! thread, against `FastWindingField::winding_numbers` on one thread.
//!
//! Axom's code stays outside this repository: Axom runs in an external driver named by the
//! environment variable [`DRIVER_VAR`], called as
//!
//! `DRIVER METHOD CURVES POINTS OUT REPS`
//!
//! - `METHOD`: `fast` (PR #1838, order 2, memoized: the default of Axom's
//!   `quest_winding_number_2d`) or `direct` (exact, memoized);
//! - `CURVES`: one rational Bezier curve a line, its degree `d`, then its `d + 1` control
//!   points `x y`, then its `d + 1` weights ([`write_curves`]);
//! - `POINTS`: the query points, little-endian `f64` pairs ([`point_sets::write_points`](super::point_sets::write_points));
//! - `OUT`: the driver writes the winding numbers there, one little-endian `f64` a point;
//! - `REPS`: repetitions (after an untimed one), each of which builds Axom's query structure from the curves
//!   (`setup`), queries every point once (`cold`: the memoization caches fill, as in Axom's
//!   example) and again (`warm`: caches full);
//!
//! and prints one JSON line with the medians `setup_s`, `cold_s`, `warm_s` (seconds, file
//! input and output excluded). The cold pass is the comparable one: inrs's field has no cache
//! to fill, and the warm pass asks the same points twice.
//!
//! The driver measured for issue 52 replays `quest::NURBSCurveGWNQuery::preprocess` and
//! `::query` (Axom's `GWNMethods.hpp`, which takes its points from an mfem mesh) on points read
//! from the file: `subdivide_curves(.., 2.0)`, a `spin::BVH` of the pieces' boxes,
//! `GWNMomentData<double, 2, 2>` reduced up the tree, `NURBSCurveCacheManager`, then
//! `fast_approximate_winding_number` or `primal::winding_number` with the default
//! `WindingTolerances`, `SEQ_EXEC`. It was built from Axom at `bdec72c` (PR #1838's head) with
//! `g++ -O3 -DNDEBUG -std=c++17` (no `-march`, as inrs's release build): core's and slic's
//! `.cpp` files, the rest being headers, with the configuration headers `CMake` would write for
//! a serial CPU build.
//!
//! The runs alternate, in rounds, between the driver and inrs (so a noisy spell on the machine
//! slows both alike); the table shows the medians over the rounds.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use inrs::contain::{DEFAULT_RELATIVE_TOLERANCE, FastWindingField, WindingField};
use inrs::{Domain, Point};
use rs_testkit::{DensePolygon, NearBoundary};

use super::peers::{SHAPES, load_shape};
use super::point_sets::{near_points, random_points, write_points};
use super::{BenchOptions, Times, interleaved_times, median, median_time};

/// The environment variable naming the Axom driver.
const DRIVER_VAR: &str = "INRS_AXOM_GWN";

/// The shapes with hundreds of pieces (the others, bubble and twirl, have 17 and 3).
const LARGE: [&str; 3] = ["butterfly", "rose", "fish"];

/// The seed of both point sets (the issue's number, as every section using them).
const SEED: u64 = 52;

/// Points where Axom's exact method runs (every k-th point of a set): it visits every curve
/// for every point.
const EXACT_POINTS: usize = 5_000;

/// Points closer to the curves than this fraction of the box's diagonal are left out of the
/// agreement check: there the methods' on-curve tolerances (Axom's `edge_tol` 1e-8) decide.
const NEAR_FRACTION: f64 = 1e-6;

/// One driver run's medians, in seconds.
struct AxomTimes {
    setup: f64,
    cold: f64,
    warm: f64,
    /// The fastest cold pass.
    cold_best: f64,
}

/// The section: one line saying how to enable it when the driver is not set.
pub(super) fn section(md: &mut String, root: &Path, o: &BenchOptions) -> Result<(), String> {
    let Some(driver) = std::env::var_os(DRIVER_VAR).map(PathBuf::from) else {
        let line = format!(
            "Axom comparison skipped: set {DRIVER_VAR} to a driver built against LLNL Axom \
             (PR #1838) outside this repository; its interface is in xtask/src/bench/axom.rs."
        );
        // Printed with the report.
        let _ = writeln!(md, "\n{line}");
        return Ok(());
    };
    let dir = root.join("target/bench-axom");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let n = if o.quick { 10_000 } else { 100_000 };
    let rounds = o.reps.clamp(1, 5);
    let reps = 3;
    let _ = writeln!(
        md,
        "\nWinding numbers against LLNL Axom (`{DRIVER_VAR}` = `{}`), one thread each: inrs \
         `FastWindingField::winding_numbers` against Axom's fast approximation of PR #1838 \
         (Taylor order 2, memoized, beta 2; the first pass over the points after building, \
         caches filling: *cold*; a second pass: *warm*) and Axom's exact GWN (memoized, one \
         cold pass on every k-th point, about {EXACT_POINTS}). Points: uniform random in the box grown by \
         5%, and near the curves at 1e-2..1e-10 of the diagonal (log-uniform), seed {SEED}. \
         Microseconds per point, medians of {rounds} rounds (each the median of {reps} runs), \
         the runs of inrs and Axom alternating; setup in ms (inrs: `WindingField::new` + \
         `FastWindingField::new`; Axom: subdivision, BVH, moments, caches). Ratio: Axom cold \
         / inrs, the median of the rounds' ratios (in parentheses: Axom's fastest cold pass \
         over inrs's fastest run). Agreement: max \\|w_inrs - w_axom\\| over the points farther than \
         {NEAR_FRACTION:e} of the diagonal from the curves (how many), and the number of points \
         anywhere differing by more than 0.01.\n",
        driver.display()
    );
    let _ = writeln!(
        md,
        "| shape | set | points | inrs | Axom order 2 cold | Axom order 2 warm | Axom exact | \
         ratio (best) | goal | setup ms inrs / Axom | max \\|dw\\| order 2 (points) | max \\|dw\\| exact | \
         \\|dw\\| > 0.01 order 2 / exact |"
    );
    let _ = writeln!(
        md,
        "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: |"
    );
    for (name, _) in SHAPES {
        let d = load_shape(root, name)?;
        let curves = dir.join(format!("{name}.curves"));
        write_curves(&curves, &d).map_err(|e| format!("{}: {e}", curves.display()))?;
        let large = LARGE.contains(&name);
        let mut sets = vec![("random", random_points(&d, n, SEED))];
        if large {
            sets.insert(0, ("near", near_points(&d, n, SEED)));
        }
        let diagonal = d.bounding_box().diagonal();
        let flattening = 0.1 * NEAR_FRACTION * diagonal;
        let near = NearBoundary::new(
            &DensePolygon::open_curves(&d, flattening),
            NEAR_FRACTION * diagonal,
        );
        for (set, pts) in sets {
            let run = Run {
                driver: &driver,
                curves: &curves,
                dir: &dir,
                stem: format!("{name}-{set}"),
            };
            let row = measure(&run, &d, &pts, &near, rounds, reps)?;
            let goal = if large { 10.0 } else { 5.0 };
            let ratio = row.ratio;
            let us = |t: f64, n: usize| t / n as f64 * 1e6;
            let _ = writeln!(
                md,
                "| {name} | {set} | {} | {:.3} | {:.3} | {:.3} | {:.2} | {ratio:.1} ({:.1}) | >= {goal}x: \
                 {} | {:.2} / {:.2} | {:.1e} ({}) | {:.1e} | {} / {} |",
                pts.len(),
                us(row.inrs_query, pts.len()),
                us(row.axom.cold, pts.len()),
                us(row.axom.warm, pts.len()),
                us(row.exact.cold, row.exact_points),
                row.ratio_best,
                if ratio >= goal { "met" } else { "not met" },
                row.inrs_setup * 1e3,
                row.axom.setup * 1e3,
                row.agreement.max_fast,
                row.agreement.compared,
                row.agreement.max_exact,
                row.agreement.far_off_fast,
                row.agreement.far_off_exact,
            );
        }
    }
    Ok(())
}

/// Where one set's files go and which driver reads them.
struct Run<'a> {
    driver: &'a Path,
    curves: &'a Path,
    dir: &'a Path,
    stem: String,
}

/// One row's measurements (seconds for all the points).
struct Row {
    inrs_query: f64,
    /// The median over the rounds of Axom's cold pass over inrs's query.
    ratio: f64,
    /// The fastest cold pass of Axom over the fastest query of inrs.
    ratio_best: f64,
    inrs_setup: f64,
    axom: AxomTimes,
    exact: AxomTimes,
    exact_points: usize,
    agreement: Agreement,
}

/// How far Axom's values are from inrs's.
struct Agreement {
    /// Points compared (those not near the curves).
    compared: usize,
    max_fast: f64,
    /// Over the compared points among those the exact method ran on.
    max_exact: f64,
    /// Points anywhere whose values differ by more than 0.01.
    far_off_fast: usize,
    far_off_exact: usize,
}

fn measure(
    run: &Run,
    d: &Domain,
    pts: &[Point],
    near: &NearBoundary,
    rounds: usize,
    reps: usize,
) -> Result<Row, String> {
    let points = run.dir.join(format!("{}.points", run.stem));
    write_points(&points, pts).map_err(|e| format!("{}: {e}", points.display()))?;
    let stride = pts.len().div_ceil(EXACT_POINTS).max(1);
    let sparse: Vec<Point> = pts.iter().step_by(stride).copied().collect();
    let sparse_file = run.dir.join(format!("{}-exact.points", run.stem));
    write_points(&sparse_file, &sparse).map_err(|e| format!("{}: {e}", sparse_file.display()))?;

    let build = || WindingField::new(d, DEFAULT_RELATIVE_TOLERANCE).map_err(|e| e.to_string());
    let field = build()?;
    let fast = FastWindingField::new(&field);
    let w_inrs = fast.winding_numbers(pts);
    // Beside the driver's values, for a look at the points where they differ.
    let inrs_file = run.dir.join(format!("{}-inrs.out", run.stem));
    write_values(&inrs_file, &w_inrs).map_err(|e| format!("{}: {e}", inrs_file.display()))?;
    let inrs_setup = median_time(reps, || {
        if let Ok(f) = build() {
            std::hint::black_box(FastWindingField::new(&f));
        }
    });
    let (mut inrs, mut axom): (Vec<Times>, Vec<AxomTimes>) = (Vec::new(), Vec::new());
    let mut w_fast = Vec::new();
    for _ in 0..rounds {
        let (t, w) = run_driver(run, "fast", &points, pts.len(), reps)?;
        axom.push(t);
        w_fast = w;
        let mut query = || {
            std::hint::black_box(fast.winding_numbers(pts));
        };
        inrs.push(interleaved_times(reps, &mut [&mut query])[0]);
    }
    // Each round's ratio is of runs close in time, so it holds better than the ratio of the
    // medians on a machine whose load changes.
    let ratio = median(
        inrs.iter()
            .zip(&axom)
            .map(|(i, a)| a.cold / i.median)
            .collect(),
    );
    let best = |v: &mut dyn Iterator<Item = f64>| v.fold(f64::INFINITY, f64::min);
    let ratio_best =
        best(&mut axom.iter().map(|a| a.cold_best)) / best(&mut inrs.iter().map(|t| t.best));
    let (exact, w_exact) = run_driver(run, "direct", &sparse_file, sparse.len(), 1)?;

    let compared: Vec<bool> = pts.iter().map(|&p| !near.is_near(p)).collect();
    let max_over = |pairs: &mut dyn Iterator<Item = (f64, f64)>| {
        pairs.map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
    };
    let agreement = Agreement {
        compared: compared.iter().filter(|&&c| c).count(),
        max_fast: max_over(
            &mut w_inrs
                .iter()
                .zip(&w_fast)
                .zip(&compared)
                .filter(|(_, c)| **c)
                .map(|((a, b), _)| (*a, *b)),
        ),
        max_exact: max_over(
            &mut w_inrs
                .iter()
                .step_by(stride)
                .zip(&w_exact)
                .zip(compared.iter().step_by(stride))
                .filter(|(_, c)| **c)
                .map(|((a, b), _)| (*a, *b)),
        ),
        far_off_fast: count_off(&w_inrs, &w_fast),
        far_off_exact: count_off(
            &w_inrs.iter().step_by(stride).copied().collect::<Vec<_>>(),
            &w_exact,
        ),
    };
    Ok(Row {
        inrs_query: median(inrs.iter().map(|t| t.median).collect()),
        ratio,
        ratio_best,
        inrs_setup,
        axom: AxomTimes {
            setup: median(axom.iter().map(|t: &AxomTimes| t.setup).collect()),
            cold: median(axom.iter().map(|t| t.cold).collect()),
            warm: median(axom.iter().map(|t| t.warm).collect()),
            cold_best: best(&mut axom.iter().map(|t| t.cold_best)),
        },
        exact,
        exact_points: sparse.len(),
        agreement,
    })
}

/// Points whose two values differ by more than 0.01.
fn count_off(a: &[f64], b: &[f64]) -> usize {
    a.iter()
        .zip(b)
        .filter(|(x, y)| {
            let diff = (*x - *y).abs();
            diff.is_nan() || diff > 0.01
        })
        .count()
}

/// Runs the driver on `points` (`n` of them): its times and the winding numbers it wrote.
fn run_driver(
    run: &Run,
    method: &str,
    points: &Path,
    n: usize,
    reps: usize,
) -> Result<(AxomTimes, Vec<f64>), String> {
    let out_file = run.dir.join(format!("{}-{method}.out", run.stem));
    let out = Command::new(run.driver)
        .arg(method)
        .arg(run.curves)
        .arg(points)
        .arg(&out_file)
        .arg(reps.to_string())
        .output()
        .map_err(|e| format!("{}: {e}", run.driver.display()))?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    if !out.status.success() {
        return Err(format!(
            "{} {method} failed: {}",
            run.driver.display(),
            String::from_utf8_lossy(&out.stderr).trim()
        ));
    }
    let field = |key: &str| {
        json_number(&stdout, key)
            .ok_or_else(|| format!("driver output lacks {key:?}: {}", stdout.trim()))
    };
    let times = AxomTimes {
        setup: field("setup_s")?,
        cold: field("cold_s")?,
        warm: field("warm_s")?,
        cold_best: field("cold_min_s")?,
    };
    let bytes = std::fs::read(&out_file).map_err(|e| format!("{}: {e}", out_file.display()))?;
    if bytes.len() != 8 * n {
        return Err(format!(
            "{}: {} bytes, expected {} winding numbers",
            out_file.display(),
            bytes.len(),
            n
        ));
    }
    let values = bytes
        .chunks_exact(8)
        .map(|c| {
            let mut b = [0u8; 8];
            b.copy_from_slice(c);
            f64::from_le_bytes(b)
        })
        .collect();
    Ok((times, values))
}

/// The number after `"key":` in a one-line JSON object of numbers and strings.
fn json_number(line: &str, key: &str) -> Option<f64> {
    let start = line.find(&format!("\"{key}\":"))? + key.len() + 3;
    let rest = &line[start..];
    let end = rest.find([',', '}']).unwrap_or(rest.len());
    rest[..end].trim().parse().ok()
}

/// Values as little-endian `f64`, the driver's output format.
fn write_values(path: &Path, values: &[f64]) -> std::io::Result<()> {
    std::fs::write(
        path,
        values
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect::<Vec<u8>>(),
    )
}

/// The shape's polynomial pieces, one a line: degree, control points `x y`, weights (`f64`'s
/// shortest round-trip decimal form, so the driver reads the same numbers).
fn write_curves(path: &Path, d: &Domain) -> std::io::Result<()> {
    std::fs::write(path, curves_text(d))
}

/// [`write_curves`]'s text.
fn curves_text(d: &Domain) -> String {
    let mut text = String::new();
    for (_, b) in d.bezier_pieces() {
        let _ = write!(text, "{}", b.degree());
        for p in b.control_points() {
            let _ = write!(text, " {} {}", p.x, p.y);
        }
        for w in b.weights() {
            let _ = write!(text, " {w}");
        }
        text.push('\n');
    }
    text
}

#[cfg(test)]
mod tests {
    use super::{curves_text, json_number};
    use inrs::{Domain, Point};

    /// The driver reads back every piece's degree, control points and weights bit for bit
    /// (a circle: rational pieces, weights other than 1).
    #[test]
    fn curves_text_round_trips_every_piece() {
        let circle = inrs::spline::circle(Point::new(0.1, -0.3), 1.0 / 3.0).expect("a circle");
        let d = Domain::new(vec![circle]).expect("a domain");
        let pieces = d.bezier_pieces();
        let text = curves_text(&d);
        assert_eq!(text.lines().count(), pieces.len());
        for ((_, b), line) in pieces.iter().zip(text.lines()) {
            let v: Vec<f64> = line
                .split(' ')
                .map(|x| x.parse().expect("a number"))
                .collect();
            let n = b.degree() + 1;
            assert_eq!(v.len(), 1 + 3 * n);
            assert_eq!(v[0], b.degree() as f64);
            for (i, p) in b.control_points().iter().enumerate() {
                assert_eq!((v[1 + 2 * i], v[2 + 2 * i]), (p.x, p.y));
            }
            assert_eq!(&v[1 + 2 * n..], b.weights());
        }
        assert!(
            pieces
                .iter()
                .any(|(_, b)| b.weights().iter().any(|&w| w != 1.0))
        );
    }

    #[test]
    fn json_numbers_are_read_by_key() {
        let line = r#"{"method":"fast","setup_s":1.5e-3,"cold_s":0.25,"warm_s":2}"#;
        assert_eq!(json_number(line, "setup_s"), Some(1.5e-3));
        assert_eq!(json_number(line, "cold_s"), Some(0.25));
        assert_eq!(json_number(line, "warm_s"), Some(2.0));
        assert_eq!(json_number(line, "method"), None);
        assert_eq!(json_number(line, "absent"), None);
    }
}
