//! The `inrs` binary: output on good input, one-line errors and non-zero exit on bad input, and
//! figures (`mesh`, `fit`, `convex-domain` `--svg`) with axes, a legend and their caption.

use std::process::Command;

mod common;
use common::{fixture, inrs, inrs_ok, last_column, stdout_of_success, temp_file};

/// `inrs classify` of a points file against a domain: the location column, in order.
fn classify_locations(domain: &str, points: &str) -> Vec<String> {
    inrs_ok(&["classify", "--domain", domain, "--points", points])
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap_or("").to_string())
        .collect()
}

#[test]
fn info_prints_a_summary() {
    let out = inrs(&[
        "info",
        "--domain",
        &fixture("inrs-paper/s4_disk_ellipse_segment.json"),
    ]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.starts_with("S(4): domain defined by a disk, an ellipse, a segment\n"),
        "{text}"
    );
    assert!(
        text.contains("curves: 3  Bezier pieces: 4  max degree: 2  rational"),
        "{text}"
    );
    assert!(
        text.contains(
            "loop 0: curves 0..=2  closed  counter-clockwise  signed area 2.07079632679\n"
        ),
        "{text}"
    );
    // Twelve significant digits: pi - 1 + (area of the segment) rounded, no digits of noise.
    assert!(
        text.contains("filled area (even-odd): 2.07079632679\n"),
        "{text}"
    );
    assert!(
        text.contains("bounding box: [-0.5, 1] x [-1, 1]\n"),
        "{text}"
    );
}

#[test]
fn classify_writes_csv_in_input_order_with_points_echoed() {
    let points = temp_file(
        "pts.csv",
        "x,y\n# centre, outside, on the circle\n0,0\n2.0 , 0\n1,0\n0.6,0.8\n1e-1,-0.0\n",
    );
    for method in ["inrs1", "inrs2"] {
        let out = inrs(&[
            "classify",
            "--domain",
            &fixture("inrs-paper/circle.json"),
            "--points",
            &points,
            "--method",
            method,
        ]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert_eq!(
            String::from_utf8(out.stdout).unwrap(),
            "x,y,location\n0,0,inside\n2.0,0,outside\n1,0,boundary\n0.6,0.8,boundary\n1e-1,-0.0,inside\n"
        );
    }
}

#[test]
fn classify_output_file_and_tolerance() {
    let points = temp_file("near.csv", "1.0000001,0\n");
    let out_path = temp_file("out.csv", "");
    let domain = fixture("inrs-paper/circle.json");
    let out = inrs(&[
        "classify", "--domain", &domain, "--points", &points, "--output", &out_path,
    ]);
    assert!(out.status.success());
    assert!(out.stdout.is_empty());
    assert_eq!(
        std::fs::read_to_string(&out_path).unwrap(),
        "x,y,location\n1.0000001,0,outside\n"
    );
    // A looser tolerance (1e-6 x diagonal 2.83 > 1e-7) makes the same point boundary.
    let out = inrs(&[
        "classify", "--domain", &domain, "--points", &points, "--tol", "1e-6",
    ]);
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        "x,y,location\n1.0000001,0,boundary\n"
    );
}

#[test]
fn bad_input_gives_one_line_errors() {
    let good_points = temp_file("good.csv", "0,0\n");
    let bad_points = temp_file("bad.csv", "0,0\n1\n");
    let nan_points = temp_file("nan.csv", "0,0\nNaN,1\n");
    let circle = fixture("inrs-paper/circle.json");
    let malformed = fixture("bad/malformed.json");
    let negative = fixture("bad/negative_weight.json");
    let open = fixture("bad/open_loop.json");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["info", "--domain", "/nonexistent/d.json"],
            "/nonexistent/d.json",
        ),
        (
            vec!["info", "--domain", &malformed],
            "invalid JSON at line 3",
        ),
        (vec!["info", "--domain", &negative], "curve 0: weight 1"),
        (
            vec!["info", "--require-closed", "--domain", &open],
            "open boundary",
        ),
        (
            vec![
                "classify",
                "--domain",
                "/nonexistent/d.json",
                "--points",
                &good_points,
            ],
            "/nonexistent/d.json",
        ),
        (
            vec!["classify", "--domain", &malformed, "--points", &good_points],
            "invalid JSON at line 3",
        ),
        (
            vec!["classify", "--domain", &open, "--points", &good_points],
            "open boundary: the loop of curves 0..=2",
        ),
        (
            vec![
                "classify",
                "--domain",
                &circle,
                "--points",
                "/nonexistent/p.csv",
            ],
            "/nonexistent/p.csv",
        ),
        (
            vec!["classify", "--domain", &circle, "--points", &bad_points],
            "line 2: expected at least two numbers",
        ),
        (
            vec!["classify", "--domain", &circle, "--points", &nan_points],
            "line 2: \"NaN\" is not a finite number",
        ),
        (
            vec![
                "classify",
                "--domain",
                &circle,
                "--points",
                &good_points,
                "--tol",
                "-1",
            ],
            "-1 must be finite and >= 0",
        ),
        (
            vec![
                "classify",
                "--domain",
                &circle,
                "--points",
                &good_points,
                "--subdivisions",
                "0",
            ],
            "0 is out of range: expected 1 to 4096",
        ),
    ];
    for (args, needle) in cases {
        let out = inrs(&args);
        assert!(!out.status.success(), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(
            err.starts_with("inrs: ") && err.contains(needle),
            "{args:?}: {err}"
        );
    }
    // An unknown method is rejected by the argument parser (non-zero exit, message names it).
    let out = inrs(&[
        "classify",
        "--domain",
        &circle,
        "--points",
        &good_points,
        "--method",
        "magic",
    ]);
    assert!(!out.status.success());
    assert!(
        String::from_utf8(out.stderr)
            .unwrap()
            .contains("invalid value 'magic' for '--method <METHOD>'")
    );
}

