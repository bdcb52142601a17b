//! The second stage of the two-stage methods: `C^1` macro-elements on a curved triangulation
//! (Schumaker and Yu 2021, Sections 8-9), each built on the companion triangles from Hermite
//! data, so that neighbours agree to first order across every edge.
//!
//! - [`C1Space::SuperSpline`], `S_5^{1,2}`: on each triangle the quintic whose derivatives up
//!   to order 2 at the vertices are given (the coefficients within distance 2 of a vertex are
//!   those of its Taylor quadratic) and whose derivative across each edge at the edge's
//!   midpoint is given (one coefficient per edge). `C^1` across edges, `C^2` at vertices.
//! - [`C1Space::CloughTocher`], `S_3^1` on the Clough–Tocher split: values and gradients at the
//!   vertices and the cross derivative at each edge's midpoint (12 data); the coefficients
//!   around the split point follow from the `C^1` conditions across the three inner edges.
//! - [`C1Space::PowellSabin`], `S_2^1` on the Powell–Sabin split: values and gradients at the
//!   vertices (9 data); the coefficients around the incentre lie on one plane and each edge
//!   split point's coefficient follows from the `C^1` condition across its inner edge.
//!
//! Every element reproduces the polynomials of its degree when the data are exact
//! ([`hermite_interpolate`] with exact derivatives). On a boundary triangle the element lives
//! on the companion triangle and its polynomials extend over the slivers between the arcs and
//! their chords (the refinement's sub-triangles carry the arcs), so the spline is defined on
//! all of the domain.
//!
//! `C^1` conditions are written with one rule: triangles `T = (u, w, a)` and `T' = (u, w, b)`
//! sharing the edge `u w` join with `C^1` when, for `i + j = d - 1`,
//! `c'_(i, j, 1) = beta_u c_(i+1, j, 0) + beta_w c_(i, j+1, 0) + beta_a c_(i, j, 1)`, with
//! `beta` the barycentric coordinates of `b` relative to `T` (Lai and Schumaker 2007,
//! Theorem 2.28).

use rs_mesh::{CurvedTriangulation, Refinement};
use rs_spline::Point;

use crate::bb::{Jet, Order, Triangle, coefficient_count, evaluate, index, multi_indices};
use crate::{SpaceKind, Spline, TriSplineError};

/// A space of `C^1` splines on a curved triangulation for scattered-data interpolation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum C1Space {
    /// `S_5^{1,2}`: quintic, `C^1`, `C^2` at the vertices (`"s512"`).
    SuperSpline,
    /// `S_3^1` on the Clough–Tocher refinement (`"ct"`).
    CloughTocher,
    /// `S_2^1` on the Powell–Sabin refinement (`"ps"`).
    PowellSabin,
    /// `S_2^1` on the Powell–Sabin refinement with minimal energy (`"min-energy"`, Section 10).
    MinimalEnergy,
}

impl C1Space {
    /// The polynomial degree.
    pub fn degree(self) -> usize {
        match self {
            C1Space::SuperSpline => 5,
            C1Space::CloughTocher => 3,
            C1Space::PowellSabin | C1Space::MinimalEnergy => 2,
        }
    }

    /// The refinement its triangulation needs (`None`: the triangulation itself).
    pub fn refinement(self) -> Option<Refinement> {
        match self {
            C1Space::SuperSpline => None,
            C1Space::CloughTocher => Some(Refinement::CloughTocher),
            C1Space::PowellSabin | C1Space::MinimalEnergy => Some(Refinement::PowellSabin),
        }
    }

    /// The degree of the first stage's local fits: cubic for `S_5^{1,2}` (it needs second
    /// derivatives) and for Clough–Tocher, quadratic for Powell–Sabin and minimal energy.
    /// Clough–Tocher takes cubic fits, not the quadratic ones of Schumaker's Sect. 6.7.2:
    /// a quadratic fit's gradients are `O(h^2)`, which limits the cubic element to order 3
    /// (`cargo xtask splines` checks the rates: 3.3 with quadratic fits, 4.2 with cubic ones).
    pub fn fit_degree(self) -> usize {
        match self {
            C1Space::SuperSpline | C1Space::CloughTocher => 3,
            _ => 2,
        }
    }

