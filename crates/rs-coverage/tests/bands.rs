//! The row bands of a grid (`GridCoverage::bands`): in row order, of any height, with the
//! values of the whole grid bit for bit; and the one rule that cuts grids (`band_rows`).

use std::ops::Range;

use rs_coverage::{
    BAND_BYTES, CellGrid, Coverage, CoverageError, CoverageOptions, GridCoverage, MAX_CELLS,
    band_rows,
};
use rs_spline::{Domain, Point, circle, polyline};

/// Every array of a coverage as bits (`NaN` centroids compare equal).
fn bits(c: &Coverage) -> [Vec<u64>; 4] {
    let b = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    [
        b(&c.fractions),
        b(c.centroids.as_deref().unwrap_or_default().as_flattened()),
        b(c.x_apertures.as_deref().unwrap_or_default()),
        b(c.y_apertures.as_deref().unwrap_or_default()),
    ]
}

/// The bands of `band_rows` rows joined into one coverage of the whole grid (the horizontal
/// faces a band shares with the next one taken once), checking that they come in row order.
fn joined(cover: &GridCoverage, rows: usize, options: CoverageOptions) -> Coverage {
    let (nx, ny) = (cover.grid().nx(), cover.grid().ny());
    let height = rows.clamp(1, ny);
    cover.bands(rows, options, |bands| {
        assert_eq!(bands.len(), ny.div_ceil(height), "{rows} rows a band");
        let mut whole = cover.rows(0..1, options).unwrap();
        let mut next = 0;
        let mut first = true;
        for (range, band) in bands {
            let band = band.unwrap();
            assert_eq!(range, next..(next + height).min(ny), "band order");
            assert_eq!(band.rows, range);
            next = range.end;
            if first {
                whole = band;
                first = false;
                continue;
            }
            whole.rows.end = range.end;
            whole.fractions.extend(band.fractions);
            if let (Some(c), Some(b)) = (&mut whole.centroids, band.centroids) {
                c.extend(b);
            }
            if let (Some(x), Some(b)) = (&mut whole.x_apertures, band.x_apertures) {
                x.extend(b);
            }
            if let (Some(y), Some(b)) = (&mut whole.y_apertures, band.y_apertures) {
                // The band's bottom line is the last band's top line.
                y.truncate(y.len() - nx);
                y.extend(b);
            }
        }
        assert_eq!(next, ny, "every row");
        whole
    })
}

/// A square ring whose edges run along grid lines and whose corners are grid vertices, a
/// disc and the butterfly on oblong grids. (Where a curved boundary passes through a grid
/// vertex within rounding, as the unit circle through `(0.6, 0.8)` on a grid of step 0.05,
/// the cells and faces at that vertex may differ in the last bits with the bands' cut, as
/// `GridCoverage::rows` documents: the separate solves of the crossings with the two lines do
/// not decide the same order there.)
fn cases() -> Vec<(&'static str, Domain, CellGrid)> {
    let p = |x, y| Point::new(x, y);
    let sq = |a: f64, b: f64| polyline(&[p(a, a), p(b, a), p(b, b), p(a, b), p(a, a)]).unwrap();
    let ring = Domain::new(vec![sq(-2.0, 2.0), sq(-1.0, 1.0)]).unwrap();
    let disc = Domain::new(vec![circle(p(0.0, 0.0), 1.0).unwrap()]).unwrap();
    let path = rs_testkit::fixture_path("axom-contours/butterfly.svg");
    let butterfly = rs_io::load_domain(path.to_str().unwrap()).unwrap();
    let b = butterfly.bounding_box();
    vec![
        (
            "ring",
            ring,
            CellGrid::uniform(-3.0, 3.0, 12, -3.0, 3.0, 36).unwrap(),
        ),
        (
            "disc",
            disc,
            CellGrid::uniform(-1.03, 0.97, 40, -0.99, 1.02, 41).unwrap(),
        ),
        (
            "butterfly",
            butterfly,
            CellGrid::uniform(b.min.x, b.max.x, 157, b.min.y, b.max.y, 93).unwrap(),
        ),
    ]
}

