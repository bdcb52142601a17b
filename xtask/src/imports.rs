//! The module graph of each crate, read from its sources: which module names which through
//! `crate::` and `super::` paths. Used by a test that keeps the imports pointing one way (no
//! module imports another that imports it back), as the crates' dependencies do.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A crate's modules (`a::b`, the crate root `""`) and, for each, the modules it names.
pub(crate) type ModuleGraph = BTreeMap<String, BTreeSet<String>>;

/// The module graph of the crate whose `src/` is `src`, tests and comments left out (a test
/// module may name anything; a doc link is not an import).
pub(crate) fn module_graph(src: &Path) -> std::io::Result<ModuleGraph> {
    let mut files = Vec::new();
    rust_files(src, &mut files)?;
    let mut code = BTreeMap::new();
    for f in &files {
        code.insert(
            module_name(src, f),
            non_test_code(&std::fs::read_to_string(f)?),
        );
    }
    // Where each item name is defined (a name may be defined in several modules).
    let mut defined: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (m, text) in &code {
        for name in definitions(text) {
            defined.entry(name).or_default().insert(m.clone());
        }
    }
    let modules: BTreeSet<String> = code.keys().cloned().collect();
    let mut graph = ModuleGraph::new();
    for (m, text) in &code {
        let parent: Vec<&str> = m.split("::").filter(|s| !s.is_empty()).collect();
        let parent = &parent[..parent.len().saturating_sub(1)];
        let mut named = BTreeSet::new();
        for (from_root, path) in paths(text) {
            let mut full: Vec<String> = if from_root {
                Vec::new()
            } else {
                parent.iter().map(|s| s.to_string()).collect()
            };
            // `super::super::x`: each further `super` climbs one more level.
            let ups = path.iter().take_while(|s| *s == "super").count();
            full.truncate(full.len().saturating_sub(ups));
            full.extend(path.into_iter().skip(ups));
            // The longest prefix that is a module; an item at the crate root (a re-export)
            // stands for the modules that define it.
            let module = (1..=full.len())
                .rev()
                .map(|k| full[..k].join("::"))
                .find(|c| modules.contains(c));
            match module {
                Some(c) => {
                    named.insert(c);
                }
                None => {
                    if let Some(ds) = full.last().and_then(|n| defined.get(n)) {
                        named.extend(ds.iter().cloned());
                    }
                }
            }
        }
        named.retain(|n| n != m && !n.is_empty() && !m.starts_with(&format!("{n}::")));
        graph.insert(m.clone(), named);
    }
    Ok(graph)
}

/// The pairs of modules that name each other (neither inside the other).
pub(crate) fn mutual_imports(graph: &ModuleGraph) -> Vec<(String, String)> {
    let mut pairs = Vec::new();
    for (a, named) in graph {
        for b in named {
            let back = graph.get(b).is_some_and(|n| n.contains(a));
            let nested = b.starts_with(&format!("{a}::"));
            if back && a < b && !nested {
                pairs.push((a.clone(), b.clone()));
            }
        }
    }
    pairs
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        if path.is_dir() {
            rust_files(&path, out)?;
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
    Ok(())
}

/// `a/b.rs` and `a/b/mod.rs` are `a::b`; `lib.rs` and `main.rs` the root `""`.
fn module_name(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).unwrap_or(file).with_extension("");
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if parts
        .last()
        .is_some_and(|l| l == "mod" || l == "lib" || l == "main")
    {
        parts.pop();
    }
    parts.join("::")
}

