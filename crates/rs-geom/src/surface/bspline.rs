//! Tensor-product rational B-spline surfaces (ISO 10303-42 `B_SPLINE_SURFACE_WITH_KNOTS` and
//! `RATIONAL_B_SPLINE_SURFACE`, IGES 128; `OpenCASCADE`'s `Geom_BSplineSurface` alike), on
//! `rs-spline`'s knot vectors and evaluation kernel.

use rs_spline::{KnotVector, Point3, RationalBSpline, tensor_rational_sums};

use super::invert::{MAX_GRID_SIDE, closest, sample_params};
use super::{
    COINCIDENCE_RELATIVE, Inversion, ParamBox, ParamSurface, Pole, SurfaceDerivatives, copy_from,
    hostile_point, interior_side, normal_from_derivatives,
};
use crate::GeomError;

/// Sample values per knot span of each parameter in the grid that starts the Newton searches
/// (fewer where there are many spans: at most [`MAX_GRID_SIDE`] a side).
const SAMPLES_PER_SPAN: usize = 3;

/// `S(u, v) = sum_ij N_i(u) M_j(v) w_ij P_ij / sum_ij N_i(u) M_j(v) w_ij` on two
/// [`KnotVector`]s, control points `P_ij` stored row by row (`[i][j]` at `i nv + j`, `i` along
/// `u`), weights `w_ij > 0` (all 1 without weights). The parameter box is the two knot
/// domains; parameters outside are clamped, except in a closed direction, where they are taken
/// modulo the domain's length.
///
/// Evaluation goes through [`rs_spline::tensor_rational_sums`] (each row's homogeneous sums
/// in `v` as [`rs_spline::rational_sums`] forms them, combined in `u`), then the
/// tensor-product quotient rule.
#[derive(Clone, Debug, PartialEq)]
pub struct BSplineSurface {
    knots: [KnotVector; 2],
    points: Vec<Point3>,
    weights: Option<Vec<f64>>,
    periods: [Option<f64>; 2],
    poles: Vec<Pole>,
    size: f64,
}

/// The homogeneous sums `(sum N M w P, sum N M w)` with their derivatives: `h[a][b]` is the
/// `a`-th derivative in `u` and `b`-th in `v` (`a + b <= 2`).
type Sums = [[(Point3, f64); 3]; 3];

impl BSplineSurface {
    /// The surface on knot vectors `knots = [along u, along v]` with the `nu x nv` control
    /// points (`nu`, `nv` the knot vectors' control-point counts) row by row and optional
    /// weights. Whether it is closed in `u` or `v` (and with what period) and which boundary
    /// lines are poles is worked out here (see [`BSplineSurface::with_closed`]).
    ///
    /// # Errors
    /// [`GeomError::ControlNetSize`] when the points do not fill the net; the control data's
    /// [`rs_spline::SplineError`]s (as [`GeomError::Spline`], indices counted row by row):
    /// non-finite or too large coordinates, a weight count other than the points', a weight
    /// not finite and `> 0`, weights spread beyond [`rs_spline::limits::MAX_WEIGHT_RATIO`]
    /// (weights are rescaled by a power of two, exactly, as curves' are).
    pub fn new(
        knots: [KnotVector; 2],
        points: Vec<Point3>,
        weights: Option<Vec<f64>>,
    ) -> Result<BSplineSurface, GeomError> {
        let (rows, columns) = (knots[0].n_control(), knots[1].n_control());
        if rows.checked_mul(columns) != Some(points.len()) {
            return Err(GeomError::ControlNetSize {
                rows,
                columns,
                got: points.len(),
            });
        }
        // The control net is checked (and its weights rescaled) as the control polygon of a
        // curve: the one check of the spline layer.
        let polygon = KnotVector::uniform_clamped(1, points.len())?;
        let checked = RationalBSpline::from_parts(polygon, points, weights)?;
        let weights = checked.weights().map(<[f64]>::to_vec);
        let points = checked.control_points().to_vec();
        let size = Point3::bounds(points.iter().copied())
            .map_or(0.0, |(lo, hi)| lo.distance(hi))
            .max(f64::MIN_POSITIVE);
        let mut s = BSplineSurface {
            knots,
            points,
            weights,
            periods: [None, None],
            poles: Vec::new(),
            size,
        };
        let tol = COINCIDENCE_RELATIVE * size;
        for dir in 0..2 {
            let (a, b) = s.knots[dir].domain();
            let (first, last) = (s.iso_net(dir, a), s.iso_net(dir, b));
            if same_curve(&first, &last, tol) {
                s.periods[dir] = Some(b - a);
            }
            for (t, net) in [(a, &first), (b, &last)] {
                if is_point(net, tol) {
                    s.poles.push(Pole {
                        param: dir,
                        value: t,
                    });
                }
            }
        }
        Ok(s)
    }

