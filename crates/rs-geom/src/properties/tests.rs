//! Closed forms: a sphere, a tilted torus and a closed cylinder (three faces), each a solid
//! built from its surfaces and `(u, v)` loops; an open shell; a face turned inside out.

use std::f64::consts::{PI, TAU};

use rs_spline::{NurbsCurve, Point, circle, polyline};

use super::*;
use crate::brep::{Face, Shell, Solid};
use crate::surface::{Cone, Cylinder, Plane, Sphere, Torus};
use crate::{Frame, Tolerance};

/// A face of `surface` bounded by `loops`, outward along `S_u x S_v` when `same_sense`.
fn face(surface: Surface, loops: Vec<Vec<NurbsCurve>>, same_sense: bool) -> Face {
    Face {
        entity: "#1".into(),
        surface_name: surface.kind_name().into(),
        surface: Some(surface),
        surface_error: None,
        same_sense,
        loops: Ok(loops),
        edges: Vec::new(),
        pcurve_deviation: None,
        natural_bounds: false,
    }
}

/// The rectangle `[u0, u1] x [v0, v1]` as one loop.
fn rectangle(u0: f64, u1: f64, v0: f64, v1: f64) -> Vec<NurbsCurve> {
    let p = [(u0, v0), (u1, v0), (u1, v1), (u0, v1), (u0, v0)].map(|(u, v)| Point::new(u, v));
    vec![polyline(&p).unwrap()]
}

/// One solid of `faces` in one shell (closed unless `open`).
fn solid(faces: Vec<Face>, open: bool) -> Model {
    let n = faces.len();
    Model {
        faces,
        shells: vec![Shell {
            entity: "#2".into(),
            faces: (0..n).collect(),
            closed: !open,
        }],
        solids: vec![Solid {
            entity: "#3".into(),
            shells: vec![0],
        }],
        tolerance: Tolerance::new(None).unwrap(),
        length_unit: None,
    }
}

fn close(got: f64, want: f64, what: &str) {
    assert!(
        (got - want).abs() <= 1e-12 * want.abs().max(1.0),
        "{what}: {got} vs {want} ({:e} relative)",
        (got - want).abs() / want.abs()
    );
}

/// The frame at `origin` with the axis tilted off every coordinate axis.
fn tilted(origin: Point3) -> Frame {
    Frame::new(
        origin,
        Some(Point3::new(1.0, 2.0, 2.0)),
        Some(Point3::new(2.0, -1.0, 0.5)),
    )
    .unwrap()
}

/// The inertia tensor `a I + b (axis axis^T)` for a unit `axis`: moments `a + b` about the
/// axis and `a` across it.
fn axial_inertia(axis: Point3, across: f64, about: f64) -> [[f64; 3]; 3] {
    let d = [axis.x, axis.y, axis.z];
    std::array::from_fn(|i| {
        std::array::from_fn(|j| {
            let delta = if i == j { across } else { 0.0 };
            delta + (about - across) * d[i] * d[j]
        })
    })
}

fn close_matrix(got: &[[f64; 3]; 3], want: &[[f64; 3]; 3], scale: f64, what: &str) {
    for i in 0..3 {
        for j in 0..3 {
            assert!(
                (got[i][j] - want[i][j]).abs() <= 1e-12 * scale,
                "{what}[{i}][{j}]: {} vs {}",
                got[i][j],
                want[i][j]
            );
        }
    }
}

/// The ball of radius `r` about `c` (a tilted frame): one spherical face on its natural box.
fn sphere_solid(r: f64, c: Point3) -> Model {
    let sphere = Surface::Sphere(Sphere::new(tilted(c), r).unwrap());
    let natural = vec![rectangle(0.0, TAU, -PI / 2.0, PI / 2.0)];
    solid(vec![face(sphere, natural, true)], false)
}

