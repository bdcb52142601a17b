//! The output arrays of a coverage by name, shape and values: the one table the front ends
//! write their files and `NumPy` arrays from.

use crate::{Coverage, CoverageOptions};

/// One output array of a [`Coverage`], in the order front ends list them ([`CoverageArray::ALL`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum CoverageArray {
    /// [`Coverage::fractions`], `(rows, nx)`.
    Fractions,
    /// [`Coverage::centroids`], `(rows, nx, 2)`.
    Centroids,
    /// [`Coverage::x_apertures`], `(rows, nx + 1)`.
    XApertures,
    /// [`Coverage::y_apertures`], `(rows + 1, nx)`.
    YApertures,
    /// [`Coverage::boundary_lengths`], `(rows, nx)`.
    BoundaryLengths,
    /// [`Coverage::boundary_centroids`], `(rows, nx, 2)`.
    BoundaryCentroids,
    /// [`Coverage::boundary_normals`], `(rows, nx, 2)`.
    BoundaryNormals,
    /// [`Coverage::x_face_centroids`], `(rows, nx + 1)`.
    XFaceCentroids,
    /// [`Coverage::y_face_centroids`], `(rows + 1, nx)`.
    YFaceCentroids,
}

impl CoverageArray {
    /// Every array: the fractions, centroids, apertures, the boundary's lengths, centroids
    /// and normals, the face centroids.
    pub const ALL: [CoverageArray; 9] = [
        CoverageArray::Fractions,
        CoverageArray::Centroids,
        CoverageArray::XApertures,
        CoverageArray::YApertures,
        CoverageArray::BoundaryLengths,
        CoverageArray::BoundaryCentroids,
        CoverageArray::BoundaryNormals,
        CoverageArray::XFaceCentroids,
        CoverageArray::YFaceCentroids,
    ];

    /// The name of its field in [`Coverage`] (`"fractions"`, `"x_apertures"`, ...).
    pub fn name(self) -> &'static str {
        match self {
            CoverageArray::Fractions => "fractions",
            CoverageArray::Centroids => "centroids",
            CoverageArray::XApertures => "x_apertures",
            CoverageArray::YApertures => "y_apertures",
            CoverageArray::BoundaryLengths => "boundary_lengths",
            CoverageArray::BoundaryCentroids => "boundary_centroids",
            CoverageArray::BoundaryNormals => "boundary_normals",
            CoverageArray::XFaceCentroids => "x_face_centroids",
            CoverageArray::YFaceCentroids => "y_face_centroids",
        }
    }

    /// Whether a coverage computed with `options` holds it.
    pub fn computed(self, options: CoverageOptions) -> bool {
        match self {
            CoverageArray::Fractions => true,
            CoverageArray::Centroids => options.centroids,
            CoverageArray::XApertures | CoverageArray::YApertures => options.apertures,
            CoverageArray::BoundaryLengths
            | CoverageArray::BoundaryCentroids
            | CoverageArray::BoundaryNormals => options.boundary,
            CoverageArray::XFaceCentroids | CoverageArray::YFaceCentroids => options.face_centroids,
        }
    }

    /// Whether it is on the horizontal faces: one line more than the rows (a band holds its
    /// bottom and top lines; the top line is the next band's bottom one).
    pub fn on_horizontal_faces(self) -> bool {
        matches!(
            self,
            CoverageArray::YApertures | CoverageArray::YFaceCentroids
        )
    }

    /// Its shape for `rows` rows of `nx` columns: cells `(rows, nx)` (pairs `(rows, nx, 2)`),
    /// vertical faces `(rows, nx + 1)`, horizontal faces `(rows + 1, nx)`.
    pub fn shape(self, nx: usize, rows: usize) -> Vec<usize> {
        match self {
            CoverageArray::Fractions | CoverageArray::BoundaryLengths => vec![rows, nx],
            CoverageArray::Centroids
            | CoverageArray::BoundaryCentroids
            | CoverageArray::BoundaryNormals => vec![rows, nx, 2],
            CoverageArray::XApertures | CoverageArray::XFaceCentroids => vec![rows, nx + 1],
            CoverageArray::YApertures | CoverageArray::YFaceCentroids => vec![rows + 1, nx],
        }
    }
}

impl Coverage {
    /// The values of `array` in row-major order (pairs flattened), `None` where this
    /// coverage does not hold it.
    pub fn values(&self, array: CoverageArray) -> Option<&[f64]> {
        match array {
            CoverageArray::Fractions => Some(&self.fractions),
            CoverageArray::Centroids => self.centroids.as_deref().map(<[_]>::as_flattened),
            CoverageArray::XApertures => self.x_apertures.as_deref(),
            CoverageArray::YApertures => self.y_apertures.as_deref(),
            CoverageArray::BoundaryLengths => self.boundary_lengths.as_deref(),
            CoverageArray::BoundaryCentroids => {
                self.boundary_centroids.as_deref().map(<[_]>::as_flattened)
            }
            CoverageArray::BoundaryNormals => {
                self.boundary_normals.as_deref().map(<[_]>::as_flattened)
            }
            CoverageArray::XFaceCentroids => self.x_face_centroids.as_deref(),
            CoverageArray::YFaceCentroids => self.y_face_centroids.as_deref(),
        }
    }

    /// The values of `array` moved out of this coverage (pairs flattened; the fractions
    /// leave an empty vector), `None` where it does not hold them.
    pub fn take_values(&mut self, array: CoverageArray) -> Option<Vec<f64>> {
        let pairs = |v: Option<Vec<[f64; 2]>>| v.map(Vec::into_flattened);
        match array {
            CoverageArray::Fractions => Some(std::mem::take(&mut self.fractions)),
            CoverageArray::Centroids => pairs(self.centroids.take()),
            CoverageArray::XApertures => self.x_apertures.take(),
            CoverageArray::YApertures => self.y_apertures.take(),
            CoverageArray::BoundaryLengths => self.boundary_lengths.take(),
            CoverageArray::BoundaryCentroids => pairs(self.boundary_centroids.take()),
            CoverageArray::BoundaryNormals => pairs(self.boundary_normals.take()),
            CoverageArray::XFaceCentroids => self.x_face_centroids.take(),
            CoverageArray::YFaceCentroids => self.y_face_centroids.take(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{CellGrid, GridCoverage};
    use rs_spline::{Domain, Point, circle};

    #[test]
    fn every_array_computed_is_held_with_its_shape() {
        let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
        let grid = CellGrid::uniform(-1.5, 1.5, 7, -1.5, 1.5, 5).unwrap();
        let options = CoverageOptions::DEFAULT
            .with_centroids(true)
            .with_apertures(true)
            .with_boundary(true)
            .with_face_centroids(true);
        let mut c = GridCoverage::new(&d, grid)
            .unwrap()
            .rows(1..4, options)
            .unwrap();
        for a in CoverageArray::ALL {
            assert!(a.computed(options));
            let len: usize = a.shape(7, 3).iter().product();
            assert_eq!(c.values(a).map(<[f64]>::len), Some(len), "{}", a.name());
            assert_eq!(a.on_horizontal_faces(), a.shape(7, 3)[0] == 4);
            assert_eq!(c.take_values(a).map(|v| v.len()), Some(len));
        }
        assert!(!CoverageArray::Centroids.computed(CoverageOptions::DEFAULT));
        let plain = GridCoverage::new(&d, CellGrid::uniform(0.0, 1.0, 2, 0.0, 1.0, 2).unwrap())
            .unwrap()
            .all(CoverageOptions::DEFAULT)
            .unwrap();
        assert!(plain.values(CoverageArray::BoundaryNormals).is_none());
    }
}
