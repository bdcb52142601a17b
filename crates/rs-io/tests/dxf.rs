//! DXF drawings written with the `dxf` crate (as a CAD program would), read back through
//! text: exact areas of splines, bulge arcs, arcs, circles and ellipses; entities chained in
//! any order and direction; errors name the entity.
// Entities are filled in field by field, as an exporter builds them.
#![allow(clippy::field_reassign_with_default)]

use rs_spline::prelude::*;
use std::f64::consts::{FRAC_1_SQRT_2, PI};

use dxf::entities::{Arc, Circle, Ellipse, Entity, EntityType, Line, LwPolyline, Spline};
use dxf::{Drawing, LwPolylineVertex, Vector, enums::AcadVersion};
use rs_contain::Locate;
use rs_io::IoError;
use rs_io::dxf_file::{DxfOptions, domain_from_dxf_str};
use rs_spline::{Domain, Point};

fn drawing(entities: Vec<EntityType>) -> String {
    let mut d = Drawing::new();
    d.header.version = AcadVersion::R2018;
    for e in entities {
        d.add_entity(Entity::new(e));
    }
    let mut out = Vec::new();
    d.save(&mut out).unwrap();
    String::from_utf8(out).unwrap()
}

fn read(entities: Vec<EntityType>) -> Result<Domain, IoError> {
    domain_from_dxf_str(&drawing(entities), &DxfOptions::default())
}

fn p3(x: f64, y: f64) -> dxf::Point {
    dxf::Point::new(x, y, 0.0)
}

fn lwpolyline(vertices: &[(f64, f64, f64)], closed: bool) -> EntityType {
    let mut p = LwPolyline::default();
    p.vertices = vertices
        .iter()
        .map(|&(x, y, bulge)| LwPolylineVertex {
            x,
            y,
            bulge,
            ..Default::default()
        })
        .collect();
    p.set_is_closed(closed);
    EntityType::LwPolyline(p)
}

#[test]
fn rational_spline_circle_has_area_pi() {
    // The nine-point rational quadratic circle of radius 1 as a DXF SPLINE.
    let circle = rs_spline::circle(Point::new(0.0, 0.0), 1.0).unwrap();
    let mut s = Spline::default();
    s.degree_of_curve = 2;
    s.set_is_rational(true);
    s.set_is_closed(true);
    s.knot_values = circle.knots().knots().to_vec();
    s.control_points = circle
        .control_points()
        .iter()
        .map(|p| p3(p.x, p.y))
        .collect();
    s.weight_values = circle.weights().to_vec();
    assert!(s.weight_values.contains(&FRAC_1_SQRT_2));
    let d = read(vec![EntityType::Spline(s)]).unwrap();
    assert_eq!(d.loops().len(), 1);
    assert!((d.signed_area() - PI).abs() < 1e-11);
    // DXF text keeps 12 decimals (the weights 1/sqrt(2) included): the circle is exact to
    // that precision.
    for i in 0..=32 {
        let q = d.curves()[0].point_at(i as f64 / 32.0);
        assert!((q.length() - 1.0).abs() < 1e-12);
    }
}

#[test]
fn bulged_lwpolyline_is_a_rounded_slot() {
    // A 4 x 2 rectangle whose short sides are half circles (bulge 1): area 8 + pi.
    let d = read(vec![lwpolyline(
        &[
            (0.0, 0.0, 0.0),
            (4.0, 0.0, 1.0),
            (4.0, 2.0, 0.0),
            (0.0, 2.0, 1.0),
        ],
        true,
    )])
    .unwrap();
    assert_eq!(d.curves().len(), 4);
    assert!(d.require_closed().is_ok());
    assert!(
        (d.signed_area() - (8.0 + PI)).abs() < 1e-12,
        "{}",
        d.signed_area()
    );
    // Negative bulges cut the half discs out instead.
    let d = read(vec![lwpolyline(
        &[
            (0.0, 0.0, 0.0),
            (4.0, 0.0, -1.0),
            (4.0, 2.0, 0.0),
            (0.0, 2.0, -1.0),
        ],
        true,
    )])
    .unwrap();
    assert!(
        (d.signed_area() - (8.0 - PI)).abs() < 1e-12,
        "{}",
        d.signed_area()
    );
}

