//! Where two rational Bezier curves meet: isolated points (crossings and tangencies) and
//! coincident stretches, with bounded work.
//!
//! # Method
//! - *Coincident stretches*: two distinct rational curves that share an arc share the
//!   whole algebraic branch, so a shared stretch of two pieces ends at an end of one of them.
//!   The four ends are projected onto the other curve; between two consecutive projections
//!   that lie on it, seven sample points of `p` all within the tolerance of `q` make the
//!   stretch coincident.
//! - *Isolated points*: the rest of `p` and `q` are halved (the longer of the two parts each
//!   time) while their control boxes and their fat lines (the slab of each part's control
//!   points round its chord, and the one across it) still meet, down to parts of
//!   [`RESOLUTION`] times the size; on each remaining pair, a damped Newton
//!   (Levenberg-Marquardt) iteration on `p(t) - q(u) = 0` from the pair's middle converges to
//!   a crossing, or to the closest approach of a tangency, kept when `|p(t) - q(u)|` is within
//!   the tolerance. The fat lines keep a tangency to a few pairs per level.
//! - *Duplicates*: hits within [`MERGE_RADIUS`] times the size of each other, or between
//!   which the curves stay within the tolerance of each other (the scattered hits of one
//!   tangency), are one hit; an end of a curve found on the other is kept as the exact end.
//!
//! Every loop is bounded: at most [`IntersectOptions::max_pairs`] pairs of parts are tested
//! for one pair of curves (plus projections), and exceeding it is [`IntersectError::Budget`],
//! never a hang: coincident stretches the sampling does not recognise (or curves with a huge
//! number of near misses) end there.

use crate::curve::prelude::*;
use crate::{BoundingBox, Point, RationalBezier};
use thiserror::Error;

/// The default tolerance relative to the curves' size (their largest control-point
/// coordinate, and at least their control boxes' diagonal): `64 eps`, above the rounding of
/// de Casteljau halvings, far below any feature.
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 64.0 * f64::EPSILON;

/// The default most pairs of parts tested for one pair of curves.
pub const DEFAULT_MAX_PAIRS: usize = 1 << 15;

/// Parts are halved down to this size relative to the curves' size before Newton refines
/// the pair.
pub const RESOLUTION: f64 = 1e-9;

/// Hits closer than this, relative to the curves' size, are one hit (two crossings closer
/// than this are a tangency at double precision).
pub const MERGE_RADIUS: f64 = 1e-9;

/// Most halvings of one part (a part of `2^-60` of its curve is far below the resolution).
const MAX_DEPTH: u32 = 60;

/// Most steps of the damped Newton iteration on one pair.
const NEWTON_STEPS: usize = 80;

/// Sample points that decide a coincident stretch.
const OVERLAP_SAMPLES: usize = 7;

/// How [`intersect`] works: its tolerance and its budget.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntersectOptions {
    /// The absolute distance within which two points count as one; `None` for
    /// [`DEFAULT_RELATIVE_TOLERANCE`] times the curves' size.
    pub tolerance: Option<f64>,
    /// Most pairs of parts tested (and points projected) for one pair of curves.
    pub max_pairs: usize,
}

impl IntersectOptions {
    /// The relative default tolerance and [`DEFAULT_MAX_PAIRS`].
    pub const DEFAULT: IntersectOptions = IntersectOptions {
        tolerance: None,
        max_pairs: DEFAULT_MAX_PAIRS,
    };

    /// The same options with an absolute tolerance.
    pub const fn with_tolerance(mut self, tolerance: f64) -> Self {
        self.tolerance = Some(tolerance);
        self
    }

    /// The same options with another budget of pairs.
    pub const fn with_max_pairs(mut self, max_pairs: usize) -> Self {
        self.max_pairs = max_pairs;
        self
    }
}

impl Default for IntersectOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Why [`intersect`] gave no answer.
#[derive(Clone, Debug, Error, PartialEq)]
#[non_exhaustive]
pub enum IntersectError {
    /// More pairs of parts than the budget: the curves run along each other (coincident
    /// without being recognised) or are too hostile to separate.
    #[error(
        "curve intersection gave up after {limit} pairs of parts (curves running along each other?)"
    )]
    Budget {
        /// The budget that was exhausted.
        limit: usize,
    },
    /// A tolerance that is not finite and `>= 0`, or curves with non-finite points.
    #[error("curve intersection needs finite curves and a finite tolerance >= 0, got {0:?}")]
    NotFinite(f64),
}

