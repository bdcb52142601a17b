//! Items `0 .. n` computed on the calling thread and rayon's pool and handed to the caller in
//! order, with at most a window of them computed ahead: the scheduler of the row bands of
//! [`GridCoverage::bands`](crate::GridCoverage::bands) (a whole grid in place needs no order:
//! [`GridCoverage::all`](crate::GridCoverage::all) hands its bands to rayon's pool).
//!
//! Workers are rayon jobs of a scope that the caller's closure runs in, so the items may
//! borrow from the caller; with the caller they are as many as rayon's threads. A worker
//! claims the next item while the window has room and exits when it has none; the caller
//! restarts workers as it takes items. A worker never waits. The caller, when the item it
//! wants is not done, computes the next item nobody has claimed, and waits only when there is
//! none: then every item it waits for is being computed by a running worker, so no thread, in
//! a pool of any size, waits for a job that cannot run.

use std::sync::{Condvar, Mutex, MutexGuard, PoisonError};

/// The state the caller and the workers share.
struct Shared<R> {
    state: Mutex<State<R>>,
    /// Signalled when an item is done or a computation panicked.
    changed: Condvar,
    /// The number of items.
    n: usize,
    /// The most items claimed and not yet taken by the caller.
    window: usize,
}

struct State<R> {
    /// Items `0 .. claimed` are being computed or done.
    claimed: usize,
    /// Items `0 .. taken` have been handed to the caller.
    taken: usize,
    /// Item `k` in `slots[k % window]` from when it is done until it is taken.
    slots: Vec<Option<R>>,
    /// Workers started and not yet finished.
    workers: usize,
    /// The caller is gone: claim nothing more.
    stop: bool,
    /// A computation panicked.
    failed: bool,
}

impl<R> Shared<R> {
    fn lock(&self) -> MutexGuard<'_, State<R>> {
        self.state.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Claims the next item if the window has room.
    fn claim(&self, s: &mut State<R>) -> Option<usize> {
        let room = s.claimed < self.n && s.claimed < s.taken.saturating_add(self.window);
        (room && !s.stop && !s.failed).then(|| {
            s.claimed += 1;
            s.claimed - 1
        })
    }

    /// Computes item `k` (claimed) and puts it in its slot.
    fn compute_into_slot(&self, k: usize, compute: &(dyn Fn(usize) -> R + Sync)) {
        let item = {
            let _failing = FailOnPanic(self);
            compute(k)
        };
        self.lock().slots[k % self.window] = Some(item);
        self.changed.notify_all();
    }

    /// A worker: computes items while it can claim them.
    #[cfg_attr(not(feature = "parallel"), allow(dead_code))]
    fn work(&self, compute: &(dyn Fn(usize) -> R + Sync)) {
        loop {
            let k = {
                let mut s = self.lock();
                match self.claim(&mut s) {
                    Some(k) => k,
                    None => {
                        s.workers -= 1;
                        return;
                    }
                }
            };
            self.compute_into_slot(k, compute);
        }
    }
}

/// Marks the run failed (and wakes the caller) if dropped while a computation unwinds.
struct FailOnPanic<'a, R>(&'a Shared<R>);

impl<R> Drop for FailOnPanic<'_, R> {
    fn drop(&mut self) {
        if std::thread::panicking() {
            self.0.lock().failed = true;
            self.0.changed.notify_all();
        }
    }
}

/// The items in order ([`in_order`]). Dropped before the end, it lets the workers finish the
/// items they are computing and claim no more.
pub(crate) struct InOrder<'a, R> {
    shared: &'a Shared<R>,
    compute: &'a (dyn Fn(usize) -> R + Sync),
    /// Starts one more worker.
    spawn: &'a (dyn Fn() + Sync),
    /// The most workers at once.
    workers: usize,
}

impl<R> InOrder<'_, R> {
    /// Starts workers up to the limit while items remain to be claimed.
    fn start_workers(&self, mut s: MutexGuard<'_, State<R>>) {
        let mut start = 0;
        while s.workers < self.workers
            && s.claimed + start < self.shared.n
            && s.claimed + start < s.taken.saturating_add(self.shared.window)
        {
            s.workers += 1;
            start += 1;
        }
        drop(s);
        for _ in 0..start {
            (self.spawn)();
        }
    }
}

