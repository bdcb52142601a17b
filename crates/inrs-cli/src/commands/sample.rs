//! `inrs sample`: well-spaced or Halton points in a domain.

use std::path::PathBuf;

use clap::Args;

use crate::args::{DomainArg, SampleMethod};
use crate::cli::error::CliError;
use crate::cli::limits::{parse_count, parse_ny};
use crate::cli::output::Output;

/// Sample points in a domain; writes CSV `x,y,kind` (kind `interior` or `boundary`).
///
/// Well-spaced points (Schumaker-Yu Algorithm 11.1: horizontal lines h apart cut exactly with
/// the boundary, interior points ~h apart, boundary points ~h apart by arc length) or the first
/// --count Halton points inside.
#[derive(Args, Debug)]
pub(crate) struct SampleArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// How to sample.
    #[arg(long, value_enum, default_value_t = SampleMethod::Lines)]
    method: SampleMethod,
    /// Number of horizontal bands for --method lines: h = height / ny (2 to 100000; at most
    /// 10^7 points).
    #[arg(long, default_value_t = 20, value_parser = parse_ny, allow_negative_numbers = true)]
    ny: usize,
    /// Number of points for --method halton (1 to 10^7).
    #[arg(long, default_value_t = 1000, value_parser = parse_count, allow_negative_numbers = true)]
    count: usize,
    /// Write the CSV here instead of standard output.
    #[arg(long)]
    output: Option<PathBuf>,
}

impl SampleArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let d = self.domain.load()?;
        let in_domain = |e: inrs::mesh::MeshError| self.domain.error(e);
        let mut out = Output::create(self.output.as_deref())?;
        writeln!(out, "x,y,kind")?;
        match self.method {
            SampleMethod::Lines => {
                let pts = inrs::mesh::well_spaced_points(&d, self.ny).map_err(in_domain)?;
                for b in pts.boundary.iter().flatten() {
                    writeln!(out, "{:?},{:?},boundary", b.point.x, b.point.y)?;
                }
                for p in &pts.interior {
                    writeln!(out, "{:?},{:?},interior", p.x, p.y)?;
                }
            }
            SampleMethod::Halton => {
                for p in inrs::mesh::halton_points_in(&d, self.count).map_err(in_domain)? {
                    writeln!(out, "{:?},{:?},interior", p.x, p.y)?;
                }
            }
        }
        out.finish()
    }
}
