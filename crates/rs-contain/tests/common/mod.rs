//! Test domains and an independent dense-polygon reference.
#![allow(dead_code, unreachable_pub)]

use std::f64::consts::PI;

use rs_spline::{Domain, NurbsCurve, Point, circle, circular_arc, polyline, segment};

/// A named test domain.
pub struct Case {
    pub name: String,
    pub domain: Domain,
}

fn case(name: &str, curves: Vec<NurbsCurve>) -> Case {
    Case {
        name: name.to_string(),
        domain: Domain::new(curves).unwrap(),
    }
}

/// The paper fixtures.
pub fn fixtures() -> Vec<Case> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/inrs-paper");
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "json"))
        .map(|p| Case {
            name: p.file_stem().unwrap().to_string_lossy().into_owned(),
            domain: Domain::from_json_file(&p).unwrap(),
        })
        .collect();
    v.sort_by(|a, b| a.name.cmp(&b.name));
    v
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
        let (c, r, start) = if i % 2 == 0 {
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
    pub edges: Vec<(Point, Point)>,
}

impl DensePolygon {
    pub fn new(d: &Domain, eps: f64) -> Self {
        let mut edges = Vec::new();
        for l in d.loops() {
            let mut pts: Vec<Point> = Vec::new();
            for ci in l.curves() {
                for b in d.curves()[ci].to_bezier() {
                    let f = |t: f64| b.point_at(t);
                    let mut local = vec![f(0.0)];
                    for j in 0..8 {
                        refine(&f, j as f64 / 8.0, (j + 1) as f64 / 8.0, eps, 0, &mut local);
                    }
                    pts.extend(local);
                }
            }
            pts.push(pts[0]);
            edges.extend(pts.windows(2).map(|w| (w[0], w[1])));
        }
        Self { edges }
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
            .map(|&(a, b)| {
                let ab = b - a;
                let len2 = ab.dot(ab);
                let t = if len2 > 0.0 {
                    ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                p.distance(a + ab * t)
            })
            .fold(f64::INFINITY, f64::min)
    }
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
