//! Sampling (Algorithm 11.1 at the paper's `ny = 251`), curved triangulation and point
//! location on the inRS paper's domains, with inRS containment of the same points as the
//! baseline measured in the same run. Each closure asserts its result.

use rs_contain::Locate;
use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rs_contain::baselines::halton_points;
use rs_contain::{Classifier, ContainOptions, Location};
use rs_mesh::{CurvedLocator, CurvedTriangulation, well_spaced_points};

fn mesh(c: &mut Criterion) {
    let mut group = c.benchmark_group("mesh");
    group.sample_size(10);
    for name in rs_testkit::PAPER_DOMAINS {
        let d = rs_testkit::inrs_fixture(name).domain;
        let area = d.signed_area().abs();
        group.bench_function(BenchmarkId::new("sample ny=251", name), |b| {
            b.iter(|| {
                let p = well_spaced_points(black_box(&d), 251).unwrap();
                assert!(p.interior.len() > 20_000);
                p
            })
        });
        let pts = well_spaced_points(&d, 251).unwrap();
        group.bench_function(BenchmarkId::new("curved triangulation ny=251", name), |b| {
            b.iter(|| {
                let m = CurvedTriangulation::new(black_box(&d), &pts).unwrap();
                let total: f64 = (0..m.triangles().len()).map(|t| m.triangle_area(t)).sum();
                assert!((total - area).abs() < 1e-9 * area);
                m
            })
        });
        let small = CurvedTriangulation::new(&d, &well_spaced_points(&d, 40).unwrap()).unwrap();
        let locator = CurvedLocator::new(&small).unwrap();
        let classifier = Classifier::new(&d, ContainOptions::default()).unwrap();
        let queries = halton_points(10_000, d.bounding_box());
        let inside = classifier
            .locate_all_with(rs_contain::Method::InRS2, &queries)
            .iter()
            .filter(|&&l| l != Location::Outside)
            .count();
        group.bench_function(BenchmarkId::new("locate 1e4 (ny=40)", name), |b| {
            b.iter(|| {
                let found = queries
                    .iter()
                    .filter(|&&p| locator.triangle_at(p).is_some())
                    .count();
                assert_eq!(found, inside);
            })
        });
        group.bench_function(
            BenchmarkId::new("baseline: inRS containment 1e4", name),
            |b| {
                b.iter(|| {
                    let n = queries
                        .iter()
                        .filter(|&&p| classifier.locate(p) != Location::Outside)
                        .count();
                    assert_eq!(n, inside);
                })
            },
        );
    }
    group.finish();
}

criterion_group!(benches, mesh);
criterion_main!(benches);
