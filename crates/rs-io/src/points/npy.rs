//! `NumPy` `.npy` files: points in as a float64 (or float32) array of shape `(N, 2)`
//! ([`NpyReader`]), results out as arrays of any shape ([`npy_header`]), both streamed.
//!
//! The format (`NumPy`'s `numpy.lib.format`, versions 1.0 to 3.0): the magic `\x93NUMPY`, two
//! version bytes, the header length (2 bytes little-endian in version 1, 4 in versions 2 and
//! 3), then a Python dict literal `{'descr': '<f8', 'fortran_order': False, 'shape': (N, 2), }`
//! padded with spaces to a multiple of 64 bytes and ended by a newline, then the data.

use std::io::Read;
use std::path::Path;

use super::encoded::{EncodedPoints, NpyType};
use super::run::Claims;
use super::run::{Content, InOrder, PointRun, PointsReader, ReadProgress, RunSizes, Source};
use super::{PointsError, open_file};

/// The most points a `.npy` header may announce: larger shapes are refused before anything
/// is read (the data are streamed, so this only guards the arithmetic).
pub const MAX_NPY_POINTS: u64 = 1 << 48;

/// The length of the headers [`npy_header`] writes: 128 bytes, room for any shape up to
/// [`MAX_NPY_POINTS`], so a header written before the count is known can be rewritten in place.
pub const NPY_HEADER_BYTES: usize = 128;

/// A `.npy` header of exactly [`NPY_HEADER_BYTES`] bytes (version 1.0) for a C-order array of
/// `ty` with `shape`.
///
/// # Examples
///
/// ```
/// let h = rs_io::points::npy_header(rs_io::points::NpyType::I8, &[3]);
/// assert_eq!(h.len(), rs_io::points::NPY_HEADER_BYTES);
/// assert!(h.starts_with(b"\x93NUMPY\x01\x00"));
/// assert!(String::from_utf8_lossy(&h).contains("'shape': (3,)"));
/// ```
pub fn npy_header(ty: NpyType, shape: &[usize]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
    let shape = if dims.len() == 1 {
        format!("({},)", dims[0])
    } else {
        format!("({})", dims.join(", "))
    };
    let dict = format!(
        "{{'descr': '{}', 'fortran_order': False, 'shape': {shape}, }}",
        ty.descr()
    );
    let mut h = b"\x93NUMPY\x01\x00".to_vec();
    let text_len = NPY_HEADER_BYTES - 10;
    h.extend_from_slice(&(text_len as u16).to_le_bytes());
    h.extend_from_slice(dict.as_bytes());
    h.resize(NPY_HEADER_BYTES - 1, b' ');
    h.push(b'\n');
    h
}

/// The points of a `.npy` file holding a C-order float64 (or float32) array of shape
/// `(N, 2)`, read in order.
#[derive(Debug)]
struct NpyStream<R> {
    input: R,
    path: String,
    ty: NpyType,
    len: usize,
    remaining: usize,
    consumed: u64,
}

impl<R: Read> NpyStream<R> {
    /// Reads the header of `input` (named `path` in errors).
    ///
    /// # Errors
    /// [`PointsError::Npy`] for a file that is not a `.npy` array of shape `(N, 2)` of
    /// float64 or float32 in C order; [`PointsError::Io`].
    fn new(mut input: R, path: impl Into<String>) -> Result<Self, PointsError> {
        let path = path.into();
        let (ty, len, consumed) = read_header(&mut input, &path, 2)?;
        Ok(Self {
            input,
            path,
            ty,
            len,
            remaining: len,
            consumed,
        })
    }

    /// Bytes read so far (for progress reports).
    fn bytes_read(&self) -> u64 {
        self.consumed
    }

