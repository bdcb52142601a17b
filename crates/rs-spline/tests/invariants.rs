//! Knot insertion, refinement, splitting, clamping, reversal and Bezier extraction leave the
//! curve unchanged (sampled, 1e-12 relative to the curve's size).

use proptest::prelude::*;
use rs_spline::prelude::*;
use rs_spline::{NurbsCurve, Point, RationalBezier};

const REL: f64 = 1e-12;

fn size(c: &NurbsCurve) -> f64 {
    c.control_bounding_box().diagonal().max(1.0)
}

fn samples(c: &NurbsCurve, n: usize) -> Vec<f64> {
    let (a, b) = c.param_range();
    (0..=n).map(|i| a + (b - a) * i as f64 / n as f64).collect()
}

/// Evaluates the Bezier piece whose parameter range holds `u`.
fn eval_pieces(pieces: &[RationalBezier], u: f64) -> Point {
    let piece = pieces
        .iter()
        .find(|b| {
            let (u0, u1) = b.knot_span();
            u >= u0 && u <= u1
        })
        .expect("pieces cover the domain");
    let (u0, u1) = piece.knot_span();
    piece.point_at((u - u0) / (u1 - u0))
}

fn assert_same(c: &NurbsCurve, other: impl Fn(f64) -> Point, what: &str) {
    let tol = REL * size(c);
    for u in samples(c, 97) {
        let (p, q) = (c.point_at(u), other(u));
        assert!(p.distance(q) <= tol, "{what}: at u = {u}: {p:?} vs {q:?}");
    }
}

fn check_invariants(c: &NurbsCurve) {
    let (a, b) = c.param_range();
    let p = c.degree();
    // Knot insertion, once and repeatedly, at a new value and at an existing knot.
    for &frac in &[0.137, 0.5, 0.861] {
        let u = a + frac * (b - a);
        let room = p.saturating_sub(c.knots().multiplicity(u));
        for times in 1..=room {
            let d = c.insert_knot(u, times).unwrap();
            assert_eq!(d.control_points().len(), c.control_points().len() + times);
            assert_same(c, |u| d.point_at(u), "insert_knot");
        }
    }
    for &k in &c.knots().interior_breaks() {
        let room = p.saturating_sub(c.knots().multiplicity(k));
        if room > 0 {
            let d = c.insert_knot(k, room).unwrap();
            assert_same(c, |u| d.point_at(u), "insert existing knot");
        }
    }
    // Refinement with many knots.
    let new: Vec<f64> = (1..10).map(|i| a + (b - a) * i as f64 / 10.0).collect();
    if let Ok(r) = c.refine(&new) {
        assert_same(c, |u| r.point_at(u), "refine");
    }
    // Clamping.
    let cl = c.clamped();
    assert_eq!(cl.param_range(), c.param_range());
    assert_same(c, |u| cl.point_at(u), "clamped");
    assert_eq!(cl.control_points()[0], cl.start_point());
    // Reversal.
    let rev = c.reversed();
    assert_same(c, |u| rev.point_at(a + b - u), "reversed");
    // Splitting.
    let s = a + 0.4 * (b - a);
    let (l, r) = c.split_at(s).unwrap();
    assert_eq!(l.param_range(), (a, s));
    assert_eq!(r.param_range(), (s, b));
    assert_same(
        c,
        |u| if u <= s { l.point_at(u) } else { r.point_at(u) },
        "split",
    );
    // Bezier extraction.
    let pieces = c.to_bezier();
    assert_eq!(pieces.first().unwrap().knot_span().0, a);
    assert_eq!(pieces.last().unwrap().knot_span().1, b);
    assert!(
        pieces
            .windows(2)
            .all(|w| w[0].knot_span().1 == w[1].knot_span().0)
    );
    // Consecutive pieces meet, except at a break (interior knot of multiplicity p + 1), where
    // the gap is the one `breaks` reports.
    let breaks = c.breaks();
    for w in pieces.windows(2) {
        let u = w[0].knot_span().1;
        let gap = w[0].end_point().distance(w[1].start_point());
        match breaks.iter().find(|b| b.0 == u) {
            Some(&(_, reported)) => assert!((gap - reported).abs() <= REL * size(c)),
            None => assert!(gap <= REL * size(c), "pieces part at u = {u}"),
        }
    }
    assert_same(c, |u| eval_pieces(&pieces, u), "to_bezier");
}

fn fixture_curves() -> Vec<(String, NurbsCurve)> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/inrs-paper");
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let d = rs_io::json::domain_from_json_file(&path).unwrap();
        for (i, c) in d.curves().iter().enumerate() {
            out.push((format!("{} curve {i}", path.display()), c.clone()));
        }
    }
    assert!(out.len() >= 6);
    out
}

#[test]
fn fixture_curves_are_invariant() {
    for (name, c) in fixture_curves() {
        eprintln!("{name}");
        check_invariants(&c);
    }
}

#[test]
fn unclamped_curve_is_invariant() {
    let c = NurbsCurve::new(
        2,
        vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0],
        vec![
            Point::new(0.0, 0.0),
            Point::new(1.0, 3.0),
            Point::new(3.0, 2.0),
            Point::new(4.0, -1.0),
            Point::new(6.0, 0.0),
        ],
        Some(vec![1.0, 2.0, 0.5, 1.5, 1.0]),
    )
    .unwrap();
    assert_eq!(c.param_range(), (2.0, 5.0));
    check_invariants(&c);
    let cl = c.clamped();
    assert_eq!(
        cl.knots().knots(),
        &[2.0, 2.0, 2.0, 3.0, 4.0, 5.0, 5.0, 5.0]
    );
}

/// A random valid NURBS: degree 1..=5, clamped or not, repeated interior knots, weights in
/// [0.1, 10].
fn arb_curve() -> impl Strategy<Value = NurbsCurve> {
    (1usize..=5, 0usize..6, any::<bool>()).prop_flat_map(|(p, extra, clamped)| {
        let n = p + 1 + extra;
        (
            Just(p),
            Just(clamped),
            proptest::collection::vec((-5.0f64..5.0, -5.0f64..5.0), n),
            proptest::collection::vec(0.1f64..10.0, n),
            proptest::collection::vec(0u8..8, n + p + 1),
        )
            .prop_filter_map("valid knot vector", |(p, clamped, pts, w, steps)| {
                // Knot values from a grid of eighths so that repeats occur.
                let mut knots = Vec::with_capacity(steps.len());
                let mut acc = 0.0;
                for (i, s) in steps.iter().enumerate() {
                    if i > 0 {
                        acc += f64::from(*s % 3) / 8.0;
                    }
                    knots.push(acc);
                }
                if clamped {
                    let m = knots.len();
                    let (first, last) = (knots[p], knots[m - p - 1]);
                    knots[..=p].iter_mut().for_each(|k| *k = first);
                    knots[m - p - 1..].iter_mut().for_each(|k| *k = last);
                }
                let pts = pts.into_iter().map(|(x, y)| Point::new(x, y)).collect();
                NurbsCurve::new(p, knots, pts, Some(w)).ok()
            })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]
    #[test]
    fn random_curves_are_invariant(c in arb_curve()) {
        check_invariants(&c);
    }
}
