//! Fuzzing in the default test run (issue 14): every input parser (network, profile, requests,
//! hop file, plan file) and the command line, over arbitrary bytes and over mutations of valid
//! files, never panics and gives either a value or coded errors. A parsed value goes on through
//! validation (and, for a valid hop, through the none, PB and FB policies; for a plan, through
//! the checker), so the numbers past the parser are fuzzed too.
//!
//! Each property tries `FUZZ_CASES` cases by default (a few seconds in release); set
//! `PROPTEST_CASES=20000` for a longer run.

mod common;

use common::{eaas_r00001, repo_path, tmp};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use std::sync::OnceLock;
use swarmplan::check::check_report;
use swarmplan::check::plan_file::parse_plan_file;
use swarmplan::eaas::hop_file::parse_hop_file;
use swarmplan::eaas::Heuristic;
use swarmplan::eaas::{simulate, SharingPolicy};
use swarmplan::error::{Error, Result};
use swarmplan::problem::io::{parse_json, parse_toml};
use swarmplan::problem::validate::validate_profile;
use swarmplan::problem::validate::{validate_network, validate_request_set};
use swarmplan::problem::SkywayGraph;
use swarmplan::problem::{Network, Profile, RequestSet};

/// Cases per property unless `PROPTEST_CASES` says otherwise.
const FUZZ_CASES: u32 = 256;

fn config() -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(FUZZ_CASES);
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// The valid files mutations start from.
struct Seeds {
    network: String,
    profile: String,
    /// The first 30 requests of the shipped paper-195 set (the whole set is 1.9 MB).
    requests: String,
    /// A hop file written by `swarmplan eaas --write-hop`.
    hop: String,
    /// The paper-195 network and graph, for the request rules and plans.
    paper_195: Network,
    graph: SkywayGraph,
    /// The paper profile.
    paper: Profile,
    /// Request r00001 of the shipped set.
    first_request: swarmplan::problem::Request,
}

fn seeds() -> &'static Seeds {
    static SEEDS: OnceLock<Seeds> = OnceLock::new();
    SEEDS.get_or_init(|| {
        let network =
            std::fs::read_to_string(repo_path("instances/paper-195/network.json")).unwrap();
        let profile = std::fs::read_to_string(repo_path("instances/profiles/paper.toml")).unwrap();
        let all = std::fs::read_to_string(repo_path("instances/paper-195/requests.json")).unwrap();
        let mut set: RequestSet = parse_json(&all, "requests").unwrap();
        set.requests.truncate(30);
        let first_request = set.requests[0].clone();
        let paper: Profile = parse_toml(&profile, "paper").unwrap();
        let requests = serde_json::to_string_pretty(&set).unwrap();
        let hop_path = tmp("hop.json");
        let out = eaas_r00001(
            "0",
            "pb",
            &["--write-hop", hop_path.to_str().unwrap(), "--force"],
        );
        assert_eq!(out.status.code(), Some(0), "{out:?}");
        let hop = std::fs::read_to_string(&hop_path).unwrap();
        let paper_195: Network = parse_json(&network, "network").unwrap();
        let graph = SkywayGraph::new(&paper_195).unwrap();
        Seeds {
            network,
            profile,
            requests,
            hop,
            paper_195,
            graph,
            paper,
            first_request,
        }
    })
}

/// `Ok`, or an error made only of coded violations (`E` and four digits, a field, a cause and
/// an action).
fn coded<T>(what: &str, r: &Result<T>) -> std::result::Result<(), TestCaseError> {
    match r {
        Ok(_) => Ok(()),
        Err(Error::Invalid(vs)) => {
            prop_assert!(!vs.is_empty(), "{what}: no violation");
            for v in vs {
                let c = v.code.as_bytes();
                prop_assert!(
                    c.len() == 5 && c[0] == b'E' && c[1..].iter().all(u8::is_ascii_digit),
                    "{what}: code {}",
                    v.code
                );
                prop_assert!(!v.cause.is_empty() && !v.action.is_empty(), "{what}: {v}");
            }
            Ok(())
        }
        Err(e) => Err(TestCaseError::fail(format!("{what}: uncoded error {e}"))),
    }
}

