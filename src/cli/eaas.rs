//! `swarmplan eaas`: one hop of a request's plan, solved by the sharing heuristics and the exact
//! models side by side.
//!
//! ```text
//! swarmplan eaas --request-id r001 --hop 0 --methods pb,fb,continuous,milp,fluid,fair --time-limit 10
//! swarmplan eaas --request-id r001 --hop 1 --methods milp --reorder free --period-min 0.5 --json
//! swarmplan eaas --request-id r001 --hop 1 --write-hop hop.json --write-lp hop.lp --methods pb
//! swarmplan eaas --hop-file hop.json --methods pb,milp
//! ```
//!
//! The request is planned as `swarmplan solve` does (PB sharing, sequential route); hop `I` of
//! that plan (its path and departure batteries) is the hop studied, or the hop of a hop file
//! (`--hop-file`, see [`crate::eaas::hop_file`]). `--write-hop` writes the hop as a hop file,
//! `--write-lp` the MILP of `milp` in CPLEX LP format (free MPS for a name ending in `.mps`); the methods then run as usual. The objective is the node time
//! at the hop's end when the plan stops there, else (the destination) the lowest delivery arrival battery. Each
//! method's gap is measured against the best reference available, labelled: the continuous
//! model's optimum (`optimal`, over every continuous-time schedule) or the infimum it approaches
//! (`infimum`), the MILP optimum (`optimal`, over grid schedules), its incumbent after a time
//! limit (`incumbent`), or the fluid LP bound (`bound`); a PB or FB schedule outside the
//! re-ordering mode of the exact models is labelled `different_policy` instead.

use super::inputs::InstanceArgs;
use crate::compose::{Context, PlanOptions, RouteMethod};
use crate::eaas::compare::{label_gaps, run_method};
use crate::eaas::compare::{HopMethod, MethodRow};
use crate::eaas::exact::milp::{write_lp, MilpOptions};
use crate::eaas::exact::EndPads;
use crate::eaas::exact::{Objective, Reorder};
use crate::eaas::hop_file::{read_hop_file, write_hop_file, HopFile};
use crate::eaas::{HopProblem, PolicyOptions, SharingPolicy};
use crate::error::{Error, Result};
use crate::precompose::Positioning;
use crate::problem::io::json_name;
use crate::solver::lp_file::ModelFormat;
use crate::solver::MilpBackend;
use serde::Serialize;
use std::path::{Path, PathBuf};

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
    /// Write the hop's MILP (objective, `--reorder`, `--period-min` as for `milp`) before
    /// running the methods: free MPS when FILE ends in `.mps`, CPLEX LP otherwise.
    #[arg(long, value_name = "FILE")]
    pub write_lp: Option<PathBuf>,
    /// Overwrite the `--write-hop` and `--write-lp` files when they exist (E0013 otherwise).
    #[arg(long)]
    pub force: bool,
    /// Methods, comma-separated.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "pb,fb,continuous,milp,fluid,fair"
    )]
    pub methods: Vec<HopMethod>,
    /// MILP backend.
    #[arg(
        long,
        value_parser = super::inputs::backend_value_parser(),
        default_value_t = MilpBackend::default()
    )]
    pub backend: MilpBackend,
    /// Wall-clock limit of each solve, seconds (a solve it stops depends on the machine).
    #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
    pub time_limit: f64,
    /// Branch-and-bound nodes of each MILP call (`continuous`, `milp`), the same on every
    /// machine [default: none].
    #[arg(long, value_name = "N")]
    pub node_limit: Option<u64>,
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
    let outputs: Vec<&Path> = args
        .write_hop
        .iter()
        .chain(&args.write_lp)
        .map(PathBuf::as_path)
        .collect();
    let inputs = [
        &args.instance.network,
        &args.instance.profile,
        &args.requests,
        &args.hop_file,
    ];
    let mut inputs: Vec<&Path> = inputs.into_iter().flatten().map(PathBuf::as_path).collect();
    if let (Some(hop), Some(lp)) = (&args.write_hop, &args.write_lp) {
        if hop == lp {
            inputs.push(hop);
        }
    }
    super::distinct_from_inputs(&outputs, &inputs)?;
    for path in &outputs {
        super::may_write(path, args.force)?;
    }
    let (hop, readings) = match &args.hop_file {
        Some(path) => {
            let (profile, hop) =
                crate::error::both(args.instance.load_profile(), read_hop_file(path))?;
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
            "wrote {} file {}: {} variables ({} binary), {} constraints",
            ModelFormat::of_path(path).name(),
            path.display(),
            size.variables,
            size.binaries,
            size.constraints
        );
    }
    // The exact methods check their time limit (E4105) under the library's name for it.
    let rows = rows(&hop.hop, &objective, &args, &readings).map_err(|e| match e {
        Error::Invalid(mut list) => {
            for v in list.iter_mut().filter(|v| v.field == "time_limit_s") {
                v.field = "--time-limit".to_string();
            }
            Error::Invalid(list)
        }
        other => other,
    })?;
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
    let profile = if args.instance.literal {
        format!("{} (--literal)", instance.profile.name)
    } else {
        instance.profile.name.clone()
    };
    let file = context
        .hop_file(&request, &options, args.hop, &profile)
        .map_err(|e| match e {
            Error::Invalid(mut list) => {
                for v in list.iter_mut().filter(|v| v.code == "E4110") {
                    v.field = "--hop".to_string();
                }
                Error::Invalid(list)
            }
            other => other,
        })?;
    Ok((file, PolicyOptions::from(&instance.profile.readings)))
}

