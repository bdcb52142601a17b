//! The fractions rows of the speed table (issue 52): whole-grid fractions in process through
//! the Python package against `NumPy` writing an array of the same shape and against
//! exactextract; `inrs fractions` as a whole process against exactextract in process.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use inrs::contain::even_odd_area;
use inrs::{BoundingBox, Domain, Point};

use super::coverage::{exactextract, flattened_geojson, peer_python};
use super::{BenchOptions, median};

/// The in-process script (`Domain.cell_fractions` beside `numpy.ones`).
const SCRIPT: &str = "xtask/scripts/inrs_fractions_in_process.py";

/// The grid box of every row: the unit disc's box grown by 2%.
const HALF_WIDTH: f64 = 1.02;

/// The Python whose `inrs` is timed: `INRS_BENCH_PYTHON`, else the CI venv's.
fn inrs_python(root: &Path) -> PathBuf {
    std::env::var_os("INRS_BENCH_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target/ci-venv/bin/python"))
}

/// The standard output of `python script args` (the script under `root`), or `Err`: `row`
/// was not run, with the command and the last line of its standard error.
fn script_output(
    python: &Path,
    root: &Path,
    script: &str,
    args: &[String],
    row: &str,
) -> Result<String, String> {
    let out = Command::new(python)
        .arg(root.join(script))
        .args(args)
        .output()
        .map_err(|e| format!("{}: {e}", python.display()))?;
    if !out.status.success() {
        return Err(format!(
            "{row} was not run: {} {script}: {} (INRS_BENCH_PYTHON names the Python whose inrs is timed)",
            python.display(),
            String::from_utf8_lossy(&out.stderr)
                .lines()
                .last()
                .unwrap_or("failed")
        ));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// `(cell_fractions, ones)` median seconds from the script, or a one-line reason.
fn in_process(python: &Path, root: &Path, n: usize, reps: usize) -> Result<(f64, f64), String> {
    let args = [n, reps].map(|v| v.to_string());
    let text = script_output(python, root, SCRIPT, &args, "the Python row")?;
    let bad = || format!("{SCRIPT} printed {text:?}");
    match text.split_whitespace().collect::<Vec<_>>().as_slice() {
        ["cell_fractions", ours, "ones", ones, "sum", _] => Ok((
            ours.parse().map_err(|_| bad())?,
            ones.parse().map_err(|_| bad())?,
        )),
        _ => Err(bad()),
    }
}

/// The many-faces script (first classify of a CAD face against the warm one).
const FACES_SCRIPT: &str = "python/benchmarks/bench_first_classify.py";

/// `(first us/face, warm us/face, faces)` from the many-faces script, or a one-line reason.
fn first_classify(python: &Path, root: &Path, rounds: usize) -> Result<(f64, f64, usize), String> {
    let args = ["--rounds".to_string(), rounds.to_string()];
    let text = script_output(python, root, FACES_SCRIPT, &args, "the many-faces row")?;
    // The number after `after` on `line`.
    let number = |line: &str, after: &str| -> Option<f64> {
        line.split(after)
            .nth(1)?
            .split_whitespace()
            .next()?
            .parse()
            .ok()
    };
    // "32 files, 3119 faces, ...": the second field's number.
    let faces = text.lines().next().and_then(|l| {
        l.split(", ")
            .nth(1)?
            .split_whitespace()
            .next()?
            .parse()
            .ok()
    });
    let times = text
        .lines()
        .find(|l| l.starts_with("first classify:"))
        .and_then(|l| Some((number(l, "first classify:")?, number(l, "warm:")?)));
    match (times, faces) {
        (Some((first, warm)), Some(faces)) => Ok((first, warm, faces)),
        _ => Err(format!("{FACES_SCRIPT} printed {text:?}")),
    }
}

/// Median wall seconds of `inrs fractions` on the disc's `n x n` grid, each run writing a new
/// file (the previous one removed outside the timing).
fn cli_fractions(bin: &Path, dir: &Path, n: usize, reps: usize) -> Result<f64, String> {
    let domain = dir.join("disc.json");
    std::fs::write(
        &domain,
        r#"{"curves": [{"circle": {"center": [0, 0], "radius": 1}}]}"#,
    )
    .map_err(|e| format!("{}: {e}", domain.display()))?;
    let out = dir.join("fractions.npy");
    let grid = format!("-{HALF_WIDTH},{HALF_WIDTH},{n},-{HALF_WIDTH},{HALF_WIDTH},{n}");
    let mut times = Vec::new();
    for _ in 0..reps.max(1) {
        let _ = std::fs::remove_file(&out);
        let start = Instant::now();
        let status = Command::new(bin)
            .args(["fractions", "--domain"])
            .arg(&domain)
            .args(["--grid", &grid, "--output"])
            .arg(&out)
            .status()
            .map_err(|e| format!("{}: {e}", bin.display()))?;
        times.push(start.elapsed().as_secs_f64());
        if !status.success() {
            return Err("inrs fractions failed".into());
        }
    }
    let _ = std::fs::remove_file(&out);
    Ok(median(times))
}

/// The section's table.
pub(super) fn section(md: &mut String, root: &Path, o: &BenchOptions) -> Result<(), String> {
    let reps = if o.quick { 3 } else { 11 };
    let (n_in, n_cli) = if o.quick { (512, 256) } else { (4096, 2048) };
    let disc = Domain::new(vec![
        inrs::spline::circle(Point::new(0.0, 0.0), 1.0).map_err(|e| e.to_string())?,
    ])
    .map_err(|e| e.to_string())?;
    let area = even_odd_area(&disc).map_err(|e| e.to_string())?;
    let b = BoundingBox {
        min: Point::new(-HALF_WIDTH, -HALF_WIDTH),
        max: Point::new(HALF_WIDTH, HALF_WIDTH),
    };
    let dir = root.join("target/bench-speed");
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let geojson = dir.join("disc.geojson");
    std::fs::write(&geojson, flattened_geojson(&disc)?)
        .map_err(|e| format!("{}: {e}", geojson.display()))?;
    let mut notes = Vec::new();
    let peer = |n: usize, reps: usize| match peer_python(root) {
        Ok((py, _)) => exactextract(&py, root, &geojson, &b, n, reps, area).map(|(t, _)| t),
        Err(e) => Err(e),
    };
    let python = inrs_python(root);
    let ours_in = in_process(&python, root, n_in, reps);
    let peer_in = peer(n_in, if o.quick { 3 } else { 1 });
    let bin = super::cli::release_binary(root)?;
    let ours_cli = cli_fractions(&bin, &dir, n_cli, reps)?;
    let peer_cli = peer(n_cli, 3);
    let faces = first_classify(&python, root, if o.quick { 1 } else { 5 });
    let _ = writeln!(
        md,
        "\nFractions at memory speed (issue 52): the unit disc on square grids over \
         [-{HALF_WIDTH}, {HALF_WIDTH}]^2. *In process*: `Domain.cell_fractions` (the Python \
         package of `{}`, all {} threads) against `numpy.ones` of the same shape (the array \
         write) and exactextract (one thread, in process: the boundary flattened within 1e-10, \
         per-cell coverage scattered into a dense array). *Whole process*: `inrs fractions` \
         writing `F.npy` (a new file each run) against exactextract in process. Medians of \
         {reps} runs (exactextract at 4096^2: one). *Many CAD faces*: every face of the FreeCAD \
         IDF parts, 400 random points in its (u, v) box, a fresh domain's first `classify` \
         against a second call on the warm domain (`{FACES_SCRIPT}`, medians of rounds).\n",
        python.display(),
        rayon::current_num_threads(),
    );
    let _ = writeln!(md, "| row | ours s | against | their s | ratio | goal |");
    let _ = writeln!(md, "| --- | ---: | --- | ---: | ---: | --- |");
    let mut row = |what: &str,
                   ours: &Result<f64, String>,
                   against: &str,
                   theirs: &Result<f64, String>,
                   ratio: fn(f64, f64) -> f64,
                   goal: &str| {
        for r in [ours, theirs] {
            if let Err(e) = r
                && !notes.contains(e)
            {
                notes.push(e.clone());
            }
        }
        let s = |r: &Result<f64, String>| r.as_ref().map_or("-".to_string(), |t| format!("{t:.4}"));
        let q = match (ours, theirs) {
            (Ok(a), Ok(b)) => format!("{:.1}x", ratio(*a, *b)),
            _ => "-".into(),
        };
        let _ = writeln!(
            md,
            "| {what} | {} | {against} | {} | {q} | {goal} |",
            s(ours),
            s(theirs)
        );
    };
    let in_ours = ours_in.as_ref().map(|t| t.0).map_err(Clone::clone);
    let in_ones = ours_in.as_ref().map(|t| t.1).map_err(Clone::clone);
    let slower = |ours: f64, theirs: f64| ours / theirs;
    let faster = |ours: f64, theirs: f64| theirs / ours;
    row(
        &format!("in process {n_in}^2"),
        &in_ours,
        "numpy.ones",
        &in_ones,
        slower,
        "<= 2x the array write",
    );
    row(
        &format!("in process {n_in}^2"),
        &in_ours,
        "exactextract",
        &peer_in,
        faster,
        ">= 20x faster",
    );
    row(
        &format!("`inrs fractions` {n_cli}^2"),
        &Ok(ours_cli),
        "exactextract",
        &peer_cli,
        faster,
        ">= 20x faster",
    );
    match faces {
        Ok((first, warm, n)) => {
            let _ = writeln!(
                md,
                "| many CAD faces ({n}, 400 points each, Python): first classify us/face | {first:.1} | warm classify us/face | {warm:.1} | {:.2} | <= 2.5 |",
                first / warm
            );
        }
        Err(e) => notes.push(e),
    }
    for n in notes {
        let _ = writeln!(md, "\n{n}");
    }
    Ok(())
}
