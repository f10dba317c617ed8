//! Skyway graph on the hand-made instances of instances/tiny (facts computed in its README), and the
//! generator's stated properties.

mod common;

use common::repo_path;
use proptest::prelude::*;
use std::collections::VecDeque;
use std::path::PathBuf;
use swarmplan::generate::{generate_network, generate_requests, NetworkParams, RequestParams};
use swarmplan::problem::io::read_json;
use swarmplan::problem::validate::{validate_network, validate_request_set};
use swarmplan::problem::Network;
use swarmplan::problem::SkywayGraph;

fn instance(name: &str) -> PathBuf {
    repo_path("instances").join(name)
}

fn tiny(name: &str) -> SkywayGraph {
    let network: Network = read_json(&instance(&format!("tiny/{name}.json"))).unwrap();
    SkywayGraph::new(&network).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * b.abs().max(1.0)
}

#[test]
fn line4_distances_paths_and_node_facts() {
    let g = tiny("line4");
    let (a, b, c, d) = (0, 1, 2, 3);
    assert_eq!(g.index_of("C"), Some(c));
    assert_eq!(g.id_of(d), "D");
    assert_eq!(g.index_of("Z"), None);
    // A-B 1000 (Euclidean), B-C 1500 (Euclidean), C-D 600 (given, not the straight 500).
    assert_eq!(g.distances_from_m(a), vec![0.0, 1000.0, 2500.0, 3100.0]);
    let p = g.shortest_path(d, b).unwrap();
    assert_eq!(p.nodes, vec![d, c, b]);
    assert!(close(p.distance_m, 2100.0));
    assert!(p.legs.iter().all(|l| close(l.heading_deg, 270.0)));
    let p = g.shortest_path(a, d).unwrap();
    assert_eq!(p.nodes, vec![a, b, c, d]);
    assert_eq!(p.legs.len(), 3);
    assert!(p.legs.iter().all(|l| close(l.heading_deg, 90.0)));
    assert_eq!(p.legs[0].wind_speed_mps, 5.0);
    assert_eq!(p.legs[0].wind_from_deg, 270.0);
    assert_eq!(p.legs[2].distance_m, 600.0);
    assert_eq!(p.legs[2].wind_speed_mps, 13.7);
    // Pads and pad rates.
    assert_eq!(
        (0..4).map(|i| g.pads(i)).collect::<Vec<_>>(),
        vec![1, 0, 2, 1]
    );
    assert_eq!(g.pad_rate_mah_per_min(d, 50.0), 100.0);
    assert_eq!(g.pad_rate_mah_per_min(b, 50.0), 50.0);
    assert_eq!(g.position_m(c), (2500.0, 0.0));
    assert_eq!(
        (0..4).map(|i| g.degree(i)).collect::<Vec<_>>(),
        vec![1, 2, 2, 1]
    );
    assert_eq!(g.neighbors(b), vec![(a, 0), (c, 1)]);
    assert_eq!(g.edge_between(c, b), Some(1));
    assert_eq!(g.edge_between(a, c), None);
    assert!(g.is_fully_connected());
}

#[test]
fn diamond_shortest_distance_is_not_fewest_hops() {
    let g = tiny("diamond");
    let (s, a, b, c, t) = (0, 1, 2, 3, 4);
    // S-B-C-T = 3 x 1000 = 3000 m; S-A-T = 2 x sqrt(1500^2 + 2000^2) = 5000 m.
    let p = g.shortest_path(s, t).unwrap();
    assert_eq!(p.nodes, vec![s, b, c, t]);
    assert!(close(p.distance_m, 3000.0));
    let hops = g.path_from_nodes(&[s, a, t]).unwrap();
    assert_eq!(hops.legs.len(), 2);
    assert!(close(hops.distance_m, 5000.0));
    // Headings: S->A atan2(1500, 2000) = 36.8699 deg, A->T 143.1301 deg, T->A 323.1301 deg.
    assert!((hops.legs[0].heading_deg - 36.869_897_6).abs() < 1e-6);
    assert!((hops.legs[1].heading_deg - 143.130_102_4).abs() < 1e-6);
    assert!((g.leg(t, a).unwrap().heading_deg - 323.130_102_4).abs() < 1e-6);
    let from_s = g.distances_from_m(s);
    for (got, want) in from_s.iter().zip([0.0, 2500.0, 1000.0, 2000.0, 3000.0]) {
        assert!(close(*got, want), "{from_s:?}");
    }
    let from_a = g.distances_from_m(a);
    for (got, want) in from_a.iter().zip([2500.0, 0.0, 3500.0, 3500.0, 2500.0]) {
        assert!(close(*got, want), "{from_a:?}");
    }
    // A path through two non-adjacent nodes does not exist.
    assert!(g.path_from_nodes(&[s, c]).is_none());
    assert!(g.path_from_nodes(&[]).is_none());
    assert!(g.path_from_nodes(&[s, 99]).is_none());
}