    /// The next (up to) `max` points as stored, read into `buf` and checked finite (none at
    /// the end).
    ///
    /// # Errors
    /// [`PointsError::Npy`] if the file ends early or holds a non-finite coordinate (naming
    /// the point's index); [`PointsError::Io`].
    fn read_encoded<'b>(
        &mut self,
        max: usize,
        buf: &'b mut Vec<u8>,
    ) -> Result<EncodedPoints<'b>, PointsError> {
        let (first, n) = (self.len - self.remaining, max.min(self.remaining));
        self.remaining -= n;
        let (input, consumed) = (&mut self.input, &mut self.consumed);
        read_run(self.ty, &self.path, self.len, first, n, buf, |bytes| {
            input.read_exact(bytes)?;
            *consumed += bytes.len() as u64;
            Ok(())
        })
    }
}

/// Reads the header of a `.npy` array of points with `columns` coordinates each (named
/// `path` in errors): its element type, its number of points and the bytes read.
///
/// # Errors
/// [`PointsError::Npy`] for a file that is not a `.npy` array of shape `(N, columns)` of
/// float64 or float32 in C order; [`PointsError::Io`].
pub(super) fn read_header(
    input: &mut impl Read,
    path: &str,
    columns: usize,
) -> Result<(NpyType, usize, u64), PointsError> {
    let text = read_header_text(input, path)?;
    let (ty, len) = parse_points_header(&text, columns).map_err(|message| PointsError::Npy {
        path: path.to_string(),
        message,
    })?;
    // The magic and version (8 bytes), the header's length (2 bytes in version 1, else 4).
    let length_bytes = if text.version == 1 { 2 } else { 4 };
    Ok((ty, len, (8 + length_bytes + text.len) as u64))
}

/// A header dict as read, with the format version and its length in bytes.
struct HeaderText {
    text: String,
    version: u8,
    len: usize,
}

impl std::ops::Deref for HeaderText {
    type Target = str;
    fn deref(&self) -> &str {
        &self.text
    }
}

/// Reads the magic, the version and the header dict of a `.npy` file (named `path` in
/// errors), leaving `input` at the data.
///
/// # Errors
/// [`PointsError::Npy`] for a file that is not a `.npy` file (versions 1.0 to 3.0, a header
/// of at most 1 MiB); [`PointsError::Io`].
fn read_header_text(input: &mut impl Read, path: &str) -> Result<HeaderText, PointsError> {
    let fail = |message: String| PointsError::Npy {
        path: path.to_string(),
        message,
    };
    let io = |source: std::io::Error| PointsError::Io {
        path: path.to_string(),
        source,
    };
    let mut magic = [0u8; 8];
    input
        .read_exact(&mut magic)
        .map_err(|_| fail("not a .npy file (too short)".into()))?;
    if &magic[..6] != b"\x93NUMPY" {
        return Err(fail("not a .npy file (no \\x93NUMPY magic)".into()));
    }
    let header_len = match magic[6] {
        1 => {
            let mut b = [0u8; 2];
            input.read_exact(&mut b).map_err(io)?;
            usize::from(u16::from_le_bytes(b))
        }
        2 | 3 => {
            let mut b = [0u8; 4];
            input.read_exact(&mut b).map_err(io)?;
            u32::from_le_bytes(b) as usize
        }
        v => return Err(fail(format!("unsupported .npy version {v}"))),
    };
    if header_len > 1 << 20 {
        return Err(fail(format!("header of {header_len} bytes")));
    }
    let mut text = vec![0u8; header_len];
    input
        .read_exact(&mut text)
        .map_err(|_| fail("header cut short".into()))?;
    Ok(HeaderText {
        text: String::from_utf8_lossy(&text).into_owned(),
        version: magic[6],
        len: header_len,
    })
}

/// Reads the bytes of points `first..first + n` of a file of `len` points of `ty` (named
/// `path` in errors) with `read` into `buf`, resized to them, and checks them finite: how both
/// readers, in order and by position, take their points.
fn read_run<'b>(
    ty: NpyType,
    path: &str,
    len: usize,
    first: usize,
    n: usize,
    buf: &'b mut Vec<u8>,
    read: impl FnOnce(&mut [u8]) -> std::io::Result<()>,
) -> Result<EncodedPoints<'b>, PointsError> {
    buf.resize(2 * ty.size() * n, 0);
    read(buf).map_err(|e| data_cut_short(path, len, &e))?;
    EncodedPoints::checked(ty, buf, first, path)
}

