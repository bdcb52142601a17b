//! What it costs to start: from a domain to its first answer, measured against the commit
//! before the lazy indexes ([`BASELINE_REV`]) in the same run.
//!
//! Both trees build the same probe (`crates/inrs/examples/build_probe.rs`, which uses only API
//! present at both); the two binaries run alternately, round after round, and each figure is the
//! median over the rounds of the probe's own medians.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use super::BenchOptions;

/// The last commit before issue #34's work (eager boxes, box grid and locator; companion-matrix
/// roots; 32 sub-boxes on every monotone piece): "today" in the goals.
pub(super) const BASELINE_REV: &str = "01e2078";

/// The shapes of the goals: the GWN paper's five, the 500-curve flower, the inRS paper's three.
const SHAPES: [&str; 9] = [
    "axom-contours/bubble.svg",
    "axom-contours/butterfly.svg",
    "axom-contours/fish.svg",
    "axom-contours/rose.svg",
    "axom-contours/twirl.svg",
    "synthetic/flower500.json",
    "inrs-paper/s3_m_shape.json",
    "inrs-paper/s4_disk_ellipse_segment.json",
    "inrs-paper/s5_lune.json",
];

/// The CAD parts of the many-faces workload (Debian's freecad-common), when installed.
const CAD_DIR: &str = "/usr/share/freecad/Mod/Idf/Idflibs";

const PROBE: &str = "crates/inrs/examples/build_probe.rs";

fn cargo() -> String {
    std::env::var("CARGO").unwrap_or_else(|_| "cargo".into())
}

/// Builds the probe of the tree at `src` into `target` and returns the binary's path.
fn build_probe(src: &Path, target: &Path) -> Result<PathBuf, String> {
    let status = Command::new(cargo())
        .args([
            "build",
            "--release",
            "--quiet",
            "-p",
            "inrs",
            "--example",
            "build_probe",
        ])
        .current_dir(src)
        .env("CARGO_TARGET_DIR", target)
        .status()
        .map_err(|e| format!("cargo build in {}: {e}", src.display()))?;
    if !status.success() {
        return Err(format!("building the probe in {} failed", src.display()));
    }
    Ok(target.join("release/examples/build_probe"))
}

/// The baseline tree (`git archive` of [`BASELINE_REV`] under `target/bench-baseline/`) with
/// the current probe copied in.
fn baseline_tree(root: &Path) -> Result<PathBuf, String> {
    let dir = root.join("target/bench-baseline").join(BASELINE_REV);
    if !dir.join("Cargo.toml").exists() {
        std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
        let status = Command::new("sh")
            .arg("-c")
            .arg(format!(
                "git -C '{}' archive {BASELINE_REV} | tar -x -C '{}'",
                root.display(),
                dir.display()
            ))
            .status()
            .map_err(|e| format!("git archive: {e}"))?;
        if !status.success() {
            return Err(format!("git archive {BASELINE_REV} failed"));
        }
    }
    std::fs::create_dir_all(dir.join("crates/inrs/examples")).map_err(|e| e.to_string())?;
    std::fs::copy(root.join(PROBE), dir.join(PROBE)).map_err(|e| e.to_string())?;
    Ok(dir)
}

type Samples = BTreeMap<String, Vec<f64>>;

/// Runs the probe once and adds its `key<TAB>value` lines to `samples`.
fn run_probe(bin: &Path, args: &[String], samples: &mut Samples) -> Result<(), String> {
    let out = Command::new(bin)
        .args(args)
        .output()
        .map_err(|e| format!("{}: {e}", bin.display()))?;
    if !out.status.success() {
        return Err(format!(
            "{} failed: {}",
            bin.display(),
            String::from_utf8_lossy(&out.stderr).trim()
        ));
    }
    for line in String::from_utf8_lossy(&out.stdout).lines() {
        if let Some((k, v)) = line.split_once('\t')
            && let Ok(v) = v.trim().parse::<f64>()
        {
            samples.entry(k.to_string()).or_default().push(v);
        }
    }
    Ok(())
}

fn median_of(samples: &Samples, key: &str) -> Option<f64> {
    samples.get(key).map(|v| super::median(v.clone()))
}

