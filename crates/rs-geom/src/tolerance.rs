//! The one tolerance policy of CAD models: how far apart two ends of trimming curves, or two
//! points of the model, may be and still meet.
//!
//! Real files are written to a tolerance (STEP's length `UNCERTAINTY_MEASURE_WITH_UNIT`, IGES's
//! minimum resolution, global parameter 19) and print about ten significant digits.
//! [`Tolerance`] holds the file's stated tolerance; every question asked of it is a method
//! here, with its formula:
//!
//! | question | method | formula |
//! | --- | --- | --- |
//! | do two model-space points coincide (vertices meeting, a curve lying on its plane)? | [`Tolerance::coincidence`] | `max(stated, 1e-8 size)` |
//! | does the next edge's pcurve start where the loop is, while a STEP loop is chained? | [`Tolerance::chain_gap`] | `max(10 stated, 1e-6)` (`stated` = `1e-6` when the file states none) |
//! | do the ends of consecutive trimming curves meet, when a face's loops are closed? | [`Tolerance::closure_gap`] | `max(stated, 1e-9 diagonal, 1e-8 magnitude)`, or the caller's relative tolerance times the diagonal |
//!
//! `size` is the size of what is compared (its largest coordinate), `diagonal` and `magnitude`
//! the diagonal and largest coordinate of the face's `(u, v)` box.

use rs_spline::limits::NonNegative;
use rs_spline::{BoundingBox, DEFAULT_RELATIVE_CLOSURE_TOLERANCE};

use crate::GeomError;

/// CAD files print about ten significant digits, so coordinates written from one point can
/// differ by a few units in the tenth digit (4e-9 at coordinates near 6 on a real IGES part
/// whose stated resolution is 5.5e-11): differences up to this fraction of the largest
/// coordinate are rounding.
pub const PRINTED_DIGITS: f64 = 1e-8;

/// The model tolerance assumed when a file states none, and the least gap accepted while a
/// STEP loop is chained.
pub const DEFAULT_MODEL_TOLERANCE: f64 = 1e-6;

/// Pcurves are approximations written to the file's tolerance in 3-D; in `(u, v)` their ends
/// may miss by the tolerance divided by the surface's parameter scale (a radius). This factor
/// leaves room for that without accepting a wrong trim (whose gap is of the size of a curve).
pub const CHAIN_FACTOR: f64 = 10.0;

/// The tolerances of one model, from the tolerance its file states (see the module
/// documentation for the formulas).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Tolerance {
    stated: Option<f64>,
}

impl Tolerance {
    /// The policy of a file stating `stated` (model units), or none.
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] for a stated tolerance that is negative, NaN or infinite.
    pub fn new(stated: Option<f64>) -> Result<Tolerance, GeomError> {
        if let Some(t) = stated {
            NonNegative::new(t).map_err(|e| GeomError::NotFinite {
                what: "model tolerance",
                value: e.0,
            })?;
        }
        Ok(Tolerance { stated })
    }

    /// The file's own tolerance, if it states one.
    pub fn stated(self) -> Option<f64> {
        self.stated
    }

    /// The largest distance at which two model-space points (of largest coordinate `size`)
    /// are the same point: `max(stated, 1e-8 size)`.
    pub fn coincidence(self, size: f64) -> f64 {
        self.stated.unwrap_or(0.0).max(PRINTED_DIGITS * size.abs())
    }

    /// The largest gap in `(u, v)` between the end of a loop chained so far and the next
    /// edge's pcurve: `max(10 stated, 1e-6)`, with `stated = 1e-6` when the file states none.
    pub fn chain_gap(self) -> f64 {
        (CHAIN_FACTOR * self.stated.unwrap_or(DEFAULT_MODEL_TOLERANCE)).max(DEFAULT_MODEL_TOLERANCE)
    }

    /// The largest gap between consecutive trimming curves of a face whose `(u, v)` box is
    /// `bbox` that still closes the loop: `relative` times the box's diagonal if the caller
    /// gives one (a validated, finite, non-negative number), else `max(stated, 1e-9 diagonal,
    /// 1e-8 magnitude)` with `magnitude` the box's largest coordinate.
    pub fn closure_gap(self, bbox: &BoundingBox, relative: Option<f64>) -> f64 {
        let diagonal = bbox.diagonal();
        match relative {
            Some(t) => t * diagonal,
            None => {
                let magnitude = bbox
                    .min
                    .x
                    .abs()
                    .max(bbox.min.y.abs())
                    .max(bbox.max.x.abs())
                    .max(bbox.max.y.abs());
                (DEFAULT_RELATIVE_CLOSURE_TOLERANCE * diagonal)
                    .max(PRINTED_DIGITS * magnitude)
                    .max(self.stated.unwrap_or(0.0))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use rs_spline::Point;

    use super::*;

    #[test]
    fn each_question_has_its_formula() {
        let t = Tolerance::new(Some(1e-7)).unwrap();
        assert_eq!(t.coincidence(2.0), 1e-7);
        assert_eq!(t.coincidence(100.0), 1e-6);
        assert_eq!(t.chain_gap(), 1e-6);
        assert_eq!(Tolerance::new(Some(1e-5)).unwrap().chain_gap(), 10.0 * 1e-5);
        assert_eq!(Tolerance::default().chain_gap(), 10.0 * 1e-6);
        let b = BoundingBox::from_points([Point::new(0.0, 0.0), Point::new(3.0, 4.0)]).unwrap();
        assert_eq!(t.closure_gap(&b, None), 1e-7);
        assert_eq!(Tolerance::default().closure_gap(&b, None), 4e-8);
        assert_eq!(t.closure_gap(&b, Some(1e-3)), 5e-3);
        assert!(Tolerance::new(Some(-1.0)).is_err() && Tolerance::new(Some(f64::NAN)).is_err());
    }
}
