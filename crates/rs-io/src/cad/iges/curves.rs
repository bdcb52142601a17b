//! Curve entities as exact NURBS pieces, in a surface's parameter space or mapped from model
//! space into a plane's `(u, v)`.
//!
//! A curve entity is read in its definition space (3-D control points, weights, knots), its
//! 124 transformation matrices are applied (each entity's own, then those of the composites
//! holding it), and the result goes to its [`Target`]: parameter space keeps `(x, y)` (the
//! 2-D part of each 124; z is not a parameter), a plane maps the model point to `(u, v)` after
//! checking it lies on the plane. All maps are affine, so the curves stay exact.

use rs_spline::prelude::*;
use rs_spline::{NurbsCurve, Point, circular_arc};

use super::conics::{Conic, ConicKind, conic_arc};
use super::directory::DirEntry;
use super::maps::{Map3, PlaneMap};
use super::{Iges, MAX_DEPTH, type_name};

/// Where curves go.
#[derive(Clone, Debug)]
pub(super) enum Target {
    /// A surface's parameter space: the curve's `(x, y)` are `(u, v)`.
    Param,
    /// A plane's parameter space from model-space curves.
    Plane(PlaneMap),
    /// Model space, two of the coordinates: `(x, y)`, or `(z, 0)` when `z` is set (to find
    /// the ends of model-space curves in 3-D).
    Model {
        /// `(z, 0)` instead of `(x, y)`.
        z: bool,
    },
}

/// One curve of a loop and the entity it came from.
#[derive(Clone, Debug)]
pub(super) struct Piece {
    /// The directory entry of the curve entity.
    pub(super) de: usize,
    /// The curve in `(u, v)`.
    pub(super) curve: NurbsCurve,
}

/// A curve in its entity's definition space, before its transformations.
struct Raw {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<[f64; 3]>,
    weights: Option<Vec<f64>>,
    /// The parameter interval to keep (126's `V0`, `V1`).
    trim: Option<(f64, f64)>,
}

impl Raw {
    /// A 2-D curve lifted to height `z`.
    fn lift(c: &NurbsCurve, z: f64) -> Raw {
        Raw {
            degree: c.degree(),
            knots: c.knots().knots().to_vec(),
            points: c.control_points().iter().map(|p| [p.x, p.y, z]).collect(),
            weights: Some(c.weights().to_vec()),
            trim: None,
        }
    }

    /// A degree-1 polyline through `points` (vertex `i` at parameter `i`).
    fn polyline(points: Vec<[f64; 3]>) -> Raw {
        let n = points.len();
        let mut knots = Vec::with_capacity(n + 2);
        knots.push(0.0);
        knots.extend((0..n).map(|i| i as f64));
        knots.push(n.saturating_sub(1) as f64);
        Raw {
            degree: 1,
            knots,
            points,
            weights: None,
            trim: None,
        }
    }
}