/// The "build" section: the goals' table (before, after, ratio) and the query speeds.
pub(super) fn section(md: &mut String, root: &Path, o: &BenchOptions) -> Result<(), String> {
    let new_bin = build_probe(root, &root.join("target"))?;
    let old_bin = build_probe(
        &baseline_tree(root)?,
        &root.join("target/bench-baseline/target"),
    )?;
    let mut args = vec!["--reps".to_string(), o.reps.max(9).to_string()];
    args.extend(
        SHAPES
            .iter()
            .map(|s| root.join("fixtures").join(s).to_string_lossy().into_owned()),
    );
    let mut cad: Vec<String> = std::fs::read_dir(CAD_DIR)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "stp" || x == "igs"))
                .map(|p| p.to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    cad.sort();
    if !cad.is_empty() {
        args.push("--cad".into());
        args.extend(cad.iter().cloned());
    }
    let rounds = if o.quick { 2 } else { 4 };
    let (mut old, mut new) = (Samples::new(), Samples::new());
    for round in 0..rounds {
        // Alternate which goes first, so that a slow spell of the machine hits both.
        if round % 2 == 0 {
            run_probe(&old_bin, &args, &mut old)?;
            run_probe(&new_bin, &args, &mut new)?;
        } else {
            run_probe(&new_bin, &args, &mut new)?;
            run_probe(&old_bin, &args, &mut old)?;
        }
    }
    let all_cores = if cad.is_empty() {
        None
    } else {
        Some(faces_on_all_cores(&cad, o)?)
    };
    report(md, &old, &new, rounds, cad.len(), all_cores);
    Ok(())
}

/// The probe's many-faces workload through [`inrs::contain::locate_each`] (the domains spread
/// over all cores): seconds per face, the median of the rounds.
fn faces_on_all_cores(paths: &[String], o: &BenchOptions) -> Result<f64, String> {
    let mut faces: Vec<(inrs::Domain, Vec<inrs::Point>)> = Vec::new();
    for p in paths {
        let model = inrs::io::cad::CadModel::read(p).map_err(|e| format!("{p}: {e}"))?;
        for d in model.face_domains(None).into_iter().flatten() {
            // The probe's points of a face (`points_around`).
            let b = d.bounding_box();
            let pts = inrs::contain::baselines::halton_points(400, b.grown_by(0.05 * b.diagonal()));
            faces.push((d, pts));
        }
    }
    let batches: Vec<(&inrs::Domain, &[inrs::Point])> =
        faces.iter().map(|(d, p)| (d, p.as_slice())).collect();
    let t = super::median_time(o.reps.clamp(3, 11), || {
        std::hint::black_box(inrs::contain::locate_each(
            &batches,
            inrs::contain::ContainOptions::DEFAULT,
        ));
    });
    Ok(t / faces.len().max(1) as f64)
}

fn stem(s: &str) -> &str {
    let name = s.rsplit('/').next().unwrap_or(s);
    name.split('.').next().unwrap_or(name)
}

fn report(
    md: &mut String,
    old: &Samples,
    new: &Samples,
    rounds: usize,
    cad_files: usize,
    all_cores: Option<f64>,
) {
    let _ = writeln!(
        md,
        "\nStart-up: from a loaded domain to its first answer, this tree against {BASELINE_REV} \
         (the commit before the lazy indexes), built from the same probe \
         (`crates/inrs/examples/build_probe.rs`) and run alternately, {rounds} rounds; medians. \
         *Field ready*: `WindingField::new` + `FastWindingField::new` + one winding number \
         (goal <= 2 us a piece and >= 10x less). *Classifier + locator*: `Classifier::new` + \
         `locator()` + one point (goal >= 5x less; the grid is built strip by strip as queries \
         need it); *whole grid*: `Classifier::new` + `PointLocator::new`, every strip. *One point*: `Containment::new` + \
         `engine(1)` on one point; *from JSON*: the same from the JSON text (goal < 50 us on the \
         paper domains). Query ratios: new time / old time per point (9 x 10^4 Halton points of the \
         box grown by 5%; inRS2 on 10^4 of them), goal within 5%.\n"
    );
    let _ = writeln!(
        md,
        "| shape | pieces | field ready us/piece (before, after, x less) | classifier + locator \
         us/piece (before, after, x less) | whole grid us/piece (before, after, x less) | one point \
         us (before, after) | from JSON us (before, \
         after) | field query new/old | locator query new/old | inRS2 query new/old |"
    );
    let _ = writeln!(md, "|{}", "---|".repeat(10));
    for s in SHAPES {
        let name = stem(s);
        let get = |m: &Samples, k: &str| median_of(m, &format!("{k}/{name}"));
        let Some(pieces) = get(new, "pieces") else {
            continue;
        };
        let per = |k: &str| -> String {
            match (get(old, k), get(new, k)) {
                (Some(a), Some(b)) => format!(
                    "{:.2}, {:.2}, {:.1}",
                    a * 1e6 / pieces,
                    b * 1e6 / pieces,
                    a / b
                ),
                _ => "-".into(),
            }
        };
        let whole = |k: &str| -> String {
            match (get(old, k), get(new, k)) {
                (Some(a), Some(b)) => format!("{:.1}, {:.1}", a * 1e6, b * 1e6),
                _ => "-".into(),
            }
        };
        let ratio = |k: &str| -> String {
            match (get(old, k), get(new, k)) {
                (Some(a), Some(b)) => format!("{:.3}", b / a),
                _ => "-".into(),
            }
        };
        let _ = writeln!(
            md,
            "| {name} | {pieces} | {} | {} | {} | {} | {} | {} | {} | {} |",
            per("field_ready"),
            per("classifier_locator"),
            per("classifier_whole_grid"),
            whole("one_point"),
            whole("json_one_point"),
            ratio("field_query"),
            ratio("locator_query"),
            ratio("inrs2_query"),
        );
    }
    if let (Some(a), Some(b), Some(n)) = (
        median_of(old, "cad_per_face"),
        median_of(new, "cad_per_face"),
        median_of(new, "cad_faces"),
    ) {
        let _ = writeln!(
            md,
            "\nMany small domains: the {n} faces read from the {cad_files} parts of {CAD_DIR} \
             (freecad-common), 400 Halton points each (the face's box grown by 5% of its diagonal), one \
             `Containment` per face on one thread: {:.1} us a face before, {:.1} after ({:.1}x).",
            a * 1e6,
            b * 1e6,
            a / b
        );
        first_and_warm_row(md, old, new);
        if let Some(c) = all_cores {
            let _ = writeln!(
                md,
                "The same faces and points through `locate_each` (the faces spread over all \
                 cores): {:.1} us a face, {:.1}x the one-thread loop before.",
                c * 1e6,
                a / c
            );
        }
    }
}

