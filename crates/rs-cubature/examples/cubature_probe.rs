//! Nodes, candidates, residual and time of the rules of degree 5, 10, 20 and 30 (or of the one
//! degree `--degree N`, e.g. 40) on the inRS paper's three domains (best of three runs each,
//! one thread).
//!
//! `cargo run --release -p rs-cubature --example cubature_probe [--candidates K] [--runs R]
//! [--degree N]`

use std::time::Instant;

use rs_cubature::{CubatureOptions, CubatureRule, dim_polynomials};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let value = |flag: &str, default: usize| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let k = value(
        "--candidates",
        rs_cubature::DEFAULT_CANDIDATES_PER_POLYNOMIAL,
    );
    let runs = value("--runs", 3).max(1);
    println!("domain                    degree  nodes  dim P_n  candidates  residual   time (ms)");
    for name in rs_testkit::PAPER_DOMAINS {
        let path = rs_testkit::fixture_path(&format!("inrs-paper/{name}.json"));
        let domain = match rs_io::json::domain_from_json_file(&path) {
            Ok(d) => d,
            Err(e) => {
                eprintln!("{name}: {e}");
                std::process::exit(1);
            }
        };
        let only = value("--degree", 0);
        let degrees = if only == 0 {
            vec![5, 10, 20, 30]
        } else {
            vec![only]
        };
        for degree in degrees {
            let options = CubatureOptions::new(degree).with_candidates_per_polynomial(k);
            let mut best = f64::INFINITY;
            let mut last = None;
            for _ in 0..runs {
                let start = Instant::now();
                let rule = CubatureRule::with_options(&domain, options);
                best = best.min(start.elapsed().as_secs_f64());
                last = Some(rule);
            }
            match last {
                Some(Ok(rule)) => println!(
                    "{name:<25} {degree:>6} {:>6} {:>8} {:>11} {:>9.1e} {:>10.1}",
                    rule.nodes().len(),
                    dim_polynomials(degree),
                    rule.candidates(),
                    rule.residual(),
                    1e3 * best
                ),
                Some(Err(e)) => println!("{name:<25} {degree:>6} error: {e}"),
                None => {}
            }
        }
    }
}
