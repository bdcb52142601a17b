//! Positive interior cubature ([`inrs::cubature`]): a rule's nodes and weights as NumPy
//! arrays, and the integral of values computed at its nodes.

use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;

use inrs::contain::FillRule;
use inrs::cubature::{CubatureOptions, CubatureRule};

use crate::domain::NativeDomain;
use crate::errors::value_error;

/// A positive interior cubature rule of a domain (the native object behind `inrs.cubature`
/// and `Domain.integrate`): at most `(n + 1)(n + 2) / 2` nodes strictly inside the domain,
/// weights `> 0`, exact for polynomials of total degree `<= n` up to its residual.
#[pyclass(module = "inrs._inrs", name = "CubatureRule", frozen)]
pub(crate) struct NativeCubatureRule {
    rule: CubatureRule,
}

#[pymethods]
impl NativeCubatureRule {
    /// The rule of degree `degree` on the set `domain` fills under `fill_rule`:
    /// [`CubatureRule::with_options`] with the GIL released. Its errors (a degree above
    /// `MAX_DEGREE`, an open boundary, loops that cross, a domain too thin for the candidates,
    /// a residual not reached) are `ValueError`s with the library's one-line message.
    #[new]
    #[pyo3(signature = (domain, degree, fill_rule = "even-odd"))]
    fn new(
        py: Python<'_>,
        domain: &NativeDomain,
        degree: usize,
        fill_rule: &str,
    ) -> PyResult<Self> {
        let rule: FillRule = fill_rule.parse().map_err(value_error)?;
        let options = CubatureOptions::new(degree).with_fill_rule(rule);
        let d = &domain.domain;
        let rule = py
            .detach(|| CubatureRule::with_options(d, options))
            .map_err(value_error)?;
        Ok(Self { rule })
    }

    /// The nodes, an `(N, 2)` float64 array.
    fn nodes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let nodes = self.rule.nodes();
        let flat: Vec<f64> = nodes.iter().flat_map(|p| [p.x, p.y]).collect();
        flat.into_pyarray(py).reshape([nodes.len(), 2])
    }

    /// The weights, an `(N,)` float64 array, all `> 0`.
    fn weights<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.rule.weights().to_vec().into_pyarray(py)
    }

    /// The degree of exactness.
    #[getter]
    fn degree(&self) -> usize {
        self.rule.degree()
    }

    /// The relative moment residual ([`CubatureRule::residual`]).
    #[getter]
    fn residual(&self) -> f64 {
        self.rule.residual()
    }

    /// The candidates of the attempt that made the rule.
    #[getter]
    fn candidates(&self) -> usize {
        self.rule.candidates()
    }

    /// `sum_i w_i values[i]` ([`CubatureRule::integrate_values`]): a `ValueError` unless there
    /// is one value per node, or naming the first node whose value is not finite.
    fn integrate_values(&self, values: PyReadonlyArray1<'_, f64>) -> PyResult<f64> {
        let values = values.as_slice().map_err(value_error)?;
        self.rule.integrate_values(values).map_err(value_error)
    }
}
