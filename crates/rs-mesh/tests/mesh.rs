//! Sampling, curved triangulations and point location against independent truth: inRS
//! containment, the domains' exact areas, dense polygons of the curved triangles, and the
//! documented spacing bounds.

use rs_contain::Locate;
use rs_contain::baselines::halton_points;
use rs_contain::{Classifier, ContainOptions, Location};
use rs_mesh::{
    CurvedLocator, CurvedTriangulation, EdgeKind, Refinement, WellSpacedPoints, halton_points_in,
    well_spaced_points,
};
use rs_spline::prelude::*;
use rs_spline::{BoundingBox, Domain, Point};
use rs_testkit::{Case, all_cases};

fn cases() -> Vec<Case> {
    all_cases()
}

fn min_pair_distance(a: &[Point], b: &[Point], same: bool) -> f64 {
    let mut m = f64::INFINITY;
    for (i, p) in a.iter().enumerate() {
        for (j, q) in b.iter().enumerate() {
            if !(same && i >= j) {
                m = m.min(p.distance(*q));
            }
        }
    }
    m
}

#[test]
fn well_spaced_points_are_inside_and_well_spaced() {
    for case in cases() {
        let d = &case.domain;
        let pts = well_spaced_points(d, 16).unwrap();
        let h = pts.h;
        let c = Classifier::new(d, ContainOptions::default()).unwrap();
        for p in &pts.interior {
            assert_eq!(c.locate(*p), Location::Inside, "{}: {p:?}", case.name);
        }
        let boundary: Vec<Point> = pts.boundary.iter().flatten().map(|b| b.point).collect();
        for p in &boundary {
            assert_eq!(c.locate(*p), Location::Boundary, "{}: {p:?}", case.name);
        }
        // Documented bounds: interior >= 0.75 h apart, >= h/2 from boundary points.
        let ii = min_pair_distance(&pts.interior, &pts.interior, true);
        let ib = min_pair_distance(&pts.interior, &boundary, false);
        assert!(
            ii >= 0.75 * h * (1.0 - 1e-9),
            "{}: interior spacing {}",
            case.name,
            ii / h
        );
        assert!(
            ib >= 0.5 * h * (1.0 - 1e-9),
            "{}: interior-boundary {}",
            case.name,
            ib / h
        );
        // Boundary points: at least h/3 apart by arc length on one curve, so (the test
        // domains have no corner sharper than 90 degrees) at least h/5 apart as chords.
        for l in &pts.boundary {
            for w in l.windows(2) {
                if w[0].curve == w[1].curve {
                    let gap = w[0].point.distance(w[1].point);
                    assert!(gap >= 0.2 * h, "{}: boundary gap {}", case.name, gap / h);
                }
            }
        }
        // Coverage: every inside point of the domain is within 1.2 h of a sample.
        let all = pts.all_points();
        let probe: Vec<Point> = halton_points(400, d.bounding_box())
            .into_iter()
            .filter(|p| c.locate(*p) == Location::Inside)
            .collect();
        for p in probe {
            let near = all
                .iter()
                .map(|q| q.distance(p))
                .fold(f64::INFINITY, f64::min);
            assert!(
                near <= 1.2 * h,
                "{}: hole in the sample at {p:?} ({})",
                case.name,
                near / h
            );
        }
    }
}

#[test]
fn point_count_scales_like_ny_squared() {
    for case in rs_testkit::fixtures() {
        let n = |ny| {
            let p: WellSpacedPoints = well_spaced_points(&case.domain, ny).unwrap();
            (p.interior.len() + p.boundary.iter().map(Vec::len).sum::<usize>()) as f64
        };
        let (a, b) = (n(24), n(48));
        let ratio = b / a;
        assert!(
            (3.2..=4.6).contains(&ratio),
            "{}: {a} -> {b} ({ratio})",
            case.name
        );
    }
}

