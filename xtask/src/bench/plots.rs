//! Companion plots of the benchmark report, written next to it as SVG: time against N per
//! method on log-log axes (one plot per domain), and speed-up bars.

use std::path::{Path, PathBuf};

use inrs::{BoundingBox, Point};
use rs_figure::{ChartAxis, Figure, Marker, Style, text_width};

use super::paper::PaperTimings;

/// Line colours of the methods (a colour-blind-safe palette) and their legend names.
const METHODS: [(&str, &str, &str); 6] = [
    ("inrs1", "#9e9e9e", "inRS1 (each point against each box)"),
    (
        "inrs2",
        "#1f77b4",
        "inRS2 (points sorted, binary search per box)",
    ),
    (
        "polygon",
        "#d62728",
        "polygon within 1e-10 (INPOLY2 strategy)",
    ),
    (
        "locator",
        "#2ca02c",
        "grid locator, build included, 1 thread",
    ),
    ("locator-parallel", "#17becf", "grid locator, all threads"),
    ("gwn", "#ff7f0e", "rounded generalized winding number"),
];

/// Time against N for every method on `domain`, log-log.
pub(super) fn times_figure(t: &PaperTimings, domain: &str) -> Option<Figure> {
    let series: Vec<(&str, &str, &str, Vec<Point>)> = METHODS
        .iter()
        .map(|&(path, colour, name)| {
            let pts = t
                .rows
                .iter()
                .filter(|((d, _, p), _)| d == domain && *p == path)
                .map(|((_, n, _), r)| Point::new((*n as f64).log10(), r.seconds.log10()))
                .collect();
            (path, colour, name, pts)
        })
        .collect();
    let data =
        BoundingBox::from_points(series.iter().flat_map(|s| s.3.iter().copied()))?.grown_by(0.15);
    let mut fig = Figure::chart(
        data,
        360.0,
        260.0,
        ChartAxis::log10("Halton points N"),
        ChartAxis::log10("seconds (median)"),
    );
    for (_, colour, name, pts) in &series {
        if pts.is_empty() {
            continue;
        }
        let style = Style::stroke(colour, 1.6)
            .with_marker(Marker::Dot(2.5))
            .labelled(name);
        fig.polyline(pts, &style);
        for &p in pts {
            fig.mark(p, &Style::fill(colour).with_marker(Marker::Dot(2.5)));
        }
    }
    fig.caption(&format!(
        "{domain}: time to classify N Halton points of the bounding box, per method (log-log; \
         lower is faster). inRS1 and the winding number stop at 10^5 points unless --full."
    ));
    Some(fig)
}

/// Bars of `log10` ratios by category: `groups[i] = (category, [(value, series)])`, one
/// colour per series, with the ratio written over each bar.
fn bars_figure(
    categories: &[&str],
    series: &[(&str, &str)],
    values: &[Vec<f64>],
    y_title: &str,
    caption: &str,
) -> Option<Figure> {
    let top = values
        .iter()
        .flatten()
        .filter(|v| v.is_finite() && **v > 0.0)
        .map(|v| v.log10())
        .fold(f64::NEG_INFINITY, f64::max);
    if !top.is_finite() {
        return None;
    }
    let lo = values
        .iter()
        .flatten()
        .filter(|v| v.is_finite() && **v > 0.0)
        .map(|v| v.log10())
        .fold(0.0f64, f64::min)
        .floor();
    let data = BoundingBox::from_point(Point::new(0.0, lo)).including(Point::new(
        categories.len() as f64,
        top.ceil().max(top + 0.3),
    ));
    // Each group is wide enough for its label.
    let longest = categories.iter().map(|c| text_width(c)).fold(0.0, f64::max);
    let per_group = (longest + 16.0).max(90.0);
    let mut fig = Figure::chart(
        data,
        (per_group * categories.len() as f64).max(240.0),
        240.0,
        ChartAxis::categories("", categories),
        ChartAxis::log10(y_title),
    );
    let width = 0.8 / series.len().max(1) as f64;
    for (c, row) in values.iter().enumerate() {
        for (s, &v) in row.iter().enumerate() {
            if !(v.is_finite() && v > 0.0) {
                continue;
            }
            let x = c as f64 + 0.1 + s as f64 * width;
            let (name, colour) = series[s];
            let style = Style::stroke("#333333", 0.5)
                .with_fill(colour, 1.0)
                .labelled(name);
            let bar = BoundingBox::from_point(Point::new(x, lo))
                .including(Point::new(x + width, v.log10()));
            fig.rect(bar, &style);
            let (px, py) = fig.to_pixels(Point::new(x + 0.5 * width, v.log10()));
            fig.raw(
                &format!(
                    r##"<text x="{px:.1}" y="{:.1}" font-size="9" text-anchor="middle" fill="#222222">{}</text>"##,
                    py - 3.0,
                    if v >= 10.0 { format!("{v:.0}x") } else { format!("{v:.1}x") }
                ),
                None,
            );
        }
    }
    fig.caption(caption);
    Some(fig)
}

