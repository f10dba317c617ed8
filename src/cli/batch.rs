//! `swarmplan batch`: plan every request of a request set with one or more method combinations and
//! report success counts (with their denominator), delivery and node times, and run time.
//!
//! The grid (requests x combinations) runs on a local rayon pool: one job per request plans every
//! combination of it ([`Context::plan_each`], which does the work they share once), and the
//! results come back in request order, so every number but the times is the same for any thread
//! count.

use super::inputs::{ExactArgs, InstanceArgs};
use crate::compose::{
    lpt_gap, Context, LptGapSummary, PlanOptions, RequestReport, RouteGapSummary, RouteMethod,
    RoutePair,
};
use crate::eaas::exact_hop::HopSolveCounts;
use crate::eaas::SharingPolicy;
use crate::error::{Error, Result};
use crate::precompose::Positioning;
use crate::problem::io;
use serde::Serialize;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Instant;

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
    #[arg(long, value_name = "S")]
    pub time_budget: Option<f64>,
    /// Write every request's outcome (id, success, dt, stops, failure) as JSON to this file.
    #[arg(long, value_name = "FILE")]
    pub per_request: Option<PathBuf>,
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

/// Summary of one method combination over a request set.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// The combination.
    pub options: PlanOptions,
    /// Requests delivered.
    pub delivered: usize,
    /// Requests planned (the denominator).
    pub requests: usize,
    /// Requests not delivered, by the kind of their outcome (`dead-end`, `hop-infeasible`,
    /// `no-route`).
    pub failed_by_kind: BTreeMap<String, usize>,
    /// Mean delivery time of the delivered requests, min.
    pub mean_dt_min: f64,
    /// Mean total node time of the delivered requests, min.
    pub mean_nt_min: f64,
    /// Mean number of recharging stops of the delivered requests.
    pub mean_stops: f64,
    /// Energy shared in flight over all delivered requests, mAh.
    pub shared_mah: f64,
    /// LPT against the exact node time at every stop of the delivered requests.
    pub lpt_node_time: LptGapSummary,
    /// `exact` and `fair`: the hop solves made over all requests (candidate hops included);
    /// with a solve stopped by its time limit the numbers depend on the machine's speed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hop_solves: Option<HopSolveCounts>,
    /// With `--gap`: the route gap against the optimal route (`None` for `optimal` itself and
    /// the exact and fair policies).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub route_gap: Option<RouteGapSummary>,
    /// Time spent planning the combination, ms: the sum over the requests of its execution time,
    /// where work shared with other combinations of the request (its swarm, the baseline edge
    /// costs and Floyd–Warshall's all-pairs result of a swarm) is split equally among the
    /// combinations using it, and the consumption rates a planner caches count in the first
    /// combination of its swarm and sharing policy (see [`Context::plan_each`]). Summed over the
    /// combinations it is the busy time of every thread together, so with several threads it
    /// exceeds the elapsed time.
    pub wall_ms: f64,
}

/// One request's outcome, for `--per-request`.
#[derive(Debug, Clone, Serialize)]
pub struct Outcome {
    /// The combination.
    pub options: PlanOptions,
    /// Request id.
    pub request_id: String,
    /// Delivered?
    pub success: bool,
    /// The kind of the plan's outcome: `delivered`, `no-route`, `dead-end`, `hop-infeasible`.
    pub outcome: String,
    /// Delivery time, min.
    pub dt_min: f64,
    /// Node time, min.
    pub nt_min: f64,
    /// Stop node ids.
    pub stops: Vec<String>,
    /// Why the request failed, as a sentence (`solve --json` gives the outcome's data).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failure: Option<String>,
    /// With `--gap`, when both delivered: `(dt - dt_opt) / dt_opt` against the optimal route.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub route_gap: Option<f64>,
}

