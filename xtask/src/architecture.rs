//! docs/ARCHITECTURE.md's crate table says what each crate depends on; a test here keeps the
//! column equal to the manifests and the rows in dependency order.

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;
    use std::path::Path;

    /// The workspace crates a manifest's `[dependencies]` section names.
    fn manifest_dependencies(manifest: &str, crates: &BTreeSet<String>) -> BTreeSet<String> {
        let mut in_dependencies = false;
        let mut found = BTreeSet::new();
        for line in manifest.lines() {
            let line = line.trim();
            if line.starts_with('[') {
                in_dependencies = line == "[dependencies]";
                continue;
            }
            let name = line.split(['.', ' ', '=']).next().unwrap_or("");
            if in_dependencies && crates.contains(name) {
                found.insert(name.to_string());
            }
        }
        found
    }

    /// Every row's "depends on" cell names exactly the workspace crates its manifest depends on
    /// and each of them is in an earlier row.
    #[test]
    fn the_crate_table_matches_the_manifests() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let doc = std::fs::read_to_string(root.join("docs/ARCHITECTURE.md")).unwrap();
        let rows: Vec<(String, String)> = doc
            .lines()
            .skip_while(|l| !l.starts_with("| crate | owns | depends on |"))
            .skip(2)
            .map_while(|l| {
                let name = l.strip_prefix("| `")?.split('`').next()?.to_string();
                let deps = l.trim_end_matches(" |").rsplit(" | ").next()?.to_string();
                Some((name, deps))
            })
            .collect();
        let crates: BTreeSet<String> = rows.iter().map(|(n, _)| n.clone()).collect();
        assert!(crates.len() >= 16, "{crates:?}");
        for (k, (name, cell)) in rows.iter().enumerate() {
            let dir = if name == "xtask" {
                root.join("xtask")
            } else {
                root.join("crates").join(name)
            };
            let manifest = std::fs::read_to_string(dir.join("Cargo.toml"))
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            let actual = manifest_dependencies(&manifest, &crates);
            let above: BTreeSet<String> = rows[..k].iter().map(|(n, _)| n.clone()).collect();
            assert!(
                actual.is_subset(&above),
                "{name} depends on {:?}, listed below it",
                actual.difference(&above).collect::<Vec<_>>()
            );
            let listed: BTreeSet<String> = cell
                .split([',', '(', ')', ' '])
                .filter(|w| crates.contains(*w))
                .map(str::to_string)
                .collect();
            assert_eq!(listed, actual, "the depends-on cell of {name}");
        }
    }
}
