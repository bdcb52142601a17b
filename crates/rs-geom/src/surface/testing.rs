//! Test helpers: a seeded generator, random frames, and the checks every surface passes
//! (derivatives against finite differences of `point`, normals against `S_u x S_v`,
//! inversion round trips).

use rs_spline::{KnotVector, Point3, RationalBSpline};

use super::{
    BSplineSurface, Cone, Cylinder, Extrusion, Offset, ParamSurface, Plane, Reparam, Revolution,
    Sphere, Surface, Torus, nearest_copy,
};
use crate::{Conic, ConicKind, Curve, Frame};

/// `SplitMix64`: a small seeded generator (reproducible test inputs).
pub(crate) struct Rng(u64);

impl Rng {
    pub(crate) fn new(seed: u64) -> Rng {
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03)
    }

    pub(crate) fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in `[a, b)`.
    pub(crate) fn range(&mut self, a: f64, b: f64) -> f64 {
        let unit = (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        a + (b - a) * unit
    }

    /// A point in the cube `[-s, s]^3`.
    pub(crate) fn point(&mut self, s: f64) -> Point3 {
        Point3::new(self.range(-s, s), self.range(-s, s), self.range(-s, s))
    }

    /// A unit vector (uniform enough for tests).
    pub(crate) fn unit(&mut self) -> Point3 {
        loop {
            let p = self.point(1.0);
            let l = p.length();
            if l > 0.1 && l <= 1.0 {
                return p * (1.0 / l);
            }
        }
    }

    /// A frame with a random origin in `[-s, s]^3` and random (tilted) axes.
    pub(crate) fn frame(&mut self, s: f64) -> Frame {
        loop {
            let (o, z, x) = (self.point(s), self.unit(), self.unit());
            if z.cross(x).length() > 0.2 {
                return Frame::new(o, Some(z), Some(x)).unwrap();
            }
        }
    }
}

/// Central differences of `f` at `t` with step `h`, Richardson-extrapolated (error `O(h^4)`):
/// `(first, second)` derivative estimates.
fn richardson(f: impl Fn(f64) -> Point3, t: f64, h: f64) -> (Point3, Point3) {
    let d1 = |h: f64| (f(t + h) - f(t - h)) * (0.5 / h);
    let d2 = |h: f64| (f(t + h) - f(t) * 2.0 + f(t - h)) * (1.0 / (h * h));
    (
        (d1(0.5 * h) * 4.0 - d1(h)) * (1.0 / 3.0),
        (d2(0.5 * h) * 4.0 - d2(h)) * (1.0 / 3.0),
    )
}

/// Checks the analytic derivatives at `uv` against Richardson-extrapolated central differences
/// of `point` (steps `1e-2 param_scale`), to a relative `1e-7` of the derivatives' size.
pub(crate) fn check_derivatives<S: ParamSurface + ?Sized>(s: &S, uv: [f64; 2], param_scale: f64) {
    let h = 1e-2 * param_scale;
    let d = s.derivatives(uv);
    assert!(
        d.point.distance(s.point(uv)) <= 1e-14 * (1.0 + d.point.length()),
        "point {:?} vs {:?}",
        d.point,
        s.point(uv)
    );
    // The first derivatives alone are the same numbers, bit for bit.
    assert_eq!(s.first_derivatives(uv), [d.point, d.du, d.dv], "at {uv:?}");
    let (du, duu) = richardson(|t| s.point([t, uv[1]]), uv[0], h);
    let (dv, dvv) = richardson(|t| s.point([uv[0], t]), uv[1], h);
    let mixed = |h: f64| {
        (s.point([uv[0] + h, uv[1] + h])
            - s.point([uv[0] + h, uv[1] - h])
            - s.point([uv[0] - h, uv[1] + h])
            + s.point([uv[0] - h, uv[1] - h]))
            * (0.25 / (h * h))
    };
    let duv = (mixed(0.5 * h) * 4.0 - mixed(h)) * (1.0 / 3.0);
    let first = d.du.length() + d.dv.length();
    let second = d.duu.length() + d.duv.length() + d.dvv.length() + first / param_scale;
    for (name, a, b, m) in [
        ("du", d.du, du, first),
        ("dv", d.dv, dv, first),
        ("duu", d.duu, duu, second),
        ("duv", d.duv, duv, second),
        ("dvv", d.dvv, dvv, second),
    ] {
        assert!(
            a.distance(b) <= 1e-7 * m,
            "{name} at {uv:?}: analytic {a:?}, differences {b:?} (scale {m:e})"
        );
    }
}

/// Checks that the normal at `uv` is the unit `S_u x S_v`.
pub(crate) fn check_normal<S: ParamSurface + ?Sized>(s: &S, uv: [f64; 2]) {
    let d = s.derivatives(uv);
    let expected = d.du.cross(d.dv).normalized().unwrap();
    let n = s.normal(uv).unwrap();
    assert!(
        n.distance(expected) < 1e-12 && (n.length() - 1.0).abs() < 1e-15,
        "normal at {uv:?}: {n:?} vs {expected:?}"
    );
}

