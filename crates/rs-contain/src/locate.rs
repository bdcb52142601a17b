//! One containment vocabulary: every classifier of the workspace answers [`Locate`].

use rs_spline::Point;

use crate::Location;

/// Point location against a boundary: [`Location::Inside`], [`Location::Outside`] or
/// [`Location::Boundary`] for each query point.
///
/// Implemented by [`Classifier`](crate::Classifier) (inRS, the method in its options),
/// [`PointLocator`](crate::PointLocator) (the grid), [`WindingField`](crate::WindingField) and
/// [`FastWindingField`](crate::FastWindingField) (generalized winding numbers with the fill rule
/// they were built with), and by the curved-triangulation locator of `rs-mesh`. The options
/// that change answers (tolerance, fill rule, method) live in the value, so code written
/// against `impl Locate` gives the same answers whichever one it is handed.
pub trait Locate: Sync {
    /// The location of one point.
    fn locate(&self, p: Point) -> Location;

    /// The locations of `points`, in input order, on the current thread (an implementor may
    /// batch the work: sort the points, share a grid).
    fn locate_all(&self, points: &[Point]) -> Vec<Location> {
        points.iter().map(|&p| self.locate(p)).collect()
    }

    /// As [`Locate::locate_all`], split over rayon's thread pool in chunks of 4096 points
    /// (with the `parallel` feature, on by default; otherwise on the current thread).
    fn locate_all_parallel(&self, points: &[Point]) -> Vec<Location> {
        in_parallel_chunks(self, points)
    }
}

/// [`Locate::locate_all`] on chunks of the points, on the calling thread and rayon's pool
/// ([`on_caller_and_pool`]).
pub(crate) fn in_parallel_chunks<L: Locate + ?Sized>(l: &L, points: &[Point]) -> Vec<Location> {
    #[cfg(feature = "parallel")]
    {
        let mut out = vec![Location::Outside; points.len()];
        on_caller_and_pool(&mut out, PARALLEL_CHUNK, |first, o| {
            o.copy_from_slice(&l.locate_all(&points[first..first + o.len()]));
        });
        out
    }
    #[cfg(not(feature = "parallel"))]
    {
        l.locate_all(points)
    }
}

/// Points per parallel task.
#[cfg(feature = "parallel")]
const PARALLEL_CHUNK: usize = 4096;

/// Runs `f(first, piece)` on the `chunk`-long pieces of `out` (`first` the index of a piece's
/// first element) on the calling thread and rayon's pool together. A shared counter hands the
/// pieces out, so the caller starts at once and the pool's threads join as they wake: handing
/// the whole job to the pool made the caller wait for sleeping threads to wake first, which on
/// this virtual machine (idle cores halt) left two threads no faster than one in the median
/// of `cargo xtask bench` (scaling 0.95-0.97 on 10^6 points, 1.3-1.8 in the best rounds).
#[cfg(feature = "parallel")]
pub(crate) fn on_caller_and_pool<T: Send>(
    out: &mut [T],
    chunk: usize,
    f: impl Fn(usize, &mut [T]) + Sync,
) {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::{Mutex, PoisonError};
    let chunk = chunk.max(1);
    let pieces: Vec<Mutex<&mut [T]>> = out.chunks_mut(chunk).map(Mutex::new).collect();
    let next = AtomicUsize::new(0);
    let work = || {
        loop {
            let k = next.fetch_add(1, Ordering::Relaxed);
            let Some(piece) = pieces.get(k) else {
                return;
            };
            // Each piece is taken once: the lock is never contended.
            let mut piece = piece.lock().unwrap_or_else(PoisonError::into_inner);
            f(k * chunk, &mut piece);
        }
    };
    rayon::in_place_scope(|s| {
        for _ in 1..rayon::current_num_threads().min(pieces.len()) {
            s.spawn(|_| work());
        }
        work();
    });
}

#[cfg(all(test, feature = "parallel"))]
mod tests {
    use super::*;

    /// Every element is handed to `f` once, in the piece starting at its own index, whatever
    /// the length and the piece size.
    #[test]
    fn the_caller_and_the_pool_cover_every_piece_once() {
        for (n, chunk) in [
            (0, 4),
            (1, 4),
            (3, 4),
            (4, 4),
            (5, 4),
            (100_003, 4096),
            (7, 0),
        ] {
            let mut out = vec![usize::MAX; n];
            on_caller_and_pool(&mut out, chunk, |first, piece| {
                for (i, v) in piece.iter_mut().enumerate() {
                    assert_eq!(*v, usize::MAX, "visited twice");
                    *v = first + i;
                }
            });
            assert!(
                out.iter().enumerate().all(|(i, &v)| v == i),
                "n {n} chunk {chunk}"
            );
        }
    }
}
