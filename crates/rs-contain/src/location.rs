//! Where a point is relative to a domain.

use std::fmt;
use std::str::FromStr;

/// The location of a point relative to a domain.
///
/// Its discriminants are its [`Location::code`]s, so that a slice of locations becomes a
/// slice of codes by a plain copy (which the compiler vectorises).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(i8)]
pub enum Location {
    /// Strictly inside (farther than the boundary tolerance from the boundary).
    Inside = 1,
    /// Strictly outside.
    Outside = 0,
    /// On the boundary, up to the boundary tolerance.
    Boundary = 2,
}

impl Location {
    /// The integer code of `.npy` outputs and the Python package: 0 outside, 1 inside,
    /// 2 boundary.
    #[inline]
    pub fn code(self) -> i8 {
        self as i8
    }

    /// The CSV word: `inside`, `outside` or `boundary`.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Inside => "inside",
            Self::Outside => "outside",
            Self::Boundary => "boundary",
        }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// How a point was decided (for diagnostics and tests).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Decision {
    /// Outside the global bounding box grown by the tolerance.
    BoundingBox,
    /// Crossing number of the vertical ray (the normal case).
    VerticalRay,
    /// The vertical ray met a critical abscissa: crossing number of the horizontal ray.
    HorizontalRay,
    /// Both rays met critical points: winding number.
    WindingNumber,
}

/// The classification algorithm.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum Method {
    /// Each point against each candidate box: `O(M N)` (the paper's inRS1).
    InRS1,
    /// Points sorted by abscissa, a binary search per box (the paper's inRS2).
    InRS2,
    /// Generalized winding number, rounded, then the fill rule (see [`crate::WindingField`]).
    Gwn,
    /// The fastest exact path for the batch size: inRS2 below
    /// [`FAST_METHOD_MIN_POINTS`] points, otherwise the grid [`crate::PointLocator`] run on all
    /// threads ([`fast_uses_locator`]). Same results as inRS2. The default, in the library as
    /// on the command line.
    #[default]
    Fast,
}

/// Batch size from which [`Method::Fast`] builds a [`crate::PointLocator`]: below it the grid's
/// build costs more than it saves (docs/BENCHMARKS.md, `cargo xtask bench --only locator`).
pub const FAST_METHOD_MIN_POINTS: usize = 50_000;

/// Whether [`Method::Fast`] answers a batch of `points` points with the grid locator (from
/// [`FAST_METHOD_MIN_POINTS`] on) rather than inRS2: the one place that decides, for the
/// library, the command line and the Python package alike.
pub fn fast_uses_locator(points: usize) -> bool {
    points >= FAST_METHOD_MIN_POINTS
}

impl Method {
    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::InRS1 => "inrs1",
            Self::InRS2 => "inrs2",
            Self::Gwn => "gwn",
            Self::Fast => "fast",
        }
    }

    /// Every method, for tests and benchmarks.
    pub const ALL: [Method; 4] = [Method::InRS1, Method::InRS2, Method::Gwn, Method::Fast];
}

impl FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "inrs1" => Ok(Self::InRS1),
            "inrs2" => Ok(Self::InRS2),
            "gwn" => Ok(Self::Gwn),
            "fast" => Ok(Self::Fast),
            other => Err(format!(
                "unknown method {other:?} (expected fast, inrs1, inrs2 or gwn)"
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fast_method_builds_the_locator_from_its_threshold_on() {
        assert!(!fast_uses_locator(0));
        assert!(!fast_uses_locator(FAST_METHOD_MIN_POINTS - 1));
        assert!(fast_uses_locator(FAST_METHOD_MIN_POINTS));
        assert!(fast_uses_locator(usize::MAX));
    }

    /// The codes of `.npy` outputs and the Python package, which the discriminants are.
    #[test]
    fn the_codes_are_outside_0_inside_1_boundary_2() {
        assert_eq!(Location::Outside.code(), 0);
        assert_eq!(Location::Inside.code(), 1);
        assert_eq!(Location::Boundary.code(), 2);
    }
}