#[test]
fn square_ties_break_towards_the_lowest_node_index() {
    let g = tiny("square");
    // P=0, Q=1, R=2, U=3; via Q and via R are both 2000 m.
    let p = g.shortest_path(0, 3).unwrap();
    assert_eq!(p.nodes, vec![0, 1, 3]);
    assert!(close(p.distance_m, 2000.0));
    assert_eq!(g.shortest_path(3, 0).unwrap().nodes, vec![3, 1, 0]);
    assert_eq!(g.shortest_path(2, 2).unwrap().nodes, vec![2]);
    assert_eq!(g.shortest_path(2, 2).unwrap().distance_m, 0.0);
}

#[test]
fn headings_of_the_four_compass_directions() {
    let g = tiny("compass");
    let (o, n, e, s, w) = (0, 1, 2, 3, 4);
    let h = |a, b| g.leg(a, b).unwrap().heading_deg;
    assert_eq!(h(o, n), 0.0);
    assert_eq!(h(o, e), 90.0);
    assert_eq!(h(o, s), 180.0);
    assert_eq!(h(o, w), 270.0);
    assert_eq!(h(n, o), 180.0);
    assert_eq!(h(e, o), 270.0);
    assert_eq!(h(s, o), 0.0);
    assert_eq!(h(w, o), 90.0);
    let p = g.shortest_path(n, e).unwrap();
    assert_eq!(p.nodes, vec![n, o, e]);
    assert_eq!(
        p.legs.iter().map(|l| l.heading_deg).collect::<Vec<_>>(),
        vec![180.0, 90.0]
    );
    assert!(close(p.distance_m, 2000.0));
}

#[test]
fn island_node_is_unreachable() {
    let g = tiny("island");
    let (x, y, z, q) = (0, 1, 2, 3);
    assert!(!g.is_connected(x, q));
    assert!(g.is_connected(y, z));
    assert!(!g.is_fully_connected());
    assert!(g.shortest_path(x, q).is_none());
    assert_eq!(g.distances_from_m(x)[q], f64::INFINITY);
    // Y-Z direct = 1000 sqrt(2) = 1414.2136 m, shorter than 2000 m via X.
    assert!((g.distances_from_m(y)[z] - 1_414.213_562_373).abs() < 1e-6);
    assert_eq!(g.shortest_path(y, z).unwrap().nodes, vec![y, z]);
    assert_eq!(g.pads(q), 3);
    assert_eq!(g.degree(q), 0);
}

#[test]
fn floyd_warshall_matches_hand_computed_diamond_distances() {
    let g = tiny("diamond");
    let all = g.all_pairs_distances_m();
    // Row S and row A from the README.
    for (got, want) in all[0].iter().zip([0.0, 2500.0, 1000.0, 2000.0, 3000.0]) {
        assert!(close(*got, want));
    }
    for (got, want) in all[1].iter().zip([2500.0, 0.0, 3500.0, 3500.0, 2500.0]) {
        assert!(close(*got, want));
    }
    let island = tiny("island").all_pairs_distances_m();
    assert_eq!(island[0][3], f64::INFINITY);
}

/// Breadth-first reachability, written here independently of the library.
fn bfs_reaches_all(n: &Network) -> bool {
    let idx = |id: &str| n.nodes.iter().position(|x| x.id == id).unwrap();
    let mut adj = vec![Vec::new(); n.nodes.len()];
    for s in &n.edges {
        let (a, b) = (idx(&s.from), idx(&s.to));
        adj[a].push(b);
        adj[b].push(a);
    }
    let mut seen = vec![false; n.nodes.len()];
    let mut queue = VecDeque::from([0]);
    seen[0] = true;
    while let Some(u) = queue.pop_front() {
        for &v in &adj[u] {
            if !seen[v] {
                seen[v] = true;
                queue.push_back(v);
            }
        }
    }
    seen.iter().all(|&s| s)
}

