//! The `inrs` command-line tool.

mod cli;

use inrs::contain::Locate;
use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use cli::limits::{
    parse_count, parse_free_index, parse_level, parse_ny, parse_subdivisions, parse_tolerance,
};
use cli::output::{Failure, Output, write_text};
use inrs::boxes::DEFAULT_SUBDIVISIONS;
use inrs::contain::DEFAULT_TOLERANCE;
use inrs::contain::baselines::WindingAlgorithm;
use inrs::contain::{FillRule, QueryStats, WindingField};
use inrs::{Classifier, ContainOptions, Domain, DomainSummary, Method, PointRecord};

/// Exact point containment for planar domains bounded by NURBS curves.
#[derive(Parser)]
#[command(
    name = "inrs",
    version,
    about = "Exact point containment for planar domains bounded by NURBS and rational Bezier curves",
    after_help = cli::limits::AFTER_HELP
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Classify points as inside, outside or boundary of a closed domain; writes CSV
    /// `x,y,location` in input order.
    #[command(after_help = cli::limits::AFTER_HELP)]
    Classify {
        /// The domain: a JSON file (CONTRACTS.md), an .svg or .dxf file, or a font glyph
        /// (`font.ttf#B`, `#U+0040`, `#gid:37`); every loop must close.
        #[arg(long)]
        domain: PathBuf,
        /// The points file: CSV `x,y` per line (extra columns ignored; optional header; `#`
        /// comments), streamed: any number of points.
        #[arg(long)]
        points: PathBuf,
        /// Algorithm: fast (the default: inRS2 for small batches, the parallel grid point
        /// locator for large ones), inrs1 (each point against each box), inrs2 (sorted points,
        /// binary search per box) or gwn (rounded generalized winding number; the only one that
        /// accepts open or overlapping boundaries). All agree on closed domains.
        #[arg(long, default_value = "fast", value_parser = parse_method)]
        method: Method,
        /// Fill rule of --method gwn: even-odd (default; agrees with the crossing methods) or
        /// nonzero.
        #[arg(long, default_value = "even-odd", value_parser = parse_fill_rule)]
        fill_rule: FillRule,
        /// Write the CSV here instead of standard output.
        #[arg(long)]
        output: Option<PathBuf>,
        /// Boundary tolerance relative to the bounding-box diagonal (>= 0, see below).
        #[arg(long, default_value = cli::limits::DEFAULT_TOL, value_parser = parse_tolerance, allow_negative_numbers = true)]
        tol: f64,
        /// Sub-boxes per monotone piece (the paper's box refinement), 1 to 4096; reduced
        /// automatically so that a domain has at most about 131072 boxes.
        #[arg(long, default_value_t = DEFAULT_SUBDIVISIONS, value_parser = parse_subdivisions, allow_negative_numbers = true)]
        subdivisions: usize,
    },
    /// Generalized winding number of every point with respect to the curves of a domain file
    /// (any collection: open chains, gaps and overlaps are fine); writes CSV `x,y,winding`.
    Winding {
        /// The domain: JSON, .svg, .dxf or `font.ttf#glyph` (see classify).
        #[arg(long)]
        domain: PathBuf,
        /// The points file: CSV `x,y` per line (extra columns ignored; optional header; `#`
        /// comments), streamed: any number of points.
        #[arg(long)]
        points: PathBuf,
        /// Write the CSV here instead of standard output.
        #[arg(long)]
        output: Option<PathBuf>,
        /// Per-curve algorithm: adaptive (the default, exact at any distance and at points on
        /// the curves), binary-search or bezier-clipping (ray-casting baselines).
        #[arg(long, default_value = "adaptive", value_parser = parse_algorithm)]
        algorithm: WindingAlgorithm,
    },
    /// Convert a domain (SVG, DXF, font glyph or JSON) to the JSON domain file format.
    Convert {
        /// The domain: JSON, .svg, .dxf or `font.ttf#glyph` (see classify).
        #[arg(long)]
        domain: PathBuf,
        /// Write the JSON here instead of standard output.
        #[arg(long)]
        output: Option<PathBuf>,
    },
    /// Sample points in a domain: well-spaced points (Schumaker-Yu Algorithm 11.1: horizontal
    /// lines h apart cut exactly with the boundary, interior points ~h apart, boundary points
    /// ~h apart by arc length) or the first --count Halton points inside. Writes CSV
    /// `x,y,kind` with kind `interior` or `boundary`.
    Sample {
        /// The domain: JSON, .svg, .dxf or `font.ttf#glyph` (see classify).
        #[arg(long)]
        domain: PathBuf,
        /// lines (Algorithm 11.1) or halton.
        #[arg(long, default_value = "lines")]
        method: String,
        /// Number of horizontal bands for --method lines: h = height / ny (2 to 100000; at most
        /// 10^7 points).
        #[arg(long, default_value_t = 20, value_parser = parse_ny, allow_negative_numbers = true)]
        ny: usize,
        /// Number of points for --method halton (1 to 10^7).
        #[arg(long, default_value_t = 1000, value_parser = parse_count, allow_negative_numbers = true)]
        count: usize,
        /// Write the CSV here instead of standard output.
        #[arg(long)]
        output: Option<PathBuf>,
    },
    /// Curved triangulation of a domain: well-spaced points (--ny), constrained Delaunay
    /// inscribed triangulation, boundary points inserted until it is convertible, boundary
    /// edges replaced by boundary arcs. Writes JSON (vertices, triangles, `curved_edges`) and a
    /// summary line on stderr.
    Mesh {
        /// The domain: JSON, .svg, .dxf or `font.ttf#glyph` (see classify).
        #[arg(long)]
        domain: PathBuf,
        /// Number of horizontal bands for the sampling: h = height / ny (2 to 100000; at most
        /// 2 x 10^6 vertices).
        #[arg(long, default_value_t = 20, value_parser = parse_ny, allow_negative_numbers = true)]
        ny: usize,
        /// Write the JSON here instead of standard output.
        #[arg(long)]
        output: Option<PathBuf>,
        /// Also write an SVG figure of the curved triangulation.
        #[arg(long)]
        svg: Option<PathBuf>,
    },
    /// Where may one control point of a curve move so that the curvature (planar curve) or
    /// torsion (space curve) keeps its sign? Prints, per refinement level, the number of
    /// inequalities, vertices (faces in space), area (volume) and absolute and relative error
    /// of the inner approximation, then the sampled outer bound.
    ConvexDomain {
        /// The curve: a JSON domain file (curve --curve-index is used) or one curve object
        /// `{"degree", "control_points", "knots"?, "weights"?}` with [x, y] or [x, y, z] points.
        #[arg(long)]
        curve: PathBuf,
        /// Which curve of a domain file.
        #[arg(long, default_value_t = 0, value_parser = parse_free_index, allow_negative_numbers = true)]
        curve_index: usize,
        /// Index of the free control point (0-based).
        #[arg(long, value_parser = parse_free_index, allow_negative_numbers = true)]
        free_index: usize,
        /// The box: xmin,xmax,ymin,ymax (plane) or xmin,xmax,ymin,ymax,zmin,zmax (space);
        /// |coordinates| <= 1e100. Write it as --box=-1,1,-1,1.
        #[arg(
            long = "box",
            required = true,
            allow_hyphen_values = true,
            value_delimiter = ','
        )]
        bbox: Vec<f64>,
        /// The sign to keep: positive, negative, or auto (the sign of the given curve at the
        /// middle of its first piece).
        #[arg(long, default_value = "auto")]
        sign: String,
        /// Stop when the relative area (volume) growth is at most this (>= 0).
        #[arg(long, default_value = cli::limits::DEFAULT_CONVEX_TOL, value_parser = parse_tolerance, allow_negative_numbers = true)]
        tol: f64,
        /// The last refinement level tried (0 to 20).
        #[arg(long, default_value_t = 10, value_parser = parse_level, allow_negative_numbers = true)]
        max_level: u32,
        /// Write an SVG of the nested polygons, the outer bound and the curve (plane only).
        #[arg(long)]
        svg: Option<PathBuf>,
    },
    /// Print a summary of a domain file: curves, Bezier pieces, loops, orientation, area, size.
    Info {
        /// The domain: JSON, .svg, .dxf or `font.ttf#glyph` (see classify).
        #[arg(long)]
        domain: PathBuf,
        /// Exit with an error if some loop does not close.
        #[arg(long)]
        require_closed: bool,
    },
}