/// One point where two curves meet: the parameters on both and the point itself (the end of a
/// curve exactly when the hit is that end).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveHit {
    /// Parameter on the first curve, in `[0, 1]`.
    pub t: f64,
    /// Parameter on the second curve, in `[0, 1]`.
    pub u: f64,
    /// The point: `p(t)`, `q(u)` and this are within the tolerance.
    pub point: Point,
}

/// A stretch along which the two curves coincide: `p` on `[t.0, t.1]` (`t.0 < t.1`) is `q`
/// from `u.0` to `u.1` (`u.0 > u.1` when they run in opposite directions).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveOverlap {
    /// The stretch on the first curve, increasing.
    pub t: (f64, f64),
    /// The matching parameters on the second curve, in the order of `t`.
    pub u: (f64, f64),
}

impl CurveOverlap {
    /// Whether the curves run the same way along the stretch.
    pub fn same_direction(&self) -> bool {
        self.u.1 > self.u.0
    }
}

/// What [`intersect`] found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Intersections {
    /// The isolated points, sorted by `t`, together with the ends of every coincident stretch.
    pub points: Vec<CurveHit>,
    /// The coincident stretches, sorted by `t`.
    pub overlaps: Vec<CurveOverlap>,
}

/// Where the rational Bezier curves `p` and `q` meet (module docs): every isolated point,
/// crossing or tangent, and every coincident stretch, within the options' tolerance.
///
/// # Errors
/// [`IntersectError::Budget`] when more than `options.max_pairs` pairs of parts are tested;
/// [`IntersectError::NotFinite`] for a bad tolerance.
///
/// # Examples
///
/// ```
/// use rs_spline::{circle, segment, intersect, IntersectOptions, Point, prelude::*};
/// // The line y = 1/2 crosses the unit circle's first quarter at (sqrt(3)/2, 1/2).
/// let arc = circle(Point::new(0.0, 0.0), 1.0).unwrap().to_bezier().remove(0);
/// let line = segment(Point::new(0.0, 0.5), Point::new(2.0, 0.5)).unwrap().to_bezier().remove(0);
/// let x = intersect(&arc, &line, &IntersectOptions::DEFAULT).unwrap();
/// assert_eq!(x.points.len(), 1);
/// assert!(x.points[0].point.distance(Point::new(0.75f64.sqrt(), 0.5)) < 1e-15);
/// ```
pub fn intersect(
    p: &RationalBezier,
    q: &RationalBezier,
    options: &IntersectOptions,
) -> Result<Intersections, IntersectError> {
    let size = curve_size(p).max(curve_size(q));
    if !size.is_finite() {
        return Err(IntersectError::NotFinite(size));
    }
    let tol = options
        .tolerance
        .unwrap_or(DEFAULT_RELATIVE_TOLERANCE * size);
    if !(tol.is_finite() && tol >= 0.0) {
        return Err(IntersectError::NotFinite(tol));
    }
    let mut work = Work {
        p,
        q,
        tol,
        resolution: RESOLUTION * size,
        merge: MERGE_RADIUS * size,
        budget: options.max_pairs,
        limit: options.max_pairs,
    };
    let mut hits: Vec<Hit> = Vec::new();
    // The ends of each curve on the other, exactly.
    for (t, end) in [(0.0, p.start_point()), (1.0, p.end_point())] {
        if let Some(u) = work.project(q, end)? {
            hits.push(Hit::end(t, u, end));
        }
    }
    for (u, end) in [(0.0, q.start_point()), (1.0, q.end_point())] {
        if let Some(t) = work.project(p, end)? {
            hits.push(Hit::end(t, u, end));
        }
    }
    hits.sort_by(|a, b| a.t.total_cmp(&b.t));
    let overlaps = work.overlaps(&hits)?;
    // The rest of p, away from the coincident stretches.
    let mut free = Vec::new();
    let mut from = 0.0;
    for o in &overlaps {
        free.push((from, o.t.0));
        from = o.t.1;
    }
    free.push((from, 1.0));
    for (a, b) in free {
        if b - a <= f64::EPSILON {
            continue;
        }
        let part = if a == 0.0 && b == 1.0 {
            p.clone()
        } else {
            p.subsegment((a, b))
                .map_err(|_| IntersectError::NotFinite(a))?
        };
        work.isolated(part, (a, b), &mut hits)?;
    }
    let mut points: Vec<CurveHit> = Vec::new();
    let mut kept: Vec<Hit> = Vec::new();
    // Ends first: a scattered hit near an end merges into the exact end.
    hits.sort_by(|a, b| b.end.cmp(&a.end).then(a.residual.total_cmp(&b.residual)));
    for h in hits {
        if overlaps
            .iter()
            .any(|o| h.t > o.t.0 && h.t < o.t.1 && !h.end)
        {
            continue;
        }
        if !kept.iter().any(|k| work.same_hit(k, &h)) {
            kept.push(h);
        }
    }
    kept.sort_by(|a, b| a.t.total_cmp(&b.t));
    points.extend(kept.iter().map(|h| CurveHit {
        t: h.t,
        u: h.u,
        point: h.point,
    }));
    Ok(Intersections { points, overlaps })
}

