//! `inrs winding`: the generalized winding number of every point.

use std::cell::OnceCell;
use std::path::PathBuf;

use clap::Args;
use inrs::NpyType;
use inrs::contain::WindingField;

use crate::args::{AlgorithmArg, DomainArg};
use crate::cli::error::CliError;
use crate::cli::limits::{self, parse_tolerance};
use crate::stream::{Column, PointsInput, stream_prepared, write_f64};

// The arguments of `inrs winding`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::Winding`.
#[derive(Args, Debug)]
#[command(after_help = limits::AFTER_HELP)]
pub(crate) struct WindingArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// The points file: CSV `x,y` per line (extra columns ignored; optional header; `#`
    /// comments), or `.npy` (float64 or float32, shape (N, 2)); streamed: any number of points.
    #[arg(long)]
    points: PathBuf,
    /// Write here instead of standard output: CSV, or `.npy` (float64) when the name ends in
    /// `.npy`.
    #[arg(long)]
    output: Option<PathBuf>,
    /// Per-curve algorithm.
    #[arg(long, value_enum, default_value_t = AlgorithmArg::Adaptive)]
    algorithm: AlgorithmArg,
    /// Boundary tolerance relative to the bounding-box diagonal (>= 0, see below): points this
    /// close to a curve get the average across the jump.
    #[arg(long, default_value = limits::DEFAULT_TOL, value_parser = parse_tolerance, allow_negative_numbers = true)]
    tol: f64,
}

/// The `winding` column: shortest round-trip decimal in CSV, float64 in `.npy`.
struct Windings;

impl Column<f64> for Windings {
    fn header(&self) -> &str {
        "x,y,winding"
    }
    fn initial(&self) -> f64 {
        0.0
    }
    #[inline]
    fn csv(&self, value: f64, out: &mut Vec<u8>) {
        write_f64(value, out);
    }
    fn npy_type(&self) -> NpyType {
        NpyType::F64
    }
    fn npy(&self, values: &[f64], out: &mut Vec<u8>) {
        out.extend(values.iter().flat_map(|v| v.to_le_bytes()));
    }
}

impl WindingArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        // A domain that cannot be read is named first.
        let input =
            PointsInput::open_after_errors_of(&self.points, 1, || self.domain.load().map(drop))?;
        // Prepared while the workers start reading the points. (The points file is opened
        // first: a named pipe with no writer yet is waited for before a bad domain is named.)
        let (field, numbers) = (OnceCell::new(), OnceCell::new());
        stream_prepared(input, self.output.as_deref(), |_| {
            let d = self.domain.load()?;
            let f = WindingField::new(&d, self.tol).map_err(|e| self.domain.error(e))?;
            let f: &WindingField = field.get_or_init(|| f);
            let numbers = numbers.get_or_init(|| [f.winding_numbers_by(self.algorithm.into())]);
            Ok((&Windings, &numbers[..]))
        })
    }
}
