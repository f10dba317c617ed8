//! Re-verifies the rows of a bench run's `requests.csv` (`swarmplan check --bench DIR`): each
//! row states the numbers of a plan that is not written, so the request is planned again with
//! the row's combination and the settings of the run's `config.json`, that plan is checked by
//! [`check_report`] like any plan file (P5702 wraps a violation), and every column is compared
//! with it (P5701, one violation per column with the stated and recomputed values):
//!
//! * from the request and the plan, by the checker's own code: ids, source, destination,
//!   packages, `distance_m` (the checker's Dijkstra), support drones, success, outcome, `dt`,
//!   `tt`, `nt`, stops, energy shared; LPT's node time at every proven stop (the checker's own
//!   LPT) and its gap against the stop's `nt`; the route gap `(dt - optimal_dt) / optimal_dt`;
//! * from the method run again: the optimal route's `dt` and whether it is proven, and with
//!   (unless `--no-joint`) the joint optimum and the parts of the gap split.
//!
//! The other tables are compared with the rows the run's own code writes for the plans made
//! again (those plans checked as above): every row of `hops.csv`, `stops.csv` and `joint.csv` of
//! a checked request, column by column (P5701 with the table, row and column), and each table's
//! rows of the request by their key (P5705 for a missing or a repeated one, and for rows of a
//! request `requests.csv` does not have). `timings.csv` holds machine times only; the run's seal
//! (`complete`, verified by the caller) covers it.
//!
//! Rows of a run made with a wall-clock limit (`--hop-time-limit`) cannot be planned again to
//! the same numbers; [`BenchCheck::skipped`] says so. Codes P5703 (a row's request is not the
//! request set's at its index), P5704 (a row's combination is not one of the run's) and P5705 (a
//! request without its row of a combination of the run, or with two).

use super::check_report;
use super::close;
use super::decision::shortest_distance_m;
use crate::bench::{BenchConfig, BenchData, RequestRow};
use crate::compose::{Context, HopPaths, JointSplit, PlanOptions, PlanSettings, RequestReport};
use crate::error::{Result, Violation};
use crate::problem::io::json_name;
use crate::problem::{Network, Profile, Request, SkywayGraph};
use crate::solver::SolveStatus;

fn violation(code: &'static str, field: impl Into<String>, cause: impl Into<String>) -> Violation {
    Violation::new(
        code,
        field,
        cause,
        "run the bench again: its rows are the plans of its combinations and settings",
    )
}

/// What checking a run's rows found.
#[derive(Debug, Default)]
pub struct BenchCheck {
    /// Every broken rule.
    pub violations: Vec<Violation>,
    /// Requests planned again.
    pub requests: usize,
    /// Rows compared.
    pub rows: usize,
    /// Why the rows were not planned again, if they were not.
    pub skipped: Option<&'static str>,
}

/// Checks the rows of the first `limit` requests of a run.
///
/// # Arguments
/// * `network`, `profile`, `requests` - the run's inputs (their fingerprint is compared with
///   `config.inputs_sha256` by the caller).
/// * `config`, `data` - the run's `config.json` and tables.
/// * `limit` - requests whose rows are checked, in the order of `requests.csv`.
///
/// # Errors
/// Those of planning a request again (an input the run could plan always plans again).
///
/// # Complexity
/// Planning each request again with every combination of the run (and the joint optimum unless
/// `--no-joint`), plus [`check_report`] on each plan.
pub fn check_bench_rows(
    network: &Network,
    profile: &Profile,
    requests: &[Request],
    config: &BenchConfig,
    data: &BenchData,
    limit: usize,
) -> Result<BenchCheck> {
    let rows = &data.requests[..];
    let mut out = BenchCheck::default();
    if config.milp.time_limit_s.is_finite() {
        out.skipped = Some(
            "the run was made with a wall-clock limit on its hop solves (--hop-time-limit), so \
             its plans depend on the machine",
        );
        return Ok(out);
    }
    let graph = SkywayGraph::new(network)?;
    let run = Rerun {
        network,
        profile,
        requests,
        config,
        data,
        context: Context::new(network, &graph, profile).with_settings(&PlanSettings {
            hop_model: config.milp,
            prune_candidates: true,
            node_limit: config.node_limit,
            hop_paths: HopPaths::Rule,
        }),
        combos: config.planned_combos(),
    };
    check_request_ids(rows, requests, &mut out);
    let mut k = 0;
    while k < rows.len() && out.requests < limit {
        let index = rows[k].request_index;
        let end = k + rows[k..]
            .iter()
            .take_while(|r| r.request_index == index)
            .count();
        out.requests += 1;
        if let Some(request) = requests.get(index).filter(|r| r.id == rows[k].request_id) {
            run.check_request(&mut out, request, index, k..end)?;
        }
        k = end;
    }
    check_rows_without_request(data, &mut out);
    Ok(out)
}

