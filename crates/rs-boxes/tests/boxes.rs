//! Monotone boxes: monotone, covering, watertight, critical points of known shapes,
//! refinement, and the boundary band.

use rs_spline::prelude::*;
use std::f64::consts::PI;

use rs_boxes::{BoxOptions, CriticalKind, MonotoneBoxes, Monotonicity};
use rs_spline::{Domain, Point, circle, circular_arc, segment};

fn all_domains() -> Vec<(String, Domain)> {
    let mut v = rs_testkit::fixtures();
    v.push(rs_testkit::lens());
    v.push(rs_testkit::staircase());
    v.into_iter().map(|c| (c.name, c.domain)).collect()
}

#[test]
fn line_crossings_lie_on_the_piece_of_a_circle() {
    let r = 2.5;
    let d = Domain::new(vec![circle(Point::new(1.0, -1.0), r).unwrap()]).unwrap();
    let mb = MonotoneBoxes::new(&d, BoxOptions::DEFAULT.with_subdivisions(3)).unwrap();
    for b in mb.boxes() {
        for s in [0.0, 0.3, 0.77] {
            let x = b.band.xmin + s * (b.band.xmax - b.band.xmin);
            let (t, y) = b.at_x(x).unwrap();
            assert!((b.point_at(t) - Point::new(x, y)).length() < 1e-14);
            assert!(((x - 1.0).hypot(y + 1.0) - r).abs() < 1e-13, "{x} {y}");
            let y = b.band.ymin + s * (b.band.ymax - b.band.ymin);
            let (t, x) = b.at_y(y).unwrap();
            assert!((b.point_at(t) - Point::new(x, y)).length() < 1e-14);
            assert!(((x - 1.0).hypot(y + 1.0) - r).abs() < 1e-13, "{x} {y}");
        }
        assert!(b.at_x(b.band.xmax + 0.1).is_none() && b.at_y(b.band.ymin - 0.1).is_none());
    }
}

#[test]
fn every_box_is_monotone_and_spanned_by_its_end_points() {
    for (name, d) in all_domains() {
        let size = d.bounding_box().diagonal();
        for k in [1, 4] {
            let mb = MonotoneBoxes::new(&d, BoxOptions::DEFAULT.with_subdivisions(k)).unwrap();
            for b in mb.boxes() {
                let pts: Vec<Point> = (0..=200).map(|i| b.point_at(i as f64 / 200.0)).collect();
                for w in pts.windows(2) {
                    let (dx, dy) = (w[1].x - w[0].x, w[1].y - w[0].y);
                    let slack = 1e-13 * size;
                    match b.x_dir {
                        Monotonicity::Increasing => {
                            assert!(dx >= -slack, "{name}: x not increasing")
                        }
                        Monotonicity::Decreasing => {
                            assert!(dx <= slack, "{name}: x not decreasing")
                        }
                        Monotonicity::Constant => assert!(dx.abs() <= slack),
                    }
                    match b.y_dir {
                        Monotonicity::Increasing => {
                            assert!(dy >= -slack, "{name}: y not increasing")
                        }
                        Monotonicity::Decreasing => {
                            assert!(dy <= slack, "{name}: y not decreasing")
                        }
                        Monotonicity::Constant => assert!(dy.abs() <= slack),
                    }
                }
                for p in pts {
                    assert!(
                        b.contains_with(p, 1e-13 * size),
                        "{name}: {p:?} outside its box"
                    );
                }
            }
        }
    }
}

#[test]
fn boxes_cover_the_boundary_and_are_watertight() {
    for (name, d) in all_domains() {
        let size = d.bounding_box().diagonal();
        let mb = MonotoneBoxes::new(&d, BoxOptions::default()).unwrap();
        for c in d.curves() {
            let (a, b) = c.param_range();
            for i in 0..=500 {
                let p = c.point_at(a + (b - a) * i as f64 / 500.0);
                assert!(
                    mb.boxes()
                        .iter()
                        .any(|bx| bx.contains_with(p, 1e-13 * size)),
                    "{name}: {p:?} in no box"
                );
            }
        }
        // Consecutive boxes of a loop share their end points exactly, including the closure.
        let boxes = mb.boxes();
        for l in 0..d.loops().len() {
            let lb: Vec<_> = boxes.iter().filter(|b| b.boundary_loop == l).collect();
            for i in 0..lb.len() {
                let next = lb[(i + 1) % lb.len()];
                assert_eq!(lb[i].band.end, next.band.start, "{name}: loop {l} box {i}");
            }
        }
        let bb = mb.bounding_box();
        let tight = d.bounding_box();
        assert!(
            (bb.min.x - tight.min.x).abs() < 1e-15 && (bb.max.y - tight.max.y).abs() < 1e-15,
            "{name}"
        );
    }
}

#[test]
fn refinement_multiplies_the_boxes() {
    for (name, d) in all_domains() {
        let n1 = MonotoneBoxes::new(&d, BoxOptions::DEFAULT.with_subdivisions(1))
            .unwrap()
            .boxes()
            .len();
        let n7 = MonotoneBoxes::new(&d, BoxOptions::DEFAULT.with_subdivisions(7))
            .unwrap()
            .boxes()
            .len();
        assert_eq!(n7, 7 * n1, "{name}");
    }
    let d = &rs_testkit::fixtures()[0].domain;
    assert!(MonotoneBoxes::new(d, BoxOptions::DEFAULT.with_subdivisions(0)).is_err());
}

