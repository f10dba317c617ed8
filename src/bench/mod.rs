//! The experiments of the paper's section 6 and the optimality-gap report (`swarmplan bench`):
//! every request of a request set planned with every method combination, written as tables
//! (one row per request and combination, per hop and per stop), summarised, and drawn.
//! User guide: "bench and bench merge" (`docs/src/commands/bench.md`) and "The bench report"
//! (`docs/src/bench-report.md`).
//!
//! A run plans the requests of its [`Shard`]; every file but `timings.csv` and the times of
//! `summary.json` is a function of the instance, the request set and the [`BenchConfig`] alone, so
//! runs with any thread count, and the merge of shards ([`merge`]), write the same bytes.
//!
//! - `requests.csv` ([`RequestRow`]): the outcome of each request and combination, with its
//!   route gap against the optimal route of the same sharing policy and positioning;
//! - `hops.csv` ([`HopRow`]): on the exact subset (the first `exact_limit` requests of the set),
//!   every hop of a delivered plan under a sharing heuristic (PB, FB) solved again by the
//!   continuous-time model (`models/eaas_config.md`) and the fluid bound, with the heuristic's gap;
//! - `stops.csv` ([`StopRow`]): on the same subset, every stop's exact node time against LPT;
//! - `timings.csv` ([`TimingRow`]): execution times, machine-dependent;
//! - `summary.json` ([`Summary`]), the SVG figures of [`figures`] and the page `report.html`
//!   that shows them all (`report`).

/// Drawn with plotters (feature `plot`; `swarmplan bench` writes them, feature `cli`).
#[cfg(feature = "plot")]
pub mod figures;
mod files;
mod findings;
/// The bench's HTML page, filled by the front ends only (feature `cli`, which brings minijinja).
#[cfg(feature = "cli")]
pub mod report;
mod runner;
mod seal;
mod summary;
pub mod table;

pub use files::{
    may_write, merge, read_data, write_outputs, CONFIG_FILE, DATA_FILES, SUMMARY_FILE,
};
pub use findings::{findings, Finding, Verdict};
pub use runner::{
    run_grid, BenchSettings, GridRun, GridSize, DEFAULT_DISTANCE_BUCKET_KM, DEFAULT_EXACT_LIMIT,
};
pub use seal::{seal_agrees, unmark_complete, verify_seal, Seal, SealedFile, COMPLETE_FILE};
pub use summary::{
    DistanceBucket, GapHistogram, GapSplitSummary, HopGapSummary, JointSummary, MethodSummary,
    StopGapSummary, Summary, GAP_BIN_EDGES, SUMMARY_SCHEMA_VERSION,
};

use crate::compose::{lpt_gap, Context, Hop, Plan, PlanOptions, RequestReport, RouteMethod};
use crate::eaas::compare::{label_gaps, run_method, HopMethod, MethodRow};
use crate::eaas::exact::milp::MilpOptions;
use crate::eaas::exact::EndPads;
use crate::eaas::exact::Objective;
use crate::eaas::{PolicyOptions, SharingPolicy};
use crate::error::{Error, Result};
use crate::experiment::{lpt_gaps, Delivery, Experiment};
use crate::node_time;
use crate::problem::Request;
use crate::solver::ReferenceKind;
use serde::{Deserialize, Serialize};

