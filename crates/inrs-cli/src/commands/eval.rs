//! `inrs eval`: a spline file's values at the points of a points file.

use std::cell::OnceCell;
use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use clap::Args;
use inrs::NpyType;
use inrs::trispline::bb::{Jet, Order};
use inrs::trispline::{Spline, TriSplineError, load_spline};

use crate::cli::error::CliError;
use crate::stream::{Column, PointsInput, stream_prepared, write_f64};

/// The spline's columns: the value, and with `gradient` also `dx,dy` (CSV only: `.npy` holds
/// the value); NaN outside the domain, counted as they are written.
struct Jets {
    gradient: bool,
    outside: AtomicUsize,
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
        self.outside
            .fetch_add(usize::from(value.is_none()), Ordering::Relaxed);
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
        let outside = values.iter().filter(|j| j.is_none()).count();
        self.outside.fetch_add(outside, Ordering::Relaxed);
        out.extend(
            values
                .iter()
                .flat_map(|j| j.unwrap_or(OUTSIDE).value.to_le_bytes()),
        );
    }
}

// The arguments of `inrs eval`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::Eval`.
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
        let named =
            |e: TriSplineError| CliError::Message(format!("{}: {e}", self.spline.display()));
        // A spline that cannot be read, or evaluated, is named first.
        let input = PointsInput::open_after_errors_of(&self.points, 1, || {
            let s = load_spline(&self.spline).map_err(named)?;
            s.evaluator().map(drop).map_err(named)
        })?;
        let order = if self.derivatives {
            Order::Gradient
        } else {
            Order::Value
        };
        // The library's evaluator is the query, streamed as classify streams its engine, and
        // prepared while the workers start reading the points.
        let column = Jets {
            gradient: self.derivatives,
            outside: AtomicUsize::new(0),
        };
        let (spline, eval) = (OnceCell::new(), OnceCell::new());
        stream_prepared(input, self.output.as_deref(), |_| {
            let s = load_spline(&self.spline).map_err(named)?;
            let s: &Spline = spline.get_or_init(|| s);
            let e = s.evaluator().map_err(named)?;
            let eval = eval.get_or_init(|| [e.with_order(order)]);
            Ok((&column, &eval[..]))
        })?;
        let outside = column.outside.into_inner();
        if outside > 0 {
            eprintln!("{outside} points outside the domain: their values are nan");
        }
        Ok(())
    }
}
