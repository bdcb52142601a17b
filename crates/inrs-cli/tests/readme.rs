//! The shell examples of README.md and docs/CLI.md run as written: every line of every `sh`
//! block, in order, in a scratch directory where `fixtures/` is the repository's, with
//! `cargo run --release -p inrs-cli --` standing for the binary under test. The lines that
//! build or test the whole workspace (`cargo xtask`, `cargo test`) or need Python (`pip`,
//! `python`) are run by `.ci/run` itself. Examples that read a system font skip with a message
//! when it is missing, and fail instead under `INRS_REQUIRE_SYSTEM_FILES=1`. And every relative
//! link of README.md, python/README.md and docs/*.md points at a file that exists.

use std::path::{Path, PathBuf};
use std::process::Command;

const CARGO_RUN: &str = "cargo run --release -p inrs-cli --";
/// Set to 1 (as `.ci/run` does), a missing system file fails the test instead of skipping.
const REQUIRE_SYSTEM_FILES: &str = "INRS_REQUIRE_SYSTEM_FILES";

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The `sh` code blocks of a Markdown file, each as its lines.
fn sh_blocks(markdown: &str) -> Vec<Vec<String>> {
    let mut blocks = Vec::new();
    let mut current: Option<Vec<String>> = None;
    for line in markdown.lines() {
        match (&mut current, line.trim_start()) {
            (None, l) if l.starts_with("```sh") => current = Some(Vec::new()),
            (Some(_), l) if l.starts_with("```") => blocks.extend(current.take()),
            (Some(block), l) => block.push(l.to_string()),
            (None, _) => {}
        }
    }
    blocks
}

/// Whether the line is left to `.ci/run` (whole-workspace commands, Python).
fn run_by_ci(line: &str) -> bool {
    ["cargo xtask", "cargo test", "pip ", "python "]
        .iter()
        .any(|p| line.starts_with(p))
}

/// A system file a line reads, if it is missing.
fn missing_system_file(line: &str) -> Option<String> {
    let start = line.find("/usr/share/")?;
    let path: String = line[start..]
        .chars()
        .take_while(|c| !matches!(c, '"' | '#' | ' '))
        .collect();
    (!Path::new(&path).exists()).then_some(path)
}

fn run_examples(file: &str) -> usize {
    let text = std::fs::read_to_string(repo().join(file)).expect("the Markdown file");
    let bin = env!("CARGO_BIN_EXE_inrs");
    let mut ran = 0;
    for (b, block) in sh_blocks(&text).iter().enumerate() {
        let dir = std::env::temp_dir()
            .join(format!("inrs-readme-{}-{file}-{b}", std::process::id()).replace('/', "_"));
        std::fs::create_dir_all(&dir).unwrap();
        let fixtures = dir.join("fixtures");
        if !fixtures.exists() {
            #[cfg(unix)]
            std::os::unix::fs::symlink(repo().join("fixtures"), &fixtures).unwrap();
        }
        for line in block {
            if line.is_empty() || line.starts_with('#') || run_by_ci(line) {
                continue;
            }
            if let Some(path) = missing_system_file(line) {
                assert!(
                    std::env::var(REQUIRE_SYSTEM_FILES).as_deref() != Ok("1"),
                    "{file}: {path} is missing and {}=1",
                    REQUIRE_SYSTEM_FILES
                );
                eprintln!("{file}: skipping an example: {path} is missing");
                continue;
            }
            assert!(
                line.starts_with(CARGO_RUN)
                    || line.starts_with("printf ")
                    || line.starts_with("awk "),
                "{file}: an example this test does not know how to run: {line}"
            );
            let command = line.replace(CARGO_RUN, bin);
            let out = Command::new("sh")
                .arg("-c")
                .arg(&command)
                .current_dir(&dir)
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "{file}: `{line}` failed: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            if line.starts_with(CARGO_RUN) {
                assert!(
                    !out.stdout.is_empty() || line.contains("--output") || line.contains("--svg"),
                    "{file}: `{line}` printed nothing"
                );
            }
            ran += 1;
        }
        std::fs::remove_dir_all(&dir).ok();
    }
    ran
}

#[test]
fn readme_examples_run() {
    let ran = run_examples("README.md");
    assert!(ran >= 3, "README.md: only {ran} example lines ran");
}

#[test]
fn cli_guide_examples_run() {
    let ran = run_examples("docs/CLI.md");
    assert!(ran >= 8, "docs/CLI.md: only {ran} example lines ran");
}

#[test]
fn the_readme_classifies_its_points_as_it_says() {
    // The README's first example: the unit circle and four points; check the answers, so the
    // example shows what it claims (inside, inside, inside, outside).
    let dir = std::env::temp_dir().join(format!("inrs-readme-answers-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let points = dir.join("points.csv");
    std::fs::write(&points, "x,y\n0,0\n0.5,0.5\n0.99,0\n2,0\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_inrs"))
        .args(["classify", "--domain"])
        .arg(repo().join("fixtures/inrs-paper/circle.json"))
        .arg("--points")
        .arg(&points)
        .output()
        .unwrap();
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let locations: Vec<&str> = text
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    assert_eq!(locations, ["inside", "inside", "inside", "outside"]);
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    assert!(readme.contains(r"printf 'x,y\n0,0\n0.5,0.5\n0.99,0\n2,0\n' > points.csv"));
    std::fs::remove_dir_all(&dir).ok();
}

/// Relative links `[text](target)` and images `![alt](target)` of a Markdown text (no
/// `http(s):`, `mailto:` or in-page `#` links), without their `#anchor`.
fn relative_links(markdown: &str) -> Vec<String> {
    let mut links = Vec::new();
    for part in markdown.split("](").skip(1) {
        let Some(end) = part.find(')') else { continue };
        let target = part[..end].split('#').next().unwrap_or("").trim();
        if target.is_empty() || target.contains("://") || target.starts_with("mailto:") {
            continue;
        }
        links.push(target.to_string());
    }
    links
}

#[test]
fn every_relative_link_in_the_docs_resolves() {
    let mut files = vec![repo().join("README.md"), repo().join("python/README.md")];
    let docs = std::fs::read_dir(repo().join("docs")).expect("docs/ exists");
    files.extend(
        docs.filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|e| e == "md")),
    );
    let mut checked = 0;
    for file in &files {
        let text = std::fs::read_to_string(file).expect("readable Markdown");
        let dir = file.parent().expect("a file has a directory");
        for link in relative_links(&text) {
            assert!(
                dir.join(&link).exists(),
                "{} links to {link}, which does not exist",
                file.display()
            );
            checked += 1;
        }
    }
    // README alone links docs/CLI.md, FORMATS.md, SEMANTICS.md, BENCHMARKS.md and more.
    assert!(checked >= 10, "only {checked} links found");
}

#[test]
fn links_are_found_and_external_ones_skipped() {
    let md = "see [a](docs/A.md#x), ![p](img/p.svg), [w](https://x.org) and [m](mailto:a@b)";
    assert_eq!(relative_links(md), ["docs/A.md", "img/p.svg"]);
}
