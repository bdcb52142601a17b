//! Mass properties of whole CAD files (issue 49): `Model::properties` (every face's area,
//! centroid and second moments; every solid's volume, area, centroid and inertia) on every
//! part of freecad-common's Idf library, beside `OpenCASCADE`'s `BRepGProp` (volume and surface
//! properties of the whole shape, through OCP) at its default rule and at `eps = 1e-9`, in the
//! same run.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use inrs::io::cad::CadModel;

use super::{BenchOptions, IDF, idf_parts, median, occ_python, run_script};

/// The OCC script, relative to the workspace root.
const SCRIPT: &str = "xtask/scripts/occ_properties.py";

/// OCC's row of a file: seconds at its default rule and at `eps = 1e-9`, volume and area.
struct Occ {
    default_s: f64,
    eps_s: f64,
    volume: f64,
    area: f64,
}

/// The section: one row per Idf part.
pub(super) fn section(md: &mut String, root: &Path, o: &BenchOptions) -> Result<(), String> {
    let files = match idf_parts(o.quick) {
        Some(files) => files,
        None => {
            let _ = writeln!(
                md,
                "\nMass properties: not run ({IDF} is missing: install Debian's freecad-common).\n"
            );
            return Ok(());
        }
    };
    let reps = o.reps.clamp(1, 3);
    let python = occ_python(root);
    let occ = occ_rows(&python, root, &files, reps);
    let _ = writeln!(
        md,
        "\nMass properties of whole files (`Model::properties`: every face's area, centroid and \
         second moments, every solid's volume, area, centroid and inertia; faces on all {} \
         threads) on freecad-common's Idf parts, beside OpenCASCADE's `BRepGProp` \
         (`VolumeProperties` and `SurfaceProperties` of the whole shape, through OCP) at its \
         default rule and at `eps = 1e-9`, in the same run; medians of {reps} runs; reading the \
         file not timed. *ratio*: ours over OCC's default. *area difference*: |ours - OCC at \
         1e-9| / OCC's (ours converted to millimetres, OCC's unit), for the faces' total area and the solids' total volume (`-` where OCC \
         finds no volume).\n",
        std::thread::available_parallelism().map_or(1, usize::from)
    );
    if let Err(e) = &occ {
        let _ = writeln!(md, "OCC not run: {e}\n");
    }
    let _ = writeln!(
        md,
        "| file | faces | ours s | OCC default s | OCC eps 1e-9 s | ratio | area difference | volume difference |"
    );
    let _ = writeln!(
        md,
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    );
    let (mut ours_total, mut occ_total) = (0.0, 0.0);
    for (i, file) in files.iter().enumerate() {
        let name = file
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
        let model = CadModel::read(file).map_err(|e| format!("{}: {e}", file.display()))?;
        let mut times = Vec::with_capacity(reps);
        let (mut area, mut volume) = (0.0, 0.0);
        for _ in 0..reps {
            let start = Instant::now();
            let p = model.properties();
            times.push(start.elapsed().as_secs_f64());
            area = p.faces.iter().flatten().map(|f| f.area).sum();
            volume = p.solids.iter().flatten().map(|s| s.volume).sum();
        }
        // OCC works in millimetres; ours are in the file's unit.
        let mm = model.length_unit.as_ref().map_or(1.0, |u| u.millimetres);
        let (area, volume) = (area * mm * mm, volume * mm * mm * mm);
        let ours = median(times);
        let row = occ
            .as_ref()
            .ok()
            .and_then(|rows| rows.get(i))
            .and_then(Option::as_ref);
        let cell =
            |v: Option<f64>, digits: usize| v.map_or("-".to_string(), |v| format!("{v:.digits$}"));
        if let Some(r) = row {
            ours_total += ours;
            occ_total += r.default_s;
        }
        let _ = writeln!(
            md,
            "| {name} | {} | {ours:.4} | {} | {} | {} | {} | {} |",
            model.faces.len(),
            cell(row.map(|r| r.default_s), 4),
            cell(row.map(|r| r.eps_s), 4),
            cell(row.map(|r| ours / r.default_s), 1),
            row.map_or("-".to_string(), |r| format!(
                "{:.1e}",
                (area - r.area).abs() / r.area
            )),
            row.filter(|r| r.volume > 0.0)
                .map_or("-".to_string(), |r| format!(
                    "{:.1e}",
                    (volume - r.volume).abs() / r.volume
                )),
        );
    }
    if occ_total > 0.0 {
        let _ = writeln!(
            md,
            "\nAll files: ours {ours_total:.3} s, OCC's default {occ_total:.3} s (ratio {:.1}).\n",
            ours_total / occ_total
        );
    }
    Ok(())
}

/// OCC's rows for `files` (in order; `None` for a file OCC could not do), or why OCC did not
/// run at all.
fn occ_rows(
    python: &Path,
    root: &Path,
    files: &[PathBuf],
    reps: usize,
) -> Result<Vec<Option<Occ>>, String> {
    let reps = reps.to_string();
    let mut args: Vec<&std::ffi::OsStr> = vec!["--reps".as_ref(), reps.as_ref()];
    args.extend(files.iter().map(|f| f.as_os_str()));
    let text = run_script(python, root, SCRIPT, &args)?;
    let rows: Vec<Option<Occ>> = text
        .lines()
        .filter(|l| l.starts_with("ok ") || l.starts_with("error"))
        .map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .skip(1)
                .filter_map(|w| w.parse().ok())
                .collect();
            (l.starts_with("ok ") && v.len() == 4).then(|| Occ {
                default_s: v[0],
                eps_s: v[1],
                volume: v[2],
                area: v[3],
            })
        })
        .collect();
    if rows.len() == files.len() {
        Ok(rows)
    } else {
        Err(format!(
            "the OCC script printed {} rows for {} files",
            rows.len(),
            files.len()
        ))
    }
}