#[allow(clippy::too_many_arguments)]
fn convex_domain(
    path: &std::path::Path,
    curve_index: usize,
    free: usize,
    bbox: &[f64],
    sign: &str,
    tol: f64,
    max_level: u32,
    svg: Option<PathBuf>,
) -> Result<(), Failure> {
    use inrs::convex::{BoundingBox3, ConvexDomainOptions, FreeCurve, Region, Sign};
    use std::fmt::Write as _;
    let in_file = |e: inrs::convex::ConvexError| format!("{}: {e}", path.display());
    let curve = inrs::convex::load_curve(path, curve_index).map_err(in_file)?;
    let bbox = BoundingBox3::from_ranges(bbox).map_err(|e| e.to_string())?;
    let h = curve.numerator(free).map_err(in_file)?;
    let sign = match sign {
        "positive" => Sign::Positive,
        "negative" => Sign::Negative,
        "auto" => {
            let d = curve.control_point(free).unwrap_or_default();
            if h.at(0, 0.5).eval(d) >= 0.0 {
                Sign::Positive
            } else {
                Sign::Negative
            }
        }
        other => {
            return Err(format!("--sign {other:?}: expected positive, negative or auto").into());
        }
    };
    let options = ConvexDomainOptions {
        sign,
        tolerance: tol,
        max_level,
        ..Default::default()
    };
    let k = inrs::convex::approximate(&h, &bbox, &options).map_err(|e| e.to_string())?;
    let space = curve.dimension() == 3;
    let (what, measure) = if space {
        ("faces", "volume")
    } else {
        ("vertices", "area")
    };
    let invariant = if space { "torsion" } else { "curvature" };
    let mut text = String::new();
    let _ = writeln!(
        text,
        "{invariant} sign {sign:?}, free control point {free}, numerator degree {} on {} piece(s)",
        h.degree(),
        h.piece_count()
    );
    let _ = writeln!(
        text,
        "level  inequalities  {what:>8}  {measure:>14}  {:>12}  {:>12}",
        "abs.error", "rel.error"
    );
    let opt = |v: Option<f64>| v.map_or("-".to_string(), |x| format!("{x:.5e}"));
    for l in &k.levels {
        let count = if space {
            l.region.face_count()
        } else {
            l.region.vertex_count()
        };
        let _ = writeln!(
            text,
            "{:>5}  {:>12}  {:>8}  {:>14.8e}  {:>12}  {:>12}",
            l.level,
            l.inequalities,
            count,
            l.region.measure(),
            opt(l.abs_error),
            opt(l.rel_error)
        );
    }
    let _ = writeln!(
        text,
        "outer bound ({} sampled parameters per piece): {measure} {:.8e}, {} {what}",
        ConvexDomainOptions::default().outer_samples,
        k.outer.measure(),
        if space {
            k.outer.face_count()
        } else {
            k.outer.vertex_count()
        }
    );
    let _ = writeln!(text, "outcome: {:?}", k.outcome);
    if let Some(out) = svg {
        let planar = match &curve {
            FreeCurve::Planar(c) => Some(c),
            FreeCurve::Space(_) => None,
        };
        let svg_text = match (&k.outer, planar) {
            (Region::Polygon(_), Some(c)) => inrs::convex::to_svg(&k, Some(c), free),
            _ => None,
        }
        .ok_or_else(|| "--svg draws planar domains only".to_string())?;
        write_text(Some(&out), &svg_text)?;
    }
    write_text(None, &text)
}

