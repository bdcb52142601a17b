//! The scheduler: the workers that take chunks of the points file, compute and format them,
//! and hand them to the ordered writing.

use std::path::Path;
use std::sync::Mutex;
use std::sync::mpsc::{Receiver, Sender};
use std::time::Duration;

use inrs::io::points::{Chunk, ChunkPoints, ChunkScratch, ChunkSource};
use inrs::{PointQuery, PointsError};

use super::format::{Column, Format, Formatted, Stage, format_csv_values, format_values};
use super::in_order::{InOrder, WriteFailure};
use super::progress::Progress;
use super::source::{PointsInput, input_error};
use super::spares::Spares;
use crate::cli::error::CliError;

/// Streams `input` through the query `kernel` (one value per point, in order) and writes `x,y,value`
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
    let workers = worker_count();
    let in_flight = chunks_in_flight(workers);
    let PointsInput {
        source,
        path,
        total_bytes,
    } = input;
    let source = &*source;
    let path = Path::new(&path).to_path_buf();
    let (texts, results) = (Spares::new(in_flight), Spares::new(in_flight));
    let stage = Stage {
        format: Format::of(output),
        column,
        kernel,
        texts: &texts,
        results: &results,
    };
    let in_order = InOrder::start(output, &stage, in_flight)?;
    let (sequential, tasks) = if source.in_order() {
        let (tx, rx) = std::sync::mpsc::channel();
        (Some(tx), Tasks::Sent(Mutex::new(rx)))
    } else {
        (None, Tasks::Taken)
    };
    let all_ok = std::thread::scope(|scope| {
        let (stage, in_order, tasks) = (&stage, &in_order, &tasks);
        let reader = sequential
            .map(|tx| scope.spawn(move || read_in_order(source, &tx, in_order, stage.texts)));
        // Each worker holds a sender; the channel closes when the last one has finished.
        let (alive_tx, alive_rx) = std::sync::mpsc::channel::<()>();
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                let alive = alive_tx.clone();
                scope.spawn(move || {
                    // A worker that panics fails the run, so that the others finish.
                    let _failing = FailOnPanic(in_order);
                    work(source, tasks, stage, in_order);
                    drop(alive);
                })
            })
            .collect();
        drop(alive_tx);
        let mut progress = Progress::new(total_bytes);
        while let Err(std::sync::mpsc::RecvTimeoutError::Timeout) =
            alive_rx.recv_timeout(Duration::from_millis(100))
        {
            progress.update(source.bytes_read());
        }
        progress.finish();
        let workers_ok = handles.into_iter().all(|h| h.join().is_ok());
        // The reader has stopped: the workers took every chunk, or the run failed.
        let reader_ok = reader.is_none_or(|reader| reader.join().is_ok());
        workers_ok && reader_ok
    });
    let (written, count) = match in_order.finish(&stage) {
        Ok(w) => w,
        Err(WriteFailure::Input(e)) => return Err(input_error(&path, e)),
        Err(WriteFailure::Output(e)) => return Err(e),
    };
    if all_ok && source.chunks_taken() == count {
        written.finish()
    } else {
        // A chunk taken was never written: a stage failed; the output is dropped (removed).
        Err(CliError::Message("a streaming thread failed".into()))
    }
}

