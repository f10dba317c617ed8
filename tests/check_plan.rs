//! The independent plan checker (`check::check_plan`): every method's plans pass it, and corrupted
//! plans are rejected with the expected code.

mod common;

use common::{flat_instance, flat_stop_request, paper_195, repo_path};
use swarmplan::check::plan_file::parse_plan_file;
use swarmplan::check::{check_plan, check_report};
use swarmplan::compose::{Context, PlanOptions, PlanOutcome, RequestReport, RouteMethod};
use swarmplan::eaas::{FailureReason, HopFailure, SharingPolicy};
use swarmplan::precompose::Positioning;
use swarmplan::problem::io::read_json;
use swarmplan::problem::Candidates;
use swarmplan::problem::SkywayGraph;
use swarmplan::problem::{Network, Profile, Request, RequestSet};

fn codes(v: &[swarmplan::error::Violation]) -> Vec<&'static str> {
    v.iter().map(|x| x.code).collect()
}

const SHARING: [SharingPolicy; 3] = [SharingPolicy::None, SharingPolicy::Pb, SharingPolicy::Fb];
const POSITIONING: [Positioning; 2] = [Positioning::LocationAware, Positioning::EnergyAware];

/// Requests of paper-195 planned by every method combination: each plan re-verified from the raw
/// instance. Requests are taken at a stride so that short, long and heavy ones all appear. Also
/// counts stops and transfers so the test cannot pass vacuously on direct flights only.
/// 150 requests x 24 combinations in a release build; a debug build (plain `cargo test`) takes a
/// 16-request sample of the same stride to stay quick.
#[test]
fn every_method_plan_passes_the_checker() {
    let (network, graph, profile, requests) = paper_195();
    let context = Context::new(&network, &graph, &profile);
    let count = if cfg!(debug_assertions) { 16 } else { 150 };
    let chosen: Vec<&Request> = requests.iter().step_by(66).take(count).collect();
    assert_eq!(chosen.len(), count);
    let mut failures = Vec::new();
    let (mut plans, mut stops, mut transfers, mut failed) = (0usize, 0usize, 0usize, 0usize);
    for route in RouteMethod::ALL {
        for sharing in SHARING {
            for positioning in POSITIONING {
                let options = PlanOptions {
                    sharing,
                    positioning,
                    route,
                    support: None,
                };
                for r in &chosen {
                    let report = context.plan(r, &options).unwrap();
                    let v = check_plan(&network, &profile, r, &report.swarm, sharing, &report.plan);
                    plans += 1;
                    stops += report.plan.stops().len();
                    transfers += report
                        .plan
                        .hops
                        .iter()
                        .map(|h| h.transfers.len())
                        .sum::<usize>();
                    failed += usize::from(!report.plan.delivered());
                    if !v.is_empty() {
                        failures.push(format!("{} {options:?}: {:?}", r.id, v));
                    }
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {plans} plans fail the checker:\n{}",
        failures.len(),
        failures.join("\n")
    );
    assert_eq!(plans, count * 24);
    // Non-vacuous: the sample exercises recharging stops and in-flight transfers.
    assert!(stops > 0, "no plan stops");
    assert!(transfers > 0, "no plan shares");
    eprintln!("{plans} plans: {stops} stops, {transfers} transfers, {failed} failed requests");
}

/// A request of paper-195 whose sequential PB plan has at least one stop and one transfer.
fn plan_with_stop_and_transfer() -> (Network, Profile, Request, RequestReport) {
    let (network, graph, profile, requests) = paper_195();
    let context = Context::new(&network, &graph, &profile);
    let options = PlanOptions {
        sharing: SharingPolicy::Pb,
        positioning: Positioning::LocationAware,
        route: RouteMethod::Sequential,
        support: None,
    };
    for r in &requests {
        let report = context.plan(r, &options).unwrap();
        let p = &report.plan;
        if p.delivered()
            && p.hops.len() >= 2
            && p.hops.iter().any(|h| !h.transfers.is_empty())
            && p.hops
                .iter()
                .any(|h| h.stop.as_ref().is_some_and(|s| s.nt_min > 0.0))
        {
            return (network, profile, r.clone(), report);
        }
    }
    panic!("paper-195 has no request with a stop and a transfer");
}

#[test]
fn corrupted_plans_are_rejected_with_their_code() {
    let (network, profile, request, report) = plan_with_stop_and_transfer();
    let swarm = &report.swarm;
    let good = report.plan.clone();
    let check = |p: &swarmplan::compose::Plan| {
        codes(&check_plan(
            &network,
            &profile,
            &request,
            swarm,
            SharingPolicy::Pb,
            p,
        ))
    };
    assert!(check(&good).is_empty(), "the original plan passes");
    let stop_hop = good.hops.iter().position(|h| h.stop.is_some()).unwrap();
    let shared_hop = good
        .hops
        .iter()
        .position(|h| !h.transfers.is_empty())
        .unwrap();

    // Wrong nt: one minute more than the makespan, totals kept consistent.
    let mut p = good.clone();
    p.hops[stop_hop].stop.as_mut().unwrap().nt_min += 1.0;
    p.nt_min += 1.0;
    p.dt_min += 1.0;
    // The makespan no longer matches, and (a small swarm) nt is above the optimum.
    let c = check(&p);
    assert_eq!(c[0], "P5026", "wrong nt: {c:?}");
    assert!(c.iter().all(|x| ["P5026", "P5028"].contains(x)), "{c:?}");

    // nt = 0: neither the makespan nor above the lower bound max(max ct, sum ct / pads).
    let mut p = good.clone();
    {
        let stop = p.hops[stop_hop].stop.as_mut().unwrap();
        stop.nt_min = 0.0;
    }
    let c = check(&p);
    assert!(c.contains(&"P5026") && c.contains(&"P5027"), "nt 0: {c:?}");

    // A drone charged twice: not a partition.
    let mut p = good.clone();
    {
        let stop = p.hops[stop_hop].stop.as_mut().unwrap();
        let d = stop.assignment[0][0];
        stop.assignment[0].push(d);
    }
    assert!(check(&p).contains(&"P5025"), "drone charged twice");

    // Broken chain: the second hop starts somewhere else.
    let mut p = good.clone();
    let other = network
        .nodes
        .iter()
        .find(|n| n.id != p.hops[1].from)
        .unwrap()
        .id
        .clone();
    p.hops[1].from = other;
    assert!(check(&p).contains(&"P5004"), "broken chain");

    // Truncated plan claiming success: the last hop ends at a stop, not the destination.
    let mut p = good.clone();
    p.hops.truncate(stop_hop + 1);
    let c = check(&p);
    assert!(c.contains(&"P5005"), "truncated: {c:?}");

    // A non-existent edge: replace the path by a direct jump between its ends (the request's
    // hop has more than one edge or the ends are not adjacent).
    let mut p = good.clone();
    let h = &mut p.hops[0];
    let far = network
        .nodes
        .iter()
        .find(|n| {
            n.id != h.path[0]
                && !network.edges.iter().any(|s| {
                    (s.from == h.path[0] && s.to == n.id) || (s.to == h.path[0] && s.from == n.id)
                })
        })
        .unwrap()
        .id
        .clone();
    h.path.insert(1, far);
    assert!(check(&p).contains(&"P5011"), "non-existent edge");

    // tt mismatch: 10% faster than distance / speed.
    let mut p = good.clone();
    let dtt = 0.1 * p.hops[0].tt_min;
    p.hops[0].tt_min -= dtt;
    p.tt_min -= dtt;
    p.dt_min -= dtt;
    assert_eq!(check(&p), vec!["P5013"], "tt mismatch");

    // A per-leg breakdown whose travel times do not add up to the hop's (P5033), with a leg
    // whose travel time is not its edge's length over the speed (P5044).
    let mut p = good.clone();
    p.hops[0].legs[0].tt_min += 1.0;
    assert_eq!(check(&p), vec!["P5033", "P5044"], "leg tt");

    // dt that is not tt + nt.
    let mut p = good.clone();
    p.dt_min += 5.0;
    assert_eq!(check(&p), vec!["P5031"], "dt mismatch");

    // Arrival batteries higher than the flight allows: the re-integration disagrees.
    let mut p = good.clone();
    p.hops[0].arrival_battery_mah[0] += 100.0;
    assert!(check(&p).contains(&"P5015"), "arrival battery");

    // A transfer doubled in length: energy no longer rho x duration and batteries disagree.
    let mut p = good.clone();
    p.hops[shared_hop].transfers[0].end_min += 1.0;
    assert!(check(&p).contains(&"P5015"), "transfer");

    // Transfers while the plan claims support drones that never share.
    let claim = |sharing| {
        codes(&check_plan(
            &network, &profile, &request, swarm, sharing, &good,
        ))
    };
    assert_eq!(
        claim(SharingPolicy::IdleSupport),
        vec!["P5016"],
        "idle support"
    );
    // The paper's baseline flies no support drone at all.
    assert_eq!(
        claim(SharingPolicy::None),
        vec!["P5034", "P5016"],
        "sharing none"
    );

    // A hop departing with a battery that is not full.
    let mut p = good.clone();
    p.hops[1].departure_battery_mah[0] -= 1.0;
    assert!(check(&p).contains(&"P5014"), "not full at departure");

    // Wrong charge time.
    let mut p = good.clone();
    p.hops[stop_hop].stop.as_mut().unwrap().charge_times_min[0] += 0.5;
    assert!(check(&p).contains(&"P5022"), "charge time");

    // Arrival batteries missing a drone: reported, not a panic.
    let mut p = good.clone();
    p.hops[stop_hop].arrival_battery_mah.pop();
    let c = check(&p);
    assert!(c.contains(&"P5014") && c.contains(&"P5022"), "{c:?}");

    // A delivered plan turned into a dead end at the source, where the swarm is not: the
    // outcome names the wrong node (P5035), and the last hop now ends without a stop (P5007).
    // (A failed plan without a reason, or a delivered one with a failure, the retired P5002
    // and P5003, cannot be written: the outcome is one typed value.)
    let mut p = good.clone();
    let first = HopFailure {
        drone: 0,
        time_min: 1.0,
        reason: FailureReason::BatteryDepleted,
    };
    p.outcome = PlanOutcome::DeadEnd {
        node: request.source.clone(),
        candidates: Candidates::PadNodes,
        direct: first,
    };
    assert_eq!(check(&p), vec!["P5007", "P5035"], "dead end elsewhere");
    // The same dead end where the last hop ends is consistent with the hops.
    p.outcome = PlanOutcome::DeadEnd {
        node: good.hops.last().unwrap().to.clone(),
        candidates: Candidates::PadNodes,
        direct: first,
    };
    assert_eq!(check(&p), vec!["P5007"], "dead end at the end of the hops");
    // A hop to the next pad node that does not fly, claimed from a node the swarm is not at.
    p.outcome = PlanOutcome::HopInfeasible {
        from: request.source.clone(),
        to: request.destination.clone(),
        failure: first,
    };
    assert!(check(&p).contains(&"P5035"), "hop infeasible elsewhere");
    // No route between two nodes the network joins.
    let mut p = good.clone();
    p.hops.clear();
    p.tt_min = 0.0;
    p.nt_min = 0.0;
    p.dt_min = 0.0;
    p.shared_mah = 0.0;
    p.outcome = PlanOutcome::NoRoute {
        from: request.source.clone(),
        to: request.destination.clone(),
    };
    assert_eq!(check(&p), vec!["P5036"], "no route on a connected network");
}

#[test]
fn plan_outcomes_are_tagged_objects_in_json_and_sentences_in_text() {
    let dead_end = PlanOutcome::DeadEnd {
        node: "n012".into(),
        candidates: Candidates::PadNodes,
        direct: HopFailure {
            drone: 2,
            time_min: 7.5,
            reason: FailureReason::BatteryDepleted,
        },
    };
    let json = serde_json::to_value(&dead_end).unwrap();
    assert_eq!(
        json,
        serde_json::json!({"kind": "dead-end", "node": "n012", "candidates": "pad-nodes",
            "direct": {"drone": 2, "time_min": 7.5, "reason": "battery_depleted"}})
    );
    assert_eq!(dead_end.kind(), "dead-end");
    assert_eq!(
        serde_json::from_value::<PlanOutcome>(json).unwrap(),
        dead_end
    );
    assert_eq!(
        serde_json::to_value(PlanOutcome::Delivered).unwrap(),
        serde_json::json!({"kind": "delivered"})
    );
    assert!(dead_end.to_string().starts_with("dead end at n012: "));
    assert!(dead_end
        .to_string()
        .contains("drone 2 runs out of energy after 7.50 min"));
    // Unknown kinds and unknown fields are refused.
    for bad in [
        r#"{"kind": "lost"}"#,
        r#"{"kind": "no-route", "from": "a", "to": "b", "why": "x"}"#,
    ] {
        assert!(serde_json::from_str::<PlanOutcome>(bad).is_err(), "{bad}");
    }
}

#[test]
fn a_valid_but_poor_pad_assignment_is_rejected_as_not_optimal() {
    // flat-stop (instances/tiny/README.md): drones 0.21, 0.21, 0.44 kg arrive at M with ct 6.655,
    // 6.655, 8.64 min on 2 pads. {0, 2} | {1} is a partition with makespan 6.655 + 8.64 =
    // 15.295 >= the bound max(8.64, 21.95 / 2) = 10.975, so only the optimality check (optimum
    // 13.31 = {0, 1} | {2}) rejects it.
    let (network, graph, profile) = flat_instance("flat-stop.json");
    let request = flat_stop_request("stop");
    let options = PlanOptions {
        sharing: SharingPolicy::None,
        positioning: Positioning::LocationAware,
        route: RouteMethod::Sequential,
        support: Some(0),
    };
    let report = Context::new(&network, &graph, &profile)
        .plan(&request, &options)
        .unwrap();
    let check = |p: &swarmplan::compose::Plan| {
        codes(&check_plan(
            &network,
            &profile,
            &request,
            &report.swarm,
            SharingPolicy::None,
            p,
        ))
    };
    assert!(check(&report.plan).is_empty());
    let mut p = report.plan.clone();
    let stop = p.hops[0].stop.as_mut().unwrap();
    let extra = 15.295 - stop.nt_min;
    assert!(
        (extra - (15.295 - 13.31)).abs() < 1e-9,
        "nt was {}",
        stop.nt_min
    );
    stop.assignment = vec![vec![0, 2], vec![1]];
    stop.nt_min = 15.295;
    p.nt_min += extra;
    p.dt_min += extra;
    assert_eq!(check(&p), vec!["P5028"]);
}

/// Plans every request of `requests` with every combination of `sharing`, both positionings and
/// every route; each plan is written as the JSON of `solve --json`, read back with the plan
/// reader, compared with the original and checked by `check_report`. Returns the plans made and
/// a line per failure.
fn read_back_and_check(
    network: &Network,
    graph: &SkywayGraph,
    profile: &Profile,
    requests: &[Request],
    sharing: &[SharingPolicy],
) -> (usize, Vec<String>) {
    let context = Context::new(network, graph, profile);
    let mut failures = Vec::new();
    let mut plans = 0;
    for &sharing in sharing {
        for positioning in POSITIONING {
            for route in RouteMethod::ALL {
                let options = PlanOptions {
                    sharing,
                    positioning,
                    route,
                    support: None,
                };
                for r in requests {
                    let report = context.plan(r, &options).unwrap();
                    let text = serde_json::to_string_pretty(&report).unwrap();
                    let read = parse_plan_file(&text, &r.id).unwrap();
                    plans += 1;
                    if read != report {
                        failures.push(format!("{} {options:?}: not read back unchanged", r.id));
                    }
                    let v = check_report(network, profile, requests, &read);
                    if !v.is_empty() {
                        failures.push(format!("{} {options:?}: {v:?}", r.id));
                    }
                }
            }
        }
    }
    (plans, failures)
}

/// The small version of `cargo run --release --example check_all`: every sharing policy,
/// positioning and route, each plan read back from its JSON and re-verified as `swarmplan
/// check` does. The simulated policies on paper-195 requests (r00023 has two stops and a
/// transfer), and every policy, exact and fair included, on the tiny flat-line requests (one
/// of which only sharing delivers) and flat-stop (a stop on 2 pads).
#[test]
fn every_method_plan_read_back_from_json_passes_the_checker() {
    let (network, graph, profile, requests) = paper_195();
    let chosen: Vec<Request> = ["r00000", "r00007", "r00023"]
        .iter()
        .map(|id| requests.iter().find(|r| r.id == *id).unwrap().clone())
        .collect();
    let simulated = [
        SharingPolicy::None,
        SharingPolicy::IdleSupport,
        SharingPolicy::Pb,
        SharingPolicy::Fb,
    ];
    let (plans, failures) = read_back_and_check(&network, &graph, &profile, &chosen, &simulated);
    assert_eq!(plans, 3 * 4 * 8);
    assert!(failures.is_empty(), "{}", failures.join("\n"));

    // Every policy there is.
    let every = <SharingPolicy as clap::ValueEnum>::value_variants();
    let (line, line_graph, flat) = flat_instance("flat-line.json");
    let set: RequestSet = read_json(&repo_path("instances/tiny/flat-requests.json")).unwrap();
    let (plans, failures) = read_back_and_check(&line, &line_graph, &flat, &set.requests, every);
    assert_eq!(plans, 3 * 6 * 8);
    assert!(failures.is_empty(), "{}", failures.join("\n"));

    let (stop, stop_graph, flat) = flat_instance("flat-stop.json");
    let request = flat_stop_request("stop");
    let (plans, failures) = read_back_and_check(&stop, &stop_graph, &flat, &[request], every);
    assert_eq!(plans, 6 * 8);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
