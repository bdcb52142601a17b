//! Point in a solid: whether a point of space is inside, outside or on the boundary of a B-rep
//! solid, by the signed crossings of a ray with its trimmed faces.
//!
//! # Method
//!
//! A [`SolidClassifier`] is built once per solid: each face's surface is cut into patches
//! (its `(u, v)` box cut at the surface's knot lines, then halved while the normals of a piece
//! spread more than 0.2 radians from its centre's), each with a box in space that holds it, all
//! in one bounding-volume hierarchy; each face keeps its trimming loops as an exact 2-D
//! classifier. A grid of at most 2^18 cells (at least 16 a side) over the solid's box marks
//! the cells the patch boxes reach (patches quartered until a box reaches at most 8 cells);
//! each connected set of the other cells lies wholly inside or wholly outside (no face passes
//! between two of them), and rays from its first and last cells decide it (where they agree).
//! Each marked cell keeps the patches that marked it and the nearest decided cell.
//!
//! For a point `p` in an unmarked cell the answer is the cell's. Otherwise:
//!
//! 1. **Boundary.** `p` is [`Location::Boundary`] when it lies within the tolerance `T` of a
//!    face: the foot of `p` on a patch whose box holds it is within `T` and lies on the face
//!    (the face's 2-D test in `(u, v)`, its band included), or a 3-D edge of such a face is
//!    within `T`.
//! 2. **Segment.** The segment from `p` to the centre `q` of its cell's nearest decided cell
//!    is cast: every patch whose box it meets is solved by Newton's method on
//!    `S(u, v) = p + t d` from the patch's centre, the iterates held within the surface's
//!    parameter range (past it a bounded surface is evaluated at its end). A patch whose normals (the sampled cone
//!    widened by 1.25 and 0.002 radians) all stay off the ray's normal plane is crossed at most
//!    once; patches the ray grazes are quartered again (six times at most). Each crossing is
//!    kept when its `(u, v)` is inside the face by the exact 2-D test and counted with its sign
//!    (`+1` leaving the solid, where the ray runs along the face's outward normal); `p` is
//!    inside when `q`'s state plus the signed count is `1`, outside when it is `0`.
//! 3. **Rays.** Where the segment is degenerate, rays to infinity in 16 fixed directions (none
//!    along an axis) are cast in turn, the first clean one deciding (a signed count of `1`
//!    inside, `0` outside). A segment or ray is **degenerate** when it meets a crossing in a
//!    face's boundary band (through an edge or a vertex, or a gap between faces the file's
//!    tolerance allows), a patch still grazed at the finest split, a Newton iteration that
//!    does not settle, or a count other than `0` or `1`. A point all 16 rays find degenerate
//!    is reported [`Location::Boundary`].
//!
//! # Tolerance
//!
//! `T = max(stated, relative x size)`: `stated` the file's own tolerance, `size` the diagonal of
//! the solid's box, `relative` [`DEFAULT_RELATIVE_TOLERANCE`] (`1e-8`: CAD files print about
//! ten significant digits, so faces meet to that) unless given. Each face's 2-D band is `T`
//! divided by the smallest speed `min(|S_u|, |S_v|)` of its surface sampled on its patches.
//! Inside and outside are exact for points farther than `T` from every face, up to the
//! rounding of Newton's method (to `64 eps` of the size).
//!
//! # Limits
//!
//! The solid must be closed (every shell closed: an open one is an error naming its free
//! edges) and consistently oriented (its volume positive and its faces' net area vector
//! `|sum n dA|` at most `1e-3` of its area, else an error). Patch boxes are the box of `5 x 5`
//! samples grown by 1.25 times the error of linear interpolation with the largest sampled
//! second derivatives: a surface whose curvature changes wildly between samples could leave
//! its box (real files' surfaces do not), and a connected set of grid cells is decided by one
//! ray on the strength of those boxes.

mod bvh;
mod grid;
mod patches;
mod roots;

use std::f64::consts::TAU;

use rs_contain::{Classifier, ContainOptions};
pub use rs_contain::{Locate, Location, PointQuery};
use rs_spline::{Point, Point3};
use smallvec::SmallVec;
use thiserror::Error;

