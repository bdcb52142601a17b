//! Tests of [`super::pcurve`]: exact iso-lines on every surface kind (random frames, both edge
//! directions), planes bit for bit as the readers convert, fitted pcurves whose bound is checked
//! against dense sampling, poles, seams, closed edges and the errors.

use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, PI, TAU};

use rs_spline::{KnotVector, NurbsCurve, ParamCurve, Point, Point3, RationalBSpline};

use super::fit::least_squares;
use super::*;
use crate::surface::testing::{Rng, sphere_octant};
use crate::surface::{
    BSplineSurface, Cone, Cylinder, Extrusion, Offset, Plane, Reparam, Revolution, Sphere, Torus,
};
use crate::{Affine3, Conic, ConicKind, Frame, PlaneCoordinates};

/// `cos t e1 + sin t e2` of a frame's `x`, `y` turned by `u`: `rho(u)`.
fn rho(f: &Frame, u: f64) -> Point3 {
    f.x * u.cos() + f.y * u.sin()
}

/// The circle `center + radius (cos(phase + sign t) e1 + sin(phase + sign t) e2)`.
fn circle(
    center: Point3,
    e1: Point3,
    e2: Point3,
    radius: f64,
    phase: f64,
    sign: f64,
) -> Curve<Point3> {
    let (s, c) = phase.sin_cos();
    Curve::Conic(Conic {
        kind: ConicKind::Ellipse,
        center,
        u: (e1 * c + e2 * s) * radius,
        v: (e2 * c - e1 * s) * (radius * sign),
    })
}

/// An edge expected on the iso-line `uv[d] = c` with the free parameter running from `w.0` to
/// `w.1` over `range`.
struct IsoCase {
    name: &'static str,
    surface: Surface,
    edge: Curve<Point3>,
    range: (f64, f64),
    d: usize,
    c: f64,
    w: (f64, f64),
}

/// The same value up to a whole period (if `period`).
fn same(a: f64, b: f64, period: Option<f64>, tol: f64) -> bool {
    let b = period.map_or(b, |p| nearest_copy(b, a, p));
    (a - b).abs() <= tol * (1.0 + a.abs())
}

fn ends(c: &NurbsCurve) -> ([f64; 2], [f64; 2]) {
    let (a, b) = (c.start_point(), c.end_point());
    ([a.x, a.y], [b.x, b.y])
}

/// The largest distance from the surface's image of `curves` (at `n` points each) to the
/// edge's closest points on `window`.
fn image_to_edge(
    s: &Surface,
    edge: &Curve<Point3>,
    curves: &[NurbsCurve],
    window: (f64, f64),
    n: usize,
) -> f64 {
    let mut worst = 0.0f64;
    for c in curves {
        let (a, b) = c.param_range();
        for i in 0..=n {
            let p = c.point_at(a + (b - a) * i as f64 / n as f64);
            let y = s.point([p.x, p.y]);
            let t = edge.closest_parameter(y, Some(window));
            worst = worst.max(edge.point(t).distance(y));
        }
    }
    worst
}

/// Consecutive pieces meet exactly; the first starts at the edge's first point and the last
/// ends at its last (within `tol`).
fn check_chain(s: &Surface, edge: &Curve<Point3>, range: (f64, f64), p: &Pcurve, tol: f64) {
    for w in p.curves.windows(2) {
        assert_eq!(ends(&w[0]).1, ends(&w[1]).0, "pieces do not meet: {p:?}");
    }
    let (first, _) = ends(&p.curves[0]);
    let (_, last) = ends(&p.curves[p.curves.len() - 1]);
    assert!(
        s.point(first).distance(edge.point(range.0)) <= tol,
        "start {p:?}"
    );
    assert!(
        s.point(last).distance(edge.point(range.1)) <= tol,
        "end {p:?}"
    );
}

fn check_iso(case: &IsoCase, reversed: bool) {
    let range = if reversed {
        (case.range.1, case.range.0)
    } else {
        case.range
    };
    let (w0, w1) = if reversed {
        (case.w.1, case.w.0)
    } else {
        case.w
    };
    let s = &case.surface;
    let p = pcurve(s, &case.edge, Some(range), &PcurveOptions::DEFAULT)
        .unwrap_or_else(|e| panic!("{}: {e}", case.name));
    let size = 20.0;
    assert_eq!(p.kind, PcurveKind::IsoLine, "{}: {p:?}", case.name);
    assert_eq!(p.curves.len(), 1, "{}", case.name);
    assert!(!p.rigorous);
    let (a, b) = ends(&p.curves[0]);
    let (d, w) = (case.d, 1 - case.d);
    let periods = s.periods();
    assert_eq!(a[d], b[d], "{}: not an iso-line", case.name);
    assert!(
        same(a[d], case.c, periods[d], 1e-9),
        "{}: {a:?} vs c = {}",
        case.name,
        case.c
    );
    assert!(
        same(a[w], w0, periods[w], 1e-9),
        "{}: {a:?} vs w0 = {w0}",
        case.name
    );
    assert!(
        ((b[w] - a[w]) - (w1 - w0)).abs() <= 1e-9 * (1.0 + (w1 - w0).abs()),
        "{}: {a:?} -> {b:?} vs {w0} -> {w1}",
        case.name
    );
    assert!(
        p.deviation <= ISO_RELATIVE * size,
        "{}: {}",
        case.name,
        p.deviation
    );
    check_chain(s, &case.edge, range, &p, 1e-11 * size);
    let dense = image_to_edge(
        s,
        &case.edge,
        &p.curves,
        (
            case.range.0.min(case.range.1),
            case.range.0.max(case.range.1),
        ),
        100,
    );
    assert!(dense <= ISO_RELATIVE * size, "{}: {dense:e}", case.name);
}

/// A rotation by `angle` about the axis through `o` along the unit `d`.
fn rotation(o: Point3, d: Point3, angle: f64) -> Affine3 {
    let (s, c) = angle.sin_cos();
    let m3 = |i: usize, j: usize| {
        let e = |k: usize| [d.x, d.y, d.z][k];
        let cross = [[0.0, -d.z, d.y], [d.z, 0.0, -d.x], [-d.y, d.x, 0.0]];
        c * f64::from(u8::from(i == j)) + (1.0 - c) * e(i) * e(j) + s * cross[i][j]
    };
    let o = [o.x, o.y, o.z];
    let m = std::array::from_fn(|i| {
        let shift = o[i] - (0..3).map(|j| m3(i, j) * o[j]).sum::<f64>();
        [m3(i, 0), m3(i, 1), m3(i, 2), shift]
    });
    Affine3 { m }
}