/// The error for data that end before the `len` points the header announces.
fn data_cut_short(path: &str, len: usize, e: &std::io::Error) -> PointsError {
    PointsError::Npy {
        path: path.to_string(),
        message: format!("the data end before the {len} points the header announces ({e})"),
    }
}

/// The `.npy` points file: a C-order float64 (or float32, converted exactly) array of shape
/// `(N, 2)`, `NumPy`'s format versions 1.0 to 3.0, every coordinate checked finite.
///
/// The [`PointsReader`] of `.npy`: runs of `sizes.npy_points` points handed over as stored
/// ([`crate::points::RunPoints::Npy`], read by index, never copied). [`NpyReader::open`] reads
/// a regular file by position (Unix: any number of threads at once, `pread`; the copies out of
/// the operating system's cache, which dominate a fast computation on many points, then run on
/// every core); [`NpyReader::new`] reads any input in order.
///
/// # Examples
///
/// ```
/// use rs_io::points::{NpyReader, NpyType, PointRun, PointsReader, RunPoints, RunSizes, npy_header};
/// let mut bytes = npy_header(NpyType::F64, &[3, 2]);
/// for v in [0.5f64, 1.0, -2.0, 3.25, 4.0, 5.0] {
///     bytes.extend_from_slice(&v.to_le_bytes());
/// }
/// let sizes = RunSizes { npy_points: 2, ..RunSizes::default() };
/// let reader = NpyReader::new(&bytes[..], "mem", sizes).unwrap();
/// assert_eq!(reader.len(), 3);
/// let (mut run, mut xs) = (PointRun::default(), Vec::new());
/// while let Some((k, read)) = reader.next_run(&mut run) {
///     read.unwrap();
///     if let RunPoints::Npy(pts) = run.points() {
///         xs.extend((0..pts.len()).map(|i| (k, pts.point(i).x)));
///     }
/// }
/// assert_eq!(xs, [(0, 0.5), (0, -2.0), (1, 4.0)]);
/// ```
#[derive(Debug)]
pub struct NpyReader<R> {
    source: Source<NpyStream<R>, NpyFile>,
    ty: NpyType,
    len: usize,
    /// Points per run.
    per_run: usize,
}

/// The most points of a run (whatever the sizes asked for): 1 GiB of float64 pairs.
const MAX_RUN_POINTS: usize = 1 << 26;

impl<R: Read> NpyReader<R> {
    /// Reads the header of `input` (named `name` in errors); the points are read in order, in
    /// runs of `sizes.npy_points`.
    ///
    /// # Errors
    /// [`PointsError::Npy`] for a file that is not a `.npy` array of shape `(N, 2)` of
    /// float64 or float32 in C order; [`PointsError::Io`].
    pub fn new(input: R, name: impl Into<String>, sizes: RunSizes) -> Result<Self, PointsError> {
        let stream = NpyStream::new(input, name)?;
        let (ty, len) = (stream.ty, stream.len);
        Ok(Self {
            source: Source::InOrder(InOrder::new(stream)),
            ty,
            len,
            per_run: sizes.npy_points.clamp(1, MAX_RUN_POINTS),
        })
    }
}

impl<R> NpyReader<R> {
    /// The number of points the header announces.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True if the array has no points.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The element type of the array.
    pub fn element_type(&self) -> NpyType {
        self.ty
    }
}

impl NpyReader<std::io::BufReader<std::fs::File>> {
    /// Opens `path` and reads its header: read by position if it is a regular file (Unix), in
    /// order otherwise (a named pipe cannot be read by position).
    ///
    /// # Errors
    /// As [`NpyReader::new`], and [`PointsError::Io`] if it cannot be opened.
    pub fn open(path: impl AsRef<Path>, sizes: RunSizes) -> Result<Self, PointsError> {
        let path = path.as_ref();
        let per_run = sizes.npy_points.clamp(1, MAX_RUN_POINTS);
        #[cfg(unix)]
        if std::fs::metadata(path).is_ok_and(|m| m.is_file()) {
            let file = NpyFile::open(path)?;
            let (ty, len) = (file.ty, file.len);
            return Ok(Self {
                source: Source::ByPosition(Claims::new(len.div_ceil(per_run)), file),
                ty,
                len,
                per_run,
            });
        }
        let input = std::io::BufReader::with_capacity(1 << 20, open_file(path)?);
        Self::new(input, path.display().to_string(), sizes)
    }
}

