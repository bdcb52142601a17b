//! The `inrs` command-line tool.

use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use inrs::boxes::DEFAULT_SUBDIVISIONS;
use inrs::contain::DEFAULT_TOLERANCE;
use inrs::contain::{FillRule, QueryStats, WindingAlgorithm, WindingField};
use inrs::{Classifier, ContainOptions, Domain, DomainSummary, Method, PointRecord, read_points};

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
        /// The domain: a JSON file (CONTRACTS.md), an .svg or .dxf file, or a font glyph
        /// (`font.ttf#B`, `#U+0040`, `#gid:37`); every loop must close.
        #[arg(long)]
        domain: PathBuf,
        /// The points file (CSV `x,y` per line, optional header, `#` comments).
        #[arg(long)]
        points: PathBuf,
        /// Algorithm: fast (the default: inRS2 for small batches, the parallel grid point
        /// locator for large ones), inrs1 (each point against each box), inrs2 (sorted points,
        /// binary search per box) or gwn (rounded generalized winding number; the only one that
        /// accepts open or overlapping boundaries). All agree on closed domains.
        #[arg(long, default_value = "fast", value_parser = parse_method)]
        method: Method,
        /// Fill rule of --method gwn: even-odd (default; agrees with the crossing methods) or
        /// nonzero.
        #[arg(long, default_value = "even-odd", value_parser = parse_fill_rule)]
        fill_rule: FillRule,
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
    /// Generalized winding number of every point with respect to the curves of a domain file
    /// (any collection: open chains, gaps and overlaps are fine); writes CSV `x,y,winding`.
    Winding {
        /// The domain: JSON, .svg, .dxf or `font.ttf#glyph` (see classify).
        #[arg(long)]
        domain: PathBuf,
        /// The points file (CSV `x,y` per line, optional header, `#` comments).
        #[arg(long)]
        points: PathBuf,
        /// Write the CSV here instead of standard output.
        #[arg(long)]
        output: Option<PathBuf>,
        /// Per-curve algorithm: adaptive (the default, exact at any distance and at points on
        /// the curves), binary-search or bezier-clipping (ray-casting baselines).
        #[arg(long, default_value = "adaptive", value_parser = parse_algorithm)]
        algorithm: WindingAlgorithm,
    },
    /// Convert a domain (SVG, DXF, font glyph or JSON) to the JSON domain file format.
    Convert {
        /// The domain: JSON, .svg, .dxf or `font.ttf#glyph` (see classify).
        #[arg(long)]
        domain: PathBuf,
        /// Write the JSON here instead of standard output.
        #[arg(long)]
        output: Option<PathBuf>,
    },
    /// Print a summary of a domain file: curves, Bezier pieces, loops, orientation, area, size.
    Info {
        /// The domain: JSON, .svg, .dxf or `font.ttf#glyph` (see classify).
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

fn parse_fill_rule(s: &str) -> Result<FillRule, String> {
    match s {
        "even-odd" | "evenodd" => Ok(FillRule::EvenOdd),
        "nonzero" | "non-zero" => Ok(FillRule::NonZero),
        other => Err(format!(
            "unknown fill rule {other:?} (expected even-odd or nonzero)"
        )),
    }
}

fn parse_algorithm(s: &str) -> Result<WindingAlgorithm, String> {
    match s {
        "adaptive" => Ok(WindingAlgorithm::Adaptive),
        "binary-search" => Ok(WindingAlgorithm::BinarySearch),
        "bezier-clipping" => Ok(WindingAlgorithm::BezierClipping),
        other => Err(format!(
            "unknown algorithm {other:?} (expected adaptive, binary-search or bezier-clipping)"
        )),
    }
}

fn load_points(path: &PathBuf) -> Result<Vec<PointRecord>, String> {
    read_points(path).map_err(|e| match e {
        inrs::PointsError::Io { .. } => e.to_string(),
        other => format!("{}: {other}", path.display()),
    })
}

/// Writes a CSV with the given header and one `x,y,value` row per record.
fn write_csv<T: std::fmt::Display>(
    output: Option<&PathBuf>,
    header: &str,
    records: &[PointRecord],
    values: &[T],
) -> Result<(), String> {
    let sink: Box<dyn Write> = match output {
        Some(path) => {
            Box::new(std::fs::File::create(path).map_err(|e| format!("{}: {e}", path.display()))?)
        }
        None => Box::new(std::io::stdout().lock()),
    };
    let mut w = BufWriter::new(sink);
    let write_err = |e: std::io::Error| format!("writing output: {e}");
    writeln!(w, "{header}").map_err(write_err)?;
    for (r, v) in records.iter().zip(values) {
        writeln!(w, "{},{},{}", r.x_text, r.y_text, v).map_err(write_err)?;
    }
    w.flush().map_err(write_err)
}

/// Reads a domain: JSON, or (feature `io`) SVG, DXF or a font glyph `font.ttf#B`.
#[cfg(feature = "io")]
fn load_domain(path: &std::path::Path) -> Result<Domain, String> {
    let spec = path.to_string_lossy();
    inrs::io::load_domain(&spec).map_err(|e| match e {
        inrs::io::IoError::Read { .. }
        | inrs::io::IoError::Domain(inrs::DomainError::Io { .. })
        | inrs::io::IoError::UnknownFormat { .. } => e.to_string(),
        other => format!("{spec}: {other}"),
    })
}

/// Reads a JSON domain file.
#[cfg(not(feature = "io"))]
fn load_domain(path: &std::path::Path) -> Result<Domain, String> {
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
            fill_rule,
            output,
            tol,
            subdivisions,
        } => {
            let d = load_domain(&domain)?;
            let in_domain = |e: inrs::ContainError| format!("{}: {e}", domain.display());
            let locations = if method == Method::Gwn {
                let field = WindingField::new(&d, tol).map_err(in_domain)?;
                let records = load_points(&points)?;
                let pts: Vec<_> = records.iter().map(|r| r.point).collect();
                (records, field.classify(&pts, fill_rule))
            } else {
                let options = ContainOptions {
                    tolerance: tol,
                    subdivisions,
                };
                let classifier = Classifier::new(&d, options).map_err(in_domain)?;
                let records = load_points(&points)?;
                let pts: Vec<_> = records.iter().map(|r| r.point).collect();
                let loc = classifier.classify(&pts, method);
                (records, loc)
            };
            write_csv(output.as_ref(), "x,y,location", &locations.0, &locations.1)
        }
        Command::Winding {
            domain,
            points,
            output,
            algorithm,
        } => {
            let d = load_domain(&domain)?;
            let field = WindingField::new(&d, inrs::contain::DEFAULT_TOLERANCE)
                .map_err(|e| format!("{}: {e}", domain.display()))?;
            let records = load_points(&points)?;
            let mut stats = QueryStats::default();
            let values: Vec<f64> = records
                .iter()
                .map(|r| field.winding_number_with(r.point, algorithm, &mut stats))
                .collect();
            write_csv(output.as_ref(), "x,y,winding", &records, &values)
        }
        Command::Convert { domain, output } => {
            let d = load_domain(&domain)?;
            let json = d.to_json_string();
            match output {
                Some(path) => std::fs::write(&path, json + "\n")
                    .map_err(|e| format!("{}: {e}", path.display())),
                None => {
                    println!("{json}");
                    Ok(())
                }
            }
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