/// Which requests of the set a run plans: those at positions `index`, `index + count`,
/// `index + 2 count`, ... (`0/1`: every request).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shard {
    /// First position planned, `0 <= index < count`.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    /// The whole request set.
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };

    /// Parses `I/N`.
    ///
    /// # Errors
    /// E7001 when the text is not two integers `I/N` with `0 <= I < N`.
    pub fn parse(text: &str) -> Result<Shard> {
        let parsed = text.split_once('/').and_then(|(i, n)| {
            Some((
                i.trim().parse::<usize>().ok()?,
                n.trim().parse::<usize>().ok()?,
            ))
        });
        match parsed {
            Some((index, count)) if index < count => Ok(Shard { index, count }),
            _ => Err(Error::invalid(
                "E7001",
                "--shard",
                format!("`{text}` is not a shard I/N with 0 <= I < N"),
                "give the shard as I/N, such as 0/4 for the first of 4 shards",
            )),
        }
    }

    /// Whether the request at `position` of the set belongs to the shard.
    pub fn holds(&self, position: usize) -> bool {
        position % self.count == self.index
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// Everything that decides a run's numbers (besides the instance files it names), written to
/// `config.json`: shards merge only when their configurations agree but for the shard.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BenchConfig {
    /// Version of the output files' schema, [`SUMMARY_SCHEMA_VERSION`].
    pub schema_version: u32,
    /// The tool's version (`swarmplan --version`).
    pub version: String,
    /// SHA-256 of the network, profile and requests considered, as read (their JSON): shards of
    /// the same files under the same names merge, others do not.
    pub inputs_sha256: String,
    /// The network, profile and request set, as given (`embedded ...` for the shipped ones).
    pub network: String,
    /// The profile.
    pub profile: String,
    /// The request set.
    pub requests: String,
    /// The method combinations reported, in the order of the files' rows.
    pub combos: Vec<PlanOptions>,
    /// Whether each combination with a simulated sharing policy and a heuristic route is also
    /// planned with `--route optimal` for its route gap.
    pub gap: bool,
    /// Whether each request's joint optimum (`--route optimal --sharing exact` over the swarms
    /// of pre-composition) is computed, and every heuristic combination's gap split against
    /// it (`joint.csv`, the `gap_*` columns of `requests.csv`).
    #[serde(default)]
    pub joint: bool,
    /// Requests of the set considered (the first `limit`); the shards split these.
    pub limit: usize,
    /// Requests (the first of the set) whose hops and stops are solved again exactly.
    pub exact_limit: usize,
    /// The hop models' settings on the exact subset (and of `--sharing exact|fair`).
    pub milp: MilpOptions,
    /// Node limit of the exact node time at every stop.
    pub node_limit: Option<u64>,
    /// Width of the distance buckets of the figures and the summary, m.
    pub distance_bucket_m: f64,
    /// The requests this run planned.
    pub shard: Shard,
}

impl BenchConfig {
    /// The run's combinations and the references they are compared with.
    pub fn experiment(&self) -> Experiment {
        Experiment {
            combos: self.combos.clone(),
            route_gap: self.gap,
            joint: self.joint,
        }
    }

    /// The combinations planned: those reported, then the optimal routes the route gaps need
    /// that are not among them ([`Experiment::planned`]).
    pub fn planned_combos(&self) -> Vec<PlanOptions> {
        self.experiment().planned()
    }

    /// The optimal route a combination's route gap is measured against, when there is one
    /// ([`Experiment::route_reference`]).
    pub fn reference_of(&self, combo: &PlanOptions) -> Option<PlanOptions> {
        self.experiment().route_reference(combo)
    }
}

