//! The area a domain fills under a fill rule, and the nesting of its loops that decides it.

use rs_spline::prelude::*;
use rs_spline::{Domain, Point};
use thiserror::Error;

use crate::{BoundaryCrossing, FillRule, QueryStats, boundary_crossing, curve_winding_number};

/// Most loops [`loop_nesting`] nests (its work is quadratic in the number of loops).
pub const MAX_NESTED_LOOPS: usize = 10_000;

/// Why the loops of a domain have no nesting that decides its fill ([`fill_nesting`]): the
/// Green's-theorem capabilities (filled areas, cell coverage, cubature) need closed loops that
/// do not cross; classification and winding numbers take any loops.
#[derive(Clone, Debug, PartialEq, Error)]
#[non_exhaustive]
pub enum NestingError {
    /// A loop does not close.
    #[error("loop {0} is open")]
    OpenLoop(usize),
    /// More loops than [`MAX_NESTED_LOOPS`].
    #[error("{loops} loops, more than the {limit} whose nesting is computed")]
    TooManyLoops {
        /// The domain's loops.
        loops: usize,
        /// [`MAX_NESTED_LOOPS`].
        limit: usize,
    },
    /// Every sampled point of a loop lies on another loop (coincident loops).
    #[error("loop {0} lies on another loop")]
    Coincident(usize),
    /// The boundary crosses itself ([`boundary_crossing`]): the fill changes along a loop.
    #[error("the loops cross ({0}): only classification and winding numbers take crossing loops")]
    Crossing(BoundaryCrossing),
    /// The boundary could not be cut into monotone pieces to look for crossings.
    #[error("{0}")]
    Boxes(rs_boxes::BoxError),
}

/// Where one loop of a domain lies among the others: [`loop_nesting`]'s answer.
///
/// For loops that do not cross each other, the winding number of the whole boundary is
/// `winding` just outside the loop and `winding + orientation` just inside it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct LoopNesting {
    /// The number of other loops that enclose this loop (whatever their orientation): those
    /// whose winding number at the loop is odd.
    pub depth: usize,
    /// The sum over the other loops of their (rounded, signed) winding numbers at this loop.
    pub winding: i64,
    /// `+1` if the loop is counter-clockwise (signed area `>= 0`), else `-1`.
    pub orientation: i64,
}

impl LoopNesting {
    /// `d = f(winding + orientation) - f(winding)` in `{-1, 0, 1}`, with `f(w)` the filled
    /// set's indicator under `rule` (`w` odd, or `w != 0`): how the filled set's indicator
    /// changes from just outside the loop to just inside it. The filled area is
    /// `sum_i d_i |A_i|`; a loop with `d = 0` does not bound the filled set (the inner of two
    /// nested counter-clockwise circles under the nonzero rule).
    ///
    /// # Examples
    ///
    /// ```
    /// use rs_contain::{loop_nesting, FillRule};
    /// use rs_spline::{circle, Domain, Point};
    /// let c = |r: f64| circle(Point::new(0.0, 0.0), r).unwrap();
    /// let n = loop_nesting(&Domain::new(vec![c(2.0), c(1.0)]).unwrap()).unwrap();
    /// assert_eq!(n[1].fill_change(FillRule::EvenOdd), -1); // a hole
    /// assert_eq!(n[1].fill_change(FillRule::NonZero), 0); // inside the filled disc anyway
    /// ```
    pub fn fill_change(&self, rule: FillRule) -> i64 {
        let filled = |w: i64| i64::from(rule.fills(w));
        filled(self.winding + self.orientation) - filled(self.winding)
    }

    /// `fill_change(rule) * orientation`: the factor that puts the filled set on the loop's
    /// left (`+1` for outer boundaries, `-1` for holes), `0` for a loop that does not bound
    /// the filled set.
    pub fn boundary_sign(&self, rule: FillRule) -> i64 {
        self.fill_change(rule) * self.orientation
    }
}

