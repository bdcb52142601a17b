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

/// An error measure of a row (max or RMS).
type Measure = fn(&Row) -> f64;

/// A convergence order between two rows in one measure.
type RateFn = fn(&Row, &Row, Measure) -> f64;

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

/// The convergence order between two rows in the mean triangle size `h = sqrt(|Omega| / n_t)`:
/// `ln(e_prev / e) / ln(h_prev / h)`, with `h_prev / h = sqrt(n_t / n_t,prev)`. The
/// triangulations for successive `ny` are not nested and their triangle counts do not grow like
/// `ny^2` (S3: 99 triangles at ny = 9, 278 at ny = 17, not 353), so `height / ny` misstates the
/// step; the mean size measures the mesh actually used.
fn rate(prev: &Row, row: &Row, e: Measure) -> f64 {
    (e(prev) / e(row)).ln() / (0.5 * (row.nt as f64 / prev.nt as f64).ln())
}

/// The order in `h = height / ny` (the paper's nominal step), reported beside [`rate`].
fn rate_in_ny(prev: &Row, row: &Row, e: Measure) -> f64 {
    (e(prev) / e(row)).ln() / (row.ny as f64 / prev.ny as f64).ln()
}

/// The order the issue asks of every RMS rate before rounding dominates: `d + 1/2`.
fn required_rate(degree: usize) -> f64 {
    degree as f64 + 0.5
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
    let mut short: Vec<String> = Vec::new();
    let mut md = format!(
        "### Quasi-interpolation in S_d^0 (curved-triangulation paper, Examples 6.1-6.3)\n\n\
         f = sin(10x) + sin(10y); triangulations of Algorithm 11.1 with the given ny; errors on \
         the well-spaced points of Algorithm 11.1 with ny = {check_ny}; rates are \
         ln(e_prev / e) / ln(h_prev / h), the order in the mean triangle size \
         h = sqrt(area / nt) (the last column: in the nominal step h = height / ny, which the \
         triangle counts do not follow because successive triangulations are not nested); \
         rows marked *rounding* have RMS errors below {ROUNDING:e} (rounding dominates there); \
         seconds: triangulation and quasi-interpolation.\n"
    );
    for (name, d) in &domains {
        let check = well_spaced_points(d, check_ny)
            .map_err(|e| e.to_string())?
            .all_points();
        for degree in [5usize, 6] {
            let _ = writeln!(
                md,
                "\n`{name}`, d = {degree} ({} check points)\n\n| ny | nt | nc | emax | rms | rate emax | rate rms | s | rate rms in ny |\n| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |",
                check.len()
            );
            let first = rows.len();
            for &ny in nys {
                let mut row = measure(d, degree, ny, &check)?;
                row.domain = name.to_string();
                let rates = (rows.len() > first).then(|| {
                    let prev = &rows[rows.len() - 1];
                    (
                        rate(prev, &row, |r| r.emax),
                        rate(prev, &row, |r| r.rms),
                        rate_in_ny(prev, &row, |r| r.rms),
                    )
                });
                if let Some((_, rms_rate, _)) = rates
                    && row.rms >= ROUNDING
                    && rms_rate < required_rate(degree)
                {
                    short.push(format!(
                        "{name} d = {degree} ny = {ny}: RMS rate {rms_rate:.2}"
                    ));
                }
                let fmt_rate = |r: Option<f64>| r.map_or("".into(), |r| format!("{r:.2}"));
                let _ = writeln!(
                    md,
                    "| {ny} | {} | {} | {:.2e} | {:.2e}{} | {} | {} | {:.2} | {} |",
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
                    row.seconds,
                    fmt_rate(rates.map(|r| r.2)),
                );
                println!(
                    "{name} d={degree} ny={ny}: nt {} nc {} emax {:.2e} rms {:.2e}",
                    row.nt, row.nc, row.emax, row.rms
                );
                rows.push(row);
            }
        }
    }
    let dir = root.join("target/bench-report");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("splines.md"), &md).map_err(|e| e.to_string())?;
    std::fs::write(dir.join("splines.csv"), csv(&rows)).map_err(|e| e.to_string())?;
    println!("{md}\nwritten: target/bench-report/splines.md, target/bench-report/splines.csv");
    if short.is_empty() {
        println!("every RMS rate before rounding is at least d + 1/2");
        Ok(())
    } else {
        Err(format!(
            "RMS rates below d + 1/2 (before rounding):\n  {}",
            short.join("\n  ")
        ))
    }
}

/// The CSV report: the columns, then the rate in the nominal step `height / ny`.
fn csv(rows: &[Row]) -> String {
    let mut csv = String::from(
        "table,space,degree,domain,ny,nt,nc,emax,rms,rate_emax,rate_rms,seconds,rate_rms_ny\n",
    );
    for (i, r) in rows.iter().enumerate() {
        let prev = (i > 0 && rows[i - 1].domain == r.domain && rows[i - 1].degree == r.degree)
            .then(|| &rows[i - 1]);
        let rate_of =
            |rate: RateFn, e: Measure| prev.map_or(String::new(), |p| format!("{}", rate(p, r, e)));
        let _ = writeln!(
            csv,
            "{},{},{},\"{}\",{},{},{},{},{},{},{},{},{}",
            r.table,
            r.space,
            r.degree,
            r.domain,
            r.ny,
            r.nt,
            r.nc,
            r.emax,
            r.rms,
            rate_of(rate, |r| r.emax),
            rate_of(rate, |r| r.rms),
            r.seconds,
            rate_of(rate_in_ny, |r| r.rms),
        );
    }
    csv
}
