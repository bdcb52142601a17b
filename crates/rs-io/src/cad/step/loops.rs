//! A face's loops in its surface's `(u, v)`: bounds -> edge loops -> oriented edges -> the
//! edges' pcurves on the face's surface (without one: on a plane, the 3-D curve mapped into
//! it; elsewhere, one computed from the 3-D curve by `rs_geom::pcurve`), trimmed to the edge,
//! oriented, and chained; with the 3-D edges of each loop.
//!
//! Orientation: an edge runs from its start vertex to its end vertex; its curve runs the
//! other way when the `EDGE_CURVE`'s `same_sense` is `.F.`; the `ORIENTED_EDGE` reverses it
//! again when its orientation is `.F.`; a `FACE_BOUND` with orientation `.F.` reverses the
//! whole loop. The three compose.
//!
//! Chaining: each curve must start where the previous one ends, within the model's
//! [`Tolerance::chain_gap`]. A seam edge (two pcurves on the surface) used twice in a loop
//! takes one pcurve per use: the first use the pcurve that continues the loop, the second the
//! other one. Where both ends lie on one pole line (sphere poles, a cone's apex: STEP has no
//! degenerate edges there, `OpenCASCADE` adds them) a straight segment along the pole line
//! joins them. Where a curve misses by a whole period of a closed surface it is translated by
//! that period (the first curve of the loop stays where it is), as `OpenCASCADE`'s wires are
//! made continuous in `(u, v)`. Where two edges that share a vertex leave a larger gap, and
//! their 3-D curves' own misses of that vertex explain it (a file's line ending off its
//! vertex: `OpenCASCADE`'s vertex tolerance covers it), a segment bridges the gap.
//!
//! Cutting: edges are trimmed between their vertices on the 3-D curve (the vertices'
//! parameters by [`Curve::closest_parameter`]); each pcurve is cut where it passes the
//! vertices' `(u, v)`, since the 3-D curve and the pcurve need not share their parameter (a
//! rational B-spline circle in 3-D, a line in `(u, v)`): on a plane the `(u, v)` is exact;
//! elsewhere the surface is inverted at the vertex ([`ParamSurface::invert`]) near the
//! pcurve's point at the 3-D parameter, and the pcurve's parameter of that `(u, v)` found
//! ([`Curve::closest_parameter`], of the periodic copies of an angle the one nearest; a
//! B-spline pcurve that stops a little short of its vertex is continued by its end span). A
//! step that does not land within the chain gap leaves the 3-D parameter (the loop's closure
//! check then decides).

use std::collections::HashMap;
use std::f64::consts::TAU;

use rs_geom::brep::Edge;
use rs_geom::pcurve::{PcurveKind, PcurveOptions, pcurve};
use rs_geom::surface::ParamSurface;
use rs_geom::{
    AffineMap, Conic, ConicKind, Curve, DEFAULT_MODEL_TOLERANCE, Point, Point3, Tolerance,
};
use rs_spline::NurbsCurve;
use rs_spline::prelude::*;

use super::error::{Result, StepError};
use super::geometry::{self, Space};
use super::graph::{Graph, Instance};
use super::surface::FaceSurface;

/// The most edges in one loop and bounds in one face (each costs at least a few bytes of
/// file, so real files stay far below).
const MAX_EDGES: usize = 1 << 20;

/// Samples of a curve other than a B-spline checked against a plane (conics are planar, so a
/// few points that are in the plane put the whole conic there; a B-spline's control points
/// are checked all).
const PLANE_SAMPLES: usize = 16;

/// Whole periods tried, each way in each parameter, when a curve misses the loop's end by a
/// period of a closed surface.
const MAX_PERIOD_SHIFTS: i32 = 2;

/// A loop is moved into the base period by at most this many periods (a loop farther away is
/// left where it is: its numbers are not a loop near the surface's box).
const MAX_PERIODS_MOVED: f64 = 1e6;

/// Two vertex parameters of a closed curve closer than this fraction of its period are one
/// (the edge is the whole period), as vertices found by rounding meet.
const WRAP_RELATIVE: f64 = 1e-12;

