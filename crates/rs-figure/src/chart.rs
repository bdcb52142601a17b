//! Charts: figures whose two axes have their own scales (times against sizes, speed-ups by
//! case), with axis titles and optionally logarithmic axes.

use rs_spline::BoundingBox;

use crate::{AXIS_ROOM, ChartAxis, Figure};

/// Pixels left of a chart's plot area: tick labels and the vertical axis title.
const CHART_LEFT: f64 = AXIS_ROOM + 18.0;

impl Figure {
    /// A chart: `data` shown on a plot area `width x height` pixels, each axis at its own scale,
    /// with the axes' titles and tick labels (logarithmic axes take `log10` of the data).
    pub fn chart(data: BoundingBox, width: f64, height: f64, x: ChartAxis, y: ChartAxis) -> Self {
        let mut fig = Figure::new(data, width);
        let data = fig.data_box();
        let size = |v: f64| if v.is_finite() { v.max(50.0) } else { 400.0 };
        let (width, height) = (size(width), size(height));
        fig.scale = width / data.width();
        fig.scale_y = height / data.height();
        fig.plot_width = width;
        fig.plot_height = height;
        fig.left = CHART_LEFT;
        fig.chart_axes = Some((x, y));
        fig
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Style;
    use rs_spline::Point;

    #[test]
    fn a_log_log_chart_has_power_ticks_titles_and_its_own_scales() {
        let data = BoundingBox::from_point(Point::new(3.0, -6.0)).including(Point::new(6.0, 0.0));
        let mut fig = Figure::chart(
            data,
            300.0,
            200.0,
            ChartAxis::log10("points N"),
            ChartAxis::log10("seconds"),
        );
        // x spans 3 decades over 300 px, y 6 decades over 200 px.
        let (a, b) = (
            fig.to_pixels(Point::new(3.0, -6.0)),
            fig.to_pixels(Point::new(6.0, 0.0)),
        );
        assert!((b.0 - a.0 - 300.0).abs() < 1e-9 && (a.1 - b.1 - 200.0).abs() < 1e-9);
        fig.polyline(
            &[Point::new(3.0, -5.0), Point::new(6.0, -2.0)],
            &Style::stroke("#1f77b4", 1.5).labelled("method"),
        );
        fig.caption("Times.");
        let svg = fig.to_svg();
        let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
        let titles: Vec<&str> = doc
            .descendants()
            .filter(|n| n.attribute("class") == Some("axis-title"))
            .filter_map(|n| n.text())
            .collect();
        assert_eq!(titles, ["points N", "seconds"]);
        // Ticks 10^3 .. 10^6 on x, 10^-6 .. 10^0 on y: the exponents as superscripts.
        let exponents: Vec<&str> = doc
            .descendants()
            .filter(|n| n.has_tag_name("tspan"))
            .filter_map(|n| n.text())
            .collect();
        for e in ["3", "4", "5", "6", "-6", "-3", "0"] {
            assert!(exponents.contains(&e), "{e} in {exponents:?}");
        }
        assert!(svg.contains(">method</text>") && svg.contains("Times."));
    }

    #[test]
    fn log_ticks_thin_out_on_long_axes_and_refuse_bad_ranges() {
        let a = ChartAxis::log10("");
        assert_eq!(a.ticks(-0.5, 2.5), [0.0, 1.0, 2.0]);
        assert_eq!(a.ticks(0.0, 20.0).len(), 11);
        assert!(a.ticks(1.0, 1.0).is_empty() && a.ticks(f64::NAN, 2.0).is_empty());
        let c = ChartAxis::categories("", &["a", "b<"]);
        assert_eq!(c.ticks(0.0, 2.0), [0.5, 1.5]);
        assert_eq!(c.label(1.5, 1.0), "b&lt;");
    }
}
