//! Scattered-data interpolation on a curved domain (Schumaker and Yu 2021, Problem 9.1 and
//! Sections 9-10): a curved triangulation whose vertices are the data points, then a `C^1`
//! spline through the data, by a two-stage method (local least-squares derivative estimates,
//! then Hermite macro-elements: [`crate::hermite`]) or by minimal energy
//! ([`crate::minimal_energy`]).

use std::collections::HashMap;

use rs_contain::{Classifier, ContainOptions, Locate, Location};
use rs_mesh::{BoundaryPoint, CurvedTriangulation, WellSpacedPoints};
use rs_spline::prelude::*;
use rs_spline::{Domain, NearestBoundary, Point};

use crate::bb::Jet;
use crate::hermite::{C1Space, HermiteData, hermite_interpolate, macro_triangles};
use crate::local_fit::{LocalFits, LocalPolynomial};
use crate::{Spline, TriSplineError, minimal_energy};

/// Data points within this distance, relative to the domain's bounding-box diagonal, of the
/// boundary count as boundary points (they become boundary vertices, moved onto the curve).
pub const BOUNDARY_TOLERANCE: f64 = 1e-9;

/// The most data points accepted (each becomes a vertex).
pub const MAX_DATA_POINTS: usize = rs_mesh::MAX_MESH_VERTICES;

/// Scattered data on a domain, checked and sorted into interior and boundary points.
#[derive(Clone, Debug)]
pub struct ScatteredData {
    /// The data sites (boundary points moved onto the boundary).
    sites: Vec<Point>,
    values: Vec<f64>,
    points: WellSpacedPoints,
}

impl ScatteredData {
    /// The data `values[i]` at `points[i]`: every point must lie in the closed domain and no
    /// two may coincide; points within [`BOUNDARY_TOLERANCE`] of the boundary are taken as
    /// boundary points, at the nearest point of the curve.
    ///
    /// # Errors
    /// [`TriSplineError::DataPoint`] naming the first bad point (not finite, outside the domain,
    /// or equal to an earlier one); [`TriSplineError::Data`] for lengths that differ or too many
    /// points; [`rs_mesh::MeshError::TooManyPieces`] for a boundary the triangulation refuses;
    /// containment errors for an open boundary.
    pub fn new(domain: &Domain, points: &[Point], values: &[f64]) -> Result<Self, TriSplineError> {
        if points.len() != values.len() {
            return Err(TriSplineError::Data(format!(
                "{} points and {} values",
                points.len(),
                values.len()
            )));
        }
        if points.len() > MAX_DATA_POINTS {
            return Err(TriSplineError::Data(format!(
                "{} points exceed the limit {MAX_DATA_POINTS}",
                points.len()
            )));
        }
        let bad = |index: usize, reason: &'static str| TriSplineError::DataPoint {
            index,
            x: points[index].x,
            y: points[index].y,
            reason,
        };
        // The triangulation would refuse such a boundary; refused before the projections.
        rs_mesh::check_boundary_pieces(domain)?;
        if let Some(i) = (0..points.len()).find(|&i| !points[i].is_finite()) {
            return Err(bad(i, "is not finite"));
        }
        if let Some(i) = (0..points.len()).find(|&i| !values[i].is_finite()) {
            return Err(bad(i, "has a value that is not finite"));
        }
        let mut seen: HashMap<(u64, u64), usize> = HashMap::with_capacity(points.len());
        for (i, p) in points.iter().enumerate() {
            if seen.insert(key(*p), i).is_some() {
                return Err(bad(i, "repeats an earlier point"));
            }
        }
        let classifier = Classifier::new(
            domain,
            ContainOptions::DEFAULT.with_relative_tolerance(BOUNDARY_TOLERANCE),
        )
        .map_err(rs_mesh::MeshError::from)?;
        let located = classifier.locate_all_parallel(points);
        let near = NearestBoundary::new(domain);
        let projected: Vec<Option<BoundaryPoint>> = {
            use rayon::prelude::*;
            points
                .par_iter()
                .zip(&located)
                .map(|(&p, loc)| {
                    (*loc == Location::Boundary).then(|| nearest_boundary_point(domain, &near, p))
                })
                .collect()
        };
        let mut sites = points.to_vec();
        let mut interior = Vec::new();
        let mut boundary: Vec<Vec<BoundaryPoint>> = vec![Vec::new(); domain.loops().len()];
        let mut on_curve: HashMap<(u64, u64), usize> = HashMap::new();
        for (i, ((&p, loc), projected)) in points.iter().zip(&located).zip(projected).enumerate() {
            match (loc, projected) {
                (Location::Outside, _) => return Err(bad(i, "lies outside the domain")),
                (_, None) => interior.push(p),
                (_, Some(bp)) => {
                    sites[i] = bp.point;
                    if let Some(&j) = on_curve.get(&key(bp.point)) {
                        // Two points that project to one (a corner given twice, say) are one
                        // vertex: fine when their values agree.
                        if (values[j] - values[i]).abs() > 1e-12 * values[j].abs().max(1.0) {
                            return Err(bad(
                                i,
                                "lands on the same boundary point as an earlier one with another value",
                            ));
                        }
                        continue;
                    }
                    on_curve.insert(key(bp.point), i);
                    boundary[bp.loop_index].push(bp);
                }
            }
        }
        for l in &mut boundary {
            l.sort_by(|a, b| a.curve.cmp(&b.curve).then(a.u.total_cmp(&b.u)));
        }
        let area = domain.signed_area().abs();
        let h = (area / points.len().max(1) as f64).sqrt();
        Ok(Self {
            sites,
            values: values.to_vec(),
            points: WellSpacedPoints {
                h,
                interior,
                boundary,
            },
        })
    }

    /// The data sites, in input order (boundary points moved onto the curve).
    pub fn sites(&self) -> &[Point] {
        &self.sites
    }

    /// The values, in input order.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The sites as interior and boundary points, for [`CurvedTriangulation::new`].
    pub fn points(&self) -> &WellSpacedPoints {
        &self.points
    }

    /// The curved triangulation with the sites as vertices, refined as `space` needs.
    ///
    /// # Errors
    /// The mesh errors of [`CurvedTriangulation::new`].
    pub fn triangulate(
        &self,
        domain: &Domain,
        space: C1Space,
    ) -> Result<CurvedTriangulation, TriSplineError> {
        Ok(match space.refinement() {
            None => CurvedTriangulation::new(domain, &self.points)?,
            Some(how) => CurvedTriangulation::new_refined(domain, &self.points, how)?,
        })
    }
}

