//! `check` verifies every number a plan states (`models/plan_file.md`): for plans of every
//! method combination (sharing x route, the exact ones included, with and without `--gap`,
//! delivered and failed), every numeric field is changed in turn (`x 1.5 + 3`, or `+ 7` for a
//! whole number) and the changed document must be rejected with a violation naming that field;
//! the untouched document must pass. The only numbers not checked are the measurement
//! `execution_ms` and the `settings` the plan was made with (the user's choices, which the
//! check's re-run reads; a changed limit the search does not reach changes nothing).

mod common;

use common::paper_195;
use serde_json::Value;
use swarmplan::check::bench_rows::check_bench_rows;
use swarmplan::check::check_report;
use swarmplan::check::hop_file::check_hop_file;
use swarmplan::check::node_time::check_node_time;
use swarmplan::check::plan_file::parse_plan_file;
use swarmplan::compose::{Context, HopPaths, PlanOptions, RequestReport, RouteMethod};
use swarmplan::eaas::hop_file::{HopFile, HOP_FILE_SCHEMA_VERSION};
use swarmplan::eaas::SharingPolicy;
use swarmplan::error::Violation;
use swarmplan::precompose::Positioning;
use swarmplan::problem::io::{read_json, read_toml};
use swarmplan::problem::{Network, Profile, Request, RequestSet, SkywayGraph};

/// Fields not checked: a measurement, and the settings the re-run uses.
fn not_checked(path: &str) -> bool {
    path == "execution_ms" || path.starts_with("settings.")
}

/// Every numeric leaf of `value` with its path (`plan.hops[2].legs[0].tt_min`).
fn numeric_leaves(value: &Value, path: String, out: &mut Vec<String>) {
    leaves_where(value, path, &|v| v.is_number(), out);
}

/// Every leaf of `value` that `keep` keeps, with its path.
fn leaves_where(value: &Value, path: String, keep: &dyn Fn(&Value) -> bool, out: &mut Vec<String>) {
    match value {
        Value::Object(m) => {
            for (k, v) in m {
                let p = if path.is_empty() {
                    k.clone()
                } else {
                    format!("{path}.{k}")
                };
                leaves_where(v, p, keep, out);
            }
        }
        Value::Array(a) => {
            for (i, v) in a.iter().enumerate() {
                leaves_where(v, format!("{path}[{i}]"), keep, out);
            }
        }
        leaf if keep(leaf) => out.push(path),
        _ => {}
    }
}

/// The leaf at `path`, mutable.
fn leaf<'v>(value: &'v mut Value, path: &str) -> &'v mut Value {
    let mut at = value;
    for part in path.split('.') {
        let (key, indices) = part
            .split_once('[')
            .map_or((part, ""), |(k, rest)| (k, rest));
        if !key.is_empty() {
            at = &mut at[key];
        }
        for index in indices.split('[').filter(|s| !s.is_empty()) {
            at = &mut at[index.trim_end_matches(']').parse::<usize>().unwrap()];
        }
    }
    at
}

/// The path with its indices as `[]`: the field's name in the schema.
fn pattern(path: &str) -> String {
    let mut out = String::new();
    let mut in_index = false;
    for c in path.chars() {
        match c {
            '[' => {
                in_index = true;
                out.push_str("[]");
            }
            ']' => in_index = false,
            _ if in_index => {}
            _ => out.push(c),
        }
    }
    out
}

/// Whether a violation's `field` names `path`: the same field (the plan checker's fields are
/// relative to the plan), the whole list `path` is an element of, or the transfer `path` is a
/// number of (a transfer is one decision, re-checked as a whole).
fn names(field: &str, path: &str) -> bool {
    [field.to_string(), format!("plan.{field}")]
        .iter()
        .any(|f| {
            f == path
                || path.strip_prefix(f.as_str()).is_some_and(|rest| {
                    rest.starts_with('[')
                        || (f.contains(".transfers[")
                            && f.ends_with(']')
                            && !rest[1..].contains('.'))
                })
        })
}

