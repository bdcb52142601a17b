//! Times `CubatureRule::new` on fixtures: `time_rules DEGREE REPS FILE...`.
use std::time::Instant;

use rs_cubature::CubatureRule;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let degree: usize = args[1].parse().unwrap();
    let reps: usize = args[2].parse().unwrap();
    for path in &args[3..] {
        let d = rs_io::json::domain_from_json_file(std::path::Path::new(path)).unwrap();
        let mut times = Vec::new();
        let mut line = String::new();
        for _ in 0..reps {
            let t = Instant::now();
            let r = CubatureRule::new(&d, degree);
            times.push(t.elapsed().as_secs_f64());
            line = match r {
                Ok(r) => format!(
                    "nodes {} candidates {} residual {:.1e}",
                    r.nodes().len(),
                    r.candidates(),
                    r.residual()
                ),
                Err(e) => format!("error {e}"),
            };
        }
        times.sort_by(f64::total_cmp);
        println!(
            "{path} n={degree}: {line} median {:.1} ms",
            times[times.len() / 2] * 1e3
        );
    }
}