fn invalid_if_any(vs: Vec<swarmplan::error::Violation>) -> Result<()> {
    if vs.is_empty() {
        Ok(())
    } else {
        Err(Error::Invalid(vs))
    }
}

/// The network path: parse, validate, build the graph, then plan with the paper profile the
/// first shipped request and a request along edge `pick` (modulo the edges), where a
/// mutated number most likely matters.
fn network_along(text: &str, pick: usize) -> std::result::Result<(), TestCaseError> {
    let parsed: Result<Network> = parse_json(text, "network");
    coded("network parse", &parsed)?;
    if let Ok(n) = parsed {
        let checked = invalid_if_any(validate_network(&n));
        coded("network rules", &checked)?;
        if checked.is_ok() {
            let graph = SkywayGraph::new(&n);
            coded("network graph", &graph)?;
            if let Ok(graph) = graph {
                let paper = &seeds().paper;
                plan_request(&n, &graph, paper, &seeds().first_request)?;
                if !n.edges.is_empty() {
                    let seg = &n.edges[pick % n.edges.len()];
                    let along = swarmplan::problem::Request {
                        id: "along".into(),
                        source: seg.from.clone(),
                        destination: seg.to.clone(),
                        packages_kg: vec![1.0, 0.5],
                    };
                    plan_request(&n, &graph, paper, &along)?;
                }
            }
        }
    }
    Ok(())
}

/// The profile path: parse, validate, then plan the first shipped request on paper-195 with it.
fn profile(text: &str) -> std::result::Result<(), TestCaseError> {
    let parsed: Result<Profile> = parse_toml(text, "profile");
    coded("profile parse", &parsed)?;
    if let Ok(p) = parsed {
        let checked = invalid_if_any(validate_profile(&p));
        coded("profile rules", &checked)?;
        if checked.is_ok() {
            let s = seeds();
            plan_request(&s.paper_195, &s.graph, &p, &s.first_request)?;
        }
    }
    Ok(())
}

/// Plans `request` (when it is valid on `graph`) with FB by Algorithm 1 and PB by Dijkstra.
/// Inputs that passed validation give a plan (delivered or not, as data), never an error but
/// FB's work bound (E4015), and every number of the plan is finite.
fn plan_request(
    n: &Network,
    graph: &SkywayGraph,
    p: &Profile,
    request: &swarmplan::problem::Request,
) -> std::result::Result<(), TestCaseError> {
    use swarmplan::compose::{Context, PlanOptions, RouteMethod};
    use swarmplan::precompose::Positioning;
    if !swarmplan::problem::validate::validate_request(request, 0, graph, p.drone.max_payload_kg)
        .is_empty()
    {
        return Ok(());
    }
    let context = Context::new(n, graph, p);
    for (sharing, route) in [
        (SharingPolicy::Fb, RouteMethod::Sequential),
        (SharingPolicy::Pb, RouteMethod::Dijkstra),
    ] {
        let options = PlanOptions {
            sharing,
            positioning: Positioning::LocationAware,
            route,
            support: None,
        };
        match &context.plan(request, &options) {
            Ok(r) => {
                let plan = serde_json::to_value(&r.plan).unwrap();
                prop_assert!(
                    all_finite(&plan),
                    "{sharing:?}: a plan number is not finite"
                );
            }
            Err(Error::Invalid(vs)) if vs.iter().all(|v| v.code == "E4015") => {}
            Err(e) => {
                return Err(TestCaseError::fail(format!(
                    "{sharing:?}, {route:?}: valid input, yet {e}"
                )))
            }
        }
    }
    Ok(())
}

