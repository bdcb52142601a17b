//! Streaming points through a computation: CSV or `.npy` in, CSV or `.npy` out, in bounded
//! batches that are parsed, computed and formatted on all threads and written in input order.
//! Memory depends on the batch size, not on the number of points.

use std::path::Path;
use std::time::{Duration, Instant};

use inrs::{CsvBlock, CsvBlocks, NpyType, ParsedBlock, Point, PointsError};
use rayon::prelude::*;

use crate::cli::error::CliError;
use crate::cli::output::Output;

mod spares;
use spares::Spares;

/// Bytes per CSV block (one parallel task).
const CSV_BLOCK_BYTES: usize = 1 << 18;
/// Points per parallel task for `.npy` input.
const NPY_TASK_POINTS: usize = 1 << 16;
/// Points a worker reads from a `.npy` file at a time: 64 KiB of float64 pairs, which stay in
/// its cache from the read to the computation (a task's megabyte at once cost the first
/// task of each worker 0.5-0.9 ms of page faults and every task another pass through memory).
#[cfg(unix)]
const NPY_READ_POINTS: usize = 1 << 12;
#[cfg(unix)]
thread_local! {
    /// Each worker's buffers for the `.npy` ranges it reads (the bytes, and the points for a
    /// computation that reads them from a slice), kept from task to task (fresh ones cost a
    /// page fault per 4 KiB and zero-filling).
    static NPY_SCRATCH: std::cell::RefCell<(Vec<u8>, Vec<Point>)> = Default::default();
}
thread_local! {
    /// Each worker's parsed CSV block (points and field positions), kept from task to task.
    static CSV_SCRATCH: std::cell::RefCell<ParsedBlock> = Default::default();
}
/// Progress is shown (on a terminal) once a run has taken this long.
const PROGRESS_AFTER: Duration = Duration::from_secs(2);

/// An output column: its CSV header and how one value is written as CSV text and in `.npy`.
pub(crate) struct Column<T> {
    /// The CSV header line (`x,y,location`).
    pub(crate) header: &'static str,
    /// A value to fill buffers with before they are computed.
    pub(crate) initial: T,
    /// Appends a value as CSV text.
    pub(crate) csv: fn(T, &mut Vec<u8>),
    /// The `.npy` element type, and how the bytes of a run of values are appended (one call
    /// per run: a call per value cost a tenth of a fast run).
    pub(crate) npy: (NpyType, AppendValues<T>),
}

/// Appends the bytes of a run of values.
pub(crate) type AppendValues<T> = fn(&[T], &mut Vec<u8>);

/// What a streamed command computes: one value per point. Any `Fn(&[Point], &mut [T])` is
/// one; a computation that can read its points one at a time (a locator's indexed query)
/// also takes them straight from a `.npy` file's bytes, without copying them into points.
pub(crate) trait PointsKernel<T>: Sync {
    /// Writes to `out[i]` the value of `points[i]`.
    fn compute(&self, points: &[Point], out: &mut [T]);

    /// Writes to `out[i]` the value of `points.point(i)`; by default through `scratch`.
    fn compute_encoded(
        &self,
        points: inrs::EncodedPoints<'_>,
        scratch: &mut Vec<Point>,
        out: &mut [T],
    ) {
        scratch.clear();
        points.append_to(scratch);
        self.compute(scratch, out);
    }
}

impl<T, F: Fn(&[Point], &mut [T]) + Sync> PointsKernel<T> for F {
    fn compute(&self, points: &[Point], out: &mut [T]) {
        self(points, out);
    }
}

/// A computation that reads its points one at a time by index (the library's
/// `*_indexed_into` queries), so that it runs on a slice of points and straight on a `.npy`
/// file's bytes alike: as a [`PointsKernel`] through [`ByIndex`].
pub(crate) trait IndexedQuery<T>: Sync {
    /// Writes to `out[i]` the value of `point(i)`.
    fn query_into(&self, point: impl Fn(usize) -> Point, out: &mut [T]);
}