use crate::PRINTED_DIGITS;
use crate::brep::{Edge, Model, ModelError};
use crate::properties::PropertiesError;
use crate::surface::{ParamSurface, Surface};
use bvh::{Bvh, ray_meets_box};
use grid::{CellState, Grid};
use patches::{Cell, Patch, face_patches, knot_cells, part_box};
use roots::{Crossing, foot, ray_crossing};

/// The default boundary tolerance relative to the diagonal of a solid's box (the file's own
/// tolerance when larger): CAD files print about ten significant digits.
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = PRINTED_DIGITS;

/// Rays shot at most for one point.
pub const MAX_RAYS: usize = 16;

/// How many times a patch is quartered at most to mark the grid cells it passes through.
const MARK_SPLITS: usize = 10;

/// How many times a patch grazed by a ray is quartered at most.
const QUERY_SPLITS: usize = 6;

/// A crossing is degenerate when the ray makes a smaller cosine with the normal there.
const MIN_COSINE: f64 = 1e-3;

/// The largest net area vector `|sum n dA|` of a consistently oriented solid, relative to its
/// area.
pub const MAX_RELATIVE_LEAK: f64 = 1e-3;

/// The widest 2-D boundary band of a face, relative to its `(u, v)` diagonal.
const MAX_RELATIVE_BAND: f64 = 1e-2;

/// Why a solid cannot be classified against.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum SolidError {
    /// No such solid, or a face that cannot be read.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// An open shell (naming its free edges), a face without surface: the checks of
    /// [`Model::solid_properties`].
    #[error(transparent)]
    Properties(#[from] PropertiesError),
    /// The faces are not consistently oriented: the volume they bound is not positive, or
    /// their net area vector is more than [`MAX_RELATIVE_LEAK`] of their area.
    #[error(
        "solid {solid}: its faces are not consistently oriented (volume {volume:.6e}, net area \
         vector {leak:.3e} of area {area:.6e}); a point-in-solid test needs outward normals"
    )]
    Orientation {
        /// The solid.
        solid: usize,
        /// The volume its faces bound.
        volume: f64,
        /// The length of the net area vector.
        leak: f64,
        /// The area.
        area: f64,
    },
    /// A face whose trimming loops cannot be made a 2-D classifier.
    #[error("face {index}: {error}")]
    Trim {
        /// The face's index.
        index: usize,
        /// Why.
        error: String,
    },
    /// A relative tolerance that is negative or not finite.
    #[error("the relative tolerance must be a finite number >= 0, not {0}")]
    InvalidTolerance(f64),
}

/// One face of the solid: its surface, outward sense, trimming test and edges.
struct SolidFace {
    surface: Surface,
    /// `+1` where the outward normal is `S_u x S_v`, `-1` otherwise.
    sense: f64,
    /// The parameters the surface is evaluated at without clamping.
    domain: Cell,
    /// The face's trimming test.
    trim: Classifier,
    edges: Vec<Edge>,
}

/// A solid prepared for point queries (see the module documentation). `Send + Sync`: one
/// classifier answers from many threads.
///
/// A model comes from a STEP or IGES file (`rs_io::cad::CadModel::read`); then
/// `SolidClassifier::new(&model, k)?.locate(point)` says where a point lies, and
/// `par_values_into(&points[..], &mut out)` where many do. A solid index the model does not
/// have is an error:
///
/// ```
/// use rs_geom::brep::Model;
/// use rs_geom::solid::SolidClassifier;
/// let e = SolidClassifier::new(&Model::default(), 0).err().unwrap();
/// assert_eq!(e.to_string(), "solid 0 does not exist: the file has no solids");
/// ```
pub struct SolidClassifier {
    faces: Vec<SolidFace>,
    /// Model face index of each face.
    face_indices: Vec<usize>,
    patches: Vec<Patch>,
    bvh: Bvh,
    grid: Grid,
    lo: Point3,
    hi: Point3,
    size: f64,
    tolerance: f64,
}

impl SolidClassifier {
    /// Solid `index` of `model` with the [`DEFAULT_RELATIVE_TOLERANCE`].
    ///
    /// # Errors
    /// See [`SolidClassifier::with_relative_tolerance`].
    pub fn new(model: &Model, index: usize) -> Result<Self, SolidError> {
        Self::with_relative_tolerance(model, index, DEFAULT_RELATIVE_TOLERANCE)
    }

