//! Point location in a curved triangulation.

use rs_contain::{Classifier, ContainOptions, Locate, Location, PointQuery};
use rs_spline::grid::{CellIndex, GridFrame};
use rs_spline::prelude::*;
use rs_spline::{BoundingBox, Domain, Point, segment};

use crate::{CurvedTriangulation, MeshError};

/// A lens (arc and chord) whose area is below this times its box's squared diagonal has no
/// room for a point between arc and chord.
const EMPTY_LENS: f64 = 1e-14;

/// A point is in a companion triangle when its barycentric coordinates are all at least this
/// (so points on a shared edge find a triangle whatever the rounding).
const ON_EDGE: f64 = -1e-12;

/// A point whose barycentric coordinates in a companion triangle are all above this is inside
/// it by far more than rounding, so no other (non-overlapping) triangle can hold it: the
/// search stops there.
const CLEARLY_INSIDE: f64 = 1e-9;

/// The barycentric coordinates of a companion triangle `a b c` as affine functions of the
/// point, relative to `a` (so that translation does not cost digits):
/// `b_1 = 1 + g[0] (x - a_x) + g[1] (y - a_y)`, `b_2 = g[2] (x - a_x) + g[3] (y - a_y)`,
/// `b_3 = 1 - b_1 - b_2`. Two products and no division per coordinate.
#[derive(Clone, Copy, Debug)]
struct BarycentricMap {
    a: Point,
    g: [f64; 4],
}

impl BarycentricMap {
    fn new([a, b, c]: [Point; 3]) -> Self {
        let area = (b - a).cross(c - a);
        Self {
            a,
            g: [
                (b.y - c.y) / area,
                (c.x - b.x) / area,
                (c.y - a.y) / area,
                (a.x - c.x) / area,
            ],
        }
    }

    /// The smallest barycentric coordinate of `p`.
    fn smallest(&self, p: Point) -> f64 {
        let (dx, dy) = (p.x - self.a.x, p.y - self.a.y);
        let b1 = 1.0 + self.g[0] * dx + self.g[1] * dy;
        let b2 = self.g[2] * dx + self.g[3] * dy;
        b1.min(b2).min(1.0 - b1 - b2)
    }
}

/// Answers "which curved triangle holds this point?" exactly: the domain's containment test
/// (inRS, through its grid locator) first, then the companion triangle, found through a
/// uniform grid of the triangles, and for points between a boundary arc and its chord (outside
/// every companion triangle) an exact containment test against that lens (arc + chord), which
/// is what the paper's extended triangulation approximates with a ring of straight triangles.
/// Works on any curved triangulation, refined ones included.
#[derive(Debug)]
pub struct CurvedLocator<'a> {
    mesh: &'a CurvedTriangulation,
    domain: Classifier,
    triangles: CellIndex<u32>,
    /// Per triangle, its barycentric coordinates as affine maps.
    barycentric: Vec<BarycentricMap>,
    lenses: Vec<(BoundingBox, usize, Classifier)>,
    lens_index: CellIndex<u32>,
}

impl<'a> CurvedLocator<'a> {
    /// Prepares the containment tests of the domain and of every lens with area, and the grids
    /// of triangles and lenses.
    ///
    /// # Errors
    /// Containment errors (never for a triangulation built by this crate).
    pub fn new(mesh: &'a CurvedTriangulation) -> Result<Self, MeshError> {
        let domain = Classifier::new(mesh.domain(), ContainOptions::default())?;
        let mut lenses = Vec::new();
        for (i, arc) in mesh.arcs().iter().enumerate() {
            let c = mesh.arc_curve(arc)?;
            if c.degree() == 1 && c.control_points().len() == 2 {
                continue;
            }
            let (a, b) = (mesh.vertices()[arc.from], mesh.vertices()[arc.to]);
            let bbox = c.bounding_box().including(a).including(b);
            let lens = Domain::new(vec![c, segment(b, a)?])?;
            if lens.signed_area().abs() <= EMPTY_LENS * bbox.diagonal().powi(2) {
                continue;
            }
            let classifier = Classifier::new(&lens, ContainOptions::default())?;
            lenses.push((bbox, i, classifier));
        }
        // About four cells per triangle, near square (at most 2^20): a few candidates per cell.
        let frame = GridFrame::near_square(
            mesh.domain().bounding_box(),
            (4 * mesh.triangles().len()).clamp(1, 1 << 20),
        );
        let barycentric = mesh
            .triangles()
            .iter()
            .map(|t| BarycentricMap::new(t.map(|i| mesh.vertices()[i])))
            .collect();
        let mut pairs = Vec::new();
        for (t, tri) in mesh.triangles().iter().enumerate() {
            let b = BoundingBox::from_points(tri.iter().map(|&v| mesh.vertices()[v]));
            if let Some(b) = b {
                frame.for_cells_in(b, |c| pairs.push((c, t as u32)));
            }
        }
        let mut lens_pairs = Vec::new();
        for (l, (b, _, _)) in lenses.iter().enumerate() {
            frame.for_cells_in(*b, |c| lens_pairs.push((c, l as u32)));
        }
        Ok(Self {
            mesh,
            domain,
            triangles: CellIndex::new(frame, pairs),
            barycentric,
            lenses,
            lens_index: CellIndex::new(frame, lens_pairs),
        })
    }

