//! Errors of the cubature layer.

use rs_spline::{DomainError, Point};
use thiserror::Error;

/// Why a rule or a moment vector could not be made, or an integral taken.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum CubatureError {
    /// The degree is above [`MAX_DEGREE`](crate::MAX_DEGREE).
    #[error("degree {degree} is above the limit {max}")]
    DegreeTooHigh {
        /// The degree asked for.
        degree: usize,
        /// [`MAX_DEGREE`](crate::MAX_DEGREE).
        max: usize,
    },
    /// A loop of the boundary does not close (or a curve falls apart at a break).
    #[error("open boundary: {0}")]
    OpenBoundary(#[from] DomainError),
    /// The loops' nesting does not decide the fill (coincident or crossing loops, or too
    /// many loops: [`rs_contain::fill_nesting`]).
    #[error("{0}")]
    Nesting(rs_contain::NestingError),
    /// The containment index could not be built.
    #[error("containment: {0}")]
    Contain(#[from] rs_contain::ContainError),
    /// The adaptive quadrature of a rational piece hit its work bound before its tolerance.
    #[error("the moments on curve {curve} did not converge (error estimate {error:e})")]
    MomentsNotConverged {
        /// The curve whose piece did not converge.
        curve: usize,
        /// The quadrature's error estimate.
        error: f64,
    },
    /// The domain has no positive area (under the fill rule).
    #[error("the domain has no area (moment of 1 is {area:e})")]
    NoArea {
        /// The computed area.
        area: f64,
    },
    /// The domain's area is below [`SMALLEST_AREA`](crate::SMALLEST_AREA): its moments would
    /// be sums of subnormal numbers, short of the precision a rule needs.
    #[error(
        "the domain's area {area:e} is below {smallest:e}: its moments lose precision (scale the coordinates up)"
    )]
    AreaTooSmall {
        /// The computed area.
        area: f64,
        /// [`SMALLEST_AREA`](crate::SMALLEST_AREA).
        smallest: f64,
    },
    /// Too few candidate points fell strictly inside the domain, or they did not resolve the
    /// polynomials of the degree, after the bounded retries: the domain is too thin or too
    /// small against its bounding box.
    #[error(
        "the domain is too thin or too small for the candidates: {found} of the {generated} points tried are strictly inside (needed {needed}), {reason}"
    )]
    TooFewCandidates {
        /// Candidates found inside in the last attempt.
        found: usize,
        /// Points generated in the bounding box.
        generated: usize,
        /// Candidates wanted by the last attempt.
        needed: usize,
        /// What failed with them.
        reason: &'static str,
    },
    /// The compression did not reach the target residual after the bounded retries.
    #[error("residual {residual:e} above the target {target:e} with {candidates} candidates")]
    ResidualNotReached {
        /// The best residual reached.
        residual: f64,
        /// The target.
        target: f64,
        /// Candidates of the last attempt.
        candidates: usize,
    },
    /// The integrand was not finite at a node.
    #[error("integrand value {value} at node {index} ({x}, {y}) is not finite", x = point.x, y = point.y)]
    NonFiniteValue {
        /// The node's index in [`CubatureRule::nodes`](crate::CubatureRule::nodes).
        index: usize,
        /// The node.
        point: Point,
        /// The value.
        value: f64,
    },
    /// The values given do not match the nodes.
    #[error("{got} values given for {expected} nodes")]
    ValuesLength {
        /// The number of nodes.
        expected: usize,
        /// The number of values.
        got: usize,
    },
    /// An option is out of its documented range.
    #[error("option {name} = {value} is out of range ({range})")]
    InvalidOption {
        /// The option's field name.
        name: &'static str,
        /// Its value, as written.
        value: String,
        /// The range allowed.
        range: &'static str,
    },
}
