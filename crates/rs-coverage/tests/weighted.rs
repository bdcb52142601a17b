//! Cell fractions over strongly weighted rational pieces against 20-digit areas.

use rs_coverage::{CellGrid, CoverageOptions, GridCoverage};
use rs_spline::Domain;
use rs_testkit::{closed_by_chord, weighted_arc};

/// The covered area of `d` on `cells`^2 cells over `[-1/2, 3/2]^2`, every fraction checked
/// within `[0, 1]`.
fn covered(d: &Domain, cells: usize) -> f64 {
    let grid = CellGrid::uniform(-0.5, 1.5, cells, -0.5, 1.5, cells).unwrap();
    let c = GridCoverage::new(d, grid)
        .unwrap()
        .all(CoverageOptions::DEFAULT)
        .unwrap();
    assert!(c.fractions.iter().all(|f| (0.0..=1.0).contains(f)));
    let h = 2.0 / cells as f64;
    c.fractions.iter().sum::<f64>() * h * h
}

/// Cut at its apex, each half of the arc moves within `1 / w` of one parameter end: the cells'
/// integrals once missed that motion (the area off by `2e-5` at `w = 1e8`, `6e-2` at `1e11`,
/// on four cells). The halves are now reparametrised to equal end weights, and the covered
/// areas add up to the arc's area (by mpmath to 20 digits, here rounded to a double; `1/2` to within `1e-17` from
/// `w = 1e9` on) within `1e-12` on four cells and on 64^2.
#[test]
fn strongly_weighted_halves_cover_their_area() {
    for (w, area) in [
        (1e3, 0.499_996_699_543_694_5),
        (1e6, 0.499_999_999_993_245_7),
        (1e7, 0.499_999_999_999_920_9),
        (1e8, 0.499_999_999_999_999_1),
        (1e11, 0.5),
        (1e12, 0.5),
    ] {
        let d = weighted_arc(w);
        for cells in [2, 64] {
            let got = covered(&d, cells);
            assert!(
                (got - area).abs() < 1e-12,
                "w {w:e}, {cells}^2 cells: {got} vs {area}"
            );
        }
    }
}

/// Cubics whose inner weights dwarf their end weights (`1, w, w, 1` and `1, w, 1, 1`): their
/// monotone pieces are halved until each part's weights are within `2^10` of its ends, and the
/// covered areas come within `1e-10` of mpmath's (Green's theorem, 40 digits, the parameter
/// cut at `1e-16 .. 1e-1` from each end); before, `8e-3` and `5e-2` off at `w = 1e11`.
#[test]
fn cubics_with_heavy_inner_weights_cover_their_area() {
    let points = [(0.0, 0.0), (0.3, 1.0), (0.8, 1.2), (1.0, 0.0)];
    for (weights, area) in [
        ([1.0, 1e8, 1e8, 1.0], 0.819_999_936_930_543_8),
        ([1.0, 1e11, 1e11, 1.0], 0.819_999_999_912_062_6),
        ([1.0, 1e8, 1.0, 1.0], 0.500_043_526_385_004_2),
        ([1.0, 1e11, 1.0, 1.0], 0.500_001_376_572_130_3),
    ] {
        let d = closed_by_chord(&points, &weights);
        for cells in [2, 64] {
            let got = covered(&d, cells);
            assert!(
                (got - area).abs() < 1e-10,
                "{weights:?}, {cells}^2 cells: {got} vs {area}"
            );
        }
    }
}
