//! Handing a DXF file to the `dxf` crate without letting hostile content crash the caller.
//!
//! The crate converts every date it reads (the header's `$TDCREATE`, `$TDUCREATE`,
//! `$TDUPDATE`, `$TDUUPDATE`, and time stamps of objects) to a calendar date and panics when
//! the number is beyond the calendar's range (`1e16` days, say). Nothing here uses those
//! dates, so a text DXF is first cleared of them: out-of-range header dates become `0` (the
//! crate's "no date") and the `OBJECTS` section is left out (only entities are read). Any
//! other panic of the crate becomes an [`IoError::Dxf`] instead of unwinding into the caller.

use crate::IoError;

/// The header variables the `dxf` crate reads as calendar dates (Julian days).
const DATE_VARIABLES: [&str; 4] = ["$TDCREATE", "$TDUCREATE", "$TDUPDATE", "$TDUUPDATE"];
/// Julian days the crate's date conversion takes without overflow, with a wide margin: up to
/// the year 20 000 or so (it fails beyond about 9.5e7 days).
const MAX_JULIAN_DAY: f64 = 1e7;

/// Parses DXF bytes (text, binary or DXB) into a drawing; see the module documentation.
///
/// # Errors
/// [`IoError::Dxf`] if the crate reports an error or panics.
pub(super) fn load_drawing(bytes: &[u8]) -> Result<dxf::Drawing, IoError> {
    let cleared = cleared_text(bytes);
    let bytes = cleared.as_deref().unwrap_or(bytes);
    match std::panic::catch_unwind(|| dxf::Drawing::load(&mut &bytes[..])) {
        Ok(result) => result.map_err(|e| IoError::Dxf(e.to_string())),
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "no message".to_string());
            Err(IoError::Dxf(format!(
                "the DXF reader failed on this file ({what})"
            )))
        }
    }
}

/// A text DXF without the content the module documentation names, or `None` if there is
/// nothing to clear or the bytes are binary. From a line that is not a group code on, the
/// text is kept as it is (the crate reports the error there, unless a date before it made it
/// panic first: those are cleared).
fn cleared_text(bytes: &[u8]) -> Option<Vec<u8>> {
    if bytes.starts_with(b"AutoCAD Binary DXF") || bytes.starts_with(b"AutoCAD DXB") {
        return None;
    }
    let lines: Vec<&[u8]> = bytes.split_inclusive(|&b| b == b'\n').collect();
    let mut out = Vec::with_capacity(bytes.len());
    let mut changed = false;
    // The section being read (its name), a `0 SECTION` pair not yet written (it is dropped
    // with an `OBJECTS` section), and whether a date variable's value comes next.
    let (mut section, mut opening, mut date_next): (&[u8], Option<&[&[u8]]>, bool) =
        (b"", None, false);
    let mut pairs = lines.chunks(2);
    while let Some(pair) = pairs.next() {
        let &[code_line, value_line] = pair else {
            out.extend(opening.take().into_iter().flatten().copied().flatten());
            out.extend_from_slice(pair[0]);
            break;
        };
        let Some(code) = std::str::from_utf8(code_line.trim_ascii())
            .ok()
            .and_then(|c| c.parse::<i32>().ok())
        else {
            out.extend(opening.take().into_iter().flatten().copied().flatten());
            out.extend(pair.iter().copied().flatten());
            out.extend(pairs.flatten().copied().flatten());
            break;
        };
        let value = value_line.trim_ascii();
        if code == 0 && value == b"SECTION" {
            opening = Some(pair);
            continue;
        }
        if let Some(open) = opening.take() {
            if code == 2 && value == b"OBJECTS" {
                skip_to_end_of_section(&mut pairs);
                changed = true;
                continue;
            }
            out.extend(open.iter().copied().flatten());
            section = if code == 2 { value } else { b"" };
        }
        if section == b"HEADER" && code == 9 {
            date_next = DATE_VARIABLES.iter().any(|v| v.as_bytes() == value);
        } else if date_next && code == 40 {
            date_next = false;
            let day = std::str::from_utf8(value)
                .ok()
                .and_then(|s| s.trim().parse::<f64>().ok());
            if !day.is_some_and(|d| (0.0..=MAX_JULIAN_DAY).contains(&d)) {
                out.extend_from_slice(code_line);
                out.extend_from_slice(b"0\n");
                changed = true;
                continue;
            }
        }
        out.extend_from_slice(code_line);
        out.extend_from_slice(value_line);
    }
    if let Some(open) = opening {
        out.extend(open.iter().copied().flatten());
    }
    changed.then_some(out)
}

