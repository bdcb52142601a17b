//! Point in a solid: `inrs classify --domain part.step#solid:K` and the library's
//! `SolidClassifier` against closed forms (a box with a spherical void, a frustum minus a
//! ball), on random points and on points chosen so that rays meet edges, vertices, poles and
//! the planes of faces; points off faces at 1e-2..1e-8 of the size get their side or
//! `boundary`; open shells, flipped faces and points files of the wrong width are one-line
//! errors.

#[allow(dead_code)]
mod common;
use common::{fixture, inrs, inrs_ok, scratch};

use inrs::geom::Point3;
use inrs::geom::solid::{Locate, Location, PointQuery, SolidClassifier};
use inrs::io::cad::CadModel;

/// A small deterministic generator in `[0, 1)`.
fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The box `[-2, 2]^3` minus the closed unit ball: `Some(inside)` farther than `margin` from
/// its boundary, `None` nearer.
fn box_void_truth(p: Point3, margin: f64) -> Option<bool> {
    let cube = 2.0 - p.x.abs().max(p.y.abs()).max(p.z.abs()); // > 0 inside the cube
    let ball = p.length() - 1.0; // > 0 outside the ball
    if cube.abs() <= margin || ball.abs() <= margin {
        return None;
    }
    Some(cube > 0.0 && ball > 0.0)
}

/// The frustum of radii 2 (z = 0) and 0.5 (z = 3) minus the ball of radius 1.2 about
/// (0, 0, 3), as `box_void_truth` (distances to the cone measured along the radius, scaled).
fn cone_truth(p: Point3, margin: f64) -> Option<bool> {
    let r = p.x.hypot(p.y);
    let side = (2.0 - 0.5 * p.z - r) / (1.0f64 + 0.25).sqrt(); // distance to the cone's line
    let bottom = p.z;
    let ball = (p - Point3::new(0.0, 0.0, 3.0)).length() - 1.2;
    let top = 3.0 - p.z;
    let inside = side > 0.0 && bottom > 0.0 && ball > 0.0 && top > 0.0;
    let near = [side, bottom, ball].iter().any(|d| d.abs() <= margin);
    if near { None } else { Some(inside) }
}

fn classifier(rel: &str) -> SolidClassifier {
    let model = CadModel::read(fixture(rel)).unwrap();
    SolidClassifier::new(&model, 0).unwrap()
}

#[test]
fn random_points_agree_with_the_closed_forms() {
    for (rel, truth, lo, hi) in [
        (
            "cad/box_void.step",
            box_void_truth as fn(Point3, f64) -> Option<bool>,
            -2.5,
            2.5,
        ),
        ("cad/cone_minus_sphere.step", cone_truth, -2.5, 3.5),
    ] {
        let c = classifier(rel);
        let mut next = uniform(99);
        let points: Vec<Point3> = (0..20_000)
            .map(|_| {
                let mut f = || lo + (hi - lo) * next();
                Point3::new(f(), f(), f())
            })
            .collect();
        let mut got = vec![Location::Outside; points.len()];
        c.par_values_into(&points[..], &mut got);
        let mut checked = 0;
        for (p, l) in points.iter().zip(&got) {
            assert_eq!(*l, c.locate(*p), "parallel and one by one differ at {p:?}");
            if let Some(inside) = truth(*p, 1e-9) {
                let want = if inside {
                    Location::Inside
                } else {
                    Location::Outside
                };
                assert_eq!(*l, want, "{rel} at {p:?}");
                checked += 1;
            }
        }
        assert!(checked > 19_900, "{checked}");
    }
}

/// Points whose rays (or segments) run through edges, vertices, the sphere's poles and the
/// planes of faces: grid-aligned coordinates equal to the box's faces and vertices, the axes,
/// the void's centre.
#[test]
fn points_on_axes_and_in_face_planes_get_their_side() {
    let c = classifier("cad/box_void.step");
    let values = [
        -3.0, -2.5, -2.0, -1.5, -1.0, -0.5, 0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0,
    ];
    let mut boundary = 0;
    for &x in &values {
        for &y in &values {
            for &z in &values {
                let p = Point3::new(x, y, z);
                let got = c.locate(p);
                match box_void_truth(p, 1e-12) {
                    Some(true) => assert_eq!(got, Location::Inside, "{p:?}"),
                    Some(false) => assert_eq!(got, Location::Outside, "{p:?}"),
                    None => {
                        assert_eq!(got, Location::Boundary, "{p:?}");
                        boundary += 1;
                    }
                }
            }
        }
    }
    assert!(boundary > 0);
    let cone = classifier("cad/cone_minus_sphere.step");
    // The axis: through the sphere's pole (z = 1.8) and the bottom plane's centre.
    for z in [-1.0, 0.5, 1.0, 1.7, 1.9, 2.5, 3.5, 5.0] {
        let p = Point3::new(0.0, 0.0, z);
        let want = if z > 0.0 && z < 1.8 {
            Location::Inside
        } else {
            Location::Outside
        };
        assert_eq!(cone.locate(p), want, "{p:?}");
    }
    assert_eq!(cone.locate(Point3::new(0.0, 0.0, 1.8)), Location::Boundary);
    assert_eq!(cone.locate(Point3::new(0.0, 0.0, 0.0)), Location::Boundary);
}

