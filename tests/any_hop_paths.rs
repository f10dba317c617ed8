//! `--route optimal --hop-paths any` (models/compose.md, "Any hop path"): the least delivery
//! time over stop sequences and over every path of each hop, without in-flight sharing.
//!
//! The reference is a brute force written here, sharing no code with the label search: every
//! simple path between every two stops, flown from full batteries with the public
//! `Planner::fly` (the hop simulation) and `Planner::stop_at`, then every sequence of distinct
//! pad nodes. Walks with a cycle never need enumerating: a cycle adds time and takes energy.

mod common;

use common::{flat_instance, repo_arg, shipped_profile, swarmplan};
use proptest::prelude::*;
use swarmplan::check::check_plan;
use swarmplan::compose::{Context, HopPaths, PlanOptions, Planner, RouteMethod};
use swarmplan::eaas::exact_hop::HopGoal;
use swarmplan::eaas::SharingPolicy;
use swarmplan::precompose::Positioning;
use swarmplan::problem::{Network, Profile, Request, SkywayGraph, Swarm};

/// Relative tolerance between delivery times summed in different orders.
const REL_TOL: f64 = 1e-9;

/// A random connected network of 5 to 7 nodes over a 6 km square, most nodes with pads, winds
/// up to 12 m/s (so that a longer path may cost less energy than the shortest), and a request
/// between the two nodes farthest apart.
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

/// Every simple path from `u` (node lists), by depth-first search.
fn simple_paths_from(graph: &SkywayGraph, u: usize) -> Vec<Vec<usize>> {
    fn extend(graph: &SkywayGraph, path: &mut Vec<usize>, out: &mut Vec<Vec<usize>>) {
        let x = *path.last().unwrap();
        for &(y, _) in graph.neighbors(x) {
            if path.contains(&y) {
                continue;
            }
            path.push(y);
            out.push(path.clone());
            extend(graph, path, out);
            path.pop();
        }
    }
    let mut out = Vec::new();
    extend(graph, &mut vec![u], &mut out);
    out
}

/// Brute force: the least delivery time over sequences of distinct pad nodes and simple hop
/// paths, without sharing (`None` when nothing delivers).
fn brute_force_dt(
    graph: &SkywayGraph,
    profile: &Profile,
    swarm: &Swarm,
    source: usize,
    destination: usize,
) -> Option<f64> {
    let planner = Planner::new(graph, profile, swarm, SharingPolicy::None);
    let full = planner.full_battery_mah();
    let speed = planner.speed_m_per_min();
    let n = graph.node_count();
    // arc[u][v]: least tt (+ nt at a pad node) over the simple paths u -> v that fly.
    let mut arc = vec![vec![f64::INFINITY; n]; n];
    for (u, arc_u) in arc.iter_mut().enumerate() {
        if u != source && graph.pads(u) == 0 {
            continue;
        }
        for nodes in simple_paths_from(graph, u) {
            let v = *nodes.last().unwrap();
            if v != destination && graph.pads(v) == 0 {
                continue;
            }
            let path = graph.path_from_nodes(&nodes).unwrap();
            let flight = planner
                .fly(&path, &full, SharingPolicy::None, HopGoal::NodeTimeMin)
                .unwrap();
            if !flight.outcome.feasible {
                continue;
            }
            let mut cost = path.distance_m / speed;
            if v != destination {
                cost += planner
                    .stop_at(v, &flight.outcome.final_battery_mah)
                    .unwrap()
                    .unwrap()
                    .nt_min;
            }
            arc_u[v] = arc_u[v].min(cost);
        }
    }
    fn walk(
        arc: &[Vec<f64>],
        graph: &SkywayGraph,
        destination: usize,
        u: usize,
        cost: f64,
        visited: &mut Vec<bool>,
        best: &mut f64,
    ) {
        *best = best.min(cost + arc[u][destination]);
        for v in 0..arc.len() {
            if visited[v] || v == destination || graph.pads(v) == 0 || !arc[u][v].is_finite() {
                continue;
            }
            visited[v] = true;
            walk(arc, graph, destination, v, cost + arc[u][v], visited, best);
            visited[v] = false;
        }
    }
    let mut visited = vec![false; n];
    visited[source] = true;
    let mut best = f64::INFINITY;
    walk(
        &arc,
        graph,
        destination,
        source,
        0.0,
        &mut visited,
        &mut best,
    );
    best.is_finite().then_some(best)
}

