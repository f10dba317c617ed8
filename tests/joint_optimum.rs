//! The joint optimum (`--route optimal --sharing exact`) and the gap split (models/compose.md,
//! "Joint optimum", "Gap split").
//!
//! The reference of the joint optimum is the exhaustive enumeration of `tests/common`: every
//! simple sequence of distinct nodes with pads, each hop along the shortest path between its
//! ends, flown with the public `Planner::fly` (the continuous-time hop optimum) and
//! `Planner::stop_at` from full batteries on a planner of its own. It shares no code with the
//! lazy search.

mod common;

use common::swarmplan;
use swarmplan::compose::{
    Context, PlanOptions, PlanOutcome, RequestReport, RouteMethod, SplitLabel,
};
use swarmplan::eaas::SharingPolicy;
use swarmplan::precompose::Positioning;
use swarmplan::problem::{Network, Profile, Request, SkywayGraph};

/// Relative tolerance between two delivery times summed in different orders.
const REL_TOL: f64 = 1e-9;

fn options(sharing: SharingPolicy, positioning: Positioning, route: RouteMethod) -> PlanOptions {
    PlanOptions {
        sharing,
        positioning,
        route,
        support: None,
    }
}

/// A random connected network of 5 to 8 nodes over a 6 km square, most nodes with pads, light
/// winds, and a request between the two nodes farthest apart.
fn random_case(seed: u64) -> (Network, SkywayGraph, Request) {
    common::random_network_case(
        seed,
        &common::RandomNetworkShape {
            nodes: 5..=8,
            square_m: 6_000.0,
            max_pads: 3,
            max_wind_mps: 6.0,
        },
    )
}

fn checked(network: &Network, profile: &Profile, request: &Request, r: &RequestReport) {
    common::assert_checked(network, profile, request, r);
}

#[test]
fn joint_optimum_equals_the_enumeration_and_never_exceeds_a_heuristic_or_a_same_policy_optimum() {
    let profile = common::shipped_profile("paper");
    let (mut cases, mut with_stops, mut no_sequence, mut below_pb) = (0, 0, 0, 0);
    for seed in 0..40u64 {
        let (network, graph, request) = random_case(seed);
        let context = Context::new(&network, &graph, &profile);
        let mut combos = vec![options(
            SharingPolicy::Exact,
            Positioning::LocationAware,
            RouteMethod::Optimal,
        )];
        for sharing in [
            SharingPolicy::IdleSupport,
            SharingPolicy::Pb,
            SharingPolicy::Fb,
        ] {
            for route in [
                RouteMethod::Optimal,
                RouteMethod::Sequential,
                RouteMethod::Astar,
            ] {
                combos.push(options(sharing, Positioning::LocationAware, route));
            }
        }
        let reports = context.plan_each(&request, &combos).unwrap();
        let joint = &reports[0];
        checked(&network, &profile, &request, joint);
        let (s, t) = (
            graph.index_of(&request.source).unwrap(),
            graph.index_of(&request.destination).unwrap(),
        );
        let proof = joint
            .plan
            .route_optimality
            .expect("optimal records its search");
        assert!(proof.proven(), "seed {seed}: {proof:?}");
        let expected =
            common::enumerate_min_dt(&graph, &profile, &joint.swarm, SharingPolicy::Exact, s, t);
        let what = format!("seed {seed}");
        match expected {
            Some(dt) => {
                assert!(joint.plan.delivered(), "{what}: {}", joint.plan.outcome);
                let got = joint.plan.dt_min;
                assert!(
                    (got - dt).abs() <= REL_TOL * dt.max(1.0) + proof.epsilon_min,
                    "{what}: joint dt {got}, enumeration {dt}, epsilon {}",
                    proof.epsilon_min
                );
                with_stops += usize::from(!joint.plan.stops().is_empty());
            }
            None => {
                assert!(
                    matches!(joint.plan.outcome, PlanOutcome::NoStopSequence { .. }),
                    "{what}: no sequence delivers, but {}",
                    joint.plan.outcome
                );
                no_sequence += 1;
            }
        }
        // Every heuristic and same-policy optimum of the same swarm: never below the joint
        // optimum (its schedules lie in `paper` mode, its hops follow the rule).
        for other in &reports[1..] {
            if !other.plan.delivered() {
                continue;
            }
            assert!(joint.plan.delivered(), "{what}: {:?}", other.options);
            assert!(
                joint.plan.dt_min <= other.plan.dt_min * (1.0 + REL_TOL) + proof.epsilon_min,
                "{what}: joint {} > {:?} {}",
                joint.plan.dt_min,
                other.options,
                other.plan.dt_min
            );
            if other.options.sharing == SharingPolicy::Pb
                && other.options.route == RouteMethod::Optimal
                && joint.plan.dt_min < other.plan.dt_min * (1.0 - 1e-6)
            {
                below_pb += 1;
            }
        }
        cases += 1;
    }
    // Not vacuous: routes stop, some requests fail, and exact sharing beats PB's optimum.
    assert!(with_stops * 3 >= cases, "only {with_stops} of {cases} stop");
    assert!(no_sequence > 0, "every request of the {cases} delivers");
    assert!(
        below_pb > 0,
        "the joint optimum never beats PB's optimal route"
    );
}

