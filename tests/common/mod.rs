//! Fixtures shared by the integration tests: the binary, paths into the repository and into a
//! temporary folder per test binary, the shipped instances, float tolerances, the known optima of
//! the hop models and small hop builders, the README's and the guide's command blocks (`docs`).
//! Each test binary uses a subset of them.
#![allow(dead_code)]

pub mod docs;
pub mod model_files;

use nalgebra::Vector2;
use serde::Deserialize;
use std::path::PathBuf;
use std::process::{Command, Output};
use swarmplan::eaas::exact::{Objective, Reorder};
use swarmplan::eaas::{DroneState, HopProblem, LegRates};
use swarmplan::problem::io::{read_json, read_toml};
use swarmplan::problem::{Network, Profile, Request, RequestSet, Role, SkywayGraph};

// ---------------------------------------------------------------------------------------------
// The binary and files.

/// Runs the `swarmplan` binary with `args` and waits for it.
pub fn swarmplan(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args(args)
        .output()
        .expect("the binary runs")
}

/// `swarmplan eaas` on hop `hop` of request r00001 of the shipped paper-195 instance (the
/// default instance of `eaas`) with `methods`, then `extra`.
pub fn eaas_r00001(hop: &str, methods: &str, extra: &[&str]) -> Output {
    let mut args = vec![
        "eaas",
        "--request-id",
        "r00001",
        "--hop",
        hop,
        "--methods",
        methods,
    ];
    args.extend_from_slice(extra);
    swarmplan(&args)
}

/// Its standard error as text.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).to_string()
}

/// A path into the repository, such as `instances/tiny/line4.json`.
pub fn repo_path(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(rel)
}

/// [`repo_path`] as a command-line argument.
pub fn repo_arg(rel: &str) -> String {
    repo_path(rel).to_str().unwrap().to_string()
}

/// A path for a file named `name` in this test binary's own temporary folder (made if missing).
pub fn tmp(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(env!("CARGO_CRATE_NAME"));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// Writes `bytes` to [`tmp`]`(name)` and returns its path as a command-line argument. Written
/// aside, then renamed: the tests of a binary run in parallel and may write the same file, and
/// a reader must never see it truncated or half written.
pub fn write_tmp(name: &str, bytes: &[u8]) -> String {
    static WRITES: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let path = tmp(name);
    let n = WRITES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let file = path.file_name().unwrap().to_string_lossy().into_owned();
    let aside = path.with_file_name(format!("{file}.{}-{n}.part", std::process::id()));
    std::fs::write(&aside, bytes).unwrap();
    std::fs::rename(&aside, &path).unwrap();
    path.to_str().unwrap().to_string()
}

// ---------------------------------------------------------------------------------------------
// Shipped instances.

/// A shipped profile, `instances/profiles/<name>.toml`.
pub fn shipped_profile(name: &str) -> Profile {
    read_toml(&repo_path(&format!("instances/profiles/{name}.toml")))
        .expect("shipped profile parses")
}

/// The paper-195 network, its graph, the paper profile and the shipped requests.
pub fn paper_195() -> (Network, SkywayGraph, Profile, Vec<Request>) {
    let network: Network = read_json(&repo_path("instances/paper-195/network.json")).unwrap();
    let graph = SkywayGraph::new(&network).unwrap();
    let profile = shipped_profile("paper");
    let set: RequestSet = read_json(&repo_path("instances/paper-195/requests.json")).unwrap();
    (network, graph, profile, set.requests)
}

/// A tiny network `instances/tiny/<file>`, its graph, and the flat profile of the tiny instances.
pub fn flat_instance(file: &str) -> (Network, SkywayGraph, Profile) {
    let dir = repo_path("instances/tiny");
    let network: Network = read_json(&dir.join(file)).unwrap();
    let graph = SkywayGraph::new(&network).unwrap();
    let profile: Profile = read_toml(&dir.join("flat.toml")).unwrap();
    (network, graph, profile)
}

/// The request of flat-stop (instances/tiny/README.md): A to B with packages of 0.21, 0.21 and
/// 0.44 kg.
pub fn flat_stop_request(id: &str) -> Request {
    Request {
        id: id.into(),
        source: "A".into(),
        destination: "B".into(),
        packages_kg: vec![0.21, 0.21, 0.44],
    }
}

/// [`flat_stop_request`] on the command line.
pub const FLAT_STOP_REQUEST_ARGS: [&str; 6] =
    ["--from", "A", "--to", "B", "--packages", "0.21,0.21,0.44"];

// ---------------------------------------------------------------------------------------------
// Tolerances.

/// Relative tolerance of computed against expected values.
pub const TOL: f64 = 1e-6;

/// `a` equals `b` within [`TOL`] relative to `b` (absolute below 1).
pub fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= TOL * (1.0 + b.abs())
}

