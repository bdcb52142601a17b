//! `inrs mesh`: a curved triangulation of a domain.

use std::path::PathBuf;

use clap::Args;
use inrs::mesh::{mesh_json, mesh_svg, well_spaced_points};

use crate::args::DomainArg;
use crate::cli::error::CliError;
use crate::cli::limits::parse_ny;
use crate::cli::output::Output;
use crate::commands::fit::RefineArg;

/// Plot-area width of the `--svg` figure, in pixels.
const FIGURE_WIDTH: f64 = 800.0;

// The arguments of `inrs mesh`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::Mesh`.
#[derive(Args, Debug)]
pub(crate) struct MeshArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// Number of horizontal bands for the sampling: h = height / ny (2 to 100000; at most
    /// 2 x 10^6 vertices).
    #[arg(long, default_value_t = 20, value_parser = parse_ny, allow_negative_numbers = true)]
    ny: usize,
    /// Refine the curved triangulation: Clough–Tocher (3 sub-triangles each) or Powell–Sabin
    /// (6), as `fit --refine` does.
    #[arg(long, value_enum, default_value_t = RefineArg::None)]
    refine: RefineArg,
    /// Write the JSON here instead of standard output.
    #[arg(long)]
    output: Option<PathBuf>,
    /// Also write an SVG figure of the curved triangulation.
    #[arg(long)]
    svg: Option<PathBuf>,
}

impl MeshArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let d = self.domain.load()?;
        let in_domain = |e: inrs::mesh::MeshError| self.domain.error(e);
        let pts = well_spaced_points(&d, self.ny).map_err(in_domain)?;
        let m = self.refine.triangulation(&d, &pts).map_err(in_domain)?;
        let area: f64 = (0..m.triangles().len()).map(|t| m.triangle_area(t)).sum();
        // Both outputs are written under temporary names and put in place together, so a
        // failure leaves neither.
        let mut json = Output::create(self.output.as_deref())?;
        let mut figure = self
            .svg
            .as_deref()
            .map(|p| Output::create(Some(p)))
            .transpose()?;
        json.write_str(&(mesh_json(&m) + "\n"))?;
        if let Some(f) = figure.as_mut() {
            f.write_str(&mesh_svg(&m, FIGURE_WIDTH))?;
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
}
