//! What the README and the guide show a command printing is what it prints:
//!
//! * the main job's excerpt: the first command of the README's "On a fresh machine" is run as
//!   written (into a scratch directory) and every line of each excerpt that follows "An excerpt
//!   of its output:" (the README's and the guide's "Install and the two commands") is found in
//!   its standard output, but for the execution times (the last column of the combination
//!   table, the end of the joint optimum's line), which depend on the machine;
//! * every ```text block that directly follows a ```sh block: the block's commands are run in
//!   order (in one scratch directory) and every line of the text is found in what they print,
//!   the times in milliseconds aside.

mod common;

use common::docs::{documents, sh_blocks, with_binary};
use std::path::PathBuf;
use std::process::Command;

/// A line with its runs of spaces made one, a combination row's timing column dropped, and the
/// joint optimum's line cut before its times (`; ms/request ...`).
fn normalised(line: &str) -> String {
    let line = match line.find("; ms/request") {
        Some(at) if line.starts_with("joint optimum (") => &line[..at],
        _ => line,
    };
    let words: Vec<&str> = line.split_whitespace().collect();
    let is_row = words
        .first()
        .is_some_and(|w| w.matches('/').count() == 2 && !w.contains(' '))
        && words.len() == 9;
    let keep = if is_row { &words[..8] } else { &words[..] };
    keep.join(" ")
}

/// The lines of the ```text block after `marker` in `text`, `...` lines left out.
fn excerpt_after<'a>(text: &'a str, marker: &str) -> Option<Vec<&'a str>> {
    let lines = text
        .split(marker)
        .nth(1)?
        .split("```text\n")
        .nth(1)?
        .split("\n```")
        .next()?
        .lines()
        .filter(|l| l.trim() != "...")
        .collect();
    Some(lines)
}

#[test]
fn the_readme_excerpt_is_the_main_jobs_output() {
    let docs = documents();
    let readme = &docs[0].text;
    let command = readme
        .lines()
        .find(|l| l.starts_with("cargo run --release -- bench"))
        .expect("the main job");
    let args: Vec<&str> = command
        .split(" #")
        .next()
        .unwrap()
        .trim()
        .strip_prefix("cargo run --release -- ")
        .unwrap()
        .split_whitespace()
        .collect();
    assert!(
        args.contains(&"--request-limit") && args.contains(&"500"),
        "{args:?}"
    );
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("readme_excerpt");
    std::fs::create_dir_all(&dir).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args(&args)
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let printed: Vec<String> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(normalised)
        .collect();
    let mut excerpts = 0;
    let mut missing = Vec::new();
    for doc in &docs {
        let Some(excerpt) = excerpt_after(&doc.text, "An excerpt of its output:") else {
            continue;
        };
        excerpts += 1;
        assert!(excerpt.len() >= 4, "{}: {} lines", doc.name, excerpt.len());
        missing.extend(
            excerpt
                .iter()
                .filter(|l| !printed.contains(&normalised(l)))
                .map(|l| format!("{}: {l}", doc.name)),
        );
    }
    assert!(excerpts >= 2, "the README's and the guide's excerpts");
    assert!(
        missing.is_empty(),
        "excerpt lines the main job does not print:\n{}",
        missing.join("\n")
    );
}

/// A line with its runs of spaces made one and every time in milliseconds (`1.38 ms`) made `_ ms`.
fn without_times(line: &str) -> String {
    let words: Vec<&str> = line.split_whitespace().collect();
    let mut out = Vec::new();
    for (i, w) in words.iter().enumerate() {
        let next_is_ms = words
            .get(i + 1)
            .is_some_and(|n| n.trim_end_matches(',') == "ms");
        let number = w.parse::<f64>().is_ok();
        out.push(if next_is_ms && number { "_" } else { w });
    }
    out.join(" ")
}

#[test]
fn every_output_shown_after_a_command_block_is_what_it_prints() {
    let binary = PathBuf::from(env!("CARGO_BIN_EXE_swarmplan"));
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("readme_outputs");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("instances"),
        dir.join("instances"),
    )
    .unwrap();
    let (mut shown, mut missing) = (0, Vec::new());
    for doc in documents() {
        for block in sh_blocks(&doc.text) {
            let Some(output) = block.output else {
                continue;
            };
            shown += 1;
            let mut printed = String::new();
            for line in &block.lines {
                let out = Command::new("sh")
                    .arg("-c")
                    .arg(with_binary(line, &binary))
                    .current_dir(&dir)
                    .output()
                    .unwrap();
                assert_eq!(out.status.code(), Some(0), "{}: {line}: {out:?}", doc.name);
                printed.push_str(&String::from_utf8_lossy(&out.stdout));
            }
            let printed: Vec<String> = printed.lines().map(without_times).collect();
            missing.extend(
                output
                    .lines()
                    .filter(|l| l.trim() != "..." && !printed.contains(&without_times(l)))
                    .map(|l| format!("{}: {l}", doc.name)),
            );
        }
    }
    assert!(shown >= 5, "{shown} outputs shown");
    assert!(
        missing.is_empty(),
        "lines shown as output that the commands do not print:\n{}",
        missing.join("\n")
    );
}

#[test]
fn a_combination_row_loses_its_timing_column_only() {
    assert_eq!(
        normalised("pb/location-aware/sequential   463/500  878.3  794.5  21.1  84/463  398.8%  6157.8%  0.37"),
        "pb/location-aware/sequential 463/500 878.3 794.5 21.1 84/463 398.8% 6157.8%"
    );
    assert_eq!(normalised("  1a  holds   sharing"), "1a holds sharing");
    assert_eq!(
        normalised("joint optimum (route): delivers 500/500; arcs flown 1 of 2; ms/request median 60.5, max 4484.4"),
        "joint optimum (route): delivers 500/500; arcs flown 1 of 2"
    );
    assert_eq!(
        normalised("fb/energy-aware/astar   469   31   522.1 (327.9%)   15.9 (10.0%)"),
        "fb/energy-aware/astar 469 31 522.1 (327.9%) 15.9 (10.0%)"
    );
    assert_eq!(
        without_times("delivered: dt 37.84 min; 2 stop(s); 1.38 ms"),
        "delivered: dt 37.84 min; 2 stop(s); _ ms"
    );
}
