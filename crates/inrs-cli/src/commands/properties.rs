//! `inrs properties`: mass properties of the faces and solids of a CAD part.

use std::path::PathBuf;

use clap::Args;
use inrs::geom::properties::{FaceProperties, PropertiesError, SolidProperties};
use inrs::io::cad::{CadModel, CadSelection, split_cad_spec};
use inrs::significant;

use crate::cli::error::CliError;
use crate::cli::output::Output;
use crate::stream::write_f64;

// The arguments of `inrs properties`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::Properties`.
#[derive(Args, Debug)]
pub(crate) struct PropertiesArgs {
    /// The CAD file: `part.step` (every face and solid), `part.step#face:K` or
    /// `part.step#solid:K` (`.step`, `.stp`, `.igs`, `.iges`; `inrs info` lists them).
    #[arg(long)]
    domain: PathBuf,
    /// Write JSON (`unit`, `faces`, `solids`; numbers in shortest round-trip form) instead of
    /// a table.
    #[arg(long)]
    json: bool,
    /// Write here instead of standard output.
    #[arg(long)]
    output: Option<PathBuf>,
}

/// The faces and solids asked for, each with its index and its properties or why they could
/// not be computed (one line).
struct Report {
    faces: Vec<(usize, Result<FaceProperties, String>)>,
    solids: Vec<(usize, Result<SolidProperties, String>)>,
}

impl PropertiesArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let spec = self.domain.to_string_lossy().into_owned();
        let Some((file, selection)) = split_cad_spec(&spec) else {
            return Err(CliError::Message(format!(
                "{spec}: not a STEP or IGES file (.step, .stp, .igs, .iges): properties are \
                 those of a CAD part's faces and solids"
            )));
        };
        let selection = selection
            .transpose()
            .map_err(|e| CliError::Message(format!("{spec}: {e}")))?;
        let model = CadModel::read(file).map_err(|e| CliError::Message(e.to_string()))?;
        // One library call per case: the whole file, one face or one solid. A selection that
        // cannot be computed is an error: nothing else would be written.
        let selected = |e: PropertiesError| CliError::Message(format!("{spec}: {}", one_line(&e)));
        let report = match selection {
            None => {
                let p = model.properties();
                Report {
                    faces: p
                        .faces
                        .into_iter()
                        .map(with_one_line_error)
                        .enumerate()
                        .collect(),
                    solids: p
                        .solids
                        .into_iter()
                        .map(with_one_line_error)
                        .enumerate()
                        .collect(),
                }
            }
            Some(CadSelection::Face(k)) => Report {
                faces: vec![(k, Ok(model.face_properties(k).map_err(selected)?))],
                solids: Vec::new(),
            },
            Some(CadSelection::Solid(k)) => Report {
                faces: Vec::new(),
                solids: vec![(k, Ok(model.solid_properties(k).map_err(selected)?))],
            },
        };
        report.require_some(file)?;
        report.warn_unconverged(&spec);
        report.warn_leaks(&spec);
        let unit = model.length_unit.as_ref().map(|u| {
            u.symbol()
                .map_or_else(|| u.name.to_ascii_lowercase(), str::to_string)
        });
        let text = if self.json {
            report.json(unit.as_deref())
        } else {
            report.table(&spec, &model, unit.as_deref())
        };
        let mut out = Output::create(self.output.as_deref())?;
        out.write_str(&text)?;
        out.finish()
    }
}

/// How much of a solid's volume its leak may leave open before `inrs properties` warns (a
/// watertight boundary's leak is rounding, some `1e-16` of its area).
const LEAK_WARNING: f64 = 1e-9;

/// A result with its error as one line.
fn with_one_line_error<T>(r: Result<T, PropertiesError>) -> Result<T, String> {
    r.map_err(|e| one_line(&e))
}

