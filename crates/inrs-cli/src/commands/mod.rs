//! One module per subcommand: its arguments (`#[derive(Args)]`) and its `run`; [`Command`], the
//! subcommands with their help.

use clap::Subcommand;

use crate::cli::error::CliError;

pub(crate) mod classify;
pub(crate) mod classify_many;
pub(crate) mod classify_solid;
pub(crate) mod convert;
pub(crate) mod convex_domain;
pub(crate) mod cubature;
pub(crate) mod eval;
pub(crate) mod fit;
pub(crate) mod fractions;
pub(crate) mod info;
pub(crate) mod integrate;
pub(crate) mod mesh;
pub(crate) mod properties;
pub(crate) mod sample;
pub(crate) mod winding;

/// The subcommands. Each one's help is its variant's doc (defined when the tool starts, for
/// `inrs --help`); its arguments are defined only when it is the one run (the whole tree took
/// 35 us to build warm, and cost 0.12 ms of `inrs --version` from a cold start).
#[derive(Subcommand)]
#[command(defer = true)]
pub(crate) enum Command {
    /// Inside, outside or boundary of a closed domain; writes CSV `x,y,location` in input order
    /// (with several domains, `x,y` and one column per domain). For a solid of a STEP or IGES part
    /// (`--domain part.step#solid:K`, or `part.step` for every solid), the points are `x,y,z`
    /// (CSV, or `.npy` of shape (N, 3)) and the output `x,y,z,location` (a column `solid:K` per
    /// solid for a whole file).
    Classify(classify::ClassifyArgs),
    /// Generalized winding number of every point; writes CSV `x,y,winding`.
    ///
    /// Any collection of curves is fine: open chains, gaps and overlaps. A point within the
    /// boundary tolerance of a curve (`--tol`; the points `classify` calls `boundary`) gets the
    /// average across the jump: 0 inside a straight piece, 1/2 on a smooth closed curve, the
    /// interior angle over 2 pi at a corner, from every algorithm.
    Winding(winding::WindingArgs),
    /// Convert a domain (SVG, DXF, font glyph, STEP/IGES face or JSON) to the JSON domain file format.
    Convert(convert::ConvertArgs),
    /// Sample points in a domain; writes CSV `x,y,kind` (kind `interior` or `boundary`).
    ///
    /// Well-spaced points (Schumaker-Yu Algorithm 11.1: horizontal lines h apart cut exactly with
    /// the boundary, interior points ~h apart, boundary points ~h apart by arc length) or the first
    /// --count Halton points inside.
    Sample(sample::SampleArgs),
    /// Curved triangulation of a domain; writes JSON (vertices, triangles, `curved_edges`).
    ///
    /// Well-spaced points (--ny), constrained Delaunay inscribed triangulation, boundary points
    /// inserted until it is convertible, boundary edges replaced by boundary arcs, optionally
    /// refined (--refine). A summary line
    /// goes to standard error.
    Mesh(mesh::MeshArgs),
    /// A spline approximating a formula on a domain, or interpolating scattered data; writes the
    /// spline file (JSON).
    ///
    /// With --function: the curved triangulation of Algorithm 11.1 with --ny lines (as `inrs mesh`
    /// builds it), optionally refined, and the quasi-interpolant Q f among continuous splines of
    /// degree d (Algorithm 6.1). With --data: the curved triangulation whose vertices are the data
    /// points, and a C1 spline of --space through the data (a two-stage method, or minimal
    /// energy). A summary line goes to standard error.
    Fit(fit::FitArgs),
    /// A spline's values at the points of a points file; writes CSV `x,y,value` in input order.
    ///
    /// Points on the boundary (within the boundary tolerance) evaluate like any other; points
    /// outside the domain get `nan`, and their number is reported on standard error.
    Eval(eval::EvalArgs),
    /// Where one control point may move keeping the sign of curvature (plane) or torsion (space).
    ///
    /// Prints, per refinement level, the number of inequalities, vertices (faces in space), area
    /// (volume) and absolute and relative error of the inner approximation, then the sampled
    /// outer bound.
    ConvexDomain(convex_domain::ConvexDomainArgs),
    /// Print a summary of a domain: curves, Bezier pieces, loops, orientation, the area it fills
    /// (--fill-rule; "-" with the reason where its loops' nesting does not decide it: open,
    /// coincident or crossing loops), size. For a
    /// STEP or IGES file without `#face:K`: its solids with their shells, then one line per face
    /// (index, entity, surface, loops, curves, (u, v) area and box, natural bounds, the bound of
    /// fitted pcurves, faces narrower than their closure tolerance, or why the face is refused);
    /// `part.step#solid:K`: that solid and its faces.
    Info(info::InfoArgs),
    /// Exact covered fraction of every cell of a grid, planar or revolved; writes float64 .npy arrays
    ///
    /// The closed loops are filled by the even-odd or the nonzero rule; the grid is uniform (--grid)
    /// or rectilinear (--x-edges, --y-edges).
    ///
    /// `F.npy` has shape (ny, nx): row j, column i is the cell `[x_i, x_i+1] x [y_j, y_j+1]`
    /// (y increases with the row), with `x_i = x0 + i (x1 - x0) / nx` for --grid, or the edges of
    /// --x-edges / --y-edges. Extra files beside it, `F.<name>.npy` (NaN where a value does not
    /// exist; shapes for one --domain):
    ///   --centroids       `centroids` (ny, nx, 2): [x, y] of each cell's covered part (NaN: empty)
    ///   --apertures       `x_apertures` (ny, nx + 1): covered fraction of each vertical face
    ///                     `x = x_i`; `y_apertures` (ny + 1, nx): of each horizontal face `y = y_j`
    ///   --boundary        `boundary_lengths` (ny, nx): length of the boundary in each cell (0: none);
    ///                     `boundary_centroids` (ny, nx, 2): its [x, y] centroid (NaN: none);
    ///                     `boundary_normals` (ny, nx, 2): unit integral of its normal, pointing out
    ///                     of the covered part (NaN: none, or an integral of 0)
    ///   --face-centroids  `x_face_centroids` (ny, nx + 1): y of the centroid of each vertical
    ///                     face's covered part; `y_face_centroids` (ny + 1, nx): x of each
    ///                     horizontal face's (NaN: not covered)
    /// With --axisymmetric a cell stands for the ring it sweeps about the axis: F holds the
    /// covered fraction of the ring's volume, the centroids are weighted by the radius, the
    /// apertures of faces across the axis are fractions of annuli (--boundary and
    /// --face-centroids are planar only).
    ///
    /// Several materials: give --domain k >= 2 times and every file gets a leading axis of k, one
    /// slice per domain in the order given (`F.npy` (k, ny, nx), `F.centroids.npy`
    /// (k, ny, nx, 2), ...). A later domain replaces the earlier ones where it lies (material m
    /// holds its domain minus the domains after it; a cell's fractions sum to at most 1); with
    /// --no-replace each slice is its domain's own coverage (overlaps counted in each), equal to a
    /// run with that domain alone. One --fill-rule and --closure-tol apply to every domain. Errors
    /// name the domain: `--domain b.json (material 1): ...`.
    ///
    /// The grid is computed in row bands on all cores and written as it goes (material after
    /// material): memory stays a few bands whatever the grid (at most 2^32 cells). The
    /// boundary must be closed (`inrs winding` handles open curves). Files appear only when the
    /// run succeeds. `docs/CLI.md` maps the files to embedded-boundary names (`volfrac`, `vcent`, ...).
    #[command(verbatim_doc_comment)]
    Fractions(fractions::FractionsArgs),
    /// A positive interior cubature rule of degree n (Sommariva and Vianello); writes CSV `x,y,w`.
    ///
    /// At most `(n + 1)(n + 2) / 2` nodes, every one strictly inside the domain (farther than the
    /// boundary tolerance from the boundary), every weight > 0, exact for every polynomial of total
    /// degree <= n up to the residual printed on standard error (with the nodes, the degree and the
    /// candidates tried): `sum_i w_i x_i^a y_i^b` is the integral of `x^a y^b` over the set the
    /// domain fills (--fill-rule) for `a + b <= n`. One node per line, floats in shortest
    /// round-trip form. The boundary must be closed, its loops must not cross.
    Cubature(cubature::CubatureArgs),
    /// The integral of a formula over a domain; prints it on standard output (shortest round-trip
    /// form).
    ///
    /// The sum `sum_i w_i f(x_i)` over the rule `inrs cubature --degree n` writes: exact (up to
    /// the residual printed on standard error) when f is a polynomial of degree <= n, and as close
    /// as f is to such a polynomial otherwise (for a smooth f the error falls fast with n). f is
    /// evaluated only at the nodes, all strictly inside the domain; a value there that is not
    /// finite (a division by zero, the square root of a negative number) is an error naming the
    /// node.
    Integrate(integrate::IntegrateArgs),
    /// Mass properties of a STEP or IGES part: each face's area and centroid; each solid's volume,
    /// boundary area, centroid, inertia tensor about the centroid (unit density) and principal
    /// moments and axes.
    ///
    /// `part.step` gives every face and every solid (a file without solids, such as an IGES file
    /// of trimmed surfaces, gives its faces), `part.step#face:K` face K, `part.step#solid:K` solid
    /// K. Lengths are in the file's length unit (areas its square, volumes its cube, moments of
    /// inertia its fifth power). Polynomial integrands (planes, polynomial B-spline surfaces) are
    /// exact to rounding; the others are integrated adaptively to their rounding noise, with the
    /// error estimate in the table's header. The table has 12 significant digits (a coordinate
    /// below 1e-12 of the part's size is written 0), the JSON every digit. A face or solid that cannot be computed (an open
    /// shell: its free edges are named) is a row with the reason, and the command still succeeds
    /// unless nothing could be computed; a bad selection is an error.
    Properties(properties::PropertiesArgs),
}

impl Command {
    /// Runs the subcommand.
    pub(crate) fn run(self) -> Result<(), CliError> {
        match self {
            Command::Classify(a) => a.run(),
            Command::Winding(a) => a.run(),
            Command::Convert(a) => a.run(),
            Command::Sample(a) => a.run(),
            Command::Mesh(a) => a.run(),
            Command::Fit(a) => a.run(),
            Command::Eval(a) => a.run(),
            Command::ConvexDomain(a) => a.run(),
            Command::Info(a) => a.run(),
            Command::Fractions(a) => a.run(),
            Command::Cubature(a) => a.run(),
            Command::Integrate(a) => a.run(),
            Command::Properties(a) => a.run(),
        }
    }
}
