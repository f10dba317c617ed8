//! `swarmplan bench`: its files agree with `batch` and `eaas` on the same requests, do not depend
//! on the thread count, and the merge of shards writes the files of one run, byte for byte.
//!
//! The runs are small (the first 12 requests of the shipped set on the default findings-195
//! instance, a few combinations, the exact subset of the first 2 requests, whose hop models solve
//! to optimality in milliseconds, far from the time limit, so `hops.csv` is reproducible).

mod common;

use common::{swarmplan, tmp};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

const LIMIT: &str = "12";
/// Combinations: the baseline and PB under Algorithm 1, PB under Dijkstra, both positionings.
const COMBOS: [&str; 6] = [
    "--sharing",
    "none,pb",
    "--positioning",
    "location-aware,energy-aware",
    "--route",
    "sequential,dijkstra",
];

/// Runs `bench` into a fresh directory `name` with the test's combinations and `extra`.
fn bench(name: &str, extra: &[&str]) -> std::path::PathBuf {
    let out = tmp(name);
    let _ = std::fs::remove_dir_all(&out);
    let out_arg = out.to_str().unwrap().to_string();
    let mut args = vec![
        "bench",
        "--limit",
        LIMIT,
        "--exact-limit",
        "2",
        "--out",
        &out_arg,
    ];
    args.extend_from_slice(&COMBOS);
    args.extend_from_slice(extra);
    let run = swarmplan(&args);
    assert!(run.status.success(), "{run:?}");
    out
}

fn read(dir: &Path, file: &str) -> String {
    std::fs::read_to_string(dir.join(file)).unwrap_or_else(|e| panic!("{file}: {e}"))
}

fn csv_rows(dir: &Path, file: &str) -> Vec<BTreeMap<String, String>> {
    let mut r = csv::Reader::from_path(dir.join(file)).unwrap();
    let header = r.headers().unwrap().clone();
    r.records()
        .map(|rec| {
            header
                .iter()
                .zip(rec.unwrap().iter())
                .map(|(h, v)| (h.to_string(), v.to_string()))
                .collect()
        })
        .collect()
}

/// `summary.json` of `dir` without what a machine's speed or the command line decide: the
/// command, the execution times, and finding 4b (which compares times).
fn without_times(dir: &Path) -> Value {
    let mut v: Value = serde_json::from_str(&read(dir, "summary.json")).unwrap();
    v["command"] = Value::Null;
    for m in v["methods"].as_array_mut().unwrap() {
        for k in ["exec_ms_total", "exec_ms_median", "exec_ms_max"] {
            m[k] = Value::Null;
        }
    }
    for h in v["hop_gaps"].as_array_mut().unwrap() {
        for k in [
            "continuous_ms_total",
            "continuous_ms_median",
            "continuous_ms_max",
        ] {
            h[k] = Value::Null;
        }
    }
    if let Some(j) = v.get_mut("joint").filter(|j| j.is_object()) {
        for k in ["ms_median", "ms_p90", "ms_max", "ms_total"] {
            j[k] = Value::Null;
        }
    }
    for f in v["findings"].as_array_mut().unwrap() {
        if f["id"] == "4b" {
            f["ours"] = Value::Null;
            f["verdict"] = Value::Null;
        }
    }
    v
}

/// The files a run writes that depend on nothing but its inputs and options.
const REPRODUCIBLE: [&str; 5] = [
    "config.json",
    "requests.csv",
    "hops.csv",
    "stops.csv",
    "joint.csv",
];

/// `a` and `b` hold the same reproducible files, byte for byte.
fn assert_same_files(a: &Path, b: &Path, what: &str) {
    for file in REPRODUCIBLE {
        assert_eq!(read(a, file), read(b, file), "{file} differs {what}");
    }
}

