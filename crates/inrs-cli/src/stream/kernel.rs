//! What a streamed command computes: a [`PointsKernel`], one value per point.

use inrs::Point;

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