struct Case {
    what: String,
    network: Network,
    profile: Profile,
    requests: Vec<Request>,
    report: RequestReport,
}

/// An instance: network, its graph, profile, request set.
type On<'a> = (&'a Network, &'a SkywayGraph, &'a Profile, &'a [Request]);

fn plan_case(
    (network, graph, profile, requests): On,
    id: &str,
    options: PlanOptions,
    gap: bool,
    hop_paths: HopPaths,
) -> Case {
    let mut context = Context::new(network, graph, profile);
    context.hop_paths = hop_paths;
    let request = requests.iter().find(|r| r.id == id).unwrap();
    let mut report = context.plan(request, &options).unwrap();
    if gap {
        report.route_gap = Some(context.route_gap(request, &report).unwrap());
    }
    Case {
        what: format!(
            "{id} {:?}/{:?}/{:?}{}{}",
            options.sharing,
            options.positioning,
            options.route,
            if gap { " --gap" } else { "" },
            if hop_paths == HopPaths::Any {
                " --hop-paths any"
            } else {
                ""
            }
        ),
        network: network.clone(),
        profile: profile.clone(),
        requests: requests.to_vec(),
        report,
    }
}

/// The findings instance (findings-195, `paper-findings`), where requests stop, share and fail.
fn findings() -> (Network, SkywayGraph, Profile, Vec<Request>) {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let network: Network = read_json(&root.join("instances/findings-195/network.json")).unwrap();
    let profile: Profile = read_toml(&root.join("instances/profiles/paper-findings.toml")).unwrap();
    let requests: RequestSet = read_json(&root.join("instances/paper-195/requests.json")).unwrap();
    let graph = SkywayGraph::new(&network).unwrap();
    (network, graph, profile, requests.requests)
}

fn cases() -> Vec<Case> {
    let mut out = Vec::new();
    let (network, graph, profile, requests) = findings();
    let case = |id: &str, options: PlanOptions, gap: bool| {
        plan_case(
            (&network, &graph, &profile, &requests),
            id,
            options,
            gap,
            HopPaths::Rule,
        )
    };
    let sharing = [
        SharingPolicy::None,
        SharingPolicy::IdleSupport,
        SharingPolicy::Pb,
        SharingPolicy::Fb,
        SharingPolicy::Exact,
        SharingPolicy::Fair,
    ];
    let routes = [
        RouteMethod::Sequential,
        RouteMethod::Astar,
        RouteMethod::Dijkstra,
        RouteMethod::FloydWarshall,
        RouteMethod::Optimal,
    ];
    for (i, &s) in sharing.iter().enumerate() {
        for (j, &route) in routes.iter().enumerate() {
            if s == SharingPolicy::Fair && route == RouteMethod::Optimal {
                continue;
            }
            let positioning = if (i + j) % 2 == 0 {
                Positioning::LocationAware
            } else {
                Positioning::EnergyAware
            };
            let options = PlanOptions {
                sharing: s,
                positioning,
                route,
                support: None,
            };
            // r00001 stops on the way (9 hops under FB, sequential) and shares under FB and
            // exact.
            out.push(case("r00001", options, false));
        }
    }
    for s in [SharingPolicy::Fb, SharingPolicy::Exact] {
        let options = PlanOptions {
            sharing: s,
            positioning: Positioning::LocationAware,
            route: RouteMethod::Sequential,
            support: Some(2),
        };
        out.push(case("r00001", options, true));
    }
    // The optimal route over every flyable hop path, and a gap against it.
    let options = PlanOptions {
        sharing: SharingPolicy::None,
        positioning: Positioning::LocationAware,
        route: RouteMethod::Sequential,
        support: None,
    };
    out.push(plan_case(
        (&network, &graph, &profile, &requests),
        "r00001",
        options,
        true,
        HopPaths::Any,
    ));
    out.push(plan_case(
        (&network, &graph, &profile, &requests),
        "r00001",
        PlanOptions {
            route: RouteMethod::Optimal,
            ..options
        },
        false,
        HopPaths::Any,
    ));
    // `solve --swarm best`: the best swarm's optimum, every swarm's in `swarms_compared`.
    let mut best = case(
        "r00001",
        PlanOptions {
            sharing: SharingPolicy::Exact,
            positioning: Positioning::LocationAware,
            route: RouteMethod::Optimal,
            support: None,
        },
        false,
    );
    let context = Context::new(&network, &graph, &profile);
    let request = requests.iter().find(|r| r.id == "r00001").unwrap();
    best.report = context
        .plan_best_swarm(request, &best.report.options)
        .unwrap();
    best.what.push_str(" --swarm best");
    assert!(best.report.swarms_compared.is_some());
    out.push(best);
    // Failed plans: a dead end under Algorithm 1, a hop out of reach on a fixed route.
    for (s, route) in [
        (SharingPolicy::None, RouteMethod::Sequential),
        (SharingPolicy::Pb, RouteMethod::Sequential),
        (SharingPolicy::None, RouteMethod::Dijkstra),
    ] {
        let options = PlanOptions {
            sharing: s,
            positioning: Positioning::LocationAware,
            route,
            support: None,
        };
        let failed = case("r00002", options, false);
        assert!(!failed.report.plan.delivered(), "{} fails", failed.what);
        out.push(failed);
    }
    // A swap: PB on the fast-sharing profile moves a consumer into the support drone's range.
    let (network, graph, _, requests) = paper_195();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let fast: Profile = read_toml(&root.join("instances/profiles/fast-sharing.toml")).unwrap();
    let options = PlanOptions {
        sharing: SharingPolicy::Pb,
        positioning: Positioning::LocationAware,
        route: RouteMethod::Sequential,
        support: None,
    };
    out.push(plan_case(
        (&network, &graph, &fast, &requests),
        "r00001",
        options,
        false,
        HopPaths::Rule,
    ));
    out
}