#[test]
fn halton_sampling_gives_the_requested_count_inside() {
    for case in rs_testkit::synthetic() {
        let d = &case.domain;
        let pts = halton_points_in(d, 500).unwrap();
        assert_eq!(pts.len(), 500);
        let c = Classifier::new(d, ContainOptions::default()).unwrap();
        assert!(pts.iter().all(|p| c.locate(*p) == Location::Inside));
        assert_eq!(pts, halton_points_in(d, 500).unwrap(), "deterministic");
    }
    // Exactly the first inside candidates, one at a time, whatever the batches (the first
    // sized for the count, the next from the share inside, at most 65 536, by the locator
    // from 50 000 on).
    let d = &rs_testkit::annulus().domain;
    let c = Classifier::new(d, ContainOptions::default()).unwrap();
    let candidates = halton_points(300_000, d.bounding_box());
    let one_at_a_time: Vec<Point> = candidates
        .into_iter()
        .filter(|&p| c.locate(p) == Location::Inside)
        .collect();
    for count in [1, 63, 64, 65, 500, 70_000, 150_000] {
        let got = halton_points_in(d, count).unwrap();
        assert!(got == one_at_a_time[..count], "count {count}");
    }
    assert!(halton_points_in(d, 0).is_err());
    // A thin strip along its box is sampled; along the box's diagonal it fills 1e-6 of the
    // box, the candidates run out (1000 per point asked for) after batches of every size, and
    // that is an error, not a short answer.
    let along = Domain::new(polygon(&[(0.0, 0.0), (1.0, 0.0), (1.0, 2e-4), (0.0, 1e-4)])).unwrap();
    assert_eq!(halton_points_in(&along, 100).unwrap().len(), 100);
    let diagonal = Domain::new(polygon(&[
        (0.0, 0.0),
        (1.0, 1.0 - 1e-6),
        (1.0, 1.0),
        (0.0, 1e-6),
    ]))
    .unwrap();
    assert!(matches!(
        halton_points_in(&diagonal, 100),
        Err(rs_mesh::MeshError::InvalidCount(100))
    ));
    assert!(well_spaced_points(d, 1).is_err());
    assert!(well_spaced_points(d, rs_mesh::MAX_LINES + 1).is_err());
}

/// The closed boundary of curved triangle `t` as a dense polygon.
fn curved_triangle_polygon(m: &CurvedTriangulation, t: usize) -> Vec<Point> {
    let tri = m.triangles()[t];
    let mut poly = Vec::new();
    for (&a, kind) in tri.iter().zip(m.edge_kinds(t)) {
        match kind {
            EdgeKind::Straight => poly.push(m.vertices()[a]),
            EdgeKind::Curved(i) => {
                let arc = &m.arcs()[i];
                let c = &m.domain().curves()[arc.curve];
                let n = 400;
                for j in 0..n {
                    let s = j as f64 / n as f64;
                    let s = if arc.from == a { s } else { 1.0 - s };
                    let u = arc.u0 + (arc.u1 - arc.u0) * s;
                    poly.push(if j == 0 {
                        m.vertices()[a]
                    } else {
                        c.point_at(u)
                    });
                }
            }
        }
    }
    poly
}

fn polygon_contains(poly: &[Point], p: Point) -> bool {
    let mut odd = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a.x <= p.x) != (b.x <= p.x) {
            let y = a.y + (p.x - a.x) * (b.y - a.y) / (b.x - a.x);
            if y < p.y {
                odd = !odd;
            }
        }
    }
    odd
}

fn distance_to_polygon(poly: &[Point], p: Point) -> f64 {
    (0..poly.len())
        .map(|i| rs_testkit::segment_distance(p, (poly[i], poly[(i + 1) % poly.len()])))
        .fold(f64::INFINITY, f64::min)
}

fn segments_cross(a: Point, b: Point, c: Point, d: Point) -> bool {
    let o = |p: Point, q: Point, r: Point| (q - p).cross(r - p);
    let (d1, d2, d3, d4) = (o(c, d, a), o(c, d, b), o(a, b, c), o(a, b, d));
    (d1 > 0.0) != (d2 > 0.0)
        && (d3 > 0.0) != (d4 > 0.0)
        && d1 != 0.0
        && d2 != 0.0
        && d3 != 0.0
        && d4 != 0.0
}

fn mesh(d: &Domain, ny: usize) -> CurvedTriangulation {
    CurvedTriangulation::new(d, &well_spaced_points(d, ny).unwrap()).unwrap()
}

