//! Streaming points through a computation: CSV or `.npy` in, CSV or `.npy` out, in bounded
//! batches that are parsed, computed and formatted on all threads and written in input order.
//! Memory depends on the batch size, not on the number of points.

use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, Sender};
use std::time::{Duration, Instant};

use inrs::{CsvBlock, NpyType, ParsedBlock, Point, PointQuery, PointsError};

use crate::cli::error::CliError;

mod in_order;
mod source;
mod spares;
use in_order::{InOrder, WriteFailure};
pub(crate) use source::PointsInput;
#[cfg(unix)]
use source::Positional;
use source::{Chunk, Sequential, Source, has_extension, input_error};
use spares::Spares;

/// Points a worker reads from a `.npy` file at a time: 64 KiB of float64 pairs, which stay in
/// its cache from the read to the computation (a task's megabyte at once cost the first
/// task of each worker 0.5-0.9 ms of page faults and every task another pass through memory).
#[cfg(unix)]
const NPY_READ_POINTS: usize = 1 << 12;
#[cfg(unix)]
thread_local! {
    /// Each worker's buffer for the bytes of the `.npy` ranges it reads, kept from task to
    /// task (a fresh one costs a page fault per 4 KiB and zero-filling).
    static NPY_SCRATCH: std::cell::RefCell<Vec<u8>> = Default::default();
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

/// Streams `input` through `compute` (one value per point, in order) and writes `x,y,value`
/// CSV rows (the coordinates echoed as written), or, when `output` ends in `.npy`, the values
/// as a 1-D `.npy` array.
///
/// The workers ([`worker_count`]) each take the next chunk, parse it (CSV), compute and format
/// it, and write the results in input order ([`InOrder`]: a chunk's results wait only if an
/// earlier chunk's are not yet written, and the worker that writes that one writes them too).
/// A regular file is cut by position and each worker reads the chunks it takes; other inputs
/// are read in order by a reading thread. The calling thread only updates the progress bar.
/// No stage waits for a whole group of chunks: a worker that finishes takes the next chunk at
/// once. Memory is bounded: a chunk is taken only while fewer than [`chunks_in_flight`]
/// chunks before it are unwritten. The byte buffers (chunks read, results formatted) go back to
/// two bounded pools once used.
pub(crate) fn stream_points<T: Copy + Send + Sync, C: Column<T>, K: PointQuery<T>>(
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
    let PointsInput {
        source,
        path,
        total_bytes,
    } = input;
    let path = Path::new(&path).to_path_buf();
    let read = AtomicU64::new(0);
    let (texts, results) = (Spares::new(in_flight), Spares::new(in_flight));
    let stage = Stage {
        format,
        column,
        kernel,
        texts: &texts,
        results: &results,
    };
    let in_order = InOrder::start(output, &stage, in_flight)?;
    let (sequential, tasks, chunk_count) = match source {
        Source::InOrder(sequential) => {
            let (tx, rx) = std::sync::mpsc::channel();
            (Some((sequential, tx)), Tasks::Sent(Mutex::new(rx)), None)
        }
        #[cfg(unix)]
        Source::ByPosition(positional) => {
            let count = positional.chunks();
            let tasks = Tasks::Claimed {
                next: AtomicUsize::new(0),
                positional,
            };
            (None, tasks, Some(count))
        }
    };
    let (workers_ok, sent) = std::thread::scope(|scope| {
        let (read, stage, in_order, tasks) = (&read, &stage, &in_order, &tasks);
        let reader = sequential.map(|(sequential, tx)| {
            scope.spawn(move || read_in_order(sequential, &tx, in_order, read, stage.texts))
        });
        // Each worker holds a sender; the channel closes when the last one has finished.
        let (alive_tx, alive_rx) = std::sync::mpsc::channel::<()>();
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                let alive = alive_tx.clone();
                scope.spawn(move || {
                    // A worker that panics fails the run, so that the others finish.
                    let _failing = FailOnPanic(in_order);
                    work(tasks, stage, in_order, read);
                    drop(alive);
                })
            })
            .collect();
        drop(alive_tx);
        let mut progress = Progress::new(total_bytes);
        while let Err(std::sync::mpsc::RecvTimeoutError::Timeout) =
            alive_rx.recv_timeout(Duration::from_millis(100))
        {
            progress.update(read.load(Ordering::Relaxed));
        }
        progress.finish();
        let workers_ok = handles.into_iter().all(|h| h.join().is_ok());
        // The reader has stopped: the workers took every chunk, or the run failed.
        let sent = match reader {
            Some(reader) => reader.join().ok(),
            None => chunk_count,
        };
        (workers_ok, sent)
    });
    let (written, count) = match in_order.finish(&stage) {
        Ok(w) => w,
        Err(WriteFailure::Input(e)) => return Err(input_error(&path, e)),
        Err(WriteFailure::Output(e)) => return Err(e),
    };
    match sent {
        Some(sent) if workers_ok && sent == count => written.finish(),
        // A chunk never arrived: a stage failed; the output is dropped (removed).
        _ => Err(CliError::Message("a streaming thread failed".into())),
    }
}

