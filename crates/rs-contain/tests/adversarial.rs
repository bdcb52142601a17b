//! Zero misclassifications against independent truth on fixtures and synthetic domains, for
//! ordinary and adversarial points; inRS1 and inRS2 agree everywhere; both fallbacks are forced.

use rs_contain::Locate;
use rs_contain::baselines::halton_points;
use rs_contain::{
    Classifier, ContainOptions, Decision, FastWindingField, Location, LocatorOptions, Method,
    PointLocator,
};
use rs_spline::Point;
use rs_spline::prelude::*;
use rs_testkit::{Case, DensePolygon, all_cases};

/// Classifies with every method, several refinements and the fast paths (grid locator at
/// several resolutions, sequential, parallel and streaming); asserts they all agree with inRS2
/// and returns the common answer.
fn classify_all(case: &Case, pts: &[Point]) -> Vec<Location> {
    let reference = Classifier::new(&case.domain, ContainOptions::default()).unwrap();
    let expected = reference.locate_all_with(Method::InRS2, pts);
    let fast_gwn = FastWindingField::new(reference.winding_field());
    for (i, e) in expected.iter().enumerate() {
        assert_eq!(
            fast_gwn.locate(pts[i]),
            *e,
            "{}: fast GWN disagrees at {:?}",
            case.name,
            pts[i]
        );
    }
    for cells in [1, 7, 64, 300] {
        let loc = PointLocator::new(&reference, LocatorOptions::DEFAULT.with_cells(cells));
        let fast = [
            loc.locate_all(pts),
            loc.locate_all_parallel(pts),
            loc.locate_iter(pts.iter().copied()).collect(),
        ];
        for got in fast {
            for (i, (g, e)) in got.iter().zip(&expected).enumerate() {
                assert_eq!(
                    g, e,
                    "{}: locator with {cells} cells disagrees at {:?}",
                    case.name, pts[i]
                );
            }
        }
    }
    for subdivisions in [1, 3, 8, 32] {
        let c = Classifier::new(
            &case.domain,
            ContainOptions::DEFAULT.with_subdivisions(subdivisions),
        )
        .unwrap();
        for method in Method::ALL {
            let got = c.locate_all_with(method, pts);
            for (i, (g, e)) in got.iter().zip(&expected).enumerate() {
                assert_eq!(
                    g, e,
                    "{}: {method:?} with {subdivisions} sub-boxes disagrees at {:?}",
                    case.name, pts[i]
                );
            }
        }
    }
    expected
}

fn size(case: &Case) -> f64 {
    case.domain.bounding_box().diagonal()
}

/// Halton points of the grown bounding box against the dense polygon, away from the boundary.
#[test]
fn halton_points_match_the_dense_polygon() {
    for case in all_cases() {
        let s = size(&case);
        let poly = DensePolygon::new(&case.domain, 1e-7 * s);
        let mut bb = case.domain.bounding_box();
        bb.min = bb.min - Point::new(0.05 * s, 0.05 * s);
        bb.max = bb.max + Point::new(0.05 * s, 0.05 * s);
        let pts = halton_points(3000, bb);
        let got = classify_all(&case, &pts);
        let mut compared = 0;
        for (p, g) in pts.iter().zip(&got) {
            if poly.distance(*p) < 1e-5 * s {
                continue;
            }
            let truth = if poly.contains(*p) {
                Location::Inside
            } else {
                Location::Outside
            };
            assert_eq!(*g, truth, "{} at {p:?}", case.name);
            compared += 1;
        }
        assert!(compared > 2500, "{}: {compared}", case.name);
    }
}

/// Points on the curves (evaluated) are on the boundary.
#[test]
fn points_on_the_curves_are_boundary() {
    for case in all_cases() {
        let mut pts = Vec::new();
        for c in case.domain.curves() {
            let (a, b) = c.param_range();
            pts.extend((0..=60).map(|i| c.point_at(a + (b - a) * i as f64 / 60.0)));
        }
        let got = classify_all(&case, &pts);
        for (p, g) in pts.iter().zip(&got) {
            assert_eq!(*g, Location::Boundary, "{} at {p:?}", case.name);
        }
    }
}

