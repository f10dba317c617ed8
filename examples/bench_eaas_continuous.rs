//! Solve time of the continuous-time configuration LP (`models/eaas_config.md`), with the grid
//! MILP on the same hops for comparison.
//!
//! 1. The three 10 + 3 drone, 30-period benchmark hops of `bench_eaas_exact` (node time on 2 pads),
//!    `paper` and `none` modes.
//! 2. Every hop ending at a stop of the PB plans (Algorithm 1, location-aware) of the first
//!    `--limit` requests of paper-195 (profile `paper`) and findings-195 (profile
//!    `paper-findings`), each on its own profile and on `fast-sharing`, modes `none` and `paper`:
//!    status counts, median and largest time.
//!
//! `cargo run --release --example bench_eaas_continuous [-- --limit 50 --grid-time-limit 1 --free]`
//! (the grid MILP beside it with a time limit, `free` mode too; `--backend highs` with the
//! `highs` feature).

#[path = "common/bench_hop.rs"]
mod bench_hop;
use bench_hop::hop;
use clap::Parser;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::PathBuf;
use swarmplan::cli::inputs::InstanceArgs;
use swarmplan::compose::{Context, PlanOptions, Planner, RouteMethod};
use swarmplan::eaas::exact::continuous::{solve_continuous, ContinuousOptions, PadMethod};
use swarmplan::eaas::exact::milp::{solve_milp, MilpOptions};
use swarmplan::eaas::exact::EndPads;
use swarmplan::eaas::exact::{ExactOutcome, ExactStatus, Objective, Reorder};
use swarmplan::eaas::{HopProblem, SharingPolicy};
use swarmplan::precompose::Positioning;
use swarmplan::problem::inputs::load_requests;
use swarmplan::problem::Instance;
use swarmplan::solver::MilpBackend;

#[derive(Parser)]
struct Args {
    /// Requests of each instance (the first of the set).
    #[arg(long, default_value_t = 50)]
    limit: usize,
    /// Time limit of each grid MILP, seconds; 0 (default) skips the grid MILP.
    #[arg(long, default_value_t = 0.0)]
    grid_time_limit: f64,
    /// Backend of both models.
    #[arg(long, value_enum)]
    backend: Option<MilpBackend>,
    /// Write every hop refused, solved in more than 0.5 s, or left more than 1e-6 relative from
    /// its optimum, as `[problem, objective]` JSON into this directory.
    #[arg(long, value_name = "DIR")]
    dump: Option<PathBuf>,
    /// Also `free` mode on the hops (refusals, E4117 above the configuration count, are counted).
    #[arg(long)]
    free: bool,
    /// Solve the pad assignment with the pad MILP (the reference) instead of the pad search.
    #[arg(long)]
    pad_milp: bool,
}

fn median(v: &[f64]) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    if v.is_empty() {
        f64::NAN
    } else {
        v[v.len() / 2]
    }
}

fn status_name(s: ExactStatus) -> String {
    serde_json::to_value(s)
        .ok()
        .and_then(|v| v.as_str().map(String::from))
        .unwrap_or_default()
}

/// Status counts, times, and the largest certified distance of a set of solves.
#[derive(Default)]
struct Tally {
    statuses: std::collections::BTreeMap<String, usize>,
    ms: Vec<f64>,
    max_rel_epsilon: f64,
}

impl Tally {
    fn add(&mut self, o: &ExactOutcome) {
        *self.statuses.entry(status_name(o.status)).or_default() += 1;
        self.ms.push(o.solve_ms);
        if let (Some(e), Some(b)) = (o.epsilon, o.bound) {
            self.max_rel_epsilon = self.max_rel_epsilon.max(e / b.abs().max(1.0));
        }
    }

    fn line(&self) -> String {
        let counts: Vec<String> = self
            .statuses
            .iter()
            .map(|(k, v)| format!("{k} {v}"))
            .collect();
        format!(
            "{} solves, median {:.2} ms, max {:.1} ms, largest relative epsilon {:.1e}; {}",
            self.ms.len(),
            median(&self.ms),
            self.ms.iter().copied().fold(0.0, f64::max),
            self.max_rel_epsilon,
            counts.join(", ")
        )
    }
}

