//! Several materials on one grid: the region each material occupies when later domains
//! replace earlier ones (the shaping rule of Axom), as closed loops the coverage kernel takes.
//!
//! # Method
//! Each domain's loops that bound its filled set (nonzero [`rs_contain::LoopNesting::boundary_sign`])
//! are turned so the filled set is on their left and cut into Bezier pieces. Every two pieces
//! of different domains whose control boxes meet are intersected ([`rs_spline::intersect`]):
//! each hit is computed once and becomes the exact end point of the split pieces on both
//! sides, and coincident stretches are split at their ends. Each sub-arc's midpoint is placed
//! once against every other domain: inside or outside (the inRS classifier; a point in its
//! boundary band by the side of the nearest boundary point's tangent), or on its boundary
//! along a coincident stretch, running the same way or the opposite way. That says which
//! domains hold the points just left and just right of the sub-arc, hence whether material
//! `k`'s region `R_k = D_k \ (D_{k+1} u ... u D_{n-1})` is on one side only: the sub-arc is
//! kept turned so that `R_k` is on its left, or dropped (of coincident copies, the one of the
//! lowest domain is kept). The kept sub-arcs are chained end to end (ends within the closure
//! tolerance are one vertex), at a vertex with several continuations taking the sharpest
//! left turn, so loops may touch there but do not cross.

use rs_contain::{Classifier, ContainOptions, FillRule, Locate, Location, fill_nesting};
use rs_spline::prelude::*;
use rs_spline::{
    BoundingBox, Domain, IntersectOptions, NearestBoundary, NurbsCurve, Point, RationalBezier,
    intersect,
};
use std::collections::HashMap;

use crate::CoverageError;

/// Most pairs of boundary pieces of different domains whose control boxes meet (each pair is
/// intersected with [`rs_spline::intersect::DEFAULT_MAX_PAIRS`] pairs of parts at most):
/// beyond it [`material_domains`] is [`CoverageError::TooManyPiecePairs`].
pub const MAX_PIECE_PAIRS: usize = 1 << 18;

/// The region each material occupies, as a domain whose even-odd coverage
/// ([`crate::GridCoverage::new`]) is that material's: with `replace`, material `k` holds
/// `R_k = D_k \ (D_{k+1} u ... u D_{n-1})` (a later domain replaces the earlier ones where
/// it is), otherwise `R_k = D_k`. `None` for a material whose region is empty (a [`Domain`]
/// has at least one curve; its coverage is 0 everywhere). Each `D_k` is the set its domain
/// fills under its fill rule, for closed loops that do not cross each other
/// ([`rs_contain::fill_nesting`]). Without `replace` an even-odd domain is returned as given,
/// a nonzero one as the loops that bound its filled set, turned to put it on their left.
///
/// With `replace`, the result's loops are closed and do not cross each other (they may touch
/// at a vertex); the module docs give the method.
///
/// # Errors
/// [`CoverageError::Nesting`] for a domain whose loops are open, cross or coincide;
/// [`CoverageError::TooManyPiecePairs`] beyond [`MAX_PIECE_PAIRS`];
/// [`CoverageError::Intersection`] when a pair of pieces exhausts its budget (pieces running
/// along each other unrecognised); [`CoverageError::Unchained`] if a material's kept
/// sub-arcs do not close into loops.
///
/// # Examples
///
/// ```
/// use rs_contain::FillRule;
/// use rs_coverage::{cell_coverage, material_domains, CellGrid, CoverageOptions};
/// use rs_spline::{circle, Domain, Point};
/// let disc = |x: f64| Domain::new(vec![circle(Point::new(x, 0.0), 1.0).unwrap()]).unwrap();
/// let (a, b) = (disc(-0.5), disc(0.5));
/// let regions = material_domains(&[(&a, FillRule::EvenOdd), (&b, FillRule::EvenOdd)], true).unwrap();
/// let grid = CellGrid::uniform(-2.0, 2.0, 1, -2.0, 2.0, 1).unwrap();
/// let area = |d: &Domain| 16.0 * cell_coverage(d, &grid, CoverageOptions::DEFAULT).unwrap().fractions[0];
/// // The first disc minus the lens the second takes: pi - (2 pi / 3 - sqrt(3) / 2).
/// let lens = 2.0 * std::f64::consts::PI / 3.0 - 0.75f64.sqrt();
/// let r0 = regions[0].as_ref().unwrap();
/// assert!((area(r0) - (std::f64::consts::PI - lens)).abs() < 1e-12);
/// ```
pub fn material_domains(
    domains: &[(&Domain, FillRule)],
    replace: bool,
) -> Result<Vec<Option<Domain>>, CoverageError> {
    let mut oriented = Vec::with_capacity(domains.len());
    for (k, &(d, rule)) in domains.iter().enumerate() {
        if !replace && rule == FillRule::EvenOdd {
            oriented.push(None);
            continue;
        }
        oriented.push(Some(
            Oriented::new(d, rule).map_err(|e| CoverageError::in_material(k, e))?,
        ));
    }
    if !replace {
        return Ok(domains
            .iter()
            .zip(oriented)
            .map(|(&(d, _), o)| match o {
                None => Some(d.clone()),
                Some(o) => o.clean,
            })
            .collect());
    }
    let oriented: Vec<Oriented> = oriented.into_iter().flatten().collect();
    Materials::new(&oriented, domains)?.regions()
}

