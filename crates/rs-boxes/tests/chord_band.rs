//! Chord bands of boxes and of the parts cut from them for a grid: the parts share out each
//! box's abscissas exactly, and whatever a band decides without a solve is the box's own
//! answer (its crossing, and that a point is not near), for points near and far from curved,
//! strongly weighted pieces.

use rs_boxes::{BoxOptions, ChordBand, MonotoneBox, MonotoneBoxes};
use rs_spline::grid::GridFrame;
use rs_spline::{Domain, Point};

fn domains() -> Vec<(String, Domain)> {
    let mut v = rs_testkit::fixtures();
    v.push(rs_testkit::lens());
    v.push(rs_testkit::staircase());
    v.into_iter().map(|c| (c.name, c.domain)).collect()
}

/// The parts of `b` for a grid of `cells` cells per side over the domain's box.
fn parts(d: &Domain, b: &MonotoneBox, cells: usize) -> Vec<(ChordBand, bool)> {
    let frame = GridFrame::new(d.bounding_box(), cells);
    let mut v = Vec::new();
    b.for_grid_parts(&frame, |band, whole| v.push((band, whole)));
    v
}

#[test]
fn parts_share_out_the_box_exactly() {
    let mut halved = 0;
    for (name, d) in domains() {
        let mb = MonotoneBoxes::new(&d, BoxOptions::DEFAULT).unwrap();
        for b in mb.boxes() {
            let p = parts(&d, b, 256);
            assert!(!p.is_empty());
            if p.len() == 1 {
                assert_eq!(p[0], (b.band, true), "{name}");
                continue;
            }
            halved += 1;
            assert!(p.iter().all(|&(_, whole)| !whole), "{name}");
            assert_eq!(p[0].0.start, b.band.start, "{name}");
            assert_eq!(p[p.len() - 1].0.end, b.band.end, "{name}");
            for w in p.windows(2) {
                assert_eq!(
                    w[0].0.end, w[1].0.start,
                    "{name}: parts must meet bit for bit"
                );
            }
            // Every abscissa of the box's half-open range lies in exactly one part's.
            for k in 0..200 {
                let x = b.band.xmin + (b.band.xmax - b.band.xmin) * k as f64 / 200.0;
                let x = if k == 0 { b.band.xmin } else { x };
                let owners = p
                    .iter()
                    .filter(|(band, _)| band.xmin <= x && x < band.xmax)
                    .count();
                let expected = usize::from(b.band.xmin <= x && x < b.band.xmax && !b.band.vertical);
                if !b.band.vertical {
                    assert_eq!(owners, expected, "{name}: x = {x}");
                }
            }
        }
    }
    assert!(halved > 20, "{halved}");
}

/// Points round a box: on a lattice over its rectangle (the first `LATTICE`), then off the
/// curve along the normal at distances from far below the tolerance to far above.
const LATTICE: usize = 25 * 25;

fn probes(b: &MonotoneBox, tol: f64) -> Vec<Point> {
    let mut v = Vec::new();
    let (w, h) = (b.band.xmax - b.band.xmin, b.band.ymax - b.band.ymin);
    for i in 0..=24 {
        for j in 0..=24 {
            v.push(Point::new(
                b.band.xmin - 0.1 * w + 1.2 * w * i as f64 / 24.0,
                b.band.ymin - 0.1 * h + 1.2 * h * j as f64 / 24.0,
            ));
        }
    }
    for k in 0..=40 {
        let t = k as f64 / 40.0;
        let q = b.point_at(t);
        let e = 1e-6 * (w + h);
        let tangent = b.point_at((t + 1e-6).min(1.0)) - b.point_at((t - 1e-6).max(0.0));
        if tangent.length() == 0.0 {
            continue;
        }
        let n = tangent.perp() / tangent.length();
        for f in [0.0, 0.5, 0.99, 1.01, 2.0, 10.0, 1e3, 1e6] {
            v.push(q + n * (f * tol));
            v.push(q - n * (f * tol));
        }
        v.push(q + n * e);
        v.push(q - n * e);
    }
    v
}

#[test]
fn bands_of_parts_decide_as_the_box_does() {
    let mut decided = 0usize;
    let mut solved = 0usize;
    for (name, d) in domains() {
        let mb = MonotoneBoxes::new(&d, BoxOptions::DEFAULT).unwrap();
        for rel in [1e-12, 0.0] {
            let tol = rel * d.bounding_box().diagonal();
            for b in mb.boxes() {
                let p = parts(&d, b, 512);
                for (k, q) in probes(b, tol).into_iter().enumerate() {
                    let near = b.is_near(q, tol);
                    // Screening: a box near q has a part whose band may be near q.
                    if near {
                        assert!(
                            p.iter().any(|(band, _)| band.may_be_near(q, tol)),
                            "{name}: {q:?} is near the box, yet no part's band may be"
                        );
                        continue;
                    }
                    // Crossing: the one part over q.x decides as the box does, when it can.
                    let over: Vec<_> = p
                        .iter()
                        .filter(|(band, _)| band.xmin <= q.x && q.x < band.xmax)
                        .collect();
                    assert!(over.len() <= 1, "{name}: {q:?} in {} parts", over.len());
                    let truth = b.crosses_below(q);
                    match over.first().map(|(band, _)| band.crossing_below(q)) {
                        Some(Some(c)) => {
                            decided += usize::from(k < LATTICE);
                            assert_eq!(c, truth, "{name}: crossing below {q:?}");
                        }
                        Some(None) => solved += usize::from(k < LATTICE),
                        None => assert!(!truth, "{name}: {q:?} crosses outside every part"),
                    }
                }
            }
        }
    }
    // Most lattice points over a part are decided by its band; a few (within its slack) are
    // solved.
    assert!(decided > 10 * solved, "decided {decided}, solved {solved}");
}
