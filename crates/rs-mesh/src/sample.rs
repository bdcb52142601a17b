//! Point sampling in a curved domain: the paper's Algorithm 11.1 and quasi-Monte Carlo.

use rs_boxes::{BoxOptions, MonotoneBoxes};
use rs_contain::baselines::radical_inverse;
use rs_contain::{Classifier, ContainOptions, Location, Method};
use rs_spline::grid::{CellIndex, GridFrame};
use rs_spline::{BoundingBox, Domain, Point};

use crate::MeshError;
use crate::boundary::{BoundaryPoint, check_boundary_pieces, place_boundary_points};
use crate::limits::{MAX_HALTON_TRIES_PER_POINT, MAX_LINES, MAX_SAMPLE_POINTS};

/// Points from [`well_spaced_points`].
#[derive(Clone, Debug)]
pub struct WellSpacedPoints {
    /// The spacing `h = (b - a) / ny`.
    pub h: f64,
    /// Interior points.
    pub interior: Vec<Point>,
    /// Boundary points of each loop, in loop order.
    pub boundary: Vec<Vec<BoundaryPoint>>,
}

impl WellSpacedPoints {
    /// Every point, boundary first.
    pub fn all_points(&self) -> Vec<Point> {
        let mut v: Vec<Point> = self.boundary.iter().flatten().map(|b| b.point).collect();
        v.extend_from_slice(&self.interior);
        v
    }
}

/// The paper's Algorithm 11.1. With `a`, `b` the lowest and highest `y` of the domain and
/// `h = (b - a) / ny`: every line `y = a + i h` (`i = 1..ny-1`) is cut exactly with the boundary
/// through the monotone boxes (one bracketed root per box, half-open in `y` so vertices count
/// once); its segments inside the domain get their end points as boundary points and interior
/// points at spacing `~h`. Then every loop gets nearly equally spaced boundary points (spacing
/// `~h` by arc length, curve starts always included, the line end points kept unless closer
/// than `h/3` to another).
///
/// Interior points closer than `h / 2` to a boundary point, or within `h / 4` of the boundary
/// (the containment test's boundary band), are dropped so no triangle gets a sliver there.
/// Spacing bounds (tested): any two interior points are at least `0.75 h` apart (a segment of
/// length `L` gets `round(L / h)` equal parts, lines are `h` apart); interior points are at
/// least `h / 2` from boundary points; consecutive boundary points on one curve are at least
/// `h / 3` apart by arc length (curve junctions can be closer where a curve is shorter than
/// that). Coverage: every point of the domain is within about `h` of a sample.
///
/// # Errors
/// [`MeshError::TooFewLines`] for `ny < 2` or `ny >` [`MAX_LINES`],
/// [`MeshError::TooManyPieces`] for a boundary of more than [`crate::MAX_MESH_PIECES`] Bezier
/// pieces (checked first), [`MeshError::NoArea`] for a
/// flat domain, [`MeshError::TooManyPoints`] when the lines or the boundary would hold more
/// than [`MAX_SAMPLE_POINTS`] points (counted before they are made), containment errors for an
/// open boundary.
pub fn well_spaced_points(domain: &Domain, ny: usize) -> Result<WellSpacedPoints, MeshError> {
    if !(2..=MAX_LINES).contains(&ny) {
        return Err(MeshError::TooFewLines(ny));
    }
    check_boundary_pieces(domain)?;
    domain.require_closed()?;
    let bb = domain.bounding_box();
    let (a, b) = (bb.min.y, bb.max.y);
    let h = (b - a) / ny as f64;
    if h.is_nan() || h <= 0.0 {
        return Err(MeshError::NoArea);
    }
    let grid = ny as f64 * (bb.width() / h + 1.0);
    if grid.is_nan() || grid > 4.0 * MAX_SAMPLE_POINTS as f64 {
        return Err(MeshError::TooManyPoints {
            estimate: grid,
            limit: MAX_SAMPLE_POINTS,
        });
    }
    let boxes = MonotoneBoxes::new(domain, BoxOptions::DEFAULT.with_subdivisions(1))?;
    let mut interior = Vec::new();
    let mut extra = Vec::new();
    for i in 1..ny {
        let y = a + i as f64 * h;
        let mut hits: Vec<(f64, usize, f64)> = Vec::new();
        for bx in boxes.boxes() {
            if bx.band.ymin <= y
                && y < bx.band.ymax
                && let Some((t, x)) = bx.at_y(y)
            {
                hits.push((x, bx.curve, bx.nurbs_parameter(t)));
            }
        }
        if hits.len() % 2 == 1 {
            continue; // cannot happen for a closed boundary; never pair wrongly
        }
        hits.sort_by(|p, q| p.0.total_cmp(&q.0));
        for pair in hits.chunks_exact(2) {
            let (x0, x1) = (pair[0].0, pair[1].0);
            extra.push((pair[0].1, pair[0].2));
            extra.push((pair[1].1, pair[1].2));
            // Checked before the points are made: a segment's length can be far more than
            // the domain's width in spacings (the crossings of a curve smaller than the
            // rounding of its coordinates are noise: 10^12 points for one segment).
            let parts = ((x1 - x0) / h).round();
            if parts.is_nan() || parts >= (MAX_SAMPLE_POINTS - interior.len()) as f64 {
                return Err(MeshError::TooManyPoints {
                    estimate: interior.len() as f64 + parts,
                    limit: MAX_SAMPLE_POINTS,
                });
            }
            let n = parts as usize;
            for k in 1..n {
                interior.push(Point::new(x0 + (x1 - x0) * k as f64 / n as f64, y));
            }
        }
    }
    let boundary = place_boundary_points(domain, h, &extra)?;
    let near = PointGrid::new(boundary.iter().flatten().map(|p| p.point), h);
    let diag = bb.diagonal();
    let band = Classifier::new(
        domain,
        ContainOptions::DEFAULT.with_relative_tolerance(0.25 * h / diag),
    )?;
    interior.retain(|&p| !near.any_within(p, 0.5 * h));
    // All at once, by the library's fastest method for the count: a point at a time scanned
    // every monotone box (4 s of a 5 s mesh of the butterfly at ny = 300).
    let located = band.locate_all_with(Method::Fast, &interior);
    let mut at = located.iter();
    interior.retain(|_| at.next() == Some(&Location::Inside));
    Ok(WellSpacedPoints {
        h,
        interior,
        boundary,
    })
}

