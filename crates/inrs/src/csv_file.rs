//! A CSV points file read by position: blocks that any thread reads and parses on its own.

use std::os::unix::fs::FileExt;
use std::path::Path;

use crate::points_csv::{CsvBlock, CsvBlocks, MAX_LINE_BYTES, ParsedBlock, PointsError, open_file};

/// A regular CSV points file cut into blocks by byte position, for threads that each read and
/// parse whole blocks (no thread reads ahead for them, and the bytes a thread reads are still
/// in its cache when it parses them). Block `k` holds the lines that *start* in its byte
/// range: its first bytes, up to a line end, belong to the line before, and its last line runs
/// on to its end. The format is that of [`crate::PointReader`]; the byte-order mark, comments
/// before the data and the header are found once, when the file is opened, and the blocks
/// cover the file's length at that time (lines appended later are not read).
///
/// # Examples
///
/// ```
/// # #[cfg(unix)] {
/// let path = std::env::temp_dir().join(format!("inrs-doc-csvfile-{}.csv", std::process::id()));
/// std::fs::write(&path, "x,y\n1,2\n3,4\n5,6\n").unwrap();
/// // Blocks of 3 bytes: "1,2\n" starts in the first, "3,4\n" and "5,6\n" in the next ones.
/// let f = inrs::CsvPointsFile::open(&path, 3).unwrap().expect("data in the first block");
/// let (mut block, mut parsed) = (inrs::CsvBlock::default(), inrs::ParsedBlock::default());
/// let mut xs = Vec::new();
/// for k in 0..f.blocks() {
///     f.read_block(k, &mut block).unwrap();
///     f.parse_block(k, &block, &mut parsed).unwrap();
///     xs.extend(parsed.points.iter().map(|p| p.x));
/// }
/// assert_eq!(xs, [1.0, 3.0, 5.0]);
/// # std::fs::remove_file(&path).unwrap();
/// # }
/// ```
#[derive(Debug)]
pub struct CsvPointsFile {
    file: std::fs::File,
    path: String,
    len: u64,
    block_bytes: u64,
    /// Where the data start: after the byte-order mark, the comments and the header.
    data_from: u64,
}

/// Bytes read at a time while looking for the end of a block's last line.
const LINE_END_READ: usize = 4096;

impl CsvPointsFile {
    /// Opens `path` and finds where its data start, reading its first block of about
    /// `block_bytes` as [`CsvBlocks`] does. `None` if it is not a regular file, or if no data
    /// line starts in that block (a file that opens with that many bytes of comments): read it
    /// in order with [`CsvBlocks`] then.
    ///
    /// # Errors
    /// [`PointsError::Io`]; [`PointsError::Line`] for a first line too long.
    pub fn open(path: impl AsRef<Path>, block_bytes: usize) -> Result<Option<Self>, PointsError> {
        let path = path.as_ref();
        let name = path.display().to_string();
        let file = open_file(path)?;
        let io = |source| PointsError::Io {
            path: name.clone(),
            source,
        };
        let meta = file.metadata().map_err(io)?;
        if !meta.is_file() {
            return Ok(None);
        }
        let mut blocks = CsvBlocks::new(&file, name.clone(), block_bytes);
        let Some(first) = blocks.next_block()? else {
            return Ok(None);
        };
        if !blocks.seen_data() {
            return Ok(None);
        }
        let data_from = (blocks.dropped_at_start() + first.data_from()) as u64;
        Ok(Some(Self {
            file,
            path: name,
            len: meta.len(),
            block_bytes: block_bytes.max(1) as u64,
            data_from,
        }))
    }

    /// The number of blocks.
    pub fn blocks(&self) -> usize {
        (self.len.saturating_sub(self.data_from)).div_ceil(self.block_bytes) as usize
    }

    /// Where block `k`'s byte range starts (the file's length past the last block).
    pub fn offset_of_block(&self, k: usize) -> u64 {
        (self.data_from)
            .saturating_add((k as u64).saturating_mul(self.block_bytes))
            .min(self.len)
    }

    /// Reads block `k` into `block`, reusing its buffer: from one byte before its range (to
    /// see whether a line starts at the range) to the end of its last line, at most
    /// [`MAX_LINE_BYTES`] past the range (a longer line is then reported by
    /// [`CsvPointsFile::parse_block`]).
    ///
    /// # Errors
    /// [`PointsError::Io`].
    pub fn read_block(&self, k: usize, block: &mut CsvBlock) -> Result<(), PointsError> {
        let (start, end) = (self.offset_of_block(k), self.offset_of_block(k + 1));
        let from = if k == 0 { start } else { start - 1 };
        let text = &mut block.text;
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
        block.set_positional(skip);
        Ok(())
    }

