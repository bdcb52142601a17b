//! `inrs fractions`: the exact covered fraction of every cell of a uniform grid, streamed band
//! by band into `.npy` files (with centroids and face apertures on request).

mod bands;
mod grid;

use std::path::{Path, PathBuf};

use clap::Args;
use inrs::coverage::{CoverageOptions, GridCoverage};

use crate::args::{DomainArg, FillRuleArg};
use crate::cli::error::CliError;
use crate::cli::limits;

use grid::{GridSpec, parse_grid};
#[cfg(test)]
pub(crate) use grid::{MAX_CELLS_PER_AXIS, MAX_GRID_CELLS};

/// Exact covered fraction of every cell of a uniform grid (even-odd or nonzero fill of closed
/// loops); writes float64 `.npy` arrays.
///
/// `F.npy` has shape (ny, nx): row j, column i is the cell `[x_i, x_i+1] x [y_j, y_j+1]` with
/// `x_i = x0 + i (x1 - x0) / nx` and `y_j` likewise (y increases with the row). --centroids
/// adds `F.centroids.npy` (ny, nx, 2): the [x, y] centroid of each cell's covered part, NaN
/// where the cell is empty. --apertures adds `F.x_apertures.npy` (ny, nx + 1), the covered
/// fraction of each vertical face `x = x_i`, and `F.y_apertures.npy` (ny + 1, nx), of each
/// horizontal face `y = y_j`.
/// The grid is computed in row bands on all cores and written as it goes: memory stays a few
/// bands whatever the grid (at most 2^32 cells). The boundary must be closed (an open one is
/// an error: `inrs winding` handles open curves). Files appear only when the run succeeds.
#[derive(Args, Debug)]
#[command(after_help = limits::AFTER_HELP)]
pub(crate) struct FractionsArgs {
    #[command(flatten)]
    domain: DomainArg,
    /// The grid: x0,x1,nx,y0,y1,ny (x0 < x1, y0 < y1 finite; nx, ny whole numbers >= 1; at
    /// most 2^32 cells). Negative bounds are fine: --grid -1,1,64,-1,1,64.
    #[arg(
        long,
        value_name = "X0,X1,NX,Y0,Y1,NY",
        value_parser = parse_grid,
        allow_hyphen_values = true
    )]
    grid: GridSpec,
    /// Also write `F.centroids.npy` (ny, nx, 2): the covered part's centroid, NaN where empty.
    #[arg(long)]
    centroids: bool,
    /// Also write `F.x_apertures.npy` (ny, nx + 1) and `F.y_apertures.npy` (ny + 1, nx): the
    /// covered fraction of each vertical and horizontal cell face.
    #[arg(long)]
    apertures: bool,
    /// Which winding numbers are inside. Under either rule the loops must not cross each other
    /// or themselves (their fill is then decided by their nesting): a domain whose loops cross
    /// is refused, naming the crossing (`classify` takes any loops).
    #[arg(long, value_enum, default_value_t = FillRuleArg::EvenOdd)]
    fill_rule: FillRuleArg,
    /// The fractions file `F.npy` (float64, shape (ny, nx)); its name must end in .npy.
    #[arg(long, value_parser = parse_npy_path)]
    output: PathBuf,
}

/// `--output`: a name ending in `.npy` (any case).
fn parse_npy_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    let is_npy = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("npy"));
    if is_npy && npy_stem(&path).is_some() {
        Ok(path)
    } else {
        Err(format!("{s:?} must be a file name ending in .npy"))
    }
}

/// `F` of `dir/F.npy`.
fn npy_stem(path: &Path) -> Option<String> {
    let stem = path.file_stem()?.to_string_lossy().into_owned();
    (!stem.is_empty()).then_some(stem)
}

/// `dir/F.<what>.npy` beside `dir/F.npy`.
fn beside(path: &Path, stem: &str, what: &str) -> PathBuf {
    path.with_file_name(format!("{stem}.{what}.npy"))
}

impl FractionsArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let grid = self
            .grid
            .cell_grid()
            .map_err(|e| CliError::Message(format!("--grid: {e}")))?;
        let d = self.domain.load()?;
        let cover = GridCoverage::with_fill_rule(&d, grid, self.fill_rule.into())
            .map_err(|e| self.domain.error(e))?;
        let options = CoverageOptions::DEFAULT
            .with_centroids(self.centroids)
            .with_apertures(self.apertures);
        bands::write_coverage(&cover, options, &self.paths()?, |e| self.domain.error(e))
    }

    /// The fractions file and the extra files asked for.
    fn paths(&self) -> Result<bands::OutputPaths, CliError> {
        let out = &self.output;
        let stem = npy_stem(out)
            .ok_or_else(|| CliError::Message(format!("{}: not a file name", out.display())))?;
        let extra = |on: bool, what: &str| on.then(|| beside(out, &stem, what));
        Ok(bands::OutputPaths {
            fractions: out.clone(),
            centroids: extra(self.centroids, "centroids"),
            x_apertures: extra(self.apertures, "x_apertures"),
            y_apertures: extra(self.apertures, "y_apertures"),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_end_in_npy_and_the_extras_sit_beside_them() {
        assert!(parse_npy_path("out/f.NPY").is_ok());
        assert_eq!(
            parse_npy_path("f.csv").unwrap_err(),
            "\"f.csv\" must be a file name ending in .npy"
        );
        assert!(parse_npy_path(".npy").is_err());
        assert!(parse_npy_path("dir/").is_err());
        let p = Path::new("out/disc.npy");
        assert_eq!(
            beside(p, &npy_stem(p).unwrap(), "centroids"),
            Path::new("out/disc.centroids.npy")
        );
    }
}
