//! Points of space for solids: CSV `x,y,z` lines or a `.npy` array of shape `(N, 3)`, read in
//! runs of at most a given number of points (bounded memory whatever the file's length).

use std::fs::File;
use std::io::{BufRead, BufReader, Read};
use std::path::Path;

use rs_spline::Point3;

use super::grammar::{content, first_fields, parse_number, shorten, too_long};
use super::npy::read_header;
use super::{MAX_LINE_BYTES, NpyType, PointsError};

/// A run of points of space, with the text of each as written (CSV: the line's first three
/// fields joined by commas; `.npy`: the shortest round-trip form).
#[derive(Clone, Debug, Default)]
pub struct XyzRun {
    /// The points.
    pub points: Vec<Point3>,
    /// Each point as written, `x,y,z`.
    pub texts: Vec<String>,
}

/// A reader of points of space: [`XyzReader::open`] picks CSV or `.npy` by the file's name.
pub struct XyzReader {
    path: String,
    source: Source,
}

enum Source {
    Csv {
        lines: BufReader<File>,
        line_no: usize,
        seen_data: bool,
    },
    Npy {
        input: BufReader<File>,
        f32: bool,
        remaining: usize,
    },
}

impl XyzReader {
    /// Opens `path`: `.npy` (float64 or float32, C order, shape `(N, 3)`) by its extension,
    /// CSV otherwise (`x,y,z` per line, split as 2-D points files are: at commas where the line
    /// has one, else at white space; extra fields
    /// ignored; blank lines, `#` comments and one header line `x,y,z` skipped).
    ///
    /// # Errors
    /// [`PointsError::Io`]; [`PointsError::Npy`] for a `.npy` file of another shape or type.
    pub fn open(path: impl AsRef<Path>) -> Result<XyzReader, PointsError> {
        let path = path.as_ref();
        let name = path.display().to_string();
        let io = |source| PointsError::Io {
            path: name.clone(),
            source,
        };
        let file = File::open(path).map_err(io)?;
        let is_npy = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
        let source = if is_npy {
            let mut input = BufReader::new(file);
            let (ty, remaining, _) = read_header(&mut input, &name, 3)?;
            Source::Npy {
                input,
                f32: ty == NpyType::F32,
                remaining,
            }
        } else {
            Source::Csv {
                lines: BufReader::new(file),
                line_no: 0,
                seen_data: false,
            }
        };
        Ok(XyzReader { path: name, source })
    }