/// [`LoopNesting::boundary_sign`] of each curve's loop, by curve index: the factor that puts
/// the filled set on each boundary curve's left under `rule` (`0` for curves of loops that do
/// not bound it), as Green's-theorem integrals over the curves want it.
///
/// # Errors
/// As [`fill_nesting`].
///
/// # Examples
///
/// ```
/// use rs_contain::{curve_boundary_signs, FillRule};
/// use rs_spline::{circle, Domain, Point};
/// let c = |r: f64| circle(Point::new(0.0, 0.0), r).unwrap();
/// let d = Domain::new(vec![c(2.0), c(1.0)]).unwrap();
/// // The outer circle as it runs, the hole turned clockwise.
/// assert_eq!(curve_boundary_signs(&d, FillRule::EvenOdd).unwrap(), vec![1, -1]);
/// // Under the nonzero rule the inner circle of one orientation bounds nothing.
/// assert_eq!(curve_boundary_signs(&d, FillRule::NonZero).unwrap(), vec![1, 0]);
/// ```
pub fn curve_boundary_signs(domain: &Domain, rule: FillRule) -> Result<Vec<i64>, NestingError> {
    let nesting = fill_nesting(domain)?;
    let mut signs = vec![0; domain.curves().len()];
    for (l, n) in domain.loops().iter().zip(&nesting) {
        for c in l.curves() {
            signs[c] = n.boundary_sign(rule);
        }
    }
    Ok(signs)
}

/// The area filled by `domain` under `rule`: `sum_i d_i |A_i|`, where `A_i` is the signed
/// area of loop `i` and `d_i` its [`LoopNesting::fill_change`]. For even-odd `d_i` is
/// `(-1)^depth_i`; for nonzero it depends on the orientations (two nested counter-clockwise
/// circles fill the outer disc, the same circles with opposite orientations an annulus).
/// Exact for closed loops that do not cross each other (they may touch and nest).
///
/// # Errors
/// As [`fill_nesting`]: an open loop, coincident loops, loops that cross, or more than
/// [`MAX_NESTED_LOOPS`] loops.
///
/// # Examples
///
/// ```
/// use rs_contain::{filled_area, FillRule};
/// use rs_spline::{circle, Domain, ParamCurve, Point};
/// use std::f64::consts::PI;
/// let c = |r: f64| circle(Point::new(0.0, 0.0), r).unwrap();
/// let same = Domain::new(vec![c(2.0), c(1.0)]).unwrap();
/// assert!((filled_area(&same, FillRule::NonZero).unwrap() - 4.0 * PI).abs() < 1e-12);
/// assert!((filled_area(&same, FillRule::EvenOdd).unwrap() - 3.0 * PI).abs() < 1e-12);
/// let opposite = Domain::new(vec![c(2.0), c(1.0).reversed()]).unwrap();
/// assert!((filled_area(&opposite, FillRule::NonZero).unwrap() - 3.0 * PI).abs() < 1e-12);
/// ```
pub fn filled_area(domain: &Domain, rule: FillRule) -> Result<f64, NestingError> {
    let nesting = fill_nesting(domain)?;
    // Summed loop by loop in order: the even-odd case has the bits it has always had.
    let total = nesting
        .iter()
        .enumerate()
        .map(|(i, n)| {
            let area = domain.loop_signed_area(i).abs();
            match n.fill_change(rule) {
                1 => area,
                -1 => -area,
                _ => 0.0,
            }
        })
        .sum();
    Ok(total)
}

