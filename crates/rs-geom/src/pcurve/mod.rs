//! Pcurves: the `(u, v)` curve of a 3-D edge on a face's surface, for faces whose file gives
//! the edges in model space only (STEP edges without `PCURVE`s, IGES 142 and 508 with model
//! curves only).
//!
//! [`pcurve`] gives, for an edge curve `C` on `[t0, t1]` and a surface `S`, planar NURBS
//! curves `g` in the edge's direction such that `S(g)` is the edge, with a bound on the 3-D
//! distance between the two ([`Pcurve::deviation`]). Three cases, tried in this order:
//!
//! 1. **Plane** ([`PcurveKind::Plane`], exact): on a plane (or an offset or reparameterised
//!    plane) the pcurve is the edge's image under the affine map of the plane's coordinates
//!    ([`crate::PlaneCoordinates`]), converted exactly ([`Curve::to_bspline_mapped`]): lines
//!    stay degree 1, conics rational quadratics, B-splines keep their knots and weights. An
//!    edge on a periodic B-spline whose range crosses the end of its domain is converted in
//!    two pieces. The deviation is the edge's largest distance from the plane, bounded by its
//!    control points (the convex hull).
//! 2. **Iso-line** ([`PcurveKind::IsoLine`], exact): the edge lies on a line `u = c` or
//!    `v = c` of the surface (rulings and circles of cylinders, cones, spheres, tori, surfaces
//!    of revolution and extrusion, the boundary and interior iso-lines of B-spline patches):
//!    the pcurve is the straight segment in `(u, v)` between the edge's inverted vertices; a
//!    closed edge spans exactly whole periods. An edge a little off the surface whose closest
//!    points all lie on one iso-line (a patch's boundary) has that line as its pcurve too.
//!    The deviation is measured (see [`iso`]).
//! 3. **Fitted** ([`PcurveKind::Fitted`]): otherwise, a cubic B-spline fitted by least squares
//!    to the edge's closest points on the surface, refined where its error is largest, with a
//!    computed bound on `|S(g(s)) - C(t(s))|` (see [`fit`] for what is rigorous).
//!
//! # Parameters of the result
//!
//! A plane's pieces keep the parameters of [`Curve::to_bspline_mapped`]. Every other piece
//! is parameterised on `[0, 1]`: a fitted piece by `s` with the edge at `t = ta + s (tb -
//! ta)` over its stretch `[ta, tb]` of the edge (in the edge's direction), so that its
//! deviation bounds the distance between `S(g(s))` and `C(t(s))` at equal `s`.
//!
//! # Poles and seams
//!
//! Where the edge passes through a pole of the surface (a sphere's pole, a cone's apex, a
//! degenerate boundary of a B-spline patch), it is cut there: the pole's point has every
//! value of the free parameter, so each side takes it from its neighbouring samples, and a
//! segment along the pole line (one point in space) joins the two sides (none where both
//! sides are one line, as a ruling through a cone's apex: consecutive segments on one line
//! are merged). An edge that starts at the pole where [`PcurveOptions::near`] is (the
//! previous edge of its loop ended there) starts with such a segment from `near`.
//!
//! Of the periodic copies of the start, the one nearest [`PcurveOptions::near`] is taken (the
//! copy on the right side of a seam); every later sample continues from the one before it, so
//! a pcurve crossing a seam runs on past the period's end.
//!
//! # Tolerances
//!
//! With `size` the largest coordinate of the edge's points and `tolerance` the options' one:
//! - a point of the edge within `Tolerance::coincidence(size) = max(tolerance, 1e-8 size)` of
//!   a pole is at the pole;
//! - a point of the edge farther than [`OFF_SURFACE_FACTOR`] times that from the surface
//!   is an error ([`GeomError::EdgeOffSurface`]);
//! - iso-lines are recognised to [`ISO_RELATIVE`] of `size`;
//! - fits aim at a deviation `min(tolerance, FIT_AIM_RELATIVE size)`, at least
//!   `FIT_FLOOR_RELATIVE size`; their bound is then checked against the tolerance.
//!
//! # Examples
//!
//! ```
//! use rs_geom::pcurve::{PcurveKind, PcurveOptions, pcurve};
//! use rs_geom::surface::{Cylinder, Surface};
//! use rs_geom::{Conic, ConicKind, Curve, Frame, Point3};
//! use rs_spline::prelude::*;
//! // The circle z = 2 of the cylinder of radius 3 about z: the line v = 2 in (u, v).
//! let s = Surface::Cylinder(Cylinder::new(Frame::WORLD, 3.0).unwrap());
//! let circle = Curve::Conic(Conic {
//!     kind: ConicKind::Ellipse,
//!     center: Point3::new(0.0, 0.0, 2.0),
//!     u: Point3::new(3.0, 0.0, 0.0),
//!     v: Point3::new(0.0, 3.0, 0.0),
//! });
//! let p = pcurve(&s, &circle, Some((0.5, 2.0)), &PcurveOptions::DEFAULT).unwrap();
//! assert_eq!(p.kind, PcurveKind::IsoLine);
//! let (a, b) = (p.curves[0].start_point(), p.curves[0].end_point());
//! assert!((a.x - 0.5).abs() < 1e-15 && (b.x - 2.0).abs() < 1e-15);
//! assert!(a.y == 2.0 && b.y == 2.0 && p.deviation < 1e-14);
//! ```

