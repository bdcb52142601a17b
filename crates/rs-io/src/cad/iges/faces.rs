//! Faces: which entities are faces, shells and solids and in what order, the loops of trimmed
//! (144) and bounded (143) surfaces, and how a loop is closed.
//!
//! - 144 trimmed surface: `PTS, N1, N2, PTO, PTI1..PTIN2`; the outer boundary (a 142, or the
//!   surface's parameter rectangle when `N1 = 0`) then the inner ones.
//! - 142 curve on a parametric surface: `CRTN, SPTR, BPTR, CPTR, PREF`; the loop is curve
//!   `BPTR` in parameter space, or, if `BPTR = 0`, the model curve `CPTR` mapped onto a plane
//!   or, on another surface, its pcurve computed (`rs_geom::pcurve`); `CPTR` gives the loop's
//!   3-D edges.
//! - 143 bounded surface: `TYPE, SPTR, N, BDPT1..BDPTN`, the first boundary taken as the
//!   outer one; 141 boundary: `TYPE, PREF, SPTR, N`, then per model curve `CRVPT, SENSE, K`
//!   and its `K` parameter-space curves (sense 2: the pieces and the edge reversed).
//!
//! A loop whose pieces do not meet is closed the way Open CASCADE closes its wires, where that
//! is sure: a gap whose whole segment is one point of the surface (its ends and its middle:
//! a pole, the apex of a surface of revolution) is the degenerate edge the writer left out
//! and becomes that segment; pieces that meet only modulo the surface's periods (the seams of
//! a torus written in another order) are put in the order in which they meet. Other gaps
//! refuse the face, naming the loop and the two pieces.

use std::collections::HashMap;
use std::rc::Rc;

use rs_geom::brep::{Edge, Face, FaceError, ReadError, Shell, Solid};
use rs_geom::surface::{ParamSurface, Surface};
use rs_spline::prelude::*;
use rs_spline::{BoundingBox, NurbsCurve, Point, segment};

use super::curves::{Piece, Placed, leaf_edges, reverse_pieces};
use super::directory::DirEntry;
use super::error::IgesError;
use super::surfaces::SurfaceInfo;
use super::{Iges, MAX_DEPTH};

/// The faces, shells and solids of the file, in Open CASCADE's order.
pub(super) fn model(iges: &Iges<'_>) -> (Vec<Face>, Vec<Shell>, Vec<Solid>) {
    let walk = iges.structure();
    let faces = walk
        .faces
        .iter()
        .map(|&(i, same_sense)| iges.face(&iges.dir[i], same_sense))
        .collect();
    (faces, walk.shells, walk.solids)
}

/// True for the group forms of 402 (with or without back pointers, ordered or not).
fn is_group(e: &DirEntry) -> bool {
    e.kind == 402 && matches!(e.form, 1 | 7 | 14 | 15)
}

/// What a grouping entity holds (pointers as written, checked when followed).
#[derive(Clone, Debug)]
enum Members {
    /// A 402 group's members.
    Group(Vec<usize>),
    /// A 186's shells, the outer one first, each with its orientation flag.
    Solid(Vec<(usize, i64)>),
    /// A 514's faces, each with its orientation flag.
    Shell(Vec<(usize, i64)>),
}

impl Members {
    /// The entities held.
    fn pointers(&self) -> Vec<usize> {
        match self {
            Members::Group(m) => m.clone(),
            Members::Solid(m) | Members::Shell(m) => m.iter().map(|m| m.0).collect(),
        }
    }
}

/// The walk of the file's roots: faces with their orientation, shells and solids, in order.
struct Walk {
    /// What each grouping entity holds, by directory index.
    members: Vec<Option<Members>>,
    /// Entities visited.
    seen: Vec<bool>,
    /// The faces: directory index and `same_sense`.
    faces: Vec<(usize, bool)>,
    /// Face number of each face entity listed, by directory index.
    face_of: HashMap<usize, usize>,
    /// Shell number of each shell entity listed, by directory index.
    shell_of: HashMap<usize, usize>,
    shells: Vec<Shell>,
    solids: Vec<Solid>,
}