/// The area filled by `domain` under the even-odd rule: `sum_i (-1)^depth_i |A_i|`, where
/// `A_i` is the signed area of loop `i` and `depth_i` the number of other loops that enclose it
/// (whatever their orientation). This is the measure of the set of points of odd crossing
/// parity, the set the crossing methods call inside, for loops that do not cross each other;
/// [`filled_area`] with [`FillRule::EvenOdd`].
///
/// The depths are [`loop_depths`]': the parity count at one of a loop's points that lies on
/// no other loop (the rounded winding number of each other loop there, which is exact away
/// from that loop).
///
/// # Errors
/// As [`fill_nesting`].
///
/// # Examples
///
/// ```
/// use rs_contain::even_odd_area;
/// use rs_spline::{circle, Domain, Point};
/// // Both circles counter-clockwise: the signed sum is 5 pi, the filled annulus 3 pi.
/// let d = Domain::new(vec![
///     circle(Point::new(0.0, 0.0), 2.0).unwrap(),
///     circle(Point::new(0.0, 0.0), 1.0).unwrap(),
/// ])
/// .unwrap();
/// assert!((d.signed_area() - 5.0 * std::f64::consts::PI).abs() < 1e-12);
/// assert!((even_odd_area(&d).unwrap() - 3.0 * std::f64::consts::PI).abs() < 1e-12);
/// ```
pub fn even_odd_area(domain: &Domain) -> Result<f64, NestingError> {
    filled_area(domain, FillRule::EvenOdd)
}

/// For every loop of `domain`, its *depth*: the number of other loops that enclose it
/// (whatever their orientation), the nesting [`even_odd_area`] weighs the loops by: the
/// `depth` of [`fill_nesting`]. Under the even-odd rule, loop `i` bounds the filled region
/// with the region on its left when it is multiplied by `(-1)^depth_i` times the sign of its
/// signed area: outer boundaries counter-clockwise, holes clockwise (for loops that do not
/// cross each other).
///
/// # Errors
/// As [`fill_nesting`].
///
/// # Examples
///
/// ```
/// use rs_contain::loop_depths;
/// use rs_spline::{circle, Domain, Point};
/// let c = |x: f64, r: f64| circle(Point::new(x, 0.0), r).unwrap();
/// // A ring (two concentric circles) and a disc beside it.
/// let d = Domain::new(vec![c(0.0, 2.0), c(0.0, 1.0), c(5.0, 1.0)]).unwrap();
/// assert_eq!(loop_depths(&d), Ok(vec![0, 1, 0]));
/// ```
pub fn loop_depths(domain: &Domain) -> Result<Vec<usize>, NestingError> {
    Ok(fill_nesting(domain)?.iter().map(|n| n.depth).collect())
}

/// For every loop of `domain`, its [`LoopNesting`]: the number of other loops enclosing it,
/// the sum of their winding numbers there and its own orientation.
///
/// Both counts come from one point of the loop (a piece's start or middle, the first of up
/// to 64 that lies on no other loop): the winding number of each other loop there, rounded
/// (exact away from that loop). They describe the fill only where the loops do not cross
/// (then a loop lies wholly inside or outside each other one), which this function does not
/// check: [`fill_nesting`] does. `None` if every sampled point of some loop lies on another
/// loop (coincident loops), if a loop is open, or if there are more than
/// [`MAX_NESTED_LOOPS`] loops.
///
/// # Examples
///
/// ```
/// use rs_contain::loop_nesting;
/// use rs_spline::{circle, Domain, ParamCurve, Point};
/// let c = |r: f64| circle(Point::new(0.0, 0.0), r).unwrap();
/// // Three nested circles, the middle one clockwise.
/// let d = Domain::new(vec![c(3.0), c(2.0).reversed(), c(1.0)]).unwrap();
/// let n = loop_nesting(&d).unwrap();
/// let got: Vec<_> = n.iter().map(|n| (n.depth, n.winding, n.orientation)).collect();
/// assert_eq!(got, vec![(0, 0, 1), (1, 1, -1), (2, 0, 1)]);
/// ```
pub fn loop_nesting(domain: &Domain) -> Option<Vec<LoopNesting>> {
    nesting_of(domain).ok()
}

