//! The points file: `x,y` per line, read as a stream.

use std::io::BufRead;
use std::path::Path;

use rs_spline::Point;
use thiserror::Error;

/// The longest line a points file may have, in bytes, without its end (`\n` or `\r\n`): a
/// file without line breaks is an error, not an unbounded allocation.
pub const MAX_LINE_BYTES: usize = 64 * 1024;

/// A parsed point with the text it was written as (echoed unchanged in outputs).
#[derive(Clone, Debug, PartialEq)]
pub struct PointRecord {
    /// The point.
    pub point: Point,
    /// The abscissa as written.
    pub x_text: String,
    /// The ordinate as written.
    pub y_text: String,
}

/// A bad points file.
#[derive(Debug, Error)]
pub enum PointsError {
    /// The file could not be read.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The underlying error.
        source: std::io::Error,
    },
    /// A `.npy` points file is not an array of shape `(N, 2)` of floats, or is cut short.
    #[error("{path}: {message}")]
    Npy {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// A line is not a point.
    #[error("line {line}: {message}")]
    Line {
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        message: String,
    },
}

/// A streaming reader of a points file: one point per line, `x,y` separated by a comma or white
/// space; further columns are allowed and ignored (so the `x,y,kind` files of `inrs sample` and
/// the `x,y,location` files of `inrs classify` read back); an optional header line whose first
/// two fields are `x` and `y`; blank lines and `#` comment lines ignored; a UTF-8 byte-order
/// mark at the start (Excel's "CSV UTF-8") skipped; Windows line ends accepted. Numbers are
/// parsed exactly as written (shortest round-trip `f64`); NaN and infinities are rejected.
///
/// Memory is one line at a time (at most [`MAX_LINE_BYTES`]), whatever the file's size.
///
/// # Examples
///
/// ```
/// let text = "\u{feff}x,y,kind\n# a comment\n0.5, 1, boundary\n2 3e-1\n";
/// let pts: Vec<_> = inrs::PointReader::new(text.as_bytes()).collect::<Result<_, _>>().unwrap();
/// assert_eq!(pts.len(), 2);
/// assert_eq!(pts[1].point, inrs::Point::new(2.0, 0.3));
/// assert_eq!(pts[1].y_text, "3e-1");
/// ```
#[derive(Debug)]
pub struct PointReader<R> {
    input: R,
    line: usize,
    seen_data: bool,
    buf: Vec<u8>,
    failed: bool,
    path: String,
}

impl<R: BufRead> PointReader<R> {
    /// Reads points from `input`.
    pub fn new(input: R) -> Self {
        Self::named(input, "input")
    }

    /// Reads points from `input`, naming it `path` in I/O errors.
    pub fn named(input: R, path: impl Into<String>) -> Self {
        Self {
            input,
            line: 0,
            seen_data: false,
            buf: Vec::new(),
            failed: false,
            path: path.into(),
        }
    }

    /// Reads the next line into `buf` (without its end, `\n` or `\r\n`), at most
    /// [`MAX_LINE_BYTES`] bytes.
    /// `Ok(false)` at the end of the input.
    fn next_line(&mut self) -> Result<bool, PointsError> {
        self.buf.clear();
        let limit = (MAX_LINE_BYTES + 2) as u64;
        let input: &mut R = &mut self.input;
        let read = std::io::Read::take(input, limit).read_until(b'\n', &mut self.buf);
        let n = read.map_err(|source| PointsError::Io {
            path: self.path.clone(),
            source,
        })?;
        if n == 0 {
            return Ok(false);
        }
        self.line += 1;
        if self.buf.last() == Some(&b'\n') {
            self.buf.pop();
        }
        if self.buf.last() == Some(&b'\r') {
            self.buf.pop();
        }
        // Cut at the limit, or whole but longer (the limit leaves room for "\r\n").
        if self.buf.len() > MAX_LINE_BYTES {
            return Err(too_long(self.line));
        }
        Ok(true)
    }

    fn parse_line(&mut self) -> Result<Option<PointRecord>, PointsError> {
        let bytes = if self.line == 1 {
            strip_bom(&self.buf)
        } else {
            &self.buf[..]
        };
        match parse_line(bytes, self.line)? {
            Line::Blank => Ok(None),
            Line::Header if !self.seen_data => {
                self.seen_data = true;
                Ok(None)
            }
            Line::Header => Err(header_as_data(bytes, self.line)),
            Line::Point { point, x, y } => {
                self.seen_data = true;
                Ok(Some(PointRecord {
                    point,
                    x_text: text_of(bytes, x),
                    y_text: text_of(bytes, y),
                }))
            }
        }
    }
}

