//! Generalized winding numbers: the accelerated field against the reference on the 500-curve
//! flower, and the GWN paper's Fig. 15 (curve evaluations per query) and Fig. 14
//! (misclassifications of fixed linearisations).

use std::fmt::Write as _;
use std::time::Instant;

use inrs::contain::baselines::{FlattenedPolygon, WindingAlgorithm, halton_points};
use inrs::contain::{FastWindingField, QueryStats, WindingField};
use inrs::{BoundingBox, Classifier, ContainOptions, Domain, Location, Method, Point};

use super::{BenchOptions, median_time};

/// Accelerated versus reference winding numbers on the 500-curve flower.
pub(super) fn flower(md: &mut String, d: &Domain, o: &BenchOptions) -> Result<(), String> {
    let field = WindingField::new(d, inrs::contain::DEFAULT_RELATIVE_TOLERANCE)
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
        "\nGeneralized winding numbers, 500-curve flower (`fixtures/synthetic/flower500.json`), \
         {n} Halton points of its box; million queries per second.\n"
    );
    let _ = writeln!(
        md,
        "| reference (per curve) | accelerated build | accelerated 1 thread | vs reference | \
         accelerated parallel |"
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

/// Uniform pseudo-random points in a box (the test kit's seeded generator, fixed seed, so
/// every run measures the same points).
pub(super) fn uniform_points(n: usize, b: BoundingBox) -> Vec<Point> {
    let mut rng = rs_testkit::XorShift64::new(0x9E37_79B9_7F4A_7C15);
    (0..n)
        .map(|_| Point::new(rng.uniform(b.min.x, b.max.x), rng.uniform(b.min.y, b.max.y)))
        .collect()
}

/// The GWN paper's comparisons on `leaf_cubic`, with uniform random points of its box grown by
/// 5%.
pub(super) fn paper_figures(md: &mut String, d: &Domain, o: &BenchOptions) -> Result<(), String> {
    let n = if o.quick { 20_000 } else { 250_000 };
    let pad = 0.05 * d.bounding_box().diagonal();
    let pts = uniform_points(n, d.bounding_box().grown_by(pad));
    evaluations_per_query(md, d, &pts)?;
    fixed_linearisations(md, d, &pts)
}

/// Upper ends of the histogram buckets of curve evaluations per query.
const BUCKETS: [usize; 9] = [1, 2, 4, 8, 16, 32, 64, 128, usize::MAX];

/// The bucket labels: `<= 1`, `2`, `3-4`, ..., `> 128`.
fn bucket_labels() -> Vec<String> {
    BUCKETS
        .iter()
        .enumerate()
        .map(|(i, &b)| match (i, b) {
            (0, _) => format!("<= {b}"),
            (_, usize::MAX) => format!("> {}", BUCKETS[i - 1]),
            _ if BUCKETS[i - 1] + 1 == b => b.to_string(),
            _ => format!("{}-{}", BUCKETS[i - 1] + 1, b),
        })
        .collect()
}

/// Fig. 15: how many sub-curves each per-curve algorithm examines per query, inside the same
/// closure framework; the three must agree on the winding numbers.
fn evaluations_per_query(md: &mut String, d: &Domain, pts: &[Point]) -> Result<(), String> {
    let field = WindingField::new(d, inrs::contain::DEFAULT_RELATIVE_TOLERANCE)
        .map_err(|e| e.to_string())?;
    let n = pts.len();
    let _ = writeln!(
        md,
        "\n### Curve evaluations per query (GWN paper Fig. 15)\n\n`leaf_cubic` ({} rational \
         cubic pieces), {n} uniform random points of its box grown by 5%: number of queries by \
         evaluations (sub-curves examined) over all pieces, each algorithm inside the same \
         closure framework.\n",
        field.pieces().len()
    );
    let labels = bucket_labels();
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
    let algorithms = [
        ("adaptive GWN", WindingAlgorithm::Adaptive),
        ("binary search", WindingAlgorithm::BinarySearch),
        ("Bezier clipping", WindingAlgorithm::BezierClipping),
    ];
    let mut values: Vec<Vec<f64>> = Vec::new();
    for (label, alg) in algorithms {
        let mut hist = [0usize; BUCKETS.len()];
        let (mut total, mut max) = (0usize, 0usize);
        let start = Instant::now();
        let mut w = Vec::with_capacity(n);
        for &q in pts {
            let mut s = QueryStats::default();
            w.push(field.winding_number_with(q, alg, &mut s));
            let e = s.curve_evaluations;
            total += e;
            max = max.max(e);
            hist[BUCKETS
                .iter()
                .position(|&b| e <= b)
                .unwrap_or(BUCKETS.len() - 1)] += 1;
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
    let disagree = values[1..]
        .iter()
        .map(|v| {
            values[0]
                .iter()
                .zip(v)
                .filter(|(a, b)| (**a - **b).abs() > 1e-6)
                .count()
        })
        .max()
        .unwrap_or(0);
    let _ = writeln!(
        md,
        "\nThe three agree on the winding number (to 1e-6) at all but {disagree} of the {n} points."
    );
    Ok(())
}

/// Fig. 14: every piece replaced by k equal-parameter chords, against the exact containment.
fn fixed_linearisations(md: &mut String, d: &Domain, pts: &[Point]) -> Result<(), String> {
    let c = Classifier::new(d, ContainOptions::default()).map_err(|e| e.to_string())?;
    let exact = c.locate_all_with(Method::Fast, pts);
    let _ = writeln!(
        md,
        "\n### Misclassifications of fixed linearisations (GWN paper Fig. 14)\n\n`leaf_cubic`, \
         the same {} points: each piece replaced by k equal-parameter chords; points whose \
         containment differs from the exact answer (boundary points excluded).\n",
        pts.len()
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
        let lin = FlattenedPolygon::uniform(d, k).classify(pts);
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
