//! The library's top-level modules form layers: no module uses another that uses it back,
//! directly or through others. Read from the source (`crate::<module>` outside comments).

mod common;

use common::rust_files;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

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
fn the_experiment_core_lies_below_bench_and_the_command_line() {
    let uses = module_uses();
    // `batch` (the command line) and `bench` share one experiment core, which knows neither.
    assert!(uses["bench"].contains("experiment") && uses["cli"].contains("experiment"));
    for above in ["bench", "check", "cli"] {
        assert!(
            !uses["experiment"].contains(above),
            "experiment uses {above}"
        );
    }
    // Nor the argument parser: the command line gives it plain values.
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/experiment");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    assert!(!files.is_empty());
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        assert!(!text.contains("clap"), "{} names clap", file.display());
    }
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

/// Inside the module directory `dir` (relative to `src`): each child module (a file, or a
/// directory's `mod.rs` for the root) -> the siblings its code names as `super::<child>`,
/// `crate::<dir path>::<child>` or, from the root, `self::<child>`/`<child>::`. The root is
/// `mod`; a child naming the root's own items (`super::Item`) uses `mod`.
fn child_uses(dir: &str) -> BTreeMap<String, BTreeSet<String>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src").join(dir);
    let children: Vec<String> = std::fs::read_dir(&root)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "rs"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().to_string())
        .collect();
    let crate_path = format!("crate::{}::", dir.replace('/', "::"));
    let mut uses: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for child in &children {
        let text = std::fs::read_to_string(root.join(format!("{child}.rs"))).unwrap();
        let entry = uses.entry(child.clone()).or_default();
        for line in text.lines() {
            let code = line.split("//").next().unwrap_or("").trim();
            if code.starts_with("pub mod ") || code.starts_with("mod ") {
                continue;
            }
            if child == "mod" {
                // The root names a child bare: `milp::Grid`, `pub use milp::...`.
                for other in &children {
                    let bare = format!("{other}::");
                    let named = code.match_indices(&bare).any(|(i, _)| {
                        i == 0
                            || !code[..i].ends_with(|c: char| {
                                c.is_ascii_alphanumeric() || c == '_' || c == ':'
                            })
                    });
                    if named && other != "mod" {
                        entry.insert(other.clone());
                    }
                }
            }
            for prefix in ["super::", crate_path.as_str(), "self::"] {
                for (i, _) in code.match_indices(prefix) {
                    let name: String = code[i + prefix.len()..]
                        .chars()
                        .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                        .collect();
                    let target = if children.contains(&name) && name != *child {
                        name
                    } else if prefix == "super::" && child != "mod" {
                        "mod".to_string()
                    } else {
                        continue;
                    };
                    if target != *child {
                        entry.insert(target);
                    }
                }
            }
        }
    }
    uses
}

/// The exact hop models: the root holds the shared vocabulary and uses none of its
/// formulations; no formulation uses another that uses it back.
#[test]
fn exact_hop_models_form_layers_under_their_shared_root() {
    let uses = child_uses("eaas/exact");
    assert!(
        ["continuous", "fluid", "milp", "mod"]
            .iter()
            .all(|c| uses.contains_key(*c)),
        "found {:?}",
        uses.keys()
    );
    assert!(uses["mod"].is_empty(), "the root uses {:?}", uses["mod"]);
    for child in uses.keys() {
        let mut path = vec![child.clone()];
        if let Some(cycle) = cycle_from(&uses, child, child, &mut path) {
            panic!("import cycle in eaas/exact: {}", cycle.join(" -> "));
        }
    }
    // The formulations share the root's vocabulary.
    assert!(uses["continuous"].contains("mod") && uses["milp"].contains("mod"));
}

#[test]
fn the_scan_of_a_module_directory_sees_a_cycle_when_there_is_one() {
    let mut uses = child_uses("eaas/exact");
    uses.get_mut("mod").unwrap().insert("milp".to_string());
    let mut path = vec!["mod".to_string()];
    assert!(cycle_from(&uses, "mod", "mod", &mut path).is_some());
}

/// Every module directory under `src` (relative paths, `/`-separated), found by its `mod.rs`.
fn module_directories() -> Vec<String> {
    fn walk(dir: &Path, rel: &str, out: &mut Vec<String>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                let name = path.file_name().unwrap().to_string_lossy().to_string();
                let rel = if rel.is_empty() {
                    name
                } else {
                    format!("{rel}/{name}")
                };
                if path.join("mod.rs").is_file() {
                    out.push(rel.clone());
                }
                walk(&path, &rel, out);
            }
        }
    }
    let mut out = Vec::new();
    walk(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
        "",
        &mut out,
    );
    out.sort();
    out
}

/// Inside every module directory, the children (apart from the root, whose items they share and
/// which re-exports them) form layers: no child uses a sibling that uses it back, directly or
/// through others.
#[test]
fn every_module_directory_layers_its_children() {
    let dirs = module_directories();
    assert!(
        dirs.len() >= 15 && dirs.iter().any(|d| d == "node_time/exact"),
        "found {dirs:?}"
    );
    for dir in dirs {
        let mut uses = child_uses(&dir);
        uses.remove("mod");
        for targets in uses.values_mut() {
            targets.remove("mod");
        }
        for child in uses.keys() {
            let mut path = vec![child.clone()];
            if let Some(cycle) = cycle_from(&uses, child, child, &mut path) {
                panic!("import cycle in src/{dir}: {}", cycle.join(" -> "));
            }
        }
    }
}

