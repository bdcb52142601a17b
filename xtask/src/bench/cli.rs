//! The command-line tool end to end: `inrs classify` file to file on CSV and `.npy` points,
//! wall time and peak memory (the release binary, run as a user runs it).

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use inrs::contain::baselines::halton_points_from;

use super::{BenchOptions, median};

/// Builds the release binary and returns its path.
pub(super) fn release_binary(root: &Path) -> Result<PathBuf, String> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let status = Command::new(cargo)
        .args(["build", "--release", "--quiet", "-p", "inrs-cli"])
        .current_dir(root)
        .status()
        .map_err(|e| format!("cargo build: {e}"))?;
    if !status.success() {
        return Err("cargo build --release -p inrs-cli failed".into());
    }
    Ok(root.join("target/release/inrs"))
}

/// Writes `n` Halton points of the box `[-1, 1]^2` as CSV and as `.npy`, anew at each run, in
/// writes of 1 MiB (as `numpy.save` writes an array: in one call). How a file was written
/// decides how fast the operating system's cache gives it back: a file written 8 KiB at a
/// time (the files of this benchmark before 2026-12-08, kept from run to run) gave this
/// benchmark's I/O floor at 10^6 `.npy` points as 2.7-3.6 ms, against 1.6-1.7 ms for files
/// written so (a reader of blocks of 256 KiB on one thread: 3.2-3.7 against 2.5-2.6 ms for
/// the same file copied by `cp`), which made the floor and the ratios over it depend on the
/// history of the checkout.
fn write_points(dir: &Path, n: usize) -> Result<(PathBuf, PathBuf), String> {
    let b = inrs::BoundingBox {
        min: inrs::Point::new(-1.0, -1.0),
        max: inrs::Point::new(1.0, 1.0),
    };
    let csv = dir.join(format!("points-{n}.csv"));
    let npy = dir.join(format!("points-{n}.npy"));
    let io = |e: std::io::Error| e.to_string();
    let mut c =
        std::io::BufWriter::with_capacity(1 << 20, std::fs::File::create(&csv).map_err(io)?);
    let mut p =
        std::io::BufWriter::with_capacity(1 << 20, std::fs::File::create(&npy).map_err(io)?);
    p.write_all(&inrs::npy_header(inrs::NpyType::F64, &[n, 2]))
        .map_err(io)?;
    writeln!(c, "x,y").map_err(io)?;
    const CHUNK: usize = 1 << 20;
    for start in (0..n).step_by(CHUNK) {
        let pts = halton_points_from(start as u64, CHUNK.min(n - start), b);
        for q in &pts {
            writeln!(c, "{},{}", q.x, q.y).map_err(io)?;
            p.write_all(&q.x.to_le_bytes()).map_err(io)?;
            p.write_all(&q.y.to_le_bytes()).map_err(io)?;
        }
    }
    c.flush().map_err(io)?;
    p.flush().map_err(io)?;
    Ok((csv, npy))
}

/// One run of `inrs classify`: wall seconds and the size of the output in bytes; with
/// `peak_memory`, run under `/usr/bin/time` (if there) and also its peak resident memory in
/// MiB. Timed runs go without it: its own start (an exec and a fork, about 1.3 ms on the
/// 2-core machine of BENCHMARKS.md) would be counted as the tool's.
fn run(
    bin: &Path,
    domain: &Path,
    points: &Path,
    out: &Path,
    peak_memory: bool,
) -> Result<(f64, Option<f64>, u64), String> {
    let _ = std::fs::remove_file(out);
    let time = Path::new("/usr/bin/time");
    let mut cmd = if peak_memory && time.exists() {
        let mut c = Command::new(time);
        c.args(["-f", "%M"]).arg(bin);
        c
    } else {
        Command::new(bin)
    };
    cmd.arg("classify")
        .arg("--domain")
        .arg(domain)
        .arg("--points")
        .arg(points)
        .arg("--output")
        .arg(out);
    let start = Instant::now();
    let result = cmd
        .output()
        .map_err(|e| format!("{}: {e}", bin.display()))?;
    let seconds = start.elapsed().as_secs_f64();
    if !result.status.success() {
        return Err(format!(
            "inrs classify failed: {}",
            String::from_utf8_lossy(&result.stderr)
        ));
    }
    let peak = peak_memory
        .then(|| {
            String::from_utf8_lossy(&result.stderr)
                .lines()
                .last()
                .and_then(|l| l.trim().parse::<f64>().ok())
                .map(|kb| kb / 1024.0)
        })
        .flatten();
    let size = std::fs::metadata(out).map_or(0, |m| m.len());
    let _ = std::fs::remove_file(out);
    Ok((seconds, peak, size))
}

