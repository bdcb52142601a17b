//! Points files as numbered chunks for parallel work: the one [`ChunkSource`] trait, for CSV
//! and `.npy` alike, read in order ([`Sequential`]) or by position ([`Positional`], Unix).

use std::io::Read;
use std::path::Path;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};

use super::{CsvBlock, CsvBlocks, EncodedPoints, NpyPoints, NpyType, ParsedBlock, PointsError};
#[cfg(unix)]
use super::{CsvPointsFile, NpyPointsFile};

/// How a points file is cut into chunks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChunkSizes {
    /// Bytes of CSV per chunk: the lines that start in a range of that many bytes (read by
    /// position), or whole lines of about that many bytes (read in order).
    pub csv_bytes: usize,
    /// `.npy` points per chunk.
    pub npy_points: usize,
    /// `.npy` points read by position and handed over at a time
    /// ([`ChunkSource::read_points`]), so that their bytes stay in the cache from the read to
    /// the computation (points read in order are handed over a chunk at a time).
    pub npy_run: usize,
}

impl Default for ChunkSizes {
    /// CSV chunks of 256 KiB; `.npy` chunks of 65 536 points handed over 4 096 at a time (64
    /// KiB of float64 pairs: a chunk's megabyte read at once cost the first chunk of each
    /// thread 0.5-0.9 ms of page faults, and every chunk another pass through memory).
    fn default() -> Self {
        Self {
            csv_bytes: 1 << 18,
            npy_points: 1 << 16,
            npy_run: 1 << 12,
        }
    }
}

/// A chunk of a points file, read by a [`ChunkSource`] and turned into points by the same
/// source ([`ChunkSource::read_points`]), on the thread that read it or any other. Its buffer
/// is reused by the next read into it.
#[derive(Debug, Default)]
pub struct Chunk {
    /// The chunk's number.
    index: usize,
    data: ChunkData,
}

#[derive(Debug)]
enum ChunkData {
    /// Nothing read: a buffer to read into.
    Spare(Vec<u8>),
    /// Whole CSV lines.
    Csv(CsvBlock),
    /// `.npy` points as stored, read in order and checked finite.
    Npy { ty: NpyType, bytes: Vec<u8> },
    /// `.npy` points `first..first + n`, to be read by position as they are handed over.
    NpyRange {
        first: usize,
        n: usize,
        buffer: Vec<u8>,
    },
}

impl Default for ChunkData {
    fn default() -> Self {
        Self::Spare(Vec::new())
    }
}

impl ChunkData {
    /// The buffer it holds.
    fn into_buffer(self) -> Vec<u8> {
        match self {
            Self::Spare(buffer)
            | Self::Csv(CsvBlock { text: buffer, .. })
            | Self::Npy { bytes: buffer, .. }
            | Self::NpyRange { buffer, .. } => buffer,
        }
    }
}

impl Chunk {
    /// A chunk that reads into `buffer` (its contents discarded): a buffer used before saves the
    /// allocation and the page faults of a fresh one.
    pub fn with_buffer(buffer: Vec<u8>) -> Self {
        Self {
            index: 0,
            data: ChunkData::Spare(buffer),
        }
    }

    /// The chunk's buffer, for reuse.
    pub fn into_buffer(self) -> Vec<u8> {
        self.data.into_buffer()
    }

    /// The chunk's number in its file (0 before a read).
    pub fn index(&self) -> usize {
        self.index
    }

    /// Takes the buffer out, leaving the chunk empty.
    fn take_buffer(&mut self) -> Vec<u8> {
        std::mem::take(&mut self.data).into_buffer()
    }

    /// The chunk's CSV block, taken out (made of its buffer if it holds none).
    #[cfg(unix)]
    fn take_csv_block(&mut self) -> CsvBlock {
        match std::mem::take(&mut self.data) {
            ChunkData::Csv(block) => block,
            other => CsvBlock {
                text: other.into_buffer(),
                ..CsvBlock::default()
            },
        }
    }
}

