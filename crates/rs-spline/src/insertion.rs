//! Knot insertion (Boehm), refinement, splitting, subsegments, clamping and reversal of rational
//! B-splines of any dimension, in homogeneous coordinates `(w P, w)`: the one implementation
//! behind [`crate::NurbsCurve`], [`crate::RationalBSpline`] and Bezier extraction.
//!
//! Every operation is written once over a control point type `P` (the plane, space); the
//! homogeneous points are built as `P w`, blended as `a (1 - t) + b t` and projected as
//! `(w P) / w`, in the order the planar code always used, so planar results keep their bits.

use std::ops::{Add, Div, Mul, Sub};

use rs_roots::Blend;

use crate::{KnotVector, SplineError};

/// A control point in homogeneous coordinates `(w P, w)`, where a rational B-spline is a
/// polynomial one (so Boehm's and de Boor's algorithms apply unchanged).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Weighted<P> {
    /// `w P`.
    pub(crate) wp: P,
    /// `w`.
    pub(crate) w: f64,
}

impl<P: Blend> Weighted<P> {
    /// `(P w, w)`.
    pub(crate) fn new(p: P, w: f64) -> Self {
        Self { wp: p * w, w }
    }
}

impl<P: Div<f64, Output = P>> Weighted<P> {
    /// The Cartesian point `(w P) / w`.
    pub(crate) fn project(self) -> P {
        self.wp / self.w
    }
}

impl<P: Add<Output = P>> Add for Weighted<P> {
    type Output = Self;
    fn add(self, o: Self) -> Self {
        Self {
            wp: self.wp + o.wp,
            w: self.w + o.w,
        }
    }
}

impl<P: Sub<Output = P>> Sub for Weighted<P> {
    type Output = Self;
    fn sub(self, o: Self) -> Self {
        Self {
            wp: self.wp - o.wp,
            w: self.w - o.w,
        }
    }
}

impl<P: Mul<f64, Output = P>> Mul<f64> for Weighted<P> {
    type Output = Self;
    fn mul(self, s: f64) -> Self {
        Self {
            wp: self.wp * s,
            w: self.w * s,
        }
    }
}

/// A rational B-spline's data, borrowed: knots, control points, weights (all of them, `1`
/// for polynomial curves).
#[derive(Clone, Copy, Debug)]
pub(crate) struct SplineRef<'a, P> {
    pub(crate) knots: &'a KnotVector,
    pub(crate) points: &'a [P],
    pub(crate) weights: &'a [f64],
}

/// A rational B-spline's data, owned: what the operations of [`SplineRef`] return.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct SplineParts<P> {
    pub(crate) knots: KnotVector,
    pub(crate) points: Vec<P>,
    pub(crate) weights: Vec<f64>,
}

impl<P: Blend + Div<f64, Output = P>> SplineParts<P> {
    /// Borrows the parts.
    pub(crate) fn as_ref(&self) -> SplineRef<'_, P> {
        SplineRef {
            knots: &self.knots,
            points: &self.points,
            weights: &self.weights,
        }
    }

    /// The curve of the homogeneous points `hp` (projected) on `knots`.
    fn from_homogeneous(knots: Vec<f64>, degree: usize, hp: &[Weighted<P>]) -> Self {
        Self {
            knots: KnotVector::from_raw(knots, degree),
            points: hp.iter().map(|h| h.project()).collect(),
            weights: hp.iter().map(|h| h.w).collect(),
        }
    }
}

