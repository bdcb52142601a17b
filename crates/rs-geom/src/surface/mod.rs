//! Surfaces of B-rep faces as objects: every surface type of STEP and IGES parts, each with its
//! point, first and second derivatives (analytic), unit normal, natural parameter box, periods,
//! poles and closest-point inversion, behind one trait, [`ParamSurface`], and one enum,
//! [`Surface`].
//!
//! # Parameterisations
//!
//! Parameters are those of ISO 10303-42 (STEP); IGES 5.3 surfaces are these surfaces, wrapped
//! in a [`Reparam`] where IGES orders or scales the parameters differently. `OpenCASCADE`'s own
//! parameterisation is given where it differs: to compare with `OpenCASCADE` go through the 3-D
//! point (evaluate here, invert on `OpenCASCADE`'s surface). With the placement's frame
//! `(o; x, y, z)` ([`Frame`]), `rho(u) = cos u x + sin u y`:
//!
//! | surface | point at `(u, v)` | `u`, `v` | `OpenCASCADE` |
//! | --- | --- | --- | --- |
//! | [`Plane`] | `o + u x + v y` | lengths | same |
//! | [`Cylinder`] | `o + r rho(u) + v z` | angle, length along `z` | same |
//! | [`Cone`] | `o + (r + v tan a) rho(u) + v z` | angle, height along `z` | `v` along the slant: `v_occ = v / cos a` |
//! | [`Sphere`] | `o + r cos v rho(u) + r sin v z` | longitude, latitude | same |
//! | [`Torus`] | `o + (R + r cos v) rho(u) + r sin v z` | two angles | same |
//! | [`Revolution`] | the swept curve at `v` turned by `u` about the axis | angle, curve parameter | same for STEP; IGES 120 is `(curve parameter, angle)`: `OpenCASCADE` swaps them, measures the angle from the entity's start angle and reparameterises a line generatrix by length |
//! | [`Extrusion`] | the swept curve at `u` plus `v` times the extrusion vector (with its magnitude) | curve parameter, multiple of the vector | `v` a length along the unit direction: `v_occ = v \|D\|`; IGES 122 normalises the directrix parameter to `[0, 1]` |
//! | [`Offset`] | the base surface plus `d` times its unit normal `S_u x S_v / \|S_u x S_v\|` | the base's | same |
//! | [`BSplineSurface`] | tensor-product rational B-spline, control points `[i][j]` at `i nv + j` | knot parameters | same |
//! | [`Reparam`] | a base surface at `(a p + b, c q + d)`, `(p, q) = (u, v)` or `(v, u)` | IGES 120 (swapped), IGES 122 (normalised), STEP files in degrees | — |
//!
//! Angles are in radians everywhere (a file in degrees is read through a [`Reparam`] with scale
//! `pi / 180` in its angle parameters).
//!
//! # What is exact and what is iterative
//!
//! Points, derivatives and normals are closed forms (an [`Offset`]'s second derivatives are
//! central differences of its analytic first derivatives: they need the base's third
//! derivatives). [`ParamSurface::invert`] is:
//!
//! - a closed form on planes, cylinders, cones, spheres and tori (to rounding);
//! - on surfaces of revolution and extrusion, a closed form for the angle (the extrusion
//!   parameter) and a 1-D search for the swept curve's parameter: the squared distance in the
//!   meridian half-plane (across the extrusion vector) sampled at the curve's knots and 16
//!   values per knot span (at most 128 samples; an unbounded curve in a window doubled from
//!   `[-1, 1]` at most 60 times until the distance must grow past it), then in the intervals
//!   beside the best 6 local minima a bracketed Newton iteration on the derivative (at most 100
//!   steps, bisection where a step would leave the bracket), to rounding;
//! - on B-spline and offset surfaces, Newton's method on the gradient of the squared distance
//!   with the analytic derivatives (the full Hessian `S_i . S_j + r . S_ij`), damped as
//!   Levenberg and Marquardt do, bounded parameters held in the box: at most 64 steps of at
//!   most 17 dampings each, from `near`, and, unless that start lands on the surface, from the
//!   best 6 local minima of a grid (a B-spline's knots and 3 values per knot span, at most 64 a
//!   side; an offset's from its base's closest point and its base's grid). It converges to
//!   rounding from a start in the basin of the closest point; the grid makes that start likely,
//!   not certain, on wildly curved surfaces.
//!
//! Of results at the same distance (within `1e-12` of the surface's size) the one nearest
//! `near` is kept.
//!
//! # Examples
//!
//! ```
//! use rs_geom::surface::{ParamSurface, Sphere, Surface};
//! use rs_geom::{Frame, Point3};
//! let s = Surface::Sphere(Sphere::new(Frame::WORLD, 2.0).unwrap());
//! let p = s.point([0.5, 0.25]);
//! assert!((p.length() - 2.0).abs() < 1e-15);
//! // The closest point of (0, 0, 5) is the north pole: v = pi / 2, at distance 3.
//! let foot = s.invert(Point3::new(0.0, 0.0, 5.0), None);
//! assert!((foot.uv[1] - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
//! assert!((foot.distance - 3.0).abs() < 1e-15);
//! ```

