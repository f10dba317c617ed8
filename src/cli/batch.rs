//! `swarmplan batch`: plan every request of a request set with one or more method combinations and
//! report success counts (with their denominator), delivery and node times, and run time. The
//! arguments and the printing; the combinations, their gap references and the summaries are
//! those of [`crate::experiment`].

use super::inputs::{ExactArgs, InstanceArgs};
use crate::compose::{Context, RouteMethod};
use crate::eaas::SharingPolicy;
use crate::error::Result;
use crate::experiment::{self, summarise_grid, write_summaries, Baseline, Experiment, Methods};
use crate::precompose::Positioning;
use crate::problem::io;
use std::path::{Path, PathBuf};

/// Plan every request of a request set and summarise.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "The grid (requests x combinations) runs on --threads worker threads, one job \
per request planning all its combinations and computing once what they share (the swarm of each \
positioning, the Dijkstra and Floyd-Warshall edge costs of each distinct swarm). The column wall_ms \
of a combination is the sum of its execution times over the requests, shared work split equally \
among the combinations using it (consumption rates, cached per swarm and sharing policy, count in \
the first combination, in CSV order, that needs them): with several threads the column adds up to more than the elapsed \
time, which the last line on stderr gives."
)]
pub struct BatchArgs {
    /// Network and profile.
    #[command(flatten)]
    pub instance: InstanceArgs,
    /// Solver settings of `--sharing exact|fair`.
    #[command(flatten)]
    pub exact: ExactArgs,
    /// Request set (JSON) [default: the shipped paper-195 requests].
    #[arg(long, alias = "request-file", value_name = "FILE")]
    pub requests: Option<PathBuf>,
    /// Plan only the first N requests (a count of requests; every limit in seconds says so:
    /// `--time-limit`, `--hop-time-limit`). `--limit` is its former name.
    #[arg(long = "request-limit", alias = "limit", value_name = "N")]
    pub limit: Option<usize>,
    /// Sharing policies, comma-separated.
    #[arg(long, value_enum, value_delimiter = ',', default_value = "pb")]
    pub sharing: Vec<SharingPolicy>,
    /// Support positionings, comma-separated.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "location-aware"
    )]
    pub positioning: Vec<Positioning>,
    /// Route methods, comma-separated (`optimal`: the least delivery time over stop sequences,
    /// with `--sharing exact` also over sharing schedules and pads; not with `fair`; never part
    /// of `--all`).
    #[arg(long, value_enum, value_delimiter = ',', default_value = "sequential")]
    pub route: Vec<RouteMethod>,
    /// Every combination of sharing, positioning and route (overrides the three lists): the
    /// paper's grid, `optimal` not included.
    #[arg(long)]
    pub all: bool,
    /// Number of support drones for every request, overriding the redundancy table (not used by
    /// `none`, the paper's baseline without support drones).
    #[arg(long, value_name = "N")]
    pub support: Option<usize>,
    /// Worker threads [default: the number of available cores]; every number but `wall_ms` is
    /// identical for any count.
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Wall-clock budget of the whole run, seconds: no request is started after it, and the
    /// output is that of the requests before the first one left out (the same numbers as
    /// `--request-limit K` for that K, said on stderr with the remaining work) [default: none].
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub time_budget: Option<f64>,
    /// Write every request's outcome (id, success, dt, stops, failure) as JSON to this file.
    #[arg(long, value_name = "FILE")]
    pub per_request: Option<PathBuf>,
    /// Overwrite the `--per-request` file when it exists (E0013 otherwise).
    #[arg(long)]
    pub force: bool,
    /// Node limit of the exact node time at every stop (search nodes, the same on every machine);
    /// a stop it stops keeps its incumbent, `status: feasible`.
    #[arg(long, value_name = "N", default_value_t = crate::node_time::DEFAULT_STOP_NODE_LIMIT)]
    pub node_limit: u64,
    /// Route gap: also plan every request with `--route optimal` (same sharing policy,
    /// positioning and support drones) and give each other route method's gap against it
    /// (columns route_gap_*; not with `fair`).
    #[arg(long)]
    pub gap: bool,
    /// Print the summaries as JSON.
    #[arg(long)]
    pub json: bool,
    /// Paths the hops of `--route optimal` (and of the `--gap` reference) may follow: `rule` or
    /// `any` (every path flyable from full batteries; `--sharing none` or `idle-support` only).
    #[arg(long, value_enum, default_value = "rule")]
    pub hop_paths: crate::compose::HopPaths,
}

/// Runs the subcommand.
pub fn run(args: BatchArgs) -> Result<i32> {
    if let Some(path) = &args.per_request {
        let inputs = [
            &args.instance.network,
            &args.instance.profile,
            &args.requests,
        ];
        let inputs: Vec<&Path> = inputs.into_iter().flatten().map(PathBuf::as_path).collect();
        super::distinct_from_inputs(&[path], &inputs)?;
        super::may_write(path, args.force)?;
    }
    let threads = experiment::threads(args.threads)?;
    let methods = if args.all {
        Methods::paper_grid(args.support)
    } else {
        Methods {
            sharing: args.sharing.clone(),
            positioning: args.positioning.clone(),
            route: args.route.clone(),
            support: args.support,
        }
    };
    let experiment = Experiment {
        combos: methods.combinations(Baseline::UnderEveryPositioning),
        route_gap: args.gap,
        joint: false,
    };
    for combo in &experiment.combos {
        combo.validate()?;
    }
    let notes = experiment::applicable_options(&experiment.combos, args.gap, args.support)?;
    let (instance, set) = args.instance.load_with_requests(args.requests.as_deref())?;
    let requests = experiment::first_requests(set.requests, args.limit)?;
    let instance = instance.with_requests(requests)?;
    let requests = &instance.requests;
    let mut context = Context::new(&instance.network, &instance.graph, &instance.profile);
    context.exact = args.exact.settings()?;
    context.node_limit = Some(args.node_limit);
    context.hop_paths = args.hop_paths;
    context.deadline = experiment::deadline(args.time_budget)?;
    let planned_combos = experiment.planned().len();
    let bar = super::progress::bar((planned_combos * requests.len()) as u64, "requests");
    bar.set_message(format!("x {}", super::count(planned_combos, "combination")));
    let grid = summarise_grid(
        &context,
        requests,
        &experiment,
        threads,
        &|n| bar.inc(n),
        args.per_request.is_some(),
    )?;
    bar.finish_and_clear();
    for note in &notes {
        eprintln!("{note}");
    }
    super::inputs::report_budget(grid.requests, requests.len(), grid.requests);
    if !args.json {
        for s in &grid.summaries {
            eprintln!(
                "sharing {:<4} positioning {:<14} route {:<14} delivered {}/{} mean dt {:.2} min, {:.0} ms",
                s.options.sharing,
                s.options.positioning,
                s.options.route,
                s.delivered,
                s.requests,
                s.mean_dt_min,
                s.wall_ms
            );
        }
        eprintln!(
            "{} x {} on {} in {:.0} ms",
            super::count(grid.requests, "request"),
            super::count(grid.planned_combos, "combination"),
            super::count(threads, "thread"),
            grid.grid_ms
        );
    }
    if let Some(path) = &args.per_request {
        io::write_json(path, &grid.outcomes)?;
    }
    if args.json {
        super::print_json(&grid.summaries)?;
    } else {
        // Data, as the JSON: every float with all its digits (the lines on stderr are rounded).
        super::stdout_written(write_summaries(
            std::io::stdout().lock(),
            &grid.summaries,
            args.gap,
        ))?;
    }
    Ok(0)
}
