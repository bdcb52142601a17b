//! `inrs fractions`: the exact covered fraction of every cell of a uniform or rectilinear
//! grid, streamed band by band into `.npy` files (with centroids, face apertures, the
//! boundary's geometry and face centroids on request; revolved about an axis on request).
//! Several `--domain`s are several materials on the grid (the library's `MaterialCoverage`):
//! every file then has a leading axis, one slice per material.

mod bands;
mod grid;

use std::path::{Path, PathBuf};

use clap::{ArgGroup, Args, ValueEnum};
use inrs::Domain;
use inrs::contain::FillRule;
use inrs::coverage::{
    CellGrid, CoverageArray, CoverageError, CoverageOptions, MAX_EDGES, MaterialCoverage,
};
use inrs::spline::Axis;

use crate::args::{DomainArg, FillRuleArg};
use crate::cli::error::CliError;
use crate::cli::limits;

use grid::{GridSpec, parse_grid};
#[cfg(test)]
pub(crate) use grid::{MAX_CELLS_PER_AXIS, MAX_GRID_CELLS};

/// `--axisymmetric`: the coordinate axis the domain revolves about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum AxisArg {
    /// About the x axis: the radius is |y|.
    X,
    /// About the y axis: the radius is |x| (r-z coordinates with x = r, y = z).
    Y,
}

impl From<AxisArg> for Axis {
    fn from(a: AxisArg) -> Self {
        match a {
            AxisArg::X => Axis::X,
            AxisArg::Y => Axis::Y,
        }
    }
}

// The arguments of `inrs fractions`. Not a doc comment: clap would take it for the help, which is
// the doc of `Command::Fractions`.
#[derive(Args, Debug)]
#[command(after_help = limits::AFTER_HELP)]
#[command(group(ArgGroup::new("grid_form").required(true).args(["grid", "x_edges"])))]
pub(crate) struct FractionsArgs {
    /// The domain: a JSON domain file (docs/FORMATS.md), an .svg or .dxf file, a font
    /// glyph (`font.ttf#B`, `#U+0040`, `#gid:37`), or a face of a STEP/IGES part in its (u, v)
    /// (`part.step#face:3`; `inrs info part.step` lists the faces). Repeat it for several
    /// materials on one grid (material m is the m-th --domain, from 0): every file then has a
    /// leading axis, one slice per material; later domains replace earlier ones (see
    /// --no-replace).
    #[arg(long, required = true, value_name = "DOMAIN")]
    domain: Vec<PathBuf>,
    /// Closure tolerance, relative to the diagonal of the domain's bounding box: consecutive
    /// curves whose end and start are at most this far apart meet [default: 1e-9; for a CAD
    /// face the larger of it and the file's own tolerance]. For every --domain.
    #[arg(long, value_name = "REL")]
    closure_tol: Option<f64>,
    /// With several --domain: keep plain overlaps, each material's slice its domain's own
    /// coverage, instead of a later domain replacing the earlier ones where it lies. No effect
    /// with one --domain.
    #[arg(long)]
    no_replace: bool,
    /// A uniform grid: x0,x1,nx,y0,y1,ny (x0 < x1, y0 < y1 finite; nx, ny whole numbers >= 1;
    /// at most 2^32 cells). Negative bounds are fine: --grid -1,1,64,-1,1,64. Or --x-edges and
    /// --y-edges.
    #[arg(
        long,
        value_name = "X0,X1,NX,Y0,Y1,NY",
        value_parser = parse_grid,
        allow_hyphen_values = true
    )]
    grid: Option<GridSpec>,
    /// A rectilinear grid's column edges `x_0 < ... < x_nx`: a .npy file of a 1-D float64 array
    /// (numpy.save), at least 2 and at most 2^26 finite values; with --y-edges, instead of
    /// --grid.
    #[arg(long, value_name = "EDGES.npy", requires = "y_edges")]
    x_edges: Option<PathBuf>,
    /// The row edges `y_0 < ... < y_ny`, as --x-edges.
    #[arg(
        long,
        value_name = "EDGES.npy",
        requires = "x_edges",
        conflicts_with = "grid"
    )]
    y_edges: Option<PathBuf>,
    /// Also write `F.centroids.npy` (ny, nx, 2): the covered part's centroid, NaN where empty.
    #[arg(long)]
    centroids: bool,
    /// Also write `F.x_apertures.npy` (ny, nx + 1) and `F.y_apertures.npy` (ny + 1, nx): the
    /// covered fraction of each vertical and horizontal cell face.
    #[arg(long)]
    apertures: bool,
    /// Also write the boundary inside each cell: `F.boundary_lengths.npy` (ny, nx), its
    /// length, 0 where there is none; `F.boundary_centroids.npy` (ny, nx, 2), the [x, y]
    /// centroid of its length; `F.boundary_normals.npy` (ny, nx, 2), the unit vector along
    /// the integral of its normal (dy, -dx), out of the covered part; NaN where there is none.
    /// Planar only.
    #[arg(long)]
    boundary: bool,
    /// Also write `F.x_face_centroids.npy` (ny, nx + 1), the y of the centroid of each
    /// vertical face's covered part, and `F.y_face_centroids.npy` (ny + 1, nx), the x of each
    /// horizontal face's; NaN where the face is not covered. Planar only.
    #[arg(long)]
    face_centroids: bool,
    /// Revolve the domain about this coordinate axis: `y` (the radius is x: r-z coordinates)
    /// or `x` (the radius is y). F.npy then holds the covered fraction of each ring's volume
    /// (int int r dA over the ring's), --centroids the r-weighted centroids, --apertures the
    /// covered fractions of the cylinders and annuli the faces sweep. The domain and the grid
    /// must each lie on one side of the axis (touching it is fine).
    #[arg(long, value_enum, value_name = "AXIS")]
    axisymmetric: Option<AxisArg>,
    /// Which winding numbers are inside. Under either rule the loops must not cross each other
    /// or themselves (their fill is then decided by their nesting): a domain whose loops cross
    /// is refused, naming the crossing (`classify` takes any loops). One rule for every
    /// --domain.
    #[arg(long, value_enum, default_value_t = FillRuleArg::EvenOdd)]
    fill_rule: FillRuleArg,
    /// The fractions file `F.npy` (float64, shape (ny, nx), or (k, ny, nx) for k --domain);
    /// its name must end in .npy.
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