/// An [`IndexedQuery`] as a streamed computation.
pub(crate) struct ByIndex<Q>(pub(crate) Q);

impl<T, Q: IndexedQuery<T>> PointsKernel<T> for ByIndex<Q> {
    fn compute(&self, points: &[Point], out: &mut [T]) {
        self.0.query_into(|i| points[i], out);
    }

    fn compute_encoded(&self, points: inrs::EncodedPoints<'_>, _: &mut Vec<Point>, out: &mut [T]) {
        self.0.query_into(|i| points.point(i), out);
    }
}

/// A points file: CSV (any other name) or `.npy` (float64 or float32, shape `(N, 2)`).
pub(crate) struct PointsInput {
    source: Source,
    path: String,
    total_bytes: u64,
}

enum Source {
    Csv(CsvBlocks<std::fs::File>),
    /// Read in order by the reading stage (a pipe, or not Unix).
    Npy(inrs::NpyPoints<std::io::BufReader<std::fs::File>>),
    /// A regular file, read by position on the workers (see [`inrs::NpyPointsFile`]); `next`
    /// is the first point not yet handed out.
    #[cfg(unix)]
    NpyFile {
        file: std::sync::Arc<inrs::NpyPointsFile>,
        next: usize,
    },
}

impl PointsInput {
    /// Opens `path`, by its extension.
    pub(crate) fn open(path: &Path) -> Result<Self, CliError> {
        let is_npy = has_extension(path, "npy");
        let source = if is_npy {
            open_npy(path)?
        } else {
            Source::Csv(
                inrs::open_points_blocks(path, CSV_BLOCK_BYTES)
                    .map_err(|e| input_error(path, e))?,
            )
        };
        Ok(Self {
            source,
            path: path.display().to_string(),
            total_bytes: std::fs::metadata(path).map_or(0, |m| m.len()),
        })
    }

    /// The number of points, exact for `.npy`, estimated from the size for CSV (at least 16
    /// bytes a line).
    pub(crate) fn estimated_points(&self) -> usize {
        match &self.source {
            Source::Npy(r) => r.len(),
            #[cfg(unix)]
            Source::NpyFile { file, .. } => file.len(),
            Source::Csv(_) => (self.total_bytes / 16) as usize,
        }
    }

    fn bytes_read(&self) -> u64 {
        match &self.source {
            Source::Npy(r) => r.bytes_read(),
            #[cfg(unix)]
            Source::NpyFile { file, next } => file.offset_of(*next),
            Source::Csv(r) => r.bytes_read(),
        }
    }
}

/// A `.npy` points file: read by position on the workers if it is a regular file (Unix), else in
/// order (a named pipe cannot be read by position).
fn open_npy(path: &Path) -> Result<Source, CliError> {
    #[cfg(unix)]
    if std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
        let file = inrs::NpyPointsFile::open(path).map_err(|e| input_error(path, e))?;
        return Ok(Source::NpyFile {
            file: std::sync::Arc::new(file),
            next: 0,
        });
    }
    Ok(Source::Npy(
        inrs::open_npy_points(path).map_err(|e| input_error(path, e))?,
    ))
}

