//! The unit disc and an annulus against closed forms, every cell: areas of circle segments
//! per cell (computed in double-double where the crossing points need it, so the reference
//! is far more accurate than the `1e-12` it checks), face apertures from the exact crossings
//! of grid lines with circles, and centroids against the disc's first moments.

use std::f64::consts::PI;

use rs_contain::FillRule;
use rs_coverage::{CellGrid, Coverage, CoverageOptions, GridCoverage, cell_coverage};
use rs_spline::{Domain, Point, circle, prelude::*};

/// `a * b` as an unevaluated sum `hi + lo`, exactly.
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// `a + b` as `hi + lo`, exactly.
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `sqrt(r^2 - t^2)` in double-double, for exact `r`, `t` with `|t| <= r`: the half chord of
/// the circle of radius `r` about the origin on the line at distance `t`.
fn half_chord(r: f64, t: f64) -> (f64, f64) {
    let (r2, r2e) = two_prod(r, r);
    let (t2, t2e) = two_prod(t, t);
    let (d, de) = two_sum(r2, -t2);
    let lo = de + r2e - t2e;
    let (d, lo) = two_sum(d, lo);
    if d <= 0.0 {
        return (0.0, 0.0);
    }
    let s = d.sqrt();
    // One Newton step on s^2 = d + lo, with s^2 exactly.
    let (s2, s2e) = two_prod(s, s);
    let corr = ((d - s2) - s2e + lo) / (2.0 * s);
    two_sum(s, corr)
}

/// `x - c` for a double-double `x`, rounded once.
fn minus(x: (f64, f64), c: f64) -> f64 {
    (x.0 - c) + x.1
}

fn neg(x: (f64, f64)) -> (f64, f64) {
    (-x.0, -x.1)
}

/// `delta - sin(delta)`, without cancellation for small angles.
fn delta_minus_sin(d: f64) -> f64 {
    if d < 0.1 {
        let d2 = d * d;
        d * d2 / 6.0
            * (1.0 - d2 / 20.0 * (1.0 - d2 / 42.0 * (1.0 - d2 / 72.0 * (1.0 - d2 / 110.0))))
    } else {
        d - d.sin()
    }
}

/// The area of the disc of radius `r` about the origin inside `[a, b] x [c, d]`: the cell
/// boundary walked counter-clockwise and clipped to the disc gives a convex polygon (in the
/// cell's coordinates, its crossing points in double-double) joined by circle arcs, each
/// adding the segment `r^2 / 2 (delta - sin delta)`.
fn disc_in_cell(r: f64, [a, b, c, d]: [f64; 4]) -> f64 {
    let (w, h) = (b - a, d - c);
    // Each edge: (fixed coordinate is x?, its value, local fixed value, from, to) with the
    // edge running from `from` to `to` along the other coordinate.
    let edges = [
        (false, c, 0.0, a, b),
        (true, b, w, c, d),
        (false, d, h, b, a),
        (true, a, 0.0, d, c),
    ];
    let mut pieces: Vec<([f64; 2], [f64; 2])> = Vec::new();
    for (vertical, value, local, from, to) in edges {
        if value.abs() >= r {
            continue; // the line misses the open disc (or touches it at one point)
        }
        let m = half_chord(r, value);
        let origin = if vertical { c } else { a };
        let (lo, hi) = (from.min(to), from.max(to));
        // The chord [-m, m] clipped to [lo, hi], in coordinates local to the cell.
        let s0 = if -m.0 > lo {
            minus(neg(m), origin)
        } else {
            lo - origin
        };
        let s1 = if m.0 < hi {
            minus(m, origin)
        } else {
            hi - origin
        };
        if s1 <= s0 {
            continue;
        }
        let (s_from, s_to) = if from < to { (s0, s1) } else { (s1, s0) };
        let point = |s: f64| if vertical { [local, s] } else { [s, local] };
        pieces.push((point(s_from), point(s_to)));
    }
    if pieces.is_empty() {
        // The disc inside the cell, or apart from it.
        let inside = a <= -r && b >= r && c <= -r && d >= r;
        return if inside { PI * r * r } else { 0.0 };
    }
    let mut twice_area = 0.0;
    let mut segments = 0.0;
    let n = pieces.len();
    for k in 0..n {
        let (p, q) = pieces[k];
        let next = pieces[(k + 1) % n].0;
        twice_area += p[0] * q[1] - p[1] * q[0];
        twice_area += q[0] * next[1] - q[1] * next[0];
        if q != next {
            let chord = (next[0] - q[0]).hypot(next[1] - q[1]);
            let mut delta = 2.0 * (chord / (2.0 * r)).min(1.0).asin();
            // A cell less than r sqrt(2) across holds no arc longer than half the circle.
            if w.max(h) >= r * 2f64.sqrt() {
                let (qg, ng) = ([q[0] + a, q[1] + c], [next[0] + a, next[1] + c]);
                if qg[0] * ng[1] - qg[1] * ng[0] < 0.0 {
                    delta = 2.0 * PI - delta;
                }
            }
            segments += 0.5 * r * r * delta_minus_sin(delta);
        }
    }
    0.5 * twice_area + segments
}

