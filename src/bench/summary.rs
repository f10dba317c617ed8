//! `summary.json`: every figure of a run, computed from its rows alone (so that one run and the
//! merge of its shards give the same summary but for the times).

use super::{BenchConfig, BenchData, Finding, RequestRow};
use crate::compose::{PlanOptions, RouteGapSummary, RoutePair};
use crate::eaas::SharingPolicy;
use crate::solver::ZERO_GAP_TOL;
use serde::Serialize;
use std::collections::BTreeMap;

/// Version of the schema of `summary.json`, `config.json` and the CSV files.
///
/// 4: `hops.csv`'s `gap` is a loss under both objectives (into a destination it was
/// `(heuristic - reference) / reference`, negative for a loss).
pub const SUMMARY_SCHEMA_VERSION: u32 = 4;

/// Upper edges of the gap histograms' bins after the bins `< 0` and `0`: `(0, 1%]`, `(1%, 5%]`,
/// ..., `(200%, 500%]`, then `> 500%`.
pub const GAP_BIN_EDGES: [f64; 8] = [0.01, 0.05, 0.1, 0.25, 0.5, 1.0, 2.0, 5.0];

/// Counts of gaps in the bins of [`GAP_BIN_EDGES`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GapHistogram {
    /// The bins' labels: `< 0`, `0`, `(0, 1%]`, ..., `> 500%`.
    pub bins: Vec<String>,
    /// The gaps in each bin.
    pub counts: Vec<usize>,
}

impl GapHistogram {
    /// The histogram of `gaps`.
    pub fn of(gaps: impl IntoIterator<Item = f64>) -> GapHistogram {
        let percent = |x: f64| format!("{}%", x * 100.0);
        let mut bins = vec!["< 0".to_string(), "0".to_string()];
        let mut lower = 0.0;
        for &e in &GAP_BIN_EDGES {
            bins.push(format!(
                "({}, {}]",
                if lower == 0.0 {
                    "0".to_string()
                } else {
                    percent(lower)
                },
                percent(e)
            ));
            lower = e;
        }
        bins.push(format!("> {}", percent(lower)));
        let mut counts = vec![0; bins.len()];
        for g in gaps {
            let bin = if g.abs() <= ZERO_GAP_TOL {
                1
            } else if g < 0.0 {
                0
            } else {
                2 + GAP_BIN_EDGES.iter().take_while(|&&e| g > e).count()
            };
            counts[bin] += 1;
        }
        GapHistogram { bins, counts }
    }
}

/// The requests of one distance bucket for one combination.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DistanceBucket {
    /// Lower edge (included), m.
    pub from_m: f64,
    /// Upper edge (excluded), m.
    pub to_m: f64,
    /// Requests in the bucket.
    pub requests: usize,
    /// Of those, delivered.
    pub delivered: usize,
    /// Mean delivery time of the delivered, min.
    pub mean_dt_min: Option<f64>,
    /// Mean node time of the delivered, min.
    pub mean_nt_min: Option<f64>,
}

