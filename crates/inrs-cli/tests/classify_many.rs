//! `inrs classify` against several domains: `--domain` repeated and `part.step#face:*`. Every
//! column equals the single-domain run on that domain; domains that cannot be read or
//! prepared fail the run naming them, or are left out with `--skip-unreadable`.

mod common;

use common::{fixture, inrs, inrs_ok, last_column, temp_file};

const PAPER: [&str; 6] = [
    "inrs-paper/circle.json",
    "inrs-paper/l_shape.json",
    "inrs-paper/leaf_cubic.json",
    "inrs-paper/s3_m_shape.json",
    "inrs-paper/s4_disk_ellipse_segment.json",
    "inrs-paper/s5_lune.json",
];

/// Points over `[-1.2, 1.2]^2` (golden-ratio steps) and some on the unit circle (the boundary
/// of circle.json), as CSV text.
fn points_csv(n: usize) -> String {
    let mut s = String::from("x,y\n");
    for i in 0..n {
        let t = i as f64 * 0.618_033_988_749_895;
        s += &format!(
            "{},{}\n",
            2.4 * t.fract() - 1.2,
            2.4 * (t * 1.7).fract() - 1.2
        );
    }
    for k in 0..16 {
        let a = k as f64 * std::f64::consts::TAU / 16.0;
        s += &format!("{},{}\n", a.cos(), a.sin());
    }
    s
}

/// The columns of a CSV output after `x,y`: its header fields and its rows' fields.
fn columns(text: &str) -> (Vec<String>, Vec<Vec<String>>) {
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .skip(2)
        .map(str::to_string)
        .collect();
    let mut cols = vec![Vec::new(); header.len()];
    for line in lines {
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), header.len() + 2, "{line}");
        for (c, f) in cols.iter_mut().zip(&fields[2..]) {
            c.push(f.to_string());
        }
    }
    (header, cols)
}

/// Every column of a several-domain run is the single-domain run's `location` column, for
/// every method; the coordinates are echoed as written; headers are the file names.
#[test]
fn every_column_is_the_single_domain_answer() {
    let points = temp_file("many.csv", &points_csv(3000));
    let domains: Vec<String> = PAPER.iter().map(|d| fixture(d)).collect();
    for method in ["fast", "inrs1", "inrs2", "gwn"] {
        let mut args = vec!["classify", "--points", &points, "--method", method];
        for d in &domains {
            args.extend(["--domain", d]);
        }
        let many = inrs_ok(&args);
        let (header, cols) = columns(&many);
        let names: Vec<&str> = PAPER.iter().map(|d| &d["inrs-paper/".len()..]).collect();
        assert_eq!(header, names);
        for (d, col) in domains.iter().zip(&cols) {
            let one = inrs_ok(&[
                "classify", "--domain", d, "--points", &points, "--method", method,
            ]);
            assert_eq!(&last_column(&one), col, "{d} {method}");
        }
        // The points as written.
        let text = points_csv(3000);
        let given: Vec<&str> = text.lines().skip(1).collect();
        let echoed: Vec<String> = many
            .lines()
            .skip(1)
            .map(|l| l.splitn(3, ',').take(2).collect::<Vec<_>>().join(","))
            .collect();
        assert_eq!(echoed, given);
        assert!(
            cols[0].iter().any(|l| l == "boundary"),
            "circle points on the circle"
        );
    }
}

/// `part.step#face:*` is every face of the part, labelled `face:K`, each the column
/// `part.step#face:K` gives; the `.npy` output is int8 of shape (points, domains), row by row.
#[test]
fn all_faces_of_a_part_and_npy_output() {
    let plate = fixture("cad/plate.step");
    let all = format!("{plate}#face:*");
    let points = temp_file("uv.csv", "x,y\n1,1\n5,5\n0.5,0.5\n0,3\n-1,-1\n");
    let many = inrs_ok(&["classify", "--domain", &all, "--points", &points]);
    let one = inrs_ok(&[
        "classify",
        "--domain",
        &format!("{plate}#face:0"),
        "--points",
        &points,
    ]);
    let (header, cols) = columns(&many);
    assert_eq!(header, ["face:0"]);
    assert_eq!(cols[0], last_column(&one));
    assert_eq!(
        cols[0],
        ["inside", "outside", "inside", "boundary", "outside"]
    );

    let lune = fixture("inrs-paper/s5_lune.json");
    let out = temp_file("many.npy", "");
    inrs_ok(&[
        "classify", "--domain", &lune, "--domain", &all, "--points", &points, "--output", &out,
    ]);
    let bytes = std::fs::read(&out).unwrap();
    let header = String::from_utf8_lossy(&bytes[..inrs::NPY_HEADER_BYTES]).into_owned();
    assert!(header.contains("'descr': '|i1'"), "{header}");
    assert!(header.contains("'shape': (5, 2)"), "{header}");
    let data = &bytes[inrs::NPY_HEADER_BYTES..];
    let csv = inrs_ok(&[
        "classify", "--domain", &lune, "--domain", &all, "--points", &points,
    ]);
    let (header, cols) = columns(&csv);
    assert_eq!(header, ["s5_lune.json", "plate.step#face:0"]);
    let code = |w: &str| match w {
        "outside" => 0u8,
        "inside" => 1,
        "boundary" => 2,
        other => panic!("{other}"),
    };
    let want: Vec<u8> = (0..5)
        .flat_map(|i| cols.iter().map(move |c| code(&c[i])))
        .collect();
    assert_eq!(data, want);
}

/// A domain that cannot be prepared (an open arc for inRS) or read (no such file) fails the
/// run naming it; with `--skip-unreadable` its column is left out and standard error names
/// it; with nothing left the run fails.
#[test]
fn bad_domains_fail_or_are_skipped() {
    let open = temp_file(
        "open-arc.json",
        r#"{"curves": [{"arc": {"center": [0, 0], "radius": 1, "start_angle": 0, "sweep": 5.5}}]}"#,
    );
    let missing = temp_file("gone.json", "");
    std::fs::remove_file(&missing).unwrap();
    let circle = fixture("inrs-paper/circle.json");
    let points = temp_file("p.csv", "0,0\n2,0\n");
    for bad in [&open, &missing] {
        let args = [
            "classify", "--domain", &circle, "--domain", bad, "--points", &points,
        ];
        let out = inrs(&args);
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        let name = std::path::Path::new(bad)
            .file_name()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        assert!(err.contains(&name), "{err}");
        let mut skip = args.to_vec();
        skip.push("--skip-unreadable");
        let out = inrs(&skip);
        assert!(out.status.success());
        assert_eq!(
            String::from_utf8(out.stdout).unwrap(),
            "x,y,circle.json\n0,0,inside\n2,0,outside\n"
        );
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        assert!(err.contains("skipped") && err.contains(&name), "{err}");
    }
    // The open arc is a domain for the winding-number method.
    let gwn = inrs_ok(&[
        "classify", "--domain", &circle, "--domain", &open, "--points", &points, "--method", "gwn",
    ]);
    assert_eq!(
        gwn,
        "x,y,circle.json,open-arc.json\n0,0,inside,inside\n2,0,outside,outside\n"
    );
    let out = inrs(&[
        "classify",
        "--domain",
        &open,
        "--domain",
        &missing,
        "--points",
        &points,
        "--skip-unreadable",
    ]);
    assert!(!out.status.success());
}
