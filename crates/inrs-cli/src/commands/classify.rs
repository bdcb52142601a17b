//! `inrs classify`: inside, outside or boundary for every point of a points file, against one
//! domain (streamed) or several ([`super::classify_many`]).

use std::path::PathBuf;

use clap::Args;
use inrs::boxes::DEFAULT_SUBDIVISIONS;
use inrs::{ContainOptions, Containment, Location, NpyType};

use crate::args::{DomainsArg, FillRuleArg, MethodArg};
use crate::cli::error::CliError;
use crate::cli::limits::{self, parse_subdivisions, parse_tolerance};
use crate::stream::{Column, PointsInput, stream_points};

/// Inside, outside or boundary of a closed domain; writes CSV `x,y,location` in input order
/// (with several domains, `x,y` and one column per domain).
#[derive(Args, Debug)]
#[command(after_help = limits::AFTER_HELP)]
pub(crate) struct ClassifyArgs {
    #[command(flatten)]
    pub(super) domains: DomainsArg,
    /// The points file: CSV `x,y` per line (extra columns ignored; optional header; `#`
    /// comments), or `.npy` (float64 or float32, shape (N, 2)); streamed: any number of points.
    #[arg(long)]
    pub(super) points: PathBuf,
    /// The algorithm; all agree on closed domains.
    #[arg(long, value_enum, default_value_t = MethodArg::Fast)]
    pub(super) method: MethodArg,
    /// Which winding numbers are inside; every method honours it, on any loops (nested,
    /// overlapping, crossing themselves).
    #[arg(long, value_enum, default_value_t = FillRuleArg::EvenOdd)]
    pub(super) fill_rule: FillRuleArg,
    /// Write here instead of standard output: CSV, or `.npy` (int8: 0 outside, 1 inside,
    /// 2 boundary; shape (points, domains) with several domains) when the name ends in `.npy`.
    #[arg(long)]
    pub(super) output: Option<PathBuf>,
    /// Boundary tolerance relative to the bounding-box diagonal (>= 0, see below).
    #[arg(long, default_value = limits::DEFAULT_TOL, value_parser = parse_tolerance, allow_negative_numbers = true)]
    pub(super) tol: f64,
    /// The most sub-boxes per monotone piece (the paper's box refinement), 1 to 4096; a piece
    /// small against the domain gets fewer (about 64 boxes per diagonal of the domain), and a
    /// domain has at most about 131072 boxes.
    #[arg(long, default_value_t = DEFAULT_SUBDIVISIONS, value_parser = parse_subdivisions, allow_negative_numbers = true)]
    pub(super) subdivisions: usize,
    /// With several domains: leave out the columns of the domains (faces) that cannot be read
    /// or prepared (an open boundary, ...), naming each on standard error, instead of failing.
    #[arg(long)]
    pub(super) skip_unreadable: bool,
}

/// The `location` column: CSV labels, `.npy` int8 codes (0 outside, 1 inside, 2 boundary,
/// as the Python package returns them).
struct Locations;

impl Column<Location> for Locations {
    fn header(&self) -> &'static str {
        "x,y,location"
    }
    fn initial(&self) -> Location {
        Location::Outside
    }
    #[inline]
    fn csv(&self, value: Location, out: &mut Vec<u8>) {
        out.extend_from_slice(value.as_str().as_bytes());
    }
    fn npy_type(&self) -> NpyType {
        NpyType::I8
    }
    fn npy(&self, values: &[Location], out: &mut Vec<u8>) {
        out.extend(values.iter().map(|l| l.code() as u8));
    }
}

impl ClassifyArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let Some(domain) = self.domains.single() else {
            return super::classify_many::run(super::classify_many::ManyDomains {
                domains: &self.domains,
                points: &self.points,
                output: self.output.as_deref(),
                skip_unreadable: self.skip_unreadable,
                options: self.options(),
            });
        };
        let d = domain.load()?;
        let input = PointsInput::open(&self.points)?;
        let options = self.options();
        let containment = Containment::new(&d, options).map_err(|e| domain.error(e))?;
        // The library picks the algorithm for the whole stream's size.
        let engine = containment.engine(input.estimated_points());
        stream_points(input, self.output.as_deref(), &Locations, &engine)
    }

    /// The options of every domain.
    pub(super) fn options(&self) -> ContainOptions {
        ContainOptions::DEFAULT
            .with_relative_tolerance(self.tol)
            .with_subdivisions(self.subdivisions)
            .with_method(self.method.into())
            .with_fill_rule(self.fill_rule.into())
    }
}
