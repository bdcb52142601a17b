//! Bernstein–Bézier polynomials on a triangle (Lai and Schumaker 2007, chapter 2): a
//! polynomial of degree `d` is `p = sum c_ijk B_ijk` over `i + j + k = d`, with
//! `B_ijk = d! / (i! j! k!) b1^i b2^j b3^k` in the barycentric coordinates `(b1, b2, b3)` of the
//! triangle. Evaluated and differentiated by de Casteljau's algorithm, anywhere in the plane
//! (barycentric coordinates outside the triangle are just negative).
//!
//! Coefficients are stored in one order everywhere: `c_ijk` by decreasing `i`, then
//! decreasing `j` ([`index`]), `i` belonging to the triangle's first vertex, `j` to its second
//! and `k` to its third. The coefficient `c_ijk` sits at the *domain point*
//! `(i v1 + j v2 + k v3) / d`.

use rs_spline::Point;

/// The largest degree accepted: the interpolation matrix at the domain points stays well
/// conditioned (its inverse's norm grows with the degree) and a triangle holds at most 91
/// coefficients.
pub const MAX_DEGREE: usize = 12;

/// Number of coefficients (domain points) of degree `d`: `(d + 1)(d + 2) / 2`.
pub const fn coefficient_count(d: usize) -> usize {
    (d + 1) * (d + 2) / 2
}

/// Position of `c_ijk` (`i + j + k = d`) in the coefficient order: with `s = j + k = d - i`,
/// the `s (s + 1) / 2` coefficients of larger `i` come first, then `k` more.
pub const fn index(j: usize, k: usize) -> usize {
    let s = j + k;
    s * (s + 1) / 2 + k
}

/// The indices `(i, j, k)` of degree `d` in coefficient order.
pub fn multi_indices(d: usize) -> impl Iterator<Item = (usize, usize, usize)> {
    (0..=d)
        .rev()
        .flat_map(move |i| (0..=d - i).rev().map(move |j| (i, j, d - i - j)))
}

/// A triangle with vertices `v1, v2, v3`, its barycentric coordinates precomputed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// The vertices.
    pub v: [Point; 3],
    /// Twice the signed area.
    area2: f64,
}

impl Triangle {
    /// The triangle `v1 v2 v3` (either orientation; it must not be degenerate).
    pub fn new(v1: Point, v2: Point, v3: Point) -> Self {
        Self {
            v: [v1, v2, v3],
            area2: (v2 - v1).cross(v3 - v1),
        }
    }

    /// Twice the signed area (positive for counter-clockwise vertices).
    pub fn double_area(&self) -> f64 {
        self.area2
    }

    /// Barycentric coordinates of `p` (they add up to 1; negative outside).
    pub fn barycentric(&self, p: Point) -> [f64; 3] {
        let [a, b, c] = self.v;
        let b1 = (b - p).cross(c - p) / self.area2;
        let b2 = (c - p).cross(a - p) / self.area2;
        [b1, b2, 1.0 - b1 - b2]
    }

    /// Barycentric coordinates of the direction `u` (they add up to 0): the change of the
    /// coordinates along `u`.
    pub fn direction(&self, u: Point) -> [f64; 3] {
        let [a, b, c] = self.v;
        let a1 = (c - b).cross(u) / self.area2;
        let a2 = (a - c).cross(u) / self.area2;
        [a1, a2, -a1 - a2]
    }

    /// The point with barycentric coordinates `b`.
    pub fn point(&self, b: [f64; 3]) -> Point {
        self.v[0] * b[0] + self.v[1] * b[1] + self.v[2] * b[2]
    }

    /// The domain points of degree `d`, in coefficient order.
    pub fn domain_points(&self, d: usize) -> Vec<Point> {
        let df = d as f64;
        multi_indices(d)
            .map(|(i, j, k)| self.point([i as f64 / df, j as f64 / df, k as f64 / df]))
            .collect()
    }
}

/// One de Casteljau step: the coefficients of degree `m - 1` from those of degree `m` in
/// `c[..count(m)]`, blended with weights `w` (in place: entry `index(j, k)` of the result only
/// reads entries `index(j, k)`, `index(j + 1, k)`, `index(j, k + 1)` of degree `m`, all at or
/// after it). Row by row: the entries with `j + k = s` are contiguous (`index(s - k, k) =
/// s (s + 1) / 2 + k`), and row `s` of the result reads rows `s` and `s + 1` only, so the
/// inner loop runs over two slices without index arithmetic.
#[inline(always)]
fn step(c: &mut [f64], m: usize, w: [f64; 3]) {
    let mut start = 0;
    for s in 0..m {
        let next = start + s + 1;
        let (rows, below) = c.split_at_mut(next);
        let row = &mut rows[start..];
        let below = &below[..s + 2];
        for (k, r) in row.iter_mut().enumerate() {
            *r = w[0] * *r + w[1] * below[k] + w[2] * below[k + 1];
        }
        start = next;
    }
}

