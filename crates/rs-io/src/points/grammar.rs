//! The grammar of the CSV points file, in one place: the line splitter ([`line_at`]), the
//! parser of a line ([`read_line`]) and the finder of where the data start ([`find_data`]).
//! Every CSV reader of the module goes through these three.

use std::ops::Range;

use rs_spline::Point;

use super::{MAX_LINE_BYTES, PointsError};

/// The UTF-8 byte-order mark (Excel's "CSV UTF-8"), skipped at the start of a file.
const BOM: &[u8] = b"\xef\xbb\xbf";

/// What a line of a points file is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    /// Blank, or a `#` comment.
    Blank,
    /// First two fields `x` and `y` (a header, if no data came before).
    Header,
    /// A point.
    Point,
}

/// What one line of a points file holds. (A struct rather than an enum with the point in a
/// variant: the parser's result then stays in registers in the loop over a block's lines.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Line {
    pub(super) kind: Kind,
    /// The point (the origin for the other kinds).
    pub(super) point: Point,
    /// The byte ranges `[x_start, x_end, y_start, y_end]` of the point's two fields in the
    /// text (zeros for the other kinds).
    pub(super) fields: [usize; 4],
}

impl Line {
    /// A line of `kind` without a point.
    fn of(kind: Kind) -> Self {
        Self {
            kind,
            point: Point::new(0.0, 0.0),
            fields: [0; 4],
        }
    }

    /// The point `(x, y)`, its fields at `x` and `y`.
    fn point(x: f64, y: f64, xs: Range<usize>, ys: Range<usize>) -> Self {
        Self {
            kind: Kind::Point,
            point: Point::new(x, y),
            fields: [xs.start, xs.end, ys.start, ys.end],
        }
    }

    /// The line with its fields' ranges moved by `by`.
    fn shifted(self, by: usize) -> Self {
        match self.kind {
            Kind::Point => Self {
                fields: self.fields.map(|f| f + by),
                ..self
            },
            _ => self,
        }
    }
}

/// The line splitter: the line starting at `text[start]` ends before the returned end (its
/// line end, `\n` or `\r\n`, left out; the text's last line may have none), and the next line
/// starts at the returned next (`text.len()` after the last line).
pub(super) fn line_at(text: &[u8], start: usize) -> (usize, usize) {
    let (end, next) = match memchr::memchr(b'\n', &text[start..]) {
        Some(i) => (start + i, start + i + 1),
        None => (text.len(), text.len()),
    };
    if end > start && text[end - 1] == b'\r' {
        (end - 1, next)
    } else {
        (end, next)
    }
}

/// The parser: what the line starting at `text[start]` holds, and where the next line starts.
/// `line_no` numbers the line in errors.
///
/// The common lines are read on bytes in one pass that also finds the line's end ([`scan`]);
/// the others are split off ([`line_at`]) and parsed as text ([`parse_text`]), which has the
/// error messages. The two read the same grammar, and agree wherever the first answers.
///
/// # Errors
/// [`PointsError::Line`]: a line longer than [`MAX_LINE_BYTES`], not UTF-8, with fewer than
/// two fields, or whose first two fields are not finite numbers (nor a header).
#[inline(always)]
pub(super) fn read_line(
    text: &[u8],
    start: usize,
    line_no: usize,
) -> Result<(Line, usize), PointsError> {
    match scan(text, start) {
        Some(plain) => Ok(plain),
        None => read_text(text, start, line_no),
    }
}

/// [`read_line`] for the lines [`scan`] leaves: split off and parsed as text.
///
/// # Errors
/// As [`read_line`].
#[cold]
#[inline(never)]
pub(super) fn read_text(
    text: &[u8],
    start: usize,
    line_no: usize,
) -> Result<(Line, usize), PointsError> {
    let (end, next) = line_at(text, start);
    if end - start > MAX_LINE_BYTES {
        return Err(too_long(line_no));
    }
    Ok((parse_text(&text[start..end], line_no)?.shifted(start), next))
}