/// What changing the numbers of one document gave.
#[derive(Default)]
struct Tally {
    changed: usize,
    /// The fields changed (paths with `[]` for indices).
    fields: std::collections::BTreeSet<String>,
    /// Changes not rejected by a violation naming the field.
    missed: Vec<String>,
}

impl Tally {
    /// Changes every numeric field of `document` but those `not_checked`, at its first, middle
    /// and last place, and runs `check` on each changed document: a violation must name the
    /// field, or the reader must refuse the document naming `read_field` when that field
    /// changed.
    fn change_every_number(
        &mut self,
        what: &str,
        document: &Value,
        not_checked: impl Fn(&str) -> bool,
        read_field: &str,
        check: impl Fn(&Value) -> Result<Vec<Violation>, String>,
    ) {
        let untouched = check(document).unwrap();
        assert!(untouched.is_empty(), "{what}: {untouched:?}");
        let mut leaves = Vec::new();
        numeric_leaves(document, String::new(), &mut leaves);
        let mut by_pattern: std::collections::BTreeMap<String, Vec<String>> = Default::default();
        for path in leaves.into_iter().filter(|p| !not_checked(p)) {
            by_pattern.entry(pattern(&path)).or_default().push(path);
        }
        for (field, paths) in &by_pattern {
            let mut picks = vec![&paths[0], &paths[paths.len() / 2], &paths[paths.len() - 1]];
            picks.dedup();
            for path in picks {
                let mut doc = document.clone();
                let at = leaf(&mut doc, path);
                *at = match (at.as_u64(), at.as_i64(), at.as_f64()) {
                    (Some(n), _, _) => Value::from(n + 7),
                    (None, Some(n), _) => Value::from(n + 7),
                    (_, _, Some(x)) => Value::from(x * 1.5 + 3.0),
                    _ => unreachable!("a numeric leaf"),
                };
                self.changed += 1;
                self.fields.insert(field.clone());
                match check(&doc) {
                    // The reader refuses a document of another version, naming the field.
                    Err(e) if path == read_field && e.contains(read_field) => {}
                    Err(e) => self.missed.push(format!("{what}: {path}: not read: {e}")),
                    Ok(found) if found.iter().any(|v| names(&v.field, path)) => {}
                    Ok(found) => self.missed.push(format!(
                        "{what}: {path}: {}",
                        if found.is_empty() {
                            "accepted".to_string()
                        } else {
                            found
                                .iter()
                                .map(|v| format!("{} {}", v.code, v.field))
                                .collect::<Vec<_>>()
                                .join(", ")
                        }
                    )),
                }
            }
        }
    }