/// The size a curve's tolerances are relative to: its largest control-point coordinate and
/// its control box's diagonal (so that curves near the origin still have a size).
fn curve_size(c: &RationalBezier) -> f64 {
    let pts = c.control_points();
    let far = pts
        .iter()
        .fold(0.0f64, |m, q| m.max(q.x.abs()).max(q.y.abs()));
    let diag = BoundingBox::from_points(pts.iter().copied()).map_or(0.0, |b| b.diagonal());
    let s = far.max(diag);
    if s > 0.0 { s } else { f64::MIN_POSITIVE }
}

/// A hit on its way: parameters, point, residual `|p(t) - q(u)|`, and whether it is an end
/// of a curve (exact).
#[derive(Clone, Copy, Debug)]
struct Hit {
    t: f64,
    u: f64,
    point: Point,
    residual: f64,
    end: bool,
}

impl Hit {
    fn end(t: f64, u: f64, point: Point) -> Self {
        Self {
            t,
            u,
            point,
            residual: 0.0,
            end: true,
        }
    }
}

/// One call's curves, tolerances and remaining budget.
struct Work<'a> {
    p: &'a RationalBezier,
    q: &'a RationalBezier,
    tol: f64,
    resolution: f64,
    merge: f64,
    budget: usize,
    limit: usize,
}