#[test]
fn lines_and_arcs_in_any_order_and_direction_are_chained() {
    // A "D": a vertical line and a half-circle arc, plus a square hole of four lines given
    // shuffled and with mixed directions, and a circular hole.
    let d = read(vec![
        EntityType::Line(Line::new(p3(0.4, 0.4), p3(0.4, 0.6))),
        EntityType::Arc(Arc::new(p3(0.0, 0.0), 1.0, -90.0, 90.0)),
        EntityType::Line(Line::new(p3(0.6, 0.4), p3(0.4, 0.4))),
        EntityType::Circle(Circle::new(p3(0.3, -0.5), 0.2)),
        EntityType::Line(Line::new(p3(0.0, -1.0), p3(0.0, 1.0))),
        EntityType::Line(Line::new(p3(0.6, 0.6), p3(0.6, 0.4))),
        EntityType::Line(Line::new(p3(0.6, 0.6), p3(0.4, 0.6))),
    ])
    .unwrap();
    assert_eq!(d.loops().len(), 3);
    assert!(d.require_closed().is_ok());
    let total: f64 = (0..3).map(|i| d.loop_signed_area(i).abs()).sum();
    let (half, square, disc) = (PI / 2.0, 0.04, PI * 0.04);
    assert!((total - (half + square + disc)).abs() < 1e-12, "{total}");
    // Containment by parity: inside the D, not in the holes.
    let c = rs_contain::Classifier::new(&d, Default::default()).unwrap();
    use rs_contain::Location::{Inside, Outside};
    for (p, want) in [
        (Point::new(0.2, 0.0), Inside),
        (Point::new(0.5, 0.5), Outside),
        (Point::new(0.3, -0.5), Outside),
        (Point::new(0.8, 0.1), Inside),
        (Point::new(-0.1, 0.0), Outside),
    ] {
        assert_eq!(c.locate(p), want, "{p:?}");
    }
}

#[test]
fn ellipses_and_mirrored_entities() {
    // A full ellipse with major axis (3, 4) (length 5) and ratio 0.4: area pi * 5 * 2.
    let mut e = Ellipse::default();
    e.center = p3(1.0, 1.0);
    e.major_axis = Vector::new(3.0, 4.0, 0.0);
    e.minor_axis_ratio = 0.4;
    let d = read(vec![EntityType::Ellipse(e.clone())]).unwrap();
    assert!((d.signed_area() - 10.0 * PI).abs() < 1e-11);
    // Half of it (parameters 0..pi) closed by a line through the centre.
    e.start_parameter = 0.0;
    e.end_parameter = PI;
    let ends = (Point::new(4.0, 5.0), Point::new(-2.0, -3.0));
    let d = read(vec![
        EntityType::Ellipse(e.clone()),
        EntityType::Line(Line::new(p3(ends.1.x, ends.1.y), p3(ends.0.x, ends.0.y))),
    ])
    .unwrap();
    assert!(d.require_closed().is_ok());
    assert!((d.signed_area() - 5.0 * PI).abs() < 1e-11);
    // Extrusion direction -z mirrors x: a circle at OCS (2, 0) lies at world (-2, 0), and
    // an ellipse's parameter runs clockwise.
    let mut c = Circle::new(p3(2.0, 0.0), 1.0);
    c.normal = Vector::new(0.0, 0.0, -1.0);
    let d = read(vec![EntityType::Circle(c)]).unwrap();
    let bb = d.bounding_box();
    assert!(bb.min.distance(Point::new(-3.0, -1.0)) < 1e-12, "{bb:?}");
    e.normal = Vector::new(0.0, 0.0, -1.0);
    let d = read(vec![
        EntityType::Ellipse(e),
        EntityType::Line(Line::new(p3(ends.1.x, ends.1.y), p3(ends.0.x, ends.0.y))),
    ])
    .unwrap();
    // Clockwise from (4, 5): the half on the other side of the major axis.
    assert!(
        (d.signed_area() + 5.0 * PI).abs() < 1e-11,
        "{}",
        d.signed_area()
    );
}

