//! Curve entities as `rs_geom` curves: each leaf entity (100, 104, 106, 110, 126) is read into a
//! [`Curve`] in its definition space with the parameter interval IGES takes of it, composites
//! (102) are expanded into their leaves, and each leaf carries the maps of its 124
//! transformation chains (its own, then those of the composites holding it): the 3-D map to
//! model space, and its 2-D part for parameter space.
//!
//! The curves are the entities' own parameterisations (IGES 5.3):
//!
//! - 110 line: `P1 + t (P2 - P1)`, `t` in `[0, 1]`: a degree-1 B-spline on `[0, 1]`, which is
//!   exactly that line and keeps both end points exact;
//! - 100 circular arc: the circle `C + r (cos t, sin t)` at height `ZT`, `t` from the start
//!   point's angle counter-clockwise to the end point's (the whole circle when they are equal);
//! - 104 conic arc: [`Conic::from_implicit`] (its parameterisation and interval), at `ZT`;
//! - 106 copious data (forms 11, 12, 63): the polyline as a degree-1 B-spline, vertex `i` at
//!   `t = i`;
//! - 126 rational B-spline: its knots, trimmed to `[V0, V1]`.
//!
//! Curves become exact NURBS by [`Curve::to_bspline`], mapped by their affine maps point by
//! point (affine maps keep rational curves exact, so nothing is ever resampled). A B-spline's
//! control points are mapped before its window is cut and a conic is converted before it is
//! mapped: the arithmetic the reader has always done, so that its curves keep their bits.

use std::f64::consts::TAU;

use rs_geom::brep::Edge;
use rs_geom::pcurve::{PcurveOptions, pcurve};
use rs_geom::surface::Surface;
use rs_geom::{
    Affine3, AffineMap, AffinePlaneCoordinates, Conic, ConicKind, Curve, DEFAULT_MODEL_TOLERANCE,
    Tolerance,
};
use rs_spline::prelude::*;
use rs_spline::{NurbsCurve, Point, Point3, RationalBSpline};

use super::directory::DirEntry;
use super::error::{FieldProblem, IgesError};
use super::params::Params;
use super::{Iges, MAX_DEPTH};

/// One curve of a loop in `(u, v)` and the entity it came from.
#[derive(Clone, Debug)]
pub(super) struct Piece {
    /// The directory entry of the curve entity.
    pub(super) de: usize,
    /// The curve in `(u, v)`.
    pub(super) curve: NurbsCurve,
}

/// A leaf curve entity read in its definition space.
#[derive(Clone, Debug)]
pub(super) struct Leaf {
    /// Its directory entry.
    pub(super) de: usize,
    /// Its type (for messages).
    pub(super) kind: i64,
    /// The curve, in the entity's parameterisation.
    pub(super) curve: Curve<Point3>,
    /// The parameter interval IGES takes of it.
    pub(super) range: (f64, f64),
}

/// A leaf with the maps of its transformation chains.
#[derive(Clone, Debug)]
pub(super) struct Placed {
    /// The leaf.
    pub(super) leaf: Leaf,
    /// Its definition space to model space (3-D).
    pub(super) model: Affine3,
    /// The 2-D parts of the same chains, for parameter-space curves: `x' = R11 x + R12 y + T1`,
    /// `y' = R21 x + R22 y + T2` (`z` is not a parameter and passes through).
    pub(super) param: Affine3,
}

impl Leaf {
    /// The exact rational B-spline of the curve on its interval with every control point
    /// mapped by `f` (`f` affine): a B-spline's points are mapped before the window is cut,
    /// other curves are converted first.
    fn to_bspline_by<Q>(&self, f: impl FnMut(Point3) -> Q) -> Result<RationalBSpline<Q>, IgesError>
    where
        Q: rs_spline::Vector + std::ops::Div<f64, Output = Q>,
    {
        let who = format!(
            "DE {} ({} {})",
            self.de,
            self.kind,
            super::type_name(self.kind)
        );
        let (t0, t1) = self.range;
        match &self.curve {
            Curve::BSpline(b) => {
                let mapped = b.map_points(f).map_err(|e| IgesError::spline(&who, e))?;
                Curve::BSpline(mapped)
                    .to_bspline(t0, t1)
                    .map_err(|e| IgesError::geometry(&who, e))
            }
            c => c
                .to_bspline(t0, t1)
                .map_err(|e| IgesError::geometry(&who, e))?
                .map_points(f)
                .map_err(|e| IgesError::spline(&who, e)),
        }
    }

