//! A face's loops in its surface's `(u, v)`: bounds -> edge loops -> oriented edges -> the
//! edges' pcurves on the face's surface (or, on a plane, the 3-D curves mapped into it),
//! trimmed to the edge, oriented, and chained.
//!
//! Orientation: an edge runs from its start vertex to its end vertex; its curve runs the
//! other way when the `EDGE_CURVE`'s `same_sense` is `.F.`; the `ORIENTED_EDGE` reverses it
//! again when its orientation is `.F.`; a `FACE_BOUND` with orientation `.F.` reverses the
//! whole loop. The three compose.
//!
//! Chaining: each curve must start where the previous one ends, within the gap tolerance.
//! A seam edge (two pcurves on the surface) used twice in a loop takes one pcurve per use:
//! the first use the pcurve that continues the loop, the second the other one. Where a
//! curve misses by a whole period of a closed surface it is translated by that period (the
//! first curve of the loop stays where it is), as `OpenCASCADE`'s wires are made continuous in
//! `(u, v)`. Where both ends lie on one pole line (sphere poles, cone apex: STEP has no
//! degenerate edges there, `OpenCASCADE` adds them) a straight segment along the pole line
//! joins them.

use rs_spline::prelude::*;
use rs_spline::{Affine, NurbsCurve, Point};

use super::curves::{Curve, PlaneMap};
use super::geom::{self, dist};
use super::graph::{Graph, Instance};
use super::surface::Surface;

/// The most edges in one loop and bounds in one face (each costs at least a few bytes of
/// file, so real files stay far below).
const MAX_EDGES: usize = 1 << 20;

/// What the edges of one face need.
pub(crate) struct FaceContext<'a> {
    pub(crate) g: &'a Graph,
    pub(crate) surface: &'a Surface,
    /// Radians per angle unit of the file.
    pub(crate) radians: f64,
    /// The largest gap accepted between consecutive curves in `(u, v)`.
    pub(crate) gap: f64,
}

/// One use of an edge in a loop: the edge's label and its candidates (two for a seam), each
/// the edge's curves in order (two when a closed pcurve wraps around its domain's end).
struct EdgeUse {
    label: u64,
    options: Vec<Piece>,
}

/// The curves of one candidate, in order, never empty.
type Piece = Vec<NurbsCurve>;

fn start_of(p: &Piece) -> Point {
    p.first()
        .map_or(Point::new(f64::NAN, f64::NAN), ParamCurve::start_point)
}

fn end_of(p: &Piece) -> Point {
    p.last()
        .map_or(Point::new(f64::NAN, f64::NAN), ParamCurve::end_point)
}

fn translated(p: &Piece, shift: Point) -> Result<Piece, String> {
    p.iter()
        .map(|c| {
            Affine::translate(shift.x, shift.y)
                .apply_to_curve(c)
                .map_err(|e| e.to_string())
        })
        .collect()
}

/// The loops of a face (`ADVANCED_FACE` or `FACE_SURFACE`), the outer bound first.
pub(crate) fn face_loops(
    cx: &FaceContext<'_>,
    face: &Instance,
) -> Result<Vec<Vec<NurbsCurve>>, String> {
    let what = face.what();
    let a = face.simple()?;
    let bounds = a.refs(1, "bounds")?;
    let mut ordered = Vec::new();
    let mut inner = Vec::new();
    for b in bounds {
        let bi = cx.g.get(b, &what)?;
        if bi.is("FACE_OUTER_BOUND") {
            ordered.push(bi);
        } else {
            inner.push(bi);
        }
    }
    ordered.extend(inner);
    let mut loops = Vec::new();
    for bi in ordered {
        let ba = bi.simple()?;
        if !(bi.is("FACE_BOUND") || bi.is("FACE_OUTER_BOUND")) {
            return Err(format!("{what}: bound {} is not a FACE_BOUND", bi.what()));
        }
        let li = cx.g.get(ba.reference(1, "bound")?, &bi.what())?;
        let forward = ba.boolean(2, "orientation")?;
        if li.is("VERTEX_LOOP") {
            // A loop of one vertex (a cone's apex) bounds nothing in (u, v).
            continue;
        }
        if !li.is("EDGE_LOOP") {
            return Err(format!("{}: loop type not supported", li.what()));
        }
        let mut curves = edge_loop(cx, li)?;
        curves = to_base_period(cx.surface, curves)?;
        if !forward {
            curves.reverse();
            curves = curves.iter().map(ParamCurve::reversed).collect();
        }
        loops.push(curves);
    }
    if loops.is_empty() {
        return Err(format!("{what}: no edge loops"));
    }
    Ok(loops)
}