/// P5703: every row names its request by position and id, as the request set has them.
fn check_request_ids(rows: &[RequestRow], requests: &[Request], out: &mut BenchCheck) {
    for (k, row) in rows.iter().enumerate() {
        let found = requests.get(row.request_index).map(|r| &r.id);
        if found != Some(&row.request_id) {
            out.violations.push(violation(
                "P5703",
                format!("requests.csv[{k}].request_index"),
                format!(
                    "request {} at index {}: the run's requests have {} there",
                    row.request_id,
                    row.request_index,
                    found.map_or("none".to_string(), |id| format!("`{id}`"))
                ),
            ));
        }
    }
}

/// P5705: the rows of the other tables whose request has no row in `requests.csv`.
fn check_rows_without_request(data: &BenchData, out: &mut BenchCheck) {
    let planned: std::collections::BTreeSet<usize> =
        data.requests.iter().map(|r| r.request_index).collect();
    for (table, indices) in [
        (
            "hops.csv",
            data.hops
                .iter()
                .map(|r| r.request_index)
                .collect::<Vec<_>>(),
        ),
        (
            "stops.csv",
            data.stops.iter().map(|r| r.request_index).collect(),
        ),
        (
            "joint.csv",
            data.joint.iter().map(|r| r.request_index).collect(),
        ),
    ] {
        for (r, index) in indices.into_iter().enumerate() {
            if !planned.contains(&index) {
                out.violations.push(violation(
                    "P5705",
                    format!("{table}[{r}].request_index"),
                    format!("request index {index} has no row in requests.csv"),
                ));
            }
        }
    }
}

/// A run to check: its inputs, `config.json` and tables, and the context that plans its
/// requests again with the run's settings.
struct Rerun<'a> {
    network: &'a Network,
    profile: &'a Profile,
    requests: &'a [Request],
    config: &'a BenchConfig,
    data: &'a BenchData,
    context: Context,
    /// Every combination the run planned, references included.
    combos: Vec<PlanOptions>,
}

