//! The IGES reader: small hand-written files with analytic answers, the four IGES files of
//! `FreeCAD`'s Idf library (face counts from Open CASCADE, loops closing, areas), and hostile
//! input (every one an `Err` with a one-line message, in bounded time, never a panic).
//!
//! The hand-written files are built by [`iges`] from entity lists, so each test states its
//! entities and parameters literally; directory entry `k` (0-based) is `DE 2k+1`.

use std::f64::consts::{PI, SQRT_2};
use std::time::{Duration, Instant};

use rs_io::cad::CadModel;
use rs_io::cad::iges::read_iges;
use rs_spline::prelude::*;
use rs_spline::{Domain, NurbsCurve, Point};

/// One entity of a hand-written file.
struct Ent {
    kind: i64,
    form: i64,
    params: String,
    /// Transformation matrix pointer (0: none).
    transform: i64,
    /// The 8-digit status number.
    status: &'static str,
}

/// An independent entity (status 00000000).
fn root(kind: i64, params: &str) -> Ent {
    Ent {
        kind,
        form: 0,
        params: params.into(),
        transform: 0,
        status: "00000000",
    }
}

/// A physically dependent entity (status 00010000).
fn sub(kind: i64, params: &str) -> Ent {
    Ent {
        status: "00010000",
        ..root(kind, params)
    }
}

impl Ent {
    fn form(mut self, form: i64) -> Self {
        self.form = form;
        self
    }
    fn transform(mut self, de: i64) -> Self {
        self.transform = de;
        self
    }
    fn status(mut self, status: &'static str) -> Self {
        self.status = status;
        self
    }
}

/// A complete IGES file (fixed 80-column form) holding `ents`, with minimum resolution `res`.
fn iges(ents: &[Ent], res: &str) -> String {
    let mut out = format!("{:<72}S{:07}\n", "hand-written by the inrs tests", 1);
    let global = format!(
        ",,4Htest,8Htest.igs,4Htest,4Htest,32,308,15,308,15,,1.,2,2HMM,1,0.01,\
         15H20240101.000000,{res},10.,4Htest,,11,0,15H20240101.000000;"
    );
    let g: Vec<&[u8]> = global.as_bytes().chunks(72).collect();
    for (i, chunk) in g.iter().enumerate() {
        out += &format!("{:<72}G{:07}\n", String::from_utf8_lossy(chunk), i + 1);
    }
    let mut d = String::new();
    let mut p = String::new();
    let mut pline = 1;
    for (i, e) in ents.iter().enumerate() {
        let de = 2 * i + 1;
        // Split the parameters after delimiters so that no line exceeds 64 columns.
        let mut lines = vec![String::new()];
        for piece in e.params.split_inclusive(',') {
            if lines.last().unwrap().len() + piece.len() > 64 {
                lines.push(String::new());
            }
            lines.last_mut().unwrap().push_str(piece);
        }
        for l in &lines {
            p += &format!("{l:<64} {de:>7}P{pline:07}\n");
            pline += 1;
        }
        let start = pline - lines.len();
        d += &format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{:07}\n",
            e.kind, start, 0, 0, 0, 0, e.transform, 0, e.status, de
        );
        d += &format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{:07}\n",
            e.kind,
            0,
            0,
            lines.len(),
            e.form,
            "",
            "",
            "",
            0,
            de + 1
        );
    }
    out += &d;
    out += &p;
    out += &format!(
        "S{:07}G{:07}D{:07}P{:07}{:40}T{:07}\n",
        1,
        g.len(),
        2 * ents.len(),
        pline - 1,
        "",
        1
    );
    out
}

fn read(text: &str) -> CadModel {
    read_iges(text.as_bytes()).unwrap_or_else(|e| panic!("{e}"))
}

/// The loops of face `k`, or a panic with its error.
fn loops(m: &CadModel, k: usize) -> &Vec<Vec<NurbsCurve>> {
    m.faces[k]
        .loops
        .as_ref()
        .unwrap_or_else(|e| panic!("face {k}: {e}"))
}

/// The error of face `k`.
fn face_err(m: &CadModel, k: usize) -> String {
    match &m.faces[k].loops {
        Ok(_) => panic!("face {k} was read"),
        Err(e) => {
            let e = e.to_string();
            assert!(!e.contains('\n'), "{e}");
            e
        }
    }
}

/// The signed area enclosed by one loop.
fn area(l: &[NurbsCurve]) -> f64 {
    Domain::new(l.to_vec()).unwrap().signed_area()
}

