//! `cargo xtask bench`: the papers' comparisons, measured in one process (medians of repeated
//! runs), printed and written as Markdown and CSV under `target/bench-report/`.

mod axom;
mod build;
mod cli;
mod coverage;
mod cubature;
mod cut_cells;
mod green_reference;
mod gwn;
mod locator;
mod paper;
mod peers;
mod plots;
mod point_sets;
mod properties;
mod solid;
mod speed;
mod winding_near;

use std::path::{Path, PathBuf};
use std::time::Instant;

use inrs::{Domain, Location};
use rs_testkit::{INRS_FIXTURES, PAPER_DOMAINS};

/// Options of a run.
pub(crate) struct BenchOptions {
    pub(crate) domains: Vec<String>,
    pub(crate) sizes: Vec<usize>,
    pub(crate) reps: usize,
    pub(crate) sweep: bool,
    pub(crate) quick: bool,
    /// Time inRS1 and the reference GWN at every size (they stop at 10^5 otherwise).
    pub(crate) full: bool,
    /// The sections to run (all when empty).
    pub(crate) only: Vec<String>,
    /// Points per solid of the `solid` section (default 20000, 2000 with `--quick`).
    pub(crate) solid_points: Option<usize>,
}

/// The report's sections, in order.
const SECTIONS: &[&str] = &[
    "paper",
    "locator",
    "gwn",
    "shapes",
    "axom",
    "build",
    "cli",
    "coverage",
    "cut_cells",
    "cubature",
    "properties",
    "solid",
    "speed",
    "winding_near",
];