    /// Solid `index` of `model`, points within `max(stated, relative x size)` of a face
    /// being [`Location::Boundary`].
    ///
    /// # Errors
    /// [`SolidError::InvalidTolerance`]; [`ModelError::NoSolid`]; an open shell or a face
    /// without surface or loops ([`SolidError::Properties`], [`SolidError::Model`]);
    /// [`SolidError::Orientation`].
    pub fn with_relative_tolerance(
        model: &Model,
        index: usize,
        relative: f64,
    ) -> Result<Self, SolidError> {
        if !(relative >= 0.0 && relative.is_finite()) {
            return Err(SolidError::InvalidTolerance(relative));
        }
        let props = model.solid_properties(index)?;
        let oriented = props.volume > 0.0 && props.leak_area <= MAX_RELATIVE_LEAK * props.area;
        if !oriented {
            return Err(SolidError::Orientation {
                solid: index,
                volume: props.volume,
                leak: props.leak_area,
                area: props.area,
            });
        }
        let solid = &model.solids[index];
        let mut face_indices: Vec<usize> = Vec::new();
        for &s in &solid.shells {
            for &f in &model.shells[s].faces {
                if !face_indices.contains(&f) {
                    face_indices.push(f);
                }
            }
        }
        // Each face's patches first (their boxes give the size, the size the tolerance, the
        // tolerance each face's 2-D band).
        let mut read = Vec::with_capacity(face_indices.len());
        let mut patches = Vec::new();
        for (k, &f) in face_indices.iter().enumerate() {
            let domain = model.face_domain(f, None)?;
            let face = &model.faces[f];
            let Some(surface) = face.surface.clone() else {
                // solid_properties has checked that every face has a surface.
                continue;
            };
            let bbox = domain.bounding_box();
            let cells = face_cells(&surface, (bbox.min.x, bbox.max.x), (bbox.min.y, bbox.max.y));
            let mine = face_patches(k as u32, &surface, &cells, 0.0);
            let slowest = slowest_speed(&mine);
            patches.extend(mine);
            read.push(ReadFace {
                index: f,
                domain,
                speed: slowest,
                surface,
                same_sense: face.same_sense,
                edges: face.edges.iter().flatten().cloned().collect(),
            });
        }
        let (lo, hi) =
            Point3::bounds(patches.iter().flat_map(|p| [p.lo, p.hi])).unwrap_or_default();
        let size = (hi - lo).length();
        let size = if size > 0.0 && size.is_finite() {
            size
        } else {
            1.0
        };
        let tolerance = model.tolerance.stated().unwrap_or(0.0).max(relative * size);
        let grow = Point3::new(tolerance, tolerance, tolerance);
        for p in &mut patches {
            p.lo = p.lo - grow;
            p.hi = p.hi + grow;
        }
        let mut faces = Vec::with_capacity(read.len());
        let mut indices = Vec::with_capacity(read.len());
        for r in read {
            let diagonal = r.domain.bounding_box().diagonal();
            let band = if r.speed > 0.0 && r.speed.is_finite() && diagonal > 0.0 {
                (tolerance / r.speed / diagonal).min(MAX_RELATIVE_BAND)
            } else {
                MAX_RELATIVE_BAND
            };
            let trim = Classifier::new(
                &r.domain,
                ContainOptions::DEFAULT.with_relative_tolerance(band),
            )
            .map_err(|error| SolidError::Trim {
                index: r.index,
                error: error.to_string(),
            })?;
            faces.push(SolidFace {
                domain: Cell::domain_of(&r.surface),
                surface: r.surface,
                sense: if r.same_sense { 1.0 } else { -1.0 },
                trim,
                edges: r.edges,
            });
            indices.push(r.index);
        }
        let boxes: Vec<(Point3, Point3)> = patches.iter().map(|p| (p.lo, p.hi)).collect();
        let mut me = SolidClassifier {
            bvh: Bvh::new(&boxes),
            grid: Grid::single(lo - grow, hi + grow),
            faces,
            face_indices: indices,
            patches,
            lo: lo - grow,
            hi: hi + grow,
            size,
            tolerance,
        };
        me.grid = Grid::new(
            me.lo,
            me.hi,
            |grid, visit| {
                for (k, patch) in me.patches.iter().enumerate() {
                    me.mark(grid, k as u32, patch.cell, MARK_SPLITS, visit);
                }
            },
            |p| me.by_rays(p).map(|l| l == Location::Inside),
        );
        Ok(me)
    }