#[test]
fn a_sphere_its_volume_area_centroid_and_inertia() {
    let (r, c) = (2.0, Point3::new(1.0, 2.0, 3.0));
    let m = sphere_solid(r, c);
    let s = m.solid_properties(0).unwrap();
    let volume = 4.0 / 3.0 * PI * r * r * r;
    close(s.volume, volume, "volume");
    close(s.area, 4.0 * PI * r * r, "area");
    assert!((s.centroid - c).length() <= 1e-12 * r, "{:?}", s.centroid);
    let i = 0.4 * volume * r * r;
    close_matrix(&s.inertia, &axial_inertia(Point3::Z, i, i), i, "inertia");
    for m in s.principal_moments {
        close(m, i, "principal moment");
    }
    assert!(s.converged);
    // The face alone: its area and centroid (the centre: the sphere is symmetric).
    let f = m.face_properties(0).unwrap();
    close(f.area, 4.0 * PI * r * r, "face area");
    assert!((f.centroid - c).length() <= 1e-12 * r);
    // Second moments of a spherical shell: (area r^2 / 3) about every axis through its centre.
    let k = f.area * r * r / 3.0;
    close_matrix(
        &f.second_moments,
        &axial_inertia(Point3::Z, k, k),
        k,
        "second moments",
    );
}

#[test]
fn a_tilted_torus() {
    let (big, small, c) = (3.0, 1.0, Point3::new(0.5, -1.0, 2.0));
    let frame = tilted(c);
    let torus = Surface::Torus(Torus::new(frame, big, small).unwrap());
    let m = solid(
        vec![face(torus, vec![rectangle(0.0, TAU, 0.0, TAU)], true)],
        false,
    );
    let s = m.solid_properties(0).unwrap();
    let volume = 2.0 * PI * PI * big * small * small;
    close(s.volume, volume, "volume");
    close(s.area, 4.0 * PI * PI * big * small, "area");
    assert!((s.centroid - c).length() <= 1e-12 * big, "{:?}", s.centroid);
    // About the axis M (R^2 + 3/4 r^2), across it M (R^2 / 2 + 5/8 r^2).
    let about = volume * (big * big + 0.75 * small * small);
    let across = volume * (0.5 * big * big + 0.625 * small * small);
    close_matrix(
        &s.inertia,
        &axial_inertia(frame.z, across, about),
        about,
        "inertia",
    );
    close(s.principal_moments[2], about, "largest principal moment");
    let axis = s.principal_axes[2];
    close(
        axis.dot(frame.z).abs(),
        1.0,
        "principal axis along the torus's axis",
    );
}

/// A cylinder of radius `r` from `z = 0` to `z = h` about a tilted axis: its side and two caps
/// (the bottom one facing against its plane's normal).
fn closed_cylinder(r: f64, h: f64, origin: Point3) -> Model {
    let frame = tilted(origin);
    let top = Frame::new(origin + frame.z * h, Some(frame.z), Some(frame.x)).unwrap();
    let disc = || vec![vec![circle(Point::new(0.0, 0.0), r).unwrap()]];
    solid(
        vec![
            face(
                Surface::Cylinder(Cylinder::new(frame, r).unwrap()),
                vec![rectangle(0.0, TAU, 0.0, h)],
                true,
            ),
            face(Surface::Plane(Plane::new(frame)), disc(), false),
            face(Surface::Plane(Plane::new(top)), disc(), true),
        ],
        false,
    )
}

#[test]
fn a_closed_cylinder() {
    let (r, h, o) = (1.5, 4.0, Point3::new(-2.0, 1.0, 0.25));
    let m = closed_cylinder(r, h, o);
    let s = m.solid_properties(0).unwrap();
    let volume = PI * r * r * h;
    close(s.volume, volume, "volume");
    close(s.area, TAU * r * h + 2.0 * PI * r * r, "area");
    let axis = tilted(o).z;
    assert!((s.centroid - (o + axis * (h / 2.0))).length() <= 1e-12 * h);
    let about = volume * r * r / 2.0;
    let across = volume * (3.0 * r * r + h * h) / 12.0;
    close_matrix(
        &s.inertia,
        &axial_inertia(axis, across, about),
        across,
        "inertia",
    );
    // Every property of the whole model at once agrees.
    let all = m.properties();
    assert_eq!(all.faces.len(), 3);
    assert_eq!(all.solids[0].as_ref().unwrap(), &s);
}

