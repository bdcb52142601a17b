//! The `inrs` binary: output on good input, one-line errors and non-zero exit on bad input.

use std::process::Command;

fn inrs(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_inrs"))
        .args(args)
        .output()
        .expect("run inrs")
}

fn fixture(rel: &str) -> String {
    format!("{}/../../fixtures/{rel}", env!("CARGO_MANIFEST_DIR"))
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
        text.contains("curves: 3  bezier pieces: 4  max degree: 2  rational"),
        "{text}"
    );
    assert!(
        text.contains("loop 0: curves 0..=2  closed  CounterClockwise  signed area 2.07079632679"),
        "{text}"
    );
}

#[test]
fn bad_input_gives_one_line_errors() {
    for (args, needle) in [
        (
            vec!["info", "--domain", "/nonexistent/d.json"],
            "/nonexistent/d.json",
        ),
        (
            vec!["info", "--domain", &fixture("bad/malformed.json")],
            "invalid JSON at line 3",
        ),
        (
            vec!["info", "--domain", &fixture("bad/negative_weight.json")],
            "curve 0: weight 1",
        ),
        (
            vec![
                "info",
                "--require-closed",
                "--domain",
                &fixture("bad/open_loop.json"),
            ],
            "open boundary",
        ),
    ] {
        let out = inrs(&args);
        assert!(!out.status.success(), "{args:?}");
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with("inrs: ") && err.contains(needle), "{err}");
    }
}
