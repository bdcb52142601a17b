//! The inRS classifier: crossing numbers over monotone boxes with fallbacks.

use rs_boxes::{BoxOptions, DEFAULT_SUBDIVISIONS, MonotoneBoxes};
use rs_spline::{BoundingBox, Domain, Point};

use crate::rays::{Hit, horizontal, parity, vertical};
use crate::winding::winding_number;
use crate::{
    ContainError, Decision, FAST_METHOD_MIN_POINTS, FillRule, Location, LocatorOptions, Method,
    PointLocator, WindingField,
};

/// Default boundary tolerance, relative to the diagonal of the domain's bounding box.
pub const DEFAULT_TOLERANCE: f64 = 1e-12;

/// Options of a [`Classifier`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContainOptions {
    /// Boundary tolerance relative to the bounding-box diagonal (see the crate's Semantics).
    pub tolerance: f64,
    /// Sub-boxes per monotone piece (paper Remark 2.1).
    pub subdivisions: usize,
}

impl Default for ContainOptions {
    fn default() -> Self {
        Self {
            tolerance: DEFAULT_TOLERANCE,
            subdivisions: DEFAULT_SUBDIVISIONS,
        }
    }
}

/// A point classifier for one closed domain: the paper's Algorithm inRS.
///
/// Build it once (monotone boxes, critical points, bounding box) and classify any number of
/// points with [`Classifier::classify`] (inRS1 or inRS2, same results) or
/// [`Classifier::classify_point`]. See the crate documentation for the exact semantics.
///
/// # Examples
///
/// ```
/// use rs_contain::{Classifier, ContainOptions, Location, Method};
/// use rs_spline::{circle, Domain, Point};
/// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
/// let c = Classifier::new(&d, ContainOptions::default()).unwrap();
/// let pts = [Point::new(0.0, 0.0), Point::new(2.0, 0.0), Point::new(0.6, 0.8)];
/// assert_eq!(
///     c.classify(&pts, Method::InRS2),
///     vec![Location::Inside, Location::Outside, Location::Boundary]
/// );
/// ```
#[derive(Clone, Debug)]
pub struct Classifier {
    /// The winding-number field of the boundary; it owns the monotone boxes, which the
    /// crossing tests share (one copy).
    field: WindingField,
    tol: f64,
    outer: BoundingBox,
}

impl Classifier {
    /// Builds the classifier of a domain whose loops all close.
    ///
    /// # Errors
    /// [`ContainError::Domain`] with [`rs_spline::DomainError::OpenLoop`] for an open boundary,
    /// [`ContainError::InvalidTolerance`], [`ContainError::Boxes`].
    pub fn new(domain: &Domain, options: ContainOptions) -> Result<Self, ContainError> {
        domain.require_closed()?;
        if !(options.tolerance.is_finite() && options.tolerance >= 0.0) {
            return Err(ContainError::InvalidTolerance(options.tolerance));
        }
        let boxes = MonotoneBoxes::new(
            domain,
            BoxOptions {
                subdivisions: options.subdivisions,
            },
        )?;
        let bbox = boxes.bounding_box();
        let tol = options.tolerance * bbox.diagonal();
        let outer = BoundingBox {
            min: Point::new(bbox.min.x - tol, bbox.min.y - tol),
            max: Point::new(bbox.max.x + tol, bbox.max.y + tol),
        };
        let field = WindingField::with_boxes(domain, boxes, options.tolerance)?;
        Ok(Self { field, tol, outer })
    }

    /// The monotone boxes and critical points in use.
    pub fn boxes(&self) -> &MonotoneBoxes {
        self.field.monotone_boxes()
    }

    /// The bounding box grown by the tolerance: everything outside is outside.
    pub(crate) fn outer(&self) -> BoundingBox {
        self.outer
    }

    /// The generalized winding-number field of the same boundary.
    pub fn winding_field(&self) -> &WindingField {
        &self.field
    }

    /// The absolute boundary tolerance: the relative tolerance times the bounding-box diagonal.
    pub fn tolerance(&self) -> f64 {
        self.tol
    }

