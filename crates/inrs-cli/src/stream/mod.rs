//! Streaming points through a computation: CSV or `.npy` in, CSV or `.npy` out, in bounded
//! batches that are parsed, computed and formatted on all threads and written in input order.
//! Memory depends on the batch size, not on the number of points.

use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};
use std::time::{Duration, Instant};

use inrs::{CsvBlock, CsvBlocks, NpyType, ParsedBlock, Point, PointsError};

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
#[cfg(unix)]
thread_local! {
    /// Each worker's CSV block read by position, its buffer kept from task to task.
    static CSV_BLOCK: std::cell::RefCell<CsvBlock> = Default::default();
}
/// Progress is shown (on a terminal) once a run has taken this long.
const PROGRESS_AFTER: Duration = Duration::from_secs(2);

/// An output column: its CSV header and how its values are written as CSV text and in
/// `.npy`. Implemented by a unit type per column, so that writing a value compiles into the
/// streaming loop (a function pointer per value: 2% more instructions in a CSV run).
pub(crate) trait Column<T>: Sync {
    /// The CSV header line (`x,y,location`).
    fn header(&self) -> &'static str;
    /// A value to fill buffers with before they are computed.
    fn initial(&self) -> T;
    /// Appends a value as CSV text.
    fn csv(&self, value: T, out: &mut Vec<u8>);
    /// The `.npy` element type.
    fn npy_type(&self) -> NpyType;
    /// Appends the `.npy` bytes of a run of values (one call per run: a call per value cost a
    /// tenth of a fast run).
    fn npy(&self, values: &[T], out: &mut Vec<u8>);
}

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
    /// Read in order by the reading stage (a pipe, a file that opens with a block of comments,
    /// or not Unix).
    Csv(CsvBlocks<std::fs::File>),
    /// A regular file, read by position on the workers (see [`inrs::CsvPointsFile`]); `next`
    /// is the first block not yet handed out.
    #[cfg(unix)]
    CsvFile {
        file: std::sync::Arc<inrs::CsvPointsFile>,
        next: usize,
    },
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
            open_csv(path)?
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
            #[cfg(unix)]
            Source::CsvFile { .. } => (self.total_bytes / 16) as usize,
        }
    }

    fn bytes_read(&self) -> u64 {
        match &self.source {
            Source::Npy(r) => r.bytes_read(),
            #[cfg(unix)]
            Source::NpyFile { file, next } => file.offset_of(*next),
            Source::Csv(r) => r.bytes_read(),
            #[cfg(unix)]
            Source::CsvFile { file, next } => file.offset_of_block(*next),
        }
    }
}

