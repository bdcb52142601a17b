//! The curved triangulation as JSON (docs/FORMATS.md): what `inrs mesh` writes, and reading
//! it back.

use serde_json::{Value, json};

use rs_spline::{Domain, Point};

use crate::{BoundaryArc, CurvedTriangulation, EdgeKind, MeshError};

/// The mesh as JSON: vertices, counter-clockwise triangles, and the curved edges (triangle,
/// edge k from vertex k to k+1, the domain curve and its parameter range from `from` to `to`).
pub fn mesh_json(m: &CurvedTriangulation) -> String {
    mesh_value(m).to_string()
}

/// [`mesh_json`] as a JSON value (the spline file adds its own fields to it).
pub fn mesh_value(m: &CurvedTriangulation) -> Value {
    let vertices: Vec<[f64; 2]> = m.vertices().iter().map(|p| [p.x, p.y]).collect();
    let mut curved = Vec::new();
    for t in 0..m.triangles().len() {
        for (k, kind) in m.edge_kinds(t).iter().enumerate() {
            if let EdgeKind::Curved(i) = kind {
                let a = &m.arcs()[*i];
                curved.push(json!({
                    "triangle": t, "edge": k, "curve": a.curve, "loop": a.loop_index,
                    "u0": a.u0, "u1": a.u1, "from": a.from, "to": a.to,
                }));
            }
        }
    }
    json!({
        "vertices": vertices,
        "triangles": m.triangles(),
        "curved_edges": curved,
    })
}

/// The curved triangulation of `domain` held in `value` (the fields [`mesh_value`] writes),
/// checked by [`CurvedTriangulation::from_parts`].
///
/// # Errors
/// [`MeshError::Invalid`] for a missing or malformed field, or a triangulation that is not
/// one.
pub fn mesh_from_json(domain: Domain, value: &Value) -> Result<CurvedTriangulation, MeshError> {
    let invalid = |m: &str| MeshError::Invalid(m.to_string());
    let array = |key: &str| {
        value
            .get(key)
            .and_then(Value::as_array)
            .ok_or_else(|| invalid(&format!("no \"{key}\" array")))
    };
    let number = |v: &Value, what: &str| v.as_f64().ok_or_else(|| invalid(what));
    let index = |v: &Value, what: &str| {
        v.as_u64()
            .and_then(|i| usize::try_from(i).ok())
            .ok_or_else(|| invalid(what))
    };
    let vertices = array("vertices")?
        .iter()
        .map(|v| match v.as_array().map(Vec::as_slice) {
            Some([x, y]) => Ok(Point::new(
                number(x, "a vertex coordinate is not a number")?,
                number(y, "a vertex coordinate is not a number")?,
            )),
            _ => Err(invalid("a vertex is not [x, y]")),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let triangles = array("triangles")?
        .iter()
        .map(|t| match t.as_array().map(Vec::as_slice) {
            Some([a, b, c]) => {
                let i = |v| index(v, "a triangle's vertex is not an index");
                Ok([i(a)?, i(b)?, i(c)?])
            }
            _ => Err(invalid("a triangle is not [i, j, k]")),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let arcs = array("curved_edges")?
        .iter()
        .map(|e| {
            let field = |k: &str| {
                e.get(k)
                    .ok_or_else(|| invalid(&format!("a curved edge has no \"{k}\"")))
            };
            let i = |k: &str| {
                field(k)
                    .and_then(|v| index(v, &format!("curved edge field \"{k}\" is not an index")))
            };
            let u = |k: &str| {
                field(k)
                    .and_then(|v| number(v, &format!("curved edge field \"{k}\" is not a number")))
            };
            Ok(BoundaryArc {
                loop_index: i("loop")?,
                curve: i("curve")?,
                u0: u("u0")?,
                u1: u("u1")?,
                from: i("from")?,
                to: i("to")?,
                triangle: i("triangle")?,
            })
        })
        .collect::<Result<Vec<_>, MeshError>>()?;
    CurvedTriangulation::from_parts(domain, vertices, triangles, arcs)
}
