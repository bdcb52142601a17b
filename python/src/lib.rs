//! The native part of the `inrs` Python package: domains, classification and winding numbers on
//! NumPy arrays (the GIL released while Rust works, all cores by default), sampling, meshing and
//! splines. The Python layer (`inrs/__init__.py`) turns any array-like into the float64 arrays
//! these functions take (a copy only when the input is not float64); any memory layout is read
//! in place.
//!
//! - [`domain`]: `NativeDomain` (loading, classification, winding numbers, flattening);
//! - [`many`]: `classify_many` (many domains at once, spread over the cores);
//! - [`summary`]: `DomainSummary`, `LoopSummary`;
//! - [`points`]: the points' layouts and the per-chunk codes;
//! - [`mesh`]: `sample`, `sample_halton`, `mesh`; [`spline`]: `FitPlan`, `interpolate`, `NativeSpline`;
//! - [`convex`]: `convex_domain`; [`halton`]: `halton_points`;
//! - [`coverage`]: `cell_coverage` (area fractions, centroids and apertures on a grid),
//!   `coverage_band_rows` (the library's band height), `material_coverage` and
//!   `NativeMaterials` (several materials on one grid);
//! - [`cubature`]: `CubatureRule` (positive interior cubature: nodes, weights, integrals);
//! - [`formula`]: `Formula` (the command line's formulas, evaluated on arrays);
//! - [`threads`], [`errors`]: thread pools and exceptions.

mod cad;
mod convex;
mod coverage;
mod cubature;
mod domain;
mod errors;
mod formula;
mod halton;
mod many;
mod mesh;
mod points;
mod spline;
mod summary;
mod threads;

use pyo3::prelude::*;

use inrs::Location;
use inrs::contain::{DEFAULT_RELATIVE_TOLERANCE, FAST_METHOD_MIN_POINTS};
use inrs::convex::ConvexDomainOptions;

/// The native module `inrs._inrs`.
#[pymodule]
fn _inrs(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<domain::NativeDomain>()?;
    m.add_class::<summary::DomainSummary>()?;
    m.add_class::<cad::CadFace>()?;
    m.add_class::<cad::NativeCadModel>()?;
    m.add_function(wrap_pyfunction!(cad::cad_faces, m)?)?;
    m.add_function(wrap_pyfunction!(many::classify_many, m)?)?;
    m.add_class::<summary::LoopSummary>()?;
    m.add_class::<spline::NativeSpline>()?;
    m.add_class::<spline::FitPlan>()?;
    m.add_function(wrap_pyfunction!(mesh::sample, m)?)?;
    m.add_function(wrap_pyfunction!(mesh::sample_halton, m)?)?;
    m.add_function(wrap_pyfunction!(mesh::mesh, m)?)?;
    m.add_function(wrap_pyfunction!(spline::interpolate, m)?)?;
    m.add_function(wrap_pyfunction!(halton::halton_points, m)?)?;
    m.add_function(wrap_pyfunction!(convex::convex_domain, m)?)?;
    m.add_function(wrap_pyfunction!(coverage::cell_coverage, m)?)?;
    m.add_function(wrap_pyfunction!(coverage::coverage_band_rows, m)?)?;
    m.add_function(wrap_pyfunction!(coverage::material_coverage, m)?)?;
    m.add_class::<coverage::NativeMaterials>()?;
    m.add_class::<cubature::NativeCubatureRule>()?;
    m.add_class::<formula::NativeFormula>()?;
    m.add("MAX_CUBATURE_DEGREE", inrs::cubature::MAX_DEGREE)?;
    m.add("MAX_CELLS", inrs::coverage::MAX_CELLS)?;
    m.add("MAX_EDGES", inrs::coverage::MAX_EDGES)?;
    m.add(
        "DEFAULT_CONVEX_TOLERANCE",
        ConvexDomainOptions::DEFAULT.relative_tolerance,
    )?;
    m.add("OUTSIDE", Location::Outside.code())?;
    m.add("INSIDE", Location::Inside.code())?;
    m.add("BOUNDARY", Location::Boundary.code())?;
    m.add("DEFAULT_TOLERANCE", DEFAULT_RELATIVE_TOLERANCE)?;
    m.add("FAST_METHOD_MIN_POINTS", FAST_METHOD_MIN_POINTS)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
