//! The query sets of the winding-number speed rows (issue 52), one definition shared by every
//! section and by the external Axom driver's input files: uniform random points in the shape's
//! box grown by 5%, and points near the curves, at distances from 1e-2 to 1e-10 of the box's
//! diagonal.

use inrs::prelude::*;
use inrs::{Domain, Point};

/// splitmix64: a small, fixed, platform-independent generator, so the sets are the same on
/// every machine and in every language that reads them back.
struct SplitMix(u64);

impl SplitMix {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `[0, 1)`, 53 bits.
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// `n` uniform random points of the shape's bounding box grown by 5% of its diagonal.
pub(crate) fn random_points(d: &Domain, n: usize, seed: u64) -> Vec<Point> {
    let b = d
        .bounding_box()
        .grown_by(0.05 * d.bounding_box().diagonal());
    let mut rng = SplitMix(seed);
    (0..n)
        .map(|_| {
            let x = b.min.x + rng.unit() * b.width();
            let y = b.min.y + rng.unit() * b.height();
            Point::new(x, y)
        })
        .collect()
}

/// `n` points near the curves: on a piece chosen at random, at a random parameter, moved along
/// the unit normal (either side at random) by `10^-(2 + 8u)` times the box's diagonal, `u`
/// uniform in `[0, 1]`: distances from 1e-2 to 1e-10 of the diagonal, log-uniform. Points where
/// the tangent vanishes are skipped (drawn again).
pub(crate) fn near_points(d: &Domain, n: usize, seed: u64) -> Vec<Point> {
    let pieces: Vec<_> = d.bezier_pieces().into_iter().map(|(_, b)| b).collect();
    let diagonal = d.bounding_box().diagonal();
    let mut rng = SplitMix(seed);
    let mut out = Vec::with_capacity(n);
    // Each draw succeeds unless it hits a cusp; the bound keeps a degenerate shape from looping.
    for _ in 0..n.saturating_mul(4) {
        if out.len() == n || pieces.is_empty() {
            break;
        }
        let piece = &pieces[(rng.next_u64() % pieces.len() as u64) as usize];
        let (t0, t1) = piece.param_range();
        let t = t0 + rng.unit() * (t1 - t0);
        let (p, tangent) = piece.point_and_tangent(t);
        let length = tangent.x.hypot(tangent.y);
        if length.is_nan() || length <= 0.0 || length.is_infinite() {
            continue;
        }
        let distance = diagonal * 10f64.powf(-(2.0 + 8.0 * rng.unit()));
        let side = if rng.next_u64() & 1 == 0 { 1.0 } else { -1.0 };
        let s = side * distance / length;
        out.push(Point::new(p.x - s * tangent.y, p.y + s * tangent.x));
    }
    out
}

/// Points as little-endian `f64` pairs, the external drivers' input format.
pub(crate) fn write_points(path: &std::path::Path, pts: &[Point]) -> std::io::Result<()> {
    let mut bytes = Vec::with_capacity(pts.len() * 16);
    for p in pts {
        bytes.extend_from_slice(&p.x.to_le_bytes());
        bytes.extend_from_slice(&p.y.to_le_bytes());
    }
    std::fs::write(path, bytes)
}
