//! Points in, values out: the one query shape of the workspace.
//!
//! A query ([`PointQuery`]) gives one value per point: a [`Location`], a winding number, a
//! spline value. It reads its points from any [`PointSource`] (a slice, interleaved or
//! separate coordinate arrays, a `.npy` file's bytes) by index, without copying them, and
//! writes the values into a slice the caller owns; the batch and parallel forms are provided
//! on top. [`Locate`] names the location queries.

use rs_spline::{Point, PointSource};

use crate::Location;

/// Points `first .. first + len` of another source (one parallel task's share).
#[cfg(feature = "parallel")]
struct Window<'a, P: ?Sized> {
    points: &'a P,
    first: usize,
    len: usize,
}

#[cfg(feature = "parallel")]
impl<Q, P: PointSource<Q> + ?Sized> PointSource<Q> for Window<'_, P> {
    #[inline]
    fn len(&self) -> usize {
        self.len
    }
    #[inline]
    fn point(&self, i: usize) -> Q {
        self.points.point(self.first + i)
    }
    #[inline]
    fn points_into(&self, first: usize, out: &mut [Q]) {
        self.points.points_into(self.first + first, out);
    }
}

/// One value of type `T` per point of type `Q` (a [`Point`] of the plane unless said otherwise;
/// `rs-geom`'s solid classifier answers points of space).
///
/// Implementors give [`PointQuery::value`] and, where a batch is cheaper than its points one
/// by one (sorting, a shared grid, vector instructions), [`PointQuery::values_into`]; the
/// vector and parallel forms are provided. Every form gives each point the value
/// [`PointQuery::value`] gives it.
///
/// A type may answer several queries (a winding field gives locations and winding numbers);
/// the output slice's type picks the one.
pub trait PointQuery<T: Copy, Q: Copy = Point>: Sync {
    /// The value at one point.
    fn value(&self, p: Q) -> T;

    /// Writes the value of `points.point(i)` to `out[i]`, on the current thread.
    ///
    /// # Panics
    /// If `out` is not as long as `points`.
    fn values_into<P: PointSource<Q> + ?Sized>(&self, points: &P, out: &mut [T]) {
        assert_eq!(points.len(), out.len(), "one value per point");
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.value(points.point(i));
        }
    }

    /// Points per parallel task of [`PointQuery::par_values_into`].
    fn parallel_chunk(&self) -> usize {
        PARALLEL_CHUNK
    }

    /// As [`PointQuery::values_into`], in tasks of [`PointQuery::parallel_chunk`] points on
    /// the calling thread and rayon's pool together (with the `parallel` feature, on by
    /// default; otherwise on the current thread).
    ///
    /// # Panics
    /// If `out` is not as long as `points`.
    fn par_values_into<P: PointSource<Q> + Sync + ?Sized>(&self, points: &P, out: &mut [T])
    where
        T: Send,
        Q: Sync,
    {
        in_tasks(self, points, out, self.parallel_chunk());
    }
}

/// [`PointQuery::values_into`] on tasks of `chunk` points, on the calling thread and rayon's
/// pool together (with the `parallel` feature; otherwise on the current thread in one go).
pub(crate) fn in_tasks<T, Q, X, P>(query: &X, points: &P, out: &mut [T], chunk: usize)
where
    T: Copy + Send,
    Q: Copy + Sync,
    X: PointQuery<T, Q> + ?Sized,
    P: PointSource<Q> + Sync + ?Sized,
{
    assert_eq!(points.len(), out.len(), "one value per point");
    #[cfg(feature = "parallel")]
    on_caller_and_pool(out, chunk, |first, o| match points.as_slice() {
        Some(s) => query.values_into(&s[first..first + o.len()], o),
        None => query.values_into(
            &Window {
                points,
                first,
                len: o.len(),
            },
            o,
        ),
    });
    #[cfg(not(feature = "parallel"))]
    {
        let _ = chunk;
        query.values_into(points, out);
    }
}

/// Points per parallel task unless a query says otherwise.
pub(crate) const PARALLEL_CHUNK: usize = 4096;

/// Point location against a boundary: [`Location::Inside`], [`Location::Outside`] or
/// [`Location::Boundary`] for each query point. Every [`PointQuery`] of locations is one.
///
/// Implemented by [`Classifier`](crate::Classifier) (inRS, the method in its options),
/// [`Engine`](crate::Engine) (what [`Containment`](crate::Containment) hands a front end),
/// [`PointLocator`](crate::PointLocator) (the grid), [`WindingField`](crate::WindingField)
/// and [`FastWindingField`](crate::FastWindingField) (generalized winding numbers with the
/// fill rule they were built with), and by the curved-triangulation locator of `rs-mesh`.
/// The options that change answers (tolerance, fill rule, method) live in the value, so code
/// written against `impl Locate` gives the same answers whichever one it is handed.
pub trait Locate<Q: Copy = Point>: PointQuery<Location, Q> {
    /// The location of one point.
    fn locate(&self, p: Q) -> Location {
        self.value(p)
    }

    /// The locations of `points`, in input order, on the current thread.
    fn locate_all(&self, points: &[Q]) -> Vec<Location> {
        let mut out = vec![Location::Outside; points.len()];
        self.values_into(points, &mut out);
        out
    }

    /// As [`Locate::locate_all`], on the calling thread and rayon's pool
    /// ([`PointQuery::par_values_into`]).
    fn locate_all_parallel(&self, points: &[Q]) -> Vec<Location>
    where
        Q: Sync,
    {
        let mut out = vec![Location::Outside; points.len()];
        self.par_values_into(points, &mut out);
        out
    }
}

impl<Q: Copy, X: PointQuery<Location, Q> + ?Sized> Locate<Q> for X {}

/// Runs `f(first, piece)` on the `chunk`-long pieces of `out` (`first` the index of a piece's
/// first element) on the calling thread and rayon's pool together. A shared counter hands the
/// pieces out, so the caller starts at once and the pool's threads join as they wake: handing
/// the whole job to the pool makes the caller wait for sleeping threads to wake first, which
/// on machines whose idle cores halt costs more than the work of a batch.
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