/// Skips pairs up to and including the `0 ENDSEC` pair.
fn skip_to_end_of_section<'a>(pairs: &mut impl Iterator<Item = &'a [&'a [u8]]>) {
    for pair in pairs {
        if let &[code, value] = pair
            && code.trim_ascii() == b"0"
            && value.trim_ascii() == b"ENDSEC"
        {
            return;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The CLI's test drawing: a plate with a hole, a slot and arcs, as written by a CAD
    /// program (header dates, an `OBJECTS` section).
    fn plate() -> Vec<u8> {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/io/plate.dxf");
        std::fs::read(path).unwrap()
    }

    /// `text` with the value of the first pair `code`/`value`'s following `40` pair set to
    /// `to`.
    fn with_value_after(text: &str, marker: &str, to: &str) -> String {
        let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
        let at = lines.iter().position(|l| l.trim() == marker).unwrap();
        assert_eq!(lines[at + 1].trim(), "40");
        lines[at + 2] = to.to_string();
        lines.join("\r\n") + "\r\n"
    }

    /// The entities of a drawing, as the domain reader sees them.
    fn entities(d: &dxf::Drawing) -> Vec<String> {
        d.entities().map(|e| format!("{:?}", e.specific)).collect()
    }

    #[test]
    fn dates_beyond_the_calendar_are_cleared_not_a_panic() {
        let original = load_drawing(&plate()).unwrap();
        let text = String::from_utf8(plate()).unwrap();
        assert!(text.contains("OBJECTS") && text.contains("$TDCREATE"));
        for bad in [
            "1e16",
            "24699999999999999999999991367.3",
            "-1e300",
            "nan",
            "inf",
            "x",
        ] {
            for marker in DATE_VARIABLES {
                let hostile = with_value_after(&text, marker, bad);
                let d = load_drawing(hostile.as_bytes())
                    .unwrap_or_else(|e| panic!("{marker} = {bad}: {e}"));
                assert_eq!(entities(&d), entities(&original), "{marker} = {bad}");
            }
        }
        // A date in range is kept as it is: the crate reads the same from the file itself.
        let fine = with_value_after(&text, "$TDCREATE", "2451545.0");
        let d = load_drawing(fine.as_bytes()).unwrap();
        let direct = dxf::Drawing::load(&mut fine.as_bytes()).unwrap();
        assert_eq!(d.header.creation_date, direct.header.creation_date);
        assert_ne!(d.header.creation_date, original.header.creation_date);
    }

    #[test]
    fn the_objects_section_is_left_out_and_the_rest_kept() {
        let text = plate();
        let cleared = cleared_text(&text).unwrap();
        let cleared = String::from_utf8(cleared).unwrap();
        assert!(!cleared.contains("OBJECTS"));
        let original = String::from_utf8(text).unwrap();
        let start = original.find("OBJECTS").unwrap();
        let before = original[..start].rfind("SECTION").unwrap();
        // Everything before the section's `0 SECTION` pair is unchanged.
        let head = &original[..original[..before].rfind('\n').unwrap()];
        let head = &head[..head.rfind('\n').unwrap()];
        assert!(cleared.starts_with(head));
        assert!(cleared.trim_end().ends_with("EOF"));
    }

    #[test]
    fn a_bad_group_code_after_a_bad_date_is_an_error_naming_its_line() {
        let text = String::from_utf8(plate()).unwrap();
        let hostile = with_value_after(&text, "$TDUPDATE", "1e200");
        let mut lines: Vec<&str> = hostile.lines().collect();
        let entities = lines.iter().position(|l| *l == "ENTITIES").unwrap();
        lines[entities + 1] = " 2\u{ff}";
        let err = load_drawing(lines.join("\n").as_bytes()).unwrap_err();
        // The crate counts from the pair's value line: one past the code line (1-based).
        let line = format!("line/offset {}", entities + 3);
        assert!(
            matches!(err, IoError::Dxf(_)) && err.to_string().contains(&line),
            "{err}"
        );
    }

    /// Binary DXF is not cleared: a date beyond the calendar makes the crate panic, which
    /// comes back as an error.
    #[test]
    fn a_panic_of_the_reader_is_an_error() {
        let mut binary = Vec::new();
        load_drawing(&plate())
            .unwrap()
            .save_binary(&mut binary)
            .unwrap();
        let name = b"$TDCREATE\0";
        let at = binary.windows(name.len()).position(|w| w == name).unwrap() + name.len();
        // The group code (40, two bytes) and then the value, eight bytes.
        assert_eq!(&binary[at..at + 2], &[40, 0]);
        binary[at + 2..at + 10].copy_from_slice(&1e16f64.to_le_bytes());
        assert!(cleared_text(&binary).is_none());
        let err = load_drawing(&binary).unwrap_err();
        assert!(err.to_string().contains("the DXF reader failed"), "{err}");
    }
}