fn degrees(n: &Network) -> Vec<usize> {
    n.nodes
        .iter()
        .map(|x| {
            n.edges
                .iter()
                .filter(|s| s.from == x.id || s.to == x.id)
                .count()
        })
        .collect()
}

fn check_generated_network(n: &Network, nodes: usize) {
    assert_eq!(n.nodes.len(), nodes);
    assert!(validate_network(n).is_empty(), "{:?}", validate_network(n));
    assert!(bfs_reaches_all(n));
    for (i, d) in degrees(n).into_iter().enumerate() {
        assert!((2..=4).contains(&d), "node {i} has degree {d}");
    }
    assert!(n.nodes.iter().all(|x| x.pads <= 4));
    assert!(n.nodes.iter().any(|x| x.pads > 0));
    assert!(n.nodes.iter().all(|x| x.x_m >= 0.0 && x.y_m >= 0.0));
    for s in &n.edges {
        assert!(s.wind_speed_mps >= 0.0 && s.wind_speed_mps < 13.8);
        assert!((0.0..360.0).contains(&s.wind_from_deg));
    }
}

#[test]
fn default_generated_network_has_the_stated_properties() {
    let n = generate_network(&NetworkParams {
        seed: 7,
        ..NetworkParams::default()
    })
    .unwrap();
    check_generated_network(&n, 195);
    // 195 nodes on a 14 x 14 grid of 500 m: every node within [0, 13 x 500 + 2 x 150] = [0, 6800] m.
    assert!(n.nodes.iter().all(|x| x.x_m <= 6800.0 && x.y_m <= 6800.0));
}

#[test]
fn same_seed_gives_the_same_network_and_requests() {
    let p = NetworkParams {
        seed: 42,
        ..NetworkParams::default()
    };
    let a = generate_network(&p).unwrap();
    let b = generate_network(&p).unwrap();
    assert_eq!(
        serde_json::to_string(&a).unwrap(),
        serde_json::to_string(&b).unwrap()
    );
    let c = generate_network(&NetworkParams { seed: 43, ..p }).unwrap();
    assert_ne!(a, c);
    let g = SkywayGraph::new(&a).unwrap();
    let rp = RequestParams {
        count: 300,
        seed: 5,
        max_package_kg: 1.4,
    };
    let r1 = generate_requests(&g, &rp).unwrap();
    let r2 = generate_requests(&g, &rp).unwrap();
    assert_eq!(
        serde_json::to_string(&r1).unwrap(),
        serde_json::to_string(&r2).unwrap()
    );
}

#[test]
fn generated_requests_have_the_stated_properties() {
    let g = tiny("island");
    let set = generate_requests(
        &g,
        &RequestParams {
            count: 500,
            seed: 9,
            max_package_kg: 0.8,
        },
    )
    .unwrap();
    assert_eq!(set.requests.len(), 500);
    assert_eq!(set.seed, Some(9));
    assert!(validate_request_set(&set, &g, 0.8).is_empty());
    for r in &set.requests {
        // Q is isolated, so it can never be a source or destination.
        assert_ne!(r.source, "Q");
        assert_ne!(r.destination, "Q");
        assert_ne!(r.source, r.destination);
        assert!((2..=8).contains(&r.packages_kg.len()));
        assert!(r.packages_kg.iter().all(|&m| m > 0.0 && m <= 0.8));
    }
    // All six ordered pairs of X, Y, Z appear in 500 uniform draws (each has probability 1/6).
    let mut pairs: Vec<(String, String)> = set
        .requests
        .iter()
        .map(|r| (r.source.clone(), r.destination.clone()))
        .collect();
    pairs.sort();
    pairs.dedup();
    assert_eq!(pairs.len(), 6);
}

#[test]
fn shipped_195_node_instances_validate() {
    // sparse-195 uses paper-195's requests (see instances/sparse-195/README.md).
    for name in ["paper-195", "sparse-195"] {
        let network: Network = read_json(&instance(&format!("{name}/network.json"))).unwrap();
        assert!(validate_network(&network).is_empty(), "{name}");
        check_generated_network(&network, 195);
        let g = SkywayGraph::new(&network).unwrap();
        let set: swarmplan::problem::RequestSet =
            read_json(&instance("paper-195/requests.json")).unwrap();
        assert_eq!(set.requests.len(), 10_000, "{name}");
        let v = validate_request_set(&set, &g, 1.4);
        assert!(v.is_empty(), "{name}: {:?}", &v[..v.len().min(5)]);
    }
}

