//! `swarmplan eaas`: one hop of a request's plan, solved by the sharing heuristics and the exact
//! models side by side.
//!
//! ```text
//! swarmplan eaas --request-id r001 --hop 0 --methods pb,fb,milp,fluid,fair --time-limit 10
//! swarmplan eaas --request-id r001 --hop 1 --methods milp --reorder free --period-min 0.5 --json
//! swarmplan eaas --request-id r001 --hop 1 --write-hop hop.json --write-lp hop.lp --methods pb
//! swarmplan eaas --hop-file hop.json --methods pb,milp
//! ```
//!
//! The request is planned as `swarmplan solve` does (PB sharing, sequential route); hop `I` of
//! that plan (its path and departure batteries) is the hop studied, or the hop of a hop file
//! (`--hop-file`, see [`crate::eaas::hop_file`]). `--write-hop` writes the hop as a hop file,
//! `--write-lp` the MILP of `milp` in CPLEX LP format; the methods then run as usual. The objective is the node time
//! at the hop's end when the plan stops there, else (the destination) the lowest delivery arrival battery. Each
//! method's gap is measured against the best reference available, labelled: the MILP optimum
//! (`optimal`, over grid schedules), its incumbent after a time limit (`incumbent`), or the fluid
//! LP bound (`bound`).

use super::inputs::{self, InstanceArgs};
use crate::compose::{Context, PlanOptions, Planner, RouteMethod};
use crate::eaas::hop_file::{read_hop_file, write_hop_file, HopEnd, HopFile};
use crate::eaas::milp::{
    objective_of, solve_milp, write_lp, ExactOutcome, ExactStatus, MilpOptions,
};
use crate::eaas::milp::{Objective, Reorder};
use crate::eaas::{fluid, simulate_with, HopProblem, PolicyOptions, SharingPolicy, Transfer};
use crate::error::{Error, Result};
use crate::precompose::Positioning;
use crate::solver::{Gap, MilpBackend, ReferenceKind};
use serde::Serialize;
use std::path::PathBuf;

/// A method `swarmplan eaas` can run on a hop.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum HopMethod {
    /// No sharing.
    None,
    /// Priority-based heuristic (Algorithm 2).
    Pb,
    /// Fairness-based heuristic (Algorithm 3).
    Fb,
    /// Time-indexed MILP (optimal over grid schedules).
    Milp,
    /// Fluid LP bound (valid for every continuous-time schedule).
    Fluid,
    /// Fair QP optimum laid out as a schedule.
    Fair,
}

display_as_value_name!(HopMethod);

/// Arguments of `swarmplan eaas`.
#[derive(Debug, clap::Args)]
pub struct EaasArgs {
    /// Network and profile.
    #[command(flatten)]
    pub instance: InstanceArgs,
    /// Request set (JSON) [default: the shipped paper-195 requests].
    #[arg(long, alias = "request-file", value_name = "FILE")]
    pub requests: Option<PathBuf>,
    /// Id of the request in the request set.
    #[arg(long, value_name = "ID", required_unless_present = "hop_file")]
    pub request_id: Option<String>,
    /// Index of the hop in the request's plan (0 = the first hop).
    #[arg(long, value_name = "I", default_value_t = 0)]
    pub hop: usize,
    /// Solve the hop of this hop file (JSON, as `--write-hop` writes it) instead of planning a
    /// request; the profile given still sets PB's and FB's readings.
    #[arg(
        long,
        value_name = "FILE",
        conflicts_with_all = ["request_id", "requests", "hop", "network", "write_hop"]
    )]
    pub hop_file: Option<PathBuf>,
    /// Write the hop as a hop file (JSON) before running the methods.
    #[arg(long, value_name = "FILE")]
    pub write_hop: Option<PathBuf>,
    /// Write the hop's MILP (objective, `--reorder`, `--period-min` as for `milp`) in CPLEX LP
    /// format before running the methods.
    #[arg(long, value_name = "FILE")]
    pub write_lp: Option<PathBuf>,
    /// Methods, comma-separated.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "pb,fb,milp,fluid,fair"
    )]
    pub methods: Vec<HopMethod>,
    /// MILP backend.
    #[arg(
        long,
        value_parser = crate::solver::backend_value_parser(),
        default_value_t = MilpBackend::default()
    )]
    pub backend: MilpBackend,
    /// Time limit of each solve, seconds.
    #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
    pub time_limit: f64,
    /// Longest period of the MILP's grid, minutes.
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub period_min: f64,
    /// Re-ordering allowed to the exact models.
    #[arg(long, value_enum, default_value_t = Reorder::Paper)]
    pub reorder: Reorder,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
}

