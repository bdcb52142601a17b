//! The domains of `inrs classify` against several domains (`--domain` repeated, or
//! `part.step#face:*`): read, labelled and prepared, each through the one decision of
//! `Containment` (the domains spread over the cores). `classify` then streams the points
//! through them as it streams them through one domain (`crate::stream`), one column per
//! domain: CSV `x,y,<label>,<label>,...` (coordinates echoed as written for CSV input, in
//! shortest round-trip form for `.npy` input), or an int8 `.npy` array of shape (points,
//! domains); any number of points, in bounded memory.

use std::path::Path;

use inrs::contain::ContainOptions;
use inrs::io::cad::CadModel;
use inrs::io::{IoError, LoadOptions};
use inrs::{Containment, Domain, prepare_many};

use crate::args::{DomainArg, DomainsArg, all_faces};
use crate::cli::error::CliError;

/// A domain of the command line with its column label, or why it could not be read.
struct Named {
    label: String,
    domain: Result<Domain, String>,
}

/// The domains of `domains` that can be read, with their labels (in the order given). One
/// that cannot be is named on standard error and left out with `skip`, else fails the run;
/// so does a file that cannot be read at all.
pub(super) fn read(domains: &DomainsArg, skip: bool) -> Result<Vec<(String, Domain)>, CliError> {
    let specs = &domains.domain;
    let mut named = Vec::new();
    for spec in specs {
        read_domains(spec, domains.closure_tol, specs.len() > 1, &mut named)?;
    }
    let mut read = Vec::with_capacity(named.len());
    for n in named {
        match n.domain {
            Ok(d) => read.push((n.label, d)),
            Err(e) => skip_or_fail(skip, e)?,
        }
    }
    Ok(read)
}

/// The domains prepared with `options` (in parallel), and their labels; one that cannot be
/// prepared is left out (naming it on standard error) with `skip`, else fails the run; so
/// does having none left.
pub(super) fn prepare(
    domains: Vec<(String, Domain)>,
    options: ContainOptions,
    skip: bool,
) -> Result<(Vec<String>, Vec<Containment>), CliError> {
    let (labels, domains): (Vec<String>, Vec<Domain>) = domains.into_iter().unzip();
    let prepared = prepare_many(&domains, options);
    let mut kept = (
        Vec::with_capacity(prepared.len()),
        Vec::with_capacity(prepared.len()),
    );
    for (label, result) in labels.into_iter().zip(prepared) {
        match result {
            Ok(c) => {
                kept.0.push(label);
                kept.1.push(c);
            }
            Err(e) => skip_or_fail(skip, format!("{label}: {e}"))?,
        }
    }
    if kept.1.is_empty() {
        return Err(CliError::Message(
            "no domain could be read and prepared (see the messages above)".into(),
        ));
    }
    Ok(kept)
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

#[cfg(test)]
mod tests {
    use super::*;

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
