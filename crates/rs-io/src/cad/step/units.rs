//! The units and uncertainty of a geometric representation context.
//!
//! A context (`GLOBAL_UNIT_ASSIGNED_CONTEXT`) names its length and plane angle units: an
//! `SI_UNIT` with an optional prefix, or a `CONVERSION_BASED_UNIT` (`'INCH'`, `'DEGREE'`) whose
//! conversion factor is a measure in another unit (followed at most [`MAX_UNIT_CHAIN`]
//! deep). Lengths are kept in the file's unit; only angles are converted (to radians).

use super::error::{Result, StepError};
use super::graph::{Graph, Instance, value_real};

/// Millimetres per metre (SI length units are metres with a prefix).
const MM_PER_METRE: f64 = 1000.0;

/// The longest chain of conversion-based units followed.
const MAX_UNIT_CHAIN: usize = 8;

/// The units of one representation context.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Units {
    /// Radians per plane angle unit of the file (1 for radians, `pi / 180` for degrees).
    pub radians_per_angle: f64,
    /// Millimetres per length unit of the file.
    pub mm_per_length: f64,
    /// The length unit's name, when the context states one (`MILLIMETRE`, `INCH`).
    pub length_name: Option<String>,
    /// The context's length uncertainty in its length unit, if it states one.
    pub uncertainty: Option<f64>,
}

impl Default for Units {
    /// Radians and millimetres (ISO 10303-41's defaults are SI, but AP203/214 files always
    /// state theirs; `OpenCASCADE` assumes millimetres), no uncertainty.
    fn default() -> Self {
        Self {
            radians_per_angle: 1.0,
            mm_per_length: 1.0,
            length_name: None,
            uncertainty: None,
        }
    }
}

/// The units of the context `#label`; anything missing or unreadable keeps its default.
/// Unit errors are not fatal: a face's geometry is read in the file's numbers either way, and
/// only the angle factor changes values (reported when it is not positive and finite).
pub(crate) fn context_units(g: &Graph, label: u64) -> Result<Units> {
    let mut u = Units::default();
    let Ok(ctx) = g.get(label, "a representation") else {
        return Ok(u);
    };
    if let Ok(a) = ctx.record("GLOBAL_UNIT_ASSIGNED_CONTEXT")
        && let Ok(units) = a.refs(0, "units")
    {
        for r in units.into_iter().take(16) {
            let Ok(unit) = g.get(r, &ctx.what()) else {
                continue;
            };
            if unit.is("LENGTH_UNIT") {
                if let Some(f) = unit_factor(g, unit, 0) {
                    u.mm_per_length = f * MM_PER_METRE;
                    u.length_name = Some(unit_name(unit));
                }
            } else if unit.is("PLANE_ANGLE_UNIT")
                && let Some(f) = unit_factor(g, unit, 0)
            {
                if !(f.is_finite() && f > 0.0) {
                    return Err(StepError::BadNumber {
                        what: unit.what(),
                        name: "plane angle unit factor",
                        value: f,
                    });
                }
                u.radians_per_angle = f;
            }
        }
    }
    if let Ok(a) = ctx.record("GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT")
        && let Ok(list) = a.refs(0, "uncertainty")
    {
        for r in list.into_iter().take(16) {
            let Ok(m) = g.get(r, &ctx.what()) else {
                continue;
            };
            let Ok(rec) = m.record("UNCERTAINTY_MEASURE_WITH_UNIT") else {
                continue;
            };
            let Some(value) = rec.get(0, "value_component").ok().and_then(value_real) else {
                continue;
            };
            let Ok(unit) = rec
                .reference(1, "unit_component")
                .and_then(|r| g.get(r, &m.what()))
            else {
                continue;
            };
            if !unit.is("LENGTH_UNIT") {
                continue;
            }
            // The measure's unit may differ from the context's length unit.
            let scale = unit_factor(g, unit, 0).map_or(1.0, |f| f * MM_PER_METRE / u.mm_per_length);
            let t = (value * scale).abs();
            if t.is_finite() && t > 0.0 {
                u.uncertainty = Some(u.uncertainty.map_or(t, |v: f64| v.max(t)));
            }
        }
    }
    Ok(u)
}