/// A polynomial's value, gradient and Hessian at a point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Jet {
    /// `p`.
    pub value: f64,
    /// `(p_x, p_y)`.
    pub gradient: [f64; 2],
    /// `(p_xx, p_xy, p_yy)`.
    pub hessian: [f64; 3],
}

/// How much of the jet to compute.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Order {
    /// The value.
    Value,
    /// Value and gradient.
    Gradient,
    /// Value, gradient and Hessian.
    Hessian,
}

/// Stack room for the coefficients of [`MAX_DEGREE`].
const STACK: usize = coefficient_count(MAX_DEGREE);

/// The value (and derivatives up to `order`) at `p` of the polynomial of degree `d` with
/// coefficients `c` (in coefficient order) on `tri`, by de Casteljau's algorithm: `d - r` steps
/// with the barycentric coordinates of `p`, then the last `r` with those of the directions
/// (the blossom), times `d! / (d - r)!`.
///
/// # Panics
/// If `c` does not hold [`coefficient_count`]`(d)` coefficients or `d > MAX_DEGREE`.
pub fn evaluate(tri: &Triangle, d: usize, c: &[f64], p: Point, order: Order) -> Jet {
    assert!(d <= MAX_DEGREE && c.len() == coefficient_count(d));
    let b = tri.barycentric(p);
    if order == Order::Value {
        return Jet {
            value: value_at(d, c, b),
            ..Jet::default()
        };
    }
    let mut work = [0.0f64; STACK];
    let n = c.len();
    work[..n].copy_from_slice(c);
    let keep = match order {
        Order::Value => 0,
        Order::Gradient => 1,
        Order::Hessian => 2,
    }
    .min(d);
    for m in (keep + 1..=d).rev() {
        step(&mut work, m, b);
    }
    let mut jet = Jet::default();
    if keep == 0 {
        jet.value = work[0];
        return jet;
    }
    let (ex, ey) = (
        tri.direction(Point::new(1.0, 0.0)),
        tri.direction(Point::new(0.0, 1.0)),
    );
    let df = d as f64;
    match keep {
        1 => {
            let lin = [work[0], work[1], work[2]];
            let dot = |w: [f64; 3]| w[0] * lin[0] + w[1] * lin[1] + w[2] * lin[2];
            jet.value = dot(b);
            jet.gradient = [df * dot(ex), df * dot(ey)];
        }
        _ => {
            // Degree 2 coefficients: the polar form with two more arguments.
            let quad = [work[0], work[1], work[2], work[3], work[4], work[5]];
            let polar = |u: [f64; 3], w: [f64; 3]| {
                let mut q = quad;
                step(&mut q, 2, u);
                step(&mut q, 1, w);
                q[0]
            };
            jet.value = polar(b, b);
            jet.gradient = [df * polar(ex, b), df * polar(ey, b)];
            let dd = df * (df - 1.0);
            jet.hessian = [dd * polar(ex, ex), dd * polar(ex, ey), dd * polar(ey, ey)];
        }
    }
    if order >= Order::Gradient && d == 0 {
        jet.gradient = [0.0; 2];
    }
    jet
}

/// The value at barycentric coordinates `b` by de Casteljau, with the degree a constant so
/// that every loop unrolls (values are the common case: five times faster than the general
/// loop at degree 5).
fn value_at(d: usize, c: &[f64], b: [f64; 3]) -> f64 {
    #[inline(always)]
    fn fixed<const D: usize, const N: usize>(c: &[f64], b: [f64; 3]) -> f64 {
        debug_assert_eq!(N, coefficient_count(D));
        let mut work = [0.0f64; N];
        work.copy_from_slice(&c[..N]);
        for m in (1..=D).rev() {
            step(&mut work, m, b);
        }
        work[0]
    }
    match d {
        0 => c[0],
        1 => fixed::<1, 3>(c, b),
        2 => fixed::<2, 6>(c, b),
        3 => fixed::<3, 10>(c, b),
        4 => fixed::<4, 15>(c, b),
        5 => fixed::<5, 21>(c, b),
        6 => fixed::<6, 28>(c, b),
        7 => fixed::<7, 36>(c, b),
        8 => fixed::<8, 45>(c, b),
        9 => fixed::<9, 55>(c, b),
        10 => fixed::<10, 66>(c, b),
        11 => fixed::<11, 78>(c, b),
        _ => fixed::<12, 91>(c, b),
    }
}

/// The polynomial's values at the domain points of `tri`, in coefficient order (the inverse
/// of [`DomainPointInterpolation::coefficients`]).
pub fn values_at_domain_points(tri: &Triangle, d: usize, c: &[f64]) -> Vec<f64> {
    tri.domain_points(d)
        .into_iter()
        .map(|p| evaluate(tri, d, c, p, Order::Value).value)
        .collect()
}

