//! Test support shared by the workspace's integration tests: named test domains (the paper
//! fixtures and adversarial synthetic shapes), [`DensePolygon`], an independent reference
//! that flattens the boundary adaptively and answers by even-odd parity, and [`XorShift64`],
//! the seeded generator of the tests' random inputs.
//!
//! Test-only code: it panics on bad input instead of returning errors.
#![allow(clippy::unwrap_used)]

mod figure_check;
mod fixture_meta;
mod rng;

pub use figure_check::assert_figure;

pub use fixture_meta::FixtureMeta;
pub use rng::XorShift64;

use rs_spline::prelude::*;
use std::f64::consts::PI;

use rs_spline::{Domain, NurbsCurve, Point, circle, circular_arc, polyline, segment};

/// A named test domain.
pub struct Case {
    /// Name shown in assertion messages.
    pub name: String,
    /// The domain.
    pub domain: Domain,
}

/// The environment variable that makes a missing system file (font, icon theme) a test
/// failure instead of a skip; `.ci/run` sets it, so CI never passes without running the
/// real-file tests.
pub const REQUIRE_SYSTEM_FILES: &str = "INRS_REQUIRE_SYSTEM_FILES";

/// Reads a system file a test needs (installed by `package`). Where it is missing the test is
/// skipped with a message, unless [`REQUIRE_SYSTEM_FILES`] is set to `1`: then it fails.
///
/// # Panics
/// If the file is missing and [`REQUIRE_SYSTEM_FILES`] is `1`.
pub fn system_file(path: &str, package: &str) -> Option<Vec<u8>> {
    match std::fs::read(path) {
        Ok(data) => Some(data),
        Err(e) => {
            missing_system_files(&format!("{path} ({e})"), package);
            None
        }
    }
}

/// Reports that system files a test needs are missing: a skip with a message, or a panic
/// when [`REQUIRE_SYSTEM_FILES`] is `1`.
///
/// # Panics
/// When [`REQUIRE_SYSTEM_FILES`] is `1`.
pub fn missing_system_files(what: &str, package: &str) {
    let required = std::env::var(REQUIRE_SYSTEM_FILES).is_ok_and(|v| v == "1");
    assert!(
        !required,
        "{what} is missing and {REQUIRE_SYSTEM_FILES}=1: install {package}"
    );
    eprintln!("SKIPPED: {what} is missing; install {package}");
}

/// Where the Adwaita icon theme installs its SVG icons (Debian package `adwaita-icon-theme`).
pub const ADWAITA_ICONS: &str = "/usr/share/icons/Adwaita";

/// Every `.svg` file under [`ADWAITA_ICONS`], sorted; empty (after
/// [`missing_system_files`], which fails under [`REQUIRE_SYSTEM_FILES`]) when none is installed.
pub fn adwaita_icons() -> Vec<std::path::PathBuf> {
    fn walk(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "svg") {
                out.push(p);
            }
        }
    }
    let mut files = Vec::new();
    walk(std::path::Path::new(ADWAITA_ICONS), &mut files);
    if files.is_empty() {
        missing_system_files(
            &format!("SVG icons under {ADWAITA_ICONS}"),
            "adwaita-icon-theme",
        );
    }
    files.sort();
    files
}

/// A [`Case`] from curves (panics if they do not form a domain).
pub fn case(name: &str, curves: Vec<NurbsCurve>) -> Case {
    Case {
        name: name.to_string(),
        domain: Domain::new(curves).unwrap(),
    }
}

/// The three domains of the inRS paper's Fig. 2 and Tables 1-2 (files in
/// `fixtures/inrs-paper/`).
pub const PAPER_DOMAINS: [&str; 3] = ["s3_m_shape", "s4_disk_ellipse_segment", "s5_lune"];

