//! The point-in-solid figure of `cargo xtask demo`: the section y = 0 of
//! `fixtures/cad/revolved_bspline.step` (a cubic B-spline profile revolved about z between two
//! discs), a grid of points in it classified by `inrs::geom::solid::SolidClassifier`, and
//! points on the surface of revolution (which it must call boundary), written as SVG and, where
//! `rsvg-convert` is installed, as PNG.

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
    pub(crate) points: Vec<Point>,
    pub(crate) locations: Vec<Location>,
    pub(crate) surface: Vec<Point>,
    pub(crate) surface_locations: Vec<Location>,
    pub(crate) tolerance: f64,
    pub(crate) bounds: BoundingBox,
}

/// Classifies the section's points (the plane y = 0, in `(x, z)`).
pub(crate) fn section(root: &Path) -> Result<Section, String> {
    let path = root.join("fixtures/cad/revolved_bspline.step");
    let model = CadModel::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let solid = SolidClassifier::new(&model, 0).map_err(|e| format!("{}: {e}", path.display()))?;
    let (lo, hi) = solid.bounds();
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
    let space = |p: &Point| Point3::new(p.x, 0.0, p.y);
    let mut locations = vec![Location::Outside; points.len()];
    solid.par_values_into(
        &points.iter().map(space).collect::<Vec<_>>()[..],
        &mut locations,
    );
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
    solid.par_values_into(
        &surface.iter().map(space).collect::<Vec<_>>()[..],
        &mut surface_locations,
    );
    Ok(Section {
        points,
        locations,
        surface,
        surface_locations,
        tolerance: solid.tolerance(),
        bounds,
    })
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
    fig.caption(&format!(
        "Point in a solid: the section y = 0 of fixtures/cad/revolved_bspline.step (a cubic \
         B-spline profile revolved about the z axis, closed by discs at z = 0 and z = 3; read \
         from STEP). A {} x {} grid of points classified by inrs::geom::solid::SolidClassifier \
         (signed ray crossings with the trimmed faces, each crossing checked by the face's exact \
         2-D test): {} inside, {} outside; and {} points on the surface of revolution's two \
         meridians in this plane, all on the boundary (within T = {:.1e}).",
        GRID[0],
        GRID[1],
        count(Location::Inside),
        count(Location::Outside),
        s.surface.len(),
        s.tolerance
    ));
    fig
}

/// Writes `solid_section.svg` (and `.png` if `rsvg-convert` is on the path) into `dir`.
pub(crate) fn write(dir: &Path, root: &Path) -> Result<Vec<PathBuf>, String> {
    let s = section(root)?;
    if s.surface_locations.iter().any(|&l| l != Location::Boundary) {
        return Err("revolved_bspline.step: a point on the surface is not on the boundary".into());
    }
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    let svg = dir.join("solid_section.svg");
    std::fs::write(&svg, section_figure(&s).to_svg())
        .map_err(|e| format!("{}: {e}", svg.display()))?;
    let mut written = vec![svg.clone()];
    written.extend(crate::figures::png_beside(&svg));
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
