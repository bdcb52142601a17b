//! Where a domain's boundary crosses itself: what the fill of nested loops cannot describe.
//!
//! Green's-theorem capabilities (filled areas, cell coverage, cubature moments) integrate
//! each loop with one sign, taken from the loops' nesting ([`crate::fill_nesting`]). That is
//! exact for loops that do not cross (nested, apart, touching), and wrong for loops that
//! cross each other or themselves: the fill then changes along a loop, at the crossings.
//! [`boundary_crossing`] finds such a crossing, so that those capabilities refuse the domain
//! instead of answering wrong (classification and winding numbers take any loops).

use rs_boxes::{BoxError, BoxGrid, BoxOptions, MonotoneBox, MonotoneBoxes};
use rs_spline::prelude::*;
use rs_spline::{Domain, Point, RationalBezier, certain_crossing, closed_in_crossing};

/// A point where the boundary certainly crosses itself: [`boundary_crossing`]'s answer.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct BoundaryCrossing {
    /// The indices of the two curves that cross (equal for a curve that crosses itself).
    pub curves: (usize, usize),
    /// Where the loops cross: the parts that show it halved while a pair of halves still
    /// shows it ([`closed_in_crossing`]), so to rounding unless the crossing is at a joint.
    pub near: Point,
}

impl std::fmt::Display for BoundaryCrossing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (a, b) = self.curves;
        let (x, y) = (
            crate::significant(self.near.x),
            crate::significant(self.near.y),
        );
        if a == b {
            write!(f, "curve {a} crosses itself near ({x}, {y})")
        } else {
            write!(f, "curves {a} and {b} cross near ({x}, {y})")
        }
    }
}

/// The rounding margin of the tests, relative to the domain's size (its bounding box's
/// diagonal plus its largest coordinate): far above the rounding of a de Casteljau halving,
/// far below any feature a user means.
const RELATIVE_MARGIN: f64 = 1e-10;

/// Most halvings of a pair of pieces on the way to a certain crossing.
const MAX_HALVINGS: u32 = 40;

/// Most pairs of parts one pair of pieces is tested as: pieces that run along each other
/// (coincident or touching over a stretch) keep every pair of parts near each other, and the
/// search stops there (nothing certain).
const PAIR_BUDGET: usize = 4096;

/// The first point found where the closed loops of `domain` certainly cross each other or
/// themselves, if any.
///
/// # Method
/// The boundary is cut into monotone pieces (a monotone piece does not cross itself).
/// - *Inside pieces*: every two pieces whose rectangles meet, other than neighbours along a
///   loop, are halved together until their parts' rectangles part, or the control polygons
///   of two parts show a crossing ([`certain_crossing`]: each part's ends on opposite sides of
///   the other's slab).
/// - *At joints*: where a loop's joint (the end of one piece, the start of the next) lies on
///   another piece (its interior or its own joint), the two passes through that point cross
///   when their tangent directions there interleave (read from the control polygons: the
///   direction to the first control point off the joint).
///
/// What is not found: crossings where the curves are tangent (no side test decides them);
/// a boundary that runs along itself (a loop traversed twice, pieces coincident over a
/// stretch: [`crate::fill_nesting`] refuses whole coincident loops); a loop that turns
/// straight back at a joint and meets itself again before the turn.
///
/// # Errors
/// [`BoxError`] if the boundary cannot be cut into monotone pieces.
///
/// # Examples
///
/// ```
/// use rs_contain::boundary_crossing;
/// use rs_spline::{circle, Domain, Point};
/// let c = |x: f64| circle(Point::new(x, 0.0), 1.0).unwrap();
/// // Two overlapping discs cross; nested circles do not.
/// let overlapping = Domain::new(vec![c(-0.5), c(0.5)]).unwrap();
/// let x = boundary_crossing(&overlapping).unwrap().unwrap();
/// assert_eq!(x.curves, (0, 1));
/// assert!(x.near.distance(Point::new(0.0, 0.75f64.sqrt())) < 0.1 || x.near.distance(Point::new(0.0, -0.75f64.sqrt())) < 0.1);
/// let nested = Domain::new(vec![circle(Point::new(0.0, 0.0), 2.0).unwrap(), c(0.0)]).unwrap();
/// assert_eq!(boundary_crossing(&nested).unwrap(), None);
/// ```
pub fn boundary_crossing(domain: &Domain) -> Result<Option<BoundaryCrossing>, BoxError> {
    let boxes = MonotoneBoxes::new(domain, BoxOptions::DEFAULT.with_subdivisions(1))?;
    let pieces = boxes.pieces();
    let bbox = boxes.bounding_box();
    let scale = bbox.min.x.abs().max(bbox.max.x.abs()) + bbox.min.y.abs().max(bbox.max.y.abs());
    let margin = RELATIVE_MARGIN * (bbox.diagonal() + scale);
    let next = loop_neighbours(pieces);
    let beziers: Vec<RationalBezier> = pieces.iter().filter_map(bezier_of).collect();
    if beziers.len() != pieces.len() {
        return Ok(None);
    }
    if let Some(x) = crossing_inside_pieces(pieces, &beziers, &next, margin) {
        return Ok(Some(x));
    }
    Ok(crossing_at_joints(pieces, &beziers, &next, margin))
}