/// What one line of a points file holds.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Line {
    /// Blank, or a `#` comment.
    Blank,
    /// First two fields `x` and `y` (a header, if no data came before).
    Header,
    /// A point, with the byte ranges of its two fields in the line.
    Point {
        point: Point,
        x: std::ops::Range<usize>,
        y: std::ops::Range<usize>,
    },
}

/// The line without a UTF-8 byte-order mark at its start.
fn strip_bom(line: &[u8]) -> &[u8] {
    line.strip_prefix(b"\xef\xbb\xbf").unwrap_or(line)
}

/// A field as text (it was validated as UTF-8 with its line).
fn text_of(line: &[u8], r: std::ops::Range<usize>) -> String {
    String::from_utf8_lossy(&line[r]).into_owned()
}

/// The error for a header line after data: its first field is not a number.
fn header_as_data(line: &[u8], line_no: usize) -> PointsError {
    let text = String::from_utf8_lossy(line);
    let (fields, _) = first_two_fields(text.trim());
    PointsError::Line {
        line: line_no,
        message: format!("{:?} is not a number", shorten(fields[0])),
    }
}

/// Parses one line (without its end) of a points file: the one grammar of the format, used by
/// [`PointReader`] and by [`CsvBlock::parse_into`]. `line_no` names the line in errors.
pub(crate) fn parse_line(bytes: &[u8], line_no: usize) -> Result<Line, PointsError> {
    match parse_plain_line(bytes) {
        Some(line) => Ok(line),
        None => parse_any_line(bytes, line_no),
    }
}

/// Is `b` white space as `char::is_whitespace` has it, for an ASCII byte?
fn is_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | 0x0b | 0x0c | b'\r')
}

/// The common case, on bytes, in one pass: a line whose first two fields are finite numbers
/// (separated by a comma, or by white space when the line has no comma), or a blank or comment
/// line in ASCII. `None` for anything else (then [`parse_any_line`] decides, with the error
/// message): the same grammar, so the two agree wherever this one answers.
fn parse_plain_line(bytes: &[u8]) -> Option<Line> {
    let n = bytes.len();
    let skip_space = |mut i: usize| {
        while i < n && is_space(bytes[i]) {
            i += 1;
        }
        i
    };
    let i = skip_space(0);
    if i == n {
        return Some(Line::Blank);
    }
    if bytes[i] == b'#' {
        return bytes.is_ascii().then_some(Line::Blank);
    }
    let number = |at: usize| {
        fast_float2::parse_partial::<f64, _>(&bytes[at..])
            .ok()
            .filter(|&(v, used)| used > 0 && v.is_finite())
    };
    let (x, used) = number(i)?;
    let x_range = i..i + used;
    let after_x = skip_space(x_range.end);
    // Comma-separated if the first field ends at a comma; white-space separated otherwise.
    let comma = after_x < n && bytes[after_x] == b',';
    let j = if comma {
        skip_space(after_x + 1)
    } else if after_x > x_range.end {
        after_x
    } else {
        return None;
    };
    let (y, used) = number(j)?;
    let y_range = j..j + used;
    let after_y = skip_space(y_range.end);
    let tail = &bytes[after_y..];
    let ends_field = if comma {
        tail.is_empty() || tail[0] == b','
    } else {
        // The second field ends at white space, and no comma anywhere makes the line
        // comma-separated after all.
        (tail.is_empty() || after_y > y_range.end) && memchr::memchr(b',', tail).is_none()
    };
    (ends_field && tail.is_ascii()).then_some(Line::Point {
        point: Point::new(x, y),
        x: x_range,
        y: y_range,
    })
}

/// The general case, on text: any line, with an error naming what is wrong.
fn parse_any_line(bytes: &[u8], line_no: usize) -> Result<Line, PointsError> {
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

impl<R: BufRead> Iterator for PointReader<R> {
    type Item = Result<PointRecord, PointsError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        loop {
            let step = self.next_line().and_then(|more| {
                if more {
                    self.parse_line().map(Some)
                } else {
                    Ok(None)
                }
            });
            match step {
                Ok(Some(Some(record))) => return Some(Ok(record)),
                Ok(Some(None)) => continue,
                Ok(None) => return None,
                Err(e) => {
                    self.failed = true;
                    return Some(Err(e));
                }
            }
        }
    }
}

