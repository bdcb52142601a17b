//! The CSV points file: [`CsvReader`], which cuts it into runs of whole lines (by byte
//! position from a regular file, or in order from any input) and parses each run on the
//! thread that takes it.

use std::io::Read;
use std::path::Path;

use super::grammar::{Kind, find_data, header_as_data, line_at, read_text, scan, too_long};
use super::run::Claims;
use super::run::{Content, InOrder, PointRun, PointsReader, ReadProgress, RunSizes, Source};
use super::{MAX_LINE_BYTES, PointsError, open_file};

/// The CSV points file: one point per line, `x,y` separated by a comma or white space;
/// further columns are allowed and ignored (so the `x,y,kind` files of `inrs sample` and the
/// `x,y,location` files of `inrs classify` read back); an optional header line whose first two
/// fields are `x` and `y`; blank lines and `#` comment lines ignored; a UTF-8 byte-order mark
/// at the start (Excel's "CSV UTF-8") skipped; Windows line ends accepted. Numbers are parsed
/// exactly as written (shortest round-trip `f64`); NaN and infinities are rejected.
///
/// The [`PointsReader`] of CSV: runs of whole lines, each parsed on the thread that takes it,
/// the fields' text kept to echo the numbers as written. Memory is the runs in hand (a line at
/// most [`MAX_LINE_BYTES`]), whatever the file's length. [`CsvReader::open`] reads a regular
/// file by position (Unix); [`CsvReader::new`] reads any input in order.
///
/// # Examples
///
/// ```
/// use rs_io::points::{CsvReader, PointRun, PointsReader, RunPoints, RunSizes};
/// let text = "\u{feff}x,y,kind\n# a comment\n0.5, 1, boundary\n2 3e-1\n1;2\n";
/// let reader = CsvReader::new(text.as_bytes(), "input", RunSizes::default());
/// let mut run = PointRun::default();
/// let (k, read) = reader.next_run(&mut run).unwrap();
/// assert_eq!(k, 0);
/// assert_eq!(
///     read.unwrap_err().to_string(),
///     "line 5: expected at least two numbers \"x,y\", got \"1;2\""
/// );
/// let pts = rs_io::points::parse_points(&text[..text.len() - 4]).unwrap();
/// assert_eq!(pts[1].point, rs_spline::Point::new(2.0, 0.3));
/// assert_eq!(pts[1].y_text, "3e-1");
/// ```
#[derive(Debug)]
pub struct CsvReader<R> {
    source: Source<Blocks<R>, CsvFile>,
}

impl<R: Read> CsvReader<R> {
    /// Reads `input` in order, in runs of whole lines of about `sizes.csv_bytes` (at least
    /// one line), naming it `name` in I/O errors.
    pub fn new(input: R, name: impl Into<String>, sizes: RunSizes) -> Self {
        let blocks = Blocks::new(input, name, sizes.csv_bytes);
        Self {
            source: Source::InOrder(InOrder::new(blocks)),
        }
    }
}

impl CsvReader<std::fs::File> {
    /// Opens `path`: read by position if it is a regular file whose first run holds data
    /// (Unix), in order otherwise (a named pipe cannot be read by position, and a file that
    /// opens with a run's worth of comments has its data found by reading on).
    ///
    /// # Errors
    /// [`PointsError::Io`] if it cannot be opened; [`PointsError::Line`] for a first line too
    /// long.
    pub fn open(path: impl AsRef<Path>, sizes: RunSizes) -> Result<Self, PointsError> {
        let path = path.as_ref();
        // Only a regular file is opened twice (a pipe's data would go with the first opening).
        #[cfg(unix)]
        if std::fs::metadata(path).is_ok_and(|m| m.is_file())
            && let Some(file) = CsvFile::open(path, sizes.csv_bytes)?
        {
            return Ok(Self {
                source: Source::ByPosition(Claims::new(file.blocks()), file),
            });
        }
        let name = path.display().to_string();
        Ok(Self::new(open_file(path)?, name, sizes))
    }
}