/// The data-start finder: where the data start in `text`, a file's first lines (`at_file_start`
/// if `text` starts the file): past a byte-order mark at the file's start, blank and comment
/// lines and a header line (first two fields `x` and `y`). A bad line counts as data (the
/// parser reports it). `None` if every line of `text` is blank or a comment: the data start
/// after it, if anywhere.
pub(super) fn find_data(text: &[u8], at_file_start: bool) -> Option<usize> {
    let mut start = if at_file_start && text.starts_with(BOM) {
        BOM.len()
    } else {
        0
    };
    while start < text.len() {
        match read_line(text, start, 0) {
            Ok((line, next)) if line.kind == Kind::Blank => start = next,
            Ok((line, next)) if line.kind == Kind::Header => return Some(next),
            Ok(_) | Err(_) => return Some(start),
        }
    }
    None
}

/// The error for line `line`, longer than [`MAX_LINE_BYTES`] without its end.
pub(super) fn too_long(line: usize) -> PointsError {
    PointsError::Line {
        line,
        message: format!("line longer than {MAX_LINE_BYTES} bytes"),
    }
}

/// The error for a header line after data (`line` without its end): its first field is not a
/// number.
pub(super) fn header_as_data(line: &[u8], line_no: usize) -> PointsError {
    let text = String::from_utf8_lossy(line);
    let (fields, _) = first_fields::<2>(text.trim());
    PointsError::Line {
        line: line_no,
        message: format!("{:?} is not a number", shorten(fields[0])),
    }
}

/// Is `b` white space within a line, as `char::is_whitespace` has it for an ASCII byte (a
/// `\n` ends the line instead)?
#[inline(always)]
fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | 0x0b | 0x0c | b'\r')
}

/// The first byte at or after `text[i]` that is not white space within a line: one test when
/// there is none (the common case), the loop out of line.
#[inline(always)]
fn skip_space(text: &[u8], i: usize) -> usize {
    if text.get(i).is_some_and(|&b| is_space(b)) {
        skip_more_space(text, i + 1)
    } else {
        i
    }
}

/// [`skip_space`]'s loop.
#[inline(never)]
fn skip_more_space(text: &[u8], mut i: usize) -> usize {
    while text.get(i).is_some_and(|&b| is_space(b)) {
        i += 1;
    }
    i
}

/// The finite number at the start of `text[at..]` and where it ends, if there is one.
#[inline(always)]
fn number_at(text: &[u8], at: usize) -> Option<(f64, usize)> {
    let (v, used) = fast_float2::parse_partial::<f64, _>(text.get(at..)?).ok()?;
    (used > 0 && v.is_finite()).then_some((v, at + used))
}

/// The common lines, on bytes, in one pass from `text[start]` that also finds where the next
/// line starts: a line whose first two fields are finite numbers (separated by a comma, or by
/// white space when the line has no comma), or a blank or comment line, in ASCII and at most
/// [`MAX_LINE_BYTES`] long. `None` for anything else, left to [`parse_text`].
///
/// The commonest line, `x,y` then its end, takes the first branch at every test.
#[inline(always)]
pub(super) fn scan(text: &[u8], start: usize) -> Option<(Line, usize)> {
    let n = text.len();
    // The first field, after white space if any; or a blank or comment line.
    let (i, (x, x_end)) = match number_at(text, start) {
        Some(x) => (start, x),
        None => {
            let i = skip_space(text, start);
            match text.get(i) {
                None | Some(b'\n') => {
                    return Some((Line::of(Kind::Blank), ends_at(text, start, i)?));
                }
                Some(b'#') => {
                    let end = line_end(text, i);
                    text[i..end].is_ascii().then_some(())?;
                    return Some((Line::of(Kind::Blank), ends_at(text, start, end)?));
                }
                Some(_) if i > start => (i, number_at(text, i)?),
                Some(_) => return None,
            }
        }
    };
    // Comma-separated if the first field ends at a comma; white-space separated otherwise.
    let (comma, j) = if text.get(x_end) == Some(&b',') {
        (true, x_end + 1)
    } else {
        after_first_field(text, x_end)?
    };
    // The second field, after white space if any.
    let (j, (y, y_end)) = match number_at(text, j) {
        Some(y) => (j, y),
        None => {
            let k = skip_space(text, j);
            (k > j).then_some(())?;
            (k, number_at(text, k)?)
        }
    };
    let point = Line::point(x, y, i..x_end, j..y_end);
    // The line ends right after the second field, or goes on.
    let fits = y_end - start <= MAX_LINE_BYTES;
    let next = match text.get(y_end) {
        Some(b'\n') => fits.then_some(y_end + 1),
        Some(b'\r') if text.get(y_end + 1) == Some(&b'\n') => fits.then_some(y_end + 2),
        None => fits.then_some(n),
        Some(_) => after_second_field(text, start, y_end, comma),
    };
    Some((point, next?))
}