/// A random sign.
fn sign(rng: &mut Rng) -> f64 {
    if rng.range(0.0, 1.0) < 0.5 { -1.0 } else { 1.0 }
}

/// Iso-line edges of every kind of surface, in a random frame.
fn iso_cases(rng: &mut Rng) -> Vec<IsoCase> {
    let f = rng.frame(3.0);
    let mut out = Vec::new();
    // Cylinder: a ruling and a circle.
    let r = rng.range(0.5, 3.0);
    let cyl = Surface::Cylinder(Cylinder::new(f, r).unwrap());
    let (c, lam) = (rng.range(0.0, TAU), rng.range(0.5, 2.0) * sign(rng));
    let v0 = rng.range(-2.0, 2.0);
    out.push(IsoCase {
        name: "cylinder ruling",
        surface: cyl.clone(),
        edge: Curve::Line {
            origin: cyl.point([c, v0]),
            direction: f.z * lam,
        },
        range: (-0.7, 1.1),
        d: 0,
        c,
        w: (v0 - 0.7 * lam, v0 + 1.1 * lam),
    });
    let (h, phase, sg) = (rng.range(-2.0, 2.0), rng.range(-PI, PI), sign(rng));
    let (t0, t1) = (rng.range(-1.0, 1.0), rng.range(1.5, 5.5));
    out.push(IsoCase {
        name: "cylinder circle",
        surface: cyl.clone(),
        edge: circle(f.origin + f.z * h, f.x, f.y, r, phase, sg),
        range: (t0, t1),
        d: 1,
        c: h,
        w: (phase + sg * t0, phase + sg * t1),
    });
    // Cone: a ruling and a circle.
    let (r, a) = (rng.range(0.5, 2.0), rng.range(0.2, 1.2));
    let cone = Surface::Cone(Cone::new(f, r, a).unwrap());
    let c = rng.range(0.0, TAU);
    let dir = (rho(&f, c) * a.tan() + f.z) * lam;
    out.push(IsoCase {
        name: "cone ruling",
        surface: cone.clone(),
        edge: Curve::Line {
            origin: cone.point([c, 0.3]),
            direction: dir,
        },
        range: (0.1, 0.9),
        d: 0,
        c,
        w: (0.3 + 0.1 * lam, 0.3 + 0.9 * lam),
    });
    let h = rng.range(-0.5, 1.5);
    out.push(IsoCase {
        name: "cone circle",
        surface: cone,
        edge: circle(f.origin + f.z * h, f.x, f.y, r + h * a.tan(), phase, sg),
        range: (t0, t1),
        d: 1,
        c: h,
        w: (phase + sg * t0, phase + sg * t1),
    });
    // Sphere: a latitude circle and a meridian arc.
    let big = rng.range(0.5, 3.0);
    let sphere = Surface::Sphere(Sphere::new(f, big).unwrap());
    let h = rng.range(-1.2, 1.2);
    out.push(IsoCase {
        name: "sphere latitude",
        surface: sphere.clone(),
        edge: circle(
            f.origin + f.z * (big * h.sin()),
            f.x,
            f.y,
            big * h.cos(),
            phase,
            sg,
        ),
        range: (t0, t1),
        d: 1,
        c: h,
        w: (phase + sg * t0, phase + sg * t1),
    });
    let (c, psi) = (rng.range(0.0, TAU), rng.range(-0.4, 0.4));
    let (m0, m1) = (rng.range(-0.9, -0.1), rng.range(0.1, 0.9));
    out.push(IsoCase {
        name: "sphere meridian",
        surface: sphere,
        edge: circle(f.origin, rho(&f, c), f.z, big, psi, sg),
        range: (m0, m1),
        d: 0,
        c,
        w: (psi + sg * m0, psi + sg * m1),
    });
    // Torus: both families of circles.
    let (major, minor) = (rng.range(1.5, 3.0), rng.range(0.2, 1.0));
    let torus = Surface::Torus(Torus::new(f, major, minor).unwrap());
    let h = rng.range(0.0, TAU);
    out.push(IsoCase {
        name: "torus parallel",
        surface: torus.clone(),
        edge: circle(
            f.origin + f.z * (minor * h.sin()),
            f.x,
            f.y,
            major + minor * h.cos(),
            phase,
            sg,
        ),
        range: (t0, t1),
        d: 1,
        c: h,
        w: (phase + sg * t0, phase + sg * t1),
    });
    let psi = rng.range(-PI, PI);
    out.push(IsoCase {
        name: "torus meridian",
        surface: torus,
        edge: circle(
            f.origin + rho(&f, c) * major,
            rho(&f, c),
            f.z,
            minor,
            psi,
            sg,
        ),
        range: (t0, t1),
        d: 0,
        c,
        w: (psi + sg * t0, psi + sg * t1),
    });
    // Revolution of a B-spline of the frame's xz half-plane: a turned generatrix and a
    // parallel circle.
    let local: Vec<(f64, f64)> = (0..5)
        .map(|i| {
            (
                rng.range(0.8, 2.0),
                f64::from(i) * 0.6 + rng.range(-0.1, 0.1),
            )
        })
        .collect();
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0];
    let weights = Some(vec![1.0, 0.8, 1.3, 0.9, 1.0]);
    let generatrix = |angle: f64| {
        Curve::BSpline(
            RationalBSpline::new(
                3,
                knots.clone(),
                local
                    .iter()
                    .map(|&(a, b)| f.to_world(a * angle.cos(), a * angle.sin(), b))
                    .collect(),
                weights.clone(),
            )
            .unwrap(),
        )
    };
    let rev = Surface::Revolution(Revolution::new(generatrix(0.0), f.origin, f.z).unwrap());
    let c = rng.range(0.0, TAU);
    let turned = generatrix(0.0)
        .map_affine(&rotation(f.origin, f.z, c))
        .unwrap();
    assert!(turned.point(0.3).distance(generatrix(c).point(0.3)) < 1e-13);
    out.push(IsoCase {
        name: "revolution generatrix",
        surface: rev.clone(),
        edge: turned,
        range: (0.15, 0.85),
        d: 0,
        c,
        w: (0.15, 0.85),
    });
    let v = rng.range(0.1, 0.9);
    let l = f.to_local(generatrix(0.0).point(v));
    out.push(IsoCase {
        name: "revolution parallel",
        surface: rev,
        edge: circle(f.origin + f.z * l.z, f.x, f.y, l.x, phase, sg),
        range: (t0, t1),
        d: 1,
        c: v,
        w: (phase + sg * t0, phase + sg * t1),
    });
    // Extrusion of an ellipse: a ruling and a translated copy of the curve.
    let ellipse = Conic {
        kind: ConicKind::Ellipse,
        center: f.origin,
        u: f.x * 1.5,
        v: f.y * 0.7 + f.z * 0.2,
    };
    let vector = f.z * 1.3 + f.x * 0.4;
    let ext = Surface::Extrusion(Extrusion::new(Curve::Conic(ellipse.clone()), vector).unwrap());
    let c = rng.range(0.0, TAU);
    out.push(IsoCase {
        name: "extrusion ruling",
        surface: ext.clone(),
        edge: Curve::Line {
            origin: ellipse.point(c),
            direction: vector * lam,
        },
        range: (-0.5, 0.8),
        d: 0,
        c,
        w: (-0.5 * lam, 0.8 * lam),
    });
    let h = rng.range(-1.0, 1.0);
    out.push(IsoCase {
        name: "extrusion copy",
        surface: ext,
        edge: Curve::Conic(Conic {
            center: ellipse.center + vector * h,
            ..ellipse.clone()
        }),
        range: (t0, t1),
        d: 1,
        c: h,
        w: (t0, t1),
    });
    out
}