impl Rerun<'_> {
    /// The rows `rows` of `requests.csv`, those of the request at `index`: the request planned
    /// again with every combination of the run, then the other tables' rows of the request
    /// (P5701, P5705), one row per combination (P5705), and every row (P5701, P5702, P5704).
    fn check_request(
        &self,
        out: &mut BenchCheck,
        request: &Request,
        index: usize,
        rows: std::ops::Range<usize>,
    ) -> Result<()> {
        let reports = self
            .combos
            .iter()
            .map(|c| self.context.plan(request, c))
            .collect::<Result<Vec<_>>>()?;
        let tables = crate::bench::tables_of_request(
            &self.context,
            self.config,
            index,
            request,
            reports.clone(),
        )?;
        compare_tables(out, self.data, index, &tables);
        let joint = if self.config.joint {
            Some(self.context.joint_split(request, &reports)?)
        } else {
            None
        };
        self.check_one_row_per_combination(out, request, rows.clone());
        let distance_m = shortest_distance_m(self.network, &request.source, &request.destination);
        for r in rows {
            self.check_row(out, request, r, &reports, joint.as_ref(), distance_m);
        }
        Ok(())
    }

    /// P5705: every combination of the run has exactly one row of the request among `rows`.
    fn check_one_row_per_combination(
        &self,
        out: &mut BenchCheck,
        request: &Request,
        rows: std::ops::Range<usize>,
    ) {
        let (k, end) = (rows.start, rows.end);
        for c in &self.config.combos {
            let n = self.data.requests[rows.clone()]
                .iter()
                .filter(|r| {
                    (r.sharing, r.positioning, r.route) == (c.sharing, c.positioning, c.route)
                })
                .count();
            if n != 1 {
                out.violations.push(violation(
                    "P5705",
                    format!("requests.csv[{k}..{end}]"),
                    format!(
                        "request {} has {n} rows of combination {}/{}/{}, the run wrote one",
                        request.id, c.sharing, c.positioning, c.route
                    ),
                ));
            }
        }
    }

    /// Row `r` of `requests.csv` against the plan of its combination among `reports`: the
    /// combination is the run's (P5704), its plan passes the plan checker (P5702), and every
    /// column is the plan's (P5701).
    fn check_row(
        &self,
        out: &mut BenchCheck,
        request: &Request,
        r: usize,
        reports: &[RequestReport],
        joint: Option<&JointSplit>,
        distance_m: f64,
    ) {
        let row = &self.data.requests[r];
        let combos = &self.combos;
        out.rows += 1;
        let f = format!("requests.csv[{r}]");
        let Some(j) = combos.iter().position(|c| {
            (c.sharing, c.positioning, c.route) == (row.sharing, row.positioning, row.route)
        }) else {
            out.violations.push(violation(
                "P5704",
                format!("{f}.sharing"),
                format!(
                    "combination {}/{}/{} is not one of the run's",
                    json_name(&row.sharing),
                    json_name(&row.positioning),
                    json_name(&row.route)
                ),
            ));
            return;
        };
        let report = &reports[j];
        for x in check_report(self.network, self.profile, self.requests, report) {
            out.violations.push(violation(
                "P5702",
                format!("{f}: {}", x.field),
                format!("the plan behind the row breaks [{}]: {}", x.code, x.cause),
            ));
        }
        let reference = self
            .config
            .reference_of(&combos[j])
            .and_then(|c| combos.iter().position(|x| *x == c))
            .map(|i| &reports[i]);
        let split = joint.and_then(|s| s.splits.get(j).cloned().flatten());
        let mut columns = Columns {
            out: &mut out.violations,
            f: &f,
        };
        columns.compare_plan(row, request, report, distance_m);
        columns.compare_reference(row, report, reference);
        if let Some(joint) = joint {
            columns.compare_split(row, joint.joint.dt_min(), split.as_ref());
        }
    }
}

/// Compares the rows of `hops.csv`, `stops.csv` and `joint.csv` of the request at `index` with
/// `expected`, the rows the run's code writes for the plans made again.
fn compare_tables(out: &mut BenchCheck, data: &BenchData, index: usize, expected: &BenchData) {
    compare_table(out, "hops.csv", &data.hops, &expected.hops, index, |r| {
        r.request_index
    });
    compare_table(out, "stops.csv", &data.stops, &expected.stops, index, |r| {
        r.request_index
    });
    compare_table(out, "joint.csv", &data.joint, &expected.joint, index, |r| {
        r.request_index
    });
}

