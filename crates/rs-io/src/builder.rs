//! Assembles drawing commands (move, line, curve, close) into closed boundary loops.

use rs_spline::prelude::*;
use rs_spline::{NurbsCurve, Point, SplineError, segment};

use rs_spline::Affine;

/// Gaps up to this fraction of a loop's size are closed by moving the loop's last control
/// point onto its start (a rounding difference, not a missing edge).
const SNAP_RELATIVE: f64 = 1e-12;

/// Builds closed loops from pen commands, the way an SVG/font renderer fills a path: every
/// subpath is closed (explicitly by `close` or implicitly at the next `move_to` / the end) with
/// a straight segment, zero-length pieces are dropped, and subpaths without area (all control
/// points on one line) are dropped, since they enclose nothing. With
/// [`OpenSubpaths::Keep`] only `close` closes a subpath, and every other one is kept as drawn,
/// open, area or not (curve collections for generalized winding numbers).
///
/// Curves are mapped by the current transform as they are added, so loops stay watertight:
/// shared end points map to bit-identical images.
#[derive(Debug)]
pub(crate) struct LoopBuilder {
    done: Vec<NurbsCurve>,
    current: Vec<NurbsCurve>,
    start: Point,
    pen: Point,
    transform: Affine,
    /// The first curve a transform could not map (say, past the coordinate limit): reported by
    /// [`LoopBuilder::take_error`] instead of dropping the loop silently.
    error: Option<SplineError>,
    open: OpenSubpaths,
}

/// How a reader treats a subpath that does not end with a close command.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum OpenSubpaths {
    /// Closed by a straight segment back to its start, as a renderer fills it (the default:
    /// the result bounds a domain).
    #[default]
    Close,
    /// Kept open, as drawn (a curve collection for generalized winding numbers; the crossing
    /// methods refuse it).
    Keep,
}

impl LoopBuilder {
    pub(crate) fn new(open: OpenSubpaths) -> Self {
        Self {
            open,
            done: Vec::new(),
            current: Vec::new(),
            start: Point::new(0.0, 0.0),
            pen: Point::new(0.0, 0.0),
            transform: Affine::IDENTITY,
            error: None,
        }
    }

    /// The first error met while mapping finished subpaths, if any (and clears it).
    pub(crate) fn take_error(&mut self) -> Option<SplineError> {
        self.error.take()
    }

    /// Ends a path: finishes the current subpath (as a new subpath or the end would) and puts
    /// the pen and the subpath start back at the origin, so the next path (an SVG element,
    /// path data) starts as if nothing had been drawn before it.
    pub(crate) fn end_path(&mut self) {
        self.finish();
        self.start = Point::new(0.0, 0.0);
        self.pen = self.start;
    }

    /// Sets the map applied to the curves of the next subpaths (finishes the current one).
    pub(crate) fn set_transform(&mut self, t: Affine) {
        self.finish();
        self.transform = t;
    }

    /// The current pen position (untransformed).
    pub(crate) fn pen(&self) -> Point {
        self.pen
    }

    /// Starts a new subpath at `p`, finishing the current one.
    pub(crate) fn move_to(&mut self, p: Point) {
        self.finish();
        self.start = p;
        self.pen = p;
    }

    /// A straight segment from the pen to `p`.
    pub(crate) fn line_to(&mut self, p: Point) -> Result<(), SplineError> {
        if p != self.pen {
            self.current.push(segment(self.pen, p)?);
        }
        self.pen = p;
        Ok(())
    }

    /// A polynomial Bezier piece from the pen through `controls` (the last one is the end).
    pub(crate) fn bezier_to(&mut self, controls: &[Point]) -> Result<(), SplineError> {
        let Some(&end) = controls.last() else {
            return Ok(());
        };
        let mut points = Vec::with_capacity(controls.len() + 1);
        points.push(self.pen);
        points.extend_from_slice(controls);
        if points.iter().all(|&q| q == self.pen) {
            return Ok(());
        }
        self.current.push(NurbsCurve::bezier(points, None)?);
        self.pen = end;
        Ok(())
    }

