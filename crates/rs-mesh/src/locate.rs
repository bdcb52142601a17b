//! Point location in a curved triangulation.

use rs_contain::Locate;
use rs_contain::{Classifier, ContainOptions, Location};
use rs_spline::prelude::*;
use rs_spline::{BoundingBox, Domain, Point, segment};
use spade::{PositionInTriangulation, Triangulation as _};

use crate::{CurvedTriangulation, MeshError};

/// A lens (arc and chord) whose area is below this times its box's squared diagonal has no
/// room for a point between arc and chord.
const EMPTY_LENS: f64 = 1e-14;

/// Answers "which curved triangle holds this point?" exactly: the domain's containment test
/// (inRS) first, then the companion triangle by `spade`'s walk, and for points between a
/// boundary arc and its chord (outside every companion triangle) an exact containment test
/// against that lens (arc + chord), which is what the paper's extended triangulation
/// approximates with a ring of straight triangles.
#[derive(Debug)]
pub struct CurvedLocator<'a> {
    mesh: &'a CurvedTriangulation,
    domain: Classifier,
    lenses: Vec<(BoundingBox, usize, Classifier)>,
}

impl<'a> CurvedLocator<'a> {
    /// Prepares the containment tests of the domain and of every lens with area.
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
        Ok(Self {
            mesh,
            domain,
            lenses,
        })
    }

    /// The curved triangle holding `p` (closed triangles: points on shared edges get one of
    /// the neighbours), or `None` outside the domain.
    pub fn triangle_at(&self, p: Point) -> Option<usize> {
        if !p.is_finite() || self.domain.locate(p) == Location::Outside {
            return None;
        }
        let m = self.mesh;
        let kept = |f: usize| m.face_triangle.get(&f).copied();
        match m.cdt.locate(spade::Point2::new(p.x, p.y)) {
            PositionInTriangulation::OnFace(f) => {
                if let Some(t) = kept(f.index()) {
                    return Some(t);
                }
            }
            PositionInTriangulation::OnEdge(e) => {
                let e = m.cdt.directed_edge(e);
                for f in [e.face(), e.rev().face()] {
                    if let Some(t) = f.as_inner().and_then(|f| kept(f.fix().index())) {
                        return Some(t);
                    }
                }
            }
            PositionInTriangulation::OnVertex(v) => {
                for e in m.cdt.vertex(v).out_edges() {
                    if let Some(t) = e.face().as_inner().and_then(|f| kept(f.fix().index())) {
                        return Some(t);
                    }
                }
            }
            _ => {}
        }
        for (bbox, i, lens) in &self.lenses {
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
