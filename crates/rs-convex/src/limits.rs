//! The limits of the refinement, named where the error messages and the approximation both
//! read them.

/// The deepest refinement level accepted (`2^20` times the original inequalities).
pub const MAX_LEVEL: u32 = 20;