mod bspline;
mod cone;
mod cylinder;
mod extrusion;
mod invert;
mod offset;
mod plane;
mod reparam;
mod revolution;
mod sphere;
mod swept;
#[cfg(test)]
pub(crate) mod testing;
mod torus;
mod transform;

pub use bspline::BSplineSurface;
pub use cone::Cone;
pub use cylinder::Cylinder;
pub use extrusion::Extrusion;
pub use offset::{MAX_NESTED_OFFSETS, Offset};
pub use plane::Plane;
pub use reparam::Reparam;
pub use revolution::Revolution;
pub use sphere::Sphere;
pub use torus::Torus;

use std::f64::consts::TAU;

use rs_spline::Point3;

use crate::{Affine3, Frame, GeomError};

/// How a surface depends on one parameter where it is a polynomial in it
/// ([`Surface::polynomial_degrees`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PolynomialDegree {
    /// The degree of the point `S` in the parameter.
    pub point: usize,
    /// The degree of the area vector `S_u x S_v` in it, which is also that of its length (the
    /// area element): the vector is a polynomial of this degree times a vector that does not
    /// depend on the parameter.
    pub area: usize,
}

/// A point of a surface with its first and second partial derivatives.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceDerivatives {
    /// `S(u, v)`.
    pub point: Point3,
    /// `S_u`.
    pub du: Point3,
    /// `S_v`.
    pub dv: Point3,
    /// `S_uu`.
    pub duu: Point3,
    /// `S_uv`.
    pub duv: Point3,
    /// `S_vv`.
    pub dvv: Point3,
}

/// A box of parameters `[u.0, u.1] x [v.0, v.1]`; infinite ends where a parameter is
/// unbounded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamBox {
    /// The range of `u`.
    pub u: (f64, f64),
    /// The range of `v`.
    pub v: (f64, f64),
}

impl ParamBox {
    /// The whole parameter plane.
    pub const UNBOUNDED: ParamBox = ParamBox {
        u: (f64::NEG_INFINITY, f64::INFINITY),
        v: (f64::NEG_INFINITY, f64::INFINITY),
    };

    /// The range of parameter `i` (`0`: `u`, otherwise `v`).
    pub fn range(&self, i: usize) -> (f64, f64) {
        if i == 0 { self.u } else { self.v }
    }

    /// Is `uv` in the box (ends included)?
    pub fn contains(&self, uv: [f64; 2]) -> bool {
        (0..2).all(|i| {
            let (a, b) = self.range(i);
            uv[i] >= a && uv[i] <= b
        })
    }

    /// The point of the box nearest `uv` (each parameter clamped to its range).
    pub fn clamp(&self, uv: [f64; 2]) -> [f64; 2] {
        std::array::from_fn(|i| {
            let (a, b) = self.range(i);
            uv[i].clamp(a, b)
        })
    }

    /// The length of each range (infinite where unbounded).
    pub fn lengths(&self) -> [f64; 2] {
        [self.u.1 - self.u.0, self.v.1 - self.v.0]
    }
}

