//! The B-rep entities of IGES 5.3 (section 4.25 on): 186 manifold solid, 514 shell, 510 face,
//! 508 loop, 504 edge list.
//!
//! - 186: `SHELL, SOF, N, (VOID, VOF) x N`: the faces of the outer shell, then of the voids.
//! - 514: `N, (FACE, OF) x N`: its faces in order.
//! - 510: `SURF, N, OF, LOOP1..LOOPN`; `OF = 1`: the first loop is the outer one; `OF = 0`:
//!   the outer boundary is the surface's parameter rectangle (as a 144 with `N1 = 0`).
//! - 508: `N`, then per edge `TYPE, EDGE, NDX, OF, K, (ISOP, CURV) x K`: the edge's `K`
//!   parameter-space curves, reversed when `OF = 0` (the edge runs against its curve); an
//!   edge without them (`K = 0`) has its model curve (entry `NDX` of the 504 list `EDGE`)
//!   mapped onto a plane; a vertex (`TYPE = 1`) adds nothing.
//! - 504: `N, (CURV, SVP, SV, TVP, TV) x N`.

use super::curves::{Piece, Target};
use super::directory::DirEntry;
use super::{Iges, type_name};
use rs_spline::NurbsCurve;
use rs_spline::prelude::*;

impl Iges<'_> {
    /// The members of a 186 (outer shell, then voids) or a 514 (faces), or `None` if the
    /// record cannot be read.
    pub(super) fn brep_members(&self, e: &DirEntry) -> Option<Vec<usize>> {
        let mut p = self.params(e).ok()?;
        match e.kind {
            186 => {
                let shell = p.pointer("SHELL").ok()?;
                p.skip("SOF").ok()?;
                let n = p.count("N").ok()?;
                p.check_count("N", n, 2).ok()?;
                let mut out = vec![shell];
                for _ in 0..n {
                    out.push(p.pointer("VOID").ok()?);
                    p.skip("VOF").ok()?;
                }
                Some(out)
            }
            514 => {
                let n = p.count("N").ok()?;
                p.check_count("N", n, 2).ok()?;
                let mut out = Vec::with_capacity(n);
                for _ in 0..n {
                    out.push(p.pointer("FACE").ok()?);
                    p.skip("OF").ok()?;
                }
                Some(out)
            }
            _ => None,
        }
    }

    /// The loops of a 510 face.
    pub(super) fn brep_face(
        &self,
        e: &DirEntry,
        surface: &mut String,
    ) -> Result<Vec<Vec<NurbsCurve>>, String> {
        let who = self.who(e);
        let mut p = self.params(e)?;
        let surf = p.pointer("SURF")?;
        let n = p.count("N")?;
        let outer = p.int("OF")?;
        let ptrs = p.pointers("N", n, "LOOP")?;
        let s = self.surface_of(e, surf, surface)?;
        let mut loops = Vec::with_capacity(n + 1);
        match outer {
            1 => {}
            0 => loops.push(self.rectangle(s)?),
            f => return Err(format!("{who}: outer loop flag {f} (expected 0 or 1)")),
        }
        for ptr in ptrs {
            loops.push(self.brep_loop(e, ptr, s)?);
        }
        if loops.is_empty() {
            return Err(format!("{who}: no loops"));
        }
        Ok(loops)
    }

    /// The model curve `ndx` (1-based) of the 504 edge list at `list`. Lists are read once
    /// (a loop's edges all index the same list).
    fn edge_curve(&self, from: &str, list: usize, ndx: usize) -> Result<usize, String> {
        let l = self.entry(list, from)?;
        if l.kind != 504 {
            return Err(format!(
                "{from}: DE {} is a {} {}, not a 504 edge list",
                l.de,
                l.kind,
                type_name(l.kind)
            ));
        }
        let cached = self.edge_lists.borrow().get(&l.de).cloned();
        let curves = match cached {
            Some(c) => c,
            None => {
                let mut p = self.params(l)?;
                let n = p.count("N")?;
                p.check_count("N", n, 5)?;
                let mut curves = Vec::with_capacity(n);
                for _ in 0..n {
                    curves.push(p.pointer("CURV")?);
                    for name in ["SVP", "SV", "TVP", "TV"] {
                        p.skip(name)?;
                    }
                }
                let curves = std::rc::Rc::new(curves);
                self.edge_lists.borrow_mut().insert(l.de, curves.clone());
                curves
            }
        };
        ndx.checked_sub(1)
            .and_then(|i| curves.get(i).copied())
            .ok_or_else(|| {
                format!(
                    "{from}: edge {ndx} of the 504 edge list DE {}, which has {}",
                    l.de,
                    curves.len()
                )
            })
    }

    /// The loop of the 508 at `ptr`, of face `face` on surface `s`.
    fn brep_loop(
        &self,
        face: &DirEntry,
        ptr: usize,
        s: &DirEntry,
    ) -> Result<Vec<NurbsCurve>, String> {
        let l = self.entry(ptr, &format!("{}: loop", self.who(face)))?;
        if l.kind != 508 {
            return Err(format!(
                "{}: loop DE {} is a {} {}, not a 508 loop",
                self.who(face),
                l.de,
                l.kind,
                type_name(l.kind)
            ));
        }
        let who = self.who(l);
        let mut p = self.params(l)?;
        let n = p.count("N")?;
        p.check_count("N", n, 5)?;
        let mut edges = Vec::with_capacity(n);
        for _ in 0..n {
            let kind = p.int("TYPE")?;
            let list = p.pointer("EDGE")?;
            let ndx = p.count("NDX")?;
            let agrees = p.int("OF")?;
            let k = p.count("K")?;
            p.check_count("K", k, 2)?;
            let mut curves = Vec::with_capacity(k);
            for _ in 0..k {
                p.skip("ISOP")?;
                curves.push(p.pointer("CURV")?);
            }
            edges.push((kind, list, ndx, agrees, curves));
        }
        let mut pieces: Vec<Piece> = Vec::new();
        for (i, (kind, list, ndx, agrees, curves)) in edges.into_iter().enumerate() {
            let from = format!("{who}: edge {}", i + 1);
            if kind == 1 {
                continue; // a vertex: nothing to draw
            }
            let mut these = Vec::new();
            if curves.is_empty() {
                let model = self.edge_curve(&from, list, ndx)?;
                let Some(plane) = self.plane_map(s)? else {
                    return Err(format!(
                        "{from} has no parameter-space curve and the surface DE {} ({} {}) \
                         is not a plane",
                        s.de,
                        s.kind,
                        type_name(s.kind)
                    ));
                };
                self.curve_pieces(model, &from, &Target::Plane(plane), &mut these)?;
            } else {
                for c in curves {
                    self.curve_pieces(c, &from, &Target::Param, &mut these)?;
                }
            }
            if agrees == 0 {
                these.reverse();
                for piece in &mut these {
                    piece.curve = piece.curve.reversed();
                }
            }
            pieces.extend(these);
        }
        if pieces.is_empty() {
            return Err(format!("{who}: no edges"));
        }
        self.check_gaps(l.de, &pieces)?;
        Ok(pieces.into_iter().map(|p| p.curve).collect())
    }
}