/// One domain's boundary with its filled set on the left: the loops that bound it, as a
/// domain (`None` when nothing is filled) and as Bezier pieces.
struct Oriented {
    clean: Option<Domain>,
    pieces: Vec<RationalBezier>,
}

impl Oriented {
    fn new(d: &Domain, rule: FillRule) -> Result<Self, CoverageError> {
        // An open boundary in the words `GridCoverage` uses.
        d.require_closed()?;
        let nesting = fill_nesting(d).map_err(CoverageError::Nesting)?;
        let mut curves: Vec<NurbsCurve> = Vec::new();
        for (l, n) in d.loops().iter().zip(&nesting) {
            let sign = n.boundary_sign(rule);
            let part = &d.curves()[l.curves()];
            if sign > 0 {
                curves.extend(part.iter().cloned());
            } else if sign < 0 {
                curves.extend(part.iter().rev().map(NurbsCurve::reversed));
            }
        }
        let pieces = curves.iter().flat_map(NurbsCurve::to_bezier).collect();
        let clean = if curves.is_empty() {
            None
        } else {
            Some(Domain::with_relative_closure_tolerance(
                curves,
                d.closure_abs_tol() / d.bounding_box().diagonal().max(f64::MIN_POSITIVE),
            )?)
        };
        Ok(Self { clean, pieces })
    }
}

/// Where a sub-arc's midpoint lies with respect to another domain.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Place {
    Inside,
    Outside,
    /// On its boundary along a coincident stretch; `true` when both run the same way (the
    /// other domain is on the sub-arc's left).
    On(bool),
}

impl Place {
    /// Whether the domain holds the points just left and just right of the sub-arc.
    fn sides(self) -> (bool, bool) {
        match self {
            Place::Inside => (true, true),
            Place::Outside => (false, false),
            Place::On(true) => (true, false),
            Place::On(false) => (false, true),
        }
    }
}

/// A sub-arc of one domain's boundary (filled set on its left), exact end points, and its
/// place with respect to every domain (its own: unused).
struct SubArc {
    domain: usize,
    curve: RationalBezier,
    places: Vec<Place>,
}

/// Every domain's boundary split at the others' into sub-arcs placed against all domains.
struct Materials {
    arcs: Vec<SubArc>,
    count: usize,
    snap: f64,
}

