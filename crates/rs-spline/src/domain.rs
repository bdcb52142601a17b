//! Domains: curves grouped into boundary loops, with size, orientation and area.

use crate::prelude::*;
use std::ops::RangeInclusive;

use crate::quadrature::Integral;
use crate::{BoundingBox, DomainError, NurbsCurve, Point, RationalBezier};

/// Default closure tolerance, relative to the diagonal of the domain's bounding box: a curve's
/// end meets the next curve's start when they are at most `1e-9 * diagonal` apart.
pub const DEFAULT_RELATIVE_CLOSURE_TOLERANCE: f64 = 1e-9;

/// Orientation of a closed loop, from the sign of its signed area.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Orientation {
    /// Positive signed area (the enclosed region is on the left).
    CounterClockwise,
    /// Negative signed area.
    Clockwise,
    /// Zero signed area (degenerate or self-cancelling loop).
    Degenerate,
}

/// A run of consecutive curves of a [`Domain`], each ending where the next starts.
#[derive(Clone, Debug, PartialEq)]
pub struct BoundaryLoop {
    first: usize,
    last: usize,
    gap: f64,
    closed: bool,
    /// When the loop ended because the next curve of the list does not start where the
    /// last one ends (rather than by returning to its start): how far apart they are.
    next_gap: Option<f64>,
}

impl BoundaryLoop {
    /// Indices of the loop's curves in the domain (inclusive range).
    pub fn curves(&self) -> RangeInclusive<usize> {
        self.first..=self.last
    }

    /// Distance from the end of the last curve to the start of the first.
    pub fn gap(&self) -> f64 {
        self.gap
    }

    /// True if the gap is within the domain's closure tolerance.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    /// For an open loop followed by another curve: the distance from the loop's last curve's
    /// end to the next curve's start (the loop was cut there because it exceeds the closure
    /// tolerance). `None` for a closed loop or the domain's last loop.
    pub fn gap_to_next(&self) -> Option<f64> {
        self.next_gap
    }
}

/// A planar domain given by its boundary curves, grouped into loops.
///
/// # Semantics
/// - Curves are in boundary order. Consecutive curves whose end and start are within the
///   closure tolerance ([`DEFAULT_RELATIVE_CLOSURE_TOLERANCE`] times the bounding-box diagonal
///   unless given) belong to one loop; a loop ends when the next curve does not continue it, or as soon
///   as a curve returns to the loop's start point.
/// - A loop is closed if its last curve ends within the tolerance of its first curve's start.
///   Crossing-number containment needs every loop closed ([`Domain::require_closed`]);
///   generalized winding numbers accept any collection.
/// - The region is the set of points with odd crossing parity (equivalently, for properly
///   nested loops, outer loops counter-clockwise and holes clockwise give winding number 1).
///   Orientation is reported, never required, by this type.
///
/// # Examples
///
/// ```
/// use rs_spline::{circle, Domain, Orientation, Point, prelude::*};
/// let outer = circle(Point::new(0.0, 0.0), 2.0).unwrap();
/// let hole = circle(Point::new(0.0, 0.0), 1.0).unwrap().reversed();
/// let d = Domain::new(vec![outer, hole]).unwrap();
/// assert_eq!(d.loops().len(), 2);
/// assert!(d.require_closed().is_ok());
/// assert_eq!(d.loop_orientation(1), Orientation::Clockwise);
/// assert!((d.signed_area() - 3.0 * std::f64::consts::PI).abs() < 1e-12);
/// ```
#[derive(Clone, Debug)]
pub struct Domain {
    name: Option<String>,
    curves: Vec<NurbsCurve>,
    loops: Vec<BoundaryLoop>,
    bbox: BoundingBox,
    tolerance: f64,
}

impl Domain {
    /// The same curves grouped again with another closure tolerance (relative to the
    /// bounding-box diagonal, as in [`Domain::with_relative_closure_tolerance`]); the name is
    /// kept.
    ///
    /// # Errors
    /// [`DomainError::InvalidTolerance`].
    pub fn with_closure_tolerance(self, relative_tolerance: f64) -> Result<Self, DomainError> {
        let name = self.name;
        let mut d = Self::with_relative_closure_tolerance(self.curves, relative_tolerance)?;
        d.name = name;
        Ok(d)
    }

