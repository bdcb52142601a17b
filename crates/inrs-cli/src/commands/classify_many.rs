//! `inrs classify` against several domains (`--domain` repeated, or `part.step#face:*`): every
//! point of the points file against every domain, through the library's `locate_many` (the
//! domains spread over the cores, each through the one decision of `Containment`).
//!
//! Unlike the single-domain stream, the points are read into memory first: each domain answers
//! its whole batch on one core, which is what makes many small domains cheap. So that memory
//! stays bounded, at most [`MAX_POINTS`] points and [`MAX_ANSWERS`] answers (points times
//! domains) are taken; more is an error naming the limit. Output: CSV
//! `x,y,<label>,<label>,...` (coordinates echoed as written for CSV input, in shortest
//! round-trip form for `.npy` input), or an int8 `.npy` array of shape (points, domains).

use std::path::Path;

use inrs::contain::ContainOptions;
use inrs::io::cad::CadModel;
use inrs::io::{IoError, LoadOptions};
use inrs::{Domain, NpyType, Point, PointRecord};

use crate::args::{DomainArg, DomainsArg, all_faces};
use crate::cli::error::CliError;
use crate::cli::output::Output;
use crate::stream::{input_error, write_f64};

/// Rows of CSV formatted before they are handed to the output.
const ROWS_PER_WRITE: usize = 4096;

/// Most points read with several domains: they are held in memory with their text (about
/// 100 bytes a point, 1.6 GB at the limit).
pub(crate) const MAX_POINTS: usize = 1 << 24;

/// Most answers (points times domains) held in memory with several domains, a byte each.
pub(crate) const MAX_ANSWERS: usize = 1 << 31;

/// `Err` naming the limit when `points` points against `domains` domains would be more than
/// [`MAX_POINTS`] or [`MAX_ANSWERS`].
fn check_size(points: usize, domains: usize) -> Result<(), CliError> {
    if points > MAX_POINTS {
        return Err(CliError::Message(format!(
            "with several domains at most {MAX_POINTS} points are classified (they are held in \
             memory); split the points file, or classify against one domain at a time \
             (streamed, any size)"
        )));
    }
    if points.saturating_mul(domains) > MAX_ANSWERS {
        return Err(CliError::Message(format!(
            "{points} points against {domains} domains is more than {MAX_ANSWERS} answers held \
             in memory; split the points file or the domains"
        )));
    }
    Ok(())
}

/// A domain of the command line with its column label, or why it could not be read.
struct Named {
    label: String,
    domain: Result<Domain, String>,
}

/// The points of the file, with their text when it is CSV (echoed as written).
struct ReadPoints {
    points: Vec<Point>,
    texts: Option<Vec<(String, String)>>,
}

/// What `inrs classify` with several domains was asked: its arguments, read by `classify`
/// (this module does not import it back).
pub(super) struct ManyDomains<'a> {
    pub(super) domains: &'a DomainsArg,
    pub(super) points: &'a Path,
    pub(super) output: Option<&'a Path>,
    pub(super) skip_unreadable: bool,
    pub(super) options: ContainOptions,
}

pub(super) fn run(args: ManyDomains<'_>) -> Result<(), CliError> {
    let specs = &args.domains.domain;
    let mut named = Vec::new();
    for spec in specs {
        read_domains(spec, args.domains.closure_tol, specs.len() > 1, &mut named)?;
    }
    let (mut labels, mut domains) = (Vec::new(), Vec::new());
    for n in named {
        match n.domain {
            Ok(d) => {
                labels.push(n.label);
                domains.push(d);
            }
            Err(e) => skip_or_fail(args.skip_unreadable, e)?,
        }
    }
    let read = read_points(args.points)?;
    check_size(read.points.len(), domains.len())?;
    let found = inrs::locate_many(&domains, &read.points[..], args.options);
    let mut columns = Vec::with_capacity(found.len());
    let mut kept = Vec::with_capacity(found.len());
    for (label, result) in labels.into_iter().zip(found) {
        match result {
            Ok(locations) => {
                columns.push(locations);
                kept.push(label);
            }
            Err(e) => skip_or_fail(args.skip_unreadable, format!("{label}: {e}"))?,
        }
    }
    if kept.is_empty() {
        return Err(CliError::Message(
            "no domain could be read and prepared (see the messages above)".into(),
        ));
    }
    write(args.output, &read, &kept, &columns)
}

/// With `skip`, names the domain left out on standard error; else fails with `message`.
fn skip_or_fail(skip: bool, message: String) -> Result<(), CliError> {
    if skip {
        eprintln!("inrs: skipped {message}");
        Ok(())
    } else {
        Err(CliError::Message(message))
    }
}

/// Appends the domains of `spec` to `out`: every face of a CAD part for `part.step#face:*`
/// (labelled `face:K`, or `part.step#face:K` when `several` specifications are given), else
/// the one domain (labelled by its file name with any `#` selection). A file that cannot be
/// read at all is an error here; a face or domain that cannot be turned into a domain is kept
/// as its message (naming it), for the caller to skip or fail on.
fn read_domains(
    spec: &Path,
    closure: Option<f64>,
    several: bool,
    out: &mut Vec<Named>,
) -> Result<(), CliError> {
    let text = spec.to_string_lossy();
    let Some(file) = all_faces(&text) else {
        let label = spec
            .file_name()
            .map_or_else(|| text.to_string(), |n| n.to_string_lossy().into_owned());
        let one = DomainArg {
            domain: spec.to_path_buf(),
            closure_tol: closure,
        };
        let domain = one.load().map_err(|e| match e {
            CliError::Message(m) => m,
            CliError::ClosedPipe => format!("{text}: cannot be read"),
        });
        out.push(Named { label, domain });
        return Ok(());
    };
    let model = CadModel::read(file).map_err(|e| match e {
        IoError::Read { .. } | IoError::UnknownFormat { .. } => CliError::Message(e.to_string()),
        other => CliError::Message(format!("{file}: {other}")),
    })?;
    // As `load_domain_with` checks it for one face.
    let options = LoadOptions {
        closure_tolerance: closure,
    };
    let name = Path::new(file)
        .file_name()
        .map_or_else(|| file.to_string(), |n| n.to_string_lossy().into_owned());
    for (k, domain) in model
        .face_domains(options.closure_tolerance)
        .into_iter()
        .enumerate()
    {
        let label = if several {
            format!("{name}#face:{k}")
        } else {
            format!("face:{k}")
        };
        out.push(Named {
            label,
            domain: domain.map_err(|e| format!("{file}: {e}")),
        });
    }
    Ok(())
}