/// The most Halton candidates [`halton_points_in`] classifies at once (1 MB of points).
const HALTON_BATCH: u64 = 1 << 16;

/// The first `count` Halton points (bases 2 and 3, over the bounding box) that lie inside the
/// domain: a deterministic quasi-Monte Carlo sample. Candidates are drawn and classified in
/// batches (by [`Method::Fast`]) sized from the share inside so far, at most 65 536,
/// so memory is the output and one batch.
///
/// # Errors
/// [`MeshError::InvalidCount`] for `count = 0` or above [`MAX_SAMPLE_POINTS`], or when
/// [`MAX_HALTON_TRIES_PER_POINT`]` * count` candidates do not yield `count` inside points
/// (the domain fills almost none of its box); containment errors for an open boundary.
pub fn halton_points_in(domain: &Domain, count: usize) -> Result<Vec<Point>, MeshError> {
    if count == 0 || count > MAX_SAMPLE_POINTS {
        return Err(MeshError::InvalidCount(count));
    }
    let classifier = Classifier::new(domain, ContainOptions::default())?;
    let bb = domain.bounding_box();
    let candidate = |i: u64| {
        Point::new(
            bb.min.x + radical_inverse(i, 2) * bb.width(),
            bb.min.y + radical_inverse(i, 3) * bb.height(),
        )
    };
    let tries = (count as u64).saturating_mul(MAX_HALTON_TRIES_PER_POINT as u64);
    let mut inside = Vec::with_capacity(count);
    let (mut next, mut batch) = (0u64, Vec::new());
    while next < tries {
        // Enough candidates for the points still wanted at the share inside seen so far (a
        // tenth more), no fewer than 64 and no more than a batch.
        let share = if next == 0 {
            1.0
        } else {
            (inside.len() as f64 / next as f64).max(1.0 / MAX_HALTON_TRIES_PER_POINT as f64)
        };
        let wanted = (count - inside.len()) as f64 / share;
        let n = ((1.1 * wanted) as u64)
            .clamp(64, HALTON_BATCH)
            .min(tries - next);
        batch.clear();
        batch.extend((next..next + n).map(candidate));
        next += n;
        let located = classifier.locate_all_with(Method::Fast, &batch);
        for (&p, location) in batch.iter().zip(located) {
            if location == Location::Inside {
                inside.push(p);
                if inside.len() == count {
                    return Ok(inside);
                }
            }
        }
    }
    Err(MeshError::InvalidCount(count))
}

/// The most cells of a [`PointGrid`]: those of a 1024 x 1024 grid.
const MAX_POINT_GRID_CELLS: usize = 1 << 20;

/// Points registered by cell, to ask whether any lies within `r` of a query point.
pub(crate) struct PointGrid {
    points: Vec<Point>,
    index: CellIndex<u32>,
}

impl PointGrid {
    /// Cells about `cell` wide, at most [`MAX_POINT_GRID_CELLS`] of them (then larger, near
    /// square): a query with `r` near `cell` looks at a few cells around the point.
    pub(crate) fn new(points: impl Iterator<Item = Point>, cell: f64) -> Self {
        let points: Vec<Point> = points.collect();
        let bb = BoundingBox::from_points(points.iter().copied())
            .unwrap_or(BoundingBox::from_point(Point::new(0.0, 0.0)));
        let count = |span: f64| {
            if cell > 0.0 && span.is_finite() {
                (span / cell).floor().max(1.0)
            } else {
                1.0
            }
        };
        let (columns, rows) = (count(bb.width()), count(bb.height()));
        // A cap on each side instead (1024) left cells 10^6 wide on a drawing 10^9 long, each
        // holding thousands of boundary points that every query compared: 30 s.
        let frame = if columns * rows <= MAX_POINT_GRID_CELLS as f64 {
            GridFrame::with_counts(bb, columns as usize, rows as usize)
        } else {
            GridFrame::near_square(bb, MAX_POINT_GRID_CELLS)
        };
        let index = CellIndex::of_points(frame, &points);
        Self { points, index }
    }

    /// Is some registered point closer than `r` to `p`? (Every cell meeting the square of
    /// half-side `r` round `p` is searched.)
    pub(crate) fn any_within(&self, p: Point, r: f64) -> bool {
        let near = BoundingBox::from_point(p).grown_by(r);
        let mut found = false;
        self.index.frame().for_cells_in(near, |c| {
            found = found
                || self
                    .index
                    .cell(c)
                    .iter()
                    .any(|&i| self.points[i as usize].distance(p) < r);
        });
        found
    }
}
