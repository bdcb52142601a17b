//! Raster images in figures: a field sampled on a grid of pixels, coloured through a colour
//! map, embedded as a PNG, with a colour bar.

use std::fmt::Write;

use rs_spline::Point;

use crate::{Figure, escape};

/// The viridis colour map (perceptually uniform, readable in grey), sampled at 9 stops and
/// interpolated linearly.
const VIRIDIS: [[f64; 3]; 9] = [
    [68.0, 1.0, 84.0],
    [71.0, 44.0, 123.0],
    [59.0, 82.0, 139.0],
    [44.0, 114.0, 142.0],
    [33.0, 145.0, 140.0],
    [39.0, 173.0, 129.0],
    [92.0, 200.0, 99.0],
    [170.0, 220.0, 50.0],
    [253.0, 231.0, 37.0],
];

/// The colour of `t` in `[0, 1]` (clamped) on the viridis map.
pub fn viridis(t: f64) -> [u8; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = t * (VIRIDIS.len() - 1) as f64;
    let i = (x.floor() as usize).min(VIRIDIS.len() - 2);
    let f = x - i as f64;
    let c = |k: usize| (VIRIDIS[i][k] * (1.0 - f) + VIRIDIS[i + 1][k] * f).round() as u8;
    [c(0), c(1), c(2)]
}

/// A scalar field on the figure's plot area: `values[row * width + col]` at the centre of each
/// pixel of a `width x height` grid (row 0 at the top), `None` where the field is not defined
/// (drawn transparent).
#[derive(Clone, Debug)]
pub struct FieldImage {
    /// Pixels per row.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// The values, row by row from the top.
    pub values: Vec<Option<f64>>,
}

impl FieldImage {
    /// Samples `field` at the centres of a grid of pixels over the figure's data box, `width`
    /// pixels wide (height in proportion), row by row from the top.
    pub fn sample(fig: &Figure, width: usize, field: impl Fn(Point) -> Option<f64>) -> Self {
        let b = fig.data_box();
        let width = width.clamp(1, 4096);
        let height = ((width as f64 * b.height() / b.width()).round() as usize).clamp(1, 4096);
        let mut values = Vec::with_capacity(width * height);
        for r in 0..height {
            for c in 0..width {
                let p = Point::new(
                    b.min.x + (c as f64 + 0.5) / width as f64 * b.width(),
                    b.max.y - (r as f64 + 0.5) / height as f64 * b.height(),
                );
                values.push(field(p).filter(|v| v.is_finite()));
            }
        }
        Self {
            width,
            height,
            values,
        }
    }

    /// The smallest and largest defined values (`None` if none is).
    pub fn range(&self) -> Option<(f64, f64)> {
        self.values.iter().flatten().fold(None, |r, &v| match r {
            None => Some((v, v)),
            Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
        })
    }

    /// The image as a PNG: each value mapped by `colour` from `[lo, hi]` to `[0, 1]`,
    /// undefined pixels transparent.
    pub fn png(&self, lo: f64, hi: f64) -> Vec<u8> {
        let span = if hi > lo { hi - lo } else { 1.0 };
        let mut rgba = Vec::with_capacity(4 * self.values.len());
        for v in &self.values {
            match v {
                Some(v) => {
                    let [r, g, b] = viridis((v - lo) / span);
                    rgba.extend_from_slice(&[r, g, b, 255]);
                }
                None => rgba.extend_from_slice(&[0, 0, 0, 0]),
            }
        }
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, self.width as u32, self.height as u32);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::High);
        let written = encoder
            .write_header()
            .and_then(|mut w| w.write_image_data(&rgba));
        if written.is_err() {
            out.clear();
        }
        out
    }
}

impl Figure {
    /// Draws `image` over the plot area, coloured on the viridis map from `lo` to `hi`, and a
    /// colour bar labelled `label` with ticks (in the legend column).
    pub fn field(&mut self, image: &FieldImage, lo: f64, hi: f64, label: &str) {
        let png = image.png(lo, hi);
        let (x0, y0) = self.to_pixels(Point::new(self.data_box().min.x, self.data_box().max.y));
        let (w, h) = (self.plot_width, self.plot_height);
        let _ = writeln!(
            self.body,
            r##"<image x="{x0:.2}" y="{y0:.2}" width="{w:.2}" height="{h:.2}" preserveAspectRatio="none" style="image-rendering:pixelated" href="data:image/png;base64,{}"/>"##,
            base64(&png)
        );
        self.colour_bar = Some((lo, hi, label.to_string()));
    }

