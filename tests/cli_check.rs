//! `swarmplan check`: plans written by `solve --json` pass; the same plans with one number
//! changed (a battery, a pad assignment, a time, a node id) are rejected with exit code 1 and
//! the code of the rule that number breaks; malformed plan files exit 2 with their code.
//!
//! The expected codes come from the rules in src/check/plan.rs, worked out by hand below, not
//! from running the checker.

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

fn swarmplan(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn repo(path: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join(path)
        .to_str()
        .unwrap()
        .to_string()
}

fn tmp(name: &str) -> String {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli_check");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name).to_str().unwrap().to_string()
}

/// Writes `text` to [`tmp`]`(name)`: aside, then renamed, since the tests run in parallel and
/// several write the same file (a reader must never see it truncated, half written).
fn write(name: &str, text: &str) -> String {
    static WRITES: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let path = tmp(name);
    let n = WRITES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let aside = format!("{path}.{}-{n}.part", std::process::id());
    std::fs::write(&aside, text).unwrap();
    std::fs::rename(&aside, &path).unwrap();
    path
}

fn stdout_json(out: &Output) -> Value {
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}: {out:?}"))
}

/// The tiny flat-stop instance (instances/tiny/README.md): A - M - B, 2500 m each, M with 2
/// pads, and a request file with the request `stop`: drones of 0.21, 0.21, 0.44 kg.
struct Tiny {
    network: String,
    profile: String,
    requests: String,
}

fn tiny() -> Tiny {
    Tiny {
        network: repo("instances/tiny/flat-stop.json"),
        profile: repo("instances/tiny/flat.toml"),
        requests: write(
            "flat-stop-requests.json",
            r#"{"schema_version": 1, "requests": [
                {"id": "stop", "source": "A", "destination": "B", "packages_kg": [0.21, 0.21, 0.44]}]}"#,
        ),
    }
}

impl Tiny {
    fn args<'a>(&'a self, command: &'a str) -> Vec<&'a str> {
        vec![
            command,
            "--network",
            &self.network,
            "--profile",
            &self.profile,
            "--requests",
            &self.requests,
        ]
    }

    /// The plan of `stop` under the paper's baseline (no sharing, no support drone), by
    /// `solve --json`.
    fn plan(&self) -> Value {
        let out = swarmplan(&[
            "solve",
            "--network",
            &self.network,
            "--profile",
            &self.profile,
            "--requests",
            &self.requests,
            "--request-id",
            "stop",
            "--sharing",
            "none",
            "--json",
        ]);
        assert_eq!(out.status.code(), Some(0), "{out:?}");
        stdout_json(&out)
    }

    /// `check --json` of `plan`: the exit code and the violation codes.
    fn check(&self, name: &str, plan: &Value) -> (Option<i32>, Vec<String>) {
        let path = write(name, &serde_json::to_string_pretty(plan).unwrap());
        let mut args = self.args("check");
        args.extend(["--plan", &path, "--json"]);
        check_output(&swarmplan(&args))
    }
}

fn check_output(out: &Output) -> (Option<i32>, Vec<String>) {
    let list = stdout_json(out);
    let codes = list
        .as_array()
        .unwrap_or_else(|| panic!("a JSON list: {out:?}"))
        .iter()
        .map(|x| x["code"].as_str().unwrap().to_string())
        .collect();
    (out.status.code(), codes)
}

fn f64_at(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

/// A hand-edited plan's violations say what happened and what to do, not that the tool has a
/// bug (was: "report it with the instance and the request").
#[test]
fn a_changed_plan_is_told_to_be_made_again_not_reported() {
    let t = tiny();
    let mut p = t.plan();
    let b = &mut p["plan"]["hops"][0]["arrival_battery_mah"][2];
    *b = Value::from(f64_at(b) + 10.0);
    let path = write("edited.json", &serde_json::to_string_pretty(&p).unwrap());
    let mut args = t.args("check");
    args.extend(["--plan", &path]);
    let out = swarmplan(&args);
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("[P5015]") && text.contains("[P5022]"),
        "{text}"
    );
    assert!(!text.contains("report it"), "{text}");
    for words in [
        "changed after it was made",
        "make it again",
        "swarmplan solve",
    ] {
        assert!(text.contains(words), "'{words}': {text}");
    }
}

