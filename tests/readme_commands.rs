//! Every command of the README's shell blocks runs as written: each line of a ```sh block that
//! calls swarmplan (`cargo run --release -- ...` or `swarmplan ...`, pipes and redirections
//! included) is run by `sh` in a scratch directory holding a link to `instances/`, in the
//! README's order (a file one line writes, the next reads), with the binary this test suite
//! built, and must exit 0 and print something (or write the file it names). The README says which lines run shorter here
//! ([`SHORTER`]). Lines that are not swarmplan runs are accounted for in [`NOT_RUN`], each with
//! where it is run instead, so a new command cannot be skipped silently.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Lines run with a smaller `--limit` (the README says so next to them): the text replaced and
/// its replacement.
const SHORTER: [(&str, &str, &str); 1] = [(
    "bench --request-limit 500 --out bench-out --force",
    "--request-limit 500",
    "--request-limit 20",
)];

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
        "an example: measured on its own (README, \"Examples\")",
    ),
];

/// The command lines of the README's ```sh blocks, continuation lines joined, comments removed.
fn readme_lines() -> Vec<String> {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    let mut out = Vec::new();
    let mut in_sh = false;
    let mut pending = String::new();
    for line in readme.lines() {
        if line.starts_with("```") {
            in_sh = !in_sh && line.trim() == "```sh";
            continue;
        }
        if !in_sh {
            continue;
        }
        let code = match line.find(" #") {
            Some(i) => &line[..i],
            None if line.trim_start().starts_with('#') => "",
            None => line,
        };
        let code = code.trim();
        if let Some(head) = code.strip_suffix('\\') {
            pending.push_str(head);
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

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `line` with the binary of this build in place of `cargo run --release --` and of a
/// command-leading `swarmplan`.
fn with_binary(line: &str, binary: &Path) -> String {
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

#[test]
fn every_readme_command_runs_as_written() {
    let binary = PathBuf::from(env!("CARGO_BIN_EXE_swarmplan"));
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("readme_commands");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(repo().join("instances"), dir.join("instances")).unwrap();
    let lines = readme_lines();
    let (mut ran, mut failures) = (0, Vec::new());
    for line in &lines {
        if let Some((_, why)) = NOT_RUN.iter().find(|(start, _)| line.starts_with(start)) {
            eprintln!("not run here ({why}): {line}");
            continue;
        }
        assert!(
            line.starts_with("cargo run --release -- ") || line.starts_with("swarmplan "),
            "a README command this test does not know how to run: {line}"
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
        let writes_a_file = [" > ", " -o ", "--out "].iter().any(|w| line.contains(w));
        let wrote = !out.stdout.is_empty() || writes_a_file;
        if out.status.code() != Some(0) || !wrote {
            failures.push(format!(
                "{line}\n  exit {:?}\n  stderr: {}",
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
        "README commands that fail:\n{}",
        failures.join("\n")
    );
    // The blocks hold the main job, the quick start and the checker's lines at least.
    assert!(ran >= 20, "{ran} commands run of {}", lines.len());
    assert!(dir.join("bench-out/summary.json").exists());
    assert!(dir.join("plan.json").exists());
}

#[test]
fn readme_lines_join_continuations_and_drop_comments() {
    let lines = readme_lines();
    assert!(lines
        .iter()
        .all(|l| !l.contains(" #") && !l.ends_with('\\')));
    assert!(lines
        .iter()
        .any(|l| l.starts_with("cargo run --release -- bench --request-limit 500")));
    let b = Path::new("/b/swarmplan");
    assert_eq!(
        with_binary("swarmplan solve --json | swarmplan check --plan -", b),
        "/b/swarmplan solve --json | /b/swarmplan check --plan -"
    );
}
