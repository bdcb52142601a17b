//! SVG figures of planar geometry, the one figure writer of the workspace: a [`Figure`] maps
//! a data box to pixels (`y` up in the data, down in SVG), collects curves (flattened to a
//! quarter pixel through [`Flatten`]), polylines, polygons, boxes and marks, and writes them
//! with coordinate axes, a legend naming every style that has a label, and a caption wrapped
//! to the figure's width.
//!
//! # Examples
//!
//! ```
//! use rs_figure::{Figure, Style};
//! use rs_spline::{Point, circle, prelude::*};
//!
//! let c = circle(Point::new(0.0, 0.0), 1.0).unwrap();
//! let mut fig = Figure::new(c.bounding_box(), 300.0);
//! fig.curve(&c, &Style::stroke("#000000", 1.5).labelled("boundary"));
//! fig.mark(Point::new(0.0, 0.0), &Style::fill("#d62728").labelled("centre"));
//! fig.caption("The unit circle and its centre.");
//! let svg = fig.to_svg();
//! assert!(svg.contains("The unit circle") && svg.contains("boundary"));
//! ```

mod axes;
mod chart;
mod raster;
mod style;

use std::fmt::Write;

use rs_spline::{BoundingBox, Flatten, Point, flatten_chain};

pub use axes::nice_ticks;
pub use axes::{AxisScale, ChartAxis};
pub use raster::{FieldImage, viridis};
pub use style::{Marker, Style};

/// Pixels between the plot area and the figure's edge on the left and bottom (room for tick
/// labels) and on the top and right.
const AXIS_ROOM: f64 = 46.0;
const EDGE: f64 = 12.0;
/// Caption and legend font size in pixels, and the width of one character as a fraction of
/// it (sans-serif average), used to wrap the caption and size the legend box.
const FONT: f64 = 12.0;
const CHAR_WIDTH: f64 = 0.56;

/// The estimated width in pixels of `text` in the caption and legend font (12 px sans-serif,
/// about 0.56 em a character): enough room for it, whatever the viewer's font.
pub fn text_width(text: &str) -> f64 {
    text.chars().count() as f64 * FONT * CHAR_WIDTH
}
/// Flattening tolerance of curves, in pixels.
const CURVE_TOLERANCE_PX: f64 = 0.25;

/// An SVG figure under construction: a plot area showing `data` at a uniform scale.
#[derive(Clone, Debug)]
pub struct Figure {
    data: BoundingBox,
    scale: f64,
    /// Pixels per data unit vertically: `scale` for geometry, its own for a chart.
    scale_y: f64,
    /// Pixels left of the plot area (tick labels, and a chart's axis title).
    left: f64,
    /// A chart's axes (titles and scales); `None` for geometry.
    chart_axes: Option<(ChartAxis, ChartAxis)>,
    plot_width: f64,
    plot_height: f64,
    body: String,
    legend: Vec<Style>,
    caption: String,
    axes: bool,
    /// The range and label of the colour map of a [`Figure::field`], shown as a colour bar.
    colour_bar: Option<(f64, f64, String)>,
}

impl Figure {
    /// A figure whose plot area is `plot_width` pixels wide (at least 50) and shows `data`
    /// (padded to a positive size) at a uniform scale; axes are on.
    pub fn new(data: BoundingBox, plot_width: f64) -> Self {
        let plot_width = if plot_width.is_finite() {
            plot_width.max(50.0)
        } else {
            600.0
        };
        let mut data = data;
        let tiny = 1e-12 * data.min.x.abs().max(data.min.y.abs()).max(1.0);
        if data.width().is_nan() || data.width() <= tiny {
            data.min.x -= tiny;
            data.max.x += tiny;
        }
        if data.height().is_nan() || data.height() <= tiny {
            data.min.y -= tiny;
            data.max.y += tiny;
        }
        let scale = plot_width / data.width().max(data.height());
        Self {
            data,
            scale,
            scale_y: scale,
            left: AXIS_ROOM,
            chart_axes: None,
            plot_width: data.width() * scale,
            plot_height: data.height() * scale,
            body: String::new(),
            legend: Vec::new(),
            caption: String::new(),
            axes: true,
            colour_bar: None,
        }
    }

