//! One face's trimming loops as a domain: closure within the file's tolerance, watertight
//! joints, positive area.

use rs_spline::prelude::*;
use rs_spline::{BoundingBox, DEFAULT_RELATIVE_CLOSURE_TOLERANCE, Domain, NurbsCurve, Point};

use super::{CadFace, CadModel};
use crate::IoError;

/// CAD files print about ten significant digits, so the ends of consecutive trimming curves
/// written from one point can differ by a few units in the tenth digit of the coordinates (4e-9
/// at coordinates near 6 on a real IGES part whose stated resolution is 5.5e-11): such gaps,
/// up to this fraction of the largest coordinate, are rounding and close by default.
const PRINTED_DIGITS_TOLERANCE: f64 = 1e-8;

impl CadModel {
    /// Face `index` (in file order, `#face:K`) as a domain in its surface's `(u, v)`.
    ///
    /// `relative_closure_tolerance`: the largest gap between consecutive trimming curves that
    /// still counts as meeting, relative to the diagonal of the face's `(u, v)` bounding box;
    /// `None` takes the largest of the file's tolerance (as a distance in `(u, v)`),
    /// [`DEFAULT_RELATIVE_CLOSURE_TOLERANCE`] of the diagonal and `1e-8` of the largest
    /// coordinate (the rounding of the ten or so digits files print). Gaps within it are closed by
    /// moving each curve's end onto the next curve's start (bit-identical joints). The loops
    /// are reversed together when needed so that the face's area is positive (outer loops
    /// counter-clockwise), whatever the orientation flags of the file made them.
    ///
    /// # Errors
    /// [`IoError::Cad`] for an index past the last face; [`IoError::CadFace`] for a face that
    /// could not be read (the reader's reason) or whose loop has a gap beyond the tolerance
    /// (naming the loop, the two curves and the gap); [`IoError::Domain`] for an invalid
    /// tolerance.
    pub fn face_domain(
        &self,
        index: usize,
        relative_closure_tolerance: Option<f64>,
    ) -> Result<Domain, IoError> {
        let face = self.faces.get(index).ok_or_else(|| IoError::Cad {
            format: self.format.name(),
            message: self.no_face_message(index),
        })?;
        let fail = |message: String| IoError::CadFace {
            format: self.format.name(),
            index,
            entity: face.entity.clone(),
            message,
        };
        let loops = face.loops.as_ref().map_err(|m| fail(m.clone()))?;
        let bbox = loops_box(face).ok_or_else(|| fail("the face has no trimming curves".into()))?;
        let diagonal = bbox.diagonal();
        if let Some(t) = relative_closure_tolerance
            && !(t.is_finite() && t >= 0.0)
        {
            return Err(rs_spline::DomainError::InvalidTolerance(t).into());
        }
        let tolerance = match relative_closure_tolerance {
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
                    .max(PRINTED_DIGITS_TOLERANCE * magnitude)
                    .max(self.tolerance.unwrap_or(0.0))
            }
        };
        let mut curves = Vec::new();
        let mut ranges = Vec::with_capacity(loops.len());
        for (l, curve_loop) in loops.iter().enumerate() {
            let start = curves.len();
            curves.extend(watertight(curve_loop, tolerance).map_err(|(k, next, gap)| {
                fail(format!(
                    "loop {l}: curve {k} ends {gap:.2e} away from the start of curve {next} \
                     (closure tolerance {tolerance:.2e}; a larger relative closure tolerance joins them)"
                ))
            })?);
            ranges.push(start..curves.len());
        }
        let relative = if diagonal > 0.0 {
            tolerance / diagonal
        } else {
            DEFAULT_RELATIVE_CLOSURE_TOLERANCE
        };
        let domain = Domain::with_relative_closure_tolerance(curves.clone(), relative)?;
        let flips = loops_to_reverse(&domain);
        let domain = if flips.is_empty() {
            domain
        } else {
            for i in flips {
                let r = domain.loops()[i].curves();
                curves[r.clone()].reverse();
                for c in &mut curves[r] {
                    *c = c.reversed();
                }
            }
            Domain::with_relative_closure_tolerance(curves, relative)?
        };
        Ok(domain.with_name(format!("face {index} ({})", face.entity)))
    }

    /// The message for a face index past the end.
    pub(crate) fn no_face_message(&self, index: usize) -> String {
        match self.faces.len() {
            0 => format!("face {index} does not exist: the file has no faces"),
            n => format!(
                "face {index} does not exist: the file has {n} face{} (#face:0 to #face:{})",
                if n == 1 { "" } else { "s" },
                n - 1
            ),
        }
    }
}

