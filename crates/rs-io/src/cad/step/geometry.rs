//! STEP geometry read into `rs-geom` objects: points, directions and placements ([`Frame`]),
//! curves of the plane and of space ([`Curve<Point>`], [`Curve<Point3>`]) and surfaces
//! ([`Surface`]), each in ISO 10303-42's parameterisation (see `rs_geom::curve` and
//! `rs_geom::surface`), angles converted to radians with the file's plane angle unit.
//!
//! Curves: `LINE`, `CIRCLE`, `ELLIPSE`, `HYPERBOLA`, `PARABOLA`, `B_SPLINE_CURVE_WITH_KNOTS`
//! (simple, or the complex instance with `RATIONAL_B_SPLINE_CURVE`), the complex instances of
//! `UNIFORM_CURVE`, `QUASI_UNIFORM_CURVE` and `BEZIER_CURVE` (whose knots ISO 10303-42
//! defines), `POLYLINE` (the degree-1 B-spline through its points with knots `1, 2, ..., n`)
//! and `TRIMMED_CURVE` (sense `.T.`; the window of its basis curve).
//!
//! Surfaces: `PLANE`, `CYLINDRICAL_SURFACE`, `CONICAL_SURFACE`, `SPHERICAL_SURFACE`,
//! `TOROIDAL_SURFACE`, `DEGENERATE_TOROIDAL_SURFACE`, `SURFACE_OF_REVOLUTION`,
//! `SURFACE_OF_LINEAR_EXTRUSION`, `OFFSET_SURFACE`, `B_SPLINE_SURFACE_WITH_KNOTS` (simple or
//! complex, rational or not; the uniform, quasi-uniform and Bezier forms), and
//! `RECTANGULAR_TRIMMED_SURFACE` as its basis surface. A file whose angle unit is not the
//! radian keeps its pcurves' angles in its own unit: the surfaces with angle parameters are
//! read as an `rs_geom::surface::Reparam` scaling them.

use std::ops::Div;

use rs_geom::surface::{
    BSplineSurface, Cone, Cylinder, Extrusion, Offset, Plane, Reparam, Revolution, Sphere, Torus,
};
use rs_geom::{Conic, ConicKind, Curve, Frame, GeomError, Point, Point3, Surface, Vector};
use rs_spline::limits::{MAX_COORDINATE, MAX_DEGREE};
use rs_spline::{KnotVector, RationalBSpline};

use super::error::{Result, StepError};
use super::graph::{Attrs, Graph, Instance, Value, value_count, value_real};

/// The deepest chain of `TRIMMED_CURVE`s followed to the basis curve.
const MAX_TRIM_CHAIN: usize = 4;

/// The deepest chain of surfaces built on surfaces (`OFFSET_SURFACE`,
/// `RECTANGULAR_TRIMMED_SURFACE`) followed to the basis surface.
const MAX_SURFACE_CHAIN: usize = 8;

/// The spaces curves are read in: the plane of pcurves and model space. A point of either is
/// read from 1 to 3 coordinates (missing ones are 0; the plane ignores a third).
pub(crate) trait Space: Vector + Div<f64, Output = Self> + Copy + std::fmt::Debug {
    /// The point of these coordinates.
    fn from_coords(c: [f64; 3]) -> Self;
    /// The point of model space (for the plane: its first two coordinates).
    fn from_point3(p: Point3) -> Self;
}

impl Space for Point {
    fn from_coords(c: [f64; 3]) -> Self {
        Point::new(c[0], c[1])
    }
    fn from_point3(p: Point3) -> Self {
        Point::new(p.x, p.y)
    }
}

impl Space for Point3 {
    fn from_coords(c: [f64; 3]) -> Self {
        Point3::new(c[0], c[1], c[2])
    }
    fn from_point3(p: Point3) -> Self {
        p
    }
}

/// The coordinates of a `CARTESIAN_POINT` (1 to 3 of them, the missing ones 0), each finite
/// and within [`MAX_COORDINATE`].
pub(crate) fn coords(g: &Graph, label: u64, from: &str) -> Result<[f64; 3]> {
    let inst = g.get(label, from)?;
    let a = inst.record("CARTESIAN_POINT")?;
    list_coords(&a, 1, "coordinates")
}

/// A `CARTESIAN_POINT` of model space.
pub(crate) fn point3(g: &Graph, label: u64, from: &str) -> Result<Point3> {
    coords(g, label, from).map(Point3::from)
}

