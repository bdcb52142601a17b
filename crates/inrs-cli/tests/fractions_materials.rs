//! `inrs fractions` with several `--domain`s (materials on one grid, the library's
//! `MaterialCoverage`): two overlapping discs against the closed forms with replacement,
//! `--no-replace` slices equal to one-domain runs byte for byte, a leading axis on every file,
//! one domain unchanged, a material replaced everywhere, and one-line errors naming the
//! domain that leave no file behind.

#[allow(dead_code)]
mod common;
use common::{inrs, read_npy};

use std::f64::consts::PI;
use std::path::{Path, PathBuf};

/// A fresh scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    common::scratch("fractions-materials", name)
}

/// Writes the JSON domain of the disc of centre `(x, 0)` and radius `r` to `dir/name`.
fn disc(dir: &Path, name: &str, x: f64, r: f64) -> String {
    let path = dir.join(name);
    let text = format!(r#"{{"curves": [{{"circle": {{"center": [{x}, 0], "radius": {r}}}}}]}}"#);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// Runs `inrs fractions` with `args`, asserting success.
fn fractions_ok(args: &[&str]) {
    let out = inrs(&[&["fractions"][..], args].concat());
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The grid of the tests: 40 x 30 cells of 0.1 x 0.1 on `[-2, 2] x [-1.5, 1.5]`.
const GRID: &str = "--grid=-2,2,40,-1.5,1.5,30";
const CELL_AREA: f64 = 0.1 * 0.1;
const NX: usize = 40;
const NY: usize = 30;

/// Every extra output.
const ALL: [&str; 4] = [
    "--centroids",
    "--apertures",
    "--boundary",
    "--face-centroids",
];

/// The extra files and their shapes on one grid, without the leading axis.
fn extra_files() -> [(&'static str, Vec<usize>); 9] {
    [
        ("", vec![NY, NX]),
        (".centroids", vec![NY, NX, 2]),
        (".x_apertures", vec![NY, NX + 1]),
        (".y_apertures", vec![NY + 1, NX]),
        (".boundary_lengths", vec![NY, NX]),
        (".boundary_centroids", vec![NY, NX, 2]),
        (".boundary_normals", vec![NY, NX, 2]),
        (".x_face_centroids", vec![NY, NX + 1]),
        (".y_face_centroids", vec![NY + 1, NX]),
    ]
}

/// `dir/<stem><what>.npy`.
fn file(dir: &Path, stem: &str, what: &str) -> PathBuf {
    dir.join(format!("{stem}{what}.npy"))
}

/// The data bytes of a `.npy` file (after its header).
fn data_bytes(path: &Path) -> Vec<u8> {
    let bytes = std::fs::read(path).unwrap();
    let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    bytes[10 + header_len..].to_vec()
}

/// Two unit discs at `x = -0.5` and `x = 0.5`: with replacement the first keeps its disc
/// minus the lens `2 pi / 3 - sqrt(3) / 2` the second takes, the second is its whole disc;
/// a cell's two fractions sum to at most 1; every file has the leading axis of 2; the last
/// material equals a run with its domain alone byte for byte.
#[test]
fn two_discs_replace_as_the_closed_forms_say() {
    let dir = scratch("two_discs");
    let (a, b) = (
        disc(&dir, "a.json", -0.5, 1.0),
        disc(&dir, "b.json", 0.5, 1.0),
    );
    let out = dir.join("m.npy");
    let args = [
        &["--domain", &a, "--domain", &b, GRID][..],
        &ALL,
        &["--output", out.to_str().unwrap()],
    ]
    .concat();
    fractions_ok(&args);
    for (what, shape) in extra_files() {
        let (got, _) = read_npy(&file(&dir, "m", what));
        assert_eq!(got, [&[2][..], &shape].concat(), "{what}");
    }
    let (_, f) = read_npy(&out);
    let (f0, f1) = f.split_at(NX * NY);
    let total = |f: &[f64]| f.iter().sum::<f64>() * CELL_AREA;
    let lens = 2.0 * PI / 3.0 - 0.75f64.sqrt();
    assert!((total(f0) - (PI - lens)).abs() < 1e-12, "{}", total(f0));
    assert!((total(f1) - PI).abs() < 1e-12, "{}", total(f1));
    for (x, y) in f0.iter().zip(f1) {
        assert!(x + y <= 1.0 + 1e-12, "{x} + {y}");
    }
    // The last material is its domain as given.
    let alone = dir.join("b_alone.npy");
    let args = [
        &["--domain", &b, GRID][..],
        &ALL,
        &["--output", alone.to_str().unwrap()],
    ]
    .concat();
    fractions_ok(&args);
    for (what, _) in extra_files() {
        let both = data_bytes(&file(&dir, "m", what));
        let one = data_bytes(&file(&dir, "b_alone", what));
        assert_eq!(both[both.len() / 2..], one[..], "{what}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `--no-replace`: each material's slice of every file is a one-domain run's data, byte for
/// byte; one domain gives the same files with or without `--no-replace`, without a leading
/// axis.
#[test]
fn no_replace_slices_are_one_domain_runs_and_one_domain_is_unchanged() {
    let dir = scratch("no_replace");
    let domains = [
        disc(&dir, "a.json", -0.5, 1.0),
        disc(&dir, "b.json", 0.5, 1.0),
        disc(&dir, "c.json", 0.25, 0.6),
    ];
    let out = dir.join("m.npy");
    let mut args = vec![];
    for d in &domains {
        args.extend(["--domain", d.as_str()]);
    }
    args.extend([GRID, "--no-replace"]);
    args.extend(ALL);
    args.extend(["--output", out.to_str().unwrap()]);
    fractions_ok(&args);
    for (k, d) in domains.iter().enumerate() {
        for (flags, stem) in [
            (&[][..], format!("one{k}")),
            (&["--no-replace"], format!("nr{k}")),
        ] {
            let path = dir.join(format!("{stem}.npy"));
            let args = [
                &["--domain", d, GRID][..],
                &ALL,
                flags,
                &["--output", path.to_str().unwrap()],
            ]
            .concat();
            fractions_ok(&args);
        }
        for (what, shape) in extra_files() {
            let one = file(&dir, &format!("one{k}"), what);
            // One domain: the shapes of the grid, and --no-replace changes nothing.
            assert_eq!(read_npy(&one).0, shape, "{what}");
            assert_eq!(
                std::fs::read(&one).unwrap(),
                std::fs::read(file(&dir, &format!("nr{k}"), what)).unwrap(),
                "{what}"
            );
            let all = data_bytes(&file(&dir, "m", what));
            let n = all.len() / 3;
            assert_eq!(all[k * n..(k + 1) * n], data_bytes(&one)[..], "{k} {what}");
        }
    }
    // Plain overlaps: both unit discs whole.
    let (_, f) = read_npy(&out);
    for slice in f.chunks(NX * NY).take(2) {
        assert!((slice.iter().sum::<f64>() * CELL_AREA - PI).abs() < 1e-12);
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Two copies of one disc: the second replaces the first everywhere, which is then zeros,
/// with NaN centroids (no covered part) and no boundary.
#[test]
fn a_domain_replaced_everywhere_is_zeros_and_nan() {
    let dir = scratch("replaced");
    let (a, b) = (
        disc(&dir, "a.json", 0.0, 1.0),
        disc(&dir, "b.json", 0.0, 1.0),
    );
    let out = dir.join("m.npy");
    let args = [
        &["--domain", &a, "--domain", &b, GRID][..],
        &ALL,
        &["--output", out.to_str().unwrap()],
    ]
    .concat();
    fractions_ok(&args);
    let first = |what: &str| {
        let (_, v) = read_npy(&file(&dir, "m", what));
        let half = v.len() / 2;
        (v[..half].to_vec(), v[half..].to_vec())
    };
    let (f0, f1) = first("");
    assert!(f0.iter().all(|&f| f == 0.0), "{f0:?}");
    assert!((f1.iter().sum::<f64>() * CELL_AREA - PI).abs() < 1e-12);
    assert!(first(".centroids").0.iter().all(|c| c.is_nan()));
    assert!(first(".boundary_lengths").0.iter().all(|&l| l == 0.0));
    assert!(first(".boundary_normals").0.iter().all(|n| n.is_nan()));
    assert!(first(".x_apertures").0.iter().all(|&a| a == 0.0));
    assert!(first(".y_face_centroids").0.iter().all(|c| c.is_nan()));
    std::fs::remove_dir_all(&dir).ok();
}

/// A domain that cannot be read, an open one, one across the axis of revolution: one line
/// naming the domain and its material, no file written.
#[test]
fn errors_name_the_domain_and_leave_no_file() {
    let dir = scratch("errors");
    let a = disc(&dir, "a.json", -0.5, 1.0);
    let b = disc(&dir, "b.json", 0.5, 1.0);
    let right = disc(&dir, "right.json", 1.5, 0.5);
    let open = dir.join("open.json");
    std::fs::write(
        &open,
        r#"{"curves": [{"degree": 1, "control_points": [[0, 0], [1, 0]]}]}"#,
    )
    .unwrap();
    let missing = dir.join("missing.json");
    let out = dir.join("f.npy");
    let run = |domains: &[&str], extra: &[&str]| {
        let mut args = vec!["fractions"];
        for d in domains {
            args.extend(["--domain", d]);
        }
        args.extend(extra);
        args.extend(["--centroids", "--output", out.to_str().unwrap()]);
        let o = inrs(&args);
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert_eq!(
            common::entries(&dir),
            ["a.json", "b.json", "open.json", "right.json"],
            "{err}"
        );
        err
    };
    let err = run(&[&a, missing.to_str().unwrap()], &[GRID]);
    assert!(
        err.starts_with(&format!(
            "inrs: --domain {} (material 1): ",
            missing.display()
        )),
        "{err}"
    );
    assert_eq!(err.matches("missing.json").count(), 1, "{err}");
    let err = run(&[&a, &b, open.to_str().unwrap()], &[GRID]);
    assert!(
        err.starts_with(&format!("inrs: --domain {} (material 2): ", open.display())),
        "{err}"
    );
    assert!(err.contains("open boundary"), "{err}");
    // Revolved about y on x >= 0: the disc at -0.5 crosses the axis, the one at 1.5 does not.
    let err = run(
        &[&right, &a],
        &["--grid=0,2,8,-1,1,8", "--axisymmetric", "y"],
    );
    assert!(
        err.starts_with(&format!(
            "inrs: --domain {a} (material 1): --axisymmetric y: "
        )),
        "{err}"
    );
    assert!(err.contains("crosses the axis"), "{err}");
    // Planar-only outputs revolved: the options' fault, not a domain's.
    let err = run(
        &[&right, &b],
        &["--grid=0,2,8,-1,1,8", "--axisymmetric", "y", "--boundary"],
    );
    assert!(err.starts_with("inrs: --axisymmetric y: "), "{err}");
    assert!(err.contains("planar cells only"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
