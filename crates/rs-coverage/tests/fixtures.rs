//! Real domains: the paper's fixtures, the Axom contours and font glyphs. The covered areas
//! add up to the domain's even-odd area, the centroids to its first moments (computed here
//! by Green's theorem on the whole loops), bands of rows give the whole grid's values, and
//! bad input gets the right error.

mod common;

use common::domain_moments;
use rs_contain::{FillRule, filled_area, loop_nesting};
use rs_coverage::{
    CellGrid, CoverageError, CoverageOptions, GridCoverage, MAX_CELLS, cell_coverage,
};
use rs_spline::Domain;

/// The closed domains of `fixtures/inrs-paper` and `fixtures/axom-contours`.
fn closed_fixtures() -> Vec<(String, Domain)> {
    let mut v: Vec<(String, Domain)> = rs_testkit::INRS_FIXTURES
        .iter()
        .map(|name| {
            let path = rs_testkit::fixture_path(&format!("inrs-paper/{name}.json"));
            (
                name.to_string(),
                rs_io::load_domain(path.to_str().unwrap()).unwrap(),
            )
        })
        .collect();
    for name in ["butterfly", "rose", "fish"] {
        let path = rs_testkit::fixture_path(&format!("axom-contours/{name}.svg"));
        v.push((
            name.to_string(),
            rs_io::load_domain(path.to_str().unwrap()).unwrap(),
        ));
    }
    v
}

/// `DejaVu` glyphs with holes and several loops, when the font is installed.
fn glyphs() -> Vec<(String, Domain)> {
    let font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    if rs_testkit::system_file(font, "fonts-dejavu-core").is_none() {
        return Vec::new();
    }
    ["B", "g", "8", "U+0040", "U+00E4"]
        .iter()
        .map(|g| {
            (
                format!("glyph {g}"),
                rs_io::load_domain(&format!("{font}#{g}")).unwrap(),
            )
        })
        .collect()
}

/// Grids over the domain's box grown by 3% on each side: square and oblong, coarse and fine.
fn covering_grids(d: &Domain) -> Vec<CellGrid> {
    let b = d.bounding_box();
    let (mx, my) = (0.03 * b.width(), 0.03 * b.height());
    let (x0, x1, y0, y1) = (b.min.x - mx, b.max.x + mx, b.min.y - my, b.max.y + my);
    [(1, 1), (3, 2), (64, 64), (257, 193), (1000, 700)]
        .iter()
        .map(|&(nx, ny)| CellGrid::uniform(x0, x1, nx, y0, y1, ny).unwrap())
        .collect()
}

/// A compensated (Neumaier) sum: the grids have up to `7 * 10^5` cells, whose naive sum
/// loses about `1e-11` relative.
#[derive(Default)]
struct Sum {
    total: f64,
    compensation: f64,
}

impl Sum {
    fn add(&mut self, v: f64) {
        let t = self.total + v;
        self.compensation += if self.total.abs() >= v.abs() {
            (self.total - t) + v
        } else {
            (v - t) + self.total
        };
        self.total = t;
    }

    fn value(&self) -> f64 {
        self.total + self.compensation
    }
}

/// Sum of covered areas and of centroid times covered area over the grid.
fn totals(grid: &CellGrid, fractions: &[f64], centroids: &[[f64; 2]]) -> (f64, f64, f64) {
    let nx = grid.nx();
    let (mut area, mut mx, mut my) = (Sum::default(), Sum::default(), Sum::default());
    for (k, f) in fractions.iter().enumerate() {
        let a = f * grid.cell_area(k % nx, k / nx);
        if a > 0.0 {
            area.add(a);
            mx.add(a * centroids[k][0]);
            my.add(a * centroids[k][1]);
        }
    }
    (area.value(), mx.value(), my.value())
}