/// Checks that inverting the point at `uv` gives `uv` back (up to periods) and the point
/// itself, within `tol` (parameters) and `tol * size` (the point), from `near` (if any).
pub(crate) fn check_round_trip<S: ParamSurface + ?Sized>(
    s: &S,
    uv: [f64; 2],
    near: Option<[f64; 2]>,
    tol: f64,
    size: f64,
) {
    let x = s.point(uv);
    let inv = s.invert(x, near);
    assert!(
        inv.distance <= tol * size && s.point(inv.uv).distance(x) <= tol * size,
        "round trip of {uv:?} (near {near:?}): {inv:?}, off by {:e}",
        inv.distance
    );
    let periods = s.periods();
    for i in 0..2 {
        let back = periods[i].map_or(inv.uv[i], |p| nearest_copy(inv.uv[i], uv[i], p));
        assert!(
            (back - uv[i]).abs() <= tol * (1.0 + uv[i].abs()),
            "round trip of {uv:?}: parameter {i} came back as {} ({inv:?})",
            inv.uv[i]
        );
    }
    if let Some(n) = near {
        for i in 0..2 {
            if let Some(p) = periods[i] {
                assert!(
                    (inv.uv[i] - n[i]).abs() <= 0.5 * p + tol,
                    "copy of parameter {i} not nearest {n:?}: {inv:?}"
                );
            }
        }
    }
}

/// One surface of each kind, in a random frame (the order of [`Surface`]'s variants).
pub(crate) fn one_of_each(rng: &mut Rng) -> Vec<Surface> {
    let f = rng.frame(2.0);
    let arc = RationalBSpline::new(
        2,
        vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
        vec![
            Point3::new(2.0, 0.0, -1.0),
            Point3::new(3.0, 0.0, 0.0),
            Point3::new(2.0, 0.5, 1.0),
        ],
        Some(vec![1.0, 0.6, 1.0]),
    )
    .unwrap();
    let ellipse = Curve::Conic(Conic {
        kind: ConicKind::Ellipse,
        center: Point3::new(0.5, 0.0, 0.0),
        u: Point3::new(2.0, 0.0, 0.0),
        v: Point3::new(0.0, 1.0, 0.3),
    });
    let mut points = Vec::new();
    for i in 0..3 {
        for j in 0..4 {
            points.push(Point3::new(
                f64::from(i),
                f64::from(j),
                rng.range(-1.0, 1.0),
            ));
        }
    }
    let bs = BSplineSurface::new(
        [
            KnotVector::bezier(2),
            KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0], 2, 4).unwrap(),
        ],
        points,
        Some(vec![
            1.0, 1.2, 0.8, 1.0, 1.1, 0.9, 1.0, 1.0, 1.0, 1.3, 0.7, 1.0,
        ]),
    )
    .unwrap();
    let sphere = Surface::Sphere(Sphere::new(f, 1.5).unwrap());
    vec![
        Surface::Plane(Plane::new(f)),
        Surface::Cylinder(Cylinder::new(f, 1.5).unwrap()),
        Surface::Cone(Cone::new(f, 1.0, 0.4).unwrap()),
        sphere.clone(),
        Surface::Torus(Torus::new(f, 2.0, 0.5).unwrap()),
        Surface::Revolution(Revolution::new(Curve::BSpline(arc), f.origin, f.z).unwrap()),
        Surface::Extrusion(Extrusion::new(ellipse, Point3::new(0.2, 0.1, 1.5)).unwrap()),
        Surface::Offset(Offset::new(sphere.clone(), 0.25).unwrap()),
        Surface::BSpline(bs),
        Surface::Reparam(Reparam::new(sphere, true, [0.5, -2.0], [0.1, 0.2]).unwrap()),
    ]
}

/// The rational biquadratic octant of the sphere of radius `r` about the origin: a quarter
/// turn about `z` (along `u`) of the meridian quarter circle from the equator to the north
/// pole (along `v`); the column `v = 1` is the pole, the normal points outwards.
pub(crate) fn sphere_octant(r: f64) -> BSplineSurface {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let meridian = [(r, 0.0, 1.0), (r, r, w), (0.0, r, 1.0)]; // (radius, height, weight)
    let turn = [(1.0, 0.0, 1.0), (1.0, 1.0, w), (0.0, 1.0, 1.0)]; // (x, y, weight)
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for &(x, y, wi) in &turn {
        for &(rad, h, wj) in &meridian {
            points.push(Point3::new(rad * x, rad * y, h));
            weights.push(wi * wj);
        }
    }
    BSplineSurface::new(
        [KnotVector::bezier(2), KnotVector::bezier(2)],
        points,
        Some(weights),
    )
    .unwrap()
}
