//! `inrs info`: a summary of a domain.

use clap::Args;
use inrs::DomainSummary;

use crate::args::DomainArg;
use crate::cli::error::CliError;
use crate::cli::output::write_text;

/// Print a summary of a domain: curves, Bezier pieces, loops, orientation, area, size.
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
        let d = self.domain.load()?;
        if self.require_closed {
            d.require_closed().map_err(|e| self.domain.error(e))?;
        }
        write_text(None, &format!("{}\n", DomainSummary::of(&d)))
    }
}
