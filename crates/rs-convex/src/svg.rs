//! An SVG figure of a planar convex domain: the outer bound, the nested inner polygons, and
//! the curve with its control polygon and free point.

use rs_figure::{Figure, Marker, Style};
use rs_spline::{BoundingBox, NurbsCurve, Point};

use crate::{ConvexDomain, Region};

/// The figure as SVG text (plot area 600 px wide, with axes, a legend and a caption), or
/// `None` for a space curve's polytopes.
pub fn to_svg(domain: &ConvexDomain, curve: Option<&NurbsCurve>, free: usize) -> Option<String> {
    let Region::Polygon(outer) = &domain.outer else {
        return None;
    };
    let polygons: Vec<(u32, usize, &[Point])> = domain
        .levels
        .iter()
        .filter_map(|l| match &l.region {
            Region::Polygon(p) if !p.is_empty() => Some((l.level, l.inequalities, p.vertices())),
            _ => None,
        })
        .collect();
    let all = outer
        .vertices()
        .iter()
        .chain(polygons.iter().flat_map(|(_, _, v)| v.iter()))
        .chain(curve.iter().flat_map(|c| c.control_points()))
        .copied();
    let data = BoundingBox::from_points(all)
        .unwrap_or(BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(1.0, 1.0)));
    let mut fig = Figure::new(data, 600.0);
    fig.polygon(
        outer.vertices(),
        &Style::stroke("#b03030", 1.4)
            .with_fill("#f3d6d6", 0.6)
            .dashed("6 3")
            .labelled("outer bound (sampled)"),
    );
    // Inner levels from light to dark blue, each outlined, the last one filled; only the first
    // and the last are named in the legend.
    let n = polygons.len();
    for (i, (level, inequalities, vertices)) in polygons.iter().enumerate() {
        let shade = 200 - (170 * (i + 1) / n.max(1)) as i32;
        let color = format!("rgb({shade},{shade},230)");
        let mut style = Style::stroke(&color, 1.2);
        if i + 1 == n {
            style = style.with_fill("#7f96d9", 0.5);
        }
        if i == 0 || i + 1 == n {
            style = style.labelled(&format!(
                "inner polygon, level {level} ({inequalities} inequalities)"
            ));
        }
        fig.polygon(vertices, &style);
    }
    if let Some(c) = curve {
        fig.curve(c, &Style::stroke("#000000", 2.0).labelled("curve"));
        fig.polyline(
            c.control_points(),
            &Style::stroke("#808080", 1.0).labelled("control polygon"),
        );
        let fixed = Style::fill("#404040")
            .with_marker(Marker::Dot(3.0))
            .labelled("fixed control point");
        let moving = Style::fill("#e08000")
            .with_marker(Marker::Dot(6.0))
            .labelled("free control point");
        for (i, &p) in c.control_points().iter().enumerate() {
            fig.mark(p, if i == free { &moving } else { &fixed });
        }
    }
    fig.caption(&format!(
        "Positions of the free control point that keep the sign of the curvature: every point \
         of the inner polygons qualifies (exact), no point outside the outer bound does. {} \
         inner levels; {}.",
        n,
        match domain.outcome {
            crate::Outcome::Converged => "converged",
            crate::Outcome::Empty => "the domain is empty",
            crate::Outcome::NotConverged => "stopped at the last level before converging",
        }
    ));
    Some(fig.to_svg())
}