/// One table's rows of one request against the expected rows, in the run's order (which a
/// merge keeps): their number (P5705), then each row column by column (P5701; numbers within
/// the checker's tolerance).
fn compare_table<T: serde::Serialize>(
    out: &mut BenchCheck,
    table: &str,
    stated: &[T],
    expected: &[T],
    index: usize,
    request_of: impl Fn(&T) -> usize,
) {
    let found: Vec<(usize, &T)> = stated
        .iter()
        .enumerate()
        .filter(|(_, r)| request_of(r) == index)
        .collect();
    if found.len() != expected.len() {
        out.violations.push(violation(
            "P5705",
            format!("{table}, request index {index}"),
            format!(
                "{} rows of the request, the run writes {}",
                found.len(),
                expected.len()
            ),
        ));
    }
    for ((r, row), want) in found.iter().zip(expected) {
        let (Ok(serde_json::Value::Object(a)), Ok(serde_json::Value::Object(b))) =
            (serde_json::to_value(row), serde_json::to_value(want))
        else {
            continue;
        };
        for (column, recomputed) in &b {
            let stated = a.get(column).unwrap_or(&serde_json::Value::Null);
            let same = match (stated.as_f64(), recomputed.as_f64()) {
                (Some(x), Some(y)) => close(x, y),
                _ => stated == recomputed,
            };
            if !same {
                out.violations.push(violation(
                    "P5701",
                    format!("{table}[{r}].{column}"),
                    format!(
                        "states {stated}, the plan made again with the row's combination and \
                         the run's settings gives {recomputed}"
                    ),
                ));
            }
        }
    }
}

/// Column comparisons of one row.
struct Columns<'a> {
    out: &'a mut Vec<Violation>,
    f: &'a str,
}

