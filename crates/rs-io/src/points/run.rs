//! Points files as numbered runs of points: the one [`PointsReader`] trait, for CSV and `.npy`
//! alike, and the [`PointRun`] it fills.

use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};

use rs_spline::Point;

use super::encoded::{EncodedPoints, NpyType};
use super::{PointRecord, PointsError};

/// How a points file is cut into runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RunSizes {
    /// Bytes of CSV per run: the lines that start in a range of that many bytes (read by
    /// position), or whole lines of about that many bytes (read in order).
    pub csv_bytes: usize,
    /// `.npy` points per run.
    pub npy_points: usize,
}

impl Default for RunSizes {
    /// Runs of 256 KiB: CSV lines, or 16 384 `.npy` float64 points. A run's bytes stay in the
    /// cache of the core that reads them until it has computed on them (a megabyte read at once
    /// cost another pass through memory), and the calls per run are few enough not to count.
    fn default() -> Self {
        Self {
            csv_bytes: 1 << 18,
            npy_points: 1 << 14,
        }
    }
}

/// A run of points of a points file, as a [`PointsReader`] reads it: its number in the file,
/// the points ([`PointRun::points`]) and, for CSV, the text they were written as (to echo
/// them unchanged). Its buffers are reused by the next read into it.
#[derive(Debug, Default)]
pub struct PointRun {
    /// The run's number.
    pub(super) index: usize,
    /// What the bytes hold.
    pub(super) content: Content,
    /// CSV: the lines; `.npy`: the points as stored, checked finite.
    pub(super) bytes: Vec<u8>,
    /// CSV: the points parsed.
    pub(super) points: Vec<Point>,
    /// CSV: per point, the byte ranges `[x_start, x_end, y_start, y_end]` of its two fields
    /// in `bytes`.
    pub(super) fields: Vec<[u32; 4]>,
}

/// What a run's bytes hold.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) enum Content {
    /// Nothing read (or a read that failed).
    #[default]
    Empty,
    /// CSV lines, parsed into the run's points and fields.
    Csv,
    /// `.npy` points of this type, as stored.
    Npy(NpyType),
}

impl PointRun {
    /// The run's number in its file: 0, 1, ... in file order (0 before a read).
    pub fn index(&self) -> usize {
        self.index
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        match self.content {
            Content::Empty => 0,
            Content::Csv => self.points.len(),
            Content::Npy(ty) => self.bytes.len() / (2 * ty.size()),
        }
    }

    /// True if the run holds no points (a run of CSV comments, say).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The points, with what echoes them.
    pub fn points(&self) -> RunPoints<'_> {
        match self.content {
            Content::Npy(ty) => RunPoints::Npy(EncodedPoints::from_checked(ty, &self.bytes)),
            // Empty: no points (see `start` and `fail`).
            Content::Csv | Content::Empty => RunPoints::Csv(CsvPoints {
                points: &self.points,
                text: &self.bytes,
                fields: &self.fields,
            }),
        }
    }

    /// Empties the run and numbers it `index`, for a read of `content` into it (its buffers
    /// kept).
    pub(super) fn start(&mut self, index: usize, content: Content) {
        self.index = index;
        self.content = content;
        self.points.clear();
        self.fields.clear();
    }

    /// Empties the run after a failed read, and hands the error on.
    pub(super) fn fail(&mut self, e: PointsError) -> PointsError {
        self.content = Content::Empty;
        self.points.clear();
        self.fields.clear();
        e
    }
}

