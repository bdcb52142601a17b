//! `inrs fit`: a spline approximating a formula on a curved triangulation of a domain.

use std::path::PathBuf;
use std::time::Instant;

use clap::{Args, ValueEnum};
use inrs::mesh::{CurvedTriangulation, Refinement, well_spaced_points};
use inrs::trispline::{quasi_interpolate, spline_to_json};

use crate::args::DomainArg;
use crate::cli::error::CliError;
use crate::cli::limits::{parse_degree, parse_ny};
use crate::cli::output::Output;
use crate::function::Function;

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

/// A spline approximating a formula on a domain; writes the spline file (JSON).
///
/// The curved triangulation of Algorithm 11.1 with --ny lines (as `inrs mesh` builds it),
/// optionally refined, and the quasi-interpolant Q f among continuous splines of degree d
/// (Algorithm 6.1). A summary line
/// goes to standard error.
#[derive(Args, Debug)]
pub(crate) struct FitArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// Number of horizontal bands for the triangulation's points (2 to 100000).
    #[arg(long, default_value_t = 9, value_parser = parse_ny, allow_negative_numbers = true)]
    ny: usize,
    /// The polynomial degree d (1 to 12).
    #[arg(long, default_value_t = 5, value_parser = parse_degree, allow_negative_numbers = true)]
    degree: usize,
    /// The function: a formula in x and y with + - * / ^, parentheses, pi, e, and sin cos tan
    /// exp log sqrt abs.
    #[arg(long)]
    function: String,
    /// Refine the triangulation first.
    #[arg(long, value_enum, default_value_t = RefineArg::None)]
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
        let f = Function::parse(&self.function)?;
        let d = self.domain.load()?;
        let start = Instant::now();
        let in_domain = |e: inrs::mesh::MeshError| self.domain.error(e);
        let pts = well_spaced_points(&d, self.ny).map_err(in_domain)?;
        let mesh = match self.refine {
            RefineArg::None => CurvedTriangulation::new(&d, &pts),
            RefineArg::Ct => CurvedTriangulation::new_refined(&d, &pts, Refinement::CloughTocher),
            RefineArg::Ps => CurvedTriangulation::new_refined(&d, &pts, Refinement::PowellSabin),
        }
        .map_err(in_domain)?;
        let s =
            quasi_interpolate(mesh, self.degree, &|p| f.at(p)).map_err(|e| self.domain.error(e))?;
        let seconds = start.elapsed().as_secs_f64();
        let mut json = Output::create(self.output.as_deref())?;
        let mut figures = Vec::new();
        for (path, error) in [(&self.svg, false), (&self.error_svg, true)] {
            if let Some(p) = path {
                let mut out = Output::create(Some(p))?;
                let svg = if error {
                    inrs::trispline::error_svg(&s, &|p| f.at(p), &self.function, FIGURE_WIDTH)
                } else {
                    inrs::trispline::spline_svg(&s, &self.function, FIGURE_WIDTH)
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
}
