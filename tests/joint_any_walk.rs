//! The joint optimum over any walk (`--route optimal --sharing exact --hop-paths any`,
//! models/compose.md, "Joint optimum", "Any hop path").
//!
//! References: the hand-computed `flat-walk` instance (instances/tiny/README.md), and an
//! enumeration written here that shares no code with the search: every walk between two stops
//! in order of travel time (a depth-first search over the network's edges), flown from full
//! batteries with the public `Planner::fly` (the continuous-time hop optimum) and
//! `Planner::stop_at`, then every sequence of distinct pad nodes.

mod common;

use common::{flat_instance, repo_arg, shipped_profile, swarmplan};
use swarmplan::compose::{
    Context, HopPaths, PlanOptions, PlanOutcome, Planner, RequestReport, RouteMethod,
};
use swarmplan::eaas::exact_hop::HopGoal;
use swarmplan::eaas::SharingPolicy;
use swarmplan::precompose::Positioning;
use swarmplan::problem::{Network, Profile, Request, SkywayGraph, Swarm};

/// Relative tolerance between delivery times summed in different orders.
const REL_TOL: f64 = 1e-9;

/// No hop of the `paper` profile lasts longer: the best-placed unloaded drone uses at least
/// `194.78 * 0.9` mAh/min (`r0` times the least wind factor `1 - c_par`, models/energy.md) and
/// receives at most `rho = 5.88`, so its 4480 mAh last at most `4480 / (175.30 - 5.88) = 26.4`
/// min; a loaded delivery drone less.
const LONGEST_HOP_MIN: f64 = 26.5;

fn options(sharing: SharingPolicy) -> PlanOptions {
    PlanOptions {
        sharing,
        positioning: Positioning::LocationAware,
        route: RouteMethod::Optimal,
        support: None,
    }
}

fn checked(network: &Network, profile: &Profile, request: &Request, r: &RequestReport) {
    common::assert_checked(network, profile, request, r);
}

fn walk_request() -> Request {
    Request {
        id: "st".into(),
        source: "S".into(),
        destination: "T".into(),
        packages_kg: vec![0.21],
    }
}

#[test]
fn any_walk_flies_the_hand_computed_detour_where_the_rule_must_stop() {
    // instances/tiny/README.md, "flat-walk.json".
    let (network, graph, profile) = flat_instance("flat-walk.json");
    let request = walk_request();
    let mut any = Context::new(&network, &graph, &profile);
    any.hop_paths = HopPaths::Any;
    let rule = Context::new(&network, &graph, &profile);
    for (sharing, rule_dt_min) in [
        (SharingPolicy::Exact, 21.464),
        (SharingPolicy::None, 14.132),
    ] {
        let r = any.plan(&request, &options(sharing)).unwrap();
        checked(&network, &profile, &request, &r);
        assert!(r.plan.delivered(), "{sharing}: {}", r.plan.outcome);
        common::assert_close(r.plan.dt_min, 6.8, &format!("{sharing} any"));
        assert_eq!(r.plan.hops.len(), 1, "{sharing}: no stop");
        assert_eq!(r.plan.hops[0].path, ["S", "A", "T"], "{sharing}");
        let optimality = r.plan.route_optimality.unwrap();
        assert_eq!(optimality.hop_paths, HopPaths::Any);
        assert!(optimality.proven(), "{optimality:?}");
        let r = rule.plan(&request, &options(sharing)).unwrap();
        checked(&network, &profile, &request, &r);
        assert!(
            (r.plan.dt_min - rule_dt_min).abs() < 1e-3,
            "{sharing} rule: {}",
            r.plan.dt_min
        );
        assert_eq!(r.plan.stops().len(), 1, "{sharing} rule stops at P");
    }
    // The swarm under exact has the support drone; its arrival battery is 2000 - 1175.04.
    let r = any.plan(&request, &options(SharingPolicy::Exact)).unwrap();
    assert_eq!(r.swarm.drones.len(), 2);
    common::assert_close(
        r.plan.hops[0].arrival_battery_mah[0],
        94.92,
        "delivery drone",
    );
    common::assert_close(
        r.plan.hops[0].arrival_battery_mah[1],
        824.96,
        "support drone",
    );
}

#[test]
fn any_walk_with_exact_runs_on_the_command_line_and_pb_is_still_refused() {
    let (net, profile) = (
        repo_arg("instances/tiny/flat-walk.json"),
        repo_arg("instances/tiny/flat.toml"),
    );
    let base = [
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
        "--route",
        "optimal",
        "--hop-paths",
        "any",
        "--json",
    ];
    let mut args = base.to_vec();
    args.extend(["--sharing", "exact"]);
    let out = swarmplan(&args);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let dt = report["plan"]["dt_min"].as_f64().unwrap();
    assert!(common::close(dt, 6.8), "{dt}");
    assert_eq!(report["plan"]["route_optimality"]["hop_paths"], "any");
    let mut args = base.to_vec();
    args.extend(["--sharing", "pb"]);
    let out = swarmplan(&args);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    assert!(common::stderr(&out).contains("[E0016]"));
}

