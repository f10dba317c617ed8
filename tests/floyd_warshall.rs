//! The dense Floyd–Warshall of `network::floyd_warshall` against petgraph 0.8's
//! `floyd_warshall_path`: the same distances, the same predecessors, hence the same routes, on
//! random directed graphs with ties (small integer costs), zero costs, parallel edges, self-loops
//! and unreachable pairs.

use petgraph::graph::{DiGraph, NodeIndex};
use proptest::prelude::*;
use swarmplan::network::floyd_warshall::{floyd_warshall, UNREACHABLE};

/// petgraph's distances (row-major, `f64::MAX` where unreachable) and predecessors.
fn petgraph_all_pairs(
    n: usize,
    edges: &[(usize, usize, f64)],
) -> (Vec<f64>, Vec<Vec<Option<usize>>>) {
    let mut g: DiGraph<(), f64> = DiGraph::new();
    for _ in 0..n {
        g.add_node(());
    }
    for &(u, v, c) in edges {
        g.add_edge(NodeIndex::new(u), NodeIndex::new(v), c);
    }
    let (dist, prev) = petgraph::algo::floyd_warshall::floyd_warshall_path(&g, |e| *e.weight())
        .expect("non-negative costs");
    let mut matrix = vec![0.0; n * n];
    for i in 0..n {
        for j in 0..n {
            matrix[i * n + j] = dist[&(NodeIndex::new(i), NodeIndex::new(j))];
        }
    }
    (matrix, prev)
}

/// The path read back from petgraph's predecessors, as `Planner::baseline_route` read it.
fn petgraph_path(prev: &[Vec<Option<usize>>], source: usize, target: usize) -> Option<Vec<usize>> {
    let mut path = vec![target];
    let mut at = target;
    while at != source {
        match prev[source][at] {
            Some(p) if path.len() <= prev.len() => {
                path.push(p);
                at = p;
            }
            _ => return None,
        }
    }
    path.reverse();
    Some(path)
}

/// A random directed graph: `n` nodes, edges with costs from `costs` (integers give ties).
fn graph() -> impl Strategy<Value = (usize, Vec<(usize, usize, f64)>)> {
    (1usize..24).prop_flat_map(|n| {
        let edge = (
            0..n,
            0..n,
            prop_oneof![(0u32..6).prop_map(f64::from), 0.0f64..100.0,],
        );
        (Just(n), prop::collection::vec(edge, 0..(4 * n)))
    })
}

fn assert_same(n: usize, edges: &[(usize, usize, f64)]) -> Result<(), TestCaseError> {
    let dense = floyd_warshall(n, edges);
    let (dist, prev) = petgraph_all_pairs(n, edges);
    prop_assert_eq!(dense.distances(), &dist[..]);
    for i in 0..n {
        for j in 0..n {
            prop_assert_eq!(dense.predecessor(i, j), prev[i][j], "prev[{}][{}]", i, j);
            prop_assert_eq!(dense.path(i, j), petgraph_path(&prev, i, j));
            let d = dist[i * n + j];
            prop_assert_eq!(dense.distance(i, j), (d != UNREACHABLE).then_some(d));
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn dense_floyd_warshall_equals_petgraph_on_random_graphs((n, edges) in graph()) {
        assert_same(n, &edges)?;
    }
}

#[test]
fn dense_floyd_warshall_equals_petgraph_on_the_paper_195_baseline_costs() {
    // The network's edges with costs from their lengths and a per-node charge, many of them tied.
    let network: swarmplan::problem::Network = swarmplan::problem::io::read_json(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("instances/paper-195/network.json"),
    )
    .unwrap();
    let g = swarmplan::problem::SkywayGraph::new(&network).unwrap();
    let mut edges = Vec::new();
    for u in 0..g.node_count() {
        for &(v, _) in g.neighbors(u) {
            let distance_m = g.path_from_nodes(&[u, v]).unwrap().distance_m;
            edges.push((
                u,
                v,
                (distance_m / 500.0).round() + f64::from(g.pads(v) % 3),
            ));
        }
    }
    assert_same(g.node_count(), &edges).unwrap();
}