/// Points offset along the normal by 1e-4, 1e-6 and 1e-8 times the domain size land on the
/// correct side (every test domain has the interior on its left).
#[test]
fn normal_offsets_land_on_the_correct_side() {
    for case in all_cases() {
        let s = size(&case);
        let mut pts = Vec::new();
        let mut truth = Vec::new();
        for c in case.domain.curves() {
            let (a, b) = c.param_range();
            let mut ends = vec![a];
            ends.extend(c.knots().interior_breaks());
            ends.push(b);
            for span in ends.windows(2) {
                for frac in [0.1, 0.3, 0.5, 0.7, 0.9] {
                    let u = span[0] + frac * (span[1] - span[0]);
                    let d = c.derivatives(u);
                    let speed = d.first.length();
                    let curvature = d.first.cross(d.second).abs() / speed.powi(3);
                    let n = d.first.perp() / speed;
                    for delta in [1e-4, 1e-6, 1e-8] {
                        let off = delta * s;
                        // Offsets beyond the radius of curvature are not "near the curve".
                        if off * curvature > 0.1 {
                            continue;
                        }
                        pts.push(d.point + n * off);
                        truth.push(Location::Inside);
                        pts.push(d.point - n * off);
                        truth.push(Location::Outside);
                    }
                }
            }
        }
        assert!(pts.len() > 40, "{}", case.name);
        let got = classify_all(&case, &pts);
        for ((p, g), t) in pts.iter().zip(&got).zip(&truth) {
            assert_eq!(g, t, "{} at {p:?}", case.name);
        }
    }
}

/// Junctions where the tangent jumps (corners), with the incoming and outgoing unit tangents.
fn corners(case: &Case) -> Vec<(Point, Point, Point)> {
    let mut out = Vec::new();
    for l in case.domain.loops() {
        let pieces: Vec<_> = l
            .curves()
            .flat_map(|ci| case.domain.curves()[ci].to_bezier())
            .collect();
        for i in 0..pieces.len() {
            let prev = &pieces[(i + pieces.len() - 1) % pieces.len()];
            let next = &pieces[i];
            let t_in = prev.derivatives(1.0).first;
            let t_out = next.derivatives(0.0).first;
            let (t_in, t_out) = (t_in / t_in.length(), t_out / t_out.length());
            if t_in.cross(t_out).abs() > 1e-3 || t_in.dot(t_out) < 0.0 {
                out.push((next.start_point(), t_in, t_out));
            }
        }
    }
    out
}

/// Points at corners along the bisector: inside on the interior side, outside on the other.
#[test]
fn corners_along_the_bisector() {
    let mut total = 0;
    for case in all_cases() {
        let s = size(&case);
        let mut pts = Vec::new();
        let mut truth = Vec::new();
        for (v, t_in, t_out) in corners(&case) {
            let b = -t_in + t_out;
            if b.length() < 1e-6 {
                continue; // a cusp: no bisector
            }
            let b = b / b.length();
            let inward = if t_in.cross(t_out) > 0.0 { b } else { -b };
            for delta in [1e-4, 1e-6, 1e-8] {
                pts.push(v + inward * (delta * s));
                truth.push(Location::Inside);
                pts.push(v - inward * (delta * s));
                truth.push(Location::Outside);
            }
            pts.push(v);
            truth.push(Location::Boundary);
        }
        total += pts.len();
        let got = classify_all(&case, &pts);
        for ((p, g), t) in pts.iter().zip(&got).zip(&truth) {
            assert_eq!(g, t, "{} at {p:?}", case.name);
        }
    }
    assert!(total > 100, "{total}");
}