    /// Calls `visit(cell, patch)` for the cells the part `cell` of patch `patch` may pass
    /// within the tolerance of, quartering the part (at most `splits` times) while its box
    /// reaches more than 8 cells.
    fn mark(
        &self,
        grid: &Grid,
        patch: u32,
        cell: Cell,
        splits: usize,
        visit: &mut dyn FnMut(usize, u32),
    ) {
        let p = &self.patches[patch as usize];
        let surface = &self.faces[p.face as usize].surface;
        let (lo, hi) = part_box(surface, cell, p.bend, self.tolerance);
        let r = grid.ranges(lo, hi);
        let count: usize = r.iter().map(|(a, b)| b - a + 1).product();
        if count <= 8 || splits == 0 {
            for i in r[0].0..=r[0].1 {
                for j in r[1].0..=r[1].1 {
                    for k in r[2].0..=r[2].1 {
                        visit(grid.linear([i, j, k]), patch);
                    }
                }
            }
            return;
        }
        for q in cell.quarters() {
            self.mark(grid, patch, q, splits - 1, visit);
        }
    }

    /// The boundary tolerance `T` (model units).
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// The box of the solid, grown by the tolerance: `(lower, upper)` corners.
    pub fn bounds(&self) -> (Point3, Point3) {
        (self.lo, self.hi)
    }

    /// The model's indices of the solid's faces.
    pub fn faces(&self) -> &[usize] {
        &self.face_indices
    }

    /// How many patches the faces were cut into.
    pub fn patch_count(&self) -> usize {
        self.patches.len()
    }

    /// Where `p` lies (see the module documentation); [`PointQuery::value`].
    fn location(&self, p: Point3) -> Location {
        let (lo, hi) = (self.lo, self.hi);
        let in_box =
            p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
        if !in_box {
            return Location::Outside;
        }
        let reference = match self.grid.state(p) {
            CellState::Inside => return Location::Inside,
            CellState::Outside => return Location::Outside,
            CellState::Mixed(reference) => reference,
        };
        if self.near_boundary(p) {
            return Location::Boundary;
        }
        if let Some(r) = reference {
            let inside = self.grid.state_of(r) == CellState::Inside;
            if let Some(l) = self.by_segment(p, self.grid.centre(r as usize), inside) {
                return l;
            }
        }
        self.by_rays(p).unwrap_or(Location::Boundary)
    }

    /// Where `p` lies by the crossings of the segment to `q`, a point `inside` or not, far
    /// from every face; `None` where the segment is degenerate.
    fn by_segment(&self, p: Point3, q: Point3, inside: bool) -> Option<Location> {
        let d = q - p;
        let length = d.length();
        let d = d * (1.0 / length);
        let usable = length > 0.0 && d.is_finite() && d.x != 0.0 && d.y != 0.0 && d.z != 0.0;
        if !usable {
            return None;
        }
        self.cast(p, d, length).location(inside)
    }

    /// Where `p` (not within the tolerance of a face) lies by the crossings of rays to
    /// infinity in the fixed directions, the first that is not degenerate; `None` if all are.
    fn by_rays(&self, p: Point3) -> Option<Location> {
        // Infinity is outside.
        (0..MAX_RAYS).find_map(|k| {
            self.cast(p, ray_direction(k), f64::INFINITY)
                .location(false)
        })
    }