/// Where the pcurve's point at the 3-D parameter is already on the vertex (to this fraction
/// of the vertex's distance from the origin, at least 1) the cut stays there: the curves
/// meeting at the vertex keep the ends they had, bit for bit, rather than ends found by
/// searches from different starts (a sliver face's two sides would then differ by rounding
/// and enclose a spurious area).
const VERTEX_ON_PCURVE_RELATIVE: f64 = 1e-9;

/// How far a B-spline pcurve may be continued past its domain to reach its vertex, relative
/// to the domain's length (the vertex must still be within the chain gap of it).
const EXTEND: f64 = 1e-2;

/// A pcurve parameter within this fraction of the domain's length of a domain end is that
/// end (no sliver of continuation).
const DOMAIN_END_RELATIVE: f64 = 1e-9;

/// Two passes of a B-spline pcurve by a vertex's `(u, v)` whose distances from it differ by
/// less than this fraction of the coordinates (at least 1) are equally near: rounding.
const PASS_TIE_RELATIVE: f64 = 1e-12;

/// The deepest chain of trimmed curves looked through for a pcurve parameter (trim chains are
/// bounded when read; this bounds the recursion whatever the curve).
const MAX_TRIM_DEPTH: usize = 8;

/// What the edges of one face need.
pub(crate) struct FaceContext<'a> {
    pub(crate) g: &'a Graph,
    pub(crate) surface: &'a FaceSurface,
    /// Radians per angle unit of the file.
    pub(crate) radians: f64,
    /// The model's tolerance policy.
    pub(crate) tolerance: Tolerance,
}

impl FaceContext<'_> {
    /// The largest gap accepted between consecutive curves in `(u, v)`.
    fn gap(&self) -> f64 {
        self.tolerance.chain_gap()
    }
}

/// A face's loops in `(u, v)` and its 3-D edges, loop by loop.
#[derive(Clone, Debug, Default)]
pub(crate) struct FaceLoops {
    /// The loops, the outer bound first.
    pub(crate) loops: Vec<Vec<NurbsCurve>>,
    /// The 3-D edges of each loop, in loop order.
    pub(crate) edges: Vec<Vec<Edge>>,
    /// Whether the loops are the surface's natural box (no edge loop in the file).
    pub(crate) natural: bool,
    /// The largest bound of the pcurves fitted to edges the file gives in model space only.
    pub(crate) pcurve_deviation: Option<f64>,
}

/// One use of an edge in a loop: the edge's label, its candidates (two for a seam), each
/// the edge's curves in order (two when a closed pcurve wraps around its domain's end), and
/// the 3-D edge.
struct EdgeUse {
    label: u64,
    options: Vec<Piece>,
    /// The use's start and end vertices (in the use's direction), each with how far the 3-D
    /// curve's end misses it.
    ends: [VertexEnd; 2],
    /// The bound of a fitted pcurve (computed from the 3-D edge, not exact).
    fitted: Option<f64>,
    edge: Edge,
}

/// The curves of one candidate, in order, never empty.
type Piece = Vec<NurbsCurve>;

/// A vertex at an end of an edge use: its label and the distance from the edge's 3-D curve's
/// end to its point (0 where the file's curve ends on its vertex).
#[derive(Clone, Copy, Debug)]
struct VertexEnd {
    label: u64,
    miss: f64,
}

fn start_of(p: &Piece) -> Point {
    p.first()
        .map_or(Point::new(f64::NAN, f64::NAN), ParamCurve::start_point)
}

fn end_of(p: &Piece) -> Point {
    p.last()
        .map_or(Point::new(f64::NAN, f64::NAN), ParamCurve::end_point)
}

fn translated(p: &Piece, shift: Point, what: &str) -> Result<Piece> {
    p.iter()
        .map(|c| {
            rs_spline::Affine::translate(shift.x, shift.y)
                .apply_to_curve(c)
                .map_err(|e| StepError::geometry(what, e.into()))
        })
        .collect()
}