    /// Without coordinate axes (for a picture whose coordinates mean nothing).
    pub fn without_axes(mut self) -> Self {
        self.axes = false;
        self
    }

    /// The data box shown.
    pub fn data_box(&self) -> BoundingBox {
        self.data
    }

    /// Pixels per data unit (horizontally; vertically too, except in a chart).
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The pixel position of a data point.
    pub fn to_pixels(&self, p: Point) -> (f64, f64) {
        (
            self.left + (p.x - self.data.min.x) * self.scale,
            EDGE + (self.data.max.y - p.y) * self.scale_y,
        )
    }

    fn remember(&mut self, style: &Style) {
        if style.label().is_some() && !self.legend.iter().any(|s| s.label() == style.label()) {
            self.legend.push(style.clone());
        }
    }

    fn points_attr(&self, pts: &[Point]) -> String {
        let mut s = String::with_capacity(pts.len() * 14);
        for (i, &p) in pts.iter().enumerate() {
            let (x, y) = self.to_pixels(p);
            let _ = write!(s, "{}{x:.2},{y:.2}", if i == 0 { "" } else { " " });
        }
        s
    }

    /// An open polyline through `pts`.
    pub fn polyline(&mut self, pts: &[Point], style: &Style) {
        self.remember(style);
        let attr = self.points_attr(pts);
        let _ = writeln!(
            self.body,
            r##"<polyline points="{attr}"{}/>"##,
            style.line_attributes()
        );
    }

    /// A closed polygon with corners `pts`.
    pub fn polygon(&mut self, pts: &[Point], style: &Style) {
        self.remember(style);
        let attr = self.points_attr(pts);
        let _ = writeln!(
            self.body,
            r##"<polygon points="{attr}"{}/>"##,
            style.attributes()
        );
    }

    /// The polyline of a curve within a quarter pixel.
    pub fn curve(&mut self, curve: &dyn Flatten, style: &Style) {
        self.polyline(&self.flattened(curve), style);
    }

    /// Closed regions bounded by the given curves, each loop a list of curves in order (each
    /// starting where the previous one ends, flattened as one polyline by [`flatten_chain`]),
    /// filled with the even-odd rule (so holes stay empty).
    pub fn region(&mut self, loops: &[Vec<&dyn Flatten>], style: &Style) {
        self.remember(style);
        let mut d = String::new();
        let accuracy = self.flattening_accuracy();
        for l in loops {
            let mut pts: Vec<Point> = Vec::new();
            flatten_chain(l.iter().copied(), accuracy, &mut |p| pts.push(p));
            for (i, &p) in pts.iter().enumerate() {
                let (x, y) = self.to_pixels(p);
                let _ = write!(d, "{}{x:.2},{y:.2} ", if i == 0 { "M" } else { "L" });
            }
            d.push('Z');
        }
        let _ = writeln!(
            self.body,
            r##"<path d="{d}" fill-rule="evenodd"{}/>"##,
            style.attributes()
        );
    }

    /// A quarter pixel in data units.
    fn flattening_accuracy(&self) -> f64 {
        CURVE_TOLERANCE_PX / self.scale.max(self.scale_y)
    }

    fn flattened(&self, curve: &dyn Flatten) -> Vec<Point> {
        let mut pts = Vec::new();
        curve.flatten(self.flattening_accuracy(), &mut |p| pts.push(p));
        pts
    }

    /// An axis-aligned box in data coordinates (at least `0.8` pixels on a side, so that tiny
    /// boxes stay visible).
    pub fn rect(&mut self, b: BoundingBox, style: &Style) {
        self.remember(style);
        let (x, y) = self.to_pixels(Point::new(b.min.x, b.max.y));
        let w = (b.width() * self.scale).max(0.8);
        let h = (b.height() * self.scale_y).max(0.8);
        let _ = writeln!(
            self.body,
            r##"<rect x="{x:.2}" y="{y:.2}" width="{w:.2}" height="{h:.2}"{}/>"##,
            style.attributes()
        );
    }