/// The rational Bezier curve of a monotone piece (local parameter `[0, 1]`).
fn bezier_of(b: &MonotoneBox) -> Option<RationalBezier> {
    b.piece().to_bezier().ok()
}

/// For each piece, the next piece along its loop when they join (its end is the next one's
/// start): the pieces are listed loop by loop in boundary order.
fn loop_neighbours(pieces: &[MonotoneBox]) -> Vec<Option<usize>> {
    let mut next = vec![None; pieces.len()];
    let mut first = 0;
    for k in 0..pieces.len() {
        let last_of_loop = pieces
            .get(k + 1)
            .is_none_or(|p| p.boundary_loop != pieces[k].boundary_loop);
        let n = if last_of_loop { first } else { k + 1 };
        if n != k && pieces[n].band.start == pieces[k].band.end {
            next[k] = Some(n);
        }
        if last_of_loop {
            first = k + 1;
        }
    }
    next
}

/// A certain crossing inside two pieces that are not neighbours along a loop (module docs).
fn crossing_inside_pieces(
    pieces: &[MonotoneBox],
    beziers: &[RationalBezier],
    next: &[Option<usize>],
    margin: f64,
) -> Option<BoundaryCrossing> {
    let rect = |b: &MonotoneBox| b.band.rectangle_near(margin);
    // A sweep along x over the rectangles: `active` holds those that reach the current one.
    let mut order: Vec<usize> = (0..pieces.len()).collect();
    order.sort_by(|&a, &b| rect(&pieces[a]).min.x.total_cmp(&rect(&pieces[b]).min.x));
    let mut active: Vec<usize> = Vec::new();
    for &i in &order {
        let ri = rect(&pieces[i]);
        active.retain(|&j| rect(&pieces[j]).max.x >= ri.min.x);
        for &j in &active {
            let neighbours = next[i] == Some(j) || next[j] == Some(i);
            if neighbours || !rect(&pieces[j]).overlaps(&ri) {
                continue;
            }
            let mut budget = PAIR_BUDGET;
            let (a, b) = (i.min(j), i.max(j));
            if let Some(near) =
                halved_crossing(&beziers[a], &beziers[b], margin, MAX_HALVINGS, &mut budget)
            {
                return Some(BoundaryCrossing {
                    curves: (pieces[a].curve, pieces[b].curve),
                    near,
                });
            }
        }
        active.push(i);
    }
    None
}