/// A run of whole lines of a points file, cut by [`CsvBlocks`], ready to be parsed on any
/// thread with [`CsvBlock::parse_into`].
#[derive(Clone, Debug, Default)]
pub struct CsvBlock {
    /// The lines, each with its `\n` (the file's last line may lack it).
    pub text: Vec<u8>,
    /// The 1-based number of the first line.
    pub first_line: usize,
    /// Bytes before this offset hold no data: blank lines, comments and the header.
    data_from: usize,
    /// The number of lines.
    lines: usize,
}

/// The points of a [`CsvBlock`], with where their fields stand in its text.
#[derive(Clone, Debug, Default)]
pub struct ParsedBlock {
    /// The points, in order.
    pub points: Vec<Point>,
    /// Per point, the byte ranges `[x_start, x_end, y_start, y_end]` of its two fields in the
    /// block's text (echo them to reproduce the numbers exactly as written).
    pub fields: Vec<[u32; 4]>,
}

impl CsvBlock {
    /// Parses the block's points into `out` (cleared first).
    ///
    /// # Errors
    /// [`PointsError::Line`] for the first bad line, with its number in the file.
    pub fn parse_into(&self, out: &mut ParsedBlock) -> Result<(), PointsError> {
        out.points.clear();
        out.fields.clear();
        out.points.reserve(self.lines);
        out.fields.reserve(self.lines);
        let mut line_no = self.first_line + count_lines(&self.text[..self.data_from]);
        let text = &self.text[..];
        let mut start = self.data_from;
        while start < text.len() {
            let at = |i: usize| i as u32;
            if let Some(r) = plain_record(text, start) {
                out.points.push(r.point);
                out.fields
                    .push([at(start), at(r.x_end), at(r.x_end + 1), at(r.y_end)]);
                start = r.next;
                line_no += 1;
                continue;
            }
            let end = memchr_newline(&text[start..]).map_or(text.len(), |i| start + i);
            let mut line = &text[start..end];
            if line.last() == Some(&b'\r') {
                line = &line[..line.len() - 1];
            }
            if line.len() > MAX_LINE_BYTES {
                return Err(too_long(line_no));
            }
            match parse_line(line, line_no)? {
                Line::Blank => {}
                Line::Header => return Err(header_as_data(line, line_no)),
                Line::Point { point, x, y } => {
                    out.points.push(point);
                    out.fields.push([
                        at(start + x.start),
                        at(start + x.end),
                        at(start + y.start),
                        at(start + y.end),
                    ]);
                }
            }
            start = end + 1;
            line_no += 1;
        }
        Ok(())
    }

    /// The bytes of a field range of [`ParsedBlock::fields`].
    #[inline]
    pub fn field(&self, start: u32, end: u32) -> &[u8] {
        &self.text[start as usize..end as usize]
    }

    /// Where the data start in the text.
    pub(crate) fn data_from(&self) -> usize {
        self.data_from
    }

    /// Marks the text as read by position (see [`crate::CsvPointsFile`]): the data start at
    /// `data_from`, lines are numbered from 1 at the text's start, and their count is not
    /// known.
    #[cfg(unix)]
    pub(crate) fn set_positional(&mut self, data_from: usize) {
        self.data_from = data_from;
        self.first_line = 1;
        self.lines = 0;
    }
}

/// A record in the form nearly every points file has, `x,y` then `\n`, `\r\n` or the end of
/// the text, with both numbers finite and no white space: read in one pass, without first
/// finding the line's end. Anything else (`None`) goes to [`parse_line`], which reads such a
/// record the same way.
struct PlainRecord {
    point: Point,
    /// Where `x` ends (at the comma; `y` starts after it).
    x_end: usize,
    /// Where `y` ends.
    y_end: usize,
    /// Where the next line starts.
    next: usize,
}

