//! Errors of the spline layer.

use thiserror::Error;

/// Why a spline on a curved triangulation could not be built, read or evaluated (the errors
/// of the boundary curves themselves are [`rs_spline::SplineError`]).
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum TriSplineError {
    /// A degree outside `1..=MAX_DEGREE`.
    #[error("degree {0} is out of range (1 to {max})", max = crate::bb::MAX_DEGREE)]
    Degree(usize),
    /// The triangulation could not be built or located in.
    #[error(transparent)]
    Mesh(#[from] rs_mesh::MeshError),
    /// The function to approximate is not finite at a point of the domain.
    #[error("the function is not finite at ({x}, {y}): {value}")]
    NotFinite {
        /// Abscissa.
        x: f64,
        /// Ordinate.
        y: f64,
        /// What it returned.
        value: f64,
    },
    /// A curved triangle leaves no room for an ordinary triangle inside it (its arcs bulge
    /// across its whole companion triangle).
    #[error(
        "curved triangle {triangle} is too thin for quasi-interpolation: its boundary arcs cover its companion triangle"
    )]
    ThinTriangle {
        /// The triangle.
        triangle: usize,
    },
    /// Scattered data that cannot be interpolated as given.
    #[error("data: {0}")]
    Data(String),
    /// A data point that cannot be used (`index` counts from 0).
    #[error("data point {} at ({x}, {y}) {reason}", index + 1)]
    DataPoint {
        /// Its place in the data, from 0.
        index: usize,
        /// Abscissa.
        x: f64,
        /// Ordinate.
        y: f64,
        /// What is wrong.
        reason: &'static str,
    },
    /// No neighbourhood of a point determines the first stage's local polynomial fit.
    #[error(
        "the data near ({x}, {y}) do not determine a local polynomial fit of degree {degree}: too few points, or nearly on a line or conic"
    )]
    IllPosedFit {
        /// Abscissa of the fit's centre.
        x: f64,
        /// Ordinate.
        y: f64,
        /// The fit's degree.
        degree: usize,
    },
    /// A triangulation that is not the refinement a space needs.
    #[error("{space} needs {needs}")]
    WrongTriangulation {
        /// The space.
        space: &'static str,
        /// What it needs.
        needs: &'static str,
    },
    /// The minimal-energy system was not solved to its tolerance.
    #[error(
        "the minimal-energy system did not converge: relative residual {residual:e} after {iterations} iterations"
    )]
    NotConverged {
        /// The last relative residual.
        residual: f64,
        /// Iterations taken.
        iterations: usize,
    },
    /// A spline file that is not one.
    #[error("spline file: {0}")]
    File(String),
    /// The domain embedded in a spline file.
    #[error(transparent)]
    Io(#[from] rs_io::IoError),
}
