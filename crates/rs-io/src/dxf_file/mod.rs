//! DXF drawings: `SPLINE` (degree, knots, weights, control points), `LWPOLYLINE` and 2-D
//! `POLYLINE` with bulges (exact circular arcs), `LINE`, `ARC`, `CIRCLE` and `ELLIPSE` in
//! model space, chained end to end into closed loops.

use rs_spline::prelude::*;
use std::f64::consts::TAU;
use std::path::Path;

use dxf::entities::{Entity, EntityType};
use rs_spline::{BoundingBox, Domain, NurbsCurve, Point, SplineError};

use crate::IoError;
use crate::builder::with_end_points;
use rs_spline::Affine;

mod load;

/// Heights that differ by less than this (relative to `1 + |z|`) are one plane.
const SAME_HEIGHT: f64 = 1e-12;
/// An extrusion direction whose x and y components are below this is the z axis.
const AXIS_NORMAL: f64 = 1e-12;
/// A sweep within this of zero or of a full turn (in the entity's angle unit: degrees for
/// ARC, radians for ELLIPSE) is a full turn (the file's rounding of equal angles).
const FULL_TURN_SLACK: f64 = 1e-10;

/// How DXF entities are joined into loops.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct DxfOptions {
    /// Entity ends closer than this fraction of the drawing's bounding-box diagonal are
    /// joined (also the domain's closure tolerance).
    pub relative_closure_tolerance: f64,
    /// Keep chains that do not close (for generalized winding numbers) instead of failing.
    pub allow_open: bool,
}

impl DxfOptions {
    /// Ends within `1e-9` of the diagonal are joined; open chains are an error.
    pub const DEFAULT: DxfOptions = DxfOptions {
        relative_closure_tolerance: 1e-9,
        allow_open: false,
    };

    /// With another relative closure tolerance.
    pub const fn with_relative_closure_tolerance(mut self, relative_tolerance: f64) -> Self {
        self.relative_closure_tolerance = relative_tolerance;
        self
    }

    /// Keeping open chains (`true`) or refusing them.
    pub const fn with_allow_open(mut self, allow_open: bool) -> Self {
        self.allow_open = allow_open;
        self
    }
}

