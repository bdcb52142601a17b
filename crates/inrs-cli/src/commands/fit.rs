//! `inrs fit`: a spline approximating a formula on a curved triangulation of a domain, or a
//! `C^1` spline interpolating scattered data.

use std::path::PathBuf;
use std::time::Instant;

use clap::{Args, ValueEnum};
use inrs::mesh::{CurvedTriangulation, Refinement, WellSpacedPoints, well_spaced_points};
use inrs::trispline::{C1Space, Spline, TriSplineError, quasi_interpolate, spline_to_json};

use crate::args::{DomainArg, FUNCTION_HELP};
use crate::cli::error::CliError;
use crate::cli::limits::{parse_degree, parse_ny};
use crate::cli::output::Output;
use inrs::io::formula::Formula;

/// Plot-area width of the `--svg` figure, in pixels.
const FIGURE_WIDTH: f64 = 700.0;

/// Which triangulation the spline lives on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum RefineArg {
    /// The curved triangulation itself.
    None,
    /// Its Clough–Tocher refinement (3 sub-triangles each).
    Ct,
    /// Its Powell–Sabin refinement (6 sub-triangles each).
    Ps,
}

impl RefineArg {
    /// The curved triangulation of `pts`, refined as asked (`inrs fit --refine`, `inrs mesh
    /// --refine`).
    pub(crate) fn triangulation(
        self,
        d: &inrs::Domain,
        pts: &WellSpacedPoints,
    ) -> Result<CurvedTriangulation, inrs::mesh::MeshError> {
        match self {
            RefineArg::None => CurvedTriangulation::new(d, pts),
            RefineArg::Ct => CurvedTriangulation::new_refined(d, pts, Refinement::CloughTocher),
            RefineArg::Ps => CurvedTriangulation::new_refined(d, pts, Refinement::PowellSabin),
        }
    }
}

/// Which C1 space interpolates scattered data.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum SpaceArg {
    /// `S_5^{1,2}`: C1 quintic, C2 at the vertices (cubic local fits).
    S512,
    /// `S_3^1` on the Clough–Tocher refinement (cubic local fits).
    Ct,
    /// `S_2^1` on the Powell–Sabin refinement (quadratic local fits).
    Ps,
    /// `S_2^1` on the Powell–Sabin refinement with minimal energy.
    MinEnergy,
}

impl SpaceArg {
    fn space(self) -> C1Space {
        match self {
            SpaceArg::S512 => C1Space::SuperSpline,
            SpaceArg::Ct => C1Space::CloughTocher,
            SpaceArg::Ps => C1Space::PowellSabin,
            SpaceArg::MinEnergy => C1Space::MinimalEnergy,
        }
    }
}

/// The largest data file read by `--data` (about 30 bytes a row: up to the vertex limit).
const MAX_DATA_BYTES: u64 = 1 << 30;

// The arguments of `inrs fit`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::Fit`.
#[derive(Args, Debug)]
pub(crate) struct FitArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// Number of horizontal bands for the triangulation's points (2 to 100000; --function
    /// only: with --data the data points are the vertices).
    #[arg(long, default_value_t = 9, value_parser = parse_ny, allow_negative_numbers = true, conflicts_with = "data")]
    ny: usize,
    /// The polynomial degree d (1 to 12; --function only: --space sets the degree with --data).
    #[arg(long, default_value_t = 5, value_parser = parse_degree, allow_negative_numbers = true, conflicts_with = "data")]
    degree: usize,
    #[arg(
        long,
        help = FUNCTION_HELP,
        allow_hyphen_values = true,
        required_unless_present = "data",
        conflicts_with = "data"
    )]
    function: Option<String>,
    /// Scattered data to interpolate: a CSV file of `x,y,z` rows (extra columns ignored; blank
    /// lines and `#` comments skipped), or with a header line naming the columns `x`, `y` and
    /// `z` in any places (so `inrs sample` output with a `z` column appended works). Every point must lie in the domain
    /// (within 1e-9 of its size of the boundary counts as on it), no two the same.
    #[arg(long, requires = "space")]
    data: Option<PathBuf>,
    /// The C1 space for --data.
    #[arg(long, value_enum, requires = "data", conflicts_with = "function")]
    space: Option<SpaceArg>,
    /// Refine the triangulation first (--function only: the C1 spaces of --data choose
    /// their own refinement).
    #[arg(long, value_enum, default_value_t = RefineArg::None, conflicts_with = "data")]
    refine: RefineArg,
    /// Write the spline file here instead of standard output.
    #[arg(long)]
    output: Option<PathBuf>,
    /// Also write an SVG figure: the spline as a colour map over the curved triangulation.
    #[arg(long)]
    svg: Option<PathBuf>,
    /// Also write an SVG figure of the absolute error |s - f|.
    #[arg(long)]
    error_svg: Option<PathBuf>,
}

