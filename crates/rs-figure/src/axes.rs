//! Coordinate axes along the bottom and left of the plot area, with "nice" ticks.

use std::fmt::Write;

use rs_spline::Point;

use crate::{FONT, Figure, escape};

/// About `target` tick values covering `[lo, hi]` at a step of 1, 2 or 5 times a power of ten
/// (Heckbert's nice numbers), ascending and inside the interval; empty for an interval that
/// is not finite and increasing.
pub fn nice_ticks(lo: f64, hi: f64, target: usize) -> Vec<f64> {
    if !(lo.is_finite() && hi.is_finite() && hi > lo) {
        return Vec::new();
    }
    let raw = (hi - lo) / target.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * mag)
        .find(|&s| s >= raw)
        .unwrap_or(10.0 * mag);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    // At most a few dozen ticks: the step is at least the interval over `target`.
    (first..=last.min(first + 4 * target as i64 + 4))
        .map(|k| {
            let v = k as f64 * step;
            // Snap -0 and rounding residue of exact multiples.
            if v.abs() < 1e-9 * step { 0.0 } else { v }
        })
        .collect()
}

/// A tick label: the shortest decimal that shows the value at the tick step's precision.
pub(crate) fn label(v: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    if (1e-4..1e6).contains(&v.abs()) || v == 0.0 {
        format!("{v:.decimals$}")
    } else {
        format!("{v:.1e}")
    }
}

/// How an axis maps data to labels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AxisScale {
    /// Data as they are, ticks at "nice" values.
    Linear,
    /// The data are `log10` of the quantity: ticks at the integers, labelled `10^k`.
    Log10,
    /// Named categories: category `i` spans `[i, i + 1]`, labelled at its middle.
    Categories,
}

/// One axis of a chart: its title and scale (a coordinate axis of the plane is
/// [`rs_spline::Axis`]).
#[derive(Clone, Debug, PartialEq)]
pub struct ChartAxis {
    /// The title, written along the axis.
    pub title: String,
    /// Linear, logarithmic or categories.
    pub scale: AxisScale,
    /// The categories' names (for [`AxisScale::Categories`]).
    pub categories: Vec<String>,
}

impl ChartAxis {
    /// A linear axis titled `title`.
    pub fn linear(title: &str) -> Self {
        Self {
            title: title.to_string(),
            scale: AxisScale::Linear,
            categories: Vec::new(),
        }
    }

    /// A logarithmic axis titled `title` (plot `log10` of the values).
    pub fn log10(title: &str) -> Self {
        Self {
            title: title.to_string(),
            scale: AxisScale::Log10,
            categories: Vec::new(),
        }
    }

    /// An axis of named categories (place category `i` over `[i, i + 1]`).
    pub fn categories(title: &str, names: &[&str]) -> Self {
        Self {
            title: title.to_string(),
            scale: AxisScale::Categories,
            categories: names.iter().map(|s| s.to_string()).collect(),
        }
    }

    /// The tick values of this axis over `[lo, hi]`.
    pub(crate) fn ticks(&self, lo: f64, hi: f64) -> Vec<f64> {
        match self.scale {
            AxisScale::Linear => nice_ticks(lo, hi, 5),
            AxisScale::Log10 => {
                if !(lo.is_finite() && hi.is_finite() && hi > lo) {
                    return Vec::new();
                }
                let (first, last) = (lo.ceil() as i64, hi.floor() as i64);
                // Every power of ten, or every other one on a long axis.
                let every = if last - first > 8 { 2 } else { 1 };
                (first..=last.min(first + 40))
                    .filter(|k| k % every == 0)
                    .map(|k| k as f64)
                    .collect()
            }
            AxisScale::Categories => (0..self.categories.len())
                .map(|i| i as f64 + 0.5)
                .filter(|&c| c >= lo && c <= hi)
                .collect(),
        }
    }

    /// The SVG text content of the label of tick `v` (`step` apart from its neighbours).
    pub(crate) fn label(&self, v: f64, step: f64) -> String {
        match self.scale {
            AxisScale::Linear => label(v, step),
            AxisScale::Log10 => format!(
                r#"10<tspan dy="-5" font-size="8">{}</tspan>"#,
                v.round() as i64
            ),
            AxisScale::Categories => {
                let i = v.floor().max(0.0) as usize;
                crate::escape(self.categories.get(i).map_or("", String::as_str))
            }
        }
    }
}

