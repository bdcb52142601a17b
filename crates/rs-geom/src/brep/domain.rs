//! A face's trimming loops as a domain: closed within the model's tolerance, watertight
//! joints, loops oriented by their nesting (positive area).

use rs_contain::loop_nesting;
use rs_spline::limits::NonNegative;
use rs_spline::prelude::*;
use rs_spline::{BoundingBox, DEFAULT_RELATIVE_CLOSURE_TOLERANCE, Domain, DomainError, NurbsCurve};

use super::{Face, FaceError, Model, ModelError};

impl Model {
    /// Face `index` (`#face:K`) as a domain in its surface's `(u, v)`.
    ///
    /// `relative_closure_tolerance`: the largest gap between consecutive trimming curves that
    /// still counts as meeting, relative to the diagonal of the face's `(u, v)` box; `None`
    /// takes [`Tolerance::closure_gap`](crate::Tolerance::closure_gap)'s default from the
    /// file's tolerance. Gaps within it are closed by moving each curve's end onto the next
    /// curve's start (bit-identical joints). Loops are reversed where their orientation
    /// disagrees with their nesting, so that the face's area is positive (outer loops
    /// counter-clockwise, holes clockwise), whatever the file's orientation flags made them.
    ///
    /// # Errors
    /// [`ModelError::NoFace`] past the last face, [`ModelError::Face`] for a face that cannot
    /// be read or whose loop has a gap beyond the tolerance, [`ModelError::Domain`] for an
    /// invalid tolerance.
    pub fn face_domain(
        &self,
        index: usize,
        relative_closure_tolerance: Option<f64>,
    ) -> Result<Domain, ModelError> {
        let face = self.faces.get(index).ok_or(ModelError::NoFace {
            index,
            count: self.faces.len(),
        })?;
        if let Some(t) = relative_closure_tolerance {
            NonNegative::new(t).map_err(|e| DomainError::InvalidTolerance(e.0))?;
        }
        let fail = |error: FaceError| ModelError::Face {
            index,
            entity: face.entity.clone(),
            error,
        };
        let domain = face_loops_domain(self, face, relative_closure_tolerance).map_err(fail)?;
        Ok(domain.with_name(format!("face {index} ({})", face.entity)))
    }

    /// Every face as a domain ([`Model::face_domain`]), in face order, each `Err` for a face
    /// that cannot be read.
    pub fn face_domains(
        &self,
        relative_closure_tolerance: Option<f64>,
    ) -> Vec<Result<Domain, ModelError>> {
        (0..self.faces.len())
            .map(|index| self.face_domain(index, relative_closure_tolerance))
            .collect()
    }
}

impl Face {
    /// The bounding box of the face's trimming curves in `(u, v)`, `None` without curves or
    /// for a face whose loops could not be read.
    pub fn loops_box(&self) -> Option<BoundingBox> {
        self.loops
            .as_ref()
            .ok()?
            .iter()
            .flatten()
            .map(NurbsCurve::bounding_box)
            .reduce(BoundingBox::union)
    }
}

/// The domain of `face`'s loops (see [`Model::face_domain`]).
fn face_loops_domain(
    model: &Model,
    face: &Face,
    relative: Option<f64>,
) -> Result<Domain, FaceError> {
    let loops = face.loops.as_ref().map_err(Clone::clone)?;
    let bbox = face.loops_box().ok_or(FaceError::NoCurves)?;
    let tolerance = model.tolerance.closure_gap(&bbox, relative);
    let mut curves = Vec::new();
    for (l, curve_loop) in loops.iter().enumerate() {
        curves.extend(watertight(curve_loop, tolerance).map_err(|(k, next, gap)| {
            FaceError::Gap {
                loop_index: l,
                curve: k,
                next,
                gap,
                tolerance,
            }
        })?);
    }
    let diagonal = bbox.diagonal();
    let relative = if diagonal > 0.0 {
        tolerance / diagonal
    } else {
        DEFAULT_RELATIVE_CLOSURE_TOLERANCE
    };
    let domain = Domain::with_relative_closure_tolerance(curves.clone(), relative)?;
    let flips = loops_to_reverse(&domain);
    if flips.is_empty() {
        return Ok(domain);
    }
    for i in flips {
        let r = domain.loops()[i].curves();
        curves[r.clone()].reverse();
        for c in &mut curves[r] {
            *c = c.reversed();
        }
    }
    Ok(Domain::with_relative_closure_tolerance(curves, relative)?)
}

