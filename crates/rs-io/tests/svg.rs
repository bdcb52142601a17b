//! SVG path data and documents against analytic answers: areas, exact conics, the equivalence
//! of absolute/relative/shorthand forms, transforms, and error messages.

use rs_spline::prelude::*;
use std::f64::consts::PI;

use rs_io::IoError;
use rs_io::svg::{curves_from_path_data, domain_from_path_data, domain_from_svg_str};
use rs_spline::{NurbsCurve, Point};

fn area(d: &str) -> f64 {
    domain_from_path_data(d).unwrap().signed_area()
}

fn same_curves(a: &[NurbsCurve], b: &[NurbsCurve]) {
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(b) {
        assert_eq!(x.degree(), y.degree());
        for i in 0..=20 {
            let u = i as f64 / 20.0;
            assert!(
                x.point_at(u).distance(y.point_at(u)) < 1e-12,
                "{x:?} vs {y:?}"
            );
        }
    }
}

#[test]
fn absolute_relative_and_shorthand_forms_draw_the_same_curves() {
    let forms = [
        // Absolute, explicit.
        "M 10 10 L 30 10 C 40 10 40 20 30 20 C 20 20 20 30 30 30 Q 40 40 30 50 Q 20 60 10 50 \
         A 5 10 30 0 1 10 40 L 10 10 Z",
        // Relative with shorthand: H, S (reflects the previous cubic's control), T, and a
        // relative arc.
        "m10 10h20c10 0 10 10 0 10s-10 10 0 10q10 10 0 20t-20 0a5 10 30 0 1 0-10z",
        // Compact numbers, commas, implicit command repetition, no separators after flags.
        "M10,10H30C40,10,40,20,30,20S20,30,30,30Q40,40,30,50T10,50A5,10,30,0,1,10,40Z",
    ];
    let reference = curves_from_path_data(forms[0]).unwrap();
    assert_eq!(reference.len(), 7);
    for f in &forms[1..] {
        same_curves(&reference, &curves_from_path_data(f).unwrap());
    }
}

#[test]
fn number_grammar_edge_cases() {
    // ".5.5" is two numbers, "1-2" too, exponents, a leading '+', and an implicit lineto
    // after a moveto with several pairs.
    let a = curves_from_path_data("M0,0 1e1,0 10-1e1 .5.5z").unwrap();
    let b = curves_from_path_data("M 0 0 L 10 0 L 10 -10 L 0.5 0.5 Z").unwrap();
    same_curves(&a, &b);
    let c = curves_from_path_data("m+0 0 l 10 0 0 -10 z").unwrap();
    assert_eq!(c.len(), 3);
    // Flags without separators: "a1 1 0 00 1 0".
    let d = curves_from_path_data("M0 0a1 1 0 00 2 0a1 1 0 00-2 0").unwrap();
    assert_eq!(d.len(), 2);
}

#[test]
fn areas_of_analytic_shapes() {
    // Rectangle (clockwise in y-up terms gives a negative area).
    assert!((area("M0 0 H3 V2 H0 Z") - 6.0).abs() < 1e-14);
    assert!((area("M0 0 V2 H3 V0 Z") + 6.0).abs() < 1e-14);
    // A circle of radius 2 as two half arcs: exact conics, so exact area.
    assert!((area("M2 0 A2 2 0 0 1 -2 0 A2 2 0 0 1 2 0Z") - 4.0 * PI).abs() < 1e-12);
    // A full ellipse rotated by 30 degrees, radii 3 and 1: area 3 pi.
    let e = "M0 0 A3 1 30 1 1 1 1 A3 1 30 0 1 0 0 Z";
    assert!((area(e).abs() - 3.0 * PI).abs() < 1e-12);
    // A cubic and its chord: x = 9t^2 - 6t^3, y = 9t(1 - t), so the area is
    // int y dx = 162 int t^2 (1 - t)^2 dt = 5.4, traversed clockwise. Also against a dense
    // polygon.
    let d = domain_from_path_data("M0 0 C0 3 3 3 3 0 Z").unwrap();
    let pts: Vec<Point> = (0..=20000)
        .map(|i| d.curves()[0].point_at(i as f64 / 20000.0))
        .collect();
    let shoelace: f64 = 0.5 * pts.windows(2).map(|w| w[0].cross(w[1])).sum::<f64>();
    assert!((d.signed_area() - shoelace).abs() < 1e-7);
    assert!(
        (d.signed_area() + 1.8 * 3.0).abs() < 1e-12,
        "{}",
        d.signed_area()
    );
}