/// One request planned with one combination: a row of `requests.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RequestRow {
    /// Position of the request in the request set (0-based).
    pub request_index: usize,
    /// Request id.
    pub request_id: String,
    /// Source node id.
    pub source: String,
    /// Destination node id.
    pub destination: String,
    /// Packages (delivery drones).
    pub packages: usize,
    /// Shortest-path distance from source to destination, m.
    pub distance_m: f64,
    /// Sharing policy.
    pub sharing: SharingPolicy,
    /// Support positioning.
    pub positioning: crate::precompose::Positioning,
    /// Route method.
    pub route: RouteMethod,
    /// Support drones flown.
    pub support_drones: usize,
    /// Delivered?
    pub success: bool,
    /// The plan's outcome: `delivered`, `no-route`, `dead-end`, `hop-infeasible`,
    /// `no-stop-sequence`.
    pub outcome: String,
    /// Delivery time, min (of the part flown when not delivered).
    pub dt_min: f64,
    /// Travel time, min.
    pub tt_min: f64,
    /// Node time, min.
    pub nt_min: f64,
    /// Recharging stops.
    pub stops: usize,
    /// Energy shared in flight, mAh.
    pub shared_mah: f64,
    /// Stops whose exact node time is proven optimal (delivered plans only).
    pub lpt_stops: usize,
    /// Of those, stops where LPT's node time equals the optimum (within 1e-9 relative).
    pub lpt_optimal: usize,
    /// Sum of LPT's relative gaps over those stops.
    pub lpt_gap_sum: f64,
    /// `optimal` when the row has a route gap reference (the optimal route of the same sharing
    /// policy and positioning, hops along the shortest path between stops); empty otherwise.
    pub route_gap_reference: String,
    /// The reference's delivery time, min, when it delivers.
    pub optimal_dt_min: Option<f64>,
    /// Whether every node time of the reference's search was proven.
    pub optimal_proven: Option<bool>,
    /// `(dt - dt_opt) / dt_opt` when both deliver (negative only for Dijkstra and
    /// Floyd–Warshall, whose hops follow their own route).
    pub route_gap: Option<f64>,
    /// Unless `--no-joint`: the request's joint optimum over swarms, stop sequences,
    /// continuous-time sharing schedules and pads, min (empty when it does not deliver or was not
    /// computed).
    pub joint_dt_min: Option<f64>,
    /// Unless `--no-joint`: why the split below is not (wholly) taken: `not_delivered`,
    /// `no_reference`, `unproven` (a hop solve stopped by a limit left a reference undecided),
    /// `different_policy`, `outside_reference` (a hop off the hop-path rule: only the sharing
    /// part); empty when every part is taken or for a reference row.
    pub split_label: String,
    /// Unless `--no-joint`: the plan's stop sequence and hop paths flown with the exact schedule
    /// and pads on every hop, `dt` min.
    pub exact_schedule_dt_min: Option<f64>,
    /// Unless `--no-joint`: the optimum of the plan's own swarm under `--sharing exact`, min.
    pub swarm_optimum_dt_min: Option<f64>,
    /// Unless `--no-joint`: `dt - joint_dt` = sharing + route + swarm, min.
    pub gap_total_min: Option<f64>,
    /// Unless `--no-joint`: `dt - exact_schedule_dt`, min: the cost of the heuristic's sharing
    /// schedules.
    pub gap_sharing_min: Option<f64>,
    /// Unless `--no-joint`: `exact_schedule_dt - swarm_optimum_dt`, min: the cost of the route
    /// choice.
    pub gap_route_min: Option<f64>,
    /// Unless `--no-joint`: `swarm_optimum_dt - joint_dt`, min: the cost of pre-composition's
    /// swarm.
    pub gap_swarm_min: Option<f64>,
    /// Unless `--no-joint`: each part is at least `-split_epsilon_min` (0 when every hop optimum is
    /// attained).
    pub split_epsilon_min: Option<f64>,
    /// Unless `--no-joint`: whether every solve behind the split's references is proven.
    pub split_proven: Option<bool>,
}

/// Unless `--no-joint`: one swarm's optimum under `--sharing exact` for one request: a row of
/// `joint.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointRow {
    /// Position of the request in the request set.
    pub request_index: usize,
    /// Request id.
    pub request_id: String,
    /// The positioning the swarm was pre-composed with (`location-aware` for the swarm
    /// without support drones).
    pub positioning: crate::precompose::Positioning,
    /// Support drones.
    pub support_drones: usize,
    /// Whether this swarm's optimum is the request's joint optimum (the first among equals).
    pub best: bool,
    /// Whether it delivers.
    pub delivered: bool,
    /// Delivery time, min.
    pub dt_min: Option<f64>,
    /// Recharging stops.
    pub stops: usize,
    /// Whether every node time and hop solve of the search is proven.
    pub proven: bool,
    /// The certified distance of `dt` to its infimum, min.
    pub epsilon_min: f64,
    /// Arcs of the stop graph flown (a hop solve each).
    pub arcs_flown: usize,
    /// Arcs of the stop graph.
    pub arcs_total: usize,
}