/// Runs the subcommand.
pub fn run(args: BatchArgs) -> Result<i32> {
    let threads = args.threads.unwrap_or_else(|| {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
    });
    if threads == 0 {
        return Err(Error::invalid(
            "E0004",
            "--threads",
            "0 worker threads",
            "give --threads 1 or more",
        ));
    }
    for combo in combinations(&args) {
        combo.validate()?;
    }
    let (instance, set) = args.instance.load_with_requests(args.requests.as_deref())?;
    let mut requests = set.requests;
    if let Some(n) = args.limit {
        requests.truncate(n);
    }
    if requests.is_empty() {
        return Err(Error::invalid(
            "E0005",
            "--request-limit / --requests",
            "no request to plan",
            "give a request file with requests and a --request-limit of 1 or more",
        ));
    }
    let instance = instance.with_requests(requests)?;
    let requests = &instance.requests;
    let mut context = Context::new(&instance.network, &instance.graph, &instance.profile);
    context.exact = args.exact.settings()?;
    context.node_limit = Some(args.node_limit);
    context.hop_paths = args.hop_paths;
    context.deadline = super::inputs::deadline(args.time_budget)?;
    let shown = combinations(&args);
    // With --gap, the optimal route of each compared combination, planned with it.
    let mut combos = shown.clone();
    let mut reference_of: Vec<Option<usize>> = vec![None; shown.len()];
    if args.gap {
        for (i, o) in shown.iter().enumerate() {
            if o.route == RouteMethod::Optimal || o.sharing == SharingPolicy::Fair {
                continue;
            }
            let optimal = PlanOptions {
                route: RouteMethod::Optimal,
                ..*o
            };
            reference_of[i] = Some(match combos.iter().position(|c| *c == optimal) {
                Some(j) => j,
                None => {
                    combos.push(optimal);
                    combos.len() - 1
                }
            });
        }
    }
    let bar = super::progress::bar((combos.len() * requests.len()) as u64, "requests");
    bar.set_message(format!("x {}", super::count(combos.len(), "combination")));
    let start = Instant::now();
    let grid = context.plan_grid(requests, &combos, threads, &|n| bar.inc(n), &|_, r| {
        Planned::of(r)
    })?;
    let grid_ms = start.elapsed().as_secs_f64() * 1e3;
    bar.finish_and_clear();
    super::inputs::report_budget(grid.len(), requests.len(), grid.len());
    let requests = &requests[..grid.len()];
    let mut summaries = Vec::new();
    let mut outcomes = Vec::new();
    for (c, &options) in shown.iter().enumerate() {
        let planned: Vec<&Planned> = grid.iter().map(|row| &row[c]).collect();
        let wall_ms = total(planned.iter().map(|p| p.execution_ms));
        let mut summary = summarise(options, &planned, wall_ms)?;
        let pairs: Option<Vec<RoutePair>> = reference_of[c].map(|j| {
            grid.iter()
                .map(|row| RoutePair {
                    heuristic_dt_min: row[c].outcome.success.then_some(row[c].outcome.dt_min),
                    optimal_dt_min: row[j].outcome.success.then_some(row[j].outcome.dt_min),
                    optimal_proven: row[j].route_proven,
                })
                .collect()
        });
        summary.route_gap = pairs
            .as_ref()
            .map(|p| RouteGapSummary::of(p.iter().copied()).with_hop_paths(args.hop_paths));
        if !args.json {
            eprintln!(
                "sharing {:<4} positioning {:<14} route {:<14} delivered {}/{} mean dt {:.2} min, {:.0} ms",
                options.sharing,
                options.positioning,
                options.route,
                summary.delivered,
                summary.requests,
                summary.mean_dt_min,
                summary.wall_ms
            );
        }
        if args.per_request.is_some() {
            outcomes.extend(planned.iter().enumerate().map(|(r, p)| Outcome {
                route_gap: pairs.as_ref().and_then(|pairs| pairs[r].gap()),
                ..p.outcome.clone()
            }));
        }
        summaries.push(summary);
    }
    if !args.json {
        eprintln!(
            "{} x {} on {} in {grid_ms:.0} ms",
            super::count(requests.len(), "request"),
            super::count(combos.len(), "combination"),
            super::count(threads, "thread")
        );
    }
    if let Some(path) = &args.per_request {
        io::write_json(path, &outcomes)?;
    }
    if args.json {
        super::print_json(&summaries)?;
    } else {
        // Data, as the JSON: every float with all its digits (the lines on stderr are rounded).
        let gap_header = if args.gap {
            ",route_gap_reference,route_gap_compared,route_gap_zero,route_gap_mean,route_gap_max,route_gap_min,heuristic_fails_optimum_delivers,optimum_fails_heuristic_delivers,route_gap_unproven_references"
        } else {
            ""
        };
        outln!("sharing,positioning,route,delivered,requests,mean_dt_min,mean_nt_min,mean_stops,stops,lpt_optimal,lpt_mean_gap,lpt_max_gap,hop_solves,hop_solves_unproven,wall_ms{gap_header}");
        for s in &summaries {
            let hops = s.hop_solves.unwrap_or_default();
            let gap_cells = match (&s.route_gap, args.gap) {
                (Some(g), _) => format!(
                    ",{},{},{},{},{},{},{},{},{}",
                    g.reference_name(),
                    g.compared,
                    g.at_zero,
                    g.mean_gap,
                    g.max_gap,
                    g.min_gap,
                    g.heuristic_fails_optimum_delivers,
                    g.optimum_fails_heuristic_delivers,
                    g.unproven_references
                ),
                (None, true) => ",,,,,,,,,".to_string(),
                (None, false) => String::new(),
            };
            outln!(
                "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}{}",
                s.options.sharing,
                s.options.positioning,
                s.options.route,
                s.delivered,
                s.requests,
                s.mean_dt_min,
                s.mean_nt_min,
                s.mean_stops,
                s.lpt_node_time.stops,
                s.lpt_node_time.lpt_optimal,
                s.lpt_node_time.mean_gap,
                s.lpt_node_time.max_gap,
                hops.solves,
                hops.time_limit_incumbent + hops.time_limit_no_solution + hops.backend_errors,
                s.wall_ms,
                gap_cells
            );
        }
    }
    Ok(0)
}

