//! Containment queries directly on a [`Domain`].

use rs_contain::{Classifier, ContainError, ContainOptions, Locate, Location, Method};
use rs_spline::{Domain, Point};

/// Point containment on a [`Domain`]: `domain.classify(&points, method)`.
///
/// Each call builds a [`Classifier`] (monotone boxes and critical points); to classify several
/// batches against the same domain, build the classifier once instead. Semantics (boundary
/// tolerance, fill rule, fallbacks) are those of [`rs_contain`].
///
/// # Examples
///
/// ```
/// use inrs::{Classify, Location, Method};
/// use inrs::spline::{circle, Domain, Point};
/// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let loc = d.classify(&[Point::new(0.2, 0.1), Point::new(1.0, 0.0)], Method::InRS2).unwrap();
/// assert_eq!(loc, vec![Location::Inside, Location::Boundary]);
/// assert_eq!(d.classify_point(Point::new(3.0, 0.0)).unwrap(), Location::Outside);
/// ```
pub trait Classify {
    /// Classifies `points` with `method` and the default options.
    ///
    /// # Errors
    /// [`ContainError`] if the domain is not closed.
    fn classify(&self, points: &[Point], method: Method) -> Result<Vec<Location>, ContainError>;

    /// Classifies one point with the default options.
    ///
    /// # Errors
    /// [`ContainError`] if the domain is not closed.
    fn classify_point(&self, point: Point) -> Result<Location, ContainError>;
}

impl Classify for Domain {
    fn classify(&self, points: &[Point], method: Method) -> Result<Vec<Location>, ContainError> {
        Ok(Classifier::new(self, ContainOptions::default())?.classify(points, method))
    }

    fn classify_point(&self, point: Point) -> Result<Location, ContainError> {
        Ok(Classifier::new(self, ContainOptions::default())?.locate(point))
    }
}