pub mod bounds;
pub mod fit;
pub mod iso;
mod plane;

use rs_spline::{NurbsCurve, Point, Point3, segment};

use crate::surface::{ParamSurface, Pole, Surface, nearest_copy};
use crate::{Curve, GeomError, Tolerance};

/// A point of the edge farther than this many coincidence tolerances (see the module
/// documentation) from the surface is not on it: an edge written to the file's tolerance lies
/// within about one tolerance of its surface (`component8.step`'s intersection edges: within
/// 2.6e-3 of a tolerance of 0.074), and a wrong surface or a misplaced edge is far beyond a
/// hundred.
pub const OFF_SURFACE_FACTOR: f64 = 100.0;

/// An edge is an iso-line of the surface when its samples are within this fraction of
/// `size` of the line (and the line's dense samples of the edge): exact iso-lines written
/// with 15 or more significant digits meet it with room to spare (`as1-tu-203.stp`'s boundary
/// lines to 1.2e-14, `component8.step`'s to 4.1e-13), while an edge that is not an
/// iso-line leaves every iso-line by far more.
pub const ISO_RELATIVE: f64 = 1e-11;

/// The least deviation a fit aims at, as a fraction of `size`: the rounding of a surface
/// point and an edge point is some `1e-15 size`; a fit aims no lower than a thousand times
/// that (a caller's tolerance of zero would otherwise make every fit run to its work limit).
pub const FIT_FLOOR_RELATIVE: f64 = 1e-12;

/// The most deviation a fit aims at, as a fraction of `size` (the largest coordinate of the
/// edge's points: the aim follows the coordinates' rounding, so it loosens as a part lies
/// farther from the origin), however loose the caller's
/// tolerance: a face's area is exact for its pcurves, so a pcurve fitted to a file's loose
/// uncertainty (`component8.step`: 0.074 mm on a 30 mm part) would make its area that loose
/// (1e-4 there); at `1e-7` fits cost about three times as much and the areas agree with the
/// converged projection to about `1e-8`.
pub const FIT_AIM_RELATIVE: f64 = 1e-7;

/// Samples of the edge that give its `size` (the largest coordinate of its points).
const SIZE_SAMPLES: usize = 16;

/// What [`pcurve`] aims at and where it starts.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct PcurveOptions {
    /// The 3-D deviation accepted, in model units (the file's tolerance): fits are refined
    /// until their bound is below the tighter of it and [`FIT_AIM_RELATIVE`] of the edge's
    /// size (or their work limit is reached).
    pub tolerance: f64,
    /// The `(u, v)` the pcurve should start near (the end of the previous edge's pcurve in the
    /// loop): of the periodic copies of the start, the nearest is taken.
    pub near: Option<[f64; 2]>,
}