#[test]
fn critical_points_of_known_shapes() {
    // Circle: vertical tangents at x = +-1, horizontal at y = +-1 (at knots).
    let c = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
    let mb = MonotoneBoxes::new(&c, BoxOptions::DEFAULT.with_subdivisions(3)).unwrap();
    assert_eq!(mb.critical_abscissas(), &[-1.0, 1.0]);
    assert_eq!(mb.critical_ordinates(), &[-1.0, 1.0]);

    // A circle of 3 arcs starting at 10 degrees: the tangencies fall inside the pieces.
    let arc = circular_arc(Point::new(0.0, 0.0), 1.0, 0.2, 2.0 * PI).unwrap();
    let mb = MonotoneBoxes::new(&Domain::new(vec![arc]).unwrap(), BoxOptions::default()).unwrap();
    let xs = mb.critical_abscissas();
    assert_eq!(xs.len(), 2, "{xs:?}");
    assert!(
        (xs[0] + 1.0).abs() < 1e-14 && (xs[1] - 1.0).abs() < 1e-14,
        "{xs:?}"
    );
    assert!(
        mb.critical_points()
            .iter()
            .any(|c| c.kind == CriticalKind::VerticalTangent)
    );

    // Lens: x-turning corners at (+-1, 0); horizontal tangents at the top and bottom.
    let mb = MonotoneBoxes::new(&rs_testkit::lens().domain, BoxOptions::default()).unwrap();
    let xs = mb.critical_abscissas();
    assert_eq!(xs.len(), 2, "{xs:?}");
    assert!((xs[0] + 1.0).abs() < 1e-15 && (xs[1] - 1.0).abs() < 1e-15);
    let ys = mb.critical_ordinates();
    let h = 1.36f64.sqrt() - 0.6;
    assert_eq!(ys.len(), 2, "{ys:?}");
    assert!(
        (ys[0] + h).abs() < 1e-14 && (ys[1] - h).abs() < 1e-14,
        "{ys:?}"
    );
    assert!(
        mb.critical_points()
            .iter()
            .any(|c| c.kind == CriticalKind::XTurningVertex)
    );

    // Staircase: vertical and horizontal pieces everywhere, plus the triangle's turning corners.
    let mb = MonotoneBoxes::new(&rs_testkit::staircase().domain, BoxOptions::default()).unwrap();
    assert_eq!(
        mb.critical_abscissas(),
        &[0.0, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0]
    );
    assert_eq!(
        mb.critical_ordinates(),
        &[0.0, 0.5, 1.0, 1.5, 2.0, 3.0, 4.0]
    );
    assert!(mb.is_critical_x(1.5 + 1e-14, 1e-13));
    assert!(!mb.is_critical_x(1.25, 1e-13));
}

#[test]
fn tiny_gaps_are_closed_exactly() {
    let p = Point::new;
    let d = Domain::new(vec![
        segment(p(0.0, 0.0), p(1.0, 0.0)).unwrap(),
        segment(p(1.0 + 1e-13, 0.0), p(0.0, 1.0)).unwrap(),
        segment(p(0.0, 1.0 - 1e-13), p(0.0, 1e-13)).unwrap(),
    ])
    .unwrap();
    assert!(d.is_closed());
    let mb = MonotoneBoxes::new(&d, BoxOptions::default()).unwrap();
    let b = mb.boxes();
    for i in 0..b.len() {
        assert_eq!(b[i].band.end, b[(i + 1) % b.len()].band.start);
    }
}

#[test]
fn boundary_band_semantics() {
    // On a circle of radius 1: a point at distance tol/2 is near, at 2 tol is not, in every
    // direction (the band is between tol/sqrt(2) and tol).
    let c = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
    let mb = MonotoneBoxes::new(&c, BoxOptions::default()).unwrap();
    let tol = 1e-9;
    for k in 0..360 {
        let th = (k as f64 + 0.37).to_radians();
        let dir = Point::new(th.cos(), th.sin());
        let near = |r: f64| mb.boxes().iter().any(|b| b.is_near(dir * r, tol));
        assert!(
            near(1.0 + 0.5 * tol) && near(1.0 - 0.5 * tol) && near(1.0),
            "{k}"
        );
        assert!(!near(1.0 + 2.0 * tol) && !near(1.0 - 2.0 * tol), "{k}");
    }
}

#[test]
fn box_grid_finds_every_near_box() {
    use rs_boxes::BoxGrid;
    for (name, d) in all_domains() {
        let size = d.bounding_box().diagonal();
        let tol = 1e-6 * size;
        let mb = MonotoneBoxes::new(&d, BoxOptions::default()).unwrap();
        let grid = BoxGrid::new(mb.boxes(), tol);
        let mut pts = Vec::new();
        for c in d.curves() {
            let (a, b) = c.param_range();
            for i in 0..=200 {
                let dv = c.derivatives(a + (b - a) * i as f64 / 200.0);
                let n = dv.first.perp() / dv.first.length().max(f64::MIN_POSITIVE);
                for off in [0.0, 0.5 * tol, -0.5 * tol, 3.0 * tol] {
                    pts.push(dv.point + n * off);
                }
            }
        }
        let bb = d.bounding_box();
        for i in 0..400 {
            let (u, v) = ((i as f64 * 0.618_034) % 1.0, (i as f64 * 0.414_214) % 1.0);
            pts.push(Point::new(
                bb.min.x + u * bb.width(),
                bb.min.y + v * bb.height(),
            ));
        }
        let mut near_count = 0;
        for p in pts {
            let candidates = grid.candidates(p);
            for (i, b) in mb.boxes().iter().enumerate() {
                if b.is_near(p, tol) {
                    near_count += 1;
                    assert!(
                        candidates.contains(&(i as u32)),
                        "{name}: box {i} near {p:?} missing"
                    );
                }
            }
        }
        assert!(near_count > 100, "{name}");
    }
}
