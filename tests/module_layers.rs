//! The library's top-level modules form layers: no module uses another that uses it back,
//! directly or through others. Read from the source (`crate::<module>` outside comments).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

fn rust_files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Top-level module -> the top-level modules its code names as `crate::<name>`.
fn module_uses() -> BTreeMap<String, BTreeSet<String>> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut uses: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for file in files {
        let rel = file.strip_prefix(&src).unwrap();
        let first = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy();
        let module = first.trim_end_matches(".rs").to_string();
        if module == "lib" || module == "main" {
            continue;
        }
        let text = std::fs::read_to_string(&file).unwrap();
        let entry = uses.entry(module.clone()).or_default();
        for line in text.lines() {
            let code = line.split("//").next().unwrap_or("");
            for (i, _) in code.match_indices("crate::") {
                let name: String = code[i + 7..]
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                    .collect();
                // `crate::Error` and `crate::Violation` are the root's re-exports of `error`.
                let name = if name.starts_with(|c: char| c.is_ascii_uppercase()) {
                    "error".to_string()
                } else {
                    name
                };
                if !name.is_empty() && name != module {
                    entry.insert(name);
                }
            }
        }
    }
    uses
}

/// A cycle through `start`, if there is one.
fn cycle_from(
    uses: &BTreeMap<String, BTreeSet<String>>,
    start: &str,
    at: &str,
    path: &mut Vec<String>,
) -> Option<Vec<String>> {
    for next in uses.get(at).into_iter().flatten() {
        if next == start {
            let mut cycle = path.clone();
            cycle.push(next.clone());
            return Some(cycle);
        }
        if !path.contains(next) {
            path.push(next.clone());
            if let Some(c) = cycle_from(uses, start, next, path) {
                return Some(c);
            }
            path.pop();
        }
    }
    None
}

#[test]
fn no_module_uses_another_that_uses_it_back() {
    let uses = module_uses();
    assert!(uses.len() >= 10, "found only {:?}", uses.keys());
    for module in uses.keys() {
        let mut path = vec![module.clone()];
        if let Some(cycle) = cycle_from(&uses, module, module, &mut path) {
            panic!("import cycle: {}", cycle.join(" -> "));
        }
    }
}

#[test]
fn domain_types_depend_on_nothing_but_errors() {
    let uses = module_uses();
    let problem: Vec<&String> = uses["problem"].iter().collect();
    assert_eq!(problem, vec!["error"], "problem uses {problem:?}");
    // The independent checker shares types with the planners, never the command line.
    assert!(!uses["check"].contains("cli"));
}

#[test]
fn the_scan_sees_a_cycle_when_there_is_one() {
    let mut uses = module_uses();
    uses.get_mut("problem")
        .unwrap()
        .insert("compose".to_string());
    let mut path = vec!["problem".to_string()];
    assert!(cycle_from(&uses, "problem", "problem", &mut path).is_some());
}
