//! The `inrs` command-line tool.

use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use inrs::boxes::DEFAULT_SUBDIVISIONS;
use inrs::contain::DEFAULT_TOLERANCE;
use inrs::contain::{FillRule, QueryStats, WindingAlgorithm, WindingField};
use inrs::{Classifier, ContainOptions, Domain, DomainSummary, Method, PointRecord, read_points};

const TOLERANCE_HELP: &str = "\
Boundary tolerance: with T = tol x (diagonal of the domain's bounding box), a point is 'boundary'
when its vertical or horizontal distance to the boundary curve is at most T. Every point within
Euclidean distance T/sqrt(2) of the boundary is 'boundary', none farther than T is; all other
points are 'inside' or 'outside' exactly (up to floating-point rounding, far below T). Default
tol = 1e-12 (relative).";

/// Exact point containment for planar domains bounded by NURBS curves.
#[derive(Parser)]
#[command(name = "inrs", version, about, after_help = TOLERANCE_HELP)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Classify points as inside, outside or boundary of a closed domain; writes CSV
    /// `x,y,location` in input order.
    #[command(after_help = TOLERANCE_HELP)]
    Classify {
        /// The domain: a JSON file (CONTRACTS.md), an .svg or .dxf file, or a font glyph
        /// (`font.ttf#B`, `#U+0040`, `#gid:37`); every loop must close.
        #[arg(long)]
        domain: PathBuf,
        /// The points file (CSV `x,y` per line, optional header, `#` comments).
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
        /// Boundary tolerance relative to the bounding-box diagonal (see below).
        #[arg(long, default_value_t = DEFAULT_TOLERANCE, allow_negative_numbers = true)]
        tol: f64,
        /// Sub-boxes per monotone piece (the paper's box refinement).
        #[arg(long, default_value_t = DEFAULT_SUBDIVISIONS)]
        subdivisions: usize,
    },
    /// Generalized winding number of every point with respect to the curves of a domain file
    /// (any collection: open chains, gaps and overlaps are fine); writes CSV `x,y,winding`.
    Winding {
        /// The domain: JSON, .svg, .dxf or `font.ttf#glyph` (see classify).
        #[arg(long)]
        domain: PathBuf,
        /// The points file (CSV `x,y` per line, optional header, `#` comments).
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
        /// Number of horizontal bands for --method lines: h = height / ny.
        #[arg(long, default_value_t = 20)]
        ny: usize,
        /// Number of points for --method halton.
        #[arg(long, default_value_t = 1000)]
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
        /// Number of horizontal bands for the sampling: h = height / ny.
        #[arg(long, default_value_t = 20)]
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
        #[arg(long, default_value_t = 0)]
        curve_index: usize,
        /// Index of the free control point (0-based).
        #[arg(long)]
        free_index: usize,
        /// The box: xmin,xmax,ymin,ymax (plane) or xmin,xmax,ymin,ymax,zmin,zmax (space).
        #[arg(long = "box", allow_hyphen_values = true, value_delimiter = ',')]
        bbox: Vec<f64>,
        /// The sign to keep: positive, negative, or auto (the sign of the given curve at the
        /// middle of its first piece).
        #[arg(long, default_value = "auto")]
        sign: String,
        /// Stop when the relative area (volume) growth is at most this.
        #[arg(long, default_value_t = 1e-3)]
        tol: f64,
        /// The last refinement level tried.
        #[arg(long, default_value_t = 10)]
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

fn write_text(output: Option<&PathBuf>, text: &str) -> Result<(), String> {
    match output {
        Some(path) => std::fs::write(path, text).map_err(|e| format!("{}: {e}", path.display())),
        None => {
            let mut out = std::io::stdout().lock();
            out.write_all(text.as_bytes())
                .and_then(|()| out.flush())
                .map_err(|e| format!("standard output: {e}"))
        }
    }
}

/// The mesh as JSON: vertices, counter-clockwise triangles, and the curved edges (triangle,
/// edge k from vertex k to k+1, the domain curve and its parameter range from `from` to `to`).
fn mesh_json(m: &inrs::mesh::CurvedTriangulation) -> String {
    use inrs::mesh::EdgeKind;
    let vertices: Vec<[f64; 2]> = m.vertices().iter().map(|p| [p.x, p.y]).collect();
    let mut curved = Vec::new();
    for t in 0..m.triangles().len() {
        for (k, kind) in m.edge_kinds(t).iter().enumerate() {
            if let EdgeKind::Curved(i) = kind {
                let a = &m.arcs()[*i];
                curved.push(serde_json::json!({
                    "triangle": t, "edge": k, "curve": a.curve, "loop": a.loop_index,
                    "u0": a.u0, "u1": a.u1, "from": a.from, "to": a.to,
                }));
            }
        }
    }
    serde_json::json!({
        "vertices": vertices,
        "triangles": m.triangles(),
        "curved_edges": curved,
    })
    .to_string()
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
) -> Result<(), String> {
    use inrs::convex::{BoundingBox3, ConvexDomainOptions, FreeCurve, Region, Sign};
    let in_file = |e: inrs::convex::ConvexError| format!("{}: {e}", path.display());
    let curve = inrs::convex::load_curve(path, curve_index).map_err(in_file)?;
    let bbox = BoundingBox3::from_ranges(bbox).map_err(|e| e.to_string())?;
    let h = curve.numerator(free).map_err(in_file)?;
    let sign = match sign {
        "positive" => Sign::Positive,
        "negative" => Sign::Negative,
        "auto" => {
            let d = curve.control_point(free).unwrap_or([0.0; 3]);
            if h.at(0, 0.5).eval(d) >= 0.0 {
                Sign::Positive
            } else {
                Sign::Negative
            }
        }
        other => {
            return Err(format!(
                "--sign {other:?}: expected positive, negative or auto"
            ));
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
    println!(
        "{invariant} sign {sign:?}, free control point {free}, numerator degree {} on {} piece(s)",
        h.degree(),
        h.piece_count()
    );
    println!(
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
        println!(
            "{:>5}  {:>12}  {:>8}  {:>14.8e}  {:>12}  {:>12}",
            l.level,
            l.inequalities,
            count,
            l.region.measure(),
            opt(l.abs_error),
            opt(l.rel_error)
        );
    }
    println!(
        "outer bound ({} sampled parameters per piece): {measure} {:.8e}, {} {what}",
        ConvexDomainOptions::default().outer_samples,
        k.outer.measure(),
        if space {
            k.outer.face_count()
        } else {
            k.outer.vertex_count()
        }
    );
    println!("outcome: {:?}", k.outcome);
    if let Some(out) = svg {
        let planar = match &curve {
            FreeCurve::Planar(c) => Some(c),
            FreeCurve::Space(_) => None,
        };
        let text = match (&k.outer, planar) {
            (Region::Polygon(_), Some(c)) => inrs::convex::to_svg(&k, Some(c), free),
            _ => None,
        }
        .ok_or_else(|| "--svg draws planar domains only".to_string())?;
        std::fs::write(&out, text).map_err(|e| format!("{}: {e}", out.display()))?;
    }
    Ok(())
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

fn load_points(path: &PathBuf) -> Result<Vec<PointRecord>, String> {
    read_points(path).map_err(|e| match e {
        inrs::PointsError::Io { .. } => e.to_string(),
        other => format!("{}: {other}", path.display()),
    })
}

/// Writes a CSV with the given header and one `x,y,value` row per record.
fn write_csv<T: std::fmt::Display>(
    output: Option<&PathBuf>,
    header: &str,
    records: &[PointRecord],
    values: &[T],
) -> Result<(), String> {
    let sink: Box<dyn Write> = match output {
        Some(path) => {
            Box::new(std::fs::File::create(path).map_err(|e| format!("{}: {e}", path.display()))?)
        }
        None => Box::new(std::io::stdout().lock()),
    };
    let mut w = BufWriter::new(sink);
    let write_err = |e: std::io::Error| format!("writing output: {e}");
    writeln!(w, "{header}").map_err(write_err)?;
    for (r, v) in records.iter().zip(values) {
        writeln!(w, "{},{},{}", r.x_text, r.y_text, v).map_err(write_err)?;
    }
    w.flush().map_err(write_err)
}

/// Reads a domain: JSON, or (feature `io`) SVG, DXF or a font glyph `font.ttf#B`.
#[cfg(feature = "io")]
fn load_domain(path: &std::path::Path) -> Result<Domain, String> {
    let spec = path.to_string_lossy();
    inrs::io::load_domain(&spec).map_err(|e| match e {
        inrs::io::IoError::Read { .. }
        | inrs::io::IoError::Domain(inrs::DomainError::Io { .. })
        | inrs::io::IoError::UnknownFormat { .. } => e.to_string(),
        other => format!("{spec}: {other}"),
    })
}

/// Reads a JSON domain file.
#[cfg(not(feature = "io"))]
fn load_domain(path: &std::path::Path) -> Result<Domain, String> {
    Domain::from_json_file(path).map_err(|e| match e {
        inrs::DomainError::Io { .. } => e.to_string(),
        other => format!("{}: {other}", path.display()),
    })
}

fn run(cli: Cli) -> Result<(), String> {
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
            let locations = if method == Method::Gwn {
                let field = WindingField::new(&d, tol).map_err(in_domain)?;
                let records = load_points(&points)?;
                let pts: Vec<_> = records.iter().map(|r| r.point).collect();
                (records, field.classify(&pts, fill_rule))
            } else {
                let options = ContainOptions {
                    tolerance: tol,
                    subdivisions,
                };
                let classifier = Classifier::new(&d, options).map_err(in_domain)?;
                let records = load_points(&points)?;
                let pts: Vec<_> = records.iter().map(|r| r.point).collect();
                let loc = classifier.classify(&pts, method);
                (records, loc)
            };
            write_csv(output.as_ref(), "x,y,location", &locations.0, &locations.1)
        }
        Command::Winding {
            domain,
            points,
            output,
            algorithm,
        } => {
            let d = load_domain(&domain)?;
            let field = WindingField::new(&d, inrs::contain::DEFAULT_TOLERANCE)
                .map_err(|e| format!("{}: {e}", domain.display()))?;
            let records = load_points(&points)?;
            let mut stats = QueryStats::default();
            let values: Vec<f64> = records
                .iter()
                .map(|r| field.winding_number_with(r.point, algorithm, &mut stats))
                .collect();
            write_csv(output.as_ref(), "x,y,winding", &records, &values)
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
            let mut text = String::from("x,y,kind\n");
            match method.as_str() {
                "lines" => {
                    let pts = inrs::mesh::well_spaced_points(&d, ny).map_err(in_domain)?;
                    for b in pts.boundary.iter().flatten() {
                        text.push_str(&format!("{:?},{:?},boundary\n", b.point.x, b.point.y));
                    }
                    for p in &pts.interior {
                        text.push_str(&format!("{:?},{:?},interior\n", p.x, p.y));
                    }
                }
                "halton" => {
                    for p in inrs::mesh::halton_points_in(&d, count).map_err(in_domain)? {
                        text.push_str(&format!("{:?},{:?},interior\n", p.x, p.y));
                    }
                }
                other => return Err(format!("--method {other:?}: expected lines or halton")),
            }
            write_text(output.as_ref(), &text)
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
            eprintln!(
                "{} vertices, {} curved triangles, {} boundary arcs, {} boundary points inserted for convertibility, total area {area:.15e}",
                m.vertices().len(),
                m.triangles().len(),
                m.arcs().len(),
                m.inserted_boundary_points()
            );
            write_text(output.as_ref(), &(mesh_json(&m) + "\n"))?;
            if let Some(path) = svg {
                std::fs::write(&path, inrs::mesh::mesh_svg(&m, 800.0))
                    .map_err(|e| format!("{}: {e}", path.display()))?;
            }
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
            let json = d.to_json_string();
            match output {
                Some(path) => std::fs::write(&path, json + "\n")
                    .map_err(|e| format!("{}: {e}", path.display())),
                None => {
                    println!("{json}");
                    Ok(())
                }
            }
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
            println!("{}", DomainSummary::of(&d));
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("inrs: {e}");
            ExitCode::FAILURE
        }
    }
}
