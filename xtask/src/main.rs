//! `cargo xtask`: project automation (demo now; benchmarks and reports as they land).

use inrs::prelude::*;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use std::time::Instant;

use inrs::contain::baselines::halton_points;
use inrs::{Classifier, ContainOptions, Domain, DomainSummary, Location, Method, Point};
use rs_testkit::FixtureMeta;

mod architecture;
mod bench;
mod coverage_figure;
mod cubature_figure;
mod cut_cells_figure;
mod figures;
mod frontends;
#[cfg(test)]
mod imports;
mod solid_figure;
mod splines;

const HELP: &str = "\
cargo xtask <command>

Commands:
  demo [--fixtures DIR]   Load the built-in fixtures (default: fixtures/inrs-paper), classify
                          Halton points, check the inside counts and areas against the reference
                          data stored in the files, print a table and a summary of each domain,
                          and write SVG figures to target/figures/ (monotone boxes, refined
                          boxes, classified points, a winding-number field with a gap, curved
                          triangulations of S(4) and of a disc with an elliptic hole, the face of
                          fixtures/cad/plate.step in its (u, v), the exact covered fractions
                          of the butterfly on a 64 x 64 grid, the nodes of the positive
                          interior cubature rules of degree 10 and 20 on S3 and S5, the cut
                          cells of two materials with boundary centroids and normals).
  bench [OPTIONS]         The papers' comparisons in one process (medians of repeated runs):
                          Tables 1-2 (inRS1, inRS2, polygon within 1e-10), the fast paths and
                          GWN, evaluation histograms and linearisation errors of the GWN paper;
                          writes target/bench-report/bench.{md,csv}.
      --quick             N = 10^3, 10^4, 3 repetitions, smaller GWN point sets
      --domains A,B       fixture names, or `paper` (S3, S4, S5) or `all` (the default)
      --sizes N,M         numbers of Halton points (default 1000,10000,100000,1000000)
      --reps R            repetitions per timing (default 11)
      --sweep             also the box-refinement and grid-resolution sweeps
      --full              time inRS1 and the reference GWN at every size (default: up to 10^5)
      --only A,B          only these sections: paper, locator, gwn, shapes, build, cli,
                          coverage (exact cell coverage at 1024^2 and 4096^2 beside
                          exactextract; --quick: 64^2 and 256^2), cubature (positive
                          interior rules of degree 5-30 on S3, S4, S5 on one thread, and
                          their errors on smooth integrands beside QMC with 100x the points),
                          properties (mass properties of the Idf parts beside OCC), solid
                          (point in a solid on every solid of the Idf parts and the OCC test
                          parts beside OCC's BRepClass3d_SolidClassifier)
      --solid-points N    points per solid of the solid section (default 20000; --quick: 2000)
  splines [--quick]       The curved-triangulation paper's convergence experiments: the
                          quasi-interpolant of sin(10x) + sin(10y) in S_d^0 (d = 5, 6) on
                          three domains, ny = 5..65; writes target/bench-report/splines.{md,csv}.
  cad-figure --domain SPEC [--output F.svg] [--points N]
                          A CAD face (`part.step#face:K`) in its (u, v): its trimming loops and
                          N Halton points (default 3000) classified; default output
                          target/figures/cad_face.svg.
  help                    Show this help.
";

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default()
}

/// Writes the curved triangulation of `d` (well-spaced points with `ny` bands) as an SVG and
/// records a failure if its curved triangles do not add up to the domain's area.
fn mesh_figure(
    dir: &Path,
    stem: &str,
    d: &Domain,
    ny: usize,
    failures: &mut Vec<String>,
) -> Result<std::path::PathBuf, String> {
    let pts = inrs::mesh::well_spaced_points(d, ny).map_err(|e| format!("{stem}: {e}"))?;
    let m = inrs::mesh::CurvedTriangulation::new(d, &pts).map_err(|e| format!("{stem}: {e}"))?;
    let area: f64 = (0..m.triangles().len()).map(|t| m.triangle_area(t)).sum();
    let exact = d.signed_area().abs();
    if (area - exact).abs() > 1e-10 * exact {
        failures.push(format!(
            "{stem}: curved triangles cover {area}, domain area {exact}"
        ));
    }
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let path = dir.join(format!("{stem}_curved_triangulation.svg"));
    std::fs::write(&path, inrs::mesh::mesh_svg(&m, 700.0))
        .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}

