//! `inrs convert`: any domain to the JSON domain file.

use std::path::PathBuf;

use clap::Args;

use crate::args::DomainArg;
use crate::cli::error::CliError;
use crate::cli::output::write_text;

/// Convert a domain (SVG, DXF, font glyph, STEP/IGES face or JSON) to the JSON domain file format.
#[derive(Args, Debug)]
pub(crate) struct ConvertArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// Write the JSON here instead of standard output.
    #[arg(long)]
    output: Option<PathBuf>,
}

impl ConvertArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let d = self.domain.load()?;
        write_text(
            self.output.as_deref(),
            &(inrs::io::json::domain_to_json(&d) + "\n"),
        )
    }
}
