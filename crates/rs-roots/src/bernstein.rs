//! Polynomials in the Bernstein basis on `[0, 1]`.

use std::ops::{Add, Mul, Sub};

use crate::Polynomial;

/// A polynomial `b(s) = sum_{k=0}^{n} b_k C(n,k) s^k (1-s)^(n-k)` in the Bernstein basis of
/// degree `n` on `[0, 1]`.
///
/// Bernstein coefficients are stored in ascending index order `b_0 .. b_n`. Unlike
/// [`Polynomial`], the degree is the basis degree `len - 1` and is never trimmed: a cubic
/// Bernstein polynomial may represent a quadratic. Evaluation by de Casteljau's algorithm is
/// numerically stable on `[0, 1]`, and the number of sign changes of the coefficients bounds the
/// number of roots in `(0, 1)` (Descartes' rule of signs / variation diminishing).
///
/// # Examples
///
/// ```
/// use rs_roots::{Bernstein, Polynomial};
/// let p = Polynomial::new(vec![0.25, -1.0, 1.0]); // (t - 0.5)^2
/// let b = Bernstein::from_power(&p, 2);
/// assert_eq!(b.coeffs(), &[0.25, -0.25, 0.25]);
/// assert_eq!(b.eval(0.5), 0.0);
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct Bernstein {
    coeffs: Vec<f64>,
}

/// Binomial coefficient `C(n, k)` as `f64`, rounded to the nearest integer (exact up to
/// `n = 56`); `0` for `k > n`.
pub fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    let mut r = 1.0;
    for i in 0..k {
        r = r * (n - i) as f64 / (i + 1) as f64;
    }
    r.round()
}

impl Bernstein {
    /// Builds a Bernstein polynomial from its coefficients `b_0 .. b_n`.
    ///
    /// An empty coefficient list is treated as the degree-0 zero polynomial.
    pub fn new(coeffs: impl Into<Vec<f64>>) -> Self {
        let mut coeffs = coeffs.into();
        if coeffs.is_empty() {
            coeffs.push(0.0);
        }
        Self { coeffs }
    }

    /// Coefficients `b_0 .. b_n`.
    pub fn coeffs(&self) -> &[f64] {
        &self.coeffs
    }

    /// The basis degree `n` (number of coefficients minus one).
    pub fn degree(&self) -> usize {
        self.coeffs.len() - 1
    }

    /// Converts a power-basis polynomial to the Bernstein basis of degree `n` on `[0, 1]`:
    /// `b_k = sum_{i<=k} C(k,i) / C(n,i) a_i`.
    ///
    /// `n` is raised to the polynomial's degree if it is smaller.
    pub fn from_power(p: &Polynomial, n: usize) -> Self {
        let a = p.coeffs();
        let n = n.max(a.len().saturating_sub(1));
        let coeffs = (0..=n)
            .map(|k| {
                (0..=k.min(a.len().saturating_sub(1)))
                    .filter(|&i| i < a.len())
                    .map(|i| binomial(k, i) / binomial(n, i) * a[i])
                    .sum()
            })
            .collect::<Vec<f64>>();
        Self::new(coeffs)
    }

    /// Converts to the power basis: `a_i = sum_{k<=i} (-1)^(i-k) C(n,i) C(i,k) b_k`.
    pub fn to_power(&self) -> Polynomial {
        let n = self.degree();
        let b = &self.coeffs;
        let a: Vec<f64> = (0..=n)
            .map(|i| {
                let s: f64 = (0..=i)
                    .map(|k| {
                        let sign = if (i - k) % 2 == 0 { 1.0 } else { -1.0 };
                        sign * binomial(i, k) * b[k]
                    })
                    .sum();
                binomial(n, i) * s
            })
            .collect();
        Polynomial::new(a)
    }

    /// Evaluates `b(s)` by de Casteljau's algorithm (stable for `s` in `[0, 1]`).
    pub fn eval(&self, s: f64) -> f64 {
        de_casteljau(&self.coeffs, s)
    }