/// The end of the line starting at `text[start]` at `at` (its `\n`, or the text's end): where
/// the next one starts, if the line is not too long without its end (`\r\n` or `\n`).
#[inline(always)]
fn ends_at(text: &[u8], start: usize, at: usize) -> Option<usize> {
    let fits =
        at - start <= MAX_LINE_BYTES || at - start == MAX_LINE_BYTES + 1 && text[at - 1] == b'\r';
    fits.then_some(if at < text.len() { at + 1 } else { text.len() })
}

/// Where the line that goes on at `text[from]` ends: its `\n`, or the text's end.
#[inline(always)]
fn line_end(text: &[u8], from: usize) -> usize {
    memchr::memchr(b'\n', &text[from..]).map_or(text.len(), |i| from + i)
}

/// [`scan`] after a second field that the line's end does not follow at once: white space,
/// then the line's end or more fields (after a comma, or after white space in a line with no
/// comma), in ASCII; where the next line starts, or `None`.
#[cold]
#[inline(never)]
fn after_second_field(text: &[u8], start: usize, y_end: usize, comma: bool) -> Option<usize> {
    let after_y = skip_space(text, y_end);
    let end = match text.get(after_y) {
        None | Some(b'\n') => after_y,
        Some(&b) => {
            if !(if comma { b == b',' } else { after_y > y_end }) {
                return None;
            }
            let end = line_end(text, after_y);
            let tail = &text[after_y..end];
            let plain = tail.is_ascii() && (comma || memchr::memchr(b',', tail).is_none());
            plain.then_some(end)?
        }
    };
    ends_at(text, start, end)
}

/// [`scan`] after a first field that a comma does not follow at once: white space, then a
/// comma (comma-separated: the second field's white space starts after it) or the second
/// field (white-space separated); `None` if neither.
#[cold]
#[inline(never)]
fn after_first_field(text: &[u8], x_end: usize) -> Option<(bool, usize)> {
    let after_x = skip_space(text, x_end);
    if text.get(after_x) == Some(&b',') {
        Some((true, after_x + 1))
    } else if after_x > x_end {
        Some((false, after_x))
    } else {
        None
    }
}

/// Any line (without its end), as text, with an error naming what is wrong; field ranges in
/// the line.
fn parse_text(bytes: &[u8], line_no: usize) -> Result<Line, PointsError> {
    let err = |message: String| PointsError::Line {
        line: line_no,
        message,
    };
    let text = std::str::from_utf8(bytes)
        .map_err(|e| err(format!("not UTF-8 text (byte {})", e.valid_up_to() + 1)))?;
    let Some(line) = content(text) else {
        return Ok(Line::of(Kind::Blank));
    };
    let (fields, count) = first_fields::<2>(line);
    if count >= 2 && fields[0].eq_ignore_ascii_case("x") && fields[1].eq_ignore_ascii_case("y") {
        return Ok(Line::of(Kind::Header));
    }
    if count < 2 {
        return Err(err(format!(
            "expected at least two numbers \"x,y\", got {:?}",
            shorten(line)
        )));
    }
    let num = |s: &str| -> Result<f64, PointsError> {
        match parse_number(s) {
            Some(v) if v.is_finite() => Ok(v),
            Some(_) => Err(err(format!("{:?} is not a finite number", shorten(s)))),
            None => Err(err(format!("{:?} is not a number", shorten(s)))),
        }
    };
    let (x, y) = (num(fields[0])?, num(fields[1])?);
    let range = |f: &str| {
        let start = f.as_ptr() as usize - text.as_ptr() as usize;
        start..start + f.len()
    };
    Ok(Line::point(x, y, range(fields[0]), range(fields[1])))
}