impl<R: Read + Send> PointsReader for CsvReader<R> {
    fn next_run(&self, run: &mut PointRun) -> Option<(usize, Result<(), PointsError>)> {
        let (k, read) = match &self.source {
            Source::InOrder(blocks) => {
                // Read under the lock, parsed outside it.
                let (k, read) =
                    blocks.next(|b| b.next_block(&mut run.bytes), Blocks::bytes_read)?;
                run.start(k, Content::Csv);
                (k, read.and_then(|lines| parse_lines(&lines, run)))
            }
            #[cfg(not(unix))]
            Source::ByPosition(_, never) => match *never {},
            #[cfg(unix)]
            Source::ByPosition(claims, file) => {
                let k = claims.claim(|k| file.offset_of_block(k + 1))?;
                run.start(k, Content::Csv);
                let read = file
                    .read_block(k, &mut run.bytes)
                    .and_then(|lines| file.parse_block(k, &lines, run));
                (k, read)
            }
        };
        Some((k, read.map_err(|e| run.fail(e))))
    }

    fn points(&self) -> Option<usize> {
        None
    }

    fn progress(&self) -> ReadProgress {
        self.source.progress()
    }
}

/// Where a run of whole lines stands in its file.
#[derive(Clone, Copy, Debug, Default)]
struct Lines {
    /// The 1-based number of the first line.
    first_line: usize,
    /// Bytes before this offset hold no data: the byte-order mark, blank lines, comments and
    /// the header.
    data_from: usize,
    /// The number of lines (0 if not known).
    lines: usize,
}

/// Parses the lines `text` (placed in the file by `at`) into `run`'s points and fields
/// (cleared first).
///
/// # Errors
/// [`PointsError::Line`] for the first bad line, with its number in the file; the run then
/// holds the points of the lines before it.
fn parse_lines(at: &Lines, run: &mut PointRun) -> Result<(), PointsError> {
    let PointRun {
        bytes: text,
        points,
        fields,
        ..
    } = run;
    points.clear();
    fields.clear();
    points.reserve(at.lines);
    fields.reserve(at.lines);
    let text = &text[..];
    let mut line_no = at.first_line + count_lines(&text[..at.data_from]);
    let mut start = at.data_from;
    let field = |i: usize| i as u32;
    while start < text.len() {
        // `read_line` in its two halves, the points the scan reads pushed at once: its
        // result then stays in registers (a tenth of the instructions of a CSV run).
        let (line, next) = match scan(text, start) {
            Some((line, next)) if line.kind == Kind::Point => {
                points.push(line.point);
                fields.push(line.fields.map(field));
                (start, line_no) = (next, line_no + 1);
                continue;
            }
            Some(blank) => blank,
            None => read_text(text, start, line_no)?,
        };
        match line.kind {
            Kind::Blank => {}
            Kind::Header => {
                let (end, _) = line_at(text, start);
                return Err(header_as_data(&text[start..end], line_no));
            }
            Kind::Point => {
                points.push(line.point);
                fields.push(line.fields.map(field));
            }
        }
        start = next;
        line_no += 1;
    }
    Ok(())
}

/// The number of `\n` in `bytes`.
fn count_lines(bytes: &[u8]) -> usize {
    memchr::memchr_iter(b'\n', bytes).count()
}

/// The most bytes a CSV run may span (whatever the sizes asked for): the fields' offsets in a
/// run are 32-bit.
const MAX_RUN_BYTES: usize = 1 << 30;

/// A points file cut into runs of whole lines (about `block_bytes` each), read in order: the
/// byte-order mark, comments and the header before the data found here, memory bounded by the
/// block size whatever the file's length.
#[derive(Debug)]
struct Blocks<R> {
    input: R,
    path: String,
    block_bytes: usize,
    /// Bytes read but not yet handed out (the lines after the last block, and a partial
    /// line).
    pending: Vec<u8>,
    /// Lines handed out so far.
    lines: usize,
    /// Whether a data line (or the header) has been found in the blocks handed out so far.
    seen_data: bool,
    eof: bool,
    /// Bytes read from the input so far.
    consumed: u64,
}