impl<R: Read + Send> PointsReader for NpyReader<R> {
    fn next_run(&self, run: &mut PointRun) -> Option<(usize, Result<(), PointsError>)> {
        let (k, read) = match &self.source {
            Source::InOrder(stream) => stream.next(
                |s| {
                    s.read_encoded(self.per_run, &mut run.bytes)
                        .map(|points| (!points.is_empty()).then_some(()))
                },
                NpyStream::bytes_read,
            )?,
            #[cfg(not(unix))]
            Source::ByPosition(_, never) => match *never {},
            #[cfg(unix)]
            Source::ByPosition(claims, file) => {
                let k = claims.claim(|k| file.offset_of((k + 1).saturating_mul(self.per_run)))?;
                let first = k * self.per_run;
                (
                    k,
                    file.read_encoded(first, self.per_run, &mut run.bytes)
                        .map(drop),
                )
            }
        };
        run.start(k, Content::Npy(self.ty));
        Some((k, read.map_err(|e| run.fail(e))))
    }

    fn points(&self) -> Option<usize> {
        Some(self.len)
    }

    fn progress(&self) -> ReadProgress {
        self.source.progress()
    }
}

/// Reading by position exists on Unix only.
#[cfg(not(unix))]
type NpyFile = std::convert::Infallible;

/// A `.npy` points file read by position, from any number of threads at once (`pread`).
/// Unix only.
#[cfg(unix)]
#[derive(Debug)]
struct NpyFile {
    file: std::fs::File,
    path: String,
    ty: NpyType,
    len: usize,
    /// Where the data start (after the header).
    data_offset: u64,
}

#[cfg(unix)]
impl NpyFile {
    /// Opens `path` and reads its header.
    ///
    /// # Errors
    /// As [`NpyReader::open`].
    fn open(path: &Path) -> Result<Self, PointsError> {
        let file = open_file(path)?;
        // The header by a few small reads (no read-ahead: the data are read by position).
        let header = NpyStream::new(file, path.display().to_string())?;
        Ok(Self {
            file: header.input,
            path: header.path,
            ty: header.ty,
            len: header.len,
            data_offset: header.consumed,
        })
    }

    /// The offset of point `i`'s data in the file (the end of the data past the last point).
    fn offset_of(&self, i: usize) -> u64 {
        let i = i.min(self.len) as u64;
        self.data_offset + 2 * self.ty.size() as u64 * i
    }

    /// Points `first..first + n` (cut at the end of the array) as stored, read into `scratch`
    /// and checked finite.
    ///
    /// # Errors
    /// As [`NpyStream::read_encoded`].
    fn read_encoded<'s>(
        &self,
        first: usize,
        n: usize,
        scratch: &'s mut Vec<u8>,
    ) -> Result<EncodedPoints<'s>, PointsError> {
        use std::os::unix::fs::FileExt;
        let n = n.min(self.len.saturating_sub(first));
        let offset = self.offset_of(first);
        read_run(self.ty, &self.path, self.len, first, n, scratch, |bytes| {
            self.file.read_exact_at(bytes, offset)
        })
    }
}

/// The element type and the number of points of a header dict for an `(N, 2)` array.
fn parse_points_header(text: &str, columns: usize) -> Result<(NpyType, usize), String> {
    let (descr, dims) = parse_dict(text)?;
    let ty = match descr {
        "<f8" | "=f8" | "f8" => NpyType::F64,
        "<f4" | "=f4" | "f4" => NpyType::F32,
        other => {
            return Err(format!(
                "element type {other:?}: points must be float64 ('<f8') or float32 ('<f4'), little-endian"
            ));
        }
    };
    let inner = shape_text(&dims);
    match dims[..] {
        [n, c] if c == columns as u64 && n <= MAX_NPY_POINTS => Ok((ty, n as usize)),
        [n, c] if c == columns as u64 => {
            Err(format!("{n} points: more than the limit {MAX_NPY_POINTS}"))
        }
        _ => Err(format!(
            "shape ({inner}): points must be an array of shape (N, {columns})"
        )),
    }
}

