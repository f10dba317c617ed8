//! Hardening regressions (issue 14) from the command line: every quantity of a network and a
//! profile in its stated range, FB's work bound, and codes on unreadable files, non-UTF-8 files
//! and command-line usage errors. Each reproducer exits 2 with its code, fast.

mod common;

use common::{repo_arg, repo_path, stderr, swarmplan, tmp, write_tmp, FLAT_STOP_REQUEST_ARGS};
use std::process::Output;

/// Asserts exit code 2 and that stderr names `code` and every one of `words`.
fn assert_exit_2_with(out: &Output, code: &str, words: &[&str]) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "{code}: {err}");
    assert!(err.contains(&format!("[{code}]")), "{code} missing: {err}");
    for w in words {
        assert!(err.contains(w), "{code}: '{w}' missing: {err}");
    }
}

/// flat-stop (A - M - B, 2500 m each, pads at M) with one node or edge field replaced.
fn flat_stop_with(name: &str, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(repo_path("instances/tiny/flat-stop.json")).unwrap();
    assert!(text.contains(from), "{from}");
    write_tmp(name, text.replacen(from, to, 1).as_bytes())
}

/// The flat profile with one line replaced.
fn flat_profile_with(name: &str, from: &str, to: &str) -> String {
    let text = std::fs::read_to_string(repo_path("instances/tiny/flat.toml")).unwrap();
    assert!(text.contains(from), "{from}");
    write_tmp(name, text.replacen(from, to, 1).as_bytes())
}

fn solve_a_to_b(network: &str, profile: &str, extra: &[&str]) -> Output {
    let mut args = vec!["solve", "--network", network, "--profile", profile];
    args.extend(FLAT_STOP_REQUEST_ARGS);
    args.extend_from_slice(extra);
    swarmplan(&args)
}