/// The points of a [`PointRun`]: parsed from CSV with the text they were written as, or
/// `.npy` points as stored (read by index, never copied).
#[derive(Clone, Copy, Debug)]
pub enum RunPoints<'a> {
    /// Points parsed from CSV lines.
    Csv(CsvPoints<'a>),
    /// `.npy` points as stored.
    Npy(EncodedPoints<'a>),
}

impl RunPoints<'_> {
    /// The number of points.
    pub fn len(&self) -> usize {
        match self {
            Self::Csv(c) => c.points.len(),
            Self::Npy(e) => e.len(),
        }
    }

    /// True if there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Points parsed from CSV lines, with where their two fields stand in the lines' text (echo
/// them to reproduce the numbers exactly as written).
#[derive(Clone, Copy, Debug)]
pub struct CsvPoints<'a> {
    /// The points, in order.
    pub points: &'a [Point],
    text: &'a [u8],
    fields: &'a [[u32; 4]],
}

impl<'a> CsvPoints<'a> {
    /// Point `i`'s abscissa as written.
    ///
    /// # Panics
    /// If `i` is not less than the number of points.
    #[inline]
    pub fn x(&self, i: usize) -> &'a [u8] {
        let f = self.fields[i];
        &self.text[f[0] as usize..f[1] as usize]
    }

    /// Point `i`'s ordinate as written.
    ///
    /// # Panics
    /// If `i` is not less than the number of points.
    #[inline]
    pub fn y(&self, i: usize) -> &'a [u8] {
        let f = self.fields[i];
        &self.text[f[2] as usize..f[3] as usize]
    }

    /// Appends point `i` as `x,y`, both numbers as written.
    ///
    /// # Panics
    /// If `i` is not less than the number of points.
    #[inline]
    pub fn echo_into(&self, i: usize, out: &mut Vec<u8>) {
        let [x0, x1, y0, y1] = self.fields[i].map(|f| f as usize);
        if &self.text[x1..y0] == b"," {
            // `x,y` as written, in one copy.
            out.extend_from_slice(&self.text[x0..y1]);
        } else {
            out.extend_from_slice(&self.text[x0..x1]);
            out.push(b',');
            out.extend_from_slice(&self.text[y0..y1]);
        }
    }

    /// The bytes of the lines the points were read from: what echoing them all takes, at most.
    pub fn text_len(&self) -> usize {
        self.text.len()
    }

    /// Point `i` with its fields as written (invalid UTF-8 replaced, which the parser never
    /// lets through).
    ///
    /// # Panics
    /// If `i` is not less than the number of points.
    pub fn record(&self, i: usize) -> PointRecord {
        PointRecord {
            point: self.points[i],
            x_text: String::from_utf8_lossy(self.x(i)).into_owned(),
            y_text: String::from_utf8_lossy(self.y(i)).into_owned(),
        }
    }
}

/// A points file, CSV ([`CsvReader`](super::CsvReader)) or `.npy` ([`NpyReader`](super::NpyReader)), as runs of points numbered
/// 0, 1, ... in file order, for threads that each take the next run
/// ([`PointsReader::next_run`]) and compute on it. Memory is the runs in hand, whatever the
/// file's length.
///
/// A regular file is read by position (Unix): any number of threads read their runs at once,
/// and a run's bytes are still in the cache of the core that read them when it computes. Any
/// other input (a pipe, a CSV file that opens with a long block of comments) is read in order,
/// one run at a time, and each run is parsed on the thread that took it, outside the lock.
///
/// # Examples
///
/// ```
/// use rs_io::points::{CsvReader, PointRun, PointsReader, RunPoints, RunSizes};
/// let reader = CsvReader::new("x,y\n1,2\n3 ,4\n".as_bytes(), "input", RunSizes::default());
/// let (mut run, mut rows) = (PointRun::default(), Vec::new());
/// while let Some((k, read)) = reader.next_run(&mut run) {
///     read.unwrap();
///     if let RunPoints::Csv(points) = run.points() {
///         for i in 0..points.points.len() {
///             let mut row = Vec::new();
///             points.echo_into(i, &mut row);
///             rows.push((k, points.points[i].x, String::from_utf8(row).unwrap()));
///         }
///     }
/// }
/// assert_eq!(rows, [(0, 1.0, "1,2".to_string()), (0, 3.0, "3,4".to_string())]);
/// assert_eq!(reader.progress().runs_taken, 1);
/// ```
pub trait PointsReader: Sync {
    /// Reads the next run into `run`, reusing its buffers, and numbers it `k` (0, 1, ... in
    /// file order); CSV is parsed on the calling thread. Any number of threads may take runs
    /// at once. `None` when the runs have run out, or after a read that failed (the input in
    /// order cannot be read past it); a run that fails on its own (a bad line) does not stop
    /// the others: the caller stops at the first failure in file order.
    ///
    /// # Errors
    /// The read's result comes with the run's number: [`PointsError::Line`] for a run's first
    /// bad line (or a line too long), with its number in the file; [`PointsError::Io`];
    /// [`PointsError::Npy`] for a `.npy` file cut short or holding a non-finite coordinate.
    fn next_run(&self, run: &mut PointRun) -> Option<(usize, Result<(), PointsError>)>;