    /// Groups `curves` into loops with the default closure tolerance.
    ///
    /// # Errors
    /// [`DomainError::NoCurves`] for an empty list.
    pub fn new(curves: Vec<NurbsCurve>) -> Result<Self, DomainError> {
        Self::with_relative_closure_tolerance(curves, DEFAULT_RELATIVE_CLOSURE_TOLERANCE)
    }

    /// Groups `curves` into loops; `relative_tolerance` times the bounding-box diagonal is the
    /// largest gap between consecutive curves that still counts as meeting.
    ///
    /// # Errors
    /// [`DomainError::NoCurves`], [`DomainError::InvalidTolerance`].
    pub fn with_relative_closure_tolerance(
        curves: Vec<NurbsCurve>,
        relative_tolerance: f64,
    ) -> Result<Self, DomainError> {
        crate::limits::NonNegative::new(relative_tolerance)
            .map_err(|e| DomainError::InvalidTolerance(e.0))?;
        let bbox = curves
            .iter()
            .map(NurbsCurve::bounding_box)
            .reduce(BoundingBox::union)
            .ok_or(DomainError::NoCurves)?;
        let tolerance = relative_tolerance * bbox.diagonal();
        let loops = group_loops(&curves, tolerance);
        Ok(Self {
            name: None,
            curves,
            loops,
            bbox,
            tolerance,
        })
    }

    /// The same domain with a name (kept in the JSON file).
    pub fn with_name(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }

    /// The name, if any.
    pub fn name(&self) -> Option<&str> {
        self.name.as_deref()
    }

    /// The boundary curves, in order.
    pub fn curves(&self) -> &[NurbsCurve] {
        &self.curves
    }

    /// The boundary loops, in order.
    pub fn loops(&self) -> &[BoundaryLoop] {
        &self.loops
    }

    /// Tight bounding box of all curves.
    pub fn bounding_box(&self) -> BoundingBox {
        self.bbox
    }

    /// The absolute closure tolerance in force (relative tolerance times the diagonal).
    pub fn closure_abs_tol(&self) -> f64 {
        self.tolerance
    }

    /// True if every loop is closed and no curve has a gap at a break (see
    /// [`Domain::require_closed`]).
    pub fn is_closed(&self) -> bool {
        self.require_closed().is_ok()
    }

    /// `Ok` if every loop is closed and no curve falls apart at a break (an interior knot of
    /// multiplicity `degree + 1` whose neighbouring pieces are more than the closure tolerance
    /// apart).
    ///
    /// # Errors
    /// [`DomainError::CurveGap`] naming the first curve with a gap and the parameter of the
    /// break; [`DomainError::OpenLoop`] naming the first open loop's curves and its gap.
    pub fn require_closed(&self) -> Result<(), DomainError> {
        for (curve, c) in self.curves.iter().enumerate() {
            if let Some(&(parameter, gap)) = c.breaks().iter().find(|b| b.1 > self.tolerance) {
                return Err(DomainError::CurveGap {
                    curve,
                    parameter,
                    gap,
                    tolerance: self.tolerance,
                });
            }
        }
        match self.loops.iter().find(|l| !l.closed) {
            None => Ok(()),
            // The loop was cut because two consecutive curves miss each other by less than
            // the loop misses its own start: name those two curves, the real cause.
            Some(l) if l.next_gap.is_some_and(|g| g < l.gap) => Err(DomainError::CurvesMiss {
                curve: l.last,
                next: l.last + 1,
                gap: l.next_gap.unwrap_or(l.gap),
                tolerance: self.tolerance,
            }),
            Some(l) => Err(DomainError::OpenLoop {
                first_curve: l.first,
                last_curve: l.last,
                gap: l.gap,
                tolerance: self.tolerance,
            }),
        }
    }

    /// Signed area enclosed by loop `i` (closed by the chord from its end to its start if it is
    /// open): `1/2 oint (x dy - y dx)`, positive for counter-clockwise loops. See
    /// [`Domain::loop_area_integral`] for its error estimate.
    ///
    /// # Panics
    /// If `i` is not a loop index.
    pub fn loop_signed_area(&self, i: usize) -> f64 {
        self.loop_area_integral(i).value
    }