/// A cone face over both nappes, `v` in `[-1, 2]` about its apex at `v = 0`: its area element
/// `|v| tan a / cos a` is linear on each side, exact only when the rule is split at the apex
/// (the cone's knot line). Area `5 pi tan a / cos a`, centroid on the axis at
/// `int v |v| / int |v| = 14 / 15`.
#[test]
fn a_cone_face_across_its_apex() {
    let a: f64 = 0.4;
    let frame = tilted(Point3::new(0.5, -1.0, 2.0));
    let cone = Surface::Cone(Cone::new(frame, 0.0, a).unwrap());
    assert_eq!(cone.knot_lines()[1], vec![0.0]);
    let m = solid(
        vec![face(cone, vec![rectangle(0.0, TAU, -1.0, 2.0)], true)],
        true,
    );
    let f = m.face_properties(0).unwrap();
    close(f.area, 5.0 * PI * a.tan() / a.cos(), "area");
    let want = frame.origin + frame.z * (14.0 / 15.0);
    assert!((f.centroid - want).length() <= 1e-12, "{:?}", f.centroid);
    assert!(f.converged && f.error <= 1e-12, "{f:?}");
}

/// A watertight boundary has no leak; a cap that misses the wall by a ring (its disc of
/// radius `0.9 r`) leaks the ring's area, `pi (r^2 - (0.9 r)^2)`, along the axis.
#[test]
fn a_gap_in_the_boundary_is_its_leak_area() {
    let (r, h) = (1.5, 4.0);
    let mut m = closed_cylinder(r, h, Point3::new(3.0, -2.0, 1.0));
    let s = m.solid_properties(0).unwrap();
    assert!(s.leak_area <= 1e-13 * r * r, "{}", s.leak_area);
    m.faces[2].loops = Ok(vec![vec![circle(Point::new(0.0, 0.0), 0.9 * r).unwrap()]]);
    let s = m.solid_properties(0).unwrap();
    close(s.leak_area, PI * r * r * (1.0 - 0.81), "leak area");
}

/// Faces turned against their surfaces' normals give the negative volume (the senses are
/// honoured, not guessed), and the same area.
#[test]
fn senses_are_honoured() {
    let mut m = closed_cylinder(1.0, 2.0, Point3::new(0.0, 0.0, 0.0));
    for f in &mut m.faces {
        f.same_sense = !f.same_sense;
    }
    let s = m.solid_properties(0).unwrap();
    close(s.volume, -2.0 * PI, "volume");
    close(s.area, 4.0 * PI + 2.0 * PI, "area");
}

#[test]
fn an_open_shell_has_no_volume() {
    let mut m = closed_cylinder(1.0, 2.0, Point3::new(0.0, 0.0, 0.0));
    m.shells[0].closed = false;
    m.shells[0].faces.pop();
    let e = m.solid_properties(0).unwrap_err();
    assert!(matches!(e, PropertiesError::OpenShell { .. }), "{e}");
    assert!(e.to_string().contains("is open"), "{e}");
    // Its faces still have areas.
    close(m.face_properties(1).unwrap().area, PI, "cap area");
    assert!(matches!(
        m.solid_properties(1),
        Err(PropertiesError::Model(ModelError::NoSolid { .. }))
    ));
}

/// A bicubic polynomial patch over `[0, 1]^2` with knots at `interior` in both parameters
/// (control points on a bumpy height field).
fn bumpy_patch(interior: &[f64]) -> Surface {
    use rs_spline::KnotVector;
    let mut knots = vec![0.0; 4];
    knots.extend_from_slice(interior);
    knots.extend([1.0; 4]);
    let n = 4 + interior.len();
    let kv = KnotVector::new(knots, 3, n).unwrap();
    let points = (0..n * n)
        .map(|k| {
            let (i, j) = ((k / n) as f64, (k % n) as f64);
            Point3::new(
                3.0 * i / (n - 1) as f64,
                2.0 * j / (n - 1) as f64,
                (i * 1.3).sin() * (j * 0.7).cos(),
            )
        })
        .collect();
    Surface::BSpline(crate::surface::BSplineSurface::new([kv.clone(), kv], points, None).unwrap())
}

