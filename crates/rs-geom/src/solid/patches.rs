//! A face's surface cut into patches: rectangles of `(u, v)` whose piece of surface is nearly
//! flat (its normals within a narrow cone), each with a box in space that holds it. A ray whose
//! direction stays clear of every tangent plane of a patch crosses it at most once, and
//! Newton's method from the patch's centre finds that crossing; patches a ray grazes are
//! halved again while the ray is cast ([`Patch::split`]).

use std::f64::consts::FRAC_PI_2;

use rs_spline::Point3;

use crate::surface::{ParamSurface, Surface};

/// Samples per side of a patch (corners and edges included).
const SAMPLES: usize = 5;

/// The widest normal cone (half angle, radians) of a patch made while building; wider ones
/// are halved.
const MAX_CONE: f64 = 0.2;

/// The most halvings of one knot cell while building.
const MAX_BUILD_SPLITS: usize = 12;

/// The most patches of one face; past it, cells become patches as they are (a ray grazing
/// them halves them while it is cast).
pub(super) const MAX_PATCHES_PER_FACE: usize = 4096;

/// How far a ray's direction must stay from a patch's tangent planes (radians), beyond the
/// widened cone, for the patch to be crossed at most once and its crossing to be well
/// conditioned (a plane's cone is exact: this alone).
const CLEARANCE: f64 = 2e-3;

/// Safety factor on sampled normal cones and on the second-derivative margin of boxes.
const SAFETY: f64 = 1.25;

/// A rectangle of a surface's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Cell {
    pub(super) u: (f64, f64),
    pub(super) v: (f64, f64),
}

impl Cell {
    /// The centre.
    pub(super) fn centre(&self) -> [f64; 2] {
        [0.5 * (self.u.0 + self.u.1), 0.5 * (self.v.0 + self.v.1)]
    }

    /// The sides' lengths.
    pub(super) fn sides(&self) -> [f64; 2] {
        [self.u.1 - self.u.0, self.v.1 - self.v.0]
    }

    /// The cell grown by `fraction` of its sides on every side.
    pub(super) fn grown(&self, fraction: f64) -> Cell {
        let [a, b] = self.sides();
        Cell {
            u: (self.u.0 - fraction * a, self.u.1 + fraction * a),
            v: (self.v.0 - fraction * b, self.v.1 + fraction * b),
        }
    }

    /// Whether `uv` lies in the cell (ends included).
    pub(super) fn contains(&self, uv: [f64; 2]) -> bool {
        uv[0] >= self.u.0 && uv[0] <= self.u.1 && uv[1] >= self.v.0 && uv[1] <= self.v.1
    }

    /// The cell held in `other`, each parameter apart: its range's part in `other`'s, or its
    /// own range where the two share no interval (a face's box beside a surface's parameter
    /// box by rounding keeps its own).
    pub(super) fn intersection(&self, other: &Cell) -> Cell {
        let within = |(a, b): (f64, f64), (lo, hi): (f64, f64)| {
            if a.max(lo) < b.min(hi) {
                (a.max(lo), b.min(hi))
            } else {
                (a, b)
            }
        };
        Cell {
            u: within(self.u, other.u),
            v: within(self.v, other.v),
        }
    }

    /// The parameters a surface is evaluated at without clamping: its parameter box, infinite
    /// in a periodic parameter.
    pub(super) fn domain_of(surface: &Surface) -> Cell {
        let b = surface.param_box();
        let p = surface.periods();
        let range = |i: usize| {
            if p[i].is_some() {
                (f64::NEG_INFINITY, f64::INFINITY)
            } else {
                b.range(i)
            }
        };
        Cell {
            u: range(0),
            v: range(1),
        }
    }

    /// The four quarters.
    pub(super) fn quarters(&self) -> [Cell; 4] {
        let [a, b] = self.halves(0);
        let [a0, a1] = a.halves(1);
        let [b0, b1] = b.halves(1);
        [a0, a1, b0, b1]
    }

    /// `uv` clamped into the cell.
    pub(super) fn clamp(&self, uv: [f64; 2]) -> [f64; 2] {
        [
            uv[0].clamp(self.u.0, self.u.1),
            uv[1].clamp(self.v.0, self.v.1),
        ]
    }

    /// The halves across parameter `axis`.
    pub(super) fn halves(&self, axis: usize) -> [Cell; 2] {
        let [mu, mv] = self.centre();
        if axis == 0 {
            [
                Cell {
                    u: (self.u.0, mu),
                    v: self.v,
                },
                Cell {
                    u: (mu, self.u.1),
                    v: self.v,
                },
            ]
        } else {
            [
                Cell {
                    u: self.u,
                    v: (self.v.0, mv),
                },
                Cell {
                    u: self.u,
                    v: (mv, self.v.1),
                },
            ]
        }
    }
}