/// Every domain of `fixtures/inrs-paper/`, the paper's three first, in the order of the
/// benchmark tables.
pub const INRS_FIXTURES: [&str; 6] = [
    "s3_m_shape",
    "s4_disk_ellipse_segment",
    "s5_lune",
    "circle",
    "l_shape",
    "leaf_cubic",
];

/// The path of `relative` under the workspace's `fixtures/` directory.
pub fn fixture_path(relative: &str) -> std::path::PathBuf {
    std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures")).join(relative)
}

/// The GWN paper's five shapes (`fixtures/axom-contours/`, LLNL Axom's contours).
pub const GWN_SHAPES: [&str; 5] = ["butterfly", "rose", "fish", "bubble", "twirl"];

/// The GWN paper's shape `name` (one of [`GWN_SHAPES`]) as drawn: its open subpaths stay open,
/// for winding numbers (panics if missing).
pub fn gwn_shape(name: &str) -> Domain {
    let path = fixture_path(&format!("axom-contours/{name}.svg"));
    rs_io::svg::domain_from_svg_file_with(&path, rs_io::svg::OpenSubpaths::Keep).unwrap()
}

/// The fixture `fixtures/inrs-paper/{name}.json` with its reference data (panics if missing).
pub fn inrs_fixture(name: &str) -> FixtureMeta {
    FixtureMeta::load(&fixture_path(&format!("inrs-paper/{name}.json"))).unwrap()
}

/// The paper fixtures.
pub fn fixtures() -> Vec<Case> {
    let dir = fixture_path("inrs-paper");
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .map(|p| Case {
            name: p.file_stem().unwrap().to_string_lossy().into_owned(),
            domain: rs_io::json::domain_from_json_file(&p).unwrap(),
        })
        .collect();
    v.sort_by(|a, b| a.name.cmp(&b.name));
    v
}

/// The files of `fixtures/fill-rule/`: nested loops of either orientation, loops that cross
/// each other and loops that cross themselves (see `fixtures/README.md`), by name.
pub const FILL_RULE_FIXTURES: [&str; 7] = [
    "nested_same",
    "nested_opposite",
    "three_nested",
    "overlapping",
    "overlapping_opposite",
    "pentagram",
    "figure_eight",
];

/// The domains of `fixtures/fill-rule/`, in the order of [`FILL_RULE_FIXTURES`], and whether
/// their loops cross (each other or themselves).
pub fn fill_rule_fixtures() -> Vec<(Case, bool)> {
    FILL_RULE_FIXTURES
        .iter()
        .map(|name| {
            let path = fixture_path(&format!("fill-rule/{name}.json"));
            let case = Case {
                name: name.to_string(),
                domain: rs_io::json::domain_from_json_file(&path).unwrap(),
            };
            let crossing = !name.starts_with("nested") && !name.starts_with("three");
            (case, crossing)
        })
        .collect()
}

/// Annulus: outer circle counter-clockwise, hole clockwise.
pub fn annulus() -> Case {
    case(
        "annulus",
        vec![
            circle(Point::new(0.5, -0.25), 2.0).unwrap(),
            circle(Point::new(0.5, -0.25), 0.75).unwrap().reversed(),
        ],
    )
}

/// A staircase polygon with a square hole and a separate triangle: vertical and horizontal
/// edges everywhere.
pub fn staircase() -> Case {
    let p = |x: f64, y: f64| Point::new(x, y);
    let outer = polyline(&[
        p(0.0, 0.0),
        p(4.0, 0.0),
        p(4.0, 1.0),
        p(3.0, 1.0),
        p(3.0, 2.0),
        p(2.0, 2.0),
        p(2.0, 3.0),
        p(1.0, 3.0),
        p(1.0, 4.0),
        p(0.0, 4.0),
        p(0.0, 0.0),
    ])
    .unwrap();
    let hole = polyline(&[
        p(0.5, 0.5),
        p(0.5, 1.5),
        p(1.5, 1.5),
        p(1.5, 0.5),
        p(0.5, 0.5),
    ])
    .unwrap();
    let triangle = vec![
        segment(p(5.0, 0.0), p(6.0, 0.0)).unwrap(),
        segment(p(6.0, 0.0), p(5.0, 2.0)).unwrap(),
        segment(p(5.0, 2.0), p(5.0, 0.0)).unwrap(),
    ];
    let mut curves = vec![outer, hole];
    curves.extend(triangle);
    case("staircase", curves)
}

