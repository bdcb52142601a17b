//! The ordered writing stage, run by the workers, and the bound it puts on the runs in flight.

use std::path::Path;
use std::sync::{Condvar, Mutex, MutexGuard};

use inrs::PointsError;

use super::format::{Column, Format, Formatted, Stage};
use crate::cli::error::CliError;
use crate::cli::output::Output;

/// Why the writing stopped early: a run's input was bad (reported with the input's name), or
/// the output failed, or a worker panicked.
pub(super) enum WriteFailure {
    Input(PointsError),
    Output(CliError),
}

impl From<CliError> for WriteFailure {
    fn from(e: CliError) -> Self {
        Self::Output(e)
    }
}

/// The ordered writing: a run's results are written by the worker that computed them if
/// every earlier run's are written, else they wait for the worker that writes the run
/// before them (which then writes them too). The bytes are mostly written from the cache of
/// the core that formatted them, and no thread waits to write. Memory is bounded here too: a
/// run taken is computed only while fewer than `in_flight` runs before it are unwritten
/// ([`InOrder::wait_for_room`]).
pub(super) struct InOrder {
    state: Mutex<State>,
    /// Signalled when a run is written or the stream fails.
    room: Condvar,
    /// The output, used by the one worker that is writing (see [`State::writing`]).
    out: Mutex<Output>,
    in_flight: usize,
}

struct State {
    /// Results that came before an earlier run's: fewer than the runs in flight.
    waiting: std::collections::BTreeMap<usize, Result<Formatted, PointsError>>,
    /// The next run to write.
    next: usize,
    /// Points written.
    points: usize,
    /// Whether a worker is writing (it writes every waiting result that comes next).
    writing: bool,
    /// Threads waiting for room.
    waiters: usize,
    /// The first failure, in input order: nothing is written after it.
    failure: Option<WriteFailure>,
}

impl InOrder {
    /// Opens the output and writes the header (for `.npy`, one without the count yet); at
    /// most `in_flight` runs will be taken and not yet written.
    pub(super) fn start<T, C: Column<T>, K>(
        output: Option<&Path>,
        stage: &Stage<'_, C, K>,
        in_flight: usize,
    ) -> Result<Self, CliError> {
        let column = stage.column;
        let mut out = Output::create(output)?;
        if stage.format == Format::Npy {
            let shape = column.npy_shape(0, stage.queries.len());
            out.write_bytes(&inrs::npy_header(column.npy_type(), &shape))?;
        } else {
            out.write_str(column.header())?;
            out.write_str("\n")?;
        }
        Ok(Self {
            state: Mutex::new(State {
                waiting: std::collections::BTreeMap::new(),
                next: 0,
                points: 0,
                writing: false,
                waiters: 0,
                failure: None,
            }),
            room: Condvar::new(),
            out: Mutex::new(out),
            in_flight: in_flight.max(1),
        })
    }

    fn lock(&self) -> MutexGuard<'_, State> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Waits until run `seq` may be computed: fewer than the runs in flight before it are
    /// unwritten. False if the stream has failed (compute nothing more). The run that is written
    /// next never waits, so neither does the stream as a whole.
    pub(super) fn wait_for_room(&self, seq: usize) -> bool {
        let mut state = self.lock();
        while state.failure.is_none() && seq >= state.next + self.in_flight {
            state.waiters += 1;
            state = self.room.wait(state).unwrap_or_else(|e| e.into_inner());
            state.waiters -= 1;
        }
        state.failure.is_none()
    }

