//! The winding number at points within the boundary tolerance: the average across the jump,
//! the same for a point on a curve bit for bit and for one within the tolerance of it.
//!
//! A query `q` in the band (some monotone box is near it, [`MonotoneBox::near_parameter`])
//! meets the boundary at *passages*: a piece and a parameter where the boundary comes within
//! the tolerance of `q`. Each piece with passages is cut there and the cut ends are moved onto
//! `q` (by at most the tolerance), so that `q` is an end point of every part. The adaptive
//! algorithm gives a part with `q` at an end the angle from its tangent at `q` to its far end
//! (Algorithm 5), without deciding on which side of the curve `q` lies: the jump of `+-pi`
//! across the curve is left out, which is the average of the two sides (`1/2` on a smooth
//! closed curve, the interior angle over `2 pi` at a corner, `0` inside a straight piece).
//! Every other piece adds its exact angle at `q`.

use smallvec::SmallVec;

use rs_boxes::MonotoneBox;
use rs_spline::Point;
use rs_spline::prelude::*;

use super::curve::{SubCurve, refine};
use super::sum::{AngleSum, ChordSink};
use super::{BoundaryIndex, QueryStats, WindingField};

/// Passages of a query: `(piece, local parameter)`, sorted, one per passage.
pub(crate) type Passages = SmallVec<[(u32, f64); 4]>;

/// Two parameters name the same passage when the boundary between them stays within this many
/// tolerances of the query (plus the rounding margin): the two monotone boxes on either side
/// of a point where a passage runs from one to the next each report it.
const SAME_PASSAGE_TOLERANCES: f64 = 8.0;

/// Up to this many pieces near one query, a passage at a piece's end is joined to one at the
/// start of any piece; past it, only of the next piece.
const MAX_JOINT_SEARCH: usize = 64;

impl WindingField {
    /// The passages of `q`: every piece within the boundary tolerance of `q` (in the sense of
    /// [`MonotoneBox::is_near`], the band of [`WindingField::is_on_boundary`]) with the local
    /// parameters where it passes; empty if `q` is not in the band.
    ///
    /// A passage is one stretch of boundary near `q`, reported once: the parameters two
    /// monotone boxes of one piece give for it are merged, and a passage that runs across the
    /// joint of two pieces (`q` near both, the joint a few tolerances away) is put at the
    /// joint on both, so that the stretch between is not counted as a detour round `q`.
    ///
    /// Builds the boundary index unless `q` lies outside every piece's frame (then it has no
    /// passage).
    pub(crate) fn passages(&self, q: Point) -> Passages {
        let mut found: Passages = SmallVec::new();
        let Some(index) = self.index_near(q) else {
            return found;
        };
        let boxes = index.boxes.boxes();
        for &i in index.grid.candidates(q) {
            let b = &boxes[i as usize];
            if let Some(t) = b.near_parameter(q, index.tol) {
                let piece = index.box_pieces[i as usize];
                found.push((piece, self.piece_parameter(piece, b, t)));
            }
        }
        if found.is_empty() {
            return found;
        }
        sort_passages(&mut found);
        let mut passages: Passages = SmallVec::new();
        for (piece, s) in found {
            if let Some(&(last_piece, last)) = passages.last()
                && last_piece == piece
                && self.part_near(index, piece, last, s, q)
            {
                continue;
            }
            passages.push((piece, s));
        }
        self.join_at_joints(index, &mut passages, q);
        passages
    }

    /// Moves to the joint the passages that run from the end of one piece into the start of
    /// another (or of the same closed piece): the last passage of a piece whose rest lies near
    /// `q` goes to its end, the first passage of a piece whose beginning lies near `q` and
    /// that starts there goes to its start. A piece lying wholly near `q` gets both.
    fn join_at_joints(&self, index: &BoundaryIndex, passages: &mut Passages, q: Point) {
        // Pieces of a loop meet within the joint gap.
        let reach = index.passage_reach() + self.joint_gap;
        // Per piece: its range in `passages`, and whether its rest and its beginning lie near.
        let mut groups: SmallVec<[(usize, usize, bool, bool); 4]> = SmallVec::new();
        let mut k = 0;
        while k < passages.len() {
            let piece = passages[k].0;
            let n = passages[k..].iter().take_while(|p| p.0 == piece).count();
            let (first, last) = (passages[k].1, passages[k + n - 1].1);
            groups.push((
                k,
                n,
                first == 0.0 || self.part_near(index, piece, 0.0, first, q),
                last == 1.0 || self.part_near(index, piece, last, 1.0, q),
            ));
            k += n;
        }
        let mut to_start: SmallVec<[bool; 4]> = SmallVec::from_elem(false, groups.len());
        let mut to_end: SmallVec<[bool; 4]> = SmallVec::from_elem(false, groups.len());
        let mut moved = false;
        // Any piece may start where another ends (loops close, chains restart); past
        // MAX_JOINT_SEARCH pieces near one query (many curves through one point) only the next
        // piece is tried, which keeps the search linear.
        let everywhere = groups.len() <= MAX_JOINT_SEARCH;
        for (g1, &(k1, _, _, end_near)) in groups.iter().enumerate() {
            if !end_near {
                continue;
            }
            let end = self.pieces[passages[k1].0 as usize].end_point();
            let candidates = if everywhere {
                0..groups.len()
            } else {
                g1 + 1..(g1 + 2).min(groups.len())
            };
            for (g2, &(k2, _, start_near, _)) in groups
                .iter()
                .enumerate()
                .skip(candidates.start)
                .take(candidates.len())
            {
                let start = self.pieces[passages[k2].0 as usize].start_point();
                let joined = (end.x - start.x).abs() <= reach && (end.y - start.y).abs() <= reach;
                // (A piece with one passage whose beginning and rest both lie near lies wholly
                // near `q`: it gets passages at both ends.)
                if start_near && joined {
                    to_end[g1] = true;
                    to_start[g2] = true;
                    moved = true;
                }
            }
        }
        if !moved {
            return;
        }
        let mut extra: Passages = SmallVec::new();
        for (g, &(k, n, _, _)) in groups.iter().enumerate() {
            let (at_start, at_end) = (to_start[g], to_end[g]);
            if at_start {
                passages[k].1 = 0.0;
            }
            if at_end {
                if n == 1 && at_start {
                    extra.push((passages[k].0, 1.0));
                } else {
                    passages[k + n - 1].1 = 1.0;
                }
            }
        }
        passages.extend(extra);
        sort_passages(passages);
    }