/// A lens of two circular arcs meeting at x-turning corners (-1, 0) and (1, 0).
pub fn lens() -> Case {
    let c_low = Point::new(0.0, 0.6);
    let c_up = Point::new(0.0, -0.6);
    let r = (1.0f64 + 0.36).sqrt();
    let a_low = (-0.6f64).atan2(-1.0);
    let b_low = (-0.6f64).atan2(1.0);
    let a_up = 0.6f64.atan2(1.0);
    let b_up = 0.6f64.atan2(-1.0);
    case(
        "lens",
        vec![
            circular_arc(c_low, r, a_low, b_low - a_low).unwrap(),
            circular_arc(c_up, r, a_up, b_up - a_up).unwrap(),
        ],
    )
}

/// The Bezier curve on `points` (from the first to the last) with `weights`, closed by the
/// segment from its end back to its start: the strongly weighted test domains.
pub fn closed_by_chord(points: &[(f64, f64)], weights: &[f64]) -> Domain {
    let pts: Vec<Point> = points.iter().map(|&(x, y)| Point::new(x, y)).collect();
    let (start, end) = (pts[0], pts[pts.len() - 1]);
    let arc = NurbsCurve::bezier(pts, Some(weights.to_vec())).unwrap();
    Domain::new(vec![arc, polyline(&[end, start]).unwrap()]).unwrap()
}

/// The quadratic `(0, 0), (1/2, 1), (1, 0)` with weights `1, w, 1`, closed by its chord: a
/// middle weight `w` moves it within about `1 / w` of its parameter ends.
pub fn weighted_arc(w: f64) -> Domain {
    closed_by_chord(&[(0.0, 0.0), (0.5, 1.0), (1.0, 0.0)], &[1.0, w, 1.0])
}

/// A closed periodic rational B-spline of `degree` around a star-shaped control polygon.
pub fn periodic_spline(degree: usize, n: usize) -> Case {
    let mut pts = Vec::new();
    let mut w = Vec::new();
    for i in 0..n {
        let th = 2.0 * PI * i as f64 / n as f64;
        let r = 1.0 + 0.35 * (3.0 * th).sin() + 0.1 * (5.0 * th).cos();
        pts.push(Point::new(1.3 * r * th.cos(), r * th.sin()));
        w.push(1.0 + 0.6 * (2.0 * th).sin());
    }
    for i in 0..degree {
        pts.push(pts[i]);
        w.push(w[i]);
    }
    let m = pts.len() + degree + 1;
    let knots: Vec<f64> = (0..m).map(|i| i as f64 / 10.0).collect();
    let c = NurbsCurve::new(degree, knots, pts, Some(w)).unwrap();
    case(&format!("periodic degree {degree}"), vec![c])
}