#[test]
fn iso_lines_of_every_elementary_surface_both_ways() {
    let mut rng = Rng::new(101);
    for _ in 0..12 {
        for case in iso_cases(&mut rng) {
            check_iso(&case, false);
            check_iso(&case, true);
        }
    }
}

/// A quarter of the cylinder of radius `r` and height `h` about `f`'s `z` from `x` to `y`, as
/// a rational B-spline patch: `u` along the rational quadratic arc, `v` the height (degree 1).
fn quarter_cylinder(f: &Frame, r: f64, h: f64) -> BSplineSurface {
    let arc = [(r, 0.0, 1.0), (r, r, FRAC_1_SQRT_2), (0.0, r, 1.0)];
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for &(x, y, w) in &arc {
        for z in [0.0, h] {
            points.push(f.to_world(x, y, z));
            weights.push(w);
        }
    }
    BSplineSurface::new(
        [KnotVector::bezier(2), KnotVector::bezier(1)],
        points,
        Some(weights),
    )
    .unwrap()
}

/// The boundary iso-lines of a rational patch (lines and arcs as native curves, whose
/// parameters are not the patch's) and interior ones, both ways.
#[test]
fn iso_lines_of_a_rational_patch() {
    let mut rng = Rng::new(102);
    for _ in 0..10 {
        let f = rng.frame(3.0);
        let (r, h) = (rng.range(0.5, 3.0), rng.range(0.5, 3.0));
        let s = Surface::BSpline(quarter_cylinder(&f, r, h));
        let arc = |z: f64| circle(f.origin + f.z * z, f.x, f.y, r, 0.0, 1.0);
        let line = |uv: [f64; 2]| Curve::Line {
            origin: s.point(uv),
            direction: f.z * h,
        };
        let u = rng.range(0.05, 0.95);
        let v = rng.range(0.05, 0.95);
        let cases = [
            (
                "v = 0 boundary",
                arc(0.0),
                (0.0, FRAC_PI_2),
                1,
                0.0,
                (0.0, 1.0),
            ),
            (
                "v = 1 boundary",
                arc(h),
                (0.0, FRAC_PI_2),
                1,
                1.0,
                (0.0, 1.0),
            ),
            (
                "u = 0 boundary",
                line([0.0, 0.0]),
                (0.0, 1.0),
                0,
                0.0,
                (0.0, 1.0),
            ),
            (
                "u = 1 boundary",
                line([1.0, 0.0]),
                (0.0, 1.0),
                0,
                1.0,
                (0.0, 1.0),
            ),
            ("interior v", arc(v * h), (0.0, FRAC_PI_2), 1, v, (0.0, 1.0)),
            ("interior u", line([u, 0.0]), (0.2, 0.7), 0, u, (0.2, 0.7)),
        ];
        for (name, edge, range, d, c, w) in cases {
            let case = IsoCase {
                name,
                surface: s.clone(),
                edge,
                range,
                d,
                c,
                w,
            };
            check_iso(&case, false);
            check_iso(&case, true);
        }
        // A part of an interior arc: its ends are the patch's points of the arc's ends.
        let edge = arc(v * h);
        let p = pcurve(&s, &edge, Some((0.3, 1.1)), &PcurveOptions::DEFAULT).unwrap();
        assert_eq!(p.kind, PcurveKind::IsoLine);
        check_chain(&s, &edge, (0.3, 1.1), &p, 1e-12 * 20.0);
    }
}

/// Edges a little off their surface whose closest points all lie on one iso-line (a circle of
/// a slightly larger radius about a cylinder, a patch's boundary arc written off the patch):
/// that line, with the edge's distance as the measured deviation; farther than the tolerance,
/// fitted instead.
#[test]
fn projections_onto_iso_lines_are_iso_lines() {
    let mut rng = Rng::new(109);
    for _ in 0..10 {
        let f = rng.frame(3.0);
        let (r, h) = (rng.range(0.5, 3.0), rng.range(0.5, 3.0));
        let off = 1e-6;
        let cylinder = Surface::Cylinder(Cylinder::new(f, r).unwrap());
        let patch = Surface::BSpline(quarter_cylinder(&f, r, h));
        let height = rng.range(-1.0, 1.0);
        for (s, z, range, constant) in [
            (&cylinder, height, (0.3, 5.0), height),
            (&patch, 0.0, (0.0, FRAC_PI_2), 0.0),
            (&patch, h, (0.2, 1.3), 1.0),
        ] {
            let edge = circle(f.origin + f.z * z, f.x, f.y, r + off, 0.0, 1.0);
            let o = PcurveOptions::DEFAULT.with_tolerance(1e-5);
            let p = pcurve(s, &edge, Some(range), &o).unwrap();
            assert_eq!(p.kind, PcurveKind::IsoLine, "{}", s.kind_name());
            let (a, b) = ends(&p.curves[0]);
            assert!(
                a[1] == b[1] && (a[1] - constant).abs() < 1e-12,
                "{a:?} {b:?}"
            );
            assert!((p.deviation - off).abs() < 1e-9, "{}", p.deviation);
            // Beyond the tolerance: the fit's bound, at least the distance.
            let o = PcurveOptions::DEFAULT.with_tolerance(1e-7);
            let p = pcurve(s, &edge, Some(range), &o).unwrap();
            assert_eq!(p.kind, PcurveKind::Fitted);
            assert!(p.deviation >= off);
        }
    }
}

