//! The curved triangulation as JSON (docs/FORMATS.md): what `inrs mesh --json` writes.

use crate::{CurvedTriangulation, EdgeKind};

/// The mesh as JSON: vertices, counter-clockwise triangles, and the curved edges (triangle,
/// edge k from vertex k to k+1, the domain curve and its parameter range from `from` to `to`).
pub fn mesh_json(m: &CurvedTriangulation) -> String {
    let vertices: Vec<[f64; 2]> = m.vertices().iter().map(|p| [p.x, p.y]).collect();
    let mut curved = Vec::new();
    for t in 0..m.triangles().len() {
        for (k, kind) in m.edge_kinds(t).iter().enumerate() {
            if let EdgeKind::Curved(i) = kind {
                let a = &m.arcs()[*i];
                curved.push(serde_json::json!({
                    "triangle": t, "edge": k, "curve": a.curve, "loop": a.loop_index,
                    "u0": a.u0, "u1": a.u1, "from": a.from, "to": a.to,
                }));
            }
        }
    }
    serde_json::json!({
        "vertices": vertices,
        "triangles": m.triangles(),
        "curved_edges": curved,
    })
    .to_string()
}
