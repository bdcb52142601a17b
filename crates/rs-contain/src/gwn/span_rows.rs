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
/// chord's ends lie in other rows, so its chord crosses every height of the row alike. A row's
/// spans, sorted by their right sides, have their left sides in order too (a leaf whose box
/// would reach left of one kept before it is kept with the row's other leaves instead): the
/// spans right of a query that hold it come first, and the scan stops at the first that does
/// not.
#[derive(Clone, Copy, Debug)]
struct Span {
    /// Its box's right side; the row's spans are sorted by it.
    hi_x: f64,
    /// Its box's left side.
    lo_x: f64,
    piece: u32,
    /// The signed crossings of the chords of the row's spans up to this one (included): what
    /// they add for a query right of all of them.
    crossings: i32,
}

/// Where a row's spans and other leaves start in [`SpanRows`]' lists (the next row's start
/// ends them).
#[derive(Clone, Copy, Debug, Default)]
struct RowStart {
    spans: u32,
    /// Its other leaves' start, with [`WALK`] set for a row left to the walk (which keeps
    /// none).
    loose: u32,
}

/// The flag of a row left to the walk ([`MOST_LOOSE`]) in [`RowStart::loose`].
const WALK: u32 = 1 << 31;

impl RowStart {
    /// Its other leaves' start.
    fn loose(self) -> usize {
        (self.loose & !WALK) as usize
    }
}

/// The leaves by rows (see the module): per row, its spans and its other leaves.
#[derive(Clone, Debug)]
pub(super) struct SpanRows {
    rows: Rows,
    /// Per row and one past the last: where its spans and its other leaves start (see
    /// [`RowStart`]).
    starts: Vec<RowStart>,
    /// The rows' spans, row after row.
    spans: Vec<Span>,
    /// The rows' other leaves (indices into `leaves`, in boundary order), row after row.
    loose: Vec<u32>,
    leaves: Vec<Leaf>,
}

/// Rows per leaf.
const ROWS_PER_LEAF: usize = 4;

/// Registrations allowed per leaf on average before the rows coarsen (a leaf as tall as the
/// field would otherwise be in every row).
const REGISTRATIONS_PER_LEAF: usize = 16;

/// A row with more leaves than this not spanning it is left to the walk: a query there would
/// visit them one by one (a comb of thousands of teeth as tall as the field, whose ends share
/// the coarsened rows at its top and bottom), where the walk decides whole runs of them by
/// their chain's chord.
const MOST_LOOSE: usize = 64;

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
        let mut starts = Vec::with_capacity(rows.len() + 1);
        starts.push(RowStart::default());
        // Per leaf, the rows of its box's bottom and top and of its chord's start and end,
        // computed once for all the rows it is in.
        let leaf_rows: Vec<[usize; 4]> = leaves
            .iter()
            .map(|l| [l.lo.y, l.hi.y, l.chord.0.y, l.chord.1.y].map(|y| rows.row(y)))
            .collect();
        let (mut spans, mut loose) = (Vec::new(), Vec::new());
        for r in 0..rows.len() {
            let first = spans.len();
            let loose_first = starts[r].loose();
            for &i in rows.items_of(r) {
                let l = &leaves[i as usize];
                // The row of a height is monotone in it, rounding included: a height in a
                // higher row is higher than every height of row r, one in a lower row lower.
                let [bottom, top, a, b] = leaf_rows[i as usize];
                let spanning = bottom < r && top > r && a != r && b != r;
                if spanning {
                    // As `left_crossing` counts it: +1 if the start is at or above the
                    // query, -1 if the end is.
                    let crossing = i32::from(a > r) - i32::from(b > r);
                    spans.push((
                        i,
                        Span {
                            hi_x: l.hi.x,
                            lo_x: l.lo.x,
                            piece: l.piece,
                            crossings: crossing,
                        },
                    ));
                } else {
                    loose.push(i);
                }
            }
            let row = &mut spans[first..];
            row.sort_by(|s, t| s.1.hi_x.total_cmp(&t.1.hi_x));
            // Left sides in order: a span reaching left of one kept before it joins the
            // others.
            let (mut kept, mut least, mut crossings) = (first, f64::NEG_INFINITY, 0);
            for k in first..spans.len() {
                let (i, mut s) = spans[k];
                if s.lo_x >= least {
                    least = s.lo_x;
                    crossings += s.crossings;
                    s.crossings = crossings;
                    spans[kept] = (i, s);
                    kept += 1;
                } else {
                    loose.push(i);
                }
            }
            spans.truncate(kept);
            // Boundary order (the hits are sorted anyway; this keeps the list as documented).
            loose[loose_first..].sort_unstable();
            if loose.len() - loose_first > MOST_LOOSE {
                loose.truncate(loose_first);
                starts[r].loose |= WALK;
            }
            starts.push(RowStart {
                spans: spans.len() as u32,
                loose: loose.len() as u32,
            });
        }
        Self {
            rows,
            starts,
            spans: spans.into_iter().map(|(_, s)| s).collect(),
            loose,
            leaves,
        }
    }

    /// Adds to `sum` the crossings of every leaf lying wholly left of `q` (its chord's, as
    /// [`WindingSum::left_crossing`] counts them), and pushes onto `hits` the pieces whose
    /// leaf's box holds `q` (in no particular order), for a `q` with no NaN coordinate; a leaf
    /// above, below or right of `q` adds nothing. Returns the leaves decided by their chord
    /// one by one; or `None`, adding nothing, if `q`'s row is left to the walk.
    #[inline]
    pub(super) fn add(
        &self,
        q: Point,
        sum: &mut WindingSum,
        hits: &mut SmallVec<[u32; 8]>,
    ) -> Option<usize> {
        if !self.rows.spans(q.y) {
            return Some(0);
        }
        let r = self.rows.row(q.y);
        let (start, end) = (self.starts[r], self.starts[r + 1]);
        if start.loose & WALK != 0 {
            return None;
        }
        let spans = &self.spans[start.spans as usize..end.spans as usize];
        let left = spans.partition_point(|s| s.hi_x < q.x);
        if left > 0 {
            sum.add_left_crossings(i64::from(spans[left - 1].crossings));
        }
        // Right of `left`, a span holds q exactly when its left side is not right of q.
        for s in spans[left..].iter().take_while(|s| s.lo_x <= q.x) {
            hits.push(s.piece);
        }
        let mut decided = 0;
        for &i in &self.loose[start.loose()..end.loose()] {
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
        Some(decided)
    }

    /// Are every row's spans in order of both sides (so a query's scan stops at its first
    /// span that does not hold it)? (A probe for the tests.)
    #[cfg(test)]
    pub(super) fn spans_in_order(&self) -> bool {
        self.starts.windows(2).all(|w| {
            self.spans[w[0].spans as usize..w[1].spans as usize]
                .windows(2)
                .all(|p| p[0].hi_x <= p[1].hi_x && p[0].lo_x <= p[1].lo_x)
        })
    }

    /// The rows left to the walk. (A probe for the tests.)
    #[cfg(test)]
    pub(super) fn rows_left_to_walk(&self) -> usize {
        self.starts.iter().filter(|s| s.loose & WALK != 0).count()
    }
}