fn list_coords(a: &Attrs<'_>, i: usize, name: &'static str) -> Result<[f64; 3]> {
    let v = a.reals(i, name)?;
    if !(1..=3).contains(&v.len()) {
        return Err(StepError::invalid(
            a.inst.what(),
            format!("{} coordinates", v.len()),
        ));
    }
    if v.iter().any(|x| x.abs() > MAX_COORDINATE) {
        return Err(StepError::invalid(
            a.inst.what(),
            format!("coordinate beyond {MAX_COORDINATE:e}"),
        ));
    }
    let mut p = [0.0; 3];
    p[..v.len()].copy_from_slice(&v);
    Ok(p)
}

/// The ratios of a `DIRECTION`, as written (not normalised).
fn direction_ratios(g: &Graph, label: u64, from: &str) -> Result<Point3> {
    let inst = g.get(label, from)?;
    let a = inst.record("DIRECTION")?;
    list_coords(&a, 1, "direction_ratios").map(Point3::from)
}

/// A `DIRECTION`, normalised; a zero direction is an error.
pub(crate) fn direction(g: &Graph, label: u64, from: &str) -> Result<Point3> {
    let d = direction_ratios(g, label, from)?;
    d.normalized().ok_or_else(|| {
        StepError::invalid(
            g.get(label, from).map(Instance::what).unwrap_or_default(),
            "zero direction",
        )
    })
}

/// An optional direction attribute (`$` or missing: `None`), as written.
fn optional_direction(
    g: &Graph,
    a: &Attrs<'_>,
    i: usize,
    name: &'static str,
) -> Result<Option<Point3>> {
    match a.get(i, name) {
        Ok(Value::Ref(r)) => direction_ratios(g, *r, &a.inst.what()).map(Some),
        Ok(Value::Unset) | Err(_) => Ok(None),
        Ok(_) => Err(StepError::Attribute {
            what: a.inst.what(),
            index: i,
            name,
            problem: "is not a reference".into(),
        }),
    }
}

/// An `AXIS2_PLACEMENT_3D` or `AXIS2_PLACEMENT_2D` (in the plane `z = 0`, axis `z`) as a
/// [`Frame`] built as ISO 10303-42's `build_axes` ([`Frame::new`]); defaults are the global
/// axes. Axes that do not span space are an error naming the placement.
pub(crate) fn placement(g: &Graph, label: u64, from: &str) -> Result<Frame> {
    let inst = g.get(label, from)?;
    let what = inst.what();
    let (origin, axis, reference) = if let Ok(a) = inst.record("AXIS2_PLACEMENT_3D") {
        (
            point3(g, a.reference(1, "location")?, &what)?,
            optional_direction(g, &a, 2, "axis")?,
            optional_direction(g, &a, 3, "ref_direction")?,
        )
    } else {
        let a = inst.record("AXIS2_PLACEMENT_2D")?;
        let o = point3(g, a.reference(1, "location")?, &what)?;
        let r = optional_direction(g, &a, 2, "ref_direction")?;
        (
            Point3::new(o.x, o.y, 0.0),
            None,
            r.map(|r| Point3::new(r.x, r.y, 0.0)),
        )
    };
    Frame::new(origin, axis, reference).map_err(|e| match e {
        GeomError::DegenerateFrame(reason) => StepError::DegenerateAxes {
            what,
            reason: reason.to_string(),
        },
        e => StepError::geometry(what, e),
    })
}

/// An `AXIS1_PLACEMENT`: its point and unit axis (default `z`).
fn axis1(g: &Graph, label: u64, from: &str) -> Result<(Point3, Point3)> {
    let ax = g.get(label, from)?;
    let a = ax.record("AXIS1_PLACEMENT")?;
    let o = point3(g, a.reference(1, "location")?, &ax.what())?;
    let d = match a.get(2, "axis") {
        Ok(Value::Ref(r)) => direction(g, *r, &ax.what())?,
        _ => Point3::Z,
    };
    Ok((o, d))
}

/// A `VECTOR`: its unit orientation times its magnitude (which must be positive).
fn vector(g: &Graph, label: u64, from: &str) -> Result<Point3> {
    let vi = g.get(label, from)?;
    let va = vi.record("VECTOR")?;
    let d = direction(g, va.reference(1, "orientation")?, &vi.what())?;
    let m = va.real(2, "magnitude")?;
    if m.is_nan() || m <= 0.0 {
        return Err(StepError::BadNumber {
            what: vi.what(),
            name: "magnitude",
            value: m,
        });
    }
    Ok(d * m)
}