    /// Whether `p` is within the tolerance of a face.
    fn near_boundary(&self, p: Point3) -> bool {
        let mut near = false;
        let mut edges_seen: Vec<u32> = Vec::new();
        let mut visit = |i: u32| {
            if near {
                return;
            }
            let patch = &self.patches[i as usize];
            if !patch.may_reach(p, 2.0 * self.tolerance) {
                return;
            }
            let face = &self.faces[patch.face as usize];
            let (uv, distance) = foot(&face.surface, patch.cell, p);
            if distance > 2.0 * self.tolerance {
                // An edge within T lies within T + the file's tolerance (<= T) of the surface.
                return;
            }
            if distance <= self.tolerance && face.on_face(uv) {
                near = true;
                return;
            }
            if !edges_seen.contains(&patch.face) {
                edges_seen.push(patch.face);
                near = face.edges.iter().any(|e| {
                    let t = e.curve.closest_parameter(p, Some(e.range));
                    e.curve.point(t).distance(p) <= self.tolerance
                });
            }
        };
        // The patches that marked the point's cell are those that may pass within T of it.
        match self.grid.members(self.grid.index(p)) {
            Some(list) => list.iter().for_each(|&i| visit(i)),
            None => self.bvh.holding(p, visit),
        }
        near
    }

    /// The signed count of the crossings of the ray `p + t d`, `0 < t < length`.
    fn cast(&self, p: Point3, d: Point3, length: f64) -> Cast {
        let inv = Point3::new(1.0 / d.x, 1.0 / d.y, 1.0 / d.z);
        let mut ray = Ray {
            p,
            d,
            inv,
            length,
            hits: SmallVec::new(),
            outcome: None,
        };
        self.bvh.along_ray(p, inv, -self.tolerance, length, |i| {
            if ray.outcome.is_none() {
                self.patch_crossings(&mut ray, &self.patches[i as usize], QUERY_SPLITS);
            }
        });
        if let Some(outcome) = ray.outcome {
            return outcome;
        }
        // The same crossing found from two neighbouring patches counts once.
        let hits = &mut ray.hits;
        hits.sort_by(|a, b| a.face.cmp(&b.face).then(a.t.total_cmp(&b.t)));
        let same = 1e-9 * self.size;
        let mut count = 0i64;
        let mut last: Option<Hit> = None;
        for &h in hits.iter() {
            if last.is_some_and(|l| l.face == h.face && h.t - l.t <= same) {
                continue;
            }
            count += h.sign;
            last = Some(h);
        }
        Cast::Count(count)
    }

    /// The crossings of `ray` with `patch` (quartered `splits` more times at most where the
    /// ray grazes it), recorded in `ray`.
    fn patch_crossings(&self, ray: &mut Ray, patch: &Patch, splits: usize) {
        let face = &self.faces[patch.face as usize];
        if !patch.is_transversal(ray.d) {
            if splits == 0 {
                ray.outcome = Some(Cast::Degenerate);
                return;
            }
            for q in patch.split(&face.surface, self.tolerance) {
                if ray.outcome.is_none()
                    && ray_meets_box(ray.p, ray.inv, -self.tolerance, ray.length, q.lo, q.hi)
                {
                    self.patch_crossings(ray, &q, splits - 1);
                }
            }
            return;
        }
        let got = ray_crossing(
            &face.surface,
            patch.cell,
            face.domain,
            ray.p,
            ray.d,
            self.size,
        );
        let (uv, t) = match got {
            Crossing::None => return,
            Crossing::Unsettled => {
                ray.outcome = Some(Cast::Degenerate);
                return;
            }
            Crossing::At { uv, t } => (uv, t),
        };
        if t < -self.tolerance || t > ray.length {
            return;
        }
        let trim = &face.trim;
        match trim.locate(Point::new(uv[0], uv[1])) {
            Location::Outside => {}
            Location::Boundary => ray.outcome = Some(Cast::Degenerate),
            Location::Inside if t <= self.tolerance => ray.outcome = Some(Cast::OnFace),
            Location::Inside => match face.surface.normal(uv) {
                Some(n) => {
                    let c = ray.d.dot(n) * face.sense;
                    if c.abs() < MIN_COSINE {
                        ray.outcome = Some(Cast::Degenerate);
                    } else {
                        ray.hits.push(Hit {
                            face: patch.face,
                            t,
                            sign: if c > 0.0 { 1 } else { -1 },
                        });
                    }
                }
                None => ray.outcome = Some(Cast::Degenerate),
            },
        }
    }
}