/// A parameter line that is one point in space (a sphere's poles, a cone's apex).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pole {
    /// `0`: the line `u = value` is one point; `1`: the line `v = value` is.
    pub param: usize,
    /// The parameter's value on the line.
    pub value: f64,
}

/// The closest point of a surface to a point: its parameters and distance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inversion {
    /// The parameters of the closest point found.
    pub uv: [f64; 2],
    /// Its distance to the point inverted (`NaN` for a point with a non-finite coordinate).
    pub distance: f64,
}

/// A parametric surface `S(u, v)`: the questions every face of a B-rep model asks of its
/// surface.
pub trait ParamSurface {
    /// The point at `uv`. A periodic parameter may take any value; a bounded non-periodic one
    /// of a B-spline surface or of a bounded swept curve is clamped into its range.
    fn point(&self, uv: [f64; 2]) -> Point3;

    /// The point with its first and second partial derivatives at `uv` (closed forms; see the
    /// module documentation for an offset's second derivatives).
    fn derivatives(&self, uv: [f64; 2]) -> SurfaceDerivatives;

    /// The point and its first partial derivatives `[S, S_u, S_v]` at `uv`: those of
    /// [`ParamSurface::derivatives`], for callers that need no second ones (integrals of the
    /// area element), cheaper where a surface can skip them (B-spline surfaces).
    fn first_derivatives(&self, uv: [f64; 2]) -> [Point3; 3] {
        let d = self.derivatives(uv);
        [d.point, d.du, d.dv]
    }

    /// The unit normal along `S_u x S_v`: a closed form where the surface has one (a sphere's
    /// at its poles, a B-spline surface's or surface of revolution's at a pole as the limit
    /// from inside the parameter box); `None` where it is truly undefined (a cone's apex, a
    /// fold, `S_u` parallel to `S_v`).
    fn normal(&self, uv: [f64; 2]) -> Option<Point3>;

    /// The natural parameter box (a period for periodic parameters, infinite where a parameter
    /// is unbounded).
    fn param_box(&self) -> ParamBox;

    /// The periods of `u` and `v` where the surface is closed in them.
    fn periods(&self) -> [Option<f64>; 2];

    /// The parameter lines that are one point in space.
    fn poles(&self) -> Vec<Pole>;

    /// The point of the surface (within its parameter box, periodic parameters free) nearest
    /// `x`, with its distance. Of periodic copies of the answer, the one nearest `near` (by
    /// default, the copy in the parameter box); where the parameters of the closest point are
    /// not unique (a point on a cylinder's axis, at a pole), `near`'s are kept where they may
    /// be. Bounded work whatever `x`: a non-finite point gives a `NaN` distance.
    fn invert(&self, x: Point3, near: Option<[f64; 2]>) -> Inversion;
}

/// A surface of any of the types of CAD parts (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub enum Surface {
    /// A plane.
    Plane(Plane),
    /// A circular cylinder.
    Cylinder(Cylinder),
    /// A circular cone.
    Cone(Cone),
    /// A sphere.
    Sphere(Sphere),
    /// A torus.
    Torus(Torus),
    /// A surface of revolution.
    Revolution(Revolution),
    /// A surface of linear extrusion.
    Extrusion(Extrusion),
    /// An offset surface.
    Offset(Offset),
    /// A rational B-spline surface.
    BSpline(BSplineSurface),
    /// Another surface with its parameters swapped, scaled and shifted.
    Reparam(Reparam),
}

/// Calls `$e` with `$s` bound to the surface inside any variant.
macro_rules! dispatch {
    ($self:expr, $s:ident => $e:expr) => {
        match $self {
            Surface::Plane($s) => $e,
            Surface::Cylinder($s) => $e,
            Surface::Cone($s) => $e,
            Surface::Sphere($s) => $e,
            Surface::Torus($s) => $e,
            Surface::Revolution($s) => $e,
            Surface::Extrusion($s) => $e,
            Surface::Offset($s) => $e,
            Surface::BSpline($s) => $e,
            Surface::Reparam($s) => $e,
        }
    };
}

impl ParamSurface for Surface {
    fn point(&self, uv: [f64; 2]) -> Point3 {
        dispatch!(self, s => s.point(uv))
    }