/// A CSV points file: read by position on the workers if it is a regular file with data in its
/// first block (Unix), else in order.
fn open_csv(path: &Path) -> Result<Source, CliError> {
    #[cfg(unix)]
    if let Some(file) =
        inrs::CsvPointsFile::open(path, CSV_BLOCK_BYTES).map_err(|e| input_error(path, e))?
    {
        return Ok(Source::CsvFile {
            file: std::sync::Arc::new(file),
            next: 0,
        });
    }
    Ok(Source::Csv(
        inrs::open_points_blocks(path, CSV_BLOCK_BYTES).map_err(|e| input_error(path, e))?,
    ))
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
/// Two stages overlap: a thread reads chunks and numbers them, and workers ([`worker_count`])
/// each take the next chunk read, parse, compute and format it, and write the results in
/// input order ([`InOrder`]: a chunk's results wait only if an earlier chunk's are not yet
/// written, and the worker that writes that one writes them too). The calling thread only
/// updates the progress bar. No stage waits for a whole group of chunks: a worker that
/// finishes takes the next chunk at once. Memory is bounded by
/// permits: a chunk is read only when one of [`chunks_in_flight`] permits is free, and its
/// permit comes back when its result is written. The byte buffers (chunks read, results
/// formatted) go back to two bounded pools once used.
pub(crate) fn stream_points<T: Copy + Send + Sync, C: Column<T>, K: PointsKernel<T>>(
    input: PointsInput,
    output: Option<&Path>,
    column: &C,
    kernel: &K,
) -> Result<(), CliError> {
    let format = if output.is_some_and(|p| has_extension(p, "npy")) {
        Format::Npy
    } else {
        Format::Csv
    };
    let workers = worker_count();
    let in_flight = chunks_in_flight(workers);
    let path = Path::new(&input.path).to_path_buf();
    let total = input.total_bytes;
    let read = AtomicU64::new(0);
    let stop = AtomicBool::new(false);
    let (texts, results) = (Spares::new(in_flight), Spares::new(in_flight));
    let (chunks_tx, chunks_rx) = sync_channel::<Numbered<Chunk>>(in_flight);
    let chunks_rx = Mutex::new(chunks_rx);
    let (permits_tx, permits_rx) = sync_channel::<()>(in_flight);
    for _ in 0..in_flight {
        // The channel holds them all: this never blocks.
        let _ = permits_tx.send(());
    }
    let stage = Stage {
        format,
        column,
        kernel,
        texts: &texts,
        results: &results,
    };
    let in_order = InOrder::start(output, &stage)?;
    let (workers_ok, sent) = std::thread::scope(|scope| {
        let (read, stop, texts) = (&read, &stop, &texts);
        let reader =
            scope.spawn(move || read_chunks(input, &chunks_tx, &permits_rx, read, stop, texts));
        // Each worker holds a sender; the channel closes when the last one has finished.
        let (alive_tx, alive_rx) = std::sync::mpsc::channel::<()>();
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                let alive = alive_tx.clone();
                let (chunks_rx, stage, in_order) = (&chunks_rx, &stage, &in_order);
                let permits = permits_tx.clone();
                scope.spawn(move || {
                    // A worker that panics stops the reader, so that the others finish.
                    let _stopping = StopOnPanic(stop, &permits);
                    work(chunks_rx, stage, in_order, &permits, stop);
                    drop(alive);
                })
            })
            .collect();
        drop(alive_tx);
        let mut progress = Progress::new(total);
        while let Err(std::sync::mpsc::RecvTimeoutError::Timeout) =
            alive_rx.recv_timeout(Duration::from_millis(100))
        {
            progress.update(read.load(Ordering::Relaxed));
        }
        progress.finish();
        // Whatever happened, the reader stops at its next permit.
        stop.store(true, Ordering::Relaxed);
        drop(permits_tx);
        let workers_ok = handles.into_iter().all(|h| h.join().is_ok());
        (workers_ok, reader.join())
    });
    let (written, count) = match in_order.finish(&stage) {
        Ok(w) => w,
        Err(WriteFailure::Input(e)) => return Err(input_error(&path, e)),
        Err(WriteFailure::Output(e)) => return Err(e),
    };
    match sent {
        Ok(sent) if workers_ok && sent == count => written.finish(),
        // A chunk never arrived: a stage failed; the output is dropped (removed).
        _ => Err(CliError::Message("a streaming thread failed".into())),
    }
}

/// How many workers a stream runs: `RAYON_NUM_THREADS` if it is set to a positive number (the
/// variable the library's parallel parts read), else one per core. (Asking rayon's pool would
/// start it: two more threads that spin for nothing beside the workers.)
fn worker_count() -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    workers_for(std::env::var("RAYON_NUM_THREADS").ok().as_deref(), cores)
}

/// [`worker_count`] for the variable's value `setting` on a machine of `cores` cores.
fn workers_for(setting: Option<&str>, cores: usize) -> usize {
    setting
        .and_then(|s| s.trim().parse::<usize>().ok())
        .filter(|&n| n > 0)
        .unwrap_or(cores)
        .max(1)
}

/// How many chunks may be read and not yet written: enough for every worker to have one in
/// hand, one queued and two results waiting for an earlier one to be written.
fn chunks_in_flight(workers: usize) -> usize {
    4 * workers
}

/// A chunk's place in the input, and the chunk (or the error reading or computing it).
type Numbered<C> = (usize, Result<C, PointsError>);

/// A chunk's results, formatted, and how many points it held.
type Formatted = (Vec<u8>, usize);

/// What a worker needs to turn a chunk into formatted results.
struct Stage<'a, C, K> {
    format: Format,
    column: &'a C,
    kernel: &'a K,
    /// Where CSV text buffers go back to once parsed.
    texts: &'a Spares,
    /// Where result buffers come from.
    results: &'a Spares,
}

