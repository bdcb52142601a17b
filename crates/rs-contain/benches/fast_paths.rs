//! The fast paths: grid point locator (one thread and all threads) against inRS2 on the paper's
//! domains, and the accelerated winding-number field on the 500-curve flower. Each measured
//! closure asserts its result (reference inside counts, or agreement with the reference field).

use rs_contain::Locate;
use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rs_contain::baselines::halton_points;
use rs_contain::{
    Classifier, ContainOptions, FastWindingField, Location, LocatorOptions, Method, PointLocator,
    WindingField,
};
use rs_spline::{BoundingBox, Point};

/// (fixture, reference bounding box, N, reference inside count) from the fixture files.
const CASES: [(&str, [f64; 4], usize, usize); 3] = [
    (
        "s3_m_shape",
        [-1.0000000000000002, 1.0, -1.0, 1.0000000000000002],
        100_000,
        49718,
    ),
    (
        "s4_disk_ellipse_segment",
        [-0.5, 1.0, -1.0000000000000002, 1.0],
        100_000,
        69031,
    ),
    ("s5_lune", [-1.0, 1.0, -1.0, 1.0], 100_000, 55285),
];

fn inside(v: &[Location]) -> usize {
    v.iter().filter(|&&l| l == Location::Inside).count()
}

fn locator(c: &mut Criterion) {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures");
    let mut group = c.benchmark_group("fast");
    group.sample_size(10);
    for (name, b, n, expected) in CASES {
        let domain = rs_io::json::domain_from_json_file(format!("{dir}/inrs-paper/{name}.json"))
            .expect("fixture");
        let bbox = BoundingBox {
            min: Point::new(b[0], b[2]),
            max: Point::new(b[1], b[3]),
        };
        let pts = halton_points(n, bbox);
        let classifier = Classifier::new(&domain, ContainOptions::default()).expect("closed");
        group.bench_with_input(BenchmarkId::new("inrs2", name), &pts, |bch, pts| {
            bch.iter(|| {
                assert_eq!(
                    inside(&classifier.classify(black_box(pts), Method::InRS2)),
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
    let flower = rs_io::json::domain_from_json_file(format!("{dir}/synthetic/flower500.json"))
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