    /// A mark (the style's [`Marker`]) at a data point.
    pub fn mark(&mut self, p: Point, style: &Style) {
        self.remember(style);
        let (x, y) = self.to_pixels(p);
        self.body.push_str(&style.marker_svg(x, y));
        self.body.push('\n');
    }

    /// The style's [`Marker`] at a data point with its size replaced by `size` pixels (a
    /// dot's or circle's radius, a cross's half-size): marks whose size carries a value. For
    /// areas proportional to values `v`, pass `size = r_ref * sqrt(v / v_ref)` (a mark of
    /// value `v_ref` then has radius `r_ref`) and say `r_ref` and `v_ref` in the caption.
    /// A size that is not finite or below zero draws nothing.
    pub fn mark_sized(&mut self, p: Point, size: f64, style: &Style) {
        self.remember(style);
        let Ok(size) = rs_spline::limits::NonNegative::new(size) else {
            return;
        };
        let size = size.get();
        let (x, y) = self.to_pixels(p);
        self.body
            .push_str(&style.sized_marker_svg(style.marker().with_size(size), x, y));
        self.body.push('\n');
    }

    /// A raw SVG fragment in pixel coordinates (for elements this type has no method for).
    pub fn raw(&mut self, svg: &str, legend: Option<&Style>) {
        if let Some(s) = legend {
            self.remember(s);
        }
        self.body.push_str(svg);
        self.body.push('\n');
    }

    /// Adds a legend entry without drawing anything (for a colour used by [`Figure::raw`]).
    pub fn legend_entry(&mut self, style: &Style) {
        self.remember(style);
    }

    /// The caption under the figure, wrapped to its width.
    pub fn caption(&mut self, text: &str) {
        self.caption = text.to_string();
    }

    fn caption_lines(&self, width: f64) -> Vec<String> {
        let per_line = ((width - 2.0 * EDGE) / (FONT * CHAR_WIDTH)).max(10.0) as usize;
        let mut lines: Vec<String> = Vec::new();
        let mut line = String::new();
        for word in self.caption.split_whitespace() {
            if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > per_line {
                lines.push(std::mem::take(&mut line));
            }
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
        }
        if !line.is_empty() {
            lines.push(line);
        }
        lines
    }