/// One combination over the requests of the run.
#[derive(Debug, Clone, Serialize)]
pub struct MethodSummary {
    /// The combination.
    pub options: PlanOptions,
    /// Requests delivered.
    pub delivered: usize,
    /// Requests planned (the denominator).
    pub requests: usize,
    /// Requests not delivered, by outcome kind.
    pub failed_by_kind: BTreeMap<String, usize>,
    /// Mean delivery time of the delivered, min (0 when none is).
    pub mean_dt_min: f64,
    /// Mean travel time of the delivered, min.
    pub mean_tt_min: f64,
    /// Mean node time of the delivered, min.
    pub mean_nt_min: f64,
    /// Mean recharging stops of the delivered.
    pub mean_stops: f64,
    /// Energy shared in flight over the delivered, mAh.
    pub shared_mah: f64,
    /// Stops of the delivered whose exact node time is proven (LPT's gaps are over these).
    pub lpt_stops: usize,
    /// Of those, stops where LPT is optimal.
    pub lpt_optimal: usize,
    /// Mean gap of LPT over those stops.
    pub lpt_mean_gap: f64,
    /// The route gap against the optimal route, when the run measured it.
    pub route_gap: Option<RouteGapSummary>,
    /// The route gaps' histogram.
    pub route_gap_histogram: Option<GapHistogram>,
    /// The route gaps of the requests both deliver, ascending: the data of the figure
    /// `route-gap-cdf.svg`. Not in `summary.json`: `requests.csv` holds them, per request.
    #[serde(skip)]
    pub route_gaps: Option<Vec<f64>>,
    /// Unless `--no-joint`: the gap to the joint optimum split into its parts.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gap_split: Option<GapSplitSummary>,
    /// The requests by source–destination distance.
    pub by_distance: Vec<DistanceBucket>,
    /// Execution time over the requests, ms (machine-dependent): total.
    pub exec_ms_total: f64,
    /// Median execution time per request, ms.
    pub exec_ms_median: f64,
    /// Longest execution time of a request, ms.
    pub exec_ms_max: f64,
}

/// One combination's gaps to the joint optimum, split (unless `--no-joint`; models/compose.md, "Gap
/// split"). Means are over the requests split wholly (`split`), in minutes, and in % of the
/// joint optimum's `dt` (the mean of each part over `dt_joint`).
#[derive(Debug, Clone, Serialize)]
pub struct GapSplitSummary {
    /// Requests whose gap is split into all three parts.
    pub split: usize,
    /// Requests delivered whose route leaves the hop-path rule: only the sharing part.
    pub outside_reference: usize,
    /// Requests delivered whose schedules lie outside `--reorder none`: no part.
    pub different_policy: usize,
    /// Requests the joint optimum delivers and the combination does not.
    pub joint_only: usize,
    /// Requests the combination delivers and the joint optimum does not (always 0: the joint
    /// optimum's swarms and schedules contain the combination's).
    pub heuristic_only: usize,
    /// Requests split whose references are all proven.
    pub proven: usize,
    /// Mean `dt - dt_joint`, min.
    pub mean_total_min: f64,
    /// Mean sharing part, min.
    pub mean_sharing_min: f64,
    /// Mean route part, min.
    pub mean_route_min: f64,
    /// Mean swarm part, min.
    pub mean_swarm_min: f64,
    /// Mean of `total / dt_joint`.
    pub mean_total_pct: f64,
    /// Mean of `sharing / dt_joint`.
    pub mean_sharing_pct: f64,
    /// Mean of `route / dt_joint`.
    pub mean_route_pct: f64,
    /// Mean of `swarm / dt_joint`.
    pub mean_swarm_pct: f64,
    /// The least part over the requests split (`>= -max_epsilon_min`).
    pub min_part_min: f64,
    /// The largest certified distance behind a split, min.
    pub max_epsilon_min: f64,
}

/// The joint optimum over the requests of the run (unless `--no-joint`).
#[derive(Debug, Clone, Serialize)]
pub struct JointSummary {
    /// Requests.
    pub requests: usize,
    /// Requests the joint optimum delivers.
    pub delivered: usize,
    /// Requests whose every swarm's search is proven.
    pub proven: usize,
    /// Of the delivered, those whose best swarm's optimum is approached (epsilon > 0).
    pub within: usize,
    /// The largest epsilon of a best swarm, min.
    pub max_epsilon_min: f64,
    /// Delivered by the swarm without support drones alone, not by a swarm with them.
    pub best_without_support: usize,
    /// Mean joint `dt` over the delivered, min.
    pub mean_dt_min: f64,
    /// Arcs flown over every swarm's search.
    pub arcs_flown: usize,
    /// Arcs of the stop graphs searched.
    pub arcs_total: usize,
    /// Execution time per request (searches and replays), ms (machine-dependent): median.
    pub ms_median: f64,
    /// 90th percentile, ms.
    pub ms_p90: f64,
    /// Longest, ms.
    pub ms_max: f64,
    /// Total, ms.
    pub ms_total: f64,
}