#[test]
fn errors_name_the_entity() {
    let mut fit_only = Spline::default();
    fit_only.degree_of_curve = 3;
    fit_only.fit_points = vec![p3(0.0, 0.0), p3(1.0, 1.0), p3(2.0, 0.0)];
    let e = read(vec![EntityType::Spline(fit_only)]).unwrap_err();
    let msg = e.to_string();
    assert!(
        matches!(e, IoError::DxfEntity { kind: "SPLINE", .. }),
        "{msg}"
    );
    assert!(msg.contains("fit points"), "{msg}");

    let mut bad_weights = Spline::default();
    bad_weights.degree_of_curve = 1;
    bad_weights.knot_values = vec![0.0, 0.0, 1.0, 1.0];
    bad_weights.control_points = vec![p3(0.0, 0.0), p3(1.0, 0.0)];
    bad_weights.weight_values = vec![1.0];
    let msg = read(vec![EntityType::Spline(bad_weights)])
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("SPLINE") && msg.contains("1 weights for 2"),
        "{msg}"
    );

    let mut bad_knots = Spline::default();
    bad_knots.degree_of_curve = 2;
    bad_knots.knot_values = vec![0.0, 1.0];
    bad_knots.control_points = vec![p3(0.0, 0.0), p3(1.0, 0.0), p3(1.0, 1.0)];
    let msg = read(vec![EntityType::Spline(bad_knots)])
        .unwrap_err()
        .to_string();
    assert!(msg.contains("SPLINE") && msg.contains("knot"), "{msg}");

    let open = vec![
        EntityType::Line(Line::new(p3(0.0, 0.0), p3(1.0, 0.0))),
        EntityType::Line(Line::new(p3(1.0, 0.0), p3(1.0, 1.0))),
    ];
    let msg = read(open.clone()).unwrap_err().to_string();
    assert!(msg.contains("LINE") && msg.contains("open"), "{msg}");
    // Open chains are kept on request (for winding numbers).
    let d =
        domain_from_dxf_str(&drawing(open), &DxfOptions::DEFAULT.with_allow_open(true)).unwrap();
    assert!(!d.is_closed());

    let mut tilted = Circle::new(p3(0.0, 0.0), 1.0);
    tilted.normal = Vector::new(0.0, 1.0, 1.0);
    let msg = read(vec![EntityType::Circle(tilted)])
        .unwrap_err()
        .to_string();
    assert!(msg.contains("CIRCLE") && msg.contains("XY plane"), "{msg}");

    let msg = read(vec![EntityType::Circle(Circle::new(p3(0.0, 0.0), -1.0))])
        .unwrap_err()
        .to_string();
    assert!(msg.contains("CIRCLE") && msg.contains("radius"), "{msg}");

    assert!(matches!(read(vec![]), Err(IoError::Empty(_))));
    let e = domain_from_dxf_str(
        "0\nSECTION\n2\nENTITIES\n0\nLINE\n10\nnot-a-number\n",
        &DxfOptions::default(),
    )
    .unwrap_err();
    assert!(matches!(e, IoError::Dxf(_)), "{e}");
}

#[test]
fn old_style_polylines_with_bulges_and_3d_polylines() {
    use dxf::entities::{Polyline, Vertex};
    let build = |z: [f64; 4], three_d: bool| {
        let mut d = Drawing::new();
        d.header.version = AcadVersion::R2018;
        let mut p = Polyline::default();
        p.set_is_closed(true);
        p.set_is_3d_polyline(three_d);
        for (i, (x, y, bulge)) in [
            (0.0, 0.0, 0.0),
            (2.0, 0.0, 1.0),
            (2.0, 2.0, 0.0),
            (0.0, 2.0, 0.0),
        ]
        .into_iter()
        .enumerate()
        {
            let mut v = Vertex::new(dxf::Point::new(x, y, z[i]));
            v.bulge = bulge;
            p.add_vertex(&mut d, v);
        }
        d.add_entity(Entity::new(EntityType::Polyline(p)));
        let mut out = Vec::new();
        d.save(&mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        domain_from_dxf_str(&text, &DxfOptions::default())
    };
    // A 2 x 2 square with a half disc of radius 1 on its right side.
    let d = build([0.0; 4], false).unwrap();
    assert!(
        (d.signed_area() - (4.0 + PI / 2.0)).abs() < 1e-11,
        "{}",
        d.signed_area()
    );
    // A flat 3-D polyline is accepted; one that leaves the plane is named in the error.
    assert!(build([1.0; 4], true).is_ok());
    let msg = build([0.0, 0.0, 1.0, 0.0], true).unwrap_err().to_string();
    assert!(
        msg.contains("POLYLINE") && msg.contains("XY plane"),
        "{msg}"
    );
}
