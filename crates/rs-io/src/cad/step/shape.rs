//! The geometry of a face's non-planar surface, enough to evaluate it and find the `(u, v)`
//! of a point on it (see `invert`). Parametrisations (ISO 10303-42, angles in radians, the
//! placement's frame `x, y, z` at `c`):
//! - `CYLINDRICAL_SURFACE`: `c + r (cos u x + sin u y) + v z`;
//! - `CONICAL_SURFACE`: `c + (r + v tan a) (cos u x + sin u y) + v z`;
//! - `SPHERICAL_SURFACE`: `c + r cos v (cos u x + sin u y) + r sin v z`;
//! - `TOROIDAL_SURFACE`: `c + (R + r cos v) (cos u x + sin u y) + r sin v z`;
//! - `SURFACE_OF_REVOLUTION`: the swept curve at `v` turned by `u` about the axis;
//! - `SURFACE_OF_LINEAR_EXTRUSION`: the swept curve at `u` plus `v` times the extrusion vector;
//! - B-spline surfaces (simple `B_SPLINE_SURFACE_WITH_KNOTS` or the complex instance with
//!   `RATIONAL_B_SPLINE_SURFACE`): their knots, the control points indexed `[u][v]`.

use rs_spline::KnotVector;
use rs_spline::limits::MAX_DEGREE;

use super::curves::Curve;
use super::geom::{self, Frame, V3, add, cross, dot, scale, sub};
use super::graph::{Attrs, Graph, Instance, Value, value_count, value_real};

/// A surface that can be evaluated.
#[derive(Clone, Debug)]
pub(crate) enum Shape {
    Cylinder { f: Frame, r: f64 },
    Cone { f: Frame, r: f64, tan: f64 },
    Sphere { f: Frame, r: f64 },
    Torus { f: Frame, major: f64, minor: f64 },
    Revolution { curve: Curve, o: V3, d: V3 },
    Extrusion { curve: Curve, d: V3 },
    Spline(SplineSurface),
}

/// A (rational) B-spline surface.
#[derive(Clone, Debug)]
pub(crate) struct SplineSurface {
    /// `nu * nv` points (`n_control()` of the two knot vectors), `[i][j]` at `i * nv + j`.
    pub(crate) points: Vec<V3>,
    pub(crate) weights: Option<Vec<f64>>,
    /// The knot vectors in `u` and `v` (with their degrees and control-point counts).
    pub(crate) knots: [KnotVector; 2],
}

impl Shape {
    /// The geometry of surface `inst`; `radians` per angle unit of the file. `None` for a
    /// plane or a type not listed above.
    pub(crate) fn read(g: &Graph, inst: &Instance, radians: f64) -> Result<Option<Shape>, String> {
        let what = inst.what();
        if inst.is("B_SPLINE_SURFACE_WITH_KNOTS") {
            return Ok(Some(Shape::Spline(spline_surface(g, inst)?)));
        }
        let Ok(a) = inst.simple() else {
            return Ok(None);
        };
        let frame = || geom::placement(g, a.reference(1, "position")?, &what);
        let positive = |x: f64, name: &str| {
            if x > 0.0 && x.is_finite() {
                Ok(x)
            } else {
                Err(format!("{what}: {name} {x}"))
            }
        };
        let shape = match a.part.name.as_str() {
            "CYLINDRICAL_SURFACE" => Shape::Cylinder {
                f: frame()?,
                r: positive(a.real(2, "radius")?, "radius")?,
            },
            "CONICAL_SURFACE" => {
                let r = a.real(2, "radius")?;
                let tan = (a.real(3, "semi_angle")? * radians).tan();
                if !(r >= 0.0 && r.is_finite() && tan.is_finite()) {
                    return Err(format!("{what}: radius {r}, semi-angle tangent {tan}"));
                }
                Shape::Cone {
                    f: frame()?,
                    r,
                    tan,
                }
            }
            "SPHERICAL_SURFACE" => Shape::Sphere {
                f: frame()?,
                r: positive(a.real(2, "radius")?, "radius")?,
            },
            "TOROIDAL_SURFACE" | "DEGENERATE_TOROIDAL_SURFACE" => Shape::Torus {
                f: frame()?,
                major: positive(a.real(2, "major_radius")?, "major_radius")?,
                minor: positive(a.real(3, "minor_radius")?, "minor_radius")?,
            },
            "SURFACE_OF_REVOLUTION" => {
                let curve = Curve::read(g, a.reference(1, "swept_curve")?, &what, radians)?;
                let ax = g.get(a.reference(2, "axis_position")?, &what)?;
                let axa = ax.record("AXIS1_PLACEMENT")?;
                let o = geom::point(g, axa.reference(1, "location")?, &ax.what())?;
                let d = match axa.get(2, "axis") {
                    Ok(Value::Ref(r)) => geom::direction(g, *r, &ax.what())?,
                    _ => [0.0, 0.0, 1.0],
                };
                Shape::Revolution { curve, o, d }
            }
            "SURFACE_OF_LINEAR_EXTRUSION" => {
                let curve = Curve::read(g, a.reference(1, "swept_curve")?, &what, radians)?;
                let vi = g.get(a.reference(2, "extrusion_axis")?, &what)?;
                let va = vi.record("VECTOR")?;
                let d = geom::direction(g, va.reference(1, "orientation")?, &vi.what())?;
                let m = positive(va.real(2, "magnitude")?, "magnitude")?;
                Shape::Extrusion {
                    curve,
                    d: scale(d, m),
                }
            }
            _ => return Ok(None),
        };
        Ok(Some(shape))
    }