/// A worker: takes the next chunk read, computes and formats it, and hands the result to the
/// ordered writing (writing it, and any that came before it and waited, if it is next), until
/// the chunks run out or a chunk failed.
fn work<T: Copy, C: Column<T>, K: PointsKernel<T>>(
    chunks: &Mutex<Receiver<Numbered<Chunk>>>,
    stage: &Stage<'_, C, K>,
    in_order: &InOrder,
    permits: &SyncSender<()>,
    stop: &AtomicBool,
) {
    loop {
        // The lock is held only while waiting for the next chunk.
        let next = match chunks.lock() {
            Ok(rx) => rx.recv(),
            Err(_) => return,
        };
        let Ok((seq, chunk)) = next else {
            return; // the reader has finished and every chunk is taken
        };
        let result = chunk.and_then(|c| compute_chunk(c, stage));
        if !in_order.hand_in(seq, result, stage, permits) {
            // Stop the reader (waiting for a permit, perhaps) and the other workers.
            stop.store(true, Ordering::Relaxed);
            let _ = permits.try_send(());
            return;
        }
    }
}

/// Parses (CSV), computes and formats one chunk.
fn compute_chunk<T: Copy, C: Column<T>, K: PointsKernel<T>>(
    chunk: Chunk,
    stage: &Stage<'_, C, K>,
) -> Result<Formatted, PointsError> {
    let Stage {
        format,
        column,
        kernel,
        texts,
        results,
    } = *stage;
    match chunk {
        Chunk::Csv(block) => {
            let parse = |parsed: &mut ParsedBlock| block.parse_into(parsed);
            let result = csv_block(&block, parse, format, column, kernel, results.take());
            texts.give(block.text);
            result
        }
        #[cfg(unix)]
        Chunk::CsvAt { file, block: k } => CSV_BLOCK.with_borrow_mut(|block| {
            file.read_block(k, block)?;
            let parse = |parsed: &mut ParsedBlock| file.parse_block(k, block, parsed);
            csv_block(block, parse, format, column, kernel, results.take())
        }),
        Chunk::Points(p) => Ok(npy_points(&p, format, column, kernel, results.take())),
        #[cfg(unix)]
        Chunk::Range { file, first, n } => NPY_SCRATCH.with_borrow_mut(|(bytes, points)| {
            let mut values = vec![column.initial(); n];
            let mut out = results.take();
            for (k, values) in values.chunks_mut(NPY_READ_POINTS).enumerate() {
                let at = first + k * NPY_READ_POINTS;
                let encoded = file.read_encoded(at, values.len(), bytes)?;
                kernel.compute_encoded(encoded, points, values);
                let point = |i| encoded.point(i);
                format_values(values, format, column, point, &mut out);
            }
            Ok((out, n))
        }),
    }
}

/// Why the writing stage stopped early: a chunk's input was bad (reported with the input's
/// name), or the output failed.
enum WriteFailure {
    Input(PointsError),
    Output(CliError),
}

impl From<CliError> for WriteFailure {
    fn from(e: CliError) -> Self {
        Self::Output(e)
    }
}

/// Stops the reading stage if dropped while its thread panics (see [`work`]'s own stop).
struct StopOnPanic<'a>(&'a AtomicBool, &'a SyncSender<()>);

impl Drop for StopOnPanic<'_> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.store(true, Ordering::Relaxed);
            let _ = self.1.try_send(());
        }
    }
}

/// The ordered writing stage, run by the workers: a chunk's results are written by the worker
/// that computed them if every earlier chunk's are written, else they wait for the worker that
/// writes the chunk before them (which then writes them too). The bytes are mostly written
/// from the cache of the core that formatted them, and no thread waits to write.
struct InOrder {
    state: Mutex<InOrderState>,
    /// The output, used by the one worker that is writing (see [`InOrderState::writing`]).
    out: Mutex<Output>,
}

struct InOrderState {
    /// Results that came before an earlier chunk's: at most the chunks in flight.
    waiting: std::collections::BTreeMap<usize, Result<Formatted, PointsError>>,
    /// The next chunk to write.
    next: usize,
    /// Points written.
    points: usize,
    /// Whether a worker is writing (it writes every waiting result that comes next).
    writing: bool,
    /// The first failure, in input order: nothing is written after it.
    failure: Option<WriteFailure>,
}

