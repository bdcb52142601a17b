//! Exact cell coverage (`GridCoverage::all`, issue 35): cells per second on whole grids, beside
//! cell-centre classification by the grid locator (first order: fractions 0 or 1) and beside
//! exactextract (through its Python package) on the boundary flattened within `1e-10` of the
//! bounding box's diagonal, on the same grid in the same run.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use inrs::contain::{Locate, even_odd_area, loop_depths};
use inrs::coverage::{CellGrid, CoverageOptions, GridCoverage};
use inrs::{BoundingBox, Classifier, ContainOptions, Domain, Point};

use super::{BenchOptions, median_time};

/// The glyph of the comparison (Debian's fonts-dejavu-core).
const FONT: &str = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

/// Flattening accuracy for exactextract, relative to the bounding box's diagonal.
const FLATTEN_RELATIVE: f64 = 1e-10;

/// The exactextract script, relative to the workspace root.
const SCRIPT: &str = "xtask/scripts/exactextract_fractions.py";

/// The section: one table row per domain and grid size.
pub(super) fn section(md: &mut String, root: &Path, o: &BenchOptions) -> Result<(), String> {
    let sizes: &[usize] = if o.quick { &[64, 256] } else { &[1024, 4096] };
    let reps = o.reps.min(3);
    let mut domains = vec![(
        "unit disc".to_string(),
        Domain::new(vec![
            inrs::spline::circle(Point::new(0.0, 0.0), 1.0).map_err(|e| e.to_string())?,
        ])
        .map_err(|e| e.to_string())?,
    )];
    let butterfly = root.join("fixtures/axom-contours/butterfly.svg");
    let butterfly = butterfly.to_string_lossy();
    domains.push((
        "butterfly".into(),
        inrs::io::load_domain(&butterfly).map_err(|e| format!("{butterfly}: {e}"))?,
    ));
    let mut notes = Vec::new();
    if Path::new(FONT).is_file() {
        let spec = format!("{FONT}#g");
        domains.push((
            "DejaVuSans 'g'".into(),
            inrs::io::load_domain(&spec).map_err(|e| format!("{spec}: {e}"))?,
        ));
    } else {
        notes.push(format!("{FONT} not installed: the glyph row is left out."));
    }
    let python = peer_python(root);
    let _ = writeln!(
        md,
        "\nExact cell coverage (`GridCoverage::all`, all {} threads, and one band of rows on one \
         thread) on square grids over each domain's bounding box grown by 1% of its diagonal: \
         million cells per second for the fractions alone and with centroids and apertures; \
         cell-centre classification (`Classifier::locator()`, `locate_all_parallel` on the \
         centres, computed beforehand: fractions 0 or 1); exactextract {} (one thread, its \
         per-cell `coverage` with `cell_id`, scattered into a dense array) on the boundary \
         flattened within {FLATTEN_RELATIVE:.0e} of the diagonal; *ratio*: ours (fractions, all \
         threads) over exactextract's cells per second. Area error: |sum of fraction x cell \
         area - even-odd area| / area (for the centres: inside count x cell area). Medians of \
         {reps} runs (exactextract: of {reps} at 1024^2 and below, one above).\n",
        rayon::current_num_threads(),
        python
            .as_ref()
            .map_or_else(|_| "(not run)".to_string(), |(_, v)| v.clone()),
    );
    let _ = writeln!(
        md,
        "| domain | cells | ours Mcells/s | ours 1 thread | with centroids + apertures | centres Mcells/s | exactextract Mcells/s | ratio | ours area error | centres area error | exactextract area error |"
    );
    let _ = writeln!(
        md,
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    );
    let tmp = std::env::temp_dir().join(format!("xtask-coverage-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).map_err(|e| format!("{}: {e}", tmp.display()))?;
    for (name, d) in &domains {
        let b = d
            .bounding_box()
            .grown_by(0.01 * d.bounding_box().diagonal());
        let area = even_odd_area(d).map_err(|e| format!("{name}: {e}"))?;
        let geojson = tmp.join("domain.geojson");
        std::fs::write(&geojson, flattened_geojson(d)?)
            .map_err(|e| format!("{}: {e}", geojson.display()))?;
        let classifier =
            Classifier::new(d, ContainOptions::default()).map_err(|e| e.to_string())?;
        for &n in sizes {
            let grid = CellGrid::uniform(b.min.x, b.max.x, n, b.min.y, b.max.y, n)
                .map_err(|e| e.to_string())?;
            let cells = (n * n) as f64;
            let cell_area = grid.cell_area(0, 0);
            let cover = GridCoverage::new(d, grid).map_err(|e| e.to_string())?;
            let everything = CoverageOptions::DEFAULT
                .with_centroids(true)
                .with_apertures(true);
            let mut sum = 0.0;
            let t_all = median_time(reps, || {
                let c = cover.all(CoverageOptions::DEFAULT);
                sum = c.map_or(f64::NAN, |c| c.fractions.iter().sum::<f64>());
            });
            let ours_error = (sum * cell_area - area).abs() / area;
            let t_one = median_time(reps, || {
                std::hint::black_box(cover.rows(0..n, CoverageOptions::DEFAULT).ok());
            });
            let t_more = median_time(reps, || {
                std::hint::black_box(cover.all(everything).ok());
            });
            let centres = cell_centres(&b, n);
            let locator = classifier.locator();
            let mut inside = 0;
            let t_centres = median_time(reps, || {
                inside = super::count_inside(&locator.locate_all_parallel(&centres));
            });
            drop(centres);
            let centres_error = (inside as f64 * cell_area - area).abs() / area;
            let peer = match &python {
                Ok((py, _)) => exactextract(
                    py,
                    root,
                    &geojson,
                    &b,
                    n,
                    if n <= 1024 { reps } else { 1 },
                    area,
                ),
                Err(e) => Err(e.clone()),
            };
            let mc = |t: f64| cells / t / 1e6;
            let (theirs, ratio, theirs_error) = match &peer {
                Ok((t, e)) => (
                    format!("{:.2}", mc(*t)),
                    format!("{:.0}x", t / t_all),
                    format!("{e:.1e}"),
                ),
                Err(e) => {
                    if !notes.contains(e) {
                        notes.push(e.clone());
                    }
                    ("-".into(), "-".into(), "-".into())
                }
            };
            let _ = writeln!(
                md,
                "| {name} | {n}^2 | {:.1} | {:.1} | {:.1} | {:.1} | {theirs} | {ratio} | {ours_error:.1e} | {centres_error:.1e} | {theirs_error} |",
                mc(t_all),
                mc(t_one),
                mc(t_more),
                mc(t_centres),
            );
        }
    }
    std::fs::remove_dir_all(&tmp).ok();
    for n in notes {
        let _ = writeln!(md, "\n{n}");
    }
    Ok(())
}

/// The centres of the `n x n` cells over `b`, row by row from the bottom.
fn cell_centres(b: &BoundingBox, n: usize) -> Vec<Point> {
    let (dx, dy) = (b.width() / n as f64, b.height() / n as f64);
    (0..n)
        .flat_map(|j| {
            (0..n).map(move |i| {
                Point::new(
                    b.min.x + (i as f64 + 0.5) * dx,
                    b.min.y + (j as f64 + 0.5) * dy,
                )
            })
        })
        .collect()
}

/// The boundary flattened within [`FLATTEN_RELATIVE`] of the diagonal as one `GeoJSON` feature
/// (a MultiPolygon): each loop of even depth a shell, each loop of odd depth a hole of the
/// loop one level up that holds its first vertex (even-odd nesting, as the coverage fills).
pub(super) fn flattened_geojson(d: &Domain) -> Result<String, String> {
    let depths = loop_depths(d).map_err(|e| e.to_string())?;
    let accuracy = FLATTEN_RELATIVE * d.bounding_box().diagonal();
    let rings: Vec<Vec<Point>> = (0..d.loops().len())
        .map(|i| {
            let mut ring = Vec::new();
            d.flatten_loop(i, accuracy, &mut |p| ring.push(p));
            // Close the ring exactly (a loop may end within its closure tolerance).
            if let Some(&first) = ring.first() {
                ring.push(first);
            }
            ring
        })
        .collect();
    let shells: Vec<usize> = (0..rings.len()).filter(|&i| depths[i] % 2 == 0).collect();
    let mut holes = vec![Vec::new(); rings.len()];
    for i in (0..rings.len()).filter(|&i| depths[i] % 2 == 1) {
        let probe = rings[i].first().copied().unwrap_or(Point::new(0.0, 0.0));
        let parent = shells
            .iter()
            .copied()
            .find(|&s| depths[s] + 1 == depths[i] && crosses_odd(&rings[s], probe))
            .ok_or_else(|| format!("hole loop {i} lies in no shell"))?;
        holes[parent].push(i);
    }
    let ring_json = |ring: &[Point]| {
        let coords: Vec<String> = ring
            .iter()
            .map(|p| format!("[{:?},{:?}]", p.x, p.y))
            .collect();
        format!("[{}]", coords.join(","))
    };
    let polygons: Vec<String> = shells
        .iter()
        .map(|&s| {
            let mut parts = vec![ring_json(&rings[s])];
            parts.extend(holes[s].iter().map(|&h| ring_json(&rings[h])));
            format!("[{}]", parts.join(","))
        })
        .collect();
    Ok(format!(
        r#"{{"type":"Feature","properties":{{}},"geometry":{{"type":"MultiPolygon","coordinates":[{}]}}}}"#,
        polygons.join(",")
    ))
}

/// Whether a ray from `p` to the right crosses the closed polyline `ring` an odd number of
/// times (`p` inside it, for a point not on it).
fn crosses_odd(ring: &[Point], p: Point) -> bool {
    let mut inside = false;
    for w in ring.windows(2) {
        let (a, b) = (w[0], w[1]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if x > p.x {
                inside = !inside;
            }
        }
    }
    inside
}

/// A Python that imports exactextract (the venv under `target/` that `bench` docs describe,
/// else `python3`) and exactextract's version; `Err` with a one-line reason otherwise.
pub(super) fn peer_python(root: &Path) -> Result<(PathBuf, String), String> {
    let venv = root.join("target/cov-venv/bin/python");
    let python = if venv.is_file() {
        venv
    } else {
        PathBuf::from("python3")
    };
    let out = Command::new(&python)
        .args(["-c", "import exactextract; print(exactextract.__version__)"])
        .output()
        .map_err(|e| format!("exactextract not run: {}: {e}", python.display()))?;
    if !out.status.success() {
        return Err(format!(
            "exactextract not run: `{} -c 'import exactextract'` failed (install it with \
             `python3 -m venv target/cov-venv && target/cov-venv/bin/pip install exactextract numpy`).",
            python.display()
        ));
    }
    Ok((
        python,
        String::from_utf8_lossy(&out.stdout).trim().to_string(),
    ))
}

/// exactextract's median seconds and relative area error on the `n x n` grid over `b`.
pub(super) fn exactextract(
    python: &Path,
    root: &Path,
    geojson: &Path,
    b: &BoundingBox,
    n: usize,
    reps: usize,
    area: f64,
) -> Result<(f64, f64), String> {
    let out = Command::new(python)
        .arg(root.join(SCRIPT))
        .arg(geojson)
        .args([b.min.x, b.min.y, b.max.x, b.max.y].map(|v| format!("{v:?}")))
        .args([n, n, reps].map(|v| v.to_string()))
        .arg(format!("{area:?}"))
        .output()
        .map_err(|e| format!("exactextract not run: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    let words: Vec<&str> = text.split_whitespace().collect();
    match (out.status.success(), words.as_slice()) {
        (true, ["seconds", _, median, "area_relative_error", error]) => Ok((
            median
                .parse()
                .map_err(|_| format!("exactextract printed {text:?}"))?,
            error
                .parse()
                .map_err(|_| format!("exactextract printed {text:?}"))?,
        )),
        _ => Err(format!(
            "exactextract failed: {}",
            String::from_utf8_lossy(&out.stderr)
                .lines()
                .last()
                .unwrap_or("no message")
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn holes_go_into_the_shell_that_holds_them() {
        let c = |x: f64, r: f64| inrs::spline::circle(Point::new(x, 0.0), r).unwrap();
        // A ring at 0 and a disc at 5: two shells, one hole, in the first.
        let d = Domain::new(vec![c(0.0, 2.0), c(0.0, 1.0), c(5.0, 1.0)]).unwrap();
        let json = flattened_geojson(&d).unwrap();
        let polygons = json.split("]]],[[[").count();
        assert_eq!(polygons, 2, "{}", &json[..200]);
        // The first polygon has two rings (shell and hole), the second one.
        let first = json.split("]]],[[[").next().unwrap();
        assert_eq!(first.matches("]],[[").count(), 1);
        assert!(crosses_odd(
            &[
                Point::new(0.0, 0.0),
                Point::new(1.0, 0.0),
                Point::new(1.0, 1.0),
                Point::new(0.0, 0.0)
            ],
            Point::new(0.7, 0.3)
        ));
    }
}