#[test]
fn curved_triangles_are_valid_and_add_up_to_the_domain() {
    for case in cases() {
        let d = &case.domain;
        let m = mesh(d, 12);
        let total: f64 = (0..m.triangles().len()).map(|t| m.triangle_area(t)).sum();
        let exact = region_area(d);
        assert!(
            (total - exact).abs() <= 1e-9 * exact,
            "{}: triangles {total} vs domain {exact}",
            case.name
        );
        for t in 0..m.triangles().len() {
            assert!(
                m.triangle_area(t) > 0.0,
                "{}: triangle {t} not positive",
                case.name
            );
            // Valid curved triangle: its boundary (arcs densely sampled) does not cross itself.
            let poly = curved_triangle_polygon(&m, t);
            let n = poly.len();
            for i in 0..n {
                for j in i + 2..n {
                    if i == 0 && j == n - 1 {
                        continue;
                    }
                    assert!(
                        !segments_cross(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n]),
                        "{}: triangle {t} crosses itself",
                        case.name
                    );
                }
            }
        }
        // Every loop is covered by arcs: one arc per boundary vertex of the loop.
        for (j, _) in d.loops().iter().enumerate() {
            let arcs = m.arcs().iter().filter(|a| a.loop_index == j).count();
            let verts = (0..m.vertices().len())
                .filter(|&v| m.boundary_vertex(v).is_some_and(|b| b.loop_index == j))
                .count();
            assert_eq!(arcs, verts, "{}: loop {j}", case.name);
        }
    }
}

/// Area of the region by parity, for domains whose loops do not cross: each loop's absolute
/// area, added at even nesting depth and subtracted at odd depth (depth = number of other
/// loops around one of its points, each tested on its own).
fn region_area(d: &Domain) -> f64 {
    let loops: Vec<Domain> = d
        .loops()
        .iter()
        .map(|l| Domain::new(d.curves()[l.curves()].to_vec()).unwrap())
        .collect();
    let classifiers: Vec<Classifier> = loops
        .iter()
        .map(|l| Classifier::new(l, ContainOptions::default()).unwrap())
        .collect();
    let mut total = 0.0;
    for (i, l) in loops.iter().enumerate() {
        let p = l.curves()[0].start_point();
        let depth = (0..loops.len())
            .filter(|&j| j != i && classifiers[j].locate(p) == Location::Inside)
            .count();
        let a = l.signed_area().abs();
        total += if depth % 2 == 0 { a } else { -a };
    }
    total
}

#[test]
fn point_location_agrees_with_containment() {
    let mut total_lens = 0;
    for case in cases() {
        let d = &case.domain;
        let m = mesh(d, 10);
        let loc = CurvedLocator::new(&m).unwrap();
        let c = Classifier::new(d, ContainOptions::default()).unwrap();
        let s = d.bounding_box().diagonal();
        let mut bb = d.bounding_box();
        bb.min = bb.min - Point::new(0.02 * s, 0.02 * s);
        bb.max = bb.max + Point::new(0.02 * s, 0.02 * s);
        let polys: Vec<Vec<Point>> = (0..m.triangles().len())
            .map(|t| curved_triangle_polygon(&m, t))
            .collect();
        let mut in_lens = 0;
        for p in halton_points(3000, bb) {
            let located = loc.triangle_at(p);
            let inside = c.locate(p) != Location::Outside;
            assert_eq!(located.is_some(), inside, "{}: {p:?}", case.name);
            if let Some(t) = located {
                let poly = &polys[t];
                if distance_to_polygon(poly, p) > 1e-9 * s {
                    assert!(
                        polygon_contains(poly, p),
                        "{}: {p:?} not in triangle {t}",
                        case.name
                    );
                }
                let v = m.triangles()[t].map(|i| m.vertices()[i]);
                let companion = polygon_contains(&v, p);
                if !companion {
                    in_lens += 1;
                }
            }
        }
        total_lens += in_lens;
    }
    assert!(total_lens > 0, "no point fell between an arc and its chord");
}

