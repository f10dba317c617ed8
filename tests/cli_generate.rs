//! `swarmplan generate`: writes valid files, same seed gives the same bytes, bad input exits 2.

mod common;

use common::{repo_path, swarmplan, tmp};
use std::path::Path;

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn generate_writes_valid_identical_files_for_the_same_seed() {
    let (n1, n2, r1, r2) = (
        tmp("n1.json"),
        tmp("n2.json"),
        tmp("r1.json"),
        tmp("r2.json"),
    );
    // Left by an earlier run: generate does not overwrite a file without --force.
    for f in [&n1, &n2, &r1, &r2, &tmp("n3.json")] {
        let _ = std::fs::remove_file(f);
    }
    for n in [&n1, &n2] {
        let out = swarmplan(&[
            "generate",
            "network",
            "--nodes",
            "40",
            "--seed",
            "3",
            "-o",
            s(n),
        ]);
        assert_eq!(out.status.code(), Some(0), "{out:?}");
    }
    assert_eq!(std::fs::read(&n1).unwrap(), std::fs::read(&n2).unwrap());
    for r in [&r1, &r2] {
        let out = swarmplan(&[
            "generate",
            "requests",
            "--network",
            s(&n1),
            "--count",
            "25",
            "--seed",
            "4",
            "--max-package-kg",
            "1.0",
            "-o",
            s(r),
        ]);
        assert_eq!(out.status.code(), Some(0), "{out:?}");
    }
    assert_eq!(std::fs::read(&r1).unwrap(), std::fs::read(&r2).unwrap());
    let net: swarmplan::problem::Network = swarmplan::problem::io::read_json(&n1).unwrap();
    assert_eq!(net.nodes.len(), 40);
    let g = swarmplan::problem::SkywayGraph::new(&net).unwrap();
    let set: swarmplan::problem::RequestSet = swarmplan::problem::io::read_json(&r1).unwrap();
    assert_eq!(set.requests.len(), 25);
    assert!(swarmplan::problem::validate::validate_request_set(&set, &g, 1.0).is_empty());
    // A different seed writes a different file.
    let n3 = tmp("n3.json");
    swarmplan(&[
        "generate",
        "network",
        "--nodes",
        "40",
        "--seed",
        "4",
        "-o",
        s(&n3),
    ]);
    assert_ne!(std::fs::read(&n1).unwrap(), std::fs::read(&n3).unwrap());
}

fn assert_exit_2_with(args: &[&str], code: &str) {
    let out = swarmplan(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(
        stderr.contains(code),
        "{args:?}: expected {code} in {stderr}"
    );
}

#[test]
fn bad_numbers_and_bad_files_exit_2_with_codes() {
    let o = tmp("unused.json");
    let o = s(&o);
    assert_exit_2_with(
        &[
            "generate", "network", "--nodes", "2", "--seed", "1", "-o", o,
        ],
        "E1901",
    );
    assert_exit_2_with(
        &[
            "generate", "network", "--nodes", "ten", "--seed", "1", "-o", o,
        ],
        "E1901",
    );
    assert_exit_2_with(&["generate", "network", "--seed", "-1", "-o", o], "E1903");
    assert_exit_2_with(
        &[
            "generate",
            "network",
            "--seed",
            "1",
            "--spacing-m",
            "NaN",
            "-o",
            o,
        ],
        "E1902",
    );
    let line4 = repo_path("instances/tiny/line4.json");
    let line4 = s(&line4);
    assert_exit_2_with(
        &[
            "generate",
            "requests",
            "--network",
            line4,
            "--count",
            "0",
            "--seed",
            "1",
            "-o",
            o,
        ],
        "E3901",
    );
    assert_exit_2_with(
        &[
            "generate",
            "requests",
            "--network",
            line4,
            "--seed",
            "1",
            "--max-package-kg",
            "-1",
            "-o",
            o,
        ],
        "E3902",
    );
    let invalid = repo_path("instances/tiny/invalid-network.json");
    let out = swarmplan(&[
        "generate",
        "requests",
        "--network",
        s(&invalid),
        "--seed",
        "1",
        "-o",
        o,
    ]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    // All eleven violations are listed, not only the first.
    for code in [
        "E1101", "E1102", "E1104", "E1105", "E1201", "E1202", "E1203", "E1204", "E1205", "E1206",
        "E1207",
    ] {
        assert!(stderr.contains(code), "{code} missing in {stderr}");
    }
    let broken = tmp("broken.json");
    std::fs::write(&broken, "{ \"schema_version\": 1, ").unwrap();
    assert_exit_2_with(
        &[
            "generate",
            "requests",
            "--network",
            s(&broken),
            "--seed",
            "1",
            "-o",
            o,
        ],
        "E0001",
    );
    assert_exit_2_with(
        &[
            "generate",
            "requests",
            "--network",
            s(&tmp("missing.json")),
            "--seed",
            "1",
            "-o",
            o,
        ],
        "missing.json",
    );
}
