//! The documents whose commands the tests run: the README, then every page of the user guide in
//! the order of `docs/src/SUMMARY.md`, each page with its `{{#include ...}}` lines replaced by the
//! files they name (as `mdbook build` does), and their ```sh blocks.

use std::path::{Path, PathBuf};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A document: its path in the repository and its text.
pub struct Document {
    pub name: String,
    pub text: String,
}

/// `text` with every `{{#include FILE}}` replaced by FILE's text, FILE relative to `dir`.
fn with_includes(text: &str, dir: &Path) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(i) = rest.find("{{#include ") {
        out.push_str(&rest[..i]);
        let after = &rest[i + "{{#include ".len()..];
        let end = after.find("}}").expect("an include ends with }}");
        let file = dir.join(after[..end].trim());
        let included = std::fs::read_to_string(&file)
            .unwrap_or_else(|e| panic!("include {}: {e}", file.display()));
        out.push_str(&included);
        rest = &after[end + 2..];
    }
    out.push_str(rest);
    out
}

/// The pages `docs/src/SUMMARY.md` lists, in its order, relative to `docs/src`.
pub fn guide_pages() -> Vec<String> {
    let summary = std::fs::read_to_string(repo().join("docs/src/SUMMARY.md")).unwrap();
    summary
        .match_indices("](")
        .map(|(i, _)| {
            let rest = &summary[i + 2..];
            rest[..rest.find(')').expect("a link ends with )")].to_string()
        })
        .collect()
}

/// The README, then the guide's pages in reading order.
pub fn documents() -> Vec<Document> {
    let mut out = vec![Document {
        name: "README.md".into(),
        text: std::fs::read_to_string(repo().join("README.md")).unwrap(),
    }];
    let src = repo().join("docs/src");
    for page in guide_pages() {
        let file = src.join(&page);
        let text =
            std::fs::read_to_string(&file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        out.push(Document {
            name: format!("docs/src/{page}"),
            text: with_includes(&text, file.parent().unwrap()),
        });
    }
    out
}

/// A ```sh block: its command lines (continuation lines joined, comments removed) and the
/// ```text block that follows it with only blank lines between, which shows what it prints.
pub struct ShBlock {
    pub lines: Vec<String>,
    pub output: Option<String>,
}

/// The ```sh blocks of `text`, in order.
pub fn sh_blocks(text: &str) -> Vec<ShBlock> {
    let lines: Vec<&str> = text.lines().collect();
    let mut blocks = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        if !lines[i].starts_with("```") {
            i += 1;
            continue;
        }
        let is_sh = lines[i].trim() == "```sh";
        let start = i + 1;
        let mut end = start;
        while end < lines.len() && !lines[end].starts_with("```") {
            end += 1;
        }
        i = end + 1;
        if !is_sh {
            continue;
        }
        let mut block = ShBlock {
            lines: command_lines(&lines[start..end.min(lines.len())]),
            output: None,
        };
        let mut next = i;
        while next < lines.len() && lines[next].trim().is_empty() {
            next += 1;
        }
        if next < lines.len() && lines[next].trim() == "```text" {
            let body_end = (next + 1..lines.len())
                .find(|&k| lines[k].starts_with("```"))
                .unwrap_or(lines.len());
            block.output = Some(lines[next + 1..body_end].join("\n"));
            i = body_end + 1;
        }
        blocks.push(block);
    }
    blocks
}

/// The command lines of a block's lines: continuation lines joined, comments removed.
fn command_lines(lines: &[&str]) -> Vec<String> {
    let mut out = Vec::new();
    let mut pending = String::new();
    for line in lines {
        let code = match line.find(" #") {
            Some(i) => &line[..i],
            None if line.trim_start().starts_with('#') => "",
            None => line,
        };
        let code = code.trim();
        if let Some(head) = code.strip_suffix('\\') {
            pending.push_str(head.trim_end());
            pending.push(' ');
            continue;
        }
        pending.push_str(code);
        if !pending.trim().is_empty() {
            out.push(pending.trim().to_string());
        }
        pending.clear();
    }
    out
}

/// `line` with the binary `binary` in place of `cargo run --release --` and of a
/// command-leading `swarmplan`.
pub fn with_binary(line: &str, binary: &Path) -> String {
    let binary = binary.display().to_string();
    let line = line.replace("cargo run --release --", &binary);
    line.split(" | ")
        .map(|part| match part.strip_prefix("swarmplan ") {
            Some(rest) => format!("{binary} {rest}"),
            None => part.to_string(),
        })
        .collect::<Vec<_>>()
        .join(" | ")
}
