//! The cut-cell figure of `cargo xtask demo`: what the coverage outputs give a cut-cell
//! (embedded-boundary) solver on a coarse grid. Two materials with replacement
//! (`MaterialCoverage`): the disc with an off-centre elliptic hole, and a disc over its rim
//! that replaces it where they overlap. Each cell is coloured by the materials' fractions; in
//! the first material's cut cells, the boundary's centroid (a dot), its unit outward normal
//! (an arrow from the dot) and the covered part's centroid (a cross). Written as SVG and,
//! where `rsvg-convert` is installed, as PNG.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use inrs::contain::{FillRule, even_odd_area};
use inrs::coverage::{CellGrid, Coverage, CoverageOptions, MaterialCoverage, material_domains};
use inrs::{Domain, Point};
use rs_figure::{Figure, Marker, Style};

/// Cells of the grid (x, then y).
pub(crate) const CELLS: [usize; 2] = [16, 12];

/// The grid's lower-left corner and cell side: off the circles' extreme points, so that no
/// boundary merely touches a grid line.
const ORIGIN: [f64; 2] = [-1.23, -1.17];
const SIDE: f64 = 0.2;

/// The second material: a disc of this centre and radius over the first one's rim.
const DISC: ([f64; 2], f64) = ([1.05, -0.35], 0.6);

/// Material colours at full fraction (a cell blends them with white by its fractions).
const COLOURS: [[u8; 3]; 2] = [[0x1f, 0x77, 0xb4], [0xff, 0x7f, 0x0e]];

/// Colours of the marks.
const BOUNDARY_MARK: &str = "#d62728";
const CENTROID_MARK: &str = "#000000";

/// The boundary centroid's circle radius in pixels.
const DOT: f64 = 2.6;

/// A normal arrow's length as a fraction of the cell side.
const ARROW: f64 = 0.5;

/// The two materials, the grid and each material's coverage (fractions, centroids and the
/// boundary's centroids and normals).
pub(crate) struct CutCells {
    pub(crate) domains: [Domain; 2],
    /// Each material's region (`material_domains`): the first disc minus the second, and the
    /// second as given.
    pub(crate) regions: Vec<Option<Domain>>,
    pub(crate) grid: CellGrid,
    pub(crate) coverage: Vec<Coverage>,
}

/// The materials, in order (the later replaces the earlier).
fn domains() -> Result<[Domain; 2], String> {
    let ([cx, cy], r) = DISC;
    let disc = Domain::new(vec![
        inrs::spline::circle(Point::new(cx, cy), r).map_err(|e| e.to_string())?,
    ])
    .map_err(|e| e.to_string())?;
    Ok([crate::disc_with_hole()?, disc])
}

/// Computes the figure's data.
pub(crate) fn cut_cells() -> Result<CutCells, String> {
    let domains = domains()?;
    let [nx, ny] = CELLS;
    let grid = CellGrid::uniform(
        ORIGIN[0],
        ORIGIN[0] + nx as f64 * SIDE,
        nx,
        ORIGIN[1],
        ORIGIN[1] + ny as f64 * SIDE,
        ny,
    )
    .map_err(|e| e.to_string())?;
    let given = [
        (&domains[0], FillRule::EvenOdd),
        (&domains[1], FillRule::EvenOdd),
    ];
    let m = MaterialCoverage::new(&given, grid.clone(), true).map_err(|e| e.to_string())?;
    let regions = material_domains(&given, true).map_err(|e| e.to_string())?;
    let options = CoverageOptions::DEFAULT
        .with_boundary(true)
        .with_centroids(true);
    let coverage = m.all(options).map_err(|e| e.to_string())?;
    Ok(CutCells {
        domains,
        regions,
        grid,
        coverage,
    })
}

impl CutCells {
    /// The cells (row-major indices) where material `k`'s boundary runs.
    pub(crate) fn cut(&self, k: usize) -> Vec<usize> {
        let lengths = self.coverage[k].boundary_lengths.as_deref().unwrap_or(&[]);
        (0..lengths.len()).filter(|&c| lengths[c] > 0.0).collect()
    }

    /// Material `k`'s area: the sum of fraction x cell area.
    pub(crate) fn area(&self, k: usize) -> f64 {
        let nx = self.grid.nx();
        self.coverage[k]
            .fractions
            .iter()
            .enumerate()
            .map(|(c, f)| f * self.grid.cell_area(c % nx, c / nx))
            .sum()
    }