/// A rectilinear grid's edges from `path` (`--x-edges`, `--y-edges`: `flag`), at most the
/// library's [`MAX_EDGES`]; the library checks their values.
fn read_edges(flag: &str, path: &Path) -> Result<Vec<f64>, CliError> {
    inrs::io::points::read_npy_vector(path, MAX_EDGES)
        .map_err(|e| CliError::Message(format!("--{flag}: {e}")))
}

impl FractionsArgs {
    pub(crate) fn run(self) -> Result<(), CliError> {
        let grid = self.cell_grid()?;
        let domains = (0..self.domain.len())
            .map(|k| self.load(k))
            .collect::<Result<Vec<_>, _>>()?;
        let rule: FillRule = self.fill_rule.into();
        let materials: Vec<(&Domain, FillRule)> = domains.iter().map(|d| (d, rule)).collect();
        let cover = MaterialCoverage::new(&materials, grid.clone(), !self.no_replace)
            .map_err(|e| self.preparation_error(e))?;
        let options = self.options();
        // Refused options (an axis a domain or the grid crosses, planar-only outputs
        // revolved) before any file is created.
        cover
            .check_options(options)
            .map_err(|e| self.options_error(e))?;
        let leading = (self.domain.len() > 1).then_some(self.domain.len());
        bands::write_materials(&cover, options, &self.paths(options)?, leading, |k, e| {
            self.domain_error(k, e)
        })
    }

    /// The `k`-th `--domain`, read.
    fn load(&self, k: usize) -> Result<Domain, CliError> {
        let one = self.domain_arg(k);
        one.load().map_err(|e| match e {
            CliError::Message(m) if self.domain.len() > 1 => {
                // The reader's message names the file already: name it once, with the flag.
                let spec = format!("{}: ", one.domain.to_string_lossy());
                self.domain_error(k, m.strip_prefix(&spec).unwrap_or(&m))
            }
            other => other,
        })
    }

    /// The `k`-th `--domain` as the one-domain argument (its file and `--closure-tol`).
    fn domain_arg(&self, k: usize) -> DomainArg {
        DomainArg {
            domain: self.domain.get(k).cloned().unwrap_or_default(),
            closure_tol: self.closure_tol,
        }
    }