fn has_extension(path: &Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// The message for a points-file error, naming the file once.
fn input_error(path: &Path, e: PointsError) -> CliError {
    match e {
        PointsError::Io { .. } | PointsError::Npy { .. } => CliError::Message(e.to_string()),
        other => CliError::Message(format!("{}: {other}", path.display())),
    }
}

/// Streams `input` through `compute` (one value per point, in order) and writes `x,y,value`
/// CSV rows (the coordinates echoed as written), or, when `output` ends in `.npy`, the values
/// as a 1-D `.npy` array.
///
/// Three stages overlap: a thread reads blocks, the calling thread parses, computes and
/// formats groups of them on rayon's pool, and a thread writes the results in input order.
/// The channels between them are bounded, so memory does not grow with the input; the byte
/// buffers (blocks read, results formatted) go back to two bounded pools once used.
pub(crate) fn stream_points<T: Copy + Send + Sync, K: PointsKernel<T>>(
    input: PointsInput,
    output: Option<&Path>,
    column: &Column<T>,
    kernel: &K,
) -> Result<(), CliError> {
    let format = if output.is_some_and(|p| has_extension(p, "npy")) {
        Format::Npy
    } else {
        Format::Csv
    };
    let group = 2 * rayon::current_num_threads().max(1);
    let path = Path::new(&input.path).to_path_buf();
    let total = input.total_bytes;
    let read = std::sync::atomic::AtomicU64::new(0);
    // Two pools, so that each converges to its buffers' size: the blocks read (a group being
    // read, one computed) and the results formatted (one group computed, two queued, one
    // being written).
    let (texts, results) = (Spares::new(2 * group), Spares::new(4 * group));
    let (texts, results) = (&texts, &results);
    std::thread::scope(|scope| {
        let (chunks_tx, chunks) =
            std::sync::mpsc::sync_channel::<Result<Chunk, PointsError>>(group);
        let read = &read;
        scope.spawn(move || read_chunks(input, &chunks_tx, read, texts));
        let (groups_tx, groups) = std::sync::mpsc::sync_channel::<Written>(2);
        let writer = scope.spawn(move || write_groups(output, format, column, groups, results));
        let mut progress = Progress::new(total);
        let mut failure = None;
        'outer: loop {
            // A group: the next chunk (waiting for it), then as many more as are ready.
            let mut next: Vec<Chunk> = Vec::with_capacity(group);
            for received in chunks.iter() {
                match received {
                    Ok(c) => next.push(c),
                    Err(e) => {
                        failure = Some(e);
                        break;
                    }
                }
                if next.len() >= group {
                    break;
                }
            }
            if next.is_empty() {
                break;
            }
            let parts: Vec<Result<(Vec<u8>, usize), PointsError>> = next
                .par_iter()
                .map(|c| match c {
                    Chunk::Csv(b) => csv_block(b, format, column, kernel, results.take()),
                    Chunk::Points(p) => Ok(npy_points(p, format, column, kernel, results.take())),
                    #[cfg(unix)]
                    Chunk::Range { file, first, n } => {
                        NPY_SCRATCH.with_borrow_mut(|(bytes, points)| {
                            let mut values = vec![column.initial; *n];
                            let mut out = results.take();
                            for (k, values) in values.chunks_mut(NPY_READ_POINTS).enumerate() {
                                let at = first + k * NPY_READ_POINTS;
                                let encoded = file.read_encoded(at, values.len(), bytes)?;
                                kernel.compute_encoded(encoded, points, values);
                                let point = |i| encoded.point(i);
                                format_values(values, format, column, point, &mut out);
                            }
                            Ok((out, *n))
                        })
                    }
                })
                .collect();
            for chunk in next {
                if let Chunk::Csv(block) = chunk {
                    texts.give(block.text);
                }
            }
            let mut done = Vec::with_capacity(parts.len());
            for part in parts {
                match part {
                    Ok(p) => done.push(p),
                    Err(e) => {
                        failure = Some(e);
                        break;
                    }
                }
            }
            if groups_tx.send(Written::Group(done)).is_err() {
                break 'outer; // the writer failed: its error is reported below
            }
            progress.update(read.load(std::sync::atomic::Ordering::Relaxed));
            if failure.is_some() {
                break;
            }
        }
        if failure.is_none() {
            // Everything read was written: the output may be committed.
            let _ = groups_tx.send(Written::End);
        }
        drop(groups_tx);
        drop(chunks);
        progress.finish();
        let written = writer
            .join()
            .unwrap_or_else(|_| Err(CliError::Message("the writer thread failed".into())));
        match failure {
            // The input's error comes first: the writer only saw what came before it.
            Some(e) => Err(input_error(&path, e)),
            None => written,
        }
    })
}

