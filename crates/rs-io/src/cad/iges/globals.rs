//! The global section (IGES 5.3, section 2.2.4): the delimiters, the length unit and the
//! minimum resolution.
//!
//! Its first two fields name the parameter and record delimiters as Hollerith strings `1Hx`;
//! an empty field means the defaults `,` and `;`. The rest is free format with those
//! delimiters; of it we keep parameters 14 and 15, the units flag and the units name, and 19,
//! the minimum user-intended resolution (model units).

use std::borrow::Cow;

use rs_geom::brep::LengthUnit;

use super::error::IgesError;
use super::params::{Field, Params};

/// What the global section says that the reader needs.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Globals {
    /// The parameter delimiter (`,` by default).
    pub(super) delim: u8,
    /// The record delimiter (`;` by default).
    pub(super) end: u8,
    /// Parameter 19 if present, finite and positive.
    pub(super) resolution: Option<f64>,
    /// The length unit of parameters 14 and 15, when they name one IGES 5.3 defines.
    pub(super) length_unit: Option<LengthUnit>,
}

/// The units of IGES 5.3's units flag (global parameter 14), by flag: the name the standard
/// gives them (also the names flag 3 refers to in parameter 15) and millimetres per unit.
const UNITS: [(i64, &str, f64); 10] = [
    (1, "INCH", 25.4),
    (2, "MM", 1.0),
    (4, "FT", 304.8),
    (5, "MI", 1_609_344.0),
    (6, "M", 1000.0),
    (7, "KM", 1_000_000.0),
    (8, "MIL", 0.0254),
    (9, "UM", 0.001),
    (10, "CM", 10.0),
    (11, "UIN", 0.000_025_4),
];

/// The length unit of units flag `flag` and units name `name` (parameter 15, which decides for
/// flag 3): `None` for a flag or name IGES 5.3 does not define. The name kept is the file's
/// when it gives one.
fn length_unit(flag: Option<i64>, name: Option<&str>) -> Option<LengthUnit> {
    let by_name = |n: &str| {
        let n = n.trim().to_ascii_uppercase();
        let n = if n == "IN" { "INCH".to_string() } else { n };
        UNITS.iter().find(|u| u.1 == n).map(|u| u.2)
    };
    let millimetres = match flag {
        Some(3) => by_name(name?)?,
        Some(f) => UNITS.iter().find(|u| u.0 == f)?.2,
        None => by_name(name?)?,
    };
    let standard = UNITS.iter().find(|u| u.2 == millimetres).map(|u| u.1);
    let name = match name.map(str::trim).filter(|n| !n.is_empty()) {
        Some(n) => n.to_string(),
        None => standard.unwrap_or("").to_string(),
    };
    Some(LengthUnit { name, millimetres })
}

/// Reads a delimiter definition `1Hx` at the start of `g[*pos..]`, or `None` for an empty
/// field; advances `*pos` past the definition (not past the delimiter that follows it).
fn delimiter(g: &[u8], pos: &mut usize, which: &'static str) -> Result<Option<u8>, IgesError> {
    while g.get(*pos) == Some(&b' ') {
        *pos += 1;
    }
    match &g[(*pos).min(g.len())..] {
        [b'1', b'H' | b'h', c, ..] => {
            *pos += 3;
            if c.is_ascii_graphic() && !c.is_ascii_digit() && *c != b'+' && *c != b'-' {
                Ok(Some(*c))
            } else {
                Err(IgesError::Delimiter {
                    which,
                    found: char::from(*c),
                })
            }
        }
        _ => Ok(None),
    }
}

/// Reads the global section's data (columns 1-72 of its records, concatenated).
pub(super) fn globals(g: &[u8]) -> Result<Globals, IgesError> {
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
            return Err(IgesError::SameDelimiters);
        }
    } else if after(pos) != Some(end) {
        return Err(IgesError::AfterFirstGlobal {
            found: after(pos).map(char::from),
        });
    }
    let mut p = Params::new(
        Cow::Borrowed(&g[start..]),
        delim,
        end,
        "global section".into(),
    );
    // Fields 2 to the end: every field is checked (a broken one is a syntax error), 14, 15
    // and 19 kept. The units are information (nothing is converted): a flag that is not a
    // number is ignored as an unknown unit is.
    let (mut resolution, mut flag, mut name) = (None, None, None);
    let mut index = 2;
    while let Some(field) = p.next_field()? {
        match (index, field) {
            (14, Field::Text(t)) => {
                flag = std::str::from_utf8(t)
                    .ok()
                    .and_then(|s| s.parse::<i64>().ok());
            }
            (15, Field::String(t)) => name = Some(String::from_utf8_lossy(t).into_owned()),
            (19, Field::Text(t)) => {
                let r = super::params::parse_real(t).map_err(|problem| IgesError::Field {
                    who: "global section".into(),
                    index: 19,
                    name: "minimum resolution",
                    problem,
                })?;
                resolution = (r > 0.0).then_some(r);
            }
            _ => {}
        }
        index += 1;
    }
    Ok(Globals {
        delim,
        end,
        resolution,
        length_unit: length_unit(flag, name.as_deref()),
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
        assert_eq!(
            g.length_unit,
            Some(LengthUnit {
                name: "INCH".into(),
                millimetres: 25.4
            })
        );
        // Delimiters `/` and `#`; fields 3 and 4 are strings holding them; 5-18 are empty.
        let custom = format!("1H//1H#/2Ha,/3Hb/c/{}1.0D-3/5.#", "/".repeat(14));
        let g = globals(custom.as_bytes()).unwrap();
        assert_eq!((g.delim, g.end), (b'/', b'#'));
        assert_eq!(g.resolution, Some(1e-3));
        assert_eq!(g.length_unit, None);
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

    #[test]
    fn units_by_flag_and_by_name() {
        let unit = |flag, name| length_unit(flag, name).map(|u| (u.name, u.millimetres));
        assert_eq!(unit(Some(2), Some("MM")), Some(("MM".into(), 1.0)));
        assert_eq!(unit(Some(6), None), Some(("M".into(), 1000.0)));
        assert_eq!(unit(Some(3), Some("in")), Some(("in".into(), 25.4)));
        assert_eq!(unit(Some(3), Some("furlong")), None);
        assert_eq!(unit(Some(3), None), None);
        assert_eq!(unit(Some(12), Some("MM")), None);
        assert_eq!(unit(None, Some("CM")), Some(("CM".into(), 10.0)));
        let g = globals(b",,,,,,,,,,,,1.,10,2HCM,,,,1e-3;").unwrap();
        assert_eq!(g.length_unit.map(|u| u.millimetres), Some(10.0));
    }
}
