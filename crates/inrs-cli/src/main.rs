//! The `inrs` command-line tool: one module per subcommand in `commands/`, shared arguments
//! and option enums in `args`, errors, outputs and option limits in `cli`.

mod args;
mod cli;
mod commands;
mod stream;

use std::io::Write;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

use cli::error::CliError;
use commands::{
    classify, convert, convex_domain, cubature, eval, fit, fractions, info, integrate, mesh,
    properties, sample, winding,
};

/// Exact point containment for planar domains bounded by NURBS curves.
#[derive(Parser)]
#[command(
    name = "inrs",
    version,
    about = "Exact point containment for planar domains bounded by NURBS and rational Bezier curves",
    after_help = cli::limits::AFTER_HELP
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    Classify(classify::ClassifyArgs),
    Winding(winding::WindingArgs),
    Convert(convert::ConvertArgs),
    Sample(sample::SampleArgs),
    Mesh(mesh::MeshArgs),
    Fit(fit::FitArgs),
    Eval(eval::EvalArgs),
    ConvexDomain(convex_domain::ConvexDomainArgs),
    Info(info::InfoArgs),
    Fractions(fractions::FractionsArgs),
    Cubature(cubature::CubatureArgs),
    Integrate(integrate::IntegrateArgs),
    Properties(properties::PropertiesArgs),
}

impl Command {
    fn run(self) -> Result<(), CliError> {
        match self {
            Command::Classify(a) => a.run(),
            Command::Winding(a) => a.run(),
            Command::Convert(a) => a.run(),
            Command::Sample(a) => a.run(),
            Command::Mesh(a) => a.run(),
            Command::Fit(a) => a.run(),
            Command::Eval(a) => a.run(),
            Command::ConvexDomain(a) => a.run(),
            Command::Info(a) => a.run(),
            Command::Fractions(a) => a.run(),
            Command::Cubature(a) => a.run(),
            Command::Integrate(a) => a.run(),
            Command::Properties(a) => a.run(),
        }
    }
}

/// A usage error as one line: clap's message without its usage block.
fn one_line(e: &clap::Error) -> String {
    let text = e.render().to_string();
    let message: Vec<&str> = text
        .lines()
        .take_while(|l| !l.trim().is_empty())
        .map(str::trim)
        .collect();
    let message = message.join(" ");
    message
        .strip_prefix("error: ")
        .unwrap_or(&message)
        .to_string()
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            // Help and version go to standard output; a closed pipe there is not an error.
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            // Usage errors: one line on standard error, clap's exit status 2.
            let _ = writeln!(
                std::io::stderr(),
                "inrs: {} (see inrs --help)",
                one_line(&e)
            );
            return ExitCode::from(2);
        }
    };
    match cli.command.run() {
        Ok(()) | Err(CliError::ClosedPipe) => ExitCode::SUCCESS,
        Err(CliError::Message(e)) => {
            let _ = writeln!(std::io::stderr(), "inrs: {e}");
            ExitCode::FAILURE
        }
    }
}