    /// The number of points, if known before reading (`.npy`).
    fn points(&self) -> Option<usize>;

    /// How far the reading has come, and how it reads.
    fn progress(&self) -> ReadProgress;
}

/// How far a [`PointsReader`] has come ([`PointsReader::progress`]), and how it reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReadProgress {
    /// How many runs have been taken (the failed one included): all of them once
    /// [`PointsReader::next_run`] has run out.
    pub runs_taken: usize,
    /// Bytes of the file read so far, or covered by the runs taken (for progress reports).
    pub bytes_read: u64,
    /// Whether the runs are read by position (any number at once), rather than in order.
    pub by_position: bool,
}

/// How a reader reads: in order through its stream `S`, or by position in its file `F`.
#[derive(Debug)]
pub(super) enum Source<S, F> {
    /// In order, one run at a time.
    InOrder(InOrder<S>),
    /// By position (a regular file; `F` is uninhabited where that does not exist).
    ByPosition(Claims, F),
}

impl<S, F> Source<S, F> {
    /// How far the reading has come ([`PointsReader::progress`]).
    pub(super) fn progress(&self) -> ReadProgress {
        let (runs_taken, bytes_read) = match self {
            Source::InOrder(stream) => (stream.taken(), stream.bytes_read()),
            Source::ByPosition(claims, _) => (claims.taken(), claims.bytes_read()),
        };
        ReadProgress {
            runs_taken,
            bytes_read,
            by_position: matches!(self, Source::ByPosition(..)),
        }
    }
}

/// Runs read in order, one at a time: the reader behind a lock, whether it has ended, and the
/// counts.
#[derive(Debug)]
pub(super) struct InOrder<S> {
    state: Mutex<(S, bool)>,
    /// Runs taken.
    taken: AtomicUsize,
    /// Bytes read.
    read: AtomicU64,
}

impl<S> InOrder<S> {
    /// Runs of `reader`.
    pub(super) fn new(reader: S) -> Self {
        Self {
            state: Mutex::new((reader, false)),
            taken: AtomicUsize::new(0),
            read: AtomicU64::new(0),
        }
    }

    /// Takes the next run: numbers it and reads it with `read` under the lock (`Ok(None)` at
    /// the end of the input), then notes the bytes the reader has read (`bytes_read`). `None`
    /// once the input has ended or failed.
    pub(super) fn next<T>(
        &self,
        read: impl FnOnce(&mut S) -> Result<Option<T>, PointsError>,
        bytes_read: impl FnOnce(&S) -> u64,
    ) -> Option<(usize, Result<T, PointsError>)> {
        let mut state = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        let (reader, done) = &mut *state;
        if *done {
            return None;
        }
        let k = self.taken.load(Ordering::Relaxed);
        let result = read(reader).transpose();
        self.read.store(bytes_read(reader), Ordering::Relaxed);
        *done = !matches!(result, Some(Ok(_)));
        if result.is_some() {
            self.taken.store(k + 1, Ordering::Relaxed);
        }
        result.map(|r| (k, r))
    }