    /// The largest relative difference between a material's area from its fractions and the
    /// even-odd area of its region.
    pub(crate) fn relative_area_difference(&self) -> Result<f64, String> {
        let mut worst: f64 = 0.0;
        for (k, r) in self.regions.iter().enumerate() {
            let exact = match r {
                Some(d) => even_odd_area(d).map_err(|e| e.to_string())?,
                None => 0.0,
            };
            worst = worst.max((self.area(k) - exact).abs() / exact.max(f64::MIN_POSITIVE));
        }
        Ok(worst)
    }
}

/// `#rrggbb` of white blended with the material colours by the fractions `f`.
fn blend(f: [f64; 2]) -> String {
    let mut rgb = [0u8; 3];
    for (ch, out) in rgb.iter_mut().enumerate() {
        let v = 255.0
            + f[0].clamp(0.0, 1.0) * (f64::from(COLOURS[0][ch]) - 255.0)
            + f[1].clamp(0.0, 1.0) * (f64::from(COLOURS[1][ch]) - 255.0);
        *out = v.round().clamp(0.0, 255.0) as u8;
    }
    format!("#{:02x}{:02x}{:02x}", rgb[0], rgb[1], rgb[2])
}

/// The SVG of an arrow from pixel `(x, y)` along the unit data vector `n` (y up), `len`
/// pixels long with a filled head.
fn arrow_svg(x: f64, y: f64, n: [f64; 2], len: f64) -> String {
    let (dx, dy) = (n[0], -n[1]);
    let (x1, y1) = (x + len * dx, y + len * dy);
    let head = 5.0_f64.min(0.45 * len);
    let (bx, by) = (x1 - head * dx, y1 - head * dy);
    let (px, py) = (-dy * 0.45 * head, dx * 0.45 * head);
    let mut s = String::new();
    let _ = write!(
        s,
        r##"<g class="normal"><line x1="{x:.2}" y1="{y:.2}" x2="{bx:.2}" y2="{by:.2}" stroke="{BOUNDARY_MARK}" stroke-width="1.3"/><polygon points="{x1:.2},{y1:.2} {:.2},{:.2} {:.2},{:.2}" fill="{BOUNDARY_MARK}"/></g>"##,
        bx + px,
        by + py,
        bx - px,
        by - py
    );
    s
}

/// The figure.
pub(crate) fn cut_cells_figure(c: &CutCells) -> Figure {
    let (nx, ny) = (c.grid.nx(), c.grid.ny());
    let mut fig = Figure::new(c.grid.bounding_box(), crate::figures::SIZE);
    let hex = |rgb: [u8; 3]| format!("#{:02x}{:02x}{:02x}", rgb[0], rgb[1], rgb[2]);
    let names = [
        "material 1: disc with a hole, minus material 2",
        "material 2: disc (replaces material 1)",
    ];
    for (k, name) in names.iter().enumerate() {
        fig.legend_entry(
            &Style::fill(&hex(COLOURS[k]))
                .with_fill(&hex(COLOURS[k]), 1.0)
                .labelled(name),
        );
    }
    let (xs, ys) = (c.grid.x_edges(), c.grid.y_edges());
    for j in 0..ny {
        for i in 0..nx {
            let cell = j * nx + i;
            let f = [c.coverage[0].fractions[cell], c.coverage[1].fractions[cell]];
            let b = inrs::BoundingBox::from_point(Point::new(xs[i], ys[j]))
                .including(Point::new(xs[i + 1], ys[j + 1]));
            fig.rect(b, &Style::stroke("#c8c8c8", 0.6).with_fill(&blend(f), 1.0));
        }
    }
    // Legend order: materials, boundaries, then the marks in the order the caption names them.
    let replaced = Style::stroke("#555555", 0.9)
        .dashed("3 3")
        .labelled("material 1's boundary as given (replaced in the disc)");
    let second = Style::stroke("#8c3c00", 1.4).labelled("material 2's boundary");
    let first = Style::stroke("#000000", 1.6).labelled("material 1's boundary after replacement");
    let dot = Style::stroke("#000000", 1.0)
        .with_fill("#ffffff", 1.0)
        .with_marker(Marker::Circle(DOT))
        .labelled("boundary centroid in material 1's cut cell");
    let normal = Style::stroke(BOUNDARY_MARK, 1.3).labelled("unit outward normal (arrow)");
    let cross = Style::fill(CENTROID_MARK)
        .with_marker(Marker::Cross(3.5))
        .labelled("centroid of material 1's covered part");
    for s in [&first, &second, &replaced, &dot, &normal, &cross] {
        fig.legend_entry(s);
    }
    for curve in c.domains[0].curves() {
        fig.curve(curve, &replaced);
    }
    for curve in c.domains[1].curves() {
        fig.curve(curve, &second);
    }
    for r in c.regions[0].iter() {
        for curve in r.curves() {
            fig.curve(curve, &first);
        }
    }
    let cut = c.cut(0);
    let cov = &c.coverage[0];
    let centroids = cov.boundary_centroids.as_deref().unwrap_or(&[]);
    let normals = cov.boundary_normals.as_deref().unwrap_or(&[]);
    let covered = cov.centroids.as_deref().unwrap_or(&[]);
    // Arrows first, then the boundary centroids on their tails, then the crosses on top (a
    // sliver's covered centroid can sit on its boundary centroid).
    let len = ARROW * SIDE * fig.scale();
    for &cell in &cut {
        let [bx, by] = centroids[cell];
        let n = normals[cell];
        let (x, y) = fig.to_pixels(Point::new(bx, by));
        if n.iter().all(|v| v.is_finite()) {
            fig.raw(&arrow_svg(x, y, n, len), Some(&normal));
        }
    }
    for &cell in &cut {
        let [bx, by] = centroids[cell];
        fig.mark(Point::new(bx, by), &dot);
    }
    for &cell in &cut {
        let [gx, gy] = covered[cell];
        if gx.is_finite() && gy.is_finite() {
            fig.mark(Point::new(gx, gy), &cross);
        }
    }
    fig.caption(&format!(
        "Cut cells of two materials on a {nx} x {ny} grid (inrs::coverage::MaterialCoverage \
         with replacement: a later shape replaces the earlier ones where they overlap): the \
         unit disc with an off-centre elliptic hole, then a disc of radius {} over its rim. Each \
         cell blends the materials' colours and white by their covered fractions. In material 1's {} \
         cut cells (CoverageOptions::DEFAULT.with_boundary(true).with_centroids(true)): the \
         boundary's centroid (white dot), its unit outward normal (arrow, {ARROW} cell long, \
         pointing out of the covered part: into the hole and into the disc that replaced it) \
         and the covered part's centroid (cross).",
        DISC.1,
        cut.len()
    ));
    fig
}