fn edge_loop(cx: &FaceContext<'_>, li: &Instance) -> Result<Vec<NurbsCurve>, String> {
    let what = li.what();
    let edges = li.simple()?.refs(1, "edge_list")?;
    if edges.is_empty() || edges.len() > MAX_EDGES {
        return Err(format!("{what}: {} edges", edges.len()));
    }
    let uses = edges
        .iter()
        .map(|&e| edge_use(cx, e, &what))
        .collect::<Result<Vec<_>, _>>()?;
    // Try each candidate of the first edge; keep the first chain that closes.
    let mut last_err = String::new();
    for first in 0..uses[0].options.len() {
        match chain(cx, &uses, first) {
            Ok(c) => return Ok(c),
            Err(e) => last_err = e,
        }
    }
    Err(format!("{what}: {last_err}"))
}

/// Chains the uses starting with option `first` of the first one.
fn chain(cx: &FaceContext<'_>, uses: &[EdgeUse], first: usize) -> Result<Vec<NurbsCurve>, String> {
    let mut out: Vec<NurbsCurve> = Vec::with_capacity(uses.len() + 2);
    // Edge -> the candidate its first use in this loop took.
    let mut taken: std::collections::HashMap<u64, usize> = std::collections::HashMap::new();
    let c0 = uses[0].options[first].clone();
    taken.insert(uses[0].label, first);
    let start = start_of(&c0);
    let mut end = end_of(&c0);
    out.extend(c0);
    for u in &uses[1..] {
        // A seam's second use takes the pcurve its first use did not.
        let before = taken.get(&u.label).copied();
        let allowed: Vec<usize> = (0..u.options.len())
            .filter(|&k| u.options.len() < 2 || before != Some(k))
            .collect();
        let (k, pre, c) = join(cx, end, u, &allowed)?;
        taken.entry(u.label).or_insert(k);
        out.extend(pre);
        end = end_of(&c);
        out.extend(c);
    }
    // Closure, with a pole segment if needed (no shift: the first curve stays).
    let gap = end.distance(start);
    if gap > cx.gap {
        if let Some(seg) = pole_segment(cx, end, start) {
            out.push(seg);
        } else {
            return Err(format!(
                "the loop does not close in (u, v): gap {gap:.3e} from ({:.6}, {:.6}) to ({:.6}, {:.6})",
                end.x, end.y, start.x, start.y
            ));
        }
    }
    Ok(out)
}

/// The option of `u` that continues from `end` (directly, through a pole segment, or
/// translated by periods), with the segment to insert before it.
fn join(
    cx: &FaceContext<'_>,
    end: Point,
    u: &EdgeUse,
    allowed: &[usize],
) -> Result<(usize, Option<NurbsCurve>, Piece), String> {
    let mut best = (f64::INFINITY, 0usize);
    for &k in allowed {
        let d = start_of(&u.options[k]).distance(end);
        if d < best.0 {
            best = (d, k);
        }
    }
    if best.0 <= cx.gap {
        return Ok((best.1, None, u.options[best.1].clone()));
    }
    for &k in allowed {
        if let Some(seg) = pole_segment(cx, end, start_of(&u.options[k])) {
            return Ok((k, Some(seg), u.options[k].clone()));
        }
    }
    let [pu, pv] = cx.surface.period;
    let (pu, pv) = (pu.unwrap_or(0.0), pv.unwrap_or(0.0));
    let mut best_shift = (f64::INFINITY, 0usize, Point::new(0.0, 0.0));
    for &k in allowed {
        let s = start_of(&u.options[k]);
        for i in -2i32..=2 {
            for j in -2i32..=2 {
                let shift = Point::new(f64::from(i) * pu, f64::from(j) * pv);
                let d = (s + shift).distance(end);
                if d < best_shift.0 {
                    best_shift = (d, k, shift);
                }
            }
        }
    }
    let (d, k, shift) = best_shift;
    if d <= cx.gap {
        return Ok((k, None, translated(&u.options[k], shift)?));
    }
    Err(format!(
        "edge #{} does not meet the previous edge in (u, v): gap {:.3e} at ({:.6}, {:.6})",
        u.label, best.0, end.x, end.y
    ))
}

/// A segment from `a` to `b` when both lie on one pole line `v = const` of the surface.
fn pole_segment(cx: &FaceContext<'_>, a: Point, b: Point) -> Option<NurbsCurve> {
    let on_pole = cx.surface.is_pole_join([a.x, a.y], [b.x, b.y], cx.gap);
    if on_pole && a.distance(b) > cx.gap {
        rs_spline::segment(a, b).ok()
    } else {
        None
    }
}