fn main() {
    let args = Args::parse();
    let backend = args.backend.unwrap_or_default();
    println!("backend {backend}");
    println!("1. benchmark hops, 10 + 3 drones, 30 periods, node time on 2 pads");
    let objective = Objective::NodeTime(EndPads {
        pads: 2,
        pad_rate_mah_per_min: 10.0,
    });
    for reorder in [Reorder::Paper, Reorder::None] {
        // The seed bench_eaas_exact uses for this size.
        let mut rng = ChaCha8Rng::seed_from_u64(1000 + 10 * 10 + 3);
        for i in 0..3 {
            let p = hop(&mut rng, 10, 3, 30);
            let o = solve(&p, &objective, reorder, backend, pad_method(&args));
            println!(
                "  {reorder} hop {i}: {} {:?} (bound {:?}, epsilon {:?}), {:.2} ms",
                status_name(o.status),
                o.objective,
                o.bound,
                o.epsilon,
                o.solve_ms
            );
        }
    }
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let sets = [
        (
            "paper-195",
            "instances/paper-195/network.json",
            "instances/profiles/paper.toml",
        ),
        (
            "findings-195",
            "instances/findings-195/network.json",
            "instances/profiles/paper-findings.toml",
        ),
    ];
    println!(
        "2. hops of the PB plans of the first {} requests",
        args.limit
    );
    let modes: Vec<Reorder> = if args.free {
        vec![Reorder::None, Reorder::Paper, Reorder::Free]
    } else {
        vec![Reorder::None, Reorder::Paper]
    };
    for (name, network, own) in sets {
        for profile in [own, "instances/profiles/fast-sharing.toml"] {
            let mut requests = load_requests(None).expect("embedded requests").requests;
            requests.truncate(args.limit);
            let instance = InstanceArgs {
                network: Some(root.join(network)),
                profile: Some(root.join(profile)),
                literal: false,
            }
            .load()
            .and_then(|i| i.with_requests(requests))
            .expect("shipped instance");
            let hops = stop_hops(&instance, args.limit);
            for &reorder in &modes {
                let (mut cont, mut grid) = (Tally::default(), Tally::default());
                let mut refused = 0;
                let mut above_grid = 0;
                for (p, objective) in &hops {
                    let options = ContinuousOptions {
                        reorder,
                        backend,
                        time_limit_s: 60.0,
                        pad_method: pad_method(&args),
                        ..ContinuousOptions::default()
                    };
                    let o = match solve_continuous(p, objective, &options) {
                        Ok(o) => o,
                        Err(e) => {
                            if refused == 0 {
                                println!("    first refusal: {e}");
                            }
                            dump(
                                &args,
                                &format!("refused_{name}_{refused}_{reorder}"),
                                p,
                                objective,
                            );
                            refused += 1;
                            continue;
                        }
                    };
                    cont.add(&o);
                    let loose = o
                        .epsilon
                        .zip(o.bound)
                        .is_some_and(|(e, b)| e > 1e-6 * b.abs().max(1.0));
                    if o.solve_ms > 500.0 || loose {
                        let profile_name = profile.rsplit('/').next().unwrap_or(profile);
                        let file = format!("hop_{name}_{profile_name}_{}_{reorder}", cont.ms.len());
                        dump(&args, &file, p, objective);
                    }
                    if args.grid_time_limit > 0.0 {
                        let g = solve_milp(
                            p,
                            objective,
                            &MilpOptions {
                                period_min: 1.0,
                                reorder,
                                backend,
                                time_limit_s: args.grid_time_limit,
                                node_limit: None,
                            },
                        )
                        .expect("valid hop");
                        if let (ExactStatus::Optimal, Some(gv), Some(cb)) =
                            (g.status, g.objective, o.bound)
                        {
                            if cb > gv + 1e-6 * (1.0 + gv.abs()) {
                                above_grid += 1;
                            }
                        }
                        grid.add(&g);
                    }
                }
                let profile_name = profile.rsplit('/').next().unwrap_or(profile);
                println!("  {name}, {profile_name}, {reorder}: {} hops", hops.len());
                println!("    continuous: {}", cont.line());
                if refused > 0 {
                    println!("    continuous refused: {refused}");
                }
                if args.grid_time_limit > 0.0 {
                    println!(
                        "    grid MILP (1 min, {} s limit): {}",
                        args.grid_time_limit,
                        grid.line()
                    );
                    println!("    continuous bound above a proven grid optimum: {above_grid}");
                }
            }
        }
    }
}

/// Writes `[problem, objective]` as `DIR/name.json` when `--dump DIR` is given.
fn dump(args: &Args, name: &str, p: &HopProblem, objective: &Objective) {
    if let Some(dir) = &args.dump {
        let text = serde_json::to_string(&(p, objective)).expect("a hop serialises");
        std::fs::create_dir_all(dir).expect("a writable --dump directory");
        std::fs::write(dir.join(format!("{name}.json")), text).expect("a writable --dump file");
    }
}

fn pad_method(args: &Args) -> PadMethod {
    if args.pad_milp {
        PadMethod::Milp
    } else {
        PadMethod::Search
    }
}

fn solve(
    p: &HopProblem,
    objective: &Objective,
    reorder: Reorder,
    backend: MilpBackend,
    pad_method: PadMethod,
) -> ExactOutcome {
    let options = ContinuousOptions {
        reorder,
        backend,
        pad_method,
        ..ContinuousOptions::default()
    };
    solve_continuous(p, objective, &options).expect("valid hop")
}

/// Every hop of the PB plans that ends at a stop, with its node-time objective.
fn stop_hops(instance: &Instance, limit: usize) -> Vec<(HopProblem, Objective)> {
    let context = Context::new(&instance.network, &instance.graph, &instance.profile);
    let options = PlanOptions {
        sharing: SharingPolicy::Pb,
        positioning: Positioning::LocationAware,
        route: RouteMethod::Sequential,
        support: None,
    };
    let mut out = Vec::new();
    for request in instance.requests.iter().take(limit) {
        let report = context.plan(request, &options).expect("plannable request");
        let planner = Planner::new(
            &instance.graph,
            &instance.profile,
            &report.swarm,
            SharingPolicy::Pb,
        );
        for hop in &report.plan.hops {
            if hop.stop.is_none() {
                continue;
            }
            let (problem, objective) = planner.studied_hop(hop).expect("a planned hop");
            out.push((problem, objective));
        }
    }
    out
}