/// One method's result on the hop.
#[derive(Debug, Clone, Serialize)]
pub struct MethodRow {
    /// The method.
    pub method: HopMethod,
    /// `heuristic`, `exact_grid` (MILP), `bound` (fluid LP) or `fair_layout` (QP schedule).
    pub kind: &'static str,
    /// Solve status of the exact models; `None` for the heuristics.
    pub status: Option<ExactStatus>,
    /// Whether the method's schedule flies (`None` without a schedule).
    pub feasible: Option<bool>,
    /// Objective of the schedule (node time, min, or lowest delivery arrival battery, mAh); the
    /// bound itself for `fluid`.
    pub objective: Option<f64>,
    /// False when `objective` is a node time not proven within the node limit of a stop (an
    /// upper bound on the schedule's node time; printed with `<=`).
    pub objective_proven: bool,
    /// The model's proven bound on the objective (MILP, fluid LP).
    pub bound: Option<f64>,
    /// `fair` only: the QP optimum, sum of squared end deficits over every drone, mAh^2 (a lower
    /// bound on that sum for every continuous-time schedule).
    pub qp_squared_deficits_mah2: Option<f64>,
    /// Gap against the reference, with its kind.
    pub gap: Option<Gap>,
    /// MILP grid step, minutes.
    pub grid_step_min: Option<f64>,
    /// Wall-clock time, ms.
    pub solve_ms: f64,
    /// The schedule.
    pub transfers: Vec<Transfer>,
}

/// The report.
#[derive(Debug, Clone, Serialize)]
pub struct EaasReport {
    /// Request id.
    pub request_id: String,
    /// Hop index.
    pub hop: usize,
    /// Node ids flown over.
    pub path: Vec<String>,
    /// The objective every method is scored by.
    pub objective: Objective,
    /// Re-ordering mode of the exact models.
    pub reorder: Reorder,
    /// The hop's sharing problem.
    pub problem: HopProblem,
    /// One row per method, in the order asked.
    pub rows: Vec<MethodRow>,
}

/// Runs the subcommand; exit code 0.
///
/// # Errors
/// Bad input (files, request id, `--hop` out of range: `E4110`, a bad hop file: `E4111`,
/// `E4112`, `E4115` and the hop's own codes, options of the exact models), an unwritable output
/// file, or a backend failure.
pub fn run(args: EaasArgs) -> Result<i32> {
    let (hop, readings) = match &args.hop_file {
        Some(path) => {
            let (profile, hop) = inputs::both(args.instance.load_profile(), read_hop_file(path))?;
            (hop, PolicyOptions::from(&profile.readings))
        }
        None => planned_hop(&args)?,
    };
    let objective = hop.objective();
    if let Some(path) = &args.write_hop {
        write_hop_file(path, &hop)?;
        eprintln!("wrote hop file {}", path.display());
    }
    if let Some(path) = &args.write_lp {
        let about = format!(
            "request {} hop {}: {}",
            hop.request_id,
            hop.hop_index,
            hop.path.join(" -> ")
        );
        let size = write_lp(&hop.hop, &objective, &milp_options(&args), &about, path)?;
        eprintln!(
            "wrote LP file {}: {} variables ({} binary), {} constraints",
            path.display(),
            size.variables,
            size.binaries,
            size.constraints
        );
    }
    let rows = rows(&hop.hop, &objective, &args, &readings)?;
    let out = EaasReport {
        request_id: hop.request_id,
        hop: hop.hop_index,
        path: hop.path,
        objective,
        reorder: args.reorder,
        problem: hop.hop,
        rows,
    };
    if args.json {
        super::print_json(&out)?;
    } else {
        print_human(&out)?;
    }
    Ok(0)
}