/// Off faces, edges and vertices by 1e-2 .. 1e-8 of the size along the outward direction:
/// the right side or `boundary`, never the wrong side; at 1e-2 and 1e-4, the right side.
#[test]
fn points_near_faces_edges_and_vertices_never_get_the_wrong_side() {
    let c = classifier("cad/box_void.step");
    let size = (c.bounds().1 - c.bounds().0).length();
    let mut next = uniform(5);
    // (a point on the boundary, its outward direction from the solid)
    let mut cases: Vec<(Point3, Point3)> = Vec::new();
    for _ in 0..200 {
        // Away from the other faces by more than the largest offset (0.07).
        let (a, b) = (3.6 * next() - 1.8, 3.6 * next() - 1.8);
        cases.push((Point3::new(2.0, a, b), Point3::new(1.0, 0.0, 0.0)));
        cases.push((Point3::new(a, -2.0, b), Point3::new(0.0, -1.0, 0.0)));
        let d = Point3::new(next() - 0.5, next() - 0.5, next() - 0.5)
            .normalized()
            .unwrap();
        // The void: outward from the solid is into the ball.
        cases.push((d, -d));
        // An edge of the cube and a vertex, outward along the bisectors.
        let t = 3.6 * next() - 1.8;
        cases.push((
            Point3::new(2.0, 2.0, t),
            Point3::new(1.0, 1.0, 0.0).normalized().unwrap(),
        ));
    }
    for s in [-2.0, 2.0] {
        cases.push((
            Point3::new(s, s, s),
            Point3::new(s, s, s).normalized().unwrap(),
        ));
    }
    for (on, out) in cases {
        for rel in [1e-2, 1e-4, 1e-6, 1e-8] {
            let d = rel * size;
            for (p, want) in [
                (on + out * d, Location::Outside),
                (on - out * d, Location::Inside),
            ] {
                let got = c.locate(p);
                if rel >= 1e-4 {
                    assert_eq!(got, want, "{p:?} at {rel}");
                } else {
                    assert!(
                        got == want || got == Location::Boundary,
                        "{p:?} at {rel}: {got:?}"
                    );
                }
            }
        }
        assert_eq!(c.locate(on), Location::Boundary, "{on:?}");
    }
}

