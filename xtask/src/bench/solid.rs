//! Point in a solid (issue 50): `SolidClassifier` (build, then `locate` on one thread and
//! `par_values_into` on all) on every solid of freecad-common's Idf parts and of the `OpenCASCADE`
//! test parts of `python/tests/cad_parts.py`, beside `OpenCASCADE`'s
//! `BRepClass3d_SolidClassifier` (through OCP) on the same uniform random points of each solid's box, in the same run. Every
//! point where one says inside and the other outside is listed.

use std::fmt::Write as _;
use std::hint::black_box;
use std::path::{Path, PathBuf};

use inrs::geom::solid::{Locate, Location, PointQuery, SolidClassifier};
use inrs::io::cad::CadModel;
use inrs::spline::Point3;

use super::{BenchOptions, IDF, idf_parts, median_time, occ_python, run_script};

/// The OCC script, relative to the workspace root.
const SCRIPT: &str = "xtask/scripts/occ_solid.py";

/// Where the OCC test parts are written, relative to the workspace root.
const PARTS_DIR: &str = "target/bench-solid-parts";

/// The OCC test parts committed under `fixtures/cad/` (used when they cannot be written).
const FIXTURE_PARTS: [&str; 5] = [
    "fixtures/cad/box_void.step",
    "fixtures/cad/cone_minus_sphere.step",
    "fixtures/cad/iges/box_void_brep.igs",
    "fixtures/cad/iges/cone_minus_sphere_brep.igs",
    "fixtures/cad/iges/torus.igs",
];

/// OCC's classifier tolerance (millimetres).
const OCC_TOL: f64 = 1e-7;

/// Points per solid, and with `--quick`.
const POINTS: usize = 20_000;
const QUICK_POINTS: usize = 2_000;

/// The seed of every solid's points.
const SEED: u64 = 0x5EED_5050_5050;

/// Disagreements listed per solid (all are counted).
const LISTED: usize = 10;

/// OCC's answers for one solid.
struct OccSolid {
    build_s: f64,
    perform_s: f64,
    /// `I`, `O`, `N` (on), `U` (unknown), one per point.
    states: Vec<u8>,
}

/// OCC's view of one file.
struct OccFile {
    solids: usize,
    overhead_s: f64,
    rows: Vec<(usize, Result<OccSolid, String>)>,
}

/// One solid measured by us.
struct Ours {
    k: usize,
    faces: usize,
    patches: usize,
    build_s: f64,
    locate_s: f64,
    parallel_s: f64,
    points: Vec<Point3>,
    locations: Vec<Location>,
}

/// A point where ours and OCC say inside and outside.
struct Disagreement {
    file: String,
    solid: usize,
    point: Point3,
    ours: Location,
    occ: char,
}

/// Totals over the solids both sides classified.
#[derive(Default)]
struct Totals {
    solids: usize,
    points: usize,
    ours_s: f64,
    occ_s: f64,
    ours_build_s: f64,
    occ_build_s: f64,
    faces: usize,
    disagreements: usize,
}