/// A full circle spans exactly one period, its start the copy nearest `near`; a closed edge
/// on a seam takes the copy of `near`.
#[test]
fn closed_edges_span_whole_periods_and_seams_follow_near() {
    let mut rng = Rng::new(103);
    for _ in 0..20 {
        let f = rng.frame(3.0);
        let r = rng.range(0.5, 3.0);
        let s = Surface::Cylinder(Cylinder::new(f, r).unwrap());
        let (h, phase, sg) = (rng.range(-2.0, 2.0), rng.range(-PI, PI), sign(&mut rng));
        let edge = circle(f.origin + f.z * h, f.x, f.y, r, phase, sg);
        let t0 = rng.range(-3.0, 3.0);
        for (range, near) in [
            ((t0, t0 + TAU), None),
            ((t0 + TAU, t0), Some([7.0 * PI, h])),
        ] {
            let o = PcurveOptions::DEFAULT.with_near(near);
            let p = pcurve(&s, &edge, Some(range), &o).unwrap();
            let (a, b) = ends(&p.curves[0]);
            assert_eq!(p.kind, PcurveKind::IsoLine);
            // Exactly a period: the end is the start plus 2 pi (rounded once).
            let turn = sg * (range.1 - range.0).signum() * TAU;
            assert_eq!(b[0], a[0] + turn, "{a:?} {b:?}");
            if let Some(n) = near {
                assert!((a[0] - n[0]).abs() <= PI);
            } else {
                assert!((0.0..TAU).contains(&a[0]));
            }
        }
        // The seam ruling u = 0 taken as u = 2 pi after an edge that ended there.
        let ruling = Curve::Line {
            origin: s.point([0.0, 0.0]),
            direction: f.z,
        };
        for near in [[TAU - 0.1, 1.0], [0.1, 1.0], [-TAU + 0.1, 1.0]] {
            let o = PcurveOptions::DEFAULT.with_near(Some(near));
            let p = pcurve(&s, &ruling, Some((1.0, -1.0)), &o).unwrap();
            let (a, b) = ends(&p.curves[0]);
            let expect = nearest_copy(0.0, near[0], TAU);
            assert!(
                (a[0] - expect).abs() < 1e-12 && a[0] == b[0],
                "{a:?} {near:?}"
            );
            assert!((a[1] - 1.0).abs() < 1e-14 && (b[1] + 1.0).abs() < 1e-14);
        }
    }
    // A closed periodic B-spline circle edge across its domain's end: two pieces of the
    // edge, one segment.
    let s = Surface::Cylinder(Cylinder::new(Frame::WORLD, 1.0).unwrap());
    let unit = rs_spline::circle(Point::new(0.0, 0.0), 1.0).unwrap();
    let b = RationalBSpline::new(
        2,
        unit.knots().knots().to_vec(),
        unit.control_points()
            .iter()
            .map(|p| Point3::new(p.x, p.y, 0.5))
            .collect(),
        Some(unit.weights().to_vec()),
    )
    .unwrap();
    let edge = Curve::BSpline(b);
    let (a, e) = edge.range().unwrap();
    let mid = a + 0.3 * (e - a);
    let p = pcurve(
        &s,
        &edge,
        Some((mid, mid + (e - a))),
        &PcurveOptions::DEFAULT,
    )
    .unwrap();
    assert_eq!(p.kind, PcurveKind::IsoLine);
    assert_eq!(p.curves.len(), 1);
    let (first, last) = ends(&p.curves[0]);
    assert!(
        ((last[0] - first[0]).abs() - TAU).abs() < 1e-12,
        "{first:?} {last:?}"
    );
    // (The edge's point at `mid + (e - a)` is its point at `mid`, a period on.)
    assert!(s.point(first).distance(edge.point(mid)) < 1e-13);
    assert!(s.point(last).distance(edge.point(mid)) < 1e-13);
}

/// A great circle over a sphere's pole: the meridian up, a segment along the pole line, the
/// opposite meridian down; continuous, exact.
#[test]
fn a_meridian_through_a_pole_is_continuous() {
    let mut rng = Rng::new(104);
    for _ in 0..20 {
        let f = rng.frame(3.0);
        let big = rng.range(0.5, 3.0);
        let s = Surface::Sphere(Sphere::new(f, big).unwrap());
        let c = rng.range(0.0, TAU);
        let edge = circle(f.origin, rho(&f, c), f.z, big, 0.0, 1.0);
        let (t0, t1) = (rng.range(0.1, 1.4), rng.range(1.8, 3.0));
        for range in [(t0, t1), (t1, t0)] {
            let near = Some([c + 0.1, 0.0]);
            let p = pcurve(
                &s,
                &edge,
                Some(range),
                &PcurveOptions::DEFAULT.with_near(near),
            )
            .unwrap();
            assert_eq!(p.kind, PcurveKind::IsoLine, "{p:?}");
            assert_eq!(p.curves.len(), 3, "{p:?}");
            check_chain(&s, &edge, range, &p, 1e-12 * 10.0);
            let (a0, a1) = ends(&p.curves[0]);
            let (b0, b1) = ends(&p.curves[1]);
            let (c0, c1) = ends(&p.curves[2]);
            assert_eq!(a0[0], a1[0]);
            assert_eq!(c0[0], c1[0]);
            assert_eq!(
                (a1[1], b0[1], b1[1], c0[1]),
                (FRAC_PI_2, FRAC_PI_2, FRAC_PI_2, FRAC_PI_2)
            );
            assert!(((c0[0] - a0[0]).abs() - PI).abs() < 1e-12, "{a0:?} {c0:?}");
            let first = if range.0 < range.1 { c } else { c + PI };
            assert!(same(a0[0], first, Some(TAU), 1e-12), "{a0:?} vs {first}");
            assert!(p.deviation <= ISO_RELATIVE * 10.0);
        }
    }
}