    /// The kind written to the spline file.
    pub fn kind(self) -> SpaceKind {
        match self {
            C1Space::SuperSpline => SpaceKind::SuperSpline,
            C1Space::CloughTocher => SpaceKind::CloughTocher,
            C1Space::PowellSabin => SpaceKind::PowellSabin,
            C1Space::MinimalEnergy => SpaceKind::MinimalEnergy,
        }
    }

    /// The name in the spline file and on the command line.
    pub fn name(self) -> &'static str {
        self.kind().name()
    }

    /// The space with that name.
    pub fn from_name(name: &str) -> Option<Self> {
        [
            C1Space::SuperSpline,
            C1Space::CloughTocher,
            C1Space::PowellSabin,
            C1Space::MinimalEnergy,
        ]
        .into_iter()
        .find(|s| s.name() == name)
    }

    /// Sub-triangles per triangle of the unrefined triangulation.
    pub(crate) fn pieces(self) -> usize {
        self.refinement().map_or(1, Refinement::factor)
    }

    /// Checks that `mesh` is the triangulation the space lives on.
    pub(crate) fn check_mesh(self, mesh: &CurvedTriangulation) -> Result<(), TriSplineError> {
        if mesh.refinement() == self.refinement() {
            return Ok(());
        }
        Err(TriSplineError::WrongTriangulation {
            space: self.name(),
            needs: match self.refinement() {
                None => "an unrefined curved triangulation",
                Some(Refinement::CloughTocher) => "the Clough-Tocher refinement of a triangulation",
                Some(Refinement::PowellSabin) => "the Powell-Sabin refinement of a triangulation",
            },
        })
    }
}

impl std::str::FromStr for C1Space {
    type Err = String;

    /// The names of the spline file and of `inrs fit --space` ([`C1Space::name`]): `s512`,
    /// `ct`, `ps`, `min-energy` (any case).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::from_name(&s.to_ascii_lowercase())
            .ok_or_else(|| format!("unknown space {s:?} (expected s512, ct, ps or min-energy)"))
    }
}

/// What the second stage interpolates: at each vertex of the unrefined triangulation the
/// value and derivatives (up to order 2 for `S_5^{1,2}`, 1 otherwise), and on each edge the
/// gradient at the midpoint of its chord (only its component across the edge is used).
pub trait HermiteData: Sync {
    /// Value, gradient and Hessian at vertex `v` (the Hessian is read by `S_5^{1,2}` only).
    fn vertex(&self, v: usize) -> Jet;
    /// The gradient at the midpoint of the chord from vertex `a` to vertex `b` (`a < b`).
    fn edge_gradient(&self, a: usize, b: usize) -> [f64; 2];
}

/// Exact Hermite data from a function's jet.
pub struct ExactJets<'a> {
    vertices: &'a [Point],
    f: &'a (dyn Fn(Point) -> Jet + Sync),
}

impl<'a> ExactJets<'a> {
    /// The data of `f` at the vertices of `mesh`.
    pub fn new(mesh: &'a CurvedTriangulation, f: &'a (dyn Fn(Point) -> Jet + Sync)) -> Self {
        Self {
            vertices: mesh.vertices(),
            f,
        }
    }
}

impl HermiteData for ExactJets<'_> {
    fn vertex(&self, v: usize) -> Jet {
        (self.f)(self.vertices[v])
    }

    fn edge_gradient(&self, a: usize, b: usize) -> [f64; 2] {
        (self.f)((self.vertices[a] + self.vertices[b]) * 0.5).gradient
    }
}

/// The vertices (mesh indices) of each triangle of the unrefined triangulation underlying
/// `mesh`, which must be the triangulation `space` lives on (the sub-triangles of a
/// refinement start at the unrefined triangle's vertices: `v_k v_(k+1) c` for Clough–Tocher,
/// `v_k m_k c` and `m_k v_(k+1) c` for Powell–Sabin).
///
/// # Errors
/// [`TriSplineError::WrongTriangulation`].
pub fn macro_triangles(
    mesh: &CurvedTriangulation,
    space: C1Space,
) -> Result<Vec<[usize; 3]>, TriSplineError> {
    space.check_mesh(mesh)?;
    let per = space.pieces();
    let first = match space.refinement() {
        Some(Refinement::PowellSabin) => [0, 2, 4],
        _ => [0, 1, 2],
    };
    Ok(mesh
        .triangles()
        .chunks(per)
        .map(|subs| {
            if per == 1 {
                subs[0]
            } else {
                first.map(|s| subs[s][0])
            }
        })
        .collect())
}

