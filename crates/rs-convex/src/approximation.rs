//! The paper's algorithm APPROXIMATECONVEXDOMAIN: inner polytopes from the Bernstein
//! coefficients of the sign numerator, refined by midpoint knot insertion until the relative
//! area (volume) growth (20) is below a tolerance; plus an outer polytope from sampled
//! parameters, so the exact domain is bracketed.

use crate::{AffineForm, Point3, SignNumerator};

use crate::{ConvexError, ConvexPolygon, ConvexPolytope, MAX_LEVEL};

/// The largest absolute box coordinate accepted by [`BoundingBox3::from_ranges`]: areas and
/// volumes of regions within such a box stay finite, so an empty result is a proof, never an
/// overflow.
pub const MAX_BOX_COORDINATE: f64 = 1e100;

/// The sign to keep.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Sign {
    /// Positive curvature (counter-clockwise turning) or positive torsion.
    Positive,
    /// Negative curvature or torsion.
    Negative,
}

/// Settings of [`approximate`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct ConvexDomainOptions {
    /// The sign the curve must keep everywhere.
    pub sign: Sign,
    /// Stop when `area(K_l \ K_{l-1}) / area(K_{l-1}) <= relative_tolerance` (formula (20)).
    pub relative_tolerance: f64,
    /// The last refinement level tried (each level doubles the inequalities).
    pub max_level: u32,
    /// Parameters sampled per Bezier piece of the numerator for the outer bound.
    pub outer_samples: usize,
}

impl ConvexDomainOptions {
    /// Positive sign, relative growth tolerance `1e-3`, at most 10 levels, 256 outer samples
    /// per piece.
    pub const DEFAULT: ConvexDomainOptions = ConvexDomainOptions {
        sign: Sign::Positive,
        relative_tolerance: 1e-3,
        max_level: 10,
        outer_samples: 256,
    };

    /// With the sign to keep.
    pub const fn with_sign(mut self, sign: Sign) -> Self {
        self.sign = sign;
        self
    }

    /// With another relative growth tolerance (formula (20)).
    pub const fn with_relative_tolerance(mut self, relative_tolerance: f64) -> Self {
        self.relative_tolerance = relative_tolerance;
        self
    }

    /// With another last level.
    pub const fn with_max_level(mut self, max_level: u32) -> Self {
        self.max_level = max_level;
        self
    }

    /// With another number of outer samples per piece.
    pub const fn with_outer_samples(mut self, outer_samples: usize) -> Self {
        self.outer_samples = outer_samples;
        self
    }
}

impl Default for ConvexDomainOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// An axis-aligned box `B` restricting the domain (2 or 3 coordinates used).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundingBox3 {
    /// Lower corner.
    pub min: Point3,
    /// Upper corner.
    pub max: Point3,
}

impl BoundingBox3 {
    /// The box from `[xmin, xmax, ymin, ymax]` or `[xmin, xmax, ymin, ymax, zmin, zmax]`.
    ///
    /// # Errors
    /// [`ConvexError::InvalidBox`] for another length, non-finite or empty ranges.
    pub fn from_ranges(r: &[f64]) -> Result<Self, ConvexError> {
        let bad = |m: &str| ConvexError::InvalidBox(m.to_string());
        if r.len() != 4 && r.len() != 6 {
            return Err(bad(
                "give xmin,xmax,ymin,ymax (plane) or six numbers (space)",
            ));
        }
        if r.iter().any(|v| !v.is_finite()) {
            return Err(bad("coordinates must be finite"));
        }
        if r.iter().any(|v| v.abs() > MAX_BOX_COORDINATE) {
            return Err(bad(
                "coordinates must be at most 1e100 in absolute value (so areas and volumes stay finite)",
            ));
        }
        for k in 0..r.len() / 2 {
            if r[2 * k] >= r[2 * k + 1] {
                return Err(bad("every range must have min < max"));
            }
        }
        let measure: f64 = (0..r.len() / 2).map(|k| r[2 * k + 1] - r[2 * k]).product();
        if !(measure > 0.0 && measure.is_finite()) {
            return Err(bad(
                "the box's area or volume underflows or overflows: rescale the problem",
            ));
        }
        let (zmin, zmax) = if r.len() == 6 {
            (r[4], r[5])
        } else {
            (0.0, 0.0)
        };
        Ok(Self {
            min: Point3::new(r[0], r[2], zmin),
            max: Point3::new(r[1], r[3], zmax),
        })
    }

    /// 2 for a planar box (zero z extent), 3 otherwise.
    pub fn dimension(&self) -> usize {
        if self.min.z == self.max.z { 2 } else { 3 }
    }

    fn size(&self) -> f64 {
        (self.max - self.min).length()
    }
}

/// A convex region of the free point: a polygon (curvature) or a polytope (torsion).
#[derive(Clone, Debug, PartialEq)]
pub enum Region {
    /// Plane.
    Polygon(ConvexPolygon),
    /// Space.
    Polytope(ConvexPolytope),
}

impl Region {
    /// Area or volume.
    pub fn measure(&self) -> f64 {
        match self {
            Region::Polygon(p) => p.area(),
            Region::Polytope(p) => p.volume(),
        }
    }

    /// True if nothing with area (volume) is left.
    pub fn is_empty(&self) -> bool {
        match self {
            Region::Polygon(p) => p.is_empty(),
            Region::Polytope(p) => p.is_empty(),
        }
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        match self {
            Region::Polygon(p) => p.vertices().len(),
            Region::Polytope(p) => p.vertices().len(),
        }
    }

    /// Number of faces (edges of a polygon).
    pub fn face_count(&self) -> usize {
        match self {
            Region::Polygon(p) => p.vertices().len(),
            Region::Polytope(p) => p.face_count(),
        }
    }

