//! A grid of requests x combinations planned and summarised per combination (`swarmplan
//! batch`): success counts with their denominator, delivery and node times, LPT's gap, the hop
//! solves of the exact policies, the route gap, and run time; each summary also as a CSV row.
//!
//! The grid runs on a local rayon pool ([`Context::plan_grid`]): one job per request plans every
//! combination of it ([`Context::plan_each`], which does the work they share once), and the
//! results come back in request order, so every number but the times is the same for any thread
//! count.

use super::{display_f64, display_opt_f64, lpt_gaps, Delivery, Experiment};
use crate::compose::{Context, LptGapSummary, PlanOptions, RequestReport, RouteGapSummary};
use crate::compose::{RouteMethod, RoutePair};
use crate::eaas::exact_hop::HopSolveCounts;
use crate::eaas::SharingPolicy;
use crate::error::Result;
use crate::precompose::Positioning;
use crate::problem::Request;
use serde::Serialize;
use std::collections::BTreeMap;
use std::time::Instant;

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
    /// With the route gap measured: the route gap against the optimal route (`None` for
    /// `optimal` itself and the fair policy).
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

/// One request's outcome with one combination (`batch --per-request`).
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
    /// With the route gap measured, when both delivered: `(dt - dt_opt) / dt_opt` against the
    /// optimal route.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub route_gap: Option<f64>,
}

/// A grid planned and summarised ([`summarise_grid`]).
#[derive(Debug, Clone)]
pub struct GridSummary {
    /// One summary per reported combination, in their order.
    pub summaries: Vec<Summary>,
    /// With `per_request`: every request's outcome, combination by combination in their order,
    /// requests in set order; empty otherwise.
    pub outcomes: Vec<Outcome>,
    /// Requests planned: all those given, or those before the first one the context's deadline
    /// left out.
    pub requests: usize,
    /// Combinations planned: those reported and the route gaps' references.
    pub planned_combos: usize,
    /// Wall-clock time of planning the grid, ms.
    pub grid_ms: f64,
}

/// Plans every request with every combination [`Experiment::planned`] on `threads` threads and
/// summarises each reported combination; `done(n)` is called as `n` more request x combination
/// plans are made (from worker threads). With a [`Context::deadline`], the requests planned are
/// those before the first one not started by then.
///
/// # Errors
/// Those of [`Context::plan_grid`], and of LPT at a stop whose charge times are not valid
/// node-time input.
///
/// # Complexity
/// That of [`Context::plan_grid`], plus linear work in the plans' stops.
pub fn summarise_grid(
    context: &Context,
    requests: &[Request],
    experiment: &Experiment,
    threads: usize,
    done: &(dyn Fn(u64) + Sync),
    per_request: bool,
) -> Result<GridSummary> {
    let combos = experiment.planned();
    let reference_of = experiment.route_reference_positions();
    let start = Instant::now();
    let grid = context.plan_grid(requests, &combos, threads, done, &|_, r| Planned::of(r))?;
    let grid_ms = start.elapsed().as_secs_f64() * 1e3;
    let mut summaries = Vec::new();
    let mut outcomes = Vec::new();
    for (c, &options) in experiment.combos.iter().enumerate() {
        let planned: Vec<&Planned> = grid.iter().map(|row| &row[c]).collect();
        let wall_ms = total(planned.iter().map(|p| p.execution_ms));
        let mut summary = summarise(options, &planned, wall_ms);
        let pairs: Option<Vec<RoutePair>> = reference_of[c].map(|j| {
            grid.iter()
                .map(|row| row[c].delivery.against(row[j].delivery))
                .collect()
        });
        summary.route_gap = pairs
            .as_ref()
            .map(|p| RouteGapSummary::of(p.iter().copied()).with_hop_paths(context.hop_paths));
        if per_request {
            outcomes.extend(planned.iter().enumerate().map(|(r, p)| Outcome {
                route_gap: pairs.as_ref().and_then(|pairs| pairs[r].gap()),
                ..p.outcome.clone()
            }));
        }
        summaries.push(summary);
    }
    Ok(GridSummary {
        summaries,
        outcomes,
        requests: grid.len(),
        planned_combos: combos.len(),
        grid_ms,
    })
}

/// What the summaries and the per-request outcomes keep of one request planned with one
/// combination.
struct Planned {
    /// The request's outcome.
    outcome: Outcome,
    /// The delivery time and its proof, for the route gap.
    delivery: Delivery,
    /// Energy shared in flight, mAh.
    shared_mah: f64,
    /// LPT's gap at every recharging stop ([`lpt_gaps`]); the stops themselves are not kept.
    lpt_gaps: Vec<Option<f64>>,
    /// The hop solves of `exact` and `fair`.
    hop_solves: Option<HopSolveCounts>,
    /// Execution time, ms ([`RequestReport::execution_ms`]).
    execution_ms: f64,
}

impl Planned {
    fn of(r: RequestReport) -> Result<Self> {
        let delivered = r.plan.delivered();
        Ok(Planned {
            lpt_gaps: lpt_gaps(&r.plan)?,
            delivery: Delivery::of(&r.plan),
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
            execution_ms: r.execution_ms,
        })
    }
}

/// Sum starting from +0.0, so that an empty sum prints as 0, not -0.
fn total(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, |a, b| a + b)
}

fn summarise(options: PlanOptions, planned: &[&Planned], wall_ms: f64) -> Summary {
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
    Summary {
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
    }
}