/// The curve `#label` in space `P`; `radians` per angle unit of the file (the trim
/// parameters of circles and ellipses are angles).
pub(crate) fn curve<P: Space>(g: &Graph, label: u64, from: &str, radians: f64) -> Result<Curve<P>> {
    curve_depth(g, label, from, radians, 0)
}

fn curve_depth<P: Space>(
    g: &Graph,
    label: u64,
    from: &str,
    radians: f64,
    depth: usize,
) -> Result<Curve<P>> {
    let inst = g.get(label, from)?;
    let what = inst.what();
    if inst.is("B_SPLINE_CURVE_WITH_KNOTS")
        || inst.is("UNIFORM_CURVE")
        || inst.is("QUASI_UNIFORM_CURVE")
        || inst.is("BEZIER_CURVE")
    {
        return Ok(Curve::BSpline(bspline_curve(g, inst)?));
    }
    let a = inst.simple()?;
    let name = a.part.name.as_str();
    match name {
        "LINE" => {
            let p = point3(g, a.reference(1, "pnt")?, &what)?;
            let v = vector(g, a.reference(2, "dir")?, &what)?;
            Ok(Curve::Line {
                origin: P::from_point3(p),
                direction: P::from_point3(v),
            })
        }
        "CIRCLE" | "ELLIPSE" | "HYPERBOLA" | "PARABOLA" => {
            let f = placement(g, a.reference(1, "position")?, &what)?;
            let (r1, r2) = match name {
                "CIRCLE" => {
                    let r = a.real(2, "radius")?;
                    (r, r)
                }
                "PARABOLA" => {
                    let r = a.real(2, "focal_dist")?;
                    (r, r)
                }
                _ => (a.real(2, "semi_axis_1")?, a.real(3, "semi_axis_2")?),
            };
            let valid = if name == "PARABOLA" {
                r1 != 0.0
            } else {
                r1 > 0.0 && r2 > 0.0
            };
            if !valid {
                return Err(StepError::invalid(
                    what,
                    "non-positive radius, axis or focal distance",
                ));
            }
            let kind = match name {
                "HYPERBOLA" => ConicKind::Hyperbola,
                "PARABOLA" => ConicKind::Parabola,
                _ => ConicKind::Ellipse,
            };
            Ok(Curve::Conic(Conic {
                kind,
                center: P::from_point3(f.origin),
                u: P::from_point3(f.x * r1),
                v: P::from_point3(f.y * r2),
            }))
        }
        "POLYLINE" => {
            let refs = a.refs(1, "points")?;
            if refs.len() < 2 {
                return Err(StepError::invalid(what, "fewer than two points"));
            }
            let points = refs
                .iter()
                .map(|&r| coords(g, r, &what).map(P::from_coords))
                .collect::<Result<Vec<_>>>()?;
            let n = points.len();
            let mut knots = vec![1.0];
            knots.extend((1..=n).map(|i| i as f64));
            knots.push(n as f64);
            RationalBSpline::new(1, knots, points, None)
                .map(Curve::BSpline)
                .map_err(|e| StepError::geometry(what, e.into()))
        }
        "TRIMMED_CURVE" => {
            if depth >= MAX_TRIM_CHAIN {
                return Err(StepError::invalid(what, "trimmed curves nested too deep"));
            }
            let basis: Curve<P> =
                curve_depth(g, a.reference(1, "basis_curve")?, &what, radians, depth + 1)?;
            if !a.boolean(4, "sense_agreement")? {
                return Err(StepError::invalid(
                    what,
                    "sense_agreement .F. is not supported",
                ));
            }
            let angular = matches!(
                basis,
                Curve::Conic(Conic {
                    kind: ConicKind::Ellipse,
                    ..
                })
            );
            let trim = |i: usize, name: &'static str| -> Result<f64> {
                let list = a.list(i, name)?;
                // The parameter value if given; else the trimming point's parameter.
                for v in list {
                    if let Value::Typed(t, x) = v
                        && t == "PARAMETER_VALUE"
                        && let Some(x) = value_real(x)
                    {
                        return Ok(if angular { x * radians } else { x });
                    }
                }
                for v in list {
                    if let Value::Ref(r) = v {
                        let p = P::from_coords(coords(g, *r, &what)?);
                        return Ok(basis.closest_parameter(p, None));
                    }
                }
                Err(StepError::invalid(
                    what.clone(),
                    format!("{name} has no parameter or point"),
                ))
            };
            let t0 = trim(2, "trim_1")?;
            let mut t1 = trim(3, "trim_2")?;
            if let Some(p) = basis.window_period()
                && t1 <= t0
            {
                t1 += p * ((t0 - t1) / p).floor() + p;
            }
            if t1.is_nan() || t1 <= t0 {
                return Err(StepError::invalid(what, format!("empty trim [{t0}, {t1}]")));
            }
            Ok(Curve::Trimmed {
                basis: Box::new(basis),
                range: (t0, t1),
            })
        }
        other => Err(StepError::Unsupported {
            what,
            role: "curve",
            name: other.to_string(),
        }),
    }
}