#[test]
fn coarse_samples_are_made_convertible_by_inserting_boundary_points() {
    let mut inserted = 0;
    for case in cases() {
        let d = &case.domain;
        for ny in [2, 3, 5] {
            let m = mesh(d, ny);
            inserted += m.inserted_boundary_points();
            let total: f64 = (0..m.triangles().len()).map(|t| m.triangle_area(t)).sum();
            let exact = region_area(d);
            assert!(
                (total - exact).abs() <= 1e-9 * exact,
                "{} ny={ny}: {total} vs {exact}",
                case.name
            );
            assert!((0..m.triangles().len()).all(|t| m.triangle_area(t) > 0.0));
        }
    }
    assert!(
        inserted > 0,
        "no case needed insertion: the test does not exercise it"
    );
}

#[test]
fn user_points_without_boundary_points_still_give_a_curved_triangulation() {
    // Only interior points: the curve starts are added and arcs split until convertible.
    let d = &rs_testkit::annulus().domain;
    let interior = halton_points_in(d, 40).unwrap();
    let pts = WellSpacedPoints {
        h: 0.5,
        interior,
        boundary: Vec::new(),
    };
    let m = CurvedTriangulation::new(d, &pts).unwrap();
    assert!(m.inserted_boundary_points() > 0);
    let total: f64 = (0..m.triangles().len()).map(|t| m.triangle_area(t)).sum();
    assert!((total - region_area(d)).abs() <= 1e-9 * total);
}

/// The ring of Algorithm 5.1 covers every sliver: points between each boundary arc and its
/// chord (outside every companion triangle) lie in a ring triangle whose neighbour is the
/// arc's triangle, and the ring has `2 n_b` triangles.
#[test]
fn the_extended_ring_covers_the_slivers() {
    use rs_spline::prelude::*;
    for case in rs_testkit::all_cases().into_iter().take(8) {
        let m = mesh(&case.domain, 6);
        let ring = m.extended_ring().unwrap();
        assert_eq!(ring.triangles.len(), 2 * m.arcs().len(), "{}", case.name);
        let inside = |tri: &[Point; 3], p: Point| {
            let area = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
            (0..3).all(|k| (tri[(k + 1) % 3] - tri[k]).cross(p - tri[k]) >= -1e-12 * area.abs())
        };
        let companions: Vec<[Point; 3]> = m
            .triangles()
            .iter()
            .map(|t| t.map(|i| m.vertices()[i]))
            .collect();
        let mut checked = 0;
        for a in m.arcs() {
            let c = m.arc_curve(a).unwrap();
            let (u0, u1) = c.param_range();
            for s in [0.2, 0.5, 0.8] {
                let on = c.point_at(u0 + s * (u1 - u0));
                let chord = m.vertices()[a.from] * (1.0 - s) + m.vertices()[a.to] * s;
                let p = on * 0.98 + chord * 0.02;
                if companions.iter().any(|t| inside(t, p)) {
                    continue; // the arc bulges inwards here: no outer sliver
                }
                checked += 1;
                let hit = ring
                    .triangles
                    .iter()
                    .zip(&ring.neighbour)
                    .find(|(t, _)| inside(t, p));
                let (_, &n) = hit.unwrap_or_else(|| panic!("{}: {p:?} not in the ring", case.name));
                assert_eq!(n, a.triangle, "{}", case.name);
            }
        }
        assert!(
            checked > 0
                || m.arcs()
                    .iter()
                    .all(|a| m.arc_curve(a).unwrap().degree() == 1)
        );
    }
}

/// A closed polygon as segments.
fn polygon(points: &[(f64, f64)]) -> Vec<rs_spline::NurbsCurve> {
    (0..points.len())
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % points.len()]);
            rs_spline::segment(Point::new(a.0, a.1), Point::new(b.0, b.1)).unwrap()
        })
        .collect()
}

