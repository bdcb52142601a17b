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

/// Point `i` of the long streams below: over `[-1.5, 1.5]^2`, as `x,y`.
fn long_line(i: usize) -> String {
    let t = i as f64 * 0.618_033_988_749_895;
    format!("{},{}", 1.5 * t.sin(), 1.5 * (t * 1.7).cos())
}

/// Several domains stream as one does: a long file read in runs gives each column the
/// single-domain answers in input order, to a file or as `.npy`; a bad line far into it fails
/// the run naming that line, and leaves no output.
#[test]
fn long_streams_keep_their_order_and_fail_at_the_right_line() {
    let n = 120_000;
    let mut text = String::from("x,y\n");
    for i in 0..n {
        text += &long_line(i);
        text.push('\n');
    }
    let points = temp_file("long.csv", &text);
    let (circle, lune) = (
        fixture("inrs-paper/circle.json"),
        fixture("inrs-paper/s5_lune.json"),
    );
    let both = ["--domain", &circle, "--domain", &lune, "--points", &points];
    let many = inrs_ok(&[&["classify"][..], &both].concat());
    let (header, cols) = columns(&many);
    assert_eq!(header, ["circle.json", "s5_lune.json"]);
    for (d, col) in [&circle, &lune].into_iter().zip(&cols) {
        let one = inrs_ok(&["classify", "--domain", d, "--points", &points]);
        assert_eq!(&last_column(&one), col, "{d}");
    }
    for (i, row) in many.lines().skip(1).enumerate() {
        assert!(
            row.starts_with(&format!("{},", long_line(i))),
            "row {i}: {row}"
        );
    }
    // `.npy` out: int8 of shape (points, domains), row by row.
    let out = temp_file("long-out.npy", "");
    inrs_ok(&[&["classify"][..], &both, &["--output", &out]].concat());
    let bytes = std::fs::read(&out).unwrap();
    let header = String::from_utf8_lossy(&bytes[..inrs::NPY_HEADER_BYTES]).into_owned();
    assert!(header.contains(&format!("'shape': ({n}, 2)")), "{header}");
    let code = |w: &str| {
        ["outside", "inside", "boundary"]
            .iter()
            .position(|c| *c == w)
    };
    let want: Vec<u8> = (0..n)
        .flat_map(|i| cols.iter().map(move |c| code(&c[i]).unwrap() as u8))
        .collect();
    assert!(bytes[inrs::NPY_HEADER_BYTES..] == want[..], "npy data");
    // Line 100 001 (point 100 000) spoiled.
    let spoiled = text.replacen(&format!("\n{}\n", long_line(99_999)), "\n0.5,oops\n", 1);
    assert_ne!(spoiled, text);
    let bad = temp_file("long-bad.csv", &spoiled);
    for output in ["long-bad-out.csv", "long-bad-out.npy"] {
        let out = temp_file(output, "");
        std::fs::remove_file(&out).unwrap();
        let run = inrs(&[
            "classify", "--domain", &circle, "--domain", &lune, "--points", &bad, "--output", &out,
        ]);
        assert!(!run.status.success());
        let err = String::from_utf8_lossy(&run.stderr);
        assert!(
            err.contains("line 100001: \"oops\" is not a number"),
            "{err}"
        );
        assert!(
            !std::path::Path::new(&out).exists(),
            "a failed run left {out}"
        );
    }
}

/// `.npy` points against several domains: each column is the single-domain answer, the
/// coordinates written as the single-domain run writes them (shortest round trip).
#[test]
fn npy_points_stream_against_several_domains() {
    let n = 40_000;
    let mut bytes = inrs::npy_header(inrs::NpyType::F64, &[n, 2]);
    let mut csv = String::from("x,y\n");
    for i in 0..n {
        let t = i as f64 * 0.618_033_988_749_895;
        let (x, y) = (1.5 * t.sin(), 1.5 * (t * 1.7).cos());
        bytes.extend(x.to_le_bytes().into_iter().chain(y.to_le_bytes()));
        csv += &format!("{x},{y}\n");
    }
    let npy = temp_file("pts-many.npy", "");
    std::fs::write(&npy, &bytes).unwrap();
    let domains: Vec<String> = PAPER.iter().map(|d| fixture(d)).collect();
    let mut args = vec!["classify", "--points", &npy];
    for d in &domains {
        args.extend(["--domain", d]);
    }
    let many = inrs_ok(&args);
    let (_, cols) = columns(&many);
    assert_eq!(cols.len(), PAPER.len());
    let csv_points = temp_file("pts-many.csv", &csv);
    for (d, col) in domains.iter().zip(&cols) {
        let one = inrs_ok(&["classify", "--domain", d, "--points", &npy]);
        assert_eq!(&last_column(&one), col, "{d}");
        let from_csv = inrs_ok(&["classify", "--domain", d, "--points", &csv_points]);
        assert_eq!(&last_column(&from_csv), col, "{d} from CSV");
        let xy = |text: &str| -> Vec<String> {
            text.lines()
                .skip(1)
                .map(|l| l.splitn(3, ',').take(2).collect::<Vec<_>>().join(","))
                .collect()
        };
        assert_eq!(xy(&one), xy(&many));
    }
}

/// The peak resident memory of process `pid` so far, in KiB (Linux).
#[cfg(target_os = "linux")]
fn peak_kib(pid: u32) -> u64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap();
    let line = status.lines().find(|l| l.starts_with("VmHWM:")).unwrap();
    line.split_whitespace().nth(1).unwrap().parse().unwrap()
}

/// Several domains, points from a pipe: the peak memory after a million more points is what
/// it was after the first hundred thousand (holding them would take some 100 MB), and every
/// row comes out.
#[cfg(target_os = "linux")]
#[test]
fn several_domains_stream_a_pipe_in_bounded_memory() {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let (circle, lune) = (
        fixture("inrs-paper/circle.json"),
        fixture("inrs-paper/s5_lune.json"),
    );
    let out = temp_file("piped-out.npy", "");
    let mut child = Command::new(env!("CARGO_BIN_EXE_inrs"))
        .args(["classify", "--domain", &circle, "--domain", &lune])
        .args(["--points", "/dev/stdin", "--output", &out])
        .stdin(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    let mut write = |from: usize, to: usize| {
        let mut block = String::new();
        for i in from..to {
            block += &long_line(i);
            block.push('\n');
            if block.len() > 1 << 16 || i + 1 == to {
                stdin.write_all(block.as_bytes()).unwrap();
                block.clear();
            }
        }
    };
    let (first, all) = (100_000, 1_100_000);
    write(0, first);
    // The reader is at most a pipe's buffer and its runs behind the writer.
    let early = peak_kib(child.id());
    write(first, all);
    let late = peak_kib(child.id());
    drop(stdin);
    let run = child.wait_with_output().unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(
        late < early + 16 * 1024,
        "peak memory grew from {early} KiB to {late} KiB over a million points"
    );
    let bytes = std::fs::metadata(&out).unwrap().len() as usize;
    assert_eq!(bytes, inrs::NPY_HEADER_BYTES + 2 * all);
}
