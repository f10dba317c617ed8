//! `swarmplan eaas` from the command line: the order the methods' values must be in (fluid LP
//! bound <= MILP optimum <= PB when PB flies on the shipped paper-195 instance), labelled gaps,
//! and coded errors for bad input.

mod common;

use common::{eaas_r00001, swarmplan, tmp};
use serde_json::Value;

fn row<'a>(report: &'a Value, method: &str) -> &'a Value {
    report["rows"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["method"] == method)
        .unwrap()
}

#[test]
fn eaas_orders_bound_optimum_and_heuristic_and_labels_the_gaps() {
    let out = eaas_r00001(
        "0",
        "pb,fb,milp,fluid,fair",
        &["--time-limit", "20", "--json"],
    );
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let r: Value = serde_json::from_slice(&out.stdout).unwrap();
    let milp = row(&r, "milp");
    let fluid = row(&r, "fluid");
    assert_eq!(fluid["status"], "optimal");
    let bound = fluid["bound"].as_f64().unwrap();
    if milp["status"] == "optimal" {
        let opt = milp["objective"].as_f64().unwrap();
        assert!(bound <= opt + 1e-6, "bound {bound} > milp {opt}");
        assert!(milp["grid_step_min"].as_f64().unwrap() <= 1.0);
        for h in ["pb", "fb"] {
            let x = row(&r, h);
            if x["feasible"] == true && r["objective"].get("node_time").is_some() {
                assert!(opt <= x["objective"].as_f64().unwrap() + 1e-6, "{h}");
                assert_eq!(x["gap"]["reference"], "optimal");
            }
        }
    }
}

