//! TrueType / OpenType glyphs: the quadratic (`glyf`) or cubic (`CFF`) contours of one glyph,
//! in font units (y up), as a domain whose inner contours are holes.

use std::path::Path;
use std::str::FromStr;

use rs_spline::{Domain, NurbsCurve, Point, SplineError};

use crate::IoError;
use crate::builder::{LoopBuilder, OpenSubpaths};

/// Which glyph of a font to read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Glyph {
    /// The glyph the font's character map gives for a character.
    Char(char),
    /// A glyph by index.
    Id(u16),
    /// A glyph by PostScript name (`post` or `CFF` table).
    Name(String),
}

impl FromStr for Glyph {
    type Err = IoError;

    /// `B` (one character), `U+0042` (a code point), `gid:37` (an index) or a glyph name
    /// (`ampersand`).
    fn from_str(s: &str) -> Result<Self, IoError> {
        let bad = |message: &str| IoError::Glyph {
            glyph: s.to_string(),
            message: message.to_string(),
        };
        let mut chars = s.chars();
        match (chars.next(), chars.next()) {
            (None, _) => Err(bad("empty glyph selection")),
            (Some(c), None) => Ok(Glyph::Char(c)),
            _ => {
                if let Some(hex) = s.strip_prefix("U+").or_else(|| s.strip_prefix("u+")) {
                    let code = u32::from_str_radix(hex, 16)
                        .map_err(|_| bad("U+ must be followed by a hexadecimal code point"))?;
                    char::from_u32(code)
                        .map(Glyph::Char)
                        .ok_or_else(|| bad("not a Unicode scalar value"))
                } else if let Some(id) = s.strip_prefix("gid:") {
                    id.parse()
                        .map(Glyph::Id)
                        .map_err(|_| bad("gid: must be followed by a glyph index 0..=65535"))
                } else {
                    Ok(Glyph::Name(s.to_string()))
                }
            }
        }
    }
}

impl std::fmt::Display for Glyph {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Glyph::Char(c) => write!(f, "{c:?} (U+{:04X})", u32::from(*c)),
            Glyph::Id(id) => write!(f, "gid:{id}"),
            Glyph::Name(n) => write!(f, "{n}"),
        }
    }
}

/// The contours of `glyph` in face `face_index` of the font data (TrueType, OpenType, or a
/// collection), one closed loop per contour, coordinates in font units.
///
/// # Errors
/// [`IoError::Font`] if the data is not a font, [`IoError::Glyph`] if the glyph is not in it
/// or has no outline (a space, say).
pub fn glyph_curves(
    font: &[u8],
    face_index: u32,
    glyph: &Glyph,
) -> Result<Vec<NurbsCurve>, IoError> {
    let face =
        ttf_parser::Face::parse(font, face_index).map_err(|e| IoError::Font(e.to_string()))?;
    let bad = |message: String| IoError::Glyph {
        glyph: glyph.to_string(),
        message,
    };
    let id = match glyph {
        Glyph::Char(c) => face.glyph_index(*c),
        Glyph::Id(id) => (*id < face.number_of_glyphs()).then_some(ttf_parser::GlyphId(*id)),
        Glyph::Name(n) => face.glyph_index_by_name(n),
    }
    .ok_or_else(|| bad("not in the font".to_string()))?;
    let mut sink = Sink {
        builder: LoopBuilder::new(OpenSubpaths::Close),
        error: None,
    };
    face.outline_glyph(id, &mut sink)
        .ok_or_else(|| bad("the glyph has no outline".to_string()))?;
    if let Some(e) = sink.error {
        return Err(bad(e.to_string()));
    }
    let curves = sink.builder.into_curves().map_err(|e| bad(e.to_string()))?;
    if curves.is_empty() {
        return Err(bad("the glyph's outline encloses no area".to_string()));
    }
    Ok(curves)
}

/// The domain of `glyph` in the first face of the font data (see [`glyph_curves`]).
///
/// # Errors
/// As [`glyph_curves`].
pub fn glyph_domain(font: &[u8], glyph: &Glyph) -> Result<Domain, IoError> {
    Ok(Domain::new(glyph_curves(font, 0, glyph)?)?.with_name(glyph.to_string()))
}

/// The domain of `glyph` in the first face of a font file.
///
/// # Errors
/// [`IoError::Read`], then as [`glyph_curves`].
///
/// # Examples
///
/// ```no_run
/// use rs_io::font::{Glyph, glyph_domain_from_file};
/// let b = glyph_domain_from_file("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", &Glyph::Char('B'))
///     .unwrap();
/// assert_eq!(b.loops().len(), 3); // the outline and two counters
/// ```
pub fn glyph_domain_from_file(path: impl AsRef<Path>, glyph: &Glyph) -> Result<Domain, IoError> {
    let path = path.as_ref();
    let data = rs_spline::limits::read_file(path).map_err(|source| IoError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(Domain::new(glyph_curves(&data, 0, glyph)?)?
        .with_name(format!("{} {glyph}", path.display())))
}

struct Sink {
    builder: LoopBuilder,
    error: Option<SplineError>,
}

impl Sink {
    fn record(&mut self, r: Result<(), SplineError>) {
        if let Err(e) = r {
            self.error.get_or_insert(e);
        }
    }
}

fn pt(x: f32, y: f32) -> Point {
    Point::new(f64::from(x), f64::from(y))
}

impl ttf_parser::OutlineBuilder for Sink {
    fn move_to(&mut self, x: f32, y: f32) {
        self.builder.move_to(pt(x, y));
    }

    fn line_to(&mut self, x: f32, y: f32) {
        let r = self.builder.line_to(pt(x, y));
        self.record(r);
    }

    fn quad_to(&mut self, x1: f32, y1: f32, x: f32, y: f32) {
        let r = self.builder.bezier_to(&[pt(x1, y1), pt(x, y)]);
        self.record(r);
    }

    fn curve_to(&mut self, x1: f32, y1: f32, x2: f32, y2: f32, x: f32, y: f32) {
        let r = self.builder.bezier_to(&[pt(x1, y1), pt(x2, y2), pt(x, y)]);
        self.record(r);
    }

    fn close(&mut self) {
        self.builder.close();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glyph_selections_parse() {
        assert_eq!("B".parse::<Glyph>().unwrap(), Glyph::Char('B'));
        assert_eq!("#".parse::<Glyph>().unwrap(), Glyph::Char('#'));
        assert_eq!("U+0040".parse::<Glyph>().unwrap(), Glyph::Char('@'));
        assert_eq!("gid:37".parse::<Glyph>().unwrap(), Glyph::Id(37));
        assert_eq!(
            "ampersand".parse::<Glyph>().unwrap(),
            Glyph::Name("ampersand".into())
        );
        for bad in ["", "U+zz", "U+D800", "gid:70000"] {
            assert!(
                matches!(bad.parse::<Glyph>(), Err(IoError::Glyph { .. })),
                "{bad}"
            );
        }
    }

    #[test]
    fn garbage_is_not_a_font() {
        let e = glyph_curves(b"not a font at all", 0, &Glyph::Char('A')).unwrap_err();
        assert!(matches!(e, IoError::Font(_)), "{e}");
    }
}