impl<R> Iterator for InOrder<'_, R> {
    type Item = R;

    fn next(&mut self) -> Option<R> {
        let shared = self.shared;
        let mut s = shared.lock();
        let k = s.taken;
        if k >= shared.n {
            return None;
        }
        loop {
            assert!(!s.failed, "a worker panicked computing a band");
            if let Some(item) = s.slots[k % shared.window].take() {
                s.taken += 1;
                self.start_workers(s);
                return Some(item);
            }
            // Rather than wait, compute the next item nobody computes: this one if it is
            // (the workers are busy or not started), else one ahead of it in the window.
            match shared.claim(&mut s) {
                Some(m) if m == k => {
                    self.start_workers(s);
                    let item = (self.compute)(k);
                    shared.lock().taken += 1;
                    return Some(item);
                }
                Some(m) => {
                    drop(s);
                    shared.compute_into_slot(m, self.compute);
                    s = shared.lock();
                }
                None => {
                    s = shared
                        .changed
                        .wait(s)
                        .unwrap_or_else(PoisonError::into_inner);
                }
            }
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.shared.n - self.shared.lock().taken;
        (left, Some(left))
    }
}

impl<R> ExactSizeIterator for InOrder<'_, R> {}

impl<R> Drop for InOrder<'_, R> {
    fn drop(&mut self) {
        self.shared.lock().stop = true;
    }
}

/// Runs `consume` with the items `compute(0) .. compute(n - 1)` in order, computed on the
/// calling thread and (with the `parallel` feature) rayon's pool, at most `window` (at least
/// one) claimed ahead of the one `consume` takes next; returns what `consume` returns once
/// every worker has finished.
///
/// # Panics
/// If a computation panics (the panic goes on to the caller).
pub(crate) fn in_order<R: Send, T>(
    n: usize,
    window: usize,
    compute: &(dyn Fn(usize) -> R + Sync),
    consume: impl FnOnce(InOrder<'_, R>) -> T,
) -> T {
    let window = window.clamp(1, n.max(1));
    let shared = Shared {
        state: Mutex::new(State {
            claimed: 0,
            taken: 0,
            slots: (0..window).map(|_| None).collect(),
            workers: 0,
            stop: false,
            failed: false,
        }),
        changed: Condvar::new(),
        n,
        window,
    };
    #[cfg(feature = "parallel")]
    {
        // The caller computes too (whenever it would wait): it stands for one of the threads.
        let workers = rayon::current_num_threads().saturating_sub(1);
        rayon::in_place_scope(|scope| {
            let shared = &shared;
            let spawn = || scope.spawn(move |_| shared.work(compute));
            let items = InOrder {
                shared,
                compute,
                spawn: &spawn,
                workers,
            };
            items.start_workers(shared.lock());
            consume(items)
        })
    }
    #[cfg(not(feature = "parallel"))]
    consume(InOrder {
        shared: &shared,
        compute,
        spawn: &|| {},
        workers: 0,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    #[test]
    fn items_come_in_order_whatever_the_window() {
        for (n, window) in [(0, 4), (1, 1), (5, 1), (37, 3), (100, 100), (64, 0)] {
            let got: Vec<usize> = in_order(n, window, &|k| k * k, |items| {
                assert_eq!(items.len(), n);
                items.collect()
            });
            assert_eq!(got, (0..n).map(|k| k * k).collect::<Vec<_>>(), "n {n}");
        }
    }

    #[test]
    fn no_more_than_the_window_is_computed_ahead() {
        let computed = AtomicUsize::new(0);
        let compute = |k: usize| {
            computed.fetch_add(1, Ordering::SeqCst);
            k
        };
        in_order(1000, 3, &compute, |items| {
            for (taken, k) in items.enumerate() {
                assert_eq!(k, taken);
                // Items `0 ..= taken` handed out, at most 3 claimed beyond the next one.
                assert!(computed.load(Ordering::SeqCst) <= taken + 1 + 3);
            }
        });
        assert_eq!(computed.into_inner(), 1000);
    }

    #[test]
    fn a_caller_that_stops_early_stops_the_workers() {
        let computed = AtomicUsize::new(0);
        let compute = |k: usize| {
            computed.fetch_add(1, Ordering::SeqCst);
            k
        };
        let first: Vec<usize> = in_order(10_000, 4, &compute, |items| items.take(3).collect());
        assert_eq!(first, [0, 1, 2]);
        assert!(computed.into_inner() <= 3 + 4);
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn a_pool_of_one_thread_does_not_wait_for_itself() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let sum: usize = pool.install(|| in_order(500, 2, &|k| k, |items| items.sum()));
        assert_eq!(sum, 500 * 499 / 2);
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn a_panicking_computation_reaches_the_caller() {
        let run = std::panic::catch_unwind(|| {
            in_order(
                64,
                8,
                &|k| {
                    assert!(k != 40, "band 40");
                    k
                },
                |items| items.count(),
            )
        });
        assert!(run.is_err());
    }
}