    fn derivatives(&self, uv: [f64; 2]) -> SurfaceDerivatives {
        dispatch!(self, s => s.derivatives(uv))
    }

    fn first_derivatives(&self, uv: [f64; 2]) -> [Point3; 3] {
        dispatch!(self, s => s.first_derivatives(uv))
    }

    fn normal(&self, uv: [f64; 2]) -> Option<Point3> {
        dispatch!(self, s => s.normal(uv))
    }

    fn param_box(&self) -> ParamBox {
        dispatch!(self, s => s.param_box())
    }

    fn periods(&self) -> [Option<f64>; 2] {
        dispatch!(self, s => s.periods())
    }

    fn poles(&self) -> Vec<Pole> {
        dispatch!(self, s => s.poles())
    }

    fn invert(&self, x: Point3, near: Option<[f64; 2]>) -> Inversion {
        dispatch!(self, s => s.invert(x, near))
    }
}

/// The deepest nesting of offsets and reparameterisations accepted (evaluation recurses
/// through them; files nest one or two).
pub const MAX_NESTING: usize = 16;

impl Surface {
    /// The kind of surface in words (`"cylinder"`, `"B-spline surface"`, ...), for messages.
    pub fn kind_name(&self) -> &'static str {
        match self {
            Surface::Plane(_) => "plane",
            Surface::Cylinder(_) => "cylinder",
            Surface::Cone(_) => "cone",
            Surface::Sphere(_) => "sphere",
            Surface::Torus(_) => "torus",
            Surface::Revolution(_) => "surface of revolution",
            Surface::Extrusion(_) => "surface of linear extrusion",
            Surface::Offset(_) => "offset surface",
            Surface::BSpline(_) => "B-spline surface",
            Surface::Reparam(_) => "reparameterised surface",
        }
    }

    /// In each parameter, how the surface depends on it where its point and its area element
    /// are polynomials in it with the other parameter fixed (`None` where they are not): a
    /// plane in both, a cylinder, cone or extrusion along its straight lines (`v`), carried
    /// through a reparameterisation. A sphere, torus, revolution, offset or B-spline surface
    /// reports `None` (an angle, or an area element `|S_u x S_v|` that is a square root).
    /// Integrands built from the point and the area vector are then polynomials of known
    /// degree in that parameter, integrated exactly by a fixed Gauss rule. Where the area
    /// vector's polynomial factor changes sign (a cone's apex) its length is only piecewise a
    /// polynomial: that parameter value must be one of [`Surface::knot_lines`].
    pub fn polynomial_degrees(&self) -> [Option<PolynomialDegree>; 2] {
        const LINE: PolynomialDegree = PolynomialDegree { point: 1, area: 0 };
        match self {
            Surface::Plane(_) => [Some(LINE), Some(LINE)],
            // S = o + r rho(u) + v z: S_u x S_v = r rho'(u) x z, free of v.
            Surface::Cylinder(_) => [None, Some(LINE)],
            // S = o + (r + v tan a) rho(u) + v z: S_u x S_v = (r + v tan a) (rho'(u) x (tan a
            // rho(u) + z)), whose length is linear in v on each side of the apex (a knot
            // line).
            Surface::Cone(_) => [None, Some(PolynomialDegree { point: 1, area: 1 })],
            // S = C(u) + v D: S_u x S_v = C'(u) x D, free of v.
            Surface::Extrusion(_) => [None, Some(LINE)],
            Surface::Reparam(r) => {
                // An affine map of each parameter keeps the degrees; a swap exchanges them.
                let mut base = r.base().polynomial_degrees();
                if r.swap() {
                    base.swap(0, 1);
                }
                base
            }
            Surface::Sphere(_)
            | Surface::Torus(_)
            | Surface::Revolution(_)
            | Surface::Offset(_)
            | Surface::BSpline(_) => [None, None],
        }
    }

    /// The parameter lines where the surface is only piecewise smooth, `[u values, v values]`
    /// ascending: a B-spline surface's distinct interior knots, a swept curve's breaks, a
    /// cone's apex, a base surface's carried through an offset or reparameterisation; none for
    /// the other elementary surfaces. Integrals split there stay exact on piecewise
    /// polynomial integrands.
    pub fn knot_lines(&self) -> [Vec<f64>; 2] {
        match self {
            Surface::BSpline(b) => b.knots().each_ref().map(|k| k.interior_breaks()),
            Surface::Revolution(r) => [Vec::new(), r.curve().breaks()],
            Surface::Extrusion(e) => [e.curve().breaks(), Vec::new()],
            Surface::Offset(o) => o.base().knot_lines(),
            Surface::Reparam(r) => {
                let base = r.base().knot_lines();
                let mut ours: [Vec<f64>; 2] = [Vec::new(), Vec::new()];
                for (k, lines) in base.iter().enumerate() {
                    // Base parameter k is ours scaled and shifted: ours = (t - offset) / scale.
                    let mine = usize::from(r.swap()) ^ k;
                    ours[mine] = lines
                        .iter()
                        .map(|&t| {
                            let mut st = [0.0; 2];
                            st[k] = t;
                            r.from_base(st)[mine]
                        })
                        .collect();
                    ours[mine].sort_by(f64::total_cmp);
                }
                ours
            }
            // The apex, where the area element `|r + v tan a| |...|` has its kink.
            Surface::Cone(c) => [Vec::new(), vec![c.apex_v()]],
            Surface::Plane(_) | Surface::Cylinder(_) | Surface::Sphere(_) | Surface::Torus(_) => {
                [Vec::new(), Vec::new()]
            }
        }
    }

    /// The image of the surface under the affine map `m`, in the same parameters: the point
    /// of the image at `(u, v)` is `m` applied to this surface's point at `(u, v)`.
    ///
    /// B-spline surfaces and surfaces of extrusion map exactly under any affine map (control
    /// points and swept curves move, weights and knots stay). Elementary surfaces, surfaces of
    /// revolution and offsets keep their kind only under similarities (rigid motions,
    /// reflections, uniform scalings, within a relative deviation of `1e-9`): frames move,
    /// radii and offset distances scale; where the image's parameters would differ (a
    /// scaled plane's lengths, a reflection's reversed angle) the image is a [`Reparam`] of
    /// the moved surface.
    ///
    /// # Errors
    /// [`GeomError::NotFinite`] for a map with a non-finite entry;
    /// [`GeomError::NotSimilarity`] for a map that is not a similarity applied to a surface
    /// that needs one; the errors of the constructors for degenerate images (a singular map).
    pub fn transformed(&self, m: &Affine3) -> Result<Surface, GeomError> {
        transform::transformed(self, m)
    }

    /// How many offsets and reparameterisations are nested in this surface.
    pub(crate) fn depth(&self) -> usize {
        match self {
            Surface::Offset(o) => 1 + o.base().depth(),
            Surface::Reparam(r) => 1 + r.base().depth(),
            _ => 0,
        }
    }

    /// How many offsets are in this surface's chain of offsets and reparameterisations.
    pub(crate) fn offsets(&self) -> usize {
        match self {
            Surface::Offset(o) => 1 + o.base().offsets(),
            Surface::Reparam(r) => r.base().offsets(),
            _ => 0,
        }
    }

    /// A length typical of the surface (a radius, the size of a control net): the scale of
    /// relative tolerances and of difference steps.
    pub(crate) fn length_scale(&self) -> f64 {
        match self {
            Surface::Plane(_) => 1.0,
            Surface::Cylinder(c) => c.radius(),
            Surface::Cone(c) => c.radius().max(1.0),
            Surface::Sphere(s) => s.radius(),
            Surface::Torus(t) => t.major_radius() + t.minor_radius(),
            Surface::Revolution(r) => r.size(),
            Surface::Extrusion(e) => e.size(),
            Surface::Offset(o) => o.base().length_scale() + o.distance().abs(),
            Surface::BSpline(b) => b.size(),
            Surface::Reparam(r) => r.base().length_scale(),
        }
    }

    /// Parameter values along `u` and along `v` whose grid samples the surface finely enough
    /// to start a Newton search from its best nodes; `None` where a parameter is unbounded.
    pub(crate) fn sample_grid(&self) -> Option<[Vec<f64>; 2]> {
        match self {
            Surface::BSpline(b) => Some(b.sample_grid()),
            Surface::Offset(o) => o.base().sample_grid(),
            Surface::Reparam(r) => r.sample_grid(),
            Surface::Revolution(r) => r.sample_grid(),
            _ => {
                let bx = self.param_box();
                let [a, b] = bx.lengths();
                (a.is_finite() && b.is_finite()).then(|| {
                    [
                        invert::sample_params(bx.u, &[], GRID_PER_PERIOD, GRID_PER_PERIOD),
                        invert::sample_params(bx.v, &[], GRID_PER_PERIOD, GRID_PER_PERIOD),
                    ]
                })
            }
        }
    }

    /// The unit normal along `S_u x S_v`, as [`ParamSurface::normal`], or where that is
    /// undefined because a parameter line degenerates to a point (a cone's apex), the limit
    /// from the side of the parameter box's interior: the normal an offset moves along.
    pub(crate) fn limit_normal(&self, uv: [f64; 2]) -> Option<Point3> {
        self.normal(uv).or_else(|| {
            normal_from_derivatives(&self.derivatives(uv), interior_side(&self.param_box(), uv))
        })
    }
}

