//! Points as NumPy hands them over: an `(N, 2)` array or two 1-D ones, in any memory layout,
//! read in place; and the codes of located points, chunk by chunk.

use numpy::ndarray::{ArrayView1, ArrayView2};
use numpy::{PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::PyResult;

use inrs::{Location, Point};

use crate::errors::value_error;

/// The points of an `(N, 2)` float64 array, or of two 1-D ones, in any memory layout (read in
/// place, never copied).
#[derive(Clone, Copy)]
pub(crate) enum Points<'a> {
    Pairs(ArrayView2<'a, f64>),
    Columns(ArrayView1<'a, f64>, ArrayView1<'a, f64>),
}

impl Points<'_> {
    pub(crate) fn len(&self) -> usize {
        match self {
            Points::Pairs(v) => v.nrows(),
            Points::Columns(x, _) => x.len(),
        }
    }
}

/// Runs `$body` with `$at: Fn(usize) -> Point` reading the points' memory directly: one
/// specialised accessor per layout (contiguous slices or strided views), so the hot loops in
/// `$body` are compiled for each and never branch on the layout per point.
macro_rules! with_point_accessor {
    ($pts:expr, |$at:ident| $body:expr) => {
        match $pts {
            $crate::points::Points::Pairs(v) => match v.as_slice() {
                Some(s) => {
                    let $at = |i: usize| ::inrs::Point::new(s[2 * i], s[2 * i + 1]);
                    $body
                }
                None => {
                    let $at = |i: usize| ::inrs::Point::new(v[[i, 0]], v[[i, 1]]);
                    $body
                }
            },
            $crate::points::Points::Columns(x, y) => match (x.as_slice(), y.as_slice()) {
                (Some(x), Some(y)) => {
                    let $at = |i: usize| ::inrs::Point::new(x[i], y[i]);
                    $body
                }
                _ => {
                    let $at = |i: usize| ::inrs::Point::new(x[i], y[i]);
                    $body
                }
            },
        }
    };
}
pub(crate) use with_point_accessor;

impl Points<'_> {
    /// A copy as points, for the kernels that take a slice.
    pub(crate) fn to_vec(self) -> Vec<Point> {
        with_point_accessor!(self, |at| (0..self.len()).map(at).collect())
    }
}

/// The points of an `(N, 2)` array.
pub(crate) fn pairs<'a>(xy: &'a PyReadonlyArray2<'_, f64>) -> PyResult<Points<'a>> {
    if xy.shape()[1] != 2 {
        return Err(value_error(format!(
            "points must have shape (N, 2), got {:?}",
            xy.shape()
        )));
    }
    Ok(Points::Pairs(xy.as_array()))
}

/// The points of two 1-D arrays of one length.
pub(crate) fn columns<'a>(
    x: &'a PyReadonlyArray1<'_, f64>,
    y: &'a PyReadonlyArray1<'_, f64>,
) -> PyResult<Points<'a>> {
    if x.len() != y.len() {
        return Err(value_error(format!(
            "x and y differ in length: {} and {}",
            x.len(),
            y.len()
        )));
    }
    Ok(Points::Columns(x.as_array(), y.as_array()))
}

/// Codes (0 outside, 1 inside, 2 boundary) of `n` points, in parallel chunks: `fill(first,
/// locations)` locates the points `first..first + locations.len()`, and each chunk's codes go
/// straight into the result (no array of locations the size of the input).
pub(crate) fn codes_in_chunks(n: usize, fill: impl Fn(usize, &mut [Location]) + Sync) -> Vec<i8> {
    use rayon::prelude::*;
    const TASK: usize = 1 << 16;
    let mut codes = vec![0i8; n];
    codes
        .par_chunks_mut(TASK)
        .enumerate()
        .for_each(|(c, codes)| {
            let mut buffer = [Location::Outside; TASK];
            let locations = &mut buffer[..codes.len()];
            fill(c * TASK, locations);
            for (code, location) in codes.iter_mut().zip(locations.iter()) {
                *code = location.code();
            }
        });
    codes
}
