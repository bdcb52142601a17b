//! Surface entities as `rs_geom` surfaces, in IGES 5.3's parameters and placed by their 124
//! chains; for planes also the exact map of model space into their `(u, v)`, and for every
//! surface its own parameter range where IGES gives one (a face with `N1 = 0` or `OF = 0` is
//! bounded by it).
//!
//! With `rho(u) = cos u X + sin u Y`, `Y = A x X` (unit axis `A`, unit reference direction `X`
//! made orthogonal to it) and `deg = pi / 180`:
//!
//! | entity | parameters | `S(u, v)` | `rs_geom` surface |
//! | --- | --- | --- | --- |
//! | 108 plane | `A, B, C, D` | `O + u e1 + v e2` (this reader's axes, below) | [`Plane`] |
//! | 120 surface of revolution | axis line `L`, generatrix `C`, `SA`, `TA` | `C(u)` turned by the angle `v` about `L` (right-handed, from `L`'s start to its end) | [`Revolution`] with `u`, `v` swapped |
//! | 122 tabulated cylinder | directrix `C` on `[t0, t1]`, point `L` | `C(t0 + u (t1 - t0)) + v (L - C(t0))` | [`Extrusion`], `u` scaled |
//! | 128 rational B-spline surface | knots, weights, control points, `U0..V1` | the tensor-product B-spline | [`BSplineSurface`] |
//! | 140 offset surface | `D`, base surface | `B(u, v) + D N(u, v)` | [`Offset`] |
//! | 190 plane | `P, N, X` | `P + u X + v Y` | [`Plane`] |
//! | 192 cylinder | `P, A, R, X` | `P + R rho(u deg) + v A` | [`Cylinder`], `u` in degrees |
//! | 194 cone | `P, A, R, a (degrees), X` | `P + (R + v sin a) rho(u deg) + v cos a A` (`v` along the slant) | [`Cone`], `u` in degrees, `v` scaled by `cos a` |
//! | 196 sphere | `C, R, A, X` | `C + R cos(v deg) rho(u deg) + R sin(v deg) A` | [`Sphere`] in degrees |
//! | 198 torus | `C, A, R, r, X` | `C + (R + r cos(v deg)) rho(u deg) + r sin(v deg) A` | [`Torus`] in degrees |
//!
//! These are the parameterisations Open CASCADE 8.0 writes pcurves in and reads them back with
//! (its `(u, v)` are the same with angles in radians; for 120 see the module `iges`). Form 0 of
//! 190 to 198 gives no reference direction: Open CASCADE's default of `gp_Ax2(P, A)` is taken
//! ([`Frame::with_default_reference`]); a form 0 sphere has no axis either and gets the world's.
//! The points (116) and directions (123) these refer to are placed by their own 124 chains.
//!
//! A 108 is not parameterised by IGES; this reader takes its origin at the plane's point
//! nearest the world origin, `e1` along the world axis least aligned with the normal, projected
//! onto the plane, and `e2 = n x e1`.

use std::f64::consts::PI;

use rs_geom::surface::{
    BSplineSurface, Cone, Cylinder, Extrusion, Offset, Plane, Reparam, Revolution, Sphere, Surface,
    Torus,
};
use rs_geom::{AffinePlaneCoordinates, Frame, GeomError};
use rs_spline::{KnotVector, Point, Point3};

use super::curves::{Leaf, Placed, point3};
use super::directory::DirEntry;
use super::error::IgesError;
use super::{Iges, MAX_DEPTH};

/// Radians per degree: the angles of 192 to 198 (their pcurves' and the cone's semi-angle).
const RADIANS_PER_DEGREE: f64 = PI / 180.0;

/// What the reader knows of a surface entity.
#[derive(Clone, Debug)]
pub(super) struct SurfaceInfo {
    /// The surface, placed in model space, in the entity's parameters.
    pub(super) surface: Result<Surface, IgesError>,
    /// For a plane (108, 190, a 128 that is a flat parallelogram): model space to its `(u,
    /// v)`, exactly.
    pub(super) plane: Option<AffinePlaneCoordinates>,
    /// The entity's own parameter range `[u0, u1] x [v0, v1]`.
    pub(super) bounds: Result<[f64; 4], IgesError>,
}

/// A plane's origin, its two axes (one unit of `u`, of `v`) and the origin's parameters.
type Axes = (Point3, Point3, Point3, Point);

/// A surface read in its definition space (before its own 124 chain): the surface, a plane's
/// axes, the parameter range.
struct Read {
    surface: Surface,
    axes: Option<Axes>,
    bounds: Result<[f64; 4], IgesError>,
}

