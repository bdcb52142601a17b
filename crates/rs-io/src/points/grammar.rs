//! The grammar of the CSV points file, in one place: the line splitter ([`line_at`]), the
//! parser of a line ([`read_line`]) and the finder of where the data start ([`find_data`]).
//! Every CSV reader of the module goes through these three.

use std::ops::Range;

use rs_spline::Point;

use super::{MAX_LINE_BYTES, PointsError};

/// The UTF-8 byte-order mark (Excel's "CSV UTF-8"), skipped at the start of a file.
const BOM: &[u8] = b"\xef\xbb\xbf";

/// What one line of a points file holds.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Line {
    /// Blank, or a `#` comment.
    Blank,
    /// First two fields `x` and `y` (a header, if no data came before).
    Header,
    /// A point, with the byte ranges of its two fields in the text.
    Point {
        point: Point,
        x: Range<usize>,
        y: Range<usize>,
    },
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
#[inline]
pub(super) fn read_line(
    text: &[u8],
    start: usize,
    line_no: usize,
) -> Result<(Line, usize), PointsError> {
    if let Some(plain) = scan(text, start) {
        return Ok(plain);
    }
    let (end, next) = line_at(text, start);
    if end - start > MAX_LINE_BYTES {
        return Err(too_long(line_no));
    }
    let line = match parse_text(&text[start..end], line_no)? {
        Line::Point { point, x, y } => Line::Point {
            point,
            x: start + x.start..start + x.end,
            y: start + y.start..start + y.end,
        },
        other => other,
    };
    Ok((line, next))
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
            Ok((Line::Blank, next)) => start = next,
            Ok((Line::Header, next)) => return Some(next),
            Ok((Line::Point { .. }, _)) | Err(_) => return Some(start),
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
    let (fields, _) = first_two_fields(text.trim());
    PointsError::Line {
        line: line_no,
        message: format!("{:?} is not a number", shorten(fields[0])),
    }
}

/// Is `b` white space within a line, as `char::is_whitespace` has it for an ASCII byte (a
/// `\n` ends the line instead)?
#[inline]
fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | 0x0b | 0x0c | b'\r')
}