/// Where the workers take their chunks from.
enum Tasks {
    /// Sent by the reading thread, numbered.
    Sent(Mutex<Receiver<Numbered>>),
    /// Taken from the source by each worker (read by position).
    Taken,
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

/// A chunk read in order: its place in the input, whether it was read, and the chunk.
type Numbered = (usize, Result<(), PointsError>, Chunk);

/// A worker's buffers, kept from chunk to chunk (fresh ones cost a page fault per 4 KiB and
/// zero-filling): the chunk it reads by position, the points parsed or read, and the values.
struct Scratch<T> {
    chunk: Chunk,
    points: ChunkScratch,
    values: Vec<T>,
}

/// A worker: takes the next chunk, computes and formats it, and hands the result to the
/// ordered writing (writing it, and any that came before it and waited, if it is next), until
/// the chunks run out or the run fails.
fn work<T: Copy, C: Column<T>, K: PointQuery<T>>(
    source: &dyn ChunkSource,
    tasks: &Tasks,
    stage: &Stage<'_, C, K>,
    in_order: &InOrder,
) {
    let mut scratch = Scratch {
        chunk: Chunk::default(),
        points: ChunkScratch::default(),
        values: Vec::new(),
    };
    loop {
        let (seq, result) = match tasks {
            Tasks::Sent(rx) => {
                // The lock is held only while waiting for the next chunk.
                let next = match rx.lock() {
                    Ok(rx) => rx.recv(),
                    Err(_) => return,
                };
                // An error: the reader has stopped and every chunk is taken.
                let Ok((seq, read, chunk)) = next else { return };
                let result = read.and_then(|()| compute(source, &chunk, stage, &mut scratch));
                stage.texts.give(chunk.into_buffer());
                (seq, result)
            }
            Tasks::Taken => {
                let mut admit = |k| in_order.wait_for_room(k);
                let Some((seq, read)) = source.next_chunk(&mut scratch.chunk, &mut admit) else {
                    return;
                };
                let chunk = std::mem::take(&mut scratch.chunk);
                let result = read.and_then(|()| compute(source, &chunk, stage, &mut scratch));
                scratch.chunk = chunk;
                (seq, result)
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

/// Computes and formats the points of `chunk`, run by run; returns the bytes (from the
/// stage's pool) and the number of points.
fn compute<T: Copy, C: Column<T>, K: PointQuery<T>>(
    source: &dyn ChunkSource,
    chunk: &Chunk,
    stage: &Stage<'_, C, K>,
    scratch: &mut Scratch<T>,
) -> Result<Formatted, PointsError> {
    let Stage {
        format,
        column,
        kernel,
        results,
        ..
    } = *stage;
    let Scratch { points, values, .. } = scratch;
    let mut bytes = results.take();
    let mut count = 0;
    source.read_points(chunk, points, &mut |run| {
        values.clear();
        values.resize(run.len(), column.initial());
        count += run.len();
        match run {
            ChunkPoints::Csv { block, parsed } => {
                kernel.values_into(&parsed.points, values);
                format_csv_values(values, block, &parsed.fields, format, column, &mut bytes);
            }
            ChunkPoints::Npy(encoded) => {
                // Read by index from the file's bytes: never copied into points.
                kernel.values_into(&encoded, values);
                format_values(values, format, column, |i| encoded.point(i), &mut bytes);
            }
        }
    })?;
    Ok((bytes, count))
}

/// The reading thread for a source read in order: takes its chunks (reading each into a
/// buffer from `spares` once there is room for it) and sends them to the workers, numbered,
/// until the source runs out or fails, or the run fails.
fn read_in_order(
    source: &dyn ChunkSource,
    tx: &Sender<Numbered>,
    in_order: &InOrder,
    spares: &Spares,
) {
    loop {
        let mut chunk = Chunk::with_buffer(spares.take());
        let Some((seq, read)) = source.next_chunk(&mut chunk, &mut |k| in_order.wait_for_room(k))
        else {
            return;
        };
        if tx.send((seq, read, chunk)).is_err() {
            return;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn workers_follow_rayon_num_threads_else_the_cores() {
        assert_eq!(workers_for(Some("3"), 2), 3);
        assert_eq!(workers_for(Some(" 8 "), 2), 8);
        for ignored in [Some("0"), Some("many"), Some("-1"), Some(""), None] {
            assert_eq!(workers_for(ignored, 2), 2, "{ignored:?}");
        }
        assert_eq!(workers_for(None, 0), 1);
    }
}