/// The [`PlainRecord`] starting at `text[start]`, if the line is one.
fn plain_record(text: &[u8], start: usize) -> Option<PlainRecord> {
    let number = |from: usize| {
        let (v, used) = fast_float2::parse_partial::<f64, _>(text.get(from..)?).ok()?;
        (used > 0 && v.is_finite()).then_some((v, from + used))
    };
    let (x, x_end) = number(start)?;
    if text.get(x_end) != Some(&b',') {
        return None;
    }
    let (y, y_end) = number(x_end + 1)?;
    let next = match text.get(y_end) {
        None => y_end,
        Some(b'\n') => y_end + 1,
        Some(b'\r') if text.get(y_end + 1) == Some(&b'\n') => y_end + 2,
        Some(_) => return None,
    };
    // The line without its end is `x,y`.
    (y_end - start <= MAX_LINE_BYTES).then_some(PlainRecord {
        point: Point::new(x, y),
        x_end,
        y_end,
        next,
    })
}

/// The error for line `line`, longer than [`MAX_LINE_BYTES`] without its end.
fn too_long(line: usize) -> PointsError {
    PointsError::Line {
        line,
        message: format!("line longer than {MAX_LINE_BYTES} bytes"),
    }
}

/// The position of the first `\n`.
fn memchr_newline(bytes: &[u8]) -> Option<usize> {
    memchr::memchr(b'\n', bytes)
}

/// The number of `\n` in `bytes`.
fn count_lines(bytes: &[u8]) -> usize {
    memchr::memchr_iter(b'\n', bytes).count()
}

/// A points file cut into [`CsvBlock`]s of whole lines (about `block_bytes` each), for
/// parsing in parallel: the format of [`PointReader`], the byte-order mark and the header
/// handled here, memory bounded by the block size whatever the file's length.
///
/// # Examples
///
/// ```
/// let text = "x,y\n1,2\n# note\n3 4\n5,6";
/// let mut blocks = inrs::CsvBlocks::new(text.as_bytes(), "input", 4);
/// let mut parsed = inrs::ParsedBlock::default();
/// let mut xs = Vec::new();
/// while let Some(b) = blocks.next_block().unwrap() {
///     b.parse_into(&mut parsed).unwrap();
///     for (p, f) in parsed.points.iter().zip(&parsed.fields) {
///         xs.push((p.x, String::from_utf8_lossy(b.field(f[0], f[1])).into_owned()));
///     }
/// }
/// assert_eq!(xs, [(1.0, "1".into()), (3.0, "3".into()), (5.0, "5".into())]);
/// ```
#[derive(Debug)]
pub struct CsvBlocks<R> {
    input: R,
    path: String,
    block_bytes: usize,
    /// Bytes read but not yet handed out (a partial last line).
    pending: Vec<u8>,
    /// A buffer given back by [`CsvBlocks::recycle`], for the bytes after the next block.
    spare: Vec<u8>,
    /// Lines handed out so far.
    lines: usize,
    at_start: bool,
    /// Bytes dropped before the first block's text: the byte-order mark's 3, or none.
    dropped_at_start: usize,
    seen_data: bool,
    eof: bool,
    /// Bytes read from the input so far.
    consumed: u64,
}

impl<R: std::io::Read> CsvBlocks<R> {
    /// Blocks of about `block_bytes` (at least one line) from `input`, naming it `path` in I/O
    /// errors.
    pub fn new(input: R, path: impl Into<String>, block_bytes: usize) -> Self {
        Self {
            input,
            path: path.into(),
            block_bytes: block_bytes.max(1),
            pending: Vec::new(),
            spare: Vec::new(),
            lines: 0,
            at_start: true,
            dropped_at_start: 0,
            seen_data: false,
            eof: false,
            consumed: 0,
        }
    }

    /// Bytes read from the input so far (for progress reports).
    pub fn bytes_read(&self) -> u64 {
        self.consumed
    }

    /// Whether a data line (or the header) has been found in the blocks handed out so far.
    #[cfg(unix)]
    pub(crate) fn seen_data(&self) -> bool {
        self.seen_data
    }

    /// Bytes of the input before the first block's text (the byte-order mark, if any).
    #[cfg(unix)]
    pub(crate) fn dropped_at_start(&self) -> usize {
        self.dropped_at_start
    }

    /// Gives back a block's text (or any buffer) for reading the following blocks into, so
    /// that a long run reuses a few buffers instead of allocating (and page-faulting) a fresh
    /// one per block. Its contents are discarded; one buffer is kept, the larger.
    pub fn recycle(&mut self, buffer: Vec<u8>) {
        if buffer.capacity() > self.spare.capacity() {
            self.spare = buffer;
        }
    }