impl PcurveOptions {
    /// Tolerance `1e-6` ([`crate::DEFAULT_MODEL_TOLERANCE`]), no `near`.
    pub const DEFAULT: PcurveOptions = PcurveOptions {
        tolerance: crate::DEFAULT_MODEL_TOLERANCE,
        near: None,
    };

    /// The options with the tolerance `tolerance` (model units).
    pub fn with_tolerance(self, tolerance: f64) -> PcurveOptions {
        PcurveOptions { tolerance, ..self }
    }

    /// The options starting near `near`.
    pub fn with_near(self, near: Option<[f64; 2]>) -> PcurveOptions {
        PcurveOptions { near, ..self }
    }
}

impl Default for PcurveOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// How a pcurve was made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PcurveKind {
    /// The affine image of the edge in a plane's coordinates: exact.
    Plane,
    /// Iso-parametric lines of the surface (with segments along pole lines where the edge
    /// passes a pole): straight segments in `(u, v)`, exact.
    IsoLine,
    /// A fitted B-spline (some pieces may be iso-lines), within its computed deviation.
    Fitted,
}

/// The `(u, v)` curve of an edge on a surface.
#[derive(Clone, Debug, PartialEq)]
pub struct Pcurve {
    /// The planar pieces, in the edge's direction (from the range's first end to its second);
    /// each starts exactly where the one before it ends.
    pub curves: Vec<NurbsCurve>,
    /// How they were made.
    pub kind: PcurveKind,
    /// A bound on the 3-D distance between the surface's image of the pieces and the edge,
    /// in model units: for a plane, the edge's largest distance from the plane (bounded by its
    /// control points); for iso-lines, the largest distance measured at dense samples (to
    /// rounding for a true iso-line); for a fit, its computed bound (see [`fit`]).
    pub deviation: f64,
    /// Whether [`Pcurve::deviation`] is proven (up to the floating-point rounding of its own
    /// arithmetic): true for planes and for fits whose derivative bounds are all closed forms
    /// or control-polygon bounds; false for iso-lines (measured at samples) and fits on offset
    /// surfaces (derivative bounds estimated from samples, see [`fit`]).
    pub rigorous: bool,
}