    /// The curve trimmed to its interval (a B-spline on its whole domain as it is).
    pub(super) fn trimmed(curve: Curve<Point3>, range: (f64, f64)) -> Curve<Point3> {
        match &curve {
            Curve::BSpline(b) if b.param_range() == range => curve,
            _ => Curve::Trimmed {
                basis: Box::new(curve),
                range,
            },
        }
    }
}

impl Placed {
    /// `DE 57 (126 rational B-spline curve)`.
    fn who(&self) -> String {
        format!(
            "DE {} ({} {})",
            self.leaf.de,
            self.leaf.kind,
            super::type_name(self.leaf.kind)
        )
    }

    /// The curve as a parameter-space curve: `(x, y)` after the 2-D maps.
    pub(super) fn param_piece(&self) -> Result<Piece, IgesError> {
        let m = self.param;
        let b = self.leaf.to_bspline_by(|p| {
            let q = m.apply(p);
            Point::new(q.x, q.y)
        })?;
        Ok(Piece {
            de: self.leaf.de,
            curve: b
                .to_planar()
                .map_err(|e| IgesError::spline(&self.who(), e))?,
        })
    }

    /// The model-space curve mapped into a plane's `(u, v)`, after checking that every control
    /// point lies on the plane within the model's coincidence tolerance (of the curve's
    /// largest coordinate).
    pub(super) fn plane_piece(
        &self,
        plane: &AffinePlaneCoordinates,
        tolerance: Tolerance,
    ) -> Result<Piece, IgesError> {
        let m = self.model;
        let (mut worst, mut size) = (0.0f64, 0.0f64);
        let b = self.leaf.to_bspline_by(|p| {
            let q = m.apply(p);
            let d = plane.distance(q);
            // NaN is kept as the worst distance.
            if d.is_nan() || d.abs() > worst {
                worst = d.abs();
            }
            size = size.max(q.max_abs());
            plane.point(q)
        })?;
        let tol = tolerance.coincidence(size);
        if worst.is_nan() || worst > tol {
            return Err(IgesError::OffPlane {
                who: self.who(),
                distance: worst,
                tolerance: tol,
            });
        }
        Ok(Piece {
            de: self.leaf.de,
            curve: b
                .to_planar()
                .map_err(|e| IgesError::spline(&self.who(), e))?,
        })
    }

    /// The pcurve of the model-space curve on `surface` (not a plane), computed by
    /// [`rs_geom::pcurve::pcurve`] to the model's tolerance (the file's, or
    /// [`DEFAULT_MODEL_TOLERANCE`] when it states none): its pieces from the curve's start to
    /// its end, or from its end to its start when `reversed`, the first starting at the
    /// periodic copy nearest `near` (the end of the loop's piece before), and the bound on
    /// their 3-D distance from the curve.
    pub(super) fn computed_pieces(
        &self,
        surface: &Surface,
        reversed: bool,
        tolerance: Tolerance,
        near: Option<Point>,
    ) -> Result<(Vec<Piece>, f64), IgesError> {
        let edge = self.model_curve()?;
        let (t0, t1) = self.leaf.range;
        let range = if reversed { (t1, t0) } else { (t0, t1) };
        let options = PcurveOptions::DEFAULT
            .with_tolerance(tolerance.stated().unwrap_or(DEFAULT_MODEL_TOLERANCE))
            .with_near(near.map(|p| [p.x, p.y]));
        let p = pcurve(surface, &edge, Some(range), &options)
            .map_err(|e| IgesError::geometry(&self.who(), e))?;
        let de = self.leaf.de;
        Ok((
            p.curves
                .into_iter()
                .map(|curve| Piece { de, curve })
                .collect(),
            p.deviation,
        ))
    }

    /// The curve placed in model space, in its own parameter (not trimmed).
    pub(super) fn model_curve(&self) -> Result<Curve<Point3>, IgesError> {
        self.leaf
            .curve
            .map_affine(&self.model)
            .map_err(|e| IgesError::geometry(&self.who(), e))
    }

    /// The curve as a 3-D edge of a loop, run backwards when `reversed`.
    pub(super) fn edge(&self, reversed: bool) -> Result<Edge, IgesError> {
        Ok(Edge {
            entity: format!("DE {}", self.leaf.de),
            curve: self.model_curve()?,
            range: self.leaf.range,
            reversed,
        })
    }
}

/// The 3-D edges of a curve's leaves in loop order, run backwards when `reversed` (none if
/// a leaf has no model-space curve: the face then has no 3-D edges there).
pub(super) fn leaf_edges(leaves: &[Placed], reversed: bool) -> Vec<Edge> {
    let mut edges: Vec<Edge> = leaves
        .iter()
        .map(|l| l.edge(reversed))
        .collect::<Result<_, _>>()
        .unwrap_or_default();
    if reversed {
        edges.reverse();
    }
    edges
}