/// A sharing heuristic's hops on the exact subset against the hop's continuous-time optimum.
#[derive(Debug, Clone, Serialize)]
pub struct HopGapSummary {
    /// The heuristic.
    pub sharing: SharingPolicy,
    /// Hops solved again.
    pub hops: usize,
    /// Hops whose reference is the continuous optimum, attained.
    pub against_optimal: usize,
    /// Hops whose reference is the continuous optimum, an infimum approached.
    pub against_infimum: usize,
    /// Hops whose reference is the fluid bound (no continuous optimum).
    pub against_bound: usize,
    /// Hops with no gap: the heuristic's schedule is outside the reference's re-ordering mode.
    pub different_policy: usize,
    /// Of the hops against the optimum (attained or approached), those where the heuristic is
    /// optimal (loss 0).
    pub at_zero: usize,
    /// Mean loss against the optimum: the relative gap signed so that positive is worse (the
    /// gap for a node time, minus the gap for an arrival battery).
    pub mean_loss: f64,
    /// Largest loss against the optimum.
    pub max_loss: f64,
    /// Histogram of the losses against the optimum.
    pub histogram: GapHistogram,
    /// Hops where the heuristic is better than the continuous optimum (loss below 0): always 0,
    /// since every PB or FB schedule of the mode is a continuous-time schedule.
    pub below_optimum: usize,
    /// Time of the continuous solves, ms (machine-dependent): total.
    pub continuous_ms_total: f64,
    /// Median continuous solve, ms.
    pub continuous_ms_median: f64,
    /// Longest continuous solve, ms.
    pub continuous_ms_max: f64,
}

/// LPT against the exact node time over the stops of the exact subset.
#[derive(Debug, Clone, Serialize)]
pub struct StopGapSummary {
    /// Stops.
    pub stops: usize,
    /// Of those, proven optimal (LPT's gap is over these).
    pub proven: usize,
    /// Of those, LPT optimal.
    pub lpt_optimal: usize,
    /// Mean gap.
    pub mean_gap: f64,
    /// Largest gap.
    pub max_gap: f64,
    /// Histogram of the gaps.
    pub histogram: GapHistogram,
}

/// `summary.json`.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    /// [`SUMMARY_SCHEMA_VERSION`].
    pub schema_version: u32,
    /// The command line that wrote the directory.
    pub command: Vec<String>,
    /// swarmplan's version.
    pub version: String,
    /// The run's configuration.
    pub config: BenchConfig,
    /// Requests planned (per combination).
    pub requests_planned: usize,
    /// One entry per combination, in the order of the configuration.
    pub methods: Vec<MethodSummary>,
    /// Per sharing heuristic, its hops on the exact subset.
    pub hop_gaps: Vec<HopGapSummary>,
    /// The stops of the exact subset.
    pub stop_gaps: StopGapSummary,
    /// Unless `--no-joint`: the joint optimum over the requests.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint: Option<JointSummary>,
    /// The paper's findings.
    pub findings: Vec<Finding>,
    /// The figure files written, relative to the output directory.
    pub figures: Vec<String>,
}

/// Sum from +0.0, in order.
pub(super) fn total(values: impl Iterator<Item = f64>) -> f64 {
    values.fold(0.0, |a, b| a + b)
}

/// The median of `values` (0 for none).
fn median(mut values: Vec<f64>) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        (values[n / 2 - 1] + values[n / 2]) / 2.0
    }
}

/// Whether `row` is of the combination `o` (support drones aside).
pub(super) fn is_of(
    row_options: (
        SharingPolicy,
        crate::precompose::Positioning,
        crate::compose::RouteMethod,
    ),
    o: &PlanOptions,
) -> bool {
    row_options == (o.sharing, o.positioning, o.route)
}