/// The loops of a face (`ADVANCED_FACE` or `FACE_SURFACE`), the outer bound first, with its
/// 3-D edges; a face bounded by nothing but vertex loops (or by nothing) takes its surface's
/// natural box.
pub(crate) fn face_loops(cx: &FaceContext<'_>, face: &Instance) -> Result<FaceLoops> {
    let what = face.what();
    let a = face.simple()?;
    let bounds = a.refs(1, "bounds")?;
    if bounds.len() > MAX_EDGES {
        return Err(StepError::TooMany {
            what: format!("{what} bounds"),
            limit: MAX_EDGES,
        });
    }
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
    let mut out = FaceLoops::default();
    for bi in ordered {
        let ba = bi.simple()?;
        if !(bi.is("FACE_BOUND") || bi.is("FACE_OUTER_BOUND")) {
            return Err(StepError::invalid(
                what,
                format!("bound {} is not a FACE_BOUND", bi.what()),
            ));
        }
        let li = cx.g.get(ba.reference(1, "bound")?, &bi.what())?;
        let forward = ba.boolean(2, "orientation")?;
        if li.is("VERTEX_LOOP") {
            // A loop of one vertex (a cone's apex, a whole sphere's pole) bounds nothing in
            // (u, v).
            continue;
        }
        if !li.is("EDGE_LOOP") {
            return Err(StepError::Unsupported {
                what: li.what(),
                role: "loop",
                name: li.type_name(),
            });
        }
        let (mut curves, mut edges, fitted) = edge_loop(cx, li)?;
        if let Some(d) = fitted {
            out.pcurve_deviation = Some(out.pcurve_deviation.map_or(d, |m: f64| m.max(d)));
        }
        curves = to_base_period(cx.surface, curves, &li.what())?;
        if !forward {
            curves.reverse();
            curves = curves.iter().map(ParamCurve::reversed).collect();
            edges.reverse();
            for e in &mut edges {
                e.reversed = !e.reversed;
            }
        }
        out.loops.push(curves);
        out.edges.push(edges);
    }
    if out.loops.is_empty() {
        out.loops.push(natural_loop(cx, &what)?);
        out.edges.push(Vec::new());
        out.natural = true;
    }
    Ok(out)
}

/// The loop of a face written without edge loops (a whole sphere or torus): its surface's
/// natural box, as `OpenCASCADE`'s wire of seams and degenerate edges runs it: from
/// `(u0, v1)` down to `(u0, v0)`, along to `(u1, v0)`, up to `(u1, v1)` and back.
fn natural_loop(cx: &FaceContext<'_>, face: &str) -> Result<Vec<NurbsCurve>> {
    let s = cx.surface;
    let Some(b) = s.param_box() else {
        return Err(StepError::NoSurface {
            face: face.to_string(),
            reason: format!("{} #{} could not be read", s.name, s.label),
        });
    };
    let [lu, lv] = b.lengths();
    if !(lu.is_finite() && lv.is_finite() && lu > 0.0 && lv > 0.0) {
        return Err(StepError::UnboundedFace {
            face: face.to_string(),
            surface: s.name.clone(),
            label: s.label,
        });
    }
    let corners = [
        Point::new(b.u.0, b.v.1),
        Point::new(b.u.0, b.v.0),
        Point::new(b.u.1, b.v.0),
        Point::new(b.u.1, b.v.1),
    ];
    (0..4)
        .map(|k| {
            rs_spline::segment(corners[k], corners[(k + 1) % 4])
                .map_err(|e| StepError::geometry(face, e.into()))
        })
        .collect()
}

/// The loop's curves, its 3-D edges and the largest bound of its fitted pcurves.
fn edge_loop(
    cx: &FaceContext<'_>,
    li: &Instance,
) -> Result<(Vec<NurbsCurve>, Vec<Edge>, Option<f64>)> {
    let what = li.what();
    let edges = li.simple()?.refs(1, "edge_list")?;
    if edges.is_empty() || edges.len() > MAX_EDGES {
        return Err(StepError::invalid(what, format!("{} edges", edges.len())));
    }
    let uses = edges
        .iter()
        .map(|&e| edge_use(cx, e, &what))
        .collect::<Result<Vec<_>>>()?;
    // Try each candidate of the first edge; keep the first chain that closes.
    let mut last_err = None;
    for first in 0..uses[0].options.len() {
        match chain(cx, &uses, first, &what) {
            Ok(c) => {
                let fitted = uses.iter().filter_map(|u| u.fitted).reduce(f64::max);
                return Ok((c, uses.into_iter().map(|u| u.edge).collect(), fitted));
            }
            Err(e) => last_err = Some(e),
        }
    }
    Err(last_err.unwrap_or_else(|| StepError::invalid(what, "no pcurve to chain")))
}