/// Writes `cut_cells.svg` (and `.png` if `rsvg-convert` is on the path) into `dir`; returns
/// the files written, the number of material 1's cut cells and the relative area difference.
pub(crate) fn write(dir: &Path) -> Result<(Vec<PathBuf>, usize, f64), String> {
    let c = cut_cells()?;
    let rel = c.relative_area_difference()?;
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let written = crate::figures::write_figure(&dir.join("cut_cells.svg"), &cut_cells_figure(&c))?;
    Ok((written, c.cut(0).len(), rel))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_cut_cell_has_its_marks_and_the_fractions_add_up_to_the_areas() {
        let c = cut_cells().unwrap();
        let rel = c.relative_area_difference().unwrap();
        assert!(rel < 1e-12, "relative area difference {rel}");
        // With replacement the fractions of a cell add up to at most 1.
        for (a, b) in c.coverage[0].fractions.iter().zip(&c.coverage[1].fractions) {
            assert!(a + b <= 1.0 + 1e-12, "{a} + {b}");
        }
        let cut = c.cut(0);
        assert!(cut.len() > 20, "{} cut cells", cut.len());
        let normals = c.coverage[0].boundary_normals.as_ref().unwrap();
        let covered = c.coverage[0].centroids.as_ref().unwrap();
        for &cell in &cut {
            let [x, y] = normals[cell];
            assert!(((x * x + y * y).sqrt() - 1.0).abs() < 1e-12, "cell {cell}");
            assert!(covered[cell].iter().all(|v| v.is_finite()), "cell {cell}");
        }
        let svg = cut_cells_figure(&c).to_svg();
        rs_testkit::assert_figure(&svg, "Cut cells of two materials", "cut cells");
        // One dot, one arrow and one cross per cut cell (and a dot and a cross in the legend).
        let dots = svg
            .matches(&format!(r##"r="{DOT:.2}" fill="#ffffff""##))
            .count();
        let arrows = svg.matches(r#"<g class="normal">"#).count();
        let crosses = svg
            .matches(&format!(
                r##"stroke="{CENTROID_MARK}" stroke-width="1.2"/>"##
            ))
            .count();
        assert_eq!(dots, cut.len() + 1, "dots");
        assert_eq!(arrows, cut.len());
        assert_eq!(crosses, cut.len() + 1, "crosses");
        for label in ["material 1", "material 2", "outward normal", "covered part"] {
            assert!(svg.contains(label), "{label}");
        }
    }
}