/// A random connected network of 5 to 7 nodes over a 6 km square, winds up to 12 m/s (a longer
/// walk may cost less energy than the shortest path), a request between the two nodes farthest
/// apart.
fn random_case(seed: u64) -> (Network, SkywayGraph, Request) {
    common::random_network_case(
        seed,
        &common::RandomNetworkShape {
            nodes: 5..=7,
            square_m: 6_000.0,
            max_pads: 2,
            max_wind_mps: 12.0,
        },
    )
}

/// The least cost of arc `u -> v` over every walk that flies from full batteries under the
/// exact policy: `tt` into the destination, `tt + nt` into a pad node (the realised node time
/// and the certified distance of its schedule to the infimum). Walks are extended depth first;
/// a walk is cut when its travel time reaches the best cost found (the cost is at least `tt`),
/// exceeds [`LONGEST_HOP_MIN`], or its prefix does not fly (a schedule of the whole walk flies
/// every prefix).
fn least_arc(
    planner: &Planner,
    graph: &SkywayGraph,
    u: usize,
    v: usize,
    into_stop: bool,
    flights: &mut usize,
) -> Option<(f64, f64)> {
    let full = planner.full_battery_mah();
    let speed = planner.speed_m_per_min();
    let mut best: Option<(f64, f64)> = None;
    let mut stack = vec![vec![u]];
    while let Some(nodes) = stack.pop() {
        let x = *nodes.last().unwrap();
        for &(y, _) in graph.neighbors(x) {
            let mut walk = nodes.clone();
            walk.push(y);
            let path = graph.path_from_nodes(&walk).unwrap();
            let tt_min = path.distance_m / speed;
            if tt_min > LONGEST_HOP_MIN || best.is_some_and(|(c, _)| tt_min >= c) {
                continue;
            }
            *flights += 1;
            let goal = if y == v && into_stop {
                HopGoal::NodeTimeMin
            } else {
                HopGoal::Feasible
            };
            let flight = planner
                .fly(&path, &full, SharingPolicy::Exact, goal)
                .unwrap();
            if !flight.outcome.feasible {
                continue;
            }
            if y == v {
                let (cost, epsilon) = if into_stop {
                    let stop = planner
                        .stop_at(v, &flight.outcome.final_battery_mah)
                        .unwrap()
                        .unwrap();
                    let solve = flight.solve.as_ref().unwrap();
                    let epsilon = solve.bound.map_or(0.0, |b| (stop.nt_min - b).max(0.0));
                    (tt_min + stop.nt_min, epsilon)
                } else {
                    (tt_min, 0.0)
                };
                if best.is_none_or(|(c, _)| cost < c) {
                    best = Some((cost, epsilon));
                }
            }
            stack.push(walk);
        }
    }
    best
}

/// The least `dt` over sequences of distinct pad nodes and any walk of each hop, and the summed
/// distances to the infimum along it; `None` when nothing delivers.
fn enumerate_dt(
    graph: &SkywayGraph,
    profile: &Profile,
    swarm: &Swarm,
    source: usize,
    destination: usize,
    flights: &mut usize,
) -> Option<(f64, f64)> {
    let planner = Planner::new(graph, profile, swarm, SharingPolicy::Exact);
    let n = graph.node_count();
    let mut arc = vec![vec![None; n]; n];
    for (u, arc_u) in arc.iter_mut().enumerate() {
        if u != source && graph.pads(u) == 0 {
            continue;
        }
        for (v, cell) in arc_u.iter_mut().enumerate() {
            if v == u || v == source || v != destination && graph.pads(v) == 0 {
                continue;
            }
            *cell = least_arc(&planner, graph, u, v, v != destination, flights);
        }
    }
    fn sequences(
        arc: &[Vec<Option<(f64, f64)>>],
        destination: usize,
        u: usize,
        (cost, eps): (f64, f64),
        visited: &mut Vec<bool>,
        best: &mut Option<(f64, f64)>,
    ) {
        if let Some((c, e)) = arc[u][destination] {
            if best.is_none_or(|(b, _)| cost + c < b) {
                *best = Some((cost + c, eps + e));
            }
        }
        for v in 0..arc.len() {
            let Some((c, e)) = arc[u][v] else { continue };
            if visited[v] || v == destination {
                continue;
            }
            visited[v] = true;
            sequences(arc, destination, v, (cost + c, eps + e), visited, best);
            visited[v] = false;
        }
    }
    let mut visited = vec![false; n];
    visited[source] = true;
    let mut best = None;
    sequences(
        &arc,
        destination,
        source,
        (0.0, 0.0),
        &mut visited,
        &mut best,
    );
    best
}

