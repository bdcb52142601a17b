//! The grid point locator: queries alone, at scale (10^5 boxes), and the refinement and
//! grid-resolution sweeps.

use std::fmt::Write as _;

use inrs::contain::baselines::halton_points;
use inrs::contain::{Locate, LocatorOptions, PointLocator, PointQuery};
use inrs::{Classifier, ContainOptions, Domain, Location, Method};

use super::{BenchOptions, interleaved_times, median_time};

/// Throughput of the locator's queries alone (index built once), on one thread and on all,
/// with inRS2 and a pass that only reads the points (counts `x < y`: the memory-bandwidth
/// ceiling) measured in the same run.
pub(super) fn single_thread(
    md: &mut String,
    domains: &[(String, Domain)],
    o: &BenchOptions,
) -> Result<(), String> {
    let n = o.largest_size();
    let threads = std::thread::available_parallelism().map_or(1, |t| t.get());
    let _ = writeln!(
        md,
        "\nLocator queries alone (index built once), N = {n} Halton points: million points per \
         second on one thread written into a buffer the caller keeps (`values_into`, as the CLI \
         streams), on one thread and on {threads} threads into a new vector (`locate_all`, \
         `locate_all_parallel`), the scaling between those two, the ratio to inRS2, and the \
         fraction of a pass that only reads the points (counts x < y: the memory-bandwidth \
         ceiling), all in the same run; the last four timed in rounds (one run of each, on every \
         domain, per round) so that a noisy spell slows them alike; medians, and the fastest of the {} rounds (what the \
         code does when the machine leaves it undisturbed: a shared machine only ever slows a run \
         down) under *best*.\n",
        o.reps
    );
    let _ = writeln!(
        md,
        "| domain | build | index | 1 thread, kept buffer Mpts/s | 1 thread, new vector | {threads} threads, new vector | scaling | 1 thread, kept buffer, best | scaling, best | vs inRS2 | of read-only pass |"
    );
    let _ = writeln!(
        md,
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    );
    // Every domain's index and points first, then the query timings of all domains in the
    // same rounds: a noisy spell on the machine (a busy neighbour halves the speed for
    // seconds) then slows every domain alike instead of the one being timed.
    let mut classifiers = Vec::with_capacity(domains.len());
    let mut builds = Vec::with_capacity(domains.len());
    for (_, d) in domains {
        let c = Classifier::new(d, ContainOptions::default()).map_err(|e| e.to_string())?;
        let pts = halton_points(n, d.bounding_box());
        let t2 = median_time(o.reps.min(3), || {
            std::hint::black_box(c.locate_all_with(Method::InRS2, &pts));
        });
        let tb = median_time(o.reps, || {
            std::hint::black_box(PointLocator::new(&c, LocatorOptions::default()).cells());
        });
        classifiers.push(c);
        builds.push((pts, t2, tb));
    }
    let locators: Vec<PointLocator<'_>> = classifiers
        .iter()
        .map(|c| PointLocator::new(c, LocatorOptions::default()))
        .collect();
    let mut kept = vec![vec![Location::Outside; n]; domains.len()];
    let mut runs: Vec<Box<dyn FnMut() + '_>> = Vec::new();
    for ((loc, (pts, _, _)), kept) in locators.iter().zip(&builds).zip(kept.iter_mut()) {
        // First a run whose time is dropped: it brings this domain's index back into the
        // caches after the other domains' runs, as a program querying one domain has it.
        runs.push(Box::new(move || {
            std::hint::black_box(loc.locate_all(pts));
        }));
        runs.push(Box::new(move || {
            loc.values_into(&pts[..], kept);
            std::hint::black_box(&*kept);
        }));
        runs.push(Box::new(move || {
            std::hint::black_box(loc.locate_all(pts));
        }));
        runs.push(Box::new(move || {
            std::hint::black_box(loc.locate_all_parallel(pts));
        }));
        runs.push(Box::new(move || {
            std::hint::black_box(pts.iter().filter(|p| p.x < p.y).count());
        }));
    }
    let mut refs: Vec<&mut dyn FnMut()> = runs
        .iter_mut()
        .map(|f| &mut **f as &mut dyn FnMut())
        .collect();
    let times = interleaved_times(o.reps, &mut refs);
    for (((name, _), (loc, (_, t2, tb))), t) in domains
        .iter()
        .zip(locators.iter().zip(&builds))
        .zip(times.chunks_exact(5))
    {
        let t = &t[1..];
        let (tk, tq, tp, ts) = (t[0].median, t[1].median, t[2].median, t[3].median);
        let mpts = |t: f64| n as f64 / t / 1e6;
        let _ = writeln!(
            md,
            "| {name} | {tb:.1e} s | {:.0} KiB | {:.0} | {:.0} | {:.0} | {:.2}x | {:.0} | {:.2}x | {:.1}x | {:.2} |",
            loc.memory_bytes() as f64 / 1024.0,
            mpts(tk),
            mpts(tq),
            mpts(tp),
            tq / tp,
            mpts(t[0].best),
            t[1].best / t[2].best,
            t2 / tk,
            ts / tk
        );
    }
    Ok(())
}

