//! `inrs eval`: a spline file's values at the points of a points file.

use std::path::PathBuf;

use clap::Args;
use inrs::trispline::bb::{Jet, Order};
use inrs::trispline::load_spline;

use crate::cli::error::CliError;
use crate::stream::{Column, PointsInput, stream_points, write_f64};

/// The value column, NaN outside the domain.
const VALUE: Column<Option<Jet>> = Column {
    header: "x,y,value",
    initial: None,
    csv: |j, out| write_f64(j.map_or(f64::NAN, |j| j.value), out),
    npy: (inrs::NpyType::F64, |js, out| {
        out.extend(
            js.iter()
                .flat_map(|j| j.map_or(f64::NAN, |j| j.value).to_le_bytes()),
        )
    }),
};

/// Value and gradient columns.
const DERIVATIVES: Column<Option<Jet>> = Column {
    header: "x,y,value,dx,dy",
    initial: None,
    csv: |j, out| {
        let j = j.unwrap_or(Jet {
            value: f64::NAN,
            gradient: [f64::NAN; 2],
            hessian: [f64::NAN; 3],
        });
        write_f64(j.value, out);
        out.push(b',');
        write_f64(j.gradient[0], out);
        out.push(b',');
        write_f64(j.gradient[1], out);
    },
    npy: (inrs::NpyType::F64, |js, out| {
        out.extend(
            js.iter()
                .flat_map(|j| j.map_or(f64::NAN, |j| j.value).to_le_bytes()),
        )
    }),
};

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
        let (column, order) = if self.derivatives {
            (&DERIVATIVES, Order::Gradient)
        } else {
            (&VALUE, Order::Value)
        };
        let outside = std::sync::atomic::AtomicUsize::new(0);
        stream_points(
            input,
            self.output.as_deref(),
            column,
            &|pts: &[inrs::Point], out: &mut [Option<Jet>]| {
                let mut missed = 0;
                for (o, &p) in out.iter_mut().zip(pts) {
                    *o = eval.evaluate(p, order);
                    missed += usize::from(o.is_none());
                }
                outside.fetch_add(missed, std::sync::atomic::Ordering::Relaxed);
            },
        )?;
        let outside = outside.into_inner();
        if outside > 0 {
            eprintln!("{outside} points outside the domain: their values are nan");
        }
        Ok(())
    }
}
