//! The documented workflow `inrs sample` -> add a `z` column -> `inrs fit --data`, through the
//! library calls the CLI makes (`well_spaced_points`, whose points `sample` writes boundary
//! first in shortest round-trip form, so the CSV reads back bit for bit; then
//! `interpolate_scattered`), on every fixture domain the fit accepts and on closed
//! single-curve rational B-splines of degrees 2 to 7 with random weights, in every space.
//!
//! `fit --data` promises interpolation ("a `C^1` spline through every value"), and each space
//! reproduces the polynomials of its local fit's degree (minimal energy: linear ones): with
//! `z` such a polynomial the spline must equal `z` at every data point, boundary points
//! included, and between the data.
//!
//! Fixtures left out: `breaks/circle_gap.json` (not closed: every fit refuses it),
//! `bad/*` (invalid on purpose), `convex/*` (space curves for `convex-domain`, not domains),
//! `io/plate.dxf` (the DXF reader is an optional feature of `rs-io`, off in this crate; the
//! CLI's tests fit it), and `axom-contours/{bubble,twirl}.svg` (open paths whose closing
//! chords cross them, which a curved triangulation cannot have: the fit refuses them, asserted
//! in [`self_crossing_fixtures_are_refused`]).

use rs_contain::{Classifier, ContainOptions, Locate, Location};
use rs_mesh::well_spaced_points;
use rs_spline::{Domain, NurbsCurve, Point};
use rs_testkit::XorShift64;
use rs_trispline::{C1Space, TriSplineError, interpolate_scattered};

const SPACES: [C1Space; 4] = [
    C1Space::SuperSpline,
    C1Space::CloughTocher,
    C1Space::PowellSabin,
    C1Space::MinimalEnergy,
];

const NY: [usize; 4] = [9, 17, 33, 65];

/// The fixtures' `ny` before this index are fitted in one test, the rest in another, so that
/// two test threads share the work evenly: the coarse ones (about 43 s of CPU in the test
/// profile, mostly the fixed cost per fit on `flower500`) on one, the fine ones (26 s) with the
/// closed B-splines (13 s) on the other.
const NY_SPLIT: usize = 3;

/// Every fixture domain the fit accepts (see the module comment for those left out).
fn fixture_domains() -> Vec<(String, Domain)> {
    let mut v: Vec<(String, Domain)> = rs_testkit::fixtures()
        .into_iter()
        .map(|c| (c.name, c.domain))
        .collect();
    for rel in [
        "breaks/circle_breaks.json",
        "breaks/heptagon_breaks.json",
        "breaks/s4_breaks.json",
        "synthetic/flower500.json",
        "io/gear.svg",
        "axom-contours/butterfly.svg",
        "axom-contours/fish.svg",
        "axom-contours/rose.svg",
    ] {
        let path = rs_testkit::fixture_path(rel);
        let d = rs_io::load_domain(&path.display().to_string())
            .unwrap_or_else(|e| panic!("{rel}: {e}"));
        v.push((rel.to_string(), d));
    }
    assert_eq!(v.len(), 14, "a fixture went missing");
    v
}

/// The family: one clamped rational B-spline of `degree` with 14 control points on
/// `r = 1 + 0.25 sin 3θ` scaled 1.3 in `x`, the first and last at `(1.3, 0)` (so it closes
/// there, on the positive x-axis), uniform interior knots, weights in `[0.5, 2]`.
fn closed_bspline(degree: usize, rng: &mut XorShift64) -> Domain {
    let n = 14;
    let points: Vec<Point> = (0..n)
        .map(|k| {
            let th = std::f64::consts::TAU * (k % (n - 1)) as f64 / (n - 1) as f64;
            let r = 1.0 + 0.25 * (3.0 * th).sin();
            Point::new(1.3 * r * th.cos(), r * th.sin())
        })
        .collect();
    let weights: Vec<f64> = (0..n).map(|_| rng.uniform(0.5, 2.0)).collect();
    let spans = n - degree;
    let mut knots = vec![0.0; degree + 1];
    knots.extend((1..spans).map(|i| i as f64 / spans as f64));
    knots.extend(vec![1.0; degree + 1]);
    let c = NurbsCurve::new(degree, knots, points, Some(weights)).unwrap();
    Domain::new(vec![c]).unwrap()
}

fn bspline_domains() -> Vec<(String, Domain)> {
    // A fixed seed, so the weights are the same on every run.
    let mut rng = XorShift64::new(0x1f2e_3d4c_5b6a_7988);
    (2..=7)
        .map(|p| {
            (
                format!("closed B-spline degree {p}"),
                closed_bspline(p, &mut rng),
            )
        })
        .collect()
}

/// A polynomial the space reproduces: quadratic for the two-stage spaces (their local fits
/// have degree 2 or 3), linear for minimal energy; in coordinates relative to the domain's
/// box (centre and diagonal), so its values are of order 1 whatever the domain's size.
fn data_function(d: &Domain, space: C1Space) -> impl Fn(Point) -> f64 {
    let bb = d.bounding_box();
    let centre = (bb.min + bb.max) * 0.5;
    let size = bb.diagonal();
    move |q: Point| {
        let p = (q - centre) * (1.0 / size);
        let linear = 0.7 - 1.3 * p.x + 2.1 * p.y;
        if space == C1Space::MinimalEnergy {
            linear
        } else {
            linear + 0.9 * p.x * p.x - 1.1 * p.x * p.y + 0.6 * p.y * p.y
        }
    }
}