    /// Splits at `s` into the Bernstein representations of `b` on `[0, s]` and on `[s, 1]`,
    /// each reparametrised to `[0, 1]`.
    pub fn split(&self, s: f64) -> (Self, Self) {
        let n = self.coeffs.len();
        let (mut left, mut right) = (vec![0.0; n], vec![0.0; n]);
        de_casteljau_split(&self.coeffs, s, &mut left, &mut right);
        (Self::new(left), Self::new(right))
    }

    /// The derivative as a Bernstein polynomial of degree `n - 1`:
    /// `b'(s) = n sum_k (b_{k+1} - b_k) B_{k,n-1}(s)`.
    pub fn derivative(&self) -> Self {
        let n = self.degree();
        if n == 0 {
            return Self::new(vec![0.0]);
        }
        Self::new(
            self.coeffs
                .windows(2)
                .map(|w| n as f64 * (w[1] - w[0]))
                .collect::<Vec<_>>(),
        )
    }

    /// The product `a(s) b(s)` in the Bernstein basis of degree `m + n`:
    /// `c_k = sum_{i + j = k} C(m, i) C(n, j) / C(m + n, k) a_i b_j` (exact, no conversion to
    /// the power basis).
    pub fn mul(&self, other: &Bernstein) -> Bernstein {
        let (m, n) = (self.degree(), other.degree());
        let cm: Vec<f64> = (0..=m).map(|i| binomial(m, i)).collect();
        let cn: Vec<f64> = (0..=n).map(|j| binomial(n, j)).collect();
        let cmn: Vec<f64> = (0..=m + n).map(|k| binomial(m + n, k)).collect();
        let mut c = vec![0.0; m + n + 1];
        for (i, a) in self.coeffs.iter().enumerate() {
            for (j, b) in other.coeffs.iter().enumerate() {
                c[i + j] += cm[i] * cn[j] * a * b;
            }
        }
        for (ck, binom) in c.iter_mut().zip(&cmn) {
            *ck /= binom;
        }
        Bernstein::new(c)
    }

    /// `self + other` (both of the same degree).
    ///
    /// # Panics
    /// If the degrees differ (a programming error, not an input error).
    pub fn add(&self, other: &Bernstein) -> Bernstein {
        assert_eq!(
            self.degree(),
            other.degree(),
            "Bernstein::add needs equal degrees"
        );
        Bernstein::new(
            self.coeffs
                .iter()
                .zip(&other.coeffs)
                .map(|(a, b)| a + b)
                .collect::<Vec<_>>(),
        )
    }

    /// `c * self`.
    pub fn scale(&self, c: f64) -> Bernstein {
        Bernstein::new(self.coeffs.iter().map(|a| c * a).collect::<Vec<_>>())
    }

    /// Number of sign changes in the coefficient sequence, ignoring exact zeros.
    ///
    /// It is an upper bound on the number of roots in the open interval `(0, 1)`, counted with
    /// multiplicity, and has the same parity.
    pub fn sign_variations(&self) -> usize {
        let mut count = 0;
        let mut last = 0.0f64;
        for &c in &self.coeffs {
            if c != 0.0 {
                if last != 0.0 && (c > 0.0) != (last > 0.0) {
                    count += 1;
                }
                last = c;
            }
        }
        count
    }

    /// Sum of `|b_k|`: bounds `|b(s)|` on `[0, 1]` and scales rounding-error estimates.
    pub fn magnitude(&self) -> f64 {
        self.coeffs.iter().map(|c| c.abs()).sum()
    }
}

/// A value de Casteljau's algorithm can blend: scalars, points, homogeneous points. Every
/// `Copy` type with `+`, `-` and scaling by `f64` qualifies.
pub trait Blend:
    Copy + Default + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self>
{
}

impl<T> Blend for T where
    T: Copy + Default + Add<Output = T> + Sub<Output = T> + Mul<f64, Output = T>
{
}

/// Coefficients kept on the stack by the de Casteljau kernels (larger degrees allocate).
const STACK_COEFFS: usize = 16;

/// Runs `f` on a scratch copy of `c`: on the stack for up to [`STACK_COEFFS`] entries.
fn with_scratch<T: Blend, R>(c: &[T], f: impl FnOnce(&mut [T]) -> R) -> R {
    if c.len() <= STACK_COEFFS {
        let mut small = [T::default(); STACK_COEFFS];
        small[..c.len()].copy_from_slice(c);
        f(&mut small[..c.len()])
    } else {
        f(&mut c.to_vec())
    }
}

