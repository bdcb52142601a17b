//! The inRS classifier: crossing numbers over monotone boxes with fallbacks.

use rs_boxes::{BoxOptions, DEFAULT_SUBDIVISIONS, MonotoneBoxes};
use rs_spline::{BoundingBox, Domain, Point};

use crate::rays::{Hit, horizontal, parity, vertical};
use std::sync::{Arc, OnceLock};

use crate::rows::{Rows, box_rows};
use crate::{
    ContainError, Decision, FillRule, Locate, Location, LocatorIndex, Method, PointSource,
    WindingField,
};

/// The rounding part of [`Classifier::vertical_parity`]'s reach, relative to the coordinates'
/// scale plus the diagonal: far above the few units in the last place by which a refined box's
/// end points can stray from its piece's rectangle, far below any tolerance in use.
const REACH_ROUNDING: f64 = 1e-12;

/// Default boundary tolerance, relative to the diagonal of the domain's bounding box.
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-12;

/// Options of a [`Classifier`]: start from [`ContainOptions::DEFAULT`] and change what you
/// need with the `with_*` setters.
///
/// ```
/// use rs_contain::{ContainOptions, Method};
/// let o = ContainOptions::DEFAULT.with_relative_tolerance(1e-10).with_method(Method::InRS2);
/// assert_eq!(o.method, Method::InRS2);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub struct ContainOptions {
    /// Boundary tolerance relative to the bounding-box diagonal (see the crate's Semantics).
    pub relative_tolerance: f64,
    /// The most sub-boxes per monotone piece (paper Remark 2.1; pieces short against the
    /// domain get fewer, see [`rs_boxes::BOXES_PER_DIAGONAL`]).
    pub subdivisions: usize,
    /// The method [`Locate::locate_all`] uses (all give the same answers; they differ in
    /// speed). Default [`Method::Fast`], as on the command line.
    pub method: Method,
    /// The fill rule of [`Method::Gwn`] through [`Containment`](crate::Containment) (a
    /// [`Classifier`] is even-odd). Default [`FillRule::EvenOdd`].
    pub fill_rule: FillRule,
}

impl ContainOptions {
    /// Relative tolerance [`DEFAULT_RELATIVE_TOLERANCE`], one box per monotone piece,
    /// [`Method::Fast`], [`FillRule::EvenOdd`].
    pub const DEFAULT: ContainOptions = ContainOptions {
        relative_tolerance: DEFAULT_RELATIVE_TOLERANCE,
        subdivisions: DEFAULT_SUBDIVISIONS,
        method: Method::Fast,
        fill_rule: FillRule::EvenOdd,
    };

    /// With another relative boundary tolerance.
    pub const fn with_relative_tolerance(mut self, relative_tolerance: f64) -> Self {
        self.relative_tolerance = relative_tolerance;
        self
    }

    /// With at most `subdivisions` sub-boxes per monotone piece.
    pub const fn with_subdivisions(mut self, subdivisions: usize) -> Self {
        self.subdivisions = subdivisions;
        self
    }

    /// With another batch method.
    pub const fn with_method(mut self, method: Method) -> Self {
        self.method = method;
        self
    }

    /// With another fill rule for [`Method::Gwn`].
    pub const fn with_fill_rule(mut self, fill_rule: FillRule) -> Self {
        self.fill_rule = fill_rule;
        self
    }
}

impl Default for ContainOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A point classifier for one closed domain: the paper's Algorithm inRS.
///
/// Build it once (monotone pieces, critical points, bounding box) and locate any number of
/// points through [`Locate`] (one point, or a batch with the method of its options), or with
/// [`Classifier::locate_all_with`] and a method of your choice (every method gives the same
/// answers; [`Classifier::engine`] says which algorithm answers a batch).
/// [`Classifier::new`] builds only the monotone pieces, their critical points and bounding box
/// and the tolerance ([`MonotoneBoxes::new`]): what one point needs. Built on first use and
/// kept (thread-safe, once): the refined boxes ([`MonotoneBoxes::boxes`], for inRS2, the rows
/// of the fallback, the grid and the winding field; a point answered one by one before they
/// exist computes the refined boxes of only the pieces it is near), the rows of the fallback,
/// the winding-number field and the grid of [`Method::Fast`].
/// See the crate documentation for the exact semantics.
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
///     c.locate_all_with(Method::InRS2, &pts),
///     vec![Location::Inside, Location::Outside, Location::Boundary]
/// );
/// ```
#[derive(Debug)]
pub struct Classifier {
    /// The monotone boxes, shared with the winding-number field (one copy).
    boxes: Arc<MonotoneBoxes>,
    /// The domain's curves, for the winding-number field built on first use.
    domain: Domain,
    relative_tolerance: f64,
    tol: f64,
    /// Distance beyond which a point is away from a monotone piece for every test of its
    /// refined boxes ([`Classifier::vertical_parity`]): twice the tolerance plus a rounding
    /// margin far above the rounding of the refined boxes' end points.
    reach: f64,
    outer: BoundingBox,
    method: Method,
    /// Built on first use: the generalized winding-number field ([`Method::Gwn`]).
    field: OnceLock<WindingField>,
    /// Built on first use: the grid of [`Method::Fast`] with the default options
    /// ([`Classifier::locator`]).
    pub(crate) grid: OnceLock<LocatorIndex>,
    /// Built on first use: the boxes by rows, for the fallback's horizontal ray.
    rows: OnceLock<Rows>,
}