/// What the writing stage receives: a group of formatted chunks (bytes and point count), or
/// the end of a complete run. A channel closed without [`Written::End`] means the run failed:
/// the output is dropped (a file output is removed).
enum Written {
    Group(Vec<(Vec<u8>, usize)>),
    End,
}

/// One unit of parallel work: a block of CSV lines, or points read from `.npy`.
enum Chunk {
    Csv(CsvBlock),
    Points(Vec<Point>),
    /// Points `first..first + n` of a `.npy` file, read by the worker.
    #[cfg(unix)]
    Range {
        file: std::sync::Arc<inrs::NpyPointsFile>,
        first: usize,
        n: usize,
    },
}

/// The reading stage: sends the input's chunks (or its first error) until the input ends or
/// the receiver hangs up; counts the bytes read in `read`; reads CSV into buffers from
/// `spares`.
fn read_chunks(
    mut input: PointsInput,
    tx: &std::sync::mpsc::SyncSender<Result<Chunk, PointsError>>,
    read: &std::sync::atomic::AtomicU64,
    spares: &Spares,
) {
    loop {
        let next = match &mut input.source {
            Source::Csv(blocks) => {
                blocks.recycle(spares.take());
                blocks.next_block().map(|b| b.map(Chunk::Csv))
            }
            Source::Npy(reader) => {
                let mut pts = Vec::new();
                reader
                    .read_block(NPY_TASK_POINTS, &mut pts)
                    .map(|n| (n > 0).then_some(Chunk::Points(pts)))
            }
            #[cfg(unix)]
            Source::NpyFile { file, next } => {
                let (first, n) = (*next, NPY_TASK_POINTS.min(file.len() - *next));
                *next += n;
                Ok((n > 0).then(|| Chunk::Range {
                    file: std::sync::Arc::clone(file),
                    first,
                    n,
                }))
            }
        };
        read.store(input.bytes_read(), std::sync::atomic::Ordering::Relaxed);
        let stop = !matches!(next, Ok(Some(_)));
        let message = match next {
            Ok(Some(c)) => Ok(c),
            Ok(None) => return,
            Err(e) => Err(e),
        };
        if tx.send(message).is_err() || stop {
            return;
        }
    }
}

