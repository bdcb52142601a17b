//! The chord band of a monotone piece: what decides most queries against it without a solve.

use rs_spline::{BoundingBox, Point};

use crate::BezierPiece;

/// Relative rounding margin: far above the error of a crossing solve or of a de Casteljau
/// halving, far below any boundary tolerance in use.
pub(crate) const SLACK_MARGIN: f64 = 1e-13;

/// The band round a monotone piece's chord that holds the piece: its end points, their
/// rectangle (which holds a monotone piece), and how far the piece strays from the chord.
///
/// A band answers the two questions of the containment tests, *may `p` be near the piece?* and
/// *does the downward ray from `p` cross it?*, without a solve for every point outside the band,
/// and says when a solve is needed. It stands either for a [`MonotoneBox`](crate::MonotoneBox)'s
/// own piece ([`MonotoneBox::band`](crate::MonotoneBox::band)), or for a part of it
/// cut by halving ([`MonotoneBox::for_grid_parts`](crate::MonotoneBox::for_grid_parts)); a part's
/// control points carry the halving's rounding, which [`ChordBand::margin`] covers, so that
/// every answer a part's band gives is the box's own answer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ChordBand {
    /// The piece's first point.
    pub start: Point,
    /// The piece's last point.
    pub end: Point,
    /// `min(start.x, end.x)`.
    pub xmin: f64,
    /// `max(start.x, end.x)`.
    pub xmax: f64,
    /// `min(start.y, end.y)`.
    pub ymin: f64,
    /// `max(start.y, end.y)`.
    pub ymax: f64,
    /// True if `x` is constant along the piece (a vertical piece, never crossed by the ray).
    pub vertical: bool,
    /// Largest distance of a control point from the chord `start -> end`: the piece lies
    /// within this distance of its chord (convex hull property).
    pub flatness: f64,
    /// For a piece that is not vertical: the largest vertical distance of a control point from
    /// the chord's line, plus a rounding margin and [`ChordBand::margin`]. At any abscissa of
    /// the band the curve lies within this vertical distance of the chord's line.
    pub vertical_slack: f64,
    /// How far the curve the band stands for may lie from the stored piece: 0 for a box's own
    /// piece, a rounding margin for a part cut from it by halving.
    pub margin: f64,
}

impl ChordBand {
    /// The band of `piece`, standing for a curve within `margin` of it.
    pub(crate) fn of_piece(piece: &BezierPiece, vertical: bool, margin: f64) -> Self {
        let n = piece.degree();
        Self::of_controls(n + 1, |i| piece.control_point(i), vertical, margin)
    }

    /// The band of the piece with the `count` control points `control(0..count)` (the first
    /// and last its end points; `count >= 1`), standing for a curve within `margin` of it.
    #[inline]
    pub(crate) fn of_controls(
        count: usize,
        control: impl Fn(usize) -> Point + Clone,
        vertical: bool,
        margin: f64,
    ) -> Self {
        let (start, end) = (control(0), control(count - 1));
        let chord = end - start;
        let len = chord.length();
        let controls = (0..count).map(control);
        let flatness = if len > 0.0 {
            controls
                .clone()
                .map(|q| chord.cross(q - start).abs() / len)
                .fold(0.0, f64::max)
        } else {
            controls
                .clone()
                .map(|q| q.distance(start))
                .fold(0.0, f64::max)
        };
        let vertical_slack = if vertical {
            f64::INFINITY
        } else {
            let slope = chord.y / chord.x;
            controls
                .map(|q| (q.y - (start.y + (q.x - start.x) * slope)).abs())
                .fold(0.0, f64::max)
                + rounding_margin(start, end)
                + margin
        };
        Self {
            start,
            end,
            xmin: start.x.min(end.x),
            xmax: start.x.max(end.x),
            ymin: start.y.min(end.y),
            ymax: start.y.max(end.y),
            vertical,
            flatness,
            vertical_slack,
            margin,
        }
    }

    /// The end points' rectangle grown by `abs_tol` plus the margin: it holds every point
    /// within `abs_tol` of the curve.
    pub fn rectangle_near(&self, abs_tol: f64) -> BoundingBox {
        BoundingBox {
            min: Point::new(self.xmin, self.ymin),
            max: Point::new(self.xmax, self.ymax),
        }
        .grown_by(abs_tol + self.margin)
    }