#[test]
fn network_quantities_beyond_their_stated_ranges_exit_2_with_codes() {
    let profile = repo_arg("instances/tiny/flat.toml");
    let edge = r#"{ "from": "A", "to": "M", "wind_speed_mps""#;
    let cases: [(&str, String, &str, &[&str]); 7] = [
        (
            "x 1e308",
            flat_stop_with("x1e308.json", r#""x_m": 2500.0"#, r#""x_m": 1e308"#),
            "E1106",
            &["nodes[1].x_m", "[-1e7, 1e7] m"],
        ),
        (
            "distance 1e308 (was: E5004 charge time inf)",
            flat_stop_with(
                "d1e308.json",
                edge,
                r#"{ "from": "A", "to": "M", "distance_m": 1e308, "wind_speed_mps""#,
            ),
            "E1208",
            &["edges[0].distance_m", "(0, 1e6] m"],
        ),
        (
            "distance 1e200 (was: destination not connected)",
            flat_stop_with(
                "d1e200.json",
                edge,
                r#"{ "from": "A", "to": "M", "distance_m": 1e200, "wind_speed_mps""#,
            ),
            "E1208",
            &["edges[0].distance_m", "1e200"],
        ),
        (
            "Euclidean length 2e6 m",
            flat_stop_with("far.json", r#""x_m": 5000.0"#, r#""x_m": 2000000.0"#),
            "E1208",
            &["edges[1].distance_m", "Euclidean"],
        ),
        (
            "pad rate 1e-300",
            flat_stop_with(
                "rate.json",
                r#""pads": 2 }"#,
                r#""pads": 2, "pad_charge_rate_mah_per_min": 1e-300 }"#,
            ),
            "E1107",
            &["nodes[1].pad_charge_rate_mah_per_min", "[0.1, 1e6]"],
        ),
        (
            "pads 4294967295",
            flat_stop_with("pads.json", r#""pads": 2"#, r#""pads": 4294967295"#),
            "E1108",
            &["nodes[1].pads", "1000"],
        ),
        (
            "y -2e7",
            flat_stop_with(
                "y.json",
                r#""y_m": 0.0, "pads": 2"#,
                r#""y_m": -2e7, "pads": 2"#,
            ),
            "E1106",
            &["nodes[1].y_m"],
        ),
    ];
    for (what, network, code, words) in cases {
        let out = solve_a_to_b(&network, &profile, &["--sharing", "none"]);
        assert_exit_2_with(&out, code, words);
        let _ = what;
    }
}

#[test]
fn profile_quantities_beyond_their_stated_ranges_exit_2_with_e2013() {
    let network = repo_arg("instances/tiny/flat-stop.json");
    let cases = [
        // Was E4007 on legs[2] from inside the planner.
        ("speed_kmh = 30.0", "speed_kmh = 1e-300", "drone.speed_kmh"),
        (
            "battery_mah = 1000.0",
            "battery_mah = 1e308",
            "drone.battery_mah",
        ),
        (
            "lambda_mah = 1200.0",
            "lambda_mah = 0.01",
            "sharing.lambda_mah",
        ),
        (
            "extra_batteries = 1",
            "extra_batteries = 65",
            "support.extra_batteries",
        ),
        (
            "charge_rate_mah_per_min = 100.0",
            "charge_rate_mah_per_min = 1e-9",
            "pads.charge_rate_mah_per_min",
        ),
        (
            "endurance_min = 10.0",
            "endurance_min = 1e300",
            "energy.endurance_min",
        ),
    ];
    for (from, to, field) in cases {
        let profile = flat_profile_with("p.toml", from, to);
        let out = solve_a_to_b(&network, &profile, &["--sharing", "fb"]);
        assert_exit_2_with(&out, "E2013", &[field, "stated range"]);
    }
}

#[test]
fn fb_with_a_tiny_lambda_ends_with_e4015_instead_of_running_for_minutes() {
    // lambda = 1 mAh at rho = 120 mAh/min: a round of 0.5 s, 600 rounds per support drone on a
    // 5-minute hop; 4 support drones ask for 2,400 rounds, over the bound of 500.
    let network = repo_arg("instances/tiny/flat-stop.json");
    let profile = flat_profile_with("lambda1.toml", "lambda_mah = 1200.0", "lambda_mah = 1.0");
    let out = solve_a_to_b(&network, &profile, &["--sharing", "fb", "--support", "4"]);
    assert_exit_2_with(
        &out,
        "E4015",
        &["lambda_mah", "rounds", "raise sharing.lambda_mah"],
    );
    // PB does not depend on lambda and plans the same request.
    let out = solve_a_to_b(&network, &profile, &["--sharing", "pb", "--support", "4"]);
    assert!(matches!(out.status.code(), Some(0 | 1)), "{}", stderr(&out));
}

#[test]
fn unreadable_and_non_utf8_files_exit_2_with_e0008_and_e0009() {
    let missing = tmp("no-such-file.json");
    let missing = missing.to_str().unwrap();
    let dir = tmp("a-directory");
    std::fs::create_dir_all(&dir).unwrap();
    let dir = dir.to_str().unwrap();
    let latin1 = write_tmp(
        "latin1.json",
        b"{\"schema_version\": 1, \"name\": \"caf\xe9\"}",
    );
    for bad in [missing, dir] {
        for args in [
            vec!["inspect", "--network", bad],
            vec!["solve", "--profile", bad, "--request-id", "r00001"],
            vec!["batch", "--requests", bad, "--limit", "1"],
            vec!["eaas", "--hop-file", bad],
            vec!["node-time", "--file", bad],
        ] {
            assert_exit_2_with(&swarmplan(&args), "E0008", &["cannot read the file"]);
        }
    }
    for args in [
        vec!["inspect", "--network", &latin1],
        vec!["solve", "--profile", &latin1, "--request-id", "r00001"],
        vec!["batch", "--requests", &latin1, "--limit", "1"],
        vec!["eaas", "--hop-file", &latin1],
        vec!["node-time", "--file", &latin1],
    ] {
        assert_exit_2_with(
            &swarmplan(&args),
            "E0009",
            &["not UTF-8", "line 1 column 35"],
        );
    }
}

#[test]
fn usage_errors_exit_2_with_e0007_and_help_and_version_exit_0() {
    for args in [
        vec!["no-such-command"],
        vec!["solve", "--no-such-flag"],
        vec!["node-time", "--pads"],
        vec!["node-time", "--pads", "three", "--times", "1"],
        vec!["solve", "--sharing", "telepathy", "--request-id", "r00001"],
        vec!["batch", "--threads", "-1"],
    ] {
        let out = swarmplan(&args);
        assert_exit_2_with(&out, "E0007", &["command line"]);
    }
    // `swarmplan` alone prints the help, without an error prefix, and exits 2.
    let out = swarmplan(&[]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("Usage: swarmplan <COMMAND>"), "{err}");
    assert!(!err.contains("error") && !err.contains("E0007"), "{err}");
    // A value parser's own code is kept, not replaced by E0007.
    let out = swarmplan(&["generate", "network", "--nodes", "ten", "-o", "x.json"]);
    assert_exit_2_with(&out, "E1901", &[]);
    assert!(!stderr(&out).contains("E0007"));
    for args in [
        vec!["--help"],
        vec!["--version"],
        vec!["solve", "--help"],
        vec!["help"],
    ] {
        let out = swarmplan(&args);
        assert_eq!(out.status.code(), Some(0), "{args:?}: {}", stderr(&out));
        assert!(!out.stdout.is_empty());
    }
}

#[test]
fn a_file_that_cannot_be_written_exits_2_with_e0010() {
    let out = swarmplan(&[
        "generate",
        "network",
        "--nodes",
        "10",
        "--seed",
        "1",
        "-o",
        "/no-such-directory/network.json",
    ]);
    assert_exit_2_with(&out, "E0010", &["cannot write the file"]);
}

#[test]
fn no_output_file_is_overwritten_unasked_and_thread_counts_are_bounded() {
    // Each writing option refuses an existing file without --force (E0013), before any work,
    // and leaves the file as it was; with --force it writes.
    let path = write_tmp("existing-output.txt", b"keep me");
    let eaas = |option| {
        let request = [
            "eaas",
            "--request-id",
            "r00001",
            "--hop",
            "0",
            "--methods",
            "pb",
        ];
        [&request[..], &[option, path.as_str()]].concat()
    };
    let cases: [Vec<&str>; 4] = [
        vec!["batch", "--request-limit", "1", "--per-request", &path],
        eaas("--write-hop"),
        eaas("--write-lp"),
        vec![
            "node-time",
            "--pads",
            "2",
            "--times",
            "3,2,2",
            "--write-lp",
            &path,
        ],
    ];
    for args in &cases {
        let out = swarmplan(args);
        assert_exit_2_with(&out, "E0013", &[&path, "--force"]);
        assert_eq!(std::fs::read(&path).unwrap(), b"keep me", "{args:?}");
        let mut forced = args.clone();
        forced.push("--force");
        let out = swarmplan(&forced);
        assert_eq!(out.status.code(), Some(0), "{forced:?}: {}", stderr(&out));
        assert_ne!(std::fs::read(&path).unwrap(), b"keep me", "{forced:?}");
        std::fs::write(&path, b"keep me").unwrap();
    }
    // --threads: 1 to 1,024 (E0004 names the range), refused before any planning.
    for bad in ["0", "1025", "100000"] {
        let out = swarmplan(&["batch", "--request-limit", "5", "--threads", bad]);
        assert_exit_2_with(&out, "E0004", &["--threads", "1024"]);
    }
}

#[test]
fn dash_is_standard_output_and_files_are_written_whole() {
    // `-o -`: the JSON on stdout, no file named `-` (in the process's directory).
    let dir = tmp("dash-output");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args([
            "generate", "network", "--nodes", "5", "--seed", "1", "-o", "-",
        ])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let network: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(network["nodes"].as_array().unwrap().len(), 5);
    assert!(
        stderr(&out).contains("to standard output"),
        "{}",
        stderr(&out)
    );
    assert!(!dir.join("-").exists());
    // A file written to a path: the whole document, and no temporary file left beside it.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args([
            "generate", "network", "--nodes", "5", "--seed", "1", "-o", "n.json",
        ])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("n.json")).unwrap()).unwrap();
    assert_eq!(written, network);
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["n.json"]);
}