/// The writing stage: opens the output, writes the header and every group in order (giving
/// the buffers back to `spares`), and on [`Written::End`] the final `.npy` header with the
/// count, then commits the output.
fn write_groups<T>(
    output: Option<&Path>,
    format: Format,
    column: &Column<T>,
    groups: std::sync::mpsc::Receiver<Written>,
    spares: &Spares,
) -> Result<(), CliError> {
    let mut out = Output::create(output)?;
    if format == Format::Npy {
        out.write_bytes(&inrs::npy_header(column.npy.0, &[0]))?;
    } else {
        out.write_str(column.header)?;
        out.write_str("\n")?;
    }
    let mut written = 0usize;
    loop {
        match groups.recv() {
            Ok(Written::Group(group)) => {
                for (bytes, n) in group {
                    out.write_bytes(&bytes)?;
                    written += n;
                    spares.give(bytes);
                }
            }
            Ok(Written::End) => break,
            // The run failed: its error is reported by the caller; the output is dropped.
            Err(_) => return Ok(()),
        }
    }
    if format == Format::Npy {
        out.rewrite_start(&inrs::npy_header(column.npy.0, &[written]))?;
    }
    out.finish()
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Format {
    Csv,
    Npy,
}

/// Parses, computes and formats one CSV block into `bytes` (empty); returns them and the
/// number of points.
fn csv_block<T: Copy>(
    block: &CsvBlock,
    format: Format,
    column: &Column<T>,
    kernel: &impl PointsKernel<T>,
    mut bytes: Vec<u8>,
) -> Result<(Vec<u8>, usize), PointsError> {
    CSV_SCRATCH.with_borrow_mut(|parsed| {
        block.parse_into(parsed)?;
        let mut values = vec![column.initial; parsed.points.len()];
        kernel.compute(&parsed.points, &mut values);
        if format == Format::Npy {
            npy_values(&values, column, &mut bytes);
            return Ok((bytes, values.len()));
        }
        bytes.reserve(block.text.len() + 16 * values.len());
        for (f, &v) in parsed.fields.iter().zip(&values) {
            bytes.extend_from_slice(block.field(f[0], f[1]));
            bytes.push(b',');
            bytes.extend_from_slice(block.field(f[2], f[3]));
            bytes.push(b',');
            (column.csv)(v, &mut bytes);
            bytes.push(b'\n');
        }
        Ok((bytes, values.len()))
    })
}

/// Computes and formats points read from `.npy` into `bytes` (empty); returns them and the
/// number of points.
fn npy_points<T: Copy>(
    points: &[Point],
    format: Format,
    column: &Column<T>,
    kernel: &impl PointsKernel<T>,
    mut bytes: Vec<u8>,
) -> (Vec<u8>, usize) {
    let mut values = vec![column.initial; points.len()];
    kernel.compute(points, &mut values);
    format_values(&values, format, column, |i| points[i], &mut bytes);
    (bytes, points.len())
}

/// Appends to `bytes` the values of points read from `.npy`: as `.npy` data, or as CSV rows
/// `x,y,value` with the coordinates `point(i)` in shortest round-trip form.
fn format_values<T: Copy>(
    values: &[T],
    format: Format,
    column: &Column<T>,
    point: impl Fn(usize) -> Point,
    bytes: &mut Vec<u8>,
) {
    if format == Format::Npy {
        return npy_values(values, column, bytes);
    }
    bytes.reserve(values.len() * 48);
    let mut digits = ryu::Buffer::new();
    for (i, &v) in values.iter().enumerate() {
        let p = point(i);
        bytes.extend_from_slice(digits.format_finite(p.x).as_bytes());
        bytes.push(b',');
        bytes.extend_from_slice(digits.format_finite(p.y).as_bytes());
        bytes.push(b',');
        (column.csv)(v, bytes);
        bytes.push(b'\n');
    }
}

/// Appends the values to `bytes` as `.npy` data.
fn npy_values<T: Copy>(values: &[T], column: &Column<T>, bytes: &mut Vec<u8>) {
    bytes.reserve(values.len() * column.npy.0.size());
    (column.npy.1)(values, bytes);
}

/// Appends `v` in shortest round-trip form (`ryu`); `nan`, `inf` and `-inf` for the
/// non-finite values.
pub(crate) fn write_f64(v: f64, out: &mut Vec<u8>) {
    if v.is_nan() {
        out.extend_from_slice(b"nan");
    } else if v.is_infinite() {
        out.extend_from_slice(if v > 0.0 { b"inf" } else { b"-inf" });
    } else {
        let mut digits = ryu::Buffer::new();
        out.extend_from_slice(digits.format_finite(v).as_bytes());
    }
}

/// A progress bar on standard error, shown only on a terminal and only once the run has
/// lasted [`PROGRESS_AFTER`].
struct Progress {
    start: Instant,
    total: u64,
    bar: Option<indicatif::ProgressBar>,
    enabled: bool,
}

impl Progress {
    fn new(total: u64) -> Self {
        use std::io::IsTerminal;
        Self {
            start: Instant::now(),
            total,
            bar: None,
            enabled: total > 0 && std::io::stderr().is_terminal(),
        }
    }

    fn update(&mut self, done: u64) {
        if !self.enabled {
            return;
        }
        if self.bar.is_none() && self.start.elapsed() >= PROGRESS_AFTER {
            let bar = indicatif::ProgressBar::new(self.total);
            if let Ok(style) = indicatif::ProgressStyle::with_template(
                "{elapsed_precise} [{bar:40}] {bytes}/{total_bytes} ({bytes_per_sec}, {eta} left)",
            ) {
                bar.set_style(style.progress_chars("=> "));
            }
            self.bar = Some(bar);
        }
        if let Some(bar) = &self.bar {
            bar.set_position(done.min(self.total));
        }
    }

    fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}
