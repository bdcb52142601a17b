//! The polynomial basis the rule works in: products of normalised Legendre polynomials of the
//! coordinates scaled to the bounding box, `phi_ij(x, y) = sqrt((2i + 1)(2j + 1)) P_i(u) P_j(v)`
//! with `u = (x - cx) / hx`, `v = (y - cy) / hy` in `[-1, 1]`, total degree `i + j <= n`.
//!
//! On the box the `phi_ij` are orthogonal with squared norm `hx hy`, so their Vandermonde
//! matrix at points spread over a domain that fills much of its box is well conditioned
//! (raw monomials of degree 20 are not). `|phi_ij| <= sqrt((2i + 1)(2j + 1)) <= n + 1` on the box.

use rs_spline::{BoundingBox, Point};

/// `(n + 1)(n + 2) / 2`: the dimension of the polynomials of total degree `<= n` in two
/// variables.
///
/// # Examples
///
/// ```
/// assert_eq!(rs_cubature::dim_polynomials(20), 231);
/// ```
pub fn dim_polynomials(degree: usize) -> usize {
    (degree + 1) * (degree + 2) / 2
}

/// Index of the exponent pair `(a, b)` (of `x^a y^b`, or of `phi_ab`) in graded order: degree
/// 0; then `(1, 0), (0, 1)`; then `(2, 0), (1, 1), (0, 2)`; ...
pub(crate) fn graded_index(a: usize, b: usize) -> usize {
    let k = a + b;
    k * (k + 1) / 2 + b
}

/// The scaled product Legendre basis of total degree `<= degree` on a box.
#[derive(Clone, Debug)]
pub(crate) struct LegendreBasis {
    degree: usize,
    centre: Point,
    /// Half the box's width and height (a degenerate side is given a positive size).
    half: Point,
    /// `sqrt(2k + 1)` for `k = 0 ..= degree`.
    norms: Vec<f64>,
}

impl LegendreBasis {
    /// The basis on `bbox` (a side of zero length is treated as of length 1, so that the map
    /// stays finite; such a domain has no area and no rule).
    pub(crate) fn new(degree: usize, bbox: BoundingBox) -> Self {
        let side = |s: f64| if s > 0.0 { 0.5 * s } else { 0.5 };
        Self {
            degree,
            centre: Point::new(
                0.5 * (bbox.min.x + bbox.max.x),
                0.5 * (bbox.min.y + bbox.max.y),
            ),
            half: Point::new(side(bbox.width()), side(bbox.height())),
            norms: (0..=degree).map(|k| ((2 * k + 1) as f64).sqrt()).collect(),
        }
    }

    /// The total degree `n`.
    pub(crate) fn degree(&self) -> usize {
        self.degree
    }

    /// The number of basis functions.
    pub(crate) fn len(&self) -> usize {
        dim_polynomials(self.degree)
    }

    /// The length of the scratch space [`LegendreBasis::values_into`] and
    /// [`LegendreBasis::x_antiderivatives_into`] need.
    pub(crate) fn scratch_len(&self) -> usize {
        2 * (self.degree + 2)
    }

    /// Writes `phi_ij(p)` in graded order into `out` (`len()` values); `scratch` holds at
    /// least `2 (degree + 2)` values.
    pub(crate) fn values_into(&self, p: Point, scratch: &mut [f64], out: &mut [f64]) {
        let n = self.degree;
        let (pu, pv) = scratch.split_at_mut(n + 2);
        self.x_factors_into(p.x, &mut pu[..=n]);
        self.y_factors_into(p.y, &mut pv[..=n]);
        graded_products(n, pu, pv, |k, value| out[k] = value);
    }

    /// Writes the factors in `x` of the basis, `sqrt(2i + 1) P_i(u)` for `i = 0 ..= degree`
    /// (`u` the scaled abscissa), into `out` (`degree + 1` values): `phi_ij(p)` is the
    /// product of the `i`-th factor in `x` and the `j`-th in `y`.
    pub(crate) fn x_factors_into(&self, x: f64, out: &mut [f64]) {
        legendre_into((x - self.centre.x) / self.half.x, out);
        for (pi, ni) in out.iter_mut().zip(&self.norms) {
            *pi *= ni;
        }
    }

    /// The factors in `y`, `sqrt(2j + 1) P_j(v)`, as [`LegendreBasis::x_factors_into`].
    pub(crate) fn y_factors_into(&self, y: f64, out: &mut [f64]) {
        legendre_into((y - self.centre.y) / self.half.y, out);
        for (pj, nj) in out.iter_mut().zip(&self.norms) {
            *pj *= nj;
        }
    }

