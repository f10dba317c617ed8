//! The command line as a newcomer meets it (issue 13, item 8): one flag name for one thing, one
//! word for a delivered request, no progress drawing when stderr is not a terminal, rounded human
//! output beside full-precision CSV and JSON, a missing backend or missing files explained at
//! once, and `generate` that does not overwrite a file unasked.

use serde_json::Value;
use std::path::PathBuf;
use std::process::{Command, Output};

fn swarmplan(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args(args)
        .output()
        .expect("the binary runs")
}

fn tiny(name: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("instances/tiny")
        .join(name)
        .to_str()
        .unwrap()
        .to_string()
}

fn tmp(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("cli_usage");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).to_string()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).to_string()
}

fn json(out: &Output) -> Value {
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{e}: {out:?}"))
}

/// Asserts exit code 2 and that stderr names `code` and every one of `words`.
fn assert_exit_2_with(out: &Output, code: &str, words: &[&str]) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains(&format!("[{code}]")), "no {code} in: {err}");
    for w in words {
        assert!(err.contains(w), "no `{w}` in: {err}");
    }
}

#[test]
fn every_subcommand_reads_the_request_set_from_requests_and_the_old_spelling_still_works() {
    let (net, profile, requests) = (
        tiny("flat-line.json"),
        tiny("flat.toml"),
        tiny("flat-requests.json"),
    );
    let base = ["--network", &net, "--profile", &profile];
    let runs: [(&str, &[&str]); 4] = [
        ("solve", &["--request-id", "pb-fb", "--json"]),
        ("inspect", &["--request-id", "pb-fb", "--json"]),
        (
            "eaas",
            &["--request-id", "pb-fb", "--methods", "pb,fb", "--json"],
        ),
        ("batch", &["--json"]),
    ];
    for (command, extra) in runs {
        let mut outputs = Vec::new();
        for flag in ["--requests", "--request-file"] {
            let mut args = vec![command];
            args.extend_from_slice(&base);
            args.extend_from_slice(&[flag, &requests]);
            args.extend_from_slice(extra);
            let out = swarmplan(&args);
            assert_eq!(out.status.code(), Some(0), "{command} {flag}: {out:?}");
            let mut v = json(&out);
            strip_times(&mut v);
            outputs.push(v);
        }
        assert_eq!(
            outputs[0], outputs[1],
            "{command}: both spellings, one result"
        );
        // The help names the one spelling; the old one is a hidden alias.
        let help = stdout(&swarmplan(&[command, "--help"]));
        assert!(help.contains("--requests <FILE>"), "{command}: {help}");
        assert!(!help.contains("request-file"), "{command}: {help}");
    }
}

/// Removes every wall-clock figure (`*_ms`), the only numbers that are not reproducible.
fn strip_times(v: &mut Value) {
    match v {
        Value::Object(map) => {
            map.retain(|k, _| !k.ends_with("_ms"));
            map.values_mut().for_each(strip_times);
        }
        Value::Array(items) => items.iter_mut().for_each(strip_times),
        _ => {}
    }
}

#[test]
fn batch_json_and_csv_both_say_delivered() {
    let (net, profile, requests) = (
        tiny("flat-line.json"),
        tiny("flat.toml"),
        tiny("flat-requests.json"),
    );
    let args = [
        "batch",
        "--network",
        &net,
        "--profile",
        &profile,
        "--requests",
        &requests,
    ];
    let out = swarmplan(&[&args[..], &["--json"]].concat());
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let summary = &json(&out)[0];
    assert!(summary.get("succeeded").is_none(), "{summary}");
    let delivered = summary["delivered"].as_u64().expect("a delivered count");
    let out = swarmplan(&args);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let text = stdout(&out);
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = header.iter().position(|&h| h == "delivered").unwrap();
    assert_eq!(row[column], delivered.to_string());
}

