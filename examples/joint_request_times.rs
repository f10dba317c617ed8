//! Time of each request's joint optimum ([`Context::joint_optimum`]: `--route optimal
//! --sharing exact` over the swarms of both positionings and the swarm without support drones),
//! one thread, one line per request as soon as it is solved, (stdout is line-buffered), so a slow
//! request shows while it runs: `index,request_id,ms,dt_min,proven`.
//!
//! ```text
//! cargo run --release --example joint_request_times -- --from 500 --to 10000 --step 2 \
//!     --network instances/findings-195/network.json --profile instances/profiles/paper-findings.toml
//! ```
//!
//! `--from`, `--to` and `--step` pick the requests at positions from, from + step, ... below to.
//! `--split` times what `bench` does per request instead: the paper's grid of 20
//! combinations and their optimal-route references (`plan_ms`), then the joint optimum with every
//! combination's gap split (`joint_ms`), on the line `index,request_id,plan_ms,joint_ms,dt_min,proven`.

use clap::Parser;
use std::path::PathBuf;
use std::time::Instant;
use swarmplan::cli::inputs::InstanceArgs;
use swarmplan::compose::Context;
use swarmplan::experiment::{Baseline, Experiment, Methods};
use swarmplan::problem::inputs::load_requests;

/// Time of each request's joint optimum.
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    instance: InstanceArgs,
    /// Request set (JSON) [default: the shipped instances/paper-195/requests.json].
    #[arg(long)]
    requests: Option<PathBuf>,
    /// First position.
    #[arg(long, default_value_t = 0)]
    from: usize,
    /// Positions below this one [default: all].
    #[arg(long)]
    to: Option<usize>,
    /// Distance between positions.
    #[arg(long, default_value_t = 1)]
    step: usize,
    /// Time the bench's grid and the gap split too.
    #[arg(long)]
    split: bool,
}

fn main() -> swarmplan::error::Result<()> {
    let args = Args::parse();
    let requests = load_requests(args.requests.as_deref())?.requests;
    let to = args.to.unwrap_or(requests.len()).min(requests.len());
    let instance = args.instance.load()?.with_requests(requests)?;
    let context = Context::new(&instance.network, &instance.graph, &instance.profile);
    if args.split {
        return split_times(&args, &context, &instance.requests, to);
    }
    println!("index,request_id,ms,dt_min,proven");
    for i in (args.from..to).step_by(args.step.max(1)) {
        let r = &instance.requests[i];
        let start = Instant::now();
        let joint = context.joint_optimum(r, None)?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let dt = joint.dt_min().map_or(String::new(), |d| format!("{d:.6}"));
        println!("{i},{},{ms:.1},{dt},{}", r.id, joint.proven);
    }
    Ok(())
}

/// `--split`: the bench's plans and the joint split of each request, timed apart.
fn split_times(
    args: &Args,
    context: &Context,
    requests: &[swarmplan::problem::Request],
    to: usize,
) -> swarmplan::error::Result<()> {
    let experiment = Experiment {
        combos: Methods::paper_grid(None).combinations(Baseline::Once),
        route_gap: true,
        joint: true,
    };
    let planned = experiment.planned();
    println!("index,request_id,plan_ms,joint_ms,dt_min,proven");
    for i in (args.from..to).step_by(args.step.max(1)) {
        let r = &requests[i];
        let start = Instant::now();
        let reports = planned
            .iter()
            .map(|o| context.plan(r, o))
            .collect::<swarmplan::error::Result<Vec<_>>>()?;
        let plan_ms = start.elapsed().as_secs_f64() * 1e3;
        let start = Instant::now();
        let split = context.joint_split(r, &reports)?;
        let joint_ms = start.elapsed().as_secs_f64() * 1e3;
        let dt = split
            .joint
            .dt_min()
            .map_or(String::new(), |d| format!("{d:.6}"));
        println!(
            "{i},{},{plan_ms:.1},{joint_ms:.1},{dt},{}",
            r.id, split.joint.proven
        );
    }
    Ok(())
}