impl Work<'_> {
    fn spend(&mut self) -> Result<(), IntersectError> {
        if self.budget == 0 {
            return Err(IntersectError::Budget { limit: self.limit });
        }
        self.budget -= 1;
        Ok(())
    }

    /// The parameter of a point of `c` within the tolerance of `x`, the nearest such if
    /// several: halving `c` while a part's control box (grown by the tolerance) holds `x`,
    /// then Newton on the squared distance.
    fn project(&mut self, c: &RationalBezier, x: Point) -> Result<Option<f64>, IntersectError> {
        let mut best: Option<(f64, f64)> = None;
        let mut stack = vec![(c.clone(), (0.0, 1.0), 0u32)];
        while let Some((part, (a, b), depth)) = stack.pop() {
            self.spend()?;
            let bbox = part.control_bounding_box();
            if !bbox.grown_by(self.tol).contains(x) {
                continue;
            }
            if bbox.diagonal() <= self.resolution || depth >= MAX_DEPTH {
                let t = newton_projection(c, x, 0.5 * (a + b));
                let d = c.point_at(t).distance(x);
                if d <= self.tol && best.is_none_or(|(_, e)| d < e) {
                    best = Some((t, d));
                }
                continue;
            }
            let (l, r) = part.subdivide();
            let m = 0.5 * (a + b);
            stack.push((r, (m, b), depth + 1));
            stack.push((l, (a, m), depth + 1));
        }
        // An end within the tolerance is that end exactly.
        Ok(best.map(|(t, _)| {
            if c.start_point().distance(x) <= self.tol
                && c.point_at(t).distance(c.start_point()) <= self.merge
            {
                0.0
            } else if c.end_point().distance(x) <= self.tol
                && c.point_at(t).distance(c.end_point()) <= self.merge
            {
                1.0
            } else {
                t
            }
        }))
    }

    /// The coincident stretches between consecutive end hits (module docs).
    fn overlaps(&mut self, ends: &[Hit]) -> Result<Vec<CurveOverlap>, IntersectError> {
        let mut out: Vec<CurveOverlap> = Vec::new();
        for w in ends.windows(2) {
            let (a, b) = (w[0], w[1]);
            if b.t - a.t <= f64::EPSILON || (b.u - a.u).abs() <= f64::EPSILON {
                continue;
            }
            if out.last().is_some_and(|o| o.t.1 > a.t) {
                continue;
            }
            let mut on = true;
            for i in 1..=OVERLAP_SAMPLES {
                let f = i as f64 / (OVERLAP_SAMPLES + 1) as f64;
                let x = self.p.point_at(a.t + f * (b.t - a.t));
                match self.project(self.q, x)? {
                    Some(u) if u >= a.u.min(b.u) && u <= a.u.max(b.u) => {}
                    _ => {
                        on = false;
                        break;
                    }
                }
            }
            if on {
                out.push(CurveOverlap {
                    t: (a.t, b.t),
                    u: (a.u, b.u),
                });
            }
        }
        Ok(out)
    }

    /// The isolated hits of `part` (which is `p` on `range`) with `q` (module docs).
    fn isolated(
        &mut self,
        part: RationalBezier,
        range: (f64, f64),
        hits: &mut Vec<Hit>,
    ) -> Result<(), IntersectError> {
        let mut stack = vec![(part, range, self.q.clone(), (0.0, 1.0), 0u32, 0u32)];
        while let Some((a, ra, b, rb, da, db)) = stack.pop() {
            self.spend()?;
            if separated(&a, &b, self.tol) {
                continue;
            }
            let (sa, sb) = (
                a.control_bounding_box().diagonal(),
                b.control_bounding_box().diagonal(),
            );
            let a_done = sa <= self.resolution || da >= MAX_DEPTH;
            let b_done = sb <= self.resolution || db >= MAX_DEPTH;
            if a_done && b_done {
                if let Some(h) = self.refine(0.5 * (ra.0 + ra.1), 0.5 * (rb.0 + rb.1)) {
                    hits.push(h);
                }
                continue;
            }
            if !a_done && (b_done || sa >= sb) {
                let (l, r) = a.subdivide();
                let m = 0.5 * (ra.0 + ra.1);
                stack.push((r, (m, ra.1), b.clone(), rb, da + 1, db));
                stack.push((l, (ra.0, m), b, rb, da + 1, db));
            } else {
                let (l, r) = b.subdivide();
                let m = 0.5 * (rb.0 + rb.1);
                stack.push((a.clone(), ra, r, (m, rb.1), da, db + 1));
                stack.push((a, ra, l, (rb.0, m), da, db + 1));
            }
        }
        Ok(())
    }

    /// Damped Newton (Levenberg-Marquardt) on `F(t, u) = p(t) - q(u)` from `(t, u)`, the
    /// parameters kept in `[0, 1]`: a crossing, or the closest approach of a tangency; kept
    /// when `|F|` ends within the tolerance.
    fn refine(&self, t0: f64, u0: f64) -> Option<Hit> {
        let eval = |t: f64, u: f64| {
            let (pp, dp) = self.p.point_and_tangent(t);
            let (qq, dq) = self.q.point_and_tangent(u);
            (pp, qq, dp, dq)
        };
        let (mut t, mut u) = (t0, u0);
        let (mut pp, mut qq, mut dp, mut dq) = eval(t, u);
        let mut f = pp - qq;
        let mut lambda = 1e-12;
        for _ in 0..NEWTON_STEPS {
            let r = f.length();
            if r == 0.0 {
                break;
            }
            // J = [dp, -dq]; (J^T J + lambda diag) d = -J^T F.
            let (a11, a12, a22) = (dp.dot(dp), -dp.dot(dq), dq.dot(dq));
            let (g1, g2) = (dp.dot(f), -dq.dot(f));
            let mut improved = false;
            for _ in 0..24 {
                let (m11, m22) = (a11 * (1.0 + lambda), a22 * (1.0 + lambda));
                let det = m11 * m22 - a12 * a12;
                if !(det.is_finite() && det > 0.0) {
                    lambda = (lambda * 16.0).max(1e-12);
                    continue;
                }
                let dt = -(m22 * g1 - a12 * g2) / det;
                let du = -(m11 * g2 - a12 * g1) / det;
                let (nt, nu) = ((t + dt).clamp(0.0, 1.0), (u + du).clamp(0.0, 1.0));
                let (np, nq, ndp, ndq) = eval(nt, nu);
                let nf = np - nq;
                if nf.length() < r {
                    (t, u, pp, qq, dp, dq, f) = (nt, nu, np, nq, ndp, ndq, nf);
                    lambda = (lambda / 16.0).max(1e-15);
                    improved = true;
                    break;
                }
                lambda *= 16.0;
            }
            if !improved {
                break;
            }
        }
        let residual = f.length();
        (residual <= self.tol).then(|| Hit {
            t,
            u,
            point: (pp + qq) * 0.5,
            residual,
            end: false,
        })
    }

    /// Whether two hits are one: close, or joined by a stretch along which the curves stay
    /// within four times the tolerance of each other at the interpolated parameters (a
    /// tangency's scattered hits).
    fn same_hit(&self, a: &Hit, b: &Hit) -> bool {
        if a.point.distance(b.point) <= self.merge {
            return true;
        }
        if (a.t - b.t).abs() > 1e-3 || (a.u - b.u).abs() > 1e-3 {
            return false;
        }
        [0.25, 0.5, 0.75].iter().all(|f| {
            let x = self.p.point_at(a.t + f * (b.t - a.t));
            let y = self.q.point_at(a.u + f * (b.u - a.u));
            x.distance(y) <= 4.0 * self.tol
        })
    }
}