/// Plans the request as `swarmplan solve` does and takes hop `--hop` of the plan; the readings
/// of PB and FB come from the profile.
fn planned_hop(args: &EaasArgs) -> Result<(HopFile, PolicyOptions)> {
    let id = args.request_id.as_deref().unwrap_or_default();
    let (instance, set) = args.instance.load_with_requests(args.requests.as_deref())?;
    let instance = instance.with_request_from(&set, id)?;
    let request = instance.requests[0].clone();
    let context = Context::new(&instance.network, &instance.graph, &instance.profile);
    let options = PlanOptions {
        sharing: SharingPolicy::Pb,
        positioning: Positioning::LocationAware,
        route: RouteMethod::Sequential,
        support: None,
    };
    let report = context.plan(&request, &options)?;
    let hops = &report.plan.hops;
    let hop = hops.get(args.hop).ok_or_else(|| {
        Error::invalid(
            "E4110",
            "--hop",
            format!("hop {} of a plan with {} hop(s)", args.hop, hops.len()),
            "give a hop index below the number of hops (see `swarmplan solve`)",
        )
    })?;
    let graph = &instance.graph;
    let nodes: Vec<usize> = hop
        .path
        .iter()
        .filter_map(|id| graph.index_of(id))
        .collect();
    let path = graph
        .path_from_nodes(&nodes)
        .ok_or_else(|| Error::Backend {
            backend: "compose".into(),
            message: format!("the plan's hop path {:?} is not a network path", hop.path),
        })?;
    let planner = Planner::new(graph, &instance.profile, &report.swarm, SharingPolicy::Pb);
    let problem = planner.hop_problem(&path, &hop.departure_battery_mah)?;
    let end = nodes.last().copied().unwrap_or(0);
    // A plan's hop without a stop ends at the destination: no node time there, whatever its pads.
    let pads = if hop.stop.is_some() {
        graph.pads(end)
    } else {
        0
    };
    let end = match pads {
        0 => None,
        pads => Some(HopEnd {
            pads: pads as usize,
            pad_rate_mah_per_min: graph
                .pad_rate_mah_per_min(end, instance.profile.pads.charge_rate_mah_per_min),
        }),
    };
    let profile = if args.instance.literal {
        format!("{} (--literal)", instance.profile.name)
    } else {
        instance.profile.name.clone()
    };
    let file = HopFile {
        schema_version: crate::eaas::hop_file::HOP_FILE_SCHEMA_VERSION,
        request_id: request.id.clone(),
        hop_index: args.hop,
        from: hop.path.first().cloned().unwrap_or_default(),
        to: hop.path.last().cloned().unwrap_or_default(),
        path: hop.path.clone(),
        profile: Some(profile),
        end,
        hop: problem,
    };
    Ok((file, PolicyOptions::from(&instance.profile.readings)))
}

/// Settings of the `milp` method and of `--write-lp`.
fn milp_options(args: &EaasArgs) -> MilpOptions {
    MilpOptions {
        period_min: args.period_min,
        reorder: args.reorder,
        backend: args.backend,
        time_limit_s: args.time_limit,
    }
}

fn exact_row(method: HopMethod, kind: &'static str, o: ExactOutcome) -> MethodRow {
    MethodRow {
        method,
        kind,
        status: Some(o.status),
        feasible: o.outcome.as_ref().map(|x| x.feasible),
        objective: if method == HopMethod::Fluid {
            o.bound
        } else {
            o.objective
        },
        objective_proven: method == HopMethod::Fluid || o.objective_proven,
        bound: if method == HopMethod::Fair {
            None
        } else {
            o.bound
        },
        qp_squared_deficits_mah2: if method == HopMethod::Fair {
            o.model_objective
        } else {
            None
        },
        gap: None,
        grid_step_min: (method == HopMethod::Milp).then_some(o.grid_step_min),
        solve_ms: o.solve_ms,
        transfers: o.transfers,
    }
}

