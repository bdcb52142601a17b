//! How an element is drawn, and how it appears in the legend.

use std::fmt::Write;

use crate::escape;

/// The shape drawn by [`Figure::mark`](crate::Figure::mark).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Marker {
    /// A filled dot of the given radius in pixels.
    Dot(f64),
    /// A cross of the given half-size in pixels.
    Cross(f64),
    /// A circle of the given radius in pixels drawn with the style's fill, fill opacity and
    /// stroke, so that overlapping circles stay visible (for marks whose size carries a value,
    /// see [`Figure::mark_sized`](crate::Figure::mark_sized)).
    Circle(f64),
}

impl Marker {
    /// The same shape with its size (a dot's or a circle's radius, a cross's half-size)
    /// replaced by `size` pixels.
    pub fn with_size(self, size: f64) -> Self {
        match self {
            Marker::Dot(_) => Marker::Dot(size),
            Marker::Cross(_) => Marker::Cross(size),
            Marker::Circle(_) => Marker::Circle(size),
        }
    }
}

/// Fill, stroke, dash pattern, opacity, marker and an optional legend label.
#[derive(Clone, Debug, PartialEq)]
pub struct Style {
    fill: Option<String>,
    fill_opacity: Option<f64>,
    stroke: Option<String>,
    stroke_width: f64,
    dash: Option<String>,
    marker: Marker,
    label: Option<String>,
}

impl Style {
    /// A stroked outline of `width` pixels in `color` (any SVG colour), no fill.
    pub fn stroke(color: &str, width: f64) -> Self {
        Self {
            fill: None,
            fill_opacity: None,
            stroke: Some(color.to_string()),
            stroke_width: width,
            dash: None,
            marker: Marker::Dot(2.0),
            label: None,
        }
    }

    /// A filled area (or dot) in `color`, no outline.
    pub fn fill(color: &str) -> Self {
        Self {
            fill: Some(color.to_string()),
            stroke: None,
            ..Self::stroke("none", 0.0)
        }
    }

    /// Also filled in `color` with opacity `opacity` (0 to 1).
    pub fn with_fill(mut self, color: &str, opacity: f64) -> Self {
        self.fill = Some(color.to_string());
        self.fill_opacity = Some(opacity.clamp(0.0, 1.0));
        self
    }

    /// Dashed with the SVG dash pattern `pattern` (for example `"4 2"`).
    pub fn dashed(mut self, pattern: &str) -> Self {
        self.dash = Some(pattern.to_string());
        self
    }

    /// Marks drawn as `marker`.
    pub fn with_marker(mut self, marker: Marker) -> Self {
        self.marker = marker;
        self
    }

    /// Named `label` in the legend.
    pub fn labelled(mut self, label: &str) -> Self {
        self.label = Some(label.to_string());
        self
    }

    /// The marker of [`Figure::mark`](crate::Figure::mark).
    pub(crate) fn marker(&self) -> Marker {
        self.marker
    }

    /// The legend label, if any.
    pub fn label(&self) -> Option<&str> {
        self.label.as_deref()
    }

    /// The SVG presentation attributes, each with a leading space.
    pub(crate) fn attributes(&self) -> String {
        let mut a = String::new();
        let _ = write!(a, r##" fill="{}""##, self.fill.as_deref().unwrap_or("none"));
        if let Some(o) = self.fill_opacity {
            let _ = write!(a, r##" fill-opacity="{o}""##);
        }
        if let Some(s) = &self.stroke {
            let _ = write!(a, r##" stroke="{s}" stroke-width="{}""##, self.stroke_width);
        }
        if let Some(d) = &self.dash {
            let _ = write!(a, r##" stroke-dasharray="{d}""##);
        }
        a
    }

    /// The attributes of an unfilled line: the stroke and dash only, `fill="none"`.
    pub(crate) fn line_attributes(&self) -> String {
        Self {
            fill: None,
            fill_opacity: None,
            ..self.clone()
        }
        .attributes()
    }

    /// The marker at pixel `(x, y)`.
    pub(crate) fn marker_svg(&self, x: f64, y: f64) -> String {
        self.sized_marker_svg(self.marker, x, y)
    }

    /// `marker` (this style's, or it with another size) at pixel `(x, y)`.
    pub(crate) fn sized_marker_svg(&self, marker: Marker, x: f64, y: f64) -> String {
        let color = self
            .fill
            .as_deref()
            .or(self.stroke.as_deref())
            .unwrap_or("#000000");
        match marker {
            Marker::Dot(r) => {
                format!(r##"<circle cx="{x:.2}" cy="{y:.2}" r="{r}" fill="{color}"/>"##)
            }
            Marker::Circle(r) => format!(
                r##"<circle cx="{x:.2}" cy="{y:.2}" r="{r:.2}"{}/>"##,
                self.attributes()
            ),
            Marker::Cross(h) => format!(
                r##"<path d="M{:.2},{:.2} L{:.2},{:.2} M{:.2},{:.2} L{:.2},{:.2}" stroke="{color}" stroke-width="1.2"/>"##,
                x - h,
                y - h,
                x + h,
                y + h,
                x - h,
                y + h,
                x + h,
                y - h
            ),
        }
    }

    /// A small sample of the style for the legend, its left middle at `(x, y)`.
    pub(crate) fn legend_swatch(&self, x: f64, y: f64) -> String {
        let title = format!(
            "<title>{}</title>",
            escape(self.label().unwrap_or_default())
        );
        if let Marker::Circle(r) = self.marker {
            // A circle of at most the legend row's height.
            return self
                .sized_marker_svg(Marker::Circle(r.min(6.0)), x + 8.0, y)
                .replace("/>", &format!(">{title}</circle>"));
        }
        if self.stroke.is_none() {
            // Filled marks and areas: a dot or a square.
            return match self.marker {
                Marker::Dot(_) if self.fill_opacity.is_none() => self
                    .marker_svg(x + 8.0, y)
                    .replace("/>", &format!(">{title}</circle>")),
                Marker::Cross(_) => self.marker_svg(x + 8.0, y),
                Marker::Circle(_) | Marker::Dot(_) => format!(
                    r##"<rect x="{x:.1}" y="{:.1}" width="16" height="10"{}>{title}</rect>"##,
                    y - 5.0,
                    self.attributes()
                ),
            };
        }
        if self.fill.is_some() {
            format!(
                r##"<rect x="{x:.1}" y="{:.1}" width="16" height="10"{}>{title}</rect>"##,
                y - 5.0,
                self.attributes()
            )
        } else {
            format!(
                r##"<line x1="{x:.1}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}"{}>{title}</line>"##,
                x + 16.0,
                self.attributes()
            )
        }
    }
}
