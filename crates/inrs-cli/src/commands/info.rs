//! `inrs info`: a summary of a domain.

use clap::Args;
use inrs::DomainSummary;
use inrs::geom::brep::ModelError;
use inrs::io::cad::{CadModel, CadSelection};

use crate::args::{DomainArg, FillRuleArg};
use crate::cli::error::CliError;
use crate::cli::output::write_text;

// The arguments of `inrs info`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::Info`.
#[derive(Args, Debug)]
pub(crate) struct InfoArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// Exit with an error if some loop does not close.
    #[arg(long)]
    require_closed: bool,
    /// The fill rule of the filled area.
    #[arg(long, value_enum, default_value_t = FillRuleArg::EvenOdd)]
    fill_rule: FillRuleArg,
}

impl InfoArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let spec = self.domain.domain.to_string_lossy().into_owned();
        match inrs::io::cad::split_cad_spec(&spec) {
            Some((file, None)) => return self.list_model(file, None),
            Some((file, Some(Ok(CadSelection::Solid(k))))) => {
                return self.list_model(file, Some(k));
            }
            _ => {}
        }
        let d = self.domain.load()?;
        if self.require_closed {
            d.require_closed().map_err(|e| self.domain.error(e))?;
        }
        let summary = DomainSummary::with_fill_rule(&d, self.fill_rule.into());
        write_text(None, &format!("{summary}\n"))
    }

    /// `inrs info part.step`: the solids of a CAD file with their shells, then its faces, one
    /// per line; `part.step#solid:K` the solid `K` and its faces only. With `--require-closed`
    /// an error if some face listed is refused.
    fn list_model(&self, file: &str, solid: Option<usize>) -> Result<(), CliError> {
        let model = CadModel::read(file).map_err(|e| CliError::Message(e.to_string()))?;
        let solids = model.solid_summaries();
        let (solids, faces): (Vec<_>, Vec<usize>) = match solid {
            None => (solids, (0..model.faces.len()).collect()),
            Some(k) => {
                let Some(s) = solids.into_iter().nth(k) else {
                    let e = ModelError::NoSolid {
                        index: k,
                        count: model.solids.len(),
                    };
                    return Err(CliError::Message(format!("{file}: {e}")));
                };
                let mut faces: Vec<usize> =
                    s.shells.iter().flat_map(|sh| sh.faces.clone()).collect();
                faces.sort_unstable();
                faces.dedup();
                (vec![s], faces)
            }
        };
        let all = model.face_summaries(self.domain.closure_tol);
        let listed: Vec<_> = faces.iter().filter_map(|&k| all.get(k)).collect();
        let refused = listed.iter().filter(|f| f.error.is_some()).count();
        let narrow = listed.iter().filter(|f| f.is_narrow()).count();
        let mut text = format!(
            "{file}: {} {} solid{}, {} shell{}, {} face{} ({} read, {refused} refused{}); tolerance {}\n",
            model.solids.len(),
            model.format.name(),
            if model.solids.len() == 1 { "" } else { "s" },
            model.shells.len(),
            if model.shells.len() == 1 { "" } else { "s" },
            model.faces.len(),
            if model.faces.len() == 1 { "" } else { "s" },
            all.len() - all.iter().filter(|f| f.error.is_some()).count(),
            if narrow > 0 {
                format!(", {narrow} narrower than their closure tolerance")
            } else {
                String::new()
            },
            model
                .tolerance
                .stated()
                .map_or_else(|| "not stated".to_string(), |t| format!("{t:e}")),
        );
        for s in &solids {
            text.push_str(&format!("{s}\n"));
        }
        if solid.is_none() {
            // The shells of no solid (open shells, and closed ones with free edges).
            let in_solids: Vec<usize> =
                model.solids.iter().flat_map(|s| s.shells.clone()).collect();
            for k in (0..model.shells.len()).filter(|k| !in_solids.contains(k)) {
                text.push_str(&format!("{}\n", model.shell_summary(k)));
            }
        }
        for f in &listed {
            text.push_str(&format!("{f}\n"));
        }
        write_text(None, &text)?;
        if self.require_closed && refused > 0 {
            return Err(CliError::Message(format!(
                "{file}: {refused} of {} faces are refused",
                listed.len()
            )));
        }
        Ok(())
    }
}
