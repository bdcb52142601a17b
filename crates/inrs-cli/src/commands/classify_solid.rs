//! `inrs classify --domain part.step#solid:K` (or `part.step`, every solid): inside, outside or
//! boundary of B-rep solids for points of space, read and written in runs.

use std::path::Path;

use inrs::geom::solid::{Location, PointQuery, SolidClassifier};
use inrs::io::cad::{CadModel, CadSelection, split_cad_spec};
use inrs::io::points::XyzReader;

use inrs::{NpyType, npy_header};

use crate::cli::error::CliError;
use crate::cli::output::Output;

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
/// int8 codes of shape `(points,)` or `(points, solids)`, run by run (bounded memory); a file
/// output appears only when the run succeeds.
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
    let shape = |count: usize| {
        if solid.is_some() {
            vec![count]
        } else {
            vec![count, classifiers.len()]
        }
    };
    let mut out = Output::create(output)?;
    if npy {
        // The count is written once known (a header of fixed length).
        out.write_bytes(&npy_header(NpyType::I8, &shape(0)))?;
    } else {
        let mut header = "x,y,z".to_string();
        if solid.is_some() {
            header.push_str(",location");
        } else {
            for k in &indices {
                header.push_str(&format!(",solid:{k}"));
            }
        }
        out.write_str(&header)?;
        out.write_str("\n")?;
    }
    let mut count = 0usize;
    let mut columns = vec![Vec::new(); classifiers.len()];
    let mut buffer = String::new();
    let mut codes: Vec<u8> = Vec::new();
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
            c.par_values_into(&run.points[..], col);
        }
        if npy {
            codes.clear();
            for i in 0..run.points.len() {
                codes.extend(columns.iter().map(|col| col[i].code() as u8));
            }
            out.write_bytes(&codes)?;
        } else {
            buffer.clear();
            for (i, text) in run.texts.iter().enumerate() {
                buffer.push_str(text);
                for col in &columns {
                    buffer.push(',');
                    buffer.push_str(col[i].as_str());
                }
                buffer.push('\n');
            }
            out.write_str(&buffer)?;
        }
        count += run.points.len();
    }
    if npy {
        out.rewrite_start(&npy_header(NpyType::I8, &shape(count)))?;
    }
    out.finish()
}
