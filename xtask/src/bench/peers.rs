//! Generalized winding numbers on the GWN paper's five shapes (`fixtures/axom-contours/`),
//! against kurbo and lyon measured in the same process on the same curves and points.
//!
//! kurbo (`BezPath::winding`, f64) and lyon (`path_winding_number_at_position`, f32, curves
//! flattened within a tolerance) answer integer winding numbers of closed paths, so they run on
//! the three closed shapes only; bubble and twirl are open curve collections whose winding
//! numbers are fractional.

use std::fmt::Write as _;
use std::path::Path;

use inrs::contain::{FastWindingField, QueryStats, WindingField, curve_winding_number};
use inrs::io::svg::{OpenSubpaths, domain_from_svg_file_with};
use inrs::prelude::*;
use inrs::{Domain, Point, RationalBezier};
use lyon_algorithms::hit_test::path_winding_number_at_position;
use lyon_algorithms::math::point as lyon_point;
use lyon_algorithms::path::Path as LyonPath;

use super::{BenchOptions, median_time};

/// The five shapes, and whether their paths are closed.
pub(super) const SHAPES: [(&str, bool); 5] = [
    ("butterfly", true),
    ("rose", true),
    ("fish", true),
    ("bubble", false),
    ("twirl", false),
];

/// lyon's flattening tolerance, relative to the shape's bounding-box diagonal (its f32
/// coordinates resolve about 1e-7 of the size).
const LYON_RELATIVE_TOLERANCE: f32 = 1e-5;

/// A shape read as drawn (open paths stay open).
pub(super) fn load_shape(root: &Path, name: &str) -> Result<Domain, String> {
    let path = root.join(format!("fixtures/axom-contours/{name}.svg"));
    domain_from_svg_file_with(&path, OpenSubpaths::Keep)
        .map_err(|e| format!("{}: {e}", path.display()))
}

/// A `k x k` grid over the box grown by 5% (the paper's query protocol).
pub(super) fn grid_points(d: &Domain, k: usize) -> Vec<Point> {
    let b = d
        .bounding_box()
        .grown_by(0.05 * d.bounding_box().diagonal());
    let step = |i: usize| (i as f64 + 0.5) / k as f64;
    (0..k * k)
        .map(|i| {
            Point::new(
                b.min.x + step(i % k) * b.width(),
                b.min.y + step(i / k) * b.height(),
            )
        })
        .collect()
}

/// Subpaths of polynomial pieces: runs of pieces each starting where the previous one ends.
fn subpaths(d: &Domain) -> Vec<Vec<RationalBezier>> {
    let mut out: Vec<Vec<RationalBezier>> = Vec::new();
    for (_, b) in d.bezier_pieces() {
        match out.last_mut() {
            Some(run) if run.last().is_some_and(|p| p.end_point() == b.start_point()) => {
                run.push(b)
            }
            _ => out.push(vec![b]),
        }
    }
    out
}

fn kurbo_path(d: &Domain) -> kurbo::BezPath {
    let kp = |p: Point| kurbo::Point::new(p.x, p.y);
    let mut path = kurbo::BezPath::new();
    for run in subpaths(d) {
        path.move_to(kp(run[0].start_point()));
        for b in &run {
            let c = b.control_points();
            match c.len() {
                2 => path.line_to(kp(c[1])),
                3 => path.quad_to(kp(c[1]), kp(c[2])),
                _ => path.curve_to(kp(c[1]), kp(c[2]), kp(c[3])),
            }
        }
        path.close_path();
    }
    path
}

fn lyon_path(d: &Domain) -> LyonPath {
    let lp = |p: Point| lyon_point(p.x as f32, p.y as f32);
    let mut builder = LyonPath::builder();
    for run in subpaths(d) {
        builder.begin(lp(run[0].start_point()));
        for b in &run {
            let c = b.control_points();
            match c.len() {
                2 => builder.line_to(lp(c[1])),
                3 => builder.quadratic_bezier_to(lp(c[1]), lp(c[2])),
                _ => builder.cubic_bezier_to(lp(c[1]), lp(c[2]), lp(c[3])),
            };
        }
        builder.end(true);
    }
    builder.build()
}