/// The fixture files of `dir`, sorted.
fn domain_files(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(format!("no domain files in {}", dir.display()));
    }
    Ok(files)
}

/// Classifies the reference Halton point sets of one fixture, prints a table row for each and
/// records a failure for every count or area that differs from the reference.
fn check_fixture(
    stem: &str,
    meta: &FixtureMeta,
    classifier: &Classifier,
    failures: &mut Vec<String>,
) -> DomainSummary {
    let d = &meta.domain;
    let mut s = DomainSummary::of(d);
    // Our file name as the heading (the files' own names are the Matlab demo's case numbers).
    s.name = stem.to_string();
    if let Some(r) = meta.signed_area
        && (r - s.signed_area).abs() > 1e-12 * r.abs()
    {
        failures.push(format!(
            "{stem}: area {} differs from reference {r}",
            s.signed_area
        ));
    }
    let bbox = meta.reference_box.unwrap_or(d.bounding_box());
    let mut counts = meta.inside_counts.clone();
    if counts.is_empty() {
        counts.push((10_000, usize::MAX));
    }
    for (n, expected) in counts {
        let pts = halton_points(n, bbox);
        let start = Instant::now();
        let loc = classifier.locate_all_with(Method::InRS2, &pts);
        let elapsed = start.elapsed();
        let inside = loc.iter().filter(|&&l| l == Location::Inside).count();
        let boundary = loc.iter().filter(|&&l| l == Location::Boundary).count();
        let reference = if expected == usize::MAX {
            "-".to_string()
        } else {
            expected.to_string()
        };
        if expected != usize::MAX && inside != expected {
            failures.push(format!(
                "{stem}: N = {n}: {inside} inside, reference {expected}"
            ));
        }
        println!(
            "{:<24} {:>6} {:>6} {:>6} {:>18} {:>8} {:>9} {:>9} {:>9} {:>8.2}ms",
            stem,
            s.curves,
            s.bezier_pieces,
            classifier.boxes().boxes().len(),
            inrs::significant(s.signed_area),
            n,
            inside,
            boundary,
            reference,
            elapsed.as_secs_f64() * 1e3
        );
    }
    s
}

/// The disc with an off-centre elliptic hole of the curved-triangulation figure.
pub(crate) fn disc_with_hole() -> Result<Domain, String> {
    Domain::new(vec![
        inrs::spline::circle(Point::new(0.0, 0.0), 1.0).map_err(|e| e.to_string())?,
        inrs::spline::ellipse(Point::new(0.2, 0.1), 0.45, 0.25, 0.4)
            .map_err(|e| e.to_string())?
            .reversed(),
    ])
    .map_err(|e| e.to_string())
}

