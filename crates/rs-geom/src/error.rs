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
    /// A parameter interval that is empty or not finite.
    #[error("empty parameter interval [{t0:?}, {t1:?}]")]
    EmptyInterval {
        /// Its start.
        t0: f64,
        /// Its end.
        t1: f64,
    },
    /// A hyperbola arc too long to convert (its rational quadratic pieces span one parameter
    /// unit each, at most [`crate::curve::MAX_HYPERBOLA_PIECES`]).
    #[error("hyperbola arc [{t0:?}, {t1:?}] longer than {max} parameter units")]
    HyperbolaTooLong {
        /// Its start.
        t0: f64,
        /// Its end.
        t1: f64,
        /// The most parameter units converted.
        max: usize,
    },
    /// Implicit conic coefficients of another kind than the one the file states.
    #[error("the coefficients describe a {found}, not the {expected} the form states")]
    ConicKindMismatch {
        /// The kind the discriminant gives.
        found: crate::ConicKind,
        /// The kind asked for.
        expected: crate::ConicKind,
    },
    /// Implicit conic coefficients with no real curve of their kind (an imaginary ellipse, a
    /// point, a pair of lines).
    #[error("the coefficients describe no real {0}")]
    NoRealConic(crate::ConicKind),
    /// An arc of an open conic (hyperbola, parabola) that starts and ends at one point.
    #[error("a {0} arc cannot start and end at the same point")]
    ClosedOpenConicArc(crate::ConicKind),
    /// Hyperbola arc ends on different branches.
    #[error("the arc's start and end are on different branches of the hyperbola")]
    EndsOnDifferentBranches,
    /// A point of an edge farther from the face's surface than its pcurve may bridge.
    #[error(
        "the edge is {distance:e} from the {surface} at its parameter {parameter:?} (more than {limit:e})"
    )]
    EdgeOffSurface {
        /// The kind of surface (`cylinder`, ...).
        surface: &'static str,
        /// The distance from the surface.
        distance: f64,
        /// The edge curve's parameter at that point.
        parameter: f64,
        /// The largest distance accepted.
        limit: f64,
    },
    /// An edge on an unbounded curve (a line, a conic) given without a parameter range.
    #[error("the edge's curve is unbounded and no parameter range was given")]
    UnboundedEdge,
    /// The work limit of a pcurve computation: the edge's `(u, v)` on the surface still jumps
    /// after the most samples allowed (the closest points of the edge are not continuous).
    #[error(
        "the edge's (u, v) on the {surface} jumps near its parameter {parameter:?} ({samples} samples, the work limit)"
    )]
    PcurveWorkLimit {
        /// The kind of surface.
        surface: &'static str,
        /// The edge curve's parameter where the jump is.
        parameter: f64,
        /// The samples taken.
        samples: usize,
    },
    /// A curve or surface that the spline layer refused.
    #[error(transparent)]
    Spline(#[from] rs_spline::SplineError),
}
