//! Cases for the tests of the split cells' side tests ([`InverseFit`](super::inverse_fit),
//! [`ImplicitSide`](super::implicit_side)): small monotone cubics, cells over part or all of
//! their heights, queries near them and around them, and the root's answer to compare with.

use rs_spline::prelude::*;
use rs_spline::{Point, RationalBezier};
use rs_testkit::XorShift64;

use super::monotone::{MonotoneCurve, RootCrossing, monotone_crossing};
use super::sum::chord_crossing;

/// A small monotone cubic with a cell over some of its heights.
pub(super) struct SideCase {
    /// Its control points.
    pub(super) p: Vec<Point>,
    pub(super) root: MonotoneCurve,
    /// The field's reach for it.
    pub(super) reach: f64,
    /// The cell's heights, and the cell (wider than the cubic by its size either side).
    pub(super) band: (f64, f64),
    pub(super) cell: (Point, Point),
    /// The larger side of its control box.
    pub(super) size: f64,
    curve: RationalBezier,
    lo: Point,
}

/// A small piece (1/64 of the parameter range) of a random cubic, if its ordinates strictly
/// rise or fall, moved by `offset`.
pub(super) fn small_monotone_cubic(rng: &mut XorShift64, offset: Point) -> Option<Vec<Point>> {
    let p: Vec<Point> = (0..4)
        .map(|_| offset + Point::new(rng.next_f64(), rng.next_f64()))
        .collect();
    let curve = RationalBezier::new(p, vec![1.0; 4]).ok()?;
    let a = rng.next_f64() * (1.0 - 1.0 / 64.0);
    let part = curve.subsegment((a, a + 1.0 / 64.0)).ok()?;
    let q = part.control_points().to_vec();
    MonotoneCurve::new(&q).map(|_| q)
}

impl SideCase {
    /// Case `i`: at the origin if `i` is even, moved by `1e3` if odd; its cell's heights over
    /// all of its own (`i % 3 == 0`), inside them, or over their lower half. `None` if the
    /// drawn piece is not monotone.
    pub(super) fn draw(rng: &mut XorShift64, i: usize) -> Option<Self> {
        let offset = if i.is_multiple_of(2) { 0.0 } else { 1e3 };
        let p = small_monotone_cubic(rng, Point::new(offset, offset))?;
        let root = MonotoneCurve::new(&p)?;
        let (y0, y1) = (p[0].y.min(p[3].y), p[0].y.max(p[3].y));
        let h = y1 - y0;
        let band = match i % 3 {
            0 => (y0 - h, y1 + h),
            1 => (y0 + 0.3 * h, y0 + 0.8 * h),
            _ => (y0 - 0.5 * h, y0 + 0.5 * h),
        };
        let (lo, hi) = super::curve::control_box(&p);
        let size = (hi.x - lo.x).max(hi.y - lo.y);
        let cell = (
            Point::new(lo.x - size, band.0),
            Point::new(hi.x + size, band.1),
        );
        let curve = RationalBezier::new(p.clone(), vec![1.0; 4]).ok()?;
        Some(Self {
            p,
            root,
            reach: 4e-12 * (offset + 2.0),
            band,
            cell,
            size,
            curve,
            lo,
        })
    }

    /// Sixty queries, those at heights of the cell and of the cubic kept: 39 displaced along
    /// the cut from a point of the cubic by `d`, `1e-1` to `1e-13` of its size (either side),
    /// with `Some(d)`; the others anywhere in and around its box.
    pub(super) fn queries(&self, rng: &mut XorShift64) -> Vec<(Point, Option<f64>)> {
        let (y0, y1) = (self.p[0].y.min(self.p[3].y), self.p[0].y.max(self.p[3].y));
        let size = self.size;
        (0..60)
            .map(|k| {
                if k < 39 {
                    let on = self.curve.point_at(rng.next_f64());
                    let d = size * 10f64.powi(-(1 + (k % 13)));
                    let x = on.x + if k % 2 == 0 { d } else { -d };
                    (Point::new(x, on.y), Some(d))
                } else {
                    let x = self.lo.x - size + 3.0 * size * rng.next_f64();
                    let y = self.lo.y - size + 3.0 * size * rng.next_f64();
                    (Point::new(x, y), None)
                }
            })
            .filter(|(q, _)| q.y >= self.band.0 && q.y <= self.band.1 && q.y >= y0 && q.y <= y1)
            .collect()
    }

    /// Asserts that the root decides at `q` the crossing of a curve passing left of `q` if
    /// `left`, right of it if not.
    pub(super) fn assert_root_agrees(&self, q: Point, left: bool, what: &str) {
        let p = &self.p;
        let want = if left {
            chord_crossing(p[0].y, p[3].y, q.y)
        } else {
            0
        };
        assert_eq!(
            monotone_crossing(p, q, self.reach),
            RootCrossing::Decided(want),
            "{what}: {p:?} band {:?} at {q:?}",
            self.band
        );
    }

    /// Whether the root decides at `q` with no margin (rounding alone).
    pub(super) fn root_decides_without_margin(&self, q: Point) -> bool {
        matches!(monotone_crossing(&self.p, q, 0.0), RootCrossing::Decided(_))
    }
}