/// The loops of `d` whose orientation disagrees with their nesting: a loop inside an even
/// number of the other loops should run counter-clockwise, inside an odd number clockwise
/// (nesting by [`loop_nesting`]: exact winding numbers at a point of each loop). None when the
/// nesting cannot be told (loops lying on each other): the loops then stay as the file has
/// them, which containment does not depend on.
fn loops_to_reverse(d: &Domain) -> Vec<usize> {
    let Some(nesting) = loop_nesting(d) else {
        return Vec::new();
    };
    nesting
        .iter()
        .enumerate()
        .filter(|(i, n)| {
            let area = d.loop_signed_area(*i);
            area != 0.0 && (area > 0.0) != (n.depth % 2 == 0)
        })
        .map(|(i, _)| i)
        .collect()
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
    use crate::Tolerance;

    fn face(loops: Vec<Vec<NurbsCurve>>) -> Face {
        Face {
            entity: "#7".into(),
            surface_name: "PLANE".into(),
            surface: None,
            surface_error: None,
            same_sense: true,
            loops: Ok(loops),
            edges: Vec::new(),
            pcurve_deviation: None,
            natural_bounds: false,
        }
    }

    /// A unit square drawn clockwise whose second corner misses by `gap`, as a one-face model
    /// with the file tolerance `tolerance`.
    fn square_model(gap: f64, tolerance: Option<f64>) -> Model {
        let p = |x, y| Point::new(x, y);
        let lines = vec![
            segment(p(0.0, 0.0), p(0.0, 1.0)).unwrap(),
            segment(p(0.0, 1.0 + gap), p(1.0, 1.0)).unwrap(),
            segment(p(1.0, 1.0), p(1.0, 0.0)).unwrap(),
            segment(p(1.0, 0.0), p(0.0, 0.0)).unwrap(),
        ];
        Model {
            faces: vec![face(vec![lines])],
            tolerance: Tolerance::new(tolerance).unwrap(),
            ..Model::default()
        }
    }

    #[test]
    fn gaps_within_the_file_tolerance_close_watertight_and_the_area_is_positive() {
        let d = square_model(5e-8, Some(1e-7)).face_domain(0, None).unwrap();
        assert!(d.is_closed());
        assert_eq!(d.loops().len(), 1);
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
        assert!(
            e.to_string().starts_with(
                "face 0 (#7): loop 0: curve 0 ends 5.00e-8 away from the start of curve 1"
            ),
            "{e}"
        );
        // A relative closure tolerance given by the caller joins them.
        let d = square_model(5e-8, None).face_domain(0, Some(1e-7)).unwrap();
        assert!(d.is_closed());
        assert!(
            square_model(0.0, None)
                .face_domain(0, Some(f64::NAN))
                .is_err()
        );
        let e = square_model(0.0, None).face_domain(3, None).unwrap_err();
        assert_eq!(
            e.to_string(),
            "face 3 does not exist: the file has 1 face (#face:0 to #face:0)"
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
        let model = Model {
            faces: vec![face(vec![
                square(0.0, 10.0, false),
                square(2.0, 8.0, true),
                square(4.0, 6.0, false),
            ])],
            ..Model::default()
        };
        let d = model.face_domain(0, None).unwrap();
        for (i, area) in [100.0, -36.0, 4.0].into_iter().enumerate() {
            assert!((d.loop_signed_area(i) - area).abs() < 1e-12, "loop {i}");
        }
    }
}
