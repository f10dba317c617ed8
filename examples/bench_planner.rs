//! Benchmark of the route planner on paper-195 (or another instance): Floyd–Warshall on the
//! baselines' edge costs, dense (`network::floyd_warshall`) against petgraph's
//! `floyd_warshall_path` (what the Floyd–Warshall baseline used before), and `batch`-like planning
//! throughput on the first requests of the request set, on one thread.
//!
//! ```text
//! cargo run --release --example bench_planner -- [--limit 100] [--runs 7] [--warmup 1]
//!     [--fw-runs 101] [--network F] [--profile F] [--requests F]
//! ```
//!
//! Every measurement is repeated after warm-up runs and printed as median, quartiles and range:
//! - `fw dense` / `fw petgraph`: one all-pairs solve on the edge costs `tt + nt` of the first
//!   request's swarm (PB, location-aware), ms per run;
//! - `one combination`: the first `--limit` requests with `batch`'s default combination (pb,
//!   location-aware, sequential), requests per second;
//! - `grid, per combination`: the same requests with every combination of `batch --all`, each
//!   combination planned apart (`Context::plan`, what `batch` did before it shared work), requests
//!   x combinations per second;
//! - `grid, per request`: the same grid, every combination of a request at once
//!   (`Context::plan_each`, what `batch` does), requests x combinations per second.
//!
//! The two grid runs must give the same plans; the benchmark checks it and stops otherwise.

use clap::Parser;
use petgraph::graph::{DiGraph, NodeIndex};
use std::hint::black_box;
use std::path::PathBuf;
use std::time::Instant;
use swarmplan::cli::inputs::InstanceArgs;
use swarmplan::compose::{Context, PlanOptions, Planner, RouteMethod};
use swarmplan::eaas::SharingPolicy;
use swarmplan::network::floyd_warshall::floyd_warshall;
use swarmplan::precompose::Positioning;
use swarmplan::problem::inputs::load_requests;

/// Floyd–Warshall and planning throughput.
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    instance: InstanceArgs,
    /// Request set (JSON) [default: the shipped instances/paper-195/requests.json].
    #[arg(long, value_name = "FILE")]
    requests: Option<PathBuf>,
    /// Requests planned per throughput run.
    #[arg(long, value_name = "N", default_value_t = 100)]
    limit: usize,
    /// Measured runs of each throughput figure.
    #[arg(long, default_value_t = 7)]
    runs: usize,
    /// Warm-up runs of each throughput figure, not measured.
    #[arg(long, default_value_t = 1)]
    warmup: usize,
    /// Measured runs of each Floyd–Warshall (after as many warm-up runs).
    #[arg(long, default_value_t = 101)]
    fw_runs: usize,
}

/// Median, quartiles and range of a sample.
struct Spread {
    median: f64,
    q1: f64,
    q3: f64,
    min: f64,
    max: f64,
}

impl Spread {
    fn of(mut sample: Vec<f64>) -> Spread {
        sample.sort_by(f64::total_cmp);
        let at = |q: f64| {
            let x = q * (sample.len() - 1) as f64;
            let (lo, hi) = (x.floor() as usize, x.ceil() as usize);
            sample[lo] + (sample[hi] - sample[lo]) * (x - lo as f64)
        };
        Spread {
            median: at(0.5),
            q1: at(0.25),
            q3: at(0.75),
            min: sample[0],
            max: sample[sample.len() - 1],
        }
    }

    fn print(&self, label: &str, unit: &str, runs: usize) {
        println!(
            "{label:<24} median {:>10.3} {unit}  quartiles {:.3}..{:.3}  range {:.3}..{:.3}  ({runs} runs)",
            self.median, self.q1, self.q3, self.min, self.max
        );
    }
}

/// Runs `f` `warmup` times, then `runs` times, and returns each measured run's seconds.
fn measure<T>(warmup: usize, runs: usize, mut f: impl FnMut() -> T) -> Vec<f64> {
    for _ in 0..warmup {
        black_box(f());
    }
    (0..runs)
        .map(|_| {
            let start = Instant::now();
            black_box(f());
            start.elapsed().as_secs_f64()
        })
        .collect()
}

fn main() -> std::process::ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{e}");
            std::process::ExitCode::from(e.exit_code() as u8)
        }
    }
}