/// The spline of `space` on `mesh` (its triangulation: see [`C1Space::refinement`])
/// interpolating the Hermite data `data`, triangle by triangle on all threads.
///
/// # Errors
/// [`TriSplineError::WrongTriangulation`]; [`TriSplineError::NotFinite`] if the data give a
/// coefficient that is not finite; for [`C1Space::MinimalEnergy`] use
/// [`crate::minimal_energy`] ([`TriSplineError::WrongTriangulation`] here).
pub fn hermite_interpolate(
    mesh: CurvedTriangulation,
    space: C1Space,
    data: &dyn HermiteData,
) -> Result<Spline, TriSplineError> {
    use rayon::prelude::*;
    if space == C1Space::MinimalEnergy {
        return Err(TriSplineError::WrongTriangulation {
            space: space.name(),
            needs: "a global solve (minimal_energy), not Hermite data",
        });
    }
    let macros = macro_triangles(&mesh, space)?;
    let per = space.pieces();
    let vertices = mesh.vertices();
    let chunks: Vec<Vec<f64>> = macros
        .par_iter()
        .enumerate()
        .map(|(t, ids)| {
            let jets = ids.map(|v| data.vertex(v));
            let subs = sub_triangles(&mesh, per, t);
            match space {
                C1Space::SuperSpline => super_spline_element(&subs[0], *ids, jets, data).to_vec(),
                C1Space::CloughTocher => {
                    clough_tocher_element(&[subs[0], subs[1], subs[2]], *ids, jets, data).to_vec()
                }
                _ => powell_sabin_element(&subs, jets).to_vec(),
            }
        })
        .collect();
    let coefficients = chunks.concat();
    if let Some(i) = coefficients.iter().position(|c| !c.is_finite()) {
        let t = i / coefficient_count(space.degree()) / per;
        let p = vertices[macros[t][0]];
        return Err(TriSplineError::NotFinite {
            x: p.x,
            y: p.y,
            value: coefficients[i],
        });
    }
    Spline::new(mesh, space.degree(), space.kind(), coefficients)
}

/// The straight (companion) triangles of macro triangle `t` of `mesh`, a refinement with `per`
/// sub-triangles per macro triangle, stored consecutively (as [`macro_triangles`] reads them).
pub(crate) fn sub_triangles(mesh: &CurvedTriangulation, per: usize, t: usize) -> Vec<Triangle> {
    let vertices = mesh.vertices();
    mesh.triangles()[per * t..per * (t + 1)]
        .iter()
        .map(|tri| {
            let v = tri.map(|i| vertices[i]);
            Triangle::new(v[0], v[1], v[2])
        })
        .collect()
}

/// The coefficient `c_alpha` (degree `d`) of the Taylor polynomial of degree 2 at vertex `at`
/// of `tri` with jet `jet`: its blossom at `alpha_m` copies of each vertex `v_m`,
/// `f + (1/d) sum_m alpha_m g.(v_m - v) + 1/(d(d-1)) sum_(pairs of arguments) (v_m - v)' H (v_n - v)`.
/// Within distance `r` of the vertex (`alpha_at >= d - r`) these are the coefficients of any
/// polynomial with that `r`-jet there.
fn taylor_coefficient(tri: &Triangle, d: usize, at: usize, jet: &Jet, alpha: [usize; 3]) -> f64 {
    let v = tri.v[at];
    let delta = tri.v.map(|p| p - v);
    let [hxx, hxy, hyy] = jet.hessian;
    let h = |a: Point, b: Point| hxx * a.x * b.x + hxy * (a.x * b.y + a.y * b.x) + hyy * a.y * b.y;
    let g = |a: Point| jet.gradient[0] * a.x + jet.gradient[1] * a.y;
    let (mut lin, mut quad) = (0.0, 0.0);
    for m in 0..3 {
        let am = alpha[m] as f64;
        lin += am * g(delta[m]);
        quad += 0.5 * am * (am - 1.0) * h(delta[m], delta[m]);
        for n in m + 1..3 {
            quad += am * alpha[n] as f64 * h(delta[m], delta[n]);
        }
    }
    let df = d as f64;
    let quad = if d >= 2 {
        quad / (df * (df - 1.0))
    } else {
        0.0
    };
    jet.value + lin / df + quad
}

