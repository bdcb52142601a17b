//! Boundary points placed by arc length on every loop, and the refusal of a boundary of too
//! many Bezier pieces to place them on (every piece gets an arc-length table).

use rs_spline::prelude::*;
use rs_spline::{ArcLengthTable, Domain, Point};

use crate::MeshError;
use crate::limits::{MAX_MESH_PIECES, MAX_SAMPLE_POINTS};

/// A point on the boundary: which loop and curve, and the curve's NURBS parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundaryPoint {
    /// Index of the loop in the domain.
    pub loop_index: usize,
    /// Index of the curve in the domain.
    pub curve: usize,
    /// The parameter on that curve.
    pub u: f64,
    /// `C(u)`.
    pub point: Point,
}

/// Panels per Bezier span of the arc-length table.
const PANELS: usize = 32;

/// Places nearly equally spaced points (spacing about `h` by arc length) on every loop.
///
/// Every curve's start point is kept (corners and curve junctions stay vertices, so each
/// boundary arc lies on one curve). `extra` points (curve, parameter) are kept where they are at
/// least `h / 3` (by arc length) from the points kept before them and from the curve's end;
/// the gaps in between are filled with equally spaced points. Returns the points of each loop
/// in loop order.
///
/// # Errors
/// [`MeshError::TooManyPoints`] when the boundary's length is more than
/// [`MAX_SAMPLE_POINTS`] spacings (or not finite: the arc length of a curve far smaller than
/// the rounding of its coordinates is noise), before any point is placed.
pub(crate) fn place_boundary_points(
    domain: &Domain,
    h: f64,
    extra: &[(usize, f64)],
) -> Result<Vec<Vec<BoundaryPoint>>, MeshError> {
    let tables: Vec<ArcLengthTable> = domain
        .curves()
        .iter()
        .map(|c| ArcLengthTable::new(c, PANELS))
        .collect();
    let estimate: f64 = tables.iter().map(|t| t.length() / h + 1.0).sum();
    if estimate.is_nan() || estimate > MAX_SAMPLE_POINTS as f64 {
        return Err(MeshError::TooManyPoints {
            estimate,
            limit: MAX_SAMPLE_POINTS,
        });
    }
    let mut out = Vec::new();
    for (j, l) in domain.loops().iter().enumerate() {
        let mut pts = Vec::new();
        for ci in l.curves() {
            let c = &domain.curves()[ci];
            let table = &tables[ci];
            let len = table.length();
            let (u_start, u_end) = c.param_range();
            let mut wanted: Vec<f64> = extra
                .iter()
                .filter(|(k, u)| *k == ci && *u > u_start && *u < u_end)
                .map(|&(_, u)| table.s_at(u))
                .collect();
            wanted.sort_by(f64::total_cmp);
            let mut kept = vec![0.0];
            for s in wanted {
                if s - kept[kept.len() - 1] >= h / 3.0 && len - s >= h / 3.0 {
                    kept.push(s);
                }
            }
            kept.push(len);
            let mut all = Vec::new();
            for w in kept.windows(2) {
                let n = ((w[1] - w[0]) / h).round().max(1.0) as usize;
                for k in 0..n {
                    all.push(w[0] + (w[1] - w[0]) * k as f64 / n as f64);
                }
            }
            for (k, s) in all.into_iter().enumerate() {
                let (u, point) = if k == 0 {
                    (u_start, c.start_point())
                } else {
                    let u = table.u_at(s);
                    (u, c.point_at(u))
                };
                pts.push(BoundaryPoint {
                    loop_index: j,
                    curve: ci,
                    u,
                    point,
                });
            }
        }
        out.push(pts);
    }
    Ok(out)
}

/// Refuses, before any work, a boundary of more than [`MAX_MESH_PIECES`] Bezier pieces.
///
/// # Errors
/// [`MeshError::TooManyPieces`].
pub fn check_boundary_pieces(domain: &Domain) -> Result<(), MeshError> {
    let pieces: usize = domain
        .curves()
        .iter()
        .map(|c| c.knots().interior_breaks().len() + 1)
        .sum();
    if pieces > MAX_MESH_PIECES {
        return Err(MeshError::TooManyPieces {
            pieces,
            limit: MAX_MESH_PIECES,
        });
    }
    Ok(())
}