    /// Runs taken so far.
    pub(super) fn taken(&self) -> usize {
        self.taken.load(Ordering::Relaxed)
    }

    /// Bytes read so far.
    pub(super) fn bytes_read(&self) -> u64 {
        self.read.load(Ordering::Relaxed)
    }
}

/// Runs read by position: a counter hands out their numbers.
#[derive(Debug)]
pub(super) struct Claims {
    next: AtomicUsize,
    runs: usize,
    /// Where the runs taken end, at the furthest.
    read: AtomicU64,
}

impl Claims {
    /// Claims on `runs` runs.
    pub(super) fn new(runs: usize) -> Self {
        Self {
            next: AtomicUsize::new(0),
            runs,
            read: AtomicU64::new(0),
        }
    }

    /// The next run's number, `None` past the last; `end(k)` is where run `k` ends in the
    /// file (for progress reports).
    pub(super) fn claim(&self, end: impl FnOnce(usize) -> u64) -> Option<usize> {
        let k = self.next.fetch_add(1, Ordering::Relaxed);
        if k >= self.runs {
            return None;
        }
        self.read.fetch_max(end(k), Ordering::Relaxed);
        Some(k)
    }

    /// Runs taken so far.
    pub(super) fn taken(&self) -> usize {
        self.next.load(Ordering::Relaxed).min(self.runs)
    }