/// A scattered-data interpolant and what it took.
#[derive(Clone, Debug)]
pub struct ScatteredFit {
    /// The spline.
    pub spline: Spline,
    /// Vertices that are not data points (curve start points, points inserted for
    /// convertibility): their values come from the first stage's local fit.
    pub added_vertices: usize,
    /// Data points (by index) that are not vertices: interior points the triangulation dropped
    /// because they lie between a boundary arc and its chord. The spline does not interpolate
    /// these. (Two boundary points that land on one point of the curve with the same value
    /// are one vertex, and both count as interpolated.)
    pub unused_points: Vec<usize>,
}

/// Problem 9.1 end to end: the triangulation of the data's sites ([`ScatteredData::new`])
/// refined as `space` needs, then [`interpolate_on`].
///
/// # Errors
/// As [`ScatteredData::new`], [`ScatteredData::triangulate`] and [`interpolate_on`].
pub fn interpolate_scattered(
    domain: &Domain,
    points: &[Point],
    values: &[f64],
    space: C1Space,
) -> Result<ScatteredFit, TriSplineError> {
    let data = ScatteredData::new(domain, points, values)?;
    let mesh = data.triangulate(domain, space)?;
    interpolate_on(mesh, space, data.sites(), data.values())
}

/// The spline of `space` on `mesh` (the triangulation `space` needs) through the data
/// `(sites[i], values[i])`: each vertex at a site takes its value; the first stage fits a
/// local polynomial ([`LocalFits`], degree [`C1Space::fit_degree`]) at every vertex of the
/// unrefined triangulation, through the vertex's value when it is a site; the second stage
/// is the Hermite element with those derivatives (cross derivatives at an edge's midpoint
/// from the mean of its two end fits there), or for [`C1Space::MinimalEnergy`] the
/// minimal-energy spline with the vertex values.
///
/// # Errors
/// [`TriSplineError::WrongTriangulation`], [`TriSplineError::Data`], [`TriSplineError::IllPosedFit`],
/// [`TriSplineError::NotConverged`].
pub fn interpolate_on(
    mesh: CurvedTriangulation,
    space: C1Space,
    sites: &[Point],
    values: &[f64],
) -> Result<ScatteredFit, TriSplineError> {
    use rayon::prelude::*;
    let fits = LocalFits::new(sites, values, space.fit_degree())?;
    let macros = macro_triangles(&mesh, space)?;
    let site_at: HashMap<(u64, u64), usize> = sites
        .iter()
        .enumerate()
        .map(|(i, &p)| (key(p), i))
        .collect();
    let nv = mesh.vertices().len();
    let mut is_macro = vec![false; nv];
    for &v in macros.iter().flatten() {
        is_macro[v] = true;
    }
    let vertex_site: Vec<Option<usize>> = mesh
        .vertices()
        .iter()
        .map(|&p| site_at.get(&key(p)).copied())
        .collect();
    let fitted: Vec<Option<LocalPolynomial>> = (0..nv)
        .into_par_iter()
        .map(|v| {
            is_macro[v]
                .then(|| fits.fit_at(mesh.vertices()[v], vertex_site[v]))
                .transpose()
        })
        .collect::<Result<_, _>>()?;
    let vertex_values: Vec<f64> = (0..nv)
        .map(|v| match (vertex_site[v], &fitted[v]) {
            (Some(i), _) => values[i],
            (None, Some(fit)) => fit.jet_at(mesh.vertices()[v]).value,
            (None, None) => 0.0,
        })
        .collect();
    let added_vertices = (0..nv)
        .filter(|&v| is_macro[v] && vertex_site[v].is_none())
        .count();
    let at_vertex: std::collections::HashSet<(u64, u64)> = (0..nv)
        .filter(|&v| is_macro[v])
        .map(|v| key(mesh.vertices()[v]))
        .collect();
    let unused_points = (0..sites.len())
        .filter(|&i| !at_vertex.contains(&key(sites[i])))
        .collect();
    let data = FittedData {
        vertices: mesh.vertices().to_vec(),
        values: vertex_values,
        fits: fitted,
    };
    let spline = if space == C1Space::MinimalEnergy {
        let start: Vec<[f64; 2]> = (0..nv).map(|v| data.vertex(v).gradient).collect();
        minimal_energy(mesh, &data.values, Some(&start))?
    } else {
        hermite_interpolate(mesh, space, &data)?
    };
    Ok(ScatteredFit {
        spline,
        added_vertices,
        unused_points,
    })
}