/// Points of a chunk, as [`ChunkSource::read_points`] hands them over.
#[derive(Clone, Copy, Debug)]
pub enum ChunkPoints<'a> {
    /// CSV lines, parsed: the points, and where their fields stand in the block's text (to
    /// echo them as written).
    Csv {
        /// The lines.
        block: &'a CsvBlock,
        /// Their points.
        parsed: &'a ParsedBlock,
    },
    /// `.npy` points as stored.
    Npy(EncodedPoints<'a>),
}

impl ChunkPoints<'_> {
    /// The number of points.
    pub fn len(&self) -> usize {
        match self {
            Self::Csv { parsed, .. } => parsed.points.len(),
            Self::Npy(points) => points.len(),
        }
    }

    /// True if there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A thread's buffers for turning chunks into points, kept from chunk to chunk (fresh ones
/// cost a page fault per 4 KiB and their zero-filling).
#[derive(Debug, Default)]
pub struct ChunkScratch {
    parsed: ParsedBlock,
    bytes: Vec<u8>,
}

/// A points file, CSV or `.npy`, as chunks numbered 0, 1, ... in file order, for threads that
/// each take a chunk ([`ChunkSource::next_chunk`]), turn it into points
/// ([`ChunkSource::read_points`]) and compute on them. Memory is the chunks in hand.
///
/// Two implementations: [`Sequential`] reads the chunks one at a time, in order (any input);
/// [`Positional`] lets any number of threads read chunks at once, by position (a regular file,
/// Unix). [`open_chunks`] chooses.
///
/// # Examples
///
/// ```
/// use rs_io::points::{Chunk, ChunkPoints, ChunkScratch, ChunkSizes, ChunkSource, CsvBlocks, Sequential};
/// let text = "x,y\n1,2\n3,4\n";
/// let source = Sequential::csv(CsvBlocks::new(text.as_bytes(), "input", 4));
/// let (mut chunk, mut scratch, mut xs) = (Chunk::default(), ChunkScratch::default(), vec![]);
/// while let Some((k, read)) = source.next_chunk(&mut chunk, &mut |_| true) {
///     read.unwrap();
///     source
///         .read_points(&chunk, &mut scratch, &mut |points| {
///             if let ChunkPoints::Csv { parsed, .. } = points {
///                 xs.extend(parsed.points.iter().map(|p| (k, p.x)));
///             }
///         })
///         .unwrap();
/// }
/// assert_eq!(xs, [(0, 1.0), (0, 3.0)]);
/// assert_eq!(source.chunks_taken(), 1);
/// ```
pub trait ChunkSource: Sync {
    /// Whether the chunks are read one at a time, in order ([`Sequential`]): a thread that
    /// reads them ahead for the others then keeps the others computing. False if any number
    /// of threads may read chunks at once ([`Positional`]).
    fn in_order(&self) -> bool;

    /// Takes the next chunk: numbers it `k` (0, 1, ... in file order), then, if `admit(k)`
    /// (which may wait, for room in an output say), reads it into `chunk`, reusing its
    /// buffer. `None` when the chunks have run out, after a chunk that failed, or if `admit`
    /// refuses. Any number of threads may take chunks at once.
    ///
    /// The read's result comes with the chunk's number: [`PointsError::Io`], a CSV line too
    /// long, a `.npy` file cut short or holding a non-finite coordinate (read in order) are
    /// errors of chunk `k`, the last one taken.
    fn next_chunk(
        &self,
        chunk: &mut Chunk,
        admit: &mut dyn FnMut(usize) -> bool,
    ) -> Option<(usize, Result<(), PointsError>)>;