/// The coefficients of the same polynomial written with degree `d + 1`:
/// `c'_ijk = (i c_(i-1)jk + j c_i(j-1)k + k c_ij(k-1)) / (d + 1)`.
pub fn raise_degree(d: usize, c: &[f64]) -> Vec<f64> {
    let e = d + 1;
    multi_indices(e)
        .map(|(i, j, k)| {
            let mut v = 0.0;
            if i > 0 {
                v += i as f64 * c[index(j, k)];
            }
            if j > 0 {
                v += j as f64 * c[index(j - 1, k)];
            }
            if k > 0 {
                v += k as f64 * c[index(j, k - 1)];
            }
            v / e as f64
        })
        .collect()
}

/// `B^d_ijk(b)`.
pub fn bernstein(d: usize, (i, j, k): (usize, usize, usize), b: [f64; 3]) -> f64 {
    multinomial(d, i, j) * b[0].powi(i as i32) * b[1].powi(j as i32) * b[2].powi(k as i32)
}

/// `d! / (i! j! k!)` with `k = d - i - j`.
fn multinomial(d: usize, i: usize, j: usize) -> f64 {
    binomial(d, i) * binomial(d - i, j)
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, t| acc * (n - t) as f64 / (t + 1) as f64)
}

/// The interpolation operator at the domain points of degree `d`, the same for every
/// triangle: coefficients from the values at the domain points (in coefficient order), and
/// back. The matrix `M[xi][ijk] = B_ijk(xi)` is factored once per degree.
#[derive(Clone, Debug)]
pub struct DomainPointInterpolation {
    d: usize,
    lu: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
}

impl DomainPointInterpolation {
    /// The operator of degree `d` (1 to [`MAX_DEGREE`]).
    ///
    /// # Panics
    /// If `d` is 0 or above [`MAX_DEGREE`].
    pub fn new(d: usize) -> Self {
        assert!(
            (1..=MAX_DEGREE).contains(&d),
            "degree {d} out of 1..={MAX_DEGREE}"
        );
        let n = coefficient_count(d);
        let df = d as f64;
        let points: Vec<[f64; 3]> = multi_indices(d)
            .map(|(i, j, k)| [i as f64 / df, j as f64 / df, k as f64 / df])
            .collect();
        let basis: Vec<(usize, usize, usize)> = multi_indices(d).collect();
        let m = nalgebra::DMatrix::from_fn(n, n, |r, c| bernstein(d, basis[c], points[r]));
        Self { d, lu: m.lu() }
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.d
    }

