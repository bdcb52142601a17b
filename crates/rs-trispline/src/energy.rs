//! Minimal-energy interpolation (Schumaker and Yu 2021, Section 10): among the splines of
//! `S_2^1` on the Powell–Sabin refinement taking given values at the vertices, the one of
//! least energy `E(s) = sum_T integral_T (s_xx^2 + 2 s_xy^2 + s_yy^2)`, integrated over the
//! companion (inscribed) triangles as the paper allows.
//!
//! A spline of this space is fixed by its values and gradients at the vertices
//! ([`crate::C1Space::PowellSabin`]'s element), so with the values given, `E` is a quadratic
//! form in the gradients: `E = g' K g + 2 g' b + const`, minimised where `K g = -b`. `K` is
//! sparse (two vertices interact only through a shared triangle), symmetric and positive
//! definite (a spline with zero values and non-zero gradients is not linear, so its energy is
//! positive). It is assembled from 9 x 9 element matrices and solved by conjugate gradients
//! with a Jacobi preconditioner, to a relative residual of [`ENERGY_TOLERANCE`] within
//! [`max_energy_iterations`] steps.

use std::collections::HashMap;

use rs_mesh::CurvedTriangulation;
use rs_spline::quadrature::gauss_rule;

use crate::bb::{Jet, Order, Triangle, coefficient_count, evaluate};
use crate::hermite::{C1Space, macro_triangles, powell_sabin_element, sub_triangles};
use crate::{Spline, TriSplineError};

/// The relative residual `|K g + b| / |b|` the conjugate gradients stop at.
pub const ENERGY_TOLERANCE: f64 = 1e-12;

/// The most conjugate-gradient steps for `n` unknowns: `n + 1000` (in exact arithmetic `n`
/// suffice; rounding needs some more).
pub fn max_energy_iterations(n: usize) -> usize {
    n + 1000
}

/// The energy `sum_T integral_T (s_xx^2 + 2 s_xy^2 + s_yy^2)` of a spline over its companion
/// triangles, by a collapsed Gauss–Legendre rule with `d` points per direction (exact for the
/// integrand's degree `2 d - 4`).
pub fn energy(s: &Spline) -> f64 {
    let d = s.degree();
    if d < 2 {
        return 0.0;
    }
    // d <= MAX_DEGREE = 12, far below the cache's bound: the rule is always there.
    let Some(gauss) = gauss_rule(d) else {
        return f64::NAN;
    };
    let (nodes, weights) = (gauss.nodes(), gauss.weights());
    let rule: Vec<(f64, f64, f64)> = nodes
        .iter()
        .zip(weights)
        .flat_map(|(&x, &wx)| {
            let (a, wa) = (0.5 * (x + 1.0), 0.5 * wx);
            nodes.iter().zip(weights).map(move |(&y, &wy)| {
                let (b, wb) = (0.5 * (y + 1.0), 0.5 * wy);
                // b1 = a, b2 = (1 - a) b, Jacobian (1 - a) times twice the area.
                (a, (1.0 - a) * b, wa * wb * (1.0 - a))
            })
        })
        .collect();
    (0..s.mesh().triangles().len())
        .map(|t| {
            let tri = s.companion(t);
            let area2 = tri.double_area().abs();
            rule.iter()
                .map(|&(b1, b2, w)| {
                    let p = tri.point([b1, b2, 1.0 - b1 - b2]);
                    let h = s.evaluate_on(t, p, Order::Hessian).hessian;
                    w * (h[0] * h[0] + 2.0 * h[1] * h[1] + h[2] * h[2])
                })
                .sum::<f64>()
                * area2
        })
        .sum()
}

