//! The fixed-column records of an IGES file (IGES 5.3, section 2.1) and its five sections.
//!
//! Every record is 80 columns: columns 1-72 hold the data, column 73 the section letter
//! (`S` start, `G` global, `D` directory, `P` parameter data, `T` terminate) and columns 74-80
//! the record's sequence number within its section. Lines may end in LF or CRLF, and a line
//! shorter than 80 columns is read as if padded with blanks. A file without any line break
//! whose length is a multiple of 80 is read as consecutive 80-byte records. Blank lines are
//! skipped. The compressed ASCII form (flag section `C`) and the binary form (`B`) are refused.

use super::error::IgesError;

/// Columns per record.
const RECORD: usize = 80;

/// One record: its line in the file (1-based) and its bytes (at most 80, no line break).
#[derive(Clone, Copy, Debug)]
pub(super) struct Record<'a> {
    /// 1-based line number in the file (record number for files without line breaks).
    pub(super) line: usize,
    /// The record's bytes, at most 80.
    pub(super) text: &'a [u8],
}

impl<'a> Record<'a> {
    /// Columns `first..=last` (1-based), cut short if the line is shorter.
    pub(super) fn columns(&self, first: usize, last: usize) -> &'a [u8] {
        let end = last.min(self.text.len());
        let start = (first - 1).min(end);
        &self.text[start..end]
    }

    /// The section letter in column 73 (a blank if the line is shorter).
    fn section(&self) -> u8 {
        self.text.get(72).copied().unwrap_or(b' ')
    }

    /// The sequence number in columns 74-80, if it is written (blank is `None`).
    fn sequence(&self) -> Result<Option<usize>, IgesError> {
        let s = trim(self.columns(74, 80));
        if s.is_empty() {
            return Ok(None);
        }
        std::str::from_utf8(s)
            .ok()
            .and_then(|s| s.parse::<usize>().ok())
            .map(Some)
            .ok_or_else(|| IgesError::BadSequence {
                line: self.line,
                text: String::from_utf8_lossy(s).into_owned(),
            })
    }
}

/// Strips blanks (spaces, tabs) at both ends.
pub(super) fn trim(mut s: &[u8]) -> &[u8] {
    while let [b' ' | b'\t', rest @ ..] = s {
        s = rest;
    }
    while let [rest @ .., b' ' | b'\t'] = s {
        s = rest;
    }
    s
}

/// The records of an IGES file, by section. Invariant: `directory.len()` is even and the
/// records of each section are numbered `1, 2, ...` in file order (checked where written).
#[derive(Debug)]
pub(super) struct Sections<'a> {
    /// The global section's data (columns 1-72 of every `G` record, concatenated).
    pub(super) global: Vec<u8>,
    /// The directory records, two per entity.
    pub(super) directory: Vec<Record<'a>>,
    /// The parameter data records; record `k` (1-based) is `parameters[k - 1]`.
    pub(super) parameters: Vec<Record<'a>>,
}

/// Splits `bytes` into records: at line breaks, or into 80-byte records for a file without any.
fn split_records(bytes: &[u8]) -> Result<Vec<Record<'_>>, IgesError> {
    let mut out = Vec::new();
    if memchr::memchr(b'\n', bytes).is_none() && bytes.len() > RECORD {
        if !bytes.len().is_multiple_of(RECORD) {
            return Err(IgesError::NoLineBreaks {
                columns: bytes.len(),
            });
        }
        for (i, text) in bytes.chunks(RECORD).enumerate() {
            out.push(Record { line: i + 1, text });
        }
        return Ok(out);
    }
    for (i, raw) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = i + 1;
        let mut text = raw.strip_suffix(b"\r").unwrap_or(raw);
        if text.len() > RECORD {
            // Blanks past column 80 are harmless; anything else is not an IGES record.
            let (head, tail) = text.split_at(RECORD);
            if !trim(tail).is_empty() {
                return Err(IgesError::LongLine {
                    line,
                    columns: text.len(),
                });
            }
            text = head;
        }
        // A blank line, or the DOS end-of-file mark, is not a record.
        if trim(text).is_empty() || text == b"\x1a" {
            continue;
        }
        out.push(Record { line, text });
    }
    Ok(out)
}

