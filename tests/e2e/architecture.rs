//! The house rules of docs/architecture.md, checked on the source tree: no
//! source file over 600 lines, no two modules of one crate importing each
//! other, and nothing outside the engine reaching past its interface.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use crate::support::root;

/// Each crate's name and its source root.
const CRATES: [(&str, &str); 6] = [
    ("dsl", "dsl/src"),
    ("engine", "engine/src"),
    ("oracles", "oracles/src"),
    ("reports", "reports/src"),
    ("osi", "osi/src"),
    ("sightline", "src"),
];

/// The most lines a source file may hold, its test module aside.
const MAX_LINES: usize = 600;

/// A module: its path from the crate root (`["compile", "world"]`).
type Module = Vec<String>;

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(dir) = pending.pop() {
        for entry in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
            let path = entry.expect("a directory entry reads").path();
            if path.is_dir() {
                pending.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    files.sort();
    files
}

/// The module a file under `src` holds (`lib.rs`, `main.rs` and `mod.rs` hold
/// their directory's).
fn module_of(src: &Path, file: &Path) -> Module {
    let relative = file.strip_prefix(src).expect("the file is under src");
    let mut module: Module = relative.iter().map(|s| s.to_string_lossy().into_owned()).collect();
    let last = module.pop().expect("a file name");
    let stem = last.trim_end_matches(".rs");
    if !matches!(stem, "lib" | "main" | "mod") {
        module.push(stem.to_string());
    }
    module
}

/// A source file's text up to its top-level test module, without comments.
fn code(text: &str) -> String {
    text.lines()
        .take_while(|line| *line != "#[cfg(test)]")
        .map(|line| line.find("//").map_or(line, |i| &line[..i]))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The modules declared under `#[cfg(test)]` (test-only files) by the files of a crate.
fn test_modules(src: &Path, files: &[PathBuf]) -> BTreeSet<Module> {
    let mut tests = BTreeSet::new();
    for file in files {
        let text = std::fs::read_to_string(file).expect("a source file reads");
        let lines: Vec<&str> = text.lines().collect();
        for pair in lines.windows(2) {
            if pair[0].trim() == "#[cfg(test)]"
                && let Some(name) = pair[1].trim().strip_prefix("mod ").and_then(|r| r.strip_suffix(';'))
            {
                let mut module = module_of(src, file);
                module.push(name.to_string());
                tests.insert(module);
            }
        }
    }
    tests
}

#[test]
fn no_source_file_is_over_600_lines() {
    let mut over = Vec::new();
    for (_, dir) in CRATES {
        let src = root().join(dir);
        let files = rust_files(&src);
        let tests = test_modules(&src, &files);
        for file in &files {
            if tests.contains(&module_of(&src, file)) {
                continue;
            }
            let text = std::fs::read_to_string(file).expect("a source file reads");
            let lines = text.lines().take_while(|line| *line != "#[cfg(test)]").count();
            if lines > MAX_LINES {
                over.push(format!(
                    "{} ({lines} lines)",
                    file.strip_prefix(root()).unwrap().display()
                ));
            }
        }
    }
    assert!(over.is_empty(), "over {MAX_LINES} lines: {over:#?}");
}

/// Expands a `use` tree (`a::{b, c::{d}}`, whitespace removed) into its paths.
fn expand(tree: &str) -> Vec<String> {
    let Some(open) = tree.find('{') else {
        return vec![tree.to_string()];
    };
    let (prefix, inner) = (&tree[..open], &tree[open + 1..tree.len() - 1]);
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (i, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    parts
        .into_iter()
        .filter(|p| !p.is_empty())
        .flat_map(|p| expand(&format!("{prefix}{p}")))
        .collect()
}

/// The crate-relative paths a module's code names, each once: its `use` trees,
/// and paths written out in code, from `crate::`, `super::` or `self::`.
fn named_paths(module: &Module, code: &str) -> BTreeSet<Vec<String>> {
    let mut trees: Vec<String> = Vec::new();
    for statement in code.split(';') {
        if let Some(at) = statement.find("use ") {
            let before = &statement[..at];
            if before.is_empty() || before.ends_with(|c: char| c.is_whitespace() || c == '{' || c == '}') {
                trees.push(statement[at + 4..].split_whitespace().collect());
            }
        }
    }
    for (at, _) in code.match_indices("::") {
        let start = code[..at]
            .rfind(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
            .map_or(0, |i| i + 1);
        let end = at
            + code[at..]
                .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .unwrap_or(0);
        let path = &code[start..end.max(at)];
        if ["crate::", "super::", "self::"].iter().any(|p| path.starts_with(p)) && !path.ends_with("::") {
            trees.push(path.to_string());
        }
    }
    let mut paths = BTreeSet::new();
    for path in trees.iter().flat_map(|t| expand(t)) {
        let mut segments = path.split("::").filter(|s| !s.is_empty());
        let mut resolved: Vec<String> = match segments.next() {
            Some("crate") => Vec::new(),
            Some("super") => module[..module.len().saturating_sub(1)].to_vec(),
            Some("self") => module.clone(),
            _ => continue,
        };
        for segment in segments {
            if segment == "super" {
                resolved.pop();
            } else {
                resolved.push(segment.to_string());
            }
        }
        paths.insert(resolved);
    }
    paths
}

/// Whether `a` is `b` or one of its ancestors.
fn is_ancestor(a: &Module, b: &Module) -> bool {
    b.starts_with(a)
}

#[test]
fn no_two_modules_of_a_crate_import_each_other() {
    let mut mutual = Vec::new();
    for (name, dir) in CRATES {
        let src = root().join(dir);
        let files = rust_files(&src);
        let modules: BTreeMap<Module, &PathBuf> = files.iter().map(|f| (module_of(&src, f), f)).collect();
        let mut imports: BTreeSet<(Module, Module)> = BTreeSet::new();
        for (module, file) in &modules {
            let text = std::fs::read_to_string(file).expect("a source file reads");
            for path in named_paths(module, &code(&text)) {
                // The deepest module the path names (an item's path ends in its module).
                let target = (0..=path.len())
                    .rev()
                    .map(|n| path[..n].to_vec())
                    .find(|m| modules.contains_key(m))
                    .expect("the crate root is a module");
                if !is_ancestor(&target, module) && !is_ancestor(module, &target) {
                    imports.insert((module.clone(), target));
                }
            }
        }
        for (a, b) in &imports {
            if a < b && imports.contains(&(b.clone(), a.clone())) {
                mutual.push(format!("{name}: {} <-> {}", a.join("::"), b.join("::")));
            }
        }
    }
    assert!(mutual.is_empty(), "modules importing each other: {mutual:#?}");
}

/// The engine's public interface is its root items, `outcome` and `trace`; its
/// `internals` feature is for its own tests and benches, so no other crate
/// enables or names it (the compiler keeps the private modules private).
#[test]
fn nothing_outside_the_engine_reaches_its_internals() {
    let mut reached = Vec::new();
    for dir in ["dsl", "oracles", "reports", "src", "tests"] {
        for file in rust_files(&root().join(dir)) {
            let text = std::fs::read_to_string(&file).expect("a source file reads");
            // Spelt in two, so that this file does not name it.
            if text.contains(concat!("sightline_engine::", "internals")) {
                reached.push(file.strip_prefix(root()).unwrap().display().to_string());
            }
        }
    }
    for manifest in [
        "Cargo.toml",
        "dsl/Cargo.toml",
        "oracles/Cargo.toml",
        "reports/Cargo.toml",
    ] {
        let text = std::fs::read_to_string(root().join(manifest)).expect("a manifest reads");
        if text.contains("internals") {
            reached.push(manifest.to_string());
        }
    }
    assert!(reached.is_empty(), "engine internals reached from: {reached:#?}");
}

/// The rules see what they are meant to see: a mutual import and a named path.
#[test]
fn the_import_scanner_reads_use_trees_and_paths() {
    let module: Module = vec!["compile".into(), "world".into()];
    let paths = named_paths(
        &module,
        "use super::{setup::Setup, traces::{Trace, x}};\nlet a = crate::geometry::length(b); use self::inner::Y;",
    );
    let names: Vec<String> = paths.iter().map(|p| p.join("::")).collect();
    assert_eq!(
        names,
        [
            "compile::setup::Setup",
            "compile::traces::Trace",
            "compile::traces::x",
            "compile::world::inner::Y",
            "geometry::length",
        ]
    );
    assert_eq!(code("a // b\n#[cfg(test)]\nmod tests;"), "a ");
}