impl Clone for Classifier {
    /// A copy; the lazily built indexes are built again when needed.
    fn clone(&self) -> Self {
        Self {
            boxes: Arc::clone(&self.boxes),
            domain: self.domain.clone(),
            relative_tolerance: self.relative_tolerance,
            tol: self.tol,
            reach: self.reach,
            outer: self.outer,
            method: self.method,
            field: OnceLock::new(),
            grid: OnceLock::new(),
            rows: OnceLock::new(),
        }
    }
}

impl Classifier {
    /// Builds the classifier of a domain whose loops all close.
    ///
    /// # Errors
    /// [`ContainError::Domain`] with [`rs_spline::DomainError::OpenLoop`] for an open boundary,
    /// [`ContainError::InvalidTolerance`], [`ContainError::Boxes`].
    pub fn new(domain: &Domain, options: ContainOptions) -> Result<Self, ContainError> {
        domain.require_closed()?;
        if !(options.relative_tolerance.is_finite() && options.relative_tolerance >= 0.0) {
            return Err(ContainError::InvalidTolerance(options.relative_tolerance));
        }
        let boxes = MonotoneBoxes::new(
            domain,
            BoxOptions::DEFAULT.with_subdivisions(options.subdivisions),
        )?;
        let bbox = boxes.bounding_box();
        let tol = options.relative_tolerance * bbox.diagonal();
        let outer = BoundingBox {
            min: Point::new(bbox.min.x - tol, bbox.min.y - tol),
            max: Point::new(bbox.max.x + tol, bbox.max.y + tol),
        };
        let scale = bbox.min.x.abs().max(bbox.max.x.abs()) + bbox.min.y.abs().max(bbox.max.y.abs());
        let reach = 2.0 * tol + REACH_ROUNDING * (scale + bbox.diagonal());
        Ok(Self {
            boxes: Arc::new(boxes),
            domain: domain.clone(),
            relative_tolerance: options.relative_tolerance,
            tol,
            reach,
            outer,
            method: options.method,
            field: OnceLock::new(),
            grid: OnceLock::new(),
            rows: OnceLock::new(),
        })
    }

    /// The monotone pieces, their refined boxes (built on first use) and critical points in
    /// use.
    pub fn boxes(&self) -> &MonotoneBoxes {
        &self.boxes
    }

    /// The method of [`Locate::locate_all`].
    pub fn method(&self) -> Method {
        self.method
    }

    /// The bounding box grown by the tolerance: everything outside is outside.
    pub(crate) fn outer(&self) -> BoundingBox {
        self.outer
    }

    /// The generalized winding-number field of the same boundary (even-odd rule), built on
    /// the first call and kept.
    pub fn winding_field(&self) -> &WindingField {
        self.field.get_or_init(|| {
            WindingField::from_shared_boxes(
                &self.domain,
                Arc::clone(&self.boxes),
                self.relative_tolerance,
            )
        })
    }

    /// The absolute boundary tolerance: the relative tolerance times the bounding-box diagonal.
    pub fn abs_tol(&self) -> f64 {
        self.tol
    }

    /// The location of one point and which step of the algorithm decided it.
    pub fn classify_point_with_decision(&self, p: Point) -> (Location, Decision) {
        if !self.outer.contains(p) {
            return (Location::Outside, Decision::BoundingBox);
        }
        if !self.boxes().is_critical_x(p.x, self.tol) {
            return (location(self.vertical_parity(p)), Decision::VerticalRay);
        }
        self.fallback(p)
    }

