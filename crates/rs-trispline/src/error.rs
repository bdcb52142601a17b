//! Errors of the spline layer.

use thiserror::Error;

/// Why a spline could not be built, read or evaluated.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum SplineError {
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
    /// A spline file that is not one.
    #[error("spline file: {0}")]
    File(String),
    /// The domain embedded in a spline file.
    #[error(transparent)]
    Io(#[from] rs_io::IoError),
}