/// A decimal number as Rust's `f64` parser reads it (sign, digits, optional fraction and
/// exponent, `inf`, `nan`), correctly rounded, by the `fast-float2` algorithm.
pub(super) fn parse_number(s: &str) -> Option<f64> {
    // fast-float2 accepts the same grammar as `str::parse::<f64>` except a leading `+` on
    // "inf"/"nan" spellings, which both reject as non-finite anyway.
    fast_float2::parse::<f64, _>(s).ok()
}

/// A line's text (without its end) as the grammar reads it: trimmed, `None` for a blank line
/// or a `#` comment.
pub(super) fn content(line: &str) -> Option<&str> {
    let line = line.trim();
    (!line.is_empty() && !line.starts_with('#')).then_some(line)
}

/// The first `N` fields of a line and how many it has (up to `N`): split at commas when the
/// line has one (each field trimmed), else at white space. The one field rule of points files,
/// in the plane (`N = 2`) and in space (`N = 3`).
pub(super) fn first_fields<const N: usize>(line: &str) -> ([&str; N], usize) {
    fn take<'a, const N: usize>(it: impl Iterator<Item = &'a str>) -> ([&'a str; N], usize) {
        let mut fields = [""; N];
        let mut count = 0;
        for (slot, f) in fields.iter_mut().zip(it) {
            *slot = f;
            count += 1;
        }
        (fields, count)
    }
    if line.contains(',') {
        take(line.split(',').map(str::trim))
    } else {
        take(line.split_whitespace())
    }
}