    /// The next block, `None` at the end.
    ///
    /// # Errors
    /// [`PointsError::Io`]; [`PointsError::Line`] for a line longer than [`MAX_LINE_BYTES`].
    pub fn next_block(&mut self) -> Result<Option<CsvBlock>, PointsError> {
        self.fill()?;
        if self.at_start {
            self.at_start = false;
            if self.pending.starts_with(b"\xef\xbb\xbf") {
                self.pending.drain(..3);
                self.dropped_at_start = 3;
            }
        }
        if self.pending.is_empty() {
            return Ok(None);
        }
        // Whole lines only, unless the input has ended.
        let cut = if self.eof {
            self.pending.len()
        } else {
            match memchr::memrchr(b'\n', &self.pending) {
                Some(i) => i + 1,
                None => return Err(too_long(self.lines + 1)),
            }
        };
        // The bytes after the cut move to the spare buffer, which becomes `pending`.
        let mut rest = std::mem::take(&mut self.spare);
        rest.clear();
        rest.extend_from_slice(&self.pending[cut..]);
        self.pending.truncate(cut);
        let text = std::mem::replace(&mut self.pending, rest);
        let first_line = self.lines + 1;
        let lines = count_lines(&text) + usize::from(self.eof && !text.ends_with(b"\n"));
        self.lines += lines;
        let data_from = if self.seen_data {
            0
        } else {
            self.skip_to_data(&text, first_line)
        };
        Ok(Some(CsvBlock {
            text,
            first_line,
            data_from,
            lines,
        }))
    }

    /// Reads until `pending` holds a block's worth of bytes and a line end after it, or the
    /// input ends, straight into `pending` (no intermediate copy).
    fn fill(&mut self) -> Result<(), PointsError> {
        // Where to look for a line end: only the bytes read since the last look.
        let mut searched = 0;
        while !self.eof {
            let last_newline =
                memchr::memrchr(b'\n', &self.pending[searched..]).map(|i| searched + i);
            searched = self.pending.len();
            let tail = last_newline.map_or(self.pending.len(), |i| self.pending.len() - i - 1);
            if self.pending.len() >= self.block_bytes && last_newline.is_some() {
                break;
            }
            if tail > MAX_LINE_BYTES + 1 {
                break; // a line too long even without a '\r' at its end: next_block says so
            }
            let want = (self.block_bytes.saturating_sub(self.pending.len())).max(1 << 16);
            // Room for a whole block and one more read at once: every block then fits a
            // buffer of that size (see `recycle`) without growing it.
            self.pending.reserve(
                (self.block_bytes + (2 << 16)).max(self.pending.len() + want) - self.pending.len(),
            );
            let before = self.pending.len();
            let read = std::io::Read::read_to_end(
                &mut std::io::Read::take(&mut self.input, want as u64),
                &mut self.pending,
            )
            .map_err(|source| PointsError::Io {
                path: self.path.clone(),
                source,
            })?;
            debug_assert_eq!(read, self.pending.len() - before);
            if read == 0 {
                self.eof = true;
            }
            self.consumed += read as u64;
        }
        Ok(())
    }

    /// Where data starts in the first block(s): blank lines and comments skipped, and a first
    /// line `x,y` taken as a header. Errors are left for [`CsvBlock::parse_into`].
    fn skip_to_data(&mut self, text: &[u8], first_line: usize) -> usize {
        let mut start = 0;
        let mut line_no = first_line;
        while start < text.len() {
            let end = memchr_newline(&text[start..]).map_or(text.len(), |i| start + i);
            let mut line = &text[start..end];
            if line.last() == Some(&b'\r') {
                line = &line[..line.len() - 1];
            }
            match parse_line(line, line_no) {
                Ok(Line::Blank) => {}
                Ok(Line::Header) => {
                    self.seen_data = true;
                    return (end + 1).min(text.len());
                }
                _ => {
                    self.seen_data = true;
                    return start;
                }
            }
            start = end + 1;
            line_no += 1;
        }
        text.len()
    }
}