impl<P: Blend + Div<f64, Output = P>> SplineRef<'_, P> {
    /// A copy of the parts.
    pub(crate) fn to_owned(self) -> SplineParts<P> {
        SplineParts {
            knots: self.knots.clone(),
            points: self.points.to_vec(),
            weights: self.weights.to_vec(),
        }
    }

    fn homogeneous(self) -> Vec<Weighted<P>> {
        self.points
            .iter()
            .zip(self.weights)
            .map(|(&p, &w)| Weighted::new(p, w))
            .collect()
    }

    fn check_in_domain(self, u: f64) -> Result<(), SplineError> {
        let (start, end) = self.knots.domain();
        if u.is_finite() && u >= start && u <= end {
            Ok(())
        } else {
            Err(SplineError::ParameterOutOfDomain { u, start, end })
        }
    }

    /// Inserts the knot `u` `times` times (Boehm's algorithm, in homogeneous coordinates). The
    /// curve is unchanged as a point set and as a function of `u`.
    ///
    /// # Errors
    /// [`SplineError::ParameterOutOfDomain`] if `u` is outside `[u_p, u_n]`;
    /// [`SplineError::MultiplicityExceeded`] if the multiplicity would exceed `p`.
    pub(crate) fn insert_knot(self, u: f64, times: usize) -> Result<SplineParts<P>, SplineError> {
        self.check_in_domain(u)?;
        let p = self.knots.degree();
        let current = self.knots.multiplicity(u);
        if current + times > p {
            return Err(SplineError::MultiplicityExceeded {
                value: u,
                times,
                current,
                max: p,
            });
        }
        let mut knots = self.knots.knots().to_vec();
        let mut hp = self.homogeneous();
        for _ in 0..times {
            insert_once(&mut knots, &mut hp, p, u);
        }
        Ok(SplineParts::from_homogeneous(knots, p, &hp))
    }

    /// Inserts every value of `new_knots` once, one after the other (knot refinement).
    ///
    /// # Errors
    /// As [`SplineRef::insert_knot`] for each value.
    pub(crate) fn refine(self, new_knots: &[f64]) -> Result<SplineParts<P>, SplineError> {
        let mut c = self.to_owned();
        for &u in new_knots {
            c = c.as_ref().insert_knot(u, 1)?;
        }
        Ok(c)
    }

    /// Splits at `u` strictly inside the domain into the curves on `[a, u]` and `[u, b]`.
    ///
    /// # Errors
    /// [`SplineError::ParameterOutOfDomain`] unless `a < u < b`.
    pub(crate) fn split_at(self, u: f64) -> Result<(SplineParts<P>, SplineParts<P>), SplineError> {
        let (a, b) = self.knots.domain();
        if !(u > a && u < b) {
            return Err(SplineError::ParameterOutOfDomain {
                u,
                start: a,
                end: b,
            });
        }
        let p = self.knots.degree();
        let have = self.knots.multiplicity(u);
        if have > p {
            // A break: the pieces on either side already have their own control points.
            let knots = self.knots.knots();
            let hp = self.homogeneous();
            let j = knots.iter().position(|&k| k == u).unwrap_or(0);
            return Ok((
                SplineParts::from_homogeneous(knots[..j + p + 1].to_vec(), p, &hp[..j]),
                SplineParts::from_homogeneous(knots[j..].to_vec(), p, &hp[j..]),
            ));
        }
        let c = self.insert_knot(u, p - have)?;
        let knots = c.knots.knots();
        let hp = c.as_ref().homogeneous();
        let j = knots.iter().position(|&k| k == u).unwrap_or(0);
        let mut left_knots = knots[..j + p].to_vec();
        left_knots.push(u);
        let mut right_knots = vec![u];
        right_knots.extend_from_slice(&knots[j..]);
        Ok((
            SplineParts::from_homogeneous(left_knots, p, &hp[..j]),
            SplineParts::from_homogeneous(right_knots, p, &hp[j - 1..]),
        ))
    }

    /// The curve on `[u0, u1]` (`a <= u0 < u1 <= b`), by at most two splits; the same curve
    /// when the window is the whole domain.
    ///
    /// # Errors
    /// [`SplineError::ParameterOutOfDomain`] for a window that is empty or not inside the
    /// domain.
    pub(crate) fn subsegment(self, (u0, u1): (f64, f64)) -> Result<SplineParts<P>, SplineError> {
        let (a, b) = self.knots.domain();
        if !(a <= u0 && u0 < u1 && u1 <= b) {
            return Err(SplineError::ParameterOutOfDomain {
                u: if (a..=b).contains(&u0) { u1 } else { u0 },
                start: a,
                end: b,
            });
        }
        let right = if u0 > a {
            self.split_at(u0)?.1
        } else {
            self.to_owned()
        };
        if u1 < b {
            Ok(right.as_ref().split_at(u1)?.0)
        } else {
            Ok(right)
        }
    }

    /// The same curve with clamped end knots (multiplicity `p + 1`), so that the first and last
    /// control points are the end points. Knot values are kept exactly.
    pub(crate) fn clamped(self) -> SplineParts<P> {
        let p = self.knots.degree();
        let mut knots = self.knots.knots().to_vec();
        let mut hp = self.homogeneous();
        clamp_start(&mut knots, &mut hp, p);
        // The start-clamped curve is projected and re-weighted before the end is clamped.
        let start = SplineParts::from_homogeneous(knots, p, &hp);
        let mut knots = start.knots.knots().to_vec();
        let mut hp = start.as_ref().homogeneous();
        clamp_end(&mut knots, &mut hp, p);
        SplineParts::from_homogeneous(knots, p, &hp)
    }

    /// The same curve traversed backwards on the same domain: `C_rev(u) = C(a + b - u)`.
    pub(crate) fn reversed(self) -> SplineParts<P> {
        let (a, b) = self.knots.domain();
        let knots: Vec<f64> = self
            .knots
            .knots()
            .iter()
            .rev()
            .map(|&k| a + b - k)
            .collect();
        SplineParts {
            knots: KnotVector::from_raw(knots, self.knots.degree()),
            points: self.points.iter().rev().copied().collect(),
            weights: self.weights.iter().rev().copied().collect(),
        }
    }
}