#[test]
fn thread_counts_give_identical_files_and_shards_merge_into_one_run() {
    let one = bench("threads-1", &["--threads", "1"]);
    let two = bench("threads-2", &["--threads", "2"]);
    assert_same_files(&one, &two, "with 2 threads");
    // Three shards, merged in a scrambled order.
    let shards: Vec<_> = (0..3)
        .map(|i| bench(&format!("shard-{i}"), &["--shard", &format!("{i}/3")]))
        .collect();
    let merged = tmp("merged");
    let _ = std::fs::remove_dir_all(&merged);
    let args = [
        "bench",
        "merge",
        shards[2].to_str().unwrap(),
        shards[0].to_str().unwrap(),
        shards[1].to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ];
    let run = swarmplan(&args);
    assert!(run.status.success(), "{run:?}");
    assert_same_files(&one, &merged, "merged from shards");
    // Each shard planned its own requests: 12 requests at positions i, i + 3, ...
    let rows = csv_rows(&shards[1], "requests.csv");
    let positions: Vec<usize> = rows
        .iter()
        .map(|r| r["request_index"].parse().unwrap())
        .collect();
    assert!(positions.iter().all(|p| p % 3 == 1), "{positions:?}");
    assert_eq!(rows.len(), 4 * 6, "4 requests x 6 combinations");
    // The summaries agree but for the times and the command.
    assert_eq!(without_times(&one), without_times(&merged));
    // Every figure listed was written, as SVG.
    let summary: Value = serde_json::from_str(&read(&one, "summary.json")).unwrap();
    let figures = summary["figures"].as_array().unwrap();
    assert!(
        figures.iter().any(|f| f == "figures/delivered.svg"),
        "{figures:?}"
    );
    for f in figures {
        let svg = read(&one, f.as_str().unwrap());
        assert!(svg.trim_end().ends_with("</svg>"), "{f}");
    }
    // A merge with a shard missing is refused.
    let missing = tmp("merged-missing");
    let args = [
        "bench",
        "merge",
        shards[0].to_str().unwrap(),
        shards[1].to_str().unwrap(),
        "--out",
        missing.to_str().unwrap(),
    ];
    let run = swarmplan(&args);
    assert_eq!(run.status.code(), Some(2), "{run:?}");
    assert!(
        String::from_utf8_lossy(&run.stderr).contains("E7003"),
        "{run:?}"
    );
}

#[test]
fn requests_and_summary_agree_with_batch() {
    let out = bench("agree-batch", &[]);
    let findings = common::repo_arg("instances/findings-195/network.json");
    let profile = common::repo_arg("instances/profiles/paper-findings.toml");
    let per_request = tmp("agree-batch-per-request.json");
    let mut args = vec![
        "batch",
        "--network",
        &findings,
        "--profile",
        &profile,
        "--limit",
        LIMIT,
        "--gap",
        "--json",
        "--per-request",
        per_request.to_str().unwrap(),
        "--force",
    ];
    args.extend_from_slice(&COMBOS);
    let run = swarmplan(&args);
    assert!(run.status.success(), "{run:?}");
    let batch: Value = serde_json::from_slice(&run.stdout).unwrap();
    let summary: Value = serde_json::from_str(&read(&out, "summary.json")).unwrap();
    let key = |o: &Value| {
        format!(
            "{}/{}/{}",
            o["sharing"].as_str().unwrap(),
            o["positioning"].as_str().unwrap(),
            o["route"].as_str().unwrap()
        )
    };
    let batch_by: BTreeMap<String, &Value> = batch
        .as_array()
        .unwrap()
        .iter()
        .map(|s| (key(&s["options"]), s))
        .collect();
    let methods = summary["methods"].as_array().unwrap();
    // The baseline is planned once per route, under location-aware: 6 combinations of batch's 8.
    assert_eq!(methods.len(), 6);
    assert!(!methods
        .iter()
        .any(|m| key(&m["options"]) == "none/energy-aware/sequential"));
    for m in methods {
        let b = batch_by[&key(&m["options"])];
        for field in [
            "delivered",
            "requests",
            "mean_dt_min",
            "mean_nt_min",
            "mean_stops",
        ] {
            assert_eq!(m[field], b[field], "{} {field}", key(&m["options"]));
        }
        assert_eq!(m["route_gap"]["compared"], b["route_gap"]["compared"]);
        assert_eq!(m["route_gap"]["mean_gap"], b["route_gap"]["mean_gap"]);
        assert_eq!(m["lpt_stops"], b["lpt_node_time"]["stops"]);
    }
    // Row by row against batch's per-request outcomes.
    let outcomes: Value =
        serde_json::from_str(&std::fs::read_to_string(&per_request).unwrap()).unwrap();
    let by_request: BTreeMap<(String, String), &Value> = outcomes
        .as_array()
        .unwrap()
        .iter()
        .map(|o| {
            (
                (
                    key(&o["options"]),
                    o["request_id"].as_str().unwrap().to_string(),
                ),
                o,
            )
        })
        .collect();
    let rows = csv_rows(&out, "requests.csv");
    assert_eq!(rows.len(), 12 * 6);
    for r in &rows {
        let k = format!("{}/{}/{}", r["sharing"], r["positioning"], r["route"]);
        let o = by_request[&(k.clone(), r["request_id"].clone())];
        assert_eq!(r["success"], o["success"].to_string(), "{k}");
        assert_eq!(r["outcome"], o["outcome"].as_str().unwrap());
        let dt: f64 = r["dt_min"].parse().unwrap();
        assert_eq!(dt, o["dt_min"].as_f64().unwrap(), "{k} {}", r["request_id"]);
        assert_eq!(r["stops"], o["stops"].as_array().unwrap().len().to_string());
        match o.get("route_gap").and_then(Value::as_f64) {
            Some(g) => assert_eq!(r["route_gap"].parse::<f64>().unwrap(), g),
            None => assert_eq!(r["route_gap"], ""),
        }
    }
}