/// The knot vector of `total` knots from the multiplicities at `mi` and the knots at `ki` of
/// record `k`; every count is checked against `total` before anything is expanded.
fn expand_knots(
    k: &Attrs<'_>,
    mi: usize,
    ki: usize,
    total: usize,
    names: (&'static str, &'static str),
) -> Result<Vec<f64>> {
    let what = k.inst.what();
    let mults = k.list(mi, names.0)?;
    let kv = k.reals(ki, names.1)?;
    if mults.len() != kv.len() {
        return Err(StepError::invalid(
            what,
            format!("{} knot multiplicities for {} knots", mults.len(), kv.len()),
        ));
    }
    let mut out = Vec::with_capacity(total.min(1 << 16));
    for (m, x) in mults.iter().zip(&kv) {
        let m = value_real(m)
            .and_then(|m| value_count(m, total))
            .ok_or_else(|| {
                StepError::invalid(
                    what.clone(),
                    format!("knot multiplicity is not a whole number <= {total}"),
                )
            })?;
        if out.len() + m > total {
            return Err(StepError::invalid(
                what,
                format!("the knot multiplicities add up to more than {total}"),
            ));
        }
        out.extend(std::iter::repeat_n(*x, m));
    }
    if out.len() != total {
        return Err(StepError::invalid(
            what,
            format!("{} knots (need {total})", out.len()),
        ));
    }
    if out.windows(2).any(|w| w[1] < w[0]) {
        return Err(StepError::invalid(what, "decreasing knots"));
    }
    Ok(out)
}

/// The knots ISO 10303-42 gives the B-spline forms that do not list them, for `n` control
/// points of degree `p`: `UNIFORM_*` from `-p` to `n`, all simple; `QUASI_UNIFORM_*` from `0`
/// to `n - p`, the ends of multiplicity `p + 1`, the integers between simple; `BEZIER_*` from
/// `0` to `(n - 1) / p`, of multiplicity `p` (`p + 1` at the ends). `None` for another form,
/// or a Bezier form whose `n - 1` is not a multiple of `p`.
fn implicit_knots(inst: &Instance, n: usize, p: usize, surface: bool) -> Option<Vec<f64>> {
    let (uniform, quasi, bezier) = if surface {
        ("UNIFORM_SURFACE", "QUASI_UNIFORM_SURFACE", "BEZIER_SURFACE")
    } else {
        ("UNIFORM_CURVE", "QUASI_UNIFORM_CURVE", "BEZIER_CURVE")
    };
    if inst.is(uniform) {
        return Some((0..n + p + 1).map(|i| i as f64 - p as f64).collect());
    }
    if inst.is(quasi) {
        let last = (n - p) as f64;
        let mut k = vec![0.0; p + 1];
        k.extend((1..n - p).map(|i| i as f64));
        k.extend(std::iter::repeat_n(last, p + 1));
        return Some(k);
    }
    if inst.is(bezier) {
        if !(n - 1).is_multiple_of(p) {
            return None;
        }
        let pieces = (n - 1) / p;
        let mut k = vec![0.0; p + 1];
        for i in 1..pieces {
            k.extend(std::iter::repeat_n(i as f64, p));
        }
        k.extend(std::iter::repeat_n(pieces as f64, p + 1));
        return Some(k);
    }
    None
}