/// Asserts [`close`]`(got, expected)`, naming `what`.
pub fn assert_close(got: f64, expected: f64, what: &str) {
    assert!(
        close(got, expected),
        "{what}: got {got}, expected {expected}"
    );
}

// ---------------------------------------------------------------------------------------------
// Hops.

/// The known optima of the hop models, `instances/eaas/known_optima.json`.
#[derive(Deserialize)]
pub struct KnownOptima {
    pub schema_version: u32,
    pub instances: Vec<Known>,
}

/// One hop of the table, its optimum and where that number comes from.
#[derive(Deserialize)]
pub struct Known {
    pub name: String,
    pub description: String,
    pub problem: HopProblem,
    pub objective: Objective,
    pub reorder: Reorder,
    pub period_min: f64,
    pub optimum: f64,
    pub source: String,
    /// The optimum over every continuous-time schedule (the configuration LP's value).
    pub continuous_optimum: f64,
    pub continuous_source: String,
}

/// Reads `instances/eaas/known_optima.json`.
pub fn known_optima() -> KnownOptima {
    let text = std::fs::read_to_string(repo_path("instances/eaas/known_optima.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

/// A drone of a hop.
pub fn drone(role: Role, capacity_mah: f64, battery_mah: f64) -> DroneState {
    DroneState {
        role,
        capacity_mah,
        battery_mah,
    }
}

/// One leg; `rates[d]` is drone d's rate in every slot.
pub fn uniform_leg(duration_min: f64, rates: &[f64]) -> LegRates {
    LegRates {
        duration_min,
        rate_mah_per_min: rates
            .iter()
            .map(|&r| vec![r; rates.len()])
            .collect::<Vec<_>>()
            .into(),
    }
}

/// Slots on the x axis at the given abscissae, drone d in slot d.
pub fn line(xs: &[f64]) -> (Vec<Vector2<f64>>, Vec<usize>) {
    (
        xs.iter().map(|&x| Vector2::new(x, 0.0)).collect(),
        (0..xs.len()).collect(),
    )
}

// ---------------------------------------------------------------------------------------------
// Random small networks for the route properties.

/// The shape of [`random_network_case`]'s networks.
pub struct RandomNetworkShape {
    /// Node counts drawn from.
    pub nodes: std::ops::RangeInclusive<usize>,
    /// Side of the square the nodes are spread over, m.
    pub square_m: f64,
    /// Most pads at a node (about 70% of the nodes have 1 to this many).
    pub max_pads: u32,
    /// Wind speeds are drawn from `[0, max_wind_mps)`, m/s.
    pub max_wind_mps: f64,
}

/// A random connected network of `shape` (a spanning path in random order, then a few chords),
/// with a node with pads (rule E1105), and a request of 1 to 3 packages between the two nodes
/// farthest apart by shortest path.
pub fn random_network_case(
    seed: u64,
    shape: &RandomNetworkShape,
) -> (Network, SkywayGraph, Request) {
    use rand::{Rng, SeedableRng};
    use swarmplan::problem::{Edge, Node};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let n = rng.random_range(shape.nodes.clone());
    let mut nodes: Vec<Node> = (0..n)
        .map(|i| Node {
            id: format!("v{i}"),
            x_m: rng.random_range(0.0..shape.square_m),
            y_m: rng.random_range(0.0..shape.square_m),
            pads: if rng.random_bool(0.7) {
                rng.random_range(1..=shape.max_pads)
            } else {
                0
            },
            pad_charge_rate_mah_per_min: None,
        })
        .collect();
    if nodes.iter().all(|v| v.pads == 0) {
        nodes[0].pads = 1;
    }
    let mut order: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        order.swap(i, rng.random_range(0..=i));
    }
    let mut pairs: Vec<(usize, usize)> = order.windows(2).map(|w| (w[0], w[1])).collect();
    for _ in 0..n {
        let (a, b) = (rng.random_range(0..n), rng.random_range(0..n));
        let known = pairs.contains(&(a, b)) || pairs.contains(&(b, a));
        if a != b && !known {
            pairs.push((a, b));
        }
    }
    let edges = pairs
        .into_iter()
        .map(|(a, b)| Edge {
            from: format!("v{a}"),
            to: format!("v{b}"),
            distance_m: None,
            wind_speed_mps: rng.random_range(0.0..shape.max_wind_mps),
            wind_from_deg: rng.random_range(0.0..360.0),
        })
        .collect();
    let network = Network {
        schema_version: swarmplan::problem::SCHEMA_VERSION,
        name: Some(format!("random-{seed}")),
        nodes,
        edges,
    };
    let graph = SkywayGraph::new(&network).unwrap();
    let mut far = (0, 1, -1.0);
    for a in 0..n {
        for (b, &x) in graph.distances_from_m(a).iter().enumerate() {
            if x.is_finite() && x > far.2 {
                far = (a, b, x);
            }
        }
    }
    let packages = rng.random_range(1..=3);
    let request = Request {
        id: format!("q{seed}"),
        source: format!("v{}", far.0),
        destination: format!("v{}", far.1),
        packages_kg: (0..packages)
            .map(|_| (rng.random_range(0.2..1.2f64) * 100.0).round() / 100.0)
            .collect(),
    };
    (network, graph, request)
}

/// A small random hop with integer rates (0-3 mAh/min), batteries (3-12 of 12 mAh), durations
/// (1-2 min) and `rho = 1` mAh/min: 2-3 delivery and 1-2 support drones on a line of slots 1 m
/// apart, shuffled, so some consumers are out of range of R = 1.2 m.
pub fn integral_hop(seed: u64) -> HopProblem {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let nd = rng.random_range(2..=3usize);
    let ns = rng.random_range(1..=2usize);
    let n = nd + ns;
    let legs = (0..rng.random_range(1..=2usize))
        .map(|_| LegRates {
            duration_min: rng.random_range(1..=2u32) as f64,
            rate_mah_per_min: (0..n)
                .map(|_| (0..n).map(|_| rng.random_range(0..=3u32) as f64).collect())
                .collect::<Vec<_>>()
                .into(),
        })
        .collect();
    let drones = (0..n)
        .map(|d| {
            let cap = 12.0;
            DroneState {
                role: if d < nd {
                    Role::Delivery
                } else {
                    Role::Support
                },
                capacity_mah: cap,
                battery_mah: rng.random_range(3..=12u32) as f64,
            }
        })
        .collect();
    // Slots 1 m apart on a line, shuffled: some consumers out of range of R = 1.2 m.
    let mut initial_slot: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        let j = rng.random_range(0..=i);
        initial_slot.swap(i, j);
    }
    HopProblem {
        legs,
        drones,
        slots_m: (0..n).map(|q| Vector2::new(q as f64, 0.0)).collect(),
        initial_slot,
        rho_mah_per_min: 1.0,
        range_m: 1.2,
        gamma_mah: 12.0,
        lambda_mah: rng.random_range(1..=2u32) as f64,
        delta_mah: rng.random_range(0..=2u32) as f64,
    }
}

/// The least delivery time over every simple sequence of distinct pad nodes from `source` to
/// `destination` (`None` when none delivers), by enumeration: from each stop, the hop into the
/// destination flies without sharing or with the policy; the hop into a pad node flies with the
/// policy, and the stop's node time is that of the arrival batteries.
pub fn enumerate_min_dt(
    graph: &SkywayGraph,
    profile: &Profile,
    swarm: &swarmplan::problem::Swarm,
    sharing: swarmplan::eaas::SharingPolicy,
    source: usize,
    destination: usize,
) -> Option<f64> {
    let planner = swarmplan::compose::Planner::new(graph, profile, swarm, sharing);
    let full = planner.full_battery_mah();
    let speed = planner.speed_m_per_min();
    let mut visited = vec![false; graph.node_count()];
    visited[source] = true;
    let mut best: Option<f64> = None;
    // Depth-first over sequences: (node, cost so far).
    fn walk(
        ctx: &(
            &swarmplan::compose::Planner,
            &SkywayGraph,
            &[f64],
            f64,
            usize,
            swarmplan::eaas::SharingPolicy,
        ),
        u: usize,
        cost_min: f64,
        visited: &mut Vec<bool>,
        best: &mut Option<f64>,
    ) {
        let (planner, graph, full, speed, destination, sharing) = *ctx;
        if let Some(path) = graph.shortest_path(u, destination) {
            let plain = planner
                .fly(
                    &path,
                    full,
                    swarmplan::eaas::SharingPolicy::None,
                    swarmplan::eaas::exact_hop::HopGoal::Feasible,
                )
                .unwrap();
            let flies = plain.outcome.feasible
                || sharing.shares()
                    && planner
                        .fly(
                            &path,
                            full,
                            sharing,
                            swarmplan::eaas::exact_hop::HopGoal::Feasible,
                        )
                        .unwrap()
                        .outcome
                        .feasible;
            if flies {
                let dt = cost_min + path.distance_m / speed;
                if best.is_none_or(|b| dt < b) {
                    *best = Some(dt);
                }
            }
        }
        for v in 0..graph.node_count() {
            if visited[v] || v == destination || graph.pads(v) == 0 {
                continue;
            }
            let Some(path) = graph.shortest_paths_to(u).reversed_path_from(v) else {
                continue;
            };
            let flight = planner
                .fly(
                    &path,
                    full,
                    sharing,
                    swarmplan::eaas::exact_hop::HopGoal::NodeTimeMin,
                )
                .unwrap();
            if !flight.outcome.feasible {
                continue;
            }
            let stop = planner
                .stop_at(v, &flight.outcome.final_battery_mah)
                .unwrap()
                .unwrap();
            visited[v] = true;
            let cost = cost_min + path.distance_m / speed + stop.nt_min;
            walk(ctx, v, cost, visited, best);
            visited[v] = false;
        }
    }
    let ctx = (
        &planner,
        graph,
        full.as_slice(),
        speed,
        destination,
        sharing,
    );
    walk(&ctx, source, 0.0, &mut visited, &mut best);
    best
}

/// Every `.rs` file under `dir`, recursively, appended to `out`.
pub fn rust_files(dir: &std::path::Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Asserts that the independent checker finds no violation in the plan of report `r`.
pub fn assert_checked(
    network: &Network,
    profile: &Profile,
    request: &Request,
    r: &swarmplan::compose::RequestReport,
) {
    let v = swarmplan::check::check_plan(
        network,
        profile,
        request,
        &r.swarm,
        r.options.sharing,
        &r.plan,
    );
    assert!(
        v.is_empty(),
        "{} {:?}: checker says {v:?}",
        request.id,
        r.options
    );
}

/// Shards 0/2 and 1/2 of a 4-request bench run (exact subset: the first request), made fresh in
/// [`tmp`]`(name)/s0` and `s1`.
pub fn bench_shards(name: &str) -> (PathBuf, PathBuf) {
    let base = tmp(name);
    let _ = std::fs::remove_dir_all(&base);
    let dirs = (base.join("s0"), base.join("s1"));
    for (dir, shard) in [(&dirs.0, "0/2"), (&dirs.1, "1/2")] {
        let out = swarmplan(&[
            "bench",
            "--request-limit",
            "4",
            "--exact-limit",
            "1",
            "--shard",
            shard,
            "--out",
            dir.to_str().unwrap(),
        ]);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    }
    dirs
}