/// The minimal-energy spline of `S_2^1` on the Powell–Sabin refinement `mesh` taking the value
/// `values[v]` at each vertex `v` of the unrefined triangulation (entries of other vertices
/// are ignored). `start` gives starting gradients per vertex (e.g. the two-stage estimates;
/// zeros otherwise).
///
/// # Errors
/// [`TriSplineError::WrongTriangulation`] unless `mesh` is a Powell–Sabin refinement;
/// [`TriSplineError::Data`] if `values` or `start` is shorter than the vertex list or a value is
/// not finite; [`TriSplineError::NotConverged`].
pub fn minimal_energy(
    mesh: CurvedTriangulation,
    values: &[f64],
    start: Option<&[[f64; 2]]>,
) -> Result<Spline, TriSplineError> {
    let space = C1Space::MinimalEnergy;
    let macros = macro_triangles(&mesh, space)?;
    let per = space.pieces();
    let nv = mesh.vertices().len();
    if values.len() < nv || start.is_some_and(|s| s.len() < nv) {
        return Err(TriSplineError::Data(format!(
            "{} values for {nv} vertices",
            values.len()
        )));
    }
    // Unknowns: the gradient at each vertex of the unrefined triangulation.
    let mut slot: HashMap<usize, usize> = HashMap::new();
    let mut order = Vec::new();
    for &v in macros.iter().flatten() {
        slot.entry(v).or_insert_with(|| {
            order.push(v);
            order.len() - 1
        });
    }
    if let Some(&v) = order.iter().find(|&&v| !values[v].is_finite()) {
        let p = mesh.vertices()[v];
        return Err(TriSplineError::NotFinite {
            x: p.x,
            y: p.y,
            value: values[v],
        });
    }
    let n = 2 * order.len();
    let mut entries: Vec<(usize, usize, f64)> = Vec::with_capacity(macros.len() * 36);
    let mut rhs = vec![0.0; n];
    for (t, ids) in macros.iter().enumerate() {
        let k = element_energy(&sub_triangles(&mesh, per, t));
        // Local data order: (z, gx, gy) per vertex; gradients are unknowns, values given.
        let global = |l: usize| -> Option<usize> {
            let v = ids[l / 3];
            (!l.is_multiple_of(3)).then(|| 2 * slot[&v] + l % 3 - 1)
        };
        for (r, row) in k.iter().enumerate() {
            let Some(gr) = global(r) else { continue };
            for (c, &kc) in row.iter().enumerate() {
                match global(c) {
                    Some(gc) => entries.push((gr, gc, kc)),
                    None => rhs[gr] -= kc * values[ids[c / 3]],
                }
            }
        }
    }
    let matrix = Csr::from_entries(n, entries);
    let mut x = vec![0.0; n];
    if let Some(start) = start {
        for (i, &v) in order.iter().enumerate() {
            x[2 * i] = start[v][0];
            x[2 * i + 1] = start[v][1];
        }
    }
    matrix.conjugate_gradients(&rhs, &mut x)?;
    let jet = |v: usize| {
        let i = slot[&v];
        Jet {
            value: values[v],
            gradient: [x[2 * i], x[2 * i + 1]],
            hessian: [0.0; 3],
        }
    };
    let coefficients: Vec<f64> = macros
        .iter()
        .enumerate()
        .flat_map(|(t, ids)| powell_sabin_element(&sub_triangles(&mesh, per, t), ids.map(jet)))
        .collect();
    Spline::new(mesh, space.degree(), space.kind(), coefficients)
}

/// The 9 x 9 matrix of the energy of one Powell–Sabin element in its data
/// `(z, g_x, g_y)` per vertex: `sum_sub area (R M)' W (R M)`, with `M` the element's linear map
/// from data to the sub-triangle's 6 coefficients, `R` the (constant) Hessian of a quadratic
/// in its coefficients and `W = diag(1, 2, 1)`.
fn element_energy(subs: &[Triangle]) -> [[f64; 9]; 9] {
    let mut map = [[0.0; 9]; 36];
    for l in 0..9 {
        let mut jets = [Jet::default(); 3];
        match l % 3 {
            0 => jets[l / 3].value = 1.0,
            i => jets[l / 3].gradient[i - 1] = 1.0,
        }
        for (r, c) in powell_sabin_element(subs, jets).iter().enumerate() {
            map[r][l] = *c;
        }
    }
    let n = coefficient_count(2);
    let mut k = [[0.0; 9]; 9];
    for (s, tri) in subs.iter().enumerate() {
        // Hessian of the sub-triangle's quadratic per unit datum.
        let mut h = [[0.0; 9]; 3];
        for i in 0..n {
            let mut unit = [0.0; 6];
            unit[i] = 1.0;
            let hi = evaluate(tri, 2, &unit, tri.v[0], Order::Hessian).hessian;
            for l in 0..9 {
                for (row, &hv) in h.iter_mut().zip(&hi) {
                    row[l] += hv * map[6 * s + i][l];
                }
            }
        }
        let area = 0.5 * tri.double_area().abs();
        for r in 0..9 {
            for c in 0..9 {
                k[r][c] += area * (h[0][r] * h[0][c] + 2.0 * h[1][r] * h[1][c] + h[2][r] * h[2][c]);
            }
        }
    }
    k
}