/// The closed-form normal of a surface at `uv` (the numerical limit at poles).
fn normal(s: &Surface, uv: [f64; 2]) -> Point3 {
    s.normal(uv).unwrap()
}

/// A 3-D cubic B-spline through `S(g(s)) + offset N(g(s))` (least squares on `spans` spans of
/// uniform knots, `8 spans` samples): an edge near a known curve of the surface, `offset` off
/// it.
fn edge_near(s: &Surface, g: &dyn Fn(f64) -> [f64; 2], offset: f64, spans: usize) -> Curve<Point3> {
    let mut knots = vec![0.0; 4];
    knots.extend((1..spans).map(|i| i as f64 / spans as f64));
    knots.extend([1.0; 4]);
    let kv = KnotVector::new(knots.clone(), 3, spans + 3).unwrap();
    let n = 8 * spans;
    let data: Vec<(f64, [f64; 3])> = (0..=n)
        .map(|i| {
            let t = i as f64 / n as f64;
            let uv = g(t);
            let x = s.point(uv) + normal(s, uv) * offset;
            (t, [x.x, x.y, x.z])
        })
        .collect();
    let points = least_squares(&kv, &data).unwrap();
    Curve::BSpline(
        RationalBSpline::new(
            3,
            knots,
            points
                .iter()
                .map(|p| Point3::new(p[0], p[1], p[2]))
                .collect(),
            None,
        )
        .unwrap(),
    )
}

/// The largest `|S(pc(s)) - C(t(s))|` at `n` points of each fitted piece (all pieces on
/// `[0, 1]` over the edge's `range` here: one stretch).
fn dense_deviation(
    s: &Surface,
    edge: &Curve<Point3>,
    range: (f64, f64),
    pc: &NurbsCurve,
    n: usize,
) -> f64 {
    (0..=n)
        .map(|i| {
            let x = i as f64 / n as f64;
            let g = pc.point_at(x);
            s.point([g.x, g.y])
                .distance(edge.point(range.0 + x * (range.1 - range.0)))
        })
        .fold(0.0, f64::max)
}

/// A bicubic wavy B-spline patch on `[0, 1]^2`.
fn wavy_patch(rng: &mut Rng) -> BSplineSurface {
    let n = 6;
    let mut points = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (x, y) = (
                i as f64 / (n - 1) as f64 * 4.0,
                j as f64 / (n - 1) as f64 * 4.0,
            );
            points.push(Point3::new(x, y, rng.range(-0.8, 0.8)));
        }
    }
    let kv = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0], 3, n).unwrap();
    BSplineSurface::new([kv.clone(), kv], points, None).unwrap()
}

/// Fitted pcurves: the bound is at least the true deviation (checked at 20,000 points), at
/// most the tolerance when the edge is near enough the surface, and at least the edge's
/// distance from the surface; both directions; on a polynomial and a rational B-spline patch,
/// a sphere, a torus (rigorous) and an offset (estimated).
#[test]
fn fitted_bounds_hold_and_meet_the_tolerance() {
    let mut rng = Rng::new(105);
    let f = rng.frame(2.0);
    let g1 = |t: f64| [0.15 + 0.7 * t, 0.3 + 0.2 * (3.0 * t).sin() + 0.3 * t * t];
    let g_octant = |t: f64| [0.1 + 0.8 * t, 0.1 + 0.5 * t + 0.2 * (4.0 * t).sin()];
    let g_sphere = |t: f64| [0.3 + 2.0 * t, 0.2 + 0.6 * (2.0 * t).sin()];
    type Case<'a> = (&'a str, Surface, &'a dyn Fn(f64) -> [f64; 2], bool);
    let surfaces: Vec<Case<'_>> = vec![
        (
            "polynomial patch",
            Surface::BSpline(wavy_patch(&mut rng)),
            &g1,
            true,
        ),
        (
            "rational octant",
            Surface::BSpline(sphere_octant(2.0)),
            &g_octant,
            true,
        ),
        (
            "sphere",
            Surface::Sphere(Sphere::new(f, 1.5).unwrap()),
            &g_sphere,
            true,
        ),
        (
            "torus",
            Surface::Torus(Torus::new(f, 2.0, 0.6).unwrap()),
            &g_sphere,
            true,
        ),
        (
            "offset sphere",
            Surface::Offset(
                Offset::new(Surface::Sphere(Sphere::new(f, 1.5).unwrap()), 0.3).unwrap(),
            ),
            &g_sphere,
            false,
        ),
    ];
    for (name, s, g, rigorous) in surfaces {
        for (offset, tolerance) in [(0.0, 1e-5), (2e-4, 1e-3), (3e-3, 1e-3)] {
            let edge = edge_near(&s, g, offset, 64);
            for range in [(0.0, 1.0), (1.0, 0.0)] {
                let o = PcurveOptions::DEFAULT.with_tolerance(tolerance);
                let start = std::time::Instant::now();
                let p =
                    pcurve(&s, &edge, Some(range), &o).unwrap_or_else(|e| panic!("{name}: {e}"));
                let took = start.elapsed();
                assert_eq!(p.kind, PcurveKind::Fitted, "{name}");
                assert_eq!(p.curves.len(), 1, "{name}");
                assert_eq!(p.rigorous, rigorous, "{name}");
                let truth = dense_deviation(&s, &edge, range, &p.curves[0], 20_000);
                assert!(
                    truth <= p.deviation,
                    "{name}: true {truth:e} > bound {:e}",
                    p.deviation
                );
                // The edge's own distance from the surface (about `offset`) cannot be beaten.
                let off = (0..=200)
                    .map(|i| s.invert(edge.point(f64::from(i) / 200.0), None).distance)
                    .fold(0.0, f64::max);
                assert!(p.deviation >= off, "{name}: {:e} < {off:e}", p.deviation);
                if off < 0.5 * tolerance {
                    assert!(
                        p.deviation <= tolerance,
                        "{name} {offset}: {:e} > {tolerance:e}",
                        p.deviation
                    );
                } else {
                    // Refined only while the fit error exceeds a quarter of the edge's
                    // distance, with a gap term of another quarter: near that distance.
                    assert!(
                        p.deviation <= 1.5 * off + tolerance,
                        "{name}: {:e}",
                        p.deviation
                    );
                }
                check_chain(&s, &edge, range, &p, p.deviation);
                eprintln!(
                    "{name}: offset {offset:e} tol {tolerance:e}: bound {:.3e} true {truth:.3e}, {} control points, {took:?}",
                    p.deviation,
                    p.curves[0].control_points().len()
                );
            }
        }
    }
}