/// One hop of a delivered plan under a sharing heuristic, solved again exactly: a row of
/// `hops.csv`. The objective is the node time at the hop's stop (min, smaller is better), or at
/// the destination the lowest delivery arrival battery (mAh, larger is better).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HopRow {
    /// Position of the request in the request set.
    pub request_index: usize,
    /// Request id.
    pub request_id: String,
    /// Sharing policy (the heuristic).
    pub sharing: SharingPolicy,
    /// Support positioning.
    pub positioning: crate::precompose::Positioning,
    /// Route method.
    pub route: RouteMethod,
    /// Position of the hop in the plan.
    pub hop_index: usize,
    /// Node the hop starts at.
    pub from: String,
    /// Node the hop ends at.
    pub to: String,
    /// Legs (edges) of the hop.
    pub legs: usize,
    /// `node-time` or `max-min-arrival`.
    pub objective: String,
    /// The heuristic's objective value.
    pub heuristic: Option<f64>,
    /// The continuous model's status (`models/eaas_config.md`): `optimal` (over every
    /// continuous-time schedule), `optimal_within` (an infimum approached within `epsilon`),
    /// `infeasible`, `no_schedule_found`, or a time-limit status.
    pub continuous_status: String,
    /// The objective of the continuous model's schedule.
    pub continuous: Option<f64>,
    /// The certified distance of that schedule to the continuous optimum (0 when attained).
    pub epsilon: Option<f64>,
    /// The fluid LP bound (valid for every continuous-time schedule).
    pub fluid_bound: Option<f64>,
    /// What the gap is measured against: `optimal` (the continuous optimum, attained),
    /// `infimum` (the continuous optimum, approached), or `bound` (the fluid LP); empty without
    /// one.
    pub reference: String,
    /// The reference's value.
    pub reference_value: Option<f64>,
    /// The heuristic's relative loss against the reference (docs/src/exact.md, "What a gap is"):
    /// positive is worse under both objectives, the node time (minimised) and the arrival
    /// battery (maximised).
    pub gap: Option<f64>,
    /// `different_policy` when the heuristic's schedule lies outside the re-ordering mode of the
    /// reference (a swapping schedule against `--reorder none`): no gap is taken.
    pub gap_label: String,
}

/// One recharging stop of a delivered plan on the exact subset: a row of `stops.csv`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StopRow {
    /// Position of the request in the request set.
    pub request_index: usize,
    /// Request id.
    pub request_id: String,
    /// Sharing policy.
    pub sharing: SharingPolicy,
    /// Support positioning.
    pub positioning: crate::precompose::Positioning,
    /// Route method.
    pub route: RouteMethod,
    /// Position of the hop ending at the stop.
    pub hop_index: usize,
    /// Node id.
    pub node: String,
    /// Pads.
    pub pads: u32,
    /// Drones charged.
    pub drones: usize,
    /// Exact node time, min.
    pub nt_min: f64,
    /// `optimal`, or `feasible` when the node limit stopped the proof.
    pub status: String,
    /// LPT's node time, min.
    pub lpt_nt_min: f64,
    /// `(lpt - nt) / nt` against the proven optimum; empty when `status` is not `optimal`.
    pub lpt_gap: Option<f64>,
}

/// Execution time of one request and combination (`what` = `plan`), or of one model on one hop
/// of the exact subset (`milp`, `fluid`): a row of `timings.csv`. Machine-dependent.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TimingRow {
    /// Position of the request in the request set.
    pub request_index: usize,
    /// Sharing policy.
    pub sharing: SharingPolicy,
    /// Support positioning.
    pub positioning: crate::precompose::Positioning,
    /// Route method.
    pub route: RouteMethod,
    /// The hop, for `milp` and `fluid`.
    pub hop_index: Option<usize>,
    /// `plan`, `milp` or `fluid`.
    pub what: String,
    /// Wall-clock time, ms.
    pub ms: f64,
}