/// A patch of one face's surface.
#[derive(Clone, Copy, Debug)]
pub(super) struct Patch {
    /// The face (an index into the solid classifier's faces).
    pub(super) face: u32,
    /// Its parameters.
    pub(super) cell: Cell,
    /// A box holding the patch, grown by the boundary tolerance.
    pub(super) lo: Point3,
    /// The box's upper corner.
    pub(super) hi: Point3,
    /// The unit normal `S_u x S_v` at the centre (zero where it is not defined).
    pub(super) normal: Point3,
    /// A ray of unit direction `d` crosses the patch at most once, transversally, when
    /// `|d . normal| > graze` (`graze >= 1` where no cone is known).
    pub(super) graze: f64,
    /// The smallest parameter speed `min(|S_u|, |S_v|)` sampled (zero at a pole).
    pub(super) speed: f64,
    /// The largest second derivatives `|S_uu|`, `|S_uv|`, `|S_vv|` sampled: they bound how
    /// far the surface leaves the box of points of any part of the patch.
    pub(super) bend: [f64; 3],
    /// The point at the centre of the cell.
    pub(super) centre: Point3,
    /// The patch lies within this distance of the plane through `centre` normal to `normal`
    /// (the samples' farthest, grown as the box is; infinite without a normal).
    pub(super) thickness: f64,
}

impl Patch {
    /// Whether `p` may lie within `reach` of the patch: within `thickness + reach` of its
    /// centre's tangent plane.
    pub(super) fn may_reach(&self, p: Point3, reach: f64) -> bool {
        (p - self.centre).dot(self.normal).abs() <= self.thickness + reach
    }
}

impl Patch {
    /// The patch of `surface` over `cell`, from its samples; its box grown by `grow`.
    pub(super) fn new(face: u32, surface: &Surface, cell: Cell, grow: f64) -> Patch {
        let s = Samples::of(surface, cell);
        s.patch(face, cell, grow)
    }

    /// Whether a ray of unit direction `d` stays clear of the patch's tangent planes.
    pub(super) fn is_transversal(&self, d: Point3) -> bool {
        self.normal.dot(d).abs() > self.graze
    }

    /// The four quarters of the patch, sampled again.
    pub(super) fn split(&self, surface: &Surface, grow: f64) -> [Patch; 4] {
        self.cell
            .quarters()
            .map(|c| Patch::new(self.face, surface, c, grow))
    }
}

/// A box holding `surface` over `cell`, a part of a patch whose largest second derivatives
/// are `bend`: the box of `3 x 3` points grown by the error of linear interpolation between
/// them (times [`SAFETY`]) and by `grow`. Nine points, no derivatives: what marking grid
/// cells needs.
pub(super) fn part_box(
    surface: &Surface,
    cell: Cell,
    bend: [f64; 3],
    grow: f64,
) -> (Point3, Point3) {
    let [hu, hv] = cell.sides().map(|s| s / 2.0);
    let mut lo = Point3::new(f64::INFINITY, f64::INFINITY, f64::INFINITY);
    let mut hi = -lo;
    for i in 0..3 {
        for j in 0..3 {
            let p = surface.point([cell.u.0 + i as f64 * hu, cell.v.0 + j as f64 * hv]);
            lo = Point3::new(lo.x.min(p.x), lo.y.min(p.y), lo.z.min(p.z));
            hi = Point3::new(hi.x.max(p.x), hi.y.max(p.y), hi.z.max(p.z));
        }
    }
    let [suu, suv, svv] = bend;
    let margin = SAFETY * (hu * hu * suu + 2.0 * hu * hv * suv + hv * hv * svv) / 8.0;
    let g = if margin.is_finite() { margin } else { 0.0 } + grow;
    let g = Point3::new(g, g, g);
    (lo - g, hi + g)
}

/// The surface sampled on a cell: box, normal cone, speeds.
struct Samples {
    lo: Point3,
    hi: Point3,
    normal: Option<Point3>,
    cone: f64,
    margin: f64,
    speed: f64,
    bend: [f64; 3],
    centre: Point3,
    thickness: f64,
    /// `|S_u| du` and `|S_v| dv` at the centre: the cell's extent in space along each side.
    extent: [f64; 2],
}

