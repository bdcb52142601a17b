//! Straight primitives: segments and polylines, as degree-1 NURBS.

use crate::{NurbsCurve, Point, SplineError};

/// The segment from `a` to `b` as a degree-1 Bezier curve on `[0, 1]`.
///
/// # Errors
/// [`SplineError::NonFiniteControlPoint`] for non-finite coordinates.
///
/// # Examples
///
/// ```
/// use rs_spline::{segment, Point, prelude::*};
/// let s = segment(Point::new(0.0, 0.0), Point::new(2.0, 2.0)).unwrap();
/// assert_eq!(s.point_at(0.5), Point::new(1.0, 1.0));
/// ```
pub fn segment(a: Point, b: Point) -> Result<NurbsCurve, SplineError> {
    NurbsCurve::bezier(vec![a, b], None)
}

/// The polyline through `points` as one degree-1 NURBS with knots `0, 0, 1, 2, ..., n-1, n-1`
/// (vertex `i` at parameter `i`). Close it by repeating the first point at the end.
///
/// # Errors
/// [`SplineError::TooFewControlPoints`] for fewer than two points, and non-finite coordinates.
pub fn polyline(points: &[Point]) -> Result<NurbsCurve, SplineError> {
    let n = points.len();
    if n < 2 {
        return Err(SplineError::TooFewControlPoints {
            degree: 1,
            needed: 2,
            got: n,
        });
    }
    let mut knots = vec![0.0];
    knots.extend((0..n).map(|i| i as f64));
    knots.push((n - 1) as f64);
    NurbsCurve::new(1, knots, points.to_vec(), None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prelude::*;

    #[test]
    fn polyline_passes_through_its_vertices() {
        let pts = [
            Point::new(0.0, 0.0),
            Point::new(1.0, 0.0),
            Point::new(1.0, 1.0),
            Point::new(0.0, 0.0),
        ];
        let c = polyline(&pts).unwrap();
        for (i, p) in pts.iter().enumerate() {
            assert_eq!(c.point_at(i as f64), *p);
        }
        assert_eq!(c.point_at(1.5), Point::new(1.0, 0.5));
        assert_eq!(c.to_bezier().len(), 3);
        assert!(polyline(&pts[..1]).is_err());
    }
}