    /// Where the runs taken end, at the furthest.
    pub(super) fn bytes_read(&self) -> u64 {
        self.read.load(Ordering::Relaxed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::points::{CsvReader, NpyReader, npy_header, open_points, parse_points};

    /// A point and its fields as written (empty for `.npy`).
    type Record = (Point, String, String);

    /// A run's number, and its records or error.
    type Drained = (usize, Result<Vec<Record>, String>);

    /// Every run of `reader`, taken by `threads` threads at once, as records; in file order, up
    /// to the first run that failed (its error then). Checks that the runs are numbered 0, 1,
    /// ... and all taken.
    fn drain(reader: &dyn PointsReader, threads: usize) -> Result<Vec<Record>, String> {
        let runs: Mutex<Vec<Drained>> = Mutex::default();
        std::thread::scope(|s| {
            for _ in 0..threads {
                s.spawn(|| {
                    let mut run = PointRun::default();
                    while let Some((k, read)) = reader.next_run(&mut run) {
                        assert_eq!(run.index(), k);
                        let records = read.map(|()| match run.points() {
                            RunPoints::Csv(c) => (0..c.points.len())
                                .map(|i| {
                                    let r = c.record(i);
                                    (r.point, r.x_text, r.y_text)
                                })
                                .collect(),
                            RunPoints::Npy(e) => (0..e.len())
                                .map(|i| (e.point(i), String::new(), String::new()))
                                .collect(),
                        });
                        let result = records.map_err(|e| e.to_string());
                        runs.lock().unwrap().push((k, result));
                    }
                });
            }
        });
        let mut runs = runs.into_inner().unwrap();
        runs.sort_by_key(|c| c.0);
        assert!(
            runs.iter().enumerate().all(|(i, c)| c.0 == i),
            "numbered in order"
        );
        assert_eq!(reader.progress().runs_taken, runs.len());
        let mut all = Vec::new();
        for (_, c) in runs {
            all.extend(c?);
        }
        Ok(all)
    }

    /// A file of its own for a test.
    fn scratch_file(name: &str, bytes: &[u8]) -> std::path::PathBuf {
        let path = std::env::temp_dir().join(format!("rs-io-runs-{}-{name}", std::process::id()));
        std::fs::write(&path, bytes).unwrap();
        path
    }

    /// The CSV and `.npy` files of the tests, as bytes.
    fn csv_text(lines: usize, bad_at: Option<usize>) -> Vec<u8> {
        let mut text = b"\xef\xbb\xbf# points\r\n\r\nx,y,kind\r\n".to_vec();
        for i in 0..lines {
            let line = match i % 5 {
                _ if Some(i) == bad_at => "1;2".to_string(),
                0 => format!("{},{}", i as f64 * 0.125, -(i as f64) / 3.0),
                1 => format!("  {i} , 2.5e-3 ,inside"),
                2 => format!("{i}\t{}", i * 7),
                3 => "# a comment".into(),
                _ => format!("-{i}.0,+{i}"),
            };
            text.extend_from_slice(line.as_bytes());
            text.extend_from_slice(if i % 2 == 0 { b"\n" } else { b"\r\n" });
        }
        text
    }

    fn npy_bytes(ty: NpyType, n: usize, announced: usize, bad: Option<usize>) -> Vec<u8> {
        let mut bytes = npy_header(ty, &[announced, 2]);
        for i in 0..n {
            let (x, y) = (i as f64 * 0.5 - 3.0, 1.0 / (i as f64 + 1.0));
            let x = if Some(i) == bad { f64::NAN } else { x };
            for v in [x, y] {
                match ty {
                    NpyType::F32 => bytes.extend_from_slice(&(v as f32).to_le_bytes()),
                    _ => bytes.extend_from_slice(&v.to_le_bytes()),
                }
            }
        }
        bytes
    }

    fn small(csv_bytes: usize) -> RunSizes {
        RunSizes {
            csv_bytes,
            npy_points: 37,
        }
    }

    /// Both readers, read in order or by position, give the points (and CSV fields as
    /// written) that the whole-file parse gives, whatever the run size and the number of
    /// threads; and its error, at the same line or point.
    #[test]
    fn both_readers_in_order_and_by_position_give_the_points_in_order() {
        let mut cases = 0;
        for bad_at in [None, Some(3), Some(999)] {
            let text = csv_text(1000, bad_at);
            let path = scratch_file("points.csv", &text);
            let want: Result<Vec<Record>, String> =
                parse_points(std::str::from_utf8(&text).unwrap())
                    .map(|v| {
                        v.into_iter()
                            .map(|r| (r.point, r.x_text, r.y_text))
                            .collect()
                    })
                    .map_err(|e| e.to_string());
            for csv_bytes in [7, 100, 1 << 18] {
                for threads in [1, 3] {
                    let in_order = CsvReader::new(&text[..], "t", small(csv_bytes));
                    let by_position = CsvReader::open(&path, small(csv_bytes)).unwrap();
                    // Runs of 7 bytes: the first holds only the comment, so the file is read in
                    // order.
                    assert_eq!(
                        by_position.progress().by_position,
                        cfg!(unix) && csv_bytes > 7
                    );
                    let readers: [&dyn PointsReader; 2] = [&in_order, &by_position];
                    for reader in readers {
                        assert_eq!(drain(reader, threads), want, "runs of {csv_bytes}");
                        cases += 1;
                    }
                }
            }
            std::fs::remove_file(&path).unwrap();
        }
        for ty in [NpyType::F64, NpyType::F32] {
            for (n, announced, bad) in [(100, 100, None), (100, 100, Some(77)), (90, 100, None)] {
                let bytes = npy_bytes(ty, n, announced, bad);
                let path = scratch_file("points.npy", &bytes);
                let whole = NpyReader::new(&bytes[..], "t", small(1)).unwrap();
                let want = drain(&whole, 1).map_err(|e| e.replace("t: ", ""));
                assert_eq!(want.is_ok(), bad.is_none() && n == announced, "{want:?}");
                for threads in [1, 3] {
                    let in_order = NpyReader::new(&bytes[..], "t", small(1)).unwrap();
                    let by_position = NpyReader::open(&path, small(1)).unwrap();
                    let readers: [&dyn PointsReader; 2] = [&in_order, &by_position];
                    for reader in readers {
                        assert_eq!(reader.points(), Some(announced));
                        // The error names the file: compare what follows its name.
                        let got = drain(reader, threads).map_err(|e| {
                            e.split_once(": ").map_or(e.clone(), |(_, m)| m.to_string())
                        });
                        assert_eq!(got, want, "{ty:?} {n} of {announced}, {bad:?}");
                        cases += 1;
                    }
                }
                std::fs::remove_file(&path).unwrap();
            }
        }
        assert_eq!(cases, 3 * 3 * 2 * 2 + 2 * 3 * 2 * 2);
    }

    /// Runs read in order are about the size asked for, even when the reads are larger; the
    /// bytes read follow the runs taken.
    #[test]
    fn runs_in_order_are_about_the_size_asked_for() {
        let text = csv_text(30000, None);
        let path = scratch_file("sizes.csv", &text);
        let in_order = CsvReader::new(&text[..], "t", small(1000));
        let by_position = CsvReader::open(&path, small(1000)).unwrap();
        let readers: [&dyn PointsReader; 2] = [&in_order, &by_position];
        for reader in readers {
            let mut run = PointRun::default();
            for k in 0..3 {
                let (taken, read) = reader.next_run(&mut run).unwrap();
                read.unwrap();
                assert_eq!(taken, k);
                let RunPoints::Csv(points) = run.points() else {
                    panic!("a CSV run")
                };
                // (The first run also holds the comments and the header.)
                assert!(
                    (1000..1100).contains(&points.text_len()),
                    "{}",
                    points.text_len()
                );
            }
            assert!(
                reader.progress().bytes_read >= 3000,
                "{}",
                reader.progress().bytes_read
            );
            assert!(reader.progress().bytes_read < text.len() as u64);
        }
        std::fs::remove_file(&path).unwrap();
    }

    /// Regular files are read by position, CSV files whose first run holds no data in order;
    /// the extension chooses the format.
    #[test]
    fn open_points_reads_regular_files_by_position() {
        let csv = scratch_file("open.csv", &csv_text(10, None));
        let comments = scratch_file("comments.csv", "# comment\n".repeat(100).as_bytes());
        let npy = scratch_file("open.NPY", &npy_bytes(NpyType::F64, 3, 3, None));
        let sizes = small(16);
        assert_eq!(
            open_points(&csv, sizes).unwrap().progress().by_position,
            cfg!(unix)
        );
        assert!(
            !open_points(&comments, sizes)
                .unwrap()
                .progress()
                .by_position
        );
        let reader = open_points(&npy, sizes).unwrap();
        assert_eq!(reader.progress().by_position, cfg!(unix));
        assert_eq!(reader.points(), Some(3));
        let e = open_points(csv.with_extension("missing"), sizes)
            .err()
            .unwrap();
        assert!(e.to_string().contains("missing"), "{e}");
        for path in [csv, comments, npy] {
            std::fs::remove_file(path).unwrap();
        }
    }

    /// A CSV run echoes each point's two fields as written, joined by a comma.
    #[test]
    fn csv_runs_echo_the_fields_as_written() {
        let reader = CsvReader::new(&b"1,2\n 3e0 \t-4\n5;6,7\n"[..], "t", small(1 << 10));
        let mut run = PointRun::default();
        let (_, read) = reader.next_run(&mut run).unwrap();
        assert!(read.is_err(), "5;6 is not a point");
        let reader = CsvReader::new(&b"1,2\n 3e0 \t-4\n"[..], "t", small(1 << 10));
        reader.next_run(&mut run).unwrap().1.unwrap();
        let RunPoints::Csv(points) = run.points() else {
            panic!("a CSV run")
        };
        let mut echoed = Vec::new();
        for i in 0..points.points.len() {
            points.echo_into(i, &mut echoed);
            echoed.push(b'\n');
        }
        assert_eq!(echoed, b"1,2\n3e0,-4\n");
        assert_eq!(run.points().len(), 2);
    }
}