/// The paper's direct algorithm is timed on every this-many-th grid point (on the large shapes
/// it takes about as long as kurbo per query).
const DIRECT_STRIDE: usize = 10;

/// Build time and microseconds per query of one method.
struct Timing {
    build: f64,
    per_query_us: f64,
}

fn time_method<T>(
    reps: usize,
    pts: &[Point],
    build: impl Fn() -> T,
    query: impl Fn(&T, Point) -> f64,
) -> (Timing, Vec<f64>) {
    time_all(reps, pts, build, |built, pts| {
        pts.iter().map(|&q| query(built, q)).collect()
    })
}

/// Build time and microseconds per query of a method answering all the points in one call.
fn time_all<T>(
    reps: usize,
    pts: &[Point],
    build: impl Fn() -> T,
    all: impl Fn(&T, &[Point]) -> Vec<f64>,
) -> (Timing, Vec<f64>) {
    let t_build = median_time(reps, || {
        std::hint::black_box(build());
    });
    let built = build();
    let mut values = Vec::new();
    let t = median_time(reps, || {
        values = all(&built, pts);
    });
    (
        Timing {
            build: t_build,
            per_query_us: t / pts.len() as f64 * 1e6,
        },
        values,
    )
}

/// Integer winding numbers of a peer that disagree with ours, after fixing the peer's sign
/// convention (y-down paths) from the first non-zero pair.
fn disagreements(ours: &[f64], peer: &[f64]) -> usize {
    let sign = ours
        .iter()
        .zip(peer)
        .find(|(a, b)| a.round() != 0.0 && **b != 0.0)
        .map_or(1.0, |(a, b)| (a.round() * b).signum());
    ours.iter()
        .zip(peer)
        .filter(|(a, b)| a.round() != sign * **b)
        .count()
}