    /// The vertices as 3-D points (`z = 0` in the plane).
    pub fn vertices3(&self) -> Vec<Point3> {
        match self {
            Region::Polygon(p) => p
                .vertices()
                .iter()
                .map(|v| Point3::new(v.x, v.y, 0.0))
                .collect(),
            Region::Polytope(p) => p.vertices(),
        }
    }

    fn from_box(b: &BoundingBox3) -> Self {
        if b.dimension() == 2 {
            Region::Polygon(ConvexPolygon::rectangle(b.min.x, b.max.x, b.min.y, b.max.y))
        } else {
            Region::Polytope(ConvexPolytope::cuboid(b.min, b.max))
        }
    }

    fn clipped(&self, forms: &[AffineForm], size: f64) -> Self {
        match self {
            Region::Polygon(p) => {
                let mut p = p.clone();
                for f in forms {
                    if p.is_empty() {
                        break;
                    }
                    p = p.clip(f.a.x, f.a.y, f.b, size);
                }
                Region::Polygon(p)
            }
            Region::Polytope(p) => {
                let mut p = p.clone();
                for f in forms {
                    if p.is_empty() {
                        break;
                    }
                    p = p.clip(f.a, f.b, size);
                }
                Region::Polytope(p)
            }
        }
    }
}

/// One iteration: the paper's table columns.
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    /// Refinement level `l` (0: the curve's own Bezier pieces).
    pub level: u32,
    /// Number of inequalities (Bernstein coefficients).
    pub inequalities: usize,
    /// The inner approximation `K_discr^(l)` within the box.
    pub region: Region,
    /// Area (volume) growth from the previous level, formula (19); `None` if that was empty.
    pub abs_error: Option<f64>,
    /// `abs_error / measure(previous)`, formula (20).
    pub rel_error: Option<f64>,
}

/// How the iteration ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// The relative growth fell below the tolerance at this level.
    Converged,
    /// The outer bound is empty: no position in the box keeps the sign (a proof, up to
    /// rounding, since every outer half-plane is necessary).
    Empty,
    /// `max_level` was reached first (the inner approximation may still be empty if the
    /// domain is thin or empty but the sampled outer bound is not).
    NotConverged,
}

/// The result: inner approximations per level (nested, growing) and an outer bound.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexDomain {
    /// Every level computed, in order.
    pub levels: Vec<Level>,
    /// Intersection of the box with the half-planes (half-spaces) `h_t > 0` at the sampled
    /// parameters: contains the exact domain within the box.
    pub outer: Region,
    /// How the iteration ended.
    pub outcome: Outcome,
}

impl ConvexDomain {
    /// The last (best) inner approximation.
    pub fn inner(&self) -> &Region {
        &self.levels[self.levels.len() - 1].region
    }
}

/// Runs the algorithm of section 4 for the numerator `h` of a curve with a free control point,
/// within `bbox`: level 0 intersects the box with the half-planes (14) of the Bernstein
/// coefficients; level `l` with those (16) after `l` rounds of midpoint subdivision. Stops when
/// the previous level was non-empty and its relative growth (20) is at most the tolerance.
/// By Remark 2 the levels are nested and by Theorem 1 they converge to the domain.
///
/// # Errors
/// [`ConvexError::DimensionMismatch`] if the box and the numerator disagree,
/// [`ConvexError::InvalidTolerance`] for a tolerance that is negative or not finite,
/// [`ConvexError::InvalidLevel`] for `max_level >` [`MAX_LEVEL`].
pub fn approximate(
    h: &SignNumerator,
    bbox: &BoundingBox3,
    options: &ConvexDomainOptions,
) -> Result<ConvexDomain, ConvexError> {
    if bbox.dimension() != h.dimension() {
        return Err(ConvexError::DimensionMismatch {
            curve: h.dimension(),
            bbox: bbox.dimension(),
        });
    }
    rs_spline::limits::NonNegative::new(options.relative_tolerance)
        .map_err(|e| ConvexError::InvalidTolerance(e.0))?;
    if options.max_level > MAX_LEVEL {
        return Err(ConvexError::InvalidLevel(options.max_level));
    }
    let orient = |f: AffineForm| match options.sign {
        Sign::Positive => f,
        Sign::Negative => f.negated(),
    };
    let size = bbox.size();
    let start = Region::from_box(bbox);
    let samples = options.outer_samples.max(2);
    let outer_forms: Vec<AffineForm> = (0..h.piece_count())
        .flat_map(|k| (0..samples).map(move |i| (k, i as f64 / (samples - 1) as f64)))
        .map(|(k, s)| orient(h.at(k, s)))
        .collect();
    let outer = start.clipped(&outer_forms, size);
    let mut levels: Vec<Level> = Vec::new();
    let mut current = h.clone();
    let mut outcome = Outcome::NotConverged;
    for level in 0..=options.max_level {
        if level > 0 {
            current = current.refined(1);
        }
        let forms: Vec<AffineForm> = current.inequalities().into_iter().map(orient).collect();
        let region = start.clipped(&forms, size);
        let (abs_error, rel_error) = match levels.last() {
            Some(prev) if !prev.region.is_empty() => {
                let before = prev.region.measure();
                let grown = (region.measure() - before).max(0.0);
                (Some(grown), Some(grown / before))
            }
            _ => (None, None),
        };
        levels.push(Level {
            level,
            inequalities: forms.len(),
            region,
            abs_error,
            rel_error,
        });
        if outer.is_empty() {
            outcome = Outcome::Empty;
            break;
        }
        if rel_error.is_some_and(|r| r <= options.relative_tolerance) {
            outcome = Outcome::Converged;
            break;
        }
    }
    Ok(ConvexDomain {
        levels,
        outer,
        outcome,
    })
}