/// Reverses a list of pieces: the last first, each run backwards.
pub(super) fn reverse_pieces(pieces: &mut [Piece]) {
    pieces.reverse();
    for p in pieces {
        p.curve = p.curve.reversed();
    }
}

impl Iges<'_> {
    /// The leaves of curve `de` (a composite's in order), each with its maps. `from` says who
    /// points to it, for messages.
    pub(super) fn curve_leaves(&self, de: usize, from: &str) -> Result<Vec<Placed>, IgesError> {
        let mut out = Vec::new();
        self.leaves_in(
            de,
            from,
            [Affine3::IDENTITY, Affine3::IDENTITY],
            &mut Vec::new(),
            &mut out,
        )?;
        Ok(out)
    }

    /// `outer` maps the curve's transformed definition space onward (3-D, 2-D part); `stack`
    /// holds the composites being read (cycle detection).
    fn leaves_in(
        &self,
        de: usize,
        from: &str,
        outer: [Affine3; 2],
        stack: &mut Vec<usize>,
        out: &mut Vec<Placed>,
    ) -> Result<(), IgesError> {
        let e = self.entry(de, from)?;
        let [model, param] = self.transforms(e)?;
        let maps = [outer[0].after(model), outer[1].after(param)];
        match e.kind {
            102 => {
                let who = self.who(e);
                if stack.contains(&e.de) {
                    return Err(IgesError::Cycle {
                        who,
                        what: "composite curves",
                        de: e.de,
                    });
                }
                if stack.len() >= MAX_DEPTH {
                    return Err(IgesError::TooDeep {
                        who,
                        what: "composite curves",
                    });
                }
                let mut p = self.params(e)?;
                let n = p.count("N")?;
                let members = p.pointers("N", n, "constituent")?;
                stack.push(e.de);
                for (i, m) in members.into_iter().enumerate() {
                    let from = format!("{who}: constituent {}", i + 1);
                    self.leaves_in(m, &from, maps, stack, out)?;
                }
                stack.pop();
                Ok(())
            }
            100 | 104 | 106 | 110 | 126 => {
                out.push(Placed {
                    leaf: self.leaf(e)?,
                    model: maps[0],
                    param: maps[1],
                });
                Ok(())
            }
            kind => Err(IgesError::WrongType {
                from: from.to_string(),
                de: e.de,
                kind,
                expected: "a curve this reader knows (100, 102, 104, 106, 110, 126)",
            }),
        }
    }

    /// Reads a curve entity other than a composite, in its definition space.
    fn leaf(&self, e: &DirEntry) -> Result<Leaf, IgesError> {
        let who = self.who(e);
        let mut p = self.params(e)?;
        let (curve, range) = match e.kind {
            110 => {
                if e.form != 0 {
                    let what = if e.form == 1 {
                        "is a ray, not a segment"
                    } else {
                        "is an unbounded line, not a segment"
                    };
                    return Err(IgesError::Form {
                        who,
                        form: e.form,
                        what,
                    });
                }
                let a = point3(&mut p, ["X1", "Y1", "Z1"])?;
                let b = point3(&mut p, ["X2", "Y2", "Z2"])?;
                let line = RationalBSpline::new(1, vec![0.0, 0.0, 1.0, 1.0], vec![a, b], None)
                    .map_err(|e| IgesError::spline(&who, e))?;
                (Curve::BSpline(line), (0.0, 1.0))
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
                    return Err(IgesError::ZeroRadius { who });
                }
                let a0 = (start.y - centre.y).atan2(start.x - centre.x);
                let a1 = (end.y - centre.y).atan2(end.x - centre.x);
                // Counter-clockwise from start to end; equal points are the full circle.
                let mut sweep = if start == end {
                    TAU
                } else {
                    (a1 - a0).rem_euclid(TAU)
                };
                if sweep <= 0.0 {
                    sweep = TAU;
                }
                let circle = Conic {
                    kind: ConicKind::Ellipse,
                    center: Point3::new(centre.x, centre.y, v[0]),
                    u: Point3::new(r, 0.0, 0.0),
                    v: Point3::new(0.0, r, 0.0),
                };
                (Curve::Conic(circle), (a0, a0 + sweep))
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
                    form => {
                        return Err(IgesError::Form {
                            who,
                            form,
                            what: "is not a conic arc (1 ellipse, 2 hyperbola, 3 parabola)",
                        });
                    }
                };
                let (c, range) = Conic::from_implicit(
                    [v[0], v[1], v[2], v[3], v[4], v[5]],
                    kind,
                    Point::new(v[7], v[8]),
                    Point::new(v[9], v[10]),
                )
                .map_err(|e| IgesError::geometry(&who, e))?;
                let lift = |p: Point, z: f64| Point3::new(p.x, p.y, z);
                let conic = Conic {
                    kind: c.kind,
                    center: lift(c.center, v[6]),
                    u: lift(c.u, 0.0),
                    v: lift(c.v, 0.0),
                };
                (Curve::Conic(conic), range)
            }
            106 => copious(e, &who, &mut p)?,
            126 => bspline(&who, &mut p)?,
            kind => {
                return Err(IgesError::WrongType {
                    from: who,
                    de: e.de,
                    kind,
                    expected: "a curve",
                });
            }
        };
        Ok(Leaf {
            de: e.de,
            kind: e.kind,
            curve,
            range,
        })
    }
}

