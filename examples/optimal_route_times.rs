//! Time per request of `--route optimal` (hop-path rule and `--hop-paths any`), one thread, on
//! the first requests of a request set: median, 90th percentile and worst, in ms, per sharing
//! policy. Each request is planned alone ([`Context::plan`]: its swarm, its planner and its
//! route), once after one warm-up pass over all the requests.
//!
//! ```text
//! cargo run --release --example optimal_route_times -- [--limit 1000] [--network F]
//!     [--profile F] [--requests F] [--sharing none,pb] [--hop-paths rule,any]
//! ```
//!
//! `--hop-paths any` with `pb` or `fb` is skipped (E0016). `max_labels`: the
//! most labels the searches of hop paths of one request created, all its searches together
//! (under `exact`, the partial walks of its arcs' searches).
//! `--sharing exact` gives the joint optimum: `proven` counts the requests whose route is
//! proven (`within`: of those, with an infimum approached, the largest `epsilon_min` in
//! `max_epsilon_min`), `arcs_flown` / `arcs_total` the arcs flown (a hop solve each) against
//! the stop graph's arcs, summed over the requests, `arcs_bounded` and `arcs_fluid_bounded`
//! the arcs bounded from their path and by the fluid LP. `--no-warm-up` skips the warm-up
//! pass.

use clap::Parser;
use std::path::PathBuf;
use std::time::Instant;
use swarmplan::cli::inputs::InstanceArgs;
use swarmplan::compose::{Context, HopPaths, PlanOptions, RouteMethod};
use swarmplan::eaas::SharingPolicy;
use swarmplan::precompose::Positioning;
use swarmplan::problem::inputs::load_requests;

/// Time per request of the optimal route.
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    instance: InstanceArgs,
    /// Request set (JSON) [default: the shipped instances/paper-195/requests.json].
    #[arg(long)]
    requests: Option<PathBuf>,
    /// Plan the first N requests.
    #[arg(long, default_value_t = 1000)]
    limit: usize,
    /// Sharing policies.
    #[arg(long, value_enum, value_delimiter = ',', default_value = "none,pb")]
    sharing: Vec<SharingPolicy>,
    /// Hop-path rules.
    #[arg(long, value_enum, value_delimiter = ',', default_value = "rule,any")]
    hop_paths: Vec<HopPaths>,
    /// Skip the warm-up pass.
    #[arg(long)]
    no_warm_up: bool,
}

fn main() -> swarmplan::error::Result<()> {
    let args = Args::parse();
    let mut requests = load_requests(args.requests.as_deref())?.requests;
    requests.truncate(args.limit.max(1));
    let instance = args.instance.load()?.with_requests(requests)?;
    println!(
        "hop_paths,sharing,requests,delivered,mean_dt_min,median_ms,p90_ms,max_ms,total_s,\
         max_labels,proven,within,max_epsilon_min,arcs_flown,arcs_total,arcs_bounded,\
         arcs_fluid_bounded"
    );
    for &hop_paths in &args.hop_paths {
        for &sharing in &args.sharing {
            let mut context = Context::new(&instance.network, &instance.graph, &instance.profile);
            context.hop_paths = hop_paths;
            let options = PlanOptions {
                sharing,
                positioning: Positioning::LocationAware,
                route: RouteMethod::Optimal,
                support: None,
            };
            if context.validate(&options).is_err() {
                continue;
            }
            if !args.no_warm_up {
                for r in &instance.requests {
                    context.plan(r, &options)?;
                }
            }
            let mut ms = Vec::with_capacity(instance.requests.len());
            let (mut delivered, mut dt_sum, mut max_labels) = (0usize, 0.0, 0usize);
            let (mut proven, mut within, mut max_epsilon_min) = (0usize, 0usize, 0.0f64);
            let mut arcs = [0usize; 4];
            for r in &instance.requests {
                let start = Instant::now();
                let report = context.plan(r, &options)?;
                ms.push(start.elapsed().as_secs_f64() * 1e3);
                if let Some(o) = &report.plan.route_optimality {
                    max_labels = max_labels.max(o.hop_path_labels);
                    proven += usize::from(o.proven());
                    within += usize::from(o.proven() && o.epsilon_min > 0.0);
                    max_epsilon_min = max_epsilon_min.max(o.epsilon_min);
                    arcs[0] += o.arcs_flown;
                    arcs[1] += o.arcs_total;
                    arcs[2] += o.arcs_bounded;
                    arcs[3] += o.arcs_fluid_bounded;
                }
                if report.plan.delivered() {
                    delivered += 1;
                    dt_sum += report.plan.dt_min;
                }
            }
            let total_s = ms.iter().sum::<f64>() / 1e3;
            ms.sort_by(f64::total_cmp);
            let at = |q: f64| ms[((ms.len() - 1) as f64 * q).round() as usize];
            println!(
                "{hop_paths},{sharing},{},{delivered},{:.4},{:.3},{:.3},{:.3},{:.2},{max_labels},\
                 {proven},{within},{max_epsilon_min:.3e},{},{},{},{}",
                ms.len(),
                dt_sum / delivered.max(1) as f64,
                at(0.5),
                at(0.9),
                at(1.0),
                total_s,
                arcs[0],
                arcs[1],
                arcs[2],
                arcs[3]
            );
        }
    }
    Ok(())
}