    /// The coefficients of the polynomial taking `values` at the domain points.
    pub fn coefficients(&self, values: &[f64]) -> Vec<f64> {
        let rhs = nalgebra::DVector::from_column_slice(values);
        self.lu
            .solve(&rhs)
            .map_or_else(|| vec![f64::NAN; values.len()], |x| x.as_slice().to_vec())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> Triangle {
        Triangle::new(
            Point::new(0.3, -0.2),
            Point::new(2.0, 0.4),
            Point::new(0.7, 1.9),
        )
    }

    /// A cubic in x and y and its derivatives.
    fn f(p: Point) -> Jet {
        let (x, y) = (p.x, p.y);
        Jet {
            value: 1.0 - 2.0 * x + 0.5 * y + x * x * y - 3.0 * y * y * y + x * y,
            gradient: [-2.0 + 2.0 * x * y + y, 0.5 + x * x - 9.0 * y * y + x],
            hessian: [2.0 * y, 2.0 * x + 1.0, -18.0 * y],
        }
    }

    #[test]
    fn indices_follow_the_file_order() {
        let order: Vec<_> = multi_indices(2).collect();
        assert_eq!(
            order,
            [
                (2, 0, 0),
                (1, 1, 0),
                (1, 0, 1),
                (0, 2, 0),
                (0, 1, 1),
                (0, 0, 2)
            ]
        );
        for d in 0..=MAX_DEGREE {
            for (n, (_, j, k)) in multi_indices(d).enumerate() {
                assert_eq!(index(j, k), n);
            }
        }
    }

    #[test]
    fn interpolation_reproduces_polynomials_with_derivatives_anywhere() {
        let t = tri();
        for d in 3..=MAX_DEGREE {
            let interp = DomainPointInterpolation::new(d);
            let values: Vec<f64> = t.domain_points(d).iter().map(|&p| f(p).value).collect();
            let c = interp.coefficients(&values);
            // Inside and well outside the triangle.
            for p in [
                Point::new(0.9, 0.6),
                Point::new(-1.0, 3.0),
                Point::new(2.5, -1.5),
            ] {
                let got = evaluate(&t, d, &c, p, Order::Hessian);
                let want = f(p);
                // Rounding grows like the interpolation matrix (about 2^d at equally spaced
                // points) and like |b|^d away from the triangle.
                let bmax = t.barycentric(p).iter().fold(1.0f64, |m, b| m.max(b.abs()));
                // Each derivative multiplies by the degree over the triangle's size.
                let tol = 1e-13 * (2.0 * (1.0 + bmax)).powi(d as i32);
                let close = |a: f64, b: f64, k: i32| {
                    (a - b).abs() < tol * (d as f64).powi(k) * (1.0 + b.abs())
                };
                assert!(
                    close(got.value, want.value, 0),
                    "d {d} {p:?}: {got:?} {want:?}"
                );
                for i in 0..2 {
                    assert!(
                        close(got.gradient[i], want.gradient[i], 1),
                        "d {d}: {got:?}"
                    );
                }
                for i in 0..3 {
                    assert!(close(got.hessian[i], want.hessian[i], 2), "d {d}: {got:?}");
                }
                let value = evaluate(&t, d, &c, p, Order::Value).value;
                assert!(close(value, want.value, 0));
            }
        }
    }

    #[test]
    fn values_and_coefficients_convert_both_ways() {
        let t = tri();
        for d in 1..=8 {
            let interp = DomainPointInterpolation::new(d);
            let values: Vec<f64> = (0..coefficient_count(d))
                .map(|i| (i as f64).sin())
                .collect();
            let c = interp.coefficients(&values);
            let back = values_at_domain_points(&t, d, &c);
            for (a, b) in values.iter().zip(&back) {
                assert!((a - b).abs() < 1e-11, "d {d}: {a} {b}");
            }
        }
    }

    #[test]
    fn degree_raising_keeps_the_polynomial() {
        let t = tri();
        let d = 4;
        let values: Vec<f64> = t.domain_points(d).iter().map(|&p| f(p).value).collect();
        let c = DomainPointInterpolation::new(d).coefficients(&values);
        let raised = raise_degree(d, &c);
        assert_eq!(raised.len(), coefficient_count(d + 1));
        for p in [Point::new(1.0, 0.5), Point::new(3.0, 3.0)] {
            let a = evaluate(&t, d, &c, p, Order::Value).value;
            let b = evaluate(&t, d + 1, &raised, p, Order::Value).value;
            assert!((a - b).abs() < 1e-12 * (1.0 + a.abs()), "{a} {b}");
        }
    }

    #[test]
    fn the_value_path_equals_the_sum_of_the_bernstein_basis_at_every_degree() {
        // Values take an unrolled de Casteljau per degree; check each against the basis sum
        // (an independent formula), inside and outside the triangle.
        let t = tri();
        for d in 0..=MAX_DEGREE {
            let c: Vec<f64> = (0..coefficient_count(d))
                .map(|i| (1.7 * i as f64 + 0.3).cos())
                .collect();
            for p in [
                Point::new(1.0, 0.5),
                Point::new(3.0, 3.0),
                Point::new(-2.0, 7.0),
            ] {
                let b = t.barycentric(p);
                let want: f64 = multi_indices(d)
                    .zip(&c)
                    .map(|(m, c)| c * bernstein(d, m, b))
                    .sum();
                let scale: f64 = multi_indices(d)
                    .zip(&c)
                    .map(|(m, c)| (c * bernstein(d, m, b)).abs())
                    .sum();
                let got = evaluate(&t, d, &c, p, Order::Value).value;
                assert!(
                    (got - want).abs() <= 1e-13 * scale.max(1.0),
                    "d {d} at {p:?}: {got} {want}"
                );
                let general = evaluate(&t, d, &c, p, Order::Gradient).value;
                assert!(
                    (got - general).abs() <= 1e-13 * scale.max(1.0),
                    "d {d}: {got} {general}"
                );
            }
        }
    }

    #[test]
    fn bernstein_basis_is_a_partition_of_unity() {
        let b = [0.2, -0.5, 1.3];
        for d in 0..=MAX_DEGREE {
            let sum: f64 = multi_indices(d).map(|m| bernstein(d, m, b)).sum();
            assert!((sum - 1.0).abs() < 1e-12, "{d}: {sum}");
        }
    }

    #[test]
    fn linear_polynomials_are_their_vertex_values() {
        let t = tri();
        // p = 2 b1 - b2 + 5 b3 has coefficients (2, -1, 5) in degree 1.
        let c = [2.0, -1.0, 5.0];
        for p in [t.v[0], t.v[1], t.v[2]] {
            let b = t.barycentric(p);
            let want = 2.0 * b[0] - b[1] + 5.0 * b[2];
            assert!((evaluate(&t, 1, &c, p, Order::Gradient).value - want).abs() < 1e-14);
        }
    }
}