    /// The local parameter on piece `piece` of box `b`'s local parameter `t` (exactly 0 or 1
    /// at the piece's ends).
    fn piece_parameter(&self, piece: u32, b: &MonotoneBox, t: f64) -> f64 {
        let u = b.nurbs_parameter(t);
        let (a, z) = self.pieces[piece as usize].knot_span();
        ((u - a) / (z - a)).clamp(0.0, 1.0)
    }

    /// Does `piece` between local parameters `s0 <= s1` stay within
    /// [`BoundaryIndex::passage_reach`] of `q` (its control points do, in each coordinate)?
    fn part_near(&self, index: &BoundaryIndex, piece: u32, s0: f64, s1: f64, q: Point) -> bool {
        if s0 == s1 {
            return true;
        }
        let Some(part) = self.roots[piece as usize].part(s0, s1) else {
            return true; // the parameters a rounding apart: one point
        };
        let reach = index.passage_reach();
        part.points()
            .iter()
            .all(|&p| (p.x - q.x).abs() <= reach && (p.y - q.y).abs() <= reach)
    }

    /// Sends `sink` the contribution of every piece with passages (see the module
    /// documentation), each as one special value over the piece.
    pub(crate) fn add_passages<K: ChordSink>(
        &self,
        q: Point,
        passages: &Passages,
        sink: &mut K,
        stats: &mut QueryStats,
    ) {
        // Passages come from the boundary index: it is built (and so is its error otherwise,
        // which leaves no passage).
        let Ok(index) = self.boundary_index() else {
            return;
        };
        let mut rest = &passages[..];
        while let Some(&(piece, _)) = rest.first() {
            let n = rest.iter().take_while(|p| p.0 == piece).count();
            let params: SmallVec<[f64; 4]> = rest[..n].iter().map(|p| p.1).collect();
            rest = &rest[n..];
            let root = &self.roots[piece as usize];
            let value = cut_at_passages(root, &params, q, index.passage_reach(), stats);
            let b = &self.pieces[piece as usize];
            sink.special(value, b.start_point(), b.end_point());
        }
    }
}

/// The winding number (turns) at `q` of `piece` cut at the sorted local parameters `params`
/// (passages of `q`), each cut end moved onto `q`; a part between two passages that stays
/// within `reach` of `q` (a piece lying wholly near `q`) is a point and adds nothing.
fn cut_at_passages(
    piece: &SubCurve,
    params: &[f64],
    q: Point,
    reach: f64,
    stats: &mut QueryStats,
) -> f64 {
    let mut cuts: SmallVec<[(f64, bool); 6]> = SmallVec::new();
    if params.first() != Some(&0.0) {
        cuts.push((0.0, false));
    }
    cuts.extend(params.iter().map(|&s| (s, true)));
    if params.last() != Some(&1.0) {
        cuts.push((1.0, false));
    }
    let near = |p: &Point| (p.x - q.x).abs() <= reach && (p.y - q.y).abs() <= reach;
    let mut sum = AngleSum::new(q);
    for w in cuts.windows(2) {
        let ((s0, at_start), (s1, at_end)) = (w[0], w[1]);
        // A part too short to cut off (parameters a rounding apart) holds no angle.
        let Some(part) = piece.part(s0, s1) else {
            continue;
        };
        if at_start && at_end && part.points().iter().all(near) {
            continue;
        }
        let part = part.with_ends(at_start.then_some(q), at_end.then_some(q));
        refine(part, q, &mut sum, stats);
    }
    sum.turns
}

impl BoundaryIndex {
    /// How far from `q` a stretch of one passage may run: [`SAME_PASSAGE_TOLERANCES`]
    /// tolerances plus the rounding margin.
    fn passage_reach(&self) -> f64 {
        SAME_PASSAGE_TOLERANCES * self.tol + self.rounding
    }
}

/// Sorts passages by piece, then parameter, and drops repeats.
fn sort_passages(passages: &mut Passages) {
    passages.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    passages.dedup();
}
