//! The scheduler: the workers that take runs of the points file, compute and format them,
//! and hand them to the ordered writing.

use std::path::Path;
use std::time::Duration;

use inrs::{PointQuery, PointRun, PointsReader, RunPoints};

use super::format::{Column, Format, Formatted, Stage, format_csv_values, format_values};
use super::in_order::{InOrder, WriteFailure};
use super::progress::Progress;
use super::source::{PointsInput, input_error};
use super::spares::Spares;
use crate::cli::error::CliError;

/// Streams `input` through the `queries` (one value each per point, in order) and writes
/// `x,y,value,...` CSV rows (the coordinates echoed as written, a value per query), or, when
/// `output` ends in `.npy`, the values as a `.npy` array (of the column's shape).
///
/// The workers ([`worker_count`]) each take the next run of points from the reader (read by
/// position, or in order, one at a time, and parsed on the worker), compute and format it,
/// and write the results in input order ([`InOrder`]: a run's results wait only if an earlier
/// run's are not yet written, and the worker that writes that one writes them too). The
/// calling thread only updates the progress bar. No stage waits for a whole group of runs: a
/// worker that finishes takes the next run at once. Memory is bounded: a worker computes a
/// run only while fewer than [`runs_in_flight`] runs before it are unwritten, and holds one
/// run at a time. The formatted results go back to a bounded pool once written.
pub(crate) fn stream_points<T: Copy + Send + Sync, C: Column<T>, K: PointQuery<T>>(
    input: PointsInput,
    output: Option<&Path>,
    column: &C,
    queries: &[K],
) -> Result<(), CliError> {
    let workers = worker_count();
    let in_flight = runs_in_flight(workers);
    let PointsInput {
        reader,
        path,
        total_bytes,
    } = input;
    let reader = &*reader;
    let path = Path::new(&path).to_path_buf();
    let results = Spares::new(in_flight);
    let stage = Stage {
        format: Format::of(output),
        column,
        queries,
        results: &results,
    };
    let in_order = InOrder::start(output, &stage, in_flight)?;
    let all_ok = std::thread::scope(|scope| {
        let (stage, in_order) = (&stage, &in_order);
        // Each worker holds a sender; the channel closes when the last one has finished.
        let (alive_tx, alive_rx) = std::sync::mpsc::channel::<()>();
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                let alive = alive_tx.clone();
                scope.spawn(move || {
                    // A worker that panics fails the run, so that the others finish.
                    let _failing = FailOnPanic(in_order);
                    work(reader, stage, in_order);
                    drop(alive);
                })
            })
            .collect();
        drop(alive_tx);
        let mut progress = Progress::new(total_bytes);
        while let Err(std::sync::mpsc::RecvTimeoutError::Timeout) =
            alive_rx.recv_timeout(Duration::from_millis(100))
        {
            progress.update(reader.progress().bytes_read);
        }
        progress.finish();
        handles.into_iter().all(|h| h.join().is_ok())
    });
    let (written, count) = match in_order.finish(&stage) {
        Ok(w) => w,
        Err(WriteFailure::Input(e)) => return Err(input_error(&path, e)),
        Err(WriteFailure::Output(e)) => return Err(e),
    };
    if all_ok && reader.progress().runs_taken == count {
        written.finish()
    } else {
        // A run taken was never written: a stage failed; the output is dropped (removed).
        Err(CliError::Message("a streaming thread failed".into()))
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

/// How many runs may be taken and not yet written (beyond the one each worker holds):
/// enough for every worker to have one in hand, one queued and two results waiting for an
/// earlier one to be written.
fn runs_in_flight(workers: usize) -> usize {
    4 * workers
}

/// A worker: takes the next run, computes and formats it once there is room for it, and
/// hands the result to the ordered writing (writing it, and any that came before it and
/// waited, if it is next), until the runs run out or the stream fails. Its run and values are
/// kept from run to run (fresh buffers cost a page fault per 4 KiB and zero-filling).
fn work<T: Copy, C: Column<T>, K: PointQuery<T>>(
    reader: &dyn PointsReader,
    stage: &Stage<'_, C, K>,
    in_order: &InOrder,
) {
    let mut run = PointRun::default();
    let mut values = Vec::new();
    while let Some((seq, read)) = reader.next_run(&mut run) {
        if !in_order.wait_for_room(seq) {
            return;
        }
        let result = read.map(|()| compute(&run, stage, &mut values));
        if !in_order.hand_in(seq, result, stage) {
            return;
        }
    }
}

/// Fails the stream if dropped while its thread panics: the other threads then stop taking
/// runs.
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

/// Computes the values of `run`'s points, query by query into `values`, and formats them;
/// returns the bytes (from the stage's pool) and the number of points.
fn compute<T: Copy, C: Column<T>, K: PointQuery<T>>(
    run: &PointRun,
    stage: &Stage<'_, C, K>,
    values: &mut Vec<T>,
) -> Formatted {
    let Stage {
        format,
        column,
        queries,
        results,
    } = *stage;
    let n = run.len();
    values.clear();
    values.resize(n * queries.len(), column.initial());
    let mut bytes = results.take();
    if n == 0 {
        return (bytes, 0);
    }
    match run.points() {
        RunPoints::Csv(points) => {
            for (query, out) in queries.iter().zip(values.chunks_exact_mut(n)) {
                query.values_into(points.points, out);
            }
            format_csv_values(values, &points, format, column, &mut bytes);
        }
        RunPoints::Npy(encoded) => {
            // Read by index from the file's bytes: never copied into points.
            for (query, out) in queries.iter().zip(values.chunks_exact_mut(n)) {
                query.values_into(&encoded, out);
            }
            format_values(values, n, format, column, |i| encoded.point(i), &mut bytes);
        }
    }
    (bytes, n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stream::format::Bytes;

    #[test]
    fn workers_follow_rayon_num_threads_else_the_cores() {
        assert_eq!(workers_for(Some("3"), 2), 3);
        assert_eq!(workers_for(Some(" 8 "), 2), 8);
        for ignored in [Some("0"), Some("many"), Some("-1"), Some(""), None] {
            assert_eq!(workers_for(ignored, 2), 2, "{ignored:?}");
        }
        assert_eq!(workers_for(None, 0), 1);
    }

    /// `floor(x) mod 7` at every point of the right half-plane; a stage that fails (panics)
    /// on the left.
    struct PanicsOnTheLeft;

    impl PointQuery<u8> for PanicsOnTheLeft {
        fn value(&self, p: inrs::Point) -> u8 {
            assert!(p.x >= 0.0, "a point on the left");
            (p.x as u64 % 7) as u8
        }
    }

    /// A scratch directory of this test process, emptied first and removed when dropped.
    struct Scratch(std::path::PathBuf);

    impl Drop for Scratch {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    /// A stage that panics on the first run fails the stream with one error and leaves no
    /// output (the other workers stop taking runs; the process goes on); without that point
    /// every value is written, in input order, over several runs.
    #[test]
    fn a_panicking_stage_fails_the_stream_and_leaves_no_output() {
        let dir = std::env::temp_dir().join(format!("inrs-scheduler-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let scratch = Scratch(dir);
        // About 1.3 MB of CSV: five runs of 256 KiB.
        let n = 120_000;
        let lines: String = (0..n).map(|i| format!("{i}.5,1\n")).collect();
        let (points, out) = (scratch.0.join("points.csv"), scratch.0.join("out.npy"));
        for failing in [true, false] {
            let first = if failing { "-1,1\n" } else { "" };
            std::fs::write(&points, format!("x,y\n{first}{lines}")).unwrap();
            let input = PointsInput::open(&points, 1).unwrap();
            let result = stream_points(input, Some(&out), &Bytes, &[PanicsOnTheLeft]);
            if failing {
                match result {
                    Err(CliError::Message(m)) => assert_eq!(m, "a streaming thread failed"),
                    other => panic!("expected the stream to fail, got {other:?}"),
                }
                let left: Vec<_> = std::fs::read_dir(&scratch.0)
                    .unwrap()
                    .map(|e| e.unwrap().file_name())
                    .collect();
                assert_eq!(left, ["points.csv"], "no output, no temporary file");
            } else {
                result.unwrap();
                let bytes = std::fs::read(&out).unwrap();
                let expected: Vec<u8> = (0..n).map(|i| (i % 7) as u8).collect();
                assert!(bytes.len() > n, "a header, then the values");
                assert_eq!(&bytes[bytes.len() - n..], &expected[..]);
            }
        }
    }
}