/// Whether every number in a JSON value is finite (serde_json writes a non-finite as null, so
/// a null where the plan has a number also fails).
fn all_finite(v: &serde_json::Value) -> bool {
    match v {
        serde_json::Value::Number(x) => x.as_f64().is_some_and(f64::is_finite),
        serde_json::Value::Array(a) => a.iter().all(all_finite),
        serde_json::Value::Object(o) => o.values().all(all_finite),
        _ => true,
    }
}

/// The request path: parse, validate against paper-195 at the paper's max payload.
fn requests(text: &str) -> std::result::Result<(), TestCaseError> {
    let parsed: Result<RequestSet> = parse_json(text, "requests");
    coded("requests parse", &parsed)?;
    if let Ok(set) = parsed {
        let vs = validate_request_set(&set, &seeds().graph, 1.4);
        coded("request rules", &invalid_if_any(vs))?;
    }
    Ok(())
}

/// The hop file path: parse and check, then fly the hop under none, PB and FB.
fn hop(text: &str) -> std::result::Result<(), TestCaseError> {
    let parsed = parse_hop_file(text, "hop");
    coded("hop file", &parsed)?;
    if let Ok(file) = parsed {
        for policy in [Heuristic::None, Heuristic::Pb, Heuristic::Fb] {
            coded("hop policy", &simulate(&file.hop, policy))?;
        }
    }
    Ok(())
}

/// Values that break parsers and arithmetic.
const NASTY: &[&str] = &[
    "0",
    "-0",
    "-1",
    "1e308",
    "-1e308",
    "1e200",
    "1e-300",
    "5e-324",
    "0.01",
    "4294967295",
    "4294967296",
    "18446744073709551615",
    "18446744073709551616",
    "9223372036854775807",
    "-9223372036854775808",
    "1e999",
    "NaN",
    "nan",
    "inf",
    "-inf",
    "\"x\"",
    "null",
    "[]",
    "{}",
    "true",
    "65",
    "1001",
    "360",
    "13.8",
];

#[derive(Debug, Clone)]
enum Mutation {
    /// Replace the number at the n-th run of digits with a nasty value.
    Number(usize, usize),
    /// Replace the byte at a position.
    Byte(usize, u8),
    /// Insert a byte at a position.
    Insert(usize, u8),
    /// Delete bytes from a position.
    Delete(usize, usize),
    /// Copy a slice to another position.
    Splice(usize, usize, usize),
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<usize>(), 0..NASTY.len()).prop_map(|(i, v)| Mutation::Number(i, v)),
        2 => (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::Byte(i, b)),
        1 => (any::<usize>(), any::<u8>()).prop_map(|(i, b)| Mutation::Insert(i, b)),
        1 => (any::<usize>(), 1usize..64).prop_map(|(i, n)| Mutation::Delete(i, n)),
        1 => (any::<usize>(), 1usize..200, any::<usize>())
            .prop_map(|(a, n, b)| Mutation::Splice(a, n, b)),
    ]
}

/// Byte ranges of the numbers in `text` (a digit, optionally after `-`, then number characters).
fn numbers(text: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < text.len() {
        if text[i].is_ascii_digit() {
            let start = if i > 0 && text[i - 1] == b'-' {
                i - 1
            } else {
                i
            };
            let mut end = i;
            while end < text.len() && (text[end].is_ascii_digit() || b".eE+-".contains(&text[end]))
            {
                end += 1;
            }
            out.push((start, end));
            i = end;
        } else {
            i += 1;
        }
    }
    out
}