/// Newton on `(c(t) - x) . c'(t) = 0` from `t`, kept in `[0, 1]`, ending at the best
/// parameter seen.
fn newton_projection(c: &RationalBezier, x: Point, t: f64) -> f64 {
    let mut t = t;
    let mut best = (t, c.point_at(t).distance(x));
    for _ in 0..40 {
        let d = c.derivatives(t);
        let e = d.point - x;
        let g = e.dot(d.first);
        let h = d.first.dot(d.first) + e.dot(d.second);
        if !(h.is_finite() && h > 0.0) {
            break;
        }
        let next = (t - g / h).clamp(0.0, 1.0);
        let dist = c.point_at(next).distance(x);
        if dist < best.1 {
            best = (next, dist);
        }
        if (next - t).abs() <= 1e-17 {
            break;
        }
        t = next;
    }
    best.0
}

/// Whether the parts certainly do not meet: their control boxes apart, or one's control
/// points all on one side of the other's fat line (along its chord or across it), beyond
/// `margin`.
fn separated(a: &RationalBezier, b: &RationalBezier, margin: f64) -> bool {
    if !a
        .control_bounding_box()
        .grown_by(margin)
        .overlaps(&b.control_bounding_box())
    {
        return true;
    }
    slab_apart(a.control_points(), b.control_points(), margin)
        || slab_apart(b.control_points(), a.control_points(), margin)
}

