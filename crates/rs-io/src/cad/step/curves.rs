//! STEP curves (2-D pcurves and 3-D edge curves alike, a 2-D curve having `z = 0`) in their
//! own parametrisation, and their exact conversion to planar NURBS over a parameter interval.
//!
//! Parametrisations (ISO 10303-42, angles in radians after the unit conversion):
//! - `LINE`: `p + t v`, `v` the `VECTOR`'s unit orientation times its magnitude;
//! - `CIRCLE`/`ELLIPSE`: `c + cos t u + sin t v` (`u = a x`, `v = b y` of the placement);
//! - `HYPERBOLA`: `c + cosh t u + sinh t v`; `PARABOLA`: `c + t^2 u + 2 t v` (`u = f x`,
//!   `v = f y`);
//! - B-splines: their knots; `POLYLINE`: the degree-1 spline through its points with knots
//!   `1, 2, ..., n`;
//! - `TRIMMED_CURVE` (sense `.T.`): its basis curve's parameter within the trims.
//!
//! A conversion to NURBS takes an affine map from the curve's space to the plane (the
//! identity on 2-D curves, the plane's frame for 3-D edges of planar faces), applied to the
//! control points, so every result is exact: lines degree 1, conics rational quadratics,
//! B-splines with their degree, knots and weights.

use rs_spline::prelude::*;
use rs_spline::{Affine, NurbsCurve, Point};

use super::geom::{self, BSplineData, V3, add, dist, dot, scale, sub};
use super::graph::{Graph, Value, value_real};

/// The deepest chain of `TRIMMED_CURVE`s followed to the basis curve.
const MAX_TRIM_CHAIN: usize = 4;

/// The most rational quadratic pieces of a hyperbola arc (each spans at most one unit of
/// its parameter, where `cosh` stays well conditioned).
const MAX_HYPERBOLA_PIECES: usize = 64;

/// The conic kinds.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum ConicKind {
    Ellipse,
    Hyperbola,
    Parabola,
}

/// A curve in its native parametrisation.
#[derive(Clone, Debug)]
pub(crate) enum Curve {
    /// `p + t v`
    Line { p: V3, v: V3 },
    /// See the module docs.
    Conic {
        kind: ConicKind,
        c: V3,
        u: V3,
        v: V3,
    },
    /// A B-spline (control points in 3-D; a 2-D one has `z = 0`).
    Spline(BSplineData),
    /// A window `[t0, t1]` of a basis curve.
    Trimmed { basis: Box<Curve>, t0: f64, t1: f64 },
}

/// The affine map of the plane conversions: `(x, y, z) -> (m[0] . (X - o), m[1] . (X - o))`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PlaneMap {
    pub(crate) origin: V3,
    pub(crate) ex: V3,
    pub(crate) ey: V3,
}

impl PlaneMap {
    /// The identity on 2-D curves: `(x, y)`.
    pub(crate) const XY: PlaneMap = PlaneMap {
        origin: [0.0; 3],
        ex: [1.0, 0.0, 0.0],
        ey: [0.0, 1.0, 0.0],
    };

    fn point(&self, p: V3) -> Point {
        let d = sub(p, self.origin);
        Point::new(dot(d, self.ex), dot(d, self.ey))
    }

    fn vector(&self, v: V3) -> Point {
        Point::new(dot(v, self.ex), dot(v, self.ey))
    }
}

impl Curve {
    /// Reads the curve `#label`; `radians` is the file's radians per angle unit (trim
    /// parameters of conics are angles).
    pub(crate) fn read(g: &Graph, label: u64, from: &str, radians: f64) -> Result<Curve, String> {
        Self::read_depth(g, label, from, radians, 0)
    }