fn names(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

impl BenchOptions {
    pub(crate) fn parse(args: &[String]) -> Result<Self, String> {
        let mut o = Self {
            domains: names(&INRS_FIXTURES),
            sizes: vec![1_000, 10_000, 100_000, 1_000_000],
            reps: 11,
            sweep: false,
            quick: false,
            full: false,
            only: Vec::new(),
            solid_points: None,
        };
        let mut it = args.iter();
        while let Some(a) = it.next() {
            let mut value = || it.next().ok_or_else(|| format!("{a} needs a value"));
            match a.as_str() {
                "--quick" => {
                    o.sizes = vec![1_000, 10_000];
                    o.reps = 3;
                    o.quick = true;
                }
                "--domains" => {
                    o.domains = match value()?.as_str() {
                        "all" => names(&INRS_FIXTURES),
                        "paper" => names(&PAPER_DOMAINS),
                        v => v.split(',').map(str::to_string).collect(),
                    }
                }
                "--sizes" => {
                    o.sizes = value()?
                        .split(',')
                        .map(|s| s.parse().map_err(|_| format!("bad size {s:?}")))
                        .collect::<Result<_, _>>()?
                }
                "--reps" => o.reps = value()?.parse().map_err(|_| "bad --reps".to_string())?,
                "--solid-points" => {
                    o.solid_points = Some(
                        value()?
                            .parse()
                            .ok()
                            .filter(|&n| n > 0)
                            .ok_or("bad --solid-points")?,
                    )
                }
                "--sweep" => o.sweep = true,
                "--full" => o.full = true,
                "--only" => {
                    o.only = value()?.split(',').map(str::to_string).collect();
                    if let Some(bad) = o.only.iter().find(|s| !SECTIONS.contains(&s.as_str())) {
                        return Err(format!("unknown section {bad:?} (one of {SECTIONS:?})"));
                    }
                }
                other => return Err(format!("unknown bench option {other:?}")),
            }
        }
        if o.reps == 0 || o.sizes.is_empty() || o.domains.is_empty() {
            return Err("need at least one repetition, size and domain".into());
        }
        Ok(o)
    }

    /// Whether section `name` runs.
    fn runs(&self, name: &str) -> bool {
        self.only.is_empty() || self.only.iter().any(|s| s == name)
    }

    /// The largest number of points asked for.
    fn largest_size(&self) -> usize {
        self.sizes.iter().copied().max().unwrap_or(1_000_000)
    }
}

/// Median wall time in seconds of `reps` runs of `f`, after a warm-up: a first run that takes
/// under [`SLOW_RUN`] is followed by untimed runs for [`WARM_UP`] (on a virtual machine the first
/// parallel runs after a quiet spell wait for the idle cores to wake: 2-3x slower for the first
/// few runs of a 2 ms task), a slower first run counts as one of the `reps`.
fn median_time(reps: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = warm_up(&mut f).into_iter().collect();
    while t.len() < reps.max(1) {
        t.push(timed(&mut f));
    }
    median(t)
}

/// The median and the fastest seconds of each of `runs`, timed in rounds (one run of each per
/// round, `reps` rounds, after each has warmed up as in [`median_time`]): a noisy spell on the
/// machine then slows every one of them alike, so the ratios between them hold better than
/// between runs timed one after the other. The fastest run is what the code does when the
/// machine lends it its cores undisturbed (a virtual machine's neighbours only ever slow a
/// run down).
fn interleaved_times(reps: usize, runs: &mut [&mut dyn FnMut()]) -> Vec<Times> {
    for f in runs.iter_mut() {
        warm_up(&mut **f);
    }
    let mut t = vec![Vec::with_capacity(reps.max(1)); runs.len()];
    for _ in 0..reps.max(1) {
        for (f, t) in runs.iter_mut().zip(t.iter_mut()) {
            t.push(timed(&mut **f));
        }
    }
    t.into_iter()
        .map(|t| Times {
            best: t.iter().copied().fold(f64::INFINITY, f64::min),
            median: median(t),
        })
        .collect()
}

/// The median and the fastest of some timed runs, in seconds.
#[derive(Clone, Copy, Debug)]
struct Times {
    median: f64,
    best: f64,
}

/// Seconds one run of `f` takes.
fn timed(f: &mut dyn FnMut()) -> f64 {
    let start = Instant::now();
    f();
    start.elapsed().as_secs_f64()
}

/// Runs `f` once, timed; if that took under [`SLOW_RUN`], runs it untimed for [`WARM_UP`] and
/// returns `None`, else returns the time (a slow run needs no warm-up and may count).
fn warm_up(f: &mut dyn FnMut()) -> Option<f64> {
    let first = timed(f);
    if first >= SLOW_RUN {
        return Some(first);
    }
    let warm = Instant::now();
    while warm.elapsed().as_secs_f64() < WARM_UP {
        f();
    }
    None
}

/// The median of some times (the upper one of an even count).
fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// A run at least this long (seconds) needs no warm-up.
const SLOW_RUN: f64 = 0.1;
/// Seconds of untimed runs before timing faster ones.
const WARM_UP: f64 = 0.05;

fn count_inside(v: &[Location]) -> usize {
    v.iter().filter(|&&l| l == Location::Inside).count()
}

/// A domain file under `fixtures/`.
fn load(root: &Path, relative: &str) -> Result<Domain, String> {
    let path = root.join("fixtures").join(relative);
    inrs::io::json::domain_from_json_file(&path).map_err(|e| format!("{}: {e}", path.display()))
}

pub(crate) fn run(root: &Path, o: &BenchOptions) -> Result<(), String> {
    let domains = o
        .domains
        .iter()
        .map(|name| {
            Ok((
                name.clone(),
                load(root, &format!("inrs-paper/{name}.json"))?,
            ))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let names: Vec<&str> = domains.iter().map(|(n, _)| n.as_str()).collect();
    let mut md = String::new();
    let mut csv = String::new();
    // The report is rewritten after every section, so that a run stopped part way keeps what
    // it measured.
    let dir = root.join("target/bench-report");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    if o.runs("paper") {
        let timings = paper::measure(&domains, o)?;
        timings.tables(&mut md, &names, &o.sizes);
        csv = timings.csv();
        let mut plots = Vec::new();
        for name in &names {
            if let Some(fig) = plots::times_figure(&timings, name) {
                plots.push(plots::save(&dir, &format!("times_{name}.svg"), &fig)?);
            }
        }
        if let Some(fig) = plots::paper_speedups_figure(&timings, &names, o.largest_size()) {
            plots.push(plots::save(&dir, "speedups_paper.svg", &fig)?);
        }
        list_plots(&mut md, &plots);
        write_report(root, o, &md, &csv, false)?;
    }
    let flower = load(root, "synthetic/flower500.json")?;
    if o.runs("locator") {
        locator::single_thread(&mut md, &domains, o)?;
        locator::at_scale(&mut md, &flower, o)?;
        if o.sweep {
            locator::refinement_sweep(&mut md, &domains, o)?;
            locator::grid_sweep(&mut md, &domains, o)?;
        }
        write_report(root, o, &md, &csv, false)?;
    }
    if o.runs("gwn") {
        gwn::flower(&mut md, &flower, o)?;
        gwn::paper_figures(&mut md, &load(root, "inrs-paper/leaf_cubic.json")?, o)?;
        write_report(root, o, &md, &csv, false)?;
    }
    if o.runs("shapes") {
        let ratios = peers::shapes(&mut md, root, o)?;
        if let Some(fig) = plots::shapes_speedups_figure(&ratios) {
            list_plots(&mut md, &[plots::save(&dir, "speedups_shapes.svg", &fig)?]);
        }
        write_report(root, o, &md, &csv, false)?;
    }
    if o.runs("axom") {
        axom::section(&mut md, root, o)?;
        write_report(root, o, &md, &csv, false)?;
    }
    if o.runs("build") {
        build::section(&mut md, root, o)?;
        write_report(root, o, &md, &csv, false)?;
    }
    if o.runs("cli") {
        cli::end_to_end(&mut md, root, o)?;
        write_report(root, o, &md, &csv, false)?;
    }
    if o.runs("coverage") {
        coverage::section(&mut md, root, o)?;
        write_report(root, o, &md, &csv, false)?;
    }
    if o.runs("cut_cells") {
        cut_cells::section(&mut md, root, o)?;
        write_report(root, o, &md, &csv, false)?;
    }
    if o.runs("cubature") {
        let paper = PAPER_DOMAINS
            .iter()
            .map(|name| {
                Ok((
                    name.to_string(),
                    load(root, &format!("inrs-paper/{name}.json"))?,
                ))
            })
            .collect::<Result<Vec<_>, String>>()?;
        cubature::section(&mut md, &paper, o)?;
        write_report(root, o, &md, &csv, false)?;
    }
    if o.runs("properties") {
        properties::section(&mut md, root, o)?;
        write_report(root, o, &md, &csv, false)?;
    }
    if o.runs("solid") {
        solid::section(&mut md, root, o)?;
        write_report(root, o, &md, &csv, false)?;
    }
    if o.runs("winding_near") {
        winding_near::section(&mut md, root, o)?;
    }
    if o.runs("speed") {
        speed::section(&mut md, root, o)?;
    }
    write_report(root, o, &md, &csv, true)
}

/// Shows the plots written beside the report (Markdown images with relative links).
fn list_plots(md: &mut String, plots: &[std::path::PathBuf]) {
    use std::fmt::Write as _;
    for name in plots
        .iter()
        .filter_map(|p| p.file_name().and_then(|n| n.to_str()))
    {
        let stem = name.trim_end_matches(".svg").replace('_', " ");
        let _ = writeln!(md, "\n![{stem}]({name})");
    }
    if !plots.is_empty() {
        md.push('\n');
    }
}

/// Prints the report and writes it with the CSV under `target/bench-report/`.
fn write_report(
    root: &Path,
    o: &BenchOptions,
    md: &str,
    csv: &str,
    last: bool,
) -> Result<(), String> {
    let report = format!(
        "Machine: {}\n\nMedian of {} runs, single thread unless stated.\n\n{md}",
        machine_line(),
        o.reps
    );
    if last {
        println!("{report}");
    }
    let dir = root.join("target/bench-report");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("bench.md"), &report).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("bench.csv"), csv).map_err(|e| e.to_string())?;
    if last {
        println!("written: target/bench-report/bench.md, target/bench-report/bench.csv");
    }
    Ok(())
}

fn machine_line() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    format!("{cpu}, {cores} cores")
}