fn mutate(seed: &str, ms: &[Mutation]) -> Vec<u8> {
    let mut b = seed.as_bytes().to_vec();
    for m in ms {
        let len = b.len().max(1);
        match *m {
            Mutation::Number(i, v) => {
                let nums = numbers(&b);
                if !nums.is_empty() {
                    let (s, e) = nums[i % nums.len()];
                    b.splice(s..e, NASTY[v].bytes());
                }
            }
            Mutation::Byte(i, x) => {
                if !b.is_empty() {
                    let i = i % b.len();
                    b[i] = x;
                }
            }
            Mutation::Insert(i, x) => b.insert(i % (b.len() + 1), x),
            Mutation::Delete(i, n) => {
                let i = i % len;
                let end = (i + n).min(b.len());
                if i < end {
                    b.drain(i..end);
                }
            }
            Mutation::Splice(a, n, at) => {
                let a = a % len;
                let end = (a + n).min(b.len());
                if a < end {
                    let piece = b[a..end].to_vec();
                    let at = at % (b.len() + 1);
                    b.splice(at..at, piece);
                }
            }
        }
    }
    b
}

/// Runs `check` on the bytes as text: as they are when UTF-8, else with every bad byte replaced
/// (such bytes are E0009 at the file reader, fuzzed in
/// `arbitrary_bytes_in_a_file_are_read_or_coded`).
fn on_text(
    bytes: &[u8],
    check: fn(&str) -> std::result::Result<(), TestCaseError>,
) -> std::result::Result<(), TestCaseError> {
    match std::str::from_utf8(bytes) {
        Ok(text) => check(text),
        Err(_) => check(&String::from_utf8_lossy(bytes)),
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn every_parser_gives_a_value_or_coded_errors_on_arbitrary_bytes(
        bytes in proptest::collection::vec(any::<u8>(), 0..400)
    ) {
        on_text(&bytes, |t| network_along(t, 0))?;
        on_text(&bytes, profile)?;
        on_text(&bytes, requests)?;
        on_text(&bytes, hop)?;
    }

    #[test]
    fn mutated_networks_give_a_value_or_coded_errors(
        ms in proptest::collection::vec(mutation(), 1..6),
        pick in any::<usize>(),
    ) {
        let bytes = mutate(&seeds().network, &ms);
        network_along(&String::from_utf8_lossy(&bytes), pick)?;
    }

    #[test]
    fn mutated_profiles_give_a_value_or_coded_errors(
        ms in proptest::collection::vec(mutation(), 1..6)
    ) {
        on_text(&mutate(&seeds().profile, &ms), profile)?;
    }

    #[test]
    fn mutated_request_sets_give_a_value_or_coded_errors(
        ms in proptest::collection::vec(mutation(), 1..6)
    ) {
        on_text(&mutate(&seeds().requests, &ms), requests)?;
    }

    #[test]
    fn mutated_hop_files_give_a_value_or_coded_errors(
        ms in proptest::collection::vec(mutation(), 1..6)
    ) {
        on_text(&mutate(&seeds().hop, &ms), hop)?;
    }

    #[test]
    fn arbitrary_bytes_in_a_file_are_read_or_coded(
        bytes in proptest::collection::vec(any::<u8>(), 0..64)
    ) {
        let path = tmp("bytes.bin");
        std::fs::write(&path, &bytes).unwrap();
        let r = swarmplan::problem::io::read_text(&path);
        coded("read_text", &r)?;
        prop_assert_eq!(r.is_ok(), std::str::from_utf8(&bytes).is_ok());
    }

    #[test]
    fn arbitrary_command_lines_parse_or_give_coded_usage_errors(
        args in proptest::collection::vec(token(), 0..8)
    ) {
        use clap::Parser;
        let argv = std::iter::once("swarmplan".to_string()).chain(args);
        if let Err(e) = swarmplan::cli::Cli::try_parse_from(argv) {
            let help_only =
                e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand;
            match swarmplan::cli::coded_usage_error(&e) {
                // A command given alone: its help, as `--help` prints it (exit 2).
                Some(message) if help_only => prop_assert!(message.contains("Usage:"), "{message}"),
                Some(message) => prop_assert!(message.contains("[E"), "{message}"),
                None => prop_assert!(!e.use_stderr()),
            }
        }
    }
}

/// Command-line tokens: subcommands, flags of every subcommand, values good and bad.
fn token() -> impl Strategy<Value = String> {
    const TOKENS: &[&str] = &[
        "solve",
        "batch",
        "inspect",
        "node-time",
        "eaas",
        "generate",
        "network",
        "requests",
        "help",
        "--help",
        "-h",
        "--version",
        "-V",
        "--json",
        "--request-id",
        "r00001",
        "--from",
        "--to",
        "n000",
        "n194",
        "--packages",
        "1.2,0.8",
        "--sharing",
        "pb",
        "fb",
        "none",
        "exact",
        "fair",
        "idle-support",
        "--route",
        "astar",
        "dijkstra",
        "sequential",
        "--positioning",
        "energy-aware",
        "--support",
        "--pads",
        "--times",
        "60,50,40",
        "--method",
        "milp",
        "lpt",
        "brute",
        "--backend",
        "microlp",
        "highs",
        "--time-limit",
        "--limit",
        "--threads",
        "--all",
        "--literal",
        "--hop",
        "--methods",
        "--period-min",
        "--reorder",
        "free",
        "--nodes",
        "--seed",
        "--count",
        "-o",
        "--spacing-m",
        "--max-package-kg",
        "--network",
        "--profile",
        "--requests",
        "--hop-file",
        "--file",
        "--write-hop",
        "--write-lp",
        "--per-request",
        "--hop-time-limit",
        "0",
        "-1",
        "3",
        "1e308",
        "NaN",
        "18446744073709551615",
        "",
        "=",
        "--",
        "-",
        "\u{fffd}",
        "--x=y",
    ];
    prop_oneof![
        8 => proptest::sample::select(TOKENS).prop_map(str::to_string),
        1 => "[ -~]{0,12}",
    ]
}

/// A plan document as `swarmplan solve --json` prints it: request r00023 under PB, Algorithm 1
/// (two stops, a transfer with a slot swap), with the request set it comes from.
struct PlanSeed {
    text: String,
    requests: Vec<swarmplan::problem::Request>,
}

fn plan_seed() -> &'static PlanSeed {
    static SEED: OnceLock<PlanSeed> = OnceLock::new();
    SEED.get_or_init(|| {
        use swarmplan::compose::{Context, PlanOptions, RouteMethod};
        let s = seeds();
        let set: RequestSet = parse_json(&s.requests, "requests").unwrap();
        let request = set.requests.iter().find(|r| r.id == "r00023").unwrap();
        let options = PlanOptions {
            sharing: SharingPolicy::Pb,
            positioning: swarmplan::precompose::Positioning::LocationAware,
            route: RouteMethod::Sequential,
            support: None,
        };
        let report = Context::new(&s.paper_195, &s.graph, &s.paper)
            .plan(request, &options)
            .unwrap();
        PlanSeed {
            text: serde_json::to_string_pretty(&report).unwrap(),
            requests: set.requests,
        }
    })
}

/// The plan path of `swarmplan check`: read the document (a value or coded errors), then check
/// it against paper-195 (violations are data, never a panic: checker codes, or the codes of a
/// plan made on another instance).
fn plan_file(text: &str) -> std::result::Result<(), TestCaseError> {
    let parsed = parse_plan_file(text, "plan");
    coded("plan file", &parsed)?;
    if let Ok(report) = parsed {
        let s = seeds();
        let violations = check_report(&s.paper_195, &s.paper, &plan_seed().requests, &report);
        // A mutated fingerprint reads as a plan made on another instance (E6004, E6005).
        for v in violations {
            prop_assert!(
                v.code.starts_with('P') || v.code == "E6004" || v.code == "E6005",
                "{v}"
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn mutated_plan_files_give_coded_errors_or_a_check_result(
        ms in proptest::collection::vec(mutation(), 1..6)
    ) {
        on_text(&mutate(&plan_seed().text, &ms), plan_file)?;
    }

    #[test]
    fn arbitrary_bytes_as_a_plan_file_give_coded_errors(
        bytes in proptest::collection::vec(any::<u8>(), 0..400)
    ) {
        on_text(&bytes, plan_file)?;
    }
}