/// Boehm's insertion of `u` once into the degree-`p` curve with `knots` and homogeneous control
/// points `hp`, in place (The NURBS Book, A5.1 with `r = 1`). The span is `k` with
/// `u_k <= u < u_{k+1}`, or `u_k < u = u_{k+1}` at the domain's end `u = u_n` (the half-open
/// span there would need a control point `P_n`). The new points are computed from the top down,
/// so each reads the old points `i - 1` and `i` before they are overwritten:
/// `Q_i = (1 - alpha_i) P_{i-1} + alpha_i P_i`, `alpha_i = (u - u_i) / (u_{i+p} - u_i)`.
pub(crate) fn insert_once<H: Blend>(knots: &mut Vec<f64>, hp: &mut Vec<H>, p: usize, u: f64) {
    let n = hp.len();
    let k = if u >= knots[n] {
        knots.iter().rposition(|&x| x < u)
    } else {
        knots.iter().rposition(|&x| x <= u)
    }
    .unwrap_or(p);
    let last = hp[n - 1];
    hp.push(last);
    for i in (0..=n).rev() {
        hp[i] = if i + p <= k {
            hp[i]
        } else if i > k {
            hp[i - 1]
        } else {
            let alpha = (u - knots[i]) / (knots[i + p] - knots[i]);
            hp[i - 1] * (1.0 - alpha) + hp[i] * alpha
        };
    }
    knots.insert(k + 1, u);
}

/// Clamps the start in place: afterwards `u_0 = ... = u_p = a` (the domain's start, knots
/// before it dropped with their control points) and the first control point is `C(a)`.
pub(crate) fn clamp_start<H: Blend>(knots: &mut Vec<f64>, hp: &mut Vec<H>, p: usize) {
    let a = knots[p];
    while count(knots, a) < p {
        insert_once(knots, hp, p, a);
    }
    let j = knots.iter().position(|&x| x == a).unwrap_or(0);
    // Keep exactly p + 1 copies of a in front; drop what precedes them.
    let start = (j + count(knots, a)).saturating_sub(p + 1);
    knots.drain(..start);
    knots[0] = a;
    hp.drain(..start);
}

/// Clamps the end in place: afterwards `u_n = ... = u_{n+p} = b` (the domain's end, knots
/// after it dropped with their control points) and the last control point is `C(b)`.
pub(crate) fn clamp_end<H: Blend>(knots: &mut Vec<f64>, hp: &mut Vec<H>, p: usize) {
    let b = knots[knots.len() - p - 1];
    while count(knots, b) < p {
        insert_once(knots, hp, p, b);
    }
    let j = knots.iter().position(|&x| x == b).unwrap_or(0);
    // Keep exactly p + 1 copies of b at the end; drop what follows them.
    knots.truncate(j + p + 1);
    knots[j + p] = b;
    hp.truncate(j);
}

fn count(knots: &[f64], u: f64) -> usize {
    knots.iter().filter(|&&x| x == u).count()
}