/// The shape's sizes as the header writes them, `3, 2` (`3,` for one).
fn shape_text(dims: &[u64]) -> String {
    match dims {
        [n] => format!("{n},"),
        _ => dims
            .iter()
            .map(u64::to_string)
            .collect::<Vec<_>>()
            .join(", "),
    }
}

/// The element type (`descr`) and the shape of a header dict in C order (a Fortran-order
/// array is refused).
fn parse_dict(text: &str) -> Result<(&str, Vec<u64>), String> {
    let value = |key: &str| -> Result<&str, String> {
        let k = format!("'{key}':");
        let at = text
            .find(&k)
            .ok_or_else(|| format!("header without '{key}'"))?;
        Ok(text[at + k.len()..].trim_start())
    };
    let descr = value("descr")?;
    let descr = descr
        .strip_prefix('\'')
        .and_then(|d| d.split('\'').next())
        .ok_or("header 'descr' is not a string")?;
    if value("fortran_order")?.starts_with("True") {
        return Err("Fortran-order array: write it in C order (numpy.ascontiguousarray)".into());
    }
    let shape = value("shape")?;
    let inner = shape
        .strip_prefix('(')
        .and_then(|s| s.split(')').next())
        .ok_or("header 'shape' is not a tuple")?;
    let dims = inner
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.parse::<u64>()
                .map_err(|_| format!("shape ({inner}) is not a tuple of sizes"))
        })
        .collect::<Result<_, _>>()?;
    Ok((descr, dims))
}

