//! A printable summary of a domain: curves, pieces, loops, orientation, area, size.

use std::fmt;

use rs_spline::{BoundingBox, Domain, Orientation};

/// Facts about one boundary loop.
#[derive(Clone, Debug, PartialEq)]
pub struct LoopSummary {
    /// First and last curve index.
    pub curves: (usize, usize),
    /// Whether the loop closes within the domain's tolerance.
    pub closed: bool,
    /// Distance from its end to its start.
    pub gap: f64,
    /// Signed area (closed by the chord if open).
    pub signed_area: f64,
    /// Orientation from the sign of the area.
    pub orientation: Orientation,
}

/// Facts about a domain, as printed by `inrs info` and `cargo xtask demo`.
#[derive(Clone, Debug, PartialEq)]
pub struct DomainSummary {
    /// The domain's name (empty if none).
    pub name: String,
    /// Number of NURBS curves.
    pub curves: usize,
    /// Number of rational Bezier pieces after extraction.
    pub bezier_pieces: usize,
    /// Largest curve degree.
    pub max_degree: usize,
    /// True if some weights differ (the boundary is genuinely rational).
    pub rational: bool,
    /// The loops.
    pub loops: Vec<LoopSummary>,
    /// Sum of the loops' signed areas (the area when outer loops run counter-clockwise and
    /// holes clockwise).
    pub signed_area: f64,
    /// The area filled under the even-odd rule, the region the crossing methods classify
    /// ([`rs_contain::even_odd_area`]); `None` for open or coincident loops.
    pub filled_area: Option<f64>,
    /// False if some piece's area quadrature stopped at its work limit before meeting its
    /// tolerance (the areas are then estimates).
    pub areas_converged: bool,
    /// Tight bounding box.
    pub bounding_box: BoundingBox,
    /// Absolute closure tolerance in force.
    pub closure_abs_tol: f64,
}

impl DomainSummary {
    /// Computes the summary of `d`.
    pub fn of(d: &Domain) -> Self {
        let areas: Vec<_> = (0..d.loops().len())
            .map(|i| d.loop_area_integral(i))
            .collect();
        let loops = d
            .loops()
            .iter()
            .enumerate()
            .map(|(i, l)| LoopSummary {
                curves: (*l.curves().start(), *l.curves().end()),
                closed: l.is_closed(),
                gap: l.gap(),
                signed_area: areas[i].value,
                orientation: d.loop_orientation(i),
            })
            .collect::<Vec<_>>();
        Self {
            name: d.name().unwrap_or_default().to_string(),
            curves: d.curves().len(),
            bezier_pieces: d.bezier_pieces().len(),
            max_degree: d.curves().iter().map(|c| c.degree()).max().unwrap_or(0),
            rational: d.curves().iter().any(|c| !c.is_polynomial()),
            signed_area: loops.iter().map(|l| l.signed_area).sum(),
            filled_area: rs_contain::even_odd_area(d),
            areas_converged: areas.iter().all(|a| a.converged),
            loops,
            bounding_box: d.bounding_box(),
            closure_abs_tol: d.closure_abs_tol(),
        }
    }

    /// True if every loop is closed.
    pub fn is_closed(&self) -> bool {
        self.loops.iter().all(|l| l.closed)
    }
}

impl fmt::Display for DomainSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = &self.bounding_box;
        writeln!(
            f,
            "{}",
            if self.name.is_empty() {
                "(unnamed domain)"
            } else {
                &self.name
            }
        )?;
        writeln!(
            f,
            "  curves: {}  bezier pieces: {}  max degree: {}  {}",
            self.curves,
            self.bezier_pieces,
            self.max_degree,
            if self.rational {
                "rational"
            } else {
                "polynomial"
            }
        )?;
        match self.filled_area {
            Some(a) => writeln!(f, "  filled area (even-odd): {a:.15}")?,
            None => writeln!(f, "  filled area (even-odd): - (open or coincident loops)")?,
        }
        writeln!(
            f,
            "  bounding box: [{}, {}] x [{}, {}]  closure tolerance: {:e}",
            b.min.x, b.max.x, b.min.y, b.max.y, self.closure_abs_tol
        )?;
        for (i, l) in self.loops.iter().enumerate() {
            writeln!(
                f,
                "  loop {i}: curves {}..={}  {}  {:?}  signed area {:.15}  gap {:e}",
                l.curves.0,
                l.curves.1,
                if l.closed { "closed" } else { "OPEN" },
                l.orientation,
                l.signed_area,
                l.gap
            )?;
        }
        write!(
            f,
            "  sum of signed loop areas: {:.15}{}",
            self.signed_area,
            if self.areas_converged {
                ""
            } else {
                "  (quadrature stopped at its work limit: estimates)"
            }
        )
    }
}