/// The covered length of the segment `[lo, hi]` of the line at distance `t` from the
/// origin (on the other axis), for the disc of radius `r`, with the line moved an
/// infinitesimal step towards `+` (the apertures' convention).
fn chord_in(r: f64, t: f64, lo: f64, hi: f64) -> f64 {
    if t >= r || t < -r {
        return 0.0;
    }
    let m = half_chord(r, t);
    let s0 = if -m.0 > lo { -m.0 - m.1 } else { lo };
    let s1 = if m.0 < hi { m.0 + m.1 } else { hi };
    (s1 - s0).max(0.0)
}

fn unit_disc() -> Domain {
    Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap()
}

fn annulus() -> Domain {
    Domain::new(vec![
        circle(Point::new(0.0, 0.0), 1.0).unwrap(),
        circle(Point::new(0.0, 0.0), 0.5).unwrap().reversed(),
    ])
    .unwrap()
}

/// The circles of radius 1 and 0.5 about the origin, the outer counter-clockwise unless
/// `outer_cw`, the inner of the same orientation unless `opposite`.
fn two_circles(outer_cw: bool, opposite: bool) -> Domain {
    let c = |r: f64, cw: bool| {
        let c = circle(Point::new(0.0, 0.0), r).unwrap();
        if cw { c.reversed() } else { c }
    };
    Domain::new(vec![c(1.0, outer_cw), c(0.5, outer_cw != opposite)]).unwrap()
}

/// Every cell of `c` (rows `c.rows` of `grid`) against `truth`, within `1e-12` of the cell's
/// area; returns the largest error relative to the cell's area.
fn check_cells(grid: &CellGrid, c: &Coverage, truth: impl Fn([f64; 4]) -> f64, what: &str) -> f64 {
    let (xs, ys) = (grid.x_edges(), grid.y_edges());
    let mut worst: f64 = 0.0;
    for j in c.rows.clone() {
        for i in 0..grid.nx() {
            let area = grid.cell_area(i, j);
            let expected = truth([xs[i], xs[i + 1], ys[j], ys[j + 1]]) / area;
            let got = c.fraction(i, j).unwrap();
            let err = (got - expected).abs();
            assert!(
                err <= 1e-12,
                "{what}: cell ({i}, {j}) of {}x{}: {got} vs {expected} ({err:e})",
                grid.nx(),
                grid.ny()
            );
            worst = worst.max(err);
        }
    }
    worst
}

fn grids(n: usize) -> Vec<CellGrid> {
    vec![
        // Lines through the centre and the extreme points (0, +-1), (+-1, 0).
        CellGrid::uniform(-1.0, 1.0, n, -1.0, 1.0, n).unwrap(),
        // Generic positions, a grid wider than the disc, non-square cells.
        CellGrid::uniform(-1.13, 1.31, n + 1, -1.27, 1.09, n - 1).unwrap(),
    ]
}

