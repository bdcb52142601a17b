//! Point location in a curved triangulation.

use rs_contain::Locate;
use rs_contain::{Classifier, ContainOptions, Location};
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
        (0..m.triangles().len()).min_by(|&s, &t| {
            distance_to_triangle(m, s, p).total_cmp(&distance_to_triangle(m, t, p))
        })
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

impl Locate for CurvedLocator<'_> {
    /// Containment in the curved triangulation's domain (the union of its curved triangles):
    /// the domain's own exact test, boundary band included.
    fn locate(&self, p: Point) -> Location {
        self.domain.locate(p)
    }
}