/// The rows of combination `o`, in request order.
pub(super) fn rows_of<'a>(data: &'a BenchData, o: &PlanOptions) -> Vec<&'a RequestRow> {
    data.requests
        .iter()
        .filter(|r| is_of((r.sharing, r.positioning, r.route), o))
        .collect()
}

fn mean_of(rows: &[&RequestRow], f: impl Fn(&RequestRow) -> f64) -> f64 {
    total(rows.iter().map(|r| f(r))) / rows.len().max(1) as f64
}

fn method_summary(config: &BenchConfig, data: &BenchData, o: &PlanOptions) -> MethodSummary {
    let rows = rows_of(data, o);
    let delivered: Vec<&RequestRow> = rows.iter().copied().filter(|r| r.success).collect();
    let mut failed_by_kind = BTreeMap::new();
    for r in rows.iter().filter(|r| !r.success) {
        *failed_by_kind.entry(r.outcome.clone()).or_insert(0) += 1;
    }
    let lpt_stops = delivered.iter().map(|r| r.lpt_stops).sum::<usize>();
    let measured = rows.iter().any(|r| !r.route_gap_reference.is_empty());
    let route_gap = measured.then(|| {
        RouteGapSummary::of(rows.iter().map(|r| RoutePair {
            heuristic_dt_min: r.success.then_some(r.dt_min),
            optimal_dt_min: r.optimal_dt_min,
            optimal_proven: r.optimal_proven.unwrap_or(true),
        }))
    });
    let route_gaps = measured.then(|| {
        let mut gaps: Vec<f64> = rows.iter().filter_map(|r| r.route_gap).collect();
        gaps.sort_by(f64::total_cmp);
        gaps
    });
    let route_gap_histogram = route_gaps
        .as_ref()
        .map(|gaps| GapHistogram::of(gaps.iter().copied()));
    // Buckets by distance, those with requests only, in order: the rows sorted by bucket (a
    // whole number as f64, so any width > 0 works, however narrow), then each run of a bucket.
    let width = config.distance_bucket_m;
    let mut by_bucket: Vec<(f64, &RequestRow)> = rows
        .iter()
        .map(|&r| {
            let b = (r.distance_m / width).floor();
            (if b.is_nan() { 0.0 } else { b }, r)
        })
        .collect();
    by_bucket.sort_by(|a, b| a.0.total_cmp(&b.0));
    let by_distance: Vec<DistanceBucket> = by_bucket
        .chunk_by(|a, b| a.0 == b.0)
        .map(|run| {
            let b = run[0].0;
            let ok: Vec<&RequestRow> = run.iter().map(|x| x.1).filter(|r| r.success).collect();
            DistanceBucket {
                from_m: b * width,
                to_m: (b + 1.0) * width,
                requests: run.len(),
                delivered: ok.len(),
                mean_dt_min: (!ok.is_empty()).then(|| mean_of(&ok, |r| r.dt_min)),
                mean_nt_min: (!ok.is_empty()).then(|| mean_of(&ok, |r| r.nt_min)),
            }
        })
        .collect();
    let times: Vec<f64> = data
        .timings
        .iter()
        .filter(|t| t.what == "plan" && is_of((t.sharing, t.positioning, t.route), o))
        .map(|t| t.ms)
        .collect();
    MethodSummary {
        options: *o,
        delivered: delivered.len(),
        requests: rows.len(),
        failed_by_kind,
        mean_dt_min: mean_of(&delivered, |r| r.dt_min),
        mean_tt_min: mean_of(&delivered, |r| r.tt_min),
        mean_nt_min: mean_of(&delivered, |r| r.nt_min),
        mean_stops: mean_of(&delivered, |r| r.stops as f64),
        shared_mah: total(delivered.iter().map(|r| r.shared_mah)),
        lpt_stops,
        lpt_optimal: delivered.iter().map(|r| r.lpt_optimal).sum(),
        lpt_mean_gap: total(delivered.iter().map(|r| r.lpt_gap_sum)) / lpt_stops.max(1) as f64,
        route_gap,
        route_gap_histogram,
        route_gaps,
        gap_split: config.joint.then(|| gap_split_summary(&rows)),
        by_distance,
        exec_ms_total: total(times.iter().copied()),
        exec_ms_median: median(times.clone()),
        exec_ms_max: times.iter().copied().fold(0.0, f64::max),
    }
}

