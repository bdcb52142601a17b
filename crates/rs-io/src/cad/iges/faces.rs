//! Faces: which entities are faces and in what order, their surfaces, and their loops.
//!
//! - 144 trimmed surface: `PTS, N1, N2, PTO, PTI1..PTIN2`; the outer boundary (a 142, or the
//!   surface's parameter rectangle when `N1 = 0`) then the inner ones.
//! - 142 curve on a parametric surface: `CRTN, SPTR, BPTR, CPTR, PREF`; the loop is curve
//!   `BPTR` in parameter space, or, if `BPTR = 0`, the model curve `CPTR` mapped onto a plane.
//! - 143 bounded surface: `TYPE, SPTR, N, BDPT1..BDPTN`, the first boundary taken as the
//!   outer one; 141 boundary: `TYPE, PREF, SPTR, N`, then per model curve `CRVPT, SENSE, K`
//!   and its `K` parameter-space curves (sense 2: the pieces reversed).
//!
//! Surface parameter rectangles (for `N1 = 0`) are known for 128 (its `U0, U1, V0, V1`).
//! Planes for model-space curves: 108 (axes chosen by this reader: origin the plane's point
//! nearest the world origin, `u` along the world axis least aligned with the normal projected
//! onto the plane, `v = n x u`; the IGES standard does not parametrise a 108), and a 128 of
//! degree 1 x 1 with four control points forming a parallelogram and equal weights (then the
//! surface is affine in `(u, v)`). Other flat 128s are refused.

use rs_spline::prelude::*;
use rs_spline::segment;

use super::curves::{Piece, Target};
use super::directory::DirEntry;
use super::maps::{PlaneMap, cross, dot, sub};
use super::{Iges, MAX_DEPTH, type_name};
use rs_geom::brep::Face;

use crate::cad::legacy_face;

/// The faces of the file, in Open CASCADE's order.
pub(super) fn faces(iges: &Iges<'_>) -> Vec<Face> {
    iges.face_order()
        .into_iter()
        .map(|i| iges.face(&iges.dir[i]))
        .collect()
}

/// The 3-D start and end of a curve.
type Ends = ([f64; 3], [f64; 3]);

/// The distance between two 3-D points.
fn dist3(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(a, b);
    dot(d, d).sqrt()
}

/// True for the group forms of 402 (with or without back pointers, ordered or not).
fn is_group(e: &DirEntry) -> bool {
    e.kind == 402 && matches!(e.form, 1 | 7 | 14 | 15)
}