    /// Asserts every change was rejected and every field in `expected` was changed somewhere.
    fn assert_all_rejected(&self, expected: &[&str]) {
        assert!(
            self.missed.is_empty(),
            "{} of {} changes not rejected by their field:\n{}",
            self.missed.len(),
            self.changed,
            self.missed.join("\n")
        );
        for field in expected {
            assert!(self.fields.contains(*field), "no document states {field}");
        }
    }
}

/// Every numeric field of every plan, changed in turn, is rejected with a violation naming it;
/// the untouched plans pass. A field listed many times (a hop's legs, batteries) is changed at
/// its first, middle and last place.
#[test]
fn every_changed_number_is_rejected_by_its_field() {
    let mut tally = Tally::default();
    for case in cases() {
        let check = |doc: &Value| -> Result<Vec<Violation>, String> {
            let report = parse_plan_file(&doc.to_string(), "plan").map_err(|e| e.to_string())?;
            Ok(check_report(
                &case.network,
                &case.profile,
                &case.requests,
                &report,
            ))
        };
        let document = serde_json::to_value(&case.report).unwrap();
        tally.change_every_number(&case.what, &document, not_checked, "schema_version", check);
    }
    // The plans exercise the fields a reader meets: stops, transfers, exact solves, gaps,
    // failures.
    tally.assert_all_rejected(&[
        "plan.hops[].stop.charge_times_min[]",
        "plan.hops[].transfers[].energy_mah",
        "plan.hops[].sharing_solve.bound",
        "plan.route_optimality.arcs_total",
        "plan.route_optimality.hop_path_labels",
        "route_gap.optimal_dt_min",
        "plan.outcome.direct.time_min",
        "plan.outcome.failure.time_min",
        "support_decision.probability_pct",
    ]);
}

/// Every number of hop files (hops of a plan with a stop, sharing, and into the destination),
/// changed in turn, is rejected by `check --hop-file`'s rules naming it; `hop_index` too (the
/// file records the plan it was taken from, P5609).
#[test]
fn every_changed_number_of_a_hop_file_is_rejected() {
    let (network, graph, profile, requests) = findings();
    let context = Context::new(&network, &graph, &profile);
    let request = requests.iter().find(|r| r.id == "r00001").unwrap();
    let options = PlanOptions {
        sharing: SharingPolicy::Fb,
        positioning: Positioning::LocationAware,
        route: RouteMethod::Sequential,
        support: None,
    };
    let report = context.plan(request, &options).unwrap();
    let last = report.plan.hops.len() - 1;
    assert!(last >= 2, "r00001 stops on the way");
    let mut tally = Tally::default();
    for index in [0, last / 2, last] {
        let file = context
            .hop_file_of(&report, index, "paper-findings")
            .unwrap();
        let document = serde_json::to_value(&file).unwrap();
        let check = |doc: &Value| -> Result<Vec<Violation>, String> {
            let file: HopFile = serde_json::from_value(doc.clone()).map_err(|e| e.to_string())?;
            if file.schema_version != HOP_FILE_SCHEMA_VERSION {
                return Err(format!("schema_version {}", file.schema_version));
            }
            Ok(check_hop_file(&network, &profile, &requests, &file))
        };
        tally.change_every_number(
            &format!("hop {index}"),
            &document,
            |_| false,
            "schema_version",
            check,
        );
    }
    tally.assert_all_rejected(&[
        "hop.legs[].duration_min",
        "hop.legs[].rate_mah_per_min[][]",
        "hop.drones[].battery_mah",
        "hop.slots_m[][]",
        "hop.initial_slot[]",
        "hop.rho_mah_per_min",
        "end.pads",
        "hop_index",
    ]);
}

