//! The curve file of `inrs convex-domain`: one curve, planar or spatial.

use std::path::Path;

use rs_spline::NurbsCurve;

use crate::{Point3, Sign, SignNumerator, SpaceCurve};
use serde_json::Value;

use crate::ConvexError;

/// A curve whose control point will move.
#[derive(Clone, Debug, PartialEq)]
pub enum FreeCurve {
    /// A planar NURBS (curvature sign).
    Planar(NurbsCurve),
    /// A space NURBS (torsion sign).
    Space(SpaceCurve),
}

impl FreeCurve {
    /// 2 or 3.
    pub fn dimension(&self) -> usize {
        match self {
            FreeCurve::Planar(_) => 2,
            FreeCurve::Space(_) => 3,
        }
    }

    /// Number of control points.
    pub fn control_point_count(&self) -> usize {
        match self {
            FreeCurve::Planar(c) => c.control_points().len(),
            FreeCurve::Space(c) => c.weights().len(),
        }
    }

    /// Control point `i` (`z = 0` in the plane), if it exists.
    pub fn control_point(&self, i: usize) -> Option<Point3> {
        match self {
            FreeCurve::Planar(c) => c
                .control_points()
                .get(i)
                .map(|p| Point3::new(p.x, p.y, 0.0)),
            FreeCurve::Space(c) => c.control_points().get(i).copied(),
        }
    }

    /// The sign numerator with control point `free` moving.
    ///
    /// # Errors
    /// [`ConvexError::Spline`] if `free` is out of range.
    pub fn numerator(&self, free: usize) -> Result<SignNumerator, ConvexError> {
        Ok(match self {
            FreeCurve::Planar(c) => SignNumerator::curvature(c, free)?,
            FreeCurve::Space(c) => SignNumerator::torsion(c, free)?,
        })
    }

    /// The sign the given curve has, for keeping it: the sign of `h` (its numerator with
    /// control point `free` moving) at the middle of the first piece, evaluated at the control
    /// point where it is ([`Sign::Positive`] at zero).
    pub fn own_sign(&self, free: usize, h: &SignNumerator) -> Sign {
        let d = self.control_point(free).unwrap_or_default();
        if h.at(0, 0.5).eval(d) >= 0.0 {
            Sign::Positive
        } else {
            Sign::Negative
        }
    }
}

/// Parses a curve: either a domain file (`{"curves": [...]}`, curve `index` taken, every form
/// of docs/FORMATS.md accepted) or a single curve object `{"degree", "control_points", "knots"?,
/// "weights"?}` whose control points have two (plane) or three (space) coordinates.
///
/// # Errors
/// [`ConvexError::CurveFile`] naming what is wrong, or the curve's own errors.
pub fn parse_curve(text: &str, index: usize) -> Result<FreeCurve, ConvexError> {
    let bad = |m: String| ConvexError::CurveFile(m);
    let v: Value = serde_json::from_str(text).map_err(|e| bad(e.to_string()))?;
    let curve = match v.get("curves") {
        Some(Value::Array(a)) => a
            .get(index)
            .ok_or_else(|| bad(format!("no curve {index} (the file has {})", a.len())))?
            .clone(),
        Some(_) => return Err(bad("\"curves\" must be an array".into())),
        None if index == 0 => v,
        None => return Err(bad(format!("a single-curve file has no curve {index}"))),
    };
    let is_space = curve
        .get("control_points")
        .and_then(|p| p.get(0))
        .and_then(Value::as_array)
        .is_some_and(|p| p.len() == 3);
    if !is_space {
        return Ok(FreeCurve::Planar(rs_io::json::curve_from_json(
            index, &curve,
        )?));
    }
    let degree = curve
        .get("degree")
        .and_then(Value::as_u64)
        .ok_or_else(|| bad("\"degree\" must be a positive integer".into()))?
        as usize;
    let numbers = |key: &str| -> Result<Option<Vec<f64>>, ConvexError> {
        match curve.get(key) {
            None => Ok(None),
            Some(Value::Array(a)) => a
                .iter()
                .map(|x| {
                    x.as_f64()
                        .ok_or_else(|| bad(format!("\"{key}\" must hold numbers")))
                })
                .collect::<Result<Vec<_>, _>>()
                .map(Some),
            Some(_) => Err(bad(format!("\"{key}\" must be an array of numbers"))),
        }
    };
    let points: Vec<Point3> = curve["control_points"]
        .as_array()
        .ok_or_else(|| bad("\"control_points\" must be an array".into()))?
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let c: Option<Vec<f64>> = p
                .as_array()
                .and_then(|a| a.iter().map(Value::as_f64).collect());
            match c.as_deref() {
                Some(&[x, y, z]) => Ok(Point3::new(x, y, z)),
                _ => Err(bad(format!("control point {i} must be [x, y, z]"))),
            }
        })
        .collect::<Result<_, _>>()?;
    let weights = numbers("weights")?;
    let curve = match numbers("knots")? {
        Some(knots) => SpaceCurve::new(degree, knots, &points, weights)?,
        None => {
            if points.len() != degree + 1 {
                return Err(ConvexError::Spline(rs_spline::SplineError::MissingKnots {
                    needed: degree + 1,
                    got: points.len(),
                }));
            }
            SpaceCurve::bezier(&points, weights)?
        }
    };
    Ok(FreeCurve::Space(curve))
}

/// [`parse_curve`] on a file.
///
/// # Errors
/// [`ConvexError::CurveFile`] if the file cannot be read, then as [`parse_curve`].
pub fn load_curve(path: impl AsRef<Path>, index: usize) -> Result<FreeCurve, ConvexError> {
    let path = path.as_ref();
    let text = rs_spline::limits::read_text_file(path)
        .map_err(|e| ConvexError::CurveFile(format!("{}: {e}", path.display())))?;
    parse_curve(&text, index)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planar_and_space_curves_parse() {
        let p = parse_curve(r#"{"degree": 2, "control_points": [[0,0],[1,1],[2,0]]}"#, 0).unwrap();
        assert_eq!(p.dimension(), 2);
        let s = parse_curve(
            r#"{"degree": 3, "control_points": [[0,0,0],[1,0,0],[1,1,0],[1,1,1]], "weights": [1,2,2,1]}"#,
            0,
        )
        .unwrap();
        assert_eq!(s.dimension(), 3);
        assert_eq!(s.control_point(3), Some(Point3::new(1.0, 1.0, 1.0)));
        let d = parse_curve(
            r#"{"curves": [{"circle": {"center": [0,0], "radius": 1}}]}"#,
            0,
        )
        .unwrap();
        assert_eq!(d.dimension(), 2);
        for (text, want) in [
            ("[", "curve file"),
            (r#"{"curves": []}"#, "no curve 0"),
            (
                r#"{"degree": 1, "control_points": [[0,0,0],[1,"a",0]]}"#,
                "control point 1",
            ),
            (
                r#"{"degree": 3, "control_points": [[0,0,0],[1,0,0]]}"#,
                "knots",
            ),
        ] {
            let e = parse_curve(text, 0).unwrap_err().to_string();
            assert!(e.contains(want), "{text}: {e}");
        }
    }
}