fn parse_method(s: &str) -> Result<Method, String> {
    s.parse()
}

fn parse_fill_rule(s: &str) -> Result<FillRule, String> {
    match s {
        "even-odd" | "evenodd" => Ok(FillRule::EvenOdd),
        "nonzero" | "non-zero" => Ok(FillRule::NonZero),
        other => Err(format!(
            "unknown fill rule {other:?} (expected even-odd or nonzero)"
        )),
    }
}

fn parse_algorithm(s: &str) -> Result<WindingAlgorithm, String> {
    match s {
        "adaptive" => Ok(WindingAlgorithm::Adaptive),
        "binary-search" => Ok(WindingAlgorithm::BinarySearch),
        "bezier-clipping" => Ok(WindingAlgorithm::BezierClipping),
        other => Err(format!(
            "unknown algorithm {other:?} (expected adaptive, binary-search or bezier-clipping)"
        )),
    }
}

/// Points per batch when streaming a points file: large enough for the parallel locator,
/// small enough that memory does not depend on the file's length.
const BATCH: usize = 1 << 16;

/// Streams the points file through `values` in batches and writes `x,y,value` rows (the
/// coordinates echoed as written) under `header`.
fn stream_points<T: std::fmt::Display>(
    points: &std::path::Path,
    output: Option<&std::path::Path>,
    header: &str,
    mut values: impl FnMut(&[inrs::Point]) -> Vec<T>,
) -> Result<(), Failure> {
    let in_file = |e: inrs::PointsError| match e {
        inrs::PointsError::Io { .. } => e.to_string(),
        other => format!("{}: {other}", points.display()),
    };
    let mut reader = inrs::open_points(points).map_err(in_file)?;
    let mut out = Output::create(output)?;
    writeln!(out, "{header}")?;
    let mut records: Vec<PointRecord> = Vec::with_capacity(BATCH);
    let mut pts = Vec::with_capacity(BATCH);
    loop {
        records.clear();
        for r in reader.by_ref().take(BATCH) {
            records.push(r.map_err(in_file)?);
        }
        if records.is_empty() {
            break;
        }
        pts.clear();
        pts.extend(records.iter().map(|r| r.point));
        for (r, v) in records.iter().zip(values(&pts)) {
            writeln!(out, "{},{},{}", r.x_text, r.y_text, v)?;
        }
        if records.len() < BATCH {
            break;
        }
    }
    out.finish()
}