    /// The surface with closedness stated rather than worked out (a file's `u_closed` and
    /// `v_closed`, whose ends meet only within the file's tolerance): `Some(true)` makes the
    /// direction periodic with the knot domain's length, `Some(false)` not, `None` keeps what
    /// [`BSplineSurface::new`] found.
    pub fn with_closed(mut self, closed: [Option<bool>; 2]) -> BSplineSurface {
        for (dir, c) in closed.into_iter().enumerate() {
            if let Some(c) = c {
                let (a, b) = self.knots[dir].domain();
                self.periods[dir] = c.then_some(b - a);
            }
        }
        self
    }

    /// The knot vectors along `u` and `v`.
    pub fn knots(&self) -> &[KnotVector; 2] {
        &self.knots
    }

    /// The control points, row by row (`[i][j]` at `i nv + j`).
    pub fn control_points(&self) -> &[Point3] {
        &self.points
    }

    /// The weights (rescaled by a power of two), `None` when all are 1.
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// The diagonal of the control points' bounding box.
    pub(crate) fn size(&self) -> f64 {
        self.size
    }

    /// The same surface with every control point mapped by `f` (exact for affine maps).
    pub(crate) fn map_points(
        &self,
        f: impl Fn(Point3) -> Point3,
    ) -> Result<BSplineSurface, GeomError> {
        let s = BSplineSurface::new(
            self.knots.clone(),
            self.points.iter().map(|&p| f(p)).collect(),
            self.weights.clone(),
        )?;
        Ok(s.with_closed([
            Some(self.periods[0].is_some()),
            Some(self.periods[1].is_some()),
        ]))
    }

    /// The parameter `t` of direction `dir` as evaluated: modulo the period where closed.
    fn param(&self, dir: usize, t: f64) -> f64 {
        match self.periods[dir] {
            Some(p) => copy_from(t, self.knots[dir].domain().0, p),
            None => t,
        }
    }

    /// The homogeneous sums with derivatives up to order `nd` (0, 1 or 2) at `uv`.
    fn sums(&self, uv: [f64; 2], nd: usize) -> Sums {
        let [ku, kv] = &self.knots;
        let uv = [self.param(0, uv[0]), self.param(1, uv[1])];
        tensor_rational_sums([ku, kv], &self.points, self.weights.as_deref(), uv, nd)
    }

    /// The control net of the iso-curve `u = t` (`dir = 0`) or `v = t` (`dir = 1`) as
    /// homogeneous pairs `(sum N w P, sum N w)`: a rational B-spline on the other knot vector.
    fn iso_net(&self, dir: usize, t: f64) -> Vec<(Point3, f64)> {
        let kv = &self.knots[dir];
        let k = kv.span(t);
        let p = kv.degree();
        let basis = kv.basis_derivatives(k, t, 0);
        let nv = self.knots[1].n_control();
        let count = self.knots[1 - dir].n_control();
        let weight = |i: usize| self.weights.as_ref().map_or(1.0, |w| w[i]);
        (0..count)
            .map(|j| {
                let mut acc = (Point3::ORIGIN, 0.0);
                for (c, &n) in basis[0].iter().enumerate() {
                    let i = k - p + c;
                    let index = if dir == 0 { i * nv + j } else { j * nv + i };
                    let w = weight(index) * n;
                    acc = (acc.0 + self.points[index] * w, acc.1 + w);
                }
                acc
            })
            .collect()
    }

