//! `cargo xtask bench`: timings of the classifiers on the paper domains, as tables of medians
//! and ratios measured in one process.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use inrs::contain::{FastWindingField, LocatorOptions, PointLocator, WindingField, halton_points};
use inrs::{Classifier, ContainOptions, Domain, Location, Method};

/// Options of a run.
pub(crate) struct BenchOptions {
    pub(crate) domains: Vec<String>,
    pub(crate) sizes: Vec<usize>,
    pub(crate) reps: usize,
    pub(crate) sweep: bool,
}

impl BenchOptions {
    pub(crate) fn parse(args: &[String]) -> Result<Self, String> {
        let mut o = Self {
            domains: vec![
                "s3_m_shape".into(),
                "s4_disk_ellipse_segment".into(),
                "s5_lune".into(),
            ],
            sizes: vec![1_000, 10_000, 100_000],
            reps: 11,
            sweep: false,
        };
        let mut it = args.iter();
        while let Some(a) = it.next() {
            let mut value = || it.next().ok_or_else(|| format!("{a} needs a value"));
            match a.as_str() {
                "--quick" => {
                    o.sizes = vec![1_000, 10_000];
                    o.reps = 3;
                }
                "--domains" => o.domains = value()?.split(',').map(str::to_string).collect(),
                "--sizes" => {
                    o.sizes = value()?
                        .split(',')
                        .map(|s| s.parse().map_err(|_| format!("bad size {s:?}")))
                        .collect::<Result<_, _>>()?
                }
                "--reps" => o.reps = value()?.parse().map_err(|_| "bad --reps".to_string())?,
                "--sweep" => o.sweep = true,
                other => return Err(format!("unknown bench option {other:?}")),
            }
        }
        if o.reps == 0 {
            return Err("--reps must be at least 1".into());
        }
        Ok(o)
    }
}

/// Median wall time in seconds of `reps` runs of `f`.
fn median_time(reps: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..reps)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn count_inside(v: &[Location]) -> usize {
    v.iter().filter(|&&l| l == Location::Inside).count()
}