/// Sets `c[unknown]` so that the derivative of the polynomial across edge `a b` (global
/// vertex ids `ids`, positions `pa`, `pb`) at the chord's midpoint, along the edge's unit
/// normal (the chord from the lower-numbered vertex turned left), matches the data's: the
/// derivative is affine in the one coefficient, so two evaluations give it.
#[allow(clippy::too_many_arguments)]
fn match_cross_derivative(
    tri: &Triangle,
    d: usize,
    c: &mut [f64],
    unknown: usize,
    (pa, pb): (Point, Point),
    (a, b): (usize, usize),
    data: &dyn HermiteData,
) {
    let (lo, hi, plo, phi) = if a < b {
        (a, b, pa, pb)
    } else {
        (b, a, pb, pa)
    };
    let chord = phi - plo;
    let n = chord.perp() * (1.0 / chord.length());
    let mid = (pa + pb) * 0.5;
    let g = data.edge_gradient(lo, hi);
    let target = g[0] * n.x + g[1] * n.y;
    let across = |c: &[f64]| {
        let jet = evaluate(tri, d, c, mid, Order::Gradient);
        jet.gradient[0] * n.x + jet.gradient[1] * n.y
    };
    c[unknown] = 0.0;
    let d0 = across(c);
    c[unknown] = 1.0;
    let d1 = across(c);
    c[unknown] = (target - d0) / (d1 - d0);
}

/// `S_5^{1,2}` on one triangle from the 2-jets at its vertices and the cross derivatives at
/// its edges' midpoints.
fn super_spline_element(
    tri: &Triangle,
    ids: [usize; 3],
    jets: [Jet; 3],
    data: &dyn HermiteData,
) -> [f64; 21] {
    let d = 5;
    let mut c = [0.0; 21];
    for (n, (i, j, k)) in multi_indices(d).enumerate() {
        let alpha = [i, j, k];
        if let Some(at) = (0..3).find(|&m| alpha[m] >= 3) {
            c[n] = taylor_coefficient(tri, d, at, &jets[at], alpha);
        }
    }
    // c_122 sits by the edge opposite v0 (v1 v2), c_212 by v2 v0, c_221 by v0 v1.
    for (unknown, (a, b)) in [
        (index(2, 2), (1, 2)),
        (index(1, 2), (2, 0)),
        (index(2, 1), (0, 1)),
    ] {
        match_cross_derivative(
            tri,
            d,
            &mut c,
            unknown,
            (tri.v[a], tri.v[b]),
            (ids[a], ids[b]),
            data,
        );
    }
    c
}

/// `S_3^1` on the Clough–Tocher split `T_k = v_k v_(k+1) c` (`c` the barycentre) from the
/// values and gradients at the vertices and the cross derivatives at the edges' midpoints.
fn clough_tocher_element(
    subs: &[Triangle; 3],
    ids: [usize; 3],
    jets: [Jet; 3],
    data: &dyn HermiteData,
) -> [f64; 30] {
    let d = 3;
    let mut c = [[0.0; 10]; 3];
    for k in 0..3 {
        let t = &subs[k];
        let vj = [jets[k], jets[(k + 1) % 3]];
        for (n, (i, j, l)) in multi_indices(d).enumerate() {
            if i >= 2 {
                c[k][n] = taylor_coefficient(t, d, 0, &vj[0], [i, j, l]);
            } else if j >= 2 {
                c[k][n] = taylor_coefficient(t, d, 1, &vj[1], [i, j, l]);
            }
        }
        match_cross_derivative(
            t,
            d,
            &mut c[k],
            index(1, 1),
            (t.v[0], t.v[1]),
            (ids[k], ids[(k + 1) % 3]),
            data,
        );
    }
    // Across the inner edge v_(k+1) c (T_k's vertices 1, 2; T_(k+1)'s 0, 2), with beta the
    // coordinates of v_(k+2) in T_k: the row next to the edge's middle gives c^k_012, the
    // row next to c gives c_003.
    let (c111, c021, c012, c102, c003) = (index(1, 1), index(2, 1), index(1, 2), index(0, 2), 9);
    let mut ring = [0.0; 3];
    for k in 0..3 {
        let next = (k + 1) % 3;
        let beta = subs[k].barycentric(subs[next].v[1]);
        ring[k] = (c[next][c111] - beta[0] * c[k][c111] - beta[1] * c[k][c021]) / beta[2];
    }
    for k in 0..3 {
        c[k][c012] = ring[k];
        c[(k + 1) % 3][c102] = ring[k];
    }
    let beta = subs[0].barycentric(subs[1].v[1]);
    let centre = (c[1][c012] - beta[0] * c[0][c102] - beta[1] * c[0][c012]) / beta[2];
    let mut out = [0.0; 30];
    for k in 0..3 {
        c[k][c003] = centre;
        out[10 * k..10 * k + 10].copy_from_slice(&c[k]);
    }
    out
}

