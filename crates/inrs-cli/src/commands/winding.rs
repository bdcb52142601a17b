//! `inrs winding`: the generalized winding number of every point.

use std::path::PathBuf;

use clap::Args;
use inrs::contain::{DEFAULT_RELATIVE_TOLERANCE, QueryStats, WindingField};

use crate::args::{AlgorithmArg, DomainArg};
use crate::cli::error::CliError;
use crate::stream::stream_points;

/// Generalized winding number of every point; writes CSV `x,y,winding`.
///
/// Any collection of curves is fine: open chains, gaps and overlaps.
#[derive(Args, Debug)]
pub(crate) struct WindingArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// The points file: CSV `x,y` per line (extra columns ignored; optional header; `#`
    /// comments), streamed: any number of points.
    #[arg(long)]
    points: PathBuf,
    /// Write the CSV here instead of standard output.
    #[arg(long)]
    output: Option<PathBuf>,
    /// Per-curve algorithm.
    #[arg(long, value_enum, default_value_t = AlgorithmArg::Adaptive)]
    algorithm: AlgorithmArg,
}

impl WindingArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let d = self.domain.load()?;
        let field =
            WindingField::new(&d, DEFAULT_RELATIVE_TOLERANCE).map_err(|e| self.domain.error(e))?;
        let algorithm = self.algorithm.into();
        let mut stats = QueryStats::default();
        stream_points(&self.points, self.output.as_deref(), "x,y,winding", |pts| {
            pts.iter()
                .map(|&q| field.winding_number_with(q, algorithm, &mut stats))
                .collect()
        })
    }
}