/// Samples per period (or per finite range) of an elementary surface's parameter in the grid
/// that starts the Newton searches of offsets.
const GRID_PER_PERIOD: usize = 16;

/// Below this ratio of `|S_u|` to `|S_v|` (or the other way round) the line through the point
/// is taken for a pole line and the normal for its limit, `S_uv x S_v` (or `S_u x S_uv`): the
/// square root of the machine epsilon balances the limit's error (the distance to the pole)
/// against the rounding of the vanishing derivative.
pub(crate) const POLE_DERIVATIVE_RATIO: f64 = 1.5e-8;

/// Below this sine of the angle between two non-vanishing `S_u` and `S_v` the normal is
/// undefined (a fold of the surface): a few roundings of the cross product.
pub(crate) const PARALLEL_SINE: f64 = 1e-14;

/// Two points within this fraction of a surface's size coincide when deciding whether a
/// B-spline surface is closed or has a pole, or whether a swept curve ends on its axis:
/// exporters write coordinates with 10 to 15 significant digits, so exact coincidence cannot
/// be asked of a file, while a boundary that is not degenerate is far longer.
pub(crate) const COINCIDENCE_RELATIVE: f64 = 1e-9;

/// A point within this many units in the last place of its distance to a surface's origin
/// from the axis is on the axis (its angle is rounding noise).
const ON_AXIS_RELATIVE: f64 = 4.0 * f64::EPSILON;

