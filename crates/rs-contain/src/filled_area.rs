//! The area a domain fills under the even-odd rule.

use rs_spline::prelude::*;
use rs_spline::{Domain, Point};

use crate::{QueryStats, curve_winding_number};

/// Most loops [`even_odd_area`] nests (its work is quadratic in the number of loops).
pub const MAX_NESTED_LOOPS: usize = 10_000;

/// The area filled by `domain` under the even-odd rule: `sum_i (-1)^depth_i |A_i|`, where
/// `A_i` is the signed area of loop `i` and `depth_i` the number of other loops that enclose it
/// (whatever their orientation). This is the measure of the set of points of odd crossing
/// parity, the set the crossing methods call inside, for loops that do not cross each other.
///
/// The depths are [`loop_depths`]': the parity count at one of a loop's points that lies on
/// no other loop (the rounded winding number of each other loop there, which is exact away
/// from that loop). `None` where [`loop_depths`] is `None`: coincident loops, an open loop,
/// or more than [`MAX_NESTED_LOOPS`] loops.
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
pub fn even_odd_area(domain: &Domain) -> Option<f64> {
    let depths = loop_depths(domain)?;
    let total = depths
        .iter()
        .enumerate()
        .map(|(i, &depth)| {
            let area = domain.loop_signed_area(i).abs();
            if depth % 2 == 0 { area } else { -area }
        })
        .sum();
    Some(total)
}

/// For every loop of `domain`, its *depth*: the number of other loops that enclose it
/// (whatever their orientation), the nesting [`even_odd_area`] weighs the loops by. Under the
/// even-odd rule, loop `i` bounds the filled region with the region on its left when it is
/// multiplied by `(-1)^depth_i` times the sign of its signed area: outer boundaries
/// counter-clockwise, holes clockwise (for loops that do not cross each other).
///
/// A loop's depth is the parity count at one of its points (a piece's start or middle) that
/// lies on no other loop. `None` if every sampled point of some loop lies on another loop
/// (coincident loops), if a loop is open, or if there are more than [`MAX_NESTED_LOOPS`]
/// loops.
///
/// # Examples
///
/// ```
/// use rs_contain::loop_depths;
/// use rs_spline::{circle, Domain, Point};
/// let c = |x: f64, r: f64| circle(Point::new(x, 0.0), r).unwrap();
/// // A ring (two concentric circles) and a disc beside it.
/// let d = Domain::new(vec![c(0.0, 2.0), c(0.0, 1.0), c(5.0, 1.0)]).unwrap();
/// assert_eq!(loop_depths(&d), Some(vec![0, 1, 0]));
/// ```
pub fn loop_depths(domain: &Domain) -> Option<Vec<usize>> {
    let loops = domain.loops();
    if loops.len() > MAX_NESTED_LOOPS || loops.iter().any(|l| !l.is_closed()) {
        return None;
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
            let samples = own
                .iter()
                .flat_map(|b| [b.start_point(), b.point_at(0.5)])
                .take(64);
            samples
                .into_iter()
                .find_map(|q| enclosing_loops(&pieces, i, q))
        })
        .collect()
}

/// The number of loops other than `own` that enclose `q`, or `None` if `q` is (within
/// rounding) on one of them.
fn enclosing_loops(
    pieces: &[Vec<rs_spline::RationalBezier>],
    own: usize,
    q: Point,
) -> Option<usize> {
    let mut stats = QueryStats::default();
    let mut depth = 0;
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
        if (w.round() as i64).rem_euclid(2) == 1 {
            depth += 1;
        }
    }
    Some(depth)
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
    fn touching_loops_use_another_sample_point() {
        // The inner circle touches the outer one at (2, 0), its first sample point.
        let outer = circle(Point::new(0.0, 0.0), 2.0).unwrap();
        let inner = circle(Point::new(1.0, 0.0), 1.0).unwrap();
        let d = Domain::new(vec![outer, inner]).unwrap();
        let pi = std::f64::consts::PI;
        assert!((even_odd_area(&d).unwrap() - 3.0 * pi).abs() < 1e-12);
    }
}
