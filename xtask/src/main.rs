//! `cargo xtask`: project automation (demo now; benchmarks and reports as they land).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use inrs::{Domain, DomainSummary};

const HELP: &str = "\
cargo xtask <command>

Commands:
  demo [--fixtures DIR]   Load the built-in fixtures (default: fixtures/inrs-paper), print a
                          summary of each domain and check it against the file's reference data.
  help                    Show this help.
";

fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default()
}

fn demo(dir: &Path) -> Result<(), String> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(format!("no domain files in {}", dir.display()));
    }
    println!(
        "{:<28} {:>6} {:>6} {:>4} {:>6} {:>8} {:>20} {:>20}",
        "file", "curves", "pieces", "deg", "loops", "closed", "signed area", "reference area"
    );
    let mut summaries = Vec::new();
    let mut mismatches = 0;
    for path in &files {
        let d = Domain::from_json_file(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let s = DomainSummary::of(&d);
        let reference = std::fs::read_to_string(path)
            .ok()
            .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
            .and_then(|v| v.get("signed_area").and_then(serde_json::Value::as_f64));
        let ok = reference.is_none_or(|r| (r - s.signed_area).abs() <= 1e-12 * r.abs());
        mismatches += usize::from(!ok);
        let stem = path.file_stem().and_then(|x| x.to_str()).unwrap_or("?");
        println!(
            "{:<28} {:>6} {:>6} {:>4} {:>6} {:>8} {:>20.15} {:>20}",
            stem,
            s.curves,
            s.bezier_pieces,
            s.max_degree,
            s.loops.len(),
            if s.is_closed() { "yes" } else { "NO" },
            s.signed_area,
            reference.map_or("-".to_string(), |r| format!("{r:.15}"))
                + if ok { "" } else { " MISMATCH" },
        );
        summaries.push(s);
    }
    println!();
    for s in &summaries {
        println!("{s}\n");
    }
    if mismatches > 0 {
        return Err(format!(
            "{mismatches} domain(s) differ from their reference area"
        ));
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("demo") => {
            let dir = match args.iter().position(|a| a == "--fixtures") {
                Some(i) => match args.get(i + 1) {
                    Some(d) => PathBuf::from(d),
                    None => {
                        eprintln!("xtask: --fixtures needs a directory");
                        return ExitCode::FAILURE;
                    }
                },
                None => workspace_root().join("fixtures/inrs-paper"),
            };
            demo(&dir)
        }
        None | Some("help" | "--help" | "-h") => {
            print!("{HELP}");
            Ok(())
        }
        Some(other) => Err(format!("unknown command {other:?}\n\n{HELP}")),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("xtask: {e}");
            ExitCode::FAILURE
        }
    }
}