/// Two rectangles that share stretches of their bottom and top edges (`[1, 2]` at `y = 0`
/// and `y = 1`): the chords along the overlap coincide however often they are split, and
/// their number doubled with every round of insertion (ny = 5: 6.4 s and 1.1 GB of memory,
/// 2^16 times the overlap's chords, before the round limit ended it). The insertion budget
/// ends it, naming a point of the overlap; so does a shared curve.
#[test]
fn overlapping_loops_end_at_the_insertion_budget_near_the_overlap() {
    let mut curves = polygon(&[(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (0.0, 1.0)]);
    curves.extend(polygon(&[(1.0, 0.0), (3.0, 0.0), (3.0, 1.0), (1.0, 1.0)]));
    let d = Domain::new(curves).unwrap();
    for ny in [2, 5, 40] {
        let points = well_spaced_points(&d, ny).unwrap();
        let initial: usize = points.boundary.iter().map(Vec::len).sum();
        match CurvedTriangulation::new(&d, &points) {
            Err(rs_mesh::MeshError::InsertionLimit {
                inserted,
                limit,
                near,
                ..
            }) => {
                assert!(inserted <= limit, "ny={ny}: {inserted} > {limit}");
                assert!(
                    limit
                        <= rs_mesh::MAX_INSERTED_PER_POINT * (initial + d.curves().len())
                            + rs_mesh::MAX_INSERTED_EXTRA,
                    "ny={ny}: limit {limit}"
                );
                let on_overlap = (near.y == 0.0 || near.y == 1.0) && (1.0..=2.0).contains(&near.x);
                assert!(on_overlap, "ny={ny}: near {near:?}");
            }
            other => panic!("ny={ny}: {:?}", other.map(|t| t.triangles().len())),
        }
    }
    // A loop and a second loop that runs back along the same cubic.
    let arc = |a: Point, b: Point| {
        rs_spline::NurbsCurve::bezier(vec![a, Point::new(1.0, 1.0), Point::new(2.0, 1.0), b], None)
            .unwrap()
    };
    let (o, e) = (Point::new(0.0, 0.0), Point::new(3.0, 0.0));
    let mut curves = vec![arc(o, e), rs_spline::segment(e, o).unwrap()];
    curves.push(arc(o, e));
    let corners = [e, Point::new(3.0, -1.0), Point::new(0.0, -1.0), o];
    curves.extend(
        corners
            .windows(2)
            .map(|w| rs_spline::segment(w[0], w[1]).unwrap()),
    );
    let d = Domain::new(curves).unwrap();
    let err = CurvedTriangulation::new(&d, &well_spaced_points(&d, 5).unwrap()).unwrap_err();
    assert!(
        matches!(err, rs_mesh::MeshError::InsertionLimit { near, .. } if near.y >= 0.0 && near.y <= 0.75),
        "{err}"
    );
}

/// A circle of radius 1e-12 at x = 1e15, where coordinates are rounded to 0.125: the lines'
/// crossings are rounding noise 10^12 spacings apart. The points are counted before they
/// are made (this ran out of memory at 24 GB): an error at once.
#[test]
fn a_curve_below_the_rounding_of_its_coordinates_is_refused_before_sampling() {
    let d = Domain::new(vec![
        rs_spline::circle(Point::new(1e15, 0.0), 1e-12).unwrap(),
    ])
    .unwrap();
    let err = well_spaced_points(&d, 20).unwrap_err();
    assert!(
        matches!(err, rs_mesh::MeshError::TooManyPoints { limit, .. } if limit == rs_mesh::MAX_SAMPLE_POINTS),
        "{err}"
    );
}

/// Two circles that cross: the chords at each crossing cross, and once the arcs there are
/// flat enough for their control polygons to show it the two curves certainly meet; the
/// error names the crossing (closed in on by halving the two arcs).
#[test]
fn crossing_loops_are_refused_naming_the_crossing() {
    let d = two_unit_circles(0.8);
    let crossing_y = (1.0f64 - 0.16).sqrt();
    for ny in [2, 20] {
        let err = CurvedTriangulation::new(&d, &well_spaced_points(&d, ny).unwrap()).unwrap_err();
        let rs_mesh::MeshError::BoundaryCrosses { near } = err else {
            panic!("ny={ny}: {err}");
        };
        let to_crossing = near.distance(Point::new(0.4, crossing_y.copysign(near.y)));
        assert!(to_crossing < 1e-9, "ny={ny}: {near:?} {to_crossing}");
        assert!(err.to_string().contains("crosses itself"), "{err}");
    }
}

/// One loop crossing itself (a figure eight of two cubics through the origin): refused before
/// any triangle is built (it used to give a triangulation whose arcs missed their vertices).
#[test]
fn a_loop_crossing_itself_is_refused() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/fill-rule/figure_eight.json"
    ))
    .unwrap();
    let d = rs_io::json::domain_from_json(&text).unwrap();
    for ny in [4, 8, 20] {
        let err = CurvedTriangulation::new(&d, &well_spaced_points(&d, ny).unwrap()).unwrap_err();
        let rs_mesh::MeshError::BoundaryCrosses { near } = err else {
            panic!("ny={ny}: {err}");
        };
        assert!(
            near.distance(Point::new(0.0, 0.0)) < 1e-6,
            "ny={ny}: {near:?}"
        );
    }
}