#[test]
fn eaas_rejects_a_hop_beyond_the_plan_and_a_bad_grid_with_codes() {
    let out = swarmplan(&["eaas", "--request-id", "r00000", "--hop", "99"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("E4110"));
    let out = swarmplan(&[
        "eaas",
        "--request-id",
        "r00000",
        "--methods",
        "milp",
        "--period-min",
        "0",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("E4101"));
}

/// A report without its wall-clock times, the only field that differs between two runs.
fn without_times(v: &Value) -> Value {
    match v {
        Value::Object(m) => Value::Object(
            m.iter()
                .filter(|(k, _)| k.as_str() != "solve_ms")
                .map(|(k, x)| (k.clone(), without_times(x)))
                .collect(),
        ),
        Value::Array(a) => Value::Array(a.iter().map(without_times).collect()),
        x => x.clone(),
    }
}

#[test]
fn a_written_hop_file_gives_the_report_of_the_request() {
    // r00001's plan (paper-195, paper profile): hop 6 flies n165 -> n164 -> n163 and ends on
    // 4 pads, hop 9 ends at the destination, which has none.
    for (hop, ends_on_pads) in [("6", true), ("9", false)] {
        let file = tmp(&format!("r00001-{hop}.json"));
        let lp = tmp(&format!("r00001-{hop}.lp"));
        let file_arg = file.to_str().unwrap();
        let common = ["--methods", "pb,milp", "--time-limit", "20", "--json"];
        let mut args = vec!["eaas", "--request-id", "r00001", "--hop", hop];
        args.extend(common);
        args.extend([
            "--write-hop",
            file_arg,
            "--write-lp",
            lp.to_str().unwrap(),
            "--force",
        ]);
        let from_request = swarmplan(&args);
        assert_eq!(from_request.status.code(), Some(0), "{from_request:?}");
        let mut args = vec!["eaas", "--hop-file", file_arg];
        args.extend(common);
        let from_file = swarmplan(&args);
        assert_eq!(from_file.status.code(), Some(0), "{from_file:?}");
        let a: Value = serde_json::from_slice(&from_request.stdout).unwrap();
        let b: Value = serde_json::from_slice(&from_file.stdout).unwrap();
        assert_eq!(row(&a, "milp")["status"], "optimal", "hop {hop}");
        assert_eq!(without_times(&a), without_times(&b), "hop {hop}");

        let written: Value =
            serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
        assert_eq!(written["schema_version"], 1);
        assert_eq!(written["request_id"], "r00001");
        assert_eq!(written["hop_index"].to_string(), hop);
        assert_eq!(written["profile"], "paper");
        assert_eq!(written["path"], a["path"]);
        assert_eq!(written["from"], a["path"][0]);
        assert_eq!(written["hop"], a["problem"]);
        assert_eq!(written["end"].is_object(), ends_on_pads, "hop {hop}");
        assert_eq!(a["objective"].get("node_time").is_some(), ends_on_pads);
        let text = std::fs::read_to_string(&lp).unwrap();
        assert!(
            text.contains(&format!("\\ hop: request r00001 hop {hop}: ")),
            "{text}"
        );
        assert!(text.contains("\\ reorder: paper"));
    }
}

#[test]
fn a_bad_hop_file_is_reported_with_its_codes_and_exit_2() {
    let good = tmp("good.json");
    let out = eaas_r00001(
        "6",
        "pb",
        &["--write-hop", good.to_str().unwrap(), "--force"],
    );
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let hop: Value = serde_json::from_str(&std::fs::read_to_string(&good).unwrap()).unwrap();
    let run = |name: &str, file: &Value| {
        let path = tmp(name);
        std::fs::write(&path, file.to_string()).unwrap();
        let out = swarmplan(&["eaas", "--hop-file", path.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{name}: {out:?}");
        String::from_utf8_lossy(&out.stderr).into_owned()
    };
    let mut unknown = hop.clone();
    unknown["hop"]["wind"] = Value::from(3.0);
    let err = run("unknown.json", &unknown);
    assert!(err.contains("E4111") && err.contains("wind"), "{err}");
    let mut version = hop.clone();
    version["schema_version"] = Value::from(2);
    version["new_field"] = Value::from(true);
    let err = run("version.json", &version);
    assert!(err.contains("E4112") && !err.contains("E4111"), "{err}");
    let mut broken = hop.clone();
    broken["to"] = Value::from("n000");
    broken["hop"]["initial_slot"] = serde_json::json!([0, 0, 1]);
    broken["end"]["pads"] = Value::from(0);
    let err = run("broken.json", &broken);
    for code in ["E4115", "E4003", "hop.initial_slot", "E4103", "end.pads"] {
        assert!(err.contains(code), "{code}: {err}");
    }
    // A path with one node more than the hop's legs has edges (or no leg at all): E4115.
    let mut extra = hop.clone();
    let last = extra["path"].as_array().unwrap().last().unwrap().clone();
    extra["path"].as_array_mut().unwrap().push(last);
    let n = extra["path"].as_array().unwrap().len();
    extra["to"] = extra["path"][n - 1].clone();
    let err = run("extra-node.json", &extra);
    assert!(err.contains("E4115") && err.contains("leg(s)"), "{err}");
    let mut legless = hop.clone();
    legless["hop"]["legs"] = serde_json::json!([]);
    let err = run("no-leg.json", &legless);
    assert!(err.contains("E4115") && err.contains("0 leg(s)"), "{err}");
    let path = tmp("not-json.json");
    std::fs::write(&path, "{\"schema_version\": 1,").unwrap();
    let out = swarmplan(&["eaas", "--hop-file", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("E4111"));
    let out = swarmplan(&[
        "eaas",
        "--hop-file",
        good.to_str().unwrap(),
        "--request-id",
        "r00001",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("cannot be used with"));
}

#[test]
fn a_hop_into_a_destination_with_pads_is_scored_by_arrival_battery_not_node_time() {
    // r00000 (paper-195) flies n179 -> n049 without stopping; n049 has 2 pads, but the swarm
    // delivers there and does not recharge, so the hop has no node time.
    let file = tmp("r00000-0.json");
    let out = swarmplan(&[
        "eaas",
        "--request-id",
        "r00000",
        "--hop",
        "0",
        "--methods",
        "pb",
        "--json",
        "--write-hop",
        file.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let a: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(a["path"].as_array().unwrap().last().unwrap(), "n049", "{a}");
    assert!(
        a["objective"].get("node_time").is_none(),
        "{}",
        a["objective"]
    );
    assert_eq!(a["objective"], "max_min_arrival", "{}", a["objective"]);
    let written: Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    assert!(written["end"].is_null(), "{}", written["end"]);
}