/// Chains the uses starting with option `first` of the first one.
fn chain(
    cx: &FaceContext<'_>,
    uses: &[EdgeUse],
    first: usize,
    what: &str,
) -> Result<Vec<NurbsCurve>> {
    let mut out: Vec<NurbsCurve> = Vec::with_capacity(uses.len() + 2);
    // Edge -> the candidate its first use in this loop took.
    let mut taken: HashMap<u64, usize> = HashMap::new();
    let c0 = uses[0].options[first].clone();
    taken.insert(uses[0].label, first);
    let start = start_of(&c0);
    let mut end = end_of(&c0);
    let mut end_vertex = uses[0].ends[1];
    out.extend(c0);
    for u in &uses[1..] {
        // A seam's second use takes the pcurve its first use did not.
        let before = taken.get(&u.label).copied();
        let allowed: Vec<usize> = (0..u.options.len())
            .filter(|&k| u.options.len() < 2 || before != Some(k))
            .collect();
        let (k, pre, c) = join(cx, (end, end_vertex), u, &allowed, what)?;
        taken.entry(u.label).or_insert(k);
        out.extend(pre);
        end = end_of(&c);
        end_vertex = u.ends[1];
        out.extend(c);
    }
    // Closure, with a pole segment or a vertex bridge if needed (no shift: the first curve
    // stays).
    let gap = end.distance(start);
    if gap > cx.gap() {
        if let Some(seg) = pole_segment(cx, end, start)
            .or_else(|| vertex_bridge(cx, (end, end_vertex), (start, uses[0].ends[0])))
        {
            out.push(seg);
        } else {
            return Err(StepError::LoopOpen {
                edge_loop: what.to_string(),
                gap,
                from: [end.x, end.y],
                to: [start.x, start.y],
            });
        }
    }
    Ok(out)
}

/// The option of `u` that continues from `end` (directly, through a pole segment, translated
/// by periods, or across the gap its edges leave at their shared vertex), with the segment to
/// insert before it.
fn join(
    cx: &FaceContext<'_>,
    (end, end_vertex): (Point, VertexEnd),
    u: &EdgeUse,
    allowed: &[usize],
    what: &str,
) -> Result<(usize, Option<NurbsCurve>, Piece)> {
    let mut best = (f64::INFINITY, 0usize);
    for &k in allowed {
        let d = start_of(&u.options[k]).distance(end);
        if d < best.0 {
            best = (d, k);
        }
    }
    if best.0 <= cx.gap() {
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
        for i in -MAX_PERIOD_SHIFTS..=MAX_PERIOD_SHIFTS {
            for j in -MAX_PERIOD_SHIFTS..=MAX_PERIOD_SHIFTS {
                let shift = Point::new(f64::from(i) * pu, f64::from(j) * pv);
                let d = (s + shift).distance(end);
                if d < best_shift.0 {
                    best_shift = (d, k, shift);
                }
            }
        }
    }
    let (d, k, shift) = best_shift;
    if d <= cx.gap() {
        return Ok((k, None, translated(&u.options[k], shift, what)?));
    }
    let k = best.1;
    if let Some(seg) = vertex_bridge(cx, (end, end_vertex), (start_of(&u.options[k]), u.ends[0])) {
        return Ok((k, Some(seg), u.options[k].clone()));
    }
    Err(StepError::EdgeGap {
        edge_loop: what.to_string(),
        edge: u.label,
        gap: best.0,
        at: [end.x, end.y],
    })
}

/// A segment from `a` to `b` when the surface maps it to one point (a pole line).
fn pole_segment(cx: &FaceContext<'_>, a: Point, b: Point) -> Option<NurbsCurve> {
    let gap = cx.gap();
    if a.distance(b) > gap && cx.surface.is_pole_join(a, b, gap, cx.tolerance) {
        rs_spline::segment(a, b).ok()
    } else {
        None
    }
}