/// The loop moved by whole periods so that the middle of its box lies in the base period.
fn to_base_period(s: &Surface, curves: Vec<NurbsCurve>) -> Result<Vec<NurbsCurve>, String> {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for c in &curves {
        for p in c.control_points() {
            lo = [lo[0].min(p.x), lo[1].min(p.y)];
            hi = [hi[0].max(p.x), hi[1].max(p.y)];
        }
    }
    let mut shift = [0.0; 2];
    for d in 0..2 {
        if let Some(p) = s.period[d] {
            let mid = 0.5 * (lo[d] + hi[d]);
            let k = ((mid - s.base[d]) / p).floor();
            if k.is_finite() && k.abs() < 1e6 {
                shift[d] = -k * p;
            }
        }
    }
    if shift == [0.0; 2] {
        return Ok(curves);
    }
    translated(&curves, Point::new(shift[0], shift[1]))
}

/// The candidate curves of one oriented edge.
fn edge_use(cx: &FaceContext<'_>, label: u64, from: &str) -> Result<EdgeUse, String> {
    let oe = cx.g.get(label, from)?;
    let (ec, oriented) = if oe.is("ORIENTED_EDGE") {
        let a = oe.simple()?;
        let e = cx.g.get(a.reference(3, "edge_element")?, &oe.what())?;
        (e, a.boolean(4, "orientation")?)
    } else {
        (oe, true)
    };
    if !ec.is("EDGE_CURVE") {
        return Err(format!(
            "{}: edge {} is not an EDGE_CURVE",
            oe.what(),
            ec.what()
        ));
    }
    let what = ec.what();
    let a = ec.simple()?;
    let (s_label, e_label) = (a.reference(1, "edge_start")?, a.reference(2, "edge_end")?);
    let vertex = |l: u64| -> Result<geom::V3, String> {
        let v = cx.g.get(l, &what)?;
        geom::point(
            cx.g,
            v.record("VERTEX_POINT")?.reference(1, "vertex_geometry")?,
            &v.what(),
        )
    };
    let (vs, ve) = (vertex(s_label)?, vertex(e_label)?);
    let same_sense = a.boolean(4, "same_sense")?;
    let gi = cx.g.get(a.reference(3, "edge_geometry")?, &what)?;
    // The 3-D curve and the pcurves on this face's surface.
    let (c3_label, pcurves) = if gi.is("SURFACE_CURVE")
        || gi.is("SEAM_CURVE")
        || gi.is("INTERSECTION_CURVE")
    {
        let ga = gi.simple()?;
        let mut pcs = Vec::new();
        for r in ga.refs(2, "associated_geometry")? {
            let pi = cx.g.get(r, &gi.what())?;
            if pi.is("PCURVE") && pi.simple()?.reference(1, "basis_surface")? == cx.surface.label {
                pcs.push(pi);
            }
        }
        (ga.reference(1, "curve_3d")?, pcs)
    } else {
        (gi.label, Vec::new())
    };
    let c3 = Curve::read(cx.g, c3_label, &gi.what(), cx.radians)?;
    let closed = s_label == e_label || dist(vs, ve) == 0.0;
    let (lo, hi) =
        edge_range(&c3, vs, ve, same_sense, closed).map_err(|m| format!("{what}: {m}"))?;
    let mut options = Vec::new();
    if pcurves.is_empty() {
        let Some(frame) = cx.surface.plane else {
            return Err(format!(
                "edge #{} has no pcurve on its {} #{}; only planar faces are mapped from their 3-D edges",
                ec.label, cx.surface.name, cx.surface.label
            ));
        };
        let map = PlaneMap {
            origin: frame.origin,
            ex: frame.x,
            ey: frame.y,
        };
        super::plane::check_in_plane(&c3, lo, hi, &frame, cx.gap)
            .map_err(|m| format!("{what}: {m}"))?;
        let mut option = Vec::new();
        for (a3, b3) in pieces(&c3, lo, hi, c3.period()) {
            option.push(
                c3.to_nurbs(a3, b3, &map)
                    .map_err(|m| format!("{what}: {m}"))?,
            );
        }
        options.push(option);
    } else {
        for pi in pcurves.into_iter().take(2) {
            let pw = pi.what();
            let dr =
                cx.g.get(pi.simple()?.reference(2, "reference_to_curve")?, &pw)?;
            let items = dr.record("DEFINITIONAL_REPRESENTATION")?.refs(1, "items")?;
            let c2_label = *items
                .first()
                .ok_or_else(|| format!("{}: no items", dr.what()))?;
            let c2 = Curve::read(cx.g, c2_label, &dr.what(), cx.radians)?;
            // The pcurve is cut where it passes the vertices' (u, v): its parametrisation
            // need not be the 3-D curve's (`OpenCASCADE` writes circles in (u, v) as
            // rational B-splines, not parametrised by angle, and 3-D circles as rational
            // B-splines under angle-parametrised pcurves). On a plane the (u, v) are exact;
            // elsewhere the 3-D parameters give the start of `invert`'s search.
            let (range, period) = match cx.surface.plane {
                Some(f) => {
                    let uv = |p: geom::V3| {
                        let d = geom::sub(p, f.origin);
                        [geom::dot(d, f.x), geom::dot(d, f.y), 0.0]
                    };
                    let r = edge_range(&c2, uv(vs), uv(ve), same_sense, closed)
                        .map_err(|m| format!("{pw} on {what}: {m}"))?;
                    (r, c2.period())
                }
                None => ((lo, hi), c3.period()),
            };
            let mut cuts = pieces(&c2, range.0, range.1, period);
            if cx.surface.plane.is_none() {
                let (x_lo, x_hi) = if same_sense { (vs, ve) } else { (ve, vs) };
                cuts = super::invert::cut_at_vertices(cx.surface, &c2, cuts, x_lo, x_hi, cx.gap);
            } else {
                cuts = super::invert::clamped(&c2, cuts);
            }
            let mut option = Vec::new();
            for (a2, b2) in cuts {
                option.extend(
                    c2.to_nurbs_extended(a2, b2, &PlaneMap::XY)
                        .map_err(|m| format!("{pw} on {what}: {m}"))?,
                );
            }
            options.push(option);
        }
    }
    let flip = !same_sense ^ !oriented;
    if flip {
        for o in &mut options {
            o.reverse();
            for c in o.iter_mut() {
                *c = c.reversed();
            }
        }
    }
    Ok(EdgeUse {
        label: ec.label,
        options,
    })
}