/// Asserts that each curve of `l` ends where the next starts and the last returns to the
/// first, within `tol`.
fn assert_closed(l: &[NurbsCurve], tol: f64, what: &str) {
    for i in 0..l.len() {
        let gap = l[i]
            .end_point()
            .distance(l[(i + 1) % l.len()].start_point());
        assert!(
            gap <= tol,
            "{what}: gap {gap:e} after curve {i} (tolerance {tol:e})"
        );
    }
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

/// A degree 1 x 1 planar 128: the unit square of the plane z = 0 on `[0, 1]^2`.
fn unit_square_128() -> Ent {
    sub(
        128,
        "128,1,1,1,1,0,0,1,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,1.,1.,1.,0.,0.,0.,1.,0.,0.,0.,1.,0.,\
         1.,1.,0.,0.,1.,0.,1.;",
    )
}

/// A 128 of degree 2 x 1 (not a plane for this reader).
fn curved_128() -> Ent {
    sub(
        128,
        "128,2,1,2,1,0,0,1,0,0,0.,0.,0.,1.,1.,1.,0.,0.,1.,1.,1.,1.,1.,1.,1.,1.,0.,0.,0.,0.5,0.,\
         1.,1.,0.,0.,0.,1.,0.,0.5,1.,1.,1.,1.,0.,0.,1.,0.,1.;",
    )
}

#[test]
fn square_with_a_round_hole() {
    let ents = [
        root(144, "144,3,1,1,5,19;"),                  // DE 1
        unit_square_128(),                             // DE 3
        sub(142, "142,0,3,7,0,1;"),                    // DE 5
        sub(102, "102,4,9,11,13,15;"),                 // DE 7
        sub(110, "110,0.,0.,0.,1.,0.,0.;"),            // DE 9
        sub(110, "110,1.,0.,0.,1.,1.,0.;"),            // DE 11
        sub(110, "110,1.,1.,0.,0.,1.,0.;"),            // DE 13
        sub(110, "110,0.,1.,0.,0.,0.,0.;"),            // DE 15
        sub(406, "406,1,1.;").form(15),                // DE 17: not a face, not a curve
        sub(142, "142,0,3,21,0,1;"),                   // DE 19
        sub(100, "100,0.,0.5,0.5,0.75,0.5,0.75,0.5;"), // DE 21: full circle
    ];
    let text = iges(&ents, "1.E-07");
    let m = read(&text);
    // CRLF line ends and a file without line breaks read the same.
    let crlf = read(&text.replace('\n', "\r\n"));
    let flat = read(&text.replace('\n', ""));
    for other in [&crlf, &flat] {
        assert_eq!(loops(other, 0), loops(&m, 0));
    }
    assert_eq!(m.tolerance.stated(), Some(1e-7));
    assert_eq!(m.faces.len(), 1);
    assert_eq!(m.faces[0].entity, "DE 1");
    assert_eq!(m.faces[0].surface_name, "128 (rational B-spline surface)");
    let l = loops(&m, 0);
    assert_eq!(l.len(), 2);
    assert_eq!(l[0].len(), 4);
    assert!(l[0].iter().all(|c| c.degree() == 1));
    assert_eq!(l[0][0].start_point(), Point::new(0.0, 0.0));
    assert_eq!(l[0][1].start_point(), Point::new(1.0, 0.0));
    assert!(close(area(&l[0]), 1.0, 1e-14));
    assert_eq!(l[1].len(), 1);
    let circle = &l[1][0];
    assert_eq!(circle.degree(), 2);
    let (a, b) = circle.param_range();
    for i in 0..=32 {
        let p = circle.point_at(a + (b - a) * f64::from(i) / 32.0);
        assert!(
            close(p.distance(Point::new(0.5, 0.5)), 0.25, 1e-15),
            "{p:?}"
        );
    }
    assert!(close(area(&l[1]), PI / 16.0, 1e-14));
    assert_closed(&l[1], 1e-15, "circle");
}

/// A rational 126 full circle of radius `r` about `(cx, cy)` (nine control points).
fn circle_126(cx: f64, cy: f64, r: f64) -> String {
    let unit = [
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (-1.0, 1.0),
        (-1.0, 0.0),
        (-1.0, -1.0),
        (0.0, -1.0),
        (1.0, -1.0),
        (1.0, 0.0),
    ];
    let mut s = String::from("126,8,2,1,1,0,0,0.,0.,0.,0.25,0.25,0.5,0.5,0.75,0.75,1.,1.,1.,");
    for i in 0..9 {
        // Corner weights 1/sqrt(2): the exact quarter circles.
        s += &if i % 2 == 1 {
            format!("{},", SQRT_2 / 2.0)
        } else {
            "1.,".to_string()
        };
    }
    for (x, y) in unit {
        s += &format!("{},{},0.,", cx + r * x, cy + r * y);
    }
    s + "0.,1.,0.,0.,1.;"
}

#[test]
fn bspline_loop_trimmed_unclamped_and_rational() {
    let ents = [
        root(144, "144,3,1,1,5,17;"),  // DE 1
        unit_square_128(),             // DE 3
        sub(142, "142,0,3,7,0,1;"),    // DE 5
        sub(102, "102,4,9,11,13,15;"), // DE 7
        // DE 9: the segment (-1, 0)-(2, 0) on [0, 3], trimmed to [1, 2]: (0, 0)-(1, 0).
        sub(
            126,
            "126,1,1,1,0,1,0,0.,0.,3.,3.,1.,1.,-1.,0.,0.,2.,0.,0.,1.,2.,0.,0.,1.;",
        ),
        // DE 11: a polynomial parabola from (1, 0) to (1, 1) bulging to x = 1.25.
        sub(
            126,
            "126,2,2,1,0,1,0,0.,0.,0.,1.,1.,1.,1.,1.,1.,1.,0.,0.,1.5,0.5,0.,1.,1.,0.,0.,1.,0.,0.,1.;",
        ),
        // DE 13: an unclamped uniform quadratic on [2, 3] from (1, 1) to (0, 1).
        sub(
            126,
            "126,2,2,1,0,1,0,0.,1.,2.,3.,4.,5.,1.,1.,1.,1.5,1.,0.,0.5,1.,0.,-0.5,1.,0.,2.,3.,0.,0.,1.;",
        ),
        sub(110, "110,0.,1.,0.,0.,0.,0.;"),   // DE 15
        sub(142, "142,0,3,19,0,1;"),          // DE 17
        sub(126, &circle_126(0.5, 0.5, 0.2)), // DE 19
    ];
    let m = read(&iges(&ents, "1.E-07"));
    let l = loops(&m, 0);
    let outer = &l[0];
    assert_eq!(outer.len(), 4);
    assert_eq!(outer[0].degree(), 1);
    assert!(outer[0].start_point().distance(Point::new(0.0, 0.0)) < 1e-15);
    assert!(outer[0].end_point().distance(Point::new(1.0, 0.0)) < 1e-15);
    assert!(outer[2].start_point().distance(Point::new(1.0, 1.0)) < 1e-15);
    assert!(outer[2].end_point().distance(Point::new(0.0, 1.0)) < 1e-15);
    assert_closed(outer, 1e-15, "outer");
    // The square plus the parabolic segment (2/3 of chord 1 times sagitta 1/4).
    assert!(
        close(area(outer), 1.0 + 1.0 / 6.0, 1e-13),
        "{}",
        area(outer)
    );
    let hole = &l[1];
    assert_eq!(hole[0].weights().len(), 9);
    assert!(close(area(hole), PI * 0.04, 1e-13));
}

#[test]
fn transformation_chains_compose() {
    let ents = [
        root(144, "144,3,1,1,5,15;"), // DE 1
        unit_square_128(),            // DE 3
        sub(142, "142,0,3,7,0,1;"),   // DE 5
        // DE 7: a unit circle at z = 5 through 124 DE 9 (scale 2, shift (5, 6); R13, R23
        // are not parameters and must not move it), then DE 11 (shift (1, 0)).
        sub(100, "100,5.,0.,0.,1.,0.,1.,0.;").transform(9),
        sub(124, "124,2.,0.,7.,5.,0.,2.,9.,6.,0.,0.,1.,0.;").transform(11), // DE 9
        sub(124, "124,1.,0.,0.,1.,0.,1.,0.,0.,0.,0.,1.,0.;"),               // DE 11
        sub(124, "124,1.,0.,0.,10.,0.,1.,0.,0.,0.,0.,1.,0.;"),              // DE 13
        sub(142, "142,0,3,17,0,1;"),                                        // DE 15
        // DE 17: a composite shifted by (10, 0) (DE 13) holding a line scaled by 2 (DE 23).
        sub(102, "102,3,19,21,25;").transform(13),
        sub(110, "110,0.,0.,0.,1.,0.,0.;").transform(23), // DE 19
        sub(110, "110,2.,0.,0.,0.,2.,0.;"),               // DE 21
        sub(124, "124,2.,0.,0.,0.,0.,2.,0.,0.,0.,0.,1.,0.;"), // DE 23
        sub(110, "110,0.,2.,0.,0.,0.,0.;"),               // DE 25
    ];
    let m = read(&iges(&ents, "1.E-07"));
    let l = loops(&m, 0);
    let c = &l[0][0];
    let (a, b) = c.param_range();
    for i in 0..=16 {
        let p = c.point_at(a + (b - a) * f64::from(i) / 16.0);
        assert!(close(p.distance(Point::new(6.0, 6.0)), 2.0, 1e-14), "{p:?}");
    }
    assert!(close(area(&l[0]), 4.0 * PI, 1e-12));
    // The line is scaled first (its own matrix), then shifted (the composite's).
    let tri = &l[1];
    assert_eq!(tri[0].start_point(), Point::new(10.0, 0.0));
    assert_eq!(tri[0].end_point(), Point::new(12.0, 0.0));
    assert!(close(area(tri), 2.0, 1e-14));
}

#[test]
fn conic_arcs_ellipse_and_parabola() {
    let ents = [
        root(144, "144,3,1,0,5;"),  // DE 1
        unit_square_128(),          // DE 3
        sub(142, "142,0,3,7,0,1;"), // DE 5
        sub(102, "102,2,9,11;"),    // DE 7
        // DE 9: x^2 + 4 y^2 = 4 from (2, 0) counter-clockwise to (-2, 0).
        sub(104, "104,1.,0.,4.,0.,0.,-4.,0.,2.,0.,-2.,0.;").form(1),
        sub(110, "110,-2.,0.,0.,2.,0.,0.;"), // DE 11
        root(144, "144,3,1,0,15;"),          // DE 13
        sub(142, "142,0,3,17,0,1;"),         // DE 15
        sub(102, "102,2,19,21;"),            // DE 17
        // DE 19: x^2 - y = 0 from (1, 1) through the vertex to (-1, 1).
        sub(104, "104,1.,0.,0.,0.,-1.,0.,0.,1.,1.,-1.,1.;").form(3),
        sub(110, "110,-1.,1.,0.,1.,1.,0.;"), // DE 21
        root(144, "144,3,1,0,25;"),          // DE 23
        sub(142, "142,0,3,27,0,1;"),         // DE 25
        // DE 27: the whole ellipse (start = end), tilted by the coefficient B.
        sub(104, "104,2.,1.,2.,0.,0.,-3.,0.,1.,1.,1.,1.;").form(1),
    ];
    let m = read(&iges(&ents, "1.E-07"));
    assert_eq!(m.faces.len(), 3);
    let half = &loops(&m, 0)[0];
    assert_closed(half, 1e-14, "half ellipse");
    assert!(close(area(half), PI, 1e-13), "{}", area(half));
    let top = half[0].point_at(0.5 * (half[0].param_range().0 + half[0].param_range().1));
    assert!(top.y > 0.0, "counter-clockwise from (2, 0) passes above");
    let cup = &loops(&m, 1)[0];
    assert!(cup[0].is_polynomial());
    assert_closed(cup, 1e-14, "parabola");
    assert!(close(area(cup), -4.0 / 3.0, 1e-13), "{}", area(cup));
    // 2x^2 + xy + 2y^2 = 3 through (1, 1): semi-axes sqrt(3/2.5), sqrt(3/1.5).
    let whole = &loops(&m, 2)[0];
    assert_closed(whole, 1e-14, "ellipse");
    let want = PI * (3.0f64 / 2.5).sqrt() * (3.0f64 / 1.5).sqrt();
    assert!(close(area(whole), want, 1e-12), "{} vs {want}", area(whole));
}

#[test]
fn model_space_curves_on_planes() {
    // A tilted plane x + y + z = 2 sqrt(3), and a frame taking z = 0 onto it.
    let n = [1.0 / 3f64.sqrt(); 3];
    let e1 = [1.0 / SQRT_2, -1.0 / SQRT_2, 0.0];
    let e2 = [
        n[1] * e1[2] - n[2] * e1[1],
        n[2] * e1[0] - n[0] * e1[2],
        n[0] * e1[1] - n[1] * e1[0],
    ];
    let t = n.map(|x| 2.0 * x);
    let frame = format!(
        "124,{},{},{},{},{},{},{},{},{},{},{},{};",
        e1[0], e2[0], n[0], t[0], e1[1], e2[1], n[1], t[1], e1[2], e2[2], n[2], t[2]
    );
    let ents = [
        root(144, "144,3,1,0,5;"),                  // DE 1: on the plane z = 3
        sub(108, "108,0.,0.,1.,3.,0,0.,0.,0.,0.;"), // DE 3
        sub(142, "142,0,3,0,7,2;"),                 // DE 5: no parameter-space curve
        sub(100, "100,3.,1.,2.,1.5,2.,1.5,2.;"),    // DE 7: circle at z = 3
        root(144, "144,11,1,0,13;"),                // DE 9: on the tilted plane
        sub(
            108,
            &format!("108,1.,1.,1.,{},0,0.,0.,0.,0.;", 2.0 * 3f64.sqrt()),
        ), // DE 11
        sub(142, "142,0,11,0,15,2;"),               // DE 13
        sub(100, "100,0.,0.,0.,0.5,0.,0.5,0.;").transform(17), // DE 15
        sub(124, &frame),                           // DE 17
        root(144, "144,21,1,0,23;"),                // DE 19: on a parallelogram 128
        // DE 21: S(u, v) = (2u + v, v, v) on [0, 1]^2.
        sub(
            128,
            "128,1,1,1,1,0,0,1,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,1.,1.,1.,0.,0.,0.,2.,0.,0.,\
                  1.,1.,1.,3.,1.,1.,0.,1.,0.,1.;",
        ),
        sub(142, "142,0,21,0,25,2;"),             // DE 23
        sub(102, "102,3,27,29,31;"),              // DE 25
        sub(110, "110,0.,0.,0.,2.,0.,0.;"),       // DE 27
        sub(110, "110,2.,0.,0.,1.,1.,1.;"),       // DE 29
        sub(110, "110,1.,1.,1.,0.,0.,0.;"),       // DE 31
        root(144, "144,35,1,0,37;"),              // DE 33: curved surface, no pcurve
        curved_128(),                             // DE 35
        sub(142, "142,0,35,0,27,2;"),             // DE 37
        root(144, "144,3,1,0,41;"),               // DE 39: a circle off the plane z = 3
        sub(142, "142,0,3,0,43,2;"),              // DE 41
        sub(100, "100,3.5,1.,2.,1.5,2.,1.5,2.;"), // DE 43
    ];
    let m = read(&iges(&ents, "1.E-09"));
    assert_eq!(m.faces.len(), 5);
    assert_eq!(m.faces[0].surface_name, "108 (plane)");
    let c = &loops(&m, 0)[0];
    // This reader's axes for the normal (0, 0, 1): u = x, v = y.
    let (a, b) = c[0].param_range();
    for i in 0..=16 {
        let p = c[0].point_at(a + (b - a) * f64::from(i) / 16.0);
        assert!(close(p.distance(Point::new(1.0, 2.0)), 0.5, 1e-15), "{p:?}");
    }
    // The tilted plane's axes are orthonormal: the circle keeps its radius and area.
    let tilted = &loops(&m, 1)[0];
    assert!(
        close(area(tilted).abs(), PI * 0.25, 1e-12),
        "{}",
        area(tilted)
    );
    let (a, b) = tilted[0].param_range();
    let centre = tilted[0]
        .point_at(a)
        .lerp(tilted[0].point_at(0.5 * (a + b)), 0.5);
    for i in 0..=16 {
        let p = tilted[0].point_at(a + (b - a) * f64::from(i) / 16.0);
        assert!(close(p.distance(centre), 0.5, 1e-12), "{p:?}");
    }
    // On the parallelogram the triangle (0,0,0), (2,0,0), (1,1,1) is (0,0), (1,0), (0,1).
    let tri = &loops(&m, 2)[0];
    assert!(tri[0].start_point().distance(Point::new(0.0, 0.0)) < 1e-15);
    assert!(tri[1].start_point().distance(Point::new(1.0, 0.0)) < 1e-15);
    assert!(tri[2].start_point().distance(Point::new(0.0, 1.0)) < 1e-15);
    assert!(close(area(tri), 0.5, 1e-15));
    // Without a parameter-space curve on a curved surface the pcurve is computed from the
    // model-space curve (rs_geom::pcurve); this line leaves the patch (it reaches x = 2, the
    // patch stops at x = 1): refused, naming the curve and how far off it is.
    let e = face_err(&m, 3);
    assert!(
        e.starts_with("DE 27 (110 line): the edge is") && e.contains("from the B-spline surface"),
        "{e}"
    );
    assert!(face_err(&m, 4).contains("off the surface's plane"));
}

#[test]
fn parameter_rectangle_and_bounded_surfaces() {
    let ents = [
        root(144, "144,3,0,0,0;"), // DE 1: N1 = 0 on a 128 with range [0, 2] x [0, 3]
        sub(
            128,
            "128,1,1,1,1,0,0,1,0,0,0.,0.,2.,2.,0.,0.,3.,3.,1.,1.,1.,1.,0.,0.,0.,1.,0.,0.,\
                  0.,1.,0.,1.,1.,0.,0.,2.,0.,3.;",
        ),
        // DE 5: a bounded surface with one 141 boundary of two model curves; the second's
        // pcurve runs from (0, 0) to (1, 1) and is used reversed (sense 2).
        root(143, "143,1,3,1,7;"),
        sub(141, "141,1,2,3,2,9,1,1,11,9,2,1,17;"), // DE 7
        sub(110, "110,0.,0.,0.,1.,1.,0.;"),         // DE 9 (model curve, not read)
        sub(102, "102,2,13,15;"),                   // DE 11
        sub(110, "110,0.,0.,0.,1.,0.,0.;"),         // DE 13
        sub(110, "110,1.,0.,0.,1.,1.,0.;"),         // DE 15
        sub(110, "110,0.,0.,0.,1.,1.,0.;"),         // DE 17
        root(144, "144,21,0,0,0;"),                 // DE 19: N1 = 0 on a plane
        sub(108, "108,0.,0.,1.,0.,0,0.,0.,0.,0.;"), // DE 21
    ];
    let m = read(&iges(&ents, "1.E-07"));
    assert_eq!(m.faces.len(), 3);
    let rect = &loops(&m, 0)[0];
    assert_eq!(rect.len(), 4);
    assert!(close(area(rect), 6.0, 1e-14));
    assert_eq!(m.faces[1].entity, "DE 5");
    assert_eq!(m.faces[1].surface_name, "128 (rational B-spline surface)");
    let tri = &loops(&m, 1)[0];
    assert_eq!(tri.len(), 3);
    assert_eq!(tri[2].start_point(), Point::new(1.0, 1.0));
    assert!(close(area(tri), 0.5, 1e-15));
    assert!(face_err(&m, 2).contains("parameter range"));
}

#[test]
fn faces_come_in_group_order_then_directory_order() {
    let face = |surface: usize, bound: usize| format!("144,{surface},1,0,{bound};");
    let ents = [
        root(402, "402,2,9,3;").form(7), // DE 1: a group listing DE 9 before DE 3
        root(144, &face(5, 7)).status("00020000"), // DE 3
        unit_square_128(),               // DE 5
        sub(142, "142,0,5,15,0,1;"),     // DE 7
        root(144, &face(5, 7)).status("00020000"), // DE 9
        sub(144, &face(5, 7)),           // DE 11: physically dependent: no face
        root(144, &face(5, 7)),          // DE 13: independent
        sub(100, "100,0.,0.5,0.5,0.75,0.5,0.75,0.5;"), // DE 15
    ];
    let m = read(&iges(&ents, "1.E-07"));
    let order: Vec<&str> = m.faces.iter().map(|f| f.entity.as_str()).collect();
    assert_eq!(order, ["DE 9", "DE 3", "DE 13"]);
}

#[test]
fn brep_solid_faces_in_shell_order() {
    let ents = [
        root(186, "186,3,1,0;"),            // DE 1: a solid, its shell DE 3
        sub(514, "514,2,9,1,5,1;").form(1), // DE 3: faces DE 9, DE 5
        sub(510, "510,7,1,1,11;").form(1),  // DE 5
        unit_square_128(),                  // DE 7
        sub(510, "510,21,1,1,23;").form(1), // DE 9: on a plane
        // DE 11: three edges with parameter-space curves, the third against its model curve
        // (OF = 0): its parameter-space curve is written in the loop's direction all the
        // same, as Open CASCADE writes and reads them.
        sub(
            508,
            "508,3,0,13,1,1,1,0,15,0,13,2,1,1,0,17,0,13,3,0,1,0,19;",
        )
        .form(1),
        sub(504, "504,3,25,0,0,0,0,27,0,0,0,0,29,0,0,0,0;").form(1), // DE 13
        sub(110, "110,0.,0.,0.,1.,0.,0.;"),                          // DE 15
        sub(110, "110,1.,0.,0.,0.,1.,0.;"),                          // DE 17
        sub(110, "110,0.,1.,0.,0.,0.,0.;"),                          // DE 19
        sub(108, "108,0.,0.,1.,0.,0,0.,0.,0.,0.;"),                  // DE 21
        // DE 23: the same edges without parameter-space curves: the 504's model curves.
        sub(508, "508,3,0,13,1,1,0,0,13,2,1,0,0,13,3,0,0;").form(1),
        sub(110, "110,0.,0.,0.,2.,0.,0.;"), // DE 25
        sub(110, "110,2.,0.,0.,0.,2.,0.;"), // DE 27
        sub(110, "110,0.,0.,0.,0.,2.,0.;"), // DE 29
    ];
    let m = read(&iges(&ents, "1.E-07"));
    let order: Vec<&str> = m.faces.iter().map(|f| f.entity.as_str()).collect();
    assert_eq!(order, ["DE 9", "DE 5"]);
    assert_eq!(m.faces[0].surface_name, "108 (plane)");
    let big = &loops(&m, 0)[0];
    assert_closed(big, 1e-15, "plane face");
    assert!(close(area(big), 2.0, 1e-15));
    let small = &loops(&m, 1)[0];
    assert_closed(small, 1e-15, "128 face");
    assert_eq!(small[2].start_point(), Point::new(0.0, 1.0));
    assert!(close(area(small), 0.5, 1e-15));
}

/// Asserts that reading `bytes` is a file-level `Err` whose one-line message contains `want`.
fn file_err(bytes: &[u8], want: &str) {
    let t = Instant::now();
    match read_iges(bytes) {
        Ok(_) => panic!("read; expected an error with {want:?}"),
        Err(e) => {
            let e = e.to_string();
            assert!(e.contains(want), "{e:?} lacks {want:?}");
            assert!(!e.contains('\n'), "{e:?}");
        }
    }
    assert!(t.elapsed() < Duration::from_secs(5));
}

/// Asserts that `ents` read as a file whose first face is an `Err` containing `want`.
fn first_face_err(ents: &[Ent], want: &str) {
    let t = Instant::now();
    let m = read(&iges(ents, "1.E-07"));
    let e = face_err(&m, 0);
    assert!(e.contains(want), "{e:?} lacks {want:?}");
    assert!(t.elapsed() < Duration::from_secs(5));
}

fn square_file() -> String {
    iges(
        &[
            root(144, "144,3,1,0,5;"),
            unit_square_128(),
            sub(142, "142,0,3,7,0,1;"),
            sub(102, "102,4,9,11,13,15;"),
            sub(110, "110,0.,0.,0.,1.,0.,0.;"),
            sub(110, "110,1.,0.,0.,1.,1.,0.;"),
            sub(110, "110,1.,1.,0.,0.,1.,0.;"),
            sub(110, "110,0.,1.,0.,0.,0.,0.;"),
        ],
        "1.E-07",
    )
}

#[test]
fn broken_files_are_file_level_errors() {
    let good = square_file();
    assert!(loops(&read(&good), 0)[0].len() == 4);
    // Truncated anywhere: an error or (cut inside a blank tail) the same file, never a panic.
    for cut in (0..good.len()).step_by(7) {
        let _ = read_iges(&good.as_bytes()[..cut]);
    }
    file_err(&good.as_bytes()[..good.len() / 2], "truncated");
    let whole_lines = good.lines().take(9).collect::<Vec<_>>().join("\n");
    file_err(whole_lines.as_bytes(), "truncated");
    file_err(b"", "empty");
    // Sections out of order: the global record before the start record.
    let mut lines: Vec<&str> = good.lines().collect();
    lines.swap(0, 1);
    file_err(lines.join("\n").as_bytes(), "section S after section G");
    // A directory field that is not a number.
    file_err(
        good.replacen("     102", "     1x2", 1).as_bytes(),
        "not an integer",
    );
    // A Hollerith count past the end of the global section.
    let g = good.replacen(",15H20240101.000000;", ",95H20240101.000000;", 1);
    assert_ne!(g, good);
    file_err(g.as_bytes(), "past the end");
    // A 100 MB single line.
    let mut huge = vec![b'7'; 100 << 20];
    // A multiple of 80 bytes reads as 80-column records without line breaks.
    file_err(&huge, "unknown section letter '7' in column 73");
    huge.push(b'7');
    file_err(&huge, "columns without a line break");
    let mut huge_line = good.clone().into_bytes();
    huge_line.extend(std::iter::repeat_n(b'x', 100 << 20));
    file_err(&huge_line, "columns");
    // The compressed form.
    file_err(format!("{:<72}C0000001\n", "").as_bytes(), "compressed");
}

#[test]
fn broken_entities_are_face_errors() {
    let square = |outer: Ent| {
        vec![
            root(144, "144,3,1,0,5;"),
            unit_square_128(),
            sub(142, "142,0,3,7,0,1;"),
            outer,
        ]
    };
    // A parameter pointer past the end, a line count past the end.
    let mut ents = square(sub(110, "110,0.,0.,0.,1.,0.,0.;"));
    let text = iges(&ents, "1.E-07");
    // Columns 9-16 of DE 7's first record: the parameter data pointer; columns 25-32 of its
    // second: the line count.
    let patch = |de: &str, cols: std::ops::Range<usize>, value: &str| {
        text.lines()
            .map(|l| {
                if l.ends_with(de) {
                    format!("{}{value:>8}{}\n", &l[..cols.start], &l[cols.end..])
                } else {
                    format!("{l}\n")
                }
            })
            .collect::<String>()
    };
    let m = read(&patch("D0000007", 8..16, "999"));
    assert!(face_err(&m, 0).contains("not in the parameter section"));
    let m = read(&patch("D0000008", 24..32, "3"));
    assert!(face_err(&m, 0).contains("runs past the end"));
    let m = read(&patch("D0000007", 8..16, "1"));
    assert!(face_err(&m, 0).contains("belongs to DE 1"));
    // An entry pointing to itself: a composite holding itself, a 144 bounded by itself.
    ents[3] = sub(102, "102,1,7;");
    first_face_err(&ents, "contain each other");
    first_face_err(&[root(144, "144,1,1,0,1;")], "not a 142");
    // Composites holding each other.
    let mut cyc = square(sub(102, "102,1,9;"));
    cyc.push(sub(102, "102,1,7;"));
    first_face_err(&cyc, "contain each other");
    // 124 chains in a cycle.
    let mut chain = square(sub(110, "110,0.,0.,0.,1.,0.,0.;").transform(9));
    chain.push(sub(124, "124,1.,0.,0.,0.,0.,1.,0.,0.,0.,0.,1.,0.;").transform(11));
    chain.push(sub(124, "124,1.,0.,0.,0.,0.,1.,0.,0.,0.,0.,1.,0.;").transform(9));
    first_face_err(&chain, "form a cycle");
    // A transformation pointer to something else.
    let wrong = square(sub(110, "110,0.,0.,0.,1.,0.,0.;").transform(3));
    first_face_err(&wrong, "a 128 rational B-spline surface");
    // A 126 claiming 10^12 control points.
    first_face_err(
        &square(sub(126, "126,1000000000000,1,1,0,1,0,0.,0.,1.,1.;")),
        "more than the",
    );
    // Non-numeric, NaN, 1e400, a Hollerith count past the end of the record.
    for (params, want) in [
        ("110,0.,abc,0.,1.,0.,0.;", "not a number"),
        ("110,NaN,0.,0.,1.,0.,0.;", "not a number"),
        ("110,1e400,0.,0.,1.,0.,0.;", "not a finite number"),
        ("110,0.,0.,0.,1.,0.", "ends before"),
        ("110,99Hxx;", "past the end"),
    ] {
        first_face_err(&square(sub(110, params)), want);
    }
    // Wrong types and forms.
    first_face_err(
        &square(sub(116, "116,0.,0.,0.;")),
        "not a curve this reader knows",
    );
    first_face_err(&square(sub(110, "110,0.,0.,0.,1.,0.,0.;").form(1)), "a ray");
    first_face_err(&[root(144, "144,3,1,0,5;")], "not a directory entry");
    // A gap between pieces names the composite and the pieces.
    let gap = square(sub(102, "102,2,9,11;"));
    let mut gap = gap;
    gap.push(sub(110, "110,0.,0.,0.,1.,0.,0.;"));
    gap.push(sub(110, "110,1.,0.5,0.,0.,0.,0.;"));
    first_face_err(&gap, "DE 7: pieces DE 9 and DE 11 are 5e-1 apart");
}

#[test]
fn shared_sub_curves_cannot_blow_up() {
    // 40 composites, each holding the next twice: 2^40 pieces if expanded.
    let mut ents = vec![
        root(144, "144,3,1,0,5;"),
        unit_square_128(),
        sub(142, "142,0,3,7,0,1;"),
    ];
    for k in 0..40 {
        let next = 7 + 2 * (k + 1);
        ents.push(sub(102, &format!("102,2,{next},{next};")));
    }
    ents.push(sub(110, "110,0.,0.,0.,1.,0.,0.;"));
    let t = Instant::now();
    let m = read(&iges(&ents, "1.E-07"));
    let e = face_err(&m, 0);
    assert!(
        e.contains("nested deeper") || e.contains("work limit"),
        "{e}"
    );
    assert!(t.elapsed() < Duration::from_secs(5));
    // 24 levels: within the depth limit, stopped by the work limit.
    ents.truncate(3 + 24);
    ents.push(sub(110, "110,0.,0.,0.,1.,0.,0.;"));
    let e = face_err(&read(&iges(&ents, "1.E-07")), 0).to_string();
    assert!(e.contains("work limit"), "{e}");
}

#[test]
fn random_damage_never_panics() {
    let brep = std::fs::read(format!(
        "{}/../../fixtures/cad/iges/cone_minus_sphere_brep.igs",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    for good in [square_file().into_bytes(), brep] {
        damage(&good);
    }
}

/// Reads 3000 copies of `good` with one to four random bytes changed: an error or a model
/// whose faces make domains or say why not, never a panic; face errors are one line.
fn damage(good: &[u8]) {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let alphabet = b"0123456789,;.-+EDH \n";
    for _ in 0..3000 {
        let mut bytes = good.to_vec();
        for _ in 0..1 + next() % 4 {
            let i = (next() % bytes.len() as u64) as usize;
            bytes[i] = alphabet[(next() % alphabet.len() as u64) as usize];
        }
        if let Ok(m) = read_iges(&bytes) {
            for (k, f) in m.faces.iter().enumerate() {
                if let Err(e) = &f.loops {
                    assert!(!e.to_string().contains('\n'));
                }
                let _ = m.face_domain(k, None);
            }
        }
    }
}

/// Face counts of the Idf library's IGES files, as Open CASCADE 7.8 gives them: OCP
/// (`cadquery-ocp-novtk`), `IGESControl_Reader.ReadFile`, `TransferRoots`, `OneShape`, then
/// `TopExp_Explorer(shape, TopAbs_FACE)`; mapping each face back with
/// `TransferReader().EntityFromShapeResult(face, -1)` gave the 144 entities in directory
/// order, the order this reader uses. Open CASCADE's loops (`BRep_Tool.CurveOnSurface`) had
/// the same vertices and edge mid-points as ours (within 1e-6) on every 128 face.
const IDF_FILES: [(&str, usize, f64); 4] = [
    ("RLF_12545", 47, 3.93728e-9),
    ("SOD_323", 75, 3.64646e-6),
    ("SOT23", 73, 5.5076e-11),
    ("SOT404", 75, 3.93739e-9),
];

/// Faces of zero area in the files themselves: 128 patches 2.9e-7 wide in `u` whose loop
/// runs along `u = const` and back (Open CASCADE reads the same two-edge wires and the same
/// `UVBounds`).
const SLIVERS: [(&str, &str); 2] = [("SOD_323", "DE 465"), ("SOD_323", "DE 761")];

#[test]
fn idf_library_files() {
    for (name, faces, tolerance) in IDF_FILES {
        let path = format!("/usr/share/freecad/Mod/Idf/Idflibs/{name}.igs");
        let Some(bytes) = rs_testkit::system_file(&path, "freecad-common") else {
            return;
        };
        let m = read_iges(&bytes).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(m.faces.len(), faces, "{name}");
        assert_eq!(m.tolerance.stated(), Some(tolerance), "{name}");
        for (k, f) in m.faces.iter().enumerate() {
            let l = f
                .loops
                .as_ref()
                .unwrap_or_else(|e| panic!("{name} face {k} ({}): {e}", f.entity));
            assert!(!l.is_empty());
            let mut net = 0.0;
            for (j, lp) in l.iter().enumerate() {
                // The reader's tolerance in (u, v): the file's, or 1e-8 of the coordinates.
                let size = lp
                    .iter()
                    .flat_map(|c| c.control_points())
                    .fold(0.0f64, |s, p| s.max(p.x.abs()).max(p.y.abs()));
                assert_closed(lp, tolerance.max(1e-8 * size), &format!("{name} face {k}"));
                let a = area(lp).abs();
                net += if j == 0 { a } else { -a };
            }
            if SLIVERS.contains(&(name, f.entity.as_str())) {
                // Zero width in u: the loop runs up and back down one line.
                let bb = l[0]
                    .iter()
                    .map(|c| c.bounding_box())
                    .reduce(|a, b| a.union(b))
                    .unwrap();
                assert!(
                    bb.width() < 1e-6 && net.abs() < 1e-12,
                    "{name} {}",
                    f.entity
                );
            } else {
                assert!(net > 0.0, "{name} face {k} ({}): area {net}", f.entity);
            }
        }
    }
}

#[test]
fn idf_surface_of_revolution_pole_is_bridged() {
    let path = "/usr/share/freecad/Mod/Idf/Idflibs/SOT23.igs";
    let Some(bytes) = rs_testkit::system_file(path, "freecad-common") else {
        return;
    };
    let m = read_iges(&bytes).unwrap();
    let k = m.faces.iter().position(|f| f.entity == "DE 197").unwrap();
    assert_eq!(m.faces[k].surface_name, "120 (surface of revolution)");
    // Three pcurves, and the degenerate edge at the generatrix's end on the axis (u = pi),
    // left out of the file and added by Open CASCADE as a degenerated edge, as a segment.
    let l = &loops(&m, k)[0];
    assert_eq!(l.len(), 4);
    assert_eq!(l[1].degree(), 1);
    assert!(l[1].start_point().distance(Point::new(PI, 4.712364081)) < 1e-9);
    assert!(l[1].end_point().distance(Point::new(PI, 6.283160408)) < 1e-9);
}

// --- surfaces, B-rep mode, shells and solids ------------------------------------------------

use rs_geom::Point3;
use rs_geom::brep::FaceError;
use rs_geom::surface::ParamSurface;
use rs_io::cad::iges::IgesError;

/// A file of `fixtures/cad/iges/`.
fn fixture(name: &str) -> CadModel {
    let path = format!(
        "{}/../../fixtures/cad/iges/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    read_iges(&std::fs::read(&path).unwrap()).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// `[x, y, z]` as a point.
fn p3(v: [f64; 3]) -> Point3 {
    Point3::new(v[0], v[1], v[2])
}

/// The surface of face `k`, or a panic with the reason.
fn surface(m: &CadModel, k: usize) -> &rs_geom::Surface {
    let f = &m.faces[k];
    f.surface
        .as_ref()
        .unwrap_or_else(|| panic!("face {k}: no surface: {:?}", f.surface_error))
}

/// Asserts that face `k`'s surface is `formula` at a grid of `(u, v)` in `[u0, u1] x [v0, v1]`,
/// within `tol`.
fn assert_surface(
    m: &CadModel,
    k: usize,
    (u0, u1, v0, v1): (f64, f64, f64, f64),
    formula: impl Fn(f64, f64) -> [f64; 3],
    tol: f64,
) {
    let s = surface(m, k);
    for i in 0..=6 {
        for j in 0..=6 {
            let u = u0 + (u1 - u0) * f64::from(i) / 6.0;
            let v = v0 + (v1 - v0) * f64::from(j) / 6.0;
            let got = s.point([u, v]);
            let want = p3(formula(u, v));
            assert!(
                got.distance(want) <= tol,
                "face {k} at ({u}, {v}): {got:?}, formula {want:?}"
            );
        }
    }
}

/// The distance from `x` to the 3-D edge `e` (its closest point in its window).
fn distance_to_edge(x: Point3, e: &rs_geom::brep::Edge) -> f64 {
    let t = e.curve.closest_parameter(x, Some(e.range));
    e.curve.point(t).distance(x)
}

/// For every face of `m` with a surface and 3-D edges, how far its pcurves are from its edges:
/// the largest distance from `S(c(t))` to the nearest edge of its loop (9 parameters of each
/// curve `c`), and the largest over the edges of the distance by which the best of the loop's
/// pcurves misses being the edge's image in the loop's direction (`S` at the pcurve's start at
/// the edge's start, at its end at the edge's end, at its middle on the edge). Returns the
/// number of faces measured and the two distances.
fn pcurve_edge_deviation(m: &CadModel) -> (usize, f64, f64) {
    let (mut faces, mut on_edges, mut as_images) = (0, 0.0f64, 0.0f64);
    for f in &m.faces {
        let (Ok(loops), Some(s)) = (&f.loops, &f.surface) else {
            continue;
        };
        if f.edges.iter().all(Vec::is_empty) {
            continue;
        }
        for (curves, edges) in loops.iter().zip(&f.edges) {
            if edges.is_empty() {
                continue;
            }
            let on_surface = |c: &NurbsCurve, s_: f64| {
                let (a, b) = c.param_range();
                let q = c.point_at(a + (b - a) * s_);
                s.point([q.x, q.y])
            };
            for c in curves {
                for j in 0..=8 {
                    let x = on_surface(c, f64::from(j) / 8.0);
                    let d = edges
                        .iter()
                        .map(|e| distance_to_edge(x, e))
                        .fold(f64::INFINITY, f64::min);
                    on_edges = on_edges.max(d);
                }
            }
            for e in edges {
                let (start, end) = e.ends();
                let miss = curves
                    .iter()
                    .map(|c| {
                        on_surface(c, 0.0)
                            .distance(start)
                            .max(on_surface(c, 1.0).distance(end))
                            .max(distance_to_edge(on_surface(c, 0.5), e))
                    })
                    .fold(f64::INFINITY, f64::min);
                as_images = as_images.max(miss);
            }
        }
        faces += 1;
    }
    (faces, on_edges, as_images)
}

/// Asserts that [`pcurve_edge_deviation`] is within `tol` for `faces` faces of `m`.
fn assert_pcurves_on_edges(m: &CadModel, name: &str, faces: usize, tol: f64) {
    let (n, on_edges, as_images) = pcurve_edge_deviation(m);
    assert_eq!(n, faces, "{name}: faces with a surface and edges");
    assert!(
        on_edges <= tol && as_images <= tol,
        "{name}: pcurves {on_edges:e} off the edges, edges {as_images:e} off the pcurves' images (tolerance {tol:e})"
    );
}

/// The error of face `k`, typed.
fn face_iges_err(m: &CadModel, k: usize) -> IgesError {
    match &m.faces[k].loops {
        Err(FaceError::Read(e)) => {
            e.0.downcast_ref::<IgesError>()
                .unwrap_or_else(|| panic!("face {k}: not an IgesError: {e}"))
                .clone()
        }
        other => panic!("face {k}: {other:?}"),
    }
}

/// The cube with a spherical void of `python/tests/cad_parts.py`, written by Open CASCADE 8.0 in
/// IGES B-rep mode: one solid of two shells, the void's written with `VOF = 0` and read
/// reversed, as Open CASCADE reads it (`TopAbs_REVERSED` shell and face); the six 190 planes
/// have no pcurves (their loops are their edges mapped into the planes), the sphere's loop is
/// its seam twice and its two poles, in degrees.
#[test]
fn brep_box_with_a_void_is_one_solid_of_two_shells() {
    let m = fixture("box_void_brep.igs");
    assert_eq!(m.faces.len(), 7);
    assert_eq!(m.solids.len(), 1);
    assert_eq!(m.solids[0].entity, "DE 1");
    assert_eq!(m.solids[0].shells, [0, 1]);
    assert_eq!(m.shells.len(), 2);
    assert_eq!(m.shells[0].faces, [0, 1, 2, 3, 4, 5]);
    assert_eq!(m.shells[1].faces, [6]);
    assert!(m.shells.iter().all(|s| s.closed));
    assert_eq!(m.shells[1].entity, "DE 109");
    // OpenCASCADE's face orientations (TopAbs_FORWARD / REVERSED after reading the file):
    // the 514's flags, the void's face turned by its shell's.
    let occ = [false, true, false, true, false, true, false];
    for (k, f) in m.faces.iter().enumerate() {
        assert_eq!(f.same_sense, occ[k], "face {k}");
        assert!(f.loops.is_ok(), "face {k}: {:?}", f.loops);
    }
    assert_eq!(m.faces[6].surface_name, "196 (spherical surface)");
    // The void's outward normal (the solid's side) points to the sphere's centre.
    let s = surface(&m, 6);
    let (u, v) = (30.0, 20.0);
    let n = s.normal([u, v]).unwrap();
    let outward = if m.faces[6].same_sense { n } else { n * -1.0 };
    let radial = s.point([u, v]) - p3([0.0, 0.0, 0.0]);
    assert!(outward.dot(radial) < 0.0, "{outward:?} {radial:?}");
    // The sphere: the rectangle [0, 360] x [-90, 90] (degrees) of two seams and two poles.
    let l = &loops(&m, 6)[0];
    assert_eq!(l.len(), 4);
    assert!(close(area(l).abs(), 360.0 * 180.0, 1e-9));
    // The planes: squares of side 4 in (u, v).
    for k in 0..6 {
        assert!(close(area(&loops(&m, k)[0]).abs(), 16.0, 1e-12), "face {k}");
    }
    assert_pcurves_on_edges(&m, "box_void_brep", 7, 1e-7);
    // The planes' loops are their edges mapped exactly, the sphere's the file's: none fitted.
    assert!(m.faces.iter().all(|f| f.pcurve_deviation.is_none()));
    assert_eq!(m.length_unit.as_ref().map(|u| u.millimetres), Some(1.0));
}

/// The frustum with a spherical dimple in IGES B-rep mode: the 194 cone (slant `v`, degrees),
/// the 196 sphere cap through its south pole (the pole's own pcurve closes the loop), the 190
/// plane (a circle of radius 2 mapped from its edge), against the formulas of the research
/// notes (b.1) from the file's numbers; orientations as Open CASCADE's (cone forward, cap and
/// plane reversed).
#[test]
fn brep_cone_sphere_and_plane_follow_the_formulas() {
    let m = fixture("cone_minus_sphere_brep.igs");
    assert_eq!(m.faces.len(), 3);
    assert_eq!(
        m.faces.iter().map(|f| f.same_sense).collect::<Vec<_>>(),
        [true, false, false]
    );
    let deg = PI / 180.0;
    // 194: P = 0, A = (0, 0, -1), R = 2, a = 26.565051177 degrees, X = (1, 0, 0); Y = A x X.
    let a = 26.565051177 * deg;
    let cone = |u: f64, v: f64| {
        let r = 2.0 + v * a.sin();
        let (c, s) = (u * deg).cos_sin_pair();
        [r * c, -r * s, -v * a.cos()]
    };
    assert_surface(&m, 0, (-360.0, 0.0, -2.464155891, 0.0), cone, 1e-14);
    // 196: C = (0, 0, 3), R = 1.2, A = z, X = x.
    let sphere = |u: f64, v: f64| {
        let (c, s) = (u * deg).cos_sin_pair();
        let (cv, sv) = (v * deg).cos_sin_pair();
        [1.2 * cv * c, 1.2 * cv * s, 3.0 + 1.2 * sv]
    };
    assert_surface(&m, 1, (0.0, 360.0, -90.0, -41.554077477), sphere, 1e-14);
    assert_surface(&m, 2, (-2.0, 2.0, -2.0, 2.0), |u, v| [u, v, 0.0], 0.0);
    // The cone's loop: the rectangle [-360, 0] x [-2.464155891, 0] of its two circles and its
    // seam twice.
    let cone_loop = &loops(&m, 0)[0];
    assert_closed(cone_loop, 1e-12, "cone");
    assert!(close(area(cone_loop).abs(), 360.0 * 2.464155891, 1e-9));
    // The cap: circle, seam, the pole's segment at v = -90, seam.
    let cap = &loops(&m, 1)[0];
    assert_eq!(cap.len(), 4);
    assert_eq!(cap[2].start_point(), Point::new(0.0, -90.0));
    assert_eq!(cap[2].end_point(), Point::new(360.0, -90.0));
    assert!(close(area(cap).abs(), 360.0 * (90.0 - 41.554077477), 1e-9));
    // The plane: one circle of radius 2 about its origin.
    let disc = &loops(&m, 2)[0];
    assert_eq!(disc.len(), 1);
    assert!(close(area(disc).abs(), 4.0 * PI, 1e-12));
    assert_pcurves_on_edges(&m, "cone_minus_sphere_brep", 3, 1e-7);
}

/// `(cos x, sin x)`.
trait CosSin {
    fn cos_sin_pair(self) -> (f64, f64);
}

impl CosSin for f64 {
    fn cos_sin_pair(self) -> (f64, f64) {
        (self.cos(), self.sin())
    }
}

/// The faces-mode torus: the 144's four seam pcurves meet only modulo the periods as written
/// (Open CASCADE re-orders them into its wire); the face is the whole `[0, 2 pi]^2`, not the
/// two slivers the pole bridges of the old reader made. Its surface (a 120 of a circle about
/// the tilted axis) is the torus of major radius 3 and minor radius 1 about (0.5, -1, 2).
#[test]
fn faces_mode_torus_is_the_whole_rectangle() {
    let m = fixture("torus.igs");
    assert_eq!(m.faces.len(), 1);
    let l = loops(&m, 0);
    assert_eq!(l.len(), 1);
    assert_eq!(l[0].len(), 4, "no bridges");
    assert!(l[0].iter().all(|c| c.degree() == 1));
    assert_closed(&l[0], 1e-9, "torus");
    assert!(close(area(&l[0]).abs(), 4.0 * PI * PI, 1e-8));
    let s = surface(&m, 0);
    let centre = p3([0.5, -1.0, 2.0]);
    let axis = p3([1.0, 1.0, 1.0]) * (1.0 / 3f64.sqrt());
    for i in 0..12 {
        for j in 0..12 {
            let uv = [f64::from(i) * 0.5, f64::from(j) * 0.5];
            let d = s.point(uv) - centre;
            let h = d.dot(axis);
            let rho = (d - axis * h).length();
            // (rho - 3)^2 + h^2 = 1 on the torus, to the file's ten printed digits.
            assert!(
                ((rho - 3.0).powi(2) + h * h - 1.0).abs() < 1e-8,
                "{uv:?} {rho} {h}"
            );
        }
    }
    assert_eq!(m.faces[0].edges.len(), 1);
    assert_eq!(m.faces[0].edges[0].len(), 4);
    assert_pcurves_on_edges(&m, "torus", 1, 1e-7);
}

/// The largest coordinate of the model's edges (its size, for the coincidence tolerance).
fn model_size(m: &CadModel) -> f64 {
    m.faces
        .iter()
        .flat_map(|f| f.edges.iter().flatten())
        .flat_map(|e| e.sample(5))
        .fold(0.0, |s, p| s.max(p.max_abs()))
}

/// On every face of the Idf library's IGES files the pcurves lie on the 3-D edges of their
/// 142s (`S(c(t))` within the model's coincidence tolerance: the file's tolerance, or the ten
/// digits the files print), and each edge is the image of one of its loop's pcurves, in the
/// loop's direction.
#[test]
fn idf_pcurves_lie_on_their_edges() {
    for (name, faces, _) in IDF_FILES {
        let path = format!("/usr/share/freecad/Mod/Idf/Idflibs/{name}.igs");
        let Some(bytes) = rs_testkit::system_file(&path, "freecad-common") else {
            return;
        };
        let m = read_iges(&bytes).unwrap();
        let tol = m.tolerance.coincidence(model_size(&m));
        assert_pcurves_on_edges(&m, name, faces, tol);
        // The Idf files are in inches (SOD_323 in millimetres).
        let mm = if name == "SOD_323" { 1.0 } else { 25.4 };
        assert_eq!(
            m.length_unit.as_ref().map(|u| u.millimetres),
            Some(mm),
            "{name}"
        );
    }
}

/// The Open CASCADE test parts of `python/tests/cad_parts.py`, in both IGES modes: faces,
/// solids and shells as Open CASCADE 8.0 reads them (its `TopExp_Explorer` counts).
const PARTS: [(&str, usize, usize, usize); 9] = [
    ("box_void", 7, 1, 2),
    ("bspline_box_hole", 7, 1, 1),
    ("bspline_two_holes", 1, 0, 0),
    ("cone_minus_sphere", 3, 1, 1),
    ("filleted_plate", 11, 1, 1),
    ("fused_cylinders", 7, 1, 1),
    ("revolved_bspline", 3, 1, 1),
    ("sphere", 1, 1, 1),
    ("torus", 1, 1, 1),
];

/// Every face of every IGES test part reads and makes a domain, with its surface and edges
/// (pcurves on the edges as for the Idf files); B-rep mode files have Open CASCADE's solids and
/// shells, faces mode files none. The parts are written by `python/tests/cad_parts.py`:
/// `python -c "import cad_parts; cad_parts.write_parts('DIR')"` in `python/tests` (with
/// OCP), then `INRS_CAD_PARTS=DIR cargo test -p rs-io --test cad_iges -- --ignored`, as
/// `.ci/run` does once OCP is installed; the parts in `fixtures/cad/iges/` are read by the
/// other tests.
#[test]
#[ignore = "needs the OCC test parts in INRS_CAD_PARTS: .ci/run writes them and runs it"]
fn every_iges_test_part_reads() {
    let dir = std::env::var("INRS_CAD_PARTS")
        .expect("INRS_CAD_PARTS names the directory of cad_parts.write_parts");
    for (name, faces, solids, shells) in PARTS {
        for brep in [false, true] {
            let file = format!("{name}{}.igs", if brep { "_brep" } else { "" });
            let path = format!("{dir}/{file}");
            let m = read_iges(&std::fs::read(&path).unwrap_or_else(|e| panic!("{path}: {e}")))
                .unwrap_or_else(|e| panic!("{file}: {e}"));
            assert_eq!(m.faces.len(), faces, "{file}");
            let (solids, shells) = if brep { (solids, shells) } else { (0, 0) };
            assert_eq!((m.solids.len(), m.shells.len()), (solids, shells), "{file}");
            for (k, f) in m.faces.iter().enumerate() {
                assert!(
                    f.surface.is_some(),
                    "{file} face {k}: {:?}",
                    f.surface_error
                );
                m.face_domain(k, None)
                    .unwrap_or_else(|e| panic!("{file} face {k}: {e}"));
            }
            let tol = m.tolerance.coincidence(model_size(&m));
            assert_pcurves_on_edges(&m, &file, faces, tol);
        }
    }
}

/// A one-face file: a 144 (DE 1) bounded by the rectangle `[u0, u1] x [v0, v1]` in `(u, v)`
/// (142 DE 3, 102 DE 5, lines DE 7 to 13) on the surface DE 15, the first entity of `surface`.
fn rect_face((u0, u1, v0, v1): (f64, f64, f64, f64), surface: Vec<Ent>) -> CadModel {
    let line = |a: (f64, f64), b: (f64, f64)| {
        sub(
            110,
            &format!("110,{:?},{:?},0.,{:?},{:?},0.;", a.0, a.1, b.0, b.1),
        )
    };
    let mut ents = vec![
        root(144, "144,15,1,0,3;"),
        sub(142, "142,0,15,5,0,1;"),
        sub(102, "102,4,7,9,11,13;"),
        line((u0, v0), (u1, v0)),
        line((u1, v0), (u1, v1)),
        line((u1, v1), (u0, v1)),
        line((u0, v1), (u0, v0)),
    ];
    ents.extend(surface);
    read(&iges(&ents, "1.E-07"))
}

/// `a x b`.
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `sum of c_i v_i`.
fn comb(terms: &[(f64, [f64; 3])]) -> [f64; 3] {
    let mut out = [0.0; 3];
    for (c, v) in terms {
        for i in 0..3 {
            out[i] += c * v[i];
        }
    }
    out
}

/// The elementary surfaces 190 to 198 (forms 1 and 0) and 120, 122, 128, 140 against IGES
/// 5.3's parameterisations as Open CASCADE writes and reads them (research notes b.1: angles
/// of 192 to 198 in degrees, the cone's `v` along the slant, form 0's reference direction
/// Open CASCADE's `gp_Ax2` default), each formula written out here from the entity's numbers,
/// a 124 placing the cylinder. The rectangle loop reads on each (in the file's own `(u, v)`).
#[test]
fn surfaces_follow_the_iges_parameterisations() {
    let deg = PI / 180.0;
    let (sqrt2, tol) = (SQRT_2, 1e-13);
    // 192 form 1 with a non-unit axis, a reference direction of length sqrt 2 and a 124: a
    // quarter turn about z, then (10, 0, 0).
    let m = rect_face(
        (0.0, 90.0, 0.0, 5.0),
        vec![
            sub(192, "192,17,19,2.,21;").form(1).transform(23), // DE 15
            sub(116, "116,1.,2.,3.,0;"),                        // DE 17
            sub(123, "123,0.,0.,2.;"),                          // DE 19
            sub(123, "123,1.,1.,0.;"),                          // DE 21
            sub(124, "124,0.,-1.,0.,10.,1.,0.,0.,0.,0.,0.,1.,0.;"), // DE 23
        ],
    );
    let (a, x) = ([0.0, 0.0, 1.0], [1.0 / sqrt2, 1.0 / sqrt2, 0.0]);
    let y = cross(a, x);
    let cylinder = |u: f64, v: f64| {
        let q = comb(&[
            (1.0, [1.0, 2.0, 3.0]),
            (2.0 * (u * deg).cos(), x),
            (2.0 * (u * deg).sin(), y),
            (v, a),
        ]);
        [10.0 - q[1], q[0], q[2]]
    };
    assert_surface(&m, 0, (0.0, 90.0, 0.0, 5.0), cylinder, tol);
    assert!(close(area(&loops(&m, 0)[0]).abs(), 450.0, 1e-12));
    assert_eq!(
        m.faces[0].surface_name,
        "192 (right circular cylindrical surface)"
    );
    // 192 form 0 about -z: Open CASCADE's reference direction (-1, 0, 0).
    let m = rect_face(
        (0.0, 90.0, 0.0, 1.0),
        vec![
            sub(192, "192,17,19,2.;"),   // DE 15
            sub(116, "116,0.,0.,0.,0;"), // DE 17
            sub(123, "123,0.,0.,-1.;"),  // DE 19
        ],
    );
    let down = |u: f64, v: f64| {
        // X = (-1, 0, 0), Y = A x X = (0, 1, 0).
        let (c, s) = ((u * deg).cos(), (u * deg).sin());
        [-2.0 * c, 2.0 * s, -v]
    };
    assert_surface(&m, 0, (0.0, 90.0, 0.0, 1.0), down, tol);
    // 194 form 1: radius 1 at P, semi-angle 30 degrees, v along the slant.
    let m = rect_face(
        (0.0, 360.0, 0.0, 2.0),
        vec![
            sub(194, "194,17,19,1.,30.,21;").form(1), // DE 15
            sub(116, "116,0.,0.,1.,0;"),              // DE 17
            sub(123, "123,0.,0.,1.;"),                // DE 19
            sub(123, "123,1.,0.,0.;"),                // DE 21
        ],
    );
    let cone = |u: f64, v: f64| {
        let r = 1.0 + v * (30.0 * deg).sin();
        [
            r * (u * deg).cos(),
            r * (u * deg).sin(),
            1.0 + v * (30.0 * deg).cos(),
        ]
    };
    assert_surface(&m, 0, (0.0, 360.0, 0.0, 2.0), cone, tol);
    // 196 form 0: no axis, the world's.
    let m = rect_face(
        (0.0, 360.0, -90.0, 90.0),
        vec![sub(196, "196,17,3.;"), sub(116, "116,1.,1.,1.,0;")],
    );
    let sphere = |u: f64, v: f64| {
        let (cu, su, cv, sv) = (
            (u * deg).cos(),
            (u * deg).sin(),
            (v * deg).cos(),
            (v * deg).sin(),
        );
        [1.0 + 3.0 * cv * cu, 1.0 + 3.0 * cv * su, 1.0 + 3.0 * sv]
    };
    assert_surface(&m, 0, (0.0, 360.0, -90.0, 90.0), sphere, tol);
    // 198 form 1 about x, reference direction y.
    let m = rect_face(
        (0.0, 360.0, 0.0, 360.0),
        vec![
            sub(198, "198,17,19,4.,1.,21;").form(1), // DE 15
            sub(116, "116,0.,0.,0.,0;"),             // DE 17
            sub(123, "123,1.,0.,0.;"),               // DE 19
            sub(123, "123,0.,1.,0.;"),               // DE 21
        ],
    );
    let torus = |u: f64, v: f64| {
        // A = x, X = y, Y = A x X = z.
        let r = 4.0 + (v * deg).cos();
        [(v * deg).sin(), r * (u * deg).cos(), r * (u * deg).sin()]
    };
    assert_surface(&m, 0, (0.0, 360.0, 0.0, 360.0), torus, tol);
    // 190 form 0 and a 140 offset of it by 0.5 along its normal z.
    let m = rect_face(
        (-1.0, 1.0, -1.0, 1.0),
        vec![
            sub(140, "140,0.,0.,1.,0.5,17;"), // DE 15
            sub(190, "190,19,21;"),           // DE 17
            sub(116, "116,0.,0.,0.,0;"),      // DE 19
            sub(123, "123,0.,0.,1.;"),        // DE 21
        ],
    );
    assert_surface(&m, 0, (-1.0, 1.0, -1.0, 1.0), |u, v| [u, v, 0.5], tol);
    // 120: the segment (1, 0, 0)-(2, 0, 3) turned about the z axis; u along the segment, v the
    // angle, right-handed about the axis line from its start to its end.
    let m = rect_face(
        (0.0, 1.0, 0.0, 2.0 * PI),
        vec![
            sub(120, "120,17,19,0.,6.283185307179586;"), // DE 15
            sub(110, "110,0.,0.,0.,0.,0.,1.;"),          // DE 17
            sub(110, "110,1.,0.,0.,2.,0.,3.;"),          // DE 19
        ],
    );
    let revolution = |t: f64, a: f64| [(1.0 + t) * a.cos(), (1.0 + t) * a.sin(), 3.0 * t];
    assert_surface(&m, 0, (0.0, 1.0, 0.0, 2.0 * PI), revolution, tol);
    // 122: the quarter circle (cos t, sin t), t in [0, pi / 2], swept to (1, 0, 3); u is the
    // directrix's parameter normalised to [0, 1].
    let m = rect_face(
        (0.0, 1.0, 0.0, 1.0),
        vec![
            sub(122, "122,17,1.,0.,3.;"),          // DE 15
            sub(100, "100,0.,0.,0.,1.,0.,0.,1.;"), // DE 17
        ],
    );
    let tabulated = |u: f64, v: f64| [(u * PI / 2.0).cos(), (u * PI / 2.0).sin(), 3.0 * v];
    assert_surface(&m, 0, (0.0, 1.0, 0.0, 1.0), tabulated, tol);
    // 128: a bilinear patch P00 = 0, P10 = (2, 0, 0), P01 = (0, 1, 0), P11 = (2, 1, 1), listed
    // with the first index fastest: S(u, v) = (2 u, v, u v).
    let m = rect_face(
        (0.0, 1.0, 0.0, 1.0),
        vec![sub(
            128,
            "128,1,1,1,1,0,0,1,0,0,0.,0.,1.,1.,0.,0.,1.,1.,1.,1.,1.,1.,0.,0.,0.,2.,0.,0.,\
             0.,1.,0.,2.,1.,1.,0.,1.,0.,1.;",
        )],
    );
    assert_surface(&m, 0, (0.0, 1.0, 0.0, 1.0), |u, v| [2.0 * u, v, u * v], tol);
    assert_eq!(
        m.length_unit
            .as_ref()
            .map(|u| (u.name.as_str(), u.millimetres)),
        Some(("MM", 1.0))
    );
}

/// Hostile B-rep and surface data: each a face error or a surface error with a one-line
/// message, or a file read without the broken structure, in bounded time, never a panic.
#[test]
fn hostile_surfaces_shells_and_loops() {
    let t = Instant::now();
    // A zero axis direction: the surface is refused, the loop (given in (u, v)) still reads.
    let m = rect_face(
        (0.0, 90.0, 0.0, 1.0),
        vec![
            sub(192, "192,17,19,2.,21;").form(1), // DE 15
            sub(116, "116,0.,0.,0.,0;"),          // DE 17
            sub(123, "123,0.,0.,0.;"),            // DE 19
            sub(123, "123,1.,0.,0.;"),            // DE 21
        ],
    );
    assert!(m.faces[0].surface.is_none());
    let e = m.faces[0].surface_error.as_ref().unwrap().to_string();
    assert!(e.contains("DE 15") && e.contains("degenerate axes"), "{e}");
    assert_eq!(loops(&m, 0)[0].len(), 4);
    // An offset surface whose base is itself.
    let m = rect_face((0.0, 1.0, 0.0, 1.0), vec![sub(140, "140,0.,0.,1.,0.5,15;")]);
    let e = m.faces[0].surface_error.as_ref().unwrap().to_string();
    assert!(e.contains("nested") || e.contains("work limit"), "{e}");
    // Pcurves far outside the box of a (non-periodic) B-spline surface: a closed loop reads as
    // it is; a loop with gaps there is not bridged (every point of the segment would clamp to
    // one corner of the patch), it is refused naming its pieces.
    let far = 1e6;
    let m = rect_face((far, far + 1.0, far, far + 1.0), vec![unit_square_128()]);
    assert!(close(area(&loops(&m, 0)[0]).abs(), 1.0, 1e-6));
    let ents = vec![
        root(144, "144,9,1,0,3;"),  // DE 1
        sub(142, "142,0,9,5,0,1;"), // DE 3
        sub(102, "102,2,7,11;"),    // DE 5
        sub(
            110,
            &format!("110,{far:?},{far:?},0.,{:?},{far:?},0.;", far + 1.0),
        ), // DE 7
        unit_square_128(),          // DE 9
        sub(
            110,
            &format!(
                "110,{:?},{:?},0.,{far:?},{:?},0.;",
                far + 1.0,
                far + 2.0,
                far + 3.0
            ),
        ), // DE 11
    ];
    let m = read(&iges(&ents, "1.E-07"));
    let e = face_iges_err(&m, 0);
    assert!(
        matches!(
            e,
            IgesError::Gap {
                named: 5,
                first: 7,
                second: 11,
                ..
            }
        ),
        "{e}"
    );
    // A 186 whose shell is missing (pointer 0), one whose shell is a line, one listing itself
    // as its shell, a group holding itself: no solid, no shell, no face, no panic; the lone 510
    // after them (physically dependent, held by nothing) is a face, as Open CASCADE reads it.
    let ents = vec![
        root(186, "186,0,1,0;"),            // DE 1
        root(186, "186,7,1,0;"),            // DE 3
        root(186, "186,5,1,0;"),            // DE 5
        sub(110, "110,0.,0.,0.,1.,0.,0.;"), // DE 7
        root(402, "402,1,9;").form(7),      // DE 9
        sub(510, "510,13,1,1,15;").form(1), // DE 11
        unit_square_128(),                  // DE 13
        // DE 15: the unit square's loop, its pcurves given, the edges of the 504 DE 17.
        sub(
            508,
            "508,4,0,17,1,1,1,0,19,0,17,2,1,1,0,21,0,17,3,1,1,0,23,0,17,4,1,1,0,25;",
        )
        .form(1),
        sub(504, "504,4,19,0,0,0,0,21,0,0,0,0,23,0,0,0,0,25,0,0,0,0;").form(1), // DE 17
        sub(110, "110,0.,0.,0.,1.,0.,0.;"),                                     // DE 19
        sub(110, "110,1.,0.,0.,1.,1.,0.;"),                                     // DE 21
        sub(110, "110,1.,1.,0.,0.,1.,0.;"),                                     // DE 23
        sub(110, "110,0.,1.,0.,0.,0.,0.;"),                                     // DE 25
    ];
    let m = read(&iges(&ents, "1.E-07"));
    assert_eq!((m.solids.len(), m.shells.len()), (0, 0));
    assert_eq!(m.faces.len(), 1);
    assert_eq!(m.faces[0].entity, "DE 11");
    assert!(close(area(&loops(&m, 0)[0]), 1.0, 1e-15));
    // The edges are the 504's model curves (here the pcurves' lines in z = 0, on the patch).
    assert_eq!(m.faces[0].edges[0].len(), 4);
    assert_pcurves_on_edges(&m, "square", 1, 1e-15);
    // A 508 use of an edge the 504 does not have, of an unknown type, and one without a
    // parameter-space curve on a curved surface whose model curve is off the surface (the
    // straight line (0, 0, 0)-(1, 0, 0) under a patch bulging to z = 0.5 along it).
    for (loop_params, want) in [
        (
            "508,1,0,17,9,1,1,0,19;",
            "edge 9 of the 504 edge list DE 17, which has 4",
        ),
        (
            "508,1,2,17,1,1,1,0,19;",
            "type 2 (expected 0 (edge) or 1 (vertex))",
        ),
    ] {
        let mut bad = ents.clone_ents();
        bad[7] = sub(508, loop_params).form(1);
        let e = face_err(&read(&iges(&bad, "1.E-07")), 0);
        assert!(e.contains(want), "{e}");
    }
    let mut curved = ents.clone_ents();
    curved[6] = curved_128();
    curved[7] = sub(508, "508,1,0,17,1,1,0;").form(1);
    let e = face_iges_err(&read(&iges(&curved, "1.E-07")), 0);
    assert!(
        matches!(
            &e,
            IgesError::Geometry { who, source: rs_geom::GeomError::EdgeOffSurface { .. } }
                if who.starts_with("DE 19")
        ),
        "{e}"
    );
    assert!(t.elapsed() < Duration::from_secs(10));
}

/// Copies of hand-written entity lists.
trait CloneEnts {
    fn clone_ents(&self) -> Vec<Ent>;
}

impl CloneEnts for Vec<Ent> {
    fn clone_ents(&self) -> Vec<Ent> {
        self.iter()
            .map(|e| Ent {
                kind: e.kind,
                form: e.form,
                params: e.params.clone(),
                transform: e.transform,
                status: e.status,
            })
            .collect()
    }
}

/// The quarter cylinder `x^2 + y^2 = 4`, `0 <= z <= 3`, `x, y >= 0`, bounded by model-space
/// curves only (a 142 without a parameter-space curve, and a 508 of four edges without
/// pcurves, two of them used against their curves): the pcurves are computed (iso-lines of the
/// 192 cylinder: exact, in degrees), the face is the rectangle `[0, 90] x [0, 3]`, its
/// deviation recorded.
#[test]
fn model_space_curves_on_curved_surfaces_get_computed_pcurves() {
    // The cylinder of radius 2 about z (DE 15) with its point, axis and reference direction.
    let cylinder = || {
        vec![
            sub(192, "192,17,19,2.,21;").form(1), // DE 15
            sub(116, "116,0.,0.,0.,0;"),          // DE 17
            sub(123, "123,0.,0.,1.;"),            // DE 19
            sub(123, "123,1.,0.,0.;"),            // DE 21
        ]
    };
    let w = SQRT_2 / 2.0;
    let quarter_at_3 = format!(
        "126,2,2,1,0,0,0,0.,0.,0.,1.,1.,1.,1.,{w},1.,0.,2.,3.,2.,2.,3.,2.,0.,3.,0.,1.,0.,0.,1.;"
    );
    // Faces mode: 144 (DE 1) -> 142 (DE 3) without BPTR -> 102 (DE 5): the arc at z = 0
    // counter-clockwise, the line up, the arc at z = 3 back, the line down.
    let mut ents = vec![
        root(144, "144,15,1,0,3;"),            // DE 1
        sub(142, "142,0,15,0,5,2;"),           // DE 3
        sub(102, "102,4,7,9,11,13;"),          // DE 5
        sub(100, "100,0.,0.,0.,2.,0.,0.,2.;"), // DE 7
        sub(110, "110,0.,2.,0.,0.,2.,3.;"),    // DE 9
        sub(126, &quarter_at_3),               // DE 11
        sub(110, "110,2.,0.,3.,2.,0.,0.;"),    // DE 13
    ];
    ents.extend(cylinder());
    let m = read(&iges(&ents, "1.E-07"));
    let check = |m: &CadModel, what: &str| {
        let l = loops(m, 0);
        assert_eq!(l.len(), 1, "{what}");
        assert_closed(&l[0], 1e-9, what);
        assert!(
            close(area(&l[0]).abs(), 270.0, 1e-9),
            "{what}: {}",
            area(&l[0])
        );
        let d = m.faces[0].pcurve_deviation.expect("computed pcurves");
        assert!(d <= 1e-12, "{what}: deviation {d:e}");
        assert_pcurves_on_edges(m, what, 1, 1e-12);
    };
    check(&m, "faces mode");
    // B-rep mode: 510 (DE 1) -> 508 (DE 3) of the 504 (DE 5) edges: the arc at z = 0, the
    // line up, the arc at z = 3 counter-clockwise (used backwards), the line from the bottom
    // up at x = 2 (used backwards).
    let mut ents = vec![
        sub(510, "510,15,1,1,3;").form(1), // DE 1
        sub(508, "508,4,0,5,1,1,0,0,5,2,1,0,0,5,3,0,0,0,5,4,0,0;").form(1), // DE 3
        sub(504, "504,4,7,0,0,0,0,9,0,0,0,0,11,0,0,0,0,13,0,0,0,0;").form(1), // DE 5
        sub(100, "100,0.,0.,0.,2.,0.,0.,2.;"), // DE 7
        sub(110, "110,0.,2.,0.,0.,2.,3.;"), // DE 9
        sub(100, "100,3.,0.,0.,2.,0.,0.,2.;"), // DE 11
        sub(110, "110,2.,0.,0.,2.,0.,3.;"), // DE 13
    ];
    ents.extend(cylinder());
    let m = read(&iges(&ents, "1.E-07"));
    check(&m, "B-rep mode");
    assert_eq!(
        m.faces[0].edges[0]
            .iter()
            .map(|e| e.reversed)
            .collect::<Vec<_>>(),
        [false, false, true, true]
    );
}