/// A segment from `a` to `b` across the gap two edges leave at the vertex they share, as
/// `OpenCASCADE`'s vertex tolerance covers it: where the edges' curves miss their common
/// vertex (a curve of the file ending off its vertex, the miss `m_a` and `m_b` of each), the
/// surface points of the two pcurve ends are at most `m_a + m_b` (and the model's coincidence
/// tolerance) apart. `None` for uses that do not share the vertex, ends farther apart, or a
/// face without a surface.
fn vertex_bridge(
    cx: &FaceContext<'_>,
    (a, va): (Point, VertexEnd),
    (b, vb): (Point, VertexEnd),
) -> Option<NurbsCurve> {
    let s = cx.surface.surface.as_ref()?;
    if va.label != vb.label {
        return None;
    }
    let (pa, pb) = (s.point([a.x, a.y]), s.point([b.x, b.y]));
    let size = pa.max_abs().max(pb.max_abs());
    let allowed = va.miss + vb.miss + cx.tolerance.coincidence(size);
    (pa.distance(pb) <= allowed && a.distance(b) > 0.0)
        .then(|| rs_spline::segment(a, b).ok())
        .flatten()
}

/// The loop moved by whole periods so that the middle of its box lies in the base period.
fn to_base_period(s: &FaceSurface, curves: Vec<NurbsCurve>, what: &str) -> Result<Vec<NurbsCurve>> {
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
            if k.is_finite() && k.abs() < MAX_PERIODS_MOVED {
                shift[d] = -k * p;
            }
        }
    }
    if shift == [0.0; 2] {
        return Ok(curves);
    }
    translated(&curves, Point::new(shift[0], shift[1]), what)
}

/// The point of a `VERTEX_POINT`.
fn vertex(g: &Graph, label: u64, from: &str) -> Result<Point3> {
    let v = g.get(label, from)?;
    geometry::point3(
        g,
        v.record("VERTEX_POINT")?.reference(1, "vertex_geometry")?,
        &v.what(),
    )
}