/// Reduces `work` by `levels` de Casteljau steps at `s`: afterwards `work[i]` for
/// `i < len - levels` holds the level-`levels` blend `(1 - s) a + s b` of its neighbours.
/// This loop is the one de Casteljau kernel of the workspace; every evaluation, split and
/// derivative of a Bernstein form (scalar or rational curve) goes through it, or through
/// [`split_fixed`]'s unrolled copy of its steps (the same operations in the same order, bit
/// for bit: a test checks them).
#[inline(always)]
fn reduce<T: Blend>(work: &mut [T], s: f64, levels: usize) {
    let r = 1.0 - s;
    let n = work.len();
    for k in 1..=levels.min(n.saturating_sub(1)) {
        for i in 0..n - k {
            work[i] = work[i] * r + work[i + 1] * s;
        }
    }
}

/// Value at `s` of the Bernstein form with coefficients `c` (scalars or points), by de
/// Casteljau's algorithm (`(1 - s) a + s b` at every step; no allocation for up to 16
/// coefficients). An empty slice gives `T::default()`.
pub fn de_casteljau<T: Blend>(c: &[T], s: f64) -> T {
    // Lines, quadratics and cubics on a copy of fixed size: the same steps, unrolled, without
    // the scratch array's set-up (which cost as much as the blends at these degrees).
    match c.len() {
        2 => return value_fixed::<T, 2>(c, s),
        3 => return value_fixed::<T, 3>(c, s),
        4 => return value_fixed::<T, 4>(c, s),
        _ => {}
    }
    with_scratch(c, |work| {
        reduce(work, s, work.len());
        work.first().copied().unwrap_or_default()
    })
}

/// [`de_casteljau`] of `N` coefficients (`c.len() == N`) on a fixed-size copy.
#[inline(always)]
fn value_fixed<T: Blend, const N: usize>(c: &[T], s: f64) -> T {
    let mut work = [T::default(); N];
    work.copy_from_slice(c);
    reduce(&mut work, s, N);
    work[0]
}

/// Value and first derivative at `s` of the Bernstein form `c` of degree `n = c.len() - 1`:
/// after `n - 1` de Casteljau levels the two remaining entries `a`, `b` give
/// `b(s) = (1 - s) a + s b` and `b'(s) = n (b - a)`.
#[inline]
pub fn de_casteljau_with_derivative<T: Blend>(c: &[T], s: f64) -> (T, T) {
    let n = c.len();
    match n {
        0 | 1 => return (c.first().copied().unwrap_or_default(), T::default()),
        // As in `de_casteljau`: the common degrees unrolled, the same steps.
        2 => return with_derivative_fixed::<T, 2>(c, s),
        3 => return with_derivative_fixed::<T, 3>(c, s),
        4 => return with_derivative_fixed::<T, 4>(c, s),
        _ => {}
    }
    with_scratch(c, |work| last_level(work, s))
}

/// [`de_casteljau_with_derivative`] of `N >= 2` coefficients (`c.len() == N`) on a
/// fixed-size copy.
#[inline(always)]
fn with_derivative_fixed<T: Blend, const N: usize>(c: &[T], s: f64) -> (T, T) {
    let mut work = [T::default(); N];
    work.copy_from_slice(c);
    last_level(&mut work, s)
}

/// The value and derivative from `work` (at least two coefficients, reduced in place to the
/// last level's pair `a`, `b`): `(1 - s) a + s b` and `n (b - a)`.
#[inline(always)]
fn last_level<T: Blend>(work: &mut [T], s: f64) -> (T, T) {
    let n = work.len();
    reduce(work, s, n - 2);
    let (a, b) = (work[0], work[1]);
    (a * (1.0 - s) + b * s, (b - a) * (n - 1) as f64)
}