/// `|S_u x S_v|` at `uv`.
fn area_element(s: &Surface, uv: [f64; 2]) -> f64 {
    let d = s.derivatives(uv);
    d.du.cross(d.dv).length()
}

/// A polynomial B-spline face trimmed to a disc: its area against an independent rule, Gauss-
/// Legendre in polar coordinates about the disc's centre (96 x 96 nodes; the area element is
/// analytic there).
#[test]
fn a_polynomial_patch_trimmed_to_a_disc() {
    let s = bumpy_patch(&[]);
    let (c, r) = (Point::new(0.45, 0.55), 0.3);
    let m = solid(
        vec![face(s.clone(), vec![vec![circle(c, r).unwrap()]], true)],
        true,
    );
    let got = m.face_properties(0).unwrap().area;
    let rule = rs_spline::quadrature::gauss_rule(96).unwrap();
    let (h_theta, thetas) = rule.on(0.0, TAU);
    let thetas: Vec<(f64, f64)> = thetas.collect();
    let (h_rho, rhos) = rule.on(0.0, r);
    let rhos: Vec<(f64, f64)> = rhos.collect();
    let mut want = 0.0;
    for &(t, wt) in &thetas {
        for &(p, wp) in &rhos {
            let uv = [c.x + p * t.cos(), c.y + p * t.sin()];
            want += wt * wp * p * area_element(&s, uv);
        }
    }
    want *= h_theta * h_rho;
    close(got, want, "area of the trimmed patch");
}

/// A patch with interior knots, on a rectangle the knot lines cross: its area against tensor
/// Gauss-Legendre split at the knots (the area element is smooth within each span).
#[test]
fn a_patch_with_knots_on_a_rectangle() {
    let knots = [0.3, 0.5, 0.8];
    let s = bumpy_patch(&knots);
    let (u0, u1, v0, v1) = (0.1, 0.9, 0.2, 0.95);
    let m = solid(
        vec![face(s.clone(), vec![rectangle(u0, u1, v0, v1)], true)],
        true,
    );
    let got = m.face_properties(0).unwrap().area;
    let rule = rs_spline::quadrature::gauss_rule(48).unwrap();
    let spans = |a: f64, b: f64| {
        let mut cuts = vec![a];
        cuts.extend(knots.iter().copied().filter(|&k| a < k && k < b));
        cuts.push(b);
        cuts.windows(2).map(|w| (w[0], w[1])).collect::<Vec<_>>()
    };
    let mut want = 0.0;
    for (ua, ub) in spans(u0, u1) {
        let (hu, us) = rule.on(ua, ub);
        let us: Vec<(f64, f64)> = us.collect();
        for (va, vb) in spans(v0, v1) {
            let (hv, vs) = rule.on(va, vb);
            let vs: Vec<(f64, f64)> = vs.collect();
            let mut sum = 0.0;
            for &(u, wu) in &us {
                for &(v, wv) in &vs {
                    sum += wu * wv * area_element(&s, [u, v]);
                }
            }
            want += hu * hv * sum;
        }
    }
    close(got, want, "area of the patch");
}

/// `int z^2 dA` over a sphere about `c`: `4 pi r^2 c_z^2 + r^2 (4 pi r^2 / 3)`; a function
/// that is not finite on the face is an error naming a point.
#[test]
fn a_surface_integral_over_a_sphere() {
    let (r, c) = (2.0, Point3::new(1.0, 2.0, 3.0));
    let m = sphere_solid(r, c);
    let got = m.surface_integral(0, &|p| p.z * p.z).unwrap();
    let area = 4.0 * PI * r * r;
    close(
        got.value,
        area * c.z * c.z + r * r * area / 3.0,
        "int z^2 dA",
    );
    assert!(got.converged);
    close(
        m.surface_integral(0, &|_| 1.0).unwrap().value,
        area,
        "int 1 dA",
    );
    let e = m.surface_integral(0, &|p| (p.z - c.z).sqrt()).unwrap_err();
    assert!(
        matches!(e, PropertiesError::FunctionNotFinite { .. })
            || e.to_string().contains("not finite"),
        "{e}"
    );
}