/// The candidate curves of one oriented edge, and its 3-D edge.
fn edge_use(cx: &FaceContext<'_>, label: u64, from: &str) -> Result<EdgeUse> {
    let oe = cx.g.get(label, from)?;
    let (ec, oriented) = if oe.is("ORIENTED_EDGE") {
        let a = oe.simple()?;
        let e = cx.g.get(a.reference(3, "edge_element")?, &oe.what())?;
        (e, a.boolean(4, "orientation")?)
    } else {
        (oe, true)
    };
    if !ec.is("EDGE_CURVE") {
        return Err(StepError::invalid(
            oe.what(),
            format!("edge {} is not an EDGE_CURVE", ec.what()),
        ));
    }
    let what = ec.what();
    let a = ec.simple()?;
    let (s_label, e_label) = (a.reference(1, "edge_start")?, a.reference(2, "edge_end")?);
    let (vs, ve) = (vertex(cx.g, s_label, &what)?, vertex(cx.g, e_label, &what)?);
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
    let c3: Curve<Point3> = geometry::curve(cx.g, c3_label, &gi.what(), cx.radians)?;
    let closed = s_label == e_label || vs.distance(ve) == 0.0;
    let (lo, hi) = edge_range(&c3, vs, ve, same_sense, closed, &what)?;
    let gap = cx.gap();
    let mut options = Vec::new();
    let mut fitted = None;
    if pcurves.is_empty() {
        let Some(surface) = &cx.surface.surface else {
            return Err(StepError::NoPcurve {
                edge: ec.label,
                surface: cx.surface.name.clone(),
                label: cx.surface.label,
            });
        };
        if let Some(map) = cx.surface.plane_coordinates() {
            // On a plane the edge's image in the plane's coordinates, exactly.
            check_in_plane(&c3, lo, hi, surface, gap, &what)?;
            let mut option = Vec::new();
            for (a3, b3) in c3.pieces_in_range(lo, hi, c3.window_period()) {
                option.push(planar(c3.to_bspline_mapped(&map, a3, b3), &what)?);
            }
            options.push(option);
        } else {
            let (option, deviation) = computed_pcurve(cx, surface, &c3, (lo, hi), ec.label)?;
            fitted = deviation;
            options.push(option);
        }
    } else {
        for pi in pcurves.into_iter().take(2) {
            let pw = pi.what();
            let dr =
                cx.g.get(pi.simple()?.reference(2, "reference_to_curve")?, &pw)?;
            let items = dr.record("DEFINITIONAL_REPRESENTATION")?.refs(1, "items")?;
            let c2_label = *items
                .first()
                .ok_or_else(|| StepError::invalid(dr.what(), "no items"))?;
            let c2: Curve<Point> = geometry::curve(cx.g, c2_label, &dr.what(), cx.radians)?;
            let in_context = |e: StepError| match e {
                StepError::VertexOrder {
                    start,
                    end,
                    same_sense,
                    ..
                } => StepError::VertexOrder {
                    edge: format!("{pw} on {what}"),
                    start,
                    end,
                    same_sense,
                },
                e => e,
            };
            // The pcurve is cut where it passes the vertices' (u, v): its parametrisation
            // need not be the 3-D curve's (`OpenCASCADE` writes circles in (u, v) as
            // rational B-splines, not parametrised by angle, and 3-D circles as rational
            // B-splines under angle-parametrised pcurves). On a plane the (u, v) are exact;
            // elsewhere the 3-D parameters give the start of the search.
            let map = cx.surface.plane_coordinates();
            let (range, period) = match map {
                Some(m) => {
                    let r = edge_range(&c2, m.point(vs), m.point(ve), same_sense, closed, &what)
                        .map_err(in_context)?;
                    (r, c2.window_period())
                }
                None => ((lo, hi), c3.window_period()),
            };
            let mut cuts = c2.pieces_in_range(range.0, range.1, period);
            cuts = clamped(&c2, cuts);
            if map.is_none() {
                let (x_lo, x_hi) = if same_sense { (vs, ve) } else { (ve, vs) };
                cuts = cut_at_vertices(cx.surface, &c2, cuts, x_lo, x_hi, gap);
            }
            let mut option = Vec::new();
            for (a2, b2) in cuts {
                let parts = c2
                    .to_bspline_extended(a2, b2)
                    .map_err(|e| StepError::geometry(format!("{pw} on {what}"), e))?;
                for p in parts {
                    option.push(planar(Ok(p), &format!("{pw} on {what}"))?);
                }
            }
            options.push(option);
        }
    }
    // The vertices at the 3-D curve's ends (lo, hi), each with the curve's miss.
    let at_lo = if same_sense {
        (s_label, vs)
    } else {
        (e_label, ve)
    };
    let at_hi = if same_sense {
        (e_label, ve)
    } else {
        (s_label, vs)
    };
    let curve_ends = [(at_lo, lo), (at_hi, hi)].map(|((label, p), t)| VertexEnd {
        label,
        miss: c3.point(t).distance(p),
    });
    let flip = !same_sense ^ !oriented;
    let ends = if flip {
        [curve_ends[1], curve_ends[0]]
    } else {
        curve_ends
    };
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
        ends,
        fitted,
        edge: Edge {
            entity: format!("#{}", ec.label),
            curve: c3,
            range: (lo, hi),
            reversed: flip,
        },
    })
}

/// The pcurve of an edge the file gives in model space only, on a surface other than a plane
/// ([`rs_geom::pcurve::pcurve`]: an exact iso-line of the surface, or a fit with a bound on
/// its 3-D deviation), in the 3-D curve's direction on `range`, with the bound of a fit. A
/// pcurve farther from its edge than the file's tolerance (the default model tolerance when it
/// states none) refuses the edge.
fn computed_pcurve(
    cx: &FaceContext<'_>,
    surface: &rs_geom::Surface,
    c3: &Curve<Point3>,
    range: (f64, f64),
    edge: u64,
) -> Result<(Piece, Option<f64>)> {
    let tolerance = cx.tolerance.stated().unwrap_or(DEFAULT_MODEL_TOLERANCE);
    let options = PcurveOptions::DEFAULT.with_tolerance(tolerance);
    let p = pcurve(surface, c3, Some(range), &options).map_err(|e| {
        StepError::geometry(
            format!("edge #{edge} on {} #{}", cx.surface.name, cx.surface.label),
            e,
        )
    })?;
    if p.deviation > tolerance || p.deviation.is_nan() {
        return Err(StepError::PcurveDeviation {
            edge,
            surface: cx.surface.name.clone(),
            label: cx.surface.label,
            bound: p.deviation,
            tolerance,
        });
    }
    let fitted = (p.kind == PcurveKind::Fitted).then_some(p.deviation);
    Ok((p.curves, fitted))
}