#[test]
fn help_documents_the_tolerance() {
    let out = inrs(&["classify", "--help"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("--tol") && text.contains("Boundary tolerance"),
        "{text}"
    );
}

#[test]
fn winding_prints_the_field_with_round_trip_digits() {
    let points = temp_file("w.csv", "x,y\n0,0\n3,0\n1,0\n0.25,0.5\n");
    let text = inrs_ok(&[
        "winding",
        "--domain",
        &fixture("inrs-paper/circle.json"),
        "--points",
        &points,
    ]);
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("x,y,winding"));
    let values: Vec<f64> = lines
        .map(|l| l.rsplit(',').next().unwrap().parse().unwrap())
        .collect();
    let expected = [1.0, 0.0, 0.5, 1.0];
    for (v, e) in values.iter().zip(expected) {
        assert!((v - e).abs() < 1e-14, "{text}");
    }
    // Every algorithm gives the same field away from the curve.
    for alg in ["binary-search", "bezier-clipping"] {
        let out = inrs(&[
            "winding",
            "--domain",
            &fixture("inrs-paper/circle.json"),
            "--points",
            &temp_file("w2.csv", "0.1,0.2\n2,2\n"),
            "--algorithm",
            alg,
        ]);
        let text = String::from_utf8(out.stdout).unwrap();
        let v: Vec<f64> = text
            .lines()
            .skip(1)
            .map(|l| l.rsplit(',').next().unwrap().parse().unwrap())
            .collect();
        assert!(
            (v[0] - 1.0).abs() < 1e-12 && v[1].abs() < 1e-12,
            "{alg}: {text}"
        );
    }
}

#[test]
fn gwn_accepts_open_collections_and_fill_rules() {
    // An open arc (no closure) and a doubly wound circle.
    let open = temp_file(
        "open.json",
        r#"{"curves": [{"arc": {"center": [0, 0], "radius": 1, "start_angle": 0, "sweep": 5.5}}]}"#,
    );
    let twice = temp_file(
        "twice.json",
        r#"{"curves": [{"arc": {"center": [0, 0], "radius": 1, "start_angle": 0, "sweep": 12.566370614359172}}]}"#,
    );
    let points = temp_file("o.csv", "0,0\n2,0\n");
    // inRS refuses the open arc; gwn classifies (the centre sees 5.5 / 2pi ~ 0.88 -> 1).
    let out = inrs(&["classify", "--domain", &open, "--points", &points]);
    assert!(!out.status.success());
    let out = inrs(&[
        "classify", "--domain", &open, "--points", &points, "--method", "gwn",
    ]);
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        "x,y,location\n0,0,inside\n2,0,outside\n"
    );
    // Winding 2 at the centre: outside by even-odd, inside by nonzero.
    let out = inrs(&[
        "classify", "--domain", &twice, "--points", &points, "--method", "gwn",
    ]);
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        "x,y,location\n0,0,outside\n2,0,outside\n"
    );
    let out = inrs(&[
        "classify",
        "--domain",
        &twice,
        "--points",
        &points,
        "--method",
        "gwn",
        "--fill-rule",
        "nonzero",
    ]);
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        "x,y,location\n0,0,inside\n2,0,outside\n"
    );
    // The crossing methods and gwn agree on a closed fixture.
    let pts = temp_file("agree.csv", "0.1,0.1\n0.9,0.9\n-0.2,0.3\n0.5,-0.6\n");
    let domain = fixture("inrs-paper/s5_lune.json");
    let outputs: Vec<String> = ["inrs1", "inrs2", "gwn"]
        .iter()
        .map(|m| {
            String::from_utf8(
                inrs(&[
                    "classify", "--domain", &domain, "--points", &pts, "--method", m,
                ])
                .stdout,
            )
            .unwrap()
        })
        .collect();
    assert_eq!(outputs[0], outputs[1]);
    assert_eq!(outputs[0], outputs[2]);
}