/// The input/output floor of a run, in seconds: reading `input` and writing `size` bytes to a
/// new file `out` (bytes of the input), in blocks of 256 KiB, in this process (no
/// start-up): what the operating system's caches cost a tool that does nothing else.
fn io_floor(input: &Path, out: &Path, size: u64) -> Result<f64, String> {
    use std::io::Read;
    let io = |e: std::io::Error| format!("{}: {e}", out.display());
    let _ = std::fs::remove_file(out);
    let start = Instant::now();
    let mut r = std::fs::File::open(input).map_err(io)?;
    let mut w = std::fs::File::create(out).map_err(io)?;
    let mut block = vec![0u8; 1 << 18];
    while r.read(&mut block).map_err(io)? > 0 {}
    let mut left = size;
    while left > 0 {
        let n = left.min(block.len() as u64) as usize;
        w.write_all(&block[..n]).map_err(io)?;
        left -= n as u64;
    }
    drop(w);
    let seconds = start.elapsed().as_secs_f64();
    let _ = std::fs::remove_file(out);
    Ok(seconds)
}

/// The CLI table: for each size, the four combinations of input and output timed in rounds
/// (one run of each per round), so that a noisy spell slows them alike; the median and the
/// fastest round of each.
pub(super) fn end_to_end(md: &mut String, root: &Path, o: &BenchOptions) -> Result<(), String> {
    let bin = release_binary(root)?;
    let dir = root.join("target/bench-cli");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let domain = root.join("fixtures/inrs-paper/s5_lune.json");
    let sizes: &[usize] = if o.quick {
        &[100_000, 1_000_000]
    } else {
        &[1_000_000, 10_000_000]
    };
    // Runs of a second or so (10^7 points as CSV) get fewer rounds than runs of milliseconds.
    // Those get at least 11 even with `--quick` (a round of the four cases at 10^6 points takes
    // about 0.15 s): the median of `--quick`'s 3 rounds of the `.npy` case moved between 3.4
    // and 4.7x its floor in two runs one after the other.
    let rounds = |n: usize| {
        if n > 1_000_000 {
            o.reps.min(3)
        } else if o.quick {
            o.reps.max(11)
        } else {
            o.reps.max(1)
        }
    };
    let _ = writeln!(
        md,
        "\n### The command-line tool end to end\n\n`inrs classify --domain s5_lune.json` (default \
         method), file to file, Halton points of `[-1, 1]^2`: wall time including start-up \
         (loading the domain, building the index), million points per second, and peak \
         resident memory (`/usr/bin/time`, in one more run: timed runs go without it). The four combinations of a size are timed in \
         rounds (one run of each per round: {} rounds at 10^6 points and fewer, {} above); \
         medians, and under *best* the fastest round. *I/O floor*: reading the input file and \
         writing a file of the output's size, in blocks of 256 KiB, in the same rounds (no \
         process start-up): what the operating system's file caches alone cost; *x floor* is \
         the tool's median over the floor's.\n",
        rounds(1),
        rounds(usize::MAX)
    );
    let _ = writeln!(
        md,
        "| points in | results out | N | seconds | Mpts/s | best seconds | best Mpts/s | I/O floor s | x floor | peak MiB |"
    );
    let _ = writeln!(
        md,
        "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    );
    for &n in sizes {
        let (csv, npy) = write_points(&dir, n)?;
        let cases = [
            (&csv, "CSV", "csv", "CSV"),
            (&csv, "CSV", "npy", ".npy"),
            (&npy, ".npy", "csv", "CSV"),
            (&npy, ".npy", "npy", ".npy"),
        ];
        let mut runs = vec![Vec::new(); cases.len()];
        let mut floors = vec![Vec::new(); cases.len()];
        for _ in 0..rounds(n) {
            for (((input, _, ext, _), runs), floors) in
                cases.iter().zip(runs.iter_mut()).zip(floors.iter_mut())
            {
                let out = dir.join(format!("out.{ext}"));
                let (seconds, _, size) = run(&bin, &domain, input, &out, false)?;
                floors.push(io_floor(input, &out, size)?);
                runs.push(seconds);
            }
        }
        for (((input, kind, ext, out_kind), times), floors) in
            cases.into_iter().zip(runs).zip(floors)
        {
            let floor = median(floors);
            // Peak memory from one more run, under `/usr/bin/time`.
            let peak = run(&bin, &domain, input, &dir.join(format!("out.{ext}")), true)?.1;
            let best = times.iter().copied().fold(f64::INFINITY, f64::min);
            let t = median(times);
            let _ = writeln!(
                md,
                "| {kind} | {out_kind} | {n} | {t:.4} | {:.1} | {best:.4} | {:.1} | {floor:.4} | {:.1} | {} |",
                n as f64 / t / 1e6,
                n as f64 / best / 1e6,
                t / floor,
                peak.map_or("-".into(), |m| format!("{m:.0}"))
            );
        }
    }
    Ok(())
}