impl FitArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        if let (Some(data), Some(space)) = (&self.data, self.space) {
            return self.run_data(data, space.space());
        }
        let text = self.function.clone().unwrap_or_default();
        let f = Formula::parse(&text).map_err(|e| CliError::Message(e.to_string()))?;
        let d = self.domain.load()?;
        let start = Instant::now();
        let in_domain = |e: inrs::mesh::MeshError| self.domain.error(e);
        let pts = well_spaced_points(&d, self.ny).map_err(in_domain)?;
        let mesh = self.refine.triangulation(&d, &pts).map_err(in_domain)?;
        let s =
            quasi_interpolate(mesh, self.degree, &|p| f.at(p)).map_err(|e| self.domain.error(e))?;
        let seconds = start.elapsed().as_secs_f64();
        let mut json = Output::create(self.output.as_deref())?;
        let mut figures = Vec::new();
        for (path, error) in [(&self.svg, false), (&self.error_svg, true)] {
            if let Some(p) = path {
                let mut out = Output::create(Some(p))?;
                let svg = if error {
                    inrs::trispline::error_svg(&s, &|p| f.at(p), &text, FIGURE_WIDTH)
                } else {
                    inrs::trispline::spline_svg(&s, &format!("f = {text}"), FIGURE_WIDTH)
                }
                .map_err(|e| self.domain.error(e))?;
                out.write_str(&svg)?;
                figures.push(out);
            }
        }
        json.write_str(&(spline_to_json(&s) + "\n"))?;
        for f in figures {
            f.finish()?;
        }
        json.finish()?;
        eprintln!(
            "degree {}, {} curved triangles, {} coefficients (n_c, S_d^0), {} boundary points inserted, {seconds:.3} s",
            s.degree(),
            s.mesh().triangles().len(),
            s.dimension(),
            s.mesh().inserted_boundary_points(),
        );
        Ok(())
    }

    /// `--data`: the C1 interpolant of the data file's points.
    fn run_data(&self, path: &std::path::Path, space: C1Space) -> Result<(), CliError> {
        if self.error_svg.is_some() {
            return Err(CliError::Message(
                "--error-svg needs --function (the data give no function to compare with)".into(),
            ));
        }
        let d = self.domain.load()?;
        let (points, values, lines) = read_data(path)?;
        let start = Instant::now();
        let named = |e: TriSplineError| match e {
            TriSplineError::DataPoint {
                index,
                x,
                y,
                reason,
            } => CliError::Message(format!(
                "{}:{}: the point ({x}, {y}) {reason}",
                path.display(),
                lines[index]
            )),
            other => self.domain.error(other),
        };
        let fit =
            inrs::trispline::interpolate_scattered(&d, &points, &values, space).map_err(named)?;
        let seconds = start.elapsed().as_secs_f64();
        let s = &fit.spline;
        let mut json = Output::create(self.output.as_deref())?;
        let mut figure = None;
        if let Some(p) = &self.svg {
            let mut out = Output::create(Some(p))?;
            let title = format!("the data of {}", path.display());
            let svg = inrs::trispline::spline_svg(s, &title, FIGURE_WIDTH)
                .map_err(|e| self.domain.error(e))?;
            out.write_str(&svg)?;
            figure = Some(out);
        }
        json.write_str(&(spline_to_json(s) + "\n"))?;
        if let Some(f) = figure {
            f.finish()?;
        }
        json.finish()?;
        summarize(s, space, points.len(), &fit, seconds);
        if !fit.unused_points.is_empty() {
            let shown: Vec<String> = fit
                .unused_points
                .iter()
                .take(5)
                .map(|&i| format!("line {}", lines[i]))
                .collect();
            eprintln!(
                "warning: {} data points lie between a boundary arc and its chord, are not vertices and are not interpolated ({}{})",
                fit.unused_points.len(),
                shown.join(", "),
                if fit.unused_points.len() > 5 {
                    ", ..."
                } else {
                    ""
                }
            );
        }
        Ok(())
    }
}