#[test]
fn arcs_are_exact_conics_through_the_given_end_points() {
    let curves = curves_from_path_data("M 1 7 A 4 2 -20 1 0 6 3").unwrap();
    let arc = &curves[0];
    assert_eq!(arc.degree(), 2);
    assert_eq!(arc.start_point(), Point::new(1.0, 7.0));
    assert_eq!(arc.end_point(), Point::new(6.0, 3.0));
    // In the frame rotated by -20 degrees the points satisfy
    // (x - cx)^2 / 16 + (y - cy)^2 / 4 = k^2 (radii 4 and 2, possibly scaled by k): linear in
    // (cx / 8, cy / 2, c0) given q = x^2 / 16 + y^2 / 4. Solve with three points, check all.
    let (s, c) = (-20f64).to_radians().sin_cos();
    let local = |p: Point| Point::new(c * p.x + s * p.y, -s * p.x + c * p.y);
    let samples: Vec<Point> = (0..=400)
        .map(|i| local(arc.point_at(i as f64 / 400.0)))
        .collect();
    let row = |p: Point| ([p.x, p.y, 1.0], -(p.x * p.x / 16.0 + p.y * p.y / 4.0));
    let rows = [row(samples[0]), row(samples[133]), row(samples[400])];
    let m = nalgebra::Matrix3::from_fn(|i, j| rows[i].0[j]);
    let rhs = nalgebra::Vector3::new(rows[0].1, rows[1].1, rows[2].1);
    let sol = m.lu().solve(&rhs).unwrap();
    for q in &samples {
        let residual = row(*q).0[0] * sol[0] + q.y * sol[1] + sol[2] - row(*q).1;
        assert!(residual.abs() < 1e-10, "{residual}");
    }
}

#[test]
fn malformed_path_data_reports_position_and_problem() {
    let cases = [
        ("L 1 1", 0, "moveto"),
        ("M 0 0 L 1", 9, "ends where a number"),
        ("M 0 0 X 1 1", 6, "unknown command"),
        ("M 0 0 L 1 x", 10, "expected a number"),
        ("M 0 0 A 1 1 0 2 0 1 1", 14, "arc flag"),
        ("M 0 0 Z 5 5", 8, "command letter"),
        ("M 0 0 L 1e999 0", 8, "out of range"),
    ];
    for (d, position, message) in cases {
        match curves_from_path_data(d) {
            Err(IoError::PathData {
                position: p,
                message: m,
            }) => {
                assert_eq!(p, position, "{d}: {m}");
                assert!(m.contains(message), "{d}: {m}");
            }
            other => panic!("{d}: {other:?}"),
        }
    }
    assert!(matches!(
        domain_from_path_data("M 0 0 L 5 5"),
        Err(IoError::Empty(_))
    ));
}

const DOC: &str = r##"<?xml version="1.0"?>
<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">
  <defs><path id="hidden-def" d="M0 0h1000v1000z"/></defs>
  <clipPath id="c"><rect width="500" height="500"/></clipPath>
  <g transform="translate(10 20) scale(2)">
    <rect x="0" y="0" width="10" height="5"/>
    <g transform="rotate(30)">
      <circle cx="20" cy="0" r="3"/>
    </g>
  </g>
  <rect x="50" y="50" width="20" height="10" rx="4" ry="2"/>
  <ellipse cx="80" cy="20" rx="5" ry="2" transform="skewX(10)"/>
  <polygon points="0,90 10,90 5,99"/>
  <path d="M 90 90 h 5 v 5 h -5 z" style="fill:red; display : none"/>
  <line x1="0" y1="0" x2="100" y2="100"/>
</svg>"##;