    /// The heights a point within `abs_tol` of the curve can have, `[ymin, ymax]` grown by
    /// `abs_tol` plus the margin: [`ChordBand::may_be_near`] is false at any other height (an
    /// index of bands by height must use these very bounds).
    #[inline]
    pub fn heights_near(&self, abs_tol: f64) -> (f64, f64) {
        let reach = abs_tol + self.margin;
        (self.ymin - reach, self.ymax + reach)
    }

    /// False only if every point of the curve is farther than `abs_tol` from `p`: `p` is
    /// outside [`ChordBand::rectangle_near`] or farther than `flatness + abs_tol + margin` from
    /// the chord segment. True means a solve must decide.
    #[inline]
    pub fn may_be_near(&self, p: Point, abs_tol: f64) -> bool {
        let reach = abs_tol + self.margin;
        let (ylo, yhi) = self.heights_near(abs_tol);
        if !(p.x >= self.xmin - reach && p.x <= self.xmax + reach && p.y >= ylo && p.y <= yhi) {
            return false;
        }
        let chord = self.end - self.start;
        let len2 = chord.dot(chord);
        if len2 > 0.0 {
            let t = ((p - self.start).dot(chord) / len2).clamp(0.0, 1.0);
            let d = p - (self.start + chord * t);
            let reach = self.flatness + reach;
            if d.dot(d) > reach * reach * (1.0 + 1e-9) {
                return false;
            }
        }
        true
    }

    /// What a crossing of the downward ray adds to the winding number: `+1` if the curve runs
    /// in the `+x` direction (`start.x < end.x`), else `-1` (for a band that is not vertical;
    /// a part's band keeps its box's direction). The sum of these over the crossings of the
    /// downward ray from a point off a closed boundary is its winding number.
    #[inline]
    pub fn x_sign(&self) -> i64 {
        if self.start.x < self.end.x { 1 } else { -1 }
    }

    /// Whether the downward vertical ray from `p` crosses the curve, when the band decides it
    /// without a solve, for a `p` not near the curve: half-open in x (`xmin <= p.x < xmax`, so
    /// the parts of one piece share out its abscissas exactly), no crossing of a vertical
    /// piece, and above or below the band by more than the margin. `None` if a solve must
    /// decide (`p` within the vertical slack of the chord's line).
    #[inline]
    pub fn crossing_below(&self, p: Point) -> Option<bool> {
        if self.vertical || !(self.xmin <= p.x && p.x < self.xmax) || p.y < self.ymin - self.margin
        {
            return Some(false);
        }
        if p.y > self.ymax + self.margin {
            return Some(true);
        }
        let line = self.start.y
            + (p.x - self.start.x) * ((self.end.y - self.start.y) / (self.end.x - self.start.x));
        if p.y > line + self.vertical_slack {
            Some(true)
        } else if p.y < line - self.vertical_slack {
            Some(false)
        } else {
            None
        }
    }
}

/// A rounding margin for a piece from `start` to `end`: [`SLACK_MARGIN`] times its coordinates'
/// scale plus its chord's length.
pub(crate) fn rounding_margin(start: Point, end: Point) -> f64 {
    let scale = start.x.abs().max(end.x.abs()) + start.y.abs().max(end.y.abs());
    SLACK_MARGIN * (scale + (end - start).length())
}

/// The margin of a part cut from `piece` by halvings: [`SLACK_MARGIN`] times twice the scale of
/// its control points (each halving's rounding is a few units in the last place of that scale,
/// and the margin is about 900 of them, enough for the 24 halvings of the deepest part).
pub(crate) fn halving_margin(piece: &BezierPiece) -> f64 {
    let (sx, sy) = (0..=piece.degree())
        .map(|i| piece.control_point(i))
        .fold((0.0f64, 0.0f64), |(sx, sy), q| {
            (sx.max(q.x.abs()), sy.max(q.y.abs()))
        });
    2.0 * SLACK_MARGIN * (sx + sy)
}