/// Every number of node-time results of every method (an optimum, and a search stopped by its
/// node limit with a bound), changed in turn, is rejected by `check --node-time`'s rules naming
/// it, the instance given; `solve_ms` is a measurement.
#[test]
fn every_changed_number_of_a_node_time_result_is_rejected() {
    use swarmplan::node_time::{self, Limits, NodeTimeMethod, NodeTimeReport};
    use swarmplan::solver::{MilpBackend, SolveStatus};
    // The paper's example, and 12 drones on 4 pads (the search stops after one node).
    let small = (3usize, vec![60.0, 50.0, 40.0, 30.0, 20.0]);
    let times: Vec<f64> = (0..12)
        .map(|j| 11.0 + ((j * 37) % 23) as f64 * 1.7)
        .collect();
    let large = (4usize, times);
    let mut tally = Tally::default();
    let mut stopped = 0;
    for (pads, times) in [&small, &large] {
        for method in [
            NodeTimeMethod::Exact,
            NodeTimeMethod::Milp,
            NodeTimeMethod::Lpt,
            NodeTimeMethod::Brute,
        ] {
            let large = times.len() > 8;
            if large && matches!(method, NodeTimeMethod::Brute | NodeTimeMethod::Milp) {
                continue;
            }
            let limits = Limits {
                time_limit_s: None,
                node_limit: large.then_some(1),
            };
            let solution =
                node_time::solve(method, MilpBackend::default(), *pads, times, &limits).unwrap();
            stopped += usize::from(
                method == NodeTimeMethod::Exact
                    && solution.status == SolveStatus::Feasible
                    && solution.lower_bound_min < solution.makespan_min,
            );
            let report = NodeTimeReport::new(*pads, times, solution);
            let document = serde_json::to_value(&report).unwrap();
            let check = |doc: &Value| -> Result<Vec<Violation>, String> {
                let report: NodeTimeReport =
                    serde_json::from_value(doc.clone()).map_err(|e| e.to_string())?;
                Ok(check_node_time(&report, Some((*pads, times))))
            };
            tally.change_every_number(
                &format!("{method:?} on {} drones", times.len()),
                &document,
                |p| p == "solve_ms",
                "",
                check,
            );
        }
    }
    assert_eq!(
        stopped, 1,
        "the exact search stopped by its node limit, with a gap"
    );
    tally.assert_all_rejected(&[
        "pads",
        "charge_times_min[]",
        "makespan_min",
        "lower_bound_min",
        "assignment[][]",
        "gap.relative",
    ]);
}