fn gap_split_summary(rows: &[&RequestRow]) -> GapSplitSummary {
    let split: Vec<&RequestRow> = rows
        .iter()
        .copied()
        .filter(|r| r.gap_total_min.is_some())
        .collect();
    let label = |l: &str| rows.iter().filter(|r| r.split_label == l).count();
    let part = |r: &RequestRow, f: fn(&RequestRow) -> Option<f64>| f(r).unwrap_or(0.0);
    let mean = |f: fn(&RequestRow) -> Option<f64>| mean_of(&split, |r| part(r, f));
    let mean_pct = |f: fn(&RequestRow) -> Option<f64>| {
        mean_of(&split, |r| {
            part(r, f) / r.joint_dt_min.filter(|&d| d > 0.0).unwrap_or(f64::INFINITY)
        })
    };
    let parts: [fn(&RequestRow) -> Option<f64>; 3] = [
        |r| r.gap_sharing_min,
        |r| r.gap_route_min,
        |r| r.gap_swarm_min,
    ];
    GapSplitSummary {
        split: split.len(),
        outside_reference: label("outside_reference"),
        different_policy: label("different_policy"),
        joint_only: rows
            .iter()
            .filter(|r| !r.success && r.joint_dt_min.is_some())
            .count(),
        heuristic_only: rows
            .iter()
            .filter(|r| r.success && r.joint_dt_min.is_none() && r.split_proven.is_some())
            .count(),
        proven: split
            .iter()
            .filter(|r| r.split_proven == Some(true))
            .count(),
        mean_total_min: mean(|r| r.gap_total_min),
        mean_sharing_min: mean(parts[0]),
        mean_route_min: mean(parts[1]),
        mean_swarm_min: mean(parts[2]),
        mean_total_pct: mean_pct(|r| r.gap_total_min),
        mean_sharing_pct: mean_pct(parts[0]),
        mean_route_pct: mean_pct(parts[1]),
        mean_swarm_pct: mean_pct(parts[2]),
        min_part_min: split
            .iter()
            .flat_map(|r| parts.iter().map(move |f| part(r, *f)))
            .fold(0.0, f64::min),
        max_epsilon_min: split
            .iter()
            .filter_map(|r| r.split_epsilon_min)
            .fold(0.0, f64::max),
    }
}

fn joint_summary(data: &BenchData) -> JointSummary {
    let mut requests: Vec<usize> = data.joint.iter().map(|j| j.request_index).collect();
    requests.dedup();
    let best: Vec<&super::JointRow> = data.joint.iter().filter(|j| j.best).collect();
    let proven = requests
        .iter()
        .filter(|&&i| {
            data.joint
                .iter()
                .filter(|j| j.request_index == i)
                .all(|j| j.proven)
        })
        .count();
    let times: Vec<f64> = data
        .timings
        .iter()
        .filter(|t| t.what == "joint")
        .map(|t| t.ms)
        .collect();
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    let p90 = sorted
        .get(((sorted.len().max(1) - 1) as f64 * 0.9).round() as usize)
        .copied()
        .unwrap_or(0.0);
    JointSummary {
        requests: requests.len(),
        delivered: best.len(),
        proven,
        within: best.iter().filter(|j| j.epsilon_min > 0.0).count(),
        max_epsilon_min: best.iter().map(|j| j.epsilon_min).fold(0.0, f64::max),
        best_without_support: best.iter().filter(|j| j.support_drones == 0).count(),
        mean_dt_min: total(best.iter().map(|j| j.dt_min.unwrap_or(0.0))) / best.len().max(1) as f64,
        arcs_flown: data.joint.iter().map(|j| j.arcs_flown).sum(),
        arcs_total: data.joint.iter().map(|j| j.arcs_total).sum(),
        ms_median: median(times.clone()),
        ms_p90: p90,
        ms_max: times.iter().copied().fold(0.0, f64::max),
        ms_total: total(times.iter().copied()),
    }
}