/// The code before the first `#[cfg(test)]`, without comment lines.
fn non_test_code(text: &str) -> String {
    let code = text.split("#[cfg(test)]").next().unwrap_or("");
    code.lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// The names of the items a module defines at its top level (`fn`, `struct`, `enum`, `trait`,
/// `const`, `static`, `type`, `macro_rules!` at the start of a line; an associated type or a
/// method is not an item of the module).
fn definitions(text: &str) -> Vec<String> {
    let keywords = [
        "fn",
        "struct",
        "enum",
        "trait",
        "const",
        "static",
        "type",
        "macro_rules!",
    ];
    let mut names = Vec::new();
    for line in text.lines() {
        if line.starts_with(char::is_whitespace) {
            continue;
        }
        let words: Vec<&str> = line
            .split(|c: char| !(is_ident(c) || c == '!'))
            .filter(|w| !w.is_empty() && !matches!(*w, "pub" | "crate" | "super" | "unsafe"))
            .collect();
        if let [kind, name, ..] = words[..]
            && keywords.contains(&kind)
        {
            names.push(name.trim_end_matches('!').to_string());
        }
    }
    names
}

/// Every path after `crate::` (`true`) or `super::` (`false`), brace groups expanded one
/// level: `crate::{A, b::C}` gives `[A]` and `[b, C]`.
fn paths(text: &str) -> Vec<(bool, Vec<String>)> {
    let mut out = Vec::new();
    for (from_root, key) in [(true, "crate::"), (false, "super::")] {
        let mut rest = text;
        while let Some(i) = rest.find(key) {
            let before = rest[..i].chars().next_back();
            rest = &rest[i + key.len()..];
            if before.is_some_and(|c| is_ident(c) || c == ':' || c == '$') {
                continue; // `$crate::`, `a::super::`
            }
            let mut head = Vec::new();
            let mut s = rest;
            loop {
                let n = s.find(|c: char| !is_ident(c)).unwrap_or(s.len());
                if n == 0 {
                    break;
                }
                head.push(s[..n].to_string());
                s = &s[n..];
                if let Some(t) = s.strip_prefix("::") {
                    s = t;
                } else {
                    break;
                }
            }
            if let Some(group) = s.strip_prefix('{') {
                let end = group.find('}').unwrap_or(group.len());
                for entry in group[..end].split(',') {
                    let mut p = head.clone();
                    p.extend(
                        entry
                            .split("::")
                            .map(|s| s.trim().trim_matches(|c: char| !is_ident(c)))
                            .filter(|s| !s.is_empty() && *s != "self")
                            .map(str::to_string),
                    );
                    out.push((from_root, p));
                }
            } else if !head.is_empty() {
                out.push((from_root, head));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// No module of any crate (or the Python binding) names a module that names it back.
    #[test]
    fn no_module_imports_one_that_imports_it_back() {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let mut sources: Vec<PathBuf> = std::fs::read_dir(root.join("crates"))
            .unwrap()
            .map(|e| e.unwrap().path().join("src"))
            .filter(|p| p.is_dir())
            .collect();
        sources.push(root.join("python/src"));
        sources.push(root.join("xtask/src"));
        assert!(sources.len() > 12, "{sources:?}");
        let mut circles = Vec::new();
        for src in &sources {
            let graph = module_graph(src).unwrap();
            for (a, b) in mutual_imports(&graph) {
                circles.push(format!("{}: {a} <-> {b}", src.display()));
            }
        }
        assert!(circles.is_empty(), "{circles:#?}");
    }

    /// The reader finds a planted circle through a brace group, a `super::` path and a
    /// re-export at the crate root, and ignores comments and tests.
    #[test]
    fn a_planted_circle_is_found() {
        let dir = std::env::temp_dir().join(format!("inrs-imports-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("a")).unwrap();
        let write = |p: &str, t: &str| std::fs::write(dir.join(p), t).unwrap();
        write("lib.rs", "mod a;\nmod b;\npub use b::Bee;\n");
        write("a/mod.rs", "mod c;\nuse crate::{Bee, x::Y};\n");
        write("a/c.rs", "use super::super::b::f;\n");
        write(
            "b.rs",
            "pub struct Bee;\n// crate::a\n#[cfg(test)]\nuse crate::a;\npub fn f() {}\n",
        );
        let graph = module_graph(&dir).unwrap();
        assert_eq!(graph["a"], BTreeSet::from(["b".to_string()]));
        assert_eq!(graph["a::c"], BTreeSet::from(["b".to_string()]));
        assert!(graph["b"].is_empty(), "{graph:?}");
        assert!(mutual_imports(&graph).is_empty());
        write("b.rs", "use crate::a::c;\npub struct Bee;\n");
        let graph = module_graph(&dir).unwrap();
        assert_eq!(
            mutual_imports(&graph),
            vec![("a::c".to_string(), "b".to_string())]
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