/// Locations of points of space: [`Locate::locate`] for one, [`PointQuery::values_into`] and
/// [`PointQuery::par_values_into`] for slices (all cores). A point with a coordinate that is
/// not finite is [`Location::Outside`].
impl PointQuery<Location, Point3> for SolidClassifier {
    fn value(&self, p: Point3) -> Location {
        self.location(p)
    }

    /// Points near the faces cost microseconds each, the others nanoseconds: small tasks keep
    /// the threads evenly busy.
    fn parallel_chunk(&self) -> usize {
        256
    }
}

/// A face as read, before the tolerance is known.
struct ReadFace {
    index: usize,
    domain: rs_spline::Domain,
    speed: f64,
    surface: Surface,
    same_sense: bool,
    edges: Vec<Edge>,
}

impl SolidFace {
    /// Whether `uv` is on the face (inside it or in its boundary band).
    fn on_face(&self, uv: [f64; 2]) -> bool {
        self.trim.locate(Point::new(uv[0], uv[1])) != Location::Outside
    }
}

/// What one ray found.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Cast {
    /// The signed count of its crossings: `1` inside, `0` outside.
    Count(i64),
    /// The point lies on a face (within the tolerance along the ray).
    OnFace,
    /// The ray cannot tell: shoot another.
    Degenerate,
}

impl Cast {
    /// Where the start of a segment or ray lies whose end is `inside` or not: its end's state
    /// plus the signed count (`+1` for each crossing leaving the solid), when that is `0` or
    /// `1`; `None` where the cast cannot tell.
    fn location(self, inside: bool) -> Option<Location> {
        match self {
            Cast::Count(s) => match i64::from(inside) + s {
                0 => Some(Location::Outside),
                1 => Some(Location::Inside),
                _ => None,
            },
            Cast::OnFace => Some(Location::Boundary),
            Cast::Degenerate => None,
        }
    }
}

/// A crossing of a ray with a face.
#[derive(Clone, Copy, Debug)]
struct Hit {
    face: u32,
    t: f64,
    /// `+1` leaving the solid, `-1` entering it.
    sign: i64,
}

/// A ray being cast.
struct Ray {
    p: Point3,
    d: Point3,
    inv: Point3,
    length: f64,
    /// A ray crosses a few faces: on the stack.
    hits: SmallVec<[Hit; 16]>,
    outcome: Option<Cast>,
}

/// A face's `(u, v)` box `u x v` cut at its surface's knot lines; non-periodic parameters held
/// in the surface's parameter box (a pcurve may stray past a B-spline's by rounding).
fn face_cells(surface: &Surface, u: (f64, f64), v: (f64, f64)) -> Vec<Cell> {
    let held = Cell { u, v }.intersection(&Cell::domain_of(surface));
    knot_cells(held.u, held.v, &surface.knot_lines())
}

/// The smallest sampled speed of a face's patches, leaving out those below `1e-3` of the
/// largest (at a pole, where the speed is zero whatever the tolerance).
fn slowest_speed(patches: &[Patch]) -> f64 {
    let fastest = patches.iter().map(|p| p.speed).fold(0.0, f64::max);
    patches
        .iter()
        .map(|p| p.speed)
        .filter(|&s| s > 1e-3 * fastest)
        .fold(f64::INFINITY, f64::min)
}

/// Ray direction `k` of [`MAX_RAYS`]: points of a golden-angle spiral on the sphere, turned
/// so that no component is near zero (no ray runs along an axis or in a coordinate plane,
/// where the faces of real parts lie).
fn ray_direction(k: usize) -> Point3 {
    let n = MAX_RAYS as f64;
    let z = 1.0 - (2.0 * k as f64 + 1.0) / n;
    let r = (1.0 - z * z).sqrt();
    let a = k as f64 * TAU * 0.381_966_011_250_105_1 + 0.577_215_664_901_532_9;
    let d = Point3::new(r * a.cos(), r * a.sin(), z);
    // A fixed rotation about (1, 2, 3) by 1 radian.
    let axis = Point3::new(1.0, 2.0, 3.0) * (1.0 / 14f64.sqrt());
    let (s, c) = 1f64.sin_cos();
    let d = d * c + axis.cross(d) * s + axis * (axis.dot(d) * (1.0 - c));
    d * (1.0 / d.length())
}