/// The `(u, v)` curve of the edge `edge` on `[range.0, range.1]` (either order: the pcurve
/// runs from the edge's point at `range.0` to its point at `range.1`; `None`: the edge's own
/// range) on `surface`, with a bound on its 3-D deviation from the edge (see the module
/// documentation).
///
/// A fit whose bound stays above the tolerance after its work limit (at most
/// [`fit::MAX_CONTROL_POINTS`] control points, [`fit::MAX_ROUNDS`] rounds) is returned with
/// that bound: the caller compares it with the file's tolerance.
///
/// # Errors
/// - [`GeomError::NotFinite`] for a tolerance that is negative or not finite;
/// - [`GeomError::UnboundedEdge`] for an edge without a range (a line, a conic) given no
///   range, or a range with an infinite end; [`GeomError::EmptyInterval`] for a range whose
///   ends are equal or not numbers;
/// - [`GeomError::EdgeOffSurface`] for a point of the edge farther from the surface than
///   [`OFF_SURFACE_FACTOR`] coincidence tolerances;
/// - [`GeomError::PcurveWorkLimit`] where the edge's closest points on the surface jump
///   (no continuous pcurve follows the edge);
/// - the spline layer's errors for curves beyond its limits.
pub fn pcurve(
    surface: &Surface,
    edge: &Curve<Point3>,
    range: Option<(f64, f64)>,
    options: &PcurveOptions,
) -> Result<Pcurve, GeomError> {
    let tolerance = rs_spline::limits::NonNegative::new(options.tolerance)
        .map_err(|e| GeomError::NotFinite {
            what: "pcurve tolerance",
            value: e.0,
        })?
        .get();
    let (t0, t1) = range
        .or_else(|| edge.range())
        .ok_or(GeomError::UnboundedEdge)?;
    if t0.is_infinite() || t1.is_infinite() {
        return Err(GeomError::UnboundedEdge);
    }
    if t0.is_nan() || t1.is_nan() || t0 == t1 {
        return Err(GeomError::EmptyInterval { t0, t1 });
    }
    let reversed = t1 < t0;
    let (lo, hi) = if reversed { (t1, t0) } else { (t0, t1) };
    let pieces = domain_pieces(edge, lo, hi);
    let ctx = Context::new(surface, edge, &pieces, tolerance)?;
    if let Some(map) = plane::PlaneMap::of(surface) {
        return plane::pcurve(&ctx, &map, &pieces, reversed);
    }
    // The stretches of the edge in its direction, cut at the poles it passes.
    let mut arcs = Vec::new();
    let directed: Vec<Arc> = if reversed {
        pieces
            .iter()
            .rev()
            .map(|&(a, b)| Arc { ta: b, tb: a })
            .collect()
    } else {
        pieces.iter().map(|&(a, b)| Arc { ta: a, tb: b }).collect()
    };
    for arc in directed {
        arcs.extend(ctx.split_at_poles(arc));
    }
    let mut out = Pcurve {
        curves: Vec::new(),
        kind: PcurveKind::IsoLine,
        deviation: 0.0,
        rigorous: true,
    };
    // The end of the previous stretch: its point and (u, v). An edge that starts at a pole
    // where `near` is (the previous edge of the loop ended there) starts from `near` with a
    // segment along the pole line, so that the loop runs on without a gap.
    let mut previous: Option<(Point3, [f64; 2])> = None;
    if let (Some(n), Some(first)) = (options.near, arcs.first()) {
        let x = edge.point(first.ta);
        if let Some((_, p)) = ctx
            .poles
            .iter()
            .find(|(_, p)| p.distance(x) <= ctx.coincidence)
            && n.iter().all(|t| t.is_finite())
            && surface.point(n).distance(*p) <= ctx.coincidence
        {
            previous = Some((x, n));
        }
    }
    // The last piece if it is an iso-line segment: its start and constant parameter.
    let mut last_iso: Option<([f64; 2], usize)> = None;
    for arc in arcs {
        let x = edge.point(arc.ta);
        let start = match previous {
            // A stretch continues the one before from its end's (u, v), except at a pole,
            // where only the copy is taken from it.
            Some((_, uv)) if ctx.pole_at(x).is_none() => Start {
                uv: Some(uv),
                near: Some(uv),
            },
            Some((_, uv)) => Start {
                uv: None,
                near: Some(uv),
            },
            None => Start {
                uv: None,
                near: options.near,
            },
        };
        let piece = match iso::iso_line(&ctx, &arc, &start)? {
            Some(p) => p,
            None => fit::fit(&ctx, &arc, &start)?,
        };
        if let Some((joint, end)) = previous
            && end != piece.start
        {
            // Along the pole line from the previous stretch's side to this one's.
            let link = segment(Point::new(end[0], end[1]), piece.start_point())?;
            out.deviation = out.deviation.max(ctx.link_deviation(&link, joint));
            out.curves.push(link);
            last_iso = None;
        }
        if piece.fitted {
            out.kind = PcurveKind::Fitted;
        }
        out.deviation = out.deviation.max(piece.deviation);
        out.rigorous &= piece.rigorous;
        previous = Some((edge.point(arc.tb), piece.end));
        match (last_iso, piece.iso) {
            // The same line on, the same way: one segment.
            (Some((from, d)), Some(e))
                if d == e
                    && from[d] == piece.end[d]
                    && (piece.start[1 - d] - from[1 - d])
                        * (piece.end[1 - d] - piece.start[1 - d])
                        > 0.0 =>
            {
                let merged = segment(
                    Point::new(from[0], from[1]),
                    Point::new(piece.end[0], piece.end[1]),
                )?;
                *out.curves.last_mut().expect("the previous piece") = merged;
            }
            _ => {
                last_iso = piece.iso.map(|d| (piece.start, d));
                out.curves.push(piece.curve);
            }
        }
    }
    Ok(out)
}