/// The planar NURBS of a converted curve.
fn planar(
    c: std::result::Result<rs_spline::RationalBSpline<Point>, rs_geom::GeomError>,
    what: &str,
) -> Result<NurbsCurve> {
    c.and_then(|c| Ok(c.to_planar()?))
        .map_err(|e| StepError::geometry(what, e))
}

/// Checks that the 3-D curve on `[lo, hi]` lies in the plane `plane` within `tol` (on a
/// plane `(u, v)` are lengths, so the chain gap is a model distance there).
fn check_in_plane(
    c: &Curve<Point3>,
    lo: f64,
    hi: f64,
    plane: &rs_geom::Surface,
    tol: f64,
    what: &str,
) -> Result<()> {
    let off = |p: Point3| plane.invert(p, None).distance;
    let worst = match c {
        Curve::BSpline(s) => s
            .control_points()
            .iter()
            .map(|&p| off(p))
            .fold(0.0, f64::max),
        _ => (0..=PLANE_SAMPLES)
            .map(|i| off(c.point(lo + (hi - lo) * i as f64 / PLANE_SAMPLES as f64)))
            .fold(0.0, f64::max),
    };
    if worst > tol {
        return Err(StepError::OffPlane {
            edge: what.to_string(),
            off: worst,
            tolerance: tol,
        });
    }
    Ok(())
}

/// The increasing parameter interval of a curve between an edge's vertices (`what` names
/// the edge).
fn edge_range<P: Space>(
    c: &Curve<P>,
    vs: P,
    ve: P,
    same_sense: bool,
    closed: bool,
    what: &str,
) -> Result<(f64, f64)> {
    let (ts, te) = (c.closest_parameter(vs, None), c.closest_parameter(ve, None));
    let (lo, mut hi) = if same_sense { (ts, te) } else { (te, ts) };
    if let Some(p) = c.window_period() {
        // Bring hi into (lo, lo + p]; a closed edge is the whole period.
        let eps = WRAP_RELATIVE * p;
        let d = (hi - lo).rem_euclid(p);
        hi = if closed || d <= eps { lo + p } else { lo + d };
        return Ok((lo, hi));
    }
    if closed && let Some((a, b)) = c.range() {
        return Ok((a, b));
    }
    if hi.is_nan() || hi <= lo {
        return Err(StepError::VertexOrder {
            edge: what.to_string(),
            start: ts,
            end: te,
            same_sense,
        });
    }
    Ok((lo, hi))
}

/// The pieces within the pcurve's B-spline domain (where the 3-D parameters, unrefined, may
/// overshoot it a little).
fn clamped(c2: &Curve<Point>, mut pieces: Vec<(f64, f64)>) -> Vec<(f64, f64)> {
    if let Some((a, b)) = c2.spline_domain() {
        for p in &mut pieces {
            *p = (p.0.clamp(a, b), p.1.clamp(a, b));
        }
    }
    pieces
}

/// The pieces `[a, b]` of the pcurve `c2` with their outer ends moved to the vertices `lo`
/// (at the first piece's start) and `hi` (at the last piece's end); the pieces unchanged
/// where a vertex's `(u, v)` or its pcurve parameter is not found within `gap`, or where a
/// piece would become empty.
fn cut_at_vertices(
    s: &FaceSurface,
    c2: &Curve<Point>,
    pieces: Vec<(f64, f64)>,
    lo: Point3,
    hi: Point3,
    gap: f64,
) -> Vec<(f64, f64)> {
    let n = pieces.len();
    if n == 0 || s.surface.is_none() {
        return pieces;
    }
    let mut out = pieces.clone();
    if let Some(t) = vertex_param(s, c2, out[0].0, lo, gap) {
        out[0].0 = t;
    }
    if let Some(t) = vertex_param(s, c2, out[n - 1].1, hi, gap) {
        out[n - 1].1 = t;
    }
    if out.iter().all(|(a, b)| a < b) {
        out
    } else {
        pieces
    }
}