    /// A curve that starts at the pen (its start point must equal the pen exactly).
    pub(crate) fn curve(&mut self, c: NurbsCurve) {
        debug_assert!(c.start_point() == self.pen);
        self.pen = c.end_point();
        self.current.push(c);
    }

    /// Closes the current subpath; the pen returns to its start.
    pub(crate) fn close(&mut self) {
        self.finish_subpath(true);
        self.pen = self.start;
    }

    /// Finishes the current subpath (adding the closing segment if needed) and returns every
    /// loop's curves, in order.
    ///
    /// # Errors
    /// The first curve that could not be mapped by its transform.
    pub(crate) fn into_curves(mut self) -> Result<Vec<NurbsCurve>, SplineError> {
        self.finish();
        match self.error {
            Some(e) => Err(e),
            None => Ok(self.done),
        }
    }

    /// Finishes the current subpath where no close command ends it.
    fn finish(&mut self) {
        self.finish_subpath(false);
    }

    /// Finishes the current subpath: closed if `explicit_close` or in [`OpenSubpaths::Close`]
    /// mode, then mapped by the transform.
    fn finish_subpath(&mut self, explicit_close: bool) {
        if self.current.is_empty() {
            return;
        }
        let mut curves = std::mem::take(&mut self.current);
        let size = loop_size(&curves);
        let gap = self.pen.distance(self.start);
        let keep_open = self.open == OpenSubpaths::Keep && !explicit_close;
        if keep_open {
            // As drawn.
        } else if gap > SNAP_RELATIVE * size {
            if let Ok(s) = segment(self.pen, self.start) {
                curves.push(s);
            }
        } else if gap > 0.0
            && let Some(last) = curves.pop()
        {
            curves.push(with_end_point(&last, self.start).unwrap_or(last));
        }
        self.pen = self.start;
        // Map first: a singular transform (scale(0), say) flattens the loop to no area.
        let mapped: Result<Vec<NurbsCurve>, SplineError> = curves
            .iter()
            .map(|c| self.transform.apply_to_curve(c))
            .collect();
        match mapped {
            Ok(mapped) if keep_open || encloses_area(&mapped) => self.done.extend(mapped),
            Ok(_) => {}
            Err(e) => {
                self.error.get_or_insert(e);
            }
        }
    }
}

/// `c` with its last control point moved to `end` (a clamped curve ends there).
pub(crate) fn with_end_point(c: &NurbsCurve, end: Point) -> Result<NurbsCurve, SplineError> {
    with_end_points(c, c.control_points()[0], end)
}

/// `c` with its first and last control points moved to `a` and `b`.
pub(crate) fn with_end_points(
    c: &NurbsCurve,
    a: Point,
    b: Point,
) -> Result<NurbsCurve, SplineError> {
    let mut pts = c.control_points().to_vec();
    if let Some(first) = pts.first_mut() {
        *first = a;
    }
    if let Some(last) = pts.last_mut() {
        *last = b;
    }
    NurbsCurve::new(
        c.degree(),
        c.knots().knots().to_vec(),
        pts,
        Some(c.weights().to_vec()),
    )
}

fn loop_size(curves: &[NurbsCurve]) -> f64 {
    curves
        .iter()
        .map(NurbsCurve::control_bounding_box)
        .reduce(rs_spline::BoundingBox::union)
        .map_or(0.0, |b| b.diagonal())
}

/// False if every control point lies on one line through the first (no enclosed area).
fn encloses_area(curves: &[NurbsCurve]) -> bool {
    let pts: Vec<Point> = curves
        .iter()
        .flat_map(|c| c.control_points().iter().copied())
        .collect();
    let Some(&p0) = pts.first() else {
        return false;
    };
    let Some(&far) = pts
        .iter()
        .max_by(|a, b| a.distance(p0).total_cmp(&b.distance(p0)))
    else {
        return false;
    };
    let d = far - p0;
    let len = d.length();
    if len == 0.0 {
        return false;
    }
    pts.iter()
        .any(|&q| (q - p0).cross(d).abs() > COLLINEAR * len * len)
}