    /// Hands the points of `chunk`, taken from this source, to `visit`, in file order, in one
    /// or more runs; CSV is parsed into `scratch`, `.npy` read by position into it. (A chunk
    /// that holds nothing this source reads gives none.)
    ///
    /// # Errors
    /// [`PointsError::Line`] for a chunk's first bad line, with its number in the file (the
    /// runs before it are handed over); for `.npy` read by position, as
    /// [`NpyPointsFile::read_encoded`].
    fn read_points(
        &self,
        chunk: &Chunk,
        scratch: &mut ChunkScratch,
        visit: &mut dyn FnMut(ChunkPoints<'_>),
    ) -> Result<(), PointsError>;

    /// How many chunks have been taken (the failed one included): all of them once
    /// [`ChunkSource::next_chunk`] has run out.
    fn chunks_taken(&self) -> usize;

    /// Bytes of the file read so far, or covered by the chunks taken (for progress reports).
    fn bytes_read(&self) -> u64;

    /// The number of points, if known before reading (`.npy`).
    fn points(&self) -> Option<usize>;
}

/// A points file read in order, one chunk at a time (a pipe, say, or a CSV file that opens
/// with a block of comments, or any file where reading by position is not available): the
/// [`ChunkSource`] over [`CsvBlocks`] or [`NpyPoints`].
#[derive(Debug)]
pub struct Sequential<R> {
    state: Mutex<InOrder<R>>,
    /// Chunks taken.
    taken: AtomicUsize,
    /// Bytes read.
    read: AtomicU64,
    /// The number of points, if known.
    points: Option<usize>,
}

#[derive(Debug)]
struct InOrder<R> {
    reader: InOrderReader<R>,
    /// Whether the input has ended or failed.
    done: bool,
}

#[derive(Debug)]
enum InOrderReader<R> {
    Csv(CsvBlocks<R>),
    Npy {
        points: NpyPoints<R>,
        per_chunk: usize,
    },
}

impl<R: Read> Sequential<R> {
    /// The CSV blocks of `blocks` as chunks.
    pub fn csv(blocks: CsvBlocks<R>) -> Self {
        Self::new(InOrderReader::Csv(blocks), None)
    }

    /// The points of `points` as chunks of `sizes.npy_points`.
    pub fn npy(points: NpyPoints<R>, sizes: ChunkSizes) -> Self {
        let len = points.len();
        let reader = InOrderReader::Npy {
            points,
            per_chunk: sizes.npy_points.max(1),
        };
        Self::new(reader, Some(len))
    }

    fn new(reader: InOrderReader<R>, points: Option<usize>) -> Self {
        Self {
            state: Mutex::new(InOrder {
                reader,
                done: false,
            }),
            taken: AtomicUsize::new(0),
            read: AtomicU64::new(0),
            points,
        }
    }
}

impl<R: Read + Send> ChunkSource for Sequential<R> {
    fn in_order(&self) -> bool {
        true
    }

    fn next_chunk(
        &self,
        chunk: &mut Chunk,
        admit: &mut dyn FnMut(usize) -> bool,
    ) -> Option<(usize, Result<(), PointsError>)> {
        let mut state = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        let k = self.taken.load(Ordering::Relaxed);
        if state.done || !admit(k) {
            return None;
        }
        let mut buffer = chunk.take_buffer();
        let (read, bytes_read) = match &mut state.reader {
            InOrderReader::Csv(blocks) => {
                blocks.recycle(buffer);
                let read = blocks.next_block().map(|b| b.map(ChunkData::Csv));
                (read, blocks.bytes_read())
            }
            InOrderReader::Npy { points, per_chunk } => {
                let ty = points.element_type();
                let read = match points
                    .read_encoded(*per_chunk, &mut buffer)
                    .map(|p| p.len())
                {
                    Ok(0) => Ok(None),
                    Ok(_) => Ok(Some(ChunkData::Npy {
                        ty,
                        bytes: std::mem::take(&mut buffer),
                    })),
                    Err(e) => Err(e),
                };
                chunk.data = ChunkData::Spare(buffer);
                (read, points.bytes_read())
            }
        };
        self.read.store(bytes_read, Ordering::Relaxed);
        let read = match read {
            Ok(None) => None,
            Ok(Some(data)) => {
                chunk.data = data;
                Some(Ok(()))
            }
            Err(e) => Some(Err(e)),
        };
        state.done = !matches!(read, Some(Ok(())));
        if read.is_some() {
            chunk.index = k;
            self.taken.store(k + 1, Ordering::Relaxed);
        }
        read.map(|r| (k, r))
    }