#[test]
fn svg_document_shapes_transforms_and_skipped_elements() {
    let d = domain_from_svg_str(DOC).unwrap();
    // rect, circle, rounded rect, ellipse, polygon: five loops.
    assert_eq!(d.loops().len(), 5);
    let areas: Vec<f64> = (0..5).map(|i| d.loop_signed_area(i).abs()).collect();
    // Scaled by 2: area x4. Rotation keeps the circle's area; skew keeps the ellipse's.
    let expected = [
        200.0,
        4.0 * PI * 9.0,
        20.0 * 10.0 - (4.0 - PI) * 4.0 * 2.0,
        PI * 10.0,
        45.0,
    ];
    for (a, e) in areas.iter().zip(expected) {
        assert!((a - e).abs() < 1e-10 * e, "{a} vs {e}");
    }
    // The circle's centre went through rotate(30), scale(2) and the translation.
    let circle_box = d.curves()[d.loops()[1].curves()].iter().fold(
        rs_spline::BoundingBox::from_point(d.curves()[4].start_point()),
        |b, c| b.union(c.bounding_box()),
    );
    let centre = (circle_box.min + circle_box.max) * 0.5;
    let (s, c) = 30f64.to_radians().sin_cos();
    let want = Point::new(10.0 + 2.0 * 20.0 * c, 20.0 + 2.0 * 20.0 * s);
    assert!(centre.distance(want) < 1e-9, "{centre:?} vs {want:?}");
    assert!(d.require_closed().is_ok());
}

#[test]
fn bad_documents_name_the_element_and_the_problem() {
    let e = domain_from_svg_str("<svg><path d='M0 0 L").unwrap_err();
    assert!(matches!(e, IoError::Xml(_)), "{e}");
    let e = domain_from_svg_str("<html/>").unwrap_err();
    assert!(e.to_string().contains("<html>"), "{e}");
    // Path data with an error is drawn up to it (as renderers draw it), and reported.
    let doc = "<svg xmlns='http://www.w3.org/2000/svg'>\n<g>\n<path id='p7' d='M0 0 L1 0 L1 1 Q'/>\n</g></svg>";
    let read = rs_io::svg::load_svg_str(doc, rs_io::svg::OpenSubpaths::Close).unwrap();
    assert_eq!(read.domain.curves().len(), 3);
    let w = read.warnings[0].to_string();
    assert!(
        w.contains("path id=\"p7\"") && w.contains("line 3") && w.contains("number"),
        "{w}"
    );
    assert_eq!(domain_from_svg_str(doc).unwrap().curves().len(), 3);
    let doc = "<svg xmlns='http://www.w3.org/2000/svg'><rect width='3em' height='1'/></svg>";
    let e = domain_from_svg_str(doc).unwrap_err().to_string();
    assert!(e.contains("rect") && e.contains("width"), "{e}");
    let doc = "<svg xmlns='http://www.w3.org/2000/svg'><g transform='rotate(1 2)'><rect width='1' height='1'/></g></svg>";
    let e = domain_from_svg_str(doc).unwrap_err().to_string();
    assert!(e.contains("<g>") && e.contains("rotate"), "{e}");
    // A singular transform flattens the shape: nothing with area is left.
    let doc = "<svg xmlns='http://www.w3.org/2000/svg'><rect width='2' height='1' transform='scale(0 1)'/></svg>";
    assert!(matches!(domain_from_svg_str(doc), Err(IoError::Empty(_))));
    let doc = "<svg xmlns='http://www.w3.org/2000/svg'><circle r='-1'/></svg>";
    let e = domain_from_svg_str(doc).unwrap_err().to_string();
    assert!(e.contains("circle") && e.contains("negative"), "{e}");
}

