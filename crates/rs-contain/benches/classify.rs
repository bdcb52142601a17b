//! inRS1 and inRS2 on the paper's three domains with Halton points of the bounding box. Each
//! measured closure asserts the reference inside count, so every benchmark is also a
//! regression test (`cargo bench -- --test` runs each once).

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rs_contain::baselines::{FlattenedPolygon, halton_points};
use rs_contain::{Classifier, ContainOptions, Location, Method};
use rs_spline::{BoundingBox, Point};

/// (fixture, reference bounding box, N, reference inside count) from the fixture files.
const CASES: [(&str, [f64; 4], usize, usize); 3] = [
    (
        "s3_m_shape",
        [-1.0000000000000002, 1.0, -1.0, 1.0000000000000002],
        10_000,
        4970,
    ),
    (
        "s4_disk_ellipse_segment",
        [-0.5, 1.0, -1.0000000000000002, 1.0],
        10_000,
        6900,
    ),
    ("s5_lune", [-1.0, 1.0, -1.0, 1.0], 10_000, 5528),
];

fn bench(c: &mut Criterion) {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/inrs-paper");
    let mut group = c.benchmark_group("classify");
    group.sample_size(20);
    for (name, b, n, expected) in CASES {
        let domain = rs_io::json::domain_from_json_file(format!("{dir}/{name}.json"))
            .expect("fixture loads");
        let bbox = BoundingBox {
            min: Point::new(b[0], b[2]),
            max: Point::new(b[1], b[3]),
        };
        let pts = halton_points(n, bbox);
        let classifier = Classifier::new(&domain, ContainOptions::default()).expect("closed");
        for method in Method::ALL {
            group.bench_with_input(BenchmarkId::new(method.name(), name), &pts, |bch, pts| {
                bch.iter(|| {
                    let loc = classifier.classify(black_box(pts), method);
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
