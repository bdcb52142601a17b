//! The `k` nearest data sites of a point, on the workspace's uniform grid
//! ([`rs_spline::grid`]): sites are registered in cells holding about four each, and a query
//! searches square rings of cells around its own until the `k`-th distance found is no larger
//! than the distance to the next ring.

use rs_spline::grid::{CellIndex, GridFrame};
use rs_spline::{BoundingBox, Point};

/// Sites per cell the grid aims at.
const SITES_PER_CELL: usize = 4;

/// A grid index of data sites for nearest-neighbour queries.
#[derive(Clone, Debug)]
pub(crate) struct NearestSites<'a> {
    sites: &'a [Point],
    index: CellIndex<u32>,
}

impl<'a> NearestSites<'a> {
    /// The index of `sites` (finite points; at most `u32::MAX`).
    pub(crate) fn new(sites: &'a [Point]) -> Self {
        let bbox = BoundingBox::from_points(sites.iter().copied())
            .unwrap_or_else(|| BoundingBox::from_point(Point::new(0.0, 0.0)));
        let n = ((sites.len() / SITES_PER_CELL) as f64)
            .sqrt()
            .ceil()
            .max(1.0) as usize;
        let frame = GridFrame::new(bbox, n);
        Self {
            sites,
            index: CellIndex::of_points(frame, sites),
        }
    }

    /// The sites.
    pub(crate) fn sites(&self) -> &'a [Point] {
        self.sites
    }

    /// The indices of the `k` sites nearest to `p` (all sites if there are fewer), nearest
    /// first; ties broken by index.
    pub(crate) fn nearest(&self, p: Point, k: usize) -> Vec<usize> {
        let k = k.min(self.sites.len());
        if k == 0 {
            return Vec::new();
        }
        let frame = self.index.frame();
        let n = frame.n();
        let (cw, ch) = frame.cell_size();
        let step = cw.min(ch);
        let (col, row) = (frame.col(p.x) as isize, frame.row(p.y) as isize);
        // Distance from p to the outside of its own cell's ring `r`: at least `r` whole cells
        // beyond p's cell, less p's offset inside it.
        let bbox = frame.bounding_box();
        let mut found: Vec<(f64, usize)> = Vec::new();
        // Every cell is within `n` rings, so the loop is bounded.
        for r in 0..=n as isize {
            for c in col - r..=col + r {
                for w in row - r..=row + r {
                    let on_ring = (c - col).abs() == r || (w - row).abs() == r;
                    if !on_ring || c < 0 || w < 0 || c >= n as isize || w >= n as isize {
                        continue;
                    }
                    for &i in self.index.cell(c as usize * n + w as usize) {
                        let i = i as usize;
                        found.push((p.distance(self.sites[i]), i));
                    }
                }
            }
            if found.len() >= k {
                found.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                found.truncate(k);
                // Points outside ring `r` are at least this far (p may lie outside the frame,
                // which only makes the bound smaller than it could be).
                let inside_x = (p.x - bbox.min.x).clamp(0.0, bbox.width()) - col as f64 * cw;
                let inside_y = (p.y - bbox.min.y).clamp(0.0, bbox.height()) - row as f64 * ch;
                let margin = inside_x
                    .min(cw - inside_x)
                    .min(inside_y)
                    .min(ch - inside_y)
                    .max(0.0);
                let reach = r as f64 * step + margin;
                if found[k - 1].0 <= reach {
                    break;
                }
            }
        }
        found.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        found.truncate(k);
        found.into_iter().map(|(_, i)| i).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_sites_match_a_sort_of_all_distances() {
        // Halton-like scattered sites, queries inside and outside their box.
        let sites: Vec<Point> = (0..500)
            .map(|i| {
                let t = i as f64;
                Point::new((t * 0.618_034).fract() * 3.0, (t * 0.414_214).fract())
            })
            .collect();
        let index = NearestSites::new(&sites);
        for q in [
            Point::new(1.5, 0.5),
            Point::new(0.0, 0.0),
            Point::new(-2.0, 3.0),
            Point::new(2.99, 0.01),
        ] {
            for k in [1, 7, 20, 499, 600] {
                let mut all: Vec<(f64, usize)> = sites
                    .iter()
                    .enumerate()
                    .map(|(i, s)| (q.distance(*s), i))
                    .collect();
                all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
                let want: Vec<usize> = all.iter().take(k).map(|x| x.1).collect();
                assert_eq!(index.nearest(q, k), want, "{q:?} k={k}");
            }
        }
    }
}