    /// Hands in run `seq`'s results; writes them and the waiting ones after them if they
    /// come next and no other worker is writing, giving each buffer written to the pool.
    /// False once a run (this or an earlier one) has failed.
    pub(super) fn hand_in<C, K>(
        &self,
        seq: usize,
        result: Result<Formatted, PointsError>,
        stage: &Stage<'_, C, K>,
    ) -> bool {
        let mut state = self.lock();
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
            state = self.lock();
            match written {
                Ok(n) => {
                    state.points += n;
                    state.next += 1;
                    if state.waiters > 0 {
                        self.room.notify_all();
                    }
                }
                Err(failure) => {
                    state.writing = false;
                    drop(state);
                    self.fail(failure);
                    return false;
                }
            }
        }
    }

    /// Fails the stream (unless it failed before): nothing more is taken or written.
    pub(super) fn fail(&self, failure: WriteFailure) {
        let mut state = self.lock();
        state.failure.get_or_insert(failure);
        self.room.notify_all();
    }

    /// Once every worker has finished: the output (for `.npy`, with the final header), to be
    /// committed once the stream is known complete, and the number of runs written; or the
    /// first failure.
    pub(super) fn finish<T, C: Column<T>, K>(
        self,
        stage: &Stage<'_, C, K>,
    ) -> Result<(Output, usize), WriteFailure> {
        let state = self.state.into_inner().unwrap_or_else(|e| e.into_inner());
        if let Some(failure) = state.failure {
            return Err(failure);
        }
        let mut out = self.out.into_inner().unwrap_or_else(|e| e.into_inner());
        if stage.format == Format::Npy {
            let shape = stage.column.npy_shape(state.points, stage.queries.len());
            out.rewrite_start(&inrs::npy_header(stage.column.npy_type(), &shape))?;
        }
        Ok((out, state.next))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stream::format::Bytes;
    use crate::stream::spares::Spares;

    fn with_stage(test: impl FnOnce(&Stage<'_, Bytes, ()>, &Path)) {
        let dir = std::env::temp_dir().join(format!(
            "inrs-in-order-{}-{:?}",
            std::process::id(),
            std::thread::current().id()
        ));
        std::fs::create_dir_all(&dir).unwrap();
        let results = Spares::new(4);
        let stage = Stage {
            format: Format::Csv,
            column: &Bytes,
            queries: &[(); 1],
            results: &results,
        };
        test(&stage, &dir.join("out.csv"));
        std::fs::remove_dir_all(&dir).unwrap_or_default();
    }

    fn run(text: &str) -> Result<Formatted, PointsError> {
        Ok((text.as_bytes().to_vec(), 1))
    }

    #[test]
    fn results_handed_in_out_of_order_are_written_in_order() {
        with_stage(|stage, path| {
            let w = InOrder::start(Some(path), stage, 4).unwrap();
            for seq in [2, 0, 3, 1] {
                assert!(w.hand_in(seq, run(&format!("{seq}\n")), stage));
            }
            let (out, count) = w.finish(stage).ok().unwrap();
            out.finish().unwrap();
            assert_eq!(count, 4);
            assert_eq!(
                std::fs::read_to_string(path).unwrap(),
                "x,y,b\n0\n1\n2\n3\n"
            );
        });
    }

    #[test]
    fn a_run_waits_for_room_until_an_earlier_one_is_written() {
        with_stage(|stage, path| {
            let w = InOrder::start(Some(path), stage, 2).unwrap();
            assert!(w.wait_for_room(0) && w.wait_for_room(1), "within the bound");
            std::thread::scope(|s| {
                let (tx, rx) = std::sync::mpsc::channel();
                let w = &w;
                s.spawn(move || tx.send(w.wait_for_room(2)).unwrap());
                // Run 1 written first changes nothing: run 0 is still unwritten.
                assert!(w.hand_in(1, run("1\n"), stage));
                let short = std::time::Duration::from_millis(50);
                assert!(rx.recv_timeout(short).is_err(), "run 2 was let in early");
                assert!(w.hand_in(0, run("0\n"), stage));
                let long = std::time::Duration::from_secs(10);
                assert_eq!(rx.recv_timeout(long), Ok(true));
            });
        });
    }

    #[test]
    fn a_bad_run_stops_the_run_and_wakes_the_waiting() {
        with_stage(|stage, path| {
            let w = InOrder::start(Some(path), stage, 1).unwrap();
            std::thread::scope(|s| {
                let (tx, rx) = std::sync::mpsc::channel();
                let w = &w;
                s.spawn(move || tx.send(w.wait_for_room(5)).unwrap());
                let bad = PointsError::Line {
                    line: 7,
                    message: "bad".into(),
                };
                assert!(w.hand_in(1, run("1\n"), stage), "waits for run 0");
                assert!(!w.hand_in(0, Err(bad), stage));
                let long = std::time::Duration::from_secs(10);
                assert_eq!(rx.recv_timeout(long), Ok(false));
            });
            assert!(!w.wait_for_room(0));
            assert!(!w.hand_in(2, run("2\n"), stage));
            match w.finish(stage) {
                Err(WriteFailure::Input(PointsError::Line { line: 7, .. })) => {}
                _ => panic!("the bad line is the failure"),
            }
        });
    }
}