/// The lines of `text` that name a front-end crate (clap, plotters, indicatif) or the command
/// line module outside an attribute applying with the `cli` feature, 1-based.
fn ungated_front_end_lines(text: &str) -> Vec<usize> {
    text.lines()
        .enumerate()
        .filter(|(_, line)| {
            let code = line.split("//").next().unwrap_or("");
            let names_front_end = ["clap::", "plotters", "indicatif", "crate::cli"]
                .iter()
                .any(|name| code.contains(name));
            names_front_end
                && !code
                    .trim_start()
                    .starts_with("#[cfg_attr(feature = \"cli\"")
        })
        .map(|(n, _)| n + 1)
        .collect()
}

/// The planning core is free of the front ends: outside `src/cli` (the command line),
/// `src/bench/figures.rs` (the bench's SVG figures) and `src/plot/draw.rs` (a plan's; both
/// feature `plot`), clap, plotters and indicatif are named only in attributes that apply with
/// the `cli` feature, and no module uses `crate::cli`. With `--no-default-features --features
/// microlp` the library builds without the three crates, with `--features microlp,plot` with
/// plotters alone (`.ci/run` builds both).
#[test]
fn the_core_names_no_front_end_crate() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut found = Vec::new();
    for file in files {
        let rel = file.strip_prefix(&src).unwrap().to_path_buf();
        let front_end = rel.starts_with("cli")
            || rel == Path::new("bench/figures.rs")
            || rel == Path::new("plot/draw.rs")
            || rel == Path::new("main.rs");
        if front_end {
            continue;
        }
        let text = std::fs::read_to_string(&file).unwrap();
        for n in ungated_front_end_lines(&text) {
            found.push(format!("src/{}:{n}", rel.display()));
        }
    }
    assert!(found.is_empty(), "front-end crates in the core: {found:?}");
}

#[test]
fn the_front_end_scan_sees_an_ungated_name() {
    let text = "#[derive(Debug, Clone)]\n#[cfg_attr(feature = \"cli\", derive(clap::ValueEnum))]\n\
                #[derive(Debug, clap::ValueEnum)] // clap::\nuse crate::cli::inputs;\n// plotters\n";
    assert_eq!(ungated_front_end_lines(text), vec![3, 4]);
}

/// The `pub use` lines of `text` that re-export from somewhere other than a child module of the
/// file (`crate::...`, `super::...`, `self::...`): a second public path to an item defined
/// elsewhere. A module may gather its private children's items (`pub use child::Item`).
fn public_aliases(text: &str) -> Vec<String> {
    text.lines()
        .map(str::trim_start)
        .filter(|l| l.starts_with("pub use "))
        .filter(|l| {
            let path = &l["pub use ".len()..];
            ["crate::", "super::", "self::"]
                .iter()
                .any(|p| path.starts_with(p))
        })
        .map(str::to_string)
        .collect()
}

/// The `pub use child::...` lines of a module whose `child` is itself public: a second path to
/// the child's items (`module::Item` beside `module::child::Item`).
fn facades_of_public_children(text: &str) -> Vec<String> {
    let public_children: Vec<&str> = text
        .lines()
        .filter_map(|l| l.strip_prefix("pub mod "))
        .filter_map(|l| l.strip_suffix(';'))
        .collect();
    text.lines()
        .filter_map(|l| l.strip_prefix("pub use "))
        .filter(|path| {
            public_children.iter().any(|c| {
                path.strip_prefix(c)
                    .is_some_and(|rest| rest.starts_with("::"))
            })
        })
        .map(|path| format!("pub use {path}"))
        .collect()
}

#[test]
fn every_public_item_has_one_path_in_the_library() {
    let mut files = Vec::new();
    rust_files(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
        &mut files,
    );
    let mut found = Vec::new();
    for f in &files {
        let text = std::fs::read_to_string(f).unwrap();
        for line in public_aliases(&text) {
            found.push(format!("{}: {line}", f.display()));
        }
        for line in facades_of_public_children(&text) {
            found.push(format!(
                "{}: {line} (the child module is public too)",
                f.display()
            ));
        }
    }
    assert!(
        found.is_empty(),
        "re-exports of items defined elsewhere (import them from their module): {found:#?}"
    );
}

#[test]
fn the_alias_scan_sees_a_re_export_from_elsewhere() {
    let text = "mod child;\npub use child::Item;\n    pub use crate::eaas::exact::Objective;\n\
                pub use super::EndPads;\nuse crate::x::Y;\n";
    assert_eq!(
        public_aliases(text),
        [
            "pub use crate::eaas::exact::Objective;",
            "pub use super::EndPads;"
        ]
    );
}

#[test]
fn the_facade_scan_sees_a_public_child_re_exported() {
    let text = "pub mod shown;\nmod hidden;\npub mod other;\npub use shown::Item;\n\
                pub use hidden::{A, B};\npub use shownx::C;\n";
    assert_eq!(facades_of_public_children(text), ["pub use shown::Item;"]);
}