impl Walk {
    /// The directory index of pointer `m`, if it is one.
    fn index(&self, m: usize) -> Option<usize> {
        (m % 2 == 1 && m / 2 < self.seen.len()).then_some(m / 2)
    }

    /// Lists face `i` (once) with its orientation; its number.
    fn face(&mut self, i: usize, same_sense: bool) -> usize {
        if let Some(&k) = self.face_of.get(&i) {
            return k;
        }
        self.seen[i] = true;
        self.faces.push((i, same_sense));
        self.face_of.insert(i, self.faces.len() - 1);
        self.faces.len() - 1
    }

    /// Lists the 514 shell `i` (once) and its 510 faces; `reversed` for a shell its solid uses
    /// reversed. Its number, or `None` for a pointer that is not a 514 that could be read.
    fn shell(&mut self, iges: &Iges<'_>, i: usize, reversed: bool) -> Option<usize> {
        if let Some(&k) = self.shell_of.get(&i) {
            return Some(k);
        }
        let Some(Members::Shell(faces)) = self.members[i].clone() else {
            return None;
        };
        self.seen[i] = true;
        let mut listed = Vec::with_capacity(faces.len());
        for (ptr, of) in faces {
            if let Some(f) = self.index(ptr)
                && iges.dir[f].kind == 510
            {
                listed.push(self.face(f, (of == 1) != reversed));
            }
        }
        let e = &iges.dir[i];
        self.shells.push(Shell {
            entity: format!("DE {}", e.de),
            faces: listed,
            closed: e.form == 1,
        });
        self.shell_of.insert(i, self.shells.len() - 1);
        Some(self.shells.len() - 1)
    }

    /// Visits entity `i` and what it holds.
    fn expand(&mut self, iges: &Iges<'_>, i: usize, depth: usize) {
        if depth > MAX_DEPTH {
            return;
        }
        let e = &iges.dir[i];
        match e.kind {
            143 | 144 | 510 if !self.seen[i] => {
                self.face(i, true);
            }
            186 => {
                if self.seen[i] {
                    return;
                }
                self.seen[i] = true;
                let Some(Members::Solid(shells)) = self.members[i].clone() else {
                    return;
                };
                let mut listed = Vec::with_capacity(shells.len());
                let mut outer = false;
                for (k, (ptr, flag)) in shells.into_iter().enumerate() {
                    let shell = self.index(ptr).and_then(|s| self.shell(iges, s, flag == 0));
                    if let Some(s) = shell {
                        listed.push(s);
                        outer |= k == 0;
                    }
                }
                // A solid whose outer shell cannot be read is not listed (its voids' faces
                // and shells are).
                if outer {
                    self.solids.push(Solid {
                        entity: format!("DE {}", e.de),
                        shells: listed,
                    });
                }
            }
            514 => {
                let _ = self.shell(iges, i, false);
            }
            402 if is_group(e) => {
                if self.seen[i] {
                    return;
                }
                self.seen[i] = true;
                let Some(Members::Group(members)) = self.members[i].clone() else {
                    return;
                };
                for m in members {
                    if let Some(k) = self.index(m) {
                        self.expand(iges, k, depth + 1);
                    }
                }
            }
            _ => {}
        }
    }
}

/// How a face entity (144 or 510) lists its loops: its outer-loop flag (144's `N1`, 510's
/// `OF`: 0 when the surface's natural rectangle is the outer loop, 1 when the face's first
/// loop is) and the entity each loop pointer points at.
pub(super) struct FaceLayout {
    /// The flag's name in the standard, for errors.
    pub(super) flag: &'static str,
    /// Its value as written.
    pub(super) outer: i64,
    /// The loops' entity type (142 or 508), what a loop is called in errors, and what an
    /// entry of that type is.
    pub(super) loop_entity: (i64, &'static str, &'static str),
}

/// A loop's `(u, v)` curves, or why it cannot be read.
pub(super) type LoopCurves = Result<Vec<NurbsCurve>, IgesError>;