#[test]
fn a_tiny_plan_passes_and_each_changed_number_breaks_its_rule() {
    let t = tiny();
    let good = t.plan();
    // The plan (tests/compose.rs): A -> M, stop at M on 2 pads (ct 6.655, 6.655, 8.64 min, pads
    // {0, 1} | {2}, nt 13.31), M -> B.
    assert_eq!(good["plan"]["outcome"]["kind"], "delivered");
    assert_eq!(good["schema_version"], 1);
    assert_eq!(good["plan"]["hops"][0]["stop"]["node"], "M");
    assert_eq!(t.check("good.json", &good), (Some(0), vec![]));

    // A battery: drone 2 arrives at M with 10 mAh more than the flight leaves it. The
    // re-integrated arrival differs (P5015 wrapping C3016), and so do the charge times at M
    // (P5022). nt is unchanged: drone 2 charges alone on the pad that is not the longest
    // (8.54 < 13.31), and {0, 1} | {2} stays optimal.
    let mut p = good.clone();
    let b = &mut p["plan"]["hops"][0]["arrival_battery_mah"][2];
    *b = Value::from(f64_at(b) + 10.0);
    assert_eq!(
        t.check("battery.json", &p),
        (Some(1), vec!["P5015".into(), "P5022".into()])
    );

    // A pad assignment: drone 2 replaced by drone 0 on its pad. Drone 0 charges twice and
    // drone 2 never (P5025); the makespan is still 6.655 + 6.655 = 13.31 = nt.
    let mut p = good.clone();
    let pads = p["plan"]["hops"][0]["stop"]["assignment"]
        .as_array_mut()
        .unwrap();
    let alone = pads.iter().position(|pad| pad == &serde_json::json!([2]));
    pads[alone.expect("drone 2 charges alone")] = serde_json::json!([0]);
    assert_eq!(t.check("pads.json", &p), (Some(1), vec!["P5025".into()]));

    // A time: the second hop one minute longer than 2500 m / 500 m/min = 5 min (P5013), and
    // the plan's tt and dt no longer its hops' sums (P5030, P5031).
    let mut p = good.clone();
    let tt = &mut p["plan"]["hops"][1]["tt_min"];
    *tt = Value::from(f64_at(tt) + 1.0);
    assert_eq!(
        t.check("time.json", &p),
        (
            Some(1),
            vec!["P5013".into(), "P5030".into(), "P5031".into()]
        )
    );

    // A node id: the stop moved to A, where the hop does not end (P5020) and which has no
    // pads (P5021).
    let mut p = good.clone();
    p["plan"]["hops"][0]["stop"]["node"] = "A".into();
    assert_eq!(
        t.check("node.json", &p),
        (Some(1), vec!["P5020".into(), "P5021".into()])
    );

    // The request: a package changed (P5042); the plan is then checked against the file's
    // request, which it fits.
    let mut p = good.clone();
    p["request"]["packages_kg"][0] = 0.3.into();
    assert_eq!(t.check("request.json", &p), (Some(1), vec!["P5042".into()]));
    // A request id the file does not have (P5041).
    let mut p = good.clone();
    p["request"]["id"] = "elsewhere".into();
    assert_eq!(
        t.check("request_id.json", &p),
        (Some(1), vec!["P5041".into()])
    );
    // A support drone claimed that the swarm does not fly (P5043).
    let mut p = good.clone();
    p["support_drones"] = 1.into();
    assert_eq!(t.check("support.json", &p), (Some(1), vec!["P5043".into()]));
}