#[test]
fn any_walk_joint_optimum_equals_the_enumeration_of_walks_and_beats_the_rule_somewhere() {
    let profile = shipped_profile("paper");
    let (mut cases, mut delivered, mut below_rule, mut off_rule, mut flights) = (0, 0, 0, 0, 0);
    for seed in 0..90u64 {
        let (network, graph, request) = random_case(seed);
        let mut any = Context::new(&network, &graph, &profile);
        any.hop_paths = HopPaths::Any;
        let rule = Context::new(&network, &graph, &profile);
        let joint = any.plan(&request, &options(SharingPolicy::Exact)).unwrap();
        checked(&network, &profile, &request, &joint);
        let proof = joint.plan.route_optimality.unwrap();
        assert!(proof.proven(), "seed {seed}: {proof:?}");
        let (s, t) = (
            graph.index_of(&request.source).unwrap(),
            graph.index_of(&request.destination).unwrap(),
        );
        let expected = enumerate_dt(&graph, &profile, &joint.swarm, s, t, &mut flights);
        let what = format!("seed {seed}");
        match expected {
            Some((dt, eps)) => {
                assert!(joint.plan.delivered(), "{what}: {}", joint.plan.outcome);
                let got = joint.plan.dt_min;
                assert!(
                    (got - dt).abs() <= REL_TOL * dt.max(1.0) + proof.epsilon_min.max(eps),
                    "{what}: joint over walks {got}, enumeration {dt}"
                );
                delivered += 1;
            }
            None => assert!(
                matches!(joint.plan.outcome, PlanOutcome::NoStopSequence { .. }),
                "{what}: nothing delivers, but {}",
                joint.plan.outcome
            ),
        }
        // Never above the rule's joint optimum nor the any-walk optimum of idle-support (the
        // same swarm, no transfer: its schedules are among exact's).
        for (context, sharing) in [
            (&rule, SharingPolicy::Exact),
            (&any, SharingPolicy::IdleSupport),
        ] {
            let other = context.plan(&request, &options(sharing)).unwrap();
            if !other.plan.delivered() {
                continue;
            }
            assert!(joint.plan.delivered(), "{what}: {sharing} delivers");
            assert!(
                joint.plan.dt_min <= other.plan.dt_min * (1.0 + REL_TOL) + proof.epsilon_min,
                "{what}: joint over walks {} > {sharing} {}",
                joint.plan.dt_min,
                other.plan.dt_min
            );
            if sharing == SharingPolicy::Exact
                && joint.plan.dt_min < other.plan.dt_min * (1.0 - 1e-6)
            {
                below_rule += 1;
            }
        }
        // Some hop leaves the shortest path between its ends.
        off_rule += usize::from(joint.plan.hops.iter().any(|h| {
            let nodes: Vec<usize> = h
                .path
                .iter()
                .map(|id| graph.index_of(id).unwrap())
                .collect();
            let shortest = graph
                .shortest_path(nodes[0], *nodes.last().unwrap())
                .unwrap();
            h.distance_m > shortest.distance_m * (1.0 + 1e-9)
        }));
        cases += 1;
    }
    // Not vacuous: most requests deliver, and walks off the rule's paths win somewhere (seeds
    // 61 and 84 leave them, 84 below the rule's optimum).
    assert!(delivered * 2 >= cases, "{delivered} of {cases} deliver");
    assert!(off_rule > 0, "no joint optimum leaves the rule's paths");
    assert!(
        below_rule > 0,
        "the walks never beat the rule's joint optimum"
    );
    assert!(flights > 100, "{flights} walks flown by the enumeration");
}

#[test]
fn a_capped_search_of_walks_leaves_the_route_unproven_and_the_plan_valid() {
    // paper-195 r00181 (models/compose.md, "Any walk", "Cost and cap"): the walks from n143 into
    // the destination n082 fill the search's 200,000 partial walks.
    let (network, graph, profile, requests) = common::paper_195();
    let request = requests.iter().find(|r| r.id == "r00181").unwrap();
    let mut context = Context::new(&network, &graph, &profile);
    context.hop_paths = HopPaths::Any;
    let r = context
        .plan(request, &options(SharingPolicy::Exact))
        .unwrap();
    checked(&network, &profile, request, &r);
    assert!(r.plan.delivered(), "{}", r.plan.outcome);
    let proof = r.plan.route_optimality.unwrap();
    assert!(proof.arcs_capped >= 1, "{proof:?}");
    assert!(!proof.proven(), "a capped search proves nothing: {proof:?}");
    assert!(
        proof.hop_path_labels >= swarmplan::compose::MAX_HOP_PATH_LABELS,
        "{proof:?}"
    );
}
