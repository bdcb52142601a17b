//! What a face's loops need to know about its surface: the surface itself (when it could be
//! read), the periods of its parameters and where their base period starts, its pole lines
//! and, for a plane, its coordinates. Everything is asked of `rs-geom`'s [`Surface`].

use rs_geom::surface::{ParamBox, ParamSurface};
use rs_geom::{Frame, PlaneCoordinates, Point, Point3, Surface, Tolerance};

/// Interior points of a joining segment checked to map to the same point of space as its
/// ends (a quarter, a half and three quarters along: a segment across whole periods of a
/// periodic parameter has an end-to-end image of one point but not its interior).
const DEGENERATE_SAMPLES: [f64; 3] = [0.25, 0.5, 0.75];

/// A face's surface, as the loops see it.
#[derive(Clone, Debug)]
pub(crate) struct FaceSurface {
    /// `#12`
    pub(crate) label: u64,
    /// The STEP type name (for a complex instance, its most specific record).
    pub(crate) name: String,
    /// The surface, `None` when it could not be read (the loops are then read without
    /// periods, poles or inversion: the pcurves cut at the 3-D curves' parameters).
    pub(crate) surface: Option<Surface>,
    /// The periods of `u` and `v`, where the surface is closed in them.
    pub(crate) period: [Option<f64>; 2],
    /// Where the base period of each closed parameter starts (the natural box's start: 0 for
    /// angles, the knot domain's start for B-spline surfaces): loops are moved by whole
    /// periods so that their middle lies in `[base, base + period)`, as `OpenCASCADE` places
    /// them.
    pub(crate) base: [f64; 2],
    /// The frame of a plane.
    pub(crate) plane: Option<Frame>,
}

impl FaceSurface {
    /// The surface `#label` of type `name`, read or not.
    pub(crate) fn new(label: u64, name: String, surface: Option<Surface>) -> FaceSurface {
        let (period, base) = match &surface {
            Some(s) => {
                let b = s.param_box();
                let start = |i: usize| {
                    let a = b.range(i).0;
                    if a.is_finite() { a } else { 0.0 }
                };
                (s.periods(), [start(0), start(1)])
            }
            None => ([None, None], [0.0; 2]),
        };
        let plane = match &surface {
            Some(Surface::Plane(p)) => Some(*p.frame()),
            _ => None,
        };
        FaceSurface {
            label,
            name,
            surface,
            period,
            base,
            plane,
        }
    }

    /// The coordinates of a plane's `(u, v)`.
    pub(crate) fn plane_coordinates(&self) -> Option<PlaneCoordinates> {
        self.plane.as_ref().map(PlaneCoordinates::new)
    }

    /// The natural parameter box, if the surface was read.
    pub(crate) fn param_box(&self) -> Option<ParamBox> {
        self.surface.as_ref().map(ParamSurface::param_box)
    }

    /// Whether `uv` lies outside the natural box by more than `tol` in a parameter that is not
    /// periodic (a sphere's latitude past a pole: a pcurve written a period off in a
    /// parameter the surface's formula happens to repeat in).
    pub(crate) fn outside_box(&self, uv: Point, tol: f64) -> bool {
        let Some(b) = self.param_box() else {
            return false;
        };
        (0..2).any(|i| {
            let (lo, hi) = b.range(i);
            let t = if i == 0 { uv.x } else { uv.y };
            self.period[i].is_none() && (t < lo - tol || t > hi + tol)
        })
    }

    /// Whether the straight segment from `a` to `b` in `(u, v)` is one point in space, so
    /// that a loop may cross it where the file leaves out a degenerate edge: both ends within
    /// `gap` of one of the surface's pole lines ([`ParamSurface::poles`]: sphere poles, a
    /// cone's apex, a B-spline or swept surface's degenerate boundary), or the surface maps
    /// the segment's ends and interior points ([`DEGENERATE_SAMPLES`]) within the model's
    /// coincidence tolerance of one point (a surface of revolution whose swept curve crosses
    /// its axis).
    pub(crate) fn is_pole_join(&self, a: Point, b: Point, gap: f64, tolerance: Tolerance) -> bool {
        let Some(s) = &self.surface else {
            return false;
        };
        let at = |p: Point, i: usize| if i == 0 { p.x } else { p.y };
        if s.poles().iter().any(|pole| {
            (at(a, pole.param) - pole.value).abs() <= gap
                && (at(b, pole.param) - pole.value).abs() <= gap
        }) {
            return true;
        }
        let point = |p: Point| s.point([p.x, p.y]);
        let pa = point(a);
        let others: Vec<Point3> = DEGENERATE_SAMPLES
            .iter()
            .map(|&t| point(a + (b - a) * t))
            .chain(std::iter::once(point(b)))
            .collect();
        let size = others.iter().fold(pa.max_abs(), |m, p| m.max(p.max_abs()));
        let tol = tolerance.coincidence(size);
        others.iter().all(|p| p.distance(pa) <= tol)
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, PI, TAU};

    use rs_geom::surface::{Cylinder, Revolution, Sphere};
    use rs_geom::{Conic, ConicKind, Curve};

    use super::*;

    fn face(s: Surface) -> FaceSurface {
        FaceSurface::new(1, "TEST".into(), Some(s))
    }

    #[test]
    fn pole_joins_are_segments_the_surface_maps_to_one_point() {
        let t = Tolerance::new(Some(1e-7)).unwrap();
        let p = Point::new;
        let sphere = face(Surface::Sphere(Sphere::new(Frame::WORLD, 2.0).unwrap()));
        assert_eq!(sphere.period, [Some(TAU), None]);
        assert!(sphere.is_pole_join(p(TAU, -FRAC_PI_2), p(0.0, -FRAC_PI_2), 1e-6, t));
        assert!(!sphere.is_pole_join(p(TAU, 0.0), p(0.0, 0.0), 1e-6, t));
        // A latitude a period off is outside the box (pcurves written there get inverted).
        assert!(sphere.outside_box(p(1.0, -FRAC_PI_2 - TAU), 1e-6));
        assert!(!sphere.outside_box(p(1.0 + TAU, 0.3), 1e-6));
        // A circle in a plane through the axis, centred on it (a sphere in disguise): the
        // lines v = +-pi/2 (where the circle crosses the axis) are points.
        let circle = Curve::Conic(Conic {
            kind: ConicKind::Ellipse,
            center: Point3::ORIGIN,
            u: Point3::new(1.0, 0.0, 0.0),
            v: Point3::new(0.0, 0.0, 1.0),
        });
        let rev = face(Surface::Revolution(
            Revolution::new(circle, Point3::ORIGIN, Point3::Z).unwrap(),
        ));
        assert!(rev.is_pole_join(p(0.0, FRAC_PI_2), p(1.5, FRAC_PI_2), 1e-6, t));
        assert!(!rev.is_pole_join(p(0.0, PI), p(1.5, PI), 1e-6, t));
        // Across a whole period of a cylinder: same ends, not a point.
        let cyl = face(Surface::Cylinder(Cylinder::new(Frame::WORLD, 1.0).unwrap()));
        assert!(!cyl.is_pole_join(p(0.0, 0.5), p(TAU, 0.5), 1e-6, t));
        assert!(!cyl.is_pole_join(p(0.0, 0.5), p(2.0 * TAU, 0.5), 1e-6, t));
        assert!(cyl.plane.is_none() && cyl.base == [0.0, 0.0]);
    }
}