    /// The colour bar's SVG at `(x, y)`, `height` pixels tall.
    pub(crate) fn colour_bar_svg(&self, x: f64, y: f64, height: f64) -> String {
        let Some((lo, hi, label)) = &self.colour_bar else {
            return String::new();
        };
        let mut out = String::from(r##"<g class="colour-bar">"##);
        let steps = 64;
        for i in 0..steps {
            let t = i as f64 / steps as f64;
            let [r, g, b] = viridis(t + 0.5 / steps as f64);
            let top = y + height * (1.0 - (i + 1) as f64 / steps as f64);
            let _ = write!(
                out,
                r##"<rect x="{x:.1}" y="{top:.2}" width="14" height="{:.2}" fill="rgb({r},{g},{b})"/>"##,
                height / steps as f64 + 0.3
            );
        }
        let _ = write!(
            out,
            r##"<rect x="{x:.1}" y="{y:.1}" width="14" height="{height:.1}" fill="none" stroke="#444444" stroke-width="0.6"/>"##
        );
        let ticks = crate::nice_ticks(*lo, *hi, 5);
        let step = if ticks.len() > 1 {
            ticks[1] - ticks[0]
        } else {
            1.0
        };
        for t in ticks {
            let ty = y + height * (1.0 - (t - lo) / (hi - lo).max(f64::MIN_POSITIVE));
            let _ = write!(
                out,
                r##"<line x1="{:.1}" y1="{ty:.2}" x2="{:.1}" y2="{ty:.2}" stroke="#444444" stroke-width="0.6"/><text x="{:.1}" y="{:.2}" font-size="10">{}</text>"##,
                x + 14.0,
                x + 18.0,
                x + 20.0,
                ty + 3.5,
                escape(&crate::axes::label(t, step))
            );
        }
        let _ = write!(
            out,
            r##"<text x="{x:.1}" y="{:.1}" font-size="11">{}</text></g>"##,
            y + height + 16.0,
            escape(label)
        );
        out.push('\n');
        out
    }
}

/// Standard base64 of `bytes`.
fn base64(bytes: &[u8]) -> String {
    const TABLE: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(TABLE[(n >> (18 - 6 * k)) as usize & 63] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::BoundingBox;

    #[test]
    fn base64_matches_the_standard() {
        assert_eq!(base64(b""), "");
        assert_eq!(base64(b"f"), "Zg==");
        assert_eq!(base64(b"fo"), "Zm8=");
        assert_eq!(base64(b"foo"), "Zm9v");
        assert_eq!(base64(b"foobar"), "Zm9vYmFy");
    }

    #[test]
    fn viridis_runs_from_purple_to_yellow() {
        assert_eq!(viridis(0.0), [68, 1, 84]);
        assert_eq!(viridis(1.0), [253, 231, 37]);
        assert_eq!(viridis(f64::NAN), viridis(0.0));
    }

    #[test]
    fn fields_become_pngs() {
        let img = FieldImage {
            width: 3,
            height: 2,
            values: vec![Some(0.0), Some(0.5), None, Some(1.0), None, Some(0.25)],
        };
        assert_eq!(img.range(), Some((0.0, 1.0)));
        let png = img.png(0.0, 1.0);
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"));
    }

    #[test]
    fn the_colour_bar_label_fits_in_the_figure() {
        let data = BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(1.0, 1.0));
        let mut fig = Figure::new(data, 200.0);
        let img = FieldImage {
            width: 2,
            height: 2,
            values: vec![Some(0.0), Some(1.0), Some(0.5), None],
        };
        let label = "a rather long colour bar label";
        fig.field(&img, 0.0, 1.0, label);
        let svg = fig.to_svg();
        let width: f64 = svg
            .split("width=\"")
            .nth(1)
            .and_then(|rest| rest.split('"').next())
            .and_then(|w| w.parse().ok())
            .expect("the svg element has a width");
        let at = svg.find(label).expect("the label is drawn");
        let x: f64 = svg[..at]
            .rsplit("<text x=\"")
            .next()
            .and_then(|rest| rest.split('"').next())
            .and_then(|x| x.parse().ok())
            .expect("the label has an x");
        // 11 px text is at most about 0.6 em per character.
        let needed = x + label.chars().count() as f64 * 11.0 * 0.6;
        assert!(
            needed <= width,
            "label ends at {needed}, figure is {width} wide"
        );
    }
}