/// The iterator yields the bands in row order, and bands of any height (one row, odd
/// heights, the rule's, the whole grid, more than the grid, 0 taken as 1) give every array of
/// `all()` bit for bit, on pools of one and of three threads.
#[test]
fn bands_come_in_row_order_and_any_height_gives_the_same_bits() {
    let options = CoverageOptions::DEFAULT
        .with_centroids(true)
        .with_apertures(true);
    for (name, d, grid) in cases() {
        let ny = grid.ny();
        let cover = GridCoverage::new(&d, grid).unwrap();
        let whole = bits(&cover.all(options).unwrap());
        let fractions_only = cover.all(CoverageOptions::DEFAULT).unwrap();
        for threads in [1, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                assert_eq!(bits(&cover.all(options).unwrap()), whole, "{name} all()");
                let rule = cover.band_rows(options);
                for rows in [0, 1, 2, 3, 7, 16, rule, ny - 1, ny, ny + 5, usize::MAX] {
                    let got = joined(&cover, rows, options);
                    assert_eq!(got.rows, 0..ny);
                    assert!(
                        bits(&got) == whole,
                        "{name}: bands of {rows} rows on {threads} threads"
                    );
                    let got = joined(&cover, rows, CoverageOptions::DEFAULT);
                    assert_eq!(got, fractions_only, "{name}: fractions, {rows} rows");
                }
            });
        }
    }
}

/// A caller that stops early gets the first bands; a band too large to compute is an error
/// in its place, as is a whole grid beyond the limit.
#[test]
fn an_early_stop_and_a_band_too_large() {
    let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
    let grid = CellGrid::uniform(-1.0, 1.0, 64, -1.0, 1.0, 64).unwrap();
    let cover = GridCoverage::new(&d, grid).unwrap();
    let first: Vec<Range<usize>> = cover.bands(5, CoverageOptions::DEFAULT, |bands| {
        bands.take(2).map(|(rows, _)| rows).collect()
    });
    assert_eq!(first, [0..5, 5..10]);
    // 2^15 x 2^14 cells: beyond MAX_CELLS in one band, never allocated.
    let huge = CellGrid::uniform(-1.0, 1.0, 1 << 15, -1.0, 1.0, 1 << 14).unwrap();
    let cover = GridCoverage::new(&d, huge).unwrap();
    assert!(matches!(
        cover.all(CoverageOptions::DEFAULT),
        Err(CoverageError::TooManyCells { .. })
    ));
    let items: Vec<_> = cover.bands(usize::MAX, CoverageOptions::DEFAULT, |bands| {
        bands.collect()
    });
    assert_eq!(items.len(), 1);
    assert_eq!(items[0].0, 0..1 << 14);
    assert!(matches!(
        items[0].1,
        Err(CoverageError::TooManyCells {
            limit: MAX_CELLS,
            ..
        })
    ));
}

/// The rule: about 8 MiB of output a band, at least one row, at least four bands a thread
/// when the grid has the rows.
#[test]
fn bands_hold_about_a_million_cells_and_feed_every_thread() {
    let fractions = CoverageOptions::DEFAULT;
    let all = fractions.with_centroids(true).with_apertures(true);
    assert_eq!(BAND_BYTES, 8 << 20);
    // Large grids: 2^20 cells a band (2^20 / 5 with centroids and apertures).
    assert_eq!(band_rows(4096, 4096, fractions, 2), 256);
    assert_eq!(band_rows(4096, 4096, all, 2), (1 << 20) / 5 / 4096);
    assert_eq!(band_rows(1000, 100_000, fractions, 8), 1048);
    // Rows longer than a band: one row at a time.
    assert_eq!(band_rows(1 << 22, 100, fractions, 2), 1);
    // Small grids: four bands a thread.
    assert_eq!(band_rows(64, 64, fractions, 2), 8);
    assert_eq!(band_rows(1024, 1024, fractions, 4), 64);
    assert_eq!(band_rows(1024, 1024, fractions, 1), 256);
    assert_eq!(band_rows(10, 3, fractions, 8), 1);
    // Degenerate arguments still give one row.
    assert_eq!(band_rows(0, 0, fractions, 0), 1);
    assert_eq!(band_rows(usize::MAX, usize::MAX, all, usize::MAX), 1);
}