/// The section: one row per solid.
pub(super) fn section(md: &mut String, root: &Path, o: &BenchOptions) -> Result<(), String> {
    let mut files = match idf_parts(o.quick) {
        Some(files) => files,
        None => {
            let _ = writeln!(
                md,
                "\nPoint in a solid: the Idf parts are missing ({IDF}: install Debian's \
                 freecad-common); the OCC test parts only.\n"
            );
            Vec::new()
        }
    };
    let python = occ_python(root);
    let (parts, parts_note) = match write_parts(&python, root) {
        Ok(p) => (p, None),
        Err(e) => (
            FIXTURE_PARTS.iter().map(|p| root.join(p)).collect(),
            Some(e),
        ),
    };
    files.extend(parts);
    let n = o
        .solid_points
        .unwrap_or(if o.quick { QUICK_POINTS } else { POINTS });
    let reps = o.reps.clamp(1, 3);
    let threads = std::thread::available_parallelism().map_or(1, usize::from);

    let mut table = String::new();
    let _ = writeln!(
        table,
        "| file | solid | faces | patches | build ms | build us / face | ours Mpts/s (1 thread) \
         | ours Mpts/s ({threads} threads) | OCC pts/s | ours / OCC | boundary: ours / OCC ON \
         | disagreements |"
    );
    let _ = writeln!(
        table,
        "| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |"
    );
    let mut totals = Totals::default();
    let mut disagreements: Vec<Disagreement> = Vec::new();
    let mut problems: Vec<String> = Vec::new();
    let mut overheads: Vec<f64> = Vec::new();
    let mut without: Vec<String> = Vec::new();
    for file in &files {
        let name = if let Ok(part) = file.strip_prefix(root.join(PARTS_DIR)) {
            format!("parts/{}", part.display())
        } else if let Ok(fixture) = file.strip_prefix(root) {
            fixture.display().to_string()
        } else {
            file.file_name()
                .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
        };
        eprintln!("solid bench: {name}");
        let model = match CadModel::read(file) {
            Ok(m) => m,
            Err(e) => {
                problems.push(format!("{name}: not read: {e}"));
                continue;
            }
        };
        if model.solids.is_empty() {
            let occ = occ_file(&python, root, file, &[], 1.0).map(|f| f.solids);
            if let Ok(found @ 1..) = occ {
                problems.push(format!("{name}: ours finds no solid, OCC {found}"));
            }
            without.push(match occ {
                Ok(found) => format!("{name} (OCC: {found})"),
                Err(e) => format!("{name} (OCC: {e})"),
            });
            continue;
        }
        // OCC works in millimetres; ours are in the file's unit.
        let mm = model.length_unit.as_ref().map_or(1.0, |u| u.millimetres);
        let mut ours: Vec<Ours> = Vec::new();
        for k in 0..model.solids.len() {
            let classifier = match SolidClassifier::new(&model, k) {
                Ok(c) => c,
                Err(e) => {
                    let _ = writeln!(
                        table,
                        "| {name} | {k} | {} | - | not built: {} | | | | | | | |",
                        solid_faces(&model, k),
                        e.to_string().replace('|', "\\|")
                    );
                    continue;
                }
            };
            let build_s = median_time(reps, || {
                black_box(SolidClassifier::new(&model, k).ok());
            });
            let (lo, hi) = classifier.bounds();
            let mut rng = rs_testkit::XorShift64::new(SEED);
            let points: Vec<Point3> = (0..n)
                .map(|_| {
                    Point3::new(
                        rng.uniform(lo.x, hi.x),
                        rng.uniform(lo.y, hi.y),
                        rng.uniform(lo.z, hi.z),
                    )
                })
                .collect();
            let mut locations = vec![Location::Outside; n];
            let locate_s = median_time(reps, || {
                for (l, &p) in locations.iter_mut().zip(&points) {
                    *l = classifier.locate(black_box(p));
                }
                black_box(&locations);
            });
            let mut parallel = vec![Location::Outside; n];
            let parallel_s = median_time(reps, || {
                classifier.par_values_into(black_box(&points[..]), &mut parallel);
                black_box(&parallel);
            });
            let differ = locations
                .iter()
                .zip(&parallel)
                .filter(|(a, b)| a != b)
                .count();
            if differ > 0 {
                problems.push(format!(
                    "{name} solid {k}: par_values_into differs from locate on {differ} points"
                ));
            }
            ours.push(Ours {
                k,
                faces: classifier.faces().len(),
                patches: classifier.patch_count(),
                build_s,
                locate_s,
                parallel_s,
                points,
                locations,
            });
        }
        if ours.is_empty() {
            continue;
        }
        let occ = occ_file(&python, root, file, &ours, mm);
        if let Ok(f) = &occ {
            overheads.push(f.overhead_s);
            if f.solids != model.solids.len() {
                problems.push(format!(
                    "{name}: OCC finds {} solids, ours {}",
                    f.solids,
                    model.solids.len()
                ));
            }
        }
        for s in &ours {
            let found = match &occ {
                Ok(f) => f
                    .rows
                    .iter()
                    .find(|(k, _)| *k == s.k)
                    .map(|(_, r)| r.as_ref().map_err(String::clone))
                    .unwrap_or_else(|| Err("no answer".to_string())),
                Err(e) => Err(e.clone()),
            };
            let found = found.and_then(|r| {
                if r.states.len() == s.points.len() {
                    Ok(r)
                } else {
                    Err(format!(
                        "{} states for {} points",
                        r.states.len(),
                        s.points.len()
                    ))
                }
            });
            let boundary = s
                .locations
                .iter()
                .filter(|&&l| l == Location::Boundary)
                .count();
            let mpts = |secs: f64| n as f64 / secs / 1e6;
            let lead = format!(
                "| {name} | {} | {} | {} | {:.2} | {:.1} | {} | {} |",
                s.k,
                s.faces,
                s.patches,
                s.build_s * 1e3,
                s.build_s * 1e6 / s.faces.max(1) as f64,
                sig(mpts(s.locate_s)),
                sig(mpts(s.parallel_s)),
            );
            match found {
                Ok(r) => {
                    let mut bad = 0;
                    for ((&p, &ours_l), &occ_s) in
                        s.points.iter().zip(&s.locations).zip(r.states.iter())
                    {
                        let clash = matches!(
                            (ours_l, occ_s),
                            (Location::Inside, b'O') | (Location::Outside, b'I')
                        );
                        if clash {
                            bad += 1;
                            if bad <= LISTED {
                                disagreements.push(Disagreement {
                                    file: name.clone(),
                                    solid: s.k,
                                    point: p,
                                    ours: ours_l,
                                    occ: occ_s as char,
                                });
                            }
                        }
                    }
                    let on = r.states.iter().filter(|&&c| c == b'N').count();
                    let unknown = r.states.iter().filter(|&&c| c == b'U').count();
                    if unknown > 0 {
                        problems.push(format!(
                            "{name} solid {}: OCC answers UNKNOWN for {unknown} points",
                            s.k
                        ));
                    }
                    totals.solids += 1;
                    totals.points += n;
                    totals.ours_s += s.locate_s;
                    totals.occ_s += r.perform_s;
                    totals.ours_build_s += s.build_s;
                    totals.occ_build_s += r.build_s;
                    totals.faces += s.faces;
                    totals.disagreements += bad;
                    let occ_rate = n as f64 / r.perform_s;
                    let _ = writeln!(
                        table,
                        "{lead} {occ_rate:.0} | {} | {boundary} / {on} | {} |",
                        sig(r.perform_s / s.locate_s),
                        if bad > 0 {
                            format!("**{bad}**")
                        } else {
                            "0".to_string()
                        }
                    );
                }
                Err(e) => {
                    problems.push(format!("{name} solid {}: OCC: {e}", s.k));
                    let _ = writeln!(table, "{lead} - | - | {boundary} / - | - |");
                }
            }
        }
    }
    if totals.solids > 0 {
        let _ = writeln!(
            table,
            "| **all** | {} | {} | | {:.1} | {:.1} | {} | | {:.0} | {} | | {} |",
            totals.solids,
            totals.faces,
            totals.ours_build_s * 1e3,
            totals.ours_build_s * 1e6 / totals.faces.max(1) as f64,
            sig(totals.points as f64 / totals.ours_s / 1e6),
            totals.points as f64 / totals.occ_s,
            sig(totals.occ_s / totals.ours_s),
            if totals.disagreements > 0 {
                format!("**{}**", totals.disagreements)
            } else {
                "0".to_string()
            }
        );
    }

    let _ = writeln!(
        md,
        "\nPoint in a solid (`SolidClassifier`: build, then `locate` on one thread and \
         `par_values_into` on {threads}) on every solid of freecad-common's Idf parts and of the \
         OpenCASCADE test parts (`python/tests/cad_parts.py`, STEP and IGES B-rep mode), beside \
         OpenCASCADE's `BRepClass3d_SolidClassifier` (built once per solid, then `Perform(p, \
         {OCC_TOL:e})` and `State()` per point, through OCP) on the same {n} uniform random \
         points of each solid's box (fixed seed), in the same run; ours medians of {reps} runs, \
         OCC one run. *ours / OCC*: OCC's seconds over ours (one thread). *boundary*: points \
         ours puts on the boundary / OCC puts ON. *disagreements*: points one puts inside and \
         the other outside (boundary and ON not counted). `parts/`: the test parts. OCC's \
         build time (totals line) is for information: its classifier may leave part of its \
         set-up to the first `Perform`."
    );
    if let Some(h) = overheads.iter().copied().reduce(f64::max) {
        let _ = writeln!(
            md,
            "OCC's times include its Python loop: making the `gp_Pnt`s alone takes up to \
             {:.2} us a point.",
            h * 1e6
        );
    }
    if let Some(e) = parts_note {
        let _ = writeln!(
            md,
            "The test parts could not be written ({e}): the committed ones under `fixtures/cad/` \
             instead."
        );
    }
    md.push('\n');
    md.push_str(&table);
    if totals.solids > 0 {
        let _ = writeln!(
            md,
            "\nAll {} solids compared ({} points): ours {:.3} s on one thread, OCC {:.3} s \
             (ours {} times as fast); builds: ours {:.1} ms, OCC {:.1} ms.",
            totals.solids,
            totals.points,
            totals.ours_s,
            totals.occ_s,
            sig(totals.occ_s / totals.ours_s),
            totals.ours_build_s * 1e3,
            totals.occ_build_s * 1e3,
        );
    }
    if totals.disagreements > 0 {
        let mut list = format!(
            "\n**DISAGREEMENTS: {} points where ours and OpenCASCADE say inside and outside \
             (bugs, one side's or the other's; at most {LISTED} listed per solid):**\n\n\
             | file | solid | point (file units) | ours | OCC |\n| --- | ---: | --- | --- | --- |\n",
            totals.disagreements
        );
        for d in &disagreements {
            let _ = writeln!(
                list,
                "| {} | {} | ({:?}, {:?}, {:?}) | {:?} | {} |",
                d.file,
                d.solid,
                d.point.x,
                d.point.y,
                d.point.z,
                d.ours,
                match d.occ {
                    'I' => "IN",
                    'O' => "OUT",
                    _ => "?",
                }
            );
        }
        eprintln!("{list}");
        md.push_str(&list);
    } else if totals.solids > 0 {
        let _ = writeln!(md, "\nNo disagreements.");
    }
    if !without.is_empty() {
        let _ = writeln!(
            md,
            "\nFiles without solids (faces or shells only; not compared): {}.",
            without.join(", ")
        );
    }
    if !problems.is_empty() {
        let _ = writeln!(md, "\nNot compared or not as expected:\n");
        for p in &problems {
            eprintln!("solid bench: {p}");
            let _ = writeln!(md, "- {p}");
        }
    }
    md.push('\n');
    Ok(())
}