/// The rows of a run (or of merged shards), in file order: by request position, then
/// combination in the order of [`BenchConfig::combos`], then hop.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BenchData {
    /// `requests.csv`.
    pub requests: Vec<RequestRow>,
    /// `hops.csv`.
    pub hops: Vec<HopRow>,
    /// `stops.csv`.
    pub stops: Vec<StopRow>,
    /// `timings.csv`.
    pub timings: Vec<TimingRow>,
    /// `joint.csv` (unless `--no-joint`).
    pub joint: Vec<JointRow>,
}

/// What is kept of one request: each combination's, and the joint optimum's rows.
type Row = (Vec<Kept>, Vec<JointRow>);

/// What is kept of one request planned with one combination.
struct Kept {
    row: RequestRow,
    /// The delivery time and its proof, for the route gaps.
    delivery: Delivery,
    hops: Vec<HopRow>,
    stops: Vec<StopRow>,
    timings: Vec<TimingRow>,
}

/// Plans the requests of `config.shard` among `requests` (the first `config.limit` of the set)
/// with every combination, on `threads` threads; `done(n)` is called as `n` more request x
/// combination plans are made.
///
/// # Errors
/// Those of [`Context::plan_grid`] and of the hop models on the exact subset.
pub fn run(
    context: &Context,
    requests: &[Request],
    config: &BenchConfig,
    threads: usize,
    done: &(dyn Fn(u64) + Sync),
) -> Result<BenchData> {
    let positions: Vec<usize> = (0..requests.len().min(config.limit))
        .filter(|&i| config.shard.holds(i))
        .collect();
    let planned: Vec<Request> = positions.iter().map(|&i| requests[i].clone()).collect();
    let experiment = config.experiment();
    let combos = experiment.planned();
    let reference_of = experiment.route_reference_positions();
    let keep_row = |i: usize, request: &Request, reports: Vec<RequestReport>| -> Result<Row> {
        rows_of_request(context, config, positions[i], request, reports)
    };
    let grid = context.plan_grid_rows(&planned, &combos, threads, done, &keep_row)?;
    let mut data = BenchData::default();
    for (row, joint) in grid {
        data.joint.extend(joint);
        // Route gaps against the optimal route planned with the request.
        let reference: Vec<Option<Delivery>> = reference_of
            .iter()
            .map(|j| j.map(|j| row[j].delivery))
            .collect();
        for (c, kept) in row.into_iter().enumerate() {
            // The optimal routes planned only as references keep their times alone.
            data.timings.extend(kept.timings);
            let Some(&reference) = reference.get(c) else {
                continue;
            };
            let mut r = kept.row;
            if let Some(reference) = reference {
                r.route_gap_reference = "optimal".into();
                r.optimal_dt_min = reference.dt_min;
                r.optimal_proven = Some(reference.proven);
                r.route_gap = kept.delivery.against(reference).gap();
            }
            data.requests.push(r);
            data.hops.extend(kept.hops);
            data.stops.extend(kept.stops);
        }
    }
    Ok(data)
}

