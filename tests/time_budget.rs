//! `--time-budget` of `batch` and `bench`: a run the budget stops is the run of the requests
//! before the first one left out, number for number (`batch`'s summaries but their times;
//! `bench`'s files, `config.json` included, which records that `--request-limit`), and says on stderr
//! how many were planned and how many remain. How many fit in the budget depends on the
//! machine; the property holds for any count, so the test does not pin one.

mod common;

use common::{stderr, swarmplan, tmp};
use serde_json::Value;

/// The count of requests planned, from the budget line on stderr (`None`: no line).
fn planned(stderr: &str) -> Option<usize> {
    let line = stderr
        .lines()
        .find(|l| l.starts_with("time budget reached: "))?;
    line["time budget reached: ".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

fn without_times(summaries: &Value) -> Value {
    let mut s = summaries.clone();
    for x in s.as_array_mut().unwrap() {
        x.as_object_mut().unwrap().remove("wall_ms");
    }
    s
}

#[test]
fn a_batch_stopped_by_its_budget_is_the_batch_of_its_prefix() {
    let out = swarmplan(&[
        "batch",
        "--request-limit",
        "3000",
        "--sharing",
        "pb,fb",
        "--time-budget",
        "0.05",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let k = planned(&stderr(&out)).expect("3,000 requests take longer than 0.05 s");
    assert!(k < 3000);
    let stopped: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(stopped[0]["requests"], k);
    if k == 0 {
        return;
    }
    let limit = k.to_string();
    let again = swarmplan(&[
        "batch",
        "--request-limit",
        &limit,
        "--sharing",
        "pb,fb",
        "--json",
    ]);
    assert_eq!(again.status.code(), Some(0));
    assert!(planned(&stderr(&again)).is_none());
    let full: Value = serde_json::from_slice(&again.stdout).unwrap();
    assert_eq!(without_times(&stopped), without_times(&full));
}

#[test]
fn a_bench_stopped_by_its_budget_writes_the_files_of_its_prefix() {
    let (a, b) = (tmp("budget-stopped"), tmp("budget-limit"));
    let _ = (std::fs::remove_dir_all(&a), std::fs::remove_dir_all(&b));
    let out = swarmplan(&[
        "bench",
        "--request-limit",
        "300",
        "--time-budget",
        "0.5",
        "--no-gap",
        "--out",
        a.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let k = planned(&stderr(&out)).expect("300 requests take longer than 0.5 s");
    let config: Value =
        serde_json::from_str(&std::fs::read_to_string(a.join("config.json")).unwrap()).unwrap();
    assert_eq!(config["limit"], k);
    if k == 0 {
        return;
    }
    let limit = k.to_string();
    let again = swarmplan(&[
        "bench",
        "--request-limit",
        &limit,
        "--no-gap",
        "--out",
        b.to_str().unwrap(),
    ]);
    assert_eq!(again.status.code(), Some(0), "{}", stderr(&again));
    for file in [
        "config.json",
        "requests.csv",
        "hops.csv",
        "stops.csv",
        "joint.csv",
    ] {
        assert_eq!(
            std::fs::read_to_string(a.join(file)).unwrap(),
            std::fs::read_to_string(b.join(file)).unwrap(),
            "{file}"
        );
    }
}

#[test]
fn a_budget_that_is_not_a_time_is_refused() {
    for bad in ["0", "-1", "nan", "1e8"] {
        let arg = format!("--time-budget={bad}");
        let out = swarmplan(&["batch", "--request-limit", "10", &arg]);
        assert_eq!(out.status.code(), Some(2), "{bad}");
        assert!(
            stderr(&out).contains("[E0028] --time-budget"),
            "{bad}: {}",
            stderr(&out)
        );
    }
}