/// The values of a `.npy` file holding a 1-D array of float64 (little-endian, `'<f8'`) of at
/// most `max_len` values, as stored (grid edges: the caller checks the values). Read whole:
/// `max_len` bounds the memory.
///
/// # Errors
/// [`PointsError::Io`] if the file cannot be opened or read; [`PointsError::Npy`] for a file
/// that is not a `.npy` array, another element type, another shape than `(N,)`, more than
/// `max_len` values, or data that end early.
///
/// # Examples
///
/// ```
/// use rs_io::points::{NpyType, npy_header, read_npy_vector};
/// let path = std::env::temp_dir().join(format!("rs_io_doc_edges_{}.npy", std::process::id()));
/// let mut bytes = npy_header(NpyType::F64, &[3]);
/// for v in [0.0f64, 0.5, 2.0] {
///     bytes.extend_from_slice(&v.to_le_bytes());
/// }
/// std::fs::write(&path, &bytes).unwrap();
/// assert_eq!(read_npy_vector(&path, 10).unwrap(), [0.0, 0.5, 2.0]);
/// let too_many = read_npy_vector(&path, 2).unwrap_err().to_string();
/// assert!(too_many.ends_with("3 values: more than the limit of 2"), "{too_many}");
/// std::fs::remove_file(&path).unwrap();
/// ```
pub fn read_npy_vector(path: impl AsRef<Path>, max_len: usize) -> Result<Vec<f64>, PointsError> {
    let path = path.as_ref();
    let name = path.display().to_string();
    let fail = |message: String| PointsError::Npy {
        path: name.clone(),
        message,
    };
    let mut input = std::io::BufReader::new(open_file(path)?);
    let text = read_header_text(&mut input, &name)?;
    let (descr, dims) = parse_dict(&text).map_err(fail)?;
    if !matches!(descr, "<f8" | "=f8" | "f8") {
        return Err(fail(format!(
            "element type {descr:?}: expected float64 ('<f8'), little-endian"
        )));
    }
    let [len] = dims[..] else {
        return Err(fail(format!(
            "shape ({}): expected a 1-D array, shape (N,)",
            shape_text(&dims)
        )));
    };
    if len > max_len as u64 {
        return Err(fail(format!(
            "{len} values: more than the limit of {max_len}"
        )));
    }
    let len = len as usize;
    let mut bytes = vec![0u8; len * 8];
    input.read_exact(&mut bytes).map_err(|e| {
        fail(format!(
            "the data end before the {len} values the header announces ({e})"
        ))
    })?;
    Ok(bytes
        .chunks_exact(8)
        .map(|b| f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]]))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::Point;

    #[test]
    fn a_vector_is_read_whole_and_bad_ones_get_one_line() {
        let dir = std::env::temp_dir().join(format!("rs_io_npy_vector_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let put = |name: &str, bytes: &[u8]| {
            let p = dir.join(name);
            std::fs::write(&p, bytes).unwrap();
            p
        };
        let ok = put("ok.npy", &file(NpyType::F64, &[4], &[-1.0, 0.25, 0.5, 7.0]));
        assert_eq!(read_npy_vector(&ok, 4).unwrap(), [-1.0, 0.25, 0.5, 7.0]);
        let err = |p: &Path, max: usize| read_npy_vector(p, max).unwrap_err().to_string();
        assert!(err(&ok, 3).ends_with("4 values: more than the limit of 3"));
        let f32 = put("f32.npy", &file(NpyType::F32, &[2], &[0.0, 1.0]));
        assert!(err(&f32, 9).contains("element type \"<f4\": expected float64"));
        let two_d = put("2d.npy", &file(NpyType::F64, &[2, 2], &[0.0; 4]));
        assert!(err(&two_d, 9).contains("shape (2, 2): expected a 1-D array"));
        let short = put("short.npy", &file(NpyType::F64, &[3], &[0.0, 1.0]));
        assert!(err(&short, 9).contains("the data end before the 3 values"));
        let text = put("text.npy", b"0,1,2\n");
        assert!(err(&text, 9).contains("not a .npy file"));
        assert!(err(&dir.join("missing.npy"), 9).contains("missing.npy"));
        for e in [
            err(&f32, 9),
            err(&text, 9),
            err(&dir.join("missing.npy"), 9),
        ] {
            assert_eq!(e.lines().count(), 1, "{e}");
        }
        std::fs::remove_dir_all(&dir).ok();
    }

    fn file(ty: NpyType, shape: &[usize], values: &[f64]) -> Vec<u8> {
        let mut bytes = npy_header(ty, shape);
        for &v in values {
            match ty {
                NpyType::F32 => bytes.extend_from_slice(&(v as f32).to_le_bytes()),
                _ => bytes.extend_from_slice(&v.to_le_bytes()),
            }
        }
        bytes
    }

    /// Runs of `n` points: every point of `reader` with its run's number, or the first error.
    fn drain_runs(reader: &dyn PointsReader) -> Result<Vec<(usize, Point)>, PointsError> {
        let (mut run, mut all) = (PointRun::default(), Vec::new());
        while let Some((k, read)) = reader.next_run(&mut run) {
            read?;
            let crate::points::RunPoints::Npy(points) = run.points() else {
                panic!("a .npy run")
            };
            all.extend((0..points.len()).map(|i| (k, points.point(i))));
        }
        Ok(all)
    }

    fn runs_of(n: usize) -> RunSizes {
        RunSizes {
            npy_points: n,
            ..RunSizes::default()
        }
    }

    #[test]
    fn points_stream_in_runs() {
        let values: Vec<f64> = (0..14).map(|i| i as f64 * 0.25).collect();
        for ty in [NpyType::F64, NpyType::F32] {
            let bytes = file(ty, &[7, 2], &values);
            let r = NpyReader::new(&bytes[..], "t", runs_of(3)).unwrap();
            assert_eq!(
                (r.len(), r.element_type(), r.progress().by_position),
                (7, ty, false)
            );
            let pts = drain_runs(&r).unwrap();
            assert_eq!(pts.len(), 7);
            assert_eq!(pts[6], (2, Point::new(3.0, 3.25)));
            assert_eq!(r.progress().bytes_read, bytes.len() as u64);
            assert_eq!(r.progress().runs_taken, 3);
        }
    }

    /// Runs read by position, taken by three threads at once, give the points the stream
    /// gives; a file cut short and a non-finite coordinate are errors naming them.
    #[cfg(unix)]
    #[test]
    fn runs_read_by_position_match_the_stream() {
        let values: Vec<f64> = (0..22).map(|i| i as f64 * 0.375 - 2.0).collect();
        let path = std::env::temp_dir().join(format!("inrs-npy-runs-{}.npy", std::process::id()));
        for ty in [NpyType::F64, NpyType::F32] {
            let bytes = file(ty, &[11, 2], &values);
            std::fs::write(&path, &bytes).unwrap();
            let stream = drain_runs(&NpyReader::new(&bytes[..], "t", runs_of(4)).unwrap());
            let f = NpyReader::open(&path, runs_of(4)).unwrap();
            assert!(f.progress().by_position);
            assert_eq!(f.len(), 11);
            let taken = std::sync::Mutex::new(Vec::new());
            std::thread::scope(|s| {
                for _ in 0..3 {
                    s.spawn(|| {
                        let mut run = PointRun::default();
                        while let Some((k, read)) = f.next_run(&mut run) {
                            read.unwrap();
                            let crate::points::RunPoints::Npy(p) = run.points() else {
                                panic!("a .npy run")
                            };
                            let pts: Vec<_> = (0..p.len()).map(|i| (k, p.point(i))).collect();
                            taken.lock().unwrap().push((k, pts));
                        }
                    });
                }
            });
            let mut taken = taken.into_inner().unwrap();
            taken.sort_by_key(|t| t.0);
            let read: Vec<_> = taken.into_iter().flat_map(|t| t.1).collect();
            assert_eq!(Ok(read), stream.map_err(|e| e.to_string()));
            assert_eq!(
                (f.progress().runs_taken, f.progress().bytes_read),
                (3, bytes.len() as u64)
            );
        }
        std::fs::write(&path, file(NpyType::F64, &[5, 2], &[0.5; 6])).unwrap();
        let short = drain_runs(&NpyReader::open(&path, runs_of(2)).unwrap());
        let e = short.unwrap_err().to_string();
        assert!(e.contains("data end before the 5 points"), "{e}");
        let bad = [0.0, 1.0, 2.0, 3.0, f64::INFINITY, 5.0];
        std::fs::write(&path, file(NpyType::F64, &[3, 2], &bad)).unwrap();
        let bad = drain_runs(&NpyReader::open(&path, runs_of(2)).unwrap());
        let e = bad.unwrap_err().to_string();
        assert!(e.contains("point 2 is not finite"), "{e}");
        std::fs::remove_file(&path).unwrap();
    }

    #[test]
    fn bad_files_are_errors() {
        let cases: Vec<(Vec<u8>, &str)> = vec![
            (b"garbage".to_vec(), "not a .npy file"),
            (file(NpyType::F64, &[3], &[1.0, 2.0, 3.0]), "shape (N, 2)"),
            (file(NpyType::F64, &[2, 3], &[0.0; 6]), "shape (N, 2)"),
            (file(NpyType::I8, &[1, 2], &[]), "element type"),
            (file(NpyType::F64, &[4, 2], &[1.0; 6]), "the data end"),
            (
                file(NpyType::F64, &[1, 2], &[1.0, f64::NAN]),
                "point 0 is not finite",
            ),
            (
                {
                    let mut b = file(NpyType::F64, &[1, 2], &[1.0, 2.0]);
                    let at = b.windows(5).position(|w| w == b"False").unwrap();
                    b[at..at + 5].copy_from_slice(b"True ");
                    b
                },
                "Fortran-order",
            ),
        ];
        for (bytes, expected) in cases {
            let e = NpyReader::new(&bytes[..], "t", RunSizes::default())
                .and_then(|r| drain_runs(&r).map(drop));
            let e = e.unwrap_err().to_string();
            assert!(e.contains(expected), "{e} (expected {expected:?})");
        }
    }

    #[test]
    fn headers_have_a_fixed_length() {
        for shape in [[0usize].as_slice(), &[12345678901], &[5, 2]] {
            let h = npy_header(NpyType::F64, shape);
            assert_eq!(h.len(), NPY_HEADER_BYTES);
            assert_eq!(h.len() % 64, 0);
        }
    }
}