/// A small circle through a sphere's pole (not a meridian): fitted on both sides of the pole,
/// joined along the pole line; continuous and within the tolerance.
#[test]
fn a_small_circle_through_a_pole_is_fitted_on_both_sides() {
    let mut rng = Rng::new(106);
    for _ in 0..5 {
        let f = rng.frame(2.0);
        let big = rng.range(0.5, 2.0);
        let s = Surface::Sphere(Sphere::new(f, big).unwrap());
        let pole = f.origin + f.z * big;
        let alpha = rng.range(0.3, 1.2);
        let c = rng.range(0.0, TAU);
        let n = f.z * alpha.cos() + rho(&f, c) * alpha.sin();
        let center = f.origin + n * (big * alpha.cos());
        let e1 = (pole - center).normalized().unwrap();
        let edge = circle(center, e1, n.cross(e1), big * alpha.sin(), 0.0, 1.0);
        assert!(edge.point(0.0).distance(pole) < 1e-14 * 10.0);
        let o = PcurveOptions::DEFAULT.with_tolerance(1e-6);
        let p = pcurve(&s, &edge, Some((-1.0, 1.3)), &o).unwrap();
        assert_eq!(p.kind, PcurveKind::Fitted);
        assert_eq!(p.curves.len(), 3, "{p:?}");
        assert!(p.deviation <= 1e-6 && p.rigorous);
        check_chain(&s, &edge, (-1.0, 1.3), &p, 1e-12 * 10.0);
        let (_, a) = ends(&p.curves[0]);
        let (b0, b1) = ends(&p.curves[1]);
        assert_eq!((a[1], b0[1], b1[1]), (FRAC_PI_2, FRAC_PI_2, FRAC_PI_2));
        // The u of each side at the pole is the limit direction: the circle's tangent there.
        assert!(((b1[0] - b0[0]).abs() - PI).abs() < 1e-2, "{b0:?} {b1:?}");
        let window = (-1.0, 1.3);
        assert!(image_to_edge(&s, &edge, &p.curves, window, 400) <= p.deviation + 1e-13);
    }
}

#[test]
fn planes_keep_the_readers_conversions_bit_for_bit() {
    let mut rng = Rng::new(107);
    for _ in 0..10 {
        let f = rng.frame(3.0);
        let s = Surface::Plane(Plane::new(f));
        let map = PlaneCoordinates::new(&f);
        let r = rng.range(0.5, 2.0);
        let edges = [
            (
                circle(f.to_world(0.5, -0.2, 0.0), f.x, f.y, r, 0.3, -1.0),
                (rng.range(-1.0, 1.0), rng.range(2.0, 6.0)),
            ),
            (
                Curve::Line {
                    origin: f.to_world(1.0, 2.0, 0.0),
                    direction: f.x * 0.3 - f.y * 1.2,
                },
                (-0.4, 2.5),
            ),
            (
                Curve::BSpline(
                    RationalBSpline::new(
                        2,
                        vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0],
                        (0..4)
                            .map(|_| f.to_world(rng.range(-2.0, 2.0), rng.range(-2.0, 2.0), 0.0))
                            .collect(),
                        Some(vec![1.0, 0.7, 1.4, 1.0]),
                    )
                    .unwrap(),
                ),
                (0.1, 0.8),
            ),
        ];
        for (edge, (t0, t1)) in edges {
            let want = edge
                .to_bspline_mapped(&map, t0, t1)
                .unwrap()
                .to_planar()
                .unwrap();
            let p = pcurve(&s, &edge, Some((t0, t1)), &PcurveOptions::DEFAULT).unwrap();
            assert_eq!(p.kind, PcurveKind::Plane);
            assert!(p.rigorous && p.deviation < 1e-14 * 10.0, "{}", p.deviation);
            assert_eq!(p.curves, vec![want.clone()]);
            let back = pcurve(&s, &edge, Some((t1, t0)), &PcurveOptions::DEFAULT).unwrap();
            assert_eq!(back.curves, vec![want.reversed()]);
        }
    }
}

