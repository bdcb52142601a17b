//! What the loops need to know about a face's surface: its name, the periods of its
//! parameters, its poles (parameter lines that are one point in space) and, for a plane, its
//! frame.

use std::f64::consts::{FRAC_PI_2, TAU};

use super::curves::Curve;
use super::geom::{self, Frame, V3};
use super::graph::Graph;
use super::shape::Shape;

/// A face's surface.
#[derive(Clone, Debug)]
pub(crate) struct Surface {
    /// `#12`
    pub(crate) label: u64,
    /// The STEP type name (for a complex instance, its most specific record).
    pub(crate) name: String,
    /// The periods of `u` and `v`, where the surface is closed in them.
    pub(crate) period: [Option<f64>; 2],
    /// Where the base period of each closed parameter starts (0 for angles, the knot
    /// domain's start for B-spline surfaces): loops are moved by whole periods so that their
    /// middle lies in `[base, base + period)`, as `OpenCASCADE` places them.
    pub(crate) base: [f64; 2],
    /// The values of `v` at which the whole line `v = const` is one point (sphere poles,
    /// cone apex).
    pub(crate) v_poles: Vec<f64>,
    /// The frame of a `PLANE`.
    pub(crate) plane: Option<Frame>,
    /// A `SURFACE_OF_REVOLUTION`'s swept curve and axis (point, unit direction): the line
    /// `v = const` is one point where the curve at `v` is on the axis.
    pub(crate) revolution: Option<(Curve, V3, V3)>,
    /// The geometry of a non-planar surface of a known type, to find the `(u, v)` of the
    /// edges' vertices (`None` for planes and types it does not know, or when it cannot be
    /// read: the pcurves are then cut at the 3-D curves' parameters).
    pub(crate) shape: Option<Shape>,
}

impl Surface {
    /// Reads the surface `#label`; `radians` per angle unit of the file. Only what the loops
    /// need is read; an unknown surface type is not an error (its pcurves are read all the
    /// same, without periods).
    pub(crate) fn read(g: &Graph, label: u64, from: &str, radians: f64) -> Result<Surface, String> {
        let inst = g.get(label, from)?;
        let name = inst.type_name();
        let what = inst.what();
        let mut s = Surface {
            label,
            name: name.clone(),
            period: [None, None],
            base: [0.0; 2],
            v_poles: Vec::new(),
            plane: None,
            revolution: None,
            shape: Shape::read(g, inst, radians).ok().flatten(),
        };
        match name.as_str() {
            "PLANE" => {
                let a = inst.simple()?;
                s.plane = Some(geom::placement(g, a.reference(1, "position")?, &what)?);
            }
            "CYLINDRICAL_SURFACE" => s.period[0] = Some(TAU),
            "SURFACE_OF_REVOLUTION" => {
                // ISO 10303-42: u is the angle of rotation, v the swept curve's parameter
                // (periodic when the curve is a circle or ellipse).
                let a = inst.simple()?;
                let curve = Curve::read(g, a.reference(1, "swept_curve")?, &what, 1.0)?;
                s.period = [Some(TAU), curve.period()];
                let ax = g.get(a.reference(2, "axis_position")?, &what)?;
                let axa = ax.record("AXIS1_PLACEMENT")?;
                let o = geom::point(g, axa.reference(1, "location")?, &ax.what())?;
                let d = match axa.get(2, "axis") {
                    Ok(super::graph::Value::Ref(r)) => geom::direction(g, *r, &ax.what())?,
                    _ => [0.0, 0.0, 1.0],
                };
                s.revolution = Some((curve, o, d));
            }
            "SPHERICAL_SURFACE" => {
                s.period[0] = Some(TAU);
                s.v_poles = vec![-FRAC_PI_2, FRAC_PI_2];
            }
            "CONICAL_SURFACE" => {
                s.period[0] = Some(TAU);
                // (R + v tan a)(cos u x + sin u y) + v z: the apex is at v = -R / tan a.
                let a = inst.simple()?;
                let (r, angle) = (a.real(2, "radius")?, a.real(3, "semi_angle")? * radians);
                let apex = -r / angle.tan();
                if apex.is_finite() {
                    s.v_poles.push(apex);
                }
            }
            "TOROIDAL_SURFACE" | "DEGENERATE_TOROIDAL_SURFACE" => s.period = [Some(TAU); 2],
            "SURFACE_OF_LINEAR_EXTRUSION" => {
                if let Some(Shape::Extrusion { curve, .. }) = &s.shape {
                    s.period[0] = curve.period();
                }
            }
            _ if inst.is("B_SPLINE_SURFACE") || inst.is("B_SPLINE_SURFACE_WITH_KNOTS") => {
                let p = bspline_periods(g, inst).unwrap_or([None, None]);
                for (d, pd) in p.into_iter().enumerate() {
                    if let Some((a, len)) = pd {
                        s.period[d] = Some(len);
                        s.base[d] = a;
                    }
                }
            }
            _ => {}
        }
        Ok(s)
    }
}