/// The common lines, on bytes, in one pass from `text[start]` that also finds where the next
/// line starts: a line whose first two fields are finite numbers (separated by a comma, or by
/// white space when the line has no comma), or a blank or comment line, in ASCII and at most
/// [`MAX_LINE_BYTES`] long. `None` for anything else, left to [`parse_text`].
#[inline]
fn scan(text: &[u8], start: usize) -> Option<(Line, usize)> {
    let n = text.len();
    let skip_space = |mut i: usize| {
        while i < n && is_space(text[i]) {
            i += 1;
        }
        i
    };
    // The line ends at `at` (its '\n', or the text's end): where the next one starts, if the
    // line is not too long without its end.
    let ends_at = |at: usize| {
        let len = at - start - usize::from(at > start && text[at - 1] == b'\r');
        (len <= MAX_LINE_BYTES).then_some((at + 1).min(n))
    };
    let line_end = |from: usize| memchr::memchr(b'\n', &text[from..]).map_or(n, |i| from + i);
    let i = skip_space(start);
    match text.get(i) {
        None | Some(b'\n') => return Some((Line::Blank, ends_at(i)?)),
        Some(b'#') => {
            let end = line_end(i);
            return text[i..end]
                .is_ascii()
                .then_some(())
                .and_then(|()| Some((Line::Blank, ends_at(end)?)));
        }
        Some(_) => {}
    }
    let number = |at: usize| {
        let (v, used) = fast_float2::parse_partial::<f64, _>(&text[at..]).ok()?;
        (used > 0 && v.is_finite()).then_some((v, at + used))
    };
    let (x, x_end) = number(i)?;
    let after_x = skip_space(x_end);
    // Comma-separated if the first field ends at a comma; white-space separated otherwise.
    let comma = text.get(after_x) == Some(&b',');
    let j = if comma {
        skip_space(after_x + 1)
    } else if after_x > x_end {
        after_x
    } else {
        return None;
    };
    let (y, y_end) = number(j)?;
    let after_y = skip_space(y_end);
    let point = Line::Point {
        point: Point::new(x, y),
        x: i..x_end,
        y: j..y_end,
    };
    match text.get(after_y) {
        None | Some(b'\n') => Some((point, ends_at(after_y)?)),
        Some(&b) => {
            // More fields: after a comma, or after white space in a line with no comma.
            if !(if comma { b == b',' } else { after_y > y_end }) {
                return None;
            }
            let end = line_end(after_y);
            let tail = &text[after_y..end];
            let plain = tail.is_ascii() && (comma || memchr::memchr(b',', tail).is_none());
            plain.then_some(())?;
            Some((point, ends_at(end)?))
        }
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
    let line = text.trim();
    if line.is_empty() || line.starts_with('#') {
        return Ok(Line::Blank);
    }
    let (fields, count) = first_two_fields(line);
    if count >= 2 && fields[0].eq_ignore_ascii_case("x") && fields[1].eq_ignore_ascii_case("y") {
        return Ok(Line::Header);
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
    Ok(Line::Point {
        point: Point::new(x, y),
        x: range(fields[0]),
        y: range(fields[1]),
    })
}

/// A decimal number as Rust's `f64` parser reads it (sign, digits, optional fraction and
/// exponent, `inf`, `nan`), correctly rounded, by the `fast-float2` algorithm.
fn parse_number(s: &str) -> Option<f64> {
    // fast-float2 accepts the same grammar as `str::parse::<f64>` except a leading `+` on
    // "inf"/"nan" spellings, which both reject as non-finite anyway.
    fast_float2::parse::<f64, _>(s).ok()
}

/// The first two fields of a line (comma-separated if it has a comma, else white-space
/// separated) and how many fields it has (counting stops at 2).
fn first_two_fields(line: &str) -> ([&str; 2], usize) {
    fn two<'a>(mut it: impl Iterator<Item = &'a str>) -> ([&'a str; 2], usize) {
        match (it.next(), it.next()) {
            (Some(a), Some(b)) => ([a, b], 2),
            (Some(a), None) => ([a, ""], 1),
            _ => (["", ""], 0),
        }
    }
    if line.contains(',') {
        two(line.split(',').map(str::trim))
    } else {
        two(line.split_whitespace())
    }
}

/// At most 60 characters of `s`, for error messages.
fn shorten(s: &str) -> String {
    if s.chars().count() <= 60 {
        s.to_string()
    } else {
        s.chars().take(57).collect::<String>() + "..."
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A xorshift generator of indices below `k`, for random lines from `seed`.
    fn xorshift(mut state: u64) -> impl FnMut(usize) -> usize {
        move |k| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % k as u64) as usize
        }
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
        let general = match parse_text(&text[4..end], 1) {
            Ok(Line::Point { point, x, y }) => Line::Point {
                point,
                x: 4 + x.start..4 + x.end,
                y: 4 + y.start..4 + y.end,
            },
            other => other.unwrap(),
        };
        *points += usize::from(matches!(fast, Line::Point { .. }));
        assert_eq!(fast, general, "{shown:?}");
        true
    }

    /// The byte-level scan answers as the text parser does wherever it answers, and finds
    /// where the next line starts: lines of white space, commas and numbers, mostly
    /// well-formed, with every kind of line end.
    #[test]
    fn the_scan_agrees_with_the_text_parser() {
        let tokens = [
            "1", "-2.5", "3e-7", "+.5", "x", "Y", "#", ",", ",", " ", "  ", "\t", "\u{b}", "\u{c}",
            "nan", "inf", "1e999", "abc", "", "0", "1_0", "\u{a0}", "é", ".", "\r", "1e", "-",
        ];
        let endings = ["\n", "\r\n", "", "\r", "\r\r\n", "\n1,2\n"];
        let mut next = xorshift(0x9E37_79B9_7F4A_7C15);
        let (mut answered, mut points) = (0, 0);
        for i in 0..80000 {
            let n = next(7);
            let mut line: String = (0..n).map(|_| tokens[next(tokens.len())]).collect();
            if i % 4 != 0 {
                // Mostly well-formed: number, separator, number, then anything.
                let sep = [",", " ", "\t", " , ", ",\u{b}", ","][next(6)];
                let x = (next(2000) as f64 - 1000.0) * 0.37;
                line = format!("{x}{sep}{}{line}", tokens[next(4)]);
            }
            let text = format!("9,9\n{line}{}", endings[next(endings.len())]);
            answered += usize::from(scan_agrees(text.as_bytes(), &mut points));
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
        let mut x: u64 = 0x2545_F491_4F6C_DD1D;
        for _ in 0..2000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
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
