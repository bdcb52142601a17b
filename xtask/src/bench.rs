//! `cargo xtask bench`: the papers' comparisons, measured in one process (medians of repeated
//! runs), printed and written as Markdown and CSV under `target/bench-report/`.

use inrs::contain::Locate;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use inrs::contain::baselines::{FlattenedPolygon, WindingAlgorithm, halton_points};
use inrs::contain::{FastWindingField, LocatorOptions, PointLocator, QueryStats, WindingField};
use inrs::{BoundingBox, Classifier, ContainOptions, Domain, Location, Method, Point};

/// Options of a run.
pub(crate) struct BenchOptions {
    pub(crate) domains: Vec<String>,
    pub(crate) sizes: Vec<usize>,
    pub(crate) reps: usize,
    pub(crate) sweep: bool,
    pub(crate) quick: bool,
    /// Time inRS1 and the reference GWN at every size (they stop at 10^5 otherwise).
    pub(crate) full: bool,
}

const ALL_DOMAINS: [&str; 6] = [
    "s3_m_shape",
    "s4_disk_ellipse_segment",
    "s5_lune",
    "circle",
    "l_shape",
    "leaf_cubic",
];

impl BenchOptions {
    pub(crate) fn parse(args: &[String]) -> Result<Self, String> {
        let mut o = Self {
            domains: ALL_DOMAINS.iter().map(|s| s.to_string()).collect(),
            sizes: vec![1_000, 10_000, 100_000, 1_000_000],
            reps: 11,
            sweep: false,
            quick: false,
            full: false,
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
                    let v = value()?;
                    o.domains = if v == "all" {
                        ALL_DOMAINS.iter().map(|s| s.to_string()).collect()
                    } else if v == "paper" {
                        ALL_DOMAINS[..3].iter().map(|s| s.to_string()).collect()
                    } else {
                        v.split(',').map(str::to_string).collect()
                    }
                }
                "--sizes" => {
                    o.sizes = value()?
                        .split(',')
                        .map(|s| s.parse().map_err(|_| format!("bad size {s:?}")))
                        .collect::<Result<_, _>>()?
                }
                "--reps" => o.reps = value()?.parse().map_err(|_| "bad --reps".to_string())?,
                "--sweep" => o.sweep = true,
                "--full" => o.full = true,
                other => return Err(format!("unknown bench option {other:?}")),
            }
        }
        if o.reps == 0 || o.sizes.is_empty() || o.domains.is_empty() {
            return Err("need at least one repetition, size and domain".into());
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

/// The paths timed for the tables.
const PATHS: [&str; 6] = [
    "inrs1",
    "inrs2",
    "polygon",
    "locator",
    "locator-parallel",
    "gwn",
];

/// inRS1 (O(MN)) and the reference GWN (every curve per point) stop at this size unless
/// `--full` is given.
const SLOW_PATH_MAX: usize = 100_000;

struct Row {
    seconds: f64,
    inside: usize,
}

pub(crate) fn run(root: &Path, o: &BenchOptions) -> Result<(), String> {
    let mut domains = Vec::new();
    for name in &o.domains {
        let path = root
            .join("fixtures/inrs-paper")
            .join(format!("{name}.json"));
        let d = inrs::io::json::domain_from_json_file(&path)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        domains.push((name.clone(), d));
    }
    let mut results: BTreeMap<(String, usize, &str), Row> = BTreeMap::new();
    let mut sides: BTreeMap<String, usize> = BTreeMap::new();
    for (name, d) in &domains {
        let c = Classifier::new(d, ContainOptions::default()).map_err(|e| e.to_string())?;
        let poly = FlattenedPolygon::new(d, 1e-10);
        sides.insert(name.clone(), poly.edge_count());
        for &n in &o.sizes {
            let pts = halton_points(n, d.bounding_box());
            for path in PATHS {
                if (path == "inrs1" || path == "gwn") && n > SLOW_PATH_MAX && !o.full {
                    continue;
                }
                let mut inside = 0;
                let seconds = median_time(o.reps, || {
                    inside = match path {
                        "inrs1" => count_inside(&c.classify(&pts, Method::InRS1)),
                        "inrs2" => count_inside(&c.classify(&pts, Method::InRS2)),
                        "polygon" => poly.classify(&pts).iter().filter(|&&b| b).count(),
                        "locator" => count_inside(
                            &PointLocator::new(&c, LocatorOptions::default()).locate_all(&pts),
                        ),
                        "locator-parallel" => count_inside(
                            &PointLocator::new(&c, LocatorOptions::default())
                                .locate_all_parallel(&pts),
                        ),
                        _ => count_inside(&c.classify(&pts, Method::Gwn)),
                    }
                });
                results.insert((name.clone(), n, path), Row { seconds, inside });
            }
            let reference = results[&(name.clone(), n, "inrs2")].inside;
            for path in PATHS {
                if let Some(r) = results.get(&(name.clone(), n, path))
                    && r.inside != reference
                {
                    return Err(format!(
                        "{name} N={n}: {path} counts {} inside, inRS2 {reference}",
                        r.inside
                    ));
                }
            }
        }
    }

    let mut md = String::new();
    let names: Vec<&str> = domains.iter().map(|(n, _)| n.as_str()).collect();
    let header = |md: &mut String, first: &str| {
        let _ = writeln!(md, "| {first} | algorithm | {} |", names.join(" | "));
        let _ = writeln!(md, "| ---: | --- |{}", " ---: |".repeat(names.len()));
    };
    let time_row = |md: &mut String, n: usize, label: &str, path: &str| {
        let cells: Vec<String> = names
            .iter()
            .map(|d| {
                results
                    .get(&(d.to_string(), n, path))
                    .map_or("-".into(), |r| format!("{:.1e} s", r.seconds))
            })
            .collect();
        let _ = writeln!(md, "| {n} | {label} | {} |", cells.join(" | "));
    };
    let ratio_row = |md: &mut String, n: usize, label: &str, slow: &str, fast: &str| {
        let cells: Vec<String> = names
            .iter()
            .map(|d| {
                match (
                    results.get(&(d.to_string(), n, slow)),
                    results.get(&(d.to_string(), n, fast)),
                ) {
                    (Some(s), Some(f)) => format!("{:.2}", s.seconds / f.seconds),
                    _ => "-".into(),
                }
            })
            .collect();
        let _ = writeln!(md, "| | {label} | {} |", cells.join(" | "));
    };

    let _ = writeln!(md, "### Table 1: inRS1 and inRS2 (paper Table 1)\n");
    let _ = writeln!(
        md,
        "CPU time for N Halton points of each domain's bounding box; speed-up = inRS1 / inRS2.\n"
    );
    header(&mut md, "N");
    for &n in &o.sizes {
        time_row(&mut md, n, "inRS1", "inrs1");
        time_row(&mut md, n, "inRS2", "inrs2");
        ratio_row(&mut md, n, "speed-up", "inrs1", "inrs2");
    }
    let _ = writeln!(
        md,
        "\n### Table 2: inRS2 and a polygon within 1e-10 (paper Table 2)\n"
    );
    let sides_row: Vec<String> = names.iter().map(|d| sides[*d].to_string()).collect();
    let _ = writeln!(
        md,
        "The polygon baseline flattens the boundary to within 1e-10 ({} sides) and classifies with sorted points and a binary search per edge (the INPOLY2 strategy); speed-up = polygon / inRS2.\n",
        sides_row.join(", ")
    );
    header(&mut md, "N");
    for &n in &o.sizes {
        time_row(&mut md, n, "polygon", "polygon");
        time_row(&mut md, n, "inRS2", "inrs2");
        ratio_row(&mut md, n, "speed-up", "polygon", "inrs2");
    }
    let _ = writeln!(
        md,
        "\n### Table 3: fast paths and generalized winding numbers\n"
    );
    let _ = writeln!(
        md,
        "Grid point locator ({0} x {0} cells) including its build, on one thread and on all threads; GWN = rounded generalized winding number (reference field, up to N = {SLOW_PATH_MAX}); speed-ups over inRS2.\n",
        inrs::contain::DEFAULT_GRID_CELLS
    );
    header(&mut md, "N");
    for &n in &o.sizes {
        time_row(&mut md, n, "inRS2", "inrs2");
        time_row(&mut md, n, "locator", "locator");
        time_row(&mut md, n, "locator parallel", "locator-parallel");
        time_row(&mut md, n, "GWN", "gwn");
        ratio_row(&mut md, n, "locator speed-up", "inrs2", "locator");
        ratio_row(&mut md, n, "parallel speed-up", "inrs2", "locator-parallel");
    }
    let mut csv = String::from("domain,n,method,seconds,inside\n");
    for ((d, n, path), r) in &results {
        let _ = writeln!(csv, "{d},{n},{path},{},{}", r.seconds, r.inside);
    }

    single_thread_locator(&mut md, &domains, o)?;
    gwn_flower(&mut md, root, o)?;
    locator_at_scale(&mut md, root, o)?;
    gwn_comparison(&mut md, root, o)?;
    if o.sweep {
        sweeps(&mut md, &domains, o)?;
    }

    let report = format!(
        "Machine: {}\n\nMedian of {} runs, single thread unless stated.\n\n{md}",
        machine_line(),
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

/// Throughput of the locator's queries alone (index built once), one thread.
fn single_thread_locator(
    md: &mut String,
    domains: &[(String, Domain)],
    o: &BenchOptions,
) -> Result<(), String> {
    let n = *o.sizes.iter().max().unwrap_or(&1_000_000);
    let _ = writeln!(
        md,
        "\nLocator queries alone (index built once), one thread, N = {n}: million points per second and ratio to inRS2 in the same run.\n"
    );
    let _ = writeln!(md, "| domain | build | queries | Mpts/s | vs inRS2 |");
    let _ = writeln!(md, "| --- | ---: | ---: | ---: | ---: |");
    for (name, d) in domains {
        let c = Classifier::new(d, ContainOptions::default()).map_err(|e| e.to_string())?;
        let pts = halton_points(n, d.bounding_box());
        let t2 = median_time(o.reps, || {
            std::hint::black_box(c.classify(&pts, Method::InRS2));
        });
        let tb = median_time(o.reps, || {
            std::hint::black_box(PointLocator::new(&c, LocatorOptions::default()).cells());
        });
        let loc = PointLocator::new(&c, LocatorOptions::default());
        let tq = median_time(o.reps, || {
            std::hint::black_box(loc.locate_all(&pts));
        });
        let _ = writeln!(
            md,
            "| {name} | {tb:.1e} s | {tq:.1e} s | {:.0} | {:.1}x |",
            n as f64 / tq / 1e6,
            t2 / tq
        );
    }
    Ok(())
}

fn flower(root: &Path) -> Result<Domain, String> {
    inrs::io::json::domain_from_json_file(root.join("fixtures/synthetic/flower500.json"))
        .map_err(|e| e.to_string())
}

/// Accelerated versus reference winding numbers on the 500-curve flower.
fn gwn_flower(md: &mut String, root: &Path, o: &BenchOptions) -> Result<(), String> {
    let d = flower(root)?;
    let field = WindingField::new(&d, inrs::contain::DEFAULT_RELATIVE_TOLERANCE)
        .map_err(|e| e.to_string())?;
    let n = if o.quick { 10_000 } else { 100_000 };
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
        "| {:.2} Mq/s | {t_build:.1e} s | {:.2} Mq/s | {:.0}x | {:.2} Mq/s |",
        mq(t_ref),
        mq(t_fast),
        t_ref / t_fast,
        mq(t_par)
    );
    Ok(())
}

/// The locator with about 10^5 boxes.
fn locator_at_scale(md: &mut String, root: &Path, o: &BenchOptions) -> Result<(), String> {
    let d = flower(root)?;
    let one = Classifier::new(&d, ContainOptions::DEFAULT.with_subdivisions(1))
        .map_err(|e| e.to_string())?;
    let k = 100_000usize.div_ceil(one.boxes().boxes().len());
    let c = Classifier::new(&d, ContainOptions::DEFAULT.with_subdivisions(k))
        .map_err(|e| e.to_string())?;
    let nboxes = c.boxes().boxes().len();
    let t_build = median_time(o.reps.min(3), || {
        std::hint::black_box(PointLocator::new(&c, LocatorOptions::default()).cells());
    });
    let loc = PointLocator::new(&c, LocatorOptions::default());
    let cells = loc.cells() * loc.cells();
    let bytes = 4 * loc.incidences() + 4 * (cells + 1) + cells + cells / 4;
    let n = if o.quick { 100_000 } else { 1_000_000 };
    let pts = halton_points(n, d.bounding_box());
    let t_q = median_time(o.reps.min(3), || {
        std::hint::black_box(loc.locate_all(&pts));
    });
    let _ = writeln!(
        md,
        "\nLocator at scale: flower500 with {k} sub-boxes per monotone piece = {nboxes} boxes; build {t_build:.2e} s, {} (box, cell) incidences, index memory {:.1} MiB, {n} Halton points in {t_q:.2e} s on one thread ({:.0} Mpts/s), mixed cells {:.2}%.",
        loc.incidences(),
        bytes as f64 / (1024.0 * 1024.0),
        n as f64 / t_q / 1e6,
        100.0 * loc.mixed_fraction()
    );
    Ok(())
}

/// Uniform pseudo-random points in a box (xorshift64*, fixed seed).
fn uniform_points(n: usize, b: BoundingBox) -> Vec<Point> {
    let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = || {
        s ^= s >> 12;
        s ^= s << 25;
        s ^= s >> 27;
        (s.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| Point::new(b.min.x + next() * b.width(), b.min.y + next() * b.height()))
        .collect()
}

/// The GWN paper's comparisons: curve evaluations per query of the three per-curve algorithms
/// (its Fig. 15) and misclassifications of fixed linearisations (its Fig. 14).
fn gwn_comparison(md: &mut String, root: &Path, o: &BenchOptions) -> Result<(), String> {
    let name = "leaf_cubic";
    let d = inrs::io::json::domain_from_json_file(
        root.join(format!("fixtures/inrs-paper/{name}.json")),
    )
    .map_err(|e| e.to_string())?;
    let field = WindingField::new(&d, inrs::contain::DEFAULT_RELATIVE_TOLERANCE)
        .map_err(|e| e.to_string())?;
    let n = if o.quick { 20_000 } else { 250_000 };
    let mut bb = d.bounding_box();
    let pad = 0.05 * bb.diagonal();
    bb.min = bb.min - Point::new(pad, pad);
    bb.max = bb.max + Point::new(pad, pad);
    let pts = uniform_points(n, bb);
    let buckets = [1usize, 2, 4, 8, 16, 32, 64, 128, usize::MAX];
    let algorithms = [
        ("adaptive GWN", WindingAlgorithm::Adaptive),
        ("binary search", WindingAlgorithm::BinarySearch),
        ("Bezier clipping", WindingAlgorithm::BezierClipping),
    ];
    let _ = writeln!(
        md,
        "\n### Curve evaluations per query (GWN paper Fig. 15)\n\n`{name}` ({} rational cubic pieces), {n} uniform random points of its box grown by 5%: number of queries by evaluations (sub-curves examined) over all pieces, each algorithm inside the same closure framework.\n",
        field.pieces().len()
    );
    let labels: Vec<String> = buckets
        .iter()
        .enumerate()
        .map(|(i, &b)| match (i, b) {
            (0, _) => "<= 1".to_string(),
            (_, usize::MAX) => "> 128".to_string(),
            _ if buckets[i - 1] + 1 == b => b.to_string(),
            _ => format!("{}-{}", buckets[i - 1] + 1, b),
        })
        .collect();
    let _ = writeln!(
        md,
        "| algorithm | {} | mean | max | time |",
        labels.join(" | ")
    );
    let _ = writeln!(
        md,
        "| --- |{} ---: | ---: | ---: |",
        " ---: |".repeat(labels.len())
    );
    let mut values: Vec<Vec<f64>> = Vec::new();
    for (label, alg) in algorithms {
        let mut hist = vec![0usize; buckets.len()];
        let (mut total, mut max) = (0usize, 0usize);
        let start = Instant::now();
        let mut w = Vec::with_capacity(n);
        for &q in &pts {
            let mut s = QueryStats::default();
            w.push(field.winding_number_with(q, alg, &mut s));
            let e = s.curve_evaluations;
            total += e;
            max = max.max(e);
            let b = buckets
                .iter()
                .position(|&b| e <= b)
                .unwrap_or(buckets.len() - 1);
            hist[b] += 1;
        }
        let t = start.elapsed().as_secs_f64();
        values.push(w);
        let cells: Vec<String> = hist.iter().map(|h| h.to_string()).collect();
        let _ = writeln!(
            md,
            "| {label} | {} | {:.1} | {max} | {t:.2e} s |",
            cells.join(" | "),
            total as f64 / n as f64
        );
    }
    let disagree = (1..values.len())
        .map(|k| {
            values[0]
                .iter()
                .zip(&values[k])
                .filter(|(a, b)| (**a - **b).abs() > 1e-6)
                .count()
        })
        .max()
        .unwrap_or(0);
    let _ = writeln!(
        md,
        "\nThe three agree on the winding number (to 1e-6) at all but {disagree} of the {n} points."
    );

    // Fig. 14: fixed linearisations versus the exact containment.
    let c = Classifier::new(&d, ContainOptions::default()).map_err(|e| e.to_string())?;
    let exact = c.classify(&pts, Method::Fast);
    let _ = writeln!(
        md,
        "\n### Misclassifications of fixed linearisations (GWN paper Fig. 14)\n\n`{name}`, the same {n} points: each piece replaced by k equal-parameter chords; points whose containment differs from the exact answer (boundary points excluded).\n"
    );
    let ks = [1usize, 2, 4, 8, 16, 32, 64];
    let _ = writeln!(
        md,
        "| chords per piece | {} | exact |",
        ks.map(|k| k.to_string()).join(" | ")
    );
    let _ = writeln!(md, "| --- |{} ---: |", " ---: |".repeat(ks.len()));
    let mut row = String::from("| misclassified |");
    for k in ks {
        let lin = FlattenedPolygon::uniform(&d, k).classify(&pts);
        let wrong = exact
            .iter()
            .zip(&lin)
            .filter(|(e, l)| **e != Location::Boundary && (**e == Location::Inside) != **l)
            .count();
        let _ = write!(row, " {wrong} |");
    }
    let _ = writeln!(md, "{row} 0 |");
    Ok(())
}

/// Box refinement and grid resolution sweeps.
fn sweeps(md: &mut String, domains: &[(String, Domain)], o: &BenchOptions) -> Result<(), String> {
    let n = *o.sizes.iter().max().unwrap_or(&100_000);
    let ks = [1usize, 2, 4, 8, 16, 32, 64, 128];
    let _ = writeln!(
        md,
        "\nBox refinement (Remark 2.1): inRS2 time for N = {n}, by sub-boxes per monotone piece; ratio to 1 sub-box.\n"
    );
    let _ = writeln!(md, "| domain | {} |", ks.map(|k| k.to_string()).join(" | "));
    let _ = writeln!(md, "| --- |{}", " ---: |".repeat(ks.len()));
    for (name, d) in domains {
        let pts = halton_points(n, d.bounding_box());
        let mut row = format!("| {name} |");
        let mut base = 0.0;
        for k in ks {
            let c = Classifier::new(d, ContainOptions::DEFAULT.with_subdivisions(k))
                .map_err(|e| e.to_string())?;
            let t = median_time(o.reps, || {
                std::hint::black_box(c.classify(&pts, Method::InRS2));
            });
            if k == 1 {
                base = t;
            }
            let _ = write!(row, " {t:.2e} s ({:.2}) |", t / base);
        }
        let _ = writeln!(md, "{row}");
    }
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
    for (name, d) in domains {
        let c = Classifier::new(d, ContainOptions::default()).map_err(|e| e.to_string())?;
        let pts = halton_points(n, d.bounding_box());
        let mut row = format!("| {name} |");
        for g in grids {
            let tb = median_time(o.reps, || {
                std::hint::black_box(
                    PointLocator::new(&c, LocatorOptions::DEFAULT.with_cells(g)).cells(),
                );
            });
            let loc = PointLocator::new(&c, LocatorOptions::DEFAULT.with_cells(g));
            let tq = median_time(o.reps, || {
                std::hint::black_box(loc.locate_all(&pts));
            });
            let _ = write!(
                row,
                " {tb:.1e} + {tq:.1e} s ({:.2}%) |",
                100.0 * loc.mixed_fraction()
            );
        }
        let _ = writeln!(md, "{row}");
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