fn demo(dir: &Path) -> Result<(), String> {
    let files = domain_files(dir)?;
    println!(
        "{:<24} {:>6} {:>6} {:>6} {:>18} {:>8} {:>9} {:>9} {:>9} {:>10}",
        "domain",
        "curves",
        "pieces",
        "boxes",
        "signed area",
        "N",
        "inside",
        "boundary",
        "reference",
        "time"
    );
    let mut failures = Vec::new();
    let mut summaries = Vec::new();
    let figures_dir = workspace_root().join("target/figures");
    let mut figures_written = Vec::new();
    for path in &files {
        let stem = path
            .file_stem()
            .and_then(|x| x.to_str())
            .unwrap_or("?")
            .to_string();
        let meta = FixtureMeta::load(path)?;
        let d = &meta.domain;
        let classifier = Classifier::new(d, ContainOptions::default())
            .map_err(|e| format!("{}: {e}", path.display()))?;
        summaries.push(check_fixture(&stem, &meta, &classifier, &mut failures));
        let fig_pts = halton_points(1000, d.bounding_box());
        let fig_loc = classifier.locate_all_with(Method::Fast, &fig_pts);
        figures_written.extend(figures::domain_figures(
            &figures_dir,
            &stem,
            d,
            &fig_pts,
            &fig_loc,
        )?);
        if stem == "s4_disk_ellipse_segment" {
            figures_written.push(figures::gap_figure(
                &figures_dir,
                d,
                1,
                Point::new(0.2, -0.15),
            )?);
            figures_written.push(mesh_figure(&figures_dir, &stem, d, 12, &mut failures)?);
        }
    }
    println!(
        "\npieces: rational Bezier pieces of the NURBS; boxes: monotone boxes (each piece cut where \
         x' or y' vanishes, then into up to 32 sub-boxes); N: the first N Halton points of the \
         box; reference: the inside count stored in the fixture (the inRS paper's code, checked \
         against a dense polygon), '-' where none is stored; time: inRS2 on one thread.\n"
    );
    for s in &summaries {
        println!("{s}\n");
    }
    figures_written.push(mesh_figure(
        &figures_dir,
        "disc_with_hole",
        &disc_with_hole()?,
        14,
        &mut failures,
    )?);
    figures_written.push(cad_demo(&figures_dir, &mut failures)?);
    let (coverage_files, relative) = coverage_figure::write(&figures_dir, &workspace_root())?;
    println!(
        "covered fractions of the butterfly on a {n} x {n} grid: sum of fraction x cell area \
         within {relative:.1e} (relative) of the even-odd area",
        n = coverage_figure::CELLS
    );
    if relative > 1e-12 {
        failures.push(format!(
            "butterfly coverage: fractions add up to the area only within {relative:e}"
        ));
    }
    figures_written.extend(coverage_files);
    figures_written.extend(cubature_figure::write(&figures_dir, &workspace_root())?);
    let (cut_cells_files, cut, relative) = cut_cells_figure::write(&figures_dir)?;
    println!(
        "cut cells: {cut} cells of material 1 cut on a {nx} x {ny} grid; each material's \
         fractions add up to its area within {relative:.1e} (relative)",
        nx = cut_cells_figure::CELLS[0],
        ny = cut_cells_figure::CELLS[1]
    );
    if relative > 1e-12 {
        failures.push(format!(
            "cut cells: materials' fractions add up to their areas only within {relative:e}"
        ));
    }
    figures_written.extend(cut_cells_files);
    figures_written.extend(solid_figure::write(&figures_dir, &workspace_root())?);
    println!("figures written to {}:", figures_dir.display());
    for f in &figures_written {
        println!(
            "  {}",
            f.file_name().and_then(|n| n.to_str()).unwrap_or("?")
        );
    }
    if failures.is_empty() {
        println!("all inside counts and areas match the reference data");
        Ok(())
    } else {
        Err(failures.join("; "))
    }
}

/// The CAD part of the demo: the face of fixtures/cad/plate.step (a plate with a round hole
/// on a tilted plane) read from the STEP file, its `(u, v)` area checked against `100 - 4 pi`,
/// and its figure.
fn cad_demo(dir: &Path, failures: &mut Vec<String>) -> Result<PathBuf, String> {
    let spec = workspace_root().join("fixtures/cad/plate.step#face:0");
    let spec = spec.to_string_lossy();
    let d = inrs::io::load_domain(&spec).map_err(|e| format!("{spec}: {e}"))?;
    let area = 100.0 - 4.0 * std::f64::consts::PI;
    println!(
        "CAD face plate.step#face:0: {} loops, {} curves, (u, v) area {:.15} (100 - 4 pi = {area:.15})",
        d.loops().len(),
        d.curves().len(),
        d.signed_area()
    );
    if (d.signed_area() - area).abs() > 1e-12 * area {
        failures.push(format!(
            "plate.step: area {} instead of {area}",
            d.signed_area()
        ));
    }
    let pts = halton_points(2000, d.bounding_box());
    let loc = Classifier::new(&d, ContainOptions::default())
        .map_err(|e| format!("{spec}: {e}"))?
        .locate_all(&pts);
    let caption = format!(
        "plate.step, {}: a plate with a round hole on a tilted plane, in the plane's (u, v); \
         {} Halton points",
        d.name().unwrap_or_default(),
        pts.len()
    );
    let path = dir.join("cad_plate_face.svg");
    std::fs::write(
        &path,
        figures::cad_face_figure(&d, &pts, &loc, &caption).to_svg(),
    )
    .map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(path)
}