fn run(args: &Args) -> swarmplan::error::Result<()> {
    let mut requests = load_requests(args.requests.as_deref())?.requests;
    requests.truncate(args.limit.max(1));
    let instance = args.instance.load()?.with_requests(requests)?;
    let requests = &instance.requests;
    let context = Context::new(&instance.network, &instance.graph, &instance.profile);
    let n = instance.graph.node_count();

    // Floyd–Warshall on the baselines' edge costs of the first request's swarm.
    let choice = context.swarm_for(&requests[0], Positioning::LocationAware, None)?;
    let planner = Planner::new(
        &instance.graph,
        &instance.profile,
        &choice.swarm,
        SharingPolicy::Pb,
    );
    let edges = planner.baseline_edge_costs_min()?;
    println!(
        "# Floyd–Warshall on {n} nodes, {} directed edges, {} warm-up + {} runs each",
        edges.len(),
        args.fw_runs,
        args.fw_runs
    );
    let petgraph_fw = || {
        let mut g: DiGraph<(), f64> = DiGraph::with_capacity(n, edges.len());
        for _ in 0..n {
            g.add_node(());
        }
        for &(u, v, c) in &edges {
            g.add_edge(NodeIndex::new(u), NodeIndex::new(v), c);
        }
        petgraph::algo::floyd_warshall::floyd_warshall_path(&g, |e| *e.weight())
            .expect("non-negative costs")
    };
    let ms = |s: Vec<f64>| s.into_iter().map(|x| x * 1e3).collect::<Vec<_>>();
    // Interleaved, so that both see the same machine load.
    let (mut dense_s, mut petgraph_s) = (Vec::new(), Vec::new());
    for round in 0..2 * args.fw_runs {
        let measured = round >= args.fw_runs;
        let d = measure(0, 1, || floyd_warshall(n, &edges));
        let p = measure(0, 1, petgraph_fw);
        if measured {
            dense_s.extend(d);
            petgraph_s.extend(p);
        }
    }
    let dense = Spread::of(ms(dense_s));
    let petgraph = Spread::of(ms(petgraph_s));
    dense.print("fw dense", "ms", args.fw_runs);
    petgraph.print("fw petgraph", "ms", args.fw_runs);
    println!(
        "{:<24} {:.1}x (median)",
        "fw speed-up",
        petgraph.median / dense.median
    );

    // Planning throughput.
    let k = requests.len() as f64;
    println!(
        "# planning the first {} requests on one thread, {} warm-up + {} runs each",
        requests.len(),
        args.warmup,
        args.runs
    );
    let single = PlanOptions {
        sharing: SharingPolicy::Pb,
        positioning: Positioning::LocationAware,
        route: RouteMethod::Sequential,
        support: None,
    };
    let per_s = |s: Vec<f64>, work: f64| s.into_iter().map(|x| work / x).collect::<Vec<_>>();
    let one = measure(args.warmup, args.runs, || {
        for r in requests {
            black_box(context.plan(r, &single).expect("valid request"));
        }
    });
    Spread::of(per_s(one, k)).print("one combination", "requests/s", args.runs);

    let mut grid = Vec::new();
    for route in RouteMethod::ALL {
        for sharing in [SharingPolicy::None, SharingPolicy::Pb, SharingPolicy::Fb] {
            for positioning in [Positioning::LocationAware, Positioning::EnergyAware] {
                grid.push(PlanOptions {
                    sharing,
                    positioning,
                    route,
                    support: None,
                });
            }
        }
    }
    let cells = k * grid.len() as f64;
    let apart = || {
        grid.iter()
            .flat_map(|o| requests.iter().map(move |r| (r, o)))
            .map(|(r, o)| context.plan(r, o).expect("valid request").plan)
            .collect::<Vec<_>>()
    };
    let together = || {
        requests
            .iter()
            .map(|r| context.plan_each(r, &grid).expect("valid request"))
            .collect::<Vec<_>>()
    };
    // The same plans either way (combination-major against request-major).
    let (a, t) = (apart(), together());
    for (c, _) in grid.iter().enumerate() {
        for (i, row) in t.iter().enumerate() {
            assert!(
                a[c * requests.len() + i] == row[c].plan,
                "different plans for combination {c}, request {i}"
            );
        }
    }
    let (mut apart_s, mut together_s) = (Vec::new(), Vec::new());
    for round in 0..args.warmup + args.runs {
        let x = measure(0, 1, apart);
        let y = measure(0, 1, together);
        if round >= args.warmup {
            apart_s.extend(x);
            together_s.extend(y);
        }
    }
    let apart = Spread::of(per_s(apart_s, cells));
    let together = Spread::of(per_s(together_s, cells));
    apart.print(
        "grid, per combination",
        "requests x combinations/s",
        args.runs,
    );
    together.print("grid, per request", "requests x combinations/s", args.runs);
    println!(
        "{:<24} {:.2}x (median)",
        "grid speed-up",
        together.median / apart.median
    );
    Ok(())
}
