//! The winding-number field near the curves against its far-field cost (issue 52's row "winding
//! field near the curves <= 3x the far field"): microseconds per point of
//! `FastWindingField::winding_numbers` on the GWN paper's five shapes, on three query sets of
//! [`super::point_sets`] (seed 52):
//!
//! - near: `near_points(d, 100_000, 52)`, at 1e-2..1e-10 of the diagonal from the curves;
//! - far: the points of `random_points(d, 1_000_000, 52)` whose distance to every piece's
//!   control box is at least 5% of the diagonal (so at least that far from the curves, which
//!   lie in those boxes), the first 100 000 of them;
//! - random: `random_points(d, 100_000, 52)`.
//!
//! Each set is answered by one field built beforehand (the pieces' subdivision hierarchies are
//! built by the warm-up runs, so the times are of a warm field). Beside the times, a hash of the
//! values' bits per shape (FNV-1a of every `f64`'s bits, over the three sets plus a grid and
//! points on the curves and at the pieces' ends), from a freshly built field (its first queries
//! walk the pieces on the fly) and from a warm one: any change to the field's arithmetic shows
//! there.

use std::fmt::Write as _;
use std::path::Path;

use inrs::contain::{FastWindingField, WindingField};
use inrs::prelude::*;
use inrs::{Domain, Point};

use super::BenchOptions;
use super::peers::{SHAPES, grid_points, load_shape};
use super::point_sets::{near_points, random_points};

/// The query sets' seed (issue 52's rows).
const SEED: u64 = 52;
/// Points per set.
const POINTS: usize = 100_000;
/// A far point is at least this fraction of the diagonal from every piece's control box.
const FAR: f64 = 0.05;

/// The far set: the first `n` random points (of `10 n` drawn) at least [`FAR`] of the diagonal
/// from every piece's control box.
fn far_points(d: &Domain, n: usize) -> Vec<Point> {
    let boxes: Vec<(Point, Point)> = d
        .bezier_pieces()
        .into_iter()
        .map(|(_, b)| {
            let p = b.control_points();
            p.iter().fold((p[0], p[0]), |(lo, hi), x| {
                (
                    Point::new(lo.x.min(x.x), lo.y.min(x.y)),
                    Point::new(hi.x.max(x.x), hi.y.max(x.y)),
                )
            })
        })
        .collect();
    let far = FAR * d.bounding_box().diagonal();
    random_points(d, 10 * n, SEED)
        .into_iter()
        .filter(|q| {
            boxes.iter().all(|(lo, hi)| {
                let dx = (lo.x - q.x).max(q.x - hi.x).max(0.0);
                let dy = (lo.y - q.y).max(q.y - hi.y).max(0.0);
                dx * dx + dy * dy >= far * far
            })
        })
        .take(n)
        .collect()
}

/// Points on the curves: every piece's ends and its points at parameters `k / 16`.
fn on_curve_points(d: &Domain) -> Vec<Point> {
    d.bezier_pieces()
        .into_iter()
        .flat_map(|(_, b)| {
            let (t0, t1) = b.param_range();
            let mut pts = vec![b.start_point(), b.end_point()];
            pts.extend((1..16).map(|k| b.point_at(t0 + (t1 - t0) * k as f64 / 16.0)));
            pts
        })
        .collect()
}

/// Seconds this thread has run on a CPU (`/proc/thread-self/schedstat`, nanoseconds), `None`
/// where the kernel does not report it.
fn thread_cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: u64 = s.split_whitespace().next()?.parse().ok()?;
    Some(ns as f64 * 1e-9)
}

/// A timed run repeats the task until it takes at least this many seconds: the kernel may count
/// a thread's CPU time by the scheduler's tick (4 ms here), so short runs would read 0 or 4 ms.
const MIN_RUN: f64 = 0.25;