impl Iges<'_> {
    /// The pieces of curve `de` sent to `target`, appended to `out`. `from` says who points
    /// to it, for messages.
    pub(super) fn curve_pieces(
        &self,
        de: usize,
        from: &str,
        target: &Target,
        out: &mut Vec<Piece>,
    ) -> Result<(), String> {
        self.curve_in(de, from, target, Map3::IDENTITY, &mut Vec::new(), out)
    }

    /// `outer` maps the curve's transformed definition space to the target's input space;
    /// `stack` holds the composites being read (cycle detection).
    fn curve_in(
        &self,
        de: usize,
        from: &str,
        target: &Target,
        outer: Map3,
        stack: &mut Vec<usize>,
        out: &mut Vec<Piece>,
    ) -> Result<(), String> {
        let e = self.entry(de, from)?;
        let map = self
            .transform(e, !matches!(target, Target::Param))?
            .then(outer);
        match e.kind {
            102 => {
                let who = self.who(e);
                if stack.contains(&e.de) {
                    return Err(format!(
                        "{who}: composite curves contain each other (a cycle through DE {})",
                        e.de
                    ));
                }
                if stack.len() >= MAX_DEPTH {
                    return Err(format!(
                        "{who}: composite curves nested deeper than {MAX_DEPTH}"
                    ));
                }
                let mut p = self.params(e)?;
                let n = p.count("N")?;
                let members = p.pointers("N", n, "constituent")?;
                stack.push(e.de);
                for (i, m) in members.into_iter().enumerate() {
                    let from = format!("{who}: constituent {}", i + 1);
                    self.curve_in(m, &from, target, map, stack, out)?;
                }
                stack.pop();
                Ok(())
            }
            100 | 104 | 106 | 110 | 126 => {
                let raw = self.leaf(e)?;
                let curve =
                    finish(raw, &map, target).map_err(|m| format!("{}: {m}", self.who(e)))?;
                out.push(Piece { de: e.de, curve });
                Ok(())
            }
            k => Err(format!(
                "{from}: DE {} is a {k} {}, not a curve this reader knows (100, 102, 104, 106, \
                 110, 126)",
                e.de,
                type_name(k)
            )),
        }
    }

    /// The map of `e`'s 124 chain (its matrix, then that matrix's own, ...), in 3-D for
    /// model space (`model`) and its 2-D part for parameter space.
    pub(super) fn transform(&self, e: &DirEntry, model: bool) -> Result<Map3, String> {
        let mut acc = Map3::IDENTITY;
        let mut ptr = e.transform;
        let mut seen: Vec<usize> = Vec::new();
        while ptr != 0 {
            let who = self.who(e);
            let Ok(de) = usize::try_from(ptr) else {
                return Err(format!(
                    "{who}: negative transformation matrix pointer {ptr}"
                ));
            };
            if seen.contains(&de) {
                return Err(format!(
                    "{who}: its transformation matrices form a cycle (DE {de} again)"
                ));
            }
            if seen.len() >= MAX_DEPTH {
                return Err(format!(
                    "{who}: a chain of more than {MAX_DEPTH} transformation matrices"
                ));
            }
            seen.push(de);
            let t = self.entry(de, &format!("{who}: transformation matrix"))?;
            if t.kind != 124 {
                return Err(format!(
                    "{who}: its transformation matrix pointer is DE {de}, a {} {}",
                    t.kind,
                    type_name(t.kind)
                ));
            }
            let mut p = self.params(t)?;
            let mut v = [0.0; 12];
            for (i, x) in v.iter_mut().enumerate() {
                *x = p.real(
                    [
                        "R11", "R12", "R13", "T1", "R21", "R22", "R23", "T2", "R31", "R32", "R33",
                        "T3",
                    ][i],
                )?;
            }
            let m = if model {
                Map3::from_124(v)
            } else {
                Map3::from_124_2d(v)
            };
            acc = acc.then(m);
            ptr = t.transform;
        }
        Ok(acc)
    }

    /// Reads a curve entity other than a composite, in its definition space.
    fn leaf(&self, e: &DirEntry) -> Result<Raw, String> {
        let who = self.who(e);
        let mut p = self.params(e)?;
        match e.kind {
            110 => {
                if e.form != 0 {
                    let what = if e.form == 1 {
                        "a ray"
                    } else {
                        "an unbounded line"
                    };
                    return Err(format!("{who}: form {} is {what}, not a segment", e.form));
                }
                let mut v = [0.0; 6];
                for (x, name) in v.iter_mut().zip(["X1", "Y1", "Z1", "X2", "Y2", "Z2"]) {
                    *x = p.real(name)?;
                }
                Ok(Raw::polyline(vec![[v[0], v[1], v[2]], [v[3], v[4], v[5]]]))
            }
            100 => {
                let mut v = [0.0; 7];
                for (x, name) in v.iter_mut().zip(["ZT", "X1", "Y1", "X2", "Y2", "X3", "Y3"]) {
                    *x = p.real(name)?;
                }
                let centre = Point::new(v[1], v[2]);
                let (start, end) = (Point::new(v[3], v[4]), Point::new(v[5], v[6]));
                let r = start.distance(centre);
                if r <= 0.0 || !r.is_finite() {
                    return Err(format!("{who}: the start point is the centre (radius 0)"));
                }
                let a0 = (start.y - centre.y).atan2(start.x - centre.x);
                let a1 = (end.y - centre.y).atan2(end.x - centre.x);
                // Counter-clockwise from start to end; equal points are the full circle.
                let mut sweep = if start == end {
                    std::f64::consts::TAU
                } else {
                    (a1 - a0).rem_euclid(std::f64::consts::TAU)
                };
                if sweep <= 0.0 {
                    sweep = std::f64::consts::TAU;
                }
                let arc = circular_arc(centre, r, a0, sweep).map_err(|m| format!("{who}: {m}"))?;
                Ok(Raw::lift(&arc, v[0]))
            }
            104 => {
                let mut v = [0.0; 11];
                for (x, name) in v
                    .iter_mut()
                    .zip(["A", "B", "C", "D", "E", "F", "ZT", "X1", "Y1", "X2", "Y2"])
                {
                    *x = p.real(name)?;
                }
                let kind = match e.form {
                    1 => ConicKind::Ellipse,
                    2 => ConicKind::Hyperbola,
                    3 => ConicKind::Parabola,
                    f => return Err(format!("{who}: form {f} (expected 1, 2 or 3)")),
                };
                let conic = Conic {
                    c: [v[0], v[1], v[2], v[3], v[4], v[5]],
                };
                let arc = conic_arc(
                    &conic,
                    kind,
                    Point::new(v[7], v[8]),
                    Point::new(v[9], v[10]),
                )
                .map_err(|m| format!("{who}: {m}"))?;
                Ok(Raw::lift(&arc, v[6]))
            }
            106 => self.copious(e, &mut p),
            126 => bspline(&who, &mut p),
            _ => Err(format!("{who}: not a curve")),
        }
    }

    /// 106 copious data, forms 11 (2-D path), 12 (3-D path), 63 (closed planar curve).
    fn copious(&self, e: &DirEntry, p: &mut super::params::Params<'_>) -> Result<Raw, String> {
        let who = self.who(e);
        if !matches!(e.form, 11 | 12 | 63) {
            return Err(format!(
                "{who}: form {} is not a path (forms 11, 12, 63 are read)",
                e.form
            ));
        }
        let ip = p.int("IP")?;
        let n = p.count("N")?;
        let (each, zt) = match ip {
            1 => (2, Some(p.real("ZT")?)),
            2 => (3, None),
            3 => (6, None),
            _ => {
                return Err(p.err(
                    "IP",
                    format!("interpretation flag {ip} (expected 1, 2 or 3)"),
                ));
            }
        };
        if n < 2 {
            return Err(p.err("N", format!("{n} points (a path needs 2)")));
        }
        p.check_count("N", n, each)?;
        let mut points = Vec::with_capacity(n + 1);
        for _ in 0..n {
            let x = p.real("X")?;
            let y = p.real("Y")?;
            let z = match zt {
                Some(z) => z,
                None => p.real("Z")?,
            };
            for _ in 3..each {
                p.skip("normal")?;
            }
            points.push([x, y, z]);
        }
        if e.form == 63 && points.first() != points.last() {
            points.push(points[0]);
        }
        Ok(Raw::polyline(points))
    }
}