fn options(route: RouteMethod) -> PlanOptions {
    PlanOptions {
        sharing: SharingPolicy::None,
        positioning: Positioning::LocationAware,
        route,
        support: None,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn any_hop_path_optimum_equals_brute_force_and_never_exceeds_any_route_method(seed in any::<u64>()) {
        let (network, graph, request) = random_case(seed);
        let profile = shipped_profile("paper");
        let rule_context = Context::new(&network, &graph, &profile);
        let mut any_context = Context::new(&network, &graph, &profile);
        any_context.hop_paths = HopPaths::Any;
        let any = any_context.plan(&request, &options(RouteMethod::Optimal)).unwrap();
        let optimality = any.plan.route_optimality.unwrap();
        prop_assert_eq!(optimality.hop_paths, HopPaths::Any);
        let violations = check_plan(&network, &profile, &request, &any.swarm, SharingPolicy::None, &any.plan);
        prop_assert!(violations.is_empty(), "checker: {:?}", violations);
        let (s, t) = (graph.index_of(&request.source).unwrap(), graph.index_of(&request.destination).unwrap());
        let brute = brute_force_dt(&graph, &profile, &any.swarm, s, t);
        prop_assert_eq!(any.plan.delivered(), brute.is_some(), "{:?} vs brute force {:?}", any.plan.outcome, brute);
        if let Some(b) = brute {
            prop_assert!((any.plan.dt_min - b).abs() <= REL_TOL * b.max(1.0), "any {} brute {}", any.plan.dt_min, b);
        }
        let mut methods = vec![RouteMethod::Optimal];
        methods.extend(RouteMethod::ALL);
        for route in methods {
            let other = rule_context.plan(&request, &options(route)).unwrap();
            if other.plan.delivered() {
                prop_assert!(any.plan.delivered(), "{:?} delivers, any-path optimum does not", route);
                prop_assert!(
                    any.plan.dt_min <= other.plan.dt_min * (1.0 + REL_TOL),
                    "{:?}: {} < any-path optimum {}", route, other.plan.dt_min, any.plan.dt_min
                );
            }
        }
    }
}

#[test]
fn any_hop_paths_gives_the_hand_optima_of_the_windless_tiny_instances() {
    // instances/tiny/README.md, "Known optima for routes": without wind the shortest path is
    // also the least-energy one, so --hop-paths any gives the hop-path rule's optima.
    for (file, dt_min) in [("flat-detour.json", 23.317), ("flat-skip.json", 16.655)] {
        let (network, graph, profile) = flat_instance(file);
        let mut context = Context::new(&network, &graph, &profile);
        context.hop_paths = HopPaths::Any;
        let request = Request {
            id: "st".into(),
            source: "S".into(),
            destination: "T".into(),
            packages_kg: vec![0.21],
        };
        let r = context
            .plan(&request, &options(RouteMethod::Optimal))
            .unwrap();
        assert!(
            common::close(r.plan.dt_min, dt_min),
            "{file}: {}",
            r.plan.dt_min
        );
    }
}

#[test]
fn hop_paths_any_with_a_sharing_policy_is_refused_with_e0016_and_exit_2() {
    let (net, profile) = (
        repo_arg("instances/tiny/flat-skip.json"),
        repo_arg("instances/tiny/flat.toml"),
    );
    for sharing in ["pb", "fb"] {
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
            sharing,
            "--route",
            "optimal",
            "--hop-paths",
            "any",
        ]);
        assert_eq!(out.status.code(), Some(2), "{out:?}");
        let err = common::stderr(&out);
        assert!(err.contains("[E0016] --hop-paths any"), "{err}");
    }
    let out = swarmplan(&[
        "batch", "--network", &net, "--profile", &profile, "--requests",
        &common::write_tmp(
            "st.json",
            br#"{"schema_version": 1, "requests": [{"id": "st", "source": "S", "destination": "T", "packages_kg": [0.21]}]}"#,
        ),
        "--sharing", "pb", "--route", "optimal", "--hop-paths", "any",
    ]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    assert!(common::stderr(&out).contains("E0016"));
}
