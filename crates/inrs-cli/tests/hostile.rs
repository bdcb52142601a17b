//! Hostile input: the CLI binary run on malformed and extreme files and options, each case
//! under a time limit and an address-space limit (`ulimit -v`). Every case asserts its exit
//! status, that a failure is one line on standard error naming the cause (never a panic or an
//! abort), that no output file (nor a temporary one) is left behind, and the bounds.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Address space for one run: far below what the defects this suite guards against took
/// (3-9 GB), far above what a correct run needs.
const MEMORY_LIMIT_MB: u64 = 2048;

struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
    elapsed: Duration,
}

/// Runs `inrs args` under `sh -c 'ulimit -v ...; exec inrs "$@"'`, killing it after `secs`.
fn run_limited(args: &[&str], secs: u64) -> Run {
    let script = format!("ulimit -v {}; exec \"$0\" \"$@\"", MEMORY_LIMIT_MB * 1024);
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(env!("CARGO_BIN_EXE_inrs"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("sh runs");
    let mut out = child.stdout.take().expect("piped");
    let mut err = child.stderr.take().expect("piped");
    let reader = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = out.read_to_end(&mut s);
        s
    });
    let err_reader = std::thread::spawn(move || {
        let mut s = Vec::new();
        let _ = err.read_to_end(&mut s);
        s
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break status;
        }
        if start.elapsed() > Duration::from_secs(secs) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{args:?}: still running after {secs} s");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    let elapsed = start.elapsed();
    Run {
        code: status.code(),
        stdout: String::from_utf8_lossy(&reader.join().unwrap_or_default()).into_owned(),
        stderr: String::from_utf8_lossy(&err_reader.join().unwrap_or_default()).into_owned(),
        elapsed,
    }
}

/// A scratch directory of its own for one test, removed when the test ends.
struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn scratch(test: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("inrs-hostile-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}

fn write(dir: &Path, name: &str, content: impl AsRef<[u8]>) -> String {
    let p = dir.join(name);
    std::fs::write(&p, content).unwrap();
    p.display().to_string()
}

fn fixture(rel: &str) -> String {
    format!("{}/../../fixtures/{rel}", env!("CARGO_MANIFEST_DIR"))
}

/// What a case must do.
enum Expect {
    /// Exit 0.
    Success,
    /// Exit 1 with one line on standard error containing this.
    Error(&'static str),
    /// Exit 2 (a usage error) with one line containing this.
    Usage(&'static str),
}

/// Runs a case and checks the exit status, the message, the bounds and that the directory
/// holds no file the run left behind.
fn check(dir: &Path, args: &[&str], expect: Expect, secs: u64) -> Run {
    let before: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.path())
        .collect();
    let r = run_limited(args, secs);
    assert!(
        !r.stderr.contains("panicked"),
        "{args:?}: panic: {}",
        r.stderr
    );
    assert!(
        !r.stderr.contains("memory allocation"),
        "{args:?}: allocation failure: {}",
        r.stderr
    );
    let (code, needle) = match expect {
        Expect::Success => (0, None),
        Expect::Error(m) => (1, Some(m)),
        Expect::Usage(m) => (2, Some(m)),
    };
    assert_eq!(r.code, Some(code), "{args:?}: stderr {}", r.stderr);
    if let Some(needle) = needle {
        assert_eq!(r.stderr.lines().count(), 1, "{args:?}: {}", r.stderr);
        assert!(
            r.stderr.starts_with("inrs: ") && r.stderr.contains(needle),
            "{args:?}: expected {needle:?} in {}",
            r.stderr
        );
        let after: Vec<_> = std::fs::read_dir(dir)
            .unwrap()
            .flatten()
            .map(|e| e.path())
            .collect();
        let left: Vec<_> = after.iter().filter(|p| !before.contains(p)).collect();
        assert!(left.is_empty(), "{args:?}: left behind {left:?}");
    }
    assert!(r.elapsed < Duration::from_secs(secs), "{args:?}");
    r
}

fn curve_json(body: &str) -> String {
    format!("{{\"curves\": [{body}]}}")
}

/// Closes a curve from (0, 0) to (1, 0).
const CHORD: &str = r#"{"segment": {"from": [1,0], "to": [0,0]}}"#;
/// Closes a curve from (1, 0) to (0, 0).
const CHORD_BACK: &str = r#"{"segment": {"from": [0,0], "to": [1,0]}}"#;

#[test]
fn malformed_and_extreme_domain_files_fail_cleanly() {
    let d = scratch("json");
    let pts = write(&d, "p.csv", "0.5,0.5\n");
    let out = d.join("out.csv").display().to_string();
    let cases: Vec<(String, &str)> = vec![
        (String::new(), "invalid JSON"),
        ("\u{0}\u{1}\u{ff}garbage".into(), "invalid JSON"),
        ("[1, 2]".into(), "not a domain file"),
        ("{\"curves\": []}".into(), "no curves"),
        ("[".repeat(100_000), "invalid JSON"),
        (
            curve_json(r#"{"degree": 1000, "control_points": [[0,0],[1,1]]}"#),
            "degree must be an integer between 1 and 32",
        ),
        (
            curve_json(
                r#"{"degree": 1, "control_points": [[0,0],[1e308,0],[0,1],[0,0]], "knots": [0,0,1,2,3,3]}"#,
            ),
            "control point coordinate 1e308 exceeds the limit 1e150",
        ),
        (
            curve_json(
                r#"{"degree": 2, "control_points": [[0,0],[1,-1],[2,0]], "weights": [1e-300, 1, 1e300]}"#,
            ),
            "weight ratio",
        ),
        (
            curve_json(
                r#"{"degree": 1, "knots": [-1e308, -1e308, 1e308, 1e308], "control_points": [[0,0],[1,1]]}"#,
            ),
            "span length is not finite",
        ),
        (
            curve_json(
                r#"{"degree": 1, "knots": [0,0,0.5,0.5,0.5,1,1], "control_points": [[0,0],[1,0],[1,1],[0,1],[0,0]]}"#,
            ),
            "multiplicity 3 > degree + 1 = 2",
        ),
        (
            curve_json(
                r#"{"arc": {"center": [0,0], "radius": 1, "start_angle": 0, "sweep": 1e10}}"#,
            ),
            "arc sweep",
        ),
        (
            curve_json(r#"{"circle": {"center": [0,0], "radius": 1e308}}"#),
            "exceeds the limit 1e150",
        ),
        (
            curve_json(r#"{"degree": 1, "control_points": [[0,0],["NaN",1]]}"#),
            "curve 0",
        ),
        (
            fixture_text("breaks/circle_gap.json"),
            "gap at parameter 0.5",
        ),
    ];
    for (i, (text, needle)) in cases.iter().enumerate() {
        let f = write(&d, &format!("bad{i}.json"), text);
        check(
            &d,
            &[
                "classify", "--domain", &f, "--points", &pts, "--output", &out,
            ],
            Expect::Error(needle),
            20,
        );
        // The message names the file once.
        let r = run_limited(&["info", "--domain", &f, "--require-closed"], 20);
        assert_eq!(r.stderr.matches(&f).count(), 1, "{}", r.stderr);
    }
}

fn fixture_text(rel: &str) -> String {
    std::fs::read_to_string(fixture(rel)).unwrap()
}

#[test]
fn extreme_but_valid_domains_work_within_bounds() {
    let d = scratch("valid");
    let pts = write(&d, "p.csv", "x,y\n0.5,0.25\n5,5\n");
    // Weights 1e-300 and 1e300 uniformly (rescaled exactly), a weight of 1e4 (area used to
    // hang), subnormal-free tiny and huge coordinates.
    let valid = [
        curve_json(&format!(
            r#"{{"degree": 2, "control_points": [[0,0],[0.5,1],[1,0]], "weights": [1e-300,1e-300,1e-300]}}, {CHORD}"#
        )),
        curve_json(&format!(
            r#"{{"degree": 2, "control_points": [[1,0],[0.5,1],[0,0]], "weights": [1e300,2e300,1e300]}}, {CHORD_BACK}"#
        )),
        curve_json(
            r#"{"degree": 2, "control_points": [[0,0],[1,1],[2,0]], "weights": [1,1e4,1]}, {"segment": {"from": [2,0], "to": [0,0]}}"#,
        ),
        curve_json(r#"{"polyline": [[0,0],[1e140,0],[1e140,1e140],[0,0]]}"#),
        curve_json(r#"{"polyline": [[0,0],[1e-140,0],[1e-140,1e-140],[0,0]]}"#),
    ];
    for (i, text) in valid.iter().enumerate() {
        let f = write(&d, &format!("ok{i}.json"), text);
        check(&d, &["info", "--domain", &f], Expect::Success, 20);
        check(
            &d,
            &["classify", "--domain", &f, "--points", &pts],
            Expect::Success,
            20,
        );
    }
    // One B-spline with 10^5 control points (Bezier extraction used to be quadratic), and
    // 10^5 separate segments (boxes used to take gigabytes).
    let n = 100_000;
    let cps: Vec<String> = (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            format!("[{},{}]", t.cos(), t.sin())
        })
        .collect();
    let spline = format!(
        "{{\"curves\": [{{\"degree\": 3, \"control_points\": [{},{}]}}]}}",
        cps.join(","),
        cps[0]
    )
    .replace(
        "\"degree\": 3,",
        &format!("\"degree\": 3, \"knots\": [{}],", clamped_knots(n + 1, 3)),
    );
    let f = write(&d, "spline.json", spline);
    let r = check(
        &d,
        &["classify", "--domain", &f, "--points", &pts],
        Expect::Success,
        60,
    );
    assert!(
        r.stdout.contains("0.5,0.25,inside") && r.stdout.contains("5,5,outside"),
        "{}",
        r.stdout
    );
    let segs: Vec<String> = (0..n)
        .map(|i| {
            format!(
                "{{\"segment\": {{\"from\": {}, \"to\": {}}}}}",
                cps[i],
                cps[(i + 1) % n]
            )
        })
        .collect();
    let f = write(&d, "segments.json", curve_json(&segs.join(",")));
    let r = check(
        &d,
        &["classify", "--domain", &f, "--points", &pts],
        Expect::Success,
        60,
    );
    assert!(r.stdout.contains("0.5,0.25,inside"), "{}", r.stdout);
}

fn clamped_knots(n: usize, p: usize) -> String {
    let spans = n - p;
    let mut k = vec!["0".to_string(); p + 1];
    k.extend((1..spans).map(|i| format!("{}", i as f64 / spans as f64)));
    k.extend(std::iter::repeat_n("1".to_string(), p + 1));
    k.join(",")
}

#[test]
fn hostile_svg_dxf_and_font_files_fail_cleanly() {
    let d = scratch("svg");
    let pts = write(&d, "p.csv", "0.5,0.5\n");
    let svg = |body: &str| format!(r#"<svg xmlns="http://www.w3.org/2000/svg">{body}</svg>"#);
    let deep = svg(&format!(
        "{}<circle r=\"1\"/>{}",
        "<g>".repeat(10_000),
        "</g>".repeat(10_000)
    ));
    let bomb = format!(
        "<?xml version=\"1.0\"?><!DOCTYPE svg [<!ENTITY a \"aaaaaaaaaa\">{}]>{}",
        (1..12)
            .map(|i| format!(
                "<!ENTITY a{i} \"{}\">",
                format!(
                    "&a{};",
                    if i == 1 {
                        String::new()
                    } else {
                        (i - 1).to_string()
                    }
                )
                .repeat(10)
            ))
            .collect::<String>(),
        svg("<desc>&a11;</desc><circle r=\"1\"/>")
    );
    let cases: Vec<(&str, String, &str)> = vec![
        ("deep.svg", deep, "nested more than 256 deep"),
        ("bomb.svg", bomb, "entity"),
        ("notxml.svg", "<svg".into(), "not well-formed XML"),
        (
            "empty.svg",
            svg(""),
            "no boundary curves found in the SVG file",
        ),
        (
            "huge.svg",
            svg(r#"<circle r="1e308"/>"#),
            "exceeds the limit 1e150",
        ),
        (
            "arc.svg",
            svg(r#"<path d="M0 0 A1e308 1e308 0 0 1 1 0 Z"/>"#),
            "arc radius",
        ),
        (
            "scale.svg",
            svg(r#"<g transform="scale(1e300)"><circle r="1e10"/></g>"#),
            "<circle> at line 1: control point 0 is not finite",
        ),
        // A path whose data breaks before its first segment draws nothing.
        (
            "badpath.svg",
            svg(r#"<path d="M0 0 L 1 Q"/>"#),
            "no boundary curves found",
        ),
        (
            "garbage.dxf",
            "0\nSECTION\n2\nENTITIES\n0\nLINE\n10\nnot-a-number\n".into(),
            "DXF",
        ),
        ("empty.dxf", "0\nEOF\n".into(), "no boundary curves found"),
    ];
    for (name, text, needle) in &cases {
        let f = write(&d, name, text);
        check(
            &d,
            &["classify", "--domain", &f, "--points", &pts],
            Expect::Error(needle),
            20,
        );
    }
    let font = write(&d, "fake.ttf", "not a font at all");
    check(
        &d,
        &["info", "--domain", &format!("{font}#A")],
        Expect::Error("font"),
        20,
    );
    // Valid extremes: an SVG 1.1 DTD (drawing programs write it) and a 10^5-command path.
    let dtd = format!(
        "<?xml version=\"1.0\"?>\n<!DOCTYPE svg PUBLIC \"-//W3C//DTD SVG 1.1//EN\" \"http://www.w3.org/Graphics/SVG/1.1/DTD/svg11.dtd\">\n{}",
        svg(r#"<circle cx="0.5" cy="0.5" r="1"/>"#)
    );
    let f = write(&d, "dtd.svg", dtd);
    let r = check(
        &d,
        &["classify", "--domain", &f, "--points", &pts],
        Expect::Success,
        20,
    );
    assert!(r.stdout.contains("0.5,0.5,inside"));
    let n = 100_000;
    let path: Vec<String> = (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            format!("L{:.9} {:.9}", t.cos(), t.sin())
        })
        .collect();
    let f = write(
        &d,
        "long.svg",
        svg(&format!("<path d=\"M1 0 {} Z\"/>", path.join(" "))),
    );
    let r = check(
        &d,
        &["classify", "--domain", &f, "--points", &pts],
        Expect::Success,
        60,
    );
    assert!(r.stdout.contains("0.5,0.5,inside"));
    // Path data with an error is drawn up to its last complete segment, with a warning.
    let f = write(
        &d,
        "broken_path.svg",
        svg(r#"<path id="icon" d="M -1,-1 2,-1 2,2 -1,2 l"/>"#),
    );
    let r = check(
        &d,
        &["classify", "--domain", &f, "--points", &pts],
        Expect::Success,
        20,
    );
    assert!(r.stdout.contains("0.5,0.5,inside"), "{}", r.stdout);
    assert!(
        r.stderr.lines().count() == 1
            && r.stderr.contains("warning")
            && r.stderr.contains("path id=\"icon\"")
            && r.stderr.contains("drawn up to its last complete segment"),
        "{}",
        r.stderr
    );
}

/// Hostile STEP and IGES files (truncated, dangling and cyclic references, non-finite numbers,
/// deep nesting, a 20 MB line, broken IGES sections) each give one line naming the format,
/// under the time and memory limits. A broken file fails its face list the same way; a file
/// whose face alone is broken lists the face as refused, with the reason.
#[test]
fn hostile_step_and_iges_files_fail_cleanly() {
    let d = scratch("cad");
    let pts = write(&d, "p.csv", "5,5\n");
    let plate = std::fs::read_to_string(fixture("cad/plate.step")).unwrap();
    let half = plate[..plate.len() / 2].to_string();
    let deep = format!(
        "ISO-10303-21;HEADER;ENDSEC;DATA;#1=A({}1{});ENDSEC;END-ISO-10303-21;",
        "(".repeat(100_000),
        ")".repeat(100_000)
    );
    let long = format!(
        "ISO-10303-21;HEADER;ENDSEC;DATA;#1=A({}",
        "(".repeat(20 << 20)
    );
    let iges_line = |text: &str, section: char, n: usize| format!("{text:<72}{section}{n:>7}\n");
    let iges_truncated = iges_line("", 'S', 1);
    let iges_bad_pointer = [
        iges_line("", 'S', 1),
        iges_line("1H,,1H;;", 'G', 1),
        iges_line(
            "     144  99999999       0       0       0       0       0       000000000",
            'D',
            1,
        ),
        iges_line(
            "     144       0       0       1       0                               0",
            'D',
            2,
        ),
        iges_line("144,1,1,0,3;", 'P', 1),
        iges_line("S      1G      1D      2P      1", 'T', 1),
    ]
    .concat();
    // Faces broken alone: (file, its text, the refusal).
    let face_cases = [
        (
            "dangling.step",
            plate.replace("#204=PLANE('',#203);", "#204=PLANE('',#999999);"),
            "#204 PLANE refers to #999999, which is not in the file",
        ),
        (
            "cycle.step",
            plate.replace(
                "#203=AXIS2_PLACEMENT_3D('',#200,#201,#202);",
                "#203=AXIS2_PLACEMENT_3D('',#203,#201,#202);",
            ),
            "#203 AXIS2_PLACEMENT_3D is not a CARTESIAN_POINT",
        ),
    ];
    for (name, text, reason) in &face_cases {
        let f = write(&d, name, text);
        let spec = format!("{f}#face:0");
        check(
            &d,
            &["classify", "--domain", &spec, "--points", &pts],
            Expect::Error(reason),
            20,
        );
        let r = check(&d, &["info", "--domain", &f], Expect::Success, 20);
        assert!(
            r.stdout.contains(&format!("refused: {reason}")),
            "{}",
            r.stdout
        );
        check(
            &d,
            &["info", "--require-closed", "--domain", &f],
            Expect::Error("1 of 1 faces are refused"),
            20,
        );
    }
    let cases: Vec<(&str, String, &str)> = vec![
        ("truncated.step", half, "STEP: line 49: the file ends early"),
        (
            "nan.step",
            plate.replacen("(1.0,2.0,3.0)", "(1.E400,2.0,3.0)", 1),
            "STEP",
        ),
        ("deep.step", deep, "STEP"),
        ("long.stp", long, "STEP"),
        ("truncated.igs", iges_truncated, "IGES"),
        ("pointer.iges", iges_bad_pointer, "IGES"),
        ("notcad.step", "hello".into(), "STEP"),
    ];
    for (name, text, needle) in &cases {
        let f = write(&d, name, text);
        check(
            &d,
            &[
                "classify",
                "--domain",
                &format!("{f}#face:0"),
                "--points",
                &pts,
            ],
            Expect::Error(needle),
            20,
        );
        check(&d, &["info", "--domain", &f], Expect::Error(needle), 20);
    }
    // Broken B-rep parts (the box with a spherical void of python/tests/cad_parts.py, written
    // by OpenCASCADE): a face with no bounds on a plane and a face on a degenerate placement
    // are refused with one line; a pcurve a million units off, or at 1e300, refuses its face;
    // a solid whose shell lost a face is no solid; shells in a cycle fail the file.
    let void = std::fs::read_to_string(fixture("cad/box_void.step")).unwrap();
    let cone = std::fs::read_to_string(fixture("cad/cone_minus_sphere.step")).unwrap();
    let refused_faces = [
        (
            "nobounds.step",
            void.replace(
                "#17 = ADVANCED_FACE('',(#18),#32,.F.);",
                "#17 = ADVANCED_FACE('',(),#32,.F.);",
            ),
            "a face with no bounds on an unbounded PLANE #32",
        ),
        (
            "degenerate.step",
            void.replace(
                "#36 = DIRECTION('',(0.,0.,1.));",
                "#36 = DIRECTION('',(1.,0.,0.));",
            ),
            "#33 AXIS2_PLACEMENT_3D: degenerate axes: the reference direction is along the axis",
        ),
        (
            "faroff.step",
            cone.replace(
                "#129 = CARTESIAN_POINT('',(0.,-6.28318530718));",
                "#129 = CARTESIAN_POINT('',(1.E6,-1.E6));",
            ),
            "edge #110 does not meet the previous edge in (u, v)",
        ),
        (
            "huge.step",
            cone.replace(
                "#122 = CARTESIAN_POINT('',(6.28318530718,-6.28318530718));",
                "#122 = CARTESIAN_POINT('',(6.28318530718,-1.E300));",
            ),
            "#122 CARTESIAN_POINT: coordinate beyond",
        ),
    ];
    for (name, text, reason) in &refused_faces {
        assert_ne!(text, &void, "{name}: the edit applies");
        let f = write(&d, name, text);
        let r = check(&d, &["info", "--domain", &f], Expect::Success, 20);
        assert!(
            r.stdout.contains("refused: ") && r.stdout.contains(reason),
            "{name}: {}",
            r.stdout
        );
    }
    let open = write(
        &d,
        "openshell.step",
        void.replace(
            "#16 = CLOSED_SHELL('',(#17,#137,#237,#284,#331,#338));",
            "#16 = CLOSED_SHELL('',(#17,#137,#237,#284,#331));",
        ),
    );
    let r = check(&d, &["info", "--domain", &open], Expect::Success, 20);
    assert!(r.stdout.contains("0 STEP solids, 2 shells"), "{}", r.stdout);
    assert!(
        r.stdout.contains("shell 0   #16       open   5 faces 0-4"),
        "{}",
        r.stdout
    );
    check(
        &d,
        &["info", "--domain", &format!("{open}#solid:0")],
        Expect::Error("solid 0 does not exist: the file has no solids"),
        20,
    );
    let cycle = write(
        &d,
        "cycle.step",
        void.replace(
            "#345 = ORIENTED_CLOSED_SHELL('',*,#346,.F.);",
            "#345 = ORIENTED_CLOSED_SHELL('',*,#345,.F.);",
        ),
    );
    check(
        &d,
        &["info", "--domain", &cycle],
        Expect::Error("#345 ORIENTED_CLOSED_SHELL: reference cycle"),
        20,
    );
    // A bad selection is an error naming the syntax.
    let f = write(&d, "plate.step", &plate);
    check(
        &d,
        &["info", "--domain", &format!("{f}#face:x")],
        Expect::Error("write #face:K or #solid:K"),
        20,
    );
    // A solid is not a planar domain: commands that take one say so (classify takes solids:
    // this file has none).
    check(
        &d,
        &["info", "--domain", &format!("{f}#solid:0")],
        Expect::Error("solid 0 does not exist"),
        20,
    );
    check(
        &d,
        &[
            "classify",
            "--domain",
            &format!("{f}#solid:0"),
            "--points",
            &pts,
        ],
        Expect::Error("solid 0 does not exist: the file has no solids"),
        20,
    );
    check(
        &d,
        &[
            "winding",
            "--domain",
            &format!("{f}#solid:0"),
            "--points",
            &pts,
        ],
        Expect::Error("is a solid, not a planar domain"),
        20,
    );
}

/// A boundary of 10^6 pieces (an SVG path of 10^6 commands: a circle polygon and a zigzag)
/// is refused at once by everything that meshes or samples by lines, naming the limit
/// (it used to run for minutes at 1.3 GB).
#[test]
fn meshing_a_million_piece_boundary_is_refused_at_once() {
    let d = scratch("million");
    let n = 1_000_000;
    let circle: Vec<String> = (1..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            format!("L{:.9} {:.9}", t.cos(), t.sin())
        })
        .collect();
    let zigzag: Vec<String> = (1..n - 2)
        .map(|i| format!("L{} {}", i as f64 / n as f64, (i % 2) as f64 * 1e-3))
        .collect();
    let svg =
        |d: String| format!(r#"<svg xmlns="http://www.w3.org/2000/svg"><path d="{d}"/></svg>"#);
    let shapes = [
        ("circle.svg", svg(format!("M1 0 {} Z", circle.join(" ")))),
        (
            "zigzag.svg",
            svg(format!("M0 0 {} L1 1 L0 1 Z", zigzag.join(" "))),
        ),
    ];
    let data = write(&d, "xyz.csv", "x,y,z\n0.5,0.5,1\n0,0.5,2\n");
    let out = d.join("out.json").display().to_string();
    for (name, text) in shapes {
        let f = write(&d, name, text);
        for args in [
            vec!["mesh", "--domain", &f, "--output", &out],
            vec!["sample", "--domain", &f, "--ny", "20", "--output", &out],
            vec![
                "fit",
                "--domain",
                &f,
                "--ny",
                "9",
                "--degree",
                "2",
                "--function",
                "x",
                "--output",
                &out,
            ],
            vec![
                "fit", "--domain", &f, "--data", &data, "--space", "ct", "--output", &out,
            ],
        ] {
            let r = check(
                &d,
                &args,
                Expect::Error("meshing and sampling by lines support at most 10000"),
                60,
            );
            assert!(
                r.stderr.contains("has 1000000 Bezier pieces"),
                "{name} {args:?}: {}",
                r.stderr
            );
        }
    }
}

/// Many chunks (a quarter megabyte each) written in input order by the workers: every row
/// echoes its input line, whatever the output; a bad line deep in the file fails the run with
/// its number, and leaves no output file.
#[test]
fn long_streams_keep_their_order_and_fail_at_the_right_line() {
    let d = scratch("order");
    let domain = fixture("inrs-paper/circle.json");
    let n = 120_000;
    let line = |i: usize| {
        let t = i as f64 * 0.618_033_988_749_895;
        format!("{},{}", 1.5 * t.sin(), 1.5 * (t * 1.7).cos())
    };
    let mut text = String::from("x,y\n");
    for i in 0..n {
        text.push_str(&line(i));
        text.push('\n');
    }
    let p = write(&d, "many.csv", &text);
    let out = d.join("o.csv").display().to_string();
    let to_stdout = check(
        &d,
        &["classify", "--domain", &domain, "--points", &p],
        Expect::Success,
        60,
    );
    check(
        &d,
        &[
            "classify", "--domain", &domain, "--points", &p, "--output", &out,
        ],
        Expect::Success,
        60,
    );
    let to_file = std::fs::read_to_string(&out).expect("output written");
    assert_eq!(to_file, to_stdout.stdout);
    let rows: Vec<&str> = to_file.lines().collect();
    assert_eq!(rows.len(), n + 1);
    for (i, row) in rows[1..].iter().enumerate() {
        let (xy, location) = row.rsplit_once(',').expect("three fields");
        assert_eq!(xy, line(i), "row {i}");
        let (x, y): (f64, f64) = {
            let (x, y) = xy.split_once(',').expect("x,y");
            (x.parse().expect("x"), y.parse().expect("y"))
        };
        let r = x.hypot(y);
        if (r - 1.0).abs() > 1e-9 {
            assert_eq!(
                location,
                if r < 1.0 { "inside" } else { "outside" },
                "row {i}"
            );
        }
    }
    // The same file with line 100 001 (point 100 000) spoiled.
    let spoiled = text.replacen(&format!("\n{}\n", line(99_999)), "\n0.5,oops\n", 1);
    assert_ne!(spoiled, text);
    let bad = write(&d, "bad.csv", &spoiled);
    let _ = std::fs::remove_file(&out);
    check(
        &d,
        &[
            "classify", "--domain", &domain, "--points", &bad, "--output", &out,
        ],
        Expect::Error("line 100001: \"oops\" is not a number"),
        60,
    );
    assert!(!Path::new(&out).exists(), "a failed run left an output");
}

#[test]
fn points_files_stream_and_bad_lines_fail_cleanly() {
    let d = scratch("csv");
    let domain = fixture("inrs-paper/circle.json");
    let out = d.join("o.csv").display().to_string();
    let bad: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "nan.csv",
            b"0,0\nnan,1\n".to_vec(),
            "line 2: \"nan\" is not a finite number",
        ),
        (
            "inf.csv",
            b"0,0\n1e999,1\n".to_vec(),
            "line 2: \"1e999\" is not a finite number",
        ),
        (
            "one.csv",
            b"0,0\n3\n".to_vec(),
            "line 2: expected at least two numbers",
        ),
        (
            "binary.csv",
            vec![0xff, 0xfe, 0x00, 0x01, b'\n'],
            "line 1: not UTF-8",
        ),
        ("long.csv", vec![b'1'; 1 << 20], "longer than 65536 bytes"),
    ];
    for (name, content, needle) in &bad {
        let p = write(&d, name, content);
        for method in ["fast", "gwn", "inrs1"] {
            check(
                &d,
                &[
                    "classify", "--domain", &domain, "--points", &p, "--method", method,
                    "--output", &out,
                ],
                Expect::Error(needle),
                20,
            );
        }
        check(
            &d,
            &[
                "winding", "--domain", &domain, "--points", &p, "--output", &out,
            ],
            Expect::Error(needle),
            20,
        );
    }
    // Bad .npy points files: each refused with the reason, whatever it announces.
    let npy = |shape: &str, data: &[f64]| {
        let dict = format!("{{'descr': '<f8', 'fortran_order': False, 'shape': {shape}, }}");
        let mut bytes = b"\x93NUMPY\x01\x00".to_vec();
        let text = format!("{dict:<117}\n");
        bytes.extend_from_slice(&(text.len() as u16).to_le_bytes());
        bytes.extend_from_slice(text.as_bytes());
        for v in data {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        bytes
    };
    let bad_npy: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "short.npy",
            npy("(1000000, 2)", &[0.5; 6]),
            "the data end before",
        ),
        (
            "huge.npy",
            npy("(100000000000000, 2)", &[0.5; 6]),
            "the data end before",
        ),
        (
            "too_huge.npy",
            npy("(1000000000000000, 2)", &[]),
            "more than the limit",
        ),
        ("flat.npy", npy("(6,)", &[0.5; 6]), "shape (N, 2)"),
        (
            "nan.npy",
            npy("(2, 2)", &[0.0, 0.0, f64::NAN, 1.0]),
            "point 1 is not finite",
        ),
        ("text.npy", b"x,y\n1,2\n".to_vec(), "not a .npy file"),
    ];
    for (name, content, needle) in &bad_npy {
        let p = write(&d, name, content);
        for cmd in ["classify", "winding"] {
            check(
                &d,
                &[cmd, "--domain", &domain, "--points", &p, "--output", &out],
                Expect::Error(needle),
                20,
            );
        }
    }
    // A tolerance far wider than a grid cell: the fast method's grid (built for batches of
    // 50000 points and more) coarsens instead of registering every box part in millions of
    // cells; every point is then within the boundary band of a circle of radius 1.
    let many: String = (0..60_000)
        .map(|i| {
            format!(
                "{},{}\n",
                (i % 300) as f64 / 100.0 - 1.5,
                (i / 300) as f64 / 100.0 - 1.0
            )
        })
        .collect();
    let p = write(&d, "many.csv", &many);
    let wide = check(
        &d,
        &[
            "classify", "--domain", &domain, "--points", &p, "--tol", "0.5",
        ],
        Expect::Success,
        20,
    );
    assert_eq!(
        wide.stdout
            .lines()
            .filter(|l| l.ends_with(",boundary"))
            .count(),
        60_000
    );
    // A BOM, CRLF line ends and the tool's own outputs read back.
    let p = write(&d, "bom.csv", "\u{feff}x,y\r\n0.1,0.2\r\n");
    let r = check(
        &d,
        &["classify", "--domain", &domain, "--points", &p],
        Expect::Success,
        20,
    );
    assert_eq!(r.stdout, "x,y,location\n0.1,0.2,inside\n");
    let sample = d.join("sample.csv").display().to_string();
    check(
        &d,
        &[
            "sample", "--domain", &domain, "--ny", "6", "--output", &sample,
        ],
        Expect::Success,
        20,
    );
    let r = check(
        &d,
        &["classify", "--domain", &domain, "--points", &sample],
        Expect::Success,
        20,
    );
    let rows = r.stdout.lines().count();
    assert_eq!(
        rows,
        std::fs::read_to_string(&sample).unwrap().lines().count()
    );
    // 10^6 points stream through (their memory is the batch, not the file).
    let big: String = (0..1_000_000)
        .map(|i| {
            format!(
                "{},{}\n",
                (i % 1000) as f64 / 500.0 - 1.0,
                (i / 1000) as f64 / 500.0 - 1.0
            )
        })
        .collect();
    let p = write(&d, "big.csv", big);
    let classified = d.join("big-out.csv").display().to_string();
    check(
        &d,
        &[
            "classify",
            "--domain",
            &domain,
            "--points",
            &p,
            "--output",
            &classified,
        ],
        Expect::Success,
        120,
    );
    let text = std::fs::read_to_string(&classified).unwrap();
    assert_eq!(text.lines().count(), 1_000_001);
    assert!(text.contains("\n0,0,inside\n"));
}

#[test]
fn extreme_options_are_refused_with_their_limits() {
    let d = scratch("options");
    let domain = fixture("inrs-paper/circle.json");
    let pts = write(&d, "p.csv", "0,0\n");
    let curve = fixture("convex/cubic.json");
    let cases: Vec<(Vec<&str>, Expect)> = vec![
        (
            vec![
                "classify",
                "--domain",
                &domain,
                "--points",
                &pts,
                "--subdivisions",
                "10000000",
            ],
            Expect::Usage("expected 1 to 4096"),
        ),
        (
            vec![
                "classify", "--domain", &domain, "--points", &pts, "--tol", "-1",
            ],
            Expect::Usage("must be finite and >= 0"),
        ),
        (
            vec![
                "classify", "--domain", &domain, "--points", &pts, "--tol", "nan",
            ],
            Expect::Usage("must be finite"),
        ),
        (
            vec![
                "sample",
                "--domain",
                &domain,
                "--method",
                "halton",
                "--count",
                "1000000000",
            ],
            Expect::Usage("expected 1 to 10000000"),
        ),
        (
            vec!["sample", "--domain", &domain, "--ny", "-3"],
            Expect::Usage("from 2 to 100000"),
        ),
        (
            vec!["sample", "--domain", &domain, "--ny", "100000"],
            Expect::Error("exceed the limit 10000000"),
        ),
        (
            vec!["mesh", "--domain", &domain, "--ny", "8000"],
            Expect::Error("exceed the limit"),
        ),
        (
            vec![
                "convex-domain",
                "--curve",
                &curve,
                "--free-index",
                "2",
                "--box=-1e154,1e154,-1e154,1e154",
            ],
            Expect::Error("at most 1e100"),
        ),
        (
            vec![
                "convex-domain",
                "--curve",
                &curve,
                "--free-index",
                "2",
                "--box=-10,10,-10,10",
                "--max-level",
                "100",
            ],
            Expect::Usage("expected 0 to 20"),
        ),
        (
            vec!["convex-domain", "--curve", &curve, "--free-index", "2"],
            Expect::Usage("--box"),
        ),
        (
            vec![
                "classify",
                "--domain",
                &domain,
                "--points",
                &pts,
                "--output",
                "/nonexistent/dir/o.csv",
            ],
            Expect::Error("/nonexistent/dir/o.csv"),
        ),
    ];
    for (args, expect) in cases {
        check(&d, &args, expect, 30);
    }
}

#[test]
fn failures_leave_no_output_and_closed_pipes_end_quietly() {
    let d = scratch("outputs");
    let domain = fixture("inrs-paper/circle.json");
    // The bad line comes after a full batch has been written: the output must still vanish.
    let mut text: String = (0..70_000)
        .map(|i| format!("{},0\n", i as f64 * 1e-5))
        .collect();
    text.push_str("oops\n");
    let pts = write(&d, "late-error.csv", text);
    let out = d.join("o.csv").display().to_string();
    check(
        &d,
        &[
            "classify", "--domain", &domain, "--points", &pts, "--output", &out,
        ],
        Expect::Error("line 70001"),
        30,
    );
    // A mesh whose SVG cannot be written leaves no JSON either.
    let json = d.join("m.json").display().to_string();
    check(
        &d,
        &[
            "mesh",
            "--domain",
            &domain,
            "--ny",
            "6",
            "--output",
            &json,
            "--svg",
            "/nonexistent/m.svg",
        ],
        Expect::Error("/nonexistent/m.svg"),
        30,
    );
    assert!(!Path::new(&json).exists());
    // An existing output is replaced only on success.
    std::fs::write(&out, "keep me\n").unwrap();
    let r = run_limited(
        &[
            "classify", "--domain", &domain, "--points", &pts, "--output", &out,
        ],
        30,
    );
    assert_eq!(r.code, Some(1));
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "keep me\n");
    // Closed pipes: the reader goes away at once; the tool ends quietly with status 0.
    let bin = env!("CARGO_BIN_EXE_inrs");
    let big = write(
        &d,
        "many.csv",
        (0..200_000).map(|i| format!("{i},0\n")).collect::<String>(),
    );
    for cmd in [
        format!("{bin} convert --domain {domain}"),
        format!("{bin} info --domain {domain}"),
        format!("{bin} classify --domain {domain} --points {big}"),
        format!(
            "{bin} convex-domain --curve {} --free-index 2 --box=-10,10,-11,9",
            fixture("convex/cubic.json")
        ),
        format!("{bin} --help"),
    ] {
        let r = Command::new("bash")
            .arg("-c")
            .arg(format!("{cmd} | head -c0; exit ${{PIPESTATUS[0]}}"))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&r.stderr);
        assert!(r.status.success(), "{cmd}: {:?} {err}", r.status);
        assert!(err.is_empty(), "{cmd}: {err}");
    }
}