/// A certain crossing of `p` and `q`, halving both until their control boxes part or
/// [`certain_crossing`] shows one (at most `depth` more halvings, `budget` pairs tested).
fn halved_crossing(
    p: &RationalBezier,
    q: &RationalBezier,
    margin: f64,
    depth: u32,
    budget: &mut usize,
) -> Option<Point> {
    if *budget == 0 {
        return None;
    }
    *budget -= 1;
    let (bp, bq) = (p.control_bounding_box(), q.control_bounding_box());
    if !bp.grown_by(margin).overlaps(&bq) {
        return None;
    }
    if certain_crossing(p.control_points(), q.control_points(), margin).is_some() {
        // Closed in on to rounding, so that the error names where the loops cross.
        return closed_in_crossing(p.clone(), q.clone(), margin, MAX_HALVINGS as usize, |c| {
            c.control_points()
        });
    }
    if depth == 0 {
        return None;
    }
    let (p0, p1) = p.subdivide();
    let (q0, q1) = q.subdivide();
    for (a, b) in [(&p0, &q0), (&p0, &q1), (&p1, &q0), (&p1, &q1)] {
        if let Some(x) = halved_crossing(a, b, margin, depth - 1, budget) {
            return Some(x);
        }
    }
    None
}

/// One pass of the boundary through a point: the directions it leaves that point in,
/// backwards and forwards, and the curve each half belongs to.
struct Pass {
    back: Point,
    forth: Point,
    curves: (usize, usize),
}

/// The direction from `v` to the first of `points` off it, as a unit vector.
fn direction_from(v: Point, points: impl Iterator<Item = Point>) -> Option<Point> {
    points.map(|q| q - v).find_map(|d| {
        let len = d.length();
        (len > 0.0 && len.is_finite()).then(|| d / len)
    })
}

impl Pass {
    /// The pass through the joint from piece `a` (ending there) to piece `b`; `None` when
    /// either piece stays within `margin` of the joint (its control points do, so the piece
    /// does): its directions there are a feature below the rounding margin (a writer's
    /// wiggle of 1e-13 at a curve's end), which decides no crossing.
    fn at_joint(
        a: &RationalBezier,
        b: &RationalBezier,
        curves: (usize, usize),
        margin: f64,
    ) -> Option<Self> {
        let v = b.control_points()[0];
        let reaches =
            |c: &RationalBezier| c.control_points().iter().any(|&q| q.distance(v) > margin);
        if !(reaches(a) && reaches(b)) {
            return None;
        }
        Some(Self {
            back: direction_from(v, a.control_points().iter().rev().copied())?,
            forth: direction_from(v, b.control_points().iter().copied())?,
            curves,
        })
    }

    /// Whether `other` crosses this pass: its two directions lie on different sides of the
    /// wedge this pass makes (counter-clockwise from `back` to `forth`). `None` when two
    /// directions of different passes are too close to order (tangent passes).
    fn crossed_by(&self, other: &Pass) -> Option<bool> {
        const PARALLEL: f64 = 1e-9;
        for d in [other.back, other.forth] {
            for e in [self.back, self.forth] {
                if d.cross(e).abs() < PARALLEL && d.dot(e) > 0.0 {
                    return None;
                }
            }
        }
        let angle = |d: Point| {
            let a = self.back.cross(d).atan2(self.back.dot(d));
            if a < 0.0 {
                a + std::f64::consts::TAU
            } else {
                a
            }
        };
        let wedge = angle(self.forth);
        Some((angle(other.back) < wedge) != (angle(other.forth) < wedge))
    }
}