/// The unit normal along `d.du x d.dv`; at a pole (one derivative vanishing against the
/// other, see [`POLE_DERIVATIVE_RATIO`]) the limit approached from the side `side[i]` (`+1`
/// from above, `-1` from below) of the pole's parameter; `None` where both vanish or they are
/// parallel.
pub(crate) fn normal_from_derivatives(d: &SurfaceDerivatives, side: [f64; 2]) -> Option<Point3> {
    let (lu, lv) = (d.du.length(), d.dv.length());
    if !(lu.is_finite() && lv.is_finite()) {
        return None;
    }
    if lu <= POLE_DERIVATIVE_RATIO * lv {
        // The line v = const is a point: S_u(u, v + e) = e S_uv + O(e^2).
        return (d.duv.cross(d.dv) * side[1]).normalized();
    }
    if lv <= POLE_DERIVATIVE_RATIO * lu {
        return (d.du.cross(d.duv) * side[0]).normalized();
    }
    let n = d.du.cross(d.dv);
    if n.length() <= PARALLEL_SINE * lu * lv {
        return None;
    }
    n.normalized()
}

/// For each parameter, the side (`+1` above, `-1` below) from which the box's interior is
/// approached at `uv`: below only in the upper half of a finite range.
pub(crate) fn interior_side(bx: &ParamBox, uv: [f64; 2]) -> [f64; 2] {
    std::array::from_fn(|i| {
        let (a, b) = bx.range(i);
        if a.is_finite() && b.is_finite() && uv[i] - a > b - uv[i] {
            -1.0
        } else {
            1.0
        }
    })
}