/// The median over `reps` runs of `f` of the seconds per call of `f` the thread spent on a CPU
/// (each run calls `f` enough times to last [`MIN_RUN`], after untimed calls as long), or of the
/// wall time where that is not reported. On a shared machine the wall time of a
/// single-threaded run counts the spells other processes hold the core; its CPU time does not.
fn median_cpu_time(reps: usize, mut f: impl FnMut()) -> f64 {
    let start = std::time::Instant::now();
    let mut calls = 0usize;
    while calls == 0 || start.elapsed().as_secs_f64() < MIN_RUN {
        f();
        calls += 1;
    }
    let mut t: Vec<f64> = (0..reps.max(1))
        .map(|_| {
            let (wall, cpu) = (std::time::Instant::now(), thread_cpu_seconds());
            for _ in 0..calls {
                f();
            }
            let seconds = match (cpu, thread_cpu_seconds()) {
                (Some(a), Some(b)) => b - a,
                _ => wall.elapsed().as_secs_f64(),
            };
            seconds / calls as f64
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// FNV-1a over the values' bits.
fn hash_bits(values: &[f64], mut h: u64) -> u64 {
    for v in values {
        for byte in v.to_bits().to_le_bytes() {
            h = (h ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    h
}

const FNV_START: u64 = 0xcbf2_9ce4_8422_2325;

/// The section: one row per shape.
pub(super) fn section(md: &mut String, root: &Path, o: &BenchOptions) -> Result<(), String> {
    let reps = o.reps.min(7);
    let _ = writeln!(
        md,
        "\n### Winding field near the curves against far from them (`fixtures/axom-contours/`)\n\n\
         Microseconds per point of `FastWindingField::winding_numbers` on one thread, warm field \
         (hierarchies built), median of {reps} runs (each of 0.25 s at least) of the thread's time on a CPU \
         (`/proc/thread-self/schedstat`; wall time where not reported). Near: `near_points(d, {POINTS}, {SEED})` \
         (1e-2..1e-10 of the diagonal from the curves); far: the first {POINTS} points of \
         `random_points(d, {}, {SEED})` at least {FAR} of the diagonal from every piece's \
         control box; random: `random_points(d, {POINTS}, {SEED})`. Goal: near / far <= 3 (near / random beside it: the random set's cost is the far-field cost of issue 52's row). \
         Bits: FNV-1a of the values' bits (near, far, random, a 300 x 300 grid, points on the \
         curves), from a fresh field and from a warm one.\n",
        10 * POINTS
    );
    let _ = writeln!(
        md,
        "| shape | pieces | near us | far us (points) | random us | near / far | near / random | bits fresh | bits warm |"
    );
    let _ = writeln!(
        md,
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | --- | --- |"
    );
    for (name, _) in SHAPES {
        let d = load_shape(root, name)?;
        let field = WindingField::new(&d, inrs::contain::DEFAULT_RELATIVE_TOLERANCE)
            .map_err(|e| e.to_string())?;
        let near = near_points(&d, POINTS, SEED);
        let far = far_points(&d, POINTS);
        let random = random_points(&d, POINTS, SEED);
        let sets = [
            near.clone(),
            far.clone(),
            random.clone(),
            grid_points(&d, 300),
            on_curve_points(&d),
        ];
        let bits = |fast: &FastWindingField| {
            sets.iter()
                .fold(FNV_START, |h, s| hash_bits(&fast.winding_numbers(s), h))
        };
        let fresh = bits(&FastWindingField::new(&field));
        let fast = FastWindingField::new(&field);
        let _ = bits(&fast);
        let warm = bits(&fast);
        let mut us = [0.0; 3];
        for (u, pts) in us.iter_mut().zip([&near, &far, &random]) {
            let t = median_cpu_time(reps, || {
                std::hint::black_box(fast.winding_numbers(pts));
            });
            *u = t / pts.len().max(1) as f64 * 1e6;
        }
        let [near_us, far_us, random_us] = us;
        let row = format!(
            "| {name} | {} | {near_us:.3} | {far_us:.3} ({}) | {random_us:.3} | {:.2} | {:.2} | {fresh:016x} | {warm:016x} |",
            field.pieces().len(),
            far.len(),
            near_us / far_us,
            near_us / random_us,
        );
        println!("{row}");
        let _ = writeln!(md, "{row}");
    }
    Ok(())
}