/// `S_2^1` on the Powell–Sabin split `A_k = v_k m_k c`, `B_k = m_k v_(k+1) c` (stored
/// `A_0 B_0 A_1 B_1 A_2 B_2`) from the values and gradients at the vertices.
pub(crate) fn powell_sabin_element(subs: &[Triangle], jets: [Jet; 3]) -> [f64; 36] {
    let d = 2;
    // Quadratic coefficient positions: c_200 c_110 c_101 c_020 c_011 c_002.
    let mut c = [[0.0; 6]; 6];
    for k in 0..3 {
        let (a, b) = (2 * k, 2 * k + 1);
        let (jk, jn) = (&jets[k], &jets[(k + 1) % 3]);
        c[a][0] = jk.value;
        c[a][1] = taylor_coefficient(&subs[a], d, 0, jk, [1, 1, 0]);
        c[a][2] = taylor_coefficient(&subs[a], d, 0, jk, [1, 0, 1]);
        c[b][3] = jn.value;
        c[b][1] = taylor_coefficient(&subs[b], d, 1, jn, [1, 1, 0]);
        c[b][4] = taylor_coefficient(&subs[b], d, 1, jn, [0, 1, 1]);
    }
    // The coefficients around c are values of one affine function L(p) = l0 + g.(p - c) at
    // their domain points; the midpoints of c v_k fix it.
    let centre = subs[0].v[2];
    let q: Vec<(Point, f64)> = (0..3)
        .map(|k| ((subs[2 * k].v[0] - centre) * 0.5, c[2 * k][2]))
        .collect();
    let det = |a: Point, b: Point| a.x * b.y - a.y * b.x;
    // l0 + g.r_k = y_k for k = 0, 1, 2: subtract the first row, solve for g, then l0.
    let (r1, r2) = (q[1].0 - q[0].0, q[2].0 - q[0].0);
    let (y1, y2) = (q[1].1 - q[0].1, q[2].1 - q[0].1);
    let den = det(r1, r2);
    let g = Point::new((y1 * r2.y - y2 * r1.y) / den, (r1.x * y2 - r2.x * y1) / den);
    let l0 = q[0].1 - g.dot(q[0].0);
    for k in 0..3 {
        let (a, b) = (2 * k, 2 * k + 1);
        let m = subs[a].v[1];
        let mid = g.dot((m - centre) * 0.5) + l0;
        c[a][5] = l0;
        c[b][5] = l0;
        c[a][4] = mid;
        c[b][2] = mid;
        // Across m_k c (A_k's vertices 1, 2; B_k's 0, 2), beta the coordinates of v_(k+1) in
        // A_k: the row next to m_k gives c_m.
        let beta = subs[a].barycentric(subs[b].v[1]);
        let cm = (c[b][1] - beta[0] * c[a][1] - beta[2] * c[a][4]) / beta[1];
        c[a][3] = cm;
        c[b][0] = cm;
    }
    let mut out = [0.0; 36];
    for (s, cs) in c.iter().enumerate() {
        out[6 * s..6 * s + 6].copy_from_slice(cs);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::C1Space;

    #[test]
    fn spaces_parse_from_their_names() {
        for space in [
            C1Space::SuperSpline,
            C1Space::CloughTocher,
            C1Space::PowellSabin,
            C1Space::MinimalEnergy,
        ] {
            assert_eq!(space.name().parse::<C1Space>(), Ok(space));
        }
        assert_eq!("CT".parse::<C1Space>(), Ok(C1Space::CloughTocher));
        assert_eq!(
            "s0".parse::<C1Space>().unwrap_err(),
            "unknown space \"s0\" (expected s512, ct, ps or min-energy)"
        );
    }
}