/// The copy `t + k period` nearest `target` (`t` itself when it is the nearest).
pub(crate) fn nearest_copy(t: f64, target: f64, period: f64) -> f64 {
    let k = ((target - t) / period).round();
    if k.is_finite() && k != 0.0 {
        t + k * period
    } else {
        t
    }
}

/// The copy `t + k period` in `[start, start + period)` (`t` itself when it is in it).
pub(crate) fn copy_from(t: f64, start: f64, period: f64) -> f64 {
    let k = ((t - start) / period).floor();
    if k.is_finite() && k != 0.0 {
        t - k * period
    } else {
        t
    }
}

/// `uv` with each periodic parameter moved by whole periods: to the copy nearest `near`, or
/// without `near` to the copy in the parameter box.
pub(crate) fn place_periodic(
    uv: [f64; 2],
    near: Option<[f64; 2]>,
    periods: [Option<f64>; 2],
    bx: &ParamBox,
) -> [f64; 2] {
    std::array::from_fn(|i| match (periods[i], near) {
        (Some(p), Some(n)) => nearest_copy(uv[i], n[i], p),
        (Some(p), None) => {
            let a = bx.range(i).0;
            copy_from(uv[i], if a.is_finite() { a } else { 0.0 }, p)
        }
        (None, _) => uv[i],
    })
}

/// `near` if every parameter of it is finite.
pub(crate) fn usable_near(near: Option<[f64; 2]>) -> Option<[f64; 2]> {
    near.filter(|n| n.iter().all(|t| t.is_finite()))
}

/// The answer for a point with a non-finite coordinate: `near` (or `fallback`), distance NaN.
pub(crate) fn hostile_point(
    x: Point3,
    near: Option<[f64; 2]>,
    fallback: [f64; 2],
) -> Option<Inversion> {
    (!x.is_finite()).then(|| Inversion {
        uv: usable_near(near).unwrap_or(fallback),
        distance: f64::NAN,
    })
}

/// `(rho(u), rho'(u))` of a frame: `cos u x + sin u y` and `-sin u x + cos u y`.
pub(crate) fn radial(frame: &Frame, u: f64) -> (Point3, Point3) {
    let (s, c) = u.sin_cos();
    (frame.x * c + frame.y * s, frame.y * c - frame.x * s)
}

/// A point's coordinates about a frame's axis: its angle about `z` from `x` (`near_u`, or 0,
/// when the point is on the axis), its distance from the axis and its height along it.
pub(crate) fn cylindrical(frame: &Frame, x: Point3, near_u: Option<f64>) -> (f64, f64, f64) {
    let l = frame.to_local(x);
    let rho = l.x.hypot(l.y);
    let u = if rho <= ON_AXIS_RELATIVE * l.length() || rho == 0.0 {
        near_u.unwrap_or(0.0)
    } else {
        l.y.atan2(l.x)
    };
    (u, rho, l.z)
}

/// The box `[0, 2 pi]` of an angle.
pub(crate) const ANGLE: (f64, f64) = (0.0, TAU);

/// The inversion at `uv` (placed among periodic copies) with its distance to `x`.
pub(crate) fn finish<S: ParamSurface + ?Sized>(
    s: &S,
    x: Point3,
    uv: [f64; 2],
    near: Option<[f64; 2]>,
) -> Inversion {
    let uv = place_periodic(uv, near, s.periods(), &s.param_box());
    Inversion {
        uv,
        distance: s.point(uv).distance(x),
    }
}

/// Checks that `value` is finite and `> 0`.
pub(crate) fn positive(what: &'static str, value: f64) -> Result<f64, GeomError> {
    if !value.is_finite() {
        return Err(GeomError::NotFinite { what, value });
    }
    if value <= 0.0 {
        return Err(GeomError::NotPositive { what, value });
    }
    Ok(value)
}

/// Checks that `value` is finite.
pub(crate) fn finite(what: &'static str, value: f64) -> Result<f64, GeomError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(GeomError::NotFinite { what, value })
    }
}