/// The pieces of the pcurve's parameter domain that `[lo, hi]` covers. Lines and conics
/// take it as it is. A bounded pcurve (a B-spline) of an edge on a periodic 3-D curve takes
/// it translated by whole periods into its domain; when the pcurve spans a whole period
/// (a closed curve written as a B-spline) an interval across the end of its domain wraps
/// around: two pieces, `[lo, b]` then `[a, hi - p]`.
fn pieces(c2: &Curve, lo: f64, hi: f64, period: Option<f64>) -> Vec<(f64, f64)> {
    let (Some((a, b)), Some(p)) = (c2.range(), period) else {
        return vec![(lo, hi)];
    };
    let eps = 1e-9 * p;
    if lo >= a - eps && hi <= b + eps {
        return vec![(lo, hi)];
    }
    let full = (b - a - p).abs() <= eps;
    let k = ((lo - a) / p).floor();
    if !k.is_finite() || k.abs() > 1e6 {
        return vec![(lo, hi)];
    }
    let (l2, h2) = (lo - k * p, hi - k * p);
    if h2 <= b + eps {
        return vec![(l2, h2)];
    }
    if full {
        let mut out = Vec::new();
        if b - l2 > eps {
            out.push((l2, b));
        }
        if h2 - p - a > eps {
            out.push((a, h2 - p));
        }
        if !out.is_empty() {
            return out;
        }
    }
    // A partial pcurve: the translation that overlaps its domain most.
    let k2 = ((a - lo) / p).round();
    vec![(lo + k2 * p, hi + k2 * p)]
}

/// The increasing parameter interval of the 3-D curve between the edge's vertices.
fn edge_range(
    c3: &Curve,
    vs: geom::V3,
    ve: geom::V3,
    same_sense: bool,
    closed: bool,
) -> Result<(f64, f64), String> {
    let (ts, te) = (c3.invert(vs)?, c3.invert(ve)?);
    let (lo, mut hi) = if same_sense { (ts, te) } else { (te, ts) };
    if let Some(p) = c3.period() {
        // Bring hi into (lo, lo + p]; a closed edge is the whole period.
        let eps = 1e-12 * p;
        let d = (hi - lo).rem_euclid(p);
        hi = if closed || d <= eps { lo + p } else { lo + d };
        return Ok((lo, hi));
    }
    if closed && let Some((a, b)) = c3.range() {
        return Ok((a, b));
    }
    if hi.is_nan() || hi <= lo {
        return Err(format!(
            "the vertices are at parameters {ts} and {te} of the curve, the wrong way round for same_sense {same_sense}"
        ));
    }
    Ok((lo, hi))
}