/// The parameter near `t0` where the pcurve `c2` passes the `(u, v)` of the point `x`.
fn vertex_param(s: &FaceSurface, c2: &Curve<Point>, t0: f64, x: Point3, gap: f64) -> Option<f64> {
    let surface = s.surface.as_ref()?;
    let start = c2.point(t0);
    if !s.outside_box(start, gap)
        && surface.point([start.x, start.y]).distance(x)
            <= VERTEX_ON_PCURVE_RELATIVE * x.length().max(1.0)
    {
        return None;
    }
    let inv = surface.invert(x, Some([start.x, start.y]));
    if !(inv.uv.iter().all(|t| t.is_finite()) && inv.distance <= gap) {
        return None;
    }
    let q = Point::new(inv.uv[0], inv.uv[1]);
    let t = pcurve_parameter(c2, q, t0, 0)?;
    (t.is_finite() && c2.point_extended(t).distance(q) <= gap).then_some(t)
}

/// The copy of `x` modulo `p` nearest `x0`.
fn near(x: f64, x0: f64, p: f64) -> f64 {
    let d = (x - x0 + 0.5 * p).rem_euclid(p) - 0.5 * p;
    if d.is_finite() { x0 + d } else { x }
}

/// The parameter of the point `q` on the pcurve `c`, near `t0`: exact on lines and conics (of
/// the periodic copies of an ellipse's angle, the one nearest `t0`); on a B-spline, of the
/// curve's nearest passes by `q` on either side of `t0`, the nearer (of two as near, the one
/// nearest `t0`), continued past the domain by at most [`EXTEND`] of it where the curve stops
/// short of `q`. `depth` counts the trimmed curves passed.
fn pcurve_parameter(c: &Curve<Point>, q: Point, t0: f64, depth: usize) -> Option<f64> {
    match c {
        Curve::Line { .. } => Some(c.closest_parameter(q, None)),
        Curve::Conic(Conic {
            kind: ConicKind::Ellipse,
            ..
        }) => Some(near(c.closest_parameter(q, None), t0, TAU)),
        Curve::Conic(_) => Some(c.closest_parameter(q, None)),
        Curve::Trimmed { basis, .. } if depth < MAX_TRIM_DEPTH => {
            pcurve_parameter(basis, q, t0, depth + 1)
        }
        Curve::Trimmed { .. } => None,
        Curve::BSpline(b) => {
            let (a, e) = b.param_range();
            let len = e - a;
            let at = t0.clamp(a, e);
            let distance = |t: f64| c.point_extended(t).distance(q);
            let candidates = [
                c.closest_parameter(q, Some((a, at))),
                c.closest_parameter(q, Some((at, e))),
            ];
            // The nearer pass; of two passes as near (a closed pcurve through `q` at both
            // ends), the one nearer `t0`.
            let nearest = candidates
                .iter()
                .map(|&t| distance(t))
                .fold(f64::INFINITY, f64::min);
            let tie = nearest + PASS_TIE_RELATIVE * q.x.abs().max(q.y.abs()).max(1.0);
            let mut t = candidates
                .into_iter()
                .filter(|&t| distance(t) <= tie)
                .min_by(|&s, &u| (s - t0).abs().total_cmp(&(u - t0).abs()))?;
            // Continued past an end of the domain where the curve stops short of `q`.
            if (t == a || t == e) && distance(t) > 0.0 {
                let (w0, w1) = if t == a {
                    (a - EXTEND * len, a)
                } else {
                    (e, e + EXTEND * len)
                };
                if let Ok(ext) = b.extension(w0, w1) {
                    let s = Curve::BSpline(ext).closest_parameter(q, None);
                    let te = w0 + s * (w1 - w0);
                    if distance(te) < distance(t) {
                        t = te;
                    }
                }
            }
            // An end within rounding of the domain's is the domain's (no sliver of extension).
            for end in [a, e] {
                if (t - end).abs() <= DOMAIN_END_RELATIVE * len {
                    t = end;
                }
            }
            Some(t)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn near_picks_the_closest_copy() {
        assert!((near(0.1, TAU - 0.05, TAU) - (TAU + 0.1)).abs() < 1e-12);
        assert!((near(TAU - 0.1, 0.05, TAU) + 0.1).abs() < 1e-12);
        assert_eq!(near(1.0, 1.0, TAU), 1.0);
    }
}