/// The pieces of `[lo, hi]` (increasing) within the edge's own parameter domain, in order
/// ([`Curve::pieces_in_range`] in its [`Curve::window_period`]).
pub(crate) fn domain_pieces(edge: &Curve<Point3>, lo: f64, hi: f64) -> Vec<(f64, f64)> {
    edge.pieces_in_range(lo, hi, edge.window_period())
}

/// A stretch of the edge from its parameter `ta` to `tb` (either order), parameterised by
/// `s` in `[0, 1]`: `t = ta + s (tb - ta)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Arc {
    /// The edge's parameter at `s = 0`.
    pub(crate) ta: f64,
    /// The edge's parameter at `s = 1`.
    pub(crate) tb: f64,
}

impl Arc {
    /// The edge's parameter at `s` (the ends exactly).
    pub(crate) fn t(&self, s: f64) -> f64 {
        if s <= 0.0 {
            self.ta
        } else if s >= 1.0 {
            self.tb
        } else {
            self.ta + s * (self.tb - self.ta)
        }
    }

    /// `s` of the edge's parameter `t`.
    pub(crate) fn s(&self, t: f64) -> f64 {
        (t - self.ta) / (self.tb - self.ta)
    }

    /// The increasing interval of the edge's parameter.
    pub(crate) fn window(&self) -> (f64, f64) {
        (self.ta.min(self.tb), self.ta.max(self.tb))
    }

    /// `dt / ds`.
    pub(crate) fn speed(&self) -> f64 {
        self.tb - self.ta
    }
}

/// Where the computation of a stretch starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Start {
    /// The `(u, v)` of the stretch's first point, when it continues the previous stretch
    /// there (not at a pole).
    pub(crate) uv: Option<[f64; 2]>,
    /// The `(u, v)` whose periodic copy the start takes.
    pub(crate) near: Option<[f64; 2]>,
}

/// A point of the edge with its closest point on the surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Sample {
    /// Its `s` on the stretch.
    pub(crate) s: f64,
    /// The edge's point.
    pub(crate) x: Point3,
    /// The parameters of its foot on the surface.
    pub(crate) uv: [f64; 2],
    /// The foot, `S(uv)`.
    pub(crate) foot: Point3,
    /// The pole the point is at, if any.
    pub(crate) pole: Option<Pole>,
}

impl Sample {
    /// The distance from the edge's point to its foot.
    pub(crate) fn distance(&self) -> f64 {
        self.foot.distance(self.x)
    }
}

/// The pcurve of one stretch.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ArcPcurve {
    /// The curve.
    pub(crate) curve: NurbsCurve,
    /// Its start, exactly.
    pub(crate) start: [f64; 2],
    /// Its end, exactly.
    pub(crate) end: [f64; 2],
    /// Its deviation (as [`Pcurve::deviation`]).
    pub(crate) deviation: f64,
    /// Whether the deviation is proven.
    pub(crate) rigorous: bool,
    /// Fitted (not an iso-line).
    pub(crate) fitted: bool,
    /// For an iso-line, its constant parameter.
    pub(crate) iso: Option<usize>,
}

impl ArcPcurve {
    /// The start as a point.
    fn start_point(&self) -> Point {
        Point::new(self.start[0], self.start[1])
    }
}

/// The surface, the edge and the tolerances of one pcurve computation.
pub(crate) struct Context<'a> {
    pub(crate) surface: &'a Surface,
    pub(crate) edge: &'a Curve<Point3>,
    /// The surface's poles with their points.
    pub(crate) poles: Vec<(Pole, Point3)>,
    /// The largest coordinate of the edge's points.
    pub(crate) size: f64,
    /// The deviation accepted: an edge off the surface along an iso-line is that line within
    /// it.
    pub(crate) target: f64,
    /// The deviation a fit aims at: the tighter of the tolerance and [`FIT_AIM_RELATIVE`] of
    /// the size.
    pub(crate) fit_target: f64,
    /// Points this near coincide (a point of the edge at a pole).
    pub(crate) coincidence: f64,
    /// The farthest a point of the edge may be from the surface.
    pub(crate) off_limit: f64,
    /// The distance within which an edge is on an iso-line.
    pub(crate) iso_tol: f64,
}

