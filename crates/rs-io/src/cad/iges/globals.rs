//! The global section (IGES 5.3, section 2.2.4): the delimiters and the minimum resolution.
//!
//! Its first two fields name the parameter and record delimiters as Hollerith strings `1Hx`;
//! an empty field means the defaults `,` and `;`. The rest is free format with those
//! delimiters; of it we keep parameter 19, the minimum user-intended resolution (model units).

use std::borrow::Cow;

use super::cad_err;
use super::params::{Field, Params};
use crate::IoError;

/// What the global section says that the reader needs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Globals {
    /// The parameter delimiter (`,` by default).
    pub(super) delim: u8,
    /// The record delimiter (`;` by default).
    pub(super) end: u8,
    /// Parameter 19 if present, finite and positive.
    pub(super) resolution: Option<f64>,
}

/// Reads a delimiter definition `1Hx` at the start of `g[*pos..]`, or `None` for an empty
/// field; advances `*pos` past the definition (not past the delimiter that follows it).
fn delimiter(g: &[u8], pos: &mut usize, which: &str) -> Result<Option<u8>, IoError> {
    while g.get(*pos) == Some(&b' ') {
        *pos += 1;
    }
    match &g[(*pos).min(g.len())..] {
        [b'1', b'H' | b'h', c, ..] => {
            *pos += 3;
            if c.is_ascii_graphic() && !c.is_ascii_digit() && *c != b'+' && *c != b'-' {
                Ok(Some(*c))
            } else {
                Err(cad_err(format!(
                    "global section: {which} delimiter {:?} is not usable",
                    char::from(*c)
                )))
            }
        }
        _ => Ok(None),
    }
}

/// Reads the global section's data (columns 1-72 of its records, concatenated).
pub(super) fn globals(g: &[u8]) -> Result<Globals, IoError> {
    let mut pos = 0;
    let delim = delimiter(g, &mut pos, "parameter")?.unwrap_or(b',');
    // The first field is followed by the parameter delimiter (or the record delimiter of a
    // global section that defines nothing else).
    let after = |pos: usize| g.get(pos).copied();
    let mut end = b';';
    // Where field 2 starts.
    let mut start = g.len();
    if after(pos) == Some(delim) {
        pos += 1;
        start = pos;
        end = delimiter(g, &mut pos, "record")?.unwrap_or(b';');
        if end == delim {
            return Err(cad_err(
                "global section: the parameter and record delimiters are the same".into(),
            ));
        }
    } else if after(pos) != Some(end) {
        return Err(cad_err(format!(
            "global section: expected the parameter delimiter after field 1, found {:?}",
            after(pos).map(char::from)
        )));
    }
    let mut p = Params::new(
        Cow::Borrowed(&g[start..]),
        delim,
        end,
        "global section".into(),
    );
    // Fields 2 to the end: every field is checked (a broken one is a syntax error), 19 kept.
    let mut resolution = None;
    let mut index = 2;
    while let Some(field) = p.next_field().map_err(cad_err)? {
        if let (19, Field::Text(t)) = (index, field) {
            let r = super::params::parse_real(t)
                .map_err(|m| cad_err(format!("global section: parameter 19: {m}")))?;
            resolution = (r > 0.0).then_some(r);
        }
        index += 1;
    }
    Ok(Globals {
        delim,
        end,
        resolution,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delimiters_and_resolution() {
        let occ = b",,31HOpen CASCADE IGES processor 6.5,13HFilename.iges,16HOpen CASCADE 6.5,\
31HOpen CASCADE IGES processor 6.5,32,308,15,308,15,,1.,1,4HINCH,1,0.000394,\
15H20120128.235219,3.93728E-09,0.246527,3Htux,,11,0,15H20120128.235219,;";
        let g = globals(occ).unwrap();
        assert_eq!((g.delim, g.end), (b',', b';'));
        assert_eq!(g.resolution, Some(3.93728e-9));
        // Delimiters `/` and `#`; fields 3 and 4 are strings holding them; 5-18 are empty.
        let custom = format!("1H//1H#/2Ha,/3Hb/c/{}1.0D-3/5.#", "/".repeat(14));
        let g = globals(custom.as_bytes()).unwrap();
        assert_eq!((g.delim, g.end), (b'/', b'#'));
        assert_eq!(g.resolution, Some(1e-3));
        let shifted = format!("1H//1H#/2Ha,/3Hb/c/{}1.0D-3/5.#", "/".repeat(15));
        assert_eq!(globals(shifted.as_bytes()).unwrap().resolution, None);
        assert_eq!(globals(b";").unwrap().resolution, None);
        assert_eq!(
            globals(b",,,,,,,,,,,,,,,,,,-1.0;").unwrap().resolution,
            None
        );
        assert!(globals(b",,,,,,,,,,,,,,,,,,1e999;").is_err());
        assert!(globals(b"1H,,1H,;").is_err());
        assert!(globals(b"x,;").is_err());
    }
}
