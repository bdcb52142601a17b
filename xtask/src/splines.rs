//! `cargo xtask splines`: the curved-triangulation paper's convergence experiments (its
//! Examples 6.1-6.3): the quasi-interpolant of `f = sin(10 x) + sin(10 y)` in `S_d^0` on
//! triangulations of Algorithm 11.1 with `ny = 5, 9, 17, 33, 65`, errors measured on the
//! well-spaced points of Algorithm 11.1 with `ny = 251`; written to
//! `target/bench-report/splines.{md,csv}`.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use inrs::mesh::{CurvedTriangulation, well_spaced_points};
use inrs::trispline::bb::Order;
use inrs::trispline::quasi_interpolate;
use inrs::{Domain, Point};

/// One row of the report.
struct Row {
    table: &'static str,
    space: &'static str,
    degree: usize,
    domain: String,
    ny: usize,
    nt: usize,
    nc: usize,
    emax: f64,
    rms: f64,
    seconds: f64,
}

/// Errors at or below this are rounding, not approximation (about `1000 eps` of `|f| <= 2`).
const ROUNDING: f64 = 5e-13;

fn f(p: Point) -> f64 {
    (10.0 * p.x).sin() + (10.0 * p.y).sin()
}

/// Max and RMS error of `Q f` of degree `d` on the triangulation with `ny` lines, measured at
/// `check`.
fn measure(d: &Domain, degree: usize, ny: usize, check: &[Point]) -> Result<Row, String> {
    let start = Instant::now();
    let pts = well_spaced_points(d, ny).map_err(|e| e.to_string())?;
    let mesh = CurvedTriangulation::new(d, &pts).map_err(|e| e.to_string())?;
    let s = quasi_interpolate(mesh, degree, &f).map_err(|e| e.to_string())?;
    let seconds = start.elapsed().as_secs_f64();
    let eval = s.evaluator().map_err(|e| e.to_string())?;
    let values = eval.evaluate_all(check, Order::Value);
    let (mut emax, mut sum, mut n) = (0.0f64, 0.0, 0usize);
    for (v, &p) in values.iter().zip(check) {
        let Some(v) = v else { continue };
        let e = (v.value - f(p)).abs();
        emax = emax.max(e);
        sum += e * e;
        n += 1;
    }
    Ok(Row {
        table: "6",
        space: "s0",
        degree,
        domain: String::new(),
        ny,
        nt: s.mesh().triangles().len(),
        nc: s.dimension(),
        emax,
        rms: (sum / n.max(1) as f64).sqrt(),
        seconds,
    })
}

/// `ln(e_prev / e) / ln(ny / ny_prev)`: the order in the mesh size `h = height / ny`.
fn rate(prev: &Row, row: &Row, e: impl Fn(&Row) -> f64) -> f64 {
    (e(prev) / e(row)).ln() / (row.ny as f64 / prev.ny as f64).ln()
}

pub(crate) fn run(root: &Path, quick: bool) -> Result<(), String> {
    let load = |name: &str| {
        inrs::io::json::domain_from_json_file(root.join(format!("fixtures/inrs-paper/{name}.json")))
            .map_err(|e| e.to_string())
    };
    let domains = [
        ("s4_disk_ellipse_segment", load("s4_disk_ellipse_segment")?),
        ("s3_m_shape (x-turning corners)", load("s3_m_shape")?),
        ("disc with an elliptic hole", crate::disc_with_hole()?),
    ];
    let nys: &[usize] = if quick {
        &[5, 9, 17]
    } else {
        &[5, 9, 17, 33, 65]
    };
    let check_ny = if quick { 101 } else { 251 };
    let mut rows: Vec<Row> = Vec::new();
    let mut md = format!(
        "### Quasi-interpolation in S_d^0 (curved-triangulation paper, Examples 6.1-6.3)\n\n\
         f = sin(10x) + sin(10y); triangulations of Algorithm 11.1 with the given ny; errors on \
         the well-spaced points of Algorithm 11.1 with ny = {check_ny}; rates are \
         ln(e_prev / e) / ln(ny / ny_prev), the order in h = height / ny; rows marked \
         *rounding* have RMS errors below {ROUNDING:e} (rounding dominates there); seconds: \
         triangulation and quasi-interpolation.\n"
    );
    for (name, d) in &domains {
        let check = well_spaced_points(d, check_ny)
            .map_err(|e| e.to_string())?
            .all_points();
        for degree in [5usize, 6] {
            let _ = writeln!(
                md,
                "\n`{name}`, d = {degree} ({} check points)\n\n| ny | nt | nc | emax | rms | rate emax | rate rms | s |\n| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
                check.len()
            );
            let first = rows.len();
            for &ny in nys {
                let mut row = measure(d, degree, ny, &check)?;
                row.domain = name.to_string();
                let rates = (rows.len() > first).then(|| {
                    let prev = &rows[rows.len() - 1];
                    (rate(prev, &row, |r| r.emax), rate(prev, &row, |r| r.rms))
                });
                let fmt_rate = |r: Option<f64>| r.map_or("".into(), |r| format!("{r:.2}"));
                let _ = writeln!(
                    md,
                    "| {ny} | {} | {} | {:.2e} | {:.2e}{} | {} | {} | {:.2} |",
                    row.nt,
                    row.nc,
                    row.emax,
                    row.rms,
                    if row.rms < ROUNDING {
                        " *rounding*"
                    } else {
                        ""
                    },
                    fmt_rate(rates.map(|r| r.0)),
                    fmt_rate(rates.map(|r| r.1)),
                    row.seconds
                );
                println!(
                    "{name} d={degree} ny={ny}: nt {} nc {} emax {:.2e} rms {:.2e}",
                    row.nt, row.nc, row.emax, row.rms
                );
                rows.push(row);
            }
        }
    }
    let mut csv =
        String::from("table,space,degree,domain,ny,nt,nc,emax,rms,rate_emax,rate_rms,seconds\n");
    for (i, r) in rows.iter().enumerate() {
        let prev = (i > 0 && rows[i - 1].domain == r.domain && rows[i - 1].degree == r.degree)
            .then(|| &rows[i - 1]);
        let rate_of =
            |e: fn(&Row) -> f64| prev.map_or(String::new(), |p| format!("{}", rate(p, r, e)));
        let _ = writeln!(
            csv,
            "{},{},{},\"{}\",{},{},{},{},{},{},{},{}",
            r.table,
            r.space,
            r.degree,
            r.domain,
            r.ny,
            r.nt,
            r.nc,
            r.emax,
            r.rms,
            rate_of(|r| r.emax),
            rate_of(|r| r.rms),
            r.seconds
        );
    }
    let dir = root.join("target/bench-report");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("splines.md"), &md).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("splines.csv"), &csv).map_err(|e| e.to_string())?;
    println!("{md}\nwritten: target/bench-report/splines.md, target/bench-report/splines.csv");
    Ok(())
}