#[test]
fn gap_split_parts_add_up_are_not_negative_and_no_heuristic_delivers_alone() {
    let profile = common::shipped_profile("paper");
    let mut split = 0;
    let mut positive = [0usize; 3];
    for seed in 0..25u64 {
        let (network, graph, request) = random_case(seed);
        let context = Context::new(&network, &graph, &profile);
        let mut combos = Vec::new();
        for sharing in [SharingPolicy::None, SharingPolicy::Pb, SharingPolicy::Fb] {
            for positioning in [Positioning::LocationAware, Positioning::EnergyAware] {
                for route in [
                    RouteMethod::Sequential,
                    RouteMethod::Astar,
                    RouteMethod::Dijkstra,
                ] {
                    combos.push(options(sharing, positioning, route));
                }
            }
        }
        let reports = context.plan_each(&request, &combos).unwrap();
        let joint = context.joint_split(&request, &reports).unwrap();
        let joint_dt = joint.joint.dt_min();
        // The joint optimum is the least of its swarms' optima.
        for s in &joint.joint.swarms {
            if let (Some(dt), Some(best)) = (s.dt_min(), joint_dt) {
                assert!(best <= dt, "seed {seed}: joint {best} > a swarm's {dt}");
            }
        }
        for (report, split_of) in reports.iter().zip(&joint.splits) {
            let g = split_of.as_ref().expect("every report is a heuristic");
            let what = format!("seed {seed} {:?}", report.options);
            if report.plan.delivered() {
                assert!(
                    joint_dt.is_some(),
                    "{what}: delivers, the joint optimum does not"
                );
            }
            let Some(total) = g.total_min else {
                continue;
            };
            let (sharing, route, swarm) = (
                g.sharing_min.unwrap(),
                g.route_min.unwrap(),
                g.swarm_min.unwrap(),
            );
            assert_eq!(g.label, None, "{what}");
            assert!(
                (sharing + route + swarm - total).abs() <= 1e-9 * total.abs().max(1.0),
                "{what}: {sharing} + {route} + {swarm} != {total}"
            );
            assert!(
                (report.plan.dt_min - joint_dt.unwrap() - total).abs() <= 1e-9,
                "{what}: total {total}"
            );
            for (i, part) in [sharing, route, swarm].into_iter().enumerate() {
                assert!(
                    part >= -g.epsilon_min - 1e-9 * report.plan.dt_min,
                    "{what}: part {i} = {part} below -epsilon {}",
                    g.epsilon_min
                );
                positive[i] += usize::from(part > 1e-6);
            }
            if report.options.sharing == SharingPolicy::None {
                // No support drone: the exact schedule is the empty one.
                assert!(
                    sharing.abs() <= 1e-9 * report.plan.dt_min,
                    "{what}: {sharing}"
                );
            }
            split += 1;
        }
        for (report, g) in reports.iter().zip(&joint.splits) {
            let g = g.as_ref().unwrap();
            if g.label == Some(SplitLabel::OutsideReference) {
                assert_eq!(report.options.route, RouteMethod::Dijkstra);
                assert!(g.sharing_min.is_some() && g.total_min.is_none());
            }
        }
    }
    assert!(split > 50, "only {split} plans split");
    // Not vacuous: each part is positive for some plan.
    assert!(
        positive.iter().all(|&n| n > 0),
        "positive parts {positive:?}"
    );
}

#[test]
fn solve_prints_the_joint_optimum_and_fair_stays_refused() {
    let out = swarmplan(&[
        "solve",
        "--request-id",
        "r00003",
        "--route",
        "optimal",
        "--sharing",
        "exact",
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", common::stderr(&out));
    let doc: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(doc["options"]["route"], "optimal");
    assert_eq!(doc["options"]["sharing"], "exact");
    let proof = &doc["plan"]["route_optimality"];
    assert!(proof["arcs_flown"].as_u64().unwrap() >= 1);
    assert!(proof.get("hop_solves_unproven").is_none(), "{proof}");
    let out = swarmplan(&[
        "solve",
        "--request-id",
        "r00003",
        "--route",
        "optimal",
        "--sharing",
        "fair",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(common::stderr(&out).contains("[E0015]"));
}