    /// The signed area of loop `i` with the quadrature's error estimate and whether every piece
    /// converged (the work per piece is bounded by
    /// [`crate::quadrature::MAX_INTERVALS`]).
    ///
    /// # Panics
    /// If `i` is not a loop index.
    pub fn loop_area_integral(&self, i: usize) -> Integral {
        let l = &self.loops[i];
        let curves = &self.curves[l.first..=l.last];
        let mut total: Integral = curves
            .iter()
            .flat_map(NurbsCurve::to_bezier)
            .map(|b| b.area_integral())
            .sum();
        let end = curves[curves.len() - 1].end_point();
        let start = curves[0].start_point();
        total.value += 0.5 * end.cross(start);
        total
    }

    /// Sum of the loops' signed areas: the area of the domain when outer loops run
    /// counter-clockwise and holes clockwise.
    pub fn signed_area(&self) -> f64 {
        (0..self.loops.len())
            .map(|i| self.loop_signed_area(i))
            .sum()
    }

    /// Orientation of loop `i` from the sign of its signed area.
    ///
    /// # Panics
    /// If `i` is not a loop index.
    pub fn loop_orientation(&self, i: usize) -> Orientation {
        let a = self.loop_signed_area(i);
        if a > 0.0 {
            Orientation::CounterClockwise
        } else if a < 0.0 {
            Orientation::Clockwise
        } else {
            Orientation::Degenerate
        }
    }

    /// Calls `emit` with the points of loop `i` as one polyline within `accuracy` (an absolute
    /// distance, see [`Flatten::flatten`]) of its curves: the first curve's start point, then
    /// every vertex up to the last curve's end, each point where two curves (or two Bezier
    /// pieces) meet emitted once ([`flatten_chain`](crate::flatten_chain)). The polyline is
    /// not closed: its last point is the last curve's end, which is the loop's
    /// [`gap`](BoundaryLoop::gap) away from the first (within the closure tolerance for a closed
    /// loop, and not necessarily equal to it); a caller that needs a closed ring adds the first
    /// point again when they differ.
    ///
    /// # Panics
    /// If `i` is not a loop index.
    ///
    /// # Examples
    ///
    /// ```
    /// use rs_spline::{circle, Domain, Point};
    /// let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
    /// let mut ring = Vec::new();
    /// d.flatten_loop(0, 1e-3, &mut |p| ring.push(p));
    /// assert_eq!(ring.first(), ring.last());
    /// assert!(ring.iter().all(|p| (p.length() - 1.0).abs() < 1e-12));
    /// ```
    pub fn flatten_loop(&self, i: usize, accuracy: f64, emit: &mut dyn FnMut(Point)) {
        let l = &self.loops[i];
        let curves = self.curves[l.first..=l.last].iter();
        crate::flatten_chain(curves.map(|c| c as &dyn Flatten), accuracy, emit);
    }

    /// Every curve's Bezier pieces, in boundary order, with the index of their curve.
    pub fn bezier_pieces(&self) -> Vec<(usize, RationalBezier)> {
        self.curves
            .iter()
            .enumerate()
            .flat_map(|(i, c)| c.to_bezier().into_iter().map(move |b| (i, b)))
            .collect()
    }
}

/// Splits the curve list into loops (see [`Domain`]'s semantics).
fn group_loops(curves: &[NurbsCurve], tol: f64) -> Vec<BoundaryLoop> {
    let ends: Vec<(Point, Point)> = curves
        .iter()
        .map(|c| (c.start_point(), c.end_point()))
        .collect();
    let mut loops = Vec::new();
    let mut first = 0;
    for i in 0..curves.len() {
        let loop_start = ends[first].0;
        let returns = ends[i].1.distance(loop_start) <= tol;
        let continues = i + 1 < curves.len() && ends[i].1.distance(ends[i + 1].0) <= tol;
        if returns || !continues {
            let gap = ends[i].1.distance(loop_start);
            let closed = gap <= tol;
            let next_gap = match ends.get(i + 1) {
                Some(next) if !closed => Some(ends[i].1.distance(next.0)),
                _ => None,
            };
            loops.push(BoundaryLoop {
                first,
                last: i,
                gap,
                closed,
                next_gap,
            });
            first = i + 1;
        }
    }
    loops
}
