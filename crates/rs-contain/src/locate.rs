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

/// [`Locate::locate_all`] on chunks of the points, the chunks spread over rayon's pool.
pub(crate) fn in_parallel_chunks<L: Locate + ?Sized>(l: &L, points: &[Point]) -> Vec<Location> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        let mut out = vec![Location::Outside; points.len()];
        out.par_chunks_mut(PARALLEL_CHUNK)
            .zip(points.par_chunks(PARALLEL_CHUNK))
            .for_each(|(o, p)| o.copy_from_slice(&l.locate_all(p)));
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
