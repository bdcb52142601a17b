//! Cut cells for solvers (issue 51): what revolved cells, the embedded boundary and face
//! centroids cost beside plain fractions, and several materials with replacement beside one
//! run per domain, on the same grids in the same run (interleaved rounds, so the ratios hold
//! on a noisy machine).

use std::fmt::Write as _;
use std::path::Path;

use inrs::contain::FillRule;
use inrs::coverage::{CellGrid, CoverageOptions, GridCoverage, MaterialCoverage};
use inrs::spline::{Affine, Axis};
use inrs::{Domain, Point};

use super::{BenchOptions, interleaved_times};

/// `d` moved by `(dx, dy)`.
fn translated(d: &Domain, dx: f64, dy: f64) -> Result<Domain, String> {
    let shift = Affine::translate(dx, dy);
    let curves = d
        .curves()
        .iter()
        .map(|c| shift.apply_to_curve(c))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| e.to_string())?;
    Domain::new(curves).map_err(|e| e.to_string())
}

/// `d` moved right so that its bounding box starts at `x = 0.25` of its width: a profile
/// revolved about the y axis.
fn right_of_the_axis(d: &Domain) -> Result<Domain, String> {
    let b = d.bounding_box();
    translated(d, 0.25 * b.width() - b.min.x, 0.0)
}

/// The square grid of `n x n` cells over `d`'s bounding box grown by 1% of its diagonal.
fn grid_over(d: &Domain, n: usize) -> Result<CellGrid, String> {
    let b = d.bounding_box();
    let b = b.grown_by(0.01 * b.diagonal());
    CellGrid::uniform(b.min.x, b.max.x, n, b.min.y, b.max.y, n).map_err(|e| e.to_string())
}

/// The section: revolved and embedded-boundary outputs against plain fractions, then
/// materials against one run per domain.
pub(super) fn section(md: &mut String, root: &Path, o: &BenchOptions) -> Result<(), String> {
    let sizes: &[usize] = if o.quick { &[256] } else { &[1024, 4096] };
    let reps = o.reps.clamp(3, 7);
    let disc = Domain::new(vec![
        inrs::spline::circle(Point::new(0.0, 0.0), 1.0).map_err(|e| e.to_string())?,
    ])
    .map_err(|e| e.to_string())?;
    let butterfly = root.join("fixtures/axom-contours/butterfly.svg");
    let butterfly = butterfly.to_string_lossy();
    let butterfly = inrs::io::load_domain(&butterfly).map_err(|e| format!("{butterfly}: {e}"))?;
    let domains = [
        ("unit disc", right_of_the_axis(&disc)?),
        ("butterfly", right_of_the_axis(&butterfly)?),
    ];
    let _ = writeln!(
        md,
        "\nCut cells (`GridCoverage::all`, all {} threads), each domain moved right of the y \
         axis, on square grids over its bounding box grown by 1% of its diagonal: milliseconds \
         for plain fractions, and each output's time over theirs in the same interleaved \
         rounds (medians of {reps}): *RZ* revolved about the y axis (`--axisymmetric y`: volume \
         fractions), *RZ + centroids* (second moments), *boundary* (`--boundary`: length, \
         centroid and normal per cell), *faces* (`--apertures --face-centroids`). *Output \
         floor*: plain fractions plus what filling the boundary's arrays alone takes (the same \
         call on the same grid with the domain moved off it: 40 bytes a cell, centroids and \
         normals `NaN`), and *boundary over floor*: the boundary's time over that floor, what \
         its computation adds beyond writing its output. *Streamed*: the same outputs band by \
         band as `inrs fractions` computes them (`GridCoverage::bands`, each band dropped \
         when taken: the arrays of a band reused from the allocator, no file written), the \
         boundary and RZ over streamed fractions.\n",
        rayon::current_num_threads(),
    );
    let _ = writeln!(
        md,
        "| domain | cells | fractions ms | RZ | RZ + centroids | boundary | apertures + face centroids | output floor ms | boundary over floor | streamed fractions ms | streamed boundary | streamed RZ |"
    );
    let _ = writeln!(
        md,
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    );
    let plain = CoverageOptions::DEFAULT;
    let rz = plain.with_axisymmetric(Some(Axis::Y));
    let options = [
        plain,
        rz,
        rz.with_centroids(true),
        plain.with_boundary(true),
        plain.with_apertures(true).with_face_centroids(true),
    ];
    for (name, d) in &domains {
        for &n in sizes {
            let grid = grid_over(d, n)?;
            let cover = GridCoverage::new(d, grid.clone()).map_err(|e| e.to_string())?;
            // The same grid with the domain moved off it: the outputs' allocation and fill.
            let moved = translated(d, 0.0, 3.0 * d.bounding_box().height())?;
            let away = GridCoverage::new(&moved, grid).map_err(|e| e.to_string())?;
            let mut runs: Vec<Box<dyn FnMut() + '_>> = options
                .iter()
                .map(|opt| (opt, &cover))
                .chain([(&options[3], &away), (&options[0], &away)])
                .map(|(&opt, cover)| {
                    Box::new(move || {
                        std::hint::black_box(cover.all(opt).ok());
                    }) as Box<dyn FnMut() + '_>
                })
                .collect();
            // Streamed as the CLI streams (bands of `band_rows`, each dropped when taken).
            for opt in [options[0], options[3], options[1]] {
                let cover = &cover;
                runs.push(Box::new(move || {
                    cover.bands(cover.band_rows(opt), opt, |bands| {
                        for (_, band) in bands {
                            std::hint::black_box(band.ok());
                        }
                    });
                }));
            }
            let mut refs: Vec<&mut dyn FnMut()> = runs
                .iter_mut()
                .map(|f| &mut **f as &mut dyn FnMut())
                .collect();
            let t = interleaved_times(reps, &mut refs);
            let base = t[0].median;
            let ratio = |k: usize| format!("{:.2}x", t[k].median / base);
            let floor = base + (t[5].median - t[6].median).max(0.0);
            let _ = writeln!(
                md,
                "| {name} | {n}^2 | {:.1} | {} | {} | {} | {} | {:.1} | {:.2}x | {:.1} | {:.2}x | {:.2}x |",
                base * 1e3,
                ratio(1),
                ratio(2),
                ratio(3),
                ratio(4),
                floor * 1e3,
                t[3].median / floor,
                t[7].median * 1e3,
                t[8].median / t[7].median,
                t[9].median / t[7].median,
            );
        }
    }
    materials(md, &disc, sizes, reps)
}