/// Every number of the rows of a bench run (`--joint`: route gaps and the gap split included;
/// the exact subset: `hops.csv` and `stops.csv`), changed in turn in the rows of its first
/// request in every table, is rejected by `check --bench`'s rules naming the table, the row and
/// the column.
#[test]
fn every_changed_number_of_a_bench_row_is_rejected() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("check_bench_rows");
    let _ = std::fs::remove_dir_all(&dir);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args([
            "bench",
            "--request-limit",
            "2",
            "--joint",
            "--exact-limit",
            "1",
            "--out",
        ])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let (config, data) = swarmplan::bench::read_data(&dir).unwrap();
    let (network, _, profile, requests) = findings();
    let requests = &requests[..config.limit];
    let of_first = |rows: Value| -> Value {
        Value::Array(
            rows.as_array()
                .unwrap()
                .iter()
                .filter(|r| r["request_index"] == 0)
                .cloned()
                .collect(),
        )
    };
    let document = serde_json::json!({
        "requests": of_first(serde_json::to_value(&data.requests).unwrap()),
        "hops": of_first(serde_json::to_value(&data.hops).unwrap()),
        "stops": of_first(serde_json::to_value(&data.stops).unwrap()),
        "joint": of_first(serde_json::to_value(&data.joint).unwrap()),
    });
    for table in ["requests", "hops", "stops", "joint"] {
        assert!(
            document[table].as_array().unwrap().len() >= 3,
            "{table}: the first request has rows"
        );
    }
    let tables = |doc: &Value| -> Result<swarmplan::bench::BenchData, String> {
        let rows = |t: &str| doc[t].clone();
        Ok(swarmplan::bench::BenchData {
            requests: serde_json::from_value(rows("requests")).map_err(|e| e.to_string())?,
            hops: serde_json::from_value(rows("hops")).map_err(|e| e.to_string())?,
            stops: serde_json::from_value(rows("stops")).map_err(|e| e.to_string())?,
            timings: Vec::new(),
            joint: serde_json::from_value(rows("joint")).map_err(|e| e.to_string())?,
        })
    };
    let check = |doc: &Value| -> Result<Vec<Violation>, String> {
        let found = check_bench_rows(&network, &profile, requests, &config, &tables(doc)?, 1)
            .map_err(|e| e.to_string())?;
        assert!(found.skipped.is_none());
        Ok(found
            .violations
            .into_iter()
            .map(|mut v| {
                v.field = v.field.replacen(".csv", "", 1);
                v
            })
            .collect())
    };
    let mut tally = Tally::default();
    tally.change_every_number("rows of r00000", &document, |_| false, "", check);
    tally.assert_all_rejected(&[
        "requests[].distance_m",
        "requests[].dt_min",
        "requests[].lpt_gap_sum",
        "requests[].optimal_dt_min",
        "requests[].route_gap",
        "requests[].joint_dt_min",
        "requests[].gap_route_min",
        "requests[].split_epsilon_min",
        "hops[].continuous",
        "hops[].fluid_bound",
        "hops[].gap",
        "stops[].nt_min",
        "stops[].lpt_nt_min",
        "joint[].dt_min",
        "joint[].arcs_flown",
    ]);
    let first = tables(&document).unwrap();
    // A row deleted, or one written twice: P5705 names the request and the combination.
    let codes = |data: &swarmplan::bench::BenchData| -> Vec<String> {
        check_bench_rows(&network, &profile, requests, &config, data, 1)
            .unwrap()
            .violations
            .iter()
            .map(|v| v.code.to_string())
            .collect()
    };
    assert!(codes(&first).is_empty(), "{:?}", codes(&first));
    let mut fewer = first.clone();
    fewer.requests.remove(3);
    assert_eq!(codes(&fewer), ["P5705"]);
    let mut more = first.clone();
    more.requests.insert(3, first.requests[3].clone());
    assert!(
        codes(&more).contains(&"P5705".to_string()),
        "{:?}",
        codes(&more)
    );
    // The same in the other tables: the first code names the count.
    for table in ["hops", "stops", "joint"] {
        let mut fewer = first.clone();
        let mut more = first.clone();
        match table {
            "hops" => {
                fewer.hops.pop();
                more.hops.push(first.hops[0].clone());
            }
            "stops" => {
                fewer.stops.pop();
                more.stops.push(first.stops[0].clone());
            }
            _ => {
                fewer.joint.pop();
                more.joint.push(first.joint[0].clone());
            }
        }
        assert_eq!(codes(&fewer), ["P5705"], "{table}: a row deleted");
        assert_eq!(
            codes(&more).first().map(String::as_str),
            Some("P5705"),
            "{table}"
        );
    }
    // A row of a request requests.csv does not have.
    let mut stray = first.clone();
    let mut row = first.stops[0].clone();
    row.request_index = 1;
    stray.stops.push(row);
    assert_eq!(codes(&stray), ["P5705"]);
}

/// The documents of the property below, each with its check (a parse error or a violation is
/// "not valid") and the leaves it does not check: measurements, the settings a re-run reads,
/// labels.
struct Documents {
    docs: Vec<(String, Value, Vec<String>)>,
    network: Network,
    profile: Profile,
    requests: Vec<Request>,
}

