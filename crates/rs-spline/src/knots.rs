//! Validated knot vectors and B-spline basis functions.

use crate::SplineError;
use crate::limits::MAX_DEGREE;

/// The numbers [`KnotVector::with_basis_derivatives`] keeps on the stack: enough for degree 7
/// with derivatives up to order 2.
const SMALL_BASIS: usize = 120;

/// The runs of equal knots of a non-decreasing `knots` whose value lies strictly inside
/// `(start, end)`: (index of the first copy, value, multiplicity), ascending.
fn interior_runs(
    knots: &[f64],
    start: f64,
    end: f64,
) -> impl Iterator<Item = (usize, f64, usize)> + '_ {
    let mut i = 0;
    std::iter::from_fn(move || {
        while i < knots.len() {
            let first = i;
            let value = knots[i];
            let mult = knots[i..].iter().take_while(|&&k| k == value).count();
            i += mult;
            if value > start && value < end {
                return Some((first, value, mult));
            }
        }
        None
    })
}

/// A validated knot vector `u_0 <= u_1 <= ... <= u_m` for a B-spline of degree `p` with
/// `n = m - p` control points.
///
/// Invariants (checked by [`KnotVector::new`]): `1 <= p <= MAX_DEGREE`, `m + 1 = n + p + 1`,
/// every knot finite with a finite range `u_m - u_0`, non-decreasing, a non-empty parameter
/// domain `[u_p, u_n]`, and no knot strictly inside the domain with multiplicity above `p + 1`.
/// Clamped (end knots repeated `p + 1` times) and unclamped vectors are both accepted; the curve
/// is defined on the domain `[u_p, u_n]` either way. An interior knot of multiplicity `p + 1`
/// is a break: the Bezier pieces on either side have independent control points (the inRS
/// Matlab package writes polygons this way), and the curve is continuous there only if those
/// points coincide (see [`crate::NurbsCurve::breaks`]).
///
/// # Examples
///
/// ```
/// use rs_spline::KnotVector;
/// let k = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0], 2, 4).unwrap();
/// assert_eq!(k.domain(), (0.0, 1.0));
/// assert_eq!(k.span(0.7), 3);
/// assert!(KnotVector::new(vec![0.0, 1.0, 0.5, 1.0], 1, 2).is_err());
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct KnotVector {
    knots: Vec<f64>,
    degree: usize,
}

impl KnotVector {
    /// Validates `knots` for a curve of `degree` with `n_control` control points.
    ///
    /// # Errors
    /// [`SplineError::ZeroDegree`], [`SplineError::TooFewControlPoints`],
    /// [`SplineError::WrongKnotCount`], [`SplineError::NonFiniteKnot`],
    /// [`SplineError::DecreasingKnots`], [`SplineError::EmptyDomain`],
    /// [`SplineError::InteriorMultiplicity`], [`SplineError::NonFiniteSpan`],
    /// [`SplineError::LimitExceeded`] (degree above [`MAX_DEGREE`]).
    pub fn new(knots: Vec<f64>, degree: usize, n_control: usize) -> Result<Self, SplineError> {
        if degree == 0 {
            return Err(SplineError::ZeroDegree);
        }
        if degree > MAX_DEGREE {
            return Err(SplineError::LimitExceeded {
                what: "degree",
                value: degree as f64,
                limit: MAX_DEGREE as f64,
            });
        }
        if n_control < degree + 1 {
            return Err(SplineError::TooFewControlPoints {
                degree,
                needed: degree + 1,
                got: n_control,
            });
        }
        let expected = n_control + degree + 1;
        if knots.len() != expected {
            return Err(SplineError::WrongKnotCount {
                expected,
                got: knots.len(),
            });
        }
        if let Some(index) = knots.iter().position(|k| !k.is_finite()) {
            return Err(SplineError::NonFiniteKnot {
                index,
                value: knots[index],
            });
        }
        if let Some(i) = (1..knots.len()).find(|&i| knots[i] < knots[i - 1]) {
            return Err(SplineError::DecreasingKnots {
                index: i,
                previous: knots[i - 1],
                value: knots[i],
            });
        }
        let (first, last) = (knots[0], knots[knots.len() - 1]);
        if !(last - first).is_finite() {
            return Err(SplineError::NonFiniteSpan {
                start: first,
                end: last,
            });
        }
        let (start, end) = (knots[degree], knots[n_control]);
        if start >= end {
            return Err(SplineError::EmptyDomain { start, end });
        }
        if let Some((_, value, multiplicity)) =
            interior_runs(&knots, start, end).find(|r| r.2 > degree + 1)
        {
            return Err(SplineError::InteriorMultiplicity {
                value,
                multiplicity,
                degree,
            });
        }
        Ok(Self { knots, degree })
    }