/// The [`loop_nesting`] that decides the fill: the loops' nesting once they are known not to
/// cross ([`boundary_crossing`]), what every Green's-theorem capability integrates the loops
/// with ([`curve_boundary_signs`], [`filled_area`]).
///
/// # Errors
/// [`NestingError::OpenLoop`], [`NestingError::TooManyLoops`] (more than
/// [`MAX_NESTED_LOOPS`]), [`NestingError::Crossing`] where the boundary certainly crosses
/// itself, [`NestingError::Coincident`] if every sampled point of some loop lies on another
/// loop, [`NestingError::Boxes`] if the boundary cannot be cut into monotone pieces.
///
/// # Examples
///
/// ```
/// use rs_contain::{fill_nesting, NestingError};
/// use rs_spline::{circle, Domain, Point};
/// let c = |x: f64| circle(Point::new(x, 0.0), 1.0).unwrap();
/// let overlapping = Domain::new(vec![c(-0.5), c(0.5)]).unwrap();
/// assert!(matches!(fill_nesting(&overlapping), Err(NestingError::Crossing(_))));
/// ```
pub fn fill_nesting(domain: &Domain) -> Result<Vec<LoopNesting>, NestingError> {
    let nesting = nesting_of(domain)?;
    if let Some(x) = boundary_crossing(domain).map_err(NestingError::Boxes)? {
        return Err(NestingError::Crossing(x));
    }
    Ok(nesting)
}

/// [`loop_nesting`] with the reason it has none.
fn nesting_of(domain: &Domain) -> Result<Vec<LoopNesting>, NestingError> {
    let loops = domain.loops();
    if let Some(open) = loops.iter().position(|l| !l.is_closed()) {
        return Err(NestingError::OpenLoop(open));
    }
    if loops.len() > MAX_NESTED_LOOPS {
        return Err(NestingError::TooManyLoops {
            loops: loops.len(),
            limit: MAX_NESTED_LOOPS,
        });
    }
    let pieces: Vec<Vec<_>> = loops
        .iter()
        .map(|l| {
            l.curves()
                .flat_map(|c| domain.curves()[c].to_bezier())
                .collect()
        })
        .collect();
    pieces
        .iter()
        .enumerate()
        .map(|(i, own)| {
            let orientation = if domain.loop_signed_area(i) < 0.0 {
                -1
            } else {
                1
            };
            let samples = own
                .iter()
                .flat_map(|b| [b.start_point(), b.point_at(0.5)])
                .take(64);
            samples
                .into_iter()
                .find_map(|q| enclosing_loops(&pieces, i, q))
                .map(|(depth, winding)| LoopNesting {
                    depth,
                    winding,
                    orientation,
                })
                .ok_or(NestingError::Coincident(i))
        })
        .collect()
}