    /// The downward vertical ray from `p` over the refined boxes, as
    /// `parity(boxes().boxes(), vertical)` gives it, but looking at the refined boxes of only
    /// the monotone pieces `p` is within `reach` of (computed on the fly while the refinement
    /// is not built).
    ///
    /// A piece's refined boxes lie in its end-point rectangle (up to the rounding of their end
    /// points, far below the rounding part of `reach`). For `p` farther than `reach` outside it,
    /// no refined box is near `p` (`reach` >= the tolerance); below it, or beside it, none is
    /// crossed; above it, each is decided by its half-open abscissas `[xmin, xmax)` alone, and
    /// along the chain of end points `x_0 .. x_k` the number of those holding `p.x` is odd
    /// exactly when `p.x` lies in the piece's own `[xmin, xmax)`, the answer taken here (a
    /// vertical piece, whose boxes are all vertical, is never crossed). So the parity, and
    /// whether a box is near `p`, are those of the scan of every refined box.
    pub(crate) fn vertical_parity(&self, p: Point) -> Option<bool> {
        let (boxes, reach) = (self.boxes(), self.reach);
        let mut odd = false;
        let mut boundary = false;
        for (i, piece) in boxes.pieces().iter().enumerate() {
            let band = &piece.band;
            if p.x < band.xmin - reach || p.x > band.xmax + reach || p.y < band.ymin - reach {
                continue;
            }
            if p.y > band.ymax + reach {
                if !band.vertical && band.xmin <= p.x && p.x < band.xmax {
                    odd = !odd;
                }
                continue;
            }
            boxes.for_each_box_of_piece(i, |b| {
                if !boundary {
                    match vertical(b, p, self.tol) {
                        Hit::Boundary => boundary = true,
                        Hit::Cross => odd = !odd,
                        Hit::Miss => {}
                    }
                }
            });
            if boundary {
                return None;
            }
        }
        Some(odd)
    }

    /// Paper steps (vii)-(viii): the horizontal ray, then the winding number.
    ///
    /// The ray and the boundary test look only at the boxes whose reach holds `p.y` (rows
    /// built on first use): the others are neither near `p` nor crossed by its horizontal ray,
    /// so the answer is the one a scan of every box gives (a domain whose tolerance is wider
    /// than the domain made every point take this path through tens of thousands of boxes).
    pub(crate) fn fallback(&self, p: Point) -> (Location, Decision) {
        let all = self.boxes().boxes();
        let rows = self.rows.get_or_init(|| box_rows(all, self.tol));
        let near = || rows.near(p.y).iter().map(|&i| &all[i as usize]);
        if !self.boxes().is_critical_y(p.y, self.tol) {
            let odd = parity(near(), |b| horizontal(b, p, self.tol));
            return (location(odd), Decision::HorizontalRay);
        }
        if near().any(|b| b.is_near(p, self.tol)) {
            return (Location::Boundary, Decision::WindingNumber);
        }
        // The generalized winding number (the one winding routine of the crate), exact up to
        // rounding at a point off the boundary; its field is built on the first call.
        let w = self.winding_field().winding_number(p).round() as i64;
        let loc = if w.rem_euclid(2) == 1 {
            Location::Inside
        } else {
            Location::Outside
        };
        (loc, Decision::WindingNumber)
    }

    /// [`Method::Gwn`]'s location of one point: outside the grown bounding box, else from the
    /// winding-number field (even-odd).
    pub(crate) fn winding_location(&self, p: Point) -> Location {
        if self.outer.contains(p) {
            self.winding_field().locate(p)
        } else {
            Location::Outside
        }
    }

    /// inRS2: the points that need the vertical ray are sorted by abscissa; each box finds the
    /// points in its x-range (grown by the tolerance) by binary search and updates their
    /// parities. Points on critical abscissas take the fallbacks one by one.
    pub(crate) fn sorted_into<P: PointSource + ?Sized>(&self, points: &P, out: &mut [Location]) {
        assert_eq!(points.len(), out.len(), "one value per point");
        out.fill(Location::Outside);
        let mut order: Vec<usize> = Vec::with_capacity(points.len());
        for (i, o) in out.iter_mut().enumerate() {
            let p = points.point(i);
            if !self.outer.contains(p) {
                continue;
            }
            if self.boxes().is_critical_x(p.x, self.tol) {
                *o = self.fallback(p).0;
            } else {
                order.push(i);
            }
        }
        order.sort_by(|&a, &b| points.point(a).x.total_cmp(&points.point(b).x));
        let xs: Vec<f64> = order.iter().map(|&i| points.point(i).x).collect();
        let mut odd = vec![false; order.len()];
        let mut on_boundary = vec![false; order.len()];
        let tol = self.tol;
        for b in self.boxes().boxes() {
            let lo = xs.partition_point(|&x| x < b.band.xmin - tol);
            let hi = xs.partition_point(|&x| x <= b.band.xmax + tol);
            for j in lo..hi {
                let p = points.point(order[j]);
                if on_boundary[j] || p.y < b.band.ymin - tol {
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
    }
}

fn location(odd: Option<bool>) -> Location {
    match odd {
        None => Location::Boundary,
        Some(true) => Location::Inside,
        Some(false) => Location::Outside,
    }
}