/// `v` to three significant digits (no exponent).
fn sig(v: f64) -> String {
    if !(v.is_finite() && v != 0.0) {
        return format!("{v}");
    }
    let digits = (2 - v.abs().log10().floor() as i32).clamp(0, 12) as usize;
    format!("{v:.digits$}")
}

/// How many faces solid `k` has (its shells' faces, each once).
fn solid_faces(model: &inrs::geom::brep::Model, k: usize) -> usize {
    let mut faces: Vec<usize> = model.solids[k]
        .shells
        .iter()
        .flat_map(|&s| model.shells[s].faces.iter().copied())
        .collect();
    faces.sort_unstable();
    faces.dedup();
    faces.len()
}

/// Writes the OCC test parts with the script; their paths.
fn write_parts(python: &Path, root: &Path) -> Result<Vec<PathBuf>, String> {
    let dir = root.join(PARTS_DIR);
    let text = run_script(
        python,
        root,
        SCRIPT,
        &["--write-parts".as_ref(), dir.as_os_str()],
    )?;
    Ok(text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .map(PathBuf::from)
        .filter(|p| p.is_file())
        .collect())
}

/// Runs OCC on `ours`' points (in millimetres) of `file`.
fn occ_file(
    python: &Path,
    root: &Path,
    file: &Path,
    ours: &[Ours],
    mm: f64,
) -> Result<OccFile, String> {
    let points_path =
        std::env::temp_dir().join(format!("inrs-solid-bench-{}.txt", std::process::id()));
    let mut text = String::new();
    for s in ours {
        for p in &s.points {
            let _ = writeln!(text, "{} {} {} {}", s.k, p.x * mm, p.y * mm, p.z * mm);
        }
    }
    std::fs::write(&points_path, text).map_err(|e| format!("{}: {e}", points_path.display()))?;
    let tol = OCC_TOL.to_string();
    let args = [
        "--tol".as_ref(),
        tol.as_ref(),
        file.as_os_str(),
        points_path.as_os_str(),
    ];
    let text = run_script(python, root, SCRIPT, &args);
    let _ = std::fs::remove_file(&points_path);
    let text = text?;
    let mut result = OccFile {
        solids: 0,
        overhead_s: 0.0,
        rows: Vec::new(),
    };
    for line in text.lines().filter(|l| l.starts_with('{')) {
        if let Some(k) = field(line, "solid").and_then(|v| v.parse().ok()) {
            let row = match field(line, "error") {
                Some(e) => Err(e.to_string()),
                None => {
                    let number = |key| {
                        field(line, key)
                            .and_then(|v| v.parse::<f64>().ok())
                            .ok_or_else(|| format!("no {key} in {line:.80}"))
                    };
                    Ok(OccSolid {
                        build_s: number("build_s")?,
                        perform_s: number("perform_s")?,
                        states: field(line, "states").unwrap_or("").as_bytes().to_vec(),
                    })
                }
            };
            result.rows.push((k, row));
        } else if let Some(e) = field(line, "error") {
            return Err(e.to_string());
        } else {
            result.solids = field(line, "solids")
                .and_then(|v| v.parse().ok())
                .unwrap_or(0);
            result.overhead_s = field(line, "overhead_s")
                .and_then(|v| v.parse().ok())
                .unwrap_or(0.0);
        }
    }
    Ok(result)
}

/// The value of `key` in one line of the script's JSON (`json.dumps` of a flat object: numbers,
/// and strings without quotes or escapes in them), without its quotes.
fn field<'a>(line: &'a str, key: &str) -> Option<&'a str> {
    let start = line.find(&format!("\"{key}\": "))? + key.len() + 4;
    let rest = &line[start..];
    if let Some(s) = rest.strip_prefix('"') {
        s.find('"').map(|end| &s[..end])
    } else {
        rest.find([',', '}']).map(|end| rest[..end].trim())
    }
}
