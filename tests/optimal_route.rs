//! `--route optimal`: the least delivery time over stop sequences (models/compose.md, "Optimal
//! route").
//!
//! The reference is an exhaustive enumeration written here: every simple sequence of distinct
//! nodes with pads between the source and the destination, each hop along the shortest path by
//! distance between its ends and flown with the public `Planner::fly` and `Planner::stop_at`
//! from full batteries, infeasible hops rejected. It shares no code with the stop-graph search.

mod common;

use common::{paper_195, swarmplan};
use swarmplan::compose::{Context, PlanOptions, PlanOutcome, RequestReport, RouteMethod};
use swarmplan::eaas::SharingPolicy;
use swarmplan::precompose::Positioning;
use swarmplan::problem::{Network, Profile, Request, SkywayGraph};
use swarmplan::solver::SolveStatus;

/// Relative tolerance between two delivery times summed in different orders.
const REL_TOL: f64 = 1e-9;

fn options(sharing: SharingPolicy, route: RouteMethod) -> PlanOptions {
    PlanOptions {
        sharing,
        positioning: Positioning::LocationAware,
        route,
        support: None,
    }
}

/// A random connected network of 5 to 9 nodes spread over a 7 km square (a loaded swarm of the
/// paper profile flies a few km on full batteries, so most far pairs need stops and some cannot
/// be joined at all), most nodes with pads, light winds;
/// and a request between the two nodes farthest apart by shortest path.
fn random_case(seed: u64) -> (Network, SkywayGraph, Request) {
    common::random_network_case(
        seed,
        &common::RandomNetworkShape {
            nodes: 5..=9,
            square_m: 7_000.0,
            max_pads: 3,
            max_wind_mps: 6.0,
        },
    )
}

fn checked(network: &Network, profile: &Profile, request: &Request, r: &RequestReport) {
    common::assert_checked(network, profile, request, r);
}

#[test]
fn optimal_route_equals_the_enumeration_of_stop_sequences_and_never_exceeds_algorithm_1_or_astar() {
    let profile = common::shipped_profile("paper");
    let mut with_stops = 0;
    let mut no_sequence = 0;
    let mut cases = 0;
    for seed in 0..100u64 {
        let (network, graph, request) = random_case(seed);
        let context = Context::new(&network, &graph, &profile);
        for sharing in [
            SharingPolicy::None,
            SharingPolicy::IdleSupport,
            SharingPolicy::Pb,
            SharingPolicy::Fb,
        ] {
            let reports = context
                .plan_each(
                    &request,
                    &[
                        options(sharing, RouteMethod::Optimal),
                        options(sharing, RouteMethod::Sequential),
                        options(sharing, RouteMethod::Astar),
                    ],
                )
                .unwrap();
            let (opt, seq, astar) = (&reports[0], &reports[1], &reports[2]);
            assert_eq!(opt.options.route, RouteMethod::Optimal);
            checked(&network, &profile, &request, opt);
            let (s, t) = (
                graph.index_of(&request.source).unwrap(),
                graph.index_of(&request.destination).unwrap(),
            );
            let expected = common::enumerate_min_dt(&graph, &profile, &opt.swarm, sharing, s, t);
            let what = format!("seed {seed} {sharing}");
            match expected {
                Some(dt) => {
                    assert!(opt.plan.delivered(), "{what}: {}", opt.plan.outcome);
                    let got = opt.plan.dt_min;
                    assert!(
                        (got - dt).abs() <= REL_TOL * dt.max(1.0),
                        "{what}: optimal dt {got}, enumeration {dt}"
                    );
                    with_stops += usize::from(!opt.plan.stops().is_empty());
                }
                None => {
                    assert!(
                        matches!(opt.plan.outcome, PlanOutcome::NoStopSequence { .. }),
                        "{what}: no sequence delivers, but {}",
                        opt.plan.outcome
                    );
                    no_sequence += 1;
                }
            }
            for other in [seq, astar] {
                if other.plan.delivered() {
                    assert!(opt.plan.delivered(), "{what}: {:?}", other.options.route);
                    assert!(
                        opt.plan.dt_min <= other.plan.dt_min * (1.0 + REL_TOL),
                        "{what}: optimal {} > {} {}",
                        opt.plan.dt_min,
                        other.options.route,
                        other.plan.dt_min
                    );
                }
            }
            let proof = opt
                .plan
                .route_optimality
                .expect("optimal records its search");
            assert!(proof.proven(), "{what}: {proof:?}");
            cases += 1;
        }
    }
    // The property is not vacuous: many optimal routes stop on the way, some requests fail.
    assert!(
        with_stops * 2 >= cases,
        "only {with_stops} of {cases} routes stop"
    );
    assert!(no_sequence > 0, "every request of the {cases} delivers");
}