    fn read_points(
        &self,
        chunk: &Chunk,
        scratch: &mut ChunkScratch,
        visit: &mut dyn FnMut(ChunkPoints<'_>),
    ) -> Result<(), PointsError> {
        match &chunk.data {
            ChunkData::Csv(block) => {
                block.parse_into(&mut scratch.parsed)?;
                visit(ChunkPoints::Csv {
                    block,
                    parsed: &scratch.parsed,
                });
            }
            ChunkData::Npy { ty, bytes } => {
                visit(ChunkPoints::Npy(EncodedPoints::from_checked(*ty, bytes)));
            }
            ChunkData::Spare(_) | ChunkData::NpyRange { .. } => {}
        }
        Ok(())
    }

    fn chunks_taken(&self) -> usize {
        self.taken.load(Ordering::Relaxed)
    }

    fn bytes_read(&self) -> u64 {
        self.read.load(Ordering::Relaxed)
    }

    fn points(&self) -> Option<usize> {
        self.points
    }
}

/// A regular file read by position: chunks that any number of threads read at once, each the
/// one it takes (no thread reads ahead for the others, and the bytes a thread reads are still
/// in its cache when it computes on them); the [`ChunkSource`] over [`CsvPointsFile`] or
/// [`NpyPointsFile`]. Unix only.
#[cfg(unix)]
#[derive(Debug)]
pub struct Positional {
    file: PositionalFile,
    /// The next chunk to take.
    next: AtomicUsize,
    /// Where the chunks taken end, at the furthest.
    read: AtomicU64,
}

#[cfg(unix)]
#[derive(Debug)]
enum PositionalFile {
    Csv(CsvPointsFile),
    Npy {
        file: NpyPointsFile,
        per_chunk: usize,
        run: usize,
    },
}

#[cfg(unix)]
impl Positional {
    /// The blocks of `file` as chunks.
    pub fn csv(file: CsvPointsFile) -> Self {
        Self::new(PositionalFile::Csv(file))
    }

    /// The points of `file` as chunks of `sizes.npy_points`.
    pub fn npy(file: NpyPointsFile, sizes: ChunkSizes) -> Self {
        Self::new(PositionalFile::Npy {
            file,
            per_chunk: sizes.npy_points.max(1),
            run: sizes.npy_run.max(1),
        })
    }

    fn new(file: PositionalFile) -> Self {
        Self {
            file,
            next: AtomicUsize::new(0),
            read: AtomicU64::new(0),
        }
    }

    /// The number of chunks.
    pub fn chunks(&self) -> usize {
        match &self.file {
            PositionalFile::Csv(f) => f.blocks(),
            PositionalFile::Npy {
                file, per_chunk, ..
            } => file.len().div_ceil(*per_chunk),
        }
    }

    /// Where chunk `k` starts in the file (the file's length past the last chunk).
    pub fn offset_of(&self, k: usize) -> u64 {
        match &self.file {
            PositionalFile::Csv(f) => f.offset_of_block(k),
            PositionalFile::Npy {
                file, per_chunk, ..
            } => file.offset_of(k.saturating_mul(*per_chunk).min(file.len())),
        }
    }
}

#[cfg(unix)]
impl ChunkSource for Positional {
    fn in_order(&self) -> bool {
        false
    }

    fn next_chunk(
        &self,
        chunk: &mut Chunk,
        admit: &mut dyn FnMut(usize) -> bool,
    ) -> Option<(usize, Result<(), PointsError>)> {
        let k = self.next.fetch_add(1, Ordering::Relaxed);
        if k >= self.chunks() || !admit(k) {
            return None;
        }
        self.read
            .fetch_max(self.offset_of(k + 1), Ordering::Relaxed);
        chunk.index = k;
        let read = match &self.file {
            PositionalFile::Csv(f) => {
                let mut block = chunk.take_csv_block();
                let read = f.read_block(k, &mut block);
                chunk.data = ChunkData::Csv(block);
                read
            }
            PositionalFile::Npy {
                file, per_chunk, ..
            } => {
                let first = k * per_chunk;
                let n = (*per_chunk).min(file.len().saturating_sub(first));
                let buffer = chunk.take_buffer();
                chunk.data = ChunkData::NpyRange { first, n, buffer };
                Ok(())
            }
        };
        Some((k, read))
    }