/// `base` with its parameters scaled: `(u, v) -> base(scale[0] u, scale[1] v)`.
fn scaled(who: &str, base: Surface, scale: [f64; 2]) -> Result<Surface, IgesError> {
    Reparam::new(base, false, scale, [0.0, 0.0])
        .map(Surface::Reparam)
        .map_err(|e| IgesError::geometry(who, e))
}

impl Iges<'_> {
    /// The surface entity `s`, read once.
    pub(super) fn surface_info(&self, s: &DirEntry) -> std::rc::Rc<SurfaceInfo> {
        if let Some(info) = self.surfaces.borrow().get(&s.de) {
            return info.clone();
        }
        let info = std::rc::Rc::new(match self.placed_surface(s, 0) {
            Ok((surface, plane, bounds)) => SurfaceInfo {
                surface: Ok(surface),
                plane,
                bounds,
            },
            Err(e) => SurfaceInfo {
                surface: Err(e.clone()),
                plane: None,
                bounds: Err(e),
            },
        });
        self.surfaces.borrow_mut().insert(s.de, info.clone());
        info
    }

    /// Surface `s` placed by its 124 chain, a plane's coordinates and the parameter range;
    /// `depth` counts the offsets it is the base of.
    #[allow(clippy::type_complexity)]
    fn placed_surface(
        &self,
        s: &DirEntry,
        depth: usize,
    ) -> Result<
        (
            Surface,
            Option<AffinePlaneCoordinates>,
            Result<[f64; 4], IgesError>,
        ),
        IgesError,
    > {
        let who = self.who(s);
        if depth > MAX_DEPTH {
            return Err(IgesError::TooDeep {
                who,
                what: "offset surfaces",
            });
        }
        let [t, _] = self.transforms(s)?;
        let r = self.surface_in_definition_space(s, depth)?;
        // The plane's origin and axes mapped (an affine map keeps the parameters of a plane's
        // points), also by the identity: the arithmetic the reader has always done.
        let plane = match r.axes {
            Some((o, e1, e2, uv0)) => Some(
                AffinePlaneCoordinates::new(
                    t.apply(o),
                    t.apply_vector(e1),
                    t.apply_vector(e2),
                    uv0,
                )
                .map_err(|e| IgesError::geometry(&who, e))?,
            ),
            None => None,
        };
        let surface = if t.is_identity() {
            r.surface
        } else {
            r.surface
                .transformed(&t)
                .map_err(|e| IgesError::geometry(&who, e))?
        };
        Ok((surface, plane, r.bounds))
    }

    /// A surface entity in its definition space.
    fn surface_in_definition_space(&self, s: &DirEntry, depth: usize) -> Result<Read, IgesError> {
        let who = self.who(s);
        let unbounded = |flag: &'static str| IgesError::NoNaturalBounds {
            who: who.clone(),
            flag,
            kind: s.kind,
        };
        let geom = |e: GeomError| IgesError::geometry(&who, e);
        let origin_uv = Point::new(0.0, 0.0);
        match s.kind {
            108 => {
                let (origin, e1, e2) = self.plane_108(s)?;
                let frame = Frame::new(origin, Some(e1.cross(e2)), Some(e1)).map_err(geom)?;
                Ok(Read {
                    surface: Surface::Plane(Plane::new(frame)),
                    axes: Some((origin, e1, e2, origin_uv)),
                    bounds: Err(unbounded("")),
                })
            }
            190 => {
                let f = self.frame_190(s)?;
                Ok(Read {
                    surface: Surface::Plane(Plane::new(f)),
                    axes: Some((f.origin, f.x, f.y, origin_uv)),
                    bounds: Err(unbounded("")),
                })
            }
            128 => {
                let (surface, axes, bounds) = self.bspline_128(s)?;
                Ok(Read {
                    surface,
                    axes,
                    bounds,
                })
            }
            120 => self.revolution_120(s),
            122 => self.tabulated_122(s),
            140 => {
                let mut p = self.params(s)?;
                for name in ["NX", "NY", "NZ"] {
                    p.skip(name)?;
                }
                let d = p.real("D")?;
                let base = p.pointer("DE")?;
                let base = self.entry(base, &format!("{who}: base surface"))?;
                let (base, _, bounds) = self.placed_surface(base, depth + 1)?;
                Ok(Read {
                    surface: Surface::Offset(Offset::new(base, d).map_err(geom)?),
                    axes: None,
                    bounds,
                })
            }
            192..=198 => self.elementary(s),
            _ => Err(IgesError::UnknownSurface { who }),
        }
    }

    /// A 108's origin and axes (see the module documentation).
    fn plane_108(&self, s: &DirEntry) -> Result<(Point3, Point3, Point3), IgesError> {
        let mut p = self.params(s)?;
        let n = point3(&mut p, ["A", "B", "C"])?;
        let d = p.real("D")?;
        let nn = n.dot(n);
        if !(nn > 0.0 && nn.is_finite()) {
            return Err(IgesError::ZeroNormal { who: self.who(s) });
        }
        let unit = n / nn.sqrt();
        let origin = n * d / nn;
        // The world axis least aligned with the normal, projected onto the plane.
        let components = [unit.x, unit.y, unit.z];
        let axis = (0..3)
            .min_by(|&i, &j| components[i].abs().total_cmp(&components[j].abs()))
            .unwrap_or(0);
        let w = [Point3::X, Point3::Y, Point3::Z][axis];
        let proj = w - unit * components[axis];
        let e1 = proj / proj.dot(proj).sqrt();
        Ok((origin, e1, unit.cross(e1)))
    }

    /// A point entity (116) placed by its own 124 chain.
    fn point_116(&self, ptr: usize, from: &str) -> Result<Point3, IgesError> {
        let e = self.entry_of(ptr, from, 116, "a 116 point")?;
        let mut p = self.params(e)?;
        let x = point3(&mut p, ["X", "Y", "Z"])?;
        Ok(self.transforms(e)?[0].apply(x))
    }

    /// A direction entity (123) turned by its own 124 chain.
    fn direction_123(&self, ptr: usize, from: &str) -> Result<Point3, IgesError> {
        let e = self.entry_of(ptr, from, 123, "a 123 direction")?;
        let mut p = self.params(e)?;
        let x = point3(&mut p, ["X", "Y", "Z"])?;
        Ok(self.transforms(e)?[0].apply_vector(x))
    }

    /// The frame of a 190 plane: origin `P`, axis `N`, reference direction `X` (form 1) or
    /// Open CASCADE's default (form 0).
    fn frame_190(&self, s: &DirEntry) -> Result<Frame, IgesError> {
        let who = self.who(s);
        let mut p = self.params(s)?;
        let origin = p.pointer("P")?;
        let normal = p.pointer("N")?;
        let reference = if s.form == 1 {
            Some(p.pointer("X")?)
        } else {
            None
        };
        let origin = self.point_116(origin, &format!("{who}: location"))?;
        let normal = self.direction_123(normal, &format!("{who}: normal"))?;
        self.frame(&who, origin, normal, reference)
    }

    /// The frame at `origin` about `axis` with the reference direction entity `reference`, or
    /// Open CASCADE's default without one.
    fn frame(
        &self,
        who: &str,
        origin: Point3,
        axis: Point3,
        reference: Option<usize>,
    ) -> Result<Frame, IgesError> {
        let frame = match reference {
            Some(r) => {
                let x = self.direction_123(r, &format!("{who}: reference direction"))?;
                Frame::new(origin, Some(axis), Some(x))
            }
            None => Frame::with_default_reference(origin, axis),
        };
        frame.map_err(|e| IgesError::geometry(who, e))
    }

    /// The frame at the 116 point `origin` with the 123 direction `axis` as its `z` (and the
    /// 123 `reference` as its `x`, else `OpenCASCADE`'s default).
    fn frame_of(
        &self,
        who: &str,
        origin: usize,
        axis: usize,
        reference: Option<usize>,
    ) -> Result<Frame, IgesError> {
        let origin = self.point_116(origin, who)?;
        let axis = self.direction_123(axis, who)?;
        self.frame(who, origin, axis, reference)
    }

    /// 192 cylinder, 194 cone, 196 sphere, 198 torus (see the module documentation).
    fn elementary(&self, s: &DirEntry) -> Result<Read, IgesError> {
        let who = self.who(s);
        let geom = |e: GeomError| IgesError::geometry(&who, e);
        let mut p = self.params(s)?;
        let form1 = s.form == 1;
        let deg = RADIANS_PER_DEGREE;
        let (surface, bounds) = match s.kind {
            192 => {
                let (origin, axis, r) = (p.pointer("P")?, p.pointer("A")?, p.real("R")?);
                let x = if form1 { Some(p.pointer("X")?) } else { None };
                let f = self.frame_of(&who, origin, axis, x)?;
                let c = Cylinder::new(f, r).map_err(geom)?;
                (scaled(&who, Surface::Cylinder(c), [deg, 1.0])?, None)
            }
            194 => {
                let (origin, axis) = (p.pointer("P")?, p.pointer("A")?);
                let (r, angle) = (p.real("R")?, p.real("SANG")?);
                let x = if form1 { Some(p.pointer("X")?) } else { None };
                let f = self.frame_of(&who, origin, axis, x)?;
                let a = angle * deg;
                let c = Cone::new(f, r, a).map_err(geom)?;
                (scaled(&who, Surface::Cone(c), [deg, a.cos()])?, None)
            }
            196 => {
                let (centre, r) = (p.pointer("C")?, p.real("R")?);
                let centre = self.point_116(centre, &who)?;
                let f = if form1 {
                    let axis = p.pointer("A")?;
                    let x = p.pointer("X")?;
                    self.frame(&who, centre, self.direction_123(axis, &who)?, Some(x))?
                } else {
                    self.frame(&who, centre, Point3::Z, None)?
                };
                let sphere = Sphere::new(f, r).map_err(geom)?;
                (
                    scaled(&who, Surface::Sphere(sphere), [deg, deg])?,
                    Some([0.0, 360.0, -90.0, 90.0]),
                )
            }
            _ => {
                let (centre, axis) = (p.pointer("C")?, p.pointer("A")?);
                let (major, minor) = (p.real("R1")?, p.real("R2")?);
                let x = if form1 { Some(p.pointer("X")?) } else { None };
                let f = self.frame_of(&who, centre, axis, x)?;
                let torus = Torus::new(f, major, minor).map_err(geom)?;
                (
                    scaled(&who, Surface::Torus(torus), [deg, deg])?,
                    Some([0.0, 360.0, 0.0, 360.0]),
                )
            }
        };
        Ok(Read {
            surface,
            axes: None,
            bounds: bounds.ok_or(IgesError::NoNaturalBounds {
                who: who.clone(),
                flag: "",
                kind: s.kind,
            }),
        })
    }

    /// The one leaf of the curve at `ptr` (a composite of several pieces is refused).
    fn single_leaf(&self, ptr: usize, who: &str, what: &'static str) -> Result<Placed, IgesError> {
        let mut leaves = self.curve_leaves(ptr, &format!("{who}: {what}"))?;
        if leaves.len() != 1 {
            return Err(IgesError::CompositeSweep {
                who: who.to_string(),
                what,
            });
        }
        Ok(leaves.remove(0))
    }

    /// 120 surface of revolution: `L, C, SA, TA`.
    fn revolution_120(&self, s: &DirEntry) -> Result<Read, IgesError> {
        let who = self.who(s);
        let geom = |e: GeomError| IgesError::geometry(&who, e);
        let mut p = self.params(s)?;
        let (axis, generatrix) = (p.pointer("L")?, p.pointer("C")?);
        let (sa, ta) = (p.real("SA")?, p.real("TA")?);
        let line = self.entry_of(axis, &format!("{who}: axis"), 110, "a 110 line")?;
        let axis = self.single_leaf(line.de, &who, "axis")?;
        let axis_curve = axis.model_curve()?;
        let (a, b) = (axis_curve.point(0.0), axis_curve.point(1.0));
        let c = self.single_leaf(generatrix, &who, "generatrix")?;
        let curve = Leaf::trimmed(c.model_curve()?, c.leaf.range);
        let rev = Revolution::new(curve, a, b - a).map_err(geom)?;
        let surface =
            Reparam::new(Surface::Revolution(rev), true, [1.0, 1.0], [0.0, 0.0]).map_err(geom)?;
        let (t0, t1) = c.leaf.range;
        let bounds = if sa < ta {
            Ok([t0, t1, sa, ta])
        } else {
            Err(IgesError::EmptyRange {
                who: who.clone(),
                u0: t0,
                u1: t1,
                v0: sa,
                v1: ta,
            })
        };
        Ok(Read {
            surface: Surface::Reparam(surface),
            axes: None,
            bounds,
        })
    }

    /// 122 tabulated cylinder: `DE, LX, LY, LZ`.
    fn tabulated_122(&self, s: &DirEntry) -> Result<Read, IgesError> {
        let who = self.who(s);
        let geom = |e: GeomError| IgesError::geometry(&who, e);
        let mut p = self.params(s)?;
        let directrix = p.pointer("DE")?;
        let end = point3(&mut p, ["LX", "LY", "LZ"])?;
        let c = self.single_leaf(directrix, &who, "directrix")?;
        let (t0, t1) = c.leaf.range;
        let placed = c.model_curve()?;
        let start = placed.point(t0);
        let ext = Extrusion::new(Leaf::trimmed(placed, (t0, t1)), end - start).map_err(geom)?;
        let surface = Reparam::new(Surface::Extrusion(ext), false, [t1 - t0, 1.0], [t0, 0.0])
            .map_err(geom)?;
        Ok(Read {
            surface: Surface::Reparam(surface),
            axes: None,
            bounds: Ok([0.0, 1.0, 0.0, 1.0]),
        })
    }

    /// 128 rational B-spline surface: the surface, its origin and axes if it is a flat
    /// parallelogram (degree 1 x 1, four control points with `P11 - P10 = P01 - P00`, equal
    /// weights: then `S(u, v) = P00 + (u - s0) e1 + (v - t0) e2`), and `[U0, U1] x [V0, V1]`.
    #[allow(clippy::type_complexity)]
    fn bspline_128(
        &self,
        s: &DirEntry,
    ) -> Result<(Surface, Option<Axes>, Result<[f64; 4], IgesError>), IgesError> {
        let who = self.who(s);
        let mut p = self.params(s)?;
        let (k1, k2) = (p.count("K1")?, p.count("K2")?);
        let (m1, m2) = (p.count("M1")?, p.count("M2")?);
        for name in ["PROP1", "PROP2"] {
            p.skip(name)?;
        }
        let polynomial = p.int("PROP3")? == 1;
        for name in ["PROP4", "PROP5"] {
            p.skip(name)?;
        }
        let (nu, nv) = (k1.saturating_add(1), k2.saturating_add(1));
        // Knots, then 4 numbers (weight, x, y, z) per control point, then U0..V1.
        let fields = (k1.checked_add(m1))
            .and_then(|a| a.checked_add(k2)?.checked_add(m2)?.checked_add(4))
            .and_then(|a| a.checked_add(nu.checked_mul(nv)?.checked_mul(4)?))
            .unwrap_or(usize::MAX);
        p.check_count("K1, K2", fields, 1)?;
        let mut read = |n: usize, name: &'static str| -> Result<Vec<f64>, IgesError> {
            (0..n).map(|_| p.real(name)).collect()
        };
        let s_knots = read(k1 + m1 + 2, "knot")?;
        let t_knots = read(k2 + m2 + 2, "knot")?;
        let w = read(nu * nv, "weight")?;
        let mut file_points = Vec::with_capacity(nu * nv);
        for _ in 0..nu * nv {
            file_points.push(point3(&mut p, ["X", "Y", "Z"])?);
        }
        let range = [p.real("U0")?, p.real("U1")?, p.real("V0")?, p.real("V1")?];
        let bounds = if range[0] < range[1] && range[2] < range[3] {
            Ok(range)
        } else {
            Err(IgesError::EmptyRange {
                who: who.clone(),
                u0: range[0],
                u1: range[1],
                v0: range[2],
                v1: range[3],
            })
        };
        // The flat parallelogram.
        let flat = if [k1, k2, m1, m2] == [1, 1, 1, 1] && w.iter().all(|&x| x == w[0]) && w[0] > 0.0
        {
            let [p00, p10, p01, p11] = [
                file_points[0],
                file_points[1],
                file_points[2],
                file_points[3],
            ];
            let (s0, s1, t0, t1) = (s_knots[1], s_knots[2], t_knots[1], t_knots[2]);
            let skew = (p11 - p10) - (p01 - p00);
            let size = file_points.iter().fold(1.0f64, |m, q| m.max(q.max_abs()));
            (s0 < s1 && t0 < t1 && skew.length() <= self.tolerance.coincidence(size)).then(|| {
                (
                    p00,
                    (p10 - p00) / (s1 - s0),
                    (p01 - p00) / (t1 - t0),
                    Point::new(s0, t0),
                )
            })
        } else {
            None
        };
        // IGES lists control points with the first index (along u) running fastest; the
        // surface wants them row by row along u, [i][j] at i nv + j.
        let mut points = Vec::with_capacity(nu * nv);
        let mut weights = Vec::with_capacity(nu * nv);
        for i in 0..nu {
            for j in 0..nv {
                points.push(file_points[j * nu + i]);
                weights.push(w[j * nu + i]);
            }
        }
        let weights = if polynomial && weights.iter().all(|&x| x == weights[0]) {
            None
        } else {
            Some(weights)
        };
        let spline = |e| IgesError::spline(&who, e);
        let knots = [
            KnotVector::new(s_knots, m1, nu).map_err(spline)?,
            KnotVector::new(t_knots, m2, nv).map_err(spline)?,
        ];
        let surface = BSplineSurface::new(knots, points, weights)
            .map_err(|e| IgesError::geometry(&who, e))?;
        Ok((Surface::BSpline(surface), flat, bounds))
    }
}