/// Three reals named `names`, as a point.
pub(super) fn point3(p: &mut Params<'_>, names: [&'static str; 3]) -> Result<Point3, IgesError> {
    Ok(Point3::new(
        p.real(names[0])?,
        p.real(names[1])?,
        p.real(names[2])?,
    ))
}

/// A degree-1 polyline through `points` (vertex `i` at parameter `i`).
fn polyline(who: &str, points: Vec<Point3>) -> Result<(Curve<Point3>, (f64, f64)), IgesError> {
    let n = points.len();
    let mut knots = Vec::with_capacity(n + 2);
    knots.push(0.0);
    knots.extend((0..n).map(|i| i as f64));
    knots.push(n.saturating_sub(1) as f64);
    let b = RationalBSpline::new(1, knots, points, None).map_err(|e| IgesError::spline(who, e))?;
    let range = b.param_range();
    Ok((Curve::BSpline(b), range))
}

/// 106 copious data, forms 11 (2-D path), 12 (3-D path), 63 (closed planar curve).
fn copious(
    e: &DirEntry,
    who: &str,
    p: &mut Params<'_>,
) -> Result<(Curve<Point3>, (f64, f64)), IgesError> {
    if !matches!(e.form, 11 | 12 | 63) {
        return Err(IgesError::Form {
            who: who.to_string(),
            form: e.form,
            what: "is not a path (forms 11, 12, 63 are read)",
        });
    }
    let ip = p.int("IP")?;
    let n = p.count("N")?;
    let (each, zt) = match ip {
        1 => (2, Some(p.real("ZT")?)),
        2 => (3, None),
        3 => (6, None),
        _ => return Err(p.err("IP", FieldProblem::InterpretationFlag(ip))),
    };
    if n < 2 {
        return Err(p.err("N", FieldProblem::TooFewPoints(n)));
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
        points.push(Point3::new(x, y, z));
    }
    if e.form == 63 && points.first() != points.last() {
        points.push(points[0]);
    }
    polyline(who, points)
}

/// 126 rational B-spline curve: `K, M, PROP1..4`, knots, weights, control points, `V0, V1`.
fn bspline(who: &str, p: &mut Params<'_>) -> Result<(Curve<Point3>, (f64, f64)), IgesError> {
    let k = p.count("K")?;
    let m = p.count("M")?;
    if m == 0 || m > rs_spline::limits::MAX_DEGREE {
        return Err(p.err(
            "M",
            FieldProblem::Degree {
                degree: m,
                max: rs_spline::limits::MAX_DEGREE,
            },
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
        points.push(point3(p, ["X", "Y", "Z"])?);
    }
    let v0 = p.real("V0")?;
    let v1 = p.real("V1")?;
    let weights = if polynomial {
        if weights.iter().any(|&w| w != weights[0]) {
            return Err(IgesError::NotPolynomial {
                who: who.to_string(),
            });
        }
        None
    } else {
        Some(weights)
    };
    // V0, V1 within the knot domain [t_M, t_(K+1)], rounding tolerated.
    let (a, b) = (knots[m], knots[n]);
    let slack = KNOT_ROUNDING * (b - a).abs().max(a.abs()).max(b.abs());
    if !(v0 < v1 && v0 >= a - slack && v1 <= b + slack) {
        return Err(IgesError::TrimRange {
            who: who.to_string(),
            v0,
            v1,
            a,
            b,
        });
    }
    let curve =
        RationalBSpline::new(m, knots, points, weights).map_err(|e| IgesError::spline(who, e))?;
    Ok((Curve::BSpline(curve), (v0.max(a), v1.min(b))))
}

/// A 126's `V0`, `V1` may pass its knot domain's ends by this fraction of the domain's size
/// (files print about ten digits; the parameters are then clamped to the domain).
const KNOT_ROUNDING: f64 = 1e-9;
