//! Running the `inrs` binary and the files its tests read, shared by the test binaries.

use std::process::Command;

/// Runs `inrs` with `args`.
pub(crate) fn inrs(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_inrs"))
        .args(args)
        .output()
        .expect("run inrs")
}

/// A file of `fixtures/`.
pub(crate) fn fixture(rel: &str) -> String {
    format!("{}/../../fixtures/{rel}", env!("CARGO_MANIFEST_DIR"))
}

/// Writes `text` to `name` in this process's scratch directory; returns its path.
pub(crate) fn temp_file(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("inrs-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// Runs `inrs`, asserts success and returns standard output.
pub(crate) fn inrs_ok(args: &[&str]) -> String {
    stdout_of_success(inrs(args))
}

/// The standard output of a run that must have succeeded (its standard error otherwise).
pub(crate) fn stdout_of_success(out: std::process::Output) -> String {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The last column of a CSV output, as text.
pub(crate) fn last_column(text: &str) -> Vec<String> {
    text.lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap().to_string())
        .collect()
}

/// A fresh scratch directory for one test, `inrs-{command}-{test}-{pid}` in the system's
/// temporary directory.
#[allow(dead_code)] // not every test binary writes files
pub(crate) fn scratch(command: &str, test: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("inrs-{command}-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The directory's entries, sorted.
#[allow(dead_code)] // not every test binary writes files
pub(crate) fn entries(dir: &std::path::Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}
