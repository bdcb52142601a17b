//! Points read by index, in any layout: the input side of every batch query
//! (`rs_contain::PointQuery`).

use crate::Point;

/// Points read by index: `point(0), ..., point(len() - 1)`, of the plane ([`Point`], the
/// default) or of another space (`Q`: [`crate::Point3`] for points of space).
///
/// Implemented by slices and vectors of points and by [`points_from_fn`] (any layout through
/// an accessor); `rs-io` implements it for a `.npy` file's bytes. A query
/// monomorphises over the source, so an accessor inlines into its loop.
pub trait PointSource<Q = Point> {
    /// The number of points.
    fn len(&self) -> usize;

    /// Point `i` (`i < len()`; an implementation may panic otherwise).
    fn point(&self, i: usize) -> Q;

    /// Whether there are no points.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The points as a slice, when they are held as one: a parallel query then hands each
    /// task a sub-slice rather than an offset accessor.
    fn as_slice(&self) -> Option<&[Q]> {
        None
    }

    /// Points `first .. first + out.len()` into `out` (all below `len()`; an implementation
    /// may panic otherwise), the same as [`PointSource::point`] gives them one by one: a
    /// source whose points are decoded (a `.npy` file's bytes) decodes a block at once,
    /// without deciding its layout per point, in a loop the compiler can vectorise; a slice
    /// copies it.
    #[inline]
    fn points_into(&self, first: usize, out: &mut [Q]) {
        for (i, q) in out.iter_mut().enumerate() {
            *q = self.point(first + i);
        }
    }
}

impl<Q: Copy> PointSource<Q> for [Q] {
    #[inline]
    fn len(&self) -> usize {
        <[Q]>::len(self)
    }
    #[inline]
    fn point(&self, i: usize) -> Q {
        self[i]
    }
    fn as_slice(&self) -> Option<&[Q]> {
        Some(self)
    }
    #[inline]
    fn points_into(&self, first: usize, out: &mut [Q]) {
        out.copy_from_slice(&self[first..first + out.len()]);
    }
}

impl<Q: Copy> PointSource<Q> for Vec<Q> {
    #[inline]
    fn len(&self) -> usize {
        Vec::len(self)
    }
    #[inline]
    fn point(&self, i: usize) -> Q {
        self[i]
    }
    fn as_slice(&self) -> Option<&[Q]> {
        Some(self)
    }
    #[inline]
    fn points_into(&self, first: usize, out: &mut [Q]) {
        self[..].points_into(first, out);
    }
}

/// `len` points given by an accessor `f(i)`: see [`points_from_fn`].
#[derive(Clone, Copy, Debug)]
pub struct PointsFn<F> {
    len: usize,
    f: F,
}

/// The points `f(0), ..., f(len - 1)`, for points held in any layout (interleaved `x, y`
/// pairs, separate `x` and `y` arrays, strided views) without copying them.
///
/// ```
/// use rs_spline::{PointSource, points_from_fn};
/// use rs_spline::Point;
/// let (x, y) = ([0.0, 1.0], [2.0, 3.0]);
/// let pts = points_from_fn(2, |i| Point::new(x[i], y[i]));
/// assert_eq!(pts.point(1), Point::new(1.0, 3.0));
/// ```
pub fn points_from_fn<Q, F: Fn(usize) -> Q>(len: usize, f: F) -> PointsFn<F> {
    PointsFn { len, f }
}

impl<Q, F: Fn(usize) -> Q> PointSource<Q> for PointsFn<F> {
    #[inline]
    fn len(&self) -> usize {
        self.len
    }
    #[inline]
    fn point(&self, i: usize) -> Q {
        (self.f)(i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A block of points is its points one by one, from every first point, for slices,
    /// vectors and an accessor (the default).
    #[test]
    fn a_block_is_its_points_one_by_one() {
        let pts: Vec<Point> = (0..9)
            .map(|i| Point::new(i as f64, -0.5 * i as f64))
            .collect();
        let by_fn = points_from_fn(pts.len(), |i| pts[i]);
        for first in 0..pts.len() {
            let expected = &pts[first..];
            let mut block = vec![Point::default(); expected.len()];
            pts.points_into(first, &mut block);
            assert_eq!(block, expected);
            pts[..].points_into(first, &mut block);
            assert_eq!(block, expected);
            block.fill(Point::default());
            by_fn.points_into(first, &mut block);
            assert_eq!(block, expected);
        }
    }
}