#[test]
fn progress_is_not_drawn_when_stderr_is_not_a_terminal() {
    // Every command that shows a bar or a spinner on a terminal, with stderr captured: stderr
    // holds exactly the messages it held before progress existed, with no carriage return or
    // escape sequence.
    let (net, profile, requests) = (
        tiny("flat-line.json"),
        tiny("flat.toml"),
        tiny("flat-requests.json"),
    );
    let instance = [
        "--network",
        &net,
        "--profile",
        &profile,
        "--requests",
        &requests,
    ];
    let batch = swarmplan(&[&["batch"], &instance[..], &["--sharing", "pb,fb"]].concat());
    assert_eq!(batch.status.code(), Some(0), "{batch:?}");
    let err = stderr(&batch);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(
        lines.len(),
        3,
        "one line per combination, then the grid's: {err}"
    );
    assert!(
        lines[..2].iter().all(|l| l.starts_with("sharing ")),
        "{err}"
    );
    assert!(lines[2].contains(" combinations on "), "{err}");
    assert!(!err.contains('\r') && !err.contains('\u{1b}'), "{err:?}");
    let quiet = [
        [&["batch"], &instance[..], &["--sharing", "exact", "--json"]].concat(),
        [
            &["solve"],
            &instance[..],
            &["--request-id", "pb-fb", "--sharing", "exact"],
        ]
        .concat(),
        [&["eaas"], &instance[..], &["--request-id", "pb-fb"]].concat(),
        vec!["node-time", "--pads", "3", "--times", "60,50,40,30,20"],
    ];
    for args in quiet {
        let out = swarmplan(&args);
        assert_eq!(out.status.code(), Some(0), "{args:?}: {out:?}");
        assert_eq!(stderr(&out), "", "{args:?}");
    }
}

#[test]
fn human_output_is_rounded_while_csv_and_json_keep_every_digit() {
    // flat-line, PB: dt 4, 6.5 and 8 min, a mean of 6.166666666666667 min.
    let (net, profile, requests) = (
        tiny("flat-line.json"),
        tiny("flat.toml"),
        tiny("flat-requests.json"),
    );
    let args = [
        "batch",
        "--network",
        &net,
        "--profile",
        &profile,
        "--requests",
        &requests,
    ];
    let from_json = json(&swarmplan(&[&args[..], &["--json"]].concat()))[0].clone();
    let out = swarmplan(&args);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let text = stdout(&out);
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    let csv = |name: &str| row[header.iter().position(|&h| h == name).unwrap()];
    // The CSV holds the JSON's number, digit for digit.
    for name in ["mean_dt_min", "mean_nt_min", "mean_stops"] {
        let value: f64 = csv(name).parse().unwrap();
        assert_eq!(value, from_json[name].as_f64().unwrap(), "{name}");
    }
    assert_eq!(csv("mean_dt_min"), "6.166666666666667");
    // The line for people on stderr rounds it.
    assert!(
        stderr(&out).contains("mean dt 6.17 min"),
        "{}",
        stderr(&out)
    );
    // node-time: 0.1 + 0.2 min is 0.30000000000000004 in JSON, 0.3 for people.
    let nt = ["node-time", "--pads", "1", "--times", "0.1,0.2"];
    let v = json(&swarmplan(&[&nt[..], &["--json"]].concat()));
    assert_eq!(v["makespan_min"].as_f64().unwrap(), 0.1 + 0.2);
    let text = stdout(&swarmplan(&nt));
    assert!(text.contains("node time: 0.3 min (optimal"), "{text}");
    assert!(text.contains("pad 0: load 0.3 min"), "{text}");
    assert!(!text.contains("0000"), "{text}");
}

#[test]
#[cfg(not(feature = "highs"))]
fn highs_in_a_build_without_it_says_how_to_build_it() {
    let runs: [&[&str]; 3] = [
        &[
            "node-time",
            "--pads",
            "2",
            "--times",
            "1,2",
            "--method",
            "milp",
        ],
        &["solve", "--request-id", "r00001", "--sharing", "exact"],
        &["eaas", "--request-id", "r00001", "--methods", "milp"],
    ];
    for args in runs {
        let out = swarmplan(&[args, &["--backend", "highs"]].concat());
        assert_exit_2_with(
            &out,
            "E0012",
            &["--features highs", "cmake", "libclang", "apt-get install"],
        );
    }
    // A name swarmplan does not know stays a plain usage error listing the known names.
    let out = swarmplan(&[
        "node-time",
        "--pads",
        "2",
        "--times",
        "1,2",
        "--backend",
        "glpk",
    ]);
    assert_exit_2_with(&out, "E0007", &["microlp", "highs"]);
    // The help names highs and how to get it.
    let help = stdout(&swarmplan(&["node-time", "--help"]));
    assert!(help.contains("--features highs"), "{help}");
}