#[test]
fn svg_dxf_and_font_domains_are_accepted_wherever_json_is() {
    let points = temp_file(
        "io-pts.csv",
        "x,y\n20,20\n40,38\n40,30\n75,30\n110,75\n15,12\n5,10\n",
    );
    // The plate: inside, the round hole's centre, on the hole's circle, in the slot, outside,
    // inside the rounded corner, outside it.
    assert_eq!(
        classify_locations(&fixture("io/gear.svg"), &points),
        [
            "inside", "outside", "boundary", "outside", "outside", "inside", "outside"
        ]
    );

    // DXF: a bulged slot with a circular hole and a periodic cubic spline hole.
    let points = temp_file(
        "io-pts2.csv",
        "x,y\n5,5\n10,10\n28,10\n-4,10\n45,10\n51,10\n",
    );
    assert_eq!(
        classify_locations(&fixture("io/plate.dxf"), &points),
        [
            "inside", "outside", "outside", "inside", "inside", "outside"
        ]
    );

    // Convert to JSON and back: the same summary.
    let json = std::env::temp_dir().join(format!("inrs-cli-{}/plate.json", std::process::id()));
    let json = json.display().to_string();
    let out = inrs(&[
        "convert",
        "--domain",
        &fixture("io/plate.dxf"),
        "--output",
        &json,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let a = inrs(&["info", "--domain", &fixture("io/plate.dxf")]).stdout;
    let b = inrs(&["info", "--domain", &json]).stdout;
    let strip = |t: Vec<u8>| {
        String::from_utf8(t)
            .unwrap()
            .lines()
            .skip(1)
            .collect::<Vec<_>>()
            .join("\n")
    };
    assert_eq!(strip(a), strip(b));

    let font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
    if std::path::Path::new(font).exists() {
        // 'o' in font units: the counter is outside, the ring inside.
        let points = temp_file("io-pts3.csv", "x,y\n600,560\n1000,560\n");
        let glyph = format!("{font}#o");
        let text = inrs_ok(&["classify", "--domain", &glyph, "--points", &points]);
        assert!(
            text.contains("600,560,outside") && text.contains("1000,560,inside"),
            "{text}"
        );
        let out = inrs(&["info", "--domain", font]);
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(!out.status.success() && err.contains("#B"), "{err}");
    } else {
        assert!(
            std::env::var("INRS_REQUIRE_SYSTEM_FILES").as_deref() != Ok("1"),
            "{font} is missing and INRS_REQUIRE_SYSTEM_FILES=1: install fonts-dejavu-core"
        );
        eprintln!("SKIPPED font part: {font} absent (install fonts-dejavu-core)");
    }

    let bad = temp_file(
        "bad.svg",
        "<svg xmlns='http://www.w3.org/2000/svg'>\n<path d='M 0 0 L 1'/></svg>",
    );
    let out = inrs(&["info", "--domain", &bad]);
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(!out.status.success(), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("<path> at line 2") && err.contains("number"),
        "{err}"
    );
}

#[test]
fn convex_domain_prints_the_papers_table_columns_and_an_svg() {
    let svg = std::env::temp_dir().join(format!("inrs-cli-{}-convex.svg", std::process::id()));
    let svg = svg.display().to_string();
    let text = inrs_ok(&[
        "convex-domain",
        "--curve",
        &fixture("convex/cubic.json"),
        "--free-index",
        "2",
        "--box=-10,10,-11,9",
        "--tol",
        "1e-4",
        "--svg",
        &svg,
    ]);
    assert!(text.contains("level  inequalities  vertices"), "{text}");
    // 4, 8, 16, ... inequalities (a cubic's numerator has degree 3).
    for (level, n) in [(0, 4), (1, 8), (2, 16), (5, 128)] {
        assert!(
            text.lines().any(|l| l
                .split_whitespace()
                .take(2)
                .eq([level.to_string(), n.to_string()])),
            "level {level}: {text}"
        );
    }
    assert!(text.contains("outcome: Converged"), "{text}");
    let figure = std::fs::read_to_string(&svg).unwrap();
    assert!(figure.starts_with("<svg") && figure.contains("level 5"));
    rs_testkit::assert_figure(&figure, "free control point", "convex-domain --svg");
    // The nested inner polygons and the outer bound are told apart in the legend.
    assert!(
        figure.contains("outer bound"),
        "no outer bound in the legend"
    );

    let text = inrs_ok(&[
        "convex-domain",
        "--curve",
        &fixture("convex/quintic_space.json"),
        "--free-index",
        "2",
        "--box=-100,100,-100,100,-100,100",
        "--max-level",
        "3",
    ]);
    assert!(
        text.starts_with("torsion sign") && text.contains("faces") && text.contains("volume"),
        "{text}"
    );

    for (args, want) in [
        (vec!["--free-index", "9", "--box=-1,1,-1,1"], "out of range"),
        (vec!["--free-index", "2", "--box=-1,1,-1"], "invalid box"),
        (
            vec!["--free-index", "2", "--box=-1,1,-1,1,-1,1"],
            "2-D but the box is 3-D",
        ),
        (
            vec!["--free-index", "2", "--box=-1,1,-1,1", "--sign", "up"],
            "--sign",
        ),
    ] {
        let mut all = vec!["convex-domain", "--curve"];
        let cubic = fixture("convex/cubic.json");
        all.push(&cubic);
        all.extend(args);
        let out = inrs(&all);
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(!out.status.success() && err.contains(want), "{want}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
}

#[test]
fn sample_and_mesh_write_points_and_curved_triangulations() {
    let domain = fixture("inrs-paper/s4_disk_ellipse_segment.json");
    let text = inrs_ok(&["sample", "--domain", &domain, "--ny", "10"]);
    assert!(text.starts_with("x,y,kind\n"));
    let boundary = text.lines().filter(|l| l.ends_with(",boundary")).count();
    let interior = text.lines().filter(|l| l.ends_with(",interior")).count();
    assert!(boundary > 10 && interior > 20, "{boundary} {interior}");
    // The sampled points classify as they are labelled.
    let pts = temp_file(
        "sampled.csv",
        &text
            .replace(",boundary", "")
            .replace(",interior", "")
            .replace("x,y,kind", "x,y"),
    );
    let want: Vec<&str> = text
        .lines()
        .skip(1)
        .map(|l| {
            if l.ends_with(",interior") {
                "inside"
            } else {
                "boundary"
            }
        })
        .collect();
    assert_eq!(classify_locations(&domain, &pts), want);

    let out = inrs(&[
        "sample", "--domain", &domain, "--method", "halton", "--count", "77",
    ]);
    assert!(out.status.success());
    assert_eq!(String::from_utf8(out.stdout).unwrap().lines().count(), 78);
    // --count alone asks for Halton points (it was ignored: the default lines came out).
    let halton = inrs_ok(&["sample", "--domain", &domain, "--count", "77"]);
    assert_eq!(halton.lines().count(), 78);
    assert!(halton.lines().skip(1).all(|l| l.ends_with(",interior")));

    let json = std::env::temp_dir().join(format!("inrs-cli-{}-mesh.json", std::process::id()));
    let svg = std::env::temp_dir().join(format!("inrs-cli-{}-mesh.svg", std::process::id()));
    let (json, svg) = (json.display().to_string(), svg.display().to_string());
    let out = inrs(&[
        "mesh", "--domain", &domain, "--ny", "8", "--output", &json, "--svg", &svg,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary = String::from_utf8(out.stderr).unwrap();
    assert!(
        summary.contains("curved triangles") && summary.contains("total area 2.0707963267"),
        "{summary}"
    );
    let m: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let nv = m["vertices"].as_array().unwrap().len();
    let tris = m["triangles"].as_array().unwrap();
    assert!(
        tris.iter()
            .flat_map(|t| t.as_array().unwrap())
            .all(|i| (i.as_u64().unwrap() as usize) < nv)
    );
    let curved = m["curved_edges"].as_array().unwrap();
    assert!(!curved.is_empty() && curved.iter().all(|c| c["u0"].as_f64() < c["u1"].as_f64()));
    let figure = std::fs::read_to_string(&svg).unwrap();
    assert!(figure.starts_with("<svg"));
    rs_testkit::assert_figure(&figure, "Curved triangulation:", "mesh --svg");

    for (args, want) in [
        (
            vec!["sample", "--domain", &domain, "--ny", "1"],
            "1 is out of range: expected 2 to 100000",
        ),
        (
            vec!["sample", "--domain", &domain, "--method", "grid"],
            "--method",
        ),
        (
            vec![
                "sample", "--domain", &domain, "--method", "lines", "--count", "5",
            ],
            "--count is for --method halton",
        ),
        (
            vec![
                "sample", "--domain", &domain, "--method", "halton", "--ny", "5",
            ],
            "--ny is for --method lines",
        ),
        (
            vec!["sample", "--domain", &domain, "--ny", "5", "--count", "5"],
            "cannot be used with",
        ),
        (
            vec!["mesh", "--domain", &domain, "--ny", "0"],
            "--ny <NY>': 0 is out of range: expected 2 to 100000",
        ),
    ] {
        let out = inrs(&args);
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(!out.status.success() && err.contains(want), "{want}: {err}");
    }
}

#[test]
fn svg_overlaps_follow_even_odd_by_default_and_nonzero_through_gwn() {
    // Two overlapping squares drawn in the same direction: their overlap has winding number 2.
    let svg = temp_file(
        "overlap.svg",
        "<svg xmlns='http://www.w3.org/2000/svg'><path d='M0 0h4v4h-4z M2 2h4v4h-4z'/></svg>",
    );
    let points = temp_file("overlap.csv", "x,y\n1,1\n3,3\n5,5\n7,7\n");
    assert_eq!(
        classify_locations(&svg, &points),
        ["inside", "outside", "inside", "outside"]
    );
    let text = inrs_ok(&[
        "classify",
        "--domain",
        &svg,
        "--points",
        &points,
        "--method",
        "gwn",
        "--fill-rule",
        "nonzero",
    ]);
    let got: Vec<&str> = text
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    assert_eq!(got, ["inside", "inside", "inside", "outside"]);
}

/// A `.npy` file of points, as `NumPy` writes one (version 1.0 header, C order).
fn npy_points(name: &str, points: &[(f64, f64)]) -> String {
    npy_points_of(name, inrs::NpyType::F64, points)
}

/// A `.npy` file of points with elements of type `ty` (float64, or float32 for points that
/// are float32 values).
fn npy_points_of(name: &str, ty: inrs::NpyType, points: &[(f64, f64)]) -> String {
    let mut bytes = inrs::npy_header(ty, &[points.len(), 2]);
    for &(x, y) in points {
        for v in [x, y] {
            if ty == inrs::NpyType::F32 {
                bytes.extend_from_slice(&(v as f32).to_le_bytes());
            } else {
                bytes.extend_from_slice(&v.to_le_bytes());
            }
        }
    }
    let path = std::path::Path::new(&temp_file(name, "")).to_path_buf();
    std::fs::write(&path, bytes).unwrap();
    path.display().to_string()
}

/// `n` points spread over `[-1, 1]^2` (golden-ratio steps).
fn spread_points(n: usize) -> Vec<(f64, f64)> {
    (0..n)
        .map(|i| {
            let t = i as f64 * 0.618_033_988_749_895;
            (2.0 * t.fract() - 1.0, 2.0 * (t * 1.7).fract() - 1.0)
        })
        .collect()
}

/// The data of a 1-D `.npy` output, after checking its header names `descr` and `n` values.
fn npy_data(path: &str, descr: &str, n: usize) -> Vec<u8> {
    let bytes = std::fs::read(path).unwrap();
    let header = String::from_utf8_lossy(&bytes[..inrs::NPY_HEADER_BYTES]).into_owned();
    assert!(header.starts_with("\u{fffd}NUMPY"), "{header}");
    assert!(header.contains(&format!("'descr': '{descr}'")), "{header}");
    assert!(header.contains(&format!("'shape': ({n},)")), "{header}");
    bytes[inrs::NPY_HEADER_BYTES..].to_vec()
}

/// `.npy` in and out: the same answers as CSV, int8 codes for classify, float64 for winding,
/// whatever the method, with the count written into the header once known (CSV in, `.npy`
/// out).
#[test]
fn npy_points_and_results_match_csv() {
    let domain = fixture("inrs-paper/s5_lune.json");
    let pts: Vec<(f64, f64)> = spread_points(70_000)
        .into_iter()
        .chain([(1.0, 0.0), (0.0, 0.0), (5.0, 5.0)])
        .collect();
    let csv_text: String = pts.iter().map(|(x, y)| format!("{x},{y}\n")).collect();
    let csv = temp_file("pts.csv", &csv_text);
    let npy = npy_points("pts.npy", &pts);
    let codes = |l: &str| match l {
        "outside" => 0u8,
        "inside" => 1,
        "boundary" => 2,
        other => panic!("{other}"),
    };
    for method in ["fast", "inrs2", "gwn"] {
        let expected: Vec<u8> = classify_locations(&domain, &csv)
            .iter()
            .map(|l| codes(l))
            .collect();
        assert!(expected.contains(&2) && expected.contains(&1) && expected.contains(&0));
        for input in [&npy, &csv] {
            let out = temp_file(&format!("out-{method}.npy"), "");
            inrs_ok(&[
                "classify", "--domain", &domain, "--points", input, "--method", method, "--output",
                &out,
            ]);
            assert_eq!(
                npy_data(&out, "|i1", pts.len()),
                expected,
                "{method} {input}"
            );
        }
        // .npy in, CSV out: the coordinates in shortest round-trip form.
        let text = inrs_ok(&[
            "classify", "--domain", &domain, "--points", &npy, "--method", method,
        ]);
        let rows: Vec<&str> = text.lines().skip(1).collect();
        assert_eq!(rows.len(), pts.len());
        for (row, (&(x, y), &e)) in rows.iter().zip(pts.iter().zip(&expected)) {
            let f: Vec<&str> = row.split(',').collect();
            assert_eq!(
                (f[0].parse::<f64>().unwrap(), f[1].parse::<f64>().unwrap()),
                (x, y)
            );
            assert_eq!(codes(f[2]), e);
        }
    }
    let out = temp_file("w.npy", "");
    inrs_ok(&[
        "winding", "--domain", &domain, "--points", &npy, "--output", &out,
    ]);
    let w: Vec<f64> = npy_data(&out, "<f8", pts.len())
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    let text = inrs_ok(&["winding", "--domain", &domain, "--points", &csv]);
    for (row, v) in text.lines().skip(1).zip(&w) {
        assert_eq!(row.rsplit(',').next().unwrap().parse::<f64>().unwrap(), *v);
    }
}

/// Coordinates read from `.npy` are echoed in shortest round-trip form at every magnitude
/// (plain, or with an exponent `e-7` / `e+16`), each reading back to the same `f64`.
#[test]
fn npy_coordinates_are_echoed_in_round_trip_form() {
    let pts = [
        (1e300, -5e-324),
        (1.5e16, 0.1),
        (-1e-7, 123_456.789),
        (2.0_f64.sqrt(), -0.0),
        (f64::MAX, f64::MIN_POSITIVE),
    ];
    let npy = npy_points("extremes.npy", &pts);
    let text = inrs_ok(&[
        "classify",
        "--domain",
        &fixture("inrs-paper/circle.json"),
        "--points",
        &npy,
    ]);
    let rows: Vec<&str> = text.lines().skip(1).collect();
    assert_eq!(
        rows.iter()
            .map(|r| r.rsplit_once(',').unwrap().0)
            .collect::<Vec<_>>(),
        [
            "1e+300,-5e-324",
            "1.5e+16,0.1",
            "-1e-7,123456.789",
            "1.4142135623730951,-0.0",
            "1.7976931348623157e+308,2.2250738585072014e-308",
        ]
    );
    for (row, (x, y)) in rows.iter().zip(pts) {
        let f: Vec<&str> = row.split(',').collect();
        let back = (f[0].parse::<f64>().unwrap(), f[1].parse::<f64>().unwrap());
        assert_eq!(
            (back.0.to_bits(), back.1.to_bits()),
            (x.to_bits(), y.to_bits())
        );
    }
}

/// Many chunks (a 6 MB CSV file of some 24 blocks, a `.npy` file of 5 ranges) come out in
/// input order whatever the number of workers, every point echoed and located as the unit
/// circle's analytic answer says (the points stay 1e-3 away from it); lines in other forms
/// (spaces, `\r\n`, comments) are mixed in.
#[test]
fn many_chunks_come_out_in_input_order_on_any_number_of_workers() {
    let n = 300_000;
    let pts: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let t = i as f64 * 0.618_033_988_749_895;
            let r = 0.3 + 1.2 * (t.fract() * 7.0).fract();
            let r = if (r - 1.0).abs() < 1e-3 { r + 2e-3 } else { r };
            let a = t * 0.001;
            (r * a.cos(), r * a.sin())
        })
        .collect();
    let mut text = String::from("x,y\n");
    for (i, (x, y)) in pts.iter().enumerate() {
        match i % 1000 {
            7 => text.push_str(&format!("{x} , {y}\n")),
            8 => text.push_str(&format!("{x},{y}\r\n# note\n")),
            _ => text.push_str(&format!("{x},{y}\n")),
        }
    }
    let csv = temp_file("ordered.csv", &text);
    let npy = npy_points("ordered.npy", &pts);
    let circle = fixture("inrs-paper/circle.json");
    let truth: Vec<&str> = pts
        .iter()
        .map(|&(x, y)| {
            if x.hypot(y) < 1.0 {
                "inside"
            } else {
                "outside"
            }
        })
        .collect();
    for workers in ["1", "3", "8"] {
        for input in [&csv, &npy] {
            let text = stdout_of_success(
                Command::new(env!("CARGO_BIN_EXE_inrs"))
                    .args(["classify", "--domain", &circle, "--points", input])
                    .env("RAYON_NUM_THREADS", workers)
                    .output()
                    .unwrap(),
            );
            let rows: Vec<&str> = text.lines().skip(1).collect();
            assert_eq!(rows.len(), n, "{workers} workers, {input}");
            for (i, (row, (&(x, y), want))) in rows.iter().zip(pts.iter().zip(&truth)).enumerate() {
                let f: Vec<&str> = row.split(',').collect();
                let echoed = (f[0].parse::<f64>().unwrap(), f[1].parse::<f64>().unwrap());
                assert_eq!(echoed, (x, y), "row {i}, {workers} workers, {input}");
                assert_eq!(f[2], *want, "row {i}, {workers} workers, {input}");
            }
        }
    }
}

/// A new empty directory `dir_name` beside the temporary files, holding a named pipe `name`:
/// `(directory, pipe)`.
#[cfg(unix)]
fn fresh_fifo(dir_name: &str, name: &str) -> (std::path::PathBuf, std::path::PathBuf) {
    let dir = std::path::Path::new(&temp_file("placeholder", "")).with_file_name(dir_name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join(name);
    assert!(
        Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .unwrap()
            .success(),
        "mkfifo"
    );
    (dir, fifo)
}

/// An output that is a pipe (or a device) is written in place, never replaced by a file.
#[cfg(unix)]
#[test]
fn outputs_to_pipes_are_written_in_place() {
    use std::os::unix::fs::FileTypeExt;
    let (dir, fifo) = fresh_fifo("fifo-test", "out.csv");
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read_to_string(fifo).unwrap())
    };
    let points = temp_file("fifo-points.csv", "0,0\n5,5\n");
    inrs_ok(&[
        "classify",
        "--domain",
        &fixture("inrs-paper/circle.json"),
        "--points",
        &points,
        "--output",
        &fifo.display().to_string(),
    ]);
    // Checked before waiting for the reader: were the pipe replaced, the reader would wait on
    // it for ever.
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
    assert_eq!(
        reader.join().unwrap(),
        "x,y,location\n0,0,inside\n5,5,outside\n"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A float32 `.npy` points file (large enough for the grid locator, which reads the points
/// straight from the file's bytes) classifies as the same points written as CSV.
#[test]
fn float32_npy_points_match_csv() {
    let domain = fixture("inrs-paper/s5_lune.json");
    // Float32 values, held exactly as float64.
    let pts: Vec<(f64, f64)> = spread_points(60_000)
        .into_iter()
        .map(|(x, y)| (f64::from(x as f32), f64::from(y as f32)))
        .collect();
    let npy = npy_points_of("pts32.npy", inrs::NpyType::F32, &pts);
    let csv_text: String = pts.iter().map(|(x, y)| format!("{x},{y}\n")).collect();
    let csv = temp_file("pts32.csv", &csv_text);
    let expected = classify_locations(&domain, &csv);
    assert!(expected.iter().any(|l| l == "inside") && expected.iter().any(|l| l == "outside"));
    let text = inrs_ok(&["classify", "--domain", &domain, "--points", &npy]);
    let got: Vec<&str> = text
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    assert_eq!(got, expected);
}

/// `.npy` points from a named pipe (which cannot be read by position) are read in order, with
/// the same answers as from a regular file.
#[cfg(unix)]
#[test]
fn npy_points_from_a_pipe_are_read_in_order() {
    let (dir, fifo) = fresh_fifo("fifo-npy-test", "points.npy");
    let pts: Vec<(f64, f64)> = (0..200_000)
        .map(|i| {
            let t = i as f64 * 0.754_877_666_246_692_7;
            (2.0 * t.fract() - 1.0, 2.0 * (t * 1.3).fract() - 1.0)
        })
        .collect();
    let file = npy_points("fifo-source.npy", &pts);
    let writer = {
        let (fifo, bytes) = (fifo.clone(), std::fs::read(&file).unwrap());
        std::thread::spawn(move || std::fs::write(fifo, bytes).unwrap())
    };
    let domain = fixture("inrs-paper/s5_lune.json");
    let (from_pipe, from_file) = (dir.join("pipe.npy"), dir.join("file.npy"));
    let run = |points: &str, out: &std::path::Path| {
        inrs_ok(&[
            "classify",
            "--domain",
            &domain,
            "--points",
            points,
            "--output",
            &out.display().to_string(),
        ])
    };
    run(&fifo.display().to_string(), &from_pipe);
    writer.join().unwrap();
    run(&file, &from_file);
    let (a, b) = (
        npy_data(&from_pipe.display().to_string(), "|i1", pts.len()),
        npy_data(&from_file.display().to_string(), "|i1", pts.len()),
    );
    assert!(a.contains(&0) && a.contains(&1));
    assert_eq!(a, b);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `inrs fit` then `inrs eval`: a polynomial of the spline's degree is reproduced exactly,
/// anywhere in the domain, with its gradient; points outside get `nan` and are counted; the
/// figures are SVG with their caption.
#[test]
fn fit_and_eval_reproduce_polynomials() {
    let domain = fixture("inrs-paper/s4_disk_ellipse_segment.json");
    let spline = temp_file("fit.json", "");
    let svg = temp_file("fit.svg", "");
    let err_svg = temp_file("fit-error.svg", "");
    for refine in ["none", "ct", "ps"] {
        let out = inrs(&[
            "fit",
            "--domain",
            &domain,
            "--ny",
            "5",
            "--degree",
            "3",
            "--refine",
            refine,
            "--function",
            "1 + 2*x - y^2 + x^2*y - 3*x*y",
            "--output",
            &spline,
            "--svg",
            &svg,
            "--error-svg",
            &err_svg,
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{err}");
        assert!(
            err.contains("degree 3") && err.contains("curved triangles"),
            "{err}"
        );
        let points = temp_file(
            "fit-points.csv",
            "x,y\n0.1,0.2\n-0.4,0.05\n0.99,0.001\n5,5\n",
        );
        let out = inrs(&[
            "eval",
            "--spline",
            &spline,
            "--points",
            &points,
            "--derivatives",
        ]);
        assert!(out.status.success());
        assert!(String::from_utf8_lossy(&out.stderr).contains("1 points outside"));
        let text = String::from_utf8(out.stdout).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("x,y,value,dx,dy"));
        for line in lines {
            let f: Vec<&str> = line.split(',').collect();
            let (x, y): (f64, f64) = (f[0].parse().unwrap(), f[1].parse().unwrap());
            if x == 5.0 {
                assert_eq!(&f[2..], ["nan", "nan", "nan"]);
                continue;
            }
            let v: Vec<f64> = f[2..].iter().map(|s| s.parse().unwrap()).collect();
            let want = [
                1.0 + 2.0 * x - y * y + x * x * y - 3.0 * x * y,
                2.0 + 2.0 * x * y - 3.0 * y,
                -2.0 * y + x * x - 3.0 * x,
            ];
            for (a, b) in v.iter().zip(want) {
                assert!((a - b).abs() < 1e-10, "{refine}: {line} vs {want:?}");
            }
        }
    }
    for (figure, caption, what) in [
        (&svg, "degree 3", "fit --svg"),
        (&err_svg, "error", "fit --error-svg"),
    ] {
        let text = std::fs::read_to_string(figure).unwrap();
        assert!(text.starts_with("<svg") && text.contains("data:image/png;base64,"));
        assert!(text.contains("class=\"caption\"") && text.contains("class=\"axes\""));
        assert!(text.contains("colour-bar"));
        rs_testkit::assert_figure(&text, caption, what);
    }
    // Bad formulas and spline files are one-line errors.
    for (args, needle) in [
        (
            vec!["fit", "--domain", &domain, "--function", "sin(z)"],
            "unknown name \"z\"",
        ),
        (
            vec!["fit", "--domain", &domain, "--function", "1/(x-x)"],
            "not finite",
        ),
        (
            vec!["eval", "--spline", &domain, "--points", &domain],
            "spline file",
        ),
    ] {
        let out = inrs(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(
            err.contains(needle) && err.lines().count() == 1,
            "{args:?}: {err}"
        );
    }
}

#[test]
fn fit_data_interpolates_scattered_points_in_every_c1_space() {
    let domain = fixture("inrs-paper/s4_disk_ellipse_segment.json");
    // `inrs sample` output with a z column appended (a cubic: every space with cubic fits
    // reproduces it; all interpolate it at the points).
    let sample = inrs_ok(&["sample", "--domain", &domain, "--ny", "9"]);
    let f = |x: f64, y: f64| 1.0 + x - 2.0 * y * y + x * x * y;
    let mut data = String::new();
    let mut points = String::from("x,y\n");
    for (i, line) in sample.lines().enumerate() {
        if i == 0 {
            data.push_str(&format!("{line},z\n"));
            continue;
        }
        let v: Vec<&str> = line.split(',').collect();
        let (x, y): (f64, f64) = (v[0].parse().unwrap(), v[1].parse().unwrap());
        data.push_str(&format!("{line},{:?}\n", f(x, y)));
        points.push_str(&format!("{},{}\n", v[0], v[1]));
    }
    let data = temp_file("fit-data.csv", &data);
    let points = temp_file("fit-data-points.csv", &points);
    let spline = temp_file("fit-data.json", "");
    let svg = temp_file("fit-data.svg", "");
    for space in ["s512", "ct", "ps", "min-energy"] {
        let out = inrs(&[
            "fit", "--domain", &domain, "--data", &data, "--space", space, "--output", &spline,
            "--svg", &svg,
        ]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{space}: {err}");
        assert!(
            err.contains(space) && err.contains("vertices added"),
            "{err}"
        );
        let file = std::fs::read_to_string(&spline).unwrap();
        assert!(file.contains(&format!("\"space\":\"{space}\"")), "{space}");
        let text = inrs_ok(&["eval", "--spline", &spline, "--points", &points]);
        let mut n = 0;
        for line in text.lines().skip(1) {
            let v: Vec<f64> = line.split(',').map(|s| s.parse().unwrap()).collect();
            let want = f(v[0], v[1]);
            assert!(
                (v[2] - want).abs() < 1e-10 * want.abs().max(1.0),
                "{space}: {line}"
            );
            n += 1;
        }
        assert!(n > 50);
        let figure = std::fs::read_to_string(&svg).unwrap();
        rs_testkit::assert_figure(&figure, "C1 interpolating spline", "fit --data --svg");
    }
    // Bad data: errors naming the file's line.
    for (text, needle) in [
        (
            "x,y,z\n0,0,1\n5,5,2\n",
            ":3: the point (5, 5) lies outside the domain",
        ),
        (
            "0,0,1\n0.1,0.1,2\n0,0,3\n",
            ":3: the point (0, 0) repeats an earlier point",
        ),
        ("0,0,1\n0.1,oops,2\n", ":2: expected numbers x, y, z"),
        (
            "a,b,c\n0,0,1\n",
            ":1: a header must name the columns x, y and z",
        ),
        ("# nothing\n", "no data rows"),
    ] {
        let bad = temp_file("fit-bad.csv", text);
        let out = inrs(&["fit", "--domain", &domain, "--data", &bad, "--space", "ps"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{text:?}: {err}");
        assert!(err.contains(needle), "{text:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
    }
    // --space needs --data, and --data needs --space.
    let out = inrs(&["fit", "--domain", &domain, "--data", &data]);
    assert_eq!(out.status.code(), Some(2));
    // The options of the other kind of fit are usage errors (they were silently ignored).
    for (extra, with) in [
        (["--degree", "3"], "--data"),
        (["--ny", "7"], "--data"),
        (["--refine", "ct"], "--data"),
        (["--space", "ct"], "--function"),
    ] {
        let mut args = vec!["fit", "--domain", &domain];
        if with == "--data" {
            args.extend(["--data", &data, "--space", "ps"]);
        } else {
            args.extend(["--function", "x"]);
        }
        args.extend(extra);
        let out = inrs(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{extra:?}: {err}");
        assert!(err.contains("cannot be used with"), "{extra:?}: {err}");
    }
}

/// Points on curves up to rounding (the issue's cubic at t = 0.1, 0.4, 0.7, evaluated in f64)
/// get the average across the jump from every `--algorithm` (Axom's values on the open cubic,
/// 1/2 once it is closed by a segment); `classify` and `classify --method gwn` call them
/// boundary; `--tol 0` keeps the exact values off the curve.
#[test]
fn winding_on_curves_is_the_average_from_every_algorithm() {
    let cubic = r#"{"degree": 3, "control_points": [[0, 0], [0, 1], [-1, 1], [-1, 0]]}"#;
    let open = temp_file("open-cubic.json", &format!(r#"{{"curves": [{cubic}]}}"#));
    let closed = temp_file(
        "closed-cubic.json",
        &format!(r#"{{"curves": [{cubic}, {{"segment": {{"from": [-1, 0], "to": [0, 0]}}}}]}}"#),
    );
    let points = temp_file(
        "on-cubic.csv",
        "x,y\n-0.028000000000000008,0.2700000000000001\n\
         -0.35200000000000004,0.7200000000000001\n-0.7839999999999999,0.63\n",
    );
    let axom = [0.276676361896, 0.310998033871, 0.305165888012];
    for alg in ["adaptive", "binary-search", "bezier-clipping"] {
        for (domain, want) in [(&open, axom), (&closed, [0.5; 3])] {
            let text = inrs_ok(&[
                "winding",
                "--domain",
                domain,
                "--points",
                &points,
                "--algorithm",
                alg,
            ]);
            for (got, w) in last_column(&text).iter().zip(want) {
                let got: f64 = got.parse().unwrap();
                assert!((got - w).abs() < 1e-9, "{alg} on {domain}: {text}");
            }
        }
    }
    for method in ["fast", "inrs1", "inrs2", "gwn"] {
        let text = inrs_ok(&[
            "classify", "--domain", &closed, "--points", &points, "--method", method,
        ]);
        assert_eq!(last_column(&text), ["boundary"; 3], "{method}: {text}");
    }
    // 1e-13 above the closing segment: in the default band (1e-12 of the diagonal), inside
    // the curve at `--tol 0`.
    let near = temp_file("near-segment.csv", "-0.5,1e-13\n");
    for (tol, want) in [("1e-12", 0.5), ("0", 1.0)] {
        let text = inrs_ok(&[
            "winding", "--domain", &closed, "--points", &near, "--tol", tol,
        ]);
        let got: f64 = last_column(&text)[0].parse().unwrap();
        assert!((got - want).abs() < 1e-12, "--tol {tol}: {text}");
    }
    let out = inrs(&[
        "winding", "--domain", &closed, "--points", &points, "--tol", "-1",
    ]);
    assert!(!out.status.success());
}

/// Two curves that miss by 2e-10 on a thin face: the error names them and their gap (not the
/// gap of the one-curve loop the grouping cut off), and `--closure-tol` joins them for every
/// command.
#[test]
fn closure_tolerance_names_the_curves_that_miss_and_joins_them() {
    let thin = fixture("bad/thin_gap.json");
    let points = temp_file("thin_points.csv", "x,y\n0.05,0.001\n0.05,-0.001\n");
    let out = inrs(&["classify", "--domain", &thin, "--points", &points]);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("open boundary: curve 0 ends 2e-10 away from the start of curve 1"),
        "{err}"
    );
    let out = inrs(&[
        "classify",
        "--domain",
        &thin,
        "--closure-tol",
        "1e-8",
        "--points",
        &points,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(last_column(&stdout), ["inside", "outside"]);
    let out = inrs(&["info", "--domain", &thin, "--closure-tol", "-1"]);
    assert!(!out.status.success());
}
