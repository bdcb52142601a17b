//! The covered-fractions figure of `cargo xtask demo`: the exact fraction of every cell of a
//! 64 x 64 grid over the Axom butterfly's bounding box that the butterfly covers (issue 35),
//! as a colour map under the boundary curves, written as SVG and, where `rsvg-convert` is
//! installed, as PNG.

use std::path::{Path, PathBuf};

use inrs::Domain;
use inrs::contain::even_odd_area;
use inrs::coverage::{CellGrid, Coverage, CoverageOptions, cell_coverage};
use rs_figure::{FieldImage, Figure, Style};

/// Cells per axis of the figure's grid.
pub(crate) const CELLS: usize = 64;

/// The covered fractions of `d` on a `CELLS x CELLS` grid over its bounding box, and the
/// relative difference `|sum of fraction x cell area - even-odd area| / even-odd area`.
pub(crate) fn butterfly_fractions(d: &Domain) -> Result<(CellGrid, Coverage, f64), String> {
    let b = d.bounding_box();
    let grid = CellGrid::uniform(b.min.x, b.max.x, CELLS, b.min.y, b.max.y, CELLS)
        .map_err(|e| e.to_string())?;
    let c = cell_coverage(d, &grid, CoverageOptions::DEFAULT).map_err(|e| e.to_string())?;
    let area = even_odd_area(d).map_err(|e| e.to_string())?;
    let mut covered = 0.0;
    for j in 0..grid.ny() {
        for i in 0..grid.nx() {
            covered += c.fractions[j * grid.nx() + i] * grid.cell_area(i, j);
        }
    }
    Ok((grid, c, (covered - area).abs() / area))
}

/// Image pixels per cell side: each cell a block of `PIXELS x PIXELS` equal pixels, so that
/// renderers that smooth embedded images (librsvg ignores `image-rendering: pixelated`) still
/// show sharp cells.
const PIXELS: usize = 8;

/// The figure: each cell a square block of the image (the image's top rows are the top row
/// of cells, the last of the coverage's rows), viridis from 0 to 1, the boundary on top.
pub(crate) fn fractions_figure(
    d: &Domain,
    grid: &CellGrid,
    c: &Coverage,
    relative_difference: f64,
) -> Figure {
    let (nx, ny) = (grid.nx(), grid.ny());
    let values = (0..ny * PIXELS)
        .rev()
        .flat_map(|r| {
            let row = &c.fractions[(r / PIXELS) * nx..(r / PIXELS + 1) * nx];
            (0..nx * PIXELS).map(move |k| Some(row[k / PIXELS]))
        })
        .collect();
    let image = FieldImage {
        width: nx * PIXELS,
        height: ny * PIXELS,
        values,
    };
    let mut fig = Figure::new(grid.bounding_box(), 560.0);
    fig.field(&image, 0.0, 1.0, "covered fraction");
    let style = Style::stroke("#e8112d", 1.1).labelled("boundary (even-odd fill)");
    for curve in d.curves() {
        fig.curve(curve, &style);
    }
    fig.caption(&format!(
        "Exact covered fraction of each cell of a {nx} x {ny} grid over the bounding box of \
         the Axom butterfly (fixtures/axom-contours/butterfly.svg, {} curves in {} loops), from \
         inrs::coverage (Green's theorem on the NURBS boundary, no flattening). The sum of \
         fraction x cell area equals the even-odd area to a relative difference of {:.1e}.",
        d.curves().len(),
        d.loops().len(),
        relative_difference
    ));
    fig
}

/// Writes `coverage_fractions_butterfly.svg` (and `.png` if `rsvg-convert` is on the path)
/// into `dir`; returns the files written and the relative area difference.
pub(crate) fn write(dir: &Path, root: &Path) -> Result<(Vec<PathBuf>, f64), String> {
    let spec = root.join("fixtures/axom-contours/butterfly.svg");
    let spec = spec.to_string_lossy();
    let d = inrs::io::load_domain(&spec).map_err(|e| format!("{spec}: {e}"))?;
    let (grid, c, rel) = butterfly_fractions(&d)?;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let svg = dir.join("coverage_fractions_butterfly.svg");
    let written = crate::figures::write_figure(&svg, &fractions_figure(&d, &grid, &c, rel))?;
    Ok((written, rel))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_figure_shows_every_cell_and_the_fractions_add_up_to_the_area() {
        let root = crate::workspace_root();
        let spec = root.join("fixtures/axom-contours/butterfly.svg");
        let d = inrs::io::load_domain(&spec.to_string_lossy()).unwrap();
        let (grid, c, rel) = butterfly_fractions(&d).unwrap();
        assert_eq!(c.fractions.len(), CELLS * CELLS);
        assert!(rel < 1e-12, "relative area difference {rel}");
        // Some cells are full, some empty, some cut: the map shows all three.
        assert!(c.fractions.contains(&1.0) && c.fractions.contains(&0.0));
        assert!(c.fractions.iter().any(|&f| f > 0.0 && f < 1.0));
        let svg = fractions_figure(&d, &grid, &c, rel).to_svg();
        rs_testkit::assert_figure(&svg, "Exact covered fraction", "butterfly fractions");
        assert_eq!(svg.matches("<image").count(), 1);
        assert!(svg.contains("covered fraction") && svg.contains("equals the even-odd area"));
    }
}
