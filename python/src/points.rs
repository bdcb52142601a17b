//! Points as NumPy hands them over: an `(N, 2)` array or two 1-D ones, in any memory layout,
//! read in place.

use numpy::ndarray::{ArrayView1, ArrayView2};
use numpy::{PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::{FromPyObject, PyResult, Python};

use inrs::Point;

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

/// Runs `$body` with `$points`, a [`PointSource`](inrs::contain::PointSource) reading the
/// arrays' memory in place: one specialised accessor per layout (contiguous slices or strided
/// views), so the library's query loops are compiled for each and never branch on the layout
/// per point.
macro_rules! with_point_source {
    ($pts:expr, |$points:ident| $body:expr) => {{
        let n = $pts.len();
        $crate::points::with_point_accessor!($pts, |at| {
            let $points = ::inrs::contain::points_from_fn(n, at);
            $body
        })
    }};
}
pub(crate) use with_point_source;

/// Runs `$body` with `$at: Fn(usize) -> Point` reading the points' memory directly, one
/// accessor per layout.
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

/// Points as the Python layer passes them to a query: an `(N, 2)` float64 array, or a tuple
/// `(x, y)` of two 1-D float64 arrays of one length.
#[derive(FromPyObject)]
pub(crate) enum PointArrays<'py> {
    Pairs(PyReadonlyArray2<'py, f64>),
    Columns(PyReadonlyArray1<'py, f64>, PyReadonlyArray1<'py, f64>),
}

impl<'py> PointArrays<'py> {
    /// The interpreter the arrays belong to.
    pub(crate) fn py(&self) -> Python<'py> {
        match self {
            PointArrays::Pairs(xy) => xy.py(),
            PointArrays::Columns(x, _) => x.py(),
        }
    }

    /// The points, read in place.
    pub(crate) fn points(&self) -> PyResult<Points<'_>> {
        match self {
            PointArrays::Pairs(xy) => pairs(xy),
            PointArrays::Columns(x, y) => columns(x, y),
        }
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