/// Runs every method, then labels the gaps against the best reference.
fn rows(
    problem: &HopProblem,
    objective: &Objective,
    args: &EaasArgs,
    readings: &PolicyOptions,
) -> Result<Vec<MethodRow>> {
    let mut rows = Vec::new();
    // The exact models may each run up to --time-limit; the heuristics take milliseconds.
    let slow = |m: &HopMethod| matches!(m, HopMethod::Milp | HopMethod::Fluid | HopMethod::Fair);
    let bar = if args.methods.iter().any(slow) {
        super::progress::bar(args.methods.len() as u64, "methods")
    } else {
        indicatif::ProgressBar::hidden()
    };
    for &m in &args.methods {
        bar.set_message(format!("{m:?}").to_lowercase());
        let start = std::time::Instant::now();
        let row = match m {
            HopMethod::None | HopMethod::Pb | HopMethod::Fb => {
                let policy = match m {
                    HopMethod::Pb => SharingPolicy::Pb,
                    HopMethod::Fb => SharingPolicy::Fb,
                    _ => SharingPolicy::None,
                };
                let o = simulate_with(problem, policy, readings)?;
                let value = if o.feasible {
                    Some(objective_of(problem, objective, &o.final_battery_mah)?)
                } else {
                    None
                };
                MethodRow {
                    method: m,
                    kind: "heuristic",
                    status: None,
                    feasible: Some(o.feasible),
                    objective: value.map(|v| v.value),
                    objective_proven: value.is_none_or(|v| v.proven),
                    bound: None,
                    qp_squared_deficits_mah2: None,
                    gap: None,
                    grid_step_min: None,
                    solve_ms: start.elapsed().as_secs_f64() * 1e3,
                    transfers: o.transfers,
                }
            }
            HopMethod::Milp => exact_row(
                m,
                "exact_grid",
                solve_milp(problem, objective, &milp_options(args))?,
            ),
            HopMethod::Fluid => exact_row(
                m,
                "bound",
                fluid::bound(problem, objective, args.reorder, args.time_limit)?,
            ),
            HopMethod::Fair => exact_row(
                m,
                "fair_layout",
                fluid::fair(problem, objective, args.reorder, args.time_limit)?,
            ),
        };
        rows.push(row);
        bar.inc(1);
    }
    bar.finish_and_clear();
    let reference = rows
        .iter()
        .find_map(|r| match (r.method, r.status, r.objective) {
            // The MILP's schedule is optimal over the grid; its node time is the reference only
            // when the exact node time proved it.
            (HopMethod::Milp, Some(ExactStatus::Optimal), Some(v)) if r.objective_proven => {
                Some((v, ReferenceKind::Optimal))
            }
            (HopMethod::Milp, Some(ExactStatus::Optimal), Some(v)) => {
                Some((v, ReferenceKind::Incumbent))
            }
            (HopMethod::Milp, Some(ExactStatus::Feasible), Some(v)) => {
                Some((v, ReferenceKind::Incumbent))
            }
            _ => None,
        })
        .or_else(|| {
            rows.iter()
                .find(|r| r.method == HopMethod::Fluid && r.status == Some(ExactStatus::Optimal))
                .and_then(|r| r.bound.map(|b| (b, ReferenceKind::Bound)))
        });
    if let Some((v, kind)) = reference {
        for r in rows.iter_mut() {
            if matches!(r.method, HopMethod::Milp | HopMethod::Fluid) {
                continue;
            }
            r.gap = r.objective.map(|h| Gap::new(h, v, kind));
        }
    }
    Ok(rows)
}

fn print_human(r: &EaasReport) -> Result<()> {
    let objective = match r.objective {
        Objective::NodeTime {
            pads,
            pad_rate_mah_per_min,
        } => format!(
            "node time on {pads} pad(s) at {} mAh/min",
            super::human::round(pad_rate_mah_per_min, 2)
        ),
        Objective::MaxMinArrival => "lowest delivery arrival battery".to_string(),
        Objective::Feasible => "any flying schedule".to_string(),
    };
    outln!(
        "request {} hop {}: {} ({} leg(s), {} drones), objective {objective}, reorder {}",
        r.request_id,
        r.hop,
        r.path.join(" -> "),
        r.problem.legs.len(),
        r.problem.drones.len(),
        r.reorder
    );
    for row in &r.rows {
        let num = |x: Option<f64>| x.map_or("-".to_string(), |v| format!("{v:.4}"));
        let gap = row.gap.map_or("-".to_string(), |g| match g.relative {
            Some(x) => format!("{:+.4}% vs {:?}", 100.0 * x, g.reference),
            None => format!("n/a vs {:?}", g.reference),
        });
        outln!(
            "  {:<6} {:<12} status {:<24} feasible {:<5} objective {:<12} bound {:<12} gap {:<24} {}{:.1} ms, {} transfer(s)",
            format!("{:?}", row.method).to_lowercase(),
            row.kind,
            row.status.map_or("-".to_string(), |s| format!("{s:?}")),
            row.feasible.map_or("-".to_string(), |f| f.to_string()),
            match row.objective {
                Some(v) if !row.objective_proven => format!("<={v:.4}"),
                v => num(v),
            },
            num(row.bound),
            gap,
            row.grid_step_min
                .map_or(String::new(), |h| format!(
                    "grid {} min, ",
                    super::human::round(h, 4)
                )),
            row.solve_ms,
            row.transfers.len()
        );
    }
    Ok(())
}
