//! Error types for curves and domains.

use thiserror::Error;

use crate::Vector;
use crate::limits::{MAX_COORDINATE, MAX_WEIGHT_RATIO};

/// Checks what every rational curve needs of its control data: finite control points within
/// [`MAX_COORDINATE`], one weight per point, every weight finite and > 0, and a weight spread
/// within [`MAX_WEIGHT_RATIO`].
pub(crate) fn check_control_points<P: Vector>(
    points: &[P],
    weights: &[f64],
) -> Result<(), SplineError> {
    if let Some(index) = points.iter().position(|p| !p.all_finite()) {
        return Err(SplineError::NonFiniteControlPoint {
            index,
            x: points[index].coord(0),
            y: points[index].coord(1),
        });
    }
    let largest = |p: &P| (0..P::DIM).map(|i| p.coord(i).abs()).fold(0.0, f64::max);
    if let Some(index) = points.iter().position(|p| largest(p) > MAX_COORDINATE) {
        return Err(SplineError::LimitExceeded {
            what: "control point coordinate",
            value: largest(&points[index]),
            limit: MAX_COORDINATE,
        });
    }
    if weights.len() != points.len() {
        return Err(SplineError::WeightCountMismatch {
            weights: weights.len(),
            points: points.len(),
        });
    }
    if let Some(index) = weights.iter().position(|&w| !(w.is_finite() && w > 0.0)) {
        return Err(SplineError::NonPositiveWeight {
            index,
            value: weights[index],
        });
    }
    let (lo, hi) = weights
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &w| {
            (lo.min(w), hi.max(w))
        });
    // Compare as hi > lo * limit, which neither overflows nor underflows for the finite
    // positive weights checked above.
    if hi / MAX_WEIGHT_RATIO > lo {
        return Err(SplineError::LimitExceeded {
            what: "weight ratio max/min",
            value: hi / lo,
            limit: MAX_WEIGHT_RATIO,
        });
    }
    Ok(())
}

/// The weights rescaled by one power of two (exact: the curve and every point on it are
/// unchanged) so that the largest lies in `[2^-32, 2^32]`, keeping homogeneous coordinates
/// `w x` far from overflow and underflow. Weights already in range are returned as they are.
pub(crate) fn normalized_weights(mut weights: Vec<f64>) -> Vec<f64> {
    let hi = weights.iter().copied().fold(0.0f64, f64::max);
    let bound = 2f64.powi(32);
    if hi > bound || hi < 1.0 / bound {
        // hi = m 2^e with m in [0.5, 1): multiply by 2^-e (|e| <= 1075).
        let e = hi.log2().floor() as i32 + 1;
        for w in &mut weights {
            *w = crate::times_power_of_two(*w, -e);
        }
    }
    weights
}