/// The axes' SVG: a frame round the plot area, ticks and labels on the bottom and left.
pub(crate) fn axes_svg(fig: &Figure) -> String {
    let b = fig.data_box();
    let (x0, y0) = fig.to_pixels(Point::new(b.min.x, b.min.y));
    let (x1, y1) = fig.to_pixels(Point::new(b.max.x, b.max.y));
    let mut out = String::from(r##"<g class="axes" stroke="#444444" stroke-width="0.8">"##);
    let _ = write!(
        out,
        r##"<rect x="{x0:.2}" y="{y1:.2}" width="{:.2}" height="{:.2}" fill="none"/>"##,
        x1 - x0,
        y0 - y1
    );
    let linear = ChartAxis::linear("");
    let (ax, ay) = match &fig.chart_axes {
        Some((x, y)) => (x, y),
        None => (&linear, &linear),
    };
    let xt = ax.ticks(b.min.x, b.max.x);
    let yt = ay.ticks(b.min.y, b.max.y);
    let step = |t: &[f64]| if t.len() > 1 { t[1] - t[0] } else { 1.0 };
    let (sx, sy) = (step(&xt), step(&yt));
    for &x in &xt {
        let (px, _) = fig.to_pixels(Point::new(x, b.min.y));
        let _ = write!(
            out,
            r##"<line x1="{px:.2}" y1="{y0:.2}" x2="{px:.2}" y2="{:.2}"/><text x="{px:.2}" y="{:.2}" font-size="{}" text-anchor="middle" stroke="none" fill="#222222">{}</text>"##,
            y0 + 4.0,
            y0 + 16.0,
            FONT - 2.0,
            ax.label(x, sx)
        );
    }
    for &y in &yt {
        let (_, py) = fig.to_pixels(Point::new(b.min.x, y));
        let _ = write!(
            out,
            r##"<line x1="{:.2}" y1="{py:.2}" x2="{x0:.2}" y2="{py:.2}"/><text x="{:.2}" y="{:.2}" font-size="{}" text-anchor="end" stroke="none" fill="#222222">{}</text>"##,
            x0 - 4.0,
            x0 - 6.0,
            py + 3.5,
            FONT - 2.0,
            ay.label(y, sy)
        );
    }
    if let Some((x, y)) = &fig.chart_axes {
        let _ = write!(
            out,
            r##"<text class="axis-title" x="{:.2}" y="{:.2}" font-size="{FONT}" text-anchor="middle" stroke="none" fill="#222222">{}</text>"##,
            0.5 * (x0 + x1),
            y0 + 34.0,
            escape(&x.title)
        );
        let (cx, cy) = (14.0, 0.5 * (y0 + y1));
        let _ = write!(
            out,
            r##"<text class="axis-title" x="{cx:.2}" y="{cy:.2}" font-size="{FONT}" text-anchor="middle" stroke="none" fill="#222222" transform="rotate(-90 {cx:.2} {cy:.2})">{}</text>"##,
            escape(&y.title)
        );
    }
    out.push_str("</g>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_nice_and_inside() {
        let close = |a: &[f64], b: &[f64]| {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
        };
        assert!(close(
            &nice_ticks(0.0, 1.0, 5),
            &[0.0, 0.2, 0.4, 0.6, 0.8, 1.0]
        ));
        assert!(close(&nice_ticks(-3.7, 12.2, 5), &[0.0, 5.0, 10.0]));
        assert!(close(
            &nice_ticks(-1.0, 1.0, 4),
            &[-1.0, -0.5, 0.0, 0.5, 1.0]
        ));
        assert!(nice_ticks(1.0, 1.0, 5).is_empty());
        assert!(nice_ticks(0.0, f64::INFINITY, 5).is_empty());
        assert!(nice_ticks(0.0, 1e300, 5).len() <= 24);
    }

    #[test]
    fn labels_show_the_step_precision() {
        assert_eq!(label(0.4, 0.2), "0.4");
        assert_eq!(label(10.0, 5.0), "10");
        assert_eq!(label(2.5e-7, 1e-7), "2.5e-7");
    }
}
