//! Every command of the README's and the user guide's shell blocks runs as written: each line of
//! a ```sh block that calls swarmplan (`cargo run --release -- ...` or `swarmplan ...`, pipes and
//! redirections included) is run by `sh` in one scratch directory holding a link to
//! `instances/`, in reading order (the README, then the guide's pages in the order of
//! `docs/src/SUMMARY.md`, the model chapters with the write-ups they include; a file one line
//! writes, a later one reads), with the binary this test suite built, and must exit 0 and print
//! something (or write the file it names). The documents say which lines run shorter here
//! ([`SHORTER`]). Lines that are not swarmplan runs are accounted for in [`NOT_RUN`], each with
//! where it is run instead, so a new command cannot be skipped silently.

mod common;

use common::docs::{documents, sh_blocks, with_binary};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Lines run with a smaller `--request-limit` (the README and the guide say so next to them):
/// a text that marks the line, the text replaced and its replacement.
const SHORTER: [(&str, &str, &str); 2] = [
    (
        "bench --request-limit 500 --out bench-out --force",
        "--request-limit 500",
        "--request-limit 20",
    ),
    (
        "bench --request-limit 500 --no-joint",
        "--request-limit 500",
        "--request-limit 20",
    ),
];

/// Lines not run here, by how they start, and where they run instead.
const NOT_RUN: [(&str, &str); 6] = [
    ("cargo test", "the test suite itself"),
    (
        "cargo build --release --features highs",
        "needs the HiGHS build (.ci/run)",
    ),
    (
        "cargo run --release --features highs",
        "needs the HiGHS build (.ci/run)",
    ),
    ("apt-get", "a system package install (.ci/run)"),
    (
        "examples/slurm/submit.sh",
        "a Slurm cluster (tests/slurm/run.sh, .ci/run)",
    ),
    (
        "cargo run --release --example",
        "an example: measured on its own (the guide, \"Examples and benchmarks\")",
    ),
];

/// The command lines of every document's ```sh blocks, each with its document's name.
fn command_lines() -> Vec<(String, String)> {
    documents()
        .into_iter()
        .flat_map(|doc| {
            sh_blocks(&doc.text)
                .into_iter()
                .flat_map(|b| b.lines)
                .map(move |line| (doc.name.clone(), line))
                .collect::<Vec<_>>()
        })
        .collect()
}

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn every_readme_and_guide_command_runs_as_written() {
    let binary = PathBuf::from(env!("CARGO_BIN_EXE_swarmplan"));
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("readme_commands");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(repo().join("instances"), dir.join("instances")).unwrap();
    let lines = command_lines();
    let (mut ran, mut failures) = (0, Vec::new());
    let mut ran_in = std::collections::BTreeSet::new();
    for (doc, line) in &lines {
        if let Some((_, why)) = NOT_RUN.iter().find(|(start, _)| line.starts_with(start)) {
            eprintln!("not run here ({why}): {line}");
            continue;
        }
        assert!(
            line.starts_with("cargo run --release -- ") || line.starts_with("swarmplan "),
            "a command of {doc} this test does not know how to run: {line}"
        );
        let mut command = line.clone();
        for (marker, from, to) in SHORTER {
            if command.contains(marker) {
                command = command.replace(from, to);
            }
        }
        let command = with_binary(&command, &binary);
        let out = Command::new("sh")
            .arg("-c")
            .arg(&command)
            .current_dir(&dir)
            .output()
            .unwrap();
        ran += 1;
        ran_in.insert(doc.clone());
        let writes_a_file = [" > ", " -o ", "--out "].iter().any(|w| line.contains(w));
        let wrote = !out.stdout.is_empty() || writes_a_file;
        if out.status.code() != Some(0) || !wrote {
            failures.push(format!(
                "{doc}: {line}\n  exit {:?}\n  stderr: {}",
                out.status.code(),
                String::from_utf8_lossy(&out.stderr)
                    .lines()
                    .take(5)
                    .collect::<Vec<_>>()
                    .join("\n  ")
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "README and guide commands that fail:\n{}",
        failures.join("\n")
    );
    // The blocks hold the main job, the first plan, every command's page and the checker's lines.
    assert!(ran >= 60, "{ran} commands run of {}", lines.len());
    for doc in [
        "README.md",
        "docs/src/first-plan.md",
        "docs/src/checking.md",
        "docs/src/commands/solve.md",
        "docs/src/commands/bench.md",
    ] {
        assert!(ran_in.contains(doc), "no command of {doc} ran");
    }
    assert!(dir.join("bench-out/summary.json").exists());
    assert!(dir.join("plan.json").exists());
}

#[test]
fn command_lines_join_continuations_and_drop_comments() {
    let lines = command_lines();
    assert!(lines
        .iter()
        .all(|(_, l)| !l.contains(" #") && !l.ends_with('\\')));
    assert!(lines.iter().any(|(doc, l)| doc == "README.md"
        && l.starts_with("cargo run --release -- bench --request-limit 500")));
    // The model chapters' blocks are read from the write-ups they include.
    assert!(lines
        .iter()
        .any(|(doc, l)| doc.starts_with("docs/src/models/")
            && l.starts_with("cargo run --release --example")));
    let b = Path::new("/b/swarmplan");
    assert_eq!(
        with_binary("swarmplan solve --json | swarmplan check --plan -", b),
        "/b/swarmplan solve --json | /b/swarmplan check --plan -"
    );
}

#[test]
fn a_block_and_the_output_after_it_are_read_together() {
    let text = "x\n```sh\n# comment\ncargo run --release -- solve \\\n  --gap   # why\n```\n\n```text\nroute gap: 0%\n```\n```sh\nswarmplan check\n```\n";
    let blocks = sh_blocks(text);
    assert_eq!(blocks.len(), 2);
    assert_eq!(blocks[0].lines, ["cargo run --release -- solve --gap"]);
    assert_eq!(blocks[0].output.as_deref(), Some("route gap: 0%"));
    assert_eq!(blocks[1].lines, ["swarmplan check"]);
    assert!(blocks[1].output.is_none());
}