/// The serde name of a unit enum value (`pb`, `location-aware`, ...).
fn combinations(args: &BatchArgs) -> Vec<PlanOptions> {
    let (sharing, positioning, route) = if args.all {
        (
            vec![SharingPolicy::None, SharingPolicy::Pb, SharingPolicy::Fb],
            vec![Positioning::LocationAware, Positioning::EnergyAware],
            RouteMethod::ALL.to_vec(),
        )
    } else {
        (
            args.sharing.clone(),
            args.positioning.clone(),
            args.route.clone(),
        )
    };
    let mut combos = Vec::new();
    for &r in &route {
        for &s in &sharing {
            for &p in &positioning {
                combos.push(PlanOptions {
                    sharing: s,
                    positioning: p,
                    route: r,
                    support: args.support,
                });
            }
        }
    }
    combos
}

/// What the summaries and `--per-request` keep of one request planned with one combination.
struct Planned {
    /// The request's line of `--per-request`.
    outcome: Outcome,
    /// Energy shared in flight, mAh.
    shared_mah: f64,
    /// LPT's gap at every recharging stop, in flight order (`None`: the stop's node time is
    /// only an incumbent); the stops themselves are not kept.
    lpt_gaps: Vec<Option<f64>>,
    /// The hop solves of `exact` and `fair`.
    hop_solves: Option<HopSolveCounts>,
    /// Execution time, ms ([`RequestReport::execution_ms`]).
    execution_ms: f64,
    /// `optimal` route: whether every node time of its search was proven (true for the others).
    route_proven: bool,
}

impl Planned {
    fn of(r: RequestReport) -> Result<Self> {
        let delivered = r.plan.delivered();
        let lpt_gaps = if delivered {
            r.plan
                .hops
                .iter()
                .filter_map(|h| h.stop.as_ref())
                .map(lpt_gap)
                .collect::<Result<Vec<_>>>()?
        } else {
            Vec::new()
        };
        Ok(Planned {
            outcome: Outcome {
                options: r.options,
                request_id: r.request.id,
                success: delivered,
                outcome: r.plan.outcome.kind(),
                dt_min: r.plan.dt_min,
                nt_min: r.plan.nt_min,
                stops: r.plan.stops().into_iter().map(String::from).collect(),
                failure: (!delivered).then(|| r.plan.outcome.to_string()),
                route_gap: None,
            },
            shared_mah: r.plan.shared_mah,
            hop_solves: r.plan.hop_solves,
            lpt_gaps,
            execution_ms: r.execution_ms,
            route_proven: r.plan.route_optimality.is_none_or(|o| o.proven()),
        })
    }
}

/// Sum starting from +0.0, so that an empty sum prints as 0, not -0.
fn total(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, |a, b| a + b)
}

fn summarise(options: PlanOptions, planned: &[&Planned], wall_ms: f64) -> Result<Summary> {
    let delivered: Vec<&Planned> = planned
        .iter()
        .copied()
        .filter(|p| p.outcome.success)
        .collect();
    let mut failed_by_kind = BTreeMap::new();
    for p in planned.iter().filter(|p| !p.outcome.success) {
        *failed_by_kind.entry(p.outcome.outcome.clone()).or_insert(0) += 1;
    }
    let k = delivered.len().max(1) as f64;
    Ok(Summary {
        options,
        delivered: delivered.len(),
        requests: planned.len(),
        failed_by_kind,
        mean_dt_min: total(delivered.iter().map(|p| p.outcome.dt_min)) / k,
        mean_nt_min: total(delivered.iter().map(|p| p.outcome.nt_min)) / k,
        mean_stops: total(delivered.iter().map(|p| p.outcome.stops.len() as f64)) / k,
        shared_mah: total(delivered.iter().map(|p| p.shared_mah)),
        lpt_node_time: LptGapSummary::of(delivered.iter().flat_map(|p| p.lpt_gaps.iter().copied())),
        hop_solves: options.sharing.is_exact().then(|| {
            let mut sum = HopSolveCounts::default();
            for c in planned.iter().filter_map(|p| p.hop_solves.as_ref()) {
                sum.merge(c);
            }
            sum
        }),
        route_gap: None,
        wall_ms,
    })
}