/// 126 rational B-spline curve: `K, M, PROP1..4`, knots, weights, control points,
/// `V0, V1`.
fn bspline(who: &str, p: &mut super::params::Params<'_>) -> Result<Raw, String> {
    let k = p.count("K")?;
    let m = p.count("M")?;
    if m == 0 || m > rs_spline::limits::MAX_DEGREE {
        return Err(p.err(
            "M",
            format!(
                "degree {m} (1 to {} accepted)",
                rs_spline::limits::MAX_DEGREE
            ),
        ));
    }
    // K + 1 control points with 4 fields each (weight, x, y, z), K + M + 2 knots.
    p.check_count("K", k, 5)?;
    let _planar = p.int("PROP1")?;
    let _closed = p.int("PROP2")?;
    let polynomial = p.int("PROP3")? == 1;
    let _periodic = p.int("PROP4")?; // the knots and points define the curve either way
    let n = k + 1;
    let mut knots = Vec::with_capacity(n + m + 1);
    for _ in 0..n + m + 1 {
        knots.push(p.real("knot")?);
    }
    let mut weights = Vec::with_capacity(n);
    for _ in 0..n {
        weights.push(p.real("weight")?);
    }
    let mut points = Vec::with_capacity(n);
    for _ in 0..n {
        points.push([p.real("X")?, p.real("Y")?, p.real("Z")?]);
    }
    let v0 = p.real("V0")?;
    let v1 = p.real("V1")?;
    let weights = if polynomial {
        if weights.iter().any(|&w| w != weights[0]) {
            return Err(format!(
                "{who}: PROP3 says polynomial but the weights are not all equal"
            ));
        }
        None
    } else {
        Some(weights)
    };
    // V0, V1 within the knot domain [t_M, t_(K+1)], rounding tolerated.
    let (a, b) = (knots[m], knots[n]);
    let slack = 1e-9 * (b - a).abs().max(a.abs()).max(b.abs());
    if !(v0 < v1 && v0 >= a - slack && v1 <= b + slack) {
        return Err(format!(
            "{who}: parameter range [{v0}, {v1}] is not inside the knot domain [{a}, {b}]"
        ));
    }
    let trim = (v0 > a || v1 < b).then_some((v0.max(a), v1.min(b)));
    Ok(Raw {
        degree: m,
        knots,
        points,
        weights,
        trim,
    })
}

/// Maps `raw` by `map` into `target` and builds the curve (trimmed if asked).
fn finish(raw: Raw, map: &Map3, target: &Target) -> Result<NurbsCurve, String> {
    let mut points = Vec::with_capacity(raw.points.len());
    for q in raw.points {
        let q = map.apply(q);
        let uv = match target {
            Target::Param | Target::Model { z: false } => Point::new(q[0], q[1]),
            Target::Model { z: true } => Point::new(q[2], 0.0),
            Target::Plane(plane) => {
                let d = plane.distance(q);
                let size = q.iter().fold(1.0f64, |m, x| m.max(x.abs()));
                if d.abs() > plane.tol.max(1e-9 * size) || d.is_nan() {
                    return Err(format!(
                        "a control point of the model-space curve is {d:e} off the surface's \
                         plane (tolerance {:e})",
                        plane.tol
                    ));
                }
                let (u, v) = plane.uv(q);
                Point::new(u, v)
            }
        };
        points.push(uv);
    }
    let curve =
        NurbsCurve::new(raw.degree, raw.knots, points, raw.weights).map_err(|e| e.to_string())?;
    match raw.trim {
        Some(range) => curve.subsegment(range).map_err(|e| e.to_string()),
        None => Ok(curve),
    }
}