/// Reads the records of `bytes` and checks the section structure: `S`, `G`, `D`, `P`, `T` in
/// this order, each numbered from 1, one `T` record last, an even number of `D` records.
pub(super) fn sections(bytes: &[u8]) -> Result<Sections<'_>, IgesError> {
    let records = split_records(bytes)?;
    let Some(first) = records.first() else {
        return Err(IgesError::Empty);
    };
    match first.section() {
        b'C' => return Err(IgesError::Compressed),
        b'B' => return Err(IgesError::Binary),
        _ => {}
    }
    const ORDER: &[u8] = b"SGDPT";
    let mut stage = 0usize; // index into ORDER of the current section
    let mut count = [0usize; 5];
    let mut global = Vec::new();
    let mut directory = Vec::new();
    let mut parameters = Vec::new();
    for r in &records {
        let letter = r.section();
        let Some(at) = ORDER.iter().position(|&c| c == letter) else {
            if r.text.len() < 73 {
                return Err(IgesError::NoSectionLetter {
                    line: r.line,
                    columns: r.text.len(),
                    last: std::ptr::eq(r, records.last().unwrap_or(r)),
                });
            }
            return Err(IgesError::UnknownSection {
                line: r.line,
                letter: char::from(letter),
            });
        };
        if at < stage || (at > stage && count[4] > 0) {
            return Err(IgesError::SectionOrder {
                line: r.line,
                found: char::from(letter),
                after: char::from(ORDER[stage]),
            });
        }
        stage = at;
        count[at] += 1;
        if let Some(seq) = r.sequence()?
            && seq != count[at]
        {
            return Err(IgesError::Sequence {
                line: r.line,
                section: char::from(letter),
                found: seq,
                expected: count[at],
            });
        }
        match letter {
            b'G' => global.extend_from_slice(r.columns(1, 72)),
            b'D' => directory.push(*r),
            b'P' => parameters.push(*r),
            b'T' if count[4] > 1 => {
                return Err(IgesError::SecondTerminate { line: r.line });
            }
            _ => {}
        }
    }
    if count[1] == 0 {
        return Err(IgesError::NoGlobal);
    }
    if count[4] == 0 {
        return Err(IgesError::NoTerminate);
    }
    if directory.len() % 2 != 0 {
        let last = directory.last().map_or(0, |r| r.line);
        return Err(IgesError::OddDirectory {
            line: last,
            count: directory.len(),
        });
    }
    Ok(Sections {
        global,
        directory,
        parameters,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rec(data: &str, letter: char, seq: usize) -> String {
        format!("{data:<72}{letter}{seq:07}\n")
    }

    #[test]
    fn sections_in_order_with_crlf_and_short_lines() {
        let mut f = rec("", 'S', 1).replace('\n', "\r\n");
        f += &rec("1H,,1H;;", 'G', 1);
        f += "     110       1       0       0       0       0       0       000000000D0000001\n";
        f += "     110       0       0       1       0                               0D0000002\n";
        f += &rec("110,0,0,0,1,1,0;", 'P', 1);
        f += "S      1G      1D      2P      1                                        T0000001";
        let s = sections(f.as_bytes()).unwrap();
        assert_eq!(s.directory.len(), 2);
        assert_eq!(s.parameters.len(), 1);
        assert_eq!(&s.global[..8], b"1H,,1H;;");
        // A short record reads as blank-padded.
        let r = Record {
            line: 1,
            text: b"abc",
        };
        assert_eq!(r.columns(2, 10), b"bc");
        assert_eq!(r.columns(5, 10), b"");
    }

    #[test]
    fn broken_structures_are_refused() {
        let g = rec(",,;", 'G', 1);
        let s = rec("", 'S', 1);
        let t = rec("", 'T', 1);
        let msg = |f: String| sections(f.as_bytes()).unwrap_err().to_string();
        assert!(msg(format!("{g}{s}{t}")).contains("section S after section G"));
        assert!(msg(format!("{s}{g}")).contains("truncated"));
        assert!(msg(String::new()).contains("empty"));
        assert!(msg(format!("{s}{}{t}", rec(",,;", 'G', 3))).contains("numbered 3"));
        assert!(msg(format!("{s}{g}{}{t}", rec("", 'D', 1))).contains("odd number"));
        assert!(msg(format!("{s}{g}{}", "x".repeat(200))).contains("200 columns"));
        assert!(msg(format!("{:<72}C0000001\n", "")).contains("compressed"));
        assert!(msg(format!("{s}{}", rec("", 'X', 1))).contains("unknown section"));
    }
}