fn svg(body: &str) -> String {
    format!(r#"<svg xmlns="http://www.w3.org/2000/svg">{body}</svg>"#)
}

/// The curves of a document, open subpaths kept as drawn (so every state a subpath leaves
/// behind shows).
fn document_curves(body: &str) -> Vec<NurbsCurve> {
    rs_io::svg::domain_from_svg_str_with(&svg(body), rs_io::svg::OpenSubpaths::Keep)
        .unwrap_or_else(|e| panic!("{body}: {e}"))
        .curves()
        .to_vec()
}

/// Same degree, knots, weights and control points, bit for bit.
fn same_bits(a: &[NurbsCurve], b: &[NurbsCurve], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    for (x, y) in a.iter().zip(b) {
        assert_eq!(x.degree(), y.degree(), "{what}");
        assert_eq!(x.knots().knots(), y.knots().knots(), "{what}");
        assert_eq!(x.weights(), y.weights(), "{what}");
        assert_eq!(x.control_points(), y.control_points(), "{what}");
    }
}

#[test]
fn a_leading_relative_moveto_is_absolute_in_every_path() {
    // The issue's document: each path starts at the origin, not where the previous one ended.
    let doc = svg(r#"<path d="m 10 10 h 5 v 5 h -5 z"/><path d="m 100 100 h 5 v 5 h -5 z"/>"#);
    let d = domain_from_svg_str(&doc).unwrap();
    let b = d.bounding_box();
    assert_eq!(
        (b.min, b.max),
        (Point::new(10.0, 10.0), Point::new(105.0, 105.0))
    );
    assert_eq!(d.loops().len(), 2);
    // Also after a subpath left open, and after other shapes.
    for before in [
        r#"<path d="M 1 1 h 3 v 3"/>"#,
        r#"<rect x="1" y="1" width="3" height="3"/>"#,
        r#"<polygon points="1 1 4 1 4 4"/>"#,
        r#"<circle cx="2" cy="2" r="1"/>"#,
    ] {
        let d = domain_from_svg_str(&svg(&format!(r#"{before}<path d="m 100 100 h 5 v 5 z"/>"#)))
            .unwrap();
        let b = d.bounding_box();
        assert_eq!(b.max, Point::new(105.0, 105.0), "{before}");
    }
}

/// Every element draws the same curves alone as after any other element, inside a group or
/// not: no pen position, subpath start, control point to reflect or transform carries over.
#[test]
fn elements_draw_the_same_curves_whatever_precedes_them() {
    // Elements that leave every kind of state behind: a cubic (S would reflect it), a
    // quadratic (T), an open subpath, a closed one with a later lone moveto, a transform.
    let before = [
        r#"<path d="M 3 3 C 10 0 20 0 30 30"/>"#,
        r#"<path d="M 3 3 Q 10 0 30 30"/>"#,
        r#"<path d="M 3 3 h 7 v 7"/>"#,
        r#"<path d="M 3 3 h 7 v 7 z m 50 50"/>"#,
        r#"<path d="M 3 3 h 7 v 7 z" transform="translate(7 9) scale(3)"/>"#,
        r#"<g transform="rotate(30)"><path d="M 3 3 s 5 0 7 7 t 4 4"/></g>"#,
        r#"<polyline points="3 3 10 3 10 10"/>"#,
        r#"<rect x="3" y="3" width="7" height="7" rx="2"/>"#,
        r#"<ellipse cx="3" cy="3" rx="2" ry="1"/>"#,
    ];
    // Elements whose curves depend on that state if it leaks: a relative moveto first, S and
    // T first after the moveto, a close then a relative moveto (relative to this path's
    // subpath start), an open subpath (closed only under OpenSubpaths::Close), an implicit
    // lineto after a relative moveto.
    let after = [
        r#"<path d="m 40 40 h 5 v 5 h -5 z"/>"#,
        r#"<path d="m 40 40 s 10 -5 10 5 c 0 5 -5 5 -10 0"/>"#,
        r#"<path d="M 40 40 S 50 35 50 45 Z"/>"#,
        r#"<path d="m 40 40 t 10 5 q 0 5 -10 0"/>"#,
        r#"<path d="M 40 40 T 50 45 L 40 50 z"/>"#,
        r#"<path d="m 40 40 h 5 v 5 z m 10 0 h 5 v 5 z l 3 -4 z"/>"#,
        r#"<path d="m 40 40 5 0 0 5"/>"#,
        r#"<polygon points="40 40 45 40 45 45"/>"#,
    ];
    for b in before {
        for a in after {
            let alone_b = document_curves(b);
            let alone_a = document_curves(a);
            let expected: Vec<NurbsCurve> = alone_b.iter().chain(&alone_a).cloned().collect();
            same_bits(
                &document_curves(&format!("{b}{a}")),
                &expected,
                &format!("{b}{a}"),
            );
            // In a group after the element, and in a sibling group.
            let grouped = format!("<g>{b}<g>{a}</g></g>");
            same_bits(&document_curves(&grouped), &expected, &grouped);
            let siblings = format!("<g>{b}</g><g>{a}</g>");
            same_bits(&document_curves(&siblings), &expected, &siblings);
        }
    }
}

#[test]
fn nested_group_transforms_compose_and_end_with_their_group() {
    let doc = svg(concat!(
        r#"<g transform="translate(100 0)">"#,
        r#"<g transform="scale(2)"><path d="m 1 1 h 1 v 1 h -1 z"/></g>"#,
        r#"<path d="m 1 1 h 1 v 1 h -1 z"/>"#,
        r#"<g transform="rotate(90)"><g transform="translate(0 -3)">"#,
        r#"<path d="m 1 1 h 1 v 1 h -1 z" transform="scale(1 2)"/></g></g>"#,
        r#"<path d="m 1 1 h 1 v 1 h -1 z"/>"#,
        r#"</g>"#,
        r#"<path d="m 1 1 h 1 v 1 h -1 z"/>"#,
    ));
    let d = domain_from_svg_str(&doc).unwrap();
    let boxes: Vec<(Point, Point)> = d
        .loops()
        .iter()
        .map(|l| {
            let b = d.curves()[l.curves()]
                .iter()
                .map(NurbsCurve::bounding_box)
                .reduce(rs_spline::BoundingBox::union)
                .unwrap();
            (b.min, b.max)
        })
        .collect();
    let p = Point::new;
    // rotate(90) maps (x, y) to (-y, x); translate(0 -3) then scale(1 2) maps the square
    // [1, 2] x [1, 2] to [1, 2] x [-1, 1], rotated to [-1, 1] x [1, 2], then moved by 100.
    let want = [
        (p(102.0, 2.0), p(104.0, 4.0)),
        (p(101.0, 1.0), p(102.0, 2.0)),
        (p(99.0, 1.0), p(101.0, 2.0)),
        (p(101.0, 1.0), p(102.0, 2.0)),
        (p(1.0, 1.0), p(2.0, 2.0)),
    ];
    assert_eq!(boxes.len(), want.len());
    for (i, ((lo, hi), (wlo, whi))) in boxes.iter().zip(want).enumerate() {
        assert!(
            lo.distance(wlo) < 1e-12 && hi.distance(whi) < 1e-12,
            "loop {i}: {lo:?} {hi:?}"
        );
    }
}

#[test]
fn numbers_follow_one_grammar_in_every_attribute() {
    // Transforms with the separators the number grammar makes optional, as editors write
    // them; points and lengths with exponents and bare fractions.
    let doc = svg(concat!(
        r#"<g transform="translate(0-1036.36)"><g transform="matrix(1 0 0 1 0-5)">"#,
        r#"<g transform="scale(1-1)"><path d="M0-1040h1v1z"/></g></g></g>"#,
        r#"<polygon points="1e1,0 2E+1-0 .2e2.5"/>"#,
        r#"<rect x=".5" y="1e-3" width="1E+1" height="2px"/>"#,
        r#"<path d="M 0 0 h 1 v 1 z" transform="rotate(90 .5.5)translate(30)"/>"#,
    ));
    let d = domain_from_svg_str(&doc).unwrap();
    assert_eq!(d.loops().len(), 4);
    let first = d.curves()[0].start_point();
    // (0, -1040) -> scale(1, -1) -> (0, 1040) -> -5 -> -1036.36.
    assert!(
        first.distance(Point::new(0.0, 1040.0 - 5.0 - 1036.36)) < 1e-9,
        "{first:?}"
    );
    assert_eq!(d.curves()[3].start_point(), Point::new(10.0, 0.0));
    assert_eq!(d.curves()[4].end_point(), Point::new(20.0, 0.5));
    assert_eq!(d.curves()[6].start_point(), Point::new(0.5, 1e-3));
    // rotate(90 .5 .5) after translate(30): (0, 0) -> (30, 0) -> (1, 30).
    let q = d.curves()[10].start_point();
    assert!(q.distance(Point::new(1.0, 30.0)) < 1e-12, "{q:?}");
    // Garbage is refused with a one-line message naming the element and the token.
    for (body, want) in [
        (
            r#"<g transform="translate(1 2px)"><path d="M0 0h1v1z"/></g>"#,
            r#"translate: "2px" is not a number"#,
        ),
        (
            r#"<polygon points="1 2 3 4 5 x"/>"#,
            r#"points: "x" is not a number"#,
        ),
        (
            r#"<polygon points="1 2 3 4 5 6,"/>"#,
            "points: a comma with no number",
        ),
        (
            r#"<rect width="1 2" height="1"/>"#,
            "width=\"1 2\" is not a length",
        ),
    ] {
        let e = domain_from_svg_str(&svg(body)).unwrap_err().to_string();
        assert!(e.contains(want) && !e.contains('\n'), "{body}: {e}");
    }
}
