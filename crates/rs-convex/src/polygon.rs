//! Convex polygons clipped by half-planes.

use rs_spline::Point;

use crate::clip::{Cut, clip_cycle};

/// A convex polygon, vertices counter-clockwise (empty when clipped away).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ConvexPolygon {
    vertices: Vec<Point>,
}

impl ConvexPolygon {
    /// The rectangle `[xmin, xmax] x [ymin, ymax]`.
    pub fn rectangle(xmin: f64, xmax: f64, ymin: f64, ymax: f64) -> Self {
        Self {
            vertices: vec![
                Point::new(xmin, ymin),
                Point::new(xmax, ymin),
                Point::new(xmax, ymax),
                Point::new(xmin, ymax),
            ],
        }
    }

    /// The vertices, counter-clockwise.
    pub fn vertices(&self) -> &[Point] {
        &self.vertices
    }

    /// True if nothing is left (fewer than three vertices or no area).
    pub fn is_empty(&self) -> bool {
        self.vertices.len() < 3 || self.area() <= 0.0
    }

    /// Area by the shoelace formula.
    pub fn area(&self) -> f64 {
        let n = self.vertices.len();
        if n < 3 {
            return 0.0;
        }
        0.5 * (0..n)
            .map(|i| self.vertices[i].cross(self.vertices[(i + 1) % n]))
            .sum::<f64>()
    }

    /// Centroid of the vertices (a point inside a non-empty polygon).
    pub fn vertex_centroid(&self) -> Option<Point> {
        let n = self.vertices.len();
        (n > 0).then(|| {
            let s = self
                .vertices
                .iter()
                .fold(Point::new(0.0, 0.0), |acc, &p| acc + p);
            s / n as f64
        })
    }

    /// The part where `a1 x + a2 y + b >= 0` (one Sutherland-Hodgman pass). A half-plane
    /// with `(a1, a2) = 0` keeps everything if `b > 0` and nothing otherwise. `scale` (a
    /// length typical of the polygon) sets the rounding threshold below which a vertex counts
    /// as on the line.
    pub fn clip(&self, a1: f64, a2: f64, b: f64, scale: f64) -> Self {
        match Cut::new(a1.hypot(a2), b, scale) {
            Cut::All(true) => self.clone(),
            Cut::All(false) => Self::default(),
            Cut::By { eps } => Self {
                vertices: clip_cycle(
                    &self.vertices,
                    |p: Point| a1 * p.x + a2 * p.y + b,
                    eps,
                    scale,
                    |_| {},
                ),
            },
        }
    }

    /// True if `p` satisfies every edge's half-plane within `eps`.
    pub fn contains(&self, p: Point, eps: f64) -> bool {
        let n = self.vertices.len();
        n >= 3
            && (0..n).all(|i| {
                let (a, b) = (self.vertices[i], self.vertices[(i + 1) % n]);
                (b - a).cross(p - a) >= -eps * (b - a).length()
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_a_square_by_a_diagonal_halves_it() {
        let sq = ConvexPolygon::rectangle(0.0, 2.0, 0.0, 2.0);
        let half = sq.clip(-1.0, -1.0, 2.0, 2.0); // x + y <= 2
        assert_eq!(half.vertices().len(), 3);
        assert!((half.area() - 2.0).abs() < 1e-15);
        assert!(sq.clip(1.0, 0.0, -3.0, 2.0).is_empty());
        assert_eq!(sq.clip(0.0, 0.0, 1.0, 2.0), sq);
        assert!(sq.clip(0.0, 0.0, -1.0, 2.0).is_empty());
        // A line through a vertex adds no sliver.
        let corner = sq.clip(1.0, -1.0, 0.0, 2.0); // x >= y
        assert_eq!(corner.vertices().len(), 3);
        assert!(corner.contains(Point::new(1.5, 0.5), 1e-12));
        assert!(!corner.contains(Point::new(0.5, 1.5), 1e-12));
    }
}
