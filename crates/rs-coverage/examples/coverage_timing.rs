//! Wall-clock time of whole-grid coverage of the unit disc and the Axom butterfly on
//! `1024^2` and `4096^2` grids (fractions only, and with centroids and apertures), on all of
//! rayon's threads and on one band.
//!
//! `cargo run --release -p rs-coverage --example coverage_timing`

use std::time::Instant;

use rs_coverage::{CellGrid, CoverageOptions, GridCoverage};
use rs_spline::{Domain, Point, circle};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let disc = Domain::new(vec![circle(Point::new(0.0, 0.0), 1.0)?])?;
    let butterfly = rs_io::load_domain(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/axom-contours/butterfly.svg"
    ))?;
    let all = CoverageOptions::DEFAULT
        .with_centroids(true)
        .with_apertures(true);
    println!("threads: {}", rayon::current_num_threads());
    for (name, d) in [("disc", &disc), ("butterfly", &butterfly)] {
        let b = d
            .bounding_box()
            .grown_by(0.01 * d.bounding_box().diagonal());
        for n in [1024, 4096] {
            let grid = CellGrid::uniform(b.min.x, b.max.x, n, b.min.y, b.max.y, n)?;
            let start = Instant::now();
            let cover = GridCoverage::new(d, grid)?;
            let prepared = start.elapsed();
            for (what, options) in [("fractions", CoverageOptions::DEFAULT), ("all", all)] {
                let start = Instant::now();
                let c = cover.all(options)?;
                let parallel = start.elapsed();
                let covered: f64 = c.fractions.iter().sum();
                drop(c);
                let start = Instant::now();
                let one = cover.rows(0..n, options)?;
                let single = start.elapsed();
                assert_eq!(covered, one.fractions.iter().sum::<f64>());
                drop(one);
                println!(
                    "{name} {n}^2 {what}: prepare {:.1} ms, all threads {:.1} ms, one band {:.1} ms ({covered:.1} cells covered)",
                    prepared.as_secs_f64() * 1e3,
                    parallel.as_secs_f64() * 1e3,
                    single.as_secs_f64() * 1e3,
                );
            }
        }
    }
    Ok(())
}