#[test]
fn a_json_type_error_names_the_field_path() {
    // A string where a number belongs: the message names the field, not only line and column.
    let requests = write_tmp(
        "typed-requests.json",
        br#"{"schema_version": 1, "requests": [{"id": "a", "source": "n000", "destination": "n001", "packages_kg": [0.5, "3"]}]}"#,
    );
    let out = swarmplan(&["batch", "--requests", &requests, "--request-limit", "1"]);
    assert_exit_2_with(&out, "E0001", &["requests[0].packages_kg[1]", "line 1"]);
    // The same in a plan file (E6003) and a hop file (E4111).
    let plan = write_tmp(
        "typed-plan.json",
        br#"{"schema_version": 1, "request": {"id": 7}}"#,
    );
    let out = swarmplan(&["check", "--plan", &plan]);
    assert_exit_2_with(&out, "E6003", &["request.id"]);
    let hop = write_tmp(
        "typed-hop.json",
        br#"{"schema_version": 1, "request_id": "r", "hop_index": "0"}"#,
    );
    let out = swarmplan(&["eaas", "--hop-file", &hop]);
    assert_exit_2_with(&out, "E4111", &["hop_index"]);
}

#[test]
fn options_that_apply_to_no_combination_are_refused_and_to_some_noted() {
    // --gap with fair alone: refused by solve and batch alike (E0015; bench measures the route
    // gaps by default and leaves fair's cells empty); beside another policy, a note on stderr
    // and empty gap cells for fair.
    let fair_gap: [&[&str]; 2] = [
        &[
            "solve",
            "--request-id",
            "r00001",
            "--sharing",
            "fair",
            "--gap",
        ],
        &[
            "batch",
            "--request-limit",
            "1",
            "--sharing",
            "fair",
            "--gap",
        ],
    ];
    for args in fair_gap {
        assert_exit_2_with(&swarmplan(args), "E0015", &["--gap", "fair"]);
    }
    let out = swarmplan(&[
        "batch",
        "--request-limit",
        "1",
        "--sharing",
        "pb,fair",
        "--route",
        "sequential",
        "--gap",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("note: --gap: the 1 combination(s) with --sharing fair"),
        "{}",
        stderr(&out)
    );
    // --support with none alone: refused (E0030); beside another policy, a note.
    let none_support: [&[&str]; 2] = [
        &[
            "solve",
            "--request-id",
            "r00001",
            "--sharing",
            "none",
            "--support",
            "2",
        ],
        &[
            "batch",
            "--request-limit",
            "1",
            "--sharing",
            "none",
            "--support",
            "2",
        ],
    ];
    for args in none_support {
        assert_exit_2_with(&swarmplan(args), "E0030", &["--support", "none"]);
    }
    let out = swarmplan(&[
        "batch",
        "--request-limit",
        "1",
        "--sharing",
        "none,pb",
        "--route",
        "sequential",
        "--support",
        "2",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("note: --support 2 does not apply to the"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_narrow_distance_bucket_keeps_the_figures_by_distance() {
    // --distance-bucket-km 1e-300 used to drop the by-distance figures without a word (the
    // bucket count overflowed); now each request is its own bucket.
    let dir = tmp("narrow-buckets");
    let _ = std::fs::remove_dir_all(&dir);
    let out = swarmplan(&[
        "bench",
        "--request-limit",
        "3",
        "--sharing",
        "none,pb",
        "--route",
        "sequential",
        "--distance-bucket-km",
        "1e-300",
        "--json",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    for m in summary["methods"].as_array().unwrap() {
        assert_eq!(m["by_distance"].as_array().unwrap().len(), 3, "{m}");
    }
    assert!(dir
        .join("figures/dt-by-distance-location-aware.svg")
        .exists());
}

#[test]
fn an_undeliverable_request_exits_1_even_when_stdout_closes_early() {
    // flat-deadend: the swarm cannot reach B (exit 1); the reader of stdout is gone before the
    // plan is printed, which used to turn the exit code into 0.
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args(["solve", "--network"])
        .arg(repo_path("instances/tiny/flat-deadend.json"))
        .args(["--profile"])
        .arg(repo_path("instances/tiny/flat.toml"))
        .args([
            "--from",
            "A",
            "--to",
            "B",
            "--packages",
            "0.21",
            "--sharing",
            "none",
            "--json",
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
}

#[test]
fn floyd_warshall_is_refused_beyond_its_stated_network_size() {
    // 10,001 nodes: its tables would take 1.1 GiB and O(n^3) time (100,000 nodes: 112 GiB,
    // which used to abort the process); E0029 names the size and Dijkstra.
    let network = tmp("fw-10001.json");
    let out = swarmplan(&[
        "generate",
        "network",
        "--nodes",
        "10001",
        "--seed",
        "1",
        "--force",
        "-o",
        network.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = std::fs::read_to_string(&network).unwrap();
    let doc: serde_json::Value = serde_json::from_str(&text).unwrap();
    let nodes = doc["nodes"].as_array().unwrap();
    let (a, b) = (
        nodes[0]["id"].as_str().unwrap(),
        nodes[1]["id"].as_str().unwrap(),
    );
    let out = swarmplan(&[
        "solve",
        "--network",
        network.to_str().unwrap(),
        "--from",
        a,
        "--to",
        b,
        "--packages",
        "0.5",
        "--route",
        "floyd-warshall",
    ]);
    assert_exit_2_with(
        &out,
        "E0029",
        &["10001 nodes", "1 GiB", "10000 nodes", "--route dijkstra"],
    );
}

#[test]
fn no_output_is_one_of_the_inputs_even_with_force() {
    // E0031: the tool never writes over what it reads.
    let network = tmp("own-input-network.json");
    std::fs::copy(repo_path("instances/tiny/flat-stop.json"), &network).unwrap();
    let network = network.to_str().unwrap();
    let before = std::fs::read(network).unwrap();
    let requests = tmp("own-input-requests.json");
    std::fs::copy(repo_path("instances/tiny/line4-requests.json"), &requests).unwrap();
    let requests = requests.to_str().unwrap();
    let cases: [&[&str]; 3] = [
        &[
            "generate",
            "requests",
            "--network",
            network,
            "--seed",
            "1",
            "-o",
            network,
            "--force",
        ],
        &[
            "batch",
            "--network",
            network,
            "--per-request",
            network,
            "--force",
        ],
        &[
            "batch",
            "--requests",
            requests,
            "--per-request",
            requests,
            "--force",
        ],
    ];
    for args in cases {
        let out = swarmplan(args);
        assert_exit_2_with(&out, "E0031", &["the output is the input"]);
    }
    assert_eq!(std::fs::read(network).unwrap(), before);
}

#[test]
fn a_hop_file_with_another_hop_index_is_not_valid() {
    // `check --hop-file` used to accept hop_index changed from 0 to 1 or 99: the file records the
    // plan it was taken from, and the request planned again has another hop there (P5609).
    let hop = tmp("hop-index.json");
    let out = swarmplan(&[
        "eaas",
        "--request-id",
        "r00001",
        "--hop",
        "0",
        "--methods",
        "pb",
        "--force",
        "--write-hop",
        hop.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = std::fs::read_to_string(&hop).unwrap();
    let check = |text: &str, name: &str| {
        let path = write_tmp(name, text.as_bytes());
        swarmplan(&["check", "--hop-file", &path])
    };
    assert_eq!(check(&text, "hop-index-0.json").status.code(), Some(0));
    for (index, words) in [
        (
            "1",
            "hop 1 of the plan (pb/location-aware/sequential) flies",
        ),
        ("99", "has 10 hop(s), not a hop 99"),
    ] {
        let changed = text.replacen("\"hop_index\": 0", &format!("\"hop_index\": {index}"), 1);
        let out = check(&changed, &format!("hop-index-{index}.json"));
        assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
        let verdict = String::from_utf8_lossy(&out.stdout);
        assert!(
            verdict.contains("[P5609] hop_index") && verdict.contains(words),
            "{verdict}"
        );
    }
}

#[test]
fn input_files_may_start_with_a_utf8_byte_order_mark() {
    // Was: E0001 at line 1 column 1 (JSON) and E5009 on an invisible `\u{feff}3` (P||Cmax).
    let bom = |name: &str, rel: &str| {
        let mut bytes = b"\xef\xbb\xbf".to_vec();
        bytes.extend(std::fs::read(repo_path(rel)).unwrap());
        write_tmp(name, &bytes)
    };
    let network = bom("bom-network.json", "instances/tiny/flat-stop.json");
    let out = swarmplan(&["inspect", "--network", &network]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let pcmax = bom(
        "bom-pcmax.txt",
        "instances/node_time/pcmax-u1-n10-m3-seed1.txt",
    );
    let out = swarmplan(&["node-time", "--instance", &pcmax, "--method", "lpt"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let profile = bom("bom-profile.toml", "instances/tiny/flat.toml");
    let flat_stop = repo_arg("instances/tiny/flat-stop.json");
    let out = solve_a_to_b(&flat_stop, &profile, &["--sharing", "none"]);
    assert!(matches!(out.status.code(), Some(0 | 1)), "{}", stderr(&out));
}

#[test]
fn a_directory_given_as_an_output_file_exits_2_with_e0010() {
    // Was: E0013 "the output file exists", then with --force "Is a directory (os error 21)".
    let dir = tmp("output-directory");
    std::fs::create_dir_all(&dir).unwrap();
    let dir = dir.to_str().unwrap();
    let roads = repo_arg("instances/import-samples/roads.geojson");
    let import = ["import", "--geojson", &roads, "--seed", "1", "-o", dir];
    let generate = [
        "generate", "network", "--nodes", "5", "--seed", "1", "-o", dir,
    ];
    let lp = [
        "node-time",
        "--pads",
        "2",
        "--times",
        "3,2",
        "--write-lp",
        dir,
    ];
    for args in [&import[..], &generate[..], &lp[..]] {
        for force in [false, true] {
            let mut args = args.to_vec();
            if force {
                args.push("--force");
            }
            let out = swarmplan(&args);
            assert_exit_2_with(&out, "E0010", &[dir, "is a directory", "path of a file"]);
            assert!(
                !stderr(&out).contains("E0013"),
                "{args:?}: {}",
                stderr(&out)
            );
        }
    }
}

#[test]
fn negative_numbers_on_the_command_line_get_their_range_errors() {
    // Was: E0007 "unexpected argument '-1' found", as if -1 were an option.
    let network = repo_arg("instances/tiny/flat-stop.json");
    let profile = repo_arg("instances/tiny/flat.toml");
    let out = swarmplan(&[
        "solve",
        "--network",
        &network,
        "--profile",
        &profile,
        "--from",
        "A",
        "--to",
        "B",
        "--packages",
        "-1,0.5",
    ]);
    assert_exit_2_with(&out, "E3302", &["--packages[0]", "-1"]);
    let out = swarmplan(&["batch", "--request-limit", "1", "--time-budget", "-1"]);
    assert_exit_2_with(&out, "E0028", &["--time-budget", "-1"]);
    let bench_dir = tmp("negative-bucket");
    let out = swarmplan(&[
        "bench",
        "--distance-bucket-km",
        "-1",
        "-o",
        bench_dir.to_str().unwrap(),
    ]);
    assert_exit_2_with(&out, "E7006", &["--distance-bucket-km", "-1"]);
    let out = swarmplan(&["node-time", "--pads", "-1", "--times", "3,2"]);
    assert_exit_2_with(&out, "E5001", &["--pads", "-1"]);
    let out = swarmplan(&["node-time", "--pads", "2", "--times", "-3,2"]);
    assert_exit_2_with(&out, "E5003", &["charge_times_min[0]", "-3"]);
}

/// The longest run of ASCII digits in `text`.
fn longest_digit_run(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

#[test]
fn huge_numbers_are_echoed_in_exponent_form() {
    // Was: 1e308 as 309 digits in the messages of --packages and --time-budget.
    let network = repo_arg("instances/tiny/flat-stop.json");
    let profile = repo_arg("instances/tiny/flat.toml");
    let x = flat_stop_with("x1e308-echo.json", r#""x_m": 2500.0"#, r#""x_m": 1e308"#);
    let cases = [
        (solve_a_to_b(&x, &profile, &["--sharing", "none"]), "E1106"),
        (
            swarmplan(&[
                "solve",
                "--network",
                &network,
                "--profile",
                &profile,
                "--from",
                "A",
                "--to",
                "B",
                "--packages",
                "1e308",
            ]),
            "E3303",
        ),
        (
            swarmplan(&["batch", "--request-limit", "1", "--time-budget", "1e308"]),
            "E0028",
        ),
        (
            swarmplan(&["node-time", "--pads", "2", "--times", "-1e300,2"]),
            "E5003",
        ),
        // Was a panic (a deadline beyond the clock's range).
        (
            swarmplan(&[
                "eaas",
                "--request-id",
                "r00001",
                "--hop",
                "0",
                "--methods",
                "milp",
                "--time-limit",
                "1e300",
            ]),
            "E4105",
        ),
    ];
    for (out, code) in cases {
        assert_exit_2_with(&out, code, &["e30"]);
        assert!(
            ["E5003", "E4105"].contains(&code) || stderr(&out).contains("1e308"),
            "{}",
            stderr(&out)
        );
        let err = stderr(&out);
        assert!(longest_digit_run(&err) < 20, "{code}: {err}");
    }
}

#[test]
fn a_full_disk_is_a_coded_error_for_files_and_for_standard_output() {
    let Ok(full) = std::fs::OpenOptions::new().write(true).open("/dev/full") else {
        return;
    };
    // A device is written to, not overwritten: no --force asked for.
    let out = swarmplan(&[
        "generate",
        "network",
        "--nodes",
        "5",
        "--seed",
        "1",
        "-o",
        "/dev/full",
    ]);
    assert_exit_2_with(&out, "E0010", &["/dev/full", "cannot write the file"]);
    // Was: "cannot write the results to stdout" without a code, exit 1.
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args(["node-time", "--pads", "2", "--times", "3,2", "--json"])
        .stdout(full)
        .output()
        .unwrap();
    assert_exit_2_with(&out, "E0010", &["standard output", "cannot write"]);
}