/// The five-shape table; returns, per closed shape, kurbo's time over our per-curve field's
/// and over our fast field's.
pub(super) fn shapes(
    md: &mut String,
    root: &Path,
    o: &BenchOptions,
) -> Result<Vec<(String, f64, f64)>, String> {
    let mut ratios = Vec::new();
    let k = if o.quick { 100 } else { 500 };
    let reps = o.reps.min(5);
    let _ = writeln!(
        md,
        "\n### Winding numbers on the GWN paper's shapes (`fixtures/axom-contours/`)\n\n\
         {k} x {k} grid over each shape's box grown by 5%; microseconds per query on one thread \
         (build times in ms), median of {reps} runs. kurbo: `BezPath::winding` (f64); lyon: \
         `path_winding_number_at_position` (f32, flattened within {LYON_RELATIVE_TOLERANCE:e} of \
         the diagonal); both only on closed shapes. Fast field: `winding_numbers` over all the \
         points (open chains' ends added for eight points at once); one at a time: \
         `winding_number` per point (the same values, bit for bit). Paper direct: the GWN \
         paper's algorithm curve by curve (`curve_winding_number` summed over the pieces: one \
         `atan2` per chord, the open chains' ends not shared), as the per-curve field computed \
         before it shared the fast field's chain-ends sum; timed on every {DIRECT_STRIDE}th \
         point of the grid. Ratios are peer time / inrs time.\n"
    );
    let _ = writeln!(
        md,
        "| shape | pieces | per-curve | fast field (build ms) | fast, one at a time | paper direct | kurbo | \
         lyon (build ms) | kurbo / per-curve | kurbo / fast | lyon / fast | per-curve / fast | paper direct / fast | max \\|w - per-curve\\| (fast, paper direct) | peer disagreements |"
    );
    let _ = writeln!(
        md,
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    );
    for (name, closed) in SHAPES {
        let d = load_shape(root, name)?;
        let pts = grid_points(&d, k);
        let (per_curve, w_ref) = time_method(
            reps,
            &pts,
            || WindingField::new(&d, inrs::contain::DEFAULT_RELATIVE_TOLERANCE),
            |f, q| f.as_ref().map_or(f64::NAN, |f| f.winding_number(q)),
        );
        let field = WindingField::new(&d, inrs::contain::DEFAULT_RELATIVE_TOLERANCE)
            .map_err(|e| e.to_string())?;
        let (fast_single, _) = time_method(
            reps,
            &pts,
            || FastWindingField::new(&field),
            |f, q| f.winding_number(q),
        );
        let (fast, w_fast) = time_all(
            reps,
            &pts,
            || FastWindingField::new(&field),
            |f, pts| f.winding_numbers(pts),
        );
        let sparse: Vec<Point> = pts.iter().step_by(DIRECT_STRIDE).copied().collect();
        let (direct, w_direct) = time_method(
            reps,
            &sparse,
            || (),
            |_, q| {
                let mut stats = QueryStats::default();
                field
                    .pieces()
                    .iter()
                    .map(|c| curve_winding_number(c, q, &mut stats))
                    .sum()
            },
        );
        let max_diff = w_ref
            .iter()
            .zip(&w_fast)
            .map(|(a, b)| (a - b).abs())
            .chain(
                w_ref
                    .iter()
                    .step_by(DIRECT_STRIDE)
                    .zip(&w_direct)
                    .map(|(a, b)| (a - b).abs()),
            )
            .fold(0.0, f64::max);
        let direct_ratio = direct.per_query_us / fast.per_query_us;
        let mut row = format!(
            "| {name} | {} | {:.3} | {:.3} ({:.2}) | {:.3} | {:.3} |",
            field.pieces().len(),
            per_curve.per_query_us,
            fast.per_query_us,
            fast.build * 1e3,
            fast_single.per_query_us,
            direct.per_query_us,
        );
        if closed {
            let (kurbo, w_kurbo) = time_method(
                reps,
                &pts,
                || kurbo_path(&d),
                |p, q| kurbo::Shape::winding(p, kurbo::Point::new(q.x, q.y)) as f64,
            );
            let tol = LYON_RELATIVE_TOLERANCE * d.bounding_box().diagonal() as f32;
            let (lyon, w_lyon) = time_method(
                reps,
                &pts,
                || lyon_path(&d),
                |p, q| {
                    path_winding_number_at_position(
                        &lyon_point(q.x as f32, q.y as f32),
                        p.iter(),
                        tol,
                    ) as f64
                },
            );
            ratios.push((
                name.to_string(),
                kurbo.per_query_us / per_curve.per_query_us,
                kurbo.per_query_us / fast.per_query_us,
            ));
            let _ = write!(
                row,
                " {:.3} | {:.3} ({:.2}) | {:.2} | {:.1} | {:.1} | {:.1} | {direct_ratio:.1} | {max_diff:.1e} | kurbo {}, lyon {} |",
                kurbo.per_query_us,
                lyon.per_query_us,
                lyon.build * 1e3,
                kurbo.per_query_us / per_curve.per_query_us,
                kurbo.per_query_us / fast.per_query_us,
                lyon.per_query_us / fast.per_query_us,
                per_curve.per_query_us / fast.per_query_us,
                disagreements(&w_ref, &w_kurbo),
                disagreements(&w_ref, &w_lyon),
            );
        } else {
            let _ = write!(
                row,
                " - | - | - | - | - | {:.1} | {direct_ratio:.1} | {max_diff:.1e} | - |",
                per_curve.per_query_us / fast.per_query_us
            );
        }
        let _ = writeln!(md, "{row}");
    }
    Ok(ratios)
}