#[test]
fn a_paper_195_plan_with_stops_and_a_transfer_passes_and_each_changed_number_breaks_its_rule() {
    // r00023 under PB, Algorithm 1: n095 -> n110 (stop) -> n124 (stop) -> n158, 7 delivery
    // drones and 1 support drone, one transfer on the last hop (support 7 to drone 4, which
    // swaps slots). 8 drones: the node time is also proved optimal by exhaustive search.
    let solve = swarmplan(&["solve", "--request-id", "r00023", "--json"]);
    assert_eq!(solve.status.code(), Some(0), "{solve:?}");
    let good = stdout_json(&solve);
    let plan = &good["plan"];
    assert_eq!(plan["hops"].as_array().unwrap().len(), 3);
    assert_eq!(plan["hops"][2]["transfers"].as_array().unwrap().len(), 1);
    let check = |name: &str, p: &Value| {
        let path = write(name, &serde_json::to_string(p).unwrap());
        check_output(&swarmplan(&["check", "--plan", &path, "--json"]))
    };
    assert_eq!(check("r00023.json", &good), (Some(0), vec![]));

    // A time: the transfer starts a minute earlier. Its energy is no longer rho x duration
    // (C3005) and the re-integrated arrival batteries differ from the reported ones (C3016),
    // each wrapped in P5015. The energy field and the hop's and plan's shared totals still
    // agree with each other (no C3018, no P5032).
    let mut p = good.clone();
    let start = &mut p["plan"]["hops"][2]["transfers"][0]["start_min"];
    *start = Value::from(f64_at(start) - 1.0);
    let path = write("r00023_time.json", &serde_json::to_string(&p).unwrap());
    let out = swarmplan(&["check", "--plan", &path, "--json"]);
    assert_eq!(
        check_output(&out),
        (Some(1), vec!["P5015".into(), "P5015".into()])
    );
    let causes: Vec<String> = stdout_json(&out)
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x["cause"].as_str().unwrap().to_string())
        .collect();
    assert!(causes[0].starts_with("[C3005]"), "{causes:?}");
    assert!(causes[1].starts_with("[C3016]"), "{causes:?}");

    // A battery: drone 1 arrives at n124 with 50 mAh less. The re-integration disagrees
    // (P5015) and so do the charge times (P5022). Drone 1 shares its pad with drone 4 (3.25 +
    // 6.59 = 9.84 min, below nt = 11.09): its charge time grows by 50 / 74.67 (the `paper` pad
    // rate) = 0.67 min, to 10.51 < nt, so the makespan stays nt; a larger charge time cannot
    // lower the optimum below nt, and the bound sum ct / 4 = 10.54 stays below nt.
    let mut p = good.clone();
    let stop = &p["plan"]["hops"][1]["stop"];
    assert_eq!(stop["assignment"][1], serde_json::json!([1, 4]), "{stop}");
    let b = &mut p["plan"]["hops"][1]["arrival_battery_mah"][1];
    *b = Value::from(f64_at(b) - 50.0);
    assert_eq!(
        check("r00023_battery.json", &p),
        (Some(1), vec!["P5015".into(), "P5022".into()])
    );

    // A pad assignment: drones 7 and 1 swap pads at n110: {0, 1} | {7, 2} | ... puts 10.48 +
    // 9.08 = 19.56 min on one pad, not nt = 14.32 (P5026); the plan is not better than the
    // optimum, so no P5028.
    let mut p = good.clone();
    let pads = &mut p["plan"]["hops"][0]["stop"]["assignment"];
    assert_eq!(pads[0], serde_json::json!([0, 7]));
    assert_eq!(pads[1], serde_json::json!([1, 2]));
    pads[0][1] = 1.into();
    pads[1][0] = 7.into();
    assert_eq!(
        check("r00023_pads.json", &p),
        (Some(1), vec!["P5026".into()])
    );

    // A node id: the second hop claims to start at n109, where the swarm is not (P5004), and
    // its path no longer starts at its start (P5009).
    let mut p = good.clone();
    p["plan"]["hops"][1]["from"] = "n109".into();
    assert_eq!(
        check("r00023_node.json", &p),
        (Some(1), vec!["P5004".into(), "P5009".into()])
    );

    // The human output names the plan and lists the violations with their codes.
    let path = write("r00023_node.json", &serde_json::to_string(&p).unwrap());
    let out = swarmplan(&["check", "--plan", &path]);
    assert_eq!(out.status.code(), Some(1));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("plan of request r00023"), "{text}");
    assert!(text.contains("2 violation(s)"), "{text}");
    assert!(text.contains("[P5004] hops[1].from"), "{text}");
}