#[test]
fn covered_areas_and_moments_add_up_on_every_fixture() {
    let mut cases = closed_fixtures();
    cases.extend(glyphs());
    let mut differ = Vec::new();
    for ((name, d), rule) in cases
        .iter()
        .flat_map(|c| [(c, FillRule::EvenOdd), (c, FillRule::NonZero)])
    {
        let (area, mx, my) = domain_moments(d, rule);
        if rule == FillRule::NonZero && area != filled_area(d, FillRule::EvenOdd).unwrap() {
            differ.push(name.clone());
        }
        let b = d.bounding_box();
        // Moments about a point of the box are of size area * diagonal at most.
        let moment_scale =
            area.abs() * (b.max.x.abs().max(b.min.x.abs()) + b.max.y.abs().max(b.min.y.abs()));
        for grid in covering_grids(d) {
            let c = GridCoverage::with_fill_rule(d, grid.clone(), rule)
                .unwrap()
                .all(CoverageOptions::DEFAULT.with_centroids(true))
                .unwrap();
            // Even-odd is `cell_coverage`'s rule; nonzero gives the same cells wherever every
            // loop bounds the filled set with the same sign under both rules.
            let alike = loop_nesting(d)
                .unwrap()
                .iter()
                .all(|n| n.boundary_sign(FillRule::EvenOdd) == n.boundary_sign(FillRule::NonZero));
            if rule == FillRule::EvenOdd || alike {
                let plain = cell_coverage(d, &grid, CoverageOptions::DEFAULT.with_centroids(true));
                assert_eq!(c.fractions, plain.unwrap().fractions, "{name} ({rule:?})");
            }
            let (a, x, y) = totals(&grid, &c.fractions, c.centroids.as_ref().unwrap());
            let tag = format!("{name} ({rule:?}) on {}x{}", grid.nx(), grid.ny());
            assert!(
                (a - area).abs() <= 1e-12 * area,
                "{tag}: area {a} vs {area}"
            );
            assert!(
                (x - mx).abs() <= 1e-12 * moment_scale,
                "{tag}: x moment {x} vs {mx}"
            );
            assert!(
                (y - my).abs() <= 1e-12 * moment_scale,
                "{tag}: y moment {y} vs {my}"
            );
        }
    }
    eprintln!("nonzero area differs from even-odd on: {differ:?}");
}

/// The whole grid on rayon's threads, one band of all rows, and many small bands give the
/// same values bit for bit.
#[test]
fn bands_give_the_whole_grids_values() {
    let path = rs_testkit::fixture_path("axom-contours/butterfly.svg");
    let d = rs_io::load_domain(path.to_str().unwrap()).unwrap();
    let grid = covering_grids(&d).swap_remove(3);
    let ny = grid.ny();
    let cover = GridCoverage::new(&d, grid).unwrap();
    let options = CoverageOptions::DEFAULT
        .with_centroids(true)
        .with_apertures(true);
    let whole = cover.all(options).unwrap();
    let one = cover.rows(0..ny, options).unwrap();
    assert_eq!(whole.fractions, one.fractions);
    assert_eq!(whole.x_apertures, one.x_apertures);
    assert_eq!(whole.y_apertures, one.y_apertures);
    // Centroids: NaN where empty, so compare bits.
    let bits = |c: &Option<Vec<[f64; 2]>>| -> Vec<u64> {
        c.as_ref()
            .unwrap()
            .iter()
            .flatten()
            .map(|v| v.to_bits())
            .collect()
    };
    assert_eq!(bits(&whole.centroids), bits(&one.centroids));
    let mut fractions = Vec::new();
    let mut j0 = 0;
    for size in [1, 7, 30, 2, 100].iter().cycle() {
        if j0 >= ny {
            break;
        }
        let j1 = (j0 + size).min(ny);
        fractions.extend(cover.rows(j0..j1, options).unwrap().fractions);
        j0 = j1;
    }
    assert_eq!(fractions, whole.fractions);
}

