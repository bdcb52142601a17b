//! Items by horizontal rows: which of many y-intervals may hold a height, without scanning
//! them all (the monotone boxes for inRS's fallback, the leaves of a small winding-number
//! field).

/// Items (`u32` ids) by rows of equal height over the span of their y-intervals: row `r` lists,
/// in the order the items were given, every item whose closed interval meets it. The row of a
/// height is monotone in it, rounding included, so the row of `y` holds every item whose
/// interval holds `y`; an item left out lies wholly above or below `y`.
#[derive(Clone, Debug)]
pub(crate) struct Rows {
    /// The span of the intervals.
    y0: f64,
    y1: f64,
    /// Rows per unit height (0 for a single row).
    scale: f64,
    /// Row `r`'s items are `items[start[r]..start[r + 1]]`.
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Rows {
    /// At most `rows` rows (at least one) over the intervals `(id, lo, hi)` (`lo <= hi`), halved
    /// until the registrations are at most `per_item` per item plus the rows (intervals that
    /// span many rows would otherwise take memory growing with their number times the rows).
    pub(crate) fn new(intervals: &[(u32, f64, f64)], rows: usize, per_item: usize) -> Self {
        let (y0, y1) = intervals.iter().fold(
            (f64::INFINITY, f64::NEG_INFINITY),
            |(a, b), &(_, lo, hi)| (a.min(lo), b.max(hi)),
        );
        let mut rows = rows.max(1);
        loop {
            let empty = Self::empty(y0, y1, rows);
            let entries: usize = intervals
                .iter()
                .map(|&(_, lo, hi)| empty.row(hi) - empty.row(lo) + 1)
                .sum();
            let bound = per_item
                .saturating_mul(intervals.len())
                .saturating_add(rows);
            if rows == 1 || entries <= bound {
                return empty.filled(intervals);
            }
            rows /= 2;
        }
    }

    /// `rows` rows over `[y0, y1]`, none filled.
    fn empty(y0: f64, y1: f64, rows: usize) -> Self {
        let scale = rows as f64 / (y1 - y0);
        Self {
            y0,
            y1,
            scale: if rows > 1 && scale.is_finite() && scale > 0.0 {
                scale
            } else {
                0.0
            },
            start: vec![0; rows + 1],
            items: Vec::new(),
        }
    }

    /// The rows with every item registered in those its interval meets.
    fn filled(mut self, intervals: &[(u32, f64, f64)]) -> Self {
        let mut lists = vec![Vec::new(); self.start.len() - 1];
        for &(id, lo, hi) in intervals {
            for list in &mut lists[self.row(lo)..=self.row(hi)] {
                list.push(id);
            }
        }
        for (r, list) in lists.iter().enumerate() {
            self.items.extend_from_slice(list);
            self.start[r + 1] = self.items.len() as u32;
        }
        self
    }

    /// The row of height `y`, clamped to the rows (row 0 for NaN). Monotone in `y`, rounding
    /// included: a height in a higher row is higher.
    #[inline]
    pub(crate) fn row(&self, y: f64) -> usize {
        let last = self.start.len() - 2;
        if last == 0 {
            return 0;
        }
        (((y - self.y0) * self.scale).max(0.0) as usize).min(last)
    }

    /// Whether `y` lies in the span of the intervals (false for NaN): off it, no interval
    /// holds `y`.
    #[inline]
    pub(crate) fn spans(&self, y: f64) -> bool {
        y >= self.y0 && y <= self.y1
    }

    /// The items of `y`'s row: every item whose interval holds `y`, and perhaps others.
    #[inline]
    pub(crate) fn near(&self, y: f64) -> &[u32] {
        let r = self.row(y);
        &self.items[self.start[r] as usize..self.start[r + 1] as usize]
    }

    /// The items of row `r`, in the order they were given.
    pub(crate) fn items_of(&self, r: usize) -> &[u32] {
        &self.items[self.start[r] as usize..self.start[r + 1] as usize]
    }

    /// The number of rows.
    pub(crate) fn len(&self) -> usize {
        self.start.len() - 1
    }

    /// The number of registrations (items counted once per row they are in).
    #[cfg(test)]
    pub(crate) fn registrations(&self) -> usize {
        self.items.len()
    }
}

/// Most rows of [`box_rows`].
const MAX_BOX_ROWS: usize = 4096;

/// Registrations allowed per box on average before [`box_rows`] coarsens its rows.
const REGISTRATIONS_PER_BOX: usize = 8;

/// The monotone boxes by their *reach*, the y-range grown by the tolerance `tol` and the band's
/// margin ([`rs_boxes::ChordBand::heights_near`], the bounds `may_be_near` tests): a box whose
/// reach does not hold `y` is neither near a point at height `y` nor crossed by the horizontal
/// ray from it, so the row of `y` holds every box that can change a horizontal ray's parity or
/// a boundary test there.
pub(crate) fn box_rows(boxes: &[rs_boxes::MonotoneBox], tol: f64) -> Rows {
    let intervals: Vec<(u32, f64, f64)> = boxes
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let (lo, hi) = b.band.heights_near(tol);
            (i as u32, lo, hi)
        })
        .collect();
    Rows::new(
        &intervals,
        boxes.len().clamp(1, MAX_BOX_ROWS),
        REGISTRATIONS_PER_BOX,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rays::{horizontal, winding};
    use crate::{Classifier, ContainOptions, Decision};
    use rs_boxes::MonotoneBox;
    use rs_spline::{Domain, Point, circle, polyline};

    /// The paper's fixtures, and a domain whose tolerance is wider than the domain (a strip 10
    /// wide and 10^13 tall round a small circle: every point's abscissa is critical).
    fn domains() -> Vec<(String, Domain)> {
        let mut out: Vec<(String, Domain)> = rs_testkit::fixtures()
            .into_iter()
            .map(|c| (c.name, c.domain))
            .collect();
        let strip = polyline(&[
            Point::new(0.0, 0.0),
            Point::new(10.0, 0.0),
            Point::new(10.0, 1e13),
            Point::new(0.0, 1e13),
            Point::new(0.0, 0.0),
        ])
        .unwrap();
        let hole = circle(Point::new(5.0, 5.0), 3.0).unwrap();
        out.push(("strip".into(), Domain::new(vec![strip, hole]).unwrap()));
        out
    }

    /// The row of a height lists every box whose reach holds it (at the reaches' own ends and
    /// between), and the registrations stay within their bound.
    #[test]
    fn a_row_holds_every_box_whose_reach_holds_its_height() {
        for (name, d) in domains() {
            let c = Classifier::new(&d, ContainOptions::default()).unwrap();
            let (boxes, tol) = (c.boxes().boxes(), c.abs_tol());
            let rows = box_rows(boxes, tol);
            let reach = |b: &MonotoneBox| b.band.heights_near(tol);
            let mut heights: Vec<f64> = boxes
                .iter()
                .flat_map(|b| {
                    let (lo, hi) = reach(b);
                    [lo, hi, 0.5 * (lo + hi)]
                })
                .collect();
            let bb = d.bounding_box();
            heights.extend((0..=300).map(|k| bb.min.y + bb.height() * k as f64 / 300.0));
            for &y in &heights {
                let near = rows.near(y);
                for (i, b) in boxes.iter().enumerate() {
                    let (lo, hi) = reach(b);
                    if lo <= y && y <= hi {
                        assert!(near.contains(&(i as u32)), "{name}: box {i} at {y}");
                    }
                }
            }
            assert!(
                rows.registrations() <= REGISTRATIONS_PER_BOX * boxes.len() + rows.len(),
                "{name}: {} registrations of {} boxes",
                rows.registrations(),
                boxes.len()
            );
        }
    }

    /// The fallback through the rows answers as a scan of every box does, at the critical
    /// abscissas (where points take it) and at heights across each domain.
    #[test]
    fn the_fallback_through_rows_equals_a_scan_of_every_box() {
        for (name, d) in domains() {
            let c = Classifier::new(&d, ContainOptions::default()).unwrap();
            let (all, tol) = (c.boxes().boxes(), c.abs_tol());
            let bb = d.bounding_box();
            let mut xs: Vec<f64> = c.boxes().critical_abscissas().to_vec();
            xs.extend((0..=20).map(|k| bb.min.x + bb.width() * k as f64 / 20.0));
            let mut ys: Vec<f64> = (0..=40)
                .map(|k| bb.min.y + bb.height() * k as f64 / 40.0)
                .collect();
            ys.extend([5.0, 2.0, 8.0, 1e12]);
            for &x in &xs {
                for &y in &ys {
                    let p = Point::new(x, y);
                    let (got, decision) = c.fallback(p);
                    if !c.boxes().is_critical_y(p.y, tol) {
                        let want = winding(all, |b| horizontal(b, p, tol));
                        assert_eq!(
                            (got, decision),
                            (want, Decision::HorizontalRay),
                            "{name} {p:?}"
                        );
                    } else if all.iter().any(|b| b.is_near(p, tol)) {
                        assert_eq!(got, None, "{name} {p:?}");
                    } else {
                        assert_ne!(got, None, "{name} {p:?}");
                    }
                }
            }
        }
    }
}
