//! The `inrs` command-line tool.

use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use inrs::boxes::DEFAULT_SUBDIVISIONS;
use inrs::contain::DEFAULT_TOLERANCE;
use inrs::{Classifier, ContainOptions, Domain, DomainSummary, Method, read_points};

const TOLERANCE_HELP: &str = "\
Boundary tolerance: with T = tol x (diagonal of the domain's bounding box), a point is 'boundary'
when its vertical or horizontal distance to the boundary curve is at most T. Every point within
Euclidean distance T/sqrt(2) of the boundary is 'boundary', none farther than T is; all other
points are 'inside' or 'outside' exactly (up to floating-point rounding, far below T). Default
tol = 1e-12 (relative).";

/// Exact point containment for planar domains bounded by NURBS curves.
#[derive(Parser)]
#[command(name = "inrs", version, about, after_help = TOLERANCE_HELP)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Classify points as inside, outside or boundary of a closed domain; writes CSV
    /// `x,y,location` in input order.
    #[command(after_help = TOLERANCE_HELP)]
    Classify {
        /// The domain file (JSON, see CONTRACTS.md); every loop must close.
        #[arg(long)]
        domain: PathBuf,
        /// The points file (CSV `x,y` per line, optional header, `#` comments).
        #[arg(long)]
        points: PathBuf,
        /// Algorithm: inrs1 (each point against each box) or inrs2 (sorted points, binary
        /// search per box; the default and the fastest). All give the same answers.
        #[arg(long, default_value = "inrs2", value_parser = parse_method)]
        method: Method,
        /// Write the CSV here instead of standard output.
        #[arg(long)]
        output: Option<PathBuf>,
        /// Boundary tolerance relative to the bounding-box diagonal (see below).
        #[arg(long, default_value_t = DEFAULT_TOLERANCE, allow_negative_numbers = true)]
        tol: f64,
        /// Sub-boxes per monotone piece (the paper's box refinement).
        #[arg(long, default_value_t = DEFAULT_SUBDIVISIONS)]
        subdivisions: usize,
    },
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

fn parse_method(s: &str) -> Result<Method, String> {
    s.parse()
}

fn load_domain(path: &PathBuf) -> Result<Domain, String> {
    Domain::from_json_file(path).map_err(|e| match e {
        inrs::DomainError::Io { .. } => e.to_string(),
        other => format!("{}: {other}", path.display()),
    })
}

fn run(cli: Cli) -> Result<(), String> {
    match cli.command {
        Command::Classify {
            domain,
            points,
            method,
            output,
            tol,
            subdivisions,
        } => {
            let d = load_domain(&domain)?;
            let options = ContainOptions {
                tolerance: tol,
                subdivisions,
            };
            let classifier =
                Classifier::new(&d, options).map_err(|e| format!("{}: {e}", domain.display()))?;
            let records = read_points(&points).map_err(|e| match e {
                inrs::PointsError::Io { .. } => e.to_string(),
                other => format!("{}: {other}", points.display()),
            })?;
            let pts: Vec<_> = records.iter().map(|r| r.point).collect();
            let locations = classifier.classify(&pts, method);
            let sink: Box<dyn Write> = match &output {
                Some(path) => Box::new(
                    std::fs::File::create(path).map_err(|e| format!("{}: {e}", path.display()))?,
                ),
                None => Box::new(std::io::stdout().lock()),
            };
            let mut w = BufWriter::new(sink);
            let write_err = |e: std::io::Error| format!("writing output: {e}");
            writeln!(w, "x,y,location").map_err(write_err)?;
            for (r, l) in records.iter().zip(&locations) {
                writeln!(w, "{},{},{}", r.x_text, r.y_text, l).map_err(write_err)?;
            }
            w.flush().map_err(write_err)
        }
        Command::Info {
            domain,
            require_closed,
        } => {
            let d = load_domain(&domain)?;
            if require_closed {
                d.require_closed()
                    .map_err(|e| format!("{}: {e}", domain.display()))?;
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