/// What `sample --ny ny` gives (the data points, boundary first) and the probes between the
/// data: the points midway between consecutive interior points that lie inside. The same for
/// every space, so sampled once per domain and `ny`.
struct Sampled {
    points: Vec<Point>,
    between: Vec<Point>,
}

impl Sampled {
    fn new(name: &str, d: &Domain, inside: &Classifier, ny: usize) -> Self {
        let sampled = well_spaced_points(d, ny).unwrap_or_else(|e| panic!("{name} ny {ny}: {e}"));
        let between = sampled
            .interior
            .windows(2)
            .map(|w| (w[0] + w[1]) * 0.5)
            .filter(|&p| inside.locate(p) == Location::Inside)
            .collect();
        Self {
            points: sampled.all_points(),
            between,
        }
    }
}

/// A `z` column of the space's polynomial on the sampled points, `fit --data --space space`;
/// then the spline must reproduce `z` at every data point and at every probe between them. A
/// fit that fails is returned as its message (the data were accepted: the triangulation
/// failed); anything else wrong panics.
fn fit_reproduces(
    name: &str,
    d: &Domain,
    sampled: &Sampled,
    ny: usize,
    space: C1Space,
) -> Result<(), String> {
    let f = data_function(d, space);
    let values: Vec<f64> = sampled.points.iter().map(|&p| f(p)).collect();
    let fit = match interpolate_scattered(d, &sampled.points, &values, space) {
        Ok(fit) => fit,
        Err(e @ TriSplineError::Mesh(_)) => return Err(e.to_string()),
        Err(e) => panic!("{name} ny {ny} {space:?}: {e}"),
    };
    let eval = fit.spline.evaluator().unwrap();
    let scale = values.iter().fold(1.0f64, |m, v| m.max(v.abs()));
    let probes: Vec<Point> = sampled
        .points
        .iter()
        .chain(&sampled.between)
        .copied()
        .collect();
    let truth = values
        .iter()
        .copied()
        .chain(sampled.between.iter().map(|&p| f(p)));
    let got = eval.evaluate_all(&probes);
    for ((p, z), v) in probes.iter().zip(truth).zip(got) {
        let v = v
            .unwrap_or_else(|| panic!("{name} ny {ny} {space:?}: {p:?} is in no triangle"))
            .value;
        assert!(
            (v - z).abs() <= 1e-9 * scale,
            "{name} ny {ny} {space:?}: {v} at {p:?}, want {z}"
        );
    }
    Ok(())
}

/// `sample --ny ny`, then [`fit_reproduces`] in `space`.
fn sample_then_fit(name: &str, d: &Domain, ny: usize, space: C1Space) -> Result<(), String> {
    let inside = Classifier::new(d, ContainOptions::DEFAULT).unwrap();
    fit_reproduces(name, d, &Sampled::new(name, d, &inside, ny), ny, space)
}

/// Every space at every `ny` in `nys` on each domain, sampled once per domain and `ny`:
/// every fit must succeed and reproduce its data.
fn every_space(domains: &[(String, Domain)], nys: &[usize]) {
    for (name, d) in domains {
        let inside = Classifier::new(d, ContainOptions::DEFAULT).unwrap();
        for &ny in nys {
            let sampled = Sampled::new(name, d, &inside, ny);
            for space in SPACES {
                if let Err(e) = fit_reproduces(name, d, &sampled, ny, space) {
                    panic!("{name} ny {ny} {space:?}: {e}");
                }
            }
        }
    }
}

/// Every space at every `ny` for the closed B-splines (the family: the seam and
/// the fast parametrisation near it).
#[test]
fn sample_then_fit_closed_bsplines_every_space_every_ny() {
    every_space(&bspline_domains(), &NY);
}

/// The fixtures whose boundary crosses itself: the data are accepted, the triangulation
/// refuses the domain, naming the crossing.
#[test]
fn self_crossing_fixtures_are_refused() {
    for name in ["bubble", "twirl"] {
        let path = rs_testkit::fixture_path(&format!("axom-contours/{name}.svg"));
        let d = rs_io::load_domain(&path.display().to_string()).unwrap();
        let e = sample_then_fit(name, &d, 9, C1Space::CloughTocher).unwrap_err();
        assert!(e.contains("crosses itself"), "{name}: {e}");
    }
}

/// Every fixture in every space at every `ny`, with [`NY_SPLIT`]: the coarse ones here.
#[test]
fn sample_then_fit_fixtures_every_space_coarse() {
    every_space(&fixture_domains(), &NY[..NY_SPLIT]);
}

/// Every fixture in every space at every `ny`: the fine ones here, in a test of their own so
/// that it runs beside the others.
#[test]
fn sample_then_fit_fixtures_every_space_fine() {
    every_space(&fixture_domains(), &NY[NY_SPLIT..]);
}
