//! A printable summary of a domain: curves, pieces, loops, orientation, area, size. It lives
//! here, not in `rs-spline`, for the filled area under a fill rule ([`crate::filled_area`]).

use std::fmt;

use rs_spline::{BoundingBox, Domain, Orientation};

use crate::{FillRule, NestingError};

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
    /// The fill rule of `filled_area`.
    pub fill_rule: FillRule,
    /// The area filled under `fill_rule`, the region the classifiers call inside with that
    /// rule ([`crate::filled_area`]), or why the loops' nesting does not decide it (open,
    /// coincident or crossing loops).
    pub filled_area: Result<f64, NestingError>,
    /// False if some piece's area quadrature stopped at its work limit before meeting its
    /// tolerance (the areas are then estimates).
    pub areas_converged: bool,
    /// Tight bounding box.
    pub bounding_box: BoundingBox,
    /// Absolute closure tolerance in force.
    pub closure_abs_tol: f64,
}

impl DomainSummary {
    /// Computes the summary of `d`, with the area it fills under the even-odd rule.
    pub fn of(d: &Domain) -> Self {
        Self::with_fill_rule(d, FillRule::EvenOdd)
    }

    /// Computes the summary of `d`, with the area it fills under `rule`.
    ///
    /// ```
    /// use rs_contain::{DomainSummary, FillRule};
    /// use rs_spline::{circle, Domain, Point};
    /// let c = |r: f64| circle(Point::new(0.0, 0.0), r).unwrap();
    /// let d = Domain::new(vec![c(2.0), c(1.0)]).unwrap(); // both counter-clockwise
    /// let pi = std::f64::consts::PI;
    /// let area = |rule| DomainSummary::with_fill_rule(&d, rule).filled_area.unwrap();
    /// assert!((area(FillRule::EvenOdd) - 3.0 * pi).abs() < 1e-12);
    /// assert!((area(FillRule::NonZero) - 4.0 * pi).abs() < 1e-12);
    /// ```
    pub fn with_fill_rule(d: &Domain, rule: FillRule) -> Self {
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
            fill_rule: rule,
            filled_area: crate::filled_area(d, rule),
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

/// `x` with the 12 significant digits a computed area or coordinate carries (the quadrature
/// and the curve arithmetic are accurate to about 1e-13 relative), in plain decimal notation
/// for moderate magnitudes, trailing zeros dropped: `5759.58333333`, `10`, `1.5e-7`.
pub fn significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let scientific = format!("{x:.11e}");
    let rounded: f64 = scientific.parse().unwrap_or(x);
    let exponent = rounded.abs().log10().floor() as i32;
    let trim = |t: String| -> String {
        if t.contains('.') {
            t.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            t
        }
    };
    if (-4..15).contains(&exponent) {
        trim(format!("{:.*}", (11 - exponent).max(0) as usize, rounded))
    } else {
        let (mantissa, exp) = scientific.split_once('e').unwrap_or((&scientific, "0"));
        format!("{}e{exp}", trim(mantissa.to_string()))
    }
}

impl fmt::Display for DomainSummary {
    /// The name, the filled area, the box, the curves, then each loop; numbers with the
    /// digits that mean something ([`significant`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let b = &self.bounding_box;
        let name = if self.name.is_empty() {
            "(unnamed domain)"
        } else {
            &self.name
        };
        writeln!(f, "{name}")?;
        let rule = self.fill_rule.as_str();
        match &self.filled_area {
            Ok(a) => writeln!(f, "  filled area ({rule}): {}", significant(*a))?,
            Err(e) => writeln!(f, "  filled area ({rule}): - ({e})")?,
        }
        writeln!(
            f,
            "  bounding box: [{}, {}] x [{}, {}]",
            significant(b.min.x),
            significant(b.max.x),
            significant(b.min.y),
            significant(b.max.y)
        )?;
        writeln!(
            f,
            "  curves: {}  Bezier pieces: {}  max degree: {}  {}  closure tolerance: {}",
            self.curves,
            self.bezier_pieces,
            self.max_degree,
            if self.rational {
                "rational"
            } else {
                "polynomial"
            },
            significant(self.closure_abs_tol)
        )?;
        for (i, l) in self.loops.iter().enumerate() {
            writeln!(
                f,
                "  loop {i}: curves {}..={}  {}  {}  signed area {}{}",
                l.curves.0,
                l.curves.1,
                if l.closed { "closed" } else { "OPEN" },
                match l.orientation {
                    Orientation::CounterClockwise => "counter-clockwise",
                    Orientation::Clockwise => "clockwise",
                    Orientation::Degenerate => "degenerate",
                },
                significant(l.signed_area),
                if l.gap > 0.0 {
                    format!("  gap {}", significant(l.gap))
                } else {
                    String::new()
                }
            )?;
        }
        write!(
            f,
            "  sum of signed loop areas: {}{}",
            significant(self.signed_area),
            if self.areas_converged {
                ""
            } else {
                "  (quadrature stopped at its work limit: estimates)"
            }
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn significant_keeps_twelve_digits_and_drops_noise() {
        assert_eq!(significant(9.999999999999996), "10");
        assert_eq!(significant(5_759.583_333_333_335), "5759.58333333");
        assert_eq!(significant(-201.061_929_829_736_33), "-201.06192983");
        assert_eq!(significant(1.1661903789690602e-7), "1.16619037897e-7");
        assert_eq!(significant(0.25), "0.25");
        assert_eq!(significant(0.0), "0");
        assert_eq!(significant(3.0e20), "3e20");
        for x in [std::f64::consts::PI, 1e-3 / 3.0, 123456.789, -7.5e-12] {
            let back: f64 = significant(x).parse().unwrap();
            assert!(
                (back - x).abs() <= 1e-11 * x.abs(),
                "{x}: {}",
                significant(x)
            );
        }
    }
}
