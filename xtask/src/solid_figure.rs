//! The point-in-solid figures of `cargo xtask demo`: sections of two solids read from STEP, a
//! grid of points in each classified by `inrs::geom::solid::SolidClassifier`:
//! `fixtures/cad/revolved_bspline.step` (a cubic B-spline profile revolved about z between two
//! discs) at y = 0 with points on the surface of revolution (which it must call boundary), and
//! a real part, `FreeCAD`'s `CAP_50SGV_8_10.stp` (an electrolytic capacitor), through its middle.
//! Written as SVG and, where `rsvg-convert` is installed, as PNG.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

use inrs::geom::solid::{Location, PointQuery, SolidClassifier};
use inrs::geom::{ParamSurface, Point3};
use inrs::io::cad::CadModel;
use inrs::{BoundingBox, Point};
use rs_figure::{ChartAxis, Figure};

/// Grid points per axis of the section (x, then z).
const GRID: [usize; 2] = [96, 72];

/// Points on the surface of revolution per side of the axis.
const ON_SURFACE: usize = 60;

/// The section: the grid's points and locations, the surface points and theirs, the tolerance.
pub(crate) struct Section {
    pub(crate) file: String,
    pub(crate) y0: f64,
    pub(crate) faces: usize,
    pub(crate) points: Vec<Point>,
    pub(crate) locations: Vec<Location>,
    pub(crate) surface: Vec<Point>,
    pub(crate) surface_locations: Vec<Location>,
    pub(crate) tolerance: f64,
    pub(crate) bounds: BoundingBox,
}

/// Solid 0 of `rel` (relative to the workspace root) classified on a grid of the plane
/// `y = y0` (`None`: the middle of its box), in `(x, z)`: the model, its classifier and the
/// section.
fn grid_section(
    root: &Path,
    rel: &str,
    y0: Option<f64>,
) -> Result<(CadModel, SolidClassifier, Section), String> {
    let path = root.join(rel);
    let model = CadModel::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let solid = SolidClassifier::new(&model, 0).map_err(|e| format!("{}: {e}", path.display()))?;
    let (lo, hi) = solid.bounds();
    let y0 = y0.unwrap_or(0.5 * (lo.y + hi.y));
    let bounds = BoundingBox::from_points([Point::new(lo.x, lo.z), Point::new(hi.x, hi.z)])
        .ok_or("an empty solid")?;
    let [nx, nz] = GRID;
    let points: Vec<Point> = (0..nz)
        .flat_map(|j| {
            (0..nx).map(move |i| {
                Point::new(
                    lo.x + (i as f64 + 0.5) * (hi.x - lo.x) / nx as f64,
                    lo.z + (j as f64 + 0.5) * (hi.z - lo.z) / nz as f64,
                )
            })
        })
        .collect();
    let mut locations = vec![Location::Outside; points.len()];
    let space: Vec<Point3> = points.iter().map(|p| Point3::new(p.x, y0, p.y)).collect();
    solid.par_values_into(&space[..], &mut locations);
    let section = Section {
        file: rel.rsplit('/').next().unwrap_or(rel).to_string(),
        y0,
        faces: solid.faces().len(),
        points,
        locations,
        surface: Vec::new(),
        surface_locations: Vec::new(),
        tolerance: solid.tolerance(),
        bounds,
    };
    Ok((model, solid, section))
}

/// The section y = 0 of the revolved B-spline, with points on its surface of revolution.
pub(crate) fn section(root: &Path) -> Result<Section, String> {
    let (model, solid, mut section) =
        grid_section(root, "fixtures/cad/revolved_bspline.step", Some(0.0))?;
    // The surface of revolution's meridians at angles 0 and pi (the plane y = 0).
    let revolution = model
        .faces
        .iter()
        .find_map(|f| {
            f.surface
                .as_ref()
                .filter(|s| s.kind_name() == "surface of revolution")
        })
        .ok_or("no surface of revolution in revolved_bspline.step")?;
    let (v0, v1) = revolution.param_box().v;
    let surface: Vec<Point> = [0.0, PI]
        .iter()
        .flat_map(|&u| {
            (0..ON_SURFACE).map(move |k| {
                let v = v0 + (k as f64 + 0.5) / ON_SURFACE as f64 * (v1 - v0);
                let p = revolution.point([u, v]);
                Point::new(p.x, p.z)
            })
        })
        .collect();
    let mut surface_locations = vec![Location::Outside; surface.len()];
    let space: Vec<Point3> = surface.iter().map(|p| Point3::new(p.x, 0.0, p.y)).collect();
    solid.par_values_into(&space[..], &mut surface_locations);
    section.surface = surface;
    section.surface_locations = surface_locations;
    Ok(section)
}

