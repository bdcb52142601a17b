//! The output: CSV rows `x,y,value,...` or a `.npy` array of the values, one [`Column`] of
//! values per query (several queries give a row several columns).

use std::path::Path;

use inrs::{CsvPoints, NpyType, Point};

use super::spares::Spares;

/// An output column: its CSV header and how its values are written as CSV text and in
/// `.npy`. Implemented by a type per column, so that writing a value compiles into the
/// streaming loop (a function pointer per value: 2% more instructions in a CSV run).
pub(crate) trait Column<T>: Sync {
    /// The CSV header line (`x,y,location`; with several queries, a field per query).
    fn header(&self) -> &str;
    /// A value to fill buffers with before they are computed.
    fn initial(&self) -> T;
    /// Appends a value as CSV text.
    fn csv(&self, value: T, out: &mut Vec<u8>);
    /// The `.npy` element type.
    fn npy_type(&self) -> NpyType;
    /// Appends the `.npy` bytes of a run of values (one call per run: a call per value cost a
    /// tenth of a fast run).
    fn npy(&self, values: &[T], out: &mut Vec<u8>);
    /// The shape of the `.npy` output of `points` points and `queries` queries: `(points,)`
    /// unless the column says otherwise (`(points, queries)`, row by row).
    fn npy_shape(&self, points: usize, queries: usize) -> Vec<usize> {
        let _ = queries;
        vec![points]
    }
}

/// The output's format.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Format {
    /// CSV rows `x,y,value,...`.
    Csv,
    /// A `.npy` array of the values.
    Npy,
}

impl Format {
    /// `.npy` if `output` ends so, else CSV (standard output too).
    pub(super) fn of(output: Option<&Path>) -> Self {
        if output.is_some_and(|p| has_extension(p, "npy")) {
            Self::Npy
        } else {
            Self::Csv
        }
    }
}

/// Appends to `bytes` the values of `points`, parsed from CSV: `values` holds the values of
/// each query in turn (`values.len() / points` queries). As `.npy` data, or as CSV rows
/// `x,y,value,...` with the coordinates as written.
pub(super) fn format_csv_values<T: Copy, C: Column<T>>(
    values: &[T],
    points: &CsvPoints<'_>,
    format: Format,
    column: &C,
    bytes: &mut Vec<u8>,
) {
    if format == Format::Npy {
        return npy_values(values, points.points.len(), column, bytes);
    }
    bytes.reserve(points.text_len() + 16 * values.len());
    rows(values, points.points.len(), column, bytes, |i, bytes| {
        points.echo_into(i, bytes);
    });
}

/// Appends to `bytes` the values of points read from `.npy` (`point(i)`, `n` of them; values
/// as for [`format_csv_values`]): as `.npy` data, or as CSV rows `x,y,value,...` with the
/// coordinates in shortest round-trip form.
pub(super) fn format_values<T: Copy, C: Column<T>>(
    values: &[T],
    n: usize,
    format: Format,
    column: &C,
    point: impl Fn(usize) -> Point,
    bytes: &mut Vec<u8>,
) {
    if format == Format::Npy {
        return npy_values(values, n, column, bytes);
    }
    bytes.reserve(n * 32 + 16 * values.len());
    let mut digits = Digits(zmij::Buffer::new());
    rows(values, n, column, bytes, |i, bytes| {
        let p = point(i);
        bytes.extend_from_slice(digits.0.format_finite(p.x).as_bytes());
        bytes.push(b',');
        bytes.extend_from_slice(digits.0.format_finite(p.y).as_bytes());
    });
}

/// The digits of a number being formatted, on a cache line of their own wherever the stack
/// puts them: a buffer across two lines made the formatting of 10^6 `.npy` points as CSV 18%
/// slower (72 against 61 ms of CPU), after a change elsewhere in the streaming loop moved it.
#[repr(align(64))]
struct Digits(zmij::Buffer);

/// The CSV rows of `n` points: each echoed by `echo`, then its value of each query (`values`
/// holds the values of each query in turn).
#[inline(always)]
fn rows<T: Copy, C: Column<T>>(
    values: &[T],
    n: usize,
    column: &C,
    bytes: &mut Vec<u8>,
    mut echo: impl FnMut(usize, &mut Vec<u8>),
) {
    if n == 0 {
        return;
    }
    if values.len() == n {
        // One query: its values in order.
        for (i, &v) in values.iter().enumerate() {
            echo(i, bytes);
            bytes.push(b',');
            column.csv(v, bytes);
            bytes.push(b'\n');
        }
        return;
    }
    for i in 0..n {
        echo(i, bytes);
        for &v in values[i..].iter().step_by(n) {
            bytes.push(b',');
            column.csv(v, bytes);
        }
        bytes.push(b'\n');
    }
}

/// Appends to `bytes` the values of `n` points as `.npy` data, row by row (`values` holds the
/// values of each query in turn).
fn npy_values<T: Copy, C: Column<T>>(values: &[T], n: usize, column: &C, bytes: &mut Vec<u8>) {
    bytes.reserve(values.len() * column.npy_type().size());
    if values.len() == n {
        return column.npy(values, bytes);
    }
    for i in 0..n {
        for v in values[i..].iter().step_by(n) {
            column.npy(std::slice::from_ref(v), bytes);
        }
    }
}

/// Appends `v` in shortest round-trip form (`zmij`); `nan`, `inf` and `-inf` for the
/// non-finite values.
#[inline]
pub(crate) fn write_f64(v: f64, out: &mut Vec<u8>) {
    if v.is_nan() {
        out.extend_from_slice(b"nan");
    } else if v.is_infinite() {
        out.extend_from_slice(if v > 0.0 { b"inf" } else { b"-inf" });
    } else {
        let mut digits = Digits(zmij::Buffer::new());
        out.extend_from_slice(digits.0.format_finite(v).as_bytes());
    }
}

/// Whether `path`'s extension is `ext`, in any case.
pub(super) fn has_extension(path: &Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// A run's results, formatted, and how many points it held.
pub(super) type Formatted = (Vec<u8>, usize);

/// A column of bytes for the stream's tests: `.npy` `int8`, a digit per value in CSV.
#[cfg(test)]
pub(super) struct Bytes;

#[cfg(test)]
impl Column<u8> for Bytes {
    fn header(&self) -> &str {
        "x,y,b"
    }
    fn initial(&self) -> u8 {
        0
    }
    fn csv(&self, value: u8, out: &mut Vec<u8>) {
        out.push(b'0' + value);
    }
    fn npy_type(&self) -> NpyType {
        NpyType::I8
    }
    fn npy(&self, values: &[u8], out: &mut Vec<u8>) {
        out.extend_from_slice(values);
    }
}

/// What a worker needs to turn a run into formatted results.
pub(super) struct Stage<'a, C, K> {
    pub(super) format: Format,
    pub(super) column: &'a C,
    /// The queries: one value each per point.
    pub(super) queries: &'a [K],
    /// Where result buffers come from.
    pub(super) results: &'a Spares,
}