    fn read_points(
        &self,
        chunk: &Chunk,
        scratch: &mut ChunkScratch,
        visit: &mut dyn FnMut(ChunkPoints<'_>),
    ) -> Result<(), PointsError> {
        match (&self.file, &chunk.data) {
            (PositionalFile::Csv(f), ChunkData::Csv(block)) => {
                f.parse_block(chunk.index, block, &mut scratch.parsed)?;
                visit(ChunkPoints::Csv {
                    block,
                    parsed: &scratch.parsed,
                });
            }
            (PositionalFile::Npy { file, run, .. }, &ChunkData::NpyRange { first, n, .. }) => {
                let mut at = first;
                while at < first + n {
                    let m = (*run).min(first + n - at);
                    visit(ChunkPoints::Npy(file.read_encoded(
                        at,
                        m,
                        &mut scratch.bytes,
                    )?));
                    at += m;
                }
            }
            _ => {}
        }
        Ok(())
    }

    fn chunks_taken(&self) -> usize {
        self.next.load(Ordering::Relaxed).min(self.chunks())
    }

    fn bytes_read(&self) -> u64 {
        self.read.load(Ordering::Relaxed)
    }

    fn points(&self) -> Option<usize> {
        match &self.file {
            PositionalFile::Csv(_) => None,
            PositionalFile::Npy { file, .. } => Some(file.len()),
        }
    }
}

/// Opens the points file `path` as chunks of `sizes`: `.npy` if its name ends so, CSV
/// otherwise; read by position if it is a regular file (Unix; for CSV, if its first chunk
/// holds data), else in order (a named pipe cannot be read by position).
///
/// # Errors
/// [`PointsError::Io`] if it cannot be opened; for `.npy`, as [`NpyPoints::new`]; for CSV, a
/// first line too long.
pub fn open_chunks(
    path: impl AsRef<Path>,
    sizes: ChunkSizes,
) -> Result<Box<dyn ChunkSource>, PointsError> {
    let path = path.as_ref();
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"))
    {
        #[cfg(unix)]
        if std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
            let file = NpyPointsFile::open(path)?;
            return Ok(Box::new(Positional::npy(file, sizes)));
        }
        let points = super::open_npy_points(path)?;
        return Ok(Box::new(Sequential::npy(points, sizes)));
    }
    // Only a regular file is opened twice (a pipe's data would go with the first opening).
    #[cfg(unix)]
    if std::fs::metadata(path).is_ok_and(|m| m.is_file())
        && let Some(file) = CsvPointsFile::open(path, sizes.csv_bytes)?
    {
        return Ok(Box::new(Positional::csv(file)));
    }
    let blocks = super::open_points_blocks(path, sizes.csv_bytes)?;
    Ok(Box::new(Sequential::csv(blocks)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::{PointReader, npy_header};
    use rs_spline::Point;

    /// A point and its fields as written (empty for `.npy`).
    type Record = (Point, String, String);

    /// A chunk's number, and its records or error.
    type Drained = (usize, Result<Vec<Record>, String>);

    /// Every chunk of `source`, taken by `threads` threads at once, turned into records; in
    /// file order, up to the first chunk that failed (its error then). Checks that the chunks
    /// are numbered 0, 1, ... and all taken.
    fn drain(source: &dyn ChunkSource, threads: usize) -> Result<Vec<Record>, String> {
        let chunks: Mutex<Vec<Drained>> = Mutex::default();
        std::thread::scope(|s| {
            for _ in 0..threads {
                s.spawn(|| {
                    let (mut chunk, mut scratch) = (Chunk::default(), ChunkScratch::default());
                    while let Some((k, read)) = source.next_chunk(&mut chunk, &mut |_| true) {
                        assert_eq!(chunk.index(), k);
                        let mut records = Vec::new();
                        let read = read.and_then(|()| {
                            source.read_points(&chunk, &mut scratch, &mut |points| match points {
                                ChunkPoints::Csv { block, parsed } => {
                                    for (p, f) in parsed.points.iter().zip(&parsed.fields) {
                                        let text = |a, b| {
                                            String::from_utf8_lossy(block.field(a, b)).into()
                                        };
                                        records.push((*p, text(f[0], f[1]), text(f[2], f[3])));
                                    }
                                }
                                ChunkPoints::Npy(e) => records.extend(
                                    (0..e.len())
                                        .map(|i| (e.point(i), String::new(), String::new())),
                                ),
                            })
                        });
                        let result = read.map(|()| records).map_err(|e| e.to_string());
                        chunks.lock().unwrap().push((k, result));
                    }
                });
            }
        });
        let mut chunks = chunks.into_inner().unwrap();
        chunks.sort_by_key(|c| c.0);
        assert!(
            chunks.iter().enumerate().all(|(i, c)| c.0 == i),
            "numbered in order"
        );
        assert_eq!(source.chunks_taken(), chunks.len());
        let mut all = Vec::new();
        for (_, c) in chunks {
            all.extend(c?);
        }
        Ok(all)
    }

    /// A file of its own for a test.
    fn scratch_file(name: &str, bytes: &[u8]) -> std::path::PathBuf {
        let path = std::env::temp_dir().join(format!("rs-io-source-{}-{name}", std::process::id()));
        std::fs::write(&path, bytes).unwrap();
        path
    }

    /// The CSV and `.npy` files of the tests, as bytes.
    fn csv_text(lines: usize, bad_at: Option<usize>) -> Vec<u8> {
        let mut text = b"\xef\xbb\xbf# points\r\n\r\nx,y,kind\r\n".to_vec();
        for i in 0..lines {
            let line = match i % 5 {
                _ if Some(i) == bad_at => "1;2".to_string(),
                0 => format!("{},{}", i as f64 * 0.125, -(i as f64) / 3.0),
                1 => format!("  {i} , 2.5e-3 ,inside"),
                2 => format!("{i}\t{}", i * 7),
                3 => "# a comment".into(),
                _ => format!("-{i}.0,+{i}"),
            };
            text.extend_from_slice(line.as_bytes());
            text.extend_from_slice(if i % 2 == 0 { b"\n" } else { b"\r\n" });
        }
        text
    }

    fn npy_bytes(ty: NpyType, n: usize, announced: usize, bad: Option<usize>) -> Vec<u8> {
        let mut bytes = npy_header(ty, &[announced, 2]);
        for i in 0..n {
            let (x, y) = (i as f64 * 0.5 - 3.0, 1.0 / (i as f64 + 1.0));
            let x = if Some(i) == bad { f64::NAN } else { x };
            for v in [x, y] {
                match ty {
                    NpyType::F32 => bytes.extend_from_slice(&(v as f32).to_le_bytes()),
                    _ => bytes.extend_from_slice(&v.to_le_bytes()),
                }
            }
        }
        bytes
    }

    fn small(csv_bytes: usize) -> ChunkSizes {
        ChunkSizes {
            csv_bytes,
            npy_points: 37,
            npy_run: 5,
        }
    }

    /// Both sources, for CSV and `.npy`, give the points (and CSV fields as written) that the
    /// record readers give, whatever the chunk size and the number of threads; and the errors
    /// of the record readers, at the same line or point.
    #[test]
    fn both_sources_give_what_the_readers_give() {
        let mut cases = 0;
        for bad_at in [None, Some(3), Some(999)] {
            let text = csv_text(1000, bad_at);
            let path = scratch_file("points.csv", &text);
            let want: Result<Vec<Record>, String> = PointReader::new(&text[..])
                .map(|r| r.map(|r| (r.point, r.x_text, r.y_text)))
                .collect::<Result<_, _>>()
                .map_err(|e| e.to_string());
            for csv_bytes in [7, 100, 1 << 18] {
                for threads in [1, 3] {
                    let sources: [&dyn ChunkSource; 2] = [
                        &Sequential::csv(CsvBlocks::new(&text[..], "t", csv_bytes)),
                        &Positional::csv(CsvPointsFile::open(&path, csv_bytes).unwrap().unwrap()),
                    ];
                    for source in sources {
                        assert_eq!(drain(source, threads), want, "blocks of {csv_bytes}");
                        cases += 1;
                    }
                }
            }
            std::fs::remove_file(&path).unwrap();
        }
        for ty in [NpyType::F64, NpyType::F32] {
            for (n, announced, bad) in [(100, 100, None), (100, 100, Some(77)), (90, 100, None)] {
                let bytes = npy_bytes(ty, n, announced, bad);
                let path = scratch_file("points.npy", &bytes);
                let mut reader = NpyPoints::new(&bytes[..], "t").unwrap();
                let mut points = Vec::new();
                let want = reader
                    .read_block(1000, &mut points)
                    .map(|_| {
                        points
                            .iter()
                            .map(|&p| (p, String::new(), String::new()))
                            .collect()
                    })
                    .map_err(|e| e.to_string().replace("t: ", ""));
                for threads in [1, 3] {
                    let sources: [&dyn ChunkSource; 2] = [
                        &Sequential::npy(NpyPoints::new(&bytes[..], "t").unwrap(), small(1)),
                        &Positional::npy(NpyPointsFile::open(&path).unwrap(), small(1)),
                    ];
                    for source in sources {
                        assert_eq!(source.points(), Some(announced));
                        // The error names the file: compare what follows its name.
                        let got = drain(source, threads).map_err(|e| {
                            e.split_once(": ").map_or(e.clone(), |(_, m)| m.to_string())
                        });
                        assert_eq!(got, want, "{ty:?} {n} of {announced}, {bad:?}");
                        cases += 1;
                    }
                }
                std::fs::remove_file(&path).unwrap();
            }
        }
        assert_eq!(cases, 3 * 3 * 2 * 2 + 2 * 3 * 2 * 2);
    }

    /// A refusal to admit a chunk stops the taking; the bytes read follow the chunks.
    #[test]
    fn chunks_are_taken_while_admitted() {
        // Blocks read in order take at least 64 KiB at a time.
        let text = csv_text(30000, None);
        let path = scratch_file("admit.csv", &text);
        let sources: [&dyn ChunkSource; 2] = [
            &Sequential::csv(CsvBlocks::new(&text[..], "t", 1000)),
            &Positional::csv(CsvPointsFile::open(&path, 1000).unwrap().unwrap()),
        ];
        for source in sources {
            let mut chunk = Chunk::default();
            let mut admitted = |k: usize| k < 3;
            let mut taken = 0;
            while let Some((k, read)) = source.next_chunk(&mut chunk, &mut admitted) {
                read.unwrap();
                assert_eq!(k, taken);
                taken += 1;
            }
            assert_eq!(taken, 3);
            assert!(source.bytes_read() >= 3000, "{}", source.bytes_read());
            assert!(source.bytes_read() < text.len() as u64);
        }
        std::fs::remove_file(&path).unwrap();
    }

    /// Regular files are read by position, other files and CSV files whose first chunk holds
    /// no data in order; chunk buffers come back for reuse.
    #[test]
    fn open_chunks_reads_regular_files_by_position() {
        let csv = scratch_file("open.csv", &csv_text(10, None));
        let comments = scratch_file("comments.csv", "# comment\n".repeat(100).as_bytes());
        let npy = scratch_file("open.NPY", &npy_bytes(NpyType::F64, 3, 3, None));
        let sizes = small(16);
        assert!(!open_chunks(&csv, sizes).unwrap().in_order());
        assert!(open_chunks(&comments, sizes).unwrap().in_order());
        let source = open_chunks(&npy, sizes).unwrap();
        assert!(!source.in_order());
        assert_eq!(source.points(), Some(3));
        let e = open_chunks(csv.with_extension("missing"), sizes)
            .err()
            .unwrap();
        assert!(e.to_string().contains("missing"), "{e}");
        let source = open_chunks(&csv, ChunkSizes::default()).unwrap();
        let mut chunk = Chunk::with_buffer(Vec::with_capacity(1 << 20));
        assert!(source.next_chunk(&mut chunk, &mut |_| true).is_some());
        assert!(chunk.into_buffer().capacity() >= 1 << 20);
        for path in [csv, comments, npy] {
            std::fs::remove_file(path).unwrap();
        }
    }
}
