//! inRS1 and inRS2 on the paper's three domains with Halton points of the bounding box. Each
//! measured closure asserts the reference inside count, so every benchmark is also a
//! regression test (`cargo bench -- --test` runs each once).

use std::hint::black_box;

mod paper;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use paper::{PaperCase, paper_cases};
use rs_contain::baselines::FlattenedPolygon;
use rs_contain::{Classifier, ContainOptions, Location, Method};

/// Halton points per domain; the fixture files record the reference inside count for it.
const N: usize = 10_000;

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("classify");
    group.sample_size(20);
    for PaperCase {
        name,
        domain,
        points: pts,
        inside: expected,
        classifier,
    } in paper_cases(N)
    {
        for method in Method::ALL {
            group.bench_with_input(BenchmarkId::new(method.name(), name), &pts, |bch, pts| {
                bch.iter(|| {
                    let loc = classifier.locate_all_with(method, black_box(pts));
                    let inside = loc.iter().filter(|&&l| l == Location::Inside).count();
                    assert_eq!(inside, expected);
                    inside
                })
            });
        }
        let polygon = FlattenedPolygon::new(&domain, 1e-10);
        group.bench_with_input(BenchmarkId::new("polygon-1e-10", name), &pts, |bch, pts| {
            bch.iter(|| {
                let inside = polygon
                    .classify(black_box(pts))
                    .iter()
                    .filter(|&&b| b)
                    .count();
                assert_eq!(inside, expected);
                inside
            })
        });
        group.bench_function(BenchmarkId::new("build", name), |bch| {
            bch.iter(|| {
                Classifier::new(black_box(&domain), ContainOptions::default()).map(|c| c.abs_tol())
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