/// Splits the Bernstein coefficients `c` at `s` (de Casteljau): `left` and `right` (each as
/// long as `c`) receive the coefficients of the form on `[0, s]` and on `[s, 1]`, each
/// reparametrised to `[0, 1]`; `left[n - 1]` and `right[0]` are the same value, bit for bit
/// (`n = c.len()`).
///
/// # Panics
/// If `left` or `right` is not as long as `c`.
pub fn de_casteljau_split<T: Blend>(c: &[T], s: f64, left: &mut [T], right: &mut [T]) {
    let n = c.len();
    assert!(
        left.len() == n && right.len() == n,
        "split buffers must match the coefficients"
    );
    // As in `de_casteljau`: the common degrees unrolled on fixed-size copies, the same steps.
    match n {
        0 => {}
        2 => split_fixed::<T, 2>(c, s, left, right),
        3 => split_fixed::<T, 3>(c, s, left, right),
        4 => split_fixed::<T, 4>(c, s, left, right),
        _ => split_any(c, s, left, right),
    }
}

/// [`de_casteljau_split`] of any number of coefficients (at least one; `left` and `right` as
/// long as `c`).
fn split_any<T: Blend>(c: &[T], s: f64, left: &mut [T], right: &mut [T]) {
    let n = c.len();
    // `right` is the work array: after level k its entry n-1-k is final, and later levels only
    // touch lower entries.
    right.copy_from_slice(c);
    left[0] = right[0];
    for (level, out) in left.iter_mut().enumerate().skip(1) {
        // One level more on the still-active prefix `right[..n - level + 1]`.
        reduce(&mut right[..n - level + 1], s, 1);
        *out = right[0];
    }
}

/// [`de_casteljau_split`] of `N` coefficients (`c`, `left` and `right` all `N` long) on
/// fixed-size copies: level `k` blends the `N - k` entries still active, `(1 - s) a + s b` as
/// [`reduce`] does, and its first entry is `left[k]`; what remains is `right`.
#[inline(always)]
fn split_fixed<T: Blend, const N: usize>(c: &[T], s: f64, left: &mut [T], right: &mut [T]) {
    let r = 1.0 - s;
    let mut work = [T::default(); N];
    work.copy_from_slice(c);
    let mut first = [T::default(); N];
    first[0] = work[0];
    for (level, out) in first.iter_mut().enumerate().skip(1) {
        for i in 0..N - level {
            work[i] = work[i] * r + work[i + 1] * s;
        }
        *out = work[0];
    }
    left.copy_from_slice(&first);
    right.copy_from_slice(&work);
}