#[cfg(test)]
mod tests {
    use super::testing::{Rng, check_derivatives, check_normal, check_round_trip, one_of_each};
    use super::*;

    #[test]
    fn every_kind_dispatches_and_names_itself() {
        let mut rng = Rng::new(71);
        let all = one_of_each(&mut rng);
        let names: Vec<&str> = all.iter().map(Surface::kind_name).collect();
        assert_eq!(
            names,
            [
                "plane",
                "cylinder",
                "cone",
                "sphere",
                "torus",
                "surface of revolution",
                "surface of linear extrusion",
                "offset surface",
                "B-spline surface",
                "reparameterised surface"
            ]
        );
        for s in &all {
            for _ in 0..5 {
                let uv = [rng.range(0.1, 0.4), rng.range(0.1, 0.4)];
                check_derivatives(s, uv, 0.1);
                check_normal(s, uv);
                check_round_trip(s, uv, None, 1e-10, 10.0);
                check_round_trip(s, uv, Some([uv[0] + 0.05, uv[1] - 0.05]), 1e-10, 10.0);
                // Through the enum, the inner surface's answers.
                let inner = dispatch!(s, x => x.derivatives(uv));
                assert_eq!(inner, s.derivatives(uv));
            }
            assert!(s.depth() <= 1 && s.length_scale() > 0.0);
        }
    }

    #[test]
    fn hostile_inputs_are_bounded() {
        let mut rng = Rng::new(72);
        let start = std::time::Instant::now();
        let points = [
            Point3::new(f64::NAN, 0.0, 0.0),
            Point3::new(0.0, f64::INFINITY, 0.0),
            Point3::new(1e300, -1e300, 1e300),
            Point3::new(1e150, 1e150, -1e150),
            Point3::new(-1e-300, 1e-300, 0.0),
        ];
        let nears = [
            None,
            Some([f64::NAN, 0.0]),
            Some([1e300, -1e300]),
            Some([0.5, 0.5]),
        ];
        for s in one_of_each(&mut rng) {
            for x in points {
                for near in nears {
                    let inv = s.invert(x, near);
                    if x.is_finite() {
                        assert!(
                            inv.distance >= 0.0 || inv.distance.is_nan(),
                            "{}: {inv:?}",
                            s.kind_name()
                        );
                    } else {
                        assert!(inv.distance.is_nan(), "{}: {inv:?}", s.kind_name());
                    }
                }
            }
            // A point at a moderate distance always gets finite parameters and distance.
            let inv = s.invert(Point3::new(1e6, -2e6, 3e6), None);
            assert!(inv.uv.iter().all(|t| t.is_finite()) && inv.distance.is_finite());
            for uv in [[f64::NAN, 0.5], [0.5, f64::INFINITY], [1e300, -1e300]] {
                let _ = (s.point(uv), s.derivatives(uv), s.normal(uv));
            }
        }
        assert!(start.elapsed().as_secs() < 30);
    }

    #[test]
    fn periodic_copies_and_box_helpers() {
        assert_eq!(nearest_copy(0.5, 0.5 + 3.0 * TAU, TAU), 0.5 + 3.0 * TAU);
        assert_eq!(nearest_copy(0.5, 0.6, TAU), 0.5);
        assert_eq!(copy_from(-0.5, 0.0, TAU), TAU - 0.5);
        assert_eq!(copy_from(1.0, 0.0, TAU), 1.0);
        let bx = ParamBox {
            u: (0.0, 1.0),
            v: (f64::NEG_INFINITY, 2.0),
        };
        assert_eq!(bx.clamp([2.0, 5.0]), [1.0, 2.0]);
        assert!(bx.contains([0.5, -1e300]) && !bx.contains([0.5, 3.0]));
        assert_eq!(bx.lengths()[0], 1.0);
        assert_eq!(interior_side(&bx, [0.9, 0.0]), [-1.0, 1.0]);
        assert_eq!(
            place_periodic([-0.5, 7.0], None, [Some(TAU), None], &bx),
            [TAU - 0.5, 7.0]
        );
    }
}