impl Iges<'_> {
    /// The members of a 402 group, 186 solid or 514 shell, or `None` if its record cannot be
    /// read (then it holds nothing).
    fn members(&self, e: &DirEntry) -> Option<Members> {
        let mut p = self.params(e).ok()?;
        match e.kind {
            402 => {
                let n = p.count("N").ok()?;
                p.check_count("N", n, 1).ok()?;
                let m: Option<Vec<usize>> = (0..n).map(|_| p.pointer("member").ok()).collect();
                m.map(Members::Group)
            }
            186 => {
                let shell = p.pointer("SHELL").ok()?;
                let sof = p.int("SOF").ok()?;
                let n = p.count("N").ok()?;
                p.check_count("N", n, 2).ok()?;
                let mut out = vec![(shell, sof)];
                for _ in 0..n {
                    out.push((p.pointer("VOID").ok()?, p.int("VOF").ok()?));
                }
                Some(Members::Solid(out))
            }
            514 => {
                let n = p.count("N").ok()?;
                p.check_count("N", n, 2).ok()?;
                let mut out = Vec::with_capacity(n);
                for _ in 0..n {
                    out.push((p.pointer("FACE").ok()?, p.int("OF").ok()?));
                }
                Some(Members::Shell(out))
            }
            _ => None,
        }
    }

    /// The faces (with their orientation), shells and solids: roots (not physically
    /// dependent, not a member of a group, solid or shell; a 510 that nothing holds is a root
    /// whatever its status) in directory order; groups, solids and shells expanded in member
    /// order (each entity once).
    fn structure(&self) -> Walk {
        let n = self.dir.len();
        let mut walk = Walk {
            members: vec![None; n],
            seen: vec![false; n],
            faces: Vec::new(),
            face_of: HashMap::new(),
            shell_of: HashMap::new(),
            shells: Vec::new(),
            solids: Vec::new(),
        };
        let mut held = vec![false; n];
        for (i, e) in self.dir.iter().enumerate() {
            if is_group(e) || matches!(e.kind, 186 | 514) {
                walk.members[i] = self.members(e);
                for m in walk.members[i].iter().flat_map(Members::pointers) {
                    if let Some(k) = walk.index(m)
                        && k != i
                    {
                        held[k] = true;
                    }
                }
            }
        }
        for (i, e) in self.dir.iter().enumerate() {
            let independent = !matches!(e.subordinate, 1 | 3) || e.kind == 510;
            if !held[i] && independent {
                walk.expand(self, i, 0);
            }
        }
        walk
    }

    /// One face: its entity, surface, loops, edges.
    fn face(&self, e: &DirEntry, same_sense: bool) -> Face {
        let mut face = Face {
            entity: format!("DE {}", e.de),
            surface_name: String::from("unknown"),
            surface: None,
            surface_error: None,
            same_sense,
            loops: Ok(Vec::new()),
            edges: Vec::new(),
            pcurve_deviation: None,
            natural_bounds: false,
        };
        let loops = match e.kind {
            144 => self.trimmed_surface(e, &mut face),
            510 => self.brep_face(e, &mut face),
            _ => self.bounded_surface(e, &mut face),
        };
        face.loops = loops.map_err(|e| FaceError::Read(ReadError::new(e)));
        face
    }

    /// The surface entry `ptr` of face `e`: its name, surface (or why not) written to `face`.
    pub(super) fn face_surface(
        &self,
        e: &DirEntry,
        ptr: usize,
        face: &mut Face,
    ) -> Result<(&DirEntry, Rc<SurfaceInfo>), IgesError> {
        let s = self.entry(ptr, &format!("{}: surface", self.who(e)))?;
        face.surface_name = format!("{} ({})", s.kind, super::type_name(s.kind));
        let info = self.surface_info(s);
        match &info.surface {
            Ok(surface) => face.surface = Some(surface.clone()),
            Err(err) => face.surface_error = Some(FaceError::Read(ReadError::new(err.clone()))),
        }
        Ok((s, info))
    }

    /// 144 trimmed surface.
    fn trimmed_surface(
        &self,
        e: &DirEntry,
        face: &mut Face,
    ) -> Result<Vec<Vec<NurbsCurve>>, IgesError> {
        let mut p = self.params(e)?;
        let pts = p.pointer("PTS")?;
        let n1 = p.int("N1")?;
        let n2 = p.count("N2")?;
        let pto = p.pointer("PTO")?;
        let inner = p.pointers("N2", n2, "PTI")?;
        let loops = (n1 == 1).then_some(pto).into_iter().chain(inner);
        let layout = FaceLayout {
            flag: "N1",
            outer: n1,
            loop_entity: (142, "boundary", "a 142 curve on a parametric surface"),
        };
        self.face_loops(e, face, pts, &layout, loops, Self::curve_on_surface)
    }

    /// The loops of face `e` (a 144 or a 510) on the surface at `surf`, each at a pointer of
    /// `loops` (of the layout's loop entity) read by `read_loop` (`(loop entry, surface, face)`
    /// to the loop's `(u, v)` curves, its 3-D edges and pcurve bound recorded in the face). With
    /// the outer flag 0 the surface's natural rectangle is the outer loop (the face has
    /// natural bounds when no loop follows); with 1 the first loop is the outer one.
    ///
    /// # Errors
    /// Another outer flag, no loop at all, or the errors of the surface and of `read_loop`.
    pub(super) fn face_loops(
        &self,
        e: &DirEntry,
        face: &mut Face,
        surf: usize,
        layout: &FaceLayout,
        loops: impl IntoIterator<Item = usize>,
        read_loop: fn(&Self, &DirEntry, &SurfaceInfo, &mut Face) -> LoopCurves,
    ) -> Result<Vec<Vec<NurbsCurve>>, IgesError> {
        let who = self.who(e);
        let (s, info) = self.face_surface(e, surf, face)?;
        let mut read = Vec::new();
        match layout.outer {
            0 => {
                read.push(self.rectangle(s, &info, layout.flag)?);
                face.edges.push(Vec::new());
            }
            1 => {}
            value => {
                return Err(IgesError::Flag {
                    who,
                    name: layout.flag.into(),
                    value,
                    expected: "0 or 1",
                });
            }
        }
        let natural = read.len();
        let (kind, role, what) = layout.loop_entity;
        for ptr in loops {
            let l = self.entry_of(ptr, &format!("{who}: {role}"), kind, what)?;
            read.push(read_loop(self, l, &info, face)?);
        }
        face.natural_bounds = natural == 1 && read.len() == 1;
        if read.is_empty() {
            return Err(IgesError::Nothing { who, what: "loops" });
        }
        Ok(read)
    }

    /// The loop of the 142 `c`, a boundary of a face on the surface `info`; its 3-D edges (from
    /// the model-space curve, if it reads) and pcurve bound recorded in `face`.
    fn curve_on_surface(&self, c: &DirEntry, info: &SurfaceInfo, face: &mut Face) -> LoopCurves {
        let who = self.who(c);
        let mut p = self.params(c)?;
        let _crtn = p.int("CRTN")?;
        let _sptr = p.pointer("SPTR")?;
        let bptr = p.pointer("BPTR")?;
        let cptr = p.pointer("CPTR")?;
        let model =
            (cptr != 0).then(|| self.curve_leaves(cptr, &format!("{who}: model-space curve")));
        let mut loop_edges: Vec<Edge> = match &model {
            Some(Ok(leaves)) => leaves
                .iter()
                .map(|l| l.edge(false))
                .collect::<Result<_, _>>()
                .unwrap_or_default(),
            _ => Vec::new(),
        };
        let pieces = if bptr != 0 {
            let from = format!("{who}: parameter-space curve");
            self.curve_leaves(bptr, &from)?
                .iter()
                .map(|l| l.param_piece())
                .collect::<Result<Vec<_>, _>>()?
        } else {
            let leaves = match model {
                Some(m) => m?,
                None => self.curve_leaves(cptr, &format!("{who}: model-space curve"))?,
            };
            self.model_pieces(&leaves, false, info, None, &mut face.pcurve_deviation)?
        };
        let named = if bptr != 0 { bptr } else { c.de };
        let closed = self.close_loop(named, c.de, pieces, &mut loop_edges, info);
        face.edges.push(loop_edges);
        closed
    }

    /// The `(u, v)` pieces of the model-space curves `leaves` of one boundary curve or edge on
    /// a face's surface (`info`), in the loop's direction (the leaves run backwards when `reversed`): on a
    /// plane (108, 190, a flat 128) the curves mapped into it exactly; on another surface their
    /// pcurves computed by [`rs_geom::pcurve::pcurve`], the first starting near `near` (the end
    /// of the loop's piece before), their deviation bound raised into `deviation`. A plane or
    /// surface that could not be read gives its error.
    pub(super) fn model_pieces(
        &self,
        leaves: &[Placed],
        reversed: bool,
        info: &SurfaceInfo,
        near: Option<Point>,
        deviation: &mut Option<f64>,
    ) -> Result<Vec<Piece>, IgesError> {
        if let Some(plane) = info.plane {
            let mut pieces = leaves
                .iter()
                .map(|l| l.plane_piece(&plane, self.tolerance))
                .collect::<Result<Vec<_>, _>>()?;
            if reversed {
                reverse_pieces(&mut pieces);
            }
            return Ok(pieces);
        }
        let surface = info.surface.as_ref().map_err(Clone::clone)?;
        let mut pieces: Vec<Piece> = Vec::new();
        let ordered: Vec<&Placed> = if reversed {
            leaves.iter().rev().collect()
        } else {
            leaves.iter().collect()
        };
        for leaf in ordered {
            let start = pieces.last().map(|p| p.curve.end_point()).or(near);
            let (these, d) = leaf.computed_pieces(surface, reversed, self.tolerance, start)?;
            *deviation = Some(deviation.unwrap_or(0.0).max(d));
            pieces.extend(these);
        }
        Ok(pieces)
    }

    /// The parameter rectangle of surface `s` as a loop (for a 144 with `N1 = 0`, a 510 with
    /// `OF = 0`; `flag` says which).
    pub(super) fn rectangle(
        &self,
        s: &DirEntry,
        info: &SurfaceInfo,
        flag: &'static str,
    ) -> Result<Vec<NurbsCurve>, IgesError> {
        let [u0, u1, v0, v1] = match &info.bounds {
            Ok(b) => *b,
            Err(IgesError::NoNaturalBounds { who, kind, .. }) => {
                return Err(IgesError::NoNaturalBounds {
                    who: who.clone(),
                    flag,
                    kind: *kind,
                });
            }
            Err(e) => return Err(e.clone()),
        };
        let who = self.who(s);
        let c = [(u0, v0), (u1, v0), (u1, v1), (u0, v1)].map(|(u, v)| Point::new(u, v));
        (0..4)
            .map(|i| segment(c[i], c[(i + 1) % 4]).map_err(|e| IgesError::spline(&who, e)))
            .collect()
    }

    /// The largest gap between consecutive pieces of a loop in `(u, v)` that closes it: the
    /// model's closure gap ([`rs_geom::Tolerance::closure_gap`]) for the box of the pieces'
    /// control points.
    fn loop_tolerance(&self, pieces: &[Piece]) -> f64 {
        let bbox = pieces
            .iter()
            .map(|p| p.curve.control_bounding_box())
            .reduce(BoundingBox::union);
        match bbox {
            Some(b) => self.tolerance.closure_gap(&b, None),
            None => self.tolerance.stated().unwrap_or(0.0),
        }
    }

    /// Closes the loop `pieces` of entity `named` where it is sure how (see the module
    /// documentation; bridges are named `bridge`), re-orders `edges` with the pieces, and
    /// checks that each piece ends where the next starts.
    pub(super) fn close_loop(
        &self,
        named: usize,
        bridge: usize,
        mut pieces: Vec<Piece>,
        edges: &mut Vec<Edge>,
        info: &SurfaceInfo,
    ) -> Result<Vec<NurbsCurve>, IgesError> {
        let tol = self.loop_tolerance(&pieces);
        let open = |ps: &[Piece]| (0..ps.len()).any(|i| meets(ps, i, tol).is_none());
        if open(&pieces)
            && let Ok(surface) = &info.surface
        {
            let before = pieces.len();
            pieces = self.bridge_poles(bridge, pieces, surface, tol);
            if open(&pieces)
                && let Some(order) = chain_order(&pieces, surface, tol)
            {
                if pieces.len() == before && edges.len() == before {
                    *edges = order.iter().map(|&k| edges[k].clone()).collect();
                }
                pieces = order.into_iter().map(|k| pieces[k].clone()).collect();
            }
        }
        check_gaps(named, &pieces, tol)?;
        Ok(pieces.into_iter().map(|p| p.curve).collect())
    }

    /// Adds the degenerate edges the file leaves out at the poles of its surface: where the
    /// end of piece `i` and the start of piece `i + 1` (or the last and the first) are apart in
    /// `(u, v)` but the segment between them is one point of the surface (its ends and its
    /// middle map to the same point within the model's coincidence tolerance, and its ends lie
    /// in the surface's parameter box, where the surface is not clamped to one corner), that
    /// segment, the edge Open CASCADE adds there.
    fn bridge_poles(
        &self,
        bridge: usize,
        pieces: Vec<Piece>,
        surface: &Surface,
        tol: f64,
    ) -> Vec<Piece> {
        let n = pieces.len();
        let (bx, periods) = (surface.param_box(), surface.periods());
        // Within the box in each parameter that is not periodic (a periodic one may take any
        // value).
        let in_box = |p: Point| {
            let c = bx.clamp([p.x, p.y]);
            let c = Point::new(
                if periods[0].is_some() { p.x } else { c[0] },
                if periods[1].is_some() { p.y } else { c[1] },
            );
            c.distance(p) <= tol
        };
        let mut out = Vec::with_capacity(n + 2);
        for i in 0..n {
            out.push(pieces[i].clone());
            if meets(&pieces, i, tol).is_some() {
                continue;
            }
            let (a, b) = (
                pieces[i].curve.end_point(),
                pieces[(i + 1) % n].curve.start_point(),
            );
            let mid = a.lerp(b, 0.5);
            if !(in_box(a) && in_box(b)) {
                continue;
            }
            let [pa, pb, pm] = [a, b, mid].map(|p| surface.point([p.x, p.y]));
            let size = pa.max_abs().max(pb.max_abs()).max(pm.max_abs());
            let same = self.tolerance.coincidence(size);
            if pa.distance(pm) <= same
                && pb.distance(pm) <= same
                && let Ok(curve) = segment(a, b)
            {
                out.push(Piece { de: bridge, curve });
            }
        }
        out
    }

    /// 143 bounded surface with 141 boundaries.
    fn bounded_surface(
        &self,
        e: &DirEntry,
        face: &mut Face,
    ) -> Result<Vec<Vec<NurbsCurve>>, IgesError> {
        let who = self.who(e);
        let mut p = self.params(e)?;
        let _kind = p.int("TYPE")?;
        let sptr = p.pointer("SPTR")?;
        let n = p.count("N")?;
        let bounds = p.pointers("N", n, "BDPT")?;
        let (_, info) = self.face_surface(e, sptr, face)?;
        if n == 0 {
            return Err(IgesError::Nothing {
                who,
                what: "boundaries",
            });
        }
        bounds
            .into_iter()
            .map(|b| self.boundary(e, b, &info, &mut face.edges, &mut face.pcurve_deviation))
            .collect()
    }

    /// The loop of a 141 boundary of face `face` on surface `s`; its edges appended to
    /// `edges`.
    fn boundary(
        &self,
        face: &DirEntry,
        ptr: usize,
        info: &SurfaceInfo,
        edges: &mut Vec<Vec<Edge>>,
        deviation: &mut Option<f64>,
    ) -> Result<Vec<NurbsCurve>, IgesError> {
        let b = self.entry_of(
            ptr,
            &format!("{}: boundary", self.who(face)),
            141,
            "a 141 boundary",
        )?;
        let who = self.who(b);
        let mut p = self.params(b)?;
        let _kind = p.int("TYPE")?;
        let _pref = p.int("PREF")?;
        let _sptr = p.pointer("SPTR")?;
        let n = p.count("N")?;
        p.check_count("N", n, 3)?;
        let mut curves = Vec::with_capacity(n);
        for _ in 0..n {
            let model = p.pointer("CRVPT")?;
            let sense = p.int("SENSE")?;
            let k = p.count("K")?;
            p.check_count("K", k, 1)?;
            let mut params = Vec::with_capacity(k);
            for _ in 0..k {
                params.push(p.pointer("PSCPT")?);
            }
            curves.push((model, sense, params));
        }
        let mut pieces = Vec::new();
        let mut loop_edges = Vec::new();
        for (i, (model, sense, params)) in curves.into_iter().enumerate() {
            let from = format!("{who}: model curve {}", i + 1);
            let reversed = match sense {
                1 => false,
                2 => true,
                _ => {
                    return Err(IgesError::Flag {
                        who: from,
                        name: "sense".into(),
                        value: sense,
                        expected: "1 or 2",
                    });
                }
            };
            let leaves = self.curve_leaves(model, &from);
            let these = if params.is_empty() {
                let near = pieces.last().map(|p: &Piece| p.curve.end_point());
                self.model_pieces(&leaves.clone()?, reversed, info, near, deviation)?
            } else {
                let mut these = Vec::new();
                for ptr in params {
                    let from = format!("{who}: parameter-space curve of model curve {}", i + 1);
                    for l in self.curve_leaves(ptr, &from)? {
                        these.push(l.param_piece()?);
                    }
                }
                if reversed {
                    reverse_pieces(&mut these);
                }
                these
            };
            if let Ok(leaves) = leaves {
                loop_edges.extend(leaf_edges(&leaves, reversed));
            }
            pieces.extend(these);
        }
        let closed = self.close_loop(b.de, b.de, pieces, &mut loop_edges, info);
        edges.push(loop_edges);
        closed
    }
}

