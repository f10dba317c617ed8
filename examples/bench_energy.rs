//! Speed of the energy model: `cargo run --release --example bench_energy`.
//! Times `rate_matrix_mah_per_min` (one call per leg of every candidate path in the route planner)
//! for swarms of 5, 10 and 20 drones, and `select_formation` on a 200-edge network.

use std::time::Instant;
use swarmplan::energy::rate_matrix_mah_per_min;
use swarmplan::precompose::{build_swarm, select_formation, Positioning};
use swarmplan::problem::io::read_toml;
use swarmplan::problem::FormationKind;
use swarmplan::problem::{Edge, Network, Node, Profile, Wind};

fn main() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("instances/profiles/paper.toml");
    let p: Profile = read_toml(&path).expect("paper profile");
    for n in [5usize, 10, 20] {
        let packages = vec![0.7; n - 2];
        let s = build_swarm(
            &p,
            FormationKind::Vee,
            &packages,
            2,
            Positioning::LocationAware,
        );
        let calls = 100_000;
        let t = Instant::now();
        let mut acc = 0.0;
        for i in 0..calls {
            let wind = Wind {
                speed_mps: 5.0 + (i % 7) as f64,
                from_deg: (i % 360) as f64,
            };
            acc += rate_matrix_mah_per_min(&p, &s, (i * 7 % 360) as f64, &wind)[0][0];
        }
        let per_call_us = t.elapsed().as_secs_f64() * 1e6 / calls as f64;
        println!(
            "rate_matrix_mah_per_min, {n:2} drones: {per_call_us:.2} us/call (checksum {acc:.1})"
        );
    }
    // A ring of 200 nodes, 200 edges with varied winds.
    let nodes: Vec<Node> = (0..200)
        .map(|i| {
            let a = i as f64 / 200.0 * std::f64::consts::TAU;
            Node {
                id: format!("n{i}"),
                x_m: 5000.0 * a.cos(),
                y_m: 5000.0 * a.sin(),
                pads: 1,
                pad_charge_rate_mah_per_min: None,
            }
        })
        .collect();
    let edges: Vec<Edge> = (0..200)
        .map(|i| Edge {
            from: format!("n{i}"),
            to: format!("n{}", (i + 1) % 200),
            distance_m: None,
            wind_speed_mps: (i % 13) as f64,
            wind_from_deg: (i * 37 % 360) as f64,
        })
        .collect();
    let net = Network {
        schema_version: 1,
        name: None,
        nodes,
        edges,
    };
    let t = Instant::now();
    let (kind, wind) = select_formation(&net, &p);
    println!(
        "select_formation, 200 edges: {:.2} ms -> {} for {:.2} m/s from {} deg",
        t.elapsed().as_secs_f64() * 1e3,
        kind,
        wind.speed_mps,
        wind.from_deg
    );
}