/// A square sparse matrix in compressed sparse rows.
struct Csr {
    offsets: Vec<usize>,
    columns: Vec<usize>,
    values: Vec<f64>,
}

impl Csr {
    /// The `n x n` matrix with the sum of the `entries` `(row, column, value)` at each place.
    fn from_entries(n: usize, mut entries: Vec<(usize, usize, f64)>) -> Self {
        entries.sort_unstable_by_key(|&(r, c, _)| (r, c));
        let mut offsets = vec![0; n + 1];
        let mut columns = Vec::with_capacity(entries.len() / 4);
        let mut values: Vec<f64> = Vec::with_capacity(entries.len() / 4);
        let mut last = None;
        for (r, c, v) in entries {
            if last == Some((r, c)) {
                if let Some(x) = values.last_mut() {
                    *x += v;
                }
                continue;
            }
            last = Some((r, c));
            offsets[r + 1] += 1;
            columns.push(c);
            values.push(v);
        }
        for r in 0..n {
            offsets[r + 1] += offsets[r];
        }
        Self {
            offsets,
            columns,
            values,
        }
    }

    fn multiply(&self, x: &[f64], y: &mut [f64]) {
        for (r, yr) in y.iter_mut().enumerate() {
            let range = self.offsets[r]..self.offsets[r + 1];
            *yr = self.columns[range.clone()]
                .iter()
                .zip(&self.values[range])
                .map(|(&c, &v)| v * x[c])
                .sum();
        }
    }

    fn diagonal(&self) -> Vec<f64> {
        (0..self.offsets.len() - 1)
            .map(|r| {
                let range = self.offsets[r]..self.offsets[r + 1];
                self.columns[range.clone()]
                    .iter()
                    .zip(&self.values[range])
                    .find(|(c, _)| **c == r)
                    .map_or(0.0, |(_, v)| *v)
            })
            .collect()
    }

    /// Solves `A x = b` (A symmetric positive definite) by preconditioned conjugate gradients
    /// from the given `x`.
    fn conjugate_gradients(&self, b: &[f64], x: &mut [f64]) -> Result<(), TriSplineError> {
        let n = b.len();
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let norm_b = dot(b, b).sqrt();
        if norm_b == 0.0 {
            x.fill(0.0);
            return Ok(());
        }
        let inv_diag: Vec<f64> = self
            .diagonal()
            .iter()
            .map(|&d| if d > 0.0 { 1.0 / d } else { 1.0 })
            .collect();
        let mut ax = vec![0.0; n];
        self.multiply(x, &mut ax);
        let mut r: Vec<f64> = b.iter().zip(&ax).map(|(b, a)| b - a).collect();
        let mut z: Vec<f64> = r.iter().zip(&inv_diag).map(|(r, d)| r * d).collect();
        let mut p = z.clone();
        let mut rz = dot(&r, &z);
        let mut ap = vec![0.0; n];
        let limit = max_energy_iterations(n);
        let mut residual = dot(&r, &r).sqrt() / norm_b;
        for iteration in 0..limit {
            if residual <= ENERGY_TOLERANCE {
                return Ok(());
            }
            self.multiply(&p, &mut ap);
            let pap = dot(&p, &ap);
            if pap.is_nan() || pap <= 0.0 {
                return Err(TriSplineError::NotConverged {
                    residual,
                    iterations: iteration,
                });
            }
            let alpha = rz / pap;
            for i in 0..n {
                x[i] += alpha * p[i];
                r[i] -= alpha * ap[i];
            }
            for i in 0..n {
                z[i] = r[i] * inv_diag[i];
            }
            let rz_next = dot(&r, &z);
            let beta = rz_next / rz;
            rz = rz_next;
            for i in 0..n {
                p[i] = z[i] + beta * p[i];
            }
            residual = dot(&r, &r).sqrt() / norm_b;
        }
        if residual <= ENERGY_TOLERANCE {
            return Ok(());
        }
        Err(TriSplineError::NotConverged {
            residual,
            iterations: limit,
        })
    }
}