impl<'a> Context<'a> {
    fn new(
        surface: &'a Surface,
        edge: &'a Curve<Point3>,
        pieces: &[(f64, f64)],
        tolerance: f64,
    ) -> Result<Context<'a>, GeomError> {
        let mut size = 0.0f64;
        for &(a, b) in pieces {
            for i in 0..=SIZE_SAMPLES {
                let t = a + (b - a) * i as f64 / SIZE_SAMPLES as f64;
                size = size.max(edge.point(t).max_abs());
            }
        }
        if !size.is_finite() {
            return Err(GeomError::NotFinite {
                what: "edge point",
                value: size,
            });
        }
        let size = size.max(f64::MIN_POSITIVE);
        let coincidence = Tolerance::new(Some(tolerance))?.coincidence(size);
        let bx = surface.param_box();
        let poles = surface
            .poles()
            .into_iter()
            .map(|pole| {
                let free = 1 - pole.param;
                let (a, _) = bx.range(free);
                let mut uv = [0.0; 2];
                uv[pole.param] = pole.value;
                uv[free] = if a.is_finite() { a } else { 0.0 };
                (pole, surface.point(uv))
            })
            .collect();
        Ok(Context {
            surface,
            edge,
            poles,
            size,
            target: tolerance.max(FIT_FLOOR_RELATIVE * size),
            fit_target: tolerance
                .min(FIT_AIM_RELATIVE * size)
                .max(FIT_FLOOR_RELATIVE * size),
            coincidence,
            off_limit: OFF_SURFACE_FACTOR * coincidence,
            iso_tol: ISO_RELATIVE * size,
        })
    }

    /// The pole `x` is at, if any.
    pub(crate) fn pole_at(&self, x: Point3) -> Option<Pole> {
        self.poles
            .iter()
            .find(|(_, p)| p.distance(x) <= self.coincidence)
            .map(|(pole, _)| *pole)
    }

    /// The edge's point at `s` of `arc` with its foot, searched from `near`.
    ///
    /// # Errors
    /// [`GeomError::EdgeOffSurface`] for a point too far from the surface.
    pub(crate) fn sample(
        &self,
        arc: &Arc,
        s: f64,
        near: Option<[f64; 2]>,
    ) -> Result<Sample, GeomError> {
        let t = arc.t(s);
        let x = self.edge.point(t);
        let inv = self.surface.invert(x, near);
        self.checked(
            Sample {
                s,
                x,
                uv: inv.uv,
                foot: self.surface.point(inv.uv),
                pole: self.pole_at(x),
            },
            t,
        )
    }

    /// The first sample of `arc`: the previous stretch's end where it continues it, otherwise
    /// the foot nearest the start's `near`.
    ///
    /// # Errors
    /// As [`Context::sample`].
    pub(crate) fn first_sample(&self, arc: &Arc, start: &Start) -> Result<Sample, GeomError> {
        let x = self.edge.point(arc.ta);
        if let Some(uv) = start.uv
            && self.pole_at(x).is_none()
        {
            return self.checked(
                Sample {
                    s: 0.0,
                    x,
                    uv,
                    foot: self.surface.point(uv),
                    pole: None,
                },
                arc.ta,
            );
        }
        self.sample(arc, 0.0, start.near.or(start.uv))
    }

    /// `sample`, unless its point is too far from its foot.
    fn checked(&self, sample: Sample, t: f64) -> Result<Sample, GeomError> {
        let distance = sample.distance();
        if distance <= self.off_limit {
            Ok(sample)
        } else {
            Err(GeomError::EdgeOffSurface {
                surface: self.surface.kind_name(),
                distance,
                parameter: t,
                limit: self.off_limit,
            })
        }
    }

    /// Places the samples (in order of `s`) among the periodic copies: each continues the one
    /// before it. A sample at a pole takes the pole's parameter exactly and the free parameter
    /// of its neighbour (the sample after it at the start, the one before it elsewhere);
    /// `near` gives the copy of a first sample at a pole.
    pub(crate) fn settle(&self, samples: &mut [Sample], near: Option<[f64; 2]>) {
        let periods = self.surface.periods();
        for k in 0..samples.len() {
            let previous = if k > 0 { Some(samples[k - 1].uv) } else { near };
            let sample = &mut samples[k];
            if let Some(pole) = sample.pole {
                let free = 1 - pole.param;
                let mut value = pole.value;
                if let (Some(p), Some(prev)) = (periods[pole.param], previous) {
                    value = nearest_copy(value, prev[pole.param], p);
                }
                sample.uv[pole.param] = value;
                if let Some(prev) = previous {
                    sample.uv[free] = prev[free];
                }
            } else if k > 0
                && let Some(prev) = previous
            {
                for i in 0..2 {
                    if let Some(p) = periods[i] {
                        sample.uv[i] = nearest_copy(sample.uv[i], prev[i], p);
                    }
                }
            }
        }
        if samples.len() > 1
            && let Some(pole) = samples[0].pole
            && samples[1].pole.is_none()
        {
            // The neighbour's free parameter, unless it is `near`'s to rounding (an edge that
            // goes on through the pole along the same line, as a ruling through a cone's
            // apex): then `near`'s, so that no segment along the pole line is needed.
            let free = 1 - pole.param;
            let next = samples[1].uv[free];
            let keep = near
                .is_some_and(|n| (n[free] - next).abs() <= PARAMETER_ROUNDING * (1.0 + next.abs()));
            if !keep {
                samples[0].uv[free] = next;
            }
        }
        for sample in samples.iter_mut().filter(|s| s.pole.is_some()) {
            sample.foot = self.surface.point(sample.uv);
        }
    }

    /// The stretch cut where the edge passes through a pole (strictly inside it).
    fn split_at_poles(&self, arc: Arc) -> Vec<Arc> {
        let (a, b) = (self.edge.point(arc.ta), self.edge.point(arc.tb));
        let mut cuts: Vec<f64> = self
            .poles
            .iter()
            .filter(|(_, p)| p.distance(a) > self.coincidence && p.distance(b) > self.coincidence)
            .filter_map(|(_, p)| {
                let t = self.edge.closest_parameter(*p, Some(arc.window()));
                (self.edge.point(t).distance(*p) <= self.coincidence).then(|| arc.s(t))
            })
            .filter(|s| *s > 0.0 && *s < 1.0)
            .collect();
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let mut out = Vec::with_capacity(cuts.len() + 1);
        let mut from = arc.ta;
        for s in cuts {
            let t = arc.t(s);
            out.push(Arc { ta: from, tb: t });
            from = t;
        }
        out.push(Arc {
            ta: from,
            tb: arc.tb,
        });
        out
    }

    /// The largest distance from `joint` (the edge's point where two stretches meet at a
    /// pole) of the surface's image of the segment `link` along the pole line, at
    /// [`LINK_SAMPLES`] points.
    fn link_deviation(&self, link: &NurbsCurve, joint: Point3) -> f64 {
        use rs_spline::ParamCurve;
        (0..=LINK_SAMPLES)
            .map(|i| {
                let p = link.point_at(i as f64 / LINK_SAMPLES as f64);
                self.surface.point([p.x, p.y]).distance(joint)
            })
            .fold(0.0, f64::max)
    }
}

/// Two values of a parameter this close (relative to `1 + |value|`) are the same up to the
/// rounding of an inversion.
pub(crate) const PARAMETER_ROUNDING: f64 = 1e-12;

/// Points of a segment along a pole line checked to map to the pole.
const LINK_SAMPLES: usize = 8;

#[cfg(test)]
mod tests;
