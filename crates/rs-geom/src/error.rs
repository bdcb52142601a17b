//! Errors of the geometry layer: each names what is wrong in one line.

use thiserror::Error;

/// Why a curve, surface or placement cannot be built or evaluated.
#[derive(Clone, Debug, Error, PartialEq)]
#[non_exhaustive]
pub enum GeomError {
    /// A placement's axes do not span space (a zero axis, or a reference direction along the
    /// axis).
    #[error("degenerate axes: {0}")]
    DegenerateFrame(&'static str),
    /// A number that must be finite is not, or a coordinate is beyond the input limits.
    #[error("{what} is not finite or too large: {value:e}")]
    NotFinite {
        /// What the number is (`radius`, `coordinate`, ...).
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// A length that must be positive is not.
    #[error("{what} must be positive, not {value:e}")]
    NotPositive {
        /// What the number is.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// A number outside the open interval it must lie in.
    #[error("{what} must lie strictly between {min:e} and {max:e}, not {value:e}")]
    OutOfRange {
        /// What the number is (`semi-angle`, ...).
        what: &'static str,
        /// Its value.
        value: f64,
        /// The interval's lower end (excluded).
        min: f64,
        /// The interval's upper end (excluded).
        max: f64,
    },
    /// A number or vector that must not be zero is zero.
    #[error("{what} must not be zero")]
    Zero {
        /// What is zero (`extrusion vector`, `parameter scale`, ...).
        what: &'static str,
    },
    /// A B-spline surface's control points do not fill its `rows x columns` net.
    #[error("a {rows} x {columns} control net needs {} points, got {got}", rows * columns)]
    ControlNetSize {
        /// Control points along `u` (the first knot vector's count).
        rows: usize,
        /// Control points along `v` (the second knot vector's count).
        columns: usize,
        /// Points given.
        got: usize,
    },
    /// A surface that only similarities keep in its kind (an elementary surface, a surface
    /// of revolution, an offset surface) mapped by an affine map that is not one.
    #[error(
        "a {surface} stays one only under rigid motions and uniform scalings; the map deviates from one by {deviation:e}"
    )]
    NotSimilarity {
        /// The kind of surface (`cylinder`, ...).
        surface: &'static str,
        /// The map's relative deviation from a similarity.
        deviation: f64,
    },
    /// Offsets and reparameterisations nested deeper than the limit.
    #[error("surfaces nested more than {limit} deep (offsets of offsets of ...)")]
    NestingTooDeep {
        /// The deepest nesting accepted.
        limit: usize,
    },
    /// A curve or surface that the spline layer refused.
    #[error(transparent)]
    Spline(#[from] rs_spline::SplineError),
}