/// Invalid curve data or an invalid request on a curve.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SplineError {
    /// Degree 0 curves are not supported.
    #[error("degree must be at least 1")]
    ZeroDegree,
    /// A control point index past the end.
    #[error("control point index {index} out of range (the curve has {count})")]
    ControlPointIndex {
        /// The index asked for.
        index: usize,
        /// Number of control points.
        count: usize,
    },
    /// Fewer control points than `degree + 1`.
    #[error("degree {degree} needs at least {needed} control points, got {got}")]
    TooFewControlPoints {
        /// Curve degree.
        degree: usize,
        /// `degree + 1`.
        needed: usize,
        /// Number given.
        got: usize,
    },
    /// Knot vector length is not `n + degree + 1`.
    #[error("expected {expected} knots (control points + degree + 1), got {got}")]
    WrongKnotCount {
        /// `n + degree + 1`.
        expected: usize,
        /// Number given.
        got: usize,
    },
    /// `knots` omitted although the curve is not a single Bezier piece.
    #[error(
        "knots may be omitted only when there are degree + 1 = {needed} control points, got {got}"
    )]
    MissingKnots {
        /// `degree + 1`.
        needed: usize,
        /// Number of control points given.
        got: usize,
    },
    /// A knot is NaN or infinite.
    #[error("knot {index} is not finite ({value:?})")]
    NonFiniteKnot {
        /// Knot index.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// `knots[index] < knots[index - 1]`.
    #[error("knots decrease at index {index}: {previous:?} > {value:?}")]
    DecreasingKnots {
        /// Index of the smaller knot.
        index: usize,
        /// The knot before it.
        previous: f64,
        /// The knot itself.
        value: f64,
    },
    /// The parameter domain `[knots[p], knots[n]]` is empty.
    #[error("empty parameter domain [{start:?}, {end:?}]")]
    EmptyDomain {
        /// `knots[degree]`.
        start: f64,
        /// `knots[n]`.
        end: f64,
    },
    /// A knot strictly inside the domain is repeated more than `degree + 1` times (a knot of
    /// multiplicity `degree + 1` is a break between independent Bezier pieces; more has no
    /// meaning).
    #[error("interior knot {value:?} has multiplicity {multiplicity} > degree + 1 = {}", degree + 1)]
    InteriorMultiplicity {
        /// Knot value.
        value: f64,
        /// Its multiplicity.
        multiplicity: usize,
        /// Curve degree.
        degree: usize,
    },
    /// A control point coordinate is NaN or infinite.
    #[error("control point {index} is not finite ({x:?}, {y:?})")]
    NonFiniteControlPoint {
        /// Control point index.
        index: usize,
        /// Abscissa.
        x: f64,
        /// Ordinate.
        y: f64,
    },
    /// Weights and control points differ in number.
    #[error("{weights} weights for {points} control points")]
    WeightCountMismatch {
        /// Number of weights.
        weights: usize,
        /// Number of control points.
        points: usize,
    },
    /// A weight is zero, negative, NaN or infinite.
    #[error("weight {index} must be finite and > 0, got {value:?}")]
    NonPositiveWeight {
        /// Weight index.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A parameter is outside the curve's domain (or not finite).
    #[error("parameter {u:?} is outside the domain [{start:?}, {end:?}]")]
    ParameterOutOfDomain {
        /// The parameter.
        u: f64,
        /// Domain start.
        start: f64,
        /// Domain end.
        end: f64,
    },
    /// Knot insertion would exceed the allowed multiplicity.
    #[error("inserting {value:?} {times} times exceeds multiplicity {max} (it has {current})")]
    MultiplicityExceeded {
        /// Knot value.
        value: f64,
        /// Requested insertions.
        times: usize,
        /// Current multiplicity.
        current: usize,
        /// Largest allowed multiplicity.
        max: usize,
    },
    /// A knot span (or the whole knot range) is so long that its length overflows.
    #[error("knots {start:?} .. {end:?}: the span length is not finite")]
    NonFiniteSpan {
        /// First knot of the range.
        start: f64,
        /// Last knot of the range.
        end: f64,
    },
    /// A documented limit (see [`crate::limits`]) is exceeded.
    #[error("{what} {value:e} exceeds the limit {limit:e}")]
    LimitExceeded {
        /// What was too large.
        what: &'static str,
        /// Its value.
        value: f64,
        /// The limit.
        limit: f64,
    },
    /// A primitive got an invalid size or angle.
    #[error("invalid {what}: {value:?}")]
    InvalidPrimitive {
        /// Which parameter.
        what: &'static str,
        /// Its value.
        value: f64,
    },
    /// An end-span extension was asked for an interval that is empty or not wholly before or
    /// after the domain.
    #[error(
        "cannot extend over [{t0:?}, {t1:?}]: not an interval before or after the domain [{start:?}, {end:?}]"
    )]
    ExtensionInterval {
        /// Start of the interval asked for.
        t0: f64,
        /// Its end.
        t1: f64,
        /// Domain start.
        start: f64,
        /// Domain end.
        end: f64,
    },
}

/// Invalid domain file or domain.
#[derive(Clone, Debug, Error)]
pub enum DomainError {
    /// A domain needs at least one curve.
    #[error("the domain has no curves")]
    NoCurves,
    /// A boundary loop does not close (required for crossing-number containment).
    #[error(
        "open boundary: the loop of curves {first_curve}..={last_curve} ends {gap:e} away from its start (tolerance {tolerance:e})"
    )]
    OpenLoop {
        /// First curve of the loop.
        first_curve: usize,
        /// Last curve of the loop.
        last_curve: usize,
        /// Distance from the loop's end to its start.
        gap: f64,
        /// The closure tolerance in force.
        tolerance: f64,
    },
    /// Two consecutive curves do not meet: the end of `curve` is more than the closure
    /// tolerance away from the start of `next`, so the loop through them is open there.
    #[error(
        "open boundary: curve {curve} ends {gap:e} away from the start of curve {next} (closure tolerance {tolerance:e}; a larger relative closure tolerance joins them)"
    )]
    CurvesMiss {
        /// The curve whose end misses.
        curve: usize,
        /// The curve whose start it misses.
        next: usize,
        /// The distance between them.
        gap: f64,
        /// The closure tolerance in force.
        tolerance: f64,
    },
    /// A curve's Bezier pieces do not meet at a break (an interior knot of multiplicity
    /// `degree + 1`): the boundary has a gap there.
    #[error(
        "curve {curve} has a gap at parameter {parameter:?}: its pieces are {gap:e} apart there (tolerance {tolerance:e}); only the winding-number methods accept gaps"
    )]
    CurveGap {
        /// Index of the curve.
        curve: usize,
        /// The knot value of the break.
        parameter: f64,
        /// Distance between the end of the piece before and the start of the piece after.
        gap: f64,
        /// The closure tolerance in force.
        tolerance: f64,
    },
    /// The closure tolerance must be finite and non-negative.
    #[error("invalid closure tolerance {0:?}")]
    InvalidTolerance(f64),
}