#[test]
fn every_missing_input_file_is_reported_at_once() {
    let dir = tmp("missing");
    let (net, profile, requests, hop) = (
        dir.join("net.json"),
        dir.join("profile.toml"),
        dir.join("requests.json"),
        dir.join("hop.json"),
    );
    let (net, profile, requests, hop) = (
        net.to_str().unwrap(),
        profile.to_str().unwrap(),
        requests.to_str().unwrap(),
        hop.to_str().unwrap(),
    );
    let files = [
        "--network",
        net,
        "--profile",
        profile,
        "--requests",
        requests,
    ];
    let runs = [
        [&["solve"], &files[..], &["--request-id", "r1"]].concat(),
        [&["inspect"], &files[..], &["--request-id", "r1"]].concat(),
        [&["eaas"], &files[..], &["--request-id", "r1"]].concat(),
        [&["batch"], &files[..]].concat(),
    ];
    for args in runs {
        let out = swarmplan(&args);
        assert_exit_2_with(&out, "E0008", &[net, profile, requests]);
        assert!(stderr(&out).contains("3 problem(s)"), "{}", stderr(&out));
    }
    let out = swarmplan(&["eaas", "--hop-file", hop, "--profile", profile]);
    assert_exit_2_with(&out, "E0008", &[hop, profile]);
    // A broken file and a missing one: both, not only the first.
    let out = swarmplan(&[
        "batch",
        "--network",
        &tiny("invalid-network.json"),
        "--requests",
        requests,
    ]);
    assert_exit_2_with(&out, "E0008", &["E1101", "E1207", requests]);
}

#[test]
fn generate_does_not_overwrite_a_file_without_force() {
    let out_file = tmp("generated-network.json");
    let out = out_file.to_str().unwrap();
    std::fs::write(&out_file, "keep me").unwrap();
    let network = [
        "generate", "network", "--nodes", "20", "--seed", "1", "-o", out,
    ];
    assert_exit_2_with(&swarmplan(&network), "E0013", &[out, "--force"]);
    assert_eq!(std::fs::read_to_string(&out_file).unwrap(), "keep me");
    let forced = swarmplan(&[&network[..], &["--force"]].concat());
    assert_eq!(forced.status.code(), Some(0), "{forced:?}");
    let written = std::fs::read_to_string(&out_file).unwrap();
    assert!(written.contains("\"nodes\""), "{written}");
    // generate requests: the existing file and a missing network, both reported.
    let requests = [
        "generate",
        "requests",
        "--network",
        "no-such-network.json",
        "--seed",
        "1",
        "-o",
        out,
    ];
    assert_exit_2_with(
        &swarmplan(&requests),
        "E0013",
        &["E0008", "no-such-network.json"],
    );
    assert_eq!(std::fs::read_to_string(&out_file).unwrap(), written);
}

#[test]
fn request_limit_counts_requests_and_limit_is_its_former_name() {
    for flag in ["--request-limit", "--limit"] {
        let out = swarmplan(&["batch", flag, "3", "--json"]);
        assert_eq!(out.status.code(), Some(0), "{flag}: {}", stderr(&out));
        let summary = json(&out);
        // One combination (the default pb/location-aware/sequential) over the first 3 requests.
        assert_eq!(summary.as_array().map(Vec::len), Some(1), "{flag}");
        assert_eq!(summary[0]["requests"], 3, "{flag}");
    }
    // The former name stays out of the help.
    let help = stdout(&swarmplan(&["batch", "--help"]));
    assert!(help.contains("--request-limit <N>"), "{help}");
    assert!(!help.contains("--limit <N>"), "{help}");
}
