//! Known optima for routes: tiny `flat` instances whose delivery times, optimal and heuristic,
//! are computed by hand in instances/tiny/README.md ("Known optima for routes"). The expected
//! values below come from that arithmetic, not from running the code.
//!
//! `flat` profile, one drone with 0.21 kg, no sharing: 133.1 mAh/min, 500 m/min, so a hop of
//! `tt` min uses 133.1 tt mAh (at most 1000: tt <= 7.513 min) and a stop at a pad charging `r`
//! mAh/min after it lasts `nt = 133.1 tt / r` min.

mod common;

use common::{close, flat_instance, repo_arg, swarmplan};
use swarmplan::check::check_plan;
use swarmplan::compose::{Context, PlanOptions, RequestReport, RouteMethod};
use swarmplan::eaas::SharingPolicy;
use swarmplan::precompose::Positioning;
use swarmplan::problem::Request;

/// One route of the table: instance, request, method, and the hand-computed answer.
struct KnownRoute {
    network: &'static str,
    from: &'static str,
    to: &'static str,
    route: RouteMethod,
    /// Hand-computed delivery time, min.
    dt_min: f64,
    /// Stops, in order.
    stops: &'static [&'static str],
}

const fn known(
    network: &'static str,
    route: RouteMethod,
    dt_min: f64,
    stops: &'static [&'static str],
) -> KnownRoute {
    KnownRoute {
        network,
        from: "S",
        to: "T",
        route,
        dt_min,
        stops,
    }
}

/// instances/tiny/README.md, "Known optima for routes".
const TABLE: [KnownRoute; 10] = [
    // flat-detour: W -1, S 0, Q 6 (pad 20 mAh/min), M 7, T 14 (minutes along a line).
    known("flat-detour.json", RouteMethod::Optimal, 23.317, &["M"]),
    known(
        "flat-detour.json",
        RouteMethod::Sequential,
        65.247,
        &["W", "Q", "M"],
    ),
    known(
        "flat-detour.json",
        RouteMethod::Astar,
        65.247,
        &["W", "Q", "M"],
    ),
    known("flat-detour.json", RouteMethod::Dijkstra, 23.317, &["M"]),
    known(
        "flat-detour.json",
        RouteMethod::FloydWarshall,
        23.317,
        &["M"],
    ),
    // flat-skip: the cycle S-P-X-T-Q2-Q1-S of 1, 7, 1, 5, 4, 1 min; Q1 pad 20 mAh/min.
    known("flat-skip.json", RouteMethod::Optimal, 16.655, &["Q2"]),
    known(
        "flat-skip.json",
        RouteMethod::Sequential,
        21.317,
        &["P", "Q2"],
    ),
    known("flat-skip.json", RouteMethod::Astar, 19.648, &["P", "X"]),
    known("flat-skip.json", RouteMethod::Dijkstra, 19.648, &["P", "X"]),
    known(
        "flat-skip.json",
        RouteMethod::FloydWarshall,
        19.648,
        &["P", "X"],
    ),
];

/// Plans `k` with the library, no sharing, one 0.21 kg drone, and runs the plan checker.
fn plan(k: &KnownRoute) -> RequestReport {
    let (network, graph, profile) = flat_instance(k.network);
    let request = Request {
        id: format!("{}-{}", k.from, k.to),
        source: k.from.into(),
        destination: k.to.into(),
        packages_kg: vec![0.21],
    };
    let options = PlanOptions {
        sharing: SharingPolicy::None,
        positioning: Positioning::LocationAware,
        route: k.route,
        support: Some(0),
    };
    let report = Context::new(&network, &graph, &profile)
        .plan(&request, &options)
        .unwrap();
    let violations = check_plan(
        &network,
        &profile,
        &request,
        &report.swarm,
        SharingPolicy::None,
        &report.plan,
    );
    assert!(
        violations.is_empty(),
        "{} {:?}: {violations:?}",
        k.network,
        k.route
    );
    report
}

