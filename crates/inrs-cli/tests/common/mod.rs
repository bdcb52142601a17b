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
#[allow(dead_code)] // not every test binary reads fixtures
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
#[allow(dead_code)] // not every test binary reads CSV
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

/// A `.npy` file read back: its shape and float64 data, after checking the header is the
/// version 1.0 C-order float64 one `NumPy` reads.
#[allow(dead_code)] // not every test binary reads .npy files
pub(crate) fn read_npy(path: &std::path::Path) -> (Vec<usize>, Vec<f64>) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00", "{}", path.display());
    let header_len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let header = std::str::from_utf8(&bytes[10..10 + header_len]).unwrap();
    assert_eq!(
        (10 + header_len) % 64,
        0,
        "NumPy aligns the data to 64 bytes"
    );
    assert!(header.contains("'descr': '<f8'"), "{header}");
    assert!(header.contains("'fortran_order': False"), "{header}");
    let shape_text = header
        .split("'shape': (")
        .nth(1)
        .and_then(|t| t.split(')').next())
        .unwrap();
    let shape: Vec<usize> = shape_text
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect();
    let data: Vec<f64> = bytes[10 + header_len..]
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    assert_eq!(
        data.len(),
        shape.iter().product::<usize>(),
        "{}: data and shape disagree",
        path.display()
    );
    assert_eq!((bytes.len() - 10 - header_len) % 8, 0);
    (shape, data)
}
