//! Figures of splines: the spline, or its error against the function it approximates, as a
//! colour map over the curved triangulation, with a colour bar, axes and a caption.

use std::collections::HashSet;

use rs_figure::{FieldImage, Figure, Style};
use rs_mesh::EdgeKind;
use rs_spline::Point;

use crate::bb::Order;
use crate::{Spline, TriSplineError};

/// Pixels per row of the colour map (the figure scales it to its plot area).
const RASTER_WIDTH: usize = 360;

/// The spline as a colour map over its curved triangulation; `source` names what it
/// approximates or interpolates, in the caption (`f = sin(x)`, `the data of z.csv`).
///
/// # Errors
/// As [`Spline::evaluator`].
pub fn spline_svg(s: &Spline, source: &str, width: f64) -> Result<String, TriSplineError> {
    let eval = s.evaluator()?;
    let mut fig = Figure::new(s.mesh().domain().bounding_box(), width);
    let image = FieldImage::sample(&fig, RASTER_WIDTH, |p| {
        eval.evaluate(p, Order::Value).map(|j| j.value)
    });
    let (lo, hi) = image.range().unwrap_or((0.0, 1.0));
    fig.field(&image, lo, hi, "s(x, y)");
    draw_triangulation(&mut fig, s)?;
    fig.caption(&format!(
        "The {} of {source} on {} curved triangles, {} coefficients: colour shows s, the grey \
         lines its curved triangulation.",
        s.kind().description(s.degree()),
        s.mesh().triangles().len(),
        s.dimension()
    ));
    Ok(fig.to_svg())
}

/// The absolute error `|s - f|` as a colour map (on a log10 scale) over the curved
/// triangulation.
///
/// # Errors
/// As [`Spline::evaluator`].
pub fn error_svg(
    s: &Spline,
    f: &(dyn Fn(Point) -> f64 + Sync),
    formula: &str,
    width: f64,
) -> Result<String, TriSplineError> {
    let eval = s.evaluator()?;
    let mut fig = Figure::new(s.mesh().domain().bounding_box(), width);
    let image = FieldImage::sample(&fig, RASTER_WIDTH, |p| {
        eval.evaluate(p, Order::Value)
            .map(|j| ((j.value - f(p)).abs().max(1e-17)).log10())
    });
    let (lo, hi) = image.range().unwrap_or((-17.0, 0.0));
    fig.field(&image, lo, hi, "log10 |s - f|");
    draw_triangulation(&mut fig, s)?;
    let max = 10f64.powf(hi);
    fig.caption(&format!(
        "The error |s - f| of the quasi-interpolating spline s of degree {} of f = {formula} on \
         {} curved triangles, on a log10 colour scale (largest error on the picture's pixels \
         {max:.2e}); the grey lines are the curved triangulation.",
        s.degree(),
        s.mesh().triangles().len()
    ));
    Ok(fig.to_svg())
}

/// The straight edges (once each) and the boundary arcs.
fn draw_triangulation(fig: &mut Figure, s: &Spline) -> Result<(), TriSplineError> {
    let m = s.mesh();
    let edge = Style::stroke("#5a5a5a", 0.4).labelled("triangle edge");
    let arc = Style::stroke("#000000", 1.2).labelled("boundary arc");
    let mut seen = HashSet::new();
    for (t, tri) in m.triangles().iter().enumerate() {
        for (k, kind) in m.edge_kinds(t).iter().enumerate() {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            match kind {
                EdgeKind::Straight => {
                    if seen.insert((a.min(b), a.max(b))) {
                        fig.polyline(&[m.vertices()[a], m.vertices()[b]], &edge);
                    }
                }
                EdgeKind::Curved(i) => fig.curve(&m.arc_curve(&m.arcs()[*i])?, &arc),
            }
        }
    }
    Ok(())
}
