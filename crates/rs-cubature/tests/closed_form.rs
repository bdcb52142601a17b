//! `monomial_moments` against closed forms: discs (centred and off-centre), an annulus (a
//! hole), a rectangle and a triangle, every monomial `x^a y^b`, `a + b <= 20`.
//!
//! Scale of the comparison: `area x max over the bounding box of |x^a y^b|` (never zero, and
//! the size of the terms a moment sums), relative error at most `1e-12`.

use rs_cubature::monomial_moments;
mod common;

use common::{binomial, factorial};
use rs_spline::prelude::*;
use rs_spline::{Domain, Point, circle, polyline};

const DEGREE: usize = 20;
const TOLERANCE: f64 = 1e-12;

/// `(2k - 1)!!` (1 for k = 0).
fn odd_double_factorial(k: usize) -> f64 {
    (1..=k).fold(1.0, |f, i| f * (2 * i - 1) as f64)
}

/// `integral over the unit disc of u^p v^q`: zero unless both are even; else
/// `2 pi (p - 1)!! (q - 1)!! / ((p + q)!! (p + q + 2))`.
fn unit_disc(p: usize, q: usize) -> f64 {
    if p % 2 == 1 || q % 2 == 1 {
        return 0.0;
    }
    let (i, j) = (p / 2, q / 2);
    let even = 2f64.powi((i + j) as i32) * factorial(i + j); // (2(i + j))!!
    2.0 * std::f64::consts::PI * odd_double_factorial(i) * odd_double_factorial(j)
        / even
        / (p + q + 2) as f64
}

/// `integral over the disc (c, r) of x^a y^b`, by the binomial expansion about `c`.
fn disc(c: Point, r: f64, a: usize, b: usize) -> f64 {
    let mut sum = 0.0;
    for p in 0..=a {
        for q in 0..=b {
            sum += binomial(a, p)
                * binomial(b, q)
                * c.x.powi((a - p) as i32)
                * c.y.powi((b - q) as i32)
                * unit_disc(p, q)
                * r.powi((p + q + 2) as i32);
        }
    }
    sum
}

/// Checks every moment of `domain` against `exact(a, b)` at the stated scale.
fn check(name: &str, domain: &Domain, area: f64, exact: impl Fn(usize, usize) -> f64) {
    let got = monomial_moments(domain, DEGREE, rs_contain::FillRule::EvenOdd).unwrap();
    let bbox = domain.bounding_box();
    let rx = bbox.min.x.abs().max(bbox.max.x.abs());
    let ry = bbox.min.y.abs().max(bbox.max.y.abs());
    let mut worst = 0.0f64;
    let mut k = 0;
    for total in 0..=DEGREE {
        for b in 0..=total {
            let a = total - b;
            let scale = area * rx.powi(a as i32) * ry.powi(b as i32);
            let want = exact(a, b);
            let err = (got[k] - want).abs() / scale;
            worst = worst.max(err);
            assert!(
                err <= TOLERANCE,
                "{name}: x^{a} y^{b}: {} vs {want} (relative {err:e})",
                got[k]
            );
            k += 1;
        }
    }
    assert_eq!(k, got.len());
    eprintln!("{name}: worst relative error {worst:e}");
}

#[test]
fn unit_disc_moments() {
    let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
    check("unit disc", &d, std::f64::consts::PI, |a, b| {
        disc(Point::new(0.0, 0.0), 1.0, a, b)
    });
}

#[test]
fn off_centre_disc_moments() {
    let (c, r) = (Point::new(1.5, -0.75), 0.6);
    let d = Domain::new(vec![circle(c, r).unwrap()]).unwrap();
    check(
        "off-centre disc",
        &d,
        std::f64::consts::PI * r * r,
        |a, b| disc(c, r, a, b),
    );
}

#[test]
fn annulus_moments_either_orientation_of_the_hole() {
    let c = Point::new(0.25, 0.5);
    let area = std::f64::consts::PI * (1.0 - 0.4 * 0.4);
    let exact = |a, b| disc(c, 1.0, a, b) - disc(c, 0.4, a, b);
    for hole in [circle(c, 0.4).unwrap(), circle(c, 0.4).unwrap().reversed()] {
        let d = Domain::new(vec![circle(c, 1.0).unwrap(), hole]).unwrap();
        check("annulus", &d, area, exact);
    }
}

#[test]
fn rectangle_moments() {
    let p = |x: f64, y: f64| Point::new(x, y);
    let (x0, x1, y0, y1) = (-0.5, 1.25, 0.5, 1.5);
    // Clockwise on purpose: the fill does not depend on orientation.
    let ring = [p(x0, y0), p(x0, y1), p(x1, y1), p(x1, y0), p(x0, y0)];
    let d = Domain::new(vec![polyline(&ring).unwrap()]).unwrap();
    let power = |lo: f64, hi: f64, k: usize| {
        (hi.powi(k as i32 + 1) - lo.powi(k as i32 + 1)) / (k + 1) as f64
    };
    check("rectangle", &d, (x1 - x0) * (y1 - y0), |a, b| {
        power(x0, x1, a) * power(y0, y1, b)
    });
}

#[test]
fn triangle_moments() {
    // The triangle {x' / 2 + y' / 3 <= 1, x', y' >= 0} moved by (1, -0.5). On the reference
    // triangle integral x'^p y'^q = 2^(p+1) 3^(q+1) p! q! / (p + q + 2)!.
    let p = |x: f64, y: f64| Point::new(x, y);
    let ring = [p(1.0, -0.5), p(3.0, -0.5), p(1.0, 2.5), p(1.0, -0.5)];
    let d = Domain::new(vec![polyline(&ring).unwrap()]).unwrap();
    let reference = |p: usize, q: usize| {
        2f64.powi(p as i32 + 1) * 3f64.powi(q as i32 + 1) * factorial(p) * factorial(q)
            / factorial(p + q + 2)
    };
    check("triangle", &d, 3.0, |a, b| {
        let mut sum = 0.0;
        for p in 0..=a {
            for q in 0..=b {
                sum += binomial(a, p)
                    * binomial(b, q)
                    * (-0.5f64).powi((b - q) as i32)
                    * reference(p, q);
            }
        }
        sum
    });
}

#[test]
fn the_closed_forms_themselves_are_right() {
    // Independent sanity checks of the reference formulas: area, second moment of the disc.
    assert!((unit_disc(0, 0) - std::f64::consts::PI).abs() < 1e-15);
    assert!((unit_disc(2, 0) - std::f64::consts::PI / 4.0).abs() < 1e-15);
    assert!((unit_disc(2, 4) - std::f64::consts::PI / 64.0).abs() < 1e-15);
    let c = circle(Point::new(0.0, 0.0), 1.0).unwrap();
    assert!((c.end_point() - c.start_point()).length() < 1e-15);
}