/// The goal of the row: a face's first classify (its `Containment` and whatever the
/// first batch builds) at most this many times the same batch on the warm value.
const FIRST_OVER_WARM_GOAL: f64 = 2.5;

/// The row "many CAD faces: first classify / warm classify" from the probe's sums over the
/// faces (`cad_first_per_face`, `cad_warm_per_face`), before and after.
fn first_and_warm_row(md: &mut String, old: &Samples, new: &Samples) {
    let cell = |m: &Samples| -> Option<String> {
        let (first, warm) = (
            median_of(m, "cad_first_per_face")?,
            median_of(m, "cad_warm_per_face")?,
        );
        Some(format!(
            "{:.2} ({:.1} us / {:.1} us)",
            first / warm,
            first * 1e6,
            warm * 1e6
        ))
    };
    let Some(after) = cell(new) else {
        return;
    };
    let before = cell(old).unwrap_or_else(|| "-".into());
    let _ = writeln!(
        md,
        "
| workload (first / warm, first us / warm us a face) | before | after | goal |
         |---|---|---|---|
         | many CAD faces: first classify / warm classify | {before} | {after} | <= \
         {FIRST_OVER_WARM_GOAL} |"
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table reads the probe's keys: per piece, ratios old / new for the builds and
    /// new / old for the queries, and the faces' line with the all-cores figure.
    #[test]
    fn the_report_turns_probe_lines_into_ratios() {
        let sample = |pairs: &[(&str, f64)]| -> Samples {
            pairs
                .iter()
                .map(|(k, v)| (k.to_string(), vec![*v]))
                .collect()
        };
        let old = sample(&[
            ("pieces/butterfly", 500.0),
            ("field_ready/butterfly", 20e-3),
            ("classifier_locator/butterfly", 25e-3),
            ("locator_query/butterfly", 10e-9),
            ("cad_per_face", 400e-6),
            ("cad_first_per_face", 102e-6),
            ("cad_warm_per_face", 20e-6),
        ]);
        let new = sample(&[
            ("pieces/butterfly", 500.0),
            ("field_ready/butterfly", 0.5e-3),
            ("classifier_locator/butterfly", 5e-3),
            ("locator_query/butterfly", 10.2e-9),
            ("cad_per_face", 200e-6),
            ("cad_faces", 3000.0),
            ("cad_first_per_face", 40e-6),
            ("cad_warm_per_face", 20e-6),
        ]);
        let mut md = String::new();
        report(&mut md, &old, &new, 2, 32, Some(100e-6));
        let row = md
            .lines()
            .find(|l| l.starts_with("| butterfly |"))
            .expect("a butterfly row");
        assert!(row.contains("| 40.00, 1.00, 40.0 |"), "{row}");
        assert!(row.contains("| 50.00, 10.00, 5.0 |"), "{row}");
        assert!(row.contains("| 1.020 |"), "{row}");
        assert!(
            md.contains("400.0 us a face before, 200.0 after (2.0x)"),
            "{md}"
        );
        assert!(md.contains("100.0 us a face, 4.0x"), "{md}");
        assert!(
            md.contains(
                "| many CAD faces: first classify / warm classify | 5.10 (102.0 us / 20.0 us) \
                 | 2.00 (40.0 us / 20.0 us) | <= 2.5 |"
            ),
            "{md}"
        );
        assert!(
            !md.contains("| rose |"),
            "shapes the probe did not report are left out"
        );
    }
}
