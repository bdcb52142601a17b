//! The output arrays of a coverage by name, shape and values: the one table the front ends
//! write their files and `NumPy` arrays from.

use crate::{CoverageError, CoverageOptions};

/// One output array of a [`Coverage`](crate::Coverage), in the order front ends list them ([`CoverageArray::ALL`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum CoverageArray {
    /// [`Coverage::fractions`](crate::Coverage::fractions), `(rows, nx)`.
    Fractions,
    /// [`Coverage::centroids`](crate::Coverage::centroids), `(rows, nx, 2)`.
    Centroids,
    /// [`Coverage::x_apertures`](crate::Coverage::x_apertures), `(rows, nx + 1)`.
    XApertures,
    /// [`Coverage::y_apertures`](crate::Coverage::y_apertures), `(rows + 1, nx)`.
    YApertures,
    /// [`Coverage::boundary_lengths`](crate::Coverage::boundary_lengths), `(rows, nx)`.
    BoundaryLengths,
    /// [`Coverage::boundary_centroids`](crate::Coverage::boundary_centroids), `(rows, nx, 2)`.
    BoundaryCentroids,
    /// [`Coverage::boundary_normals`](crate::Coverage::boundary_normals), `(rows, nx, 2)`.
    BoundaryNormals,
    /// [`Coverage::x_face_centroids`](crate::Coverage::x_face_centroids), `(rows, nx + 1)`.
    XFaceCentroids,
    /// [`Coverage::y_face_centroids`](crate::Coverage::y_face_centroids), `(rows + 1, nx)`.
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

    /// The name of its field in [`Coverage`](crate::Coverage) (`"fractions"`, `"x_apertures"`, ...).
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

/// A whole grid's output arrays in the caller's memory, for [`GridCoverage::all_into`](crate::GridCoverage::all_into): the
/// fields of [`Coverage`](crate::Coverage) borrowed, row-major, pairs `[x, y]` flattened (`(rows, nx, 2)` as
/// `2 x rows x nx` values), so that a `NumPy` array or a reused buffer receives the values
/// where they stay. Their contents on entry do not matter: every value is written.
#[derive(Debug)]
#[non_exhaustive]
pub struct CoverageSlices<'a> {
    /// `(ny, nx)`.
    pub fractions: &'a mut [f64],
    /// `(ny, nx, 2)`, with [`CoverageOptions::centroids`].
    pub centroids: Option<&'a mut [f64]>,
    /// `(ny, nx + 1)`, with [`CoverageOptions::apertures`].
    pub x_apertures: Option<&'a mut [f64]>,
    /// `(ny + 1, nx)`, with [`CoverageOptions::apertures`].
    pub y_apertures: Option<&'a mut [f64]>,
    /// `(ny, nx)`, with [`CoverageOptions::boundary`].
    pub boundary_lengths: Option<&'a mut [f64]>,
    /// `(ny, nx, 2)`, with [`CoverageOptions::boundary`].
    pub boundary_centroids: Option<&'a mut [f64]>,
    /// `(ny, nx, 2)`, with [`CoverageOptions::boundary`].
    pub boundary_normals: Option<&'a mut [f64]>,
    /// `(ny, nx + 1)`, with [`CoverageOptions::face_centroids`].
    pub x_face_centroids: Option<&'a mut [f64]>,
    /// `(ny + 1, nx)`, with [`CoverageOptions::face_centroids`].
    pub y_face_centroids: Option<&'a mut [f64]>,
}

impl<'a> CoverageSlices<'a> {
    /// The fractions alone.
    pub fn fractions(fractions: &'a mut [f64]) -> Self {
        Self {
            fractions,
            centroids: None,
            x_apertures: None,
            y_apertures: None,
            boundary_lengths: None,
            boundary_centroids: None,
            boundary_normals: None,
            x_face_centroids: None,
            y_face_centroids: None,
        }
    }

    /// With `values` as `array`'s slice (the fractions' replaced).
    pub fn with(mut self, array: CoverageArray, values: &'a mut [f64]) -> Self {
        match array {
            CoverageArray::Fractions => self.fractions = values,
            CoverageArray::Centroids => self.centroids = Some(values),
            CoverageArray::XApertures => self.x_apertures = Some(values),
            CoverageArray::YApertures => self.y_apertures = Some(values),
            CoverageArray::BoundaryLengths => self.boundary_lengths = Some(values),
            CoverageArray::BoundaryCentroids => self.boundary_centroids = Some(values),
            CoverageArray::BoundaryNormals => self.boundary_normals = Some(values),
            CoverageArray::XFaceCentroids => self.x_face_centroids = Some(values),
            CoverageArray::YFaceCentroids => self.y_face_centroids = Some(values),
        }
        self
    }

    /// The slice of `array`, if given.
    pub fn get_mut(&mut self, array: CoverageArray) -> Option<&mut [f64]> {
        match array {
            CoverageArray::Fractions => Some(&mut *self.fractions),
            CoverageArray::Centroids => self.centroids.as_deref_mut(),
            CoverageArray::XApertures => self.x_apertures.as_deref_mut(),
            CoverageArray::YApertures => self.y_apertures.as_deref_mut(),
            CoverageArray::BoundaryLengths => self.boundary_lengths.as_deref_mut(),
            CoverageArray::BoundaryCentroids => self.boundary_centroids.as_deref_mut(),
            CoverageArray::BoundaryNormals => self.boundary_normals.as_deref_mut(),
            CoverageArray::XFaceCentroids => self.x_face_centroids.as_deref_mut(),
            CoverageArray::YFaceCentroids => self.y_face_centroids.as_deref_mut(),
        }
    }

    /// [`CoverageError::Output`] unless each array `options` asks for is given with the
    /// length of its shape for `ny` rows of `nx` columns, and no other is given.
    pub(crate) fn check(
        &mut self,
        nx: usize,
        ny: usize,
        options: CoverageOptions,
    ) -> Result<(), CoverageError> {
        for array in CoverageArray::ALL {
            let expected: usize = array.shape(nx, ny).iter().product();
            let wanted = array.computed(options);
            match (self.get_mut(array).map(|s| s.len()), wanted) {
                (Some(got), true) if got == expected => {}
                (None, false) => {}
                (got, _) => {
                    return Err(CoverageError::Output {
                        array: array.name(),
                        expected: wanted.then_some(expected),
                        got,
                    });
                }
            }
        }
        Ok(())
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
