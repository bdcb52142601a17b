//! The reference data stored beside the curves in a fixture file: the one parser of it, for
//! the tests, the demo and the benchmarks.

use std::path::Path;

use rs_spline::{BoundingBox, Domain, Point};
use serde_json::Value;

/// A fixture file: its domain and the reference numbers its metadata records.
#[derive(Clone, Debug)]
pub struct FixtureMeta {
    /// The domain.
    pub domain: Domain,
    /// `signed_area`, if recorded.
    pub signed_area: Option<f64>,
    /// `orientation` (`"ccw"` or `"cw"`), if recorded.
    pub orientation: Option<String>,
    /// `bbox_xmin_xmax_ymin_ymax`: the box the reference Halton points were mapped to.
    pub reference_box: Option<BoundingBox>,
    /// Reference inside counts `(N, count)` of the first `N` Halton points in that box (the
    /// paper protocol's counts and the 10^4 check), ascending in `N`.
    pub inside_counts: Vec<(usize, usize)>,
}

impl FixtureMeta {
    /// Reads a fixture file.
    ///
    /// # Errors
    /// A message naming the file if it cannot be read or is not a domain file.
    pub fn load(path: &Path) -> Result<Self, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let meta: Value =
            serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let domain =
            rs_io::json::domain_from_json(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        Ok(Self {
            domain,
            signed_area: meta.get("signed_area").and_then(Value::as_f64),
            orientation: meta
                .get("orientation")
                .and_then(Value::as_str)
                .map(str::to_string),
            reference_box: reference_box(&meta),
            inside_counts: inside_counts(&meta),
        })
    }
}

impl FixtureMeta {
    /// The reference inside count of the first `n` Halton points of [`FixtureMeta::reference_box`],
    /// if the file records one.
    pub fn inside_count(&self, n: usize) -> Option<usize> {
        self.inside_counts
            .iter()
            .find(|&&(m, _)| m == n)
            .map(|&(_, c)| c)
    }
}

fn reference_box(meta: &Value) -> Option<BoundingBox> {
    let b: Vec<f64> = meta
        .get("bbox_xmin_xmax_ymin_ymax")?
        .as_array()?
        .iter()
        .filter_map(Value::as_f64)
        .collect();
    (b.len() == 4).then(|| BoundingBox {
        min: Point::new(b[0], b[2]),
        max: Point::new(b[1], b[3]),
    })
}

fn inside_counts(meta: &Value) -> Vec<(usize, usize)> {
    let refs = &meta["reference_inside_counts_halton"];
    let mut out: Vec<(usize, usize)> = Vec::new();
    if let Some(paper) = refs["paper_protocol"].as_object() {
        for (n, r) in paper {
            if let (Ok(n), Some(c)) = (n.parse(), r["inRS_nbox200_safe1_in"].as_u64()) {
                out.push((n, c as usize));
            }
        }
    }
    if let (Some(n), Some(c)) = (
        refs["N10000_check"]["N"].as_u64(),
        refs["N10000_check"]["inRS_nbox100_safe1_in"].as_u64(),
    ) {
        out.push((n as usize, c as usize));
    }
    out.sort_unstable();
    out.dedup();
    out
}