    /// Sample values along `u` and `v`: knots and [`SAMPLES_PER_SPAN`] per span.
    pub(crate) fn sample_grid(&self) -> [Vec<f64>; 2] {
        std::array::from_fn(|dir| {
            let k = &self.knots[dir];
            sample_params(
                k.domain(),
                &k.interior_breaks(),
                SAMPLES_PER_SPAN,
                MAX_GRID_SIDE,
            )
        })
    }
}

/// Do two iso-curve nets (homogeneous) describe the same curve: the same points within `tol`
/// and proportional weights?
fn same_curve(a: &[(Point3, f64)], b: &[(Point3, f64)], tol: f64) -> bool {
    let (Some(&(_, wa)), Some(&(_, wb))) = (a.first(), b.first()) else {
        return false;
    };
    a.len() == b.len()
        && a.iter().zip(b).all(|(&(pa, ua), &(pb, ub))| {
            (pa * (1.0 / ua)).distance(pb * (1.0 / ub)) <= tol
                && (ua / wa - ub / wb).abs() <= COINCIDENCE_RELATIVE * (ua / wa)
        })
}

/// Is an iso-curve net one point (within `tol`)?
fn is_point(net: &[(Point3, f64)], tol: f64) -> bool {
    let Some(&(p0, w0)) = net.first() else {
        return false;
    };
    let first = p0 * (1.0 / w0);
    net.iter()
        .all(|&(p, w)| (p * (1.0 / w)).distance(first) <= tol)
}

impl ParamSurface for BSplineSurface {
    fn point(&self, uv: [f64; 2]) -> Point3 {
        let h = self.sums(uv, 0);
        h[0][0].0 * (1.0 / h[0][0].1)
    }

    /// The tensor-product quotient rule on the homogeneous sums `A`, `w`: `S = A / w`,
    /// `S_u = (A_u - w_u S) / w`, `S_uu = (A_uu - 2 w_u S_u - w_uu S) / w`, `S_uv = (A_uv -
    /// w_uv S - w_u S_v - w_v S_u) / w` (likewise in `v`). At a knot the derivatives are those
    /// of the span above it (below it at the domain's end).
    fn derivatives(&self, uv: [f64; 2]) -> SurfaceDerivatives {
        let h = self.sums(uv, 2);
        let w = h[0][0].1;
        let inv = 1.0 / w;
        let point = h[0][0].0 * inv;
        let (wu, wv) = (h[1][0].1, h[0][1].1);
        let du = (h[1][0].0 - point * wu) * inv;
        let dv = (h[0][1].0 - point * wv) * inv;
        SurfaceDerivatives {
            point,
            du,
            dv,
            duu: (h[2][0].0 - du * (2.0 * wu) - point * h[2][0].1) * inv,
            duv: (h[1][1].0 - point * h[1][1].1 - dv * wu - du * wv) * inv,
            dvv: (h[0][2].0 - dv * (2.0 * wv) - point * h[0][2].1) * inv,
        }
    }

    /// The quotient rule on the sums of order 1 only.
    fn first_derivatives(&self, uv: [f64; 2]) -> [Point3; 3] {
        let h = self.sums(uv, 1);
        let inv = 1.0 / h[0][0].1;
        let point = h[0][0].0 * inv;
        let du = (h[1][0].0 - point * h[1][0].1) * inv;
        let dv = (h[0][1].0 - point * h[0][1].1) * inv;
        [point, du, dv]
    }

    /// The unit `S_u x S_v`; on a pole line (a boundary row of coincident control points) its
    /// limit from inside the knot domain.
    fn normal(&self, uv: [f64; 2]) -> Option<Point3> {
        normal_from_derivatives(&self.derivatives(uv), interior_side(&self.param_box(), uv))
    }

    fn param_box(&self) -> ParamBox {
        ParamBox {
            u: self.knots[0].domain(),
            v: self.knots[1].domain(),
        }
    }

    /// The knot domain's length in a direction whose two boundary iso-curves coincide (within
    /// `1e-9` of the control net's size), or as stated by [`BSplineSurface::with_closed`].
    fn periods(&self) -> [Option<f64>; 2] {
        self.periods
    }