/// Settings of the `milp` method and of `--write-lp`.
fn milp_options(args: &EaasArgs) -> MilpOptions {
    MilpOptions {
        period_min: args.period_min,
        reorder: args.reorder,
        backend: args.backend,
        time_limit_s: args.time_limit,
        node_limit: args.node_limit,
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
    let bar = if args.methods.iter().any(|m| m.is_model()) {
        super::progress::bar(args.methods.len() as u64, "methods")
    } else {
        indicatif::ProgressBar::hidden()
    };
    for &m in &args.methods {
        bar.set_message(m.to_string());
        rows.push(run_method(
            problem,
            objective,
            m,
            &milp_options(args),
            readings,
        )?);
        bar.inc(1);
    }
    bar.finish_and_clear();
    label_gaps(&mut rows, problem, objective, args.reorder);
    Ok(rows)
}

fn print_human(r: &EaasReport) -> Result<()> {
    let objective = match r.objective {
        Objective::NodeTime(EndPads {
            pads,
            pad_rate_mah_per_min,
        }) => format!(
            "node time on {pads} pad(s) at {} mAh/min",
            crate::human::round(pad_rate_mah_per_min, 2)
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
        let gap = match (row.gap, row.gap_label) {
            (_, Some(label)) => json_name(&label),
            (Some(g), None) => match g.relative {
                Some(x) => format!(
                    "{} vs {}",
                    crate::human::gap_percent(x, 4),
                    json_name(&g.reference)
                ),
                None => format!("n/a vs {}", json_name(&g.reference)),
            },
            (None, None) => "-".to_string(),
        };
        outln!(
            "  {:<10} {:<16} status {:<24} feasible {:<5} objective {:<12} bound {:<12} gap {:<24} {}{}{:.1} ms, {} transfer(s)",
            row.method.to_string(),
            row.kind,
            row.status.map_or("-".to_string(), |s| json_name(&s)),
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
                    crate::human::round(h, 4)
                )),
            row.epsilon
                .filter(|e| *e > 0.0)
                .map_or(String::new(), |e| format!("epsilon {e:.3e}, ")),
            row.solve_ms,
            row.transfers.len()
        );
    }
    Ok(())
}
