//! docs/FRONTENDS.md names, for each capability and front end, the test that exercises it;
//! a test here keeps every named test real.

#[cfg(test)]
mod tests {
    use std::path::Path;

    /// Every `path::name` the table cites (a `…` stands for the row's previous file) is a test
    /// function in that file, and every row names at least one test per front end.
    #[test]
    fn every_test_the_frontends_table_names_exists() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let table = std::fs::read_to_string(root.join("docs/FRONTENDS.md")).unwrap();
        let rows: Vec<&str> = table
            .lines()
            .filter(|l| l.starts_with("| ") && !l.starts_with("| Capability"))
            .collect();
        assert!(rows.len() >= 20, "{} rows", rows.len());
        let mut checked = 0;
        for row in rows {
            let cells: Vec<&str> = row.split(" | ").skip(1).collect();
            assert_eq!(cells.len(), 3, "{row}");
            for cell in cells {
                let mut file = String::new();
                let mut found = 0;
                for code in cell.split('`').skip(1).step_by(2) {
                    let Some((path, name)) = code.rsplit_once("::") else {
                        continue;
                    };
                    let path = path
                        .strip_prefix("…")
                        .map_or(path.to_string(), |_| file.clone());
                    if !(path.ends_with(".rs") || path.ends_with(".py")) {
                        continue;
                    }
                    file = path.clone();
                    let text = std::fs::read_to_string(root.join(&path))
                        .unwrap_or_else(|e| panic!("{path}: {e}"));
                    let def = if path.ends_with(".py") { "def " } else { "fn " };
                    assert!(
                        text.contains(&format!("{def}{name}(")),
                        "{path} has no test {name}"
                    );
                    found += 1;
                }
                assert!(
                    found > 0 || cell.contains("same"),
                    "no test named in {cell}"
                );
                checked += found;
            }
        }
        assert!(checked >= 40, "{checked} tests checked");
    }
}
