//! `batch --gap`: each heuristic route method against the optimal route of the same sharing
//! policy and positioning. The expected figures are recomputed here from the per-request delivery
//! times of a separate run that plans `optimal` as an ordinary route method.

mod common;

use common::{stderr, swarmplan, tmp};
use serde_json::Value;

const ROUTES: &str = "sequential,astar,dijkstra";

fn per_request(path: &std::path::Path) -> Vec<Value> {
    serde_json::from_slice::<Vec<Value>>(&std::fs::read(path).unwrap()).unwrap()
}

#[test]
fn route_gaps_equal_the_gaps_of_the_per_request_delivery_times() {
    let (with_gap, plain) = (tmp("gap.json"), tmp("plain.json"));
    let out = swarmplan(&[
        "batch",
        "--limit",
        "40",
        "--sharing",
        "none,pb",
        "--route",
        ROUTES,
        "--gap",
        "--json",
        "--per-request",
        with_gap.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let summaries: Vec<Value> = serde_json::from_slice(&out.stdout).unwrap();
    // Only the combinations asked for: the optimal routes behind the gaps are not printed.
    assert_eq!(summaries.len(), 6);
    let out = swarmplan(&[
        "batch",
        "--limit",
        "40",
        "--sharing",
        "none,pb",
        "--route",
        &format!("{ROUTES},optimal"),
        "--per-request",
        plain.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let plain = per_request(&plain);
    let dt = |sharing: &str, route: &str| -> Vec<Option<f64>> {
        plain
            .iter()
            .filter(|o| o["options"]["sharing"] == sharing && o["options"]["route"] == route)
            .map(|o| {
                o["success"]
                    .as_bool()
                    .unwrap()
                    .then(|| o["dt_min"].as_f64().unwrap())
            })
            .collect()
    };
    let with_gap = per_request(&with_gap);
    for s in &summaries {
        let (sharing, route) = (
            s["options"]["sharing"].as_str().unwrap(),
            s["options"]["route"].as_str().unwrap(),
        );
        let (h, o) = (dt(sharing, route), dt(sharing, "optimal"));
        assert_eq!(h.len(), 40);
        let gaps: Vec<Option<f64>> = h
            .iter()
            .zip(&o)
            .map(|(h, o)| Some((h.unwrap_or(f64::NAN) - (*o)?) / (*o)?).filter(|g| !g.is_nan()))
            .collect();
        let compared: Vec<f64> = gaps.iter().flatten().copied().collect();
        let g = &s["route_gap"];
        assert_eq!(g["reference"], "optimal");
        assert_eq!(g["compared"], compared.len());
        let mean = compared.iter().fold(0.0, |a, b| a + b) / compared.len() as f64;
        assert_eq!(g["mean_gap"].as_f64().unwrap(), mean, "{sharing} {route}");
        let max = compared.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let min = compared.iter().copied().fold(f64::INFINITY, f64::min);
        assert_eq!(g["max_gap"].as_f64().unwrap(), max);
        assert_eq!(g["min_gap"].as_f64().unwrap(), min);
        let zero = compared.iter().filter(|g| g.abs() <= 1e-9).count();
        assert_eq!(g["at_zero"], zero);
        let fails = h
            .iter()
            .zip(&o)
            .filter(|(h, o)| h.is_none() && o.is_some())
            .count();
        assert_eq!(g["heuristic_fails_optimum_delivers"], fails);
        if route != "dijkstra" {
            // Same hop-path rule: never below the optimum (beyond rounding), never delivering
            // where it does not.
            assert!(min >= -1e-12, "{sharing} {route}: {min}");
            assert_eq!(g["optimum_fails_heuristic_delivers"], 0);
        }
        // The per-request file carries the same gaps.
        let lines: Vec<&Value> = with_gap
            .iter()
            .filter(|x| x["options"]["sharing"] == sharing && x["options"]["route"] == route)
            .collect();
        for (line, gap) in lines.iter().zip(&gaps) {
            assert_eq!(line["route_gap"].as_f64(), *gap);
        }
    }
    // Algorithm 1 is not optimal on every one of these requests: the comparison is not vacuous.
    assert!(summaries
        .iter()
        .any(|s| s["route_gap"]["max_gap"].as_f64().unwrap() > 0.01));
}

#[test]
fn gap_columns_appear_only_with_gap() {
    let out = swarmplan(&[
        "batch",
        "--limit",
        "3",
        "--route",
        "sequential,optimal",
        "--gap",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    assert!(lines.next().unwrap().ends_with(
        ",route_gap_reference,route_gap_compared,route_gap_zero,route_gap_mean,route_gap_max,route_gap_min,heuristic_fails_optimum_delivers,optimum_fails_heuristic_delivers,route_gap_unproven_references"
    ));
    // `optimal` itself has no gap: empty cells.
    let optimal = lines
        .find(|l| l.starts_with("pb,location-aware,optimal,"))
        .unwrap();
    assert!(optimal.ends_with(",,,,,,,,,"), "{optimal}");
    let out = swarmplan(&["batch", "--limit", "3"]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(!text.lines().next().unwrap().contains("route_gap"));
}

#[test]
fn solve_gap_is_the_gap_to_a_separate_optimal_solve_and_reads_back() {
    let plan = tmp("solve_gap.json");
    let out = swarmplan(&[
        "solve",
        "--request-id",
        "r00042",
        "--sharing",
        "pb",
        "--route",
        "sequential",
        "--gap",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    std::fs::write(&plan, &out.stdout).unwrap();
    let report: Value = serde_json::from_slice(&out.stdout).unwrap();
    let out = swarmplan(&[
        "solve",
        "--request-id",
        "r00042",
        "--sharing",
        "pb",
        "--route",
        "optimal",
        "--json",
    ]);
    let optimal: Value = serde_json::from_slice(&out.stdout).unwrap();
    let (dt, dt_opt) = (
        report["plan"]["dt_min"].as_f64().unwrap(),
        optimal["plan"]["dt_min"].as_f64().unwrap(),
    );
    let g = &report["route_gap"];
    assert_eq!(g["reference"], "optimal");
    assert_eq!(g["optimal_dt_min"].as_f64().unwrap(), dt_opt);
    assert_eq!(g["gap"].as_f64().unwrap(), (dt - dt_opt) / dt_opt);
    // The document with its gap is still a plan the checker reads.
    let out = swarmplan(&["check", "--plan", plan.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    // The fair policy has no optimal route to compare with; exact has the joint optimum.
    let out = swarmplan(&[
        "solve",
        "--request-id",
        "r00042",
        "--sharing",
        "fair",
        "--gap",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("E0015"), "{}", stderr(&out));
    let out = swarmplan(&[
        "solve",
        "--request-id",
        "r00042",
        "--sharing",
        "exact",
        "--gap",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let gap = doc["route_gap"]["gap"].as_f64().unwrap();
    assert!(
        gap >= -1e-9,
        "Algorithm 1 under exact below the joint optimum: {gap}"
    );
}

/// With `--hop-paths any` the reference is labelled as the any-path optimum, and no heuristic
/// beats it (its hops may take any flyable path, so even Dijkstra's gap is not negative).
#[test]
fn batch_labels_the_any_path_reference() {
    let out = swarmplan(&[
        "batch",
        "--limit",
        "30",
        "--sharing",
        "none",
        "--route",
        "sequential,dijkstra",
        "--gap",
        "--hop-paths",
        "any",
    ]);
    assert!(out.status.success(), "{out:?}");
    let text = String::from_utf8(out.stdout).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let mut labelled = 0;
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        if cells[col("route")] == "optimal" {
            continue;
        }
        assert_eq!(
            cells[col("route_gap_reference")],
            "optimal-any-path",
            "{line}"
        );
        let min: f64 = cells[col("route_gap_min")].parse().unwrap();
        assert!(min >= -1e-9, "{line}");
        labelled += 1;
    }
    assert_eq!(labelled, 2);
}