/// A B-spline curve, simple (`B_SPLINE_CURVE_WITH_KNOTS`) or complex (`B_SPLINE_CURVE` with
/// `B_SPLINE_CURVE_WITH_KNOTS`, `UNIFORM_CURVE`, `QUASI_UNIFORM_CURVE` or `BEZIER_CURVE`, and
/// `RATIONAL_B_SPLINE_CURVE`). Multiplicities are checked against the number of control
/// points before the knot vector is expanded, so a claimed huge multiplicity allocates
/// nothing.
fn bspline_curve<P: Space>(g: &Graph, inst: &Instance) -> Result<RationalBSpline<P>> {
    let what = inst.what();
    // Attribute positions: (degree, points) and (mults, knots) records.
    let (curve, c0) = if inst.is_complex() {
        (inst.record("B_SPLINE_CURVE")?, 0)
    } else {
        (inst.record("B_SPLINE_CURVE_WITH_KNOTS")?, 1)
    };
    let degree = curve.count(c0, "degree", MAX_DEGREE)?;
    if degree == 0 {
        return Err(StepError::invalid(what, "degree 0"));
    }
    let refs = curve.refs(c0 + 1, "control_points_list")?;
    let points = refs
        .iter()
        .map(|&r| coords(g, r, &what).map(P::from_coords))
        .collect::<Result<Vec<_>>>()?;
    let n = points.len();
    if n <= degree {
        return Err(StepError::invalid(
            what,
            format!("{n} control points for degree {degree}"),
        ));
    }
    let total = n + degree + 1;
    let knots = match inst.record("B_SPLINE_CURVE_WITH_KNOTS") {
        Ok(k) => {
            let k0 = if inst.is_complex() { 0 } else { 6 };
            expand_knots(&k, k0, k0 + 1, total, ("knot_multiplicities", "knots"))?
        }
        Err(_) => implicit_knots(inst, n, degree, false).ok_or_else(|| {
            StepError::invalid(what.clone(), "no knots for this form of B-spline")
        })?,
    };
    let weights = if let Ok(r) = inst.record("RATIONAL_B_SPLINE_CURVE") {
        let w = r.reals(0, "weights_data")?;
        if w.len() != n {
            return Err(StepError::invalid(
                what,
                format!("{} weights for {n} control points", w.len()),
            ));
        }
        Some(w)
    } else {
        None
    };
    RationalBSpline::new(degree, knots, points, weights)
        .map_err(|e| StepError::geometry(what, e.into()))
}

/// The surface `#label`; `radians` per angle unit of the file.
pub(crate) fn surface(g: &Graph, label: u64, from: &str, radians: f64) -> Result<Surface> {
    surface_depth(g, label, from, radians, 0)
}

fn surface_depth(g: &Graph, label: u64, from: &str, radians: f64, depth: usize) -> Result<Surface> {
    let inst = g.get(label, from)?;
    let what = inst.what();
    if inst.is("B_SPLINE_SURFACE_WITH_KNOTS")
        || inst.is("UNIFORM_SURFACE")
        || inst.is("QUASI_UNIFORM_SURFACE")
        || inst.is("BEZIER_SURFACE")
    {
        return bspline_surface(g, inst);
    }
    let a = inst.simple()?;
    let geo = |e: GeomError| StepError::geometry(what.clone(), e);
    let frame = || placement(g, a.reference(1, "position")?, &what);
    // Angle parameters in the file's unit: `u` (and `v` where `both`) scaled to radians.
    let in_file_angles = |s: Surface, both: bool| -> Result<Surface> {
        if radians == 1.0 {
            return Ok(s);
        }
        let scale = [radians, if both { radians } else { 1.0 }];
        Reparam::new(s, false, scale, [0.0, 0.0])
            .map(Surface::Reparam)
            .map_err(geo)
    };
    let name = a.part.name.as_str();
    match name {
        "PLANE" => Ok(Surface::Plane(Plane::new(frame()?))),
        "CYLINDRICAL_SURFACE" => {
            let s = Cylinder::new(frame()?, a.real(2, "radius")?).map_err(geo)?;
            in_file_angles(Surface::Cylinder(s), false)
        }
        "CONICAL_SURFACE" => {
            let s = Cone::new(
                frame()?,
                a.real(2, "radius")?,
                a.real(3, "semi_angle")? * radians,
            )
            .map_err(geo)?;
            in_file_angles(Surface::Cone(s), false)
        }
        "SPHERICAL_SURFACE" => {
            let s = Sphere::new(frame()?, a.real(2, "radius")?).map_err(geo)?;
            in_file_angles(Surface::Sphere(s), true)
        }
        "TOROIDAL_SURFACE" | "DEGENERATE_TOROIDAL_SURFACE" => {
            let s = Torus::new(
                frame()?,
                a.real(2, "major_radius")?,
                a.real(3, "minor_radius")?,
            )
            .map_err(geo)?;
            in_file_angles(Surface::Torus(s), true)
        }
        "SURFACE_OF_REVOLUTION" => {
            let c = curve::<Point3>(g, a.reference(1, "swept_curve")?, &what, radians)?;
            let (o, d) = axis1(g, a.reference(2, "axis_position")?, &what)?;
            let s = Revolution::new(c, o, d).map_err(geo)?;
            in_file_angles(Surface::Revolution(s), false)
        }
        "SURFACE_OF_LINEAR_EXTRUSION" => {
            let c = curve::<Point3>(g, a.reference(1, "swept_curve")?, &what, radians)?;
            let v = vector(g, a.reference(2, "extrusion_axis")?, &what)?;
            Ok(Surface::Extrusion(Extrusion::new(c, v).map_err(geo)?))
        }
        "OFFSET_SURFACE" | "RECTANGULAR_TRIMMED_SURFACE" => {
            if depth >= MAX_SURFACE_CHAIN {
                return Err(StepError::invalid(what, "surfaces nested too deep"));
            }
            let base = surface_depth(
                g,
                a.reference(1, "basis_surface")?,
                &what,
                radians,
                depth + 1,
            )?;
            if name == "RECTANGULAR_TRIMMED_SURFACE" {
                return Ok(base);
            }
            let d = a.real(2, "distance")?;
            Ok(Surface::Offset(Offset::new(base, d).map_err(geo)?))
        }
        other => Err(StepError::Unsupported {
            what,
            role: "surface",
            name: other.to_string(),
        }),
    }
}