/// A plane reparameterised (swapped, scaled, shifted) or offset gives the same points in its
/// own `(u, v)`; an edge tilted off the plane reports its distance as the deviation (at least
/// the true one) and is refused beyond the limit.
#[test]
fn reparameterised_offset_and_tilted_planes() {
    let mut rng = Rng::new(108);
    let f = rng.frame(3.0);
    let plane = Surface::Plane(Plane::new(f));
    let reparam =
        Surface::Reparam(Reparam::new(plane.clone(), true, [2.0, -0.5], [0.3, 1.0]).unwrap());
    let offset = Surface::Offset(Offset::new(reparam.clone(), 0.7).unwrap());
    let edge = circle(f.to_world(0.2, 0.1, 0.0), f.x, f.y, 1.3, 0.0, 1.0);
    for s in [&reparam, &offset] {
        let d = if matches!(s, Surface::Offset(_)) {
            0.7
        } else {
            0.0
        };
        let n = s.normal([0.0, 0.0]).unwrap();
        let lifted = edge
            .map_affine(&Affine3 {
                m: [
                    [1.0, 0.0, 0.0, n.x * d],
                    [0.0, 1.0, 0.0, n.y * d],
                    [0.0, 0.0, 1.0, n.z * d],
                ],
            })
            .unwrap();
        let p = pcurve(s, &lifted, Some((0.5, 4.0)), &PcurveOptions::DEFAULT).unwrap();
        assert_eq!(p.kind, PcurveKind::Plane);
        assert!(p.deviation < 1e-13, "{}", p.deviation);
        for c in &p.curves {
            for i in 0..=20 {
                let q = c.point_at(f64::from(i) / 20.0 * c.param_range().1);
                let x = s.point([q.x, q.y]);
                let t = lifted.closest_parameter(x, Some((0.5, 4.0)));
                assert!(lifted.point(t).distance(x) < 1e-12);
            }
        }
    }
    // Tilted: the deviation bounds the true largest height and is refused past 100 x tol.
    let tilt = 1e-4;
    let tilted = Curve::Line {
        origin: f.origin,
        direction: f.x + f.z * tilt,
    };
    let o = PcurveOptions::DEFAULT.with_tolerance(1e-5);
    let p = pcurve(&plane, &tilted, Some((0.0, 2.0)), &o).unwrap();
    assert!(p.deviation >= 2.0 * tilt * (1.0 - 1e-12) && p.deviation <= 2.0 * tilt * (1.0 + 1e-9));
    let o = PcurveOptions::DEFAULT.with_tolerance(1e-7);
    match pcurve(&plane, &tilted, Some((0.0, 2.0)), &o) {
        Err(GeomError::EdgeOffSurface {
            distance,
            parameter,
            ..
        }) => {
            assert!((distance - 2.0 * tilt).abs() < 1e-12 && parameter == 2.0);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn errors_are_typed() {
    let s = Surface::Cylinder(Cylinder::new(Frame::WORLD, 1.0).unwrap());
    let line = Curve::Line {
        origin: Point3::new(3.0, 0.0, 0.0),
        direction: Point3::Z,
    };
    let o = PcurveOptions::DEFAULT;
    assert!(matches!(
        pcurve(&s, &line, None, &o),
        Err(GeomError::UnboundedEdge)
    ));
    assert!(matches!(
        pcurve(&s, &line, Some((0.0, f64::INFINITY)), &o),
        Err(GeomError::UnboundedEdge)
    ));
    assert!(matches!(
        pcurve(&s, &line, Some((1.0, 1.0)), &o),
        Err(GeomError::EmptyInterval { .. })
    ));
    assert!(matches!(
        pcurve(&s, &line, Some((0.0, 1.0)), &o.with_tolerance(-1.0)),
        Err(GeomError::NotFinite { .. })
    ));
    // Two units off the cylinder: refused, naming the distance and a parameter.
    match pcurve(&s, &line, Some((0.0, 1.0)), &o.with_tolerance(1e-3)) {
        Err(
            e @ GeomError::EdgeOffSurface {
                distance,
                parameter,
                ..
            },
        ) => {
            assert!((distance - 2.0).abs() < 1e-12 && parameter == 0.0, "{e}");
            assert!(e.to_string().contains("cylinder"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    // A full cylinder as a B-spline patch not known to be closed: a circle across its seam
    // has no continuous pcurve.
    let f = Frame::WORLD;
    let quarter = quarter_cylinder(&f, 1.0, 1.0);
    let mut points = Vec::new();
    let mut weights = Vec::new();
    let w = FRAC_1_SQRT_2;
    let ring = [
        (1.0, 0.0, 1.0),
        (1.0, 1.0, w),
        (0.0, 1.0, 1.0),
        (-1.0, 1.0, w),
        (-1.0, 0.0, 1.0),
        (-1.0, -1.0, w),
        (0.0, -1.0, 1.0),
        (1.0, -1.0, w),
        (1.0, 0.0, 1.0),
    ];
    for &(x, y, wi) in &ring {
        for z in [0.0, 1.0] {
            points.push(Point3::new(x, y, z));
            weights.push(wi);
        }
    }
    drop(quarter);
    let ku = KnotVector::new(
        vec![
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
        ],
        2,
        9,
    )
    .unwrap();
    let full = BSplineSurface::new([ku, KnotVector::bezier(1)], points, Some(weights))
        .unwrap()
        .with_closed([Some(false), Some(false)]);
    let s = Surface::BSpline(full);
    let c = circle(
        Point3::new(0.0, 0.0, 0.5),
        Point3::X,
        Point3::Y,
        1.0,
        0.0,
        1.0,
    );
    // An arc across the seam at angle 0: a jump from u = 1 to u = 0.
    match pcurve(&s, &c, Some((-0.5, 0.5)), &o) {
        Err(e @ GeomError::PcurveWorkLimit { parameter, .. }) => {
            assert!(parameter.abs() < 1e-6, "{e}");
        }
        other => panic!("{other:?}"),
    }
    // The same arc on one side of the seam is an iso-line.
    let p = pcurve(&s, &c, Some((0.1, 3.0)), &o).unwrap();
    assert_eq!(p.kind, PcurveKind::IsoLine);
}

#[test]
fn domain_pieces_split_closed_curves_at_their_seam() {
    let b = Curve::BSpline(
        RationalBSpline::new(
            1,
            vec![0.0, 0.0, 1.0, 2.0, 3.0, 3.0],
            vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(0.0, 1.0, 0.0),
                Point3::new(0.0, 0.0, 0.0),
            ],
            None,
        )
        .unwrap(),
    );
    assert_eq!(b.period(), Some(3.0));
    assert_eq!(domain_pieces(&b, 0.5, 2.5), vec![(0.5, 2.5)]);
    assert_eq!(domain_pieces(&b, 2.0, 4.0), vec![(2.0, 3.0), (0.0, 1.0)]);
    assert_eq!(domain_pieces(&b, 5.0, 5.5), vec![(2.0, 2.5)]);
    let line = Curve::Line {
        origin: Point3::ORIGIN,
        direction: Point3::X,
    };
    assert_eq!(domain_pieces(&line, -4.0, 9.0), vec![(-4.0, 9.0)]);
}

/// Edges ending at a pole: a meridian of a sphere and of a rational B-spline octant (whose
/// pole is its column `v = 1`) from the equator up, and a ruling of a cone down to its apex:
/// iso-lines whose end at the pole keeps the line's free parameter.
#[test]
fn iso_lines_ending_at_poles_keep_their_parameter() {
    let mut rng = Rng::new(110);
    for _ in 0..10 {
        let f = rng.frame(3.0);
        let r = rng.range(0.5, 3.0);
        let c = rng.range(0.1, 1.4);
        let sphere = Surface::Sphere(Sphere::new(f, r).unwrap());
        let meridian = circle(f.origin, rho(&f, c), f.z, r, 0.0, 1.0);
        let octant_frame = Frame::WORLD;
        let octant = Surface::BSpline(sphere_octant(r));
        let octant_meridian = circle(
            Point3::ORIGIN,
            rho(&octant_frame, c),
            Point3::Z,
            r,
            0.0,
            1.0,
        );
        let (a, t) = (rng.range(0.2, 1.2), rng.range(0.5, 2.0));
        let cone = Surface::Cone(Cone::new(f, r, a).unwrap());
        let apex = cone.point([0.0, -r / a.tan()]);
        let ruling = Curve::Line {
            origin: cone.point([c, t]),
            direction: apex - cone.point([c, t]),
        };
        for (s, edge, range, top) in [
            (&sphere, &meridian, (0.3, FRAC_PI_2), FRAC_PI_2),
            (&octant, &octant_meridian, (0.0, FRAC_PI_2), 1.0),
            (&cone, &ruling, (0.0, 1.0), -r / a.tan()),
        ] {
            for range in [range, (range.1, range.0)] {
                let p = pcurve(s, edge, Some(range), &PcurveOptions::DEFAULT).unwrap();
                assert_eq!(p.kind, PcurveKind::IsoLine, "{}", s.kind_name());
                assert_eq!(p.curves.len(), 1);
                let (x, y) = ends(&p.curves[0]);
                assert_eq!(x[0], y[0], "{}: {x:?} {y:?}", s.kind_name());
                let at_pole = if range.0 < range.1 { y } else { x };
                assert!(
                    (at_pole[1] - top).abs() < 1e-12,
                    "{}: {at_pole:?}",
                    s.kind_name()
                );
                check_chain(s, edge, range, &p, 1e-11 * 10.0);
            }
        }
    }
}

/// Fitted edges across the seams of periodic surfaces: a helix-like curve across `u = 0` of a
/// cylinder and a curve across both seams of a torus give continuous pcurves running past the
/// period's end (no jump of 2 pi), within the tolerance.
#[test]
fn fitted_edges_cross_seams_continuously() {
    let mut rng = Rng::new(111);
    for _ in 0..5 {
        let f = rng.frame(2.0);
        let cylinder = Surface::Cylinder(Cylinder::new(f, rng.range(0.5, 2.0)).unwrap());
        let torus = Surface::Torus(Torus::new(f, 2.0, 0.7).unwrap());
        let helix = |t: f64| [-1.0 + 2.5 * t, 0.3 + t + 0.2 * (5.0 * t).sin()];
        let knot = |t: f64| [-1.0 + 2.5 * t, -1.5 + 3.0 * t];
        for (s, g) in [
            (&cylinder, &helix as &dyn Fn(f64) -> [f64; 2]),
            (&torus, &knot as &dyn Fn(f64) -> [f64; 2]),
        ] {
            let edge = edge_near(s, g, 0.0, 64);
            let o = PcurveOptions::DEFAULT
                .with_tolerance(1e-5)
                .with_near(Some(g(0.0)));
            let p = pcurve(s, &edge, Some((0.0, 1.0)), &o).unwrap();
            assert_eq!(p.kind, PcurveKind::Fitted);
            assert!(p.deviation <= 1e-5, "{}", p.deviation);
            let (a, b) = ends(&p.curves[0]);
            let (ga, gb) = (g(0.0), g(1.0));
            for i in 0..2 {
                if s.periods()[i].is_some() {
                    assert!(
                        (a[i] - ga[i]).abs() < 1e-6 && (b[i] - gb[i]).abs() < 1e-6,
                        "{a:?} {b:?}"
                    );
                }
            }
            let truth = dense_deviation(s, &edge, (0.0, 1.0), &p.curves[0], 20_000);
            assert!(truth <= p.deviation);
        }
    }
}

/// A tolerance the edge cannot meet (zero, with the edge about 2e-6 off its surface): the work
/// stays bounded and the fit stops refining once its error is small against the edge's own
/// distance.
#[test]
fn an_unreachable_tolerance_stops_at_the_edges_distance() {
    let mut rng = Rng::new(105);
    let g = |t: f64| [0.15 + 0.7 * t, 0.3 + 0.2 * (3.0 * t).sin() + 0.3 * t * t];
    let s = Surface::BSpline(wavy_patch(&mut rng));
    let edge = edge_near(&s, &g, 0.0, 64);
    let off = (0..=400)
        .map(|i| s.invert(edge.point(f64::from(i) / 400.0), None).distance)
        .fold(0.0, f64::max);
    let start = std::time::Instant::now();
    let o = PcurveOptions::DEFAULT.with_tolerance(0.0);
    let p = pcurve(&s, &edge, Some((0.0, 1.0)), &o).unwrap();
    assert!(start.elapsed().as_secs() < 30);
    assert!(
        p.deviation >= off && p.deviation <= 1.5 * off,
        "{} vs {off:e}",
        p.deviation
    );
    assert!(p.curves[0].control_points().len() <= fit::MAX_CONTROL_POINTS);
    let truth = dense_deviation(&s, &edge, (0.0, 1.0), &p.curves[0], 20_000);
    assert!(truth <= p.deviation);
}

/// An edge leaving a pole where the previous edge of its loop ended (`near`) starts with a
/// segment along the pole line from `near`: the loop runs on without a gap.
#[test]
fn an_edge_leaving_a_pole_starts_at_near() {
    let mut rng = Rng::new(112);
    for _ in 0..10 {
        let f = rng.frame(3.0);
        let r = rng.range(0.5, 3.0);
        let s = Surface::Sphere(Sphere::new(f, r).unwrap());
        let c = rng.range(0.0, TAU);
        let meridian = circle(f.origin, rho(&f, c), f.z, r, 0.0, 1.0);
        for k in [-1.0, 0.0, 1.0, 2.0] {
            let near = [c + 0.7 + k * TAU, FRAC_PI_2];
            let o = PcurveOptions::DEFAULT.with_near(Some(near));
            let p = pcurve(&s, &meridian, Some((FRAC_PI_2, 0.2)), &o).unwrap();
            assert_eq!(p.kind, PcurveKind::IsoLine);
            assert_eq!(p.curves.len(), 2, "{p:?}");
            let (a, b) = ends(&p.curves[0]);
            assert_eq!(a, near);
            assert!(
                (b[0] - (c + k * TAU)).abs() < 1e-12 && b[1] == FRAC_PI_2,
                "{b:?}"
            );
            check_chain(&s, &meridian, (FRAC_PI_2, 0.2), &p, 1e-11 * 10.0);
            assert!(p.deviation < 1e-11 * 10.0);
        }
        // Without near, or near elsewhere: no segment.
        for near in [None, Some([c, 0.5])] {
            let o = PcurveOptions::DEFAULT.with_near(near);
            let p = pcurve(&s, &meridian, Some((FRAC_PI_2, 0.2)), &o).unwrap();
            assert_eq!(p.curves.len(), 1);
        }
    }
}