#[test]
fn hop_rows_agree_with_eaas_on_the_same_hop() {
    let out = bench("agree-eaas", &[]);
    let rows = csv_rows(&out, "hops.csv");
    // PB, location-aware, Algorithm 1: the plan `eaas` studies.
    let ours: Vec<_> = rows
        .iter()
        .filter(|r| {
            r["request_id"] == "r00000"
                && r["sharing"] == "pb"
                && r["positioning"] == "location-aware"
                && r["route"] == "sequential"
        })
        .collect();
    assert!(ours.len() >= 2, "{ours:?}");
    let findings = common::repo_arg("instances/findings-195/network.json");
    let profile = common::repo_arg("instances/profiles/paper-findings.toml");
    for r in ours.iter().take(3) {
        let run = swarmplan(&[
            "eaas",
            "--network",
            &findings,
            "--profile",
            &profile,
            "--request-id",
            "r00000",
            "--hop",
            &r["hop_index"],
            "--methods",
            "pb,continuous,fluid",
            "--time-limit",
            "60",
            "--json",
        ]);
        assert!(run.status.success(), "{run:?}");
        let e: Value = serde_json::from_slice(&run.stdout).unwrap();
        let m = e["rows"].as_array().unwrap();
        let num = |s: &str| s.parse::<f64>().ok();
        assert_eq!(
            num(&r["heuristic"]),
            m[0]["objective"].as_f64(),
            "hop {}",
            r["hop_index"]
        );
        assert_eq!(num(&r["continuous"]), m[1]["objective"].as_f64());
        assert_eq!(num(&r["fluid_bound"]), m[2]["bound"].as_f64());
        assert_eq!(r["continuous_status"], m[1]["status"].as_str().unwrap());
        assert_eq!(r["reference"], "optimal");
        let gap = m[0]["gap"]["relative"].as_f64().unwrap();
        assert_eq!(r["gap"].parse::<f64>().unwrap(), gap);
    }
}

