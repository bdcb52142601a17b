//! `inrs convert`: any domain to the JSON domain file.

use std::path::PathBuf;

use clap::Args;

use crate::args::DomainArg;
use crate::cli::error::CliError;
use crate::cli::output::write_text;

// The arguments of `inrs convert`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::Convert`.
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