/// The locator with about 10^5 boxes (the 500-curve flower, refined).
pub(super) fn at_scale(md: &mut String, flower: &Domain, o: &BenchOptions) -> Result<(), String> {
    let one = Classifier::new(flower, ContainOptions::DEFAULT.with_subdivisions(1))
        .map_err(|e| e.to_string())?;
    let k = 100_000usize.div_ceil(one.boxes().boxes().len());
    let c = Classifier::new(flower, ContainOptions::DEFAULT.with_subdivisions(k))
        .map_err(|e| e.to_string())?;
    let nboxes = c.boxes().boxes().len();
    let t_build = median_time(o.reps.min(3), || {
        std::hint::black_box(PointLocator::new(&c, LocatorOptions::default()).cells());
    });
    let loc = PointLocator::new(&c, LocatorOptions::default());
    let bytes = loc.memory_bytes();
    let n = if o.quick { 100_000 } else { 1_000_000 };
    let pts = halton_points(n, flower.bounding_box());
    let t_q = median_time(o.reps.min(3), || {
        std::hint::black_box(loc.locate_all(&pts));
    });
    let _ = writeln!(
        md,
        "\nLocator at scale: flower500 with {k} sub-boxes per monotone piece = {nboxes} boxes; \
         build {t_build:.2e} s, {} (box, cell) incidences, index memory {:.1} MiB, {n} Halton \
         points in {t_q:.2e} s on one thread ({:.0} Mpts/s), mixed cells {:.2}%.",
        loc.incidences(),
        bytes as f64 / (1024.0 * 1024.0),
        n as f64 / t_q / 1e6,
        100.0 * loc.mixed_fraction()
    );
    Ok(())
}

/// inRS2 time by sub-boxes per monotone piece (Remark 2.1).
pub(super) fn refinement_sweep(
    md: &mut String,
    domains: &[(String, Domain)],
    o: &BenchOptions,
) -> Result<(), String> {
    let n = o.largest_size();
    let ks = [1usize, 2, 4, 8, 16, 32, 64, 128];
    let _ = writeln!(
        md,
        "\nBox refinement (Remark 2.1): inRS2 time for N = {n}, by sub-boxes per monotone \
         piece; ratio to 1 sub-box.\n"
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
                std::hint::black_box(c.locate_all_with(Method::InRS2, &pts));
            });
            if k == 1 {
                base = t;
            }
            let _ = write!(row, " {t:.2e} s ({:.2}) |", t / base);
        }
        let _ = writeln!(md, "{row}");
    }
    Ok(())
}

/// Locator build and query time by grid resolution.
pub(super) fn grid_sweep(
    md: &mut String,
    domains: &[(String, Domain)],
    o: &BenchOptions,
) -> Result<(), String> {
    let n = o.largest_size();
    let grids = [128usize, 256, 512, 1024, 2048, 4096];
    let _ = writeln!(
        md,
        "\nGrid resolution: locator build + one-thread classification of N = {n} points, \
         mixed-cell fraction.\n"
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
