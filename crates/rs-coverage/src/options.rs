//! What a coverage computes besides the fractions.

use rs_spline::Axis;

use crate::arc::Moments;

/// What to compute besides the fractions: [`CoverageOptions::DEFAULT`] (fractions only) and
/// `with_*` setters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct CoverageOptions {
    /// The centroid of each cell's covered part.
    pub centroids: bool,
    /// The covered fraction of each cell face.
    pub apertures: bool,
    /// The boundary's length, centroid and unit outward normal in each cell (the embedded
    /// boundary of a cut cell). Planar only: refused with [`CoverageOptions::axisymmetric`].
    pub boundary: bool,
    /// The centroid of each cell face's covered part. Planar only.
    pub face_centroids: bool,
    /// The axis the domain revolves about (`Axis::Y`: the radius is `|x|`; `Axis::X`: `|y|`),
    /// for the revolved cells' volume fractions: every value is then weighted by the
    /// distance to the axis (see [`Coverage`](crate::Coverage)). The domain and the grid must each lie on one
    /// side of the axis (touching it is fine).
    pub axisymmetric: Option<Axis>,
}

impl CoverageOptions {
    /// Fractions only.
    pub const DEFAULT: CoverageOptions = CoverageOptions {
        centroids: false,
        apertures: false,
        boundary: false,
        face_centroids: false,
        axisymmetric: None,
    };

    /// With or without the centroids.
    pub const fn with_centroids(mut self, centroids: bool) -> Self {
        self.centroids = centroids;
        self
    }

    /// With or without the apertures.
    pub const fn with_apertures(mut self, apertures: bool) -> Self {
        self.apertures = apertures;
        self
    }

    /// With or without the boundary's geometry in each cell.
    pub const fn with_boundary(mut self, boundary: bool) -> Self {
        self.boundary = boundary;
        self
    }

    /// With or without the faces' centroids.
    pub const fn with_face_centroids(mut self, face_centroids: bool) -> Self {
        self.face_centroids = face_centroids;
        self
    }

    /// Revolved about `axis` (`None`: planar).
    pub const fn with_axisymmetric(mut self, axis: Option<Axis>) -> Self {
        self.axisymmetric = axis;
        self
    }

    /// The area moments the cells need.
    /// Revolved fractions alone take one integral per part (the cell's volume integral, see
    /// `Arc::volume_integral`) and so count as `Area`.
    pub(crate) fn moments(self) -> Moments {
        match (self.centroids, self.axisymmetric.is_some()) {
            (true, true) => Moments::Second,
            (true, false) => Moments::First,
            (false, _) => Moments::Area,
        }
    }
}

impl Default for CoverageOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
