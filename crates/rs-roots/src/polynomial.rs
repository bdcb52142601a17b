//! Real polynomials in the power basis.

use std::ops::{Add, Mul, Neg, Sub};

/// A real polynomial `p(t) = c[0] + c[1] t + ... + c[n] t^n` in the power basis.
///
/// Coefficients are stored in **ascending** order (the crate-wide convention). Exact trailing
/// zeros are trimmed on construction, so `coeffs().last()` is non-zero unless the polynomial is
/// the zero polynomial, whose coefficient slice is empty.
///
/// # Examples
///
/// ```
/// use rs_roots::Polynomial;
/// // p(t) = (t - 1)(t - 2) = 2 - 3t + t^2
/// let p = Polynomial::from_roots(&[1.0, 2.0]);
/// assert_eq!(p.coeffs(), &[2.0, -3.0, 1.0]);
/// assert_eq!(p.eval(3.0), 2.0);
/// assert_eq!(p.derivative().coeffs(), &[-3.0, 2.0]);
/// ```
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Polynomial {
    coeffs: Vec<f64>,
}

impl Polynomial {
    /// Builds a polynomial from ascending coefficients, trimming exact trailing zeros.
    pub fn new(coeffs: impl Into<Vec<f64>>) -> Self {
        let mut coeffs = coeffs.into();
        while coeffs.last() == Some(&0.0) {
            coeffs.pop();
        }
        Self { coeffs }
    }

    /// The zero polynomial.
    pub fn zero() -> Self {
        Self { coeffs: Vec::new() }
    }

    /// The constant polynomial `c`.
    pub fn constant(c: f64) -> Self {
        Self::new(vec![c])
    }

    /// The monic polynomial `prod_i (t - r_i)` with the given roots (repeat a root for multiplicity).
    pub fn from_roots(roots: &[f64]) -> Self {
        let mut p = Self::constant(1.0);
        for &r in roots {
            p = &p * &Self::new(vec![-r, 1.0]);
        }
        p
    }

    /// Ascending coefficients `c[0], c[1], ...` (empty for the zero polynomial).
    pub fn coeffs(&self) -> &[f64] {
        &self.coeffs
    }

    /// Degree, or `None` for the zero polynomial.
    pub fn degree(&self) -> Option<usize> {
        self.coeffs.len().checked_sub(1)
    }

    /// True for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.coeffs.is_empty()
    }

    /// True if every coefficient is finite.
    pub fn is_finite(&self) -> bool {
        self.coeffs.iter().all(|c| c.is_finite())
    }

    /// Evaluates `p(t)` by Horner's rule.
    pub fn eval(&self, t: f64) -> f64 {
        self.coeffs.iter().rev().fold(0.0, |acc, &c| acc * t + c)
    }

    /// Evaluates `(p(t), p'(t))` in one Horner pass.
    pub fn eval_with_derivative(&self, t: f64) -> (f64, f64) {
        let mut p = 0.0;
        let mut dp = 0.0;
        for &c in self.coeffs.iter().rev() {
            dp = dp * t + p;
            p = p * t + c;
        }
        (p, dp)
    }

    /// The magnitude `sum_i |c_i| |t|^i`, which bounds the rounding error of Horner's rule:
    /// the computed `p(t)` differs from the exact value by at most about
    /// `2 n eps * magnitude(t)` for degree `n`.
    pub fn magnitude(&self, t: f64) -> f64 {
        let at = t.abs();
        self.coeffs
            .iter()
            .rev()
            .fold(0.0, |acc, &c| acc * at + c.abs())
    }

    /// A bound on the rounding error of [`Polynomial::eval`] at `t`:
    /// `4 (n + 1) eps sum_i |c_i| |t|^i`. A computed `|p(t)|` below it is numerically zero.
    pub fn eval_error_bound(&self, t: f64) -> f64 {
        4.0 * (self.coeffs.len() as f64 + 1.0) * f64::EPSILON * self.magnitude(t)
    }

    /// The derivative `p'(t)`.
    pub fn derivative(&self) -> Self {
        Self::new(
            self.coeffs
                .iter()
                .enumerate()
                .skip(1)
                .map(|(i, &c)| c * i as f64)
                .collect::<Vec<_>>(),
        )
    }

    /// The Taylor shift `q(s) = p(s + h)`, computed by repeated synthetic division (O(n^2)).
    pub fn taylor_shift(&self, h: f64) -> Self {
        let mut c = self.coeffs.clone();
        let n = c.len();
        for i in 0..n {
            for j in (i..n.saturating_sub(1)).rev() {
                c[j] += h * c[j + 1];
            }
        }
        Self::new(c)
    }

    /// The affine reparametrisation `q(s) = p(a + h s)`, mapping `s in [0, 1]` to
    /// `t in [a, a + h]`.
    pub fn compose_affine(&self, a: f64, h: f64) -> Self {
        let shifted = self.taylor_shift(a);
        let mut scale = 1.0;
        let coeffs: Vec<f64> = shifted
            .coeffs
            .iter()
            .map(|&c| {
                let v = c * scale;
                scale *= h;
                v
            })
            .collect();
        Self::new(coeffs)
    }

    /// Multiplies every coefficient by `s`.
    pub fn scale(&self, s: f64) -> Self {
        Self::new(self.coeffs.iter().map(|&c| c * s).collect::<Vec<_>>())
    }

    /// Drops leading coefficients that cannot change any value on `|t| <= radius` by more than
    /// rounding: `|c_n| r^n <= eps sum_{i<n} |c_i| r^i` with `r = max(radius, 1)`.
    ///
    /// Polynomials converted from other bases often carry a leading coefficient that is pure
    /// cancellation noise; removing it keeps companion matrices well scaled.
    pub fn trim_negligible(&self, radius: f64) -> Self {
        let r = radius.abs().max(1.0);
        let mut c = self.coeffs.clone();
        while c.len() > 1 {
            let n = c.len() - 1;
            let lower = c[..n].iter().rev().fold(0.0, |acc, &x| acc * r + x.abs());
            let lead = c[n].abs() * r.powi(n as i32);
            if lead <= f64::EPSILON * lower {
                c.pop();
            } else {
                break;
            }
        }
        Self::new(c)
    }
}