    fn read_depth(
        g: &Graph,
        label: u64,
        from: &str,
        radians: f64,
        depth: usize,
    ) -> Result<Curve, String> {
        let inst = g.get(label, from)?;
        let what = inst.what();
        if inst.is("B_SPLINE_CURVE_WITH_KNOTS") {
            return Ok(Curve::Spline(geom::bspline(g, inst)?));
        }
        let a = inst.simple()?;
        match a.part.name.as_str() {
            "LINE" => {
                let p = geom::point(g, a.reference(1, "pnt")?, &what)?;
                let vi = g.get(a.reference(2, "dir")?, &what)?;
                let va = vi.record("VECTOR")?;
                let d = geom::direction(g, va.reference(1, "orientation")?, &vi.what())?;
                let m = va.real(2, "magnitude")?;
                if m.is_nan() || m <= 0.0 {
                    return Err(format!("{}: magnitude {m}", vi.what()));
                }
                Ok(Curve::Line { p, v: scale(d, m) })
            }
            "CIRCLE" | "ELLIPSE" | "HYPERBOLA" | "PARABOLA" => {
                let f = geom::placement(g, a.reference(1, "position")?, &what)?;
                let name = a.part.name.as_str();
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
                    return Err(format!(
                        "{what}: non-positive radius, axis or focal distance"
                    ));
                }
                let kind = match name {
                    "HYPERBOLA" => ConicKind::Hyperbola,
                    "PARABOLA" => ConicKind::Parabola,
                    _ => ConicKind::Ellipse,
                };
                Ok(Curve::Conic {
                    kind,
                    c: f.origin,
                    u: scale(f.x, r1),
                    v: scale(f.y, r2),
                })
            }
            "POLYLINE" => {
                let refs = a.refs(1, "points")?;
                if refs.len() < 2 {
                    return Err(format!("{what}: fewer than two points"));
                }
                let points = refs
                    .iter()
                    .map(|&r| geom::point(g, r, &what))
                    .collect::<Result<Vec<_>, _>>()?;
                let n = points.len();
                let mut knots = vec![1.0];
                knots.extend((1..=n).map(|i| i as f64));
                knots.push(n as f64);
                Ok(Curve::Spline(BSplineData {
                    degree: 1,
                    points,
                    knots,
                    weights: None,
                }))
            }
            "TRIMMED_CURVE" => {
                if depth >= MAX_TRIM_CHAIN {
                    return Err(format!("{what}: trimmed curves nested too deep"));
                }
                let basis =
                    Self::read_depth(g, a.reference(1, "basis_curve")?, &what, radians, depth + 1)?;
                if !a.boolean(4, "sense_agreement")? {
                    return Err(format!("{what}: sense_agreement .F. is not supported"));
                }
                let angular = matches!(
                    basis,
                    Curve::Conic {
                        kind: ConicKind::Ellipse,
                        ..
                    }
                );
                let trim = |i: usize, name: &str| -> Result<f64, String> {
                    let list = a.list(i, name)?;
                    // Prefer the parameter value; else invert the trimming point.
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
                            let p = geom::point(g, *r, &what)?;
                            return basis.invert(p);
                        }
                    }
                    Err(format!("{what}: {name} has no parameter or point"))
                };
                let t0 = trim(2, "trim_1")?;
                let mut t1 = trim(3, "trim_2")?;
                if let Some(p) = basis.period()
                    && t1 <= t0
                {
                    t1 += p * ((t0 - t1) / p).floor() + p;
                }
                if t1.is_nan() || t1 <= t0 {
                    return Err(format!("{what}: empty trim [{t0}, {t1}]"));
                }
                Ok(Curve::Trimmed {
                    basis: Box::new(basis),
                    t0,
                    t1,
                })
            }
            other => Err(format!("{what}: curve type {other} is not supported")),
        }
    }

    /// The period of a closed curve: `2 pi` for circles and ellipses, the domain's length for
    /// a B-spline whose ends meet (to `1e-12` of its size), so an edge across its seam wraps.
    pub(crate) fn period(&self) -> Option<f64> {
        match self {
            Curve::Conic {
                kind: ConicKind::Ellipse,
                ..
            } => Some(std::f64::consts::TAU),
            Curve::Spline(s) => {
                let (a, b) = self.range()?;
                let size = s.points.iter().map(|&p| geom::norm(p)).fold(0.0, f64::max);
                (b > a && dist(self.point(a), self.point(b)) <= 1e-12 * size.max(1e-300))
                    .then_some(b - a)
            }
            _ => None,
        }
    }

    /// The parameter interval of a bounded curve.
    pub(crate) fn range(&self) -> Option<(f64, f64)> {
        match self {
            Curve::Spline(s) => Some((
                *s.knots.get(s.degree)?,
                *s.knots.get(s.knots.len().checked_sub(s.degree + 1)?)?,
            )),
            Curve::Trimmed { t0, t1, .. } => Some((*t0, *t1)),
            _ => None,
        }
    }

    /// The point at `t`.
    pub(crate) fn point(&self, t: f64) -> V3 {
        match self {
            Curve::Line { p, v } => add(*p, scale(*v, t)),
            Curve::Conic { kind, c, u, v } => {
                let (a, b) = match kind {
                    ConicKind::Ellipse => (t.cos(), t.sin()),
                    ConicKind::Hyperbola => (t.cosh(), t.sinh()),
                    ConicKind::Parabola => (t * t, 2.0 * t),
                };
                add(*c, add(scale(*u, a), scale(*v, b)))
            }
            Curve::Spline(s) => spline_point(s, t),
            Curve::Trimmed { basis, .. } => basis.point(t),
        }
    }

    /// The parameter of the point of the curve nearest `x`: exact for lines and conics (`x`
    /// on the curve), a bounded search for B-splines.
    pub(crate) fn invert(&self, x: V3) -> Result<f64, String> {
        match self {
            Curve::Line { p, v } => Ok(dot(sub(x, *p), *v) / dot(*v, *v)),
            Curve::Conic { kind, c, u, v } => {
                let d = sub(x, *c);
                let a = dot(d, *u) / dot(*u, *u);
                let b = dot(d, *v) / dot(*v, *v);
                Ok(match kind {
                    ConicKind::Ellipse => b.atan2(a),
                    ConicKind::Hyperbola => b.asinh(),
                    ConicKind::Parabola => 0.5 * b,
                })
            }
            Curve::Spline(_) | Curve::Trimmed { .. } => {
                let (a, b) = self.range().ok_or("empty spline")?;
                Ok(nearest_on(self, x, a, b))
            }
        }
    }

    /// The exact planar NURBS of the curve on `[t0, t1]` (`t0 < t1`) through `map`.
    pub(crate) fn to_nurbs(&self, t0: f64, t1: f64, map: &PlaneMap) -> Result<NurbsCurve, String> {
        if !t0.is_finite() || !t1.is_finite() || t0 >= t1 {
            return Err(format!("empty parameter interval [{t0}, {t1}]"));
        }
        match self {
            Curve::Line { .. } => {
                rs_spline::segment(map.point(self.point(t0)), map.point(self.point(t1)))
                    .map_err(|e| e.to_string())
            }
            Curve::Conic { kind, c, u, v } => {
                let unit = match kind {
                    ConicKind::Ellipse => {
                        rs_spline::circular_arc(Point::new(0.0, 0.0), 1.0, t0, t1 - t0)
                            .map_err(|e| e.to_string())?
                    }
                    ConicKind::Hyperbola => unit_hyperbola(t0, t1)?,
                    ConicKind::Parabola => {
                        // (t^2, 2t): the tangents at t0, t1 meet at (t0 t1, t0 + t1).
                        NurbsCurve::bezier(
                            vec![
                                Point::new(t0 * t0, 2.0 * t0),
                                Point::new(t0 * t1, t0 + t1),
                                Point::new(t1 * t1, 2.0 * t1),
                            ],
                            None,
                        )
                        .map_err(|e| e.to_string())?
                    }
                };
                let (mu, mv, mc) = (map.vector(*u), map.vector(*v), map.point(*c));
                Affine {
                    m: [mu.x, mu.y, mv.x, mv.y, mc.x, mc.y],
                }
                .apply_to_curve(&unit)
                .map_err(|e| e.to_string())
            }
            Curve::Spline(s) => {
                let c = NurbsCurve::new(
                    s.degree,
                    s.knots.clone(),
                    s.points.iter().map(|&p| map.point(p)).collect(),
                    s.weights.clone(),
                )
                .map_err(|e| e.to_string())?;
                let (a, b) = c.param_range();
                if t0 <= a && t1 >= b {
                    return Ok(c);
                }
                c.subsegment((t0.max(a), t1.min(b)))
                    .map_err(|e| e.to_string())
            }
            Curve::Trimmed { basis, .. } => basis.to_nurbs(t0, t1, map),
        }
    }
}

