//! A rule scales with its domain: the same rule, exactly, whatever the domain's size. Scaling
//! the coordinates by a power of two `2^k` scales every value and every rounding of the rule's
//! making exactly, so the nodes come out times `2^k` and the weights times `4^k`, bit for bit,
//! from `2^-480` to `2^480` across (areas about `1e-289` to `1e289`; the compression squares
//! the moments' size, which overflowed beyond about `1e77` across and underflowed below
//! `1e-77` before the moments were scaled to a unit area). Other sizes give a rule within the
//! target on the domain scaled (up to the coordinates' limit, `1e150`); areas below [`SMALLEST_AREA`] are refused.

use rs_contain::{Classifier, ContainOptions, FillRule, Location, Method, filled_area};
use rs_cubature::{CubatureError, CubatureRule, DEFAULT_TARGET_RESIDUAL, SMALLEST_AREA};
use rs_spline::{Domain, Point, circle, polyline};

/// An off-centre disc (rational pieces) with a triangular hole (lines), times `s`.
fn holed_disc(s: f64) -> Domain {
    let p = |x: f64, y: f64| Point::new(x * s, y * s);
    let hole = polyline(&[p(0.1, -0.5), p(0.7, 0.1), p(0.2, 0.3), p(0.1, -0.5)]).unwrap();
    Domain::new(vec![circle(p(0.3, -0.2), s).unwrap(), hole]).unwrap()
}

#[test]
fn a_rule_scaled_by_a_power_of_two_is_the_same_rule_bit_for_bit() {
    // Degree 36 takes the chord formula's first attempt (its orders' tolerance in the
    // domain's units); two sizes there, each a second of the test profile.
    for (degree, powers) in [
        (6, &[-480, -260, -7, 9, 260, 480][..]),
        (12, &[-480, -260, -7, 9, 260, 480][..]),
        (36, &[-480, 480][..]),
    ] {
        let unit = CubatureRule::new(&holed_disc(1.0), degree).unwrap();
        for &k in powers {
            let s = 2f64.powi(k);
            let rule = CubatureRule::new(&holed_disc(s), degree)
                .unwrap_or_else(|e| panic!("degree {degree}, 2^{k}: {e}"));
            assert_eq!(
                rule.nodes().len(),
                unit.nodes().len(),
                "degree {degree}, 2^{k}"
            );
            assert_eq!(rule.residual(), unit.residual(), "degree {degree}, 2^{k}");
            for (a, b) in unit.nodes().iter().zip(rule.nodes()) {
                assert_eq!((a.x * s, a.y * s), (b.x, b.y), "degree {degree}, 2^{k}");
            }
            // 4^k in two factors: 2^(2k) alone is not a number for |k| = 480.
            for (a, b) in unit.weights().iter().zip(rule.weights()) {
                assert_eq!(a * s * s, *b, "degree {degree}, 2^{k}");
            }
        }
    }
}

#[test]
fn a_rule_at_any_other_size_is_within_its_target() {
    for s in [1e-140, 3e-100, 7e99, 5e148] {
        let domain = holed_disc(s);
        let rule = CubatureRule::new(&domain, 10).unwrap_or_else(|e| panic!("{s:e}: {e}"));
        assert!(rule.residual() <= DEFAULT_TARGET_RESIDUAL, "{s:e}");
        assert!(
            rule.weights().iter().all(|&w| w > 0.0 && w.is_finite()),
            "{s:e}"
        );
        let classifier = Classifier::new(&domain, ContainOptions::DEFAULT).unwrap();
        let locations = classifier.locate_all_with(Method::InRS2, rule.nodes());
        assert!(locations.iter().all(|l| *l == Location::Inside), "{s:e}");
        // The area and a second moment, in units of the scale (their values at scale 1).
        let unit = filled_area(&holed_disc(1.0), FillRule::EvenOdd).unwrap();
        let area = rule.weights().iter().map(|w| w / s / s).sum::<f64>();
        assert!(
            (area - unit).abs() <= 1e-12 * unit,
            "{s:e}: area {area} against {unit}"
        );
        let x2 = rule.integrate(|q| (q.x / s) * (q.x / s) / s / s).unwrap();
        let at_one = CubatureRule::new(&holed_disc(1.0), 10)
            .unwrap()
            .integrate(|q| q.x * q.x)
            .unwrap();
        assert!(
            (x2 - at_one).abs() <= 1e-12 * at_one,
            "{s:e}: {x2} against {at_one}"
        );
    }
}

#[test]
fn an_area_below_the_smallest_is_refused_in_one_line() {
    let e = CubatureRule::new(&holed_disc(1e-150), 8).unwrap_err();
    assert!(
        matches!(e, CubatureError::AreaTooSmall { area, smallest } if area > 0.0 && area < smallest && smallest == SMALLEST_AREA),
        "{e:?}"
    );
    let line = e.to_string();
    assert!(!line.contains('\n') && line.contains("below"), "{line}");
}
