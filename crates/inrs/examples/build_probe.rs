//! The timing probe of `cargo xtask bench --only build`: what it costs to get from a domain to
//! its first answer, and the query speeds after, printed as `key<TAB>value` lines.
//!
//! The bench builds this same file at the current tree and at the commit before the lazy
//! indexes (it uses only API that exists at both) and runs the two alternately, so that the
//! ratios compare builds measured in the same run.
//!
//! Usage: `build_probe [--reps N] DOMAIN_FILE... [--cad CAD_FILE...]`

use std::time::Instant;

use inrs::contain::baselines::halton_points;
use inrs::contain::{
    Classifier, ContainOptions, Containment, FastWindingField, Locate, LocatorOptions, Method,
    PointLocator, PointQuery, WindingField,
};
use inrs::{Domain, Location, Point};

/// The median of `reps` timings of `f`, in seconds.
fn median_time(reps: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..reps.max(1))
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64()
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

/// `n` Halton points of `d`'s bounding box grown by 5% of its diagonal.
fn points_around(d: &Domain, n: usize) -> Vec<Point> {
    let b = d.bounding_box();
    halton_points(n, b.grown_by(0.05 * b.diagonal()))
}

/// One query point away from the boundary's vertices (an odd offset from the box's centre).
fn probe_point(d: &Domain) -> Point {
    let b = d.bounding_box();
    Point::new(
        b.min.x + 0.4137 * (b.max.x - b.min.x),
        b.min.y + 0.5371 * (b.max.y - b.min.y),
    )
}

fn per_domain(path: &str, reps: usize) -> Result<(), String> {
    let d = inrs::io::load_domain(path).map_err(|e| format!("{path}: {e}"))?;
    let name = std::path::Path::new(path)
        .file_stem()
        .map_or_else(|| path.to_string(), |s| s.to_string_lossy().into_owned());
    let q = probe_point(&d);
    let options = ContainOptions::DEFAULT;
    println!("pieces/{name}\t{}", d.bezier_pieces().len());
    let field_ready = median_time(reps, || {
        let w = WindingField::new(&d, options.relative_tolerance).expect("a valid tolerance");
        std::hint::black_box(FastWindingField::new(&w).winding_number(q));
    });
    println!("field_ready/{name}\t{field_ready:e}");
    let one_point = median_time(reps, || {
        let c = Containment::new(&d, options).expect("a closed fixture");
        let mut out = [Location::Outside];
        c.engine(1).values_into(&[q][..], &mut out);
        std::hint::black_box(out);
    });
    println!("one_point/{name}\t{one_point:e}");
    let with_locator = median_time(reps, || {
        let c = Classifier::new(&d, options).expect("a closed fixture");
        std::hint::black_box(c.locator().locate(q));
    });
    println!("classifier_locator/{name}\t{with_locator:e}");
    // The whole grid built at once (the eager constructor), whatever the first query needs.
    let whole_grid = median_time(reps, || {
        let c = Classifier::new(&d, options).expect("a closed fixture");
        std::hint::black_box(PointLocator::new(&c, LocatorOptions::DEFAULT).locate(q));
    });
    println!("classifier_whole_grid/{name}\t{whole_grid:e}");
    if path.ends_with(".json") {
        let text = std::fs::read_to_string(path).map_err(|e| e.to_string())?;
        let from_text = median_time(reps, || {
            let d = inrs::io::json::domain_from_json(&text).expect("the fixture parses");
            let c = Containment::new(&d, options).expect("a closed fixture");
            let mut out = [Location::Outside];
            c.engine(1).values_into(&[q][..], &mut out);
            std::hint::black_box(out);
        });
        println!("json_one_point/{name}\t{from_text:e}");
    }
    // Query speeds, the indexes built before the clock starts (seconds per point).
    let pts = points_around(&d, 90_000);
    let field = WindingField::new(&d, options.relative_tolerance).expect("a valid tolerance");
    let fast = FastWindingField::new(&field);
    let mut w = vec![0.0f64; pts.len()];
    let t = median_time(reps.min(5), || fast.values_into(&pts[..], &mut w));
    println!("field_query/{name}\t{:e}", t / pts.len() as f64);
    let c = Classifier::new(&d, options).expect("a closed fixture");
    let locator = c.locator();
    let mut loc = vec![Location::Outside; pts.len()];
    let t = median_time(reps.min(5), || locator.values_into(&pts[..], &mut loc));
    println!("locator_query/{name}\t{:e}", t / pts.len() as f64);
    let small = &pts[..10_000];
    let t = median_time(reps.min(5), || {
        c.engine(Method::InRS2, small.len())
            .values_into(small, &mut loc[..small.len()])
    });
    println!("inrs2_query/{name}\t{:e}", t / small.len() as f64);
    Ok(())
}