#[test]
fn malformed_plan_files_exit_2_with_their_code() {
    let t = tiny();
    let good = serde_json::to_string_pretty(&t.plan()).unwrap();
    let check = |name: &str, text: &str| {
        let path = write(name, text);
        let mut args = t.args("check");
        args.extend(["--plan", &path]);
        swarmplan(&args)
    };
    let coded = |out: &Output, code: &str| {
        assert_eq!(out.status.code(), Some(2), "{out:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(&format!("[{code}]")), "{code}: {err}");
        assert!(out.stdout.is_empty(), "{out:?}");
    };
    // Not JSON: cut in the middle.
    coded(&check("cut.json", &good[..good.len() / 2]), "E6001");
    coded(&check("text.json", "plan"), "E6001");
    // Another schema version, or none.
    coded(
        &check(
            "version.json",
            &good.replacen("\"schema_version\": 1", "\"schema_version\": 2", 1),
        ),
        "E6002",
    );
    coded(&check("no_version.json", "{}"), "E6002");
    // JSON, but not a plan document: an unknown field, a mistyped one, an unknown outcome.
    coded(
        &check(
            "unknown.json",
            &good.replacen(
                "\"schema_version\": 1",
                "\"schema_version\": 1, \"note\": 0",
                1,
            ),
        ),
        "E6003",
    );
    coded(
        &check(
            "mistyped.json",
            &good.replacen("\"dt_min\": ", "\"dt_min\": \"soon\", \"x\": ", 1),
        ),
        "E6003",
    );
    coded(
        &check(
            "kind.json",
            &good.replacen("\"kind\": \"delivered\"", "\"kind\": \"arrived\"", 1),
        ),
        "E6003",
    );
    coded(&check("list.json", "[1, 2]"), "E6003");
    // A file that is not there.
    let mut args = t.args("check");
    let missing = tmp("missing.json");
    args.extend(["--plan", &missing]);
    coded(&swarmplan(&args), "E0008");
}

#[test]
fn solve_json_piped_into_check_passes_and_solve_check_checks_what_it_prints() {
    let mut solve = Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args([
            "solve",
            "--request-id",
            "r00007",
            "--route",
            "astar",
            "--json",
        ])
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let check = Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args(["check", "--plan", "-"])
        .stdin(solve.stdout.take().unwrap())
        .output()
        .unwrap();
    assert_eq!(solve.wait().unwrap().code(), Some(0));
    assert_eq!(check.status.code(), Some(0), "{check:?}");
    assert!(String::from_utf8_lossy(&check.stdout).contains(": valid"));

    let t = tiny();
    let out = swarmplan(&[
        "solve",
        "--network",
        &t.network,
        "--profile",
        &t.profile,
        "--requests",
        &t.requests,
        "--request-id",
        "stop",
        "--sharing",
        "pb",
        "--support",
        "1",
        "--check",
    ]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("passes the independent checker"), "{err}");
}

/// A plan records the network and profile it was made on (SHA-256 of their JSON); checked
/// against another network or profile it gets one coded error naming the mismatch, exit 2,
/// before any model check; without the record (an earlier version's plan) it is checked as
/// before.
#[test]
fn a_plan_checked_on_another_instance_names_the_mismatch() {
    let out = swarmplan(&["solve", "--request-id", "r00042", "--json"]);
    assert!(out.status.success());
    let plan = stdout_json(&out);
    let made_on = &plan["made_on"];
    // SHA-256 in hex of the network's and the profile's JSON.
    for key in ["network_sha256", "profile_sha256"] {
        let h = made_on[key].as_str().unwrap();
        assert_eq!(h.len(), 64);
        assert!(h.chars().all(|c| c.is_ascii_hexdigit()));
    }
    let path = write("made_on.json", &plan.to_string());
    assert!(swarmplan(&["check", "--plan", &path]).status.success());

    let other = swarmplan(&[
        "check",
        "--plan",
        &path,
        "--network",
        &repo("instances/findings-195/network.json"),
    ]);
    assert_eq!(other.status.code(), Some(2));
    let err = String::from_utf8_lossy(&other.stderr);
    assert!(err.contains("1 problem(s)"), "{err}");
    assert!(
        err.contains("[E6004]") && err.contains("made on another network"),
        "{err}"
    );
    assert!(!err.contains("P50"), "{err}");

    let profile = swarmplan(&[
        "check",
        "--plan",
        &path,
        "--profile",
        &repo("instances/profiles/fast-sharing.toml"),
    ]);
    assert_eq!(profile.status.code(), Some(2));
    let err = String::from_utf8_lossy(&profile.stderr);
    assert!(
        err.contains("1 problem(s)") && err.contains("[E6005]"),
        "{err}"
    );

    // The same file read from disk is the same network: no mismatch.
    let same = swarmplan(&[
        "check",
        "--plan",
        &path,
        "--network",
        &repo("instances/paper-195/network.json"),
    ]);
    assert!(
        same.status.success(),
        "{}",
        String::from_utf8_lossy(&same.stderr)
    );

    // Without the record, a plan on another network reads as broken rules (exit 1).
    let mut old = plan.clone();
    old.as_object_mut().unwrap().remove("made_on");
    let old_path = write("made_on_absent.json", &old.to_string());
    let unrecorded = swarmplan(&[
        "check",
        "--plan",
        &old_path,
        "--network",
        &repo("instances/findings-195/network.json"),
    ]);
    assert_eq!(unrecorded.status.code(), Some(1));
}

/// Every number of a leg is its edge's: a plan whose leg states another length, heading, wind
/// or travel time (changed to x * 1.5 + 3, never the same number nor, for an angle, the same
/// direction: the change 0.5 x + 3 lies in [3, 183) degrees) is rejected with P5044 naming that
/// field.
#[test]
fn a_changed_leg_number_is_rejected_with_its_field() {
    let out = swarmplan(&["solve", "--request-id", "r00042", "--json"]);
    let plan = stdout_json(&out);
    let path = write("legs.json", &plan.to_string());
    assert!(swarmplan(&["check", "--plan", &path]).status.success());
    for field in [
        "distance_m",
        "heading_deg",
        "wind_speed_mps",
        "wind_from_deg",
        "tt_min",
    ] {
        let mut changed = plan.clone();
        let leg = &mut changed["plan"]["hops"][0]["legs"][1];
        let x = leg[field].as_f64().unwrap();
        leg[field] = serde_json::json!(x * 1.5 + 3.0);
        let path = write(&format!("legs-{field}.json"), &changed.to_string());
        let out = swarmplan(&["check", "--plan", &path, "--json"]);
        assert_eq!(out.status.code(), Some(1), "{field}");
        let violations = stdout_json(&out);
        let hit = violations
            .as_array()
            .unwrap()
            .iter()
            .any(|v| v["code"] == "P5044" && v["field"] == format!("hops[0].legs[1].{field}"));
        assert!(hit, "{field}: {violations}");
    }
}

/// `check --node-time`: the paper's example (70 min on 3 pads: loads 60, 50 + 20, 40 + 30)
/// passes; the same result stating 80 min is rejected with P5502 alone (the bound, 70, is still
/// the largest pad load), exit 1; given another instance file, P5506 names the charge time that
/// differs.
#[test]
fn node_time_results_are_checked() {
    let out = swarmplan(&[
        "node-time",
        "--pads",
        "3",
        "--times",
        "60,50,40,30,20",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let mut result = stdout_json(&out);
    assert_eq!(result["pads"], 3);
    let path = write("node-time.json", &result.to_string());
    let ok = swarmplan(&["check", "--node-time", &path, "--json"]);
    assert_eq!(ok.status.code(), Some(0), "{ok:?}");
    assert_eq!(stdout_json(&ok), serde_json::json!([]));
    result["makespan_min"] = 80.0.into();
    let changed = write("node-time-80.json", &result.to_string());
    let bad = swarmplan(&["check", "--node-time", &changed, "--json"]);
    assert_eq!(bad.status.code(), Some(1), "{bad:?}");
    let codes: Vec<String> = stdout_json(&bad)
        .as_array()
        .unwrap()
        .iter()
        .map(|v| {
            format!(
                "{} {}",
                v["code"].as_str().unwrap(),
                v["field"].as_str().unwrap()
            )
        })
        .collect();
    assert_eq!(codes, vec!["P5502 makespan_min"]);
    let other = write(
        "node-time-instance.json",
        r#"{"pads": 3, "charge_times_min": [60, 50, 40, 30, 25]}"#,
    );
    let mismatch = swarmplan(&[
        "check",
        "--node-time",
        &path,
        "--node-time-instance",
        &other,
        "--json",
    ]);
    assert_eq!(mismatch.status.code(), Some(1), "{mismatch:?}");
    assert_eq!(stdout_json(&mismatch)[0]["field"], "charge_times_min[4]");
}

/// Asserts exit code 2 and that stderr names `code` and every one of `words`.
fn assert_exit_2_with(out: &Output, code: &str, words: &[&str]) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{code}: {err}");
    assert!(err.contains(&format!("[{code}]")), "{code} missing: {err}");
    for w in words {
        assert!(err.contains(w), "{code}: '{w}' missing: {err}");
    }
}

/// `check --node-time` in words: a gap that does not fit the status is told as relative gaps
/// against their references (was Rust debug text, `Some(Gap { relative: Some(0.5), reference:
/// Bound })`); a negative charge time in the result, or in the instance file, is bad input
/// (E5003, exit 2, the file and field named), not a violation of the exhaustive optimum.
#[test]
fn node_time_checks_speak_in_words_and_a_negative_charge_time_is_input() {
    let out = swarmplan(&["node-time", "--pads", "2", "--times", "3,2,2", "--json"]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let result = stdout_json(&out);
    let mut gap = result.clone();
    gap["gap"] = serde_json::json!({"relative": 0.5, "reference": "bound"});
    let path = write("node-time-gap.json", &gap.to_string());
    let out = swarmplan(&["check", "--node-time", &path]);
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("[P5505]"), "{text}");
    assert!(
        text.contains("relative gap 0.5 against the lower bound")
            && text.contains("status optimal gives relative gap 0 against the optimum"),
        "{text}"
    );
    for debug in ["Some(", "Gap {", "Optimal", "Bound"] {
        assert!(!text.contains(debug), "{debug}: {text}");
    }
    let mut negative = result.clone();
    negative["charge_times_min"][0] = (-3.0).into();
    let path = write("node-time-negative.json", &negative.to_string());
    let out = swarmplan(&["check", "--node-time", &path]);
    assert_exit_2_with(
        &out,
        "E5003",
        &["node-time-negative.json", "charge_times_min[0]", "-3"],
    );
    let ok = write("node-time-ok.json", &result.to_string());
    let instance = write(
        "node-time-negative-instance.json",
        r#"{"pads": 2, "charge_times_min": [3, -2, 2]}"#,
    );
    let out = swarmplan(&[
        "check",
        "--node-time",
        &ok,
        "--node-time-instance",
        &instance,
    ]);
    assert_exit_2_with(
        &out,
        "E5003",
        &["node-time-negative-instance.json", "charge_times_min[1]"],
    );
}

/// `check --hop-file`: the hop `eaas --write-hop` writes passes; its first leg said to last a
/// minute longer is rejected with P5603 naming that leg; no document at all is a usage error.
#[test]
fn hop_files_are_checked() {
    let t = tiny();
    let path = tmp("stop-hop.json");
    let mut args = t.args("eaas");
    args.extend([
        "--request-id",
        "stop",
        "--write-hop",
        &path,
        "--force",
        "--methods",
        "pb",
    ]);
    let out = swarmplan(&args);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let mut args = t.args("check");
    args.extend(["--hop-file", &path, "--json"]);
    let ok = swarmplan(&args);
    assert_eq!(ok.status.code(), Some(0), "{ok:?}");
    let mut hop: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    let minutes = hop["hop"]["legs"][0]["duration_min"].as_f64().unwrap();
    hop["hop"]["legs"][0]["duration_min"] = (minutes + 1.0).into();
    let changed = write("stop-hop-longer.json", &hop.to_string());
    let mut args = t.args("check");
    args.extend(["--hop-file", &changed, "--json"]);
    let bad = swarmplan(&args);
    assert_eq!(bad.status.code(), Some(1), "{bad:?}");
    let found = stdout_json(&bad);
    assert_eq!(found[0]["code"], "P5603");
    assert_eq!(found[0]["field"], "hop.legs[0].duration_min");
    assert_eq!(swarmplan(&["check"]).status.code(), Some(2));
}

#[test]
fn one_document_per_check_and_a_bench_check_of_nothing_is_refused() {
    // Two documents: refused before either is read, never "valid" for one of them alone.
    let out = swarmplan(&["check", "--plan", "p.json", "--node-time", "r.json"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("[E0007]") && err.contains("--node-time"),
        "{err}"
    );
    let out = swarmplan(&["check", "--hop-file", "h.json", "--bench", "d"]);
    assert_eq!(out.status.code(), Some(2));
    // --request-limit 0 would check nothing.
    let out = swarmplan(&["check", "--bench", "d", "--request-limit", "0"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("E6007") && err.contains("--request-limit"),
        "{err}"
    );
}

#[test]
fn a_plan_of_a_request_given_on_the_command_line_checks_clean() {
    // `solve --from --to --packages` plans request `cli`, which no request file holds: the plan
    // is checked against its own request, and a changed number is still caught.
    let out = swarmplan(&[
        "solve",
        "--from",
        "n000",
        "--to",
        "n194",
        "--packages",
        "1.2,0.8,0.5",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let mut plan: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(plan["request"]["id"], "cli");
    let path = write("cli-request-plan.json", &plan.to_string());
    let (code, codes) = check_output(&swarmplan(&["check", "--plan", &path, "--json"]));
    assert_eq!((code, codes), (Some(0), Vec::<String>::new()));
    plan["plan"]["dt_min"] = Value::from(f64_at(&plan["plan"]["dt_min"]) + 1.0);
    let path = write("cli-request-plan-changed.json", &plan.to_string());
    let (code, codes) = check_output(&swarmplan(&["check", "--plan", &path, "--json"]));
    assert_eq!(code, Some(1), "{codes:?}");
    assert!(!codes.is_empty());
}