/// A spiral band: two-centre spiral of semicircles (centres (0,0) and (h,0)) thickened by
/// `+-w`, closed by radial caps. Vertical rays cross it many times.
pub fn spiral(turns: usize) -> Case {
    let (r0, h, w) = (1.0, 0.5, 0.15);
    let k = 2 * turns;
    let arc = |i: usize, off: f64| {
        let (c, r, start) = if i.is_multiple_of(2) {
            (Point::new(0.0, 0.0), r0 + i as f64 * h + off, 0.0)
        } else {
            (Point::new(h, 0.0), r0 + i as f64 * h + off, PI)
        };
        (c, r, start)
    };
    let mut curves = Vec::new();
    for i in 0..k {
        let (c, r, s) = arc(i, w);
        curves.push(circular_arc(c, r, s, PI).unwrap());
    }
    let last_outer = curves.last().unwrap().end_point();
    let (c, r, s) = arc(k - 1, -w);
    let last_inner = circular_arc(c, r, s, PI).unwrap().end_point();
    curves.push(segment(last_outer, last_inner).unwrap());
    for i in (0..k).rev() {
        let (c, r, s) = arc(i, -w);
        curves.push(circular_arc(c, r, s + PI, -PI).unwrap());
    }
    let first_inner = curves.last().unwrap().end_point();
    let first_outer = curves[0].start_point();
    curves.push(segment(first_inner, first_outer).unwrap());
    case(&format!("spiral {turns} turns"), curves)
}

/// Every synthetic domain.
pub fn synthetic() -> Vec<Case> {
    vec![
        annulus(),
        staircase(),
        lens(),
        periodic_spline(3, 11),
        periodic_spline(5, 13),
        spiral(4),
    ]
}

/// Fixtures and synthetic domains.
pub fn all_cases() -> Vec<Case> {
    let mut v = fixtures();
    v.extend(synthetic());
    v
}

/// The boundary flattened to polygons, one per loop, within about `eps` of the curves
/// (adaptive midpoint test, at least 8 segments per Bezier piece).
pub struct DensePolygon {
    /// The polygon edges of every loop.
    pub edges: Vec<(Point, Point)>,
}

impl DensePolygon {
    /// Flattens every loop of `d` within about `eps`.
    pub fn new(d: &Domain, eps: f64) -> Self {
        let mut edges = Vec::new();
        for l in d.loops() {
            let mut pts: Vec<Point> = Vec::new();
            for ci in l.curves() {
                pts.extend(flatten_curve(&d.curves()[ci], eps));
            }
            pts.push(pts[0]);
            edges.extend(pts.windows(2).map(|w| (w[0], w[1])));
        }
        Self { edges }
    }

    /// Every curve of `d` flattened on its own within about `eps`, nothing closed: the
    /// polylines of a curve collection (open chains, gaps), for winding numbers.
    pub fn open_curves(d: &Domain, eps: f64) -> Self {
        let mut edges = Vec::new();
        for c in d.curves() {
            let pts = flatten_curve(c, eps);
            edges.extend(pts.windows(2).map(|w| (w[0], w[1])));
        }
        Self { edges }
    }

    /// The winding number at `p`: the angles the edges subtend, added one `atan2` at a time,
    /// over `2 pi` (the curves' own value wherever `p` is farther from them than the
    /// flattening error).
    pub fn winding_number(&self, p: Point) -> f64 {
        self.edges
            .iter()
            .map(|&(a, b)| {
                let (u, v) = (a - p, b - p);
                u.cross(v).atan2(u.dot(v))
            })
            .sum::<f64>()
            / (2.0 * PI)
    }

    /// Even-odd containment.
    pub fn contains(&self, p: Point) -> bool {
        let mut odd = false;
        for &(a, b) in &self.edges {
            if (a.x <= p.x) != (b.x <= p.x) {
                let y = a.y + (p.x - a.x) * (b.y - a.y) / (b.x - a.x);
                if y < p.y {
                    odd = !odd;
                }
            }
        }
        odd
    }

    /// Distance to the polygon.
    pub fn distance(&self, p: Point) -> f64 {
        self.edges
            .iter()
            .map(|&e| segment_distance(p, e))
            .fold(f64::INFINITY, f64::min)
    }
}

/// Answers "is `p` within `radius` of the polygon?" fast, by bucketing the edges (their
/// boxes grown by `radius`) in a uniform grid.
pub struct NearBoundary {
    edges: Vec<(Point, Point)>,
    radius: f64,
    min: Point,
    cell: f64,
    n: usize,
    buckets: Vec<Vec<usize>>,
}