/// The summary line of `--data` on standard error.
fn summarize(
    s: &Spline,
    space: C1Space,
    n: usize,
    fit: &inrs::trispline::ScatteredFit,
    seconds: f64,
) {
    eprintln!(
        "{} (degree {}), {n} data points, {} triangles, {} coefficients (n_c), {} vertices added (curve starts or for convertibility; values from the local fit), {seconds:.3} s",
        space.name(),
        s.degree(),
        s.mesh().triangles().len(),
        s.dimension(),
        fit.added_vertices,
    );
}

/// A data file's rows: points, values, and 1-based line numbers.
type DataRows = (Vec<inrs::Point>, Vec<f64>, Vec<usize>);

/// The rows of a data file.
fn read_data(path: &std::path::Path) -> Result<DataRows, CliError> {
    let show = path.display();
    let size = std::fs::metadata(path)
        .map_err(|e| CliError::Message(format!("{show}: {e}")))?
        .len();
    if size > MAX_DATA_BYTES {
        return Err(CliError::Message(format!(
            "{show}: {size} bytes exceed the limit {MAX_DATA_BYTES}"
        )));
    }
    let text =
        std::fs::read_to_string(path).map_err(|e| CliError::Message(format!("{show}: {e}")))?;
    let (mut points, mut values, mut lines) = (Vec::new(), Vec::new(), Vec::new());
    // Columns of x, y and z: the first three, or those a header line names so.
    let mut columns = [0usize, 1, 2];
    let mut first_row = true;
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if first_row {
            first_row = false;
            let named = |name: &str| fields.iter().position(|f| f.eq_ignore_ascii_case(name));
            if let (Some(x), Some(y), Some(z)) = (named("x"), named("y"), named("z")) {
                columns = [x, y, z];
                continue;
            }
            if fields.iter().all(|f| f.parse::<f64>().is_err()) {
                return Err(CliError::Message(format!(
                    "{show}:{}: a header must name the columns x, y and z, got {line:?}",
                    n + 1
                )));
            }
        }
        let number = |c: usize| fields.get(c).and_then(|f| f.parse::<f64>().ok());
        match (number(columns[0]), number(columns[1]), number(columns[2])) {
            (Some(x), Some(y), Some(z)) => {
                points.push(inrs::Point::new(x, y));
                values.push(z);
                lines.push(n + 1);
            }
            _ => {
                return Err(CliError::Message(format!(
                    "{show}:{}: expected numbers x, y, z in columns {}, {}, {}, got {line:?}",
                    n + 1,
                    columns[0] + 1,
                    columns[1] + 1,
                    columns[2] + 1
                )));
            }
        }
        if points.len() > inrs::trispline::MAX_DATA_POINTS {
            return Err(CliError::Message(format!(
                "{show}: more than {} data points",
                inrs::trispline::MAX_DATA_POINTS
            )));
        }
    }
    if points.is_empty() {
        return Err(CliError::Message(format!("{show}: no data rows")));
    }
    Ok((points, values, lines))
}
