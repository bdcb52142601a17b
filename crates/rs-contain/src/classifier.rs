//! The inRS classifier: crossing numbers over monotone boxes with fallbacks.

use rs_boxes::{BoxOptions, DEFAULT_SUBDIVISIONS, MonotoneBoxes};
use rs_spline::{BoundingBox, Domain, Point};

use crate::rays::{Hit, downward_sign, horizontal, vertical, winding};
use std::sync::{Arc, OnceLock};

use crate::rows::{Rows, box_rows};
use crate::{
    ContainError, Decision, FillRule, Locate, Location, LocatorIndex, Method, PointSource,
    WindingField,
};

/// The rounding part of [`Classifier::vertical_winding`]'s reach, relative to the coordinates'
/// scale plus the diagonal: far above the few units in the last place by which a refined box's
/// end points can stray from its piece's rectangle, far below any tolerance in use.
const REACH_ROUNDING: f64 = 1e-12;

/// Default boundary tolerance, relative to the diagonal of the domain's bounding box.
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-12;

/// Options of a [`Classifier`] and a [`Containment`](crate::Containment): start from
/// [`ContainOptions::DEFAULT`] and change what you need with the `with_*` setters. Every
/// option that changes answers lives here, so the value itself is what a cache of prepared
/// domains is keyed by (it is `Eq` and `Hash`: the tolerance compares by its bits, and
/// [`ContainOptions::with_relative_tolerance`] stores `-0.0` as `0.0`);
/// [`ContainOptions::validated`] checks it, once, for every front end.
///
/// ```
/// use rs_contain::{ContainOptions, FillRule, Method};
/// let o = ContainOptions::DEFAULT
///     .with_relative_tolerance(1e-10)
///     .with_method(Method::InRS2)
///     .with_fill_rule(FillRule::NonZero);
/// assert_eq!(o.method, Method::InRS2);
/// assert_eq!(o.validated().unwrap(), o);
/// assert!(o.with_relative_tolerance(f64::NAN).validated().is_err());
/// ```
#[derive(Clone, Copy, Debug)]
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
    /// Which winding numbers are inside, for every method (the crossing methods count
    /// signed crossings: see the crate's Semantics). Default [`FillRule::EvenOdd`].
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

    /// With another relative boundary tolerance (`-0.0` stored as `0.0`).
    pub const fn with_relative_tolerance(mut self, relative_tolerance: f64) -> Self {
        self.relative_tolerance = if relative_tolerance == 0.0 {
            0.0
        } else {
            relative_tolerance
        };
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

    /// With another fill rule.
    pub const fn with_fill_rule(mut self, fill_rule: FillRule) -> Self {
        self.fill_rule = fill_rule;
        self
    }

    /// The options if every one is usable, checked once for every front end (the
    /// constructors that take options check them the same way).
    ///
    /// # Errors
    /// [`ContainError::InvalidTolerance`] for a relative tolerance that is negative or not
    /// finite.
    pub fn validated(self) -> Result<Self, ContainError> {
        rs_spline::limits::NonNegative::new(self.relative_tolerance)
            .map(|_| self)
            .map_err(|e| ContainError::InvalidTolerance(e.0))
    }

    /// The fields, the tolerance by its bits: what equality and hashing compare.
    fn key(&self) -> (u64, usize, Method, FillRule) {
        (
            self.relative_tolerance.to_bits(),
            self.subdivisions,
            self.method,
            self.fill_rule,
        )
    }
}

impl PartialEq for ContainOptions {
    fn eq(&self, other: &Self) -> bool {
        self.key() == other.key()
    }
}

impl Eq for ContainOptions {}

impl std::hash::Hash for ContainOptions {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.key().hash(state);
    }
}