pub(crate) fn run(root: &Path, o: &BenchOptions) -> Result<(), String> {
    let mut md = String::new();
    let mut csv = String::from("domain,n,method,subdivisions,seconds,inside\n");
    let _ = writeln!(
        md,
        "| domain | N | build | inRS1 | inRS2 | GWN | inRS1 / inRS2 | GWN / inRS2 | inside |"
    );
    let _ = writeln!(
        md,
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    );
    let mut domains = Vec::new();
    for name in &o.domains {
        let path = root
            .join("fixtures/inrs-paper")
            .join(format!("{name}.json"));
        let d = Domain::from_json_file(&path).map_err(|e| e.to_string())?;
        domains.push((name.clone(), d));
    }
    for (name, d) in &domains {
        let bbox = d.bounding_box();
        for &n in &o.sizes {
            let pts = halton_points(n, bbox);
            let build = median_time(o.reps, || {
                std::hint::black_box(Classifier::new(d, ContainOptions::default()).ok());
            });
            let c = Classifier::new(d, ContainOptions::default()).map_err(|e| e.to_string())?;
            let mut inside = 0;
            let t2 = median_time(o.reps, || {
                inside = count_inside(&c.classify(&pts, Method::InRS2))
            });
            let t1 = if n <= 10_000 {
                let mut inside1 = 0;
                let t = median_time(o.reps, || {
                    inside1 = count_inside(&c.classify(&pts, Method::InRS1))
                });
                if inside1 != inside {
                    return Err(format!("{name} N={n}: inRS1 {inside1} != inRS2 {inside}"));
                }
                Some(t)
            } else {
                None
            };
            let mut inside_gwn = 0;
            let tg = median_time(o.reps, || {
                inside_gwn = count_inside(&c.classify(&pts, Method::Gwn))
            });
            if inside_gwn != inside {
                return Err(format!("{name} N={n}: GWN {inside_gwn} != inRS2 {inside}"));
            }
            let _ = writeln!(csv, "{name},{n},gwn,default,{tg},{inside}");
            let _ = writeln!(
                md,
                "| {name} | {n} | {:.2e} s | {} | {:.2e} s | {:.2e} s | {} | {:.1} | {inside} |",
                build,
                t1.map_or("-".into(), |t| format!("{t:.2e} s")),
                t2,
                tg,
                t1.map_or("-".into(), |t| format!("{:.1}", t / t2)),
                tg / t2,
            );
            if let Some(t) = t1 {
                let _ = writeln!(csv, "{name},{n},inrs1,default,{t},{inside}");
            }
            let _ = writeln!(csv, "{name},{n},inrs2,default,{t2},{inside}");
        }
    }
    let _ = writeln!(
        md,
        "\nFast paths: grid point locator (`PointLocator`, {} cells per side): index build, classification on one thread and on all threads; throughput in million points per second; ratios to inRS2 in the same run.\n",
        inrs::contain::DEFAULT_GRID_CELLS
    );
    let _ = writeln!(
        md,
        "| domain | N | inRS2 | locator build | locator 1 thread | Mpts/s | vs inRS2 | locator parallel | Mpts/s |"
    );
    let _ = writeln!(
        md,
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    );
    for (name, d) in &domains {
        let c = Classifier::new(d, ContainOptions::default()).map_err(|e| e.to_string())?;
        for &n in &o.sizes {
            let pts = halton_points(n, d.bounding_box());
            let expected = count_inside(&c.classify(&pts, Method::InRS2));
            let t2 = median_time(o.reps, || {
                std::hint::black_box(c.classify(&pts, Method::InRS2));
            });
            let tb = median_time(o.reps, || {
                std::hint::black_box(PointLocator::new(&c, LocatorOptions::default()).cells());
            });
            let loc = PointLocator::new(&c, LocatorOptions::default());
            let mut inside = 0;
            let t1 = median_time(o.reps, || inside = count_inside(&loc.classify(&pts)));
            if inside != expected {
                return Err(format!(
                    "{name} N={n}: locator {inside} != inRS2 {expected}"
                ));
            }
            let tp = median_time(o.reps, || {
                inside = count_inside(&loc.classify_parallel(&pts))
            });
            if inside != expected {
                return Err(format!(
                    "{name} N={n}: parallel locator {inside} != inRS2 {expected}"
                ));
            }
            let mpts = |t: f64| n as f64 / t / 1e6;
            let _ = writeln!(
                md,
                "| {name} | {n} | {t2:.2e} s | {tb:.2e} s | {t1:.2e} s | {:.0} | {:.1}x | {tp:.2e} s | {:.0} |",
                mpts(t1),
                t2 / t1,
                mpts(tp),
            );
            let _ = writeln!(csv, "{name},{n},locator-build,default,{tb},");
            let _ = writeln!(csv, "{name},{n},locator,default,{t1},{inside}");
            let _ = writeln!(csv, "{name},{n},locator-parallel,default,{tp},{inside}");
        }
    }
    // Generalized winding numbers on the 500-curve flower: reference versus accelerated.
    {
        let path = root.join("fixtures/synthetic/flower500.json");
        let d = Domain::from_json_file(&path).map_err(|e| e.to_string())?;
        let field =
            WindingField::new(&d, inrs::contain::DEFAULT_TOLERANCE).map_err(|e| e.to_string())?;
        let n = 100_000.min(*o.sizes.iter().max().unwrap_or(&100_000));
        let pts = halton_points(n, d.bounding_box());
        let reference_n = (n / 10).max(1);
        let t_ref = median_time(o.reps.min(3), || {
            std::hint::black_box(
                pts[..reference_n]
                    .iter()
                    .map(|&q| field.winding_number(q))
                    .sum::<f64>(),
            );
        }) * (n as f64 / reference_n as f64);
        let t_build = median_time(o.reps, || {
            std::hint::black_box(FastWindingField::new(&field).winding_number(pts[0]));
        });
        let fast = FastWindingField::new(&field);
        let t_fast = median_time(o.reps, || {
            std::hint::black_box(fast.winding_numbers(&pts));
        });
        let t_par = median_time(o.reps, || {
            std::hint::black_box(fast.winding_numbers_parallel(&pts));
        });
        let mq = |t: f64| n as f64 / t / 1e6;
        let _ = writeln!(
            md,
            "\nGeneralized winding numbers, 500-curve flower (`fixtures/synthetic/flower500.json`), {n} Halton points of its box; million queries per second.\n"
        );
        let _ = writeln!(
            md,
            "| reference (per curve) | accelerated build | accelerated 1 thread | vs reference | accelerated parallel |"
        );
        let _ = writeln!(md, "| ---: | ---: | ---: | ---: | ---: |");
        let _ = writeln!(
            md,
            "| {:.2} Mq/s | {t_build:.2e} s | {:.2} Mq/s | {:.0}x | {:.2} Mq/s |",
            mq(t_ref),
            mq(t_fast),
            t_ref / t_fast,
            mq(t_par)
        );
        let _ = writeln!(csv, "flower500,{n},gwn-reference,,{t_ref},");
        let _ = writeln!(csv, "flower500,{n},gwn-fast,,{t_fast},");
        let _ = writeln!(csv, "flower500,{n},gwn-fast-parallel,,{t_par},");
    }
    // The locator at scale: about 10^5 boxes (the flower with fine box refinement).
    {
        let path = root.join("fixtures/synthetic/flower500.json");
        let d = Domain::from_json_file(&path).map_err(|e| e.to_string())?;
        let one = Classifier::new(
            &d,
            ContainOptions {
                subdivisions: 1,
                ..Default::default()
            },
        )
        .map_err(|e| e.to_string())?;
        let k = 100_000usize.div_ceil(one.boxes().boxes().len());
        let c = Classifier::new(
            &d,
            ContainOptions {
                subdivisions: k,
                ..Default::default()
            },
        )
        .map_err(|e| e.to_string())?;
        let nboxes = c.boxes().boxes().len();
        let t_build = median_time(o.reps.min(3), || {
            std::hint::black_box(PointLocator::new(&c, LocatorOptions::default()).cells());
        });
        let loc = PointLocator::new(&c, LocatorOptions::default());
        let cells = loc.cells() * loc.cells();
        let bytes = 4 * loc.incidences() + 4 * (cells + 1) + cells + cells / 4;
        let pts = halton_points(1_000_000, d.bounding_box());
        let t_q = median_time(o.reps.min(3), || {
            std::hint::black_box(loc.classify(&pts));
        });
        let _ = writeln!(
            md,
            "\nLocator at scale: flower500 with {k} sub-boxes per monotone piece = {nboxes} boxes; build {t_build:.2e} s, {} (box, cell) incidences, index memory {:.1} MiB, 10^6 Halton points in {t_q:.2e} s on one thread ({:.0} Mpts/s), mixed cells {:.2}%.",
            loc.incidences(),
            bytes as f64 / (1024.0 * 1024.0),
            1e6 / t_q / 1e6,
            100.0 * loc.mixed_fraction()
        );
    }
    if o.sweep {
        let n = *o.sizes.iter().max().unwrap_or(&100_000);
        let ks = [1usize, 2, 4, 8, 16, 32, 64, 128];
        let _ = writeln!(
            md,
            "\nBox refinement (Remark 2.1): inRS2 time for N = {n}, by sub-boxes per monotone piece; ratio to 1 sub-box.\n"
        );
        let _ = writeln!(md, "| domain | {} |", ks.map(|k| k.to_string()).join(" | "));
        let _ = writeln!(md, "| --- |{}", " ---: |".repeat(ks.len()));
        for (name, d) in &domains {
            let pts = halton_points(n, d.bounding_box());
            let mut row = format!("| {name} |");
            let mut base = 0.0;
            for k in ks {
                let c = Classifier::new(
                    d,
                    ContainOptions {
                        subdivisions: k,
                        ..Default::default()
                    },
                )
                .map_err(|e| e.to_string())?;
                let t = median_time(o.reps, || {
                    std::hint::black_box(c.classify(&pts, Method::InRS2));
                });
                if k == 1 {
                    base = t;
                }
                let _ = write!(row, " {t:.2e} s ({:.2}) |", t / base);
                let _ = writeln!(csv, "{name},{n},inrs2,{k},{t},");
            }
            let _ = writeln!(md, "{row}");
        }
    }
    if o.sweep {
        let n = *o.sizes.iter().max().unwrap_or(&100_000);
        let grids = [128usize, 256, 512, 1024, 2048, 4096];
        let _ = writeln!(
            md,
            "\nGrid resolution: locator build + one-thread classification of N = {n} points, mixed-cell fraction.\n"
        );
        let _ = writeln!(
            md,
            "| domain | {} |",
            grids.map(|g| g.to_string()).join(" | ")
        );
        let _ = writeln!(md, "| --- |{}", " ---: |".repeat(grids.len()));
        for (name, d) in &domains {
            let c = Classifier::new(d, ContainOptions::default()).map_err(|e| e.to_string())?;
            let pts = halton_points(n, d.bounding_box());
            let mut row = format!("| {name} |");
            for g in grids {
                let tb = median_time(o.reps, || {
                    std::hint::black_box(
                        PointLocator::new(&c, LocatorOptions { cells: g }).cells(),
                    );
                });
                let loc = PointLocator::new(&c, LocatorOptions { cells: g });
                let tq = median_time(o.reps, || {
                    std::hint::black_box(loc.classify(&pts));
                });
                let _ = write!(
                    row,
                    " {tb:.1e} + {tq:.1e} s ({:.2}%) |",
                    100.0 * loc.mixed_fraction()
                );
            }
            let _ = writeln!(md, "{row}");
        }
    }
    let machine = machine_line();
    let report = format!(
        "Machine: {machine}\n\nMedian of {} runs, single thread.\n\n{md}",
        o.reps
    );
    println!("{report}");
    let dir = root.join("target/bench-report");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("bench.md"), &report).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("bench.csv"), &csv).map_err(|e| e.to_string())?;
    println!("written: target/bench-report/bench.md, target/bench-report/bench.csv");
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