impl Default for DxfOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The domain bounded by the curves of a DXF file (see [`domain_from_drawing`]).
///
/// # Errors
/// [`IoError::Read`] / [`IoError::Dxf`] if the file cannot be read or parsed, then as
/// [`domain_from_drawing`].
pub fn domain_from_dxf_file(
    path: impl AsRef<Path>,
    options: &DxfOptions,
) -> Result<Domain, IoError> {
    let path = path.as_ref();
    let data = rs_spline::limits::read_file(path).map_err(|source| IoError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let drawing = load::load_drawing(&data)?;
    Ok(domain_from_drawing(&drawing, options)?.with_name(path.display().to_string()))
}

/// The domain bounded by the curves of DXF text.
///
/// # Errors
/// As [`domain_from_dxf_file`].
pub fn domain_from_dxf_str(text: &str, options: &DxfOptions) -> Result<Domain, IoError> {
    let drawing = load::load_drawing(text.as_bytes())?;
    domain_from_drawing(&drawing, options)
}

/// The domain bounded by the model-space curves of a drawing. Each entity becomes exact
/// NURBS (arcs and bulges as rational quadratics, splines as given); entities are chained by
/// matching end points (reversing where needed) into loops. Other entity types (text,
/// hatches, block inserts, ...) are ignored.
///
/// # Errors
/// [`IoError::DxfEntity`] naming the entity (type and handle) for an invalid spline, a curve
/// outside the XY plane, or (unless [`DxfOptions::allow_open`]) an end that meets no other
/// entity; [`IoError::Empty`] if the drawing has no curves.
pub fn domain_from_drawing(
    drawing: &dxf::Drawing,
    options: &DxfOptions,
) -> Result<Domain, IoError> {
    if !(options.relative_closure_tolerance.is_finite()
        && options.relative_closure_tolerance >= 0.0)
    {
        return Err(IoError::Domain(rs_spline::DomainError::InvalidTolerance(
            options.relative_closure_tolerance,
        )));
    }
    let mut chains = Vec::new();
    for e in drawing.entities() {
        if e.common.is_in_paper_space {
            continue;
        }
        if let Some(chain) = entity_curves(e)? {
            chains.push(chain);
        }
    }
    let bbox = chains
        .iter()
        .flat_map(|c| c.curves.iter().map(NurbsCurve::bounding_box))
        .reduce(BoundingBox::union)
        .ok_or_else(|| IoError::Empty("DXF drawing".to_string()))?;
    let tol = options.relative_closure_tolerance * bbox.diagonal();
    let curves = join_chains(chains, tol, options.allow_open)?;
    Ok(Domain::with_relative_closure_tolerance(
        curves,
        options.relative_closure_tolerance,
    )?)
}

/// The curves of one entity, in order, with where they came from.
struct Chain {
    kind: &'static str,
    handle: String,
    curves: Vec<NurbsCurve>,
}

impl Chain {
    fn start(&self) -> Point {
        self.curves[0].start_point()
    }

    fn end(&self) -> Point {
        self.curves[self.curves.len() - 1].end_point()
    }

    fn reverse(&mut self) {
        self.curves.reverse();
        for c in &mut self.curves {
            *c = c.reversed();
        }
    }
}

fn entity_curves(e: &Entity) -> Result<Option<Chain>, IoError> {
    let handle = e.common.handle.as_string();
    let (kind, curves): (&'static str, Result<Vec<NurbsCurve>, String>) = match &e.specific {
        EntityType::Line(l) => ("LINE", line(l)),
        EntityType::Arc(a) => ("ARC", arc(a)),
        EntityType::Circle(c) => ("CIRCLE", circle(c)),
        EntityType::Ellipse(el) => ("ELLIPSE", ellipse(el)),
        EntityType::LwPolyline(p) => {
            let vertices: Vec<(Point, f64)> = p
                .vertices
                .iter()
                .map(|v| (Point::new(v.x, v.y), v.bulge))
                .collect();
            (
                "LWPOLYLINE",
                bulge_polyline(&vertices, p.is_closed(), &p.extrusion_direction),
            )
        }
        // Polygon and polyface meshes are surfaces, not boundaries.
        EntityType::Polyline(p) if p.is_3d_polygon_mesh() || p.is_polyface_mesh() => {
            return Ok(None);
        }
        EntityType::Polyline(p) => {
            let vertices: Vec<(Point, f64)> = p
                .vertices()
                .map(|v| (Point::new(v.location.x, v.location.y), v.bulge))
                .collect();
            let z0 = p.vertices().next().map_or(0.0, |v| v.location.z);
            let planar = p
                .vertices()
                .all(|v| (v.location.z - z0).abs() <= SAME_HEIGHT * (1.0 + z0.abs()));
            let curves = if p.is_3d_polyline() && !planar {
                Err("3-D polyline with vertices at different heights: not in the XY plane".into())
            } else {
                bulge_polyline(&vertices, p.is_closed(), &p.normal)
            };
            ("POLYLINE", curves)
        }
        EntityType::Spline(s) => ("SPLINE", spline(s)),
        _ => return Ok(None),
    };
    let curves = curves.map_err(|message| IoError::DxfEntity {
        kind,
        handle: handle.clone(),
        message,
    })?;
    Ok((!curves.is_empty()).then_some(Chain {
        kind,
        handle,
        curves,
    }))
}

fn spline_err(e: SplineError) -> String {
    e.to_string()
}

/// The map from an entity's object coordinate system to the drawing's XY plane: identity
/// for extrusion `+z`, the mirror `x -> -x` for `-z` (the arbitrary-axis rule).
fn ocs(normal: &dxf::Vector) -> Result<Affine, String> {
    let len = (normal.x * normal.x + normal.y * normal.y + normal.z * normal.z).sqrt();
    if len > 0.0 && (normal.x / len).abs() < AXIS_NORMAL && (normal.y / len).abs() < AXIS_NORMAL {
        Ok(if normal.z > 0.0 {
            Affine::IDENTITY
        } else {
            Affine::scale(-1.0, 1.0)
        })
    } else {
        Err(format!(
            "extrusion direction ({}, {}, {}) is not the z axis: the curve is not in the XY plane",
            normal.x, normal.y, normal.z
        ))
    }
}

fn line(l: &dxf::entities::Line) -> Result<Vec<NurbsCurve>, String> {
    let (a, b) = (Point::new(l.p1.x, l.p1.y), Point::new(l.p2.x, l.p2.y));
    if a == b {
        return Ok(Vec::new());
    }
    Ok(vec![rs_spline::segment(a, b).map_err(spline_err)?])
}

fn arc(a: &dxf::entities::Arc) -> Result<Vec<NurbsCurve>, String> {
    let map = ocs(&a.normal)?;
    let mut sweep = (a.end_angle - a.start_angle).rem_euclid(360.0);
    if sweep < FULL_TURN_SLACK || 360.0 - sweep < FULL_TURN_SLACK {
        sweep = 360.0;
    }
    let c = rs_spline::circular_arc(
        Point::new(a.center.x, a.center.y),
        a.radius,
        a.start_angle.to_radians(),
        sweep.to_radians(),
    )
    .map_err(spline_err)?;
    Ok(vec![map.apply_to_curve(&c).map_err(spline_err)?])
}

fn circle(c: &dxf::entities::Circle) -> Result<Vec<NurbsCurve>, String> {
    let map = ocs(&c.normal)?;
    let curve =
        rs_spline::circle(Point::new(c.center.x, c.center.y), c.radius).map_err(spline_err)?;
    Ok(vec![map.apply_to_curve(&curve).map_err(spline_err)?])
}

/// An ELLIPSE: centre and major axis in world coordinates, the minor axis `ratio * (N x major)`,
/// parameters in radians counter-clockwise about the normal `N`.
fn ellipse(e: &dxf::entities::Ellipse) -> Result<Vec<NurbsCurve>, String> {
    let flip = ocs(&e.normal)?.m[0] < 0.0;
    let major = Point::new(e.major_axis.x, e.major_axis.y);
    let rx = major.length();
    let ry = rx * e.minor_axis_ratio;
    let tilt = major.y.atan2(major.x);
    // Equal parameters, or parameters a full turn apart up to the file's rounding, mean
    // the whole ellipse.
    let mut sweep = (e.end_parameter - e.start_parameter).rem_euclid(TAU);
    if sweep < FULL_TURN_SLACK || TAU - sweep < FULL_TURN_SLACK {
        sweep = TAU;
    }
    let (start, sweep) = if flip {
        (-e.start_parameter, -sweep)
    } else {
        (e.start_parameter, sweep)
    };
    let c = rs_spline::elliptic_arc(
        Point::new(e.center.x, e.center.y),
        rx,
        ry,
        tilt,
        start,
        sweep,
    )
    .map_err(spline_err)?;
    Ok(vec![c])
}

/// A polyline whose vertex `i` carries the bulge of the edge to vertex `i + 1`:
/// `bulge = tan(theta / 4)` with `theta` the included angle, positive counter-clockwise.
fn bulge_polyline(
    vertices: &[(Point, f64)],
    closed: bool,
    normal: &dxf::Vector,
) -> Result<Vec<NurbsCurve>, String> {
    let map = ocs(normal)?;
    let n = vertices.len();
    let edges = if closed { n } else { n.saturating_sub(1) };
    let mut curves = Vec::with_capacity(edges);
    for i in 0..edges {
        let (a, bulge) = vertices[i];
        let (b, _) = vertices[(i + 1) % n];
        if a == b {
            continue;
        }
        if !bulge.is_finite() {
            return Err(format!("vertex {i}: bulge {bulge} is not finite"));
        }
        let c = if bulge == 0.0 {
            rs_spline::segment(a, b).map_err(spline_err)?
        } else {
            bulge_arc(a, b, bulge).map_err(spline_err)?
        };
        curves.push(map.apply_to_curve(&c).map_err(spline_err)?);
    }
    Ok(curves)
}

/// The circular arc from `a` to `b` with included angle `theta = 4 atan(bulge)`: the centre
/// is `m + n (d / 2) / tan(theta / 2)` with `m` the chord midpoint, `d` its length and `n`
/// the unit normal to the left of the chord.
fn bulge_arc(a: Point, b: Point, bulge: f64) -> Result<NurbsCurve, SplineError> {
    let theta = 4.0 * bulge.atan();
    let chord = b - a;
    let d = chord.length();
    let m = (a + b) * 0.5;
    let n = chord.perp() / d;
    let centre = m + n * (0.5 * d / (0.5 * theta).tan());
    let r = a.distance(centre);
    let start = (a.y - centre.y).atan2(a.x - centre.x);
    let arc = rs_spline::circular_arc(centre, r, start, theta)?;
    with_end_points(&arc, a, b)
}

fn spline(s: &dxf::entities::Spline) -> Result<Vec<NurbsCurve>, String> {
    // Control points are in world coordinates: the curve is planar in XY when they are all
    // at one height, whatever the stored normal.
    if s.control_points.is_empty() {
        return Err(if s.fit_points.is_empty() {
            "no control points".to_string()
        } else {
            format!(
                "defined by {} fit points only: re-save the spline with control points",
                s.fit_points.len()
            )
        });
    }
    let z0 = s.control_points[0].z;
    if s.control_points
        .iter()
        .any(|p| (p.z - z0).abs() > SAME_HEIGHT * (1.0 + z0.abs()))
    {
        return Err("control points at different heights: the curve is not in the XY plane".into());
    }
    let degree = usize::try_from(s.degree_of_curve)
        .map_err(|_| format!("degree {} is negative", s.degree_of_curve))?;
    let points: Vec<Point> = s
        .control_points
        .iter()
        .map(|p| Point::new(p.x, p.y))
        .collect();
    let weights = if s.weight_values.is_empty() {
        None
    } else if s.weight_values.len() == points.len() {
        Some(s.weight_values.clone())
    } else {
        return Err(format!(
            "{} weights for {} control points",
            s.weight_values.len(),
            points.len()
        ));
    };
    let c = NurbsCurve::new(degree, s.knot_values.clone(), points, weights).map_err(spline_err)?;
    Ok(vec![c.clamped()])
}

/// Joins chains into loops by end-point matching within `tol`; chains that close on
/// themselves are loops already.
fn join_chains(chains: Vec<Chain>, tol: f64, allow_open: bool) -> Result<Vec<NurbsCurve>, IoError> {
    let mut pending: Vec<Option<Chain>> = chains.into_iter().map(Some).collect();
    let mut curves = Vec::new();
    for i in 0..pending.len() {
        let Some(mut current) = pending[i].take() else {
            continue;
        };
        let loop_start = current.start();
        let mut members = vec![(current.kind, current.handle.clone())];
        while current.end().distance(loop_start) > tol {
            let end = current.end();
            let next = pending.iter().enumerate().find_map(|(j, c)| {
                let c = c.as_ref()?;
                if c.start().distance(end) <= tol {
                    Some((j, false))
                } else if c.end().distance(end) <= tol {
                    Some((j, true))
                } else {
                    None
                }
            });
            let Some((j, reverse)) = next else {
                if allow_open {
                    break;
                }
                let (kind, handle) = members.pop().unwrap_or(("?", String::new()));
                return Err(IoError::DxfEntity {
                    kind,
                    handle,
                    message: format!(
                        "its end ({}, {}) meets no other entity within {tol:e}: the boundary is open",
                        end.x, end.y
                    ),
                });
            };
            let Some(mut c) = pending[j].take() else {
                break;
            };
            if reverse {
                c.reverse();
            }
            members.push((c.kind, c.handle.clone()));
            current.curves.append(&mut c.curves);
        }
        curves.append(&mut current.curves);
    }
    Ok(curves)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn bulge_one_is_a_half_circle_to_the_right_of_travel_when_negative() {
        let (a, b) = (Point::new(0.0, 0.0), Point::new(2.0, 0.0));
        let ccw = bulge_arc(a, b, 1.0).unwrap();
        let cw = bulge_arc(a, b, -1.0).unwrap();
        assert_eq!((ccw.start_point(), ccw.end_point()), (a, b));
        for i in 0..=8 {
            let t = i as f64 / 8.0;
            assert!((ccw.point_at(t).distance(Point::new(1.0, 0.0)) - 1.0).abs() < 1e-14);
            assert!((cw.point_at(t).distance(Point::new(1.0, 0.0)) - 1.0).abs() < 1e-14);
        }
        // Counter-clockwise from (0,0) to (2,0) about (1,0) goes below the chord.
        assert!(ccw.point_at(0.5).y < -0.99);
        assert!(cw.point_at(0.5).y > 0.99);
        // A quarter bulge tan(pi/16): included angle pi/4.
        let q = bulge_arc(a, b, (PI / 16.0).tan()).unwrap();
        let r = 1.0 / (PI / 8.0).sin();
        let centre = Point::new(1.0, (PI / 8.0).cos() * r);
        assert!((q.point_at(0.3).distance(centre) - r).abs() < 1e-13);
    }
}