impl Materials {
    fn new(oriented: &[Oriented], domains: &[(&Domain, FillRule)]) -> Result<Self, CoverageError> {
        let count = oriented.len();
        let mut pieces: Vec<(usize, RationalBezier, BoundingBox)> = Vec::new();
        for (k, o) in oriented.iter().enumerate() {
            for p in &o.pieces {
                pieces.push((k, p.clone(), p.control_bounding_box()));
            }
        }
        let size = pieces
            .iter()
            .map(|(_, _, b)| {
                b.min
                    .x
                    .abs()
                    .max(b.max.x.abs())
                    .max(b.min.y.abs())
                    .max(b.max.y.abs())
                    .max(b.diagonal())
            })
            .fold(f64::MIN_POSITIVE, f64::max);
        let tol = rs_spline::intersect::DEFAULT_RELATIVE_TOLERANCE * size;
        let snap = domains
            .iter()
            .map(|(d, _)| d.closure_abs_tol())
            .fold(16.0 * tol, f64::max);
        // Split points and coincident stretches of every piece.
        let mut splits: Vec<Vec<(f64, Point)>> = vec![Vec::new(); pieces.len()];
        let mut overlaps: Vec<Vec<(f64, f64, usize, bool)>> = vec![Vec::new(); pieces.len()];
        let options = IntersectOptions::DEFAULT.with_tolerance(tol);
        for (i, j) in meeting_pairs(&pieces, tol)? {
            let x = intersect(&pieces[i].1, &pieces[j].1, &options)?;
            for h in &x.points {
                splits[i].push((h.t, h.point));
                splits[j].push((h.u, h.point));
            }
            for o in &x.overlaps {
                let same = o.same_direction();
                overlaps[i].push((o.t.0, o.t.1, pieces[j].0, same));
                overlaps[j].push((o.u.0.min(o.u.1), o.u.0.max(o.u.1), pieces[i].0, same));
            }
        }
        let classifiers: Vec<Option<(Classifier, NearestBoundary, &Domain)>> = oriented
            .iter()
            .map(|o| {
                o.clean
                    .as_ref()
                    .map(|d| {
                        Classifier::new(d, ContainOptions::default())
                            .map(|c| (c, NearestBoundary::new(d), d))
                    })
                    .transpose()
            })
            .collect::<Result<_, _>>()?;
        let mut arcs = Vec::new();
        for (i, (domain, piece, _)) in pieces.iter().enumerate() {
            for (t0, t1, curve) in split_piece(piece, &mut splits[i], snap)? {
                let tm = 0.5 * (t0 + t1);
                let mid = curve.point_at(0.5);
                let along = curve.derivatives(0.5).first;
                let mut places = Vec::with_capacity(count);
                for (j, c) in classifiers.iter().enumerate() {
                    if j == *domain {
                        places.push(Place::Inside);
                        continue;
                    }
                    let on = overlaps[i]
                        .iter()
                        .find(|o| o.2 == j && o.0 <= tm && tm <= o.1)
                        .map(|o| Place::On(o.3));
                    places.push(match (on, c) {
                        (Some(p), _) => p,
                        (None, None) => Place::Outside,
                        (None, Some((c, near, d))) => place(c, near, d, mid, along, tol),
                    });
                }
                arcs.push(SubArc {
                    domain: *domain,
                    curve,
                    places,
                });
            }
        }
        Ok(Self { arcs, count, snap })
    }

    /// Every material's region (see [`material_domains`]).
    fn regions(&self) -> Result<Vec<Option<Domain>>, CoverageError> {
        (0..self.count).map(|k| self.region(k)).collect()
    }

    /// Material `k`'s region: its kept sub-arcs chained into loops.
    fn region(&self, k: usize) -> Result<Option<Domain>, CoverageError> {
        let mut kept = Vec::new();
        for a in self.arcs.iter().filter(|a| a.domain >= k) {
            // A coincident copy on a lower candidate domain stands for this one.
            if (k..a.domain).any(|j| matches!(a.places[j], Place::On(_))) {
                continue;
            }
            let holds = |j: usize| {
                if j == a.domain {
                    (true, false)
                } else {
                    a.places[j].sides()
                }
            };
            let region = |side: fn((bool, bool)) -> bool| {
                side(holds(k)) && !(k + 1..self.count).any(|m| side(holds(m)))
            };
            let (left, right) = (region(|s| s.0), region(|s| s.1));
            if left && !right {
                kept.push(a.curve.clone());
            } else if right && !left {
                kept.push(a.curve.reversed());
            }
        }
        chain(kept, self.snap, k)
    }
}

/// The pairs of pieces of different domains whose control boxes (grown by `tol`) meet, by a
/// sweep along `x`.
fn meeting_pairs(
    pieces: &[(usize, RationalBezier, BoundingBox)],
    tol: f64,
) -> Result<Vec<(usize, usize)>, CoverageError> {
    let mut order: Vec<usize> = (0..pieces.len()).collect();
    order.sort_by(|&a, &b| pieces[a].2.min.x.total_cmp(&pieces[b].2.min.x));
    let mut active: Vec<usize> = Vec::new();
    let mut pairs = Vec::new();
    for &i in &order {
        let bi = pieces[i].2.grown_by(tol);
        active.retain(|&j| pieces[j].2.max.x >= bi.min.x);
        for &j in &active {
            if pieces[j].0 != pieces[i].0 && bi.overlaps(&pieces[j].2) {
                if pairs.len() == MAX_PIECE_PAIRS {
                    return Err(CoverageError::TooManyPiecePairs {
                        pairs: MAX_PIECE_PAIRS + 1,
                        limit: MAX_PIECE_PAIRS,
                    });
                }
                pairs.push((i.min(j), i.max(j)));
            }
        }
        active.push(i);
    }
    Ok(pairs)
}