impl Add for &Polynomial {
    type Output = Polynomial;
    fn add(self, rhs: &Polynomial) -> Polynomial {
        let n = self.coeffs.len().max(rhs.coeffs.len());
        let c: Vec<f64> = (0..n)
            .map(|i| self.coeffs.get(i).unwrap_or(&0.0) + rhs.coeffs.get(i).unwrap_or(&0.0))
            .collect();
        Polynomial::new(c)
    }
}

impl Sub for &Polynomial {
    type Output = Polynomial;
    fn sub(self, rhs: &Polynomial) -> Polynomial {
        self + &(-rhs)
    }
}

impl Mul for &Polynomial {
    type Output = Polynomial;
    fn mul(self, rhs: &Polynomial) -> Polynomial {
        if self.is_zero() || rhs.is_zero() {
            return Polynomial::zero();
        }
        let mut c = vec![0.0; self.coeffs.len() + rhs.coeffs.len() - 1];
        for (i, &a) in self.coeffs.iter().enumerate() {
            for (j, &b) in rhs.coeffs.iter().enumerate() {
                c[i + j] += a * b;
            }
        }
        Polynomial::new(c)
    }
}

impl Neg for &Polynomial {
    type Output = Polynomial;
    fn neg(self) -> Polynomial {
        self.scale(-1.0)
    }
}

impl Add for Polynomial {
    type Output = Polynomial;
    fn add(self, rhs: Polynomial) -> Polynomial {
        &self + &rhs
    }
}

impl Sub for Polynomial {
    type Output = Polynomial;
    fn sub(self, rhs: Polynomial) -> Polynomial {
        &self - &rhs
    }
}

impl Mul for Polynomial {
    type Output = Polynomial;
    fn mul(self, rhs: Polynomial) -> Polynomial {
        &self * &rhs
    }
}

impl Neg for Polynomial {
    type Output = Polynomial;
    fn neg(self) -> Polynomial {
        -&self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn trims_trailing_zeros() {
        let p = Polynomial::new(vec![1.0, 2.0, 0.0, 0.0]);
        assert_eq!(p.degree(), Some(1));
        assert_eq!(Polynomial::new(vec![0.0]).degree(), None);
        assert!(Polynomial::new(vec![0.0, 0.0]).is_zero());
    }

    #[test]
    fn arithmetic_matches_pointwise() {
        let p = Polynomial::new(vec![1.0, -2.0, 3.0]);
        let q = Polynomial::new(vec![0.5, 4.0, 0.0, -1.0]);
        for &t in &[-2.0, -0.3, 0.0, 0.7, 1.9] {
            assert_relative_eq!((&p + &q).eval(t), p.eval(t) + q.eval(t), epsilon = 1e-12);
            assert_relative_eq!((&p - &q).eval(t), p.eval(t) - q.eval(t), epsilon = 1e-12);
            assert_relative_eq!((&p * &q).eval(t), p.eval(t) * q.eval(t), epsilon = 1e-12);
        }
        assert!((&p - &p).is_zero());
    }

    #[test]
    fn derivative_and_combined_eval() {
        let p = Polynomial::new(vec![1.0, -2.0, 3.0, 0.25]);
        let d = p.derivative();
        assert_eq!(d.coeffs(), &[-2.0, 6.0, 0.75]);
        let (v, dv) = p.eval_with_derivative(1.3);
        assert_relative_eq!(v, p.eval(1.3), epsilon = 1e-14);
        assert_relative_eq!(dv, d.eval(1.3), epsilon = 1e-14);
        assert!(Polynomial::constant(3.0).derivative().is_zero());
    }

    #[test]
    fn taylor_shift_and_affine_composition() {
        let p = Polynomial::new(vec![0.3, -1.0, 2.0, 0.5, -0.125]);
        let q = p.taylor_shift(0.75);
        let r = p.compose_affine(-1.0, 2.5);
        for &s in &[-1.0, 0.0, 0.2, 0.9, 1.4] {
            assert_relative_eq!(q.eval(s), p.eval(s + 0.75), epsilon = 1e-12);
            assert_relative_eq!(r.eval(s), p.eval(-1.0 + 2.5 * s), epsilon = 1e-12);
        }
    }

    #[test]
    fn from_roots_vanishes_at_roots() {
        let p = Polynomial::from_roots(&[0.1, -2.0, 3.5]);
        assert_eq!(p.degree(), Some(3));
        for r in [0.1, -2.0, 3.5] {
            assert!(p.eval(r).abs() <= p.eval_error_bound(r));
        }
    }

    #[test]
    fn trim_negligible_drops_only_noise() {
        let p = Polynomial::new(vec![1.0, -3.0, 2.0, 1e-30]);
        assert_eq!(p.trim_negligible(1.0).degree(), Some(2));
        let q = Polynomial::new(vec![1.0, -3.0, 2.0, 1e-10]);
        assert_eq!(q.trim_negligible(1.0).degree(), Some(3));
    }
}
