//! The fill rule, honoured by every method: nested loops of either orientation, loops that
//! cross each other and loops that cross themselves (`fixtures/fill-rule/`), classified by
//! inRS1, inRS2, the grid locator and the winding field, in batches of every size and one by
//! one, against the winding numbers of a dense polygon; the filled area against closed forms
//! where the loops do not cross, and a clear error where they do.

use rs_boxes::{BoxOptions, MonotoneBoxes};
use rs_contain::{
    Classifier, ContainOptions, Containment, FAST_METHOD_MIN_POINTS, FillRule, Locate, Location,
    Method, NestingError, PointQuery, WindingField, filled_area,
};
use rs_spline::{Domain, Point};
use rs_testkit::{DensePolygon, NearBoundary};

const RULES: [FillRule; 2] = [FillRule::EvenOdd, FillRule::NonZero];

/// Points over the domain's box grown by a tenth: a grid with at least `n` points, and the
/// vertical and horizontal lines through every critical point (where the crossing methods
/// turn to their fallbacks: the horizontal ray, then the winding number).
fn points(d: &Domain, n: usize) -> Vec<Point> {
    let b = d.bounding_box();
    let (mx, my) = (0.1 * b.width(), 0.1 * b.height());
    let (x0, y0, w, h) = (
        b.min.x - mx,
        b.min.y - my,
        b.width() + 2.0 * mx,
        b.height() + 2.0 * my,
    );
    let side = (n as f64).sqrt().ceil() as usize;
    let mut pts = Vec::with_capacity(side * side);
    for j in 0..side {
        for i in 0..side {
            // Off the (often round) coordinates of the fixtures.
            let (u, v) = (
                (i as f64 + 0.37) / side as f64,
                (j as f64 + 0.61) / side as f64,
            );
            pts.push(Point::new(x0 + u * w, y0 + v * h));
        }
    }
    let boxes = MonotoneBoxes::new(d, BoxOptions::DEFAULT).unwrap();
    for &x in boxes.critical_abscissas() {
        pts.extend((0..40).map(|k| Point::new(x, y0 + (k as f64 + 0.5) / 40.0 * h)));
    }
    for &y in boxes.critical_ordinates() {
        pts.extend((0..40).map(|k| Point::new(x0 + (k as f64 + 0.5) / 40.0 * w, y)));
        for &x in boxes.critical_abscissas() {
            pts.push(Point::new(x, y));
        }
    }
    pts
}

/// The truth at `p`: the dense polygon's winding number (its signed crossings of the downward
/// ray, an independent count on straight edges), `None` near the boundary (not compared).
fn truth_winding(poly: &DensePolygon, near: &NearBoundary, p: Point) -> Option<i64> {
    if near.is_near(p) {
        return None;
    }
    let mut w = 0;
    for &(a, b) in &poly.edges {
        if (a.x <= p.x) != (b.x <= p.x) {
            let y = a.y + (p.x - a.x) * (b.y - a.y) / (b.x - a.x);
            if y < p.y {
                w += if a.x < b.x { 1 } else { -1 };
            }
        }
    }
    Some(w)
}

/// The locations `rule` gives the winding numbers `w`.
fn locations(w: &[Option<i64>], rule: FillRule) -> Vec<Option<Location>> {
    w.iter()
        .map(|w| {
            w.map(|w| {
                if rule.fills(w) {
                    Location::Inside
                } else {
                    Location::Outside
                }
            })
        })
        .collect()
}