/// A B-spline surface, simple or complex, rational or not; its closedness is the file's
/// `u_closed` and `v_closed`. Every count is checked against the points the file lists before
/// a knot vector is expanded.
fn bspline_surface(g: &Graph, inst: &Instance) -> Result<Surface> {
    let what = inst.what();
    // (u_degree, v_degree, control_points_list, form, u_closed, v_closed, ...) and (u_mults,
    // v_mults, u_knots, v_knots, ...), offset by the name in a simple instance.
    let (s, s0) = if inst.is_complex() {
        (inst.record("B_SPLINE_SURFACE")?, 0)
    } else {
        (inst.record("B_SPLINE_SURFACE_WITH_KNOTS")?, 1)
    };
    let degree = [
        s.count(s0, "u_degree", MAX_DEGREE)?,
        s.count(s0 + 1, "v_degree", MAX_DEGREE)?,
    ];
    if degree.contains(&0) {
        return Err(StepError::invalid(what, "degree 0"));
    }
    let rows = s.list(s0 + 2, "control_points_list")?;
    let nv = match rows.first() {
        Some(Value::List(r)) => r.len(),
        _ => 0,
    };
    let count = [rows.len(), nv];
    if count[0] <= degree[0] || count[1] <= degree[1] {
        return Err(StepError::invalid(
            what,
            format!(
                "{}x{} control points for degrees {degree:?}",
                count[0], count[1]
            ),
        ));
    }
    // Grown as the points are read (rows of unequal length are found only on the way).
    let mut points = Vec::with_capacity(count[0].saturating_mul(count[1]).min(1 << 16));
    for r in rows {
        let Value::List(r) = r else {
            return Err(StepError::invalid(
                what,
                "control_points_list is not a list of lists",
            ));
        };
        if r.len() != nv {
            return Err(StepError::invalid(
                what,
                "rows of control points of unequal length",
            ));
        }
        for p in r {
            let Value::Ref(l) = p else {
                return Err(StepError::invalid(what, "control point is not a reference"));
            };
            points.push(point3(g, *l, &what)?);
        }
    }
    let closed = [
        s.boolean(s0 + 4, "u_closed").ok(),
        s.boolean(s0 + 5, "v_closed").ok(),
    ];
    let knots = match inst.record("B_SPLINE_SURFACE_WITH_KNOTS") {
        Ok(k) => {
            let k0 = if inst.is_complex() { 0 } else { 8 };
            [
                expand_knots(
                    &k,
                    k0,
                    k0 + 2,
                    count[0] + degree[0] + 1,
                    ("u_multiplicities", "u_knots"),
                )?,
                expand_knots(
                    &k,
                    k0 + 1,
                    k0 + 3,
                    count[1] + degree[1] + 1,
                    ("v_multiplicities", "v_knots"),
                )?,
            ]
        }
        Err(_) => {
            let implicit = |d: usize| {
                implicit_knots(inst, count[d], degree[d], true).ok_or_else(|| {
                    StepError::invalid(what.clone(), "no knots for this form of B-spline")
                })
            };
            [implicit(0)?, implicit(1)?]
        }
    };
    let weights = match inst.record("RATIONAL_B_SPLINE_SURFACE") {
        Ok(r) => {
            let mut w = Vec::with_capacity(points.len());
            for row in r.list(0, "weights_data")? {
                let Value::List(row) = row else {
                    return Err(StepError::invalid(
                        what,
                        "weights_data is not a list of lists",
                    ));
                };
                for x in row {
                    let x = value_real(x).unwrap_or(f64::NAN);
                    if !(x > 0.0 && x.is_finite()) {
                        return Err(StepError::BadNumber {
                            what,
                            name: "weight",
                            value: x,
                        });
                    }
                    w.push(x);
                }
            }
            if w.len() != points.len() {
                return Err(StepError::invalid(
                    what,
                    format!("{} weights for {} control points", w.len(), points.len()),
                ));
            }
            Some(w)
        }
        Err(_) => None,
    };
    let geo = |e: GeomError| StepError::geometry(what.clone(), e);
    let [ku, kv] = knots;
    let kv = [
        KnotVector::new(ku, degree[0], count[0]).map_err(|e| geo(e.into()))?,
        KnotVector::new(kv, degree[1], count[1]).map_err(|e| geo(e.into()))?,
    ];
    let s = BSplineSurface::new(kv, points, weights).map_err(geo)?;
    Ok(Surface::BSpline(s.with_closed(closed)))
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, PI};

    use rs_geom::surface::ParamSurface;

    use super::*;

    fn graph(data: &str) -> Graph {
        let text = format!(
            "ISO-10303-21;\nHEADER;\nFILE_NAME('a',(''));\nENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n"
        );
        Graph::parse(text.as_bytes()).unwrap()
    }

    /// Points `#1..#n` on the x axis at `0, 1, ..., n - 1`.
    fn points(n: usize) -> String {
        (1..=n)
            .map(|i| format!("#{i}=CARTESIAN_POINT('',({}.,0.));\n", i - 1))
            .collect()
    }

    fn knots(c: &Curve<Point>) -> Vec<f64> {
        let Curve::BSpline(b) = c else {
            panic!("{c:?}")
        };
        b.knots().knots().to_vec()
    }

    #[test]
    fn b_spline_forms_without_knots_get_iso_s_knots() {
        let form = |name: &str, n: usize, p: usize| {
            let refs: Vec<String> = (1..=n).map(|i| format!("#{i}")).collect();
            let g = graph(&format!(
                "{}#50=(BOUNDED_CURVE()B_SPLINE_CURVE({p},({}),.UNSPECIFIED.,.F.,.F.){name}()CURVE()GEOMETRIC_REPRESENTATION_ITEM()REPRESENTATION_ITEM(''));",
                points(n),
                refs.join(",")
            ));
            curve::<Point>(&g, 50, "test", 1.0)
        };
        assert_eq!(
            knots(&form("UNIFORM_CURVE", 4, 2).unwrap()),
            [-2.0, -1.0, 0.0, 1.0, 2.0, 3.0, 4.0]
        );
        assert_eq!(
            knots(&form("QUASI_UNIFORM_CURVE", 5, 2).unwrap()),
            [0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0]
        );
        let bezier = form("BEZIER_CURVE", 7, 3).unwrap();
        assert_eq!(
            knots(&bezier),
            [0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 2.0, 2.0, 2.0]
        );
        // A piecewise Bezier curve passes through every third point.
        assert_eq!(bezier.point(1.0), Point::new(3.0, 0.0));
        let e = form("BEZIER_CURVE", 6, 3).unwrap_err().to_string();
        assert!(e.contains("#50") && e.contains("no knots"), "{e}");
    }

    #[test]
    fn conics_and_trims_in_their_parameters() {
        let g = graph(
            "#1=CARTESIAN_POINT('',(1.,2.,3.));
#2=DIRECTION('',(0.,0.,1.));
#3=DIRECTION('',(1.,0.,0.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
#5=HYPERBOLA('',#4,2.,1.);
#6=PARABOLA('',#4,0.5);
#7=CIRCLE('',#4,2.);
#8=CARTESIAN_POINT('',(1.,4.,3.));
#9=TRIMMED_CURVE('',#7,(PARAMETER_VALUE(0.)),(#8),.T.,.PARAMETER.);
#10=TRIMMED_CURVE('',#7,(PARAMETER_VALUE(90.)),(PARAMETER_VALUE(0.)),.T.,.PARAMETER.);",
        );
        let h = curve::<Point3>(&g, 5, "test", 1.0).unwrap();
        // (x - 1)^2 / 4 - (y - 2)^2 = 1.
        let p = h.point(0.7);
        assert!(((p.x - 1.0).powi(2) / 4.0 - (p.y - 2.0).powi(2) - 1.0).abs() < 1e-14);
        let q = curve::<Point3>(&g, 6, "test", 1.0).unwrap().point(3.0);
        // Vertex (1, 2, 3), focal distance 1/2: (y - 2)^2 = 2 (x - 1).
        assert!(((q.y - 2.0).powi(2) - 2.0 * (q.x - 1.0)).abs() < 1e-14);
        // A trim by a point: its angle on the circle.
        let t = curve::<Point3>(&g, 9, "test", 1.0).unwrap();
        assert_eq!(t.range(), Some((0.0, FRAC_PI_2)));
        // Angles in degrees; a trim past the circle's end wraps by a period.
        let t = curve::<Point3>(&g, 10, "test", PI / 180.0).unwrap();
        let (a, b) = t.range().unwrap();
        assert!((a - FRAC_PI_2).abs() < 1e-15 && (b - 2.0 * PI).abs() < 1e-15);
    }

    fn surface_graph() -> Graph {
        graph(
            "#1=CARTESIAN_POINT('',(0.,0.,0.));
#2=DIRECTION('',(0.,0.,1.));
#3=DIRECTION('',(1.,0.,0.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
#5=CYLINDRICAL_SURFACE('',#4,2.);
#6=RECTANGULAR_TRIMMED_SURFACE('',#5,0.,1.,0.,1.,.T.,.T.);
#7=OFFSET_SURFACE('',#5,0.5,.F.);
#8=LINE('',#1,#9);
#9=VECTOR('',#3,1.);
#10=VECTOR('',#2,3.);
#11=SURFACE_OF_LINEAR_EXTRUSION('',#8,#10);
#12=AXIS2_PLACEMENT_3D('',#1,#2,#2);",
        )
    }

    #[test]
    fn surfaces_built_on_surfaces_and_swept_curves() {
        let g = surface_graph();
        let cyl = surface(&g, 5, "test", 1.0).unwrap();
        assert!(matches!(cyl, Surface::Cylinder(_)));
        assert_eq!(surface(&g, 6, "test", 1.0).unwrap(), cyl);
        let off = surface(&g, 7, "test", 1.0).unwrap();
        assert!(off.point([0.0, 1.0]).distance(Point3::new(2.5, 0.0, 1.0)) < 1e-15);
        let ext = surface(&g, 11, "test", 1.0).unwrap();
        // The line's point at u plus v times the vector (0, 0, 3).
        assert_eq!(ext.point([2.0, 0.5]), Point3::new(2.0, 0.0, 1.5));
    }

    #[test]
    fn a_file_in_degrees_keeps_its_angle_parameters() {
        let g = surface_graph();
        let deg = PI / 180.0;
        let rad = surface(&g, 5, "test", 1.0).unwrap();
        let s = surface(&g, 5, "test", deg).unwrap();
        assert!(matches!(s, Surface::Reparam(_)));
        assert!(s.point([90.0, 1.5]).distance(rad.point([FRAC_PI_2, 1.5])) < 1e-15);
        assert_eq!(s.periods()[0], Some(360.0));
    }

    #[test]
    fn degenerate_placements_and_unknown_types_are_named() {
        let g = surface_graph();
        let e = placement(&g, 12, "test").unwrap_err();
        assert_eq!(
            e.to_string(),
            "#12 AXIS2_PLACEMENT_3D: degenerate axes: the reference direction is along the axis"
        );
        let e = surface(&g, 8, "test", 1.0).unwrap_err();
        assert_eq!(e.to_string(), "#8 LINE: surface type LINE is not supported");
        let e = curve::<Point>(&g, 5, "test", 1.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "#5 CYLINDRICAL_SURFACE: curve type CYLINDRICAL_SURFACE is not supported"
        );
    }
}