    /// Parses block `k`, read into `block` by [`CsvPointsFile::read_block`], into `out`;
    /// errors name the line's number in the file.
    ///
    /// # Errors
    /// [`PointsError::Line`] for the block's first bad line; [`PointsError::Io`] if the
    /// lines before it cannot be counted.
    pub fn parse_block(
        &self,
        k: usize,
        block: &CsvBlock,
        out: &mut ParsedBlock,
    ) -> Result<(), PointsError> {
        block.parse_into(out).map_err(|e| match e {
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
            count += memchr::memchr_iter(b'\n', &buf[..got]).count();
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

    /// Points and their fields as written, or the error message: by blocks in order
    /// ([`CsvBlocks`], the reference) or by position.
    type Parsed = Result<Vec<(f64, f64, Vec<u8>, Vec<u8>)>, String>;

    fn in_order(path: &Path, block_bytes: usize) -> Parsed {
        let mut blocks = crate::open_points_blocks(path, block_bytes).map_err(|e| e.to_string())?;
        let mut parsed = ParsedBlock::default();
        let mut all = Vec::new();
        while let Some(b) = blocks.next_block().map_err(|e| e.to_string())? {
            b.parse_into(&mut parsed).map_err(|e| e.to_string())?;
            collect(&b, &parsed, &mut all);
        }
        Ok(all)
    }

    fn by_position(f: &CsvPointsFile) -> Parsed {
        let (mut block, mut parsed) = (CsvBlock::default(), ParsedBlock::default());
        let mut all = Vec::new();
        for k in 0..f.blocks() {
            f.read_block(k, &mut block).map_err(|e| e.to_string())?;
            f.parse_block(k, &block, &mut parsed)
                .map_err(|e| e.to_string())?;
            collect(&block, &parsed, &mut all);
        }
        Ok(all)
    }

    /// A directory of its own for a test, and the points file's name in it.
    fn scratch(test: &str) -> (std::path::PathBuf, std::path::PathBuf) {
        let dir = std::env::temp_dir().join(format!("inrs-csvfile-{test}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("points.csv");
        (dir, path)
    }

    fn collect(b: &CsvBlock, parsed: &ParsedBlock, all: &mut Vec<(f64, f64, Vec<u8>, Vec<u8>)>) {
        for (p, f) in parsed.points.iter().zip(&parsed.fields) {
            all.push((
                p.x,
                p.y,
                b.field(f[0], f[1]).to_vec(),
                b.field(f[2], f[3]).to_vec(),
            ));
        }
    }

    #[test]
    fn blocks_read_by_position_hold_the_lines_read_in_order() {
        let (dir, path) = scratch("blocks");
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = |n: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % n
        };
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
                match CsvPointsFile::open(&path, block_bytes) {
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

    #[test]
    fn a_line_too_long_is_reported_at_its_number() {
        let (dir, path) = scratch("long");
        let mut text = b"1,2\n3,4\n".to_vec();
        text.extend(std::iter::repeat_n(b'5', MAX_LINE_BYTES + 10));
        text.extend_from_slice(b",1\n6,7\n");
        std::fs::write(&path, &text).unwrap();
        for block_bytes in [3, 1000, 1 << 18] {
            let f = CsvPointsFile::open(&path, block_bytes).unwrap().unwrap();
            let err = by_position(&f).unwrap_err();
            assert_eq!(err, in_order(&path, block_bytes).unwrap_err());
            assert!(err.starts_with("line 3: line longer than"), "{err}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn files_without_data_in_the_first_block_are_left_to_the_sequential_reader() {
        let (dir, path) = scratch("none");
        // 190 KB of comments (a first block reads at least 64 KiB), then one point.
        let mut text = "# a comment of twenty bytes\n".repeat(7000);
        text.push_str("\n1,2\n");
        std::fs::write(&path, &text).unwrap();
        assert!(CsvPointsFile::open(&path, 4).unwrap().is_none());
        let f = CsvPointsFile::open(&path, 1 << 20).unwrap().unwrap();
        assert_eq!(by_position(&f).unwrap().len(), 1);
        std::fs::write(&path, "").unwrap();
        assert!(CsvPointsFile::open(&path, 4).unwrap().is_none());
        assert!(CsvPointsFile::open(&dir, 4).map_or(true, |f| f.is_none()));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
