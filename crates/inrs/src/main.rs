//! The `inrs` command-line tool.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use inrs::{Domain, DomainSummary};

/// Exact point containment for planar domains bounded by NURBS curves.
#[derive(Parser)]
#[command(name = "inrs", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print a summary of a domain file: curves, Bezier pieces, loops, orientation, area, size.
    Info {
        /// The domain file (JSON, see CONTRACTS.md).
        #[arg(long)]
        domain: PathBuf,
        /// Exit with an error if some loop does not close.
        #[arg(long)]
        require_closed: bool,
    },
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Info {
            domain,
            require_closed,
        } => {
            let d = Domain::from_json_file(&domain).map_err(|e| e.to_string())?;
            if require_closed {
                d.require_closed().map_err(|e| e.to_string())?;
            }
            println!("{}", DomainSummary::of(&d));
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("inrs: {e}");
            ExitCode::FAILURE
        }
    }
}