#[test]
fn the_cli_classifies_points_of_space_as_the_library_does() {
    let dir = scratch("classify", "solid");
    let csv = dir.join("p.csv");
    std::fs::write(&csv, "x,y,z\n0,0,0\n1.5,0,0\n2,0,0\n3,0,0\n# end\n").unwrap();
    let spec = format!("{}#solid:0", fixture("cad/box_void.step"));
    let text = inrs_ok(&[
        "classify",
        "--domain",
        &spec,
        "--points",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(
        text,
        "x,y,z,location\n0,0,0,outside\n1.5,0,0,inside\n2,0,0,boundary\n3,0,0,outside\n"
    );
    // The whole file: a column per solid.
    let file = fixture("cad/box_void.step");
    let text = inrs_ok(&[
        "classify",
        "--domain",
        &file,
        "--points",
        csv.to_str().unwrap(),
    ]);
    assert!(text.starts_with("x,y,z,solid:0\n0,0,0,outside\n"), "{text}");
    // .npy in and out.
    let npy = dir.join("p.npy");
    let mut bytes = inrs::io::points::npy_header(inrs::NpyType::F64, &[2, 3]);
    for v in [1.5f64, 0.0, 0.0, 0.0, 0.0, 0.0] {
        bytes.extend(v.to_le_bytes());
    }
    std::fs::write(&npy, bytes).unwrap();
    let out = dir.join("codes.npy");
    inrs_ok(&[
        "classify",
        "--domain",
        &spec,
        "--points",
        npy.to_str().unwrap(),
        "--output",
        out.to_str().unwrap(),
    ]);
    let codes = std::fs::read(&out).unwrap();
    assert_eq!(&codes[codes.len() - 2..], [1, 0]);
}

fn error_of(args: &[&str]) -> String {
    let out = inrs(args);
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    let e = String::from_utf8(out.stderr).unwrap();
    assert_eq!(e.lines().count(), 1, "{e}");
    e
}

#[test]
fn bad_solids_and_bad_points_files_are_one_line_errors() {
    let dir = scratch("classify", "solid_errors");
    let spec = format!("{}#solid:0", fixture("cad/box_void.step"));
    let two = dir.join("two.csv");
    std::fs::write(&two, "1,2,3\n1,2\n").unwrap();
    let e = error_of(&[
        "classify",
        "--domain",
        &spec,
        "--points",
        two.to_str().unwrap(),
    ]);
    assert!(
        e.contains("line 2: expected three numbers \"x,y,z\""),
        "{e}"
    );
    // A failed run leaves no output file.
    let out = dir.join("never.npy");
    error_of(&[
        "classify",
        "--domain",
        &spec,
        "--points",
        two.to_str().unwrap(),
        "--output",
        out.to_str().unwrap(),
    ]);
    assert!(!out.exists());
    // Points of space for a face: refused by their header.
    let xyz = dir.join("xyz.csv");
    std::fs::write(&xyz, "x,y,z\n1,2,3\n").unwrap();
    let e = error_of(&[
        "classify",
        "--domain",
        &format!("{}#face:0", fixture("cad/box_void.step")),
        "--points",
        xyz.to_str().unwrap(),
    ]);
    assert!(e.contains("the header names x, y and z"), "{e}");
    let text = std::fs::read_to_string(fixture("cad/box_void.step")).unwrap();
    // An open void shell: named with its free edges.
    let open = dir.join("open.step");
    std::fs::write(
        &open,
        text.replace(
            "#346 = CLOSED_SHELL('',(#347));",
            "#346 = OPEN_SHELL('',(#17,#137,#237,#284,#331));",
        ),
    )
    .unwrap();
    let ok = dir.join("ok.csv");
    std::fs::write(&ok, "0,0,0\n").unwrap();
    let e = error_of(&[
        "classify",
        "--domain",
        &format!("{}#solid:0", open.display()),
        "--points",
        ok.to_str().unwrap(),
    ]);
    assert!(e.contains("is open") && e.contains("free edges"), "{e}");
    // One of the box's faces turned inside out.
    let flipped = text.replace(
        "#137 = ADVANCED_FACE('',(#138),#152,.T.);",
        "#137 = ADVANCED_FACE('',(#138),#152,.F.);",
    );
    assert_ne!(flipped, text);
    let flipped_path = dir.join("flipped.step");
    std::fs::write(&flipped_path, flipped).unwrap();
    let e = error_of(&[
        "classify",
        "--domain",
        &format!("{}#solid:0", flipped_path.display()),
        "--points",
        ok.to_str().unwrap(),
    ]);
    assert!(e.contains("not consistently oriented"), "{e}");
    let e = error_of(&[
        "classify",
        "--domain",
        &format!("{}#solid:3", fixture("cad/box_void.step")),
        "--points",
        ok.to_str().unwrap(),
    ]);
    assert!(e.contains("solid 3 does not exist"), "{e}");
}

/// The B-spline profile `C` of `revolved_bspline.step` in (r, z) at its parameter `t` in
/// `[0, 1]` (poles (1, 0), (2, 0.5), (1.5, 1.5), (2.5, 2.5), (1, 3), knots 0, 0.5, 1, cubic).
fn profile(t: f64) -> (f64, f64) {
    let poles = [(1.0, 0.0), (2.0, 0.5), (1.5, 1.5), (2.5, 2.5), (1.0, 3.0)];
    let knots = [0.0, 0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0, 1.0];
    // de Boor on the span holding t.
    let k = if t < 0.5 { 3 } else { 4 };
    let mut d: Vec<(f64, f64)> = (0..4).map(|j| poles[j + k - 3]).collect();
    for r in 1..=3 {
        for j in (r..=3).rev() {
            let i = j + k - 3;
            let a = (t - knots[i]) / (knots[i + 4 - r] - knots[i]);
            d[j] = (
                (1.0 - a) * d[j - 1].0 + a * d[j].0,
                (1.0 - a) * d[j - 1].1 + a * d[j].1,
            );
        }
    }
    d[3]
}

/// Under the overhang at the rims of the revolved B-spline (the profile leaves the discs'
/// rims outwards): points just outside, where a crossing lies near the end of the surface's
/// parameter range, were once called inside (Newton's iterate left the range, where the
/// surface is evaluated at its end, and stalled).
#[test]
fn points_under_the_overhang_of_a_revolved_bspline_are_outside() {
    let c = classifier("cad/revolved_bspline.step");
    assert_eq!(c.locate(Point3::new(1.0001, 0.0, -1e-4)), Location::Outside);
    let mut next = uniform(17);
    let mut checked = 0;
    for _ in 0..2000 {
        // Just off the profile, on either side, near the rims.
        let t = if next() < 0.5 {
            0.02 * next()
        } else {
            1.0 - 0.02 * next()
        };
        let (r, z) = profile(t);
        let h = 1e-5;
        let (r1, z1) = profile((t + h).min(1.0));
        let (r0, z0) = profile((t - h).max(0.0));
        let (tr, tz) = (r1 - r0, z1 - z0);
        let len = tr.hypot(tz);
        // The outward normal of the profile (it runs from the bottom rim up).
        let (nr, nz) = (tz / len, -tr / len);
        let a = std::f64::consts::TAU * next();
        for (off, want) in [(1e-4, Location::Outside), (-1e-4, Location::Inside)] {
            let (pr, pz) = (r + off * nr, z + off * nz);
            if !(0.0..=3.0).contains(&pz) && want == Location::Inside {
                continue;
            }
            let p = Point3::new(pr * a.cos(), pr * a.sin(), pz);
            assert_eq!(c.locate(p), want, "t {t} offset {off}: {p:?}");
            checked += 1;
        }
    }
    assert!(checked > 3000, "{checked}");
}
