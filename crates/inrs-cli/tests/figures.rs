//! Every figure the command-line tool writes (`mesh --svg`, `fit --svg --error-svg`,
//! `convex-domain --svg`) parses as SVG and has axes, a legend (or a colour bar) and a caption
//! that says what it shows.

use std::path::{Path, PathBuf};
use std::process::Command;

fn fixture(relative: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(relative)
        .display()
        .to_string()
}

fn out(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("inrs-figures-{}-{name}", std::process::id()))
}

fn run(args: &[&str]) {
    let o = Command::new(env!("CARGO_BIN_EXE_inrs"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

fn read(path: &Path) -> String {
    let s = std::fs::read_to_string(path).unwrap();
    std::fs::remove_file(path).ok();
    s
}

#[test]
fn mesh_figure_explains_itself() {
    let svg = out("mesh.svg");
    let s4 = fixture("inrs-paper/s4_disk_ellipse_segment.json");
    run(&[
        "mesh",
        "--domain",
        &s4,
        "--ny",
        "8",
        "--svg",
        svg.to_str().unwrap(),
        "--output",
        out("mesh.json").to_str().unwrap(),
    ]);
    std::fs::remove_file(out("mesh.json")).ok();
    rs_testkit::assert_figure(&read(&svg), "Curved triangulation:", "mesh --svg");
}

#[test]
fn spline_figures_explain_themselves() {
    let (svg, err, json) = (out("fit.svg"), out("fit-error.svg"), out("fit.json"));
    let s4 = fixture("inrs-paper/s4_disk_ellipse_segment.json");
    run(&[
        "fit",
        "--domain",
        &s4,
        "--ny",
        "6",
        "--degree",
        "3",
        "--function",
        "sin(3*x) + y",
        "--output",
        json.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
        "--error-svg",
        err.to_str().unwrap(),
    ]);
    std::fs::remove_file(&json).ok();
    rs_testkit::assert_figure(&read(&svg), "degree 3", "fit --svg");
    rs_testkit::assert_figure(&read(&err), "error", "fit --error-svg");
}

#[test]
fn convex_domain_figure_explains_itself() {
    let svg = out("convex.svg");
    run(&[
        "convex-domain",
        "--curve",
        &fixture("convex/cubic.json"),
        "--free-index",
        "2",
        "--box=-10,10,-11,9",
        "--max-level",
        "3",
        "--svg",
        svg.to_str().unwrap(),
    ]);
    let text = read(&svg);
    rs_testkit::assert_figure(&text, "free control point", "convex-domain --svg");
    // The nested inner polygons and the outer bound are told apart in the legend.
    assert!(text.contains("outer bound"), "no outer bound in the legend");
}
