//! `inrs info`: a summary of a domain.

use clap::Args;
use inrs::DomainSummary;
use inrs::io::cad::CadModel;

use crate::args::DomainArg;
use crate::cli::error::CliError;
use crate::cli::output::write_text;

/// Print a summary of a domain: curves, Bezier pieces, loops, orientation, area, size. For a
/// STEP or IGES file without `#face:K`: one line per face (index, entity, surface, loops,
/// curves, (u, v) area and box, or why the face is refused).
#[derive(Args, Debug)]
pub(crate) struct InfoArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// Exit with an error if some loop does not close.
    #[arg(long)]
    require_closed: bool,
}

impl InfoArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let spec = self.domain.domain.to_string_lossy().into_owned();
        if let Some((file, None)) = inrs::io::cad::split_face_spec(&spec) {
            return self.list_faces(file);
        }
        let d = self.domain.load()?;
        if self.require_closed {
            d.require_closed().map_err(|e| self.domain.error(e))?;
        }
        write_text(None, &format!("{}\n", DomainSummary::of(&d)))
    }

    /// `inrs info part.step`: the faces of a CAD file, one per line; with `--require-closed`
    /// an error if some face is refused.
    fn list_faces(&self, file: &str) -> Result<(), CliError> {
        let model = CadModel::read(file).map_err(|e| CliError::Message(e.to_string()))?;
        let faces = model.face_summaries(self.domain.closure_tol);
        let refused = faces.iter().filter(|f| f.error.is_some()).count();
        let mut text = format!(
            "{file}: {} {} faces ({} read, {refused} refused); tolerance {}\n",
            faces.len(),
            model.format.name(),
            faces.len() - refused,
            model
                .tolerance
                .map_or_else(|| "not stated".to_string(), |t| format!("{t:e}")),
        );
        for f in &faces {
            text.push_str(&format!("{f}\n"));
        }
        write_text(None, &text)?;
        if self.require_closed && refused > 0 {
            return Err(CliError::Message(format!(
                "{file}: {refused} of {} faces are refused",
                faces.len()
            )));
        }
        Ok(())
    }
}
