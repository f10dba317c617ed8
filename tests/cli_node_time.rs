//! `swarmplan node-time` end to end: the paper's example and bad input (exit code 2).

mod common;

use common::tmp;
use std::process::Command;

/// Exit code, standard output and standard error of the binary run with `args`.
fn swarmplan(args: &[&str]) -> (i32, String, String) {
    let out = common::swarmplan(args);
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn paper_example_prints_200_70_and_60_minutes_as_json() {
    // Paper, section 5: 1 pad 200, 3 pads 70, 5 pads 60.
    for (pads, expected) in [("1", 200.0), ("3", 70.0), ("5", 60.0)] {
        for method in ["exact", "milp", "brute"] {
            let (code, stdout, stderr) = swarmplan(&[
                "node-time",
                "--pads",
                pads,
                "--times",
                "60,50,40,30,20",
                "--method",
                method,
                "--json",
            ]);
            assert_eq!(code, 0, "stderr: {stderr}");
            let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
            assert_eq!(v["method"], method);
            assert_eq!(v["status"], "optimal");
            assert!((v["makespan_min"].as_f64().unwrap() - expected).abs() < 1e-9);
            assert!((v["lower_bound_min"].as_f64().unwrap() - expected).abs() < 1e-9);
            let pads_used = v["assignment"].as_array().unwrap();
            let mut drones: Vec<u64> = pads_used
                .iter()
                .flat_map(|p| p.as_array().unwrap().iter().map(|d| d.as_u64().unwrap()))
                .collect();
            drones.sort();
            assert_eq!(drones, vec![0, 1, 2, 3, 4]);
            assert!(v["solve_ms"].as_f64().unwrap() >= 0.0);
        }
    }
}

#[test]
fn file_input_and_human_output_give_the_same_node_time() {
    let path = tmp("stop.json");
    std::fs::write(
        &path,
        r#"{"pads": 3, "charge_times_min": [60, 50, 40, 30, 20]}"#,
    )
    .unwrap();
    let (code, stdout, _) = swarmplan(&["node-time", "--file", path.to_str().unwrap()]);
    assert_eq!(code, 0);
    assert!(stdout.contains("node time: 70 min (optimal"), "{stdout}");
}

#[test]
fn bad_input_exits_2_with_a_coded_message() {
    let malformed = tmp("bad.json");
    std::fs::write(&malformed, r#"{"pads": 3, "charge_times_min": [60, 50"#).unwrap();
    let malformed = malformed.to_str().unwrap().to_string();
    let cases: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (vec!["--pads", "0", "--times", "60,50"], vec!["E5001"]),
        (
            vec!["--pads", "2", "--times", "60,-5,nan"],
            vec!["E5003", "E5004"],
        ),
        (vec!["--pads", "2", "--times", ""], vec!["E5002"]),
        (vec!["--pads", "2", "--times", "60,abc"], vec!["E5007"]),
        (vec!["--file", &malformed], vec!["E0001"]),
        (
            vec!["--pads", "2", "--times", "1,2,3", "--time-limit", "-1"],
            vec!["E5006"],
        ),
    ];
    for (args, expected_codes) in cases {
        let mut all = vec!["node-time"];
        all.extend(&args);
        let (code, stdout, stderr) = swarmplan(&all);
        assert_eq!(code, 2, "{args:?}: stderr {stderr}");
        assert!(stdout.is_empty(), "{args:?}: nothing on stdout");
        for c in expected_codes {
            assert!(stderr.contains(c), "{args:?}: {c} missing from {stderr}");
        }
    }
    // Neither --times nor --file: a usage error, also exit 2.
    let (code, _, _) = swarmplan(&["node-time", "--pads", "2"]);
    assert_eq!(code, 2);
}

#[test]
fn out_of_range_time_limits_and_charge_times_are_coded_errors() {
    // 1e308 s once panicked converting to a Duration; 1e308 min once printed "inf min (optimal)".
    for (args, code, field) in [
        (
            vec![
                "--times",
                "60,50,40",
                "--method",
                "milp",
                "--time-limit",
                "1e308",
            ],
            "E5006",
            "time_limit_s",
        ),
        (
            vec!["--times", "60,50,40", "--time-limit", "-1"],
            "E5006",
            "time_limit_s",
        ),
        (vec!["--times", "1e308,5"], "E5004", "charge_times_min[0]"),
        (vec!["--times", "5,1e10"], "E5004", "charge_times_min[1]"),
    ] {
        let mut all = vec!["node-time", "--pads", "3"];
        all.extend(args);
        let (exit, _, stderr) = swarmplan(&all);
        assert_eq!(exit, 2, "{all:?}: {stderr}");
        assert!(
            stderr.contains(&format!("[{code}] {field}")),
            "{all:?}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

#[test]
fn a_closed_stdout_ends_quietly_and_a_full_disk_is_reported() {
    use std::process::Stdio;
    // The reader goes away before anything is written: no panic, exit 0, nothing on stderr.
    let mut child = Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args(["solve", "--request-id", "r00001", "--json"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    if let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") {
        let out = Command::new(env!("CARGO_BIN_EXE_swarmplan"))
            .args(["node-time", "--pads", "3", "--times", "60,50,40,30,20"])
            .stdout(full)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{stderr}");
        assert!(
            stderr.contains("[E0010] standard output: cannot write the results"),
            "{stderr}"
        );
    }
}

/// A solve stopped by its node limit reports its incumbent with a gap against the search's own
/// lower bound, which on this hard class is above the trivial bound `max(sum/k, max t)`; a
/// proven solve reports gap 0 against the optimum. The trivial bound is computed here from the
/// file; the relative gap from the two numbers printed.
#[test]
fn a_stopped_solve_reports_its_gap_against_a_non_trivial_bound() {
    let file = tmp("nu3-25-5.json");
    let file = file.to_str().unwrap();
    let (code, _, err) = swarmplan(&[
        "generate",
        "node-time",
        "--class",
        "nu3",
        "--jobs",
        "25",
        "--pads",
        "5",
        "--seed",
        "1",
        "-o",
        file,
        "--force",
    ]);
    assert_eq!(code, 0, "{err}");
    let instance: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap();
    let times: Vec<f64> = instance["charge_times_min"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_f64().unwrap())
        .collect();
    let trivial = (times.iter().sum::<f64>() / 5.0).max(times.iter().cloned().fold(0.0, f64::max));

    let (code, out, err) = swarmplan(&["node-time", "--file", file, "--node-limit", "1", "--json"]);
    assert_eq!(code, 0, "{err}");
    let stopped: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(stopped["status"], "feasible");
    let (ms, lb) = (
        stopped["makespan_min"].as_f64().unwrap(),
        stopped["lower_bound_min"].as_f64().unwrap(),
    );
    assert!(lb > trivial, "bound {lb} not above the trivial {trivial}");
    assert!(ms > lb);
    assert_eq!(stopped["gap"]["reference"], "bound");
    let relative = stopped["gap"]["relative"].as_f64().unwrap();
    assert!((relative - (ms - lb) / lb).abs() < 1e-12);

    let (_, human, _) = swarmplan(&["node-time", "--file", file, "--node-limit", "1"]);
    assert!(
        human.contains(&format!(
            "gap: {:+.4}% against the lower bound",
            100.0 * relative
        )),
        "{human}"
    );

    let (_, out, _) = swarmplan(&["node-time", "--file", file, "--json"]);
    let proven: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(proven["status"], "optimal");
    assert!(proven["makespan_min"].as_f64().unwrap() >= lb);
    assert_eq!(proven["gap"]["reference"], "optimal");
    assert_eq!(proven["gap"]["relative"].as_f64(), Some(0.0));
}

/// A stopped search reports the best bound there is: on `l6`, 100 drones on 40 pads, seed 2,
/// stopped after one search node, the bound is not the root bound `ceil(sum / 40) = 615`
/// (computed here from the instance) but the bin-packing LP's 618, the optimum (proven by the
/// arc-flow MILP, README "HiGHS backend"), and the gap is taken against it.
#[test]
fn a_stopped_search_reports_the_lp_bound_and_its_gap() {
    let file = tmp("l6-100-40-2.json");
    let path = file.to_str().unwrap();
    let (code, _, stderr) = swarmplan(&[
        "generate",
        "node-time",
        "--class",
        "l6",
        "--jobs",
        "100",
        "--pads",
        "40",
        "--seed",
        "2",
        "-o",
        path,
        "--force",
    ]);
    assert_eq!(code, 0, "{stderr}");
    let instance: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    let sum: f64 = instance["charge_times_min"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_f64().unwrap())
        .sum();
    assert_eq!((sum / 40.0).ceil(), 615.0);
    let (code, stdout, stderr) =
        swarmplan(&["node-time", "--file", path, "--node-limit", "1", "--json"]);
    assert_eq!(code, 0, "{stderr}");
    let v: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(v["status"], "feasible");
    assert_eq!(v["lower_bound_min"], 618.0);
    let makespan = v["makespan_min"].as_f64().unwrap();
    assert!(makespan > 618.0);
    let gap = v["gap"]["relative"].as_f64().unwrap();
    assert!((gap - (makespan - 618.0) / 618.0).abs() < 1e-12);
    assert_eq!(v["gap"]["reference"], "bound");
}
