//! Iso-parametric pcurves: an edge that lies on a line `u = c` or `v = c` of its surface has
//! the straight segment between its vertices' `(u, v)` as its pcurve, exactly.
//!
//! The edge is sampled at [`ISO_SAMPLES`] (its ends and seven interior points), each point
//! inverted on the surface continuing from the one before (the first from the previous edge's
//! end or the options' `near`), the periodic copies unwrapped and the samples at a pole given
//! the pole's parameter and their neighbour's free parameter. With `c` the first sample's
//! `uv[d]`, the edge is on the line `uv[d] = c` when the free parameter runs strictly one way
//! and either
//! - every sample is within [`super::ISO_RELATIVE`] of the edge's size of the surface's point
//!   with its own free parameter and `c` (the edge is the line), or
//! - every sample's foot has `uv[d] = c` to the rounding of an inversion and lies within the
//!   fit's target (the options' tolerance) of the sample (the edge's projection is the line:
//!   a patch's boundary edge written a little off the patch, whose feet all land on the
//!   boundary).
//!
//! The segment runs from the first sample's `(u, v)` to the last's (with `c`); a closed edge
//! spans whole periods exactly. The deviation is measured: the largest of those samples'
//! distances and of the distances from [`ISO_CHECKS`] points of the segment's image to their
//! closest points on the edge; it must be within the same limit (the iso-line tolerance, or
//! the target), or the edge is fitted instead.

use rs_spline::{Point, Point3, segment};

use super::{Arc, ArcPcurve, Context, PARAMETER_ROUNDING, Sample, Start};
use crate::GeomError;
use crate::surface::ParamSurface;

/// The fractions of a stretch sampled to recognise an iso-line: its ends and seven interior
/// points, unevenly spaced (no symmetry of the edge's parameterisation lines up with them),
/// at most an eighth of a turn apart on a full circle.
pub const ISO_SAMPLES: [f64; 9] = [0.0, 0.093, 0.21, 0.347, 0.5, 0.618, 0.77, 0.885, 1.0];

/// Points of the segment whose closest points on the edge measure the deviation.
pub const ISO_CHECKS: usize = 32;

/// The ends of a closed edge whose free parameters differ by whole periods to this fraction of
/// a period span exactly those periods (the inversion's rounding).
const PERIOD_SNAP: f64 = 1e-9;

/// The iso-line pcurve of the stretch `arc`, or `None` when the edge is not on an iso-line.
///
/// # Errors
/// [`GeomError::EdgeOffSurface`] for a sample too far from the surface; the spline layer's
/// errors.
pub(crate) fn iso_line(
    ctx: &Context<'_>,
    arc: &Arc,
    start: &Start,
) -> Result<Option<ArcPcurve>, GeomError> {
    let mut samples: Vec<Sample> = Vec::with_capacity(ISO_SAMPLES.len());
    samples.push(ctx.first_sample(arc, start)?);
    for &s in &ISO_SAMPLES[1..] {
        let near = samples.last().map(|p| p.uv);
        samples.push(ctx.sample(arc, s, near)?);
    }
    ctx.settle(&mut samples, start.near.or(start.uv));
    let last = samples.len() - 1;
    let closed = samples[0].x.distance(samples[last].x) <= ctx.iso_tol;
    let periods = ctx.surface.periods();
    for d in 0..2 {
        let w = 1 - d;
        let c = samples[0].uv[d];
        let on_line = |p: &Sample| {
            let mut uv = p.uv;
            uv[d] = c;
            ctx.surface.point(uv).distance(p.x)
        };
        let worst = samples.iter().map(on_line).fold(0.0f64, f64::max);
        // On the line in space, or every foot on it to the rounding of its parameters (the
        // edge's projection is the line: a patch's boundary edge written a little off it).
        let exact = worst <= ctx.iso_tol;
        let flat = samples
            .iter()
            .all(|p| (p.uv[d] - c).abs() <= PARAMETER_ROUNDING * (1.0 + c.abs()));
        let accept = if exact { ctx.iso_tol } else { ctx.target };
        if !(exact || flat) || worst > accept || worst.is_nan() {
            continue;
        }
        let up = samples[last].uv[w] > samples[0].uv[w];
        let monotone = samples.windows(2).all(|p| {
            let (a, b) = (p[0].uv[w], p[1].uv[w]);
            if up { b > a } else { b < a }
        });
        if !monotone {
            continue;
        }
        let from = samples[0].uv;
        let mut to = samples[last].uv;
        to[d] = c;
        if closed && let Some(p) = periods[w] {
            let k = ((to[w] - from[w]) / p).round();
            if k != 0.0 && (to[w] - from[w] - k * p).abs() <= PERIOD_SNAP * p {
                to[w] = from[w] + k * p;
            }
        }
        let deviation = worst.max(measured(ctx, arc, from, to));
        if deviation > accept || deviation.is_nan() {
            continue;
        }
        return Ok(Some(ArcPcurve {
            curve: segment(Point::new(from[0], from[1]), Point::new(to[0], to[1]))?,
            start: from,
            end: to,
            deviation,
            rigorous: false,
            fitted: false,
            iso: Some(d),
        }));
    }
    Ok(None)
}

/// The largest distance from the surface's points on the segment `from -> to` (at
/// [`ISO_CHECKS`] points between its ends) to their closest points on the edge's stretch.
fn measured(ctx: &Context<'_>, arc: &Arc, from: [f64; 2], to: [f64; 2]) -> f64 {
    (0..ISO_CHECKS)
        .map(|i| {
            let l = (i as f64 + 0.5) / ISO_CHECKS as f64;
            let uv = [
                from[0] + l * (to[0] - from[0]),
                from[1] + l * (to[1] - from[1]),
            ];
            let y: Point3 = ctx.surface.point(uv);
            let t = ctx.edge.closest_parameter(y, Some(arc.window()));
            ctx.edge.point(t).distance(y)
        })
        .fold(0.0, f64::max)
}