/// Opens a points file for block-wise parsing (see [`CsvBlocks`]).
///
/// # Errors
/// [`PointsError::Io`] if it cannot be opened.
pub fn open_points_blocks(
    path: impl AsRef<Path>,
    block_bytes: usize,
) -> Result<CsvBlocks<std::fs::File>, PointsError> {
    let path = path.as_ref();
    let file = open_file(path)?;
    Ok(CsvBlocks::new(
        file,
        path.display().to_string(),
        block_bytes,
    ))
}

/// Parses a whole points text (see [`PointReader`] for the format).
///
/// # Errors
/// [`PointsError::Line`] with the line number of the first bad line.
///
/// # Examples
///
/// ```
/// let pts = inrs::parse_points("x,y\n# a comment\n0.5, 1\n2 3e-1\n").unwrap();
/// assert_eq!(pts.len(), 2);
/// assert_eq!(pts[1].point, inrs::Point::new(2.0, 0.3));
/// assert_eq!(pts[1].y_text, "3e-1");
/// assert!(inrs::parse_points("1,2\n3;4\n").unwrap_err().to_string().starts_with("line 2:"));
/// ```
pub fn parse_points(text: &str) -> Result<Vec<PointRecord>, PointsError> {
    PointReader::new(text.as_bytes()).collect()
}

/// Opens the points file `path` ([`PointsError::Io`] naming it if it cannot be opened).
pub(crate) fn open_file(path: &Path) -> Result<std::fs::File, PointsError> {
    std::fs::File::open(path).map_err(|source| PointsError::Io {
        path: path.display().to_string(),
        source,
    })
}

/// Opens a points file for streaming.
///
/// # Errors
/// [`PointsError::Io`] if it cannot be opened.
pub fn open_points(
    path: impl AsRef<Path>,
) -> Result<PointReader<std::io::BufReader<std::fs::File>>, PointsError> {
    let path = path.as_ref();
    let file = open_file(path)?;
    Ok(PointReader::named(
        std::io::BufReader::with_capacity(1 << 16, file),
        path.display().to_string(),
    ))
}