#[test]
fn every_method_classifies_by_the_fill_rule() {
    for (case, _) in rs_testkit::fill_rule_fixtures() {
        let d = &case.domain;
        let poly = DensePolygon::new(d, 1e-7);
        let near = NearBoundary::new(&poly, 1e-5 * d.bounding_box().diagonal());
        // Points for every method against the truth, and enough for the grid locator,
        // checked against inRS2 (checked itself on the first ones).
        let few = points(d, 2000);
        let many = points(d, FAST_METHOD_MIN_POINTS);
        let w_few: Vec<_> = few
            .iter()
            .map(|&p| truth_winding(&poly, &near, p))
            .collect();
        let differ = locations(&w_few, FillRule::EvenOdd) != locations(&w_few, FillRule::NonZero);
        for rule in RULES {
            let check = |pts: &[Point], got: &[Location], want: &[Option<Location>], how: &str| {
                let wrong: Vec<_> = pts
                    .iter()
                    .zip(got)
                    .zip(want)
                    .filter(|((_, g), w)| w.is_some_and(|w| w != **g))
                    .map(|((p, g), w)| format!("{p:?}: {g:?}, not {w:?}"))
                    .collect();
                assert!(
                    wrong.is_empty(),
                    "{} ({rule}), {how}: {} wrong, first {}",
                    case.name,
                    wrong.len(),
                    wrong[0]
                );
            };
            let want_few = locations(&w_few, rule);
            for method in Method::ALL {
                let options = ContainOptions::DEFAULT
                    .with_method(method)
                    .with_fill_rule(rule);
                let c = Containment::new(d, options).unwrap();
                // A large batch (the grid locator for the fast method), a small one (inRS2),
                // a tiny one (one by one), and single points.
                if method == Method::Fast {
                    let mut out = vec![Location::Boundary; many.len()];
                    c.engine(many.len()).par_values_into(&many[..], &mut out);
                    let inrs2 = ContainOptions::DEFAULT
                        .with_method(Method::InRS2)
                        .with_fill_rule(rule);
                    let inrs2 = Classifier::new(d, inrs2).unwrap().locate_all(&many);
                    assert!(out == inrs2, "{} ({rule}): the grid locator", case.name);
                }
                let mut out = vec![Location::Boundary; few.len()];
                c.engine(few.len()).values_into(&few[..], &mut out);
                check(&few, &out, &want_few, &format!("{method:?} on a batch"));
                let engine = c.engine(1);
                let one: Vec<_> = few.iter().map(|&p| engine.value(p)).collect();
                check(&few, &one, &want_few, &format!("{method:?} one by one"));
            }
            // The classifier's own methods and a winding field take the same rule.
            let c = Classifier::new(d, ContainOptions::DEFAULT.with_fill_rule(rule)).unwrap();
            assert_eq!(c.fill_rule(), rule);
            for method in Method::ALL {
                let got = c.locate_all_with(method, &few);
                check(&few, &got, &want_few, &format!("classifier {method:?}"));
            }
            let field = WindingField::new(d, rs_contain::DEFAULT_RELATIVE_TOLERANCE)
                .unwrap()
                .with_fill_rule(rule);
            check(&few, &field.locate_all(&few), &want_few, "winding field");
        }
        // The rules differ on every fixture but those whose windings are 0 and +-1.
        let alike = ["nested_opposite", "overlapping_opposite", "figure_eight"];
        assert_eq!(
            !differ,
            alike.contains(&case.name.as_str()),
            "{}",
            case.name
        );
    }
}

/// The winding numbers themselves: the field's, rounded, are the dense polygon's.
#[test]
fn winding_numbers_are_the_dense_polygons() {
    for (case, _) in rs_testkit::fill_rule_fixtures() {
        let d = &case.domain;
        let poly = DensePolygon::new(d, 1e-8);
        let near = NearBoundary::new(&poly, 1e-6 * d.bounding_box().diagonal());
        let field = WindingField::new(d, rs_contain::DEFAULT_RELATIVE_TOLERANCE).unwrap();
        let pts = points(d, 1000);
        let mut values = vec![0.0; pts.len()];
        let numbers = field.winding_numbers_by(rs_contain::baselines::WindingAlgorithm::Adaptive);
        numbers.values_into(&pts[..], &mut values);
        for (p, w) in pts.iter().zip(&values) {
            if !near.is_near(*p) {
                let want = poly.winding_number(*p);
                assert!(
                    (w - want).abs() < 1e-6,
                    "{} at {p:?}: {w} vs {want}",
                    case.name
                );
            }
        }
    }
}

/// The filled area under each rule: the closed forms for nested circles; an error naming the
/// crossing for loops that cross.
#[test]
fn filled_areas_follow_the_rule_or_name_the_crossing() {
    use std::f64::consts::PI;
    let exact = |name: &str, rule: FillRule| -> f64 {
        match (name, rule) {
            ("nested_same", FillRule::EvenOdd) => 3.0 * PI,
            ("nested_same", FillRule::NonZero) => 4.0 * PI,
            ("nested_opposite", _) => 3.0 * PI,
            // Ring 3..2, the inner disc, less (even-odd) the small disc in the ring.
            ("three_nested", FillRule::EvenOdd) => 5.0 * PI + PI - 0.09 * PI,
            ("three_nested", FillRule::NonZero) => 5.0 * PI + PI,
            _ => unreachable!(),
        }
    };
    for (case, crossing) in rs_testkit::fill_rule_fixtures() {
        for rule in RULES {
            let got = filled_area(&case.domain, rule);
            if crossing {
                let e = got.unwrap_err();
                assert!(matches!(e, NestingError::Crossing(_)), "{}: {e}", case.name);
                assert!(e.to_string().contains("cross"), "{e}");
            } else {
                let (got, want) = (got.unwrap(), exact(&case.name, rule));
                assert!(
                    (got - want).abs() < 1e-12,
                    "{} ({rule}): {got} vs {want}",
                    case.name
                );
            }
        }
    }
}
