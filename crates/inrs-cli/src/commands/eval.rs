//! `inrs eval`: a spline file's values at the points of a points file.

use std::path::PathBuf;

use std::sync::atomic::{AtomicUsize, Ordering};

use clap::Args;
use inrs::contain::PointSource;
use inrs::trispline::bb::{Jet, Order};
use inrs::trispline::{SplineEvaluator, load_spline};
use inrs::{NpyType, Point, PointQuery};

use crate::cli::error::CliError;
use crate::stream::{Column, PointsInput, stream_points, write_f64};

/// The spline's columns: the value, and with `gradient` also `dx,dy` (CSV only: `.npy` holds
/// the value); NaN outside the domain.
struct Jets {
    gradient: bool,
}

/// A jet with NaN everywhere: the value of a point outside the domain.
const OUTSIDE: Jet = Jet {
    value: f64::NAN,
    gradient: [f64::NAN; 2],
    hessian: [f64::NAN; 3],
};

impl Column<Option<Jet>> for Jets {
    fn header(&self) -> &str {
        if self.gradient {
            "x,y,value,dx,dy"
        } else {
            "x,y,value"
        }
    }
    fn initial(&self) -> Option<Jet> {
        None
    }
    fn csv(&self, value: Option<Jet>, out: &mut Vec<u8>) {
        let j = value.unwrap_or(OUTSIDE);
        write_f64(j.value, out);
        if self.gradient {
            out.push(b',');
            write_f64(j.gradient[0], out);
            out.push(b',');
            write_f64(j.gradient[1], out);
        }
    }
    fn npy_type(&self) -> NpyType {
        NpyType::F64
    }
    fn npy(&self, values: &[Option<Jet>], out: &mut Vec<u8>) {
        out.extend(
            values
                .iter()
                .flat_map(|j| j.unwrap_or(OUTSIDE).value.to_le_bytes()),
        );
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
        let input = PointsInput::open(&self.points, 1)?;
        let order = if self.derivatives {
            Order::Gradient
        } else {
            Order::Value
        };
        let values = Values {
            eval: &eval,
            order,
            outside: AtomicUsize::new(0),
        };
        stream_points(
            input,
            self.output.as_deref(),
            &Jets {
                gradient: self.derivatives,
            },
            std::slice::from_ref(&values),
        )?;
        let outside = values.outside.into_inner();
        if outside > 0 {
            eprintln!("{outside} points outside the domain: their values are nan");
        }
        Ok(())
    }
}

/// The spline's value (and gradient) at each point, counting the points outside the domain.
struct Values<'a> {
    eval: &'a SplineEvaluator<'a>,
    order: Order,
    outside: AtomicUsize,
}

impl PointQuery<Option<Jet>> for Values<'_> {
    fn value(&self, p: Point) -> Option<Jet> {
        let v = self.eval.evaluate(p, self.order);
        self.outside
            .fetch_add(usize::from(v.is_none()), Ordering::Relaxed);
        v
    }

    fn values_into<P: PointSource + ?Sized>(&self, points: &P, out: &mut [Option<Jet>]) {
        let mut missed = 0;
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.eval.evaluate(points.point(i), self.order);
            missed += usize::from(o.is_none());
        }
        self.outside.fetch_add(missed, Ordering::Relaxed);
    }
}