impl Curve {
    /// The domain of the B-spline under the curve (through trims), `None` for lines and
    /// conics.
    pub(crate) fn spline_domain(&self) -> Option<(f64, f64)> {
        match self {
            Curve::Spline(_) => self.range(),
            Curve::Trimmed { basis, .. } => basis.spline_domain(),
            _ => None,
        }
    }

    /// The point at `t`, a B-spline continued past its domain by the polynomial of its end
    /// span (how a pcurve that stops just short of its vertex is extended to it).
    pub(crate) fn point_extended(&self, t: f64) -> V3 {
        match self {
            Curve::Spline(s) => match self.range() {
                Some((a, b)) if t < a || t > b => {
                    let (k, _) = end_span(s, t < a);
                    let h = blossom(s, k, &vec![t; s.degree]);
                    [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
                }
                _ => self.point(t),
            },
            Curve::Trimmed { basis, .. } => basis.point_extended(t),
            _ => self.point(t),
        }
    }

    /// [`Curve::to_nurbs`] on `[t0, t1]`, where a B-spline's interval may reach past its
    /// domain `[a, b]`: the part inside, with the end spans' polynomials on `[t0, a]` and
    /// `[b, t1]` as Bezier curves before and after (exact: their control points are the
    /// polar forms of the end span, in homogeneous coordinates).
    pub(crate) fn to_nurbs_extended(
        &self,
        t0: f64,
        t1: f64,
        map: &PlaneMap,
    ) -> Result<Vec<NurbsCurve>, String> {
        let Some((a, b)) = self.spline_domain() else {
            return Ok(vec![self.to_nurbs(t0, t1, map)?]);
        };
        let s = match self {
            Curve::Spline(s) => s,
            Curve::Trimmed { basis, .. } => return basis.to_nurbs_extended(t0, t1, map),
            _ => return Ok(vec![self.to_nurbs(t0, t1, map)?]),
        };
        let mut out = Vec::new();
        if t0 < a {
            out.push(extension(s, true, t0, a.min(t1), map)?);
        }
        if t0.max(a) < t1.min(b) {
            out.push(self.to_nurbs(t0.max(a), t1.min(b), map)?);
        }
        if t1 > b {
            out.push(extension(s, false, t0.max(b), t1, map)?);
        }
        if out.is_empty() {
            return Err(format!("empty parameter interval [{t0}, {t1}]"));
        }
        Ok(out)
    }
}

/// The first (`start`) or last non-empty knot span `k` (`knots[k] < knots[k + 1]`) and
/// whether there is one.
fn end_span(s: &BSplineData, start: bool) -> (usize, bool) {
    let p = s.degree;
    let n = s.points.len();
    let ok = |k: usize| s.knots[k] < s.knots[k + 1];
    if start {
        (p..n).find(|&k| ok(k)).map_or((p, false), |k| (k, true))
    } else {
        (p..n)
            .rev()
            .find(|&k| ok(k))
            .map_or((n - 1, false), |k| (k, true))
    }
}

/// The polar form (blossom) of span `k`'s polynomial at the `degree` arguments `us`, in
/// homogeneous coordinates: de Boor's algorithm with argument `us[r - 1]` at level `r`.
fn blossom(s: &BSplineData, k: usize, us: &[f64]) -> [f64; 4] {
    let p = s.degree;
    let w = |i: usize| s.weights.as_ref().map_or(1.0, |w| w[i]);
    let mut d: Vec<[f64; 4]> = (0..=p)
        .map(|j| {
            let i = k - p + j;
            let q = s.points[i];
            let wi = w(i);
            [q[0] * wi, q[1] * wi, q[2] * wi, wi]
        })
        .collect();
    for r in 1..=p {
        let t = us.get(r - 1).copied().unwrap_or(f64::NAN);
        for j in (r..=p).rev() {
            let i = k - p + j;
            let den = s.knots[i + p + 1 - r] - s.knots[i];
            let alpha = if den > 0.0 {
                (t - s.knots[i]) / den
            } else {
                0.0
            };
            let prev = d[j - 1];
            for (x, p) in d[j].iter_mut().zip(prev) {
                *x = (1.0 - alpha) * p + alpha * *x;
            }
        }
    }
    d[p]
}

/// The end span's polynomial (the first span's if `start`) on `[t0, t1]` as a Bezier curve:
/// control point `i` is the polar form at `t0` (`degree - i` times) and `t1` (`i` times).
fn extension(
    s: &BSplineData,
    start: bool,
    t0: f64,
    t1: f64,
    map: &PlaneMap,
) -> Result<NurbsCurve, String> {
    let (k, ok) = end_span(s, start);
    if !ok || t0.is_nan() || t1.is_nan() || t0 >= t1 {
        return Err(format!("no end span to extend over [{t0}, {t1}]"));
    }
    let p = s.degree;
    let mut points = Vec::with_capacity(p + 1);
    let mut weights = Vec::with_capacity(p + 1);
    for i in 0..=p {
        let mut us = vec![t0; p - i];
        us.extend(std::iter::repeat_n(t1, i));
        let h = blossom(s, k, &us);
        if !(h[3] > 0.0 && h[3].is_finite()) {
            return Err(format!(
                "the extension over [{t0}, {t1}] has weight {}",
                h[3]
            ));
        }
        points.push(map.point([h[0] / h[3], h[1] / h[3], h[2] / h[3]]));
        weights.push(h[3]);
    }
    let weights = s.weights.as_ref().map(|_| weights);
    NurbsCurve::bezier(points, weights).map_err(|e| e.to_string())
}

/// The unit hyperbola `(cosh t, sinh t)` on `[t0, t1]`: pieces of half-width `d <= 1/2`, each
/// the rational quadratic with ends on the curve, middle point `(cosh m, sinh m) / cosh d`
/// (the tangents' intersection, `m` the middle parameter) and middle weight `cosh d`.
fn unit_hyperbola(t0: f64, t1: f64) -> Result<NurbsCurve, String> {
    let k = (t1 - t0).ceil().max(1.0);
    if k > MAX_HYPERBOLA_PIECES as f64 {
        return Err(format!(
            "hyperbola arc [{t0}, {t1}] longer than {MAX_HYPERBOLA_PIECES} parameter units"
        ));
    }
    let k = k as usize;
    let h = (t1 - t0) / k as f64;
    let d = 0.5 * h;
    let w = d.cosh();
    let at = |t: f64| Point::new(t.cosh(), t.sinh());
    let mut points = vec![at(t0)];
    let mut weights = vec![1.0];
    let mut knots = vec![0.0; 3];
    for j in 0..k {
        let a = t0 + j as f64 * h;
        points.push(at(a + d) / w);
        points.push(at(a + h));
        weights.extend([w, 1.0]);
        if j + 1 < k {
            let u = (j + 1) as f64;
            knots.extend([u, u]);
        }
    }
    knots.extend([k as f64; 3]);
    if points.iter().any(|p| !p.is_finite()) {
        return Err(format!("hyperbola arc [{t0}, {t1}] overflows"));
    }
    NurbsCurve::new(2, knots, points, Some(weights)).map_err(|e| e.to_string())
}

/// The point of a B-spline at `t` (clamped to its domain), by de Boor's algorithm on
/// homogeneous coordinates.
fn spline_point(s: &BSplineData, t: f64) -> V3 {
    let p = s.degree;
    let n = s.points.len();
    let (a, b) = (s.knots[p], s.knots[n]);
    let t = t.clamp(a, b);
    // The span k with knots[k] <= t < knots[k+1], p <= k < n (binary search: the knots are
    // non-decreasing, checked when the curve is read; a spline of many points stays fast).
    let k = (p + s.knots[p + 1..n].partition_point(|&x| x <= t)).min(n - 1);
    // de Boor's algorithm is the blossom with every argument t.
    let h = blossom(s, k, &vec![t; p]);
    [h[0] / h[3], h[1] / h[3], h[2] / h[3]]
}

/// The parameter in `[a, b]` of the point nearest `x`: the best of 16 samples per knot span
/// (at most 4096 in all), refined by 60 steps of golden-section search in its neighbourhood.
fn nearest_on(c: &Curve, x: V3, a: f64, b: f64) -> f64 {
    let spans = match c {
        Curve::Spline(s) => s.points.len().saturating_sub(s.degree).max(1),
        _ => 1,
    };
    let n = (16 * spans).clamp(16, 4096);
    let h = (b - a) / n as f64;
    let f = |t: f64| dist(c.point(t), x);
    let mut best = (f(a), a);
    for i in 1..=n {
        let t = if i == n { b } else { a + h * i as f64 };
        let d = f(t);
        if d < best.0 {
            best = (d, t);
        }
    }
    let (mut lo, mut hi) = ((best.1 - h).max(a), (best.1 + h).min(b));
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let m1 = hi - g * (hi - lo);
        let m2 = lo + g * (hi - lo);
        if f(m1) < f(m2) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    let t = 0.5 * (lo + hi);
    // Keep an exact end when it is as near (vertices at the ends are the common case).
    [a, b, t]
        .into_iter()
        .min_by(|p, q| f(*p).total_cmp(&f(*q)))
        .unwrap_or(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hyperbola_and_parabola_lie_on_their_curves() {
        let h = unit_hyperbola(-1.3, 2.2).unwrap();
        let (a, b) = h.param_range();
        for i in 0..=50 {
            let p = h.point_at(a + (b - a) * i as f64 / 50.0);
            assert!((p.x * p.x - p.y * p.y - 1.0).abs() < 1e-12, "{p:?}");
        }
        assert!(
            h.start_point()
                .distance(Point::new(1.3f64.cosh(), -1.3f64.sinh()))
                < 1e-14
        );
        assert!(
            h.end_point()
                .distance(Point::new(2.2f64.cosh(), 2.2f64.sinh()))
                < 1e-13
        );
        let c = Curve::Conic {
            kind: ConicKind::Parabola,
            c: [1.0, 2.0, 0.0],
            u: [0.5, 0.0, 0.0],
            v: [0.0, 0.5, 0.0],
        };
        let n = c.to_nurbs(-1.0, 3.0, &PlaneMap::XY).unwrap();
        for i in 0..=20 {
            let p = n.point_at(i as f64 / 20.0);
            // x - 1 = f t^2, y - 2 = 2 f t with f = 1/2: (y - 2)^2 = 4 f (x - 1).
            assert!(((p.y - 2.0).powi(2) - 2.0 * (p.x - 1.0)).abs() < 1e-12);
        }
    }

    #[test]
    fn conic_inversion_is_exact() {
        let c = Curve::Conic {
            kind: ConicKind::Ellipse,
            c: [1.0, 0.0, 0.0],
            u: [2.0, 0.0, 0.0],
            v: [0.0, 1.0, 0.0],
        };
        for t in [-3.0, -1.0, 0.0, 0.5, 3.0] {
            assert!((c.invert(c.point(t)).unwrap() - t).abs() < 1e-14);
        }
    }
}
