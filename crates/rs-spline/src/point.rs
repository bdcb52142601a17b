//! Points (and vectors) in the plane, and axis-aligned bounding boxes.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A coordinate axis of the plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Axis {
    /// The abscissa `x`.
    X,
    /// The ordinate `y`.
    Y,
}

impl Axis {
    /// Both axes, `X` first.
    pub const BOTH: [Axis; 2] = [Axis::X, Axis::Y];

    /// The other axis.
    pub fn other(self) -> Axis {
        match self {
            Axis::X => Axis::Y,
            Axis::Y => Axis::X,
        }
    }
}

/// A point or a vector in the plane: one type for both, as in the papers' formulas (a
/// difference of points, a derivative `C'(u)` and a normal are `Point`s too).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Point {
    /// Abscissa.
    pub x: f64,
    /// Ordinate.
    pub y: f64,
}

impl Point {
    /// The point `(x, y)`.
    pub const fn new(x: f64, y: f64) -> Self {
        Self { x, y }
    }

    /// The coordinate along `axis`.
    pub fn coord(self, axis: Axis) -> f64 {
        match axis {
            Axis::X => self.x,
            Axis::Y => self.y,
        }
    }

    /// Dot product `x1 x2 + y1 y2`.
    pub fn dot(self, o: Point) -> f64 {
        self.x * o.x + self.y * o.y
    }

    /// Cross product (z-component) `x1 y2 - y1 x2`: positive when `o` is counter-clockwise
    /// from `self`.
    pub fn cross(self, o: Point) -> f64 {
        self.x * o.y - self.y * o.x
    }

    /// Euclidean length `sqrt(x^2 + y^2)`.
    pub fn length(self) -> f64 {
        self.x.hypot(self.y)
    }

    /// Euclidean distance to `o`.
    pub fn distance(self, o: Point) -> f64 {
        (self - o).length()
    }

    /// Linear interpolation `(1 - t) self + t o`.
    pub fn lerp(self, o: Point, t: f64) -> Point {
        Point::new(self.x + t * (o.x - self.x), self.y + t * (o.y - self.y))
    }

    /// True if both coordinates are finite.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }

    /// The vector rotated by +90 degrees, `(-y, x)`.
    pub fn perp(self) -> Point {
        Point::new(-self.y, self.x)
    }
}

impl From<[f64; 2]> for Point {
    fn from(a: [f64; 2]) -> Self {
        Point::new(a[0], a[1])
    }
}

impl From<Point> for [f64; 2] {
    fn from(p: Point) -> Self {
        [p.x, p.y]
    }
}

impl Add for Point {
    type Output = Point;
    fn add(self, o: Point) -> Point {
        Point::new(self.x + o.x, self.y + o.y)
    }
}

impl Sub for Point {
    type Output = Point;
    fn sub(self, o: Point) -> Point {
        Point::new(self.x - o.x, self.y - o.y)
    }
}

impl Mul<f64> for Point {
    type Output = Point;
    fn mul(self, s: f64) -> Point {
        Point::new(self.x * s, self.y * s)
    }
}

impl Div<f64> for Point {
    type Output = Point;
    fn div(self, s: f64) -> Point {
        Point::new(self.x / s, self.y / s)
    }
}

impl Neg for Point {
    type Output = Point;
    fn neg(self) -> Point {
        Point::new(-self.x, -self.y)
    }
}

/// An axis-aligned bounding box `[min.x, max.x] x [min.y, max.y]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoundingBox {
    /// Lower-left corner.
    pub min: Point,
    /// Upper-right corner.
    pub max: Point,
}

impl BoundingBox {
    /// The box of a single point.
    pub fn from_point(p: Point) -> Self {
        Self { min: p, max: p }
    }

    /// The smallest box holding all points, or `None` for an empty iterator.
    pub fn from_points(points: impl IntoIterator<Item = Point>) -> Option<Self> {
        let mut it = points.into_iter();
        let first = it.next()?;
        Some(it.fold(Self::from_point(first), |b, p| b.including(p)))
    }

    /// The box grown to hold `p`.
    pub fn including(self, p: Point) -> Self {
        Self {
            min: Point::new(self.min.x.min(p.x), self.min.y.min(p.y)),
            max: Point::new(self.max.x.max(p.x), self.max.y.max(p.y)),
        }
    }

    /// The smallest box holding both boxes.
    pub fn union(self, o: BoundingBox) -> Self {
        self.including(o.min).including(o.max)
    }

    /// Width `max.x - min.x`.
    pub fn width(&self) -> f64 {
        self.max.x - self.min.x
    }

    /// Height `max.y - min.y`.
    pub fn height(&self) -> f64 {
        self.max.y - self.min.y
    }

    /// Length of the diagonal: the domain-size scale used by relative tolerances.
    pub fn diagonal(&self) -> f64 {
        self.width().hypot(self.height())
    }

    /// The box grown by `d` on every side.
    pub fn grown_by(self, d: f64) -> Self {
        Self {
            min: Point::new(self.min.x - d, self.min.y - d),
            max: Point::new(self.max.x + d, self.max.y + d),
        }
    }

    /// Is `p` in the closed box?
    pub fn contains(&self, p: Point) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }

    /// Do the closed boxes share a point?
    ///
    /// ```
    /// use rs_spline::{BoundingBox, Point};
    /// let unit = BoundingBox::from_point(Point::new(0.0, 0.0)).including(Point::new(1.0, 1.0));
    /// let corner = BoundingBox::from_point(Point::new(1.0, 1.0)).including(Point::new(2.0, 3.0));
    /// let beside = BoundingBox::from_point(Point::new(1.5, 0.0)).including(Point::new(2.0, 1.0));
    /// assert!(unit.overlaps(&corner) && corner.overlaps(&unit));
    /// assert!(!unit.overlaps(&beside) && !beside.overlaps(&unit));
    /// ```
    pub fn overlaps(&self, other: &BoundingBox) -> bool {
        self.min.x <= other.max.x
            && other.min.x <= self.max.x
            && self.min.y <= other.max.y
            && other.min.y <= self.max.y
    }
}
