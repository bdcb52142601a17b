//! The cubature-nodes figures of `cargo xtask demo` (issue 36): the nodes of the positive
//! interior rules of degree 10 and 20 on the M-shaped domain and on the lune, each node a
//! circle whose area is proportional to its weight, written as SVG and, where
//! `rsvg-convert` is installed, as PNG.

use std::path::{Path, PathBuf};

use inrs::Domain;
use inrs::cubature::{CubatureRule, dim_polynomials};
use rs_figure::{Figure, Marker, Style};

/// The domains drawn (fixtures under `fixtures/inrs-paper/`) and their names in captions.
pub(crate) const DOMAINS: [(&str, &str); 2] = [("s3_m_shape", "M-shaped"), ("s5_lune", "lune")];

/// The degrees drawn, the lower one as outlined circles over the higher one's filled ones.
pub(crate) const DEGREES: [usize; 2] = [10, 20];

/// Plot width in pixels.
const SIZE: f64 = 520.0;

/// Radius in pixels of the circle of a node whose weight is the mean weight of the degree-10
/// rule (`area / nodes`); every circle's area is proportional to its weight at the same scale
/// for both degrees.
const REFERENCE_RADIUS: f64 = 9.0;

/// The styles of the two degrees' nodes.
fn node_style(degree: usize, nodes: usize) -> Style {
    let label = format!("degree {degree}: {nodes} nodes");
    if degree == DEGREES[0] {
        Style::stroke("#d95f02", 1.2)
            .with_marker(Marker::Circle(5.0))
            .labelled(&label)
    } else {
        Style::stroke("#1b4f9c", 0.5)
            .with_fill("#3b7dd8", 0.55)
            .with_marker(Marker::Circle(3.0))
            .labelled(&label)
    }
}

/// The figure of `d` (named `title` in the caption, read from `source`) with the rules of
/// [`DEGREES`] (`rules[k]` of degree `DEGREES[k]`).
pub(crate) fn nodes_figure(
    d: &Domain,
    title: &str,
    source: &str,
    rules: &[CubatureRule],
) -> Figure {
    let mut fig = Figure::new(d.bounding_box(), SIZE);
    let boundary = Style::stroke("#000000", 1.3).labelled("boundary (NURBS curves)");
    for c in d.curves() {
        fig.curve(c, &boundary);
    }
    let area: f64 = rules.first().map_or(0.0, |r| r.weights().iter().sum());
    let reference_weight = rules
        .first()
        .map_or(1.0, |r| area / r.nodes().len().max(1) as f64);
    // The legend lists the degrees in increasing order; higher degrees are drawn first, so
    // that the lower degree's outlines lie on top.
    for rule in rules {
        fig.legend_entry(&node_style(rule.degree(), rule.nodes().len()));
    }
    for rule in rules.iter().rev() {
        let style = node_style(rule.degree(), rule.nodes().len());
        for (&p, &w) in rule.nodes().iter().zip(rule.weights()) {
            fig.mark_sized(p, REFERENCE_RADIUS * (w / reference_weight).sqrt(), &style);
        }
    }
    let described: Vec<String> = rules
        .iter()
        .map(|r| {
            format!(
                "degree {} ({} nodes, dim P_{} = {}, moment residual {:.1e}, smallest / largest \
                 weight {:.1e})",
                r.degree(),
                r.nodes().len(),
                r.degree(),
                dim_polynomials(r.degree()),
                r.residual(),
                min_over_max(r.weights()),
            )
        })
        .collect();
    fig.caption(&format!(
        "Positive interior cubature (inrs::cubature, Sommariva-Vianello compression) on the \
         {title} domain ({source}, even-odd area {area:.6}): the nodes of the rules of {}. Every \
         node is strictly inside and every weight positive; each circle's area is proportional \
         to its node's weight, at one scale for both degrees: a circle of radius \
         {REFERENCE_RADIUS} px holds weight {reference_weight:.4e} (area / {} nodes of degree {}).",
        described.join(" and "),
        rules.first().map_or(0, |r| r.nodes().len()),
        rules.first().map_or(0, CubatureRule::degree),
    ));
    fig
}

/// The smallest weight over the largest.
fn min_over_max(w: &[f64]) -> f64 {
    let lo = w.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = w.iter().copied().fold(0.0, f64::max);
    lo / hi
}

/// The rules of [`DEGREES`] on `d`.
pub(crate) fn rules(d: &Domain) -> Result<Vec<CubatureRule>, String> {
    DEGREES
        .iter()
        .map(|&n| CubatureRule::new(d, n).map_err(|e| format!("degree {n}: {e}")))
        .collect()
}

/// Writes `cubature_nodes_<domain>.svg` (and `.png` if `rsvg-convert` is on the path) for
/// each of [`DOMAINS`] into `dir`; returns the files written.
pub(crate) fn write(dir: &Path, root: &Path) -> Result<Vec<PathBuf>, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut written = Vec::new();
    for (stem, title) in DOMAINS {
        let source = format!("fixtures/inrs-paper/{stem}.json");
        let path = root.join(&source);
        let d = inrs::io::json::domain_from_json_file(&path)
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let rules = rules(&d).map_err(|e| format!("{stem}: {e}"))?;
        let svg = dir.join(format!("cubature_nodes_{stem}.svg"));
        written.extend(crate::figures::write_figure(
            &svg,
            &nodes_figure(&d, title, &source, &rules),
        )?);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_node_is_drawn_with_an_area_proportional_to_its_weight() {
        for (stem, title) in DOMAINS {
            let d = rs_testkit::inrs_fixture(stem).domain;
            let rules = rules(&d).unwrap();
            let svg = nodes_figure(&d, title, stem, &rules).to_svg();
            rs_testkit::assert_figure(&svg, "each circle's area is proportional", stem);
            // One circle per node, plus one legend swatch per degree (the SVG is well formed:
            // `assert_figure` parsed it).
            let circles: Vec<f64> = svg
                .split("<circle ")
                .skip(1)
                .filter_map(|c| c.split(" r=\"").nth(1)?.split('"').next()?.parse().ok())
                .collect();
            let nodes: usize = rules.iter().map(|r| r.nodes().len()).sum();
            assert_eq!(circles.len(), nodes + DEGREES.len(), "{stem}");
            // The squared radii of the degree-20 circles (drawn first) are the weights at one
            // scale: their sum over the reference circle's is the area over the mean weight.
            let r20 = &rules[1];
            let squares: f64 = circles[..r20.nodes().len()].iter().map(|r| r * r).sum();
            let ratio = squares / (REFERENCE_RADIUS * REFERENCE_RADIUS);
            let expected = rules[0].nodes().len() as f64;
            // Radii are written to 0.01 px.
            assert!(
                (ratio - expected).abs() < 1e-2 * expected,
                "{stem}: {ratio} vs {expected}"
            );
            for r in &rules {
                let label = format!("degree {}: {} nodes", r.degree(), r.nodes().len());
                assert!(svg.contains(&label), "{stem}: no {label:?}");
                assert!(r.nodes().len() <= dim_polynomials(r.degree()));
            }
            assert!(svg.contains("moment residual") && svg.contains("boundary (NURBS curves)"));
        }
    }
}
