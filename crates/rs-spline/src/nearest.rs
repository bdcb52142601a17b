//! The point of a domain's boundary nearest to a given point, over every Bezier piece.

use crate::curve::prelude::*;
use crate::{BoundingBox, Domain, Point, RationalBezier};

/// A point of the boundary: its curve, its parameter on that curve, and its distance from the
/// point asked about.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NearestPoint {
    /// Index of the curve in [`Domain::curves`].
    pub curve: usize,
    /// The curve's own parameter (in its knot domain).
    pub u: f64,
    /// The distance from the point asked about.
    pub distance: f64,
}

/// A domain's Bezier pieces with their control boxes, for nearest-point queries
/// ([`NearestBoundary::nearest`]).
#[derive(Clone, Debug)]
pub struct NearestBoundary {
    pieces: Vec<(usize, RationalBezier, BoundingBox)>,
}

impl NearestBoundary {
    /// The pieces of every curve of `domain` ([`Domain::bezier_pieces`]).
    pub fn new(domain: &Domain) -> Self {
        Self {
            pieces: domain
                .bezier_pieces()
                .into_iter()
                .map(|(c, b)| {
                    let bbox = b.control_bounding_box();
                    (c, b, bbox)
                })
                .collect(),
        }
    }

    /// A point of the boundary nearest to `p`, exactly (each piece by
    /// [`RationalBezier::nearest_to`]), found without solving every piece: the nearest piece
    /// end bounds the distance, and a piece whose control box (which holds it) lies farther
    /// is skipped; the others are solved in order of their boxes' distance until the next box
    /// is farther than the best point found. Among equally near points the first piece (in
    /// boundary order) wins, and a piece end is given by its exact knot, so a point at the
    /// seam of a closed curve is `u = start` or `u = end` of that curve, never in between.
    pub fn nearest(&self, p: Point) -> NearestPoint {
        let bound = self
            .pieces
            .iter()
            .map(|(_, b, _)| b.start_point().distance(p).min(b.end_point().distance(p)))
            .fold(f64::INFINITY, f64::min);
        let mut near: Vec<(f64, usize)> = self
            .pieces
            .iter()
            .enumerate()
            .map(|(i, (_, _, bbox))| (box_distance(bbox, p), i))
            .filter(|&(d, _)| d <= bound)
            .collect();
        near.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let mut best: Option<(f64, usize, f64)> = None;
        for (reach, i) in near {
            if best.is_some_and(|(d, _, _)| reach > d) {
                break;
            }
            let (t, d) = self.pieces[i].1.nearest_to(p);
            let better = match best {
                None => true,
                Some((bd, bi, _)) => d < bd || (d == bd && i < bi),
            };
            if better {
                best = Some((d, i, t));
            }
        }
        // A domain has a curve, and the piece with the nearest end is never skipped (its box
        // holds that end); the fallback is the first curve's start.
        let (distance, i, t) = best.unwrap_or((f64::INFINITY, 0, 0.0));
        let Some((curve, piece, _)) = self.pieces.get(i) else {
            return NearestPoint {
                curve: 0,
                u: 0.0,
                distance,
            };
        };
        let (u0, u1) = piece.knot_span();
        let u = if t <= 0.0 {
            u0
        } else if t >= 1.0 {
            u1
        } else {
            (u0 + t * (u1 - u0)).clamp(u0, u1)
        };
        NearestPoint {
            curve: *curve,
            u,
            distance,
        }
    }
}

/// The distance from `p` to the box (0 inside it).
fn box_distance(b: &BoundingBox, p: Point) -> f64 {
    let dx = (b.min.x - p.x).max(p.x - b.max.x).max(0.0);
    let dy = (b.min.y - p.y).max(p.y - b.max.y).max(0.0);
    dx.hypot(dy)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{NurbsCurve, circle};

    /// A closed rational B-spline whose parametrisation is far from uniform near its seam
    /// (weights 2 then 0.5 at the end make it fast there).
    fn fast_seam() -> NurbsCurve {
        let n = 14;
        let pts: Vec<Point> = (0..n)
            .map(|k| {
                let th = std::f64::consts::TAU * (k % (n - 1)) as f64 / (n - 1) as f64;
                let r = 1.0 + 0.25 * (3.0 * th).sin();
                Point::new(1.3 * r * th.cos(), r * th.sin())
            })
            .collect();
        let weights: Vec<f64> = (0..n).map(|k| if k % 2 == 0 { 2.0 } else { 0.5 }).collect();
        let p = 5;
        let spans = n - p;
        let mut knots = vec![0.0; p + 1];
        knots.extend((1..spans).map(|i| i as f64 / spans as f64));
        knots.extend(vec![1.0; p + 1]);
        NurbsCurve::new(p, knots, pts, Some(weights)).unwrap()
    }

    #[test]
    fn points_on_the_curve_find_their_own_parameter_even_next_to_the_seam() {
        let c = fast_seam();
        let d = Domain::new(vec![c.clone()]).unwrap();
        let near = NearestBoundary::new(&d);
        let us = [
            0.0,
            1e-9,
            1e-4,
            0.003,
            0.25,
            0.5,
            0.997,
            1.0 - 1e-4,
            1.0 - 1e-9,
            1.0,
        ];
        for &u in &us {
            let q = c.point_at(u);
            let found = near.nearest(q);
            assert!(found.distance <= 1e-15, "u {u}: {found:?}");
            let back = c.point_at(found.u);
            assert!(back.distance(q) <= 4e-15, "u {u}: {found:?}");
            if u > 0.0 && u < 1.0 {
                // Never confused with the seam: the same side of it.
                assert!((found.u - u).abs() < 1e-9, "u {u}: {found:?}");
            }
        }
    }

    #[test]
    fn the_nearest_point_beats_a_dense_scan_off_the_curve() {
        let c = fast_seam();
        let d = Domain::new(vec![c.clone(), circle(Point::new(0.1, 0.0), 0.3).unwrap()]).unwrap();
        let near = NearestBoundary::new(&d);
        for k in 0..200 {
            let t = k as f64 * 0.618_034;
            let q = Point::new(
                1.6 * (t.fract() - 0.5) * 2.0,
                1.4 * ((t * 1.3).fract() - 0.5) * 2.0,
            );
            let found = near.nearest(q);
            let point = d.curves()[found.curve].point_at(found.u);
            assert!((point.distance(q) - found.distance).abs() < 1e-12, "{q:?}");
            for (ci, curve) in d.curves().iter().enumerate() {
                let (a, b) = curve.param_range();
                for j in 0..=20_000 {
                    let u = a + (b - a) * j as f64 / 20_000.0;
                    let scan = curve.point_at(u).distance(q);
                    assert!(found.distance <= scan + 1e-12, "{q:?} curve {ci} u {u}");
                }
            }
        }
    }

    #[test]
    fn the_centre_of_a_circle_is_equally_far_from_all_of_it() {
        let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 2.0).unwrap()]).unwrap();
        let found = NearestBoundary::new(&d).nearest(Point::new(0.0, 0.0));
        assert!((found.distance - 2.0).abs() < 1e-15, "{found:?}");
    }
}