/// The gap in `(u, v)` after piece `i` of a loop (the last's to the first's start).
fn gap(pieces: &[Piece], i: usize) -> f64 {
    pieces[i]
        .curve
        .end_point()
        .distance(pieces[(i + 1) % pieces.len()].curve.start_point())
}

/// `Some(gap)` when piece `i` ends within `tol` of the next one's start (cyclically), `None`
/// when it does not (or the gap is not a number).
fn meets(pieces: &[Piece], i: usize, tol: f64) -> Option<f64> {
    Some(gap(pieces, i)).filter(|&g| g <= tol)
}

/// Checks that each piece ends where the next starts; `named` is the loop's entity.
fn check_gaps(named: usize, pieces: &[Piece], tolerance: f64) -> Result<(), IgesError> {
    for w in pieces.windows(2) {
        let gap = w[0].curve.end_point().distance(w[1].curve.start_point());
        if gap > tolerance || gap.is_nan() {
            return Err(IgesError::Gap {
                named,
                first: w[0].de,
                second: w[1].de,
                gap,
                tolerance,
            });
        }
    }
    Ok(())
}

/// The order in which the pieces of a loop meet, when they meet as written only modulo the
/// periods of `surface` (each gap a whole number of periods in each parameter, within `tol`)
/// and, in another order, exactly: from the first piece, each next piece is the unused one
/// starting where the last ends. `None` when the gaps are not whole periods or no order
/// closes.
fn chain_order(pieces: &[Piece], surface: &Surface, tol: f64) -> Option<Vec<usize>> {
    let periods = surface.periods();
    if periods.iter().all(Option::is_none) {
        return None;
    }
    let n = pieces.len();
    let whole = |d: f64, period: Option<f64>| match period {
        Some(p) if p > 0.0 => (d - p * (d / p).round()).abs() <= tol,
        _ => d.abs() <= tol,
    };
    for i in 0..n {
        let a = pieces[i].curve.end_point();
        let b = pieces[(i + 1) % n].curve.start_point();
        if !(whole(b.x - a.x, periods[0]) && whole(b.y - a.y, periods[1])) {
            return None;
        }
    }
    let mut used = vec![false; n];
    let mut order = vec![0];
    used[0] = true;
    while order.len() < n {
        let end = pieces[*order.last()?].curve.end_point();
        let next = (0..n)
            .filter(|&k| !used[k])
            .map(|k| (k, pieces[k].curve.start_point().distance(end)))
            .filter(|&(_, d)| d <= tol)
            .min_by(|a, b| a.1.total_cmp(&b.1))?
            .0;
        used[next] = true;
        order.push(next);
    }
    let last = pieces[*order.last()?].curve.end_point();
    (last.distance(pieces[0].curve.start_point()) <= tol).then_some(order)
}