impl Iges<'_> {
    /// The members of a 402 group, or `None` if its record cannot be read.
    fn group_members(&self, e: &DirEntry) -> Option<Vec<usize>> {
        let mut p = self.params(e).ok()?;
        let n = p.count("N").ok()?;
        p.check_count("N", n, 1).ok()?;
        (0..n).map(|_| p.pointer("member").ok()).collect()
    }

    /// Indices into `dir` of the faces: roots (not physically dependent, not a member of a
    /// group, solid or shell) in directory order; groups, solids and shells expanded in member
    /// order (each entity once).
    fn face_order(&self) -> Vec<usize> {
        let n = self.dir.len();
        let mut in_group = vec![false; n];
        let mut members: Vec<Option<Vec<usize>>> = vec![None; n];
        for (i, e) in self.dir.iter().enumerate() {
            if is_group(e) || matches!(e.kind, 186 | 514) {
                members[i] = if e.kind == 402 {
                    self.group_members(e)
                } else {
                    self.brep_members(e)
                };
                for &m in members[i].iter().flatten() {
                    if m % 2 == 1 && m / 2 < n && m / 2 != i {
                        in_group[m / 2] = true;
                    }
                }
            }
        }
        let mut seen = vec![false; n];
        let mut out = Vec::new();
        for (i, e) in self.dir.iter().enumerate() {
            if !in_group[i] && !matches!(e.subordinate, 1 | 3) {
                self.expand(i, &members, &mut seen, &mut out, 0);
            }
        }
        out
    }

    fn expand(
        &self,
        i: usize,
        members: &[Option<Vec<usize>>],
        seen: &mut [bool],
        out: &mut Vec<usize>,
        depth: usize,
    ) {
        if seen[i] || depth > MAX_DEPTH {
            return;
        }
        seen[i] = true;
        match self.dir[i].kind {
            143 | 144 | 510 => out.push(i),
            186 | 402 | 514 => {
                for &m in members[i].iter().flatten() {
                    if m % 2 == 1 && m / 2 < self.dir.len() {
                        self.expand(m / 2, members, seen, out, depth + 1);
                    }
                }
            }
            _ => {}
        }
    }

    /// One face: its entity, surface and loops.
    fn face(&self, e: &DirEntry) -> Face {
        let mut surface = String::from("unknown");
        let loops = match e.kind {
            144 => self.trimmed_surface(e, &mut surface),
            510 => self.brep_face(e, &mut surface),
            _ => self.bounded_surface(e, &mut surface),
        };
        legacy_face(format!("DE {}", e.de), surface, loops)
    }

    /// The surface entry `ptr` of face `e`, its name written to `surface`.
    pub(super) fn surface_of(
        &self,
        e: &DirEntry,
        ptr: usize,
        surface: &mut String,
    ) -> Result<&DirEntry, String> {
        let s = self.entry(ptr, &format!("{}: surface", self.who(e)))?;
        *surface = format!("{} ({})", s.kind, type_name(s.kind));
        Ok(s)
    }

    fn trimmed_surface(
        &self,
        e: &DirEntry,
        surface: &mut String,
    ) -> Result<Vec<Vec<rs_spline::NurbsCurve>>, String> {
        let who = self.who(e);
        let mut p = self.params(e)?;
        let pts = p.pointer("PTS")?;
        let n1 = p.int("N1")?;
        let n2 = p.count("N2")?;
        let pto = p.pointer("PTO")?;
        let inner = p.pointers("N2", n2, "PTI")?;
        let s = self.surface_of(e, pts, surface)?;
        let mut loops = Vec::with_capacity(n2 + 1);
        match n1 {
            0 => loops.push(self.rectangle(s)?),
            1 => loops.push(self.curve_on_surface(e, pto, s)?),
            _ => return Err(format!("{who}: N1 = {n1} (expected 0 or 1)")),
        }
        for ptr in inner {
            loops.push(self.curve_on_surface(e, ptr, s)?);
        }
        Ok(loops)
    }

    /// The loop of the 142 at `ptr`, a boundary of face `face` on surface `s`.
    fn curve_on_surface(
        &self,
        face: &DirEntry,
        ptr: usize,
        s: &DirEntry,
    ) -> Result<Vec<rs_spline::NurbsCurve>, String> {
        let c = self.entry(ptr, &format!("{}: boundary", self.who(face)))?;
        let who = self.who(c);
        if c.kind != 142 {
            return Err(format!(
                "{}: boundary DE {} is a {} {}, not a 142 curve on a parametric surface",
                self.who(face),
                c.de,
                c.kind,
                type_name(c.kind)
            ));
        }
        let mut p = self.params(c)?;
        let _crtn = p.int("CRTN")?;
        let _sptr = p.pointer("SPTR")?;
        let bptr = p.pointer("BPTR")?;
        let cptr = p.pointer("CPTR")?;
        let mut pieces = Vec::new();
        if bptr != 0 {
            let from = format!("{who}: parameter-space curve");
            self.curve_pieces(bptr, &from, &Target::Param, &mut pieces)?;
        } else {
            let Some(plane) = self.plane_map(s)? else {
                return Err(format!(
                    "DE {}: curve on surface has no parameter-space curve (pointer 0) and its \
                     surface DE {} ({} {}) is not a plane",
                    c.de,
                    s.de,
                    s.kind,
                    type_name(s.kind)
                ));
            };
            let from = format!("{who}: model-space curve");
            self.curve_pieces(cptr, &from, &Target::Plane(plane), &mut pieces)?;
        }
        let named = if bptr != 0 { bptr } else { c.de };
        if bptr != 0 && cptr != 0 {
            pieces = self.bridge_poles(c.de, cptr, pieces);
        }
        self.check_gaps(named, &pieces)?;
        Ok(pieces.into_iter().map(|p| p.curve).collect())
    }

    /// The 3-D start and end of each piece of the model-space curve `de`.
    fn model_ends(&self, de: usize, from: &str) -> Result<Vec<Ends>, String> {
        let (mut xy, mut z) = (Vec::new(), Vec::new());
        self.curve_pieces(de, from, &Target::Model { z: false }, &mut xy)?;
        self.curve_pieces(de, from, &Target::Model { z: true }, &mut z)?;
        Ok(xy
            .iter()
            .zip(&z)
            .map(|(a, b)| {
                let (s, e) = (a.curve.start_point(), a.curve.end_point());
                let (sz, ez) = (b.curve.start_point().x, b.curve.end_point().x);
                ([s.x, s.y, sz], [e.x, e.y, ez])
            })
            .collect())
    }

    /// Closes the gaps of a loop in `(u, v)` at the poles of its surface: where the parameter
    /// pieces `i` and `i + 1` (or the last and the first) are apart but the model-space curve's
    /// pieces `i` and `i + 1` meet, the gap is a degenerate edge (the whole segment maps to one
    /// point of the surface, as at the apex of a surface of revolution) that the writer left
    /// out; it is closed by the segment between the two pieces, the edge Open CASCADE adds
    /// there. Needs as many model pieces as parameter pieces; otherwise `pieces` is returned
    /// as it is (and its gaps are reported).
    fn bridge_poles(&self, c: usize, cptr: usize, pieces: Vec<Piece>) -> Vec<Piece> {
        let tol = self.gap_tolerance(&pieces);
        let n = pieces.len();
        let gap = |i: usize| {
            pieces[i]
                .curve
                .end_point()
                .distance(pieces[(i + 1) % n].curve.start_point())
        };
        if n == 0 || (0..n).all(|i| gap(i) <= tol) {
            return pieces;
        }
        let Ok(ends) = self.model_ends(cptr, &format!("DE {c}: model-space curve")) else {
            return pieces;
        };
        if ends.len() != n {
            return pieces;
        }
        let size = ends
            .iter()
            .flat_map(|(a, b)| a.iter().chain(b))
            .fold(0.0f64, |m, x| m.max(x.abs()));
        let mtol = self.globals.resolution.unwrap_or(0.0).max(1e-8 * size);
        let mut out = Vec::with_capacity(n + 2);
        for i in 0..n {
            let g = gap(i);
            let (a, b) = (
                pieces[i].curve.end_point(),
                pieces[(i + 1) % n].curve.start_point(),
            );
            let meet = dist3(ends[i].1, ends[(i + 1) % n].0) <= mtol;
            out.push(pieces[i].clone());
            if g > tol
                && meet
                && let Ok(curve) = segment(a, b)
            {
                out.push(Piece { de: c, curve });
            }
        }
        out
    }

    /// The largest gap accepted between consecutive pieces of a loop in `(u, v)`: the file's
    /// resolution, but at least `1e-8` of the loop's largest coordinate (parameters need not
    /// be lengths, and files print about ten significant digits).
    fn gap_tolerance(&self, pieces: &[Piece]) -> f64 {
        let size = pieces
            .iter()
            .flat_map(|p| p.curve.control_points())
            .fold(0.0f64, |m, q| m.max(q.x.abs()).max(q.y.abs()));
        self.globals.resolution.unwrap_or(0.0).max(1e-8 * size)
    }

    /// Checks that each piece ends where the next starts; `named` is the loop's entity.
    pub(super) fn check_gaps(&self, named: usize, pieces: &[Piece]) -> Result<(), String> {
        let tol = self.gap_tolerance(pieces);
        for w in pieces.windows(2) {
            let gap = w[0].curve.end_point().distance(w[1].curve.start_point());
            if gap > tol || gap.is_nan() {
                return Err(format!(
                    "DE {named}: pieces DE {} and DE {} are {gap:e} apart (tolerance {tol:e})",
                    w[0].de, w[1].de
                ));
            }
        }
        Ok(())
    }

    /// The parameter rectangle of surface `s` as a loop (for a 144 with `N1 = 0`).
    pub(super) fn rectangle(&self, s: &DirEntry) -> Result<Vec<rs_spline::NurbsCurve>, String> {
        let who = self.who(s);
        if s.kind != 128 {
            return Err(format!(
                "{who}: the outer boundary is the surface's parameter range (N1 = 0), which \
                 this reader knows only for 128 rational B-spline surfaces"
            ));
        }
        let mut p = self.params(s)?;
        let (k1, k2) = (p.count("K1")?, p.count("K2")?);
        let (m1, m2) = (p.count("M1")?, p.count("M2")?);
        for name in ["PROP1", "PROP2", "PROP3", "PROP4", "PROP5"] {
            p.skip(name)?;
        }
        // Knots, then 4 numbers (weight, x, y, z) per control point.
        let fields = (k1.checked_add(m1))
            .and_then(|a| a.checked_add(k2)?.checked_add(m2)?.checked_add(4))
            .and_then(|a| {
                let grid = k1.checked_add(1)?.checked_mul(k2.checked_add(1)?)?;
                a.checked_add(grid.checked_mul(4)?)
            })
            .unwrap_or(usize::MAX);
        p.check_count("K1, K2", fields, 1)?;
        for _ in 0..fields {
            p.skip("knots, weights, control points")?;
        }
        let (u0, u1, v0, v1) = (p.real("U0")?, p.real("U1")?, p.real("V0")?, p.real("V1")?);
        if !(u0 < u1 && v0 < v1) {
            return Err(format!(
                "{who}: empty parameter range [{u0}, {u1}] x [{v0}, {v1}]"
            ));
        }
        let c = [(u0, v0), (u1, v0), (u1, v1), (u0, v1)].map(|(u, v)| rs_spline::Point::new(u, v));
        (0..4)
            .map(|i| segment(c[i], c[(i + 1) % 4]).map_err(|m| format!("{who}: {m}")))
            .collect()
    }

    /// The affine map from model space into the parameters of surface `s`, if `s` is a plane
    /// this reader parametrises (see the module documentation); `Ok(None)` if it is not.
    pub(super) fn plane_map(&self, s: &DirEntry) -> Result<Option<PlaneMap>, String> {
        let who = self.who(s);
        let tol = self.globals.resolution.unwrap_or(0.0);
        let (origin, e1, e2, uv0) = match s.kind {
            108 => {
                let mut p = self.params(s)?;
                let n = [p.real("A")?, p.real("B")?, p.real("C")?];
                let d = p.real("D")?;
                let nn = dot(n, n);
                if !(nn > 0.0 && nn.is_finite()) {
                    return Err(format!("{who}: the normal (A, B, C) is zero"));
                }
                let unit = n.map(|x| x / nn.sqrt());
                let origin = n.map(|x| x * d / nn);
                // The world axis least aligned with the normal, projected onto the plane.
                let axis = (0..3)
                    .min_by(|&i, &j| unit[i].abs().total_cmp(&unit[j].abs()))
                    .unwrap_or(0);
                let mut w = [0.0; 3];
                w[axis] = 1.0;
                let proj = sub(w, unit.map(|x| x * unit[axis]));
                let len = dot(proj, proj).sqrt();
                let e1 = proj.map(|x| x / len);
                (origin, e1, cross(unit, e1), (0.0, 0.0))
            }
            128 => match self.flat_bilinear(s)? {
                Some(parts) => parts,
                None => return Ok(None),
            },
            _ => return Ok(None),
        };
        // The surface's own transformation places it in model space.
        let t = self.transform(s, true)?;
        let map = PlaneMap::new(
            t.apply(origin),
            t.apply_vector(e1),
            t.apply_vector(e2),
            uv0,
            tol,
        );
        map.map(Some)
            .ok_or_else(|| format!("{who}: the plane's axes are degenerate"))
    }

    /// A 128 of degree 1 x 1, four control points forming a parallelogram, equal weights:
    /// `S(u, v) = P00 + (u - s0) e1 + (v - t0) e2`. Returns `(P00, e1, e2, (s0, t0))`, or
    /// `None` for any other 128.
    #[allow(clippy::type_complexity)]
    fn flat_bilinear(
        &self,
        s: &DirEntry,
    ) -> Result<Option<([f64; 3], [f64; 3], [f64; 3], (f64, f64))>, String> {
        let who = self.who(s);
        let mut p = self.params(s)?;
        let head = [
            p.count("K1")?,
            p.count("K2")?,
            p.count("M1")?,
            p.count("M2")?,
        ];
        if head != [1, 1, 1, 1] {
            return Ok(None);
        }
        for name in ["PROP1", "PROP2", "PROP3", "PROP4", "PROP5"] {
            p.skip(name)?;
        }
        let mut knots = [0.0; 8];
        for k in &mut knots {
            *k = p.real("knot")?;
        }
        let mut w = [0.0; 4];
        for x in &mut w {
            *x = p.real("weight")?;
        }
        if w.iter().any(|&x| x != w[0]) || w[0] <= 0.0 {
            return Ok(None);
        }
        let mut pts = [[0.0; 3]; 4];
        for q in &mut pts {
            *q = [p.real("X")?, p.real("Y")?, p.real("Z")?];
        }
        let [p00, p10, p01, p11] = pts;
        let (s0, s1, t0, t1) = (knots[1], knots[2], knots[5], knots[6]);
        if !(s0 < s1 && t0 < t1) {
            return Err(format!("{who}: empty knot domain"));
        }
        let skew = sub(sub(p11, p10), sub(p01, p00));
        let size = pts.iter().flatten().fold(1.0f64, |m, x| m.max(x.abs()));
        let tol = self.globals.resolution.unwrap_or(0.0).max(1e-12 * size);
        if dot(skew, skew).sqrt() > tol {
            return Ok(None);
        }
        let e1 = sub(p10, p00).map(|x| x / (s1 - s0));
        let e2 = sub(p01, p00).map(|x| x / (t1 - t0));
        Ok(Some((p00, e1, e2, (s0, t0))))
    }

    /// 143 bounded surface with 141 boundaries.
    fn bounded_surface(
        &self,
        e: &DirEntry,
        surface: &mut String,
    ) -> Result<Vec<Vec<rs_spline::NurbsCurve>>, String> {
        let who = self.who(e);
        let mut p = self.params(e)?;
        let _kind = p.int("TYPE")?;
        let sptr = p.pointer("SPTR")?;
        let n = p.count("N")?;
        let bounds = p.pointers("N", n, "BDPT")?;
        let s = self.surface_of(e, sptr, surface)?;
        if n == 0 {
            return Err(format!("{who}: no boundaries"));
        }
        bounds.into_iter().map(|b| self.boundary(e, b, s)).collect()
    }

    /// The loop of a 141 boundary of face `face` on surface `s`.
    fn boundary(
        &self,
        face: &DirEntry,
        ptr: usize,
        s: &DirEntry,
    ) -> Result<Vec<rs_spline::NurbsCurve>, String> {
        let b = self.entry(ptr, &format!("{}: boundary", self.who(face)))?;
        if b.kind != 141 {
            return Err(format!(
                "{}: boundary DE {} is a {} {}, not a 141 boundary",
                self.who(face),
                b.de,
                b.kind,
                type_name(b.kind)
            ));
        }
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
        let mut plane = None;
        for (i, (model, sense, params)) in curves.into_iter().enumerate() {
            let mut these = Vec::new();
            if params.is_empty() {
                let map = match &plane {
                    Some(m) => PlaneMap::clone(m),
                    None => {
                        let m = self.plane_map(s)?.ok_or_else(|| {
                            format!(
                                "{who}: model curve {} has no parameter-space curve and the \
                                 surface DE {} ({} {}) is not a plane",
                                i + 1,
                                s.de,
                                s.kind,
                                type_name(s.kind)
                            )
                        })?;
                        plane = Some(m.clone());
                        m
                    }
                };
                let target = Target::Plane(map);
                let from = format!("{who}: model curve {}", i + 1);
                self.curve_pieces(model, &from, &target, &mut these)?;
            } else {
                for ptr in params {
                    let from = format!("{who}: parameter-space curve of model curve {}", i + 1);
                    self.curve_pieces(ptr, &from, &Target::Param, &mut these)?;
                }
            }
            match sense {
                1 => {}
                2 => {
                    these.reverse();
                    for piece in &mut these {
                        piece.curve = piece.curve.reversed();
                    }
                }
                _ => {
                    return Err(format!(
                        "{who}: model curve {}: sense {sense} (expected 1 or 2)",
                        i + 1
                    ));
                }
            }
            pieces.extend(these);
        }
        self.check_gaps(b.de, &pieces)?;
        Ok(pieces.into_iter().map(|p| p.curve).collect())
    }
}