#[test]
fn sparse_195_is_paper_195_stretched_to_1000_m_blocks() {
    // Both come from seed 195 with spacing 500 m and 1000 m: the generator scales every position
    // draw with the spacing, so the node ids, pads and edges are the same and every
    // coordinate is doubled (to the 0.1 m rounding of the files).
    let a: Network = read_json(&instance("paper-195/network.json")).unwrap();
    let b: Network = read_json(&instance("sparse-195/network.json")).unwrap();
    assert_eq!(a.nodes.len(), b.nodes.len());
    for (x, y) in a.nodes.iter().zip(&b.nodes) {
        assert_eq!((&x.id, x.pads), (&y.id, y.pads));
        assert!((2.0 * x.x_m - y.x_m).abs() <= 0.2 && (2.0 * x.y_m - y.y_m).abs() <= 0.2);
    }
    let ends = |n: &Network| {
        n.edges
            .iter()
            .map(|s| (s.from.clone(), s.to.clone()))
            .collect::<Vec<_>>()
    };
    assert_eq!(ends(&a), ends(&b));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn every_generated_network_is_connected_with_degree_two_to_four(
        nodes in 3usize..80, seed in any::<u64>()
    ) {
        let n = generate_network(&NetworkParams { nodes, seed, spacing_m: 300.0 }).unwrap();
        check_generated_network(&n, nodes);
    }

    #[test]
    fn dijkstra_path_length_equals_floyd_warshall_distance(seed in any::<u64>()) {
        let n = generate_network(&NetworkParams { nodes: 30, seed, spacing_m: 400.0 }).unwrap();
        let g = SkywayGraph::new(&n).unwrap();
        let all = g.all_pairs_distances_m();
        for (a, row) in all.iter().enumerate() {
            for (b, &d) in row.iter().enumerate() {
                let p = g.shortest_path(a, b).unwrap();
                prop_assert!((p.distance_m - d).abs() < 1e-6);
                prop_assert_eq!(p.nodes.first(), Some(&a));
                prop_assert_eq!(p.nodes.last(), Some(&b));
            }
        }
    }

    #[test]
    fn shortest_path_equals_the_best_of_all_simple_paths(nodes in 4usize..9, seed in any::<u64>()) {
        let n = generate_network(&NetworkParams { nodes, seed, spacing_m: 250.0 }).unwrap();
        let g = SkywayGraph::new(&n).unwrap();
        // Brute force: depth-first enumeration of every simple path, lengths from the coordinates.
        let pos: Vec<(f64, f64)> = n.nodes.iter().map(|x| (x.x_m, x.y_m)).collect();
        let idx = |id: &str| n.nodes.iter().position(|x| x.id == id).unwrap();
        let mut adj = vec![Vec::new(); nodes];
        for s in &n.edges {
            let (a, b) = (idx(&s.from), idx(&s.to));
            let l = ((pos[a].0 - pos[b].0).powi(2) + (pos[a].1 - pos[b].1).powi(2)).sqrt();
            adj[a].push((b, l));
            adj[b].push((a, l));
        }
        fn best(adj: &[Vec<(usize, f64)>], u: usize, t: usize, seen: &mut Vec<bool>, len: f64) -> f64 {
            if u == t {
                return len;
            }
            let mut out = f64::INFINITY;
            for &(v, l) in &adj[u] {
                if !seen[v] {
                    seen[v] = true;
                    out = out.min(best(adj, v, t, seen, len + l));
                    seen[v] = false;
                }
            }
            out
        }
        for a in 0..nodes {
            for b in 0..nodes {
                let mut seen = vec![false; nodes];
                seen[a] = true;
                let want = best(&adj, a, b, &mut seen, 0.0);
                let p = g.shortest_path(a, b).unwrap();
                prop_assert!((p.distance_m - want).abs() < 1e-6, "{} -> {}: {} vs {}", a, b, p.distance_m, want);
                prop_assert_eq!(p.legs.len() + 1, p.nodes.len());
            }
        }
    }
}
