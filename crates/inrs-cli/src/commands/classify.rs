//! `inrs classify`: inside, outside or boundary for every point of a points file.

use std::path::PathBuf;

use clap::Args;
use inrs::boxes::DEFAULT_SUBDIVISIONS;
use inrs::contain::{Locate, WindingField};
use inrs::{Classifier, ContainOptions, Method};

use crate::args::{DomainArg, FillRuleArg, MethodArg};
use crate::cli::error::CliError;
use crate::cli::limits::{self, parse_subdivisions, parse_tolerance};
use crate::stream::stream_points;

/// Inside, outside or boundary of a closed domain; writes CSV `x,y,location` in input order.
#[derive(Args, Debug)]
#[command(after_help = limits::AFTER_HELP)]
pub(crate) struct ClassifyArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// The points file: CSV `x,y` per line (extra columns ignored; optional header; `#`
    /// comments), streamed: any number of points.
    #[arg(long)]
    points: PathBuf,
    /// The algorithm; all agree on closed domains.
    #[arg(long, value_enum, default_value_t = MethodArg::Fast)]
    method: MethodArg,
    /// Fill rule of --method gwn.
    #[arg(long, value_enum, default_value_t = FillRuleArg::EvenOdd)]
    fill_rule: FillRuleArg,
    /// Write the CSV here instead of standard output.
    #[arg(long)]
    output: Option<PathBuf>,
    /// Boundary tolerance relative to the bounding-box diagonal (>= 0, see below).
    #[arg(long, default_value = limits::DEFAULT_TOL, value_parser = parse_tolerance, allow_negative_numbers = true)]
    tol: f64,
    /// Sub-boxes per monotone piece (the paper's box refinement), 1 to 4096; reduced
    /// automatically so that a domain has at most about 131072 boxes.
    #[arg(long, default_value_t = DEFAULT_SUBDIVISIONS, value_parser = parse_subdivisions, allow_negative_numbers = true)]
    subdivisions: usize,
}

impl ClassifyArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let d = self.domain.load()?;
        let output = self.output.as_deref();
        let method = Method::from(self.method);
        if method == Method::Gwn {
            // Open boundaries are fine here: no closed-domain classifier is built.
            let field = WindingField::new(&d, self.tol)
                .map_err(|e| self.domain.error(e))?
                .with_fill_rule(self.fill_rule.into());
            return stream_points(&self.points, output, "x,y,location", |pts| {
                field.locate_all(pts)
            });
        }
        let options = ContainOptions::DEFAULT
            .with_relative_tolerance(self.tol)
            .with_subdivisions(self.subdivisions)
            .with_method(method);
        let classifier = Classifier::new(&d, options).map_err(|e| self.domain.error(e))?;
        // The fast method builds its grid once, on the first batch large enough to pay for it,
        // and the classifier keeps it for every later batch.
        stream_points(&self.points, output, "x,y,location", |pts| {
            classifier.locate_all(pts)
        })
    }
}
