//! Monotone boxes: monotone, covering, watertight, critical points of known shapes,
//! refinement, and the boundary band.

use rs_spline::prelude::*;
use std::f64::consts::PI;

use rs_boxes::{BOXES_PER_DIAGONAL, BoxOptions, CriticalKind, MonotoneBoxes, Monotonicity};
use rs_spline::{Domain, Point, circle, circular_arc, polyline, segment};

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

/// The piece a box exposes is its curve: de Casteljau on its control points and weights (an
/// evaluation independent of the box's own) gives `point_at`, and the end points are the band's.
#[test]
fn the_piece_is_the_boxs_curve() {
    for (name, d) in all_domains() {
        let mb = MonotoneBoxes::new(&d, BoxOptions::DEFAULT.with_subdivisions(2)).unwrap();
        for b in mb.boxes() {
            let piece = b.piece();
            let pts: Vec<Point> = (0..=piece.degree())
                .map(|i| piece.control_point(i))
                .collect();
            let w = piece.weights();
            assert_eq!(pts.len(), w.len());
            assert_eq!(pts[0], b.band.start, "{name}");
            assert_eq!(pts[pts.len() - 1], b.band.end, "{name}");
            let curve = rs_spline::RationalBezier::new(pts, w.to_vec()).unwrap();
            let size = d.bounding_box().diagonal();
            for i in 0..=16 {
                let t = i as f64 / 16.0;
                let gap = curve.point_at(t).distance(b.point_at(t));
                assert!(gap <= 1e-14 * size, "{name}: {gap} at {t}");
            }
        }
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

/// The refined boxes follow the size policy: `ceil(BOXES_PER_DIAGONAL * l1 / diagonal)` per
/// monotone piece, clamped to `1..=subdivisions`, in boundary order; each piece's boxes run
/// from its start to its end sharing their end points bit for bit and keep its directions (so
/// the critical points, taken from the pieces, are those the refined boxes give).
#[test]
fn refinement_follows_the_size_policy() {
    for (name, d) in all_domains() {
        for most in [1, 7, 32] {
            let mb = MonotoneBoxes::new(&d, BoxOptions::DEFAULT.with_subdivisions(most)).unwrap();
            assert_eq!(mb.subdivisions(), most);
            let diagonal = mb.bounding_box().diagonal();
            let all = mb.boxes();
            let mut next = 0;
            for (i, piece) in mb.pieces().iter().enumerate() {
                let range = mb.boxes_of_piece(i);
                assert_eq!(range.start, next, "{name}");
                next = range.end;
                let band = &piece.band;
                let l1 = (band.xmax - band.xmin) + (band.ymax - band.ymin);
                let want = ((BOXES_PER_DIAGONAL * l1 / diagonal).ceil() as usize).clamp(1, most);
                assert_eq!(range.len(), want, "{name}: piece {i} of l1 {l1}");
                let own = &all[range];
                assert_eq!(own[0].band.start, band.start, "{name}");
                assert_eq!(own[own.len() - 1].band.end, band.end, "{name}");
                assert_eq!(own[0].param_range.0, piece.param_range.0, "{name}");
                for w in own.windows(2) {
                    assert_eq!(w[0].band.end, w[1].band.start, "{name}");
                    assert_eq!(w[0].param_range.1, w[1].param_range.0, "{name}");
                }
                for b in own {
                    assert_eq!((b.x_dir, b.y_dir), (piece.x_dir, piece.y_dir), "{name}");
                    assert_eq!(
                        (b.curve, b.boundary_loop),
                        (piece.curve, piece.boundary_loop)
                    );
                }
                if want == 1 {
                    assert_eq!(&own[0], piece, "{name}: a whole piece is its own box");
                }
            }
            assert_eq!((next, mb.box_count()), (all.len(), all.len()), "{name}");
        }
    }
    let d = &rs_testkit::fixtures()[0].domain;
    assert!(MonotoneBoxes::new(d, BoxOptions::DEFAULT.with_subdivisions(0)).is_err());

    // A circle's quadrants span the domain: 32 boxes each. A 400-gon's sides are short: one.
    let c = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
    let mb = MonotoneBoxes::new(&c, BoxOptions::DEFAULT).unwrap();
    assert_eq!((mb.pieces().len(), mb.box_count()), (4, 128));
    let corners: Vec<Point> = (0..=400)
        .map(|i| {
            let a = 2.0 * PI * (i % 400) as f64 / 400.0;
            Point::new(a.cos(), a.sin())
        })
        .collect();
    let d = Domain::new(vec![polyline(&corners).unwrap()]).unwrap();
    let mb = MonotoneBoxes::new(&d, BoxOptions::DEFAULT).unwrap();
    assert_eq!(mb.pieces().len(), 400);
    assert_eq!(mb.box_count(), 400);
}

/// The refined boxes are built on the first call of `boxes()`, not before; one piece's boxes
/// computed on the fly are bit for bit the built ones; once the boxes computed on the fly reach
/// the total, the refinement is built and kept.
#[test]
fn refined_boxes_are_built_on_first_use() {
    for (name, d) in all_domains() {
        let eager = MonotoneBoxes::new(&d, BoxOptions::DEFAULT).unwrap();
        let lazy = MonotoneBoxes::new(&d, BoxOptions::DEFAULT).unwrap();
        assert!(!eager.is_refined() && !lazy.is_refined(), "{name}");
        let all = eager.boxes();
        assert!(eager.is_refined());
        let pass = |mb: &MonotoneBoxes| {
            let mut got = Vec::new();
            for i in 0..mb.pieces().len() {
                mb.for_each_box_of_piece(i, |b| got.push(b.clone()));
            }
            got
        };
        // One pass computes at most box_count boxes on the fly: nothing is kept.
        assert_eq!(pass(&lazy), all, "{name}");
        assert!(!lazy.is_refined(), "{name}");
        let refined = lazy.box_count() > lazy.pieces().len();
        assert_eq!(pass(&lazy), all, "{name}");
        assert_eq!(lazy.is_refined(), refined, "{name}: the second pass builds");
        assert_eq!(lazy.boxes(), all, "{name}");
        // A copy keeps what is built.
        assert!(eager.clone().is_refined());
        assert_eq!(eager.critical_abscissas(), lazy.critical_abscissas());
    }
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

/// The split parameters of one open Bezier curve: where its monotone pieces meet.
fn splits_of(points: Vec<Point>, weights: Option<Vec<f64>>) -> Vec<f64> {
    let c = rs_spline::NurbsCurve::bezier(points, weights).unwrap();
    let mb = MonotoneBoxes::new(&Domain::new(vec![c]).unwrap(), BoxOptions::DEFAULT).unwrap();
    mb.pieces()[1..].iter().map(|b| b.param_range.0).collect()
}

/// The tangency roots against analytic ones: a cubic with two vertical tangents, one with a
/// double root of `x'` (an inflection with a vertical tangent), an ellipse arc (rational) with
/// its vertical tangent in the middle, roots near the ends (within the end margin: no split,
/// just outside it: a split), and the quarter circle's tangents at its ends.
#[test]
fn tangency_roots_are_the_analytic_ones() {
    let p = Point::new;
    // x(t) = t^3 - 1.5 t^2 + 0.63 t: x' = 3 (t - 0.3)(t - 0.7); y(t) = t.
    let s = splits_of(
        vec![
            p(0.0, 0.0),
            p(0.21, 1.0 / 3.0),
            p(-0.08, 2.0 / 3.0),
            p(0.13, 1.0),
        ],
        None,
    );
    assert_eq!(s.len(), 2, "{s:?}");
    assert!(
        (s[0] - 0.3).abs() < 1e-14 && (s[1] - 0.7).abs() < 1e-14,
        "{s:?}"
    );
    // x(t) = (t - 0.5)^3 + 0.125: x' = 3 (t - 0.5)^2, a double root, reported once.
    let s = splits_of(
        vec![
            p(0.0, 0.0),
            p(0.25, 1.0 / 3.0),
            p(0.0, 2.0 / 3.0),
            p(0.25, 1.0),
        ],
        None,
    );
    assert_eq!(s.len(), 1, "{s:?}");
    assert!((s[0] - 0.5).abs() < 1e-7, "{s:?}");
    // The ellipse x = 3 cos a, y = sin a for a in [-1, 1], one rational quadratic: symmetric,
    // so its vertical tangent (a = 0) is at t = 1/2, and y' has no root.
    let (a, w) = (1.0f64, 1.0f64.cos());
    let s = splits_of(
        vec![
            p(3.0 * a.cos(), -a.sin()),
            p(3.0 / a.cos(), 0.0),
            p(3.0 * a.cos(), a.sin()),
        ],
        Some(vec![1.0, w, 1.0]),
    );
    assert_eq!(s.len(), 1, "{s:?}");
    assert!((s[0] - 0.5).abs() < 1e-15, "{s:?}");
    // Near-end roots: x(t) = (t - e)^2 on [0, 1] as a quadratic, y(t) = t.
    for (e, split) in [
        (1e-12, false),
        (1e-9, true),
        (1.0 - 1e-12, false),
        (1.0 - 1e-9, true),
    ] {
        // Power form e^2 - 2 e t + t^2: controls e^2, e^2 - e, (1 - e)^2.
        let s = splits_of(
            vec![
                p(e * e, 0.0),
                p(e * e - e, 0.5),
                p((1.0 - e) * (1.0 - e), 1.0),
            ],
            None,
        );
        if split {
            assert_eq!(s.len(), 1, "{e}: {s:?}");
            assert!((s[0] - e).abs() < 1e-15, "{e}: {s:?}");
        } else {
            assert!(s.is_empty(), "{e}: {s:?}");
        }
    }
    // A quarter circle: tangents at both ends, vertical at (1, 0) and horizontal at (0, 1).
    let c = rs_spline::NurbsCurve::bezier(
        vec![p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
        Some(vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0]),
    )
    .unwrap();
    let mb = MonotoneBoxes::new(&Domain::new(vec![c]).unwrap(), BoxOptions::DEFAULT).unwrap();
    assert_eq!(mb.pieces().len(), 1);
    let kinds: Vec<(Point, CriticalKind)> = mb
        .critical_points()
        .iter()
        .map(|c| (c.point, c.kind))
        .collect();
    assert!(
        kinds.contains(&(p(1.0, 0.0), CriticalKind::VerticalTangent)),
        "{kinds:?}"
    );
}

/// A quadratic of weights `1, w, 1` cut at its apex: each half moves within `1 / w` of one
/// parameter end, so its end weights are balanced (reparametrised) and, at `w = 1e10`, it is
/// halved until each part's weights are within `2^10` of its end weights; every box, refined
/// or not, still maps its parameter onto the curve's: its point at `s` is the curve's at
/// `nurbs_parameter(s)` (within what the curve's speed there, up to `w` times its size, makes
/// of the parameter's rounding), and consecutive boxes meet at the same point and parameter.
#[test]
fn balanced_boxes_map_their_parameters_onto_the_curve() {
    for (w, tol) in [(1e4, 1e-11), (1e10, 1e-5)] {
        let d = rs_testkit::weighted_arc(w);
        let arc = &d.curves()[0];
        for most in [1, 5] {
            let mb = MonotoneBoxes::new(&d, BoxOptions::DEFAULT.with_subdivisions(most)).unwrap();
            let on_arc: Vec<_> = mb.boxes().iter().filter(|b| b.curve == 0).collect();
            assert!(
                on_arc.len() >= 2 * most.min(2),
                "w {w}: {} boxes",
                on_arc.len()
            );
            assert!(on_arc.iter().any(|b| b.odds != 1.0), "w {w}: none balanced");
            for pair in on_arc.windows(2) {
                assert_eq!(pair[0].param_range.1, pair[1].param_range.0);
                assert_eq!(pair[0].band.end, pair[1].band.start);
            }
            if most == 1 {
                for b in &on_arc {
                    let w = b.piece().weights();
                    let ends = w[0].min(w[w.len() - 1]);
                    assert!(w.iter().all(|&x| x <= rs_spline::BALANCE_RATIO * ends));
                }
            }
            for b in &on_arc {
                for i in 0..=16 {
                    let s = f64::from(i) / 16.0;
                    let (p, q) = (b.point_at(s), arc.point_at(b.nurbs_parameter(s)));
                    assert!(p.distance(q) < tol, "w {w}, {most}: s {s}: {p:?} {q:?}");
                }
            }
        }
    }
}