/// `e`'s message on one line.
fn one_line(e: &impl std::fmt::Display) -> String {
    e.to_string()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

impl Report {
    /// An error when nothing was computed: a file without faces, or every face and solid
    /// refused (the first reason given).
    fn require_some(&self, file: &str) -> Result<(), CliError> {
        let computed = self.faces.iter().filter(|(_, r)| r.is_ok()).count()
            + self.solids.iter().filter(|(_, r)| r.is_ok()).count();
        if computed > 0 {
            return Ok(());
        }
        let first = self
            .faces
            .iter()
            .filter_map(|(_, r)| r.as_ref().err())
            .chain(self.solids.iter().filter_map(|(_, r)| r.as_ref().err()))
            .next();
        let plural = |n: usize, what: &str| format!("{n} {what}{}", if n == 1 { "" } else { "s" });
        Err(CliError::Message(match first {
            None => format!("{file}: the file has no faces"),
            Some(e) => format!(
                "{file}: no properties could be computed ({} and {} refused); the first: {e}",
                plural(self.faces.len(), "face"),
                plural(self.solids.len(), "solid"),
            ),
        }))
    }

    /// One warning line on standard error naming the faces and solids whose adaptive
    /// integration stopped at its bound of work before meeting its tolerance.
    fn warn_unconverged(&self, spec: &str) {
        let faces = self.faces.iter().filter_map(|(k, r)| {
            r.as_ref()
                .ok()
                .filter(|p| !p.converged)
                .map(|p| (k, p.error))
        });
        let solids = self.solids.iter().filter_map(|(k, r)| {
            r.as_ref()
                .ok()
                .filter(|p| !p.converged)
                .map(|p| (k, p.error))
        });
        let names: Vec<(String, f64)> = faces
            .map(|(k, e)| (format!("face {k}"), e))
            .chain(solids.map(|(k, e)| (format!("solid {k}"), e)))
            .collect();
        if names.is_empty() {
            return;
        }
        let worst = names.iter().fold(0.0f64, |m, (_, e)| m.max(*e));
        let list: Vec<&str> = names.iter().map(|(n, _)| n.as_str()).collect();
        eprintln!(
            "inrs: warning: {spec}: {} did not meet the integration tolerance within the bounded \
             work (largest error estimate {worst:.1e} of the model's size)",
            list.join(", ")
        );
    }

    /// One warning line on standard error per solid whose faces leave gaps enough to matter:
    /// the volume depends on the divergence theorem's reference point by up to the leak area
    /// times the distance between two such points over 3; with the part's size taken as the
    /// square root of its boundary's area, warned where that is above [`LEAK_WARNING`] of the
    /// volume.
    fn warn_leaks(&self, spec: &str) {
        for (k, p) in self
            .solids
            .iter()
            .filter_map(|(k, r)| Some((k, r.as_ref().ok()?)))
        {
            let spread = p.leak_area * p.area.abs().sqrt() / 3.0 / p.volume.abs();
            if spread > LEAK_WARNING {
                eprintln!(
                    "inrs: warning: {spec}: solid {k}: its faces leave gaps (net area vector of \
                     length {:.3e}, {:.1e} of its boundary's area): its volume depends on the \
                     reference point by about {spread:.1e} of itself, its moments likewise",
                    p.leak_area,
                    p.leak_area / p.area.abs()
                );
            }
        }
    }

    /// The largest error estimate of what was computed.
    fn largest_error(&self) -> f64 {
        let faces = self.faces.iter().filter_map(|(_, r)| r.as_ref().ok());
        let solids = self.solids.iter().filter_map(|(_, r)| r.as_ref().ok());
        faces
            .map(|p| p.error)
            .chain(solids.map(|p| p.error))
            .fold(0.0, f64::max)
    }

    /// `{"unit": ..., "faces": [...], "solids": [...]}` on one line.
    fn json(&self, unit: Option<&str>) -> String {
        let mut out = Vec::with_capacity(256 * (self.faces.len() + self.solids.len()) + 64);
        out.extend_from_slice(b"{\"unit\": ");
        out.extend_from_slice(
            unit.map_or_else(|| "null".to_string(), json_string)
                .as_bytes(),
        );
        out.extend_from_slice(b", \"faces\": [");
        json_entries(&self.faces, &mut out, |p, out| {
            out.extend_from_slice(b"\"area\": ");
            json_number(p.area, out);
            out.extend_from_slice(b", \"centroid\": ");
            json_array(&point(p.centroid), out);
        });
        out.extend_from_slice(b"], \"solids\": [");
        json_entries(&self.solids, &mut out, |p, out| {
            out.extend_from_slice(b"\"volume\": ");
            json_number(p.volume, out);
            out.extend_from_slice(b", \"area\": ");
            json_number(p.area, out);
            out.extend_from_slice(b", \"centroid\": ");
            json_array(&point(p.centroid), out);
            out.extend_from_slice(b", \"inertia\": ");
            json_matrix(&p.inertia, out);
            out.extend_from_slice(b", \"principal\": {\"moments\": ");
            json_array(&p.principal_moments, out);
            out.extend_from_slice(b", \"axes\": ");
            json_matrix(&p.principal_axes.map(point), out);
            out.extend_from_slice(b"}, \"leak_area\": ");
            json_number(p.leak_area, out);
        });
        out.extend_from_slice(b"]}\n");
        String::from_utf8(out).expect("JSON text is UTF-8")
    }

    /// A header line (the file, what it holds, the unit, the largest error estimate), then a
    /// table of the faces and one of the solids, numbers to 12 significant digits.
    fn table(&self, spec: &str, model: &CadModel, unit: Option<&str>) -> String {
        let plural = |n: usize, what: &str| format!("{n} {what}{}", if n == 1 { "" } else { "s" });
        let mut text = format!(
            "{spec}: {}, {}, {}; unit {}; largest error estimate {:.1e} of the model's size\n",
            model.format.name(),
            plural(model.faces.len(), "face"),
            plural(model.solids.len(), "solid"),
            unit.unwrap_or("not stated"),
            self.largest_error(),
        );
        if !self.faces.is_empty() {
            let rows = table_rows(&self.faces, |p| {
                vec![
                    significant(p.area),
                    triple(point(p.centroid), p.area.sqrt()),
                ]
            });
            text.push_str(&columns(&["face", "area", "centroid"], rows));
        }
        if !self.solids.is_empty() {
            if !self.faces.is_empty() {
                text.push('\n');
            }
            let rows = table_rows(&self.solids, |p| {
                vec![
                    significant(p.volume),
                    significant(p.area),
                    triple(point(p.centroid), p.area.sqrt()),
                    triple(p.principal_moments, 0.0),
                ]
            });
            text.push_str(&columns(
                &["solid", "volume", "area", "centroid", "principal moments"],
                rows,
            ));
        }
        text
    }
}

/// Three numbers to 12 significant digits of the largest of them and `scale` (a part's size
/// for a centroid): a number below `1e-12` of that is rounding noise about 0, written `0`.
fn triple(v: [f64; 3], scale: f64) -> String {
    let scale = v.iter().fold(scale, |m, x| m.max(x.abs()));
    v.iter()
        .map(|&x| {
            if x.abs() < 1e-12 * scale {
                "0".to_string()
            } else {
                significant(x)
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// A point's coordinates.
fn point(p: inrs::geom::Point3) -> [f64; 3] {
    [p.x, p.y, p.z]
}

/// A header and rows in columns two spaces apart, each as wide as its widest cell; a row
/// shorter than the header (an error) runs its last cell on past the columns it skips.
fn columns(header: &[&str], rows: Vec<Vec<String>>) -> String {
    let mut width: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for row in rows.iter().filter(|r| r.len() == header.len()) {
        for (w, cell) in width.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |cells: &[String]| {
        let mut l = String::new();
        for (i, cell) in cells.iter().enumerate() {
            if i + 1 == cells.len() {
                l.push_str(cell);
            } else {
                l.push_str(&format!("{cell:<w$}  ", w = width[i]));
            }
        }
        l.push('\n');
        l
    };
    let mut text = line(&header.iter().map(|h| h.to_string()).collect::<Vec<_>>());
    for row in &rows {
        text.push_str(&line(row));
    }
    text
}

/// The table rows of `entries`: the index, then `cells` of one computed, or `error: ...` for
/// one that could not be (the table's counterpart of [`json_entries`]).
fn table_rows<T>(
    entries: &[(usize, Result<T, String>)],
    cells: impl Fn(&T) -> Vec<String>,
) -> Vec<Vec<String>> {
    entries
        .iter()
        .map(|(k, r)| {
            let rest = match r {
                Ok(p) => cells(p),
                Err(e) => vec![format!("error: {e}")],
            };
            std::iter::once(k.to_string()).chain(rest).collect()
        })
        .collect()
}

/// The entries `{"index": K, ...}` of `entries`, comma-separated: `write` gives the fields of
/// one computed, [`json_error`] those of one that could not be.
fn json_entries<T>(
    entries: &[(usize, Result<T, String>)],
    out: &mut Vec<u8>,
    write: impl Fn(&T, &mut Vec<u8>),
) {
    for (i, (k, r)) in entries.iter().enumerate() {
        if i > 0 {
            out.extend_from_slice(b", ");
        }
        out.extend_from_slice(format!("{{\"index\": {k}, ").as_bytes());
        match r {
            Ok(p) => write(p, out),
            Err(e) => json_error(e, out),
        }
        out.push(b'}');
    }
}

/// A number in shortest round-trip form; `null` for one that is not finite (JSON has none).
fn json_number(v: f64, out: &mut Vec<u8>) {
    if v.is_finite() {
        write_f64(v, out);
    } else {
        out.extend_from_slice(b"null");
    }
}

fn json_array(v: &[f64; 3], out: &mut Vec<u8>) {
    out.push(b'[');
    for (i, &x) in v.iter().enumerate() {
        if i > 0 {
            out.extend_from_slice(b", ");
        }
        json_number(x, out);
    }
    out.push(b']');
}

fn json_matrix(m: &[[f64; 3]; 3], out: &mut Vec<u8>) {
    out.push(b'[');
    for (i, row) in m.iter().enumerate() {
        if i > 0 {
            out.extend_from_slice(b", ");
        }
        json_array(row, out);
    }
    out.push(b']');
}

fn json_error(e: &str, out: &mut Vec<u8>) {
    out.extend_from_slice(b"\"error\": ");
    out.extend_from_slice(json_string(e).as_bytes());
}

/// `s` as a JSON string.
fn json_string(s: &str) -> String {
    serde_json::to_string(s).expect("a string serialises")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn columns_align_and_errors_run_on() {
        let rows = vec![
            vec!["0".to_string(), "16".to_string(), "2, 0, 2".to_string()],
            vec!["10".to_string(), "error: no surface".to_string()],
        ];
        assert_eq!(
            columns(&["face", "area", "centroid"], rows),
            "face  area  centroid\n0     16    2, 0, 2\n10    error: no surface\n"
        );
    }

    #[test]
    fn noise_about_zero_is_zero_at_the_parts_scale() {
        assert_eq!(triple([-2.0, 1.4e-16, -2.2e-16], 4.0), "-2, 0, 0");
        assert_eq!(triple([2.3e-18, -3.1e-18, 6.3e-18], 10.0), "0, 0, 0");
        assert_eq!(
            triple([1e-3, 0.5, 1.0 / 3.0], 1.0),
            "0.001, 0.5, 0.333333333333"
        );
    }

    #[test]
    fn json_numbers_are_shortest_and_finite_or_null() {
        let mut out = Vec::new();
        json_array(&[16.0, 0.1, f64::NAN], &mut out);
        assert_eq!(String::from_utf8(out).unwrap(), "[16.0, 0.1, null]");
        assert_eq!(json_string("a \"b\""), "\"a \\\"b\\\"\"");
    }
}
