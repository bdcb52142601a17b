//! The monotone boxes by horizontal rows: the boxes a horizontal ray or a boundary test at one
//! height must look at, without scanning them all.

use rs_boxes::MonotoneBox;

/// Most rows of a [`BoxRows`].
const MAX_ROWS: usize = 4096;

/// Registrations allowed per box on average before the rows are coarsened (tall boxes span
/// many rows): memory stays linear in the boxes.
const ENTRIES_PER_BOX: usize = 8;

/// The boxes by rows of equal height: row `r` lists every box whose *reach* meets it, the box's
/// y-range grown by the tolerance and its band's margin, as [`rs_boxes::ChordBand::may_be_near`]
/// grows it. A box whose reach does not hold `y` is neither near a point at height `y` nor
/// crossed by the horizontal ray from it, so the row of `y` holds every box that can change a
/// horizontal ray's parity or a boundary test there (the row of a height is monotone in it,
/// rounding included).
#[derive(Clone, Debug)]
pub(crate) struct BoxRows {
    y0: f64,
    /// Rows per unit height (0 for a single row).
    scale: f64,
    /// Row `r`'s boxes are `boxes[start[r]..start[r + 1]]`.
    start: Vec<u32>,
    boxes: Vec<u32>,
}

impl BoxRows {
    /// The rows of `boxes` for the boundary tolerance `tol`.
    pub(crate) fn new(boxes: &[MonotoneBox], tol: f64) -> Self {
        let reach = |b: &MonotoneBox| {
            let r = tol + b.band.margin;
            (b.band.ymin - r, b.band.ymax + r)
        };
        let (y0, y1) = boxes
            .iter()
            .map(reach)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (a, b)| {
                (lo.min(a), hi.max(b))
            });
        let mut rows = boxes.len().clamp(1, MAX_ROWS);
        loop {
            let scaled = Self::empty(y0, y1, rows);
            let entries: usize = boxes
                .iter()
                .map(|b| {
                    let (lo, hi) = reach(b);
                    scaled.row(hi) - scaled.row(lo) + 1
                })
                .sum();
            if rows == 1 || entries <= ENTRIES_PER_BOX * boxes.len() + rows {
                return scaled.filled(boxes, reach);
            }
            rows /= 2;
        }
    }

    /// `rows` rows over `[y0, y1]`, none filled.
    fn empty(y0: f64, y1: f64, rows: usize) -> Self {
        let scale = rows as f64 / (y1 - y0);
        Self {
            y0,
            scale: if rows > 1 && scale.is_finite() && scale > 0.0 {
                scale
            } else {
                0.0
            },
            start: vec![0; rows + 1],
            boxes: Vec::new(),
        }
    }

    /// The rows with every box registered in those its reach meets.
    fn filled(mut self, boxes: &[MonotoneBox], reach: impl Fn(&MonotoneBox) -> (f64, f64)) -> Self {
        let mut lists = vec![Vec::new(); self.start.len() - 1];
        for (i, b) in boxes.iter().enumerate() {
            let (lo, hi) = reach(b);
            for list in &mut lists[self.row(lo)..=self.row(hi)] {
                list.push(i as u32);
            }
        }
        for (r, list) in lists.iter().enumerate() {
            self.boxes.extend_from_slice(list);
            self.start[r + 1] = self.boxes.len() as u32;
        }
        self
    }

    /// The row of height `y`, clamped to the rows (row 0 for NaN).
    fn row(&self, y: f64) -> usize {
        let last = self.start.len() - 2;
        (((y - self.y0) * self.scale).max(0.0) as usize).min(last)
    }

    /// The indices of the boxes whose reach may hold height `y`: every one whose reach does.
    pub(crate) fn near(&self, y: f64) -> &[u32] {
        let r = self.row(y);
        &self.boxes[self.start[r] as usize..self.start[r + 1] as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rays::{horizontal, parity};
    use crate::{Classifier, ContainOptions, Decision, Location};
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
            let rows = BoxRows::new(boxes, tol);
            let reach = |b: &MonotoneBox| {
                let r = tol + b.band.margin;
                (b.band.ymin - r, b.band.ymax + r)
            };
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
                rows.boxes.len() <= ENTRIES_PER_BOX * boxes.len() + rows.start.len(),
                "{name}: {} registrations of {} boxes",
                rows.boxes.len(),
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
                        let want = match parity(all, |b| horizontal(b, p, tol)) {
                            None => Location::Boundary,
                            Some(true) => Location::Inside,
                            Some(false) => Location::Outside,
                        };
                        assert_eq!(
                            (got, decision),
                            (want, Decision::HorizontalRay),
                            "{name} {p:?}"
                        );
                    } else if all.iter().any(|b| b.is_near(p, tol)) {
                        assert_eq!(got, Location::Boundary, "{name} {p:?}");
                    } else {
                        assert_ne!(got, Location::Boundary, "{name} {p:?}");
                    }
                }
            }
        }
    }
}