impl NearBoundary {
    /// Indexes the edges of `poly` for queries at distance `radius`.
    pub fn new(poly: &DensePolygon, radius: f64) -> Self {
        let edges = poly.edges.clone();
        let (mut lo, mut hi) = (
            Point::new(f64::INFINITY, f64::INFINITY),
            Point::new(f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for &(a, b) in &edges {
            for q in [a, b] {
                lo = Point::new(lo.x.min(q.x), lo.y.min(q.y));
                hi = Point::new(hi.x.max(q.x), hi.y.max(q.y));
            }
        }
        let n = ((edges.len() as f64).sqrt().ceil() as usize).clamp(1, 512);
        let min = lo - Point::new(radius, radius);
        let span = (hi.x - lo.x).max(hi.y - lo.y) + 2.0 * radius;
        let cell = (span / n as f64).max(f64::MIN_POSITIVE);
        let mut buckets = vec![Vec::new(); n * n];
        let index = |v: f64, o: f64| (((v - o) / cell).floor().max(0.0) as usize).min(n - 1);
        for (k, &(a, b)) in edges.iter().enumerate() {
            let (x0, x1) = (
                index(a.x.min(b.x) - radius, min.x),
                index(a.x.max(b.x) + radius, min.x),
            );
            let (y0, y1) = (
                index(a.y.min(b.y) - radius, min.y),
                index(a.y.max(b.y) + radius, min.y),
            );
            for j in y0..=y1 {
                for i in x0..=x1 {
                    buckets[j * n + i].push(k);
                }
            }
        }
        Self {
            edges,
            radius,
            min,
            cell,
            n,
            buckets,
        }
    }

    /// True if `p` is within the radius of an edge.
    pub fn is_near(&self, p: Point) -> bool {
        let (fx, fy) = (
            (p.x - self.min.x) / self.cell,
            (p.y - self.min.y) / self.cell,
        );
        if !(fx >= 0.0 && fy >= 0.0 && fx < self.n as f64 && fy < self.n as f64) {
            return false;
        }
        let bucket = &self.buckets[fy as usize * self.n + fx as usize];
        bucket
            .iter()
            .any(|&k| segment_distance(p, self.edges[k]) <= self.radius)
    }
}

/// Distance from `p` to the segment `a b`.
pub fn segment_distance(p: Point, (a, b): (Point, Point)) -> f64 {
    let ab = b - a;
    let len2 = ab.dot(ab);
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

/// The polyline of a curve within about `eps`: its first point, then at least 8 chords per
/// Bezier piece, halved until the mid and quarter points are within `eps`.
fn flatten_curve(c: &NurbsCurve, eps: f64) -> Vec<Point> {
    let mut pts: Vec<Point> = Vec::new();
    for b in c.to_bezier() {
        let f = |t: f64| b.point_at(t);
        let mut local = vec![f(0.0)];
        for j in 0..8 {
            refine(&f, j as f64 / 8.0, (j + 1) as f64 / 8.0, eps, 0, &mut local);
        }
        let skip = usize::from(!pts.is_empty());
        pts.extend(local.into_iter().skip(skip));
    }
    pts
}

fn refine(f: &impl Fn(f64) -> Point, t0: f64, t1: f64, eps: f64, depth: u32, out: &mut Vec<Point>) {
    let (a, b) = (f(t0), f(t1));
    let tm = 0.5 * (t0 + t1);
    let m = f(tm);
    let q1 = f(0.5 * (t0 + tm));
    let chord = b - a;
    let dev = |p: Point| {
        let l = chord.length();
        if l == 0.0 {
            p.distance(a)
        } else {
            (p - a).cross(chord).abs() / l
        }
    };
    if depth >= 30 || (dev(m) <= eps && dev(q1) <= eps) {
        out.push(b);
    } else {
        refine(f, t0, tm, eps, depth + 1, out);
        refine(f, tm, t1, eps, depth + 1, out);
    }
}
