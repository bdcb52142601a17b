//! The spline file (JSON, docs/FORMATS.md): everything needed to evaluate the spline
//! anywhere in its domain, from the file alone.
//!
//! ```json
//! {"space": "s0", "degree": 2,
//!  "domain": {"curves": [...]},
//!  "vertices": [[x, y], ...], "triangles": [[i, j, k], ...], "curved_edges": [...],
//!  "coefficients": [[c_200, c_110, c_101, c_020, c_011, c_002], ...]}
//! ```
//!
//! `domain` is a domain file, `vertices`, `triangles` and `curved_edges` are what `inrs mesh`
//! writes, and `coefficients` holds per triangle its `C(d + 2, 2)` Bernstein–Bézier
//! coefficients `c_ijk` (`i` for its first vertex, `j` second, `k` third) by decreasing `i`,
//! then decreasing `j`.

use std::path::Path;

use serde_json::{Value, json};

use crate::bb::coefficient_count;
use crate::{SpaceKind, Spline, TriSplineError};

/// The largest spline file read (the domain, the mesh and the coefficients together).
pub const MAX_SPLINE_FILE_BYTES: u64 = 1 << 30;

/// The spline as the JSON of a spline file.
pub fn spline_to_json(s: &Spline) -> String {
    let mut value = rs_mesh::mesh_value(s.mesh());
    let domain: Value = serde_json::from_str(&rs_io::json::domain_to_json(s.mesh().domain()))
        .unwrap_or(Value::Null);
    let n = coefficient_count(s.degree());
    let coefficients: Vec<&[f64]> = s.coefficients().chunks(n).collect();
    if let Value::Object(map) = &mut value {
        map.insert("space".into(), json!(s.kind().name()));
        map.insert("degree".into(), json!(s.degree()));
        map.insert("domain".into(), domain);
        map.insert("coefficients".into(), json!(coefficients));
    }
    value.to_string()
}

/// The spline of a spline file's JSON text.
///
/// # Errors
/// [`TriSplineError::File`] for malformed JSON or fields, [`TriSplineError::Io`] for a bad
/// embedded domain, [`TriSplineError::Mesh`] for a triangulation that is not one.
pub fn spline_from_json(text: &str) -> Result<Spline, TriSplineError> {
    let bad = |m: String| TriSplineError::File(m);
    let value: Value = serde_json::from_str(text).map_err(|e| bad(e.to_string()))?;
    let space = value
        .get("space")
        .and_then(Value::as_str)
        .ok_or_else(|| bad("no \"space\"".into()))?;
    let kind =
        SpaceKind::from_name(space).ok_or_else(|| bad(format!("unknown space {space:?}")))?;
    let degree = value
        .get("degree")
        .and_then(Value::as_u64)
        .ok_or_else(|| bad("no \"degree\"".into()))?;
    let degree = usize::try_from(degree).map_err(|_| TriSplineError::Degree(usize::MAX))?;
    if !(1..=crate::bb::MAX_DEGREE).contains(&degree) {
        return Err(TriSplineError::Degree(degree));
    }
    let domain = value
        .get("domain")
        .ok_or_else(|| bad("no \"domain\"".into()))?;
    let domain = rs_io::json::domain_from_json(&domain.to_string())?;
    let mesh = rs_mesh::mesh_from_json(domain, &value)?;
    let n = coefficient_count(degree);
    let rows = value
        .get("coefficients")
        .and_then(Value::as_array)
        .ok_or_else(|| bad("no \"coefficients\" array".into()))?;
    if rows.len() != mesh.triangles().len() {
        return Err(bad(format!(
            "{} coefficient arrays for {} triangles",
            rows.len(),
            mesh.triangles().len()
        )));
    }
    let mut coefficients = Vec::with_capacity(rows.len() * n);
    for (t, row) in rows.iter().enumerate() {
        let row = row
            .as_array()
            .filter(|r| r.len() == n)
            .ok_or_else(|| bad(format!("triangle {t}: expected {n} coefficients")))?;
        for c in row {
            let v = c.as_f64().filter(|v| v.is_finite()).ok_or_else(|| {
                bad(format!(
                    "triangle {t}: a coefficient is not a finite number"
                ))
            })?;
            coefficients.push(v);
        }
    }
    Spline::new(mesh, degree, kind, coefficients)
}

/// Writes a spline file.
///
/// # Errors
/// [`TriSplineError::File`] naming the file.
pub fn save_spline(s: &Spline, path: impl AsRef<Path>) -> Result<(), TriSplineError> {
    let path = path.as_ref();
    std::fs::write(path, spline_to_json(s))
        .map_err(|e| TriSplineError::File(format!("{}: {e}", path.display())))
}

/// Reads a spline file (at most [`MAX_SPLINE_FILE_BYTES`]).
///
/// # Errors
/// As [`spline_from_json`], and [`TriSplineError::File`] if it cannot be read.
pub fn load_spline(path: impl AsRef<Path>) -> Result<Spline, TriSplineError> {
    let path = path.as_ref();
    let size = std::fs::metadata(path)
        .map_err(|e| TriSplineError::File(format!("{}: {e}", path.display())))?
        .len();
    if size > MAX_SPLINE_FILE_BYTES {
        return Err(TriSplineError::File(format!(
            "{}: {size} bytes exceed the limit {MAX_SPLINE_FILE_BYTES}",
            path.display()
        )));
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| TriSplineError::File(format!("{}: {e}", path.display())))?;
    spline_from_json(&text)
}
