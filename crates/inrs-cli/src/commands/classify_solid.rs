//! `inrs classify --domain part.step#solid:K` (or `part.step`, every solid): inside, outside or
//! boundary of B-rep solids for points of space, read and written in runs.

use std::io::Write;
use std::path::Path;

use inrs::NpyType;
use inrs::geom::solid::{Location, SolidClassifier};
use inrs::io::cad::{CadModel, CadSelection, split_cad_spec};
use inrs::io::points::XyzReader;

use crate::cli::error::CliError;

/// Points per run.
const RUN: usize = 1 << 16;

/// The solids a `--domain` names: `Some((file, Some(k)))` for `part.step#solid:K`,
/// `Some((file, None))` for a CAD file without a selection (every solid); `None` otherwise.
pub(super) fn solid_spec(spec: &str) -> Option<(&str, Option<usize>)> {
    match split_cad_spec(spec)? {
        (file, None) => Some((file, None)),
        (file, Some(Ok(CadSelection::Solid(k)))) => Some((file, Some(k))),
        _ => None,
    }
}

/// Classifies the points of `points` against the solids, writing CSV `x,y,z,location` (a
/// column per solid, headed `solid:K`, for a whole file) or, for an output ending in `.npy`,
/// int8 codes of shape `(points,)` or `(points, solids)`.
pub(super) fn run(
    file: &str,
    solid: Option<usize>,
    points: &Path,
    output: Option<&Path>,
) -> Result<(), CliError> {
    let model = CadModel::read(file).map_err(|e| CliError::Message(e.to_string()))?;
    let indices: Vec<usize> = match solid {
        Some(k) => vec![k],
        None if model.solids.is_empty() => {
            return Err(CliError::Message(format!(
                "{file} has no solids: name a face with {file}#face:K (`inrs info --domain {file}` lists them)"
            )));
        }
        None => (0..model.solids.len()).collect(),
    };
    let classifiers = indices
        .iter()
        .map(|&k| {
            SolidClassifier::new(&model, k).map_err(|e| CliError::Message(format!("{file}: {e}")))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut reader = XyzReader::open(points).map_err(|e| CliError::Message(e.to_string()))?;
    let npy = output.is_some_and(|o| o.extension().is_some_and(|e| e.eq_ignore_ascii_case("npy")));
    let sink: Box<dyn Write> = match output {
        Some(o) => Box::new(
            std::fs::File::create(o)
                .map_err(|e| CliError::Message(format!("{}: {e}", o.display())))?,
        ),
        None => Box::new(std::io::stdout().lock()),
    };
    let mut out = std::io::BufWriter::new(sink);
    let write_err = |e: std::io::Error| {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            CliError::ClosedPipe
        } else {
            CliError::Message(format!("writing the output: {e}"))
        }
    };
    if !npy {
        let header = if solid.is_some() {
            "x,y,z,location".to_string()
        } else {
            let mut h = "x,y,z".to_string();
            for k in &indices {
                h.push_str(&format!(",solid:{k}"));
            }
            h
        };
        writeln!(out, "{header}").map_err(write_err)?;
    }
    // .npy: the codes (one byte a point and solid) are kept until the count is known.
    let mut codes: Vec<u8> = Vec::new();
    let mut count = 0usize;
    let mut columns = vec![Vec::new(); classifiers.len()];
    loop {
        let run = reader
            .next_run(RUN)
            .map_err(|e| CliError::Message(format!("{}: {e}", points.display())))?;
        if run.points.is_empty() {
            break;
        }
        for (c, col) in classifiers.iter().zip(&mut columns) {
            col.clear();
            col.resize(run.points.len(), Location::Outside);
            c.locate_into(&run.points, col);
        }
        for (i, text) in run.texts.iter().enumerate() {
            if npy {
                codes.extend(columns.iter().map(|col| col[i].code() as u8));
            } else {
                write!(out, "{text}").map_err(write_err)?;
                for col in &columns {
                    write!(out, ",{}", col[i].as_str()).map_err(write_err)?;
                }
                writeln!(out).map_err(write_err)?;
            }
        }
        count += run.points.len();
    }
    if npy {
        let shape = if solid.is_some() {
            vec![count]
        } else {
            vec![count, classifiers.len()]
        };
        out.write_all(&inrs::io::points::npy_header(NpyType::I8, &shape))
            .map_err(write_err)?;
        out.write_all(&codes).map_err(write_err)?;
    }
    out.flush().map_err(write_err)
}