#[test]
fn unit_disc_every_cell_from_4_to_256() {
    let d = unit_disc();
    for n in [4, 16, 64, 256] {
        for grid in grids(n) {
            let c = cell_coverage(&d, &grid, CoverageOptions::DEFAULT).unwrap();
            let worst = check_cells(&grid, &c, |cell| disc_in_cell(1.0, cell), "disc");
            eprintln!("disc {n}: worst {worst:e}");
        }
    }
}

#[test]
fn annulus_every_cell_from_4_to_256() {
    let d = annulus();
    let truth = |cell| disc_in_cell(1.0, cell) - disc_in_cell(0.5, cell);
    for n in [4, 16, 64, 256] {
        for grid in grids(n) {
            let c = cell_coverage(&d, &grid, CoverageOptions::DEFAULT).unwrap();
            let worst = check_cells(&grid, &c, truth, "annulus");
            eprintln!("annulus {n}: worst {worst:e}");
        }
    }
}

/// Nonzero: two nested circles of one orientation (either) fill the unit disc, of opposite
/// orientations the annulus; even-odd gives the annulus for all four. Every cell against the
/// closed forms.
#[test]
fn nonzero_two_circles_every_cell() {
    let disc = |cell| disc_in_cell(1.0, cell);
    let ring = |cell| disc_in_cell(1.0, cell) - disc_in_cell(0.5, cell);
    for n in [4, 16, 64, 256] {
        for grid in grids(n) {
            for outer_cw in [false, true] {
                for opposite in [false, true] {
                    let d = two_circles(outer_cw, opposite);
                    let tag = format!("cw {outer_cw} opposite {opposite} {n}");
                    let cover = |rule| {
                        let cover = GridCoverage::with_fill_rule(&d, grid.clone(), rule).unwrap();
                        cover.all(CoverageOptions::DEFAULT).unwrap()
                    };
                    let c = cover(FillRule::NonZero);
                    if opposite {
                        check_cells(&grid, &c, ring, &format!("nonzero {tag}"));
                    } else {
                        check_cells(&grid, &c, disc, &format!("nonzero {tag}"));
                    }
                    let c = cover(FillRule::EvenOdd);
                    check_cells(&grid, &c, ring, &format!("even-odd {tag}"));
                }
            }
        }
    }
}

/// Nonzero on two counter-clockwise circles keeps only the outer one's pieces: the values,
/// apertures and centroids are the unit disc's bit for bit, and the apertures (both
/// orientations) are the exact chords of the unit circle.
#[test]
fn nonzero_same_orientation_apertures_are_the_outer_discs() {
    let options = CoverageOptions::DEFAULT
        .with_apertures(true)
        .with_centroids(true);
    for grid in grids(64) {
        let (xs, ys) = (grid.x_edges(), grid.y_edges());
        let (nx, ny) = (grid.nx(), grid.ny());
        let disc = cell_coverage(&unit_disc(), &grid, options).unwrap();
        for outer_cw in [false, true] {
            let d = two_circles(outer_cw, false);
            let c = GridCoverage::with_fill_rule(&d, grid.clone(), FillRule::NonZero)
                .unwrap()
                .all(options)
                .unwrap();
            if !outer_cw {
                assert_eq!(c.fractions, disc.fractions);
                assert_eq!(c.x_apertures, disc.x_apertures);
                assert_eq!(c.y_apertures, disc.y_apertures);
            }
            let xa = c.x_apertures.unwrap();
            let ya = c.y_apertures.unwrap();
            for j in 0..ny {
                for (i, &x) in xs.iter().enumerate() {
                    let expected = chord_in(1.0, x, ys[j], ys[j + 1]) / (ys[j + 1] - ys[j]);
                    let got = xa[j * (nx + 1) + i];
                    assert!((got - expected).abs() <= 1e-12, "x face {i},{j}: {got}");
                }
            }
            for (j, &y) in ys.iter().enumerate() {
                for i in 0..nx {
                    let expected = chord_in(1.0, y, xs[i], xs[i + 1]) / (xs[i + 1] - xs[i]);
                    let got = ya[j * nx + i];
                    assert!((got - expected).abs() <= 1e-12, "y face {i},{j}: {got}");
                }
            }
        }
    }
}

