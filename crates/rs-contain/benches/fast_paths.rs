//! The fast paths: grid point locator (one thread and all threads) against inRS2 on the paper's
//! domains, and the accelerated winding-number field on the 500-curve flower. Each measured
//! closure asserts its result (reference inside counts, or agreement with the reference field).

use rs_contain::Locate;
use std::hint::black_box;

mod paper;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use paper::{PaperCase, paper_cases};
use rs_contain::baselines::halton_points;
use rs_contain::{FastWindingField, Location, LocatorOptions, Method, PointLocator, WindingField};

/// Halton points per domain; the fixture files record the reference inside count for it.
const N: usize = 100_000;

fn inside(v: &[Location]) -> usize {
    v.iter().filter(|&&l| l == Location::Inside).count()
}

fn locator(c: &mut Criterion) {
    let mut group = c.benchmark_group("fast");
    group.sample_size(10);
    for PaperCase {
        name,
        points: pts,
        inside: expected,
        classifier,
        ..
    } in paper_cases(N)
    {
        group.bench_with_input(BenchmarkId::new("inrs2", name), &pts, |bch, pts| {
            bch.iter(|| {
                assert_eq!(
                    inside(&classifier.locate_all_with(Method::InRS2, black_box(pts))),
                    expected
                )
            })
        });
        let loc = PointLocator::new(&classifier, LocatorOptions::default());
        group.bench_with_input(BenchmarkId::new("locator", name), &pts, |bch, pts| {
            bch.iter(|| assert_eq!(inside(&loc.locate_all(black_box(pts))), expected))
        });
        group.bench_with_input(
            BenchmarkId::new("locator-parallel", name),
            &pts,
            |bch, pts| {
                bch.iter(|| assert_eq!(inside(&loc.locate_all_parallel(black_box(pts))), expected))
            },
        );
        group.bench_function(BenchmarkId::new("locator-build", name), |bch| {
            bch.iter(|| {
                PointLocator::new(black_box(&classifier), LocatorOptions::default()).cells()
            })
        });
    }
    let flower =
        rs_io::json::domain_from_json_file(rs_testkit::fixture_path("synthetic/flower500.json"))
            .expect("fixture");
    let field = WindingField::new(&flower, rs_contain::DEFAULT_RELATIVE_TOLERANCE).expect("field");
    let fast = FastWindingField::new(&field);
    let pts = halton_points(10_000, flower.bounding_box());
    let check: Vec<f64> = pts[..100]
        .iter()
        .map(|&q| field.winding_number(q))
        .collect();
    group.bench_with_input(
        BenchmarkId::new("gwn-fast", "flower500"),
        &pts,
        |bch, pts| {
            bch.iter(|| {
                let w = fast.winding_numbers(black_box(pts));
                assert!(w.iter().zip(&check).all(|(a, b)| (a - b).abs() < 1e-12));
                w.len()
            })
        },
    );
    group.finish();
}

criterion_group!(benches, locator);
criterion_main!(benches);