/// Every face of the CAD files, each with 400 Halton points around its box: the per-face loop (a
/// fresh `Containment` per face, one thread), as a front end did it one call at a time.
fn cad_faces(paths: &[String]) -> Result<(), String> {
    let mut faces: Vec<(Domain, Vec<Point>)> = Vec::new();
    for p in paths {
        let model = inrs::io::cad::CadModel::read(p).map_err(|e| format!("{p}: {e}"))?;
        for d in model.face_domains(None).into_iter().flatten() {
            let pts = points_around(&d, 400);
            faces.push((d, pts));
        }
    }
    let options = ContainOptions::DEFAULT;
    let t = median_time(3, || {
        for (d, pts) in &faces {
            let mut out = vec![Location::Outside; pts.len()];
            if let Ok(c) = Containment::new(d, options) {
                c.engine(pts.len()).values_into(&pts[..], &mut out);
            }
            std::hint::black_box(out);
        }
    });
    println!("cad_faces\t{}", faces.len());
    println!("cad_per_face\t{:e}", t / faces.len().max(1) as f64);
    first_and_warm(&faces, options);
    Ok(())
}

/// The "first classify / warm classify" of the faces: per face, a fresh `Containment`
/// and its first batch (which builds what the batch needs), then the same batch again on the
/// warm value; each the sum over the faces, the median of a few rounds.
fn first_and_warm(faces: &[(Domain, Vec<Point>)], options: ContainOptions) {
    let (mut firsts, mut warms) = (Vec::new(), Vec::new());
    for _ in 0..5 {
        let (mut first, mut warm) = (0.0, 0.0);
        for (d, pts) in faces {
            let mut out = vec![Location::Outside; pts.len()];
            let start = Instant::now();
            let Ok(c) = Containment::new(d, options) else {
                continue;
            };
            c.engine(pts.len()).par_values_into(&pts[..], &mut out);
            let built = Instant::now();
            c.engine(pts.len()).par_values_into(&pts[..], &mut out);
            let end = Instant::now();
            first += (built - start).as_secs_f64();
            warm += (end - built).as_secs_f64();
            std::hint::black_box(&out);
        }
        firsts.push(first);
        warms.push(warm);
    }
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let n = faces.len().max(1) as f64;
    println!("cad_first_per_face\t{:e}", median(firsts) / n);
    println!("cad_warm_per_face\t{:e}", median(warms) / n);
}

fn main() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let mut reps = 21;
    let (mut domains, mut cad) = (Vec::new(), Vec::new());
    let mut in_cad = false;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--reps" => {
                reps = args
                    .next()
                    .and_then(|r| r.parse().ok())
                    .ok_or("--reps needs a count")?
            }
            "--cad" => in_cad = true,
            _ if in_cad => cad.push(a),
            _ => domains.push(a),
        }
    }
    for d in &domains {
        per_domain(d, reps)?;
    }
    if !cad.is_empty() {
        cad_faces(&cad)?;
    }
    Ok(())
}
