//! The joint optima and exact-schedule replays of `bench --joint` on the first 100 requests of
//! findings-195 and paper-195 against values recorded once (tests/fixtures/README.md gives the
//! command and the commit): a faster search may find another optimal schedule or route, but no
//! value moves beyond its certified epsilon and the optimality tolerance of its hops, and nothing
//! proven becomes unproven.

mod common;

use common::{repo_arg, repo_path, swarmplan, tmp};
use std::collections::BTreeMap;
use std::path::Path;

/// One recorded or measured value: a swarm's optimum or a heuristic route's exact replay.
#[derive(Debug, Clone, Copy)]
struct Value {
    delivered: bool,
    dt_min: f64,
    /// The stops of the route: one hop more than that, each optimal within its tolerance.
    stops: usize,
    proven: bool,
    epsilon_min: f64,
}

/// A hop's value is optimal within `1e-7 + 1e-9 |V|` min (`models/eaas_config.md`, "Statuses";
/// `OPTIMAL_ABS_TOL`, `OPTIMAL_REL_TOL`): two optimal schedules of a hop may differ by that.
const HOP_ABS_TOL_MIN: f64 = 1e-7;
const HOP_REL_TOL: f64 = 1e-9;

type Key = (String, String, String, String, String, String);

fn parse_bool(s: &str) -> bool {
    match s {
        "true" => true,
        "false" => false,
        other => panic!("not a boolean: {other:?}"),
    }
}

fn parse_f64(s: &str) -> f64 {
    s.parse().unwrap_or_else(|_| panic!("not a number: {s:?}"))
}

/// The recorded values of `network`, by (request, what, sharing, positioning, route, support).
fn recorded(network: &str) -> BTreeMap<Key, Value> {
    let path = repo_path(&format!("tests/fixtures/joint_first100_{network}.csv"));
    let mut reader = csv::Reader::from_path(&path).unwrap();
    let mut out = BTreeMap::new();
    for row in reader.records() {
        let r = row.unwrap();
        let key = (
            r[0].to_string(),
            r[1].to_string(),
            r[2].to_string(),
            r[3].to_string(),
            r[4].to_string(),
            r[5].to_string(),
        );
        let value = Value {
            delivered: parse_bool(&r[6]),
            dt_min: parse_f64(&r[7]),
            stops: r[8].parse().unwrap(),
            proven: parse_bool(&r[9]),
            epsilon_min: parse_f64(&r[10]),
        };
        assert!(
            out.insert(key, value).is_none(),
            "a repeated row in {path:?}"
        );
    }
    out
}

/// Rows of `file` in `dir` as maps from column name to text.
fn rows(dir: &Path, file: &str) -> Vec<BTreeMap<String, String>> {
    let mut reader = csv::Reader::from_path(dir.join(file)).unwrap();
    let headers = reader.headers().unwrap().clone();
    reader
        .records()
        .map(|r| {
            let r = r.unwrap();
            headers
                .iter()
                .zip(r.iter())
                .map(|(h, v)| (h.to_string(), v.to_string()))
                .collect()
        })
        .collect()
}

/// The same values measured now, by `bench --joint` on the first 100 requests.
fn measured(network: &str, profile: &str) -> BTreeMap<Key, Value> {
    let out = tmp(&format!("joint-reference-{network}"));
    let _ = std::fs::remove_dir_all(&out);
    let run = swarmplan(&[
        "bench",
        "--network",
        &repo_arg(&format!("instances/{network}/network.json")),
        "--profile",
        &repo_arg(&format!("instances/profiles/{profile}.toml")),
        "--request-limit",
        "100",
        "--joint",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", common::stderr(&run));
    let mut values = BTreeMap::new();
    for r in rows(&out, "joint.csv") {
        let key = (
            r["request_id"].clone(),
            "swarm_optimum".to_string(),
            "exact".to_string(),
            r["positioning"].clone(),
            "optimal".to_string(),
            r["support_drones"].clone(),
        );
        let value = Value {
            delivered: parse_bool(&r["delivered"]),
            dt_min: if r["dt_min"].is_empty() {
                f64::INFINITY
            } else {
                parse_f64(&r["dt_min"])
            },
            stops: r["stops"].parse().unwrap_or(0),
            proven: parse_bool(&r["proven"]),
            epsilon_min: parse_f64(&r["epsilon_min"]),
        };
        values.insert(key, value);
    }
    for r in rows(&out, "requests.csv") {
        if r["exact_schedule_dt_min"].is_empty() {
            continue;
        }
        let key = (
            r["request_id"].clone(),
            "exact_schedule".to_string(),
            r["sharing"].clone(),
            r["positioning"].clone(),
            r["route"].clone(),
            r["support_drones"].clone(),
        );
        let value = Value {
            delivered: true,
            dt_min: parse_f64(&r["exact_schedule_dt_min"]),
            stops: r["stops"].parse().unwrap(),
            proven: parse_bool(&r["split_proven"]),
            epsilon_min: parse_f64(&r["split_epsilon_min"]),
        };
        values.insert(key, value);
    }
    let _ = std::fs::remove_dir_all(&out);
    values
}

fn agrees(network: &str, profile: &str) {
    let before = recorded(network);
    let now = measured(network, profile);
    assert_eq!(
        before.keys().collect::<Vec<_>>(),
        now.keys().collect::<Vec<_>>(),
        "{network}: the swarms and replays measured are not those recorded"
    );
    let mut compared = 0;
    for (key, was) in &before {
        let is = now[key];
        assert_eq!(was.delivered, is.delivered, "{network} {key:?}");
        if was.proven {
            assert!(is.proven, "{network} {key:?}: proven before, not now");
        }
        if !was.delivered {
            continue;
        }
        // Both values lie within their certified epsilons and their hops' optimality
        // tolerances of the same optimum (a route's node times sum its hops' values).
        let hops = (was.stops.max(is.stops) + 1) as f64;
        let tolerance = 2.0 * (hops * HOP_ABS_TOL_MIN + HOP_REL_TOL * was.dt_min.abs())
            + was.epsilon_min.max(0.0)
            + is.epsilon_min.max(0.0);
        assert!(
            (is.dt_min - was.dt_min).abs() <= tolerance,
            "{network} {key:?}: {} min now against {} recorded (tolerance {tolerance})",
            is.dt_min,
            was.dt_min
        );
        compared += 1;
    }
    assert!(
        compared >= 1500,
        "{network}: only {compared} values compared"
    );
}

#[test]
fn the_joint_optima_of_findings_195_agree_with_those_recorded() {
    agrees("findings-195", "paper-findings");
}

#[test]
fn the_joint_optima_of_paper_195_agree_with_those_recorded() {
    agrees("paper-195", "paper");
}