#[cfg(test)]
mod tests {
    /// The unrolled splits of two to four coefficients give the very bits of the general
    /// loop, on coefficients and parameters of every scale and sign (a deterministic
    /// pseudo-random sequence).
    #[test]
    fn unrolled_splits_are_the_general_split_bit_for_bit() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut value = || {
            let bits = next();
            let mantissa = (bits >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
            mantissa * 2f64.powi((bits % 61) as i32 - 30)
        };
        for n in 2..=4 {
            for round in 0..2000 {
                let c: Vec<f64> = (0..n).map(|_| value()).collect();
                let s = match round % 4 {
                    0 => 0.5,
                    1 => 1.0 / 3.0,
                    _ => value().abs().fract(),
                };
                let (mut l, mut r) = (vec![0.0; n], vec![0.0; n]);
                let (mut gl, mut gr) = (vec![0.0; n], vec![0.0; n]);
                super::de_casteljau_split(&c, s, &mut l, &mut r);
                super::split_any(&c, s, &mut gl, &mut gr);
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(&l), bits(&gl), "left, {c:?} at {s}");
                assert_eq!(bits(&r), bits(&gr), "right, {c:?} at {s}");
            }
        }
    }

    #[test]
    fn product_sum_and_scale_evaluate_pointwise() {
        let a = Bernstein::new(vec![1.0, -2.0, 0.5, 3.0]);
        let b = Bernstein::new(vec![0.25, 4.0, -1.0]);
        let c = Bernstein::new(vec![2.0, 1.0, -3.0, 0.0]);
        let ab = a.mul(&b);
        assert_eq!(ab.degree(), 5);
        for i in 0..=20 {
            let s = i as f64 / 20.0;
            assert!((ab.eval(s) - a.eval(s) * b.eval(s)).abs() < 1e-13);
            assert!((a.add(&c).eval(s) - a.eval(s) - c.eval(s)).abs() < 1e-14);
            assert!((a.scale(-1.5).eval(s) + 1.5 * a.eval(s)).abs() < 1e-14);
        }
    }

    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn binomials() {
        assert_eq!(binomial(5, 2), 10.0);
        assert_eq!(binomial(20, 10), 184_756.0);
        assert_eq!(binomial(3, 4), 0.0);
    }

    #[test]
    fn power_round_trip_and_evaluation() {
        let p = Polynomial::new(vec![0.3, -1.0, 2.0, 0.5, -0.125]);
        for n in 4..8 {
            let b = Bernstein::from_power(&p, n);
            assert_eq!(b.degree(), n);
            let back = b.to_power();
            for &s in &[0.0, 0.1, 0.5, 0.77, 1.0] {
                assert_relative_eq!(b.eval(s), p.eval(s), epsilon = 1e-13);
                assert_relative_eq!(back.eval(s), p.eval(s), epsilon = 1e-12);
            }
        }
    }

    #[test]
    fn split_reproduces_both_halves() {
        let b = Bernstein::new(vec![1.0, -2.0, 0.5, 3.0, -1.0, 0.25, 2.0, -0.5, 1.5, 0.0]);
        let (l, r) = b.split(0.3);
        for &u in &[0.0, 0.25, 0.5, 0.9, 1.0] {
            assert_relative_eq!(l.eval(u), b.eval(0.3 * u), epsilon = 1e-13);
            assert_relative_eq!(r.eval(u), b.eval(0.3 + 0.7 * u), epsilon = 1e-13);
        }
    }

    #[test]
    fn derivative_matches_power_derivative() {
        let p = Polynomial::new(vec![0.3, -1.0, 2.0, 0.5]);
        let db = Bernstein::from_power(&p, 3).derivative();
        let dp = p.derivative();
        for &s in &[0.0, 0.4, 1.0] {
            assert_relative_eq!(db.eval(s), dp.eval(s), epsilon = 1e-13);
        }
    }

    #[test]
    fn sign_variations_ignore_zeros() {
        assert_eq!(
            Bernstein::new(vec![1.0, 0.0, -1.0, 0.0, 2.0]).sign_variations(),
            2
        );
        assert_eq!(Bernstein::new(vec![0.0, 0.0]).sign_variations(), 0);
    }

    #[test]
    fn derivative_kernel_matches_the_derivative_polynomial() {
        // Degrees 0..=20: the stack path and the heap path of the scratch buffer.
        for n in 0..=20usize {
            let c: Vec<f64> = (0..=n).map(|k| ((k * 7 % 5) as f64) - 1.5).collect();
            let b = Bernstein::new(c.clone());
            for i in 0..=8 {
                let s = i as f64 / 8.0;
                let (v, d) = de_casteljau_with_derivative(&c, s);
                assert_relative_eq!(v, b.eval(s), epsilon = 1e-12);
                assert_relative_eq!(d, b.derivative().eval(s), epsilon = 1e-10);
            }
        }
    }

    #[test]
    fn kernel_blends_points_like_scalars() {
        // A 2-vector type through the generic kernel equals two scalar runs bit for bit.
        #[derive(Clone, Copy, Default, Debug, PartialEq)]
        struct V(f64, f64);
        impl std::ops::Add for V {
            type Output = V;
            fn add(self, o: V) -> V {
                V(self.0 + o.0, self.1 + o.1)
            }
        }
        impl std::ops::Sub for V {
            type Output = V;
            fn sub(self, o: V) -> V {
                V(self.0 - o.0, self.1 - o.1)
            }
        }
        impl std::ops::Mul<f64> for V {
            type Output = V;
            fn mul(self, s: f64) -> V {
                V(self.0 * s, self.1 * s)
            }
        }
        let xs = [0.0, 1.0, 3.0, 2.5];
        let ys = [1.0, -1.0, 0.5, 4.0];
        let vs: Vec<V> = xs.iter().zip(&ys).map(|(&x, &y)| V(x, y)).collect();
        let v = de_casteljau(&vs, 0.3);
        assert_eq!(v, V(de_casteljau(&xs, 0.3), de_casteljau(&ys, 0.3)));
        let (mut l, mut r) = (vs.clone(), vs.clone());
        de_casteljau_split(&vs, 0.3, &mut l, &mut r);
        assert_eq!(l[3], r[0]);
        assert_eq!(l[3], v);
    }
}