    /// The location of one point (the inRS1 path).
    pub fn classify_point(&self, p: Point) -> Location {
        self.classify_point_with_decision(p).0
    }

    /// The location of one point and which step of the algorithm decided it.
    pub fn classify_point_with_decision(&self, p: Point) -> (Location, Decision) {
        if !self.outer.contains(p) {
            return (Location::Outside, Decision::BoundingBox);
        }
        if !self.boxes().is_critical_x(p.x, self.tol) {
            let odd = parity(self.boxes().boxes(), |b| vertical(b, p, self.tol));
            return (location(odd), Decision::VerticalRay);
        }
        self.fallback(p)
    }

    /// Paper steps (vii)-(viii): the horizontal ray, then the winding number.
    pub(crate) fn fallback(&self, p: Point) -> (Location, Decision) {
        if !self.boxes().is_critical_y(p.y, self.tol) {
            let odd = parity(self.boxes().boxes(), |b| horizontal(b, p, self.tol));
            return (location(odd), Decision::HorizontalRay);
        }
        if self.boxes().boxes().iter().any(|b| b.is_near(p, self.tol)) {
            return (Location::Boundary, Decision::WindingNumber);
        }
        let w = winding_number(self.boxes().boxes(), p).round() as i64;
        let loc = if w.rem_euclid(2) == 1 {
            Location::Inside
        } else {
            Location::Outside
        };
        (loc, Decision::WindingNumber)
    }

    /// Classifies `points` with the chosen method; the result is in input order and the same
    /// for every method.
    pub fn classify(&self, points: &[Point], method: Method) -> Vec<Location> {
        match method {
            Method::InRS1 => points.iter().map(|&p| self.classify_point(p)).collect(),
            Method::InRS2 => self.classify_sorted(points),
            Method::Fast if points.len() < FAST_METHOD_MIN_POINTS => self.classify_sorted(points),
            Method::Fast => {
                PointLocator::new(self, LocatorOptions::default()).classify_parallel(points)
            }
            Method::Gwn => points
                .iter()
                .map(|&p| {
                    if self.outer.contains(p) {
                        self.field.classify_point(p, FillRule::EvenOdd)
                    } else {
                        Location::Outside
                    }
                })
                .collect(),
        }
    }

    /// inRS2: the points that need the vertical ray are sorted by abscissa; each box finds the
    /// points in its x-range (grown by the tolerance) by binary search and updates their
    /// parities. Points on critical abscissas take the fallbacks one by one.
    fn classify_sorted(&self, points: &[Point]) -> Vec<Location> {
        let mut out = vec![Location::Outside; points.len()];
        let mut order: Vec<usize> = Vec::with_capacity(points.len());
        for (i, &p) in points.iter().enumerate() {
            if !self.outer.contains(p) {
                continue;
            }
            if self.boxes().is_critical_x(p.x, self.tol) {
                out[i] = self.fallback(p).0;
            } else {
                order.push(i);
            }
        }
        order.sort_by(|&a, &b| points[a].x.total_cmp(&points[b].x));
        let xs: Vec<f64> = order.iter().map(|&i| points[i].x).collect();
        let mut odd = vec![false; order.len()];
        let mut on_boundary = vec![false; order.len()];
        let tol = self.tol;
        for b in self.boxes().boxes() {
            let lo = xs.partition_point(|&x| x < b.xmin - tol);
            let hi = xs.partition_point(|&x| x <= b.xmax + tol);
            for j in lo..hi {
                let p = points[order[j]];
                if on_boundary[j] || p.y < b.ymin - tol {
                    continue;
                }
                match vertical(b, p, tol) {
                    Hit::Boundary => on_boundary[j] = true,
                    Hit::Cross => odd[j] = !odd[j],
                    Hit::Miss => {}
                }
            }
        }
        for (j, &i) in order.iter().enumerate() {
            out[i] = if on_boundary[j] {
                Location::Boundary
            } else {
                location(Some(odd[j]))
            };
        }
        out
    }
}

fn location(odd: Option<bool>) -> Location {
    match odd {
        None => Location::Boundary,
        Some(true) => Location::Inside,
        Some(false) => Location::Outside,
    }
}