/// The value after `flag` in `args`, if the flag is there.
fn flag_value<'a>(args: &'a [String], flag: &str) -> Result<Option<&'a str>, String> {
    match args.iter().position(|a| a == flag) {
        Some(i) => args
            .get(i + 1)
            .map(|v| Some(v.as_str()))
            .ok_or_else(|| format!("{flag} needs a value")),
        None => Ok(None),
    }
}

/// `cargo xtask cad-figure`: a CAD face's trimming loops and classified points.
fn cad_figure(args: &[String]) -> Result<(), String> {
    let spec = flag_value(args, "--domain")?.ok_or("cad-figure needs --domain part.step#face:K")?;
    let output = flag_value(args, "--output")?.map_or_else(
        || workspace_root().join("target/figures/cad_face.svg"),
        PathBuf::from,
    );
    let n: usize = match flag_value(args, "--points")? {
        Some(v) => v
            .parse()
            .map_err(|_| format!("--points {v}: not a count"))?,
        None => 3000,
    };
    let d = inrs::io::load_domain(spec).map_err(|e| format!("{spec}: {e}"))?;
    let mut bb = d.bounding_box();
    let pad = Point::new(0.06 * bb.width(), 0.06 * bb.height());
    bb.min = bb.min - pad;
    bb.max = bb.max + pad;
    let pts = halton_points(n.min(200_000), bb);
    let loc = Classifier::new(&d, ContainOptions::default())
        .map_err(|e| format!("{spec}: {e}"))?
        .locate_all(&pts);
    let inside = loc.iter().filter(|l| **l == Location::Inside).count();
    let file = Path::new(spec.split('#').next().unwrap_or(spec))
        .file_name()
        .map_or_else(String::new, |f| f.to_string_lossy().into_owned());
    let max_degree = d.curves().iter().map(|c| c.degree()).max().unwrap_or(0);
    let caption = format!(
        "{file}, {} in its surface's parameters (u, v): {} trimming loop(s) of {} curves \
         (degree up to {max_degree}); {} Halton points classified, {inside} inside",
        d.name().unwrap_or_default(),
        d.loops().len(),
        d.curves().len(),
        pts.len()
    );
    let fig = figures::cad_face_figure(&d, &pts, &loc, &caption);
    if let Some(dir) = output.parent() {
        std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    }
    std::fs::write(&output, fig.to_svg()).map_err(|e| format!("{}: {e}", output.display()))?;
    println!("{}", output.display());
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("demo") => {
            let dir = match args.iter().position(|a| a == "--fixtures") {
                Some(i) => match args.get(i + 1) {
                    Some(d) => PathBuf::from(d),
                    None => {
                        eprintln!("xtask: --fixtures needs a directory");
                        return ExitCode::FAILURE;
                    }
                },
                None => workspace_root().join("fixtures/inrs-paper"),
            };
            demo(&dir)
        }
        Some("cad-figure") => cad_figure(&args[1..]),
        Some("splines") => splines::run(&workspace_root(), args.iter().any(|a| a == "--quick")),
        Some("bench") => {
            bench::BenchOptions::parse(&args[1..]).and_then(|o| bench::run(&workspace_root(), &o))
        }
        None | Some("help" | "--help" | "-h") => {
            print!("{HELP}");
            Ok(())
        }
        Some(other) => Err(format!("unknown command {other:?}\n\n{HELP}")),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("xtask: {e}");
            ExitCode::FAILURE
        }
    }
}