    /// An error about the `k`-th domain: `<file>: <e>` for one domain (as every command
    /// names it), `--domain <file> (material k): <e>` for several.
    fn domain_error(&self, k: usize, e: impl std::fmt::Display) -> CliError {
        let one = self.domain_arg(k);
        if self.domain.len() > 1 {
            CliError::Message(format!(
                "--domain {} (material {k}): {e}",
                one.domain.display()
            ))
        } else {
            one.error(e)
        }
    }

    /// The library's refusal to prepare the materials: naming the domain the library names
    /// (its own refusal, or a region that does not chain), else every domain (their
    /// boundaries together: too many pairs of pieces, an intersection not found).
    fn preparation_error(&self, e: CoverageError) -> CliError {
        match e {
            CoverageError::Material { material, source } => self.domain_error(material, source),
            e if self.domain.len() == 1 => self.domain_error(0, e),
            e => {
                let all: Vec<String> = self
                    .domain
                    .iter()
                    .map(|d| format!("--domain {}", d.display()))
                    .collect();
                CliError::Message(format!("{}: {e}", all.join(" ")))
            }
        }
    }

    /// The library's refusal of the options: `--axisymmetric <axis>: <e>`, with several
    /// domains naming the one the library names (a domain across the axis).
    fn options_error(&self, e: CoverageError) -> CliError {
        let flag = match self.axisymmetric {
            Some(AxisArg::X) => "--axisymmetric x",
            Some(AxisArg::Y) => "--axisymmetric y",
            None => "fractions",
        };
        match e {
            CoverageError::Material { material, source } if self.domain.len() > 1 => {
                self.domain_error(material, format!("{flag}: {source}"))
            }
            CoverageError::Material { source, .. } => {
                CliError::Message(format!("{flag}: {source}"))
            }
            e => CliError::Message(format!("{flag}: {e}")),
        }
    }

    /// The library's options for the flags.
    fn options(&self) -> CoverageOptions {
        CoverageOptions::DEFAULT
            .with_centroids(self.centroids)
            .with_apertures(self.apertures)
            .with_boundary(self.boundary)
            .with_face_centroids(self.face_centroids)
            .with_axisymmetric(self.axisymmetric.map(Axis::from))
    }

    /// The grid of `--grid`, or of `--x-edges` and `--y-edges` (clap requires one form),
    /// checked by the library, with at most [`MAX_GRID_CELLS`](grid::MAX_GRID_CELLS) cells.
    fn cell_grid(&self) -> Result<CellGrid, CliError> {
        let grid = match (&self.grid, &self.x_edges, &self.y_edges) {
            (Some(g), _, _) => g
                .cell_grid()
                .map_err(|e| CliError::Message(format!("--grid: {e}")))?,
            (None, Some(x), Some(y)) => {
                let (xs, ys) = (read_edges("x-edges", x)?, read_edges("y-edges", y)?);
                let grid = CellGrid::new(xs, ys)
                    .map_err(|e| CliError::Message(format!("--x-edges, --y-edges: {e}")))?;
                grid::check_cells(grid.nx(), grid.ny())
                    .map_err(|e| CliError::Message(format!("--x-edges, --y-edges: {e}")))?;
                grid
            }
            _ => {
                return Err(CliError::Message(
                    "give --grid, or --x-edges and --y-edges".into(),
                ));
            }
        };
        Ok(grid)
    }

    /// The fractions file and the extra files `options` compute, beside it.
    fn paths(&self, options: CoverageOptions) -> Result<bands::OutputPaths, CliError> {
        let out = &self.output;
        let stem = npy_stem(out)
            .ok_or_else(|| CliError::Message(format!("{}: not a file name", out.display())))?;
        Ok(bands::OutputPaths(
            CoverageArray::ALL
                .into_iter()
                .filter(|a| a.computed(options))
                .map(|a| {
                    // The fractions are `F.npy` itself, every other array `F.<name>.npy`.
                    let path = match a {
                        CoverageArray::Fractions => out.clone(),
                        a => beside(out, &stem, a.name()),
                    };
                    (a, path)
                })
                .collect(),
        ))
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