impl Documents {
    fn new() -> Documents {
        use swarmplan::node_time::{self, Limits, NodeTimeMethod, NodeTimeReport};
        let (network, graph, profile, requests) = findings();
        let context = Context::new(&network, &graph, &profile);
        let request = requests.iter().find(|r| r.id == "r00001").unwrap();
        let options = PlanOptions {
            sharing: SharingPolicy::Pb,
            positioning: Positioning::LocationAware,
            route: RouteMethod::Sequential,
            support: None,
        };
        let report = context.plan(request, &options).unwrap();
        let hop = context.hop_file_of(&report, 1, "paper-findings").unwrap();
        let times = [60.0, 50.0, 40.0, 30.0, 20.0];
        let solution = node_time::solve(
            NodeTimeMethod::Exact,
            swarmplan::solver::MilpBackend::default(),
            3,
            &times,
            &Limits::default(),
        )
        .unwrap();
        let node_time = NodeTimeReport::new(3, &times, solution);
        let leaves = |v: &Value| {
            let mut out = Vec::new();
            leaves_where(v, String::new(), &|l| !l.is_null(), &mut out);
            out
        };
        let docs = [
            ("plan", serde_json::to_value(&report).unwrap()),
            ("hop file", serde_json::to_value(&hop).unwrap()),
            (
                "node-time result",
                serde_json::to_value(&node_time).unwrap(),
            ),
        ]
        .into_iter()
        .map(|(what, doc)| {
            let checked: Vec<String> = leaves(&doc)
                .into_iter()
                .filter(|p| {
                    !(not_checked(p)
                        || p == "solve_ms"
                        || (what == "hop file" && p == "profile")
                        || (what == "node-time result" && p == "method"))
                })
                .collect();
            (what.to_string(), doc, checked)
        })
        .collect();
        Documents {
            docs,
            network,
            profile,
            requests,
        }
    }

    /// Whether `doc`, the `k`-th document changed, is called valid by its check.
    fn valid(&self, k: usize, doc: &Value) -> bool {
        use swarmplan::node_time::NodeTimeReport;
        match self.docs[k].0.as_str() {
            "plan" => parse_plan_file(&doc.to_string(), "plan").is_ok_and(|report| {
                check_report(&self.network, &self.profile, &self.requests, &report).is_empty()
            }),
            "hop file" => serde_json::from_value::<HopFile>(doc.clone()).is_ok_and(|file| {
                file.violations().is_empty()
                    && check_hop_file(&self.network, &self.profile, &self.requests, &file)
                        .is_empty()
            }),
            _ => serde_json::from_value::<NodeTimeReport>(doc.clone()).is_ok_and(|r| {
                check_node_time(&r, Some((3, &[60.0, 50.0, 40.0, 30.0, 20.0]))).is_empty()
            }),
        }
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(192))]

    /// A plan, a hop file and a node-time result changed at any checked leaf (a number scaled
    /// by a factor at least 0.1% away from 1 and shifted, a whole number moved by 1 to 9, a
    /// bool flipped, a string lengthened) are never called valid; the untouched ones are.
    #[test]
    fn a_document_changed_anywhere_is_never_called_valid(
        kind in 0usize..3,
        at in proptest::prelude::any::<proptest::sample::Index>(),
        factor in proptest::prop_oneof![0.05f64..0.999, 1.001f64..20.0],
        shift in 1u64..10,
    ) {
        static DOCS: std::sync::OnceLock<Documents> = std::sync::OnceLock::new();
        let docs = DOCS.get_or_init(|| {
            let d = Documents::new();
            for (k, (what, doc, _)) in d.docs.iter().enumerate() {
                assert!(d.valid(k, doc), "the untouched {what} is valid");
            }
            d
        });
        let (what, document, checked) = &docs.docs[kind];
        let path = at.get(checked);
        let mut doc = document.clone();
        let x = leaf(&mut doc, path);
        *x = match x.clone() {
            Value::Bool(b) => Value::Bool(!b),
            Value::String(s) => Value::String(format!("{s}x")),
            Value::Number(n) => match (n.as_u64(), n.as_f64()) {
                (Some(u), _) => Value::from(u + shift),
                (None, Some(f)) => Value::from(f * factor + shift as f64 * f.signum()),
                _ => unreachable!("a number"),
            },
            other => unreachable!("a leaf: {other}"),
        };
        proptest::prop_assert!(!docs.valid(kind, &doc), "{what}: {path} changed to {} is called valid", leaf(&mut doc.clone(), path));
    }
}