    /// The figure as SVG text.
    pub fn to_svg(&self) -> String {
        let legend_width = self
            .legend
            .iter()
            .filter_map(|s| s.label())
            .map(|l| text_width(l) + 34.0)
            .fold(0.0, f64::max);
        // The colour bar goes in the legend's column, under the legend if there is one.
        let bar_width = match &self.colour_bar {
            // Wide enough for the ticks and for the label written under the bar.
            Some((_, _, label)) => (text_width(label) + 8.0).max(86.0),
            None => 0.0,
        };
        let legend_width = legend_width.max(bar_width);
        let legend_room = if self.legend.is_empty() && self.colour_bar.is_none() {
            0.0
        } else {
            legend_width + 2.0 * EDGE
        };
        let width = self.left + self.plot_width + EDGE + legend_room;
        let plot_bottom = EDGE + self.plot_height;
        let captions = self.caption_lines(width);
        let axis_band = match (self.axes, &self.chart_axes) {
            (false, _) => 0.0,
            (true, None) => 30.0,
            (true, Some(_)) => 46.0,
        };
        let legend_height = if self.legend.is_empty() {
            0.0
        } else {
            self.legend.len() as f64 * 18.0 + 12.0
        };
        let bar_top = EDGE + legend_height + if self.legend.is_empty() { 0.0 } else { 14.0 };
        let bar_height = (0.6 * self.plot_height).clamp(80.0, 240.0);
        let bar_bottom = if self.colour_bar.is_some() {
            bar_top + bar_height + 24.0
        } else {
            EDGE + legend_height
        };
        let body_bottom = (plot_bottom + axis_band).max(bar_bottom);
        let height = body_bottom + captions.len() as f64 * (FONT + 4.0) + EDGE;
        let mut out = String::new();
        let _ = writeln!(
            out,
            r##"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif">"##
        );
        let _ = writeln!(
            out,
            r##"<rect width="100%" height="100%" fill="#ffffff"/>"##
        );
        out.push_str(&self.body);
        if self.axes {
            out.push_str(&axes::axes_svg(self));
        }
        if !self.legend.is_empty() {
            let x0 = self.left + self.plot_width + EDGE;
            let _ = writeln!(
                out,
                r##"<g class="legend"><rect x="{x0:.1}" y="{EDGE:.1}" width="{legend_width:.1}" height="{legend_height:.1}" fill="#ffffff" stroke="#888888" stroke-width="0.8"/>"##
            );
            for (i, s) in self.legend.iter().enumerate() {
                let y = EDGE + 15.0 + i as f64 * 18.0;
                out.push_str(&s.legend_swatch(x0 + 8.0, y - 4.0));
                let _ = writeln!(
                    out,
                    r##"<text x="{:.1}" y="{y:.1}" font-size="{FONT}">{}</text>"##,
                    x0 + 30.0,
                    escape(s.label().unwrap_or_default())
                );
            }
            out.push_str("</g>\n");
        }
        out.push_str(&self.colour_bar_svg(
            self.left + self.plot_width + EDGE + 8.0,
            bar_top,
            bar_height,
        ));
        if !captions.is_empty() {
            let _ = writeln!(out, r##"<g class="caption">"##);
            for (i, line) in captions.iter().enumerate() {
                let y = body_bottom + (i as f64 + 1.0) * (FONT + 4.0);
                let _ = writeln!(
                    out,
                    r##"<text x="{EDGE:.1}" y="{y:.1}" font-size="{FONT}">{}</text>"##,
                    escape(line)
                );
            }
            out.push_str("</g>\n");
        }
        out.push_str("</svg>\n");
        out
    }
}

/// Text with `&`, `<`, `>` and `"` escaped for XML.
pub fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::{circle, prelude::*};