/// The piece cut at its split points (those not within `snap` of its ends or of the split
/// before): `(t0, t1, sub-arc)` with the split points as the sub-arcs' exact ends.
fn split_piece(
    piece: &RationalBezier,
    splits: &mut [(f64, Point)],
    snap: f64,
) -> Result<Vec<(f64, f64, RationalBezier)>, CoverageError> {
    splits.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (start, end) = (piece.start_point(), piece.end_point());
    let mut cuts: Vec<(f64, Point)> = vec![(0.0, start)];
    for &(t, p) in splits.iter() {
        let last = cuts[cuts.len() - 1];
        if t <= last.0
            || t >= 1.0
            || p.distance(last.1) <= snap
            || p.distance(end) <= snap
            || !p.is_finite()
        {
            continue;
        }
        cuts.push((t, p));
    }
    cuts.push((1.0, end));
    let mut out = Vec::with_capacity(cuts.len() - 1);
    for w in cuts.windows(2) {
        let ((t0, a), (t1, b)) = (w[0], w[1]);
        let part = if t0 == 0.0 && t1 == 1.0 {
            piece.clone()
        } else {
            piece.subsegment((t0, t1))?
        };
        out.push((t0, t1, with_ends(&part, a, b)?));
    }
    Ok(out)
}

/// `c` with its first and last control points moved to `a` and `b`.
fn with_ends(c: &RationalBezier, a: Point, b: Point) -> Result<RationalBezier, CoverageError> {
    let mut points = c.control_points().to_vec();
    let n = points.len() - 1;
    points[0] = a;
    points[n] = b;
    Ok(RationalBezier::new(points, c.weights().to_vec())?)
}

/// Where `mid` (a sub-arc's midpoint, running along `along`) lies with respect to domain `d`
/// (filled set on the left of its curves): the classifier's answer, or in its boundary band
/// the side of the nearest boundary point's tangent; on the boundary (within `tol`), the
/// way the boundary runs there.
fn place(
    c: &Classifier,
    near: &NearestBoundary,
    d: &Domain,
    mid: Point,
    along: Point,
    tol: f64,
) -> Place {
    match c.locate(mid) {
        Location::Inside => Place::Inside,
        Location::Outside => Place::Outside,
        Location::Boundary => {
            let n = near.nearest(mid);
            let (p, tangent) = d.curves()[n.curve].point_and_tangent(n.u);
            let side = tangent.cross(mid - p);
            if n.distance > tol && side != 0.0 {
                if side > 0.0 {
                    Place::Inside
                } else {
                    Place::Outside
                }
            } else {
                Place::On(tangent.dot(along) > 0.0)
            }
        }
    }
}

/// The direction from `v` to the first of `points` off it, as a unit vector (the tangent of a
/// rational Bezier curve at that end).
fn direction_from(v: Point, points: impl Iterator<Item = Point>) -> Point {
    points
        .map(|q| q - v)
        .find_map(|d| {
            let len = d.length();
            (len > 0.0 && len.is_finite()).then(|| d / len)
        })
        .unwrap_or(Point::new(0.0, 0.0))
}