#[test]
fn optimal_route_on_paper_195_passes_the_checker_and_never_exceeds_algorithm_1_or_astar() {
    let (network, graph, profile, requests) = paper_195();
    let context = Context::new(&network, &graph, &profile);
    let mut stops = 0;
    for request in requests.iter().take(12) {
        for sharing in [SharingPolicy::None, SharingPolicy::Pb] {
            let reports = context
                .plan_each(
                    request,
                    &[
                        options(sharing, RouteMethod::Optimal),
                        options(sharing, RouteMethod::Sequential),
                        options(sharing, RouteMethod::Astar),
                    ],
                )
                .unwrap();
            let opt = &reports[0];
            checked(&network, &profile, request, opt);
            stops += opt.plan.stops().len();
            for other in &reports[1..] {
                checked(&network, &profile, request, other);
                if other.plan.delivered() {
                    assert!(opt.plan.delivered());
                    assert!(
                        opt.plan.dt_min <= other.plan.dt_min * (1.0 + REL_TOL),
                        "{} {sharing}: optimal {} > {} {}",
                        request.id,
                        opt.plan.dt_min,
                        other.options.route,
                        other.plan.dt_min
                    );
                }
            }
        }
    }
    assert!(stops > 0, "some of these requests need a stop");
}

#[test]
fn optimal_route_is_not_part_of_the_papers_grid() {
    assert!(!RouteMethod::ALL.contains(&RouteMethod::Optimal));
}

#[test]
fn solve_with_route_optimal_prints_an_optimal_plan() {
    let out = swarmplan(&[
        "solve",
        "--request-id",
        "r00042",
        "--route",
        "optimal",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", common::stderr(&out));
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(doc["options"]["route"], "optimal");
    assert_eq!(doc["plan"]["outcome"]["kind"], "delivered");
    assert!(doc["plan"]["route_optimality"].is_object());
}

#[test]
fn route_optimal_with_fair_sharing_is_refused_with_e0015() {
    {
        let sharing = "fair";
        let out = swarmplan(&[
            "solve",
            "--request-id",
            "r00042",
            "--route",
            "optimal",
            "--sharing",
            sharing,
        ]);
        assert_eq!(out.status.code(), Some(2));
        assert!(common::stderr(&out).contains("[E0015]"));
        let out = swarmplan(&[
            "batch",
            "--limit",
            "1",
            "--route",
            "optimal",
            "--sharing",
            sharing,
        ]);
        assert_eq!(out.status.code(), Some(2));
        assert!(common::stderr(&out).contains("[E0015]"));
    }
}

#[test]
fn a_stop_stopped_by_the_node_limit_leaves_the_route_unproven() {
    let (network, graph, profile, requests) = paper_195();
    let mut context = Context::new(&network, &graph, &profile);
    context.node_limit = Some(1);
    let mut unproven = 0;
    for request in requests.iter().take(30) {
        let r = context
            .plan(request, &options(SharingPolicy::Pb, RouteMethod::Optimal))
            .unwrap();
        checked(&network, &profile, request, &r);
        let proof = r.plan.route_optimality.expect("optimal records its search");
        let chosen_unproven = r
            .plan
            .hops
            .iter()
            .filter_map(|h| h.stop.as_ref())
            .filter(|s| s.status != SolveStatus::Optimal)
            .count();
        assert!(proof.stops_unproven >= chosen_unproven, "{}", request.id);
        assert!(proof.stops_unproven <= proof.stops_solved, "{}", request.id);
        assert_eq!(proof.proven(), proof.stops_unproven == 0);
        unproven += usize::from(!proof.proven());
    }
    assert!(unproven > 0, "a node limit of 1 stops some search");
}

#[test]
fn solve_check_reads_back_an_optimal_plan() {
    let out = swarmplan(&[
        "solve",
        "--request-id",
        "r00001",
        "--route",
        "optimal",
        "--sharing",
        "fb",
        "--check",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", common::stderr(&out));
}
