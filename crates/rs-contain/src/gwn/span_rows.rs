//! The leaves of a [`FastWindingField`](super::FastWindingField) of many pieces by rows of
//! their height, each row's leaves that span it sorted by their right side with the running
//! sum of their chords' crossings: a query adds the crossings of every such leaf wholly left of
//! it by one binary search, and visits the few other leaves of its row one by one, instead of
//! walking the tree.

use rs_spline::Point;
use smallvec::SmallVec;

use super::curve::misses_cut;
use super::sum::WindingSum;
use crate::rows::Rows;

/// A leaf of the field as the rows read it: its box, its piece and its chord.
#[derive(Clone, Copy, Debug)]
pub(super) struct Leaf {
    pub(super) lo: Point,
    pub(super) hi: Point,
    pub(super) piece: u32,
    /// The piece's start and end.
    pub(super) chord: (Point, Point),
}

/// A leaf spanning a row: every height of the row lies strictly inside its box's, and its
/// chord's ends lie in other rows, so its chord crosses every height of the row alike.
#[derive(Clone, Copy, Debug)]
struct Span {
    /// Its box's right side; the row's spans are sorted by it.
    hi_x: f64,
    /// Its box's left side.
    lo_x: f64,
    /// The least `lo_x` of this span and those after it in the row: past a query's abscissa,
    /// no later span holds the query.
    least_lo_x: f64,
    piece: u32,
    /// The signed crossings of the chords of the row's spans up to this one (included): what
    /// they add for a query right of all of them.
    crossings: i32,
}

/// The leaves by rows (see the module): per row, its spans and its other leaves.
#[derive(Clone, Debug)]
pub(super) struct SpanRows {
    rows: Rows,
    /// Row `r`'s spans are `spans[span_start[r]..span_start[r + 1]]`.
    span_start: Vec<u32>,
    spans: Vec<Span>,
    /// Row `r`'s other leaves (indices into the leaves given), in boundary order, are
    /// `loose[loose_start[r]..loose_start[r + 1]]`.
    loose_start: Vec<u32>,
    loose: Vec<u32>,
    leaves: Vec<Leaf>,
}

/// Rows per leaf.
const ROWS_PER_LEAF: usize = 4;

/// Registrations allowed per leaf on average before the rows coarsen (a leaf as tall as the
/// field would otherwise be in every row).
const REGISTRATIONS_PER_LEAF: usize = 16;

impl SpanRows {
    /// The rows of `leaves` (in boundary order).
    pub(super) fn new(leaves: Vec<Leaf>) -> Self {
        let intervals: Vec<(u32, f64, f64)> = leaves
            .iter()
            .enumerate()
            .map(|(i, l)| (i as u32, l.lo.y, l.hi.y))
            .collect();
        let rows = Rows::new(
            &intervals,
            ROWS_PER_LEAF * leaves.len(),
            REGISTRATIONS_PER_LEAF,
        );
        let (mut span_start, mut spans) = (vec![0u32], Vec::new());
        let (mut loose_start, mut loose) = (vec![0u32], Vec::new());
        for r in 0..rows.len() {
            let first = spans.len();
            for &i in rows.items_of(r) {
                let l = &leaves[i as usize];
                // The row of a height is monotone in it, rounding included: a height in a
                // higher row is higher than every height of row r, one in a lower row lower.
                let (a, b) = l.chord;
                let spanning = rows.row(l.lo.y) < r
                    && rows.row(l.hi.y) > r
                    && rows.row(a.y) != r
                    && rows.row(b.y) != r;
                if spanning {
                    // `left_crossing`: +1 for each end at or above the query, -1 for the end.
                    let crossing = i32::from(rows.row(a.y) > r) - i32::from(rows.row(b.y) > r);
                    spans.push(Span {
                        hi_x: l.hi.x,
                        lo_x: l.lo.x,
                        least_lo_x: l.lo.x,
                        piece: l.piece,
                        crossings: crossing,
                    });
                } else {
                    loose.push(i);
                }
            }
            let row = &mut spans[first..];
            row.sort_by(|s, t| s.hi_x.total_cmp(&t.hi_x));
            for k in 1..row.len() {
                row[k].crossings += row[k - 1].crossings;
            }
            for k in (0..row.len().saturating_sub(1)).rev() {
                row[k].least_lo_x = row[k].lo_x.min(row[k + 1].least_lo_x);
            }
            span_start.push(spans.len() as u32);
            loose_start.push(loose.len() as u32);
        }
        Self {
            rows,
            span_start,
            spans,
            loose_start,
            loose,
            leaves,
        }
    }

    /// Adds to `sum` the crossings of every leaf lying wholly left of `q` (its chord's, as
    /// [`WindingSum::left_crossing`] counts them), and pushes onto `hits` the pieces whose
    /// leaf's box holds `q` (in no particular order), for a `q` with no NaN coordinate; a leaf
    /// above, below or right of `q` adds nothing. Returns the leaves decided by their chord
    /// one by one.
    #[inline]
    pub(super) fn add(
        &self,
        q: Point,
        sum: &mut WindingSum,
        hits: &mut SmallVec<[u32; 8]>,
    ) -> usize {
        if !self.rows.spans(q.y) {
            return 0;
        }
        let r = self.rows.row(q.y);
        let spans = &self.spans[self.span_start[r] as usize..self.span_start[r + 1] as usize];
        let left = spans.partition_point(|s| s.hi_x < q.x);
        if left > 0 {
            sum.add_left_crossings(i64::from(spans[left - 1].crossings));
        }
        for s in &spans[left..] {
            if s.least_lo_x > q.x {
                break;
            }
            if s.lo_x <= q.x {
                hits.push(s.piece);
            }
        }
        let mut decided = 0;
        for &i in &self.loose[self.loose_start[r] as usize..self.loose_start[r + 1] as usize] {
            let l = &self.leaves[i as usize];
            if misses_cut(l.lo, l.hi, q) {
                continue;
            }
            if q.x > l.hi.x {
                sum.left_crossing(l.chord.0, l.chord.1);
                decided += 1;
            } else {
                hits.push(l.piece);
            }
        }
        decided
    }
}
