//! Directory entries (IGES 5.3, section 2.2.4.4): two records per entity, nine 8-column
//! fields each.
//!
//! Record 1: entity type, parameter data pointer, structure, line font, level, view,
//! transformation matrix pointer, label display, status number. Record 2: entity type, line
//! weight, color, parameter line count, form number, two reserved fields, label, subscript.
//! The status number's eight digits are four two-digit switches: blank status, subordinate
//! entity switch, entity use flag, hierarchy.

use super::error::IgesError;
use super::records::{Record, trim};

/// What the reader uses of one directory entry. Pointers are as written (range checked where
/// they are followed, so a broken entry only breaks the faces that use it).
#[derive(Clone, Debug, PartialEq)]
pub(super) struct DirEntry {
    /// The sequence number of the entry's first record (odd): its "DE" number.
    pub(super) de: usize,
    /// The entity type number.
    pub(super) kind: i64,
    /// The first parameter data record (1-based).
    pub(super) param_start: i64,
    /// How many parameter data records the entity has.
    pub(super) param_lines: i64,
    /// The transformation matrix (124) pointer; 0 for none.
    pub(super) transform: i64,
    /// The subordinate entity switch (0 independent, 1 physically dependent, 2 logically
    /// dependent, 3 both).
    pub(super) subordinate: u8,
    /// The form number.
    pub(super) form: i64,
}

/// Field `k` (1-based, 8 columns each) of a directory record, as an integer; blank is 0.
fn int_field(r: &Record<'_>, k: usize, name: &'static str) -> Result<i64, IgesError> {
    let raw = trim(r.columns(8 * k - 7, 8 * k));
    if raw.is_empty() {
        return Ok(0);
    }
    let digits = match raw {
        [b'+' | b'-', rest @ ..] => rest,
        _ => raw,
    };
    let parsed = if !digits.is_empty() && digits.iter().all(u8::is_ascii_digit) {
        std::str::from_utf8(raw).ok().and_then(|s| s.parse().ok())
    } else {
        None
    };
    parsed.ok_or_else(|| IgesError::DirectoryField {
        line: r.line,
        field: k,
        name,
        text: String::from_utf8_lossy(raw).into_owned(),
    })
}

/// The subordinate switch: digits 3-4 of the status number (blanks read as zeros).
fn subordinate(r: &Record<'_>) -> Result<u8, IgesError> {
    let status = r.columns(65, 72);
    let digit = |i: usize| -> Result<u8, IgesError> {
        match status.get(i) {
            None | Some(b' ') => Ok(0),
            Some(c) if c.is_ascii_digit() => Ok(c - b'0'),
            Some(_) => Err(IgesError::StatusNumber {
                line: r.line,
                text: String::from_utf8_lossy(status).into_owned(),
            }),
        }
    };
    for i in 0..8 {
        digit(i)?;
    }
    Ok(digit(2)? * 10 + digit(3)?)
}

/// Reads all directory entries (the record pairs of the `D` section).
pub(super) fn entries(directory: &[Record<'_>]) -> Result<Vec<DirEntry>, IgesError> {
    directory
        .chunks_exact(2)
        .enumerate()
        .map(|(i, pair)| {
            let (a, b) = (&pair[0], &pair[1]);
            let kind = int_field(a, 1, "entity type")?;
            let kind2 = int_field(b, 1, "entity type")?;
            if kind != kind2 {
                return Err(IgesError::EntityTypes {
                    line: b.line,
                    de: 2 * i + 1,
                    first: kind,
                    second: kind2,
                });
            }
            Ok(DirEntry {
                de: 2 * i + 1,
                kind,
                param_start: int_field(a, 2, "parameter data")?,
                param_lines: int_field(b, 4, "parameter line count")?,
                transform: int_field(a, 7, "transformation matrix")?,
                subordinate: subordinate(a)?,
                form: int_field(b, 5, "form number")?,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_an_entry_pair() {
        let a = "     144       3       0       0       0       0     121       000020000D0000005";
        let b = "     144       0       0       4       1                               0D0000006";
        let recs = [
            Record {
                line: 9,
                text: a.as_bytes(),
            },
            Record {
                line: 10,
                text: b.as_bytes(),
            },
        ];
        let e = entries(&recs).unwrap();
        assert_eq!(
            e[0],
            DirEntry {
                de: 1,
                kind: 144,
                param_start: 3,
                param_lines: 4,
                transform: 121,
                subordinate: 2,
                form: 1
            }
        );
        let bad = "     14x       3";
        let recs = [
            Record {
                line: 9,
                text: bad.as_bytes(),
            },
            recs[1],
        ];
        let msg = entries(&recs).unwrap_err().to_string();
        assert!(
            msg.contains("line 9") && msg.contains("not an integer"),
            "{msg}"
        );
    }
}