/// A [`Summary`] as a row of `batch`'s CSV: every number as the JSON has it, with all its digits,
/// written as Rust's `Display` writes it (the cells `batch` has always written).
#[derive(Debug, Clone, Serialize)]
pub struct SummaryRow {
    /// Sharing policy.
    pub sharing: SharingPolicy,
    /// Support positioning.
    pub positioning: Positioning,
    /// Route method.
    pub route: RouteMethod,
    /// Requests delivered.
    pub delivered: usize,
    /// Requests planned.
    pub requests: usize,
    /// Mean delivery time of the delivered, min.
    #[serde(serialize_with = "display_f64")]
    pub mean_dt_min: f64,
    /// Mean node time of the delivered, min.
    #[serde(serialize_with = "display_f64")]
    pub mean_nt_min: f64,
    /// Mean recharging stops of the delivered.
    #[serde(serialize_with = "display_f64")]
    pub mean_stops: f64,
    /// Stops compared against a proven optimum node time.
    pub stops: usize,
    /// Of those, stops where LPT is optimal.
    pub lpt_optimal: usize,
    /// LPT's mean gap over those stops.
    #[serde(serialize_with = "display_f64")]
    pub lpt_mean_gap: f64,
    /// LPT's largest gap.
    #[serde(serialize_with = "display_f64")]
    pub lpt_max_gap: f64,
    /// Hop solves of `exact` and `fair` (0 for the others).
    pub hop_solves: usize,
    /// Of those, the solves a limit stopped or the backend failed.
    pub hop_solves_unproven: usize,
    /// Time spent planning the combination, ms ([`Summary::wall_ms`]).
    #[serde(serialize_with = "display_f64")]
    pub wall_ms: f64,
}

impl SummaryRow {
    /// The row of `s`.
    pub fn of(s: &Summary) -> SummaryRow {
        let hops = s.hop_solves.unwrap_or_default();
        SummaryRow {
            sharing: s.options.sharing,
            positioning: s.options.positioning,
            route: s.options.route,
            delivered: s.delivered,
            requests: s.requests,
            mean_dt_min: s.mean_dt_min,
            mean_nt_min: s.mean_nt_min,
            mean_stops: s.mean_stops,
            stops: s.lpt_node_time.stops,
            lpt_optimal: s.lpt_node_time.lpt_optimal,
            lpt_mean_gap: s.lpt_node_time.mean_gap,
            lpt_max_gap: s.lpt_node_time.max_gap,
            hop_solves: hops.solves,
            hop_solves_unproven: hops.time_limit_incumbent
                + hops.time_limit_no_solution
                + hops.backend_errors,
            wall_ms: s.wall_ms,
        }
    }
}

/// The route gap cells that follow a [`SummaryRow`] when the route gaps are measured: empty for a
/// combination without a reference (`optimal` itself, `fair`).
#[derive(Debug, Clone, Default, Serialize)]
pub struct RouteGapCells {
    /// `optimal` (hops along the shortest path between stops) or `optimal-any-path`.
    pub route_gap_reference: Option<&'static str>,
    /// Requests both delivered.
    pub route_gap_compared: Option<usize>,
    /// Of those, at gap 0.
    pub route_gap_zero: Option<usize>,
    /// Mean gap.
    #[serde(serialize_with = "display_opt_f64")]
    pub route_gap_mean: Option<f64>,
    /// Largest gap.
    #[serde(serialize_with = "display_opt_f64")]
    pub route_gap_max: Option<f64>,
    /// Smallest gap.
    #[serde(serialize_with = "display_opt_f64")]
    pub route_gap_min: Option<f64>,
    /// Requests the heuristic fails and the optimum delivers.
    pub heuristic_fails_optimum_delivers: Option<usize>,
    /// Requests the optimum fails and the heuristic delivers.
    pub optimum_fails_heuristic_delivers: Option<usize>,
    /// Compared requests whose optimum is proven only for the node times found.
    pub route_gap_unproven_references: Option<usize>,
}

impl RouteGapCells {
    /// The cells of a combination's route gap (all empty for `None`).
    pub fn of(gap: Option<&RouteGapSummary>) -> RouteGapCells {
        let Some(g) = gap else {
            return RouteGapCells::default();
        };
        RouteGapCells {
            route_gap_reference: Some(g.reference_name()),
            route_gap_compared: Some(g.compared),
            route_gap_zero: Some(g.at_zero),
            route_gap_mean: Some(g.mean_gap),
            route_gap_max: Some(g.max_gap),
            route_gap_min: Some(g.min_gap),
            heuristic_fails_optimum_delivers: Some(g.heuristic_fails_optimum_delivers),
            optimum_fails_heuristic_delivers: Some(g.optimum_fails_heuristic_delivers),
            route_gap_unproven_references: Some(g.unproven_references),
        }
    }
}

/// Writes `summaries` as `batch`'s CSV to `out`: a [`SummaryRow`] per combination, followed by
/// its [`RouteGapCells`] when `route_gap` (the route gaps were measured).
///
/// # Errors
/// The writer's.
pub fn write_summaries<W: std::io::Write>(
    out: W,
    summaries: &[Summary],
    route_gap: bool,
) -> std::io::Result<()> {
    if route_gap {
        super::write_csv(
            out,
            summaries
                .iter()
                .map(|s| (SummaryRow::of(s), RouteGapCells::of(s.route_gap.as_ref()))),
        )
    } else {
        super::write_csv(out, summaries.iter().map(SummaryRow::of))
    }
}