/// Where the workers take their chunks from.
enum Tasks {
    /// Sent by the reading thread, numbered.
    Sent(Mutex<Receiver<Numbered<Chunk>>>),
    /// Claimed by number, each read by position by the worker that claims it.
    #[cfg(unix)]
    Claimed {
        next: AtomicUsize,
        positional: Positional,
    },
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

/// A worker: takes the next chunk, computes and formats it, and hands the result to the
/// ordered writing (writing it, and any that came before it and waited, if it is next), until
/// the chunks run out or the run fails. Claimed chunks count as read, for the progress.
fn work<T: Copy, C: Column<T>, K: PointQuery<T>>(
    tasks: &Tasks,
    stage: &Stage<'_, C, K>,
    in_order: &InOrder,
    read: &AtomicU64,
) {
    loop {
        let (seq, result) = match tasks {
            Tasks::Sent(rx) => {
                // The lock is held only while waiting for the next chunk.
                let next = match rx.lock() {
                    Ok(rx) => rx.recv(),
                    Err(_) => return,
                };
                match next {
                    Ok((seq, chunk)) => (seq, chunk.and_then(|c| compute_sent(c, stage))),
                    Err(_) => return, // the reader has stopped and every chunk is taken
                }
            }
            #[cfg(unix)]
            Tasks::Claimed { next, positional } => {
                let k = next.fetch_add(1, Ordering::Relaxed);
                if k >= positional.chunks() || !in_order.wait_for_room(k) {
                    return;
                }
                read.fetch_max(positional.offset_of(k + 1), Ordering::Relaxed);
                (k, compute_claimed(positional, k, stage))
            }
        };
        if !in_order.hand_in(seq, result, stage) {
            return;
        }
    }
}

/// Fails the run if dropped while its thread panics: the other threads then stop taking
/// chunks.
struct FailOnPanic<'a>(&'a InOrder);

impl Drop for FailOnPanic<'_> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.fail(WriteFailure::Output(CliError::Message(
                "a streaming thread failed".into(),
            )));
        }
    }
}

/// Parses (CSV), computes and formats a chunk read in order.
fn compute_sent<T: Copy, C: Column<T>, K: PointQuery<T>>(
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
        Chunk::Points(p) => Ok(npy_points(&p, format, column, kernel, results.take())),
    }
}

/// Reads chunk `k` of a file by position, parses (CSV), computes and formats it.
#[cfg(unix)]
fn compute_claimed<T: Copy, C: Column<T>, K: PointQuery<T>>(
    positional: &Positional,
    k: usize,
    stage: &Stage<'_, C, K>,
) -> Result<Formatted, PointsError> {
    let Stage {
        format,
        column,
        kernel,
        results,
        ..
    } = *stage;
    match positional {
        Positional::Csv(file) => CSV_BLOCK.with_borrow_mut(|block| {
            file.read_block(k, block)?;
            let parse = |parsed: &mut ParsedBlock| file.parse_block(k, block, parsed);
            csv_block(block, parse, format, column, kernel, results.take())
        }),
        Positional::Npy(file) => NPY_SCRATCH.with_borrow_mut(|bytes| {
            let (first, n) = source::npy_chunk(file, k);
            let mut values = vec![column.initial(); n];
            let mut out = results.take();
            for (j, values) in values.chunks_mut(NPY_READ_POINTS).enumerate() {
                let at = first + j * NPY_READ_POINTS;
                let encoded = file.read_encoded(at, values.len(), bytes)?;
                // Read by index from the bytes: never copied into points.
                kernel.values_into(&encoded, values);
                let point = |i| encoded.point(i);
                format_values(values, format, column, point, &mut out);
            }
            Ok((out, n))
        }),
    }
}

/// The reading thread for an input read in order: numbers and sends its chunks (or its
/// first error, as the last chunk), each once there is room for it, until the input ends or
/// the run fails; counts the bytes read in `read`; reads CSV into buffers from `spares`.
/// Returns how many chunks it sent.
fn read_in_order(
    mut input: Sequential,
    tx: &Sender<Numbered<Chunk>>,
    in_order: &InOrder,
    read: &AtomicU64,
    spares: &Spares,
) -> usize {
    let mut sent = 0;
    loop {
        if !in_order.wait_for_room(sent) {
            return sent;
        }
        let next = input.next_chunk(spares);
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
    kernel: &impl PointQuery<T>,
    mut bytes: Vec<u8>,
) -> Result<(Vec<u8>, usize), PointsError> {
    CSV_SCRATCH.with_borrow_mut(|parsed| {
        parse(parsed)?;
        let mut values = vec![column.initial(); parsed.points.len()];
        kernel.values_into(&parsed.points, &mut values);
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
    kernel: &impl PointQuery<T>,
    mut bytes: Vec<u8>,
) -> (Vec<u8>, usize) {
    let mut values = vec![column.initial(); points.len()];
    kernel.values_into(points, &mut values);
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