/// Two and three overlapping discs with replacement (`MaterialCoverage`, preparation
/// included: intersections and regions) beside one `GridCoverage` run per domain.
fn materials(md: &mut String, disc: &Domain, sizes: &[usize], reps: usize) -> Result<(), String> {
    let discs = [
        translated(disc, -0.5, 0.0)?,
        translated(disc, 0.5, 0.0)?,
        translated(disc, 0.0, 0.6)?,
    ];
    let _ = writeln!(
        md,
        "\nSeveral materials (`MaterialCoverage::new` then `all`, later discs replacing earlier \
         ones: each material's region built from the boundaries split at their intersections) \
         beside one plain `GridCoverage::new` + `all` per disc (plain overlaps), unit discs at \
         (-0.5, 0), (0.5, 0), (0, 0.6) on the square grid over [-1.6, 1.6]^2; medians of {reps} \
         interleaved rounds.\n"
    );
    let _ = writeln!(
        md,
        "| materials | cells | per-domain runs ms | with replacement ms | ratio |"
    );
    let _ = writeln!(md, "| ---: | ---: | ---: | ---: | ---: |");
    for k in [2, 3] {
        let list: Vec<(&Domain, FillRule)> =
            discs[..k].iter().map(|d| (d, FillRule::EvenOdd)).collect();
        for &n in sizes {
            let grid = CellGrid::uniform(-1.6, 1.6, n, -1.6, 1.6, n).map_err(|e| e.to_string())?;
            let mut separate = || {
                for d in &discs[..k] {
                    let c = GridCoverage::new(d, grid.clone()).ok();
                    std::hint::black_box(c.and_then(|c| c.all(CoverageOptions::DEFAULT).ok()));
                }
            };
            let mut replaced = || {
                let m = MaterialCoverage::new(&list, grid.clone(), true).ok();
                std::hint::black_box(m.and_then(|m| m.all(CoverageOptions::DEFAULT).ok()));
            };
            let t = interleaved_times(reps, &mut [&mut separate, &mut replaced]);
            let _ = writeln!(
                md,
                "| {k} | {n}^2 | {:.1} | {:.1} | {:.2}x |",
                t[0].median * 1e3,
                t[1].median * 1e3,
                t[1].median / t[0].median
            );
        }
    }
    Ok(())
}