/// The rows of one request: each combination's row, hops, stops and timings (the route gaps
/// are filled in by [`run`], across combinations), and unless `--no-joint` the joint optimum's
/// rows.
fn rows_of_request(
    context: &Context,
    config: &BenchConfig,
    position: usize,
    request: &Request,
    reports: Vec<RequestReport>,
) -> Result<Row> {
    let experiment = config.experiment();
    let graph = context.graph();
    let readings = PolicyOptions::from(&context.profile().readings);
    let distance_m = match (
        graph.index_of(&request.source),
        graph.index_of(&request.destination),
    ) {
        (Some(s), Some(d)) => graph.distances_from_m(s)[d],
        _ => f64::NAN,
    };
    let joint = if experiment.joint {
        Some(context.joint_split(request, &reports)?)
    } else {
        None
    };
    let mut kept = reports
        .into_iter()
        .map(|report| keep_report(context, config, &readings, position, distance_m, report))
        .collect::<Result<Vec<_>>>()?;
    let Some(joint) = joint else {
        return Ok((kept, Vec::new()));
    };
    let joint_dt = joint.joint.dt_min();
    for (k, split) in kept.iter_mut().zip(&joint.splits) {
        let Some(split) = split else { continue };
        let r = &mut k.row;
        r.joint_dt_min = joint_dt;
        r.split_label = split.label.map(|l| serde_name(&l)).unwrap_or_default();
        r.exact_schedule_dt_min = split.exact_schedule_dt_min;
        r.swarm_optimum_dt_min = split.swarm_optimum_dt_min;
        r.gap_total_min = split.total_min;
        r.gap_sharing_min = split.sharing_min;
        r.gap_route_min = split.route_min;
        r.gap_swarm_min = split.swarm_min;
        r.split_epsilon_min = Some(split.epsilon_min);
        r.split_proven = Some(split.proven);
    }
    if let Some(first) = kept.first_mut() {
        first.timings.push(TimingRow {
            request_index: position,
            sharing: SharingPolicy::Exact,
            positioning: crate::precompose::Positioning::LocationAware,
            route: RouteMethod::Optimal,
            hop_index: None,
            what: "joint".into(),
            ms: joint.joint.execution_ms,
        });
    }
    let rows = joint
        .joint
        .swarms
        .iter()
        .enumerate()
        .map(|(s, swarm)| {
            let o = swarm.plan.route_optimality.unwrap_or_default();
            JointRow {
                request_index: position,
                request_id: request.id.clone(),
                positioning: swarm.positioning,
                support_drones: swarm.support_drones,
                best: joint.joint.best == Some(s),
                delivered: swarm.plan.delivered(),
                dt_min: swarm.dt_min(),
                stops: swarm.plan.stops().len(),
                proven: o.proven(),
                epsilon_min: o.epsilon_min,
                arcs_flown: o.arcs_flown,
                arcs_total: o.arcs_total,
            }
        })
        .collect();
    Ok((kept, rows))
}

/// The rows of `hops.csv`, `stops.csv` and `joint.csv` a run writes for the request at
/// `position` of its set, given the plans of every combination the run makes
/// ([`BenchConfig::planned_combos`], in that order): what `check --bench` compares a run's tables
/// with.
///
/// # Errors
/// Those of the hop models on the exact subset and of the joint optimum.
pub fn tables_of_request(
    context: &Context,
    config: &BenchConfig,
    position: usize,
    request: &Request,
    reports: Vec<RequestReport>,
) -> Result<BenchData> {
    let (kept, joint) = rows_of_request(context, config, position, request, reports)?;
    let reported = config.experiment().route_reference_positions().len();
    let mut data = BenchData {
        joint,
        ..BenchData::default()
    };
    for k in kept.into_iter().take(reported) {
        data.hops.extend(k.hops);
        data.stops.extend(k.stops);
    }
    Ok(data)
}

/// The rows of one report; on the exact subset, its hops and stops solved again.
fn keep_report(
    context: &Context,
    config: &BenchConfig,
    readings: &PolicyOptions,
    position: usize,
    distance_m: f64,
    report: RequestReport,
) -> Result<Kept> {
    let plan = &report.plan;
    let o = report.options;
    let lpt = lpt_counts(plan)?;
    let mut kept = Kept {
        row: request_row(&report, position, distance_m, lpt),
        delivery: Delivery::of(plan),
        hops: Vec::new(),
        stops: Vec::new(),
        timings: vec![TimingRow {
            request_index: position,
            sharing: o.sharing,
            positioning: o.positioning,
            route: o.route,
            hop_index: None,
            what: "plan".into(),
            ms: report.execution_ms,
        }],
    };
    let reported = config
        .combos
        .iter()
        .any(|c| c.sharing == o.sharing && c.positioning == o.positioning && c.route == o.route);
    if !plan.delivered() || position >= config.exact_limit || !reported {
        return Ok(kept);
    }
    kept.stops = stop_rows(&report, position)?;
    // Hops under a sharing heuristic (PB, FB): solved again by the continuous model and the
    // fluid bound.
    let heuristic = HopMethod::of_policy(o.sharing);
    if heuristic.heuristic().is_none() || heuristic == HopMethod::None {
        return Ok(kept);
    }
    study_hops(
        context, config, readings, position, &report, heuristic, &mut kept,
    )?;
    Ok(kept)
}