/// Points on vertical and horizontal lines through every vertex and critical point, and at the
/// intersections of such lines: the vertical ray is critical there, so the horizontal ray and
/// the winding number decide. Checked against the dense polygon away from the boundary.
#[test]
fn critical_lines_force_both_fallbacks() {
    let mut decisions = std::collections::HashMap::new();
    for case in all_cases() {
        let s = size(&case);
        let c = Classifier::new(&case.domain, ContainOptions::default()).unwrap();
        // Vertices: ends of the unrefined monotone boxes (Bezier junctions, tangency splits).
        let unrefined =
            Classifier::new(&case.domain, ContainOptions::DEFAULT.with_subdivisions(1)).unwrap();
        let boxes = unrefined.boxes();
        let mut xs: Vec<f64> = boxes.critical_abscissas().to_vec();
        let mut ys: Vec<f64> = boxes.critical_ordinates().to_vec();
        for b in boxes.boxes() {
            xs.push(b.band.start.x);
            ys.push(b.band.start.y);
        }
        for v in [&mut xs, &mut ys] {
            v.sort_by(f64::total_cmp);
            v.dedup();
        }
        let bb = case.domain.bounding_box();
        let grid = |lo: f64, hi: f64| -> Vec<f64> {
            (0..=40)
                .map(|i| lo - 0.02 * s + (hi - lo + 0.04 * s) * i as f64 / 40.0)
                .collect()
        };
        let mut pts = Vec::new();
        for &x in &xs {
            pts.extend(
                grid(bb.min.y, bb.max.y)
                    .into_iter()
                    .map(|y| Point::new(x, y)),
            );
            pts.extend(ys.iter().map(|&y| Point::new(x, y)));
        }
        for &y in &ys {
            pts.extend(
                grid(bb.min.x, bb.max.x)
                    .into_iter()
                    .map(|x| Point::new(x, y)),
            );
        }
        let got = classify_all(&case, &pts);
        let poly = DensePolygon::new(&case.domain, 1e-7 * s);
        for (p, g) in pts.iter().zip(&got) {
            let (loc, decision) = c.classify_point_with_decision(*p);
            assert_eq!(loc, *g);
            *decisions.entry(decision).or_insert(0usize) += 1;
            let dist = poly.distance(*p);
            if dist < 1e-5 * s {
                // Near or on the boundary: on it only if the polygon says so (within its error).
                if *g == Location::Boundary {
                    assert!(
                        dist < 1e-6 * s,
                        "{} at {p:?}: boundary but {dist} away",
                        case.name
                    );
                }
                continue;
            }
            let truth = if poly.contains(*p) {
                Location::Inside
            } else {
                Location::Outside
            };
            assert_eq!(*g, truth, "{} at {p:?} ({decision:?})", case.name);
        }
    }
    assert!(
        decisions
            .get(&Decision::HorizontalRay)
            .copied()
            .unwrap_or(0)
            > 100,
        "{decisions:?}"
    );
    assert!(
        decisions
            .get(&Decision::WindingNumber)
            .copied()
            .unwrap_or(0)
            > 100,
        "{decisions:?}"
    );
}

/// The annulus against its analytic description, including points 1e-8 x size from either
/// circle and points exactly on the critical lines x = 0.5 +- r and y = -0.25 +- r.
#[test]
fn annulus_is_exact() {
    let case = rs_testkit::annulus();
    let s = size(&case);
    let center = Point::new(0.5, -0.25);
    let mut pts = halton_points(4000, case.domain.bounding_box());
    for r in [0.75, 2.0] {
        for k in 0..64 {
            let th = k as f64 * std::f64::consts::TAU / 64.0 + 0.01;
            for off in [-1e-8 * s, 1e-8 * s, -1e-4 * s, 1e-4 * s] {
                pts.push(center + Point::new(th.cos(), th.sin()) * (r + off));
            }
        }
        for y in [-1.0, -0.25, 0.0, 0.5] {
            pts.push(Point::new(0.5 + r, y));
            pts.push(Point::new(0.5 - r, y));
            pts.push(Point::new(y, -0.25 + r));
        }
    }
    let got = classify_all(&case, &pts);
    let tol = c_tol(&case);
    for (p, g) in pts.iter().zip(&got) {
        let d = p.distance(center);
        let truth = if (d - 2.0).abs() <= tol || (d - 0.75).abs() <= tol {
            Location::Boundary
        } else if d < 2.0 && d > 0.75 {
            Location::Inside
        } else {
            Location::Outside
        };
        if (d - 2.0).abs() <= 2.0 * tol || (d - 0.75).abs() <= 2.0 * tol {
            continue; // inside the boundary band's fuzzy edge
        }
        assert_eq!(*g, truth, "annulus at {p:?} (r = {d})");
    }
}

fn c_tol(case: &Case) -> f64 {
    Classifier::new(&case.domain, ContainOptions::default())
        .unwrap()
        .abs_tol()
}