/// The name of a unit: an SI unit's prefix and name (`MILLIMETRE`), a conversion-based unit's
/// own name (`INCH`), else its type.
fn unit_name(unit: &Instance) -> String {
    use super::graph::Value;
    if let Ok(si) = unit.record("SI_UNIT") {
        let prefix = match si.get(0, "prefix") {
            Ok(Value::Enum(p)) => p.as_str(),
            _ => "",
        };
        let name = match si.get(1, "name") {
            Ok(Value::Enum(n)) => n.as_str(),
            _ => "",
        };
        return format!("{prefix}{name}");
    }
    if let Ok(cb) = unit.record("CONVERSION_BASED_UNIT")
        && let Ok(Value::Str(n)) = cb.get(0, "name")
    {
        return n.clone();
    }
    unit.type_name()
}

/// SI base units (metre, radian) per unit of `unit`.
fn unit_factor(g: &Graph, unit: &Instance, depth: usize) -> Option<f64> {
    if depth > MAX_UNIT_CHAIN {
        return None;
    }
    if let Ok(si) = unit.record("SI_UNIT") {
        let prefix = match si.get(0, "prefix").ok()? {
            super::graph::Value::Enum(p) => prefix_factor(p)?,
            _ => 1.0,
        };
        return Some(prefix);
    }
    if let Ok(cb) = unit.record("CONVERSION_BASED_UNIT") {
        let m = g.get(cb.reference(1, "conversion_factor").ok()?, "").ok()?;
        let rec = m
            .parts
            .iter()
            .find(|p| p.name.ends_with("MEASURE_WITH_UNIT"))?;
        let value = rec.params.first().and_then(value_real)?;
        let inner = match rec.params.get(1)? {
            super::graph::Value::Ref(r) => g.get(*r, "").ok()?,
            _ => return None,
        };
        return Some(value * unit_factor(g, inner, depth + 1)?);
    }
    None
}

fn prefix_factor(p: &str) -> Option<f64> {
    Some(match p {
        "EXA" => 1e18,
        "PETA" => 1e15,
        "TERA" => 1e12,
        "GIGA" => 1e9,
        "MEGA" => 1e6,
        "KILO" => 1e3,
        "HECTO" => 1e2,
        "DECA" => 1e1,
        "DECI" => 1e-1,
        "CENTI" => 1e-2,
        "MILLI" => 1e-3,
        "MICRO" => 1e-6,
        "NANO" => 1e-9,
        "PICO" => 1e-12,
        "FEMTO" => 1e-15,
        "ATTO" => 1e-18,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn millimetres_degrees_and_uncertainty() {
        let text = "ISO-10303-21;HEADER;ENDSEC;DATA;
#1=(GEOMETRIC_REPRESENTATION_CONTEXT(2)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#5))GLOBAL_UNIT_ASSIGNED_CONTEXT((#2,#3,#6))REPRESENTATION_CONTEXT('',''));
#2=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));
#3=(CONVERSION_BASED_UNIT('DEGREE',#4)NAMED_UNIT(*)PLANE_ANGLE_UNIT());
#4=PLANE_ANGLE_MEASURE_WITH_UNIT(PLANE_ANGLE_MEASURE(0.0174532925199433),#7);
#7=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));
#6=(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT());
#5=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#2,'distance_accuracy_value','');
ENDSEC;END-ISO-10303-21;";
        let g = Graph::parse(text.as_bytes()).unwrap();
        let u = context_units(&g, 1).unwrap();
        assert_eq!(u.mm_per_length, 1.0);
        assert_eq!(u.length_name.as_deref(), Some("MILLIMETRE"));
        assert!((u.radians_per_angle - std::f64::consts::PI / 180.0).abs() < 1e-15);
        assert_eq!(u.uncertainty, Some(1e-7));
    }
}