#[test]
fn bad_shard_and_existing_output_are_refused() {
    let out = tmp("bad-shard");
    let run = swarmplan(&["bench", "--shard", "3/3", "--out", out.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(2), "{run:?}");
    assert!(
        String::from_utf8_lossy(&run.stderr).contains("E7001"),
        "{run:?}"
    );
    let done = bench("exists", &[]);
    let run = swarmplan(&["bench", "--limit", "1", "--out", done.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(2), "{run:?}");
    assert!(
        String::from_utf8_lossy(&run.stderr).contains("E7005"),
        "{run:?}"
    );
}

#[test]
fn request_rows_agree_with_solve() {
    let out = bench("agree-solve", &["--no-gap"]);
    let rows = csv_rows(&out, "requests.csv");
    let findings = common::repo_arg("instances/findings-195/network.json");
    let profile = common::repo_arg("instances/profiles/paper-findings.toml");
    for (id, sharing, positioning, route) in [
        ("r00003", "none", "location-aware", "sequential"),
        ("r00007", "pb", "energy-aware", "dijkstra"),
    ] {
        let row = rows
            .iter()
            .find(|r| {
                r["request_id"] == id
                    && r["sharing"] == sharing
                    && r["positioning"] == positioning
                    && r["route"] == route
            })
            .unwrap();
        let run = swarmplan(&[
            "solve",
            "--network",
            &findings,
            "--profile",
            &profile,
            "--request-id",
            id,
            "--sharing",
            sharing,
            "--positioning",
            positioning,
            "--route",
            route,
            "--json",
        ]);
        let report: Value = serde_json::from_slice(&run.stdout).unwrap();
        let plan = &report["plan"];
        let num = |k: &str| row[k].parse::<f64>().unwrap();
        assert_eq!(num("dt_min"), plan["dt_min"].as_f64().unwrap(), "{id}");
        assert_eq!(num("tt_min"), plan["tt_min"].as_f64().unwrap(), "{id}");
        assert_eq!(num("nt_min"), plan["nt_min"].as_f64().unwrap(), "{id}");
        assert_eq!(
            num("shared_mah"),
            plan["shared_mah"].as_f64().unwrap(),
            "{id}"
        );
        assert_eq!(
            row["support_drones"],
            report["support_drones"].to_string(),
            "{id}"
        );
        assert_eq!(row["success"], (run.status.code() == Some(0)).to_string());
        // The gap columns are empty without --gap.
        assert_eq!(row["route_gap_reference"], "");
    }
}

#[test]
fn joint_split_adds_up_and_agrees_with_solve() {
    // The default run computes the joint optimum and the split.
    let one = bench("joint-1", &["--threads", "1"]);
    let rows = csv_rows(&one, "requests.csv");
    let joint = csv_rows(&one, "joint.csv");
    let num = |r: &BTreeMap<String, String>, k: &str| -> Option<f64> {
        (!r[k].is_empty()).then(|| r[k].parse().unwrap())
    };
    let mut split = 0;
    for r in &rows {
        let what = format!(
            "{} {}/{}/{}",
            r["request_id"], r["sharing"], r["positioning"], r["route"]
        );
        // The joint optimum is the best row of joint.csv for the request.
        let best: Vec<_> = joint
            .iter()
            .filter(|j| j["request_index"] == r["request_index"] && j["best"] == "true")
            .collect();
        assert!(best.len() <= 1, "{what}");
        assert_eq!(
            num(r, "joint_dt_min"),
            best.first().and_then(|b| num(b, "dt_min")),
            "{what}"
        );
        if r["success"] == "true" {
            assert!(num(r, "joint_dt_min").is_some(), "{what}: delivered alone");
        }
        let Some(total) = num(r, "gap_total_min") else {
            continue;
        };
        let parts =
            ["gap_sharing_min", "gap_route_min", "gap_swarm_min"].map(|k| num(r, k).unwrap());
        let eps = num(r, "split_epsilon_min").unwrap();
        assert!(
            (parts.iter().sum::<f64>() - total).abs() <= 1e-9 * total.abs().max(1.0),
            "{what}"
        );
        let dt: f64 = r["dt_min"].parse().unwrap();
        assert!(
            (dt - num(r, "joint_dt_min").unwrap() - total).abs() <= 1e-9 * dt,
            "{what}"
        );
        assert!(
            parts.iter().all(|&p| p >= -eps - 1e-9 * dt),
            "{what}: {parts:?}"
        );
        split += 1;
    }
    assert!(split >= 12, "only {split} rows split");
    // A swarm's optimum is what `solve --route optimal --sharing exact` gives.
    let first = joint
        .iter()
        .find(|j| {
            j["positioning"] == "location-aware"
                && j["support_drones"] != "0"
                && j["delivered"] == "true"
        })
        .expect("a location-aware swarm delivers");
    let request: usize = first["request_index"].parse().unwrap();
    let id = &rows
        .iter()
        .find(|r| r["request_index"] == request.to_string())
        .unwrap()["request_id"];
    let out = swarmplan(&[
        "solve",
        "--network",
        &common::repo_arg("instances/findings-195/network.json"),
        "--profile",
        &common::repo_arg("instances/profiles/paper-findings.toml"),
        "--request-id",
        id,
        "--route",
        "optimal",
        "--sharing",
        "exact",
        "--hop-time-limit",
        "0.5",
        "--json",
    ]);
    assert!(out.status.success(), "{}", common::stderr(&out));
    let doc: Value = serde_json::from_slice(&out.stdout).unwrap();
    let dt = doc["plan"]["dt_min"].as_f64().unwrap();
    assert_eq!(dt, num(first, "dt_min").unwrap(), "request {id}");
    // Shards merge into one run, joint.csv included: see the test of thread counts and shards.
    let summary: Value = serde_json::from_str(&read(&one, "summary.json")).unwrap();
    assert!(
        summary["joint"]["requests"].as_u64() == Some(12),
        "{}",
        summary["joint"]
    );
    assert!(
        summary["figures"]
            .as_array()
            .unwrap()
            .iter()
            .any(|f| f == "figures/gap-split.svg"),
        "{}",
        summary["figures"]
    );
}

/// `--no-joint` leaves the joint optimum and the split out, and nothing else: `joint.csv` has its
/// header only, the split columns of `requests.csv` are empty and every other column is the
/// default run's; `--joint`, the default, is still accepted, and not with `--no-joint`.
#[test]
fn no_joint_leaves_out_the_split_and_nothing_else() {
    const SPLIT: [&str; 10] = [
        "joint_dt_min",
        "split_label",
        "exact_schedule_dt_min",
        "swarm_optimum_dt_min",
        "gap_total_min",
        "gap_sharing_min",
        "gap_route_min",
        "gap_swarm_min",
        "split_epsilon_min",
        "split_proven",
    ];
    let with = bench("with-joint", &["--joint", "--no-gap"]);
    let without = bench("no-joint", &["--no-joint", "--no-gap"]);
    assert!(csv_rows(&without, "joint.csv").is_empty());
    assert!(!csv_rows(&with, "joint.csv").is_empty());
    let (a, b) = (
        csv_rows(&with, "requests.csv"),
        csv_rows(&without, "requests.csv"),
    );
    assert_eq!(a.len(), b.len());
    assert!(a.iter().any(|r| !r["gap_total_min"].is_empty()));
    for (a, b) in a.iter().zip(&b) {
        for (k, v) in b {
            if SPLIT.contains(&k.as_str()) {
                assert_eq!(v, "", "{k}");
            } else {
                assert_eq!(&a[k], v, "{k}");
            }
        }
    }
    for file in ["hops.csv", "stops.csv"] {
        assert_eq!(read(&with, file), read(&without, file), "{file}");
    }
    let summary: Value = serde_json::from_str(&read(&without, "summary.json")).unwrap();
    assert!(summary["joint"].is_null(), "{}", summary["joint"]);
    let both = swarmplan(&["bench", "--joint", "--no-joint", "--out", "x"]);
    assert_eq!(both.status.code(), Some(2), "{both:?}");
}

/// Hop solves stop on node limits, not on the clock: a run of 60 requests on a CPU kept busy by
/// spinning threads writes the same files (timings and command line aside) as a run on a quiet
/// one.
#[test]
fn a_loaded_cpu_gives_the_same_files() {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;
    let run = |name: &str| {
        let out = tmp(name);
        let _ = std::fs::remove_dir_all(&out);
        let out_arg = out.to_str().unwrap().to_string();
        let mut args = vec!["bench", "--limit", "60", "--exact-limit", "3", "--joint"];
        args.extend_from_slice(&COMBOS);
        args.extend_from_slice(&["--threads", "2", "--out", &out_arg]);
        let done = swarmplan(&args);
        assert!(done.status.success(), "{done:?}");
        out
    };
    let quiet = run("quiet");
    let stop = Arc::new(AtomicBool::new(false));
    let spinners: Vec<_> = (0..4)
        .map(|_| {
            let stop = Arc::clone(&stop);
            std::thread::spawn(move || {
                let mut x = 0u64;
                while !stop.load(Ordering::Relaxed) {
                    x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
                }
                x
            })
        })
        .collect();
    let loaded = run("loaded");
    stop.store(true, Ordering::Relaxed);
    for s in spinners {
        s.join().unwrap();
    }
    assert_same_files(&quiet, &loaded, "under load");
    let config: Value = serde_json::from_str(&read(&quiet, "config.json")).unwrap();
    assert!(config["milp"]["node_limit"].as_u64().is_some(), "{config}");
    // No wall-clock limit unless asked for.
    assert!(config["milp"]["time_limit_s"].is_null(), "{config}");
}