/// Reversing every loop (and the curve order) changes nothing.
#[test]
fn orientation_does_not_matter() {
    for case in all_cases() {
        let rev: Vec<_> = case
            .domain
            .curves()
            .iter()
            .rev()
            .map(|c| c.reversed())
            .collect();
        let reversed = Case {
            name: format!("{} reversed", case.name),
            domain: rs_spline::Domain::new(rev).unwrap(),
        };
        let mut bb = case.domain.bounding_box();
        bb.min = bb.min - Point::new(0.1, 0.1);
        bb.max = bb.max + Point::new(0.1, 0.1);
        let pts = halton_points(2000, bb);
        assert_eq!(
            classify_all(&case, &pts),
            classify_all(&reversed, &pts),
            "{}",
            case.name
        );
    }
}

/// Points off the grid and at its edges: far away, on the edges of the bounding box grown by
/// the tolerance, just inside and outside them, non-finite. Every fast path agrees with inRS2
/// (non-finite points are outside).
#[test]
fn points_off_and_at_the_edges_of_the_grid() {
    for case in all_cases() {
        let c = Classifier::new(&case.domain, ContainOptions::default()).unwrap();
        let b = case.domain.bounding_box();
        let t = c.abs_tol();
        let mut pts = Vec::new();
        for x in [
            b.min.x - t,
            b.min.x,
            b.max.x,
            b.max.x + t,
            0.5 * (b.min.x + b.max.x),
        ] {
            for y in [
                b.min.y - t,
                b.min.y,
                b.max.y,
                b.max.y + t,
                0.5 * (b.min.y + b.max.y),
            ] {
                for (dx, dy) in [
                    (0.0, 0.0),
                    (-1e-3, 0.0),
                    (1e-3, 0.0),
                    (0.0, -1e-3),
                    (0.0, 1e-3),
                ] {
                    let s = size(&case);
                    pts.push(Point::new(x + dx * s, y + dy * s));
                    pts.push(Point::new(x.next_up(), y.next_down()));
                }
            }
        }
        pts.extend([
            Point::new(1e300, 0.0),
            Point::new(-1e300, -1e300),
            Point::new(b.min.x - 1e9 * size(&case), b.max.y),
        ]);
        classify_all(&case, &pts);
        let loc = c.locator();
        for q in [
            Point::new(f64::NAN, b.min.y),
            Point::new(b.min.x, f64::NAN),
            Point::new(f64::INFINITY, 0.0),
            Point::new(0.0, f64::NEG_INFINITY),
        ] {
            assert_eq!(loc.locate(q), Location::Outside, "{}: {q:?}", case.name);
            assert_eq!(c.locate(q), Location::Outside, "{}: {q:?}", case.name);
            assert_eq!(loc.locate_all(&[q; 3]), vec![Location::Outside; 3]);
        }
    }
}

/// Points off the curves along the normal at multiples of the boundary tolerance (below it,
/// just inside and outside it, beyond it), with the default tolerance and with none: the
/// locator, whose cells hold short parts of the long curved pieces, agrees with inRS2 on
/// every one.
#[test]
fn offsets_at_the_tolerance_agree_with_inrs2() {
    for case in all_cases() {
        for rel in [1e-12, 0.0] {
            let c = Classifier::new(
                &case.domain,
                ContainOptions::DEFAULT.with_relative_tolerance(rel),
            )
            .unwrap();
            let tol = rel * size(&case);
            let mut pts = Vec::new();
            for curve in case.domain.curves() {
                let (a, b) = curve.param_range();
                for k in 0..=60 {
                    let d = curve.derivatives(a + (b - a) * k as f64 / 60.0);
                    let speed = d.first.length();
                    if speed == 0.0 {
                        continue;
                    }
                    let n = d.first.perp() / speed;
                    for f in [0.0, 0.5, 0.99, 1.01, 2.0, 10.0, 1e3] {
                        pts.push(d.point + n * (f * tol));
                        pts.push(d.point - n * (f * tol));
                    }
                    pts.push(d.point + n * (1e-14 * size(&case)));
                    pts.push(d.point - n * (1e-14 * size(&case)));
                }
            }
            let expected = c.locate_all_with(Method::InRS2, &pts);
            for cells in [64, 512] {
                let loc = PointLocator::new(&c, LocatorOptions::DEFAULT.with_cells(cells));
                for (i, (g, e)) in loc.locate_all(&pts).iter().zip(&expected).enumerate() {
                    assert_eq!(
                        g, e,
                        "{}: tolerance {rel}, {cells} cells, at {:?}",
                        case.name, pts[i]
                    );
                }
            }
        }
    }
}