    /// The next run of at most `max` points; an empty run at the end of the file.
    ///
    /// # Errors
    /// [`PointsError::Line`] for a line that is not three finite numbers (naming the line);
    /// [`PointsError::Npy`] for a `.npy` file cut short or holding a value that is not
    /// finite; [`PointsError::Io`].
    pub fn next_run(&mut self, max: usize) -> Result<XyzRun, PointsError> {
        let mut run = XyzRun::default();
        let path = self.path.clone();
        match &mut self.source {
            Source::Csv {
                lines,
                line_no,
                seen_data,
            } => {
                let mut line = String::new();
                while run.points.len() < max {
                    line.clear();
                    let n = lines
                        .by_ref()
                        .take(MAX_LINE_BYTES as u64 + 2)
                        .read_line(&mut line)
                        .map_err(|source| PointsError::Io {
                            path: path.clone(),
                            source,
                        })?;
                    if n == 0 {
                        break;
                    }
                    *line_no += 1;
                    if n > MAX_LINE_BYTES + 1 && !line.ends_with('\n') {
                        return Err(too_long(*line_no));
                    }
                    // The 2-D files' grammar: blank lines and comments, the field rule, the
                    // numbers.
                    let Some(text) = content(line.trim_start_matches('\u{feff}')) else {
                        continue;
                    };
                    let (fields, count) = first_fields::<3>(text);
                    let numbers: Vec<Option<f64>> = fields[..count]
                        .iter()
                        .map(|f| parse_number(f).filter(|x| x.is_finite()))
                        .collect();
                    if !*seen_data && numbers.first() == Some(&None) {
                        *seen_data = true; // a header line
                        continue;
                    }
                    *seen_data = true;
                    match numbers.as_slice() {
                        [Some(x), Some(y), Some(z)] => {
                            run.points.push(Point3::new(*x, *y, *z));
                            run.texts.push(fields.join(","));
                        }
                        _ => {
                            return Err(PointsError::Line {
                                line: *line_no,
                                message: format!(
                                    "expected three numbers \"x,y,z\" (a solid's points), got {:?}",
                                    shorten(text)
                                ),
                            });
                        }
                    }
                }
            }
            Source::Npy {
                input,
                f32,
                remaining,
            } => {
                let take = (*remaining).min(max);
                let width = if *f32 { 4 } else { 8 };
                let mut bytes = vec![0u8; take * 3 * width];
                input.read_exact(&mut bytes).map_err(|_| PointsError::Npy {
                    path: path.clone(),
                    message: "the data are cut short".into(),
                })?;
                *remaining -= take;
                for chunk in bytes.chunks_exact(3 * width) {
                    let v: [f64; 3] = std::array::from_fn(|k| {
                        let b = &chunk[k * width..(k + 1) * width];
                        if *f32 {
                            f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                        } else {
                            f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]])
                        }
                    });
                    if !v.iter().all(|x| x.is_finite()) {
                        return Err(PointsError::Npy {
                            path: path.clone(),
                            message: format!(
                                "point {} has a coordinate that is not finite",
                                run.points.len()
                            ),
                        });
                    }
                    run.points.push(Point3::from(v));
                    run.texts.push(format!("{},{},{}", v[0], v[1], v[2]));
                }
            }
        }
        Ok(run)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(name: &str, bytes: &[u8]) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("rs-io-xyz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join(name);
        std::fs::write(&p, bytes).unwrap();
        p
    }

    #[test]
    fn csv_runs_skip_headers_and_comments_and_name_bad_lines() {
        let p = write("a.csv", b"x,y,z\n# c\n1,2,3\n4 5 6 extra\n\n7,8,9\n");
        let mut r = XyzReader::open(&p).unwrap();
        let a = r.next_run(2).unwrap();
        assert_eq!(
            a.points,
            [Point3::new(1.0, 2.0, 3.0), Point3::new(4.0, 5.0, 6.0)]
        );
        assert_eq!(a.texts, ["1,2,3", "4,5,6"]);
        let b = r.next_run(2).unwrap();
        assert_eq!(b.points, [Point3::new(7.0, 8.0, 9.0)]);
        assert!(r.next_run(2).unwrap().points.is_empty());
        let p = write("b.csv", b"1,2,3\n1,2\n");
        let e = XyzReader::open(&p).unwrap().next_run(10).unwrap_err();
        assert_eq!(
            e.to_string(),
            "line 2: expected three numbers \"x,y,z\" (a solid's points), got \"1,2\""
        );
    }

    #[test]
    fn npy_of_shape_n_3_reads_and_other_shapes_are_refused() {
        let data: Vec<f64> = vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.5];
        let mut bytes = crate::points::npy_header(crate::points::NpyType::F64, &[2, 3]);
        bytes.extend(data.iter().flat_map(|x| x.to_le_bytes()));
        let p = write("a.npy", &bytes);
        let run = XyzReader::open(&p).unwrap().next_run(10).unwrap();
        assert_eq!(run.points[1], Point3::new(4.0, 5.0, 6.5));
        let mut bytes = crate::points::npy_header(crate::points::NpyType::F64, &[3, 2]);
        bytes.extend(data.iter().flat_map(|x| x.to_le_bytes()));
        let p = write("b.npy", &bytes);
        let e = XyzReader::open(&p).err().unwrap().to_string();
        assert!(
            e.ends_with("shape (3, 2): points must be an array of shape (N, 3)"),
            "{e}"
        );
    }
}