    /// The curved triangle holding `p` (closed triangles: points on shared edges get one of
    /// the neighbours), or `None` outside the domain.
    pub fn triangle_at(&self, p: Point) -> Option<usize> {
        if !p.is_finite() || self.domain.locator().locate(p) == Location::Outside {
            return None;
        }
        let m = self.mesh;
        // The companion triangle holding p: the first one it is clearly inside, else the one
        // holding it best (largest smallest barycentric coordinate) within the edge tolerance.
        let mut best = (usize::MAX, ON_EDGE);
        for &t in self.triangles.at(p) {
            let b = self.barycentric[t as usize].smallest(p);
            if b > CLEARLY_INSIDE {
                return Some(t as usize);
            }
            if b >= best.1 {
                best = (t as usize, b);
            }
        }
        if best.0 != usize::MAX {
            return Some(best.0);
        }
        for &l in self.lens_index.at(p) {
            let (bbox, i, lens) = &self.lenses[l as usize];
            if bbox.contains(p) && lens.locate(p) != Location::Outside {
                return Some(m.arcs()[*i].triangle);
            }
        }
        // Only points within the boundary tolerance of the domain get here: the triangle
        // whose companion is nearest.
        self.nearest_triangle(p)
    }

    /// The triangle whose companion (straight-sided) is nearest to `p`, the lowest index among
    /// equally near ones: from the cells round `p` in squares of doubling half-side `r`, until
    /// the nearest found is within `r` (a nearer one's box meets the square, so its cells were
    /// searched) or the square covers the grid: a scan of every triangle would cost `O(T)` per
    /// point just outside the domain.
    fn nearest_triangle(&self, p: Point) -> Option<usize> {
        let m = self.mesh;
        let frame = self.triangles.frame();
        let grid = frame.bbox();
        let (cw, ch) = frame.cell_size();
        let beyond = (grid.min.x - p.x)
            .max(p.x - grid.max.x)
            .max(grid.min.y - p.y)
            .max(p.y - grid.max.y)
            .max(0.0);
        // Every triangle's box lies in the grid: a square this large meets them all.
        let everything = 2.0 * (grid.diagonal() + beyond);
        let mut r = cw.max(ch).max(everything / 1024.0);
        loop {
            let mut best: Option<(f64, usize)> = None;
            frame.for_cells_in(BoundingBox::from_point(p).grown_by(r), |c| {
                for &t in self.triangles.cell(c) {
                    let d = (distance_to_triangle(m, t as usize, p), t as usize);
                    if best.is_none_or(|b| d.0.total_cmp(&b.0).then(d.1.cmp(&b.1)).is_lt()) {
                        best = Some(d);
                    }
                }
            });
            match best {
                Some((d, t)) if d <= r => return Some(t),
                _ if r >= everything || !r.is_finite() => return best.map(|b| b.1),
                _ => r *= 2.0,
            }
        }
    }

    /// [`CurvedLocator::triangle_at`] of every point, in order, on all threads (with the
    /// `parallel` feature of rs-contain, as its locators).
    pub fn triangles_at(&self, points: &[Point]) -> Vec<Option<usize>> {
        use rayon::prelude::*;
        points
            .par_iter()
            .with_min_len(1024)
            .map(|&p| self.triangle_at(p))
            .collect()
    }
}

fn distance_to_triangle(m: &CurvedTriangulation, t: usize, p: Point) -> f64 {
    let v = m.triangles()[t].map(|i| m.vertices()[i]);
    (0..3)
        .map(|k| {
            let (a, b) = (v[k], v[(k + 1) % 3]);
            let ab = b - a;
            let s = ((p - a).dot(ab) / ab.dot(ab)).clamp(0.0, 1.0);
            p.distance(a + ab * s)
        })
        .fold(f64::INFINITY, f64::min)
}

impl PointQuery<Location> for CurvedLocator<'_> {
    /// Containment in the curved triangulation's domain (the union of its curved triangles):
    /// the domain's own exact test, boundary band included.
    fn value(&self, p: Point) -> Location {
        self.domain.locate(p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::well_spaced_points;

    /// The grid search gives the triangle a scan of all of them gives (the lowest index of the
    /// nearest), for points just outside the boundary (where `triangle_at` uses it), inside,
    /// and far outside the grid.
    #[test]
    fn the_nearest_triangle_is_the_one_a_full_scan_finds() {
        let d = Domain::new(vec![
            rs_spline::circle(Point::new(0.3, -0.2), 1.0).unwrap(),
            rs_spline::circle(Point::new(0.3, -0.2), 0.4).unwrap(),
        ])
        .unwrap();
        let mesh = CurvedTriangulation::new(&d, &well_spaced_points(&d, 12).unwrap()).unwrap();
        let loc = CurvedLocator::new(&mesh).unwrap();
        let scan = |p: Point| {
            (0..mesh.triangles().len()).min_by(|&s, &t| {
                distance_to_triangle(&mesh, s, p).total_cmp(&distance_to_triangle(&mesh, t, p))
            })
        };
        let mut points = Vec::new();
        for i in 0..400 {
            let a = std::f64::consts::TAU * i as f64 / 400.0;
            let (c, s) = (a.cos(), a.sin());
            for r in [1.0 + 1e-13, 1.0 + 1e-3, 0.4 - 1e-13, 0.7, 3.0, 1e6] {
                points.push(Point::new(0.3 + r * c, -0.2 + r * s));
            }
        }
        for p in points {
            assert_eq!(loc.nearest_triangle(p), scan(p), "{p:?}");
        }
        // Just outside, within the boundary tolerance: located, not lost.
        let p = Point::new(0.3 + 1.0 + 1e-13, -0.2);
        assert_eq!(loc.triangle_at(p), scan(p));
    }
}
