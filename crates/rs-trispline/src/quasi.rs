//! The quasi-interpolation operator `Q` of Algorithm 6.1 (Schumaker and Yu 2021): a local,
//! linear projection of continuous functions onto `S_d^0` of a curved triangulation that
//! reproduces every polynomial of degree `d`.

use rs_mesh::{CurvedTriangulation, EdgeKind};
use rs_spline::prelude::*;
use rs_spline::{Affine, Point};

use crate::bb::{DomainPointInterpolation, MAX_DEGREE, Order, Triangle, evaluate, multi_indices};
use crate::{SpaceKind, Spline, TriSplineError};

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
/// continuous; for `f` a polynomial of degree `<= d` every step is exact, so `Q f = f`. This
/// is [`QuasiInterpolation`] with `f` sampled in parallel.
///
/// # Errors
/// [`TriSplineError::Degree`] outside `1..=`[`MAX_DEGREE`]; [`TriSplineError::NotFinite`] if `f` is not
/// finite at a point it is sampled at; [`TriSplineError::ThinTriangle`].
pub fn quasi_interpolate(
    mesh: CurvedTriangulation,
    d: usize,
    f: &(dyn Fn(Point) -> f64 + Sync),
) -> Result<Spline, TriSplineError> {
    use rayon::prelude::*;
    let plan = QuasiInterpolation::new(mesh, d)?;
    let values: Vec<f64> = plan.points().par_iter().map(|&p| f(p)).collect();
    plan.finish(&values)
}

/// Algorithm 6.1 in two steps, for a function known only by its values (sampled by the
/// caller, all at once: a vectorised function, measurements): [`QuasiInterpolation::points`]
/// lists where the function is needed, [`QuasiInterpolation::finish`] builds `Q f` from the
/// values there.
#[derive(Clone, Debug)]
pub struct QuasiInterpolation {
    mesh: CurvedTriangulation,
    d: usize,
    inner: Vec<Triangle>,
    /// Per triangle, where its values start in `points`.
    offsets: Vec<usize>,
    points: Vec<Point>,
}

impl QuasiInterpolation {
    /// The plan for degree `d` on `mesh`: for each triangle the domain points of its inner
    /// triangle and, where that is not the companion, the companion's domain points on
    /// interior edges.
    ///
    /// # Errors
    /// [`TriSplineError::Degree`], [`TriSplineError::ThinTriangle`].
    pub fn new(mesh: CurvedTriangulation, d: usize) -> Result<Self, TriSplineError> {
        if !(1..=MAX_DEGREE).contains(&d) {
            return Err(TriSplineError::Degree(d));
        }
        let mut inner = Vec::with_capacity(mesh.triangles().len());
        let mut offsets = Vec::with_capacity(mesh.triangles().len() + 1);
        let mut points = Vec::new();
        for t in 0..mesh.triangles().len() {
            let companion = companion(&mesh, t);
            let hat = inner_triangle(&mesh, t)?;
            offsets.push(points.len());
            points.extend(hat.domain_points(d));
            if hat != companion {
                points.extend(interior_edge_points(&mesh, t, d).map(|(_, p)| p));
            }
            inner.push(hat);
        }
        offsets.push(points.len());
        Ok(Self {
            mesh,
            d,
            inner,
            offsets,
            points,
        })
    }

    /// Where the function is needed, in the order [`QuasiInterpolation::finish`] takes its
    /// values.
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// `Q f` from the values of `f` at [`QuasiInterpolation::points`].
    ///
    /// # Errors
    /// [`TriSplineError::NotFinite`] for a value that is not finite, [`TriSplineError::File`] if
    /// the number of values is wrong.
    pub fn finish(self, values: &[f64]) -> Result<Spline, TriSplineError> {
        use rayon::prelude::*;
        if values.len() != self.points.len() {
            return Err(TriSplineError::File(format!(
                "{} values for {} points",
                values.len(),
                self.points.len()
            )));
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(TriSplineError::NotFinite {
                x: self.points[i].x,
                y: self.points[i].y,
                value: values[i],
            });
        }
        let interp = DomainPointInterpolation::new(self.d);
        let per_triangle: Vec<Vec<f64>> = (0..self.inner.len())
            .into_par_iter()
            .map(|t| self.triangle_coefficients(t, &interp, values))
            .collect();
        Spline::new(
            self.mesh,
            self.d,
            SpaceKind::Continuous,
            per_triangle.concat(),
        )
    }

    /// Steps 2-4 for triangle `t`.
    fn triangle_coefficients(
        &self,
        t: usize,
        interp: &DomainPointInterpolation,
        values: &[f64],
    ) -> Vec<f64> {
        let d = self.d;
        let n = crate::bb::coefficient_count(d);
        let own = &values[self.offsets[t]..self.offsets[t + 1]];
        let companion = companion(&self.mesh, t);
        let hat = &self.inner[t];
        if *hat == companion {
            return interp.coefficients(&own[..n]);
        }
        let p = interp.coefficients(&own[..n]);
        let mut at_companion: Vec<f64> = companion
            .domain_points(d)
            .into_iter()
            .map(|x| evaluate(hat, d, &p, x, Order::Value).value)
            .collect();
        // Step 3: f itself at the domain points of interior (straight) edges.
        for ((index, _), &v) in interior_edge_points(&self.mesh, t, d).zip(&own[n..]) {
            at_companion[index] = v;
        }
        interp.coefficients(&at_companion)
    }
}

fn companion(mesh: &CurvedTriangulation, t: usize) -> Triangle {
    let v = mesh.triangles()[t].map(|i| mesh.vertices()[i]);
    Triangle::new(v[0], v[1], v[2])
}

/// The companion triangle's domain points of degree `d` on its interior (straight) edges,
/// vertices included, with their positions in coefficient order.
fn interior_edge_points(
    mesh: &CurvedTriangulation,
    t: usize,
    d: usize,
) -> impl Iterator<Item = (usize, Point)> {
    let edges = mesh.edge_kinds(t);
    let tri = companion(mesh, t);
    let df = d as f64;
    multi_indices(d)
        .enumerate()
        .filter(move |&(_, (i, j, k))| {
            let on_edge = [k == 0, i == 0, j == 0];
            (0..3).any(|e| on_edge[e] && edges[e] == EdgeKind::Straight)
        })
        .map(move |(n, (i, j, k))| (n, tri.point([i as f64 / df, j as f64 / df, k as f64 / df])))
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
/// [`TriSplineError::ThinTriangle`] if `sum alpha_k >= 1`; [`TriSplineError::Mesh`] if an arc cannot
/// be cut from its curve.
pub fn inner_triangle(mesh: &CurvedTriangulation, t: usize) -> Result<Triangle, TriSplineError> {
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
            .map_err(|e| TriSplineError::Mesh(e.into()))?;
        alpha[opposite] = lambda.bounding_box().max.x.max(0.0);
    }
    let total = alpha[0] + alpha[1] + alpha[2];
    if total == 0.0 {
        return Ok(companion);
    }
    if total >= 1.0 {
        return Err(TriSplineError::ThinTriangle { triangle: t });
    }
    let corner = |k: usize| {
        let mut b = alpha;
        b[k] = 1.0 - (total - alpha[k]);
        companion.point(b)
    };
    Ok(Triangle::new(corner(0), corner(1), corner(2)))
}