/// At most 60 characters of `s`, for error messages.
pub(super) fn shorten(s: &str) -> String {
    if s.chars().count() <= 60 {
        s.to_string()
    } else {
        s.chars().take(57).collect::<String>() + "..."
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Indices below `k`, for random lines from `seed`.
    fn xorshift(seed: u64) -> impl FnMut(usize) -> usize {
        let mut rng = rs_testkit::XorShift64::new(seed);
        move |k| rng.below(k as u64) as usize
    }

    /// Checks the one-pass scan of the line after `9,9\n` in `text` against the line split
    /// off and parsed as text; true if the scan answered (with a point if `points`).
    fn scan_agrees(text: &[u8], points: &mut usize) -> bool {
        let Some((fast, next)) = scan(text, 4) else {
            return false;
        };
        let shown = String::from_utf8_lossy(text);
        let (end, want_next) = line_at(text, 4);
        assert_eq!(next, want_next, "{shown:?}");
        assert!(end - 4 <= MAX_LINE_BYTES);
        let general = parse_text(&text[4..end], 1).unwrap().shifted(4);
        *points += usize::from(fast.kind == Kind::Point);
        assert_eq!(fast, general, "{shown:?}");
        true
    }

    /// The byte-level scan answers as the text parser does wherever it answers, and finds
    /// where the next line starts: lines of white space, commas and numbers, mostly
    /// well-formed, with every kind of line end.
    #[test]
    fn the_scan_agrees_with_the_text_parser() {
        let tokens: [&[u8]; 29] = [
            b"1",
            b"-2.5",
            b"3e-7",
            b"+.5",
            b"x",
            b"Y",
            b"#",
            b",",
            b",",
            b" ",
            b"  ",
            b"\t",
            b"\x0b",
            b"\x0c",
            b"nan",
            b"inf",
            b"1e999",
            b"abc",
            b"",
            b"0",
            b"1_0",
            "\u{a0}".as_bytes(),
            "\u{e9}".as_bytes(),
            b".",
            b"\r",
            b"1e",
            b"-",
            b"\xff",
            b"\xc3",
        ];
        let endings: [&[u8]; 6] = [b"\n", b"\r\n", b"", b"\r", b"\r\r\n", b"\n1,2\n"];
        let mut next = xorshift(0x9E37_79B9_7F4A_7C15);
        let (mut answered, mut points) = (0, 0);
        for i in 0..80000 {
            let mut text = b"9,9\n".to_vec();
            if i % 4 != 0 {
                // Mostly well-formed: number, separator, number, then anything.
                let sep = [",", " ", "\t", " , ", ",\u{b}", ","][next(6)];
                let x = (next(2000) as f64 - 1000.0) * 0.37;
                text.extend_from_slice(format!("{x}{sep}").as_bytes());
                text.extend_from_slice(tokens[next(4)]);
            }
            for _ in 0..next(7) {
                text.extend_from_slice(tokens[next(tokens.len())]);
            }
            text.extend_from_slice(endings[next(endings.len())]);
            answered += usize::from(scan_agrees(&text, &mut points));
        }
        assert!(answered > 20000 && points > 15000, "{answered} {points}");
    }

    /// Lines about [`MAX_LINE_BYTES`] long are measured without their end, blank and comment
    /// lines too.
    #[test]
    fn lines_are_measured_without_their_end() {
        for filler in ["1,0.", " ", "#"] {
            for len in [MAX_LINE_BYTES, MAX_LINE_BYTES + 1] {
                for ending in ["\n", "\r\n", ""] {
                    let line = format!("{filler}{}", "0".repeat(len - filler.len()));
                    let line = if filler == " " { " ".repeat(len) } else { line };
                    let text = format!("9,9\n{line}{ending}");
                    let read = read_line(text.as_bytes(), 4, 2);
                    assert_eq!(
                        read.is_ok(),
                        len <= MAX_LINE_BYTES,
                        "{filler:?} {len} {ending:?}"
                    );
                    if let Ok((_, next)) = read {
                        assert_eq!(next, text.len());
                    }
                }
            }
        }
    }

    #[test]
    fn the_data_start_after_the_mark_the_comments_and_the_header() {
        let cases: [(&[u8], bool, Option<usize>); 9] = [
            (b"\xef\xbb\xbfx,y\n1,2\n", true, Some(7)),
            (b"\xef\xbb\xbf1,2\n", true, Some(3)),
            (b"\xef\xbb\xbf1,2\n", false, Some(0)), // a mark not at the start is data (bad)
            (b"# c\n\n  \r\nX , Y,kind\r\n1,2", true, Some(21)),
            (b"# c\n\n", true, None),
            (b"", true, None),
            (b"\n\nbad\n", true, Some(2)),
            (b"1,2\nx,y\n", true, Some(0)),
            (b"\xef\xbb\xbf", true, None),
        ];
        for (text, at_start, want) in cases {
            assert_eq!(
                find_data(text, at_start),
                want,
                "{:?}",
                String::from_utf8_lossy(text)
            );
        }
    }

    /// The fast parser reads every number as `str::parse` does.
    #[test]
    fn numbers_parse_as_the_standard_library_does() {
        let mut cases: Vec<String> = [
            "1",
            "+1",
            "-1",
            "1.",
            ".5",
            "+.5",
            ".",
            "+",
            "",
            "1e5",
            "1E+5",
            "1e-5",
            "1e",
            "e5",
            "inf",
            "-inf",
            "infinity",
            "NaN",
            "1_000",
            "0x10",
            " 1",
            "1.2.3",
            "1e400",
            "1e-400",
            "5e-324",
            "2.2250738585072011e-308",
            "1,5",
            "1.e5",
            ".e5",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        let mut rng = rs_testkit::XorShift64::new(0x2545_F491_4F6C_DD1D);
        for _ in 0..2000 {
            let x = rng.next_u64();
            let v = f64::from_bits(x);
            cases.push(format!("{v}"));
            cases.push(format!("{v:e}"));
            cases.push(format!("{:.17}", (x >> 11) as f64 / 1e3));
        }
        for c in &cases {
            let std = c.parse::<f64>().ok();
            let fast = parse_number(c);
            assert!(
                std.map(f64::to_bits) == fast.map(f64::to_bits)
                    || std.is_some_and(f64::is_nan) && fast.is_some_and(f64::is_nan),
                "{c:?}: {std:?} vs {fast:?}"
            );
        }
    }
}