/// 2048^2, every cell, on the grid through the centre and the extreme points and on a generic
/// one.
#[test]
fn disc_and_annulus_2048() {
    let annulus_truth = |cell| disc_in_cell(1.0, cell) - disc_in_cell(0.5, cell);
    for grid in grids(2048) {
        let c = cell_coverage(&unit_disc(), &grid, CoverageOptions::DEFAULT).unwrap();
        let worst = check_cells(&grid, &c, |cell| disc_in_cell(1.0, cell), "disc");
        eprintln!("disc 2048: worst {worst:e}");
        let c = cell_coverage(&annulus(), &grid, CoverageOptions::DEFAULT).unwrap();
        let worst = check_cells(&grid, &c, annulus_truth, "annulus");
        eprintln!("annulus 2048: worst {worst:e}");
    }
}

/// Apertures: the face `x = a` (just right of it), `y in [c, d]` is covered on
/// `|y| <= sqrt(1 - a^2)`, likewise the horizontal faces; within `1e-12` of the face length.
#[test]
fn disc_apertures_are_the_exact_chords() {
    let d = unit_disc();
    for n in [4, 64, 256] {
        for grid in grids(n) {
            let (xs, ys) = (grid.x_edges(), grid.y_edges());
            let (nx, ny) = (grid.nx(), grid.ny());
            let c =
                cell_coverage(&d, &grid, CoverageOptions::DEFAULT.with_apertures(true)).unwrap();
            let xa = c.x_apertures.unwrap();
            let ya = c.y_apertures.unwrap();
            assert_eq!((xa.len(), ya.len()), (ny * (nx + 1), (ny + 1) * nx));
            for j in 0..ny {
                for (i, &x) in xs.iter().enumerate() {
                    let h = ys[j + 1] - ys[j];
                    let expected = chord_in(1.0, x, ys[j], ys[j + 1]) / h;
                    let got = xa[j * (nx + 1) + i];
                    assert!(
                        (got - expected).abs() <= 1e-12,
                        "x face {i},{j}: {got} vs {expected}"
                    );
                }
            }
            for (j, &y) in ys.iter().enumerate() {
                for i in 0..nx {
                    let w = xs[i + 1] - xs[i];
                    let expected = chord_in(1.0, y, xs[i], xs[i + 1]) / w;
                    let got = ya[j * nx + i];
                    assert!(
                        (got - expected).abs() <= 1e-12,
                        "y face {i},{j}: {got} vs {expected}"
                    );
                }
            }
        }
    }
}

/// The apertures of a band are the whole grid's: the vertical lines' status at the band's
/// bottom comes from the bottom line's crossings.
#[test]
fn band_apertures_equal_the_whole_grids() {
    let d = annulus();
    let grid = CellGrid::uniform(-1.0, 1.0, 64, -1.0, 1.0, 64).unwrap();
    let cover = GridCoverage::new(&d, grid).unwrap();
    let options = CoverageOptions::DEFAULT
        .with_apertures(true)
        .with_centroids(true);
    let whole = cover.all(options).unwrap();
    let (xa, ya) = (whole.x_apertures.unwrap(), whole.y_apertures.unwrap());
    for rows in [0..1, 16..32, 31..33, 48..64] {
        let band = cover.rows(rows.clone(), options).unwrap();
        let (j0, j1) = (rows.start, rows.end);
        assert_eq!(band.x_apertures.unwrap(), xa[j0 * 65..j1 * 65], "{rows:?}");
        assert_eq!(
            band.y_apertures.unwrap(),
            ya[j0 * 64..(j1 + 1) * 64],
            "{rows:?}"
        );
        assert_eq!(
            band.fractions,
            whole.fractions[j0 * 64..j1 * 64],
            "{rows:?}"
        );
    }
}