impl Samples {
    fn of(surface: &Surface, cell: Cell) -> Samples {
        let [hu, hv] = cell.sides().map(|s| s / (SAMPLES - 1) as f64);
        let mut points = Vec::with_capacity(SAMPLES * SAMPLES);
        let mut normals = Vec::with_capacity(SAMPLES * SAMPLES);
        let (mut suu, mut suv, mut svv) = (0.0f64, 0.0f64, 0.0f64);
        let mut speed = f64::INFINITY;
        for i in 0..SAMPLES {
            for j in 0..SAMPLES {
                let uv = [cell.u.0 + i as f64 * hu, cell.v.0 + j as f64 * hv];
                let d = surface.derivatives(uv);
                points.push(d.point);
                suu = suu.max(d.duu.length());
                suv = suv.max(d.duv.length());
                svv = svv.max(d.dvv.length());
                speed = speed.min(d.du.length().min(d.dv.length()));
                // The closed form where S_u x S_v vanishes (a pole).
                let n = d.du.cross(d.dv).normalized();
                normals.push(n.or_else(|| surface.normal(uv)));
            }
        }
        let centre = cell.centre();
        let c = surface.derivatives(centre);
        let normal = surface.normal(centre);
        let cone = match normal {
            None => FRAC_PI_2,
            Some(n) => normals
                .iter()
                .map(|m| match m {
                    Some(m) => m.dot(n).clamp(-1.0, 1.0).acos(),
                    None => FRAC_PI_2,
                })
                .fold(0.0, f64::max),
        };
        // Between samples `h` apart the surface leaves the samples' box by at most
        // `(h_u^2 |S_uu| + 2 h_u h_v |S_uv| + h_v^2 |S_vv|) / 8` (the error of linear
        // interpolation), with the largest second derivatives sampled.
        let margin = SAFETY * (hu * hu * suu + 2.0 * hu * hv * suv + hv * hv * svv) / 8.0;
        let margin = if margin.is_finite() { margin } else { 0.0 };
        let (lo, hi) = Point3::bounds(points.iter().copied().filter(|p| p.is_finite()))
            .unwrap_or((c.point, c.point));
        let thickness = match normal {
            Some(n) => {
                points
                    .iter()
                    .map(|&q| (q - c.point).dot(n).abs())
                    .fold(0.0, f64::max)
                    + margin
            }
            None => f64::INFINITY,
        };
        let thickness = if thickness.is_finite() || normal.is_none() {
            thickness
        } else {
            f64::INFINITY
        };
        Samples {
            lo,
            hi,
            normal,
            cone,
            margin,
            speed: if speed.is_finite() { speed } else { 0.0 },
            bend: [suu, suv, svv],
            centre: c.point,
            thickness,
            extent: [
                c.du.length() * cell.sides()[0],
                c.dv.length() * cell.sides()[1],
            ],
        }
    }

    fn patch(&self, face: u32, cell: Cell, grow: f64) -> Patch {
        let g = self.margin + grow;
        let grow3 = Point3::new(g, g, g);
        let graze = match self.normal {
            Some(_) => {
                let a = SAFETY * self.cone + CLEARANCE;
                if a >= FRAC_PI_2 { 1.0 } else { a.sin() }
            }
            None => 1.0,
        };
        Patch {
            face,
            cell,
            lo: self.lo - grow3,
            hi: self.hi + grow3,
            normal: self.normal.unwrap_or(Point3::new(0.0, 0.0, 0.0)),
            graze,
            speed: self.speed,
            bend: self.bend,
            centre: self.centre,
            thickness: self.thickness,
        }
    }
}

/// The patches of one face's surface over `cells` (a face's `(u, v)` box cut at the surface's
/// knot lines), each cell halved across its longer side in space while its normals spread
/// wider than [`MAX_CONE`], at most [`MAX_BUILD_SPLITS`] times and to at most
/// [`MAX_PATCHES_PER_FACE`] patches.
pub(super) fn face_patches(face: u32, surface: &Surface, cells: &[Cell], grow: f64) -> Vec<Patch> {
    let mut out = Vec::new();
    let mut todo: Vec<(Cell, usize)> = cells.iter().rev().map(|&c| (c, 0)).collect();
    while let Some((cell, depth)) = todo.pop() {
        let s = Samples::of(surface, cell);
        let room = out.len() + todo.len() + 2 <= MAX_PATCHES_PER_FACE;
        if s.cone > MAX_CONE && depth < MAX_BUILD_SPLITS && room {
            let axis = usize::from(s.extent[1] > s.extent[0]);
            let [a, b] = cell.halves(axis);
            todo.push((b, depth + 1));
            todo.push((a, depth + 1));
        } else {
            out.push(s.patch(face, cell, grow));
        }
    }
    out
}

/// `box` (`lo`, `hi`) cut at the interior `lines` of each parameter.
pub(super) fn knot_cells(u: (f64, f64), v: (f64, f64), lines: &[Vec<f64>; 2]) -> Vec<Cell> {
    let cuts = |(a, b): (f64, f64), lines: &[f64]| {
        let mut c = vec![a];
        c.extend(lines.iter().copied().filter(|&t| t > a && t < b));
        c.push(b);
        c.dedup();
        c
    };
    let us = cuts(u, &lines[0]);
    let vs = cuts(v, &lines[1]);
    let mut cells = Vec::with_capacity((us.len() - 1) * (vs.len() - 1));
    for u in us.windows(2) {
        for v in vs.windows(2) {
            cells.push(Cell {
                u: (u[0], u[1]),
                v: (v[0], v[1]),
            });
        }
    }
    cells
}
