//! The scheduler: the workers that take runs of the points file, compute and format them,
//! and hand them to the ordered writing.

use std::path::Path;
use std::sync::{Condvar, Mutex, MutexGuard, OnceLock};
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
pub(crate) fn stream_points<T: Copy + Send + Sync, C: Column<T>, K: PointQuery<T>>(
    input: PointsInput,
    output: Option<&Path>,
    column: &C,
    queries: &[K],
) -> Result<(), CliError> {
    stream_prepared(input, output, |_| Ok((column, queries)))
}

/// [`stream_points`] with the column and the queries made by `prepare` (given the number of
/// points, exact for `.npy`, estimated for CSV) on the calling thread while the workers start
/// and read their first runs: the two took 0.2-0.4 ms one after the other on 10^6 `.npy`
/// points (a thread's start, its first read into fresh memory, against loading a domain
/// and choosing its engine). The output is created once `prepare` has succeeded; if it
/// fails, its error is the stream's and nothing is written.
///
/// The workers ([`worker_count`]) each take the next run of points from the reader (read by
/// position, or in order, one at a time, and parsed on the worker), compute and format it,
/// and write the results in input order ([`InOrder`]: a run's results wait only if an earlier
/// run's are not yet written, and the worker that writes that one writes them too). The
/// calling thread only prepares, then updates the progress bar. No stage waits for a whole
/// group of runs: a worker that finishes takes the next run at once. Memory is bounded: a
/// worker computes a run only while fewer than [`runs_in_flight`] runs before it are
/// unwritten, and holds one run at a time. The formatted results go back to a bounded pool
/// once written.
pub(crate) fn stream_prepared<'p, T, C, K>(
    input: PointsInput,
    output: Option<&Path>,
    prepare: impl FnOnce(usize) -> Result<(&'p C, &'p [K]), CliError>,
) -> Result<(), CliError>
where
    T: Copy + Send + Sync,
    C: Column<T> + 'p,
    K: PointQuery<T> + 'p,
{
    let workers = worker_count();
    let in_flight = runs_in_flight(workers);
    let points = input.estimated_points();
    let PointsInput {
        reader,
        path,
        total_bytes,
    } = input;
    let reader = &*reader;
    let path = Path::new(&path).to_path_buf();
    let results = Spares::new(in_flight);
    let format = Format::of(output);
    let ready = Ready::new();
    let (prepared, ended) = std::thread::scope(|scope| {
        let ready = &ready;
        // Should a worker fail to start, or the preparation panic, the workers started are
        // released before the scope joins them.
        let _release = EndOnDrop(ready);
        // Each worker holds a sender; the channel closes when the last one has finished.
        let (alive_tx, alive_rx) = std::sync::mpsc::channel::<()>();
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                let alive = alive_tx.clone();
                scope.spawn(move || {
                    // A worker that panics fails the run, so that the others finish.
                    let _failing = FailOnPanic(ready);
                    let mut buffers = (PointRun::default(), Vec::new());
                    work(reader, ready, &mut buffers.0, &mut buffers.1);
                    drop(alive);
                    // Freed by the calling thread once every worker has ended: a worker
                    // that freed its run's buffer (unmapping it) while another still ran
                    // took 60-150 us more to end.
                    buffers
                })
            })
            .collect();
        drop(alive_tx);
        let prepared = prepare(points).and_then(|(column, queries)| {
            let stage = Stage {
                format,
                column,
                queries,
                results: &results,
            };
            let in_order = InOrder::start(output, &stage, in_flight)?;
            Ok((stage, in_order))
        });
        let prepared = ready.open(prepared);
        let mut progress = Progress::new(total_bytes);
        while let Err(std::sync::mpsc::RecvTimeoutError::Timeout) =
            alive_rx.recv_timeout(Duration::from_millis(100))
        {
            progress.update(reader.progress().bytes_read);
        }
        progress.finish();
        let ended: Vec<_> = handles.into_iter().map(|h| h.join()).collect();
        (prepared, ended)
    });
    let all_ok = ended.iter().all(Result::is_ok);
    prepared?;
    let Some((stage, in_order)) = ready.into_inner() else {
        unreachable!("the stage is set when it was prepared")
    };
    let (written, count) = match in_order.finish(&stage) {
        Ok(w) => w,
        Err(WriteFailure::Input(e)) => return Err(input_error(&path, e)),
        Err(WriteFailure::Output(e)) => return Err(e),
    };
    if all_ok && reader.progress().runs_taken == count {
        written.finish()
    } else {
        // A run taken was never written: a stage failed; the output is dropped (removed).
        Err(thread_failed())
    }
}