/// Loops that touch without crossing, and a loop near another without meeting it: never
/// refused as crossing (the certificate needs each arc's ends on both sides of the other).
#[test]
fn touching_or_close_loops_are_not_called_crossing() {
    for apart in [2.0, 2.0 + 1e-6] {
        let d = two_unit_circles(apart);
        let m = CurvedTriangulation::new(&d, &well_spaced_points(&d, 5).unwrap());
        assert!(
            !matches!(m, Err(rs_mesh::MeshError::BoundaryCrosses { .. })),
            "{apart}: {m:?}"
        );
    }
}

/// Unit circles centred at the origin and at `(apart, 0)`, as two loops.
fn two_unit_circles(apart: f64) -> Domain {
    Domain::new(vec![
        rs_spline::circle(Point::new(0.0, 0.0), 1.0).unwrap(),
        rs_spline::circle(Point::new(apart, 0.0), 1.0).unwrap(),
    ])
    .unwrap()
}

/// A hole sampled at one point (its curve's start): its one arc is split, and the two arcs
/// it then has share one chord; both are split again (the chord is not an overlap of the
/// boundary), and the mesh covers the domain.
#[test]
fn two_arcs_on_one_chord_are_split_not_refused() {
    let d = Domain::new(vec![
        rs_spline::circle(Point::new(0.0, 0.0), 4.0).unwrap(),
        rs_spline::circle(Point::new(1.0, 0.5), 0.3).unwrap(),
    ])
    .unwrap();
    let mut points = well_spaced_points(&d, 2).unwrap();
    // The hole's boundary points: its curve's start only.
    let hole = &mut points.boundary[1];
    hole.truncate(1);
    let m = CurvedTriangulation::new(&d, &points).unwrap();
    assert!(m.inserted_boundary_points() > 0);
    let total: f64 = (0..m.triangles().len()).map(|t| m.triangle_area(t)).sum();
    let exact = std::f64::consts::PI * (16.0 - 0.09);
    assert!((total - exact).abs() < 1e-9 * exact, "{total} vs {exact}");
}

/// A rectangle 2000 times longer than wide at ny = 5: 20 000 boundary points along two long
/// straight sides. Inserted in loop order they took a flip of every edge back to the start
/// per point (3.4 s at 3000 x 1, minutes for a mutated drawing of 77 000 points); the mesh
/// must cover the rectangle exactly, with the boundary vertices first and in loop order.
#[test]
fn a_long_thin_rectangle_is_meshed_exactly() {
    let d = Domain::new(polygon(&[
        (0.0, 0.0),
        (2000.0, 0.0),
        (2000.0, 1.0),
        (0.0, 1.0),
    ]))
    .unwrap();
    let points = well_spaced_points(&d, 5).unwrap();
    let boundary: Vec<Point> = points.boundary.iter().flatten().map(|b| b.point).collect();
    assert!(boundary.len() > 20_000, "{}", boundary.len());
    let m = CurvedTriangulation::new(&d, &points).unwrap();
    assert_eq!(&m.vertices()[..boundary.len()], &boundary[..]);
    let total: f64 = (0..m.triangles().len()).map(|t| m.triangle_area(t)).sum();
    assert!((total - 2000.0).abs() < 1e-9 * 2000.0, "{total}");
    assert!((0..m.triangles().len()).all(|t| m.triangle_area(t) > 0.0));
    // Point location on it (its grid's cells near square, not 2000 times wider than high).
    let loc = CurvedLocator::new(&m).unwrap();
    let bb = BoundingBox::from_point(Point::new(-1.0, -0.5)).including(Point::new(2001.0, 1.5));
    for p in halton_points(5000, bb) {
        let inside = (0.0..=2000.0).contains(&p.x) && (0.0..=1.0).contains(&p.y);
        match loc.triangle_at(p) {
            Some(t) => {
                let v = m.triangles()[t].map(|i| m.vertices()[i]);
                assert!(
                    inside && distance_to_polygon(&v, p) < 1e-9 || polygon_contains(&v, p),
                    "{p:?}"
                );
            }
            None => assert!(!inside, "{p:?}"),
        }
    }
}