impl InOrder {
    /// Opens the output and writes the header (for `.npy`, one without the count yet).
    fn start<T, C: Column<T>, K>(
        output: Option<&Path>,
        stage: &Stage<'_, C, K>,
    ) -> Result<Self, CliError> {
        let column = stage.column;
        let mut out = Output::create(output)?;
        if stage.format == Format::Npy {
            out.write_bytes(&inrs::npy_header(column.npy_type(), &[0]))?;
        } else {
            out.write_str(column.header())?;
            out.write_str("\n")?;
        }
        Ok(Self {
            state: Mutex::new(InOrderState {
                waiting: std::collections::BTreeMap::new(),
                next: 0,
                points: 0,
                writing: false,
                failure: None,
            }),
            out: Mutex::new(out),
        })
    }

    /// Hands in chunk `seq`'s results; writes them and the waiting ones after them if they
    /// come next and no other worker is writing. Gives each written chunk's permit back, and
    /// its buffer to the pool. False once a chunk (this or an earlier one) has failed.
    fn hand_in<C, K>(
        &self,
        seq: usize,
        result: Result<Formatted, PointsError>,
        stage: &Stage<'_, C, K>,
        permits: &SyncSender<()>,
    ) -> bool {
        let lock = || self.state.lock().unwrap_or_else(|e| e.into_inner());
        let mut state = lock();
        if state.failure.is_some() {
            return false;
        }
        state.waiting.insert(seq, result);
        if state.writing {
            return true; // the writing worker takes it when its turn comes
        }
        state.writing = true;
        loop {
            let next = state.next;
            let Some(result) = state.waiting.remove(&next) else {
                state.writing = false;
                return true;
            };
            drop(state);
            let written = result.map_err(WriteFailure::Input).and_then(|(bytes, n)| {
                let mut out = self.out.lock().unwrap_or_else(|e| e.into_inner());
                out.write_bytes(&bytes)?;
                stage.results.give(bytes);
                Ok(n)
            });
            state = lock();
            match written {
                Ok(n) => {
                    state.points += n;
                    state.next += 1;
                    // The reader may have stopped already: a permit nobody takes is harmless.
                    let _ = permits.try_send(());
                }
                Err(failure) => {
                    state.failure = Some(failure);
                    state.writing = false;
                    return false;
                }
            }
        }
    }

    /// Once every worker has finished: the output (for `.npy`, with the final header), to be
    /// committed once the run is known complete, and the number of chunks written; or the
    /// first failure.
    fn finish<T, C: Column<T>, K>(
        self,
        stage: &Stage<'_, C, K>,
    ) -> Result<(Output, usize), WriteFailure> {
        let state = self.state.into_inner().unwrap_or_else(|e| e.into_inner());
        if let Some(failure) = state.failure {
            return Err(failure);
        }
        let mut out = self.out.into_inner().unwrap_or_else(|e| e.into_inner());
        if stage.format == Format::Npy {
            out.rewrite_start(&inrs::npy_header(stage.column.npy_type(), &[state.points]))?;
        }
        Ok((out, state.next))
    }
}

/// One unit of parallel work: a block of CSV lines, or points read from `.npy`.
enum Chunk {
    Csv(CsvBlock),
    /// Block `block` of a CSV file, read by the worker.
    #[cfg(unix)]
    CsvAt {
        file: std::sync::Arc<inrs::CsvPointsFile>,
        block: usize,
    },
    Points(Vec<Point>),
    /// Points `first..first + n` of a `.npy` file, read by the worker.
    #[cfg(unix)]
    Range {
        file: std::sync::Arc<inrs::NpyPointsFile>,
        first: usize,
        n: usize,
    },
}

