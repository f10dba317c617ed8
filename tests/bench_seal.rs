//! A bench directory is sealed (issue 46): its `complete` mark records the shard and the SHA-256
//! and row count of every file the run wrote; `bench merge` and `check --bench` verify the seal
//! before they read a row, and nothing of an output directory is touched before the inputs are
//! read and valid. Each case below replays a reproducer by name.

mod common;

use common::{bench_shards, stderr, swarmplan, tmp};
use std::path::Path;
use std::process::Output;

fn assert_exit_2_with(out: &Output, code: &str, words: &[&str]) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "{code}: {err}");
    assert!(err.contains(&format!("[{code}]")), "{code} missing: {err}");
    for w in words {
        assert!(err.contains(w), "{code}: '{w}' missing: {err}");
    }
}

fn arg(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `dir/file` with the cell of `column` in data row `row` replaced by `f(cell)`.
fn edit_cell(dir: &Path, file: &str, row: usize, column: &str, f: impl Fn(&str) -> String) {
    let path = dir.join(file);
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let at = lines[0].split(',').position(|c| c == column).unwrap();
    let mut cells: Vec<String> = lines[row + 1].split(',').map(String::from).collect();
    cells[at] = f(&cells[at]);
    lines[row + 1] = cells.join(",");
    std::fs::write(&path, lines.join("\n") + "\n").unwrap();
}

fn merge(dirs: &[&Path], out: &Path) -> Output {
    let mut args = vec!["bench", "merge"];
    args.extend(dirs.iter().map(|d| arg(d)));
    args.extend(["--out", arg(out), "--force"]);
    swarmplan(&args)
}

#[test]
fn bench_merge_refuses_a_shard_edited_after_its_run() {
    let (s0, s1) = bench_shards("seal-merge");
    let merged = s0.parent().unwrap().join("merged");
    let out = merge(&[&s0, &s1], &merged);
    assert_eq!(out.status.code(), Some(0), "untouched: {}", stderr(&out));

    // A hand-edited dt_min: the merge used to carry it into the merged files.
    let saved = std::fs::read(s0.join("requests.csv")).unwrap();
    edit_cell(&s0, "requests.csv", 0, "dt_min", |x| {
        (x.parse::<f64>().unwrap() * 0.5).to_string()
    });
    let out = merge(&[&s0, &s1], &merged);
    assert_exit_2_with(&out, "E7009", &["requests.csv", "changed after the run"]);
    std::fs::write(s0.join("requests.csv"), &saved).unwrap();

    // hops.csv lost a row: the count is named.
    let saved = std::fs::read_to_string(s0.join("hops.csv")).unwrap();
    let mut lines: Vec<&str> = saved.lines().collect();
    assert!(lines.len() > 2, "the exact subset has hop rows");
    let rows = lines.len() - 1;
    lines.pop();
    std::fs::write(s0.join("hops.csv"), lines.join("\n") + "\n").unwrap();
    let out = merge(&[&s0, &s1], &merged);
    assert_exit_2_with(
        &out,
        "E7009",
        &[
            "hops.csv",
            &format!("has {} rows where the run wrote {rows}", rows - 1),
        ],
    );
    std::fs::write(s0.join("hops.csv"), &saved).unwrap();

    // A `complete` mark rewritten to name another shard.
    let mark = std::fs::read_to_string(s0.join("complete")).unwrap();
    std::fs::write(s0.join("complete"), mark.replace("shard 0/2", "shard 1/2")).unwrap();
    let out = merge(&[&s0, &s1], &merged);
    assert_exit_2_with(&out, "E7009", &["complete", "shard 1/2", "shard 0/2"]);
    // The other shard's mark copied over: its hashes are not this shard's files.
    std::fs::copy(s1.join("complete"), s0.join("complete")).unwrap();
    let out = merge(&[&s0, &s1], &merged);
    assert_exit_2_with(&out, "E7009", &["s0"]);
    // A mark of the format before the seal: named as such.
    std::fs::write(
        s0.join("complete"),
        "shard 0/2\ninputs_sha256 0123456789abcdef\n",
    )
    .unwrap();
    let out = merge(&[&s0, &s1], &merged);
    assert_exit_2_with(&out, "E7008", &["complete", "run the bench again"]);
    std::fs::write(s0.join("complete"), &mark).unwrap();
    let out = merge(&[&s0, &s1], &merged);
    assert_eq!(out.status.code(), Some(0), "restored: {}", stderr(&out));
}

#[test]
fn check_bench_refuses_edited_tables_and_checks_every_table() {
    let (s0, _) = bench_shards("seal-check");
    let check = |dir: &Path| swarmplan(&["check", "--bench", arg(dir)]);
    let out = check(&s0);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let verdict = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(verdict.contains("rows of 2 requests: valid"), "{verdict}");

    // A requests.csv row deleted: was "valid".
    let saved = std::fs::read_to_string(s0.join("requests.csv")).unwrap();
    let mut lines: Vec<&str> = saved.lines().collect();
    lines.remove(5);
    std::fs::write(s0.join("requests.csv"), lines.join("\n") + "\n").unwrap();
    assert_exit_2_with(&check(&s0), "E7009", &["requests.csv", "rows"]);
    std::fs::write(s0.join("requests.csv"), &saved).unwrap();

    // A halved nt_min in stops.csv: was "valid" (only requests.csv was read).
    edit_cell(&s0, "stops.csv", 0, "nt_min", |x| {
        (x.parse::<f64>().unwrap() / 2.0).to_string()
    });
    assert_exit_2_with(&check(&s0), "E7009", &["stops.csv"]);
}

#[test]
fn nothing_of_an_output_directory_is_touched_before_the_inputs_are_valid() {
    let (s0, s1) = bench_shards("seal-outputs");
    // `bench --out D --force` with a broken --network: D's mark stays.
    let broken = tmp("seal-outputs/broken.json");
    std::fs::write(&broken, "{ not json").unwrap();
    let mark = std::fs::read(s1.join("complete")).unwrap();
    let out = swarmplan(&[
        "bench",
        "--network",
        arg(&broken),
        "--out",
        arg(&s1),
        "--force",
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("broken.json"), "{}", stderr(&out));
    assert_eq!(std::fs::read(s1.join("complete")).unwrap(), mark);

    // `bench merge s0 s1 --out s1 --force`: refused (E7010) with s1's mark intact.
    let out = merge(&[&s0, &s1], &s1);
    assert_exit_2_with(&out, "E7010", &["--out", "one of the shards merged"]);
    assert_eq!(std::fs::read(s1.join("complete")).unwrap(), mark);

    // A merge whose input is not there: named as missing, not as a run that "did not finish";
    // a file where a directory is expected: E0008.
    let out = merge(&[&s0, Path::new("/nonexistent")], &s0.with_file_name("m"));
    assert_exit_2_with(&out, "E7007", &["/nonexistent", "no such directory"]);
    let out = merge(&[&s0, &s0.join("requests.csv")], &s0.with_file_name("m"));
    assert_exit_2_with(&out, "E0008", &["requests.csv", "not a directory"]);
}