/// Every point of the file, by its extension: `.npy` (float64 or float32, (N, 2)) or CSV.
fn read_points(path: &Path) -> Result<ReadPoints, CliError> {
    let is_npy = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
    if is_npy {
        let mut npy = inrs::open_npy_points(path).map_err(|e| input_error(path, e))?;
        check_size(npy.len(), 1)?;
        let mut points = Vec::with_capacity(npy.len());
        // Each block is at least one point until the end: at most `len` blocks.
        for _ in 0..=npy.len() {
            if npy
                .read_block(1 << 16, &mut points)
                .map_err(|e| input_error(path, e))?
                == 0
            {
                break;
            }
        }
        return Ok(ReadPoints {
            points,
            texts: None,
        });
    }
    // One more than the limit is read, to tell a file at the limit from one beyond it.
    let records: Vec<PointRecord> = inrs::open_points(path)
        .map_err(|e| input_error(path, e))?
        .take(MAX_POINTS + 1)
        .collect::<Result<_, _>>()
        .map_err(|e| input_error(path, e))?;
    check_size(records.len(), 1)?;
    let points = records.iter().map(|r| r.point).collect();
    let texts = records.into_iter().map(|r| (r.x_text, r.y_text)).collect();
    Ok(ReadPoints {
        points,
        texts: Some(texts),
    })
}

/// Writes the columns: CSV `x,y,<labels>` rows, or `.npy` int8 of shape (points, domains)
/// when `output` ends in `.npy`; atomically into a file, or to standard output.
fn write(
    output: Option<&Path>,
    read: &ReadPoints,
    labels: &[String],
    columns: &[Vec<inrs::Location>],
) -> Result<(), CliError> {
    let n = read.points.len();
    let mut out = Output::create(output)?;
    let is_npy =
        output.is_some_and(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("npy")));
    if is_npy {
        out.write_bytes(&inrs::npy_header(NpyType::I8, &[n, columns.len()]))?;
        let mut bytes = Vec::with_capacity(ROWS_PER_WRITE * columns.len());
        for first in (0..n).step_by(ROWS_PER_WRITE) {
            bytes.clear();
            for i in first..(first + ROWS_PER_WRITE).min(n) {
                bytes.extend(columns.iter().map(|c| c[i].code() as u8));
            }
            out.write_bytes(&bytes)?;
        }
        return out.finish();
    }
    let mut header = String::from("x,y");
    for l in labels {
        header.push(',');
        header.push_str(&csv_field(l));
    }
    header.push('\n');
    out.write_str(&header)?;
    let mut bytes = Vec::new();
    for first in (0..n).step_by(ROWS_PER_WRITE) {
        bytes.clear();
        for i in first..(first + ROWS_PER_WRITE).min(n) {
            match &read.texts {
                Some(t) => {
                    bytes.extend_from_slice(t[i].0.as_bytes());
                    bytes.push(b',');
                    bytes.extend_from_slice(t[i].1.as_bytes());
                }
                None => {
                    write_f64(read.points[i].x, &mut bytes);
                    bytes.push(b',');
                    write_f64(read.points[i].y, &mut bytes);
                }
            }
            for c in columns {
                bytes.push(b',');
                bytes.extend_from_slice(c[i].as_str().as_bytes());
            }
            bytes.push(b'\n');
        }
        out.write_bytes(&bytes)?;
    }
    out.finish()
}

/// `s` as a CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_points_held_in_memory_are_bounded() {
        assert!(check_size(MAX_POINTS, MAX_ANSWERS / MAX_POINTS).is_ok());
        let message = |e| match e {
            CliError::Message(m) => m,
            CliError::ClosedPipe => String::new(),
        };
        let many = message(check_size(MAX_POINTS + 1, 1).unwrap_err());
        assert!(many.contains("at most 16777216 points"), "{many}");
        let answers = message(check_size(1 << 20, 1 << 12).unwrap_err());
        assert!(answers.contains("2147483648 answers"), "{answers}");
    }

    #[test]
    fn labels_with_commas_or_quotes_are_quoted() {
        assert_eq!(csv_field("face:3"), "face:3");
        assert_eq!(csv_field("a,b.json"), "\"a,b.json\"");
        assert_eq!(csv_field("say \"x\".json"), "\"say \"\"x\"\".json\"");
    }

    #[test]
    fn only_cad_files_name_all_their_faces() {
        assert_eq!(all_faces("dir/p.STEP#face:*"), Some("dir/p.STEP"));
        assert_eq!(all_faces("p.igs#FACE:*"), Some("p.igs"));
        assert_eq!(all_faces("p.step#face:3"), None);
        assert_eq!(all_faces("p.json#face:*"), None);
        assert_eq!(all_faces("#face:*"), None);
        assert_eq!(all_faces("é"), None);
    }
}