/// The reading stage: numbers and sends the input's chunks (or its first error, as the last
/// chunk), each once a permit is free, until the input ends, `stop` is set or the permits
/// are gone; counts the bytes read in `read`; reads CSV into buffers from `spares`. Returns
/// how many chunks it sent.
fn read_chunks(
    mut input: PointsInput,
    tx: &SyncSender<Numbered<Chunk>>,
    permits: &Receiver<()>,
    read: &AtomicU64,
    stop: &AtomicBool,
    spares: &Spares,
) -> usize {
    let mut sent = 0;
    loop {
        if permits.recv().is_err() || stop.load(Ordering::Relaxed) {
            return sent;
        }
        let next = match &mut input.source {
            Source::Csv(blocks) => {
                blocks.recycle(spares.take());
                blocks.next_block().map(|b| b.map(Chunk::Csv))
            }
            #[cfg(unix)]
            Source::CsvFile { file, next } => {
                let block = *next;
                *next += 1;
                Ok((block < file.blocks()).then(|| Chunk::CsvAt {
                    file: std::sync::Arc::clone(file),
                    block,
                }))
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
        read.store(input.bytes_read(), Ordering::Relaxed);
        let (message, last) = match next {
            Ok(Some(c)) => (Ok(c), false),
            Ok(None) => return sent,
            Err(e) => (Err(e), true),
        };
        if tx.send((sent, message)).is_err() {
            return sent;
        }
        sent += 1;
        if last {
            return sent;
        }
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Format {
    Csv,
    Npy,
}

/// Parses (with `parse`), computes and formats one CSV block into `bytes` (empty); returns
/// them and the number of points.
fn csv_block<T: Copy, C: Column<T>>(
    block: &CsvBlock,
    parse: impl FnOnce(&mut ParsedBlock) -> Result<(), PointsError>,
    format: Format,
    column: &C,
    kernel: &impl PointsKernel<T>,
    mut bytes: Vec<u8>,
) -> Result<(Vec<u8>, usize), PointsError> {
    CSV_SCRATCH.with_borrow_mut(|parsed| {
        parse(parsed)?;
        let mut values = vec![column.initial(); parsed.points.len()];
        kernel.compute(&parsed.points, &mut values);
        if format == Format::Npy {
            npy_values(&values, column, &mut bytes);
            return Ok((bytes, values.len()));
        }
        bytes.reserve(block.text.len() + 16 * values.len());
        for (f, &v) in parsed.fields.iter().zip(&values) {
            if block.field(f[1], f[2]) == b"," {
                // `x,y` as written, in one copy.
                bytes.extend_from_slice(block.field(f[0], f[3]));
            } else {
                bytes.extend_from_slice(block.field(f[0], f[1]));
                bytes.push(b',');
                bytes.extend_from_slice(block.field(f[2], f[3]));
            }
            bytes.push(b',');
            column.csv(v, &mut bytes);
            bytes.push(b'\n');
        }
        Ok((bytes, values.len()))
    })
}

/// Computes and formats points read from `.npy` into `bytes` (empty); returns them and the
/// number of points.
fn npy_points<T: Copy, C: Column<T>>(
    points: &[Point],
    format: Format,
    column: &C,
    kernel: &impl PointsKernel<T>,
    mut bytes: Vec<u8>,
) -> (Vec<u8>, usize) {
    let mut values = vec![column.initial(); points.len()];
    kernel.compute(points, &mut values);
    format_values(&values, format, column, |i| points[i], &mut bytes);
    (bytes, points.len())
}

/// Appends to `bytes` the values of points read from `.npy`: as `.npy` data, or as CSV rows
/// `x,y,value` with the coordinates `point(i)` in shortest round-trip form.
fn format_values<T: Copy, C: Column<T>>(
    values: &[T],
    format: Format,
    column: &C,
    point: impl Fn(usize) -> Point,
    bytes: &mut Vec<u8>,
) {
    if format == Format::Npy {
        return npy_values(values, column, bytes);
    }
    bytes.reserve(values.len() * 48);
    let mut digits = zmij::Buffer::new();
    for (i, &v) in values.iter().enumerate() {
        let p = point(i);
        bytes.extend_from_slice(digits.format_finite(p.x).as_bytes());
        bytes.push(b',');
        bytes.extend_from_slice(digits.format_finite(p.y).as_bytes());
        bytes.push(b',');
        column.csv(v, bytes);
        bytes.push(b'\n');
    }
}

/// Appends the values to `bytes` as `.npy` data.
fn npy_values<T: Copy, C: Column<T>>(values: &[T], column: &C, bytes: &mut Vec<u8>) {
    bytes.reserve(values.len() * column.npy_type().size());
    column.npy(values, bytes);
}

/// Appends `v` in shortest round-trip form (`zmij`); `nan`, `inf` and `-inf` for the
/// non-finite values.
pub(crate) fn write_f64(v: f64, out: &mut Vec<u8>) {
    if v.is_nan() {
        out.extend_from_slice(b"nan");
    } else if v.is_infinite() {
        out.extend_from_slice(if v > 0.0 { b"inf" } else { b"-inf" });
    } else {
        let mut digits = zmij::Buffer::new();
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
    /// How long a run goes before the bar appears.
    after: Duration,
    /// Where the bar is drawn (standard error; hidden in tests).
    target: fn() -> indicatif::ProgressDrawTarget,
}

impl Progress {
    fn new(total: u64) -> Self {
        use std::io::IsTerminal;
        let enabled = total > 0 && std::io::stderr().is_terminal();
        Self::shown_after(
            total,
            PROGRESS_AFTER,
            enabled,
            indicatif::ProgressDrawTarget::stderr,
        )
    }

    /// A bar over `total` bytes that appears once `after` has passed, if `enabled`.
    fn shown_after(
        total: u64,
        after: Duration,
        enabled: bool,
        target: fn() -> indicatif::ProgressDrawTarget,
    ) -> Self {
        Self {
            start: Instant::now(),
            total,
            bar: None,
            enabled,
            after,
            target,
        }
    }

    /// Reports `done` bytes read.
    fn update(&mut self, done: u64) {
        if !self.enabled {
            return;
        }
        if self.bar.is_none() && self.start.elapsed() >= self.after {
            // Started where the run is, so that its clock and rate count the whole run.
            let bar = indicatif::ProgressBar::with_draw_target(Some(self.total), (self.target)())
                .with_position(done.min(self.total))
                .with_elapsed(self.start.elapsed());
            if let Ok(style) = indicatif::ProgressStyle::with_template(
                "{elapsed_precise} [{bar:40}] {bytes}/{total_bytes} {msg}",
            ) {
                bar.set_style(style.progress_chars("=> "));
            }
            self.bar = Some(bar);
        }
        if let Some(bar) = &self.bar {
            let done = done.min(self.total);
            bar.set_position(done);
            bar.set_message(rate_and_time_left(done, self.total, self.start.elapsed()));
        }
    }

    /// Removes the bar, if shown.
    fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}

/// `(12.3 MiB/s, 4 s left)`: the average rate of the whole run so far and the time the rest
/// takes at that rate (the bar's own estimate follows the bursts in which chunks are written).
fn rate_and_time_left(done: u64, total: u64, elapsed: Duration) -> String {
    let seconds = elapsed.as_secs_f64();
    if done == 0 || seconds <= 0.0 {
        return String::new();
    }
    let rate = done as f64 / seconds;
    let left = (total - done.min(total)) as f64 / rate;
    format!("({:.1} MiB/s, {left:.0} s left)", rate / (1 << 20) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use indicatif::ProgressDrawTarget;

    /// The bar appears only when enabled (standard error a terminal) and once the run has
    /// lasted long enough; it follows the bytes read, never past the total, and goes away at
    /// the end.
    #[test]
    fn the_progress_bar_appears_late_and_only_on_a_terminal() {
        let hour = Duration::from_secs(3600);
        let mut quiet =
            Progress::shown_after(100, Duration::ZERO, false, ProgressDrawTarget::hidden);
        quiet.update(50);
        assert!(quiet.bar.is_none(), "not a terminal");
        let mut early = Progress::shown_after(100, hour, true, ProgressDrawTarget::hidden);
        early.update(50);
        assert!(early.bar.is_none(), "a short run");
        let mut long = Progress::shown_after(100, Duration::ZERO, true, ProgressDrawTarget::hidden);
        long.update(50);
        assert_eq!(
            long.bar.as_ref().map(indicatif::ProgressBar::position),
            Some(50)
        );
        long.update(500);
        assert_eq!(
            long.bar.as_ref().map(indicatif::ProgressBar::position),
            Some(100)
        );
        long.finish();
        assert!(long.bar.is_none());
    }

    #[test]
    fn workers_follow_rayon_num_threads_else_the_cores() {
        assert_eq!(workers_for(Some("3"), 2), 3);
        assert_eq!(workers_for(Some(" 8 "), 2), 8);
        for ignored in [Some("0"), Some("many"), Some("-1"), Some(""), None] {
            assert_eq!(workers_for(ignored, 2), 2, "{ignored:?}");
        }
        assert_eq!(workers_for(None, 0), 1);
    }

    #[test]
    fn the_rate_is_the_average_so_far_and_the_time_left_follows_from_it() {
        let mib = 1 << 20;
        assert_eq!(
            rate_and_time_left(10 * mib, 40 * mib, Duration::from_secs(2)),
            "(5.0 MiB/s, 6 s left)"
        );
        assert_eq!(rate_and_time_left(0, 40, Duration::from_secs(2)), "");
        assert_eq!(
            rate_and_time_left(50 * mib, 40 * mib, Duration::from_secs(5)),
            "(10.0 MiB/s, 0 s left)"
        );
    }
}
