//! The `inrs` command-line tool: one module per subcommand in `commands/`, shared arguments
//! and option enums in `args`, errors, outputs and option limits in `cli`.

mod args;
mod cli;
mod commands;
mod stream;

use std::io::Write;
use std::process::ExitCode;

use clap::Parser;

use cli::error::CliError;
use commands::Command;

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

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    /// Every subcommand's arguments are consistent (clap's own checks, on the whole tree: a
    /// subcommand's arguments are otherwise defined only when it runs).
    #[test]
    fn the_whole_command_tree_passes_clap_checks() {
        Cli::command().debug_assert();
    }

    /// A subcommand's help, as `inrs --help` lists it (before its arguments are defined), is
    /// the one its own `--help` shows once they are: no doc comment of an argument struct (one
    /// flattened in, say) takes its place.
    #[test]
    fn each_subcommand_has_one_help_before_and_after_its_arguments_are_defined() {
        let listed = Cli::command();
        let mut built = Cli::command();
        built.build();
        let text = |s: Option<&clap::builder::StyledStr>| s.map(ToString::to_string);
        assert_eq!(listed.get_subcommands().count(), 13);
        for (a, b) in listed.get_subcommands().zip(built.get_subcommands()) {
            assert_eq!(a.get_name(), b.get_name());
            assert!(a.get_about().is_some(), "{}", a.get_name());
            assert_eq!(text(a.get_about()), text(b.get_about()), "{}", a.get_name());
            assert_eq!(
                text(a.get_long_about()),
                text(b.get_long_about()),
                "{}",
                a.get_name()
            );
            // Defined once built (never before: they are deferred).
            assert!(b.get_arguments().count() > 0, "{}", b.get_name());
        }
    }
}
