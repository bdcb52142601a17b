//! Documented limits on curve data.
//!
//! Every limit is checked where the data enters ([`crate::NurbsCurve::new`],
//! [`crate::RationalBezier::new`], the primitives) and reported as
//! [`crate::SplineError::LimitExceeded`] (or a more specific error) instead of letting a
//! computation overflow, lose every digit or allocate without bound.

/// The largest curve degree accepted. Crossing solves and tight boxes work with derivative
/// numerators of degree `2p - 2`; beyond this, binomial weights and power-basis coefficients
/// lose the digits the root finders need.
pub const MAX_DEGREE: usize = 32;

/// The largest absolute value of a control-point coordinate. Areas, cross products and
/// squared distances multiply two coordinates, so `1e150` keeps every such product finite
/// (below `1e300`) with room for the quadrature's sums.
pub const MAX_COORDINATE: f64 = 1e150;

/// The largest ratio `max w_i / min w_i` of the weights of one curve. Weights are homogeneous
/// (scaling them all changes nothing), but their spread skews the parametrisation: with a
/// spread `r` a piece of degree `p` is traversed in a parameter interval of width about
/// `r^(-1/p)`, and beyond `1e12` the tangency roots and crossing solves no longer resolve it
/// in double precision. Uniformly huge or tiny weights (all near `1e50`, or `1e-300`) are
/// fine: they are rescaled exactly by a power of two.
pub const MAX_WEIGHT_RATIO: f64 = 1e12;

/// The most quarter-turn pieces a circular or elliptic arc may have (`|sweep| <= 1024 * 2 pi`,
/// 4096 rational quadratic pieces).
pub const MAX_ARC_PIECES: usize = 4096;