/// Speed-ups at the largest N per domain: polygon / inRS2 and inRS2 / locator.
pub(super) fn paper_speedups_figure(t: &PaperTimings, names: &[&str], n: usize) -> Option<Figure> {
    let seconds = |d: &str, path: &str| t.rows.get(&(d.to_string(), n, path)).map(|r| r.seconds);
    let ratio = |d: &str, a: &str, b: &str| match (seconds(d, a), seconds(d, b)) {
        (Some(a), Some(b)) if b > 0.0 => a / b,
        _ => f64::NAN,
    };
    let values: Vec<Vec<f64>> = names
        .iter()
        .map(|d| {
            vec![
                ratio(d, "polygon", "inrs2"),
                ratio(d, "inrs2", "locator"),
                ratio(d, "inrs2", "locator-parallel"),
            ]
        })
        .collect();
    bars_figure(
        names,
        &[
            ("polygon within 1e-10 / inRS2", "#d62728"),
            ("inRS2 / grid locator (build included)", "#2ca02c"),
            ("inRS2 / grid locator, all threads", "#17becf"),
        ],
        &values,
        "speed-up",
        &format!(
            "Speed-ups at N = {n} Halton points (ratios of median times measured in the same run; \
             above 1: the second method is faster)."
        ),
    )
}

/// Speed-ups of our winding numbers over kurbo's on the GWN paper's closed shapes.
pub(super) fn shapes_speedups_figure(rows: &[(String, f64, f64)]) -> Option<Figure> {
    let names: Vec<&str> = rows.iter().map(|r| r.0.as_str()).collect();
    let values: Vec<Vec<f64>> = rows.iter().map(|r| vec![r.1, r.2]).collect();
    bars_figure(
        &names,
        &[
            ("kurbo / inrs per-curve field", "#1f77b4"),
            ("kurbo / inrs fast field (BVH)", "#ff7f0e"),
        ],
        &values,
        "speed-up over kurbo",
        "Winding numbers on the GWN paper's closed shapes: kurbo's time per query over ours \
         (median per-query times on one thread, same run, same points).",
    )
}

/// Writes `fig` as `dir/name`; returns the path.
pub(super) fn save(dir: &Path, name: &str, fig: &Figure) -> Result<PathBuf, String> {
    let path = dir.join(name);
    std::fs::write(&path, fig.to_svg()).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::super::paper::Row;
    use super::*;

    fn timings() -> PaperTimings {
        let mut rows = BTreeMap::new();
        for d in ["s3", "s4"] {
            for (k, n) in [1_000usize, 10_000, 100_000].into_iter().enumerate() {
                for (m, (path, _, _)) in METHODS.iter().enumerate() {
                    let seconds = 1e-5 * 10f64.powi(k as i32) * (m + 1) as f64;
                    rows.insert((d.to_string(), n, *path), Row { seconds, inside: 0 });
                }
            }
        }
        PaperTimings::from_rows(rows)
    }

    #[test]
    fn time_plots_draw_every_method_on_log_axes() {
        let fig = times_figure(&timings(), "s3").unwrap();
        let svg = fig.to_svg();
        rs_testkit::assert_figure(&svg, "s3: time to classify", "times plot");
        for (_, _, name) in METHODS {
            assert!(svg.contains(name), "{name}");
        }
        // Three sizes per method: a polyline of three points each.
        assert_eq!(svg.matches("<polyline").count(), METHODS.len());
        assert!(times_figure(&timings(), "unknown").is_none());
    }

    #[test]
    fn speedup_bars_carry_their_ratios() {
        let t = timings();
        let svg = paper_speedups_figure(&t, &["s3", "s4"], 100_000)
            .unwrap()
            .to_svg();
        rs_testkit::assert_figure(&svg, "Speed-ups at N = 100000", "speed-up bars");
        // polygon (method 3) over inRS2 (method 2) = 1.5; inRS2 over the locator (4) = 0.5.
        assert!(svg.contains(">1.5x<") && svg.contains(">0.5x<"), "{svg}");
        let svg = shapes_speedups_figure(&[("fish".into(), 60.0, 300.0)])
            .unwrap()
            .to_svg();
        rs_testkit::assert_figure(&svg, "kurbo's time per query", "shape bars");
        assert!(svg.contains(">60x<") && svg.contains(">300x<") && svg.contains(">fish<"));
    }
}