/// The loops of `d` whose orientation disagrees with their nesting: a loop inside an even
/// number of the other loops should run counter-clockwise, inside an odd number clockwise.
/// Nesting is decided for a point of each loop (the middle of its first curve) by crossing
/// parity against the other loops flattened within `1e-7` of the diagonal: rs-io has no
/// containment kernel (rs-contain sits above it), and orientation needs only the nesting of
/// disjoint loops, which a point well on one loop settles.
fn loops_to_reverse(d: &Domain) -> Vec<usize> {
    let n = d.loops().len();
    let accuracy = 1e-7 * d.bounding_box().diagonal();
    let rings: Vec<Vec<Point>> = (0..n)
        .map(|i| {
            let mut ring = Vec::new();
            d.flatten_loop(i, accuracy, &mut |p| ring.push(p));
            ring
        })
        .collect();
    let boxes: Vec<BoundingBox> = (0..n)
        .map(|i| {
            d.curves()[d.loops()[i].curves()]
                .iter()
                .map(NurbsCurve::bounding_box)
                .reduce(BoundingBox::union)
                .unwrap_or(d.bounding_box())
        })
        .collect();
    (0..n)
        .filter(|&i| {
            let first = &d.curves()[*d.loops()[i].curves().start()];
            let (a, b) = first.param_range();
            let probe = first.point_at(0.5 * (a + b));
            let depth = (0..n)
                .filter(|&j| j != i && boxes[j].contains(probe) && odd_crossings(&rings[j], probe))
                .count();
            let area = d.loop_signed_area(i);
            area != 0.0 && (area > 0.0) != (depth % 2 == 0)
        })
        .collect()
}

/// Crossing parity of the closed polygon `ring` (its last point joined to its first) at `p`:
/// true when a ray from `p` towards `+x` crosses it an odd number of times (half-open rule on
/// `y`).
fn odd_crossings(ring: &[Point], p: Point) -> bool {
    let mut odd = false;
    for (k, a) in ring.iter().enumerate() {
        let b = ring[(k + 1) % ring.len()];
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if x > p.x {
                odd = !odd;
            }
        }
    }
    odd
}

/// The bounding box of a face's trimming curves, `None` without curves or for an unread face.
pub(crate) fn loops_box(face: &CadFace) -> Option<BoundingBox> {
    face.loops
        .as_ref()
        .ok()?
        .iter()
        .flatten()
        .map(NurbsCurve::bounding_box)
        .reduce(BoundingBox::union)
}