/// Whether `q`'s points all lie outside `p`'s slab round its chord, or outside its slab
/// across the chord, on one side, by more than `margin`.
fn slab_apart(p: &[Point], q: &[Point], margin: f64) -> bool {
    let (Some(&a), Some(&b)) = (p.first(), p.last()) else {
        return false;
    };
    let len = a.distance(b);
    if !(len > 0.0 && len.is_finite()) {
        return false;
    }
    let along = (b - a) / len;
    for n in [along.perp(), along] {
        let range = |pts: &[Point]| {
            pts.iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
                    let s = n.dot(x - a);
                    (lo.min(s), hi.max(s))
                })
        };
        let (plo, phi) = range(p);
        let (qlo, qhi) = range(q);
        if qlo > phi + margin || qhi < plo - margin {
            return true;
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{NurbsCurve, circle, segment};

    fn pieces(c: &NurbsCurve) -> Vec<RationalBezier> {
        c.to_bezier()
    }

    /// Every hit of two whole curves (all pairs of pieces), points merged across pieces.
    fn all_hits(a: &NurbsCurve, b: &NurbsCurve) -> Vec<Point> {
        let mut out: Vec<Point> = Vec::new();
        for p in pieces(a) {
            for q in pieces(b) {
                let x = intersect(&p, &q, &IntersectOptions::DEFAULT).unwrap();
                assert!(x.overlaps.is_empty());
                for h in x.points {
                    assert!(p.point_at(h.t).distance(h.point) < 1e-13);
                    assert!(q.point_at(h.u).distance(h.point) < 1e-13);
                    if !out.iter().any(|o| o.distance(h.point) < 1e-9) {
                        out.push(h.point);
                    }
                }
            }
        }
        out
    }

    fn near(got: &[Point], want: &[Point], tol: f64) {
        assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
        for w in want {
            assert!(
                got.iter().any(|g| g.distance(*w) < tol),
                "{w:?} not in {got:?}"
            );
        }
    }

    #[test]
    fn line_and_circle() {
        let c = circle(Point::new(0.0, 0.0), 1.0).unwrap();
        let l = segment(Point::new(-2.0, 0.3), Point::new(2.0, 0.3)).unwrap();
        let x = (1.0f64 - 0.09).sqrt();
        near(
            &all_hits(&c, &l),
            &[Point::new(x, 0.3), Point::new(-x, 0.3)],
            1e-15,
        );
    }

    #[test]
    fn two_circles() {
        let a = circle(Point::new(-0.5, 0.0), 1.0).unwrap();
        let b = circle(Point::new(0.5, 0.0), 1.0).unwrap();
        let y = 0.75f64.sqrt();
        near(
            &all_hits(&a, &b),
            &[Point::new(0.0, y), Point::new(0.0, -y)],
            1e-15,
        );
    }

    #[test]
    fn two_cubics_cross_at_known_points() {
        // y = x^3 - x and y = -(x^3 - x) / 2 on [-1.5, 1.5]: both vanish at -1, 0 and 1.
        let cubic = |s: f64| {
            // Bezier control points of x = t, y = s (t^3 - t) on t in [-1.5, 1.5].
            let f = |t: f64| Point::new(t, s * (t * t * t - t));
            let (a, b) = (-1.5, 1.5);
            let d = |t: f64| Point::new(1.0, s * (3.0 * t * t - 1.0));
            let h = (b - a) / 3.0;
            NurbsCurve::bezier(vec![f(a), f(a) + d(a) * h, f(b) - d(b) * h, f(b)], None).unwrap()
        };
        let got = all_hits(&cubic(1.0), &cubic(-0.5));
        let want: Vec<Point> = [-1.0, 0.0, 1.0]
            .iter()
            .map(|&x| Point::new(x, 0.0))
            .collect();
        near(&got, &want, 1e-14);
    }

    #[test]
    fn tangent_line_and_circles() {
        let c = circle(Point::new(0.0, 0.0), 1.0).unwrap();
        let l = segment(Point::new(-2.0, 1.0), Point::new(2.0, 1.0)).unwrap();
        near(&all_hits(&c, &l), &[Point::new(0.0, 1.0)], 1e-7);
        // A tangent at 45 degrees.
        let s = 0.5f64.sqrt();
        let l = segment(Point::new(2.0 * s, 0.0), Point::new(0.0, 2.0 * s)).unwrap();
        near(&all_hits(&c, &l), &[Point::new(s, s)], 1e-7);
        // Circles touching outside and inside.
        let d = circle(Point::new(2.0, 0.0), 1.0).unwrap();
        near(&all_hits(&c, &d), &[Point::new(1.0, 0.0)], 1e-7);
        let e = circle(Point::new(0.5, 0.0), 0.5).unwrap();
        near(&all_hits(&c, &e), &[Point::new(1.0, 0.0)], 1e-7);
    }

    #[test]
    fn nearly_tangent_crossings_stay_two() {
        // Circles whose two crossings are 1e-6 apart: the lens is 2.5e-13 thick.
        let h = 0.5e-6f64;
        let c = circle(Point::new(0.0, 0.0), 1.0).unwrap();
        let d = circle(Point::new(2.0 * (1.0 - h * h).sqrt(), 0.0), 1.0).unwrap();
        let got = all_hits(&c, &d);
        let x = (1.0 - h * h).sqrt();
        near(&got, &[Point::new(x, h), Point::new(x, -h)], 1e-9);
        // A line 1e-12 inside the circle's top crosses it twice, 2.8e-6 apart.
        let y = 1.0 - 1e-12;
        let l = segment(Point::new(-1.0, y), Point::new(1.0, y)).unwrap();
        let x = (1.0 - y * y).sqrt();
        near(
            &all_hits(&c, &l),
            &[Point::new(x, y), Point::new(-x, y)],
            1e-9,
        );
    }

    #[test]
    fn coincident_stretches() {
        // Two segments on one line, overlapping on [1, 2], one reversed.
        let p = segment(Point::new(0.0, 0.0), Point::new(2.0, 0.0))
            .unwrap()
            .to_bezier()
            .remove(0);
        let q = segment(Point::new(3.0, 0.0), Point::new(1.0, 0.0))
            .unwrap()
            .to_bezier()
            .remove(0);
        let x = intersect(&p, &q, &IntersectOptions::DEFAULT).unwrap();
        assert_eq!(x.overlaps.len(), 1);
        let o = x.overlaps[0];
        assert_eq!(o.t, (0.5, 1.0));
        assert_eq!(o.u, (1.0, 0.5));
        assert!(!o.same_direction());
        // An arc against itself and against its own second half.
        let arc = circle(Point::new(0.0, 0.0), 1.0)
            .unwrap()
            .to_bezier()
            .remove(0);
        let x = intersect(&arc, &arc, &IntersectOptions::DEFAULT).unwrap();
        assert_eq!(x.overlaps.len(), 1);
        assert_eq!(x.overlaps[0].t, (0.0, 1.0));
        assert!(x.overlaps[0].same_direction());
        let half = arc.split_at(0.5).unwrap().1.reversed();
        let x = intersect(&arc, &half, &IntersectOptions::DEFAULT).unwrap();
        assert_eq!(x.overlaps.len(), 1);
        assert!((x.overlaps[0].t.0 - 0.5).abs() < 1e-12 && x.overlaps[0].t.1 == 1.0);
        assert!(!x.overlaps[0].same_direction());
    }

    #[test]
    fn touching_ends_and_t_junctions() {
        let seg = |a: (f64, f64), b: (f64, f64)| {
            segment(Point::new(a.0, a.1), Point::new(b.0, b.1))
                .unwrap()
                .to_bezier()
                .remove(0)
        };
        let x = intersect(
            &seg((0.0, 0.0), (1.0, 0.0)),
            &seg((1.0, 0.0), (1.0, 1.0)),
            &IntersectOptions::DEFAULT,
        )
        .unwrap();
        assert_eq!(x.points.len(), 1);
        assert_eq!((x.points[0].t, x.points[0].u), (1.0, 0.0));
        let x = intersect(
            &seg((0.0, 0.0), (2.0, 0.0)),
            &seg((1.0, 0.0), (1.0, 1.0)),
            &IntersectOptions::DEFAULT,
        )
        .unwrap();
        assert_eq!(x.points.len(), 1);
        assert_eq!(x.points[0].point, Point::new(1.0, 0.0));
        assert_eq!(x.points[0].u, 0.0);
    }

    #[test]
    fn a_hostile_pair_ends_in_the_budget() {
        // Two degree-32 zigzags along one line crossing each other about 30 times.
        let n = 32;
        let zigzag = |phase: f64| {
            let pts: Vec<Point> = (0..=n)
                .map(|i| Point::new(i as f64, (i as f64 * 1.3 + phase).sin()))
                .collect();
            RationalBezier::new(pts, vec![1.0; n + 1]).unwrap()
        };
        let (a, b) = (zigzag(0.0), zigzag(1.0));
        let tight = IntersectOptions::DEFAULT.with_max_pairs(50);
        assert_eq!(
            intersect(&a, &b, &tight),
            Err(IntersectError::Budget { limit: 50 })
        );
        // With the default budget: an answer, every hit on both curves.
        let start = std::time::Instant::now();
        let x = intersect(&a, &b, &IntersectOptions::DEFAULT).unwrap();
        assert!(start.elapsed().as_secs() < 20);
        for h in &x.points {
            assert!(a.point_at(h.t).distance(b.point_at(h.u)) < 1e-12);
        }
        // Curves 1e-15 apart everywhere: coincident within the tolerance, or refused.
        let c = RationalBezier::new(
            b.control_points()
                .iter()
                .map(|p| Point::new(p.x, p.y + 1e-15))
                .collect(),
            vec![1.0; n + 1],
        )
        .unwrap();
        match intersect(&b, &c, &IntersectOptions::DEFAULT) {
            Ok(x) => assert_eq!(x.overlaps.len(), 1),
            Err(e) => assert!(matches!(e, IntersectError::Budget { .. })),
        }
    }
}