impl Columns<'_> {
    fn differs(&mut self, column: &str, stated: String, recomputed: String) {
        self.out.push(violation(
            "P5701",
            format!("{}.{column}", self.f),
            format!(
                "states {stated}, the plan made again with the row's combination and the run's \
                 settings gives {recomputed}"
            ),
        ));
    }

    fn number(&mut self, column: &str, stated: f64, recomputed: f64) {
        let same = close(stated, recomputed) || (stated.is_nan() && recomputed.is_nan());
        if !same {
            self.differs(column, stated.to_string(), recomputed.to_string());
        }
    }

    fn option(&mut self, column: &str, stated: Option<f64>, recomputed: Option<f64>) {
        let same = match (stated, recomputed) {
            (Some(a), Some(b)) => close(a, b),
            (a, b) => a.is_none() && b.is_none(),
        };
        if !same {
            self.differs(column, json_name(&stated), json_name(&recomputed));
        }
    }

    fn exact<T: PartialEq + serde::Serialize>(&mut self, column: &str, stated: T, recomputed: T) {
        if stated != recomputed {
            self.differs(column, json_name(&stated), json_name(&recomputed));
        }
    }

    /// The columns a plan states.
    fn compare_plan(
        &mut self,
        row: &RequestRow,
        request: &Request,
        report: &RequestReport,
        distance_m: f64,
    ) {
        let plan = &report.plan;
        self.exact("source", &row.source, &request.source);
        self.exact("destination", &row.destination, &request.destination);
        self.exact("packages", row.packages, request.packages_kg.len());
        self.number("distance_m", row.distance_m, distance_m);
        self.exact("support_drones", row.support_drones, report.support_drones);
        self.exact("success", row.success, plan.delivered());
        self.exact("outcome", row.outcome.clone(), plan.outcome.kind());
        self.number("dt_min", row.dt_min, plan.dt_min);
        self.number("tt_min", row.tt_min, plan.tt_min);
        self.number("nt_min", row.nt_min, plan.nt_min);
        let stops: Vec<_> = plan.hops.iter().filter_map(|h| h.stop.as_ref()).collect();
        self.exact("stops", row.stops, stops.len());
        self.number("shared_mah", row.shared_mah, plan.shared_mah);
        // LPT at every proven stop of a delivered plan, by the checker's own LPT.
        let (mut proven, mut equal, mut gap_sum) = (0usize, 0usize, 0.0);
        if plan.delivered() {
            for stop in stops.iter().filter(|s| s.status == SolveStatus::Optimal) {
                let lpt = lpt_makespan_min(&stop.charge_times_min, stop.pads as usize);
                let gap = if stop.nt_min > 0.0 {
                    (lpt - stop.nt_min) / stop.nt_min
                } else {
                    0.0
                };
                proven += 1;
                equal += usize::from(gap.abs() <= crate::solver::ZERO_GAP_TOL);
                gap_sum += gap;
            }
        }
        self.exact("lpt_stops", row.lpt_stops, proven);
        self.exact("lpt_optimal", row.lpt_optimal, equal);
        self.number("lpt_gap_sum", row.lpt_gap_sum, gap_sum);
    }

    /// The route gap columns against the optimal route of the same combination.
    fn compare_reference(
        &mut self,
        row: &RequestRow,
        report: &RequestReport,
        reference: Option<&RequestReport>,
    ) {
        let Some(best) = reference else {
            self.exact("route_gap_reference", row.route_gap_reference.as_str(), "");
            return;
        };
        let optimal_dt = best.plan.delivered().then_some(best.plan.dt_min);
        let proven = best.plan.route_optimality.is_none_or(|o| o.proven());
        let gap = match (report.plan.delivered(), optimal_dt) {
            (true, Some(b)) if b > 0.0 => Some((report.plan.dt_min - b) / b),
            (true, Some(_)) => Some(0.0),
            _ => None,
        };
        self.exact(
            "route_gap_reference",
            row.route_gap_reference.as_str(),
            "optimal",
        );
        self.option("optimal_dt_min", row.optimal_dt_min, optimal_dt);
        self.exact("optimal_proven", row.optimal_proven, Some(proven));
        self.option("route_gap", row.route_gap, gap);
    }

    /// Unless `--no-joint`: the joint optimum and the parts of the gap split.
    fn compare_split(
        &mut self,
        row: &RequestRow,
        joint_dt: Option<f64>,
        split: Option<&crate::compose::GapSplit>,
    ) {
        let Some(s) = split else {
            self.option("joint_dt_min", row.joint_dt_min, None);
            return;
        };
        self.option("joint_dt_min", row.joint_dt_min, joint_dt);
        let label = s
            .label
            .and_then(|l| serde_json::to_value(l).ok())
            .and_then(|l| l.as_str().map(String::from))
            .unwrap_or_default();
        self.exact("split_label", row.split_label.clone(), label);
        for (column, stated, recomputed) in [
            (
                "exact_schedule_dt_min",
                row.exact_schedule_dt_min,
                s.exact_schedule_dt_min,
            ),
            (
                "swarm_optimum_dt_min",
                row.swarm_optimum_dt_min,
                s.swarm_optimum_dt_min,
            ),
            ("gap_total_min", row.gap_total_min, s.total_min),
            ("gap_sharing_min", row.gap_sharing_min, s.sharing_min),
            ("gap_route_min", row.gap_route_min, s.route_min),
            ("gap_swarm_min", row.gap_swarm_min, s.swarm_min),
            (
                "split_epsilon_min",
                row.split_epsilon_min,
                Some(s.epsilon_min),
            ),
        ] {
            self.option(column, stated, recomputed);
        }
        self.exact("split_proven", row.split_proven, Some(s.proven));
    }
}

/// Longest processing time first (Graham 1969): drones by charge time, longest first, each on
/// the least loaded pad; its makespan (which ties do not change).
fn lpt_makespan_min(times: &[f64], pads: usize) -> f64 {
    let mut sorted = times.to_vec();
    sorted.sort_by(|a, b| b.total_cmp(a));
    let mut load = vec![0.0f64; pads.max(1)];
    for t in sorted {
        let least = (0..load.len())
            .min_by(|&a, &b| load[a].total_cmp(&load[b]))
            .expect("one pad at least");
        load[least] += t;
    }
    load.into_iter().fold(0.0, f64::max)
}