/// Hermite data from the first stage's local fits.
struct FittedData {
    vertices: Vec<Point>,
    values: Vec<f64>,
    fits: Vec<Option<LocalPolynomial>>,
}

impl HermiteData for FittedData {
    fn vertex(&self, v: usize) -> Jet {
        let mut jet = self.fits[v]
            .as_ref()
            .map_or_else(Jet::default, |f| f.jet_at(self.vertices[v]));
        jet.value = self.values[v];
        jet
    }

    fn edge_gradient(&self, a: usize, b: usize) -> [f64; 2] {
        let mid = (self.vertices[a] + self.vertices[b]) * 0.5;
        let g = |v: usize| {
            self.fits[v]
                .as_ref()
                .map_or([0.0; 2], |f| f.jet_at(mid).gradient)
        };
        let (ga, gb) = (g(a), g(b));
        [0.5 * (ga[0] + gb[0]), 0.5 * (ga[1] + gb[1])]
    }
}

/// The bits of a point, for exact matching.
fn key(p: Point) -> (u64, u64) {
    // +0.0 and -0.0 are the same point.
    ((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits())
}

/// A boundary point within this distance, relative to the domain's bounding-box diagonal, of
/// a curve's end is that end: distinct vertices so close would make triangles of rounding
/// size. (Far below [`BOUNDARY_TOLERANCE`]; a distance, so it does not depend on how fast the
/// curve is parametrised there.)
const END_SNAP: f64 = 1e-12;

/// The boundary point at the point of the boundary nearest to `p` ([`NearestBoundary`]), with
/// a point at (or within [`END_SNAP`] of) a curve's end given as the next curve's start in its
/// loop, so it matches the start point the triangulation always keeps: the seam of a closed
/// curve is one parameter, its start.
fn nearest_boundary_point(domain: &Domain, near: &NearestBoundary, p: Point) -> BoundaryPoint {
    let found = near.nearest(p);
    let ci = found.curve;
    let c = &domain.curves()[ci];
    let (start, end) = c.param_range();
    let loop_index = domain
        .loops()
        .iter()
        .position(|l| l.curves().contains(&ci))
        .unwrap_or(0);
    let snap = END_SNAP * domain.bounding_box().diagonal();
    let point = c.point_at(found.u);
    let (curve, u) = if found.u <= start || point.distance(c.start_point()) <= snap {
        (ci, start)
    } else if found.u >= end || point.distance(c.end_point()) <= snap {
        let l = &domain.loops()[loop_index];
        let next = if ci == *l.curves().end() {
            *l.curves().start()
        } else {
            ci + 1
        };
        (next, domain.curves()[next].param_range().0)
    } else {
        (ci, found.u)
    };
    BoundaryPoint {
        loop_index,
        curve,
        u,
        point: domain.curves()[curve].point_at(u),
    }
}