/// Reads and parses a whole points file into memory (use [`open_points`] to stream).
///
/// # Errors
/// [`PointsError::Io`] or as [`parse_points`].
pub fn read_points(path: impl AsRef<Path>) -> Result<Vec<PointRecord>, PointsError> {
    open_points(path)?.collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_the_tool_writes_read_back() {
        let sample = "x,y,kind\n0.5,0.25,boundary\n1,2,interior\n";
        let pts = parse_points(sample).unwrap();
        assert_eq!(pts.len(), 2);
        let classified = "x,y,location\r\n0.5,0.25,inside\r\n";
        assert_eq!(parse_points(classified).unwrap()[0].x_text, "0.5");
    }

    #[test]
    fn a_byte_order_mark_is_skipped_only_at_the_start() {
        assert_eq!(parse_points("\u{feff}1,2\n").unwrap().len(), 1);
        assert_eq!(parse_points("\u{feff}x,y\n1,2\n").unwrap().len(), 1);
        assert!(parse_points("1,2\n\u{feff}3,4\n").is_err());
    }

    #[test]
    fn bad_lines_are_errors_with_their_number() {
        for (text, line) in [
            ("1,2\n3\n", 2),
            ("1,nan\n", 1),
            ("1,2\n\n# c\n1e999,0\n", 4),
            ("\u{0}\u{ff}", 1),
        ] {
            let e = parse_points(text).unwrap_err().to_string();
            assert!(e.starts_with(&format!("line {line}:")), "{text:?}: {e}");
        }
        let invalid_utf8: &[u8] = b"1,2\n\xff\xfe,3\n";
        let e = PointReader::new(invalid_utf8)
            .collect::<Result<Vec<_>, _>>()
            .unwrap_err();
        assert!(e.to_string().contains("line 2: not UTF-8"), "{e}");
    }

    #[test]
    fn a_file_without_line_breaks_is_bounded() {
        let long = "1".repeat(MAX_LINE_BYTES * 3);
        let e = parse_points(&long).unwrap_err().to_string();
        assert!(e.contains("longer than"), "{e}");
    }

    /// Every record of `text` read through [`CsvBlocks`] of `block_bytes`, or the first error;
    /// with `recycle`, each block's text is given back (with stale bytes in it) for reading
    /// the next ones.
    fn read_in_blocks(
        text: &[u8],
        block_bytes: usize,
        recycle: bool,
    ) -> Result<Vec<PointRecord>, PointsError> {
        let mut blocks = CsvBlocks::new(text, "t", block_bytes);
        let mut parsed = ParsedBlock::default();
        let mut got = Vec::new();
        while let Some(b) = blocks.next_block()? {
            b.parse_into(&mut parsed)?;
            for (p, f) in parsed.points.iter().zip(&parsed.fields) {
                got.push(PointRecord {
                    point: *p,
                    x_text: String::from_utf8_lossy(b.field(f[0], f[1])).into(),
                    y_text: String::from_utf8_lossy(b.field(f[2], f[3])).into(),
                });
            }
            if recycle {
                let mut stale = b.text;
                stale.extend_from_slice(b"9,9\nbad\n");
                blocks.recycle(stale);
            }
        }
        Ok(got)
    }

    /// A xorshift generator of indices below `k`, for random lines from `seed`.
    fn xorshift(mut state: u64) -> impl FnMut(usize) -> usize {
        move |k| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state % k as u64) as usize
        }
    }

    /// The block reader gives what the line reader gives, whatever the block size, and the
    /// same first error; also when each block's text is given back (with stale bytes in it)
    /// for reading the next ones.
    #[test]
    fn blocks_agree_with_the_line_reader() {
        let texts: [&[u8]; 9] = [
            b"\xef\xbb\xbfx,y,kind\n# c\n\n0.5, 1, b\r\n2 3e-1\n-0,+5\n1e-300\t7",
            b"\n\n# only comments\n",
            b"1,2\nx,y\n",
            b"# c\nX , Y\n1,2\n3,4\n",
            b"1,2\n3,4\nbad\n5,6\n",
            b"1,2\n\xff\n",
            b"1,2\r\n-3,4e1\r\n5,6\r",
            b"1,2\r\n3,4,5\n6, 7\n8,9",
            b"",
        ];
        for text in texts {
            let lines: Result<Vec<PointRecord>, _> = PointReader::new(text).collect();
            for (block_bytes, recycle) in [1, 3, 7, 64, 1 << 20]
                .into_iter()
                .flat_map(|b| [(b, false), (b, true)])
            {
                let result = read_in_blocks(text, block_bytes, recycle);
                match (&lines, &result) {
                    (Ok(a), Ok(b)) => assert_eq!(a, b, "{text:?} in blocks of {block_bytes}"),
                    (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string(), "{text:?}"),
                    _ => panic!("{text:?} in blocks of {block_bytes}: {lines:?} vs {result:?}"),
                }
            }
        }
    }

    /// Lines about [`MAX_LINE_BYTES`] long (one long number), ended by `\n`, `\r\n` or the
    /// end: the block reader accepts and refuses the same ones as the line reader.
    #[test]
    fn lines_near_the_length_limit_are_measured_alike() {
        // Short lines before the long one: a few, or 65 535 bytes of them, so that the block
        // cutter's second read of 64 KiB ends between a long line's '\r' and its '\n'.
        let aligned = format!("x,y\n{}2,3333\n", "2,3\n".repeat(16381));
        assert_eq!(aligned.len(), 65535);
        for prefix in ["x,y\n2,3\n", &aligned] {
            for len in [MAX_LINE_BYTES - 1, MAX_LINE_BYTES, MAX_LINE_BYTES + 1] {
                for ending in ["\n", "\r\n", ""] {
                    // "1,0.000...01", len bytes long without its end.
                    let line = format!("1,0.{}1", "0".repeat(len - 5));
                    let text = format!("{prefix}{line}{ending}");
                    let lines: Result<Vec<Point>, String> = PointReader::new(text.as_bytes())
                        .map(|r| r.map(|r| r.point).map_err(|e| e.to_string()))
                        .collect();
                    for block_bytes in [1024, 1 << 20] {
                        let blocks_result: Result<Vec<Point>, String> =
                            read_in_blocks(text.as_bytes(), block_bytes, false)
                                .map(|v| v.iter().map(|r| r.point).collect())
                                .map_err(|e| e.to_string());
                        // (Summaries in the message: the points number 16 000.)
                        let summary = |r: &Result<Vec<Point>, String>| match r {
                            Ok(v) => format!("{} points, the last {:?}", v.len(), v.last()),
                            Err(e) => e.clone(),
                        };
                        assert!(
                            lines == blocks_result,
                            "{len} bytes, {ending:?}, blocks of {block_bytes}: {} vs {}",
                            summary(&lines),
                            summary(&blocks_result)
                        );
                    }
                    let accepted = lines.is_ok();
                    assert_eq!(accepted, len <= MAX_LINE_BYTES, "{len} bytes, {ending:?}");
                }
            }
        }
    }

    #[test]
    fn blocks_bound_a_file_without_line_breaks() {
        let long = "1".repeat(MAX_LINE_BYTES * 3);
        let mut blocks = CsvBlocks::new(long.as_bytes(), "t", 1024);
        let e = blocks.next_block().unwrap_err().to_string();
        assert!(e.contains("longer than"), "{e}");
    }

    /// The byte-level fast path answers as the general parser does wherever it answers.
    #[test]
    fn the_plain_path_agrees_with_the_general_one() {
        let tokens = [
            "1", "-2.5", "3e-7", "+.5", "x", "Y", "#", ",", ",", " ", "  ", "\t", "\u{b}", "\u{c}",
            "nan", "inf", "1e999", "abc", "", "0", "1_0", "\u{a0}", "é", ".",
        ];
        let mut next = xorshift(0x9E37_79B9_7F4A_7C15);
        let mut points = 0;
        for i in 0..40000 {
            let n = next(7);
            let mut line: String = (0..n).map(|_| tokens[next(tokens.len())]).collect();
            if i % 2 == 0 {
                // Mostly well-formed: number, separator, number, then anything.
                let sep = [",", " ", "\t", " , ", ",\u{b}"][next(5)];
                line = format!("{}{sep}{}{line}", next(1000) as f64 * 0.37, tokens[next(4)]);
            }
            if let Some(fast) = parse_plain_line(line.as_bytes()) {
                let general = parse_any_line(line.as_bytes(), 1).unwrap();
                points += usize::from(matches!(fast, Line::Point { .. }));
                assert_eq!(fast, general, "{line:?}");
            }
        }
        assert!(points > 5000, "{points}");
    }

    /// The one-pass record reader answers as the line parser does wherever it answers, and
    /// finds where the next line starts.
    #[test]
    fn plain_records_agree_with_the_line_parser() {
        let tokens = [
            "1", "-2.5", "3e-7", "+.5", "x", ",", " ", "\t", "nan", "inf", "1e999", "", "0", ".",
            "\r", "é", "1e", "-",
        ];
        let endings = ["\n", "\r\n", "", "\r", "\r\r\n", "\n1,2\n"];
        let mut next = xorshift(0x2545_F491_4F6C_DD1D);
        let (mut records, mut lines) = (0, 0);
        for i in 0..40000 {
            let n = next(4);
            let mut line: String = (0..n).map(|_| tokens[next(tokens.len())]).collect();
            if i % 4 != 0 {
                let sep = [",", ",", ", ", " "][next(4)];
                let x = (next(2000) as f64 - 1000.0) * 0.37;
                line = format!("{x}{sep}{}{line}", tokens[next(4)]);
            }
            let text = format!("9,9\n{line}{}", endings[next(endings.len())]);
            let text = text.as_bytes();
            let Some(r) = plain_record(text, 4) else {
                continue;
            };
            records += 1;
            let end = memchr_newline(&text[4..]).map_or(text.len(), |k| 4 + k);
            let mut whole = &text[4..end];
            if whole.last() == Some(&b'\r') {
                whole = &whole[..whole.len() - 1];
            }
            assert_eq!(r.next, (end + 1).min(text.len()), "{line:?}");
            match parse_line(whole, 1) {
                Ok(Line::Point { point, x, y }) => {
                    lines += 1;
                    assert_eq!(point, r.point, "{line:?}");
                    assert_eq!(
                        (x, y),
                        (0..r.x_end - 4, r.x_end - 3..r.y_end - 4),
                        "{line:?}"
                    );
                }
                other => panic!("{line:?}: {other:?} but a plain record"),
            }
        }
        assert!(records > 2000, "{records}");
        assert_eq!(records, lines);
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

    #[test]
    fn reading_stops_after_the_first_error() {
        let mut r = PointReader::new("1,2\nbad\n3,4\n".as_bytes());
        assert!(r.next().unwrap().is_ok());
        assert!(r.next().unwrap().is_err());
        assert!(r.next().is_none());
    }
}
