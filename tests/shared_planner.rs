//! The planning types own their data and are `Send + Sync`: a context or a planner can be held
//! by another thread (or a Python object) and one planner may compose on several threads at once.
//! What a composition counts (its hop solves) comes back in its plan, so compositions running
//! side by side on one planner give the plans and counts each gives alone on a fresh planner.

mod common;

use std::sync::Arc;
use swarmplan::compose::{Context, EdgeFactorCache, Plan, Planner, RouteMethod};
use swarmplan::eaas::SharingPolicy;
use swarmplan::precompose::Positioning;

fn send_and_sync<T: Send + Sync>() {}

/// Index of paper-195's request r00001 (n176 -> n020, two packages): its routes stop on the way,
/// with exact hop solves (17 for Algorithm 1, 9 for A* and Dijkstra).
const R00001: usize = 1;

#[test]
fn planning_types_are_send_and_sync() {
    send_and_sync::<Context>();
    send_and_sync::<Planner>();
    send_and_sync::<EdgeFactorCache>();
}

/// Every (request, route) pair composed on a fresh planner of its own, one at a time.
fn alone(context: &Context, jobs: &[(usize, RouteMethod)]) -> Vec<Plan> {
    let (_, _, _, requests) = common::paper_195();
    jobs.iter()
        .map(|&(r, method)| {
            let choice = context
                .swarm_for(&requests[r], Positioning::LocationAware, Some(1))
                .unwrap();
            context
                .planner(&choice.swarm, SharingPolicy::Exact)
                .compose(choice.source, choice.destination, method)
                .unwrap()
        })
        .collect()
}

#[test]
fn compositions_side_by_side_on_one_planner_match_each_alone() {
    let (network, graph, profile, requests) = common::paper_195();
    // Shared, not copied: the context holds the same graph and profile.
    let context = Context::new(&network, Arc::new(graph), Arc::new(profile));
    // One swarm, one planner, four compositions at once (two of them the same).
    let choice = context
        .swarm_for(&requests[R00001], Positioning::LocationAware, Some(1))
        .unwrap();
    let planner = Arc::new(context.planner(&choice.swarm, SharingPolicy::Exact));
    let methods = [
        RouteMethod::Sequential,
        RouteMethod::Astar,
        RouteMethod::Dijkstra,
        RouteMethod::Sequential,
    ];
    let together: Vec<Plan> = std::thread::scope(|scope| {
        let handles: Vec<_> = methods
            .iter()
            .map(|&method| {
                let planner = Arc::clone(&planner);
                let (s, d) = (choice.source, choice.destination);
                scope.spawn(move || planner.compose(s, d, method).unwrap())
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let jobs: Vec<(usize, RouteMethod)> = methods.iter().map(|&m| (R00001, m)).collect();
    let expected = alone(&context, &jobs);
    for ((got, want), method) in together.iter().zip(&expected).zip(methods) {
        assert!(
            want.hop_solves.is_some_and(|c| c.solves > 0),
            "{method}: no hop solve"
        );
        assert_eq!(
            got.hop_solves, want.hop_solves,
            "{method}: hop solve counts"
        );
        assert_eq!(got, want, "{method}: plan");
    }
}
