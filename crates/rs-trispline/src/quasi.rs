//! The quasi-interpolation operator `Q` of Algorithm 6.1 (Schumaker and Yu 2021): a local,
//! linear projection of continuous functions onto `S_d^0` of a curved triangulation that
//! reproduces every polynomial of degree `d`.

use rs_mesh::{CurvedTriangulation, EdgeKind};
use rs_spline::prelude::*;
use rs_spline::{Affine, Point};

use crate::bb::{DomainPointInterpolation, MAX_DEGREE, Order, Triangle, evaluate, multi_indices};
use crate::{SpaceKind, Spline, SplineError};

/// `Q f` of degree `d` on `mesh` (Algorithm 6.1), triangle by triangle on all threads:
///
/// 1. an ordinary triangle `T^` inside the curved triangle: its companion triangle when every
///    boundary arc bulges outwards, otherwise the largest triangle homothetic to it that no arc
///    enters ([`inner_triangle`]);
/// 2. the polynomial `p` interpolating `f` at the domain points of `T^`;
/// 3. the values of `p` at the companion triangle's domain points, those on interior edges
///    (vertices included) replaced by `f` there;
/// 4. the polynomial interpolating these values.
///
/// Neighbours interpolate the same values along their shared edge, so the result is
/// continuous; for `f` a polynomial of degree `<= d` every step is exact, so `Q f = f`.
///
/// # Errors
/// [`SplineError::Degree`] outside `1..=`[`MAX_DEGREE`]; [`SplineError::NotFinite`] if `f` is not
/// finite at a point it is sampled at; [`SplineError::ThinTriangle`].
pub fn quasi_interpolate(
    mesh: CurvedTriangulation,
    d: usize,
    f: &(dyn Fn(Point) -> f64 + Sync),
) -> Result<Spline, SplineError> {
    if !(1..=MAX_DEGREE).contains(&d) {
        return Err(SplineError::Degree(d));
    }
    use rayon::prelude::*;
    let interp = DomainPointInterpolation::new(d);
    let per_triangle: Vec<Vec<f64>> = (0..mesh.triangles().len())
        .into_par_iter()
        .map(|t| triangle_coefficients(&mesh, t, d, &interp, f))
        .collect::<Result<_, _>>()?;
    let coefficients = per_triangle.concat();
    Spline::new(mesh, d, SpaceKind::Continuous, coefficients)
}

/// Steps 1-4 for triangle `t`.
fn triangle_coefficients(
    mesh: &CurvedTriangulation,
    t: usize,
    d: usize,
    interp: &DomainPointInterpolation,
    f: &(dyn Fn(Point) -> f64 + Sync),
) -> Result<Vec<f64>, SplineError> {
    let v = mesh.triangles()[t].map(|i| mesh.vertices()[i]);
    let companion = Triangle::new(v[0], v[1], v[2]);
    let sample = |p: Point| {
        let value = f(p);
        if value.is_finite() {
            Ok(value)
        } else {
            Err(SplineError::NotFinite {
                x: p.x,
                y: p.y,
                value,
            })
        }
    };
    let inner = inner_triangle(mesh, t)?;
    let mut values: Vec<f64> = if inner == companion {
        companion
            .domain_points(d)
            .into_iter()
            .map(sample)
            .collect::<Result<_, _>>()?
    } else {
        let at_inner: Vec<f64> = inner
            .domain_points(d)
            .into_iter()
            .map(sample)
            .collect::<Result<_, _>>()?;
        let p = interp.coefficients(&at_inner);
        companion
            .domain_points(d)
            .into_iter()
            .map(|x| evaluate(&inner, d, &p, x, Order::Value).value)
            .collect()
    };
    // Step 3: f itself at the domain points of interior (straight) edges.
    let edges = mesh.edge_kinds(t);
    let df = d as f64;
    for (n, (i, j, k)) in multi_indices(d).enumerate() {
        let on_edge = [k == 0, i == 0, j == 0];
        if (0..3).any(|e| on_edge[e] && edges[e] == EdgeKind::Straight) {
            values[n] = sample(companion.point([i as f64 / df, j as f64 / df, k as f64 / df]))?;
        }
    }
    Ok(interp.coefficients(&values))
}

/// An ordinary triangle inside curved triangle `t`, as large as its arcs allow: with
/// `lambda_k` the barycentric coordinate of vertex `k` of the companion triangle and
/// `alpha_k >= 0` the largest value `lambda_k` takes on the arc of the opposite edge (0 for a
/// straight edge or an arc outside the companion triangle), the triangle
/// `{lambda_k >= alpha_k, k = 0, 1, 2}`, similar to the companion with ratio
/// `1 - sum alpha_k`. No arc enters it, so it lies in the curved triangle; it is the companion
/// itself when every arc bulges outwards.
///
/// # Errors
/// [`SplineError::ThinTriangle`] if `sum alpha_k >= 1`; [`SplineError::Mesh`] if an arc cannot
/// be cut from its curve.
pub fn inner_triangle(mesh: &CurvedTriangulation, t: usize) -> Result<Triangle, SplineError> {
    let v = mesh.triangles()[t].map(|i| mesh.vertices()[i]);
    let companion = Triangle::new(v[0], v[1], v[2]);
    let mut alpha = [0.0f64; 3];
    for (e, kind) in mesh.edge_kinds(t).iter().enumerate() {
        let EdgeKind::Curved(i) = *kind else {
            continue;
        };
        let opposite = (e + 2) % 3;
        let arc = mesh.arc_curve(&mesh.arcs()[i])?;
        // lambda_opposite as an affine function, zero at the edge's first vertex.
        let ex = companion.direction(Point::new(1.0, 0.0))[opposite];
        let ey = companion.direction(Point::new(0.0, 1.0))[opposite];
        let map = Affine {
            m: [ex, 0.0, ey, 0.0, 0.0, 0.0],
        }
        .then_apply_to(Affine::translate(-v[e].x, -v[e].y));
        let lambda = map
            .apply_to_curve(&arc)
            .map_err(|e| SplineError::Mesh(e.into()))?;
        alpha[opposite] = lambda.bounding_box().max.x.max(0.0);
    }
    let total = alpha[0] + alpha[1] + alpha[2];
    if total == 0.0 {
        return Ok(companion);
    }
    if total >= 1.0 {
        return Err(SplineError::ThinTriangle { triangle: t });
    }
    let corner = |k: usize| {
        let mut b = alpha;
        b[k] = 1.0 - (total - alpha[k]);
        companion.point(b)
    };
    Ok(Triangle::new(corner(0), corner(1), corner(2)))
}