impl<R: Read> Blocks<R> {
    /// Blocks of about `block_bytes` (at least one line) from `input`, naming it `path` in I/O
    /// errors.
    fn new(input: R, path: impl Into<String>, block_bytes: usize) -> Self {
        Self {
            input,
            path: path.into(),
            block_bytes: block_bytes.clamp(1, MAX_RUN_BYTES),
            pending: Vec::new(),
            lines: 0,
            seen_data: false,
            eof: false,
            consumed: 0,
        }
    }

    /// Bytes read from the input so far (for progress reports).
    fn bytes_read(&self) -> u64 {
        self.consumed
    }

    /// Puts the next block into `text` and says where it stands; `None` at the end. The
    /// buffer `text` held (its contents discarded) takes the bytes read past the block, so
    /// that a long run reuses a few buffers instead of allocating (and page-faulting) a fresh
    /// one per block.
    ///
    /// # Errors
    /// [`PointsError::Io`]; [`PointsError::Line`] for a line longer than [`MAX_LINE_BYTES`].
    fn next_block(&mut self, text: &mut Vec<u8>) -> Result<Option<Lines>, PointsError> {
        self.fill()?;
        if self.pending.is_empty() {
            return Ok(None);
        }
        // Whole lines only, unless the input has ended: up to the first line end at or past
        // the block's size (the lines after it wait for the next block), else the last one.
        let past = self.block_bytes.min(self.pending.len()) - 1;
        let cut = match memchr::memchr(b'\n', &self.pending[past..]) {
            Some(i) => past + i + 1,
            None if self.eof => self.pending.len(),
            None => match memchr::memrchr(b'\n', &self.pending[..past]) {
                Some(i) => i + 1,
                None => return Err(too_long(self.lines + 1)),
            },
        };
        // The bytes after the cut move to the buffer given, which becomes `pending`.
        let mut rest = std::mem::take(text);
        rest.clear();
        rest.extend_from_slice(&self.pending[cut..]);
        self.pending.truncate(cut);
        *text = std::mem::replace(&mut self.pending, rest);
        let first_line = self.lines + 1;
        // Only the input's last block can end without a line end.
        let lines = count_lines(text) + usize::from(self.eof && !text.ends_with(b"\n"));
        self.lines += lines;
        let data_from = if self.seen_data {
            0
        } else if let Some(at) = find_data(text, first_line == 1) {
            self.seen_data = true;
            at
        } else {
            text.len()
        };
        Ok(Some(Lines {
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
            // buffer of that size without growing it.
            self.pending.reserve(
                (self.block_bytes + (2 << 16)).max(self.pending.len() + want) - self.pending.len(),
            );
            let before = self.pending.len();
            let read = (&mut self.input)
                .take(want as u64)
                .read_to_end(&mut self.pending)
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
}

/// Reading by position exists on Unix only.
#[cfg(not(unix))]
type CsvFile = std::convert::Infallible;

/// A regular CSV points file cut into blocks by byte position, for threads that each read and
/// parse whole blocks (no thread reads ahead for them, and the bytes a thread reads are still
/// in its cache when it parses them). Block `k` holds the lines that *start* in its byte
/// range: its first bytes, up to a line end, belong to the line before, and its last line runs
/// on to its end. The format is that of [`CsvReader`]; the byte-order mark, comments before
/// the data and the header are found once, when the file is opened, and the blocks cover the
/// file's length at that time (lines appended later are not read). Unix only.
#[cfg(unix)]
#[derive(Debug)]
struct CsvFile {
    file: std::fs::File,
    path: String,
    len: u64,
    block_bytes: u64,
    /// Where the data start: after the byte-order mark, the comments and the header.
    data_from: u64,
}

/// Bytes read at a time while looking for the end of a block's last line.
#[cfg(unix)]
const LINE_END_READ: usize = 4096;

#[cfg(unix)]
impl CsvFile {
    /// Opens `path` and finds where its data start, reading its first block of about
    /// `block_bytes` as [`Blocks`] does. `None` if it is not a regular file, or if no data
    /// line starts in that block (a file that opens with that many bytes of comments): read it
    /// in order with [`Blocks`] then.
    ///
    /// # Errors
    /// [`PointsError::Io`]; [`PointsError::Line`] for a first line too long.
    fn open(path: impl AsRef<Path>, block_bytes: usize) -> Result<Option<Self>, PointsError> {
        let path = path.as_ref();
        let name = path.display().to_string();
        let file = super::open_file(path)?;
        let meta = file.metadata().map_err(|source| PointsError::Io {
            path: name.clone(),
            source,
        })?;
        if !meta.is_file() {
            return Ok(None);
        }
        let mut blocks = Blocks::new(&file, name.clone(), block_bytes);
        let Some(first) = blocks.next_block(&mut Vec::new())? else {
            return Ok(None);
        };
        if !blocks.seen_data {
            return Ok(None);
        }
        let block_bytes = blocks.block_bytes as u64;
        drop(blocks);
        Ok(Some(Self {
            file,
            path: name,
            len: meta.len(),
            block_bytes,
            data_from: first.data_from as u64,
        }))
    }

    /// The number of blocks.
    fn blocks(&self) -> usize {
        (self.len.saturating_sub(self.data_from)).div_ceil(self.block_bytes) as usize
    }

    /// Where block `k`'s byte range starts (the file's length past the last block).
    fn offset_of_block(&self, k: usize) -> u64 {
        (self.data_from)
            .saturating_add((k as u64).saturating_mul(self.block_bytes))
            .min(self.len)
    }

    /// Reads block `k` into `text`, reusing its buffer: from one byte before its range (to
    /// see whether a line starts at the range) to the end of its last line, at most
    /// [`MAX_LINE_BYTES`] past the range (a longer line is then reported by
    /// [`CsvFile::parse_block`]).
    ///
    /// # Errors
    /// [`PointsError::Io`].
    fn read_block(&self, k: usize, text: &mut Vec<u8>) -> Result<Lines, PointsError> {
        let (start, end) = (self.offset_of_block(k), self.offset_of_block(k + 1));
        let from = if k == 0 { start } else { start - 1 };
        let got = self.read_into(from, (end - from) as usize, text, 0)?;
        text.truncate(got);
        // The bytes up to the first line end belong to the line before (unless a line ends
        // just before the range).
        let skip = if k == 0 {
            0
        } else {
            memchr::memchr(b'\n', text).map_or(text.len(), |i| i + 1)
        };
        if skip < text.len() && text.last() != Some(&b'\n') {
            // The last line runs on past the range: read up to its end.
            let last_start = memchr::memrchr(b'\n', &text[skip..]).map_or(skip, |i| skip + i + 1);
            loop {
                let at = text.len();
                let got = self.read_into(from + at as u64, LINE_END_READ, text, at)?;
                text.truncate(at + got);
                if let Some(i) = memchr::memchr(b'\n', &text[at..]) {
                    text.truncate(at + i + 1);
                    break;
                }
                if got == 0 || text.len() - last_start > MAX_LINE_BYTES + 2 {
                    break; // the end of the file, or a line too long (parse_block says so)
                }
            }
        }
        // Lines are numbered from 1 at the text's start; their count is not known.
        Ok(Lines {
            first_line: 1,
            data_from: skip,
            lines: 0,
        })
    }

    /// Parses block `k`, read into `run` by [`CsvFile::read_block`] (which said where it
    /// stands: `lines`); errors name the line's number in the file.
    ///
    /// # Errors
    /// [`PointsError::Line`] for the block's first bad line; [`PointsError::Io`] if the
    /// lines before it cannot be counted.
    fn parse_block(&self, k: usize, lines: &Lines, run: &mut PointRun) -> Result<(), PointsError> {
        parse_lines(lines, run).map_err(|e| match e {
            PointsError::Line { line, message } => {
                // Numbered from 1 at the block's text, which starts one byte before its range.
                let text_start = self.offset_of_block(k).saturating_sub(u64::from(k > 0));
                match self.line_ends_before(text_start) {
                    Ok(before) => PointsError::Line {
                        line: line + before,
                        message,
                    },
                    Err(io) => io,
                }
            }
            other => other,
        })
    }

    /// The number of `\n` in the file's first `offset` bytes (for an error's line number).
    fn line_ends_before(&self, offset: u64) -> Result<usize, PointsError> {
        let mut buf = Vec::new();
        let (mut at, mut count) = (0, 0);
        while at < offset {
            let want = (offset - at).min(1 << 20) as usize;
            let got = self.read_into(at, want, &mut buf, 0)?;
            if got == 0 {
                break;
            }
            count += count_lines(&buf[..got]);
            at += got as u64;
        }
        Ok(count)
    }

    /// Reads up to `n` bytes at `offset` into `buf[at..]` (grown as needed, never shrunk:
    /// bytes past the read are left as they were); returns how many were read (fewer only at
    /// the end of the file).
    fn read_into(
        &self,
        offset: u64,
        n: usize,
        buf: &mut Vec<u8>,
        at: usize,
    ) -> Result<usize, PointsError> {
        use std::os::unix::fs::FileExt;
        if buf.len() < at + n {
            buf.resize(at + n, 0);
        }
        let mut got = 0;
        while got < n {
            match self
                .file
                .read_at(&mut buf[at + got..at + n], offset + got as u64)
            {
                Ok(0) => break,
                Ok(m) => got += m,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(source) => {
                    return Err(PointsError::Io {
                        path: self.path.clone(),
                        source,
                    });
                }
            }
        }
        Ok(got)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::grammar::read_line;
    use crate::points::{PointRecord, RunPoints, parse_points, records};
    use rs_spline::Point;

    /// Every record of `text` read in order in runs of about `block_bytes`, or the first
    /// error; with `stale`, the run's buffer holds stale bytes before each read.
    fn read_in_blocks(
        text: &[u8],
        block_bytes: usize,
        stale: bool,
    ) -> Result<Vec<PointRecord>, PointsError> {
        let sizes = RunSizes {
            csv_bytes: block_bytes,
            ..RunSizes::default()
        };
        if !stale {
            return records(&CsvReader::new(text, "t", sizes));
        }
        let reader = CsvReader::new(text, "t", sizes);
        let (mut run, mut got) = (PointRun::default(), Vec::new());
        loop {
            run.bytes.extend_from_slice(b"9,9\nbad\n");
            let Some((_, read)) = reader.next_run(&mut run) else {
                return Ok(got);
            };
            read?;
            got.extend(csv_records(&run));
        }
    }

    /// The records of a CSV run.
    fn csv_records(run: &PointRun) -> Vec<PointRecord> {
        match run.points() {
            RunPoints::Csv(points) => (0..points.points.len()).map(|i| points.record(i)).collect(),
            RunPoints::Npy(_) => panic!("a CSV run"),
        }
    }

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
        let e = read_in_blocks(invalid_utf8, 1 << 18, false).unwrap_err();
        assert!(e.to_string().contains("line 2: not UTF-8"), "{e}");
    }

    #[test]
    fn a_file_without_line_breaks_is_bounded() {
        let long = "1".repeat(MAX_LINE_BYTES * 3);
        let e = parse_points(&long).unwrap_err().to_string();
        assert!(e.contains("longer than"), "{e}");
    }

    /// A line too long is an error wherever it stands: among the data, or a comment before
    /// them.
    #[test]
    fn every_line_is_bounded_comments_before_the_data_too() {
        let comment = format!("#{}\n1,2\n", "c".repeat(MAX_LINE_BYTES));
        let data = format!("1,2\n#{}\n3,4\n", "c".repeat(MAX_LINE_BYTES));
        for (text, line) in [(comment, 1), (data, 2)] {
            let want = format!("line {line}: line longer than {MAX_LINE_BYTES} bytes");
            assert_eq!(parse_points(&text).unwrap_err().to_string(), want);
            for block_bytes in [10, 1 << 20] {
                let e = read_in_blocks(text.as_bytes(), block_bytes, false).unwrap_err();
                assert_eq!(e.to_string(), want);
            }
        }
    }

    /// The format read the plain way, as the reference for the readers: the text split at
    /// every `\n`, the byte-order mark taken off the first line, each line parsed on its own,
    /// the first header-like line before any data skipped.
    fn reference(text: &[u8]) -> Result<Vec<PointRecord>, PointsError> {
        let text = text.strip_prefix(b"\xef\xbb\xbf").unwrap_or(text);
        let mut lines: Vec<&[u8]> = text.split(|&b| b == b'\n').collect();
        if lines.last().is_some_and(|l| l.is_empty()) {
            lines.pop();
        }
        let (mut got, mut seen_data) = (Vec::new(), false);
        for (i, line) in lines.into_iter().enumerate() {
            let (parsed, _) = read_line(line, 0, i + 1)?;
            match parsed.kind {
                Kind::Blank => {}
                Kind::Header if !seen_data => seen_data = true,
                Kind::Header => {
                    let line = line.strip_suffix(b"\r").unwrap_or(line);
                    return Err(header_as_data(line, i + 1));
                }
                Kind::Point => {
                    seen_data = true;
                    let [x0, x1, y0, y1] = parsed.fields;
                    got.push(PointRecord {
                        point: parsed.point,
                        x_text: String::from_utf8_lossy(&line[x0..x1]).into(),
                        y_text: String::from_utf8_lossy(&line[y0..y1]).into(),
                    });
                }
            }
        }
        Ok(got)
    }

    /// The reader gives what the reference gives, whatever the block size, and the same first
    /// error; also when the run's buffer holds stale bytes before each read.
    #[test]
    fn the_readers_agree_with_the_reference() {
        let texts: [&[u8]; 12] = [
            b"\xef\xbb\xbfx,y,kind\n# c\n\n0.5, 1, b\r\n2 3e-1\n-0,+5\n1e-300\t7",
            b"\n\n# only comments\n",
            b"1,2\nx,y\n",
            b"# c\nX , Y\n1,2\n3,4\n",
            b"1,2\n3,4\nbad\n5,6\n",
            b"1,2\n\xff\n",
            b"1,2\r\n-3,4e1\r\n5,6\r",
            b"1,2\r\n3,4,5\n6, 7\n8,9",
            b"",
            b"\xef\xbb\xbf",
            b"x,y\nx,y\n1,2\n",
            b"x,y\n1,2\r\r\n \xc2\xa01\xc2\xa0,\t2\n\xc2\xa0# \xc3\xa9\n",
        ];
        for text in texts {
            let want = reference(text).map_err(|e| e.to_string());
            for (block_bytes, recycle) in [1, 3, 7, 64, 1 << 20]
                .into_iter()
                .flat_map(|b| [(b, false), (b, true)])
            {
                let result = read_in_blocks(text, block_bytes, recycle).map_err(|e| e.to_string());
                assert_eq!(result, want, "{text:?} in blocks of {block_bytes}");
            }
        }
    }

    /// Lines about [`MAX_LINE_BYTES`] long (one long number), ended by `\n`, `\r\n` or the
    /// end: the readers accept and refuse the same ones as the reference, whatever the block
    /// size.
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
                    let points = |r: Result<Vec<PointRecord>, PointsError>| {
                        r.map(|v| v.iter().map(|r| r.point).collect::<Vec<_>>())
                            .map_err(|e| e.to_string())
                    };
                    let want = points(reference(text.as_bytes()));
                    let mut results = Vec::new();
                    for block_bytes in [1024, 1 << 18, 1 << 20] {
                        results.push(points(read_in_blocks(text.as_bytes(), block_bytes, false)));
                    }
                    for got in results {
                        // (Summaries in the message: the points number 16 000.)
                        let summary = |r: &Result<Vec<Point>, String>| match r {
                            Ok(v) => format!("{} points, the last {:?}", v.len(), v.last()),
                            Err(e) => e.clone(),
                        };
                        assert!(
                            got == want,
                            "{len} bytes, {ending:?}: {} vs {}",
                            summary(&got),
                            summary(&want)
                        );
                    }
                    assert_eq!(
                        want.is_ok(),
                        len <= MAX_LINE_BYTES,
                        "{len} bytes, {ending:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn blocks_bound_a_file_without_line_breaks() {
        let long = "1".repeat(MAX_LINE_BYTES * 3);
        let mut blocks = Blocks::new(long.as_bytes(), "t", 1024);
        let e = blocks.next_block(&mut Vec::new()).unwrap_err().to_string();
        assert!(e.contains("longer than"), "{e}");
    }

    /// Runs in order are numbered 0, 1, ...; a run that fails to parse fails alone (the
    /// caller stops at the first failure in file order), a read that fails ends the runs.
    #[test]
    fn a_bad_line_fails_its_run_and_a_failed_read_ends_the_runs() {
        let sizes = RunSizes {
            csv_bytes: 1,
            ..RunSizes::default()
        };
        let reader = CsvReader::new("1,2\nbad\n3,4\n".as_bytes(), "t", sizes);
        let mut run = PointRun::default();
        let (k, read) = reader.next_run(&mut run).unwrap();
        assert!(k == 0 && read.is_ok() && run.len() == 1);
        let (k, read) = reader.next_run(&mut run).unwrap();
        assert!(k == 1 && read.is_err() && run.is_empty());
        let (k, read) = reader.next_run(&mut run).unwrap();
        assert!(k == 2 && read.is_ok() && run.len() == 1);
        assert!(reader.next_run(&mut run).is_none());
        assert_eq!(reader.progress().runs_taken, 3);
        let long = format!("1,2\n{}\n3,4\n", "5".repeat(MAX_LINE_BYTES + 10));
        let reader = CsvReader::new(long.as_bytes(), "t", sizes);
        assert!(reader.next_run(&mut run).unwrap().1.is_ok());
        let e = reader.next_run(&mut run).unwrap().1.unwrap_err();
        assert!(e.to_string().starts_with("line 2: line longer than"), "{e}");
        /// An input whose reads fail.
        struct Failing;
        impl Read for Failing {
            fn read(&mut self, _: &mut [u8]) -> std::io::Result<usize> {
                Err(std::io::Error::other("gone"))
            }
        }
        let reader = CsvReader::new(Failing, "pipe", sizes);
        let e = reader.next_run(&mut run).unwrap().1.unwrap_err();
        assert_eq!(e.to_string(), "pipe: gone");
        assert!(reader.next_run(&mut run).is_none());
        assert_eq!(reader.progress().runs_taken, 1);
    }

    /// Points and their fields as written, or the error message: by blocks in order
    /// (the reference) or by position.
    #[cfg(unix)]
    type Parsed = Result<Vec<(f64, f64, Vec<u8>, Vec<u8>)>, String>;

    #[cfg(unix)]
    fn in_order(path: &Path, block_bytes: usize) -> Parsed {
        let file = open_file(path).map_err(|e| e.to_string())?;
        let sizes = RunSizes {
            csv_bytes: block_bytes,
            ..RunSizes::default()
        };
        let reader = CsvReader::new(file, "t", sizes);
        let (mut run, mut all) = (PointRun::default(), Vec::new());
        while let Some((_, read)) = reader.next_run(&mut run) {
            read.map_err(|e| e.to_string())?;
            collect(&run, &mut all);
        }
        Ok(all)
    }

    #[cfg(unix)]
    fn by_position(f: &CsvFile) -> Parsed {
        let mut run = PointRun::default();
        let mut all = Vec::new();
        for k in 0..f.blocks() {
            let lines = f.read_block(k, &mut run.bytes).map_err(|e| e.to_string())?;
            f.parse_block(k, &lines, &mut run)
                .map_err(|e| e.to_string())?;
            run.content = Content::Csv;
            collect(&run, &mut all);
        }
        Ok(all)
    }

    /// A directory of its own for a test, and the points file's name in it.
    #[cfg(unix)]
    fn scratch(test: &str) -> (std::path::PathBuf, std::path::PathBuf) {
        let dir = std::env::temp_dir().join(format!("rs-io-csvfile-{test}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("points.csv");
        (dir, path)
    }

    #[cfg(unix)]
    fn collect(run: &PointRun, all: &mut Vec<(f64, f64, Vec<u8>, Vec<u8>)>) {
        let RunPoints::Csv(points) = run.points() else {
            panic!("a CSV run")
        };
        for (i, p) in points.points.iter().enumerate() {
            all.push((p.x, p.y, points.x(i).to_vec(), points.y(i).to_vec()));
        }
    }

    #[cfg(unix)]
    #[test]
    fn blocks_read_by_position_hold_the_lines_read_in_order() {
        let (dir, path) = scratch("blocks");
        let mut rng = rs_testkit::XorShift64::new(0x2545_f491_4f6c_dd1d);
        let mut next = |n: u64| rng.below(n);
        let mut files = 0;
        let mut failures = 0;
        for case in 0..400 {
            // Lines of every kind the format allows, and now and then a bad one.
            let mut text = Vec::new();
            if case % 7 == 0 {
                text.extend_from_slice(b"\xef\xbb\xbf");
            }
            if case % 3 == 0 {
                text.extend_from_slice(b"# a comment\n\n");
            }
            if case % 2 == 0 {
                text.extend_from_slice(b"x,y\n");
            }
            let lines = next(60);
            for i in 0..lines {
                let line: String = match next(40) {
                    0 => "# note".into(),
                    1 => String::new(),
                    2 => format!("{} {}", i, next(1000)),
                    3 => format!("{},{},extra\r", next(100), i),
                    4 => format!("  {} , {}", i, next(7)),
                    5 => format!("-0.{:0>30},1", next(1_000_000)), // a long number
                    6 if case % 5 == 0 => "1,oops".into(),
                    7 if case % 11 == 0 => "x,y".into(), // a header among the data
                    _ => format!("{}.{},{}", i, next(1000), next(1 << 40) as f64 / 3.0),
                };
                text.extend_from_slice(line.as_bytes());
                if i + 1 < lines || next(2) == 0 {
                    text.push(b'\n');
                }
            }
            std::fs::write(&path, &text).unwrap();
            for block_bytes in [1, 2, 5, 16, 37, 200, 1 << 16] {
                let want = in_order(&path, block_bytes);
                match CsvFile::open(&path, block_bytes) {
                    Ok(Some(f)) => {
                        files += 1;
                        failures += usize::from(want.is_err());
                        assert_eq!(
                            by_position(&f),
                            want,
                            "case {case}, blocks of {block_bytes}"
                        );
                    }
                    // The first block holds no data (or the file none at all): the sequential
                    // path reads such a file.
                    Ok(None) => {}
                    Err(e) => assert_eq!(Err(e.to_string()), want),
                }
            }
        }
        assert!(
            files > 2000 && failures > 100,
            "{files} files, {failures} bad"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_line_too_long_is_reported_at_its_number() {
        let (dir, path) = scratch("long");
        let mut text = b"1,2\n3,4\n".to_vec();
        text.extend(std::iter::repeat_n(b'5', MAX_LINE_BYTES + 10));
        text.extend_from_slice(b",1\n6,7\n");
        std::fs::write(&path, &text).unwrap();
        for block_bytes in [3, 1000, 1 << 18] {
            let f = CsvFile::open(&path, block_bytes).unwrap().unwrap();
            let err = by_position(&f).unwrap_err();
            assert_eq!(err, in_order(&path, block_bytes).unwrap_err());
            assert!(err.starts_with("line 3: line longer than"), "{err}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn files_without_data_in_the_first_block_are_left_to_the_sequential_reader() {
        let (dir, path) = scratch("none");
        // 190 KB of comments (a first block reads at least 64 KiB), then one point.
        let mut text = "# a comment of twenty bytes\n".repeat(7000);
        text.push_str("\n1,2\n");
        std::fs::write(&path, &text).unwrap();
        assert!(CsvFile::open(&path, 4).unwrap().is_none());
        let f = CsvFile::open(&path, 1 << 20).unwrap().unwrap();
        assert_eq!(by_position(&f).unwrap().len(), 1);
        std::fs::write(&path, "").unwrap();
        assert!(CsvFile::open(&path, 4).unwrap().is_none());
        assert!(CsvFile::open(&dir, 4).map_or(true, |f| f.is_none()));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