/// The number of loops other than `own` that enclose `q` and the sum of their rounded
/// winding numbers there, or `None` if `q` is (within rounding) on one of them.
fn enclosing_loops(
    pieces: &[Vec<rs_spline::RationalBezier>],
    own: usize,
    q: Point,
) -> Option<(usize, i64)> {
    let mut stats = QueryStats::default();
    let (mut depth, mut winding) = (0, 0_i64);
    for (j, other) in pieces.iter().enumerate() {
        if j == own {
            continue;
        }
        let w: f64 = other
            .iter()
            .map(|b| curve_winding_number(b, q, &mut stats))
            .sum();
        if (w - w.round()).abs() > 1e-6 {
            return None;
        }
        // A loop of finitely many pieces winds a bounded number of times: the cast is exact.
        let w = w.round() as i64;
        if w.rem_euclid(2) == 1 {
            depth += 1;
        }
        winding = winding.saturating_add(w);
    }
    Some((depth, winding))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::circle;

    #[test]
    fn nested_loops_alternate_whatever_their_orientation() {
        let pi = std::f64::consts::PI;
        let c = |r: f64| circle(Point::new(0.0, 0.0), r).unwrap();
        // Three nested circles, the middle one clockwise: 9 pi - 4 pi + pi.
        let d = Domain::new(vec![c(3.0), c(2.0).reversed(), c(1.0)]).unwrap();
        assert!((even_odd_area(&d).unwrap() - 6.0 * pi).abs() < 1e-12);
        // Two disjoint circles add.
        let far = circle(Point::new(10.0, 0.0), 1.0).unwrap().reversed();
        let d = Domain::new(vec![c(1.0), far]).unwrap();
        assert!((even_odd_area(&d).unwrap() - 2.0 * pi).abs() < 1e-12);
    }

    #[test]
    fn nonzero_fills_nested_loops_of_one_orientation() {
        let pi = std::f64::consts::PI;
        let (r_out, r_in) = (2.0_f64, 0.75_f64);
        let c = |r: f64| circle(Point::new(0.5, -0.25), r).unwrap();
        let disc = pi * r_out * r_out;
        let annulus = pi * (r_out * r_out - r_in * r_in);
        let cases = [
            // (outer, inner) orientation: same ones fill the disc under nonzero.
            (c(r_out), c(r_in), disc),
            (c(r_out).reversed(), c(r_in).reversed(), disc),
            (c(r_out), c(r_in).reversed(), annulus),
            (c(r_out).reversed(), c(r_in), annulus),
        ];
        for (outer, inner, nonzero) in cases {
            let d = Domain::new(vec![outer, inner]).unwrap();
            let got = filled_area(&d, FillRule::NonZero).unwrap();
            assert!((got - nonzero).abs() < 1e-12, "{got} vs {nonzero}");
            let even_odd = filled_area(&d, FillRule::EvenOdd).unwrap();
            assert!(
                (even_odd - annulus).abs() < 1e-12,
                "{even_odd} vs {annulus}"
            );
            assert_eq!(even_odd.to_bits(), even_odd_area(&d).unwrap().to_bits());
        }
    }

    #[test]
    fn nonzero_windings_add_through_three_levels() {
        // Radii 3, 2, 1, all counter-clockwise: windings 1, 2, 3 inside; nonzero fills the
        // big disc and only the outer loop bounds it. With the middle one clockwise the
        // windings are 1, 0, 1: the same set as even-odd.
        let pi = std::f64::consts::PI;
        let c = |r: f64| circle(Point::new(0.0, 0.0), r).unwrap();
        let d = Domain::new(vec![c(3.0), c(2.0), c(1.0)]).unwrap();
        let n = loop_nesting(&d).unwrap();
        let changes: Vec<_> = n.iter().map(|n| n.fill_change(FillRule::NonZero)).collect();
        assert_eq!(changes, vec![1, 0, 0]);
        assert!((filled_area(&d, FillRule::NonZero).unwrap() - 9.0 * pi).abs() < 1e-12);
        let d = Domain::new(vec![c(3.0), c(2.0).reversed(), c(1.0)]).unwrap();
        let n = loop_nesting(&d).unwrap();
        let signs: Vec<_> = n
            .iter()
            .map(|n| n.boundary_sign(FillRule::NonZero))
            .collect();
        assert_eq!(signs, vec![1, 1, 1]); // each loop has the filled set on its left
        assert!((filled_area(&d, FillRule::NonZero).unwrap() - 6.0 * pi).abs() < 1e-12);
    }

    #[test]
    fn touching_loops_use_another_sample_point() {
        // The inner circle touches the outer one at (2, 0), its first sample point.
        let outer = circle(Point::new(0.0, 0.0), 2.0).unwrap();
        let inner = circle(Point::new(1.0, 0.0), 1.0).unwrap();
        let d = Domain::new(vec![outer, inner]).unwrap();
        let pi = std::f64::consts::PI;
        assert!((even_odd_area(&d).unwrap() - 3.0 * pi).abs() < 1e-12);
    }
}
