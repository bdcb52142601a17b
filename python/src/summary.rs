//! `DomainSummary` and `LoopSummary`: what `Domain.summary()` returns, with named read-only
//! attributes.

use pyo3::prelude::*;

use inrs::Domain;
use inrs::contain::FillRule;

/// Facts about one boundary loop (an item of [`DomainSummary::loops`]).
#[pyclass(module = "inrs._inrs", name = "LoopSummary", frozen, get_all)]
#[derive(Clone)]
pub(crate) struct LoopSummary {
    /// Index of the loop's first curve.
    first_curve: usize,
    /// Index of its last curve (the loop is the curves `first_curve..=last_curve`).
    last_curve: usize,
    /// Whether the loop closes within the domain's closure tolerance.
    closed: bool,
    /// Distance from its end to its start.
    gap: f64,
    /// Signed area, positive counter-clockwise (closed by the chord if open).
    signed_area: f64,
}

#[pymethods]
impl LoopSummary {
    fn __repr__(&self) -> String {
        format!(
            "LoopSummary(first_curve={}, last_curve={}, closed={}, gap={}, signed_area={})",
            self.first_curve,
            self.last_curve,
            py_bool(self.closed),
            self.gap,
            self.signed_area
        )
    }
}

/// Facts about a domain, as `inrs info` prints them.
#[pyclass(module = "inrs._inrs", name = "DomainSummary", frozen, get_all)]
pub(crate) struct DomainSummary {
    /// Number of NURBS curves.
    curves: usize,
    /// Number of rational Bezier pieces after knot insertion.
    bezier_pieces: usize,
    /// Largest curve degree.
    max_degree: usize,
    /// Whether some weights differ (the boundary is genuinely rational).
    rational: bool,
    /// The boundary loops, in order.
    loops: Vec<LoopSummary>,
    /// The fill rule of `filled_area` (`even-odd` or `nonzero`).
    fill_rule: &'static str,
    /// The area filled under `fill_rule` (holes subtracted), the region `classify` calls
    /// inside with that rule; `None` for open, coincident or crossing loops
    /// (`Domain.filled_area` says which).
    filled_area: Option<f64>,
    /// Sum of the loops' signed areas.
    signed_area: f64,
    /// Whether every area quadrature met its tolerance (otherwise the areas are estimates).
    areas_converged: bool,
    /// `(xmin, ymin, xmax, ymax)` of the curves.
    bounds: (f64, f64, f64, f64),
}

impl DomainSummary {
    /// The summary of `domain` with the area it fills under `rule`
    /// ([`inrs::DomainSummary::with_fill_rule`]).
    pub(crate) fn of(domain: &Domain, rule: FillRule) -> Self {
        let s = inrs::DomainSummary::with_fill_rule(domain, rule);
        let b = s.bounding_box;
        Self {
            curves: s.curves,
            bezier_pieces: s.bezier_pieces,
            max_degree: s.max_degree,
            rational: s.rational,
            loops: s
                .loops
                .iter()
                .map(|l| LoopSummary {
                    first_curve: l.curves.0,
                    last_curve: l.curves.1,
                    closed: l.closed,
                    gap: l.gap,
                    signed_area: l.signed_area,
                })
                .collect(),
            fill_rule: rule.as_str(),
            filled_area: s.filled_area.ok(),
            signed_area: s.signed_area,
            areas_converged: s.areas_converged,
            bounds: (b.min.x, b.min.y, b.max.x, b.max.y),
        }
    }
}

#[pymethods]
impl DomainSummary {
    fn __repr__(&self) -> String {
        let filled = self
            .filled_area
            .map_or_else(|| "None".to_string(), |a| a.to_string());
        let (x0, y0, x1, y1) = self.bounds;
        format!(
            "DomainSummary(curves={}, loops={}, filled_area={filled}, signed_area={}, bounds=({x0}, {y0}, {x1}, {y1}))",
            self.curves,
            self.loops.len(),
            self.signed_area
        )
    }
}

/// `True` or `False`, as Python prints them.
fn py_bool(b: bool) -> &'static str {
    if b { "True" } else { "False" }
}