    /// The knot vector of a single Bezier piece of `degree` on `[0, 1]`:
    /// `p + 1` zeros then `p + 1` ones.
    pub fn bezier(degree: usize) -> Self {
        let mut knots = vec![0.0; degree + 1];
        knots.extend(std::iter::repeat_n(1.0, degree + 1));
        Self { knots, degree }
    }

    /// The clamped uniform knot vector on `[0, 1]` for `n_control` control points.
    ///
    /// # Errors
    /// As [`KnotVector::new`].
    pub fn uniform_clamped(degree: usize, n_control: usize) -> Result<Self, SplineError> {
        let spans = n_control.saturating_sub(degree).max(1);
        let mut knots = vec![0.0; degree + 1];
        knots.extend((1..spans).map(|i| i as f64 / spans as f64));
        knots.extend(std::iter::repeat_n(1.0, degree + 1));
        Self::new(knots, degree, n_control)
    }

    /// Builds without validation; callers guarantee the invariants.
    pub(crate) fn from_raw(knots: Vec<f64>, degree: usize) -> Self {
        Self { knots, degree }
    }

    /// The knots `u_0 .. u_m`.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The degree `p` this vector was validated for.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Number of control points `n = m + 1 - (p + 1)`.
    pub fn n_control(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The parameter domain `(u_p, u_n)`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.n_control()])
    }

    /// Number of knots equal to `u`.
    pub fn multiplicity(&self, u: f64) -> usize {
        self.knots.iter().filter(|&&k| k == u).count()
    }

    /// The span index `k` with `u_k <= u < u_{k+1}` and `p <= k < n`, for `u` clamped to the
    /// domain; at the domain end the last non-empty span is returned.
    pub fn span(&self, u: f64) -> usize {
        let p = self.degree;
        let n = self.n_control();
        let (start, end) = self.domain();
        if u >= end {
            // Last non-empty span ending at u_n.
            let mut k = n - 1;
            while k > p && self.knots[k] == end {
                k -= 1;
            }
            return k;
        }
        if u <= start {
            let mut k = p;
            while k + 1 < n && self.knots[k + 1] == start {
                k += 1;
            }
            return k;
        }
        // Binary search for u_k <= u < u_{k+1} in [p, n).
        let (mut lo, mut hi) = (p, n);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if u < self.knots[mid] {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        lo
    }

    /// The distinct knot values strictly inside the domain, ascending.
    pub fn interior_breaks(&self) -> Vec<f64> {
        self.interior_runs().map(|r| r.1).collect()
    }

    /// Each distinct knot value strictly inside the domain, ascending, as (index of its first
    /// copy, value, multiplicity).
    pub(crate) fn interior_runs(&self) -> impl Iterator<Item = (usize, f64, usize)> + '_ {
        let (start, end) = self.domain();
        interior_runs(&self.knots, start, end)
    }

    /// Values and derivatives up to order `nd` of the `p + 1` basis functions that are non-zero
    /// on span `k` at `u` (Piegl and Tiller, The NURBS Book, algorithm A2.3).
    ///
    /// `out[d][j]` is the `d`-th derivative of `N_{k-p+j, p}(u)`.
    pub fn basis_derivatives(&self, k: usize, u: f64, nd: usize) -> Vec<Vec<f64>> {
        let w = self.degree + 1;
        self.with_basis_derivatives(k, u, nd, |table| {
            table.chunks_exact(w).map(<[f64]>::to_vec).collect()
        })
    }

    /// Calls `f` with [`KnotVector::basis_derivatives`] as one flat table (row `d` at
    /// `d (p + 1)`), worked out in storage on the stack up to degree 7 and degree-2 derivatives
    /// (a table of vectors cost a dozen allocations per curve evaluation: most of the time of
    /// an arc-length table).
    pub(crate) fn with_basis_derivatives<R>(
        &self,
        k: usize,
        u: f64,
        nd: usize,
        f: impl FnOnce(&[f64]) -> R,
    ) -> R {
        let w = self.degree + 1;
        let need = (w + 4) * w + (nd + 1) * w;
        if need <= SMALL_BASIS {
            let mut store = [0.0; SMALL_BASIS];
            f(self.basis_derivatives_in(k, u, nd, &mut store[..need]))
        } else {
            let mut store = vec![0.0; need];
            f(self.basis_derivatives_in(k, u, nd, &mut store))
        }
    }

    /// Algorithm A2.3 in `store` (zeros, `(p + 5) (p + 1) + (nd + 1) (p + 1)` numbers); returns
    /// the part that holds the table.
    fn basis_derivatives_in<'s>(
        &self,
        k: usize,
        u: f64,
        nd: usize,
        store: &'s mut [f64],
    ) -> &'s [f64] {
        let p = self.degree;
        let w = p + 1;
        let u_k = &self.knots;
        // ndu[j][r] at j * w + r: basis values (upper triangle) and knot differences (lower);
        // the two alternating rows of coefficients a[s][j] at s * w + j.
        let (ndu, rest) = store.split_at_mut(w * w);
        let (left, rest) = rest.split_at_mut(w);
        let (right, rest) = rest.split_at_mut(w);
        let (a, ders) = rest.split_at_mut(2 * w);
        ndu[0] = 1.0;
        for j in 1..=p {
            left[j] = u - u_k[k + 1 - j];
            right[j] = u_k[k + j] - u;
            let mut saved = 0.0;
            for r in 0..j {
                ndu[j * w + r] = right[r + 1] + left[j - r];
                let temp = ndu[r * w + j - 1] / ndu[j * w + r];
                ndu[r * w + j] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            ndu[j * w + j] = saved;
        }
        for j in 0..=p {
            ders[j] = ndu[j * w + p];
        }
        for r in 0..=p as isize {
            let (mut s1, mut s2) = (0usize, w);
            a[0] = 1.0;
            for kk in 1..=nd.min(p) as isize {
                let mut d = 0.0;
                let rk = r - kk;
                let pk = p as isize - kk;
                let below = (pk + 1) as usize * w;
                if r >= kk {
                    a[s2] = a[s1] / ndu[below + rk as usize];
                    d = a[s2] * ndu[rk as usize * w + pk as usize];
                }
                let j1 = if rk >= -1 { 1 } else { -rk };
                let j2 = if r - 1 <= pk { kk - 1 } else { p as isize - r };
                for j in j1..=j2 {
                    let (ju, rkj) = (j as usize, (rk + j) as usize);
                    a[s2 + ju] = (a[s1 + ju] - a[s1 + ju - 1]) / ndu[below + rkj];
                    d += a[s2 + ju] * ndu[rkj * w + pk as usize];
                }
                if r <= pk {
                    a[s2 + kk as usize] = -a[s1 + (kk - 1) as usize] / ndu[below + r as usize];
                    d += a[s2 + kk as usize] * ndu[r as usize * w + pk as usize];
                }
                ders[kk as usize * w + r as usize] = d;
                std::mem::swap(&mut s1, &mut s2);
            }
        }
        let mut factor = p as f64;
        for (kk, row) in ders.chunks_exact_mut(w).enumerate().skip(1) {
            if kk > p {
                row.iter_mut().for_each(|v| *v = 0.0);
                continue;
            }
            row.iter_mut().for_each(|v| *v *= factor);
            factor *= (p - kk) as f64;
        }
        ders
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn validation_errors() {
        assert_eq!(
            KnotVector::new(vec![0.0; 4], 0, 2),
            Err(SplineError::ZeroDegree)
        );
        assert!(matches!(
            KnotVector::new(vec![0.0, 0.0, 1.0, 1.0], 1, 3),
            Err(SplineError::WrongKnotCount {
                expected: 5,
                got: 4
            })
        ));
        assert!(matches!(
            KnotVector::new(vec![0.0, 0.0, f64::NAN, 1.0, 1.0], 1, 3),
            Err(SplineError::NonFiniteKnot { index: 2, .. })
        ));
        assert!(matches!(
            KnotVector::new(vec![0.0, 0.0, 2.0, 1.0, 1.0], 1, 3),
            Err(SplineError::DecreasingKnots { index: 3, .. })
        ));
        assert!(matches!(
            KnotVector::new(vec![0.0, 1.0, 1.0, 1.0], 1, 2),
            Err(SplineError::EmptyDomain { .. })
        ));
        assert!(KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0], 2, 6).is_ok());
        assert!(matches!(
            KnotVector::new(vec![0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0], 1, 5),
            Err(SplineError::InteriorMultiplicity {
                multiplicity: 3,
                ..
            })
        ));
        assert!(matches!(
            KnotVector::new(vec![-1e308, 0.0, 1.0, 1e308], 1, 2),
            Err(SplineError::NonFiniteSpan { .. })
        ));
        assert!(matches!(
            KnotVector::new(vec![0.0; 68], 33, 34),
            Err(SplineError::LimitExceeded { what: "degree", .. })
        ));
        assert!(matches!(
            KnotVector::new(vec![0.0, 1.0], 1, 1),
            Err(SplineError::TooFewControlPoints { .. })
        ));
    }

    #[test]
    fn spans() {
        let k = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0], 2, 5).unwrap();
        assert_eq!(k.span(0.0), 2);
        assert_eq!(k.span(0.25), 2);
        assert_eq!(k.span(0.5), 4);
        assert_eq!(k.span(1.0), 4);
        assert_eq!(k.interior_breaks(), vec![0.5]);
    }

    #[test]
    fn basis_is_a_partition_of_unity_with_zero_sum_derivatives() {
        let k = KnotVector::new(vec![-1.0, -0.5, 0.0, 0.3, 0.3, 0.9, 1.4, 2.0, 2.5], 3, 5).unwrap();
        let (a, b) = k.domain();
        for i in 0..=20 {
            let u = a + (b - a) * i as f64 / 20.0;
            let d = k.basis_derivatives(k.span(u), u, 2);
            assert_relative_eq!(d[0].iter().sum::<f64>(), 1.0, epsilon = 1e-14);
            assert!(d[0].iter().all(|&v| v >= -1e-15));
            assert!(d[1].iter().sum::<f64>().abs() < 1e-11);
            assert!(d[2].iter().sum::<f64>().abs() < 1e-9);
        }
    }

    /// The table worked out on the stack (degree up to 7) and on the heap (above) alike: a
    /// partition of unity whose first derivatives match central differences of the values.
    #[test]
    fn basis_derivatives_of_every_degree_match_differences_of_the_values() {
        for p in [1, 2, 3, 7, 8, 12] {
            let k = KnotVector::uniform_clamped(p, p + 4).unwrap();
            let (a, b) = k.domain();
            for i in 1..20 {
                let u = a + (b - a) * (i as f64 + 0.3) / 20.0;
                let span = k.span(u);
                let d = k.basis_derivatives(span, u, 2);
                assert_eq!((d.len(), d[0].len()), (3, p + 1));
                assert_relative_eq!(d[0].iter().sum::<f64>(), 1.0, epsilon = 1e-13);
                let h = 1e-6;
                let (lo, hi) = (
                    k.basis_derivatives(span, u - h, 0),
                    k.basis_derivatives(span, u + h, 0),
                );
                for j in 0..=p {
                    let diff = (hi[0][j] - lo[0][j]) / (2.0 * h);
                    assert!(
                        (d[1][j] - diff).abs() < 1e-6 * (1.0 + d[1][j].abs()),
                        "p {p} u {u} j {j}"
                    );
                }
            }
        }
    }

    #[test]
    fn uniform_clamped() {
        let k = KnotVector::uniform_clamped(2, 5).unwrap();
        assert_eq!(
            k.knots(),
            &[0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0]
        );
        assert_eq!(
            KnotVector::bezier(3).knots(),
            &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]
        );
    }
}