    /// Writes `F_ij(p) = integral phi_ij dx` (an antiderivative in `x`, for Green's theorem
    /// `integral phi dA = oint F dy`) in graded order into `out`; returns `max |F_ij(p)|`.
    /// With `Q_i(u) = integral P_i du = (P_{i+1}(u) - P_{i-1}(u)) / (2i + 1)` (and
    /// `Q_0 = u`), `F_ij = hx sqrt((2i + 1)(2j + 1)) Q_i(u) P_j(v)`. `scratch` holds at least
    /// `2 (degree + 2)` values.
    pub(crate) fn x_antiderivatives_into(
        &self,
        p: Point,
        scratch: &mut [f64],
        out: &mut [f64],
    ) -> f64 {
        let n = self.degree;
        let u = (p.x - self.centre.x) / self.half.x;
        let (pu, pv) = scratch.split_at_mut(n + 2);
        legendre_into(u, &mut pu[..n + 2]);
        self.y_factors_into(p.y, &mut pv[..=n]);
        // Q_i in place, upwards, keeping P_{i-1} aside (its slot already holds Q_{i-1}).
        let mut previous = pu[0];
        pu[0] = self.half.x * u;
        for i in 1..=n {
            let current = pu[i];
            pu[i] = self.half.x * self.norms[i] * (pu[i + 1] - previous) / (2 * i + 1) as f64;
            previous = current;
        }
        let mut largest = 0.0f64;
        graded_products(n, pu, pv, |k, f| {
            largest = largest.max(f.abs());
            out[k] = f;
        });
        largest
    }
}

/// Calls `each(k, a[i] b[j])` for every pair `i + j <= n` in graded order, `k` its index
/// ([`graded_index`]): a factor in `x` times one in `y`, as the basis's values and their
/// antiderivatives and sums are.
#[inline(always)]
pub(crate) fn graded_products(n: usize, a: &[f64], b: &[f64], mut each: impl FnMut(usize, f64)) {
    let mut at = 0;
    for k in 0..=n {
        for j in 0..=k {
            each(at, a[k - j] * b[j]);
            at += 1;
        }
    }
}

/// `P_0(t) .. P_{len-1}(t)` by the three-term recurrence `(k + 1) P_{k+1} = (2k + 1) t P_k - k P_{k-1}`.
fn legendre_into(t: f64, out: &mut [f64]) {
    if let Some(first) = out.first_mut() {
        *first = 1.0;
    }
    if out.len() > 1 {
        out[1] = t;
    }
    for k in 1..out.len().saturating_sub(1) {
        out[k + 1] = ((2 * k + 1) as f64 * t * out[k] - k as f64 * out[k - 1]) / (k + 1) as f64;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn graded_order_counts_every_pair_once() {
        let n = 7;
        let mut seen = vec![false; dim_polynomials(n)];
        for a in 0..=n {
            for b in 0..=n - a {
                let i = graded_index(a, b);
                assert!(!seen[i]);
                seen[i] = true;
            }
        }
        assert!(seen.iter().all(|&s| s));
        assert_eq!(graded_index(1, 0), 1);
        assert_eq!(graded_index(0, 1), 2);
        assert_eq!(graded_index(2, 0), 3);
    }

    #[test]
    fn legendre_matches_closed_forms() {
        let mut p = [0.0; 4];
        let t = 0.3;
        legendre_into(t, &mut p);
        assert!((p[2] - 0.5 * (3.0 * t * t - 1.0)).abs() < 1e-15);
        assert!((p[3] - 0.5 * (5.0 * t * t * t - 3.0 * t)).abs() < 1e-15);
    }

    #[test]
    fn antiderivatives_differentiate_back_to_the_basis() {
        let b = BoundingBox {
            min: Point::new(-1.0, 2.0),
            max: Point::new(3.0, 3.0),
        };
        let basis = LegendreBasis::new(6, b);
        let (mut s, mut f0, mut f1, mut phi) =
            (vec![0.0; 16], vec![0.0; 28], vec![0.0; 28], vec![0.0; 28]);
        let (p, h) = (Point::new(0.7, 2.4), 1e-5);
        basis.x_antiderivatives_into(Point::new(p.x + h, p.y), &mut s, &mut f1);
        basis.x_antiderivatives_into(Point::new(p.x - h, p.y), &mut s, &mut f0);
        basis.values_into(p, &mut s, &mut phi);
        for k in 0..28 {
            let d = (f1[k] - f0[k]) / (2.0 * h);
            assert!((d - phi[k]).abs() < 1e-8, "{k}: {d} vs {}", phi[k]);
        }
    }
}