/// The stage and the ordered writing, set once the calling thread has prepared them; the
/// workers wait for them after reading their first runs.
struct Ready<'s, C, K> {
    /// The stage and the ordered writing, once prepared (never if the preparation failed).
    stage: OnceLock<(Stage<'s, C, K>, InOrder)>,
    /// Whether the preparation has ended, and whether a worker failed before it did.
    state: Mutex<Preparation>,
    /// Signalled when the preparation ends.
    ended: Condvar,
}

/// [`Ready`]'s state.
#[derive(Default)]
struct Preparation {
    /// The preparation has ended (the stage set, or not if it failed).
    ended: bool,
    /// A worker panicked before the stage was set: the stream fails as soon as it is (the run
    /// that worker took would never be written, and the workers after it would wait for room
    /// forever).
    worker_failed: bool,
}

/// The stream's error when a worker panicked (or a run taken was never written).
fn thread_failed() -> CliError {
    CliError::Message("a streaming thread failed".into())
}

impl<'s, C, K> Ready<'s, C, K> {
    /// Not prepared yet.
    fn new() -> Self {
        Self {
            stage: OnceLock::new(),
            state: Mutex::new(Preparation::default()),
            ended: Condvar::new(),
        }
    }

    fn lock(&self) -> MutexGuard<'_, Preparation> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Ends the preparation: sets the stage if it was prepared (failed at once if a worker
    /// panicked meanwhile), and wakes the workers (who stop if it was not); returns the
    /// preparation's error, if any.
    fn open(&self, prepared: Result<(Stage<'s, C, K>, InOrder), CliError>) -> Result<(), CliError> {
        let result = prepared.map(|stage| {
            // Set once, here: `set` cannot find it set.
            let _ = self.stage.set(stage);
        });
        self.end();
        result
    }

    /// Marks the preparation ended (failing the stage if a worker panicked before it) and
    /// wakes the workers waiting for it.
    fn end(&self) {
        let mut state = self.lock();
        state.ended = true;
        if state.worker_failed
            && let Some((_, in_order)) = self.stage.get()
        {
            in_order.fail(thread_failed().into());
        }
        drop(state);
        self.ended.notify_all();
    }

    /// A worker panicked: fails the stream now if the stage is set, else once it is. (Under
    /// the lock that [`Ready::end`] takes after setting the stage: one of the two sees the
    /// other.)
    fn worker_failed(&self) {
        let mut state = self.lock();
        match self.stage.get() {
            Some((_, in_order)) => in_order.fail(thread_failed().into()),
            None => state.worker_failed = true,
        }
    }

    /// The stage and the ordered writing, once prepared; `None` if the preparation failed.
    fn wait(&self) -> Option<&(Stage<'s, C, K>, InOrder)> {
        let mut state = self.lock();
        while !state.ended {
            state = self.ended.wait(state).unwrap_or_else(|e| e.into_inner());
        }
        self.stage.get()
    }

    /// The stage and the ordered writing, if they were prepared.
    fn into_inner(self) -> Option<(Stage<'s, C, K>, InOrder)> {
        self.stage.into_inner()
    }
}

/// Ends the preparation when dropped (again, harmlessly, after [`Ready::open`]; or on a
/// panic in the preparation or in a worker's start, so that no worker waits for it forever).
struct EndOnDrop<'r, 's, C, K>(&'r Ready<'s, C, K>);

impl<C, K> Drop for EndOnDrop<'_, '_, C, K> {
    fn drop(&mut self) {
        self.0.end();
    }
}

/// Fails the stream if dropped while its thread panics, at once or as soon as the stage is
/// set: the other threads then stop taking runs.
struct FailOnPanic<'r, 's, C, K>(&'r Ready<'s, C, K>);

impl<C, K> Drop for FailOnPanic<'_, '_, C, K> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.worker_failed();
        }
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

