//! The faces of IGES B-rep solids (IGES 5.3, section 4.25 on: 510 face, 508 loop, 504 edge
//! list; the 186 solids and 514 shells that hold them are read in `faces`).
//!
//! - 510: `SURF, N, OF, LOOP1..LOOPN`; `OF = 1`: the first loop is the outer one; `OF = 0`:
//!   the outer boundary is the surface's parameter range (as a 144 with `N1 = 0`).
//! - 508: `N`, then per edge use `TYPE, EDGE, NDX, OF, K, (ISOP, CURV) x K`:
//!   - `TYPE = 0`: an edge, entry `NDX` (from 1) of the 504 edge list `EDGE`. Its `K`
//!     parameter-space curves run in the loop's direction as written (Open CASCADE writes them
//!     so, whatever `OF`, and reads them so); `OF` says whether the loop runs along the edge's
//!     model curve (1) or against it (0): the 3-D edge and, where there is no parameter-space
//!     curve (`K = 0`, Open CASCADE's planes), the model curve mapped into the plane's `(u,
//!     v)` (on another surface its pcurve computed by `rs_geom::pcurve`) are taken in that
//!     direction.
//!   - `TYPE = 1`: a vertex of the 502 vertex list `EDGE`: a degenerate edge (a pole of a
//!     sphere), whose parameter-space curves (Open CASCADE writes the pole's segment) are part
//!     of the loop; it has no 3-D edge.
//! - 504: `N, (CURV, SVP, SV, TVP, TV) x N`: each edge's model curve and its vertices; the
//!   edge is the model curve on its parameter interval.

use std::rc::Rc;

use rs_geom::brep::Face;
use rs_spline::NurbsCurve;
use rs_spline::prelude::*;

use super::Iges;
use super::curves::{Piece, leaf_edges};
use super::directory::DirEntry;
use super::error::IgesError;
use super::faces::{FaceLayout, LoopCurves};
use super::surfaces::SurfaceInfo;

/// An entry of a 504 edge list: the model curve's pointer (its vertices are not needed: the
/// edge is the curve's interval).
#[derive(Clone, Copy, Debug)]
pub(super) struct EdgeEntry {
    /// The model curve.
    curve: usize,
}

impl Iges<'_> {
    /// The loops of a 510 face.
    pub(super) fn brep_face(
        &self,
        e: &DirEntry,
        face: &mut Face,
    ) -> Result<Vec<Vec<NurbsCurve>>, IgesError> {
        let mut p = self.params(e)?;
        let surf = p.pointer("SURF")?;
        let n = p.count("N")?;
        let layout = FaceLayout {
            flag: "OF",
            outer: p.int("OF")?,
            loop_entity: (508, "loop", "a 508 loop"),
        };
        let loops = p.pointers("N", n, "LOOP")?;
        self.face_loops(e, face, surf, &layout, loops, Self::brep_loop)
    }

    /// Entry `ndx` (1-based) of the 504 edge list at `list`. Lists are read once (a shell's
    /// faces all index the same list).
    fn edge_entry(&self, from: &str, list: usize, ndx: usize) -> Result<EdgeEntry, IgesError> {
        let l = self.entry_of(list, from, 504, "a 504 edge list")?;
        let cached = self.edge_lists.borrow().get(&l.de).cloned();
        let entries = match cached {
            Some(c) => c,
            None => {
                let mut p = self.params(l)?;
                let n = p.count("N")?;
                p.check_count("N", n, 5)?;
                let mut entries = Vec::with_capacity(n);
                for _ in 0..n {
                    entries.push(EdgeEntry {
                        curve: p.pointer("CURV")?,
                    });
                    for name in ["SVP", "SV", "TVP", "TV"] {
                        p.skip(name)?;
                    }
                }
                let entries = Rc::new(entries);
                self.edge_lists.borrow_mut().insert(l.de, entries.clone());
                entries
            }
        };
        ndx.checked_sub(1)
            .and_then(|i| entries.get(i).copied())
            .ok_or_else(|| IgesError::ListIndex {
                from: from.to_string(),
                what: "edge",
                index: ndx,
                list_kind: "504 edge",
                list: l.de,
                count: entries.len(),
            })
    }

    /// The loop of the 508 `l` of a face on the surface `info`; its 3-D edges and pcurve bound
    /// recorded in `face`.
    fn brep_loop(&self, l: &DirEntry, info: &SurfaceInfo, face: &mut Face) -> LoopCurves {
        let who = self.who(l);
        let mut p = self.params(l)?;
        let n = p.count("N")?;
        p.check_count("N", n, 5)?;
        let mut uses = Vec::with_capacity(n);
        for _ in 0..n {
            let kind = p.int("TYPE")?;
            let list = p.pointer("EDGE")?;
            let ndx = p.count("NDX")?;
            let along = p.int("OF")?;
            let k = p.count("K")?;
            p.check_count("K", k, 2)?;
            let mut curves = Vec::with_capacity(k);
            for _ in 0..k {
                p.skip("ISOP")?;
                curves.push(p.pointer("CURV")?);
            }
            uses.push((kind, list, ndx, along, curves));
        }
        let mut pieces: Vec<Piece> = Vec::new();
        let mut loop_edges = Vec::new();
        for (i, (kind, list, ndx, along, curves)) in uses.into_iter().enumerate() {
            let from = format!("{who}: edge {}", i + 1);
            let mut these = Vec::new();
            for c in curves {
                let from = format!("{from}: parameter-space curve");
                for leaf in self.curve_leaves(c, &from)? {
                    these.push(leaf.param_piece()?);
                }
            }
            match kind {
                // A vertex: its parameter-space curves (a pole's segment), no 3-D edge.
                1 => {}
                0 => {
                    let reversed = along == 0;
                    let entry = self.edge_entry(&from, list, ndx)?;
                    let leaves = self.curve_leaves(entry.curve, &format!("{from}: model curve"));
                    if these.is_empty() {
                        let near = pieces.last().map(|p| p.curve.end_point());
                        these = self.model_pieces(
                            &leaves.clone()?,
                            reversed,
                            info,
                            near,
                            &mut face.pcurve_deviation,
                        )?;
                    }
                    if let Ok(leaves) = leaves {
                        loop_edges.extend(leaf_edges(&leaves, reversed));
                    }
                }
                t => {
                    return Err(IgesError::Flag {
                        who: from,
                        name: "type".into(),
                        value: t,
                        expected: "0 (edge) or 1 (vertex)",
                    });
                }
            }
            pieces.extend(these);
        }
        if pieces.is_empty() {
            return Err(IgesError::Nothing { who, what: "edges" });
        }
        let closed = self.close_loop(l.de, l.de, pieces, &mut loop_edges, info);
        face.edges.push(loop_edges);
        closed
    }
}