    #[test]
    fn caption_wraps_inside_the_figure() {
        let mut fig = Figure::new(
            BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(1.0, 1.0)),
            200.0,
        );
        fig.caption(&"word ".repeat(80));
        let width = AXIS_ROOM + 200.0 + EDGE;
        let lines = fig.caption_lines(width);
        assert!(lines.len() > 3);
        for l in &lines {
            assert!(l.len() as f64 * FONT * CHAR_WIDTH <= width - 2.0 * EDGE);
        }
    }

    #[test]
    fn curves_are_flattened_to_a_quarter_pixel() {
        let c = circle(Point::new(0.0, 0.0), 1.0).unwrap();
        let fig = Figure::new(c.control_bounding_box(), 400.0);
        let pts = fig.flattened(&c);
        for w in pts.windows(2) {
            let gap = 1.0 - ((w[0] + w[1]) * 0.5).length();
            assert!(gap * fig.scale() <= CURVE_TOLERANCE_PX * (1.0 + 1e-9));
        }
    }

    #[test]
    fn every_element_is_well_formed_xml() {
        let c = circle(Point::new(0.0, 0.0), 1.0).unwrap();
        let mut fig = Figure::new(c.control_bounding_box(), 300.0);
        let s = Style::stroke("#000000", 1.0)
            .with_fill("#ff0000", 0.5)
            .dashed("2 2");
        fig.curve(&c, &s.clone().labelled("curve & <co>"));
        fig.polygon(
            &[Point::new(0.0, 0.0), Point::new(1.0, 0.0)],
            &s.clone().labelled("p"),
        );
        fig.rect(
            c.control_bounding_box(),
            &Style::fill("#00ff00").labelled("r"),
        );
        fig.region(&[vec![&c]], &s.clone().labelled("region"));
        fig.mark(
            Point::new(0.0, 0.0),
            &Style::fill("#0000ff").labelled("dot"),
        );
        fig.mark(
            Point::new(0.5, 0.0),
            &Style::stroke("#0000ff", 1.0)
                .with_marker(Marker::Cross(3.0))
                .labelled("cross"),
        );
        fig.caption("A caption with <angle> & ampersand.");
        let svg = fig.to_svg();
        let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
        let texts: Vec<&str> = doc.descendants().filter_map(|n| n.text()).collect();
        assert!(texts.contains(&"A caption with <angle> & ampersand."));
        for label in ["curve & <co>", "p", "r", "region", "dot", "cross"] {
            assert!(texts.contains(&label), "{label}");
        }
        assert!(
            doc.descendants()
                .any(|n| n.attribute("class") == Some("axes"))
        );
    }

    #[test]
    fn sized_marks_take_their_size_and_the_style() {
        let mut fig = Figure::new(
            BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(1.0, 1.0)),
            100.0,
        );
        let s = Style::stroke("#123456", 0.5)
            .with_fill("#abcdef", 0.4)
            .with_marker(Marker::Circle(2.0))
            .labelled("weighted");
        fig.mark_sized(Point::new(0.5, 0.5), 7.25, &s);
        fig.mark_sized(Point::new(0.2, 0.5), f64::NAN, &s);
        fig.mark_sized(
            Point::new(0.2, 0.2),
            4.0,
            &Style::fill("#000000").with_marker(Marker::Cross(1.0)),
        );
        let svg = fig.to_svg();
        let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
        let circles: Vec<_> = doc
            .descendants()
            .filter(|n| n.has_tag_name("circle"))
            .collect();
        // The mark of radius 7.25 at the plot's centre, and the legend's swatch (radius 6 at
        // most); the mark of size NaN draws nothing.
        assert_eq!(circles.len(), 2, "{svg}");
        let mark = circles
            .iter()
            .find(|c| c.attribute("r") == Some("7.25"))
            .expect("the sized circle");
        let (x, y) = fig.to_pixels(Point::new(0.5, 0.5));
        assert_eq!(mark.attribute("cx"), Some(format!("{x:.2}").as_str()));
        assert_eq!(mark.attribute("cy"), Some(format!("{y:.2}").as_str()));
        assert_eq!(mark.attribute("fill"), Some("#abcdef"));
        assert_eq!(mark.attribute("fill-opacity"), Some("0.4"));
        assert_eq!(mark.attribute("stroke"), Some("#123456"));
        let swatch = circles.iter().find(|c| c != &mark).unwrap();
        assert_eq!(swatch.attribute("r"), Some("2.00"));
        // The cross's half-size is 4: its path spans 8 pixels.
        let (cx, cy) = fig.to_pixels(Point::new(0.2, 0.2));
        assert!(svg.contains(&format!(
            "M{:.2},{:.2} L{:.2},{:.2}",
            cx - 4.0,
            cy - 4.0,
            cx + 4.0,
            cy + 4.0
        )));
        assert_eq!(svg.matches(">weighted</text>").count(), 1);
    }

    #[test]
    fn degenerate_boxes_get_a_size() {
        let fig = Figure::new(BoundingBox::from_point(Point::new(5.0, 5.0)), 100.0);
        assert!(fig.scale().is_finite() && fig.scale() > 0.0);
        let svg = fig.to_svg();
        assert!(svg.starts_with("<svg") && svg.ends_with("</svg>\n"));
    }

    #[test]
    fn legend_lists_each_label_once() {
        let mut fig = Figure::new(
            BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(1.0, 1.0)),
            100.0,
        );
        let s = Style::fill("#ff0000").labelled("a <b>");
        fig.mark(Point::new(0.5, 0.5), &s);
        fig.mark(Point::new(0.2, 0.5), &s);
        let svg = fig.to_svg();
        assert_eq!(svg.matches(">a &lt;b&gt;</text>").count(), 1);
    }
}