/// Reads a domain: JSON, SVG, a font glyph `font.ttf#B`, or (feature `dxf`) DXF.
fn load_domain(path: &std::path::Path) -> Result<Domain, Failure> {
    let spec = path.to_string_lossy();
    inrs::io::load_domain(&spec).map_err(|e| {
        Failure::Message(match e {
            inrs::io::IoError::Read { .. }
            | inrs::io::IoError::UnknownFormat { .. }
            | inrs::io::IoError::FormatDisabled { .. } => e.to_string(),
            other => format!("{spec}: {other}"),
        })
    })
}

fn run(cli: Cli) -> Result<(), Failure> {
    match cli.command {
        Command::Classify {
            domain,
            points,
            method,
            fill_rule,
            output,
            tol,
            subdivisions,
        } => {
            let d = load_domain(&domain)?;
            let in_domain = |e: inrs::ContainError| format!("{}: {e}", domain.display());
            let output = output.as_deref();
            if method == Method::Gwn {
                let field = WindingField::new(&d, tol)
                    .map_err(in_domain)?
                    .with_fill_rule(fill_rule);
                return stream_points(&points, output, "x,y,location", |pts| field.locate_all(pts));
            }
            let options = ContainOptions::DEFAULT
                .with_tolerance(tol)
                .with_subdivisions(subdivisions);
            let classifier = Classifier::new(&d, options.with_method(method)).map_err(in_domain)?;
            // The fast method builds its grid once, on the first batch large enough to pay
            // for it, and the classifier keeps it for every later batch.
            stream_points(&points, output, "x,y,location", |pts| {
                classifier.locate_all(pts)
            })
        }
        Command::Winding {
            domain,
            points,
            output,
            algorithm,
        } => {
            let d = load_domain(&domain)?;
            let field = WindingField::new(&d, DEFAULT_TOLERANCE)
                .map_err(|e| format!("{}: {e}", domain.display()))?;
            let mut stats = QueryStats::default();
            stream_points(&points, output.as_deref(), "x,y,winding", |pts| {
                pts.iter()
                    .map(|&q| field.winding_number_with(q, algorithm, &mut stats))
                    .collect()
            })
        }
        Command::Sample {
            domain,
            method,
            ny,
            count,
            output,
        } => {
            let d = load_domain(&domain)?;
            let in_domain = |e: inrs::mesh::MeshError| format!("{}: {e}", domain.display());
            let mut out = Output::create(output.as_deref())?;
            writeln!(out, "x,y,kind")?;
            match method.as_str() {
                "lines" => {
                    let pts = inrs::mesh::well_spaced_points(&d, ny).map_err(in_domain)?;
                    for b in pts.boundary.iter().flatten() {
                        writeln!(out, "{:?},{:?},boundary", b.point.x, b.point.y)?;
                    }
                    for p in &pts.interior {
                        writeln!(out, "{:?},{:?},interior", p.x, p.y)?;
                    }
                }
                "halton" => {
                    for p in inrs::mesh::halton_points_in(&d, count).map_err(in_domain)? {
                        writeln!(out, "{:?},{:?},interior", p.x, p.y)?;
                    }
                }
                other => {
                    return Err(format!("--method {other:?}: expected lines or halton").into());
                }
            }
            out.finish()
        }
        Command::Mesh {
            domain,
            ny,
            output,
            svg,
        } => {
            let d = load_domain(&domain)?;
            let in_domain = |e: inrs::mesh::MeshError| format!("{}: {e}", domain.display());
            let pts = inrs::mesh::well_spaced_points(&d, ny).map_err(in_domain)?;
            let m = inrs::mesh::CurvedTriangulation::new(&d, &pts).map_err(in_domain)?;
            let area: f64 = (0..m.triangles().len()).map(|t| m.triangle_area(t)).sum();
            // Both outputs are written under temporary names and put in place together, so a
            // failure leaves neither.
            let mut json = Output::create(output.as_deref())?;
            let mut figure = svg
                .as_deref()
                .map(|p| Output::create(Some(p)))
                .transpose()?;
            json.write_str(&(inrs::mesh::mesh_json(&m) + "\n"))?;
            if let Some(f) = figure.as_mut() {
                f.write_str(&inrs::mesh::mesh_svg(&m, 800.0))?;
            }
            if let Some(f) = figure {
                f.finish()?;
            }
            json.finish()?;
            eprintln!(
                "{} vertices, {} curved triangles, {} boundary arcs, {} boundary points inserted for convertibility, total area {area:.15e}",
                m.vertices().len(),
                m.triangles().len(),
                m.arcs().len(),
                m.inserted_boundary_points()
            );
            Ok(())
        }
        Command::ConvexDomain {
            curve,
            curve_index,
            free_index,
            bbox,
            sign,
            tol,
            max_level,
            svg,
        } => convex_domain(
            &curve,
            curve_index,
            free_index,
            &bbox,
            &sign,
            tol,
            max_level,
            svg,
        ),
        Command::Convert { domain, output } => {
            let d = load_domain(&domain)?;
            write_text(
                output.as_deref(),
                &(inrs::io::json::domain_to_json(&d) + "\n"),
            )
        }
        Command::Info {
            domain,
            require_closed,
        } => {
            let d = load_domain(&domain)?;
            if require_closed {
                d.require_closed()
                    .map_err(|e| format!("{}: {e}", domain.display()))?;
            }
            write_text(None, &format!("{}\n", DomainSummary::of(&d)))
        }
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) if !e.use_stderr() => {
            // Help and version go to standard output; a closed pipe there is not an error.
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            // Usage errors: one line on standard error, clap's exit status 2.
            let text = e.render().to_string();
            let message: Vec<&str> = text
                .lines()
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            let message = message.join(" ");
            let message = message.strip_prefix("error: ").unwrap_or(&message);
            let _ = writeln!(std::io::stderr(), "inrs: {message} (see inrs --help)");
            return ExitCode::from(2);
        }
    };
    match run(cli) {
        Ok(()) | Err(Failure::ClosedPipe) => ExitCode::SUCCESS,
        Err(Failure::Message(e)) => {
            let _ = writeln!(std::io::stderr(), "inrs: {e}");
            ExitCode::FAILURE
        }
    }
}