/// Centroids: the sum over cells of centroid times covered area is the first moment of a
/// disc about its centre off the origin (area times centre), and every centroid lies in its
/// cell; empty cells have no centroid.
#[test]
fn centroids_give_the_first_moments() {
    let (cx, cy, r) = (0.3, -0.2, 0.7);
    let d = Domain::new(vec![circle(Point::new(cx, cy), r).unwrap()]).unwrap();
    for n in [4, 16, 128] {
        let grid = CellGrid::uniform(-0.5, 1.1, n, -1.0, 0.6, n + 3).unwrap();
        let c = cell_coverage(&d, &grid, CoverageOptions::DEFAULT.with_centroids(true)).unwrap();
        let cent = c.centroids.as_ref().unwrap();
        let (xs, ys) = (grid.x_edges(), grid.y_edges());
        let (mut area, mut mx, mut my) = (0.0, 0.0, 0.0);
        for j in 0..grid.ny() {
            for i in 0..grid.nx() {
                let k = j * grid.nx() + i;
                let a = c.fractions[k] * grid.cell_area(i, j);
                let [x, y] = cent[k];
                if c.fractions[k] == 0.0 {
                    assert!(x.is_nan() && y.is_nan());
                    continue;
                }
                assert!(x >= xs[i] && x <= xs[i + 1] && y >= ys[j] && y <= ys[j + 1]);
                area += a;
                mx += a * x;
                my += a * y;
            }
        }
        let exact = PI * r * r;
        assert!((area - exact).abs() <= 1e-13 * exact, "{n}: {area}");
        assert!((mx - exact * cx).abs() <= 1e-13 * exact, "{n}: {mx}");
        assert!((my - exact * cy).abs() <= 1e-13 * exact, "{n}: {my}");
    }
}

/// The reference itself: its cells add up to the disc's area, and quarter cells are pi / 4.
#[test]
fn reference_areas_are_consistent() {
    assert!((disc_in_cell(1.0, [0.0, 1.0, 0.0, 1.0]) - PI / 4.0).abs() < 1e-15);
    assert!((disc_in_cell(1.0, [-2.0, 2.0, -2.0, 2.0]) - PI).abs() < 1e-15);
    assert!((disc_in_cell(1.0, [-2.0, 2.0, -0.999, 2.0]) - PI).abs() < 1e-4);
    let n = 100;
    let e: Vec<f64> = (0..=n).map(|i| -1.0 + 2.0 * i as f64 / n as f64).collect();
    // Neumaier's compensated sum: 10^4 terms summed naively lose about 1e-13.
    let (mut total, mut comp) = (0.0f64, 0.0f64);
    for j in 0..n {
        for i in 0..n {
            let v = disc_in_cell(1.0, [e[i], e[i + 1], e[j], e[j + 1]]);
            let t = total + v;
            comp += if total.abs() >= v.abs() {
                (total - t) + v
            } else {
                (v - t) + total
            };
            total = t;
        }
    }
    assert!((total + comp - PI).abs() < 1e-14, "{total}");
    // A thin cap: the segment of height 1e-3 below y = -1 + 1e-3.
    let t: f64 = 1e-3;
    let half = 0.5 * (1.0 - (1.0 - t) * (1.0 - t)).sqrt() * 2.0;
    let cap = (1.0 - t).acos() - (1.0 - t) * (2.0 * t - t * t).sqrt();
    let got = disc_in_cell(1.0, [-1.0, 1.0, -1.0, -1.0 + t]);
    assert!((got - cap).abs() < 1e-15 * half.max(1.0), "{got} vs {cap}");
}