    /// The boundary lines whose iso-curve is one point (the boundary row of control points,
    /// combined by the basis functions there, coincides within `1e-9` of the net's size).
    fn poles(&self) -> Vec<Pole> {
        self.poles.clone()
    }

    /// Newton's method (see [`crate::surface`]) from `near` and from the best nodes of a grid
    /// of the knots and three values per knot span.
    fn invert(&self, x: Point3, near: Option<[f64; 2]>) -> Inversion {
        let bx = self.param_box();
        if let Some(bad) = hostile_point(x, near, [bx.u.0, bx.v.0]) {
            return bad;
        }
        let grid = self.sample_grid();
        closest(self, x, near, &[], Some(&grid), self.size)
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::{FRAC_PI_2, TAU};

    use super::*;
    use crate::Frame;
    use crate::surface::Sphere;
    use crate::surface::testing::{
        Rng, check_derivatives, check_normal, check_round_trip, sphere_octant,
    };

    #[test]
    fn a_rational_octant_is_the_sphere() {
        let s = sphere_octant(2.0);
        let sphere = Sphere::new(Frame::WORLD, 2.0).unwrap();
        assert_eq!(
            s.poles(),
            vec![Pole {
                param: 1,
                value: 1.0
            }]
        );
        assert_eq!(s.periods(), [None, None]);
        let mut rng = Rng::new(41);
        for _ in 0..40 {
            let uv = [rng.range(0.03, 0.97), rng.range(0.03, 0.97)];
            let p = s.point(uv);
            assert!((p.length() - 2.0).abs() < 1e-14 * 4.0);
            check_derivatives(&s, uv, 0.1);
            check_normal(&s, uv);
            // The normal is the sphere's closed form p / r.
            assert!(s.normal(uv).unwrap().distance(p * 0.5) < 1e-12);
            check_round_trip(&s, uv, None, 1e-10, 4.0);
            check_round_trip(&s, uv, Some([0.5, 0.5]), 1e-10, 4.0);
            // Points in the octant's cone: the foot is the sphere's.
            let dir = Point3::new(
                rng.range(0.05, 1.0),
                rng.range(0.05, 1.0),
                rng.range(0.05, 1.0),
            );
            let x = dir * (rng.range(0.2, 5.0) / dir.length());
            let (i, j) = (s.invert(x, None), sphere.invert(x, None));
            assert!(
                (i.distance - j.distance).abs() < 1e-12 * 4.0,
                "{i:?} vs {j:?}"
            );
            assert!(s.point(i.uv).distance(sphere.point(j.uv)) < 1e-10 * 4.0);
        }
        // The pole: one point, the normal +z (the limit from inside), near's u kept.
        assert!(s.point([0.2, 1.0]).distance(Point3::new(0.0, 0.0, 2.0)) < 1e-15);
        assert!(s.normal([0.3, 1.0]).unwrap().distance(Point3::Z) < 1e-12);
        let inv = s.invert(Point3::new(0.0, 0.0, 3.0), Some([0.4, 0.9]));
        assert!((inv.distance - 1.0).abs() < 1e-14 && inv.uv[1] == 1.0);
        assert!((inv.uv[0] - 0.4).abs() < 1e-9, "{inv:?}");
    }

    #[test]
    fn polynomial_surfaces_and_knot_spans() {
        // A bicubic patch by two by three spans over a wavy net.
        let ku = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0], 3, 5).unwrap();
        let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0], 2, 5).unwrap();
        let mut rng = Rng::new(42);
        let mut points = Vec::new();
        for i in 0..5 {
            for j in 0..5 {
                points.push(Point3::new(
                    f64::from(i),
                    f64::from(j),
                    rng.range(-1.0, 1.0),
                ));
            }
        }
        let s = BSplineSurface::new([ku, kv], points.clone(), None).unwrap();
        assert!(s.weights().is_none() && s.poles().is_empty());
        // Corners interpolate the net's corners (clamped knots).
        assert!(s.point([0.0, 0.0]).distance(points[0]) < 1e-15);
        assert!(s.point([1.0, 3.0]).distance(points[24]) < 1e-14);
        for k in 0..40 {
            let uv = [
                0.5 * f64::from(k % 2) + rng.range(0.05, 0.45),
                f64::from(k % 3) + rng.range(0.05, 0.95),
            ];
            check_derivatives(&s, uv, 0.1);
            check_normal(&s, uv);
            check_round_trip(&s, uv, None, 1e-10, 8.0);
            let x = s.point(uv) + s.normal(uv).unwrap() * rng.range(-0.05, 0.05);
            let inv = s.invert(x, None);
            assert!(inv.distance <= x.distance(s.point(uv)) + 1e-12);
        }
        // Parameters outside the domain are clamped.
        assert_eq!(s.point([-1.0, 5.0]), s.point([0.0, 3.0]));
        // A weighted copy with all weights equal is the same surface.
        let w = BSplineSurface::new(s.knots().clone(), points, Some(vec![3.0; 25])).unwrap();
        for uv in [[0.1, 0.2], [0.7, 2.5]] {
            let (a, b) = (s.derivatives(uv), w.derivatives(uv));
            assert!(a.point.distance(b.point) < 1e-14 * 8.0 && a.duv.distance(b.duv) < 1e-12 * 8.0);
        }
    }

    #[test]
    fn feet_are_global_and_stationary() {
        // A wavy rational bicubic; the truth is a dense grid (independent of the grid the
        // search starts from) and the stationarity of the foot.
        let ku =
            KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0], 3, 6).unwrap();
        let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0], 3, 5).unwrap();
        let mut rng = Rng::new(44);
        let mut points = Vec::new();
        let mut weights = Vec::new();
        for i in 0..6 {
            for j in 0..5 {
                points.push(Point3::new(
                    f64::from(i),
                    f64::from(j),
                    2.0 * rng.range(-1.0, 1.0),
                ));
                weights.push(rng.range(0.5, 2.0));
            }
        }
        let s = BSplineSurface::new([ku, kv], points, Some(weights)).unwrap();
        let n = 300;
        let dense: Vec<([f64; 2], Point3)> = (0..=n)
            .flat_map(|i| {
                (0..=n).map(move |j| [f64::from(i) / f64::from(n), f64::from(j) / f64::from(n)])
            })
            .map(|uv| (uv, s.point(uv)))
            .collect();
        for _ in 0..40 {
            let x = Point3::new(
                rng.range(-1.0, 6.0),
                rng.range(-1.0, 5.0),
                rng.range(-3.0, 3.0),
            );
            let inv = s.invert(x, None);
            let grid_best = dense
                .iter()
                .map(|(_, p)| p.distance(x))
                .fold(f64::INFINITY, f64::min);
            assert!(
                inv.distance <= grid_best + 1e-12,
                "{inv:?} vs the grid's {grid_best}"
            );
            // Stationary: the offset is orthogonal to the surface in each free direction.
            let d = s.derivatives(inv.uv);
            let r = x - d.point;
            for (i, t) in [d.du, d.dv].into_iter().enumerate() {
                let at_bound = inv.uv[i] == 0.0 || inv.uv[i] == 1.0;
                if !at_bound {
                    assert!(
                        r.dot(t).abs() <= 1e-12 * 8.0 * t.length(),
                        "{inv:?}: {}",
                        r.dot(t)
                    );
                }
            }
        }
        // Off the surface along the normal, within the curvature radii: the same parameters.
        for _ in 0..40 {
            let uv = [rng.range(0.05, 0.95), rng.range(0.05, 0.95)];
            let h = rng.range(-0.01, 0.01);
            let x = s.point(uv) + s.normal(uv).unwrap() * h;
            let inv = s.invert(x, None);
            assert!(
                (inv.distance - h.abs()).abs() < 1e-12 * 8.0,
                "{inv:?} vs {h}"
            );
            assert!(
                (inv.uv[0] - uv[0]).abs() < 1e-10 && (inv.uv[1] - uv[1]).abs() < 1e-10,
                "{inv:?} vs {uv:?}"
            );
        }
    }

    #[test]
    fn a_periodic_surface_wraps_its_seam() {
        // Along u: a uniform periodic cubic over 8 points on a circle (the first 3 repeated
        // at the end, unclamped knots); along v: a linear segment. A tube.
        let n = 8;
        let ring: Vec<(f64, f64)> = (0..n)
            .map(|i| (TAU * f64::from(i) / f64::from(n)).sin_cos())
            .map(|(s, c)| (2.0 * c, 2.0 * s))
            .collect();
        let mut points = Vec::new();
        for i in 0..n + 3 {
            let (x, y) = ring[i as usize % n as usize];
            for z in [0.0, 3.0] {
                points.push(Point3::new(x, y + 0.1 * z, z));
            }
        }
        let knots: Vec<f64> = (0..(n + 3 + 4)).map(f64::from).collect();
        let ku = KnotVector::new(knots, 3, (n + 3) as usize).unwrap();
        let kv = KnotVector::bezier(1);
        let s = BSplineSurface::new([ku, kv], points, None).unwrap();
        let (a, b) = s.param_box().u;
        assert_eq!((a, b), (3.0, 11.0));
        assert_eq!(s.periods(), [Some(8.0), None]);
        // Across the seam the surface and its derivatives are continuous; u + 8 is u.
        for v in [0.0, 0.4, 1.0] {
            let (lo, hi) = (s.derivatives([a, v]), s.derivatives([b, v]));
            assert!(lo.point.distance(hi.point) < 1e-14 * 4.0);
            assert!(lo.du.distance(hi.du) < 1e-13 && lo.duu.distance(hi.duu) < 1e-12);
            assert!(s.point([4.2 + 8.0, v]).distance(s.point([4.2, v])) < 1e-13);
        }
        let mut rng = Rng::new(43);
        for _ in 0..30 {
            let uv = [
                3.0 + f64::from(rng.next_u64() as u32 % 8) + rng.range(0.05, 0.95),
                rng.range(0.05, 0.95),
            ];
            check_derivatives(&s, uv, 0.1);
            check_normal(&s, uv);
            check_round_trip(&s, uv, None, 1e-10, 4.0);
            check_round_trip(&s, uv, Some([uv[0] + 7.0, 0.5]), 1e-10, 4.0);
        }
        // A point beside the seam inverts to the copy nearest near, on either side.
        let x = s.point([3.01, 0.5]);
        let above = s.invert(x, Some([10.9, 0.5]));
        assert!((above.uv[0] - 11.01).abs() < 1e-10, "{above:?}");
        let below = s.invert(x, Some([3.2, 0.5]));
        assert!((below.uv[0] - 3.01).abs() < 1e-10, "{below:?}");
        // Closedness can be stated.
        let open = s.clone().with_closed([Some(false), None]);
        assert_eq!(open.periods(), [None, None]);
        let _ = FRAC_PI_2;
    }

    #[test]
    fn control_nets_are_validated() {
        let k = || [KnotVector::bezier(1), KnotVector::bezier(1)];
        let four = vec![
            Point3::ORIGIN,
            Point3::X,
            Point3::Y,
            Point3::new(1.0, 1.0, 0.0),
        ];
        assert!(matches!(
            BSplineSurface::new(k(), four[..3].to_vec(), None),
            Err(GeomError::ControlNetSize {
                rows: 2,
                columns: 2,
                got: 3
            })
        ));
        assert!(matches!(
            BSplineSurface::new(k(), four.clone(), Some(vec![1.0; 3])),
            Err(GeomError::Spline(_))
        ));
        assert!(matches!(
            BSplineSurface::new(k(), four.clone(), Some(vec![1.0, 1.0, 0.0, 1.0])),
            Err(GeomError::Spline(_))
        ));
        let mut bad = four.clone();
        bad[2].z = f64::NAN;
        assert!(BSplineSurface::new(k(), bad, None).is_err());
        // Huge but uniform weights are rescaled exactly.
        let s = BSplineSurface::new(k(), four.clone(), Some(vec![1e200; 4])).unwrap();
        assert!(s.weights().unwrap()[0] < 1e10);
        assert!(s.point([0.5, 0.5]).distance(Point3::new(0.5, 0.5, 0.0)) < 1e-15);
    }
}
