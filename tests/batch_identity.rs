//! `batch --all` gives the same numbers for any thread count, and the same numbers as before the
//! grid was planned on a thread pool with work shared between combinations: the fixture in
//! tests/fixtures/ (see its README) was written by the binary of commit 38e3827.

mod common;

use common::{repo_path, swarmplan, tmp};

/// The CSV's rows without the last column (`wall_ms`), and the per-request JSON.
fn batch_all_40(threads: &str) -> (Vec<String>, Vec<u8>) {
    let per_request = tmp(&format!("all40-{threads}.json"));
    let out = swarmplan(&[
        "batch",
        "--all",
        "--limit",
        "40",
        "--threads",
        threads,
        "--per-request",
        per_request.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let csv = String::from_utf8(out.stdout).unwrap();
    (without_wall_ms(&csv), std::fs::read(&per_request).unwrap())
}

fn without_wall_ms(csv: &str) -> Vec<String> {
    csv.lines()
        .map(|line| {
            let (values, wall_ms) = line.rsplit_once(',').unwrap();
            assert!(
                wall_ms == "wall_ms" || wall_ms.parse::<f64>().is_ok(),
                "{line}"
            );
            values.to_string()
        })
        .collect()
}

#[test]
fn batch_all_gives_the_numbers_of_the_fixture_with_one_or_two_threads() {
    let fixture_csv = std::fs::read_to_string(repo_path("tests/fixtures/batch_all40.csv")).unwrap();
    let fixture_json = std::fs::read(repo_path("tests/fixtures/batch_all40.json")).unwrap();
    let fixture_csv = without_wall_ms(&fixture_csv);
    assert_eq!(fixture_csv.len(), 1 + 24);
    for threads in ["1", "2"] {
        let (csv, json) = batch_all_40(threads);
        assert_eq!(csv, fixture_csv, "--threads {threads}");
        assert!(
            json == fixture_json,
            "--threads {threads}: per-request JSON differs"
        );
    }
}
