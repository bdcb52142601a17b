//! `inrs eval`: a spline file's values at the points of a points file.

use std::path::PathBuf;

use clap::Args;
use inrs::NpyType;
use inrs::trispline::bb::{Jet, Order};
use inrs::trispline::load_spline;

use crate::cli::error::CliError;
use crate::stream::{Column, PointsInput, stream_points, write_f64};

/// The value column, NaN outside the domain.
pub(crate) struct Values;

/// Value and gradient columns.
pub(crate) struct Derivatives;

/// A jet with NaN everywhere: the value of a point outside the domain.
const OUTSIDE: Jet = Jet {
    value: f64::NAN,
    gradient: [f64::NAN; 2],
    hessian: [f64::NAN; 3],
};

/// The values of a run of jets as float64 `.npy` bytes (both columns write the value only).
fn npy_values(jets: &[Option<Jet>], out: &mut Vec<u8>) {
    out.extend(
        jets.iter()
            .flat_map(|j| j.unwrap_or(OUTSIDE).value.to_le_bytes()),
    );
}

impl Column<Option<Jet>> for Values {
    fn header(&self) -> &'static str {
        "x,y,value"
    }
    fn initial(&self) -> Option<Jet> {
        None
    }
    fn csv(&self, value: Option<Jet>, out: &mut Vec<u8>) {
        write_f64(value.unwrap_or(OUTSIDE).value, out);
    }
    fn npy_type(&self) -> NpyType {
        NpyType::F64
    }
    fn npy(&self, values: &[Option<Jet>], out: &mut Vec<u8>) {
        npy_values(values, out);
    }
}

impl Column<Option<Jet>> for Derivatives {
    fn header(&self) -> &'static str {
        "x,y,value,dx,dy"
    }
    fn initial(&self) -> Option<Jet> {
        None
    }
    fn csv(&self, value: Option<Jet>, out: &mut Vec<u8>) {
        let j = value.unwrap_or(OUTSIDE);
        write_f64(j.value, out);
        out.push(b',');
        write_f64(j.gradient[0], out);
        out.push(b',');
        write_f64(j.gradient[1], out);
    }
    fn npy_type(&self) -> NpyType {
        NpyType::F64
    }
    fn npy(&self, values: &[Option<Jet>], out: &mut Vec<u8>) {
        npy_values(values, out);
    }
}

/// A spline's values at the points of a points file; writes CSV `x,y,value` in input order.
///
/// Points on the boundary (within the boundary tolerance) evaluate like any other; points
/// outside the domain get `nan`, and their number is reported on standard error.
#[derive(Args, Debug)]
pub(crate) struct EvalArgs {
    /// The spline file (JSON, as `inrs fit` writes it).
    #[arg(long)]
    spline: PathBuf,
    /// The points file: CSV `x,y` per line, or `.npy` (float64 or float32, shape (N, 2)).
    #[arg(long)]
    points: PathBuf,
    /// Also write the gradient: columns `dx,dy`.
    #[arg(long)]
    derivatives: bool,
    /// Write here instead of standard output (`.npy`: the values as float64).
    #[arg(long)]
    output: Option<PathBuf>,
}

impl EvalArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let s = load_spline(&self.spline)
            .map_err(|e| CliError::Message(format!("{}: {e}", self.spline.display())))?;
        let eval = s
            .evaluator()
            .map_err(|e| CliError::Message(format!("{}: {e}", self.spline.display())))?;
        let input = PointsInput::open(&self.points)?;
        let outside = std::sync::atomic::AtomicUsize::new(0);
        let output = self.output.as_deref();
        // The evaluator at every point, counting those outside the domain.
        let at_points = |order: Order| {
            let (eval, outside) = (&eval, &outside);
            move |pts: &[inrs::Point], out: &mut [Option<Jet>]| {
                let mut missed = 0;
                for (o, &p) in out.iter_mut().zip(pts) {
                    *o = eval.evaluate(p, order);
                    missed += usize::from(o.is_none());
                }
                outside.fetch_add(missed, std::sync::atomic::Ordering::Relaxed);
            }
        };
        if self.derivatives {
            stream_points(input, output, &Derivatives, &at_points(Order::Gradient))?;
        } else {
            stream_points(input, output, &Values, &at_points(Order::Value))?;
        }
        let outside = outside.into_inner();
        if outside > 0 {
            eprintln!("{outside} points outside the domain: their values are nan");
        }
        Ok(())
    }
}
