//! `GridCoverage::all_into` writes the values of `GridCoverage::all`, bit for bit, into the
//! caller's arrays whatever they hold on entry, for every combination of outputs, and refuses
//! arrays that do not match the options or the grid.

use rs_coverage::{
    CellGrid, Coverage, CoverageArray, CoverageError, CoverageOptions, CoverageSlices, GridCoverage,
};
use rs_spline::{Axis, Domain, Point, circle};

/// Bit patterns (NaN equal to NaN).
fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Every output's values of `c` in the library's order, as bits.
fn all_bits(mut c: Coverage) -> Vec<(CoverageArray, Vec<u64>)> {
    CoverageArray::ALL
        .into_iter()
        .filter_map(|a| c.take_values(a).map(|v| (a, bits(&v))))
        .collect()
}

/// `all_into` on buffers filled with `garbage`, compared with `all`.
fn check(what: &str, d: &Domain, grid: CellGrid, options: CoverageOptions, garbage: f64) {
    let (nx, ny) = (grid.nx(), grid.ny());
    let cover = GridCoverage::new(d, grid).unwrap();
    let expected = all_bits(cover.all(options).unwrap());
    let mut buffers: Vec<(CoverageArray, Vec<f64>)> = CoverageArray::ALL
        .into_iter()
        .filter(|a| a.computed(options))
        .map(|a| (a, vec![garbage; a.shape(nx, ny).iter().product()]))
        .collect();
    let mut slices = CoverageSlices::fractions(&mut []);
    for (a, v) in &mut buffers {
        slices = slices.with(*a, v);
    }
    cover.all_into(options, slices).unwrap();
    let got: Vec<(CoverageArray, Vec<u64>)> = buffers.iter().map(|(a, v)| (*a, bits(v))).collect();
    assert_eq!(got.len(), expected.len(), "{what}: arrays");
    for ((a, g), (b, e)) in got.iter().zip(&expected) {
        assert_eq!(a, b);
        if let Some(k) = g.iter().zip(e).position(|(g, e)| g != e) {
            panic!(
                "{what} {options:?}: {} differs at {k}: {} vs {}",
                a.name(),
                f64::from_bits(g[k]),
                f64::from_bits(e[k])
            );
        }
    }
}

fn domains() -> Vec<(String, Domain)> {
    let mut v = vec![
        (
            "unit circle".to_string(),
            Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap(),
        ),
        (
            "off-centre circle".to_string(),
            Domain::new(vec![circle(Point::new(0.31, 0.7), 1.2).unwrap()]).unwrap(),
        ),
    ];
    for name in ["butterfly", "s3_m_shape"] {
        let path = match name {
            "butterfly" => rs_testkit::fixture_path("axom-contours/butterfly.svg"),
            _ => rs_testkit::fixture_path(&format!("inrs-paper/{name}.json")),
        };
        v.push((
            name.to_string(),
            rs_io::load_domain(path.to_str().unwrap()).unwrap(),
        ));
    }
    v
}

#[test]
fn every_output_equals_the_whole_grid_whatever_the_buffers_held() {
    let planar = [
        CoverageOptions::DEFAULT,
        CoverageOptions::DEFAULT.with_centroids(true),
        CoverageOptions::DEFAULT.with_apertures(true),
        CoverageOptions::DEFAULT
            .with_centroids(true)
            .with_apertures(true)
            .with_boundary(true)
            .with_face_centroids(true),
    ];
    for (name, d) in domains() {
        let b = d
            .bounding_box()
            .grown_by(0.07 * d.bounding_box().diagonal());
        for (nx, ny) in [(1, 1), (37, 23), (200, 301)] {
            let grid = CellGrid::uniform(b.min.x, b.max.x, nx, b.min.y, b.max.y, ny).unwrap();
            for options in planar {
                for garbage in [f64::NAN, 0.0, 7.5] {
                    check(&name, &d, grid.clone(), options, garbage);
                }
            }
        }
    }
    // Revolved about y: the grid right of the axis.
    let d = Domain::new(vec![circle(Point::new(2.0, 0.5), 1.0).unwrap()]).unwrap();
    let grid = CellGrid::uniform(0.5, 3.5, 90, -1.0, 2.0, 70).unwrap();
    for options in [
        CoverageOptions::DEFAULT.with_axisymmetric(Some(Axis::Y)),
        CoverageOptions::DEFAULT
            .with_axisymmetric(Some(Axis::Y))
            .with_centroids(true)
            .with_apertures(true),
    ] {
        check("revolved circle", &d, grid.clone(), options, -3.0);
    }
}

#[test]
fn arrays_that_do_not_match_are_refused_in_one_line() {
    let d = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0).unwrap()]).unwrap();
    let grid = CellGrid::uniform(-1.0, 1.0, 8, -1.0, 1.0, 4).unwrap();
    let cover = GridCoverage::new(&d, grid).unwrap();
    let mut short = vec![0.0; 31];
    let e = cover
        .all_into(
            CoverageOptions::DEFAULT,
            CoverageSlices::fractions(&mut short),
        )
        .unwrap_err();
    assert!(matches!(
        e,
        CoverageError::Output {
            array: "fractions",
            expected: Some(32),
            got: Some(31)
        }
    ));
    assert_eq!(
        e.to_string(),
        "output fractions: 31 values given, the grid needs 32"
    );
    let mut f = vec![0.0; 32];
    let e = cover
        .all_into(
            CoverageOptions::DEFAULT.with_centroids(true),
            CoverageSlices::fractions(&mut f),
        )
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "output centroids: not given, the options ask for it (64 values)"
    );
    let mut c = vec![0.0; 64];
    let mut slices = CoverageSlices::fractions(&mut f);
    slices.centroids = Some(&mut c);
    let e = cover
        .all_into(CoverageOptions::DEFAULT, slices)
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "output centroids: given, but the options do not ask for it"
    );
}

/// Every output of every band, as bits, from `GridCoverage::bands` with each band handed back
/// (`recycle`) or not.
fn streamed(
    cover: &GridCoverage,
    band_rows: usize,
    options: CoverageOptions,
    recycle: bool,
) -> Vec<Vec<(CoverageArray, Vec<u64>)>> {
    cover.bands(band_rows, options, |mut bands| {
        let mut out = Vec::new();
        while let Some((_, band)) = bands.next() {
            let band = band.unwrap();
            out.push(all_bits(band.clone()));
            if recycle {
                bands.recycle(band);
            }
        }
        out
    })
}

#[test]
fn bands_in_recycled_arrays_equal_new_ones() {
    let everything = CoverageOptions::DEFAULT
        .with_centroids(true)
        .with_apertures(true)
        .with_boundary(true)
        .with_face_centroids(true);
    for (name, d) in domains() {
        let b = d
            .bounding_box()
            .grown_by(0.07 * d.bounding_box().diagonal());
        let grid = CellGrid::uniform(b.min.x, b.max.x, 150, b.min.y, b.max.y, 211).unwrap();
        let cover = GridCoverage::new(&d, grid).unwrap();
        for options in [CoverageOptions::DEFAULT, everything] {
            // 211 rows in bands of 13: the last band is lower than the arrays it reuses.
            for band_rows in [13, 50] {
                let new = streamed(&cover, band_rows, options, false);
                let reused = streamed(&cover, band_rows, options, true);
                assert_eq!(new.len(), reused.len());
                for (k, (a, b)) in new.iter().zip(&reused).enumerate() {
                    assert!(
                        a == b,
                        "{name} {options:?}: band {k} of {band_rows} rows differs"
                    );
                }
            }
        }
    }
}