/// The loop with every joint made bit-identical: a curve ending within `tolerance` of the next
/// one's start (cyclically) ends exactly there. `Err((k, next, gap))` for the first joint
/// beyond the tolerance.
fn watertight(
    curve_loop: &[NurbsCurve],
    tolerance: f64,
) -> Result<Vec<NurbsCurve>, (usize, usize, f64)> {
    let n = curve_loop.len();
    let mut out = Vec::with_capacity(n);
    for (k, c) in curve_loop.iter().enumerate() {
        let next = (k + 1) % n;
        let target = curve_loop[next].start_point();
        let end = c.end_point();
        let gap = end.distance(target);
        if gap > tolerance || gap.is_nan() {
            return Err((k, next, gap));
        }
        if gap == 0.0 {
            out.push(c.clone());
            continue;
        }
        // A clamped curve ends at its last control point: moving that point moves the end
        // (and nothing else by more than the gap).
        let clamped = c.clamped();
        let last = clamped.control_points().len() - 1;
        out.push(
            clamped
                .with_control_point(last, target)
                .map_err(|_| (k, next, gap))?,
        );
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use rs_spline::{Point, segment};

    use super::*;
    use crate::cad::CadFormat;

    /// A unit square drawn clockwise whose second corner misses by `gap`, as a one-face model
    /// with the file tolerance `tolerance`.
    fn square_model(gap: f64, tolerance: Option<f64>) -> CadModel {
        let p = |x, y| Point::new(x, y);
        let lines = vec![
            segment(p(0.0, 0.0), p(0.0, 1.0)).unwrap(),
            segment(p(0.0, 1.0 + gap), p(1.0, 1.0)).unwrap(),
            segment(p(1.0, 1.0), p(1.0, 0.0)).unwrap(),
            segment(p(1.0, 0.0), p(0.0, 0.0)).unwrap(),
        ];
        CadModel {
            format: CadFormat::Step,
            tolerance,
            faces: vec![CadFace {
                entity: "#7".into(),
                surface: "PLANE".into(),
                loops: Ok(vec![lines]),
            }],
        }
    }

    #[test]
    fn gaps_within_the_file_tolerance_close_watertight_and_the_area_is_positive() {
        let d = square_model(5e-8, Some(1e-7)).face_domain(0, None).unwrap();
        assert!(d.is_closed());
        assert_eq!(d.loops().len(), 1);
        // Watertight: every end is bit-identical to the next start.
        let c = d.curves();
        for k in 0..c.len() {
            assert_eq!(c[k].end_point(), c[(k + 1) % c.len()].start_point());
        }
        // Drawn clockwise in the file; reversed to be counter-clockwise.
        assert!((d.signed_area() - 1.0).abs() < 1e-7);
        assert_eq!(d.name(), Some("face 0 (#7)"));
    }

    #[test]
    fn a_gap_beyond_the_tolerance_names_the_loop_the_curves_and_the_gap() {
        let e = square_model(5e-8, None).face_domain(0, None).unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.starts_with(
                "STEP face 0 (#7): loop 0: curve 0 ends 5.00e-8 away from the start of curve 1"
            ),
            "{msg}"
        );
        // A relative closure tolerance given by the caller joins them.
        let d = square_model(5e-8, None).face_domain(0, Some(1e-7)).unwrap();
        assert!(d.is_closed());
        assert!(
            square_model(0.0, None)
                .face_domain(0, Some(f64::NAN))
                .is_err()
        );
    }

    /// Loops oriented by nesting whatever the file says: an outer square drawn clockwise, a
    /// hole drawn counter-clockwise like an outer loop, and an island in the hole drawn
    /// clockwise come out counter-clockwise, clockwise and counter-clockwise.
    #[test]
    fn loops_are_oriented_by_their_nesting() {
        let square = |lo: f64, hi: f64, ccw: bool| {
            let p = |x, y| Point::new(x, y);
            let mut c = [p(lo, lo), p(hi, lo), p(hi, hi), p(lo, hi)];
            if !ccw {
                c.reverse();
            }
            (0..4)
                .map(|k| segment(c[k], c[(k + 1) % 4]).unwrap())
                .collect::<Vec<_>>()
        };
        let model = CadModel {
            format: CadFormat::Iges,
            tolerance: None,
            faces: vec![CadFace {
                entity: "DE 1".into(),
                surface: "128".into(),
                loops: Ok(vec![
                    square(0.0, 10.0, false),
                    square(2.0, 8.0, true),
                    square(4.0, 6.0, false),
                ]),
            }],
        };
        let d = model.face_domain(0, None).unwrap();
        for (i, area) in [100.0, -36.0, 4.0].into_iter().enumerate() {
            assert!((d.loop_signed_area(i) - area).abs() < 1e-12, "loop {i}");
        }
        assert!((model.face_summaries(None)[0].area - 68.0).abs() < 1e-12);
    }

    #[test]
    fn missing_and_refused_faces_say_why() {
        let model = square_model(0.0, None);
        let msg = model.face_domain(3, None).unwrap_err().to_string();
        assert_eq!(
            msg,
            "STEP: face 3 does not exist: the file has 1 face (#face:0 to #face:0)"
        );
        let mut refused = model.clone();
        refused.faces[0].loops = Err("edge #9 has no pcurve".into());
        let msg = refused.face_domain(0, None).unwrap_err().to_string();
        assert_eq!(msg, "STEP face 0 (#7): edge #9 has no pcurve");
        let rows = refused.face_summaries(None);
        assert_eq!(rows[0].error.as_deref(), Some("edge #9 has no pcurve"));
        assert!(
            rows[0]
                .to_string()
                .contains("refused: edge #9 has no pcurve")
        );
        let rows = model.face_summaries(None);
        assert_eq!((rows[0].loops, rows[0].curves), (1, 4));
        assert!((rows[0].area - 1.0).abs() < 1e-12);
    }
}