impl Default for ContainOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A point classifier for one closed domain: the paper's Algorithm inRS, with the crossings
/// counted with their signs, so that its options' [`FillRule`] decides (the sum of the signed
/// crossings is the winding number, `crate::rays` shows why; even-odd reads its parity).
///
/// Build it once (monotone pieces, critical points, bounding box) and locate any number of
/// points through [`Locate`] (one point, or a batch with the method of its options), or with
/// [`Classifier::locate_all_with`] and a method of your choice (every method gives the same
/// answers; [`Classifier::engine`] says which algorithm answers a batch).
/// [`Classifier::new`] builds only the monotone pieces, their critical points and bounding box
/// and the tolerance ([`MonotoneBoxes::new`]): what one point needs. Built on first use and
/// kept (thread-safe, once): the refined boxes ([`MonotoneBoxes::boxes`], for the rows of the
/// fallback, the grid and the winding field; inRS1 and inRS2 before they exist compute the
/// refined boxes of only the pieces their points are near), the rows of the fallback,
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
    /// refined boxes ([`Classifier::vertical_winding`]): twice the tolerance plus a rounding
    /// margin far above the rounding of the refined boxes' end points.
    reach: f64,
    outer: BoundingBox,
    method: Method,
    fill_rule: FillRule,
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
            fill_rule: self.fill_rule,
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
        let options = options.validated()?;
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
            fill_rule: options.fill_rule,
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

    /// The fill rule every method applies.
    pub fn fill_rule(&self) -> FillRule {
        self.fill_rule
    }

    /// The bounding box grown by the tolerance: everything outside is outside.
    pub(crate) fn outer(&self) -> BoundingBox {
        self.outer
    }

    /// The generalized winding-number field of the same boundary (with the classifier's fill
    /// rule), built on the first call and kept.
    pub fn winding_field(&self) -> &WindingField {
        self.field.get_or_init(|| {
            WindingField::from_shared_boxes(
                &self.domain,
                Arc::clone(&self.boxes),
                self.relative_tolerance,
            )
            .with_fill_rule(self.fill_rule)
        })
    }

    /// The absolute boundary tolerance: the relative tolerance times the bounding-box diagonal.
    pub fn abs_tol(&self) -> f64 {
        self.tol
    }

    /// The location of one point and which step of the algorithm decided it.
    pub fn classify_point_with_decision(&self, p: Point) -> (Location, Decision) {
        let (w, decision) = self.winding_with_decision(p);
        (self.location(w), decision)
    }

    /// The winding number of one point (`None` on the boundary) and which step of the
    /// algorithm decided it: the signed crossings of the ray it takes.
    pub(crate) fn winding_with_decision(&self, p: Point) -> (Option<i64>, Decision) {
        if !self.outer.contains(p) {
            return (Some(0), Decision::BoundingBox);
        }
        if !self.boxes().is_critical_x(p.x, self.tol) {
            return (self.vertical_winding(p), Decision::VerticalRay);
        }
        self.fallback(p)
    }

    /// [`Location::Boundary`] for `None`, else inside where the fill rule fills winding
    /// number `w`.
    #[inline]
    pub(crate) fn location(&self, w: Option<i64>) -> Location {
        match w {
            None => Location::Boundary,
            Some(w) if self.fill_rule.fills(w) => Location::Inside,
            Some(_) => Location::Outside,
        }
    }

    /// The downward vertical ray from `p` over the refined boxes, as
    /// `winding(boxes().boxes(), vertical)` gives it, but looking at the refined boxes of only
    /// the monotone pieces `p` is within `reach` of (computed on the fly while the refinement
    /// is not built).
    ///
    /// A piece's refined boxes lie in its end-point rectangle (up to the rounding of their end
    /// points, far below the rounding part of `reach`). For `p` farther than `reach` outside it,
    /// no refined box is near `p` (`reach` >= the tolerance); below it, or beside it, none is
    /// crossed; above it, each is decided by its half-open abscissas `[xmin, xmax)` alone, and
    /// along the monotone chain of end points `x_0 .. x_k` one of them holds `p.x` exactly
    /// when `p.x` lies in the piece's own `[xmin, xmax)`, and none otherwise, the answer taken
    /// here, with the piece's sign (its boxes share its direction; a vertical piece, whose
    /// boxes are all vertical, is never crossed). So the winding number, and whether a box is
    /// near `p`, are those of the scan of every refined box.
    pub(crate) fn vertical_winding(&self, p: Point) -> Option<i64> {
        let (boxes, reach) = (self.boxes(), self.reach);
        let mut w = 0;
        let mut boundary = false;
        for (i, piece) in boxes.pieces().iter().enumerate() {
            let band = &piece.band;
            if p.x < band.xmin - reach || p.x > band.xmax + reach || p.y < band.ymin - reach {
                continue;
            }
            if p.y > band.ymax + reach {
                if !band.vertical && band.xmin <= p.x && p.x < band.xmax {
                    w += downward_sign(piece);
                }
                continue;
            }
            boxes.for_each_box_of_piece(i, |b| {
                if !boundary {
                    match vertical(b, p, self.tol) {
                        Hit::Boundary => boundary = true,
                        Hit::Cross(s) => w += s,
                        Hit::Miss => {}
                    }
                }
            });
            if boundary {
                return None;
            }
        }
        Some(w)
    }

    /// Paper steps (vii)-(viii): the horizontal ray, then the winding number (`None` on the
    /// boundary).
    ///
    /// The ray and the boundary test look only at the boxes whose reach holds `p.y` (rows
    /// built on first use): the others are neither near `p` nor crossed by its horizontal ray,
    /// so the answer is the one a scan of every box gives (a domain whose tolerance is wider
    /// than the domain made every point take this path through tens of thousands of boxes).
    pub(crate) fn fallback(&self, p: Point) -> (Option<i64>, Decision) {
        let all = self.boxes().boxes();
        let rows = self.rows.get_or_init(|| box_rows(all, self.tol));
        let near = || rows.near(p.y).iter().map(|&i| &all[i as usize]);
        if !self.boxes().is_critical_y(p.y, self.tol) {
            let w = winding(near(), |b| horizontal(b, p, self.tol));
            return (w, Decision::HorizontalRay);
        }
        if near().any(|b| b.is_near(p, self.tol)) {
            return (None, Decision::WindingNumber);
        }
        // The generalized winding number (the one winding routine of the crate), exact up to
        // rounding at a point off the boundary; its field is built on the first call.
        let w = self.winding_field().winding_number(p).round() as i64;
        (Some(w), Decision::WindingNumber)
    }

    /// [`Method::Gwn`]'s location of one point: outside the grown bounding box, else from the
    /// winding-number field (with the classifier's fill rule).
    pub(crate) fn winding_location(&self, p: Point) -> Location {
        if self.outer.contains(p) {
            self.winding_field().locate(p)
        } else {
            Location::Outside
        }
    }

    /// inRS2: the points that need the vertical ray are sorted by abscissa; each monotone
    /// piece finds the points in its abscissas (grown by `reach`) by binary search. Those
    /// above its end-point rectangle by more than `reach` take the piece's signed crossing
    /// when its half-open abscissas `[xmin, xmax)` hold them, those below it nothing (the
    /// argument of [`Classifier::vertical_winding`]: what every refined box would add); only
    /// the points within `reach` of the rectangle meet the piece's refined boxes
    /// ([`MonotoneBoxes::for_each_box_of_piece`], computed on the fly while the refinement is
    /// not built), each box finding its points among them by binary search as it did among
    /// all. So a first batch refines only the pieces its points come near, with no allocation
    /// per piece. Points on critical abscissas take the fallbacks one by one.
    pub(crate) fn sorted_into<P: PointSource + ?Sized>(&self, points: &P, out: &mut [Location]) {
        assert_eq!(points.len(), out.len(), "one value per point");
        out.fill(Location::Outside);
        // The points with their indexes, sorted by abscissa (in any order among equal ones:
        // each point's answer depends on its own tests only).
        let mut order: Vec<(Point, usize)> = Vec::with_capacity(points.len());
        for (i, o) in out.iter_mut().enumerate() {
            let p = points.point(i);
            if !self.outer.contains(p) {
                continue;
            }
            if self.boxes().is_critical_x(p.x, self.tol) {
                *o = self.location(self.fallback(p).0);
            } else {
                order.push((p, i));
            }
        }
        order.sort_unstable_by(|a, b| a.0.x.total_cmp(&b.0.x));
        let sorted: Vec<Point> = order.iter().map(|&(p, _)| p).collect();
        let mut windings = vec![0_i64; order.len()];
        let mut on_boundary = vec![false; order.len()];
        let (boxes, tol, reach) = (self.boxes(), self.tol, self.reach);
        // The indexes (into `sorted`, in abscissa order) of the points near the current
        // piece: one buffer for every piece.
        let mut near: Vec<usize> = Vec::new();
        for (i, piece) in boxes.pieces().iter().enumerate() {
            let band = &piece.band;
            let lo = sorted.partition_point(|p| p.x < band.xmin - reach);
            let hi = sorted.partition_point(|p| p.x <= band.xmax + reach);
            near.clear();
            for (j, p) in sorted.iter().enumerate().take(hi).skip(lo) {
                if p.y < band.ymin - reach {
                    continue;
                }
                if p.y > band.ymax + reach {
                    if !band.vertical && band.xmin <= p.x && p.x < band.xmax {
                        windings[j] += downward_sign(piece);
                    }
                    continue;
                }
                near.push(j);
            }
            if near.is_empty() {
                continue;
            }
            boxes.for_each_box_of_piece(i, |b| {
                let first = near.partition_point(|&j| sorted[j].x < b.band.xmin - tol);
                let last = near.partition_point(|&j| sorted[j].x <= b.band.xmax + tol);
                for &j in &near[first..last] {
                    let p = sorted[j];
                    if on_boundary[j] || p.y < b.band.ymin - tol {
                        continue;
                    }
                    match vertical(b, p, tol) {
                        Hit::Boundary => on_boundary[j] = true,
                        Hit::Cross(s) => windings[j] += s,
                        Hit::Miss => {}
                    }
                }
            });
        }
        for (j, &(_, i)) in order.iter().enumerate() {
            out[i] = self.location((!on_boundary[j]).then_some(windings[j]));
        }
    }
}