/// A worker: takes a run and reads it, then waits for the stage (which the calling thread
/// prepares meanwhile; it stops if that failed); then, run after run, computes and formats
/// it once there is room for it, and hands the result to the ordered writing (writing it,
/// and any that came before it and waited, if it is next), until the runs run out or the
/// stream fails. Its `run` and `values` are kept from run to run (fresh buffers cost a page
/// fault per 4 KiB and zero-filling).
fn work<T: Copy, C: Column<T>, K: PointQuery<T>>(
    reader: &dyn PointsReader,
    ready: &Ready<'_, C, K>,
    run: &mut PointRun,
    values: &mut Vec<T>,
) {
    let Some(mut taken) = reader.next_run(run) else {
        return;
    };
    let Some((stage, in_order)) = ready.wait() else {
        return;
    };
    loop {
        let (seq, read) = taken;
        if !in_order.wait_for_room(seq) {
            return;
        }
        let result = read.map(|()| compute(run, stage, values));
        if !in_order.hand_in(seq, result, stage) {
            return;
        }
        match reader.next_run(run) {
            Some(next) => taken = next,
            None => return,
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
    use std::path::PathBuf;
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, Ordering};

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

    impl Scratch {
        /// An empty directory `name-<process id>` in the system's temporary directory.
        fn new(name: &str) -> Self {
            let dir = std::env::temp_dir().join(format!("{name}-{}", std::process::id()));
            let _ = std::fs::remove_dir_all(&dir);
            std::fs::create_dir_all(&dir).unwrap();
            Self(dir)
        }

        /// Writes `points.csv` here: a header, `first`, then the points `(i + 0.5, 1)` for `i`
        /// in `0..n` (lines of 6 bytes or more); returns its path and that of an output `out.npy`.
        fn points(&self, first: &str, n: usize) -> (PathBuf, PathBuf) {
            let lines: String = (0..n).map(|i| format!("{i}.5,1\n")).collect();
            let points = self.0.join("points.csv");
            std::fs::write(&points, format!("x,y\n{first}{lines}")).unwrap();
            (points, self.0.join("out.npy"))
        }

        /// The names of the files here.
        fn files(&self) -> Vec<std::ffi::OsString> {
            std::fs::read_dir(&self.0)
                .unwrap()
                .map(|e| e.unwrap().file_name())
                .collect()
        }

        /// `result` is the error `message`, and no output (nor temporary file) is left beside
        /// the points.
        fn assert_failed_with(&self, result: Result<(), CliError>, message: &str) {
            match result {
                Err(CliError::Message(m)) => assert_eq!(m, message),
                other => panic!("expected the error {message:?}, got {other:?}"),
            }
            assert_eq!(self.files(), ["points.csv"], "no output, no temporary file");
        }
    }

    /// `out` holds, after its header, the values of `PanicsOnTheLeft` at the `n` points of
    /// [`Scratch::points`], in order.
    fn assert_values_in_order(out: &Path, n: usize) {
        let bytes = std::fs::read(out).unwrap();
        let expected: Vec<u8> = (0..n).map(|i| (i % 7) as u8).collect();
        assert!(bytes.len() > n, "a header, then the values");
        assert_eq!(&bytes[bytes.len() - n..], &expected[..]);
    }

    impl Drop for Scratch {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    /// The stage is prepared on the calling thread while the workers read their first runs:
    /// a slow preparation still gives every value in order; a failed one is the stream's
    /// error, and no output (nor temporary file) is left; one that panics does not leave the
    /// workers waiting.
    #[test]
    fn the_stream_waits_for_its_preparation_and_a_failed_one_writes_nothing() {
        let scratch = Scratch::new("inrs-prepared");
        // About 1.3 MB of CSV: five runs of 256 KiB.
        let n = 120_000;
        let (points, out) = scratch.points("", n);
        let input = PointsInput::open(&points, 1).unwrap();
        let failed = stream_prepared(
            input,
            Some(&out),
            |_| -> Result<(&Bytes, &[PanicsOnTheLeft]), _> {
                Err(CliError::Message("no domain".into()))
            },
        );
        scratch.assert_failed_with(failed, "no domain");
        // A preparation that panics releases the workers (no hang) and the panic goes on.
        let input = PointsInput::open(&points, 1).unwrap();
        let panicked = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            stream_prepared(
                input,
                Some(&out),
                |_| -> Result<(&Bytes, &[PanicsOnTheLeft]), _> {
                    panic!("a preparation that panics")
                },
            )
        }));
        assert!(panicked.is_err());
        assert!(!out.exists());
        let input = PointsInput::open(&points, 1).unwrap();
        let estimated = input.estimated_points();
        stream_prepared(input, Some(&out), |points| {
            assert_eq!(points, estimated);
            // Long enough for every worker to have read its first run and be waiting.
            std::thread::sleep(Duration::from_millis(50));
            Ok((&Bytes, &[PanicsOnTheLeft][..]))
        })
        .unwrap();
        assert_values_in_order(&out, n);
    }

    /// A reader that panics when it has taken run 0 (as a CSV parse that panicked would), and
    /// sets its flag as the panic leaves it.
    struct PanicsOnTheFirstRun(Box<dyn PointsReader>, Arc<AtomicBool>);

    /// Sets its flag when dropped.
    struct SetOnDrop<'a>(&'a AtomicBool);

    impl Drop for SetOnDrop<'_> {
        fn drop(&mut self) {
            self.0.store(true, Ordering::Release);
        }
    }

    impl PointsReader for PanicsOnTheFirstRun {
        fn next_run(&self, run: &mut PointRun) -> Option<(usize, Result<(), inrs::PointsError>)> {
            let taken = self.0.next_run(run);
            let unwound = SetOnDrop(&self.1);
            assert!(!matches!(taken, Some((0, _))), "a read that panics");
            std::mem::forget(unwound);
            taken
        }
        fn points(&self) -> Option<usize> {
            self.0.points()
        }
        fn progress(&self) -> inrs::ReadProgress {
            self.0.progress()
        }
    }

    /// A worker that panics before the stage is set fails the stream once it is (and leaves
    /// no output): the run it took is never written, so the workers past the runs in flight
    /// would otherwise wait for room forever. The preparation ends only once the panic has
    /// left the reader (and, 20 ms later, the worker). Run on a thread of its own, so that a
    /// hang fails the test.
    #[test]
    fn a_worker_that_panics_before_the_stage_is_set_fails_the_stream() {
        let scratch = Scratch::new("inrs-early-panic");
        // Runs of 256 KiB of lines of 6 bytes or more: more runs than may be in flight.
        let runs = runs_in_flight(worker_count()) + 4;
        let (points, out) = scratch.points("", runs * (1 << 18) / 6);
        let (tx, rx) = std::sync::mpsc::channel();
        let (p, o) = (points.clone(), out.clone());
        std::thread::spawn(move || {
            let input = PointsInput::open(&p, 1).unwrap();
            let panicked = Arc::new(AtomicBool::new(false));
            let input = PointsInput {
                reader: Box::new(PanicsOnTheFirstRun(input.reader, panicked.clone())),
                ..input
            };
            let result = stream_prepared(input, Some(&o), |_| {
                for _ in 0..10_000 {
                    if panicked.load(Ordering::Acquire) {
                        break;
                    }
                    std::thread::sleep(Duration::from_millis(1));
                }
                std::thread::sleep(Duration::from_millis(20));
                Ok((&Bytes, &[PanicsOnTheLeft][..]))
            });
            let _ = tx.send(result.map_err(|e| format!("{e:?}")));
        });
        let result = rx
            .recv_timeout(Duration::from_secs(120))
            .expect("the stream ends");
        assert_eq!(
            result,
            Err("Message(\"a streaming thread failed\")".to_string())
        );
        assert!(!out.exists());
    }

    /// A stage that panics on the first run fails the stream with one error and leaves no
    /// output (the other workers stop taking runs; the process goes on); without that point
    /// every value is written, in input order, over several runs.
    #[test]
    fn a_panicking_stage_fails_the_stream_and_leaves_no_output() {
        let scratch = Scratch::new("inrs-scheduler");
        // About 1.3 MB of CSV: five runs of 256 KiB.
        let n = 120_000;
        for failing in [true, false] {
            let (points, out) = scratch.points(if failing { "-1,1\n" } else { "" }, n);
            let input = PointsInput::open(&points, 1).unwrap();
            let result = stream_points(input, Some(&out), &Bytes, &[PanicsOnTheLeft]);
            if failing {
                scratch.assert_failed_with(result, "a streaming thread failed");
            } else {
                result.unwrap();
                assert_values_in_order(&out, n);
            }
        }
    }
}