impl Surface {
    /// Whether the straight segment from `a` to `b` in `(u, v)` is one point in space: both on
    /// a pole line `v = const` (sphere, cone), or on a line `v = const` of a surface of
    /// revolution whose swept curve meets the axis there.
    pub(crate) fn is_pole_join(&self, a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
        if self
            .v_poles
            .iter()
            .any(|&v| (a[1] - v).abs() <= tol && (b[1] - v).abs() <= tol)
        {
            return true;
        }
        if let Some((c, o, d)) = &self.revolution
            && (a[1] - b[1]).abs() <= tol
        {
            let p = geom::sub(c.point(a[1]), *o);
            let off = geom::sub(p, geom::scale(*d, geom::dot(p, *d)));
            return geom::norm(off) <= tol;
        }
        false
    }
}

/// A closed B-spline surface's knot-domain start and length in the closed directions.
fn bspline_periods(_g: &Graph, inst: &super::graph::Instance) -> Option<[Option<(f64, f64)>; 2]> {
    // Simple: (name, u_degree, v_degree, points, form, u_closed, v_closed, self_int,
    // u_mults, v_mults, u_knots, v_knots, spec); complex: B_SPLINE_SURFACE(u_degree,
    // v_degree, points, form, u_closed, v_closed, self_int) and
    // B_SPLINE_SURFACE_WITH_KNOTS(u_mults, v_mults, u_knots, v_knots, spec).
    let (s, s0, k, k0) = if inst.is_complex() {
        (
            inst.record("B_SPLINE_SURFACE").ok()?,
            0,
            inst.record("B_SPLINE_SURFACE_WITH_KNOTS").ok()?,
            0,
        )
    } else {
        let a = inst.record("B_SPLINE_SURFACE_WITH_KNOTS").ok()?;
        (a, 1, a, 8)
    };
    let mut out = [None, None];
    for (d, slot) in out.iter_mut().enumerate() {
        if s.boolean(s0 + 4 + d, "closed").ok()? {
            let knots = k.reals(k0 + 2 + d, "knots").ok()?;
            let mults = k.reals(k0 + d, "multiplicities").ok()?;
            let degree = s.real(s0 + d, "degree").ok()?;
            // The domain runs from the knot of index `degree` to the one `degree` from the
            // end, counting multiplicities.
            let mut expanded = Vec::new();
            for (m, x) in mults.iter().zip(&knots) {
                if !(*m >= 0.0 && *m <= 64.0) || expanded.len() > 1 << 16 {
                    return None;
                }
                expanded.extend(std::iter::repeat_n(*x, *m as usize));
            }
            let p = degree as usize;
            let a = *expanded.get(p)?;
            let b = *expanded.get(expanded.len().checked_sub(p + 1)?)?;
            *slot = (b > a).then_some((a, b - a));
        }
    }
    Some(out)
}
