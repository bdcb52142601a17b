//! Pcurves on planes: the edge mapped into the plane's `(u, v)` by the affine map of its
//! coordinates, exactly (lines stay lines, conics rational quadratics, B-splines keep knots
//! and weights), then converted piece by piece with [`Curve::to_bspline_mapped`]: the
//! arithmetic of the CAD readers' planar faces, so their bytes stay.

use rs_spline::{Affine, ParamCurve, Point3};

use super::{Context, Pcurve, PcurveKind};
use crate::surface::{ParamSurface, Surface};
use crate::{GeomError, PlaneCoordinates};

/// Samples per piece searched for the worst point of an edge whose control points leave the
/// plane by more than the limit (to name its parameter, or find it is within the limit).
const OFF_PLANE_SAMPLES: usize = 32;

/// The `(u, v)` of a planar surface: its plane's coordinates, then (for a reparameterised
/// plane) a map of the plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct PlaneMap {
    /// The coordinates of the plane (its origin moved along the normal for an offset).
    coords: PlaneCoordinates,
    /// The plane's unit normal.
    normal: Point3,
    /// The surface's `(u, v)` of the plane's coordinates, when they differ.
    affine: Option<Affine>,
}

impl PlaneMap {
    /// The map of a plane, an offset plane or a reparameterised one; `None` for any other
    /// surface.
    pub(super) fn of(surface: &Surface) -> Option<PlaneMap> {
        match surface {
            Surface::Plane(p) => Some(PlaneMap {
                coords: PlaneCoordinates::new(p.frame()),
                normal: p.frame().z,
                affine: None,
            }),
            Surface::Offset(o) => {
                let mut map = PlaneMap::of(o.base())?;
                // The base's unit normal (the plane's, turned by an orientation-reversing
                // reparameterisation) is the offset's direction.
                let n = o.base().normal([0.0, 0.0])?;
                map.coords.origin = map.coords.origin + n * o.distance();
                Some(map)
            }
            Surface::Reparam(r) => {
                let mut map = PlaneMap::of(r.base())?;
                // Our (u, v) of the base's (s, t): ours(k) = (st[k] - offset[k]) / scale[k].
                let ([a0, a1], [o0, o1]) = (r.scale(), r.offset());
                let (p, q) = ((1.0 / a0, -o0 / a0), (1.0 / a1, -o1 / a1));
                let ours = if r.swap() {
                    Affine {
                        m: [0.0, p.0, q.0, 0.0, q.1, p.1],
                    }
                } else {
                    Affine {
                        m: [p.0, 0.0, 0.0, q.0, p.1, q.1],
                    }
                };
                map.affine = Some(match map.affine {
                    Some(inner) => ours.then_apply_to(inner),
                    None => ours,
                });
                Some(map)
            }
            _ => None,
        }
    }

    /// The signed distance of `x` from the plane.
    fn height(&self, x: Point3) -> f64 {
        (x - self.coords.origin).dot(self.normal)
    }
}

/// The exact pcurve of the edge on the pieces `pieces` of its parameter (increasing), in the
/// edge's direction (reversed when `reversed`), with the edge's largest distance from the
/// plane as its deviation (the largest of its pieces' control points', which bound it).
///
/// # Errors
/// [`GeomError::EdgeOffSurface`] where a sample of the edge is farther from the plane than
/// the context's limit; the conversion errors of [`crate::Curve::to_bspline_mapped`].
pub(super) fn pcurve(
    ctx: &Context<'_>,
    map: &PlaneMap,
    pieces: &[(f64, f64)],
    reversed: bool,
) -> Result<Pcurve, GeomError> {
    let mut curves = Vec::with_capacity(pieces.len());
    let mut deviation = 0.0f64;
    for &(a, b) in pieces {
        let mut c = ctx.edge.to_bspline_mapped(&map.coords, a, b)?.to_planar()?;
        if let Some(m) = map.affine {
            c = m.apply_to_curve(&c)?;
        }
        curves.push(c);
        let hull = ctx.edge.to_bspline(a, b)?;
        for &p in hull.control_points() {
            deviation = deviation.max(map.height(p).abs());
        }
    }
    if deviation > ctx.off_limit || deviation.is_nan() {
        // The control points are too far: find the worst point itself.
        let mut worst = (0.0f64, pieces[0].0);
        for &(a, b) in pieces {
            for i in 0..=OFF_PLANE_SAMPLES {
                let t = a + (b - a) * i as f64 / OFF_PLANE_SAMPLES as f64;
                let d = map.height(ctx.edge.point(t)).abs();
                if d > worst.0 || d.is_nan() {
                    worst = (d, t);
                }
            }
        }
        if worst.0 > ctx.off_limit || worst.0.is_nan() {
            return Err(GeomError::EdgeOffSurface {
                surface: ctx.surface.kind_name(),
                distance: worst.0,
                parameter: worst.1,
                limit: ctx.off_limit,
            });
        }
    }
    if reversed {
        curves.reverse();
        for c in &mut curves {
            *c = c.reversed();
        }
    }
    Ok(Pcurve {
        curves,
        kind: PcurveKind::Plane,
        deviation,
        rigorous: true,
    })
}