/// LPT at the proven stops of a plan: how many, how many of them LPT meets, and the sum of
/// LPT's gaps (`lpt_stops`, `lpt_optimal`, `lpt_gap_sum`).
fn lpt_counts(plan: &Plan) -> Result<(usize, usize, f64)> {
    let mut lpt = (0, 0, 0.0);
    for gap in lpt_gaps(plan)?.into_iter().flatten() {
        lpt.0 += 1;
        lpt.1 += usize::from(gap.abs() <= crate::solver::ZERO_GAP_TOL);
        lpt.2 += gap;
    }
    Ok(lpt)
}

/// The row of `requests.csv` of a plan, its route gap and joint columns left empty (the run
/// fills them once every combination of the request is planned).
fn request_row(
    report: &RequestReport,
    position: usize,
    distance_m: f64,
    lpt: (usize, usize, f64),
) -> RequestRow {
    let plan = &report.plan;
    let o = report.options;
    RequestRow {
        request_index: position,
        request_id: report.request.id.clone(),
        source: report.request.source.clone(),
        destination: report.request.destination.clone(),
        packages: report.request.packages_kg.len(),
        distance_m,
        sharing: o.sharing,
        positioning: o.positioning,
        route: o.route,
        support_drones: report.support_drones,
        success: plan.delivered(),
        outcome: plan.outcome.kind(),
        dt_min: plan.dt_min,
        tt_min: plan.tt_min,
        nt_min: plan.nt_min,
        stops: plan.hops.iter().filter(|h| h.stop.is_some()).count(),
        shared_mah: plan.shared_mah,
        lpt_stops: lpt.0,
        lpt_optimal: lpt.1,
        lpt_gap_sum: lpt.2,
        route_gap_reference: String::new(),
        optimal_dt_min: None,
        optimal_proven: None,
        route_gap: None,
        joint_dt_min: None,
        split_label: String::new(),
        exact_schedule_dt_min: None,
        swarm_optimum_dt_min: None,
        gap_total_min: None,
        gap_sharing_min: None,
        gap_route_min: None,
        gap_swarm_min: None,
        split_epsilon_min: None,
        split_proven: None,
    }
}

/// The rows of `stops.csv` of a plan: every stop's node time against LPT's.
fn stop_rows(report: &RequestReport, position: usize) -> Result<Vec<StopRow>> {
    let o = report.options;
    let mut rows = Vec::new();
    for (h, hop) in report.plan.hops.iter().enumerate() {
        if let Some(stop) = &hop.stop {
            let lpt = node_time::lpt(stop.pads as usize, &stop.charge_times_min)?;
            rows.push(StopRow {
                request_index: position,
                request_id: report.request.id.clone(),
                sharing: o.sharing,
                positioning: o.positioning,
                route: o.route,
                hop_index: h,
                node: stop.node.clone(),
                pads: stop.pads,
                drones: stop.charge_times_min.len(),
                nt_min: stop.nt_min,
                status: serde_name(&stop.status),
                lpt_nt_min: lpt.makespan_min,
                lpt_gap: lpt_gap(stop)?,
            });
        }
    }
    Ok(rows)
}