/// The three builders on `d` from `points`: each convertible, its curved triangles positive
/// and adding up to the domain. Returns the Powell–Sabin one.
fn every_refinement_is_exact(
    d: &Domain,
    points: &WellSpacedPoints,
    what: &str,
) -> CurvedTriangulation {
    let exact = region_area(d);
    let mut last = None;
    for how in [
        None,
        Some(Refinement::CloughTocher),
        Some(Refinement::PowellSabin),
    ] {
        let m = match how {
            None => CurvedTriangulation::new(d, points),
            Some(how) => CurvedTriangulation::new_refined(d, points, how),
        }
        .unwrap_or_else(|e| panic!("{what} {how:?}: {e}"));
        let total: f64 = (0..m.triangles().len()).map(|t| m.triangle_area(t)).sum();
        assert!(
            (total - exact).abs() <= 1e-9 * exact,
            "{what} {how:?}: {total} vs {exact}"
        );
        assert!(
            (0..m.triangles().len()).all(|t| m.triangle_area(t) > 0.0),
            "{what} {how:?}"
        );
        last = Some(m);
    }
    last.unwrap_or_else(|| unreachable!())
}

/// A reflex corner of a polygon written as one degree-1 curve (knots 0, 1, ..., 5), at
/// parameter 3: every arc across it turns by the corner's angle however short it is, into
/// its triangle, and parameter midpoints of `[0, 5]` never land on 3, so splitting the
/// failing arc at its midpoint ended after 16 rounds (`NotConvertible`, unrefined and refined
/// alike) with the arc 2^-16 of the loop long. The corner must become a vertex.
#[test]
fn a_corner_off_every_parameter_midpoint_becomes_a_vertex() {
    let q = Point::new;
    let outline = [
        q(0.0, 0.0),
        q(3.0, 0.0),
        q(3.0, 3.0),
        q(1.5, 1.0),
        q(0.0, 3.0),
        q(0.0, 0.0),
    ];
    let d = Domain::new(vec![rs_spline::polyline(&outline).unwrap()]).unwrap();
    for n in [0, 3, 10, 40] {
        let interior = if n == 0 {
            Vec::new()
        } else {
            halton_points_in(&d, n).unwrap()
        };
        let points = WellSpacedPoints {
            h: 0.5,
            interior,
            boundary: Vec::new(),
        };
        let m = every_refinement_is_exact(&d, &points, &format!("{n} interior points"));
        assert!(m.inserted_boundary_points() > 0);
        assert!(
            m.vertices().contains(&q(1.5, 1.0)),
            "{n}: the reflex corner is no vertex"
        );
    }
}

/// The heptagon written as one quadratic curve with break points of full multiplicity at
/// parameters k/7: at ny = 17 an arc across its reflex corner (0.9, 1.4) passed the
/// unrefined check but crossed an edge of its Powell–Sabin split, and its halvings never
/// reached the corner (`inrs fit --refine ps --ny 17` ended in `NotConvertible`). Every ny of
/// the sample -> fit tests, every refinement.
#[test]
fn heptagon_breaks_is_convertible_in_every_refinement_at_every_fit_ny() {
    let path = rs_testkit::fixture_path("breaks/heptagon_breaks.json");
    let d = rs_io::json::domain_from_json_file(&path).unwrap();
    for ny in [9, 17, 33, 65] {
        let points = well_spaced_points(&d, ny).unwrap();
        every_refinement_is_exact(&d, &points, &format!("ny {ny}"));
    }
}