/// Points whose distance from a line is below this times the squared length of its defining
/// chord are on it.
const COLLINEAR: f64 = 1e-14;

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64) -> Point {
        Point::new(x, y)
    }

    #[test]
    fn open_subpaths_are_closed_and_lines_without_area_dropped() {
        let mut b = LoopBuilder::new(OpenSubpaths::Close);
        b.move_to(p(0.0, 0.0));
        b.line_to(p(1.0, 0.0)).unwrap();
        b.line_to(p(1.0, 1.0)).unwrap();
        // Implicitly closed at the next move.
        b.move_to(p(5.0, 5.0));
        b.line_to(p(6.0, 6.0)).unwrap(); // a line: no area, dropped
        b.move_to(p(9.0, 9.0)); // a lone move: nothing
        let curves = b.into_curves().unwrap();
        assert_eq!(curves.len(), 3);
        assert_eq!(curves[2].end_point(), p(0.0, 0.0));
        let d = rs_spline::Domain::new(curves).unwrap();
        assert_eq!(d.loops().len(), 1);
        assert!(d.require_closed().is_ok());
        assert!((d.signed_area() - 0.5).abs() < 1e-15);
    }

    #[test]
    fn open_subpaths_can_be_kept_as_drawn() {
        let mut b = LoopBuilder::new(OpenSubpaths::Keep);
        b.move_to(p(0.0, 0.0));
        b.line_to(p(1.0, 0.0)).unwrap();
        b.line_to(p(1.0, 1.0)).unwrap();
        b.move_to(p(5.0, 5.0));
        b.line_to(p(6.0, 6.0)).unwrap(); // kept: no area, but a curve
        b.move_to(p(0.0, 3.0));
        b.line_to(p(1.0, 3.0)).unwrap();
        b.line_to(p(1.0, 4.0)).unwrap();
        b.close(); // an explicit close still closes
        let curves = b.into_curves().unwrap();
        assert_eq!(curves.len(), 6);
        assert_eq!(curves[1].end_point(), p(1.0, 1.0));
        assert_eq!(curves[5].end_point(), p(0.0, 3.0));
        let d = rs_spline::Domain::new(curves).unwrap();
        assert_eq!(d.loops().len(), 3);
        assert!(d.require_closed().is_err());
    }

    #[test]
    fn rounding_gaps_are_snapped_not_bridged() {
        let mut b = LoopBuilder::new(OpenSubpaths::Close);
        b.move_to(p(0.0, 0.0));
        b.line_to(p(1.0, 0.0)).unwrap();
        b.line_to(p(1.0, 1.0)).unwrap();
        b.line_to(p(1e-17, 1e-17)).unwrap();
        b.close();
        let curves = b.into_curves().unwrap();
        assert_eq!(curves.len(), 3);
        assert_eq!(curves[2].end_point(), p(0.0, 0.0));
    }

    #[test]
    fn transform_keeps_loops_watertight() {
        let mut b = LoopBuilder::new(OpenSubpaths::Close);
        b.set_transform(Affine::rotate(0.3).then_apply_to(Affine::scale(1.7, 0.2)));
        b.move_to(p(0.1, 0.2));
        b.bezier_to(&[p(1.0, 3.0), p(2.0, -1.0), p(3.0, 0.7)])
            .unwrap();
        b.bezier_to(&[p(2.0, 2.0), p(0.3, 0.9)]).unwrap();
        b.close();
        let curves = b.into_curves().unwrap();
        assert_eq!(curves.len(), 3);
        for w in 0..3 {
            assert_eq!(curves[w].end_point(), curves[(w + 1) % 3].start_point());
        }
    }
}
