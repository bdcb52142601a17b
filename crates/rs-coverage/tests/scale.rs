//! Cells of any size: scaling the domain and the grid by a power of two `2^k` scales every
//! output exactly (fractions and apertures the same, lengths and centroids times `2^k`, bit for
//! bit) for cells from about `1e-80` to `1e98` across, and an output whose moments would overflow or lose their precision at the cells' size
//! is refused in one line (`CoverageError::CellsOutOfRange`) instead of coming out `NaN` or
//! wrong (centroids of cells `1e119` across were `NaN`, of cells `1e-140` across up to 3% off;
//! revolved volumes of cells `1e119` across `NaN`).

use rs_coverage::{CellGrid, Coverage, CoverageError, CoverageOptions, GridCoverage};
use rs_spline::{Axis, Domain, Point, circle, polyline};

/// An off-centre disc with a triangular hole, lifted by `lift` along y, times `s`; its grid,
/// 24 x 18 cells over `[-0.8, 1.4] x [lift - 1.3, lift + 0.9]` times `s`.
fn case(s: f64, lift: f64) -> (Domain, CellGrid) {
    let p = |x: f64, y: f64| Point::new(x * s, (y + lift) * s);
    let hole = polyline(&[p(0.1, -0.5), p(0.7, 0.1), p(0.2, 0.3), p(0.1, -0.5)]).unwrap();
    let domain = Domain::new(vec![circle(p(0.3, -0.2), s).unwrap(), hole]).unwrap();
    let grid = CellGrid::uniform(
        -0.8 * s,
        1.4 * s,
        24,
        (lift - 1.3) * s,
        (lift + 0.9) * s,
        18,
    )
    .unwrap();
    (domain, grid)
}

fn cover(s: f64, lift: f64, options: CoverageOptions) -> Result<Coverage, CoverageError> {
    let (domain, grid) = case(s, lift);
    GridCoverage::new(&domain, grid).unwrap().all(options)
}

/// `a` scaled: the same where `power` is 0, times `s` where it is 1 (NaN where `a` is NaN).
fn assert_scaled(what: &str, a: &[f64], b: &[f64], s: f64, power: i32) {
    assert_eq!(a.len(), b.len(), "{what}");
    for (x, y) in a.iter().zip(b) {
        let want = x * s.powi(power);
        assert!(
            want == *y || (x.is_nan() && y.is_nan()),
            "{what}: {y:e}, want {want:e}"
        );
    }
}

/// Within `1e-14` of each other, relative to the larger.
fn assert_close(what: &str, a: &[f64], b: &[f64]) {
    assert_eq!(a.len(), b.len(), "{what}");
    for (x, y) in a.iter().zip(b) {
        assert!(
            (x - y).abs() <= 1e-14 * x.abs().max(y.abs()),
            "{what}: {y:e} against {x:e}"
        );
    }
}

/// `c`'s fractions and cell centroids those of `unit` scaled by `2^k`, bit for bit.
fn assert_cells_scaled(unit: &Coverage, c: &Coverage, k: i32) {
    let s = 2f64.powi(k);
    assert_scaled(
        &format!("fractions 2^{k}"),
        &unit.fractions,
        &c.fractions,
        s,
        0,
    );
    let (a, b) = (flat(&unit.centroids), flat(&c.centroids));
    assert_scaled(&format!("centroids 2^{k}"), &a, &b, s, 1);
}

fn flat(v: &Option<Vec<[f64; 2]>>) -> Vec<f64> {
    v.as_ref().unwrap().iter().flatten().copied().collect()
}

#[test]
fn planar_outputs_scale_exactly_and_centroids_out_of_range_are_refused() {
    let all = CoverageOptions::DEFAULT
        .with_centroids(true)
        .with_apertures(true)
        .with_boundary(true)
        .with_face_centroids(true);
    let unit = cover(1.0, 0.0, all).unwrap();
    for k in [-260, -90, 77, 260, 330] {
        let s = 2f64.powi(k);
        let c = cover(s, 0.0, all).unwrap_or_else(|e| panic!("2^{k}: {e}"));
        assert_cells_scaled(&unit, &c, k);
        let same = |a: &Option<Vec<f64>>, b: &Option<Vec<f64>>, power, what| {
            assert_scaled(what, a.as_ref().unwrap(), b.as_ref().unwrap(), s, power)
        };
        same(&unit.x_apertures, &c.x_apertures, 0, "x apertures");
        same(&unit.y_apertures, &c.y_apertures, 0, "y apertures");
        same(&unit.boundary_lengths, &c.boundary_lengths, 1, "lengths");
        same(&unit.x_face_centroids, &c.x_face_centroids, 1, "x faces");
        same(&unit.y_face_centroids, &c.y_face_centroids, 1, "y faces");
        let (bu, bc) = (flat(&unit.boundary_centroids), flat(&c.boundary_centroids));
        assert_scaled("boundary centroids", &bu, &bc, s, 1);
    }
    for (k, overflow) in [(-460, false), (400, true), (480, true)] {
        let s = 2f64.powi(k);
        let e = cover(s, 0.0, CoverageOptions::DEFAULT.with_centroids(true)).unwrap_err();
        assert!(
            matches!(e, CoverageError::CellsOutOfRange { what: "centroids", overflow: o, .. } if o == overflow),
            "2^{k}: {e:?}"
        );
        assert!(!e.to_string().contains('\n'));
        // The fractions alone stay in range (within a few units of rounding: at `2^-460`
        // some of their terms are subnormal, and they move by 2 ulp).
        let c = cover(s, 0.0, CoverageOptions::DEFAULT).unwrap();
        assert_close(&format!("fractions 2^{k}"), &unit.fractions, &c.fractions);
    }
}

#[test]
fn revolved_outputs_scale_exactly_and_moments_out_of_range_are_refused() {
    // Lifted above the x axis: the grid lies on one side of it.
    let options = |centroids| {
        CoverageOptions::DEFAULT
            .with_axisymmetric(Some(Axis::X))
            .with_centroids(centroids)
    };
    let unit = cover(1.0, 1.4, options(true)).unwrap();
    for k in [-180, 200] {
        let s = 2f64.powi(k);
        let c = cover(s, 1.4, options(true)).unwrap_or_else(|e| panic!("2^{k}: {e}"));
        assert_cells_scaled(&unit, &c, k);
    }
    // Revolved centroids (moments like r s^3 and s^4) leave the range before the fractions
    // (r s^2 and s^3) do.
    for k in [-260, 330] {
        let s = 2f64.powi(k);
        let e = cover(s, 1.4, options(true)).unwrap_err();
        assert!(
            matches!(
                e,
                CoverageError::CellsOutOfRange {
                    what: "revolved centroids",
                    ..
                }
            ),
            "2^{k}: {e:?}"
        );
        let c = cover(s, 1.4, options(false)).unwrap();
        assert_close(&format!("fractions 2^{k}"), &unit.fractions, &c.fractions);
    }
    for (k, overflow) in [(-400, false), (400, true)] {
        let e = cover(2f64.powi(k), 1.4, options(false)).unwrap_err();
        assert!(
            matches!(e, CoverageError::CellsOutOfRange { what: "revolved fractions", overflow: o, .. } if o == overflow),
            "2^{k}: {e:?}"
        );
    }
}