#[test]
fn open_boundaries_and_bad_grids_are_refused() {
    let grid = CellGrid::uniform(0.0, 1.0, 4, 0.0, 1.0, 4).unwrap();
    for name in ["bubble", "twirl"] {
        let path = rs_testkit::fixture_path(&format!("axom-contours/{name}.svg"));
        let spec = path.to_str().unwrap();
        let options = rs_io::svg::OpenSubpaths::Keep;
        let d = rs_io::svg::domain_from_svg_file_with(spec, options).unwrap();
        let e = cell_coverage(&d, &grid, CoverageOptions::DEFAULT).unwrap_err();
        assert!(matches!(e, CoverageError::Domain(_)), "{name}: {e}");
        assert!(e.to_string().starts_with("open boundary: "), "{e}");
    }
    let d = rs_io::load_domain(
        rs_testkit::fixture_path("inrs-paper/circle.json")
            .to_str()
            .unwrap(),
    )
    .unwrap();
    let cover = GridCoverage::new(&d, grid).unwrap();
    let reversed = std::ops::Range { start: 3, end: 2 };
    for rows in [0..0, reversed, 2..5] {
        let e = cover.rows(rows, CoverageOptions::DEFAULT).unwrap_err();
        assert!(matches!(e, CoverageError::BadRows { .. }), "{e}");
    }
    // Two coincident loops: no nesting to decide the fill by.
    let c = || rs_spline::circle(rs_spline::Point::new(0.0, 0.0), 1.0).unwrap();
    let twice = Domain::new(vec![c(), c()]).unwrap();
    let grid = CellGrid::uniform(-1.0, 1.0, 4, -1.0, 1.0, 4).unwrap();
    let e = cell_coverage(&twice, &grid, CoverageOptions::DEFAULT).unwrap_err();
    assert!(matches!(e, CoverageError::Nesting { .. }), "{e}");
    // Too many cells for one call, fine in bands.
    let big = CellGrid::uniform(-1.0, 1.0, 1 << 15, -1.0, 1.0, 1 << 14).unwrap();
    let cover = GridCoverage::new(&d, big).unwrap();
    let e = cover.all(CoverageOptions::DEFAULT).unwrap_err();
    assert!(
        matches!(
            e,
            CoverageError::TooManyCells {
                limit: MAX_CELLS,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("268435456 cells"), "{e}");
    let band = cover.rows(8191..8193, CoverageOptions::DEFAULT).unwrap();
    assert_eq!(band.fractions.len(), 2 << 15);
    // Bad edges through the grid constructors.
    let errs = [
        CellGrid::new(vec![0.0], vec![0.0, 1.0]).unwrap_err(),
        CellGrid::new(vec![0.0, 1.0], vec![]).unwrap_err(),
        CellGrid::new(vec![1.0, 0.0], vec![0.0, 1.0]).unwrap_err(),
        CellGrid::new(vec![0.0, f64::NAN], vec![0.0, 1.0]).unwrap_err(),
        CellGrid::new(vec![0.0, 1.0], vec![f64::NEG_INFINITY, 1.0]).unwrap_err(),
        CellGrid::uniform(0.0, f64::INFINITY, 3, 0.0, 1.0, 3).unwrap_err(),
        CellGrid::uniform(1.0, 0.0, 3, 0.0, 1.0, 3).unwrap_err(),
        CellGrid::uniform(0.0, 1.0, 3, 0.0, 1.0, 0).unwrap_err(),
    ];
    for e in errs {
        let msg = e.to_string();
        assert!(!msg.contains('\n') && !msg.is_empty(), "{msg}");
    }
}

/// A square ring `[-2, 2]^2` minus `[-1, 1]^2`, on grids whose lines run along its edges and
/// across them: cell `(i, j)` is covered `o_i o_j - h_i h_j`, with `o` and `h` the shares of
/// column and row inside the outer and the inner square.
#[test]
fn a_square_ring_is_exact_cell_by_cell() {
    let sq = |a: f64, b: f64| {
        let p = |x, y| rs_spline::Point::new(x, y);
        rs_spline::polyline(&[p(a, a), p(b, a), p(b, b), p(a, b), p(a, a)]).unwrap()
    };
    let d = Domain::new(vec![sq(-2.0, 2.0), sq(-1.0, 1.0)]).unwrap();
    let share = |e: &[f64], k: usize, half: f64| {
        ((e[k + 1].min(half) - e[k].max(-half)) / (e[k + 1] - e[k])).max(0.0)
    };
    for (lo, hi, n) in [
        (-2.0, 2.0, 4),
        (-2.5, 2.5, 5),
        (-3.0, 3.0, 12),
        (-2.0, 2.25, 17),
    ] {
        let grid = CellGrid::uniform(lo, hi, n, lo, hi, n).unwrap();
        let c = cell_coverage(&d, &grid, CoverageOptions::DEFAULT).unwrap();
        let e = grid.x_edges();
        for j in 0..n {
            for i in 0..n {
                let expected =
                    share(e, i, 2.0) * share(e, j, 2.0) - share(e, i, 1.0) * share(e, j, 1.0);
                let got = c.fractions[j * n + i];
                assert!(
                    (got - expected).abs() <= 1e-15,
                    "{n}: ({i}, {j}) {got} vs {expected}"
                );
            }
        }
    }
}

/// `fixtures/fill-rule`: nested loops of either orientation are covered by the rule's
/// filled area (the cells add up to `rs_contain::filled_area`); loops that cross each other
/// or themselves are refused, naming the crossing, under either rule.
#[test]
fn fill_rule_fixtures_are_covered_by_their_rule_or_refused() {
    for (case, crossing) in rs_testkit::fill_rule_fixtures() {
        let d = &case.domain;
        let grid = covering_grids(d).swap_remove(2);
        for rule in [FillRule::EvenOdd, FillRule::NonZero] {
            match GridCoverage::with_fill_rule(d, grid.clone(), rule) {
                Err(e) => {
                    assert!(crossing, "{} ({rule}): {e}", case.name);
                    assert!(
                        matches!(
                            e,
                            CoverageError::Nesting(rs_contain::NestingError::Crossing(_))
                        ),
                        "{e}"
                    );
                }
                Ok(cover) => {
                    assert!(!crossing, "{} ({rule})", case.name);
                    let c = cover
                        .all(CoverageOptions::DEFAULT.with_centroids(true))
                        .unwrap();
                    let (a, _, _) = totals(&grid, &c.fractions, c.centroids.as_ref().unwrap());
                    let want = filled_area(d, rule).unwrap();
                    assert!(
                        (a - want).abs() < 1e-12 * want,
                        "{} ({rule}): {a} vs {want}",
                        case.name
                    );
                }
            }
        }
    }
}
