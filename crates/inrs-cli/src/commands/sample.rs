//! `inrs sample`: well-spaced or Halton points in a domain.

use std::path::PathBuf;

use clap::Args;

use crate::args::{DomainArg, SampleMethod};
use crate::cli::error::CliError;
use crate::cli::limits::{parse_count, parse_ny};
use crate::cli::output::Output;

// The arguments of `inrs sample`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::Sample`.
#[derive(Args, Debug)]
pub(crate) struct SampleArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// How to sample: lines (the default), or halton when --count is given.
    #[arg(long, value_enum)]
    method: Option<SampleMethod>,
    /// Number of horizontal bands for --method lines: h = height / ny (2 to 100000; at most
    /// 10^7 points) [default: 20].
    #[arg(long, value_parser = parse_ny, allow_negative_numbers = true, conflicts_with = "count")]
    ny: Option<usize>,
    /// Number of points for --method halton (1 to 10^7) [default: 1000].
    #[arg(long, value_parser = parse_count, allow_negative_numbers = true)]
    count: Option<usize>,
    /// Write the CSV here instead of standard output.
    #[arg(long)]
    output: Option<PathBuf>,
}

/// What `inrs sample` was asked for once its options are put together.
#[derive(Debug, PartialEq)]
enum Sampling {
    Lines { ny: usize },
    Halton { count: usize },
}

impl SampleArgs {
    /// The sampling the options ask for: --count alone means Halton points; an option of the
    /// other method is an error (silently ignoring it would answer another question).
    fn sampling(&self) -> Result<Sampling, CliError> {
        let method = self.method.unwrap_or(if self.count.is_some() {
            SampleMethod::Halton
        } else {
            SampleMethod::Lines
        });
        match (method, self.ny, self.count) {
            (SampleMethod::Lines, _, Some(_)) => Err(CliError::Message(
                "--count is for --method halton; --method lines takes --ny".into(),
            )),
            (SampleMethod::Halton, Some(_), _) => Err(CliError::Message(
                "--ny is for --method lines; --method halton takes --count".into(),
            )),
            (SampleMethod::Lines, ny, None) => Ok(Sampling::Lines {
                ny: ny.unwrap_or(20),
            }),
            (SampleMethod::Halton, None, count) => Ok(Sampling::Halton {
                count: count.unwrap_or(1000),
            }),
        }
    }

    pub(crate) fn run(self) -> Result<(), CliError> {
        let sampling = self.sampling()?;
        let d = self.domain.load()?;
        let in_domain = |e: inrs::mesh::MeshError| self.domain.error(e);
        let mut out = Output::create(self.output.as_deref())?;
        writeln!(out, "x,y,kind")?;
        match sampling {
            Sampling::Lines { ny } => {
                let pts = inrs::mesh::well_spaced_points(&d, ny).map_err(in_domain)?;
                for b in pts.boundary.iter().flatten() {
                    writeln!(out, "{:?},{:?},boundary", b.point.x, b.point.y)?;
                }
                for p in &pts.interior {
                    writeln!(out, "{:?},{:?},interior", p.x, p.y)?;
                }
            }
            Sampling::Halton { count } => {
                for p in inrs::mesh::halton_points_in(&d, count).map_err(in_domain)? {
                    writeln!(out, "{:?},{:?},interior", p.x, p.y)?;
                }
            }
        }
        out.finish()
    }
}