/// The section through the middle of a real part, `FreeCAD`'s capacitor.
pub(crate) fn real_section(root: &Path) -> Result<Section, String> {
    Ok(grid_section(root, "fixtures/cad/freecad-idf/CAP_50SGV_8_10.stp", None)?.2)
}

/// The figure of a section.
pub(crate) fn section_figure(s: &Section) -> Figure {
    let size = crate::figures::SIZE;
    let aspect = s.bounds.height() / s.bounds.width();
    let mut fig = Figure::chart(
        s.bounds,
        size,
        aspect.clamp(0.4, 1.4) * size,
        ChartAxis::linear("x"),
        ChartAxis::linear("z"),
    );
    let all: Vec<Point> = s.points.iter().chain(&s.surface).copied().collect();
    let locations: Vec<Location> = s
        .locations
        .iter()
        .chain(&s.surface_locations)
        .copied()
        .collect();
    crate::figures::mark_locations(&mut fig, &all, &locations);
    let count = |l: Location| s.locations.iter().filter(|&&x| x == l).count();
    let surface = if s.surface.is_empty() {
        String::new()
    } else {
        format!(
            "; and {} points on the surface of revolution's two meridians in this plane, all on \
             the boundary",
            s.surface.len()
        )
    };
    fig.caption(&format!(
        "Point in a solid: the section y = {:.4} of {} ({} faces, read from STEP). A {} x {} grid \
         of points classified by inrs::geom::solid::SolidClassifier (signed ray crossings with \
         the trimmed faces, each crossing checked by the face's exact 2-D test): {} inside, {} \
         outside, {} on the boundary (within T = {:.1e}){surface}.",
        s.y0,
        s.file,
        s.faces,
        GRID[0],
        GRID[1],
        count(Location::Inside),
        count(Location::Outside),
        count(Location::Boundary),
        s.tolerance
    ));
    fig
}

/// Writes `solid_section.svg` (the revolved B-spline) and `solid_section_capacitor.svg` (the
/// real part), and `.png`s beside them if `rsvg-convert` is on the path, into `dir`.
pub(crate) fn write(dir: &Path, root: &Path) -> Result<Vec<PathBuf>, String> {
    let s = section(root)?;
    if s.surface_locations.iter().any(|&l| l != Location::Boundary) {
        return Err("revolved_bspline.step: a point on the surface is not on the boundary".into());
    }
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let mut written = Vec::new();
    for (name, s) in [
        ("solid_section.svg", s),
        ("solid_section_capacitor.svg", real_section(root)?),
    ] {
        written.extend(crate::figures::write_figure(
            &dir.join(name),
            &section_figure(&s),
        )?);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The profile's closed form: inside at the axis between the discs, outside beyond the
    /// bulge, every surface point on the boundary; the figure has its axes, legend and caption.
    #[test]
    fn the_section_is_classified_and_drawn() {
        let s = section(&crate::workspace_root()).unwrap();
        assert!(s.surface_locations.iter().all(|&l| l == Location::Boundary));
        for (p, l) in s.points.iter().zip(&s.locations) {
            // The discs bound z to [0, 3]; the profile's poles bound r to at most 2.5.
            if p.y < -1e-6 || p.y > 3.0 + 1e-6 || p.x.abs() > 2.5 {
                assert_eq!(*l, Location::Outside, "{p:?}");
            }
            if p.x.abs() < 0.9 && p.y > 1e-3 && p.y < 3.0 - 1e-3 {
                assert_eq!(*l, Location::Inside, "{p:?}");
            }
        }
        let svg = section_figure(&s).to_svg();
        rs_testkit::assert_figure(&svg, "Point in a solid", "solid section");
        assert!(
            svg.contains("inside") && svg.contains("outside") && svg.contains("on the boundary")
        );
    }
}
