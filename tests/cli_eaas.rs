//! `swarmplan eaas` from the command line: the order the methods' values must be in (fluid LP
//! bound <= MILP optimum <= PB when PB flies on the shipped paper-195 instance), labelled gaps,
//! and coded errors for bad input.

use serde_json::Value;
use std::process::{Command, Output};

fn swarmplan(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args(args)
        .output()
        .expect("the binary runs")
}

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
    let out = swarmplan(&[
        "eaas",
        "--request-id",
        "r00001",
        "--hop",
        "0",
        "--methods",
        "pb,fb,milp,fluid,fair",
        "--time-limit",
        "20",
        "--json",
    ]);
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
