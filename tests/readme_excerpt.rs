//! The README's excerpt of the main job's output is that job's output: the first command of
//! "On a fresh machine" is run as written (into a scratch directory) and every line of the
//! excerpt that follows it is found in its standard output, but for the execution times (the
//! last column of the combination table), which depend on the machine.

use std::path::PathBuf;
use std::process::Command;

/// A line with its runs of spaces made one, and a combination row's timing column dropped.
fn normalised(line: &str) -> String {
    let words: Vec<&str> = line.split_whitespace().collect();
    let is_row = words
        .first()
        .is_some_and(|w| w.matches('/').count() == 2 && !w.contains(' '))
        && words.len() == 9;
    let keep = if is_row { &words[..8] } else { &words[..] };
    keep.join(" ")
}

#[test]
fn the_readme_excerpt_is_the_main_jobs_output() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
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
    let excerpt: Vec<&str> = readme
        .split("An excerpt of its output:")
        .nth(1)
        .expect("the excerpt")
        .split("```text\n")
        .nth(1)
        .unwrap()
        .split("\n```")
        .next()
        .unwrap()
        .lines()
        .filter(|l| l.trim() != "...")
        .collect();
    assert!(excerpt.len() > 15, "{} lines", excerpt.len());
    let missing: Vec<&&str> = excerpt
        .iter()
        .filter(|l| !printed.contains(&normalised(l)))
        .collect();
    assert!(
        missing.is_empty(),
        "excerpt lines the main job does not print:\n{}",
        missing
            .iter()
            .map(|l| l.to_string())
            .collect::<Vec<_>>()
            .join("\n")
    );
}

#[test]
fn a_combination_row_loses_its_timing_column_only() {
    assert_eq!(
        normalised("pb/location-aware/sequential   463/500  878.3  794.5  21.1  84/463  398.8%  6157.8%  0.37"),
        "pb/location-aware/sequential 463/500 878.3 794.5 21.1 84/463 398.8% 6157.8%"
    );
    assert_eq!(normalised("  1a  holds   sharing"), "1a holds sharing");
}