/// Chains `arcs` into closed loops: ends within `snap` are one vertex (the first end seen
/// there, which every arc ending there then takes exactly); at a vertex the walk leaves by the
/// arc that turns left the most. [`CoverageError::Unchained`] as material `material`'s
/// ([`CoverageError::Material`]) when some vertex has more arcs in than out.
fn chain(
    arcs: Vec<RationalBezier>,
    snap: f64,
    material: usize,
) -> Result<Option<Domain>, CoverageError> {
    let unchained = || CoverageError::in_material(material, CoverageError::Unchained);
    let cell = 2.0 * snap.max(f64::MIN_POSITIVE);
    let mut grid: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
    let mut vertices: Vec<Point> = Vec::new();
    let mut vertex = |p: Point| -> usize {
        let (cx, cy) = ((p.x / cell).floor() as i64, (p.y / cell).floor() as i64);
        for dx in -1..=1 {
            for dy in -1..=1 {
                if let Some(list) = grid.get(&(cx + dx, cy + dy)) {
                    for &v in list {
                        if vertices[v].distance(p) <= snap {
                            return v;
                        }
                    }
                }
            }
        }
        vertices.push(p);
        grid.entry((cx, cy)).or_default().push(vertices.len() - 1);
        vertices.len() - 1
    };
    let mut ends: Vec<(usize, usize)> = Vec::new();
    let mut kept: Vec<RationalBezier> = Vec::new();
    for a in arcs {
        let (s, e) = (vertex(a.start_point()), vertex(a.end_point()));
        if s == e && a.control_bounding_box().diagonal() <= 4.0 * snap {
            continue;
        }
        ends.push((s, e));
        kept.push(a);
    }
    let mut out: Vec<Vec<usize>> = vec![Vec::new(); vertices.len()];
    let mut into = vec![0usize; vertices.len()];
    for (i, &(s, e)) in ends.iter().enumerate() {
        out[s].push(i);
        into[e] += 1;
    }
    if out.iter().zip(&into).any(|(o, &n)| o.len() != n) {
        return Err(unchained());
    }
    let mut used = vec![false; kept.len()];
    let mut curves: Vec<NurbsCurve> = Vec::new();
    for first in 0..kept.len() {
        if used[first] {
            continue;
        }
        used[first] = true;
        let mut path = vec![first];
        let mut at = first;
        while ends[at].1 != ends[first].0 {
            let v = ends[at].1;
            let c = &kept[at];
            let back = direction_from(c.end_point(), c.control_points().iter().rev().copied());
            let turn = |i: usize| {
                let d = direction_from(
                    kept[i].start_point(),
                    kept[i].control_points().iter().copied(),
                );
                let a = (-back.cross(d)).atan2(back.dot(d));
                if a <= 0.0 {
                    a + std::f64::consts::TAU
                } else {
                    a
                }
            };
            let next = out[v]
                .iter()
                .copied()
                .filter(|&i| !used[i])
                .min_by(|&a, &b| turn(a).total_cmp(&turn(b)))
                .ok_or_else(unchained)?;
            used[next] = true;
            path.push(next);
            at = next;
        }
        for &i in &path {
            let (s, e) = ends[i];
            let c = with_ends(&kept[i], vertices[s], vertices[e])?;
            curves.push(NurbsCurve::bezier(
                c.control_points().to_vec(),
                Some(c.weights().to_vec()),
            )?);
        }
    }
    if curves.is_empty() {
        return Ok(None);
    }
    Ok(Some(Domain::new(curves)?))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::{circle, polyline};

    fn square(x0: f64, y0: f64, s: f64) -> Domain {
        let p = Point::new;
        Domain::new(vec![
            polyline(&[
                p(x0, y0),
                p(x0 + s, y0),
                p(x0 + s, y0 + s),
                p(x0, y0 + s),
                p(x0, y0),
            ])
            .unwrap(),
        ])
        .unwrap()
    }

    fn areas(regions: &[Option<Domain>]) -> Vec<f64> {
        regions
            .iter()
            .map(|r| {
                r.as_ref()
                    .map_or(0.0, |d| rs_contain::even_odd_area(d).unwrap())
            })
            .collect()
    }

    #[test]
    fn squares_sharing_an_edge_and_overlapping() {
        let (a, b) = (square(0.0, 0.0, 1.0), square(1.0, 0.0, 1.0));
        let r =
            material_domains(&[(&a, FillRule::EvenOdd), (&b, FillRule::EvenOdd)], true).unwrap();
        let got = areas(&r);
        assert!(
            (got[0] - 1.0).abs() < 1e-15 && (got[1] - 1.0).abs() < 1e-15,
            "{got:?}"
        );
        let c = square(0.5, 0.5, 1.0);
        let r =
            material_domains(&[(&a, FillRule::EvenOdd), (&c, FillRule::EvenOdd)], true).unwrap();
        let got = areas(&r);
        assert!(
            (got[0] - 0.75).abs() < 1e-15 && (got[1] - 1.0).abs() < 1e-15,
            "{got:?}"
        );
    }

    #[test]
    fn an_identical_copy_replaces_everything() {
        let a = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
        let r =
            material_domains(&[(&a, FillRule::EvenOdd), (&a, FillRule::EvenOdd)], true).unwrap();
        assert!(r[0].is_none());
        assert!((areas(&r)[1] - std::f64::consts::PI).abs() < 1e-14);
        // Reversed copy too.
        let b = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap().reversed()]).unwrap();
        let r =
            material_domains(&[(&a, FillRule::EvenOdd), (&b, FillRule::EvenOdd)], true).unwrap();
        assert!(r[0].is_none());
    }

    #[test]
    fn without_replacement_the_inputs_come_back() {
        let a = square(0.0, 0.0, 1.0);
        let r =
            material_domains(&[(&a, FillRule::EvenOdd), (&a, FillRule::EvenOdd)], false).unwrap();
        assert!(areas(&r).iter().all(|a| (a - 1.0).abs() < 1e-15));
        assert_eq!(r[0].as_ref().unwrap().curves(), a.curves());
    }
}