fn hop_gap_summary(data: &BenchData, sharing: SharingPolicy) -> HopGapSummary {
    let hops: Vec<&super::HopRow> = data.hops.iter().filter(|h| h.sharing == sharing).collect();
    // A gap is a loss under either sense of the objective (solver::Gap).
    let loss = |h: &super::HopRow| h.gap;
    let optimal: Vec<f64> = hops
        .iter()
        .filter(|h| h.reference == "optimal" || h.reference == "infimum")
        .filter_map(|h| loss(h))
        .collect();
    let times: Vec<f64> = data
        .timings
        .iter()
        .filter(|t| t.what == "continuous" && t.sharing == sharing)
        .map(|t| t.ms)
        .collect();
    HopGapSummary {
        sharing,
        hops: hops.len(),
        against_optimal: hops.iter().filter(|h| h.reference == "optimal").count(),
        against_infimum: hops.iter().filter(|h| h.reference == "infimum").count(),
        against_bound: hops.iter().filter(|h| h.reference == "bound").count(),
        different_policy: hops
            .iter()
            .filter(|h| h.gap_label == "different_policy")
            .count(),
        at_zero: optimal.iter().filter(|g| g.abs() <= ZERO_GAP_TOL).count(),
        mean_loss: total(optimal.iter().copied()) / optimal.len().max(1) as f64,
        max_loss: optimal.iter().copied().fold(0.0, f64::max),
        histogram: GapHistogram::of(optimal.iter().copied()),
        below_optimum: optimal.iter().filter(|&&g| g < -ZERO_GAP_TOL).count(),
        continuous_ms_total: total(times.iter().copied()),
        continuous_ms_median: median(times.clone()),
        continuous_ms_max: times.iter().copied().fold(0.0, f64::max),
    }
}

fn stop_gap_summary(data: &BenchData) -> StopGapSummary {
    let gaps: Vec<f64> = data.stops.iter().filter_map(|s| s.lpt_gap).collect();
    StopGapSummary {
        stops: data.stops.len(),
        proven: gaps.len(),
        lpt_optimal: gaps.iter().filter(|g| g.abs() <= ZERO_GAP_TOL).count(),
        mean_gap: total(gaps.iter().copied()) / gaps.len().max(1) as f64,
        max_gap: gaps.iter().copied().fold(0.0, f64::max),
        histogram: GapHistogram::of(gaps.iter().copied()),
    }
}

impl Summary {
    /// The summary of `data`, planned with `config` by `command`; the findings and figures are
    /// filled in by the caller.
    pub fn of(config: &BenchConfig, data: &BenchData, command: Vec<String>) -> Summary {
        let methods: Vec<MethodSummary> = config
            .combos
            .iter()
            .map(|o| method_summary(config, data, o))
            .collect();
        let mut sharing: Vec<SharingPolicy> = Vec::new();
        for h in &data.hops {
            if !sharing.contains(&h.sharing) {
                sharing.push(h.sharing);
            }
        }
        sharing.sort_by_key(|s| config.combos.iter().position(|c| c.sharing == *s));
        Summary {
            schema_version: SUMMARY_SCHEMA_VERSION,
            command,
            version: env!("CARGO_PKG_VERSION").to_string(),
            config: config.clone(),
            requests_planned: methods.first().map_or(0, |m| m.requests),
            hop_gaps: sharing
                .into_iter()
                .map(|s| hop_gap_summary(data, s))
                .collect(),
            stop_gaps: stop_gap_summary(data),
            joint: config.joint.then(|| joint_summary(data)),
            findings: Vec::new(),
            figures: Vec::new(),
            methods,
        }
    }
}