#[test]
fn every_route_of_the_known_optima_table_has_its_hand_computed_delivery_time() {
    let mut failures = Vec::new();
    for k in &TABLE {
        let report = plan(k);
        let p = &report.plan;
        if !p.delivered() || !close(p.dt_min, k.dt_min) || p.stops() != k.stops {
            failures.push(format!(
                "{} {:?}: dt {} stops {:?} ({:?}), expected dt {} stops {:?}",
                k.network,
                k.route,
                p.dt_min,
                p.stops(),
                p.outcome,
                k.dt_min,
                k.stops
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn algorithm_1_is_at_least_twice_the_optimum_on_flat_detour() {
    // 65.247 / 23.317 = 2.798 (hand values of the table).
    let dt = |route| {
        TABLE
            .iter()
            .find(|k| k.network == "flat-detour.json" && k.route == route)
            .map(|k| plan(k).plan.dt_min)
            .unwrap()
    };
    assert!(dt(RouteMethod::Sequential) >= 2.0 * dt(RouteMethod::Optimal));
}

#[test]
fn the_optimum_skips_the_pad_node_every_heuristic_stops_at_on_flat_skip() {
    for k in TABLE.iter().filter(|k| k.network == "flat-skip.json") {
        let stops_at_p = plan(k).plan.stops().contains(&"P");
        assert_eq!(stops_at_p, k.route != RouteMethod::Optimal, "{:?}", k.route);
    }
}

#[test]
fn solve_prints_the_hand_computed_optima_and_the_gaps() {
    // The command line gives the same numbers, and `--gap` the ratio to the hand optimum:
    // flat-detour sequential (65.247 - 23.317) / 23.317; flat-skip A* (19.648 - 16.655) / 16.655.
    for (network, route, dt_min, optimal_dt_min) in [
        ("flat-detour.json", "sequential", 65.247, 23.317),
        ("flat-skip.json", "astar", 19.648, 16.655),
        ("flat-skip.json", "optimal", 16.655, 16.655),
    ] {
        let (net, profile) = (
            repo_arg(&format!("instances/tiny/{network}")),
            repo_arg("instances/tiny/flat.toml"),
        );
        let out = swarmplan(&[
            "solve",
            "--network",
            &net,
            "--profile",
            &profile,
            "--from",
            "S",
            "--to",
            "T",
            "--packages",
            "0.21",
            "--sharing",
            "none",
            "--route",
            route,
            "--gap",
            "--json",
        ]);
        assert_eq!(out.status.code(), Some(0), "{network} {route}: {out:?}");
        let r: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let got = r["plan"]["dt_min"].as_f64().unwrap();
        assert!(close(got, dt_min), "{network} {route}: dt {got}");
        let gap = r["route_gap"]["gap"].as_f64().unwrap();
        let expected = (dt_min - optimal_dt_min) / optimal_dt_min;
        assert!(
            (gap - expected).abs() < 1e-6,
            "{network} {route}: gap {gap}"
        );
    }
}

/// flat-joint (instances/tiny/README.md, "flat-joint.json"): S, M (1 pad), T on a line, 4 min
/// apart; packages 0.21 and 0.44 kg with one support drone. Hand values: the joint optimum flies
/// S → T direct in 8 min sharing 305.9 · 8 − 2000 = 447.2 mAh; PB and FB cannot fly it direct
/// and stop at M (dt 8 + 19.148), idle-support too, the baseline without support 8 + 12.236.
#[test]
fn the_joint_optimum_beats_every_same_policy_optimum_on_flat_joint() {
    let (network, graph, profile) = flat_instance("flat-joint.json");
    let request = Request {
        id: "joint".into(),
        source: "S".into(),
        destination: "T".into(),
        packages_kg: vec![0.21, 0.44],
    };
    let context = Context::new(&network, &graph, &profile);
    let expected = [
        (SharingPolicy::None, 20.236, vec!["M"]),
        (SharingPolicy::IdleSupport, 27.148, vec!["M"]),
        (SharingPolicy::Pb, 27.148, vec!["M"]),
        (SharingPolicy::Fb, 27.148, vec!["M"]),
        (SharingPolicy::Exact, 8.0, vec![]),
    ];
    for (sharing, dt_min, stops) in expected {
        let options = PlanOptions {
            sharing,
            positioning: Positioning::LocationAware,
            route: RouteMethod::Optimal,
            support: None,
        };
        let report = context.plan(&request, &options).unwrap();
        let p = &report.plan;
        assert!(p.delivered(), "{sharing}: {}", p.outcome);
        assert!(
            close(p.dt_min, dt_min),
            "{sharing}: dt {} expected {dt_min}",
            p.dt_min
        );
        assert_eq!(p.stops(), stops, "{sharing}");
        if sharing == SharingPolicy::Exact {
            assert!(close(p.shared_mah, 447.2), "shared {}", p.shared_mah);
            assert!(p.route_optimality.unwrap().proven());
        }
        let v = check_plan(&network, &profile, &request, &report.swarm, sharing, p);
        assert!(v.is_empty(), "{sharing}: {v:?}");
    }
}