/// `FreeCAD`'s Idf library (Debian's freecad-common): real STEP and IGES parts.
pub(super) const IDF: &str = "/usr/share/freecad/Mod/Idf/Idflibs";

/// The Idf parts (`.stp`, `.igs`), sorted, the first 4 with `quick`; `None` when the library
/// is not installed.
pub(super) fn idf_parts(quick: bool) -> Option<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(IDF)
        .ok()?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| {
            let name = p.to_string_lossy().to_ascii_lowercase();
            name.ends_with(".stp") || name.ends_with(".igs")
        })
        .collect();
    files.sort();
    if quick {
        files.truncate(4);
    }
    Some(files)
}

/// The Python that runs `OpenCASCADE`: the CI's virtual environment when it exists, else
/// `python3`.
pub(super) fn occ_python(root: &Path) -> PathBuf {
    let python = root.join("target/ci-venv/bin/python");
    if python.is_file() {
        python
    } else {
        PathBuf::from("python3")
    }
}

/// Runs the script `script` (relative to the workspace root) with `python` and `args`: its
/// standard output, or the last line of its standard error when it fails.
pub(super) fn run_script(
    python: &Path,
    root: &Path,
    script: &str,
    args: &[&std::ffi::OsStr],
) -> Result<String, String> {
    let out = std::process::Command::new(python)
        .arg(root.join(script))
        .args(args)
        .output()
        .map_err(|e| format!("{}: {e}", python.display()))?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        return Err(err.lines().last().unwrap_or("failed").to_string());
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}
