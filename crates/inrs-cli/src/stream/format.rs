//! The output: CSV rows `x,y,value` or a 1-D `.npy` array of the values, one [`Column`] of
//! values per command.

use std::path::Path;

use inrs::{CsvBlock, NpyType, Point};

use super::spares::Spares;

/// An output column: its CSV header and how its values are written as CSV text and in
/// `.npy`. Implemented by a unit type per column, so that writing a value compiles into the
/// streaming loop (a function pointer per value: 2% more instructions in a CSV run).
pub(crate) trait Column<T>: Sync {
    /// The CSV header line (`x,y,location`).
    fn header(&self) -> &'static str;
    /// A value to fill buffers with before they are computed.
    fn initial(&self) -> T;
    /// Appends a value as CSV text.
    fn csv(&self, value: T, out: &mut Vec<u8>);
    /// The `.npy` element type.
    fn npy_type(&self) -> NpyType;
    /// Appends the `.npy` bytes of a run of values (one call per run: a call per value cost a
    /// tenth of a fast run).
    fn npy(&self, values: &[T], out: &mut Vec<u8>);
}

/// The output's format.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Format {
    /// CSV rows `x,y,value`.
    Csv,
    /// A 1-D `.npy` array of the values.
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

/// Appends to `bytes` the values of points parsed from CSV, whose fields `fields` stand in
/// `block`'s text: as `.npy` data, or as CSV rows `x,y,value` with the coordinates as written.
pub(super) fn format_csv_values<T: Copy, C: Column<T>>(
    values: &[T],
    block: &CsvBlock,
    fields: &[[u32; 4]],
    format: Format,
    column: &C,
    bytes: &mut Vec<u8>,
) {
    if format == Format::Npy {
        return npy_values(values, column, bytes);
    }
    bytes.reserve(block.text.len() + 16 * values.len());
    for (f, &v) in fields.iter().zip(values) {
        if block.field(f[1], f[2]) == b"," {
            // `x,y` as written, in one copy.
            bytes.extend_from_slice(block.field(f[0], f[3]));
        } else {
            bytes.extend_from_slice(block.field(f[0], f[1]));
            bytes.push(b',');
            bytes.extend_from_slice(block.field(f[2], f[3]));
        }
        bytes.push(b',');
        column.csv(v, bytes);
        bytes.push(b'\n');
    }
}

/// Appends to `bytes` the values of points read from `.npy`: as `.npy` data, or as CSV rows
/// `x,y,value` with the coordinates `point(i)` in shortest round-trip form.
pub(super) fn format_values<T: Copy, C: Column<T>>(
    values: &[T],
    format: Format,
    column: &C,
    point: impl Fn(usize) -> Point,
    bytes: &mut Vec<u8>,
) {
    if format == Format::Npy {
        return npy_values(values, column, bytes);
    }
    bytes.reserve(values.len() * 48);
    let mut digits = zmij::Buffer::new();
    for (i, &v) in values.iter().enumerate() {
        let p = point(i);
        bytes.extend_from_slice(digits.format_finite(p.x).as_bytes());
        bytes.push(b',');
        bytes.extend_from_slice(digits.format_finite(p.y).as_bytes());
        bytes.push(b',');
        column.csv(v, bytes);
        bytes.push(b'\n');
    }
}

/// Appends the values to `bytes` as `.npy` data.
fn npy_values<T: Copy, C: Column<T>>(values: &[T], column: &C, bytes: &mut Vec<u8>) {
    bytes.reserve(values.len() * column.npy_type().size());
    column.npy(values, bytes);
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
        let mut digits = zmij::Buffer::new();
        out.extend_from_slice(digits.format_finite(v).as_bytes());
    }
}

/// Whether `path`'s extension is `ext`, in any case.
pub(super) fn has_extension(path: &Path, ext: &str) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// A chunk's results, formatted, and how many points it held.
pub(super) type Formatted = (Vec<u8>, usize);

/// What a worker needs to turn a chunk into formatted results.
pub(super) struct Stage<'a, C, K> {
    pub(super) format: Format,
    pub(super) column: &'a C,
    pub(super) kernel: &'a K,
    /// Where the buffers of chunks read in order go back to once computed.
    pub(super) texts: &'a Spares,
    /// Where result buffers come from.
    pub(super) results: &'a Spares,
}