    /// The point at `(u, v)` (B-spline parameters clamped to their domain).
    pub(crate) fn point(&self, u: f64, v: f64) -> V3 {
        let ring = |f: &Frame, rho: f64, h: f64| {
            add(
                f.origin,
                add(
                    scale(add(scale(f.x, u.cos()), scale(f.y, u.sin())), rho),
                    scale(f.z, h),
                ),
            )
        };
        match self {
            Shape::Cylinder { f, r } => ring(f, *r, v),
            Shape::Cone { f, r, tan } => ring(f, r + v * tan, v),
            Shape::Sphere { f, r } => ring(f, r * v.cos(), r * v.sin()),
            Shape::Torus { f, major, minor } => ring(f, major + minor * v.cos(), minor * v.sin()),
            Shape::Revolution { curve, o, d } => {
                // Rodrigues: p cos u + (d . p) d (1 - cos u) + (d x p) sin u.
                let p = sub(curve.point(v), *o);
                let (s, c) = u.sin_cos();
                add(
                    *o,
                    add(
                        add(scale(p, c), scale(*d, dot(*d, p) * (1.0 - c))),
                        scale(cross(*d, p), s),
                    ),
                )
            }
            Shape::Extrusion { curve, d } => add(curve.point(u), scale(*d, v)),
            Shape::Spline(s) => s.point(u, v),
        }
    }

    /// The parameter domain of a bounded parameter (B-spline knots, a bounded swept curve).
    pub(crate) fn domain(&self, d: usize) -> Option<(f64, f64)> {
        match (self, d) {
            (Shape::Spline(s), _) => s.domain(d),
            (Shape::Revolution { curve, .. }, 1) | (Shape::Extrusion { curve, .. }, 0) => {
                curve.range()
            }
            _ => None,
        }
    }
}

impl SplineSurface {
    fn domain(&self, d: usize) -> Option<(f64, f64)> {
        Some(self.knots.get(d)?.domain())
    }