/// Every hop of a plan under the sharing `heuristic`, solved again by the continuous model and
/// the fluid bound: a row of `hops.csv` per hop, and the two solve times.
fn study_hops(
    context: &Context,
    config: &BenchConfig,
    readings: &PolicyOptions,
    position: usize,
    report: &RequestReport,
    heuristic: HopMethod,
    kept: &mut Kept,
) -> Result<()> {
    let o = report.options;
    let planner = context.planner(&report.swarm, o.sharing);
    for (h, hop) in report.plan.hops.iter().enumerate() {
        let (problem, objective) = planner.studied_hop(hop)?;
        let mut rows = [heuristic, HopMethod::Continuous, HopMethod::Fluid]
            .into_iter()
            .map(|m| run_method(&problem, &objective, m, &config.milp, readings))
            .collect::<Result<Vec<_>>>()?;
        label_gaps(&mut rows, &problem, &objective, config.milp.reorder);
        let [_, exact, fluid] = &rows[..] else {
            unreachable!("three methods were run")
        };
        for (row, what) in [(exact, "continuous"), (fluid, "fluid")] {
            kept.timings.push(TimingRow {
                request_index: position,
                sharing: o.sharing,
                positioning: o.positioning,
                route: o.route,
                hop_index: Some(h),
                what: what.into(),
                ms: row.solve_ms,
            });
        }
        kept.hops
            .push(hop_row(report, position, h, hop, &objective, &rows));
    }
    Ok(())
}

/// The row of `hops.csv` of hop `h`: the heuristic's, the continuous model's and the fluid
/// bound's results (`rows`, in that order) on it, and the heuristic's gap.
fn hop_row(
    report: &RequestReport,
    position: usize,
    h: usize,
    hop: &Hop,
    objective: &Objective,
    rows: &[MethodRow],
) -> HopRow {
    let o = report.options;
    let [heur, exact, fluid] = rows else {
        unreachable!("three methods were run")
    };
    let reference = crate::eaas::compare::reference(rows);
    HopRow {
        request_index: position,
        request_id: report.request.id.clone(),
        sharing: o.sharing,
        positioning: o.positioning,
        route: o.route,
        hop_index: h,
        from: hop.from.clone(),
        to: hop.to.clone(),
        legs: hop.legs.len(),
        objective: match objective {
            Objective::NodeTime(EndPads { .. }) => "node-time",
            Objective::MaxMinArrival => "max-min-arrival",
            Objective::Feasible => "feasible",
        }
        .into(),
        heuristic: heur.objective,
        continuous_status: exact.status.map(|s| serde_name(&s)).unwrap_or_default(),
        continuous: exact.objective,
        epsilon: exact.epsilon,
        fluid_bound: fluid.bound,
        reference: reference
            .map(|(_, k)| reference_name(k).to_string())
            .unwrap_or_default(),
        reference_value: reference.map(|(v, _)| v),
        gap: heur.gap.and_then(|g| g.relative),
        gap_label: heur
            .gap_label
            .map(|l| crate::problem::io::json_name(&l))
            .unwrap_or_default(),
    }
}

/// SHA-256, in hex, of the JSON of `network`, `profile` and `requests` as read: the fingerprint
/// of a run's inputs in [`BenchConfig::inputs_sha256`].
///
/// # Errors
/// Only if the inputs do not serialise (they always do).
pub fn inputs_sha256(
    network: &crate::problem::Network,
    profile: &crate::problem::Profile,
    requests: &[Request],
) -> Result<String> {
    Ok(crate::problem::fingerprint::sha256_json(&(
        network, profile, requests,
    )))
}

/// The name of a reference kind as in JSON.
pub fn reference_name(kind: ReferenceKind) -> &'static str {
    match kind {
        ReferenceKind::Optimal => "optimal",
        ReferenceKind::Incumbent => "incumbent",
        ReferenceKind::Bound => "bound",
        ReferenceKind::Infimum => "infimum",
    }
}

/// The serde name of a unit enum value.
fn serde_name<T: Serialize>(value: &T) -> String {
    serde_json::to_value(value)
        .ok()
        .and_then(|v| v.as_str().map(String::from))
        .unwrap_or_default()
}
