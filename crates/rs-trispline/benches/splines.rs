//! Quasi-interpolation at the paper's finest triangulation (`ny = 65`, `d = 5`) and evaluation
//! of the spline at 10^6 points, against the domain's own grid point locator on the same
//! points in the same run (evaluation starts with that containment test). Each closure
//! asserts its result.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rs_contain::baselines::halton_points;
use rs_contain::{Classifier, ContainOptions, Locate, Location};
use rs_mesh::{CurvedTriangulation, well_spaced_points};
use rs_spline::Point;
use rs_trispline::quasi_interpolate;

fn f(p: Point) -> f64 {
    (10.0 * p.x).sin() + (10.0 * p.y).sin()
}

fn splines(c: &mut Criterion) {
    let d = rs_testkit::inrs_fixture("s4_disk_ellipse_segment").domain;
    let mesh = CurvedTriangulation::new(&d, &well_spaced_points(&d, 65).unwrap()).unwrap();
    let mut group = c.benchmark_group("splines");
    group.sample_size(10);
    group.bench_function("quasi-interpolation ny=65 d=5", |b| {
        b.iter(|| {
            let s = quasi_interpolate(black_box(mesh.clone()), 5, &f).unwrap();
            assert_eq!(s.mesh().triangles().len(), mesh.triangles().len());
            s
        })
    });
    let s = quasi_interpolate(mesh.clone(), 5, &f).unwrap();
    let eval = s.evaluator().unwrap();
    let pts = halton_points(1_000_000, d.bounding_box());
    let classifier = Classifier::new(&d, ContainOptions::default()).unwrap();
    let inside = classifier
        .locator()
        .locate_all(&pts)
        .iter()
        .filter(|&&l| l != Location::Outside)
        .count();
    group.bench_function("evaluate 1e6 points", |b| {
        b.iter(|| {
            let v = eval.evaluate_all(black_box(&pts));
            assert_eq!(v.iter().filter(|j| j.is_some()).count(), inside);
            v
        })
    });
    group.bench_function("baseline: grid locator containment 1e6 points", |b| {
        b.iter(|| {
            let l = classifier.locator().locate_all_parallel(black_box(&pts));
            assert_eq!(
                l.iter().filter(|&&l| l != Location::Outside).count(),
                inside
            );
            l
        })
    });
    group.finish();
}

criterion_group!(benches, splines);
criterion_main!(benches);
