//! Points, directions, placements and B-spline records read from instances, in 2-D and 3-D.

use rs_spline::limits::{MAX_COORDINATE, MAX_DEGREE};

use super::graph::{Attrs, Graph, Instance, value_count, value_real};

/// A 3-D vector.
pub(crate) type V3 = [f64; 3];

pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub(crate) fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub(crate) fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}
pub(crate) fn dist(a: V3, b: V3) -> f64 {
    norm(sub(a, b))
}

/// A right-handed orthonormal frame: origin and axes.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame {
    pub(crate) origin: V3,
    pub(crate) x: V3,
    pub(crate) y: V3,
    pub(crate) z: V3,
}

/// The coordinates of a `CARTESIAN_POINT` (2 or 3 of them; a 2-D point gets `z = 0`),
/// each finite and within [`MAX_COORDINATE`].
pub(crate) fn point(g: &Graph, label: u64, from: &str) -> Result<V3, String> {
    let inst = g.get(label, from)?;
    let a = inst.record("CARTESIAN_POINT")?;
    coords(&a, 1, "coordinates")
}

fn coords(a: &Attrs<'_>, i: usize, name: &str) -> Result<V3, String> {
    let v = a.reals(i, name)?;
    if !(1..=3).contains(&v.len()) {
        return Err(format!("{}: {} coordinates", a.inst.what(), v.len()));
    }
    if v.iter().any(|x| x.abs() > MAX_COORDINATE) {
        return Err(format!(
            "{}: coordinate beyond {MAX_COORDINATE:e}",
            a.inst.what()
        ));
    }
    let mut p = [0.0; 3];
    p[..v.len()].copy_from_slice(&v);
    Ok(p)
}

/// A `DIRECTION`, normalised; a zero direction is an error.
pub(crate) fn direction(g: &Graph, label: u64, from: &str) -> Result<V3, String> {
    let inst = g.get(label, from)?;
    let a = inst.record("DIRECTION")?;
    let d = coords(&a, 1, "direction_ratios")?;
    unit(d).ok_or_else(|| format!("{}: zero direction", inst.what()))
}

pub(crate) fn unit(d: V3) -> Option<V3> {
    let n = norm(d);
    (n > 0.0 && n.is_finite()).then(|| scale(d, 1.0 / n))
}

/// `AXIS2_PLACEMENT_2D` or `AXIS2_PLACEMENT_3D` as a frame (2-D: `z = (0, 0, 1)`). The
/// reference direction is made orthogonal to the axis (ISO 10303-42 `build_axes`); defaults
/// are the global axes.
pub(crate) fn placement(g: &Graph, label: u64, from: &str) -> Result<Frame, String> {
    let inst = g.get(label, from)?;
    let (a, three_d) = if let Ok(a) = inst.record("AXIS2_PLACEMENT_3D") {
        (a, true)
    } else {
        (inst.record("AXIS2_PLACEMENT_2D")?, false)
    };
    let what = inst.what();
    let origin = point(g, a.reference(1, "location")?, &what)?;
    let opt_dir = |i: usize, name: &str| -> Result<Option<V3>, String> {
        match a.get(i, name) {
            Ok(super::graph::Value::Ref(r)) => direction(g, *r, &what).map(Some),
            Ok(super::graph::Value::Unset) | Err(_) => Ok(None),
            Ok(_) => Err(format!("{what}: {name} is not a reference")),
        }
    };
    let (z, xref) = if three_d {
        (
            opt_dir(2, "axis")?.unwrap_or([0.0, 0.0, 1.0]),
            opt_dir(3, "ref_direction")?,
        )
    } else {
        ([0.0, 0.0, 1.0], opt_dir(2, "ref_direction")?)
    };
    let mut xr = xref.unwrap_or([1.0, 0.0, 0.0]);
    xr[2] = if three_d { xr[2] } else { 0.0 };
    let mut x = unit(sub(xr, scale(z, dot(xr, z))));
    if x.is_none() {
        // The reference direction is along the axis: any perpendicular will do.
        let alt = if z[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        x = unit(sub(alt, scale(z, dot(alt, z))));
    }
    let x = x.ok_or_else(|| format!("{what}: degenerate axes"))?;
    Ok(Frame {
        origin,
        x,
        y: cross(z, x),
        z,
    })
}

/// The data of a B-spline curve record, simple (`B_SPLINE_CURVE_WITH_KNOTS`) or complex
/// (`B_SPLINE_CURVE` + `B_SPLINE_CURVE_WITH_KNOTS` + `RATIONAL_B_SPLINE_CURVE`).
#[derive(Clone, Debug)]
pub(crate) struct BSplineData {
    pub(crate) degree: usize,
    pub(crate) points: Vec<V3>,
    pub(crate) knots: Vec<f64>,
    pub(crate) weights: Option<Vec<f64>>,
}

/// Reads a B-spline curve. Multiplicities are checked against the number of control points
/// before the knot vector is expanded, so a claimed huge multiplicity allocates nothing.
pub(crate) fn bspline(g: &Graph, inst: &Instance) -> Result<BSplineData, String> {
    let what = inst.what();
    // Attribute positions: (degree, points) and (mults, knots) records.
    let (curve, c0, knots_rec, k0) = if inst.is_complex() {
        (
            inst.record("B_SPLINE_CURVE")?,
            0,
            inst.record("B_SPLINE_CURVE_WITH_KNOTS")?,
            0,
        )
    } else {
        let a = inst.record("B_SPLINE_CURVE_WITH_KNOTS")?;
        (a, 1, a, 6)
    };
    let degree = curve.count(c0, "degree", MAX_DEGREE)?;
    if degree == 0 {
        return Err(format!("{what}: degree 0"));
    }
    let refs = curve.refs(c0 + 1, "control_points_list")?;
    let points = refs
        .iter()
        .map(|&r| point(g, r, &what))
        .collect::<Result<Vec<_>, _>>()?;
    let n = points.len();
    if n <= degree {
        return Err(format!("{what}: {n} control points for degree {degree}"));
    }
    let mults = knots_rec.list(k0, "knot_multiplicities")?;
    let kv = knots_rec.reals(k0 + 1, "knots")?;
    if mults.len() != kv.len() {
        return Err(format!(
            "{what}: {} knot multiplicities for {} knots",
            mults.len(),
            kv.len()
        ));
    }
    let total = n + degree + 1;
    let mut knots = Vec::new();
    for (m, k) in mults.iter().zip(&kv) {
        let m = value_real(m)
            .and_then(|m| value_count(m, total))
            .ok_or_else(|| format!("{what}: knot multiplicity is not a whole number <= {total}"))?;
        if knots.len() + m > total {
            return Err(format!(
                "{what}: the knot multiplicities add up to more than {total} ({n} control points, degree {degree})"
            ));
        }
        knots.extend(std::iter::repeat_n(*k, m));
    }
    if knots.len() != total {
        return Err(format!(
            "{what}: {} knots for {n} control points of degree {degree} (need {total})",
            knots.len()
        ));
    }
    if knots.windows(2).any(|w| w[1] < w[0]) {
        return Err(format!("{what}: decreasing knots"));
    }
    let weights = if let Ok(r) = inst.record("RATIONAL_B_SPLINE_CURVE") {
        let w = r.reals(0, "weights_data")?;
        if w.len() != n {
            return Err(format!(
                "{what}: {} weights for {n} control points",
                w.len()
            ));
        }
        Some(w)
    } else {
        None
    };
    Ok(BSplineData {
        degree,
        points,
        knots,
        weights,
    })
}