    /// The point at `(u, v)`, each clamped to its domain; NaN where the surface is degenerate.
    fn point(&self, u: f64, v: f64) -> V3 {
        let nan = [f64::NAN; 3];
        let (Some((iu, bu)), Some((iv, bv))) = (self.basis(0, u), self.basis(1, v)) else {
            return nan;
        };
        let (p, q) = (self.knots[0].degree(), self.knots[1].degree());
        let nv = self.knots[1].n_control();
        let mut h = [0.0; 4];
        for (a, nu) in bu.iter().enumerate().take(p + 1) {
            for (b, nv_b) in bv.iter().enumerate().take(q + 1) {
                let k = (iu - p + a) * nv + (iv - q + b);
                let (Some(x), w) = (
                    self.points.get(k),
                    self.weights
                        .as_ref()
                        .map_or(Some(1.0), |w| w.get(k).copied()),
                ) else {
                    return nan;
                };
                let c = nu * nv_b * w.unwrap_or(f64::NAN);
                h = [h[0] + c * x[0], h[1] + c * x[1], h[2] + c * x[2], h[3] + c];
            }
        }
        [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
    }

    /// The span index `k` holding `t` (clamped; NaN reads as the domain's start) in direction
    /// `d` and the `degree + 1` basis functions non-zero there ([`KnotVector::span`],
    /// [`KnotVector::basis_derivatives`]).
    fn basis(&self, d: usize, t: f64) -> Option<(usize, Vec<f64>)> {
        let kv = self.knots.get(d)?;
        let (a, b) = kv.domain();
        let t = if t.is_nan() { a } else { t.clamp(a, b) };
        let i = kv.span(t);
        let values = kv.basis_derivatives(i, t, 0).into_iter().next()?;
        Some((i, values))
    }
}

/// Reads a B-spline surface, simple or complex. Every count is checked against the points
/// the file lists before a knot vector is expanded.
fn spline_surface(g: &Graph, inst: &Instance) -> Result<SplineSurface, String> {
    let what = inst.what();
    // (u_degree, v_degree, control_points_list, ...) and (u_mults, v_mults, u_knots,
    // v_knots, ...), offset by the name in a simple instance.
    let (s, s0, k, k0) = if inst.is_complex() {
        (
            inst.record("B_SPLINE_SURFACE")?,
            0,
            inst.record("B_SPLINE_SURFACE_WITH_KNOTS")?,
            0,
        )
    } else {
        let a = inst.record("B_SPLINE_SURFACE_WITH_KNOTS")?;
        (a, 1, a, 8)
    };
    let degree = [
        s.count(s0, "u_degree", MAX_DEGREE)?,
        s.count(s0 + 1, "v_degree", MAX_DEGREE)?,
    ];
    if degree.contains(&0) {
        return Err(format!("{what}: degree 0"));
    }
    let rows = s.list(s0 + 2, "control_points_list")?;
    let nv = match rows.first() {
        Some(Value::List(r)) => r.len(),
        _ => 0,
    };
    let count = [rows.len(), nv];
    if count[0] <= degree[0] || count[1] <= degree[1] {
        return Err(format!(
            "{what}: {}x{} control points for degrees {degree:?}",
            count[0], count[1]
        ));
    }
    // Grown as the points are read (rows of unequal length are found only on the way).
    let mut points = Vec::with_capacity(count[0].saturating_mul(count[1]).min(1 << 16));
    for r in rows {
        let Value::List(r) = r else {
            return Err(format!(
                "{what}: control_points_list is not a list of lists"
            ));
        };
        if r.len() != nv {
            return Err(format!("{what}: rows of control points of unequal length"));
        }
        for p in r {
            let Value::Ref(l) = p else {
                return Err(format!("{what}: control point is not a reference"));
            };
            points.push(geom::point(g, *l, &what)?);
        }
    }
    let knots = [
        expand(&k, k0, k0 + 2, count[0] + degree[0] + 1, &what)?,
        expand(&k, k0 + 1, k0 + 3, count[1] + degree[1] + 1, &what)?,
    ];
    let weights = match inst.record("RATIONAL_B_SPLINE_SURFACE") {
        Ok(r) => {
            let mut w = Vec::with_capacity(points.len());
            for row in r.list(0, "weights_data")? {
                let Value::List(row) = row else {
                    return Err(format!("{what}: weights_data is not a list of lists"));
                };
                for x in row {
                    let x = value_real(x).unwrap_or(f64::NAN);
                    if !(x > 0.0 && x.is_finite()) {
                        return Err(format!("{what}: weight {x}"));
                    }
                    w.push(x);
                }
            }
            if w.len() != points.len() {
                return Err(format!(
                    "{what}: {} weights for {} control points",
                    w.len(),
                    points.len()
                ));
            }
            Some(w)
        }
        Err(_) => None,
    };
    let [ku, kv] = knots;
    let knot_vector = |knots, d: usize| {
        KnotVector::new(knots, degree[d], count[d]).map_err(|e| format!("{what}: {e}"))
    };
    Ok(SplineSurface {
        points,
        weights,
        knots: [knot_vector(ku, 0)?, knot_vector(kv, 1)?],
    })
}

/// The knot vector of `total` knots from the multiplicities at `mi` and knots at `ki`.
fn expand(
    k: &Attrs<'_>,
    mi: usize,
    ki: usize,
    total: usize,
    what: &str,
) -> Result<Vec<f64>, String> {
    let mults = k.list(mi, "multiplicities")?;
    let kv = k.reals(ki, "knots")?;
    if mults.len() != kv.len() {
        return Err(format!(
            "{what}: {} knot multiplicities for {} knots",
            mults.len(),
            kv.len()
        ));
    }
    let mut out = Vec::with_capacity(total);
    for (m, x) in mults.iter().zip(&kv) {
        let m = value_real(m)
            .and_then(|m| value_count(m, total))
            .filter(|m| out.len() + m <= total)
            .ok_or_else(|| format!("{what}: knot multiplicities do not add up to {total}"))?;
        out.extend(std::iter::repeat_n(*x, m));
    }
    if out.len() != total || out.windows(2).any(|w| w[1] < w[0]) {
        return Err(format!(
            "{what}: {} knots (need {total}, non-decreasing)",
            out.len()
        ));
    }
    Ok(out)
}