/// A crossing at a loop's joint lying on another piece (module docs).
fn crossing_at_joints(
    pieces: &[MonotoneBox],
    beziers: &[RationalBezier],
    next: &[Option<usize>],
    margin: f64,
) -> Option<BoundaryCrossing> {
    let grid = BoxGrid::new(pieces, margin);
    let mut previous = vec![None; pieces.len()];
    for (k, n) in next.iter().enumerate() {
        if let Some(n) = *n {
            previous[n] = Some(k);
        }
    }
    for (k, n) in next.iter().enumerate() {
        let Some(n) = *n else { continue };
        let v = pieces[k].band.end;
        let Some(pass) = Pass::at_joint(
            &beziers[k],
            &beziers[n],
            (pieces[k].curve, pieces[n].curve),
            margin,
        ) else {
            continue;
        };
        for &m in grid.candidates(v) {
            let m = m as usize;
            if m == k || m == n {
                continue;
            }
            let Some(t) = pieces[m].near_parameter(v, margin) else {
                continue;
            };
            // The other pass: through a joint of the other loop (found from its own joint
            // too: tested once, from the joint of the lower piece), or through the inside of
            // piece `m`, cut there.
            let other = if t == 0.0 || t == 1.0 {
                let (a, b) = if t == 0.0 {
                    (previous[m], Some(m))
                } else {
                    (Some(m), next[m])
                };
                let (Some(a), Some(b)) = (a, b) else { continue };
                if a <= k || a == n || b == k {
                    continue;
                }
                Pass::at_joint(
                    &beziers[a],
                    &beziers[b],
                    (pieces[a].curve, pieces[b].curve),
                    margin,
                )
            } else {
                let Ok((a, b)) = beziers[m].split_at(t) else {
                    continue;
                };
                Pass::at_joint(&a, &b, (pieces[m].curve, pieces[m].curve), margin)
            };
            if let Some(other) = other
                && pass.crossed_by(&other) == Some(true)
            {
                return Some(BoundaryCrossing {
                    curves: (pass.curves.1, other.curves.1),
                    near: v,
                });
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use rs_spline::{circle, polyline};

    fn poly(points: &[(f64, f64)]) -> rs_spline::NurbsCurve {
        let pts: Vec<Point> = points.iter().map(|&(x, y)| Point::new(x, y)).collect();
        polyline(&pts).unwrap()
    }

    fn crossing(curves: Vec<rs_spline::NurbsCurve>) -> Option<BoundaryCrossing> {
        boundary_crossing(&Domain::new(curves).unwrap()).unwrap()
    }

    /// Face 90 of `FreeCAD`'s `TSM_103_01_L_DV_A.stp`: its last arc starts with a span 9e-13
    /// long whose control points wiggle by 4e-13 at the joint, a writer's cut next to a knot.
    /// That is below the rounding margin: the loop does not cross itself.
    #[test]
    fn a_wiggle_below_the_margin_at_a_joint_is_no_crossing() {
        let p = Point::new;
        let line = |a: Point, b: Point| rs_spline::segment(a, b).unwrap();
        let curves = vec![
            line(
                p(-0.14605000000020651, -0.039133979554642574),
                p(-0.14605, -0.08428903421600009),
            ),
            rs_spline::NurbsCurve::new(
                2,
                vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
                vec![
                    p(-0.14605, -0.08428903421600009),
                    p(-1.1885991542759075e-16, 0.01835522432679393),
                    p(0.14604999999991072, -0.0842890342161269),
                ],
                Some(vec![1.0, 0.8181534085979254, 1.0]),
            )
            .unwrap(),
            line(
                p(0.14604999999991072, -0.0842890342161269),
                p(0.14605, -0.039133979555000094),
            ),
            rs_spline::NurbsCurve::new(
                2,
                vec![
                    1.0471975511957594,
                    1.0471975511957594,
                    1.0471975511957594,
                    1.047197551196649,
                    1.047197551196649,
                    2.0943951023938894,
                    2.0943951023938894,
                    2.0943951023938894,
                ],
                vec![
                    p(0.14605, -0.039133979555000094),
                    p(0.14605000000009305, -0.039133979554623714),
                    p(0.14605, -0.03913397955457),
                    p(-1.3768615877062894e-13, 0.04518802726069949),
                    p(-0.14605000000020651, -0.039133979554642574),
                ],
                Some(vec![
                    0.9999999999995755,
                    0.9999999999997877,
                    1.0,
                    0.7499999999998233,
                    0.75,
                ]),
            )
            .unwrap(),
        ];
        assert!(crossing(curves).is_none());
    }

    #[test]
    fn crossings_inside_pieces_are_found() {
        // A bowtie (its crossing inside two segments), a pentagram, two overlapping discs.
        let bowtie = poly(&[(0.0, 0.0), (2.0, 2.0), (2.0, 0.0), (0.0, 2.0), (0.0, 0.0)]);
        let x = crossing(vec![bowtie]).unwrap();
        assert!(x.near.distance(Point::new(1.0, 1.0)) < 1e-9, "{x}");
        assert_eq!(x.curves, (0, 0));
        let star: Vec<(f64, f64)> = (0..=5)
            .map(|k| {
                let a = std::f64::consts::FRAC_PI_2 + 4.0 * std::f64::consts::PI * k as f64 / 5.0;
                (a.cos(), a.sin())
            })
            .collect();
        let mut star = star;
        star[5] = star[0];
        assert!(crossing(vec![poly(&star)]).is_some());
        let c = |x: f64, r: f64| circle(Point::new(x, 0.0), r).unwrap();
        assert!(crossing(vec![c(-0.5, 1.0), c(0.5, 1.0)]).is_some());
        // A small circle poking out of a big one.
        assert!(crossing(vec![c(0.0, 2.0), c(1.95, 0.1)]).is_some());
    }

    #[test]
    fn crossings_at_joints_are_found_and_touches_are_not() {
        // A loop through (1, 1) twice, crossing there at its joints.
        let through = poly(&[
            (0.0, 0.0),
            (1.0, 1.0),
            (2.0, 2.0),
            (2.0, 0.0),
            (1.0, 1.0),
            (0.0, 2.0),
            (0.0, 0.0),
        ]);
        let x = crossing(vec![through]).unwrap();
        assert_eq!(x.near, Point::new(1.0, 1.0));
        // Two triangles touching at (1, 1): one loop through it twice, not crossing.
        let touching = poly(&[
            (0.0, 0.0),
            (1.0, 1.0),
            (2.0, 0.0),
            (2.0, 2.0),
            (1.0, 1.0),
            (0.0, 2.0),
            (0.0, 0.0),
        ]);
        assert_eq!(crossing(vec![touching]), None);
        // A square with a triangle whose vertex lies on the square's side, inside or across.
        let square = || poly(&[(0.0, 0.0), (4.0, 0.0), (4.0, 4.0), (0.0, 4.0), (0.0, 0.0)]);
        let inside = poly(&[(4.0, 2.0), (2.0, 3.0), (2.0, 1.0), (4.0, 2.0)]);
        assert_eq!(crossing(vec![square(), inside]), None);
        let across = poly(&[(4.0, 2.0), (5.0, 3.0), (3.0, 1.0), (4.0, 2.0)]);
        assert!(crossing(vec![square(), across]).is_some());
        // Nested, apart and tangent circles do not cross.
        let c = |x: f64, r: f64| circle(Point::new(x, 0.0), r).unwrap();
        assert_eq!(crossing(vec![c(0.0, 2.0), c(0.0, 1.0)]), None);
        assert_eq!(crossing(vec![c(0.0, 1.0), c(3.0, 1.0)]), None);
        assert_eq!(crossing(vec![c(0.0, 2.0), c(1.0, 1.0)]), None);
        assert_eq!(crossing(vec![c(0.0, 1.0), c(2.0, 1.0)]), None);
        // Every fixture is a domain of loops that do not cross.
        for case in rs_testkit::fixtures() {
            assert_eq!(
                boundary_crossing(&case.domain).unwrap(),
                None,
                "{}",
                case.name
            );
        }
    }
}
