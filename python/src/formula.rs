//! `Formula`: a formula in `x` and `y` parsed by the library's one grammar
//! ([`inrs::io::formula`], as `inrs fit --function` and `inrs integrate --function` read it)
//! and evaluated on NumPy arrays.

use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;

use inrs::Point;
use inrs::io::formula::Formula;

use crate::errors::value_error;

/// A parsed formula (the native object behind `inrs.Formula`).
#[pyclass(module = "inrs._inrs", name = "Formula", frozen)]
pub(crate) struct NativeFormula {
    formula: Formula,
}

#[pymethods]
impl NativeFormula {
    /// Parses `text`: a `ValueError` naming the column and what was expected there.
    #[new]
    fn new(text: &str) -> PyResult<Self> {
        Ok(Self {
            formula: Formula::parse(text).map_err(value_error)?,
        })
    }

    /// The formula as written.
    #[getter]
    fn text(&self) -> &str {
        self.formula.text()
    }

    /// The values at the points `(x[i], y[i])` (1-D float64 arrays of one length, any
    /// layout), the GIL released.
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'py, f64>,
        y: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (x, y) = (x.as_array(), y.as_array());
        if x.len() != y.len() {
            return Err(value_error(format!(
                "x and y must have one length, got {} and {}",
                x.len(),
                y.len()
            )));
        }
        let values: Vec<f64> = py.detach(|| {
            x.iter()
                .zip(y.iter())
                .map(|(&x, &y)| self.formula.at(Point::new(x, y)))
                .collect()
        });
        Ok(values.into_pyarray(py))
    }
}
