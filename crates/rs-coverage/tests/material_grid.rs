//! Several materials on one grid (`MaterialCoverage`): replacement against closed forms,
//! the last material equal to its domain's coverage bit for bit, bands equal to the whole
//! grid, empty regions as zeros.

use std::f64::consts::PI;

use rs_contain::FillRule;
use rs_coverage::{CellGrid, Coverage, CoverageOptions, GridCoverage, MaterialCoverage};
use rs_spline::{Domain, Point, circle};

fn disc(x: f64, y: f64, r: f64) -> Domain {
    Domain::new(vec![circle(Point::new(x, y), r).unwrap()]).unwrap()
}

/// Fractions and centroids equal bit for bit (`NaN` equal to `NaN`).
fn same_bits(a: &Coverage, b: &Coverage) -> bool {
    let bits = |c: &Coverage| {
        let mut v: Vec<u64> = c.fractions.iter().map(|f| f.to_bits()).collect();
        if let Some(m) = &c.centroids {
            v.extend(m.as_flattened().iter().map(|f| f.to_bits()));
        }
        v
    };
    bits(a) == bits(b)
}

fn total(fractions: &[f64], grid: &CellGrid) -> f64 {
    let nx = grid.nx();
    fractions
        .iter()
        .enumerate()
        .map(|(k, f)| f * grid.cell_area(k % nx, k / nx))
        .sum()
}

#[test]
fn overlapping_discs_replace_and_overlap_as_closed_forms_say() {
    let (a, b) = (disc(-0.5, 0.0, 1.0), disc(0.5, 0.0, 1.0));
    let grid = CellGrid::uniform(-2.0, 2.0, 64, -1.5, 1.5, 48).unwrap();
    let domains = [(&a, FillRule::EvenOdd), (&b, FillRule::EvenOdd)];
    let lens = 2.0 * PI / 3.0 - 0.75f64.sqrt();
    let options = CoverageOptions::DEFAULT.with_centroids(true);
    let replaced = MaterialCoverage::new(&domains, grid.clone(), true).unwrap();
    assert_eq!(replaced.len(), 2);
    let c = replaced.all(options).unwrap();
    assert!((total(&c[0].fractions, &grid) - (PI - lens)).abs() < 1e-12);
    assert!((total(&c[1].fractions, &grid) - PI).abs() < 1e-12);
    for (f0, f1) in c[0].fractions.iter().zip(&c[1].fractions) {
        assert!(f0 + f1 <= 1.0 + 1e-12, "{f0} + {f1}");
    }
    // The last material is its domain's coverage, bit for bit.
    let alone = GridCoverage::new(&b, grid.clone())
        .unwrap()
        .all(options)
        .unwrap();
    assert!(same_bits(&c[1], &alone));
    // Without replacement: each domain's own coverage.
    let plain = MaterialCoverage::new(&domains, grid.clone(), false).unwrap();
    let p = plain.all(options).unwrap();
    let a_alone = GridCoverage::new(&a, grid.clone())
        .unwrap()
        .all(options)
        .unwrap();
    assert!(same_bits(&p[0], &a_alone));
    assert!((total(&p[0].fractions, &grid) - PI).abs() < 1e-12);
    // Bands of every height give the whole grid's values.
    for (k, whole) in c.iter().enumerate() {
        for rows in [1, 5, 48] {
            let mut got = Vec::new();
            replaced.bands(k, rows, options, |bands| {
                for (_, band) in bands {
                    got.extend(band.unwrap().fractions);
                }
            });
            assert_eq!(got, whole.fractions, "material {k}, {rows} rows");
        }
    }
}

#[test]
fn a_disc_in_an_annulus_takes_its_cells() {
    // The annulus 1 < r < 2 with a disc of radius 1.5 about the same centre replacing it:
    // the annulus keeps 1.5 < r < 2 (area 1.75 pi), the disc holds 2.25 pi.
    let ring = Domain::new(vec![
        circle(Point::new(0.0, 0.0), 2.0).unwrap(),
        circle(Point::new(0.0, 0.0), 1.0).unwrap(),
    ])
    .unwrap();
    let inner = disc(0.0, 0.0, 1.5);
    let grid = CellGrid::uniform(-2.5, 2.5, 50, -2.5, 2.5, 50).unwrap();
    let m = MaterialCoverage::new(
        &[(&ring, FillRule::EvenOdd), (&inner, FillRule::EvenOdd)],
        grid.clone(),
        true,
    )
    .unwrap();
    let c = m.all(CoverageOptions::DEFAULT).unwrap();
    assert!((total(&c[0].fractions, &grid) - 1.75 * PI).abs() < 1e-12);
    assert!((total(&c[1].fractions, &grid) - 2.25 * PI).abs() < 1e-12);
    // Per cell: the annulus' share is the coverage of the ring 1.5 < r < 2.
    let outer = Domain::new(vec![
        circle(Point::new(0.0, 0.0), 2.0).unwrap(),
        circle(Point::new(0.0, 0.0), 1.5).unwrap(),
    ])
    .unwrap();
    let want = GridCoverage::new(&outer, grid)
        .unwrap()
        .all(CoverageOptions::DEFAULT)
        .unwrap();
    for (got, want) in c[0].fractions.iter().zip(&want.fractions) {
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }
}

#[test]
fn a_material_replaced_everywhere_is_zero_with_nan_centroids() {
    let (a, b) = (disc(0.0, 0.0, 1.0), disc(0.0, 0.0, 1.0));
    let grid = CellGrid::uniform(-1.0, 1.0, 8, -1.0, 1.0, 8).unwrap();
    let m = MaterialCoverage::new(
        &[(&a, FillRule::EvenOdd), (&b, FillRule::EvenOdd)],
        grid,
        true,
    )
    .unwrap();
    let options = CoverageOptions::DEFAULT
        .with_centroids(true)
        .with_boundary(true);
    let c = m.all(options).unwrap();
    assert!(c[0].fractions.iter().all(|&f| f < 1e-14));
    let band = m.rows(0, 2..5, options).unwrap();
    assert_eq!(band.rows, 2..5);
    assert!(band.fractions.iter().all(|&f| f < 1e-14));
    assert!(m.rows(2, 0..1, options).is_err());
    assert!(m.rows(0, 0..9, options).is_err());
    // An empty region refuses what a region refuses: the boundary revolved.
    let revolved = options.with_axisymmetric(Some(rs_spline::Axis::Y));
    let e = m.rows(0, 0..2, revolved).unwrap_err();
    assert!(
        matches!(e, rs_coverage::CoverageError::PlanarOnly { .. }),
        "{e}"
    );
    m.bands(0, 3, revolved, |bands| {
        for (_, band) in bands {
            assert!(band.is_err());
        }
    });
}

#[test]
fn revolved_materials_are_checked_against_the_axis() {
    let (a, b) = (disc(2.0, 0.0, 1.0), disc(-0.5, 0.0, 1.0));
    let grid = CellGrid::uniform(0.0, 4.0, 8, -2.0, 2.0, 8).unwrap();
    let m = MaterialCoverage::new(
        &[(&a, FillRule::EvenOdd), (&b, FillRule::EvenOdd)],
        grid,
        false,
    )
    .unwrap();
    let options = CoverageOptions::DEFAULT.with_axisymmetric(Some(rs_spline::Axis::Y));
    let e = m.all(options).unwrap_err().to_string();
    assert!(e.contains("domain crosses the axis"), "{e}");
}
